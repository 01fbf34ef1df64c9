//! Single-factor sensitivity analysis (paper 000 §5.1): each parameter alone at levels
//! `p₀·(1 + L/100)` (paper: L = −30, 0, +30 %), all others at the model's values; the response's peak
//! frequency and peak magnitude at each level.
//!
//! Influence weights: paper 000 derives its weights (0.276, 0.241, …, summing to 1, eq. 10) from this
//! analysis without stating the formula. Here, the range method of single-factor experiments:
//! `S_i = (max_L f_i − min_L f_i)/f̄_i + (max_L T_i − min_L T_i)/T̄_i` (relative ranges of peak
//! frequency `f` and peak magnitude `T` over the levels, bars are means over the levels) and
//! `w_i = S_i / Σ_j S_j`.

use super::evaluate::Evaluator;
use super::param::Param;
use super::shard::Shard;
use super::sweep::evaluate_point;
use crate::error::{Error, Result};
use crate::model::Model;
use rayon::prelude::*;
use std::io::Write;

/// One (parameter, level) point.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Global point index: `parameter index × levels + level index`.
    pub point: usize,
    /// Parameter spec.
    pub param: String,
    /// Level in % of the model's value.
    pub level_pct: f64,
    /// Parameter value at this level.
    pub value: f64,
    /// Peak frequency in Hz.
    pub peak_freq_hz: f64,
    /// Peak magnitude in the response's unit.
    pub peak_mag: f64,
}

/// Runs the points of `shard` (see [`Shard`]) in parallel; rows in point order.
pub fn run(
    model: &Model,
    params: &[Param],
    levels_pct: &[f64],
    response: &str,
    freq_hz: &[f64],
    shard: Shard,
) -> Result<Vec<Row>> {
    if let Some(l) = levels_pct.iter().find(|l| !(l.is_finite() && **l > -100.0)) {
        return Err(Error::parameter(
            "--levels",
            format!("{l} %: expected > −100 %"),
        ));
    }
    let base = Evaluator::new(model.system(), response, freq_hz)?;
    let nl = levels_pct.len();
    shard
        .points(params.len() * nl)
        .into_par_iter()
        .map_init(
            || (base.clone(), model.clone()),
            |(ev, m), point| {
                let (p, l) = (&params[point / nl], levels_pct[point % nl]);
                let value = p.get(model)? * (1.0 + l / 100.0);
                let (_, peak) =
                    evaluate_point(model, m, ev, std::slice::from_ref(p), &[value], freq_hz)?;
                Ok(Row {
                    point,
                    param: p.spec.clone(),
                    level_pct: l,
                    value,
                    peak_freq_hz: peak.freq_hz,
                    peak_mag: peak.value,
                })
            },
        )
        .collect()
}

/// Per-parameter summary: relative ranges of peak frequency and magnitude (in %) and the weight.
#[derive(Debug, Clone, PartialEq)]
pub struct Influence {
    /// Parameter spec.
    pub param: String,
    /// `(max − min)/mean` of the peak frequency over the levels, in %.
    pub freq_range_pct: f64,
    /// `(max − min)/mean` of the peak magnitude over the levels, in %.
    pub mag_range_pct: f64,
    /// Normalised influence weight `w_i` (sums to 1).
    pub weight: f64,
}

/// Influence weights from complete rows (all levels of every parameter), in parameter order.
pub fn influence(rows: &[Row]) -> Vec<Influence> {
    let mut names: Vec<&str> = Vec::new();
    for r in rows {
        if !names.contains(&r.param.as_str()) {
            names.push(&r.param);
        }
    }
    let rel = |v: Vec<f64>| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(*x), b.max(*x))
            });
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        100.0 * (hi - lo) / mean
    };
    let mut out: Vec<Influence> = names
        .iter()
        .map(|n| {
            let mine = rows.iter().filter(|r| r.param == *n);
            Influence {
                param: n.to_string(),
                freq_range_pct: rel(mine.clone().map(|r| r.peak_freq_hz).collect()),
                mag_range_pct: rel(mine.map(|r| r.peak_mag).collect()),
                weight: 0.0,
            }
        })
        .collect();
    let total: f64 = out.iter().map(|i| i.freq_range_pct + i.mag_range_pct).sum();
    for i in &mut out {
        i.weight = if total > 0.0 {
            (i.freq_range_pct + i.mag_range_pct) / total
        } else {
            0.0
        };
    }
    out
}

/// Writes `point,param,level_pct,value,peak_freq_hz,peak_mag` (mergeable across shards).
pub fn write(rows: &[Row], w: &mut dyn Write) -> std::io::Result<()> {
    writeln!(w, "point,param,level_pct,value,peak_freq_hz,peak_mag")?;
    for r in rows {
        writeln!(
            w,
            "{},{},{},{},{},{}",
            r.point, r.param, r.level_pct, r.value, r.peak_freq_hz, r.peak_mag
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;
    use crate::response::frf;

    #[test]
    fn stiffer_cushion_raises_the_peak_and_weights_sum_to_one() {
        let model = catalog::resolve("seed001-full").unwrap();
        let params: Vec<Param> = ["link.cushion.k", "link.cushion.c", "mass.head.m"]
            .iter()
            .map(|p| Param::parse(p, &model).unwrap())
            .collect();
        let f = frf::grid(0.5, 15.0, 600, false).unwrap();
        let rows = run(
            &model,
            &params,
            &[-30.0, 0.0, 30.0],
            "t_head",
            &f,
            Shard::default(),
        )
        .unwrap();
        assert_eq!(rows.len(), 9);
        // A stiffer single-DOF-like support raises the resonance (f ∝ √k).
        assert!(
            rows[2].peak_freq_hz > rows[1].peak_freq_hz
                && rows[1].peak_freq_hz > rows[0].peak_freq_hz
        );
        // More damping lowers the peak.
        assert!(rows[5].peak_mag < rows[3].peak_mag);
        let inf = influence(&rows);
        assert!((inf.iter().map(|i| i.weight).sum::<f64>() - 1.0).abs() < 1e-12);
    }
}
