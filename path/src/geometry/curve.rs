//! Curves through points (HMC `MoveSplineND`, digest 000 §4.3: a C2 cubic spline) and
//! ellipses (NMC `CrdEllipse`, digest 001 §4.4), sampled by path length through a table
//! built once.
//!
//! A curve is a parametric shape `p(u)` (exact position, tangent and curvature at any `u`)
//! plus a table of `(s, u, du/ds, d²u/ds²)` rows, the lengths found by Gauss–Legendre
//! quadrature. `sample(s)` finds the table interval by binary search, interpolates `u(s)` with
//! a quintic Hermite (the rows' derivatives), and evaluates the shape at that `u`: the point is
//! on the curve exactly and the tangent has norm 1; only the `s ↔ u` mapping carries the
//! (small) interpolation error. The table is shared ([`std::sync::Arc`]), so clones and
//! trimmed pieces are cheap.
//!
//! The table is built in two passes, so that a command carrying a long spline does not stall
//! the servo thread that accepts it: construction finds each piece's length (a spline span, or
//! an eighth of an ellipse) and the bounds the planner needs (tangent components, curvature,
//! cusps), about 50 evaluations per piece; the rows of a piece, refined until `u(s)` is exact
//! to 1e-8 of a step (some 20 rows and 2 000 evaluations per span of a tight zigzag), are built
//! the first time a sample falls in it, a few pieces per tick at most. Lazily built rows are a
//! pure function of the shape and the piece, so when they are built changes nothing.

use std::f64::consts::TAU;
use std::sync::{Arc as Shared, OnceLock};

use super::{
    add, check_dims, check_finite, check_number, dot, norm, scale, sub, GeometryError, PathPoint,
    Segment, Turn, POINT_TOLERANCE,
};
use crate::frames::Transform;
use crate::{Point, MAX_AXES};

mod build;
pub use build::SplineBuild;

/// Most points of one spline (HMC: `uiSplineNum` 1 to 1000 nodes after the start).
pub const MAX_SPLINE_POINTS: usize = 1001;

/// Table intervals per spline span (one piece), per eighth of an ellipse (one piece of
/// eight), and for a corner blend (one piece).
const STEPS_PER_SPAN: usize = 4;
const ELLIPSE_PIECES: usize = 8;
const STEPS_PER_ELLIPSE_PIECE: usize = 8;
const BLEND_STEPS: usize = 8;
/// cos 30°: the most the tangent may turn between two bound evaluations.
const SHARPEST_STEP_COS: f64 = 0.866;
/// Extra evaluations per table interval when bounding the tangent and curvature.
const BOUND_SUBSTEPS: usize = 8;

/// The NMC ellipse's axis ratio range (`abRatio`, digest 001 §4.4).
pub const ELLIPSE_RATIO: std::ops::RangeInclusive<f64> = 0.05..=1.0;

#[derive(Clone, Debug, PartialEq)]
enum Shape {
    /// Span `i` covers `u ∈ [knots[i], knots[i+1]]`: `p = c[0] + c[1]·t + c[2]·t² + c[3]·t³`
    /// with `t = u − knots[i]`.
    Spline {
        knots: Vec<f64>,
        coefficients: Vec<[Point; 4]>,
        /// Coordinates `active..` have every coefficient exactly +0 (see [`active_axes`]): an
        /// evaluation skips them, which changes no bit of its result.
        active: usize,
    },
    /// `p(φ) = center + cos φ·major + sin φ·minor`, φ from 0 to 2π.
    Ellipse {
        center: Point,
        major: Point,
        minor: Point,
    },
    /// `p(u) = Σ c[i]·uⁱ`, u from 0 to 1: a corner blend (see [`Curve::blend`]).
    Quintic { coefficients: Box<[Point; 6]> },
}

/// One more than the last coordinate with a coefficient that is not exactly +0 in any span
/// (0 if none). Past it an evaluation's terms are `+0 + t·(+0 …) = +0`, the value `Eval::ZERO`
/// already holds, and a sum of squares adds +0: skipping them is exact, and a spline through
/// 2 of 9 coordinates evaluates about 4× faster (accepting a long spline costs mostly
/// evaluations).
fn active_axes(coefficients: &[[Point; 4]]) -> usize {
    coefficients
        .iter()
        .flat_map(|c| c.iter())
        .filter_map(|p| p.iter().rposition(|x| x.to_bits() != 0))
        .max()
        .map_or(0, |k| k + 1)
}

/// Position and the first two derivatives with respect to the parameter.
struct Eval {
    p: Point,
    d1: Point,
    d2: Point,
}

impl Eval {
    const ZERO: Eval = Eval {
        p: [0.0; MAX_AXES],
        d1: [0.0; MAX_AXES],
        d2: [0.0; MAX_AXES],
    };
}

