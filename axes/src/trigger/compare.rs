//! One position-compare channel: positions in order, each firing a digital output once when the
//! axis reaches it (1-D: NMC 1-D compare, HMC `Switch`/`NormalSwitch1D`, HIMC PT trigger; 2-D:
//! closest approach within an error zone, NMC §2.11/§4.6, HMC `NormalSwitch2D`).
//!
//! When it fires: 1-D, at the tick whose motion passes the position (it lies in (start, end] of
//! the tick's travel, either direction: "the first sample past the target", digest 000 §4.4;
//! the list need not be monotonic: the channel waits on the next position, HMC NormalSwitch1D);
//! 2-D, at the tick in which the path's closest approach to the point lies, within `error_zone`
//! (the closest point of the tick's straight travel is not its end), or at a standstill inside
//! the zone. Several positions passed in one tick all fire in that tick, in order.

use super::{channel_in_range, invalid, Env, COMPARE_CHANNELS, MAX_COMPARE_POSITIONS};
use crate::command::{bounded, nonnegative, positive, CompareStart, EngineError};
use crate::status::{CompareOutputMode, CompareState, CompareStatus, PositionSource};

/// The positions of a channel.
#[derive(Clone, Debug)]
enum Targets {
    /// 1-D, a list.
    List(Vec<f64>),
    /// 1-D, `start + k·step` for k < count (HIMC PT trigger: start, end, interval).
    Grid { start: f64, step: f64, count: u32 },
    /// 2-D; `disturbance` > 0 only on the actual position.
    Points {
        points: Vec<[f64; 2]>,
        zone: f64,
        disturbance: f64,
    },
}

impl Targets {
    fn len(&self) -> u32 {
        match self {
            Targets::List(v) => v.len() as u32,
            Targets::Grid { count, .. } => *count,
            Targets::Points { points, .. } => points.len() as u32,
        }
    }

    /// Position `k` of a 1-D channel.
    fn position(&self, k: u32) -> Option<f64> {
        match self {
            Targets::List(v) => v.get(k as usize).copied(),
            Targets::Grid { start, step, count } => {
                (k < *count).then(|| start + f64::from(k) * step)
            }
            Targets::Points { .. } => None,
        }
    }
}

#[derive(Clone, Debug)]
pub(super) struct Compare {
    status: CompareStatus,
    targets: Targets,
    mode: CompareOutputMode,
    level: bool,
    pulse_ticks: u64,
    min_interval_ticks: u64,
    /// Positions passed but not yet fired (waiting for the minimum interval).
    due: u32,
    last_fire: Option<u64>,
    /// The tick at which a pulse ends.
    pulse_end: Option<u64>,
    /// The level the next toggle writes.
    toggle_level: bool,
    /// 2-D with a disturbance: the least distance to the next point seen since the path
    /// entered its zone.
    closest: Option<f64>,
}

/// Whole servo periods in `seconds`, rounded up (a duration shorter than a period lasts one:
/// outputs exist in the I/O image only between ticks).
fn ticks(seconds: f64, period: f64) -> u64 {
    let n = (seconds / period - 1e-9).ceil();
    if n.is_finite() && n > 0.0 {
        n.min(u64::MAX as f64) as u64
    } else {
        0
    }
}

impl Compare {
    /// A channel started as `c` asks, or why it cannot be. In pulse mode the output goes to
    /// its idle level at once.
    pub(super) fn start(env: &mut Env, c: &CompareStart) -> Result<Compare, EngineError> {
        let channel = c.channel;
        channel_in_range("compare", channel, COMPARE_CHANNELS)?;
        env.axis(c.axis)?;
        if let Some(y) = c.axis_y {
            env.axis(y)?;
            if y == c.axis {
                return Err(invalid(
                    "compare",
                    channel,
                    "axis_y is the same axis as axis",
                ));
            }
        }
        let count = env.outputs.len() as u16;
        if c.output >= count {
            // "Compare on a missing DO" (issue 12, bad input).
            return Err(EngineError::InvalidChannel {
                kind: "digital outputs",
                channel: c.output,
                count,
            });
        }
        let targets = targets(c)?;
        if targets.len() == 0 {
            return Err(invalid("compare", channel, "no positions"));
        }
        let pulse_width = nonnegative("pulse_width", c.pulse_width)?;
        let min_interval = nonnegative("min_interval", c.min_interval)?;
        let compare = Compare {
            status: CompareStatus {
                channel,
                axis: c.axis,
                axis_y: c.axis_y,
                source: c.source,
                output: c.output,
                state: CompareState::Running,
                count: 0,
                remaining: targets.len(),
                total: targets.len(),
            },
            targets,
            mode: c.mode,
            level: c.level,
            pulse_ticks: ticks(pulse_width, env.period).max(1),
            min_interval_ticks: ticks(min_interval, env.period),
            due: 0,
            last_fire: None,
            pulse_end: None,
            toggle_level: c.level,
            closest: None,
        };
        if compare.mode == CompareOutputMode::Pulse {
            env.write_output(c.output, !c.level);
        }
        Ok(compare)
    }

