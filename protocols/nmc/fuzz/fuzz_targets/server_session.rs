//! Arbitrary bytes into the server's session as a socket feeds them, in two chunks split where
//! the input says: never panics; every request event names a row of the table; after a close
//! nothing more comes out of `poll`; the output is whole frames.

#![no_main]

use libfuzzer_sys::fuzz_target;
use mcemu_nmc::session::{Event, ServerSession};
use mcemu_nmc::table;

fuzz_target!(|data: &[u8]| {
    let Some((&cut, bytes)) = data.split_first() else {
        return;
    };
    let (a, b) = bytes.split_at(usize::from(cut).min(bytes.len()));
    let mut s = ServerSession::new();
    for chunk in [a, b] {
        s.receive(chunk);
        while let Some(e) = s.poll() {
            match e {
                Event::Request {
                    sequence,
                    function,
                    payload,
                } => {
                    assert_eq!(table::by_id(function.id), Some(function));
                    // Answer as the server would: an error text, to exercise the reply path.
                    s.reply(sequence, function.id, 5, &payload[..payload.len().min(64)]);
                }
                Event::Close(_) => {
                    assert!(s.is_closed());
                    assert!(s.poll().is_none());
                }
                Event::Negotiated { .. } | Event::UnknownFunction { .. } => {}
            }
        }
    }
    let out = s.take_output();
    let mut d = mcemu_nmc::frame::FrameDecoder::new();
    d.push(&out);
    while let Ok(Some(_)) = d.next_frame() {}
    assert_eq!(d.pending(), 0, "the session wrote a partial frame");
});
