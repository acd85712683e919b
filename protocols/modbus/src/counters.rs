//! Per-front-end statistics. Plain atomics (relaxed: each counter is independent and only ever
//! read for display), so the request path takes no lock.
//!
//! Two kinds of numbers live here:
//! - lifetime statistics (requests, replies, errors, connections, bytes, faults applied), which
//!   only grow, for the control API's `GET /state`;
//! - the serial-line diagnostic counters that FC 8 reports and clears (Modbus over Serial Line
//!   V1.02 §6.1.1), which a master may reset at any time, so they are kept apart.

use std::collections::BTreeMap;
use std::sync::Arc;

use serde::Serialize;

use crate::pdu::Exception;

pub use mcemu_frontend::counter::{ConnectionCounters, Counter};

/// The counters FC 8 reports (sub-functions 0x0B–0x12) and clears (0x01, 0x0A). Their
/// meaning, from Modbus over Serial Line V1.02 §6.1.1, as this server applies it on every
/// transport:
#[derive(Debug, Default)]
pub struct Diagnostics {
    /// 0x0B: frames seen with a good CRC (RTU) or a well-formed MBAP header (TCP), whatever
    /// unit they address.
    pub bus_message: Counter,
    /// 0x0C: frames dropped for a bad CRC, or too short to carry one; on TCP, MBAP headers
    /// that were refused (wrong protocol id, impossible length).
    pub bus_communication_error: Counter,
    /// 0x0D: exception responses, including those a broadcast raised but could not send.
    pub server_exception_error: Counter,
    /// 0x0E: messages addressed to this server (a served unit or a broadcast), this one included.
    pub server_message: Counter,
    /// 0x0F: addressed messages that got no response: broadcasts, listen-only mode, `no_reply`
    /// faults.
    pub server_no_response: Counter,
    /// 0x10: exception 07 responses (never sent by this server, so 0).
    pub server_nak: Counter,
    /// 0x11: exception 06 (server busy) responses, e.g. forced by an `exception` fault.
    pub server_busy: Counter,
    /// 0x12: frames longer than the 256-byte RTU ADU, dropped (the line outran the buffer).
    pub bus_character_overrun: Counter,
}

impl Diagnostics {
    /// FC 8 sub-functions 0x01 and 0x0A.
    pub fn clear(&self) {
        for c in [
            &self.bus_message,
            &self.bus_communication_error,
            &self.server_exception_error,
            &self.server_message,
            &self.server_no_response,
            &self.server_nak,
            &self.server_busy,
            &self.bus_character_overrun,
        ] {
            c.reset();
        }
    }

    /// The counter a sub-function 0x0B–0x12 returns.
    pub fn by_sub_function(&self, sub_function: u16) -> Option<&Counter> {
        Some(match sub_function {
            0x0B => &self.bus_message,
            0x0C => &self.bus_communication_error,
            0x0D => &self.server_exception_error,
            0x0E => &self.server_message,
            0x0F => &self.server_no_response,
            0x10 => &self.server_nak,
            0x11 => &self.server_busy,
            0x12 => &self.bus_character_overrun,
            _ => return None,
        })
    }
}

/// Everything counted for one front-end.
#[derive(Debug)]
pub struct Counters {
    requests_by_function: [Counter; 256],
    exceptions_by_code: [Counter; 256],
    /// Responses sent (normal and exception).
    pub replies: Counter,
    /// Requests addressed to this server that got no response.
    pub no_response: Counter,
    /// RTU broadcasts (unit 0) received.
    pub broadcasts: Counter,
    /// RTU frames for a unit this server does not serve (ignored, multi-drop).
    pub other_unit: Counter,
    pub crc_errors: Counter,
    /// RTU frames shorter than address + function + CRC.
    pub too_short: Counter,
    /// RTU frames longer than 256 bytes.
    pub too_long: Counter,
    /// MBAP frames whose protocol id is not 0 (skipped, connection kept).
    pub not_modbus: Counter,
    /// MBAP length fields that cannot be right (connection closed).
    pub bad_length: Counter,
    /// Opened, closed, refused and evicted at the bound (shared with the accept loop).
    pub connections: Arc<ConnectionCounters>,
    /// Connections closed after `idle_timeout_ms` without a byte.
    pub idle_timeouts: Counter,
    /// Connections closed because a started frame did not complete in `frame_timeout_ms`, or
    /// a reply could not be written in that time.
    pub frame_timeouts: Counter,
    pub bytes_in: Counter,
    pub bytes_out: Counter,
    pub faults_applied: FaultsApplied,
    pub diagnostics: Diagnostics,
}

