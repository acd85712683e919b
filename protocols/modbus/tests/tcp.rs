// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! Modbus TCP over real sockets against `MemoryModel`, asserting exact reply bytes.

mod common;

use std::collections::BTreeMap;
use std::time::Duration;

use common::*;
use mcemu_frontend::bound::AtLimit;
use mcemu_modbus::config::TcpConfig;
use mcemu_modbus::memory::{MemoryModel, Table};
use mcemu_modbus::model::{DataModel, DeviceIdentity, ExecError, RequestContext};
use mcemu_modbus::pdu::{Exception, Request, Response};
use serde_json::{json, Map, Value};
use tokio::io::AsyncWriteExt;
use tokio::net::TcpStream;
use tokio::time::Instant;

async fn connect(addr: std::net::SocketAddr) -> TcpStream {
    let s = TcpStream::connect(addr).await.unwrap();
    s.set_nodelay(true).unwrap();
    s
}

/// Send `pdu` and expect exception `code` for its function, in an exact MBAP frame.
async fn expect_exception(s: &mut TcpStream, tid: u16, pdu: &[u8], code: u8) {
    let reply = transact(s, tid, 1, pdu).await;
    assert_eq!(
        reply,
        mbap(tid, 1, &[pdu[0] | 0x80, code]),
        "request {pdu:02X?}"
    );
}

#[tokio::test]
async fn every_function_refuses_bad_quantities_addresses_and_values() {
    let server = start_tcp(model_100_to_199(), TcpConfig::default()).await;
    let mut s = connect(server.addr).await;
    let mut tid = 0u16;
    let mut next = || {
        tid += 1;
        tid
    };

    // Unknown function code → 01.
    expect_exception(&mut s, next(), &[0x42, 0, 0], 1).await;

    // Quantity 0 and max+1 → 03 (libmodbus's limits: 2001, 126, 1969, 124, FC 23 126/122).
    let mut fc15_1969 = vec![15, 0, 100, 0x07, 0xB1, 247];
    fc15_1969.extend_from_slice(&[0; 247]);
    let quantity_cases: Vec<Vec<u8>> = vec![
        vec![1, 0, 100, 0, 0],
        vec![1, 0, 100, 0x07, 0xD1],
        vec![2, 0, 100, 0, 0],
        vec![2, 0, 100, 0x07, 0xD1],
        vec![3, 0, 100, 0, 0],
        vec![3, 0, 100, 0, 126],
        vec![4, 0, 100, 0, 0],
        vec![4, 0, 100, 0, 126],
        vec![15, 0, 100, 0, 0, 0],
        fc15_1969,
        vec![16, 0, 100, 0, 0, 0],
        // 124 registers do not fit a PDU: the quantity alone is refused.
        vec![16, 0, 100, 0, 124, 0],
        vec![23, 0, 100, 0, 0, 0, 100, 0, 1, 2, 0, 0],
        vec![23, 0, 100, 0, 126, 0, 100, 0, 1, 2, 0, 0],
        vec![23, 0, 100, 0, 1, 0, 100, 0, 0, 0],
        vec![23, 0, 100, 0, 1, 0, 100, 0, 122, 244],
    ];
    for pdu in &quantity_cases {
        expect_exception(&mut s, next(), pdu, 3).await;
    }
    // FC 5 takes only FF00 and 0000.
    expect_exception(&mut s, next(), &[5, 0, 100, 0x12, 0x34], 3).await;

    // Address start−1 (99), end+1 (200) and a range running past the end → 02.
    let mut address_cases: Vec<Vec<u8>> = vec![];
    for fc in [1u8, 2, 3, 4] {
        address_cases.push(vec![fc, 0, 99, 0, 1]);
        address_cases.push(vec![fc, 0, 200, 0, 1]);
        address_cases.push(vec![fc, 0, 199, 0, 2]);
    }
    for a in [99u8, 200] {
        address_cases.push(vec![5, 0, a, 0xFF, 0]);
        address_cases.push(vec![6, 0, a, 0, 1]);
        address_cases.push(vec![15, 0, a, 0, 1, 1, 1]);
        address_cases.push(vec![16, 0, a, 0, 1, 2, 0, 1]);
        address_cases.push(vec![22, 0, a, 0xFF, 0xFF, 0, 0]);
        // FC 23, the read range and the write range in turn.
        address_cases.push(vec![23, 0, a, 0, 1, 0, 100, 0, 1, 2, 0, 1]);
        address_cases.push(vec![23, 0, 100, 0, 1, 0, a, 0, 1, 2, 0, 1]);
    }
    for pdu in &address_cases {
        expect_exception(&mut s, next(), pdu, 2).await;
    }
    // The refused FC 23 wrote nothing; the edges themselves are in range.
    assert_eq!(server.model.register(Table::HoldingRegisters, 100), Some(0));
    for (t, pdu) in [[3u8, 0, 100, 0, 100], [1, 0, 199, 0, 1]]
        .iter()
        .enumerate()
    {
        let reply = transact(&mut s, 900 + t as u16, 1, pdu).await;
        assert_eq!(pdu_of(&reply)[0], pdu[0], "{pdu:02X?} answered normally");
    }

    let c = server.state.counters.snapshot();
    assert_eq!(
        c.exceptions_by_code,
        BTreeMap::from([
            (1, 1),
            (2, address_cases.len() as u64),
            (3, quantity_cases.len() as u64 + 1)
        ])
    );
    assert_eq!(
        c.replies,
        2 + 1 + address_cases.len() as u64 + quantity_cases.len() as u64 + 1
    );
    server.shutdown().await;
}

