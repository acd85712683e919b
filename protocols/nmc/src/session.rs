//! The server side of one connection, sans-IO.
//!
//! Inputs, in this order: [`ServerSession::receive`] the bytes read from the socket; then
//! [`ServerSession::poll`] until it returns `None`, handling each [`Event::Request`] and
//! answering it with [`ServerSession::reply`] (in any order: replies carry the sequence
//! number). Outputs: [`ServerSession::take_output`] the bytes to write after each round;
//! once [`ServerSession::is_closed`] is true, write what is left and close the socket.
//!
//! The session answers by itself what needs no engine: the version hello (which must come
//! first), a function id the table does not have or that the library serves alone
//! (`RTN_UNKNOWN_FUNCTION`: the connection stays), and a broken stream (garbage, a frame above
//! the size limit: an error reply with sequence 0, then close).

use crate::errors::{RTN_FRAME_TOO_LARGE, RTN_UNKNOWN_FUNCTION, RTN_VERSION};
use crate::frame::{self, Frame, FrameDecoder, FrameError, Header, Kind, VERSION};
use crate::payload::{Reader, Writer};
use crate::table::{self, Function, Served};

/// What [`ServerSession::poll`] found.
#[derive(Debug, PartialEq)]
pub enum Event {
    /// A call to serve; answer with [`ServerSession::reply`].
    Request {
        sequence: u32,
        function: &'static Function,
        payload: Vec<u8>,
    },
    /// The version was agreed.
    Negotiated { version: u8 },
    /// A request for a function the server does not serve was answered with
    /// `RTN_UNKNOWN_FUNCTION`; the connection stays.
    UnknownFunction { function: u16 },
    /// The connection must close (after the output is written): why.
    Close(CloseReason),
}

#[derive(Debug, PartialEq)]
pub enum CloseReason {
    /// Not this protocol, or a frame above the size limit.
    Frame(FrameError),
    /// No version in common, or a request before the hello.
    Version,
}

/// One connection's protocol state.
#[derive(Debug, Default)]
pub struct ServerSession {
    decoder: FrameDecoder,
    version: Option<u8>,
    out: Vec<u8>,
    closed: bool,
}

impl ServerSession {
    pub fn new() -> ServerSession {
        ServerSession::default()
    }

    /// Bytes read from the socket.
    pub fn receive(&mut self, bytes: &[u8]) {
        if !self.closed {
            self.decoder.push(bytes);
        }
    }

    /// The next thing to act on, `None` when the bytes received so far are used up.
    pub fn poll(&mut self) -> Option<Event> {
        if self.closed {
            return None;
        }
        let frame = match self.decoder.next_frame() {
            Ok(Some(f)) => f,
            Ok(None) => return None,
            Err(e) => {
                let status = match e {
                    FrameError::TooLarge { .. } => RTN_FRAME_TOO_LARGE,
                    FrameError::Garbage => crate::errors::RTN_BAD_PAYLOAD,
                };
                self.answer(Kind::Reply, 0, 0, status, e.to_string().as_bytes());
                self.closed = true;
                return Some(Event::Close(CloseReason::Frame(e)));
            }
        };
        Some(self.handle(frame))
    }

    fn handle(&mut self, frame: Frame) -> Event {
        let h = frame.header;
        match (h.kind, self.version) {
            (Kind::Hello, _) => self.hello(h, &frame.payload),
            (Kind::Request, Some(_)) => match table::by_id(h.function) {
                Some(function) if function.served == Served::Server => Event::Request {
                    sequence: h.sequence,
                    function,
                    payload: frame.payload,
                },
                _ => {
                    let text = format!("function id {:#06x} is not served", h.function);
                    self.reply(
                        h.sequence,
                        h.function,
                        RTN_UNKNOWN_FUNCTION,
                        text.as_bytes(),
                    );
                    Event::UnknownFunction {
                        function: h.function,
                    }
                }
            },
            // A request before the hello, or a reply sent to the server.
            _ => {
                let text = b"the first frame must be a hello (version negotiation)";
                self.answer(Kind::Reply, h.sequence, h.function, RTN_VERSION, text);
                self.closed = true;
                Event::Close(CloseReason::Version)
            }
        }
    }

    fn hello(&mut self, h: Header, payload: &[u8]) -> Event {
        let mut r = Reader::new(payload);
        let range = (r.u16(), r.u16());
        let chosen = match range {
            (Ok(low), Ok(high)) if low <= u16::from(VERSION) && u16::from(VERSION) <= high => {
                Some(VERSION)
            }
            _ => None,
        };
        match chosen {
            Some(v) => {
                self.version = Some(v);
                let mut w = Writer::new();
                w.u16(u16::from(v));
                self.answer(Kind::Hello, h.sequence, 0, 0, &w.bytes);
                Event::Negotiated { version: v }
            }
            None => {
                let text = format!("this server speaks version {VERSION} only");
                self.answer(Kind::Hello, h.sequence, 0, RTN_VERSION, text.as_bytes());
                self.closed = true;
                Event::Close(CloseReason::Version)
            }
        }
    }

