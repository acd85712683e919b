//! What a call returns, and its text on the wire (issue 14 item 1): `int` as a signed decimal
//! (0x830207DA prints -2097018918, TV 71), `double` as C's `%.15g`, `int64` in decimal, the
//! array getters as the code then six values, `GetConfigVar` as its status then its value,
//! `void` as `0`.

use std::fmt::Write;

/// A function's return value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outcome {
    Int(i32),
    Double(f64),
    Int64(i64),
    /// The return code and the six output values (§8.3.30, §8.3.32–33).
    Array(i32, [f64; 6]),
    /// A status and a value: `GetConfigVar`'s `int *` status output then the `double` it
    /// returns (§17.3.1); `GetTouchProbe1Pos`'s `int` code then its `double *` output (§13.10).
    WithStatus(i32, f64),
    Void,
}

impl Outcome {
    /// An HMPL error code as the `int` a function returns (axis and group codes read negative).
    pub fn code(code: u32) -> Outcome {
        Outcome::Int(code as i32)
    }

    /// A BOOL.
    pub fn bool(b: bool) -> Outcome {
        Outcome::Int(i32::from(b))
    }

    /// Append the reply text, without the line ending.
    pub fn write(&self, out: &mut String) {
        match *self {
            Outcome::Int(i) => {
                let _ = write!(out, "{i}");
            }
            Outcome::Int64(i) => {
                let _ = write!(out, "{i}");
            }
            Outcome::Double(d) => write_g15(d, out),
            Outcome::Array(code, values) => {
                let _ = write!(out, "{code}");
                for v in values {
                    out.push(',');
                    write_g15(v, out);
                }
            }
            Outcome::WithStatus(status, value) => {
                let _ = write!(out, "{status},");
                write_g15(value, out);
            }
            Outcome::Void => out.push('0'),
        }
    }
}

/// `d` as C's `printf("%.15g", d)`.
pub fn write_g15(d: f64, out: &mut String) {
    const PRECISION: i32 = 15;
    if d.is_nan() {
        out.push_str(if d.is_sign_negative() { "-nan" } else { "nan" });
        return;
    }
    if d.is_infinite() {
        out.push_str(if d < 0.0 { "-inf" } else { "inf" });
        return;
    }
    if d == 0.0 {
        out.push_str(if d.is_sign_negative() { "-0" } else { "0" });
        return;
    }
    // The exponent after rounding to 15 significant digits decides the style, as in C.
    let sci = format!("{:.*e}", (PRECISION - 1) as usize, d);
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    if (-4..PRECISION).contains(&exp) {
        let decimals = usize::try_from(PRECISION - 1 - exp).unwrap_or(0);
        let fixed = format!("{d:.decimals$}");
        out.push_str(trim_zeros(&fixed));
    } else {
        out.push_str(trim_zeros(mantissa));
        let _ = write!(out, "e{}{:02}", if exp < 0 { '-' } else { '+' }, exp.abs());
    }
}

fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(o: Outcome) -> String {
        let mut s = String::new();
        o.write(&mut s);
        s
    }

    fn g(d: f64) -> String {
        text(Outcome::Double(d))
    }

    #[test]
    fn ints_are_signed_tv71() {
        assert_eq!(text(Outcome::code(0x8302_07da)), "-2097018918");
        assert_eq!(text(Outcome::code(0x1451)), "5201");
        assert_eq!(text(Outcome::Int64(-1)), "-1");
        assert_eq!(text(Outcome::Void), "0");
        assert_eq!(text(Outcome::bool(true)), "1");
    }

    #[test]
    fn doubles_as_percent_15g() {
        assert_eq!(g(1.234), "1.234");
        assert_eq!(g(100.0), "100");
        assert_eq!(g(-0.5), "-0.5");
        assert_eq!(g(0.1 + 0.2), "0.3");
        assert_eq!(g(125_410_439.217_423), "125410439.217423");
        assert_eq!(g(1e20), "1e+20");
        assert_eq!(g(1.5e-5), "1.5e-05");
        assert_eq!(g(0.0001), "0.0001");
        assert_eq!(g(123_456_789_012_345.0), "123456789012345");
        assert_eq!(g(1_234_567_890_123_456.0), "1.23456789012346e+15");
        assert_eq!(g(f64::MAX), "1.79769313486232e+308");
        assert_eq!(g(0.0), "0");
        assert_eq!(g(f64::INFINITY), "inf");
    }

    #[test]
    fn arrays_are_the_code_then_six_values() {
        let o = Outcome::Array(0, [400.0, 200.0, 0.0, 0.0, 0.0, 45.0]);
        assert_eq!(text(o), "0,400,200,0,0,0,45");
    }

    #[test]
    fn a_status_output_comes_before_the_value() {
        assert_eq!(text(Outcome::WithStatus(0, 2000.0)), "0,2000");
        assert_eq!(text(Outcome::WithStatus(-1, 0.0)), "-1,0");
    }
}