#[tokio::test]
async fn reads_and_writes_answer_exact_frames_echoing_transaction_and_unit() {
    let server = start_tcp(model_100_to_199(), TcpConfig::default()).await;
    server
        .model
        .set_register(Table::InputRegisters, 100, 0x0102);
    server.model.set_bit(Table::DiscreteInputs, 100, true);
    let mut s = connect(server.addr).await;
    // (request PDU, reply PDU), each on unit 0x11 with its own transaction id.
    let cases: Vec<(Vec<u8>, Vec<u8>)> = vec![
        (vec![6, 0, 100, 0x12, 0x34], vec![6, 0, 100, 0x12, 0x34]),
        (
            vec![16, 0, 101, 0, 2, 4, 0, 1, 0, 2],
            vec![16, 0, 101, 0, 2],
        ),
        (vec![3, 0, 100, 0, 3], vec![3, 6, 0x12, 0x34, 0, 1, 0, 2]),
        (vec![5, 0, 100, 0xFF, 0], vec![5, 0, 100, 0xFF, 0]),
        // Specification §6.11 example bits CD 01 at 101..110, with coil 100 already on.
        (
            vec![15, 0, 101, 0, 10, 2, 0xCD, 0x01],
            vec![15, 0, 101, 0, 10],
        ),
        (vec![1, 0, 100, 0, 11], vec![1, 2, 0x9B, 0x03]),
        // (0x1234 AND 0xF2) OR (0x25 AND NOT 0xF2) = 0x35.
        (
            vec![22, 0, 100, 0, 0xF2, 0, 0x25],
            vec![22, 0, 100, 0, 0xF2, 0, 0x25],
        ),
        (vec![3, 0, 100, 0, 1], vec![3, 2, 0, 0x35]),
        // FC 23 writes 101 first, then reads 100..101.
        (
            vec![23, 0, 100, 0, 2, 0, 101, 0, 1, 2, 0xAB, 0xCD],
            vec![23, 4, 0, 0x35, 0xAB, 0xCD],
        ),
        (vec![4, 0, 100, 0, 1], vec![4, 2, 1, 2]),
        (vec![2, 0, 100, 0, 1], vec![2, 1, 1]),
        (vec![8, 0, 0, 0xA5, 0x37], vec![8, 0, 0, 0xA5, 0x37]),
        (vec![17], [&[17u8, 6][..], b"mcemu", &[0xFF]].concat()),
    ];
    for (i, (request, reply)) in cases.iter().enumerate() {
        let tid = 0xBE00 + i as u16;
        let got = transact(&mut s, tid, 0x11, request).await;
        assert_eq!(got, mbap(tid, 0x11, reply), "request {request:02X?}");
    }
    // FC 43/14 basic identification (§6.21): conformity 0x82, objects 0–2.
    let version = env!("CARGO_PKG_VERSION").as_bytes();
    let mut expected = vec![0x2B, 0x0E, 1, 0x82, 0, 0, 3, 0, 5];
    expected.extend_from_slice(b"mcemu");
    expected.extend_from_slice(&[1, 11]);
    expected.extend_from_slice(b"MemoryModel");
    expected.extend_from_slice(&[2, version.len() as u8]);
    expected.extend_from_slice(version);
    let got = transact(&mut s, 0xFFFF, 0xFF, &[0x2B, 0x0E, 1, 0]).await;
    assert_eq!(got, mbap(0xFFFF, 0xFF, &expected));
    // TCP answers unit 0 too (it is no broadcast there).
    let got = transact(&mut s, 1, 0, &[3, 0, 100, 0, 1]).await;
    assert_eq!(got, mbap(1, 0, &[3, 2, 0, 0x35]));
    server.shutdown().await;
}

