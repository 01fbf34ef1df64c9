//! Health assessment: ISO 2631-1:1997 clause 7 / Annex B and the EU Directive 2002/44/EC.
//!
//! - Exposure basis (Directive Annex Part B; ISO 2631-1 7.2.3): the highest of 1.4 a_wx, 1.4 a_wy
//!   and a_wz measured on the seat surface.
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
    BelowAction,
    AboveAction,
    AboveLimit,
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
    pub axis: String,
    /// A(8) in m/s².
    pub a8: f64,
    pub a8_status: DirectiveStatus,
    /// VDV of the highest k-weighted axis scaled to the exposure, (VDV⁴ T/T_run)^¼, m/s^1.75.
    pub vdv_exposure: f64,
    pub vdv_status: DirectiveStatus,
    /// Caution zone by eq. B.1 and B.2.
    pub zone_b1: Zone,
    pub zone_b2: Zone,
}

/// Health figures from per-axis (axis name, a_w m/s², VDV m/s^1.75) of the seat surface measured
/// over `run_s` seconds, for a daily exposure of `hours`.
pub fn assess(axes: &[(String, f64, f64)], run_s: f64, hours: f64) -> Option<Health> {
    let k = |axis: &str| match axis {
        "x" => K_HEALTH[0],
        "y" => K_HEALTH[1],
        _ => K_HEALTH[2],
    };
    let (axis, a, v) = axes
        .iter()
        .map(|(ax, a, v)| (ax.clone(), k(ax) * a, k(ax) * v))
        .max_by(|l, r| l.1.total_cmp(&r.1))?;
    let a8v = a8(a, hours);
    let vdv_exposure = v * (hours * 3600.0 / run_s).powf(0.25);
    Some(Health {
        exposure_hours: hours,
        a_w_max: a,
        axis,
        a8: a8v,
        a8_status: status(a8v, A8_ACTION, A8_LIMIT),
        vdv_exposure,
        vdv_status: status(vdv_exposure, VDV_ACTION, VDV_LIMIT),
        zone_b1: zone(a, hours, ZoneEquation::B1),
        zone_b2: zone(a, hours, ZoneEquation::B2),
    })
}
