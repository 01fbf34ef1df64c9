//! Vibration containing multiple shocks: ISO 2631-5:2018 (second edition), clause 5 and Annex C,
//! for a seated person and the vertical (z) axis. Nothing here comes from the withdrawn 2004
//! edition (its recurrent neural-network spine model, its x/y models, m_x/m_y, c = 0.25 MPa).
//!
//! The chain (each step cited; `docs/exposure.md` has the sources table):
//! 1. The seat's vertical acceleration a_z(t), mean removed (the transfer function is 1 at 0 Hz,
//!    so gravity or an offset would pass straight through), goes through the seat-to-spine transfer
//!    function (clause 5.2, Formula 1)
//!    H(s) = (1 + 2ζ₁s/ω₁ + s²/ω₁²) / Π_{k=1..6} (1 + 2ζ_k s/ω_k + s²/ω_k²),
//!    giving the spinal response A_z(t) (Formula 2).
//! 2. Peaks (clause 5.3): A_z,i is the largest value of A_z between two consecutive zero crossings;
//!    only positive peaks (compression) count.
//! 3. Acceleration dose (Formula 3) D_z = 1.07 (Σ A_z,i⁶)^⅙ m/s²; daily dose (Formula 4)
//!    D_zd = D_z (t_d/t_m)^⅙; several exposures a day (Formula 5) D_zd = [Σ_j D_z,j⁶ t_d,j/t_m,j]^⅙.
//! 4. Annex C: daily compressive stress S_ed = m_z D_zd MPa (Formula C.1; written S_d there),
//!    m_z = 0.029 MPa/(m/s²) for a man, 0.025 for a woman; the stress variable over the years of
//!    exposure R = [Σ_{i=0}^{n−1} (S_ed N^⅙ / (S_u,i − S_stat))⁶]^⅙ (Formulae C.3/C.4),
//!    S_u,i = 6.75 − S_age (b + i) MPa, S_stat = m_z g; and the probability of an injury of the
//!    vertebral end-plates P = 1 − exp(−(R/α)^β) (Formula C.5, Table C.1).
//!
//! Sources and what is verified (the standard's text was not reachable here):
//! - Every coefficient above is as transcribed by one open implementation of ISO 2631-5:2018
//!   (the `multiple_shock` module of the phonometry Python toolkit), which is secondary.
//! - The transfer function's coefficients are checked against a second, independent record of the
//!   same standard: the 256 Hz digital filter of Annex D (Table D.1, as transcribed by that
//!   toolkit's reference data): its response and the dose of shocks through it agree with Formula 1
//!   (tests in `tests/analysis_shocks.rs`).
//! - D_z, D_zd, S_ed, R and P are checked against the Annex C worked example (five 40 m/s² peaks a
//!   day, a man exposed from 20 years of age for 20 years, 120 days a year: D_zd = 55.97 m/s²,
//!   R = 1.22, P = 0.37), as quoted by the same toolkit. The woman's note of that example prints
//!   R = 0.97 where these formulas give 0.962 (with S_stat = 0.281 MPa, the man's, they give 0.969):
//!   NOT resolved without the standard's text.
//! - S_age (0.052 / 0.039 MPa per year), the 6.75 MPa intercept, α and β (Table C.1) and i counted
//!   from 0 are NOT verified beyond reproducing the man's worked example.
//!
//! The weighting filters' start applies here too: the filter runs over a past predicted from the
//! record's first seconds ([`crate::analysis::filter::predict_past`]), so a record cut out of a
//! longer ride does not begin with a step that the spine model would turn into a false peak.

use crate::analysis::filter::{FIT_S, predict_past};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};
use num_complex::Complex64;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The complex zero pair of Formula 1: (ω₁ in rad/s, ζ₁). Secondary source; see the module doc.
pub const ZERO: (f64, f64) = (34.0, 0.35);
/// The six complex pole pairs of Formula 1: (ω_k in rad/s, ζ_k). Secondary source, checked against
/// the Annex D filter; see the module doc.
pub const POLES: [(f64, f64); 6] = [
    (31.0, 0.21),
    (230.0, 0.88),
    (260.0, 0.80),
    (320.0, 0.40),
    (380.0, 0.75),
    (420.0, 0.65),
];
/// Formula 3's factor 1.07 (the spine's amplitude response in the dose).
pub const DOSE_FACTOR: f64 = 1.07;
/// Formula 3's exponent 6 (Palmgren–Miner fatigue of the vertebral end-plates).
pub const DOSE_EXPONENT: f64 = 6.0;
/// Annex C: acceleration of gravity for the static stress, m/s².
pub const GRAVITY: f64 = 9.81;
/// Annex C Formula C.4: the ultimate strength's intercept, MPa.
pub const STRENGTH_INTERCEPT_MPA: f64 = 6.75;
/// Transient amplitude, relative to its start, below which the spine filter counts as settled.
const SETTLED: f64 = 1e-4;

