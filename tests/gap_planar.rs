//! `wbv gap` on the planar segment model (issues 15 and 21): the diagnosis acts on the system any
//! model kind builds, so a foam effect planted under the `planar-occupant`'s contacts is named,
//! with the fore-and-aft paths (`a_seat_x`, `a_head_x`) judged beside the vertical ones.
//!
//! Truth data: the planar model with its segment masses and joint stiffness off by a few per cent
//! (a real subject is never the model's), a foam relaxation planted as a standard linear solid on
//! the contacts' *normal* axes only with its own relaxation time and a lower parallel damping —
//! not the candidate's form, which puts one Maxwell arm of one ratio on every cushion axis —
//! simulated in the time domain at 2 kHz, sampled at 500 Hz and measured with 1 % noise. A second
//! foam has a broad log-normal relaxation spectrum (fourteen Maxwell arms), a form outside both
//! viscoelastic candidates (one arm; a power law).

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use wbv::diagnosis::{VerdictId, diagnose};
use wbv::excitation::{ExcitationSpec, Kind};
use wbv::integrator::Method;
use wbv::model::{Model, catalog};
use wbv::signals::Signals;
use wbv::simulate::collect::Collector;
use wbv::simulate::{self, Settings};
use wbv::system::{Element, Link, System};

const FS_SIM: f64 = 2000.0;
const DECIMATE: usize = 4;

/// The subject: segment masses and joint stiffness scattered about the model's.
fn subject(model: &Model, rng: &mut ChaCha8Rng) -> Model {
    let values: Vec<(String, f64)> = model
        .params()
        .into_iter()
        .filter(|p| p.starts_with("segment.") && p.ends_with(".m") || p.starts_with("joint."))
        .map(|p| {
            let v = model.get(&p).unwrap();
            (p, v * (1.0 + rng.random_range(-0.06..0.06)))
        })
        .collect();
    model.with_values(&values).unwrap()
}

/// A standard linear solid under each cushion contact: a Maxwell arm of stiffness `ratio`·k
/// (`ratio.0` in compression, the normal axes, `ratio.1` in shear) and relaxation time `tau_s`,
/// and the compression axes' parallel damping scaled by `c_scale`.
fn plant_sls(system: &mut System, ratio: (f64, f64), tau_s: f64, c_scale: f64) {
    let cushion: Vec<usize> = (0..system.links.len())
        .filter(|&i| system.links[i].role == wbv::system::Role::Cushion)
        .collect();
    assert_eq!(
        cushion.len(),
        4,
        "ischial and thigh contacts, two axes each"
    );
    for i in cushion {
        let l = system.links[i].clone();
        let Element::KelvinVoigt { k, c } = l.element else {
            panic!("contact axes are Kelvin–Voigt")
        };
        let normal = l.name.ends_with("_n");
        let r = if normal { ratio.0 } else { ratio.1 };
        if normal {
            system.links[i].element = Element::KelvinVoigt { k, c: c * c_scale };
        }
        system.links.push(Link {
            name: format!("{}-relaxation", l.name),
            element: Element::Maxwell {
                k: r * k,
                c: r * k * tau_s,
            },
            record_deflection: false,
            ..l
        });
    }
}

/// A foam with a broad relaxation spectrum under each cushion contact: Maxwell arms with
/// relaxation times three per decade over 0.05–500 Hz whose stiffnesses follow a log-normal
/// spectrum, k_j ∝ exp(−ln²(τ_j/τ_c)/(2σ²)) with τ_c = 1/(2π·`f_c_hz`) and σ = `width` decades
/// (a Cole–Cole-like foam), scaled so that their storage stiffness at 5 Hz is `share.0`·k on the
/// normal axes and `share.1`·k in shear; the normal axes' parallel damping scaled by `c_scale`.
/// Neither the single-arm candidate, nor the fractional candidate's power law, nor the
/// Havriliak–Negami candidate's power-law flanks (its arms sit on the same grid, its weights
/// differ), nor the bench's least-squares Prony fit.
fn plant_broad(system: &mut System, f_c_hz: f64, width: f64, share: (f64, f64), c_scale: f64) {
    let w5 = 2.0 * std::f64::consts::PI * 5.0;
    let taus: Vec<f64> = (0..=13)
        .map(|j| 1.0 / (2.0 * std::f64::consts::PI * 0.05 * 10f64.powf(j as f64 / 3.0)))
        .collect();
    let tau_c = 1.0 / (2.0 * std::f64::consts::PI * f_c_hz);
    let sigma = width * std::f64::consts::LN_10;
    let weight = |t: f64| (-(t / tau_c).ln().powi(2) / (2.0 * sigma * sigma)).exp();
    // Storage stiffness at 5 Hz of arms with unit scale.
    let storage: f64 = taus
        .iter()
        .map(|&t| weight(t) * (w5 * t).powi(2) / (1.0 + (w5 * t).powi(2)))
        .sum();
    let cushion: Vec<usize> = (0..system.links.len())
        .filter(|&i| system.links[i].role == wbv::system::Role::Cushion)
        .collect();
    for i in cushion {
        let l = system.links[i].clone();
        let Element::KelvinVoigt { k, c } = l.element else {
            panic!("contact axes are Kelvin–Voigt")
        };
        let normal = l.name.ends_with("_n");
        let a = if normal { share.0 } else { share.1 } * k / storage;
        if normal {
            system.links[i].element = Element::KelvinVoigt { k, c: c * c_scale };
        }
        for (j, &t) in taus.iter().enumerate() {
            let kj = a * weight(t);
            system.links.push(Link {
                name: format!("{}-arm{j}", l.name),
                element: Element::Maxwell { k: kj, c: kj * t },
                record_deflection: false,
                ..l.clone()
            });
        }
    }
}

