//! Health assessment: ISO 2631-1:1997 clause 7 / Annex B and the EU Directive 2002/44/EC.
//!
//! - Exposure basis (Directive Annex Part B; ISO 2631-1 7.2.3): the highest of 1.4 a_wx, 1.4 a_wy
//!   and a_wz measured on the seat surface; for the dose, the highest of 1.4 VDV_x, 1.4 VDV_y and
//!   VDV_z, taken axis by axis on its own (Directive Annex B.1): the axis with the largest dose need
//!   not be the axis with the largest r.m.s. (shocks in x, steady vibration in z).
//! - Daily exposure A(8) = a (T/T0)^½, T0 = 8 h (Directive Annex A.1).
//! - Directive whole-body values (Article 3): action 0.5 m/s² A(8) or 9.1 m/s^1.75 VDV; limit
//!   1.15 m/s² A(8) or 21 m/s^1.75 VDV.
//! - Health guidance caution zone (ISO 2631-1 Figure B.1): boundaries follow eq. B.1,
//!   a_w1 T1^½ = a_w2 T2^½, or eq. B.2, a_w1 T1^¼ = a_w2 T2^¼. Anchored at the zone read from
//!   Figure B.1 for 8 h, 0.43–0.87 m/s² (the figure is not tabulated; these anchors are the
//!   widely quoted reading and are NOT verified against the standard's text).

use serde::{Deserialize, Serialize};

/// k factors for health, seated, seat surface (ISO 2631-1 7.2.3): x, y, z.
pub const K_HEALTH: [f64; 3] = [1.4, 1.4, 1.0];
/// Directive 2002/44/EC Article 3: daily exposure action value, m/s² A(8).
pub const A8_ACTION: f64 = 0.5;
/// Directive 2002/44/EC Article 3: daily exposure limit value, m/s² A(8).
pub const A8_LIMIT: f64 = 1.15;
/// Directive 2002/44/EC Article 3: VDV action value, m/s^1.75.
pub const VDV_ACTION: f64 = 9.1;
/// Directive 2002/44/EC Article 3: VDV limit value, m/s^1.75.
pub const VDV_LIMIT: f64 = 21.0;
/// Caution zone at 8 h, m/s² (Figure B.1 reading, unverified; see module docs).
pub const CAUTION_8H: (f64, f64) = (0.43, 0.87);
const T0_S: f64 = 8.0 * 3600.0;

/// Where an exposure lies relative to the caution zone.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Zone {
    /// "health effects have not been clearly documented and/or objectively observed".
    Below,
    /// "caution with respect to potential health risks is indicated".
    Caution,
    /// "health risks are likely".
    Above,
}

/// Caution-zone equation of Annex B.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ZoneEquation {
    /// Eq. B.1: a T^½ constant (energy equivalence).
    B1,
    /// Eq. B.2: a T^¼ constant (fourth-power, VDV-like).
    B2,
}

/// The caution-zone bounds (m/s²) for an exposure of `hours`.
pub fn caution_zone(hours: f64, eq: ZoneEquation) -> (f64, f64) {
    let ratio = T0_S / (hours * 3600.0);
    let p = match eq {
        ZoneEquation::B1 => 0.5,
        ZoneEquation::B2 => 0.25,
    };
    let s = ratio.powf(p);
    (CAUTION_8H.0 * s, CAUTION_8H.1 * s)
}

/// Classifies `a_w` (m/s²) against the zone for `hours` of exposure.
pub fn zone(a_w: f64, hours: f64, eq: ZoneEquation) -> Zone {
    let (lo, hi) = caution_zone(hours, eq);
    if a_w < lo {
        Zone::Below
    } else if a_w <= hi {
        Zone::Caution
    } else {
        Zone::Above
    }
}

/// Daily exposure A(8) = a (T/8 h)^½ in m/s² for `a` m/s² over `hours`.
pub fn a8(a: f64, hours: f64) -> f64 {
    a * (hours / 8.0).sqrt()
}

/// Directive status of a daily exposure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DirectiveStatus {
    /// At or below the exposure action value.
    BelowAction,
    /// Above the exposure action value, at or below the exposure limit value.
    AboveAction,
    /// Above the exposure limit value.
    AboveLimit,
}

