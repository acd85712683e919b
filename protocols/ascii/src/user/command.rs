//! The data of a User ASCII grammar as the config writes it: [`CommandConfig`] (one command) and
//! [`ShippedGrammar`] (which of mcemu's grammars follows the config's own commands).

use serde::{Deserialize, Serialize};

use super::pattern::CaptureType;

/// A grammar mcemu ships: the manual's two `START_ASCII_AGENT` examples (digest 004 §1.7).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum ShippedGrammar {
    /// §22.2.1 Example 1: each character + 1 (`hello` → `ifmmp`, TV 79).
    Example1,
    /// §22.2.1 Example 2: `ENABLE n`, `MOVEABS n pos`, `MOVEREL n dist`, `STOP n`; replies
    /// an empty line, as the manual's parser writes no response.
    #[default]
    Example2,
    /// Only the `commands` of the section.
    None,
}

/// One command of a grammar: a pattern, the engine commands it issues, its replies.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields, default)]
pub struct CommandConfig {
    /// scanf-like pattern the whole line must match: `%d` integer, `%f` double, `%s` word,
    /// `%%` a `%`; spaces match one or more. Either this or `regex`.
    pub pattern: Option<String>,
    /// Regex the whole line must match (Rust `regex` syntax); its groups are the captures.
    pub regex: Option<String>,
    /// The regex groups' types in order: `int`, `float` or `str` (the default).
    pub captures: Vec<CaptureType>,
    /// Engine commands to apply, as one batch, before replying: the JSON commands of the control
    /// API and scenarios. A string `"$1"` (or `"$name"`) is the capture itself, typed; `$1`
    /// inside a longer string is its text; `$$` is `$`.
    #[cfg_attr(
        feature = "schema",
        schemars(with = "Vec<serde_json::Map<String, serde_json::Value>>")
    )]
    pub engine: Vec<serde_json::Value>,
    /// Reply template (without the line ending): `{1}` a capture, `{axis[$1].position}` the
    /// machine's state, `{1|shift:1}` each character + 1; see README "HIWIN ASCII".
    pub reply: String,
    /// Reply when the engine refuses the commands (`{error}` says why).
    pub error_reply: Option<String>,
}
