//! Frames per second through the hub, beside baselines measured in the same run
//! (ARCHITECTURE §7):
//!
//! - `fanout/hub/N`: one endpoint sends 1000 frames, N − 1 endpoints drain them (one thread,
//!   `try_recv`); `fanout/mpsc/N`: the same frames through N − 1 bare bounded tokio mpsc
//!   channels (what the hub does per frame, without its lock, counters and bookkeeping);
//!   `fanout/broadcast/N`: tokio's broadcast channel.
//! - `fanout/hub-model/N`: the hub with the 1 Mbit/s bit-rate model on a virtual clock.
//! - `async/hub` and `async/mpsc`: 10 000 frames from a sending thread to 4 receiving tokio
//!   tasks on a 2-thread runtime, until every task has them all.
//! - `socketcand/encode` and `socketcand/decode`: 1000 frames to `< frame … >` text, and 1000
//!   `< send … >` commands parsed; baselines: the candump text of the same frames, and only
//!   splitting the same bytes at `>`.
//!
//! Run: `cargo bench -p mcemu-can --bench hub`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use mcemu_can::socketcand::codec::encode_frame;
use mcemu_can::socketcand::Decoder;
use mcemu_can::{
    BitTiming, Clock, Delivery, EndpointOptions, Hub, HubConfig, Timestamp, WireFrame,
};
use tokio::sync::{broadcast, mpsc};

const BATCH: usize = 1000;

fn frames(n: usize) -> Vec<WireFrame> {
    (0..n)
        .map(|i| {
            let i = i as u32;
            if i % 4 == 3 {
                WireFrame::extended(0x1000_0000 | i, &i.to_le_bytes()).unwrap()
            } else {
                WireFrame::standard((0x180 + i % 0x600) as u16, &[i as u8; 8]).unwrap()
            }
        })
        .collect()
}

fn fanout(c: &mut Criterion) {
    let batch = frames(BATCH);
    let mut group = c.benchmark_group("fanout");
    group.throughput(Throughput::Elements(BATCH as u64));
    for n in [2usize, 8, 32] {
        let hub = Hub::new(HubConfig::new("vcan0").with_clock(Clock::Virtual));
        let sender = hub.attach(EndpointOptions::new("sender"));
        let mut receivers: Vec<_> = (1..n)
            .map(|i| hub.attach(EndpointOptions::new(format!("rx {i}")).queue_capacity(BATCH)))
            .collect();
        group.bench_with_input(BenchmarkId::new("hub", n), &n, |b, _| {
            b.iter(|| {
                for frame in &batch {
                    sender.send(*frame).unwrap();
                }
                for rx in &mut receivers {
                    while let Some(d) = rx.try_recv() {
                        black_box(d);
                    }
                }
            })
        });
        assert_eq!(hub.counters().rx_dropped, 0);

        let model_hub = Hub::new(
            HubConfig::new("vcan0")
                .with_clock(Clock::Virtual)
                .with_timing(BitTiming::new(1_000_000).unwrap()),
        );
        let model_sender = model_hub.attach(EndpointOptions::new("sender"));
        let mut model_receivers: Vec<_> = (1..n)
            .map(|i| {
                model_hub.attach(EndpointOptions::new(format!("rx {i}")).queue_capacity(BATCH))
            })
            .collect();
        let mut now = Duration::ZERO;
        group.bench_with_input(BenchmarkId::new("hub-model", n), &n, |b, _| {
            b.iter(|| {
                for frame in &batch {
                    model_sender.send(*frame).unwrap();
                }
                now += Duration::from_secs(1); // ample bus time for 1000 frames
                model_hub.advance(now);
                for rx in &mut model_receivers {
                    while let Some(d) = rx.try_recv() {
                        black_box(d);
                    }
                }
            })
        });
        assert_eq!(model_hub.counters().rx_dropped, 0);

        let (txs, mut rxs): (Vec<_>, Vec<_>) =
            (1..n).map(|_| mpsc::channel::<Delivery>(BATCH)).unzip();
        let source = hub.attach(EndpointOptions::new("id source")).id();
        group.bench_with_input(BenchmarkId::new("mpsc", n), &n, |b, _| {
            b.iter(|| {
                for frame in &batch {
                    let delivery = Delivery {
                        frame: *frame,
                        at: Duration::ZERO,
                        source,
                    };
                    for tx in &txs {
                        tx.try_send(delivery).unwrap();
                    }
                }
                for rx in &mut rxs {
                    while let Ok(d) = rx.try_recv() {
                        black_box(d);
                    }
                }
            })
        });

        let (btx, _) = broadcast::channel::<Delivery>(BATCH);
        let mut brxs: Vec<_> = (1..n).map(|_| btx.subscribe()).collect();
        group.bench_with_input(BenchmarkId::new("broadcast", n), &n, |b, _| {
            b.iter(|| {
                for frame in &batch {
                    let _ = btx.send(Delivery {
                        frame: *frame,
                        at: Duration::ZERO,
                        source,
                    });
                }
                for rx in &mut brxs {
                    while let Ok(d) = rx.try_recv() {
                        black_box(d);
                    }
                }
            })
        });
    }
    group.finish();
}

