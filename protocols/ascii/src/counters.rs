//! What `GET /api/v1/state` shows of the ASCII front-ends: [`StreamCounters`], what the shared
//! transport counts for either; [`Counters`], the Native server's; `user::UserCounters`, the
//! User server's.

use std::sync::Arc;

use mcemu_frontend::counter::{ConnectionCounters, Counter};
use serde::Serialize;

/// What the line transport counts for a server, Native or User (relaxed atomics, see
/// `mcemu_frontend::counter`).
#[derive(Debug, Default)]
pub struct StreamCounters {
    pub connections: Arc<ConnectionCounters>,
    pub bytes_in: Counter,
    /// Connections that ended in the middle of a line (its bytes dropped).
    pub partial_lines: Counter,
    /// Connections closed for sending nothing for `idle_timeout_ms`.
    pub idle_timeouts: Counter,
    /// Connections closed because a reply could not be written in `write_timeout_ms` (a client
    /// that never reads).
    pub write_timeouts: Counter,
}

/// Counts of one Native ASCII front-end.
#[derive(Debug, Default)]
pub struct Counters {
    pub stream: StreamCounters,
    /// Lines read (too long ones included).
    pub lines: Counter,
    /// Calls that returned their value.
    pub calls_ok: Counter,
    /// Calls that returned an error code (a handler's check or an engine refusal).
    pub calls_failed: Counter,
    /// Of those, refused by the engine.
    pub engine_refusals: Counter,
    /// Lines that are not a call (`eERR_HMPL_INVALID_STR_FORMAT`), binary garbage included.
    pub syntax_errors: Counter,
    /// Lines over 512 characters (`eERR_HMPL_STR_TOO_LONG`).
    pub too_long: Counter,
    /// Unknown or unserved functions (`eERR_HMPL_NOT_SUPPORTED`).
    pub unsupported: Counter,
    /// Wrong argument count or type (`eERR_HMPL_INVALID_ARG`).
    pub invalid_args: Counter,
}

/// [`Counters`] as JSON.
#[derive(Debug, Serialize)]
pub struct CountersSnapshot {
    pub connections_open: u64,
    pub connections_opened: u64,
    pub connections_closed: u64,
    pub refused_at_limit: u64,
    pub evicted_idle: u64,
    pub bytes_in: u64,
    pub lines: u64,
    pub calls_ok: u64,
    pub calls_failed: u64,
    pub engine_refusals: u64,
    pub syntax_errors: u64,
    pub too_long: u64,
    pub unsupported: u64,
    pub invalid_args: u64,
    pub partial_lines: u64,
    pub idle_timeouts: u64,
    pub write_timeouts: u64,
}

impl Counters {
    pub fn snapshot(&self) -> CountersSnapshot {
        let c = &self.stream.connections;
        CountersSnapshot {
            connections_open: c.open(),
            connections_opened: c.opened.get(),
            connections_closed: c.closed.get(),
            refused_at_limit: c.refused_at_limit.get(),
            evicted_idle: c.evicted_idle.get(),
            bytes_in: self.stream.bytes_in.get(),
            lines: self.lines.get(),
            calls_ok: self.calls_ok.get(),
            calls_failed: self.calls_failed.get(),
            engine_refusals: self.engine_refusals.get(),
            syntax_errors: self.syntax_errors.get(),
            too_long: self.too_long.get(),
            unsupported: self.unsupported.get(),
            invalid_args: self.invalid_args.get(),
            partial_lines: self.stream.partial_lines.get(),
            idle_timeouts: self.stream.idle_timeouts.get(),
            write_timeouts: self.stream.write_timeouts.get(),
        }
    }
}

/// Counts of the User ASCII front-end.
#[derive(Debug, Default)]
pub struct UserCounters {
    pub stream: StreamCounters,
    /// Lines read (too long ones included).
    pub lines: Counter,
    /// Lines a command matched.
    pub matched: Counter,
    /// Lines no command matched (too long ones included): the `unmatched` reply.
    pub unmatched: Counter,
    /// Lines over 512 characters.
    pub too_long: Counter,
    /// Matched lines whose engine commands could not be made or were refused.
    pub engine_refusals: Counter,
    /// Replies whose template read a state field the machine lacks (`axis[7]` of four).
    pub reply_errors: Counter,
    /// Messages sent to every client (`ASCII_ServerBroadcast`).
    pub broadcasts: Counter,
}

/// [`UserCounters`] as JSON.
#[derive(Debug, Serialize)]
pub struct UserCountersSnapshot {
    pub connections_open: u64,
    pub connections_opened: u64,
    pub connections_closed: u64,
    pub refused_at_limit: u64,
    pub evicted_idle: u64,
    pub bytes_in: u64,
    pub lines: u64,
    pub matched: u64,
    pub unmatched: u64,
    pub too_long: u64,
    pub engine_refusals: u64,
    pub reply_errors: u64,
    pub broadcasts: u64,
    pub partial_lines: u64,
    pub idle_timeouts: u64,
    pub write_timeouts: u64,
}

impl UserCounters {
    pub fn snapshot(&self) -> UserCountersSnapshot {
        let s = &self.stream;
        let c = &s.connections;
        UserCountersSnapshot {
            connections_open: c.open(),
            connections_opened: c.opened.get(),
            connections_closed: c.closed.get(),
            refused_at_limit: c.refused_at_limit.get(),
            evicted_idle: c.evicted_idle.get(),
            bytes_in: s.bytes_in.get(),
            lines: self.lines.get(),
            matched: self.matched.get(),
            unmatched: self.unmatched.get(),
            too_long: self.too_long.get(),
            engine_refusals: self.engine_refusals.get(),
            reply_errors: self.reply_errors.get(),
            broadcasts: self.broadcasts.get(),
            partial_lines: s.partial_lines.get(),
            idle_timeouts: s.idle_timeouts.get(),
            write_timeouts: s.write_timeouts.get(),
        }
    }
}
