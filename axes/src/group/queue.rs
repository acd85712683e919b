//! The group queue as the group sees it: the planner holds the geometry, this mirror holds what
//! each entry is (its command id is the planner's tag) so the planner's events can be turned
//! into command states and the buffered commands' effects (issue 11 item 5).

use std::collections::VecDeque;

use crate::command::{
    AxisIndex, CommandId, GroupAxisMove, GroupId, PositionCondition, PositionSource,
};

/// A buffered non-motion command, or a motion.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Item {
    /// A path motion; `user_segment` is reported while it runs; `length_ratio` is its counted
    /// length per path length (`segment::length_ratio`).
    Motion {
        user_segment: u32,
        length_ratio: f64,
        /// The result axis's `speed` this motion's velocity was taken from (none given, HMC):
        /// a live change of it changes the path speed (digest 000 §4.3).
        speed_basis: Option<f64>,
    },
    /// Set a digital output as the path passes (NMC CrdBufDO).
    SetOutput { channel: u16, value: bool },
    /// Stand for a number of ticks (NMC CrdBufDelay).
    Dwell { ticks: u64 },
    /// Stand until the digital input has the level (NMC CrdBufWaitDI).
    WaitInput {
        channel: u16,
        level: bool,
        timeout: Option<u64>,
    },
    /// Stand until the axis's position meets the condition.
    WaitPosition {
        axis: AxisIndex,
        position: f64,
        tolerance: f64,
        timeout: Option<u64>,
        condition: PositionCondition,
        /// `None`: the actual position.
        source: Option<PositionSource>,
    },
    /// Start a single-axis move of a non-member axis (NMC CrdBufAxMoveEx).
    AxisMove(GroupAxisMove),
    /// Stand at a tangential axis's corner stop until released (`corner`); the next motion
    /// starts in `next_direction` (radians, in the tracked plane).
    CornerStop { next_direction: f64 },
    /// Buffered I/O or a stop, here or at a path distance from here (`buffered_io`).
    Io { action: IoAction, at: PathPoint },
}

/// What a buffered I/O marker does.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum IoAction {
    /// `level` written (if any), then `toggles` toggles, or (0) the end of a running train.
    Digital {
        channel: u16,
        level: Option<bool>,
        level_time: f64,
        other_time: f64,
        toggles: u32,
    },
    Analog {
        channel: u16,
        value: f64,
    },
    /// Watch `slot` set to (input, level), or ended.
    StopInput {
        slot: u16,
        watch: Option<(u16, bool)>,
    },
    Halt {
        target: GroupId,
        deceleration: Option<f64>,
    },
}

/// Where on the path a marker acts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum PathPoint {
    /// Where the marker stands.
    Here,
    /// This much path length past it.
    After(f64),
    /// This much path length before the end of the motion queued when the path reaches it.
    BeforeEnd(f64),
}

#[derive(Clone, Debug, PartialEq)]
pub(super) struct Entry {
    pub id: CommandId,
    pub item: Item,
}

/// A buffered wait the path stands at, since `since` (tick).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Wait {
    pub id: CommandId,
    pub item: Item,
    pub since: u64,
}

/// The entries in queue order, bounded by the group's capacity.
#[derive(Clone, Debug)]
pub(super) struct GroupQueue {
    entries: VecDeque<Entry>,
    capacity: u32,
}

impl GroupQueue {
    pub fn new(capacity: u32) -> GroupQueue {
        GroupQueue {
            entries: VecDeque::new(),
            capacity,
        }
    }

    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn push(&mut self, entry: Entry) {
        self.entries.push_back(entry);
    }

    pub fn contains(&self, id: CommandId) -> bool {
        self.entries.iter().any(|e| e.id == id)
    }

    pub fn get(&self, id: CommandId) -> Option<&Entry> {
        self.entries.iter().find(|e| e.id == id)
    }

    /// Take the entry `id` out (events arrive in queue order, so it is at or near the front).
    pub fn take(&mut self, id: CommandId) -> Option<Entry> {
        let i = self.entries.iter().position(|e| e.id == id)?;
        self.entries.remove(i)
    }

    /// The position the last queued `group_axis_move` of `axis` goes to.
    pub fn last_axis_move(&self, axis: AxisIndex) -> Option<f64> {
        self.entries.iter().rev().find_map(|e| match &e.item {
            Item::AxisMove(m) if m.axis == axis => Some(m.position),
            _ => None,
        })
    }

    /// Remove everything, oldest first.
    pub fn drain(&mut self) -> impl Iterator<Item = Entry> + '_ {
        self.entries.drain(..)
    }
}
