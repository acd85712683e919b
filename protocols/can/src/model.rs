//! The bit-rate model of a bus, sans-IO: frames queued by senders wait for the bus; when the
//! bus goes idle, the queued frame with the highest priority (lowest arbitration key, i.e.
//! lowest id) wins and occupies the bus for its bit time. Time is whatever the caller passes
//! as `now` (a virtual clock in tests and in the engine, real time under a driver task).
//!
//! A frame is eligible for an arbitration round when it was queued at or before the round's
//! start; a round starts when the bus goes idle with frames waiting, or when a frame arrives at
//! an idle bus. A transmission that started is not pre-empted by a later, higher-priority
//! frame, as on a real bus. Results do not depend on how often `advance` is called.

use std::cmp::{Ordering, Reverse};
use std::collections::{BinaryHeap, VecDeque};
use std::time::Duration;

use crate::frame::WireFrame;
use crate::timing::{arbitration_key, BitTiming};

/// The transmit queue is full: the frame was not queued (SocketCAN's `ENOBUFS`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the bus's transmit queue is full ({capacity} frames waiting)")]
pub struct TxQueueFull {
    pub capacity: usize,
}

/// A frame that went over the bus.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Transmitted<T> {
    pub frame: WireFrame,
    /// What the sender attached (the hub: the sending endpoint).
    pub tag: T,
    pub queued_at: Duration,
    pub start: Duration,
    /// End of the frame (intermission included): when receivers have it.
    pub end: Duration,
}

struct Queued<T> {
    frame: WireFrame,
    tag: T,
    queued_at: Duration,
    key: u32,
    seq: u64,
}

// Heap order: arbitration key, then arrival order (equal ids: first queued first).
impl<T> PartialEq for Queued<T> {
    fn eq(&self, other: &Self) -> bool {
        (self.key, self.seq) == (other.key, other.seq)
    }
}
impl<T> Eq for Queued<T> {}
impl<T> PartialOrd for Queued<T> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl<T> Ord for Queued<T> {
    fn cmp(&self, other: &Self) -> Ordering {
        (self.key, self.seq).cmp(&(other.key, other.seq))
    }
}

/// A bus with a bit rate: a transmit queue, arbitration by id, and bus-time accounting.
pub struct BusModel<T> {
    timing: BitTiming,
    capacity: usize,
    /// Frames not yet eligible for the round in progress, in arrival order.
    arrivals: VecDeque<Queued<T>>,
    /// Frames eligible for the current or next round, lowest key on top.
    ready: BinaryHeap<Reverse<Queued<T>>>,
    bus_free_at: Duration,
    /// Latest `now` seen: arrivals are never dated before it, so rounds already decided stay
    /// decided.
    last_now: Duration,
    seq: u64,
    busy: Duration,
}

impl<T> BusModel<T> {
    /// A model with `capacity` frames of transmit queue (at least 1).
    pub fn new(timing: BitTiming, capacity: usize) -> Self {
        Self {
            timing,
            capacity: capacity.max(1),
            arrivals: VecDeque::new(),
            ready: BinaryHeap::new(),
            bus_free_at: Duration::ZERO,
            last_now: Duration::ZERO,
            seq: 0,
            busy: Duration::ZERO,
        }
    }

    pub fn timing(&self) -> BitTiming {
        self.timing
    }

    /// Queue `frame` for transmission at `now` (dated no earlier than the last `advance`).
    pub fn enqueue(&mut self, frame: WireFrame, tag: T, now: Duration) -> Result<(), TxQueueFull> {
        if self.pending() >= self.capacity {
            return Err(TxQueueFull {
                capacity: self.capacity,
            });
        }
        let queued_at = now.max(self.last_now);
        self.last_now = queued_at;
        self.seq += 1;
        self.arrivals.push_back(Queued {
            key: arbitration_key(&frame),
            frame,
            tag,
            queued_at,
            seq: self.seq,
        });
        Ok(())
    }

    /// Frames waiting for the bus (including one being transmitted).
    pub fn pending(&self) -> usize {
        self.arrivals.len() + self.ready.len()
    }

    /// Total bus time spent transmitting.
    pub fn busy(&self) -> Duration {
        self.busy
    }

