//! Cams at the engine level (issue 12 item 2): NMC S-FOLLOW / TV 59 (digest 001 §2.17, §4.7),
//! HMC single and cyclic cams and the spline cam (digest 000 §4.3, §8.3 TV 25–27), start on a
//! master position and on a DI, absolute master and slave with offsets and scaling (PLCopen
//! MC_CamIn), loop counts, bad tables, and the property that the slave lies on its table.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    CamIn, CamInterpolation, CamOut, CamPoint, CamTableDefine, CamTableLink, Command, Direction,
    EngineError, FollowSegment, ForceDigitalInput, MasterSource,
};
use axes::coupling::table::CamTable;
use axes::status::{CouplingKind, CouplingPhase};
use axes::{AxisFlags, AxisState, Engine};
use common::{jog_of, move_rel_of, ok, refused};
use proptest::prelude::*;

fn machine(n: usize) -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), n)
}

fn points(p: &[(f64, f64)]) -> Vec<CamPoint> {
    p.iter()
        .map(|&(master, slave)| CamPoint {
            master,
            slave,
            segment: FollowSegment::Normal,
        })
        .collect()
}

fn table(e: &mut Engine, id: u16, p: &[(f64, f64)], interpolation: CamInterpolation) {
    ok(
        e,
        Command::from(CamTableDefine {
            table: id,
            points: points(p),
            interpolation,
        }),
    );
}

fn cam(master: u16, slave: u16, table: u16) -> CamIn {
    CamIn {
        master,
        slave,
        table,
        master_source: MasterSource::Commanded,
        periodic: false,
        loop_count: 0,
        master_absolute: false,
        slave_absolute: false,
        master_offset: 0.0,
        slave_offset: 0.0,
        master_scaling: 1.0,
        slave_scaling: 1.0,
        start_position: None,
        start_direction: None,
        start_input: None,
        start_capture: None,
    }
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

/// Move the master (axis 0) by `d` and let it stop.
fn master_by(e: &mut Engine, d: f64) {
    ok(e, move_rel_of(0, d));
    for _ in 0..5000 {
        e.step();
        if !e.axis_status(0).unwrap().flags.contains(AxisFlags::MOVING) {
            return;
        }
    }
    panic!("master still moving");
}

#[test]
fn s_follow_starts_when_the_master_passes_50000_and_repeats_every_60000_tv59() {
    // S-FOLLOW: master axis 0 jogs positive; slave axis 1 follows FIFO 0 = (20000, 10000),
    // (40000, 30000), (60000, 40000) from the start point, NORMAL segments, loop count 0
    // (for ever), event 2: start when the master crosses 50000 moving positive.
    let mut e = machine(2);
    let mut p = points(&[
        (0.0, 0.0),
        (20_000.0, 10_000.0),
        (40_000.0, 30_000.0),
        (60_000.0, 40_000.0),
    ]);
    p[3].segment = FollowSegment::Normal;
    ok(
        &mut e,
        Command::from(CamTableDefine {
            table: 0,
            points: p,
            interpolation: CamInterpolation::Follow,
        }),
    );
    ok(
        &mut e,
        Command::from(CamIn {
            periodic: true,
            start_position: Some(50_000.0),
            start_direction: Some(Direction::Positive),
            ..cam(0, 1, 0)
        }),
    );
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::Waiting);
    assert!(e.axis_status(1).unwrap().flags.contains(AxisFlags::COUPLED));
    // 50 pulses per 1 ms tick, as MtMoveJog(…, 50, …).
    ok(&mut e, jog_of(0, 50_000.0));
    let mut k = 1;
    for _ in 0..10_000 {
        e.step();
        let (m, s) = (cmd(&e, 0), cmd(&e, 1));
        if m < 50_000.0 {
            assert_eq!(s, 0.0, "slave moved before the start at master {m}");
            continue;
        }
        let at = 50_000.0 + 60_000.0 * k as f64;
        if m >= at {
            // The ratio is 0 at each period's start: the slave is within a rounding of 40000·k
            // plus the quadratic start of the next period (≤ 0.5/20000 · 50²).
            assert!((s - 40_000.0 * k as f64).abs() < 0.07, "k {k}: slave {s}");
            k += 1;
        }
    }
    assert!(k > 5, "{k}");
    let c = e.snapshot().couplings[0];
    assert_eq!(
        (c.kind, c.phase),
        (CouplingKind::Cam, CouplingPhase::InSync)
    );
    assert!(c.cycle >= 5);
    assert_eq!(
        e.axis_status(1).unwrap().state,
        AxisState::SynchronizedMotion
    );
}

