//! Bad input at the binary level (issue 4, "Bad input"); the codecs and transports have their
//! unit tests, this proves isolation: while one client sends malformed MBAP headers (protocol id
//! ≠ 0, length > 254 or < 2), stalls in the middle of a frame, idles, trickles a request byte
//! by byte or opens more connections than allowed, and while garbage arrives on the RTU pty and
//! on an RTU-over-TCP connection, another client's requests keep being answered, correctly and
//! promptly; each abuse is answered or closed as the transport's rules say and counted in
//! `GET /state`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::net::TcpStream;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread;
use std::time::{Duration, Instant};

use mcemu_tests::{
    mbap_frame, rtu_frame, to_hex, wait_for, ByteLink, MbapClient, Mcemu, RawSerial,
};
use serde_json::Value;

/// A client that writes and reads back HR `register` in a loop until stopped: its request
/// count and slowest round trip. Any wrong answer fails it.
struct Victim {
    stop: Arc<AtomicBool>,
    thread: thread::JoinHandle<(u64, Duration)>,
}

impl Victim {
    fn start(address: &str, register: u16) -> Victim {
        let stop = Arc::new(AtomicBool::new(false));
        let mut client = MbapClient::connect(address);
        let flag = Arc::clone(&stop);
        let thread = thread::spawn(move || {
            let (mut n, mut slowest) = (0u64, Duration::ZERO);
            let a = register.to_be_bytes();
            while !flag.load(Ordering::Relaxed) {
                let v = (n as u16).to_be_bytes();
                let write = [6, a[0], a[1], v[0], v[1]];
                let t = Instant::now();
                assert_eq!(client.request(1, &write), write, "victim write #{n}");
                let read = client.request(1, &[3, a[0], a[1], 0, 1]);
                slowest = slowest.max(t.elapsed());
                assert_eq!(read, [3, 2, v[0], v[1]], "victim read-back #{n}");
                n += 1;
                thread::sleep(Duration::from_millis(2));
            }
            (n, slowest)
        });
        Victim { stop, thread }
    }

    /// Stop it; it must have kept going.
    fn finish(self, what: &str) {
        self.stop.store(true, Ordering::Relaxed);
        let (n, slowest) = self.thread.join().expect("the victim client failed");
        eprintln!("{what}: victim made {n} round trips, slowest {slowest:?}");
        assert!(n >= 10, "{what}: the victim made only {n} round trips");
        // Generous for a shared VM (stalls of a few hundred ms happen); a victim that waited
        // for an abuser's frame timeout (1.5 s) or idle timeout (2.5 s) would show it.
        assert!(
            slowest < Duration::from_millis(1200),
            "{what}: a victim round trip took {slowest:?}"
        );
    }
}

fn counters(m: &Mcemu, frontend: &str) -> Value {
    m.frontend(frontend)["counters"].clone()
}

fn start() -> Mcemu {
    let mut args = vec!["--clock", "virtual"];
    for s in [
        "frontends.modbus_tcp.max_connections=6",
        "frontends.modbus_tcp.at_limit=refuse",
        "frontends.modbus_tcp.frame_timeout_ms=1500",
        "frontends.modbus_tcp.idle_timeout_ms=2500",
        "frontends.modbus_rtu_over_tcp.frame_timeout_ms=1500",
    ] {
        args.extend(["--set", s]);
    }
    Mcemu::start(None, &args)
}

