//! Each rule on a hand-made evidence fixture whose expected verdict follows from the rule's
//! statement, and the rule list's order on the cases where two rules meet.

use super::*;
use crate::diagnosis::all_runs::AllRuns;
use crate::diagnosis::candidate::{Candidate, from_id};
use crate::diagnosis::distortion::{Distortion, Site};
use crate::diagnosis::gapmap::Weighted;
use crate::diagnosis::outcome::{Effects, Stage, VerdictId};
use crate::diagnosis::verdict::{Decision, Rule, decide, held_out_accepted};

/// The candidate called `id`.
fn c(id: &str) -> Candidate {
    from_id(id).expect(id)
}

/// The entry of `id` (`null` or a candidate).
fn effects(id: &str) -> Effects {
    if id == "null" {
        Effects::Null
    } else {
        Effects::One(c(id))
    }
}

/// A ranked entry with the figures the rules read (sizes 2 % / 2 points).
fn ranked(id: &str, train: f64, check: f64, dbic: f64, dbic_all: f64, closed: f64) -> Ranked {
    Ranked {
        id: effects(id),
        params: Vec::new(),
        train_chi2_red: train,
        delta_bic: dbic,
        delta_bic_all: dbic_all,
        probability: 0.0,
        fraction_closed: closed,
        check: Stage {
            iso_sigma: None,
            replayed_chi2_red: None,
            chi2_red: check,
            residuals: 2000,
            gap_db_rms: 0.3,
            phase_deg_rms: 1.0,
            weighted: Weighted {
                aw_seat_meas: 1.0,
                aw_seat_model: 1.0,
                aw_gap_percent: 0.0,
                seat_meas: 80.0,
                seat_model: 80.0,
                driving_bands: Vec::new(),
                replayed: false,
            },
            cells: Vec::new(),
        },
        aw_change_percent: 2.0,
        seat_change_points: 2.0,
        band_gap_change_db: -0.1,
    }
}

/// The evidence of `null` and `cands` with the held-out acceptance the diagnosis computes.
fn evidence(null: &Ranked, cands: &[Ranked]) -> Evidence {
    Evidence {
        null: null.clone(),
        cands: cands.to_vec(),
        accepted: held_out_accepted(null, cands).cloned(),
        all_runs: None,
        distortion: None,
        clock: None,
        added: None,
        channel_errors: Vec::new(),
    }
}

/// The verdict and its sentence.
fn judged(e: &Evidence) -> (Verdict, String) {
    let d = decide(e);
    let t = crate::diagnosis::text::sentence(&d, e);
    (d.verdict, t)
}

/// The sentence of verdict `v` decided by `rule` on `e`.
fn sentence(v: &Verdict, rule: Rule, e: &Evidence) -> String {
    let d = Decision {
        verdict: v.clone(),
        rule,
        set_aside: None,
        caveat: None,
        calibration: None,
    };
    crate::diagnosis::text::sentence(&d, e)
}

fn named(c: Candidate) -> impl Fn(&Verdict) -> bool {
    move |v| v.effect() == Some(c)
}

#[test]
fn the_rule_list_ends_in_a_rule_that_always_applies() {
    let null = ranked("null", 1.0, 1.0, 0.0, 0.0, 1.0);
    let e = evidence(&null, &[]);
    let (rule, apply) = RULES.last().expect("rules");
    assert_eq!(rule.name(), "no-candidate-closes-the-gap");
    assert_eq!(apply(&e), Some(Verdict::Unexplained));
}

