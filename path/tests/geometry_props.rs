//! Property tests over every segment constructor: exact start and end, unit tangents,
//! curvature norm = the arc's curvature, length = a fine numerical integration of the
//! sampled path, trimmed pieces follow the original; and the bad inputs each constructor
//! refuses with a typed error.

mod common;

use std::f64::consts::TAU;

use path::geometry::{dot, norm, sub, Arc, GeometryError, Line, Segment, Turn};
use path::{Point, MAX_AXES};
use proptest::prelude::*;

use common::{close, p};

/// The invariants of a segment; `scale` is the size of its coordinates (for tolerances).
fn check_segment(seg: &Segment, start: &Point, end: &Point, scale: f64) -> Result<(), String> {
    let tol = 1e-9 * scale.max(1.0);
    let len = seg.length();
    if !close(&seg.start(), start, tol) {
        return Err(format!("start {:?} vs {start:?}", seg.start()));
    }
    if seg.end() != *end || seg.sample(len).p != *end {
        return Err(format!("end {:?} vs {end:?}", seg.end()));
    }
    // Length by a fine polyline (converges from below as κ²Δs³/24 per piece).
    let n = 4000;
    let mut polyline = 0.0;
    let mut previous = seg.sample(0.0).p;
    for i in 1..=n {
        let s = len * f64::from(i) / f64::from(n);
        let x = seg.sample(s);
        polyline += norm(&sub(&x.p, &previous));
        previous = x.p;
        if (norm(&x.t) - 1.0).abs() > 1e-9 {
            return Err(format!("|t| = {} at {s}", norm(&x.t)));
        }
        if let Segment::Arc(a) = seg {
            if (norm(&x.k) - a.curvature()).abs() > 1e-9 * a.curvature().max(1.0 / scale) {
                return Err(format!("|k| = {} vs {}", norm(&x.k), a.curvature()));
            }
        }
        for axis in 0..MAX_AXES {
            if x.t[axis].abs() > seg.max_tangent(axis) + 1e-12 {
                return Err(format!("tangent bound of axis {axis} at {s}"));
            }
        }
    }
    let ds = len / f64::from(n);
    let deficit = len * (seg.max_curvature() * ds).powi(2) / 24.0;
    if polyline > len + tol || polyline < len - deficit - tol {
        return Err(format!("polyline {polyline} vs length {len}"));
    }
    // Trimmed pieces follow the original.
    let (a, b) = (len * 0.25, len * 0.9);
    let piece = seg.trimmed(a, b);
    if (piece.length() - (b - a)).abs() > tol {
        return Err(format!("trimmed length {} vs {}", piece.length(), b - a));
    }
    for i in 0..=10 {
        let s = piece.length() * f64::from(i) / 10.0;
        let (x, y) = (piece.sample(s), seg.sample(s + a));
        if !close(&x.p, &y.p, tol) || !close(&x.t, &y.t, 1e-9) {
            return Err(format!("trimmed piece leaves the original at {s}"));
        }
    }
    Ok(())
}

fn coord() -> impl Strategy<Value = f64> {
    -1000.0f64..1000.0
}

