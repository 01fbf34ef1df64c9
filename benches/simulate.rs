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
/// States of the paper-001 seat: x, v, a of 6 masses.
const N: usize = 18;

/// `y₊ = Φ·y + Γ₀·u + Γ₁·u₊` for [`STEPS`] steps from rest, `Φ` given by columns.
#[inline(always)]
fn hand_loop(cols: &[[f64; N]; N], g0: &[f64; N], g1: &[f64; N], dt: f64) -> [f64; N] {
    let mut y = [0.0; N];
    let mut exc = Input { step: dt, k: 0 };
    let mut u = [0.0; 2];
    exc.fill(&mut u[..1]);
    for _ in 0..STEPS {
        exc.fill(&mut u[1..2]);
        let mut next: [f64; N] = std::array::from_fn(|i| g0[i] * u[0] + g1[i] * u[1]);
        for (col, yj) in cols.iter().zip(&y) {
            for (n, c) in next.iter_mut().zip(col) {
                *n += c * yj;
            }
        }
        y = next;
        u[0] = u[1];
    }
    y
}

#[target_feature(enable = "avx2")]
fn hand_loop_avx2(cols: &[[f64; N]; N], g0: &[f64; N], g1: &[f64; N], dt: f64) -> [f64; N] {
    hand_loop(cols, g0, g1, dt)
}

fn bench(c: &mut Criterion) {
    let model = catalog::resolve("seed001-full").unwrap();
    let dt = 1e-3;
    let mut group = c.benchmark_group("simulate_seed001_full");
    group.throughput(Throughput::Elements(STEPS));
    group.sample_size(10);
    // RK4 is explicit: 1 ms exceeds its stability limit on this seat (0.82 ms, set by a 541 Hz
    // overdamped mode), so it steps at 0.5 ms; both run 100 000 steps.
    for (name, method, dt) in [
        ("newmark", Method::AVERAGE_ACCELERATION, dt),
        ("rk4", Method::Rk4, 0.5 * dt),
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
                run(model.system(), &mut exc, &settings, &mut [], None).unwrap();
            })
        });
    }
    // Hand-written lower bound: y₊ = Φ·y + Γ₀·u + Γ₁·u₊ (18 states: x, v, a of 6 masses).
    let dynamics = wbv::system::Dynamics::new(model.system());
    let method = Method::AVERAGE_ACCELERATION;
    let mut newmark = wbv::integrator::build_stepping(method, &dynamics, model.system(), dt)
        .expect("linear model");
    let step =
        wbv::integrator::linear::LinearStep::probe(newmark.as_mut(), &dynamics, 2).expect("probe");
    let (phi, gamma) = (step.phi_matrix(), step.gamma_matrix());
    // Fixed-size arrays (every length known to the compiler), the product as a sum of columns
    // (independent lanes), compiled for AVX2 where the processor has it: the fastest plain loop
    // of this recursion we know how to write.
    assert_eq!(phi.nrows(), N, "seed001-full has 6 masses: 18 states");
    let cols: [[f64; N]; N] = std::array::from_fn(|j| std::array::from_fn(|i| phi[(i, j)]));
    let g0: [f64; N] = std::array::from_fn(|i| gamma[(i, 0)]);
    let g1: [f64; N] = std::array::from_fn(|i| gamma[(i, 1)]);
    let avx2 = std::arch::is_x86_feature_detected!("avx2");
    group.bench_function("hand_written_loop", |b| {
        b.iter(|| {
            let y = if avx2 {
                // SAFETY: the processor reports AVX2.
                unsafe { hand_loop_avx2(&cols, &g0, &g1, dt) }
            } else {
                hand_loop(&cols, &g0, &g1, dt)
            };
            black_box(y);
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
