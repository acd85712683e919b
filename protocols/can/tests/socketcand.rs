//! The socketcand server against real clients: python-can's `socketcand` interface (from the
//! venv of scripts/setup) sends and receives frames both ways, two python-can clients see each
//! other's frames; a raw TCP client covers what python-can cannot send or parse (RTR, error
//! frames, bad commands, the connection limit).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::process::Command;
use std::time::{Duration, Instant};

use mcemu_can::socketcand::{AtLimit, SocketcandConfig, SocketcandServer};
use mcemu_can::{CanId, Endpoint, EndpointOptions, Hub, HubConfig, WireFrame};
use mcemu_tests::{python, python_script, run_with_timeout, spawn_until_line};
use serde_json::{json, Value};

struct Served {
    runtime: tokio::runtime::Runtime,
    server: Option<SocketcandServer>,
    hub: Hub,
}

impl Served {
    fn new(config: SocketcandConfig) -> Served {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .unwrap();
        let hub = Hub::new(HubConfig::new("vcan0"));
        let config = SocketcandConfig {
            bind: "127.0.0.1:0".parse().unwrap(),
            ..config
        };
        let server = runtime
            .block_on(SocketcandServer::start(config, vec![hub.clone()]))
            .unwrap();
        Served {
            runtime,
            server: Some(server),
            hub,
        }
    }

    fn start() -> Served {
        Self::new(SocketcandConfig::default())
    }

    fn addr(&self) -> SocketAddr {
        self.server.as_ref().unwrap().local_addr()
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        if let Some(server) = self.server.take() {
            self.runtime.block_on(server.shutdown());
        }
    }
}

/// Wait for `n` frames on `endpoint`.
fn receive(endpoint: &mut Endpoint, n: usize) -> Vec<WireFrame> {
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut got = vec![];
    while got.len() < n {
        match endpoint.try_recv() {
            Some(d) => got.push(d.frame),
            None if Instant::now() > deadline => panic!("got {got:?}, expected {n} frames"),
            None => std::thread::sleep(Duration::from_millis(2)),
        }
    }
    got
}

fn as_json(frame: &WireFrame) -> Value {
    let hex: String = frame.data().iter().map(|b| format!("{b:02x}")).collect();
    json!({"id": frame.id().raw(), "ext": frame.is_extended(), "data": hex})
}

fn strip(received: &Value) -> Vec<Value> {
    received
        .as_array()
        .unwrap()
        .iter()
        .map(|f| json!({"id": f["id"], "ext": f["ext"], "data": f["data"]}))
        .collect()
}

fn frames() -> Vec<WireFrame> {
    vec![
        WireFrame::standard(0x000, &[]).unwrap(),
        WireFrame::standard(0x7FF, &[0xDE, 0xAD, 0xBE, 0xEF, 0, 1, 2, 0xFF]).unwrap(),
        WireFrame::standard(0x181, &[0x0A]).unwrap(),
        WireFrame::extended(0x1FFF_FFFF, &[1, 2, 3]).unwrap(),
        // A small extended id stays extended (8 digits on the wire).
        WireFrame::extended(0x123, &[]).unwrap(),
    ]
}

#[test]
fn python_can_sends_and_receives_frames() {
    let served = Served::start();
    let mut rust = served.hub.attach(EndpointOptions::new("rust side"));
    let out =
        std::env::temp_dir().join(format!("mcemu-can-socketcand-{}.json", std::process::id()));
    let from_python: Vec<WireFrame> = frames().into_iter().rev().collect();
    let mut command = Command::new(python());
    command
        .arg(python_script("can_socketcand.py"))
        .args(["exchange", "--port", &served.addr().port().to_string()])
        .args(["--expect", &frames().len().to_string()])
        .args([
            "--send",
            &Value::from(from_python.iter().map(as_json).collect::<Vec<_>>()).to_string(),
        ])
        .arg("--out")
        .arg(&out);
    let (mut client, _) = spawn_until_line(command, "ready", Duration::from_secs(30));
    for frame in frames() {
        rust.send(frame).unwrap();
    }
    assert_eq!(receive(&mut rust, from_python.len()), from_python);
    let deadline = Instant::now() + Duration::from_secs(30);
    let status = loop {
        if let Some(status) = client.try_wait() {
            break status;
        }
        assert!(
            Instant::now() < deadline,
            "python did not exit: {}",
            client.kill()
        );
        std::thread::sleep(Duration::from_millis(10));
    };
    assert!(status.success(), "python failed: {}", client.kill());
    let result: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    std::fs::remove_file(&out).unwrap();
    let expected: Vec<Value> = frames().iter().map(as_json).collect();
    assert_eq!(strip(&result["received"]), expected);
    // Stamps are the wall clock (the hub's epoch is when it started).
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_secs_f64();
    for frame in result["received"].as_array().unwrap() {
        let stamp = frame["timestamp"].as_f64().unwrap();
        assert!((now - stamp).abs() < 60.0, "stamp {stamp} vs now {now}");
    }
    let stats = served.server.as_ref().unwrap().stats();
    assert_eq!(stats.frames_from_clients, from_python.len() as u64);
    assert_eq!(stats.frames_to_clients, frames().len() as u64);
    assert_eq!(stats.errors, 0);
}

