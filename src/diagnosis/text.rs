//! The text stage: the verdict's sentence, rendered in one place from the [`Decision`] and the
//! evidence it was made on, followed by the second effect, the check run's ISO figures and any
//! calibration finding. Nothing here changes the decision or re-tests a threshold to word it.

use super::outcome::{ChannelError, PartialEffect, Ranked, Rule, Stage};
use super::score;
use super::thresholds::{EXPLAINED_CHI2, MIN_CLOSED};
use super::verdict::{
    Basis, Decision, Evidence, Shortfall, Verdict, practically_small, training_closed,
};

/// The diagnosis's text for decision `d` on evidence `e`: the verdict's sentence, the second
/// effect's clause and the check run's ISO figures (nominal → re-fitted → with the effect(s)), or
/// the partial explanation with its `partial` candidates; then the calibration finding.
pub(super) fn render(
    d: &Decision,
    e: &Evidence,
    nominal: &Stage,
    partial: &[PartialEffect],
) -> String {
    let text = match &d.verdict {
        Verdict::Partial { shortfall, .. } => {
            self::partial(shortfall, partial, nominal, &e.null.check)
        }
        Verdict::Named { effect, added, .. } => {
            let mut text = sentence(d, e);
            if let Some(r) = e.entry(effect).filter(|_| added.is_empty()) {
                text += &replayed_fit(&r.check);
            }
            let stack = e.added.as_ref().filter(|_| !added.is_empty());
            if let Some(s) = stack {
                text += &self::added(effect, &s.added, &s.entry);
            }
            let with = stack.map_or_else(
                || e.entry(effect).map(|r| &r.check),
                |s| Some(&s.entry.check),
            );
            if let Some(with) = with {
                text += &iso(nominal, &e.null.check, with);
            }
            text
        }
        _ => sentence(d, e),
    };
    calibration(
        text,
        &e.channel_errors,
        matches!(d.verdict, Verdict::Calibration(_)),
    )
}

/// The verdict's sentence (before the second effect, the ISO figures and calibration).
pub(super) fn sentence(d: &Decision, e: &Evidence) -> String {
    let d0 = e.null.check.chi2_red;
    let set_aside = d.set_aside.and_then(|c| e.entry(c));
    match &d.verdict {
        Verdict::Named { effect, basis, .. } => match basis {
            Basis::AllRuns { refitted: true } => refitted(e, e.entry(effect).expect("ranked")),
            Basis::AllRuns { refitted: false } => on_all_runs(e, e.entry(effect).expect("ranked")),
            Basis::HeldOut { tie, alternative } => held_out(e, effect, *tie, *alternative),
            Basis::Distortion { responses } => distortion(e, e.entry(effect).expect("ranked"), responses),
            Basis::Clock { responses } => clock(e, e.entry(effect).expect("ranked"), responses),
            Basis::Replayed { responses } => replayed(e, e.entry(effect).expect("ranked"), responses),
        },
        Verdict::NotIdentifiable { a, b, separating } => {
            let (a, b) = (
                e.held_out_entry(a).expect("ranked"),
                e.held_out_entry(b).expect("ranked"),
            );
            format!(
                "{} and {} explain the held-out run equally well (ΔBIC {:.1} vs {:.1}); to separate them, measure {separating}",
                a.id, b.id, a.delta_bic, b.delta_bic
            )
        }
        // Rendered in full by [`partial`] once the ISO figures are known.
        Verdict::Partial { best, .. } => format!(
            "a structural gap remains that {} explains only in part",
            best.id
        ),
        Verdict::Unexplained if d.rule == Rule::DistortionSite => located_without_form(e),
        Verdict::Unexplained => match set_aside {
            Some(b) => format!(
                "a structural gap remains (reduced χ² {d0:.2} after the re-fit); {} is detected (ΔBIC {:.1}) but closes only {:.0} % of it",
                b.id,
                b.delta_bic,
                100.0 * b.fraction_closed
            ),
            None => format!(
                "a structural gap remains (reduced χ² {d0:.2} after the re-fit) that no candidate closes{}",
                e.best().map_or(String::new(), |b| format!(
                    "; best {} closes {:.0} %",
                    b.id,
                    100.0 * b.fraction_closed
                ))
            ),
        },
        Verdict::None | Verdict::Calibration(_) => format!(
            "no effect is detected: the re-fitted base parameters explain the held-out run (reduced χ² {d0:.2}, band gap {:.2} dB RMS, phase {:.2}° RMS){}",
            e.null.check.gap_db_rms,
            e.null.check.phase_deg_rms,
            set_aside.map_or(String::new(), |b| format!(
                "; {} is statistically detected (ΔBIC {:.1}) but closes only {:.0} % of a residue below the structural threshold",
                b.id,
                b.delta_bic,
                100.0 * b.fraction_closed
            ))
        ),
    }
}

