//! No command panics the engine, whatever its numbers (issue: "Bad input … the engine keeps
//! running. No panic on any command."): random sequences of every command kind with hostile
//! values, interleaved with ticks, on a machine with switches, a drive and I/O. And atomic
//! batches of them (issue 11 item 6): accepted, a batch is the same commands one by one;
//! refused, it leaves the engine as a twin that never saw it.

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::cia402::DriveConfig;
use axes::command::{
    AxisInput, BufferMode, Cancel, CancelScope, Command, Disable, DisableAll, EmergencyStopAll,
    Enable, EnableAll, EngineError, ForceAnalogInput, ForceDigitalInput, ForceInput,
    GetCommandState, GetParameter, Halt, Home, InjectFollowingError, ModifyTarget, MoveAbsolute,
    MoveRelative, MoveTogether, MoveVelocity, PositionFrame, ReadObject, Reset, ResetAll, Resume,
    SetParameter, SetPosition, Setpoint, Stop, StopAll, StopAxes, StopMode, StreamSetpoint,
    TogetherMove, WriteAnalogOutput, WriteDigitalOutput, WriteObject,
};
use axes::command::{
    CamIn, CamInterpolation, CamOut, CamPoint, CamTableDefine, Direction, FollowSegment, GearIn,
    GearOut, GearSetRatio, MasterSource,
};
use axes::homing::HomingQuirks;
use axes::od::Value;
use axes::{Engine, EngineConfig, ParamId};
use proptest::prelude::*;
use proptest::strategy::Union;

fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -1000.0..1000.0f64,
        1 => Just(0.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(1e300),
        1 => Just(-1e300),
        1 => Just(f64::MIN_POSITIVE),
        1 => Just(1e-12),
    ]
}

fn opt_number() -> impl Strategy<Value = Option<f64>> {
    prop_oneof![2 => Just(None), 1 => number().prop_map(Some)]
}

fn axis() -> impl Strategy<Value = u16> {
    prop_oneof![6 => Just(0u16), 2 => Just(1u16), 1 => Just(2u16), 1 => any::<u16>()]
}

fn buffer_mode() -> impl Strategy<Value = BufferMode> {
    prop_oneof![Just(BufferMode::Aborting), Just(BufferMode::Buffered)]
}

fn param() -> impl Strategy<Value = ParamId> {
    (0..ParamId::COUNT).prop_map(|i| ParamId::all().nth(i).unwrap())
}

fn input() -> impl Strategy<Value = AxisInput> {
    prop_oneof![
        Just(AxisInput::LimitPos),
        Just(AxisInput::LimitNeg),
        Just(AxisInput::Home),
        Just(AxisInput::Index),
        Just(AxisInput::DriveAlarm),
        Just(AxisInput::EncoderLoss),
    ]
}

fn value() -> impl Strategy<Value = Value> {
    prop_oneof![
        any::<u16>().prop_map(Value::U16),
        any::<i32>().prop_map(Value::I32),
        any::<i8>().prop_map(Value::I8),
        any::<u32>().prop_map(Value::U32),
        number().prop_map(Value::F64),
        ".{0,8}".prop_map(Value::String),
    ]
}

fn stop_mode() -> impl Strategy<Value = StopMode> {
    prop_oneof![
        Just(StopMode::Smooth),
        Just(StopMode::Abrupt),
        Just(StopMode::Emergency),
        Just(StopMode::Immediate),
    ]
}

/// A single-axis move as `move_together` takes it: any motion command, hostile values included.
fn together_move() -> BoxedStrategy<TogetherMove> {
    (0..3u8, axis(), number(), opt_number(), buffer_mode())
        .prop_map(|(kind, axis, x, velocity, buffer_mode)| match kind {
            0 => TogetherMove::MoveAbsolute(MoveAbsolute {
                axis,
                position: x,
                velocity,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode,
            }),
            1 => TogetherMove::MoveRelative(MoveRelative {
                axis,
                distance: x,
                velocity,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode,
            }),
            _ => TogetherMove::MoveVelocity(MoveVelocity {
                axis,
                velocity: x,
                acceleration: None,
                deceleration: velocity,
                jerk: None,
                buffer_mode,
            }),
        })
        .boxed()
}

