//! SDO server: the three transfer types both ways and every abort path (CiA 301 §7.2.4).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::time::Duration;

use mcemu_canopen::bus::{sample_dictionary, Bus};
use mcemu_canopen::client::{ClientError, SdoClient};
use mcemu_canopen::{CanFrame, Node, NodeConfig, NodeEvent, ParameterGroup, SdoAbort};

const ID: u8 = 3;

fn bus_with(config: NodeConfig) -> Bus {
    let mut bus = Bus::new();
    bus.add(Node::new(config, sample_dictionary()).unwrap());
    bus.start();
    bus
}

fn bus() -> Bus {
    bus_with(NodeConfig {
        node_id: ID,
        ..NodeConfig::default()
    })
}

fn client() -> SdoClient {
    SdoClient::new(ID)
}

/// Send one raw request; the server's single reply.
fn raw(bus: &mut Bus, d: [u8; 8]) -> [u8; 8] {
    let replies = bus.send(CanFrame::new(0x603, &d).unwrap());
    assert_eq!(replies.len(), 1, "{replies:?}");
    assert_eq!(replies[0].id(), 0x583);
    replies[0].data().try_into().unwrap()
}

fn abort_of(reply: [u8; 8]) -> SdoAbort {
    assert_eq!(reply[0], 0x80, "not an abort: {reply:02x?}");
    SdoAbort(u32::from_le_bytes([reply[4], reply[5], reply[6], reply[7]]))
}

fn expect_abort(result: Result<impl std::fmt::Debug, ClientError>, code: SdoAbort) {
    match result {
        Err(ClientError::Abort(a)) => assert_eq!(a, code, "{a} instead of {code}"),
        other => panic!("expected abort {code}, got {other:?}"),
    }
}

fn data(n: usize) -> Vec<u8> {
    (0..n).map(|i| (i * 7 + i / 251) as u8).collect()
}

#[test]
fn expedited_download_and_upload() {
    let mut bus = bus();
    let c = client();
    c.download(&mut bus, 0x2000, 0, &500u32.to_le_bytes())
        .unwrap();
    assert_eq!(c.upload(&mut bus, 0x2000, 0).unwrap(), 500u32.to_le_bytes());
    // Size not indicated (0x22): the object's own size is taken.
    assert_eq!(
        raw(&mut bus, [0x22, 0x01, 0x20, 0, 0xF6, 0xFF, 0xAA, 0xBB])[0],
        0x60
    );
    assert_eq!(
        c.upload(&mut bus, 0x2001, 0).unwrap(),
        (-10i16).to_le_bytes()
    );
    // Upload answer: 0x4B = expedited, size indicated, 2 bytes.
    assert_eq!(
        raw(&mut bus, [0x40, 0x01, 0x20, 0, 0, 0, 0, 0]),
        [0x4B, 0x01, 0x20, 0, 0xF6, 0xFF, 0, 0]
    );
    let events: Vec<_> = bus.node_mut(0).unwrap().drain_events().collect();
    assert!(events.contains(&NodeEvent::ObjectWritten {
        index: 0x2001,
        subindex: 0
    }));
}

#[test]
fn segmented_download_and_upload_of_strings() {
    let mut bus = bus();
    let c = client();
    let text = b"a VISIBLE_STRING longer than one segment";
    c.download(&mut bus, 0x2003, 0, text).unwrap();
    assert_eq!(c.upload(&mut bus, 0x2003, 0).unwrap(), text);
    assert_eq!(
        c.upload(&mut bus, 0x2008, 0).unwrap(),
        b"mcemu sample firmware 1.0"
    );
    // Zero-length value: segmented upload of size 0, one empty last segment.
    c.download(&mut bus, 0x2004, 0, &[]).unwrap();
    assert_eq!(c.upload(&mut bus, 0x2004, 0).unwrap(), Vec::<u8>::new());
    // Exact multiple of 7.
    c.download(&mut bus, 0x2004, 0, &data(14)).unwrap();
    assert_eq!(c.upload(&mut bus, 0x2004, 0).unwrap(), data(14));
}

