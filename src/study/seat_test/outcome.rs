//! What a seat test yields ([`super`]): each run's figures, each test person's test, the damping
//! test and the whole test's JSON document, with the verdict against the application standard's
//! limits.

use super::contacts::Contacts;
use super::{Limits, Occupant};
use crate::excitation::classes::PsdCheck;
use serde::Serialize;
use std::collections::BTreeMap;

/// The outcome against the limits, from the best to the worst (so the worst of several is their
/// maximum).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Every limit given is met (SEAT, damping-test transmissibility and end-stop contacts at or
    /// below their limits) and no end-stop impact went unjudged.
    Pass,
    /// Every limit given is met, but the suspension struck its end stops and no contact limit
    /// (`--contact-limit`) was given to judge the impacts.
    Warning,
    /// At least one limit given is exceeded, or the runs did not make a valid test.
    Fail,
}

impl Verdict {
    /// `PASS`, `WARNING`, `FAIL`.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Pass => "PASS",
            Verdict::Warning => "WARNING",
            Verdict::Fail => "FAIL",
        }
    }

    /// A verdict as a table cell: its word, `-` for none.
    pub fn cell(v: Option<Verdict>) -> &'static str {
        v.map_or("-", Verdict::word)
    }
}

/// The end-stop impacts of one test person over the three runs used.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Impacts {
    /// Contacts over the runs used.
    pub count: usize,
    /// The same per 10 min of run (count × 600 s / the runs' total duration): what
    /// `--contact-limit` is judged against.
    pub per_10_min: f64,
    /// Total duration of the runs used, s.
    pub over_s: f64,
    /// Largest absolute seat-surface acceleration during an impact, m/s² (unweighted).
    pub peak_seat_acceleration_m_s2: f64,
    /// Mean of the impacts' peak seat accelerations, m/s².
    pub mean_peak_seat_acceleration_m_s2: f64,
    /// The largest seat VDV of the runs used, m/s^1.75 (Wk, ISO 2631-1 6.3.2).
    pub vdv_s: f64,
    /// The VDV the impacts add to that run's (the largest over the runs used), m/s^1.75.
    pub vdv_added_m_s1_75: f64,
    /// The largest seat crest factor of the runs used.
    pub crest_factor_s: f64,
}

/// One run of a test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Run {
    /// The seed of a simulated run, or the file of a measured one.
    pub id: String,
    /// Wk-weighted r.m.s. of the platform, m/s².
    pub a_wp: f64,
    /// Wk-weighted r.m.s. of the seat surface, m/s².
    pub a_ws: f64,
    /// a_ws / a_wp of this run.
    pub seat: f64,
    /// VDV of the seat surface, m/s^1.75.
    pub vdv_s: f64,
    /// Crest factor of the Wk-weighted seat acceleration.
    pub crest_factor_s: f64,
    /// The run's platform PSD against the class tolerance.
    pub platform_psd: Option<PsdCheck>,
    /// End-stop contacts (simulated runs).
    pub end_stop_contacts: Option<Contacts>,
}

/// Spectra kept for the report (not part of the JSON document).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Spectra {
    /// Bin frequencies, Hz.
    pub freq_hz: Vec<f64>,
    /// Platform PSD averaged over the runs used, (m/s²)²/Hz.
    pub platform: Vec<f64>,
    /// Seat PSD averaged over the runs used, (m/s²)²/Hz.
    pub seat: Vec<f64>,
    /// Bin spacing, Hz.
    pub df_hz: f64,
    /// Welch segments summed over the runs used.
    pub segments: usize,
    /// Bin frequencies of the transmissibility, Hz (spacing
    /// [`super::TRANSMISSIBILITY_RESOLUTION_HZ`]).
    pub fine_freq_hz: Vec<f64>,
    /// Seat transmissibility `√(G_S/G_P)` from the runs' averaged spectra (NaN where the platform
    /// carries no power).
    pub transmissibility: Vec<f64>,
}

