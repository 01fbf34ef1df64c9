//! A working day of several operations: the daily exposure A(8), the day's VDV and the Directive
//! 2002/44/EC verdict, and the day's ISO 2631-5 spinal dose when it has shocks.
//!
//! Formulas (each operation i measured for T_m,i and lasting T_i a day; k = 1.4, 1.4, 1 for x, y, z
//! on the seat, ISO 2631-1 7.2.3):
//! - A(8) of an axis = k [Σ_i a_w,i² T_i / T₀]^½, T₀ = 8 h: the energy-equivalent magnitude of
//!   ISO 2631-1 Annex B (B.3.2, a_w,e = [Σ a_w,i² T_i / Σ T_i]^½) normalised to 8 h as Directive
//!   2002/44/EC Annex A.1 (Part B point 1) defines A(8).
//! - VDV of an axis over the day = k [Σ_i VDV_i⁴]^¼ (ISO 2631-1 6.3.2 for exposures of several
//!   periods), each VDV_i scaled from its measurement to its duration as VDV·(T_i/T_m,i)^¼ (ISO
//!   2631-1 eq. 5 for a stationary signal).
//! - The day's values (Directive 2002/44/EC Annex Part B point 1, Article 3): the highest of
//!   1.4·a_wx, 1.4·a_wy, a_wz for A(8), and the highest of 1.4·VDV_x, 1.4·VDV_y, VDV_z for the VDV,
//!   each axis on its own; against the action values 0.5 m/s² / 9.1 m/s^1.75 and the limit values
//!   1.15 m/s² / 21 m/s^1.75.
//! - Time to reach a value, keeping the day's mix of operations: A(8) grows as the square root of
//!   the hours, the VDV as their fourth root, so T = T_day (value/A(8))² and T_day (value/VDV)⁴.
//!
//! The clause numbers of ISO 2631-1 for the several-period formulas (6.3.2 and B.3.2) are as quoted
//! by secondary sources and NOT checked against the standard's text; the formulas themselves
//! follow from eq. 1 and eq. 5 (the r.m.s. and the fourth-power integral add over periods).

use super::health::{self, DirectiveStatus};
pub use super::spine::ShockSettings;
use super::spine::{self, Peaks, Shocks, Trigger};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// Reference duration T₀ of A(8), h.
pub const T0_HOURS: f64 = 8.0;

/// One seat axis of one operation, as measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisFigures {
    /// `x`, `y` or `z`.
    pub axis: String,
    /// Frequency-weighted r.m.s. a_w, m/s².
    pub a_w: f64,
    /// VDV over the measurement, m/s^1.75.
    pub vdv: f64,
}

/// One operation of the day: what was measured on the seat and how long it lasts a day.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Operation {
    /// The operation's name as the user gave it (e.g. `loading`), labelling its row of the day.
    pub name: String,
    /// Daily duration T_i, h.
    pub hours: f64,
    /// Duration of the measurement T_m,i, s.
    pub measured_s: f64,
    /// The seat axes measured (x, y and/or z) with their a_w and VDV.
    pub axes: Vec<AxisFigures>,
    /// Weighted crest factor of the seat's z axis, when measured.
    pub crest_factor_z: Option<f64>,
    /// The spinal response's peaks of the seat's z axis (ISO 2631-5), when computed.
    pub spine: Option<Peaks>,
    /// Seat channels whose unit neither the file nor `--units` declared: their figures assume
    /// m/s² ([`super::Report::unit_assumed_channels`]).
    #[serde(default)]
    pub unit_assumed_channels: Vec<String>,
}

impl Operation {
    /// The operation `name` lasting `hours` a day, from the seat channels of `report`.
    pub fn from_report(name: &str, hours: f64, report: &super::Report) -> Result<Operation> {
        let axes: Vec<AxisFigures> = report
            .channels
            .iter()
            .filter(|c| c.place == "seat")
            .map(|c| AxisFigures {
                axis: c.axis.clone(),
                a_w: c.a_w,
                vdv: c.vdv,
            })
            .collect();
        if axes.is_empty() {
            return Err(Error::data(
                &report.source,
                None,
                "no seat channel `a_seat_<x|y|z>`: the daily exposure of a seated person is \
                 measured on the seat (ISO 2631-1 7.2.2); name the columns with --column",
            ));
        }
        Ok(Operation {
            name: name.to_string(),
            hours,
            measured_s: report.duration_s,
            axes,
            crest_factor_z: report.channel("a_seat_z").map(|c| c.crest_factor),
            spine: report.seat_spine,
            unit_assumed_channels: report
                .unit_assumed_channels
                .iter()
                .filter(|c| c.starts_with("a_seat_"))
                .cloned()
                .collect(),
        })
    }
}

