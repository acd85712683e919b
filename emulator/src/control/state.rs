//! `GET /api/v1/state`: the machine as humans and scripts read it. Field names are part of the
//! API (docs/decisions.md "Control API"); axis fields are named as the trace CSV columns.

use axes::command::CommandId;
use axes::command::{CoordinateSystem, Direction, ErrorKind};
use axes::runtime::RuntimeStats;
use axes::sampling::SamplerStatus;
use axes::status::{
    AxisState, AxisStatus, CaptureStatus, CommandRef, CompareStatus, CouplingStatus, DriveStatus,
    GroupFault, GroupState, GroupStatus, HandwheelStatus, InterferenceStatus, IoImage,
    StreamStatus,
};
use axum::extract::State;
use axum::Json;
use serde::Serialize;

use super::names::{drive_state_name, flag_names};
use super::recorder::TraceStatus;
use super::ControlState;

#[derive(Serialize)]
pub struct StateView<'a> {
    pub machine: &'a str,
    /// `realtime`, `virtual` or `scaled:K`.
    pub clock: &'a str,
    /// Servo period, seconds.
    pub period: f64,
    pub tick: u64,
    /// Engine time, seconds (tick × period).
    pub time: f64,
    pub axes: Vec<AxisView<'a>>,
    /// The axis groups (coordinated motion), by group number.
    pub groups: Vec<GroupView<'a>>,
    /// The gears and cams (issue 12), by slave axis: master, kind, phase, ratio, table.
    pub couplings: &'a [CouplingStatus],
    /// The armed (or done) capture channels, by axis and channel (`axes::status::CaptureStatus`).
    pub captures: &'a [CaptureStatus],
    /// The position-compare channels, by channel (`axes::status::CompareStatus`).
    pub compares: &'a [CompareStatus],
    /// The handwheels, by axis: input, ratio, counts, target, lag, dropped travel
    /// (`axes::status::HandwheelStatus`).
    pub handwheels: &'a [HandwheelStatus],
    pub io: IoView<'a>,
    pub drives: Vec<DriveView>,
    /// The configured data samplers (`sampling_configure`); their data come from
    /// `sampling_read`.
    pub samplers: &'a [SamplerStatus],
    /// The servo runtime's counters and lateness histogram (`axes::runtime::RuntimeStats`).
    pub runtime: RuntimeStats,
    pub trace: TraceStatus,
    /// The dashboard streams: open, the bound, batches lost by slow clients.
    pub stream: super::StreamStatus,
    /// Each running protocol front-end: counters, active faults, last error.
    pub frontends: Vec<serde_json::Value>,
    /// What the machine listens on, as its `listening:` lines say (`{protocol, address}`), the
    /// control port included.
    pub listeners: Vec<crate::frontend::Listener>,
}

#[derive(Serialize)]
pub struct AxisView<'a> {
    pub axis: usize,
    /// The config's `name`, if it gave one.
    pub name: Option<&'a str>,
    pub state: AxisState,
    /// Live flags and latched faults, by name (`enabled`, `moving`, `hw_limit_pos` …).
    pub flags: Vec<&'static str>,
    /// The subset of `flags` latched until a `reset`.
    pub latched: Vec<&'static str>,
    pub cmd_pos: f64,
    pub cmd_vel: f64,
    pub cmd_acc: f64,
    pub act_pos: f64,
    pub act_vel: f64,
    pub following_error: f64,
    /// The position sent to the drive: `cmd_pos` + `compensation`.
    pub output_pos: f64,
    /// The correction of compensation after the planner (`compensation_*` commands).
    pub compensation: f64,
    pub target_pos: f64,
    pub pulses: i64,
    pub pulses_last_tick: i32,
    pub pulse_frequency: f64,
    pub direction: Direction,
    pub encoder_counts: i64,
    pub quadrature: u8,
    pub dac_out: f64,
    /// Commands in the FIFO, the running one included.
    pub fifo_len: u16,
    pub current_command: Option<CommandRef>,
    pub next_command: Option<CommandRef>,
    pub homing_phase: u8,
    pub last_error: Option<ErrorKind>,
    /// Edges latched by the axis's capture channels, the newest one's actual position.
    pub captures: u32,
    pub capture_position: f64,
    /// Outputs fired by the compare channels on the axis.
    pub compare_outputs: u32,
    /// The PT/PVT buffer and its run: mode, running, space, used, loop_count, loops_done,
    /// underruns, time_ms.
    pub stream: StreamStatus,
}

