//! Compensation commands (issue 12 item 8): corrections added after the planner to what an
//! axis sends to its drive (digest 001 §2.19 and §4.1, digest 004 §2.13).
//!
//! `compensation_lead_screw`, `compensation_backlash` and `compensation_table` each install
//! one table of their kind on an axis (replacing that kind's previous table); the kinds add up. `compensation_enable` / `compensation_disable` switch all of the
//! axis's tables on and off; `compensation_clear` removes them.

use serde::{Deserialize, Serialize};

use super::{command_from, AxisIndex};

/// NMC lead-screw compensation (MtSetLeadScrewCompPara + MtEnableLeadScrew, S-LEADSCREW): a
/// correction per planned position, one table while moving positive and one while moving
/// negative, interpolated linearly, the end value held outside.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationLeadScrew {
    pub axis: AxisIndex,
    /// Strictly increasing planned positions, at least 2.
    pub positions: Vec<f64>,
    /// Correction at each position while moving positive.
    pub positive: Vec<f64>,
    /// Correction at each position while moving negative; the positive table if absent.
    #[serde(default)]
    pub negative: Option<Vec<f64>>,
    /// Switch the axis's compensation on at once (default); `false` only stores the table.
    #[serde(default = "yes")]
    pub enable: bool,
}

/// NMC backlash (MtSetBacklash, TV 72): while the planned motion goes in `direction`, an extra
/// `amount` is added, reached at `step` per servo period; moving the other way takes it back at
/// the same rate.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationBacklash {
    pub axis: AxisIndex,
    /// User units, ≥ 0; 0 removes the backlash compensation.
    pub amount: f64,
    /// User units per servo period, > 0 (NMC compDelta: 1000 / 200 ⇒ 5 periods).
    pub step: f64,
    #[serde(default)]
    pub direction: BacklashDirection,
    #[serde(default = "yes")]
    pub enable: bool,
}

/// A uniform 1/2/3-D grid: the correction of `axis` from the positions of 1–3 reference axes
/// (HIMC SetupComp/SetupComp2D/SetupComp3D; NMC 2-D table, S-2DCOMP, one table per corrected
/// axis). `values` lists the grid points with the first reference varying fastest.
/// `angle` (degrees, 2-D tables only; NMC `T2DCompensationTable.angle`, S-2DCOMP) turns the
/// table's axes counter-clockwise about its first point; `interpolation` `cubic` (HIMC
/// SetCompAlgType 1, 1-D and 2-D only) interpolates by natural cubic splines.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationTable {
    pub axis: AxisIndex,
    pub references: Vec<CompensationReference>,
    /// Grid position of the first point, per reference.
    pub start: Vec<f64>,
    /// Grid spacing, per reference, > 0.
    pub step: Vec<f64>,
    /// Points per reference, ≥ 2.
    pub count: Vec<u32>,
    pub values: Vec<f64>,
    #[serde(default = "yes")]
    pub enable: bool,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub angle: f64,
    #[serde(default, skip_serializing_if = "is_linear")]
    pub interpolation: CompensationInterpolation,
}

/// How a compensation grid is interpolated between its points (HIMC SetCompAlgType).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CompensationInterpolation {
    /// 0: (multi)linear, the default.
    #[default]
    Linear,
    /// 1: natural cubic spline per reference (a tensor-product spline in 2-D).
    Cubic,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_linear(v: &CompensationInterpolation) -> bool {
    *v == CompensationInterpolation::Linear
}

fn yes() -> bool {
    true
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CompensationKind {
    LeadScrew,
    Backlash,
    Table,
}

/// NMC compDir: 0 positive, 1 negative.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BacklashDirection {
    #[default]
    Positive,
    Negative,
}

/// A reference axis of a grid table and which of its positions is read (NMC
/// `T2DCompensation.axisType`: 0 planned, 1 encoder).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationReference {
    pub axis: AxisIndex,
    #[serde(default)]
    pub source: ReferenceSource,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceSource {
    /// The planned position (before compensation).
    #[default]
    Planned,
    /// The actual (encoder) position.
    Actual,
}

/// Switch the axis's compensation tables on (NMC MtEnableLeadScrew 1, HIMC EnableComp).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationEnable {
    pub axis: AxisIndex,
}

/// Switch them off; the correction steps back to 0 (NMC MtEnableLeadScrew 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationDisable {
    pub axis: AxisIndex,
}

/// Remove every table of the axis (HIMC DisableComp clears the setup).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationClear {
    pub axis: AxisIndex,
}

/// The compensation family.
#[derive(Clone, Debug, PartialEq)]
pub enum CompensationCommand {
    LeadScrew(CompensationLeadScrew),
    Backlash(CompensationBacklash),
    Table(CompensationTable),
    Enable(CompensationEnable),
    Disable(CompensationDisable),
    Clear(CompensationClear),
    OffsetAmount(CompensationOffsetAmount),
    OffsetProfile(CompensationOffsetProfile),
    OffsetTrigger(CompensationOffsetTrigger),
    OffsetStop(CompensationOffsetStop),
    FilterInputShaping(FilterInputShaping),
    FilterVsf(FilterVsf),
    FilterDisable(FilterDisable),
}