#[test]
fn block_download_and_upload_with_crc() {
    let mut bus = bus();
    let c = client();
    for n in [0, 1, 6, 7, 8, 127 * 7, 127 * 7 + 1, 1000, 100_000] {
        let d = data(n);
        c.block_download(&mut bus, 0x2004, 0, &d, &[]).unwrap();
        assert_eq!(
            c.upload(&mut bus, 0x2004, 0).unwrap(),
            d,
            "segmented check of {n}"
        );
        assert_eq!(
            c.block_upload(&mut bus, 0x2004, 0, 0).unwrap(),
            d,
            "block upload of {n}"
        );
    }
    // Small block sizes on both sides.
    let mut small = bus_with(NodeConfig {
        node_id: ID,
        sdo_block_size: 3,
        ..NodeConfig::default()
    });
    let c3 = SdoClient {
        node_id: ID,
        block_size: 2,
    };
    c3.block_download(&mut small, 0x2004, 0, &data(50), &[])
        .unwrap();
    assert_eq!(c3.block_upload(&mut small, 0x2004, 0, 0).unwrap(), data(50));
}

#[test]
fn block_upload_switches_to_a_normal_upload_below_the_threshold() {
    let mut bus = bus();
    let c = client();
    c.download(&mut bus, 0x2004, 0, &data(20)).unwrap();
    // pst 21 ≥ 20 bytes: the server answers as an initiate upload (0x41, segmented).
    assert_eq!(raw(&mut bus, [0xA4, 0x04, 0x20, 0, 127, 21, 0, 0])[0], 0x41);
    assert!(bus
        .send(CanFrame::new(0x603, &[0x80, 0x04, 0x20, 0, 0, 0, 0, 0x08]).unwrap())
        .is_empty());
    assert_eq!(c.block_upload(&mut bus, 0x2004, 0, 21).unwrap(), data(20));
    assert_eq!(
        c.block_upload(&mut bus, 0x2000, 0, 4).unwrap(),
        vec![0, 0, 0, 0]
    );
}

#[test]
fn block_download_repeats_from_the_last_good_segment() {
    let mut bus = bus();
    let c = client();
    let d = data(2000);
    // Segments 5 and 9 of the first sub-block are lost once; the server acknowledges 4 and the
    // client repeats from 5.
    c.block_download(&mut bus, 0x2004, 0, &d, &[5, 9]).unwrap();
    assert_eq!(c.upload(&mut bus, 0x2004, 0).unwrap(), d);
    // Losing the last segment of the transfer.
    let short = data(20);
    c.block_download(&mut bus, 0x2004, 0, &short, &[3]).unwrap();
    assert_eq!(c.upload(&mut bus, 0x2004, 0).unwrap(), short);
}

#[test]
fn block_upload_repeats_after_a_partial_acknowledgement() {
    let mut bus = bus();
    let c = client();
    c.download(&mut bus, 0x2004, 0, &data(40)).unwrap();
    raw(&mut bus, [0xA4, 0x04, 0x20, 0, 10, 0, 0, 0]);
    let segs = bus.send(CanFrame::new(0x603, &[0xA3, 0, 0, 0, 0, 0, 0, 0]).unwrap());
    assert_eq!(segs.len(), 6);
    assert_eq!(segs[5].data()[0], 0x86);
    // Only 2 segments arrived: the server repeats from the third.
    let again = bus.send(CanFrame::new(0x603, &[0xA2, 2, 10, 0, 0, 0, 0, 0]).unwrap());
    assert_eq!(again.len(), 4);
    assert_eq!(again[0].data()[1..], data(40)[14..21]);
    let end = raw(&mut bus, [0xA2, 4, 10, 0, 0, 0, 0, 0]);
    // 40 bytes = 5×7 + 5: two unused bytes in the last segment.
    assert_eq!(end[0], 0xC1 | (2 << 2));
    let crc = mcemu_canopen::sdo::crc::crc16(&data(40)).to_le_bytes();
    assert_eq!(end[1..3], crc);
    assert!(bus
        .send(CanFrame::new(0x603, &[0xA1, 0, 0, 0, 0, 0, 0, 0]).unwrap())
        .is_empty());
}

// ---- abort paths ----

