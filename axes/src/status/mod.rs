//! The vendor-neutral axis status record (ARCHITECTURE §3.4) and the machine snapshot.
//!
//! Every vendor status word (HMC AxisStatus/LimitState, NMC `BIT_AXIS_*`, HIMC `Is*`, CPU 226H
//! STATUS, CiA 402 statusword) is a pure function of [`AxisStatus`] plus the dialect's own
//! latched bits; those functions live in the dialects.

use serde::{Deserialize, Serialize};

use crate::homing::HomingFailure;
use crate::types::{AxisIndex, CommandId, CommandKind, ErrorKind, StreamMode};

mod coupling;
mod gang;
mod group;
mod snapshot;
pub use coupling::{CouplingKind, CouplingPhase, CouplingStatus};
mod follow;
pub use follow::{FollowDirection, FollowEvent, FollowState, FollowStatus};
mod gantry_home;
pub use gantry_home::{GantryHomePhase, GantryHomeStatus};
mod stream_arm;
pub use gang::{GantryStatus, HandwheelStatus};
pub use stream_arm::StreamInputStart;
mod trigger;
pub use group::{GroupFault, GroupState, GroupStatus, InterferenceStatus};
pub use snapshot::Snapshot;
pub use trigger::{
    CaptureEdge, CaptureSource, CaptureState, CaptureStatus, CaptureWindow, CompareOutputMode,
    CompareState, CompareStatus, Latch, PositionSource, ZCompareStatus,
};

/// PLCopen axis state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisState {
    #[default]
    Disabled,
    Standstill,
    Homing,
    DiscreteMotion,
    ContinuousMotion,
    SynchronizedMotion,
    Stopping,
    ErrorStop,
}

impl AxisState {
    /// snake_case name, as in traces and JSON.
    pub const fn name(self) -> &'static str {
        match self {
            AxisState::Disabled => "disabled",
            AxisState::Standstill => "standstill",
            AxisState::Homing => "homing",
            AxisState::DiscreteMotion => "discrete_motion",
            AxisState::ContinuousMotion => "continuous_motion",
            AxisState::SynchronizedMotion => "synchronized_motion",
            AxisState::Stopping => "stopping",
            AxisState::ErrorStop => "error_stop",
        }
    }
}

impl std::fmt::Display for AxisState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

bitflags::bitflags! {
    /// Axis flags. The same type carries the live flags and the latched faults.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
    #[serde(transparent)]
    pub struct AxisFlags: u32 {
        const ENABLED = 1 << 0;
        /// The commanded position is changing.
        const MOVING = 1 << 1;
        /// Motion done and |following error| within the window for the window time.
        const IN_POSITION = 1 << 2;
        const HOMED = 1 << 3;
        const HW_LIMIT_POS = 1 << 4;
        const HW_LIMIT_NEG = 1 << 5;
        const SW_LIMIT_POS = 1 << 6;
        const SW_LIMIT_NEG = 1 << 7;
        const HOME_SWITCH = 1 << 8;
        const INDEX = 1 << 9;
        /// |FE| over the limit at least once recently (auto-clearing, HMC AxisStatus bit 1).
        const FE_WARNING = 1 << 10;
        /// |FE| over the limit for `fe_fault_cycles` consecutive ticks (latched, HMC bit 0).
        const FE_FAULT = 1 << 11;
        const DRIVE_ALARM = 1 << 12;
        const ESTOP = 1 << 13;
        const CAPTURE_TRIGGERED = 1 << 14;
        /// A parameter write was corrected (HMC AxisStatus bit 2, latched).
        const PARAMETER_ERROR = 1 << 15;
        const QUEUE_FULL = 1 << 16;
        const IN_GROUP = 1 << 17;
        const ENCODER_LOSS = 1 << 18;
        /// Paused by `halt`, waiting for `resume`.
        const HALTED = 1 << 19;
        const HOMING_FAILED = 1 << 20;
        /// The last motion command ended in an error or could not start (NMC BIT_AXIS_MVERR).
        const MOTION_ERROR = 1 << 21;
        /// Soft-limit parameters inconsistent: positive limit ≤ negative limit (HMC LimitState bit 4).
        const SW_LIMIT_CONFIG = 1 << 22;
        /// Both limits of one kind active at once (HMC LimitState bit 5).
        const BOTH_LIMITS = 1 << 23;
        /// Accelerating (|v| increasing) — HIMC IsAcc.
        const ACCELERATING = 1 << 24;
        /// The slave of a gear or cam (HIMC IsGearSlave): single-axis motion is refused.
        const COUPLED = 1 << 25;
        /// A coupled slave past its clutch or start, following exactly (HIMC IsInGear,
        /// PLCopen InGear/InSync).
        const IN_SYNC = 1 << 26;
        /// A PT/PVT stream ran out of points while moving (latched, issue 12 item 3).
        const STREAM_UNDERRUN = 1 << 27;
        /// A gantry axis whose deviation from its master is over the warning limit
        /// (auto-clearing, HMC AxisStatus bit 5; issue 12 item 6).
        const GANTRY_WARNING = 1 << 28;
        /// A gantry's deviation went over the fault limit (HMC AxisStatus bit 6): latched on
        /// the master (an error-stop fault until `reset`), shown on its slaves while latched.
        const GANTRY_FAULT = 1 << 29;
        /// Driven by a handwheel (issue 12 item 7): single-axis motion is refused.
        const HANDWHEEL = 1 << 30;
        /// The compensation went over `compensation_limit` (latched, an error-stop fault;
        /// HIMC eERR_AXIS_COMP_LIMIT, digest 004 §2.13).
        const COMPENSATION_LIMIT = 1 << 31;
    }
}

