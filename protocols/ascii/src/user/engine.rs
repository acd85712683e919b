//! A User ASCII command's engine commands: JSON (the control API's) with `$capture` fields,
//! filled from a line's captures and read as `axes::Command`s.

use serde_json::Value as Json;

use super::pattern::{Captures, Pattern, Value};

/// `template` with its `$…` strings replaced from `captures`: a string that is one reference
/// (`"$1"`, `"$axis"`) becomes the capture's typed value, one inside a string its text; `$$` is
/// a `$`.
pub fn fill(template: &Json, captures: &Captures) -> Result<Json, String> {
    Ok(match template {
        Json::String(s) => match s.strip_prefix('$').filter(|k| is_key(k)) {
            Some(key) => capture(captures, key)?.json(),
            None => Json::String(interpolate(s, captures)?),
        },
        Json::Array(items) => Json::Array(
            items
                .iter()
                .map(|v| fill(v, captures))
                .collect::<Result<_, _>>()?,
        ),
        Json::Object(map) => Json::Object(
            map.iter()
                .map(|(k, v)| Ok((k.clone(), fill(v, captures)?)))
                .collect::<Result<_, String>>()?,
        ),
        other => other.clone(),
    })
}

/// The engine command `template` makes of `captures`.
pub fn command(template: &Json, captures: &Captures) -> Result<axes::Command, String> {
    let json = fill(template, captures)?;
    serde_json::from_value(json).map_err(|e| e.to_string())
}

/// Whether `template` makes an engine command for any line `pattern` matches: filled with an
/// example value of each capture's type, it must read as one.
pub fn check_engine(template: &Json, pattern: &Pattern) -> Result<(), String> {
    let captures = Captures {
        values: pattern.types().into_iter().map(Value::example).collect(),
        names: pattern.names().to_vec(),
    };
    command(template, &captures).map(|_| ())
}

fn is_key(k: &str) -> bool {
    !k.is_empty() && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

fn capture<'a>(captures: &'a Captures, key: &str) -> Result<&'a Value, String> {
    captures
        .get(key)
        .ok_or_else(|| format!("`${key}`: the pattern has no such capture"))
}

/// `$key` references inside `s` replaced by their text.
fn interpolate(s: &str, captures: &Captures) -> Result<String, String> {
    let mut out = String::new();
    let mut rest = s;
    while let Some(i) = rest.find('$') {
        out.push_str(rest.get(..i).unwrap_or_default());
        let after = rest.get(i + 1..).unwrap_or_default();
        if let Some(tail) = after.strip_prefix('$') {
            out.push('$');
            rest = tail;
            continue;
        }
        // `$12` is capture 12; `$axis` the group named so.
        let digits = after.starts_with(|c: char| c.is_ascii_digit());
        let len = after
            .find(|c: char| {
                if digits {
                    !c.is_ascii_digit()
                } else {
                    !(c.is_ascii_alphanumeric() || c == '_')
                }
            })
            .unwrap_or(after.len());
        let (key, tail) = after.split_at(len);
        if key.is_empty() {
            return Err(format!("`{s}`: a lone `$` (write `$$` for one)"));
        }
        capture(captures, key)?.write(&mut out);
        rest = tail;
    }
    out.push_str(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn captures_fill_typed_values_and_text() {
        let p = Pattern::scanf("MOVEABS %d %f").unwrap();
        let c = p.matches("MOVEABS 1 2.5").unwrap();
        let t = json!({"type": "move_absolute", "axis": "$1", "position": "$2"});
        assert_eq!(
            fill(&t, &c).unwrap(),
            json!({"type": "move_absolute", "axis": 1, "position": 2.5})
        );
        assert!(command(&t, &c).is_ok());
        assert_eq!(fill(&json!("a$1b $$"), &c).unwrap(), json!("a1b $"));
    }

    #[test]
    fn a_command_that_cannot_be_made_says_why() {
        let p = Pattern::scanf("GO %s").unwrap();
        // A word is no axis number: caught when the config is read.
        let e = check_engine(&json!({"type": "enable", "axis": "$1"}), &p).unwrap_err();
        assert!(e.contains("axis") || e.contains("invalid type"), "{e}");
        let e = check_engine(&json!({"type": "enable", "axis": "$3"}), &p).unwrap_err();
        assert!(e.contains("$3"), "{e}");
        let e = check_engine(&json!({"type": "no_such"}), &p).unwrap_err();
        assert!(e.contains("no_such"), "{e}");
    }
}
