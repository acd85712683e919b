//! Helpers shared by the path crate's integration tests (planner and geometry).

// Each test binary uses its own subset.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use path::geometry::{norm, sub, Arc, Line, Segment, Turn};
use path::planner::{
    AxisLimits, Join, Motion, PathEvent, PathLimits, PathPlanner, PathState, PlannerConfig,
    Transition,
};
use path::{Point, MAX_AXES};

/// A point from its first coordinates (the rest 0).
pub fn p(c: &[f64]) -> Point {
    let mut out = [0.0; MAX_AXES];
    out[..c.len()].copy_from_slice(c);
    out
}

pub fn line(a: Point, b: Point, dims: usize) -> Segment {
    Segment::Line(Line::new(a, b, dims).unwrap())
}

pub fn arc(a: Point, b: Point, c: Point, turn: Turn, dims: usize) -> Segment {
    Segment::Arc(Arc::from_center(a, b, c, (0, 1), turn, 0, dims).unwrap())
}

pub fn limits(v: f64, a: f64, j: f64) -> PathLimits {
    PathLimits {
        velocity: v,
        acceleration: a,
        deceleration: a,
        jerk: j,
    }
}

pub fn axis(v: f64, a: f64, j: f64) -> AxisLimits {
    AxisLimits {
        velocity: v,
        acceleration: a,
        jerk: j,
    }
}

pub fn motion(
    segment: Segment,
    limits: PathLimits,
    join: Join,
    tr: Transition,
    tag: u64,
) -> Motion {
    Motion {
        segment,
        limits,
        join,
        transition: tr,
        tag,
    }
}

/// Step until idle (or `max` steps); the states after every step (the first is the start
/// state) and the events.
pub fn run(planner: &mut PathPlanner, max: usize) -> (Vec<PathState>, Vec<PathEvent>) {
    let mut states = vec![*planner.state()];
    let mut events = Vec::new();
    for _ in 0..max {
        let st = *planner.step(&mut events);
        states.push(st);
        if planner.is_idle() {
            break;
        }
    }
    (states, events)
}

/// Largest ratio over all ticks and axes of |finite-difference velocity| / V_k and of
/// |finite-difference acceleration| / A_k, and of the reported values.
pub struct Peaks {
    pub v_fd: f64,
    pub a_fd: f64,
    pub v_reported: f64,
    pub a_reported: f64,
}

/// `tolerance_a`: absolute slack in acceleration, for the rounding of positions divided by T².
pub fn peaks(states: &[PathState], config: &PlannerConfig) -> Peaks {
    let t = config.period;
    let mut pk = Peaks {
        v_fd: 0.0,
        a_fd: 0.0,
        v_reported: 0.0,
        a_reported: 0.0,
    };
    for k in 0..config.dims {
        let lim = config.axes[k];
        // Rounding of a position of magnitude |x| is ≤ ε|x|; a second difference of three
        // rounded positions errs by ≤ 4ε|x|/T², which the ratio discounts.
        let scale = states
            .iter()
            .map(|s| s.position[k].abs())
            .fold(1.0, f64::max);
        let slack_v = 2.0 * f64::EPSILON * scale / t;
        let slack_a = 4.0 * f64::EPSILON * scale / (t * t);
        for w in states.windows(2) {
            let v = (w[1].position[k] - w[0].position[k]) / t;
            pk.v_fd = pk.v_fd.max((v.abs() - slack_v).max(0.0) / lim.velocity);
            pk.v_reported = pk.v_reported.max(w[1].velocity[k].abs() / lim.velocity);
            pk.a_reported = pk
                .a_reported
                .max(w[1].acceleration[k].abs() / lim.acceleration);
        }
        for w in states.windows(3) {
            let a = (w[2].position[k] - 2.0 * w[1].position[k] + w[0].position[k]) / (t * t);
            pk.a_fd = pk.a_fd.max((a.abs() - slack_a).max(0.0) / lim.acceleration);
        }
    }
    pk
}

