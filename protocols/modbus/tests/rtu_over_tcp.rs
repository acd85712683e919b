// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! RTU frames over real TCP connections against `MemoryModel`.

mod common;

use std::time::Duration;

use common::*;
use mcemu_modbus::config::RtuOverTcpConfig;
use mcemu_modbus::frame::rtu;
use mcemu_modbus::memory::Table;
use serde_json::{json, Map, Value};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio::time::Instant;

async fn connect(addr: std::net::SocketAddr) -> TcpStream {
    let s = TcpStream::connect(addr).await.unwrap();
    s.set_nodelay(true).unwrap();
    s
}

async fn recv(s: &mut TcpStream, n: usize) -> Vec<u8> {
    let mut out = vec![0u8; n];
    tokio::time::timeout(MUST_HAPPEN, s.read_exact(&mut out))
        .await
        .expect("no reply")
        .unwrap();
    out
}

async fn transact(s: &mut TcpStream, request: &[u8], n: usize) -> Vec<u8> {
    s.write_all(request).await.unwrap();
    recv(s, n).await
}

fn object(v: Value) -> Map<String, Value> {
    match v {
        Value::Object(m) => m,
        _ => panic!("not an object"),
    }
}

#[tokio::test]
async fn frames_are_delimited_by_length_and_answered_with_crc() {
    let server = start_rtu_over_tcp(
        model_100_to_199().with_units([1, 2]),
        RtuOverTcpConfig::default(),
    )
    .await;
    let mut s = connect(server.addr).await;
    assert_eq!(
        transact(&mut s, &rtu_frame(1, &[3, 0, 100, 0, 1]), 7).await,
        [0x01, 0x03, 0x02, 0x00, 0x00, 0xB8, 0x44]
    );
    // Three requests in one write, one split over two writes: all answered in order.
    let burst = [
        rtu_frame(1, &[16, 0, 100, 0, 2, 4, 0, 7, 0, 8]),
        rtu_frame(2, &[3, 0, 100, 0, 2]),
        rtu_frame(1, &[5, 0, 100, 0xFF, 0]),
    ]
    .concat();
    s.write_all(&burst[..17]).await.unwrap();
    s.flush().await.unwrap();
    s.write_all(&burst[17..]).await.unwrap();
    assert_eq!(
        recv(&mut s, 8 + 9 + 8).await,
        [
            rtu_frame(1, &[16, 0, 100, 0, 2]),
            rtu_frame(2, &[3, 4, 0, 7, 0, 8]),
            rtu_frame(1, &[5, 0, 100, 0xFF, 0]),
        ]
        .concat()
    );
    // An unpredictable function code ends by silence and is answered 01.
    assert_eq!(
        transact(&mut s, &rtu_frame(1, &[0x42, 0, 0, 0]), 5).await,
        rtu_frame(1, &[0xC2, 1])
    );
    server.shutdown().await;
}

#[tokio::test]
async fn bad_crc_other_units_and_broadcasts_get_no_reply() {
    let server = start_rtu_over_tcp(
        model_100_to_199().with_units([1]),
        RtuOverTcpConfig::default(),
    )
    .await;
    let mut s = connect(server.addr).await;
    let counters = || server.state.counters.snapshot();
    let probe = rtu_frame(1, &[3, 0, 140, 0, 1]);

    let mut bad = rtu_frame(1, &[6, 0, 140, 0, 9]);
    bad[2] ^= 0x10;
    // A bad CRC leaves the stream's framing in doubt: what came with it (in the same write,
    // so in the same read on loopback) is dropped too.
    s.write_all(&[bad, rtu_frame(1, &[6, 0, 141, 0, 9])].concat())
        .await
        .unwrap();
    eventually("CRC error", || counters().crc_errors == 1).await;
    assert_eq!(
        transact(&mut s, &probe, 7).await,
        rtu_frame(1, &[3, 2, 0, 0])
    );
    assert_eq!(server.model.register(Table::HoldingRegisters, 141), Some(0));

    // Another unit and a broadcast write: the next bytes back answer the probe.
    s.write_all(&rtu_frame(4, &[6, 0, 140, 0, 9]))
        .await
        .unwrap();
    s.write_all(&rtu_frame(0, &[6, 0, 140, 0, 5]))
        .await
        .unwrap();
    assert_eq!(
        transact(&mut s, &probe, 7).await,
        rtu_frame(1, &[3, 2, 0, 5])
    );
    let c = counters();
    assert_eq!((c.other_unit_ignored, c.broadcasts, c.replies), (1, 1, 2));
    assert_eq!(server.model.register(Table::HoldingRegisters, 140), Some(5));
    server.shutdown().await;
}