#[test]
fn two_python_can_clients_see_each_others_frames_but_not_their_own() {
    let served = Served::start();
    let mut watcher = served.hub.attach(EndpointOptions::new("watcher"));
    let send_a: Vec<Value> = frames().iter().map(as_json).collect();
    let send_b: Vec<Value> = frames().iter().rev().map(as_json).collect();
    let mut command = Command::new(python());
    command
        .arg(python_script("can_socketcand.py"))
        .args(["pair", "--port", &served.addr().port().to_string()])
        .args(["--send-a", &Value::from(send_a.clone()).to_string()])
        .args(["--send-b", &Value::from(send_b.clone()).to_string()]);
    let output = run_with_timeout(command, b"", Duration::from_secs(60));
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let result: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(strip(&result["b_got"]), send_a);
    assert_eq!(strip(&result["a_got"]), send_b);
    assert_eq!(result["a_own"], 0);
    assert_eq!(result["b_own"], 0);
    // The emulator's own endpoints saw all of it.
    assert_eq!(
        receive(&mut watcher, 2 * frames().len()).len(),
        2 * frames().len()
    );
}

/// A plain TCP client that reads whole `< … >` elements.
struct RawClient {
    stream: TcpStream,
    pending: Vec<u8>,
}

impl RawClient {
    fn connect(addr: SocketAddr) -> RawClient {
        let stream = TcpStream::connect(addr).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_millis(100)))
            .unwrap();
        RawClient {
            stream,
            pending: vec![],
        }
    }

    fn send(&mut self, text: &str) {
        self.stream.write_all(text.as_bytes()).unwrap();
    }

    /// The next element, or `None` if nothing complete arrives within `wait` (or the server
    /// closed the connection).
    fn element(&mut self, wait: Duration) -> Option<String> {
        let deadline = Instant::now() + wait;
        loop {
            if let Some(end) = self.pending.iter().position(|&b| b == b'>') {
                let element: Vec<u8> = self.pending.drain(..=end).collect();
                let text = String::from_utf8(element).unwrap();
                return Some(text.trim_start().to_string());
            }
            if Instant::now() > deadline {
                return None;
            }
            let mut buf = [0u8; 1024];
            match self.stream.read(&mut buf) {
                Ok(0) => return None,
                Ok(n) => self.pending.extend_from_slice(&buf[..n]),
                Err(e)
                    if matches!(
                        e.kind(),
                        std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                    ) => {}
                Err(_) => return None,
            }
        }
    }

    fn expect(&mut self, what: &str) -> String {
        self.element(Duration::from_secs(5))
            .unwrap_or_else(|| panic!("nothing received, expected {what}"))
    }

    /// Whether the server closes the connection within 5 s (what it sent first is dropped).
    fn closed(&mut self) -> bool {
        let deadline = Instant::now() + Duration::from_secs(5);
        let mut buf = [0u8; 1024];
        while Instant::now() < deadline {
            match self.stream.read(&mut buf) {
                Ok(0) => return true,
                Ok(_) => {}
                Err(e)
                    if matches!(
                        e.kind(),
                        std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                    ) => {}
                Err(_) => return true,
            }
        }
        false
    }

    fn open_raw(addr: SocketAddr) -> RawClient {
        let mut client = RawClient::connect(addr);
        assert_eq!(client.expect("hi"), "< hi >");
        client.send("< open vcan0 >");
        assert_eq!(client.expect("ok"), "< ok >");
        client.send("< rawmode >");
        assert_eq!(client.expect("ok"), "< ok >");
        client
    }
}

