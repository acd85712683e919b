// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! Modbus RTU on real ptys: one that the server creates, and an existing device (one side of a
//! pty pair this test makes) that the server opens and configures.

mod common;

use std::io;
use std::sync::Arc;
use std::time::Duration;

use common::*;
use mcemu_modbus::config::{Parity, RtuConfig};
use mcemu_modbus::frame::rtu;
use mcemu_modbus::memory::{MemoryModel, Table};
use mcemu_modbus::state::{Framing, FrontendState};
use mcemu_modbus::transport::rtu::{serve_rtu, RtuLine};
use nix::sys::termios::{cfgetospeed, tcgetattr, BaudRate, ControlFlags};
use serde_json::{json, Map, Value};
use tokio::sync::oneshot;
use tokio::task::JoinHandle;
use tokio::time::Instant;

struct RtuServer {
    path: String,
    state: Arc<FrontendState>,
    model: Arc<MemoryModel>,
    _stop: oneshot::Sender<()>,
    task: JoinHandle<io::Result<()>>,
}

fn start(model: MemoryModel, config: RtuConfig) -> RtuServer {
    let line = RtuLine::open(&config).unwrap();
    let path = line.path().to_owned();
    let state = Arc::new(FrontendState::new("modbus_rtu", Framing::Rtu, &config.faults).unwrap());
    let model = Arc::new(model);
    let (stop, stopped) = oneshot::channel::<()>();
    let task = tokio::spawn(serve_rtu(
        line,
        Arc::clone(&model),
        Arc::clone(&state),
        async move {
            let _ = stopped.await;
        },
    ));
    RtuServer {
        path,
        state,
        model,
        _stop: stop,
        task,
    }
}

/// Units 1 and 2 on one line (multi-drop), tables at 100..200.
fn two_units() -> MemoryModel {
    model_100_to_199().with_units([1, 2])
}

fn object(v: Value) -> Map<String, Value> {
    match v {
        Value::Object(m) => m,
        _ => panic!("not an object"),
    }
}

#[tokio::test]
async fn a_pty_of_its_own_answers_exact_frames_and_survives_reconnects() {
    let server = start(two_units(), RtuConfig::default());
    assert!(server.path.starts_with("/dev/pts/"), "{}", server.path);
    let line = Line::open(&server.path);
    // Read 1 register at 100 from unit 1; the reply's CRC as every Modbus tool knows it.
    let request = rtu_frame(1, &[3, 0, 100, 0, 1]);
    assert_eq!(
        line.transact(&request, 7).await,
        [0x01, 0x03, 0x02, 0x00, 0x00, 0xB8, 0x44]
    );
    // Unit 2 answers with its own address.
    assert_eq!(
        line.transact(&rtu_frame(2, &[6, 0, 101, 0xAB, 0xCD]), 8)
            .await,
        rtu_frame(2, &[6, 0, 101, 0xAB, 0xCD])
    );
    // The client goes away and comes back: the line is still there.
    drop(line);
    let line = Line::open(&server.path);
    assert_eq!(
        line.transact(&rtu_frame(1, &[3, 0, 101, 0, 1]), 7).await,
        rtu_frame(1, &[3, 2, 0xAB, 0xCD])
    );
    // Two requests back to back are both answered, in order.
    line.send(
        &[
            rtu_frame(1, &[3, 0, 100, 0, 1]),
            rtu_frame(2, &[3, 0, 101, 0, 1]),
        ]
        .concat(),
    )
    .await;
    assert_eq!(
        line.recv(14).await,
        [
            rtu_frame(1, &[3, 2, 0, 0]),
            rtu_frame(2, &[3, 2, 0xAB, 0xCD])
        ]
        .concat()
    );
    let c = server.state.counters.snapshot();
    assert_eq!((c.replies, c.bytes_out), (5, 7 + 8 + 7 + 14));
}

