//! The CiA 402 drive: controlword/statusword state machine and modes PP, PV, HM, CSP, CSV, CST,
//! bound to an axis of the engine (ARCHITECTURE §3.8; CiA 402-2 / IEC 61800-7-201).
//!
//! A [`Cia402Drive`] owns an object dictionary and is bound to one engine axis. It runs no
//! trajectory generator and no homing of its own: each servo tick [`Cia402Drive::step`] reads the
//! controlword, the mode and the targets from its dictionary and the axis's [`AxisStatus`],
//! emits engine [`Command`]s for its axis (power, moves, homing, setpoint streams, stops), and
//! publishes the statusword and actual values. Commands emitted by one `step` are applied before
//! the next; a refusal comes back through [`Cia402Drive::on_reply`] (internal limit bit 11,
//! warning bit 7, homing error, or a fault when the axis refuses power).
//!
//! Masters reach the dictionary through the drive ([`read`](Cia402Drive::read),
//! [`write`](Cia402Drive::write), [`read_bytes`](Cia402Drive::read_bytes),
//! [`write_bytes`](Cia402Drive::write_bytes)) so that read-only objects, types, lengths, ranges
//! and device rules (supported modes, homing methods) are enforced. The engine can also drive a
//! drive as its own slave (HIMC Enable/Disable/Reset through 0x6040/0x6041, ARCHITECTURE §3.8)
//! with [`controlword_for`].
//!
//! Units on the bus are increments (positions), increments/s and increments/s²;
//! [`DriveConfig::increments_per_unit`] converts them to the axis's user units.

mod cyclic;
mod hm;
mod modes;
mod objects;
mod power;
mod pp;
mod pv;
mod state;
mod statusword;

#[cfg(test)]
mod tests;

use serde::{Deserialize, Serialize};

use crate::command::{
    AxisCommand, AxisIndex, BufferMode, Command, CommandKind, Disable, Enable, EngineError, Halt,
    Home, MoveAbsolute, MoveRelative, MoveVelocity, PositionFrame, Reply, Reset, Resume,
    SetPosition, Setpoint, Stop, StopMode, StreamSetpoint,
};
use crate::homing::HomingQuirks;
use crate::od::{DefinitionError, ObjectDictionary, OdError, Value};
use crate::status::{AxisFlags, AxisState, AxisStatus};

pub use objects::{error_code, obj, object_table, supported_drive_modes};
pub use state::{controlword_for, cw, sw, DeviceCommand, OperationMode, PowerTarget, State};

/// What a drive is: its axis, its units and its identity.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DriveConfig {
    /// The engine axis the drive moves.
    pub axis: AxisIndex,
    /// Who writes the controlword: an external fieldbus master (CANopen, the default), or the
    /// engine itself, which then powers the axis through the drive's state machine on `enable`,
    /// `disable` and `reset` (an EtherCAT-style slave of the emulated controller, as HIMC's
    /// Enable/Disable/Reset work through 0x6040/0x6041).
    pub master: DriveMaster,
    /// Increments per axis user unit. Velocities (increments/s) and accelerations
    /// (increments/s²) scale with it.
    pub increments_per_unit: f64,
    /// 0x1008 manufacturer device name.
    pub name: String,
    /// 0x1009 manufacturer hardware version.
    pub hardware_version: String,
    /// 0x100A manufacturer software version.
    pub software_version: String,
    /// 0x1018:01 vendor ID.
    pub vendor_id: u32,
    /// 0x1018:02 product code.
    pub product_code: u32,
    /// 0x1018:03 revision number.
    pub revision: u32,
    /// 0x1018:04 serial number.
    pub serial: u32,
}

/// Who drives a drive's controlword.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DriveMaster {
    /// A master on a bus (CANopen SDO/PDO) writes 0x6040 and the targets.
    #[default]
    External,
    /// The engine walks the state machine on the axis's power commands.
    Engine,
}

impl Default for DriveConfig {
    fn default() -> Self {
        DriveConfig {
            axis: 0,
            master: DriveMaster::External,
            increments_per_unit: 1.0,
            name: "mcemu CiA 402 drive".to_string(),
            hardware_version: "simulated".to_string(),
            software_version: concat!("mcemu ", env!("CARGO_PKG_VERSION")).to_string(),
            vendor_id: 0,
            product_code: 0x0000_0402,
            revision: 0x0001_0000,
            serial: 0,
        }
    }
}

