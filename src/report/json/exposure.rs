//! `wbv exposure`: a working day of several operations.

use super::{Document, units};
use crate::analysis::exposure::Day;
use crate::error::Result;
use serde::Serialize;
use std::collections::BTreeMap;

/// `wbv exposure --json` (and the Python binding's result): the day's `a8`, `vdv_day`, `zone`
/// (`below_action`, `above_action`, `above_limit`), a row per operation under `operations`, the
/// axes, the ISO 2631-5 block `iso2631_5` when assessed, and the unit of every numeric key.
/// Hours that a day never reaches are `null`.
#[derive(Debug, Clone, Serialize)]
pub struct Exposure {
    /// The day’s figures and operations ([`crate::analysis::exposure::Day`]), at the top level.
    #[serde(flatten)]
    pub day: Day,
    /// The unit of every numeric key, by its dotted path (`a8`: `m/s^2`, `vdv_day`: `m/s^1.75`, …).
    pub units: BTreeMap<String, String>,
}

impl Exposure {
    /// The document of `day`.
    pub fn of(day: Day) -> Exposure {
        Exposure {
            day,
            units: units(&[
                ("hours", "h"),
                ("a8", "m/s^2"),
                ("vdv_day", "m/s^1.75"),
                ("hours_to_a8_action", "h"),
                ("hours_to_a8_limit", "h"),
                ("hours_to_vdv_action", "h"),
                ("hours_to_vdv_limit", "h"),
                ("axes.a8", "m/s^2"),
                ("axes.vdv", "m/s^1.75"),
                ("operations.hours", "h"),
                ("operations.measured_s", "s"),
                ("operations.axes.a_w", "m/s^2"),
                ("operations.axes.k_a_w", "m/s^2"),
                ("operations.axes.k_vdv", "m/s^1.75"),
                ("operations.a8_share", "1"),
                ("operations.vdv_share", "1"),
                ("operations.d_z", "m/s^2"),
                ("iso2631_5.d_z", "m/s^2"),
                ("iso2631_5.d_zd", "m/s^2"),
                ("iso2631_5.peak_max", "m/s^2"),
                ("iso2631_5.s_ed_mpa", "MPa"),
                ("iso2631_5.r", "1"),
                ("iso2631_5.injury_probability", "1"),
            ]),
        }
    }
}

/// The document of `wbv exposure --json` (and of the Python binding's `wbv.exposure`): the day
/// ([`Exposure`]) with what the readers and the analysis noted as its `warnings`.
pub fn exposure(day: Day, notes: Vec<String>) -> Result<Document> {
    Document::new("exposure", &Exposure::of(day), notes)
}
