//! Road excitation: ISO 8608 road roughness seen through a quarter-car vehicle model.
//!
//! ISO 8608:2016 (Annex C, as quoted by public ISO 8608 synthesis code): displacement PSD G_d(n) = G_d(n0)·(n/n0)^(−w) with n0 = 0.1 cycle/m,
//! waviness w = 2, over n = 0.011–2.83 cycle/m; class A–H geometric means G_d(n0) = 16·4^k ×10⁻⁶ m³
//! (A = 16e-6 … H = 262 144e-6 m³; Table C.2). At speed v the temporal frequency is f = v·n and the
//! one-sided road displacement PSD is G_z(f) = G_d(f/v)/v (m²/Hz). The seat base is taken as the
//! sprung mass of a quarter car, so its acceleration PSD is |H_a(f)|²·G_z(f) with
//! H_a = (2πf)²·X_s/Z_r (displacement transmissibility of the two-mass model, Gillespie,
//! *Fundamentals of Vehicle Dynamics*, SAE 1992, ch. 5 "ride").

use crate::error::{Error, Result};
use num_complex::Complex;
use std::f64::consts::PI;

/// Reference spatial frequency n0 of ISO 8608 in cycle/m.
pub const N0_CYCLES_PER_M: f64 = 0.1;
/// Lowest and highest spatial frequency of the ISO 8608 classification band in cycle/m.
pub const BAND_CYCLES_PER_M: [f64; 2] = [0.011, 2.83];

/// Geometric-mean G_d(n0) in m³ (m²/(cycle/m)) of ISO 8608 class `class` (A–H), Table C.2.
pub fn class_gd_n0_m3(class: &str) -> Result<f64> {
    const CLASSES: &str = "ABCDEFGH";
    let c = class.trim().to_ascii_uppercase();
    match CLASSES.find(c.as_str()) {
        Some(k) if c.len() == 1 => Ok(16e-6 * 4f64.powi(k as i32)),
        _ => Err(Error::parameter(
            "class",
            format!("`{class}` is not an ISO 8608 road class A–H"),
        )),
    }
}

/// A linear quarter car: sprung mass on a suspension spring and damper, unsprung mass on a tyre
/// spring (and optional damper) in point contact with the road.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuarterCar {
    /// Sprung (body) mass per wheel in kg.
    pub sprung_mass_kg: f64,
    /// Unsprung (wheel, axle) mass in kg.
    pub unsprung_mass_kg: f64,
    /// Suspension stiffness in N/m.
    pub suspension_stiffness_n_m: f64,
    /// Suspension damping in N·s/m.
    pub suspension_damping_n_s_m: f64,
    /// Tyre vertical stiffness in N/m.
    pub tyre_stiffness_n_m: f64,
    /// Tyre damping in N·s/m (usually neglected).
    #[serde(default)]
    pub tyre_damping_n_s_m: f64,
}

impl QuarterCar {
    /// Passenger-car quarter car of the TU Delft vehicle-dynamics course (B. Shyrokau, Intelligent
    /// Vehicles & Cognitive Robotics, 2022, public quarter-car script): m_s = 410 kg, m_u = 45 kg,
    /// k_s = 25 500 N/m, k_t = 230 000 N/m, suspension damping 0.3 of critical for the body mode,
    /// c_s = 0.3·2·m_s·sqrt(k_s k_t/(k_s + k_t)/m_s) = 1 841 N·s/m. Body mode ≈ 1.2 Hz, wheel hop
    /// ≈ 12 Hz, in the usual ranges for cars (Gillespie 1992, ch. 5: 1–1.5 Hz and 10–12 Hz).
    pub fn passenger_car() -> Self {
        let (ms, ks, kt): (f64, f64, f64) = (410.0, 25_500.0, 230_000.0);
        let wn = (ks * kt / (ks + kt) / ms).sqrt();
        QuarterCar {
            sprung_mass_kg: ms,
            unsprung_mass_kg: 45.0,
            suspension_stiffness_n_m: ks,
            suspension_damping_n_s_m: 0.3 * 2.0 * ms * wn,
            tyre_stiffness_n_m: kt,
            tyre_damping_n_s_m: 0.0,
        }
    }

    /// Checks that every parameter is positive (damping non-negative) and finite.
    pub fn validate(&self, what: &str) -> Result<()> {
        let pos = [
            ("sprung_mass_kg", self.sprung_mass_kg),
            ("unsprung_mass_kg", self.unsprung_mass_kg),
            ("suspension_stiffness_n_m", self.suspension_stiffness_n_m),
            ("tyre_stiffness_n_m", self.tyre_stiffness_n_m),
        ];
        for (k, v) in pos {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::parameter(
                    format!("{what}.{k}"),
                    format!("{v} must be positive"),
                ));
            }
        }
        for (k, v) in [
            ("suspension_damping_n_s_m", self.suspension_damping_n_s_m),
            ("tyre_damping_n_s_m", self.tyre_damping_n_s_m),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::parameter(
                    format!("{what}.{k}"),
                    format!("{v} must be ≥ 0"),
                ));
            }
        }
        Ok(())
    }

    /// Sprung-mass displacement transmissibility X_s/Z_r at `f_hz`, from
    /// [−ω²m_s + jωc_s + k_s, −(jωc_s + k_s); −(jωc_s + k_s), −ω²m_u + jω(c_s+c_t) + k_s + k_t]·[X_s; X_u]
    /// = [0; (jωc_t + k_t) Z_r] solved by Cramer's rule.
    pub fn transmissibility(&self, f_hz: f64) -> Complex<f64> {
        let w = 2.0 * PI * f_hz;
        let j = Complex::new(0.0, w);
        let s = j * self.suspension_damping_n_s_m + self.suspension_stiffness_n_m;
        let t = j * self.tyre_damping_n_s_m + self.tyre_stiffness_n_m;
        let a11 = -w * w * self.sprung_mass_kg + s;
        let a22 = -w * w * self.unsprung_mass_kg + s + t;
        let det = a11 * a22 - s * s;
        s * t / det
    }
}

