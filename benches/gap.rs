//! Speed of one gap diagnosis (issue 15: ≤ 10 s): three 120 s runs at 500 Hz with the seat force,
//! a viscoelastic cushion planted (so candidates, statistical linearisation and the forward
//! selection all run), diagnosed against the nominal `reference` model.

use criterion::{Criterion, criterion_group, criterion_main};
use std::time::Duration;
use wbv::diagnosis::diagnose;
use wbv::gap_bench::case::{CaseOptions, make_case_with};
use wbv::gap_bench::forms::Form;
use wbv::model::catalog;

fn gap(c: &mut Criterion) {
    let case = make_case_with(
        1,
        1,
        &CaseOptions {
            effects: Some(vec![(Form::Sls, 0.6)]),
            spectrum: Some("white"),
            fs_hz: Some(500.0),
            duration_s: Some(120.0),
            noise: Some(0.01),
            force: Some(true),
            ..CaseOptions::default()
        },
    )
    .expect("case");
    let model = catalog::resolve("reference").expect("reference model");
    let mut g = c.benchmark_group("gap");
    g.sample_size(10).measurement_time(Duration::from_secs(60));
    g.bench_function("diagnose 3 × 120 s at 500 Hz", |b| {
        b.iter(|| diagnose(&model, &case.train, &case.check).expect("diagnosis"))
    });
    g.finish();
}

criterion_group!(benches, gap);
criterion_main!(benches);