/// One operation's row of the day.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OperationRow {
    /// The operation's name, as in [`Operation::name`].
    pub name: String,
    /// Daily duration, h.
    pub hours: f64,
    /// Duration of the measurement, s.
    pub measured_s: f64,
    /// Per axis: k, a_w, k·a_w and k·VDV scaled to the operation's duration.
    pub axes: Vec<AxisRow>,
    /// This operation's share of the day's A(8)² on the day's A(8) axis (0–1).
    pub a8_share: f64,
    /// This operation's share of the day's VDV⁴ on the day's VDV axis (0–1).
    pub vdv_share: f64,
    /// Hours a day of this operation alone that reach the A(8) exposure action value, 0.5 m/s²
    /// (2002/44/EC art. 3).
    pub hours_to_a8_action: f64,
    /// Hours a day of this operation alone that reach the A(8) exposure limit value, 1.15 m/s²
    /// (2002/44/EC art. 3).
    pub hours_to_a8_limit: f64,
    /// Weighted crest factor of the seat's z axis.
    pub crest_factor_z: Option<f64>,
    /// ISO 2631-5 acceleration dose D_z of the measurement, m/s², when computed.
    pub d_z: Option<f64>,
    /// Seat channels whose unit was assumed (m/s²): none declared by the file or `--units`.
    #[serde(default)]
    pub unit_assumed_channels: Vec<String>,
}

impl OperationRow {
    /// `f` of the seat axes x, y and z with `digits` decimals (`-` for an axis not measured),
    /// joined by `sep`: a table cell.
    pub fn per_axis(&self, f: fn(&AxisRow) -> f64, digits: usize, sep: &str) -> String {
        ["x", "y", "z"]
            .iter()
            .map(|ax| {
                self.axes
                    .iter()
                    .find(|a| a.axis == *ax)
                    .map_or("-".to_string(), |a| format!("{:.*}", digits, f(a)))
            })
            .collect::<Vec<_>>()
            .join(sep)
    }
}

/// One axis of one operation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisRow {
    /// `x`, `y` or `z` (seat axes, ISO 2631-1 fig. 1).
    pub axis: String,
    /// Multiplying factor k of the axis for health on the seat: 1.4 for x and y, 1 for z
    /// (ISO 2631-1 7.2.3); dimensionless.
    pub k: f64,
    /// Weighted r.m.s., m/s².
    pub a_w: f64,
    /// k·a_w, m/s².
    pub k_a_w: f64,
    /// k·VDV·(T_i/T_m,i)^¼: the operation's dose over its daily duration, m/s^1.75.
    pub k_vdv: f64,
}

/// One axis of the day.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DayAxis {
    /// `x`, `y` or `z` (seat axes, ISO 2631-1 fig. 1).
    pub axis: String,
    /// Multiplying factor k of the axis for health on the seat: 1.4 for x and y, 1 for z
    /// (ISO 2631-1 7.2.3); dimensionless.
    pub k: f64,
    /// k [Σ a_w,i² T_i / 8 h]^½, m/s².
    pub a8: f64,
    /// k [Σ VDV_i⁴]^¼, m/s^1.75.
    pub vdv: f64,
}

