//! The socketcand ASCII protocol (linux-can/socketcand, doc/protocol.md), sans-IO.
//!
//! Every message in either direction is one element `< word args… >`. Client bytes outside
//! elements are ignored (as socketcand does); an element longer than [`MAX_ELEMENT`] bytes is
//! refused and skipped up to its `>`, so a client cannot make the decoder buffer without bound.
//! Decoding is total: any bytes give commands or [`CommandError`]s, never a panic.
//!
//! The server's messages follow what socketcand sends, byte for byte where python-can depends
//! on it: `< hi >`, `< ok >`, `< frame ID SECS.USECS HEX >` (data bytes as one run of hex
//! digits, a space before `>` even when there are none; a 3-digit id is standard, 8 digits
//! extended), `< error CLASS SECS.USECS >` for an error frame.

use std::fmt::Write;

use crate::clock::Timestamp;
use crate::frame::{CanId, FrameKind, WireFrame, EFF_MAX, MAX_DATA, SFF_MAX};

/// Longest element accepted, `<` to `>` (socketcand's longest classic command,
/// `< send 1FFFFFFF 8 FF FF FF FF FF FF FF FF >`, has 43).
pub const MAX_ELEMENT: usize = 256;
/// Longest bus name (socketcand: 16, the kernel's interface-name limit).
pub const MAX_BUS_NAME: usize = 16;

/// A client's command.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Command {
    /// `< open BUS >`
    Open(String),
    /// `< rawmode >`: receive every frame.
    RawMode,
    /// `< bcmmode >`: the default mode after `open`.
    BcmMode,
    /// `< controlmode >`
    ControlMode,
    /// `< isotpmode >`
    IsoTpMode,
    /// `< echo >`: answered with `< echo >`.
    Echo,
    /// `< send ID LEN BYTES… >` (a data frame) or `< sendrtr ID DLC >` (a remote frame).
    Send(WireFrame),
    /// A command of the protocol that mcemu does not implement; refused with the reason.
    Unsupported {
        command: &'static str,
        reason: &'static str,
    },
}

/// A client element that is not a valid command.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CommandError {
    #[error("element longer than {MAX_ELEMENT} bytes")]
    TooLong,
    #[error("element is not ASCII text")]
    NotAscii,
    #[error("empty element")]
    Empty,
    #[error("unknown command '{0}'")]
    Unknown(String),
    #[error("{command}: {reason}")]
    Syntax {
        command: &'static str,
        reason: String,
    },
}

/// Splits a client's byte stream into elements and parses them.
#[derive(Debug, Default)]
pub struct Decoder {
    element: Vec<u8>,
    state: State,
}

#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
enum State {
    /// Between elements: bytes up to `<` are ignored.
    #[default]
    Outside,
    /// After `<`: collecting up to `>`.
    Inside,
    /// An element grew past the limit: skipping up to its `>`.
    Skipping,
}

impl Decoder {
    pub fn new() -> Self {
        Self::default()
    }

    /// Feed bytes; each complete element becomes a command or an error, in order.
    pub fn decode(&mut self, input: &[u8], mut emit: impl FnMut(Result<Command, CommandError>)) {
        for &byte in input {
            match (self.state, byte) {
                (State::Outside, b'<') => {
                    self.element.clear();
                    self.element.push(byte);
                    self.state = State::Inside;
                }
                (State::Outside, _) => {}
                (State::Inside, b'>') => {
                    self.element.push(byte);
                    self.state = State::Outside;
                    emit(parse_element(&self.element));
                    self.element.clear();
                }
                (State::Inside, _) if self.element.len() + 1 >= MAX_ELEMENT => {
                    self.element.clear();
                    self.state = State::Skipping;
                    emit(Err(CommandError::TooLong));
                }
                (State::Inside, _) => self.element.push(byte),
                (State::Skipping, b'>') => self.state = State::Outside,
                (State::Skipping, _) => {}
            }
        }
    }

