//! Welch PSD and Wk weighting of one hour at 1 kHz (3.6 M samples).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wbv::analysis::{Segment, Weighting, WeightingFilter, Welch, WelchOptions};

fn signal(n: usize) -> Vec<f64> {
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let fs = 1000.0;
    let x = signal(3_600_000);
    let mut g = c.benchmark_group("one hour at 1 kHz");
    g.sample_size(10);
    g.bench_function("welch psd (0.125 Hz, Hann, 50 %)", |b| {
        let opts = WelchOptions {
            segment: Segment::ResolutionHz(0.125),
            ..Default::default()
        };
        let mut w = Welch::new(fs, &opts).unwrap();
        b.iter(|| black_box(w.psd(black_box(&x)).unwrap()))
    });
    g.bench_function("Wk time-domain weighting", |b| {
        let f = WeightingFilter::new(Weighting::Wk, fs).unwrap();
        b.iter(|| black_box(f.apply(black_box(&x))))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