/// ISO 8608 road at a speed through a quarter car.
#[derive(Debug, Clone, PartialEq)]
pub struct Road {
    /// G_d(n0) in m³.
    pub gd_n0_m3: f64,
    /// Vehicle speed in m/s.
    pub speed_m_s: f64,
    /// Quarter car through which the road profile reaches the cab floor (masses, suspension and tyre).
    pub vehicle: QuarterCar,
}

impl Road {
    /// Temporal frequency band in Hz: v·[0.011, 2.83] cycle/m (ISO 8608 band).
    pub fn band_hz(&self) -> [f64; 2] {
        BAND_CYCLES_PER_M.map(|n| n * self.speed_m_s)
    }

    /// Road displacement PSD in m²/Hz at temporal frequency `f_hz` (w = 2): G_d(n0)·n0²·v/f².
    pub fn displacement_psd(&self, f_hz: f64) -> f64 {
        let [lo, hi] = self.band_hz();
        if !(f_hz >= lo && f_hz <= hi) {
            return 0.0;
        }
        self.gd_n0_m3 * N0_CYCLES_PER_M * N0_CYCLES_PER_M * self.speed_m_s / (f_hz * f_hz)
    }

    /// Seat-base (sprung-mass) acceleration PSD in (m/s²)²/Hz: (2πf)⁴·|X_s/Z_r|²·G_z(f).
    pub fn psd(&self, f_hz: f64) -> f64 {
        let w2 = (2.0 * PI * f_hz).powi(2);
        w2 * w2 * self.vehicle.transmissibility(f_hz).norm_sqr() * self.displacement_psd(f_hz)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_follow_table_c2() {
        assert_eq!(class_gd_n0_m3("A").unwrap(), 16e-6);
        assert!((class_gd_n0_m3("c").unwrap() - 256e-6).abs() < 1e-18);
        assert!((class_gd_n0_m3("H").unwrap() - 262_144e-6).abs() < 1e-15);
        assert!(class_gd_n0_m3("I").is_err());
        assert!(class_gd_n0_m3("AB").is_err());
    }

    #[test]
    fn quarter_car_limits_and_body_mode() {
        let q = QuarterCar::passenger_car();
        assert!((q.transmissibility(1e-4).norm() - 1.0).abs() < 1e-6);
        // Undamped body mode of the series springs: sqrt(k_s k_t/(k_s+k_t)/m_s)/2π ≈ 1.19 Hz; with
        // ζ = 0.3 the peak transmissibility is near it and ≈ 1/(2ζ)·sqrt(1+(2ζ)²) ≈ 1.9.
        let fb = (q.suspension_stiffness_n_m * q.tyre_stiffness_n_m
            / (q.suspension_stiffness_n_m + q.tyre_stiffness_n_m)
            / q.sprung_mass_kg)
            .sqrt()
            / (2.0 * PI);
        assert!((fb - 1.19).abs() < 0.01, "{fb}");
        // Rigid tyre limit: the single-DOF base-excitation transmissibility
        // |T| = sqrt(1 + (2ζr)²)/sqrt((1 − r²)² + (2ζr)²), r = ω/ω_n, ω_n² = k_s/m_s, ζ = c_s/(2 sqrt(k_s m_s)).
        let stiff = QuarterCar {
            tyre_stiffness_n_m: 1e13,
            ..q
        };
        let wn = (q.suspension_stiffness_n_m / q.sprung_mass_kg).sqrt();
        let zeta = q.suspension_damping_n_s_m
            / (2.0 * (q.suspension_stiffness_n_m * q.sprung_mass_kg).sqrt());
        for f in [0.3, 1.0, 1.25, 2.0, 5.0] {
            let r = 2.0 * PI * f / wn;
            let want = (1.0 + (2.0 * zeta * r).powi(2)).sqrt()
                / ((1.0 - r * r).powi(2) + (2.0 * zeta * r).powi(2)).sqrt();
            let got = stiff.transmissibility(f).norm();
            assert!((got / want - 1.0).abs() < 1e-5, "f={f}: {got} vs {want}");
        }
        // Velocity PSD of class C at 20 m/s is white: 4π²·256e-6·0.01·20 = 2.02e-3 (m/s)²/Hz.
        let r = Road {
            gd_n0_m3: 256e-6,
            speed_m_s: 20.0,
            vehicle: q,
        };
        let vel = (2.0 * PI * 3.0).powi(2) * r.displacement_psd(3.0);
        assert!((vel - 4.0 * PI * PI * 256e-6 * 0.01 * 20.0).abs() < 1e-12);
    }
}
