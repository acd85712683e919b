//! [`User`]: the sans-IO core of the User ASCII server (port 4000, digest 004 §1.7). On the
//! HIMC a user HMPL program parses each line (`START_ASCII_AGENT`); mcemu runs no HMPL, so the
//! parser is a grammar declared in the config ([`config`]): commands as patterns with typed
//! captures ([`pattern`]; a command's data in [`command`]), the engine commands they issue ([`engine`]) and reply templates over
//! the machine's state ([`template`]). [`shipped`] holds the manual's two examples.
//!
//! Order of calls, per line (terminator already stripped by `line::LineSplitter`):
//! [`User::line`] with the line and the engine's latest snapshot; on [`Step::Reply`] send the
//! text to the asking client only; on [`Step::Engine`] apply the commands as one batch, then
//! [`User::finish`] with the result and a snapshot taken after it, and send its text. Lines of
//! one client are handled one after the other, in order. [`User::broadcast`] checks a message
//! for every client (`ASCII_ServerBroadcast`); the transport sends it.

pub mod command;
pub mod config;
pub mod engine;
pub mod pattern;
pub mod shipped;
pub mod template;

use std::sync::Arc;

use axes::Snapshot;

use crate::counters::UserCounters;
use crate::line::Line;
use pattern::{Captures, Pattern};
use template::Template;

/// `ASCII_ServerBroadcast`'s `length` at most (digest 004 §1.7).
pub const BROADCAST_MAX: usize = 128;

/// One compiled command.
#[derive(Clone, Debug)]
pub struct UserCommand {
    pattern: Pattern,
    engine: Vec<serde_json::Value>,
    reply: Template,
    error_reply: Template,
}

/// A compiled grammar: commands in the order they are tried, the reply to an unmatched line.
#[derive(Clone, Debug)]
pub struct Grammar {
    commands: Vec<UserCommand>,
    unmatched: Template,
    line_ending: String,
}

/// What to do with a line.
#[derive(Debug)]
pub enum Step {
    /// Send this (line ending included).
    Reply(String),
    /// Apply these commands as one batch, then [`User::finish`].
    Engine(Vec<axes::Command>, Pending),
}

/// A matched line waiting for the engine.
#[derive(Debug)]
pub struct Pending {
    command: usize,
    captures: Captures,
}

/// A broadcast that cannot be sent.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "a broadcast is at most {BROADCAST_MAX} bytes (ASCII_ServerBroadcast); this one is {length}"
)]
pub struct BroadcastTooLong {
    pub length: usize,
}

/// The User ASCII server's grammar and counters.
pub struct User {
    grammar: Grammar,
    counters: Arc<UserCounters>,
}

impl User {
    pub fn new(grammar: Grammar, counters: Arc<UserCounters>) -> User {
        User { grammar, counters }
    }

    pub fn counters(&self) -> &UserCounters {
        &self.counters
    }

    fn end(&self, mut text: String) -> String {
        text.push_str(&self.grammar.line_ending);
        text
    }

    fn unmatched(&self, line: &str, snapshot: &Snapshot) -> String {
        self.counters.unmatched.inc();
        let captures = Captures {
            values: vec![pattern::Value::Str(line.to_string())],
            names: Vec::new(),
        };
        let text = self
            .grammar
            .unmatched
            .render(&captures, snapshot, "")
            .unwrap_or_default();
        self.end(text)
    }

    /// Handle one line.
    pub fn line(&self, line: &Line, snapshot: &Snapshot) -> Step {
        self.counters.lines.inc();
        let text = match line {
            Line::Text(t) => t,
            Line::TooLong => {
                self.counters.too_long.inc();
                return Step::Reply(self.unmatched("", snapshot));
            }
        };
        let found = self
            .grammar
            .commands
            .iter()
            .enumerate()
            .find_map(|(i, c)| c.pattern.matches(text).map(|caps| (i, c, caps)));
        let Some((index, command, captures)) = found else {
            return Step::Reply(self.unmatched(text, snapshot));
        };
        self.counters.matched.inc();
        let commands: Result<Vec<_>, String> = command
            .engine
            .iter()
            .map(|t| engine::command(t, &captures))
            .collect();
        match commands {
            Ok(c) if c.is_empty() => Step::Reply(self.reply(command, &captures, snapshot, Ok(()))),
            Ok(c) => Step::Engine(
                c,
                Pending {
                    command: index,
                    captures,
                },
            ),
            // A capture that fits the pattern but not the command (axis 70000 …).
            Err(e) => Step::Reply(self.reply(command, &captures, snapshot, Err(e))),
        }
    }

    /// The reply to a line whose commands the engine applied (`Ok`) or refused (why).
    pub fn finish(
        &self,
        pending: Pending,
        result: Result<(), String>,
        snapshot: &Snapshot,
    ) -> String {
        match self.grammar.commands.get(pending.command) {
            Some(command) => self.reply(command, &pending.captures, snapshot, result),
            None => self.end(String::new()),
        }
    }

