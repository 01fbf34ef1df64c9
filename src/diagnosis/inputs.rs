//! Checks of the measured runs before a diagnosis: the channels' calibration (an inverted sign, a
//! unit slip), the paths every run shares, coherence and the paths left out where too few bins are
//! coherent, clipping, and runs given twice.

use super::measure::{Path, RunSpectra};
use super::outcome::ChannelError;
use super::*;
use crate::error::{Error, Result};
use crate::system::Role;
use num_complex::Complex64;

pub(super) fn paths_of(r: &RunSpectra) -> Vec<Path> {
    r.paths.iter().map(|p| p.path).collect()
}

/// Leaves out of every run the paths whose channels `system` does not yield (a triaxial
/// accelerometer's fore-aft axis under a vertical model), with one warning naming them: the
/// model cannot be judged there, and the rest of the run still can. A model without a backrest is
/// judged on a measured backrest force: it predicts none; one whose backrest is a contact it does
/// not resolve vertically (a planar model's) is not.
pub(super) fn keep_modelled<'a>(
    runs: impl IntoIterator<Item = &'a mut RunSpectra>,
    system: &crate::system::System,
    warnings: &mut Vec<String>,
) {
    let no_backrest = !system.links.iter().any(|l| l.role == Role::Backrest);
    let modelled = |p: Path| {
        if p == Path::BackrestMass && no_backrest {
            return true;
        }
        let (x, y) = p.channels();
        [x, y]
            .iter()
            .all(|c| *c == "a_base_z" || system.channel_index(c).is_some())
    };
    let mut dropped: Vec<Path> = Vec::new();
    for r in runs {
        for p in &r.paths {
            if !modelled(p.path) && !dropped.contains(&p.path) {
                dropped.push(p.path);
            }
        }
        r.paths.retain(|p| modelled(p.path));
    }
    if !dropped.is_empty() {
        let channels: Vec<&str> = dropped.iter().map(|p| p.channels().1).collect();
        let paths: Vec<&str> = dropped.iter().map(|p| p.name()).collect();
        warnings.push(format!(
            "{} measured but not an output of model `{}`: path {} not judged",
            channels.join(", "),
            system.name,
            paths.join(", ")
        ));
    }
}

/// Keeps in every run only the paths all runs measured (a force plate fitted for some runs only,
/// a head accelerometer that failed in one), with a warning naming what each run loses; the
/// diagnosis compares runs path by path, so a path judged in one run only cannot be used.
pub(super) fn keep_common(
    train: &mut [RunSpectra],
    check: &mut RunSpectra,
    warnings: &mut Vec<String>,
) {
    let all = || train.iter().chain(std::iter::once(&*check));
    let common: Vec<Path> = paths_of(check)
        .into_iter()
        .filter(|p| all().all(|r| r.path(*p).is_some()))
        .collect();
    for r in train.iter_mut().chain(std::iter::once(check)) {
        let lost: Vec<&str> = r
            .paths
            .iter()
            .filter(|p| !common.contains(&p.path))
            .map(|p| p.path.name())
            .collect();
        if !lost.is_empty() {
            warnings.push(format!(
                "{}: path {} left out: not measured in every run (all runs are compared path by path)",
                r.source,
                lost.join(", ")
            ));
        }
        r.paths.retain(|p| common.contains(&p.path));
    }
}

