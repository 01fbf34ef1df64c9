//! Issue 38: design studies at interactive speed. One run measures, on `reference` under
//! `bell-214` through `study::sweep::run` (what `wbv sweep` runs; a 2-point response grid so the
//! ISO figures dominate):
//! - `per_point_1000x60s`: today's per-point path (`IsoRun`: every point builds its excitation,
//!   simulates and analyses every channel with the full report) — the baseline;
//! - `batched_1000x60s`: the batched time-domain path (`BatchIso`: one shared excitation, points
//!   stepped together, figures-only streaming analysis), a_w, a_v, SEAT, comfort, VDV, MTVV, crest;
//! - `spectral_100000`: the spectral path (`SpectralIso`) on 100 000 points, a_w, a_v, SEAT,
//!   comfort. Acceptance: both ≤ 5 s wall on the 2-core machine.
//!
//! `WBV_STUDY_BASELINE_POINTS` sets the baseline's points (default 1000).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use wbv::excitation::ExcitationSpec;
use wbv::integrator::Method;
use wbv::model::catalog;
use wbv::simulate::Settings;
use wbv::study::batch::BatchIso;
use wbv::study::iso::IsoRun;
use wbv::study::param::Param;
use wbv::study::shard::Shard;
use wbv::study::spectral::SpectralIso;
use wbv::study::sweep::{self, PointFigures, Spec};

fn spec(points: usize) -> Spec {
    let model = catalog::resolve("reference").unwrap();
    let values = (0..points)
        .map(|i| 40_000.0 + 80_000.0 * i as f64 / (points.max(2) - 1) as f64)
        .collect();
    Spec {
        params: vec![Param::parse("link.cushion.k", &model).unwrap()],
        values: vec![values],
        response: "seat".into(),
        freq_hz: vec![2.0, 4.0],
    }
}

fn bench(c: &mut Criterion) {
    let model = catalog::resolve("reference").unwrap();
    let run = IsoRun {
        excitation: ExcitationSpec::load("bell-214").unwrap(),
        settings: Settings {
            dt: 1e-3,
            duration_s: 60.0,
            method: Method::AVERAGE_ACCELERATION,
        },
        seed: 1,
    };
    let baseline_points: usize = std::env::var("WBV_STUDY_BASELINE_POINTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000);
    let sweep = |spec: &Spec, hook: &dyn PointFigures| {
        black_box(sweep::run(&model, spec, Shard::default(), &[hook], &|| {}).unwrap())
    };
    let mut g = c.benchmark_group("study");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(10));
    let base = spec(baseline_points);
    g.bench_function(format!("per_point_{baseline_points}x60s"), |b| {
        b.iter(|| sweep(&base, &run))
    });
    let thousand = spec(1000);
    g.bench_function("batched_1000x60s", |b| {
        // The shared excitation is drawn inside: it is part of the study's cost.
        b.iter(|| sweep(&thousand, &BatchIso::new(&run).unwrap()))
    });
    let many = spec(100_000);
    g.bench_function("spectral_100000", |b| {
        b.iter(|| sweep(&many, &SpectralIso::new(&model, &run.excitation).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