#[test]
fn malformed_mbap_stalled_idle_and_surplus_connections_do_not_disturb_another_client() {
    let m = start();
    let address = m.address("modbus-tcp").to_string();
    let victim = Victim::start(&address, 3000);
    let read = [3, 0x0B, 0xB8, 0, 1]; // HR 3000

    // Surplus connections: the victim holds 1 of 6; of 7 more, 5 are accepted and answer, 2
    // are closed at once (a request on them meets the end of the stream, not a timeout).
    let mut extra: Vec<MbapClient> = (0..7).map(|_| MbapClient::connect(&address)).collect();
    let mut refused = 0;
    for e in extra.iter_mut() {
        e.send_raw(&mbap_frame(1, 1, &read));
        let t = Instant::now();
        match e.read_reply(Duration::from_secs(10)) {
            Some(reply) => assert_eq!(reply.pdu[..2], [3, 2], "an accepted connection"),
            None => {
                assert!(
                    t.elapsed() < Duration::from_secs(5),
                    "neither answered nor closed"
                );
                refused += 1;
            }
        }
    }
    assert_eq!(refused, 2, "connections beyond max_connections = 6");
    drop(extra);
    // The server sees those five ends on its own time: wait until only the victim is open.
    wait_for(
        "the surplus connections closed",
        Duration::from_secs(10),
        || (m.frontend("modbus_tcp")["counters"]["connections"]["open"] == 1).then_some(()),
    );

    // Protocol id ≠ 0: skipped without an answer, the connection kept.
    let mut c = MbapClient::connect(&address);
    let mut foreign = mbap_frame(1, 1, &read);
    foreign[3] = 1;
    c.send_raw(&foreign);
    foreign[2] = 0x12;
    c.send_raw(&foreign);
    assert_eq!(
        c.request(1, &read)[..2],
        [3, 2],
        "answered after two foreign frames"
    );

    // Length > 254 and < 2: closed.
    for length in [0x0200u16, 300, 1] {
        let mut c = MbapClient::connect(&address);
        let mut frame = mbap_frame(7, 1, &read);
        frame[4..6].copy_from_slice(&length.to_be_bytes());
        c.send_raw(&frame);
        assert!(
            c.closed_within(Duration::from_secs(5)),
            "length {length}: not closed"
        );
    }

    // A frame announced longer than what comes (length mismatch, then silence): closed when
    // the frame timeout expires, nothing answered.
    let mut stalled = MbapClient::connect(&address);
    let mut frame = mbap_frame(8, 1, &read);
    frame[4..6].copy_from_slice(&20u16.to_be_bytes());
    stalled.send_raw(&frame);
    // A half-open header: 3 bytes of 7.
    let mut half = MbapClient::connect(&address);
    half.send_raw(&mbap_frame(9, 1, &read)[..3]);
    // A slow but complete request, a byte every 20 ms (within the frame timeout): answered.
    let mut slow = MbapClient::connect(&address);
    for b in mbap_frame(10, 1, &read) {
        slow.send_raw(&[b]);
        thread::sleep(Duration::from_millis(20));
    }
    let reply = slow
        .read_reply(Duration::from_secs(5))
        .expect("slow request answered");
    assert_eq!((reply.transaction, &reply.pdu[..2]), (10, &[3u8, 2][..]));
    assert!(
        stalled.closed_within(Duration::from_secs(5)),
        "stalled frame"
    );
    assert!(
        half.closed_within(Duration::from_secs(5)),
        "half-open header"
    );
    // An idle connection: closed after idle_timeout_ms.
    let mut idle = MbapClient::connect(&address);
    let t = Instant::now();
    assert!(
        idle.closed_within(Duration::from_secs(5)),
        "idle connection"
    );
    assert!(
        t.elapsed() >= Duration::from_millis(2400),
        "{:?}",
        t.elapsed()
    );
    // The foreign-frame and slow connections, silent since before it, were closed first.
    assert!(
        c.closed_within(Duration::from_millis(100)),
        "idle since the foreign frames"
    );
    assert!(
        slow.closed_within(Duration::from_millis(100)),
        "idle since its answer"
    );

    victim.finish("modbus_tcp");

    let c = counters(&m, "modbus_tcp");
    let malformed = &c["malformed_frames"];
    assert_eq!(malformed["not_modbus_protocol"], 2, "{c}");
    assert_eq!(malformed["bad_length"], 3, "{c}");
    let conns = &c["connections"];
    assert_eq!(conns["frame_timeouts"], 2, "{c}");
    assert_eq!(conns["refused_at_limit"], 2, "{c}");
    assert_eq!(conns["idle_timeouts"], 3, "{c}");
    assert_eq!(c["exceptions"], 0, "{c}");
}

