//! A Native ASCII client over a plain `TcpStream`, and the golden-transcript runner of
//! `tests/ascii/` (a request file in, the replies diffed against an expected file, the way
//! linuxcncrsh's tests diff `expected-telnet-output`).

use std::io::{BufRead, BufReader, Write};
use std::net::TcpStream;
use std::path::Path;
use std::time::Duration;

use serde_json::Value;

use crate::Mcemu;

/// How long a reply may take before the client gives up (the test then fails).
pub const ASCII_REPLY_TIMEOUT: Duration = Duration::from_secs(20);

/// One Native ASCII connection.
pub struct AsciiClient {
    reader: BufReader<TcpStream>,
    writer: TcpStream,
}

impl AsciiClient {
    pub fn connect(address: &str) -> AsciiClient {
        let stream = TcpStream::connect(address)
            .unwrap_or_else(|e| panic!("cannot connect to ascii-native {address}: {e}"));
        stream.set_read_timeout(Some(ASCII_REPLY_TIMEOUT)).unwrap();
        let writer = stream.try_clone().unwrap();
        AsciiClient {
            reader: BufReader::new(stream),
            writer,
        }
    }

    /// Send raw bytes.
    pub fn send(&mut self, bytes: &[u8]) {
        self.writer.write_all(bytes).unwrap();
    }

    /// One reply line, with its terminator.
    pub fn read_reply(&mut self) -> String {
        let mut line = String::new();
        let n = self.reader.read_line(&mut line).unwrap();
        assert!(n > 0, "the server closed the connection");
        line
    }

    /// A reply if one arrives within `wait` (a fence on a reply that needs virtual time to
    /// run first); the client's usual timeout is restored.
    pub fn try_read_reply(&mut self, wait: Duration) -> Option<String> {
        self.reader.get_ref().set_read_timeout(Some(wait)).unwrap();
        let mut line = String::new();
        let got = self.reader.read_line(&mut line);
        self.reader
            .get_ref()
            .set_read_timeout(Some(ASCII_REPLY_TIMEOUT))
            .unwrap();
        match got {
            Ok(n) if n > 0 => Some(line),
            _ => None,
        }
    }

    /// Send `line` + CRLF; the reply without its CRLF (which must be there).
    pub fn call(&mut self, line: &str) -> String {
        self.send(format!("{line}\r\n").as_bytes());
        let reply = self.read_reply();
        reply
            .strip_suffix("\r\n")
            .unwrap_or_else(|| panic!("{line}: reply {reply:?} does not end in CRLF"))
            .to_string()
    }
}

/// Run transcript `tests/ascii/NAME.in` against `mcemu` and compare with `NAME.expected`.
///
/// Each line of the request file is sent as one call, and its reply is one line of the output;
/// blank lines and lines starting with `#` are skipped; `@advance {json}` posts the JSON to
/// `/time/advance` (virtual clock) and `@command {json}` to `/commands` (forcing an input …),
/// and neither replies. On a mismatch, panics with both
/// transcripts side by side, line by line.
pub fn run_transcript(mcemu: &Mcemu, dir: &Path, name: &str) {
    let request = std::fs::read_to_string(dir.join(format!("{name}.in")))
        .unwrap_or_else(|e| panic!("{name}.in: {e}"));
    let expected = std::fs::read_to_string(dir.join(format!("{name}.expected")))
        .unwrap_or_else(|e| panic!("{name}.expected: {e}"));
    let mut client = AsciiClient::connect(mcemu.address("ascii-native"));
    let mut got = String::new();
    for line in request.lines() {
        let line = line.trim_end();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if let Some(body) = line.strip_prefix("@advance ") {
            let body: Value =
                serde_json::from_str(body).unwrap_or_else(|e| panic!("{name}.in: `{line}`: {e}"));
            mcemu.advance(&body);
            continue;
        }
        if let Some(body) = line.strip_prefix("@command ") {
            let body: Value =
                serde_json::from_str(body).unwrap_or_else(|e| panic!("{name}.in: `{line}`: {e}"));
            mcemu.post_ok("/commands", &body);
            continue;
        }
        got.push_str(&client.call(line));
        got.push('\n');
    }
    if got != expected {
        let calls: Vec<&str> = request
            .lines()
            .filter(|l| !l.trim().is_empty() && !l.starts_with('#') && !l.starts_with('@'))
            .collect();
        let mut table = String::new();
        let (g, e): (Vec<&str>, Vec<&str>) = (got.lines().collect(), expected.lines().collect());
        for i in 0..g.len().max(e.len()) {
            let (gi, ei) = (g.get(i).unwrap_or(&"-"), e.get(i).unwrap_or(&"-"));
            let mark = if gi == ei { " " } else { "≠" };
            let call = calls.get(i).unwrap_or(&"");
            table.push_str(&format!("{mark} {call:<40} got {gi:<16} expected {ei}\n"));
        }
        panic!("transcript {name} differs:\n{table}");
    }
}
