//! Machines and helpers shared by the engine's behaviour tests.
// Test support: failing loudly is the point.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use axes::command::{
    ArcDirection, AxisInput, CircleMode, Command, CommandState, Enable, ForceInput,
    GetCommandState, GetParameter, GroupBufferMode, GroupCreate, GroupEnable, GroupParameter,
    GroupSetParameter, MoveAbsolute, MoveCircularAbsolute, MoveLinearAbsolute, MoveRelative,
    MoveSpline, MoveVelocity, Reply, SetParameter, TransitionMode,
};
use axes::config::{AxisConfig, HomeSwitchConfig, SwitchConfig};
use axes::status::{GroupState, GroupStatus};
use axes::{Engine, EngineConfig, EngineError, ParamId, Snapshot};

/// A stepper axis in mm: 1000 pulses/mm, finite travel, limits at ±500 mm, a home cam on
/// [100, 120] mm, 10 000 counts per rev and 1000 counts/mm (so one index every 10 mm).
pub fn stepper_mm() -> AxisConfig {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 10.0),
        (ParamId::Units, 1000.0),
        (ParamId::RepMode, 0.0),
        (ParamId::Speed, 100.0),
        (ParamId::Accel, 1000.0),
        (ParamId::Decel, 1000.0),
        (ParamId::FastDecel, 10_000.0),
        (ParamId::FeLimit, 1.0),
    ] {
        a.params.insert(p, v);
    }
    a.switches.limit_pos = Some(SwitchConfig {
        position: 500.0,
        filter: 0,
        active_low: false,
    });
    a.switches.limit_neg = Some(SwitchConfig {
        position: -500.0,
        filter: 0,
        active_low: false,
    });
    a.switches.home = Some(HomeSwitchConfig {
        low: 100.0,
        high: 120.0,
        filter: 0,
        active_low: false,
    });
    a
}

/// A command from its JSON (the scenario and control-API form), panicking with the text and
/// serde's reason when it does not parse.
pub fn cmd(json: &str) -> Command {
    serde_json::from_str(json).unwrap_or_else(|e| panic!("{json}: {e}"))
}

pub fn engine_with(axes: Vec<AxisConfig>) -> Engine {
    Engine::new(&EngineConfig {
        axes,
        ..EngineConfig::default()
    })
    .expect("valid test machine")
}

pub fn one_axis() -> Engine {
    engine_with(vec![stepper_mm()])
}

pub fn enabled(axis: AxisConfig) -> Engine {
    let mut e = engine_with(vec![axis]);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    e
}

pub fn ok(e: &mut Engine, c: Command) -> Reply {
    match e.apply(c.clone()) {
        Ok(r) => r,
        Err(err) => panic!("{c:?} refused: {err}"),
    }
}

pub fn refused(e: &mut Engine, c: Command) -> EngineError {
    match e.apply(c.clone()) {
        Ok(r) => panic!("{c:?} accepted: {r:?}"),
        Err(err) => err,
    }
}

/// The JSON `code` of the error `c` is refused with (`invalid_argument` …).
pub fn refused_code(e: &mut Engine, c: Command) -> String {
    let err = refused(e, c);
    let json = serde_json::to_value(&err).expect("an error serializes");
    json["code"].as_str().expect("a code").to_owned()
}

pub fn id_of(r: Reply) -> u32 {
    match r {
        Reply::Accepted { id } => id,
        other => panic!("expected an id, got {other:?}"),
    }
}

pub fn state_of(e: &mut Engine, id: u32) -> CommandState {
    match ok(e, Command::from(GetCommandState { id })) {
        Reply::CommandState { state, .. } => state,
        other => panic!("{other:?}"),
    }
}

pub fn param(e: &mut Engine, name: ParamId) -> f64 {
    match ok(e, Command::from(GetParameter { axis: 0, name })) {
        Reply::Value { value } => value,
        other => panic!("{other:?}"),
    }
}

pub fn set(e: &mut Engine, name: ParamId, value: f64) {
    ok(
        e,
        Command::from(SetParameter {
            axis: 0,
            name,
            value,
            lenient: false,
        }),
    );
}

pub fn force(e: &mut Engine, input: AxisInput, value: Option<bool>) {
    ok(
        e,
        Command::from(ForceInput {
            axis: 0,
            input,
            value,
        }),
    );
}

pub fn move_abs(position: f64) -> Command {
    move_abs_of(0, position)
}

pub fn move_rel_buffered(distance: f64) -> Command {
    Command::from(MoveRelative {
        axis: 0,
        distance,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: axes::command::BufferMode::Buffered,
    })
}