/// A drive configuration that cannot make a drive.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DriveConfigError {
    #[error("increments_per_unit = {0}: must be a finite number greater than zero")]
    IncrementsPerUnit(f64),
    #[error("`{field}` = {value:?}: must be printable ASCII (CiA 301 VISIBLE_STRING)")]
    NotVisibleString { field: &'static str, value: String },
    #[error("object table: {0}")]
    Table(#[from] DefinitionError),
}

impl DriveConfig {
    pub fn validate(&self) -> Result<(), DriveConfigError> {
        let ipu = self.increments_per_unit;
        if !(ipu.is_finite() && ipu > 0.0) {
            return Err(DriveConfigError::IncrementsPerUnit(ipu));
        }
        for (field, value) in [
            ("name", &self.name),
            ("hardware_version", &self.hardware_version),
            ("software_version", &self.software_version),
        ] {
            if !value.bytes().all(|b| (0x20..=0x7E).contains(&b)) {
                return Err(DriveConfigError::NotVisibleString {
                    field,
                    value: value.clone(),
                });
            }
        }
        Ok(())
    }
}

/// An emergency the drive raised: entering a fault (the 0x603F code) or leaving it (code 0).
/// The CANopen crate sends them as EMCY; other dialects may log them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Emergency {
    pub code: u16,
    /// 0x1001 error register at the time.
    pub register: u8,
}

/// Faults of the axis that put the drive into Fault reaction active, with their 0x603F codes,
/// in priority order.
const AXIS_FAULTS: [(AxisFlags, u16); 4] = [
    (AxisFlags::FE_FAULT, error_code::FOLLOWING_ERROR),
    (AxisFlags::ENCODER_LOSS, error_code::ENCODER),
    (AxisFlags::DRIVE_ALARM, error_code::DRIVE_ALARM),
    (AxisFlags::ESTOP, error_code::EMERGENCY_STOP),
];

fn axis_fault_flags() -> AxisFlags {
    AXIS_FAULTS
        .iter()
        .fold(AxisFlags::empty(), |all, (flag, _)| all | *flag)
}

const LIMIT_FLAGS: AxisFlags = AxisFlags::HW_LIMIT_POS
    .union(AxisFlags::HW_LIMIT_NEG)
    .union(AxisFlags::SW_LIMIT_POS)
    .union(AxisFlags::SW_LIMIT_NEG);

/// Progress of the last homing (statusword bits 13/12/10 in HM, CiA 402 Table "homing").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum HomingProgress {
    NotStarted,
    /// Started at step `since`; `direct` when method 37 ran as a position redefinition
    /// outside Operation enabled.
    InProgress {
        since: u64,
        direct: bool,
    },
    Attained,
    Error,
    Interrupted,
}

/// What happens when a stop ramp started by a transition has brought the axis to rest.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum AfterStop {
    /// Transitions 5 and 8 with option code 1: remove power.
    Disable,
    /// Quick stop active: options 1–4 go to Switch on disabled (12), 5–8 stay.
    QuickStopDone,
    /// Fault reaction active → Fault (14).
    FaultDone,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct PendingStop {
    issued_at: u64,
    then: AfterStop,
}

/// A condition that must hold for a time (the window times 0x6066, 0x6068, 0x606E, 0x6070).
#[derive(Clone, Copy, Debug, Default)]
struct Dwell {
    since: Option<f64>,
}

impl Dwell {
    fn update(&mut self, condition: bool, now: f64, millis: i64) -> bool {
        if !condition {
            self.since = None;
            return false;
        }
        let since = *self.since.get_or_insert(now);
        // A tolerance of 1 ns keeps `k × period` sums from missing an exact window time.
        now - since >= millis as f64 * 1e-3 - 1e-9
    }

    fn reset(&mut self) {
        self.since = None;
    }
}

/// One touch probe channel (0x60B8/0x60B9; ETG.6010 / CiA 402 touch probe function).
#[derive(Clone, Copy, Debug, Default)]
struct Probe {
    enabled: bool,
    positive: bool,
    negative: bool,
    previous_function: u8,
    previous_level: bool,
}

