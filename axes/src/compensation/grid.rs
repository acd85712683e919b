//! Uniform 1/2/3-D correction grids: HIMC SetupComp/SetupComp2D/SetupComp3D (digest 004 §2.13)
//! and the NMC 2-D table (digest 001 §2.19, `T2DCompensationTable`). The first reference varies
//! fastest in `values` (NMC S-2DCOMP: x = i % count_x). Linear in each dimension; outside the
//! grid the nearest edge is held (digest 004 §2.13). The cell follows from the position by one
//! division per dimension: no search. Options: a 2-D table turned by an angle about its first
//! point (NMC `T2DCompensationTable.angle`), and cubic-spline interpolation in 1-D and 2-D
//! (HIMC SetCompAlgType 1, `spline.rs`).

use super::spline::{Cell, SplineSlopes};
use super::table::check_finite;
use crate::error::EngineError;

/// The most reference axes a grid has (HIMC SetupComp3D).
pub const MAX_DIMENSIONS: usize = 3;
/// The most values a grid holds (NMC: X·Y·3 ≤ 3000 values, one axis's share 1000; HIMC user
/// tables are of that order too). Bounds the memory a command can ask for.
pub const MAX_GRID_VALUES: usize = 65_536;

#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    start: Vec<f64>,
    step: Vec<f64>,
    count: Vec<usize>,
    values: Vec<f64>,
    /// sin and cos of the angle the table's axes are turned by (2-D).
    turn: Option<(f64, f64)>,
    /// Cubic-spline slopes (`interpolation: cubic`).
    spline: Option<Box<SplineSlopes>>,
}

impl Grid {
    pub fn new(
        axis: u32,
        start: &[f64],
        step: &[f64],
        count: &[u32],
        values: &[f64],
    ) -> Result<Grid, EngineError> {
        let bad = |reason: String| EngineError::InvalidCompensation { axis, reason };
        let dims = start.len();
        if dims == 0 || dims > MAX_DIMENSIONS {
            return Err(bad(format!(
                "a table has 1 to {MAX_DIMENSIONS} reference axes, got {dims}"
            )));
        }
        if step.len() != dims || count.len() != dims {
            return Err(bad(format!(
                "start, step and count need one entry per reference axis ({dims}); got {}, {}, {}",
                start.len(),
                step.len(),
                count.len()
            )));
        }
        check_finite(axis, "start", start)?;
        check_finite(axis, "step", step)?;
        if let Some(i) = step.iter().position(|s| *s <= 0.0) {
            return Err(bad(format!(
                "step[{i}] must be > 0 so that positions increase"
            )));
        }
        if let Some(i) = count.iter().position(|c| *c < 2) {
            return Err(bad(format!(
                "count[{i}]: a table needs at least 2 points per reference axis"
            )));
        }
        let total = count
            .iter()
            .try_fold(1usize, |acc, c| acc.checked_mul(*c as usize))
            .filter(|t| *t <= MAX_GRID_VALUES)
            .ok_or_else(|| bad(format!("more than {MAX_GRID_VALUES} table values")))?;
        if values.len() != total {
            return Err(bad(format!(
                "{total} grid points but {} values",
                values.len()
            )));
        }
        check_finite(axis, "values", values)?;
        Ok(Grid {
            start: start.to_vec(),
            step: step.to_vec(),
            count: count.iter().map(|c| *c as usize).collect(),
            values: values.to_vec(),
            turn: None,
            spline: None,
        })
    }

