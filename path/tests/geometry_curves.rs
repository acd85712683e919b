//! Curves: splines through points (HMC MoveSplineND) and ellipses (NMC CrdEllipse), sampled by
//! path length through their tables.

mod common;

use std::f64::consts::TAU;

use path::frames::Transform;
use path::geometry::{norm, sub, Curve, CurveKind, GeometryError, Segment, SplineBuild, Turn};
use path::{Point, MAX_AXES};
use proptest::prelude::*;

use common::p;

fn curve(seg: &Segment) -> Option<&Curve> {
    match seg {
        Segment::Curve(c) => Some(c),
        _ => None,
    }
}

/// The checks every curve passes: exact ends, unit tangents, s is arc length (short chords ≈
/// their s), curvature ≈ the second difference, bounds hold, trimming keeps the shape.
fn check_curve(seg: &Segment, start: &Point, end: &Point) {
    let len = seg.length();
    // A cubic spline's third derivative jumps at its points: differences across one carry
    // an O(h) error, so they are not checked there.
    let knots: Vec<f64> = curve(seg).map_or(Vec::new(), |c| c.point_lengths().collect());
    assert!(len > 0.0);
    assert!(norm(&sub(&seg.start(), start)) < 1e-9, "{:?}", seg.start());
    assert_eq!(seg.end(), *end);
    assert_eq!(seg.sample(len).p, *end);
    let n = 2000;
    let mut polyline = 0.0;
    let mut previous = seg.sample(0.0).p;
    for i in 0..=n {
        let s = len * f64::from(i) / f64::from(n);
        let x = seg.sample(s);
        assert!((norm(&x.t) - 1.0).abs() < 1e-12, "|t| at {s}");
        for axis in 0..MAX_AXES {
            assert!(
                x.t[axis].abs() <= seg.max_tangent(axis) + 1e-12,
                "axis {axis} at {s}"
            );
        }
        assert!(norm(&x.k) <= seg.max_curvature() + 1e-12, "κ at {s}");
        if i > 0 {
            polyline += norm(&sub(&x.p, &previous));
        }
        previous = x.p;
        // Curvature against the second difference of positions.
        // Small against the length and against the radius of curvature, so the difference's
        // own error stays below the tolerance.
        let h = (len * 1e-4).min(1e-2 / seg.max_curvature().max(1e-12));
        let near_knot = knots.iter().any(|k| (k - s).abs() <= 1.5 * h);
        if s > h && s < len - h && !near_knot {
            let (a, b) = (seg.sample(s - h).p, seg.sample(s + h).p);
            let mut second = [0.0; MAX_AXES];
            for k in 0..MAX_AXES {
                second[k] = (a[k] - 2.0 * x.p[k] + b[k]) / (h * h);
            }
            let scale = norm(&x.k).max(1.0 / len);
            // The difference's own error is about h²·κ³/12 ≤ 1e-4·κmax/12 by the choice of h.
            assert!(
                norm(&sub(&second, &x.k)) < 2e-3 * scale + 1e-4 * seg.max_curvature(),
                "k at {s}: {second:?} vs {:?}",
                x.k
            );
            // Short chords match their path length.
            let chord = norm(&sub(&b, &a));
            assert!(
                (chord / (2.0 * h) - 1.0).abs() < 1e-6 + (norm(&x.k) * h).powi(2),
                "chord at {s}: {}",
                chord / (2.0 * h) - 1.0
            );
        }
    }
    // The polyline through 2001 samples is a little shorter than the curve: each chord of
    // length Δs loses at most κ²Δs³/24.
    let ds = len / f64::from(n);
    let deficit = len * (seg.max_curvature() * ds).powi(2) / 24.0;
    assert!(
        polyline <= len * (1.0 + 1e-9) && polyline >= len - deficit - 1e-9 * len,
        "{polyline} vs {len}"
    );
    // Trimmed pieces follow the original.
    let piece = seg.trimmed(len * 0.3, len * 0.8);
    assert!((piece.length() - len * 0.5).abs() < 1e-9 * len);
    for i in 0..=20 {
        let s = piece.length() * f64::from(i) / 20.0;
        let (a, b) = (piece.sample(s), seg.sample(s + len * 0.3));
        assert!(norm(&sub(&a.p, &b.p)) < 1e-9 * len.max(1.0), "{s}");
        assert!(norm(&sub(&a.t, &b.t)) < 1e-9);
    }
    assert_eq!(seg.trimmed(len * 0.5, len).end(), *end);
}