    pub(super) fn channel(&self) -> u8 {
        self.status.channel
    }

    pub(super) fn status(&self) -> &CompareStatus {
        &self.status
    }

    /// Dropped: a pulse in progress ends.
    pub(super) fn stop(self, env: &mut Env) {
        if self.pulse_end.is_some() {
            env.write_output(self.status.output, !self.level);
        }
    }

    /// One tick; whether an output fired.
    pub(super) fn step(&mut self, env: &mut Env) -> bool {
        let count = self.status.count;
        if self.pulse_end.is_some_and(|t| env.tick >= t) {
            self.pulse_end = None;
            env.write_output(self.status.output, !self.level);
        }
        let passed = self.passed(env);
        self.status.remaining -= passed.min(self.status.remaining);
        self.due = self.due.saturating_add(passed);
        while self.due > 0
            && self
                .last_fire
                .is_none_or(|t| env.tick.saturating_sub(t) >= self.min_interval_ticks)
        {
            self.fire(env);
            self.due -= 1;
            if self.min_interval_ticks > 0 {
                break;
            }
        }
        self.status.state = if self.status.remaining == 0 && self.due == 0 {
            CompareState::Done
        } else {
            CompareState::Running
        };
        self.status.count != count
    }

    /// How many positions, from the next one on, the last tick's motion reached.
    fn passed(&mut self, env: &Env) -> u32 {
        let s = &self.status;
        let next = s.total - s.remaining;
        let Some(x) = env.axes.get(s.axis as usize) else {
            return 0;
        };
        let [x0, x1] = x.swept(s.source);
        match &self.targets {
            Targets::Points {
                points,
                zone,
                disturbance,
            } => {
                let Some(y) = s.axis_y.and_then(|y| env.axes.get(y as usize)) else {
                    return 0;
                };
                let [y0, y1] = y.swept(s.source);
                if *disturbance > 0.0 {
                    let resting = x.commanded().v == 0.0 && y.commanded().v == 0.0;
                    let zone = Zone {
                        radius: *zone,
                        disturbance: *disturbance,
                    };
                    let travel = [[x0, y0], [x1, y1]];
                    zone.settled_approaches(points, next, travel, resting, &mut self.closest)
                } else {
                    closest_approaches(points, next, [x0, y0], [x1, y1], *zone)
                }
            }
            targets => passed_1d(|k| targets.position(k), next, [x0, x1]),
        }
    }

    /// A manual output (NMC `Comp2DimensOnoff` 2): fired as a position would fire it, counted
    /// in `count`, no position used up; the minimum interval does not hold it back.
    pub(super) fn fire_now(&mut self, env: &mut Env) {
        self.fire(env);
    }

    fn fire(&mut self, env: &mut Env) {
        let output = self.status.output;
        match self.mode {
            CompareOutputMode::Pulse => {
                env.write_output(output, self.level);
                self.pulse_end = Some(env.tick.saturating_add(self.pulse_ticks));
            }
            CompareOutputMode::Toggle => {
                env.write_output(output, self.toggle_level);
                self.toggle_level = !self.toggle_level;
            }
        }
        self.status.count = self.status.count.saturating_add(1);
        self.last_fire = Some(env.tick);
    }
}

/// How many positions, from `next` on, the travel `x[0]` → `x[1]` passes, in order. The first
/// must lie in (x0, x1]: at x0 it was reached the tick before. Each further one is looked for
/// from where the last was reached on, that included (a repeated position fires with the one
/// before it).
pub(super) fn passed_1d(position: impl Fn(u32) -> Option<f64>, next: u32, x: [f64; 2]) -> u32 {
    let [x0, x1] = x;
    let mut k = next;
    let first = position(k);
    if !first.is_some_and(|p| (x0 < p && p <= x1) || (x0 > p && p >= x1)) {
        return 0;
    }
    let mut from = first.unwrap_or(x0);
    k += 1;
    while let Some(p) = position(k) {
        if !((from <= p && p <= x1) || (from >= p && p >= x1)) {
            break;
        }
        from = p;
        k += 1;
    }
    k - next
}

/// How many points from `next` on the straight travel `a` → `b` passes at its closest within
/// `zone`, each searched from where the one before was reached.
fn closest_approaches(points: &[[f64; 2]], next: u32, a: [f64; 2], b: [f64; 2], zone: f64) -> u32 {
    let mut from = a;
    let mut k = next;
    while let Some(p) = points.get(k as usize) {
        let (c, d, t) = closest_point(from, b, *p);
        let still = from == b;
        // Still closing in at the tick's end (t = 1): the closest approach is in a later tick.
        if !(d <= zone && (t < 1.0 || still)) {
            break;
        }
        from = c;
        k += 1;
    }
    k - next
}

