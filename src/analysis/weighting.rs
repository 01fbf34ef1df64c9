//! Analog frequency weightings of ISO 2631-1:1997 Annex A (Table A.2), with the parameters as
//! tabulated in ISO 8041-1:2017 Table 3, plus Wb (ISO 2631-4:2001 Table A.1 / BS 6841) and Wm
//! (ISO 2631-2:2003).
//!
//! H(s) = Hh·Hl·Ht·Hs, s = j2πf, ω_i = 2πf_i (ISO 2631-1 Annex A, eqs. A.1–A.4):
//! - band-limiting high-pass Hh = 1 / (1 + ω1/(Q1 s) + (ω1/s)²),
//! - band-limiting low-pass  Hl = 1 / (1 + s/(Q2 ω2) + (s/ω2)²),
//! - a–v transition          Ht = K (1 + s/ω3) / (1 + s/(Q4 ω4) + (s/ω4)²),
//! - upward step             Hs = (1 + s/(Q5 ω5) + (s/ω5)²) / (1 + s/(Q6 ω6) + (s/ω6)²) · (ω5/ω6)².
//!
//! A corner at ∞ removes its factor. Each stage is kept as its own second-order section so that the
//! digital filter (`filter/mod.rs`) maps it separately.

use num_complex::Complex64;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// A frequency weighting.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Weighting {
    /// Vertical z on seat, standing, recumbent (ISO 2631-1 Table 1).
    Wk,
    /// Horizontal x, y (ISO 2631-1 Table 1).
    Wd,
    /// Motion sickness, vertical (ISO 2631-1 clause 9).
    Wf,
    /// Seat-back x (ISO 2631-1 Table 2).
    Wc,
    /// Rotational (ISO 2631-1 Table 2).
    We,
    /// Recumbent, under the head (ISO 2631-1 Table 2).
    Wj,
    /// Vertical, rail passenger comfort (ISO 2631-4:2001 Table A.1; BS 6841).
    Wb,
    /// Buildings, combined direction (ISO 2631-2:2003).
    Wm,
    /// Band-limiting only (Hh·Hl of the whole-body weightings), for tests of instruments.
    BandLimiting,
}

/// Annex A parameters; `None` is a corner at ∞. Frequencies in Hz.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parameters {
    /// High-pass corner f1 of Hh, Hz (eq. A.1).
    pub f1: f64,
    /// Quality factor Q1 of Hh.
    pub q1: f64,
    /// Low-pass corner f2 of Hl, Hz (eq. A.2).
    pub f2: f64,
    /// Quality factor Q2 of Hl.
    pub q2: f64,
    /// Transition zero f3 of Ht, Hz (eq. A.3).
    pub f3: Option<f64>,
    /// Transition pole f4 of Ht, Hz (eq. A.3).
    pub f4: Option<f64>,
    /// Quality factor Q4 of Ht.
    pub q4: f64,
    /// Upward-step zero f5 of Hs, Hz (eq. A.4).
    pub f5: Option<f64>,
    /// Quality factor Q5 of Hs.
    pub q5: f64,
    /// Upward-step pole f6 of Hs, Hz (eq. A.4).
    pub f6: Option<f64>,
    /// Quality factor Q6 of Hs.
    pub q6: f64,
    /// Gain K of Ht (dimensionless).
    pub k: f64,
}

/// An analog second-order section (b2 s² + b1 s + b0) / (a2 s² + a1 s + a0), s in rad/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalogSection {
    /// Numerator coefficients b0, b1, b2.
    pub b: [f64; 3],
    /// Denominator coefficients a0, a1, a2.
    pub a: [f64; 3],
}

impl AnalogSection {
    /// Complex response at frequency `f` in Hz.
    pub fn response(&self, f: f64) -> Complex64 {
        let s = Complex64::new(0.0, 2.0 * PI * f);
        let [b0, b1, b2] = self.b;
        let [a0, a1, a2] = self.a;
        (b2 * s * s + b1 * s + b0) / (a2 * s * s + a1 * s + a0)
    }

    /// Natural frequency of the poles √(a0/a2)/(2π) in Hz.
    pub fn pole_hz(&self) -> f64 {
        (self.a[0] / self.a[2]).sqrt() / (2.0 * PI)
    }
}

const W: f64 = 2.0 * PI;
const Q: f64 = FRAC_1_SQRT_2;

impl Weighting {
    /// Every weighting, for listings and tests.
    pub const ALL: [Weighting; 9] = [
        Weighting::Wk,
        Weighting::Wd,
        Weighting::Wf,
        Weighting::Wc,
        Weighting::We,
        Weighting::Wj,
        Weighting::Wb,
        Weighting::Wm,
        Weighting::BandLimiting,
    ];

