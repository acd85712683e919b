//! The coupling family: a slave axis that follows a master axis through an electronic gear or a
//! cam table (issue 12 items 1–2). Applied by `Engine::apply_coupling_command`; the per-tick
//! work is `crate::coupling`.

use serde::{Deserialize, Serialize};

use super::superimpose::{
    SuperimposeIn, SuperimposeOut, SuperimposeSetRatios, TangentialCornerContinue,
    TangentialCornerFollowNext, TangentialCornerMode, TangentialIn, TangentialOut,
};
use super::AddAxisSet;
use super::{
    command_from, AxisIndex, Direction, FollowClear, FollowConfig, FollowOut, FollowPush,
    FollowStart, FollowSwitch, GantryDisable, GantryEnable, GantrySetPid, GantrySetPosition,
    HandwheelIn, HandwheelOut, HandwheelSetRatio, HandwheelTurn, MasterSource,
};

/// Couple `slave` to `master` through a gear: slave travel = numerator / denominator × master
/// travel (PLCopen MC_GearIn; NMC MtGearSetRatio/StartMtn, HMC_Gear, HIMC GearIn). JSON `type`:
/// `gear_in`.
///
/// The clutch: `clutch_distance` ramps the ratio linearly from 0 over that much master travel
/// (NMC `masterSlope`); `acceleration` brings the slave's velocity to ratio × master velocity
/// with that acceleration, then locks the positions (PLCopen: InGear once the velocities match);
/// neither engages at once. `direction` makes the slave follow only master travel that way
/// (NMC MtGearSetDir).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearIn {
    pub master: AxisIndex,
    pub slave: AxisIndex,
    pub numerator: f64,
    pub denominator: f64,
    #[serde(default)]
    pub master_source: MasterSource,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clutch_distance: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub acceleration: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<Direction>,
    /// Servo periods the slave runs behind the gear, 0 to 128 (HMC_SetGearPhaseOffset, digest
    /// 000 §4.3: "delays the slave trajectory"; fixed while the gear runs).
    #[serde(default, skip_serializing_if = "is_zero_u32")]
    pub phase_offset: u32,
    /// HMC_SetGearTransationSwitch = 1 (digest 000 §4.3): engage, and change the ratio, with
    /// the slave's own `accel` (speeding up) and `decel` (slowing down), then lock the positions
    /// once the velocities match. Not with `clutch_distance` or `acceleration`.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub transition: bool,
}

/// Change the ratio of a running gear (HMC_SetGearRatio, NMC MtGearSetRatio in motion), through
/// the gear's own clutch. JSON `type`: `gear_set_ratio`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearSetRatio {
    pub slave: AxisIndex,
    pub numerator: f64,
    pub denominator: f64,
}

/// Decouple a gear's slave: it keeps its velocity and decelerates to rest with its `decel`
/// (PLCopen MC_GearOut, HIMC GearOut). JSON `type`: `gear_out`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearOut {
    pub slave: AxisIndex,
}

/// How a cam table is interpolated between its points.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CamInterpolation {
    /// Straight lines (HMC_Cam).
    #[default]
    Linear,
    /// A natural cubic spline through the points (HMC_SplineCam): no velocity steps inside.
    Cubic,
    /// NMC Follow segments: each point's `segment` says how the slave's velocity runs from the
    /// previous point (digest 001 §4.7), starting from rest.
    Follow,
}

/// How the slave's velocity (its ratio to the master's) runs through an NMC Follow segment
/// (NMC_MtFollowPushData `type`, the PT rules with master travel for time).
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FollowSegment {
    /// 0: the ratio runs linearly and ends at 2·Δslave/Δmaster − its start.
    #[default]
    Normal,
    /// 1: constant ratio Δslave/Δmaster.
    Even,
    /// 2: the ratio ends at 0 (it starts at 2·Δslave/Δmaster).
    Stop,
    /// 3: as `normal`, the ratio continuous across FIFOs.
    Continuous,
}

/// One point of a cam table: master position → slave position.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamPoint {
    /// Master position (the table's coordinate).
    pub master: f64,
    /// Slave position at that master position.
    pub slave: f64,
    /// With `follow` interpolation: the segment that ends at this point.
    #[serde(default, skip_serializing_if = "is_normal")]
    pub segment: FollowSegment,
}

fn is_normal(s: &FollowSegment) -> bool {
    *s == FollowSegment::Normal
}

/// Define (or replace) cam table `table`: at least 2 points, master positions strictly
/// increasing. A table a running cam uses cannot be replaced (HMC: "arrays must not be modified
/// while the cam runs"). JSON `type`: `cam_table`.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamTableDefine {
    /// The table's number, as `cam_in` names it.
    pub table: u16,
    /// At least 2 points, master positions strictly increasing (at most 4096).
    pub points: Vec<CamPoint>,
    #[serde(default)]
    pub interpolation: CamInterpolation,
}

