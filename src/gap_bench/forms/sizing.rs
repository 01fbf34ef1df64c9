//! Sizing the truth forms: a link's r.m.s. deflection under the run's spectrum, Gaussian means for
//! tangent-stiffness targets, and the random draws — the truth side's own, independent of the
//! diagnosis's statistical linearisation.

use crate::error::Result;
use crate::model::{Chain, Element, Link, Mass, Node, Role};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// r.m.s. deflection and rate of a link (m, m/s), from the linear model's exact response to the
/// run's base spectrum, given as `(frequency Hz, mean square (m/s²)² in that line)` pairs.
pub fn link_sigma(model: &Chain, link: usize, lines: &[(f64, f64)]) -> Result<(f64, f64)> {
    let mut m = model.clone();
    for l in &mut m.links {
        l.law = None;
    }
    let (mut vd, mut vv) = (0.0, 0.0);
    // The linear model's exact FRF (crate::response::frf), not the diagnosis's predictor.
    let system = m.system();
    for &(f, ms) in lines {
        if f <= 0.0 || ms <= 0.0 {
            continue;
        }
        let xs = crate::response::frf::displacements(&system, f)?;
        let w2 = (2.0 * PI * f).powi(2);
        // Base-relative displacement per unit base acceleration (D(ω)·X = −M·r).
        let x = |n: Node| match n {
            Node::Base => num_complex::Complex64::new(0.0, 0.0),
            Node::Mass(i) => xs[i],
        };
        let l = &m.links[link];
        let d2 = (x(l.a) - x(l.b)).norm_sqr() * ms;
        vd += d2;
        vv += d2 * w2;
    }
    Ok((vd.sqrt(), vv.sqrt()))
}

/// E[g(σ z)] for z ~ N(0, 1): trapezoid rule on |z| ≤ 7, 2801 points (the truth side's own
/// quadrature, independent of the diagnosis's statistical linearisation).
pub fn gauss_mean(sigma: f64, g: impl Fn(f64) -> f64) -> f64 {
    const N: usize = 2801;
    let h = 14.0 / (N - 1) as f64;
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..N {
        let z = -7.0 + i as f64 * h;
        let w = (-0.5 * z * z).exp();
        num += w * g(sigma * z);
        den += w;
    }
    num / den
}

/// Bisection for the x in [lo, hi] where the increasing `f` crosses `target`.
pub(super) fn bisect(mut lo: f64, mut hi: f64, target: f64, f: impl Fn(f64) -> f64) -> f64 {
    for _ in 0..80 {
        let m = 0.5 * (lo + hi);
        if f(m) < target { lo = m } else { hi = m }
    }
    0.5 * (lo + hi)
}

pub(super) fn log_uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    (lo.ln() + rng.random::<f64>() * (hi.ln() - lo.ln())).exp()
}

pub(super) fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    lo + rng.random::<f64>() * (hi - lo)
}

/// A Kelvin–Voigt link from `a` to `b` tuned to `f_hz` with damping ratio `zeta` on a mass of
/// `m_kg`: k = m·(2πf)², c = 2ζ·m·2πf.
pub(super) fn tuned(
    name: &str,
    (a, b): (Node, Node),
    m_kg: f64,
    f_hz: f64,
    zeta: f64,
    role: Role,
) -> Link {
    let w = 2.0 * PI * f_hz;
    Link {
        name: name.into(),
        a,
        b,
        element: Element::KelvinVoigt {
            k: m_kg * w * w,
            c: 2.0 * zeta * m_kg * w,
        },
        law: None,
        role,
    }
}

/// Puts a frame mass `name` of `m_kg` under the cushion: the cushion link's base end moves to it.
/// Returns the mass's index (its own links to the base are the caller's).
pub(super) fn under_cushion(model: &mut Chain, name: &str, m_kg: f64) -> Result<usize> {
    let i = cushion(model)?;
    let j = model.masses.len();
    model.masses.push(Mass {
        name: name.into(),
        m: m_kg,
        role: Role::Frame,
    });
    let l = &mut model.links[i];
    if l.b == Node::Base {
        l.b = Node::Mass(j);
    } else if l.a == Node::Base {
        l.a = Node::Mass(j);
    }
    Ok(j)
}

pub(super) fn kv(model: &Chain, i: usize) -> (f64, f64) {
    match model.links[i].element {
        Element::KelvinVoigt { k, c } => (k, c),
        e => (e.static_stiffness(), e.parallel_damping()),
    }
}

/// Indices of the cushion link, the body–seat interface link and the heaviest body mass.
pub(super) fn cushion(model: &Chain) -> Result<usize> {
    model
        .links
        .iter()
        .position(|l| l.role == Role::Cushion)
        .ok_or_else(|| {
            crate::error::Error::parameter("model", "the bench's truth forms need a cushion link")
        })
}

pub(super) fn interface(model: &Chain) -> usize {
    model.measure.interface[0]
}

/// Sum of the static stiffnesses (N/m) of the links that end on mass `i`: the springs a path
/// planted on it acts beside.
pub(super) fn stiffness_on(model: &Chain, i: usize) -> f64 {
    model
        .links
        .iter()
        .filter(|l| l.a == Node::Mass(i) || l.b == Node::Mass(i))
        .map(|l| l.element.static_stiffness())
        .sum()
}

/// The body mass on the seat (the interface link's body end), for `form`'s error when the model
/// has none.
pub(super) fn seat_body(model: &Chain, form: &str) -> Result<usize> {
    match model.links[interface(model)].a {
        Node::Mass(i) => Ok(i),
        Node::Base => Err(crate::error::Error::parameter(
            form,
            "the bench's base model has no body mass on the seat",
        )),
    }
}
