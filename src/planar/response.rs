//! Frequency responses of the planar model to a vertical base acceleration (paper 000 §5):
//! `X(ω) = −(K − ω²M + iωC)⁻¹·M·r_z` per unit base acceleration, and for a body point with
//! Jacobian `J` the absolute acceleration `−ω²·J·X + (0, 1)`.
//!
//! Responses (names of the `wbv frf` columns):
//! - `seat` — vertical in-line (v-v) seat transmissibility: vertical acceleration of the seat point
//!   (the body on the cushion under the ischial tuberosities, where a seat pad measures) / base;
//! - `seat_x` — fore-and-aft cross-axis (v-h) seat transmissibility: its fore-and-aft acceleration
//!   / vertical base acceleration;
//! - `head_z`, `head_x` — base-to-head (centre of mass) vertical and fore-and-aft transmissibility,
//!   and `stht` = `head_z / seat`;
//! - `apms_z`, `apms_x` — apparent masses in kg: the vertical and fore-and-aft force the seat
//!   (cushion, backrest, footrest) exerts on the body / vertical base acceleration, computed as the
//!   body's momentum rate `Σ m_s·A_s`;
//! - `t_<coordinate>` — each generalized coordinate's absolute acceleration / base (1, or rad/m
//!   for pitches).

use super::Planar;
use crate::error::{Error, Result};
use crate::response::frf::{FrfSet, Response};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;
use std::f64::consts::PI;

/// Displacements per unit vertical base acceleration at `f` Hz.
pub fn solve(p: &Planar, f: f64) -> Result<DVector<Complex64>> {
    let w = 2.0 * PI * f;
    let l = &p.linear;
    let d = DMatrix::from_fn(l.m.nrows(), l.m.ncols(), |i, j| {
        Complex64::new(l.k[(i, j)] - w * w * l.m[(i, j)], w * l.c[(i, j)])
    });
    let rhs = (-(&l.m * &l.r_z)).map(|v| Complex64::new(v, 0.0));
    d.lu().solve(&rhs).ok_or_else(|| {
        Error::parameter(
            "frequency",
            format!("the planar dynamic stiffness is singular at {f} Hz"),
        )
    })
}

/// Jacobian rows `[x; z]` at equilibrium of the centre of mass of each segment.
fn com_jacobians(p: &Planar) -> Vec<[Vec<f64>; 2]> {
    let pos = &p.spec.posture;
    let pl = pos.place(&p.equilibrium.q);
    pos.segments
        .iter()
        .enumerate()
        .map(|(s, seg)| pos.jacobian(&pl, s, seg.com))
        .collect()
}

fn dot(j: &[f64], x: &DVector<Complex64>) -> Complex64 {
    j.iter().zip(x.iter()).map(|(a, b)| *a * b).sum()
}

/// Every response on the grid `freq_hz`.
pub fn compute(p: &Planar, names: &[String], freq_hz: &[f64]) -> Result<FrfSet> {
    let jc = com_jacobians(p);
    let masses: Vec<f64> = p.spec.posture.segments.iter().map(|s| s.m).collect();
    let n = p.spec.posture.dof();
    let mut cols: Vec<(String, &'static str, Vec<Complex64>)> = Vec::new();
    let mut push = |k: usize, name: &str, unit: &'static str, v: Complex64| {
        if cols.len() <= k {
            cols.push((name.to_string(), unit, Vec::with_capacity(freq_hz.len())));
        }
        cols[k].2.push(v);
    };
    for &f in freq_hz {
        let x = solve(p, f)?;
        let w2 = (2.0 * PI * f).powi(2);
        let rz = &p.linear.r_z;
        let abs = |i: usize| -w2 * x[i] + rz[i];
        let seat = abs(1);
        let mut k = 0;
        let mut next = |name: &str, unit, v| {
            push(k, name, unit, v);
            k += 1;
        };
        if let Some(h) = p.spec.head {
            let hz = -w2 * dot(&jc[h][1], &x) + 1.0;
            next("stht", "1", hz / seat);
        }
        next("seat", "1", seat);
        next("seat_x", "1", abs(0));
        if let Some(h) = p.spec.head {
            next("head_z", "1", -w2 * dot(&jc[h][1], &x) + 1.0);
            next("head_x", "1", -w2 * dot(&jc[h][0], &x));
        }
        let (mut fx, mut fz) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
        for (j, m) in jc.iter().zip(&masses) {
            fx += *m * (-w2 * dot(&j[0], &x));
            fz += *m * (-w2 * dot(&j[1], &x) + 1.0);
        }
        next("apms_z", "kg", fz);
        next("apms_x", "kg", fx);
        for (i, name) in names.iter().enumerate().take(n) {
            let unit = if i < 2 { "1" } else { "rad/m" };
            next(&format!("t_{name}"), unit, abs(i));
        }
    }
    Ok(FrfSet {
        freq_hz: freq_hz.to_vec(),
        responses: cols
            .into_iter()
            .map(|(name, unit, values)| Response { name, unit, values })
            .collect(),
    })
}