/// The effect's size on the check run: seat a_w, SEAT and band-gap change against the null.
fn size(b: &Ranked) -> String {
    format!(
        "seat a_w {:+.1} %, SEAT {:+.1} points, band gap {:+.2} dB RMS",
        b.aw_change_percent, b.seat_change_points, b.band_gap_change_db
    )
}

/// Named on the all-run re-fit ([`Basis::AllRuns`] `refitted`).
fn refitted(e: &Evidence, b: &Ranked) -> String {
    let a = e.all_runs.as_ref().expect("the all-run judgement named it");
    format!(
        "{} is detected on all runs together: re-fitted on the training and check runs it lowers the BIC by {:.1} against the base model re-fitted on the same runs and closes {:.0} % of their structural gap (reduced χ² {:.2} → {:.2}). An effect that changes with magnitude, whose form two training magnitudes cannot fix, so the check run is not held out for it; its size on the check run: {}",
        b.id,
        -a.delta_bic,
        100.0 * a.fraction_closed(),
        a.null_chi2_red,
        a.chi2_red,
        size(b)
    ) + &e.accepted.as_ref().filter(|h| h.id != b.id).map_or(String::new(), |h| {
        format!(
            "; the held-out run's best, {} (ΔBIC {:.1}), closes only {:.0} % of the training runs' gap",
            h.id,
            h.delta_bic,
            100.0 * training_closed(&e.null, h)
        )
    })
}

/// Named on the training fit's in-sample BIC plus the held-out one.
fn on_all_runs(e: &Evidence, b: &Ranked) -> String {
    format!(
        "{} is detected on all runs together (ΔBIC {:.1} over training and check runs; {:.1} on the check run alone) and closes {:.0} % of the training runs' structural gap without making the check run structurally worse: an effect that changes with magnitude between the training runs; its size on the check run: {}",
        b.id,
        b.delta_bic_all,
        b.delta_bic,
        100.0 * training_closed(&e.null, b),
        size(b)
    )
}

/// The note on a same-family `alternative` to the named `effect`. Support paths of one family
/// differ in where the load enters the body (upper torso, shoulders, pelvis), so for them the place
/// is what is uncertain and the measurement that would tell is named.
fn alternative_note(
    effect: super::candidate::Candidate,
    alternative: super::candidate::Candidate,
) -> String {
    use super::candidate::{Family, separating_measurement};
    if alternative.family == Family::SupportPath {
        format!(
            " ({} fits almost as well: where the path enters the body is uncertain; to tell, {})",
            alternative.id,
            separating_measurement(effect, alternative)
        )
    } else {
        format!(
            " ({} fits almost as well: the form is uncertain)",
            alternative.id
        )
    }
}

/// Named on the held-out run, with a same-family alternative and a tie all runs decided.
fn held_out(
    e: &Evidence,
    effect: super::candidate::Candidate,
    tie: Option<super::candidate::Candidate>,
    alternative: Option<super::candidate::Candidate>,
) -> String {
    let b = e.held_out_entry(effect).expect("ranked");
    let null = &e.null.check;
    let what = if score::chi2_within_noise(null.chi2_red, null.residuals) {
        format!(
            "lowers the held-out run's reduced χ², already within the noise after the re-fit, by {:.0} % ({:.2} → {:.2})",
            (100.0 * (1.0 - b.check.chi2_red / null.chi2_red)).max(0.0),
            null.chi2_red,
            b.check.chi2_red
        )
    } else {
        format!(
            "closes {:.0} % of the structural gap on the held-out run",
            100.0 * b.fraction_closed
        )
    };
    let alt = alternative.map_or(String::new(), |s| alternative_note(effect, s));
    let tie_note = tie.map_or(String::new(), |l| {
        let lose = e.held_out_entry(l).expect("ranked");
        let fits = if e.accepted.as_ref().is_some_and(|a| a.id == lose.id) {
            "as well"
        } else {
            "almost as well"
        };
        format!(
            "; on the held-out run alone {} fits {fits} (ΔBIC {:.1} vs {:.1}), on all runs together {} is ahead (ΔBIC {:.1} vs {:.1})",
            lose.id, lose.delta_bic, b.delta_bic, b.id, b.delta_bic_all, lose.delta_bic_all
        )
    });
    format!(
        "{} (detected: ΔBIC {:.1}, probability {:.2}) {what}; its size: {}{}{alt}",
        b.id,
        b.delta_bic,
        b.probability,
        size(b),
        if practically_small(b) {
            " — detected, but practically small in these figures"
        } else {
            ""
        }
    ) + &tie_note
}