/// The person of Annex C: the stress conversion m_z, the ageing of the ultimate strength and the
/// Weibull coefficients of the injury probability differ between men and women.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Sex {
    /// The 82 kg man of Annex C.
    #[default]
    Male,
    /// The 64 kg woman of Annex C NOTE 5.
    Female,
}

impl Sex {
    /// m_z, MPa per m/s² (Annex C Formula C.1 / C.2).
    pub fn m_z(self) -> f64 {
        match self {
            Sex::Male => 0.029,
            Sex::Female => 0.025,
        }
    }

    /// S_age, the yearly loss of ultimate strength, MPa per year (Formula C.4).
    pub fn strength_loss_per_year(self) -> f64 {
        match self {
            Sex::Male => 0.052,
            Sex::Female => 0.039,
        }
    }

    /// (α, β) of the Weibull injury probability (Table C.1).
    pub fn weibull(self) -> (f64, f64) {
        match self {
            Sex::Male => (1.613, 2.799),
            Sex::Female => (0.959, 3.709),
        }
    }

    /// Parses `male` or `female`.
    pub fn parse(s: &str) -> Result<Sex> {
        match s.to_ascii_lowercase().as_str() {
            "male" | "m" | "man" => Ok(Sex::Male),
            "female" | "f" | "woman" => Ok(Sex::Female),
            _ => Err(Error::parameter(
                "--spine-sex",
                format!("`{s}`: expected male or female"),
            )),
        }
    }
}

/// The exposure history of Annex C's stress variable R. The defaults are the Annex C worked
/// example's: a man exposed from 20 years of age for 20 years, 120 days a year.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct History {
    /// The person assessed (Annex C: m_z, strength ageing and Weibull coefficients depend on it).
    pub sex: Sex,
    /// Age b at which the exposure began, years.
    pub start_age_years: f64,
    /// Number n of years of exposure.
    pub years: u32,
    /// Number N of exposure days a year.
    pub days_per_year: f64,
}

impl Default for History {
    fn default() -> Self {
        History {
            sex: Sex::Male,
            start_age_years: 20.0,
            years: 20,
            days_per_year: 120.0,
        }
    }
}

impl History {
    /// Refuses a history Annex C cannot take: a start age outside 0–100 years, no year of
    /// exposure, or exposure days a year outside 0 < N ≤ 366 (each error names the command's
    /// option).
    pub fn validate(&self) -> Result<()> {
        let bad = |flag: &str, what: &str| Error::parameter(flag, what.to_string());
        if !(self.start_age_years.is_finite() && (0.0..=100.0).contains(&self.start_age_years)) {
            return Err(bad("--spine-start-age", "expected an age in years, 0–100"));
        }
        if self.years == 0 {
            return Err(bad("--spine-years", "expected at least 1 year"));
        }
        if !(self.days_per_year.is_finite()
            && self.days_per_year > 0.0
            && self.days_per_year <= 366.0)
        {
            return Err(bad("--spine-days-per-year", "expected 0 < days ≤ 366"));
        }
        Ok(())
    }

    /// The history in words, for a statement.
    pub fn text(&self) -> String {
        format!(
            "a {} exposed from {} years of age for {} years, {} days a year",
            match self.sex {
                Sex::Male => "man",
                Sex::Female => "woman",
            },
            self.start_age_years,
            self.years,
            self.days_per_year
        )
    }
}

/// Seat-to-spine transfer function H(j2πf) of Formula 1 (dimensionless, 1 at 0 Hz).
pub fn transfer(f_hz: f64) -> Complex64 {
    let s = Complex64::new(0.0, 2.0 * PI * f_hz);
    let quad = |(w, z): (f64, f64)| 1.0 + 2.0 * z * s / w + s * s / (w * w);
    POLES.iter().fold(quad(ZERO), |h, &p| h / quad(p))
}