#[tokio::test]
async fn pipelined_and_split_requests_are_answered_in_order() {
    let server = start_tcp(model_100_to_199(), TcpConfig::default()).await;
    for a in 100..103u16 {
        server.model.set_register(Table::HoldingRegisters, a, a * 2);
    }
    let mut s = connect(server.addr).await;
    let mut burst = vec![];
    for (tid, a) in [(7u16, 100u8), (8, 101), (9, 102)] {
        burst.extend(mbap(tid, 1, &[3, 0, a, 0, 1]));
    }
    s.write_all(&burst).await.unwrap();
    for (tid, v) in [(7u16, 200u16), (8, 202), (9, 204)] {
        let [hi, lo] = v.to_be_bytes();
        assert_eq!(read_mbap(&mut s).await, mbap(tid, 1, &[3, 2, hi, lo]));
    }
    // One frame in two writes, the second carrying the start of another.
    let a = mbap(10, 1, &[3, 0, 100, 0, 1]);
    let b = mbap(11, 1, &[3, 0, 101, 0, 1]);
    s.write_all(&a[..5]).await.unwrap();
    s.flush().await.unwrap();
    s.write_all(&[&a[5..], &b[..3]].concat()).await.unwrap();
    s.flush().await.unwrap();
    s.write_all(&b[3..]).await.unwrap();
    assert_eq!(read_mbap(&mut s).await, mbap(10, 1, &[3, 2, 0, 200]));
    assert_eq!(read_mbap(&mut s).await, mbap(11, 1, &[3, 2, 0, 202]));
    server.shutdown().await;
}

#[tokio::test]
async fn foreign_protocol_frames_are_skipped_and_bad_lengths_close() {
    let server = start_tcp(model_100_to_199(), TcpConfig::default()).await;
    let mut s = connect(server.addr).await;
    // Protocol id 1, then a good frame: only the good one is answered.
    let mut foreign = mbap(1, 1, &[3, 0, 100, 0, 1]);
    foreign[3] = 1;
    s.write_all(&[foreign, mbap(2, 1, &[3, 0, 100, 0, 1])].concat())
        .await
        .unwrap();
    assert_eq!(read_mbap(&mut s).await, mbap(2, 1, &[3, 2, 0, 0]));
    assert_eq!(
        server
            .state
            .counters
            .snapshot()
            .malformed_frames
            .not_modbus_protocol,
        1
    );
    // Length 1 (no room for a function code) and 255 (past 260 bytes) close the connection.
    for header in [[0u8, 3, 0, 0, 0, 1, 1], [0, 3, 0, 0, 0, 255, 1]] {
        let mut s = connect(server.addr).await;
        s.write_all(&header).await.unwrap();
        assert!(closed_by_peer(&mut s).await);
    }
    let c = server.state.counters.snapshot();
    assert_eq!(c.malformed_frames.bad_length, 2);
    assert_eq!(c.diagnostics.bus_communication_error_count, 3);
    // The first connection is untouched.
    assert_eq!(
        transact(&mut s, 3, 1, &[3, 0, 100, 0, 1]).await,
        mbap(3, 1, &[3, 2, 0, 0])
    );
    eventually("two connections closed", || {
        server.state.counters.snapshot().connections.closed == 2
    })
    .await;
    server.shutdown().await;
}

