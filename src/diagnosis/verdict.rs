//! The verdict rule: detected (ΔBIC), named (fraction of the structural gap closed), practically
//! small, not identifiable, or named on all runs together for an effect between magnitudes.

use super::all_runs::AllRuns;
use super::candidate::Candidate;
use super::distortion::Distortion;
use super::*;

/// Which measurement separates two look-alike candidates (gap.md §3.8).
pub fn separating_measurement(a: &str, b: &str) -> String {
    let pair = |x: &str, y: &str| (a == x && b == y) || (a == y && b == x);
    if pair("cushion-stiffening", "cushion-viscoelastic")
        || pair("cushion-contact", "cushion-viscoelastic")
    {
        "a run at a clearly different magnitude (stiffening grows with amplitude, viscoelasticity does not)".into()
    } else if pair("body-softening", "cushion-stiffening")
        || pair("body-softening", "cushion-viscoelastic")
        || pair("body-softening-magnitude", "cushion-stiffening")
        || pair("body-softening-magnitude", "cushion-viscoelastic")
    {
        "the seat-head path or the seat force (body effects move apparent mass and seat-head, cushion effects only base-seat)".into()
    } else if pair("cushion-viscoelastic", "missing-dof")
        || pair("cushion-stiffening", "missing-dof")
    {
        "a base-seat measurement above 20 Hz or a frame accelerometer (a frame mode shows as a narrow peak)".into()
    } else if a.starts_with("sensor-") || b.starts_with("sensor-") {
        "a sensor calibration: a shaker run against a reference accelerometer gives each channel's gain, group delay and mount response".into()
    } else if a == "backrest" || b == "backrest" {
        "a run without backrest contact, or a backrest force (a backrest drives the torso past the seat pan)".into()
    } else if a == "thigh-support" || b == "thigh-support" {
        "the seat-pan force f_seat_z, or a run with the thighs clear of the seat's front edge (a thigh path carries weight past the seat pan; without the force it looks like a stiffer cushion)".into()
    } else if a == "feet-support" || b == "feet-support" {
        "a run with the feet on a fixed floor, or a footrest force (the feet carry part of the thighs past the seat pan)".into()
    } else if pair("missing-dof", "body-mode") {
        "a frame accelerometer (a frame mode moves base-seat and the frame, a body mode seat-head)"
            .into()
    } else {
        "a repeat run and a run at a third magnitude".into()
    }
}

/// Fraction of the training runs' structural gap that `c` closes against the null re-fit,
/// measured down to 1 even when the null fits within σ (not [`score::gap_floor`]): on the training
/// runs every candidate fits in sample, and measuring down to 0 there let candidates close "all" of
/// a residue at the noise level (null cases named body-mode at ΔBIC −3).
pub(super) fn training_closed(null: &Ranked, c: &Ranked) -> f64 {
    score::fraction_closed(null.train_chi2_red, c.train_chi2_red, 1.0)
}

/// Overdispersion ĉ = max(1, χ²/ν) of a fit (QAIC, Burnham & Anderson 2002, §2.5): when even the
/// better of two models leaves residuals ĉ times the noise estimate's variance, every
/// log-likelihood difference between them is ĉ times too large, so a BIC margin between
/// candidates is read in units of ĉ. Detection against the null is not rescaled.
pub(super) fn overdispersion(chi2_red: f64) -> f64 {
    if chi2_red.is_finite() {
        chi2_red.max(1.0)
    } else {
        1.0
    }
}

/// The best candidate if the held-out run accepts it: detected, and closing at least
/// [`MIN_CLOSED`] of the structural gap when there is one. When the null already fits within the
/// noise estimate (reduced χ² ≤ 1) there is no structural gap to close, and detection alone names
/// the effect, with its size however small (issue 15: `none` means nothing significant). A size
/// gate (0.5 % of a_w) and the relative fall of χ² stood here while the null re-fit stopped short
/// of its optimum on parameters at their bounds: clean subjects then left residues that candidates
/// detected at ΔBIC −24 (CI subset case 14, seed 7); with the active-set fit
/// ([`super::fitting`]) the best ΔBIC of the 32 blind clean cases whose null fits within the noise
/// is ≥ −4.1, and a backrest detected at −27 closing 23 % (bench case 188) is named.
pub(super) fn held_out_accepted<'a>(null: &Ranked, cands: &'a [Ranked]) -> Option<&'a Ranked> {
    cands.first().filter(|b| {
        b.delta_bic <= ACCEPT_DELTA_BIC
            && (b.fraction_closed >= MIN_CLOSED || score::within_noise(null.check.chi2_red))
    })
}

