//! `wbv gap` with an instrumented backrest (`f_back_z`, the backrest's vertical force): what a
//! backrest study adds to the z-only channels. A weak backrest that the z-only channels cannot
//! tell from the base model's own parameter freedom (the re-fitted model fits them within the
//! noise) is named once its force is measured, since a model without a backrest predicts none.
//! The truth is the bench's chain edit (a standard linear solid and a lumbar contact), not the
//! candidate's form (a spring–damper with a Maxwell arm on the upper torso).

use wbv::diagnosis::{diagnose, report};
use wbv::gap_bench::case::{CaseOptions, make_case_with};
use wbv::gap_bench::forms::Form;
use wbv::model::catalog;

fn case(index: usize, backrest_force: bool) -> wbv::gap_bench::case::Case {
    make_case_with(
        index,
        3,
        &CaseOptions {
            effects: Some(vec![(Form::Backrest, 0.05)]),
            spectrum: Some("road"),
            fs_hz: Some(500.0),
            duration_s: Some(90.0),
            force: Some(false),
            base_floor: Some(0.0),
            backrest_force: Some(backrest_force),
            ..CaseOptions::default()
        },
    )
    .unwrap()
}

#[test]
fn a_measured_backrest_force_names_a_backrest_the_z_only_channels_cannot_see() {
    let model = catalog::resolve("reference").unwrap();
    for index in 0..2 {
        // z-only: the re-fitted base model already fits within the noise, so nothing is named.
        let c = case(index, false);
        assert!(c.check.get("f_back_z").is_none());
        let d = diagnose(&model, &c.train, &c.check).unwrap();
        assert!(
            d.null.check.chi2_red <= 1.0,
            "z-only null {}",
            d.null.check.chi2_red
        );
        assert_eq!(d.verdict.as_str(), "none", "{}", d.verdict_text);

        // The same seat with its backrest force measured.
        let c = case(index, true);
        assert!(c.check.get("f_back_z").is_some());
        let d = diagnose(&model, &c.train, &c.check).unwrap();
        assert_eq!(d.verdict.as_str(), "backrest", "{}", d.verdict_text);
        // Without a backrest the model's backrest force is a 100 % gap on every coherent bin.
        assert!(
            d.null.check.chi2_red > 100.0,
            "null {}",
            d.null.check.chi2_red
        );
        let named = d.named_stage().unwrap();
        assert!(named.chi2_red < 2.0, "backrest {}", named.chi2_red);
        // The path is judged, and its gap map has cells once a backrest predicts a force.
        assert!(
            named
                .cells
                .iter()
                .any(|c| c.path == "backrest-mass" && c.trusted)
        );
        assert!(!(d.null.check.cells.iter()).any(|c| c.path == "backrest-mass" && c.trusted));
        let json = serde_json::to_string(&report::json(&d)).unwrap();
        assert!(
            !json.contains("NaN") && !json.contains("null,\"phase"),
            "{json}"
        );
        let text = report::text(&d);
        assert!(text.contains("backrest-mass"), "{text}");
    }
}