/// The machine family (issue 11 item 6).
fn machine_command() -> BoxedStrategy<Command> {
    prop_oneof![
        3 => prop::collection::vec(together_move(), 0..4)
            .prop_map(|moves| Command::from(MoveTogether { moves })),
        1 => (prop::collection::vec(axis(), 0..4), stop_mode(), opt_number())
            .prop_map(|(axes, mode, deceleration)| Command::from(StopAxes { axes, mode, deceleration })),
        1 => (stop_mode(), opt_number())
            .prop_map(|(mode, deceleration)| Command::from(StopAll { mode, deceleration })),
        2 => Just(Command::from(EnableAll {})),
        1 => Just(Command::from(DisableAll {})),
        1 => Just(Command::from(EmergencyStopAll {})),
        2 => Just(Command::from(ResetAll {})),
    ]
    .boxed()
}

fn command() -> BoxedStrategy<Command> {
    let moves: Vec<BoxedStrategy<Command>> = vec![
        (
            axis(),
            number(),
            opt_number(),
            opt_number(),
            opt_number(),
            opt_number(),
            buffer_mode(),
        )
            .prop_map(
                |(axis, position, velocity, acceleration, deceleration, jerk, buffer_mode)| {
                    Command::from(MoveAbsolute {
                        axis,
                        position,
                        velocity,
                        acceleration,
                        deceleration,
                        jerk,
                        buffer_mode,
                    })
                },
            )
            .boxed(),
        (
            axis(),
            number(),
            opt_number(),
            opt_number(),
            opt_number(),
            opt_number(),
            buffer_mode(),
        )
            .prop_map(
                |(axis, distance, velocity, acceleration, deceleration, jerk, buffer_mode)| {
                    Command::from(MoveRelative {
                        axis,
                        distance,
                        velocity,
                        acceleration,
                        deceleration,
                        jerk,
                        buffer_mode,
                    })
                },
            )
            .boxed(),
        (
            axis(),
            number(),
            opt_number(),
            opt_number(),
            opt_number(),
            buffer_mode(),
        )
            .prop_map(
                |(axis, velocity, acceleration, deceleration, jerk, buffer_mode)| {
                    Command::from(MoveVelocity {
                        axis,
                        velocity,
                        acceleration,
                        deceleration,
                        jerk,
                        buffer_mode,
                    })
                },
            )
            .boxed(),
        (
            axis(),
            prop::option::of(-5i16..40),
            opt_number(),
            opt_number(),
            opt_number(),
            opt_number(),
            opt_number(),
        )
            .prop_map(
                |(axis, method, switch_velocity, zero_velocity, acceleration, offset, timeout)| {
                    Command::from(Home {
                        axis,
                        method,
                        switch_velocity,
                        zero_velocity,
                        acceleration,
                        offset,
                        timeout,
                        quirks: HomingQuirks::default(),
                        buffer_mode: BufferMode::Aborting,
                    })
                },
            )
            .boxed(),
    ];
    let control: Vec<BoxedStrategy<Command>> = vec![
        axis()
            .prop_map(|axis| Command::from(Enable { axis }))
            .boxed(),
        axis()
            .prop_map(|axis| Command::from(Disable { axis }))
            .boxed(),
        axis()
            .prop_map(|axis| Command::from(Reset { axis }))
            .boxed(),
        (axis(), 0..4u8, opt_number())
            .prop_map(|(axis, m, deceleration)| {
                Command::from(Stop {
                    axis,
                    mode: [
                        StopMode::Smooth,
                        StopMode::Abrupt,
                        StopMode::Emergency,
                        StopMode::Immediate,
                    ][m as usize],
                    deceleration,
                })
            })
            .boxed(),
        (axis(), opt_number())
            .prop_map(|(axis, deceleration)| Command::from(Halt { axis, deceleration }))
            .boxed(),
        axis()
            .prop_map(|axis| Command::from(Resume { axis }))
            .boxed(),
        (axis(), number(), 0..3u8)
            .prop_map(|(axis, position, f)| {
                Command::from(SetPosition {
                    axis,
                    position,
                    frame: [
                        PositionFrame::Both,
                        PositionFrame::Commanded,
                        PositionFrame::Actual,
                    ][f as usize],
                })
            })
            .boxed(),
        (axis(), param(), number(), any::<bool>())
            .prop_map(|(axis, name, value, lenient)| {
                Command::from(SetParameter {
                    axis,
                    name,
                    value,
                    lenient,
                })
            })
            .boxed(),
        (axis(), param())
            .prop_map(|(axis, name)| Command::from(GetParameter { axis, name }))
            .boxed(),
        (axis(), number(), any::<bool>())
            .prop_map(|(axis, position, relative)| {
                Command::from(ModifyTarget {
                    axis,
                    position,
                    relative,
                })
            })
            .boxed(),
        (axis(), 0..3u8)
            .prop_map(|(axis, s)| {
                Command::from(Cancel {
                    axis,
                    scope: [CancelScope::Next, CancelScope::Current, CancelScope::All][s as usize],
                })
            })
            .boxed(),
        any::<u32>()
            .prop_map(|id| Command::from(GetCommandState { id }))
            .boxed(),
    ];
    let io: Vec<BoxedStrategy<Command>> = vec![
        (axis(), input(), prop::option::of(any::<bool>()))
            .prop_map(|(axis, input, value)| Command::from(ForceInput { axis, input, value }))
            .boxed(),
        (0..80u16, prop::option::of(any::<bool>()))
            .prop_map(|(channel, value)| Command::from(ForceDigitalInput { channel, value }))
            .boxed(),
        (0..12u16, opt_number())
            .prop_map(|(channel, value)| Command::from(ForceAnalogInput { channel, value }))
            .boxed(),
        (0..80u16, any::<bool>())
            .prop_map(|(channel, value)| Command::from(WriteDigitalOutput { channel, value }))
            .boxed(),
        (0..12u16, number())
            .prop_map(|(channel, value)| Command::from(WriteAnalogOutput { channel, value }))
            .boxed(),
        (axis(), opt_number())
            .prop_map(|(axis, amount)| Command::from(InjectFollowingError { axis, amount }))
            .boxed(),
        (axis(), prop::option::of((0..3u8, number())))
            .prop_map(|(axis, sp)| {
                Command::from(StreamSetpoint {
                    axis,
                    setpoint: sp.map(|(k, x)| match k {
                        0 => Setpoint::Position { position: x },
                        1 => Setpoint::Velocity { velocity: x },
                        _ => Setpoint::Torque { torque: x },
                    }),
                })
            })
            .boxed(),
        (
            0..3u16,
            prop_oneof![
                Just(0x6040u16),
                Just(0x6060),
                Just(0x607A),
                Just(0x6081),
                Just(0x6098),
                any::<u16>()
            ],
            0..3u8,
        )
            .prop_map(|(slave, index, subindex)| {
                Command::from(ReadObject {
                    slave,
                    index,
                    subindex,
                })
            })
            .boxed(),
        (
            0..3u16,
            prop_oneof![
                Just(0x6040u16),
                Just(0x6060),
                Just(0x607A),
                Just(0x6081),
                Just(0x6098),
                any::<u16>()
            ],
            0..3u8,
            value(),
        )
            .prop_map(|(slave, index, subindex, value)| {
                Command::from(WriteObject {
                    slave,
                    index,
                    subindex,
                    value,
                })
            })
            .boxed(),
    ];
    let group = |v: Vec<BoxedStrategy<Command>>| Union::new(v).boxed();
    prop_oneof![
        4 => group(moves),
        4 => group(control),
        3 => group(io),
        2 => machine_command(),
        2 => coupling_command(),
    ]
    .boxed()
}