/// The verdict, its text and the measurement that would separate a not-identifiable pair, from the
/// null re-fit, the ranked candidates, the best one if the held-out run accepts it
/// ([`held_out_accepted`]) and the all-run judgement of amplitude-dependent effects.
pub(super) fn decide(
    null: &Ranked,
    cands: &[Ranked],
    accepted: Option<&Ranked>,
    all: Option<&AllRuns>,
) -> (String, String, Option<String>) {
    let d0 = null.check.chi2_red;
    let best = cands.first();
    let family = |id: &str| Candidate::from_id(id).map(|c| c.family());
    // Present only when no held-out best explains the training runs' residue and the
    // amplitude-dependent effect fits all runs better than that best (`all_runs::judge`).
    if let Some(a) = all
        && let Some(b) = cands.iter().find(|c| c.id == a.candidate.id())
    {
        return (
            b.id.clone(),
            format!(
                "{} is detected on all runs together: re-fitted on the training and check runs it lowers the BIC by {:.1} against the base model re-fitted on the same runs and closes {:.0} % of their structural gap (reduced χ² {:.2} → {:.2}). An effect that changes with magnitude, whose form two training magnitudes cannot fix, so the check run is not held out for it; its size on the check run: seat a_w {:+.1} %, SEAT {:+.1} points, band gap {:+.2} dB RMS",
                b.id,
                -a.delta_bic,
                100.0 * a.fraction_closed(),
                a.null_chi2_red,
                a.chi2_red,
                b.aw_change_percent,
                b.seat_change_points,
                b.band_gap_change_db
            ) + &accepted.filter(|h| h.id != b.id).map_or(String::new(), |h| {
                format!(
                    "; the held-out run's best, {} (ΔBIC {:.1}), closes only {:.0} % of the training runs' gap",
                    h.id,
                    h.delta_bic,
                    100.0 * training_closed(null, h)
                )
            }),
            None,
        );
    }
    // An amplitude-dependent effect trained on the lowest and highest magnitudes may barely show
    // on a check run between them: accept it on the evidence of all runs together when it closes
    // part of the training gap and does not make the check run worse — or, when the training runs
    // leave a structural residue the null cannot fit, keeps the check run within the noise (the
    // null's compromise between two magnitudes can fit a middle one that an effect whose form is
    // only close to the truth's interpolates a little less well). A sensor's response does not
    // depend on magnitude, so a sensor effect is named on the held-out run or not at all: on all
    // runs a channel gain or delay otherwise stood in for a nonlinearity's equivalent-linear change
    // (blind suspension end-stops named `sensor-gain`). A linear effect (a viscoelastic foam, a
    // mode, a support path) is the same at every magnitude, so one the held-out run does not
    // accept is not named on the training runs' evidence either: the two magnitudes' compromise
    // it fits is a subject's residue (blind suspension seed 2, a clean seat named
    // `cushion-viscoelastic` at ΔBIC −48 over all runs, −7 on the check run).
    let on_all = || {
        cands
            .iter()
            .filter(|c| Candidate::from_id(&c.id).is_some_and(|k| k.amplitude_dependent()))
            .filter(|c| {
                let check_ok = c.check.chi2_red <= null.check.chi2_red
                    || (null.train_chi2_red > GAP_CHI2 && c.check.chi2_red <= 1.0);
                c.delta_bic_all <= ACCEPT_DELTA_BIC
                    && check_ok
                    && training_closed(null, c) >= MIN_CLOSED
            })
            .min_by(|a, b| a.delta_bic_all.total_cmp(&b.delta_bic_all))
    };
    if accepted.is_none()
        && let Some(b) = on_all()
    {
        return (
            b.id.clone(),
            format!(
                "{} is detected on all runs together (ΔBIC {:.1} over training and check runs; {:.1} on the check run alone) and closes {:.0} % of the training runs' structural gap without making the check run structurally worse: an effect that changes with magnitude between the training runs; its size on the check run: seat a_w {:+.1} %, SEAT {:+.1} points, band gap {:+.2} dB RMS",
                b.id,
                b.delta_bic_all,
                b.delta_bic,
                100.0 * training_closed(null, b),
                b.aw_change_percent,
                b.seat_change_points,
                b.band_gap_change_db
            ),
            None,
        );
    }
    match accepted {
        Some(b) => {
            // A close second of another family makes the pair not identifiable on the held-out
            // run; a close second of the same family is another form of the same effect, named in
            // the text. All three runs together (the training fit's in-sample BIC plus the
            // held-out run's) decide such a pair when they separate it by the same margin.
            // Both margins are in units of the better candidate's overdispersion ĉ (see
            // [`overdispersion`]): a misfit that leaves χ²/ν = 25 makes a 15-unit ΔBIC difference
            // chance (blind lab case, a stick-slip suspension and a base mount resonance both
            // closing 100 % at ΔBIC −5·10⁵, 15 apart; all runs put the friction 870 ahead).
            // ĉ of the better candidate over the runs it was fitted and judged on: a check run
            // that a misfit leaves at 3.9 while the training runs show 25 does not make a
            // 36-unit difference evidence (blind suspension seed 2, case 014).
            let check_c = overdispersion(b.check.chi2_red.max(b.train_chi2_red));
            let rival = cands.iter().skip(1).find(|s| {
                (s.delta_bic - b.delta_bic) / check_c < IDENTIFIABLE_MARGIN
                    && s.fraction_closed >= MIN_CLOSED
                    && family(&s.id) != family(&b.id)
            });
            let all_c =
                |s: &Ranked| overdispersion(b.train_chi2_red.min(s.train_chi2_red));
            let (b, rival, tie_note) = match rival {
                Some(s) if (b.delta_bic_all - s.delta_bic_all).abs() / all_c(s) >= IDENTIFIABLE_MARGIN => {
                    let (win, lose) = if s.delta_bic_all < b.delta_bic_all {
                        (s, b)
                    } else {
                        (b, s)
                    };
                    let fits = if std::ptr::eq(lose, b) { "as well" } else { "almost as well" };
                    (
                        win,
                        None,
                        format!(
                            "; on the held-out run alone {} fits {fits} (ΔBIC {:.1} vs {:.1}), on all runs together {} is ahead (ΔBIC {:.1} vs {:.1})",
                            lose.id,
                            lose.delta_bic,
                            win.delta_bic,
                            win.id,
                            win.delta_bic_all,
                            lose.delta_bic_all
                        ),
                    )
                }
                other => (b, other, String::new()),
            };
            if let Some(s) = rival {
                let m = separating_measurement(&b.id, &s.id);
                return (
                    "not-identifiable".into(),
                    format!(
                        "{} and {} explain the held-out run equally well (ΔBIC {:.1} vs {:.1}); to separate them, measure {m}",
                        b.id, s.id, b.delta_bic, s.delta_bic
                    ),
                    Some(m),
                );
            }
            let small = b.aw_change_percent.abs() < PRACTICAL_SIZE.0
                && b.seat_change_points.abs() < PRACTICAL_SIZE.1
                && b.band_gap_change_db.abs() < PRACTICAL_SIZE.2;
            let alt = cands
                .iter()
                .skip(1)
                .find(|s| {
                    s.delta_bic - b.delta_bic < IDENTIFIABLE_MARGIN
                        && family(&s.id) == family(&b.id)
                })
                .map_or(String::new(), |s| {
                    format!(" ({} fits almost as well: the form is uncertain)", s.id)
                });
            let what = if score::within_noise(d0) {
                format!(
                    "lowers the held-out run's reduced χ², already within the noise after the re-fit, by {:.0} %",
                    100.0 * b.fraction_closed
                )
            } else {
                format!(
                    "closes {:.0} % of the structural gap on the held-out run",
                    100.0 * b.fraction_closed
                )
            };
            (
                b.id.clone(),
                format!(
                    "{} (detected: ΔBIC {:.1}, probability {:.2}) {what}; its size: seat a_w {:+.1} %, SEAT {:+.1} points, band gap {:+.2} dB RMS{}{alt}",
                    b.id,
                    b.delta_bic,
                    b.probability,
                    b.aw_change_percent,
                    b.seat_change_points,
                    b.band_gap_change_db,
                    if small {
                        " — detected but practically small"
                    } else {
                        ""
                    }
                ) + &tie_note,
                None,
            )
        }
        // A detected candidate that closes little of a gap that is itself below the structural
        // threshold is not evidence of an unmodelled effect (a subject whose masses differ leaves
        // such residue after the re-fit): `none`, with the candidate mentioned.
        None if best.is_some_and(|b| b.delta_bic <= ACCEPT_DELTA_BIC) && d0 > GAP_CHI2 => {
            let b = best.expect("checked");
            (
                "unexplained".into(),
                format!(
                    "a structural gap remains (reduced χ² {d0:.2} after the re-fit); {} is detected (ΔBIC {:.1}) but closes only {:.0} % of it",
                    b.id,
                    b.delta_bic,
                    100.0 * b.fraction_closed
                ),
                None,
            )
        }
        None if d0 <= GAP_CHI2
            || (null.check.gap_db_rms < PRACTICAL_GAP.0
                && null.check.phase_deg_rms < PRACTICAL_GAP.1) =>
        {
            (
                "none".into(),
                format!(
                    "no effect is detected: the re-fitted base parameters explain the held-out run (reduced χ² {d0:.2}, band gap {:.2} dB RMS, phase {:.2}° RMS){}",
                    null.check.gap_db_rms,
                    null.check.phase_deg_rms,
                    best.filter(|b| b.delta_bic <= ACCEPT_DELTA_BIC).map_or(String::new(), |b| format!(
                        "; {} is statistically detected (ΔBIC {:.1}) but closes only {:.0} % of a residue below the structural threshold",
                        b.id,
                        b.delta_bic,
                        100.0 * b.fraction_closed
                    ))
                ),
                None,
            )
        }
        None => (
            "unexplained".into(),
            format!(
                "a structural gap remains (reduced χ² {d0:.2} after the re-fit) that no candidate closes{}",
                best.map_or(String::new(), |b| format!(
                    "; best {} closes {:.0} %",
                    b.id,
                    100.0 * b.fraction_closed
                ))
            ),
            None,
        ),
    }
}