#[test]
fn hmc_single_cam_back_and_forth_inside_the_table_tv25() {
    // Digest 000 TV 25: 45° table (0,0),(500,500),(1000,1000), single cam, immediate.
    let mut e = machine(2);
    table(
        &mut e,
        1,
        &[(0.0, 0.0), (500.0, 500.0), (1000.0, 1000.0)],
        CamInterpolation::Linear,
    );
    ok(&mut e, Command::from(cam(0, 1, 1)));
    for (d, want) in [
        (800.0, 800.0),
        (-600.0, 200.0),
        (600.0, 800.0),
        (-600.0, 200.0),
        (600.0, 800.0),
    ] {
        master_by(&mut e, d);
        assert!((cmd(&e, 1) - want).abs() < 1e-9, "{}", cmd(&e, 1));
    }
    assert_eq!(e.snapshot().couplings.len(), 1);
    // Leaving the table cancels the cam; the slave stands at the table's end.
    master_by(&mut e, 300.0);
    assert!(e.snapshot().couplings.is_empty());
    assert!((cmd(&e, 1) - 1000.0).abs() < 1e-9, "{}", cmd(&e, 1));
    assert!(!e.axis_status(1).unwrap().flags.contains(AxisFlags::COUPLED));
}

#[test]
fn hmc_cyclic_cam_starts_each_period_where_the_last_ended_tv26() {
    let mut e = machine(2);
    table(
        &mut e,
        1,
        &[(0.0, 0.0), (500.0, 500.0), (1000.0, 1000.0)],
        CamInterpolation::Linear,
    );
    ok(
        &mut e,
        Command::from(CamIn {
            periodic: true,
            ..cam(0, 1, 1)
        }),
    );
    for (d, want) in [
        (4000.0, 4000.0),
        (-6000.0, -2000.0),
        (6000.0, 4000.0),
        (-4000.0, 0.0),
    ] {
        master_by(&mut e, d);
        assert!((cmd(&e, 1) - want).abs() < 1e-9, "{}", cmd(&e, 1));
    }
}

#[test]
fn hmc_spline_cam_of_a_sine_period_tv27() {
    // Digest 000 TV 27: x = (2π/100·n)·150, y = sin(2π/100·n)·1000, n = 0..100; Delta =
    // 942.4778; the slave is +1000 at master ≈ 235.62.
    let mut e = machine(2);
    let delta = std::f64::consts::PI * 2.0 / 100.0;
    let p: Vec<(f64, f64)> = (0..=100)
        .map(|n| (delta * n as f64 * 150.0, (delta * n as f64).sin() * 1000.0))
        .collect();
    table(&mut e, 2, &p, CamInterpolation::Cubic);
    let (x0, x1) = e.couplings().table(2).unwrap().master_range();
    assert!((x1 - x0 - 942.4778).abs() < 1e-4);
    ok(&mut e, Command::from(cam(0, 1, 2)));
    master_by(&mut e, 235.619_449);
    assert!((cmd(&e, 1) - 1000.0).abs() < 1e-3, "{}", cmd(&e, 1));
    assert!((24..=25).contains(&e.snapshot().couplings[0].table_index));
    // Past start + Delta a single cam is cancelled.
    master_by(&mut e, 800.0);
    assert!(e.snapshot().couplings.is_empty());
}

#[test]
fn a_cam_started_by_a_digital_input_starts_at_the_master_position_of_that_tick() {
    let mut e = machine(2);
    table(
        &mut e,
        0,
        &[(0.0, 0.0), (100.0, 200.0)],
        CamInterpolation::Linear,
    );
    ok(
        &mut e,
        Command::from(CamIn {
            start_input: Some(3),
            start_capture: None,
            ..cam(0, 1, 0)
        }),
    );
    master_by(&mut e, 50.0);
    assert_eq!(cmd(&e, 1), 0.0);
    ok(
        &mut e,
        Command::from(ForceDigitalInput {
            channel: 3,
            value: Some(true),
        }),
    );
    e.step();
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::InSync);
    master_by(&mut e, 40.0);
    assert!((cmd(&e, 1) - 80.0).abs() < 1e-9, "{}", cmd(&e, 1));
}