#[test]
fn a_spline_through_points_passes_them_in_order() {
    let points = [
        p(&[0.0, 0.0]),
        p(&[10.0, 5.0]),
        p(&[20.0, -5.0]),
        p(&[30.0, 0.0]),
        p(&[35.0, 10.0]),
    ];
    let seg = Curve::spline(&points, 2).unwrap();
    check_curve(&seg, &points[0], &points[4]);
    let c = curve(&seg).unwrap();
    assert_eq!(c.kind(), CurveKind::Spline);
    let at: Vec<f64> = c.point_lengths().collect();
    assert_eq!(at.len(), points.len());
    for (s, q) in at.iter().zip(&points) {
        assert!(norm(&sub(&seg.sample(*s).p, q)) < 1e-9, "{s}");
    }
    assert!(at.windows(2).all(|w| w[0] < w[1]));
    // Natural end: no curvature at the ends.
    assert!(norm(&seg.sample(0.0).k) < 1e-12);
}

#[test]
fn a_spline_in_4d_carries_follow_axes() {
    // HMC: endpoint axes X, Y plus a follow axis; here all four axes are spline axes.
    let points = [
        p(&[0.0, 0.0, 0.0, 0.0]),
        p(&[10.0, 10.0, 1.0, 90.0]),
        p(&[20.0, 0.0, 2.0, 180.0]),
    ];
    let seg = Curve::spline(&points, 4).unwrap();
    check_curve(&seg, &points[0], &points[2]);
}

#[test]
fn collinear_or_two_points_are_a_line_and_bad_points_are_refused() {
    let two = Curve::spline(&[p(&[0.0, 0.0]), p(&[3.0, 4.0])], 2).unwrap();
    assert!(matches!(two, Segment::Line(_)));
    let on_line = Curve::spline(&[p(&[0.0, 0.0]), p(&[1.0, 1.0]), p(&[5.0, 5.0])], 2).unwrap();
    assert!(matches!(on_line, Segment::Line(_)));
    // Collinear but turning back: a real spline (it reverses along the line, with a cusp) —
    // refused for having no tangent at the turn.
    let back = Curve::spline(&[p(&[0.0, 0.0]), p(&[5.0, 0.0]), p(&[2.0, 0.0])], 2);
    assert!(back.is_err(), "{back:?}");
    let e = Curve::spline(&[p(&[0.0, 0.0]), p(&[0.0, 0.0]), p(&[1.0, 0.0])], 2);
    assert!(matches!(e, Err(GeometryError::Coincident { .. })), "{e:?}");
    assert!(Curve::spline(&[p(&[0.0, 0.0])], 2).is_err());
    let e = Curve::spline(&[p(&[0.0, 0.0]), p(&[f64::NAN, 0.0])], 2);
    assert!(matches!(e, Err(GeometryError::NotFinite { .. })), "{e:?}");
    let many: Vec<Point> = (0..1002)
        .map(|i| p(&[f64::from(i), (f64::from(i) * 0.1).sin()]))
        .collect();
    assert!(Curve::spline(&many, 2).is_err());
    assert!(Curve::spline(&many[..1001], 2).is_ok());
    assert!(Curve::spline(&[p(&[0.0, 0.0]), p(&[1.0, 0.0, 1.0])], 2).is_err());
    assert!(Curve::spline(&[p(&[0.0]), p(&[1.0])], 0).is_err());
}

/// The ellipse's perimeter by a fine midpoint rule on its parametric form, independent of the
/// crate.
fn perimeter(a: f64, b: f64) -> f64 {
    let n = 1_000_000;
    let h = TAU / f64::from(n);
    (0..n)
        .map(|i| {
            let phi = (f64::from(i) + 0.5) * h;
            (a * phi.sin()).hypot(b * phi.cos()) * h
        })
        .sum()
}