/// A 2-D zone with an anti-jitter threshold (HMC NormalSwitch2D `dDisturbValue`, manual
/// §4.4.4.2: "when the compare source is the actual feedback position, jitter is filtered with
/// dDisturbValue"; "once the zone was entered the output always fires").
struct Zone {
    radius: f64,
    disturbance: f64,
}

impl Zone {
    /// How many points from `next` on the travel `travel[0]` → `travel[1]` settles: the path
    /// entered a point's zone (now or in an earlier tick, `closest` keeps the least distance
    /// since), and its distance at the travel's end exceeds that least distance by more than
    /// the disturbance (it recedes beyond what jitter explains; so a path that leaves the zone
    /// fires once it is the disturbance beyond it, "always fires"), or the axes' commands rest
    /// (no closer approach comes). Leaving is debounced too: a noisy sample just outside the
    /// zone's edge is not leaving. A point fired, the next is looked for from the fired one's
    /// closest point on.
    fn settled_approaches(
        &self,
        points: &[[f64; 2]],
        next: u32,
        travel: [[f64; 2]; 2],
        resting: bool,
        closest: &mut Option<f64>,
    ) -> u32 {
        let [mut from, b] = travel;
        let mut k = next;
        while let Some(p) = points.get(k as usize) {
            let (c, d, _) = closest_point(from, b, *p);
            if d <= self.radius {
                *closest = Some(closest.map_or(d, |m| m.min(d)));
            }
            let Some(least) = *closest else { break };
            let end = (p[0] - b[0]).hypot(p[1] - b[1]);
            if !(end > least + self.disturbance || resting) {
                break;
            }
            *closest = None;
            from = c;
            k += 1;
        }
        k - next
    }
}

/// The point of the straight travel `a` → `b` closest to `p`, its distance from `p`, and where
/// on the travel it lies (0 = `a`, 1 = `b`).
fn closest_point(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> ([f64; 2], f64, f64) {
    let u = [b[0] - a[0], b[1] - a[1]];
    let uu = u[0] * u[0] + u[1] * u[1];
    let t = if uu > 0.0 {
        (((p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1]) / uu).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let c = [a[0] + t * u[0], a[1] + t * u[1]];
    (c, (p[0] - c[0]).hypot(p[1] - c[1]), t)
}

/// The positions `c` gives, checked: exactly one of a list, a grid or 2-D points.
fn targets(c: &CompareStart) -> Result<Targets, EngineError> {
    let channel = c.channel;
    let grid = c.start.is_some() || c.interval.is_some() || c.end.is_some();
    let given = [!c.positions.is_empty(), grid, !c.points.is_empty()];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(invalid(
            "compare",
            channel,
            "give exactly one of `positions`, `start`/`interval`/`end` or `points`",
        ));
    }
    if c.points.is_empty() != c.axis_y.is_none() {
        return Err(invalid(
            "compare",
            channel,
            "2-D `points` need `axis_y`, and `axis_y` needs `points`",
        ));
    }
    if c.positions.len().max(c.points.len()) > MAX_COMPARE_POSITIONS {
        return Err(invalid(
            "compare",
            channel,
            format!("more than {MAX_COMPARE_POSITIONS} positions"),
        ));
    }
    if !c.points.is_empty() {
        for p in &c.points {
            bounded("points", p[0])?;
            bounded("points", p[1])?;
        }
        let disturbance = nonnegative("disturbance", c.disturbance)?;
        return Ok(Targets::Points {
            points: c.points.clone(),
            zone: nonnegative("error_zone", c.error_zone)?,
            // The commanded position does not jitter (manual: "valid only on MPos").
            disturbance: match c.source {
                PositionSource::Actual => disturbance,
                PositionSource::Commanded => 0.0,
            },
        });
    }
    if grid {
        let (Some(start), Some(interval), Some(end)) = (c.start, c.interval, c.end) else {
            return Err(invalid(
                "compare",
                channel,
                "a grid needs all of `start`, `interval` and `end`",
            ));
        };
        let start = bounded("start", start)?;
        let end = bounded("end", end)?;
        let interval = positive("interval", bounded("interval", interval)?)?;
        // HIMC PT: outputs from start_pos every interval, none past end_pos; either direction.
        let n = ((end - start).abs() / interval + 1e-9).floor() + 1.0;
        if n > f64::from(u32::MAX) {
            return Err(invalid(
                "compare",
                channel,
                "the grid has too many positions",
            ));
        }
        return Ok(Targets::Grid {
            start,
            step: interval.copysign(end - start),
            count: n as u32,
        });
    }
    for p in &c.positions {
        bounded("positions", *p)?;
    }
    Ok(Targets::List(c.positions.clone()))
}
