//! A cam started by a capture channel of its master (HMC_Cam modes 2 and 6, digest 000 §4.3:
//! "event: the capture channel dTrigMes fires (its CaptureAxis must be the cam master);
//! start = the captured MPos"), and the check that every HMC mode 0–7 has its start.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    CamIn, CamInterpolation, CamPoint, CamTableDefine, CaptureArm, CaptureEdge, CaptureSource,
    Command, EngineError, FollowSegment, ForceDigitalInput, MasterSource,
};
use axes::status::CouplingPhase;
use axes::Engine;
use common::{jog_of, ok, refused};

fn machine() -> Engine {
    let mut e = common::enabled_machine(common::virtual_pulse_axis(), 2);
    ok(
        &mut e,
        Command::from(CamTableDefine {
            table: 0,
            points: [(0.0, 0.0), (100.0, 200.0), (200.0, 300.0)]
                .iter()
                .map(|&(master, slave)| CamPoint {
                    master,
                    slave,
                    segment: FollowSegment::Normal,
                })
                .collect(),
            interpolation: CamInterpolation::Linear,
        }),
    );
    e
}

fn cam_on_capture(channel: u8, periodic: bool) -> Command {
    Command::from(CamIn {
        master: 0,
        slave: 1,
        table: 0,
        master_source: MasterSource::Commanded,
        periodic,
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
        start_capture: Some(channel),
    })
}

fn arm(e: &mut Engine, channel: u8) {
    ok(
        e,
        Command::from(CaptureArm {
            axis: 0,
            channel,
            source: CaptureSource::Di,
            input: Some(4),
            source_axis: None,
            edge: CaptureEdge::Rising,
            repeat: 1,
            continuous: false,
            window: None,
        }),
    );
}

fn di(e: &mut Engine, value: bool) {
    ok(
        e,
        Command::from(ForceDigitalInput {
            channel: 4,
            value: Some(value),
        }),
    );
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

fn steps(e: &mut Engine, n: usize) {
    for _ in 0..n {
        e.step();
    }
}

#[test]
fn hmc_mode_2_the_cam_starts_at_the_latched_master_position() {
    let mut e = machine();
    arm(&mut e, 2);
    ok(&mut e, cam_on_capture(2, false));
    ok(&mut e, jog_of(0, 50.0));
    steps(&mut e, 300);
    // Waiting: the slave is coupled but not fed.
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::Waiting);
    assert_eq!(cmd(&e, 1), 0.0);
    di(&mut e, true);
    let latched = e.triggers().capture(0, 2).unwrap().latches[0].cmd_pos;
    assert!(latched > 0.0);
    e.step();
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::InSync);
    // From then on the slave is table(master − latched): slope 2 for the first 100.
    for _ in 0..400 {
        e.step();
        let x = cmd(&e, 0) - latched;
        if x > 100.0 {
            break;
        }
        assert!(
            (cmd(&e, 1) - 2.0 * x).abs() < 1e-9,
            "{} vs {}",
            cmd(&e, 1),
            x
        );
    }
}

#[test]
fn hmc_mode_6_a_latch_from_before_the_cam_does_not_start_it() {
    let mut e = machine();
    arm(&mut e, 5);
    di(&mut e, true);
    assert_eq!(e.triggers().capture(0, 5).unwrap().count, 1);
    ok(&mut e, cam_on_capture(5, true));
    ok(&mut e, jog_of(0, 50.0));
    steps(&mut e, 200);
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::Waiting);
    // Re-armed: the next edge starts the cyclic cam (mode 6) at its latch.
    arm(&mut e, 5);
    di(&mut e, false);
    steps(&mut e, 100);
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::Waiting);
    di(&mut e, true);
    let latched = e.triggers().capture(0, 5).unwrap().latches[0].cmd_pos;
    steps(&mut e, 1);
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::InSync);
    // Cyclic: one period (200 of master) later the slave has risen by the table's 300.
    while cmd(&e, 0) - latched < 250.0 {
        e.step();
    }
    let x = cmd(&e, 0) - latched - 200.0;
    assert!((cmd(&e, 1) - (300.0 + 2.0 * x)).abs() < 1e-9);
}

#[test]
fn a_capture_start_is_checked() {
    let mut e = machine();
    let mut two = cam_on_capture(1, false);
    if let Command::Coupling(axes::command::CouplingCommand::CamIn(c)) = &mut two {
        c.start_input = Some(0);
    }
    assert!(matches!(
        refused(&mut e, two),
        EngineError::InvalidArgument {
            name: "start_capture",
            ..
        }
    ));
    assert!(matches!(
        refused(&mut e, cam_on_capture(8, false)),
        EngineError::InvalidArgument {
            name: "start_capture",
            ..
        }
    ));
    assert!(e.snapshot().couplings.is_empty());
}

#[test]
fn start_capture_is_pinned_in_json() {
    common::assert_pinned(vec![(
        cam_on_capture(3, false),
        r#"{"type":"cam_in","master":0,"slave":1,"table":0,"master_source":"commanded","start_capture":3}"#,
    )]);
}
