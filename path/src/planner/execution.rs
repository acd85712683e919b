//! The per-step advance (issue 11 item 3): each motion runs a 1-D [`Profile`] along its path
//! length, from its start state to its end at the velocity the look-ahead allows; a step that
//! reaches a motion's end carries the rest of its period into the next motion. Work per step:
//! at most one re-plan, and per motion started (at most [`MAX_STARTS_PER_STEP`]) one profile
//! plan plus, when more than the look-ahead window is queued, one look-ahead pass.

use profile::{Goal, Limits, MotionState, Options, Profile};

use super::queue::{Entry, QueuedMotion};
use super::reach::{lowest_end, ramp_distance, reach, settle};
use super::{MarkerKind, PathEvent, PathPlanner};
use crate::MAX_AXES;

/// Most motions started in one step. A motion's velocity is capped at its length per period,
/// so it lasts about a period at least and two starts per step are the most that moving
/// motions need; the rest of the bound is for motions of length 0 (passed at rest). Past it,
/// the step ends early at a junction and the next step goes on.
pub const MAX_STARTS_PER_STEP: usize = 8;

/// A first stage shorter than this fraction of its motion is not worth planning (it would
/// only be rounding: the last stage starts where the first ended).
const STAGE_MIN: f64 = 1e-9;

/// A re-plan part-way needs more room than this fraction of the motion left once its
/// acceleration is settled.
const REPLAN_SLACK: f64 = 1e-6;

/// The executing motion's profile and where the path is on it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Execution {
    profile: Profile,
    /// Path length along the motion at which the profile ends.
    target: f64,
    /// Profile time at the end of the step in which it was planned; each later step adds a
    /// period (`lead + n·T`, not a running sum, so long motions do not drift).
    lead: f64,
    advances: u64,
    hint: usize,
    /// Path length along the motion, path velocity and acceleration after the last step.
    pub s: f64,
    pub v: f64,
    pub a: f64,
}

impl Execution {
    fn new(profile: Profile, target: f64, lead: f64, s: f64, v: f64, a: f64) -> Execution {
        Execution {
            profile,
            target,
            lead,
            advances: 0,
            hint: 0,
            s,
            v,
            a,
        }
    }
}

/// The end velocity to plan a motion for, from the path state `(v, a)` with `room` left:
/// the look-ahead's `pref` if it can be reached (accelerating or braking), else the lowest
/// velocity the motion can brake to (≤ `phys` whenever the path entered the motion below its
/// look-ahead start velocity, which the look-ahead guarantees). `None` when the start
/// acceleration cannot be brought to 0 within the room left, or, for a `replan` part-way
/// (where `settle` is conservative for a braking start), when `pref` cannot be reached: the
/// current profile goes on, and the re-plan is tried again next step.
fn end_velocity(m: &QueuedMotion, v: f64, a: f64, room: f64, replan: bool) -> Option<f64> {
    let l = &m.limits;
    let (v1, s1) = settle(v, a, l.jerk);
    let room = room - s1;
    if room < 0.0 || v1 < 0.0 {
        return None;
    }
    if replan && room <= REPLAN_SLACK * m.length {
        // Part-way, on the boundary of what is reachable: the current profile is the one
        // that gets there; a new plan would only add rounding.
        return None;
    }
    // Part-way, keep off the boundary too (a profile braking exactly to `pref` is common).
    let room = if replan {
        room - REPLAN_SLACK * m.length
    } else {
        room
    };
    let wanted = m.end_pref.min(reach(v1, room, l.acceleration, l.jerk));
    if wanted >= v1 || ramp_distance(v1, wanted, l.deceleration, l.jerk) <= room {
        return Some(wanted);
    }
    if replan {
        return None;
    }
    Some(lowest_end(v1, room, l.deceleration, l.jerk).max(wanted))
}

/// A profile that stays at rest at `s` and never ends (a velocity goal of 0): a motion halted
/// part-way waits on it.
fn rest_at(s: f64) -> Profile {
    let limits = Limits {
        velocity: 1.0,
        acceleration: 1.0,
        deceleration: 1.0,
        jerk: f64::INFINITY,
    };
    let start = MotionState {
        p: s,
        v: 0.0,
        a: 0.0,
    };
    Profile::plan(
        start,
        Goal::Velocity { target: 0.0 },
        &limits,
        &Options::default(),
    )
    .unwrap_or(Profile::hold(s))
}