/// How often each fault kind changed what the server did.
#[derive(Debug, Default)]
pub struct FaultsApplied {
    pub delay: Counter,
    pub no_reply: Counter,
    pub exception: Counter,
    pub drop_bytes: Counter,
    pub corrupt: Counter,
    pub close: Counter,
}

impl Default for Counters {
    fn default() -> Self {
        Counters {
            requests_by_function: std::array::from_fn(|_| Counter::default()),
            exceptions_by_code: std::array::from_fn(|_| Counter::default()),
            replies: Counter::default(),
            no_response: Counter::default(),
            broadcasts: Counter::default(),
            other_unit: Counter::default(),
            crc_errors: Counter::default(),
            too_short: Counter::default(),
            too_long: Counter::default(),
            not_modbus: Counter::default(),
            bad_length: Counter::default(),
            connections: Arc::default(),
            idle_timeouts: Counter::default(),
            frame_timeouts: Counter::default(),
            bytes_in: Counter::default(),
            bytes_out: Counter::default(),
            faults_applied: FaultsApplied::default(),
            diagnostics: Diagnostics::default(),
        }
    }
}

impl Counters {
    /// A request addressed to this server, by its function code (unknown ones included).
    pub fn request(&self, function: u8) {
        self.requests_by_function[usize::from(function)].inc();
    }

    /// An exception response sent (or, for a broadcast, raised).
    pub fn exception(&self, exception: Exception) {
        self.exceptions_by_code[usize::from(exception.code())].inc();
        self.diagnostics.server_exception_error.inc();
        // 07 (NAK) has no variant: this server never sends it.
        if exception == Exception::ServerDeviceBusy {
            self.diagnostics.server_busy.inc();
        }
    }

    pub fn requests_for(&self, function: u8) -> u64 {
        self.requests_by_function[usize::from(function)].get()
    }

    pub fn exceptions_for(&self, exception: Exception) -> u64 {
        self.exceptions_by_code[usize::from(exception.code())].get()
    }

    pub fn snapshot(&self) -> CountersSnapshot {
        let nonzero = |table: &[Counter; 256]| -> BTreeMap<u8, u64> {
            (0..=255u8)
                .filter_map(|i| {
                    let n = table[usize::from(i)].get();
                    (n > 0).then_some((i, n))
                })
                .collect()
        };
        let requests_by_function = nonzero(&self.requests_by_function);
        let exceptions_by_code = nonzero(&self.exceptions_by_code);
        let d = &self.diagnostics;
        let f = &self.faults_applied;
        CountersSnapshot {
            requests: requests_by_function.values().sum(),
            requests_by_function,
            replies: self.replies.get(),
            exceptions: exceptions_by_code.values().sum(),
            exceptions_by_code,
            no_response: self.no_response.get(),
            broadcasts: self.broadcasts.get(),
            other_unit_ignored: self.other_unit.get(),
            crc_errors: self.crc_errors.get(),
            malformed_frames: MalformedSnapshot {
                too_short: self.too_short.get(),
                too_long: self.too_long.get(),
                not_modbus_protocol: self.not_modbus.get(),
                bad_length: self.bad_length.get(),
            },
            connections: ConnectionsSnapshot {
                open: self.connections.open(),
                opened: self.connections.opened.get(),
                closed: self.connections.closed.get(),
                refused_at_limit: self.connections.refused_at_limit.get(),
                evicted_idle: self.connections.evicted_idle.get(),
                idle_timeouts: self.idle_timeouts.get(),
                frame_timeouts: self.frame_timeouts.get(),
            },
            bytes_in: self.bytes_in.get(),
            bytes_out: self.bytes_out.get(),
            faults_applied: FaultsAppliedSnapshot {
                delay: f.delay.get(),
                no_reply: f.no_reply.get(),
                exception: f.exception.get(),
                drop_bytes: f.drop_bytes.get(),
                corrupt: f.corrupt.get(),
                close: f.close.get(),
            },
            diagnostics: DiagnosticsSnapshot {
                bus_message_count: d.bus_message.get(),
                bus_communication_error_count: d.bus_communication_error.get(),
                server_exception_error_count: d.server_exception_error.get(),
                server_message_count: d.server_message.get(),
                server_no_response_count: d.server_no_response.get(),
                server_nak_count: d.server_nak.get(),
                server_busy_count: d.server_busy.get(),
                bus_character_overrun_count: d.bus_character_overrun.get(),
            },
        }
    }
}