/// A warning when the named effect(s) fit the frequency responses better but move the check
/// run's ISO figures away from the measurement: the seat a_w gap and the SEAT gap both grow by
/// more than [`VISIBLE_SIZE`]. The χ² is dominated by the many coherent bins above 10 Hz, a_w and
/// SEAT by the 4–8 Hz band, so a form only close to the truth's (one Maxwell arm for a foam's
/// power-law relaxation) can improve the one and worsen the other; the user judges by the ISO
/// figures, so the report says which model to take them from.
pub(super) fn iso_figures_move_away(null: &Stage, with: &Stage) -> Option<String> {
    let (n, w) = (&null.weighted, &with.weighted);
    let seat_gap = |s: f64| (s - w.seat_meas).abs();
    let aw_worse = w.aw_gap_percent.abs() - n.aw_gap_percent.abs();
    let seat_worse = seat_gap(w.seat_model) - seat_gap(n.seat_model);
    (aw_worse > VISIBLE_SIZE.0 && seat_worse > VISIBLE_SIZE.1).then(|| {
        format!(
            "the named effect fits the frequency responses better but moves the check run's ISO figures away from the measurement (seat a_w gap {:+.1} % → {:+.1} %, SEAT {:.1} → {:.1} % against {:.1} %): its form is only close to the truth's; take a_w and SEAT from the re-fitted model",
            n.aw_gap_percent, w.aw_gap_percent, n.seat_model, w.seat_model, w.seat_meas
        )
    })
}

