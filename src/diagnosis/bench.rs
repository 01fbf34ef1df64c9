//! `wbv gap-bench`: blind cases made inside the simulator (gap.md §4.1). Each case perturbs the
//! reference setup's link stiffness and damping by up to ±10 %, plants one effect (or none) with a
//! random strength from barely detectable to strong, simulates two training runs and a check run at
//! three magnitudes with 1 % sensor noise, and hides the label from the diagnosis; the scorer joins
//! the labels afterwards.

use super::candidate::{add_frame, base_params, interface_link, role_link};
use super::predict::equivalent;
use super::{Diagnosis, diagnose};
use crate::error::Result;
use crate::excitation::{ExcitationSpec, Kind};
use crate::integrator::Method;
use crate::model::{Element, Law, Model, Role, catalog, params};
use crate::scenario::Scenario;
use crate::signals::{Signals, delay};
use crate::simulate::Settings;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use serde::Serialize;

/// Planted effects, in rotation order (`none` first).
pub const EFFECTS: [&str; 6] = [
    "none",
    "body-softening",
    "cushion-stiffening",
    "cushion-viscoelastic",
    "sensor-delay",
    "missing-dof",
];

/// Benchmark settings.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// Number of cases.
    pub cases: usize,
    /// Master seed.
    pub seed: u64,
    /// Run length in s.
    pub duration_s: f64,
    /// Sample rate of the runs in Hz (truth simulated at twice this and decimated).
    pub fs: f64,
    /// Base r.m.s. of the two training runs and the check run, m/s².
    pub magnitudes: [f64; 3],
}

impl Default for BenchOptions {
    fn default() -> Self {
        BenchOptions {
            cases: 60,
            seed: 1,
            duration_s: 120.0,
            fs: 250.0,
            magnitudes: [0.5, 1.5, 1.0],
        }
    }
}