#[tokio::test]
async fn bad_frames_and_other_units_are_ignored_and_broadcasts_execute_silently() {
    let server = start(two_units(), RtuConfig::default());
    let line = Line::open(&server.path);
    let counters = || server.state.counters.snapshot();
    // Each ignored frame is followed by a good request once the server has dealt with it: the
    // first bytes back must be that request's reply, so nothing was sent for the other.
    let probe = rtu_frame(1, &[3, 0, 120, 0, 1]);

    let mut bad = rtu_frame(1, &[3, 0, 100, 0, 1]);
    bad[7] ^= 0x01;
    line.send(&bad).await;
    eventually("CRC error counted", || counters().crc_errors == 1).await;
    assert_eq!(line.transact(&probe, 7).await, rtu_frame(1, &[3, 2, 0, 0]));

    line.send(&rtu_frame(9, &[3, 0, 100, 0, 1])).await;
    eventually("other unit counted", || counters().other_unit_ignored == 1).await;
    assert_eq!(line.transact(&probe, 7).await, rtu_frame(1, &[3, 2, 0, 0]));

    // Broadcast write: executed by the model, never answered.
    line.send(&rtu_frame(0, &[6, 0, 120, 0, 0x42])).await;
    eventually("broadcast executed", || {
        server.model.register(Table::HoldingRegisters, 120) == Some(0x42)
    })
    .await;
    assert_eq!(
        line.transact(&probe, 7).await,
        rtu_frame(1, &[3, 2, 0, 0x42])
    );

    // Broadcast read, and a broadcast that fails (address 99): no reply either way.
    line.send(&rtu_frame(0, &[3, 0, 120, 0, 1])).await;
    line.send(&rtu_frame(0, &[6, 0, 99, 0, 1])).await;
    eventually("broadcasts counted", || counters().broadcasts == 3).await;
    eventually("both unanswered", || counters().no_response == 3).await;
    assert_eq!(
        line.transact(&probe, 7).await,
        rtu_frame(1, &[3, 2, 0, 0x42])
    );

    // A frame too short for a CRC is dropped too.
    line.send(&[1, 3]).await;
    eventually("short frame counted", || {
        counters().malformed_frames.too_short == 1
    })
    .await;
    assert_eq!(
        line.transact(&probe, 7).await,
        rtu_frame(1, &[3, 2, 0, 0x42])
    );

    let c = counters();
    assert_eq!(
        c.exceptions_by_code.get(&2),
        Some(&1),
        "the failed broadcast"
    );
    assert_eq!(c.diagnostics.bus_communication_error_count, 2);
}

