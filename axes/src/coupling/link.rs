//! HMC's link profiles as cam tables (HMC_MoveLink, HMC_MoveFlexLink; manual §4.3.6.4,
//! §4.3.6.7–4.3.6.8; digest 000 §4.3, §3.2 "MoveLink S ratio", TV 28–30).
//!
//! MoveLink: while the master travels `M`, the slave travels `S`: its ratio to the master ramps
//! from 0 to `r` over the master's first `A`, stays `r`, and ramps back to 0 over the last `D`
//! (`A + D ≤ M`). A ramp is linear in master travel when the S ratio `s` is 0 (trapezoid), else
//! it rises with a constant second derivative over `s/2` of the ramp, a constant first over
//! `1 − s`, and falls back over the last `s/2` (HMC's jerk fractions, with master travel for
//! time: the manual's figures have the master at constant speed). Each ramp averages `r/2`, so
//! `r = S / (M − (A + D)/2)`. FlexLink adds a base ratio `B/M` over the whole `M` and places the
//! link of `S` (dSlaveAddDist) between the master's first `before` and last `after`
//! (`before + after + A + D ≤ M`); with `B`, `before`, `after` 0 it is MoveLink.
//!
//! The manual computes the slave from the master position analytically rather than from a
//! sampled table; every span here is a polynomial of degree ≤ 3 between knots at the phase
//! boundaries, and a cubic Hermite piece with the exact end values and slopes is that
//! polynomial, so the table is the analytic law (to rounding), with no velocity steps inside.

use super::table::CamTable;
use crate::command::{CamTableLink, EngineError, MAX_MAGNITUDE};

/// The link profile of `c` as a table over master 0..`master_distance`, slave from 0.
pub(super) fn link_table(c: &CamTableLink) -> Result<CamTable, EngineError> {
    let invalid = |reason: String| EngineError::InvalidCamTable {
        table: c.table,
        reason,
    };
    let values = [
        ("slave_distance", c.slave_distance),
        ("master_distance", c.master_distance),
        (
            "master_acceleration_distance",
            c.master_acceleration_distance,
        ),
        (
            "master_deceleration_distance",
            c.master_deceleration_distance,
        ),
        ("s_ratio", c.s_ratio),
        ("slave_base_distance", c.slave_base_distance),
        ("master_before_distance", c.master_before_distance),
        ("master_after_distance", c.master_after_distance),
    ];
    for (name, v) in values {
        if !v.is_finite() || v.abs() > MAX_MAGNITUDE {
            return Err(invalid(format!(
                "{name} {v} is not a finite number within ±1e12"
            )));
        }
    }
    let m = c.master_distance;
    if m <= 0.0 {
        return Err(invalid(format!("master_distance {m} must be positive")));
    }
    for (name, v) in values.iter().skip(2).take(2).chain(values.iter().skip(6)) {
        if *v < 0.0 {
            return Err(invalid(format!("{name} {v} must not be negative")));
        }
    }
    if !(0.0..=1.0).contains(&c.s_ratio) {
        return Err(invalid(format!("s_ratio {} is 0 to 1", c.s_ratio)));
    }
    let (acc, dec) = (
        c.master_acceleration_distance,
        c.master_deceleration_distance,
    );
    let (before, after) = (c.master_before_distance, c.master_after_distance);
    let used = before + after + acc + dec;
    if used > m {
        return Err(invalid(format!(
            "the master distances before, after, accelerating and decelerating ({used}) exceed master_distance ({m})"
        )));
    }
    let link = m - before - after;
    let base = c.slave_base_distance / m;
    let mut knots = Vec::with_capacity(12);
    // Where the link (span `link`, ratio r) is a point: only the base remains.
    let plateau = link - (acc + dec) / 2.0;
    let r = if plateau > 0.0 {
        c.slave_distance / plateau
    } else {
        0.0
    };
    knots.push((0.0, 0.0, 0.0));
    if plateau > 0.0 {
        let rise = ramp(acc, r, c.s_ratio);
        let fall = ramp(dec, r, c.s_ratio);
        for &(x, y, m) in &rise {
            knots.push((before + x, y, m));
        }
        let (x3, y3) = (before + acc, r * acc / 2.0);
        let x4 = before + link - dec;
        let y4 = y3 + r * (x4 - x3);
        knots.push((x3, y3, r));
        knots.push((x4, y4, r));
        // The fall mirrors the rise: ratio r − ramp slope, distance r·x − ramp distance.
        for &(x, y, m) in &fall {
            knots.push((x4 + x, y4 + r * x - y, r - m));
        }
        knots.push((before + link, c.slave_distance, 0.0));
    }
    knots.push((m, c.slave_distance, 0.0));
    // Drop repeated master positions (zero-length phases), keep the last of each.
    let mut clean: Vec<(f64, f64, f64)> = Vec::with_capacity(knots.len());
    for k in knots {
        match clean.last_mut() {
            Some(last) if k.0 <= last.0 => *last = k,
            _ => clean.push(k),
        }
    }
    // The base ratio over the whole table.
    let knots: Vec<_> = clean
        .into_iter()
        .map(|(x, y, s)| (x, y + base * x, s + base))
        .collect();
    if knots.len() < 2 {
        return Err(invalid("the profile has no extent".to_string()));
    }
    Ok(CamTable::from_knots(&knots))
}

