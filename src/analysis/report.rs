//! The per-run ISO 2631-1 report: figures of every acceleration channel, the comfort total value
//! and class, SEAT and health. Serializable so that a recorder can store it and a replay can
//! reproduce it byte for byte (all computations are deterministic).

use super::comfort::{self, Comfort};
use super::figures as fig;
use super::health::{self, Health};
use super::octave::{self, Band};
use super::seat;
use super::spectrum::WelchOptions;
use super::spine::{Peaks, ShockSettings, Shocks};
use super::weighting::Weighting;
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
    /// Channels whose unit neither the file nor the user (`--units`) declared, read as m/s²
    /// (`crate::io::input::Input::undeclared`): every figure of theirs assumes m/s²
    /// ([`Report::unit_assumed`]) and their samples are checked for another unit
    /// ([`ChannelReport::unit_doubt`]). Empty (the default) for signals in SI units by
    /// construction: a simulation, a wbv run.
    pub units_assumed: Vec<String>,
    /// ISO 2631-5 shocks: asked for even without a crest factor above 9, and the exposure history
    /// of the stress variable R.
    #[serde(default)]
    pub shocks: ShockSettings,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            exposure_hours: None,
            tau_s: 1.0,
            welch: WelchOptions::default(),
            units_assumed: Vec::new(),
            shocks: ShockSettings::default(),
        }
    }
}

/// Figures of one acceleration channel `a_<place>_<axis>` (m/s² in).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelReport {
    /// The channel's name, `a_<place>_<axis>`.
    pub name: String,
    /// The measuring place, e.g. `seat`, `base`, `backrest`.
    pub place: String,
    /// The axis, `x`, `y` or `z` (ISO 2631-1 Figure 1).
    pub axis: String,
    /// Weighting applied (ISO 2631-1 Tables 1–2: z → Wk, x/y → Wd, backrest x → Wc).
    pub weighting: Weighting,
    /// Comfort multiplying factor k (ISO 2631-1 8.2.2).
    pub k: f64,
    /// Mean of the samples, m/s²: a sensor offset or gravity. Every weighting has zero gain at DC
    /// and the filters start in the steady state of the recording's vibration
    /// ([`crate::analysis::filter::WeightingChain`]), so it changes no weighted figure.
    #[serde(default)]
    pub mean: f64,
    /// Unweighted r.m.s. (mean included), m/s².
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
    /// Why this channel's figures are doubtful, when its samples look like another unit than m/s²
    /// ([`super::units::looks_like`]); absent otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit_doubt: Option<String>,
}