impl Shape {
    // Several arrays indexed by the same axis: an index loop reads best.
    #[allow(clippy::needless_range_loop)]
    fn eval(&self, u: f64, span: usize) -> Eval {
        match self {
            Shape::Spline {
                knots,
                coefficients,
                active,
            } => {
                let span = span.min(coefficients.len().saturating_sub(1));
                let mut e = Eval::ZERO;
                let (Some(k0), Some(c)) = (knots.get(span), coefficients.get(span)) else {
                    return e;
                };
                let t = u - k0;
                for a in 0..(*active).min(MAX_AXES) {
                    let (c0, c1, c2, c3) = (c[0][a], c[1][a], c[2][a], c[3][a]);
                    e.p[a] = c0 + t * (c1 + t * (c2 + t * c3));
                    e.d1[a] = c1 + t * (2.0 * c2 + 3.0 * t * c3);
                    e.d2[a] = 2.0 * c2 + 6.0 * t * c3;
                }
                e
            }
            Shape::Ellipse {
                center,
                major,
                minor,
            } => {
                let (s, c) = u.sin_cos();
                let mut e = Eval::ZERO;
                for a in 0..MAX_AXES {
                    e.p[a] = center[a] + c * major[a] + s * minor[a];
                    e.d1[a] = -s * major[a] + c * minor[a];
                    e.d2[a] = -c * major[a] - s * minor[a];
                }
                e
            }
            Shape::Quintic { coefficients: c } => {
                let mut e = Eval::ZERO;
                for a in 0..MAX_AXES {
                    let (c0, c1, c2, c3, c4, c5) =
                        (c[0][a], c[1][a], c[2][a], c[3][a], c[4][a], c[5][a]);
                    e.p[a] = c0 + u * (c1 + u * (c2 + u * (c3 + u * (c4 + u * c5))));
                    e.d1[a] = c1 + u * (2.0 * c2 + u * (3.0 * c3 + u * (4.0 * c4 + u * 5.0 * c5)));
                    e.d2[a] = 2.0 * c2 + u * (6.0 * c3 + u * (12.0 * c4 + u * 20.0 * c5));
                }
                e
            }
        }
    }

    /// `|dp/du|` alone: the integrand of the arc length, evaluated far more often than
    /// anything else while a table is built.
    fn speed(&self, u: f64, span: usize) -> f64 {
        match self {
            Shape::Spline {
                knots,
                coefficients,
                active,
            } => {
                let span = span.min(coefficients.len().saturating_sub(1));
                let (Some(k0), Some(c)) = (knots.get(span), coefficients.get(span)) else {
                    return 0.0;
                };
                let t = u - k0;
                let mut sum = 0.0;
                for ((c1, c2), c3) in c[1].iter().zip(&c[2]).zip(&c[3]).take(*active) {
                    let d = c1 + t * (2.0 * c2 + 3.0 * t * c3);
                    sum += d * d;
                }
                sum.sqrt()
            }
            Shape::Ellipse { .. } | Shape::Quintic { .. } => norm(&self.eval(u, span).d1),
        }
    }

    fn transformed(&self, t: &Transform) -> Shape {
        match self {
            Shape::Spline {
                knots,
                coefficients,
                ..
            } => {
                let coefficients: Vec<[Point; 4]> = coefficients
                    .iter()
                    .map(|c| {
                        [
                            t.apply(&c[0]),
                            t.apply_vector(&c[1]),
                            t.apply_vector(&c[2]),
                            t.apply_vector(&c[3]),
                        ]
                    })
                    .collect();
                Shape::Spline {
                    knots: knots.clone(),
                    active: active_axes(&coefficients),
                    coefficients,
                }
            }
            Shape::Ellipse {
                center,
                major,
                minor,
            } => Shape::Ellipse {
                center: t.apply(center),
                major: t.apply_vector(major),
                minor: t.apply_vector(minor),
            },
            Shape::Quintic { coefficients: c } => Shape::Quintic {
                coefficients: Box::new([
                    t.apply(&c[0]),
                    t.apply_vector(&c[1]),
                    t.apply_vector(&c[2]),
                    t.apply_vector(&c[3]),
                    t.apply_vector(&c[4]),
                    t.apply_vector(&c[5]),
                ]),
            },
        }
    }
}

/// One table row: path length, parameter, `du/ds`, `d²u/ds²`, and the spline span the row
/// starts.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Row {
    s: f64,
    u: f64,
    du_ds: f64,
    d2u_ds2: f64,
    span: usize,
}

