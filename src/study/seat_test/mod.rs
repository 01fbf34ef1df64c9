//! The ISO 10326-1 laboratory seat test, done virtually (`wbv seat-test`), or applied to a lab's
//! own measured runs.
//!
//! Clauses as used here (ISO 10326-1:2016, read second-hand [S] through an open-source
//! implementation's clause-numbered docstrings and the ISVR toolbox; the standard itself was not
//! read):
//! - 10.2.1: a_wP and a_wS (frequency-weighted r.m.s. of platform and seat, Wk) are the arithmetic
//!   means of three consecutive runs whose values lie within ±5 % of their mean ([`runs`]); when
//!   three do not agree, more runs are made and the report says so.
//! - 10.2.2: `SEAT = a_wS / a_wP` (from the means).
//! - 10.2.3: the seat value corrected to the intended input, `a*_wS = SEAT · a*_wP`, with a*_wP the
//!   Wk-weighted r.m.s. of the class's target PSD (`√∫|W_k|²G df`, derived from the [S] class).
//! - 10.3: the damping test ([`damping`]).
//! - clause 11 sets no limits: the application standards do, and they are inputs here
//!   ([`Limits`]); without them there is no verdict.
//!
//! The test persons (light and heavy operator, [`Occupant`]) are made by scaling the model's
//! body: every body mass, and the stiffness and damping of every body link, times
//! `s = operator mass / 75 kg` ([`REFERENCE_OPERATOR_KG`]), which keeps the body's natural
//! frequencies and damping ratios and scales its apparent mass by `s` (the apparent mass
//! normalised by static mass is nearly mass-independent: Fairley & Griffin 1989).

pub mod contacts;
pub mod damping;
pub mod measured;
pub mod occupant;
pub mod outcome;
pub mod runs;

use crate::analysis::{Spectrum, Weighting};
use crate::error::{Error, Result};
use crate::excitation::ExcitationSpec;
use crate::excitation::classes::{self, InputClass};
use crate::integrator::Method;
use crate::model::Model;
use crate::scenario::Scenario;
use crate::simulate::Settings as RunSettings;
use crate::simulate::{AnalysisObserver, SpectraObserver};
use contacts::{ContactObserver, Contacts};
pub use occupant::{HEAVY_KG, LIGHT_KG, Occupant, REFERENCE_OPERATOR_KG, occupant_model};
pub use outcome::{
    DampingTest, Impacts, OccupantTest, Run, SeatTest, SeatTests, Spectra, SummaryRow, Verdict,
};
use serde::Serialize;
use std::collections::BTreeMap;

/// Duration of one simulated run, s **[U]**: ISO 10326-1's run duration was not read. 600 s makes
/// the three runs' averaged platform PSD (Δf 0.5 Hz, ~1800 Welch segments) scatter by 7 % of its
/// peak (3σ), inside the class's ±10 % tolerance, so the PSD check judges the generator rather
/// than chance; a_wP then scatters by ~1 % between runs.
pub const RUN_DURATION_S: f64 = 600.0;

/// Most runs made while looking for three consecutive ones that agree.
pub const MAX_RUNS: usize = 8;

/// Acceptance values from the application standard; either may be absent.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Limits {
    /// Largest SEAT allowed (every test person).
    pub seat: Option<f64>,
    /// Largest damping-test transmissibility allowed.
    pub damping: Option<f64>,
    /// Most end-stop contacts allowed per 10 min of run (each test person, over the three runs
    /// used: count × 600 s / their total duration). Without it, impacts make a `warning`.
    pub contacts_per_10_min: Option<f64>,
}

impl Limits {
    /// Refuses a limit that is not positive and finite.
    pub fn validate(&self) -> Result<()> {
        for (v, flag) in [
            (self.seat, "--seat-limit"),
            (self.damping, "--damping-limit"),
        ] {
            if let Some(x) = v
                && !(x.is_finite() && x > 0.0)
            {
                return Err(Error::parameter(flag, format!("{x}; expected a ratio > 0")));
            }
        }
        if let Some(x) = self.contacts_per_10_min
            && !(x.is_finite() && x >= 0.0)
        {
            return Err(Error::parameter(
                "--contact-limit",
                format!("{x}; expected a number of contacts per 10 min ≥ 0"),
            ));
        }
        Ok(())
    }
}

