//! Planar model core: the analytic gradient and Hessian of the potential against finite
//! differences, symmetry of M and K, static equilibrium sums, modes = eig(M⁻¹K).

use wbv::model::catalog;
use wbv::model::planar::equilibrium::{gradient, potential};
use wbv::model::planar::file::parse_spec;
use wbv::model::planar::linearise::{mass, stiffness};

const TEXT: &str = include_str!("../models/planar-occupant.toml");

fn spec() -> wbv::model::planar::Spec {
    parse_spec(TEXT, "planar-occupant.toml").unwrap().0
}

type Coefficients = Vec<wbv::model::planar::contact::Coefficients>;

/// A non-trivial configuration and plausible contact coefficients.
fn probe(spec: &wbv::model::planar::Spec) -> (Vec<f64>, Coefficients) {
    let n = spec.posture.dof();
    let q: Vec<f64> = (0..n)
        .map(|i| 0.01 * ((i as f64) * 1.7 + 0.3).sin())
        .collect();
    let coef = spec
        .contacts
        .iter()
        .enumerate()
        .map(|(i, _)| (3e4 + 1e4 * i as f64, 1e4 + 2e3 * i as f64, 0.0, 0.0))
        .collect();
    (q, coef)
}

#[test]
fn gradient_and_hessian_match_finite_differences_of_the_potential() {
    let spec = spec();
    let (q, coef) = probe(&spec);
    let n = q.len();
    let g = gradient(&spec, &coef, &q);
    let k = stiffness(&spec, &coef, &q);
    let h = 1e-6;
    for i in 0..n {
        let mut qp = q.clone();
        let mut qm = q.clone();
        qp[i] += h;
        qm[i] -= h;
        let fd = (potential(&spec, &coef, &qp) - potential(&spec, &coef, &qm)) / (2.0 * h);
        assert!(
            (fd - g[i]).abs() < 1e-6 * g[i].abs().max(1.0),
            "∂V/∂q{i}: fd {fd} vs {}",
            g[i]
        );
        let gp = gradient(&spec, &coef, &qp);
        let gm = gradient(&spec, &coef, &qm);
        for j in 0..n {
            let fd = (gp[j] - gm[j]) / (2.0 * h);
            assert!(
                (fd - k[(j, i)]).abs() < 1e-6 * k[(j, i)].abs().max(10.0),
                "K[{j},{i}]: fd {fd} vs {}",
                k[(j, i)]
            );
        }
    }
}

#[test]
fn mass_and_stiffness_are_symmetric_and_mass_is_positive_definite() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let l = &model.planar().unwrap().linear;
    for (name, m) in [("M", &l.m), ("K", &l.k), ("C", &l.c)] {
        let asym = (m - m.transpose()).amax();
        assert!(asym <= 1e-9 * m.amax(), "{name} asymmetric by {asym}");
    }
    assert!(l.m.clone().cholesky().is_some());
    // M at zero pitch rates: the total mass sits on the translational coordinates.
    let total = model.planar().unwrap().spec.body_mass();
    assert!((l.m[(0, 0)] - total).abs() < 1e-9 && (l.m[(1, 1)] - total).abs() < 1e-9);
    let _ = mass;
}

fn planar() -> wbv::model::planar::Planar {
    catalog::resolve("planar-occupant")
        .unwrap()
        .planar()
        .unwrap()
        .clone()
}

#[test]
fn static_equilibrium_balances_weight_and_moments() {
    let p = planar();
    let eq = &p.equilibrium;
    let spec = &p.spec;
    // Weight from the segments, independently of the solver.
    let weight: f64 = spec.posture.segments.iter().map(|s| s.m * 9.81).sum();
    assert!((eq.weight - weight).abs() < 1e-9 * weight);
    let f = eq.total_force();
    assert!(f[0].abs() < 1e-8 * weight, "ΣFx = {}", f[0]);
    assert!(
        (f[1] - weight).abs() < 1e-8 * weight,
        "ΣFz = {} vs W = {weight}",
        f[1]
    );
    // Seat (cushion), backrest and footrest together carry the weight.
    let by_role: f64 = ["cushion", "backrest", "footrest"]
        .iter()
        .map(|r| eq.vertical_load(r))
        .sum();
    assert!((by_role - weight).abs() < 1e-8 * weight);
    // Moments: gravity acting at the segments' centres of mass at equilibrium.
    let pl = spec.posture.place(&eq.q);
    let gravity: f64 = spec
        .posture
        .segments
        .iter()
        .enumerate()
        .map(|(s, seg)| seg.m * 9.81 * spec.posture.point(&pl, s, seg.com)[0])
        .sum();
    assert!(
        (eq.contact_moment() + gravity).abs() < 1e-8 * weight,
        "moment residual"
    );
    // Every support pushes, and each carries a share: the cushion most, the backrest some.
    for l in &eq.loads {
        assert!(l.normal > 0.0, "{} pulls", l.name);
    }
    assert!(eq.vertical_load("cushion") > 0.5 * weight);
    assert!(eq.vertical_load("backrest") > 0.02 * weight);
}

