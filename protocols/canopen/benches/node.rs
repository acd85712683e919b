//! SDO block transfers of 100 kB through the in-process bus, beside a baseline measured in the
//! same run: routing the same number of frames to the same node when they are not for it (the
//! cost of the bus and the node's dispatch without the SDO server).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mcemu_canopen::bus::{sample_dictionary, Bus};
use mcemu_canopen::client::SdoClient;
use mcemu_canopen::{CanFrame, Node, NodeConfig};

const SIZE: usize = 100_000;

fn bus() -> Bus {
    let mut bus = Bus::new();
    bus.add(
        Node::new(
            NodeConfig {
                node_id: 1,
                ..NodeConfig::default()
            },
            sample_dictionary(),
        )
        .unwrap(),
    );
    bus.start();
    bus
}

/// Frames of a 100 kB block download: initiate, 14 286 segments, one ack per 127, end.
fn download_frames() -> u64 {
    let segments = SIZE.div_ceil(7) as u64;
    2 * 2 + segments + segments.div_ceil(127)
}

fn transfers(c: &mut Criterion) {
    let data: Vec<u8> = (0..SIZE).map(|i| i as u8).collect();
    let frames = download_frames();
    let mut group = c.benchmark_group("sdo_block_100kB");
    group.throughput(Throughput::Elements(frames));
    group.sample_size(30);

    group.bench_function("baseline_route_frames_to_another_node", |b| {
        let mut bus = bus();
        let frame = CanFrame::new(0x602, &[1, 2, 3, 4, 5, 6, 7, 8]).unwrap();
        let mut seen = Vec::new();
        b.iter(|| {
            for _ in 0..frames {
                bus.send_into(black_box(frame), &mut seen);
            }
            seen.clear();
        });
    });

    group.bench_function("block_download", |b| {
        let mut bus = bus();
        let client = SdoClient::new(1);
        b.iter(|| {
            client
                .block_download(&mut bus, 0x2004, 0, black_box(&data), &[])
                .unwrap()
        });
    });

    group.bench_function("block_upload", |b| {
        let mut bus = bus();
        let client = SdoClient::new(1);
        client
            .block_download(&mut bus, 0x2004, 0, &data, &[])
            .unwrap();
        b.iter(|| black_box(client.block_upload(&mut bus, 0x2004, 0, 0).unwrap()));
    });
    group.finish();
}

criterion_group!(benches, transfers);
criterion_main!(benches);