impl PathPlanner {
    /// The profile for the front motion from path state `(s, v, a)` on it, and the path
    /// length at which it ends (the motion's end, or where its last stage begins).
    /// `replan`: part-way through the motion and moving, with a profile that already works
    /// (see `end_velocity`); from rest every plan is a fresh start.
    fn plan_front(&self, s: f64, v: f64, a: f64, replan: bool) -> Option<(Profile, f64)> {
        let Some(Entry::Motion(m)) = self.queue.front() else {
            return None;
        };
        let l = &m.limits;
        let start = MotionState { p: s, v, a };
        let cruise = m.cruise(self.override_factor);
        if let Some(halt) = self.halt {
            // Halt / stop (PLCopen MC_GroupHalt / MC_GroupStop): brake along the path with the
            // given deceleration (never more than the axes allow here), across motion ends.
            let dec = halt
                .deceleration
                .map_or(l.deceleration, |d| d.min(l.deceleration));
            if v <= 0.0 && a <= 0.0 {
                return Some((rest_at(s), m.length));
            }
            let (v1, s1) = settle(v, a, l.jerk);
            let room = m.length - s - s1;
            if replan && room <= REPLAN_SLACK * m.length {
                // On the boundary (see `end_velocity`): the current profile goes on to the
                // motion's end, and the halt continues from there.
                return None;
            }
            let room = room - if replan { REPLAN_SLACK * m.length } else { 0.0 };
            if room >= 0.0 {
                let limits = Limits {
                    velocity: v.max(cruise).max(f64::MIN_POSITIVE),
                    acceleration: l.acceleration,
                    deceleration: dec,
                    jerk: l.jerk,
                };
                if ramp_distance(v1, 0.0, dec, l.jerk) <= room {
                    let goal = Goal::Velocity { target: 0.0 };
                    let p = Profile::plan(start, goal, &limits, &Options::default()).ok()?;
                    return Some((p, m.length));
                }
                let w = lowest_end(v1, room, dec, l.jerk);
                if w <= m.end_phys {
                    let limits = Limits {
                        velocity: v1.max(v).max(w).max(f64::MIN_POSITIVE),
                        ..limits
                    };
                    let p = Profile::plan_passing(start, m.length, w, &limits).ok()?;
                    return Some((p, m.length));
                }
            }
        }
        let w = end_velocity(m, v, a, m.length - s, replan)?;
        if self.halt.is_none() && w > cruise && cruise > 0.0 {
            // BlendingNext/High into a faster motion (PLCopen Part 4): run at this motion's
            // own velocity, then speed up to the junction velocity at the end — two stages.
            let split = m.length - ramp_distance(cruise, w, l.acceleration, l.jerk) * (1.0 + 1e-9);
            let (v1, s1) = settle(v, a, l.jerk);
            let room = split - s - s1;
            let reachable = split - s > STAGE_MIN * m.length
                && room >= 0.0
                && (v1 <= cruise || ramp_distance(v1, cruise, l.deceleration, l.jerk) <= room)
                && reach(v1, room, l.acceleration, l.jerk) >= cruise;
            if reachable {
                let limits = Limits {
                    velocity: cruise,
                    acceleration: l.acceleration,
                    deceleration: l.deceleration,
                    jerk: l.jerk,
                };
                let p = Profile::plan_passing(start, split, cruise, &limits).ok()?;
                return Some((p, split));
            }
        }
        let (v1, s1) = settle(v, a, l.jerk);
        let mut velocity = if self.halt.is_some() {
            v1.max(v).max(w)
        } else {
            cruise.max(w)
        };
        // Faster than the cruise velocity (override lowered, BlendingPrevious/High): the
        // profile brakes to the cruise velocity, then to `w`. With a jerk limit those two
        // ramps take longer than one straight to `w`; when the room left is between, brake
        // straight to `w` (the lower cruise velocity applies from the next motion on).
        if v1 > velocity
            && ramp_distance(v1, velocity, l.deceleration, l.jerk)
                + ramp_distance(velocity, w, l.deceleration, l.jerk)
                > m.length - s - s1
        {
            velocity = v1;
        }
        if velocity.is_nan() || velocity <= 0.0 {
            return Some((rest_at(s), m.length));
        }
        let limits = Limits {
            velocity,
            acceleration: l.acceleration,
            deceleration: l.deceleration,
            jerk: l.jerk,
        };
        let p = Profile::plan_passing(start, m.length, w, &limits).ok()?;
        Some((p, m.length))
    }