/// `< frame 123 1700000000.123456 0102 >` without its stamp.
fn without_stamp(element: &str) -> String {
    // The stamp is the only word with a '.'.
    let kept: Vec<&str> = element.split(' ').filter(|w| !w.contains('.')).collect();
    kept.join(" ")
}

#[test]
fn rtr_and_error_frames_over_a_raw_connection() {
    let served = Served::start();
    let mut rust = served.hub.attach(EndpointOptions::new("rust side"));
    let mut client = RawClient::open_raw(served.addr());
    client.send("< sendrtr 123 4 >< sendrtr 1AAAAAAA 0 >< send 1AAAAAAA 2 1 F1 >");
    assert_eq!(
        receive(&mut rust, 3),
        [
            WireFrame::remote(CanId::standard(0x123).unwrap(), 4).unwrap(),
            WireFrame::remote(CanId::extended(0x1AAA_AAAA).unwrap(), 0).unwrap(),
            WireFrame::extended(0x1AAA_AAAA, &[1, 0xF1]).unwrap(),
        ]
    );
    rust.send(WireFrame::remote(CanId::standard(0x7FF).unwrap(), 8).unwrap())
        .unwrap();
    rust.send(WireFrame::error(0x4, &[0, 0x10]).unwrap())
        .unwrap();
    rust.send(WireFrame::standard(0x001, &[]).unwrap()).unwrap();
    assert_eq!(without_stamp(&client.expect("rtr")), "< rtr 7FF 8 >");
    assert_eq!(
        without_stamp(&client.expect("error frame")),
        "< error 004 >"
    );
    assert_eq!(without_stamp(&client.expect("frame")), "< frame 001  >");
}

#[test]
fn bad_commands_get_errors_and_the_connection_survives() {
    let served = Served::start();
    let mut rust = served.hub.attach(EndpointOptions::new("rust side"));
    let mut client = RawClient::connect(served.addr());
    assert_eq!(client.expect("hi"), "< hi >");
    // Before a bus is open, and a bus that is not served.
    for bad in [
        "< rawmode >",
        "< send 123 0 >",
        "< open vcan9 >",
        "< hello >",
    ] {
        client.send(bad);
        let reply = client.expect("error");
        assert!(
            reply.starts_with("< error ") && reply.ends_with(" >"),
            "{bad} → {reply}"
        );
    }
    client.send("< echo >");
    assert_eq!(client.expect("echo"), "< echo >");
    client.send("< open vcan0 >< rawmode >");
    assert_eq!(client.expect("ok"), "< ok >");
    assert_eq!(client.expect("ok"), "< ok >");
    let mut long = String::from("< send ");
    long.push_str(&"0".repeat(1000));
    long.push_str(" >");
    for bad in [
        "< send 800 0 >",
        "< send 123 9 >",
        "< send 123 2 11 >",
        "< send 123 1 1FF >",
        "< send 2AAAAAAA 0 >",
        "< send nothex 0 >",
        "< sendrtr 123 >",
        "< fdsend 123 0 0 >",
        "< subscribe 0 0 123 >",
        "< add 1 0 123 0 >",
        "< isotpmode >",
        "< open vcan0 >",
        "< \u{7f}\u{1} >",
        long.as_str(),
    ] {
        client.send(bad);
        let reply = client.expect("error");
        assert!(
            reply.starts_with("< error ") && reply.ends_with(" >"),
            "{bad} → {reply}"
        );
    }
    // Still alive: frames pass both ways.
    client.send("< send 123 2 AA BB >");
    assert_eq!(
        receive(&mut rust, 1),
        [WireFrame::standard(0x123, &[0xAA, 0xBB]).unwrap()]
    );
    rust.send(WireFrame::standard(0x321, &[1]).unwrap())
        .unwrap();
    assert_eq!(without_stamp(&client.expect("frame")), "< frame 321 01 >");
    assert_eq!(served.server.as_ref().unwrap().stats().errors, 18);
}

