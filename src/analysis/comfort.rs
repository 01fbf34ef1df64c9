//! Comfort reactions to vibration in public transport, ISO 2631-1:1997 Annex C (C.2.3), applied to
//! the vibration total value a_v (eq. 10) in m/s².
//!
//! The standard's ranges overlap on purpose:
//! < 0.315 not uncomfortable; 0.315–0.63 a little uncomfortable; 0.5–1 fairly uncomfortable;
//! 0.8–1.6 uncomfortable; 1.25–2.5 very uncomfortable; > 2 extremely uncomfortable.
//! A single class therefore needs a rule. wbv uses: **the class is the highest range whose lower
//! bound is ≤ a_v** (so 0.55 m/s² is "fairly uncomfortable"), and [`overlap_statement`] words all
//! the ranges a_v falls in, as the standard does. The value a_v itself is always reported.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Comfort class, ordered from best to worst so that tests can write
/// `assert!(report.comfort() <= Comfort::ALittleUncomfortable)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Comfort {
    /// a_v < 0.315 m/s² (Annex C.2.3).
    NotUncomfortable,
    /// 0.315–0.63 m/s² (Annex C.2.3).
    ALittleUncomfortable,
    /// 0.5–1 m/s² (Annex C.2.3).
    FairlyUncomfortable,
    /// 0.8–1.6 m/s² (Annex C.2.3).
    Uncomfortable,
    /// 1.25–2.5 m/s² (Annex C.2.3).
    VeryUncomfortable,
    /// a_v > 2 m/s² (Annex C.2.3).
    ExtremelyUncomfortable,
}

/// The Annex C ranges (lower, upper) in m/s²; `None` is open.
pub const RANGES: [(Comfort, Option<f64>, Option<f64>); 6] = [
    (Comfort::NotUncomfortable, None, Some(0.315)),
    (Comfort::ALittleUncomfortable, Some(0.315), Some(0.63)),
    (Comfort::FairlyUncomfortable, Some(0.5), Some(1.0)),
    (Comfort::Uncomfortable, Some(0.8), Some(1.6)),
    (Comfort::VeryUncomfortable, Some(1.25), Some(2.5)),
    (Comfort::ExtremelyUncomfortable, Some(2.0), None),
];

impl Comfort {
    /// Class of a total value `a_v` (m/s²): the highest range whose lower bound is ≤ a_v.
    pub fn from_total_value(a_v: f64) -> Comfort {
        RANGES
            .iter()
            .rev()
            .find(|(_, lo, _)| lo.is_none_or(|lo| a_v >= lo))
            .map_or(Comfort::NotUncomfortable, |r| r.0)
    }

    /// The standard's wording.
    pub fn text(self) -> &'static str {
        match self {
            Comfort::NotUncomfortable => "not uncomfortable",
            Comfort::ALittleUncomfortable => "a little uncomfortable",
            Comfort::FairlyUncomfortable => "fairly uncomfortable",
            Comfort::Uncomfortable => "uncomfortable",
            Comfort::VeryUncomfortable => "very uncomfortable",
            Comfort::ExtremelyUncomfortable => "extremely uncomfortable",
        }
    }
}

impl fmt::Display for Comfort {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.text())
    }
}

/// All Annex C ranges containing `a_v`, worded as the standard does, e.g.
/// "0.550 m/s²: a little uncomfortable (0.315–0.63) or fairly uncomfortable (0.5–1) (ISO 2631-1 Annex C)".
pub fn overlap_statement(a_v: f64) -> String {
    format!(
        "{a_v:.3} m/s²: {} (ISO 2631-1 Annex C)",
        overlap_ranges(a_v)
    )
}

/// The Annex C ranges that contain `a_v` (m/s²), e.g. `a little uncomfortable (0.315–0.63)`; the
/// ranges overlap, so there may be two.
pub fn overlap_ranges(a_v: f64) -> String {
    let parts: Vec<String> = RANGES
        .iter()
        .filter(|(_, lo, hi)| lo.is_none_or(|lo| a_v >= lo) && hi.is_none_or(|hi| a_v <= hi))
        .map(|(c, lo, hi)| match (lo, hi) {
            (None, Some(h)) => format!("{c} (< {h})"),
            (Some(l), None) => format!("{c} (> {l})"),
            (Some(l), Some(h)) => format!("{c} ({l}–{h})"),
            (None, None) => c.to_string(),
        })
        .collect();
    parts.join(" or ")
}
