//! Splines still under construction, and the commands accepted after them (issue 11 item 4:
//! the planning work per tick bounded; docs/decisions.md, "Group tick and spline acceptance
//! cost").
//!
//! Constructing a spline (its pieces' bounds and lengths) costs some 48 k instructions per
//! point, so a 1000-point spline built when it is applied would take several servo periods.
//! A motion's segment is built when it is accepted, but a spline's construction only begins
//! there and does at most `spline_spans_per_tick` spans; a longer one waits here with every
//! command accepted after it (the planner needs a motion's length and bounds when it is
//! pushed, and the next command starts where the spline ends), and each tick does at most
//! `spline_spans_per_tick` more spans. When the spline is done it is pushed to the planner
//! and the commands after it follow in the same tick, in order, as if applied then: the same
//! motion, started that many ticks later (the same path if it was built before the path
//! before it ended). A refusal that only the construction finds (a cusp), or that a later
//! command's geometry meets at its start, ends that command with the error in the ledger and
//! aborts those after it, which would start elsewhere than they were given.
//!
//! Inputs: [`Group::place_motion`] and [`Group::accept_marker`] (from `apply`),
//! [`Group::advance_staging`] (once per tick, before the planner steps). Dropped with the
//! queue ([`Group::abort_staged`]).

use std::collections::VecDeque;

use path::planner::MarkerKind;

use super::queue::{Entry, Item};
use super::segment::{Construction, PathRequest, StagedSpline};
use super::{Env, Group};
use crate::command::{AxisIndex, CommandId, CommandState, EngineError};

/// See the module doc. Empty unless a spline is under construction.
#[derive(Clone, Debug)]
pub(super) struct Staging {
    /// Spline spans constructed per tick, and at most per `move_spline` applied
    /// (`[groups] spline_spans_per_tick`).
    spans_per_tick: usize,
    building: Option<Box<Building>>,
    /// Accepted after the spline, in order; empty while nothing is built.
    after: VecDeque<Staged>,
}

#[derive(Clone, Debug)]
struct Building {
    id: CommandId,
    request: PathRequest,
    staged: StagedSpline,
}

#[derive(Clone, Debug)]
enum Staged {
    Motion {
        id: CommandId,
        request: Box<PathRequest>,
    },
    Marker {
        id: CommandId,
        item: Item,
        kind: MarkerKind,
    },
}

impl Staged {
    fn id(&self) -> CommandId {
        match self {
            Staged::Motion { id, .. } | Staged::Marker { id, .. } => *id,
        }
    }
}

impl Staging {
    pub fn new(spans_per_tick: u32) -> Staging {
        Staging {
            spans_per_tick: (spans_per_tick as usize).max(1),
            building: None,
            after: VecDeque::new(),
        }
    }

    /// A spline is under construction: new commands wait behind it.
    pub fn is_busy(&self) -> bool {
        self.building.is_some()
    }

    /// Commands held here.
    pub fn len(&self) -> usize {
        usize::from(self.building.is_some()) + self.after.len()
    }

    pub fn contains(&self, id: CommandId) -> bool {
        self.building.as_ref().is_some_and(|b| b.id == id)
            || self.after.iter().any(|s| s.id() == id)
    }

    /// The position the last staged `group_axis_move` of `axis` goes to.
    pub fn last_axis_move(&self, axis: AxisIndex) -> Option<f64> {
        self.after.iter().rev().find_map(|s| match s {
            Staged::Marker {
                item: Item::AxisMove(m),
                ..
            } if m.axis == axis => Some(m.position),
            _ => None,
        })
    }
}

impl Group {
    /// Queue a checked motion that does not abort (or one that waited for rest), under `id`
    /// or, once it is accepted, a new id: behind a spline under construction, or built from
    /// the queue's end now; a spline longer than `spline_spans_per_tick` spans is staged.
    /// The caller has checked the room.
    pub(super) fn place_motion(
        &mut self,
        env: &mut Env,
        id: Option<CommandId>,
        request: PathRequest,
    ) -> Result<CommandId, EngineError> {
        let take_id = |env: &mut Env| id.unwrap_or_else(|| env.ledger.allocate());
        if self.staging.is_busy() {
            let id = take_id(env);
            self.staging.after.push_back(Staged::Motion {
                id,
                request: Box::new(request),
            });
            return Ok(id);
        }
        self.sync_position(env)?;
        let start = self.planner.queue_end();
        let (segment, share) = match request.begin(self.id, start, self.dims())? {
            Construction::Done(segment, share) => (segment, share),
            Construction::Spline(mut staged) => {
                if !staged.spline.advance(self.staging.spans_per_tick).1 {
                    let id = take_id(env);
                    self.staging.building = Some(Box::new(Building {
                        id,
                        request,
                        staged,
                    }));
                    return Ok(id);
                }
                request.finish(self.id, staged, self.dims())?
            }
        };
        // Built before the id is taken: a refused motion uses none.
        let id = take_id(env);
        self.enqueue_segment(env, id, segment, share, &request)?;
        Ok(id)
    }

