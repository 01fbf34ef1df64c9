//! The replay refinement: an amplitude-dependent law fitted through its statistical
//! linearisation, refined so that its replayed best linear approximation matches the measured H1
//! (docs/gap.md §6.2).

use super::*;

/// Iterations of the replay refinement ([`refine_by_replay`]): each evaluates one time-domain
/// replay per training run and parameter, about 0.1 s each at 120 s and 500 Hz.
const REFINE_ITERATIONS: usize = 4;

/// The effect parameters of the fit `u` of `cands` on `train` refined so that the model's
/// replayed best linear approximation ([`crate::diagnosis::replay::responses`]) matches the measured H1,
/// the base parameters held: the law was fitted through its statistical linearisation
/// ([`predict::predict`]), which matches the response's second moments for a Gaussian input,
/// not the H1 a run measures of a nonlinear structure, so the law's strength comes out biased
/// (docs/gap.md §6.2). Levenberg–Marquardt from the linearised fit's values, at most
/// [`REFINE_ITERATIONS`] iterations; a structural choice stays pinned.
///
/// With `restart` (the linearised law leaves the check run far above the noise), a law parameter
/// the linearised fit left on its bound is a sign the linearisation could not place the law
/// inside its range (a strong one-sided stop is far from Gaussian: its equivalent
/// stiffness k·P(rise > slack) keeps asking for a stiffer, slacker strap than the replayed one
/// needs). Then those parameters' own starting values (their Cartesian product, the other
/// parameters at their fitted values) are replayed once per point, and the refinement also runs
/// from the point of lowest cost; the lower of the two refined fits is kept.
pub(in crate::diagnosis) fn refine_by_replay(
    base: &Base,
    cands: &[Candidate],
    u: &[f64],
    train: &[RunSpectra],
    restart: bool,
) -> Result<Vec<f64>> {
    let nb = base.params.len();
    let rms_ref = reference_rms(train);
    let (lo, hi) = bounds(base, cands);
    let v0 = build(base, cands, u, rms_ref)?;
    // The paths a replay does not yield (a backrest force) keep the linearised prediction.
    let fallback: Vec<Vec<Vec<num_complex::Complex64>>> = train
        .iter()
        .map(|run| Ok(predict::predict(&v0, run)?.as_estimated))
        .collect::<Result<_>>()?;
    let f = |u: &[f64]| -> Result<Vec<f64>> {
        let v = build(base, cands, u, rms_ref)?;
        let mut r = Vec::new();
        for (run, fb) in train.iter().zip(&fallback) {
            score::run_residuals(
                run,
                &crate::diagnosis::replay::responses(&v, run, fb)?,
                &mut r,
            );
        }
        Ok(r)
    };
    let eff = effect_params(cands).concat();
    let pinned: Vec<usize> = (0..nb)
        .chain((nb..u.len()).filter(|&i| eff[i - nb].discrete))
        .collect();
    let mut starts = vec![u.to_vec()];
    let on_bound: Vec<(usize, &Param)> = (nb..u.len())
        .filter(|&i| restart && !pinned.contains(&i) && near_bound(u[i], lo[i], hi[i]))
        .map(|i| (i, &eff[i - nb]))
        .collect();
    if !on_bound.is_empty() {
        let cost = |s: &Vec<f64>| -> Result<f64> { Ok(fit::cost(&f(s)?)) };
        // The grid over the parameters on their bounds; the others keep their fitted values.
        let grid = start_grid(u, &on_bound);
        let costs: Vec<f64> = grid.par_iter().map(cost).collect::<Result<_>>()?;
        let best = (0..grid.len()).min_by(|&a, &b| costs[a].total_cmp(&costs[b]));
        starts.extend(best.map(|k| grid[k].clone()));
    }
    let fits: Vec<fit::Fit> = starts
        .par_iter()
        .map(|s| {
            multistart(
                &f,
                std::slice::from_ref(s),
                &lo,
                &hi,
                &pinned,
                REFINE_ITERATIONS,
            )
        })
        .collect::<Result<_>>()?;
    Ok(fits
        .into_iter()
        .min_by(|a, b| a.cost.total_cmp(&b.cost))
        .expect("at least one start")
        .u)
}
