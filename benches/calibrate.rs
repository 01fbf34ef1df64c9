//! GA with paper 000's settings (population 200, 300 generations) on a 4-parameter fit of the
//! `reference` model's seat transmissibility (60 target frequencies, 1–15 Hz). Requirement: < 30 s on
//! the 2-core development machine.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wbv::model::catalog;
use wbv::response::frf;
use wbv::study::calibrate::{Method, Problem, Target, calibrate, ga};
use wbv::study::param::Param;

fn problem() -> Problem {
    let truth = catalog::resolve("reference").unwrap();
    let freq = frf::grid(1.0, 15.0, 60, false).unwrap();
    let mag = frf::compute(truth.system(), &freq)
        .unwrap()
        .get("seat")
        .unwrap()
        .magnitude();
    let fitted = [
        ("link.cushion.k", 20_000.0, 300_000.0, 50_000.0),
        ("link.cushion.c", 100.0, 3_000.0, 900.0),
        ("link.k4.k", 30_000.0, 300_000.0, 60_000.0),
        ("link.k4.c", 500.0, 6_000.0, 3_000.0),
    ];
    let mut start = truth.clone();
    for (p, _, _, v) in fitted {
        start.set(p, v).unwrap();
    }
    Problem {
        params: fitted
            .iter()
            .map(|f| Param::parse(f.0, &start).unwrap())
            .collect(),
        bounds: fitted.iter().map(|f| (f.1, f.2)).collect(),
        model: start,
        response: "seat".into(),
        target: Target {
            freq_hz: freq,
            mag,
            phase_deg: None,
            weight: None,
        },
    }
}

fn bench(c: &mut Criterion) {
    let p = problem();
    let mut g = c.benchmark_group("calibrate");
    g.sample_size(10);
    g.bench_function("ga_paper000_4_params_reference", |b| {
        b.iter(|| black_box(calibrate(&p, Method::Ga(ga::Settings::paper(1))).unwrap()))
    });
    g.bench_function("lm_4_params_reference", |b| {
        b.iter(|| black_box(calibrate(&p, Method::Lm).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