#[test]
fn nmc_ellipse_full_turn() {
    // Start (100,0), centre (0,0): semi-major 100 along x, ratio 0.5, counter-clockwise.
    let seg = Curve::ellipse(
        p(&[100.0, 0.0, 3.0]),
        p(&[0.0, 0.0]),
        0.5,
        (0, 1),
        Turn::Ccw,
        3,
    )
    .unwrap();
    check_curve(&seg, &p(&[100.0, 0.0, 3.0]), &p(&[100.0, 0.0, 3.0]));
    assert!((seg.length() - perimeter(100.0, 50.0)).abs() < 1e-8 * seg.length());
    // A quarter of the way round (by symmetry, a quarter of the length): (0, 50).
    let q = seg.sample(seg.length() / 4.0).p;
    assert!(norm(&sub(&q, &p(&[0.0, 50.0, 3.0]))) < 1e-6, "{q:?}");
    let cw = Curve::ellipse(p(&[100.0, 0.0]), p(&[0.0, 0.0]), 0.5, (0, 1), Turn::Cw, 2).unwrap();
    assert!(cw.sample(cw.length() / 4.0).p[1] < -49.999);
    // The largest curvature is at the ends of the major axis: a/b² = 100/2500.
    assert!(seg.max_curvature() >= 0.04 && seg.max_curvature() < 0.04 * 1.06);
    assert!(Curve::ellipse(p(&[1.0, 0.0]), p(&[0.0, 0.0]), 0.04, (0, 1), Turn::Cw, 2).is_err());
    assert!(Curve::ellipse(p(&[1.0, 0.0]), p(&[0.0, 0.0]), 1.01, (0, 1), Turn::Cw, 2).is_err());
    assert!(Curve::ellipse(p(&[0.0, 0.0]), p(&[0.0, 0.0]), 0.5, (0, 1), Turn::Cw, 2).is_err());
    // The flattest allowed ellipse.
    let flat =
        Curve::ellipse(p(&[400.0, 0.0]), p(&[0.0, 0.0]), 0.05, (0, 1), Turn::Ccw, 2).unwrap();
    check_curve(&flat, &p(&[400.0, 0.0]), &p(&[400.0, 0.0]));
    assert!((flat.length() - perimeter(400.0, 20.0)).abs() < 1e-8 * flat.length());
    // Ratio 1 is the circle.
    let circle =
        Curve::ellipse(p(&[10.0, 0.0]), p(&[0.0, 0.0]), 1.0, (0, 1), Turn::Ccw, 2).unwrap();
    assert!((circle.length() - TAU * 10.0).abs() < 1e-9);
}