const ASYNC_FRAMES: usize = 10_000;
const ASYNC_RECEIVERS: usize = 4;

fn cross_thread(c: &mut Criterion) {
    let batch = frames(ASYNC_FRAMES);
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .build()
        .unwrap();
    let mut group = c.benchmark_group("async");
    group.throughput(Throughput::Elements(ASYNC_FRAMES as u64));
    group.sample_size(20);
    group.bench_function("hub", |b| {
        b.iter(|| {
            let hub = Hub::new(HubConfig::new("vcan0").with_queue_capacity(ASYNC_FRAMES));
            let sender = hub.attach(EndpointOptions::new("sender"));
            let tasks: Vec<_> = (0..ASYNC_RECEIVERS)
                .map(|i| {
                    let (_, mut rx) = hub.attach(EndpointOptions::new(format!("rx {i}"))).split();
                    runtime.spawn(async move {
                        for _ in 0..ASYNC_FRAMES {
                            black_box(rx.recv().await.unwrap());
                        }
                    })
                })
                .collect();
            for frame in &batch {
                sender.send(*frame).unwrap();
            }
            for task in tasks {
                runtime.block_on(task).unwrap();
            }
        })
    });
    group.bench_function("mpsc", |b| {
        let source = Hub::new(HubConfig::new("ids"))
            .attach(EndpointOptions::new("id"))
            .id();
        b.iter(|| {
            let (txs, rxs): (Vec<_>, Vec<_>) = (0..ASYNC_RECEIVERS)
                .map(|_| mpsc::channel::<Delivery>(ASYNC_FRAMES))
                .unzip();
            let tasks: Vec<_> = rxs
                .into_iter()
                .map(|mut rx| {
                    runtime.spawn(async move {
                        for _ in 0..ASYNC_FRAMES {
                            black_box(rx.recv().await.unwrap());
                        }
                    })
                })
                .collect();
            for frame in &batch {
                let delivery = Delivery {
                    frame: *frame,
                    at: Duration::ZERO,
                    source,
                };
                for tx in &txs {
                    tx.try_send(delivery).unwrap();
                }
            }
            for task in tasks {
                runtime.block_on(task).unwrap();
            }
        })
    });
    group.finish();
}

fn socketcand_codec(c: &mut Criterion) {
    let batch = frames(BATCH);
    let stamp = Timestamp {
        secs: 1_700_000_000,
        micros: 123_456,
    };
    let mut group = c.benchmark_group("socketcand");
    group.throughput(Throughput::Elements(BATCH as u64));
    let mut out = String::with_capacity(64 * BATCH);
    group.bench_function("encode", |b| {
        b.iter(|| {
            out.clear();
            for frame in &batch {
                encode_frame(&mut out, stamp, frame);
            }
            black_box(out.len())
        })
    });
    group.bench_function("encode-baseline-candump-text", |b| {
        use std::fmt::Write;
        b.iter(|| {
            out.clear();
            for frame in &batch {
                let _ = write!(out, "({stamp}) vcan0 {frame}");
            }
            black_box(out.len())
        })
    });
    let commands: String = batch
        .iter()
        .map(|f| {
            let bytes: Vec<String> = f.data().iter().map(|b| format!("{b:02X}")).collect();
            format!("< send {} {} {} >", f.id(), f.dlc(), bytes.join(" "))
        })
        .collect();
    let bytes = commands.as_bytes();
    group.bench_function("decode", |b| {
        b.iter(|| {
            let mut decoder = Decoder::new();
            let mut n = 0;
            decoder.decode(bytes, |c| {
                black_box(c.unwrap());
                n += 1;
            });
            assert_eq!(n, BATCH);
        })
    });
    group.bench_function("decode-baseline-split-only", |b| {
        b.iter(|| {
            let n = bytes
                .split(|&b| b == b'>')
                .filter(|e| !e.is_empty())
                .map(black_box)
                .count();
            assert_eq!(n, BATCH);
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = fanout, cross_thread, socketcand_codec
}
criterion_main!(benches);