impl Probe {
    /// Advance with this tick's function byte and input level; returns which edges latched.
    fn update(&mut self, function: u8, level: bool) -> (bool, bool) {
        let armed = function & !self.previous_function;
        let rising = level && !self.previous_level;
        let falling = !level && self.previous_level;
        self.previous_function = function;
        self.previous_level = level;
        if function & 0x01 == 0 {
            *self = Probe {
                previous_function: function,
                previous_level: level,
                ..Probe::default()
            };
            return (false, false);
        }
        // Enabling the probe or an edge's sampling re-arms "first event" latching.
        if armed & 0x01 != 0 {
            self.positive = false;
            self.negative = false;
        }
        if armed & 0x10 != 0 {
            self.positive = false;
        }
        if armed & 0x20 != 0 {
            self.negative = false;
        }
        self.enabled = true;
        let continuous = function & 0x02 != 0;
        let pos = function & 0x10 != 0 && rising && (continuous || !self.positive);
        let neg = function & 0x20 != 0 && falling && (continuous || !self.negative);
        self.positive |= pos;
        self.negative |= neg;
        (pos, neg)
    }

    fn status(&self) -> u16 {
        u16::from(self.enabled) | u16::from(self.positive) << 1 | u16::from(self.negative) << 2
    }
}

/// A CSP interpolation segment.
#[derive(Clone, Copy, Debug)]
struct CspSegment {
    from: f64,
    to: i64,
    started: f64,
}

impl CspSegment {
    /// The set-point at time `t` (end of the tick being computed).
    fn at(self, t: f64, period: f64) -> f64 {
        let to = self.to as f64;
        if period <= 0.0 {
            return to;
        }
        let f = ((t - self.started) / period).clamp(0.0, 1.0);
        self.from + (to - self.from) * f
    }
}

/// Controlwords kept between two steps; older ones are dropped (a master writing more than this
/// within one servo period is flooding, not commanding).
pub const MAX_WRITTEN_CONTROLWORDS: usize = 8;

/// A CiA 402 drive bound to one engine axis.
#[derive(Clone, Debug)]
pub struct Cia402Drive {
    config: DriveConfig,
    od: ObjectDictionary,
    state: State,
    mode: OperationMode,
    /// Steps taken; stamps commands so that their effect is looked for only afterwards.
    steps: u64,
    previous_cw: u16,
    /// Controlword bits that rose in a master's writes since the last step. A master may write
    /// several controlwords between two steps (SDOs and RPDOs are served as they arrive): an
    /// edge among them is an edge, as on a drive whose RPDO handler runs on reception, even if
    /// the step sees only the last value.
    written_rises: u16,
    /// The controlwords a master wrote since the last step, oldest first (at most
    /// [`MAX_WRITTEN_CONTROLWORDS`]): `0x06`, `0x07`, `0x0F` written back to back walk the state
    /// machine through each command, not only the last.
    written_cws: Vec<u16>,
    transitions: Vec<u8>,
    // ---- power ----
    /// Step at which the drive asked the axis for power; `None` while it wants none.
    powered_since: Option<u64>,
    /// The axis has been seen enabled since the drive powered it.
    power_confirmed: bool,
    pending_stop: Option<PendingStop>,
    reset_requested_at: Option<u64>,
    /// A drive-internal fault to react to in the next step.
    pending_fault: Option<u16>,
    // ---- modes ----
    set_point_ack: bool,
    /// The target relative set-points add to (CiA 402 0x60F2 default: the preceding target).
    pp_reference: i64,
    /// Final target of the accepted set-points; `None` until the first.
    pp_target: Option<i64>,
    /// PV: (velocity, acceleration, deceleration, profile type) last sent to the axis.
    last_velocity_command: Option<(i64, i64, i64, i64)>,
    /// A `Halt` was sent and not yet resumed.
    engine_halted: bool,
    streaming: bool,
    stream_accepted: bool,
    torque_demand: i64,
    /// CSP: the segment being interpolated, from the set-point in force when a new target came
    /// to that target, over the interpolation period (0x60C2).
    csp_segment: Option<CspSegment>,
    /// Engine time of the current step, and the time since the one before, seconds.
    now: f64,
    dt: f64,
    homing: HomingProgress,
    homing_offset: i64,
    /// 0x6063/0x60FC = 0x6064/0x6062 − shift; the home offset of the last homing.
    home_shift: i64,
    // ---- monitoring ----
    /// A target or velocity was limited by 0x607D, 0x607F, 0x6080 or 0x6072.
    clamped: bool,
    /// The axis refused motion with `LimitActive`.
    limit_refused: bool,
    /// The axis refused the drive's last command.
    warning: bool,
    last_refusal: Option<EngineError>,
    target_dwell: Dwell,
    following_dwell: Dwell,
    zero_speed_dwell: Dwell,
    probes: [Probe; 2],
    emergencies: Vec<Emergency>,
}