/// A working day's exposure.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Day {
    /// Σ T_i, h.
    pub hours: f64,
    /// The day's operations, each with its durations, per-axis figures and share of the dose.
    pub operations: Vec<OperationRow>,
    /// Per seat axis: k, A(8) in m/s² and VDV in m/s^1.75 over the day (ISO 2631-1 7.2.3, B.3.2).
    pub axes: Vec<DayAxis>,
    /// Daily exposure A(8): the highest of the axes' k-weighted A(8), m/s², and its axis.
    pub a8: f64,
    /// The axis (`x`, `y` or `z`) whose k-weighted A(8) is the day's A(8).
    pub a8_axis: String,
    /// A(8) against the exposure action (0.5 m/s²) and limit (1.15 m/s²) values of 2002/44/EC art. 3.
    pub a8_status: DirectiveStatus,
    /// The day's VDV: the highest of the axes' k-weighted VDV, m/s^1.75, and its axis.
    pub vdv_day: f64,
    /// The axis (`x`, `y` or `z`) whose k-weighted VDV is the day's VDV.
    pub vdv_axis: String,
    /// The day's VDV against the exposure action (9.1 m/s^1.75) and limit (21 m/s^1.75) values of
    /// 2002/44/EC art. 3.
    pub vdv_status: DirectiveStatus,
    /// The worse of `a8_status` and `vdv_status` (a member state uses one of the two; the worse is
    /// the answer that holds for both).
    pub zone: DirectiveStatus,
    /// Hours of this day's mix of operations (in its proportions) that reach the A(8) exposure
    /// action value, 0.5 m/s² (2002/44/EC art. 3).
    pub hours_to_a8_action: f64,
    /// Hours of this day's mix of operations that reach the A(8) exposure limit value, 1.15 m/s²
    /// (2002/44/EC art. 3).
    pub hours_to_a8_limit: f64,
    /// Hours of this day's mix of operations that reach the VDV exposure action value,
    /// 9.1 m/s^1.75 (2002/44/EC art. 3).
    pub hours_to_vdv_action: f64,
    /// Hours of this day's mix of operations that reach the VDV exposure limit value,
    /// 21 m/s^1.75 (2002/44/EC art. 3).
    pub hours_to_vdv_limit: f64,
    /// ISO 2631-5:2018 over the day (Formula 5), when an operation's crest factor exceeds 9 or it
    /// was asked for.
    pub iso2631_5: Option<Shocks>,
    /// What the reader should know (operations left out of the spinal dose, shocks).
    pub notes: Vec<String>,
    /// Whether any operation's seat channel had no declared unit, so that the day's figures and
    /// verdict assume m/s² (the rows' `unit_assumed_channels` name them).
    pub unit_assumed: bool,
}

/// Refuses hours a day of the operation `name` outside 0 < hours ≤ 24.
pub fn check_hours(name: &str, hours: f64) -> Result<()> {
    if !(hours.is_finite() && hours > 0.0 && hours <= 24.0) {
        return Err(Error::parameter(
            "--operation",
            format!("{name}: {hours} h; expected 0 < hours ≤ 24"),
        ));
    }
    Ok(())
}