    fn reply(
        &self,
        command: &UserCommand,
        captures: &Captures,
        snapshot: &Snapshot,
        result: Result<(), String>,
    ) -> String {
        let rendered = match &result {
            Ok(()) => command.reply.render(captures, snapshot, ""),
            Err(e) => {
                self.counters.engine_refusals.inc();
                command.error_reply.render(captures, snapshot, e)
            }
        };
        let text = rendered.unwrap_or_else(|e| {
            // A state field that is not there (an axis this machine lacks): say so.
            self.counters.reply_errors.inc();
            command
                .error_reply
                .render(captures, snapshot, &e)
                .unwrap_or_else(|_| format!("ERR {e}"))
        });
        self.end(text)
    }

    /// `message` as it goes to every client (no terminator added, as `ASCII_ServerBroadcast`
    /// adds none), if it is at most 128 bytes.
    pub fn broadcast(&self, message: &str) -> Result<Arc<[u8]>, BroadcastTooLong> {
        if message.len() > BROADCAST_MAX {
            return Err(BroadcastTooLong {
                length: message.len(),
            });
        }
        self.counters.broadcasts.inc();
        Ok(Arc::from(message.as_bytes()))
    }
}

#[cfg(test)]
mod tests {
    use super::config::{CommandConfig, ShippedGrammar, UserConfig};
    use super::*;
    use serde_json::json;

    fn user(config: &UserConfig) -> User {
        User::new(config.grammar().unwrap(), Arc::new(UserCounters::default()))
    }

    fn step(u: &User, line: &str) -> Step {
        let mut s = Snapshot::default();
        s.axes.push(axes::AxisStatus::default());
        u.line(&Line::Text(line.into()), &s)
    }

    fn reply(u: &User, line: &str) -> String {
        match step(u, line) {
            Step::Reply(t) => t,
            Step::Engine(c, _) => format!("engine {c:?}"),
        }
    }

    #[test]
    fn example1_answers_each_character_plus_one_tv79() {
        let u = user(&UserConfig {
            grammar: ShippedGrammar::Example1,
            ..UserConfig::default()
        });
        assert_eq!(reply(&u, "hello"), "ifmmp\r\n");
        assert_eq!(reply(&u, "asdf"), "bteg\r\n");
    }

    #[test]
    fn example2_issues_engine_commands_and_replies_empty() {
        let u = user(&UserConfig::default());
        let Step::Engine(commands, pending) = step(&u, "MOVEABS 0  0.05") else {
            panic!("MOVEABS goes to the engine");
        };
        assert_eq!(
            serde_json::to_value(&commands).unwrap()[0]["position"],
            json!(0.05)
        );
        assert_eq!(u.finish(pending, Ok(()), &Snapshot::default()), "\r\n");
        let Step::Engine(_, pending) = step(&u, "STOP 0") else {
            panic!("STOP goes to the engine");
        };
        assert_eq!(
            u.finish(pending, Err("no".into()), &Snapshot::default()),
            "\r\n"
        );
        assert_eq!(reply(&u, "ENABLE 0 1"), "ERR unknown command\r\n");
        assert_eq!(u.counters().unmatched.get(), 1);
    }

    #[test]
    fn config_commands_come_first_and_read_state() {
        let u = user(&UserConfig {
            commands: vec![CommandConfig {
                regex: Some(r"POS\? (?P<axis>\d+)".into()),
                captures: vec![pattern::CaptureType::Int],
                reply: "POS {axis} {axis[$axis].position}".into(),
                error_reply: Some("NAK {error}".into()),
                ..CommandConfig::default()
            }],
            unmatched: "? {line}".into(),
            line_ending: crate::config::LineEnding::Lf,
            ..UserConfig::default()
        });
        assert_eq!(reply(&u, "POS? 0"), "POS 0 0\n");
        assert_eq!(reply(&u, "POS? 5"), "NAK no axes[5] on this machine\n");
        assert_eq!(reply(&u, "HELLO"), "? HELLO\n");
        assert!(matches!(step(&u, "STOP 0"), Step::Engine(..)));
    }

    #[test]
    fn bad_grammar_names_its_key() {
        let key = |commands: Vec<CommandConfig>, unmatched: &str| {
            UserConfig {
                commands,
                unmatched: unmatched.into(),
                ..UserConfig::default()
            }
            .grammar()
            .unwrap_err()
            .key
        };
        let ok = CommandConfig {
            pattern: Some("GO %d".into()),
            ..CommandConfig::default()
        };
        let with = |f: fn(&mut CommandConfig)| {
            let mut c = ok.clone();
            f(&mut c);
            vec![ok.clone(), c]
        };
        assert_eq!(
            key(with(|c| c.regex = Some("(".into())), "?"),
            "commands[1]"
        );
        assert_eq!(
            key(with(|c| c.pattern = Some("GO %q".into())), "?"),
            "commands[1].pattern"
        );
        assert_eq!(
            key(
                with(|c| c.engine = vec![json!({"type": "enable", "axis": "$2"})]),
                "?"
            ),
            "commands[1].engine[0]"
        );
        assert_eq!(
            key(with(|c| c.reply = "{9}".into()), "?"),
            "commands[1].reply"
        );
        assert_eq!(key(vec![ok.clone()], "{nope}"), "unmatched");
    }

    #[test]
    fn broadcasts_are_at_most_128_bytes() {
        let u = user(&UserConfig::default());
        assert_eq!(&*u.broadcast("test\n\r").unwrap(), b"test\n\r");
        assert!(u.broadcast(&"x".repeat(128)).is_ok());
        assert_eq!(u.broadcast(&"x".repeat(129)).unwrap_err().length, 129);
    }
}
