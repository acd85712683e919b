//! `estimate_group_time` (NMC `_NMC_CrdGetExeTime`): a dry run of the engine gives the ticks a
//! path takes, equal to the ticks running it takes, and leaves the engine as it was.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    ArcDirection, Command, EstimateGroupTime, GroupBufferMode, GroupDwell, Reply, TransitionMode,
};
use axes::status::GroupState;
use axes::{Engine, EngineConfig, EngineError};
use common::{ok, refused, stepper_mm};

fn machine() -> Engine {
    let e = Engine::new(&EngineConfig {
        axes: (0..3).map(|_| stepper_mm()).collect(),
        ..EngineConfig::default()
    })
    .unwrap();
    common::with_group(e, &[0, 1])
}

/// Lines blended into each other and into arcs, a dwell, then an exact stop and an arc.
fn program() -> Vec<Command> {
    let blended = |mut m: axes::command::MoveLinearAbsolute| {
        m.buffer_mode = GroupBufferMode::BlendingLow;
        m.transition = TransitionMode::CornerDistance(2.0);
        m
    };
    let mut arc = common::group_arc(1, &[30.0, 10.0], &[30.0, 20.0], ArcDirection::Ccw);
    arc.buffer_mode = GroupBufferMode::BlendingPrevious;
    vec![
        common::group_line(1, &[20.0, 0.0]).into(),
        blended(common::group_line(1, &[30.0, 0.0])).into(),
        arc.into(),
        blended(common::group_line(1, &[0.0, 20.0])).into(),
        GroupDwell {
            group: 1,
            seconds: 0.05,
        }
        .into(),
        common::group_line(1, &[0.0, 0.0]).into(),
        common::group_arc(1, &[5.0, 0.0], &[10.0, 0.0], ArcDirection::Cw).into(),
    ]
}

fn estimate(e: &mut Engine, commands: Vec<Command>) -> Result<u64, EngineError> {
    let reply = e.apply(EstimateGroupTime { group: 1, commands }.into())?;
    match reply {
        Reply::Value { value } => Ok(value as u64),
        other => panic!("{other:?}"),
    }
}

/// Steps until group 1 is back in Standby.
fn run(e: &mut Engine) -> u64 {
    for k in 1..=1_000_000 {
        e.step();
        if e.snapshot().groups[0].state == GroupState::Standby {
            return k;
        }
    }
    panic!("the path did not end");
}

#[test]
fn the_estimate_is_the_ticks_running_the_path_takes() {
    let mut e = machine();
    let ticks = estimate(&mut e, program()).unwrap();
    // Blends, arcs and a dwell: a closed form would not land on the tick.
    assert!(ticks > 1000, "{ticks}");
    for c in program() {
        ok(&mut e, c);
    }
    assert_eq!(run(&mut e), ticks);
}

#[test]
fn an_estimate_leaves_the_engine_as_it_was() {
    let mut with = machine();
    let mut without = machine();
    common::run(&mut with, 0.01);
    common::run(&mut without, 0.01);
    let before = with.snapshot();
    estimate(&mut with, program()).unwrap();
    assert_eq!(with.snapshot(), before);
    // And the next ticks are those of an engine that never saw it.
    for c in program() {
        let a = with.apply(c.clone()).unwrap();
        let b = without.apply(c).unwrap();
        assert_eq!(a, b, "command ids");
    }
    for _ in 0..500 {
        with.step();
        without.step();
        assert_eq!(with.snapshot(), without.snapshot());
    }
}

#[test]
fn an_estimate_while_moving_counts_the_path_already_running() {
    let mut e = machine();
    ok(&mut e, common::group_line(1, &[20.0, 0.0]).into());
    common::run(&mut e, 0.05);
    let rest = estimate(&mut e, Vec::new()).unwrap();
    let more = estimate(&mut e, vec![common::group_line(1, &[20.0, 20.0]).into()]).unwrap();
    assert!(rest > 0 && more > rest, "{rest} {more}");
    ok(&mut e, common::group_line(1, &[20.0, 20.0]).into());
    assert_eq!(run(&mut e), more);
}

#[test]
fn a_refused_command_or_an_unknown_group_is_an_error_and_changes_nothing() {
    let mut e = machine();
    let before = e.snapshot();
    let mut far = common::group_line(1, &[1e6, 0.0]);
    far.velocity = Some(-1.0);
    let err = estimate(&mut e, vec![far.into()]).unwrap_err();
    assert!(matches!(err, EngineError::Item { .. }), "{err:?}");
    assert_eq!(e.snapshot(), before);
    let err = refused(
        &mut e,
        EstimateGroupTime {
            group: 9,
            commands: Vec::new(),
        }
        .into(),
    );
    assert!(
        matches!(err, EngineError::UnknownGroup { group: 9 }),
        "{err:?}"
    );
    // Samplers are not put back after a dry run: no sampling command in one.
    let err = estimate(
        &mut e,
        vec![axes::command::SamplingStart { sampler: 0 }.into()],
    )
    .unwrap_err();
    assert!(matches!(err, EngineError::Item { .. }), "{err:?}");
    assert_eq!(e.snapshot(), before);
}
