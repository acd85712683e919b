//! A curve's construction spread over calls (issue 11: the planning work per servo tick
//! bounded). Constructing a spline of 1000 points costs some 48 M instructions, nearly all of
//! it the bounds and lengths of its pieces (docs/decisions.md, "Group tick and spline
//! acceptance cost"); a [`SplineBuild`] does the cheap part (checks, the spline's
//! coefficients) at once and the pieces a few at a time, so a servo tick can take a bounded
//! share of it. The pieces are visited in the same order with the same arithmetic as a
//! construction in one go, so the curve is the same bit for bit however the work is split.

use super::MAX_SPLINE_POINTS;
use super::{
    active_axes, collinear_in_order, natural_second_derivatives, step_bounds, Bounds, Curve,
    CurveKind, Piece, Shape, Table, STEPS_PER_SPAN,
};
use crate::geometry::{
    add, check_dims, check_finite, norm, scale, sub, GeometryError, Line, Segment, POINT_TOLERANCE,
};
use crate::Point;

/// A curve's table being built piece by piece: the bounds and lengths gathered so far.
#[derive(Clone, Debug)]
pub(super) struct TableBuild {
    shape: Shape,
    /// Every piece `(u0, u1, steps, span)` in path order; `next` is the first not visited.
    plan: Vec<(f64, f64, usize, usize)>,
    next: usize,
    bounds: Bounds,
    built: Vec<Piece>,
    /// Path length at the start of piece `next`.
    s: f64,
}

impl TableBuild {
    pub(super) fn new(shape: Shape, plan: Vec<(f64, f64, usize, usize)>) -> TableBuild {
        TableBuild {
            shape,
            built: Vec::with_capacity(plan.len()),
            plan,
            next: 0,
            bounds: Bounds::new(),
            s: 0.0,
        }
    }

    /// Pieces not visited yet.
    fn remaining(&self) -> usize {
        self.plan.len().saturating_sub(self.next)
    }

    /// Visit up to `pieces` more pieces (bounds, then the length step by step, as the rows
    /// will be: shorter intervals converge in fewer halvings). True when every piece is done.
    fn advance(&mut self, pieces: usize) -> bool {
        for &(u0, u1, steps, span) in self.plan.iter().skip(self.next).take(pieces) {
            self.bounds.visit_piece(&self.shape, (u0, u1), steps, span);
            let length = (0..steps)
                .map(|k| {
                    let (a, b) = step_bounds(u0, u1, steps, k);
                    super::arc_length(&self.shape, a, b, span)
                })
                .sum::<f64>();
            self.built.push(Piece {
                s0: self.s,
                length,
                u0,
                u1,
                steps,
                span,
                rows: std::sync::OnceLock::new(),
            });
            self.s += length;
            self.next += 1;
        }
        self.remaining() == 0
    }

    /// The table, its pieces all visited (those not visited yet are visited now).
    pub(super) fn finish(mut self) -> Result<Table, GeometryError> {
        self.advance(usize::MAX);
        let (Some(&(first_u, ..)), Some(&(_, u_end, _, span))) =
            (self.plan.first(), self.plan.last())
        else {
            return Err(GeometryError::Invalid("a curve needs at least one step"));
        };
        let (bounds, shape, s) = (self.bounds, self.shape, self.s);
        let e = shape.eval(u_end, span);
        let min_speed = bounds.min_speed.min(norm(&e.d1));
        // The parameter runs at about unit speed on average (chord length, or the ellipse's
        // mean radius); a speed near 0 somewhere is a cusp.
        let mean_speed = s / (u_end - first_u);
        let stalls = min_speed.is_nan() || min_speed <= 1e-3 * mean_speed;
        if bounds.sharp || stalls || !s.is_finite() {
            return Err(GeometryError::Invalid(
                "the curve stops or turns back on itself (a cusp): no tangent there",
            ));
        }
        // Between the evaluations the tangent turns by at most κ·Δs; pad both bounds for it
        // (conservative, so the planner never under-estimates an axis's share of the speed).
        let mut max_tangent = bounds.max_tangent;
        let max_curvature = bounds.max_curvature;
        for m in max_tangent.iter_mut().filter(|m| **m > 0.0) {
            // An axis whose tangent is exactly 0 at every evaluation does not move (its
            // coordinate's polynomial coefficients are 0): it stays 0, so the coordinates a
            // curve leaves alone are known exactly (`Curve::lifted`).
            *m = (*m + max_curvature * bounds.spacing).min(1.0);
        }
        Ok(Table {
            shape,
            pieces: self.built,
            max_tangent,
            max_curvature: max_curvature * 1.05,
            // A difference quotient is the mean of the rate over its interval; the margin
            // covers a peak between two evaluations of a smooth curve (64 per blend, 32 per
            // span).
            max_curvature_rate: bounds.max_curvature_rate * 1.25,
        })
    }
}