pub fn jog(velocity: f64) -> Command {
    Command::from(MoveVelocity {
        axis: 0,
        velocity,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: Default::default(),
    })
}

/// Step `seconds` of engine time.
pub fn run(e: &mut Engine, seconds: f64) {
    let n = (seconds / e.period()).round() as u64;
    for _ in 0..n {
        e.step();
    }
}

/// Step until `cond` holds on axis 0's status, at most `max_seconds`. Returns the ticks taken.
pub fn run_until(
    e: &mut Engine,
    max_seconds: f64,
    cond: impl Fn(&axes::AxisStatus) -> bool,
) -> Option<u64> {
    let n = (max_seconds / e.period()).round() as u64;
    for k in 1..=n {
        e.step();
        if cond(&e.axis_status(0).expect("axis 0")) {
            return Some(k);
        }
    }
    None
}

/// Record axis 0 for `seconds`.
pub fn record(e: &mut Engine, seconds: f64) -> Vec<axes::AxisStatus> {
    let n = (seconds / e.period()).round() as usize;
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        e.step();
        out.push(e.axis_status(0).expect("axis 0"));
    }
    out
}

pub fn status(e: &Engine) -> axes::AxisStatus {
    e.axis_status(0).expect("axis 0")
}

pub fn snapshot(e: &Engine) -> Snapshot {
    e.snapshot()
}

/// Enable every axis of `e`, make group 1 of `members` and enable it.
pub fn with_group(mut e: Engine, members: &[u16]) -> Engine {
    for axis in 0..e.axis_count() as u16 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    ok(
        &mut e,
        Command::from(GroupCreate {
            group: 1,
            axes: members.to_vec(),
            queue_capacity: None,
            lookahead: None,
            result_axis: None,
            orientation: Default::default(),
        }),
    );
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    e
}

/// Set group parameter `name` of group 1.
pub fn group_parameter(e: &mut Engine, name: GroupParameter, value: f64) {
    ok(
        e,
        Command::from(GroupSetParameter {
            group: 1,
            name,
            value,
        }),
    );
}

/// A free mm axis (no switches, no following-error check) whose own limits (`speed`, `accel`
/// and `decel` = `accel`) are far above the path's in the group tests.
pub fn fast_mm_axis(speed: f64, accel: f64) -> AxisConfig {
    free_linear_axis(
        1000.0,
        &[
            (ParamId::Speed, speed),
            (ParamId::Accel, accel),
            (ParamId::Decel, accel),
        ],
    )
}

/// A buffered straight group motion to `position`, the group's own limits, no transition.
pub fn group_line(group: u16, position: &[f64]) -> MoveLinearAbsolute {
    MoveLinearAbsolute {
        group,
        position: position.to_vec(),
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: GroupBufferMode::Buffered,
        transition: TransitionMode::None,
        user_segment: None,
        independent: Default::default(),
        coordinate_system: None,
    }
}

/// A buffered spline of group `group` through `points` (absolute), the group's own limits.
pub fn group_spline(group: u16, points: Vec<Vec<f64>>) -> MoveSpline {
    MoveSpline {
        group,
        points,
        relative: false,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: GroupBufferMode::Buffered,
        transition: TransitionMode::None,
        user_segment: None,
        coordinate_system: None,
        independent: Default::default(),
    }
}

/// A buffered arc of group `group` about `center` to `end`, in the plane of the first two
/// coordinates, the group's own limits.
pub fn group_arc(
    group: u16,
    center: &[f64],
    end: &[f64],
    direction: ArcDirection,
) -> MoveCircularAbsolute {
    MoveCircularAbsolute {
        group,
        mode: CircleMode::Center,
        aux_point: center.to_vec(),
        radius: None,
        end_point: end.to_vec(),
        direction,
        plane: None,
        normal: None,
        turns: 0,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: GroupBufferMode::Buffered,
        transition: TransitionMode::None,
        user_segment: None,
        independent: Default::default(),
        coordinate_system: None,
    }
}

/// A linear axis without switches, no following-error check, and `params` (the vendor vectors'
/// axes: their own limits set far above the path's, or to the manual's).
pub fn free_linear_axis(units: f64, params: &[(ParamId, f64)]) -> AxisConfig {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 10.0),
        (ParamId::Units, units),
        (ParamId::RepMode, 0.0),
        (ParamId::FeLimit, 0.0),
    ]
    .iter()
    .chain(params)
    {
        a.params.insert(*p, *v);
    }
    a
}

