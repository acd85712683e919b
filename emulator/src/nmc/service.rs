//! The NMC service: one request (a row of `mcemu_nmc::table` and its payload) → a reply
//! payload and, for what moves the machine, the engine commands to apply. Handlers are plain
//! functions over a [`Call`] (the request's reader, the reply's writer, a snapshot, the
//! device's NMC settings); the transport applies their commands in one batch and answers.
//!
//! Adding a function: its row in the table, its export in the shim, and one
//! `(row, handler)` pair in a family's `HANDLERS` here.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use axes::command::{Command, EngineError};
use axes::param::ParamId;
use axes::runtime::EngineHandle;
use axes::status::{AxisStatus, Snapshot};
use mcemu_dialects::PulseScale;
use mcemu_nmc::errors::{
    RTN_ARG_RANGE, RTN_BAD_PAYLOAD, RTN_INVALID_HANDLE, RTN_WRONG_HANDLE_KIND,
};
use mcemu_nmc::handle::{Handle, HandleKind};
use mcemu_nmc::payload::{PayloadError, Reader, Writer};
use mcemu_nmc::structs::{HomeSetting, JogPara, PtpPara};
use mcemu_nmc::table::Function;

use super::config::NmcDevice;
use super::crd::{CrdState, CRD_COUNT};
use super::stored::Stored;

/// Why a request is refused: its return code and the text `NMC_GetErrDesc` shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Refusal {
    pub code: i16,
    pub text: String,
}

impl Refusal {
    pub fn new(code: i16, text: impl Into<String>) -> Refusal {
        Refusal {
            code,
            text: text.into(),
        }
    }

    /// An argument outside its range: names the argument, the value and the range.
    pub fn range(argument: &str, value: impl std::fmt::Display, allowed: &str) -> Refusal {
        Refusal::new(
            RTN_ARG_RANGE,
            format!("{argument} = {value} is outside {allowed}"),
        )
    }

    pub fn engine(e: &EngineError) -> Refusal {
        Refusal::new(mcemu_dialects::nmc::code_for(e), e.to_string())
    }
}

impl From<PayloadError> for Refusal {
    fn from(e: PayloadError) -> Refusal {
        Refusal::new(RTN_BAD_PAYLOAD, format!("request payload: {e}"))
    }
}

/// What a handler leaves to the transport.
#[derive(Default)]
pub struct Plan {
    /// Applied in one batch (between the same two ticks), all or none; a refusal becomes the
    /// reply's code.
    pub commands: Vec<Command>,
    /// Reads the batch's outcome into the reply (an SDO's value, a drive's answer, the
    /// samples of `NMC_GetCollectData`) once the commands are applied, or turns their refusal
    /// into the call's; `None`: replies unread. Runs only when `commands` is not empty.
    pub then: Option<Then>,
}

impl std::fmt::Debug for Plan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Plan")
            .field("commands", &self.commands)
            .field("then", &self.then.is_some())
            .finish()
    }
}

/// See [`Plan::then`]: given the service, the batch's replies or refusal, the reply's writer.
pub type Then = Box<
    dyn FnOnce(
            &NmcService,
            Result<&[axes::command::Reply], &EngineError>,
            &mut Writer,
        ) -> Result<(), Refusal>
        + Send,
>;

pub type Handler = fn(&mut Call<'_>) -> Result<(), Refusal>;

/// The NMC settings of one axis that the engine does not keep: what `NMC_MtUpdate` starts
/// (digest 001 §2.5, §4.3) and the homing parameters (§3.13), in the manual's units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisSettings {
    pub prf_mode: i16,
    pub ptp: PtpPara,
    pub target: i64,
    /// pulse/ms; signed in JOG mode.
    pub vel: f64,
    pub jog: JogPara,
    pub home: HomeSetting,
    /// The last `NMC_MtHome` was refused for its parameters (home status bit 3).
    pub home_param_error: bool,
}