/// How the simulated test is run.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// The test persons (default both).
    pub occupants: Vec<Occupant>,
    /// Duration of each run, s ([`RUN_DURATION_S`]).
    pub run_duration_s: f64,
    /// Integration step, s.
    pub dt: f64,
    /// Seed of the first run; run i uses `seed + i`.
    pub seed: u64,
    /// The acceptance values.
    pub limits: Limits,
    /// Whether to run the damping test.
    pub damping: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            occupants: Occupant::BOTH.to_vec(),
            run_duration_s: RUN_DURATION_S,
            dt: 1e-3,
            seed: 1,
            limits: Limits::default(),
            damping: true,
        }
    }
}

/// The Wk-weighted r.m.s. of `class`'s target PSD, m/s²: a*_wP.
pub fn intended_a_wp(class: &InputClass) -> f64 {
    class.integral(|f| Weighting::Wk.magnitude(f)).sqrt()
}

/// The class called `name`, or an error listing them.
pub fn find_class(name: &str) -> Result<&'static InputClass> {
    classes::find(name).ok_or_else(|| {
        Error::parameter(
            "--class",
            format!(
                "`{name}` is not an input spectral class; expected one of {}",
                classes::CLASSES
                    .iter()
                    .map(|c| c.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        )
    })
}

/// The classes named in `names`, each a name or a comma-separated list of names, in the order
/// given; an error for an unknown, repeated or missing one.
pub fn find_classes(names: &[String]) -> Result<Vec<&'static InputClass>> {
    let mut out: Vec<&'static InputClass> = Vec::new();
    for name in names.iter().flat_map(|n| n.split(',')).map(str::trim) {
        if name.is_empty() {
            return Err(Error::parameter(
                "--class",
                "an empty class name; expected names separated by commas",
            ));
        }
        let c = find_class(name)?;
        if out.iter().any(|o| o.name == c.name) {
            return Err(Error::parameter("--class", format!("`{name}` given twice")));
        }
        out.push(c);
    }
    if out.is_empty() {
        return Err(Error::parameter("--class", "required: at least one class"));
    }
    Ok(out)
}

/// The chain of masses of `model`: the seat test scales and edits its masses and links.
pub(crate) fn chain_of(model: &Model) -> Result<&crate::model::chain::Chain> {
    model.chain().ok_or_else(|| {
        Error::parameter(
            "--model",
            format!(
                "`{}` is not a chain of masses; the seat test needs one",
                model.name
            ),
        )
    })
}

/// The results of one simulated or measured run: figures from the ISO 2631-1 report, the PSDs.
pub(crate) fn run_of(
    id: String,
    report: &crate::analysis::Report,
    base: &Spectrum,
    class: &InputClass,
    contacts: Option<Contacts>,
) -> Result<Run> {
    let ch = |name: &str| {
        report.channel(name).ok_or_else(|| {
            Error::parameter(
                "seat test",
                format!("run {id} has no channel {name}; expected a_base_z and a_seat_z"),
            )
        })
    };
    let (p, s) = (ch("a_base_z")?, ch("a_seat_z")?);
    let contacts = contacts.map(|mut c| {
        c.vdv_added_m_s1_75 = contacts::vdv_added(s.vdv, c.episode_dose);
        c
    });
    Ok(Run {
        seat: s.a_w / p.a_w,
        a_wp: p.a_w,
        a_ws: s.a_w,
        vdv_s: s.vdv,
        crest_factor_s: s.crest_factor,
        platform_psd: Some(class.check(&base.freq_hz, &base.density, base.df_hz, base.segments)),
        end_stop_contacts: contacts,
        id,
    })
}

/// Resolution of the spectra the seat transmissibility `√(G_S/G_P)` is drawn from, Hz: fine
/// enough to place a suspension resonance near 1.5 Hz to a few per cent (the PSD check's 0.5 Hz
/// would put it on one of three bins).
pub const TRANSMISSIBILITY_RESOLUTION_HZ: f64 = 0.125;

/// The transmissibility's resolution for runs of `duration_s`: [`TRANSMISSIBILITY_RESOLUTION_HZ`],
/// or coarser so that a run holds at least four Welch segments.
pub fn transmissibility_resolution(duration_s: f64) -> f64 {
    TRANSMISSIBILITY_RESOLUTION_HZ.max(4.0 / duration_s)
}

/// Band over which the seat transmissibility's largest value is the suspension's resonance, Hz.
pub const RESONANCE_BAND_HZ: [f64; 2] = [0.5, 20.0];