/// The counters as `GET /state` shows them.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct CountersSnapshot {
    /// Requests addressed to this server (served units and broadcasts).
    pub requests: u64,
    /// By function code (decimal keys); only codes seen.
    pub requests_by_function: BTreeMap<u8, u64>,
    /// Responses sent, normal and exception.
    pub replies: u64,
    pub exceptions: u64,
    /// By exception code (decimal keys); only codes seen.
    pub exceptions_by_code: BTreeMap<u8, u64>,
    /// Addressed requests that got no response (broadcasts, listen-only mode, faults).
    pub no_response: u64,
    pub broadcasts: u64,
    /// RTU frames for units this server does not serve.
    pub other_unit_ignored: u64,
    pub crc_errors: u64,
    pub malformed_frames: MalformedSnapshot,
    pub connections: ConnectionsSnapshot,
    pub bytes_in: u64,
    pub bytes_out: u64,
    pub faults_applied: FaultsAppliedSnapshot,
    /// The FC 8 counters (cleared by FC 8 sub-functions 0x01 and 0x0A).
    pub diagnostics: DiagnosticsSnapshot,
}

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct MalformedSnapshot {
    pub too_short: u64,
    pub too_long: u64,
    pub not_modbus_protocol: u64,
    pub bad_length: u64,
}

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ConnectionsSnapshot {
    pub open: u64,
    pub opened: u64,
    pub closed: u64,
    pub refused_at_limit: u64,
    /// Closed to admit a new connection, idle longest (`at_limit = "evict_idle"`).
    pub evicted_idle: u64,
    pub idle_timeouts: u64,
    pub frame_timeouts: u64,
}

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct FaultsAppliedSnapshot {
    pub delay: u64,
    pub no_reply: u64,
    pub exception: u64,
    pub drop_bytes: u64,
    pub corrupt: u64,
    pub close: u64,
}

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct DiagnosticsSnapshot {
    pub bus_message_count: u64,
    pub bus_communication_error_count: u64,
    pub server_exception_error_count: u64,
    pub server_message_count: u64,
    pub server_no_response_count: u64,
    pub server_nak_count: u64,
    pub server_busy_count: u64,
    pub bus_character_overrun_count: u64,
}

/// The last request the engine refused (exception 04), for `GET /state`.
pub type LastError = mcemu_frontend::refusal::Refusal<RefusedRequest>;

/// What Modbus tells of a refused request, beside the kit's time, peer and reason.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct RefusedRequest {
    pub unit: u8,
    pub function: u8,
    pub exception: u8,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snapshot_lists_only_codes_seen_and_diagnostics_clear_alone() {
        let c = Counters::default();
        c.request(3);
        c.request(3);
        c.request(0x42);
        c.exception(Exception::ServerDeviceBusy);
        c.replies.inc();
        c.diagnostics.bus_message.add(5);
        let s = c.snapshot();
        assert_eq!(s.requests, 3);
        assert_eq!(s.requests_by_function, BTreeMap::from([(3, 2), (0x42, 1)]));
        assert_eq!(s.exceptions_by_code, BTreeMap::from([(6, 1)]));
        assert_eq!(s.diagnostics.server_busy_count, 1);
        assert_eq!(s.diagnostics.bus_message_count, 5);
        let json = serde_json::to_value(&s).unwrap_or_default();
        assert_eq!(json["requests_by_function"]["66"], 1);
        c.diagnostics.clear();
        let s = c.snapshot();
        assert_eq!(s.diagnostics.bus_message_count, 0);
        assert_eq!(s.requests, 3, "statistics survive a diagnostic clear");
        assert_eq!(s.replies, 1);
    }
}