/// Step until the first group is in Standby again (at most `max_s`), calling `each` with the
/// engine and that group's status every tick.
pub fn run_path(e: &mut Engine, max_s: f64, mut each: impl FnMut(&Engine, &GroupStatus)) {
    let n = (max_s / e.period()).round() as u64;
    for _ in 0..n {
        e.step();
        let g = e.snapshot().groups[0];
        each(e, &g);
        if g.state == GroupState::Standby {
            return;
        }
    }
    panic!(
        "path not done after {max_s} s: {:?}",
        e.snapshot().groups[0]
    );
}

/// The distance from `p` to the nearest of the points `seen` (x, y).
pub fn nearest(seen: &[(f64, f64)], p: (f64, f64)) -> f64 {
    seen.iter()
        .map(|(x, y)| (x - p.0).hypot(y - p.1))
        .fold(f64::INFINITY, f64::min)
}

/// The angle swept about `center` along the points `seen` after `start`, unwrapped, in degrees
/// (counter-clockwise positive).
pub fn swept_degrees(seen: &[(f64, f64)], center: (f64, f64), start: (f64, f64)) -> f64 {
    let pi = std::f64::consts::PI;
    let angle = |(x, y): (f64, f64)| (y - center.1).atan2(x - center.0);
    let mut last = angle(start);
    let mut total = 0.0;
    for &p in seen {
        let now = angle(p);
        total += (now - last + pi).rem_euclid(2.0 * pi) - pi;
        last = now;
    }
    total.to_degrees()
}

/// A machine of `axes`, axis 1 behind a CiA 402 drive whose power the engine masters
/// (1000 increments per unit).
pub fn engine_with_mastered_drive(axes: Vec<AxisConfig>) -> Engine {
    Engine::new(&EngineConfig {
        axes,
        drives: vec![axes::cia402::DriveConfig {
            axis: 1,
            master: axes::cia402::DriveMaster::Engine,
            increments_per_unit: 1000.0,
            ..axes::cia402::DriveConfig::default()
        }],
        ..EngineConfig::default()
    })
    .expect("valid test machine")
}

/// A virtual axis in pulses (1 unit = 1 pulse): actual = commanded exactly, limits far above
/// any move's (gear and cam tests).
pub fn virtual_pulse_axis() -> AxisConfig {
    free_linear_axis(
        1.0,
        &[
            (ParamId::AxisType, 0.0),
            (ParamId::Speed, 10_000.0),
            (ParamId::Accel, 1e7),
            (ParamId::Decel, 1e6),
            (ParamId::FastDecel, 1e7),
        ],
    )
}

/// `n` copies of `axis`, all enabled.
pub fn enabled_machine(axis: AxisConfig, n: usize) -> Engine {
    let mut e = engine_with(vec![axis; n]);
    for axis in 0..n as u16 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    e
}

/// `move_absolute` of `axis`, aborting, with the axis's own limits.
pub fn move_abs_of(axis: u16, position: f64) -> Command {
    Command::from(MoveAbsolute {
        axis,
        position,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: Default::default(),
    })
}

/// `move_relative` of `axis`, aborting, with the axis's own limits.
pub fn move_rel_of(axis: u16, distance: f64) -> Command {
    Command::from(MoveRelative {
        axis,
        distance,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: Default::default(),
    })
}

/// `move_velocity` of `axis`, aborting, with the axis's own limits.
pub fn jog_of(axis: u16, velocity: f64) -> Command {
    Command::from(MoveVelocity {
        axis,
        velocity,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: Default::default(),
    })
}

/// Each command serializes to its pinned JSON, and that JSON reads back as the command.
pub fn assert_pinned(cases: Vec<(Command, &'static str)>) {
    for (command, json) in cases {
        assert_eq!(serde_json::to_string(&command).unwrap(), json);
        assert_eq!(
            serde_json::from_str::<Command>(json).unwrap(),
            command,
            "{json}"
        );
    }
}

/// `home` of `axis` with every setting of `spec`, aborting.
pub fn home_of(axis: u16, spec: &axes::homing::HomingSpec) -> Command {
    Command::from(axes::command::Home::with_spec(axis, spec))
}

/// `gear_in` of `slave` to `master`'s commanded position at 1:1, engaged at once.
pub fn gear_in_of(master: u16, slave: u16) -> Command {
    Command::from(axes::command::GearIn {
        master,
        slave,
        numerator: 1.0,
        denominator: 1.0,
        master_source: axes::command::MasterSource::Commanded,
        clutch_distance: None,
        acceleration: None,
        direction: None,
        phase_offset: 0,
        transition: false,
    })
}