/// The report of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// The run or file analysed, as given.
    pub source: String,
    /// Sample rate of the channels, Hz.
    pub sample_rate_hz: f64,
    /// Duration analysed, s.
    pub duration_s: f64,
    /// One report per acceleration channel.
    pub channels: Vec<ChannelReport>,
    /// Contact surface used for comfort ("seat" when present).
    pub comfort_place: String,
    /// Vibration total value a_v = (Σ k² a_w²)^½ over the comfort surface (and backrest), m/s² (eq. 10).
    pub total_value: f64,
    /// Comfort class of [`Report::total_value`] (ISO 2631-1 Annex C.2.3).
    pub comfort: Comfort,
    /// All Annex C ranges containing a_v.
    pub comfort_statement: String,
    /// SEAT % from a_seat_z over a_base_z with Wk, when both exist.
    pub seat_percent: Option<f64>,
    /// Health figures for the daily exposure (ISO 2631-1 Annex B, Directive 2002/44/EC); `None`
    /// when no exposure duration was given or no seat channel exists.
    pub health: Option<Health>,
    /// ISO 2631-5:2018 spinal dose of the seat's z axis (seated, vertical), when its crest factor
    /// exceeds 9 (ISO 2631-1 6.2.1) or it was asked for ([`Options::shocks`]); for the daily dose
    /// the exposure is [`Options::exposure_hours`], or 8 h when none is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub iso2631_5: Option<Shocks>,
    /// The spinal response's peaks of `a_seat_z` (ISO 2631-5 clause 5.3): what a working day of
    /// several records adds up (`wbv::analysis::exposure`). A report built block by block
    /// ([`super::ReportBuilder`]) always has them; [`Report::from_signals`] computes them only when
    /// it assesses ISO 2631-5 ([`Report::iso2631_5`]), and a day computes the rest
    /// (`wbv::report::exposure::day_of`). Not serialized.
    #[serde(skip)]
    pub seat_spine: Option<Peaks>,
    /// Frequency-weighted one-third-octave band r.m.s. 0.5–80 Hz of each channel, m/s²: band
    /// r.m.s. times the channel's weighting at the band centre (ISO 2631-1 eq. 6, Tables 3–4).
    pub weighted_bands: BTreeMap<String, Vec<Band>>,
    /// Warnings that make figures or verdicts doubtful (a channel that looks like g read as m/s²):
    /// shown before everything else.
    #[serde(default)]
    pub warnings: Vec<String>,
    /// Whether the comfort and health verdicts rest on a channel with a [`ChannelReport::unit_doubt`].
    #[serde(default)]
    pub verdict_doubtful: bool,
    /// Whether any analysed channel's unit was assumed (m/s²) rather than declared by the file or
    /// `--units`: then every figure of those channels, and every verdict that uses them, assumes
    /// m/s². No number can tell g from m/s² on a channel without gravity (a mean-free channel in g
    /// reads 9.81 × too low, its comfort class two or three classes too good), so the assumption
    /// is stated beside every verdict ([`Report::unit_assumption`]).
    #[serde(default)]
    pub unit_assumed: bool,
    /// The analysed channels whose unit was assumed (m/s²), in the order analysed.
    #[serde(default)]
    pub unit_assumed_channels: Vec<String>,
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
        ("weighted_bands.rms", "m/s^2"),
        ("total_value", "m/s^2"),
        ("seat_percent", "%"),
        ("health.a8", "m/s^2"),
        ("health.a_w_max", "m/s^2"),
        ("health.vdv_exposure", "m/s^1.75"),
        ("health.exposure_hours", "h"),
        ("iso2631_5.peak_max", "m/s^2"),
        ("iso2631_5.d_z", "m/s^2"),
        ("iso2631_5.d_zd", "m/s^2"),
        ("iso2631_5.measured_s", "s"),
        ("iso2631_5.exposure_hours", "h"),
        ("iso2631_5.s_ed_mpa", "MPa"),
        ("iso2631_5.r", "1"),
        ("iso2631_5.injury_probability", "1"),
    ]
    .into_iter()
    .map(|(k, u)| (k.to_string(), u.to_string()))
    .collect()
}

/// A note on a channel's mean: 1 g of gravity read by a DC-coupled accelerometer, data in g read
/// as m/s², or a sensor offset (mean over half the r.m.s. fluctuation); `None` when the mean is
/// unremarkable. `mean` and `rms` (including the mean) in the channel's unit.
pub fn offset_note(name: &str, mean: f64, rms: f64) -> Option<String> {
    let g = super::units::STANDARD_GRAVITY;
    let ac = (rms * rms - mean * mean).max(0.0).sqrt();
    let m = mean.abs();
    if name.starts_with("a_") && (m - g).abs() < 0.1 * g {
        Some(format!(
            "{name}: mean {mean:.3} m/s² is close to 1 g: gravity seems to be included"
        ))
    } else if name.starts_with("a_")
        && super::units::looks_like(mean, ac) == Some(super::units::LooksLike::GWithGravity)
    {
        Some(format!(
            "{name}: mean {mean:.3} with r.m.s. fluctuation {ac:.3}: the data look like g with \
             gravity (1 g ≈ 1.0) read as m/s²; give --units g if so"
        ))
    } else if m > 0.5 * ac && m > 0.0 {
        Some(format!(
            "{name}: mean {mean:.4} m/s² is {:.0} % of the r.m.s. fluctuation: a sensor offset?",
            100.0 * m / ac.max(f64::MIN_POSITIVE)
        ))
    } else {
        None
    }
}

/// The contact surface whose channels make the comfort total value: `seat` when any channel is on
/// the seat, else the first channel's place (ISO 2631-1 8.2.3: the seat surface, with backrest
/// and feet, for seated persons).
pub fn comfort_place<'a>(mut places: impl Iterator<Item = &'a str> + Clone) -> String {
    if places.clone().any(|p| p == "seat") {
        "seat".to_string()
    } else {
        places.next().unwrap_or_default().to_string()
    }
}

/// Whether a channel at `place` counts in the total value of `comfort_place`: the surface itself,
/// and for the seat also the backrest and the feet (ISO 2631-1 8.2.3).
pub fn in_total_value(place: &str, comfort_place: &str) -> bool {
    place == comfort_place || (comfort_place == "seat" && (place == "back" || place == "feet"))
}