/// One measured run of `system`: random base of r.m.s. `rms` (m/s²) over 0.5–40 Hz for
/// `duration_s`, every measured channel with 1 % noise, at 500 Hz.
fn run(system: &System, rms: f64, duration_s: f64, seed: u64) -> Signals {
    let spec = ExcitationSpec::new(
        Kind::Random {
            rms_m_s2: rms,
            band_hz: [0.5, 40.0],
        },
        "test base",
    )
    .unwrap();
    let settings = Settings {
        dt: 1.0 / FS_SIM,
        duration_s,
        method: Method::AVERAGE_ACCELERATION,
    };
    let mut exc = spec.build(settings.dt, duration_s, seed).unwrap();
    let mut col = Collector::new();
    simulate::run(system, exc.as_mut(), &settings, &mut [&mut col], None).unwrap();
    let full = col.into_signals("planar truth").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let mut out = Signals::new(FS_SIM / DECIMATE as f64, format!("planar run {seed}"));
    for (name, x) in full.names.iter().zip(&full.data) {
        let sd = 0.01 * wbv::analysis::figures::rms(x);
        let y: Vec<f64> = x
            .iter()
            .step_by(DECIMATE)
            .map(|v| v + sd * rng.sample::<f64, _>(StandardNormal))
            .collect();
        out.push(name.clone(), y).unwrap();
    }
    out
}

fn runs(system: &System) -> (Vec<Signals>, Signals) {
    let train = vec![run(system, 0.6, 60.0, 11), run(system, 1.4, 60.0, 12)];
    (train, run(system, 1.0, 60.0, 13))
}

#[test]
fn planar_cushion_relaxation_is_named_with_fore_and_aft_paths_judged() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut truth = subject(&model, &mut rng).system().clone();
    plant_sls(&mut truth, (0.6, 0.25), 0.03, 0.8);
    let (train, check) = runs(&truth);
    let t0 = std::time::Instant::now();
    let d = diagnose(&model, &train, &check).unwrap();
    eprintln!(
        "{}\n({:.1} s)",
        wbv::diagnosis::report::text(&d),
        t0.elapsed().as_secs_f64()
    );
    let paths: Vec<&str> = d.bands.iter().map(|b| b.path).collect();
    for p in [
        "base-seat",
        "seat-head",
        "apparent-mass",
        "base-seat-x",
        "base-head-x",
    ] {
        assert!(paths.contains(&p), "path {p} judged: {paths:?}");
    }
    // Neither candidate is the truth's standard linear solid: a named effect must bring the check
    // run's a_w and SEAT toward the measurement (within the practically-small 1 % and 1 point),
    // else the verdict is `unexplained` with the foam as the best partial candidate.
    let foam = |id: &str| {
        matches!(
            id,
            "cushion-viscoelastic" | "cushion-fractional" | "cushion-havriliak-negami"
        )
    };
    match d.named_stage() {
        Some(with) => {
            assert!(foam(d.named[0].id), "{}", d.verdict_text);
            let (n, w) = (&d.null.check.weighted, &with.weighted);
            assert!(
                w.aw_gap_percent.abs() < n.aw_gap_percent.abs() + 1.0,
                "{}",
                d.verdict_text
            );
            assert!(
                w.seat_gap_points().abs() < n.seat_gap_points().abs() + 1.0,
                "{}",
                d.verdict_text
            );
        }
        None => {
            assert_eq!(d.verdict, VerdictId::Unexplained, "{}", d.verdict_text);
            assert!(foam(&d.partial[0].id.to_string()), "{:?}", d.partial);
            assert!(
                d.verdict_text.contains("Partial candidates"),
                "{}",
                d.verdict_text
            );
        }
    }
}

#[test]
fn planar_clean_seat_with_another_subject_is_none() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let truth = subject(&model, &mut rng).system().clone();
    let (train, check) = runs(&truth);
    let d = diagnose(&model, &train, &check).unwrap();
    eprintln!("{}", wbv::diagnosis::report::text(&d));
    assert_eq!(d.verdict, VerdictId::None, "{}", d.verdict_text);
}

#[test]
fn planar_broad_relaxation_foam_is_named_viscoelastic() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut truth = subject(&model, &mut rng).system().clone();
    plant_broad(&mut truth, 3.0, 0.8, (0.5, 0.2), 0.6);
    let (train, check) = runs(&truth);
    let d = diagnose(&model, &train, &check).unwrap();
    eprintln!("{}", wbv::diagnosis::report::text(&d));
    // The family, whichever of its forms fits best: one Maxwell arm and the Havriliak–Negami
    // spectrum both approximate a symmetric log-normal spectrum; neither is its form.
    assert_eq!(
        d.named.first().map(|c| c.family),
        Some(wbv::diagnosis::candidate::Family::CushionViscoelasticity),
        "{}",
        d.verdict_text
    );
    // And it brings the check run's a_w toward the measurement against the re-fitted model.
    let with = d.named_stage().expect("a named effect");
    assert!(
        with.weighted.aw_gap_percent.abs() < d.null.check.weighted.aw_gap_percent.abs(),
        "{}",
        d.verdict_text
    );
}