impl CompensationCommand {
    pub fn axis(&self) -> AxisIndex {
        match self {
            CompensationCommand::LeadScrew(c) => c.axis,
            CompensationCommand::Backlash(c) => c.axis,
            CompensationCommand::Table(c) => c.axis,
            CompensationCommand::Enable(c) => c.axis,
            CompensationCommand::Disable(c) => c.axis,
            CompensationCommand::Clear(c) => c.axis,
            CompensationCommand::OffsetAmount(c) => c.axis,
            CompensationCommand::OffsetProfile(c) => c.axis,
            CompensationCommand::OffsetTrigger(c) => c.axis,
            CompensationCommand::OffsetStop(c) => c.axis,
            CompensationCommand::FilterInputShaping(c) => c.axis,
            CompensationCommand::FilterVsf(c) => c.axis,
            CompensationCommand::FilterDisable(c) => c.axis,
        }
    }
}

command_from!(
    CompensationCommand,
    Compensation,
    [
        CompensationLeadScrew => LeadScrew,
        CompensationBacklash => Backlash,
        CompensationTable => Table,
        CompensationEnable => Enable,
        CompensationDisable => Disable,
        CompensationClear => Clear,
        CompensationOffsetAmount => OffsetAmount,
        CompensationOffsetProfile => OffsetProfile,
        CompensationOffsetTrigger => OffsetTrigger,
        CompensationOffsetStop => OffsetStop,
        FilterInputShaping => FilterInputShaping,
        FilterVsf => FilterVsf,
        FilterDisable => FilterDisable,
    ]
);

// HMC axis position compensation (manual §4.4.12, digest 000 §4.4 "Axis position
// compensation"): an offset added after the planner, moved by its own profile on command.

/// The amount the next `compensation_offset_trigger` moves the axis's offset by (HMC
/// `HMC_SetAxisCompenPos`): a move in progress keeps the amount it started with. JSON `type`:
/// `compensation_offset_amount`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationOffsetAmount {
    pub axis: AxisIndex,
    /// User units, signed.
    pub amount: f64,
}

/// The offset's move profile (HMC `HMC_SetAxisCompenPara`): `velocity`, `acceleration` and
/// `deceleration` > 0; `s_curve` (ucJerkMode 1) with `jerk` > 0, else a trapezoid. Takes effect
/// at once: a move in progress is replanned to its target from where it stands. JSON `type`:
/// `compensation_offset_profile`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationOffsetProfile {
    pub axis: AxisIndex,
    #[serde(default)]
    pub s_curve: bool,
    pub velocity: f64,
    pub acceleration: f64,
    pub deceleration: f64,
    #[serde(default)]
    pub jerk: f64,
}

/// Move the offset by the amount set (HMC `HMC_TrigAxisCompens`): the target is the offset
/// now plus the amount; a move in progress is abandoned where it stands and the new one
/// starts from there, with its velocity. Needs a profile. JSON `type`:
/// `compensation_offset_trigger`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationOffsetTrigger {
    pub axis: AxisIndex,
}

/// Stop the offset's move at once where it stands (HMC `HMC_StopAxisCompens`, "立即停止").
/// JSON `type`: `compensation_offset_stop`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationOffsetStop {
    pub axis: AxisIndex,
}

/// Install an input shaper on the command of `axis` (HIMC SetAxisInShape + EnableAxisInShape,
/// digest 004 §2.14), replacing what the slot held (a shaper or a VSF: they exclude each other).
/// `slot: group` is the slot used while the axis is in a group (HIMC SetGrpInShape on each
/// member). Refused while the axis moves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FilterInputShaping {
    pub axis: AxisIndex,
    /// `zv` (default), `zvd` or `ei` (`type` is the command's own tag).
    #[serde(default)]
    pub shaper: crate::filter::ShaperType,
    /// The mode's natural frequency (Hz), > 0 and below half the servo rate.
    pub frequency: f64,
    /// Its damping ratio, 0 ≤ ζ < 1.
    #[serde(default)]
    pub damping: f64,
    #[serde(default)]
    pub slot: crate::filter::FilterSlot,
}

/// Install the vibration suppression filter (a notch) on the command of `axis` (HIMC SetAxisVsf
/// + EnableAxisVsf), replacing a shaper in the axis slot. Refused while the axis moves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FilterVsf {
    pub axis: AxisIndex,
    /// The notch frequency (Hz), > 0 and below half the servo rate.
    pub frequency: f64,
    /// The notch's damping ratio (its width), 0 < ζ ≤ 10; HIMC recommends 1.
    #[serde(default = "one")]
    pub damping: f64,
}

/// Remove the filter of a slot, or of both when `slot` is absent (HIMC Disable*). Refused while
/// the axis moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FilterDisable {
    pub axis: AxisIndex,
    #[serde(default)]
    pub slot: Option<crate::filter::FilterSlot>,
}

fn one() -> f64 {
    1.0
}