#[test]
fn absolute_master_and_slave_with_offsets_and_scaling() {
    // PLCopen MC_CamIn: x = (master − master_offset) / master_scaling, slave = slave_scaling ·
    // table(x) + slave_offset.
    let mut e = machine(2);
    table(
        &mut e,
        0,
        &[(0.0, 0.0), (10.0, 10.0), (20.0, 40.0)],
        CamInterpolation::Linear,
    );
    master_by(&mut e, 30.0);
    ok(
        &mut e,
        Command::from(CamIn {
            master_absolute: true,
            slave_absolute: true,
            master_offset: 20.0,
            master_scaling: 2.0,
            slave_offset: 5.0,
            slave_scaling: 3.0,
            ..cam(0, 1, 0)
        }),
    );
    e.step();
    // x = (30 − 20) / 2 = 5 → table 5 → 3·5 + 5 = 20.
    assert!((cmd(&e, 1) - 20.0).abs() < 1e-9, "{}", cmd(&e, 1));
    master_by(&mut e, 20.0);
    // x = 15 → 25 → 80.
    assert!((cmd(&e, 1) - 80.0).abs() < 1e-9, "{}", cmd(&e, 1));
}

#[test]
fn a_periodic_cam_with_a_loop_count_ends_exactly_at_its_last_period() {
    let mut e = machine(2);
    table(
        &mut e,
        0,
        &[(0.0, 0.0), (100.0, 50.0)],
        CamInterpolation::Linear,
    );
    ok(
        &mut e,
        Command::from(CamIn {
            periodic: true,
            loop_count: 2,
            ..cam(0, 1, 0)
        }),
    );
    master_by(&mut e, 333.0);
    assert!(e.snapshot().couplings.is_empty());
    assert_eq!(cmd(&e, 1), 100.0);
    assert_eq!(e.axis_status(1).unwrap().state, AxisState::Standstill);
}

#[test]
fn cam_out_frees_the_slave() {
    let mut e = machine(2);
    table(
        &mut e,
        0,
        &[(0.0, 0.0), (100.0, 50.0)],
        CamInterpolation::Linear,
    );
    ok(&mut e, Command::from(cam(0, 1, 0)));
    assert_eq!(
        refused(&mut e, move_rel_of(1, 1.0)),
        EngineError::AxisCoupled { axis: 1, master: 0 }
    );
    ok(&mut e, Command::from(CamOut { slave: 1 }));
    ok(&mut e, move_rel_of(1, 1.0));
}