    /// Answer request `sequence` of `function` with return code `status` and `payload` (the out
    /// arguments when `status` is 0, else the error's description).
    pub fn reply(&mut self, sequence: u32, function: u16, status: i16, payload: &[u8]) {
        self.answer(Kind::Reply, sequence, function, status, payload);
    }

    fn answer(&mut self, kind: Kind, sequence: u32, function: u16, status: i16, payload: &[u8]) {
        let header = Header {
            version: self.version.unwrap_or(VERSION),
            kind,
            sequence,
            function,
            status,
            length: 0,
        };
        frame::encode(header, payload, &mut self.out);
    }

    /// The bytes to write now (empty if none).
    pub fn take_output(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.out)
    }

    /// Write what is left, then close.
    pub fn is_closed(&self) -> bool {
        self.closed
    }
}

/// The client's hello: it speaks versions `low ..= high`.
pub fn hello(low: u8, high: u8, out: &mut Vec<u8>) {
    let mut w = Writer::new();
    w.u16(u16::from(low)).u16(u16::from(high));
    let header = Header {
        version: high,
        kind: Kind::Hello,
        sequence: 0,
        function: 0,
        status: 0,
        length: 0,
    };
    frame::encode(header, &w.bytes, out);
}

/// A request frame for `function` with `payload` (its in arguments).
pub fn request(sequence: u32, function: u16, payload: &[u8], out: &mut Vec<u8>) {
    let header = Header {
        version: VERSION,
        kind: Kind::Request,
        sequence,
        function,
        status: 0,
        length: 0,
    };
    frame::encode(header, payload, out);
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::table::MT_GET_STS;

    fn frames(bytes: &[u8]) -> Vec<Frame> {
        let mut d = FrameDecoder::new();
        d.push(bytes);
        let mut v = Vec::new();
        while let Some(f) = d.next_frame().unwrap() {
            v.push(f);
        }
        v
    }

    fn negotiated() -> ServerSession {
        let mut s = ServerSession::new();
        let mut b = Vec::new();
        hello(1, 3, &mut b);
        s.receive(&b);
        assert_eq!(s.poll(), Some(Event::Negotiated { version: 1 }));
        let f = frames(&s.take_output());
        assert_eq!(f[0].header.kind, Kind::Hello);
        assert_eq!(f[0].payload, [1, 0]);
        s
    }

    #[test]
    fn a_request_after_the_hello_is_an_event_and_its_reply_echoes_the_sequence() {
        let mut s = negotiated();
        let mut b = Vec::new();
        request(77, MT_GET_STS.id, &[5, 0x80], &mut b);
        s.receive(&b);
        let Some(Event::Request {
            sequence,
            function,
            payload,
        }) = s.poll()
        else {
            panic!("no request");
        };
        assert_eq!(
            (sequence, function.name, payload),
            (77, "NMC_MtGetSts", vec![5, 0x80])
        );
        assert_eq!(s.poll(), None);
        s.reply(77, MT_GET_STS.id, 0, &[8, 0]);
        let f = frames(&s.take_output());
        assert_eq!(f[0].header.sequence, 77);
        assert_eq!(f[0].header.status, 0);
        assert_eq!(f[0].payload, [8, 0]);
    }

    #[test]
    fn unknown_and_library_only_functions_are_answered_and_the_connection_stays() {
        let mut s = negotiated();
        let mut b = Vec::new();
        request(1, 0x7FFF, &[], &mut b);
        request(2, table::GET_LAST_ERR.id, &[], &mut b);
        s.receive(&b);
        assert_eq!(s.poll(), Some(Event::UnknownFunction { function: 0x7FFF }));
        assert_eq!(s.poll(), Some(Event::UnknownFunction { function: 3 }));
        let f = frames(&s.take_output());
        assert_eq!(f.len(), 2);
        assert!(f.iter().all(|f| f.header.status == RTN_UNKNOWN_FUNCTION));
        assert!(!s.is_closed());
    }

    #[test]
    fn garbage_a_request_before_the_hello_and_a_bad_version_close() {
        let mut s = ServerSession::new();
        s.receive(b"\x00\x01garbage garbage!");
        assert!(matches!(
            s.poll(),
            Some(Event::Close(CloseReason::Frame(FrameError::Garbage)))
        ));
        assert!(s.is_closed());
        assert_eq!(
            frames(&s.take_output())[0].header.status,
            crate::errors::RTN_BAD_PAYLOAD
        );

        let mut s = ServerSession::new();
        let mut b = Vec::new();
        request(1, MT_GET_STS.id, &[], &mut b);
        s.receive(&b);
        assert_eq!(s.poll(), Some(Event::Close(CloseReason::Version)));

        let mut s = ServerSession::new();
        let mut b = Vec::new();
        hello(2, 9, &mut b);
        s.receive(&b);
        assert_eq!(s.poll(), Some(Event::Close(CloseReason::Version)));
        assert_eq!(frames(&s.take_output())[0].header.status, RTN_VERSION);
    }
}
