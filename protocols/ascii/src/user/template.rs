//! A User ASCII reply template: text with `{…}` fields, rendered over a line's captures and the
//! machine's snapshot.
//!
//! - `{1}`, `{axis}`: a capture by index or regex group name; `{0}` or `{line}`: the whole line;
//! - `{error}`: why the engine refused (in `error_reply`);
//! - a path into the snapshot as `GET /api/v1/state` shows it: `{axes[0].act_pos}`,
//!   `{tick}`, `{io.digital_inputs}`; `axis`/`group` stand for `axes`/`groups`, and an axis's
//!   `position`/`velocity` for `act_pos`/`act_vel`, so `{axis[0].position}` reads; an index may
//!   be a capture: `{axis[$1].position}`;
//! - `|shift:N` after a field adds N to each character's code (Example 1's parser, TV 79);
//! - `{{` and `}}` are braces.
//!
//! Numbers print as C's `%.15g` (integers in decimal), booleans as 1/0, strings as they are.

use axes::Snapshot;
use serde_json::Value as Json;

use super::pattern::{CaptureType, Captures, Value};

/// One piece of a template.
#[derive(Clone, Debug, PartialEq)]
enum Piece {
    Text(String),
    Field { source: Source, shift: i64 },
}

#[derive(Clone, Debug, PartialEq)]
enum Source {
    Capture(String),
    Error,
    State(Vec<Segment>),
}

/// A step of a state path: a key, then an index that may come from a capture.
#[derive(Clone, Debug, PartialEq)]
struct Segment {
    key: String,
    index: Option<Index>,
}

#[derive(Clone, Debug, PartialEq)]
enum Index {
    Literal(usize),
    Capture(String),
}

/// A compiled reply template.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Template {
    pieces: Vec<Piece>,
}

/// What a template may refer to: the pattern's capture types and group names.
pub struct Scope<'a> {
    pub types: &'a [CaptureType],
    pub names: &'a [(String, usize)],
}

impl Scope<'_> {
    fn has(&self, key: &str) -> bool {
        match key.parse::<usize>() {
            Ok(i) => i < self.types.len(),
            Err(_) => self.names.iter().any(|(n, _)| n == key),
        }
    }
}

impl Template {
    /// Compile `text`; an error names the field and what is wrong with it.
    pub fn parse(text: &str, scope: &Scope<'_>) -> Result<Template, String> {
        let mut pieces = Vec::new();
        let mut literal = String::new();
        let mut rest = text;
        while let Some(i) = rest.find(['{', '}']) {
            let (before, after) = rest.split_at(i);
            literal.push_str(before);
            if let Some(tail) = after.strip_prefix("{{") {
                literal.push('{');
                rest = tail;
                continue;
            }
            if let Some(tail) = after.strip_prefix("}}") {
                literal.push('}');
                rest = tail;
                continue;
            }
            let Some(body_end) = after.find('}').filter(|_| after.starts_with('{')) else {
                return Err(format!(
                    "unmatched `{}` (write `{{{{` or `}}}}` for a brace)",
                    after.get(..1).unwrap_or_default()
                ));
            };
            let body = after.get(1..body_end).unwrap_or_default();
            if !literal.is_empty() {
                pieces.push(Piece::Text(std::mem::take(&mut literal)));
            }
            pieces.push(field(body, scope).map_err(|e| format!("`{{{body}}}`: {e}"))?);
            rest = after.get(body_end + 1..).unwrap_or_default();
        }
        literal.push_str(rest);
        if !literal.is_empty() {
            pieces.push(Piece::Text(literal));
        }
        Ok(Template { pieces })
    }

    /// A template of plain text.
    pub fn text(s: &str) -> Template {
        Template {
            pieces: vec![Piece::Text(s.to_string())],
        }
    }

