//! The socketcand decoder and session on an arbitrary client byte stream, split into reads at
//! an arbitrary point: never panics; the split does not change what is decoded; the decoder
//! never holds more than one element's worth of bytes; every accepted `send` re-encodes to a
//! command that decodes to the same frame; the session's replies and its frame messages are
//! single well-formed elements. The same bytes as text go through the candump frame parser,
//! whose accepted frames print back to text that parses to the same frame.

#![no_main]

use libfuzzer_sys::fuzz_target;
use mcemu_can::socketcand::codec::{encode_frame, MAX_ELEMENT};
use mcemu_can::socketcand::{Command, Decoder, Session, SessionAction};
use mcemu_can::{Timestamp, WireFrame};

fn decode(chunks: &[&[u8]]) -> Vec<String> {
    let mut decoder = Decoder::new();
    let mut out = Vec::new();
    for chunk in chunks {
        decoder.decode(chunk, |c| out.push(format!("{c:?}")));
        assert!(decoder.buffered() < MAX_ELEMENT);
    }
    out
}

fn one_element(text: &str) {
    assert!(text.starts_with("< ") && text.ends_with(" >"), "{text:?}");
    let inner = &text[1..text.len() - 1];
    assert!(!inner.contains('<') && !inner.contains('>'), "{text:?}");
}

fuzz_target!(|data: &[u8]| {
    let split = usize::from(data.first().copied().unwrap_or(0)).min(data.len());
    let (a, b) = data.split_at(split);
    assert_eq!(decode(&[data]), decode(&[a, b]));

    let served = vec!["vcan0".to_string()];
    let mut session = Session::new();
    let mut decoder = Decoder::new();
    let mut actions = Vec::new();
    let mut frames = Vec::new();
    decoder.decode(data, |command| {
        if let Ok(Command::Send(frame)) = &command {
            frames.push(*frame);
        }
        session.on_command(command, &served, &mut actions);
    });
    for action in &actions {
        if let SessionAction::Reply(reply) = action {
            one_element(reply);
        }
    }
    let stamp = Timestamp {
        secs: 1_700_000_000,
        micros: 1,
    };
    for frame in frames {
        let mut text = String::new();
        encode_frame(&mut text, stamp, &frame);
        one_element(&text);
        let command = if frame.is_remote() {
            format!("< sendrtr {} {} >", frame.id(), frame.dlc())
        } else {
            let bytes: Vec<String> = frame.data().iter().map(|b| format!("{b:x}")).collect();
            format!(
                "< send {} {} {} >",
                frame.id(),
                frame.dlc(),
                bytes.join(" ")
            )
        };
        let mut again = Vec::new();
        Decoder::new().decode(command.as_bytes(), |c| again.push(c));
        assert_eq!(again, [Ok(Command::Send(frame))], "{command}");
    }

    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(frame) = text.parse::<WireFrame>() {
            assert_eq!(frame.to_string().parse::<WireFrame>(), Ok(frame));
        }
    }
});