impl std::fmt::Display for AxisFlags {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.is_empty() {
            return f.write_str("none");
        }
        bitflags::parser::to_writer(self, f)
    }
}

impl AxisFlags {
    /// Set or clear `flag` without a branch (`bitflags`' `set` branches; this runs a dozen
    /// times per axis per tick).
    #[inline]
    pub fn put(&mut self, flag: AxisFlags, on: bool) {
        let mask = flag.bits();
        let bits = (self.bits() & !mask) | (mask & (on as u32).wrapping_neg());
        *self = AxisFlags::from_bits_retain(bits);
    }

    /// Faults that put the axis into ErrorStop while latched.
    pub const ERROR_STOP_FAULTS: AxisFlags = AxisFlags::FE_FAULT
        .union(AxisFlags::DRIVE_ALARM)
        .union(AxisFlags::ESTOP)
        .union(AxisFlags::ENCODER_LOSS)
        .union(AxisFlags::HOMING_FAILED)
        .union(AxisFlags::STREAM_UNDERRUN)
        .union(AxisFlags::GANTRY_FAULT)
        .union(AxisFlags::COMPENSATION_LIMIT);

    /// Flags that can be latched and must be cleared by `reset`.
    pub const LATCHABLE: AxisFlags = AxisFlags::ERROR_STOP_FAULTS
        .union(AxisFlags::PARAMETER_ERROR)
        .union(AxisFlags::MOTION_ERROR)
        .union(AxisFlags::HW_LIMIT_POS)
        .union(AxisFlags::HW_LIMIT_NEG)
        .union(AxisFlags::SW_LIMIT_POS)
        .union(AxisFlags::SW_LIMIT_NEG);
}