#[test]
fn toggle_errors_abort_0x05030000() {
    let mut bus = bus();
    raw(&mut bus, [0x21, 0x03, 0x20, 0, 20, 0, 0, 0]);
    assert_eq!(
        abort_of(raw(
            &mut bus,
            [0x10, b'a', b'b', b'c', b'd', b'e', b'f', b'g']
        )),
        SdoAbort::TOGGLE
    );
    assert_eq!(raw(&mut bus, [0x40, 0x08, 0x20, 0, 0, 0, 0, 0])[0], 0x41);
    assert_eq!(raw(&mut bus, [0x60, 0, 0, 0, 0, 0, 0, 0])[0] & 0x10, 0);
    let a = raw(&mut bus, [0x60, 0, 0, 0, 0, 0, 0, 0]);
    assert_eq!(abort_of(a), SdoAbort::TOGGLE);
    assert_eq!(a[1..4], [0x08, 0x20, 0]);
}

#[test]
fn silence_during_a_transfer_aborts_0x05040000() {
    let mut bus = bus_with(NodeConfig {
        node_id: ID,
        sdo_timeout: Duration::from_millis(500),
        ..NodeConfig::default()
    });
    raw(&mut bus, [0x21, 0x03, 0x20, 0, 20, 0, 0, 0]);
    assert!(bus
        .advance(Duration::from_millis(499), Duration::from_millis(1))
        .is_empty());
    let sent = bus.advance(Duration::from_millis(501), Duration::from_millis(1));
    assert_eq!(sent.len(), 1);
    let d: [u8; 8] = sent[0].data().try_into().unwrap();
    assert_eq!(abort_of(d), SdoAbort::TIMEOUT);
    assert_eq!(d[1..4], [0x03, 0x20, 0]);
    // Block download stalled mid sub-block.
    raw(&mut bus, [0xC6, 0x04, 0x20, 0, 100, 0, 0, 0]);
    bus.send(CanFrame::new(0x603, &[1, 0, 0, 0, 0, 0, 0, 0]).unwrap());
    let sent = bus.advance(Duration::from_secs(2), Duration::from_millis(10));
    // First the sub-block is acknowledged up to segment 1 (timeout / 10), then, with no
    // answer from the client, the transfer is aborted.
    assert_eq!(sent[0].data()[..3], [0xA2, 1, 127]);
    assert_eq!(
        abort_of(sent[1].data().try_into().unwrap()),
        SdoAbort::TIMEOUT
    );
    assert_eq!(bus.node(0).unwrap().counters().sdo.timeouts, 2);
}

#[test]
fn unknown_or_unexpected_command_specifiers_abort_0x05040001() {
    let mut bus = bus();
    // ccs 7 does not exist; a segment without a transfer; a block end without a block.
    for d in [
        [0xE0, 0x00, 0x20, 0, 0, 0, 0, 0],
        [0x00, 1, 2, 3, 4, 5, 6, 7],
        [0x60, 0, 0, 0, 0, 0, 0, 0],
        [0xC1, 0, 0, 0, 0, 0, 0, 0],
        [0xA3, 0, 0, 0, 0, 0, 0, 0],
    ] {
        assert_eq!(abort_of(raw(&mut bus, d)), SdoAbort::COMMAND, "{d:02x?}");
    }
    // Block end before the last segment arrived.
    raw(&mut bus, [0xC6, 0x04, 0x20, 0, 20, 0, 0, 0]);
    bus.send(CanFrame::new(0x603, &[1, 0, 0, 0, 0, 0, 0, 0]).unwrap());
    bus.send(CanFrame::new(0x603, &[2, 0, 0, 0, 0, 0, 0, 0]).unwrap());
    // Anything in a sub-block is a segment; seq 3 is the last one (c bit).
    let ack = raw(&mut bus, [0x83, 0, 0, 0, 0, 0, 0, 0]);
    assert_eq!(ack[..3], [0xA2, 3, 127]);
    assert_eq!(
        abort_of(raw(&mut bus, [0xA1, 0, 0, 0, 0, 0, 0, 0])),
        SdoAbort::COMMAND
    );
}

#[test]
fn invalid_block_size_aborts_0x05040002() {
    let mut bus = bus();
    for blksize in [0u8, 128, 255] {
        assert_eq!(
            abort_of(raw(&mut bus, [0xA4, 0x08, 0x20, 0, blksize, 0, 0, 0])),
            SdoAbort::BLOCK_SIZE
        );
    }
    // A new block size of 0 in an acknowledgement.
    client().download(&mut bus, 0x2004, 0, &data(30)).unwrap();
    raw(&mut bus, [0xA4, 0x04, 0x20, 0, 127, 0, 0, 0]);
    bus.send(CanFrame::new(0x603, &[0xA3, 0, 0, 0, 0, 0, 0, 0]).unwrap());
    assert_eq!(
        abort_of(raw(&mut bus, [0xA2, 5, 0, 0, 0, 0, 0, 0])),
        SdoAbort::BLOCK_SIZE
    );
}