impl Cia402Drive {
    /// A drive in Not ready to switch on (transition 0); its first `step` performs transition 1.
    pub fn new(config: DriveConfig) -> Result<Cia402Drive, DriveConfigError> {
        config.validate()?;
        let od = ObjectDictionary::from_defs(object_table(&config))?;
        Ok(Cia402Drive {
            config,
            od,
            state: State::NotReadyToSwitchOn,
            mode: OperationMode::NoMode,
            steps: 0,
            previous_cw: 0,
            written_rises: 0,
            written_cws: Vec::new(),
            transitions: vec![0],
            powered_since: None,
            power_confirmed: false,
            pending_stop: None,
            reset_requested_at: None,
            pending_fault: None,
            set_point_ack: false,
            pp_reference: 0,
            pp_target: None,
            last_velocity_command: None,
            engine_halted: false,
            streaming: false,
            stream_accepted: false,
            torque_demand: 0,
            csp_segment: None,
            now: 0.0,
            dt: 0.0,
            homing: HomingProgress::NotStarted,
            homing_offset: 0,
            home_shift: 0,
            clamped: false,
            limit_refused: false,
            warning: false,
            last_refusal: None,
            target_dwell: Dwell::default(),
            following_dwell: Dwell::default(),
            zero_speed_dwell: Dwell::default(),
            probes: [Probe::default(); 2],
            emergencies: Vec::new(),
        })
    }

    pub fn config(&self) -> &DriveConfig {
        &self.config
    }

    pub fn axis(&self) -> AxisIndex {
        self.config.axis
    }

    pub fn state(&self) -> State {
        self.state
    }

    /// The mode in effect (0x6061).
    pub fn mode(&self) -> OperationMode {
        self.mode
    }

    pub fn statusword(&self) -> u16 {
        self.int(obj::STATUSWORD, 0) as u16
    }

    /// 0x603F.
    pub fn error_code(&self) -> u16 {
        self.int(obj::ERROR_CODE, 0) as u16
    }

    /// The CiA 402 transitions (0–16) the last `step` made, in order.
    pub fn last_transitions(&self) -> &[u8] {
        &self.transitions
    }

    /// The last engine error a command of this drive got, for diagnostics.
    pub fn last_refusal(&self) -> Option<&EngineError> {
        self.last_refusal.as_ref()
    }

    /// Emergencies raised since the last call.
    pub fn take_emergencies(&mut self) -> Vec<Emergency> {
        std::mem::take(&mut self.emergencies)
    }

    pub fn od(&self) -> &ObjectDictionary {
        &self.od
    }

    /// Device access to the dictionary, for a fieldbus stack that keeps its own communication
    /// state in it (CANopen 0x1000–0x1FFF). Master writes go through [`write`](Self::write).
    pub fn od_mut(&mut self) -> &mut ObjectDictionary {
        &mut self.od
    }

    // ---- bus access ----

    pub fn read(&self, index: u16, subindex: u8) -> Result<Value, OdError> {
        self.od.read(index, subindex)
    }

    pub fn read_bytes(&self, index: u16, subindex: u8) -> Result<Vec<u8>, OdError> {
        self.od.read_bytes(index, subindex)
    }

    /// A master's write: the dictionary's checks, then the drive's own rules.
    pub fn write(&mut self, index: u16, subindex: u8, value: Value) -> Result<(), OdError> {
        self.od.validate(index, subindex, &value)?;
        self.check_device_rules(index, subindex, &value)?;
        if (index, subindex) == (obj::CONTROLWORD, 0) {
            let before = self.int(obj::CONTROLWORD, 0) as u16;
            let after = value.as_i64().unwrap_or(0) as u16;
            self.written_rises |= after & !before;
            if self.written_cws.len() == MAX_WRITTEN_CONTROLWORDS {
                self.written_cws.remove(0);
            }
            self.written_cws.push(after);
        }
        self.od.write(index, subindex, value)
    }

