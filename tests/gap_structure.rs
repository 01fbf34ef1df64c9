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
        d.named.iter().map(|c| c.id).collect::<Vec<_>>(),
        ["missing-dof", "missing-dof"],
        "{}",
        d.verdict_text
    );
    let one = d
        .candidates
        .iter()
        .find(|c| c.id.to_string() == "missing-dof")
        .unwrap();
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
        d.verdict_text
            .contains("a second missing-dof (more than one mode of the structure"),
        "{}",
        d.verdict_text
    );
}

/// A frame that rocks on unequal legs (the pan on a front and a rear member, the truth bench's own
/// chain edit): vertical channels see frame modes, so the family is missing-dof, and the named
/// model brings the check run's a_w at least as near the measurement as the re-fitted base model.
#[test]
fn a_rocking_seat_frame_is_named_a_missing_mode_and_closes_the_check_run() {
    let case = make_case_with(
        5,
        7,
        &CaseOptions {
            effects: Some(vec![(Form::RockingFrame, 0.7)]),
            spectrum: Some("road"),
            fs_hz: Some(400.0),
            duration_s: Some(90.0),
            noise: Some(0.01),
            force: Some(true),
            ..CaseOptions::default()
        },
    )
    .unwrap();
    assert!(
        case.label.effects[0]
            .detail
            .starts_with("rocking seat frame")
    );
    let model = catalog::resolve("reference").unwrap();
    let d = diagnose(&model, &case.train, &case.check).unwrap();
    assert_eq!(d.verdict.as_str(), "missing-dof", "{}", d.verdict_text);
    let named = d.named_stage().unwrap();
    assert!(named.chi2_red < 3.0, "{}", d.verdict_text);
    assert!(
        named.weighted.aw_gap_percent.abs() <= d.null.check.weighted.aw_gap_percent.abs() + 0.5,
        "{}",
        d.verdict_text
    );
}

/// A two-mode frame (pan on riser) measured through a 4-pole anti-alias low-pass on one channel:
/// three effects, two of them frame modes. Forward selection goes on past the pair while the
/// stack leaves a structural residual, so the named model holds all three and explains the check
/// run, which the pair alone cannot.
#[test]
fn a_two_mode_frame_behind_a_low_pass_is_named_with_both_modes_and_the_filter() {
    let case = make_case_with(
        4,
        11,
        &CaseOptions {
            effects: Some(vec![(Form::FrameTwoMode, 0.6), (Form::LowPass, 0.8)]),
            spectrum: Some("white"),
            fs_hz: Some(500.0),
            duration_s: Some(90.0),
            noise: Some(0.01),
            force: Some(false),
            ..CaseOptions::default()
        },
    )
    .unwrap();
    let planted: Vec<&str> = case
        .label
        .effects
        .iter()
        .map(|e| e.detail.as_str())
        .collect();
    let model = catalog::resolve("reference").unwrap();
    let d = diagnose(&model, &case.train, &case.check).unwrap();
    let named: Vec<&str> = d.named.iter().map(|c| c.id).collect();
    assert_eq!(named.len(), 3, "{planted:?}: {}", d.verdict_text);
    assert_eq!(
        named.iter().filter(|&&c| c == "missing-dof").count(),
        2,
        "{planted:?}: {}",
        d.verdict_text
    );
    assert!(
        named.iter().any(|c| c.starts_with("sensor-lowpass")),
        "{planted:?}: {}",
        d.verdict_text
    );
    let stack = d.second.as_ref().unwrap();
    assert_eq!(stack.id.candidates().len(), 3);
    assert!(stack.check.chi2_red < 3.0, "{}", d.verdict_text);
    assert!(d.verdict_text.contains("and a third"), "{}", d.verdict_text);
}