#[test]
fn curves_move_with_a_transform() {
    let seg = Curve::ellipse(
        p(&[100.0, 0.0, 0.0]),
        p(&[0.0, 0.0]),
        0.3,
        (0, 1),
        Turn::Ccw,
        3,
    )
    .unwrap();
    let t = Transform::from_himc_pose([5.0, -7.0, 2.0, 10.0, 20.0, 30.0]).unwrap();
    let moved = seg.transformed(&t);
    assert!((moved.length() - seg.length()).abs() < 1e-12);
    for i in 0..=50 {
        let s = seg.length() * f64::from(i) / 50.0;
        let (a, b) = (seg.sample(s), moved.sample(s));
        assert!(norm(&sub(&b.p, &t.apply(&a.p))) < 1e-9);
        assert!(norm(&sub(&b.t, &t.apply_vector(&a.t))) < 1e-12);
        for axis in 0..3 {
            assert!(b.t[axis].abs() <= moved.max_tangent(axis) + 1e-12);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_splines_pass_the_checks(
        steps in prop::collection::vec(prop::array::uniform3(-50.0f64..50.0), 2..8),
    ) {
        let mut points = vec![p(&[0.0, 0.0, 0.0])];
        for d in &steps {
            let last = points[points.len() - 1];
            // Steps of at least 1 so no two points coincide.
            let mut next = last;
            for k in 0..3 {
                next[k] += d[k] + if d[k] >= 0.0 { 1.0 } else { -1.0 };
            }
            points.push(next);
        }
        // A random spline can have a cusp; that is refused with a typed error. Otherwise all
        // the curve checks hold.
        match Curve::spline(&points, 3) {
            Ok(seg) => check_curve(&seg, &points[0], &points[points.len() - 1]),
            Err(e) => prop_assert!(matches!(e, GeometryError::Invalid(_)), "{e:?}"),
        }
    }
}

/// A zigzag through `n` points after the start: tight turns, the table's worst case.
fn zigzag(n: u32) -> Vec<Point> {
    (0..=n)
        .map(|i| p(&[f64::from(i), if i % 2 == 0 { 0.0 } else { 1.0 }]))
        .collect()
}

#[test]
fn a_long_spline_builds_its_rows_only_where_it_is_sampled() {
    // Construction runs on the servo thread that accepts the command: it finds lengths and
    // bounds only; the refined rows come a span at a time as the path reaches them.
    let seg = Curve::spline(&zigzag(1000), 2).unwrap();
    let c = curve(&seg).unwrap();
    assert_eq!(c.table_len(), 0);
    let first = seg.sample(0.5);
    let built = c.table_len();
    assert!(
        (2..200).contains(&built),
        "one span's rows, not the table's: {built}"
    );
    // The middle of the curve, then its start again: one more span, nothing rebuilt.
    let _ = seg.sample(seg.length() / 2.0);
    assert!(c.table_len() < 2 * built + 200, "{}", c.table_len());
    assert_eq!(seg.sample(0.5), first);
}

#[test]
fn when_a_curves_rows_are_built_changes_no_sample() {
    let points = zigzag(40);
    let forward = Curve::spline(&points, 2).unwrap();
    let backward = Curve::spline(&points, 2).unwrap();
    let len = forward.length();
    assert_eq!(len, backward.length());
    let at: Vec<f64> = (0..=400).map(|i| len * f64::from(i) / 400.0).collect();
    // Built front to back in one, back to front in the other: the same samples, bit for bit.
    let ahead: Vec<_> = at.iter().map(|&s| forward.sample(s)).collect();
    let behind: Vec<_> = at.iter().rev().map(|&s| backward.sample(s)).collect();
    assert!(ahead.iter().eq(behind.iter().rev()));
    // A trimmed piece shares the table; a moved copy builds its own rows, the same lengths.
    let piece = forward.trimmed(len / 4.0, len / 2.0);
    assert_eq!(piece.sample(1.0), forward.sample(len / 4.0 + 1.0));
    let moved = forward.transformed(&Transform::translation(p(&[5.0, -2.0])).unwrap());
    let q = moved.sample(len / 3.0).p;
    let r = forward.sample(len / 3.0).p;
    assert!((q[0] - r[0] - 5.0).abs() < 1e-9 && (q[1] - r[1] + 2.0).abs() < 1e-9);
}

/// The planner's corner blend (issue 11 item 4): a quintic that leaves one segment and joins
/// the next with their tangents and curvatures (G2), inside the hull of its control points.
#[test]
fn a_corner_blend_matches_both_ends_to_the_curvature_and_stays_in_its_hull() {
    use path::geometry::{blend_control_points, PathPoint};
    let from = PathPoint {
        p: p(&[-1.0, 0.0]),
        t: p(&[1.0, 0.0]),
        k: p(&[0.0, 0.0]),
    };
    // A point of the circle of radius 5 about (0, 5), 90° turned: tangent (0, 1), curvature
    // toward the centre.
    let to = PathPoint {
        p: p(&[0.0, 1.0]),
        t: p(&[0.0, 1.0]),
        k: p(&[-0.2, 0.0]),
    };
    let seg = Curve::blend(&from, &to, 2).unwrap();
    assert_eq!(curve(&seg).unwrap().kind(), CurveKind::Blend);
    check_curve(&seg, &from.p, &to.p);
    let (a, b) = (seg.sample(0.0), seg.sample(seg.length()));
    assert!(norm(&sub(&a.t, &from.t)) < 1e-9 && norm(&sub(&b.t, &to.t)) < 1e-9);
    assert!(norm(&sub(&a.k, &from.k)) < 1e-6 && norm(&sub(&b.k, &to.k)) < 1e-6);
    let hull = blend_control_points(&from, &to);
    let corner = p(&[0.0, 0.0]);
    let reach = hull
        .iter()
        .map(|q| norm(&sub(q, &corner)))
        .fold(0.0, f64::max);
    for i in 0..=100 {
        let q = seg.sample(seg.length() * f64::from(i) / 100.0).p;
        assert!(norm(&sub(&q, &corner)) <= reach + 1e-12);
    }
    // Coincident points: refused.
    assert!(Curve::blend(&from, &from, 2).is_err());
}

/// Coordinates that move in proportion along a curve (NMC D8, HMC MoveND independent axes):
/// a spline in (x, y) lifted by a rise on z and on a fourth axis passes the curve checks, its
/// rise grows in proportion to the path length, and the shape keeps its share of the length.
#[test]
fn a_lifted_spline_moves_its_rise_in_proportion_to_the_length() {
    let points = [
        p(&[0.0, 0.0, 1.0, 2.0]),
        p(&[10.0, 5.0, 1.0, 2.0]),
        p(&[20.0, -5.0, 1.0, 2.0]),
        p(&[30.0, 0.0, 1.0, 2.0]),
    ];
    let flat = Curve::spline(&points, 4).unwrap();
    let flat = curve(&flat).unwrap().clone();
    let rise = p(&[0.0, 0.0, 12.0, -5.0]);
    let lifted = Segment::Curve(flat.lifted(&rise).unwrap());
    let end = p(&[30.0, 0.0, 13.0, -3.0]);
    check_curve(&lifted, &points[0], &end);
    let stretch = (1.0 + (13.0f64 / flat.length()).powi(2)).sqrt();
    assert!((lifted.length() - flat.length() * stretch).abs() < 1e-9);
    for i in 0..=10 {
        let s = lifted.length() * f64::from(i) / 10.0;
        let q = lifted.sample(s).p;
        let f = s / lifted.length();
        assert!((q[2] - (1.0 + 12.0 * f)).abs() < 1e-9, "z at {s}");
        assert!((q[3] - (2.0 - 5.0 * f)).abs() < 1e-9, "w at {s}");
    }
    let c = curve(&lifted).unwrap();
    let counted = [true, true, false, false, true, true, true, true, true];
    assert!((c.counted_share(&counted).unwrap() - 1.0 / stretch).abs() < 1e-12);
    // The rise on a coordinate of the shape is refused; so is counting it.
    assert!(flat.lifted(&p(&[1.0, 0.0, 0.0, 0.0])).is_err());
    assert!(c.counted_share(&[true; 9]).is_none());
    assert!(c.lifted(&rise).is_err());
}

#[test]
fn a_spline_built_in_steps_is_the_spline_built_at_once() {
    // Issue 11: the construction spread over servo ticks changes no bit of the curve.
    let points = zigzag(60);
    let whole = Curve::spline(&points, 2).unwrap();
    for chunk in [1, 3, 8, 59, 60, 1000] {
        let mut build = SplineBuild::new(&points, 2).unwrap();
        assert_eq!(build.remaining(), 60);
        let mut calls = 0;
        while !build.advance(chunk) {
            calls += 1;
        }
        assert_eq!(calls, 60_usize.div_ceil(chunk) - 1, "chunk {chunk}");
        assert_eq!(build.remaining(), 0);
        let stepped = build.finish().unwrap();
        assert_eq!(stepped.length().to_bits(), whole.length().to_bits());
        for axis in 0..2 {
            assert_eq!(stepped.max_tangent(axis), whole.max_tangent(axis));
        }
        assert_eq!(stepped.max_curvature(), whole.max_curvature());
        let len = whole.length();
        for i in 0..=200 {
            let s = len * f64::from(i) / 200.0;
            assert_eq!(stepped.sample(s), whole.sample(s), "chunk {chunk}, s {s}");
        }
    }
    // Finished early, the rest is done by `finish`; collinear points are a line at once; a
    // cusp is found only when the spans are visited.
    let early = SplineBuild::new(&points, 2).unwrap().finish().unwrap();
    assert_eq!(early.length().to_bits(), whole.length().to_bits());
    let on_line = SplineBuild::new(&[p(&[0.0, 0.0]), p(&[1.0, 1.0]), p(&[5.0, 5.0])], 2).unwrap();
    assert_eq!(on_line.remaining(), 0);
    assert!(matches!(on_line.finish(), Ok(Segment::Line(_))));
    let back = SplineBuild::new(&[p(&[0.0, 0.0]), p(&[5.0, 0.0]), p(&[2.0, 0.0])], 2).unwrap();
    assert!(matches!(back.finish(), Err(GeometryError::Invalid(_))));
}