    /// Queue a checked buffered command: behind a spline under construction, or to the
    /// planner now. The caller has checked the room and synchronised the position.
    pub(super) fn accept_marker(
        &mut self,
        env: &mut Env,
        item: Item,
        kind: MarkerKind,
    ) -> Result<CommandId, EngineError> {
        if self.staging.is_busy() {
            let id = env.ledger.allocate();
            self.staging
                .after
                .push_back(Staged::Marker { id, item, kind });
            return Ok(id);
        }
        let id = env.ledger.allocate();
        self.push_marker(id, item, kind)?;
        Ok(id)
    }

    pub(super) fn push_marker(
        &mut self,
        id: CommandId,
        item: Item,
        kind: MarkerKind,
    ) -> Result<(), EngineError> {
        // A buffered command between two motions: no corner stop at that junction (`corner`).
        self.last_direction = None;
        self.planner
            .push_marker(u64::from(id), kind)
            .map_err(|e| self.planner_error(e))?;
        self.queue.push(Entry { id, item });
        Ok(())
    }

    /// This tick's share of the spline under construction: at most `spline_spans_per_tick`
    /// spans in all; a spline done is pushed to the planner with the commands after it, up to
    /// the next spline, which takes what is left of the tick's spans.
    pub(super) fn advance_staging(&mut self, env: &mut Env) {
        let mut budget = self.staging.spans_per_tick;
        while let Some(mut building) = self.staging.building.take() {
            let (visited, done) = building.staged.spline.advance(budget);
            budget = budget.saturating_sub(visited);
            if !done {
                self.staging.building = Some(building);
                return;
            }
            let Building {
                id,
                request,
                staged,
            } = *building;
            let pushed =
                request
                    .finish(self.id, staged, self.dims())
                    .and_then(|(segment, share)| {
                        self.enqueue_segment(env, id, segment, share, &request)
                    });
            if let Err(e) = pushed {
                self.refuse_staged(env, id, e);
                return;
            }
            self.release_staged(env);
        }
    }

    /// Push the commands staged after a finished spline, in order, until the next spline
    /// (begun, and staged: [`Group::advance_staging`] goes on with it).
    fn release_staged(&mut self, env: &mut Env) {
        while let Some(next) = self.staging.after.pop_front() {
            let result = match next {
                Staged::Marker { id, item, kind } => {
                    self.push_marker(id, item, kind).map_err(|e| (id, e))
                }
                Staged::Motion { id, request } => self.release_motion(env, id, *request),
            };
            match result {
                Ok(()) if self.staging.is_busy() => return,
                Ok(()) => {}
                Err((id, e)) => {
                    self.refuse_staged(env, id, e);
                    return;
                }
            }
        }
    }

    /// A staged motion built from the queue's end now (a spline: begun and staged again).
    fn release_motion(
        &mut self,
        env: &mut Env,
        id: CommandId,
        request: PathRequest,
    ) -> Result<(), (CommandId, EngineError)> {
        let start = self.planner.queue_end();
        let built = request
            .begin(self.id, start, self.dims())
            .map_err(|e| (id, e))?;
        match built {
            Construction::Done(segment, share) => self
                .enqueue_segment(env, id, segment, share, &request)
                .map_err(|e| (id, e)),
            Construction::Spline(staged) => {
                self.staging.building = Some(Box::new(Building {
                    id,
                    request,
                    staged,
                }));
                Ok(())
            }
        }
    }

    /// A staged command refused when it came to be built: it ends with the error, and every
    /// command staged after it is aborted.
    fn refuse_staged(&mut self, env: &mut Env, id: CommandId, e: EngineError) {
        let kind = e.kind();
        self.last_error = Some(kind);
        env.ledger.finish(id, CommandState::Error(kind));
        self.abort_staged(env);
    }

    /// Drop everything staged: each command ends aborted.
    pub(super) fn abort_staged(&mut self, env: &mut Env) {
        if let Some(b) = self.staging.building.take() {
            env.ledger.finish(b.id, CommandState::Aborted);
        }
        for s in self.staging.after.drain(..) {
            env.ledger.finish(s.id(), CommandState::Aborted);
        }
    }
}