#[tokio::test]
async fn diagnostics_echo_count_and_listen_only_mode() {
    let server = start(two_units(), RtuConfig::default());
    let line = Line::open(&server.path);
    let counters = || server.state.counters.snapshot();
    let diag = |sub: u16, data: [u8; 2]| {
        let [hi, lo] = sub.to_be_bytes();
        rtu_frame(1, &[8, hi, lo, data[0], data[1]])
    };
    let count = |sub: u16, n: u16| {
        let ([hi, lo], [a, b]) = (sub.to_be_bytes(), n.to_be_bytes());
        rtu_frame(1, &[8, hi, lo, a, b])
    };

    // 00: the query data come back.
    let echo = diag(0x00, [0x12, 0x34]);
    assert_eq!(line.transact(&echo, 8).await, echo);
    // 0A: clear, then a known sequence.
    assert_eq!(
        line.transact(&diag(0x0A, [0, 0]), 8).await,
        diag(0x0A, [0, 0])
    );
    let mut bad = rtu_frame(1, &[3, 0, 100, 0, 1]);
    bad[6] ^= 0x80;
    line.send(&bad).await;
    eventually("CRC error", || counters().crc_errors == 1).await;
    line.send(&rtu_frame(9, &[3, 0, 100, 0, 1])).await;
    eventually("other unit", || counters().other_unit_ignored == 1).await;
    assert_eq!(
        line.transact(&rtu_frame(1, &[3, 0, 100, 0, 1]), 7).await,
        rtu_frame(1, &[3, 2, 0, 0])
    );
    assert_eq!(
        line.transact(&rtu_frame(1, &[3, 0, 99, 0, 1]), 5).await,
        rtu_frame(1, &[0x83, 2])
    );
    // Bus messages: other unit, read, exception, this query.
    assert_eq!(line.transact(&diag(0x0B, [0, 0]), 8).await, count(0x0B, 4));
    assert_eq!(line.transact(&diag(0x0C, [0, 0]), 8).await, count(0x0C, 1));
    assert_eq!(line.transact(&diag(0x0D, [0, 0]), 8).await, count(0x0D, 1));
    // Server messages: read, exception, three queries and this one.
    assert_eq!(line.transact(&diag(0x0E, [0, 0]), 8).await, count(0x0E, 6));
    assert_eq!(line.transact(&diag(0x0F, [0, 0]), 8).await, count(0x0F, 0));
    for sub in [0x10, 0x11, 0x12] {
        assert_eq!(line.transact(&diag(sub, [0, 0]), 8).await, count(sub, 0));
    }
    // Unknown sub-function → 01; a counter query with data other than 0000 → 03.
    assert_eq!(
        line.transact(&diag(0x03, [0, 0]), 5).await,
        rtu_frame(1, &[0x88, 1])
    );
    assert_eq!(
        line.transact(&diag(0x0B, [0, 1]), 5).await,
        rtu_frame(1, &[0x88, 3])
    );
    // Restart communications outside listen-only mode answers, and clears the counters.
    assert_eq!(
        line.transact(&diag(0x01, [0xFF, 0]), 8).await,
        diag(0x01, [0xFF, 0])
    );
    assert_eq!(line.transact(&diag(0x0E, [0, 0]), 8).await, count(0x0E, 1));

    // 04: listen-only. Nothing is answered or executed until 01, which is not answered either.
    line.send(&diag(0x04, [0, 0])).await;
    eventually("listen-only", || server.state.listen_only()).await;
    line.send(&rtu_frame(1, &[6, 0, 100, 0, 7])).await;
    line.send(&diag(0x0B, [0, 0])).await;
    eventually("ignored while listening", || counters().no_response == 3).await;
    line.send(&diag(0x01, [0, 0])).await;
    eventually("listen-only left", || !server.state.listen_only()).await;
    assert_eq!(line.transact(&diag(0x0E, [0, 0]), 8).await, count(0x0E, 1));
    assert_eq!(server.model.register(Table::HoldingRegisters, 100), Some(0));
    assert_eq!(counters().no_response, 4);
}

#[tokio::test]
async fn faults_delay_swallow_force_drop_and_corrupt() {
    let server = start(two_units(), RtuConfig::default());
    let line = Line::open(&server.path);
    let state = &server.state;
    let read = rtu_frame(1, &[3, 0, 100, 0, 1]);
    let reply = rtu_frame(1, &[3, 2, 0, 0]);

    state
        .inject(&object(json!({"fault": "delay", "ms": 100, "count": 1})))
        .unwrap();
    let sent = Instant::now();
    assert_eq!(line.transact(&read, 7).await, reply);
    assert!(sent.elapsed() >= Duration::from_millis(100));

    state
        .inject(&object(json!({"fault": "no_reply", "count": 1})))
        .unwrap();
    line.send(&rtu_frame(1, &[6, 0, 130, 0, 5])).await;
    eventually("swallowed", || {
        state.counters.snapshot().faults_applied.no_reply == 1
    })
    .await;
    assert_eq!(line.transact(&read, 7).await, reply);
    assert_eq!(server.model.register(Table::HoldingRegisters, 130), Some(0));

    state
        .inject(&object(
            json!({"fault": "exception", "code": 4, "function": 3, "count": 1}),
        ))
        .unwrap();
    assert_eq!(line.transact(&read, 5).await, rtu_frame(1, &[0x83, 4]));

    // corrupt: one bit flipped, so the client's CRC check fails.
    state
        .inject(&object(json!({"fault": "corrupt", "count": 1})))
        .unwrap();
    let got = line.transact(&read, 7).await;
    let flipped: u32 = got
        .iter()
        .zip(&reply)
        .map(|(a, b)| (a ^ b).count_ones())
        .sum();
    assert_eq!(flipped, 1, "{got:02X?}");
    assert_eq!(rtu::decode(&got), rtu::Decoded::BadCrc);

    // drop_bytes: the reply is 2 bytes short; the next reply follows it on the line.
    state
        .inject(&object(
            json!({"fault": "drop_bytes", "bytes": 2, "count": 1}),
        ))
        .unwrap();
    line.send(&read).await;
    eventually("dropped", || {
        state.counters.snapshot().faults_applied.drop_bytes == 1
    })
    .await;
    let next = rtu_frame(2, &[3, 0, 100, 0, 1]);
    let got = line.transact(&next, 5 + 7).await;
    assert_eq!(got[..5], reply[..5]);
    assert_eq!(rtu::decode(&got[..5]), rtu::Decoded::BadCrc);
    assert_eq!(got[5..], rtu_frame(2, &[3, 2, 0, 0]));

    let c = state.snapshot().counters.faults_applied;
    assert_eq!(
        (c.delay, c.no_reply, c.exception, c.corrupt, c.drop_bytes),
        (1, 1, 1, 1, 1)
    );
    assert!(state.snapshot().active_faults.is_empty());
}