impl AxisSettings {
    /// From the axis's configured parameters (`scale`: pulses per user unit).
    pub fn from_params(params: &axes::param::ParamSet, scale: PulseScale) -> AxisSettings {
        let vel = |id| scale.from_engine(params.get(id)) / 1e3;
        let acc = |id| scale.from_engine(params.get(id)) / 1e6;
        let ptp = PtpPara {
            acc: acc(ParamId::Accel),
            dec: acc(ParamId::Decel),
            start_vel: vel(ParamId::StartVelocity),
            end_vel: vel(ParamId::EndVelocity),
            smooth_coef: (params.get(ParamId::SmoothTime) * 1e3)
                .round()
                .clamp(0.0, 199.0) as i16,
        };
        AxisSettings {
            prf_mode: 0,
            ptp,
            target: 0,
            vel: vel(ParamId::Speed),
            jog: JogPara {
                acc: ptp.acc,
                dec: ptp.dec,
                smooth_coef: 0.0,
            },
            home: HomeSetting {
                mode: 1,
                scan1st_vel: vel(ParamId::HomeSwitchVelocity),
                scan2nd_vel: vel(ParamId::HomeZeroVelocity),
                acc: acc(ParamId::HomeAcceleration),
                ..HomeSetting::default()
            },
            home_param_error: false,
        }
    }
}

/// Counts for `GET /state`.
#[derive(Debug, Default)]
pub struct NmcCounters {
    pub requests: mcemu_frontend::counter::Counter,
    /// Requests answered with a code other than 0.
    pub refused: mcemu_frontend::counter::Counter,
    pub unknown_function: mcemu_frontend::counter::Counter,
    /// Connections closed for garbage or an oversized frame.
    pub bad_frames: mcemu_frontend::counter::Counter,
    pub version_refused: mcemu_frontend::counter::Counter,
    pub idle_closed: mcemu_frontend::counter::Counter,
}

/// The NMC device one front-end section presents.
pub struct NmcService {
    pub engine: EngineHandle,
    pub device: NmcDevice,
    pub counters: NmcCounters,
    /// Injected faults (`POST /api/v1/faults`).
    pub faults: super::faults::NmcFaults,
    pub last_refusal: mcemu_frontend::refusal::LastRefusal<RefusedCall>,
    settings: Mutex<Vec<AxisSettings>>,
    /// The gear, PT, capture, compare, gantry, handwheel and compensation settings.
    sync: Mutex<super::sync_state::SyncState>,
    /// The coordinate systems (`NMC_Crd*`), by number.
    crd: Mutex<[CrdState; CRD_COUNT]>,
    /// Settings the engine has no model of (pulse mode, filters, encoder modes).
    stored: Mutex<Stored>,
    /// Coordinate transforms, arc sections, break points, move protection (0x17xx family).
    frames: Mutex<super::crd_frames::FramesState>,
    /// The axis-level additions' settings, the watchdog and the E-stop inputs.
    ax: Mutex<super::ax_state::AxState>,
    /// Extension modules, dedicated outputs, the written ID (0x12xx families).
    io: Mutex<super::io_state::IoState>,
    /// Data collection, users, the execution-time calculation (0x18xx).
    sys: Mutex<super::sys_state::SysState>,
    /// `TCardInfo` counts (digest 001 §1.1).
    pub io_counts: [i16; 4],
    /// Where `NMC_SaveMotionConfig` saves (`saved_config`), and the section's name (the
    /// file's); set once when the section starts.
    saving: std::sync::OnceLock<(Option<crate::state_dir::StateDir>, &'static str)>,
    // ---- EtherCAT bus (nmcecat) ----
    /// An `ecat` card's bus: axis numbers from 16, SDO slaves (set once at start).
    bus: std::sync::OnceLock<super::ecat_bus::EcatBus>,
}

/// What `GET /state` shows of a refused call.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct RefusedCall {
    pub function: String,
    pub code: i16,
}

