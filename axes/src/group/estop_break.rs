//! The group e-stop that keeps the path (NMC `NMC_CrdEstopMtn`: "急停(并不清空指令缓冲区)",
//! digest 001 §2.7; issue 13, docs/decisions.md "`NMC_CrdGotoBreak(acc, vel)`"). The planner
//! is frozen where the path was (the break), its queue kept with the executing motion cut
//! there; each member ramps down on its own with its emergency deceleration, off the path.
//! The reset returns to Halted (not Standby); the one motion then taken is a linear move from
//! where the members stand back to the break, put in front of what is left; `group_continue`
//! runs it and finishes the path.

use path::geometry::{Line, Segment};
use path::planner::{Join, Motion, Transition};

use super::queue::{Entry, Item};
use super::segment::{Construction, PathRequest};
use super::{Env, Group};
use crate::command::{CommandState, EngineError, Reply};
use crate::status::{GroupFault, GroupState};

impl Group {
    /// `group_emergency_stop` with `keep_path`. A group with no path moving or halted (idle,
    /// jogging, stopping, faulted) gets the plain e-stop.
    pub(super) fn emergency_stop_keeping_path(&mut self, env: &mut Env) -> bool {
        let has_path = matches!(self.state, GroupState::Moving | GroupState::Halted)
            && self.jog.is_none()
            && !self.planner.is_idle();
        if !has_path {
            return false;
        }
        self.planner.freeze();
        self.state = GroupState::ErrorStop;
        self.fault = Some(GroupFault::EmergencyStop);
        self.last_error = Some(crate::command::ErrorKind::Fault);
        // The members are let go (no more setpoints from the path) and stop on their own.
        self.release(env);
        self.emergency_stop_members(env);
        self.off_path = true;
        true
    }

    /// The move back to the break: `request` (a linear absolute move, its limits; the end it
    /// names is taken as the break) from where the members stand. In front of the path's
    /// remainder, replacing an earlier return a second e-stop cut; Halted until
    /// `group_continue`. It reports the interrupted motion's user segment unless it names one.
    pub(super) fn return_to_break(
        &mut self,
        env: &mut Env,
        request: PathRequest,
    ) -> Result<Reply, EngineError> {
        if self.state != GroupState::Halted {
            return Err(EngineError::GroupState {
                group: self.id,
                state: self.state,
                action: "return to the break point before its reset",
            });
        }
        // A return cut by a second e-stop is replaced: the break stays where the program was
        // interrupted (the manual's break point), not the point on the return line.
        if let Some(cut) = self.return_motion.take() {
            if self.planner.drop_front(u64::from(cut)) {
                self.queue.take(cut);
                env.ledger.finish(cut, CommandState::Aborted);
            }
        }
        let here = self.current_position(env.axes);
        let share = match request.begin(self.id, here, self.dims())? {
            Construction::Done(_, share) => share,
            Construction::Spline(_) => {
                return Err(self.off_path_refusal("a spline cannot return to the break point"))
            }
        };
        // It ends at the break exactly, whatever end it names: the caller's reading of the
        // break (its commanded position when it asked for the e-stop) may be a tick or more
        // late, and the remainder starts at the break.
        let at = self.planner.state().position;
        let segment = Line::new(here, at, self.dims())
            .map(Segment::Line)
            .map_err(|_| self.off_path_refusal("the line back to the break point"))?;
        let id = env.ledger.allocate();
        self.planner
            .insert_front(Motion {
                segment,
                limits: share.limits,
                join: Join::Buffered,
                transition: Transition::None,
                tag: u64::from(id),
            })
            .map_err(|e| self.planner_error(e))?;
        self.queue.push(Entry {
            id,
            item: Item::Motion {
                // None given (0): the way back into the interrupted motion is reported as it.
                user_segment: match request.user_segment {
                    0 => self.user_segment,
                    n => n,
                },
                length_ratio: share.ratio,
                speed_basis: None,
            },
        });
        self.off_path = false;
        self.return_motion = Some(id);
        Ok(Reply::Accepted { id })
    }

    fn off_path_refusal(&self, reason: &str) -> EngineError {
        EngineError::InvalidPath {
            group: self.id,
            reason: reason.to_string(),
        }
    }
}
