//! The decision's rule list in order, each rule on a fixture it decides.

use super::*;
use crate::diagnosis::clock::ClockTrend;
use crate::diagnosis::outcome::ChannelError;
use crate::diagnosis::verdict::Shortfall;

/// `effect` named on the held-out check run, with no tie and no second effect.
fn held(effect: &str) -> Verdict {
    Verdict::Named {
        effect: c(effect),
        basis: Basis::HeldOut {
            tie: None,
            alternative: None,
        },
        added: Vec::new(),
    }
}

/// The no-gap evidence: null 1.5 on the check run and nothing detected.
fn quiet() -> Evidence {
    evidence(
        &ranked("null", 1.5, 1.5, 0.0, 0.0, 1.0),
        &[ranked("backrest", 1.4, 1.45, -3.0, -5.0, 0.1)],
    )
}

/// The all-run judgement found a stiffening that the held-out run ranks second.
fn refitted_on_all_runs() -> (Evidence, Verdict) {
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
    let v = Verdict::Named {
        effect: c("cushion-stiffening"),
        basis: Basis::AllRuns { refitted: true },
        added: Vec::new(),
    };
    (e, v)
}

/// Nothing accepted on the check run; a softening detected on all runs.
fn amplitude_effect_on_all_runs() -> (Evidence, Verdict) {
    let e = evidence(
        &ranked("null", 5.0, 1.5, 0.0, 0.0, 1.0),
        &[ranked("body-softening", 2.0, 1.4, -5.0, -80.0, 0.2)],
    );
    let v = Verdict::Named {
        effect: c("body-softening"),
        basis: Basis::AllRuns { refitted: false },
        added: Vec::new(),
    };
    (e, v)
}

/// Two families 0.3 apart on the check run and 3 on all runs.
fn look_alikes() -> (Evidence, Verdict) {
    let e = evidence(
        &ranked("null", 1.5, 1.2, 0.0, 0.0, 1.0),
        &[
            ranked("sensor-delay", 1.1, 0.8, -24.0, -98.0, 0.33),
            ranked("backrest", 0.9, 0.8, -23.7, -101.0, 0.44),
        ],
    );
    let v = Verdict::NotIdentifiable {
        a: c("sensor-delay"),
        b: c("backrest"),
        separating: separating_measurement(c("sensor-delay"), c("backrest")).to_string(),
    };
    (e, v)
}

/// Detected at −40 and closing 60 % of the check run's structural gap.
fn accepted_on_held_out() -> (Evidence, Verdict) {
    let e = evidence(
        &ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0),
        &[
            ranked("missing-dof", 1.5, 1.8, -40.0, -60.0, 0.6),
            ranked("backrest", 2.5, 2.8, -12.0, -20.0, 0.1),
        ],
    );
    (e, held("missing-dof"))
}

/// A structural gap, the best detected at −40 closing 10 %.
fn detected_but_closes_little() -> (Evidence, Verdict) {
    let e = evidence(
        &ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0),
        &[ranked("body-mode", 2.9, 2.8, -40.0, -41.0, 0.1)],
    );
    (e, Verdict::Unexplained)
}

/// χ²/ν 40 with a 0.3 dB band gap, nothing detected.
fn no_candidate_closes_the_gap() -> (Evidence, Verdict) {
    let e = evidence(
        &ranked("null", 40.0, 40.0, 0.0, 0.0, 1.0),
        &[ranked("backrest", 39.0, 39.5, -3.0, -5.0, 0.01)],
    );
    (e, Verdict::Unexplained)
}

/// The responses name a linear foam; the distortion grows between base and seat.
fn distortion_site() -> (Evidence, Verdict) {
    let mut e = evidence(
        &ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0),
        &[
            ranked("cushion-viscoelastic", 1.5, 1.8, -40.0, -60.0, 0.6),
            ranked("cushion-contact", 2.0, 2.5, -12.0, -50.0, 0.25),
            ranked("cushion-stiffening", 2.0, 2.5, -11.0, -55.0, 0.25),
        ],
    );
    e.distortion = Some(located_at(Site::Support));
    let v = Verdict::Named {
        effect: c("cushion-stiffening"),
        basis: Basis::Distortion {
            responses: VerdictId::Effect(c("cushion-viscoelastic")),
        },
        added: Vec::new(),
    };
    (e, v)
}

