//! Nonlinear links: the Newton iterations of Newmark and the explicit RK4 must converge to the same
//! trajectory, and the laws must behave as their physics says.

use wbv::integrator::Method;
use wbv::model::{Model, catalog};
use wbv::simulate::observer::{Layout, Observer, Step};
use wbv::simulate::{Settings, run};

mod common;
use common::Sine;

#[derive(Default)]
struct Head(Vec<f64>, Option<usize>);

impl Observer for Head {
    fn begin(&mut self, l: &Layout) -> wbv::Result<()> {
        self.1 = l.masses.iter().position(|m| m == "head");
        Ok(())
    }
    fn step(&mut self, s: &Step<'_>) -> wbv::Result<()> {
        self.0.push(s.x[self.1.unwrap()]);
        Ok(())
    }
    fn end(&mut self) -> wbv::Result<()> {
        Ok(())
    }
}

fn model_with(law: &str) -> Model {
    let text = format!(
        r#"
name = "nl"
description = "body mass on a nonlinear cushion"
[[mass]]
name = "head"
m = 8.0
[[mass]]
name = "body"
m = 50.0
[[link]]
name = "spine"
between = ["head", "body"]
type = "kelvin-voigt"
k = 150000.0
c = 600.0
[[link]]
name = "cushion"
between = ["body", "base"]
type = "kelvin-voigt"
k = 60000.0
c = 900.0
{law}
[measure]
seat = "base"
head = "head"
interface = ["cushion"]
"#
    );
    catalog::parse(&text, "nl.toml").unwrap()
}

fn head_motion(model: &Model, method: Method, dt: f64, amp: f64, f: f64, dur: f64) -> Vec<f64> {
    let settings = Settings {
        dt,
        duration_s: dur,
        method,
    };
    let mut exc = Sine::new(amp, f, settings.excitation_step());
    let mut head = Head::default();
    run(model.system(), &mut exc, &settings, &mut [&mut head], None).unwrap();
    head.0
}

const LAWS: [&str; 4] = [
    "[link.law]\ntype = \"cubic\"\nk3 = 2e10",
    "[link.law]\ntype = \"softening\"\nd_ref = 0.002",
    "[link.law]\ntype = \"friction\"\nf_c = 40.0\nv_ref = 0.005",
    "[link.law]\ntype = \"end-stop\"\ngap = 0.003\nk_stop = 400000.0",
];

#[test]
fn newmark_newton_and_rk4_agree_on_every_law() {
    for law in LAWS {
        let model = model_with(law);
        let dt = 1e-4;
        let nm = head_motion(&model, Method::AVERAGE_ACCELERATION, dt, 4.0, 3.5, 2.0);
        let rk = head_motion(&model, Method::Rk4, dt, 4.0, 3.5, 2.0);
        let peak = nm.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = nm
            .iter()
            .zip(&rk)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        eprintln!("{law}: peak {peak:.3e} m, max difference {diff:.3e} m");
        assert!(peak > 1e-3, "the law must be exercised: peak {peak}");
        assert!(
            diff < 1e-4 * peak,
            "{law}: Newmark and RK4 differ by {diff:.3e} m"
        );
    }
}

#[test]
fn newmark_converges_at_second_order_on_a_nonlinear_model() {
    let model = model_with(LAWS[0]);
    let reference = head_motion(&model, Method::Rk4, 2.5e-5, 4.0, 3.5, 1.0);
    let errs: Vec<f64> = [2e-3, 1e-3, 5e-4]
        .iter()
        .map(|&dt| {
            let x = head_motion(&model, Method::AVERAGE_ACCELERATION, dt, 4.0, 3.5, 1.0);
            (x.last().unwrap() - reference.last().unwrap()).abs()
        })
        .collect();
    let order1 = (errs[0] / errs[1]).log2();
    let order2 = (errs[1] / errs[2]).log2();
    eprintln!("errors {errs:?}, orders {order1:.2} {order2:.2}");
    assert!(
        (order1 - 2.0).abs() < 0.3 && (order2 - 2.0).abs() < 0.3,
        "{errs:?}"
    );
}

#[test]
fn hardening_stiffens_and_softening_softens_with_amplitude() {
    // Ratio of head response at large and small input: a linear model gives 1 after scaling.
    let ratio = |law: &str| {
        let model = model_with(law);
        let small = head_motion(&model, Method::AVERAGE_ACCELERATION, 5e-4, 0.05, 3.0, 6.0);
        let large = head_motion(&model, Method::AVERAGE_ACCELERATION, 5e-4, 5.0, 3.0, 6.0);
        let amp = |x: &[f64]| x[x.len() / 2..].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        amp(&large) / (100.0 * amp(&small))
    };
    let linear = ratio("");
    assert!((linear - 1.0).abs() < 1e-6, "linear model scales: {linear}");
    // Below resonance (3 Hz < ≈ 5 Hz) a stiffer spring moves less; a softer one, nearer resonance, more.
    let hard = ratio(LAWS[0]);
    let soft = ratio(LAWS[1]);
    eprintln!("amplitude ratio: hardening {hard:.3}, softening {soft:.3}");
    assert!(hard < 0.98, "hardening: {hard}");
    assert!(soft > 1.02, "softening: {soft}");
}