#[tokio::test]
async fn a_truncated_frame_times_out_and_an_idle_connection_too() {
    let config = TcpConfig {
        frame_timeout_ms: 150,
        idle_timeout_ms: 250,
        ..TcpConfig::default()
    };
    let server = start_tcp(model_100_to_199(), config).await;

    let mut half = connect(server.addr).await;
    let started = Instant::now();
    // A whole request, then the start of another that never completes.
    let request = mbap(1, 1, &[3, 0, 100, 0, 1]);
    half.write_all(&[&request[..], &request[..8]].concat())
        .await
        .unwrap();
    assert_eq!(read_mbap(&mut half).await, mbap(1, 1, &[3, 2, 0, 0]));
    assert!(closed_by_peer(&mut half).await);
    assert!(started.elapsed() >= Duration::from_millis(150));

    let mut idle = connect(server.addr).await;
    // The idle time runs from the request's arrival, which is after this.
    let sent = Instant::now();
    assert_eq!(
        transact(&mut idle, 1, 1, &[3, 0, 100, 0, 1]).await,
        mbap(1, 1, &[3, 2, 0, 0])
    );
    assert!(closed_by_peer(&mut idle).await);
    assert!(sent.elapsed() >= Duration::from_millis(250));

    let c = server.state.counters.snapshot().connections;
    assert_eq!((c.frame_timeouts, c.idle_timeouts), (1, 1));
    server.shutdown().await;
}

#[tokio::test]
async fn connections_beyond_the_bound_are_closed_at_once() {
    let config = TcpConfig {
        max_connections: 2,
        at_limit: AtLimit::Refuse,
        ..TcpConfig::default()
    };
    let server = start_tcp(model_100_to_199(), config).await;
    let mut a = connect(server.addr).await;
    let mut b = connect(server.addr).await;
    for s in [&mut a, &mut b] {
        assert_eq!(
            transact(s, 1, 1, &[3, 0, 100, 0, 1]).await,
            mbap(1, 1, &[3, 2, 0, 0])
        );
    }
    let mut c = connect(server.addr).await;
    assert!(closed_by_peer(&mut c).await);
    assert_eq!(
        server
            .state
            .counters
            .snapshot()
            .connections
            .refused_at_limit,
        1
    );
    drop(a);
    eventually("a's place freed", || {
        server.state.counters.snapshot().connections.closed == 1
    })
    .await;
    let mut d = connect(server.addr).await;
    assert_eq!(
        transact(&mut d, 2, 1, &[3, 0, 100, 0, 1]).await,
        mbap(2, 1, &[3, 2, 0, 0])
    );
    assert_eq!(
        transact(&mut b, 3, 1, &[3, 0, 100, 0, 1]).await,
        mbap(3, 1, &[3, 2, 0, 0])
    );
    let snapshot = server.state.counters.snapshot().connections;
    assert_eq!((snapshot.open, snapshot.opened), (2, 3));
    server.shutdown().await;
}

#[tokio::test]
async fn at_the_bound_the_connection_idle_longest_is_closed_for_a_new_one() {
    let config = TcpConfig {
        max_connections: 2,
        ..TcpConfig::default()
    };
    let server = start_tcp(model_100_to_199(), config).await;
    let mut a = connect(server.addr).await;
    let mut b = connect(server.addr).await;
    for (tid, s) in [(1, &mut a), (2, &mut b)] {
        assert_eq!(
            transact(s, tid, 1, &[3, 0, 100, 0, 1]).await,
            mbap(tid, 1, &[3, 2, 0, 0])
        );
    }
    // `a` asks again: `b` is now idle longest.
    assert_eq!(
        transact(&mut a, 3, 1, &[3, 0, 100, 0, 1]).await,
        mbap(3, 1, &[3, 2, 0, 0])
    );
    let mut c = connect(server.addr).await;
    assert_eq!(
        transact(&mut c, 4, 1, &[3, 0, 100, 0, 1]).await,
        mbap(4, 1, &[3, 2, 0, 0]),
        "the newcomer is served"
    );
    assert!(closed_by_peer(&mut b).await, "b was idle longest");
    assert_eq!(
        transact(&mut a, 5, 1, &[3, 0, 100, 0, 1]).await,
        mbap(5, 1, &[3, 2, 0, 0])
    );
    let snapshot = server.state.counters.snapshot().connections;
    assert_eq!(
        (
            snapshot.evicted_idle,
            snapshot.refused_at_limit,
            snapshot.opened
        ),
        (1, 0, 3)
    );
    server.shutdown().await;
}

