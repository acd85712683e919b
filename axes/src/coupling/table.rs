//! Cam tables: master → slave points, each span a cubic Hermite piece given by its end values
//! and end slopes. Linear tables use the chord as both slopes (the piece is the straight line),
//! cubic tables the slopes of the natural spline through the points (HMC_SplineCam), NMC
//! Follow tables the slopes of the PT rules with master travel for time (digest 001 §4.7):
//! NORMAL ends at 2·Δy/Δx − its start slope (the piece is a parabola), EVEN is the chord, STOP
//! ends at 0. Everything is computed when the table is defined; a sample is a binary search and
//! one Hermite evaluation.

use crate::command::{CamInterpolation, CamPoint, EngineError, FollowSegment};

/// Most points in one table: bounds the work at definition time and a sample's search.
pub const MAX_CAM_POINTS: usize = 4096;

/// A validated cam table.
#[derive(Clone, Debug, PartialEq)]
pub struct CamTable {
    xs: Vec<f64>,
    /// The first and last slave values.
    y_ends: (f64, f64),
    /// Per span i (from point i to i + 1), its polynomial.
    pieces: Vec<Piece>,
}

/// One span as y = y0 + c1·t + c2·t² + c3·t³, t = (x − x0) / h: the Hermite piece from its end
/// values and slopes, in a form that keeps t = 0 exact and a straight piece (equal chord
/// slopes) straight to rounding (c2 = c3 = 0). Computed once; a sample is a few multiplies.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Piece {
    x0: f64,
    /// The span's end: a sample from the last span checks x0 ≤ x < x1 on the piece alone.
    x1: f64,
    inv_h: f64,
    y0: f64,
    c1: f64,
    c2: f64,
    c3: f64,
}

impl Piece {
    fn new(x0: f64, x1: f64, y0: f64, y1: f64, m0: f64, m1: f64) -> Piece {
        let h = x1 - x0;
        let d = y1 - y0;
        Piece {
            x0,
            x1,
            inv_h: 1.0 / h,
            y0,
            c1: h * m0,
            c2: 3.0 * d - h * (2.0 * m0 + m1),
            c3: h * (m0 + m1) - 2.0 * d,
        }
    }

    #[inline]
    fn sample(&self, x: f64) -> CamSample {
        let t = ((x - self.x0) * self.inv_h).clamp(0.0, 1.0);
        let (c1, c2, c3) = (self.c1, self.c2, self.c3);
        CamSample {
            y: self.y0 + t * (c1 + t * (c2 + t * c3)),
            dy: (c1 + t * (2.0 * c2 + t * 3.0 * c3)) * self.inv_h,
            ddy: (2.0 * c2 + 6.0 * c3 * t) * self.inv_h * self.inv_h,
        }
    }
}

/// The table's value and its first two derivatives at one master coordinate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CamSample {
    pub y: f64,
    pub dy: f64,
    pub ddy: f64,
}

impl CamTable {
    /// Validate `points` (≥ 2, finite, master strictly increasing) and compute the slopes.
    pub fn new(
        table: u16,
        points: &[CamPoint],
        interpolation: CamInterpolation,
    ) -> Result<CamTable, EngineError> {
        let invalid = |reason: String| EngineError::InvalidCamTable { table, reason };
        if points.len() < 2 {
            return Err(invalid(format!(
                "{} point(s): a table needs at least 2",
                points.len()
            )));
        }
        if points.len() > MAX_CAM_POINTS {
            return Err(invalid(format!(
                "{} points: at most {MAX_CAM_POINTS}",
                points.len()
            )));
        }
        for (i, p) in points.iter().enumerate() {
            for v in [p.master, p.slave] {
                if !v.is_finite() || v.abs() > crate::command::MAX_MAGNITUDE {
                    return Err(invalid(format!(
                        "point {i}: {v} is not a finite number within ±1e12"
                    )));
                }
            }
        }
        for (i, w) in points.windows(2).enumerate() {
            if let [a, b] = w {
                if b.master <= a.master {
                    return Err(invalid(format!(
                        "master positions must increase: point {} ({}) is not after point {i} ({})",
                        i + 1,
                        b.master,
                        a.master
                    )));
                }
            }
        }
        let xs: Vec<f64> = points.iter().map(|p| p.master).collect();
        let ys: Vec<f64> = points.iter().map(|p| p.slave).collect();
        let chords: Vec<f64> = xs
            .windows(2)
            .zip(ys.windows(2))
            .map(|(x, y)| match (x, y) {
                ([x0, x1], [y0, y1]) => (y1 - y0) / (x1 - x0),
                _ => 0.0,
            })
            .collect();
        let slopes = match interpolation {
            CamInterpolation::Linear => chords.iter().map(|&c| (c, c)).collect(),
            CamInterpolation::Cubic => spline_slopes(&xs, &chords),
            CamInterpolation::Follow => follow_slopes(points, &chords),
        };
        let pieces = slopes
            .iter()
            .enumerate()
            .map(|(i, &(m0, m1))| Piece::new(xs[i], xs[i + 1], ys[i], ys[i + 1], m0, m1))
            .collect();
        Ok(CamTable {
            y_ends: (first(&ys), last(&ys)),
            xs,
            pieces,
        })
    }

