//! Data sampling (issue 12 item 9): HMC sampling (digest 000 §4.4, TV 33–34) and NMC data
//! collection (digest 001 §3.19, S-COLLECT): chosen variables, every N periods, after a trigger,
//! into a bounded buffer read with `sampling_read`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, Enable, Reply};
use axes::config::IoConfig;
use axes::sampling::SamplerState;
use axes::{Engine, EngineConfig, EngineError, ParamId};
use common::{cmd, free_linear_axis, ok, refused, run};

/// One pulse axis per unit, 1 ms period, 4 DI and 4 DO.
fn machine() -> Engine {
    let axis = free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, 2000.0),
            (ParamId::Accel, 1e9),
            (ParamId::Decel, 1e9),
        ],
    );
    let mut e = Engine::new(&EngineConfig {
        axes: vec![axis],
        io: IoConfig {
            digital_inputs: 4,
            digital_outputs: 4,
            ..IoConfig::default()
        },
        ..EngineConfig::default()
    })
    .unwrap();
    ok(&mut e, Command::from(Enable { axis: 0 }));
    e
}

fn read(e: &mut Engine, sampler: u16) -> (u32, Vec<f64>) {
    match ok(
        e,
        cmd(&format!(
            r#"{{"type":"sampling_read","sampler":{sampler}}}"#
        )),
    ) {
        Reply::Samples {
            variables, values, ..
        } => (variables, values),
        other => panic!("{other:?}"),
    }
}

/// TV 33: at 2000 units/s and a 1 ms period, samples every period differ by 2 and samples
/// every 10 periods by 20; with 4 sub-channels × 3000 points, 12000 values. TV 34: sub-channel
/// 2 of sample 5 is value 5·4 + 2 (byte offset 176 in the HMC record area).
#[test]
fn hmc_sampling_deltas_tv33_and_layout_tv34() {
    let mut e = machine();
    ok(
        &mut e,
        cmd(r#"{"type":"move_velocity","axis":0,"velocity":2000}"#),
    );
    run(&mut e, 0.01); // at speed
    let four = r#"[{"kind":"actual_position","axis":0},{"kind":"planned_position","axis":0},
                   {"kind":"planned_velocity","axis":0},{"kind":"output_position","axis":0}]"#;
    for (sampler, interval) in [(0, 1), (1, 10)] {
        ok(
            &mut e,
            cmd(&format!(
                r#"{{"type":"sampling_configure","sampler":{sampler},"variables":{four},
                    "interval":{interval},"points":3000,"trigger":{{"kind":"command"}}}}"#
            )),
        );
        ok(
            &mut e,
            cmd(&format!(
                r#"{{"type":"sampling_start","sampler":{sampler}}}"#
            )),
        );
        ok(
            &mut e,
            cmd(&format!(
                r#"{{"type":"sampling_trigger","sampler":{sampler}}}"#
            )),
        );
    }
    run(&mut e, 31.0);
    for (sampler, delta) in [(0, 2.0), (1, 20.0)] {
        let (k, values) = read(&mut e, sampler);
        assert_eq!(k, 4);
        assert_eq!(values.len(), 12_000, "GetSampleNum = 4 · 3000");
        for n in 1..3000 {
            let d = values[n * 4] - values[(n - 1) * 4];
            assert!(
                (d - delta).abs() < 1e-6,
                "sampler {sampler} sample {n}: {d}"
            );
        }
        // TV 34: value n·4 + i is sub-channel i of sample n.
        assert_eq!(values[5 * 4 + 2], 2000.0, "sub-channel 2 is the velocity");
        assert_eq!(5 * 4 * 8 + 2 * 8, 176);
    }
    let snap = e.snapshot();
    assert_eq!(snap.samplers.len(), 2);
    assert_eq!(snap.samplers[0].state, SamplerState::Done);
    assert_eq!(
        (snap.samplers[1].points, snap.samplers[1].capacity),
        (3000, 3000)
    );
}