#[tokio::test]
async fn a_delayed_reply_in_flight_is_not_evicted_before_an_idle_connection() {
    let config = TcpConfig {
        max_connections: 2,
        ..TcpConfig::default()
    };
    let server = start_tcp(model_100_to_199(), config).await;
    let mut waiting = connect(server.addr).await;
    let mut idle = connect(server.addr).await;
    server
        .state
        .inject(&object(json!({"fault": "delay", "ms": 1000, "count": 1})))
        .unwrap();
    waiting
        .write_all(&mbap(2, 1, &[3, 0, 100, 0, 1]))
        .await
        .unwrap();
    eventually("the delay is running", || {
        server.state.counters.snapshot().faults_applied.delay == 1
    })
    .await;
    assert_eq!(
        transact(&mut idle, 1, 1, &[3, 0, 100, 0, 1]).await,
        mbap(1, 1, &[3, 2, 0, 0])
    );
    // `waiting` has received nothing for longest, but were it chosen its reply would never
    // come: `idle` goes.
    let mut newcomer = connect(server.addr).await;
    assert_eq!(
        transact(&mut newcomer, 3, 1, &[3, 0, 100, 0, 1]).await,
        mbap(3, 1, &[3, 2, 0, 0])
    );
    assert!(closed_by_peer(&mut idle).await);
    assert_eq!(read_mbap(&mut waiting).await, mbap(2, 1, &[3, 2, 0, 0]));
    server.shutdown().await;
}

#[tokio::test]
async fn a_misbehaving_connection_does_not_disturb_another() {
    let config = TcpConfig {
        frame_timeout_ms: 300,
        ..TcpConfig::default()
    };
    let server = start_tcp(model_100_to_199(), config).await;
    let mut good = connect(server.addr).await;
    let mut stalled = connect(server.addr).await;
    stalled.write_all(&[0, 1, 0, 0, 0, 6, 1, 3]).await.unwrap();
    // While one connection sits on half a frame, the other is served at once, many times.
    for tid in 0..20u16 {
        let v = tid.to_be_bytes();
        assert_eq!(
            transact(&mut good, tid, 1, &[6, 0, 150, v[0], v[1]]).await,
            mbap(tid, 1, &[6, 0, 150, v[0], v[1]])
        );
    }
    let mut garbage = connect(server.addr).await;
    garbage.write_all(&[0xFF; 7]).await.unwrap();
    assert!(closed_by_peer(&mut garbage).await);
    assert!(closed_by_peer(&mut stalled).await);
    assert_eq!(
        transact(&mut good, 99, 1, &[3, 0, 150, 0, 1]).await,
        mbap(99, 1, &[3, 2, 0, 19])
    );
    server.shutdown().await;
}

#[tokio::test]
async fn unserved_units_get_gateway_exception_0b() {
    let server = start_tcp(model_100_to_199().with_units([1]), TcpConfig::default()).await;
    let mut s = connect(server.addr).await;
    for unit in [5u8, 0, 0xFF] {
        assert_eq!(
            transact(&mut s, 4, unit, &[3, 0, 100, 0, 1]).await,
            mbap(4, unit, &[0x83, 0x0B])
        );
    }
    assert_eq!(
        transact(&mut s, 5, 1, &[3, 0, 100, 0, 1]).await,
        mbap(5, 1, &[3, 2, 0, 0])
    );
    server.shutdown().await;
}

/// A model whose engine refuses every write (exception 04) and that reports no identity.
struct Refusing(MemoryModel);

impl DataModel for Refusing {
    fn serves(&self, unit: u8) -> bool {
        self.0.serves(unit)
    }

    fn identity(&self, _unit: u8) -> Option<&DeviceIdentity> {
        None
    }

    async fn execute<'a>(
        &'a self,
        context: &'a RequestContext,
        request: &'a Request<'a>,
    ) -> Result<Response, ExecError> {
        if request.is_write() {
            Err(ExecError::new(
                Exception::ServerDeviceFailure,
                "axis 0 is disabled",
            ))
        } else {
            self.0.execute(context, request).await
        }
    }
}

