//! Recording throughput of `McapRecorder` for the synthetic 5-mass layout at 1 kHz: steps/s per
//! compression (4 time-series messages per step + the 30 Hz scene), bytes per simulated second, and
//! the JSON float-formatting cost alone. Scale the per-step time by 3.6 M steps for one hour.
//!
//! `cargo bench --bench record`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use wbv::record::{Compression, McapRecorder, Overwrite, Provenance, RecordOptions, demo};

const FS: f64 = 1000.0;
const SECONDS: u64 = 10;

fn record(path: &std::path::Path, compression: Compression) {
    let options = RecordOptions {
        compression,
        overwrite: Overwrite::Allow,
        ..RecordOptions::default()
    };
    let mut rec = McapRecorder::create(path, Provenance::new(), options).expect("create");
    demo::drive(&mut rec, FS, SECONDS * 1000 + 1).expect("record");
}

fn bench_record(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut g = c.benchmark_group("record_10s_at_1kHz_5_masses");
    g.sample_size(10);
    g.throughput(Throughput::Elements(SECONDS * 1000 + 1));
    for compression in [Compression::Lz4, Compression::Zstd, Compression::None] {
        let path = dir.path().join(format!("{}.mcap", compression.as_str()));
        g.bench_function(compression.as_str(), |b| {
            b.iter(|| record(&path, compression))
        });
        let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        println!(
            "{}: {} bytes per simulated second ({:.2} GB per simulated hour)",
            compression.as_str(),
            bytes / SECONDS,
            bytes as f64 / SECONDS as f64 * 3600.0 / 1e9
        );
    }
    g.finish();

    // The synthetic state alone (what the recorder is fed), to subtract from the above.
    let mut g = c.benchmark_group("synthetic_steps_only");
    g.throughput(Throughput::Elements(1000));
    g.bench_function("1000_steps", |b| {
        b.iter(|| {
            for i in 0..1000 {
                black_box(demo::State::at(black_box(i), 1e-3));
            }
        })
    });
    g.finish();

    // JSON formatting cost: the 51 floats of one step with the formatter the recorder uses.
    let mut g = c.benchmark_group("json_floats");
    g.throughput(Throughput::Elements(51));
    let state = demo::State::at(1234, 1e-3);
    let values: Vec<f64> = (0..51)
        .map(|k| state.x[k % 5] * (1.0 + k as f64 * 1e-3))
        .collect();
    g.bench_function("51_floats_per_step", |b| {
        let mut out = Vec::with_capacity(4096);
        b.iter(|| {
            out.clear();
            for v in &values {
                use serde_json::ser::{CompactFormatter, Formatter};
                CompactFormatter.write_f64(&mut out, *v).expect("vec");
            }
            black_box(out.len())
        })
    });
    g.finish();
}

criterion_group!(benches, bench_record);
criterion_main!(benches);
