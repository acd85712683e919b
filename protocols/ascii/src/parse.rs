//! The call grammar of a Native ASCII line (issue 14, digest 004 §7.1 items 1, 5, 6):
//!
//! ```text
//! line  = ws name ws "(" ws [ arg ws { "," ws arg ws } ] ")" ws [ ";" ] ws
//! arg   = term { ws "|" ws term }          (| only between integers: CS_WCS1 | CS_PCS)
//! term  = [ "-" | "+" ] ( number | constant ) | string | "{" ws number-list ws "}"
//! number = decimal or 0x hex integer | C double (1.5, .5, 1e3, -2.5E-3)
//! string = '"' { char | \" | \\ | \n | \r | \t } '"'
//! ```
//!
//! Names are identifiers (`[A-Za-z_][A-Za-z0-9_]*`); constants are looked up in
//! `mcemu_dialects::himc::constants` (`TRUE`, `HOME_METHOD_33`, `BM_BUFF` …).

use mcemu_dialects::himc::constants::{constant, ConstantValue};

/// One argument as written.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    Int(i64),
    Double(f64),
    Str(String),
    Array(Vec<f64>),
}

/// A parsed call: `name(args…)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    pub name: String,
    pub args: Vec<Arg>,
}

/// Why a line is not a call.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParseError {
    /// Not the grammar (→ `eERR_HMPL_INVALID_STR_FORMAT`).
    #[error("syntax error at character {at}: {what}")]
    Syntax { at: usize, what: &'static str },
    /// Well-formed, but an argument cannot be a value: an unknown constant, an integer out of
    /// range, `|` on a double (→ `eERR_HMPL_INVALID_ARG`).
    #[error("invalid argument: {0}")]
    Argument(String),
}

struct Cursor<'a> {
    s: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    fn peek(&self) -> Option<u8> {
        self.s.get(self.at).copied()
    }

    fn ws(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t')) {
            self.at += 1;
        }
    }

    fn eat(&mut self, b: u8) -> bool {
        if self.peek() == Some(b) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    fn syntax<T>(&self, what: &'static str) -> Result<T, ParseError> {
        Err(ParseError::Syntax { at: self.at, what })
    }

    fn text(&self, from: usize) -> &str {
        std::str::from_utf8(self.s.get(from..self.at).unwrap_or_default()).unwrap_or_default()
    }

    fn ident(&mut self) -> Option<String> {
        let start = self.at;
        match self.peek() {
            Some(b) if b.is_ascii_alphabetic() || b == b'_' => self.at += 1,
            _ => return None,
        }
        while matches!(self.peek(), Some(b) if b.is_ascii_alphanumeric() || b == b'_') {
            self.at += 1;
        }
        Some(self.text(start).to_string())
    }
}

/// Parse one line (without its terminator).
pub fn parse_call(line: &str) -> Result<Call, ParseError> {
    let mut c = Cursor {
        s: line.as_bytes(),
        at: 0,
    };
    c.ws();
    let Some(name) = c.ident() else {
        return c.syntax("expected a function name");
    };
    c.ws();
    if !c.eat(b'(') {
        return c.syntax("expected `(`");
    }
    c.ws();
    let mut args = Vec::new();
    if !c.eat(b')') {
        loop {
            args.push(arg(&mut c)?);
            c.ws();
            if c.eat(b')') {
                break;
            }
            if !c.eat(b',') {
                return c.syntax("expected `,` or `)`");
            }
            c.ws();
        }
    }
    c.ws();
    c.eat(b';');
    c.ws();
    if c.peek().is_some() {
        return c.syntax("unexpected text after the call");
    }
    Ok(Call { name, args })
}

fn arg(c: &mut Cursor<'_>) -> Result<Arg, ParseError> {
    let first = term(c)?;
    c.ws();
    if c.peek() != Some(b'|') {
        return Ok(first);
    }
    let Arg::Int(mut bits) = first else {
        return Err(ParseError::Argument("`|` combines integers only".into()));
    };
    while c.eat(b'|') {
        c.ws();
        match term(c)? {
            Arg::Int(b) => bits |= b,
            _ => return Err(ParseError::Argument("`|` combines integers only".into())),
        }
        c.ws();
    }
    Ok(Arg::Int(bits))
}

