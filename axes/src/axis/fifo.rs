//! The per-axis command FIFO and the engine-wide command ledger (HMC §2.2).
//!
//! The FIFO holds the running command at its head and the commands waiting behind it; its depth
//! counts both (HMC: 64 slots, the executing one included). Finished commands leave the FIFO and
//! their final state goes to the [`Ledger`], where `command_state` finds it later.

use std::collections::VecDeque;

use crate::command::{CommandId, CommandKind, CommandState};
use crate::homing::HomingSpec;

/// Per-command kinematic overrides (PLCopen style); `None` = the axis parameter.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Overrides {
    pub velocity: Option<f64>,
    pub acceleration: Option<f64>,
    pub deceleration: Option<f64>,
    /// 0 = trapezoid.
    pub jerk: Option<f64>,
}

impl Overrides {
    pub fn any(&self) -> bool {
        self.velocity.is_some()
            || self.acceleration.is_some()
            || self.deceleration.is_some()
            || self.jerk.is_some()
    }
}

/// What a queued command asks for.
#[derive(Clone, Debug, PartialEq)]
pub enum MotionAction {
    MoveAbsolute {
        position: f64,
    },
    MoveRelative {
        distance: f64,
    },
    MoveVelocity {
        velocity: f64,
    },
    Home(HomingSpec),
    /// Run the axis's PT/PVT stream (issue 12 item 3).
    Stream,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Queued {
    pub id: CommandId,
    pub kind: CommandKind,
    pub action: MotionAction,
    pub overrides: Overrides,
}

/// Bounded FIFO of one axis. The head (index 0) is the running command while the axis runs one.
#[derive(Clone, Debug)]
pub struct Fifo {
    items: VecDeque<Queued>,
    depth: usize,
}

impl Fifo {
    pub fn new(depth: u16) -> Fifo {
        let depth = depth.max(1) as usize;
        Fifo {
            items: VecDeque::with_capacity(depth),
            depth,
        }
    }

    pub fn depth(&self) -> usize {
        self.depth
    }

    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    pub fn is_full(&self) -> bool {
        self.items.len() >= self.depth
    }

    /// Append; the caller checked `is_full`.
    pub fn push(&mut self, item: Queued) {
        self.items.push_back(item);
    }

    pub fn front(&self) -> Option<&Queued> {
        self.items.front()
    }

    pub fn get(&self, index: usize) -> Option<&Queued> {
        self.items.get(index)
    }

    pub fn pop_front(&mut self) -> Option<Queued> {
        self.items.pop_front()
    }

    pub fn remove(&mut self, index: usize) -> Option<Queued> {
        self.items.remove(index)
    }

    /// Remove everything, oldest first.
    pub fn drain(&mut self) -> impl Iterator<Item = Queued> + '_ {
        self.items.drain(..)
    }

    pub fn iter(&self) -> impl Iterator<Item = &Queued> {
        self.items.iter()
    }

    pub fn position_of(&self, id: CommandId) -> Option<usize> {
        self.items.iter().position(|q| q.id == id)
    }
}

/// Engine-wide command ids and the final states of finished commands.
#[derive(Clone, Debug)]
pub struct Ledger {
    next_id: CommandId,
    finished: VecDeque<(CommandId, CommandState)>,
    capacity: usize,
    /// While a checkpoint is open: every `finish`, with the entry it pushed out (if any), so
    /// that [`Ledger::rollback`] can undo them without copying the whole history.
    journal: Vec<Option<(CommandId, CommandState)>>,
    /// Checkpoints open (they nest: an atomic batch holding a `move_together`).
    open: u32,
}

/// Where [`Ledger::rollback`] returns to: from [`Ledger::checkpoint`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LedgerMark {
    next_id: CommandId,
    journal_len: usize,
}

/// How many finished commands the ledger remembers.
pub const LEDGER_CAPACITY: usize = 65_536;

impl Default for Ledger {
    fn default() -> Self {
        Ledger::with_capacity(LEDGER_CAPACITY)
    }
}

impl Ledger {
    pub fn with_capacity(capacity: usize) -> Ledger {
        Ledger {
            next_id: 1,
            finished: VecDeque::new(),
            capacity: capacity.max(1),
            journal: Vec::new(),
            open: 0,
        }
    }

    /// Open a checkpoint: from here, ids and finished commands can be rolled back to this
    /// point. Close it with [`Ledger::rollback`] or [`Ledger::commit`], innermost first.
    pub fn checkpoint(&mut self) -> LedgerMark {
        self.open += 1;
        LedgerMark {
            next_id: self.next_id,
            journal_len: self.journal.len(),
        }
    }

