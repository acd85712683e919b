//! Error control: heartbeat producer and consumer (CiA 301 §7.2.8.3.2.2), node guarding and
//! life guarding (§7.2.8.3.2.1).

use std::time::Duration;

use axes::od::ObjectDictionary;

use crate::device::{get_u16, get_u32, get_u8};
use crate::objects::idx;

/// The heartbeat producer (0x1017, ms).
#[derive(Debug, Default)]
pub(crate) struct Producer {
    period: Duration,
    next: Option<Duration>,
}

impl Producer {
    /// Read 0x1017; `restart_at` is when the next heartbeat goes out (None: one period on).
    pub(crate) fn load(
        &mut self,
        od: &ObjectDictionary,
        now: Duration,
        restart_at: Option<Duration>,
    ) {
        let ms = get_u16(od, idx::PRODUCER_HEARTBEAT, 0).unwrap_or(0);
        self.period = Duration::from_millis(u64::from(ms));
        self.next = (ms > 0).then(|| restart_at.unwrap_or(now.saturating_add(self.period)));
    }

    pub(crate) fn enabled(&self) -> bool {
        self.next.is_some()
    }

    /// Send now at a state change (CiA 301 leaves it open; masters learn the state at once),
    /// and restart the period.
    pub(crate) fn send_now(&mut self, now: Duration) -> bool {
        if self.next.is_some() {
            self.next = Some(now.saturating_add(self.period));
            return true;
        }
        false
    }

    /// Whether a heartbeat is due; keeps the period's phase unless a whole period was missed.
    pub(crate) fn due(&mut self, now: Duration) -> bool {
        match self.next {
            Some(next) if now >= next => {
                let following = next.saturating_add(self.period);
                self.next = Some(if following > now {
                    following
                } else {
                    now.saturating_add(self.period)
                });
                true
            }
            _ => false,
        }
    }

    pub(crate) fn deadline(&self) -> Option<Duration> {
        self.next
    }
}

/// One monitored node of 0x1016.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Monitored {
    node: u8,
    timeout: Duration,
    /// None until the first heartbeat (CiA 301: monitoring starts with it) and after a loss.
    deadline: Option<Duration>,
    lost: bool,
}

/// What a consumer saw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ConsumerEvent {
    /// A heartbeat came after a loss.
    Recovered(u8),
    /// The node sent its boot-up message.
    BootUp(u8),
}

/// The heartbeat consumer (0x1016).
#[derive(Debug, Default)]
pub(crate) struct Consumers {
    list: Vec<Monitored>,
}

impl Consumers {
    /// Read 0x1016; monitoring of nodes that stay configured with the same time goes on.
    pub(crate) fn load(&mut self, od: &ObjectDictionary) {
        let count = get_u8(od, idx::CONSUMER_HEARTBEAT, 0).unwrap_or(0);
        let old = std::mem::take(&mut self.list);
        for sub in 1..=count {
            let Some(v) = get_u32(od, idx::CONSUMER_HEARTBEAT, sub) else {
                continue;
            };
            let (node, ms) = (((v >> 16) & 0xFF) as u8, v & 0xFFFF);
            if !(1..=127).contains(&node) || ms == 0 {
                continue;
            }
            let timeout = Duration::from_millis(u64::from(ms));
            let kept = old
                .iter()
                .find(|m| m.node == node && m.timeout == timeout)
                .copied();
            self.list.push(kept.unwrap_or(Monitored {
                node,
                timeout,
                deadline: None,
                lost: false,
            }));
        }
    }

    /// Forget every deadline (reset communication).
    pub(crate) fn reset(&mut self) {
        for m in &mut self.list {
            m.deadline = None;
            m.lost = false;
        }
    }

    pub(crate) fn monitors(&self, node: u8) -> bool {
        self.list.iter().any(|m| m.node == node)
    }

    pub(crate) fn any_lost(&self) -> bool {
        self.list.iter().any(|m| m.lost)
    }

    /// A heartbeat or boot-up message from `node` with `state`.
    pub(crate) fn on_heartbeat(
        &mut self,
        node: u8,
        state: u8,
        now: Duration,
    ) -> Option<ConsumerEvent> {
        let m = self.list.iter_mut().find(|m| m.node == node)?;
        m.deadline = Some(now.saturating_add(m.timeout));
        if std::mem::take(&mut m.lost) {
            return Some(ConsumerEvent::Recovered(node));
        }
        (state == 0).then_some(ConsumerEvent::BootUp(node))
    }

    /// Nodes whose heartbeat is overdue at `now` (each reported once per loss).
    pub(crate) fn expired(&mut self, now: Duration) -> Vec<u8> {
        let mut lost = Vec::new();
        for m in &mut self.list {
            if m.deadline.is_some_and(|d| now > d) {
                m.deadline = None;
                m.lost = true;
                lost.push(m.node);
            }
        }
        lost
    }

    pub(crate) fn deadline(&self) -> Option<Duration> {
        // `expired` fires strictly after the deadline; ask to be woken just past it.
        self.list
            .iter()
            .filter_map(|m| m.deadline)
            .min()
            .map(|d| d.saturating_add(Duration::from_nanos(1)))
    }
}

/// Node guarding answers and life guarding (0x100C guard time ms × 0x100D life time factor).
#[derive(Debug, Default)]
pub(crate) struct Guarding {
    toggle: bool,
    life: Duration,
    deadline: Option<Duration>,
    lost: bool,
}

impl Guarding {
    pub(crate) fn load(&mut self, od: &ObjectDictionary) {
        let guard = u64::from(get_u16(od, idx::GUARD_TIME, 0).unwrap_or(0));
        let factor = u64::from(get_u8(od, idx::LIFE_TIME_FACTOR, 0).unwrap_or(0));
        self.life = Duration::from_millis(guard * factor);
        if self.life.is_zero() {
            self.deadline = None;
        }
    }

    /// Reset communication: the toggle bit starts at 0 and guarding waits for the first RTR.
    pub(crate) fn reset(&mut self) {
        self.toggle = false;
        self.deadline = None;
        self.lost = false;
    }

    /// A guarding RTR: the reply byte (state | toggle) and whether life guarding recovered.
    pub(crate) fn on_rtr(&mut self, state: u8, now: Duration) -> (u8, bool) {
        let reply = state | if self.toggle { 0x80 } else { 0 };
        self.toggle = !self.toggle;
        if !self.life.is_zero() {
            self.deadline = Some(now.saturating_add(self.life));
        }
        (reply, std::mem::take(&mut self.lost))
    }

    /// Whether the life time ran out (reported once).
    pub(crate) fn expired(&mut self, now: Duration) -> bool {
        if self.deadline.is_some_and(|d| now > d) {
            self.deadline = None;
            self.lost = true;
            return true;
        }
        false
    }

    pub(crate) fn deadline(&self) -> Option<Duration> {
        self.deadline
            .map(|d| d.saturating_add(Duration::from_nanos(1)))
    }
}
