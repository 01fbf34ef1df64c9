//! Speed of one gap diagnosis (issue 15: ≤ 10 s): three 120 s runs at 500 Hz with the seat force,
//! a viscoelastic cushion planted (so candidates, statistical linearisation and the forward
//! selection all run), diagnosed against the nominal `reference` model; and the same with an
//! exponentially stiffening cushion, so the named effect's law is refined by replays and its ISO
//! figures come from a replay of the check run (issue 55, point 3).

use criterion::{Criterion, criterion_group, criterion_main};
use std::time::Duration;
use wbv::diagnosis::diagnose;
use wbv::gap_bench::case::{CaseOptions, make_case_with};
use wbv::gap_bench::forms::Form;
use wbv::model::catalog;

/// Three 120 s runs at 500 Hz with the seat force and `form` planted at `strength`.
fn case(form: Form, strength: f64) -> wbv::gap_bench::case::Case {
    make_case_with(
        1,
        1,
        &CaseOptions {
            effects: Some(vec![(form, strength)]),
            spectrum: Some("white"),
            fs_hz: Some(500.0),
            duration_s: Some(120.0),
            noise: Some(0.01),
            force: Some(true),
            ..CaseOptions::default()
        },
    )
    .expect("case")
}

fn gap(c: &mut Criterion) {
    let model = catalog::resolve("reference").expect("reference model");
    let mut g = c.benchmark_group("gap");
    g.sample_size(10).measurement_time(Duration::from_secs(60));
    for (name, form, strength) in [
        ("diagnose 3 × 120 s at 500 Hz", Form::Sls, 0.6),
        (
            "diagnose 3 × 120 s at 500 Hz, stiffening cushion (replays)",
            Form::Exponential,
            0.8,
        ),
    ] {
        let case = case(form, strength);
        g.bench_function(name, |b| {
            b.iter(|| diagnose(&model, &case.train, &case.check).expect("diagnosis"))
        });
    }
    g.finish();
}

criterion_group!(benches, gap);
criterion_main!(benches);
