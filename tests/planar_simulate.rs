//! Time-domain runs of the planar model: sine steady state against the planar FRF (v-v and v-h)
//! for both integrators, through the shared simulation driver and its measured channels; the
//! contact links' forces balance the body's momentum rate at every step.

use num_complex::Complex64;
use std::f64::consts::PI;
use wbv::integrator::Method;
use wbv::model::catalog;
use wbv::response::frf;
use wbv::simulate::collect::Collector;
use wbv::simulate::{Settings, run};

mod common;
use common::Sine;

fn amplitude(fs: f64, y: &[f64], f: f64, from: usize) -> Complex64 {
    let w = 2.0 * PI * f;
    y.iter()
        .enumerate()
        .skip(from)
        .map(|(i, v)| v * Complex64::from_polar(1.0, -w * i as f64 / fs))
        .sum()
}

#[test]
fn sine_steady_state_matches_the_planar_frf_for_both_integrators() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let dt = 1e-3;
    for method in [Method::AVERAGE_ACCELERATION, Method::Rk4] {
        for f in [2.0, 4.0, 5.0, 8.0] {
            let settings = Settings {
                dt,
                duration_s: 16.0,
                method,
            };
            let mut exc = Sine::new(1.0, f, settings.excitation_step());
            let mut c = Collector::new();
            run(model.system(), &mut exc, &settings, &mut [&mut c], None).unwrap();
            let sig = c.into_signals("test").unwrap();
            let get = |n: &str| sig.get(n).unwrap().to_vec();
            let base = get("a_base_z");
            // Analyse t in [8, 16): whole periods, transients (slowest decay ~4 1/s) gone.
            let from = 8000;
            let ab = amplitude(1.0 / dt, &base[..16000], f, from);
            let set = frf::compute(model.system(), &[f]).unwrap();
            for (name, channel) in [
                ("seat", "a_seat_z"),
                ("seat_x", "a_seat_x"),
                ("head_z", "a_head_z"),
                ("head_x", "a_head_x"),
            ] {
                let y = get(channel);
                let got = amplitude(1.0 / dt, &y[..16000], f, from) / ab;
                let exact = set.get(name).unwrap().values[0];
                let err = (got - exact).norm() / exact.norm();
                assert!(err < 5e-3, "{method:?} {f} Hz {name}: {got} vs {exact}");
            }
        }
    }
}

/// Keeps, per step, `−Σ n_z·tension` over the contact links and the vertical momentum rate
/// `r_zᵀ·M·(a + r_z·a_base)` computed from the mass matrix.
struct Balance {
    vertical: Vec<f64>,
    m_r: Vec<f64>,
    influence: Vec<f64>,
    worst: f64,
    scale: f64,
}

impl wbv::simulate::observer::Observer for Balance {
    fn begin(&mut self, layout: &wbv::simulate::observer::Layout) -> wbv::Result<()> {
        assert_eq!(layout.links.len(), self.vertical.len());
        assert!(layout.links.iter().any(|l| l == "backrest_t"));
        Ok(())
    }
    fn step(&mut self, s: &wbv::simulate::observer::Step<'_>) -> wbv::Result<()> {
        let support: f64 = -self
            .vertical
            .iter()
            .zip(s.link_force)
            .map(|(n, t)| n * t)
            .sum::<f64>();
        let momentum: f64 = self
            .m_r
            .iter()
            .zip(s.a)
            .zip(&self.influence)
            .map(|((m, a), r)| m * (a + r * s.a_base))
            .sum();
        self.worst = self.worst.max((support - momentum).abs());
        self.scale = self.scale.max(momentum.abs());
        Ok(())
    }
    fn end(&mut self) -> wbv::Result<()> {
        Ok(())
    }
}

#[test]
fn contact_forces_balance_the_momentum_rate_at_every_step() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let p = model.planar().unwrap();
    let links = &p.links;
    let l = &p.linear;
    // M is symmetric: r_zᵀM is the row of M·r_z.
    let m_r: Vec<f64> = (&l.m * &l.r_z).iter().copied().collect();
    let settings = Settings {
        dt: 1e-3,
        duration_s: 4.0,
        method: Method::AVERAGE_ACCELERATION,
    };
    let mut exc = Sine::new(1.0, 4.5, settings.excitation_step());
    let mut b = Balance {
        vertical: links.iter().map(|c| c.vertical).collect(),
        m_r,
        influence: l.r_z.iter().copied().collect(),
        worst: 0.0,
        scale: 0.0,
    };
    run(model.system(), &mut exc, &settings, &mut [&mut b], None).unwrap();
    // The body weighs ~70 kg under 1 m/s²: forces of tens of N.
    assert!(b.scale > 10.0, "momentum rate {} N", b.scale);
    assert!(b.worst < 1e-9 * b.scale, "{} N of {} N", b.worst, b.scale);
}