impl Row {
    fn new(s: f64, u: f64, e: &Eval, span: usize) -> Row {
        let speed2 = dot(&e.d1, &e.d1);
        Row {
            s,
            u,
            du_ds: 1.0 / speed2.sqrt(),
            // d/ds (1/|p'|) = −(p'·p'')/|p'|⁴.
            d2u_ds2: -dot(&e.d1, &e.d2) / (speed2 * speed2),
            span,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
struct Table {
    shape: Shape,
    /// In path order; the first starts at `s = 0`.
    pieces: Vec<Piece>,
    /// Bounds over the whole curve (see [`Curve::max_tangent`]).
    max_tangent: Point,
    max_curvature: f64,
    max_curvature_rate: f64,
}

/// A stretch of the curve with a length of its own: a spline span, or an eighth of an ellipse.
#[derive(Clone, Debug, PartialEq)]
struct Piece {
    /// Path length at the piece's start.
    s0: f64,
    length: f64,
    /// Parameter range, in `steps` equal table steps before refinement.
    u0: f64,
    u1: f64,
    steps: usize,
    /// The spline span `u` lies in (0 for an ellipse).
    span: usize,
    /// The rows from `u0` to `u1` inclusive, built on first use ([`Piece::rows`]).
    rows: OnceLock<Vec<Row>>,
}

impl Piece {
    /// The piece's table rows, built now if no sample has needed them before.
    fn rows(&self, shape: &Shape) -> &[Row] {
        self.rows.get_or_init(|| {
            let mut builder = Builder {
                shape,
                rows: Vec::with_capacity(self.steps + 1),
            };
            let mut s = self.s0;
            for k in 0..self.steps {
                let (a, b) = step_bounds(self.u0, self.u1, self.steps, k);
                s = builder.step(a, b, self.span, s, 0);
            }
            let mut rows = builder.rows;
            // The piece's own length is where the next piece starts: the last row says so
            // (the steps' lengths add up to it within 1e-12).
            let end = self.s0 + self.length;
            rows.push(Row::new(
                end,
                self.u1,
                &shape.eval(self.u1, self.span),
                self.span,
            ));
            rows
        })
    }
}

/// The `k`-th of `steps` equal parameter steps of `[u0, u1]`, ending exactly on `u1`.
fn step_bounds(u0: f64, u1: f64, steps: usize, k: usize) -> (f64, f64) {
    let at = |j: usize| u0 + (u1 - u0) * j as f64 / steps as f64;
    (at(k), if k + 1 == steps { u1 } else { at(k + 1) })
}

/// Which kind of curve, for status and errors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveKind {
    Spline,
    Ellipse,
    /// A corner blend the planner made between two segments ([`Curve::blend`]).
    Blend,
}

/// A curve sampled by path length (see the module doc). A trimmed curve shares its table.
///
/// Inputs: [`Curve::spline`] or [`Curve::ellipse`] (once; they build the table). Outputs, in
/// any order and as often as needed: [`Curve::length`], [`Curve::sample`], [`Curve::end`],
/// the bounds [`Curve::max_tangent`] and [`Curve::max_curvature`]; [`Curve::trimmed`] and
/// [`Curve::transformed`] make new curves.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    table: Shared<Table>,
    kind: CurveKind,
    /// Length along the shape (the table's) of this piece's start on the shared table.
    s0: f64,
    /// Path length of this piece (the shape's length × `lift.stretch`).
    length: f64,
    end: Point,
    dims: usize,
    lift: Lift,
}

/// Coordinates that move in proportion along a curve without being part of its shape (NMC
/// D8's extra axes, HMC MoveND's independent axes; see [`Curve::lifted`]): at length `σ` along
/// the shape the point is `shape(σ) + (σ/L)·rise`, `L` the whole shape's length. The rise is
/// orthogonal to the shape (on coordinates the shape does not move), so the path length is
/// the shape's × `stretch = √(1 + |rise/L|²)` everywhere, like a helix's.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Lift {
    rise: Point,
    shape_length: f64,
    stretch: f64,
}

impl Lift {
    const NONE: Lift = Lift {
        rise: [0.0; MAX_AXES],
        shape_length: 1.0,
        stretch: 1.0,
    };

    /// The rise per length along the shape.
    fn slope(&self) -> Point {
        scale(&self.rise, 1.0 / self.shape_length)
    }
}

/// 5-point Gauss–Legendre nodes and weights on [−1, 1].
const GAUSS: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// The length of `p(u)` for `u ∈ [u0, u1]`: 5-point Gauss–Legendre, halved until the halves
/// agree with the whole to 1e-12 (relative) or 8 levels deep (the speed |p'| has a kink
/// where it nears 0 in a tight turn, where a single rule is poor).
fn arc_length(shape: &Shape, u0: f64, u1: f64, span: usize) -> f64 {
    let whole = gauss_length(shape, u0, u1, span);
    refined_length(shape, u0, u1, span, whole, 0)
}

/// One 5-point Gauss–Legendre rule over `[a, b]`.
fn gauss_length(shape: &Shape, a: f64, b: f64, span: usize) -> f64 {
    let half = (b - a) / 2.0;
    GAUSS
        .iter()
        .map(|&(x, w)| w * shape.speed(a + half * (1.0 + x), span))
        .sum::<f64>()
        * half
}

/// [`arc_length`] given the single rule's value over the interval, so that each level of
/// the halving evaluates each half once.
fn refined_length(shape: &Shape, u0: f64, u1: f64, span: usize, whole: f64, depth: u32) -> f64 {
    let mid = (u0 + u1) / 2.0;
    let left = gauss_length(shape, u0, mid, span);
    let right = gauss_length(shape, mid, u1, span);
    let halves = left + right;
    if depth >= 8 || (whole - halves).abs() <= 1e-12 * halves.abs() {
        return halves;
    }
    refined_length(shape, u0, mid, span, left, depth + 1)
        + refined_length(shape, mid, u1, span, right, depth + 1)
}

/// The rows of one piece being built.
struct Builder<'a> {
    shape: &'a Shape,
    rows: Vec<Row>,
}

/// How far the table's `u(s)` may stray from the curve's inside a step, as a distance
/// along the curve relative to the step's length.
const TABLE_TOLERANCE: f64 = 1e-8;
/// Most halvings of one step.
const MAX_REFINE_DEPTH: u32 = 12;