    pub fn write_bytes(&mut self, index: u16, subindex: u8, bytes: &[u8]) -> Result<(), OdError> {
        let value = self.od.decode(index, subindex, bytes)?;
        self.write(index, subindex, value)
    }

    /// Rules a data type and range cannot express.
    fn check_device_rules(&self, index: u16, subindex: u8, value: &Value) -> Result<(), OdError> {
        let v = value.as_i64().unwrap_or(0);
        let invalid = |detail: String| {
            Err(OdError::InvalidValue {
                index,
                subindex,
                detail,
            })
        };
        let homing_parameter = matches!(
            index,
            obj::HOMING_METHOD | obj::HOMING_SPEEDS | obj::HOMING_ACCELERATION | obj::HOME_OFFSET
        );
        if homing_parameter && matches!(self.homing, HomingProgress::InProgress { .. }) {
            return Err(OdError::DeviceState {
                index,
                subindex,
                detail: "homing is in progress".to_string(),
            });
        }
        match index {
            obj::MODES_OF_OPERATION
                if i8::try_from(v)
                    .ok()
                    .and_then(OperationMode::from_code)
                    .is_none() =>
            {
                invalid(format!(
                    "mode {v} is not supported (0x6502 = {:#06x})",
                    supported_drive_modes()
                ))
            }
            // The engine's homing runs CiA 402 methods 1–35 and 37 (ARCHITECTURE §3.7).
            obj::HOMING_METHOD if !((1..=35).contains(&v) || v == 37) => {
                invalid(format!("homing method {v} is not supported (1–35, 37)"))
            }
            // 0 linear ramp (trapezoid) and 3 jerk-limited ramp are what the profiles offer.
            obj::MOTION_PROFILE_TYPE if !matches!(v, 0 | 3) => {
                invalid(format!("motion profile type {v} is not supported (0, 3)"))
            }
            obj::SOFTWARE_POSITION_LIMIT if matches!(subindex, 1 | 2) => {
                self.check_position_limits(subindex, value)
            }
            _ => Ok(()),
        }
    }

    /// 0x607D: a write must not make the max position limit less than the min (CiA 301 abort
    /// 0x06090036, "maximum value is less than minimum value"). Each sub-index is checked
    /// against the other's present value, so moving the window past itself takes the writes
    /// in the right order (max first when moving up). Equal limits are accepted: they switch
    /// the limits off, as min > max did before this check (`clamp_position`).
    fn check_position_limits(&self, subindex: u8, value: &Value) -> Result<(), OdError> {
        let other = |sub| {
            self.od
                .get(obj::SOFTWARE_POSITION_LIMIT, sub)
                .cloned()
                .unwrap_or(Value::I32(0))
        };
        let (min, max) = if subindex == 1 {
            (value.clone(), other(2))
        } else {
            (other(1), value.clone())
        };
        if max.compare(&min) == Some(std::cmp::Ordering::Less) {
            return Err(OdError::MaxBelowMin {
                index: obj::SOFTWARE_POSITION_LIMIT,
                subindex,
                min,
                max,
            });
        }
        Ok(())
    }

    // ---- the servo tick ----

    /// One servo tick: read the controlword and targets, run the state machine and the mode,
    /// push the axis commands to `out`, publish statusword and actual values. `axis` is the bound
    /// axis's status after the previous engine step; `now` is engine time in seconds.
    pub fn step(&mut self, axis: &AxisStatus, now: f64, out: &mut Vec<Command>) {
        self.steps += 1;
        self.dt = (now - self.now).max(0.0);
        self.now = now;
        self.transitions.clear();
        let cw = self.int(obj::CONTROLWORD, 0) as u16;
        let rises = (cw & !self.previous_cw) | std::mem::take(&mut self.written_rises);
        let falls = self.previous_cw & !cw;
        if axis.flags.contains(AxisFlags::ENABLED) && self.powered_since.is_some() {
            self.power_confirmed = true;
        }
        self.update_inputs(axis);
        // Commands written before the last one since the previous step, each in turn (a drive
        // that runs its state machine on reception would have).
        let mut written = std::mem::take(&mut self.written_cws);
        if written.last() == Some(&cw) {
            written.pop();
        }
        let mut previous = self.previous_cw;
        for &earlier in &written {
            self.run_state_machine(earlier, earlier & !previous, axis, out);
            previous = earlier;
        }
        written.clear();
        self.written_cws = written; // keeps its allocation
        self.run_state_machine(cw, rises, axis, out);
        self.switch_mode(axis, out);
        match self.state {
            State::OperationEnabled => self.run_mode(cw, rises, falls, axis, out),
            // HIMC §20.1 (digest 004 §4.3): method 37 does not need Operation enabled.
            State::SwitchOnDisabled | State::ReadyToSwitchOn | State::SwitchedOn
                if self.mode == OperationMode::Homing
                    && rises & cw::HOMING_START != 0
                    && !matches!(self.homing, HomingProgress::InProgress { .. }) =>
            {
                self.start_homing(false, out);
            }
            _ => {}
        }
        self.track_homing(axis, out);
        self.publish(cw, axis, now);
        self.previous_cw = cw;
    }