/// The responses name a head mount (χ²/ν 41.8 on the check run); the distortion grows on the
/// support, where a lap belt's linearisation leaves 130 but its replay 31.
fn replayed_at_site() -> (Evidence, Verdict) {
    let (e, _) = strap_behind_a_mount(31.0);
    let v = Verdict::Named {
        effect: c("lap-belt"),
        basis: Basis::Replayed {
            responses: VerdictId::Effect(c("sensor-mount-head")),
        },
        added: Vec::new(),
    };
    (e, v)
}

/// The responses name a delay; the lag moves between the runs' halves by 150 ± 2 ppm and the
/// drift is detected on the check run.
fn clock_drift() -> (Evidence, Verdict) {
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
    let v = Verdict::Named {
        effect: c("logger-drift"),
        basis: Basis::Clock {
            responses: VerdictId::Effect(c("sensor-delay")),
        },
        added: Vec::new(),
    };
    (e, v)
}

/// Accepted (closes 67 %) but the check run stays at χ²/ν 100, above EXPLAINED_CHI2.
fn explains_only_in_part() -> (Evidence, Verdict) {
    let e = evidence(
        &ranked("null", 300.0, 300.0, 0.0, 0.0, 1.0),
        &[ranked("missing-dof", 100.0, 100.0, -4000.0, -5000.0, 0.67)],
    );
    let v = Verdict::Partial {
        best: c("missing-dof"),
        added: Vec::new(),
        shortfall: Shortfall::FarAboveNoise { chi2_red: 100.0 },
    };
    (e, v)
}

/// A quiet case whose seat accelerometer reads inverted on one run.
fn calibration_finding() -> (Evidence, Verdict) {
    let mut e = quiet();
    e.channel_errors = vec![ChannelError {
        channels: "a_seat_z".into(),
        error: "inverted (gain −1)".into(),
        factor: -1.0,
        runs: vec!["run-1".into()],
    }];
    (e, Verdict::Calibration(c("sensor-gain")))
}

/// Each rule's fixture: the evidence it decides and the verdict that follows from the rule's
/// statement (docs/gap.md §7). The match is exhaustive, so a new rule needs a fixture to compile.
fn fixture(rule: Rule) -> (Evidence, Verdict) {
    match rule {
        Rule::RefittedOnAllRuns => refitted_on_all_runs(),
        Rule::AmplitudeEffectOnAllRuns => amplitude_effect_on_all_runs(),
        Rule::LookAlikes => look_alikes(),
        Rule::AcceptedOnHeldOut => accepted_on_held_out(),
        Rule::DetectedButClosesLittle => detected_but_closes_little(),
        Rule::NoStructuralGap => (quiet(), Verdict::None),
        Rule::NoCandidateClosesTheGap => no_candidate_closes_the_gap(),
        Rule::DistortionSite => distortion_site(),
        Rule::ReplayedAtSite => replayed_at_site(),
        Rule::ClockDrift => clock_drift(),
        Rule::ExplainsOnlyInPart => explains_only_in_part(),
        Rule::CalibrationFinding => calibration_finding(),
    }
}

/// Every rule in [`Rule::ORDER`] decides its own fixture: no earlier rule takes it, and the rule
/// gives the verdict its statement says.
#[test]
fn every_rule_in_order_decides_its_fixture() {
    for rule in Rule::ORDER {
        let (e, want) = fixture(rule);
        let d = decide(&e);
        assert_eq!((&d.verdict, d.rule), (&want, rule), "{}", rule.name());
    }
}

/// The rule that decided is what the JSON's `decided_by` names, and it reads back.
#[test]
fn decided_by_names_the_rule() {
    for r in Rule::ORDER {
        let json = serde_json::to_value(r).unwrap();
        assert_eq!(json, serde_json::json!(r.name()));
        assert_eq!(serde_json::from_value::<Rule>(json).unwrap(), r);
    }
}
