//! The execution-time calculation (digest 001 §2.7 (11)–(12)): `NMC_CrdStartExeTimeCalc`
//! and `_NMC_CrdGetExeTime` take no handle (the vendor computes it in the host library with its
//! own look-ahead); mcemu's library asks every device it has open through these two rows.
//!
//! While the calculation runs, what the coordinate systems are pushed is kept back (the manual:
//! "all buffer commands are not pushed into the controller"): pushes wait in the pending list
//! as before `NMC_CrdStartMtn`, and reading the time puts the coordinate systems back as they
//! were at the start, so none of it ever runs. The time is computed from the pushed path
//! profile in closed form, without running it: each motion's length on the `path` geometry
//! (`crd_length`), its velocity and acceleration as the engine was to get them, junction
//! velocities as the engine's blending takes them (the lower of the two motions' velocities,
//! 0 before an exact stop, a dwell or the end), limited by what each length lets the path
//! reach (a backward then forward pass), then a trapezoid per motion; dwells add their time.
//! The sum over the device's coordinate systems, in ms.

use axes::command::{Command, ErrorKind, GroupBufferMode, GroupCommand};
use mcemu_dialects::nmc::code_for_kind;
use mcemu_nmc::table::{self, Function};

use crate::nmc::crd::CrdState;
use crate::nmc::crd_length;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (
        table::CRD_START_EXE_TIME_CALC_EX,
        crd_start_exe_time_calc_ex,
    ),
    (table::CRD_GET_EXE_TIME_EX, crd_get_exe_time_ex),
];

fn crd_start_exe_time_calc_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let mut crd = c.service.crd();
    let saved = Box::new(crd.clone());
    // Pushes wait in the pending list while the calculation runs, even on a started system.
    for s in crd.iter_mut() {
        s.started = false;
    }
    drop(crd);
    c.service.sys().exe_calc = Some(saved);
    Ok(())
}

fn crd_get_exe_time_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let saved = c.service.sys().exe_calc.take().ok_or_else(|| {
        Refusal::new(
            code_for_kind(ErrorKind::InvalidState),
            "no execution-time calculation is running (NMC_CrdStartExeTimeCalc first)",
        )
    })?;
    let mut crd = c.service.crd();
    let mut ms = 0.0;
    for (n, (now, before)) in crd.iter().zip(saved.iter()).enumerate() {
        // A buffer cleared meanwhile holds only what came after the clear.
        let pushed = now
            .pending
            .get(before.pending.len()..)
            .unwrap_or(&now.pending);
        ms += 1e3 * seconds(&start(c, n, before), pushed);
    }
    // What was pushed never runs: the coordinate systems as they were.
    *crd = *saved;
    c.output.f64(ms);
    Ok(())
}

/// Where the path stood when the calculation started, engine units: the end of what was
/// pushed before, or where the group is.
fn start(c: &Call<'_>, n: usize, before: &CrdState) -> Vec<f64> {
    let axes = before.axes();
    if before.started || !before.pending.is_empty() {
        return axes
            .iter()
            .zip(before.end)
            .map(|(a, p)| c.scale(*a).to_engine(p as f64))
            .collect();
    }
    c.snapshot
        .groups
        .iter()
        .find(|g| usize::from(g.group) == n)
        .map_or_else(
            || vec![0.0; axes.len()],
            |g| g.coordinates.iter().take(axes.len()).copied().collect(),
        )
}

/// One motion as the closed form needs it: length, velocity, acceleration (engine units),
/// whether it is entered blended.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Piece {
    length: f64,
    vel: f64,
    acc: f64,
    blended: bool,
}

/// The motion parameters `command` carries (velocity, acceleration, buffer mode).
fn kinematics(command: &Command) -> Option<(f64, f64, GroupBufferMode)> {
    let Command::Group(g) = command else {
        return None;
    };
    let (v, a, m) = match g {
        GroupCommand::MoveLinearAbsolute(m) => (m.velocity, m.acceleration, m.buffer_mode),
        GroupCommand::MoveCircularAbsolute(m) => (m.velocity, m.acceleration, m.buffer_mode),
        GroupCommand::MoveEllipse(m) => (m.velocity, m.acceleration, m.buffer_mode),
        _ => return None,
    };
    Some((v.unwrap_or(0.0), a.unwrap_or(0.0), m))
}

