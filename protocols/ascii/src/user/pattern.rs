//! A User ASCII command's pattern (digest 004 §1.7): what a line must look like, and its typed
//! captures. Two forms, as the `lewis` simulator's stream commands take them:
//!
//! - scanf-like: `MOVEABS %d %f`. `%d` an integer (decimal or `0x` hex, signed), `%f` a double
//!   (C's syntax, exponent allowed), `%s` a word (no whitespace), `%%` a `%`; a run of spaces
//!   matches one or more whitespace characters; anything else matches itself (case-sensitive).
//! - a regex (Rust `regex` syntax) that must match the whole line, its groups typed in order by
//!   `captures` (`int`, `float`, `str`; groups beyond the list are `str`); named groups are also
//!   reachable by name.
//!
//! Capture 0 is the whole line.

use serde::{Deserialize, Serialize};

/// A capture's type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum CaptureType {
    Int,
    Float,
    Str,
}

/// A captured value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Int(i64),
    Float(f64),
    Str(String),
}

impl Value {
    /// The value a config check substitutes for a capture of type `ty`.
    pub fn example(ty: CaptureType) -> Value {
        match ty {
            CaptureType::Int => Value::Int(0),
            CaptureType::Float => Value::Float(0.0),
            CaptureType::Str => Value::Str("x".into()),
        }
    }

    pub fn json(&self) -> serde_json::Value {
        match self {
            Value::Int(i) => (*i).into(),
            Value::Float(f) => {
                serde_json::Number::from_f64(*f).map_or(serde_json::Value::Null, Into::into)
            }
            Value::Str(s) => s.clone().into(),
        }
    }

    /// As reply text: integers in decimal, doubles as C's `%.15g`, strings as they are.
    pub fn write(&self, out: &mut String) {
        match self {
            Value::Int(i) => out.push_str(&i.to_string()),
            Value::Float(f) => crate::reply::write_g15(*f, out),
            Value::Str(s) => out.push_str(s),
        }
    }
}

/// A line's captures: index 0 the whole line, then each conversion or group in order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Captures {
    pub values: Vec<Value>,
    /// `(name, index)` of the regex's named groups.
    pub names: Vec<(String, usize)>,
}

impl Captures {
    /// Capture `key`: an index (`1`) or a group's name.
    pub fn get(&self, key: &str) -> Option<&Value> {
        let index = match key.parse::<usize>() {
            Ok(i) => i,
            Err(_) => self.names.iter().find(|(n, _)| n == key)?.1,
        };
        self.values.get(index)
    }
}

/// A scanf-like pattern's pieces.
#[derive(Clone, Debug, PartialEq)]
pub enum Piece {
    Literal(char),
    Space,
    Conversion(CaptureType),
}

/// A compiled pattern.
#[derive(Clone, Debug)]
pub enum Pattern {
    Scanf(Vec<Piece>),
    Regex {
        regex: regex::Regex,
        types: Vec<CaptureType>,
        names: Vec<(String, usize)>,
    },
}

impl Pattern {
    /// `%d`/`%f`/`%s`, `%%`, spaces and literals; an error names what is wrong.
    pub fn scanf(pattern: &str) -> Result<Pattern, String> {
        let mut pieces = Vec::new();
        let mut chars = pattern.trim().chars();
        if pattern.trim().is_empty() {
            return Err("is empty".into());
        }
        while let Some(c) = chars.next() {
            let piece = match c {
                '%' => match chars.next() {
                    Some('d') => Piece::Conversion(CaptureType::Int),
                    Some('f') => Piece::Conversion(CaptureType::Float),
                    Some('s') => Piece::Conversion(CaptureType::Str),
                    Some('%') => Piece::Literal('%'),
                    Some(other) => {
                        return Err(format!("`%{other}` is no conversion (%d, %f, %s or %%)"))
                    }
                    None => return Err("ends in a lone `%`".into()),
                },
                c if c.is_whitespace() => {
                    if pieces.last() != Some(&Piece::Space) {
                        pieces.push(Piece::Space);
                    }
                    continue;
                }
                c => Piece::Literal(c),
            };
            pieces.push(piece);
        }
        Ok(Pattern::Scanf(pieces))
    }