pub(super) fn check_inputs(
    train: &[RunSpectra],
    check: &RunSpectra,
    warnings: &mut Vec<String>,
) -> Result<()> {
    if train.is_empty() {
        return Err(Error::parameter(
            "--run",
            "at least one training run is needed",
        ));
    }
    // Every run has the same paths here (`keep_common`).
    let want = paths_of(check);
    debug_assert!(train.iter().all(|r| paths_of(r) == want));
    if !want.contains(&Path::BaseSeat) {
        return Err(Error::data(
            &check.source,
            None,
            "needs a_base_z and a_seat_z",
        ));
    }
    // Low coherence leaves a path (or some of its bands) out, with a warning; only a run whose
    // seat does not follow its base anywhere (base→seat without coherent bins) cannot be used.
    for r in train.iter().chain(std::iter::once(check)) {
        let mut usable = true;
        for p in &r.paths {
            let total = p.coherence.len();
            let good = p.coherence.iter().filter(|&&g| score::trusted(g)).count();
            if p.path == Path::BaseSeat && good < MIN_PATH_BINS {
                usable = false;
            }
            if good < MIN_PATH_BINS {
                warnings.push(format!(
                    "{}: path {} left out: only {good} of {total} bins have coherence ≥ 0.8 (its output is barely driven by its input there)",
                    r.source,
                    p.path.name()
                ));
            } else if good * 4 < total * 3 {
                warnings.push(format!(
                    "{}: path {} judged on {good} of {total} bins (coherence ≥ 0.8); the rest is not judged",
                    r.source,
                    p.path.name()
                ));
            }
        }
        if !usable {
            return Err(Error::data(
                &r.source,
                None,
                format!(
                    "path base-seat has fewer than {MIN_PATH_BINS} bins with coherence ≥ 0.8: a_seat_z is not driven by a_base_z (wrong channels, another run's outputs, or noise)"
                ),
            ));
        }
    }
    let (lo, hi) = train.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
        (a.min(r.base_rms), b.max(r.base_rms))
    });
    if check.base_rms < 0.95 * lo || check.base_rms > 1.05 * hi {
        warnings.push(format!(
            "the check run's base r.m.s. {:.3} m/s² lies outside the training range {:.3}–{:.3} m/s²: the held-out score extrapolates in magnitude",
            check.base_rms, lo, hi
        ));
    }
    if train.len() < 2 {
        warnings.push("one training run: magnitude-dependent effects cannot be trained".into());
    }
    Ok(())
}

/// Removes from a run the paths with fewer than [`MIN_PATH_BINS`] coherent bins (their cells are
/// untrusted everywhere), by zeroing their coherence, so that every run keeps the same paths.
pub(super) fn mask_incoherent(r: &mut RunSpectra) {
    for p in &mut r.paths {
        if p.coherence.iter().filter(|&&g| score::trusted(g)).count() < MIN_PATH_BINS {
            p.coherence.iter_mut().for_each(|g| *g = 0.0);
        }
    }
}

/// The channels of `s` that look clipped, with the number of samples at their rail and its value
/// (docs/gap.md §3, quality gates; the one rail test of [`crate::analysis::faults::rails`], so
/// `wbv analyze` and the diagnosis never disagree). Clipping is a distortion of the sensor chain
/// that grows with magnitude, which the distortion trend would otherwise put in the structure.
pub(super) fn clipped(s: &Signals) -> Vec<(String, usize, f64)> {
    s.names
        .iter()
        .zip(&s.data)
        .filter_map(|(name, x)| {
            crate::analysis::faults::clipping(x, s.sample_rate_hz)
                .into_iter()
                .max_by_key(|&(_, n)| n)
                .map(|(v, n)| (name.clone(), n, v))
        })
        .collect()
}

/// Warnings for runs given twice: the check run equal to a training run (its score is then not
/// held out, and an over-fitted candidate is not caught) or a training run repeated (it counts
/// twice in the fit and the evidence). Runs are the same recording when their sample rates and
/// base channels are identical, sample for sample, whatever their file names.
pub(super) fn repeated(train: &[&Signals], check: &Signals) -> Vec<String> {
    let same = |a: &Signals, b: &Signals| {
        a.sample_rate_hz == b.sample_rate_hz
            && a.get("a_base_z").is_some()
            && a.get("a_base_z") == b.get("a_base_z")
    };
    let mut out = Vec::new();
    for (i, t) in train.iter().enumerate() {
        if same(t, check) {
            out.push(format!(
                "the check run {} is the same recording as training run {}: its score is not held out, so an over-fitted candidate is not caught; give a run the fit has not seen",
                check.source, t.source
            ));
        }
        if let Some(u) = train[..i].iter().find(|u| same(u, t)) {
            out.push(format!(
                "training run {} is the same recording as {}: it counts twice in the fit and the evidence",
                t.source, u.source
            ));
        }
    }
    out
}

/// Vertical paths whose level and sign below the first resonance are known: every vertical
/// transmissibility tends to +1 and the apparent mass to +M there (papers 001 eqs. 8–10).
const SIGNED_PATHS: [Path; 4] = [
    Path::BaseSeat,
    Path::SeatHead,
    Path::BaseHead,
    Path::ApparentMass,
];