/// Formula 1 as a cascade state space (ẋ = Ax + Bu, y = Cx + Du, 12 states): the zero pair over
/// the slowest pole pair, then the five all-pole sections ω²/(s² + 2ζωs + ω²). A cascade keeps the
/// matrices well scaled (the polynomial of degree 12 would span 10³⁰).
fn state_space() -> (DMatrix<f64>, DVector<f64>, DVector<f64>, f64) {
    let n = 2 * POLES.len();
    let mut a = DMatrix::<f64>::zeros(n, n);
    let mut b = DVector::<f64>::zeros(n);
    // Each section in controllable form: states (q, q̇), q̈ = −ω²q − 2ζωq̇ + u_in, output
    // y = c0 q + c1 q̇ + d u_in. `input` holds (row coefficients on earlier states, d on u).
    let mut input_c = DVector::<f64>::zeros(n);
    let mut input_d = 1.0;
    for (k, &(w, z)) in POLES.iter().enumerate() {
        let (q, qd) = (2 * k, 2 * k + 1);
        a[(q, qd)] = 1.0;
        a[(qd, q)] = -w * w;
        a[(qd, qd)] = -2.0 * z * w;
        // u_in = input_c·x + input_d·u.
        for j in 0..n {
            a[(qd, j)] += input_c[j];
        }
        b[qd] = input_d;
        let (c0, c1, d) = if k == 0 {
            // (w²/w1²)(s² + 2ζ1 w1 s + w1²)/(s² + 2ζ w s + w²): with s²Q = u_in − w²Q − 2ζwsQ,
            // y = (w²/w1²)[u_in + (w1² − w²) Q + (2ζ1 w1 − 2ζ w) sQ].
            let (w1, z1) = ZERO;
            let g = w * w / (w1 * w1);
            (g * (w1 * w1 - w * w), g * (2.0 * z1 * w1 - 2.0 * z * w), g)
        } else {
            (w * w, 0.0, 0.0)
        };
        let mut next_c = input_c.clone() * d;
        next_c[q] += c0;
        next_c[qd] += c1;
        input_c = next_c;
        input_d *= d;
    }
    (a, b, input_c, input_d)
}

/// Formula 1 discretised exactly for an input that is linear between samples (first-order hold,
/// Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed., §6.3.2): with
/// M = exp([[A, B, 0], [0, 0, 1], [0, 0, 0]]·T), Φ = M₁₁, Γ₁ = M₁₂, Γ₂ = M₁₃,
/// x_{k+1} = Φx_k + Γ₁u_k + Γ₂(u_{k+1} − u_k), y_k = Cx_k + Du_k.
///
/// The matrices have the model's fixed size ([`STATES`]), so a step allocates nothing; nalgebra
/// multiplies them in the same order as the dynamic ones it was first written with (column by
/// column, the same dot product), so the response is the same bit for bit (test
/// `fixed_size_steps_equal_dynamic_ones`).
#[derive(Debug, Clone)]
pub struct SpineFilter {
    phi: SMatrix<f64, STATES, STATES>,
    g1: SVector<f64, STATES>,
    g2: SVector<f64, STATES>,
    c: SVector<f64, STATES>,
    d: f64,
    x: SVector<f64, STATES>,
    prev: f64,
    fs: f64,
}

/// Number of states of Formula 1's state space: two per pole pair.
pub const STATES: usize = 2 * POLES.len();

impl SpineFilter {
    /// The filter at `fs` Hz, at rest.
    pub fn new(fs: f64) -> Result<Self> {
        if !(fs.is_finite() && fs > 0.0) {
            return Err(Error::parameter(
                "sample rate",
                format!("{fs} Hz; expected > 0"),
            ));
        }
        let (a, b, c, d) = state_space();
        let n = a.nrows();
        let t = 1.0 / fs;
        let mut m = DMatrix::<f64>::zeros(n + 2, n + 2);
        m.view_mut((0, 0), (n, n)).copy_from(&(&a * t));
        for i in 0..n {
            m[(i, n)] = b[i] * t;
        }
        m[(n, n + 1)] = 1.0;
        let e = m.exp();
        Ok(SpineFilter {
            phi: e.fixed_view::<STATES, STATES>(0, 0).into_owned(),
            g1: e.fixed_view::<STATES, 1>(0, n).into_owned(),
            g2: e.fixed_view::<STATES, 1>(0, n + 1).into_owned(),
            c: c.fixed_rows::<STATES>(0).into_owned(),
            d,
            x: SVector::zeros(),
            prev: 0.0,
            fs,
        })
    }