/// The SEAT test of one test person.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OccupantTest {
    /// `light`, `heavy`, or `null` for measured runs.
    pub occupant: Option<Occupant>,
    /// The test person's body mass, kg (`null` for measured runs).
    pub body_mass_kg: Option<f64>,
    /// The model's body masses, after scaling, kg.
    pub supported_mass_kg: Option<f64>,
    /// The factor the model's body was scaled by.
    pub scale: Option<f64>,
    /// Every run made, in order.
    pub runs: Vec<Run>,
    /// Index of the first of the three consecutive runs used.
    pub first_used: usize,
    /// Whether those three agree within ±5 % in a_wP (clause 10.2.1); when no three did, the last
    /// three are used and this is false.
    pub runs_agree: bool,
    /// Mean a_wP of the runs used, m/s².
    pub a_wp: f64,
    /// Mean a_wS of the runs used, m/s².
    pub a_ws: f64,
    /// a_ws / a_wp (clause 10.2.2).
    pub seat: f64,
    /// SEAT · a*_wP: the seat value at the class's intended input, m/s² (clause 10.2.3).
    pub a_ws_corrected: f64,
    /// The runs' averaged platform PSD against the class's tolerance.
    pub platform_psd: Option<PsdCheck>,
    /// Whether that averaged PSD is within the tolerance.
    pub psd_within_tolerance: Option<bool>,
    /// End-stop contacts over the runs used.
    pub end_stop_contacts: Option<usize>,
    /// The impacts behind those contacts (`null` for measured runs, which count none).
    pub impacts: Option<Impacts>,
    /// Frequency of the largest seat transmissibility `√(G_S/G_P)` of the averaged spectra over
    /// 0.5–20 Hz, Hz: the suspension's resonance with this test person.
    pub seat_resonance_hz: Option<f64>,
    /// That largest transmissibility.
    pub seat_transmissibility_peak: Option<f64>,
    /// This test person's verdict against the limits (SEAT, contacts, the damping test).
    pub verdict: Option<Verdict>,
    /// The averaged platform and seat PSDs, (m/s²)²/Hz, for the report's plots (not serialised).
    #[serde(skip)]
    pub spectra: Spectra,
}

/// The damping test's outcome.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DampingTest {
    /// The inert mass, kg.
    pub mass_kg: f64,
    /// Resonance frequency, Hz (largest transmissibility of the sweep, parabola-refined).
    pub f_r_hz: f64,
    /// T = a_S/a_P at f_r.
    pub transmissibility: f64,
    /// The first estimate: the lowest undamped mode of the loaded seat, Hz.
    pub undamped_estimate_hz: f64,
    /// Platform displacement amplitude of the dwells, m.
    pub platform_amplitude_m: f64,
    /// The suspension's free travel either way, m (`null` without end stops).
    pub free_travel_m: Option<f64>,
    /// The sweep: dwell frequencies, Hz.
    pub sweep_hz: Vec<f64>,
    /// And the transmissibility at each.
    pub sweep_transmissibility: Vec<f64>,
    /// End-stop contacts over all dwells.
    pub end_stop_contacts: usize,
}

/// The seat test on one input class: one entry of the document's `classes`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SeatTest {
    /// `simulated` or `measured`.
    pub source: &'static str,
    /// The model (simulated) or `null`.
    pub model: Option<String>,
    /// The input class's name (`iso7096-em3`).
    pub class: String,
    /// `ISO 7096`, `EN 13490` or `ISO 5007`.
    pub standard: &'static str,
    /// The class as the standard names it (`EM3`).
    pub class_code: &'static str,
    /// The machines the class stands for (unverified per class).
    pub machine: &'static str,
    /// The quantity that puts a machine in the class (`operating mass > 4500 kg`, `tractor mass
    /// 3600–6500 kg`).
    pub defining: &'static str,
    /// How far `machine` and `defining` are verified against the standard.
    pub scope: crate::excitation::classes::Scope,
    /// a*_wP: the Wk-weighted r.m.s. of the class's target PSD, m/s².
    pub intended_a_wp: f64,
    /// Duration of each run, s.
    pub run_duration_s: Option<f64>,
    /// Every test person tested.
    pub occupants: Vec<OccupantTest>,
    /// The test person with the highest SEAT; the keys below are theirs.
    pub governing_occupant: Option<Occupant>,
    /// The governing test person's runs, in order.
    pub runs: Vec<Run>,
    /// The governing test person's mean Wk-weighted platform r.m.s. a_wP, m/s² (ISO 10326-1 10.2.1).
    pub a_wp: f64,
    /// The governing test person's mean Wk-weighted seat r.m.s. a_wS, m/s² (ISO 10326-1 10.2.1).
    pub a_ws: f64,
    /// The governing SEAT value a_wS/a_wP, dimensionless (ISO 10326-1 10.2.2).
    pub seat: f64,
    /// SEAT · a*_wP: the governing seat value at the class's intended input, m/s²
    /// (ISO 10326-1 10.2.3).
    pub a_ws_corrected: f64,
    /// Whether every test person's averaged platform PSD is within the class's ±10 %-of-peak
    /// tolerance (`null` when any test person's PSD was not checked).
    pub psd_within_tolerance: Option<bool>,
    /// End-stop contacts over every test person's runs used.
    pub end_stop_contacts: Option<usize>,
    /// The application standard's acceptance values the verdict is judged against.
    pub limits: Limits,
    /// `pass`, `warning`, `fail`, or `null` without limits and impacts: the worst of the test
    /// persons'.
    pub verdict: Option<Verdict>,
    /// The verdict in one line: `WARNING — PASS on SEAT; 47 end-stop impacts in 30 min (heavy),
    /// crest factor 14.3`.
    pub verdict_line: String,
    /// Why, one sentence per criterion judged.
    pub verdict_reasons: Vec<String>,
    /// What was decided on the way (extra runs, PSD out of tolerance, …).
    pub notes: Vec<String>,
    /// The numbers this test rests on that are not verified against the standards' text.
    pub unverified: Vec<String>,
}

