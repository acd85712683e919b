//! Compensation grids turned by an angle (NMC `T2DCompensationTable.angle`, digest 001 §2.19,
//! §3.17, S-2DCOMP) and interpolated by cubic splines (HIMC SetCompAlgType 1, digest 004
//! §2.13): the correction read at the table coordinates of the turned axes, the natural spline
//! through the points in 1-D and its tensor product in 2-D, and the shapes refused.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, Enable};
use axes::{Engine, EngineError, ParamId};
use common::{cmd, engine_with, free_linear_axis, ok, refused, run};

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

fn go(e: &mut Engine, targets: &[(u16, f64)]) {
    for &(axis, position) in targets {
        ok(
            e,
            cmd(&format!(
                r#"{{"type":"move_absolute","axis":{axis},"position":{position}}}"#
            )),
        );
    }
    run(e, 2.0);
}

fn compensation(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().compensation
}

/// S-2DCOMP's table (3 × 4, begin (0, 0), step (3000, 4000), x-correction = i % 3) turned by
/// 30°: the machine point of table coordinates (3000, 4000) reads the value of grid point
/// (1, 1), 1, where the unturned table would read about 0.2.
#[test]
fn a_turned_2d_table_reads_at_the_turned_coordinates_s_2dcomp() {
    let mut e = machine(2);
    let values: Vec<String> = (0..12).map(|i| (i % 3).to_string()).collect();
    ok(
        &mut e,
        cmd(&format!(
            r#"{{"type":"compensation_table","axis":0,
                "references":[{{"axis":0,"source":"planned"}},{{"axis":1,"source":"planned"}}],
                "start":[0,0],"step":[3000,4000],"count":[3,4],"values":[{}],"angle":30}}"#,
            values.join(",")
        )),
    );
    let (s, c) = 30f64.to_radians().sin_cos();
    let (u, v) = (3000.0, 4000.0);
    go(&mut e, &[(0, u * c - v * s), (1, u * s + v * c)]);
    assert!(
        (compensation(&e, 0) - 1.0).abs() < 1e-9,
        "{}",
        compensation(&e, 0)
    );
    // Half a step further along the turned x axis: 1.5.
    let (u, v) = (4500.0, 4000.0);
    go(&mut e, &[(0, u * c - v * s), (1, u * s + v * c)]);
    assert!(
        (compensation(&e, 0) - 1.5).abs() < 1e-9,
        "{}",
        compensation(&e, 0)
    );
}

/// y = 0, 1, 0, 1 at 0, 1000, 2000, 3000: the natural spline is 0.75, 0.5 and 0.25 at the
/// spans' middles (M = 0, −4, 4, 0 per step²), where the linear table reads 0.5.
#[test]
fn a_cubic_1d_table_follows_the_natural_spline_himc_setcompalgtype_1() {
    let mut e = machine(1);
    let table = |interpolation: &str| {
        cmd(&format!(
            r#"{{"type":"compensation_table","axis":0,"references":[{{"axis":0}}],
                "start":[0],"step":[1000],"count":[4],"values":[0,1,0,1],
                "interpolation":"{interpolation}"}}"#
        ))
    };
    ok(&mut e, table("cubic"));
    for (x, want) in [(500.0, 0.75), (1500.0, 0.5), (2500.0, 0.25), (2000.0, 0.0)] {
        go(&mut e, &[(0, x)]);
        assert!(
            (compensation(&e, 0) - want).abs() < 1e-9,
            "at {x}: {}",
            compensation(&e, 0)
        );
    }
    ok(&mut e, table("linear"));
    go(&mut e, &[(0, 500.0)]);
    assert!((compensation(&e, 0) - 0.5).abs() < 1e-9);
}

/// Values a_i · b_j with a = 0, 1, 0, 1 (x) and b = 1, 2 (y): the tensor-product spline is the
/// product of the row spline and the (straight) column spline.
#[test]
fn a_cubic_2d_table_is_the_tensor_product_spline() {
    let mut e = machine(3);
    ok(
        &mut e,
        cmd(r#"{"type":"compensation_table","axis":2,
                "references":[{"axis":0},{"axis":1}],
                "start":[0,0],"step":[1000,500],"count":[4,2],
                "values":[0,1,0,1, 0,2,0,2],"interpolation":"cubic"}"#),
    );
    go(&mut e, &[(0, 500.0), (1, 250.0)]);
    assert!(
        (compensation(&e, 2) - 0.75 * 1.5).abs() < 1e-9,
        "{}",
        compensation(&e, 2)
    );
    go(&mut e, &[(0, 1500.0), (1, 500.0)]);
    assert!(
        (compensation(&e, 2) - 0.5 * 2.0).abs() < 1e-9,
        "{}",
        compensation(&e, 2)
    );
    // Grid points exactly.
    go(&mut e, &[(0, 3000.0), (1, 0.0)]);
    assert!(
        (compensation(&e, 2) - 1.0).abs() < 1e-9,
        "{}",
        compensation(&e, 2)
    );
}

#[test]
fn an_angle_off_2d_or_a_spline_in_3d_is_refused() {
    let mut e = machine(3);
    let r = refused(
        &mut e,
        cmd(
            r#"{"type":"compensation_table","axis":0,"references":[{"axis":0}],
                "start":[0],"step":[1],"count":[2],"values":[0,1],"angle":10}"#,
        ),
    );
    assert!(
        matches!(r, EngineError::InvalidCompensation { axis: 0, .. }),
        "{r}"
    );
    assert!(r.to_string().contains("2-D"), "{r}");
    let r = refused(
        &mut e,
        cmd(r#"{"type":"compensation_table","axis":0,
                "references":[{"axis":0},{"axis":1},{"axis":2}],
                "start":[0,0,0],"step":[1,1,1],"count":[2,2,2],"values":[0,0,0,0,0,0,0,0],
                "interpolation":"cubic"}"#),
    );
    assert!(r.to_string().contains("3-D has no spline"), "{r}");
    let r = refused(
        &mut e,
        cmd(
            r#"{"type":"compensation_table","axis":0,"references":[{"axis":0},{"axis":1}],
                "start":[0,0],"step":[1,1],"count":[2,2],"values":[0,0,0,0],"angle":1e300}"#,
        ),
    );
    assert!(r.to_string().contains("angle"), "{r}");
    assert!(e.axis_status(0).unwrap().compensation == 0.0);
}