/// The verdict when the runs' distortion locates a nonlinearity ([`super::distortion`]) and the
/// decided `verdict` is not an effect at that site (a linear structural candidate, `none`,
/// `unexplained` or `not-identifiable`; a sensor effect stands): the site's candidate with the
/// lowest BIC over all runs is named, on the distortion's evidence, with its linearised fit's
/// figures. A linear effect cannot make a path's incoherent power grow with magnitude, and a
/// one-sided foam's linearisation barely moves the FRFs (gap.md §2 row 3: even harmonics,
/// coherence reduced at high magnitude), so the χ² alone named a viscoelastic foam or nothing for
/// a preloaded cushion.
pub(super) fn located(
    dist: &Distortion,
    null: &Ranked,
    cands: &[Ranked],
    verdict: &str,
) -> Option<(String, String)> {
    let site = dist.site?;
    // A sensor effect is named on its own evidence (phase slope, one channel) and coexists with
    // any nonlinearity of the structure: the distortion does not contradict it.
    if Candidate::from_id(verdict).is_some_and(|c| site.admits(c) || c.family() == "sensor") {
        return None;
    }
    let b = cands
        .iter()
        .filter(|r| Candidate::from_id(&r.id).is_some_and(|c| site.admits(c)))
        .min_by(|a, b| a.delta_bic_all.total_cmp(&b.delta_bic_all))?;
    // A nonlinearity whose distortion does not grow with magnitude (Coulomb friction, see
    // [`Candidate::distortion_grows`]) cannot be placed by the trend: one the frequency responses
    // name stands unless the site's best fits all runs as well (blind lab case s1-1/016, a stick-slip
    // suspension: friction ΔBIC −257 over all runs, the body softening the site named +6). Other
    // nonlinear names do not stand against the site — a stiffer cushion and a softer body shift
    // the same resonance, and there the distortion is the better witness (blind seed 1 cases
    // 001 and seed 2 case 000: the FRFs named body-softening, the truth was cushion stiffening).
    if Candidate::from_id(verdict).is_some_and(|c| c.amplitude_dependent() && !c.distortion_grows())
        && let Some(v) = cands.iter().find(|r| r.id == verdict)
        && (b.delta_bic_all - v.delta_bic_all) / overdispersion(v.train_chi2_red)
            >= IDENTIFIABLE_MARGIN
    {
        return None;
    }
    let paths = dist
        .paths
        .iter()
        .map(|p| format!("{} {:+.1} dB", p.path, p.rise_db))
        .collect::<Vec<_>>()
        .join(", ");
    let small = b.aw_change_percent.abs() < PRACTICAL_SIZE.0
        && b.seat_change_points.abs() < PRACTICAL_SIZE.1
        && b.band_gap_change_db.abs() < PRACTICAL_SIZE.2;
    Some((
        b.id.clone(),
        format!(
            "a nonlinearity {} is detected by its distortion: the incoherent-to-coherent power ratio (1 − γ²)/γ² grows from the run at {:.2} to the one at {:.2} m/s² on {paths}, which no linear effect does (noise keeps it or lowers it); {} is the best nonlinear candidate there (ΔBIC {:.1} over all runs, {:.1} on the check run, closes {:.0} % of the check run's structural gap){}; the frequency-response fit alone pointed to {verdict}. Its size on the check run: seat a_w {:+.1} %, SEAT {:+.1} points, band gap {:+.2} dB RMS{}",
            site.describe(),
            dist.magnitudes.0,
            dist.magnitudes.1,
            b.id,
            b.delta_bic_all,
            b.delta_bic,
            100.0 * b.fraction_closed,
            if b.fraction_closed < MIN_CLOSED && b.check.chi2_red >= null.check.chi2_red - 1e-9 {
                " — its statistically linearised form reproduces little of what the runs show (a one-sided foam's best linear approximation hardly changes: the distortion is the effect)"
            } else {
                ""
            },
            b.aw_change_percent,
            b.seat_change_points,
            b.band_gap_change_db,
            if small {
                " — practically small in the linear figures"
            } else {
                ""
            }
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnosis::gapmap::Weighted;

    /// A ranked entry with the figures the rule reads (sizes 2 % / 2 points).
    fn ranked(id: &str, train: f64, check: f64, dbic: f64, dbic_all: f64, closed: f64) -> Ranked {
        Ranked {
            id: id.into(),
            params: Vec::new(),
            train_chi2_red: train,
            delta_bic: dbic,
            delta_bic_all: dbic_all,
            probability: 0.0,
            fraction_closed: closed,
            check: Stage {
                chi2_red: check,
                gap_db_rms: 0.3,
                phase_deg_rms: 1.0,
                weighted: Weighted {
                    aw_seat_meas: 1.0,
                    aw_seat_model: 1.0,
                    aw_gap_percent: 0.0,
                    seat_meas: 80.0,
                    seat_model: 80.0,
                    driving_bands: Vec::new(),
                },
                cells: Vec::new(),
            },
            aw_change_percent: 2.0,
            seat_change_points: 2.0,
            band_gap_change_db: -0.1,
        }
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
        let accepted = held_out_accepted(&null, &cands);
        assert!(accepted.is_none());
        let (verdict, text, _) = decide(&null, &cands, accepted, None);
        assert_eq!(verdict, "cushion-stiffening", "{text}");
        // A linear effect is the same at every magnitude: the held-out run's word stands.
        let mut linear = cands.clone();
        linear[1].id = "cushion-viscoelastic".into();
        let (verdict, text, _) = decide(&null, &linear, accepted, None);
        assert_ne!(verdict, "cushion-viscoelastic", "{text}");
        // Accepted on the held-out run (closes 30 % there), the sensor gain is named.
        let mut cands = cands;
        cands[0].fraction_closed = 0.30;
        let accepted = held_out_accepted(&null, &cands);
        let (verdict, text, _) = decide(&null, &cands, accepted, None);
        assert_eq!(verdict, "sensor-gain", "{text}");
    }

    #[test]
    fn within_the_noise_a_detected_effect_is_named_however_little_it_closes() {
        // Bench case 188: the null fits the check run within the noise (0.41); a backrest is
        // detected at ΔBIC −27.4 and lowers χ² by 23 %. There is no structural gap to close.
        let null = ranked("null", 0.42, 0.41, 0.0, 0.0, 1.0);
        let mut cands = vec![ranked("backrest", 0.29, 0.31, -27.4, -167.8, 0.23)];
        cands[0].aw_change_percent = 0.5;
        cands[0].seat_change_points = 0.6;
        cands[0].band_gap_change_db = -0.0;
        let accepted = held_out_accepted(&null, &cands);
        let (verdict, text, _) = decide(&null, &cands, accepted, None);
        assert_eq!(verdict, "backrest", "{text}");
        assert!(text.contains("practically small"), "{text}");
        assert!(
            text.contains("within the noise after the re-fit, by 23 %"),
            "{text}"
        );
        // Not detected (ΔBIC −8): nothing significant, `none`.
        cands[0].delta_bic = -8.0;
        let accepted = held_out_accepted(&null, &cands);
        assert!(accepted.is_none());
        assert_eq!(decide(&null, &cands, accepted, None).0, "none");
        // Above the noise the fraction of the gap still rules: 23 % of a gap of 1.6 is not named.
        let gap = ranked("null", 1.7, 1.6, 0.0, 0.0, 1.0);
        cands[0].delta_bic = -27.4;
        assert!(held_out_accepted(&gap, &cands).is_none());
    }

    #[test]
    fn the_overdispersion_of_a_margin_counts_the_training_runs_misfit() {
        // Blind suspension seed 2, case 014 (stick-slip): both candidates close all of the check
        // run's gap and leave χ²/ν 3.9 there but 24–25 on the training runs. 36 units apart on
        // the check run is 1.4 ĉ of the training misfit: a tie that all runs (828 apart) decide.
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
        let accepted = held_out_accepted(&null, &cands);
        let (verdict, text, _) = decide(&null, &cands, accepted, None);
        assert_eq!(verdict, "suspension-friction", "{text}");
        assert!(
            text.contains("on all runs together suspension-friction is ahead"),
            "{text}"
        );
    }

    #[test]
    fn a_held_out_tie_is_decided_by_all_runs_only_when_they_separate_it() {
        // Two families within the identifiability margin on the held-out run.
        let null = ranked("null", 1.5, 1.2, 0.0, 0.0, 1.0);
        let mut cands = vec![
            ranked("sensor-delay", 1.1, 0.8, -24.0, -98.0, 0.33),
            ranked("backrest", 0.9, 0.8, -23.7, -139.0, 0.44),
        ];
        let accepted = held_out_accepted(&null, &cands);
        let (verdict, text, _) = decide(&null, &cands, accepted, None);
        assert_eq!(verdict, "backrest", "{text}");
        assert!(
            text.contains("on all runs together backrest is ahead"),
            "{text}"
        );
        // The held-out run's best ahead on all runs as well keeps its name, the rival noted.
        let ahead = vec![
            ranked("backrest", 0.9, 0.8, -24.0, -139.0, 0.44),
            ranked("sensor-delay", 1.1, 0.8, -23.7, -98.0, 0.33),
        ];
        let accepted = held_out_accepted(&null, &ahead);
        let (verdict, text, _) = decide(&null, &ahead, accepted, None);
        assert_eq!(verdict, "backrest", "{text}");
        assert!(text.contains("sensor-delay fits almost as well"), "{text}");
        // A misfit both share (χ²/ν 25 on the held-out run, 24 on training) makes a 15-unit
        // held-out difference a tie that all runs, 870 apart (36 ĉ), decide.
        let poor = ranked("null", 600.0, 500.0, 0.0, 0.0, 1.0);
        let big = vec![
            ranked("sensor-delay", 25.0, 25.0, -533_636.0, -14_203_707.0, 0.997),
            ranked("backrest", 24.0, 25.1, -533_621.0, -14_204_576.0, 0.997),
        ];
        let accepted = held_out_accepted(&poor, &big);
        let (verdict, text, _) = decide(&poor, &big, accepted, None);
        assert_eq!(verdict, "backrest", "{text}");
        // Unscaled, 15 units would have named the held-out run's best.
        let mut fit = big.clone();
        for c in &mut fit {
            c.check.chi2_red = 1.0;
            c.train_chi2_red = 1.0;
        }
        let accepted = held_out_accepted(&poor, &fit);
        let (verdict, text, _) = decide(&poor, &fit, accepted, None);
        assert_eq!(verdict, "sensor-delay", "{text}");
        // All runs within the margin as well: not identifiable, with the separating measurement.
        cands[1].delta_bic_all = -101.0;
        let accepted = held_out_accepted(&null, &cands);
        let (verdict, _, separating) = decide(&null, &cands, accepted, None);
        assert_eq!(verdict, "not-identifiable");
        assert!(separating.is_some());
    }

    #[test]
    fn a_friction_named_on_the_responses_stands_against_a_body_site() {
        use crate::diagnosis::distortion::{Distortion, Site};
        let dist = Distortion {
            magnitudes: (0.4, 1.6),
            paths: Vec::new(),
            site: Some(Site::Body),
        };
        let null = ranked("null", 3.0, 1.6, 0.0, 0.0, 1.0);
        let cands = vec![
            ranked("suspension-friction", 1.3, 1.1, -44.0, -257.0, 0.34),
            ranked("body-softening", 2.9, 1.6, 4.9, 6.3, 0.0),
        ];
        assert!(located(&dist, &null, &cands, "suspension-friction").is_none());
        // The same figures for a cushion stiffening: the body site renames it.
        let mut cands = cands;
        cands[0].id = "cushion-stiffening".into();
        let (v, _) = located(&dist, &null, &cands, "cushion-stiffening").expect("renamed");
        assert_eq!(v, "body-softening");
        // A friction the site's best fits as well as (within 6 ĉ over all runs) is renamed too.
        cands[0].id = "suspension-friction".into();
        cands[1].delta_bic_all = -255.0;
        let (v, _) = located(&dist, &null, &cands, "suspension-friction").expect("renamed");
        assert_eq!(v, "body-softening");
    }
}
