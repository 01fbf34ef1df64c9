//! The per-run ISO 2631-1 report: figures of every acceleration channel, the comfort total value
//! and class, SEAT and health. Serializable so that a recorder can store it and a replay can
//! reproduce it byte for byte (all computations are deterministic).

use super::comfort::{self, Comfort};
use super::figures::{self as fig, Averaging};
use super::filter::WeightingFilter;
use super::health::{self, Health};
use super::octave::{self, Band};
use super::seat;
use super::spectrum::{Segment, Welch, WelchOptions};
use super::weighting::Weighting;
use crate::error::{Error, Result};
use crate::signals::Signals;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Analysis settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Options {
    /// Daily exposure in hours for the health figures (None: no health section).
    pub exposure_hours: Option<f64>,
    /// Running r.m.s. integration time τ in s (ISO 2631-1 6.3.1 recommends 1 s).
    pub tau_s: f64,
    /// Spectral estimation of the one-third-octave bands.
    pub welch: WelchOptions,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            exposure_hours: None,
            tau_s: 1.0,
            welch: WelchOptions::default(),
        }
    }
}

/// Figures of one acceleration channel `a_<place>_<axis>` (m/s² in).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelReport {
    pub name: String,
    pub place: String,
    pub axis: String,
    /// Weighting applied (ISO 2631-1 Tables 1–2: z → Wk, x/y → Wd, backrest x → Wc).
    pub weighting: Weighting,
    /// Comfort multiplying factor k (ISO 2631-1 8.2.2).
    pub k: f64,
    /// Unweighted r.m.s., m/s².
    pub rms: f64,
    /// Weighted r.m.s. a_w, m/s² (eq. 1).
    pub a_w: f64,
    /// Vibration dose value, m/s^1.75 (eq. 5).
    pub vdv: f64,
    /// MTVV with linear 1 s running r.m.s., m/s² (eqs. 2, 4).
    pub mtvv: f64,
    /// MTVV with exponential running r.m.s., m/s² (eq. 3).
    pub mtvv_exponential: f64,
    /// Largest |a_w|, m/s².
    pub peak: f64,
    /// |peak| / a_w of the weighted signal (6.2.1).
    pub crest_factor: f64,
    /// Motion sickness dose value with Wf, m/s^1.5 (clause 9), z axes only.
    pub msdv: Option<f64>,
    /// Unweighted one-third-octave band r.m.s. 0.5–80 Hz, m/s².
    pub bands: Vec<Band>,
}

/// The report of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    pub source: String,
    pub sample_rate_hz: f64,
    pub duration_s: f64,
    pub channels: Vec<ChannelReport>,
    /// Contact surface used for comfort ("seat" when present).
    pub comfort_place: String,
    /// Vibration total value a_v = (Σ k² a_w²)^½ over the comfort surface (and backrest), m/s² (eq. 10).
    pub total_value: f64,
    pub comfort: Comfort,
    /// All Annex C ranges containing a_v.
    pub comfort_statement: String,
    /// SEAT % from a_seat_z over a_base_z with Wk, when both exist.
    pub seat_percent: Option<f64>,
    pub health: Option<Health>,
    /// Advice triggered by the figures (crest factor > 9, 6.3.3 ratios).
    pub notes: Vec<String>,
    /// Unit of every numeric key.
    pub units: BTreeMap<String, String>,
}

fn units() -> BTreeMap<String, String> {
    [
        ("sample_rate_hz", "Hz"),
        ("duration_s", "s"),
        ("rms", "m/s^2"),
        ("a_w", "m/s^2"),
        ("vdv", "m/s^1.75"),
        ("mtvv", "m/s^2"),
        ("mtvv_exponential", "m/s^2"),
        ("peak", "m/s^2"),
        ("crest_factor", "1"),
        ("msdv", "m/s^1.5"),
        ("bands.rms", "m/s^2"),
        ("total_value", "m/s^2"),
        ("seat_percent", "%"),
        ("health.a8", "m/s^2"),
        ("health.a_w_max", "m/s^2"),
        ("health.vdv_exposure", "m/s^1.75"),
        ("health.exposure_hours", "h"),
    ]
    .into_iter()
    .map(|(k, u)| (k.to_string(), u.to_string()))
    .collect()
}