    /// A regex anchored at both ends; `types` types its groups in order.
    pub fn regex(pattern: &str, types: &[CaptureType]) -> Result<Pattern, String> {
        let regex = regex::Regex::new(&format!("^(?:{pattern})$")).map_err(|e| e.to_string())?;
        let groups = regex.captures_len().saturating_sub(1);
        if types.len() > groups {
            return Err(format!(
                "`captures` types {} groups but the regex has {groups}",
                types.len()
            ));
        }
        let names = regex
            .capture_names()
            .enumerate()
            .filter_map(|(i, n)| n.map(|n| (n.to_string(), i)))
            .collect();
        Ok(Pattern::Regex {
            regex,
            types: types.to_vec(),
            names,
        })
    }

    /// The captures' types, index 0 (the line) included: what a config check substitutes.
    pub fn types(&self) -> Vec<CaptureType> {
        let mut out = vec![CaptureType::Str];
        match self {
            Pattern::Scanf(pieces) => out.extend(pieces.iter().filter_map(|p| match p {
                Piece::Conversion(t) => Some(*t),
                _ => None,
            })),
            Pattern::Regex { regex, types, .. } => {
                let groups = regex.captures_len().saturating_sub(1);
                out.extend((0..groups).map(|i| types.get(i).copied().unwrap_or(CaptureType::Str)));
            }
        }
        out
    }

    pub fn names(&self) -> &[(String, usize)] {
        match self {
            Pattern::Scanf(_) => &[],
            Pattern::Regex { names, .. } => names,
        }
    }

    /// The captures if `line` matches.
    pub fn matches(&self, line: &str) -> Option<Captures> {
        let mut values = vec![Value::Str(line.to_string())];
        match self {
            Pattern::Scanf(pieces) => scan(pieces, line.trim(), &mut values)?,
            Pattern::Regex {
                regex,
                types,
                names,
            } => {
                let caps = regex.captures(line)?;
                for i in 1..caps.len() {
                    let text = caps.get(i).map_or("", |m| m.as_str());
                    let ty = types.get(i - 1).copied().unwrap_or(CaptureType::Str);
                    values.push(convert(ty, text)?);
                }
                return Some(Captures {
                    values,
                    names: names.clone(),
                });
            }
        }
        Some(Captures {
            values,
            names: Vec::new(),
        })
    }
}

/// Match `pieces` against all of `rest`, pushing the conversions.
fn scan(pieces: &[Piece], mut rest: &str, values: &mut Vec<Value>) -> Option<()> {
    for piece in pieces {
        match piece {
            Piece::Literal(c) => rest = rest.strip_prefix(*c)?,
            Piece::Space => {
                let trimmed = rest.trim_start();
                if trimmed.len() == rest.len() {
                    return None;
                }
                rest = trimmed;
            }
            Piece::Conversion(ty) => {
                let len = match ty {
                    CaptureType::Str => rest.find(char::is_whitespace).unwrap_or(rest.len()),
                    CaptureType::Int => int_len(rest),
                    CaptureType::Float => float_len(rest),
                };
                let (text, tail) = rest.split_at_checked(len)?;
                if text.is_empty() {
                    return None;
                }
                values.push(convert(*ty, text)?);
                rest = tail;
            }
        }
    }
    rest.is_empty().then_some(())
}

fn sign_len(s: &str) -> usize {
    usize::from(s.starts_with(['+', '-']))
}

/// The length of the integer `s` starts with: sign, then `0x` and hex digits, or decimal ones.
fn int_len(s: &str) -> usize {
    let sign = sign_len(s);
    let body = s.get(sign..).unwrap_or_default();
    let hex = body
        .strip_prefix("0x")
        .or_else(|| body.strip_prefix("0X"))
        .map(|h| h.len() - h.trim_start_matches(|c: char| c.is_ascii_hexdigit()).len());
    match hex {
        Some(digits) if digits > 0 => sign + 2 + digits,
        _ => sign + body.len() - body.trim_start_matches(|c: char| c.is_ascii_digit()).len(),
    }
}