#[test]
fn refitted_on_all_runs_names_the_all_run_judgement() {
    // The all-run judgement found a cushion stiffening; the held-out best is a viscoelastic foam
    // that the check run accepts. The re-fit on all runs is the stronger evidence for an effect
    // that changes with magnitude: it is named, and the held-out best is mentioned.
    let null = ranked("null", 5.0, 3.0, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("cushion-viscoelastic", 4.5, 1.5, -30.0, -40.0, 0.75),
        ranked("cushion-stiffening", 1.2, 2.5, -12.0, -300.0, 0.25),
    ];
    let all = AllRuns {
        candidate: c("cushion-stiffening"),
        delta_bic: -300.0,
        null_chi2_red: 4.0,
        chi2_red: 1.5,
    };
    let mut e = evidence(&null, &cands);
    e.all_runs = Some(all);
    assert!(refitted_on_all_runs(&e).is_some_and(|v| named(c("cushion-stiffening"))(&v)));
    let (v, text) = judged(&e);
    assert_eq!(
        v,
        Verdict::Named {
            effect: c("cushion-stiffening"),
            basis: Basis::AllRuns { refitted: true },
            added: Vec::new()
        }
    );
    // (4 − 1.5)/(4 − 1) = 83 %.
    assert!(
        text.contains("closes 83 % of their structural gap"),
        "{text}"
    );
    assert!(
        text.contains("the held-out run's best, cushion-viscoelastic"),
        "{text}"
    );
    // Without an all-run judgement the rule does not apply.
    assert_eq!(refitted_on_all_runs(&evidence(&null, &cands)), None);
}

#[test]
fn amplitude_effect_on_all_runs_needs_detection_and_a_share_of_the_training_gap() {
    // Nothing accepted on the check run (ΔBIC −5). A body softening detected on all runs (−80),
    // closing (5 − 2)/(5 − 1) = 75 % of the training gap and no worse on the check run, is named.
    let null = ranked("null", 5.0, 1.5, 0.0, 0.0, 1.0);
    let cands = vec![ranked("body-softening", 2.0, 1.4, -5.0, -80.0, 0.2)];
    let e = evidence(&null, &cands);
    assert!(e.accepted.is_none());
    assert_eq!(
        amplitude_effect_on_all_runs(&e),
        Some(Verdict::Named {
            effect: c("body-softening"),
            basis: Basis::AllRuns { refitted: false },
            added: Vec::new()
        })
    );
    // Not detected on all runs (−8 > −10): the rule does not apply.
    let weak = vec![ranked("body-softening", 2.0, 1.4, -5.0, -8.0, 0.2)];
    assert_eq!(amplitude_effect_on_all_runs(&evidence(&null, &weak)), None);
    // Worse on the check run (1.6 > 1.5, and above the noise): not named.
    let worse = vec![ranked("body-softening", 2.0, 1.6, -5.0, -80.0, 0.0)];
    assert_eq!(amplitude_effect_on_all_runs(&evidence(&null, &worse)), None);
    // A linear effect with the same figures is the same at every magnitude: not named here.
    let linear = vec![ranked("cushion-viscoelastic", 2.0, 1.4, -5.0, -80.0, 0.2)];
    assert_eq!(
        amplitude_effect_on_all_runs(&evidence(&null, &linear)),
        None
    );
}

#[test]
fn a_sensor_effect_is_named_on_the_held_out_run_only() {
    // Training residue 5 (structural), check run 1.5; the sensor gain closes a fifth of the
    // check run's gap (not accepted there) but most of the training runs' and has the best
    // all-run ΔBIC: the all-run evidence names the stiffening cushion, never the sensor.
    let null = ranked("null", 5.0, 1.5, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("sensor-gain", 3.0, 1.40, -42.0, -173.0, 0.20),
        ranked("cushion-stiffening", 3.5, 1.45, -38.0, -104.0, 0.20),
    ];
    let e = evidence(&null, &cands);
    assert!(e.accepted.is_none());
    let (v, text) = judged(&e);
    assert!(named(c("cushion-stiffening"))(&v), "{text}");
    // A linear effect is the same at every magnitude: the held-out run's word stands.
    let mut linear = cands.clone();
    linear[1].id = effects("cushion-viscoelastic");
    let (v, text) = judged(&evidence(&null, &linear));
    assert!(!named(c("cushion-viscoelastic"))(&v), "{text}");
    // Accepted on the held-out run (closes 30 % there), the sensor gain is named.
    let mut cands = cands;
    cands[0].fraction_closed = 0.30;
    let (v, text) = judged(&evidence(&null, &cands));
    assert!(named(c("sensor-gain"))(&v), "{text}");
}