fn term(c: &mut Cursor<'_>) -> Result<Arg, ParseError> {
    match c.peek() {
        Some(b'"') => string(c).map(Arg::Str),
        Some(b'{') => array(c).map(Arg::Array),
        Some(b'-' | b'+') => {
            let negative = c.peek() == Some(b'-');
            c.at += 1;
            c.ws();
            match term(c)? {
                Arg::Int(i) if negative => Ok(Arg::Int(-i)),
                Arg::Double(d) if negative => Ok(Arg::Double(-d)),
                a @ (Arg::Int(_) | Arg::Double(_)) => Ok(a),
                _ => c.syntax("a sign before a string or an array"),
            }
        }
        Some(b) if b.is_ascii_digit() || b == b'.' => number(c),
        Some(b) if b.is_ascii_alphabetic() || b == b'_' => {
            let at = c.at;
            let name = c.ident().unwrap_or_default();
            match constant(&name) {
                Some(ConstantValue::Int(i)) => Ok(Arg::Int(i)),
                Some(ConstantValue::Double(d)) => Ok(Arg::Double(d)),
                None if c.peek() == Some(b'(') => Err(ParseError::Syntax {
                    at,
                    what: "a call inside a call",
                }),
                None => Err(ParseError::Argument(format!("unknown constant `{name}`"))),
            }
        }
        _ => c.syntax("expected an argument"),
    }
}

fn number(c: &mut Cursor<'_>) -> Result<Arg, ParseError> {
    let start = c.at;
    if c.s
        .get(start..start + 2)
        .is_some_and(|p| p.eq_ignore_ascii_case(b"0x"))
    {
        c.at += 2;
        let digits = c.at;
        while matches!(c.peek(), Some(b) if b.is_ascii_hexdigit()) {
            c.at += 1;
        }
        if c.at == digits {
            return c.syntax("expected hex digits after 0x");
        }
        return i64::from_str_radix(c.text(digits), 16)
            .map(Arg::Int)
            .map_err(|_| ParseError::Argument(format!("{} is too large", c.text(start))));
    }
    let mut real = false;
    while let Some(b) = c.peek() {
        match b {
            b'0'..=b'9' => {}
            b'.' => real = true,
            b'e' | b'E' => {
                real = true;
                if matches!(c.s.get(c.at + 1), Some(b'+' | b'-')) {
                    c.at += 1;
                }
            }
            _ => break,
        }
        c.at += 1;
    }
    // A trailing C suffix as a C program may write it (1.5f, 10L) is not HMPL.
    if matches!(c.peek(), Some(b) if b.is_ascii_alphanumeric() || b == b'_') {
        return c.syntax("unexpected character in a number");
    }
    let text = c.text(start);
    if real {
        match text.parse::<f64>() {
            Ok(d) if d.is_finite() => Ok(Arg::Double(d)),
            Ok(_) => Err(ParseError::Argument(format!("{text} is out of range"))),
            Err(_) => Err(ParseError::Syntax {
                at: start,
                what: "not a number",
            }),
        }
    } else {
        text.parse::<i64>()
            .map(Arg::Int)
            .map_err(|_| ParseError::Argument(format!("{text} is too large")))
    }
}

fn string(c: &mut Cursor<'_>) -> Result<String, ParseError> {
    c.at += 1;
    let mut out = Vec::new();
    loop {
        match c.peek() {
            None => return c.syntax("unterminated string"),
            Some(b'"') => {
                c.at += 1;
                return Ok(String::from_utf8_lossy(&out).into_owned());
            }
            Some(b'\\') => {
                c.at += 1;
                let e = match c.peek() {
                    Some(b'n') => b'\n',
                    Some(b'r') => b'\r',
                    Some(b't') => b'\t',
                    Some(b'0') => 0,
                    Some(b @ (b'"' | b'\\' | b'\'')) => b,
                    _ => return c.syntax("unknown escape"),
                };
                out.push(e);
                c.at += 1;
            }
            Some(b) => {
                out.push(b);
                c.at += 1;
            }
        }
    }
}

