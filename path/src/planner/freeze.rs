//! An emergency stop that keeps the path (NMC `NMC_CrdEstopMtn`, "急停(并不清空指令缓冲区)",
//! digest 001 §2.7, issue 13): the path stops where it is and the queue stays, the executing
//! motion cut at the break so that its remainder is the queue's front; the axes stop on their
//! own, off the path. A return motion put in front of the remainder (`NMC_CrdGotoBreak`)
//! brings the path back to the break, and `resume` finishes the program from there.

use super::push::queued;
use super::queue::Entry;
use super::{Halt, Motion, PathPlanner, PlannerError};
use crate::geometry::{norm, sub, POINT_TOLERANCE};
use crate::MAX_AXES;

impl PathPlanner {
    /// Stop at once where the path is (velocity 0 this step) and keep the queue, halted: the
    /// executing motion's remainder stays at the front (a line cut exactly, an arc by its
    /// centre and end; it reports `Started` again when it runs), the break point is the
    /// position. Nothing moves until [`PathPlanner::resume`].
    pub fn freeze(&mut self) {
        if let (Some(e), Some(Entry::Motion(m))) = (self.exec.take(), self.queue.front_mut()) {
            if e.s > 0.0 {
                m.segment = m.segment.trimmed(e.s, m.length);
                m.length = m.segment.length();
            }
            self.end_tangent = m.segment.start_tangent();
        }
        self.position = self.state.position;
        self.carry = 0.0;
        self.replan_pending = false;
        self.halt = Some(Halt {
            deceleration: None,
            stop: false,
        });
        self.at_rest_reported = true;
        self.state.halted = true;
        self.state.velocity = [0.0; MAX_AXES];
        self.state.acceleration = [0.0; MAX_AXES];
        self.state.path_velocity = 0.0;
        self.state.path_acceleration = 0.0;
        self.state.tag = None;
        // Every motion now starts from rest: the look-ahead again from the front.
        self.lookahead(0);
    }

    /// Halted with nothing executing and nothing carried: where a frozen path waits.
    fn halted_at_rest(&self) -> bool {
        self.state.halted && self.exec.is_none() && self.carry <= 0.0
    }

    /// Put `motion` in front of the queue of a frozen path (see [`PathPlanner::freeze`]): it
    /// starts wherever the axes now are and must end where the path broke off (the current
    /// position); the path's position moves to its start. It ends at rest (a junction into
    /// the remainder would need the two planned together; the break is a stop anyway).
    /// Refused unless halted at rest.
    pub fn insert_front(&mut self, motion: Motion) -> Result<(), PlannerError> {
        if !self.halted_at_rest() {
            return Err(PlannerError::Invalid(
                "a motion goes in front of the queue only while the path is halted at rest",
            ));
        }
        self.check_motion(&motion)?;
        let start = motion.segment.start();
        if start.iter().any(|c| !c.is_finite()) {
            return Err(PlannerError::Invalid("the segment's start is not finite"));
        }
        let end = motion.segment.end();
        let gap = norm(&sub(&end, &self.position));
        if gap.is_nan() || gap > POINT_TOLERANCE * (1.0 + norm(&self.position)) {
            return Err(PlannerError::Invalid(
                "the motion does not end where the path broke off",
            ));
        }
        super::limits::check_path_limits(&motion.limits).map_err(PlannerError::Invalid)?;
        let dims = self.config.dims.min(self.config.axes.len());
        let axes = self.config.axes;
        let q = queued(
            motion.segment,
            motion.limits,
            motion.join,
            motion.tag,
            axes.get(..dims).unwrap_or(&[]),
            self.config.period,
            &self.lookahead_limits,
        );
        self.end_tangent = q.segment.start_tangent();
        self.position = start;
        self.state.position = start;
        self.queue.push_front(Entry::Motion(Box::new(q)));
        self.user_entries += 1;
        self.lookahead(0);
        Ok(())
    }

    /// Drop the front motion of a frozen path if it is tagged `tag` (a motion put in front by
    /// [`PathPlanner::insert_front`] and cut by a second freeze): the path's position becomes
    /// its end, the break it was returning to. Whether it was dropped.
    pub fn drop_front(&mut self, tag: u64) -> bool {
        if !self.halted_at_rest() {
            return false;
        }
        let end = match self.queue.front() {
            Some(Entry::Motion(m)) if m.tag == tag => m.segment.end(),
            _ => return false,
        };
        self.pop_front();
        if let Some(Entry::Motion(m)) = self.queue.front() {
            self.end_tangent = m.segment.start_tangent();
        }
        self.position = end;
        self.state.position = end;
        self.lookahead(0);
        true
    }
}