#[test]
fn look_alikes_of_two_families_are_not_identifiable() {
    // Two families 0.3 apart on the held-out run (within 6) and 3 apart on all runs (within 6):
    // neither run set separates them.
    let null = ranked("null", 1.5, 1.2, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("sensor-delay", 1.1, 0.8, -24.0, -98.0, 0.33),
        ranked("backrest", 0.9, 0.8, -23.7, -101.0, 0.44),
    ];
    let e = evidence(&null, &cands);
    let v = look_alikes(&e).expect("a tie");
    assert_eq!(v.id(), VerdictId::NotIdentifiable);
    assert_eq!(
        v,
        Verdict::NotIdentifiable {
            a: c("sensor-delay"),
            b: c("backrest"),
            separating: separating_measurement(c("sensor-delay"), c("backrest")).to_string(),
        }
    );
    assert!(v.separating().is_some_and(|m| m.contains("shaker run")));
    // The same family 0.3 apart is one effect in two forms: no tie.
    let same = vec![
        ranked("sensor-delay", 1.1, 0.8, -24.0, -98.0, 0.33),
        ranked("sensor-lowpass", 0.9, 0.8, -23.7, -101.0, 0.44),
    ];
    assert_eq!(look_alikes(&evidence(&null, &same)), None);
    let (v, text) = judged(&evidence(&null, &same));
    assert!(named(c("sensor-delay"))(&v), "{text}");
    assert!(
        text.contains("sensor-lowpass fits almost as well"),
        "{text}"
    );
}

#[test]
fn a_support_path_close_to_another_names_what_tells_their_places_apart() {
    // Hands on a wheel and feet on the floor within 6 of each other: one family, so named, and the
    // note says the place is uncertain and which measurement would tell.
    let null = ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("hands-support", 1.2, 1.3, -50.0, -80.0, 0.7),
        ranked("feet-support", 1.2, 1.35, -47.0, -78.0, 0.68),
    ];
    let (v, text) = judged(&evidence(&null, &cands));
    assert!(named(c("hands-support"))(&v), "{text}");
    assert!(
        text.contains("feet-support fits almost as well: where the path enters the body is uncertain; to tell, a head accelerometer with the seat-pan force"),
        "{text}"
    );
}

#[test]
fn accepted_on_held_out_names_a_detected_effect_that_closes_a_quarter_of_the_gap() {
    // Null 3.0 on the check run, best detected at −40 closing 60 %: named on the held-out run.
    let null = ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("missing-dof", 1.5, 1.8, -40.0, -60.0, 0.6),
        ranked("backrest", 2.5, 2.8, -12.0, -20.0, 0.1),
    ];
    let e = evidence(&null, &cands);
    let v = accepted_on_held_out(&e).expect("accepted");
    assert_eq!(
        v,
        Verdict::Named {
            effect: c("missing-dof"),
            basis: Basis::HeldOut {
                tie: None,
                alternative: None
            },
            added: Vec::new()
        }
    );
    let text = sentence(&v, Rule::AcceptedOnHeldOut, &e);
    assert!(
        text.contains("closes 60 % of the structural gap on the held-out run"),
        "{text}"
    );
    // Closing 20 % of a structural gap is not an explanation: the rule does not apply.
    let mut little = cands.clone();
    little[0].fraction_closed = 0.2;
    assert_eq!(accepted_on_held_out(&evidence(&null, &little)), None);
}