    /// Bytes held for an incomplete element.
    pub fn buffered(&self) -> usize {
        self.element.len()
    }
}

/// Parse one element, `<` to `>` included.
pub fn parse_element(element: &[u8]) -> Result<Command, CommandError> {
    let text = std::str::from_utf8(element)
        .ok()
        .filter(|t| t.is_ascii())
        .ok_or(CommandError::NotAscii)?;
    let inner = text
        .strip_prefix('<')
        .and_then(|t| t.strip_suffix('>'))
        .unwrap_or(text);
    let mut words = inner.split_ascii_whitespace();
    let name = words.next().ok_or(CommandError::Empty)?;
    let args: Vec<&str> = words.collect();
    let no_args = |command: &'static str, then: Command| {
        if args.is_empty() {
            Ok(then)
        } else {
            Err(syntax(command, "takes no arguments".to_string()))
        }
    };
    match name {
        "open" => parse_open(&args),
        "rawmode" => no_args("rawmode", Command::RawMode),
        "bcmmode" => no_args("bcmmode", Command::BcmMode),
        "controlmode" => no_args("controlmode", Command::ControlMode),
        "isotpmode" => no_args("isotpmode", Command::IsoTpMode),
        "echo" => no_args("echo", Command::Echo),
        "send" => parse_send(&args).map(Command::Send),
        "sendrtr" => parse_sendrtr(&args).map(Command::Send),
        "fdsend" => Ok(unsupported("fdsend", "CAN FD is off on this bus")),
        "add" | "update" | "delete" => Ok(unsupported(
            "add/update/delete",
            "cyclic BCM transmission is not implemented by mcemu; send frames with send",
        )),
        "filter" | "muxfilter" | "subscribe" | "unsubscribe" => Ok(unsupported(
            "filter/subscribe",
            "BCM reception filters are not implemented by mcemu; use rawmode",
        )),
        "statistics" => Ok(unsupported(
            "statistics",
            "statistics are not implemented by mcemu; read the control API's counters",
        )),
        "isotpconf" | "sendpdu" => Ok(unsupported("isotp", "ISO-TP is not implemented by mcemu")),
        // `< can0 B … >` / `< can0 C … >`: bit timing and control mode of a real interface.
        _ if args.first().is_some_and(|op| *op == "B" || *op == "C") => Ok(unsupported(
            "bus configuration",
            "the emulated bus's bit timing and control mode are set in mcemu's config",
        )),
        other => Err(CommandError::Unknown(printable(other))),
    }
}

fn unsupported(command: &'static str, reason: &'static str) -> Command {
    Command::Unsupported { command, reason }
}

fn syntax(command: &'static str, reason: String) -> CommandError {
    CommandError::Syntax { command, reason }
}

/// At most 32 characters of `text`, each a letter, digit, `_`, `-` or `.` (others become
/// `?`): safe to echo back inside an element.
fn printable(text: &str) -> String {
    text.chars()
        .take(32)
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.') {
                c
            } else {
                '?'
            }
        })
        .collect()
}

fn parse_open(args: &[&str]) -> Result<Command, CommandError> {
    let [bus] = args else {
        return Err(syntax(
            "open",
            "takes one bus name: < open vcan0 >".to_string(),
        ));
    };
    if bus.len() > MAX_BUS_NAME || printable(bus) != *bus {
        return Err(syntax(
            "open",
            format!(
                "bad bus name '{}': at most {MAX_BUS_NAME} letters, digits, '_', '-', '.'",
                printable(bus)
            ),
        ));
    }
    Ok(Command::Open((*bus).to_string()))
}