/// Seconds the pushed `commands` take from `start` (see the module's doc).
fn seconds(start: &[f64], commands: &[Command]) -> f64 {
    let mut total = 0.0;
    let mut run: Vec<Piece> = Vec::new();
    let mut at = start.to_vec();
    for command in commands {
        if let Command::Group(GroupCommand::Dwell(d)) = command {
            total += run_seconds(&run) + d.seconds.max(0.0);
            run.clear();
            continue;
        }
        let (Some((segment, end)), Some((vel, acc, mode))) =
            (crd_length::segment(&at, command), kinematics(command))
        else {
            continue;
        };
        at = end;
        let piece = Piece {
            length: segment.length(),
            vel,
            acc,
            blended: !matches!(mode, GroupBufferMode::Buffered | GroupBufferMode::Aborting),
        };
        if !piece.blended {
            total += run_seconds(&run);
            run.clear();
        }
        run.push(piece);
    }
    total + run_seconds(&run)
}

/// Seconds of a run of motions from rest to rest, blended at their junctions.
fn run_seconds(run: &[Piece]) -> f64 {
    let usable = |p: &Piece| p.vel > 0.0 && p.acc > 0.0 && p.length.is_finite();
    if run.is_empty() || !run.iter().all(usable) {
        return 0.0;
    }
    // Junction k is the start of motion k; junction run.len() the end (at rest).
    let mut v: Vec<f64> = (0..=run.len())
        .map(
            |k| match (k.checked_sub(1).and_then(|i| run.get(i)), run.get(k)) {
                (Some(a), Some(b)) if b.blended => a.vel.min(b.vel),
                _ => 0.0,
            },
        )
        .collect();
    // Backward: each junction low enough to stop in time; forward: reachable from the last.
    for k in (0..run.len()).rev() {
        if let (Some(p), Some(next)) = (run.get(k), v.get(k + 1).copied()) {
            if let Some(j) = v.get_mut(k) {
                *j = j.min((next * next + 2.0 * p.acc * p.length).sqrt());
            }
        }
    }
    for k in 0..run.len() {
        if let (Some(p), Some(prev)) = (run.get(k), v.get(k).copied()) {
            if let Some(j) = v.get_mut(k + 1) {
                *j = j.min((prev * prev + 2.0 * p.acc * p.length).sqrt());
            }
        }
    }
    run.iter()
        .zip(v.windows(2))
        .map(|(p, w)| match w {
            [v0, v1] => trapezoid(p.length, *v0, *v1, p.vel, p.acc),
            _ => 0.0,
        })
        .sum()
}

/// Seconds to cover `length` from `v0` to `v1` with at most `vmax` and `acc` both ways
/// (`v0`, `v1` reachable from each other over `length`, as the passes above make them).
fn trapezoid(length: f64, v0: f64, v1: f64, vmax: f64, acc: f64) -> f64 {
    let peak = ((2.0 * acc * length + v0 * v0 + v1 * v1) / 2.0).sqrt();
    let vp = peak.min(vmax).max(v0).max(v1);
    if vp <= 0.0 {
        return 0.0;
    }
    let ramps = (vp - v0) / acc + (vp - v1) / acc;
    let ramp_length = (2.0 * vp * vp - v0 * v0 - v1 * v1) / (2.0 * acc);
    let cruise = ((length - ramp_length) / vp).max(0.0);
    ramps + cruise
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece(length: f64, vel: f64, acc: f64, blended: bool) -> Piece {
        Piece {
            length,
            vel,
            acc,
            blended,
        }
    }

    /// 10 000 pulses at 10 pulse/ms, 1 pulse/ms² (in ms units): 10 ms up, 10 down, 990
    /// cruising = 1010 ms.
    #[test]
    fn one_line_is_a_trapezoid() {
        let t = run_seconds(&[piece(10_000.0, 10.0, 1.0, false)]);
        assert!((t - 1010.0).abs() < 1e-9, "{t}");
    }

    /// Too short to reach the velocity: a triangle, 2·√(L/a).
    #[test]
    fn a_short_line_is_a_triangle() {
        let t = run_seconds(&[piece(16.0, 10.0, 1.0, false)]);
        assert!((t - 8.0).abs() < 1e-9, "{t}");
    }

    /// Two equal lines blended pass the junction at full speed: one trapezoid of the sum.
    #[test]
    fn blended_lines_do_not_stop() {
        let t = run_seconds(&[
            piece(5_000.0, 10.0, 1.0, false),
            piece(5_000.0, 10.0, 1.0, true),
        ]);
        assert!((t - 1010.0).abs() < 1e-9, "{t}");
        let stop = run_seconds(&[piece(5_000.0, 10.0, 1.0, false)]) * 2.0;
        assert!((stop - 1020.0).abs() < 1e-9, "{stop}");
    }

    #[test]
    fn nothing_usable_takes_no_time() {
        assert_eq!(run_seconds(&[]), 0.0);
        assert_eq!(run_seconds(&[piece(10.0, 0.0, 1.0, false)]), 0.0);
        assert_eq!(run_seconds(&[piece(f64::NAN, 1.0, 1.0, false)]), 0.0);
    }
}
