//! One-dimensional correction table: explicit positions, linear interpolation, the value of the
//! nearest end held outside (digest 004 §2.13; NMC lead screw "平均补偿", digest 001 §2.19).

use crate::error::EngineError;

/// Points `(position, value)` with strictly increasing positions. The segment found last is
/// carried from tick to tick, so a lookup walks only the points crossed since the last tick.
#[derive(Clone, Debug, PartialEq)]
pub struct Table1d {
    positions: Vec<f64>,
    values: Vec<f64>,
    /// Index `i` of the segment `positions[i]..positions[i+1]` used last.
    segment: usize,
}

impl Table1d {
    /// Check and build. `what` names the table in errors.
    pub fn new(axis: u32, positions: &[f64], values: &[f64]) -> Result<Table1d, EngineError> {
        let bad = |reason: String| EngineError::InvalidCompensation { axis, reason };
        if positions.len() < 2 {
            return Err(bad(format!(
                "a table needs at least 2 points, got {}",
                positions.len()
            )));
        }
        if values.len() != positions.len() {
            return Err(bad(format!(
                "{} positions but {} values",
                positions.len(),
                values.len()
            )));
        }
        check_finite(axis, "positions", positions)?;
        check_finite(axis, "values", values)?;
        if let Some(i) = positions.windows(2).position(|w| w[1] <= w[0]) {
            return Err(bad(format!(
                "positions must increase: positions[{}] = {} is not above positions[{i}] = {}",
                i + 1,
                positions.get(i + 1).copied().unwrap_or(f64::NAN),
                positions.get(i).copied().unwrap_or(f64::NAN),
            )));
        }
        Ok(Table1d {
            positions: positions.to_vec(),
            values: values.to_vec(),
            segment: 0,
        })
    }

    pub fn positions(&self) -> &[f64] {
        &self.positions
    }

    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The interpolated value at `x`, moving the carried segment to the one holding `x`.
    pub fn value_at(&mut self, x: f64) -> f64 {
        let last = self.positions.len().saturating_sub(2);
        let mut i = self.segment.min(last);
        while i > 0 && self.positions.get(i).is_some_and(|&p| x < p) {
            i -= 1;
        }
        while i < last && self.positions.get(i + 1).is_some_and(|&p| x >= p) {
            i += 1;
        }
        self.segment = i;
        let (Some(&x0), Some(&x1), Some(&y0), Some(&y1)) = (
            self.positions.get(i),
            self.positions.get(i + 1),
            self.values.get(i),
            self.values.get(i + 1),
        ) else {
            return 0.0;
        };
        if x <= x0 {
            y0
        } else if x >= x1 {
            y1
        } else {
            y0 + (y1 - y0) * (x - x0) / (x1 - x0)
        }
    }
}

/// Every number finite and within ±1e12 (the engine's bound for positions).
pub(super) fn check_finite(axis: u32, name: &str, xs: &[f64]) -> Result<(), EngineError> {
    match xs
        .iter()
        .position(|x| !x.is_finite() || x.abs() > crate::command::MAX_MAGNITUDE)
    {
        Some(i) => Err(EngineError::InvalidCompensation {
            axis,
            reason: format!(
                "{name}[{i}] = {} is not a finite number within ±1e12",
                xs.get(i).copied().unwrap_or(f64::NAN)
            ),
        }),
        None => Ok(()),
    }
}