#[tokio::test]
async fn rtu_faults_damage_replies_on_tcp_too() {
    let server = start_rtu_over_tcp(model_100_to_199(), RtuOverTcpConfig::default()).await;
    let mut s = connect(server.addr).await;
    let read = rtu_frame(1, &[3, 0, 100, 0, 1]);
    let reply = rtu_frame(1, &[3, 2, 0, 0]);
    server
        .state
        .inject(&object(
            json!({"fault": "corrupt", "byte": 0, "bit": 7, "count": 1}),
        ))
        .unwrap();
    let got = transact(&mut s, &read, 7).await;
    assert_eq!(got[0], 0x81, "bit 7 of the address byte");
    assert_eq!(got[1..], reply[1..]);
    assert_eq!(rtu::decode(&got), rtu::Decoded::BadCrc);
    server
        .state
        .inject(&object(
            json!({"fault": "drop_bytes", "bytes": 3, "count": 1}),
        ))
        .unwrap();
    s.write_all(&read).await.unwrap();
    s.write_all(&read).await.unwrap();
    let got = recv(&mut s, 4 + 7).await;
    assert_eq!(got[..4], reply[..4]);
    assert_eq!(got[4..], reply[..]);
    server.shutdown().await;
}

#[tokio::test]
async fn a_close_fault_closes_the_connection_instead_of_answering() {
    let server = start_rtu_over_tcp(model_100_to_199(), RtuOverTcpConfig::default()).await;
    server
        .state
        .inject(&object(json!({"fault": "close", "count": 1})))
        .unwrap();
    let mut s = connect(server.addr).await;
    s.write_all(&rtu_frame(1, &[6, 0, 150, 0x11, 0x11]))
        .await
        .unwrap();
    assert!(closed_by_peer(&mut s).await, "closed, not answered");
    assert_eq!(server.model.register(Table::HoldingRegisters, 150), Some(0));
    let mut again = connect(server.addr).await;
    let read = rtu_frame(1, &[3, 0, 100, 0, 1]);
    assert_eq!(
        transact(&mut again, &read, 7).await,
        rtu_frame(1, &[3, 2, 0, 0])
    );
    assert_eq!(server.state.counters.snapshot().faults_applied.close, 1);
    server.shutdown().await;
}

#[tokio::test]
async fn a_stalled_frame_closes_only_its_connection() {
    let config = RtuOverTcpConfig {
        frame_timeout_ms: 150,
        ..RtuOverTcpConfig::default()
    };
    let server = start_rtu_over_tcp(model_100_to_199(), config).await;
    let mut stalled = connect(server.addr).await;
    let mut good = connect(server.addr).await;
    let started = Instant::now();
    stalled
        .write_all(&rtu_frame(1, &[3, 0, 100, 0, 1])[..5])
        .await
        .unwrap();
    assert_eq!(
        transact(&mut good, &rtu_frame(1, &[3, 0, 100, 0, 1]), 7).await,
        rtu_frame(1, &[3, 2, 0, 0])
    );
    assert!(closed_by_peer(&mut stalled).await);
    assert!(started.elapsed() >= Duration::from_millis(150));
    assert_eq!(
        server.state.counters.snapshot().connections.frame_timeouts,
        1
    );
    assert_eq!(
        transact(&mut good, &rtu_frame(1, &[3, 0, 100, 0, 1]), 7).await,
        rtu_frame(1, &[3, 2, 0, 0])
    );
    server.shutdown().await;
}