    /// Undo every id and finish since `mark`, and close its checkpoint.
    pub fn rollback(&mut self, mark: LedgerMark) {
        while self.journal.len() > mark.journal_len {
            let Some(evicted) = self.journal.pop() else {
                break;
            };
            self.finished.pop_back();
            if let Some(entry) = evicted {
                self.finished.push_front(entry);
            }
        }
        self.next_id = mark.next_id;
        self.close();
    }

    /// Keep everything since `mark`, and close its checkpoint.
    pub fn commit(&mut self, mark: LedgerMark) {
        let _ = mark;
        self.close();
    }

    fn close(&mut self) {
        self.open = self.open.saturating_sub(1);
        if self.open == 0 {
            self.journal.clear();
        }
    }

    /// A fresh id. Ids increase from 1 and wrap past u32::MAX back to 1 (0 is never issued).
    pub fn allocate(&mut self) -> CommandId {
        let id = self.next_id;
        self.next_id = self.next_id.checked_add(1).unwrap_or(1);
        id
    }

    /// Whether `id` was ever issued.
    pub fn issued(&self, id: CommandId) -> bool {
        id != 0 && id < self.next_id
    }

    /// Record the final state of a command.
    pub fn finish(&mut self, id: CommandId, state: CommandState) {
        let evicted = if self.finished.len() >= self.capacity {
            self.finished.pop_front()
        } else {
            None
        };
        self.finished.push_back((id, state));
        if self.open > 0 {
            self.journal.push(evicted);
        }
    }

    /// Final state of a finished command, if still remembered. Ids finish roughly in order, so
    /// search from the newest.
    pub fn lookup(&self, id: CommandId) -> Option<CommandState> {
        self.finished
            .iter()
            .rev()
            .find(|(i, _)| *i == id)
            .map(|(_, s)| *s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fifo_is_bounded_and_ordered() {
        let mut f = Fifo::new(2);
        let q = |id| Queued {
            id,
            kind: CommandKind::MoveRelative,
            action: MotionAction::MoveRelative { distance: 1.0 },
            overrides: Overrides::default(),
        };
        f.push(q(1));
        assert!(!f.is_full());
        f.push(q(2));
        assert!(f.is_full());
        assert_eq!(f.position_of(2), Some(1));
        assert_eq!(f.pop_front().map(|q| q.id), Some(1));
        assert_eq!(f.front().map(|q| q.id), Some(2));
    }

    #[test]
    fn ledger_ids_and_history() {
        let mut l = Ledger::with_capacity(2);
        let a = l.allocate();
        let b = l.allocate();
        let c = l.allocate();
        assert_eq!((a, b, c), (1, 2, 3));
        assert!(l.issued(3) && !l.issued(4) && !l.issued(0));
        l.finish(a, CommandState::Done);
        l.finish(b, CommandState::Aborted);
        l.finish(c, CommandState::Done);
        assert_eq!(l.lookup(a), None, "evicted");
        assert_eq!(l.lookup(b), Some(CommandState::Aborted));
        let mut w = Ledger::with_capacity(1);
        w.next_id = u32::MAX;
        assert_eq!(w.allocate(), u32::MAX);
        assert_eq!(w.allocate(), 1);
    }

    #[test]
    fn ledger_rollback_undoes_ids_and_finishes_even_past_the_capacity() {
        let history = |l: &Ledger| l.finished.iter().copied().collect::<Vec<_>>();
        let mut l = Ledger::with_capacity(3);
        for _ in 0..3 {
            let id = l.allocate();
            l.finish(id, CommandState::Done);
        }
        let before = history(&l);
        let outer = l.checkpoint();
        let id = l.allocate();
        l.finish(id, CommandState::Aborted);
        let inner = l.checkpoint();
        for _ in 0..4 {
            let id = l.allocate();
            l.finish(id, CommandState::Done);
        }
        l.rollback(inner);
        assert_eq!(l.lookup(4), Some(CommandState::Aborted));
        assert_eq!(
            l.allocate(),
            5,
            "the inner checkpoint's ids are issued again"
        );
        l.rollback(outer);
        assert_eq!(history(&l), before);
        assert_eq!(l.allocate(), 4);
        assert!(l.journal.is_empty() && l.open == 0);
        let mark = l.checkpoint();
        l.finish(4, CommandState::Done);
        l.commit(mark);
        assert_eq!(l.lookup(4), Some(CommandState::Done));
        assert!(l.journal.is_empty());
    }
}