    /// The text, or why a field could not be read (an axis the machine does not have …).
    pub fn render(
        &self,
        captures: &Captures,
        snapshot: &Snapshot,
        error: &str,
    ) -> Result<String, String> {
        let mut out = String::new();
        let mut state: Option<Json> = None;
        for piece in &self.pieces {
            let (source, shift) = match piece {
                Piece::Text(t) => {
                    out.push_str(t);
                    continue;
                }
                Piece::Field { source, shift } => (source, *shift),
            };
            let mut text = String::new();
            match source {
                Source::Error => text.push_str(error),
                Source::Capture(key) => captures
                    .get(key)
                    .ok_or_else(|| format!("no capture {key}"))?
                    .write(&mut text),
                Source::State(path) => {
                    let root = match &state {
                        Some(s) => s,
                        None => {
                            state.insert(serde_json::to_value(snapshot).map_err(|e| e.to_string())?)
                        }
                    };
                    write_json(lookup(root, path, captures)?, &mut text);
                }
            }
            if shift == 0 {
                out.push_str(&text);
            } else {
                out.extend(text.chars().map(|c| shifted(c, shift)));
            }
        }
        Ok(out)
    }
}

/// `c`'s code plus `n`, as Example 1's `cmd[i] + 1`; `c` itself where that is no character.
fn shifted(c: char, n: i64) -> char {
    i64::from(u32::from(c))
        .checked_add(n)
        .and_then(|v| u32::try_from(v).ok())
        .and_then(char::from_u32)
        .unwrap_or(c)
}

fn field(body: &str, scope: &Scope<'_>) -> Result<Piece, String> {
    let (key, filter) = match body.split_once('|') {
        Some((k, f)) => (k.trim(), Some(f.trim())),
        None => (body.trim(), None),
    };
    let shift = match filter {
        None => 0,
        Some(f) => f
            .strip_prefix("shift:")
            .and_then(|n| n.trim().parse::<i64>().ok())
            .ok_or_else(|| format!("`{f}` is no filter (`shift:N` is)"))?,
    };
    let source = if key.is_empty() {
        return Err("is empty".into());
    } else if key == "error" {
        Source::Error
    } else if key == "line" && !scope.has("line") {
        Source::Capture("0".into())
    } else if scope.has(key) {
        Source::Capture(key.to_string())
    } else if key.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!("the pattern has no capture {key}"));
    } else {
        Source::State(state_path(key, scope)?)
    };
    Ok(Piece::Field { source, shift })
}

/// `axis[$1].position` → `axes`[capture 1] `act_pos`, checked against the snapshot's fields.
fn state_path(key: &str, scope: &Scope<'_>) -> Result<Vec<Segment>, String> {
    let mut path = Vec::new();
    for (n, part) in key.split('.').enumerate() {
        let (name, index) = match part.split_once('[') {
            Some((name, idx)) => {
                let idx = idx
                    .strip_suffix(']')
                    .ok_or_else(|| format!("`{part}`: an index ends in `]`"))?;
                let index = if let Some(cap) = idx.strip_prefix('$') {
                    if !scope.has(cap) {
                        return Err(format!("the pattern has no capture {cap}"));
                    }
                    Index::Capture(cap.to_string())
                } else {
                    Index::Literal(
                        idx.parse()
                            .map_err(|_| format!("`{idx}` is no index (a number or `$capture`)"))?,
                    )
                };
                (name, Some(index))
            }
            None => (part, None),
        };
        let name = match (n, name) {
            (0, "axis") => "axes",
            (0, "group") => "groups",
            (1, "position") if path.first().is_some_and(|s: &Segment| s.key == "axes") => "act_pos",
            (1, "velocity") if path.first().is_some_and(|s: &Segment| s.key == "axes") => "act_vel",
            (_, name) => name,
        };
        path.push(Segment {
            key: name.to_string(),
            index,
        });
    }
    check_path(&path)?;
    Ok(path)
}

/// The path's keys exist in a snapshot (with one axis, so `axes[i].field` can be checked).
fn check_path(path: &[Segment]) -> Result<(), String> {
    let mut example = Snapshot::default();
    example.axes.push(axes::AxisStatus::default());
    let root = serde_json::to_value(&example).map_err(|e| e.to_string())?;
    let mut at = &root;
    for seg in path {
        at = at.get(&seg.key).ok_or_else(|| {
            let known = at
                .as_object()
                .map(|o| o.keys().cloned().collect::<Vec<_>>().join(", "))
                .unwrap_or_default();
            format!(
                "the machine's state has no `{}` here (it has: {known})",
                seg.key
            )
        })?;
        if seg.index.is_some() {
            match at.as_array() {
                Some(a) => match a.first() {
                    Some(first) => at = first,
                    // An empty list in the example (groups …): what follows cannot be checked.
                    None => return Ok(()),
                },
                None => return Err(format!("`{}` is not a list", seg.key)),
            }
        }
    }
    Ok(())
}

