//! What the 0x17xx family keeps between calls (digest 001 §2.7, §2.20 C3§10.5, §3.7): each
//! coordinate system's transform, XYZA parameters, arc-section table, A-axis corner velocity
//! and break point, and the device's move protection. The engine's group keeps the transform
//! and the protection it carries out; this is the manual's view of them, read back as written.

use axes::command::{Command, GroupId, GroupParameter, GroupSetParameter, GroupSetPolarTransform};
use mcemu_dialects::PulseScale;
use mcemu_nmc::crd::CRD_MAX_AXES;
use mcemu_nmc::crd_frames::{ArcSecSetting, MvProtectPara};

use super::crd::CRD_COUNT;

/// The transform a coordinate system has (one at a time, as the engine's group has).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum CrdTransform {
    #[default]
    None,
    /// `NMC_CrdSetTransRotate`: the table axis, rad/pulse, the centre (X, Y pulses).
    Rotary {
        axis: usize,
        rad_per_pulse: f64,
        center: [i64; 2],
    },
    /// `NMC_CrdSetTransPolar`: the rotary and the linear axis, rad/pulse of the rotary.
    /// `path`: the two are the coordinate system's X and Y axes, so the engine group feeds them
    /// the path's (θ, r) (`group_set_polar_transform`); else only `RunToPolarPos/Theta` use it.
    Polar {
        rot_axis: usize,
        trans_axis: usize,
        rot_equiv: f64,
        path: bool,
    },
    /// `NMC_CrdSetTransXYZA`: the X, Y, Z, A axes (the coordinate system's members in order).
    Xyza { map: [usize; CRD_MAX_AXES] },
}

impl CrdTransform {
    /// The engine's polar transform of group `n` when this is the polar transform of the crd's
    /// own X and Y axes; `pulses_per_unit(axis)` (θ = pulses × rotEquiv = units × pulses per
    /// unit × rotEquiv).
    pub fn polar_command(
        &self,
        n: usize,
        pulses_per_unit: impl Fn(usize) -> f64,
    ) -> Option<Command> {
        let CrdTransform::Polar {
            rot_axis,
            trans_axis,
            rot_equiv,
            path: true,
        } = *self
        else {
            return None;
        };
        Some(
            GroupSetPolarTransform {
                group: n as GroupId,
                rotary: rot_axis as u16,
                feed: trans_axis as u16,
                rotary_units_per_radian: 1.0 / (rot_equiv * pulses_per_unit(rot_axis)),
                plane: None,
            }
            .into(),
        )
    }
}

/// One coordinate system's settings of this family.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrdFrames {
    pub transform: CrdTransform,
    /// `NMC_CrdSetXYZAPara`: A's rad/pulse and the tool offset (X, Y pulses).
    pub pulse2rad: f64,
    pub tool: [i64; 2],
    pub arc_sec: ArcSecSetting,
    /// `NMC_CrdSetFourthAxisToTurnVel`, pulse/ms (0: not set).
    pub fourth_axis_turn_vel: f64,
    /// Where the path was when `NMC_CrdEstopMtn` stopped it (user coordinates, pulses).
    pub break_point: Option<[i64; CRD_MAX_AXES]>,
}

impl Default for CrdFrames {
    fn default() -> CrdFrames {
        CrdFrames {
            transform: CrdTransform::None,
            pulse2rad: 0.0,
            tool: [0; 2],
            arc_sec: ArcSecSetting::default(),
            fourth_axis_turn_vel: 0.0,
            break_point: None,
        }
    }
}

/// The device's move protection (NMC has one, groupNo 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MvProtect {
    pub para: MvProtectPara,
    /// `NMC_SetMvProtect`'s mode while enabled.
    pub mode: Option<i16>,
}

impl MvProtect {
    /// Enabled and guarding coordinate system `n`.
    pub fn guards(&self, n: usize) -> bool {
        self.mode.is_some()
            && self
                .para
                .crd_no
                .iter()
                .any(|c| usize::try_from(*c).ok() == Some(n))
    }
}

/// This family's state of one device.
#[derive(Clone, Debug, Default)]
pub struct FramesState {
    pub crd: [CrdFrames; CRD_COUNT],
    pub protect: MvProtect,
}

impl FramesState {
    /// `NMC_CrdConfig` of coordinate system `n`: the new group has no transform and no break
    /// point, a protection guarding the old group ended with it; the arc-section table to
    /// give the new group.
    pub fn on_config(&mut self, n: usize) -> ArcSecSetting {
        if self.protect.guards(n) {
            self.protect.mode = None;
        }
        match self.crd.get_mut(n) {
            Some(f) => {
                f.transform = CrdTransform::None;
                f.break_point = None;
                f.arc_sec
            }
            None => ArcSecSetting::default(),
        }
    }

    /// `NMC_CrdSetFourthAxisToTurnVel`'s tolVel of `n` (0: off).
    pub fn crd_turn_vel(&self, n: usize) -> f64 {
        self.crd.get(n).map_or(0.0, |f| f.fourth_axis_turn_vel)
    }

    /// `NMC_CrdDelete`: the family's settings of `n` back to their defaults.
    pub fn on_delete(&mut self, n: usize) {
        if self.protect.guards(n) {
            self.protect.mode = None;
        }
        if let Some(f) = self.crd.get_mut(n) {
            *f = CrdFrames::default();
        }
    }

    /// `NMC_CrdEstopMtn`: the path of `n` was at `at` (user coordinates, pulses).
    pub fn note_break(&mut self, n: usize, at: [i64; CRD_MAX_AXES]) {
        if let Some(f) = self.crd.get_mut(n) {
            f.break_point = Some(at);
        }
    }
}

/// The engine's chord error bands for the table `a`, pulses: (err0, [r0, r1], [err1, err2])
/// — err0 up to r0, err1 up to r1, err2 beyond (0: no limit in that band); all 0 (off) when
/// the radii are all 0 ("all 0 = feature off").
pub fn chord_error(a: &ArcSecSetting) -> (f64, [f64; 2], [f64; 2]) {
    if a.r.iter().all(|r| *r == 0.0) {
        return (0.0, [0.0; 2], [0.0; 2]);
    }
    (a.err[0], [a.r[0], a.r[1]], [a.err[1], a.err[2]])
}

/// The group parameters of the table `a` for group `n`, in the pulses of `scale` (the group's
/// first member): the band edges, then the bands' errors, then the first band's
/// (`chord_error`).
pub fn chord_commands(n: usize, scale: PulseScale, a: &ArcSecSetting) -> Vec<Command> {
    let (first, edges, errors) = chord_error(a);
    [
        (GroupParameter::ChordErrorRadius1, edges[0]),
        (GroupParameter::ChordErrorRadius2, edges[1]),
        (GroupParameter::ChordErrorBand1, errors[0]),
        (GroupParameter::ChordErrorBand2, errors[1]),
        (GroupParameter::ChordError, first),
    ]
    .into_iter()
    .map(|(name, value)| {
        GroupSetParameter {
            group: n as GroupId,
            name,
            value: scale.to_engine(value),
        }
        .into()
    })
    .collect()
}

/// The engine's corner speed of the fourth coordinate (the A axis) for tolVel of group `n`
/// (0: off), in the units of `scale` (the A axis's).
pub fn turn_vel_command(n: usize, scale: PulseScale, tol_vel: f64) -> Command {
    GroupSetParameter {
        group: n as GroupId,
        name: GroupParameter::FourthCoordinateCornerVelocity,
        value: mcemu_dialects::nmc::velocity_to_engine(scale, tol_vel),
    }
    .into()
}
