//! Compensation after the planner (issue 12 item 8): NMC lead screw, backlash (TV 72) and 2-D
//! tables (digest 001 §2.19, S-LEADSCREW, S-BACKLASH, S-2DCOMP), HIMC 1/2/3-D tables (digest
//! 004 §2.13, TV 61). The planned position never includes the correction; the output does.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{BacklashDirection, Command, Enable};
use axes::{Engine, EngineError, ParamId};
use common::{cmd, engine_with, free_linear_axis, ok, refused, run};

/// Pulse axes (1 pulse per unit) that move fast enough for the NMC examples' pulse distances.
fn machine(n: usize) -> Engine {
    let axis = free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, 100_000.0),
            (ParamId::Accel, 1_000_000.0),
            (ParamId::Decel, 1_000_000.0),
        ],
    );
    let mut e = engine_with(vec![axis; n]);
    for i in 0..n {
        ok(&mut e, Command::from(Enable { axis: i as u16 }));
    }
    e
}

fn move_to(e: &mut Engine, axis: u16, position: f64) {
    ok(
        e,
        cmd(&format!(
            r#"{{"type":"move_absolute","axis":{axis},"position":{position}}}"#
        )),
    );
}

fn settle(e: &mut Engine) {
    run(e, 2.0);
}

/// S-LEADSCREW: `MtSetLeadScrewCompPara(ax,3,10000,20000,{10,20,-10},{5,-5,5})`: points at
/// 10000, 20000, 30000; positive table while moving positive, negative while moving negative.
#[test]
fn lead_screw_per_direction_s_leadscrew() {
    let mut e = machine(1);
    ok(
        &mut e,
        cmd(r#"{"type":"compensation_lead_screw","axis":0,
                "positions":[10000,20000,30000],"positive":[10,20,-10],"negative":[5,-5,5]}"#),
    );
    move_to(&mut e, 0, 15_000.0);
    settle(&mut e);
    let s = e.axis_status(0).unwrap();
    assert_eq!(s.cmd_pos, 15_000.0, "planned position has no correction");
    assert_eq!(s.compensation, 15.0, "halfway between 10 and 20");
    assert_eq!(s.output_pos, 15_015.0);
    // Moving back: the negative table (5 → −5 halfway is 0 at 15000; at 12500 it is 2.5).
    move_to(&mut e, 0, 12_500.0);
    settle(&mut e);
    let s = e.axis_status(0).unwrap();
    assert_eq!(s.compensation, 2.5);
    assert_eq!(s.output_pos, 12_502.5);
    // Beyond the table the end value is held (digest 004 §2.13).
    move_to(&mut e, 0, 40_000.0);
    settle(&mut e);
    assert_eq!(e.axis_status(0).unwrap().compensation, -10.0);
    // Disabled: the output is the planned position again.
    ok(&mut e, cmd(r#"{"type":"compensation_disable","axis":0}"#));
    e.step();
    let s = e.axis_status(0).unwrap();
    assert_eq!((s.compensation, s.output_pos), (0.0, 40_000.0));
}

/// TV 72 / S-BACKLASH: `MtSetBacklash(ax,1000,200,1)` reads back as (1000, 200, 1); on a
/// reversal into negative the output leaves the planned position by 1000 over 5 periods.
#[test]
fn backlash_tv72() {
    let mut e = machine(1);
    ok(
        &mut e,
        cmd(
            r#"{"type":"compensation_backlash","axis":0,"amount":1000,"step":200,"direction":"negative"}"#,
        ),
    );
    let setting = e
        .axis(0)
        .unwrap()
        .compensation_status()
        .backlash_setting
        .unwrap();
    assert_eq!(setting, (1000.0, 200.0, BacklashDirection::Negative));
    // Moving positive: nothing (pre-loaded positive).
    move_to(&mut e, 0, 5_000.0);
    settle(&mut e);
    assert_eq!(e.axis_status(0).unwrap().compensation, 0.0);
    // Reversal into negative: −200 per period for 5 periods, then −1000 held.
    move_to(&mut e, 0, 0.0);
    let mut seen = Vec::new();
    for _ in 0..7 {
        e.step();
        let s = e.axis_status(0).unwrap();
        assert_eq!(s.output_pos, s.cmd_pos + s.compensation);
        seen.push(s.compensation);
    }
    assert_eq!(
        seen,
        [-200.0, -400.0, -600.0, -800.0, -1000.0, -1000.0, -1000.0]
    );
    settle(&mut e);
    let s = e.axis_status(0).unwrap();
    assert_eq!((s.cmd_pos, s.output_pos), (0.0, -1000.0));
    // The actual position is the load's: it follows the plan, not the motor's extra travel.
    assert!(s.following_error.abs() < 1e-9, "{s:?}");
    assert_eq!(e.axis(0).unwrap().motor_position(), -1000.0);
    // Back to positive: the backlash is taken back at the same rate.
    move_to(&mut e, 0, 100.0);
    e.step();
    assert_eq!(e.axis_status(0).unwrap().compensation, -800.0);
}

/// S-2DCOMP: a 3 × 4 table, begin (0, 0), step (3000, 4000), x-correction = i % 3 at point i
/// (first reference fastest), axis 0 corrected from the encoder positions of axes 0 and 1.
#[test]
fn table_2d_s_2dcomp() {
    let mut e = machine(2);
    let values: Vec<String> = (0..12).map(|i| (i % 3).to_string()).collect();
    let y_values: Vec<String> = (0..12).map(|i| (i / 3).to_string()).collect();
    for (axis, v) in [(0, &values), (1, &y_values)] {
        ok(
            &mut e,
            cmd(&format!(
                r#"{{"type":"compensation_table","axis":{axis},
                    "references":[{{"axis":0,"source":"actual"}},{{"axis":1,"source":"actual"}}],
                    "start":[0,0],"step":[3000,4000],"count":[3,4],"values":[{}]}}"#,
                v.join(",")
            )),
        );
    }
    move_to(&mut e, 0, 4_500.0);
    move_to(&mut e, 1, 6_000.0);
    settle(&mut e);
    // x = 4500 is 1.5 steps, y = 6000 is 1.5 steps: corrections 1.5 and 1.5, read from the
    // encoders (one count of quantisation is 1/3000 of a step).
    let x = e.axis_status(0).unwrap();
    let y = e.axis_status(1).unwrap();
    assert!((x.compensation - 1.5).abs() < 1e-3, "{}", x.compensation);
    assert!((y.compensation - 1.5).abs() < 1e-3, "{}", y.compensation);
    assert_eq!(x.cmd_pos, 4_500.0);
    assert_eq!(x.output_pos, x.cmd_pos + x.compensation);
    // Cancel (enable 0): the outputs return to the plan.
    ok(&mut e, cmd(r#"{"type":"compensation_disable","axis":0}"#));
    e.step();
    assert_eq!(e.axis_status(0).unwrap().output_pos, 4_500.0);
}

/// HIMC TV 61: SetupComp(0, 1, −100, 200, 5, 1) with {−0.2, 0.1, −0.3, 0.4, −0.1}; axis 1 at
/// −100 / 0 / 100 / 700 / 1000 ⇒ GetCompPos(0) = −0.2 / −0.05 / 0.1 / −0.1 / −0.1.
#[test]
fn himc_one_d_table_tv61() {
    let mut e = machine(2);
    ok(
        &mut e,
        cmd(
            r#"{"type":"compensation_table","axis":0,"references":[{"axis":1}],
                "start":[-100],"step":[200],"count":[5],"values":[-0.2,0.1,-0.3,0.4,-0.1]}"#,
        ),
    );
    for (p, want) in [
        (-100.0, -0.2),
        (0.0, -0.05),
        (100.0, 0.1),
        (700.0, -0.1),
        (1000.0, -0.1),
    ] {
        move_to(&mut e, 1, p);
        settle(&mut e);
        let got = e.axis_status(0).unwrap().compensation;
        assert!((got - want).abs() < 1e-12, "axis 1 at {p}: {got} ≠ {want}");
    }
}

/// A 3-D grid (HIMC SetupComp3D): trilinear, the value at a cell's centre is the mean of its
/// eight corners.
#[test]
fn himc_three_d_table() {
    let mut e = machine(3);
    let values: Vec<String> = (0..8).map(|i| i.to_string()).collect();
    ok(
        &mut e,
        cmd(&format!(
            r#"{{"type":"compensation_table","axis":2,
                "references":[{{"axis":0}},{{"axis":1}},{{"axis":2}}],
                "start":[0,0,0],"step":[10,10,10],"count":[2,2,2],"values":[{}]}}"#,
            values.join(",")
        )),
    );
    for a in 0..3 {
        move_to(&mut e, a, 5.0);
    }
    settle(&mut e);
    assert_eq!(e.axis_status(2).unwrap().compensation, 3.5);
}