impl Builder<'_> {
    /// Adds the rows of the step `[u0, u1]` starting at path length `s0`, halving it while
    /// the interpolated `u` inside the step misses the true one; returns `s` at `u1`.
    fn step(&mut self, u0: f64, u1: f64, span: usize, s0: f64, depth: u32) -> f64 {
        let shape = self.shape;
        let length = arc_length(shape, u0, u1, span);
        let um = (u0 + u1) / 2.0;
        let a = Row::new(s0, u0, &shape.eval(u0, span), span);
        let b = Row::new(s0 + length, u1, &shape.eval(u1, span), span);
        // The interpolation's error vanishes at both ends and may be odd about the middle,
        // so it is checked at the quarter points.
        let miss_at = |f: f64| {
            let uq = u0 + (u1 - u0) * f;
            let sq = s0 + arc_length(shape, u0, uq, span);
            (hermite(&a, &b, sq) - uq).abs() * shape.speed(uq, span)
        };
        let miss = miss_at(0.25).max(miss_at(0.75));
        let fine = miss <= TABLE_TOLERANCE * length || !miss.is_finite();
        if !fine && depth < MAX_REFINE_DEPTH {
            let s_mid = self.step(u0, um, span, s0, depth + 1);
            return self.step(um, u1, span, s_mid, depth + 1);
        }
        self.rows.push(a);
        s0 + length
    }
}

/// The bounds of a curve, gathered over evaluations in path order.
#[derive(Clone, Debug)]
struct Bounds {
    max_tangent: Point,
    max_curvature: f64,
    /// The largest |Δκ|/Δs between two neighbouring evaluations (`κ` the curvature vector).
    max_curvature_rate: f64,
    min_speed: f64,
    /// The longest stretch between two evaluations (its length bound).
    spacing: f64,
    previous_tangent: Option<Point>,
    sharp: bool,
    /// The curvature at each evaluation of the piece being visited (a buffer).
    kappa: Vec<f64>,
}

impl Bounds {
    fn new() -> Bounds {
        Bounds {
            max_tangent: [0.0; MAX_AXES],
            max_curvature: 0.0,
            max_curvature_rate: 0.0,
            min_speed: f64::INFINITY,
            spacing: 0.0,
            previous_tangent: None,
            sharp: false,
            kappa: Vec::new(),
        }
    }

    /// [`BOUND_SUBSTEPS`] evaluations per step over the piece `[u0, u1]` of `steps` steps
    /// (both ends included), and each curvature peak among them searched for between its
    /// neighbours: the peaks of a tight turn are narrower than the evaluations' spacing.
    fn visit_piece(&mut self, shape: &Shape, (u0, u1): (f64, f64), steps: usize, span: usize) {
        let n = steps * BOUND_SUBSTEPS;
        let du = (u1 - u0) / n as f64;
        let at = |k: usize| if k == n { u1 } else { u0 + du * k as f64 };
        let mut fastest: f64 = 0.0;
        let mut kappa = std::mem::take(&mut self.kappa);
        kappa.clear();
        let mut previous: Option<(Point, f64)> = None;
        for k in 0..=n {
            let e = shape.eval(at(k), span);
            let speed = norm(&e.d1);
            fastest = fastest.max(speed);
            let kv = curvature(&e);
            kappa.push(norm(&kv));
            if let Some((kp, sp)) = previous {
                let ds = 0.5 * (sp + speed) * du.abs();
                if ds > 0.0 {
                    let rate = norm(&sub(&kv, &kp)) / ds;
                    if rate.is_finite() {
                        self.max_curvature_rate = self.max_curvature_rate.max(rate);
                    }
                }
            }
            previous = Some((kv, speed));
            if k == n {
                break;
            }
            self.min_speed = self.min_speed.min(speed);
            if speed > 0.0 {
                let t = scale(&e.d1, 1.0 / speed);
                for (m, d) in self.max_tangent.iter_mut().zip(&t) {
                    *m = f64::max(*m, d.abs());
                }
                // A turn of more than ~30° between two evaluations is a cusp or a kink the
                // table cannot follow.
                if self
                    .previous_tangent
                    .is_some_and(|prev| dot(&prev, &t) < SHARPEST_STEP_COS)
                {
                    self.sharp = true;
                }
                self.previous_tangent = Some(t);
            }
        }
        for (k, &here) in kappa.iter().enumerate() {
            let left = k.checked_sub(1).and_then(|j| kappa.get(j)).copied();
            let right = kappa.get(k + 1).copied();
            self.max_curvature = self.max_curvature.max(here);
            let peak = left.is_none_or(|l| here >= l) && right.is_none_or(|r| here >= r);
            if peak && here.is_finite() {
                let (a, b) = (at(k.saturating_sub(1)), at((k + 1).min(n)));
                self.max_curvature = self.max_curvature.max(curvature_peak(shape, span, a, b));
            }
        }
        self.kappa = kappa;
        // Between two evaluations the curve runs at most Δu × the speed there; the fastest
        // evaluation of the piece, with a margin for the speed between them.
        self.spacing = self.spacing.max(1.25 * fastest * du);
    }
}

