//! The in-process bus: fan-out, own frames, bounded queues with counted drops, detaching, the
//! bit-rate model on a virtual clock (arbitration order, latency, bus load), the candump log,
//! and async receivers under tokio.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::time::Duration;

use mcemu_can::{
    BitTiming, CandumpLog, Clock, EndpointOptions, Hub, HubConfig, Stuffing, WireFrame,
};

fn frame(id: u16, data: &[u8]) -> WireFrame {
    WireFrame::standard(id, data).unwrap()
}

fn virtual_hub() -> Hub {
    Hub::new(HubConfig::new("vcan0").with_clock(Clock::Virtual))
}

#[test]
fn a_frame_reaches_every_other_endpoint_but_not_its_sender() {
    let hub = virtual_hub();
    let mut a = hub.attach(EndpointOptions::new("a"));
    let mut b = hub.attach(EndpointOptions::new("b"));
    let mut c = hub.attach(EndpointOptions::new("c"));
    a.send(frame(0x181, &[1, 2])).unwrap();
    assert!(a.try_recv().is_none());
    for ep in [&mut b, &mut c] {
        let d = ep.try_recv().unwrap();
        assert_eq!(d.frame, frame(0x181, &[1, 2]));
        assert_eq!(d.source, a.id());
        assert!(ep.try_recv().is_none());
    }
    let counters = hub.counters();
    assert_eq!((counters.frames, counters.data_bytes), (1, 2));
    let sent: Vec<_> = counters
        .endpoints
        .iter()
        .map(|e| (e.sent, e.received))
        .collect();
    assert_eq!(sent, [(1, 0), (0, 1), (0, 1)]);
}

#[test]
fn receive_own_is_optional() {
    let hub = virtual_hub();
    let mut a = hub.attach(EndpointOptions::new("a").receive_own(true));
    let mut b = hub.attach(EndpointOptions::new("b"));
    a.send(frame(1, &[])).unwrap();
    assert_eq!(a.try_recv().unwrap().source, a.id());
    assert!(b.try_recv().is_some());
}

#[test]
fn a_slow_endpoint_loses_frames_and_the_sender_never_waits() {
    let hub = virtual_hub();
    let sender = hub.attach(EndpointOptions::new("fast sender"));
    let mut slow = hub.attach(EndpointOptions::new("slow").queue_capacity(4));
    let mut roomy = hub.attach(EndpointOptions::new("roomy").queue_capacity(100));
    for i in 0..10u8 {
        sender.send(frame(0x100, &[i])).unwrap();
    }
    let got: Vec<u8> = std::iter::from_fn(|| slow.try_recv())
        .map(|d| d.frame.data()[0])
        .collect();
    // The oldest frames stay (a full FIFO refuses new ones, as a CAN controller's does).
    assert_eq!(got, [0, 1, 2, 3]);
    assert_eq!(std::iter::from_fn(|| roomy.try_recv()).count(), 10);
    let c = hub.counters();
    assert_eq!(c.rx_dropped, 6);
    assert_eq!(c.endpoints[1].dropped, 6);
    assert_eq!(c.endpoints[2].dropped, 0);
}

#[test]
fn on_delivery_runs_for_each_frame_queued_for_that_endpoint_only() {
    use std::sync::atomic::{AtomicU64, Ordering};
    use std::sync::Arc;
    let hub = virtual_hub();
    let calls = Arc::new(AtomicU64::new(0));
    let c = Arc::clone(&calls);
    let mut polled = hub.attach(
        EndpointOptions::new("polled")
            .queue_capacity(2)
            .on_delivery(move || {
                c.fetch_add(1, Ordering::Relaxed);
            }),
    );
    let other = hub.attach(EndpointOptions::new("other"));
    other.send(frame(0x601, &[0x40])).unwrap();
    assert_eq!(calls.load(Ordering::Relaxed), 1);
    // Its own frames are not delivered to it, so they do not call it; nor do dropped ones.
    polled.send(frame(0x581, &[0x43])).unwrap();
    other.send(frame(0x601, &[0x40])).unwrap();
    other.send(frame(0x601, &[0x40])).unwrap(); // the queue holds 2: dropped
    assert_eq!(calls.load(Ordering::Relaxed), 2);
    assert_eq!(std::iter::from_fn(|| polled.try_recv()).count(), 2);
}

#[test]
fn dropping_the_receiver_detaches_the_endpoint() {
    let hub = virtual_hub();
    let a = hub.attach(EndpointOptions::new("a"));
    let b = hub.attach(EndpointOptions::new("b"));
    let (b_tx, b_rx) = b.split();
    drop(b_rx);
    assert_eq!(hub.counters().endpoints.len(), 1);
    // Its sender still sends.
    let mut a = a;
    b_tx.send(frame(2, &[])).unwrap();
    assert_eq!(a.try_recv().unwrap().source, b_tx.id());
}

#[test]
fn error_frames_are_counted_and_delivered() {
    let hub = virtual_hub();
    let a = hub.attach(EndpointOptions::new("controller"));
    let mut b = hub.attach(EndpointOptions::new("b"));
    a.send(WireFrame::error(0x4, &[0, 0x10]).unwrap()).unwrap();
    assert!(b.try_recv().unwrap().frame.is_error());
    assert_eq!(hub.counters().error_frames, 1);
}

fn modelled_hub(bitrate: u32) -> Hub {
    let timing = BitTiming::new(bitrate)
        .unwrap()
        .with_stuffing(Stuffing::WorstCase);
    Hub::new(
        HubConfig::new("vcan0")
            .with_clock(Clock::Virtual)
            .with_timing(timing)
            .with_queue_capacity(10_000),
    )
}

