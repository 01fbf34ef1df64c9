//! The sample rate of time stamps that lie on a uniform grid.

use super::MAX_JITTER;
use crate::error::{Error, Result};

/// The sample rate of time stamps `t` (s) that lie on a uniform grid up to half their printed
/// resolution `res` plus [`MAX_JITTER`] of a step. The grid is the least-squares line through the
/// stamps; a rate within the stamps' resolution of a whole number of Hz is taken as that number
/// (loggers print rounded times of an integer rate). Errors name the line of the first stamp off
/// the grid.
pub(crate) fn fit_rate(
    t: &[f64],
    res: Option<&[f64]>,
    line_of: &dyn Fn(usize) -> Option<usize>,
    source: &str,
    name: &str,
) -> Result<f64> {
    let n = t.len();
    if n < 2 {
        return Err(Error::data(source, None, "fewer than two samples"));
    }
    for i in 1..n {
        if t[i] <= t[i - 1] || !t[i].is_finite() {
            return Err(Error::data(
                source,
                line_of(i),
                format!(
                    "`{name}`: time {} s does not increase (previous {} s)",
                    t[i],
                    t[i - 1]
                ),
            ));
        }
    }
    // A gap first: a step of more than 1.5 × the median one means the logger dropped samples, which
    // the least-squares grid below would report only as some stamp far off it.
    let mut steps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let mid = steps.len() / 2;
    let median = *steps.select_nth_unstable_by(mid, f64::total_cmp).1;
    if let Some(i) = (1..n).find(|&i| t[i] - t[i - 1] > 1.5 * median + half_step_res(res, i)) {
        let jump = t[i] - t[i - 1];
        return Err(Error::data(
            source,
            line_of(i),
            format!(
                "`{name}`: the time stamps jump from {} s to {} s, {:.0} steps of {median:.6e} s: a gap in the record (the logger dropped samples); split the file at the gap, or give --fs HZ --ignore-time to ignore the time stamps",
                t[i - 1],
                t[i],
                jump / median
            ),
        ));
    }
    // Least-squares t_i = a + b i, computed about the means for accuracy.
    let nf = n as f64;
    let im = (nf - 1.0) / 2.0;
    let tm = t.iter().sum::<f64>() / nf;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (i, &ti) in t.iter().enumerate() {
        let di = i as f64 - im;
        sxy += di * (ti - tm);
        sxx += di * di;
    }
    let dt_ls = sxy / sxx;
    let check = |dt: f64| match off_grid(t, res, dt) {
        Some(off) => Err(off),
        None => Ok(()),
    };
    // An integer rate first, when the stamps' typical resolution allows it over the whole run.
    let mut typical = res.map_or(0.0, |r| {
        let mut r = r.to_vec();
        r.sort_by(f64::total_cmp);
        r[r.len() / 2]
    });
    typical += 1e-9 * dt_ls;
    let whole = (1.0 / dt_ls).round();
    if whole >= 1.0 && (1.0 / whole - dt_ls).abs() * nf <= typical && check(1.0 / whole).is_ok() {
        return Ok(whole);
    }
    match check(dt_ls) {
        Ok(()) => Ok(1.0 / dt_ls),
        Err((i, ti, off)) => Err(Error::data(
            source,
            line_of(i),
            format!(
                "`{name}`: time {ti} s is {off:.3e} s off the uniform {:.6} Hz grid (more than \
                 its printed resolution and 1 % of the {dt_ls:.6e} s step): the sampling has \
                 jitter or a gap; resample the file, or give --fs HZ --ignore-time to ignore the time stamps",
                1.0 / dt_ls
            ),
        )),
    }
}

/// The first stamp of `t` (s) off the uniform grid of step `dt` (s) through the stamps' mean, as
/// `(index, stamp, offset)`: off by more than half its printed resolution `res` plus
/// [`MAX_JITTER`] of a step; None when every stamp lies on the grid.
fn off_grid(t: &[f64], res: Option<&[f64]>, dt: f64) -> Option<(usize, f64, f64)> {
    let nf = t.len() as f64;
    let im = (nf - 1.0) / 2.0;
    let tm = t.iter().sum::<f64>() / nf;
    let a = tm - dt * im;
    let half_res = |i: usize| res.map_or(0.0, |r| 0.5 * r[i]);
    t.iter().enumerate().find_map(|(i, &ti)| {
        let off = ti - (a + dt * i as f64);
        (off.abs() > half_res(i) + MAX_JITTER * dt + 1e-12 * ti.abs()).then_some((i, ti, off))
    })
}

/// Whether the time stamps `t` (s, printed to `res`) lie on the uniform grid of `fs` Hz: a rate
/// given by the user agrees with the file's stamps exactly when [`fit_rate`] would accept it as
/// their grid.
pub(crate) fn on_grid(t: &[f64], res: Option<&[f64]>, fs: f64) -> bool {
    t.len() < 2 || off_grid(t, res, 1.0 / fs).is_none()
}

/// The printed resolution of the stamps on either side of step `i` (a rounded time can make one
/// step look longer by up to that much).
fn half_step_res(res: Option<&[f64]>, i: usize) -> f64 {
    res.map_or(0.0, |r| r[i] + r[i - 1])
}
