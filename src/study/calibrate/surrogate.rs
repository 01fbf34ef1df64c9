//! The polynomial surrogate of paper 000 §5.2: each parameter's effect on the response peak is
//! sampled alone (others at the starting model) and fitted by a cubic (eq. 9,
//! `F = m·x³ + n·x² + p·x + q`, least squares, `x` the normalised log-scaled parameter); the
//! cubics are combined (eq. 10) and the squared error to the measured peak (eq. 11) is minimised by
//! the GA.
//!
//! Two deliberate differences from the paper, both stated in the report:
//! - eq. 10 weights `w_i` summing to 1 would shrink each parameter's effect by `w_i`; here the
//!   first-order additive form `F = F₀ + Σ_i (f_i(x_i) − F₀)` is used (all `w_i = 1` on deviations);
//! - the peak *frequency* is fitted next to the peak magnitude (relative errors), since one scalar
//!   cannot identify more than one parameter.
//!
//! The surrogate ignores interactions, so its optimum is only as good as that assumption; the
//! report gives the full-model goodness at the surrogate's optimum.

use super::ga;
use super::objective::Problem;
use crate::error::{Error, Result};
use crate::response::peak::global_peak;
use crate::study::evaluate::Evaluator;
use crate::study::param::apply;
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

/// Least-squares cubic `[m, n, p, q]` through `(x, y)` (eq. 9) and its coefficient of determination.
pub fn fit_cubic(x: &[f64], y: &[f64]) -> Result<([f64; 4], f64)> {
    if x.len() < 4 || x.len() != y.len() {
        return Err(Error::parameter(
            "surrogate",
            "a cubic needs at least 4 samples",
        ));
    }
    let a = DMatrix::from_fn(x.len(), 4, |i, j| x[i].powi(3 - j as i32));
    let b = DVector::from_column_slice(y);
    let sol = a
        .clone()
        .svd(true, true)
        .solve(&b, 1e-12)
        .map_err(|e| Error::parameter("surrogate", e.to_string()))?;
    let c = [sol[0], sol[1], sol[2], sol[3]];
    let mean = y.iter().sum::<f64>() / y.len() as f64;
    let ss_tot: f64 = y.iter().map(|v| (v - mean).powi(2)).sum();
    let ss_res: f64 = (&a * &sol - &b).iter().map(|v| v * v).sum();
    Ok((
        c,
        if ss_tot > 0.0 {
            1.0 - ss_res / ss_tot
        } else {
            1.0
        },
    ))
}

fn cubic(c: &[f64; 4], x: f64) -> f64 {
    ((c[0] * x + c[1]) * x + c[2]) * x + c[3]
}

/// Peak magnitude and frequency of `problem`'s response at physical values `p`.
fn peak_features(
    problem: &Problem,
    ev: &mut Evaluator,
    h: &mut [Complex64],
    p: &[f64],
) -> Result<[f64; 2]> {
    let mut m = problem.model.clone();
    apply(&mut m, &problem.params, p)?;
    ev.eval(m.system(), h)?;
    let mag: Vec<f64> = h.iter().map(|v| v.norm()).collect();
    let pk = global_peak(&problem.target.freq_hz, &mag)
        .ok_or_else(|| Error::parameter("surrogate", "no peak"))?;
    Ok([pk.value, pk.freq_hz])
}

/// Fits the surrogate with `levels` samples per parameter and minimises it with the GA; returns the
/// physical optimum and the number of full-model evaluations.
pub fn fit(problem: &Problem, s: ga::Settings, levels: usize) -> Result<(Vec<f64>, usize)> {
    let t = &problem.target;
    let meas = global_peak(&t.freq_hz, &t.mag)
        .ok_or_else(|| Error::parameter("--target", "no peak in the target"))?;
    let meas = [meas.value, meas.freq_hz];
    let mut ev = Evaluator::new(problem.model.system(), &problem.response, &t.freq_hz)?;
    let mut h = vec![Complex64::default(); t.freq_hz.len()];
    let u0 = problem.to_unit(&problem.start()?);
    let f0 = peak_features(problem, &mut ev, &mut h, &problem.to_physical(&u0))?;
    let xs: Vec<f64> = (0..levels)
        .map(|i| i as f64 / (levels - 1).max(1) as f64)
        .collect();
    let mut cubics = Vec::new();
    for i in 0..u0.len() {
        let mut ys = [Vec::new(), Vec::new()];
        for &x in &xs {
            let mut u = u0.clone();
            u[i] = x;
            let f = peak_features(problem, &mut ev, &mut h, &problem.to_physical(&u))?;
            ys[0].push(f[0]);
            ys[1].push(f[1]);
        }
        cubics.push([fit_cubic(&xs, &ys[0])?.0, fit_cubic(&xs, &ys[1])?.0]);
    }
    let se = |_: &mut (), u: &[f64]| -> f64 {
        (0..2)
            .map(|k| {
                let pred = f0[k]
                    + cubics
                        .iter()
                        .zip(u)
                        .map(|(c, x)| cubic(&c[k], *x) - f0[k])
                        .sum::<f64>();
                ((pred - meas[k]) / meas[k]).powi(2)
            })
            .sum()
    };
    let out = ga::minimise(u0.len(), Some(&u0), s, || (), se);
    Ok((problem.to_physical(&out.u), 1 + u0.len() * levels))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_fit_is_exact_on_a_cubic() {
        let x: Vec<f64> = (0..7).map(|i| i as f64 / 6.0).collect();
        let y: Vec<f64> = x
            .iter()
            .map(|x| 2.0 * x * x * x - x * x + 0.5 * x + 3.0)
            .collect();
        let (c, r2) = fit_cubic(&x, &y).unwrap();
        for (a, b) in c.iter().zip([2.0, -1.0, 0.5, 3.0]) {
            assert!((a - b).abs() < 1e-9, "{c:?}");
        }
        assert!((r2 - 1.0).abs() < 1e-12);
    }
}