#[test]
fn bad_tables_and_cams_are_refused_naming_what_is_wrong() {
    let mut e = machine(3);
    let one = refused(
        &mut e,
        Command::from(CamTableDefine {
            table: 4,
            points: points(&[(0.0, 0.0)]),
            interpolation: CamInterpolation::Linear,
        }),
    );
    assert!(
        matches!(one, EngineError::InvalidCamTable { table: 4, ref reason } if reason.contains("at least 2")),
        "{one}"
    );
    let back = refused(
        &mut e,
        Command::from(CamTableDefine {
            table: 4,
            points: points(&[(0.0, 0.0), (5.0, 1.0), (5.0, 2.0)]),
            interpolation: CamInterpolation::Cubic,
        }),
    );
    assert!(back.to_string().contains("must increase"), "{back}");
    assert_eq!(
        refused(&mut e, Command::from(cam(0, 1, 9))),
        EngineError::UnknownCamTable { table: 9 }
    );
    table(
        &mut e,
        0,
        &[(0.0, 0.0), (1.0, 1.0)],
        CamInterpolation::Linear,
    );
    assert_eq!(
        refused(&mut e, Command::from(cam(1, 1, 0))),
        EngineError::CoupledToItself { axis: 1 }
    );
    assert!(matches!(
        refused(
            &mut e,
            Command::from(CamIn {
                master_scaling: 0.0,
                ..cam(0, 1, 0)
            })
        ),
        EngineError::InvalidArgument {
            name: "master_scaling",
            ..
        }
    ));
    assert!(matches!(
        refused(
            &mut e,
            Command::from(CamIn {
                start_input: Some(999),
                start_capture: None,
                ..cam(0, 1, 0)
            })
        ),
        EngineError::InvalidChannel { channel: 999, .. }
    ));
    ok(&mut e, Command::from(cam(0, 1, 0)));
    assert_eq!(
        refused(
            &mut e,
            Command::from(CamTableDefine {
                table: 0,
                points: points(&[(0.0, 0.0), (2.0, 1.0)]),
                interpolation: CamInterpolation::Linear,
            })
        ),
        EngineError::CamTableInUse { table: 0, slave: 1 }
    );
    assert_eq!(
        refused(&mut e, Command::from(cam(1, 0, 0))),
        EngineError::CouplingLoop {
            slave: 0,
            master: 1
        }
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// At every tick the slave is exactly where the table puts it for the master's position.
    #[test]
    fn a_cam_slave_lies_on_its_table_at_every_master_position(
        steps in prop::collection::vec((0.1f64..50.0, -20.0f64..20.0), 2..12),
        cubic in any::<bool>(),
        periodic in any::<bool>(),
        moves in prop::collection::vec(-300.0f64..300.0, 1..4),
    ) {
        let mut x = 0.0;
        let p: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
            .chain(steps.iter().map(|&(dx, y)| { x += dx; (x, y) }))
            .collect();
        let interpolation = if cubic { CamInterpolation::Cubic } else { CamInterpolation::Linear };
        let model = CamTable::new(0, &points(&p), interpolation).unwrap();
        let (x0, x1) = model.master_range();
        let (y0, y1) = model.slave_range();
        let mut e = machine(2);
        table(&mut e, 0, &p, interpolation);
        ok(&mut e, Command::from(CamIn { periodic, ..cam(0, 1, 0) }));
        for d in moves {
            ok(&mut e, move_rel_of(0, d));
            for _ in 0..2000 {
                e.step();
                if e.snapshot().couplings.is_empty() {
                    return Ok(());
                }
                let m = cmd(&e, 0);
                let want = if periodic {
                    let k = ((m - x0) / (x1 - x0)).floor();
                    model.sample(m - k * (x1 - x0)).y + k * (y1 - y0)
                } else {
                    model.sample(m).y
                };
                prop_assert!((cmd(&e, 1) - want).abs() <= 1e-9 * (1.0 + want.abs()),
                    "master {} slave {} table {}", m, cmd(&e, 1), want);
                if !e.axis_status(0).unwrap().flags.contains(AxisFlags::MOVING) {
                    break;
                }
            }
        }
    }
}

#[test]
fn hmc_move_link_cyclic_from_a_link_table_tv28() {
    // HMC_MoveLink(500, 1000, 200, 200, 0, 1, 0, 4, 0) (manual §4.3.6.7, cyclic immediate): per
    // 1000 of master the slave travels 500, its ratio ramping 0 → 0.625 over 200 and back over
    // the last 200. A cam on the link table, relative and periodic.
    let mut e = machine(2);
    let link = CamTableLink {
        table: 3,
        slave_distance: 500.0,
        master_distance: 1000.0,
        master_acceleration_distance: 200.0,
        master_deceleration_distance: 200.0,
        s_ratio: 0.0,
        slave_base_distance: 0.0,
        master_before_distance: 0.0,
        master_after_distance: 0.0,
    };
    ok(&mut e, Command::from(link.clone()));
    ok(
        &mut e,
        Command::from(CamIn {
            periodic: true,
            ..cam(0, 1, 3)
        }),
    );
    for (d, want) in [(1000.0, 500.0), (2500.0, 1750.0), (-500.0, 1500.0)] {
        master_by(&mut e, d);
        assert!((cmd(&e, 1) - want).abs() < 1e-9, "{}", cmd(&e, 1));
    }
    // A table a running cam uses is not replaced; accelerating and decelerating beyond the
    // master distance is refused (TV 28: 600 + 500 > 1000).
    let err = refused(&mut e, Command::from(link.clone()));
    assert!(
        matches!(err, EngineError::CamTableInUse { table: 3, .. }),
        "{err}"
    );
    let err = refused(
        &mut e,
        Command::from(CamTableLink {
            table: 4,
            master_acceleration_distance: 600.0,
            master_deceleration_distance: 500.0,
            ..link
        }),
    );
    assert!(
        matches!(err, EngineError::InvalidCamTable { table: 4, .. }),
        "{err}"
    );
}