#[test]
fn modes_are_the_eigenvalues_of_m_inverse_k() {
    let p = planar();
    let l = &p.linear;
    let modes = wbv::response::modes::generalized(&l.m, &l.k).unwrap();
    let a = l.m.clone().try_inverse().unwrap() * &l.k;
    let mut eig: Vec<f64> = a
        .complex_eigenvalues()
        .iter()
        .map(|e| {
            assert!(e.im.abs() < 1e-6 * e.re.abs(), "complex eigenvalue {e}");
            e.re.sqrt() / (2.0 * std::f64::consts::PI)
        })
        .collect();
    eig.sort_by(f64::total_cmp);
    assert_eq!(eig.len(), modes.len());
    for (m, e) in modes.iter().zip(&eig) {
        assert!((m.freq_hz - e).abs() < 1e-6 * e, "{} vs {e}", m.freq_hz);
        let phi = nalgebra::DVector::from_column_slice(&m.shape);
        let w2 = (2.0 * std::f64::consts::PI * m.freq_hz).powi(2);
        let res = &l.k * &phi - &l.m * &phi * w2;
        assert!(res.amax() < 1e-7 * (&l.k * &phi).amax());
    }
    // All stable at the seated equilibrium, and the words name the paper's kinds of motion.
    assert!(modes[0].freq_hz > 0.5);
    let described = wbv::response::modes::describe(&p.system()).unwrap();
    assert!(
        described
            .iter()
            .any(|d| d.words().contains("fore-and-aft head"))
    );
    assert!(
        described
            .iter()
            .any(|d| d.words().contains("vertical whole-body"))
    );
}

#[test]
fn bad_planar_files_name_the_key_and_expectation() {
    let bad = |from: &str, to: &str| {
        let text = TEXT.replacen(from, to, 1);
        assert_ne!(text, TEXT, "replacement `{from}` not found");
        wbv::model::catalog::parse(&text, "bad.toml")
            .unwrap_err()
            .to_string()
    };
    let e = bad("k = 2080.0", "k = -2080.0");
    assert!(e.contains("joint[1] (waist).k") && e.contains("≥ 0"), "{e}");
    let e = bad("segment = \"thighs\"", "segment = \"tail\"");
    assert!(
        e.contains("contact[1] (thigh).segment") && e.contains("unknown segment"),
        "{e}"
    );
    let e = bad("anthropometry = \"thighs\"", "anthropometry = \"wings\"");
    assert!(
        e.contains("anthropometry") && e.contains("legs-feet"),
        "{e}"
    );
    let e = bad("cushion_share = 0.4", "cushion_share = 0.6");
    assert!(e.contains("shares add up to 1.2"), "{e}");
    // A footrest pushing downwards would have to pull the feet: refused at equilibrium.
    let e = bad(
        "at = [0.72, -0.275]\nnormal_deg = 90.0",
        "at = [0.72, -0.275]\nnormal_deg = -90.0",
    );
    assert!(e.contains("footrest") && e.contains("compression"), "{e}");
    let e = bad("thickness = 0.08", "thickness = \"thick\"");
    assert!(e.starts_with("bad.toml: line"), "{e}");
    let mut model = catalog::resolve("planar-occupant").unwrap();
    let e = model.set("joint.elbow.k", 1.0).unwrap_err().to_string();
    assert!(
        e.contains("joint.elbow.k") && e.contains("unknown planar parameter"),
        "{e}"
    );
    let e = model.set("cushion.area", 0.0).unwrap_err().to_string();
    assert!(e.contains("> 0"), "{e}");
    assert!(catalog::resolve("planar-occupant+cushion-zener").is_err());
}
