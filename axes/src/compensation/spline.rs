//! Cubic-spline interpolation of a uniform 1-D or 2-D compensation grid (HIMC SetCompAlgType 1,
//! digest 004 §2.13: "cubic spline; 3D does not support spline"). The natural cubic spline
//! through each row and column is fixed by its slopes at the grid points; in 2-D the surface
//! is the tensor product of those splines, which on each cell is the bicubic Hermite patch of
//! the values, the x and y slopes and the cross slopes at its four corners. All slopes are
//! computed when the table is installed (O(points)); a tick evaluates one patch.

/// The slopes a spline grid needs at each point, in the grid's value order (first reference
/// fastest): ∂/∂x, ∂/∂y and ∂²/∂x∂y (the last two empty in 1-D), per unit of position.
#[derive(Clone, Debug, PartialEq)]
pub struct SplineSlopes {
    dx: Vec<f64>,
    dy: Vec<f64>,
    dxy: Vec<f64>,
}

/// Slopes at the points of the natural cubic spline through `y` at spacing `h` (second
/// derivative 0 at both ends): the tridiagonal system M[i−1] + 4·M[i] + M[i+1] = 6·Δ²y/h²,
/// solved by the Thomas algorithm.
fn natural_slopes(y: &[f64], h: f64) -> Vec<f64> {
    let n = y.len();
    let at = |i: usize| y.get(i).copied().unwrap_or(0.0);
    let mut m = vec![0.0; n];
    if n > 2 {
        let inner = n - 2;
        let mut diag = vec![4.0; inner];
        let mut rhs: Vec<f64> = (0..inner)
            .map(|k| 6.0 * (at(k + 2) - 2.0 * at(k + 1) + at(k)) / (h * h))
            .collect();
        for k in 1..inner {
            let w = 1.0 / diag[k - 1];
            diag[k] -= w;
            rhs[k] -= w * rhs[k - 1];
        }
        for k in (0..inner).rev() {
            let next = if k + 1 < inner { m[k + 2] } else { 0.0 };
            m[k + 1] = (rhs[k] - next) / diag[k];
        }
    }
    (0..n)
        .map(|i| {
            if i + 1 < n {
                (at(i + 1) - at(i)) / h - h * (2.0 * m[i] + m[i + 1]) / 6.0
            } else {
                (at(i) - at(i - 1)) / h + h * (m[i - 1] + 2.0 * m[i]) / 6.0
            }
        })
        .collect()
}

/// The natural-spline slopes along dimension `d` (0 or 1) of every line of `values`, a grid of
/// `count` points at spacing `h` along `d` (first dimension fastest).
fn along(values: &[f64], count: &[usize], d: usize, h: f64) -> Vec<f64> {
    let nx = count.first().copied().unwrap_or(1);
    let ny = count.get(1).copied().unwrap_or(1);
    let mut out = vec![0.0; values.len()];
    let (lines, len, stride, step) = if d == 0 {
        (ny, nx, nx, 1)
    } else {
        (nx, ny, 1, nx)
    };
    let mut line = Vec::with_capacity(len);
    for l in 0..lines {
        let base = l * stride;
        line.clear();
        line.extend((0..len).map(|k| values.get(base + k * step).copied().unwrap_or(0.0)));
        for (k, s) in natural_slopes(&line, h).into_iter().enumerate() {
            if let Some(o) = out.get_mut(base + k * step) {
                *o = s;
            }
        }
    }
    out
}

impl SplineSlopes {
    /// The slopes of a 1-D or 2-D grid of `count` points at spacing `step`.
    pub fn new(values: &[f64], count: &[usize], step: &[f64]) -> SplineSlopes {
        let hx = step.first().copied().unwrap_or(1.0);
        let dx = along(values, count, 0, hx);
        if count.len() < 2 {
            return SplineSlopes {
                dx,
                dy: Vec::new(),
                dxy: Vec::new(),
            };
        }
        let hy = step.get(1).copied().unwrap_or(1.0);
        let dy = along(values, count, 1, hy);
        let dxy = along(&dx, count, 1, hy);
        SplineSlopes { dx, dy, dxy }
    }

    /// The spline of the grid's `values` at `cell`.
    pub fn patch(&self, values: &[f64], cell: Cell) -> f64 {
        let v = |k: usize| values.get(k).copied().unwrap_or(0.0);
        let g = |a: &[f64], k: usize| a.get(k).copied().unwrap_or(0.0);
        // Hermite basis: value weights (h00, h01) and slope weights (h10, h11) of t.
        let basis = |t: f64| {
            let (t2, t3) = (t * t, t * t * t);
            (
                [2.0 * t3 - 3.0 * t2 + 1.0, -2.0 * t3 + 3.0 * t2],
                [t3 - 2.0 * t2 + t, t3 - t2],
            )
        };
        let (px, sx) = basis(cell.t);
        let Some(stride) = cell.stride else {
            return (0..2)
                .map(|a| {
                    let k = cell.i0 + a;
                    px[a] * v(k) + sx[a] * cell.hx * g(&self.dx, k)
                })
                .sum();
        };
        let (py, sy) = basis(cell.u);
        let mut sum = 0.0;
        for b in 0..2 {
            for a in 0..2 {
                let k = cell.i0 + a + b * stride;
                sum += px[a] * py[b] * v(k)
                    + sx[a] * py[b] * cell.hx * g(&self.dx, k)
                    + px[a] * sy[b] * cell.hy * g(&self.dy, k)
                    + sx[a] * sy[b] * cell.hx * cell.hy * g(&self.dxy, k);
            }
        }
        sum
    }
}

/// Where in the grid a spline is evaluated.
#[derive(Clone, Copy, Debug)]
pub struct Cell {
    /// Value index of the cell's lower corner.
    pub i0: usize,
    /// Values per row (2-D), or none (1-D).
    pub stride: Option<usize>,
    pub t: f64,
    pub u: f64,
    pub hx: f64,
    pub hy: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn natural_slopes_of_a_line_are_its_slope_and_of_two_points_the_chord() {
        // A straight line: every slope is the line's.
        let s = natural_slopes(&[1.0, 3.0, 5.0, 7.0], 2.0);
        assert!(s.iter().all(|&d| (d - 1.0).abs() < 1e-12), "{s:?}");
        // Two points: the chord.
        assert_eq!(natural_slopes(&[0.0, 4.0], 2.0), vec![2.0, 2.0]);
    }
}