/// Every axis flag and its snake_case name, in bit order: the names the control API, traces and
/// register maps use. A fixed table, so that renaming a constant cannot silently change them.
pub const FLAG_NAMES: [(AxisFlags, &str); 32] = [
    (AxisFlags::ENABLED, "enabled"),
    (AxisFlags::MOVING, "moving"),
    (AxisFlags::IN_POSITION, "in_position"),
    (AxisFlags::HOMED, "homed"),
    (AxisFlags::HW_LIMIT_POS, "hw_limit_pos"),
    (AxisFlags::HW_LIMIT_NEG, "hw_limit_neg"),
    (AxisFlags::SW_LIMIT_POS, "sw_limit_pos"),
    (AxisFlags::SW_LIMIT_NEG, "sw_limit_neg"),
    (AxisFlags::HOME_SWITCH, "home_switch"),
    (AxisFlags::INDEX, "index"),
    (AxisFlags::FE_WARNING, "fe_warning"),
    (AxisFlags::FE_FAULT, "fe_fault"),
    (AxisFlags::DRIVE_ALARM, "drive_alarm"),
    (AxisFlags::ESTOP, "estop"),
    (AxisFlags::CAPTURE_TRIGGERED, "capture_triggered"),
    (AxisFlags::PARAMETER_ERROR, "parameter_error"),
    (AxisFlags::QUEUE_FULL, "queue_full"),
    (AxisFlags::IN_GROUP, "in_group"),
    (AxisFlags::ENCODER_LOSS, "encoder_loss"),
    (AxisFlags::HALTED, "halted"),
    (AxisFlags::HOMING_FAILED, "homing_failed"),
    (AxisFlags::MOTION_ERROR, "motion_error"),
    (AxisFlags::SW_LIMIT_CONFIG, "sw_limit_config"),
    (AxisFlags::BOTH_LIMITS, "both_limits"),
    (AxisFlags::ACCELERATING, "accelerating"),
    (AxisFlags::COUPLED, "coupled"),
    (AxisFlags::IN_SYNC, "in_sync"),
    (AxisFlags::STREAM_UNDERRUN, "stream_underrun"),
    (AxisFlags::GANTRY_WARNING, "gantry_warning"),
    (AxisFlags::GANTRY_FAULT, "gantry_fault"),
    (AxisFlags::HANDWHEEL, "handwheel"),
    (AxisFlags::COMPENSATION_LIMIT, "compensation_limit"),
];

/// The names of the flags set in `flags`, in bit order.
pub fn flag_names(flags: AxisFlags) -> Vec<&'static str> {
    FLAG_NAMES
        .iter()
        .filter(|(flag, _)| flags.contains(*flag))
        .map(|(_, name)| *name)
        .collect()
}

/// The flag called `name`.
pub fn flag_by_name(name: &str) -> Option<AxisFlags> {
    FLAG_NAMES
        .iter()
        .find(|(_, n)| *n == name)
        .map(|(flag, _)| *flag)
}

/// A reference to the command at a FIFO position.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CommandRef {
    pub id: CommandId,
    pub kind: CommandKind,
}