/// The largest curvature on `[a, b]` found by golden-section search (a single peak assumed,
/// which the caller's bracketing makes likely); 24 evaluations narrow it to 1e-5 of `b − a`.
fn curvature_peak(shape: &Shape, span: usize, mut a: f64, mut b: f64) -> f64 {
    const INVERSE_PHI: f64 = 0.618_033_988_749_895;
    let kappa = |u: f64| norm(&curvature(&shape.eval(u, span)));
    let mut c = b - INVERSE_PHI * (b - a);
    let mut d = a + INVERSE_PHI * (b - a);
    let (mut kc, mut kd) = (kappa(c), kappa(d));
    let mut best = kc.max(kd);
    for _ in 0..24 {
        if kc >= kd {
            b = d;
            d = c;
            kd = kc;
            c = b - INVERSE_PHI * (b - a);
            kc = kappa(c);
        } else {
            a = c;
            c = d;
            kc = kd;
            d = a + INVERSE_PHI * (b - a);
            kd = kappa(d);
        }
        best = best.max(kc).max(kd);
    }
    if best.is_finite() {
        best
    } else {
        0.0
    }
}

/// The quintic Hermite `u(s)` between two rows (their `u`, `du/ds` and `d²u/ds²`), clamped to
/// the interval.
fn hermite(a: &Row, b: &Row, s: f64) -> f64 {
    let h = b.s - a.s;
    if h <= 0.0 {
        return a.u;
    }
    let x = ((s - a.s) / h).clamp(0.0, 1.0);
    let (x2, x3) = (x * x, x * x * x);
    let (x4, x5) = (x3 * x, x3 * x2);
    let h2 = h * h;
    let u = (1.0 - 10.0 * x3 + 15.0 * x4 - 6.0 * x5) * a.u
        + (x - 6.0 * x3 + 8.0 * x4 - 3.0 * x5) * h * a.du_ds
        + 0.5 * (x2 - 3.0 * x3 + 3.0 * x4 - x5) * h2 * a.d2u_ds2
        + 0.5 * (x3 - 2.0 * x4 + x5) * h2 * b.d2u_ds2
        + (-4.0 * x3 + 7.0 * x4 - 3.0 * x5) * h * b.du_ds
        + (10.0 * x3 - 15.0 * x4 + 6.0 * x5) * b.u;
    u.clamp(a.u.min(b.u), a.u.max(b.u))
}

/// The table's pieces `(u0, u1, steps, span)` with their lengths and the curve's bounds; the
/// rows wait for their first sample (module doc). All at once: [`build::TableBuild`] does it
/// piece by piece.
fn build_table(
    shape: Shape,
    pieces: impl Iterator<Item = (f64, f64, usize, usize)>,
) -> Result<Table, GeometryError> {
    build::TableBuild::new(shape, pieces.collect()).finish()
}

/// The curvature vector `d²p/ds²` from the parameter derivatives.
fn curvature(e: &Eval) -> Point {
    let speed2 = dot(&e.d1, &e.d1);
    if speed2 <= 0.0 {
        return [0.0; MAX_AXES];
    }
    let along = dot(&e.d2, &e.d1) / speed2;
    scale(&sub(&e.d2, &scale(&e.d1, along)), 1.0 / speed2)
}

impl Curve {
    /// The natural cubic spline (C2, second derivative 0 at both ends) through `points`
    /// (the first is the start), parametrised by chord length, over the first `dims` axes.
    /// HMC's `MoveSplineND` gives its spline as "cubic, C2-continuous" without end conditions
    /// or parametrisation (digest 000 §4.3); these are ours (docs/decisions.md). Two points, or
    /// points all on one line in order, give a [`Line`] (HMC: "collinear nodes → a straight
    /// line"; "a single node → the segment from the origin to it"). Consecutive equal points,
    /// fewer than 2 or more than [`MAX_SPLINE_POINTS`] points are refused.
    /// [`SplineBuild`] does the same in steps.
    pub fn spline(points: &[Point], dims: usize) -> Result<Segment, GeometryError> {
        SplineBuild::new(points, dims)?.finish()
    }

    /// NMC `CrdEllipse` (digest 001 §4.4): the full ellipse from `start` around `center`
    /// (only its coordinates in `plane` are used) turning `turn`, back to `start`; the
    /// semi-major axis is start − centre and the semi-minor axis `ratio` × that
    /// (`abRatio` ∈ [0.05, 1]; 1 is a circle).
    pub fn ellipse(
        start: Point,
        center: Point,
        ratio: f64,
        plane: (usize, usize),
        turn: Turn,
        dims: usize,
    ) -> Result<Segment, GeometryError> {
        super::check_planar(plane, dims, &[("start", &start), ("center", &center)])?;
        check_number("ratio", ratio)?;
        if !ELLIPSE_RATIO.contains(&ratio) {
            return Err(GeometryError::Invalid(
                "an ellipse's axis ratio is 0.05 to 1",
            ));
        }
        let (i, j) = plane;
        let (ax, ay) = (start[i] - center[i], start[j] - center[j]);
        let a = ax.hypot(ay);
        if a <= POINT_TOLERANCE {
            return Err(GeometryError::Invalid(
                "the ellipse's centre is its start point",
            ));
        }
        let mut c = start;
        c[i] = center[i];
        c[j] = center[j];
        let mut major = [0.0; MAX_AXES];
        major[i] = ax;
        major[j] = ay;
        let mut minor = [0.0; MAX_AXES];
        let sign = turn.sign();
        minor[i] = -ay * ratio * sign;
        minor[j] = ax * ratio * sign;
        let pieces = (0..ELLIPSE_PIECES).map(|k| {
            let (u0, u1) = step_bounds(0.0, TAU, ELLIPSE_PIECES, k);
            (u0, u1, STEPS_PER_ELLIPSE_PIECE, 0)
        });
        let table = build_table(
            Shape::Ellipse {
                center: c,
                major,
                minor,
            },
            pieces,
        )?;
        Ok(Segment::Curve(Curve::whole(
            table,
            CurveKind::Ellipse,
            start,
            dims,
        )))
    }

