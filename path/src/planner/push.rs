//! Appending a motion: its path limits, its junction with the motion before it, and the
//! corner blend that may replace that junction (issue 11 item 4).

use super::blend::corner_curve;
use super::junction::{junction_rule, mode_velocity, with_shares};
use super::limits::motion_limits;
use super::queue::{Entry, QueuedMotion};
use super::reach::{lowest_end, reach, settle};
use super::{AxisLimits, Join, LookaheadLimits, MarkerKind, Motion, PathLimits, PathPlanner};
use crate::geometry::Segment;

pub(super) fn queued(
    segment: Segment,
    programmed: PathLimits,
    join: Join,
    tag: u64,
    axes: &[AxisLimits],
    period: f64,
    rules: &LookaheadLimits,
) -> QueuedMotion {
    let limits = motion_limits(&segment, &programmed, axes, period, rules);
    QueuedMotion {
        length: segment.length(),
        segment,
        tag,
        join,
        programmed,
        limits,
        end_cap: 0.0,
        end_phys: 0.0,
        end_pref: 0.0,
        start_phys: 0.0,
        start_pref: 0.0,
        reports_start: true,
        entry_factor: 1.0,
        reports_done: true,
        acceleration_share: 1.0,
        jerk_share: 1.0,
    }
}

/// `m`'s path limits again (its segment changed, or its share of the axes' acceleration).
fn relimit(m: &mut QueuedMotion, axes: &[AxisLimits], period: f64, rules: &LookaheadLimits) {
    let shared;
    let axes = if m.acceleration_share < 1.0 || m.jerk_share < 1.0 {
        shared = with_shares(axes, m.acceleration_share, m.jerk_share);
        shared.get(..axes.len()).unwrap_or(&[])
    } else {
        axes
    };
    m.limits = motion_limits(&m.segment, &m.programmed, axes, period, rules);
}

/// The junction from `prev` into `next` (see `junction::junction_rule`): sets `prev`'s end
/// cap and lowers both motions' shares of the axes' acceleration and jerk where the junction
/// needs them (then their limits are computed again). Returns whether `prev`'s limits changed.
fn join(
    prev: &mut QueuedMotion,
    next: &mut QueuedMotion,
    axes: &[AxisLimits],
    period: f64,
    rules: &LookaheadLimits,
) -> bool {
    let before = prev.segment.sample(prev.length);
    let after = next.segment.sample(0.0);
    let v_limit = prev.limits.velocity_cap.min(next.limits.velocity_cap);
    let rule = junction_rule(&before, &after, axes, period, v_limit);
    prev.end_cap = rule.cap;
    let lower = |m: &mut QueuedMotion| {
        let a = m.acceleration_share.min(rule.acceleration_share);
        let j = m.jerk_share.min(rule.jerk_share);
        let changed = a < m.acceleration_share || j < m.jerk_share;
        if changed {
            m.acceleration_share = a;
            m.jerk_share = j;
            relimit(m, axes, period, rules);
        }
        changed
    };
    lower(next);
    lower(prev)
}

/// The highest velocity at which the path may enter `first` and still stop by the end of
/// `second` (the look-ahead's rule for two motions that end the queue).
fn entry_velocity(first: &QueuedMotion, second: &QueuedMotion) -> f64 {
    let l2 = &second.limits;
    let start2 = reach(0.0, second.length, l2.deceleration, l2.jerk).min(l2.velocity_cap);
    let l1 = &first.limits;
    let end1 = start2.min(l1.velocity_cap);
    reach(end1, first.length, l1.deceleration, l1.jerk).min(l1.velocity_cap)
}