    /// Slowest decay rate of the model's free response, 1/s (ζω of the slowest pole pair).
    pub fn slowest_decay_rate() -> f64 {
        POLES
            .iter()
            .map(|(w, z)| z * w)
            .fold(f64::INFINITY, f64::min)
    }

    /// The spinal response A_z at the next input sample `u` (m/s² in, m/s² out).
    pub fn step(&mut self, u: f64) -> f64 {
        self.x = self.phi * self.x + self.g1 * self.prev + self.g2 * (u - self.prev);
        self.prev = u;
        self.c.dot(&self.x) + self.d * u
    }

    /// The spinal response of `x` from rest (Formula 2), m/s².
    pub fn response(mut self, x: &[f64]) -> Vec<f64> {
        x.iter().map(|&u| self.step(u)).collect()
    }

    /// Sample rate, Hz.
    pub fn rate_hz(&self) -> f64 {
        self.fs
    }
}

/// The positive peaks of a response (clause 5.3): the largest value between two consecutive zero
/// crossings, for every run of positive samples (a run cut by the record's start or end counts).
pub fn positive_peaks(response: &[f64]) -> Vec<f64> {
    let mut peaks = Vec::new();
    let mut run = 0.0f64;
    for &y in response {
        if y > 0.0 {
            run = run.max(y);
        } else if run > 0.0 {
            peaks.push(run);
            run = 0.0;
        }
    }
    if run > 0.0 {
        peaks.push(run);
    }
    peaks
}

/// Acceleration dose D_z = 1.07 (Σ A_i⁶)^⅙ in m/s² of positive peaks `peaks` (m/s²) (Formula 3).
pub fn dose(peaks: &[f64]) -> f64 {
    dose_of_sum(peaks.iter().map(|p| p.powi(6)).sum())
}

fn dose_of_sum(sum6: f64) -> f64 {
    DOSE_FACTOR * sum6.powf(1.0 / DOSE_EXPONENT)
}

/// Daily dose D_zd = D_z (t_d/t_m)^⅙ (Formula 4) of a dose `d_z` measured over `measured_s` for an
/// exposure of `exposure_s` a day (same units), m/s².
pub fn daily_dose(d_z: f64, exposure_s: f64, measured_s: f64) -> f64 {
    d_z * (exposure_s / measured_s).powf(1.0 / DOSE_EXPONENT)
}

/// Daily dose of several exposures a day (Formula 5): D_zd = [Σ_j D_z,j⁶ t_d,j/t_m,j]^⅙ over
/// `(D_z,j m/s², t_d,j, t_m,j)` (times in one unit), m/s².
pub fn daily_dose_of(exposures: &[(f64, f64, f64)]) -> f64 {
    exposures
        .iter()
        .map(|(d, td, tm)| d.powi(6) * td / tm)
        .sum::<f64>()
        .powf(1.0 / DOSE_EXPONENT)
}

/// Daily compressive stress S_ed = m_z D_zd in MPa (Annex C Formula C.1) of a daily dose `d_zd`
/// m/s².
pub fn compressive_stress(d_zd: f64, sex: Sex) -> f64 {
    sex.m_z() * d_zd
}

/// The stress variable R = [Σ_{i=0}^{n−1} (S_ed N^⅙ / (S_u,i − S_stat))⁶]^⅙ of a daily stress
/// `s_ed` MPa over the years of `history` (Annex C Formulae C.3, C.4), with
/// S_u,i = 6.75 − S_age (b + i) MPa and S_stat = m_z g. Dimensionless; an error when the strength
/// left over the static stress runs out within the years (an age beyond the model).
pub fn risk_factor(s_ed: f64, history: &History) -> Result<f64> {
    let h = history;
    if !(h.days_per_year.is_finite() && h.days_per_year > 0.0) || h.years == 0 {
        return Err(Error::parameter(
            "spine history",
            "expected at least one year and more than 0 days a year",
        ));
    }
    let s_stat = h.sex.m_z() * GRAVITY;
    let mut sum = 0.0;
    for i in 0..h.years {
        let age = h.start_age_years + f64::from(i);
        let margin = STRENGTH_INTERCEPT_MPA - h.sex.strength_loss_per_year() * age - s_stat;
        if margin <= 0.0 {
            return Err(Error::parameter(
                "spine history",
                format!(
                    "at {age} years of age the ultimate strength of ISO 2631-5 Annex C has fallen \
                     below the static stress: the ages lie beyond the model"
                ),
            ));
        }
        sum += (s_ed * h.days_per_year.powf(1.0 / 6.0) / margin).powi(6);
    }
    Ok(sum.powf(1.0 / 6.0))
}

