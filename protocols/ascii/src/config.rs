//! `[frontends.ascii_native]`: the Native ASCII server's config section.

use std::net::SocketAddr;

use mcemu_frontend::bound::AtLimit;
use serde::{Deserialize, Serialize};

use crate::native::Options;

/// A reply's line ending.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum LineEnding {
    #[default]
    Crlf,
    Lf,
    Cr,
}

impl LineEnding {
    pub fn text(self) -> &'static str {
        match self {
            LineEnding::Crlf => "\r\n",
            LineEnding::Lf => "\n",
            LineEnding::Cr => "\r",
        }
    }
}

/// `[frontends.ascii_native]`: HIMC Native ASCII server (HMPL calls as text lines).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields, default)]
pub struct NativeConfig {
    /// Serve this front-end.
    pub enabled: bool,
    /// Address to listen on (the HIMC's port is 3999).
    pub bind: SocketAddr,
    /// Open connections at most; what happens to one beyond it is `at_limit`'s.
    pub max_connections: usize,
    /// What a new connection meets while `max_connections` are open.
    pub at_limit: AtLimit,
    /// Close a connection that sends nothing for this long (ms; 0 = never).
    pub idle_timeout_ms: u64,
    /// Close a connection that does not take a reply in this time (ms; 0 = never): a client
    /// that never reads.
    pub write_timeout_ms: u64,
    /// Function names match whatever their case (`moveabs` calls `MoveAbs`).
    pub case_insensitive: bool,
    /// Serve only the 270 icon-marked functions (digest 004 §1.6); by default the unmarked
    /// scalar ones served (`GetAllGPI` …) are accepted too.
    pub strict: bool,
    /// Every reply's line ending: `crlf`, `lf` or `cr`.
    pub line_ending: LineEnding,
    /// `MoveHome` replies once homing has ended (as the manual's example expects) instead of
    /// once it started.
    pub move_home_waits: bool,
}

impl Default for NativeConfig {
    fn default() -> Self {
        NativeConfig {
            enabled: true,
            bind: SocketAddr::from(([127, 0, 0, 1], 3999)),
            max_connections: 16,
            at_limit: AtLimit::EvictIdle,
            idle_timeout_ms: 300_000,
            write_timeout_ms: 5_000,
            case_insensitive: false,
            strict: false,
            line_ending: LineEnding::Crlf,
            move_home_waits: false,
        }
    }
}

impl NativeConfig {
    pub fn options(&self) -> Options {
        Options {
            case_insensitive: self.case_insensitive,
            strict: self.strict,
            line_ending: self.line_ending.text().into(),
            move_home_waits: self.move_home_waits,
        }
    }
}