impl PathPlanner {
    /// Append `motion` after the queue's last entry; returns the queue index from which the
    /// look-ahead data changed.
    pub(super) fn append_motion(&mut self, motion: Motion) -> usize {
        let period = self.config.period;
        let dims = self.config.dims.min(self.config.axes.len());
        let axes = self.config.axes;
        let axes = axes.get(..dims).unwrap_or(&[]);
        let new = queued(
            motion.segment,
            motion.limits,
            motion.join,
            motion.tag,
            axes,
            period,
            &self.lookahead_limits,
        );
        let mut previous = None;
        let mut hold = false;
        for (i, e) in self.queue.iter().enumerate().rev() {
            match e {
                Entry::Marker { kind, .. } => hold |= *kind == MarkerKind::Hold,
                Entry::Motion(_) => {
                    previous = Some(i);
                    break;
                }
            }
        }
        let Some(pi) = previous else {
            self.queue.push_back(Entry::Motion(Box::new(new)));
            return self.queue.len() - 1;
        };
        // PLCopen Part 4: Buffered stops exactly; a Hold marker in between stops there too.
        if motion.join == Join::Buffered || hold {
            self.queue.push_back(Entry::Motion(Box::new(new)));
            return pi;
        }
        if let Some((arc, second)) = self.blend(pi, &new, motion.transition, axes) {
            self.queue.push_back(Entry::Motion(Box::new(arc)));
            self.queue.push_back(Entry::Motion(Box::new(second)));
            return pi;
        }
        // Transition::None (or a blend that did not fit): the junction rule (a direction
        // step, a curvature step).
        let rules = self.lookahead_limits;
        let mut new = new;
        let after = new.segment.sample(0.0);
        let mut before = after;
        if let Some(Entry::Motion(prev)) = self.queue.get_mut(pi) {
            before = prev.segment.sample(prev.length);
            let changed = join(prev, &mut new, axes, period, &rules);
            let step = crate::geometry::norm(&crate::geometry::sub(&before.t, &after.t));
            if let Some(a) = rules.corner_acceleration {
                if step > 0.0 {
                    prev.end_cap = prev.end_cap.min(a * period / step);
                }
            }
            if let Some((k, v)) = rules.corner_coordinate_velocity {
                let share = before
                    .t
                    .get(k)
                    .map_or(0.0, |t| t.abs())
                    .max(after.t.get(k).map_or(0.0, |t| t.abs()));
                if step > 0.0 && share > 0.0 {
                    prev.end_cap = prev.end_cap.min(v / share);
                }
            }
            if changed && pi == 0 && self.exec.is_some() {
                self.replan_pending = true;
            }
        }
        if let Some(angles) = self.corner_angles {
            let k = angles.factor(direction_change(&before.t, &after.t));
            new.entry_factor = self.merge_rule.map_or(k, |r| r.suppress(k));
        }
        self.queue.push_back(Entry::Motion(Box::new(new)));
        pi
    }

    /// Round the corner between the motion at queue index `pi` and `new` (any segments; see
    /// `blend::corner_curve`): trims the previous motion in place and returns the blend and the
    /// trimmed new motion. `None` when there is no corner geometry to make, or the path is
    /// already past where the blend would begin, or too fast to enter it (HIMC TV 55, digest
    /// 004 §6.4: a motion blends only if the next is queued before it ends; then the corner
    /// rule applies).
    fn blend(
        &mut self,
        pi: usize,
        new: &QueuedMotion,
        transition: super::Transition,
        axes: &[AxisLimits],
    ) -> Option<(QueuedMotion, QueuedMotion)> {
        let period = self.config.period;
        let dims = self.config.dims;
        let executing = if pi == 0 { self.exec } else { None };
        let Some(Entry::Motion(prev)) = self.queue.get(pi) else {
            return None;
        };
        let rounded = corner_curve(&prev.segment, &new.segment, transition, dims)?;
        let mode = new.join;
        let programmed = PathLimits {
            velocity: mode_velocity(mode, prev.programmed.velocity, new.programmed.velocity),
            acceleration: prev
                .programmed
                .acceleration
                .min(new.programmed.acceleration),
            deceleration: prev
                .programmed
                .deceleration
                .min(new.programmed.deceleration),
            jerk: prev.programmed.jerk.min(new.programmed.jerk),
        };
        let rules = self.lookahead_limits;
        let mut arc = queued(
            rounded.blend,
            programmed,
            mode,
            new.tag,
            axes,
            period,
            &rules,
        );
        arc.reports_done = false;
        let mut rest = queued(
            rounded.tail,
            new.programmed,
            mode,
            new.tag,
            axes,
            period,
            &rules,
        );
        rest.reports_start = false;
        // The previous motion, shortened (installed only once the blend is sure to fit).
        let mut head = (**prev).clone();
        head.length = rounded.head.length();
        head.segment = rounded.head;
        relimit(&mut head, axes, period, &rules);
        // Where the curvature steps (a corner arc's ends), the junction rule.
        join(&mut arc, &mut rest, axes, period, &rules);
        join(&mut head, &mut arc, axes, period, &rules);
        if let Some(e) = executing {
            // The path must be able to enter the arc from where it is now.
            let l = &head.limits;
            let (v1, s1) = settle(e.v, e.a, l.jerk);
            let room = head.length - e.s - s1;
            if room < 0.0
                || lowest_end(v1, room, l.deceleration, l.jerk)
                    > entry_velocity(&arc, &rest).min(head.end_cap)
            {
                return None;
            }
        }
        if let Some(Entry::Motion(prev)) = self.queue.get_mut(pi) {
            **prev = head;
        }
        if executing.is_some() {
            self.replan_pending = true;
        }
        Some((arc, rest))
    }
}

/// The angle between two unit directions, radians in [0, π] (0 when either is 0).
fn direction_change(before: &crate::Point, after: &crate::Point) -> f64 {
    let (nb, na) = (crate::geometry::norm(before), crate::geometry::norm(after));
    if nb == 0.0 || na == 0.0 {
        return 0.0;
    }
    (crate::geometry::dot(before, after) / (nb * na))
        .clamp(-1.0, 1.0)
        .acos()
}