#[test]
fn connections_are_bounded() {
    let served = Served::new(SocketcandConfig {
        max_connections: 2,
        at_limit: AtLimit::Refuse,
        ..SocketcandConfig::default()
    });
    let mut a = RawClient::connect(served.addr());
    let mut b = RawClient::connect(served.addr());
    assert_eq!(a.expect("hi"), "< hi >");
    assert_eq!(b.expect("hi"), "< hi >");
    let mut c = RawClient::connect(served.addr());
    let reply = c.expect("refusal");
    assert!(reply.starts_with("< error too many connections"), "{reply}");
    assert_eq!(c.element(Duration::from_millis(500)), None);
    drop(a);
    // The slot frees once the server notices the close.
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        let mut d = RawClient::connect(served.addr());
        if d.expect("greeting") == "< hi >" {
            break;
        }
        assert!(Instant::now() < deadline, "the slot was not freed");
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(served.server.as_ref().unwrap().stats().refused >= 1);
}

#[test]
fn at_the_limit_the_client_idle_longest_makes_room() {
    let served = Served::new(SocketcandConfig {
        max_connections: 2,
        ..SocketcandConfig::default()
    });
    let mut a = RawClient::connect(served.addr());
    assert_eq!(a.expect("hi"), "< hi >");
    let mut b = RawClient::connect(served.addr());
    assert_eq!(b.expect("hi"), "< hi >");
    // `b` speaks after `a` last did: `a` is idle longest.
    b.send("< echo >");
    assert_eq!(b.expect("echo"), "< echo >");
    let mut c = RawClient::connect(served.addr());
    assert_eq!(c.expect("hi"), "< hi >", "the newcomer is served");
    assert!(a.closed(), "a was idle longest");
    b.send("< echo >");
    assert_eq!(b.expect("echo"), "< echo >");
    let stats = served.server.as_ref().unwrap().stats();
    assert_eq!(
        (stats.evicted_idle, stats.refused, stats.accepted),
        (1, 0, 3)
    );
}

#[test]
fn a_client_that_does_not_read_loses_frames_without_slowing_the_bus() {
    let served = Served::start();
    let _client = RawClient::open_raw(served.addr()); // never reads again
    let sender = served.hub.attach(EndpointOptions::new("fast"));
    let mut listener = served
        .hub
        .attach(EndpointOptions::new("listener").queue_capacity(600_000));
    let started = Instant::now();
    for i in 0..500_000u32 {
        sender
            .send(WireFrame::standard((i % 0x7FF) as u16, &i.to_le_bytes()).unwrap())
            .unwrap();
    }
    assert!(started.elapsed() < Duration::from_secs(10));
    assert_eq!(std::iter::from_fn(|| listener.try_recv()).count(), 500_000);
    let counters = served.hub.counters();
    let socketcand = counters
        .endpoints
        .iter()
        .find(|e| e.name.starts_with("socketcand"))
        .unwrap();
    assert!(socketcand.dropped > 0, "{socketcand:?}");
    assert_eq!(socketcand.received + socketcand.dropped, 500_000);
}

