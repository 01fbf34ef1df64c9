//! A linear model's integration step as a matrix.
//!
//! For a model without nonlinear laws, one step of either integrator is a linear map of the state
//! and of the step's base accelerations: `y₊ = Φ·y + Γ·u` with `y = [x, v, a, q, q̇]` ([`State`])
//! and `u = [a_base(t), …, a_base(t + dt)]` at the integrator's sub-points. Stepping the integrator
//! once from each unit state and each unit input gives the columns of `Φ` and `Γ` (each column is
//! the integrator's own arithmetic, so the recursion equals it to round-off), and a step then costs
//! one dense matrix–vector product instead of force evaluations, a triangular solve (Newmark) or
//! four stages (RK4). This is the discrete-time recursion `scipy.signal.lsim` and a hand-written
//! loop would run; `benches/simulate.rs` compares the two.

use super::{Integrator, State};
use crate::error::Result;
use crate::system::Dynamics;

/// Column length padded to a multiple of this, so the product runs on fixed-size arrays.
const LANES: usize = 4;
/// Largest padded column length with a fixed-size kernel; longer ones use the general loop.
const MAX_FIXED: usize = 32;

/// `out = Σ_j cols_j · s_j` over columns of length `P` (a compile-time size, so the loop is
/// unrolled and vectorised), `s` the concatenation of `parts` (read in place, not copied).
/// Always inlined, so the AVX2 wrapper compiles it with AVX2.
#[inline(always)]
fn product<const P: usize>(cols: &[f64], parts: &[&[f64]], out: &mut [f64]) {
    let mut acc = [0.0; P];
    let mut start = 0;
    for part in parts {
        let block = &cols[start * P..(start + part.len()) * P];
        for (col, s) in block.chunks_exact(P).zip(*part) {
            for (a, c) in acc.iter_mut().zip(col) {
                *a += c * s;
            }
        }
        start += part.len();
    }
    out[..P].copy_from_slice(&acc);
}

/// [`product`] compiled for AVX2 (four `f64` per instruction instead of two). The arithmetic is
/// the same multiplications and additions in the same order (no fused multiply–add), so the
/// results are bit-identical to the baseline build.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn product_avx2<const P: usize>(cols: &[f64], parts: &[&[f64]], out: &mut [f64]) {
    product::<P>(cols, parts, out)
}

/// [`product`] with the widest vectors this processor has.
#[inline]
fn product_best<const P: usize>(avx2: bool, cols: &[f64], parts: &[&[f64]], out: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if avx2 {
        // SAFETY: `avx2` is true only when the processor reports AVX2 (`LinearStep::probe`).
        return unsafe { product_avx2::<P>(cols, parts, out) };
    }
    let _ = avx2;
    product::<P>(cols, parts, out)
}

/// The same for any column length `p`.
fn product_any(p: usize, cols: &[f64], parts: &[&[f64]], out: &mut [f64]) {
    out.fill(0.0);
    for (col, s) in cols
        .chunks_exact(p)
        .zip(parts.iter().flat_map(|p| p.iter()))
    {
        for (a, c) in out.iter_mut().zip(col) {
            *a += c * s;
        }
    }
}

/// The step of a linear model as `y₊ = Φ·y + Γ·u`.
pub struct LinearStep {
    /// State entries `m = 3n + 2r` (`n` masses, `r` relaxing arms).
    m: usize,
    /// Input samples per step `s`.
    inputs: usize,
    /// Padded column length (a multiple of [`LANES`]).
    padded: usize,
    /// The `s` columns of `Γ` then the `m` columns of `Φ`, each zero-padded to `padded`: the
    /// product is a sum of columns scaled by the inputs and state entries (independent lanes, no
    /// long reduction chain).
    columns: Vec<f64>,
    next: Vec<f64>,
    /// The processor has AVX2.
    avx2: bool,
}

fn pack(s: &State, y: &mut [f64]) {
    let mut k = 0;
    for part in [&s.x, &s.v, &s.a, &s.q, &s.qdot] {
        if !part.is_empty() {
            y[k..k + part.len()].copy_from_slice(part);
            k += part.len();
        }
    }
}

/// Fills `s` from the first `3n + 2r` entries of `y`.
fn unpack(y: &[f64], s: &mut State) {
    let mut k = 0;
    for part in [&mut s.x, &mut s.v, &mut s.a, &mut s.q, &mut s.qdot] {
        let len = part.len();
        if len > 0 {
            part.copy_from_slice(&y[k..k + len]);
            k += len;
        }
    }
}

fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::arch::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    false
}