/// The inner knots `(x, y, slope)` of a ramp of the ratio from 0 to `r` over master travel `len`
/// with S ratio `s` (ends excluded: the ramp's end, `(len, r·len/2, r)`, is the caller's).
fn ramp(len: f64, r: f64, s: f64) -> [(f64, f64, f64); 2] {
    let l1 = len * s / 2.0;
    let l2 = len * (1.0 - s);
    // The ratio's second derivative on the constant part: a·(l1 + l2) = r.
    let a = if l1 + l2 > 0.0 { r / (l1 + l2) } else { 0.0 };
    let (y1, m1) = (a * l1 * l1 / 6.0, a * l1 / 2.0);
    let (y2, m2) = (y1 + m1 * l2 + a * l2 * l2 / 2.0, m1 + a * l2);
    [(l1, y1, m1), (l1 + l2, y2, m2)]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn link(s: f64, m: f64, acc: f64, dec: f64, s_ratio: f64) -> CamTableLink {
        CamTableLink {
            table: 1,
            slave_distance: s,
            master_distance: m,
            master_acceleration_distance: acc,
            master_deceleration_distance: dec,
            s_ratio,
            slave_base_distance: 0.0,
            master_before_distance: 0.0,
            master_after_distance: 0.0,
        }
    }

    #[test]
    fn a_trapezoid_link_ramps_the_ratio_linearly_tv28() {
        // HMC_ClcMoveLinkData(500, 1000, 200, 200): r = 500 / (1000 − 200) = 0.625.
        let t = link_table(&link(500.0, 1000.0, 200.0, 200.0, 0.0)).unwrap();
        let r = 0.625;
        for (x, y, dy) in [
            (0.0, 0.0, 0.0),
            (100.0, r * 100.0 * 100.0 / 400.0, r / 2.0),
            (200.0, r * 100.0, r),
            (500.0, r * 100.0 + r * 300.0, r),
            (1000.0, 500.0, 0.0),
        ] {
            let s = t.sample(x);
            assert!(
                (s.y - y).abs() < 1e-9 && (s.dy - dy).abs() < 1e-12,
                "{x}: {s:?}"
            );
        }
        // TV 28: 600 + 500 > 1000 is refused.
        assert!(link_table(&link(500.0, 1000.0, 600.0, 500.0, 0.0)).is_err());
    }

    #[test]
    fn an_s_ratio_splits_each_ramp_into_jerk_and_constant_parts() {
        // s = 0.5: over a ramp of 200, 50 rising, 100 constant, 50 falling second derivative.
        let t = link_table(&link(500.0, 1000.0, 200.0, 200.0, 0.5)).unwrap();
        let r = 0.625;
        let a = r / 150.0;
        // The second derivative: 0 at the start, a on the constant part, 0 at the ramp's end.
        assert!(t.sample(0.0).ddy.abs() < 1e-12);
        assert!((t.sample(100.0).ddy - a).abs() < 1e-12);
        assert!((t.sample(200.0).dy - r).abs() < 1e-12);
        // Symmetric ramps: the same total.
        assert!((t.sample(1000.0).y - 500.0).abs() < 1e-9);
        assert!((t.sample(500.0).y - (r * 100.0 + r * 300.0)).abs() < 1e-9);
        // s = 1: no constant part; the ratio still reaches r.
        let t = link_table(&link(500.0, 1000.0, 200.0, 200.0, 1.0)).unwrap();
        assert!((t.sample(200.0).dy - r).abs() < 1e-12);
        assert!((t.sample(1000.0).y - 500.0).abs() < 1e-9);
    }

    #[test]
    fn flex_link_adds_a_base_ratio_and_places_the_link_tv30() {
        // HMC_ClcFlexLinkData(400, 200, 400, 75, 75, 125, 125): base 400 over 400, add 200
        // between master 75 and 325 (250 long, ramps 125 each: r = 200 / 125 = 1.6).
        let c = CamTableLink {
            slave_base_distance: 400.0,
            master_before_distance: 75.0,
            master_after_distance: 75.0,
            ..link(200.0, 400.0, 125.0, 125.0, 0.0)
        };
        let t = link_table(&c).unwrap();
        assert!(
            (t.sample(75.0).dy - 1.0).abs() < 1e-12,
            "synchronous before"
        );
        assert!(
            (t.sample(200.0).dy - 2.6).abs() < 1e-12,
            "1 + r at the link's middle"
        );
        assert!((t.sample(400.0).y - 600.0).abs() < 1e-9);
        assert!(
            (t.sample(390.0).dy - 1.0).abs() < 1e-12,
            "synchronous after"
        );
        // (400, 200, 400, 75, 75, 130, 125): 405 > 400.
        let c = CamTableLink {
            master_acceleration_distance: 130.0,
            ..c
        };
        assert!(link_table(&c).is_err());
        // Bad numbers.
        assert!(link_table(&link(1.0, 0.0, 0.0, 0.0, 0.0)).is_err());
        assert!(link_table(&link(1.0, 10.0, -1.0, 0.0, 0.0)).is_err());
        assert!(link_table(&link(1.0, 10.0, 1.0, 1.0, 1.5)).is_err());
        assert!(link_table(&link(f64::NAN, 10.0, 1.0, 1.0, 0.0)).is_err());
    }
}
