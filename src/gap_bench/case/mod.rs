//! Blind cases: the `reference` setup with nuisance errors (masses ±10 %, stiffness ±15 %, damping
//! ±25 %), zero, one or two planted truth forms, three runs (two training magnitudes and a held-out
//! one) driven by a base spectrum from the excitation library, simulated in the time domain with
//! the average-acceleration Newmark rule at ≥ 2 kHz, passed through the sensors and sampled at
//! 200–2000 Hz with 0.5–3 % noise, 60–300 s long, with or without `f_seat_z`. The label is sealed
//! in the [`Case`] and only read by the scorer.

use super::forms::{self, Family, Form, Planted, Sensor};
use acquire::{measure, simulate};
use detect::detectability;

mod acquire;
mod detect;
pub mod logger;
use crate::analysis::spectrum::{Segment, Welch, WelchOptions};
use crate::error::Result;
use crate::excitation::{ExcitationSpec, Kind};
use crate::integrator::Method;
use crate::model::{Chain, Element, catalog};
use crate::scenario::Scenario;
use crate::signals::Signals;
use crate::simulate::Settings;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use serde::Serialize;

/// Base spectrum kinds drawn per case.
pub const SPECTRA: [&str; 4] = ["white", "helicopter", "road", "shaped"];
/// Acquisition rates drawn per case, Hz.
pub const RATES: [f64; 6] = [200.0, 256.0, 500.0, 512.0, 1000.0, 2000.0];
/// Lowest internal simulation rate, Hz (Newmark period error (ωΔt)²/12 < 0.1 % at 35 Hz).
pub const SIM_RATE: f64 = 2000.0;
/// Fraction of effect cases that carry a second effect from another family.
pub const PAIR_FRACTION: f64 = 0.1;

/// One planted effect in the sealed label.
#[derive(Debug, Clone, Serialize)]
pub struct PlantedLabel {
    /// Family.
    pub family: Family,
    /// Functional form.
    pub form: Form,
    /// Strength in [0, 1].
    pub strength: f64,
    /// Parameter description.
    pub detail: String,
}

/// Nuisances of a case.
#[derive(Debug, Clone, Serialize)]
pub struct Nuisance {
    /// Base spectrum kind (one of [`SPECTRA`]).
    pub spectrum: &'static str,
    /// Acquisition rate, Hz.
    pub fs_hz: f64,
    /// Run length, s.
    pub duration_s: f64,
    /// White noise per channel, % of the channel r.m.s.
    pub noise_percent: f64,
    /// Whether `f_seat_z` is measured.
    pub force: bool,
    /// Largest |mass error| over the masses, %.
    pub mass_error_percent: f64,
    /// Base r.m.s. of the runs (train, train, check), m/s².
    pub rms: [f64; 3],
    /// A logger fault planted on the measured runs ([`logger::FAULTS`]), if any.
    pub logger_fault: Option<&'static str>,
    /// The base accelerometer's own white noise floor on top of `noise_percent`, % of the base
    /// r.m.s. (a field logger's MEMS sensor under a road spectrum; 0 = none).
    pub base_floor_percent: f64,
    /// Whether the backrest's vertical force `f_back_z` is measured (half the cases with a planted
    /// backrest: what a backrest study adds to the z-only channels).
    pub backrest_force: bool,
}

/// The sealed label of a case.
#[derive(Debug, Clone, Serialize)]
pub struct Label {
    /// Planted effects (empty: none).
    pub effects: Vec<PlantedLabel>,
    /// Nuisances.
    pub nuisance: Nuisance,
    /// Detectability: RMS over the top-magnitude training run's coherent bins of |ln(H_truth/H_without)|/σ on the
    /// most affected path, σ² = σ_H1² + 0.01² (H1 random error from coherence and averages plus a
    /// 1 % repeatability floor). 0 for no-effect cases.
    pub detectability: f64,
}