/// Probability of an injury of the vertebral end-plates P = 1 − exp(−(R/α)^β) (Annex C Formula
/// C.5, Table C.1), 0–1.
pub fn injury_probability(r: f64, sex: Sex) -> f64 {
    let (alpha, beta) = sex.weibull();
    1.0 - (-(r.max(0.0) / alpha).powf(beta)).exp()
}

/// The spinal response's peaks of a record, accumulated block by block ([`SpineDose`]).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Peaks {
    /// Number of positive peaks.
    pub count: usize,
    /// Σ A_z,i⁶, (m/s²)⁶.
    pub sum6: f64,
    /// Largest A_z,i, m/s².
    pub max: f64,
    /// Duration of the record t_m, s.
    pub measured_s: f64,
}

impl Peaks {
    /// The peaks of the whole record `x` (seat z, m/s²) sampled at `fs` Hz: [`SpineDose`] fed
    /// with it at once (any split gives the same peaks).
    pub fn of_record(x: &[f64], fs: f64) -> Result<Peaks> {
        let mut dose = SpineDose::new(fs)?;
        dose.push(x);
        Ok(dose.finish())
    }

    /// D_z of these peaks (Formula 3), m/s².
    pub fn dose(&self) -> f64 {
        dose_of_sum(self.sum6)
    }
}

/// The spine's response to a seat's vertical acceleration, fed in blocks: the offset (the mean of
/// the first [`FIT_S`] s) is removed, the filter runs over a past predicted from them, then over
/// the record, and the positive peaks of the response are accumulated. Any split of the input
/// gives the same peaks bit for bit.
#[derive(Debug, Clone)]
pub struct SpineDose {
    filter: SpineFilter,
    fit_len: usize,
    prefix_len: usize,
    pending: Vec<f64>,
    offset: Option<f64>,
    run: f64,
    peaks: Peaks,
    samples: usize,
}

impl SpineDose {
    /// The accumulator for a record sampled at `fs` Hz.
    pub fn new(fs: f64) -> Result<Self> {
        let filter = SpineFilter::new(fs)?;
        let settle_s = 1.5 * (1.0 / SETTLED).ln() / SpineFilter::slowest_decay_rate();
        Ok(SpineDose {
            filter,
            fit_len: ((FIT_S * fs).round() as usize).max(1),
            prefix_len: (settle_s * fs).ceil() as usize,
            pending: Vec::new(),
            offset: None,
            run: 0.0,
            peaks: Peaks::default(),
            samples: 0,
        })
    }

    /// Adds the next block of seat acceleration, m/s².
    pub fn push(&mut self, x: &[f64]) {
        self.samples += x.len();
        if let Some(offset) = self.offset {
            for &v in x {
                self.feed(v - offset);
            }
            return;
        }
        let take = (self.fit_len - self.pending.len()).min(x.len());
        self.pending.extend_from_slice(&x[..take]);
        if self.pending.len() == self.fit_len {
            self.start();
            let offset = self.offset.unwrap_or(0.0);
            for &v in &x[take..] {
                self.feed(v - offset);
            }
        }
    }

    fn start(&mut self) {
        let pending = std::mem::take(&mut self.pending);
        let offset = pending.iter().sum::<f64>() / pending.len().max(1) as f64;
        self.offset = Some(offset);
        let centred: Vec<f64> = pending.iter().map(|v| v - offset).collect();
        for v in predict_past(&centred, self.prefix_len, self.filter.rate_hz()) {
            self.filter.step(v);
        }
        for v in centred {
            self.feed(v);
        }
    }

    fn feed(&mut self, u: f64) {
        let y = self.filter.step(u);
        if y > 0.0 {
            self.run = self.run.max(y);
        } else if self.run > 0.0 {
            self.close_run();
        }
    }