/// Splits `a_<place>_<axis>` into (place, axis) for translational axes x, y, z.
fn parse_name(name: &str) -> Option<(&str, &str)> {
    let rest = name.strip_prefix("a_")?;
    let (place, axis) = rest.rsplit_once('_')?;
    (!place.is_empty() && matches!(axis, "x" | "y" | "z")).then_some((place, axis))
}

/// Weighting and comfort k of a channel (ISO 2631-1 Tables 1–2, 8.2.2).
fn weighting_for(place: &str, axis: &str) -> (Weighting, f64) {
    match (place, axis) {
        ("back", "x") => (Weighting::Wc, 0.8),
        ("back", "y") => (Weighting::Wd, 0.5),
        ("back", "z") => (Weighting::Wd, 0.4),
        ("feet", "z") => (Weighting::Wk, 0.4),
        ("feet", _) => (Weighting::Wk, 0.25),
        (_, "z") => (Weighting::Wk, 1.0),
        _ => (Weighting::Wd, 1.0),
    }
}

fn check_samples(signals: &Signals, name: &str, x: &[f64]) -> Result<()> {
    match x.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(Error::data(
            &signals.source,
            None,
            format!(
                "channel `{name}` sample {i} is {}; expected a finite acceleration",
                x[i]
            ),
        )),
        None => Ok(()),
    }
}

impl ChannelReport {
    fn compute(name: &str, x: &[f64], fs: f64, opts: &Options) -> Result<Self> {
        let (place, axis) = parse_name(name).expect("caller filtered names");
        let (weighting, k) = weighting_for(place, axis);
        let aw = WeightingFilter::new(weighting, fs)?.apply(x);
        let a_w = fig::rms(&aw);
        let msdv = if axis == "z" {
            Some(fig::msdv(
                &WeightingFilter::new(Weighting::Wf, fs)?.apply(x),
                fs,
            ))
        } else {
            None
        };
        let mut welch_opts = opts.welch;
        let mut welch = Welch::new(fs, &welch_opts)?;
        if welch.segment_len() > x.len() {
            welch_opts.segment = Segment::Samples(x.len());
            welch = Welch::new(fs, &welch_opts)?;
        }
        let bands = octave::third_octave_bands(&welch.psd(x)?, -3, 19);
        Ok(ChannelReport {
            name: name.to_string(),
            place: place.to_string(),
            axis: axis.to_string(),
            weighting,
            k,
            rms: fig::rms(x),
            a_w,
            vdv: fig::vdv(&aw, fs),
            mtvv: fig::mtvv(&aw, fs, opts.tau_s, Averaging::Linear),
            mtvv_exponential: fig::mtvv(&aw, fs, opts.tau_s, Averaging::Exponential),
            peak: fig::peak(&aw),
            crest_factor: fig::crest_factor(&aw),
            msdv,
            bands,
        })
    }

    fn notes(&self, duration_s: f64) -> Vec<String> {
        let mut notes = Vec::new();
        if self.crest_factor > fig::CREST_FACTOR_LIMIT {
            notes.push(format!(
                "{}: crest factor {:.1} > 9: the basic r.m.s. method may underestimate shocks; \
                 use MTVV and VDV (ISO 2631-1 6.2.1, 6.3)",
                self.name, self.crest_factor
            ));
        }
        if self.a_w > 0.0 {
            let mr = self.mtvv / self.a_w;
            let vr = self.vdv / (self.a_w * duration_s.powf(0.25));
            if mr > fig::MTVV_RATIO_LIMIT || vr > fig::VDV_RATIO_LIMIT {
                notes.push(format!(
                    "{}: MTVV/a_w = {mr:.2} (limit 1.5), VDV/(a_w T^1/4) = {vr:.2} (limit 1.75): \
                     report MTVV and VDV with a_w (ISO 2631-1 6.3.3)",
                    self.name
                ));
            }
        }
        notes
    }
}

