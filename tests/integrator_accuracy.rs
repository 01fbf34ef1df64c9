//! Integrators against closed forms: steady-state sine response vs the FRF, convergence order
//! against the exact state-space solution, and the energy balance.

use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;
use std::f64::consts::PI;
use wbv::excitation::Excitation;
use wbv::integrator::Method;
use wbv::model::{Model, catalog};
use wbv::response::frf;
use wbv::simulate::observer::{Layout, Observer, Step};
use wbv::simulate::{Settings, run};

/// A sum of sines `Σ A·sin(ωt)`, sampled exactly at the integrator's stage times.
struct Sines {
    parts: Vec<(f64, f64)>,
    step: f64,
    k: u64,
}

impl Excitation for Sines {
    fn fill(&mut self, out: &mut [f64]) {
        for o in out {
            let t = self.k as f64 * self.step;
            *o = self
                .parts
                .iter()
                .map(|(a, f)| a * (2.0 * PI * f * t).sin())
                .sum();
            self.k += 1;
        }
    }
    fn step_s(&self) -> f64 {
        self.step
    }
    fn describe(&self) -> String {
        "test sines".into()
    }
}

/// Keeps every step's full state.
#[derive(Default)]
struct Trace {
    layout: Option<Layout>,
    t: Vec<f64>,
    a_base: Vec<f64>,
    v_base: Vec<f64>,
    x: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    a: Vec<Vec<f64>>,
    tension: Vec<Vec<f64>>,
    deflection: Vec<Vec<f64>>,
}

impl Observer for Trace {
    fn begin(&mut self, layout: &Layout) -> wbv::Result<()> {
        self.layout = Some(layout.clone());
        Ok(())
    }
    fn step(&mut self, s: &Step<'_>) -> wbv::Result<()> {
        self.t.push(s.t);
        self.a_base.push(s.a_base);
        self.v_base.push(s.v_base);
        self.x.push(s.x.to_vec());
        self.v.push(s.v.to_vec());
        self.a.push(s.a.to_vec());
        self.tension.push(s.link_force.to_vec());
        self.deflection.push(s.link_deflection.to_vec());
        Ok(())
    }
    fn end(&mut self) -> wbv::Result<()> {
        Ok(())
    }
}

fn simulate(
    model: &Model,
    method: Method,
    dt: f64,
    duration: f64,
    parts: Vec<(f64, f64)>,
) -> Trace {
    let settings = Settings {
        dt,
        duration_s: duration,
        method,
    };
    let mut exc = Sines {
        parts,
        step: settings.excitation_step(),
        k: 0,
    };
    let mut trace = Trace::default();
    run(model.system(), &mut exc, &settings, &mut [&mut trace], None).unwrap();
    trace
}

/// Fourier coefficient of `y` at `f` Hz (unnormalised; ratios of two of them are transfer
/// functions). The samples must span a whole number of periods.
fn amplitude(t: &[f64], y: &[f64], f: f64) -> Complex64 {
    let w = 2.0 * PI * f;
    t.iter()
        .zip(y)
        .map(|(ti, yi)| yi * Complex64::from_polar(1.0, -w * ti))
        .sum()
}

#[test]
fn steady_state_sine_matches_the_frf_for_both_integrators() {
    let model = catalog::resolve("reference").unwrap();
    let dt = 1e-3;
    for method in [Method::AVERAGE_ACCELERATION, Method::Rk4] {
        for f in [1.0, 4.0, 8.0, 15.0] {
            let tr = simulate(&model, method, dt, 12.0, vec![(1.0, f)]);
            let head = model.chain().unwrap().measure.head.unwrap();
            // Analyse t in [4, 12): a whole number of periods at each test frequency.
            let keep = |i: usize| tr.t[i] >= 4.0 - 1e-9 && tr.t[i] < 12.0 - 1e-9;
            let idx: Vec<usize> = (0..tr.t.len()).filter(|&i| keep(i)).collect();
            let t: Vec<f64> = idx.iter().map(|&i| tr.t[i]).collect();
            let base: Vec<f64> = idx.iter().map(|&i| tr.a_base[i]).collect();
            let abs_head: Vec<f64> = idx.iter().map(|&i| tr.a[i][head] + tr.a_base[i]).collect();
            let ratio = amplitude(&t, &abs_head, f) / amplitude(&t, &base, f);
            let exact = frf::compute(model.system(), &[f])
                .unwrap()
                .get("t_head")
                .unwrap()
                .values[0];
            let mag_err = (ratio.norm() / exact.norm() - 1.0).abs();
            let phase_err = (ratio / exact).arg().to_degrees().abs();
            eprintln!(
                "{method:?} {f} Hz: |T| error {:.5} %, phase error {phase_err:.5}°",
                100.0 * mag_err
            );
            assert!(
                mag_err < 0.005,
                "{method:?} {f} Hz: |T| error {:.4} %",
                100.0 * mag_err
            );
            assert!(
                phase_err < 0.5,
                "{method:?} {f} Hz: phase error {phase_err:.3}°"
            );
        }
    }
}