    fn close_run(&mut self) {
        self.peaks.count += 1;
        self.peaks.sum6 += self.run.powi(6);
        self.peaks.max = self.peaks.max.max(self.run);
        self.run = 0.0;
    }

    /// The peaks of the whole record.
    pub fn finish(mut self) -> Peaks {
        if self.offset.is_none() && !self.pending.is_empty() {
            self.start();
        }
        if self.run > 0.0 {
            self.close_run();
        }
        self.peaks.measured_s = self.samples as f64 / self.filter.rate_hz();
        self.peaks
    }
}

/// Whether and how to assess shocks by ISO 2631-5.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ShockSettings {
    /// Assess even without a crest factor above 9.
    pub requested: bool,
    /// The exposure history used for R (ISO 2631-5:2018 Annex C).
    pub history: History,
}

impl ShockSettings {
    /// Why to assess a record whose seat crest factor is `crest_factor` (none: no assessment).
    pub fn trigger(&self, crest_factor: Option<f64>) -> Option<Trigger> {
        if crest_factor.is_some_and(|c| c > super::figures::CREST_FACTOR_LIMIT) {
            Some(Trigger::CrestFactor)
        } else if self.requested {
            Some(Trigger::Requested)
        } else {
            None
        }
    }
}

/// Why an ISO 2631-5 assessment was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Trigger {
    /// The seat's weighted crest factor exceeds 9: ISO 2631-1 6.2.1 sends such records to
    /// methods for shocks.
    CrestFactor,
    /// Asked for (`--iso2631-5`).
    Requested,
}

/// The ISO 2631-5:2018 assessment of one exposure (JSON block `iso2631_5`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Shocks {
    /// The standard and edition applied.
    pub standard: String,
    /// The seat channel assessed (`a_seat_z`).
    pub channel: String,
    /// Why the assessment was made.
    pub trigger: Trigger,
    /// Number of positive peaks of the spinal response.
    pub peaks: usize,
    /// Largest peak A_z,i, m/s².
    pub peak_max: f64,
    /// Acceleration dose over the record D_z, m/s² (Formula 3).
    pub d_z: f64,
    /// Duration over which D_z was measured t_m, s.
    pub measured_s: f64,
    /// Daily exposure t_d, h.
    pub exposure_hours: f64,
    /// Daily dose D_zd, m/s² (Formulae 4, 5).
    pub d_zd: f64,
    /// Daily compressive stress S_ed = m_z D_zd, MPa (Annex C Formula C.1).
    pub s_ed_mpa: f64,
    /// Stress variable R over `history` (Annex C Formula C.3), dimensionless.
    pub r: f64,
    /// Probability of an injury of the vertebral end-plates P(R) (Annex C Formula C.5), 0–1.
    pub injury_probability: f64,
    /// The exposure history R was computed for (ISO 2631-5:2018 Annex C).
    pub history: History,
}

impl Shocks {
    /// The assessment of a daily dose `d_zd` m/s²; `peaks` and `measured_s` describe the record(s).
    pub fn of_daily_dose(
        channel: &str,
        trigger: Trigger,
        peaks: &Peaks,
        exposure_hours: f64,
        d_zd: f64,
        history: &History,
    ) -> Result<Shocks> {
        let s_ed = compressive_stress(d_zd, history.sex);
        let r = risk_factor(s_ed, history)?;
        Ok(Shocks {
            standard: "ISO 2631-5:2018".into(),
            channel: channel.to_string(),
            trigger,
            peaks: peaks.count,
            peak_max: peaks.max,
            d_z: peaks.dose(),
            measured_s: peaks.measured_s,
            exposure_hours,
            d_zd,
            s_ed_mpa: s_ed,
            r,
            injury_probability: injury_probability(r, history.sex),
            history: *history,
        })
    }

    /// The assessment of one record's `peaks` for `exposure_hours` a day (Formula 4).
    pub fn of_record(
        channel: &str,
        trigger: Trigger,
        peaks: &Peaks,
        exposure_hours: f64,
        history: &History,
    ) -> Result<Shocks> {
        let d_zd = daily_dose(peaks.dose(), exposure_hours * 3600.0, peaks.measured_s);
        Self::of_daily_dose(channel, trigger, peaks, exposure_hours, d_zd, history)
    }