/// The spectra of one run: platform and seat at the check's resolution
/// ([`classes::CHECK_RESOLUTION_HZ`]) and at [`TRANSMISSIBILITY_RESOLUTION_HZ`].
#[derive(Debug, Clone)]
pub(crate) struct RunSpectra {
    pub base: Spectrum,
    pub seat: Spectrum,
    pub fine_base: Spectrum,
    pub fine_seat: Spectrum,
}

/// The mean over `sp` of the density `pick` takes from each (equal lengths: a plain mean of the
/// Welch averages is the Welch average over all their segments).
fn mean_density(sp: &[RunSpectra], pick: &dyn Fn(&RunSpectra) -> &Spectrum) -> Vec<f64> {
    let n = sp.len() as f64;
    let len = pick(&sp[0]).density.len();
    (0..len)
        .map(|k| sp.iter().map(|s| pick(s).density[k]).sum::<f64>() / n)
        .collect()
}

/// Share of the platform's peak density below which the transmissibility is not estimated: there
/// the seat's response comes from elsewhere (the stops' and the friction's harmonics of the
/// driven band), and `√(G_S/G_P)` would show them as a gain of the seat [choice].
pub const DRIVEN_OF_PEAK: f64 = 1e-2;

/// The seat transmissibility `√(G_S/G_P)` at each frequency of `f` (NaN where the platform has
/// less than [`DRIVEN_OF_PEAK`] of its peak density: the class does not drive the seat there).
pub fn transmissibility(platform: &[f64], seat: &[f64]) -> Vec<f64> {
    let peak = platform.iter().copied().fold(0.0, f64::max);
    platform
        .iter()
        .zip(seat)
        .map(|(&p, &s)| {
            if p > DRIVEN_OF_PEAK * peak {
                (s / p).sqrt()
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// `(frequency Hz, value)` of the largest finite `y` over `band`, refined by a parabola through it
/// and its neighbours: a resonance. `None` without a finite value there, or when the largest is
/// at an end of the finite values (a slope cut off by the band or by the class's driven band, not
/// a peak).
pub fn resonance(f: &[f64], y: &[f64], band: [f64; 2]) -> Option<(f64, f64)> {
    let k = (0..f.len())
        .filter(|&k| f[k] >= band[0] && f[k] <= band[1] && y[k].is_finite())
        .max_by(|&a, &b| y[a].total_cmp(&y[b]))?;
    if k == 0 || k + 1 >= f.len() || !y[k - 1].is_finite() || !y[k + 1].is_finite() {
        return None;
    }
    if f[k - 1] < band[0] || f[k + 1] > band[1] {
        return None;
    }
    let (a, b, c) = (y[k - 1], y[k], y[k + 1]);
    let den = a - 2.0 * b + c;
    if den >= 0.0 {
        return Some((f[k], b));
    }
    let p = 0.5 * (a - c) / den;
    Some((f[k] + p * (f[k + 1] - f[k]), b - 0.25 * (a - c) * p))
}

/// One test person's test from its runs and their spectra: the ±5 % rule, the means, SEAT, the
/// correction, the averaged PSD check, the impacts and the seat's resonance. Notes go to `notes`.
pub(crate) fn occupant_test(
    occupant: Option<Occupant>,
    runs: Vec<Run>,
    spectra: &[RunSpectra],
    class: &InputClass,
    run_duration_s: Option<f64>,
    notes: &mut Vec<String>,
) -> OccupantTest {
    let a_wp: Vec<f64> = runs.iter().map(|r| r.a_wp).collect();
    let (first, agree) = match runs::agreeing_window(&a_wp) {
        Some(i) => (i, true),
        None => (a_wp.len().saturating_sub(runs::RUNS), false),
    };
    let last = (first + runs::RUNS).min(runs.len());
    let who = occupant.map_or("the measured runs".to_string(), |o| {
        format!("the {} operator", o.name())
    });
    if !agree {
        notes.push(format!(
            "{who}: no {} consecutive runs agree within ±{:.0} % in a_wP (ISO 10326-1 10.2.1); \
             the last ones are used and the result is not a valid test",
            runs::RUNS,
            100.0 * runs::AGREEMENT
        ));
    } else if first > 0 {
        notes.push(format!(
            "{who}: runs {}–{} agree within ±{:.0} % in a_wP after {} more run(s) than three",
            first + 1,
            last,
            100.0 * runs::AGREEMENT,
            first
        ));
    }
    let used = &runs[first..last];
    let mean_wp = runs::mean(&used.iter().map(|r| r.a_wp).collect::<Vec<_>>());
    let mean_ws = runs::mean(&used.iter().map(|r| r.a_ws).collect::<Vec<_>>());
    let seat = mean_ws / mean_wp;
    let sp = &spectra[first..last];
    let spectra = Spectra {
        freq_hz: sp[0].base.freq_hz.clone(),
        platform: mean_density(sp, &|s| &s.base),
        seat: mean_density(sp, &|s| &s.seat),
        df_hz: sp[0].base.df_hz,
        segments: sp.iter().map(|s| s.base.segments).sum(),
        fine_freq_hz: sp[0].fine_base.freq_hz.clone(),
        transmissibility: transmissibility(
            &mean_density(sp, &|s| &s.fine_base),
            &mean_density(sp, &|s| &s.fine_seat),
        ),
    };
    let peak = resonance(
        &spectra.fine_freq_hz,
        &spectra.transmissibility,
        RESONANCE_BAND_HZ,
    );
    let check = class.check(
        &spectra.freq_hz,
        &spectra.platform,
        spectra.df_hz,
        spectra.segments,
    );
    if !check.within_tolerance {
        notes.push(format!("{who}: {}", check.sentence()));
    }
    let contacts = used
        .iter()
        .map(|r| r.end_stop_contacts.as_ref().map(|c| c.count))
        .sum::<Option<usize>>();
    let crest = used.iter().map(|r| r.crest_factor_s).fold(0.0, f64::max);
    let impacts = match (contacts, run_duration_s) {
        (Some(count), Some(d)) => {
            let each: Vec<&Contacts> = used
                .iter()
                .filter_map(|r| r.end_stop_contacts.as_ref())
                .collect();
            let over_s = d * used.len() as f64;
            let episodes: Vec<f64> = each
                .iter()
                .filter(|c| c.count > 0)
                .map(|c| c.mean_peak_seat_acceleration_m_s2)
                .collect();
            Some(Impacts {
                count,
                per_10_min: count as f64 * 600.0 / over_s,
                over_s,
                peak_seat_acceleration_m_s2: each
                    .iter()
                    .map(|c| c.peak_seat_acceleration_m_s2)
                    .fold(0.0, f64::max),
                mean_peak_seat_acceleration_m_s2: if episodes.is_empty() {
                    0.0
                } else {
                    runs::mean(&episodes)
                },
                vdv_s: used.iter().map(|r| r.vdv_s).fold(0.0, f64::max),
                vdv_added_m_s1_75: each.iter().map(|c| c.vdv_added_m_s1_75).fold(0.0, f64::max),
                crest_factor_s: crest,
            })
        }
        _ => None,
    };
    if crest > 9.0 {
        notes.push(format!(
            "{who}: seat crest factor up to {crest:.1}, above 9: ISO 2631-1 6.2.1 asks for VDV and \
             MTVV beside a_w{}",
            match contacts {
                Some(n) if n > 0 => format!(" ({n} end-stop impacts)"),
                _ => String::new(),
            }
        ));
    }
    OccupantTest {
        occupant,
        body_mass_kg: None,
        supported_mass_kg: None,
        scale: None,
        first_used: first,
        runs_agree: agree,
        a_wp: mean_wp,
        a_ws: mean_ws,
        seat,
        a_ws_corrected: seat * intended_a_wp(class),
        psd_within_tolerance: Some(check.within_tolerance),
        platform_psd: Some(check),
        end_stop_contacts: contacts,
        impacts,
        seat_resonance_hz: peak.map(|p| p.0),
        seat_transmissibility_peak: peak.map(|p| p.1),
        verdict: None,
        spectra,
        runs,
    }
}

/// One simulated run of `model` under `class` with `seed`: its figures, spectra and contacts.
fn simulate_run(
    model: &Model,
    class: &InputClass,
    settings: &Settings,
    seed: u64,
) -> Result<(Run, RunSpectra)> {
    let scenario = Scenario {
        model: model.clone(),
        excitation: ExcitationSpec::input_class(class)?,
        settings: RunSettings {
            dt: settings.dt,
            duration_s: settings.run_duration_s,
            method: Method::AVERAGE_ACCELERATION,
        },
        seed,
    };
    let mut analysis = AnalysisObserver::new(
        &format!("seat test {} s{seed}", model.name),
        Default::default(),
    );
    let channels = ["a_base_z", "a_seat_z"];
    let mut spectra = SpectraObserver::new(&channels, classes::CHECK_RESOLUTION_HZ);
    let mut fine = SpectraObserver::new(
        &channels,
        transmissibility_resolution(settings.run_duration_s),
    );
    let mut contacts = ContactObserver::new(model.system());
    let has_stops = contacts.has_stops();
    scenario.simulate(
        &mut [&mut analysis, &mut spectra, &mut fine, &mut contacts],
        None,
    )?;
    let report = analysis.into_report()?;
    let pair = |o: SpectraObserver| -> Result<(Spectrum, Spectrum)> {
        let mut sp = o.finish()?.into_iter().map(|(_, s)| s);
        match (sp.next(), sp.next()) {
            (Some(b), Some(s)) => Ok((b, s)),
            _ => Err(Error::parameter(
                "--model",
                format!("`{}` has no a_base_z and a_seat_z channels", model.name),
            )),
        }
    };
    let (base, seat) = pair(spectra)?;
    let (fine_base, fine_seat) = pair(fine)?;
    let run = run_of(
        format!("seed {seed}"),
        &report,
        &base,
        class,
        has_stops.then(|| contacts.into_contacts()),
    )?;
    Ok((
        run,
        RunSpectra {
            base,
            seat,
            fine_base,
            fine_seat,
        },
    ))
}

fn units() -> BTreeMap<String, String> {
    [
        ("a_wp", "m/s^2"),
        ("a_ws", "m/s^2"),
        ("a_ws_corrected", "m/s^2"),
        ("intended_a_wp", "m/s^2"),
        ("seat", "1"),
        ("seat_resonance_hz", "Hz"),
        ("seat_transmissibility_peak", "1"),
        ("runs.vdv_s", "m/s^1.75"),
        ("impacts.peak_seat_acceleration_m_s2", "m/s^2"),
        ("impacts.vdv_added_m_s1_75", "m/s^1.75"),
        ("impacts.per_10_min", "1/(600 s)"),
        ("impacts.over_s", "s"),
        ("damping.transmissibility", "1"),
        ("damping.f_r_hz", "Hz"),
        ("damping.platform_amplitude_m", "m"),
        ("platform_psd.peak_psd", "(m/s^2)^2/Hz"),
        ("run_duration_s", "s"),
    ]
    .into_iter()
    .map(|(k, u)| (k.to_string(), u.to_string()))
    .collect()
}

/// What the test on `class` rests on that is not verified.
fn unverified(class: &InputClass, simulated: bool) -> Vec<String> {
    let mut v = vec![
        format!(
            "class {}: corners, orders and G_s from the ISVR HVLab toolbox, not the standard's table{}",
            class.code,
            if class.code == "EM7" {
                "; its toolbox band r.m.s. (2.36 m/s²) disagrees with its PSD by 4.6 %"
            } else {
                ""
            }
        ),
        "PSD tolerance ±10 % of the peak: the toolbox's convention, not ISO 10326-1's text".into(),
        format!(
            "class {} ({}, {}): {}",
            class.code,
            class.machine,
            class.defining,
            class.scope.sentence(class.standard)
        ),
        "ISO 10326-1 clauses 10.2.1–10.3 read second-hand".into(),
    ];
    if simulated {
        v.push(format!(
            "test persons {LIGHT_KG} kg and {HEAVY_KG} kg (52–55 and 98–103 kg), and a built-in body taken as a {REFERENCE_OPERATOR_KG} kg operator"
        ));
        v.push(format!(
            "default run duration {RUN_DURATION_S} s (the standard's duration not read)"
        ));
        v.push("damping-test amplitude (40 % of the stroke peak-to-peak)".into());
        v.push(format!(
            "an impact's episode: contact to {} s after leaving the stop (engineering choice)",
            contacts::IMPACT_TAIL_S
        ));
    }
    v
}

/// The verdict of one test person and why: SEAT, end-stop contacts and the damping test against
/// their limits; impacts without a contact limit make a warning.
fn judge(
    o: &OccupantTest,
    limits: &Limits,
    damping: Option<&DampingTest>,
    reasons: &mut Vec<String>,
) -> Option<Verdict> {
    let who = o
        .occupant
        .map_or(String::new(), |p| format!(" ({} operator)", p.name()));
    let mut v: Option<Verdict> = None;
    let mark = |ok: bool, v: &mut Option<Verdict>| {
        *v = (*v).max(Some(if ok { Verdict::Pass } else { Verdict::Fail }));
    };
    if let Some(lim) = limits.seat {
        let ok = o.seat <= lim;
        mark(ok, &mut v);
        reasons.push(format!(
            "SEAT {:.3} {} the limit {lim}{who}",
            o.seat,
            if ok { "within" } else { "ABOVE" },
        ));
    }
    if let (Some(lim), Some(d)) = (limits.damping, damping) {
        mark(d.transmissibility <= lim, &mut v);
    }
    if let Some(i) = &o.impacts {
        match limits.contacts_per_10_min {
            Some(lim) => {
                let ok = i.per_10_min <= lim;
                mark(ok, &mut v);
                reasons.push(format!(
                    "{} end-stop contacts in {:.0} min, {:.1} per 10 min, {} the limit {lim}{who}",
                    i.count,
                    i.over_s / 60.0,
                    i.per_10_min,
                    if ok { "within" } else { "ABOVE" },
                ));
            }
            None if i.count > 0 => {
                v = v.max(Some(Verdict::Warning));
                reasons.push(format!(
                    "{} end-stop impacts in {:.0} min{who}, not judged: no contact limit given \
                     (--contact-limit)",
                    i.count,
                    i.over_s / 60.0
                ));
            }
            None => {}
        }
    }
    if !o.runs_agree && v.is_some() {
        reasons.push(format!(
            "no three consecutive runs agreed{who}: not a valid ISO 10326-1 test"
        ));
        v = Some(Verdict::Fail);
    }
    v
}

/// The class's verdict line: `WARNING — PASS on SEAT; 47 end-stop impacts in 30 min (heavy),
/// crest factor 14.3`.
fn verdict_line(t: &SeatTest, damping: Option<&DampingTest>) -> String {
    let Some(verdict) = t.verdict else {
        return "no verdict: no limit given (ISO 10326-1 sets none; the application standard \
                does) and no end-stop impact"
            .into();
    };
    let mut parts = Vec::new();
    let label = |o: &OccupantTest| o.label();
    if let Some(lim) = t.limits.seat {
        let over: Vec<String> = t
            .occupants
            .iter()
            .filter(|o| o.seat > lim)
            .map(|o| format!("{} {:.3}", label(o), o.seat))
            .collect();
        parts.push(if over.is_empty() {
            format!("PASS on SEAT (≤ {lim})")
        } else {
            format!("FAIL on SEAT ({} > {lim})", over.join(", "))
        });
    }
    if let (Some(lim), Some(d)) = (t.limits.damping, damping) {
        parts.push(format!(
            "{} on damping (T {:.2} {} {lim})",
            if d.transmissibility <= lim {
                "PASS"
            } else {
                "FAIL"
            },
            d.transmissibility,
            if d.transmissibility <= lim {
                "≤"
            } else {
                ">"
            }
        ));
    }
    let struck: Vec<&OccupantTest> = t
        .occupants
        .iter()
        .filter(|o| o.impacts.as_ref().is_some_and(|i| i.count > 0))
        .collect();
    if let Some(lim) = t.limits.contacts_per_10_min {
        let over: Vec<String> = t
            .occupants
            .iter()
            .filter_map(|o| o.impacts.as_ref().map(|i| (o, i)))
            .filter(|(_, i)| i.per_10_min > lim)
            .map(|(o, i)| format!("{} {:.1}", label(o), i.per_10_min))
            .collect();
        parts.push(if over.is_empty() {
            format!("PASS on end stops (≤ {lim} per 10 min)")
        } else {
            format!("FAIL on end stops ({} per 10 min > {lim})", over.join(", "))
        });
    }
    if !struck.is_empty() {
        let counts: Vec<String> = struck
            .iter()
            .filter_map(|o| o.impacts.as_ref().map(|i| (o, i)))
            .map(|(o, i)| {
                format!(
                    "{} end-stop impact{} in {:.0} min ({}), crest factor {:.1}",
                    i.count,
                    if i.count == 1 { "" } else { "s" },
                    i.over_s / 60.0,
                    label(o),
                    i.crest_factor_s
                )
            })
            .collect();
        parts.push(counts.join("; "));
    }
    if t.occupants.iter().any(|o| !o.runs_agree) {
        parts.push("no three consecutive runs agreed: not a valid test".into());
    }
    match verdict {
        // Every part says PASS already.
        Verdict::Pass => parts.join("; "),
        _ => format!("{} — {}", verdict.word(), parts.join("; ")),
    }
}

/// Judges `t` against its limits (and the seat's damping test), and fills the governing test
/// person's keys.
pub(crate) fn finish(mut t: SeatTest, damping: Option<&DampingTest>) -> SeatTest {
    if let Some(g) = t
        .occupants
        .iter()
        .max_by(|a, b| a.seat.total_cmp(&b.seat))
        .cloned()
    {
        t.governing_occupant = g.occupant;
        t.runs = g.runs.clone();
        t.a_wp = g.a_wp;
        t.a_ws = g.a_ws;
        t.seat = g.seat;
        t.a_ws_corrected = g.a_ws_corrected;
    }
    t.psd_within_tolerance = t
        .occupants
        .iter()
        .map(|o| o.psd_within_tolerance)
        .try_fold(true, |a, b| b.map(|b| a && b));
    t.end_stop_contacts = t.occupants.iter().map(|o| o.end_stop_contacts).sum();
    let limits = t.limits;
    let mut reasons = Vec::new();
    for o in &mut t.occupants {
        o.verdict = judge(o, &limits, damping, &mut reasons);
    }
    if let (Some(lim), Some(d)) = (limits.damping, damping) {
        reasons.push(format!(
            "damping-test transmissibility {:.3} at {:.2} Hz {} the limit {lim}",
            d.transmissibility,
            d.f_r_hz,
            if d.transmissibility <= lim {
                "within"
            } else {
                "ABOVE"
            }
        ));
    }
    t.verdict_reasons = reasons;
    t.verdict = t.occupants.iter().map(|o| o.verdict).max().flatten();
    t.verdict_line = verdict_line(&t, damping);
    t
}

/// An empty test of `class`.
pub(crate) fn document(class: &InputClass, source: &'static str, limits: Limits) -> SeatTest {
    SeatTest {
        source,
        model: None,
        class: class.name.to_string(),
        standard: class.standard.name(),
        class_code: class.code,
        machine: class.machine,
        defining: class.defining,
        scope: class.scope,
        intended_a_wp: intended_a_wp(class),
        run_duration_s: None,
        occupants: Vec::new(),
        governing_occupant: None,
        runs: Vec::new(),
        a_wp: f64::NAN,
        a_ws: f64::NAN,
        seat: f64::NAN,
        a_ws_corrected: f64::NAN,
        psd_within_tolerance: None,
        end_stop_contacts: None,
        limits,
        verdict: None,
        verdict_line: String::new(),
        verdict_reasons: Vec::new(),
        notes: Vec::new(),
        unverified: unverified(class, source == "simulated"),
    }
}

/// The whole test's document from the test of each class: the summary table, the worst verdict
/// and each class's verdict line.
pub(crate) fn assemble(
    classes: Vec<SeatTest>,
    damping: Option<DampingTest>,
    damping_skipped: Option<String>,
    limits: Limits,
    warnings: Vec<String>,
) -> SeatTests {
    let damping_t = damping.as_ref().map(|d| d.transmissibility);
    let summary = classes
        .iter()
        .flat_map(|t| {
            let scope = classes::find(&t.class).map_or(String::new(), |c| c.scope_label());
            t.occupants.iter().map(move |o| SummaryRow {
                class: t.class.clone(),
                class_code: format!("{} {}", t.standard, t.class_code),
                machine: scope.clone(),
                occupant: o.label(),
                seat: o.seat,
                a_ws_corrected: o.a_ws_corrected,
                end_stop_contacts: o.end_stop_contacts,
                contacts_per_10_min: o.impacts.as_ref().map(|i| i.per_10_min),
                damping_transmissibility: damping_t,
                verdict: o.verdict,
            })
        })
        .collect();
    SeatTests {
        source: classes.first().map_or("simulated", |t| t.source),
        model: classes.first().and_then(|t| t.model.clone()),
        run_duration_s: classes.first().and_then(|t| t.run_duration_s),
        summary,
        verdict: classes.iter().map(|t| t.verdict).max().flatten(),
        verdict_lines: classes
            .iter()
            .map(|t| {
                format!(
                    "{} ({} {}): {}",
                    t.class, t.standard, t.class_code, t.verdict_line
                )
            })
            .collect(),
        damping,
        damping_skipped,
        limits,
        classes,
        warnings,
        units: units(),
    }
}

/// Checks the settings before any run.
fn validate(settings: &Settings) -> Result<()> {
    settings.limits.validate()?;
    for (v, flag) in [
        (settings.run_duration_s, "--duration"),
        (settings.dt, "--dt"),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::parameter(flag, format!("{v} s; expected > 0")));
        }
    }
    if settings.run_duration_s < 4.0 / classes::CHECK_RESOLUTION_HZ {
        return Err(Error::parameter(
            "--duration",
            format!(
                "{} s; a run needs at least {} s for its PSD check",
                settings.run_duration_s,
                4.0 / classes::CHECK_RESOLUTION_HZ
            ),
        ));
    }
    if settings.occupants.is_empty() {
        return Err(Error::parameter("--occupant", "no test person to test"));
    }
    Ok(())
}

/// One test person's runs on one class: runs with seeds `seed`, `seed + 1`, … until three
/// consecutive ones agree (at most [`MAX_RUNS`]), and their test.
fn occupant_runs(
    model: &Model,
    class: &InputClass,
    o: Occupant,
    settings: &Settings,
) -> Result<(OccupantTest, Vec<String>)> {
    let (m, scale, body) = occupant_model(model, o)?;
    let mut runs = Vec::new();
    let mut spectra = Vec::new();
    for i in 0..MAX_RUNS {
        crate::cancel::check("the seat test")?;
        let (run, sp) = simulate_run(&m, class, settings, settings.seed + i as u64)?;
        runs.push(run);
        spectra.push(sp);
        let a: Vec<f64> = runs.iter().map(|r| r.a_wp).collect();
        if runs.len() >= runs::RUNS && runs::agreeing_window(&a).is_some() {
            break;
        }
    }
    let mut notes = Vec::new();
    let mut ot = occupant_test(
        Some(o),
        runs,
        &spectra,
        class,
        Some(settings.run_duration_s),
        &mut notes,
    );
    ot.body_mass_kg = Some(o.mass_kg());
    ot.supported_mass_kg = Some(body);
    ot.scale = Some(scale);
    Ok((ot, notes))
}

/// The ISO 10326-1 test of `model` (an occupant on a seat) on each of `classes`: the damping test
/// once (it does not depend on the class), then every class and test person, in parallel, each
/// with the same seeds (so a class's result does not depend on the others given).
pub fn simulate(model: &Model, classes: &[&InputClass], settings: &Settings) -> Result<SeatTests> {
    use rayon::prelude::*;
    validate(settings)?;
    if classes.is_empty() {
        return Err(Error::parameter("--class", "required: at least one class"));
    }
    // The damping test first: a model it cannot take is refused before the long runs.
    let (damping, damping_skipped) = if settings.damping {
        match damping::run(model, settings.dt) {
            Ok(d) => (Some(d), None),
            Err(e) if settings.limits.damping.is_some() => return Err(e),
            Err(e @ Error::Interrupted { .. }) => return Err(e),
            Err(e) => (None, Some(e.to_string())),
        }
    } else {
        if settings.limits.damping.is_some() {
            return Err(Error::parameter(
                "--damping-limit",
                "given, but the damping test is switched off",
            ));
        }
        (None, Some("not asked for".to_string()))
    };
    let jobs: Vec<(&InputClass, Occupant)> = classes
        .iter()
        .flat_map(|&c| settings.occupants.iter().map(move |&o| (c, o)))
        .collect();
    let mut done = jobs
        .par_iter()
        .map(|&(c, o)| occupant_runs(model, c, o, settings))
        .collect::<Result<Vec<_>>>()?
        .into_iter();
    let mut tests = Vec::new();
    for &class in classes {
        let mut t = document(class, "simulated", settings.limits);
        t.model = Some(model.name.clone());
        t.run_duration_s = Some(settings.run_duration_s);
        for _ in &settings.occupants {
            if let Some((ot, notes)) = done.next() {
                t.notes.extend(notes);
                t.occupants.push(ot);
            }
        }
        tests.push(finish(t, damping.as_ref()));
    }
    Ok(assemble(
        tests,
        damping,
        damping_skipped,
        settings.limits,
        Vec::new(),
    ))
}
