//! The decision's rule list in order, each rule on a fixture it decides.

use super::*;

/// The decision's rules in order, each with a fixture it decides: the verdict follows from the
/// rule's statement (docs/gap.md §7), and a rule added to [`Rule::ORDER`] without a fixture here
/// fails the test.
#[test]
fn every_rule_in_order_decides_its_fixture() {
    use crate::diagnosis::clock::ClockTrend;
    use crate::diagnosis::outcome::ChannelError;
    use crate::diagnosis::verdict::Shortfall;
    let held = |effect: &str| Verdict::Named {
        effect: c(effect),
        basis: Basis::HeldOut {
            tie: None,
            alternative: None,
        },
        second: None,
    };
    // The no-gap fixture: null 1.5 on the check run and nothing detected.
    let quiet = || {
        evidence(
            &ranked("null", 1.5, 1.5, 0.0, 0.0, 1.0),
            &[ranked("backrest", 1.4, 1.45, -3.0, -5.0, 0.1)],
        )
    };
    let fixtures: Vec<(Rule, Evidence, Verdict)> = vec![
        (
            Rule::RefittedOnAllRuns,
            {
                // The all-run judgement found a stiffening that the held-out run ranks second.
                let mut e = evidence(
                    &ranked("null", 5.0, 3.0, 0.0, 0.0, 1.0),
                    &[
                        ranked("cushion-viscoelastic", 4.5, 1.5, -30.0, -40.0, 0.75),
                        ranked("cushion-stiffening", 1.2, 2.5, -12.0, -300.0, 0.25),
                    ],
                );
                e.all_runs = Some(AllRuns {
                    candidate: c("cushion-stiffening"),
                    delta_bic: -300.0,
                    null_chi2_red: 4.0,
                    chi2_red: 1.5,
                });
                e
            },
            Verdict::Named {
                effect: c("cushion-stiffening"),
                basis: Basis::AllRuns { refitted: true },
                second: None,
            },
        ),
        (
            Rule::AmplitudeEffectOnAllRuns,
            evidence(
                // Nothing accepted on the check run; a softening detected on all runs.
                &ranked("null", 5.0, 1.5, 0.0, 0.0, 1.0),
                &[ranked("body-softening", 2.0, 1.4, -5.0, -80.0, 0.2)],
            ),
            Verdict::Named {
                effect: c("body-softening"),
                basis: Basis::AllRuns { refitted: false },
                second: None,
            },
        ),
        (
            Rule::LookAlikes,
            evidence(
                // Two families 0.3 apart on the check run and 3 on all runs.
                &ranked("null", 1.5, 1.2, 0.0, 0.0, 1.0),
                &[
                    ranked("sensor-delay", 1.1, 0.8, -24.0, -98.0, 0.33),
                    ranked("backrest", 0.9, 0.8, -23.7, -101.0, 0.44),
                ],
            ),
            Verdict::NotIdentifiable {
                a: c("sensor-delay"),
                b: c("backrest"),
                separating: separating_measurement(c("sensor-delay"), c("backrest")).to_string(),
            },
        ),
        (
            Rule::AcceptedOnHeldOut,
            evidence(
                // Detected at −40 and closing 60 % of the check run's structural gap.
                &ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0),
                &[
                    ranked("missing-dof", 1.5, 1.8, -40.0, -60.0, 0.6),
                    ranked("backrest", 2.5, 2.8, -12.0, -20.0, 0.1),
                ],
            ),
            held("missing-dof"),
        ),
        (
            Rule::DetectedButClosesLittle,
            evidence(
                // A structural gap, the best detected at −40 closing 10 %.
                &ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0),
                &[ranked("body-mode", 2.9, 2.8, -40.0, -41.0, 0.1)],
            ),
            Verdict::Unexplained,
        ),
        (Rule::NoStructuralGap, quiet(), Verdict::None),
        (
            Rule::NoCandidateClosesTheGap,
            evidence(
                // χ²/ν 40 with a 0.3 dB band gap, nothing detected.
                &ranked("null", 40.0, 40.0, 0.0, 0.0, 1.0),
                &[ranked("backrest", 39.0, 39.5, -3.0, -5.0, 0.01)],
            ),
            Verdict::Unexplained,
        ),
        (
            Rule::DistortionSite,
            {
                // The responses name a linear foam; the distortion grows between base and seat.
                let mut e = evidence(
                    &ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0),
                    &[
                        ranked("cushion-viscoelastic", 1.5, 1.8, -40.0, -60.0, 0.6),
                        ranked("cushion-contact", 2.0, 2.5, -12.0, -50.0, 0.25),
                        ranked("cushion-stiffening", 2.0, 2.5, -11.0, -55.0, 0.25),
                    ],
                );
                e.distortion = Some(located_at(Site::Support));
                e
            },
            Verdict::Named {
                effect: c("cushion-stiffening"),
                basis: Basis::Distortion {
                    responses: VerdictId::Effect(c("cushion-viscoelastic")),
                },
                second: None,
            },
        ),
        (
            Rule::ClockDrift,
            {
                // The responses name a delay; the lag moves between the runs' halves by 150 ± 2 ppm
                // and the drift is detected on the check run.
                let mut e = evidence(
                    &ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0),
                    &[
                        ranked("sensor-delay", 1.5, 1.8, -40.0, -60.0, 0.6),
                        ranked("logger-drift", 1.6, 1.9, -36.0, -58.0, 0.55),
                    ],
                );
                e.clock = Some(ClockTrend {
                    drift_ppm: 150.0,
                    sigma_ppm: 2.0,
                    runs: 3,
                });
                e
            },
            Verdict::Named {
                effect: c("logger-drift"),
                basis: Basis::Clock {
                    responses: VerdictId::Effect(c("sensor-delay")),
                },
                second: None,
            },
        ),
        (
            Rule::ExplainsOnlyInPart,
            evidence(
                // Accepted (closes 67 %) but the check run stays at χ²/ν 100, above EXPLAINED_CHI2.
                &ranked("null", 300.0, 300.0, 0.0, 0.0, 1.0),
                &[ranked("missing-dof", 100.0, 100.0, -4000.0, -5000.0, 0.67)],
            ),
            Verdict::Partial {
                best: c("missing-dof"),
                second: None,
                shortfall: Shortfall::FarAboveNoise { chi2_red: 100.0 },
            },
        ),
        (
            Rule::CalibrationFinding,
            {
                let mut e = quiet();
                e.channel_errors = vec![ChannelError {
                    channels: "a_seat_z".into(),
                    error: "inverted (gain −1)".into(),
                    factor: -1.0,
                    runs: vec!["run-1".into()],
                }];
                e
            },
            Verdict::Calibration(c("sensor-gain")),
        ),
    ];
    let order: Vec<Rule> = fixtures.iter().map(|(r, _, _)| *r).collect();
    assert_eq!(
        order,
        Rule::ORDER,
        "one fixture per rule, in the decision's order"
    );
    for (rule, e, want) in &fixtures {
        let d = decide(e);
        assert_eq!((&d.verdict, d.rule), (want, *rule), "{}", rule.name());
    }
    // The rule that decided is what the JSON's `decided_by` names.
    for r in Rule::ORDER {
        let json = serde_json::to_value(r).unwrap();
        assert_eq!(json, serde_json::json!(r.name()));
        assert_eq!(serde_json::from_value::<Rule>(json).unwrap(), r);
    }
}
