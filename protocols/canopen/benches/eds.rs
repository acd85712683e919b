// Benches fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! Loading `fixtures/canopen/cia402-drive.eds` (2 060 lines, 94 objects, 215 entries): parse and
//! check, then build the dictionary for a node, beside two baselines measured in the same run on
//! the same text:
//! - `baseline/line_split`: the INI floor — split into lines, trim, skip comments, split
//!   sections and `key=value` pairs into a vector, no lookups, no types;
//! - `baseline/rust_ini`: a general-purpose INI library (`rust-ini`) loading the same text into
//!   its maps, untyped.
//!
//! Run: `cargo bench -p mcemu-canopen --bench eds`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mcemu_canopen::eds::Eds;

const DRIVE: &str = include_str!("../../../fixtures/canopen/cia402-drive.eds");

/// The least any INI reader does: one pass over the lines.
fn line_split(text: &str) -> Vec<(&str, &str, &str)> {
    let mut section = "";
    let mut items = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with(';') {
            continue;
        }
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            section = name;
        } else if let Some((key, value)) = line.split_once('=') {
            items.push((section, key.trim(), value.trim()));
        }
    }
    items
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("eds");
    group.throughput(Throughput::Bytes(DRIVE.len() as u64));

    group.bench_function("baseline/line_split", |b| {
        b.iter(|| line_split(black_box(DRIVE)).len())
    });
    group.bench_function("baseline/rust_ini", |b| {
        b.iter(|| ini::Ini::load_from_str(black_box(DRIVE)).unwrap().len())
    });
    group.bench_function("parse", |b| {
        b.iter(|| Eds::parse("cia402-drive.eds", black_box(DRIVE)).unwrap())
    });
    let eds = Eds::parse("cia402-drive.eds", DRIVE).unwrap();
    group.bench_function("dictionary", |b| {
        b.iter(|| black_box(&eds).dictionary(black_box(5)).unwrap().len())
    });
    group.bench_function("parse+dictionary", |b| {
        b.iter(|| {
            Eds::parse("cia402-drive.eds", black_box(DRIVE))
                .unwrap()
                .dictionary(5)
                .unwrap()
                .len()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
