//! The SocketCAN bridge on a real `vcan0`, against other SocketCAN users on the same interface
//! (a raw socket of the `socketcan` crate, can-utils' `cansend` and `candump`).
//!
//! These tests need a kernel with vcan, so they are `#[ignore]`d in a plain `cargo nextest
//! run` (listed as skipped, never silently passed) and run through the vcan harness, which
//! provides `vcan0` on the host or in a VM:
//!
//! ```text
//! tests/vcan/run -- cargo nextest run -p mcemu-can --test socketcan --run-ignored only
//! ```
//!
//! Run by hand without `vcan0` they fail, saying so. They share `vcan0` with whatever else
//! runs there and ignore frames with ids they did not send; the link-down test creates an
//! interface of its own (root: the VM harness runs as root). See docs/decisions.md, "CAN
//! transports".

#![cfg(target_os = "linux")]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;
use std::time::{Duration, Instant};

use mcemu_can::socketcan::{convert, open, LinkState, SocketCanBridge, SocketCanConfig};
use mcemu_can::{CanId, Endpoint, EndpointOptions, Hub, HubConfig, WireFrame};
use mcemu_tests::{require_tool, run_with_timeout};
use socketcan::Socket;

const IGNORED: &str = "needs a real vcan0: tests/vcan/run -- cargo nextest run -p mcemu-can --test socketcan --run-ignored only";

fn require_vcan0() {
    let up = std::fs::read_to_string("/sys/class/net/vcan0/flags")
        .ok()
        .and_then(|f| u32::from_str_radix(f.trim().trim_start_matches("0x"), 16).ok())
        .is_some_and(|flags| flags & 1 != 0);
    assert!(
        up,
        "vcan0 is absent or down: run these tests through the vcan harness \
         ({IGNORED})"
    );
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap()
}

/// Another program's socket (blocking, with a read timeout).
fn outside_on(interface: &str) -> socketcan::CanSocket {
    let socket = socketcan::CanSocket::open(interface).unwrap();
    socket.set_read_timeout(Duration::from_millis(100)).unwrap();
    socket
}

fn outside() -> socketcan::CanSocket {
    outside_on("vcan0")
}

/// Frames with the ids of `expected` (others on a shared vcan0 are not ours), as many as
/// `expected` has.
fn read_outside(socket: &socketcan::CanSocket, expected: &[WireFrame]) -> Vec<WireFrame> {
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut got = vec![];
    while got.len() < expected.len() {
        assert!(
            Instant::now() < deadline,
            "outside got {got:?}, expected {expected:?}"
        );
        if let Ok(native) = socket.read_frame() {
            let frame = convert::from_socketcan(&native).unwrap();
            if ours(expected, &frame) {
                got.push(frame);
            }
        }
    }
    got
}

fn ours(expected: &[WireFrame], frame: &WireFrame) -> bool {
    expected
        .iter()
        .any(|e| e.id() == frame.id() && e.kind() == frame.kind())
}

fn receive(endpoint: &mut Endpoint, expected: &[WireFrame]) -> Vec<WireFrame> {
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut got = vec![];
    while got.len() < expected.len() {
        match endpoint.try_recv() {
            Some(d) if ours(expected, &d.frame) => got.push(d.frame),
            Some(_) => {}
            None if Instant::now() > deadline => panic!("hub got {got:?}, expected {expected:?}"),
            None => std::thread::sleep(Duration::from_millis(2)),
        }
    }
    got
}

fn frames() -> Vec<WireFrame> {
    vec![
        WireFrame::standard(0x000, &[]).unwrap(),
        WireFrame::standard(0x7FF, &[0xDE, 0xAD, 0xBE, 0xEF, 0, 1, 2, 0xFF]).unwrap(),
        WireFrame::extended(0x1FFF_FFFF, &[1, 2, 3]).unwrap(),
        WireFrame::extended(0x123, &[]).unwrap(),
        WireFrame::remote(CanId::standard(0x181).unwrap(), 8).unwrap(),
        WireFrame::remote(CanId::extended(0x1ABC_DEF0).unwrap(), 0).unwrap(),
    ]
}