    /// The corner blend from `from` to `to` (each a point with its unit tangent and curvature
    /// vector): the quintic `p(u)`, u ∈ [0, 1], with `p(0) = from.p`, `p'(0) = λ·from.t`,
    /// `p''(0) = λ²·from.k` and the same at `u = 1` with `to`, `λ` the chord length. So the
    /// blend joins both segments with the same tangent and the same curvature (G2): no
    /// velocity and no centripetal-acceleration step at its ends (docs/decisions.md, "Blends
    /// between any segments"). It lies inside the convex hull of [`blend_control_points`].
    /// Refused (as any curve) when it would have a cusp.
    #[allow(clippy::needless_range_loop)]
    pub fn blend(from: &PathPoint, to: &PathPoint, dims: usize) -> Result<Segment, GeometryError> {
        check_dims(dims)?;
        check_finite("blend start", &from.p)?;
        check_finite("blend end", &to.p)?;
        let chord = norm(&sub(&to.p, &from.p));
        if chord.is_nan() || chord <= POINT_TOLERANCE {
            return Err(GeometryError::Invalid("a blend needs two distinct points"));
        }
        let (v0, a0) = (scale(&from.t, chord), scale(&from.k, chord * chord));
        let (v1, a1) = (scale(&to.t, chord), scale(&to.k, chord * chord));
        let mut c = [[0.0; MAX_AXES]; 6];
        for k in 0..MAX_AXES {
            // The quintic Hermite: c0..c2 from the start, c3..c5 so that the end matches.
            let d = to.p[k] - from.p[k] - v0[k] - 0.5 * a0[k];
            let e = v1[k] - v0[k] - a0[k];
            let f = a1[k] - a0[k];
            c[0][k] = from.p[k];
            c[1][k] = v0[k];
            c[2][k] = 0.5 * a0[k];
            c[3][k] = 10.0 * d - 4.0 * e + 0.5 * f;
            c[4][k] = -15.0 * d + 7.0 * e - f;
            c[5][k] = 6.0 * d - 3.0 * e + 0.5 * f;
        }
        let table = build_table(
            Shape::Quintic {
                coefficients: Box::new(c),
            },
            std::iter::once((0.0, 1.0, BLEND_STEPS, 0)),
        )?;
        Ok(Segment::Curve(Curve::whole(
            table,
            CurveKind::Blend,
            to.p,
            dims,
        )))
    }

    fn whole(table: Table, kind: CurveKind, end: Point, dims: usize) -> Curve {
        let length = table.pieces.last().map_or(0.0, |p| p.s0 + p.length);
        Curve {
            table: Shared::new(table),
            kind,
            s0: 0.0,
            length,
            end,
            dims,
            lift: Lift::NONE,
        }
    }

    /// This curve (whole, not trimmed, without a rise yet) with `rise` added in proportion to
    /// the length along it (see `Lift`): it ends at `end + rise`. The rise must lie on
    /// coordinates the curve does not move (its tangent bound 0 there), so the path length
    /// grows by the same factor everywhere and the coordinates of the rise move in
    /// proportion to the curve's own length (NMC D8, HMC MoveND independent axes).
    pub fn lifted(&self, rise: &Point) -> Result<Curve, GeometryError> {
        check_finite("rise", rise)?;
        if self.s0 != 0.0 || self.lift != Lift::NONE {
            return Err(GeometryError::Invalid(
                "only a whole curve without a rise can be lifted",
            ));
        }
        let crosses = rise
            .iter()
            .zip(&self.table.max_tangent)
            .any(|(r, t)| *r != 0.0 && *t != 0.0);
        if crosses {
            return Err(GeometryError::Invalid(
                "the coordinates moved in proportion must not be part of the curve's shape",
            ));
        }
        let shape_length = self.length;
        if !(shape_length > 0.0 && shape_length.is_finite()) {
            return Err(GeometryError::Invalid(
                "a curve of length 0 cannot be lifted",
            ));
        }
        let slope = norm(rise) / shape_length;
        let stretch = (1.0 + slope * slope).sqrt();
        Ok(Curve {
            length: shape_length * stretch,
            end: add(&self.end, rise),
            lift: Lift {
                rise: *rise,
                shape_length,
                stretch,
            },
            ..self.clone()
        })
    }

    /// The share of the path length that the coordinates not in the rise make (`1/stretch`),
    /// when the shape lies wholly on `counted` coordinates and the rise wholly on the others
    /// (then it is the same along the whole curve); else `None`.
    pub fn counted_share(&self, counted: &[bool]) -> Option<f64> {
        let flag = |k: usize| counted.get(k).copied().unwrap_or(false);
        let shape_in = self
            .table
            .max_tangent
            .iter()
            .enumerate()
            .all(|(k, t)| *t == 0.0 || flag(k));
        let rise_out = self
            .lift
            .rise
            .iter()
            .enumerate()
            .all(|(k, r)| *r == 0.0 || !flag(k));
        (shape_in && rise_out).then(|| 1.0 / self.lift.stretch)
    }