/// Property: at every tick of a move through a lead-screw table, output = planned + the table's
/// interpolated value at the planned position.
#[test]
fn output_is_planned_plus_table_every_tick() {
    let mut e = machine(1);
    let positions = [0.0, 100.0, 250.0, 400.0, 1000.0];
    let values = [0.5, -1.0, 2.0, 0.25, -0.75];
    ok(
        &mut e,
        cmd(r#"{"type":"compensation_lead_screw","axis":0,
                "positions":[0,100,250,400,1000],"positive":[0.5,-1,2,0.25,-0.75]}"#),
    );
    let table = |x: f64| {
        let i = positions.windows(2).position(|w| x < w[1]).unwrap_or(3);
        let (x0, x1, y0, y1) = (positions[i], positions[i + 1], values[i], values[i + 1]);
        let u = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
        y0 + (y1 - y0) * u
    };
    move_to(&mut e, 0, 900.0);
    for _ in 0..2000 {
        e.step();
        let s = e.axis_status(0).unwrap();
        let want = table(s.cmd_pos);
        assert!(
            (s.compensation - want).abs() < 1e-9,
            "{} {want}",
            s.compensation
        );
        assert_eq!(s.output_pos, s.cmd_pos + s.compensation);
    }
}

/// Same commands, same ticks: bit-identical outputs.
#[test]
fn deterministic() {
    let run_once = || {
        let mut e = machine(2);
        ok(
            &mut e,
            cmd(
                r#"{"type":"compensation_backlash","axis":0,"amount":3,"step":0.5,"direction":"positive"}"#,
            ),
        );
        ok(
            &mut e,
            cmd(
                r#"{"type":"compensation_table","axis":0,"references":[{"axis":1,"source":"actual"}],
                    "start":[0],"step":[50],"count":[3],"values":[0,1,-1]}"#,
            ),
        );
        move_to(&mut e, 0, 300.0);
        move_to(&mut e, 1, 80.0);
        (0..500)
            .map(|_| {
                e.step();
                e.axis_status(0).unwrap().output_pos.to_bits()
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(run_once(), run_once());
}

#[test]
fn bad_input_is_typed_and_changes_nothing() {
    let mut e = machine(2);
    ok(
        &mut e,
        cmd(r#"{"type":"compensation_lead_screw","axis":0,"positions":[0,10],"positive":[1,2]}"#),
    );
    let before = e.axis(0).unwrap().compensation().cloned();
    let compensation = |e: EngineError| match e {
        EngineError::InvalidCompensation { axis, reason } => (axis, reason),
        other => panic!("not a compensation error: {other:?}"),
    };
    let (_, r) = compensation(refused(
        &mut e,
        cmd(
            r#"{"type":"compensation_lead_screw","axis":0,"positions":[0,10,5],"positive":[1,2,3]}"#,
        ),
    ));
    assert!(r.contains("must increase"), "{r}");
    let (_, r) = compensation(refused(
        &mut e,
        cmd(r#"{"type":"compensation_lead_screw","axis":0,"positions":[0],"positive":[1]}"#),
    ));
    assert!(r.contains("at least 2"), "{r}");
    let (_, r) = compensation(refused(
        &mut e,
        cmd(
            r#"{"type":"compensation_table","axis":0,"references":[{"axis":1}],"start":[0],"step":[1],"count":[1],"values":[1]}"#,
        ),
    ));
    assert!(r.contains("at least 2"), "{r}");
    let (_, r) = compensation(refused(
        &mut e,
        cmd(
            r#"{"type":"compensation_table","axis":0,"references":[{"axis":1}],"start":[0],"step":[1],"count":[3],"values":[1,2]}"#,
        ),
    ));
    assert!(r.contains("3 grid points but 2 values"), "{r}");
    let (_, r) = compensation(refused(
        &mut e,
        cmd(
            r#"{"type":"compensation_table","axis":0,"references":[{"axis":0},{"axis":1},{"axis":0},{"axis":1}],"start":[0,0,0,0],"step":[1,1,1,1],"count":[2,2,2,2],"values":[]}"#,
        ),
    ));
    assert!(r.contains("1 to 3 reference axes"), "{r}");
    let (_, r) = compensation(refused(
        &mut e,
        cmd(
            r#"{"type":"compensation_backlash","axis":0,"amount":10,"step":0,"direction":"negative"}"#,
        ),
    ));
    assert!(r.contains("step"), "{r}");
    // NaN cannot be written in JSON; a command built in Rust can carry it.
    let nan = Command::from(axes::command::CompensationLeadScrew {
        axis: 0,
        positions: vec![0.0, f64::NAN],
        positive: vec![1.0, 2.0],
        negative: None,
        enable: true,
    });
    let (_, r) = compensation(refused(&mut e, nan));
    assert!(r.contains("positions[1]"), "{r}");
    assert!(matches!(
        refused(
            &mut e,
            cmd(
                r#"{"type":"compensation_table","axis":0,"references":[{"axis":7}],"start":[0],"step":[1],"count":[2],"values":[1,2]}"#
            )
        ),
        EngineError::InvalidAxis { axis: 7, count: 2 }
    ));
    assert!(matches!(
        refused(&mut e, cmd(r#"{"type":"compensation_enable","axis":9}"#)),
        EngineError::InvalidAxis { axis: 9, .. }
    ));
    let (axis, r) = compensation(refused(
        &mut e,
        cmd(r#"{"type":"compensation_enable","axis":1}"#),
    ));
    assert_eq!(axis, 1);
    assert!(r.contains("no compensation table"), "{r}");
    assert_eq!(e.axis(0).unwrap().compensation().cloned(), before);
    // The rest keeps running.
    move_to(&mut e, 0, 5.0);
    settle(&mut e);
    assert_eq!(e.axis_status(0).unwrap().output_pos, 5.0 + 1.5);
}