/// The distortion trend that located a nonlinearity, its site, and each path's rise in words.
fn located(
    e: &Evidence,
) -> (
    &super::distortion::Distortion,
    super::distortion::Site,
    String,
) {
    let dist = e.distortion.as_ref().expect("located by the distortion");
    let site = dist.site.expect("a located site");
    let paths = dist
        .paths
        .iter()
        .map(|p| format!("{} {:+.1} dB", p.path, p.rise_db))
        .collect::<Vec<_>>()
        .join(", ");
    (dist, site, paths)
}

/// A nonlinearity the distortion places but no form at its site explains ([`Rule::DistortionSite`]
/// with the verdict `unexplained`): where it is and how it grows, and the site's best.
fn located_without_form(e: &Evidence) -> String {
    let (dist, site, paths) = located(e);
    let best = e
        .cands
        .iter()
        .filter(|r| r.id.candidate().is_some_and(|c| site.admits(c)))
        .min_by(|a, b| a.delta_bic_all.total_cmp(&b.delta_bic_all))
        .map_or(String::new(), |b| {
            format!(
                "; the best form there, {}, does not explain the runs (ΔBIC {:+.1} over all runs, {:+.1} on the check run, closes {:.0} % of its gap)",
                b.id,
                b.delta_bic_all,
                b.delta_bic,
                100.0 * b.fraction_closed
            )
        });
    format!(
        "a nonlinearity {} that no candidate's form explains: its distortion, the incoherent-to-coherent power ratio (1 − γ²)/γ², grows from the run at {:.2} to the one at {:.2} m/s² on {paths}, which no linear effect does{best}; the law there is not among the candidates (docs/gap.md §5)",
        site.describe(),
        dist.magnitudes.0,
        dist.magnitudes.1,
    )
}

/// Named on the distortion's evidence.
fn distortion(e: &Evidence, b: &Ranked, responses: &super::outcome::VerdictId) -> String {
    let (dist, site, paths) = located(e);
    let phase = |name: &str| {
        dist.paths
            .iter()
            .find(|p| p.path == name)
            .map_or(f64::NAN, |p| p.phase_move_deg)
    };
    let placed = dist.phase_stays.map_or(String::new(), |p| {
        format!(
            "; {p} rises too, but its phase moves {:.1}° with magnitude against base-seat's {:.1}°: the body follows the seat's own motion linearly, where a nonlinearity in the occupant would move it more",
            phase(p),
            phase("base-seat")
        )
    });
    format!(
        "a nonlinearity {} is detected by its distortion: the incoherent-to-coherent power ratio (1 − γ²)/γ² grows from the run at {:.2} to the one at {:.2} m/s² on {paths}, which no linear effect does (noise keeps it or lowers it){placed}; {} is the best nonlinear candidate there (ΔBIC {:.1} over all runs, {:.1} on the check run, closes {:.0} % of the check run's structural gap){}; the frequency-response fit alone pointed to {responses}. Its size on the check run: {}{}",
        site.describe(),
        dist.magnitudes.0,
        dist.magnitudes.1,
        b.id,
        b.delta_bic_all,
        b.delta_bic,
        100.0 * b.fraction_closed,
        if b.fraction_closed < MIN_CLOSED && b.check.chi2_red >= e.null.check.chi2_red - 1e-9 {
            " — its statistically linearised form reproduces little of what the runs show (a one-sided foam's best linear approximation hardly changes: the distortion is the effect)"
        } else {
            ""
        },
        size(b),
        if practically_small(b) {
            " — practically small in the linear figures"
        } else {
            ""
        }
    )
}

