//! Support paths at their place: the hands on a steering wheel (an upper-body path) and the feet
//! on the floor (a lower-body one), planted by the truth bench's own forms.

use wbv::diagnosis::diagnose;
use wbv::gap_bench::case::{CaseOptions, make_case_with};
use wbv::model::catalog;

#[test]
fn hands_on_a_wheel_are_named_an_upper_body_path_and_legs_still_a_lower_one() {
    // The truth bench's forms, not a candidate's: the hands on a steering wheel (upper arms and
    // forearms split off the upper torso, gripping a wheel on a compliant column) and the feet on
    // the floor (thighs and lower legs off the pelvis). With a head channel and the seat-pan
    // force, a path into the shoulders shapes seat→head and one into the pelvis the apparent
    // mass, so each is named at its own place in the support-path family, not only in the family —
    // with the force plate and, by seat→head alone, without it.
    use wbv::gap_bench::forms::Form;
    let model = catalog::resolve("reference").unwrap();
    for (form, expect, force) in [
        (Form::Hands, &["hands-support"][..], true),
        (Form::Legs, &["feet-support", "thigh-support"][..], true),
        (Form::Hands, &["hands-support"][..], false),
        (Form::Legs, &["feet-support", "thigh-support"][..], false),
    ] {
        let case = make_case_with(
            6,
            3,
            &CaseOptions {
                effects: Some(vec![(form, 0.7)]),
                spectrum: Some("white"),
                fs_hz: Some(500.0),
                duration_s: Some(120.0),
                noise: Some(0.01),
                force: Some(force),
                ..CaseOptions::default()
            },
        )
        .unwrap();
        let d = diagnose(&model, &case.train, &case.check).unwrap();
        let named = d.verdict.effect().map_or("", |c| c.id);
        assert!(
            expect.contains(&named),
            "{form:?} ({}): {} — {}",
            case.label.effects[0].detail,
            d.verdict,
            d.verdict_text
        );
        // A named model within reach of the noise carries its ISO figures' standard errors, and
        // the report prints them beside a_w and SEAT.
        let st = d.named_stage().expect("a named stage");
        assert!(
            st.chi2_red <= wbv::diagnosis::EXPLAINED_CHI2,
            "{}",
            st.chi2_red
        );
        let sigma = st
            .iso_sigma
            .expect("σ of a fitted model within the noise's reach");
        assert!(
            sigma.aw_percent > 0.0 && sigma.aw_percent < 1.0 && sigma.seat_points > 0.0,
            "{sigma:?}"
        );
        let line = format!(
            "{:+.1} ± {:.2} %",
            st.weighted.aw_gap_percent, sigma.aw_percent
        );
        assert!(wbv::diagnosis::report::text(&d).contains(&line), "{line}");
        assert!(d.verdict_text.contains(&line), "{line}: {}", d.verdict_text);
    }
}
