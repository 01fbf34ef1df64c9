//! The step matrix of a linear model ([`wbv::integrator::linear::LinearStep`]): its eigenvalues
//! are the integrators' closed-form amplification factors on a single oscillator, and stepping
//! with it equals stepping the integrators themselves to round-off on every linear built-in model
//! (Maxwell and Zener arms, the planar model) for both integrators.

use num_complex::Complex64;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use wbv::integrator::linear::LinearStep;
use wbv::integrator::{Integrator, Method, State, build, build_stepping};
use wbv::model::catalog;
use wbv::system::Dynamics;

/// Undamped single oscillator, ω = √(k/m).
fn oscillator(m: f64, k: f64) -> wbv::model::Model {
    let text = format!(
        "name = \"sdof\"\ndescription = \"d\"\n[[mass]]\nname = \"a\"\nm = {m}\n\
         [[link]]\nname = \"s\"\nbetween = [\"a\", \"base\"]\ntype = \"kelvin-voigt\"\nk = {k}\nc = 0.0\n\
         [measure]\nseat = \"base\"\nhead = \"a\"\ninterface = [\"s\"]\n"
    );
    catalog::parse(&text, "sdof.toml").unwrap()
}

/// Eigenvalues of the `[x, v, a]` step matrix of the oscillator under `method`.
fn eigenvalues(method: Method, m: f64, k: f64, dt: f64) -> Vec<Complex64> {
    let model = oscillator(m, k);
    let dynamics = Dynamics::new(model.system());
    let mut inner = build_stepping(method, &dynamics, model.system(), dt).unwrap();
    let step = LinearStep::probe(inner.as_mut(), &dynamics, method.substeps() + 1).unwrap();
    step.phi_matrix()
        .complex_eigenvalues()
        .iter()
        .copied()
        .collect()
}

#[test]
fn newmark_average_acceleration_step_is_the_cayley_rotation() {
    // Trapezoidal rule on ẍ = −ω²x: |λ| = 1 (no numerical damping) and the phase per step is
    // θ = 2·atan(ω·dt/2) (period elongation); the acceleration, a function of x, adds λ = 0.
    let (m, k, dt): (f64, f64, f64) = (2.0, 8.0e4, 1.0e-3);
    let w: f64 = (k / m).sqrt();
    let theta = 2.0 * (0.5 * w * dt).atan();
    let mut lam = eigenvalues(Method::AVERAGE_ACCELERATION, m, k, dt);
    lam.sort_by(|a, b| a.norm().total_cmp(&b.norm()));
    // Tolerances: eigenvalues of a matrix mixing m and m/s² entries (ω² = 4e4) are accurate to
    // about ε·‖Φ‖ ≈ 1e-11.
    assert!(lam[0].norm() < 1e-8, "{lam:?}");
    for l in &lam[1..] {
        assert!((l.norm() - 1.0).abs() < 1e-8, "{lam:?}");
        assert!((l.arg().abs() - theta).abs() < 1e-8, "{l} vs θ = {theta}");
    }
}

#[test]
fn rk4_step_is_the_fourth_order_taylor_polynomial() {
    // RK4 on ẏ = A·y multiplies each mode by R(z) = 1 + z + z²/2 + z³/6 + z⁴/24, z = ±iω·dt.
    let (m, k, dt): (f64, f64, f64) = (2.0, 8.0e4, 2.0e-3);
    let z = Complex64::new(0.0, (k / m).sqrt() * dt);
    let r = 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0;
    let lam = eigenvalues(Method::Rk4, m, k, dt);
    for expect in [r, r.conj()] {
        let best = lam
            .iter()
            .map(|l| (l - expect).norm())
            .fold(f64::INFINITY, f64::min);
        // ε·‖Φ‖ as above.
        assert!(best < 1e-8, "R = {expect}, eigenvalues {lam:?}");
    }
}

/// Steps `a` and `b` side by side on the same random input; the largest state difference
/// relative to the largest state value.
fn divergence(a: &mut dyn Integrator, b: &mut dyn Integrator, d: &Dynamics, inputs: usize) -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut u = vec![0.0; inputs];
    u[0] = rng.random_range(-1.0..1.0);
    let (mut sa, mut sb) = (State::at_rest(d, u[0]), State::at_rest(d, u[0]));
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for step in 0..20_000 {
        for v in &mut u[1..] {
            *v = rng.random_range(-1.0..1.0);
        }
        let t = step as f64;
        a.advance(&mut sa, &u, t).unwrap();
        b.advance(&mut sb, &u, t).unwrap();
        for (pa, pb) in [
            (&sa.x, &sb.x),
            (&sa.v, &sb.v),
            (&sa.a, &sb.a),
            (&sa.q, &sb.q),
            (&sa.qdot, &sb.qdot),
        ] {
            for (x, y) in pa.iter().zip(pb.iter()) {
                worst = worst.max((x - y).abs());
                scale = scale.max(x.abs());
            }
        }
        u[0] = u[inputs - 1];
    }
    assert!(scale > 0.0);
    worst / scale
}

#[test]
fn step_matrix_equals_the_integrators_to_round_off() {
    for name in [
        "reference",
        "seed001-full",
        "seed002-maxwell",
        "boileau-rakheja-4dof+cushion-zener",
        "planar-occupant",
    ] {
        let model = catalog::resolve(name).unwrap();
        let dynamics = Dynamics::new(model.system());
        assert!(!dynamics.is_nonlinear(), "{name}");
        for (method, dt) in [(Method::AVERAGE_ACCELERATION, 1e-3), (Method::Rk4, 2e-4)] {
            let mut fast = build(method, &dynamics, model.system(), dt).unwrap();
            let mut slow = build_stepping(method, &dynamics, model.system(), dt).unwrap();
            let err = divergence(
                fast.as_mut(),
                slow.as_mut(),
                &dynamics,
                method.substeps() + 1,
            );
            assert!(
                err < 1e-10,
                "{name} {method:?}: relative difference {err:e}"
            );
        }
    }
}