fn lookup<'a>(root: &'a Json, path: &[Segment], captures: &Captures) -> Result<&'a Json, String> {
    let mut at = root;
    for seg in path {
        at = at
            .get(&seg.key)
            .ok_or_else(|| format!("no {} in the machine's state", seg.key))?;
        let Some(index) = &seg.index else {
            continue;
        };
        let i = match index {
            Index::Literal(i) => *i,
            Index::Capture(c) => match captures.get(c) {
                Some(Value::Int(i)) => {
                    usize::try_from(*i).map_err(|_| format!("no {}[{i}]", seg.key))?
                }
                Some(v) => return Err(format!("{}[…]: capture {c} ({v:?}) is no index", seg.key)),
                None => return Err(format!("no capture {c}")),
            },
        };
        at = at
            .get(i)
            .ok_or_else(|| format!("no {}[{i}] on this machine", seg.key))?;
    }
    Ok(at)
}

fn write_json(v: &Json, out: &mut String) {
    match v {
        Json::Null => {}
        Json::Bool(b) => out.push(if *b { '1' } else { '0' }),
        Json::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => out.push_str(&i.to_string()),
            (None, Some(f)) => crate::reply::write_g15(f, out),
            (None, None) => out.push_str(&n.to_string()),
        },
        Json::String(s) => out.push_str(s),
        other => out.push_str(&other.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::user::pattern::Pattern;

    fn render(
        pattern: &str,
        template: &str,
        line: &str,
        snapshot: &Snapshot,
    ) -> Result<String, String> {
        let p = Pattern::scanf(pattern)?;
        let types = p.types();
        let t = Template::parse(
            template,
            &Scope {
                types: &types,
                names: p.names(),
            },
        )?;
        let caps = p.matches(line).ok_or("no match")?;
        t.render(&caps, snapshot, "refused")
    }

    fn machine() -> Snapshot {
        let mut s = Snapshot::default();
        for pos in [1.5, -2.25] {
            s.axes.push(axes::AxisStatus {
                act_pos: pos,
                ..Default::default()
            });
        }
        s.tick = 42;
        s
    }

    #[test]
    fn captures_state_and_braces() {
        let s = machine();
        assert_eq!(
            render("POS %d", "{1}: {axis[$1].position} @{tick}", "POS 1", &s).unwrap(),
            "1: -2.25 @42"
        );
        assert_eq!(
            render("X", "{{{axes[0].act_pos}}} {error}", "X", &s).unwrap(),
            "{1.5} refused"
        );
        assert_eq!(
            render("POS %d", "{axis[$1].position}", "POS 7", &s).unwrap_err(),
            "no axes[7] on this machine"
        );
    }

    #[test]
    fn tv79_each_character_plus_one() {
        let p = Pattern::regex("(.*)", &[]).unwrap();
        let t = Template::parse(
            "{1|shift:1}",
            &Scope {
                types: &p.types(),
                names: p.names(),
            },
        )
        .unwrap();
        let s = Snapshot::default();
        for (line, want) in [("hello", "ifmmp"), ("asdf", "bteg")] {
            assert_eq!(t.render(&p.matches(line).unwrap(), &s, "").unwrap(), want);
        }
    }

    #[test]
    fn bad_templates_name_the_field() {
        let scope = Scope {
            types: &[CaptureType::Str, CaptureType::Int],
            names: &[],
        };
        for (t, part) in [
            ("{2}", "no capture 2"),
            ("{axis[0].nope}", "no `nope`"),
            ("{axis[$3].act_pos}", "no capture 3"),
            ("{nosuch}", "no `nosuch`"),
            ("{1|upper}", "no filter"),
            ("a } b", "unmatched"),
            ("{1", "unmatched"),
        ] {
            let e = Template::parse(t, &scope).unwrap_err();
            assert!(e.contains(part), "{t}: {e}");
        }
    }
}