#[test]
fn invalid_sequence_numbers_abort_0x05040003() {
    let mut bus = bus_with(NodeConfig {
        node_id: ID,
        sdo_block_size: 10,
        ..NodeConfig::default()
    });
    raw(&mut bus, [0xC6, 0x04, 0x20, 0, 100, 0, 0, 0]);
    assert_eq!(
        abort_of(raw(&mut bus, [11, 0, 0, 0, 0, 0, 0, 0])),
        SdoAbort::SEQUENCE
    );
    raw(&mut bus, [0xC6, 0x04, 0x20, 0, 100, 0, 0, 0]);
    assert_eq!(
        abort_of(raw(&mut bus, [0x00, 0, 0, 0, 0, 0, 0, 0])),
        SdoAbort::SEQUENCE
    );
    // Block upload: acknowledging more segments than were sent.
    client().download(&mut bus, 0x2004, 0, &data(30)).unwrap();
    raw(&mut bus, [0xA4, 0x04, 0x20, 0, 127, 0, 0, 0]);
    assert_eq!(
        bus.send(CanFrame::new(0x603, &[0xA3, 0, 0, 0, 0, 0, 0, 0]).unwrap())
            .len(),
        5
    );
    assert_eq!(
        abort_of(raw(&mut bus, [0xA2, 6, 127, 0, 0, 0, 0, 0])),
        SdoAbort::SEQUENCE
    );
}

#[test]
fn block_crc_error_aborts_0x05040004_and_stores_nothing() {
    let mut bus = bus();
    let c = client();
    let d = data(300);
    let wrong = mcemu_canopen::sdo::crc::crc16(&d) ^ 0x0100;
    expect_abort(
        c.block_download_with(&mut bus, 0x2004, 0, &d, &[], Some(wrong)),
        SdoAbort::CRC,
    );
    assert_eq!(c.upload(&mut bus, 0x2004, 0).unwrap(), Vec::<u8>::new());
}

#[test]
fn oversized_transfers_abort_0x05040005() {
    let mut bus = bus_with(NodeConfig {
        node_id: ID,
        sdo_max_len: 100,
        ..NodeConfig::default()
    });
    assert_eq!(
        abort_of(raw(&mut bus, [0x21, 0x04, 0x20, 0, 101, 0, 0, 0])),
        SdoAbort::OUT_OF_MEMORY
    );
    assert_eq!(
        abort_of(raw(&mut bus, [0xC6, 0x04, 0x20, 0, 101, 0, 0, 0])),
        SdoAbort::OUT_OF_MEMORY
    );
    client()
        .block_download(&mut bus, 0x2004, 0, &data(100), &[])
        .unwrap();
    // Size not indicated: refused when the data pass the limit.
    raw(&mut bus, [0x20, 0x04, 0x20, 0, 0, 0, 0, 0]);
    let mut toggle = 0;
    let mut last = [0; 8];
    for _ in 0..15 {
        last = raw(&mut bus, [toggle, 1, 2, 3, 4, 5, 6, 7]);
        if last[0] == 0x80 {
            break;
        }
        toggle ^= 0x10;
    }
    assert_eq!(abort_of(last), SdoAbort::OUT_OF_MEMORY);
}

#[test]
fn object_access_aborts_from_the_dictionary() {
    let mut bus = bus();
    let c = client();
    let four = 1u32.to_le_bytes();
    expect_abort(c.upload(&mut bus, 0x2002, 0), SdoAbort::WRITE_ONLY);
    expect_abort(
        c.download(&mut bus, 0x2005, 0, &[1, 0]),
        SdoAbort::READ_ONLY,
    );
    expect_abort(c.download(&mut bus, 0x1000, 0, &four), SdoAbort::READ_ONLY);
    expect_abort(c.upload(&mut bus, 0x3000, 0), SdoAbort::NO_OBJECT);
    expect_abort(c.download(&mut bus, 0x3000, 0, &four), SdoAbort::NO_OBJECT);
    expect_abort(c.upload(&mut bus, 0x200B, 5), SdoAbort::NO_SUBINDEX);
    expect_abort(
        c.download(&mut bus, 0x2001, 0, &four),
        SdoAbort::LENGTH_HIGH,
    );
    expect_abort(c.download(&mut bus, 0x2000, 0, &[1]), SdoAbort::LENGTH_LOW);
    expect_abort(
        c.download(&mut bus, 0x2000, 0, &2000u32.to_le_bytes()),
        SdoAbort::VALUE_HIGH,
    );
    expect_abort(
        c.download(&mut bus, 0x2001, 0, &(-200i16).to_le_bytes()),
        SdoAbort::VALUE_LOW,
    );
    // A segmented download to a fixed-size object with the wrong indicated size.
    expect_abort(
        c.download(&mut bus, 0x200A, 0, &[0; 9]),
        SdoAbort::LENGTH_HIGH,
    );
    // A VISIBLE_STRING must be printable.
    expect_abort(
        c.download(&mut bus, 0x2003, 0, &[0x41, 0x01, 0x42, 0x43, 0x44]),
        SdoAbort::INVALID_VALUE,
    );
}