impl NmcService {
    pub fn new(engine: EngineHandle, device: NmcDevice, io_counts: [i16; 4]) -> Arc<NmcService> {
        let service = NmcService {
            engine,
            device,
            counters: NmcCounters::default(),
            faults: Default::default(),
            last_refusal: Default::default(),
            settings: Mutex::new(Vec::new()),
            sync: Mutex::new(Default::default()),
            crd: Mutex::new(std::array::from_fn(|_| CrdState::fresh())),
            stored: Mutex::new(Stored::default()),
            frames: Mutex::new(Default::default()),
            ax: Mutex::new(Default::default()),
            io: Mutex::new(Default::default()),
            sys: Mutex::new(Default::default()),
            io_counts,
            saving: std::sync::OnceLock::new(),
            bus: std::sync::OnceLock::new(),
        };
        service.reset_settings();
        Arc::new(service)
    }

    /// Every axis's NMC settings back to the configured defaults (start, `NMC_DevReset`).
    pub fn reset_settings(&self) {
        let snapshot = self.engine.snapshot();
        let fresh = (0..snapshot.axes.len())
            .map(|a| {
                let params = snapshot.params.get(a).cloned().unwrap_or_default();
                AxisSettings::from_params(&params, scale_of(&snapshot, a))
            })
            .collect();
        *self.settings() = fresh;
        *self.sync() = super::sync_state::SyncState::new(snapshot.axes.len());
    }

    pub fn sync(&self) -> MutexGuard<'_, super::sync_state::SyncState> {
        self.sync.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub fn settings(&self) -> MutexGuard<'_, Vec<AxisSettings>> {
        self.settings.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub fn crd(&self) -> MutexGuard<'_, [CrdState; CRD_COUNT]> {
        self.crd.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub fn io(&self) -> MutexGuard<'_, super::io_state::IoState> {
        self.io.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub fn sys(&self) -> MutexGuard<'_, super::sys_state::SysState> {
        self.sys.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub fn frames(&self) -> MutexGuard<'_, super::crd_frames::FramesState> {
        self.frames.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub fn stored(&self) -> MutexGuard<'_, Stored> {
        self.stored.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Set where the saved motion configuration lives (once, at start).
    pub fn set_saving(&self, dir: Option<crate::state_dir::StateDir>, section: &'static str) {
        let _ = self.saving.set((dir, section));
    }

    pub fn state_dir(&self) -> Option<&crate::state_dir::StateDir> {
        self.saving.get().and_then(|(d, _)| d.as_ref())
    }