#[test]
fn garbage_on_the_rtu_line_and_on_rtu_over_tcp_is_dropped_counted_and_isolated() {
    let m = start();
    let victim = Victim::start(m.address("modbus-tcp"), 3001);
    let request = rtu_frame(1, &[3, 0x0B, 0xB8, 0, 1]); // HR 3000 of unit 1
    let answer = rtu_frame(1, &[3, 2, 0, 0]);
    let quiet = Duration::from_millis(200);

    // The pty: a long run of garbage (no function code mcemu knows, so only silence ends it),
    // a frame with a bad CRC, a frame too short for a CRC, then a good request.
    let device = m.address("modbus-rtu").to_string();
    let mut line = RawSerial::open(Path::new(&device));
    let mut x: u32 = 12345;
    let garbage: Vec<u8> = (0..300)
        .map(|i| {
            x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
            if i == 1 {
                0xAA
            } else {
                (x >> 16) as u8
            }
        })
        .collect();
    line.send(&garbage);
    assert_eq!(to_hex(&line.drain(quiet)), "", "garbage answered");
    let mut bad_crc = request.clone();
    *bad_crc.last_mut().unwrap() ^= 0xFF;
    line.send(&bad_crc);
    assert_eq!(to_hex(&line.drain(quiet)), "", "bad CRC answered");
    line.send(&[1, 3]);
    assert_eq!(to_hex(&line.drain(quiet)), "", "a 2-byte frame answered");
    // Another unit's request on the shared line: ignored.
    line.send(&rtu_frame(9, &[3, 0x0B, 0xB8, 0, 1]));
    assert_eq!(to_hex(&line.drain(quiet)), "", "unit 9 answered");
    line.exchange(&request, &answer, quiet);
    let c = counters(&m, "modbus_rtu");
    assert_eq!(c["malformed_frames"]["too_long"], 1, "{c}");
    assert_eq!(c["malformed_frames"]["too_short"], 1, "{c}");
    assert_eq!(c["crc_errors"], 1, "{c}");
    assert_eq!(c["other_unit_ignored"], 1, "{c}");
    assert_eq!(c["diagnostics"]["bus_communication_error_count"], 2, "{c}");
    assert_eq!(c["diagnostics"]["bus_character_overrun_count"], 1, "{c}");
    assert_eq!(c["replies"], 1, "{c}");

    // RTU over TCP: one connection sends garbage and a bad CRC, another is served meanwhile;
    // the first recovers after the silence.
    let address = m.address("modbus-rtu-over-tcp").to_string();
    let mut dirty = TcpStream::connect(&address).unwrap();
    let mut clean = TcpStream::connect(&address).unwrap();
    dirty.send(&garbage[..100]);
    clean.exchange(&request, &answer, quiet);
    dirty.send(&bad_crc);
    clean.exchange(&request, &answer, quiet);
    assert_eq!(to_hex(&dirty.drain(quiet)), "", "garbage answered over TCP");
    dirty.exchange(&request, &answer, quiet);
    let c = counters(&m, "modbus_rtu_over_tcp");
    assert!(
        c["crc_errors"].as_u64().unwrap() >= 1,
        "garbage and a bad CRC counted: {c}"
    );
    assert_eq!(c["replies"], 3, "{c}");
    victim.finish("modbus_rtu");
}

/// The lock-out this used to be (issue 10): 200 idle connections, then a real client. At the
/// bound (16 by default) each newcomer closes the connection idle longest, so the client is
/// admitted and answered; under `refuse` it was reset.
#[test]
fn idle_connections_at_the_limit_do_not_lock_a_client_out() {
    let m = Mcemu::start(None, &["--clock", "virtual"]);
    let address = m.address("modbus-tcp").to_string();
    let idle: Vec<TcpStream> = (0..200)
        .map(|_| TcpStream::connect(&address).unwrap())
        .collect();
    let mut client = MbapClient::connect(&address);
    assert_eq!(client.request(1, &[3, 0x0B, 0xB8, 0, 1])[..2], [3, 2]);
    // 16 admitted, then each of the other 184 and the client evicted one.
    wait_for("every eviction counted", Duration::from_secs(10), || {
        let c = &counters(&m, "modbus_tcp")["connections"];
        (c["evicted_idle"] == 185).then_some(())
    });
    let c = counters(&m, "modbus_tcp");
    assert_eq!(c["connections"]["refused_at_limit"], 0, "{c}");
    assert_eq!(c["connections"]["opened"], 201, "{c}");
    assert_eq!(client.request(1, &[3, 0x0B, 0xB8, 0, 1])[..2], [3, 2]);
    drop(idle);
}