#[tokio::test]
async fn engine_refusals_are_recorded_as_the_last_error() {
    let server = start_tcp(Refusing(model_100_to_199()), TcpConfig::default()).await;
    let mut s = connect(server.addr).await;
    let local = s.local_addr().unwrap();
    assert!(server.state.last_error().is_none());
    assert_eq!(
        transact(&mut s, 1, 7, &[6, 0, 120, 0, 1]).await,
        mbap(1, 7, &[0x86, 4])
    );
    let e = server.state.last_error().unwrap();
    assert_eq!(
        (
            e.peer,
            e.detail.unit,
            e.detail.function,
            e.detail.exception,
            e.reason.as_str()
        ),
        (local.to_string(), 7, 6, 4, "axis 0 is disabled")
    );
    assert!(e.time_unix_ms > 1_600_000_000_000);
    // No identity: FC 17 and FC 43/14 are not supported.
    assert_eq!(transact(&mut s, 2, 7, &[17]).await, mbap(2, 7, &[0x91, 1]));
    assert_eq!(
        transact(&mut s, 3, 7, &[0x2B, 0x0E, 1, 0]).await,
        mbap(3, 7, &[0xAB, 1])
    );
    let json = serde_json::to_value(server.state.snapshot()).unwrap();
    assert_eq!(json["last_error"]["reason"], "axis 0 is disabled");
    assert_eq!(json["last_error"]["function"], 6);
    server.shutdown().await;
}

fn object(v: Value) -> Map<String, Value> {
    match v {
        Value::Object(m) => m,
        _ => panic!("not an object"),
    }
}

#[tokio::test]
async fn faults_delay_swallow_and_force_exceptions() {
    let server = start_tcp(model_100_to_199(), TcpConfig::default()).await;
    let state = &server.state;
    let mut s = connect(server.addr).await;

    // delay: the reply comes no sooner than asked (a lower bound only).
    state
        .inject(&object(json!({"fault": "delay", "ms": 150, "count": 1})))
        .unwrap();
    let sent = Instant::now();
    assert_eq!(
        transact(&mut s, 1, 1, &[3, 0, 100, 0, 1]).await,
        mbap(1, 1, &[3, 2, 0, 0])
    );
    assert!(sent.elapsed() >= Duration::from_millis(150));

    // no_reply: the first of two pipelined requests vanishes, unexecuted.
    let answer = state
        .inject(&object(json!({"fault": "no_reply", "count": 1})))
        .unwrap();
    assert_eq!(
        answer,
        json!({"active_faults": [{"fault": "no_reply", "count": 1}]})
    );
    s.write_all(
        &[
            mbap(2, 1, &[6, 0, 150, 0x11, 0x11]),
            mbap(3, 1, &[3, 0, 150, 0, 1]),
        ]
        .concat(),
    )
    .await
    .unwrap();
    assert_eq!(read_mbap(&mut s).await, mbap(3, 1, &[3, 2, 0, 0]));
    assert_eq!(server.model.register(Table::HoldingRegisters, 150), Some(0));

    // exception: by function until cleared, by address for a count.
    state
        .inject(&object(
            json!({"fault": "exception", "code": 6, "function": 3}),
        ))
        .unwrap();
    state
        .inject(&object(
            json!({"fault": "exception", "code": 4, "address": 151, "count": 1}),
        ))
        .unwrap();
    assert_eq!(
        transact(&mut s, 4, 1, &[3, 0, 100, 0, 1]).await,
        mbap(4, 1, &[0x83, 6])
    );
    assert_eq!(
        transact(&mut s, 5, 1, &[3, 0, 100, 0, 1]).await,
        mbap(5, 1, &[0x83, 6])
    );
    assert_eq!(
        transact(&mut s, 6, 1, &[4, 0, 100, 0, 1]).await,
        mbap(6, 1, &[4, 2, 0, 0])
    );
    assert_eq!(
        transact(&mut s, 7, 1, &[16, 0, 150, 0, 2, 4, 0, 1, 0, 2]).await,
        mbap(7, 1, &[0x90, 4]),
        "the write covers 151"
    );
    assert_eq!(
        server.model.register(Table::HoldingRegisters, 150),
        Some(0),
        "not executed"
    );
    assert_eq!(
        transact(&mut s, 8, 1, &[16, 0, 150, 0, 2, 4, 0, 1, 0, 2]).await,
        mbap(8, 1, &[16, 0, 150, 0, 2])
    );
    let snapshot = state.snapshot();
    assert_eq!(snapshot.active_faults.len(), 1);
    let c = snapshot.counters;
    assert_eq!(
        (
            c.faults_applied.delay,
            c.faults_applied.no_reply,
            c.faults_applied.exception
        ),
        (1, 1, 3)
    );
    assert_eq!(c.diagnostics.server_busy_count, 2);
    assert_eq!(c.no_response, 1);

    assert_eq!(
        state.inject(&object(json!({"fault": "clear"}))).unwrap(),
        json!({"active_faults": []})
    );
    assert_eq!(
        transact(&mut s, 9, 1, &[3, 0, 100, 0, 1]).await,
        mbap(9, 1, &[3, 2, 0, 0])
    );
    // RTU-only faults are refused on TCP, naming the field.
    let e = state
        .inject(&object(json!({"fault": "corrupt"})))
        .unwrap_err();
    assert_eq!(e.field.as_deref(), Some("fault"));
    server.shutdown().await;
}