/// Distance from `q` to the polyline through `pts` (first two axes … all axes).
pub fn distance_to_polyline(q: &Point, pts: &[Point]) -> f64 {
    let mut best = f64::INFINITY;
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let mut ab = [0.0; MAX_AXES];
        let mut aq = [0.0; MAX_AXES];
        for k in 0..MAX_AXES {
            ab[k] = b[k] - a[k];
            aq[k] = q[k] - a[k];
        }
        let len2: f64 = ab.iter().map(|x| x * x).sum();
        let t = if len2 > 0.0 {
            (ab.iter().zip(&aq).map(|(x, y)| x * y).sum::<f64>() / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d: f64 = (0..MAX_AXES)
            .map(|k| (aq[k] - t * ab[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        best = best.min(d);
    }
    best
}

/// Rotate the planar vector (x, y) by `angle`.
pub fn rotate(x: f64, y: f64, angle: f64) -> (f64, f64) {
    let (s, c) = angle.sin_cos();
    (c * x - s * y, s * x + c * y)
}

/// Whether two points are within `tol` of each other.
pub fn close(a: &Point, b: &Point, tol: f64) -> bool {
    norm(&sub(a, b)) <= tol
}

/// An upper bound on the distance from `q` to `segment` (exact for a line; for an arc or
/// helix, the distance to the point at the angle of `q`'s projection on its plane, or to its
/// nearer end): 0 for a point on the segment.
pub fn distance_to_segment(q: &Point, segment: &Segment) -> f64 {
    match segment {
        Segment::Line(l) => distance_to_polyline(q, &[l.start(), l.end()]),
        Segment::Arc(a) => {
            let (u, v) = a.basis();
            let c = a.center();
            let w = sub(q, &c);
            let x: f64 = w.iter().zip(&u).map(|(a, b)| a * b).sum();
            let y: f64 = w.iter().zip(&v).map(|(a, b)| a * b).sum();
            let at = |theta: f64| {
                let (s, co) = theta.sin_cos();
                let h = a.helix();
                let mut pt = [0.0; MAX_AXES];
                for k in 0..MAX_AXES {
                    pt[k] = c[k] + a.radius() * (co * u[k] + s * v[k]) + theta / a.sweep() * h[k];
                }
                norm(&sub(q, &pt))
            };
            let theta = y.atan2(x).rem_euclid(std::f64::consts::TAU);
            let ends = norm(&sub(q, &segment.start())).min(norm(&sub(q, &a.end())));
            if theta <= a.sweep() {
                at(theta).min(ends)
            } else {
                ends
            }
        }
        Segment::Curve(_) => norm(&sub(q, &segment.start())).min(norm(&sub(q, &segment.end()))),
    }
}

/// An upper bound on the distance from `q` to the path made of `segments`.
pub fn distance_to_path(q: &Point, segments: &[Segment]) -> f64 {
    segments
        .iter()
        .map(|s| distance_to_segment(q, s))
        .fold(f64::INFINITY, f64::min)
}

/// Largest ratio over all ticks and the axes with a jerk limit of |finite-difference jerk|
/// (third differences of the positions) / J_k, less the rounding of four positions
/// (≤ 8ε|x|/T³).
pub fn jerk_peak(states: &[PathState], config: &PlannerConfig) -> f64 {
    let t = config.period;
    let mut worst: f64 = 0.0;
    for k in 0..config.dims {
        let lim = config.axes[k];
        if !lim.jerk.is_finite() {
            continue;
        }
        let scale = states
            .iter()
            .map(|s| s.position[k].abs())
            .fold(1.0, f64::max);
        let slack = 8.0 * f64::EPSILON * scale / (t * t * t);
        for w in states.windows(4) {
            let j = (w[3].position[k] - 3.0 * w[2].position[k] + 3.0 * w[1].position[k]
                - w[0].position[k])
                / (t * t * t);
            worst = worst.max((j.abs() - slack).max(0.0) / lim.jerk);
        }
    }
    worst
}

/// LinuxCNC issue #3773's path: 200 small arcs (R ≈ 4 mm, sweeps 20°–90°) joined tangentially,
/// alternating counter-clockwise and clockwise, climbing 0.01 in z each (a fixed seed).
pub fn linuxcnc_3773_arcs() -> Vec<Segment> {
    let (mut x, mut y) = (0.0, 0.0);
    let mut heading: f64 = 0.0;
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut out = Vec::with_capacity(200);
    for i in 0..200 {
        let r = 3.8 + 0.4 * rnd();
        let sweep = (20.0 + 70.0 * rnd()).to_radians();
        let ccw = i % 2 == 0;
        let side = if ccw { 1.0 } else { -1.0 };
        // Centre on the left (CCW) or right (CW) of the heading: tangent junctions.
        let (nx, ny) = rotate(
            heading.cos(),
            heading.sin(),
            side * std::f64::consts::FRAC_PI_2,
        );
        let (cx, cy) = (x + r * nx, y + r * ny);
        let (ex, ey) = rotate(x - cx, y - cy, side * sweep);
        let (ex, ey) = (cx + ex, cy + ey);
        let z = 0.01 * f64::from(i);
        let turn = if ccw { Turn::Ccw } else { Turn::Cw };
        out.push(Segment::Arc(
            Arc::from_center(
                p(&[x, y, z]),
                p(&[ex, ey, z + 0.01]),
                p(&[cx, cy, z]),
                (0, 1),
                turn,
                0,
                3,
            )
            .unwrap(),
        ));
        x = ex;
        y = ey;
        heading += side * sweep;
    }
    out
}
