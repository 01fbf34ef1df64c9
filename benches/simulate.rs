//! Integrator step throughput on the 6-DOF paper-001 seat (body + cushion + suspension), both
//! integrators, against a hand-written loop of the same discrete-time recursion (the lower bound
//! on time per step: the linear average-acceleration Newmark step is the state-space recursion
//! `y₊ = Φ·y + Γ₀·u + Γ₁·u₊` with precomputed matrices).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use wbv::excitation::Excitation;
use wbv::integrator::Method;
use wbv::model::catalog;
use wbv::simulate::{Settings, run};

/// Deterministic broadband input (sum of incommensurate sines), cheap to generate.
struct Input {
    step: f64,
    k: u64,
}

impl Excitation for Input {
    fn fill(&mut self, out: &mut [f64]) {
        for o in out {
            let t = self.k as f64 * self.step;
            *o = (7.1 * t).sin() + 0.5 * (31.7 * t).sin() + 0.25 * (83.3 * t).sin();
            self.k += 1;
        }
    }
    fn step_s(&self) -> f64 {
        self.step
    }
    fn describe(&self) -> String {
        "bench input".into()
    }
}

const STEPS: u64 = 100_000;

fn bench(c: &mut Criterion) {
    let model = catalog::resolve("seed001-full").unwrap();
    let dt = 1e-3;
    let mut group = c.benchmark_group("simulate_seed001_full");
    group.throughput(Throughput::Elements(STEPS));
    group.sample_size(10);
    for (name, method) in [
        ("newmark", Method::AVERAGE_ACCELERATION),
        ("rk4", Method::Rk4),
    ] {
        let settings = Settings {
            dt,
            duration_s: STEPS as f64 * dt,
            method,
        };
        group.bench_function(name, |b| {
            b.iter(|| {
                let mut exc = Input {
                    step: settings.excitation_step(),
                    k: 0,
                };
                run(&model, &mut exc, &settings, &mut [], None).unwrap();
            })
        });
    }
    // Hand-written lower bound: y₊ = Φ·y + Γ₀·u + Γ₁·u₊ on fixed-size arrays (n = 12 states).
    let (phi, g0, g1) = wbv::integrator::newmark::discrete_recursion(&model, dt);
    let n = phi.nrows();
    let phi: Vec<f64> = phi.transpose().iter().copied().collect();
    let (g0, g1): (Vec<f64>, Vec<f64>) =
        (g0.iter().copied().collect(), g1.iter().copied().collect());
    group.bench_function("hand_written_loop", |b| {
        b.iter(|| {
            let mut y = vec![0.0; n];
            let mut next = vec![0.0; n];
            let mut exc = Input { step: dt, k: 0 };
            let mut u = [0.0; 2];
            exc.fill(&mut u[..1]);
            for _ in 0..STEPS {
                exc.fill(&mut u[1..2]);
                for i in 0..n {
                    let row = &phi[i * n..(i + 1) * n];
                    let mut acc = g0[i] * u[0] + g1[i] * u[1];
                    for j in 0..n {
                        acc += row[j] * y[j];
                    }
                    next[i] = acc;
                }
                std::mem::swap(&mut y, &mut next);
                u[0] = u[1];
            }
            black_box(&y);
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