impl Report {
    /// Analyses every `a_<place>_<x|y|z>` channel of `signals`.
    pub fn from_signals(signals: &Signals, opts: &Options) -> Result<Report> {
        let fs = signals.sample_rate_hz;
        if signals.is_empty() {
            return Err(Error::data(&signals.source, None, "the run has no samples"));
        }
        if !(opts.tau_s.is_finite() && opts.tau_s > 0.0) {
            return Err(Error::parameter(
                "tau",
                format!("{} s; expected > 0", opts.tau_s),
            ));
        }
        if let Some(h) = opts.exposure_hours.filter(|h| !(h.is_finite() && *h > 0.0)) {
            return Err(Error::parameter(
                "exposure-hours",
                format!("{h}; expected > 0"),
            ));
        }
        let mut channels = Vec::new();
        for (name, x) in signals.names.iter().zip(&signals.data) {
            if parse_name(name).is_some() {
                check_samples(signals, name, x)?;
                channels.push(ChannelReport::compute(name, x, fs, opts)?);
            }
        }
        if channels.is_empty() {
            return Err(Error::data(
                &signals.source,
                None,
                format!(
                    "no acceleration channel `a_<place>_<x|y|z>` (present: {})",
                    signals.names.join(", ")
                ),
            ));
        }
        let duration_s = signals.duration_s();
        let comfort_place = if channels.iter().any(|c| c.place == "seat") {
            "seat".to_string()
        } else {
            channels[0].place.clone()
        };
        let in_total = |c: &&ChannelReport| {
            c.place == comfort_place
                || (comfort_place == "seat" && (c.place == "back" || c.place == "feet"))
        };
        let total_value = channels
            .iter()
            .filter(in_total)
            .map(|c| (c.k * c.a_w).powi(2))
            .sum::<f64>()
            .sqrt();
        let find = |n: &str| channels.iter().find(|c| c.name == n);
        let seat_percent = match (find("a_seat_z"), find("a_base_z")) {
            (Some(s), Some(b)) => seat::seat_percent(s.a_w, b.a_w),
            _ => None,
        };
        let health = opts.exposure_hours.and_then(|h| {
            let axes: Vec<_> = channels
                .iter()
                .filter(|c| c.place == "seat")
                .map(|c| (c.axis.clone(), c.a_w, c.vdv))
                .collect();
            health::assess(&axes, duration_s, h)
        });
        let notes = channels.iter().flat_map(|c| c.notes(duration_s)).collect();
        Ok(Report {
            source: signals.source.clone(),
            sample_rate_hz: fs,
            duration_s,
            comfort_place,
            total_value,
            comfort: Comfort::from_total_value(total_value),
            comfort_statement: comfort::overlap_statement(total_value),
            seat_percent,
            health,
            notes,
            channels,
            units: units(),
        })
    }

    /// Comfort class of the total value (ISO 2631-1 Annex C; rule in [`comfort`]).
    pub fn comfort(&self) -> Comfort {
        self.comfort
    }

    /// The figures of channel `name`, if it was analysed.
    pub fn channel(&self, name: &str) -> Option<&ChannelReport> {
        self.channels.iter().find(|c| c.name == name)
    }

    /// SEAT % (seat z over base z, Wk), if both channels exist.
    pub fn seat_percent(&self) -> Option<f64> {
        self.seat_percent
    }

    /// For users' tests: panics with the a_v value and the Annex C wording when the comfort class
    /// is worse than `worst_allowed`.
    pub fn assert_comfort_at_most(&self, worst_allowed: Comfort) {
        assert!(
            self.comfort <= worst_allowed,
            "{}: comfort `{}` is worse than the allowed `{}` ({})",
            self.source,
            self.comfort,
            worst_allowed,
            self.comfort_statement
        );
    }
}