#[test]
fn segmented_length_mismatch_aborts_0x06070010() {
    let mut bus = bus();
    // 20 bytes announced, the last segment comes after 14.
    raw(&mut bus, [0x21, 0x03, 0x20, 0, 20, 0, 0, 0]);
    raw(&mut bus, [0x00, b'a', b'b', b'c', b'd', b'e', b'f', b'g']);
    assert_eq!(
        abort_of(raw(
            &mut bus,
            [0x11, b'a', b'b', b'c', b'd', b'e', b'f', b'g']
        )),
        SdoAbort::LENGTH
    );
    // More than announced.
    raw(&mut bus, [0x21, 0x03, 0x20, 0, 3, 0, 0, 0]);
    assert_eq!(
        abort_of(raw(
            &mut bus,
            [0x01, b'a', b'b', b'c', b'd', b'e', b'f', b'g']
        )),
        SdoAbort::LENGTH
    );
    // Block download whose data do not match the indicated size.
    raw(&mut bus, [0xC6, 0x04, 0x20, 0, 10, 0, 0, 0]);
    raw(&mut bus, [0x81, 1, 2, 3, 4, 5, 6, 7]);
    let crc = mcemu_canopen::sdo::crc::crc16(&[1, 2, 3, 4, 5, 6, 7]).to_le_bytes();
    assert_eq!(
        abort_of(raw(&mut bus, [0xC1, crc[0], crc[1], 0, 0, 0, 0, 0])),
        SdoAbort::LENGTH
    );
}

#[test]
fn communication_object_rules() {
    let mut bus = bus();
    let c = client();
    // 0x1003: only 0 may be written to sub-index 0; the entries are read-only.
    expect_abort(
        c.download(&mut bus, 0x1003, 0, &[3]),
        SdoAbort::INVALID_VALUE,
    );
    expect_abort(
        c.download(&mut bus, 0x1003, 1, &[0; 4]),
        SdoAbort::READ_ONLY,
    );
    c.download(&mut bus, 0x1003, 0, &[0]).unwrap();
    // 0x1019: 1 and above 240 are invalid; any change needs 0x1006 = 0.
    expect_abort(
        c.download(&mut bus, 0x1019, 0, &[1]),
        SdoAbort::INVALID_VALUE,
    );
    expect_abort(
        c.download(&mut bus, 0x1019, 0, &[241]),
        SdoAbort::INVALID_VALUE,
    );
    c.download(&mut bus, 0x1006, 0, &1000u32.to_le_bytes())
        .unwrap();
    expect_abort(
        c.download(&mut bus, 0x1019, 0, &[10]),
        SdoAbort::DEVICE_STATE,
    );
    c.download(&mut bus, 0x1006, 0, &0u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1019, 0, &[10]).unwrap();
    // 0x1005: the node does not produce SYNC, nor use extended ids; restricted ids refused.
    expect_abort(
        c.download(&mut bus, 0x1005, 0, &0x4000_0080u32.to_le_bytes()),
        SdoAbort::INVALID_VALUE,
    );
    expect_abort(
        c.download(&mut bus, 0x1005, 0, &0x0000_0701u32.to_le_bytes()),
        SdoAbort::INVALID_VALUE,
    );
    c.download(&mut bus, 0x1005, 0, &0x0000_0081u32.to_le_bytes())
        .unwrap();
    // 0x1014: the CAN-ID changes only while invalid.
    expect_abort(
        c.download(&mut bus, 0x1014, 0, &0x0000_0090u32.to_le_bytes()),
        SdoAbort::INVALID_VALUE,
    );
    c.download(&mut bus, 0x1014, 0, &0x8000_0083u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1014, 0, &0x0000_0090u32.to_le_bytes())
        .unwrap();
    // 0x1016: two entries for one node are incompatible.
    c.download(&mut bus, 0x1016, 1, &0x0001_0064u32.to_le_bytes())
        .unwrap();
    expect_abort(
        c.download(&mut bus, 0x1016, 2, &0x0001_00C8u32.to_le_bytes()),
        SdoAbort::PARAMETER_INCOMPATIBLE,
    );
    c.download(&mut bus, 0x1016, 2, &0x0002_00C8u32.to_le_bytes())
        .unwrap();
    // 0x1029:01 takes 0–2.
    expect_abort(
        c.download(&mut bus, 0x1029, 1, &[3]),
        SdoAbort::INVALID_VALUE,
    );
    // 0x1200 is read-only.
    expect_abort(
        c.download(&mut bus, 0x1200, 1, &0x604u32.to_le_bytes()),
        SdoAbort::READ_ONLY,
    );
    assert_eq!(
        c.upload(&mut bus, 0x1200, 2).unwrap(),
        0x583u32.to_le_bytes()
    );
}

