//! `[frontends.ascii_user]`: the User ASCII server's config section and its grammar, compiled
//! once at start ([`UserConfig::grammar`]); a bad pattern, template or engine command is a
//! [`GrammarError`] naming its key.

use std::net::SocketAddr;

use mcemu_frontend::bound::AtLimit;
use serde::{Deserialize, Serialize};

pub use super::command::{CommandConfig, ShippedGrammar};
use super::pattern::CaptureType;
use super::{shipped, Grammar, UserCommand};
use crate::config::LineEnding;
use crate::user::engine::check_engine;
use crate::user::pattern::Pattern;
use crate::user::template::{Scope, Template};

/// `[frontends.ascii_user]`: HIMC User ASCII server (the user's `START_ASCII_AGENT` parser,
/// declared as command patterns, digest 004 §1.7).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields, default)]
pub struct UserConfig {
    /// Serve this front-end.
    pub enabled: bool,
    /// Address to listen on (the HIMC's port is 4000).
    pub bind: SocketAddr,
    /// Open connections at most; what happens to one beyond it is `at_limit`'s.
    pub max_connections: usize,
    /// What a new connection meets while `max_connections` are open.
    pub at_limit: AtLimit,
    /// Close a connection that sends nothing for this long (ms; 0 = never).
    pub idle_timeout_ms: u64,
    /// Close a connection that does not take a reply in this time (ms; 0 = never).
    pub write_timeout_ms: u64,
    /// Every reply's line ending: `crlf`, `lf` or `cr` (broadcasts are sent as given).
    pub line_ending: LineEnding,
    /// The shipped grammar served after `commands`: `example1`, `example2` or `none`.
    pub grammar: ShippedGrammar,
    /// Commands tried in order before the shipped grammar's; the first that matches answers.
    pub commands: Vec<CommandConfig>,
    /// Reply template for a line no command matches (`{line}` is the line).
    pub unmatched: String,
}

impl Default for UserConfig {
    fn default() -> Self {
        UserConfig {
            enabled: true,
            bind: SocketAddr::from(([127, 0, 0, 1], 4000)),
            max_connections: 16,
            at_limit: AtLimit::EvictIdle,
            idle_timeout_ms: 300_000,
            write_timeout_ms: 5_000,
            line_ending: LineEnding::Crlf,
            grammar: ShippedGrammar::Example2,
            commands: Vec::new(),
            unmatched: "ERR unknown command".into(),
        }
    }
}

/// A grammar that cannot be served: the key in the section, and why.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{key}: {reason}")]
pub struct GrammarError {
    /// `commands[1].regex`, `unmatched` …
    pub key: String,
    pub reason: String,
}

/// The reply an engine refusal gets when a command names none.
const DEFAULT_ERROR_REPLY: &str = "ERR {error}";

impl UserConfig {
    /// The grammar: the section's commands, then the shipped grammar's.
    pub fn grammar(&self) -> Result<Grammar, GrammarError> {
        let mut commands = Vec::new();
        for (i, c) in self.commands.iter().enumerate() {
            commands.push(compile(c, &format!("commands[{i}]"))?);
        }
        for c in shipped::commands(self.grammar) {
            commands.push(compile(&c, "grammar")?);
        }
        let line = [CaptureType::Str];
        let unmatched = Template::parse(
            &self.unmatched,
            &Scope {
                types: &line,
                names: &[],
            },
        )
        .map_err(|reason| GrammarError {
            key: "unmatched".into(),
            reason,
        })?;
        Ok(Grammar {
            commands,
            unmatched,
            line_ending: self.line_ending.text().into(),
        })
    }
}

fn compile(c: &CommandConfig, key: &str) -> Result<UserCommand, GrammarError> {
    let err = |field: &str, reason: String| GrammarError {
        key: format!("{key}.{field}"),
        reason,
    };
    let pattern = match (&c.pattern, &c.regex) {
        (Some(p), None) => {
            if !c.captures.is_empty() {
                return Err(err(
                    "captures",
                    "types regex groups; a `pattern` types its own".into(),
                ));
            }
            Pattern::scanf(p).map_err(|e| err("pattern", e))?
        }
        (None, Some(r)) => Pattern::regex(r, &c.captures).map_err(|e| err("regex", e))?,
        _ => {
            return Err(GrammarError {
                key: key.to_string(),
                reason: "give a command either `pattern` or `regex`".into(),
            })
        }
    };
    let types = pattern.types();
    let scope = Scope {
        types: &types,
        names: pattern.names(),
    };
    for (j, command) in c.engine.iter().enumerate() {
        check_engine(command, &pattern).map_err(|e| err(&format!("engine[{j}]"), e))?;
    }
    let reply = Template::parse(&c.reply, &scope).map_err(|e| err("reply", e))?;
    let error_reply = Template::parse(
        c.error_reply.as_deref().unwrap_or(DEFAULT_ERROR_REPLY),
        &scope,
    )
    .map_err(|e| err("error_reply", e))?;
    Ok(UserCommand {
        pattern,
        engine: c.engine.clone(),
        reply,
        error_reply,
    })
}
