//! Checks of the measured runs before a diagnosis: the paths every run shares, coherence, and the
//! paths left out where too few bins are coherent.

use super::measure::{Path, RunSpectra};
use super::outcome::Inversion;
use super::*;
use crate::error::{Error, Result};

pub(super) fn paths_of(r: &RunSpectra) -> Vec<Path> {
    r.paths.iter().map(|p| p.path).collect()
}

/// Leaves out of every run the paths whose channels `system` does not yield (a triaxial
/// accelerometer's fore-aft axis under a vertical model), with one warning naming them: the
/// model cannot be judged there, and the rest of the run still can.
pub(super) fn keep_modelled<'a>(
    runs: impl IntoIterator<Item = &'a mut RunSpectra>,
    system: &crate::system::System,
    warnings: &mut Vec<String>,
) {
    let modelled = |p: Path| {
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

/// Fewest samples at a channel's extreme value that mark it as clipped: a continuous signal
/// reaches its maximum once, and even a 1e-4 m/s² CSV resolution repeats a peak value only a few
/// times in a long run; an amplifier or ADC at its rail holds it for whole flat tops.
pub const CLIPPED_SAMPLES: usize = 10;

/// The channels of `s` that look clipped, with the number of samples at their extreme value and
/// that value (gap.md §3.5 item 1: quality gates). Clipping is a distortion of the sensor chain
/// that grows with magnitude, which the distortion trend would otherwise put in the structure.
pub(super) fn clipped(s: &Signals) -> Vec<(String, usize, f64)> {
    s.names
        .iter()
        .zip(&s.data)
        .filter_map(|(name, x)| {
            let hi = x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let lo = x.iter().copied().fold(f64::INFINITY, f64::min);
            if hi.is_nan() || lo.is_nan() || hi <= lo {
                return None;
            }
            let at = |v: f64| x.iter().filter(|&&y| y == v).count();
            let (n_hi, n_lo) = (at(hi), at(lo));
            let (n, v) = if n_hi >= n_lo { (n_hi, hi) } else { (n_lo, lo) };
            (n >= CLIPPED_SAMPLES).then(|| (name.clone(), n, v))
        })
        .collect()
}

/// Warnings for runs given twice: the check run equal to a training run (its score is then not
/// held out, and an over-fitted candidate is not caught) or a training run repeated (it counts
/// twice in the fit and the evidence). Runs are the same recording when their sample rates and
/// base channels are identical, sample for sample, whatever their file names.
pub(super) fn repeated(train: &[Signals], check: &Signals) -> Vec<String> {
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

/// Vertical paths whose sign below the first resonance is known: every vertical transmissibility
/// tends to +1 and the apparent mass to +M there (papers 001 eqs. 8–10).
const SIGNED_PATHS: [Path; 4] = [
    Path::BaseSeat,
    Path::SeatHead,
    Path::BaseHead,
    Path::ApparentMass,
];

/// Finds channels whose polarity is inverted and corrects the path estimates in place (H1 of a
/// path with one inverted channel is negated; coherence and PSDs do not change).
///
/// Per run and path, the sign is the median over coherent bins up to 1.5 × the model's first
/// natural frequency (at least the 4 lowest coherent bins) of cos(arg(H_meas/H_model)), with
/// H_model the nominal model's linear FRF ([`crate::response::frf`]): below its first resonance a
/// structural error moves the phase by tens of degrees, an inverted channel by 180°. A path reads
/// inverted below −0.5, upright above +0.5. The channels are then the fewest flips that explain
/// every decided path; a path set no flip pattern explains is left alone, with a warning.
pub(super) fn polarity(
    system: &crate::system::System,
    runs: &mut [&mut RunSpectra],
    warnings: &mut Vec<String>,
) -> Vec<Inversion> {
    let f1 = crate::response::modes::undamped(system)
        .ok()
        .and_then(|m| m.first().map(|m| m.freq_hz))
        .unwrap_or(4.0);
    let channel = |name: &str| system.channels.iter().position(|c| c.name == name);
    let mut found: Vec<Inversion> = Vec::new();
    for r in runs.iter_mut() {
        // Sign of each signed path present in this run: Some(±1) decided, None undecided.
        let mut signs: Vec<(Path, f64)> = Vec::new();
        for p in &r.paths {
            if !SIGNED_PATHS.contains(&p.path) {
                continue;
            }
            let (x, y) = p.path.channels();
            let (Some(ix), Some(iy)) = (channel(x), channel(y)) else {
                continue;
            };
            let bins: Vec<usize> = (0..r.freq_hz.len())
                .filter(|&i| score::trusted(p.coherence[i]))
                .collect();
            let mut low: Vec<usize> = bins
                .iter()
                .copied()
                .filter(|&i| r.freq_hz[i] <= 1.5 * f1)
                .collect();
            if low.len() < 4 {
                low = bins.iter().copied().take(4).collect();
            }
            if low.len() < 4 {
                continue;
            }
            let mut cos: Vec<f64> = low
                .iter()
                .filter_map(|&i| {
                    let ch = crate::response::frf::solve_point(system, r.freq_hz[i]).ok()?;
                    let model = ch[iy] / ch[ix];
                    let c = (p.h1[i] / model).arg().cos();
                    c.is_finite().then_some(c)
                })
                .collect();
            if cos.len() < 4 {
                continue;
            }
            cos.sort_by(f64::total_cmp);
            let med = cos[cos.len() / 2];
            if med.abs() > 0.5 {
                signs.push((p.path, med.signum()));
            }
        }
        if signs.iter().all(|(_, s)| *s > 0.0) {
            continue;
        }
        // The fewest channel flips that give every decided path its sign.
        let names: Vec<&str> = ["a_base_z", "a_seat_z", "a_head_z", "f_seat_z"]
            .into_iter()
            .filter(|n| {
                signs
                    .iter()
                    .any(|(p, _)| [p.channels().0, p.channels().1].contains(n))
            })
            .collect();
        let sign_of = |mask: usize, n: &str| {
            let i = names.iter().position(|m| *m == n);
            if i.is_some_and(|i| mask >> i & 1 == 1) {
                -1.0
            } else {
                1.0
            }
        };
        let explains = |mask: usize| {
            signs.iter().all(|(p, s)| {
                let (x, y) = p.channels();
                sign_of(mask, x) * sign_of(mask, y) == *s
            })
        };
        let fewest = (0..1usize << names.len())
            .filter(|&m| explains(m))
            .map(|m| m.count_ones())
            .min();
        let Some(fewest) = fewest else {
            warnings.push(format!(
                "{}: the phases below the first resonance fit no pattern of inverted channels (paths {}): polarity left as read",
                r.source,
                signs
                    .iter()
                    .map(|(p, s)| format!("{} {}", p.name(), if *s > 0.0 { "upright" } else { "inverted" }))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
            continue;
        };
        let masks: Vec<usize> = (0..1usize << names.len())
            .filter(|&m| explains(m) && m.count_ones() == fewest)
            .collect();
        // Ambiguous masks (base→seat alone: base or seat) name every channel they could be.
        let label = masks
            .iter()
            .map(|&m| {
                names
                    .iter()
                    .enumerate()
                    .filter(|(i, _)| m >> i & 1 == 1)
                    .map(|(_, n)| *n)
                    .collect::<Vec<_>>()
                    .join(" and ")
            })
            .collect::<Vec<_>>()
            .join(" or ");
        let mask = masks[0];
        for p in &mut r.paths {
            let (x, y) = p.path.channels();
            if SIGNED_PATHS.contains(&p.path) && sign_of(mask, x) * sign_of(mask, y) < 0.0 {
                p.h1.iter_mut().for_each(|h| *h = -*h);
            }
        }
        match found.iter_mut().find(|f| f.channels == label) {
            Some(f) => f.runs.push(r.source.clone()),
            None => found.push(Inversion {
                channels: label,
                runs: vec![r.source.clone()],
            }),
        }
    }
    for f in &found {
        warnings.push(format!(
            "{} inverted in {}: below the first resonance its paths are 180° from the model's (a transmissibility tends to +1 there, the apparent mass to +M); the diagnosis uses it with the sign corrected — check the sensor's mounting or axis convention",
            f.channels,
            f.runs.join(", ")
        ));
    }
    found
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
        assert!(
            repeated(
                &[a.clone(), b.clone()],
                &run("mid.csv", 500.0, &[0.2, 0.1, -0.1, 0.0])
            )
            .is_empty()
        );
        // The check run is a training run under another name.
        let w = repeated(
            &[a.clone(), b.clone()],
            &run("copy.csv", 500.0, &[0.3, -0.6, 0.9, 0.15]),
        );
        assert_eq!(w.len(), 1);
        assert!(
            w[0].contains("copy.csv") && w[0].contains("high.csv") && w[0].contains("not held out")
        );
        // A training run repeated; the same samples at another rate are another recording.
        let w = repeated(
            &[a.clone(), b.clone(), a.clone()],
            &run("x.csv", 250.0, &[0.1, -0.2, 0.3, 0.05]),
        );
        assert_eq!(w.len(), 1);
        assert!(w[0].contains("counts twice"));
    }

    /// The reference model's own response to a random base, 120 s at 256 Hz, with `invert`
    /// negated.
    fn replayed(invert: &[&str]) -> (crate::model::Model, RunSpectra) {
        use rand::SeedableRng;
        use rand_distr::Distribution;
        let model = crate::model::catalog::resolve("reference").unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let base: Vec<f64> = (0..256 * 120)
            .map(|_| rand_distr::StandardNormal.sample(&mut rng))
            .collect();
        let sim = super::super::replay::replay(model.system(), &base, 256.0, "run.csv").unwrap();
        let mut s = Signals::new(256.0, "run.csv".to_string());
        for (n, d) in sim.names.iter().zip(&sim.data) {
            let k = if invert.contains(&n.as_str()) {
                -1.0
            } else {
                1.0
            };
            s.push(n.clone(), d.iter().map(|v| k * v).collect())
                .unwrap();
        }
        (model, super::super::measure::estimate(&s).unwrap())
    }

    #[test]
    fn an_inverted_channel_is_found_and_corrected() {
        let (model, upright) = replayed(&[]);
        for (flip, name) in [
            (vec!["a_seat_z"], "a_seat_z"),
            (vec!["a_head_z"], "a_head_z"),
            (vec!["f_seat_z"], "f_seat_z"),
            (vec!["a_base_z"], "a_base_z"),
        ] {
            let (_, mut r) = replayed(&flip);
            let mut w = Vec::new();
            let found = polarity(model.system(), &mut [&mut r], &mut w);
            assert_eq!(found.len(), 1, "{flip:?}: {found:?}");
            assert_eq!(found[0].channels, name);
            assert!(w[0].contains("inverted in run.csv"), "{w:?}");
            // Every path is back to the upright estimate.
            for (p, q) in r.paths.iter().zip(&upright.paths) {
                for (a, b) in p.h1.iter().zip(&q.h1) {
                    assert!(
                        (a - b).norm() <= 1e-9 * b.norm().max(1e-12),
                        "{flip:?} {:?}",
                        p.path
                    );
                }
            }
        }
        // Upright channels are left alone, silently.
        let (_, mut r) = replayed(&[]);
        let mut w = Vec::new();
        assert!(polarity(model.system(), &mut [&mut r], &mut w).is_empty());
        assert!(w.is_empty());
    }
}