#[test]
fn pdo_mapping_procedure_aborts() {
    let mut bus = bus();
    let c = client();
    let w = |v: u32| v.to_le_bytes();
    // Mapping while the PDO is valid: 0x06010000.
    expect_abort(
        c.download(&mut bus, 0x1A00, 0, &[0]),
        SdoAbort::UNSUPPORTED_ACCESS,
    );
    // Changing the CAN-ID of a valid PDO: 0x06090030.
    expect_abort(
        c.download(&mut bus, 0x1800, 1, &w(0x190)),
        SdoAbort::INVALID_VALUE,
    );
    c.download(&mut bus, 0x1800, 1, &w(0x8000_0183)).unwrap();
    // Entries need sub-index 0 = 0 first.
    c.download(&mut bus, 0x1A00, 0, &[0]).unwrap();
    expect_abort(
        c.download(&mut bus, 0x1A00, 1, &w(0x2000_0020)),
        SdoAbort::NOT_MAPPABLE,
    );
    expect_abort(
        c.download(&mut bus, 0x1A00, 1, &w(0x2006_0010)),
        SdoAbort::NOT_MAPPABLE,
    );
    expect_abort(
        c.download(&mut bus, 0x1A00, 1, &w(0x3000_0010)),
        SdoAbort::NO_OBJECT,
    );
    expect_abort(
        c.download(&mut bus, 0x1A00, 1, &w(0x2005_0009)),
        SdoAbort::NOT_MAPPABLE,
    );
    // An RPDO-only object cannot go into a TPDO; dummy entries only into RPDOs.
    expect_abort(
        c.download(&mut bus, 0x1A00, 1, &w(0x2006_0020)),
        SdoAbort::NOT_MAPPABLE,
    );
    expect_abort(
        c.download(&mut bus, 0x1A00, 1, &w(0x0005_0008)),
        SdoAbort::NOT_MAPPABLE,
    );
    c.download(&mut bus, 0x1A00, 1, &w(0x200A_0040)).unwrap();
    c.download(&mut bus, 0x1A00, 2, &w(0x2005_0010)).unwrap();
    // 64 + 16 bits: 0x06040042.
    expect_abort(c.download(&mut bus, 0x1A00, 0, &[2]), SdoAbort::PDO_LENGTH);
    // More entries than the record has: 0x06090031.
    expect_abort(c.download(&mut bus, 0x1A00, 0, &[9]), SdoAbort::VALUE_HIGH);
    c.download(&mut bus, 0x1A00, 0, &[1]).unwrap();
    expect_abort(
        c.download(&mut bus, 0x1A00, 2, &w(0x2005_0010)),
        SdoAbort::UNSUPPORTED_ACCESS,
    );
    // Restricted CAN-ID; transmission types 241–251 are reserved.
    expect_abort(
        c.download(&mut bus, 0x1800, 1, &w(0x0000_0601)),
        SdoAbort::INVALID_VALUE,
    );
    expect_abort(
        c.download(&mut bus, 0x1800, 2, &[245]),
        SdoAbort::INVALID_VALUE,
    );
    expect_abort(
        c.download(&mut bus, 0x1400, 2, &[252]),
        SdoAbort::INVALID_VALUE,
    );
    c.download(&mut bus, 0x1800, 1, &w(0x0000_0183)).unwrap();
    // Inhibit time of a valid PDO: 0x06090030.
    expect_abort(
        c.download(&mut bus, 0x1800, 3, &10u16.to_le_bytes()),
        SdoAbort::INVALID_VALUE,
    );
    // Validating a PDO whose mapping is broken: 0x06040043 (mapping 0x1A01 made invalid
    // through device access to simulate a stale mapping).
    c.download(&mut bus, 0x1801, 1, &w(0x8000_0283)).unwrap();
    let od = bus.node_mut(0).unwrap().device_mut();
    od.set(0x1A01, 1, axes::od::Value::U32(0x2000_0020))
        .unwrap();
    od.set(0x1A01, 0, axes::od::Value::U8(1)).unwrap();
    expect_abort(
        c.download(&mut bus, 0x1801, 1, &w(0x0000_0283)),
        SdoAbort::PARAMETER_INCOMPATIBLE,
    );
}