impl LinearStep {
    /// Measures `Φ` and `Γ` by stepping `integrator` (built for the linear `dynamics`) from unit
    /// states and unit inputs; `inputs` is the number of base samples per step
    /// ([`super::Method::substeps`] + 1).
    pub fn probe(
        integrator: &mut dyn Integrator,
        dynamics: &Dynamics,
        inputs: usize,
    ) -> Result<LinearStep> {
        let m = 3 * dynamics.dof() + 2 * dynamics.arms;
        let padded = m.next_multiple_of(LANES).max(LANES);
        let mut columns = vec![0.0; padded * (inputs + m)];
        let mut state = State::at_rest(dynamics, 0.0);
        let mut y = vec![0.0; m];
        let mut u = vec![0.0; inputs];
        let mut column = |y0: &[f64], u: &[f64], out: &mut [f64]| {
            unpack(y0, &mut state);
            integrator.advance(&mut state, u, 0.0)?;
            pack(&state, &mut out[..m]);
            Ok::<(), crate::Error>(())
        };
        let (gamma, phi) = columns.split_at_mut(padded * inputs);
        for (k, col) in gamma.chunks_exact_mut(padded).enumerate() {
            u[k] = 1.0;
            column(&y, &u, col)?;
            u[k] = 0.0;
        }
        for (j, col) in phi.chunks_exact_mut(padded).enumerate() {
            y[j] = 1.0;
            column(&y, &u, col)?;
            y[j] = 0.0;
        }
        Ok(LinearStep {
            m,
            inputs,
            padded,
            columns,
            next: vec![0.0; padded],
            avx2: has_avx2(),
        })
    }

    /// Number of state entries `3n + 2r`.
    pub fn states(&self) -> usize {
        self.m
    }

    /// Column `j` of `[Γ Φ]`, unpadded.
    fn column(&self, j: usize) -> &[f64] {
        &self.columns[j * self.padded..j * self.padded + self.m]
    }

    /// `Φ` (`m × m`, over `y = [x, v, a, q, q̇]`).
    pub fn phi_matrix(&self) -> nalgebra::DMatrix<f64> {
        nalgebra::DMatrix::from_fn(self.m, self.m, |i, j| self.column(self.inputs + j)[i])
    }

    /// `Γ` (`m × s`, one column per input sample of the step).
    pub fn gamma_matrix(&self) -> nalgebra::DMatrix<f64> {
        nalgebra::DMatrix::from_fn(self.m, self.inputs, |i, k| self.column(k)[i])
    }
}

impl Integrator for LinearStep {
    fn advance(&mut self, state: &mut State, a_base: &[f64], _t: f64) -> Result<()> {
        let parts: [&[f64]; 6] = [
            &a_base[..self.inputs],
            &state.x,
            &state.v,
            &state.a,
            &state.q,
            &state.qdot,
        ];
        let (c, s, o, w) = (&self.columns, &parts[..], &mut self.next, self.avx2);
        match self.padded {
            4 => product_best::<4>(w, c, s, o),
            8 => product_best::<8>(w, c, s, o),
            12 => product_best::<12>(w, c, s, o),
            16 => product_best::<16>(w, c, s, o),
            20 => product_best::<20>(w, c, s, o),
            24 => product_best::<24>(w, c, s, o),
            28 => product_best::<28>(w, c, s, o),
            MAX_FIXED => product_best::<MAX_FIXED>(w, c, s, o),
            p => product_any(p, c, s, o),
        }
        unpack(&self.next, state);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kernel gives the same bits: fixed-size, AVX2 and general, on a padded 8-column case.
    #[test]
    fn kernels_agree_bit_for_bit() {
        let (p, cols) = (8, 11);
        let c: Vec<f64> = (0..p * cols)
            .map(|i| ((i * 37 % 101) as f64).sin())
            .collect();
        let s: Vec<f64> = (0..cols).map(|j| (j as f64 * 0.7).cos() * 1e3).collect();
        let mut fixed = vec![0.0; p];
        let mut any = vec![0.0; p];
        let mut best = vec![0.0; p];
        let parts: [&[f64]; 2] = [&s[..4], &s[4..]];
        product::<8>(&c, &parts, &mut fixed);
        product_any(p, &c, &parts, &mut any);
        product_best::<8>(has_avx2(), &c, &parts, &mut best);
        assert_eq!(fixed, any);
        assert_eq!(fixed, best);
        let by_hand: f64 = (0..cols).map(|j| c[j * p + 3] * s[j]).sum();
        assert!((fixed[3] - by_hand).abs() < 1e-9 * by_hand.abs().max(1.0));
    }
}