fn one() -> f64 {
    1.0
}

fn is_one(v: &f64) -> bool {
    *v == 1.0
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_false(v: &bool) -> bool {
    !*v
}

fn is_zero_u32(v: &u32) -> bool {
    *v == 0
}

/// Couple `slave` to `master` through cam table `table` (PLCopen MC_CamIn, HMC_Cam modes 0–7,
/// NMC Follow). JSON `type`: `cam_in`.
///
/// The table's master coordinate is x = (master − `master_offset`) / `master_scaling`, measured
/// from the master position where the cam starts unless `master_absolute` (then the table's
/// first point lies there); the slave is `slave_scaling` × table value + `slave_offset`, added
/// to the slave position where the cam starts unless `slave_absolute`. `periodic`: the table
/// repeats, each period starting the slave where the last ended (HMC cyclic cam), for
/// `loop_count` periods (0 = for ever, NMC FollowSetLoopCount); otherwise the cam ends when the
/// master leaves the table. Start: at once, or when the master crosses `start_position` (in
/// `start_direction`, either way if absent: HMC fixed-position modes 1/5, NMC FollowSetEvent 2),
/// or when digital input `start_input` is on (HMC DI modes 3/7), or when capture channel
/// `start_capture` of the master latches (HMC event modes 2/6: the cam starts at the latched
/// master position).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamIn {
    pub master: AxisIndex,
    pub slave: AxisIndex,
    pub table: u16,
    #[serde(default)]
    pub master_source: MasterSource,
    #[serde(default, skip_serializing_if = "is_false")]
    pub periodic: bool,
    #[serde(default, skip_serializing_if = "is_zero_u32")]
    pub loop_count: u32,
    #[serde(default, skip_serializing_if = "is_false")]
    pub master_absolute: bool,
    #[serde(default, skip_serializing_if = "is_false")]
    pub slave_absolute: bool,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub master_offset: f64,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub slave_offset: f64,
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub master_scaling: f64,
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub slave_scaling: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_position: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_direction: Option<Direction>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_input: Option<u16>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_capture: Option<u8>,
}

/// Define cam table `table` as HMC's link profile (HMC_MoveLink / HMC_MoveFlexLink, digest 000
/// §4.3, §3.2; manual §4.3.6.4, §4.3.6.7–4.3.6.8): over master 0..`master_distance` the slave
/// travels `slave_base_distance` at a constant ratio plus `slave_distance` whose ratio ramps up
/// over `master_acceleration_distance`, holds, and ramps down over
/// `master_deceleration_distance`, between the master's first `master_before_distance` and
/// last `master_after_distance` (`crate::coupling` `link`). `s_ratio` 0 ramps linearly, (0, 1]
/// with HMC's S-curve fractions. HMC MoveLink is this table and `cam_in` with relative master
/// and slave and the mode's start. JSON `type`: `cam_table_link`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamTableLink {
    pub table: u16,
    /// dSlaveDistance (FlexLink: dSlaveAddDist).
    pub slave_distance: f64,
    /// dMasterDistance (FlexLink: dMasterSumDist), > 0.
    pub master_distance: f64,
    /// dMasterDistAcc, ≥ 0.
    pub master_acceleration_distance: f64,
    /// dMasterDistDec, ≥ 0.
    pub master_deceleration_distance: f64,
    /// dSRatio, [0, 1].
    #[serde(default, skip_serializing_if = "is_zero")]
    pub s_ratio: f64,
    /// FlexLink dSlaveBaseDist.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub slave_base_distance: f64,
    /// FlexLink dMasterBeforeDist, ≥ 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub master_before_distance: f64,
    /// FlexLink dMasterAfterDist, ≥ 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub master_after_distance: f64,
}

/// Decouple a cam's slave (PLCopen MC_CamOut): as `gear_out`. JSON `type`: `cam_out`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamOut {
    pub slave: AxisIndex,
}