#[tokio::test]
async fn an_existing_device_is_configured_and_served() {
    let (master, path, slave) = pty_pair();
    let config = RtuConfig {
        device: path.clone(),
        baud: 9600,
        parity: Parity::Odd,
        stop_bits: 2,
        ..RtuConfig::default()
    };
    let server = start(two_units(), config);
    assert_eq!(server.path, path);
    // The line settings are the device's (a pty shares them between its two sides).
    let t = tcgetattr(&slave).unwrap();
    let flags = t.control_flags;
    // Linux's pty driver drops PARENB (and forces CS8) whatever is set; PARODD and CSTOPB stay,
    // which shows the configured parity and stop bits were applied.
    assert!(
        flags.contains(ControlFlags::PARODD | ControlFlags::CSTOPB),
        "{flags:?}"
    );
    assert_eq!(flags & ControlFlags::CSIZE, ControlFlags::CS8);
    assert_eq!(cfgetospeed(&t), BaudRate::B9600);
    drop(slave);

    let line = Line::from_fd(master);
    assert_eq!(
        line.transact(&rtu_frame(1, &[16, 0, 110, 0, 2, 4, 0, 1, 0, 2]), 8)
            .await,
        rtu_frame(1, &[16, 0, 110, 0, 2])
    );
    assert_eq!(
        line.transact(&rtu_frame(2, &[3, 0, 110, 0, 2]), 9).await,
        rtu_frame(2, &[3, 4, 0, 1, 0, 2])
    );
    // A function code whose length nobody can predict ends by silence alone (4 ms at 9600).
    assert_eq!(
        line.transact(&rtu_frame(1, &[0x42, 1, 2]), 5).await,
        rtu_frame(1, &[0xC2, 1])
    );
    line.send(&rtu_frame(3, &[3, 0, 110, 0, 1])).await;
    eventually("unit 3 ignored", || {
        server.state.counters.snapshot().other_unit_ignored == 1
    })
    .await;
    assert_eq!(
        line.transact(&rtu_frame(1, &[3, 0, 111, 0, 1]), 7).await,
        rtu_frame(1, &[3, 2, 0, 2])
    );
    // The other side goes away: the server reports the line as gone.
    drop(line);
    let ended = tokio::time::timeout(MUST_HAPPEN, server.task)
        .await
        .unwrap();
    assert!(ended.unwrap().is_err());
}

#[test]
fn lines_that_cannot_be_opened_say_why() {
    let e = RtuLine::open(&RtuConfig {
        device: "/nonexistent/tty".into(),
        ..RtuConfig::default()
    })
    .unwrap_err();
    assert!(e.to_string().contains("/nonexistent/tty"), "{e}");
    let e = RtuLine::open(&RtuConfig {
        baud: 12_345,
        ..RtuConfig::default()
    })
    .unwrap_err();
    assert!(e.to_string().contains("12345"), "{e}");
    let e = RtuLine::open(&RtuConfig {
        stop_bits: 3,
        ..RtuConfig::default()
    })
    .unwrap_err();
    assert!(e.to_string().contains("stop_bits"), "{e}");
    // Not a terminal.
    let e = RtuLine::open(&RtuConfig {
        device: "/dev/null".into(),
        ..RtuConfig::default()
    })
    .unwrap_err();
    assert!(e.to_string().contains("not a terminal"), "{e}");
}