/// S-COLLECT: planned position and planned velocity of axis 0, interval 0 (every period),
/// no trigger; start; a point-to-point move to 10000; stop; read.
#[test]
fn nmc_collect_s_collect() {
    let mut e = machine();
    ok(
        &mut e,
        cmd(
            r#"{"type":"sampling_configure","sampler":0,"interval":0,"points":100000,
                "variables":[{"kind":"planned_position","axis":0},{"kind":"planned_velocity","axis":0}]}"#,
        ),
    );
    ok(&mut e, cmd(r#"{"type":"sampling_start","sampler":0}"#));
    ok(
        &mut e,
        cmd(
            r#"{"type":"move_absolute","axis":0,"position":10000,"velocity":1000,"acceleration":10000,"deceleration":10000}"#,
        ),
    );
    run(&mut e, 12.0);
    ok(&mut e, cmd(r#"{"type":"sampling_stop","sampler":0}"#));
    let snap = e.snapshot();
    assert_eq!(snap.samplers[0].state, SamplerState::Stopped);
    assert_eq!(snap.samplers[0].points, 12_000);
    let (k, values) = read(&mut e, 0);
    assert_eq!(k, 2);
    let rows: Vec<&[f64]> = values.chunks(2).collect();
    assert!(rows.windows(2).all(|w| w[1][0] >= w[0][0]), "monotonic");
    assert_eq!(rows.last().unwrap()[0], 10_000.0);
    let vmax = rows.iter().map(|r| r[1]).fold(0.0, f64::max);
    assert!((vmax - 1000.0).abs() < 1e-6, "{vmax}");
    // Reading a window: rows 100 … 102.
    match ok(
        &mut e,
        cmd(r#"{"type":"sampling_read","sampler":0,"from":100,"count":3}"#),
    ) {
        Reply::Samples {
            from, values: w, ..
        } => {
            assert_eq!(from, 100);
            assert_eq!(w, values[200..206].to_vec());
        }
        other => panic!("{other:?}"),
    }
}

/// Triggers on a level or an edge of a chosen variable: a rising edge of the planned position
/// through 500, and a digital input going high.
#[test]
fn edge_and_level_triggers() {
    let mut e = machine();
    ok(
        &mut e,
        cmd(r#"{"type":"sampling_configure","sampler":0,"points":5,
                "variables":[{"kind":"planned_position","axis":0}],
                "trigger":{"kind":"rising","variable":{"kind":"planned_position","axis":0},"value":500}}"#),
    );
    ok(
        &mut e,
        cmd(r#"{"type":"sampling_configure","sampler":1,"points":3,
                "variables":[{"kind":"digital_input","channel":2},{"kind":"planned_position","axis":0}],
                "trigger":{"kind":"above","variable":{"kind":"digital_input","channel":2},"value":1}}"#),
    );
    for s in 0..2 {
        ok(
            &mut e,
            cmd(&format!(r#"{{"type":"sampling_start","sampler":{s}}}"#)),
        );
    }
    ok(
        &mut e,
        cmd(r#"{"type":"move_velocity","axis":0,"velocity":2000}"#),
    );
    run(&mut e, 1.0);
    let (_, v) = read(&mut e, 0);
    assert_eq!(v.len(), 5);
    assert!(
        v[0] >= 500.0 && v[0] < 502.0 + 1e-9,
        "first sample at the crossing: {v:?}"
    );
    let (_, v) = read(&mut e, 1);
    assert!(v.is_empty(), "DI 2 still low");
    ok(
        &mut e,
        cmd(r#"{"type":"force_digital_input","channel":2,"value":true}"#),
    );
    run(&mut e, 0.01);
    let (_, v) = read(&mut e, 1);
    assert_eq!(v.len(), 6);
    assert_eq!((v[0], v[2], v[4]), (1.0, 1.0, 1.0));
}

#[test]
fn deterministic() {
    let once = || {
        let mut e = machine();
        ok(
            &mut e,
            cmd(
                r#"{"type":"sampling_configure","sampler":3,"interval":3,"points":200,
                    "variables":[{"kind":"actual_velocity","axis":0},{"kind":"following_error","axis":0}]}"#,
            ),
        );
        ok(&mut e, cmd(r#"{"type":"sampling_start","sampler":3}"#));
        ok(
            &mut e,
            cmd(r#"{"type":"move_absolute","axis":0,"position":300}"#),
        );
        run(&mut e, 1.0);
        read(&mut e, 3)
            .1
            .iter()
            .map(|v| v.to_bits())
            .collect::<Vec<_>>()
    };
    assert_eq!(once(), once());
}

#[test]
fn bad_input_is_typed() {
    let mut e = machine();
    let sampling = |err: EngineError| match err {
        EngineError::InvalidSampling { sampler, reason } => (sampler, reason),
        other => panic!("{other:?}"),
    };
    let nine: Vec<String> = (0..9)
        .map(|_| r#"{"kind":"planned_position","axis":0}"#.to_string())
        .collect();
    let (_, r) = sampling(refused(
        &mut e,
        cmd(&format!(
            r#"{{"type":"sampling_configure","sampler":0,"points":10,"variables":[{}]}}"#,
            nine.join(",")
        )),
    ));
    assert!(r.contains("1 to 8 variables"), "{r}");
    let (s, _) = sampling(refused(
        &mut e,
        cmd(
            r#"{"type":"sampling_configure","sampler":4,"points":1,"variables":[{"kind":"planned_position","axis":0}]}"#,
        ),
    ));
    assert_eq!(s, 4);
    assert!(matches!(
        refused(
            &mut e,
            cmd(
                r#"{"type":"sampling_configure","sampler":0,"points":1,"variables":[{"kind":"planned_position","axis":3}]}"#
            )
        ),
        EngineError::InvalidAxis { axis: 3, count: 1 }
    ));
    assert!(matches!(
        refused(
            &mut e,
            cmd(
                r#"{"type":"sampling_configure","sampler":0,"points":1,"variables":[{"kind":"digital_output","channel":9}]}"#
            )
        ),
        EngineError::InvalidChannel { channel: 9, .. }
    ));
    let (_, r) = sampling(refused(
        &mut e,
        cmd(
            r#"{"type":"sampling_configure","sampler":0,"points":900000,"variables":[{"kind":"planned_position","axis":0},{"kind":"planned_velocity","axis":0}]}"#,
        ),
    ));
    assert!(r.contains("more than 1000000 values"), "{r}");
    let (_, r) = sampling(refused(
        &mut e,
        cmd(r#"{"type":"sampling_start","sampler":1}"#),
    ));
    assert!(r.contains("not configured"), "{r}");
    let (_, r) = sampling(refused(
        &mut e,
        cmd(r#"{"type":"sampling_trigger","sampler":1}"#),
    ));
    assert!(r.contains("not armed"), "{r}");
    // The engine keeps running.
    ok(
        &mut e,
        cmd(r#"{"type":"move_absolute","axis":0,"position":10}"#),
    );
    run(&mut e, 1.0);
    assert_eq!(e.axis_status(0).unwrap().cmd_pos, 10.0);
}

/// NMC COLLECT_ADDRESS_CRD_POS/CRD_VEL: a group's coordinates and path velocity, recorded
/// `delay` periods after the trigger (TCollectTrig startDelay).
#[test]
fn group_coordinates_and_path_velocity_after_a_start_delay() {
    let mut e = common::with_group(
        Engine::new(&EngineConfig {
            axes: (0..2).map(|_| common::stepper_mm()).collect(),
            ..EngineConfig::default()
        })
        .unwrap(),
        &[0, 1],
    );
    ok(
        &mut e,
        cmd(
            r#"{"type":"sampling_configure","sampler":3,"points":1000,"delay":20,
                "variables":[{"kind":"group_coordinate","group":1,"coordinate":1},
                             {"kind":"group_velocity","group":1}]}"#,
        ),
    );
    ok(&mut e, cmd(r#"{"type":"sampling_start","sampler":3}"#));
    ok(&mut e, common::group_line(1, &[30.0, 40.0]).into());
    let start = e.tick();
    let mut seen = Vec::new();
    for _ in 0..40 {
        e.step();
        let g = e.snapshot().groups[0];
        seen.push((g.coordinates[1], g.path_velocity));
    }
    let s = e.snapshot().samplers[0].clone();
    assert_eq!(s.triggered_at, Some(start + 1 + 20), "{s:?}");
    let (variables, values) = read(&mut e, 3);
    assert_eq!(variables, 2);
    assert_eq!(values.len(), 2 * 20);
    // Sample 0 is the state the 21st tick left.
    for (k, row) in values.chunks(2).enumerate() {
        let (y, v) = seen[20 + k];
        assert_eq!(row, [y, v], "sample {k}");
    }
    assert!(values[values.len() - 2] > 0.0 && values[values.len() - 1] > 0.0);
    let err = refused(
        &mut e,
        cmd(r#"{"type":"sampling_configure","sampler":3,"points":10,
                "variables":[{"kind":"group_coordinate","group":1,"coordinate":2}]}"#),
    );
    assert!(
        matches!(err, EngineError::InvalidGroup { group: 1, .. }),
        "{err:?}"
    );
    let err = refused(
        &mut e,
        cmd(r#"{"type":"sampling_configure","sampler":3,"points":10,
                "variables":[{"kind":"group_velocity","group":7}]}"#),
    );
    assert!(
        matches!(err, EngineError::UnknownGroup { group: 7 }),
        "{err:?}"
    );
}