    /// The front-end section's name (`nmc`, `nmc_local`).
    pub fn section(&self) -> &'static str {
        self.saving.get().map_or("nmc", |(_, s)| s)
    }

    // ---- EtherCAT bus (nmcecat) ----
    /// Set the card's bus (once, at start).
    pub fn set_bus(&self, bus: super::ecat_bus::EcatBus) {
        let _ = self.bus.set(bus);
    }

    /// The card's bus (none until set).
    pub fn bus(&self) -> &super::ecat_bus::EcatBus {
        self.bus.get_or_init(Default::default)
    }

    pub fn ax(&self) -> MutexGuard<'_, super::ax_state::AxState> {
        self.ax.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Serve one request with `handler` (the function's, from the handler tables; `None` if it
    /// has none): the reply's code and payload (out arguments, or the error's text).
    pub async fn serve(
        &self,
        function: &Function,
        handler: Option<Handler>,
        payload: &[u8],
        peer: &str,
    ) -> (i16, Vec<u8>) {
        self.counters.requests.inc();
        let result = self.run(handler, payload).await;
        match result {
            Ok(out) => (0, out),
            Err(r) => {
                self.counters.refused.inc();
                let text = format!("{}: {}", function.name, r.text);
                self.last_refusal.record(
                    peer.to_string(),
                    RefusedCall {
                        function: function.name.to_string(),
                        code: r.code,
                    },
                    &text,
                );
                (r.code, text.into_bytes())
            }
        }
    }

    async fn run(&self, handler: Option<Handler>, payload: &[u8]) -> Result<Vec<u8>, Refusal> {
        let handler = handler.ok_or_else(|| {
            Refusal::new(
                mcemu_nmc::errors::RTN_UNKNOWN_FUNCTION,
                "not served by this mcemu",
            )
        })?;
        let mut reply = Writer::new();
        let mut plan = Plan::default();
        {
            let snapshot = self.engine.snapshot();
            // Any request moves the watchdog's deadline (digest 001 §2.20, TV71): queued
            // before the request's own commands. A full queue loses it; the next tick's
            // request sends another.
            if let Some(kick) = self.ax().heard(snapshot.tick) {
                let _ = self.engine.submit(kick.into());
            }
            let mut call = Call {
                service: self,
                snapshot,
                input: Reader::new(payload),
                output: &mut reply,
                plan: &mut plan,
            };
            handler(&mut call)?;
            call.input.finish()?;
        }
        if !plan.commands.is_empty() {
            let result = self.engine.call_batch_async(plan.commands).await;
            match result {
                Ok(replies) => {
                    if let Some(then) = plan.then {
                        then(self, Ok(&replies), &mut reply)?;
                    }
                }
                Err(axes::runtime::CallError::Engine(e)) => {
                    if let Some(then) = plan.then {
                        then(self, Err(&e), &mut reply)?;
                    }
                    return Err(Refusal::engine(&e));
                }
                Err(e) => {
                    return Err(Refusal::new(
                        mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::Fault),
                        e.to_string(),
                    ))
                }
            }
        }
        Ok(reply.bytes)
    }
}

/// Pulses per user unit of axis `axis` (its `units` parameter; 1 if unknown).
pub fn scale_of(snapshot: &Snapshot, axis: usize) -> PulseScale {
    let units = snapshot
        .params
        .get(axis)
        .map_or(1.0, |p| p.get(ParamId::Units));
    PulseScale {
        pulses_per_unit: if units > 0.0 && units.is_finite() {
            units
        } else {
            1.0
        },
    }
}

/// One request being handled.
pub struct Call<'a> {
    pub service: &'a NmcService,
    pub snapshot: Arc<Snapshot>,
    pub input: Reader<'a>,
    pub output: &'a mut Writer,
    pub plan: &'a mut Plan,
}

impl Call<'_> {
    /// The device handle that starts the request.
    pub fn device(&mut self) -> Result<(), Refusal> {
        let h = self.input.u16()?;
        match Handle::decode(h) {
            Some(d) if d.kind == HandleKind::Device => Ok(()),
            Some(_) => Err(Refusal::new(
                RTN_WRONG_HANDLE_KIND,
                format!("{h:#06x} is an axis handle; a device handle is expected"),
            )),
            None => Err(Refusal::new(
                RTN_INVALID_HANDLE,
                format!("{h:#06x} is not a handle"),
            )),
        }
    }

    /// The axis handle that starts the request: its axis number.
    pub fn axis(&mut self) -> Result<usize, Refusal> {
        let h = self.input.u16()?;
        match Handle::decode(h) {
            // Local axes and, on an `ecat` card, bus drives from 16 (`ecat_bus`).
            Some(a) if a.kind == HandleKind::Axis => {
                let bus = self.service.bus();
                let n = self.snapshot.axes.len();
                bus.engine_axis(a.item, n).ok_or_else(|| {
                    Refusal::new(
                        RTN_INVALID_HANDLE,
                        format!(
                            "{h:#06x} names axis {}; the device has {} local axes and {} bus drives",
                            a.item,
                            bus.local_count(n),
                            bus.drives().len()
                        ),
                    )
                })
            }
            Some(_) => Err(Refusal::new(
                RTN_WRONG_HANDLE_KIND,
                format!("{h:#06x} is a device handle; an axis handle is expected"),
            )),
            None => Err(Refusal::new(
                RTN_INVALID_HANDLE,
                format!("{h:#06x} is not a handle"),
            )),
        }
    }

    pub fn status(&self, axis: usize) -> Option<&AxisStatus> {
        self.snapshot.axes.get(axis)
    }

    pub fn scale(&self, axis: usize) -> PulseScale {
        scale_of(&self.snapshot, axis)
    }

    /// A copy of axis `axis`'s settings (exists: `axis` was checked).
    pub fn settings(&self, axis: usize) -> AxisSettings {
        let s = self.service.settings();
        s.get(axis).copied().unwrap_or_else(|| {
            AxisSettings::from_params(
                &Default::default(),
                PulseScale {
                    pulses_per_unit: 1.0,
                },
            )
        })
    }

    /// Change axis `axis`'s settings.
    pub fn update(&self, axis: usize, f: impl FnOnce(&mut AxisSettings)) {
        if let Some(s) = self.service.settings().get_mut(axis) {
            f(s);
        }
    }

    pub fn command(&mut self, c: impl Into<Command>) {
        self.plan.commands.push(c.into());
    }
}

