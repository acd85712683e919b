//! A raw socketcand client (the protocol of python-can's `socketcand` interface) for tests that
//! must control how frames are written: several frames in one TCP write arrive at mcemu as one
//! batch, which no Python client can force.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

/// A socketcand client in raw mode on bus `vcan0`.
pub struct Socketcand {
    stream: TcpStream,
    pending: Vec<u8>,
}

impl Socketcand {
    pub fn open(address: &str) -> Socketcand {
        let stream = TcpStream::connect(address).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_millis(100)))
            .unwrap();
        let mut c = Socketcand {
            stream,
            pending: Vec::new(),
        };
        assert_eq!(c.element(), "< hi >");
        c.send("< open vcan0 >");
        assert_eq!(c.element(), "< ok >");
        c.send("< rawmode >");
        assert_eq!(c.element(), "< ok >");
        c
    }

    pub fn send(&mut self, text: &str) {
        self.stream.write_all(text.as_bytes()).unwrap();
    }

    /// The next element; panics when none comes within 10 s.
    pub fn element(&mut self) -> String {
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            if let Some(end) = self.pending.iter().position(|&b| b == b'>') {
                let element: Vec<u8> = self.pending.drain(..=end).collect();
                return String::from_utf8(element).unwrap().trim().to_string();
            }
            assert!(Instant::now() < deadline, "no element from socketcand");
            let mut buf = [0u8; 1024];
            match self.stream.read(&mut buf) {
                Ok(0) => panic!("socketcand closed the connection"),
                Ok(n) => self.pending.extend_from_slice(&buf[..n]),
                Err(e) if matches!(e.kind(), std::io::ErrorKind::WouldBlock) => {}
                Err(e) if matches!(e.kind(), std::io::ErrorKind::TimedOut) => {}
                Err(e) => panic!("socketcand: {e}"),
            }
        }
    }

    /// Send an expedited SDO upload request of (index, sub) to `node` and wait for the node's
    /// answer; both frames as candump's `ID#DATA`.
    pub fn sdo_upload(&mut self, node: u16, index: u16, sub: u8) -> (String, String) {
        let [lo, hi] = index.to_le_bytes();
        let request = [0x40, lo, hi, sub, 0, 0, 0, 0];
        let bytes: Vec<String> = request.iter().map(|b| format!("{b:02X}")).collect();
        self.send(&format!(
            "< send {:03X} 8 {} >",
            0x600 + node,
            bytes.join(" ")
        ));
        let answer_id = format!("{:03X}", 0x580 + node);
        loop {
            let element = self.element();
            let fields: Vec<&str> = element.split_whitespace().collect();
            // < frame ID SECS.USECS DATA >
            if fields.get(1) == Some(&"frame") && fields.get(2) == Some(&answer_id.as_str()) {
                let data = fields.get(4).unwrap().to_string();
                return (
                    format!("{:03X}#{}", 0x600 + node, hex(&request)),
                    format!("{answer_id}#{data}"),
                );
            }
        }
    }
}

/// The frame of a socketcand `< frame ID SECS.USECS DATA >` element as (ID, DATA) in hex, or
/// `None` for another element.
pub fn frame_of(element: &str) -> Option<(String, String)> {
    let fields: Vec<&str> = element.split_whitespace().collect();
    match fields.as_slice() {
        ["<", "frame", id, _, data, ">"] => Some((id.to_string(), data.to_string())),
        ["<", "frame", id, _, ">"] => Some((id.to_string(), String::new())),
        _ => None,
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02X}")).collect()
}