fn turn() -> impl Strategy<Value = Turn> {
    prop_oneof![Just(Turn::Cw), Just(Turn::Ccw)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    #[test]
    fn lines_in_n_dimensions(dims in 1usize..=9, a in prop::array::uniform9(coord()), b in prop::array::uniform9(coord())) {
        let (mut start, mut end) = (a, b);
        start.iter_mut().skip(dims).for_each(|x| *x = 0.0);
        end.iter_mut().skip(dims).for_each(|x| *x = 0.0);
        let seg = Segment::Line(Line::new(start, end, dims).unwrap());
        prop_assume!(seg.length() > 1e-6);
        check_segment(&seg, &start, &end, 1000.0).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn arcs_by_centre_with_helix_and_extra_axes(
        c in prop::array::uniform2(coord()),
        r in 1.0f64..500.0,
        a0 in 0.0f64..TAU,
        a1 in 0.0f64..TAU,
        rise in prop::array::uniform3(coord()),
        extra in 0u32..3,
        dir in turn(),
    ) {
        let start = p(&[c[0] + r * a0.cos(), c[1] + r * a0.sin(), 0.0, 5.0, -5.0]);
        let end = p(&[c[0] + r * a1.cos(), c[1] + r * a1.sin(), rise[0], rise[1], rise[2]]);
        let arc = Arc::from_center(start, end, p(&[c[0], c[1]]), (0, 1), dir, extra, 5).unwrap();
        check_segment(&Segment::Arc(arc), &start, &end, 1500.0).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn arcs_by_signed_radius(
        a in prop::array::uniform2(coord()),
        b in prop::array::uniform2(coord()),
        grow in 0.0f64..3.0,
        major in any::<bool>(),
        dir in turn(),
        z in coord(),
    ) {
        let (start, end) = (p(&[a[0], 0.0, a[1]]), p(&[b[0], z, b[1]]));
        let half = (a[0] - b[0]).hypot(a[1] - b[1]) / 2.0;
        prop_assume!(half > 1e-3);
        let r = half * (1.0 + grow);
        let radius = if major { -r } else { r };
        // The plane is axes (0, 2); axis 1 rises linearly.
        let arc = Arc::from_radius(start, end, radius, (0, 2), dir, 3).unwrap();
        prop_assert!((arc.radius() - r).abs() < 1e-9 * r.max(1.0));
        let side_ok = if major {
            arc.sweep() >= std::f64::consts::PI - 1e-9
        } else {
            arc.sweep() <= std::f64::consts::PI + 1e-9
        };
        prop_assert!(side_ok);
        check_segment(&Segment::Arc(arc), &start, &end, 3000.0).map_err(TestCaseError::fail)?;
        let e = Arc::from_radius(start, end, half * 0.99, (0, 2), dir, 3);
        let too_small = matches!(e, Err(GeometryError::RadiusTooSmall { .. }));
        prop_assert!(too_small);
    }

    #[test]
    fn arcs_through_three_points(
        dims in 2usize..=9,
        pts in prop::array::uniform3(prop::array::uniform9(coord())),
    ) {
        let mut pts = pts;
        for q in pts.iter_mut() {
            q.iter_mut().skip(dims).for_each(|x| *x = 0.0);
        }
        let [start, via, end] = pts;
        match Segment::through_points(start, via, end, dims) {
            Ok(seg) => {
                check_segment(&seg, &start, &end, 3000.0).map_err(TestCaseError::fail)?;
                // It passes through via: on the circle, at an angle inside the sweep.
                if let Segment::Arc(arc) = &seg {
                    let w = sub(&via, &arc.center());
                    let (u, v) = arc.basis();
                    let angle = dot(&w, &v).atan2(dot(&w, &u)).rem_euclid(TAU);
                    prop_assert!((norm(&w) - arc.radius()).abs() < 1e-6 * arc.radius().max(1.0));
                    prop_assert!(angle <= arc.sweep() + 1e-9, "{angle} > {}", arc.sweep());
                }
            }
            Err(e) => prop_assert!(false, "{e}"),
        }
    }

    #[test]
    fn arcs_about_a_normal(
        start in prop::array::uniform3(coord()),
        center in prop::array::uniform3(coord()),
        normal in prop::array::uniform3(-1.0f64..1.0),
        angle in -20.0f64..20.0,
    ) {
        prop_assume!(normal.iter().map(|x| x * x).sum::<f64>() > 1e-4 && angle.abs() > 1e-6);
        let (s, c) = (p(&start), p(&center));
        match Arc::about_normal(s, c, normal, angle, [0, 1, 2], 3) {
            Ok(arc) => {
                let end = arc.end();
                check_segment(&Segment::Arc(arc), &s, &end, 3000.0).map_err(TestCaseError::fail)?;
            }
            // Only when start is on the axis (radius 0).
            Err(e) => prop_assert!(matches!(e, GeometryError::Invalid(_)), "{e}"),
        }
    }

    #[test]
    fn arcs_by_centre_and_angle(
        start in prop::array::uniform2(coord()),
        center in prop::array::uniform2(coord()),
        angle in -20.0f64..20.0,
    ) {
        prop_assume!(angle.abs() > 1e-6);
        let (s, c) = (p(&start), p(&center));
        prop_assume!(norm(&sub(&s, &c)) > 1e-3);
        let arc = Arc::from_center_angle(s, c, angle, (0, 1), 2).unwrap();
        prop_assert!((arc.sweep() - angle.abs()).abs() < 1e-12);
        let end = arc.end();
        check_segment(&Segment::Arc(arc), &s, &end, 3000.0).map_err(TestCaseError::fail)?;
    }
}

#[test]
fn nmc_d8_line_carries_the_extra_axes() {
    // S-CRD-D8 / TV 47: a line over crd XYZ plus extra axes 3, 4, 5 (6 dimensions).
    let start = p(&[0.0; 6]);
    let end = p(&[9000.0, -9000.0, 9000.0, -9000.0, 9000.0, -9000.0]);
    let seg = Segment::Line(Line::new(start, end, 6).unwrap());
    assert_eq!(seg.end(), end);
    let half = seg.sample(seg.length() / 2.0).p;
    assert!(close(
        &half,
        &p(&[4500.0, -4500.0, 4500.0, -4500.0, 4500.0, -4500.0]),
        1e-9
    ));
    // HMC MoveND TV 17: 5 axes [10000, 20000, 30000, 180, 120]; every axis in proportion.
    let end = p(&[10000.0, 20000.0, 30000.0, 180.0, 120.0]);
    let seg = Segment::Line(Line::new(p(&[0.0; 5]), end, 5).unwrap());
    let q = seg.sample(seg.length() * 0.3).p;
    for k in 0..5 {
        assert!((q[k] - 0.3 * end[k]).abs() < 1e-9);
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let (a, b, c) = (p(&[1.0, 0.0]), p(&[0.0, 1.0]), p(&[0.0, 0.0]));
    let nan = p(&[f64::NAN, 0.0]);
    let inf = p(&[0.0, f64::INFINITY]);
    // Not finite.
    for bad in [nan, inf] {
        assert!(matches!(
            Line::new(bad, b, 2),
            Err(GeometryError::NotFinite { .. })
        ));
        assert!(matches!(
            Arc::from_center(a, bad, c, (0, 1), Turn::Cw, 0, 2),
            Err(GeometryError::NotFinite { .. })
        ));
        assert!(matches!(
            Arc::from_radius(a, bad, 2.0, (0, 1), Turn::Cw, 2),
            Err(GeometryError::NotFinite { .. })
        ));
        assert!(matches!(
            Segment::through_points(a, bad, b, 2),
            Err(GeometryError::NotFinite { .. })
        ));
        assert!(matches!(
            Arc::from_center_angle(a, bad, 1.0, (0, 1), 2),
            Err(GeometryError::NotFinite { .. })
        ));
        assert!(matches!(
            Arc::about_normal(a, bad, [0.0, 0.0, 1.0], 1.0, [0, 1, 2], 3),
            Err(GeometryError::NotFinite { .. })
        ));
    }
    assert!(matches!(
        Arc::from_center_angle(a, c, f64::INFINITY, (0, 1), 2),
        Err(GeometryError::NotFinite { .. })
    ));
    assert!(matches!(
        Arc::about_normal(a, c, [0.0, f64::NAN, 1.0], 1.0, [0, 1, 2], 3),
        Err(GeometryError::NotFinite { .. })
    ));
    // Dimensions out of 1..=9.
    for dims in [0, 10] {
        assert!(matches!(
            Line::new(a, b, dims),
            Err(GeometryError::Dimensions { .. })
        ));
        assert!(matches!(
            Arc::from_center(a, b, c, (0, 1), Turn::Cw, 0, dims),
            Err(GeometryError::Dimensions { .. })
        ));
        assert!(matches!(
            Arc::from_radius(a, b, 1.0, (0, 1), Turn::Cw, dims),
            Err(GeometryError::Dimensions { .. })
        ));
        assert!(matches!(
            Segment::through_points(a, b, p(&[-1.0, 0.0]), dims),
            Err(GeometryError::Dimensions { .. })
        ));
    }
    // Plane axes out of range or equal.
    assert!(matches!(
        Arc::from_center(a, b, c, (0, 2), Turn::Cw, 0, 2),
        Err(GeometryError::AxisOutOfRange { axis: 2, dims: 2 })
    ));
    assert!(matches!(
        Arc::from_center(a, b, c, (1, 1), Turn::Cw, 0, 2),
        Err(GeometryError::Invalid(_))
    ));
    assert!(matches!(
        Arc::about_normal(p(&[1.0]), c, [0.0, 0.0, 1.0], 1.0, [0, 1, 3], 3),
        Err(GeometryError::AxisOutOfRange { axis: 3, dims: 3 })
    ));
    // Centre not equidistant; centre at the start.
    assert!(matches!(
        Arc::from_center(a, p(&[0.0, 2.0]), c, (0, 1), Turn::Cw, 0, 2),
        Err(GeometryError::Invalid(_))
    ));
    assert!(matches!(
        Arc::from_center(c, b, c, (0, 1), Turn::Cw, 0, 2),
        Err(GeometryError::Invalid(_))
    ));
    // Zero normal.
    assert!(matches!(
        Arc::from_center_normal(a, b, c, [0.0; 3], Turn::Cw, 0, [0, 1, 2], 3),
        Err(GeometryError::Invalid(_))
    ));
    // Every error has a message that names the problem.
    let e = Arc::from_radius(a, b, 0.1, (0, 1), Turn::Cw, 2).unwrap_err();
    assert!(e.to_string().contains("smaller than half the chord"), "{e}");
}