/// Gears and cams (issue 12) with hostile numbers, tables and axes.
fn coupling_command() -> BoxedStrategy<Command> {
    let source = || {
        prop_oneof![
            Just(MasterSource::Commanded),
            Just(MasterSource::Actual),
            Just(MasterSource::Encoder),
        ]
    };
    let direction = || {
        prop_oneof![
            Just(None),
            Just(Some(Direction::Positive)),
            Just(Some(Direction::Negative))
        ]
    };
    prop_oneof![
        (
            axis(),
            axis(),
            number(),
            number(),
            source(),
            opt_number(),
            opt_number(),
            direction()
        )
            .prop_map(|(master, slave, n, d, source, clutch, acc, direction)| {
                Command::from(GearIn {
                    master,
                    slave,
                    numerator: n,
                    denominator: d,
                    master_source: source,
                    clutch_distance: clutch,
                    acceleration: acc,
                    direction,
                    phase_offset: 0,
                    transition: false,
                })
            }),
        (axis(), number(), number()).prop_map(|(slave, numerator, denominator)| {
            Command::from(GearSetRatio {
                slave,
                numerator,
                denominator,
            })
        }),
        axis().prop_map(|slave| Command::from(GearOut { slave })),
        axis().prop_map(|slave| Command::from(CamOut { slave })),
        (
            0..3u16,
            prop::collection::vec((number(), number()), 0..6),
            0..3u8
        )
            .prop_map(|(table, p, k)| {
                Command::from(CamTableDefine {
                    table,
                    points: p
                        .into_iter()
                        .map(|(master, slave)| CamPoint {
                            master,
                            slave,
                            segment: FollowSegment::Normal,
                        })
                        .collect(),
                    interpolation: [
                        CamInterpolation::Linear,
                        CamInterpolation::Cubic,
                        CamInterpolation::Follow,
                    ][k as usize],
                })
            }),
        (
            (axis(), axis(), 0..3u16, source(), any::<bool>(), 0..3u32),
            (
                any::<bool>(),
                any::<bool>(),
                number(),
                number(),
                number(),
                number()
            ),
            (opt_number(), direction(), prop::option::of(0..80u16)),
        )
            .prop_map(
                |(
                    (master, slave, table, source, periodic, loop_count),
                    (ma, sa, mo, so, ms, ss),
                    (sp, sd, si),
                )| {
                    Command::from(CamIn {
                        master,
                        slave,
                        table,
                        master_source: source,
                        periodic,
                        loop_count,
                        master_absolute: ma,
                        slave_absolute: sa,
                        master_offset: mo,
                        slave_offset: so,
                        master_scaling: ms,
                        slave_scaling: ss,
                        start_position: sp,
                        start_direction: sd,
                        start_input: si,
                        start_capture: None,
                    })
                }
            ),
    ]
    .boxed()
}