#[test]
fn detected_but_closes_little_reports_the_gap_unexplained() {
    // A structural gap (3.0 > 2) and a best detected at −40 that closes 10 %: unexplained, the
    // detected candidate mentioned.
    let null = ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0);
    let cands = vec![ranked("body-mode", 2.9, 2.8, -40.0, -41.0, 0.1)];
    let e = evidence(&null, &cands);
    assert_eq!(detected_but_closes_little(&e), Some(Verdict::Unexplained));
    let (v, text) = judged(&e);
    assert_eq!(v, Verdict::Unexplained);
    assert!(
        text.contains("body-mode is detected (ΔBIC -40.0) but closes only 10 %"),
        "{text}"
    );
    // Below the structural threshold (1.8 ≤ 2) it is not a gap to explain: the rule stands back.
    let small = ranked("null", 1.8, 1.8, 0.0, 0.0, 1.0);
    assert_eq!(detected_but_closes_little(&evidence(&small, &cands)), None);
}

#[test]
fn no_structural_gap_is_none() {
    // Null 1.5 on the check run (≤ 2) and nothing detected: none.
    let null = ranked("null", 1.5, 1.5, 0.0, 0.0, 1.0);
    let cands = vec![ranked("backrest", 1.4, 1.45, -3.0, -5.0, 0.1)];
    let e = evidence(&null, &cands);
    assert_eq!(no_structural_gap(&e), Some(Verdict::None));
    // A reduced χ² of 40 on noise-free data with a 0.1 dB, 1° gap is of no practical size.
    let mut clean = ranked("null", 40.0, 40.0, 0.0, 0.0, 1.0);
    clean.check.gap_db_rms = 0.1;
    clean.check.phase_deg_rms = 1.0;
    assert_eq!(
        no_structural_gap(&evidence(&clean, &cands)),
        Some(Verdict::None)
    );
    // The same χ² with a 0.3 dB gap is a gap: the rule does not apply, the last one does.
    let gap = ranked("null", 40.0, 40.0, 0.0, 0.0, 1.0);
    assert_eq!(no_structural_gap(&evidence(&gap, &cands)), None);
    assert_eq!(
        decide(&evidence(&gap, &cands)).verdict,
        Verdict::Unexplained
    );
}

#[test]
fn within_the_noise_a_detected_effect_is_named_however_little_it_closes() {
    // The null fits the check run within the noise (0.41); a backrest is detected at ΔBIC −35
    // (beyond the within-noise threshold −30) and lowers χ² by 23 %. There is no structural gap
    // to close: detection names it.
    let null = ranked("null", 0.42, 0.41, 0.0, 0.0, 1.0);
    let mut cands = vec![ranked("backrest", 0.29, 0.31, -35.0, -167.8, 0.23)];
    cands[0].aw_change_percent = 0.5;
    cands[0].seat_change_points = 0.6;
    cands[0].band_gap_change_db = -0.0;
    let (v, text) = judged(&evidence(&null, &cands));
    assert!(named(c("backrest"))(&v), "{text}");
    assert!(text.contains("practically small"), "{text}");
    assert!(
        text.contains("within the noise after the re-fit, by 24 % (0.41 → 0.31)"),
        "{text}"
    );
    // Detected at the usual −10 but not at −30 (ΔBIC −27.4): within the noise that is what clean
    // field-like cases reach, so nothing significant, `none`.
    cands[0].delta_bic = -27.4;
    let e = evidence(&null, &cands);
    assert!(e.accepted.is_none());
    assert_eq!(decide(&e).verdict, Verdict::None);
    // Above the noise the fraction of the gap rules: 23 % of a gap of 1.6 is not named.
    let gap = ranked("null", 1.7, 1.6, 0.0, 0.0, 1.0);
    cands[0].delta_bic = -35.0;
    assert!(held_out_accepted(&gap, &cands).is_none());
    // A null at χ²/ν 1.03 on 2 000 residuals is within χ²'s own scatter (√(2/n) = 0.03) of the
    // noise: a mount detected at ΔBIC −23.5 that takes it to 0.98 meets −30, not −10, and is not
    // named (blind field seed 21, case 010, a cubic cushion). At 1.2 the gap is real and −10 with
    // the fraction closed rules.
    let edge = ranked("null", 1.03, 1.03, 0.0, 0.0, 1.0);
    let mount = vec![ranked("sensor-mount-seat", 0.98, 0.98, -23.5, -111.0, 1.0)];
    assert!(held_out_accepted(&edge, &mount).is_none());
    let above = ranked("null", 1.2, 1.2, 0.0, 0.0, 1.0);
    assert!(held_out_accepted(&above, &mount).is_some());
}