/// A blind case: runs for the tool, label for the scorer.
pub struct Case {
    /// Training runs.
    pub train: Vec<Signals>,
    /// Held-out run.
    pub check: Signals,
    /// The hidden truth.
    pub label: Label,
}

fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    lo + rng.random::<f64>() * (hi - lo)
}

/// The base excitation of `kind` scaled to r.m.s. `rms` (m/s²).
fn spectrum(kind: &str, rms: f64, shape: &[f64; 3]) -> Result<ExcitationSpec> {
    let spec = match kind {
        "white" => ExcitationSpec::new(
            Kind::Random {
                rms_m_s2: rms,
                band_hz: [0.5, 40.0 + 40.0 * shape[0]],
            },
            "bench white",
        )?,
        "helicopter" => ExcitationSpec::load("bell-214")?,
        "road" => ExcitationSpec::load("road-c-72kmh")?,
        _ => {
            // A PSD-shaped floor spectrum: a broad hump at 2–8 Hz over a sloping floor to 60 Hz.
            let fp = 2.0 + 6.0 * shape[1];
            let slope = 1.0 + 2.0 * shape[2];
            let points: Vec<[f64; 2]> = [0.5, 1.0, fp * 0.7, fp, fp * 1.4, 20.0, 40.0, 60.0]
                .iter()
                .map(|&f| {
                    let hump = if (fp * 0.7..=fp * 1.4).contains(&f) {
                        4.0
                    } else {
                        1.0
                    };
                    [f, hump * (f.max(1.0)).powf(-slope / 2.0)]
                })
                .collect();
            ExcitationSpec::new(
                Kind::Psd {
                    points,
                    csv: None,
                    table: None,
                },
                "bench shaped PSD",
            )?
        }
    };
    let now = spec.rms_m_s2().unwrap_or(1.0);
    let s = rms / now;
    let mut spec = spec;
    match &mut spec.kind {
        Kind::Helicopter(h) => {
            h.broadband_psd_m2_s4_hz *= s * s;
            for l in &mut h.lines {
                l.amplitude_m_s2 *= s;
            }
        }
        Kind::Road {
            gd_n0_m3, class, ..
        } => {
            let gd = crate::excitation::road::class_gd_n0_m3(class.as_deref().unwrap_or("C"))
                .unwrap_or(256e-6);
            *gd_n0_m3 = Some(gd * s * s);
        }
        Kind::Psd { points, .. } => {
            for p in points.iter_mut() {
                p[1] *= s * s;
            }
            return ExcitationSpec::new(
                Kind::Psd {
                    points: points.clone(),
                    csv: None,
                    table: None,
                },
                "bench shaped PSD",
            );
        }
        _ => {}
    }
    Ok(spec)
}

/// The spectrum as (Hz, mean square) lines on a 0.1 Hz grid to 100 Hz, tones added.
fn lines(spec: &ExcitationSpec) -> Vec<(f64, f64)> {
    let df = 0.1;
    let mut out: Vec<(f64, f64)> = (1..1000)
        .map(|i| {
            let f = i as f64 * df;
            (f, spec.psd(f) * df)
        })
        .collect();
    out.extend(spec.tones().iter().map(|&(f, a)| (f, a * a / 2.0)));
    out
}

/// Nuisance perturbation of the base model: every mass ±10 %, every Kelvin–Voigt k ±15 % and c ±25 %
/// (uniform); returns the largest |mass error| in %.
fn perturb(model: &mut Chain, rng: &mut ChaCha8Rng) -> f64 {
    let mut worst = 0.0f64;
    for m in &mut model.masses {
        let e = uniform(rng, -0.1, 0.1);
        m.m *= 1.0 + e;
        worst = worst.max(e.abs());
    }
    for l in &mut model.links {
        if let Element::KelvinVoigt { k, c } = l.element {
            l.element = Element::KelvinVoigt {
                k: k * (1.0 + uniform(rng, -0.15, 0.15)),
                c: c * (1.0 + uniform(rng, -0.25, 0.25)),
            };
        }
    }
    100.0 * worst
}