/// The added effects' clause: what forward selection's stack closes beyond the named effect.
pub(super) fn added(
    first: super::candidate::Candidate,
    added: &[super::candidate::Candidate],
    stack: &Ranked,
) -> String {
    const ORDINALS: [&str; 2] = ["second", "third"];
    // A frame on legs of unequal stiffness under an off-centre load has its bounce and pitch
    // coupled: both modes move the pan vertically, so vertical channels see two frame modes
    // whichever it is; a riser or a floor panel under it adds modes they cannot place either.
    const MODES: &str = " (more than one mode of the structure: a frame's bounce and pitch, two bending modes, a riser or a floor panel under it, which vertical channels cannot tell apart; a fore-and-aft accelerometer on the seat pan, or a second vertical one off its centre or on the floor, can)";
    let all: Vec<_> = std::iter::once(first)
        .chain(added.iter().copied())
        .collect();
    let twice = |c: &super::candidate::Candidate| all.iter().filter(|o| o.id == c.id).count() > 1;
    // Another part of a family a structure can lack more than one of (a frame's second mode, a
    // mode beside its load path): the note says what vertical channels cannot place.
    let another_part = |c: &super::candidate::Candidate| {
        c.family.adds_parts() && all.iter().filter(|o| o.family == c.family).count() > 1
    };
    let mut noted = false;
    let parts: Vec<String> = added
        .iter()
        .zip(ORDINALS)
        .map(|(c, nth)| {
            let note = if another_part(c) && !noted {
                noted = true;
                MODES
            } else {
                ""
            };
            if twice(c) {
                format!("a {nth} {}{note}", c.id)
            } else {
                format!("a {nth} effect, {}{note}", c.id)
            }
        })
        .collect();
    let (verb, what) = match parts.as_slice() {
        [one] => ("closes", one.clone()),
        [a, b] => ("close", format!("{a} and {b}")),
        _ => return String::new(),
    };
    format!(
        "; {what} {verb} a further {:.0} % of what remains (ΔBIC {:.1} against {} alone)",
        100.0 * stack.fraction_closed,
        stack.delta_bic,
        first.id,
    )
}

/// How close a_w and SEAT come on the check run: nominal → re-fitted → with the effect(s).
/// " ± σ" of a stage's a_w gap (%) and SEAT (points), empty where not known.
pub(super) fn iso_sigmas(s: &Stage) -> (String, String) {
    s.iso_sigma.map_or((String::new(), String::new()), |e| {
        (
            format!(" ± {:.2}", e.aw_percent),
            format!(" ± {:.2}", e.seat_points),
        )
    })
}

/// With the standard errors of the model with the effect(s) where known.
pub(super) fn iso(nominal: &Stage, null: &Stage, with: &Stage) -> String {
    let (aw_sigma, seat_sigma) = iso_sigmas(with);
    format!(
        ". On the check run the seat a_w gap goes {:+.1} % (nominal) → {:+.1} % (re-fitted) → {:+.1}{aw_sigma} % (with the effect), SEAT {:.1} → {:.1} → {:.1}{seat_sigma} % against {:.1} % measured",
        nominal.weighted.aw_gap_percent,
        null.weighted.aw_gap_percent,
        with.weighted.aw_gap_percent,
        nominal.weighted.seat_model,
        null.weighted.seat_model,
        with.weighted.seat_model,
        with.weighted.seat_meas
    )
}

/// The text with the calibration findings: named first when the verdict is `none`
/// (`nothing_else`), after the verdict otherwise.
pub(super) fn calibration(text: String, errors: &[ChannelError], nothing_else: bool) -> String {
    if errors.is_empty() {
        return text;
    }
    let what = errors
        .iter()
        .map(|f| format!("{} {} in {}", f.channels, f.error, f.runs.join(", ")))
        .collect::<Vec<_>>()
        .join("; ");
    if nothing_else {
        format!("a channel's calibration is wrong: {what}; with it corrected, {text}")
    } else {
        format!(
            "{text}. Also a channel's calibration is wrong: {what}; the diagnosis above uses it corrected"
        )
    }
}

/// Named on the lag's movement between the runs' halves ([`Basis::Clock`]).
fn clock(e: &Evidence, b: &Ranked, responses: &super::VerdictId) -> String {
    let c = e.clock.as_ref().expect("the clock named it");
    format!(
        "{} (ΔBIC {:.1}): the lag of the seat and head behind the base grows by {:+.0} ± {:.0} ppm of the elapsed time between the runs' halves, which a drifting logger clock makes and a filter or a constant offset does not; the whole-run responses alone named {responses}. Its size on the check run: {}",
        b.id,
        b.delta_bic,
        c.drift_ppm,
        c.sigma_ppm,
        size(b)
    )
}