fn array(c: &mut Cursor<'_>) -> Result<Vec<f64>, ParseError> {
    c.at += 1;
    c.ws();
    let mut values = Vec::new();
    if c.eat(b'}') {
        return Ok(values);
    }
    loop {
        match term(c)? {
            Arg::Int(i) => values.push(i as f64),
            Arg::Double(d) => values.push(d),
            _ => return c.syntax("an array holds numbers"),
        }
        c.ws();
        if c.eat(b'}') {
            return Ok(values);
        }
        if !c.eat(b',') {
            return c.syntax("expected `,` or `}`");
        }
        c.ws();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn call(s: &str) -> Call {
        parse_call(s).unwrap()
    }

    #[test]
    fn calls_with_spaces_and_a_trailing_semicolon() {
        let c = call("  MoveAbs( 0 , 100.5 ) ; ");
        assert_eq!(c.name, "MoveAbs");
        assert_eq!(c.args, [Arg::Int(0), Arg::Double(100.5)]);
        assert_eq!(call("IsSystemOper()").args, []);
        assert_eq!(call("EStop();").name, "EStop");
    }

    #[test]
    fn numbers_as_c_writes_them() {
        let c = call("f(0x6041, -3, 1e3, -2.5E-3, .5, 7., +4, 0XFF)");
        assert_eq!(
            c.args,
            [
                Arg::Int(0x6041),
                Arg::Int(-3),
                Arg::Double(1000.0),
                Arg::Double(-0.0025),
                Arg::Double(0.5),
                Arg::Double(7.0),
                Arg::Int(4),
                Arg::Int(255),
            ]
        );
    }

    #[test]
    fn strings_constants_and_arrays() {
        let c = call(r#"StrFindStr("hello \"world\"", "wor")"#);
        assert_eq!(
            c.args,
            [Arg::Str("hello \"world\"".into()), Arg::Str("wor".into())]
        );
        let c = call("SetHomeMethod(0, HOME_METHOD_33)");
        assert_eq!(c.args, [Arg::Int(0), Arg::Int(33)]);
        let c = call("SetGrpCoordSys(0, CS_WCS1 | CS_PCS)");
        assert_eq!(c.args, [Arg::Int(0), Arg::Int(0x11)]);
        let c = call("SetGrpCoordTrans(0, CS_PCS, {400, 200, 0, 0, 0, 45})");
        assert_eq!(
            c.args[2],
            Arg::Array(vec![400.0, 200.0, 0.0, 0.0, 0.0, 45.0])
        );
        assert_eq!(
            call("f(TRUE, FALSE, -PI)").args[2],
            Arg::Double(-std::f64::consts::PI)
        );
    }

    #[test]
    fn what_is_not_a_call_is_a_syntax_error() {
        for bad in [
            "",
            "MoveAbs",
            "MoveAbs(0, 1",
            "MoveAbs(0,, 1)",
            "MoveAbs(0, 1) x",
            "1Move()",
            "f(\"abc)",
            "f(1.5f)",
            "f(0x)",
            "f(g(1))",
            "\u{fffd}()",
        ] {
            assert!(
                matches!(parse_call(bad), Err(ParseError::Syntax { .. })),
                "{bad:?}: {:?}",
                parse_call(bad)
            );
        }
    }

    #[test]
    fn well_formed_but_not_a_value_is_an_argument_error() {
        for bad in [
            "f(NO_SUCH_CONSTANT)",
            "f(99999999999999999999)",
            "f(1.5 | 2)",
            "f(1e999)",
        ] {
            assert!(
                matches!(parse_call(bad), Err(ParseError::Argument(_))),
                "{bad:?}"
            );
        }
    }
}