/// Exact response of the linear state-space model to `a_base = sin(ωt)` from rest, at time `t`.
fn exact_state(model: &Model, f: f64, t: f64) -> DVector<f64> {
    let ss = model.system().state_space();
    let size = ss.a.nrows();
    let w = 2.0 * PI * f;
    let ac = DMatrix::from_fn(size, size, |i, j| Complex64::new(ss.a[(i, j)], 0.0));
    let bc = ss.b.map(|v| Complex64::new(v, 0.0));
    // Particular solution y_p(t) = Im(Y·e^{iωt}), Y = (iωI − A)⁻¹·b.
    let lhs = DMatrix::<Complex64>::identity(size, size) * Complex64::new(0.0, w) - ac;
    let y = lhs.lu().solve(&bc).unwrap();
    let yp = |t: f64| y.map(|v| (v * Complex64::from_polar(1.0, w * t)).im);
    let expo = (ss.a.clone() * t).exp();
    yp(t) - expo * yp(0.0)
}

fn slope(dts: &[f64], errs: &[f64]) -> f64 {
    let n = dts.len() as f64;
    let xs: Vec<f64> = dts.iter().map(|d| d.ln()).collect();
    let ys: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
    let mx = xs.iter().sum::<f64>() / n;
    let my = ys.iter().sum::<f64>() / n;
    let num: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let den: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    num / den
}

#[test]
fn convergence_order_is_two_for_newmark_and_four_for_rk4() {
    let model = catalog::resolve("boileau-rakheja-4dof").unwrap();
    let (f, t_end) = (4.0, 1.0);
    let exact = exact_state(&model, f, t_end);
    let n = model.dof();
    for (method, dts, order) in [
        (
            Method::AVERAGE_ACCELERATION,
            vec![4e-3, 2e-3, 1e-3, 5e-4],
            2.0,
        ),
        (
            Method::LINEAR_ACCELERATION,
            vec![2e-3, 1e-3, 5e-4, 2.5e-4],
            2.0,
        ),
        (Method::Rk4, vec![1e-3, 5e-4, 2.5e-4, 1.25e-4], 4.0),
    ] {
        let errs: Vec<f64> = dts
            .iter()
            .map(|&dt| {
                let tr = simulate(&model, method, dt, t_end, vec![(1.0, f)]);
                let last = tr.x.len() - 1;
                (0..n)
                    .map(|i| (tr.x[last][i] - exact[i]).abs())
                    .fold(0.0, f64::max)
            })
            .collect();
        let s = slope(&dts, &errs);
        eprintln!("{method:?}: slope {s:.3}, errors {errs:?}");
        assert!(
            (s - order).abs() <= 0.3,
            "{method:?}: slope {s:.3}, errors {errs:?}"
        );
    }
}

