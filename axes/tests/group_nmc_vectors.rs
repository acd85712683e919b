//! NMC coordinate-system test vectors (digest 001 §6, TV 42–54) at the engine level, in pulses
//! (user unit = 1 pulse) with the manual's p/ms and p/ms² turned into p/s and p/s². The axes'
//! own limits are far above the path's, so the path limits govern, as in the manual's examples.
//! The NMC-only rules (4 axes per coordinate system, 18 per D8 pack) belong to the NMC
//! front-end (issue 13); the engine's own bound (9 axes) is in `group_lifecycle.rs`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    ArcDirection, CircleMode, Command, CommandState, ErrorKind, GroupAxisMove, GroupContinue,
    GroupDwell, GroupHalt, GroupSetOutput, GroupSetOverride, GroupStop, MoveCircularAbsolute,
    MoveLinearAbsolute, WriteDigitalOutput,
};
use axes::config::AxisConfig;
use axes::status::{GroupState, GroupStatus};
use axes::{Engine, EngineConfig, ParamId};
use common::{id_of, nearest, ok, refused, run_path, state_of};

/// NMC velocities in p/ms and accelerations in p/ms², in p/s and p/s².
const P_PER_MS: f64 = 1e3;
const P_PER_MS2: f64 = 1e6;

fn pulse_axis() -> AxisConfig {
    common::free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, 1e6),
            (ParamId::Accel, 1e8),
            (ParamId::Decel, 1e8),
        ],
    )
}

/// `n` pulse axes, enabled; group 1 of `members`.
fn machine(n: usize, members: &[u16]) -> Engine {
    let e = Engine::new(&EngineConfig {
        axes: vec![pulse_axis(); n],
        ..EngineConfig::default()
    })
    .unwrap();
    common::with_group(e, members)
}

/// `CrdLine…(crd, seg, mask, pos, endVel 0, vel, acc)`.
fn line(seg: u32, pos: &[f64], vel: f64, acc: f64) -> MoveLinearAbsolute {
    MoveLinearAbsolute {
        velocity: Some(vel * P_PER_MS),
        acceleration: Some(acc * P_PER_MS2),
        deceleration: Some(acc * P_PER_MS2),
        jerk: Some(0.0),
        user_segment: Some(seg),
        coordinate_system: None,
        ..common::group_line(1, pos)
    }
}

