//! Whether an acceleration channel's samples look like another unit than the m/s² they are read in.
//!
//! A DC-coupled accelerometer records gravity: its mean is 1 g whatever the vibration, so the mean
//! tells the unit — ≈ 9.81 in m/s², ≈ 1.0 in g, ≈ 1000 in mg — when the vibration around it is
//! small against 1 g (whole-body vibration stays below 0.5 g r.m.s.; ISO 2631-1 Annex C ends at
//! 2 m/s²). Data in g read as m/s² make every figure 9.81 × too small and the comfort class two or
//! three classes too good, so [`refuse_ambiguous`] makes it an error where no unit was declared:
//! one `--units` settles it, while a warning printed after a confident verdict is read too late.

use crate::error::{Error, Result};
use crate::io::input::{Input, STANDARD_GRAVITY};
use std::fmt;

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
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt())
}

/// Refuses a measurement whose acceleration channel had no declared unit (read as m/s²) and whose
/// samples look like g or mg with gravity ([`looks_like`]): the error names the file, the channel,
/// its mean and the two ways to settle it.
pub fn refuse_ambiguous(input: &Input) -> Result<()> {
    let s = &input.signals;
    for name in input.undeclared.iter().filter(|n| n.starts_with("a_")) {
        let Some(x) = s.get(name) else { continue };
        let (mean, ac) = mean_and_fluctuation(x);
        if let Some(like) = looks_like(mean, ac) {
            return Err(Error::data(
                &s.source,
                None,
                format!(
                    "`{name}` has no declared unit and its mean {mean:.3} with fluctuation \
                     {ac:.3} looks like {like} read as m/s² (every figure would be {:.4} × the \
                     true one): give --units {name}={} if so, or --units {name}=m/s2 if the \
                     samples are m/s²",
                    1.0 / like.factor(),
                    like.unit()
                ),
            ));
        }
    }
    Ok(())
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