/// The sealed label of a case.
#[derive(Debug, Clone, Serialize)]
pub struct Label {
    /// Planted effect id or `none`.
    pub effect: &'static str,
    /// Strength in [0, 1] (0 barely detectable, 1 strong).
    pub strength: f64,
    /// Planted parameter description.
    pub detail: String,
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

/// r.m.s. deflection of `link` in the linear `model` for white base acceleration of r.m.s. `rms`
/// over 0.5–40 Hz, m.
fn link_rms(model: &Model, link: usize, rms: f64) -> Result<f64> {
    let df = 0.25;
    let freq: Vec<f64> = (0..=400).map(|i| i as f64 * df).collect();
    let g = rms * rms / 39.5;
    let psd: Vec<f64> = freq
        .iter()
        .map(|&f| if (0.5..=40.0).contains(&f) { g } else { 0.0 })
        .collect();
    let mut m = model.clone();
    m.links[link].law = None;
    let mut var = 0.0;
    for (&f, &p) in freq.iter().zip(&psd) {
        if p == 0.0 {
            continue;
        }
        let (acc, _) = crate::response::frf::solve_point(&m, f)?;
        let w2 = (2.0 * std::f64::consts::PI * f).powi(2);
        let x = |n: crate::model::Node| match n {
            crate::model::Node::Base => num_complex::Complex64::new(0.0, 0.0),
            crate::model::Node::Mass(i) => (1.0 - acc[i]) / w2,
        };
        let l = &m.links[link];
        var += (x(l.a) - x(l.b)).norm_sqr() * p * df;
    }
    Ok(var.sqrt())
}

/// A planted truth: model, optional (channel, delay in s), description.
type Truth = (Model, Option<(&'static str, f64)>, String);

/// The truth model and output delay of one case.
fn plant(effect: &str, u: f64, rng: &mut ChaCha8Rng, hi_rms: f64) -> Result<Truth> {
    let mut m = catalog::resolve("reference")?;
    for (path, nominal) in base_params(&m) {
        let f = 1.0 + 0.1 * (2.0 * rng.random::<f64>() - 1.0);
        params::set(&mut m, &path, nominal * f)?;
    }
    let mut out_delay = None;
    let detail = match effect {
        "body-softening" => {
            let i = interface_link(&m).expect("reference has an interface");
            let (k, c) = (m.links[i].element.static_stiffness(), 0.0);
            // Stiffness loss at the high magnitude from 3 % (barely) to 40 % (strong).
            let target = 1.0 - (0.03 + 0.37 * u);
            let s = link_rms(&m, i, hi_rms)?;
            let (mut lo, mut hi) = (1e-3, 20.0);
            for _ in 0..60 {
                let x = 0.5 * (lo + hi);
                let (ke, _) = equivalent(&Law::Softening { d_ref: s / x }, k, c, s, 0.0);
                if ke / k > target { lo = x } else { hi = x }
            }
            let d_ref = s / lo;
            m.links[i].law = Some(Law::Softening { d_ref });
            format!(
                "softening on {}: d_ref = {:.3} mm",
                m.links[i].name,
                d_ref * 1e3
            )
        }
        "cushion-stiffening" => {
            let i = role_link(&m, Role::Cushion).expect("reference has a cushion");
            let k = m.links[i].element.static_stiffness();
            let s = link_rms(&m, i, hi_rms)?;
            let k3 = (0.04 + 0.6 * u) * k / (3.0 * s * s);
            m.links[i].law = Some(Law::Cubic { k3 });
            format!("cubic cushion: k3 = {k3:.3e} N/m³")
        }
        "cushion-viscoelastic" => {
            let i = role_link(&m, Role::Cushion).expect("reference has a cushion");
            if let Element::KelvinVoigt { k, c } = m.links[i].element {
                let r = (20f64.ln() + u * (0.5f64.ln() - 20f64.ln())).exp();
                m.links[i].element = Element::Zener {
                    k,
                    k_m: r * k,
                    c_m: c,
                };
                format!("Zener cushion: k_m/k = {r:.2}")
            } else {
                unreachable!("reference cushion is Kelvin–Voigt")
            }
        }
        "sensor-delay" => {
            let ch = if rng.random::<f64>() < 0.5 {
                "a_seat_z"
            } else {
                "a_head_z"
            };
            let tau = 0.001 + 0.019 * u;
            out_delay = Some((ch, tau));
            format!("delay of {:.1} ms on {ch}", tau * 1e3)
        }
        "missing-dof" => {
            let f = 40.0 - 25.0 * u;
            let z = 0.05 + 0.1 * rng.random::<f64>();
            add_frame(&mut m, f, z, super::candidate::FRAME_MASS_KG)?;
            format!("seat frame at {f:.1} Hz, ζ = {z:.3}")
        }
        _ => "no effect".into(),
    };
    Ok((m, out_delay, detail))
}

/// Simulates one run of `model` at base r.m.s. `rms`; decimates by 2 and adds 1 % white sensor noise.
fn simulate_run(
    model: &Model,
    rms: f64,
    opts: &BenchOptions,
    seed: u64,
    delay_ch: Option<(&str, f64)>,
) -> Result<Signals> {
    let exc = ExcitationSpec::new(
        Kind::Random {
            rms_m_s2: rms,
            band_hz: [0.5, 40.0],
        },
        "bench random",
    )?;
    let sc = Scenario {
        model: model.clone(),
        excitation: exc,
        settings: Settings {
            dt: 0.5 / opts.fs,
            duration_s: opts.duration_s,
            method: Method::AVERAGE_ACCELERATION,
        },
        seed,
    };
    let full = sc.signals()?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed_0000_0000_0001);
    let mut out = Signals::new(opts.fs, format!("bench run {rms} m/s² (seed {seed})"));
    for (name, data) in full.names.iter().zip(&full.data) {
        let x: Vec<f64> = data.iter().step_by(2).copied().collect();
        let x = match delay_ch {
            Some((ch, tau)) if ch == name => delay(&x, opts.fs, tau),
            _ => x,
        };
        let s = 0.01 * crate::analysis::figures::rms(&x);
        let noisy = x
            .iter()
            .map(|v| v + s * rng.sample::<f64, _>(StandardNormal))
            .collect();
        out.push(name.clone(), noisy)?;
    }
    Ok(out)
}

/// Builds case `index` of a benchmark with master seed `seed`.
pub fn make_case(index: usize, opts: &BenchOptions) -> Result<Case> {
    let seed = opts.seed.wrapping_mul(1_000_003).wrapping_add(index as u64);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let effect = EFFECTS[index % EFFECTS.len()];
    let u: f64 = rng.random();
    let hi = opts.magnitudes.iter().cloned().fold(0.0, f64::max);
    let (model, d, detail) = plant(effect, u, &mut rng, hi)?;
    let runs: Vec<Signals> = opts
        .magnitudes
        .iter()
        .enumerate()
        .map(|(j, &a)| {
            simulate_run(
                &model,
                a,
                opts,
                seed.wrapping_mul(31).wrapping_add(j as u64 + 1),
                d,
            )
        })
        .collect::<Result<_>>()?;
    let mut runs = runs;
    let check = runs.pop().expect("three magnitudes");
    Ok(Case {
        train: runs,
        check,
        label: Label {
            effect,
            strength: if effect == "none" { 0.0 } else { u },
            detail,
        },
    })
}

/// Score of one case.
#[derive(Debug, Clone, Serialize)]
pub struct CaseScore {
    /// Case index.
    pub index: usize,
    /// The sealed label.
    pub label: Label,
    /// The tool's verdict.
    pub verdict: String,
    /// The two best candidates.
    pub top2: Vec<String>,
    /// Difficulty tier from the null re-fit's held-out reduced χ²: easy > 10, medium 3–10, hard < 3.
    pub tier: &'static str,
    /// Held-out reduced χ² after the null re-fit.
    pub null_chi2_red: f64,
    /// Fraction of the structural gap closed by the truth's candidate (if fitted).
    pub fraction_closed: Option<f64>,
    /// Top-1 correct.
    pub top1: bool,
    /// Truth among the two best (or `none` verdict on a null case).
    pub top2_hit: bool,
}

/// Scores a diagnosis against its label.
pub fn score_case(index: usize, label: Label, d: &Diagnosis) -> CaseScore {
    let top2: Vec<String> = d.candidates.iter().take(2).map(|c| c.id.clone()).collect();
    let tier = if label.effect == "none" {
        "null"
    } else if d.null.check.chi2_red > 10.0 {
        "easy"
    } else if d.null.check.chi2_red > 3.0 {
        "medium"
    } else {
        "hard"
    };
    let top1 = d.verdict == label.effect;
    let top2_hit = if label.effect == "none" {
        top1
    } else {
        top2.iter().any(|t| t == label.effect)
    };
    let fraction_closed = d
        .candidates
        .iter()
        .find(|c| c.id == label.effect)
        .map(|c| c.fraction_closed);
    CaseScore {
        index,
        verdict: d.verdict.clone(),
        top2,
        tier,
        null_chi2_red: d.null.check.chi2_red,
        fraction_closed,
        top1,
        top2_hit,
        label,
    }
}

/// Runs case `index` end to end.
pub fn run_case(index: usize, opts: &BenchOptions) -> Result<CaseScore> {
    let case = make_case(index, opts)?;
    let model = catalog::resolve("reference")?;
    let d = diagnose(&model, &case.train, &case.check)?;
    Ok(score_case(index, case.label, &d))
}

/// Aggregate figures of a benchmark, per difficulty tier.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Per tier: (tier, cases, top-1 accuracy, top-2 accuracy, median fraction closed over the
    /// correctly identified cases).
    pub tiers: Vec<(String, usize, f64, f64, Option<f64>)>,
    /// False-positive rate on no-effect cases (verdict other than `none`).
    pub false_positive_rate: Option<f64>,
    /// Confusion counts: (truth, verdict, count).
    pub confusion: Vec<(String, String, usize)>,
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

/// Summarises case scores.
pub fn summary(scores: &[CaseScore]) -> Summary {
    let mut tiers = Vec::new();
    for t in ["easy", "medium", "hard", "null"] {
        let c: Vec<&CaseScore> = scores.iter().filter(|s| s.tier == t).collect();
        if c.is_empty() {
            continue;
        }
        let n = c.len() as f64;
        let fgc = median(
            c.iter()
                .filter(|s| s.top1)
                .filter_map(|s| s.fraction_closed)
                .collect(),
        );
        tiers.push((
            t.to_string(),
            c.len(),
            c.iter().filter(|s| s.top1).count() as f64 / n,
            c.iter().filter(|s| s.top2_hit).count() as f64 / n,
            fgc,
        ));
    }
    let nulls: Vec<&CaseScore> = scores.iter().filter(|s| s.label.effect == "none").collect();
    let false_positive_rate = (!nulls.is_empty())
        .then(|| nulls.iter().filter(|s| s.verdict != "none").count() as f64 / nulls.len() as f64);
    let mut confusion: Vec<(String, String, usize)> = Vec::new();
    for s in scores {
        match confusion
            .iter_mut()
            .find(|c| c.0 == s.label.effect && c.1 == s.verdict)
        {
            Some(c) => c.2 += 1,
            None => confusion.push((s.label.effect.to_string(), s.verdict.clone(), 1)),
        }
    }
    confusion.sort();
    Summary {
        tiers,
        false_positive_rate,
        confusion,
    }
}

impl Summary {
    /// Readable summary.
    pub fn text(&self) -> String {
        let mut out =
            String::from("\ntier     cases  top-1  top-2  median fraction closed (correct)\n");
        for (t, n, a1, a2, f) in &self.tiers {
            out += &format!(
                "{t:<8} {n:>5}  {:>5.2}  {:>5.2}  {}\n",
                a1,
                a2,
                f.map_or("-".into(), |f| format!("{f:.2}"))
            );
        }
        if let Some(fp) = self.false_positive_rate {
            out += &format!("false-positive rate on no-effect cases: {fp:.2}\n");
        }
        out += "confusion (truth → verdict: count):\n";
        for (t, v, n) in &self.confusion {
            out += &format!("  {t:<21} → {v:<21} {n}\n");
        }
        out
    }
}