    /// Advance one period (see [`PathPlanner::step`]).
    pub(super) fn advance(&mut self, events: &mut Vec<PathEvent>) {
        let period = self.config.period;
        self.starts_last_step = 0;
        self.lookahead_visits = 0;
        if self.replan_pending {
            match self.exec {
                Some(e) => {
                    if let Some((profile, target)) =
                        self.plan_front(e.s, e.v, e.a, e.v > 0.0 || e.a != 0.0)
                    {
                        self.exec = Some(Execution::new(profile, target, period, e.s, e.v, e.a));
                        self.replan_pending = false;
                    }
                }
                None => self.replan_pending = false,
            }
        }
        let mut dt = period;
        loop {
            if self.exec.is_none() && !self.begin_next(events, dt) {
                break;
            }
            let Some(exec) = self.exec.as_mut() else {
                break;
            };
            let length = match self.queue.front() {
                Some(Entry::Motion(m)) => m.length,
                _ => 0.0,
            };
            let t = exec.lead + exec.advances as f64 * period;
            exec.advances += 1;
            let profile = &exec.profile;
            if !profile.is_velocity_goal() && t >= profile.duration() {
                dt = t - profile.duration();
                let arrival = profile.arrival_velocity().max(0.0);
                let target = exec.target;
                self.state.travelled += target - exec.s;
                if target < length {
                    if self.starts_last_step >= MAX_STARTS_PER_STEP {
                        // The per-step bound: wait at the stage's end, plan next step.
                        exec.s = target;
                        exec.v = arrival;
                        exec.a = 0.0;
                        self.replan_pending = true;
                        break;
                    }
                    // The first stage of a two-stage motion ended: plan the last one.
                    self.starts_last_step += 1;
                    let (profile, end) = self
                        .plan_front(target, arrival, 0.0, false)
                        .unwrap_or((rest_at(target), length));
                    self.exec = Some(Execution::new(profile, end, dt, target, arrival, 0.0));
                    continue;
                }
                self.complete_front(events, arrival);
                continue;
            }
            let sample = profile.sample_from(t, &mut exec.hint);
            // The path never goes back (a profile that would is a planning bug: hold the line).
            let s = sample.p.clamp(exec.s, exec.target.min(length));
            self.state.travelled += s - exec.s;
            exec.s = s;
            exec.v = sample.v.max(0.0);
            exec.a = sample.a;
            break;
        }
        self.publish();
        self.check_at_rest(events);
    }

    /// Start what comes next in the queue with `dt` of the period left: pass markers, start the
    /// next motion. False when nothing can start (empty queue, a Hold, halted, the per-step
    /// bound).
    fn begin_next(&mut self, events: &mut Vec<PathEvent>, dt: f64) -> bool {
        loop {
            let (tag, kind) = match self.queue.front() {
                None => {
                    self.carry = 0.0;
                    return false;
                }
                Some(Entry::Marker { tag, kind }) => (*tag, *kind),
                Some(Entry::Motion(m)) => {
                    if (self.halt.is_some() && self.carry <= 0.0)
                        || self.starts_last_step >= MAX_STARTS_PER_STEP
                    {
                        return false;
                    }
                    self.starts_last_step += 1;
                    if m.reports_start {
                        events.push(PathEvent::Started { tag: m.tag });
                    }
                    if m.length.is_nan() || m.length <= 0.0 {
                        self.complete_front(events, 0.0);
                        continue;
                    }
                    let v = self.carry;
                    let (profile, target) = match self.plan_front(0.0, v, 0.0, false) {
                        Some(planned) => planned,
                        None => {
                            // Unreachable with validated limits; rather a stop than a jump,
                            // and try again next step.
                            self.replan_pending = true;
                            (rest_at(0.0), m.length)
                        }
                    };
                    self.exec = Some(Execution::new(profile, target, dt, 0.0, v, 0.0));
                    return true;
                }
            };
            match kind {
                MarkerKind::PassThrough => {
                    events.push(PathEvent::Marker { tag, kind });
                    self.pop_front();
                }
                MarkerKind::Hold => {
                    if self.hold_released {
                        self.hold_released = false;
                        self.state.holding = None;
                        self.pop_front();
                        continue;
                    }
                    if self.state.holding != Some(tag) {
                        events.push(PathEvent::Marker { tag, kind });
                        self.state.holding = Some(tag);
                    }
                    self.carry = 0.0;
                    return false;
                }
            }
        }
    }