    /// The assessment in words, one line each.
    pub fn statement(&self) -> Vec<String> {
        let why = match self.trigger {
            Trigger::CrestFactor => "the seat's crest factor exceeds 9 (ISO 2631-1 6.2.1)",
            Trigger::Requested => "as requested",
        };
        vec![
            format!("Shocks (ISO 2631-5:2018, seated, z; {why}):"),
            format!(
                "  spinal response of {}: {} positive peaks, the largest {:.2} m/s²; D_z = {:.2} m/s² \
                 over {:.1} s (Formula 3)",
                self.channel, self.peaks, self.peak_max, self.d_z, self.measured_s
            ),
            format!(
                "  daily dose D_zd = {:.2} m/s² for {} a day; S_ed = m_z·D_zd = {:.3} MPa (Annex C)",
                self.d_zd,
                super::health::hours_text(self.exposure_hours),
                self.s_ed_mpa
            ),
            format!(
                "  R = {:.2} for {} (Annex C); probability of an end-plate injury {:.0} %",
                self.r,
                self.history.text(),
                100.0 * self.injury_probability
            ),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_state_space_is_formula_1() {
        let (a, b, c, d) = state_space();
        for f in [0.0, 0.7, 3.0, 5.0, 12.0, 40.0, 80.0] {
            let s = Complex64::new(0.0, 2.0 * PI * f);
            let n = a.nrows();
            let m = DMatrix::<Complex64>::identity(n, n) * s - a.map(Complex64::from);
            let x = m
                .lu()
                .solve(&b.map(Complex64::from))
                .expect("regular at these frequencies");
            let h = c.map(Complex64::from).dot(&x) + d;
            assert!(
                (h - transfer(f)).norm() < 1e-9,
                "{f} Hz: {h} vs {}",
                transfer(f)
            );
        }
    }

    #[test]
    fn peaks_are_the_largest_of_each_positive_run() {
        let y = [0.0, 1.0, 3.0, 2.0, -1.0, -4.0, 5.0, 1.0];
        assert_eq!(positive_peaks(&y), vec![3.0, 5.0]);
    }

    #[test]
    fn any_split_gives_the_same_peaks() {
        let fs = 400.0;
        let x: Vec<f64> = (0..16_000)
            .map(|i| {
                let t = i as f64 / fs;
                (2.0 * PI * 3.0 * t).sin() + if i % 3000 == 700 { 20.0 } else { 0.0 }
            })
            .collect();
        let mut whole = SpineDose::new(fs).unwrap();
        whole.push(&x);
        let mut parts = SpineDose::new(fs).unwrap();
        for c in x.chunks(977) {
            parts.push(c);
        }
        assert_eq!(whole.finish(), parts.finish());
    }

    /// The response through nalgebra's dynamic matrices, as `SpineFilter::step` was first written.
    fn dynamic_response(fs: f64, x: &[f64]) -> Vec<f64> {
        let f = SpineFilter::new(fs).unwrap();
        let phi = DMatrix::from_column_slice(STATES, STATES, f.phi.as_slice());
        let g1 = DVector::from_column_slice(f.g1.as_slice());
        let g2 = DVector::from_column_slice(f.g2.as_slice());
        let c = DVector::from_column_slice(f.c.as_slice());
        let mut s = DVector::<f64>::zeros(STATES);
        let mut prev = 0.0;
        x.iter()
            .map(|&u| {
                let next = &phi * &s + &g1 * prev + &g2 * (u - prev);
                s = next;
                prev = u;
                c.dot(&s) + f.d * u
            })
            .collect()
    }

    #[test]
    fn fixed_size_steps_equal_dynamic_ones() {
        let fs = 1000.0;
        let x: Vec<f64> = (0..20_000)
            .map(|i| {
                let t = i as f64 / fs;
                (2.0 * PI * 4.0 * t).sin()
                    + 0.3 * (2.0 * PI * 37.0 * t + 1.0).sin()
                    + if i % 5000 == 900 { 15.0 } else { 0.0 }
            })
            .collect();
        let fixed = SpineFilter::new(fs).unwrap().response(&x);
        let dynamic = dynamic_response(fs, &x);
        assert!(
            fixed
                .iter()
                .zip(&dynamic)
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
    }

    #[test]
    fn an_age_beyond_the_model_is_an_error() {
        let h = History {
            start_age_years: 100.0,
            years: 40,
            ..History::default()
        };
        assert!(risk_factor(1.0, &h).is_err());
    }
}