#[test]
fn the_overdispersion_of_a_margin_counts_the_training_runs_misfit() {
    // Both candidates close all of the check run's gap and leave χ²/ν 3.9 there but 24–25 on the
    // training runs. 36 units apart on the check run is 1.4 ĉ of the training misfit: a tie that
    // all runs (828 apart, 35 ĉ) decide.
    let null = ranked("null", 13_154.0, 979.5, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked(
            "sensor-mount-base",
            24.8,
            3.86,
            -524_892.3,
            -13_102_329.0,
            1.0,
        ),
        ranked(
            "suspension-friction",
            23.9,
            3.93,
            -524_856.5,
            -13_103_157.3,
            1.0,
        ),
    ];
    let (v, text) = judged(&evidence(&null, &cands));
    assert!(named(c("suspension-friction"))(&v), "{text}");
    assert!(
        text.contains("on all runs together suspension-friction is ahead"),
        "{text}"
    );
}

#[test]
fn a_held_out_tie_is_decided_by_all_runs_only_when_they_separate_it() {
    // Two families within the identifiability margin on the held-out run, 41 apart on all runs.
    let null = ranked("null", 1.5, 1.2, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("sensor-delay", 1.1, 0.8, -24.0, -98.0, 0.33),
        ranked("backrest", 0.9, 0.8, -23.7, -139.0, 0.44),
    ];
    let (v, text) = judged(&evidence(&null, &cands));
    assert!(
        matches!(
            v,
            Verdict::Named {
                effect,
                basis: Basis::HeldOut {
                    tie: Some(tie),
                    ..
                },
                ..
            } if effect == c("backrest") && tie == c("sensor-delay")
        ),
        "{text}"
    );
    assert!(
        text.contains("on all runs together backrest is ahead"),
        "{text}"
    );
    // The held-out run's best ahead on all runs as well keeps its name, the rival noted.
    let ahead = vec![
        ranked("backrest", 0.9, 0.8, -24.0, -139.0, 0.44),
        ranked("sensor-delay", 1.1, 0.8, -23.7, -98.0, 0.33),
    ];
    let (v, text) = judged(&evidence(&null, &ahead));
    assert!(named(c("backrest"))(&v), "{text}");
    assert!(text.contains("sensor-delay fits almost as well"), "{text}");
    // A misfit both share (χ²/ν 25 on the held-out run, 24 on training) makes a 15-unit
    // held-out difference a tie that all runs, 870 apart (36 ĉ), decide.
    let poor = ranked("null", 600.0, 500.0, 0.0, 0.0, 1.0);
    let big = vec![
        ranked("sensor-delay", 25.0, 25.0, -533_636.0, -14_203_707.0, 0.997),
        ranked("backrest", 24.0, 25.1, -533_621.0, -14_204_576.0, 0.997),
    ];
    let (v, text) = judged(&evidence(&poor, &big));
    assert!(named(c("backrest"))(&v), "{text}");
    // Unscaled, 15 units would have named the held-out run's best.
    let mut fit = big.clone();
    for c in &mut fit {
        c.check.chi2_red = 1.0;
        c.train_chi2_red = 1.0;
    }
    let (v, text) = judged(&evidence(&poor, &fit));
    assert!(named(c("sensor-delay"))(&v), "{text}");
}

/// A distortion trend that locates a nonlinearity at `site`.
fn located_at(site: Site) -> Distortion {
    Distortion {
        magnitudes: (0.4, 1.6),
        paths: Vec::new(),
        site: Some(site),
        phase_stays: None,
        site_in_model: false,
    }
}

