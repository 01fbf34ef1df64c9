//! Seat effective amplitude transmissibility (ISO 10326-1:2016 10.2.2; paper 000 eq. 14):
//! SEAT % = 100 · a_w(seat) / a_w(base), both weighted with the same weighting. Below 100 % the
//! seat attenuates the weighted vibration.
//!
//! For a stationary response the weighted r.m.s. comes from its one-sided PSD by Parseval
//! (ISO 2631-1:1997 eq. 1 with the weighting W of Annex A): `a_w² = ∫ |W(f)|² S(f) df`, here on
//! quadrature nodes f_j with weights q_j (Hz: a Welch bin's Δf, or a Simpson factor),
//! `a_w² = Σ_j q_j·|W(f_j)|²·S_j` ([`Stationary`]). A linear response to a stationary input of
//! PSD G has `S_j = |H_j|²·G_j`; where the nodes' measure is the input's mean square at each
//! node (`q_j·G_j`, a line's `A²/2`), its terms are `|W(f_j)|²·(q_j·G_j)·|H_j|²`
//! ([`Stationary::gain_terms`]). The spectral studies (`study::spectral`) and the gap diagnosis's
//! predicted and measured seat (`diagnosis::gapmap`) both take a_w and SEAT from here.

use super::weighting::Weighting;
use num_complex::Complex64;

/// SEAT in percent from the weighted r.m.s. of seat and base (m/s²); `None` if the base is still.
pub fn seat_percent(a_w_seat: f64, a_w_base: f64) -> Option<f64> {
    (a_w_base > 0.0).then(|| 100.0 * a_w_seat / a_w_base)
}

/// A frequency weighting on the quadrature nodes of a one-sided spectrum: each node's factor
/// `w_j = |W(f_j)|²·q_j` (Hz), so that a stationary signal's weighted mean square is the sum of
/// its nodes' terms `w_j·S_j` (ISO 2631-1 eq. 1 by Parseval). Computed once, used for any number
/// of spectra on the same nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct Stationary {
    weights: Vec<f64>,
}

impl Stationary {
    /// The weighting `weighting` on nodes `(f_j Hz, q_j)`: q_j in Hz for [`Stationary::psd_terms`]
    /// and [`Stationary::response_terms`], the input's mean square at the node ((m/s²)²) for
    /// [`Stationary::gain_terms`].
    pub fn new(weighting: Weighting, nodes: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Stationary {
            weights: nodes
                .into_iter()
                .map(|(f, q)| weighting.magnitude(f).powi(2) * q)
                .collect(),
        }
    }

    /// Each node's term `w_j·S_j` of a signal of one-sided PSD `psd` on the nodes ((m/s²)²/Hz,
    /// terms in (m/s²)²): a measured spectrum.
    pub fn psd_terms<'a>(
        &'a self,
        psd: impl IntoIterator<Item = f64> + 'a,
    ) -> impl Iterator<Item = f64> + 'a {
        self.weights.iter().zip(psd).map(|(w, s)| w * s)
    }

    /// Each node's term `w_j·|H_j|²` of a linear response `h` (per unit input) when the nodes'
    /// measure q_j is the input's mean square at each node ((m/s²)²: `G_j·Δf_j` of a band, `A²/2`
    /// of a line), as a spectral study's quadrature of its excitation is: terms in (m/s²)².
    pub fn gain_terms<'a>(
        &'a self,
        h: impl IntoIterator<Item = Complex64> + 'a,
    ) -> impl Iterator<Item = f64> + 'a {
        self.weights.iter().zip(h).map(|(w, h)| w * h.norm_sqr())
    }

    /// Each node's term of a linear response `h` (per unit input) to a stationary input of PSD
    /// `input` ((m/s²)²/Hz): `(w_j·|H_j|²)·G_j / b_j`. `b_j` is the share of the input's PSD that
    /// its coherent motion is where `h` was estimated against a noisy input, as H1 is (`H·b`:
    /// `|H·b|²·G/b = |H|²·b·G`, the response to the motion alone); 1 where `coherent` ends or is
    /// empty (an exact input).
    pub fn response_terms<'a>(
        &'a self,
        h: impl IntoIterator<Item = Complex64> + 'a,
        input: impl IntoIterator<Item = f64> + 'a,
        coherent: &'a [f64],
    ) -> impl Iterator<Item = f64> + 'a {
        self.weights
            .iter()
            .zip(h.into_iter().zip(input))
            .enumerate()
            .map(|(j, (w, (h, g)))| w * h.norm_sqr() * g / coherent.get(j).copied().unwrap_or(1.0))
    }
}

/// The weighted r.m.s. (m/s²) of the terms of [`Stationary::psd_terms`] or
/// [`Stationary::response_terms`]: `a_w = √(Σ_j terms_j)`, summed in node order.
pub fn weighted_rms(terms: impl IntoIterator<Item = f64>) -> f64 {
    terms.into_iter().fold(0.0, |a, t| a + t).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weighted_rms_is_the_parseval_sum_over_the_nodes() {
        // ISO 2631-1 eq. 1 by Parseval on two nodes: a_w² = Σ |W(f_j)|²·q_j·S_j.
        let (w4, w8) = (Weighting::Wk.magnitude(4.0), Weighting::Wk.magnitude(8.0));
        let s = Stationary::new(Weighting::Wk, [(4.0, 0.5), (8.0, 0.25)]);
        let a = weighted_rms(s.psd_terms([2.0, 3.0]));
        let expect = (w4 * w4 * 0.5 * 2.0 + w8 * w8 * 0.25 * 3.0).sqrt();
        assert!((a / expect - 1.0).abs() < 1e-15, "{a} vs {expect}");
        // A response H to that input: S = |H|²·G; a noisy input's H1 carries the motion's share
        // b of the input PSD, H·b, and the response to the motion alone is |H·b|²·G/b = |H|²·b·G.
        let h = [Complex64::new(0.0, 0.5), Complex64::new(0.3, -0.4)];
        let b = [0.8, 0.5];
        let biased = h.iter().zip(&b).map(|(h, b)| h * b);
        let r = weighted_rms(s.response_terms(biased, [2.0, 3.0], &b));
        let expect = (w4 * w4 * 0.5 * 0.25 * 0.8 * 2.0 + w8 * w8 * 0.25 * 0.25 * 0.5 * 3.0).sqrt();
        assert!((r / expect - 1.0).abs() < 1e-15, "{r} vs {expect}");
        // The same response with the input's mean square per node as the nodes' measure.
        let per_node = Stationary::new(Weighting::Wk, [(4.0, 0.5 * 2.0), (8.0, 0.25 * 3.0)]);
        let g = weighted_rms(per_node.gain_terms(h));
        let expect = (w4 * w4 * 0.5 * 2.0 * 0.25 + w8 * w8 * 0.25 * 3.0 * 0.25).sqrt();
        assert!((g / expect - 1.0).abs() < 1e-15, "{g} vs {expect}");
        assert_eq!(seat_percent(r, a), Some(100.0 * r / a));
        assert_eq!(seat_percent(r, 0.0), None);
    }
}