#[tokio::test]
async fn a_close_fault_closes_the_connection_instead_of_answering() {
    let server = start_tcp(model_100_to_199(), TcpConfig::default()).await;
    let state = &server.state;
    let answer = state
        .inject(&object(json!({"fault": "close", "count": 1})))
        .unwrap();
    assert_eq!(
        answer,
        json!({"active_faults": [{"fault": "close", "count": 1}]})
    );
    let mut s = connect(server.addr).await;
    s.write_all(&mbap(1, 1, &[6, 0, 150, 0x11, 0x11]))
        .await
        .unwrap();
    assert!(closed_by_peer(&mut s).await, "closed, not answered");
    assert_eq!(
        server.model.register(Table::HoldingRegisters, 150),
        Some(0),
        "not executed"
    );
    // Spent: the next connection is answered.
    let mut again = connect(server.addr).await;
    assert_eq!(
        transact(&mut again, 2, 1, &[6, 0, 150, 0x11, 0x11]).await,
        mbap(2, 1, &[6, 0, 150, 0x11, 0x11])
    );
    let c = state.snapshot().counters;
    assert_eq!((c.faults_applied.close, c.no_response), (1, 1));
    assert!(state.snapshot().active_faults.is_empty());
    server.shutdown().await;
}

#[tokio::test]
async fn configured_faults_apply_from_the_start() {
    let config: TcpConfig = serde_json::from_value(json!({
        "faults": [{"fault": "exception", "code": 2, "function": 6, "count": 1}]
    }))
    .unwrap();
    let server = start_tcp(model_100_to_199(), config).await;
    let mut s = connect(server.addr).await;
    assert_eq!(
        transact(&mut s, 1, 1, &[6, 0, 100, 0, 1]).await,
        mbap(1, 1, &[0x86, 2])
    );
    assert_eq!(
        transact(&mut s, 2, 1, &[6, 0, 100, 0, 1]).await,
        mbap(2, 1, &[6, 0, 100, 0, 1])
    );
    // Unknown keys are refused, in the config as at run time.
    assert!(serde_json::from_value::<TcpConfig>(json!({"max_conections": 3})).is_err());
    assert!(serde_json::from_value::<TcpConfig>(json!({"faults": [{"fault": "delay"}]})).is_err());
    server.shutdown().await;
}

#[tokio::test]
async fn shutdown_does_not_wait_for_a_delayed_reply() {
    let server = start_tcp(model_100_to_199(), TcpConfig::default()).await;
    server
        .state
        .inject(&object(json!({"fault": "delay", "ms": 60_000})))
        .unwrap();
    let mut s = connect(server.addr).await;
    s.write_all(&mbap(1, 1, &[3, 0, 100, 0, 1])).await.unwrap();
    eventually("the delay is running", || {
        server.state.counters.snapshot().faults_applied.delay == 1
    })
    .await;
    // `shutdown` gives up after MUST_HAPPEN (5 s), far below the 60 s delay.
    server.shutdown().await;
    assert!(closed_by_peer(&mut s).await);
}