/// What case `index` of a bench with master `seed` plants: `None` for every seventh case, otherwise
/// a family in rotation and a form in rotation within it.
pub fn effects_of(index: usize, rng: &mut ChaCha8Rng) -> Vec<(Form, f64)> {
    let period = Family::ALL.len() + 1;
    let slot = index % period;
    if slot == 0 {
        return Vec::new();
    }
    let family = Family::ALL[slot - 1];
    let forms = Form::of(family);
    let form = forms[(index / period) % forms.len()];
    let mut out = vec![(form, rng.random::<f64>())];
    if rng.random::<f64>() < PAIR_FRACTION {
        let others: Vec<Family> = Family::ALL.into_iter().filter(|f| *f != family).collect();
        let f2 = others[(rng.random::<f64>() * others.len() as f64) as usize % others.len()];
        let forms2 = Form::of(f2);
        let form2 = forms2[(rng.random::<f64>() * forms2.len() as f64) as usize % forms2.len()];
        out.push((form2, rng.random::<f64>()));
    }
    out
}

/// Fixed values replacing a case's random draws (tests, timing); `None` keeps the draw. The draws
/// are made either way, so the other values of a case do not change.
#[derive(Debug, Clone, Default)]
pub struct CaseOptions {
    /// Planted effects (form, strength); `Some(vec![])` plants none.
    pub effects: Option<Vec<(Form, f64)>>,
    /// Base spectrum kind (one of [`SPECTRA`]).
    pub spectrum: Option<&'static str>,
    /// Acquisition rate, Hz.
    pub fs_hz: Option<f64>,
    /// Run length, s.
    pub duration_s: Option<f64>,
    /// Noise, fraction of the channel r.m.s.
    pub noise: Option<f64>,
    /// Whether `f_seat_z` is measured.
    pub force: Option<bool>,
    /// The base accelerometer's extra noise floor, fraction of the base r.m.s.
    pub base_floor: Option<f64>,
    /// Whether a planted backrest's force `f_back_z` is measured.
    pub backrest_force: Option<bool>,
}

/// Builds case `index` of a bench with master seed `seed`.
pub fn make_case(index: usize, seed: u64) -> Result<Case> {
    make_case_with(index, seed, &CaseOptions::default())
}

