//! One frequency-domain FRF evaluation (every response of the 6-DOF paper-001 seat) on 1,000
//! frequencies, 0.1–100 Hz on a log grid.
//!
//! `cargo bench --bench response`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use wbv::model::catalog;
use wbv::response::frf;

fn bench(c: &mut Criterion) {
    let model = catalog::resolve("seed001-full").expect("built-in model");
    let freq = frf::grid(0.1, 100.0, 1000, true).expect("grid");
    let mut g = c.benchmark_group("frf_seed001_full");
    g.throughput(Throughput::Elements(freq.len() as u64));
    g.bench_function("1000_frequencies", |b| {
        b.iter(|| black_box(frf::compute(model.system(), black_box(&freq)).expect("frf")))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