/// Commands that couple a slave axis to a master (gear, cam).
#[derive(Clone, Debug, PartialEq)]
pub enum CouplingCommand {
    GearIn(GearIn),
    GearSetRatio(GearSetRatio),
    GearOut(GearOut),
    CamTable(CamTableDefine),
    CamIn(CamIn),
    CamOut(CamOut),
    SuperimposeIn(SuperimposeIn),
    SuperimposeSetRatios(SuperimposeSetRatios),
    SuperimposeOut(SuperimposeOut),
    TangentialIn(TangentialIn),
    TangentialOut(TangentialOut),
    GantryEnable(GantryEnable),
    GantryDisable(GantryDisable),
    HandwheelIn(HandwheelIn),
    HandwheelOut(HandwheelOut),
    HandwheelTurn(HandwheelTurn),
    // NMC Follow FIFOs (digest 001 §2.17), `command/follow.rs`.
    FollowConfig(FollowConfig),
    FollowPush(FollowPush),
    FollowClear(FollowClear),
    FollowStart(FollowStart),
    FollowSwitch(FollowSwitch),
    FollowOut(FollowOut),
    HandwheelSetRatio(HandwheelSetRatio),
    // HMC MoveTang corner mode (engine-level: they touch the group too).
    TangentialCornerMode(TangentialCornerMode),
    TangentialCornerFollowNext(TangentialCornerFollowNext),
    TangentialCornerContinue(TangentialCornerContinue),
    CamTableLink(CamTableLink),
    // HMC_GantryGroupDefPos and HMC_SetGantryAxisPID (digest 000 §4.4), `command/gantry.rs`.
    GantrySetPosition(GantrySetPosition),
    GantrySetPid(GantrySetPid),
    // HMC_SetAddAxis (digest 000 §4.4), `command/add_axis.rs`.
    AddAxisSet(AddAxisSet),
}

impl CouplingCommand {
    /// The slave axis the command addresses (none for a table definition).
    pub fn axis(&self) -> Option<AxisIndex> {
        match self {
            CouplingCommand::GearIn(c) => Some(c.slave),
            CouplingCommand::GearSetRatio(c) => Some(c.slave),
            CouplingCommand::GearOut(c) => Some(c.slave),
            CouplingCommand::CamTable(_) => None,
            CouplingCommand::CamIn(c) => Some(c.slave),
            CouplingCommand::CamOut(c) => Some(c.slave),
            CouplingCommand::SuperimposeIn(c) => Some(c.slave),
            CouplingCommand::SuperimposeSetRatios(c) => Some(c.slave),
            CouplingCommand::SuperimposeOut(c) => Some(c.slave),
            CouplingCommand::TangentialIn(c) => Some(c.axis),
            CouplingCommand::TangentialOut(c) => Some(c.axis),
            CouplingCommand::GantryEnable(c) => Some(c.master),
            CouplingCommand::GantryDisable(c) => Some(c.master),
            CouplingCommand::HandwheelIn(c) => Some(c.axis),
            CouplingCommand::HandwheelOut(c) => Some(c.axis),
            CouplingCommand::HandwheelTurn(_) => None,
            CouplingCommand::FollowConfig(c) => Some(c.axis),
            CouplingCommand::FollowPush(c) => Some(c.axis),
            CouplingCommand::FollowClear(c) => Some(c.axis),
            CouplingCommand::FollowStart(c) => c.axes.first().copied(),
            CouplingCommand::FollowSwitch(c) => c.axes.first().copied(),
            CouplingCommand::FollowOut(c) => Some(c.axis),
            CouplingCommand::HandwheelSetRatio(c) => c.axis,
            CouplingCommand::TangentialCornerMode(c) => Some(c.axis),
            CouplingCommand::TangentialCornerFollowNext(c) => Some(c.axis),
            CouplingCommand::TangentialCornerContinue(c) => Some(c.axis),
            CouplingCommand::CamTableLink(_) => None,
            CouplingCommand::GantrySetPosition(c) => Some(c.master),
            CouplingCommand::GantrySetPid(c) => Some(c.axis),
            CouplingCommand::AddAxisSet(c) => Some(c.base),
        }
    }
}

command_from!(
    CouplingCommand,
    Coupling,
    [
        GearIn => GearIn,
        GearSetRatio => GearSetRatio,
        GearOut => GearOut,
        CamTableDefine => CamTable,
        CamIn => CamIn,
        CamOut => CamOut,
        SuperimposeIn => SuperimposeIn,
        SuperimposeSetRatios => SuperimposeSetRatios,
        SuperimposeOut => SuperimposeOut,
        TangentialIn => TangentialIn,
        TangentialOut => TangentialOut,
        GantryEnable => GantryEnable,
        GantryDisable => GantryDisable,
        HandwheelIn => HandwheelIn,
        HandwheelOut => HandwheelOut,
        HandwheelTurn => HandwheelTurn,
        FollowConfig => FollowConfig,
        FollowPush => FollowPush,
        FollowClear => FollowClear,
        FollowStart => FollowStart,
        FollowSwitch => FollowSwitch,
        FollowOut => FollowOut,
        HandwheelSetRatio => HandwheelSetRatio,
        TangentialCornerMode => TangentialCornerMode,
        TangentialCornerFollowNext => TangentialCornerFollowNext,
        TangentialCornerContinue => TangentialCornerContinue,
        CamTableLink => CamTableLink,
        GantrySetPosition => GantrySetPosition,
        GantrySetPid => GantrySetPid,
        AddAxisSet => AddAxisSet,
    ]
);