/// A lap belt behind a head mount, as a strong strap leaves them: the mount fits the check run to
/// χ²/ν 41.8 (ΔBIC −22 000); the belt's statistical linearisation leaves 130 (ΔBIC −4 000) and
/// its replay `replayed`; the distortion grows on the support. The evidence, and the verdict so
/// far.
fn strap_behind_a_mount(replayed: f64) -> (Evidence, Verdict) {
    let mut belt = ranked("lap-belt", 60.0, 130.0, -4000.0, -12900.0, 0.2);
    belt.check.replayed_chi2_red = Some(replayed);
    let mut e = evidence(
        &ranked("null", 100.0, 104.7, 0.0, 0.0, 1.0),
        &[
            ranked("sensor-mount-head", 40.0, 41.8, -22000.0, -80000.0, 0.6),
            ranked("body-mode", 45.0, 49.0, -19500.0, -62600.0, 0.54),
            belt,
        ],
    );
    e.distortion = Some(located_at(Site::Support));
    let responses = Verdict::Named {
        effect: c("sensor-mount-head"),
        basis: Basis::HeldOut {
            tie: None,
            alternative: None,
        },
        added: Vec::new(),
    };
    (e, responses)
}

#[test]
fn a_one_sided_path_is_judged_by_its_replay_where_the_distortion_places_it() {
    // Replayed, the belt leaves 31 against the mount's 41.8: 2 000 residuals × 10.8 / ĉ 31 ≈ 700
    // BIC units, far past the margin: the belt is named on the simulator's opinion.
    let (e, responses) = strap_behind_a_mount(31.0);
    assert_eq!(to_replay(&e, &responses), vec![c("lap-belt")]);
    let (v, text) = judged(&e);
    assert_eq!(v.effect(), Some(c("lap-belt")), "{text}");
    assert!(text.contains("acts on one side only"), "{text}");
    assert!(
        text.contains("reduced χ² of 31.0") && text.contains("sensor-mount-head, leaves (41.8)"),
        "{text}"
    );
    // Replayed no better than the mount's linear fit: the responses' verdict stands.
    let (e, _) = strap_behind_a_mount(41.8);
    assert_eq!(judged(&e).0.effect(), Some(c("sensor-mount-head")));
    // With no distortion there is nothing to replay and nothing to judge.
    let (mut e, responses) = strap_behind_a_mount(31.0);
    e.distortion = None;
    assert!(to_replay(&e, &responses).is_empty());
    assert_eq!(judged(&e).0.effect(), Some(c("sensor-mount-head")));
    // A verdict at the site already (the distortion's own candidate) is not second-guessed.
    let (e, _) = strap_behind_a_mount(31.0);
    let at_site = Verdict::Named {
        effect: c("cushion-contact"),
        basis: Basis::HeldOut {
            tie: None,
            alternative: None,
        },
        added: Vec::new(),
    };
    assert!(to_replay(&e, &at_site).is_empty());
    assert!(replayed(&e, &at_site).is_none());
}

/// Forward selection's pair of `first` and `added` whose linearised fit leaves `chi2` on the
/// check run.
fn pair_leaving(first: &str, added: &str, chi2: f64) -> crate::diagnosis::select::Added {
    let mut entry = ranked(first, chi2, chi2, -500.0, -500.0, 0.5);
    entry.id = Effects::Pair(c(first), c(added));
    crate::diagnosis::select::Added {
        first: c(first),
        added: vec![c(added)],
        entry,
        // The rules read the entry only; the fit is the corrected model's.
        fit: crate::numeric::lm::Fit {
            u: Vec::new(),
            cost: 0.0,
            sigma_u: Vec::new(),
            covariance: None,
            scale: 1.0,
            evaluations: 0,
        },
    }
}

