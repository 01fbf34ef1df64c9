//! `wbv gap` under a base accelerometer's noise floor (docs/gap.md §3, `diagnosis::input_noise`):
//! runs come from the truth bench's case generator, whose acquisition adds the floor and shares no
//! code with the estimator.

use wbv::diagnosis::{VerdictId, diagnose};
use wbv::gap_bench::case::{CaseOptions, make_case_with};
use wbv::model::catalog;

#[test]
fn a_base_accelerometer_floor_under_a_road_spectrum_is_no_effect() {
    // Clean road runs at 200 Hz with a force plate and a white floor of 4 % of the base r.m.s. on
    // the base accelerometer (the bench's acquisition, which shares no code with the estimator):
    // H1 from the base reads low where the road's motion falls under the floor. Before the floor
    // was put on the prediction these three were named `sensor-mount-base`.
    let model = catalog::resolve("reference").unwrap();
    for i in 0..3 {
        let case = make_case_with(
            i,
            31,
            &CaseOptions {
                effects: Some(Vec::new()),
                spectrum: Some("road"),
                fs_hz: Some(200.0),
                force: Some(true),
                base_floor: Some(0.04),
                ..CaseOptions::default()
            },
        )
        .unwrap();
        let d = diagnose(&model, &case.train, &case.check).unwrap();
        assert_eq!(d.verdict, VerdictId::None, "case {i}: {}", d.verdict_text);
        // The floor is found: the report says from where it biases H1.
        assert!(
            d.runs
                .iter()
                .all(|r| r.base_floor.0 > 0.0 && r.base_floor.1.is_some()),
            "{:?}",
            d.runs.iter().map(|r| r.base_floor).collect::<Vec<_>>()
        );
    }
}