/// The day of `operations` (see the module doc for the formulas).
pub fn assess(operations: &[Operation], shocks: &ShockSettings) -> Result<Day> {
    if operations.is_empty() {
        return Err(Error::parameter(
            "--operation",
            "expected at least one FILE:HOURS",
        ));
    }
    for op in operations {
        check_hours(&op.name, op.hours)?;
        if !(op.measured_s.is_finite() && op.measured_s > 0.0) {
            return Err(Error::data(
                &op.name,
                None,
                "the measurement has no duration",
            ));
        }
    }
    let hours: f64 = operations.iter().map(|o| o.hours).sum();
    if hours > 24.0 + 1e-9 {
        return Err(Error::parameter(
            "--operation",
            format!("the operations add up to {hours} h; a day has 24"),
        ));
    }
    let mut names: Vec<&str> = Vec::new();
    for op in operations {
        for a in &op.axes {
            if !names.contains(&a.axis.as_str()) {
                names.push(&a.axis);
            }
        }
    }
    names.sort_unstable();
    // Per operation and axis: k² a_w² T_i (for A(8)) and (k VDV_i (T_i/T_m)^¼)⁴ (for the VDV).
    let scaled_vdv = |op: &Operation, a: &AxisFigures| {
        health::k_health(&a.axis) * a.vdv * (op.hours * 3600.0 / op.measured_s).powf(0.25)
    };
    let energy = |op: &Operation, axis: &str| {
        op.axes
            .iter()
            .find(|a| a.axis == axis)
            .map_or(0.0, |a| (health::k_health(axis) * a.a_w).powi(2) * op.hours)
    };
    let dose4 = |op: &Operation, axis: &str| {
        op.axes
            .iter()
            .find(|a| a.axis == axis)
            .map_or(0.0, |a| scaled_vdv(op, a).powi(4))
    };
    let axes: Vec<DayAxis> = names
        .iter()
        .map(|&axis| DayAxis {
            axis: axis.to_string(),
            k: health::k_health(axis),
            a8: (operations.iter().map(|o| energy(o, axis)).sum::<f64>() / T0_HOURS).sqrt(),
            vdv: operations
                .iter()
                .map(|o| dose4(o, axis))
                .sum::<f64>()
                .powf(0.25),
        })
        .collect();
    // The Directive's rule: each value is the highest over the axes, axis by axis.
    let top = |value: fn(&DayAxis) -> f64| {
        axes.iter()
            .max_by(|l, r| value(l).total_cmp(&value(r)))
            .map(|a| (a.axis.clone(), value(a)))
            .unwrap_or_default()
    };
    let (a8_axis, a8) = top(|a| a.a8);
    let (vdv_axis, vdv_day) = top(|a| a.vdv);
    let share = |part: f64, whole: f64| if whole > 0.0 { part / whole } else { 0.0 };
    let rows: Vec<OperationRow> = operations
        .iter()
        .map(|op| {
            let k_a_w_max = op
                .axes
                .iter()
                .map(|a| health::k_health(&a.axis) * a.a_w)
                .fold(0.0, f64::max);
            OperationRow {
                name: op.name.clone(),
                hours: op.hours,
                measured_s: op.measured_s,
                axes: op
                    .axes
                    .iter()
                    .map(|a| AxisRow {
                        axis: a.axis.clone(),
                        k: health::k_health(&a.axis),
                        a_w: a.a_w,
                        k_a_w: health::k_health(&a.axis) * a.a_w,
                        k_vdv: scaled_vdv(op, a),
                    })
                    .collect(),
                a8_share: share(energy(op, &a8_axis), a8 * a8 * T0_HOURS),
                vdv_share: share(dose4(op, &vdv_axis), vdv_day.powi(4)),
                hours_to_a8_action: health::hours_to_a8(k_a_w_max, health::A8_ACTION),
                hours_to_a8_limit: health::hours_to_a8(k_a_w_max, health::A8_LIMIT),
                crest_factor_z: op.crest_factor_z,
                d_z: op.spine.map(|p| p.dose()),
                unit_assumed_channels: op.unit_assumed_channels.clone(),
            }
        })
        .collect();
    let a8_status = health::status(a8, health::A8_ACTION, health::A8_LIMIT);
    let vdv_status = health::status(vdv_day, health::VDV_ACTION, health::VDV_LIMIT);
    let scale = |value: f64, now: f64, power: i32| {
        if now > 0.0 {
            hours * (value / now).powi(power)
        } else {
            f64::INFINITY
        }
    };
    let mut notes = Vec::new();
    let iso2631_5 = day_shocks(operations, shocks, hours, &mut notes)?;
    Ok(Day {
        hours,
        operations: rows,
        axes,
        a8,
        a8_axis,
        a8_status,
        vdv_day,
        vdv_axis,
        vdv_status,
        zone: a8_status.max(vdv_status),
        hours_to_a8_action: scale(health::A8_ACTION, a8, 2),
        hours_to_a8_limit: scale(health::A8_LIMIT, a8, 2),
        hours_to_vdv_action: scale(health::VDV_ACTION, vdv_day, 4),
        hours_to_vdv_limit: scale(health::VDV_LIMIT, vdv_day, 4),
        iso2631_5,
        notes,
        unit_assumed: operations
            .iter()
            .any(|o| !o.unit_assumed_channels.is_empty()),
    })
}

/// The day's ISO 2631-5 assessment (Formula 5 over the operations with a seat z record).
fn day_shocks(
    operations: &[Operation],
    settings: &ShockSettings,
    hours: f64,
    notes: &mut Vec<String>,
) -> Result<Option<Shocks>> {
    let triggered: Vec<Trigger> = operations
        .iter()
        .filter_map(|o| settings.trigger(o.crest_factor_z))
        .collect();
    let Some(&trigger) = triggered
        .iter()
        .find(|t| **t == Trigger::CrestFactor)
        .or(triggered.first())
    else {
        return Ok(None);
    };
    for o in operations
        .iter()
        .filter(|o| o.crest_factor_z.is_some_and(|c| c > 9.0))
    {
        notes.push(format!(
            "{}: crest factor {:.1} > 9 on the seat's z axis: the r.m.s. method may underestimate \
             its shocks (ISO 2631-1 6.2.1); see the ISO 2631-5 spinal dose",
            o.name,
            o.crest_factor_z.unwrap_or_default()
        ));
    }
    let mut exposures = Vec::new();
    let mut all = Peaks::default();
    for o in operations {
        match o.spine {
            Some(p) => {
                exposures.push((p.dose(), o.hours * 3600.0, p.measured_s));
                all.count += p.count;
                all.sum6 += p.sum6;
                all.max = all.max.max(p.max);
                all.measured_s += p.measured_s;
            }
            None => notes.push(format!(
                "{}: no seat z channel, left out of the ISO 2631-5 daily dose",
                o.name
            )),
        }
    }
    if exposures.is_empty() {
        return Ok(None);
    }
    let d_zd = spine::daily_dose_of(&exposures);
    Shocks::of_daily_dose("a_seat_z", trigger, &all, hours, d_zd, &settings.history).map(Some)
}

