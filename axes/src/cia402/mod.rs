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

mod objects;
mod state;

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
enum Homing {
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
    homing: Homing,
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
            homing: Homing::NotStarted,
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
        if homing_parameter && matches!(self.homing, Homing::InProgress { .. }) {
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
                    && !matches!(self.homing, Homing::InProgress { .. }) =>
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
                if matches!(self.homing, Homing::InProgress { .. }) {
                    self.homing = Homing::Error;
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

    // ---- state machine (CiA 402 §6.2.1, transitions 0–16) ----

    fn run_state_machine(
        &mut self,
        cw: u16,
        rises: u16,
        axis: &AxisStatus,
        out: &mut Vec<Command>,
    ) {
        if let Some(stop) = self.pending_stop {
            if stop.issued_at < self.steps && at_rest(axis) {
                self.pending_stop = None;
                self.finish_stop(stop.then, axis, out);
            }
        }
        match self.state {
            State::NotReadyToSwitchOn => {
                // The drive owns its axis's power: start unpowered.
                if axis.flags.contains(AxisFlags::ENABLED) {
                    self.power_off(out);
                }
                self.go(State::SwitchOnDisabled, 1);
                return;
            }
            // Waits for its stop ramp (above).
            State::FaultReactionActive => return,
            State::Fault => {
                self.fault_reset(rises, axis, out);
                return;
            }
            _ => {}
        }
        if let Some(code) = self.detect_fault(axis) {
            self.fault_reaction(code, axis, out);
            return;
        }
        use DeviceCommand as C;
        use State as S;
        match (self.state, DeviceCommand::decode(cw)) {
            (S::SwitchOnDisabled, C::Shutdown) => self.go(S::ReadyToSwitchOn, 2),
            (S::ReadyToSwitchOn, C::SwitchOn) => self.go(S::SwitchedOn, 3),
            // "Switch on + enable operation": 3, then 4 at once.
            (S::ReadyToSwitchOn, C::EnableOperation) => {
                self.go(S::SwitchedOn, 3);
                self.enable_operation(axis, out, 4);
            }
            (S::ReadyToSwitchOn, C::DisableVoltage | C::QuickStop) => self.disable_voltage(out, 7),
            (S::SwitchedOn, C::EnableOperation) => self.enable_operation(axis, out, 4),
            (S::SwitchedOn, C::Shutdown) => self.go(S::ReadyToSwitchOn, 6),
            (S::SwitchedOn, C::DisableVoltage | C::QuickStop) => self.disable_voltage(out, 10),
            (S::OperationEnabled, C::SwitchOn) => {
                self.leave_operation(S::SwitchedOn, 5, obj::DISABLE_OPERATION_OPTION, out)
            }
            (S::OperationEnabled, C::Shutdown) => {
                self.leave_operation(S::ReadyToSwitchOn, 8, obj::SHUTDOWN_OPTION, out)
            }
            (S::OperationEnabled, C::DisableVoltage) => {
                self.wind_down(out);
                self.power_off(out);
                self.go(S::SwitchOnDisabled, 9);
            }
            (S::OperationEnabled, C::QuickStop) => self.quick_stop(out),
            (S::QuickStopActive, C::DisableVoltage) => {
                self.pending_stop = None;
                self.power_off(out);
                self.go(S::SwitchOnDisabled, 12);
            }
            (S::QuickStopActive, C::EnableOperation)
                if self.int(obj::QUICK_STOP_OPTION, 0) >= 5 =>
            {
                self.pending_stop = None;
                self.enable_operation(axis, out, 16);
            }
            // Every other (state, command) pair is no transition.
            _ => {}
        }
    }

    fn go(&mut self, state: State, transition: u8) {
        self.state = state;
        self.transitions.push(transition);
    }

    fn finish_stop(&mut self, then: AfterStop, axis: &AxisStatus, out: &mut Vec<Command>) {
        match then {
            AfterStop::Disable => self.power_off(out),
            AfterStop::QuickStopDone => {
                if self.int(obj::QUICK_STOP_OPTION, 0) <= 4 {
                    self.power_off(out);
                    self.go(State::SwitchOnDisabled, 12);
                }
            }
            AfterStop::FaultDone => {
                if axis.flags.contains(AxisFlags::ENABLED) {
                    self.power_off(out);
                }
                self.powered_since = None;
                self.go(State::Fault, 14);
            }
        }
    }

    /// Transitions 7 and 10. A ramp still running from transition 5 or 8 ends in coasting.
    fn disable_voltage(&mut self, out: &mut Vec<Command>, transition: u8) {
        if self.pending_stop.take().is_some() || self.powered_since.is_some() {
            self.power_off(out);
        }
        self.go(State::SwitchOnDisabled, transition);
    }

    fn enable_operation(&mut self, axis: &AxisStatus, out: &mut Vec<Command>, transition: u8) {
        self.pending_stop = None;
        if self.powered_since.is_none() {
            self.power_on(out);
        }
        self.go(State::OperationEnabled, transition);
        self.enter_mode(axis);
        self.limit_refused = false;
    }

    /// Transitions 5 and 8: 0x605C / 0x605B option 0 removes power at once, 1 ramps down with
    /// the profile deceleration first.
    fn leave_operation(
        &mut self,
        state: State,
        transition: u8,
        option: u16,
        out: &mut Vec<Command>,
    ) {
        self.wind_down(out);
        if self.int(option, 0) == 1 {
            out.push(self.stop(StopMode::Smooth, Some(self.slow_down_deceleration())));
            self.pending_stop = Some(PendingStop {
                issued_at: self.steps,
                then: AfterStop::Disable,
            });
        } else {
            self.power_off(out);
        }
        self.go(state, transition);
    }

    /// Transition 11 with 0x605A: 0 disable drive (and 12 at once); 1/5 slow-down ramp; 2/6
    /// quick stop ramp (0x6085); 3/4/7/8 current/voltage limit, i.e. as fast as the axis can.
    fn quick_stop(&mut self, out: &mut Vec<Command>) {
        self.wind_down(out);
        let option = self.int(obj::QUICK_STOP_OPTION, 0);
        self.go(State::QuickStopActive, 11);
        if option == 0 {
            self.power_off(out);
            self.go(State::SwitchOnDisabled, 12);
            return;
        }
        let stop = match option {
            1 | 5 => self.stop(StopMode::Smooth, Some(self.slow_down_deceleration())),
            2 | 6 => self.stop(
                StopMode::Smooth,
                Some(self.int(obj::QUICK_STOP_DECELERATION, 0)),
            ),
            _ => self.stop(StopMode::Immediate, None),
        };
        out.push(stop);
        self.pending_stop = Some(PendingStop {
            issued_at: self.steps,
            then: AfterStop::QuickStopDone,
        });
    }

    fn detect_fault(&mut self, axis: &AxisStatus) -> Option<u16> {
        if let Some(code) = self.pending_fault.take() {
            return Some(code);
        }
        if let Some((_, code)) = AXIS_FAULTS.iter().find(|(f, _)| axis.flags.contains(*f)) {
            return Some(*code);
        }
        let lost = self.state.is_operational()
            && self.power_confirmed
            && !axis.flags.contains(AxisFlags::ENABLED);
        lost.then_some(error_code::POWER_LOST)
    }

    /// Transition 13 with 0x605E: 0 disable drive; 1 slow-down ramp; 2 quick stop ramp; 3/4 as
    /// fast as possible. Fault (14) follows when the axis is at rest.
    fn fault_reaction(&mut self, code: u16, axis: &AxisStatus, out: &mut Vec<Command>) {
        self.wind_down(out);
        self.set_error(code);
        self.go(State::FaultReactionActive, 13);
        if axis.flags.contains(AxisFlags::ENABLED) {
            let stop = match self.int(obj::FAULT_REACTION_OPTION, 0) {
                0 => None,
                1 => Some(self.stop(StopMode::Smooth, Some(self.slow_down_deceleration()))),
                2 => Some(self.stop(
                    StopMode::Smooth,
                    Some(self.int(obj::QUICK_STOP_DECELERATION, 0)),
                )),
                _ => Some(self.stop(StopMode::Immediate, None)),
            };
            match stop {
                Some(stop) => out.push(stop),
                None => self.power_off(out),
            }
        }
        self.pending_stop = Some(PendingStop {
            issued_at: self.steps,
            then: AfterStop::FaultDone,
        });
    }

    /// Transition 15: the 0 → 1 edge of bit 7 resets the axis; the drive leaves Fault once the
    /// axis shows no fault any more.
    fn fault_reset(&mut self, rises: u16, axis: &AxisStatus, out: &mut Vec<Command>) {
        if rises & cw::FAULT_RESET != 0 {
            out.push(Command::from(Reset {
                axis: self.config.axis,
            }));
            self.reset_requested_at = Some(self.steps);
            return;
        }
        let Some(at) = self.reset_requested_at else {
            return;
        };
        if at < self.steps {
            self.reset_requested_at = None;
            if !axis.flags.intersects(axis_fault_flags()) {
                self.clear_error();
                self.warning = false;
                self.go(State::SwitchOnDisabled, 15);
            }
        }
    }

    fn set_error(&mut self, code: u16) {
        let register = error_register(code);
        self.pending_fault = None;
        self.put(obj::ERROR_CODE, 0, Value::U16(code));
        self.put(obj::ERROR_REGISTER, 0, Value::U8(register));
        self.emergencies.push(Emergency { code, register });
    }

    fn clear_error(&mut self) {
        self.put(obj::ERROR_CODE, 0, Value::U16(error_code::NO_ERROR));
        self.put(obj::ERROR_REGISTER, 0, Value::U8(0));
        self.emergencies.push(Emergency {
            code: error_code::NO_ERROR,
            register: 0,
        });
    }

    fn power_on(&mut self, out: &mut Vec<Command>) {
        out.push(Command::from(Enable {
            axis: self.config.axis,
        }));
        self.powered_since = Some(self.steps);
        self.power_confirmed = false;
    }

    fn power_off(&mut self, out: &mut Vec<Command>) {
        out.push(Command::from(Disable {
            axis: self.config.axis,
        }));
        self.powered_since = None;
        self.power_confirmed = false;
    }

    // ---- modes ----

    /// Follow 0x6060. Leaving a mode in Operation enabled ends what it started: a setpoint
    /// stream, a homing, a profile move (stopped with the slow-down ramp).
    fn switch_mode(&mut self, axis: &AxisStatus, out: &mut Vec<Command>) {
        let code = self.int(obj::MODES_OF_OPERATION, 0);
        let requested = i8::try_from(code)
            .ok()
            .and_then(OperationMode::from_code)
            .unwrap_or(self.mode);
        if requested == self.mode {
            return;
        }
        let old = self.mode;
        // Between cyclic modes the next setpoint simply takes over.
        let bumpless = old.is_cyclic() && requested.is_cyclic();
        if self.state == State::OperationEnabled && !bumpless && old != OperationMode::NoMode {
            let busy = axis.flags.contains(AxisFlags::MOVING)
                || axis.fifo_len > 0
                || matches!(self.homing, Homing::InProgress { .. });
            let deceleration = self.slow_down_deceleration();
            self.wind_down(out);
            if busy {
                out.push(self.stop(StopMode::Smooth, Some(deceleration)));
            }
        }
        self.mode = requested;
        self.enter_mode(axis);
    }

    fn enter_mode(&mut self, axis: &AxisStatus) {
        self.set_point_ack = false;
        self.csp_segment = None;
        self.pp_reference = self.to_increments(axis.cmd_pos);
        self.pp_target = None;
        self.last_velocity_command = None;
        self.clamped = false;
        self.target_dwell.reset();
    }

    /// End the mode's activity when leaving Operation enabled or the mode.
    fn wind_down(&mut self, out: &mut Vec<Command>) {
        if self.streaming {
            out.push(Command::from(StreamSetpoint {
                axis: self.config.axis,
                setpoint: None,
            }));
            self.streaming = false;
        }
        if matches!(self.homing, Homing::InProgress { direct: false, .. }) {
            self.homing = Homing::Interrupted;
        }
        self.engine_halted = false;
        self.set_point_ack = false;
        self.last_velocity_command = None;
        self.torque_demand = 0;
        self.clamped = false;
    }

    fn run_mode(
        &mut self,
        cw: u16,
        rises: u16,
        falls: u16,
        axis: &AxisStatus,
        out: &mut Vec<Command>,
    ) {
        let halt = cw & cw::HALT != 0;
        match self.mode {
            OperationMode::NoMode => {}
            OperationMode::ProfilePosition => {
                self.halt_profile(halt, axis, out);
                self.profile_position(cw, rises, halt, axis, out);
            }
            OperationMode::ProfileVelocity => {
                self.halt_profile(halt, axis, out);
                if !halt {
                    self.profile_velocity(out);
                }
            }
            OperationMode::Homing => self.homing_mode(rises, falls, halt, out),
            OperationMode::CyclicPosition
            | OperationMode::CyclicVelocity
            | OperationMode::CyclicTorque => self.cyclic(halt, rises, out),
        }
    }

    /// Bit 8 in PP and PV: pause with 0x605D's ramp, keeping the plan (engine Halt/Resume).
    /// An idle axis gets no Halt: nothing starts while bit 8 is set anyway.
    fn halt_profile(&mut self, halt: bool, axis: &AxisStatus, out: &mut Vec<Command>) {
        let busy = axis.flags.contains(AxisFlags::MOVING) || axis.fifo_len > 0;
        if halt && !self.engine_halted && busy {
            out.push(Command::from(Halt {
                axis: self.config.axis,
                deceleration: Some(self.to_units(self.halt_deceleration())),
            }));
            self.engine_halted = true;
        } else if !halt && self.engine_halted {
            out.push(Command::from(Resume {
                axis: self.config.axis,
            }));
            self.engine_halted = false;
        }
    }

    /// PP set-point handshake (CiA 402 §10 profile position): a rising edge of bit 4 hands over
    /// 0x607A; bit 12 acknowledges and stays set while the set-point buffer (the running move
    /// plus one) is full; bit 5 aborts the running move, else the set-point is queued. Bit 9
    /// (change on set-point) is accepted but queued set-points stop in between: the engine has
    /// no blending buffer mode yet.
    fn profile_position(
        &mut self,
        cw: u16,
        rises: u16,
        halt: bool,
        axis: &AxisStatus,
        out: &mut Vec<Command>,
    ) {
        let immediate = cw & cw::CHANGE_SET_IMMEDIATELY != 0;
        let room = immediate || axis.fifo_len < 2;
        if rises & cw::NEW_SET_POINT != 0 && room && !halt {
            let raw = self.int(obj::TARGET_POSITION, 0);
            let relative = cw & cw::RELATIVE != 0;
            let wanted = if relative {
                self.pp_reference.saturating_add(raw)
            } else {
                raw
            };
            let (target, clamped_position) = self.clamp_position(wanted);
            let (velocity, clamped_velocity) = self.profile_velocity_limit();
            let (velocity, acceleration, deceleration, jerk) = (
                Some(self.to_units(velocity)),
                Some(self.to_units(self.int(obj::PROFILE_ACCELERATION, 0))),
                Some(self.to_units(self.int(obj::PROFILE_DECELERATION, 0))),
                self.jerk(),
            );
            let axis_index = self.config.axis;
            // A relative set-point is relative to the preceding target (0x60F2 default). The
            // engine's buffered MoveRelative starts from the previous command's end, which is
            // that target; an aborting one would start from the current position, so a changed-
            // immediately relative set-point goes out as the absolute target it means.
            let command = if relative && !immediate {
                Command::from(MoveRelative {
                    axis: axis_index,
                    distance: self.to_units(target - self.pp_reference),
                    velocity,
                    acceleration,
                    deceleration,
                    jerk,
                    buffer_mode: BufferMode::Buffered,
                })
            } else {
                Command::from(MoveAbsolute {
                    axis: axis_index,
                    position: self.to_units(target),
                    velocity,
                    acceleration,
                    deceleration,
                    jerk,
                    buffer_mode: if immediate {
                        BufferMode::Aborting
                    } else {
                        BufferMode::Buffered
                    },
                })
            };
            out.push(command);
            self.pp_reference = target;
            self.pp_target = Some(target);
            self.set_point_ack = true;
            self.clamped = clamped_position || clamped_velocity;
            self.target_dwell.reset();
        } else if cw & cw::NEW_SET_POINT == 0 && room {
            self.set_point_ack = false;
        }
    }

    /// PV: command 0x60FF (limited by 0x607F/0x6080) with 0x6083/0x6084 whenever any changes.
    fn profile_velocity(&mut self, out: &mut Vec<Command>) {
        let limit = self.max_velocity();
        let raw = self.int(obj::TARGET_VELOCITY, 0);
        let velocity = raw.clamp(-limit, limit);
        self.clamped = velocity != raw;
        let key = (
            velocity,
            self.int(obj::PROFILE_ACCELERATION, 0),
            self.int(obj::PROFILE_DECELERATION, 0),
            self.int(obj::MOTION_PROFILE_TYPE, 0),
        );
        if self.last_velocity_command != Some(key) {
            out.push(Command::from(MoveVelocity {
                axis: self.config.axis,
                velocity: self.to_units(velocity),
                acceleration: Some(self.to_units(key.1)),
                deceleration: Some(self.to_units(key.2)),
                jerk: self.jerk(),
                buffer_mode: BufferMode::Aborting,
            }));
            self.last_velocity_command = Some(key);
        }
    }

    /// HM: the rising edge of bit 4 starts homing with 0x6098/0x6099/0x609A/0x607C; its falling
    /// edge, or halt, interrupts it (stopping with the homing acceleration).
    fn homing_mode(&mut self, rises: u16, falls: u16, halt: bool, out: &mut Vec<Command>) {
        let running = matches!(self.homing, Homing::InProgress { .. });
        if running && (falls & cw::HOMING_START != 0 || (halt && rises & cw::HALT != 0)) {
            out.push(self.stop(
                StopMode::Smooth,
                Some(self.int(obj::HOMING_ACCELERATION, 0)),
            ));
            self.homing = Homing::Interrupted;
        } else if !running && rises & cw::HOMING_START != 0 && !halt {
            self.start_homing(true, out);
        }
    }

    /// Start homing. Outside Operation enabled only method 37 (and its older number 35) runs,
    /// as a redefinition of the position: no motion, so no power is needed.
    fn start_homing(&mut self, operational: bool, out: &mut Vec<Command>) {
        let method = self.int(obj::HOMING_METHOD, 0);
        self.homing_offset = self.int(obj::HOME_OFFSET, 0);
        let axis = self.config.axis;
        let direct = !operational;
        if direct {
            if !matches!(method, 35 | 37) {
                return;
            }
            out.push(Command::from(SetPosition {
                axis,
                position: self.to_units(self.homing_offset),
                frame: PositionFrame::Both,
            }));
        } else {
            out.push(Command::from(Home {
                axis,
                method: i16::try_from(method).ok(),
                switch_velocity: Some(self.to_units(self.int(obj::HOMING_SPEEDS, 1))),
                zero_velocity: Some(self.to_units(self.int(obj::HOMING_SPEEDS, 2))),
                acceleration: Some(self.to_units(self.int(obj::HOMING_ACCELERATION, 0))),
                offset: Some(self.to_units(self.homing_offset)),
                timeout: None,
                quirks: HomingQuirks::default(),
                buffer_mode: BufferMode::Aborting,
            }));
        }
        self.homing = Homing::InProgress {
            since: self.steps,
            direct,
        };
    }

    /// Learn how a homing ended from the axis: HOMING_FAILED → error; no longer homing and
    /// HOMED → attained; no longer homing otherwise → interrupted.
    fn track_homing(&mut self, axis: &AxisStatus, out: &mut Vec<Command>) {
        let Homing::InProgress { since, direct } = self.homing else {
            return;
        };
        if since >= self.steps {
            return;
        }
        if direct {
            // A refused SetPosition has already turned this into an error (on_reply).
            self.homing_attained();
            return;
        }
        if axis.flags.contains(AxisFlags::HOMING_FAILED) {
            self.homing = Homing::Error;
            // A failed homing is a homing error (bit 13), not a drive fault: clear the axis's
            // latch so that the master can move it again.
            if !axis.flags.intersects(axis_fault_flags()) {
                out.push(Command::from(Reset {
                    axis: self.config.axis,
                }));
            }
            return;
        }
        let busy = axis.state == AxisState::Homing
            || axis
                .current_command
                .is_some_and(|c| c.kind == CommandKind::Home);
        if busy {
            return;
        }
        if axis.flags.contains(AxisFlags::HOMED) {
            self.homing_attained();
        } else {
            self.homing = Homing::Interrupted;
        }
    }

    fn homing_attained(&mut self) {
        self.homing = Homing::Attained;
        // HIMC §20 method 37: 0x6063 = 0x60FC = 0 where 0x6064 = 0x6062 = 0x607C.
        self.home_shift = self.homing_offset;
    }

    /// The interpolation period (0x60C2), seconds; 0 when unset.
    fn interpolation_period(&self) -> f64 {
        let value = self.int(obj::INTERPOLATION_TIME_PERIOD, 1) as f64;
        let index = self.int(obj::INTERPOLATION_TIME_PERIOD, 2) as i32;
        value * 10f64.powi(index)
    }

    /// CSP (CiA 402 §6.3.4): a new target is reached linearly over the interpolation period
    /// from where the set-point stood, so a master whose SYNC is slower than the servo tick
    /// still gives a smooth stream; a period at or below the tick passes targets through.
    fn interpolate(&mut self, target: i64) -> f64 {
        let period = self.interpolation_period();
        let current = match self.csp_segment {
            Some(s) => s.at(self.now, period),
            None => target as f64,
        };
        match self.csp_segment {
            Some(s) if s.to == target => {}
            _ => {
                self.csp_segment = Some(CspSegment {
                    from: current,
                    to: target,
                    started: self.now,
                })
            }
        }
        self.csp_segment
            .map_or(target as f64, |s| s.at(self.now + self.dt, period))
    }

    /// CSP/CSV/CST: one setpoint every tick from 0x607A / 0x60FF / 0x6071; halt ends the stream
    /// and stops with 0x605D's ramp.
    fn cyclic(&mut self, halt: bool, rises: u16, out: &mut Vec<Command>) {
        let axis = self.config.axis;
        if halt {
            if self.streaming {
                out.push(Command::from(StreamSetpoint {
                    axis,
                    setpoint: None,
                }));
                self.streaming = false;
            }
            if rises & cw::HALT != 0 {
                out.push(self.stop(StopMode::Smooth, Some(self.halt_deceleration())));
            }
            self.clamped = false;
            return;
        }
        let setpoint = match self.mode {
            OperationMode::CyclicVelocity => {
                let limit = self.max_velocity();
                let raw = self.int(obj::TARGET_VELOCITY, 0);
                let velocity = raw.clamp(-limit, limit);
                self.clamped = velocity != raw;
                Setpoint::Velocity {
                    velocity: self.to_units(velocity),
                }
            }
            OperationMode::CyclicTorque => {
                let limit = self.int(obj::MAX_TORQUE, 0);
                let raw = self.int(obj::TARGET_TORQUE, 0);
                let torque = raw.clamp(-limit, limit);
                self.clamped = torque != raw;
                self.torque_demand = torque;
                // ‰ of rated torque → fraction of rated torque.
                Setpoint::Torque {
                    torque: torque as f64 / 1000.0,
                }
            }
            _ => {
                let (position, clamped) = self.clamp_position(self.int(obj::TARGET_POSITION, 0));
                self.clamped = clamped;
                let interpolated = self.interpolate(position);
                Setpoint::Position {
                    position: self.to_units_f64(interpolated),
                }
            }
        };
        if !self.streaming {
            self.stream_accepted = true;
        }
        out.push(Command::from(StreamSetpoint {
            axis,
            setpoint: Some(setpoint),
        }));
        self.streaming = true;
    }

    // ---- inputs and outputs ----

    /// 0x60FD from the switches; touch probes latch 0x6064 on edges of their inputs (probe 1
    /// input: the home switch; probe 2 has no input of its own; either may select the index
    /// pulse). Latching has servo-tick resolution.
    fn update_inputs(&mut self, axis: &AxisStatus) {
        let f = axis.flags;
        let inputs = u32::from(f.contains(AxisFlags::HW_LIMIT_NEG))
            | u32::from(f.contains(AxisFlags::HW_LIMIT_POS)) << 1
            | u32::from(f.contains(AxisFlags::HOME_SWITCH)) << 2;
        self.put(obj::DIGITAL_INPUTS, 0, Value::U32(inputs));
        let function = self.int(obj::TOUCH_PROBE_FUNCTION, 0) as u16;
        let position = saturate(self.to_increments(axis.act_pos));
        let mut latched = [(false, false); 2];
        for (n, (probe, latch)) in self.probes.iter_mut().zip(&mut latched).enumerate() {
            let bits = (function >> (8 * n)) as u8;
            let own_input = n == 0 && f.contains(AxisFlags::HOME_SWITCH);
            let level = match (bits >> 2) & 0x03 {
                0 => own_input,
                1 => f.contains(AxisFlags::INDEX),
                _ => false,
            };
            *latch = probe.update(bits, level);
        }
        let [(p1_pos, p1_neg), (p2_pos, p2_neg)] = latched;
        for (hit, index) in [
            (p1_pos, obj::TOUCH_PROBE_1_POSITIVE),
            (p1_neg, obj::TOUCH_PROBE_1_NEGATIVE),
            (p2_pos, obj::TOUCH_PROBE_2_POSITIVE),
            (p2_neg, obj::TOUCH_PROBE_2_NEGATIVE),
        ] {
            if hit {
                self.put(index, 0, Value::I32(position));
            }
        }
        let [p1, p2] = self.probes;
        let status = p1.status() | p2.status() << 8;
        self.put(obj::TOUCH_PROBE_STATUS, 0, Value::U16(status));
    }

    fn publish(&mut self, cw: u16, axis: &AxisStatus, now: f64) {
        let demand = self.to_increments(axis.cmd_pos);
        let actual = self.to_increments(axis.act_pos);
        let values = [
            (obj::POSITION_DEMAND, demand),
            (
                obj::POSITION_DEMAND_INTERNAL,
                demand.saturating_sub(self.home_shift),
            ),
            (obj::POSITION_ACTUAL, actual),
            (
                obj::POSITION_ACTUAL_INTERNAL,
                actual.saturating_sub(self.home_shift),
            ),
            (obj::VELOCITY_DEMAND, self.to_increments(axis.cmd_vel)),
            (obj::VELOCITY_ACTUAL, self.to_increments(axis.act_vel)),
            (
                obj::FOLLOWING_ERROR_ACTUAL,
                self.to_increments(axis.following_error),
            ),
        ];
        for (index, value) in values {
            self.put(index, 0, Value::I32(saturate(value)));
        }
        let torque = if self.streaming && self.mode == OperationMode::CyclicTorque {
            self.torque_demand
        } else {
            0
        };
        self.put(
            obj::TORQUE_ACTUAL,
            0,
            Value::I16(torque.clamp(-32768, 32767) as i16),
        );
        self.put(
            obj::MODES_OF_OPERATION_DISPLAY,
            0,
            Value::I8(self.mode.code()),
        );
        let statusword = self.compose_statusword(cw, axis, now);
        self.put(obj::STATUSWORD, 0, Value::U16(statusword));
    }

    fn compose_statusword(&mut self, cw: u16, axis: &AxisStatus, now: f64) -> u16 {
        let f = axis.flags;
        let mut s = self.state.statusword_bits() | sw::REMOTE;
        if self.warning || f.contains(AxisFlags::FE_WARNING) {
            s |= sw::WARNING;
        }
        if f.intersects(LIMIT_FLAGS) || self.clamped || self.limit_refused {
            s |= sw::INTERNAL_LIMIT_ACTIVE;
        }
        if f.contains(AxisFlags::HOMED) {
            s |= sw::HOMED;
        }
        if f.contains(AxisFlags::MOVING) {
            s |= sw::MOVING;
        }
        s | self.mode_bits(cw, axis, now)
    }

    /// Bits 10, 12 and 13 (see `docs/decisions.md`, CiA 402 drive, for "target reached").
    fn mode_bits(&mut self, cw: u16, axis: &AxisStatus, now: f64) -> u16 {
        let at_rest = at_rest(axis);
        let bit = |on: bool, mask: u16| if on { mask } else { 0 };
        if self.mode == OperationMode::Homing {
            // Homing status is kept across modes and states (python-canopen's `is_homed`).
            return match self.homing {
                Homing::NotStarted | Homing::Interrupted => sw::TARGET_REACHED,
                Homing::InProgress { .. } => 0,
                Homing::Attained => sw::OMS_12 | bit(at_rest, sw::TARGET_REACHED),
                Homing::Error => sw::OMS_13 | bit(at_rest, sw::TARGET_REACHED),
            };
        }
        if self.state != State::OperationEnabled {
            self.target_dwell.reset();
            self.following_dwell.reset();
            self.zero_speed_dwell.reset();
            return 0;
        }
        let halt = cw & cw::HALT != 0;
        let following_error = self.following_error(axis, now);
        let follows = bit(self.streaming && self.stream_accepted, sw::OMS_12);
        match self.mode {
            OperationMode::NoMode | OperationMode::Homing => 0,
            OperationMode::ProfilePosition => {
                let idle = at_rest && axis.fifo_len == 0;
                let reached = if halt {
                    at_rest
                } else {
                    let near = self.pp_target.is_none_or(|t| self.near_position(axis, t));
                    self.dwell_position(idle && near, now)
                };
                bit(reached, sw::TARGET_REACHED)
                    | bit(self.set_point_ack, sw::OMS_12)
                    | bit(following_error, sw::OMS_13)
            }
            OperationMode::ProfileVelocity => {
                let target = self.last_velocity_command.map_or(0, |k| k.0);
                let reached = if halt {
                    at_rest
                } else {
                    self.dwell_velocity(axis, target, now)
                };
                let threshold = self.int(obj::VELOCITY_THRESHOLD, 0);
                let slow = self.to_increments(axis.act_vel).abs() <= threshold;
                let zero = self.zero_speed_dwell.update(
                    slow,
                    now,
                    self.int(obj::VELOCITY_THRESHOLD_TIME, 0),
                );
                bit(reached, sw::TARGET_REACHED) | bit(zero, sw::OMS_12)
            }
            OperationMode::CyclicPosition => {
                let (target, _) = self.clamp_position(self.int(obj::TARGET_POSITION, 0));
                let reached = if halt {
                    at_rest
                } else {
                    let near = self.near_position(axis, target);
                    self.dwell_position(near, now)
                };
                bit(reached, sw::TARGET_REACHED) | follows | bit(following_error, sw::OMS_13)
            }
            OperationMode::CyclicVelocity => {
                let limit = self.max_velocity();
                let target = self.int(obj::TARGET_VELOCITY, 0).clamp(-limit, limit);
                let reached = if halt {
                    at_rest
                } else {
                    self.dwell_velocity(axis, target, now)
                };
                bit(reached, sw::TARGET_REACHED) | follows
            }
            OperationMode::CyclicTorque => bit(halt && at_rest, sw::TARGET_REACHED) | follows,
        }
    }

    /// |actual − target| within 0x6067 (0xFFFFFFFF: window off, always near).
    fn near_position(&self, axis: &AxisStatus, target: i64) -> bool {
        let window = self.int(obj::POSITION_WINDOW, 0);
        window == i64::from(u32::MAX) || (self.to_increments(axis.act_pos) - target).abs() <= window
    }

    fn dwell_position(&mut self, condition: bool, now: f64) -> bool {
        let time = self.int(obj::POSITION_WINDOW_TIME, 0);
        self.target_dwell.update(condition, now, time)
    }

    /// |actual velocity − target| within 0x606D for 0x606E.
    fn dwell_velocity(&mut self, axis: &AxisStatus, target: i64, now: f64) -> bool {
        let window = self.int(obj::VELOCITY_WINDOW, 0);
        let near = (self.to_increments(axis.act_vel) - target).abs() <= window;
        let time = self.int(obj::VELOCITY_WINDOW_TIME, 0);
        self.target_dwell.update(near, now, time)
    }

    /// |following error| beyond 0x6065 for longer than 0x6066 (0xFFFFFFFF: monitoring off).
    fn following_error(&mut self, axis: &AxisStatus, now: f64) -> bool {
        let window = self.int(obj::FOLLOWING_ERROR_WINDOW, 0);
        let over = window != i64::from(u32::MAX)
            && self.to_increments(axis.following_error).abs() > window;
        let time = self.int(obj::FOLLOWING_ERROR_TIMEOUT, 0);
        self.following_dwell.update(over, now, time)
    }

    // ---- parameters and units ----

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