/// The construction of [`Curve::spline`] in steps.
///
/// Inputs: [`SplineBuild::new`] (the points; every check that needs no piece's bounds, and
/// the coefficients), then [`SplineBuild::advance`] as often as wanted (a number of spline
/// spans each). Output: [`SplineBuild::finish`], the segment `Curve::spline` gives for the
/// same points (it does what is left, so it may be called at any time). A cusp is found only
/// by the pieces' bounds, so `finish` may still refuse the curve.
#[derive(Clone, Debug)]
pub struct SplineBuild {
    state: State,
}

#[derive(Clone, Debug)]
enum State {
    /// Points all on one line in order: the line, built at once.
    Line(Line),
    Table {
        table: Box<TableBuild>,
        last: Point,
        dims: usize,
    },
}

impl SplineBuild {
    /// The natural cubic spline's checks and coefficients (see [`Curve::spline`]); the
    /// pieces are still to visit.
    pub fn new(points: &[Point], dims: usize) -> Result<SplineBuild, GeometryError> {
        check_dims(dims)?;
        if points.len() < 2 {
            return Err(GeometryError::Invalid(
                "a spline needs its start and at least one more point",
            ));
        }
        if points.len() > MAX_SPLINE_POINTS {
            return Err(GeometryError::Invalid("a spline has at most 1001 points"));
        }
        for (k, p) in points.iter().enumerate() {
            check_finite(if k == 0 { "start" } else { "spline point" }, p)?;
            if p.iter().skip(dims).any(|&c| c != 0.0) {
                return Err(GeometryError::Invalid(
                    "a point has coordinates past the path's axes",
                ));
            }
        }
        let mut h = Vec::with_capacity(points.len() - 1);
        for w in points.windows(2) {
            let d = norm(&sub(&w[1], &w[0]));
            if d <= POINT_TOLERANCE {
                return Err(GeometryError::Coincident {
                    first: "a spline point",
                    second: "the next one",
                });
            }
            h.push(d);
        }
        let (first, last) = (points[0], points[points.len() - 1]);
        if collinear_in_order(points) {
            return Ok(SplineBuild {
                state: State::Line(Line::new(first, last, dims)?),
            });
        }
        let m = natural_second_derivatives(points, &h);
        let mut knots = Vec::with_capacity(points.len());
        let mut u = 0.0;
        knots.push(u);
        let mut coefficients = Vec::with_capacity(h.len());
        for (i, &hi) in h.iter().enumerate() {
            let (p0, p1, m0, m1) = (points[i], points[i + 1], m[i], m[i + 1]);
            let slope = scale(&sub(&p1, &p0), 1.0 / hi);
            let b = sub(&slope, &scale(&add(&scale(&m0, 2.0), &m1), hi / 6.0));
            let c = scale(&m0, 0.5);
            let d = scale(&sub(&m1, &m0), 1.0 / (6.0 * hi));
            coefficients.push([p0, b, c, d]);
            u += hi;
            knots.push(u);
        }
        let plan = knots
            .windows(2)
            .enumerate()
            .map(|(span, k)| (k[0], k[1], STEPS_PER_SPAN, span))
            .collect();
        let shape = Shape::Spline {
            knots,
            active: active_axes(&coefficients),
            coefficients,
        };
        Ok(SplineBuild {
            state: State::Table {
                table: Box::new(TableBuild::new(shape, plan)),
                last,
                dims,
            },
        })
    }

    /// Spans still to visit (0: [`SplineBuild::finish`] only checks and assembles).
    pub fn remaining(&self) -> usize {
        match &self.state {
            State::Line(_) => 0,
            State::Table { table, .. } => table.remaining(),
        }
    }

    /// Visit up to `spans` more spline spans, each a bounded amount of work (some 33
    /// evaluations for its bounds, golden-section searches at its curvature peaks, its length
    /// by Gauss–Legendre halved at most 8 levels deep). True when none is left.
    pub fn advance(&mut self, spans: usize) -> bool {
        match &mut self.state {
            State::Line(_) => true,
            State::Table { table, .. } => table.advance(spans),
        }
    }

    /// The segment: the spline (its remaining spans visited now), or the line of collinear
    /// points; a cusp found on the way refuses it.
    pub fn finish(self) -> Result<Segment, GeometryError> {
        match self.state {
            State::Line(line) => Ok(Segment::Line(line)),
            State::Table { table, last, dims } => Ok(Segment::Curve(Curve::whole(
                table.finish()?,
                CurveKind::Spline,
                last,
                dims,
            ))),
        }
    }
}