impl<'a> AxisView<'a> {
    pub fn new(axis: usize, name: Option<&'a str>, s: &AxisStatus) -> AxisView<'a> {
        AxisView {
            axis,
            name,
            state: s.state,
            flags: flag_names(s.flags),
            latched: flag_names(s.latched),
            cmd_pos: s.cmd_pos,
            cmd_vel: s.cmd_vel,
            cmd_acc: s.cmd_acc,
            act_pos: s.act_pos,
            act_vel: s.act_vel,
            following_error: s.following_error,
            output_pos: s.output_pos,
            compensation: s.compensation,
            target_pos: s.target_pos,
            pulses: s.pulses,
            pulses_last_tick: s.pulses_last_tick,
            pulse_frequency: s.pulse_frequency,
            direction: if s.direction {
                Direction::Positive
            } else {
                Direction::Negative
            },
            encoder_counts: s.encoder_counts,
            quadrature: s.quadrature,
            dac_out: s.dac_out,
            fifo_len: s.fifo_len,
            current_command: s.current_command,
            next_command: s.next_command,
            homing_phase: s.homing_phase,
            last_error: s.last_error,
            captures: s.captures,
            capture_position: s.capture_position,
            compare_outputs: s.compare_outputs,
            stream: s.stream,
        }
    }
}

/// One axis group (`axes::status::GroupStatus`, coordinates as arrays of the members' count).
#[derive(Serialize)]
pub struct GroupView<'a> {
    pub group: u16,
    pub state: GroupState,
    /// Member axes in group-coordinate order.
    pub axes: &'a [u16],
    /// HMC's result axis (digest 000 §4.3), if the group has one.
    pub result_axis: Option<u16>,
    /// Commanded path position in group coordinates (member position − origin).
    pub position: &'a [f64],
    pub origin: &'a [f64],
    /// The coordinate system of moves that name none (`group_set_coordinate_system`).
    pub coordinate_system: CoordinateSystem,
    /// `position` in that system.
    pub frame_position: &'a [f64],
    /// The group's move protection: `not_enabled`, `clear` or `interference`.
    pub interference: InterferenceStatus,
    pub interference_distance: f64,
    pub path_velocity: f64,
    pub path_acceleration: f64,
    pub current_command: Option<CommandId>,
    /// Ordinal of the motion being executed since the group was created.
    pub segment: u64,
    pub user_segment: u32,
    pub queue_used: u32,
    pub queue_free: u32,
    pub remaining_length: f64,
    pub in_position: bool,
    pub override_factor: f64,
    pub last_error: Option<ErrorKind>,
    /// Why the group is in ErrorStop.
    pub fault: Option<GroupFault>,
}

impl<'a> GroupView<'a> {
    pub fn new(g: &'a GroupStatus) -> GroupView<'a> {
        let n = g.axes().len();
        GroupView {
            group: g.group,
            state: g.state,
            axes: g.axes(),
            result_axis: g.result_axis,
            position: g.position(),
            origin: g.origin.get(..n).unwrap_or(&g.origin),
            coordinate_system: g.coordinate_system,
            frame_position: g.frame_position(),
            interference: g.interference,
            interference_distance: g.interference_distance,
            path_velocity: g.path_velocity,
            path_acceleration: g.path_acceleration,
            current_command: g.current_command,
            segment: g.segment,
            user_segment: g.user_segment,
            queue_used: g.queue_used,
            queue_free: g.queue_free,
            remaining_length: g.remaining_length,
            in_position: g.in_position,
            override_factor: g.override_factor,
            last_error: g.last_error,
            fault: g.fault,
        }
    }
}

/// I/O images by channel number.
#[derive(Serialize)]
pub struct IoView<'a> {
    pub di: &'a [bool],
    #[serde(rename = "do")]
    pub do_: &'a [bool],
    pub ai: &'a [f64],
    pub ao: &'a [f64],
}

impl<'a> From<&'a IoImage> for IoView<'a> {
    fn from(io: &'a IoImage) -> Self {
        IoView {
            di: &io.di,
            do_: &io.do_,
            ai: &io.ai,
            ao: &io.ao,
        }
    }
}

#[derive(Serialize)]
pub struct DriveView {
    /// Slave number.
    pub slave: usize,
    pub axis: u16,
    /// CiA 402 state decoded from the statusword (`operation_enabled` …).
    pub state: Option<String>,
    /// 0x6041.
    pub statusword: u16,
    /// 0x6061, modes of operation display.
    pub mode: i8,
    /// 0x603F.
    pub error_code: u16,
}

impl DriveView {
    fn new(slave: usize, d: &DriveStatus) -> DriveView {
        DriveView {
            slave,
            axis: d.axis,
            state: drive_state_name(d.statusword),
            statusword: d.statusword,
            mode: d.mode,
            error_code: d.error_code,
        }
    }
}

pub async fn get_state(State(state): State<ControlState>) -> axum::response::Response {
    use axum::response::IntoResponse;
    let snapshot = state.handle.snapshot();
    let machine = &state.machine;
    let view = StateView {
        machine: &machine.name,
        clock: &machine.clock,
        period: snapshot.period,
        tick: snapshot.tick,
        time: snapshot.time(),
        axes: snapshot
            .axes
            .iter()
            .enumerate()
            .map(|(i, s)| AxisView::new(i, machine.axis_name(i), s))
            .collect(),
        groups: snapshot.groups.iter().map(GroupView::new).collect(),
        couplings: &snapshot.couplings,
        captures: &snapshot.captures,
        compares: &snapshot.compares,
        handwheels: &snapshot.handwheels,
        io: IoView::from(&snapshot.io),
        samplers: &snapshot.samplers,
        drives: snapshot
            .drives
            .iter()
            .enumerate()
            .map(|(i, d)| DriveView::new(i, d))
            .collect(),
        runtime: state.handle.stats(),
        trace: state.trace.status(),
        stream: state.streams.status(state.stream_max_clients),
        frontends: state.frontends.iter().map(|f| f.state()).collect(),
        listeners: crate::frontend::listeners(),
    };
    Json(view).into_response()
}