#[test]
fn a_second_effect_is_kept_only_where_the_pair_beats_the_named_effects_replay() {
    // The belt, named on its replay (31), with a pair whose linearised fit leaves 47.5: the pair
    // explains less than the belt alone as the simulator judges it, so the belt stands alone.
    let (mut e, _) = strap_behind_a_mount(31.0);
    e.added = Some(pair_leaving("lap-belt", "sensor-mount-head", 47.5));
    let d = decide(&e);
    assert_eq!(d.verdict.effect(), Some(c("lap-belt")));
    assert!(d.verdict.added().is_empty(), "{:?}", d.verdict);
    // A pair that leaves less than the belt's replay is a second effect.
    e.added = Some(pair_leaving("lap-belt", "sensor-mount-head", 20.0));
    let d = decide(&e);
    assert_eq!(d.verdict.added(), [c("sensor-mount-head")]);
    // A pair of another effect than the one named is never taken.
    e.added = Some(pair_leaving("body-mode", "sensor-mount-head", 5.0));
    assert!(decide(&e).verdict.added().is_empty());
}

#[test]
fn the_distortion_names_the_site_s_nonlinearity_over_a_linear_verdict() {
    // The responses name a viscoelastic foam (linear), the distortion grows on the support: the
    // support's nonlinear candidate with the lowest all-run BIC is named on the distortion.
    let dist = located_at(Site::Support);
    let null = ranked("null", 3.0, 3.0, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("cushion-viscoelastic", 1.5, 1.8, -40.0, -60.0, 0.6),
        ranked("cushion-contact", 2.0, 2.5, -12.0, -50.0, 0.25),
        ranked("cushion-stiffening", 2.0, 2.5, -11.0, -55.0, 0.25),
    ];
    let mut e = evidence(&null, &cands);
    e.distortion = Some(dist.clone());
    let responses = RULES.iter().find_map(|(_, apply)| apply(&e)).unwrap();
    assert!(named(c("cushion-viscoelastic"))(&responses));
    assert_eq!(
        located(&e, &responses),
        Some(Verdict::Named {
            effect: c("cushion-stiffening"),
            basis: Basis::Distortion {
                responses: VerdictId::Effect(c("cushion-viscoelastic"))
            },
            added: Vec::new()
        })
    );
    // A sensor effect coexists with a structural nonlinearity: it stands.
    let sensor = Verdict::Named {
        effect: c("sensor-delay"),
        basis: Basis::HeldOut {
            tie: None,
            alternative: None,
        },
        added: Vec::new(),
    };
    assert_eq!(located(&e, &sensor), None);
    // Unless its evidence is marginal: the null fits the check run within the noise (χ²/ν 0.9 on
    // 2000 residuals) and the sensor effect is practically small there (a_w 0.1 %, SEAT 0.1
    // points): the distortion's site is named over it.
    let within = ranked("null", 3.0, 0.9, 0.0, 0.0, 1.0);
    let mut small = ranked("sensor-delay", 1.5, 0.85, -37.0, -130.0, 0.1);
    (small.aw_change_percent, small.seat_change_points) = (0.1, 0.1);
    let marginal = vec![small, cands[1].clone(), cands[2].clone()];
    let mut m = evidence(&within, &marginal);
    m.distortion = Some(dist.clone());
    let v = located(&m, &sensor).expect("renamed");
    assert!(named(c("cushion-stiffening"))(&v), "{v:?}");
    // The same sensor effect at its full size (a_w 2 %) stands.
    let mut full = marginal.clone();
    full[0].aw_change_percent = 2.0;
    let mut m = evidence(&within, &full);
    m.distortion = Some(dist.clone());
    assert_eq!(located(&m, &sensor), None);
    // Without a located site there is no second opinion.
    e.distortion = None;
    assert_eq!(located(&e, &responses), None);
}