    /// Feed back the engine's answer to a command the last `step` emitted. Successes need no
    /// feedback (the drive learns outcomes from the axis status) but clear an earlier refusal's
    /// bits. Refusals surface as: `Enable` → fault 0xFF01 in the next step; `Reset` → the drive
    /// stays in Fault; `Home`/`SetPosition` → homing error (bit 13); `LimitActive` → internal
    /// limit active (bit 11); a refused setpoint → bit 12 drops; anything else → warning
    /// (bit 7). [`last_refusal`](Self::last_refusal) keeps the error.
    pub fn on_reply(&mut self, command: &Command, result: &Result<Reply, EngineError>) {
        let error = match result {
            Ok(_) => {
                if let Command::Axis(AxisCommand::Setpoint(StreamSetpoint {
                    setpoint: Some(_),
                    ..
                })) = command
                {
                    self.stream_accepted = true;
                }
                if matches!(
                    command,
                    Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute { .. }))
                        | Command::Axis(AxisCommand::MoveRelative(MoveRelative { .. }))
                        | Command::Axis(AxisCommand::MoveVelocity(MoveVelocity { .. }))
                        | Command::Axis(AxisCommand::Home(Home { .. }))
                        | Command::Axis(AxisCommand::Setpoint(StreamSetpoint {
                            setpoint: Some(_),
                            ..
                        }))
                ) {
                    self.warning = false;
                    self.limit_refused = false;
                }
                return;
            }
            Err(error) => error,
        };
        self.last_refusal = Some(error.clone());
        let limit = matches!(error, EngineError::LimitActive { .. });
        match command {
            Command::Axis(AxisCommand::Enable(Enable { .. })) => {
                if !matches!(self.state, State::FaultReactionActive | State::Fault) {
                    self.pending_fault = Some(error_code::ENABLE_REFUSED);
                }
            }
            // Transition 15 needs the axis's errors cleared.
            Command::Axis(AxisCommand::Reset(Reset { .. })) => self.reset_requested_at = None,
            Command::Axis(AxisCommand::Home(Home { .. }))
            | Command::Axis(AxisCommand::SetPosition(SetPosition { .. })) => {
                if matches!(self.homing, HomingProgress::InProgress { .. }) {
                    self.homing = HomingProgress::Error;
                }
            }
            Command::Axis(AxisCommand::Setpoint(StreamSetpoint {
                setpoint: Some(_), ..
            })) => {
                self.stream_accepted = false;
                self.limit_refused |= limit;
                self.warning |= !limit;
            }
            _ => {
                self.limit_refused |= limit;
                self.warning |= !limit;
            }
        }
    }

    /// The master is gone (heartbeat or node guarding lost): act per 0x6007 abort connection
    /// option code — 0 nothing, 1 fault 0x8130, 2 disable voltage, 3 quick stop.
    pub fn connection_lost(&mut self) {
        match self.int(obj::ABORT_CONNECTION_OPTION, 0) {
            1 if !matches!(self.state, State::FaultReactionActive | State::Fault) => {
                self.pending_fault = Some(error_code::CONNECTION_LOST);
            }
            2 => self.put(obj::CONTROLWORD, 0, Value::U16(cw::DISABLE_VOLTAGE)),
            3 => self.put(obj::CONTROLWORD, 0, Value::U16(cw::QUICK_STOP_COMMAND)),
            _ => {}
        }
    }

    // ---- parameters and units ----
    // (power state machine: power.rs; modes: modes.rs, pp.rs, pv.rs, hm.rs, cyclic.rs;
    // statusword and inputs: statusword.rs)

    fn int(&self, index: u16, subindex: u8) -> i64 {
        self.od
            .get(index, subindex)
            .and_then(Value::as_i64)
            .unwrap_or(0)
    }

    /// Store a value the drive computes. The table is the drive's own and every object it
    /// writes has the right type (checked by the tests), so failure is a programming error.
    fn put(&mut self, index: u16, subindex: u8, value: Value) {
        let result = self.od.set(index, subindex, value);
        debug_assert!(result.is_ok(), "{result:?}");
    }

    fn to_units(&self, increments: i64) -> f64 {
        increments as f64 / self.config.increments_per_unit
    }

    fn to_units_f64(&self, increments: f64) -> f64 {
        increments / self.config.increments_per_unit
    }

    /// User units → increments, rounded; saturating (and NaN → 0) by `as`.
    fn to_increments(&self, units: f64) -> i64 {
        (units * self.config.increments_per_unit).round() as i64
    }

    fn max_velocity(&self) -> i64 {
        self.int(obj::MAX_PROFILE_VELOCITY, 0)
            .min(self.int(obj::MAX_MOTOR_SPEED, 0))
    }

    /// 0x6081 limited by 0x607F and 0x6080; whether it was limited.
    fn profile_velocity_limit(&self) -> (i64, bool) {
        let requested = self.int(obj::PROFILE_VELOCITY, 0);
        let velocity = requested.min(self.max_velocity());
        (velocity, velocity != requested)
    }

    /// 0x607D: targets are limited to [min, max] when min < max.
    fn clamp_position(&self, target: i64) -> (i64, bool) {
        let min = self.int(obj::SOFTWARE_POSITION_LIMIT, 1);
        let max = self.int(obj::SOFTWARE_POSITION_LIMIT, 2);
        if min >= max {
            return (target, false);
        }
        let limited = target.clamp(min, max);
        (limited, limited != target)
    }

    /// 0x6086: 0 linear ramp → trapezoid (jerk 0); 3 jerk-limited → the axis's jerk.
    fn jerk(&self) -> Option<f64> {
        (self.int(obj::MOTION_PROFILE_TYPE, 0) == 0).then_some(0.0)
    }

    /// The "slow down ramp": the profile deceleration, the homing acceleration in HM.
    fn slow_down_deceleration(&self) -> i64 {
        if self.mode == OperationMode::Homing {
            self.int(obj::HOMING_ACCELERATION, 0)
        } else {
            self.int(obj::PROFILE_DECELERATION, 0)
        }
    }

    /// 0x605D: 1 slow-down ramp; 2 quick stop ramp; 3/4 (current/voltage limit) also use the
    /// quick stop ramp, the steepest one a halt can keep the plan with.
    fn halt_deceleration(&self) -> i64 {
        match self.int(obj::HALT_OPTION, 0) {
            1 => self.slow_down_deceleration(),
            _ => self.int(obj::QUICK_STOP_DECELERATION, 0),
        }
    }

    /// A Stop with a deceleration in increments/s².
    fn stop(&self, mode: StopMode, deceleration: Option<i64>) -> Command {
        Command::from(Stop {
            axis: self.config.axis,
            mode,
            deceleration: deceleration.map(|d| self.to_units(d)),
        })
    }
}

/// The axis no longer moves under command (or is unpowered and can only coast).
fn at_rest(axis: &AxisStatus) -> bool {
    !axis.flags.contains(AxisFlags::MOVING) || !axis.flags.contains(AxisFlags::ENABLED)
}

fn saturate(value: i64) -> i32 {
    value.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// 0x1001 error register for an error code (CiA 301 §7.5.2.2): bit 0 generic, 1 current,
/// 2 voltage, 3 temperature, 4 communication, 5 device profile specific, 7 manufacturer.
fn error_register(code: u16) -> u8 {
    let class = match code >> 12 {
        0x2 => 1 << 1,
        0x3 => 1 << 2,
        0x4 => 1 << 3,
        _ if code >> 8 == 0x81 => 1 << 4,
        _ if code >> 8 == 0xFF => 1 << 7,
        _ => 1 << 5,
    };
    if code == 0 {
        0
    } else {
        1 | class
    }
}