/// An arc about `center` at 10 p/ms and 1 p/ms².
fn arc(seg: u32, end: &[f64], center: &[f64], dir: ArcDirection) -> MoveCircularAbsolute {
    MoveCircularAbsolute {
        velocity: Some(10.0 * P_PER_MS),
        acceleration: Some(1.0 * P_PER_MS2),
        deceleration: Some(1.0 * P_PER_MS2),
        jerk: Some(0.0),
        user_segment: Some(seg),
        coordinate_system: None,
        ..common::group_arc(1, center, end, dir)
    }
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

fn send(e: &mut Engine, c: impl Into<Command>) -> u32 {
    id_of(ok(e, c.into()))
}

#[test]
fn tv42_s_crd_full_ends_at_10000_after_a_ccw_semicircle_and_the_delayed_output() {
    let mut e = machine(3, &[0, 1, 2]);
    ok(
        &mut e,
        Command::from(WriteDigitalOutput {
            channel: 1,
            value: true,
        }),
    );
    send(&mut e, line(1, &[0.0, 0.0, 0.0], 2.0, 0.5));
    send(
        &mut e,
        MoveCircularAbsolute {
            velocity: Some(2.0 * P_PER_MS),
            acceleration: Some(0.5 * P_PER_MS2),
            deceleration: Some(0.5 * P_PER_MS2),
            ..arc(
                2,
                &[10000.0, 0.0, 0.0],
                &[5000.0, 0.0, 0.0],
                ArcDirection::Ccw,
            )
        },
    );
    send(
        &mut e,
        GroupDwell {
            group: 1,
            seconds: 0.1,
        },
    );
    let output = send(
        &mut e,
        GroupSetOutput {
            group: 1,
            channel: 1,
            value: false,
        },
    );
    let mut seen = Vec::new();
    let mut arrived = None;
    let mut cleared = None;
    run_path(&mut e, 20.0, |e, g| {
        let p = g.position();
        seen.push((p[0], p[1]));
        if arrived.is_none() && p == [10000.0, 0.0, 0.0] {
            arrived = Some(e.tick());
        }
        if cleared.is_none() && !e.io().do_[1] {
            cleared = Some(e.tick());
        }
    });
    assert_eq!(group(&e).position(), &[10000.0, 0.0, 0.0]);
    assert!(
        nearest(&seen, (5000.0, -5000.0)) < 2.0,
        "CCW passes y = −5000"
    );
    assert!(seen.iter().all(|(_, y)| *y <= 1e-6));
    let wait = cleared.unwrap() - arrived.unwrap();
    assert!(wait >= 100, "the output cleared {wait} ms after arrival");
    assert_eq!(state_of(&mut e, output), CommandState::Done);
    assert_eq!(
        group(&e).user_segment,
        2,
        "the last motion's segment number"
    );
    // π·5000 / 2000 p/s ≈ 7.85 s plus the ramps.
    let t = arrived.unwrap() as f64 * e.period();
    assert!((7.85..8.5).contains(&t), "{t} s");
}

#[test]
fn tv43_a_full_cw_circle_about_5000_5000_passes_10000_10000_and_returns() {
    let mut e = machine(2, &[0, 1]);
    send(
        &mut e,
        arc(1, &[0.0, 0.0], &[5000.0, 5000.0], ArcDirection::Cw),
    );
    let mut seen = Vec::new();
    let mut travelled = 0.0;
    let mut last = (0.0, 0.0);
    run_path(&mut e, 20.0, |_, g| {
        let p = (g.position()[0], g.position()[1]);
        travelled += (p.0 - last.0).hypot(p.1 - last.1);
        last = p;
        seen.push(p);
    });
    assert!(nearest(&seen, (10000.0, 10000.0)) < 10.0);
    let length = std::f64::consts::TAU * 5000.0 * std::f64::consts::SQRT_2;
    assert!((travelled - length).abs() < 1.0, "{travelled} vs {length}");
    assert_eq!(group(&e).position(), &[0.0, 0.0]);
}

#[test]
fn tv44_a_radius_2500_semicircle_passes_its_side_by_direction() {
    for (dir, side) in [
        (ArcDirection::Ccw, (3500.0, 500.0)),
        (ArcDirection::Cw, (-500.0, 3500.0)),
    ] {
        let mut e = machine(2, &[0, 1]);
        send(
            &mut e,
            MoveCircularAbsolute {
                mode: CircleMode::Radius,
                radius: Some(2500.0),
                ..arc(2, &[3000.0, 4000.0], &[], dir)
            },
        );
        let mut seen = Vec::new();
        run_path(&mut e, 10.0, |_, g| {
            seen.push((g.position()[0], g.position()[1]))
        });
        assert!(nearest(&seen, side) < 5.0, "{dir:?}");
        assert_eq!(group(&e).position(), &[3000.0, 4000.0]);
    }
}

#[test]
fn tv45_a_signed_radius_takes_the_60_or_the_300_degree_arc() {
    for (radius, sweep) in [(10000.0, 60.0_f64), (-10000.0, 300.0)] {
        let mut e = machine(2, &[0, 1]);
        send(
            &mut e,
            MoveCircularAbsolute {
                mode: CircleMode::Radius,
                radius: Some(radius),
                ..arc(1, &[10000.0, 0.0], &[], ArcDirection::Ccw)
            },
        );
        let mut travelled = 0.0;
        let mut last = (0.0, 0.0);
        run_path(&mut e, 20.0, |_, g| {
            let p = (g.position()[0], g.position()[1]);
            travelled += (p.0 - last.0).hypot(p.1 - last.1);
            last = p;
        });
        let length = sweep.to_radians() * 10000.0;
        assert!((travelled - length).abs() < 1.0, "r {radius}: {travelled}");
        assert_eq!(group(&e).position(), &[10000.0, 0.0]);
    }
}

#[test]
fn tv46_s_crd_helix_five_cw_turns_climb_to_20000() {
    let mut e = machine(3, &[0, 1, 2]);
    send(
        &mut e,
        MoveCircularAbsolute {
            turns: 4,
            ..arc(
                16,
                &[0.0, 0.0, 20000.0],
                &[5000.0, 0.0, 0.0],
                ArcDirection::Cw,
            )
        },
    );
    // The angle about the centre, unwrapped: 5 turns clockwise, z = 4000 per turn.
    let tau = std::f64::consts::TAU;
    let (mut angle, mut last) = (0.0, std::f64::consts::PI);
    run_path(&mut e, 30.0, |_, g| {
        let p = g.position();
        let now = p[1].atan2(p[0] - 5000.0);
        angle += (now - last + std::f64::consts::PI).rem_euclid(tau) - std::f64::consts::PI;
        last = now;
        assert!(
            (p[2] - 4000.0 * -angle / tau).abs() < 1e-6,
            "{p:?} at {angle}"
        );
    });
    assert!((angle + 5.0 * tau).abs() < 1e-6, "{angle}");
    assert_eq!(group(&e).position(), &[0.0, 0.0, 20000.0]);
}

#[test]
fn tv47_s_crd_d8_six_axes_end_at_9000_minus_9000() {
    let mut e = machine(6, &[0, 1, 2, 3, 4, 5]);
    send(&mut e, line(4, &[10000.0; 6], 10.0, 1.0));
    send(
        &mut e,
        line(5, &[0.0, 10000.0, 0.0, 0.0, 10000.0, 0.0], 10.0, 1.0),
    );
    for i in 0..10 {
        let k = 1000.0 * f64::from(i);
        send(&mut e, line(10, &[k, -k, k, -k, k, -k], 10.0, 1.0));
    }
    run_path(&mut e, 60.0, |_, _| {});
    assert_eq!(
        group(&e).position(),
        &[9000.0, -9000.0, 9000.0, -9000.0, 9000.0, -9000.0]
    );
}

#[test]
fn tv48_s_crd_bufio_outputs_dwell_and_an_axis_move_with_the_last_segment() {
    let mut e = machine(4, &[0, 1, 2]);
    ok(
        &mut e,
        Command::from(WriteDigitalOutput {
            channel: 0,
            value: true,
        }),
    );
    send(&mut e, line(19, &[0.0, 0.0, 0.0], 10.0, 1.0));
    send(&mut e, line(20, &[10000.0, 10000.0, 0.0], 10.0, 1.0));
    send(
        &mut e,
        GroupSetOutput {
            group: 1,
            channel: 0,
            value: false,
        },
    );
    send(&mut e, line(21, &[0.0, 0.0, 0.0], 10.0, 1.0));
    send(
        &mut e,
        GroupDwell {
            group: 1,
            seconds: 1.0,
        },
    );
    send(
        &mut e,
        GroupSetOutput {
            group: 1,
            channel: 0,
            value: true,
        },
    );
    send(&mut e, line(24, &[10000.0, 10000.0, 0.0], 10.0, 1.0));
    send(
        &mut e,
        GroupAxisMove {
            group: 1,
            axis: 3,
            position: 10000.0,
            velocity: Some(10.0 * P_PER_MS),
            acceleration: Some(1.0 * P_PER_MS2),
            deceleration: Some(1.0 * P_PER_MS2),
            jerk: Some(0.0),
        },
    );
    send(&mut e, line(26, &[0.0, 0.0, 0.0], 10.0, 1.0));
    let mut low_at = None;
    let mut back_home = None;
    let mut high_again = None;
    let mut axis3_start = None;
    run_path(&mut e, 30.0, |e, g| {
        let p = g.position().to_vec();
        let out = e.io().do_[0];
        if low_at.is_none() && !out {
            low_at = Some(p.clone());
        }
        if low_at.is_some() && back_home.is_none() && p == [0.0, 0.0, 0.0] {
            back_home = Some(e.tick());
        }
        if back_home.is_some() && high_again.is_none() && out {
            high_again = Some(e.tick());
        }
        if axis3_start.is_none() && e.axis_status(3).unwrap().cmd_pos != 0.0 {
            axis3_start = Some((g.user_segment, p));
        }
    });
    // A buffered (exact-stop) junction between two ticks: the path is at (10000, 10000) within
    // the tick the output changes in, and the samples around it are within a tick's travel.
    let low = low_at.unwrap();
    assert!(
        (low[0] - 10000.0).abs() < 1.0 && (low[1] - 10000.0).abs() < 1.0,
        "{low:?}"
    );
    let dwell = high_again.unwrap() - back_home.unwrap();
    assert!((1000..=1001).contains(&dwell), "{dwell} ms");
    let (seg, at) = axis3_start.unwrap();
    assert_eq!(seg, 26, "axis 3 starts with the last segment");
    assert!(at[0] > 9990.0, "{at:?}");
    common::run(&mut e, 2.0);
    assert_eq!(e.axis_status(3).unwrap().cmd_pos, 10000.0);
}

/// S-CRD-LINE's two lines, stopped mid-segment with the buffer kept (NMC CrdStopMtn is
/// `group_halt`); the lines' command ids.
fn stopped_mid_segment() -> (Engine, [u32; 2]) {
    let mut e = machine(3, &[0, 1, 2]);
    let first = send(&mut e, line(0, &[10000.0, 10000.0, 0.0], 10.0, 0.5));
    let second = send(&mut e, line(0, &[0.0, 0.0, 0.0], 10.0, 0.5));
    common::run(&mut e, 0.5);
    ok(
        &mut e,
        Command::from(GroupHalt {
            group: 1,
            deceleration: None,
        }),
    );
    common::run(&mut e, 0.5);
    (e, [first, second])
}

#[test]
fn tv49_a_stop_mid_segment_keeps_the_buffer_and_the_start_completes_it() {
    let (mut e, _) = stopped_mid_segment();
    let g = group(&e);
    assert_eq!((g.state, g.path_velocity), (GroupState::Halted, 0.0));
    assert!(g.queue_used > 0, "the buffer is kept");
    ok(&mut e, Command::from(GroupContinue { group: 1 }));
    run_path(&mut e, 10.0, |_, _| {});
    assert_eq!(group(&e).position(), &[0.0, 0.0, 0.0]);
}

/// NMC CrdBufClr after CrdStopMtn (the buffer kept, TV49) is `group_stop`: the queue is
/// dropped; CrdBufGetUsed = 0 and BIT_CORD_EMPTY are `queue_used` 0 with the whole capacity
/// free.
#[test]
fn tv50_clearing_the_buffer_leaves_it_empty() {
    let (mut e, ids) = stopped_mid_segment();
    assert_eq!(group(&e).queue_used, 2, "the buffer is kept by the stop");
    ok(
        &mut e,
        Command::from(GroupStop {
            group: 1,
            deceleration: None,
        }),
    );
    common::run(&mut e, 0.1);
    let g = group(&e);
    assert_eq!(g.state, GroupState::Standby);
    assert_eq!((g.queue_used, g.queue_free), (0, 512));
    assert_eq!(g.remaining_length, 0.0);
    for id in ids {
        assert_eq!(state_of(&mut e, id), CommandState::Aborted);
    }
}

#[test]
fn tv51_an_override_of_10_or_0_is_refused_and_0_5_halves_the_path_speed() {
    let mut e = machine(2, &[0, 1]);
    for factor in [10.0, 0.0] {
        let err = refused(&mut e, Command::from(GroupSetOverride { group: 1, factor }));
        assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    }
    ok(
        &mut e,
        Command::from(GroupSetOverride {
            group: 1,
            factor: 0.5,
        }),
    );
    send(&mut e, line(1, &[30000.0, 40000.0], 10.0, 1.0));
    let mut fastest: f64 = 0.0;
    run_path(&mut e, 20.0, |_, g| fastest = fastest.max(g.path_velocity));
    assert!((fastest - 5.0 * P_PER_MS).abs() < 1e-6, "{fastest}");
}

#[test]
fn tv54_a_2_s_dwell_between_two_lines() {
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(1, &[5000.0, 0.0], 10.0, 1.0));
    send(
        &mut e,
        GroupDwell {
            group: 1,
            seconds: 2.0,
        },
    );
    send(&mut e, line(2, &[5000.0, 5000.0], 10.0, 1.0));
    let mut standing = 0;
    run_path(&mut e, 10.0, |_, g| {
        if g.position() == [5000.0, 0.0] {
            standing += 1;
        }
    });
    // At the corner for the 2 s dwell, plus the tick of arrival.
    assert!((2000..=2001).contains(&standing), "{standing} ticks");
}