#[test]
fn with_the_model_frames_arrive_in_arbitration_order_when_their_transmission_ends() {
    let hub = modelled_hub(1_000_000);
    let a = hub.attach(EndpointOptions::new("a"));
    let b = hub.attach(EndpointOptions::new("b"));
    let mut rx = hub.attach(EndpointOptions::new("rx"));
    a.send(frame(0x300, &[0; 8])).unwrap();
    b.send(frame(0x080, &[0; 8])).unwrap();
    a.send(frame(0x200, &[0; 8])).unwrap();
    // Nothing has finished yet at t = 0.
    assert!(rx.try_recv().is_none());
    assert_eq!(
        hub.advance(Duration::from_micros(134)),
        Some(Duration::from_micros(135))
    );
    assert!(rx.try_recv().is_none());
    hub.advance(Duration::from_millis(1));
    let got: Vec<_> = std::iter::from_fn(|| rx.try_recv())
        .map(|d| (d.frame.id().raw(), d.at.as_micros()))
        .collect();
    // Worst-case 8-byte standard frames take 135 µs at 1 Mbit/s.
    assert_eq!(got, [(0x080, 135), (0x200, 270), (0x300, 405)]);
    let c = hub.counters();
    assert_eq!(c.latency_max, Duration::from_micros(405));
    assert_eq!(c.busy, Duration::from_micros(405));
    assert!(
        (c.load_percent() - 40.5).abs() < 1e-9,
        "{}",
        c.load_percent()
    );
}

#[test]
fn the_model_reproduces_bus_load_and_saturation() {
    // 125 kbit/s: a worst-case 8-byte standard frame takes 1.08 ms. Offer 500 frames/s of
    // them for one second (54 % load), then 2000 frames/s (beyond what the bus can carry).
    let hub = modelled_hub(125_000);
    let tx = hub.attach(EndpointOptions::new("tx"));
    let mut rx = hub.attach(EndpointOptions::new("rx"));
    let mut t = Duration::ZERO;
    for _ in 0..500 {
        tx.send(frame(0x181, &[0; 8])).unwrap();
        t += Duration::from_millis(2);
        hub.advance(t);
    }
    let first = hub.counters();
    assert_eq!(first.frames, 500);
    assert!(
        (first.load_percent() - 54.0).abs() < 0.1,
        "{}",
        first.load_percent()
    );
    assert!(first.latency_max <= Duration::from_micros(1080));
    for _ in 0..1000 {
        tx.send(frame(0x181, &[0; 8])).unwrap();
        t += Duration::from_micros(500);
        hub.advance(t);
    }
    let second = hub.counters();
    // The bus is saturated: ~463 frames/s carried in that 0.5 s, the rest still queued.
    let carried = second.frames - first.frames;
    assert!((460..=464).contains(&carried), "{carried}");
    assert!(second.load_percent_since(&first) > 99.5);
    assert_eq!(second.pending as u64, 1000 - carried);
    assert_eq!(
        std::iter::from_fn(|| rx.try_recv()).count() as u64,
        second.frames
    );
}

#[test]
fn the_candump_log_records_every_frame_with_bus_stamps() {
    let dir = std::env::temp_dir().join(format!("mcemu-can-log-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bus.log");
    let hub = Hub::new(
        HubConfig::new("vcan0")
            .with_clock(Clock::Virtual)
            .with_epoch(Duration::from_secs(1_700_000_000)),
    );
    hub.start_log(CandumpLog::create(&path, hub.name(), 64).unwrap());
    let a = hub.attach(EndpointOptions::new("a"));
    hub.advance(Duration::from_micros(123_456));
    a.send(frame(0x123, &[0xDE, 0xAD, 0xBE, 0xEF])).unwrap();
    a.send(WireFrame::extended(0x1234_5678, &[]).unwrap())
        .unwrap();
    let summary = hub.stop_log().unwrap().unwrap();
    assert_eq!(summary.lines, 2);
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        text,
        "(1700000000.123456) vcan0 123#DEADBEEF\n(1700000000.123456) vcan0 12345678#\n"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[tokio::test]
async fn async_receivers_wake_on_frames() {
    let hub = Hub::new(HubConfig::new("vcan0"));
    let a = hub.attach(EndpointOptions::new("a"));
    let (_b_tx, mut b_rx) = hub.attach(EndpointOptions::new("b")).split();
    let reader = tokio::spawn(async move {
        let mut ids = vec![];
        while ids.len() < 3 {
            ids.push(b_rx.recv().await.unwrap().frame.id().raw());
        }
        ids
    });
    tokio::task::yield_now().await;
    for id in [1, 2, 3] {
        a.send(frame(id, &[])).unwrap();
    }
    assert_eq!(reader.await.unwrap(), [1, 2, 3]);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_realtime_driver_delivers_modelled_frames() {
    let timing = BitTiming::new(10_000).unwrap(); // 10 kbit/s: a frame takes milliseconds
    let hub = Hub::new(HubConfig::new("can0").with_timing(timing));
    let driver = tokio::spawn({
        let hub = hub.clone();
        async move { hub.drive_realtime().await }
    });
    let a = hub.attach(EndpointOptions::new("a"));
    let mut b = hub.attach(EndpointOptions::new("b"));
    let sent_at = hub.now();
    a.send(frame(0x100, &[0; 8])).unwrap();
    let d = tokio::time::timeout(Duration::from_secs(2), b.recv())
        .await
        .unwrap()
        .unwrap();
    // 135 bits at 10 kbit/s = 13.5 ms of bus time, from an idle bus.
    assert!(d.at - sent_at >= Duration::from_micros(13_500));
    assert_eq!(hub.counters().latency_max, Duration::from_micros(13_500));
    assert!(hub.now() >= d.at);
    driver.abort();
}
