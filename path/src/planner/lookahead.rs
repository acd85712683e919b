//! The look-ahead (issue 11 item 4): a backward pass over the first `config.lookahead`
//! queued motions that gives each the highest velocity at its end from which the path can
//! still stop by the end of the window, under every junction's cap and every motion's
//! deceleration (NMC TLookaheadPara n segments, digest 001 §2.7/§3.7; LinuxCNC's planner
//! does the same over its queue). The last motion of the window ends at rest, so the path
//! never depends on motions not yet queued.
//!
//! It runs when a motion is pushed, when the override changes and when a motion completes
//! while more than the window is queued — never per tick otherwise. The pass walks back from
//! the window's end and stops at the first motion before the changed ones whose results did
//! not change: at most `lookahead` motions, each a few arithmetic operations and square roots
//! (`reach`), so a push costs O(lookahead) in the worst case and O(1) typically.

use super::junction::mode_velocity;
use super::merge::junction_preference;
use super::queue::Entry;
use super::reach::reach;
use super::{MarkerKind, PathPlanner};

/// What the pass carries from a motion to the one before it.
#[derive(Clone, Copy)]
struct Next {
    start_phys: f64,
    start_pref: f64,
    join: super::Join,
    cruise: f64,
    cap: f64,
    /// The corner-angle factor of the junction into it.
    factor: f64,
}

impl PathPlanner {
    /// Recompute the look-ahead results; entries before queue index `dirty_from` have
    /// unchanged data, so the pass may stop there once a result repeats. Sets
    /// `replan_pending` when the executing motion's end velocity changed.
    pub(super) fn lookahead(&mut self, dirty_from: usize) {
        let window = self.config.lookahead.max(1);
        let mut count = 0;
        let mut last = None;
        for (i, e) in self.queue.iter().enumerate() {
            if matches!(e, Entry::Motion(_)) {
                count += 1;
                last = Some(i);
                if count == window {
                    break;
                }
            }
        }
        let Some(last) = last else { return };
        let factor = self.override_factor;
        let mut next: Option<Next> = None;
        let mut hold_between = false;
        let mut front_changed = false;
        for i in (0..=last).rev() {
            let Some(entry) = self.queue.get_mut(i) else {
                continue;
            };
            self.lookahead_visits += 1;
            let m = match entry {
                Entry::Marker { kind, .. } => {
                    hold_between |= *kind == MarkerKind::Hold;
                    continue;
                }
                Entry::Motion(m) => m,
            };
            let cruise = m.cruise(factor);
            let cap = m.limits.velocity_cap;
            let (end_phys, end_pref) = match next {
                // The window's last motion, or a Hold marker after it: an exact stop.
                None => (0.0, 0.0),
                Some(_) if hold_between => (0.0, 0.0),
                Some(n) => {
                    let junction = m.end_cap.min(cap).min(n.cap);
                    let requested =
                        junction.min(mode_velocity(n.join, cruise, n.cruise) * n.factor);
                    (
                        junction.min(n.start_phys),
                        junction_preference(self.merge_rule, requested, n.start_pref),
                    )
                }
            };
            let l = &m.limits;
            let start_phys = reach(end_phys, m.length, l.deceleration, l.jerk).min(cap);
            let start_pref = reach(end_pref, m.length, l.deceleration, l.jerk).min(cap);
            let unchanged = m.end_phys == end_phys
                && m.end_pref == end_pref
                && m.start_phys == start_phys
                && m.start_pref == start_pref;
            m.end_phys = end_phys;
            m.end_pref = end_pref;
            m.start_phys = start_phys;
            m.start_pref = start_pref;
            if i == 0 && !unchanged {
                front_changed = true;
            }
            if unchanged && i < dirty_from {
                break;
            }
            next = Some(Next {
                start_phys,
                start_pref,
                join: m.join,
                cruise,
                cap,
                factor: m.entry_factor,
            });
            hold_between = false;
        }
        if front_changed && self.exec.is_some() {
            self.replan_pending = true;
        }
    }
}
