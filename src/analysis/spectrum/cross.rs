//! Cross-spectral densities of a channel pair and the transfer-function estimates H1, H2 with the
//! ordinary coherence (Bendat & Piersol §9.2).

use super::Welch;
use crate::error::{Error, Result};
use num_complex::Complex64;
use std::ops::Range;

/// Auto- and cross-spectral densities of a channel pair x → y (one-sided, per Hz).
#[derive(Debug, Clone, PartialEq)]
pub struct CrossSpectra {
    /// Bin frequencies in Hz.
    pub freq_hz: Vec<f64>,
    /// G_xx in (unit x)²/Hz.
    pub gxx: Vec<f64>,
    /// G_yy in (unit y)²/Hz.
    pub gyy: Vec<f64>,
    /// G_xy = 2 E[X* Y]/(fs Σw²) in (unit x)(unit y)/Hz.
    pub gxy: Vec<Complex64>,
    /// Number of averaged segments.
    pub segments: usize,
}

impl CrossSpectra {
    /// H1 = G_xy / G_xx: unbiased by noise on the output y (Bendat & Piersol eq. 9.64).
    pub fn h1(&self) -> Vec<Complex64> {
        self.gxy
            .iter()
            .zip(&self.gxx)
            .map(|(g, &xx)| {
                if xx > 0.0 {
                    g / xx
                } else {
                    Complex64::new(f64::NAN, 0.0)
                }
            })
            .collect()
    }

    /// H2 = G_yy / G_yx: unbiased by noise on the input x (Bendat & Piersol eq. 9.65).
    pub fn h2(&self) -> Vec<Complex64> {
        self.gxy
            .iter()
            .zip(&self.gyy)
            .map(|(g, &yy)| {
                let gyx = g.conj();
                if gyx.norm() > 0.0 {
                    yy / gyx
                } else {
                    Complex64::new(f64::NAN, 0.0)
                }
            })
            .collect()
    }

    /// Ordinary coherence γ² = |G_xy|² / (G_xx G_yy) in [0, 1] (Bendat & Piersol eq. 9.66).
    pub fn coherence(&self) -> Vec<f64> {
        self.gxy
            .iter()
            .zip(self.gxx.iter().zip(&self.gyy))
            .map(|(g, (&xx, &yy))| {
                let d = xx * yy;
                if d > 0.0 {
                    (g.norm_sqr() / d).min(1.0)
                } else {
                    0.0
                }
            })
            .collect()
    }
}

impl Welch {
    /// Whether segment `s` overlaps none of the sample ranges `excluded`.
    fn clean(&self, s: usize, excluded: &[Range<usize>]) -> bool {
        let (start, end) = (s * self.step, s * self.step + self.n);
        !excluded.iter().any(|r| r.start < end && start < r.end)
    }

    /// The number of segments of a record of `len` samples that overlap none of `excluded`, and
    /// of all its segments.
    pub fn clean_segments(&self, len: usize, excluded: &[Range<usize>]) -> Result<(usize, usize)> {
        let total = self.segment_count(len)?;
        Ok((
            (0..total).filter(|&s| self.clean(s, excluded)).count(),
            total,
        ))
    }

    /// Auto- and cross-spectral densities of the pair x → y (same length, same segments).
    pub fn cross(&mut self, x: &[f64], y: &[f64]) -> Result<CrossSpectra> {
        self.cross_excluding(x, y, &[])
    }

    /// [`Welch::cross`] over the segments that overlap none of the sample ranges `excluded`
    /// (stretches where an acquisition fault left no data, [`crate::analysis::faults`]): the
    /// average of the clean segments is the same unbiased estimate with fewer averages.
    pub fn cross_excluding(
        &mut self,
        x: &[f64],
        y: &[f64],
        excluded: &[Range<usize>],
    ) -> Result<CrossSpectra> {
        if x.len() != y.len() {
            return Err(Error::parameter(
                "cross spectrum",
                format!(
                    "channels have {} and {} samples; expected equal lengths",
                    x.len(),
                    y.len()
                ),
            ));
        }
        let segments = self.segment_count(x.len())?;
        let m = self.n / 2 + 1;
        let (mut gxx, mut gyy, mut gxy) =
            (vec![0.0; m], vec![0.0; m], vec![Complex64::default(); m]);
        let mut count = 0;
        for s in 0..segments {
            let start = s * self.step;
            if !self.clean(s, excluded) {
                continue;
            }
            count += 1;
            self.transform(&x[start..start + self.n], false);
            self.transform(&y[start..start + self.n], true);
            for k in 0..m {
                let (a, b) = (self.out_x[k], self.out_y[k]);
                gxx[k] += a.norm_sqr();
                gyy[k] += b.norm_sqr();
                gxy[k] += a.conj() * b;
            }
        }
        if count == 0 {
            return Err(Error::parameter(
                "cross spectrum",
                format!("all {segments} segments overlap excluded samples; expected a clean one"),
            ));
        }
        for k in 0..m {
            let c = self.one_sided_scale(k) / count as f64;
            gxx[k] *= c;
            gyy[k] *= c;
            gxy[k] *= c;
        }
        Ok(CrossSpectra {
            freq_hz: self.frequencies(),
            gxx,
            gyy,
            gxy,
            segments: count,
        })
    }
}
