//! Whether an acceleration channel's samples look like another unit than the m/s² they are read in.
//!
//! A DC-coupled accelerometer records gravity: its mean is 1 g whatever the vibration, so the mean
//! tells the unit — ≈ 9.81 in m/s², ≈ 1.0 in g, ≈ 1000 in mg — when the vibration around it is
//! small against 1 g (whole-body vibration stays below 0.5 g r.m.s.; ISO 2631-1 Annex C ends at
//! 2 m/s²). Data in g read as m/s² make every figure 9.81 × too small and the comfort class two or
//! three classes too good. Where no unit was declared, such a channel gets a warning that stands
//! first in the text, the JSON (`warnings`, and `unit_doubt` beside the channel's figures) and the
//! HTML report, and the verdicts that use it are marked doubtful
//! ([`crate::analysis::Report::verdict_doubtful`]). Not an error: m/s² data with a 1 m/s² sensor
//! bias look the same, and a report that says what it doubts is more use than none; `--units`
//! (either way) settles it and removes the warning.

use std::fmt;

/// Standard gravity g_n in m/s² (ISO 80000-3, CGPM 1901), for files in g.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// A unit an acceleration channel's mean points to, read as m/s².
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LooksLike {
    /// Mean within 10 % of 1.0, fluctuation below 0.5: g with gravity.
    GWithGravity,
    /// Mean within 10 % of 1000, fluctuation below 500: mg with gravity.
    MilliGWithGravity,
}

impl LooksLike {
    /// The unit the samples point to, as `--units` spells it.
    pub fn unit(self) -> &'static str {
        match self {
            LooksLike::GWithGravity => "g",
            LooksLike::MilliGWithGravity => "mg",
        }
    }

    /// Factor by which every figure read as m/s² is off.
    pub fn factor(self) -> f64 {
        match self {
            LooksLike::GWithGravity => STANDARD_GRAVITY,
            LooksLike::MilliGWithGravity => STANDARD_GRAVITY * 1e-3,
        }
    }
}

impl fmt::Display for LooksLike {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            LooksLike::GWithGravity => "g with gravity (1 g ≈ 1.0)",
            LooksLike::MilliGWithGravity => "mg with gravity (1 g ≈ 1000)",
        })
    }
}

/// The unit an acceleration channel with mean `mean` and r.m.s. fluctuation about it `ac` (both as
/// read, in m/s²) points to, if not m/s².
pub fn looks_like(mean: f64, ac: f64) -> Option<LooksLike> {
    let m = mean.abs();
    if (m - 1.0).abs() < 0.1 && ac < 0.5 {
        Some(LooksLike::GWithGravity)
    } else if (m - 1000.0).abs() < 100.0 && ac < 500.0 {
        Some(LooksLike::MilliGWithGravity)
    } else {
        None
    }
}

/// Mean and r.m.s. fluctuation about it of `x`.
pub fn mean_and_fluctuation(x: &[f64]) -> (f64, f64) {
    let n = x.len().max(1) as f64;
    let mean = x.iter().sum::<f64>() / n;
    // (v − mean)² as a product: what `powi(2)` computes, without its call.
    let var = x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    (mean, var.sqrt())
}

/// The statement beside every verdict that rests on an assumed unit: `names` (channels) had no
/// declared unit and were read as m/s², and a record in g read so is 9.81 × too low.
pub fn undeclared(names: &str) -> String {
    format!(
        "no unit was declared for {names}; data in g would read 9.81 × too low and the verdicts \
         be several classes or zones too mild: give --units (m/s2, g, mg or mm/s2, or \
         CHANNEL=UNIT)"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gravity_tells_the_unit() {
        assert_eq!(looks_like(1.0, 0.05), Some(LooksLike::GWithGravity));
        assert_eq!(looks_like(-0.98, 0.2), Some(LooksLike::GWithGravity));
        assert_eq!(looks_like(1003.0, 40.0), Some(LooksLike::MilliGWithGravity));
        // m/s² with gravity, and m/s² with a small offset against a strong vibration.
        assert_eq!(looks_like(9.81, 0.5), None);
        assert_eq!(looks_like(1.0, 0.9), None);
    }
}