/// Per channel, the factor its samples are multiplied by to correct them.
pub(super) type Fix = Vec<(&'static str, f64)>;

/// Per channel, a value in [`fewest`]'s search (0: unchanged).
type Assignment = Vec<(&'static str, f64)>;

/// Channels a calibration check can name, in the order a tie is broken.
const CHECKED: [&str; 4] = ["a_base_z", "a_seat_z", "a_head_z", "f_seat_z"];

const G: f64 = crate::io::input::STANDARD_GRAVITY;

/// Unit mix-ups a channel's level can show, as (factor the channel reads, what it means): g and
/// m/s², milli- and kilo- (mm/s², kN), mg, lbf and N. Read values are factor × true.
const UNIT_SLIPS: [(f64, &str); 8] = [
    (1.0 / G, "g read as m/s²"),
    (G, "m/s² read as g"),
    (1.0e-3, "kilo-units (kN) read as base units"),
    (1.0e3, "milli-units (mm/s²) read as base units"),
    (1.0e3 / G, "mg read as m/s²"),
    (G * 1.0e-3, "m/s² read as mg"),
    (1.0 / 4.448_222, "lbf read as N"),
    (4.448_222, "N read as lbf"),
];

/// A path's measured level and sign relative to the model below its first resonance.
struct PathCheck {
    path: Path,
    /// Median of cos(arg(H_meas/H_model)): +1 upright, −1 inverted.
    sign: f64,
    /// Median of ln|H_meas/H_model|.
    level: f64,
}

/// The level and sign of each vertical path of run `r` relative to the nominal model's linear
/// FRF ([`crate::response::frf`]) over its coherent bins up to 1.5 × the model's first natural
/// frequency `f1` (a path with fewer than 4 is not checked): below the first resonance a structural
/// error moves a path by tens of per cent and degrees, an inverted channel by 180°, a unit slip by
/// a fixed factor (9.81, 1000).
fn path_checks(system: &crate::system::System, r: &RunSpectra, f1: f64) -> Vec<PathCheck> {
    let channel = |name: &str| system.channels.iter().position(|c| c.name == name);
    // Only below the first resonance: above it a shifted mode moves the phase by up to 180°. The
    // model's channels per bin, solved once for every path.
    let model: Vec<Option<Vec<Complex64>>> = r
        .freq_hz
        .iter()
        .map(|&f| {
            (f <= 1.5 * f1)
                .then(|| crate::response::frf::solve_point(system, f).ok())
                .flatten()
        })
        .collect();
    let mut out = Vec::new();
    for p in &r.paths {
        if !SIGNED_PATHS.contains(&p.path) {
            continue;
        }
        let (x, y) = p.path.channels();
        let (Some(ix), Some(iy)) = (channel(x), channel(y)) else {
            continue;
        };
        let q: Vec<Complex64> = (0..r.freq_hz.len())
            .filter(|&i| score::trusted(p.coherence[i]))
            .filter_map(|i| {
                let ch = model[i].as_ref()?;
                let q = p.h1[i] / (ch[iy] / ch[ix]);
                (q.norm() > 0.0 && q.is_finite()).then_some(q)
            })
            .collect();
        if q.len() < 4 {
            continue;
        }
        let median = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        out.push(PathCheck {
            path: p.path,
            sign: median(q.iter().map(|q| q.arg().cos()).collect()),
            level: median(q.iter().map(|q| q.norm().ln()).collect()),
        });
    }
    out
}

/// The fewest channel corrections that explain every decided path: `decide(path)` gives the
/// path's required value (None: undecided), `options` the values a corrected channel may take
/// (log factors; the uncorrected value is 0), `fits(sum_y − sum_x, required)` the tolerance.
/// Returns the channels' values and every channel set that explains the paths as well (a tie:
/// base→seat alone cannot tell the base from the seat).
fn fewest(
    checks: &[PathCheck],
    decide: impl Fn(&PathCheck) -> Option<f64>,
    options: &[f64],
    fits: impl Fn(f64, f64) -> bool,
) -> Option<(Assignment, Vec<Vec<&'static str>>)> {
    let names: Vec<&'static str> = CHECKED
        .into_iter()
        .filter(|n| {
            checks
                .iter()
                .any(|c| [c.path.channels().0, c.path.channels().1].contains(n))
        })
        .collect();
    let choices = options.len() + 1;
    let total = choices.pow(names.len() as u32);
    let value = |combo: usize, i: usize| {
        let k = combo / choices.pow(i as u32) % choices;
        if k == 0 { 0.0 } else { options[k - 1] }
    };
    let at = |combo: usize, n: &str| {
        names
            .iter()
            .position(|m| *m == n)
            .map_or(0.0, |i| value(combo, i))
    };
    let explains = |combo: usize| {
        checks.iter().all(|c| match decide(c) {
            None => true,
            Some(want) => {
                let (x, y) = c.path.channels();
                fits(at(combo, y) - at(combo, x), want)
            }
        })
    };
    let changed = |combo: usize| (0..names.len()).filter(|&i| value(combo, i) != 0.0).count();
    let explaining: Vec<usize> = (0..total).filter(|&c| explains(c)).collect();
    let best = explaining.iter().map(|&c| changed(c)).min()?;
    // Each error must show in a path of its own: slips on more channels than there are paths off
    // combine into almost any level (8 slips on 4 channels reach 8⁴ levels), so such a fit is
    // chance, not evidence, and the level is left to the structural diagnosis (a load path that
    // bypasses the force plate lowers the apparent mass by the share of the weight it carries).
    let off = checks
        .iter()
        .filter(|c| decide(c).is_some_and(|v| v != 0.0))
        .count();
    if best > off {
        return None;
    }
    let combos: Vec<usize> = explaining
        .into_iter()
        .filter(|&c| changed(c) == best)
        .collect();
    let values = names
        .iter()
        .enumerate()
        .map(|(i, n)| (*n, value(combos[0], i)))
        .collect();
    let mut sets: Vec<Vec<&'static str>> = Vec::new();
    for &c in &combos {
        let set: Vec<&'static str> = names
            .iter()
            .enumerate()
            .filter(|(i, _)| value(c, *i) != 0.0)
            .map(|(_, n)| *n)
            .collect();
        if !sets.contains(&set) {
            sets.push(set);
        }
    }
    Some((values, sets))
}

/// Calibration errors of the channels of each run, found on the path estimates: an inverted
/// channel (an accelerometer mounted upside down, a force plate reading compression as negative)
/// and a unit slip (a channel in g read as m/s², kN as N), the commonest set-up errors. Returns per
/// run the factor to multiply each wrong channel by, and the findings (merged over runs) for the
/// report; adds a warning per finding and for a level or sign no pattern explains.
///
/// Per run and path, [`path_checks`] gives the sign and level against the model. A path reads
/// inverted below −0.5 and upright above +0.5; its level is off by a unit factor when within
/// ±35 % of one ([`UNIT_SLIPS`]) and right within 0.6–1.6 (a structural error's reach there).
/// The channels named are the fewest that explain every decided path; a level off by more than
/// 2.5× that no unit slip explains is reported, not corrected.
pub(super) fn calibration(
    system: &crate::system::System,
    runs: &[&RunSpectra],
    warnings: &mut Vec<String>,
) -> (Vec<Fix>, Vec<ChannelError>) {
    let f1 = crate::response::modes::undamped(system)
        .ok()
        .and_then(|m| m.first().map(|m| m.freq_hz))
        .unwrap_or(4.0);
    let mut found: Vec<ChannelError> = Vec::new();
    let mut fixes = Vec::new();
    let mut note = |channels: String, error: String, factor: f64, run: &str| match found
        .iter_mut()
        .find(|f| f.channels == channels && f.error == error)
    {
        Some(f) if f.runs.iter().any(|r| r == run) => {}
        Some(f) => f.runs.push(run.to_string()),
        None => found.push(ChannelError {
            channels,
            error,
            factor,
            runs: vec![run.to_string()],
        }),
    };
    for r in runs {
        let checks = path_checks(system, r, f1);
        let mut fix: Fix = Vec::new();
        let or = |sets: &[Vec<&str>]| {
            sets.iter()
                .map(|s| s.join(" and "))
                .collect::<Vec<_>>()
                .join(" or ")
        };
        // Signs: each channel upright (0) or inverted (1); a path's sign is the sum mod 2.
        let sign =
            |c: &PathCheck| (c.sign.abs() > 0.5).then_some(if c.sign < 0.0 { 1.0 } else { 0.0 });
        if checks.iter().any(|c| c.sign < -0.5) {
            match fewest(&checks, sign, &[1.0], |got, want| (got.abs() % 2.0 - want).abs() < 0.5) {
                Some((values, sets)) => {
                    for (n, v) in values {
                        if v != 0.0 {
                            fix.push((n, -1.0));
                        }
                    }
                    note(or(&sets), "inverted (gain −1)".into(), -1.0, &r.source);
                }
                None => warnings.push(format!(
                    "{}: the phases below the first resonance fit no pattern of inverted channels: polarity left as read",
                    r.source
                )),
            }
        }
        // Levels: each channel right (0) or off by a unit slip (ln factor).
        let slips: Vec<f64> = UNIT_SLIPS.iter().map(|(f, _)| f.ln()).collect();
        let level = |c: &PathCheck| {
            if c.level.abs() < 1.6f64.ln() {
                Some(0.0)
            } else if c.level.abs() > 2.5f64.ln() {
                Some(c.level)
            } else {
                None
            }
        };
        if checks.iter().any(|c| c.level.abs() > 2.5f64.ln()) {
            match fewest(&checks, level, &slips, |got, want| {
                (got - want).abs() < 1.35f64.ln()
            }) {
                Some((values, sets)) => {
                    for (n, v) in values {
                        if v != 0.0 {
                            let (f, what) = UNIT_SLIPS
                                .iter()
                                .find(|(f, _)| f.ln() == v)
                                .expect("a slip's value");
                            match fix.iter_mut().find(|(m, _)| *m == n) {
                                Some((_, k)) => *k /= f,
                                None => fix.push((n, 1.0 / f)),
                            }
                            // A tie names every set that explains the paths; one set its
                            // channels one by one, each with its own slip.
                            let who = if sets.len() == 1 {
                                n.to_string()
                            } else {
                                or(&sets)
                            };
                            note(
                                who,
                                format!("reads {f:.4} × the model's level ({what})"),
                                1.0 / f,
                                &r.source,
                            );
                        }
                    }
                }
                None => {
                    let worst = checks
                        .iter()
                        .max_by(|a, b| a.level.abs().total_cmp(&b.level.abs()))
                        .expect("a path off");
                    // Below the first resonance the apparent mass is the weight the plate
                    // carries: a load path past it (thighs on a front frame, hands on a wheel)
                    // lowers it by the share it takes, by more than a mass error's 2.5×.
                    let bypass = if worst.path == Path::ApparentMass && worst.level < 0.0 {
                        ", or a load path that bypasses the force plate (it lowers the apparent mass by the share of the weight it carries; left to the diagnosis)"
                    } else {
                        ""
                    };
                    warnings.push(format!(
                        "{}: path {} reads {:.3} × the model's level below the first resonance, beyond a stiffness or mass error's reach, and no unit slip fits: check the channels' sensitivities and units{bypass}",
                        r.source,
                        worst.path.name(),
                        worst.level.exp()
                    ));
                }
            }
        }
        fixes.push(fix);
    }
    for f in &found {
        warnings.push(format!(
            "{} {} in {}: read from its paths below the model's first natural frequency ({f1:.2} Hz), where every vertical transmissibility tends to +1 and the apparent mass to +M; corrected (× {:.4}) before the diagnosis — check the sensor's mounting, axis convention or units",
            f.channels,
            f.error,
            f.runs.join(", "),
            f.factor
        ));
    }
    (fixes, found)
}

/// `s` with each channel of `fix` multiplied by its factor (a calibration correction).
pub(super) fn scaled(s: &Signals, fix: &[(&str, f64)]) -> Result<Signals> {
    let mut out = Signals::new(s.sample_rate_hz, s.source.clone());
    for (n, d) in s.names.iter().zip(&s.data) {
        let k = fix.iter().find(|(m, _)| m == n).map_or(1.0, |(_, k)| *k);
        out.push(n.clone(), d.iter().map(|v| k * v).collect())?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn a_flat_top_is_clipping_and_a_sine_is_not() {
        let mut s = Signals::new(500.0, "run.csv".to_string());
        let t: Vec<f64> = (0..5000).map(|i| i as f64 / 500.0).collect();
        let sine: Vec<f64> = t.iter().map(|t| (2.0 * PI * 3.3 * t).sin()).collect();
        let rail: Vec<f64> = sine.iter().map(|x| (1.5 * x).clamp(-1.2, 1.2)).collect();
        s.push("a_base_z".to_string(), sine).unwrap();
        s.push("a_seat_z".to_string(), rail).unwrap();
        let c = clipped(&s);
        assert_eq!(c.len(), 1, "{c:?}");
        assert_eq!(c[0].0, "a_seat_z");
        assert!(c[0].1 > 100 && (c[0].2.abs() - 1.2).abs() < 1e-12);
    }

    fn run(name: &str, fs: f64, base: &[f64]) -> Signals {
        let mut s = Signals::new(fs, name.to_string());
        s.push("a_base_z".to_string(), base.to_vec()).unwrap();
        s.push(
            "a_seat_z".to_string(),
            base.iter().map(|v| 0.9 * v).collect(),
        )
        .unwrap();
        s
    }

    #[test]
    fn a_run_given_twice_is_named() {
        let a = run("low.csv", 500.0, &[0.1, -0.2, 0.3, 0.05]);
        let b = run("high.csv", 500.0, &[0.3, -0.6, 0.9, 0.15]);
        assert!(repeated(&[&a, &b], &run("mid.csv", 500.0, &[0.2, 0.1, -0.1, 0.0])).is_empty());
        // The check run is a training run under another name.
        let w = repeated(&[&a, &b], &run("copy.csv", 500.0, &[0.3, -0.6, 0.9, 0.15]));
        assert_eq!(w.len(), 1);
        assert!(
            w[0].contains("copy.csv") && w[0].contains("high.csv") && w[0].contains("not held out")
        );
        // A training run repeated; the same samples at another rate are another recording.
        let w = repeated(&[&a, &b, &a], &run("x.csv", 250.0, &[0.1, -0.2, 0.3, 0.05]));
        assert_eq!(w.len(), 1);
        assert!(w[0].contains("counts twice"));
    }

    /// The reference model's own response to a random base, 120 s at 256 Hz, with each channel
    /// of `fix` multiplied by its factor (an inverted or mis-scaled sensor).
    fn replayed(fix: &[(&str, f64)]) -> (crate::model::Model, RunSpectra) {
        use rand::SeedableRng;
        use rand_distr::Distribution;
        let model = crate::model::catalog::resolve("reference").unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let base: Vec<f64> = (0..256 * 120)
            .map(|_| rand_distr::StandardNormal.sample(&mut rng))
            .collect();
        let sim = super::super::replay::replay(model.system(), &base, 256.0, "run.csv").unwrap();
        let s = scaled(&sim, fix).unwrap();
        (model, super::super::measure::estimate(&s, &[]).unwrap())
    }

    #[test]
    fn an_inverted_or_mis_scaled_channel_is_found_with_its_correction() {
        let g = 9.80665;
        let (model, _) = replayed(&[]);
        for (fix, name, factor) in [
            (vec![("a_seat_z", -1.0)], "a_seat_z", -1.0),
            (vec![("a_head_z", -1.0)], "a_head_z", -1.0),
            (vec![("f_seat_z", -1.0)], "f_seat_z", -1.0),
            (vec![("a_base_z", -1.0)], "a_base_z", -1.0),
            // A seat accelerometer in g read as m/s², a force in kN read as N.
            (vec![("a_seat_z", 1.0 / g)], "a_seat_z", g),
            (vec![("f_seat_z", 1.0e-3)], "f_seat_z", 1.0e3),
            // Upside down and in g.
            (vec![("a_head_z", -1.0 / g)], "a_head_z", -g),
        ] {
            let (_, r) = replayed(&fix);
            let mut w = Vec::new();
            let (fixes, found) = calibration(model.system(), &[&r], &mut w);
            assert!(!found.is_empty(), "{fix:?}");
            assert!(
                found.iter().all(|f| f.channels == name),
                "{fix:?}: {found:?}"
            );
            assert_eq!(fixes[0].len(), 1, "{fix:?}: {:?}", fixes[0]);
            assert_eq!(fixes[0][0].0, name);
            assert!(
                (fixes[0][0].1 / factor - 1.0).abs() < 1e-12,
                "{fix:?}: {:?}",
                fixes[0]
            );
            assert!(w.iter().any(|w| w.contains("in run.csv")), "{w:?}");
        }
        // Upright, right channels are left alone, silently.
        let (_, r) = replayed(&[]);
        let mut w = Vec::new();
        let (fixes, found) = calibration(model.system(), &[&r], &mut w);
        assert!(
            found.is_empty() && fixes[0].is_empty() && w.is_empty(),
            "{found:?} {w:?}"
        );
    }

    #[test]
    fn a_level_no_single_slip_fits_is_reported_not_corrected_by_a_combination() {
        // The apparent mass reading 0.38 × the model's (a load path bypassing the plate carries
        // 62 % of the weight): beyond a structural error's 2.5× and within 35 % of no unit slip;
        // only a combination of slips on several channels reaches it (base, seat and head in
        // lbf, the force in g: 0.102/0.225 = 0.45).
        let (model, r) = replayed(&[("f_seat_z", 0.38)]);
        let mut w = Vec::new();
        let (fixes, found) = calibration(model.system(), &[&r], &mut w);
        assert!(found.is_empty() && fixes[0].is_empty(), "{found:?}");
        assert!(
            w.len() == 1 && w[0].contains("no unit slip fits") && w[0].contains("bypasses"),
            "{w:?}"
        );
    }
}