#[test]
fn a_friction_named_on_the_responses_stands_against_a_body_site() {
    let dist = located_at(Site::Body);
    let null = ranked("null", 3.0, 1.6, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("suspension-friction", 1.3, 1.1, -44.0, -257.0, 0.34),
        ranked("body-softening", 2.9, 1.6, 4.9, 6.3, 0.0),
    ];
    let held = |c| Verdict::Named {
        effect: c,
        basis: Basis::HeldOut {
            tie: None,
            alternative: None,
        },
        added: Vec::new(),
    };
    let mut e = evidence(&null, &cands);
    e.distortion = Some(dist.clone());
    assert_eq!(located(&e, &held(c("suspension-friction"))), None);
    // The same figures for a cushion stiffening: the body site renames it.
    let mut stiff = cands.clone();
    stiff[0].id = effects("cushion-stiffening");
    let mut e = evidence(&null, &stiff);
    e.distortion = Some(dist.clone());
    let v = located(&e, &held(c("cushion-stiffening"))).expect("renamed");
    assert!(named(c("body-softening"))(&v));
    // A friction the site's best fits as well as (within 6 ĉ over all runs) is renamed too.
    let mut close = cands.clone();
    close[1].delta_bic_all = -255.0;
    let mut e = evidence(&null, &close);
    e.distortion = Some(dist.clone());
    let v = located(&e, &held(c("suspension-friction"))).expect("renamed");
    assert!(named(c("body-softening"))(&v));
}

#[test]
fn docs_gap_md_lists_the_rules_in_their_order() {
    let doc = std::fs::read_to_string("docs/gap.md").expect("docs/gap.md");
    let section = &doc[doc.find("## 7 The verdict rules").expect("§7")..];
    let mut at = 0;
    for r in Rule::ORDER {
        let i = section[at..]
            .find(&format!("**{}**", r.name()))
            .unwrap_or_else(|| {
                panic!("docs/gap.md §7 lacks rule {} after position {at}", r.name())
            });
        at += i + r.name().len();
    }
}

mod order;
mod shortfall;

#[test]
fn the_distortion_names_a_support_path_only_where_all_runs_and_the_held_out_run_support_it() {
    // Responses name a foam; the distortion grows on the support. Feet that lift off fit all runs
    // worse than the null (ΔBIC +7.9) yet better than the cushion's stiffening (+14): the
    // distortion locates a law, not a second load path, so the cushion's law is named.
    let null = ranked("null", 1.0, 1.0, 0.0, 0.0, 1.0);
    let cands = vec![
        ranked("cushion-viscoelastic", 1.0, 1.0, -2.0, -72.0, 0.9),
        ranked("feet-lift-off", 1.1, 1.1, 25.6, 7.9, 0.0),
        ranked("cushion-stiffening", 1.1, 1.1, 7.0, 14.0, 0.0),
    ];
    let mut e = evidence(&null, &cands);
    e.distortion = Some(located_at(Site::Support));
    let foam = Verdict::Named {
        effect: c("cushion-viscoelastic"),
        basis: Basis::HeldOut {
            tie: None,
            alternative: None,
        },
        added: Vec::new(),
    };
    let v = located(&e, &foam).expect("renamed");
    assert!(named(c("cushion-stiffening"))(&v), "{v:?}");
    // All runs supporting the path (ΔBIC −20) is not enough while the held-out run does not
    // detect it (+25.6): a second load path moves the FRFs at every magnitude.
    let mut supported = cands.clone();
    supported[1].delta_bic_all = -20.0;
    let mut e = evidence(&null, &supported);
    e.distortion = Some(located_at(Site::Support));
    let v = located(&e, &foam).expect("renamed");
    assert!(named(c("cushion-stiffening"))(&v), "{v:?}");
    // Supported on all runs and detected on the held-out run (−15), it is the site's best.
    supported[1].delta_bic = -15.0;
    let mut e = evidence(&null, &supported);
    e.distortion = Some(located_at(Site::Support));
    let v = located(&e, &foam).expect("renamed");
    assert!(named(c("feet-lift-off"))(&v), "{v:?}");
}