    pub fn kind(&self) -> CurveKind {
        self.kind
    }

    pub fn length(&self) -> f64 {
        self.length
    }

    pub fn dims(&self) -> usize {
        self.dims
    }

    /// The end point, exactly as programmed.
    pub fn end(&self) -> Point {
        self.end
    }

    /// Rows of the length table built so far (memory and lookup cost; a piece's rows are
    /// built when a sample first falls in it).
    pub fn table_len(&self) -> usize {
        self.table
            .pieces
            .iter()
            .filter_map(|p| p.rows.get())
            .map(Vec::len)
            .sum()
    }

    /// For a spline, the path lengths (from this piece's start) at which it passes its
    /// points, within the piece; empty for an ellipse.
    pub fn point_lengths(&self) -> impl Iterator<Item = f64> + '_ {
        let spline = matches!(self.table.shape, Shape::Spline { .. });
        let pieces = if spline { &self.table.pieces[..] } else { &[] };
        // Each span starts at a point; the last point ends the last span.
        pieces
            .iter()
            .map(|p| p.s0)
            .chain(pieces.last().map(|p| p.s0 + p.length))
            .map(move |s| (s - self.s0) * self.lift.stretch)
            .filter(move |&s| (0.0..=self.length).contains(&s))
    }

    /// A bound on |tangent component| of `axis` over the whole curve (≤ 1): the largest
    /// value at 8 evaluations per table step, padded by the most the tangent can turn between
    /// them (curvature × spacing). For a trimmed piece, the whole curve's bound.
    pub fn max_tangent(&self, axis: usize) -> f64 {
        let shape = self.table.max_tangent.get(axis).copied().unwrap_or(0.0);
        let rise = self.lift.slope().get(axis).map_or(0.0, |r| r.abs());
        ((shape + rise) / self.lift.stretch).min(1.0)
    }

    /// A bound on the curvature over the whole curve: the largest evaluated value + 5 %.
    pub fn max_curvature(&self) -> f64 {
        let k = self.lift.stretch;
        self.table.max_curvature / (k * k)
    }

    /// An estimate from above of `|dκ/ds|` over the whole curve (`κ` the curvature vector,
    /// so this is `|d³p/ds³|`): the largest difference quotient between neighbouring bound
    /// evaluations + 25 %. The planner's jerk rule on curves uses it.
    pub fn max_curvature_rate(&self) -> f64 {
        self.table.max_curvature_rate / self.lift.stretch.powi(3)
    }

    /// The point, unit tangent and curvature vector at path length `s` (clamped).
    pub fn sample(&self, s: f64) -> PathPoint {
        let s = if s.is_nan() {
            0.0
        } else {
            s.clamp(0.0, self.length)
        };
        let lift = &self.lift;
        let sigma = self.s0 + s / lift.stretch;
        let (u, span) = self.parameter_at(sigma);
        let e = self.table.shape.eval(u, span);
        let speed = norm(&e.d1);
        let t = if speed > 0.0 {
            scale(&e.d1, 1.0 / speed)
        } else {
            [0.0; MAX_AXES]
        };
        if *lift == Lift::NONE {
            let p = if s >= self.length { self.end } else { e.p };
            return PathPoint {
                p,
                t,
                k: curvature(&e),
            };
        }
        // d/ds = (1/stretch)·d/dσ: the tangent gains the rise's slope, the curvature shrinks.
        let p = if s >= self.length {
            self.end
        } else {
            add(&e.p, &scale(&lift.rise, sigma / lift.shape_length))
        };
        let k = lift.stretch;
        PathPoint {
            p,
            t: scale(&add(&t, &lift.slope()), 1.0 / k),
            k: scale(&curvature(&e), 1.0 / (k * k)),
        }
    }

    /// `u(s)` on the shared table: binary search, then the quintic Hermite through the
    /// interval's ends with their `du/ds` and `d²u/ds²` (so the path speed and the
    /// acceleration along the path carry almost no table ripple).
    fn parameter_at(&self, s: f64) -> (f64, usize) {
        let pieces = &self.table.pieces;
        // The last piece that starts at or before s.
        let Some(piece) = pieces.get(pieces.partition_point(|p| p.s0 <= s).saturating_sub(1))
        else {
            return (0.0, 0);
        };
        let rows = piece.rows(&self.table.shape);
        // The last row with row.s ≤ s.
        let k = rows.partition_point(|r| r.s <= s).saturating_sub(1);
        let (Some(a), Some(b)) = (rows.get(k), rows.get(k + 1)) else {
            return rows.last().map_or((0.0, 0), |r| (r.u, r.span));
        };
        (hermite(a, b, s), a.span)
    }

    /// The piece from `s0` to `s1` (clamped, `s0 ≤ s1`), sharing the table; `s1 = length`
    /// keeps the exact end.
    pub fn trimmed(&self, s0: f64, s1: f64) -> Curve {
        let s0 = s0.clamp(0.0, self.length);
        let s1 = s1.clamp(s0, self.length);
        let end = if s1 >= self.length {
            self.end
        } else {
            self.sample(s1).p
        };
        Curve {
            table: Shared::clone(&self.table),
            kind: self.kind,
            s0: self.s0 + s0 / self.lift.stretch,
            length: s1 - s0,
            end,
            dims: self.dims,
            lift: self.lift,
        }
    }

    /// The curve moved by a rigid transform: its shape is moved, the pieces' lengths (a
    /// function of the shape's lengths only) are kept; the tangent bounds are recomputed
    /// from the rotation (each axis's bound becomes the sum over the source axes it mixes).
    pub fn transformed(&self, t: &Transform) -> Curve {
        let table = &self.table;
        let r = t.rotation_part();
        let mut max_tangent = [0.0; MAX_AXES];
        for (out, row) in max_tangent.iter_mut().zip(&r) {
            *out = row
                .iter()
                .zip(&table.max_tangent)
                .map(|(x, m)| x.abs() * m)
                .sum::<f64>()
                .min(1.0);
        }
        Curve {
            table: Shared::new(Table {
                shape: table.shape.transformed(t),
                // Lengths are kept; rows are rebuilt from the moved shape when sampled (not
                // shared: which curve built them first must not change a value).
                pieces: table
                    .pieces
                    .iter()
                    .map(|p| Piece {
                        rows: OnceLock::new(),
                        ..p.clone()
                    })
                    .collect(),
                max_tangent,
                max_curvature: table.max_curvature,
                max_curvature_rate: table.max_curvature_rate,
            }),
            end: t.apply(&self.end),
            lift: Lift {
                rise: t.apply_vector(&self.lift.rise),
                ..self.lift
            },
            ..self.clone()
        }
    }
}