/// Everything a front-end may want to know about one axis, after one tick. `Copy` so that
/// publishing a snapshot is a memcpy.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct AxisStatus {
    pub state: AxisState,
    /// Live flags (switch levels, motion, enable …) and latched faults.
    pub flags: AxisFlags,
    /// The subset of `flags` that is latched until a reset.
    pub latched: AxisFlags,
    /// Commanded (planned) position, user units (HMC DPos, NMC prfPos).
    pub cmd_pos: f64,
    pub cmd_vel: f64,
    pub cmd_acc: f64,
    /// Actual position from feedback, user units (HMC MPos, NMC encPos/Ke).
    pub act_pos: f64,
    pub act_vel: f64,
    /// cmd_pos − act_pos (HMC FE).
    pub following_error: f64,
    /// Target of the running command (HMC EndPos).
    pub target_pos: f64,
    /// Distance from the commanded position to the target, unwrapped on cyclic axes (HMC Remain).
    pub remaining: f64,
    /// Direction of the last motion, +1 or −1 (HMC Direction).
    pub motion_direction: i8,
    /// Pulse output counter (integer pulses, signed).
    pub pulses: i64,
    /// Pulses emitted in the last tick (HMC PulseNum, signed).
    pub pulses_last_tick: i32,
    /// Pulse frequency of the last tick, Hz, signed.
    pub pulse_frequency: f64,
    /// Direction output level (true = positive, before inversion).
    pub direction: bool,
    /// Encoder counter.
    pub encoder_counts: i64,
    /// Quadrature levels: bit 0 = A, bit 1 = B.
    pub quadrature: u8,
    /// Servo output of a closed position loop (HMC DACOut).
    pub dac_out: f64,
    /// Commands in the FIFO, the running one included.
    pub fifo_len: u16,
    pub current_command: Option<CommandRef>,
    pub next_command: Option<CommandRef>,
    /// Phase of a running homing, 0 when none (vendor maps refine it).
    pub homing_phase: u8,
    /// The error that ended the last command or the last refused command, if any.
    pub last_error: Option<ErrorKind>,
    /// Edges latched by the axis's capture channels since they were armed (issue 12 item 4).
    #[serde(default)]
    pub captures: u32,
    /// The actual position of the newest of those latches (0 when none).
    #[serde(default)]
    pub capture_position: f64,
    /// Outputs fired by the compare channels whose (first) axis this is (issue 12 item 5).
    #[serde(default)]
    pub compare_outputs: u32,
    /// The axis's PT/PVT stream (issue 12 item 3).
    #[serde(default)]
    pub stream: StreamStatus,
    /// The position sent to the drive: `cmd_pos` (planned) plus `compensation` (issue 12
    /// item 8; NMC cmdPos vs axisPos, HIMC GetPosOut).
    #[serde(default)]
    pub output_pos: f64,
    /// The correction compensation after the planner adds this tick (HIMC GetCompPos).
    #[serde(default)]
    pub compensation: f64,
    /// The kind of the coupling whose slave the axis is (issue 12; `coupling` in traces).
    #[serde(default)]
    pub coupling: Option<CouplingKind>,
    /// Gantry slave: its deviation from the master, (slave − master actual) − the offset at
    /// engagement; gantry master: the largest of its slaves' by magnitude (issue 12 item 6).
    #[serde(default)]
    pub gantry_deviation: f64,
    /// The user frame's origin offset: commanded position − motor command, moved by
    /// `set_position` and homing (HIMC GetPosOffset, `pos_offset`).
    #[serde(default)]
    pub position_offset: f64,
    /// Whole turns of a rollover (cyclic) axis past its range's start (HIMC GetRolloverTurns);
    /// 0 on a finite axis.
    #[serde(default)]
    pub rollover_turns: i64,
    /// Seconds the last finished move's commanded position changed (HIMC GetMoveTime).
    #[serde(default)]
    pub move_time: f64,
    /// Seconds from the end of the last move until in position; 0 while not settled (HIMC
    /// GetSettlingTime).
    #[serde(default)]
    pub settling_time: f64,
    /// The drive's torque as a fraction of rated torque (`rated_torque`): the setpoint in
    /// torque mode, else the commanded acceleration over the rated one (HIMC GetCurrFb).
    #[serde(default)]
    pub torque: f64,
    /// Changes of the dedicated inputs as the controller reads them, wrapping: negative limit,
    /// positive limit, home, index (NMC GetDiReverseCount types 1–4).
    #[serde(default)]
    pub input_edges: [u32; 4],
    /// The level of the axis's Z-phase output (the encoder-output port's Z line, which HMC
    /// SwitchTZ and Switch ucOutputMode 1 drive as a fast output; issue 12 item 5). Low unless
    /// a `z_compare` channel drives it.
    #[serde(default)]
    pub z_output: bool,
    /// The HMC axis position compensation offset: the part of `compensation` that
    /// `compensation_offset_trigger` moves (issue 12 item 8).
    #[serde(default)]
    pub compensation_offset: f64,
    /// That offset's move is in progress (HMC GetAxisCompenState 1; 0 done).
    #[serde(default)]
    pub compensation_offset_moving: bool,
    /// The active command filter after smoothing (issue 14: input shaper or VSF); `cmd_pos`
    /// is its output.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub command_filter: Option<crate::filter::FilterStatus>,
    /// The dedicated inputs' active states this tick, after their configured sense and never
    /// latched: HW_LIMIT_POS, HW_LIMIT_NEG, HOME_SWITCH, INDEX, DRIVE_ALARM (an alarm input
    /// that is not enabled reads inactive). NMC_MtGetMotionIO reads these (TV40).
    #[serde(default)]
    pub inputs: AxisFlags,
    /// Why the last homing failed, while HOMING_FAILED says it did (NMC home status bits 3/4).
    #[serde(default)]
    pub homing_failure: Option<HomingFailure>,
    /// The home point the last homing found minus the one the last completed homing defined,
    /// user units (NMC_MtGetHomeError; 0 until a home point is found).
    #[serde(default)]
    pub home_error: f64,
    /// The HMC add axis whose commanded travel is added to this axis's own (`add_axis_set`,
    /// HMC_GetAddAxis; none is HMC's 255).
    #[serde(default)]
    pub add_axis: Option<AxisIndex>,
    /// The actual position's user-frame offset in encoder counts (rounded): what
    /// `set_position` (frames actual and both) and homing moved it by. `encoder_counts +
    /// encoder_offset` is the counter of a controller that redefines its encoder with the
    /// position (NMC encPos; a CiA 402 drive's 0x6064), `encoder_counts` the raw one.
    #[serde(default)]
    pub encoder_offset: i64,
}

