//! Arc constructors against the manuals' vectors (NMC TV 43–46, CPU 226H TV-31/32, HIMC TV
//! 42–45 and the Circle2D table, HMC TV 14/19) and their invariants.

mod common;

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use path::geometry::{norm, sub, Arc, GeometryError, Segment, Turn};
use path::Point;

use common::{close, p};

/// The point of the arc nearest to `q`, by sampling (for "passes through" checks).
fn min_distance(seg: &Segment, q: &Point) -> f64 {
    let n = 20_000;
    (0..=n)
        .map(|i| norm(&sub(&seg.sample(seg.length() * i as f64 / n as f64).p, q)))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn nmc_tv44_radius_semicircle_ccw_and_cw() {
    // ArcRadiusEx(crd,2,{3000,4000},2500,1,…) from (0,0): semicircle about (1500,2000).
    let ccw = Arc::from_radius(
        p(&[0.0, 0.0]),
        p(&[3000.0, 4000.0]),
        2500.0,
        (0, 1),
        Turn::Ccw,
        2,
    )
    .unwrap();
    assert!(close(&ccw.center(), &p(&[1500.0, 2000.0]), 1e-9));
    assert!((ccw.sweep() - PI).abs() < 1e-12);
    let mid = ccw.sample(ccw.length() / 2.0).p;
    assert!(close(&mid, &p(&[3500.0, 500.0]), 1e-9), "{mid:?}");
    let cw = Arc::from_radius(
        p(&[0.0, 0.0]),
        p(&[3000.0, 4000.0]),
        2500.0,
        (0, 1),
        Turn::Cw,
        2,
    )
    .unwrap();
    let mid = cw.sample(cw.length() / 2.0).p;
    assert!(close(&mid, &p(&[-500.0, 3500.0]), 1e-9), "{mid:?}");
    assert_eq!(cw.end(), p(&[3000.0, 4000.0]));
}

#[test]
fn nmc_tv45_positive_radius_is_the_minor_arc_negative_the_major() {
    let minor = Arc::from_radius(
        p(&[0.0, 0.0]),
        p(&[10000.0, 0.0]),
        10000.0,
        (0, 1),
        Turn::Cw,
        2,
    )
    .unwrap();
    let major = Arc::from_radius(
        p(&[0.0, 0.0]),
        p(&[10000.0, 0.0]),
        -10000.0,
        (0, 1),
        Turn::Cw,
        2,
    )
    .unwrap();
    assert!((minor.sweep() - PI / 3.0).abs() < 1e-12);
    assert!((major.sweep() - 5.0 * PI / 3.0).abs() < 1e-12);
    // Both on circles of radius 10000 through the two points, on opposite sides.
    assert!((minor.radius() - 10000.0).abs() < 1e-9 && (major.radius() - 10000.0).abs() < 1e-9);
    assert!(minor.center()[1] * major.center()[1] < 0.0);
    // Clockwise minor arc from (0,0) to (10000,0) bulges up: centre below.
    assert!(minor.center()[1] < 0.0);
    assert!(minor.sample(minor.length() / 2.0).p[1] > 0.0);
}

#[test]
fn cpu226h_tv31_signed_radius_arcs() {
    // MC_CIRCLE_R from (0,0), end (1000,1000), RADIUS +1000, CW → centre (1000,0), 90°.
    let a = Arc::from_radius(
        p(&[0.0, 0.0]),
        p(&[1000.0, 1000.0]),
        1000.0,
        (0, 1),
        Turn::Cw,
        2,
    )
    .unwrap();
    assert!(close(&a.center(), &p(&[1000.0, 0.0]), 1e-9));
    assert!((a.sweep() - FRAC_PI_2).abs() < 1e-12);
    // RADIUS −1000, CW → centre (0,1000), 270°.
    let b = Arc::from_radius(
        p(&[0.0, 0.0]),
        p(&[1000.0, 1000.0]),
        -1000.0,
        (0, 1),
        Turn::Cw,
        2,
    )
    .unwrap();
    assert!(close(&b.center(), &p(&[0.0, 1000.0]), 1e-9));
    assert!((b.sweep() - 3.0 * FRAC_PI_2).abs() < 1e-12);
}

#[test]
fn a_radius_below_half_the_chord_is_refused_and_rounding_is_a_semicircle() {
    let e = Arc::from_radius(p(&[0.0, 0.0]), p(&[10.0, 0.0]), 4.9, (0, 1), Turn::Ccw, 2);
    assert!(
        matches!(e, Err(GeometryError::RadiusTooSmall { .. })),
        "{e:?}"
    );
    let a = Arc::from_radius(
        p(&[0.0, 0.0]),
        p(&[10.0, 0.0]),
        5.0 - 1e-12,
        (0, 1),
        Turn::Ccw,
        2,
    )
    .unwrap();
    assert!((a.sweep() - PI).abs() < 1e-9);
    let e = Arc::from_radius(p(&[1.0, 1.0]), p(&[1.0, 1.0]), 5.0, (0, 1), Turn::Ccw, 2);
    assert!(matches!(e, Err(GeometryError::Invalid(_))), "{e:?}");
    let e = Arc::from_radius(
        p(&[0.0, 0.0]),
        p(&[1.0, 1.0]),
        f64::NAN,
        (0, 1),
        Turn::Ccw,
        2,
    );
    assert!(
        matches!(e, Err(GeometryError::NotFinite { name: "radius", .. })),
        "{e:?}"
    );
    let e = Arc::from_radius(p(&[0.0, 0.0]), p(&[1.0, 1.0]), 5.0, (0, 2), Turn::Ccw, 2);
    assert!(
        matches!(e, Err(GeometryError::AxisOutOfRange { axis: 2, dims: 2 })),
        "{e:?}"
    );
}

#[test]
fn a_radius_arc_carries_the_other_axes_linearly() {
    // NMC D8-style extra axes ride along an arc: axes 2 and 3 move in proportion.
    let a = Arc::from_radius(
        p(&[0.0, 0.0, 0.0, 100.0]),
        p(&[10.0, 0.0, 5.0, 80.0]),
        -5.0,
        (0, 1),
        Turn::Ccw,
        4,
    )
    .unwrap();
    let half = a.sample(a.length() / 2.0).p;
    assert!((half[2] - 2.5).abs() < 1e-12 && (half[3] - 90.0).abs() < 1e-12);
    assert_eq!(a.end(), p(&[10.0, 0.0, 5.0, 80.0]));
}

#[test]
fn nmc_tv43_center_full_circle() {
    // ArcCenterEx(crd,1,{0,0},{5000,5000},0,…) from (0,0): CW full circle, passes (10000,10000).
    let a = Arc::from_center(
        p(&[0.0, 0.0]),
        p(&[0.0, 0.0]),
        p(&[5000.0, 5000.0]),
        (0, 1),
        Turn::Cw,
        0,
        2,
    )
    .unwrap();
    assert!((a.length() - TAU * 5000.0 * 2f64.sqrt()).abs() < 1e-6);
    assert!((a.length() - 44428.829).abs() < 1e-3);
    let seg = Segment::Arc(a);
    assert!(min_distance(&seg, &p(&[10000.0, 10000.0])) < 2.0);
    // Clockwise from 225° about the centre: toward −x, +y.
    let t = seg.start_tangent();
    assert!(t[0] < 0.0 && t[1] > 0.0, "{t:?}");
    assert_eq!(seg.end(), p(&[0.0, 0.0]));
}

#[test]
fn nmc_s_crd_full_ccw_semicircle_passes_below() {
    // NMC_CrdArcCenter(crd,2,{10000,0},{5000,0,0},1,…) from (0,0): CCW semicircle via (5000,−5000).
    let a = Arc::from_center(
        p(&[0.0, 0.0, 0.0]),
        p(&[10000.0, 0.0, 0.0]),
        p(&[5000.0, 0.0, 0.0]),
        (0, 1),
        Turn::Ccw,
        0,
        3,
    )
    .unwrap();
    let mid = a.sample(a.length() / 2.0).p;
    assert!(close(&mid, &p(&[5000.0, -5000.0, 0.0]), 1e-9), "{mid:?}");
    assert!((a.length() - PI * 5000.0).abs() < 1e-9);
}

#[test]
fn nmc_tv46_five_turn_helix() {
    // HelixCenterEx(crd,16,{0,0,20000},{5000,0},0,5,…) from (0,0,0): 5 CW turns about
    // (5000,0), Z 0 → 20000: XY back at (0,0) after every turn, Z ≈ 4000 per turn.
    let a = Arc::from_center(
        p(&[0.0, 0.0, 0.0]),
        p(&[0.0, 0.0, 20000.0]),
        p(&[5000.0, 0.0, 0.0]),
        (0, 1),
        Turn::Cw,
        4,
        3,
    )
    .unwrap();
    assert!((a.sweep() - 5.0 * TAU).abs() < 1e-12);
    for k in 1..=5 {
        let q = a.sample(a.length() * k as f64 / 5.0).p;
        assert!(
            close(&q, &p(&[0.0, 0.0, 4000.0 * k as f64]), 1e-6),
            "{k}: {q:?}"
        );
    }
    assert_eq!(a.end(), p(&[0.0, 0.0, 20000.0]));
}

#[test]
fn cpu226h_tv32_three_point_clockwise_semicircle() {
    let s = Segment::through_points(p(&[0.0, 0.0]), p(&[1000.0, 1000.0]), p(&[2000.0, 0.0]), 2)
        .unwrap();
    let Segment::Arc(a) = &s else { panic!("{s:?}") };
    assert!(close(&a.center(), &p(&[1000.0, 0.0]), 1e-9));
    assert!((a.radius() - 1000.0).abs() < 1e-9);
    assert!((a.sweep() - PI).abs() < 1e-12);
    assert_eq!(s.end(), p(&[2000.0, 0.0]));
    assert!(close(
        &s.sample(s.length() / 2.0).p,
        &p(&[1000.0, 1000.0]),
        1e-9
    ));
}

#[test]
fn himc_tv42_arc2d_through_the_border_point() {
    let s =
        Segment::through_points(p(&[0.0, 0.0]), p(&[100.0, 100.0]), p(&[200.0, 0.0]), 2).unwrap();
    let Segment::Arc(a) = &s else { panic!("{s:?}") };
    assert!(close(&a.center(), &p(&[100.0, 0.0]), 1e-9));
    assert_eq!(s.end(), p(&[200.0, 0.0]));
}

#[test]
fn three_points_major_arc_and_3d_plane() {
    // Via on the far side: a 270° arc.
    let s = Segment::through_points(p(&[1.0, 0.0]), p(&[-1.0, 0.0]), p(&[0.0, -1.0]), 2).unwrap();
    let Segment::Arc(a) = &s else { panic!("{s:?}") };
    assert!((a.sweep() - 1.5 * PI).abs() < 1e-12);
    assert!(min_distance(&s, &p(&[-1.0, 0.0])) < 1e-3);
    // NMC S-CRD-3DARC: from the origin through (5000,5000,5000) to (0,0,10000).
    let s = Segment::through_points(
        p(&[0.0, 0.0, 0.0]),
        p(&[5000.0, 5000.0, 5000.0]),
        p(&[0.0, 0.0, 10000.0]),
        3,
    )
    .unwrap();
    assert!(min_distance(&s, &p(&[5000.0, 5000.0, 5000.0])) < 2.0);
    assert_eq!(s.end(), p(&[0.0, 0.0, 10000.0]));
    let Segment::Arc(a) = &s else { panic!("{s:?}") };
    for q in [
        [0.0, 0.0, 0.0],
        [5000.0, 5000.0, 5000.0],
        [0.0, 0.0, 10000.0],
    ] {
        assert!((norm(&sub(&a.center(), &p(&q))) - a.radius()).abs() < 1e-6);
    }
}

#[test]
fn three_collinear_points_are_a_line_or_refused() {
    let s = Segment::through_points(p(&[0.0, 0.0]), p(&[1.0, 1.0]), p(&[3.0, 3.0]), 2).unwrap();
    assert!(matches!(s, Segment::Line(_)));
    assert_eq!(s.end(), p(&[3.0, 3.0]));
    let e = Segment::through_points(p(&[0.0, 0.0]), p(&[4.0, 4.0]), p(&[3.0, 3.0]), 2);
    assert!(matches!(e, Err(GeometryError::Invalid(_))), "{e:?}");
    let e = Segment::through_points(p(&[0.0, 0.0]), p(&[1.0, 1.0]), p(&[0.0, 0.0]), 2);
    assert!(
        matches!(
            e,
            Err(GeometryError::Coincident {
                first: "start",
                second: "end"
            })
        ),
        "{e:?}"
    );
    let e = Segment::through_points(p(&[0.0, 0.0]), p(&[0.0, 0.0]), p(&[1.0, 0.0]), 2);
    assert!(matches!(e, Err(GeometryError::Coincident { .. })), "{e:?}");
}

#[test]
fn full_circle_through_three_points() {
    let a =
        Arc::circle_through(p(&[0.0, 0.0]), p(&[1000.0, 1000.0]), p(&[2000.0, 0.0]), 2).unwrap();
    assert!((a.sweep() - TAU).abs() < 1e-12);
    assert_eq!(a.end(), p(&[0.0, 0.0]));
    // Clockwise (via the top first).
    assert!(a.sample(1.0).p[1] > 0.0);
    let e = Arc::circle_through(p(&[0.0, 0.0]), p(&[1.0, 0.0]), p(&[2.0, 0.0]), 2);
    assert!(e.is_err());
}

#[test]
fn himc_tv44_arc_angle() {
    // ArcAngle2D(0, 10, 10, 45) from (0,0): ends at (10, 10 − 10√2).
    let a = Arc::from_center_angle(
        p(&[0.0, 0.0]),
        p(&[10.0, 10.0]),
        45f64.to_radians(),
        (0, 1),
        2,
    )
    .unwrap();
    assert!(
        close(&a.end(), &p(&[10.0, 10.0 - 10.0 * 2f64.sqrt()]), 1e-12),
        "{:?}",
        a.end()
    );
    let b = Arc::from_center_angle(
        p(&[0.0, 0.0]),
        p(&[10.0, 10.0]),
        -45f64.to_radians(),
        (0, 1),
        2,
    )
    .unwrap();
    assert!(
        close(&b.end(), &p(&[10.0 - 10.0 * 2f64.sqrt(), 10.0]), 1e-12),
        "{:?}",
        b.end()
    );
    // More than a turn is allowed.
    let c = Arc::from_center_angle(p(&[0.0, 0.0]), p(&[10.0, 0.0]), 3.0 * TAU, (0, 1), 2).unwrap();
    assert!((c.length() - 60.0 * PI).abs() < 1e-9);
    assert!(Arc::from_center_angle(p(&[0.0, 0.0]), p(&[10.0, 0.0]), 0.0, (0, 1), 2).is_err());
    assert!(Arc::from_center_angle(p(&[0.0, 0.0]), p(&[0.0, 0.0]), 1.0, (0, 1), 2).is_err());
}

#[test]
fn about_normal_turns_by_the_right_hand_rule() {
    // Normal +z: counter-clockwise in XY, as HIMC's {0,0,1}.
    let a = Arc::about_normal(
        p(&[10.0, 0.0, 0.0]),
        p(&[0.0, 0.0, 0.0]),
        [0.0, 0.0, 1.0],
        FRAC_PI_2,
        [0, 1, 2],
        3,
    )
    .unwrap();
    assert!(close(&a.end(), &p(&[0.0, 10.0, 0.0]), 1e-12));
    // Normal −z, or a negative angle: clockwise.
    let b = Arc::about_normal(
        p(&[10.0, 0.0, 0.0]),
        p(&[0.0, 0.0, 0.0]),
        [0.0, 0.0, -2.0],
        FRAC_PI_2,
        [0, 1, 2],
        3,
    )
    .unwrap();
    assert!(close(&b.end(), &p(&[0.0, -10.0, 0.0]), 1e-12));
    // A centre off start's plane is projected along the normal: the circle stays at z = 5.
    let c = Arc::about_normal(
        p(&[0.0, 0.0, 5.0, 7.0]),
        p(&[0.0, 3.0, 0.0, 0.0]),
        [0.0, 0.0, 1.0],
        PI,
        [0, 1, 2],
        4,
    )
    .unwrap();
    assert!(
        close(&c.end(), &p(&[0.0, 6.0, 5.0, 7.0]), 1e-12),
        "{:?}",
        c.end()
    );
    for i in 0..=10 {
        let q = c.sample(c.length() * i as f64 / 10.0).p;
        assert!((q[2] - 5.0).abs() < 1e-12 && q[3] == 7.0);
    }
    // Axes permuted: (y, z, x) with normal +z of that frame = +x of the path: y → z.
    let d = Arc::about_normal(
        p(&[0.0, 1.0, 0.0]),
        p(&[0.0, 0.0, 0.0]),
        [0.0, 0.0, 1.0],
        FRAC_PI_2,
        [1, 2, 0],
        3,
    )
    .unwrap();
    assert!(
        close(&d.end(), &p(&[0.0, 0.0, 1.0]), 1e-12),
        "{:?}",
        d.end()
    );
    let zero = Arc::about_normal(
        p(&[1.0, 0.0, 0.0]),
        p(&[0.0, 0.0, 0.0]),
        [0.0; 3],
        1.0,
        [0, 1, 2],
        3,
    );
    assert!(matches!(zero, Err(GeometryError::Invalid(_))));
    let same = Arc::about_normal(
        p(&[1.0, 0.0, 0.0]),
        p(&[0.0, 0.0, 0.0]),
        [0.0, 0.0, 1.0],
        1.0,
        [0, 1, 1],
        3,
    );
    assert!(same.is_err());
    let on_axis = Arc::about_normal(
        p(&[0.0, 0.0, 1.0]),
        p(&[0.0, 0.0, 0.0]),
        [0.0, 0.0, 1.0],
        1.0,
        [0, 1, 2],
        3,
    );
    assert!(on_axis.is_err());
}

#[test]
fn turn_names() {
    assert_eq!(Turn::from_name("cw"), Some(Turn::Cw));
    assert_eq!(Turn::from_name("CCW"), Some(Turn::Ccw));
    assert_eq!(Turn::from_name("left"), None);
}

/// HIMC Circle2D from (0,0) about (0,0)+… for θ = 210°: start (10,0) about the origin, end at
/// 210°.
fn circle2d(turns: i32) -> Result<Arc, GeometryError> {
    let end = p(&[
        10.0 * 210f64.to_radians().cos(),
        10.0 * 210f64.to_radians().sin(),
    ]);
    Arc::from_center_turns(p(&[10.0, 0.0]), end, p(&[0.0, 0.0]), (0, 1), turns, 2)
}

#[test]
fn himc_circle2d_turn_table() {
    // Digest 004 §8.2.17: θ = 210°: −2 → −510°, −1 → −150°, 0 → 210°, 1 → 210°, 2 → 570°.
    for (turns, degrees) in [
        (-2, -510.0),
        (-1, -150.0),
        (0, 210.0),
        (1, 210.0),
        (2, 570.0),
    ] {
        let a = circle2d(turns).unwrap();
        let signed = a.sweep().to_degrees() * if a.sample(0.1).p[1] > 0.0 { 1.0 } else { -1.0 };
        assert!((signed - degrees).abs() < 1e-9, "turns {turns}: {signed}");
        assert!((a.length() - 10.0 * a.sweep()).abs() < 1e-9);
    }
    assert_eq!(path::geometry::himc_turns_angle(PI, 3), 5.0 * PI);
}

#[test]
fn himc_tv45_circle2d_half_turn() {
    // Circle2D(0, 100, 0, 200, 0, 1) from (0,0): 180° CCW to (200,0), passing (100,−100).
    let a = Arc::from_center_turns(
        p(&[0.0, 0.0]),
        p(&[200.0, 0.0]),
        p(&[100.0, 0.0]),
        (0, 1),
        1,
        2,
    )
    .unwrap();
    assert!(close(
        &a.sample(a.length() / 2.0).p,
        &p(&[100.0, -100.0]),
        1e-9
    ));
    assert_eq!(a.end(), p(&[200.0, 0.0]));
    // End = start: turns 0/1 is no motion (refused), 2 is one full circle, −1 one clockwise.
    let s = p(&[0.0, 0.0]);
    let c = p(&[100.0, 0.0]);
    assert!(Arc::from_center_turns(s, s, c, (0, 1), 1, 2).is_err());
    assert!(Arc::from_center_turns(s, s, c, (0, 1), 0, 2).is_err());
    let full = Arc::from_center_turns(s, s, c, (0, 1), 2, 2).unwrap();
    assert!((full.sweep() - TAU).abs() < 1e-12);
    let cw = Arc::from_center_turns(s, s, c, (0, 1), -1, 2).unwrap();
    assert!((cw.sweep() - TAU).abs() < 1e-12 && cw.sample(1.0).p[1] > 0.0);
}

#[test]
fn himc_tv55_circle_abs_stadium() {
    // CircleAbs centre (100,50,0), normal {0,0,1}, turns 0, from (100,0) to (100,100): passes
    // (150,50); centre (0,50,0) from (0,100) to (0,0): passes (−50,50).
    let a = Arc::from_center_normal_turns(
        p(&[100.0, 0.0, 0.0]),
        p(&[100.0, 100.0, 0.0]),
        p(&[100.0, 50.0, 0.0]),
        [0.0, 0.0, 1.0],
        0,
        [0, 1, 2],
        3,
    )
    .unwrap();
    assert!(close(
        &a.sample(a.length() / 2.0).p,
        &p(&[150.0, 50.0, 0.0]),
        1e-9
    ));
    let b = Arc::from_center_normal_turns(
        p(&[0.0, 100.0, 0.0]),
        p(&[0.0, 0.0, 0.0]),
        p(&[0.0, 50.0, 0.0]),
        [0.0, 0.0, 1.0],
        0,
        [0, 1, 2],
        3,
    )
    .unwrap();
    assert!(close(
        &b.sample(b.length() / 2.0).p,
        &p(&[-50.0, 50.0, 0.0]),
        1e-9
    ));
    assert_eq!(b.end(), p(&[0.0, 0.0, 0.0]));
}

#[test]
fn circle_about_a_normal_with_a_helix_along_it() {
    // Normal +x: the circle is in the YZ plane; the end's x offset is the helix's rise.
    let a = Arc::from_center_normal(
        p(&[0.0, 10.0, 0.0]),
        p(&[6.0, 10.0, 0.0]),
        p(&[3.0, 0.0, 0.0]),
        [1.0, 0.0, 0.0],
        Turn::Ccw,
        2,
        [0, 1, 2],
        3,
    )
    .unwrap();
    assert!((a.sweep() - 3.0 * TAU).abs() < 1e-12);
    assert!((a.radius() - 10.0).abs() < 1e-12);
    // Counter-clockwise about +x carries +y toward +z.
    assert!(a.sample(0.5).p[2] > 0.0);
    let q = a.sample(a.length() / 3.0).p;
    assert!(close(&q, &p(&[2.0, 10.0, 0.0]), 1e-9), "{q:?}");
    assert_eq!(a.end(), p(&[6.0, 10.0, 0.0]));
    // The end off the cylinder is refused.
    let e = Arc::from_center_normal(
        p(&[0.0, 10.0, 0.0]),
        p(&[6.0, 11.0, 0.0]),
        p(&[3.0, 0.0, 0.0]),
        [1.0, 0.0, 0.0],
        Turn::Ccw,
        0,
        [0, 1, 2],
        3,
    );
    assert!(matches!(e, Err(GeometryError::Invalid(_))));
}

#[test]
fn hmc_tv14_full_circle_and_ray_projection() {
    // MoveCircle(0,1,2,3,0,0,10000,0) from (0,0): CW full circle about (10000,0), 2π·10000.
    let a = Arc::from_center_toward(
        p(&[0.0, 0.0]),
        p(&[0.0, 0.0]),
        p(&[10000.0, 0.0]),
        (0, 1),
        Turn::Cw,
        2,
    )
    .unwrap();
    assert!((a.length() - 62831.853).abs() < 1e-3);
    assert_eq!(a.end(), p(&[0.0, 0.0]));
    // An end off the circle is moved along the ray from the centre.
    let b = Arc::from_center_toward(
        p(&[10.0, 0.0]),
        p(&[0.0, 3.0]),
        p(&[0.0, 0.0]),
        (0, 1),
        Turn::Ccw,
        2,
    )
    .unwrap();
    assert!(close(&b.end(), &p(&[0.0, 10.0]), 1e-12));
    // HMC TV 18's slot: from (2000,0) CW about (2000,−1000) to (2000,−2000): π·1000.
    let c = Arc::from_center_toward(
        p(&[2000.0, 0.0]),
        p(&[2000.0, -2000.0]),
        p(&[2000.0, -1000.0]),
        (0, 1),
        Turn::Cw,
        2,
    )
    .unwrap();
    assert!((c.length() - PI * 1000.0).abs() < 1e-9);
    assert!(c.sample(c.length() / 2.0).p[0] > 2000.0);
}

#[test]
fn hmc_tv19_helical_thread() {
    // MoveHelical mode 7: CW full circle of radius 50 about (50,0) with Z +500, twice.
    let mut start = p(&[0.0, 0.0, 0.0]);
    let mut xy_length = 0.0;
    for _ in 0..2 {
        let mut end = start;
        end[2] += 500.0;
        let a = Arc::helix_turns(start, end, p(&[50.0, 0.0, 0.0]), (0, 1), Turn::Cw, 1, 3).unwrap();
        xy_length += a.circle_length();
        start = a.end();
    }
    assert!((xy_length - 2.0 * 314.159).abs() < 1e-2);
    assert_eq!(start, p(&[0.0, 0.0, 1000.0]));
    assert!(Arc::helix_turns(start, start, p(&[50.0, 0.0, 0.0]), (0, 1), Turn::Cw, 0, 3).is_err());
}