    /// A table from knots `(master, slave, slope)` whose spans are exact polynomials of degree
    /// ≤ 3 (HMC's link profiles, `link`): each span is the Hermite piece of its end values and
    /// slopes. The caller gives at least 2 knots, master strictly increasing, all finite.
    pub(super) fn from_knots(knots: &[(f64, f64, f64)]) -> CamTable {
        let pieces = knots
            .windows(2)
            .filter_map(|w| match w {
                [(x0, y0, m0), (x1, y1, m1)] => Some(Piece::new(*x0, *x1, *y0, *y1, *m0, *m1)),
                _ => None,
            })
            .collect();
        let ys: Vec<f64> = knots.iter().map(|k| k.1).collect();
        CamTable {
            xs: knots.iter().map(|k| k.0).collect(),
            y_ends: (first(&ys), last(&ys)),
            pieces,
        }
    }

    /// The first and last master coordinates.
    pub fn master_range(&self) -> (f64, f64) {
        (first(&self.xs), last(&self.xs))
    }

    /// The first and last slave values.
    pub fn slave_range(&self) -> (f64, f64) {
        self.y_ends
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.xs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.xs.is_empty()
    }

    /// The span that holds `x` (clamped to the table): the last point at or before it.
    pub fn span_of(&self, x: f64) -> usize {
        let after = self.xs.partition_point(|&p| p <= x);
        after
            .saturating_sub(1)
            .min(self.pieces.len().saturating_sub(1))
    }

    /// The table at `x`, clamped to its master range.
    pub fn sample(&self, x: f64) -> CamSample {
        self.sample_span(self.span_of(x), x)
    }

    /// [`CamTable::sample`] starting from the span of the last sample (`span`, updated): O(1)
    /// while the master stays in it, a binary search when it leaves.
    #[inline]
    pub fn sample_from(&self, x: f64, span: &mut usize) -> CamSample {
        // Piece i spans xs[i] to xs[i + 1], so this is the search's own test, one load away.
        if let Some(piece) = self.pieces.get(*span) {
            if piece.x0 <= x && x < piece.x1 {
                return piece.sample(x);
            }
        }
        *span = self.span_of(x);
        self.sample_span(*span, x)
    }

    fn sample_span(&self, i: usize, x: f64) -> CamSample {
        match self.pieces.get(i) {
            Some(piece) => piece.sample(x),
            None => CamSample {
                y: self.y_ends.0,
                dy: 0.0,
                ddy: 0.0,
            },
        }
    }
}

fn first(v: &[f64]) -> f64 {
    v.first().copied().unwrap_or(0.0)
}

fn last(v: &[f64]) -> f64 {
    v.last().copied().unwrap_or(0.0)
}

/// Slopes of the natural cubic spline through the points (second derivative 0 at both ends),
/// from the tridiagonal system for the second derivatives (Thomas algorithm, O(n)).
fn spline_slopes(xs: &[f64], chords: &[f64]) -> Vec<(f64, f64)> {
    let n = xs.len();
    let h: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
    // Second derivatives M[0..n], M[0] = M[n-1] = 0.
    let mut m = vec![0.0; n];
    if n > 2 {
        let inner = n - 2;
        let mut diag = vec![0.0; inner];
        let mut rhs = vec![0.0; inner];
        let mut upper = vec![0.0; inner];
        for k in 0..inner {
            let (h0, h1) = (h[k], h[k + 1]);
            diag[k] = 2.0 * (h0 + h1);
            upper[k] = h1;
            rhs[k] = 6.0 * (chords[k + 1] - chords[k]);
        }
        // Forward sweep: the sub-diagonal of row k is h[k].
        for k in 1..inner {
            let w = h[k] / diag[k - 1];
            diag[k] -= w * upper[k - 1];
            rhs[k] -= w * rhs[k - 1];
        }
        for k in (0..inner).rev() {
            let next = if k + 1 < inner { m[k + 2] } else { 0.0 };
            m[k + 1] = (rhs[k] - upper[k] * next) / diag[k];
        }
    }
    (0..n - 1)
        .map(|i| {
            let hi = h[i];
            let s0 = chords[i] - hi * (2.0 * m[i] + m[i + 1]) / 6.0;
            let s1 = chords[i] + hi * (m[i] + 2.0 * m[i + 1]) / 6.0;
            (s0, s1)
        })
        .collect()
}

