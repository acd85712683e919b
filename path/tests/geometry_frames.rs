//! Frames: HIMC TV 56–57, the roll-pitch-yaw order, the frame chain, NMC's origin offset and
//! rotary transforms, segments moved exactly, and round trips (proptest).

mod common;

use std::f64::consts::{FRAC_PI_2, PI};

use path::frames::{
    rpy_matrix, xyza_tool_offset, Frame, FrameChain, FrameSelection, RotaryTransform, Transform,
    XyzaTransform,
};
use path::geometry::{norm, sub, Arc, Line, Segment, Turn};
use path::MAX_AXES;
use proptest::prelude::*;

use common::{close, p};

#[test]
fn himc_tv56_pcs_rotated_45_degrees() {
    let mut chain = FrameChain::new();
    chain
        .set(Frame::Pcs, [400.0, 200.0, 0.0, 0.0, 0.0, 45.0])
        .unwrap();
    let pcs = FrameSelection {
        pcs: true,
        ..FrameSelection::default()
    };
    let m = chain.point_to_machine(pcs, &p(&[10.0, 10.0])).unwrap();
    assert!(close(&m, &p(&[400.0, 214.142136]), 1e-6), "{m:?}");
    assert!((m[0] - 400.0).abs() < 1e-12);
    let back = chain.point_from_machine(pcs, &m).unwrap();
    assert!(close(&back, &p(&[10.0, 10.0]), 1e-12));
    // TV 57: the pose reads back as set.
    assert_eq!(
        chain.pose(Frame::Pcs).unwrap(),
        [400.0, 200.0, 0.0, 0.0, 0.0, 45.0]
    );
    // CS_MCS: no link.
    let mcs = chain
        .point_to_machine(FrameSelection::default(), &p(&[10.0, 10.0]))
        .unwrap();
    assert_eq!(mcs, p(&[10.0, 10.0]));
    // The transform keeps a 2-axis group in its plane.
    assert!(chain.to_machine(pcs).unwrap().keeps(2));
}

#[test]
fn roll_pitch_yaw_is_fixed_axes_x_then_y_then_z() {
    // R = Rz(C)·Ry(B)·Rx(A): roll 90° then yaw 90°: x̂ → x̂ → ŷ; ŷ → ẑ → ẑ; ẑ → −ŷ → x̂.
    let t = Transform::from_xyzrpy(0.0, 0.0, 0.0, FRAC_PI_2, 0.0, FRAC_PI_2).unwrap();
    assert!(close(
        &t.apply(&p(&[1.0, 0.0, 0.0])),
        &p(&[0.0, 1.0, 0.0]),
        1e-15
    ));
    assert!(close(
        &t.apply(&p(&[0.0, 1.0, 0.0])),
        &p(&[0.0, 0.0, 1.0]),
        1e-15
    ));
    assert!(close(
        &t.apply(&p(&[0.0, 0.0, 1.0])),
        &p(&[1.0, 0.0, 0.0]),
        1e-15
    ));
    // Pitch 90°: x̂ → −ẑ (right-hand rule about y).
    let m = rpy_matrix(0.0, FRAC_PI_2, 0.0);
    assert!((m[2][0] + 1.0).abs() < 1e-15);
    // A 6-D pose with a pitch leaves a 2-axis group's plane.
    let tilt = Transform::from_himc_pose([0.0, 0.0, 0.0, 0.0, 10.0, 0.0]).unwrap();
    assert!(!tilt.keeps(2) && tilt.keeps(3));
    assert!(tilt.check_keeps(2).is_err());
}