/// Builds case `index` of a bench with master seed `seed`, with some draws fixed by `o`.
pub fn make_case_with(index: usize, seed: u64, o: &CaseOptions) -> Result<Case> {
    let cseed = seed.wrapping_mul(1_000_003).wrapping_add(index as u64);
    let mut rng = ChaCha8Rng::seed_from_u64(cseed);
    let effects = effects_of(index, &mut rng);
    let effects = o.effects.clone().unwrap_or(effects);
    let kind = SPECTRA[(rng.random::<f64>() * 4.0) as usize % 4];
    let kind = o.spectrum.unwrap_or(kind);
    let fs = RATES[(rng.random::<f64>() * RATES.len() as f64) as usize % RATES.len()];
    let fs = o.fs_hz.unwrap_or(fs);
    // Log-uniform 60–300 s, whole seconds.
    let duration_s = (60f64.ln() + rng.random::<f64>() * 5f64.ln()).exp().round();
    let duration_s = o.duration_s.unwrap_or(duration_s);
    let noise = uniform(&mut rng, 0.005, 0.03);
    let noise = o.noise.unwrap_or(noise);
    let force = rng.random::<f64>() < 0.5;
    let force = o.force.unwrap_or(force);
    let shape = [
        rng.random::<f64>(),
        rng.random::<f64>(),
        rng.random::<f64>(),
    ];
    let m0 = uniform(&mut rng, 0.6, 1.4);
    let rms = [0.5 * m0, 1.5 * m0, m0];
    let mut base = catalog::resolve_chain("reference")?;
    let mass_error = perturb(&mut base, &mut rng);
    let specs: Vec<ExcitationSpec> = rms
        .iter()
        .map(|&a| spectrum(kind, a, &shape))
        .collect::<Result<_>>()?;
    let top = lines(&specs[1]);
    let mut truth = base.clone();
    let mut planted = Planted::default();
    let mut labels = Vec::new();
    for &(form, u) in &effects {
        let (p, detail) = forms::plant(
            form,
            u,
            &mut rng,
            &mut truth,
            &top,
            forms::Acquisition { fs, force },
            rms,
        )?;
        planted.schedule = planted.schedule.or(p.schedule);
        planted.sensors.extend(p.sensors);
        labels.push(PlantedLabel {
            family: form.family(),
            form,
            strength: u,
            detail,
        });
    }
    // Half the road cases measure the base with a field logger's accelerometer: a white floor of
    // 2–6 % of the base r.m.s. (MEMS, 1–3 mg/√Hz over 100 Hz), under which a road spectrum falls
    // above ~15 Hz; drawn from its own stream, so the other draws stay.
    let mut frng = ChaCha8Rng::seed_from_u64(cseed ^ 0xf100_0000_0000_0001);
    let base_floor = if kind == "road" && frng.random::<f64>() < 0.5 {
        uniform(&mut frng, 0.02, 0.06)
    } else {
        0.0
    };
    let base_floor = o.base_floor.unwrap_or(base_floor);
    // Half the cases with a backrest instrument it (its own stream too).
    let mut brng = ChaCha8Rng::seed_from_u64(cseed ^ 0xbac4_0000_0000_0001);
    let has_backrest = effects.iter().any(|(f, _)| *f == Form::Backrest);
    let backrest_force = has_backrest && brng.random::<f64>() < 0.5;
    let backrest_force = has_backrest && o.backrest_force.unwrap_or(backrest_force);
    let mut runs = Vec::new();
    let mut clean_top = None;
    for (j, spec) in specs.iter().enumerate() {
        let model = match &planted.schedule {
            Some(s) => forms::scheduled(&truth, s, rms[j]),
            None => truth.clone(),
        };
        let rseed = cseed.wrapping_mul(31).wrapping_add(j as u64 + 1);
        let sim = simulate(&model, spec, fs, duration_s, rseed, &planted.sensors)?;
        let mut nrng = ChaCha8Rng::seed_from_u64(rseed ^ 0x5eed_0000_0000_0001);
        let role = if j == 2 { "check" } else { "train" };
        let meas = measure(
            &sim,
            (noise, base_floor),
            (force, backrest_force),
            &mut nrng,
            format!("case {index} {role} run {j} ({:.2} m/s²)", rms[j]),
        )?;
        if j == 1 {
            clean_top = Some(sim);
        }
        runs.push(meas);
    }
    let check = runs.pop().expect("three runs");
    let detect = if effects.is_empty() {
        0.0
    } else {
        // Same realisation as the top-magnitude training run, without the effects.
        let without = simulate(
            &base,
            &specs[1],
            fs,
            duration_s,
            cseed.wrapping_mul(31).wrapping_add(2),
            &[],
        )?;
        detectability(
            clean_top.as_ref().expect("top run simulated"),
            &without,
            &runs[1],
        )?
    };
    // The logger's faults after the detectability, which is the effect's and not the logger's.
    runs.push(check);
    let logger_fault = logger::plant(cseed, &mut runs)?;
    let check = runs.pop().expect("three runs");
    Ok(Case {
        train: runs,
        check,
        label: Label {
            effects: labels,
            nuisance: Nuisance {
                spectrum: kind,
                fs_hz: fs,
                duration_s,
                noise_percent: 100.0 * noise,
                force,
                mass_error_percent: mass_error,
                rms,
                logger_fault,
                base_floor_percent: 100.0 * base_floor,
                backrest_force,
            },
            detectability: detect,
        },
    })
}
