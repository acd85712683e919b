//! An in-process CAN bus with virtual time: nodes hear every frame except their own, a test
//! master sends and sees everything the nodes send. Deterministic: delivery is in order of
//! transmission, nodes in the order they were added.

use std::collections::VecDeque;
use std::time::Duration;

use axes::od::{Access, DataType, EntryDef, ObjectDictionary, Value};

use crate::device::Device;
use crate::frame::CanFrame;
use crate::node::Node;

/// A bound on frames routed per call, so that two nodes answering each other forever cannot
/// hang a test.
const MAX_ROUTED: usize = 1_000_000;

/// The bus and the nodes on it.
#[derive(Debug)]
pub struct Bus<D: Device = ObjectDictionary> {
    nodes: Vec<Node<D>>,
    now: Duration,
    log: Option<Vec<(Duration, CanFrame)>>,
    scratch: Vec<CanFrame>,
}

impl<D: Device> Default for Bus<D> {
    fn default() -> Self {
        Bus {
            nodes: Vec::new(),
            now: Duration::ZERO,
            log: None,
            scratch: Vec::new(),
        }
    }
}

impl<D: Device> Bus<D> {
    pub fn new() -> Bus<D> {
        Bus::default()
    }

    /// Add a node; returns its position.
    pub fn add(&mut self, node: Node<D>) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    pub fn node(&self, i: usize) -> Option<&Node<D>> {
        self.nodes.get(i)
    }

    pub fn node_mut(&mut self, i: usize) -> Option<&mut Node<D>> {
        self.nodes.get_mut(i)
    }

    pub fn nodes(&self) -> &[Node<D>] {
        &self.nodes
    }

    pub fn now(&self) -> Duration {
        self.now
    }

    /// Keep every frame with its time (a `candump -L`-like trace).
    pub fn record(&mut self, on: bool) {
        self.log = on.then(Vec::new);
    }

    pub fn log(&self) -> &[(Duration, CanFrame)] {
        self.log.as_deref().unwrap_or_default()
    }

    /// Start every node (boot-up); returns what they sent.
    pub fn start(&mut self) -> Vec<CanFrame> {
        let mut seen = Vec::new();
        for k in 0..self.nodes.len() {
            let now = self.now;
            let sent = self
                .nodes
                .get_mut(k)
                .map(|n| n.start(now))
                .unwrap_or_default();
            self.spread(Some(k), sent, &mut seen);
        }
        seen
    }

    /// The master transmits `frame`; returns every frame the nodes sent in reaction.
    pub fn send(&mut self, frame: CanFrame) -> Vec<CanFrame> {
        let mut seen = Vec::new();
        self.send_into(frame, &mut seen);
        seen
    }

    /// [`send`](Self::send) appending to `seen`.
    pub fn send_into(&mut self, frame: CanFrame, seen: &mut Vec<CanFrame>) {
        self.spread(None, vec![frame], seen);
    }

    /// Advance virtual time to `until` in steps of `step` (at least 1 ns), ticking every node;
    /// returns what the nodes sent.
    pub fn advance(&mut self, until: Duration, step: Duration) -> Vec<CanFrame> {
        let step = step.max(Duration::from_nanos(1));
        let mut seen = Vec::new();
        while self.now < until {
            self.now = (self.now + step).min(until);
            self.tick(&mut seen);
        }
        seen
    }

    /// Advance by `dt` in steps of `step`.
    pub fn advance_by(&mut self, dt: Duration, step: Duration) -> Vec<CanFrame> {
        self.advance(self.now + dt, step)
    }

    /// Tick every node at the present time.
    pub fn tick(&mut self, seen: &mut Vec<CanFrame>) {
        for k in 0..self.nodes.len() {
            let now = self.now;
            let mut out = Vec::new();
            if let Some(n) = self.nodes.get_mut(k) {
                n.on_tick_into(now, &mut out);
            }
            self.spread(Some(k), out, seen);
        }
    }

    /// Deliver `frames` sent by `from` (None: the master) to everyone else, then what those
    /// deliveries caused, in order.
    fn spread(&mut self, from: Option<usize>, frames: Vec<CanFrame>, seen: &mut Vec<CanFrame>) {
        let mut queue: VecDeque<(Option<usize>, CanFrame)> =
            frames.into_iter().map(|f| (from, f)).collect();
        let mut routed = 0;
        let mut out = std::mem::take(&mut self.scratch);
        while let Some((sender, frame)) = queue.pop_front() {
            routed += 1;
            if routed > MAX_ROUTED {
                break;
            }
            if let Some(log) = &mut self.log {
                log.push((self.now, frame));
            }
            if sender.is_some() {
                seen.push(frame);
            }
            for (k, node) in self.nodes.iter_mut().enumerate() {
                if Some(k) == sender {
                    continue;
                }
                out.clear();
                node.on_frame_into(&frame, self.now, &mut out);
                queue.extend(out.iter().map(|f| (Some(k), *f)));
            }
        }
        out.clear();
        self.scratch = out;
    }
}

/// A small application dictionary for tests, benchmarks and examples: one entry of each kind a
/// master meets (ranges, write-only, strings, a DOMAIN for block transfers, PDO-mappable
/// process data in both directions).
pub fn sample_dictionary() -> ObjectDictionary {
    use Access::{Const, Ro, Rw, Rwr, Rww, Wo};
    let e = EntryDef::new;
    let table = [
        e(0x2000, 0, "Parameter", Rw, Value::U32(0)).range(Value::U32(0), Value::U32(1000)),
        e(0x2001, 0, "Signed parameter", Rw, Value::I16(0))
            .range(Value::I16(-100), Value::I16(100)),
        e(0x2002, 0, "Command", Wo, Value::U8(0)),
        e(0x2003, 0, "Text", Rw, Value::String(String::new())),
        e(0x2004, 0, "Blob", Rw, Value::Bytes(Vec::new())).data_type(DataType::Domain),
        e(0x2005, 0, "Input", Ro, Value::U16(0)).pdo(),
        e(0x2006, 0, "Output", Rww, Value::I32(0)).pdo(),
        e(0x2007, 0, "Small output", Rww, Value::U8(0)).pdo(),
        e(
            0x2008,
            0,
            "Firmware",
            Const,
            Value::String("mcemu sample firmware 1.0".into()),
        ),
        e(0x2009, 0, "Process value", Rwr, Value::U32(0)).pdo(),
        e(0x200A, 0, "Wide", Rw, Value::U64(0)).pdo(),
        e(0x200B, 0, "Array: count", Const, Value::U8(2)),
        e(0x200B, 1, "Array: first", Rw, Value::U16(0)),
        e(0x200B, 2, "Array: second", Rw, Value::U16(0)),
        e(0x6040, 0, "Controlword", Rww, Value::U16(0)).pdo(),
        e(0x6041, 0, "Statusword", Ro, Value::U16(0)).pdo(),
        e(0x6064, 0, "Position actual value", Ro, Value::I32(0)).pdo(),
    ];
    ObjectDictionary::from_defs(table).unwrap_or_default()
}