/// Slopes of NMC Follow segments: the ratio starts at 0 (the slave starts from rest, as PT's
/// v0 = 0); segment i's type is that of the point it ends at.
fn follow_slopes(points: &[CamPoint], chords: &[f64]) -> Vec<(f64, f64)> {
    let mut start = 0.0;
    chords
        .iter()
        .zip(points.iter().skip(1))
        .map(|(&c, p)| {
            let pair = match p.segment {
                FollowSegment::Normal | FollowSegment::Continuous => (start, 2.0 * c - start),
                FollowSegment::Even => (c, c),
                FollowSegment::Stop => (2.0 * c, 0.0),
            };
            start = pair.1;
            pair
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(p: &[(f64, f64)]) -> Vec<CamPoint> {
        p.iter()
            .map(|&(master, slave)| CamPoint {
                master,
                slave,
                segment: FollowSegment::Normal,
            })
            .collect()
    }

    #[test]
    fn every_interpolation_passes_through_its_points() {
        let p = pts(&[(0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 5.0)]);
        for mode in [
            CamInterpolation::Linear,
            CamInterpolation::Cubic,
            CamInterpolation::Follow,
        ] {
            let t = CamTable::new(0, &p, mode).unwrap();
            for q in &p {
                assert!((t.sample(q.master).y - q.slave).abs() < 1e-12, "{mode:?}");
            }
        }
    }

    #[test]
    fn the_natural_spline_is_smooth_at_inner_points_and_flat_at_the_ends() {
        let p = pts(&[(0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 5.0)]);
        let t = CamTable::new(0, &p, CamInterpolation::Cubic).unwrap();
        for x in [1.0, 3.0] {
            let a = t.sample(x - 1e-9);
            let b = t.sample(x + 1e-9);
            assert!((a.dy - b.dy).abs() < 1e-6);
            assert!((a.ddy - b.ddy).abs() < 1e-5);
        }
        assert!(t.sample(0.0).ddy.abs() < 1e-12);
        assert!(t.sample(4.0).ddy.abs() < 1e-9);
    }

    #[test]
    fn follow_normal_segments_ramp_the_ratio_from_rest_s_follow() {
        // S-FOLLOW's table with the start point (digest 001 §5, TV 59).
        let p = pts(&[
            (0.0, 0.0),
            (20000.0, 10000.0),
            (40000.0, 30000.0),
            (60000.0, 40000.0),
        ]);
        let t = CamTable::new(0, &p, CamInterpolation::Follow).unwrap();
        assert_eq!(t.sample(0.0).dy, 0.0);
        assert!((t.sample(20000.0).dy - 1.0).abs() < 1e-12);
        assert!((t.sample(30000.0).dy - 1.0).abs() < 1e-12);
        assert!(t.sample(60000.0).dy.abs() < 1e-12);
    }

    #[test]
    fn bad_tables_are_refused_naming_what_is_wrong() {
        let one = pts(&[(0.0, 0.0)]);
        assert!(matches!(
            CamTable::new(3, &one, CamInterpolation::Linear),
            Err(EngineError::InvalidCamTable { table: 3, .. })
        ));
        let back = pts(&[(0.0, 0.0), (2.0, 1.0), (1.0, 2.0)]);
        let e = CamTable::new(3, &back, CamInterpolation::Linear).unwrap_err();
        assert!(e.to_string().contains("must increase"), "{e}");
        let nan = pts(&[(0.0, 0.0), (f64::NAN, 1.0)]);
        assert!(CamTable::new(3, &nan, CamInterpolation::Cubic).is_err());
    }
}