#[test]
fn work_of_the_base_equals_stored_plus_dissipated_energy() {
    for name in [
        "reference",
        "seed001-full",
        "seed002-maxwell",
        "boileau-rakheja-4dof+cushion-zener",
    ] {
        let model = catalog::resolve(name).unwrap();
        for method in [Method::AVERAGE_ACCELERATION, Method::Rk4] {
            let dt = 2.5e-4;
            let tr = simulate(
                &model,
                method,
                dt,
                4.0,
                vec![(1.0, 3.1), (0.6, 7.3), (0.3, 13.0)],
            );
            let m: Vec<f64> = model.chain().unwrap().masses.iter().map(|m| m.m).collect();
            let energy = |i: usize| -> f64 {
                let kinetic: f64 = (0..m.len())
                    .map(|j| 0.5 * m[j] * (tr.v[i][j] + tr.v_base[i]).powi(2))
                    .sum();
                let potential: f64 = model
                    .chain()
                    .unwrap()
                    .links
                    .iter()
                    .enumerate()
                    .map(|(l, link)| {
                        let d = tr.deflection[i][l];
                        let k = link.element.parallel_stiffness();
                        let spring = 0.5 * k * d * d;
                        let arm = match link.element.relaxing_arm() {
                            Some((k_m, _)) => {
                                let q = tr.tension[i][l] - k * d;
                                0.5 * q * q / k_m
                            }
                            None => 0.0,
                        };
                        spring + arm
                    })
                    .sum();
                kinetic + potential
            };
            // Power dissipated and power put in by the base at each step.
            let rel_v = |i: usize, l: usize| -> f64 {
                let link = &model.chain().unwrap().links[l];
                let at = |n: wbv::model::Node| match n {
                    wbv::model::Node::Base => 0.0,
                    wbv::model::Node::Mass(j) => tr.v[i][j],
                };
                at(link.a) - at(link.b)
            };
            let dissipation = |i: usize| -> f64 {
                model
                    .chain()
                    .unwrap()
                    .links
                    .iter()
                    .enumerate()
                    .map(|(l, link)| {
                        let dv = rel_v(i, l);
                        let k = link.element.parallel_stiffness();
                        match link.element.relaxing_arm() {
                            Some((_, c_m)) => {
                                let q = tr.tension[i][l] - k * tr.deflection[i][l];
                                q * q / c_m
                            }
                            None => link.element.parallel_damping() * dv * dv,
                        }
                    })
                    .sum()
            };
            let input = |i: usize| -> f64 {
                model
                    .chain()
                    .unwrap()
                    .links
                    .iter()
                    .enumerate()
                    .filter(|(_, l)| l.b == wbv::model::Node::Base)
                    .map(|(l, _)| -tr.tension[i][l] * tr.v_base[i])
                    .sum()
            };
            let last = tr.t.len() - 1;
            let (mut work, mut dissipated) = (0.0, 0.0);
            for i in 0..last {
                work += 0.5 * dt * (input(i) + input(i + 1));
                dissipated += 0.5 * dt * (dissipation(i) + dissipation(i + 1));
            }
            let stored = energy(last) - energy(0);
            let err = (work - stored - dissipated).abs() / work.abs();
            eprintln!(
                "{name} {method:?}: work {work:.6} J, stored {stored:.6} J, dissipated {dissipated:.6} J, error {:.5} %",
                100.0 * err
            );
            assert!(
                err < 1e-3,
                "{name} {method:?}: work {work:.6} J, stored {stored:.6} J, dissipated {dissipated:.6} J, error {:.4} %",
                100.0 * err
            );
        }
    }
}

#[test]
fn rk4_refuses_a_step_beyond_its_stability_limit() {
    let model = catalog::resolve("reference").unwrap();
    let settings = Settings {
        dt: 5e-3,
        duration_s: 1.0,
        method: Method::Rk4,
    };
    let mut exc = Sines {
        parts: vec![(1.0, 4.0)],
        step: settings.excitation_step(),
        k: 0,
    };
    let err = run(model.system(), &mut exc, &settings, &mut [], None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("RK4 stability limit") && err.contains("Hz"),
        "{err}"
    );
    let (limit, _) = wbv::integrator::stability::rk4_max_step(model.system());
    // Just below the limit the run stays bounded; just above it is refused.
    let ok = Settings {
        dt: 0.99 * limit,
        duration_s: 2.0,
        method: Method::Rk4,
    };
    let mut exc = Sines {
        parts: vec![(1.0, 4.0)],
        step: ok.excitation_step(),
        k: 0,
    };
    run(model.system(), &mut exc, &ok, &mut [], None).unwrap();
}
