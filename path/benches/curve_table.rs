//! What accepting a long spline costs the servo thread (`move_spline`, 1000 points of a tight
//! zigzag, the table's worst case): the curve's construction (lengths and bounds; the rows
//! wait for their first sample), beside the baseline of building every row as well (what
//! construction cost before the rows were built lazily), and one sample through a span not
//! yet built (the most a tick pays for the rows: a few spans at most per tick).
//!
//! `cargo bench -p path --bench curve_table -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use path::geometry::{Curve, Segment};
use path::Point;

fn zigzag(n: u32) -> Vec<Point> {
    (0..=n)
        .map(|i| {
            let mut p = [0.0; path::MAX_AXES];
            p[0] = f64::from(i);
            p[1] = if i % 2 == 0 { 0.0 } else { 1.0 };
            p
        })
        .collect()
}

/// Samples every span once, which builds all the rows.
fn build_all_rows(seg: &Segment, spans: u32) {
    let len = seg.length();
    for k in 0..spans {
        std::hint::black_box(seg.sample(len * (f64::from(k) + 0.5) / f64::from(spans)));
    }
}

fn bench_spline_table(c: &mut Criterion) {
    let points = zigzag(1000);
    let mut group = c.benchmark_group("spline_1000_zigzag");
    group.sample_size(10);
    group.bench_function("construct (on accept)", |b| {
        b.iter(|| Curve::spline(std::hint::black_box(&points), 2))
    });
    group.bench_function("baseline: construct + every row", |b| {
        b.iter(|| {
            let seg = Curve::spline(&points, 2).ok();
            if let Some(seg) = &seg {
                build_all_rows(seg, 1000);
            }
            seg
        })
    });
    group.bench_function("first sample in a span", |b| {
        b.iter_batched(
            || Curve::spline(&points, 2).ok(),
            |seg| seg.map(|s| s.sample(s.length() / 2.0)),
            BatchSize::LargeInput,
        )
    });
    group.finish();
}

criterion_group!(benches, bench_spline_table);
criterion_main!(benches);
