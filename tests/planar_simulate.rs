//! Time-domain runs of the planar model: sine steady state against the planar FRF (v-v and v-h)
//! for both integrators, through the shared simulation driver and its measured channels.

use num_complex::Complex64;
use std::f64::consts::PI;
use wbv::excitation::Excitation;
use wbv::integrator::Method;
use wbv::model::catalog;
use wbv::response::frf;
use wbv::simulate::collect::Collector;
use wbv::simulate::{Settings, run};

/// `A·sin(ωt)` sampled at the integrator's stage times.
struct Sine {
    f: f64,
    step: f64,
    k: u64,
}

impl Excitation for Sine {
    fn fill(&mut self, out: &mut [f64]) {
        for o in out {
            *o = (2.0 * PI * self.f * self.k as f64 * self.step).sin();
            self.k += 1;
        }
    }
    fn step_s(&self) -> f64 {
        self.step
    }
    fn describe(&self) -> String {
        "test sine".into()
    }
}

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
            let mut exc = Sine {
                f,
                step: settings.excitation_step(),
                k: 0,
            };
            let mut c = Collector::new();
            run(&model, &mut exc, &settings, &mut [&mut c], None).unwrap();
            let sig = c.into_signals("test").unwrap();
            let get = |n: &str| sig.get(n).unwrap().to_vec();
            let (base, vv, vh) = (get("a_base_z"), get("a_seat_z"), get("a_seat_x"));
            // Analyse t in [8, 16): whole periods, transients (slowest decay ~4 1/s) gone.
            let from = 8000;
            let ab = amplitude(1.0 / dt, &base[..16000], f, from);
            let set = frf::compute(&model, &[f]).unwrap();
            for (name, y) in [("seat", &vv), ("seat_x", &vh)] {
                let got = amplitude(1.0 / dt, &y[..16000], f, from) / ab;
                let exact = set.get(name).unwrap().values[0];
                let err = (got - exact).norm() / exact.norm();
                assert!(err < 5e-3, "{method:?} {f} Hz {name}: {got} vs {exact}");
            }
        }
    }
}