/// `ID`: 8 hex digits for an extended id (socketcand's rule), fewer for a standard one.
fn parse_id(command: &'static str, text: &str) -> Result<CanId, CommandError> {
    let value = parse_hex(text, 8)
        .ok_or_else(|| syntax(command, format!("bad CAN id '{}'", printable(text))))?;
    if text.len() == 8 {
        if value > EFF_MAX {
            return Err(syntax(
                command,
                format!("extended id {value:08X} exceeds 1FFFFFFF"),
            ));
        }
        CanId::extended(value).map_err(|e| syntax(command, e.to_string()))
    } else {
        if value > SFF_MAX {
            return Err(syntax(
                command,
                format!("id {value:X} does not fit 11 bits; extended ids take 8 hex digits"),
            ));
        }
        CanId::standard(value as u16).map_err(|e| syntax(command, e.to_string()))
    }
}

fn parse_len(command: &'static str, text: &str) -> Result<u8, CommandError> {
    match text.as_bytes() {
        [digit @ b'0'..=b'8'] => Ok(digit - b'0'),
        _ => Err(syntax(
            command,
            format!("bad length '{}': classic CAN takes 0-8", printable(text)),
        )),
    }
}

fn parse_hex(text: &str, max_digits: usize) -> Option<u32> {
    if text.is_empty() || text.len() > max_digits || !text.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(text, 16).ok()
}

fn parse_send(args: &[&str]) -> Result<WireFrame, CommandError> {
    let [id, len, bytes @ ..] = args else {
        return Err(syntax("send", "expects < send ID LEN BYTES… >".to_string()));
    };
    let id = parse_id("send", id)?;
    let len = parse_len("send", len)?;
    if bytes.len() != usize::from(len) {
        return Err(syntax(
            "send",
            format!("length {len} but {} data bytes", bytes.len()),
        ));
    }
    let mut data = [0u8; MAX_DATA];
    for (slot, text) in data.iter_mut().zip(bytes) {
        *slot = parse_hex(text, 2)
            .ok_or_else(|| syntax("send", format!("bad data byte '{}'", printable(text))))?
            as u8;
    }
    WireFrame::new(id, &data[..usize::from(len)]).map_err(|e| syntax("send", e.to_string()))
}

fn parse_sendrtr(args: &[&str]) -> Result<WireFrame, CommandError> {
    let [id, dlc] = args else {
        return Err(syntax("sendrtr", "expects < sendrtr ID DLC >".to_string()));
    };
    let id = parse_id("sendrtr", id)?;
    let dlc = parse_len("sendrtr", dlc)?;
    WireFrame::remote(id, dlc).map_err(|e| syntax("sendrtr", e.to_string()))
}

/// `< hi >`, the greeting.
pub const HI: &str = "< hi >";
/// `< ok >`
pub const OK: &str = "< ok >";
/// `< echo >`
pub const ECHO: &str = "< echo >";

/// `< error TEXT >` for a refused command (`TEXT` must not contain `<` or `>`).
pub fn encode_error_reply(out: &mut String, text: &str) {
    out.push_str("< error ");
    out.extend(
        text.chars()
            .map(|c| if c == '<' || c == '>' { '?' } else { c }),
    );
    out.push_str(" >");
}