/// The length of the C double `s` starts with: sign, digits, `.`, digits, exponent.
fn float_len(s: &str) -> usize {
    let b = s.as_bytes();
    let digits = |from: usize| {
        b.get(from..)
            .map_or(0, |t| t.iter().take_while(|c| c.is_ascii_digit()).count())
    };
    let mut i = sign_len(s);
    let whole = digits(i);
    i += whole;
    let mut frac = 0;
    if b.get(i) == Some(&b'.') {
        frac = digits(i + 1);
        i += 1 + frac;
    }
    if whole + frac == 0 {
        return 0;
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        let j = i + 1 + usize::from(matches!(b.get(i + 1), Some(b'+' | b'-')));
        let exp = digits(j);
        if exp > 0 {
            i = j + exp;
        }
    }
    i
}

/// `text` as a `ty`; `None` if it is not one (an integer that does not fit, a non-finite double).
fn convert(ty: CaptureType, text: &str) -> Option<Value> {
    match ty {
        CaptureType::Str => Some(Value::Str(text.to_string())),
        CaptureType::Int => parse_int(text).map(Value::Int),
        CaptureType::Float => text
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|f| f.is_finite())
            .map(Value::Float),
    }
}

fn parse_int(text: &str) -> Option<i64> {
    let t = text.trim();
    let (negative, body) = match t.strip_prefix('-') {
        Some(b) => (true, b),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let magnitude = match body.strip_prefix("0x").or_else(|| body.strip_prefix("0X")) {
        Some(hex) => i128::from_str_radix(hex, 16).ok()?,
        None => body.parse::<i128>().ok()?,
    };
    i64::try_from(if negative { -magnitude } else { magnitude }).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scanf(p: &str, line: &str) -> Option<Vec<Value>> {
        Pattern::scanf(p)
            .ok()?
            .matches(line)
            .map(|c| c.values[1..].to_vec())
    }

    #[test]
    fn scanf_conversions_are_typed_and_the_whole_line_must_match() {
        // Example 2's lines (digest 004 §1.7), two spaces included.
        assert_eq!(
            scanf("MOVEABS %d %f", "MOVEABS 0  0.05"),
            Some(vec![Value::Int(0), Value::Float(0.05)])
        );
        assert_eq!(
            scanf("ENABLE %d", "ENABLE 0x1f"),
            Some(vec![Value::Int(31)])
        );
        // `%s` takes the whole word, as scanf's does: nothing is left for `=`.
        assert_eq!(scanf("SET %s=%f;", "SET speed=-1.5e3;"), None);
        assert_eq!(scanf("P %d", "P 1 2"), None);
        assert_eq!(scanf("P %d", "P1"), None);
        assert_eq!(scanf("P %d", "P x"), None);
        assert_eq!(scanf("P %d", "P 99999999999999999999"), None);
        assert_eq!(scanf("P %f", "P 1e999"), None);
        assert_eq!(scanf("100%%", "100%"), Some(vec![]));
        assert_eq!(
            scanf("V%f,%f", "V-1.,.5"),
            Some(vec![Value::Float(-1.0), Value::Float(0.5)])
        );
    }

    #[test]
    fn bad_patterns_say_why() {
        assert!(Pattern::scanf("X %q").unwrap_err().contains("%q"));
        assert!(Pattern::scanf("X %").is_err());
        assert!(Pattern::scanf("  ").is_err());
        assert!(Pattern::regex("(", &[]).is_err());
        let e = Pattern::regex("A(\\d)", &[CaptureType::Int, CaptureType::Int]).unwrap_err();
        assert!(e.contains("2 groups"), "{e}");
    }

    #[test]
    fn regex_groups_are_typed_named_and_anchored() {
        let p = Pattern::regex(
            r"POS (?P<axis>\d+) (\S+)",
            &[CaptureType::Int, CaptureType::Float],
        )
        .unwrap();
        let c = p.matches("POS 2 1.5").unwrap();
        assert_eq!(c.get("axis"), Some(&Value::Int(2)));
        assert_eq!(c.get("2"), Some(&Value::Float(1.5)));
        assert_eq!(c.get("0"), Some(&Value::Str("POS 2 1.5".into())));
        assert!(p.matches("xPOS 2 1.5").is_none());
        assert!(p.matches("POS 2 abc").is_none());
    }
}
