//! Property tests of groups at the engine level (issue 11 "Tests"): random paths of lines and
//! arcs on a 3-axis group with random member limits, fed through the engine: every member's
//! commanded velocity and acceleration stay within its own limits at every tick, the path ends
//! exactly on the last programmed point, and every motion's command ends `done`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    ArcDirection, CircleMode, Command, CommandState, Enable, GroupBufferMode, GroupCreate,
    GroupEnable, MoveCircularAbsolute, MoveLinearAbsolute, TransitionMode,
};
use axes::config::AxisConfig;
use axes::status::GroupState;
use axes::{Engine, EngineConfig, ParamId};
use common::{id_of, ok, state_of};
use proptest::prelude::*;

#[derive(Clone, Debug)]
enum Step {
    Line([f64; 3]),
    /// Centre offset from the start (in x, y), the angle to turn (signed), the z change.
    Arc {
        center: [f64; 2],
        angle: f64,
        dz: f64,
    },
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        prop::array::uniform3(-50.0..50.0f64).prop_map(Step::Line),
        (
            prop::array::uniform2(-20.0..20.0f64),
            -6.0..6.0f64,
            -5.0..5.0f64
        )
            .prop_filter("a real arc", |(c, a, _)| c[0].hypot(c[1]) > 1.0
                && a.abs() > 0.1)
            .prop_map(|(center, angle, dz)| Step::Arc { center, angle, dz }),
    ]
}

fn axis(velocity: f64, acceleration: f64) -> AxisConfig {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 0.0),
        (ParamId::RepMode, 0.0),
        (ParamId::Speed, velocity),
        (ParamId::Accel, acceleration),
        (ParamId::Decel, acceleration),
        (ParamId::FeLimit, 0.0),
    ] {
        a.params.insert(p, v);
    }
    a
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn members_stay_within_their_limits_and_the_path_ends_exactly(
        limits in prop::array::uniform3((20.0..200.0f64, 500.0..5000.0f64)),
        steps in prop::collection::vec(step(), 1..6),
        blend in any::<bool>(),
        corner in 0.0..2.0f64,
    ) {
        let mut e = Engine::new(&EngineConfig {
            axes: limits.iter().map(|(v, a)| axis(*v, *a)).collect(),
            ..EngineConfig::default()
        })
        .unwrap();
        for a in 0..3 {
            ok(&mut e, Command::from(Enable { axis: a }));
        }
        ok(&mut e, Command::from(GroupCreate { group: 1, axes: vec![0, 1, 2], queue_capacity: None, lookahead: None, result_axis: None, orientation: Default::default() }));
        ok(&mut e, Command::from(GroupEnable { group: 1 }));
        let (buffer_mode, transition) = if blend {
            (GroupBufferMode::BlendingLow, TransitionMode::CornerDistance(corner))
        } else {
            (GroupBufferMode::Buffered, TransitionMode::None)
        };
        let mut at = [0.0; 3];
        let mut ids = Vec::new();
        for s in &steps {
            let command = match *s {
                Step::Line(p) => {
                    at = p;
                    Command::from(MoveLinearAbsolute {
                        group: 1, position: p.to_vec(), velocity: Some(150.0),
                        acceleration: Some(4000.0), deceleration: Some(4000.0), jerk: Some(0.0),
                        buffer_mode, transition, user_segment: None,
                        independent: Default::default(),
                        coordinate_system: None,
                    })
                }
                Step::Arc { center, angle, dz } => {
                    let c = [at[0] + center[0], at[1] + center[1]];
                    let (sin, cos) = angle.sin_cos();
                    let (dx, dy) = (at[0] - c[0], at[1] - c[1]);
                    let end = [c[0] + dx * cos - dy * sin, c[1] + dx * sin + dy * cos, at[2] + dz];
                    at = end;
                    Command::from(MoveCircularAbsolute {
                        group: 1, mode: CircleMode::Center, aux_point: vec![c[0], c[1], 0.0],
                        radius: None, end_point: end.to_vec(),
                        direction: if angle > 0.0 { ArcDirection::Ccw } else { ArcDirection::Cw },
                        plane: None, normal: None, turns: 0, velocity: Some(150.0),
                        acceleration: Some(4000.0), deceleration: Some(4000.0), jerk: Some(0.0),
                        buffer_mode, transition, user_segment: None,
                        independent: Default::default(),
                        coordinate_system: None,
                    })
                }
            };
            ids.push(id_of(ok(&mut e, command)));
        }
        let mut done = false;
        for _ in 0..120_000 {
            e.step();
            for (a, (v, acc)) in limits.iter().enumerate() {
                let s = e.axis_status(a).unwrap();
                prop_assert!(s.cmd_vel.abs() <= v * (1.0 + 1e-9) + 1e-9, "axis {a}: v {} > {v}", s.cmd_vel);
                prop_assert!(s.cmd_acc.abs() <= acc * (1.0 + 1e-6) + 1e-6, "axis {a}: a {} > {acc}", s.cmd_acc);
            }
            if e.snapshot().groups[0].state == GroupState::Standby {
                done = true;
                break;
            }
        }
        prop_assert!(done, "the path did not end");
        let end = e.snapshot().groups[0];
        prop_assert_eq!(end.position(), &at[..]);
        for id in ids {
            prop_assert_eq!(state_of(&mut e, id), CommandState::Done);
        }
    }
}