/// A client that sends but never reads, with the bus flooding frames towards it: its receive
/// window fills, its frames still all reach the bus (the server keeps reading its commands),
/// frames for it are dropped and counted, the connection stays, and once it reads again
/// frames flow again.
#[test]
fn a_client_that_does_not_read_can_still_send() {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;

    const SENDS: u32 = 50_000;
    let served = Served::start();
    let mut client = RawClient::open_raw(served.addr()); // stops reading here
    client
        .stream
        .set_write_timeout(Some(Duration::from_secs(30)))
        .unwrap();
    // One endpoint floods the bus and receives what the client sends (a sender does not
    // receive its own frames, so only the client's frames arrive here).
    let (flooder, mut watcher) = served
        .hub
        .attach(EndpointOptions::new("flood").queue_capacity(SENDS as usize + 1))
        .split();
    let flooding = Arc::new(AtomicBool::new(true));
    let flood = {
        let flooding = Arc::clone(&flooding);
        let flooder = flooder.clone();
        std::thread::spawn(move || {
            let mut i = 0u32;
            while flooding.load(Ordering::Relaxed) {
                for _ in 0..256 {
                    let frame = WireFrame::standard(0x7FF, &i.to_le_bytes()).unwrap();
                    flooder.send(frame).unwrap();
                    i = i.wrapping_add(1);
                }
                // Leave the 2 cores some room for the server.
                std::thread::sleep(Duration::from_millis(1));
            }
        })
    };
    let socketcand_counters = |served: &Served| {
        served
            .hub
            .counters()
            .endpoints
            .into_iter()
            .find(|e| e.name.starts_with("socketcand"))
            .unwrap()
    };
    // Wait until the client's window is full: the server passes no more frames on (its
    // count stays put over 20 polls) while the bus still floods it (its queue drops).
    let server = served.server.as_ref().unwrap();
    let deadline = Instant::now() + Duration::from_secs(60);
    let (mut passed_on, mut dropped, mut still) = (u64::MAX, 0, 0);
    while still < 20 {
        assert!(
            Instant::now() < deadline,
            "the client's window never filled"
        );
        std::thread::sleep(Duration::from_millis(10));
        let now = (
            server.stats().frames_to_clients,
            socketcand_counters(&served).dropped,
        );
        still = if now.0 == passed_on && now.1 > dropped {
            still + 1
        } else {
            0
        };
        (passed_on, dropped) = now;
    }
    let expected: Vec<WireFrame> = (0..SENDS)
        .map(|i| WireFrame::standard(0x123, &i.to_be_bytes()).unwrap())
        .collect();
    for chunk in (0..SENDS).collect::<Vec<_>>().chunks(100) {
        let text: String = chunk
            .iter()
            .map(|i| {
                let [a, b, c, d] = i.to_be_bytes();
                format!("< send 123 4 {a:02X} {b:02X} {c:02X} {d:02X} >")
            })
            .collect();
        client.send(&text);
    }
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut got = Vec::with_capacity(SENDS as usize);
    while got.len() < SENDS as usize {
        match watcher.try_recv() {
            Some(d) => got.push(d.frame),
            None if Instant::now() > deadline || server.stats().active == 0 => panic!(
                "{} of {SENDS} frames reached the bus; {:?}",
                got.len(),
                server.stats()
            ),
            None => std::thread::sleep(Duration::from_millis(2)),
        }
    }
    assert!(got == expected, "the client's frames arrived changed");
    let counters = socketcand_counters(&served);
    assert_eq!(counters.sent, u64::from(SENDS));
    assert!(counters.dropped > 0, "{counters:?}");
    let stats = server.stats();
    assert_eq!(stats.active, 1, "{stats:?}");
    assert_eq!(stats.frames_from_clients, u64::from(SENDS));

    // It reads again: what was queued for it, then frames sent from now on.
    flooding.store(false, Ordering::Relaxed);
    flood.join().unwrap();
    let marker = WireFrame::standard(0x555, &[0x55]).unwrap();
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut frames_read = 0u64;
    'resumed: loop {
        assert!(
            Instant::now() < deadline,
            "no new frame after reading {frames_read}"
        );
        // Sent until one finds room in the client's queue.
        flooder.send(marker).unwrap();
        while let Some(element) = client.element(Duration::from_millis(20)) {
            let element = without_stamp(&element);
            if element == "< frame 555 55 >" {
                break 'resumed;
            }
            assert!(element.starts_with("< frame 7FF "), "{element}");
            frames_read += 1;
        }
    }
    assert!(frames_read > 0);
}

/// Replies are never dropped: a client that sends commands with replies and does not read
/// them is held back (the server stops reading it past its output limit), and gets every
/// reply, in order, once it reads.
#[test]
fn replies_to_a_client_that_does_not_read_wait_for_it() {
    // 2 MB of bad commands, each answered with 30 bytes: 10 MB of replies, more than the
    // sockets' buffers (4 MB send buffer at most here) and the server's output limit hold.
    const BAD: usize = 350_000;
    let served = Served::start();
    let mut client = RawClient::open_raw(served.addr());
    let mut writer = client.stream.try_clone().unwrap();
    writer
        .set_write_timeout(Some(Duration::from_secs(60)))
        .unwrap();
    // Written from another thread: once the server holds back, this write waits for us.
    let sending = std::thread::spawn(move || {
        writer.write_all("< xx >".repeat(BAD).as_bytes()).unwrap();
        writer.write_all(b"< echo >< send 123 1 AA >").unwrap();
    });
    let mut watcher = served.hub.attach(EndpointOptions::new("watcher"));
    for i in 0..BAD {
        assert_eq!(
            client.element(Duration::from_secs(30)).as_deref(),
            Some("< error unknown command 'xx' >"),
            "reply {i}"
        );
    }
    assert_eq!(client.expect("echo"), "< echo >");
    sending.join().unwrap();
    assert_eq!(
        receive(&mut watcher, 1),
        [WireFrame::standard(0x123, &[0xAA]).unwrap()]
    );
    let stats = served.server.as_ref().unwrap().stats();
    assert_eq!((stats.active, stats.errors), (1, BAD as u64));
}