impl DirectiveStatus {
    /// The Directive's terms: "below the exposure action value", ….
    pub fn text(self) -> &'static str {
        match self {
            DirectiveStatus::BelowAction => "at or below the exposure action value",
            DirectiveStatus::AboveAction => {
                "above the exposure action value, at or below the exposure limit value"
            }
            DirectiveStatus::AboveLimit => "above the exposure limit value",
        }
    }
}

impl Zone {
    /// ISO 2631-1 Annex B.3.1 wording of the region.
    pub fn text(self) -> &'static str {
        match self {
            Zone::Below => {
                "below the health guidance caution zone: health effects have not been clearly \
                 documented and/or objectively observed"
            }
            Zone::Caution => {
                "in the health guidance caution zone: caution with respect to potential health \
                 risks is indicated"
            }
            Zone::Above => "above the health guidance caution zone: health risks are likely",
        }
    }
}

/// Daily exposure in hours at which a constant `a_w` (m/s²) reaches A(8) = `value`:
/// T = 8 h · (value / a_w)², from A(8) = a_w (T/8 h)^½ (Directive Annex A.1). Infinite for a_w = 0.
pub fn hours_to_a8(a_w: f64, value: f64) -> f64 {
    if a_w > 0.0 {
        8.0 * (value / a_w).powi(2)
    } else {
        f64::INFINITY
    }
}

/// Daily exposure in hours at which the dose reaches `value` m/s^1.75, given the dose `vdv` over
/// `hours`: VDV grows as T^¼ (ISO 2631-1 eq. 5 for a stationary signal), so T = hours·(value/vdv)⁴.
pub fn hours_to_vdv(vdv: f64, hours: f64, value: f64) -> f64 {
    if vdv > 0.0 {
        hours * (value / vdv).powi(4)
    } else {
        f64::INFINITY
    }
}

/// Daily exposure in hours at which a constant `a_w` reaches the caution-zone boundary that is
/// `bound_8h` m/s² at 8 h, along eq. B.1 (T ∝ a⁻²) or B.2 (T ∝ a⁻⁴).
pub fn hours_to_zone(a_w: f64, bound_8h: f64, eq: ZoneEquation) -> f64 {
    if a_w <= 0.0 {
        return f64::INFINITY;
    }
    let p = match eq {
        ZoneEquation::B1 => 2,
        ZoneEquation::B2 => 4,
    };
    8.0 * (bound_8h / a_w).powi(p)
}

/// A duration in hours as a person reads it: `40 min`, `6.2 h`, or `more than 24 h` (a working
/// day never reaches it).
pub fn hours_text(h: f64) -> String {
    if !h.is_finite() || h > 24.0 {
        "more than 24 h".into()
    } else if h < 1.0 / 60.0 {
        "less than 1 min".into()
    } else if h < 1.0 {
        format!("{:.0} min", h * 60.0)
    } else {
        format!("{h:.1} h")
    }
}

/// Status of a value against (action, limit).
pub fn status(value: f64, action: f64, limit: f64) -> DirectiveStatus {
    if value > limit {
        DirectiveStatus::AboveLimit
    } else if value > action {
        DirectiveStatus::AboveAction
    } else {
        DirectiveStatus::BelowAction
    }
}

/// Health figures of a seat for a daily exposure.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Health {
    /// Daily exposure duration in hours.
    pub exposure_hours: f64,
    /// Highest k-weighted axis r.m.s. (m/s²) and its axis.
    pub a_w_max: f64,
    /// The axis of [`Health::a_w_max`] (`x`, `y` or `z`).
    pub axis: String,
    /// A(8) in m/s².
    pub a8: f64,
    /// [`Health::a8`] against the Directive 2002/44/EC action and limit values (Art. 3(2)).
    pub a8_status: DirectiveStatus,
    /// The highest of 1.4·VDV_x, 1.4·VDV_y and VDV_z, each scaled to the exposure as
    /// (VDV⁴ T/T_run)^¼, m/s^1.75 (Directive 2002/44/EC Annex B.1, axis by axis).
    pub vdv_exposure: f64,
    /// The axis of [`Health::vdv_exposure`] (not necessarily [`Health::axis`]).
    #[serde(default)]
    pub vdv_axis: String,
    /// [`Health::vdv_exposure`] against the Directive 2002/44/EC VDV action and limit values
    /// (Art. 3(2)).
    pub vdv_status: DirectiveStatus,
    /// Caution zone by eq. B.1 and B.2.
    pub zone_b1: Zone,
    /// Caution zone by eq. B.2 (a T^¼ constant), ISO 2631-1:1997 Annex B.
    pub zone_b2: Zone,
}