/// Pulses (rounded, saturated) from user units.
pub fn pulses(scale: PulseScale, units: f64) -> i64 {
    let p = scale.from_engine(units).round();
    if p.is_nan() {
        0
    } else {
        p.clamp(i64::MIN as f64, i64::MAX as f64) as i64
    }
}

#[cfg(test)]
mod tests {
    use axes::command::ErrorKind;

    /// `mtn_lib20_err.h` codes 1–21 are the dialect's engine codes, name for name.
    #[test]
    fn engine_codes_match_the_dialect() {
        for (kind, name) in [
            (ErrorKind::InvalidAxis, "RTN_INVALID_AXIS"),
            (ErrorKind::UnknownParameter, "RTN_UNKNOWN_PARAMETER"),
            (ErrorKind::InvalidParameter, "RTN_INVALID_PARAMETER"),
            (ErrorKind::ReadOnlyParameter, "RTN_READ_ONLY_PARAMETER"),
            (ErrorKind::InvalidArgument, "RTN_INVALID_ARGUMENT"),
            (ErrorKind::AxisDisabled, "RTN_AXIS_DISABLED"),
            (ErrorKind::AxisInError, "RTN_AXIS_IN_ERROR"),
            (ErrorKind::LimitActive, "RTN_LIMIT_ACTIVE"),
            (ErrorKind::QueueFull, "RTN_QUEUE_FULL"),
            (ErrorKind::Unsupported, "RTN_UNSUPPORTED"),
            (ErrorKind::InvalidState, "RTN_INVALID_STATE"),
            (ErrorKind::CauseStillPresent, "RTN_CAUSE_STILL_PRESENT"),
            (ErrorKind::UnknownCommand, "RTN_UNKNOWN_COMMAND"),
            (ErrorKind::Homing, "RTN_HOMING"),
            (ErrorKind::Object, "RTN_OBJECT"),
            (ErrorKind::InvalidSlave, "RTN_INVALID_SLAVE"),
            (ErrorKind::InvalidChannel, "RTN_INVALID_CHANNEL"),
            (ErrorKind::LimitReached, "RTN_LIMIT_REACHED"),
            (ErrorKind::Fault, "RTN_FAULT"),
            (ErrorKind::InvalidGroup, "RTN_INVALID_GROUP"),
            (ErrorKind::GroupState, "RTN_GROUP_STATE"),
        ] {
            let code = mcemu_dialects::nmc::code_for_kind(kind);
            let row = mcemu_nmc::errors::lookup(code);
            assert_eq!(row.map(|r| r.name), Some(name), "{kind:?}");
        }
    }
}