    /// Run the bus up to `now`: every frame whose transmission ends at or before `now` goes to
    /// `emit`, in bus order. Returns when the next transmission in progress or due will end
    /// (`None`: nothing is waiting).
    pub fn advance(
        &mut self,
        now: Duration,
        mut emit: impl FnMut(Transmitted<T>),
    ) -> Option<Duration> {
        self.last_now = self.last_now.max(now);
        loop {
            let start = self.next_round_start()?;
            // The round is decided at `start`: the bus is taken from then on, so a later call
            // resumes the same round.
            self.bus_free_at = start;
            while let Some(first) = self.arrivals.front() {
                if first.queued_at > start {
                    break;
                }
                if let Some(queued) = self.arrivals.pop_front() {
                    self.ready.push(Reverse(queued));
                }
            }
            let Some(Reverse(winner)) = self.ready.peek() else {
                return None; // unreachable: the round start came from a waiting frame
            };
            let length = self.timing.frame_time(&winner.frame);
            let end = start + length;
            if end > now {
                return Some(end);
            }
            let Reverse(winner) = self.ready.pop()?;
            self.bus_free_at = end;
            self.busy += length;
            emit(Transmitted {
                frame: winner.frame,
                tag: winner.tag,
                queued_at: winner.queued_at,
                start,
                end,
            });
        }
    }

    /// When the next arbitration round starts: at once when the bus frees if frames are
    /// eligible, else when the first arrival comes (not before the bus frees).
    fn next_round_start(&self) -> Option<Duration> {
        if !self.ready.is_empty() {
            return Some(self.bus_free_at);
        }
        let first = self.arrivals.front()?;
        Some(first.queued_at.max(self.bus_free_at))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::timing::Stuffing;

    fn model() -> BusModel<u32> {
        // 1 Mbit/s with no stuffing: a standard frame with n bytes takes 47 + 8n µs.
        BusModel::new(
            BitTiming::new(1_000_000)
                .unwrap()
                .with_stuffing(Stuffing::None),
            16,
        )
    }

    fn frame(id: u16) -> WireFrame {
        WireFrame::standard(id, &[]).unwrap()
    }

    fn run(model: &mut BusModel<u32>, now: Duration) -> Vec<(u32, u64, u64)> {
        let mut out = vec![];
        model.advance(now, |t| {
            out.push((t.tag, t.start.as_micros() as u64, t.end.as_micros() as u64))
        });
        out
    }

    #[test]
    fn lowest_id_wins_among_queued_frames() {
        let mut m = model();
        let t0 = Duration::ZERO;
        m.enqueue(frame(0x300), 1, t0).unwrap();
        m.enqueue(frame(0x100), 2, t0).unwrap();
        m.enqueue(frame(0x200), 3, t0).unwrap();
        assert_eq!(
            run(&mut m, Duration::from_micros(1000)),
            [(2, 0, 47), (3, 47, 94), (1, 94, 141)]
        );
        assert_eq!(m.busy(), Duration::from_micros(141));
    }

    #[test]
    fn a_started_frame_is_not_preempted_and_results_do_not_depend_on_polling() {
        let script = |polls: &[u64]| {
            let mut m = model();
            m.enqueue(frame(0x300), 1, Duration::ZERO).unwrap();
            let mut out = vec![];
            for &p in polls {
                out.extend(run(&mut m, Duration::from_micros(p)));
                if p == 10 {
                    // Arrives while 0x300 is on the bus: waits, then goes before 0x200.
                    m.enqueue(frame(0x100), 2, Duration::from_micros(10))
                        .unwrap();
                    m.enqueue(frame(0x200), 3, Duration::from_micros(10))
                        .unwrap();
                }
            }
            out.extend(run(&mut m, Duration::from_secs(1)));
            out
        };
        let expected = [(1, 0, 47), (2, 47, 94), (3, 94, 141)];
        assert_eq!(script(&[10]), expected);
        assert_eq!(script(&[0, 5, 10, 46, 47, 50, 93, 94, 100]), expected);
    }

    #[test]
    fn idle_bus_starts_on_arrival_and_reports_the_next_completion() {
        let mut m = model();
        assert_eq!(m.advance(Duration::from_micros(100), |_| {}), None);
        m.enqueue(frame(1), 7, Duration::from_micros(200)).unwrap();
        assert_eq!(
            m.advance(Duration::from_micros(200), |_| {}),
            Some(Duration::from_micros(247))
        );
        assert_eq!(run(&mut m, Duration::from_micros(247)), [(7, 200, 247)]);
        assert_eq!(m.pending(), 0);
    }

    #[test]
    fn full_queue_refuses() {
        let mut m = BusModel::new(BitTiming::new(125_000).unwrap(), 2);
        m.enqueue(frame(1), 1, Duration::ZERO).unwrap();
        m.enqueue(frame(2), 2, Duration::ZERO).unwrap();
        assert_eq!(
            m.enqueue(frame(3), 3, Duration::ZERO),
            Err(TxQueueFull { capacity: 2 })
        );
    }
}