    pub(super) fn pop_front(&mut self) {
        if let Some(e) = self.queue.pop_front() {
            let user = match &e {
                Entry::Marker { .. } => true,
                Entry::Motion(m) => m.reports_done,
            };
            if user {
                self.user_entries = self.user_entries.saturating_sub(1);
            }
        }
    }

    /// The front motion reached its end at path velocity `arrival`.
    fn complete_front(&mut self, events: &mut Vec<PathEvent>, arrival: f64) {
        if let Some(Entry::Motion(m)) = self.queue.front() {
            self.position = m.segment.end();
            self.end_tangent = m.segment.end_tangent();
            if m.reports_done {
                events.push(PathEvent::Done { tag: m.tag });
                self.state.completed += 1;
            }
        }
        self.pop_front();
        self.exec = None;
        self.carry = arrival;
        // A motion may have entered the window: extend the look-ahead to it.
        if self.queue.len() >= self.config.lookahead {
            self.lookahead(self.queue.len());
        }
    }

    /// Write the path state from the executing motion (or the last point reached).
    fn publish(&mut self) {
        let st = &mut self.state;
        // By reference: an `Execution` holds a whole profile (hundreds of bytes), and this
        // runs every tick.
        match (self.exec.as_ref(), self.queue.front()) {
            (Some(e), Some(Entry::Motion(m))) => {
                let pt = m.segment.sample(e.s);
                st.position = pt.p;
                // The path's own axes: past them the tangent and curvature are 0, and so are
                // the velocity and acceleration written there (never anything else).
                let dims = self.config.dims.min(MAX_AXES);
                for k in 0..dims {
                    st.velocity[k] = pt.t[k] * e.v;
                    st.acceleration[k] = pt.t[k] * e.a + pt.k[k] * e.v * e.v;
                }
                st.path_velocity = e.v;
                st.path_acceleration = e.a;
                st.tag = Some(m.tag);
            }
            _ => {
                st.position = self.position;
                st.acceleration = [0.0; MAX_AXES];
                for k in 0..MAX_AXES {
                    st.velocity[k] = self.end_tangent[k] * self.carry;
                }
                st.path_velocity = self.carry;
                st.path_acceleration = 0.0;
                st.tag = None;
            }
        }
    }

    /// Report a halt or stop that has brought the path to rest; a stop then drops the queue.
    fn check_at_rest(&mut self, events: &mut Vec<PathEvent>) {
        let Some(halt) = self.halt else { return };
        let resting = match &self.exec {
            None => self.carry <= 0.0,
            Some(e) => e.v <= 0.0 && e.a == 0.0,
        };
        if resting && !self.at_rest_reported {
            events.push(PathEvent::AtRest);
            self.at_rest_reported = true;
            if halt.stop {
                self.drop_queue(events);
                self.halt = None;
                self.state.halted = false;
            }
        }
    }

    /// Drop every queued entry (reporting the caller's), at the current point, at rest.
    pub(super) fn drop_queue(&mut self, events: &mut Vec<PathEvent>) {
        for e in self.queue.drain(..) {
            match e {
                Entry::Marker { tag, .. } => events.push(PathEvent::Dropped { tag }),
                Entry::Motion(m) if m.reports_done => {
                    events.push(PathEvent::Dropped { tag: m.tag })
                }
                Entry::Motion(_) => {}
            }
        }
        self.user_entries = 0;
        self.exec = None;
        self.carry = 0.0;
        self.position = self.state.position;
        self.replan_pending = false;
        self.hold_released = false;
        self.state.holding = None;
        self.state.velocity = [0.0; MAX_AXES];
        self.state.acceleration = [0.0; MAX_AXES];
        self.state.path_velocity = 0.0;
        self.state.path_acceleration = 0.0;
        self.state.tag = None;
    }
}