#[test]
fn pdo_configuration_in_operational_can_be_refused_0x08000022() {
    let mut bus = bus_with(NodeConfig {
        node_id: ID,
        pdo_config_in_operational: false,
        ..NodeConfig::default()
    });
    mcemu_canopen::client::nmt(&mut bus, mcemu_canopen::NmtCommand::Start, ID);
    expect_abort(
        client().download(&mut bus, 0x1800, 1, &0x8000_0183u32.to_le_bytes()),
        SdoAbort::DEVICE_STATE,
    );
}

#[test]
fn store_restore_signatures_local_control_and_hardware_errors() {
    let mut bus = bus();
    let c = client();
    expect_abort(
        c.download(&mut bus, 0x1010, 1, b"SAVE"),
        SdoAbort::CANNOT_STORE,
    );
    expect_abort(
        c.download(&mut bus, 0x1011, 1, b"save"),
        SdoAbort::CANNOT_STORE,
    );
    // The transport fails to write: 0x06060000.
    assert!(bus
        .send(CanFrame::new(0x603, &[0x23, 0x10, 0x10, 1, b's', b'a', b'v', b'e']).unwrap())
        .is_empty());
    let events: Vec<_> = bus.node_mut(0).unwrap().drain_events().collect();
    assert!(matches!(
        events.last(),
        Some(NodeEvent::StoreRequested {
            group: ParameterGroup::All,
            ..
        })
    ));
    let now = bus.now();
    let sent = bus.node_mut(0).unwrap().finish_persist(false, now);
    assert_eq!(
        abort_of(sent[0].data().try_into().unwrap()),
        SdoAbort::HARDWARE
    );
    bus.node_mut(0).unwrap().set_local_control(true);
    expect_abort(
        c.download(&mut bus, 0x2000, 0, &[1, 0, 0, 0]),
        SdoAbort::LOCAL_CONTROL,
    );
    assert_eq!(c.upload(&mut bus, 0x2000, 0).unwrap(), [0; 4]);
}

#[test]
fn abort_from_the_client_ends_the_transfer_silently() {
    let mut bus = bus();
    raw(&mut bus, [0x21, 0x03, 0x20, 0, 20, 0, 0, 0]);
    assert!(bus
        .send(CanFrame::new(0x603, &[0x80, 0x03, 0x20, 0, 0, 0, 4, 5]).unwrap())
        .is_empty());
    assert_eq!(
        abort_of(raw(&mut bus, [0x00, 1, 2, 3, 4, 5, 6, 7])),
        SdoAbort::COMMAND
    );
    assert_eq!(bus.node(0).unwrap().counters().sdo.aborts_received, 1);
    // Short SDO frames are not CiA 301 SDO frames: ignored.
    assert!(bus
        .send(CanFrame::new(0x603, &[0x40, 0x00, 0x10, 0]).unwrap())
        .is_empty());
}

#[test]
fn a_new_initiate_replaces_a_transfer_in_progress() {
    let mut bus = bus();
    raw(&mut bus, [0x21, 0x03, 0x20, 0, 20, 0, 0, 0]);
    assert_eq!(client().upload(&mut bus, 0x1018, 0).unwrap(), [4]);
}