/// Named by the simulator's second opinion ([`Basis::Replayed`]).
fn replayed(e: &Evidence, b: &Ranked, responses: &super::VerdictId) -> String {
    let site = e
        .distortion
        .as_ref()
        .and_then(|d| d.site)
        .expect("located by the distortion");
    // What the verdict it replaces leaves on the check run (the best's, when it named nothing).
    let against = match responses {
        super::VerdictId::Effect(c) => e.entry(c),
        _ => e.best(),
    }
    .map_or(String::new(), |r| {
        format!(" ({:.1})", r.check.explained_chi2_red())
    });
    format!(
        "{}, a path that acts on one side only: the runs' distortion places a nonlinearity {}, and the check run replayed through its law (refined on the training runs by the replayed best linear approximation) leaves a reduced χ² of {:.1}, clearly below what the frequency-response verdict, {responses}, leaves{against}; its statistical linearisation (reduced χ² {:.1}, ΔBIC {:+.1}) ranked it lower, as a clipped force is far from the Gaussian one it assumes. Its size on the check run: {}",
        b.id,
        site.describe(),
        b.check.replayed_chi2_red.unwrap_or(f64::NAN),
        b.check.chi2_red,
        b.delta_bic,
        size(b)
    )
}

/// The sentence of a partial explanation ([`Verdict::Partial`]): how the best falls short, and
/// what each partial candidate closes.
pub(super) fn partial(
    shortfall: &Shortfall,
    partial: &[PartialEffect],
    nominal: &Stage,
    null: &Stage,
) -> String {
    let best = partial
        .first()
        .map_or("the best effect".to_string(), |p| p.id.written(" + "));
    let why = match *shortfall {
        Shortfall::FarAboveNoise { chi2_red } => format!(
            "leaves the check run's reduced χ² at {chi2_red:.1}, more than {EXPLAINED_CHI2} times the noise: the model lacks more than this effect adds"
        ),
        Shortfall::IsoAway {
            aw_gap_percent: (a0, a1),
            seat_gap_points: (s0, s1),
            sigma,
        } => format!(
            "moves the check run's ISO figures away from the measurement (seat a_w gap {a0:+.1} % → {a1:+.1} %, SEAT gap {s0:+.1} → {s1:+.1} points{}): it fits the responses but not where the seat's frequency weighting counts, so its form, its size or a further effect is off there",
            sigma.map_or(String::new(), |s| format!(
                "; its fitted parameters give these ±{:.2} % and ±{:.2} points, so the move is the form's, not the fit's scatter",
                s.aw_percent, s.seat_points
            ))
        ),
    };
    let list = partial
        .iter()
        .map(|p| {
            format!(
                "{} closes {:.0} % (reduced χ² {:.1}, a_w gap {:+.1} %, SEAT gap {:+.1} points)",
                p.id.written(" + "),
                100.0 * p.fraction_closed,
                p.chi2_red,
                p.aw_gap_percent,
                p.seat_gap_points
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    let lead = match shortfall {
        Shortfall::FarAboveNoise { .. } => "a structural gap remains that no candidate explains",
        Shortfall::IsoAway { .. } => {
            "no candidate explains the check run as its a_w and SEAT judge it"
        }
    };
    format!(
        "{lead}: {best} {why}. Partial candidates: {list}. Take a_w and SEAT from the re-fitted model (a_w gap {:+.1} % nominal → {:+.1} % re-fitted, SEAT {:.1} → {:.1} % against {:.1} % measured)",
        nominal.weighted.aw_gap_percent,
        null.weighted.aw_gap_percent,
        nominal.weighted.seat_model,
        null.weighted.seat_model,
        null.weighted.seat_meas
    )
}

/// How the named amplitude-dependent effect's law fits the check run replayed through the
/// simulator, beside its statistical linearisation (`Stage::replayed_chi2_red`); empty when it
/// was not replayed.
fn replayed_fit(st: &Stage) -> String {
    st.replayed_chi2_red.map_or(String::new(), |r| {
        format!(
            "; replayed through the simulator, its fitted law leaves the check run's reduced χ² at {r:.1} (its statistical linearisation {:.1})",
            st.chi2_red
        )
    })
}

/// The warning when amplitude-dependent effect(s) move the check run's ISO figures away
/// ([`Shortfall::decides`]): their law was fitted through its statistical linearisation.
pub(super) fn replayed_iso(s: &Shortfall) -> String {
    match *s {
        Shortfall::IsoAway {
            aw_gap_percent: (a0, a1),
            seat_gap_points: (s0, s1),
            ..
        } => format!(
            "the named effect fits the frequency responses but the check run replayed through its fitted nonlinear model moves the ISO figures away from the measurement (seat a_w gap {a0:+.1} % → {a1:+.1} %, SEAT gap {s0:+.1} → {s1:+.1} points): its law was fitted through its statistical linearisation, which matches second moments rather than the response a run measures, so take a_w and SEAT from the re-fitted model"
        ),
        Shortfall::FarAboveNoise { chi2_red } => {
            format!("the named effect leaves the check run's reduced χ² at {chi2_red:.1}")
        }
    }
}