/// One row of the summary table: one class and test person.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SummaryRow {
    /// The class's name (`iso7096-em3`).
    pub class: String,
    /// The class as the standard names it, with the standard (`ISO 7096 EM3`).
    pub class_code: String,
    /// Machine group and defining quantity with their verification mark.
    pub machine: String,
    /// `light`, `heavy`, or `measured`.
    pub occupant: &'static str,
    /// SEAT = a_wS / a_wP.
    pub seat: f64,
    /// a*_wS, m/s².
    pub a_ws_corrected: f64,
    /// End-stop contacts over the runs used (`null` for measured runs).
    pub end_stop_contacts: Option<usize>,
    /// The same per 10 min of run.
    pub contacts_per_10_min: Option<f64>,
    /// The damping test's transmissibility (one test of the seat, the same on every row).
    pub damping_transmissibility: Option<f64>,
    /// This test person's verdict on this class.
    pub verdict: Option<Verdict>,
}

/// The seat test on one or more classes: the JSON document of `wbv seat-test --json` and of
/// `wbv.seat_test`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SeatTests {
    /// `simulated` or `measured`.
    pub source: &'static str,
    /// The model (simulated) or `null`.
    pub model: Option<String>,
    /// Duration of each simulated run, s.
    pub run_duration_s: Option<f64>,
    /// One row per class and test person, in the order tested.
    pub summary: Vec<SummaryRow>,
    /// The worst verdict of the classes (`null` when none has one).
    pub verdict: Option<Verdict>,
    /// Each class's verdict line, prefixed with its class.
    pub verdict_lines: Vec<String>,
    /// The damping test (ISO 10326-1 10.3): one test of the seat, whatever the class (`null`
    /// when not run; see `damping_skipped`).
    pub damping: Option<DampingTest>,
    /// Why the damping test was not run, when it was not.
    pub damping_skipped: Option<String>,
    /// The application standard's acceptance values.
    pub limits: Limits,
    /// The test on each class, in the order given.
    pub classes: Vec<SeatTest>,
    /// What the input looks like that the results may not show (a run given twice, …).
    pub warnings: Vec<String>,
    /// Unit of each numeric key of the document (`classes.seat` → `1`, …).
    pub units: BTreeMap<String, String>,
}

impl OccupantTest {
    /// `light`, `heavy`, or `measured` for a lab's runs.
    pub fn label(&self) -> &'static str {
        self.occupant.map_or("measured", |p| p.name())
    }
    /// The body mass as a table cell: kg to 0.1, `-` for a lab's runs.
    pub fn mass_cell(&self) -> String {
        self.body_mass_kg.map_or("-".into(), |m| format!("{m:.1}"))
    }
    /// Whether the platform's PSD kept the standard's tolerance, as a table cell: `yes`, `NO`
    /// (capitals: it voids the test), `-` when not checked.
    pub fn psd_cell(&self) -> &'static str {
        match self.psd_within_tolerance {
            Some(true) => "yes",
            Some(false) => "NO",
            None => "-",
        }
    }
    /// The end-stop contacts as a table cell: the count, `-` when not simulated.
    pub fn contacts_cell(&self) -> String {
        self.end_stop_contacts.map_or("-".into(), |c| c.to_string())
    }
}