/// Vibration total value a_v = (Σ k² a_w²)^½ in m/s² of `(k, a_w)` pairs, summed in order
/// (ISO 2631-1 eq. 10).
pub fn total_value(channels: impl Iterator<Item = (f64, f64)>) -> f64 {
    channels
        .map(|(k, a_w)| (k * a_w).powi(2))
        .sum::<f64>()
        .sqrt()
}

impl ChannelReport {
    fn notes(&self, duration_s: f64) -> Vec<String> {
        // A unit doubt is a warning of its own (Report::warnings), not a note.
        let offset =
            offset_note(&self.name, self.mean, self.rms).filter(|_| self.unit_doubt.is_none());
        let mut notes: Vec<String> = offset
            .map(|n| {
                if n.contains("gravity seems") {
                    format!("{n} (removed before weighting; the unweighted r.m.s. includes it)")
                } else if n.contains("sensor offset") {
                    format!("{n} (removed before weighting)")
                } else {
                    n
                }
            })
            .into_iter()
            .collect();
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
    /// Combines the channel figures of a run into the report: comfort total value, SEAT, health
    /// and notes.
    pub(super) fn assemble(
        source: &str,
        fs: f64,
        duration_s: f64,
        mut channels: Vec<ChannelReport>,
        seat_spine: Option<Peaks>,
        opts: &Options,
    ) -> Report {
        for c in &mut channels {
            let ac = (c.rms * c.rms - c.mean * c.mean).max(0.0).sqrt();
            if !opts.units_assumed.contains(&c.name) {
                continue;
            }
            c.unit_doubt = super::units::looks_like(c.mean, ac).map(|like| {
                format!(
                    "{}: the samples look like {like} read as m/s² (mean {:.3}, fluctuation \
                     {ac:.3}): if so every figure of this channel is {:.4} × the true one and \
                     the verdicts that use it are doubtful; give --units {}={}",
                    c.name,
                    c.mean,
                    1.0 / like.factor(),
                    c.name,
                    like.unit()
                )
            });
        }
        let warnings: Vec<String> = channels
            .iter()
            .filter_map(|c| c.unit_doubt.clone())
            .collect();
        let comfort_place = comfort_place(channels.iter().map(|c| c.place.as_str()));
        let in_total = |c: &&ChannelReport| in_total_value(&c.place, &comfort_place);
        let verdict_doubtful = channels
            .iter()
            .filter(in_total)
            .any(|c| c.unit_doubt.is_some());
        let total_value = total_value(channels.iter().filter(in_total).map(|c| (c.k, c.a_w)));
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
        let mut notes: Vec<String> = channels.iter().flat_map(|c| c.notes(duration_s)).collect();
        let seat_z_crest = find("a_seat_z").map(|c| c.crest_factor);
        let iso2631_5 = match (seat_spine, opts.shocks.trigger(seat_z_crest)) {
            (Some(peaks), Some(trigger)) => {
                let hours = opts
                    .exposure_hours
                    .unwrap_or(health::DEFAULT_EXPOSURE_HOURS);
                match Shocks::of_record("a_seat_z", trigger, &peaks, hours, &opts.shocks.history) {
                    Ok(s) => Some(s),
                    Err(e) => {
                        notes.push(format!("ISO 2631-5: {e}"));
                        None
                    }
                }
            }
            _ => None,
        };
        let unit_assumed_channels: Vec<String> = channels
            .iter()
            .filter(|c| opts.units_assumed.contains(&c.name))
            .map(|c| c.name.clone())
            .collect();
        let weighted_bands = channels
            .iter()
            .map(|c| {
                (
                    c.name.clone(),
                    octave::weighted_bands(&c.bands, c.weighting),
                )
            })
            .collect();
        Report {
            source: source.to_string(),
            sample_rate_hz: fs,
            duration_s,
            comfort_place,
            total_value,
            comfort: Comfort::from_total_value(total_value),
            comfort_statement: comfort::overlap_statement(total_value),
            seat_percent,
            health,
            iso2631_5,
            seat_spine,
            weighted_bands,
            warnings,
            verdict_doubtful,
            unit_assumed: !unit_assumed_channels.is_empty(),
            unit_assumed_channels,
            notes,
            channels,
            units: units(),
        }
    }

    /// The sentence that goes beside every verdict when a channel's unit was assumed
    /// ([`Report::unit_assumed`]): which channels, and what to give; None when every unit was
    /// declared.
    pub fn unit_assumption(&self) -> Option<String> {
        self.unit_assumed.then(|| {
            let names = self.unit_assumed_channels.join(", ");
            format!("assumes m/s²: {}", super::units::undeclared(&names))
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