impl Day {
    /// The day in words: the Directive's values with their axes and times, one line each.
    pub fn statement(&self) -> Vec<String> {
        let t = health::hours_text;
        let mut lines = vec![
            format!(
                "Working day of {} in {} operations (ISO 2631-1 Annex B, 6.3.2; Directive 2002/44/EC \
                 Annex B, Article 3):",
                t(self.hours),
                self.operations.len()
            ),
            format!(
                "  A(8) = {:.3} m/s² (the highest of 1.4·A(8)_x, 1.4·A(8)_y, A(8)_z: {} axis): {}; \
                 with this day's mix the action value {} m/s² is reached after {}, the limit value \
                 {} m/s² after {}",
                self.a8,
                self.a8_axis,
                self.a8_status.text(),
                health::A8_ACTION,
                t(self.hours_to_a8_action),
                health::A8_LIMIT,
                t(self.hours_to_a8_limit)
            ),
            format!(
                "  VDV = {:.2} m/s^1.75 (the highest of 1.4·VDV_x, 1.4·VDV_y, VDV_z: {} axis): {}; \
                 the action value {} m/s^1.75 is reached after {}, the limit value {} m/s^1.75 \
                 after {}",
                self.vdv_day,
                self.vdv_axis,
                self.vdv_status.text(),
                health::VDV_ACTION,
                t(self.hours_to_vdv_action),
                health::VDV_LIMIT,
                t(self.hours_to_vdv_limit)
            ),
        ];
        if self.unit_assumed {
            // No number tells g from m/s² on a zero-mean channel: the verdict carries the
            // assumption where it is read.
            let named: Vec<String> = self
                .operations
                .iter()
                .flat_map(|o| {
                    o.unit_assumed_channels
                        .iter()
                        .map(move |c| format!("{} {c}", o.name))
                })
                .collect();
            lines.insert(
                1,
                format!(
                    "  UNIT NOT DECLARED: the day's figures assume m/s²: {}",
                    super::units::undeclared(&named.join(", "))
                ),
            );
        }
        if let Some(s) = &self.iso2631_5 {
            lines.extend(s.statement());
        }
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn op(name: &str, hours: f64, axes: &[(&str, f64, f64)]) -> Operation {
        Operation {
            name: name.into(),
            hours,
            measured_s: 600.0,
            axes: axes
                .iter()
                .map(|(a, w, v)| AxisFigures {
                    axis: a.to_string(),
                    a_w: *w,
                    vdv: *v,
                })
                .collect(),
            crest_factor_z: Some(4.0),
            spine: None,
            unit_assumed_channels: Vec::new(),
        }
    }

    /// Two operations of 4 h, z only, a_w 0.5 and 0.25 m/s², VDV 5 and 2 over 600 s. By hand:
    /// A(8) = √((0.25·4 + 0.0625·4)/8) = √0.15625 = 0.395285; VDV_i scaled by (14400/600)^¼ = 24^¼:
    /// VDV = (5⁴·24 + 2⁴·24)^¼ = (15384)^¼ = 11.1370.
    #[test]
    fn a_day_of_two_operations_by_hand() {
        let day = assess(
            &[
                op("a", 4.0, &[("z", 0.5, 5.0)]),
                op("b", 4.0, &[("z", 0.25, 2.0)]),
            ],
            &ShockSettings::default(),
        )
        .unwrap();
        assert!((day.a8 - 0.15625f64.sqrt()).abs() < 1e-12);
        assert!((day.vdv_day - 15384f64.powf(0.25)).abs() < 1e-9);
        assert_eq!(day.a8_status, DirectiveStatus::BelowAction);
        assert_eq!(day.vdv_status, DirectiveStatus::AboveAction);
        assert_eq!(day.zone, DirectiveStatus::AboveAction);
        // Keeping the mix: A(8) ∝ √T, so 8·(0.5/0.395285)² = 12.8 h to the action value.
        assert!((day.hours_to_a8_action - 12.8).abs() < 1e-9);
        assert!((day.operations[0].a8_share - 0.8).abs() < 1e-12);
    }

    #[test]
    fn a_day_longer_than_24_hours_is_refused() {
        let e = assess(
            &[
                op("a", 20.0, &[("z", 0.5, 5.0)]),
                op("b", 5.0, &[("z", 0.5, 5.0)]),
            ],
            &ShockSettings::default(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("25"), "{e}");
    }
}
