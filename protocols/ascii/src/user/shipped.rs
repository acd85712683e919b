//! The grammars mcemu ships, written in the same terms a config declares its own: the manual's
//! two `START_ASCII_AGENT` parsers (digest 004 §1.7, manual §22.2.1).

use serde_json::json;

use super::command::{CommandConfig, ShippedGrammar};

/// `grammar`'s commands.
pub fn commands(grammar: ShippedGrammar) -> Vec<CommandConfig> {
    match grammar {
        ShippedGrammar::Example1 => example1(),
        ShippedGrammar::Example2 => example2(),
        ShippedGrammar::None => Vec::new(),
    }
}

/// Example 1: `res[i] = cmd[i] + 1` for the whole line (TV 79: `hello` → `ifmmp`).
fn example1() -> Vec<CommandConfig> {
    vec![CommandConfig {
        regex: Some("(.*)".into()),
        reply: "{1|shift:1}".into(),
        ..CommandConfig::default()
    }]
}

/// Example 2: up to three space-separated tokens; `ENABLE n`, `MOVEABS n pos`, `MOVEREL n
/// dist`, `STOP n` call Enable, MoveAbs, MoveRel, Stop. The manual's parser never writes the
/// response: every line answers an empty line, refusals too (digest 004 §1.7, inferred).
fn example2() -> Vec<CommandConfig> {
    let command = |pattern: &str, engine| CommandConfig {
        pattern: Some(pattern.into()),
        engine: vec![engine],
        error_reply: Some(String::new()),
        ..CommandConfig::default()
    };
    vec![
        command("ENABLE %d", json!({"type": "enable", "axis": "$1"})),
        command(
            "MOVEABS %d %f",
            json!({"type": "move_absolute", "axis": "$1", "position": "$2"}),
        ),
        command(
            "MOVEREL %d %f",
            json!({"type": "move_relative", "axis": "$1", "distance": "$2"}),
        ),
        command("STOP %d", json!({"type": "stop", "axis": "$1"})),
    ]
}
