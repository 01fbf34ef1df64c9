//! `wbv gap` on a structure that lacks more than one mode: a seat frame with two modes (a pan on a
//! riser) planted by the truth bench's own chain edit, found as a frame mode plus a second frame
//! mode under it by forward selection, and explaining the check run once both are added.

use wbv::diagnosis::diagnose;
use wbv::gap_bench::case::{CaseOptions, make_case_with};
use wbv::gap_bench::forms::Form;
use wbv::model::catalog;

#[test]
fn a_two_mode_seat_frame_is_named_as_a_frame_mode_and_a_second_one_under_it() {
    let case = make_case_with(
        2,
        3,
        &CaseOptions {
            effects: Some(vec![(Form::FrameTwoMode, 0.6)]),
            spectrum: Some("white"),
            fs_hz: Some(500.0),
            duration_s: Some(90.0),
            noise: Some(0.01),
            force: Some(false),
            ..CaseOptions::default()
        },
    )
    .unwrap();
    let model = catalog::resolve("reference").unwrap();
    let d = diagnose(&model, &case.train, &case.check).unwrap();
    assert_eq!(d.verdict.as_str(), "missing-dof", "{}", d.verdict_text);
    assert_eq!(
        d.named,
        ["missing-dof", "missing-dof"],
        "{}",
        d.verdict_text
    );
    let one = d.candidates.iter().find(|c| c.id == "missing-dof").unwrap();
    let both = d.named_stage().unwrap();
    // One frame mode leaves a structural residual; the pair brings the check run near the noise.
    assert!(one.check.chi2_red > 5.0, "one mode: {}", one.check.chi2_red);
    assert!(both.chi2_red < 3.0, "two modes: {}", both.chi2_red);
    assert!(
        both.weighted.aw_gap_percent.abs() <= d.null.check.weighted.aw_gap_percent.abs() + 0.5,
        "{}",
        d.verdict_text
    );
    assert!(
        d.verdict_text.contains("a second mode of the frame"),
        "{}",
        d.verdict_text
    );
}
