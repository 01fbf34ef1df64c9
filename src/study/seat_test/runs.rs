//! ISO 10326-1 clause 10.2.1: the three consecutive runs whose values lie within ±5 % of their
//! arithmetic mean, and that mean (the rule as the research notes give it [S]: the clause was read
//! second-hand, in an open-source implementation's clause-numbered docstrings).

/// Runs that make one test (clause 10.2.1).
pub const RUNS: usize = 3;

/// Largest allowed deviation of a run from the mean of its test, a fraction (clause 10.2.1).
pub const AGREEMENT: f64 = 0.05;

/// Arithmetic mean.
pub fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len().max(1) as f64
}

/// Largest |x_i − x̄|/x̄ of `x`.
pub fn spread(x: &[f64]) -> f64 {
    let m = mean(x);
    x.iter().map(|v| (v - m).abs() / m).fold(0.0, f64::max)
}

/// Start of the first [`RUNS`] consecutive values that all lie within ±[`AGREEMENT`] of their
/// mean (a value on the edge is inside: 10⁻¹² of slack for rounding), or `None`.
pub fn agreeing_window(values: &[f64]) -> Option<usize> {
    (0..=values.len().saturating_sub(RUNS))
        .take_while(|&i| i + RUNS <= values.len())
        .find(|&i| spread(&values[i..i + RUNS]) <= AGREEMENT * (1.0 + 1e-12))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_agreeing_triple_is_found() {
        // 1.00, 1.10, 0.90: mean 1.0, ±10 %: no. 1.10, 0.90, 1.0 likewise; 0.9, 1.0, 0.95: mean
        // 0.95, spread 0.05/0.95 = 5.3 %: no; 1.0, 0.95, 0.97: mean 0.9733, spread 2.7 %: yes.
        let v = [1.0, 1.10, 0.90, 1.0, 0.95, 0.97];
        assert_eq!(agreeing_window(&v), Some(3));
        assert_eq!(agreeing_window(&[1.0, 1.0]), None);
        assert_eq!(agreeing_window(&[1.05, 1.0, 0.95]), Some(0));
        assert!((spread(&[1.0, 2.0, 3.0]) - 0.5).abs() < 1e-15);
    }
}