#[test]
#[ignore = "needs a real vcan0 (tests/vcan/run)"]
fn the_bridge_carries_frames_both_ways() {
    require_vcan0();
    let rt = runtime();
    let hub = Hub::new(HubConfig::new("vcan0"));
    let bridge = rt
        .block_on(SocketCanBridge::start(&hub, SocketCanConfig::default()))
        .unwrap();
    let mut node = hub.attach(EndpointOptions::new("node"));
    let other = outside();
    for frame in frames() {
        other
            .write_frame(&convert::to_socketcan(&frame).unwrap())
            .unwrap();
    }
    assert_eq!(receive(&mut node, &frames()), frames());
    for frame in frames() {
        node.send(frame).unwrap();
    }
    assert_eq!(read_outside(&other, &frames()), frames());
    // The counter moves after the write returns, which may be after the frame was read.
    let deadline = Instant::now() + Duration::from_secs(5);
    while bridge.stats().frames_out < 6 {
        assert!(Instant::now() < deadline, "{:?}", bridge.stats());
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(bridge.stats().frames_in >= 6, "{:?}", bridge.stats());
    assert_eq!(bridge.state(), LinkState::Up);
    rt.block_on(bridge.stop());
    assert_eq!(hub.counters().endpoints.len(), 1, "the bridge detached");
}

#[test]
#[ignore = "needs a real vcan0 (tests/vcan/run)"]
fn cansend_and_candump_see_the_emulated_bus() {
    require_vcan0();
    let cansend = require_tool("cansend");
    let candump = require_tool("candump");
    let rt = runtime();
    let hub = Hub::new(HubConfig::new("vcan0"));
    let _bridge = rt
        .block_on(SocketCanBridge::start(&hub, SocketCanConfig::default()))
        .unwrap();
    let mut node = hub.attach(EndpointOptions::new("node"));
    let mut send = Command::new(&cansend);
    send.args(["vcan0", "601#4000100000000000"]);
    assert!(run_with_timeout(send, b"", Duration::from_secs(10))
        .status
        .success());
    let request = ["601#4000100000000000".parse::<WireFrame>().unwrap()];
    assert_eq!(receive(&mut node, &request), request);
    // candump, filtered to our id, while the node answers until candump has seen it.
    let mut dump = Command::new(&candump);
    dump.args(["-L", "-n", "1", "-T", "10000", "vcan0,581:7FF"]);
    let answer = "581#4300100092010000".parse::<WireFrame>().unwrap();
    let sender = node.split().0;
    let keep_sending = std::thread::spawn(move || {
        for _ in 0..100 {
            sender.send(answer).unwrap();
            std::thread::sleep(Duration::from_millis(50));
        }
    });
    let output = run_with_timeout(dump, b"", Duration::from_secs(20));
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.trim_end().ends_with("vcan0 581#4300100092010000"),
        "{text}"
    );
    keep_sending.join().unwrap();
}