    /// Turn a 2-D table's axes by `degrees` counter-clockwise about its first point (NMC
    /// S-2DCOMP `angle`), and interpolate by cubic splines (`cubic`, 1-D and 2-D: HIMC's 3-D
    /// tables have no spline).
    pub fn with_options(
        mut self,
        axis: u32,
        degrees: f64,
        cubic: bool,
    ) -> Result<Grid, EngineError> {
        let bad = |reason: String| EngineError::InvalidCompensation { axis, reason };
        if !degrees.is_finite() || degrees.abs() > 360.0 {
            return Err(bad(format!(
                "angle = {degrees}: must be a finite number of degrees within ±360"
            )));
        }
        if degrees != 0.0 {
            if self.dimensions() != 2 {
                return Err(bad(format!(
                    "an angle turns a 2-D table; this one has {} reference axes",
                    self.dimensions()
                )));
            }
            self.turn = Some(degrees.to_radians().sin_cos());
        }
        if cubic {
            if self.dimensions() > 2 {
                return Err(bad(
                    "cubic interpolation is for 1-D and 2-D tables (HIMC: 3-D has no spline)"
                        .into(),
                ));
            }
            self.spline = Some(Box::new(SplineSlopes::new(
                &self.values,
                &self.count,
                &self.step,
            )));
        }
        Ok(self)
    }

    pub fn dimensions(&self) -> usize {
        self.start.len()
    }

    pub fn start(&self) -> &[f64] {
        &self.start
    }

    pub fn step(&self) -> &[f64] {
        &self.step
    }

    pub fn count(&self) -> Vec<u32> {
        self.count.iter().map(|c| *c as u32).collect()
    }

    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The interpolated value at the reference positions `x` (one per dimension).
    pub fn value_at(&self, x: &[f64; MAX_DIMENSIONS]) -> f64 {
        let turned;
        let x = match (self.turn, self.start.as_slice()) {
            (Some((sin, cos)), [s0, s1, ..]) => {
                // The machine position in the table's turned axes, about its first point.
                let (dx, dy) = (x[0] - s0, x[1] - s1);
                turned = [s0 + dx * cos + dy * sin, s1 - dx * sin + dy * cos, x[2]];
                &turned
            }
            _ => x,
        };
        // Per dimension: the lower grid index and the fraction towards the next one.
        let mut cell = [(0usize, 0.0f64); MAX_DIMENSIONS];
        let mut stride = [0usize; MAX_DIMENSIONS];
        let mut s = 1usize;
        for d in 0..self.dimensions().min(MAX_DIMENSIONS) {
            let (Some(&start), Some(&step), Some(&n), Some(&xd)) = (
                self.start.get(d),
                self.step.get(d),
                self.count.get(d),
                x.get(d),
            ) else {
                return 0.0;
            };
            let u = ((xd - start) / step).clamp(0.0, (n - 1) as f64);
            // NaN clamps to NaN; `as usize` turns it into 0, and the fraction below into 0.
            let i = (u.floor() as usize).min(n - 2);
            let f = u - i as f64;
            if let (Some(c), Some(st)) = (cell.get_mut(d), stride.get_mut(d)) {
                *c = (i, if f.is_finite() { f } else { 0.0 });
                *st = s;
            }
            s *= n;
        }
        let dims = self.dimensions().min(MAX_DIMENSIONS);
        if let Some(spline) = &self.spline {
            let (i, t) = cell[0];
            let (j, u) = cell[1];
            let (sx, sy) = (stride[0], stride[1]);
            return spline.patch(
                &self.values,
                Cell {
                    i0: i * sx + j * sy,
                    stride: (dims == 2).then_some(sy),
                    t,
                    u,
                    hx: self.step.first().copied().unwrap_or(1.0),
                    hy: self.step.get(1).copied().unwrap_or(1.0),
                },
            );
        }
        // Sum over the 2^dims corners of the cell, each weighted by its fractions.
        let mut sum = 0.0;
        for corner in 0..(1usize << dims) {
            let mut weight = 1.0;
            let mut index = 0usize;
            for d in 0..dims {
                let (i, f) = cell.get(d).copied().unwrap_or((0, 0.0));
                let st = stride.get(d).copied().unwrap_or(0);
                if corner & (1 << d) == 0 {
                    weight *= 1.0 - f;
                    index += i * st;
                } else {
                    weight *= f;
                    index += (i + 1) * st;
                }
            }
            if weight != 0.0 {
                sum += weight * self.values.get(index).copied().unwrap_or(0.0);
            }
        }
        sum
    }
}