/// The Bézier control points of [`Curve::blend`]`(from, to)`: the blend lies in their convex
/// hull, so within `max |B_i − q|` of any point `q` (the planner's deviation bound).
// Six arrays indexed by the same axis: an index loop reads best.
#[allow(clippy::needless_range_loop)]
pub fn blend_control_points(from: &PathPoint, to: &PathPoint) -> [Point; 6] {
    let chord = norm(&sub(&to.p, &from.p));
    let mut b = [[0.0; MAX_AXES]; 6];
    for k in 0..MAX_AXES {
        let (v0, a0) = (chord * from.t[k], chord * chord * from.k[k]);
        let (v1, a1) = (chord * to.t[k], chord * chord * to.k[k]);
        b[0][k] = from.p[k];
        b[1][k] = from.p[k] + v0 / 5.0;
        b[2][k] = from.p[k] + 2.0 * v0 / 5.0 + a0 / 20.0;
        b[3][k] = to.p[k] - 2.0 * v1 / 5.0 + a1 / 20.0;
        b[4][k] = to.p[k] - v1 / 5.0;
        b[5][k] = to.p[k];
    }
    b
}

/// Whether every point lies on the line from the first to the last, in order along it, within
/// [`POINT_TOLERANCE`] + 1e-9 of the span.
fn collinear_in_order(points: &[Point]) -> bool {
    let (Some(first), Some(last)) = (points.first(), points.last()) else {
        return false;
    };
    let d = sub(last, first);
    let len = norm(&d);
    if len <= POINT_TOLERANCE {
        return false;
    }
    let dir = scale(&d, 1.0 / len);
    let tol = POINT_TOLERANCE + 1e-9 * len;
    let mut previous = -tol;
    for p in points {
        let w = sub(p, first);
        let along = dot(&w, &dir);
        if norm(&sub(&w, &scale(&dir, along))) > tol || along < previous - tol {
            return false;
        }
        previous = along;
    }
    true
}

/// The natural spline's second derivatives at the points (0 at both ends), by the Thomas
/// algorithm on the tridiagonal system, all axes at once.
fn natural_second_derivatives(points: &[Point], h: &[f64]) -> Vec<Point> {
    let n = points.len();
    let mut m = vec![[0.0; MAX_AXES]; n];
    if n < 3 {
        return m;
    }
    // Unknowns m[1..n-1]: h[i-1]·m[i-1] + 2(h[i-1]+h[i])·m[i] + h[i]·m[i+1] = rhs[i].
    let inner = n - 2;
    let mut diag = vec![0.0; inner];
    let mut upper = vec![0.0; inner];
    let mut rhs = vec![[0.0; MAX_AXES]; inner];
    for k in 0..inner {
        let i = k + 1;
        diag[k] = 2.0 * (h[i - 1] + h[i]);
        upper[k] = h[i];
        let right = scale(&sub(&points[i + 1], &points[i]), 1.0 / h[i]);
        let left = scale(&sub(&points[i], &points[i - 1]), 1.0 / h[i - 1]);
        rhs[k] = scale(&sub(&right, &left), 6.0);
    }
    // Forward sweep: the lower diagonal of row k is h[k] (= h[i-1]).
    for k in 1..inner {
        let w = h[k] / diag[k - 1];
        diag[k] -= w * upper[k - 1];
        let prev = rhs[k - 1];
        rhs[k] = sub(&rhs[k], &scale(&prev, w));
    }
    let mut x = vec![[0.0; MAX_AXES]; inner];
    for k in (0..inner).rev() {
        let next = if k + 1 < inner {
            x[k + 1]
        } else {
            [0.0; MAX_AXES]
        };
        x[k] = scale(&sub(&rhs[k], &scale(&next, upper[k])), 1.0 / diag[k]);
    }
    m[1..=inner].copy_from_slice(&x);
    m
}
