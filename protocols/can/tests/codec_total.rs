//! The text codecs are total: any bytes decode to commands or errors without panicking, in
//! the same way however the stream is split into reads; frames survive a round trip through
//! the socketcand `send` form, the candump form and SocketCAN's layout.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use mcemu_can::socketcand::codec::MAX_ELEMENT;
use mcemu_can::socketcand::{Command, Decoder};
use mcemu_can::{CanId, WireFrame};
use proptest::prelude::*;

fn decode(chunks: &[&[u8]]) -> Vec<String> {
    let mut decoder = Decoder::new();
    let mut out = Vec::new();
    for chunk in chunks {
        decoder.decode(chunk, |c| out.push(format!("{c:?}")));
        assert!(decoder.buffered() < MAX_ELEMENT);
    }
    out
}

fn frame_strategy() -> impl Strategy<Value = WireFrame> {
    let data = prop::collection::vec(any::<u8>(), 0..=8);
    prop_oneof![
        (0u16..=0x7FF, data.clone()).prop_map(|(id, d)| WireFrame::standard(id, &d).unwrap()),
        (0u32..=0x1FFF_FFFF, data).prop_map(|(id, d)| WireFrame::extended(id, &d).unwrap()),
        (0u16..=0x7FF, 0u8..=8).prop_map(|(id, n)| WireFrame::remote(
            CanId::standard(id).unwrap(),
            n
        )
        .unwrap()),
        (0u32..=0x1FFF_FFFF, 0u8..=8).prop_map(|(id, n)| WireFrame::remote(
            CanId::extended(id).unwrap(),
            n
        )
        .unwrap()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2_000, ..ProptestConfig::default() })]

    #[test]
    fn any_bytes_decode_the_same_however_split(
        bytes in prop::collection::vec(prop_oneof![any::<u8>(), Just(b'<'), Just(b'>'), Just(b' ')], 0..300),
        split in any::<prop::sample::Index>(),
    ) {
        let at = split.index(bytes.len() + 1);
        let (a, b) = bytes.split_at(at);
        prop_assert_eq!(decode(&[&bytes]), decode(&[a, b]));
        let _ = std::str::from_utf8(&bytes).map(|t| t.parse::<WireFrame>());
    }

    #[test]
    fn frames_round_trip(frame in frame_strategy()) {
        let command = if frame.is_remote() {
            format!("< sendrtr {} {} >", frame.id(), frame.dlc())
        } else {
            let bytes: Vec<String> = frame.data().iter().map(|b| format!("{b:02X}")).collect();
            format!("< send {} {} {} >", frame.id(), frame.dlc(), bytes.join(" "))
        };
        let mut got = vec![];
        Decoder::new().decode(command.as_bytes(), |c| got.push(c));
        prop_assert_eq!(got, vec![Ok(Command::Send(frame))]);
        prop_assert_eq!(frame.to_string().parse::<WireFrame>(), Ok(frame));
        prop_assert_eq!(
            WireFrame::from_socketcan(frame.socketcan_id(), frame.dlc(), frame.data()),
            Ok(frame)
        );
    }
}