    /// Annex A / ISO 8041-1 Table 3 parameters.
    pub fn parameters(self) -> Parameters {
        let base = Parameters {
            f1: 0.4,
            q1: Q,
            f2: 100.0,
            q2: Q,
            f3: None,
            f4: None,
            q4: 1.0,
            f5: None,
            q5: 1.0,
            f6: None,
            q6: 1.0,
            k: 1.0,
        };
        let av = |f: f64, q4: f64| Parameters {
            f3: Some(f),
            f4: Some(f),
            q4,
            ..base
        };
        match self {
            Weighting::Wk => Parameters {
                f5: Some(2.37),
                q5: 0.91,
                f6: Some(3.35),
                q6: 0.91,
                ..av(12.5, 0.63)
            },
            Weighting::Wd => av(2.0, 0.63),
            Weighting::Wc => av(8.0, 0.63),
            Weighting::We => av(1.0, 0.63),
            Weighting::Wf => Parameters {
                f1: 0.08,
                f2: 0.63,
                f3: None,
                f4: Some(0.25),
                q4: 0.86,
                f5: Some(0.0625),
                q5: 0.80,
                f6: Some(0.10),
                q6: 0.80,
                ..base
            },
            Weighting::Wj => Parameters {
                f5: Some(3.75),
                q5: 0.91,
                f6: Some(5.32),
                q6: 0.91,
                ..base
            },
            Weighting::Wb => Parameters {
                f5: Some(2.5),
                q5: 0.9,
                f6: Some(4.0),
                q6: 0.95,
                k: 1.024,
                ..av(16.0, 0.55)
            },
            // ISO 2631-2:2003: f1 = 10^-0.1 Hz, f3 = f4 = 1/(0.028·2π) Hz, Q4 = 0.5.
            Weighting::Wm => Parameters {
                f1: 10f64.powf(-0.1),
                ..av(1.0 / (0.028 * W), 0.5)
            },
            Weighting::BandLimiting => base,
        }
    }

    /// The cascade of analog second-order sections Hh, Hl, Ht, Hs (factors at ∞ omitted).
    pub fn sections(self) -> Vec<AnalogSection> {
        let p = self.parameters();
        let (w1, w2) = (W * p.f1, W * p.f2);
        let mut out = vec![
            AnalogSection {
                b: [0.0, 0.0, 1.0],
                a: [w1 * w1, w1 / p.q1, 1.0],
            },
            AnalogSection {
                b: [w2 * w2, 0.0, 0.0],
                a: [w2 * w2, w2 / p.q2, 1.0],
            },
        ];
        // K multiplies the a–v stage; no weighting has K ≠ 1 without one (ISO 8041-1 Table 3).
        if let Some(f4) = p.f4 {
            let w4 = W * f4;
            let b1 = p.f3.map_or(0.0, |f3| p.k / (W * f3));
            out.push(AnalogSection {
                b: [p.k, b1, 0.0],
                a: [1.0, 1.0 / (p.q4 * w4), 1.0 / (w4 * w4)],
            });
        }
        if let (Some(f5), Some(f6)) = (p.f5, p.f6) {
            let (w5, w6) = (W * f5, W * f6);
            out.push(AnalogSection {
                b: [w5 * w5, w5 / p.q5, 1.0],
                a: [w6 * w6, w6 / p.q6, 1.0],
            });
        }
        out
    }

    /// Complex weighting H(j2πf) at `f` Hz (dimensionless).
    pub fn response(self, f: f64) -> Complex64 {
        self.sections().iter().map(|s| s.response(f)).product()
    }

    /// Weighting factor |H(j2πf)| at `f` Hz, the quantity tabulated in ISO 2631-1 Tables 3 and 4.
    pub fn magnitude(self, f: f64) -> f64 {
        self.response(f).norm()
    }

    /// Upper end of the frequency range the weighting is defined for, in Hz: 80 Hz for the
    /// whole-body weightings (ISO 2631-1 clause 1), 0.5 Hz for Wf (motion sickness, clause 9).
    pub fn upper_range_hz(self) -> f64 {
        match self {
            Weighting::Wf => 0.5,
            _ => 80.0,
        }
    }

    /// Short name, e.g. "Wk".
    pub fn name(self) -> &'static str {
        match self {
            Weighting::Wk => "Wk",
            Weighting::Wd => "Wd",
            Weighting::Wf => "Wf",
            Weighting::Wc => "Wc",
            Weighting::We => "We",
            Weighting::Wj => "Wj",
            Weighting::Wb => "Wb",
            Weighting::Wm => "Wm",
            Weighting::BandLimiting => "band-limiting",
        }
    }

    /// The weighting named `name` ("Wk", "wk", "band-limiting", …), case-insensitive.
    pub fn parse(name: &str) -> Option<Weighting> {
        Weighting::ALL
            .into_iter()
            .find(|w| w.name().eq_ignore_ascii_case(name))
    }
}