/// A frame from the bus, as socketcand sends it in raw mode.
pub fn encode_frame(out: &mut String, stamp: Timestamp, frame: &WireFrame) {
    // `write!` to a String cannot fail.
    let _ = match frame.kind() {
        FrameKind::Data => {
            let _ = write!(out, "< frame {} {stamp} ", frame.id());
            for byte in frame.data() {
                let _ = write!(out, "{byte:02X}");
            }
            write!(out, " >")
        }
        FrameKind::Remote => write!(out, "< rtr {} {stamp} {} >", frame.id(), frame.dlc()),
        FrameKind::Error => write!(
            out,
            "< error {:03X} {stamp} >",
            frame.error_class().unwrap_or_default()
        ),
    };
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    fn decode_all(bytes: &[u8]) -> Vec<Result<Command, CommandError>> {
        let mut out = vec![];
        Decoder::new().decode(bytes, |c| out.push(c));
        out
    }

    #[test]
    fn python_can_commands() {
        // What python-can's socketcand interface sends (hex length, unpadded lowercase bytes).
        let got =
            decode_all(b"< open vcan0 >< rawmode >< send 123 3 1 f1 ff >< send 1AAAAAAA 0  >");
        assert_eq!(
            got,
            [
                Ok(Command::Open("vcan0".into())),
                Ok(Command::RawMode),
                Ok(Command::Send(
                    WireFrame::standard(0x123, &[1, 0xF1, 0xFF]).unwrap()
                )),
                Ok(Command::Send(
                    WireFrame::extended(0x1AAA_AAAA, &[]).unwrap()
                )),
            ]
        );
    }

    #[test]
    fn elements_split_across_reads_and_garbage_between() {
        let mut decoder = Decoder::new();
        let mut out = vec![];
        for chunk in [&b"junk < se"[..], b"nd 7FF 1 4", b"2 >\r\n<", b" echo >"] {
            decoder.decode(chunk, |c| out.push(c));
        }
        assert_eq!(
            out,
            [
                Ok(Command::Send(WireFrame::standard(0x7FF, &[0x42]).unwrap())),
                Ok(Command::Echo),
            ]
        );
    }

    #[test]
    fn bad_commands_are_errors() {
        let cases: &[&[u8]] = &[
            b"< >",
            b"< frobnicate >",
            b"< send 800 0 >",
            b"< send 123 9 >",
            b"< send 123 2 1 >",
            b"< send 123 1 100 >",
            b"< send 2AAAAAAA 0 >",
            b"< send xyz 0 >",
            b"< sendrtr 123 >",
            b"< open >",
            b"< open a-bus-name-far-too-long >",
            b"< rawmode now >",
            b"< \xff >",
        ];
        for case in cases {
            let got = decode_all(case);
            assert!(
                matches!(got.as_slice(), [Err(_)]),
                "{:?} → {got:?}",
                String::from_utf8_lossy(case)
            );
        }
        let mut long = b"<".to_vec();
        long.extend([b'a'; 1000]);
        long.extend(b">< echo >");
        assert_eq!(
            decode_all(&long),
            [Err(CommandError::TooLong), Ok(Command::Echo)]
        );
    }

    #[test]
    fn unsupported_commands_say_why() {
        for case in [
            &b"< subscribe 0 0 123 >"[..],
            b"< add 1 0 123 0 >",
            b"< fdsend 123 0 0 >",
            b"< vcan0 B 500000 >",
        ] {
            assert!(matches!(
                decode_all(case).as_slice(),
                [Ok(Command::Unsupported { .. })]
            ));
        }
    }

    #[test]
    fn frames_as_socketcand_sends_them() {
        let stamp = Timestamp {
            secs: 23,
            micros: 424_242,
        };
        let mut out = String::new();
        let cases = [
            (
                WireFrame::standard(0x123, &[0x11, 0x22, 0x33, 0x44]).unwrap(),
                "< frame 123 23.424242 11223344 >",
            ),
            (
                WireFrame::standard(0x123, &[]).unwrap(),
                "< frame 123 23.424242  >",
            ),
            (
                WireFrame::extended(0x1AAA_AAAA, &[1]).unwrap(),
                "< frame 1AAAAAAA 23.424242 01 >",
            ),
            (
                WireFrame::remote(CanId::standard(0x123).unwrap(), 4).unwrap(),
                "< rtr 123 23.424242 4 >",
            ),
            (
                WireFrame::error(0x4, &[]).unwrap(),
                "< error 004 23.424242 >",
            ),
        ];
        for (frame, text) in cases {
            out.clear();
            encode_frame(&mut out, stamp, &frame);
            assert_eq!(out, text);
        }
        out.clear();
        encode_error_reply(&mut out, "no <such> bus");
        assert_eq!(out, "< error no ?such? bus >");
    }
}