fn machine() -> Engine {
    let mut servo = common::stepper_mm();
    servo.params.insert(ParamId::AxisType, 20.0);
    servo.params.insert(ParamId::ServoLoop, 1.0);
    servo.params.insert(ParamId::Kp, 2000.0);
    servo.plant.model = axes::config::PlantModel::PositionLoop;
    let mut cyclic = common::stepper_mm();
    cyclic.params.insert(ParamId::RepMode, 2.0);
    cyclic.params.insert(ParamId::RepDist, 180.0);
    cyclic.params.insert(ParamId::SmoothTime, 0.02);
    Engine::new(&EngineConfig {
        axes: vec![common::stepper_mm(), servo, cyclic],
        drives: vec![DriveConfig {
            axis: 1,
            increments_per_unit: 100.0,
            ..DriveConfig::default()
        }],
        ..EngineConfig::default()
    })
    .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn random_commands_never_panic_and_positions_stay_finite(
        script in prop::collection::vec((command(), 0..40u32), 1..40)
    ) {
        let mut e = machine();
        for (c, ticks) in script {
            let _ = e.apply(c);
            for _ in 0..ticks {
                e.step();
            }
            for a in &e.snapshot().axes {
                for x in [a.cmd_pos, a.cmd_vel, a.cmd_acc, a.act_pos, a.act_vel, a.following_error, a.target_pos] {
                    prop_assert!(x.is_finite(), "non-finite status {a:?}");
                }
            }
        }
    }

    #[test]
    fn a_batch_is_its_commands_one_by_one_or_nothing(
        warm_up in prop::collection::vec((command(), 0..20u32), 0..12),
        batch in prop::collection::vec(command(), 1..12),
    ) {
        let start = || {
            let mut e = machine();
            for (c, ticks) in &warm_up {
                let _ = e.apply(c.clone());
                for _ in 0..*ticks {
                    e.step();
                }
            }
            e
        };
        let (mut atomic, mut one_by_one, mut untouched) = (start(), start(), start());
        let mut replies = Vec::new();
        let mut first_error = None;
        for (index, c) in batch.iter().enumerate() {
            match one_by_one.apply(c.clone()) {
                Ok(r) => replies.push(r),
                Err(e) => {
                    first_error = Some((index, e));
                    break;
                }
            }
        }
        let twin = match (atomic.apply_batch(batch.clone()), first_error) {
            (Ok(got), None) => {
                prop_assert_eq!(got, replies);
                &mut one_by_one
            }
            (Err(EngineError::Item { list: "commands", index, error }), Some((at, e))) => {
                // Debug text: NaN in an error is not equal to itself.
                prop_assert_eq!(format!("{index} {error:?}"), format!("{at} {e:?}"));
                &mut untouched
            }
            (got, expected) => {
                return Err(TestCaseError::fail(format!("batch {got:?}, one by one {expected:?}")));
            }
        };
        // Same state now and after every tick; the next id is the same too.
        prop_assert_eq!(atomic.snapshot(), twin.snapshot());
        for _ in 0..30 {
            atomic.step();
            twin.step();
            prop_assert_eq!(atomic.snapshot(), twin.snapshot());
        }
        let probe = Command::from(MoveRelative {
            axis: 0,
            distance: 1.0,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: BufferMode::Buffered,
        });
        prop_assert_eq!(
            format!("{:?}", atomic.apply(probe.clone())),
            format!("{:?}", twin.apply(probe))
        );
    }
}