/// An axis's PT/PVT buffer and run (NMC `MtPtGetSpace`, `MtPtGetStatic`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StreamStatus {
    pub mode: StreamMode,
    /// The stream is running (the axis's command source).
    pub running: bool,
    /// Points the buffer can take now (NMC `pSpace`).
    pub space: u16,
    /// Points held (NMC `pUsed`): in refresh mode those of a FIFO half not yet run out count.
    pub used: u16,
    /// Static mode: runs asked for (0 = until stopped).
    pub loop_count: u32,
    /// Static mode: runs completed of the current start.
    pub loops_done: u32,
    /// Times a stream ran dry while moving (`STREAM_UNDERRUN`), since power-on.
    pub underruns: u32,
    /// Milliseconds since the running stream started (0 when none runs).
    pub time_ms: f64,
}

/// Digital and analog I/O images of the machine.
#[derive(Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct IoImage {
    pub di: Vec<bool>,
    pub do_: Vec<bool>,
    pub ai: Vec<f64>,
    pub ao: Vec<f64>,
    /// Changes of each digital input since start, wrapping (NMC GetDiReverseCount).
    #[serde(default)]
    pub di_edges: Vec<u32>,
    /// Pulses the timed-output trains (`pulse_digital_output`, `group_pulse_output`) have
    /// completed on each digital output since start, wrapping: a pulse is one hold of the
    /// level a train starts at (NMC AdvBufIoGetPulseCnt).
    #[serde(default)]
    pub do_pulses: Vec<u32>,
}

impl Clone for IoImage {
    fn clone(&self) -> Self {
        IoImage {
            di: self.di.clone(),
            do_: self.do_.clone(),
            ai: self.ai.clone(),
            ao: self.ao.clone(),
            di_edges: self.di_edges.clone(),
            do_pulses: self.do_pulses.clone(),
        }
    }

    /// Field by field, reusing the vectors: snapshots are refreshed every tick and must not
    /// allocate (the derived `clone_from` would replace each vector).
    fn clone_from(&mut self, source: &Self) {
        self.di.clone_from(&source.di);
        self.do_.clone_from(&source.do_);
        self.ai.clone_from(&source.ai);
        self.ao.clone_from(&source.ao);
        self.di_edges.clone_from(&source.di_edges);
        self.do_pulses.clone_from(&source.do_pulses);
    }
}

/// A CiA 402 drive as its master sees it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DriveStatus {
    /// The axis the drive moves.
    pub axis: u16,
    /// 0x6041.
    pub statusword: u16,
    /// 0x6061.
    pub mode: i8,
    /// 0x603F.
    pub error_code: u16,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_names_every_flag_as_its_constant_in_snake_case() {
        let table: Vec<(AxisFlags, String)> = FLAG_NAMES
            .iter()
            .map(|(f, n)| (*f, n.to_string()))
            .collect();
        let constants: Vec<(AxisFlags, String)> = AxisFlags::all()
            .iter_names()
            .map(|(n, f)| (f, n.to_ascii_lowercase()))
            .collect();
        assert_eq!(table, constants);
    }
}