#[test]
fn the_chain_composes_offset_wcs_pcs_in_that_order() {
    let mut chain = FrameChain::new();
    chain
        .set(Frame::Offset, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        .unwrap();
    chain
        .set(Frame::Wcs(2), [0.0, 0.0, 0.0, 0.0, 0.0, 90.0])
        .unwrap();
    chain
        .set(Frame::Pcs, [10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        .unwrap();
    let all = FrameSelection {
        offset: true,
        wcs: Some(2),
        pcs: true,
    };
    // PCS (0,0) → WCS2 (10,0) → OFFSET (0,10) (turned 90°) → MCS (1,10).
    let m = chain.point_to_machine(all, &p(&[0.0, 0.0])).unwrap();
    assert!(close(&m, &p(&[1.0, 10.0]), 1e-12), "{m:?}");
    let back = chain.point_from_machine(all, &m).unwrap();
    assert!(close(&back, &p(&[0.0, 0.0]), 1e-12));
    // WCS2 alone.
    let wcs = FrameSelection {
        wcs: Some(2),
        ..FrameSelection::default()
    };
    let m = chain.point_to_machine(wcs, &p(&[1.0, 0.0])).unwrap();
    assert!(close(&m, &p(&[0.0, 1.0]), 1e-12));
    assert!(chain.set(Frame::Wcs(16), [0.0; 6]).is_err());
    assert!(chain.set(Frame::Wcs(0), [0.0; 6]).is_err());
    assert!(chain
        .set(Frame::Pcs, [f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0])
        .is_err());
    // A refused set leaves the link as it was.
    assert_eq!(chain.pose(Frame::Pcs).unwrap()[0], 10.0);
}

#[test]
fn nmc_origin_offset_is_a_translation() {
    // orgFlag 1, offset (1000, 2000, 0): user (0,0,0) is machine (1000, 2000, 0).
    let t = Transform::translation(p(&[1000.0, 2000.0, 0.0])).unwrap();
    assert_eq!(t.apply(&p(&[0.0, 0.0, 0.0])), p(&[1000.0, 2000.0, 0.0]));
    assert_eq!(
        t.inverse().apply(&p(&[1000.0, 2000.0, 5.0])),
        p(&[0.0, 0.0, 5.0])
    );
    assert!(Transform::translation(p(&[f64::INFINITY])).is_err());
}

#[test]
fn nmc_rotary_table_transform() {
    // CrdSetTransRotate(crd, 3, 2π/10000, 0, 15000): axis 3 turns the table about (0, 15000);
    // −2500 units = −90°.
    let r = RotaryTransform::new((0, 1), (0.0, 15000.0), 3, PI * 2.0 / 10000.0).unwrap();
    let m = r.to_machine(&p(&[1000.0, 15000.0, 0.0, -2500.0]));
    assert!(close(&m, &p(&[0.0, 14000.0, 0.0, -2500.0]), 1e-9), "{m:?}");
    assert_eq!(
        r.to_machine(&p(&[5.0, 6.0, 0.0, 0.0])),
        p(&[5.0, 6.0, 0.0, 0.0])
    );
    assert!(RotaryTransform::new((0, 1), (0.0, 0.0), 1, 1.0).is_err());
}

#[test]
fn nmc_xyza_tool_offset_round_trip() {
    // S-TRANS-XYZA: ToolCalc(π/3, −3687, −9494); turning A by π/3 moves the tip by exactly
    // the measured (dx, dy).
    let (tx, ty) = xyza_tool_offset(PI / 3.0, -3687.0, -9494.0).unwrap();
    let x = XyzaTransform::new(2.0 * PI / 288000.0, (tx, ty)).unwrap();
    let a = 48000.0; // π/3 in pulses
    let m0 = x.to_machine(&p(&[0.0, 0.0, 0.0, 0.0]));
    let m1 = x.to_machine(&p(&[0.0, 0.0, 0.0, a]));
    // Machine XY moved by −(dx, dy) to hold the tip still.
    assert!(
        close(&sub(&m1, &m0), &p(&[3687.0, 9494.0, 0.0, a]), 1e-6),
        "{m1:?}"
    );
    assert!(close(&x.from_machine(&m1), &p(&[0.0, 0.0, 0.0, a]), 1e-9));
    assert!(xyza_tool_offset(2.0 * PI, 1.0, 1.0).is_err());
}

#[test]
fn rotation_about_a_point() {
    let t = Transform::rotation_about((0, 1), (5.0, 5.0), FRAC_PI_2).unwrap();
    assert!(close(
        &t.apply(&p(&[10.0, 5.0, 7.0])),
        &p(&[5.0, 10.0, 7.0]),
        1e-12
    ));
    assert!(close(&t.apply(&p(&[5.0, 5.0])), &p(&[5.0, 5.0]), 1e-15));
    assert!(Transform::rotation_about((1, 1), (0.0, 0.0), 1.0).is_err());
    assert!(Transform::rotation_about((0, 9), (0.0, 0.0), 1.0).is_err());
}

#[test]
fn from_rotation_refuses_non_rotations() {
    let mirror = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
    assert!(Transform::from_rotation(mirror, [0, 1, 2], [0.0; MAX_AXES]).is_err());
    let shear = [[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    assert!(Transform::from_rotation(shear, [0, 1, 2], [0.0; MAX_AXES]).is_err());
    let m = rpy_matrix(0.1, 0.2, 0.3);
    assert!(Transform::from_rotation(m, [3, 4, 5], [0.0; MAX_AXES]).is_ok());
}

fn check_segment_moves_exactly(seg: &Segment, t: &Transform) {
    let moved = seg.transformed(t);
    assert!((moved.length() - seg.length()).abs() < 1e-12 * (1.0 + seg.length()));
    assert!(close(&moved.end(), &t.apply(&seg.end()), 1e-9));
    for i in 0..=20 {
        let s = seg.length() * f64::from(i) / 20.0;
        let (a, b) = (seg.sample(s), moved.sample(s));
        assert!(close(&b.p, &t.apply(&a.p), 1e-9), "{s}");
        assert!(close(&b.t, &t.apply_vector(&a.t), 1e-12));
        assert!(close(&b.k, &t.apply_vector(&a.k), 1e-12));
    }
}

proptest! {
    #[test]
    fn transforms_round_trip_and_compose(
        pose_a in prop::array::uniform6(-100.0f64..100.0),
        pose_b in prop::array::uniform6(-100.0f64..100.0),
        q in prop::array::uniform3(-1000.0f64..1000.0),
    ) {
        let a = Transform::from_himc_pose(pose_a).unwrap();
        let b = Transform::from_himc_pose(pose_b).unwrap();
        let x = p(&q);
        let back = a.inverse().apply(&a.apply(&x));
        prop_assert!(close(&back, &x, 1e-9));
        let ab = a.compose(&b);
        prop_assert!(close(&ab.apply(&x), &a.apply(&b.apply(&x)), 1e-9));
        prop_assert!(close(&ab.inverse().apply(&ab.apply(&x)), &x, 1e-9));
        // Rigid: distances kept.
        let y = p(&[q[1], q[2], q[0]]);
        prop_assert!((norm(&sub(&a.apply(&x), &a.apply(&y))) - norm(&sub(&x, &y))).abs() < 1e-9);
    }

    #[test]
    fn segments_move_exactly(
        pose in prop::array::uniform6(-100.0f64..100.0),
        extra in 0u32..3,
        z in -50.0f64..50.0,
    ) {
        let t = Transform::from_himc_pose(pose).unwrap();
        let line = Line::new(p(&[1.0, 2.0, 3.0]), p(&[-4.0, 5.0, z]), 3).unwrap();
        check_segment_moves_exactly(&Segment::Line(line), &t);
        let arc = Arc::from_center(
            p(&[10.0, 0.0, 0.0]),
            p(&[0.0, 10.0, z]),
            p(&[0.0, 0.0, 0.0]),
            (0, 1),
            Turn::Cw,
            extra,
            3,
        )
        .unwrap();
        check_segment_moves_exactly(&Segment::Arc(arc), &t);
    }
}