#[test]
#[ignore = "needs a real vcan0 (tests/vcan/run)"]
fn error_frames_from_the_interface_are_counted_and_passed_on() {
    require_vcan0();
    let rt = runtime();
    let hub = Hub::new(HubConfig::new("vcan0"));
    let bridge = rt
        .block_on(SocketCanBridge::start(&hub, SocketCanConfig::default()))
        .unwrap();
    let mut node = hub.attach(EndpointOptions::new("node"));
    // vcan passes an error frame written by another socket to sockets whose error mask takes
    // its class (the bridge takes all).
    let error = WireFrame::error(0x4, &[0, 0x10]).unwrap();
    outside()
        .write_frame(&convert::to_socketcan(&error).unwrap())
        .unwrap();
    assert_eq!(receive(&mut node, &[error]), [error]);
    assert!(bridge.stats().error_frames_in >= 1);
    assert!(hub.counters().error_frames >= 1);
    // The hub's error frames are not written to the interface.
    node.send(error).unwrap();
    let deadline = Instant::now() + Duration::from_secs(5);
    while bridge.stats().error_frames_not_sent == 0 {
        assert!(Instant::now() < deadline);
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn ip(args: &[&str]) -> Result<(), String> {
    let mut ip = Command::new("ip");
    ip.args(args);
    let output = run_with_timeout(ip, b"", Duration::from_secs(10));
    if output.status.success() {
        Ok(())
    } else {
        Err(format!(
            "ip {}: {}",
            args.join(" "),
            String::from_utf8_lossy(&output.stderr).trim()
        ))
    }
}

/// A vcan interface of this test's own, deleted on drop: taking a shared vcan0 down would
/// break whatever else uses it.
struct OwnVcan(&'static str);

impl OwnVcan {
    fn create(name: &'static str) -> OwnVcan {
        let _ = ip(&["link", "del", "dev", name]);
        ip(&["link", "add", "dev", name, "type", "vcan"])
            .and_then(|()| ip(&["link", "set", "up", "dev", name]))
            .unwrap_or_else(|e| panic!("{e}: this test creates a vcan interface and needs root (the VM harness runs as root)"));
        OwnVcan(name)
    }
}

impl Drop for OwnVcan {
    fn drop(&mut self) {
        let _ = ip(&["link", "del", "dev", self.0]);
    }
}

fn wait_for(bridge: &SocketCanBridge, what: impl Fn(&LinkState) -> bool) -> LinkState {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let state = bridge.state();
        if what(&state) {
            return state;
        }
        assert!(Instant::now() < deadline, "link state stayed {state:?}");
        std::thread::sleep(Duration::from_millis(10));
    }
}

#[test]
#[ignore = "needs a real vcan0 (tests/vcan/run)"]
fn the_bridge_survives_the_interface_going_down() {
    require_vcan0();
    let link = OwnVcan::create("mcemudown0");
    let rt = runtime();
    let hub = Hub::new(HubConfig::new(link.0));
    let config = SocketCanConfig {
        interface: link.0.to_string(),
        retry: Duration::from_millis(100),
        ..SocketCanConfig::default()
    };
    let bridge = rt
        .block_on(SocketCanBridge::start(&hub, config.clone()))
        .unwrap();
    let mut node = hub.attach(EndpointOptions::new("node"));
    ip(&["link", "set", "down", "dev", link.0]).unwrap();
    let down = wait_for(&bridge, |s| matches!(s, LinkState::Down(_)));
    let expected = "mcemudown0: the interface is down (`ip link set up mcemudown0`)";
    assert_eq!(down, LinkState::Down(expected.to_string()));
    // Opening it now says why not.
    let err = rt.block_on(async { open(link.0).err().unwrap().to_string() });
    assert_eq!(err, expected);
    // Frames sent meanwhile are dropped and counted; the hub carries on.
    node.send(WireFrame::standard(0x100, &[1]).unwrap())
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(5);
    while bridge.stats().dropped_out == 0 {
        assert!(Instant::now() < deadline, "{:?}", bridge.stats());
        std::thread::sleep(Duration::from_millis(5));
    }
    ip(&["link", "set", "up", "dev", link.0]).unwrap();
    wait_for(&bridge, |s| *s == LinkState::Up);
    let other = outside_on(link.0);
    let incoming = [WireFrame::standard(0x200, &[2]).unwrap()];
    other
        .write_frame(&convert::to_socketcan(&incoming[0]).unwrap())
        .unwrap();
    assert_eq!(receive(&mut node, &incoming), incoming);
    let outgoing = [WireFrame::standard(0x300, &[3]).unwrap()];
    node.send(outgoing[0]).unwrap();
    assert_eq!(read_outside(&other, &outgoing), outgoing);
    assert_eq!(bridge.stats().link_losses, 1);
    // An interface deleted under the bridge is reported as gone.
    drop(other);
    drop(link);
    let gone = wait_for(
        &bridge,
        |s| matches!(s, LinkState::Down(r) if r.contains("no such")),
    );
    assert_eq!(
        gone,
        LinkState::Down(
            "mcemudown0: no such interface (a virtual one: `ip link add dev mcemudown0 type \
             vcan && ip link set up mcemudown0`)"
                .to_string()
        )
    );
    assert_eq!(bridge.stats().link_losses, 2);
    rt.block_on(bridge.stop());
}

#[test]
#[ignore = "needs a real vcan0 (tests/vcan/run)"]
fn a_missing_interface_is_named() {
    require_vcan0();
    let rt = runtime();
    let hub = Hub::new(HubConfig::new("vcan7"));
    let config = SocketCanConfig {
        interface: "mcemunone0".to_string(),
        ..SocketCanConfig::default()
    };
    let err = rt
        .block_on(SocketCanBridge::start(&hub, config))
        .err()
        .unwrap()
        .to_string();
    assert!(err.starts_with("mcemunone0: no such interface"), "{err}");
    assert!(hub.counters().endpoints.is_empty());
}