impl Health {
    /// The health assessment in the words of ISO 2631-1 (clause 7, Annex B) and Directive
    /// 2002/44/EC, one line each: the exposure assumed, the basis, A(8) and VDV against the action
    /// and limit values with the daily time to reach each, and the caution zone.
    pub fn statement(&self) -> Vec<String> {
        let h = self.exposure_hours;
        let t = |v: f64| hours_text(hours_to_a8(self.a_w_max, v));
        let tv = |v: f64| hours_text(hours_to_vdv(self.vdv_exposure, h, v));
        let tz = |v: f64, eq| hours_text(hours_to_zone(self.a_w_max, v, eq));
        vec![
            format!(
                "Health (ISO 2631-1 clause 7 and Annex B; Directive 2002/44/EC), assuming {} of \
                 this vibration a day:",
                hours_text(h)
            ),
            format!(
                "  basis: the highest of 1.4·a_wx, 1.4·a_wy, a_wz on the seat = {:.3} m/s² ({} axis)",
                self.a_w_max, self.axis
            ),
            format!(
                "  A(8) = {:.3} m/s²: {} (action value {A8_ACTION}, limit value {A8_LIMIT} m/s² A(8)); the action value \
                 is reached after {} a day, the limit value after {}",
                self.a8,
                self.a8_status.text(),
                t(A8_ACTION),
                t(A8_LIMIT)
            ),
            format!(
                "  VDV (the highest of 1.4·VDV_x, 1.4·VDV_y, VDV_z: {} axis) = {:.2} m/s^1.75 over {}: {} \
                 (action value {VDV_ACTION}, limit value {VDV_LIMIT} m/s^1.75); the action value is reached \
                 after {} a day, the limit value after {}",
                self.vdv_axis,
                self.vdv_exposure,
                hours_text(h),
                self.vdv_status.text(),
                tv(VDV_ACTION),
                tv(VDV_LIMIT)
            ),
            format!(
                "  Figure B.1, eq. (B.1): {}; the zone is entered after {} a day and left after {}",
                self.zone_b1.text(),
                tz(CAUTION_8H.0, ZoneEquation::B1),
                tz(CAUTION_8H.1, ZoneEquation::B1)
            ),
            format!(
                "  Figure B.1, eq. (B.2): {}; the zone is entered after {} a day and left after {}",
                self.zone_b2.text(),
                tz(CAUTION_8H.0, ZoneEquation::B2),
                tz(CAUTION_8H.1, ZoneEquation::B2)
            ),
        ]
    }
}

/// Default daily exposure in hours when none is given (`wbv run`, `wbv report`): a working day,
/// the reference duration T0 of A(8).
pub const DEFAULT_EXPOSURE_HOURS: f64 = 8.0;

/// The health multiplying factor k of a seat axis `x`, `y` or `z` (ISO 2631-1 7.2.3).
pub fn k_health(axis: &str) -> f64 {
    match axis {
        "x" => K_HEALTH[0],
        "y" => K_HEALTH[1],
        _ => K_HEALTH[2],
    }
}

/// The axis and value of the largest k·`value(axis)` over `axes` (each axis on its own: ISO 2631-1
/// 7.2.3 and Directive 2002/44/EC Annex B.1 take the highest of 1.4·x, 1.4·y and z); `None` when
/// `axes` is empty.
pub fn highest_axis<'a, T>(
    axes: &'a [T],
    axis: impl Fn(&'a T) -> &'a str,
    value: impl Fn(&'a T) -> f64,
) -> Option<(&'a str, f64)> {
    axes.iter()
        .map(|t| (axis(t), k_health(axis(t)) * value(t)))
        .max_by(|l, r| l.1.total_cmp(&r.1))
}

/// Health figures from per-axis (axis name, a_w m/s², VDV m/s^1.75) of the seat surface measured
/// over `run_s` seconds, for a daily exposure of `hours`. The A(8) basis is the highest of
/// 1.4·a_wx, 1.4·a_wy, a_wz and the dose the highest of 1.4·VDV_x, 1.4·VDV_y, VDV_z, each taken
/// axis by axis (Directive 2002/44/EC Annex B.1); the dose is scaled to the exposure as
/// VDV·(T/T_run)^¼ (ISO 2631-1 eq. 5 for a stationary signal).
pub fn assess(axes: &[(String, f64, f64)], run_s: f64, hours: f64) -> Option<Health> {
    let (axis, a) = highest_axis(axes, |t| t.0.as_str(), |t| t.1)?;
    let (vdv_axis, v) = highest_axis(axes, |t| t.0.as_str(), |t| t.2)?;
    let a8v = a8(a, hours);
    let vdv_exposure = v * (hours * 3600.0 / run_s).powf(0.25);
    Some(Health {
        exposure_hours: hours,
        a_w_max: a,
        axis: axis.to_string(),
        vdv_axis: vdv_axis.to_string(),
        a8: a8v,
        a8_status: status(a8v, A8_ACTION, A8_LIMIT),
        vdv_exposure,
        vdv_status: status(vdv_exposure, VDV_ACTION, VDV_LIMIT),
        zone_b1: zone(a, hours, ZoneEquation::B1),
        zone_b2: zone(a, hours, ZoneEquation::B2),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_to_the_values_invert_the_definitions() {
        // a_w = 1 m/s²: A(8) = 0.5 after 8·0.25 = 2 h; 1.15 after 8·1.3225 = 10.58 h (hand values).
        assert!((hours_to_a8(1.0, A8_ACTION) - 2.0).abs() < 1e-12);
        assert!((hours_to_a8(1.0, A8_LIMIT) - 10.58).abs() < 1e-9);
        // VDV 10 over 1 h reaches 20 after 16 h (2⁴).
        assert!((hours_to_vdv(10.0, 1.0, 20.0) - 16.0).abs() < 1e-12);
        assert_eq!(hours_text(0.5), "30 min");
        assert_eq!(hours_text(30.0), "more than 24 h");
        assert_eq!(hours_text(6.25), "6.2 h");
    }

    /// The record: z highest by r.m.s., x carries the shocks. By hand: basis max(1.4·0.30,
    /// 0.60) = 0.60 m/s² (z); dose max(1.4·9.43, 7.9) = 13.2 m/s^1.75 (x), above the 9.1 action
    /// value, where the VDV of the axis highest by r.m.s. (z, 7.9) is below it.
    #[test]
    fn the_dose_is_the_highest_of_the_axes_doses_not_the_dose_of_the_rms_axis() {
        let axes = vec![("x".to_string(), 0.30, 9.43), ("z".to_string(), 0.60, 7.9)];
        let h = assess(&axes, 8.0 * 3600.0, 8.0).unwrap();
        assert_eq!(h.axis, "z");
        assert!((h.a_w_max - 0.60).abs() < 1e-12);
        assert_eq!(h.vdv_axis, "x");
        assert!((h.vdv_exposure - 13.202).abs() < 1e-9, "{}", h.vdv_exposure);
        assert_eq!(h.vdv_status, DirectiveStatus::AboveAction);
    }

    #[test]
    fn the_statement_uses_the_standard_words_not_enum_names() {
        let axes = vec![("z".to_string(), 0.8, 12.0)];
        let h = assess(&axes, 60.0, 8.0).unwrap();
        let text = h.statement().join("\n");
        for word in [
            "AboveLimit",
            "AboveAction",
            "BelowAction",
            "Caution,",
            "Above\n",
        ] {
            assert!(!text.contains(word), "{text}");
        }
        for word in [
            "8.0 h",
            "0.5",
            "1.15",
            "9.1",
            "21",
            "Directive 2002/44/EC",
            "caution zone",
        ] {
            assert!(text.contains(word), "{word}: {text}");
        }
    }
}
