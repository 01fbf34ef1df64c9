//! Frequency-domain responses checked against closed-form solutions worked by hand.

use num_complex::Complex64;
use std::f64::consts::PI;
use wbv::model::catalog;
use wbv::response::{frf, modes};

fn one_dof(element: &str) -> wbv::model::Model {
    let text = format!(
        r#"
name = "sdof"
description = "one mass on one link"
[[mass]]
name = "m"
m = 50.0
[[link]]
name = "l"
between = ["m", "base"]
{element}
[measure]
seat = "base"
head = "m"
interface = ["l"]
"#
    );
    catalog::parse(&text, "sdof.toml").unwrap()
}

fn close(a: Complex64, b: Complex64, rel: f64) -> bool {
    (a - b).norm() <= rel * b.norm().max(1e-12)
}

#[test]
fn one_dof_transmissibility_and_phase() {
    let (m, k, c) = (50.0, 40_000.0, 300.0);
    let model = one_dof(&format!("type = \"kelvin-voigt\"\nk = {k}\nc = {c}"));
    let freqs = frf::grid(0.1, 40.0, 300, true).unwrap();
    let set = frf::compute(model.system(), &freqs).unwrap();
    let stht = set.get("stht").unwrap();
    for (f, t) in freqs.iter().zip(&stht.values) {
        let w = 2.0 * PI * f;
        // T = (k + iωc) / (k − mω² + iωc)
        let expect = Complex64::new(k, w * c) / Complex64::new(k - m * w * w, w * c);
        assert!(close(*t, expect, 1e-10), "{f} Hz: {t} vs {expect}");
    }
    // Phase at resonance of the undamped system: arg T = atan(ωc/k) − π/2 exactly.
    let fn_ = (k / m).sqrt() / (2.0 * PI);
    let set = frf::compute(model.system(), &[fn_]).unwrap();
    let w = 2.0 * PI * fn_;
    let phase = set.get("stht").unwrap().phase_deg()[0];
    let expect = ((w * c / k).atan() - PI / 2.0).to_degrees();
    assert!((phase - expect).abs() < 1e-9, "{phase} vs {expect}");
}

#[test]
fn maxwell_and_zener_one_dof_match_their_complex_stiffness() {
    let m = 50.0;
    fn maxwell(w: f64) -> Complex64 {
        let iwc = Complex64::new(0.0, w * 900.0);
        40_000.0 * iwc / (40_000.0 + iwc)
    }
    fn zener(w: f64) -> Complex64 {
        let iwc = Complex64::new(0.0, w * 700.0);
        20_000.0 + 30_000.0 * iwc / (30_000.0 + iwc)
    }
    type Stiffness = fn(f64) -> Complex64;
    let cases: [(&str, Stiffness); 2] = [
        ("type = \"maxwell\"\nk = 40000.0\nc = 900.0", maxwell),
        (
            "type = \"zener\"\nk = 20000.0\nk_m = 30000.0\nc_m = 700.0",
            zener,
        ),
    ];
    for (spec, kstar) in cases {
        let model = one_dof(spec);
        for f in [0.5, 2.0, 4.7, 9.0, 25.0] {
            let w = 2.0 * PI * f;
            let t = frf::compute(model.system(), &[f])
                .unwrap()
                .get("stht")
                .unwrap()
                .values[0];
            let ks = kstar(w);
            let expect = ks / (ks - m * w * w);
            assert!(close(t, expect, 1e-10), "{spec} at {f} Hz");
        }
    }
}

#[test]
fn two_dof_chain_solved_by_hand() {
    // m1 on k1,c1 on m2 on k2,c2 on the base. Absolute motion z1, z2 per unit base motion:
    // [k1* + k2* − m2ω², −k1*; −k1*, k1* − m1ω²]·[z2; z1] = [k2*; 0]  (k* = k + iωc), solved by
    // Cramer's rule, with transmissibility = absolute acceleration ratio = displacement ratio.
    let (m1, k1, c1, m2, k2, c2) = (6.0, 120_000.0, 350.0, 30.0, 60_000.0, 1_500.0);
    let text = format!(
        r#"
name = "chain2"
description = "two-mass chain"
[[mass]]
name = "top"
m = {m1}
[[mass]]
name = "bottom"
m = {m2}
[[link]]
name = "upper"
between = ["top", "bottom"]
type = "kelvin-voigt"
k = {k1}
c = {c1}
[[link]]
name = "lower"
between = ["bottom", "base"]
type = "kelvin-voigt"
k = {k2}
c = {c2}
[measure]
seat = "base"
head = "top"
interface = ["lower"]
"#
    );
    let model = catalog::parse(&text, "chain2.toml").unwrap();
    for f in [0.3, 1.0, 3.3, 6.0, 11.0, 30.0] {
        let w = 2.0 * PI * f;
        let k1s = Complex64::new(k1, w * c1);
        let k2s = Complex64::new(k2, w * c2);
        let a11 = k1s + k2s - m2 * w * w;
        let a12 = -k1s;
        let a22 = k1s - m1 * w * w;
        let det = a11 * a22 - a12 * a12;
        let z2 = k2s * a22 / det;
        let z1 = -a12 * k2s / det;
        let set = frf::compute(model.system(), &[f]).unwrap();
        assert!(close(set.get("t_top").unwrap().values[0], z1, 1e-10));
        assert!(close(set.get("t_bottom").unwrap().values[0], z2, 1e-10));
        // Apparent mass: the lower link's compression force on the body per unit base
        // acceleration, F = k2*·(X_b − X_2) with displacement X = A/(−ω²) and A_b = 1.
        let force = k2s * (1.0 - z2) / (-w * w);
        let am = set.get("apms").unwrap().values[0];
        assert!(close(am, force, 1e-9), "{am} vs {force}");
        // Newton: the interface force accelerates both masses: F = m1·A1 + m2·A2.
        assert!(
            close(am, m1 * z1 + m2 * z2, 1e-9),
            "{am} vs {}",
            m1 * z1 + m2 * z2
        );
    }
}

#[test]
fn apparent_mass_static_limit_and_impedance_relation() {
    for model in catalog::all().unwrap() {
        let Some(chain) = model.chain() else {
            continue;
        };
        if chain.measure.interface.is_empty() {
            continue;
        }
        let set = frf::compute(model.system(), &[1e-4, 3.0, 7.5]).unwrap();
        let am = set.get("apms").unwrap();
        let dpmi = set.get("dpmi").unwrap();
        let supported = chain.supported_mass();
        let has_maxwell = chain
            .links
            .iter()
            .any(|l| matches!(l.element, wbv::model::Element::Maxwell { .. }));
        if !has_maxwell {
            assert!(
                (am.values[0].norm() - supported).abs() < 1e-4 * supported,
                "{}: AM(0) {} vs supported {supported}",
                model.name,
                am.values[0]
            );
        }
        for (i, f) in set.freq_hz.iter().enumerate() {
            let expect = Complex64::new(0.0, 2.0 * PI * f) * am.values[i];
            assert!(close(dpmi.values[i], expect, 1e-12), "{}", model.name);
        }
    }
    let br = catalog::resolve("boileau-rakheja-4dof").unwrap();
    assert!((br.chain().unwrap().supported_mass() - 55.2).abs() < 1e-9);
}

#[test]
fn undamped_modes_are_eigenvalues_of_m_inv_k() {
    // Two-mass chain: det(K − ω²M) = 0 gives
    // m1 m2 λ² − (m1 (k1 + k2) + m2 k1) λ + k1 k2 = 0, λ = ω².
    let (m1, k1, m2, k2): (f64, f64, f64, f64) = (5.0, 300_000.0, 40.0, 90_000.0);
    let text = format!(
        "name = \"c\"\ndescription = \"d\"\n[[mass]]\nname = \"a\"\nm = {m1}\n[[mass]]\nname = \"b\"\nm = {m2}\n\
         [[link]]\nname = \"u\"\nbetween = [\"a\", \"b\"]\ntype = \"kelvin-voigt\"\nk = {k1}\nc = 10.0\n\
         [[link]]\nname = \"l\"\nbetween = [\"b\", \"base\"]\ntype = \"kelvin-voigt\"\nk = {k2}\nc = 10.0\n\
         [measure]\nseat = \"base\"\nhead = \"a\"\ninterface = [\"l\"]\n"
    );
    let model = catalog::parse(&text, "c.toml").unwrap();
    let a = m1 * m2;
    let b = -(m1 * (k1 + k2) + m2 * k1);
    let c = k1 * k2;
    let disc = (b * b - 4.0 * a * c).sqrt();
    let mut expect =
        [(-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a)].map(|l: f64| l.sqrt() / (2.0 * PI));
    expect.sort_by(f64::total_cmp);
    let got = modes::undamped(model.system()).unwrap();
    for (g, e) in got.iter().zip(expect) {
        assert!((g.freq_hz - e).abs() < 1e-9 * e, "{} vs {e}", g.freq_hz);
    }
    // For the built-in chains, compare with the eigenvalues of M⁻¹K from a general solver.
    for model in catalog::all().unwrap() {
        let m = model.system().m.clone();
        let k = model.system().locked_stiffness();
        let minv_k = m.try_inverse().unwrap() * k;
        let mut eig: Vec<f64> = minv_k
            .complex_eigenvalues()
            .iter()
            .map(|l| l.re.max(0.0).sqrt() / (2.0 * PI))
            .collect();
        eig.sort_by(f64::total_cmp);
        let got = modes::undamped(model.system()).unwrap();
        for (g, e) in got.iter().zip(&eig) {
            assert!(
                (g.freq_hz - e).abs() < 1e-6 * e.max(1.0),
                "{}: {} vs {e}",
                model.name,
                g.freq_hz
            );
        }
    }
}

#[test]
fn damped_modes_of_one_dof_match_closed_form() {
    let (m, k, c): (f64, f64, f64) = (50.0, 40_000.0, 300.0);
    let model = one_dof(&format!("type = \"kelvin-voigt\"\nk = {k}\nc = {c}"));
    let d = modes::damped(model.system()).unwrap();
    assert_eq!(d.len(), 1);
    let wn = (k / m).sqrt();
    let zeta = c / (2.0 * (k * m).sqrt());
    assert!((d[0].natural_hz - wn / (2.0 * PI)).abs() < 1e-9);
    assert!((d[0].zeta - zeta).abs() < 1e-9);
    assert!((d[0].damped_hz - wn * (1.0 - zeta * zeta).sqrt() / (2.0 * PI)).abs() < 1e-9);
}

#[test]
fn stacked_configurations_have_the_expected_structure() {
    let full = catalog::resolve("seed001-full").unwrap();
    assert_eq!(full.dof(), 6);
    let names: Vec<_> = full
        .chain()
        .unwrap()
        .masses
        .iter()
        .map(|m| m.name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "head",
            "upper_torso",
            "lower_torso",
            "pelvis",
            "cushion",
            "seat_frame"
        ]
    );
    // The occupant's seat link now ends on the cushion, and the cushion on the suspension.
    let k4 = &full.chain().unwrap().links[full.chain().unwrap().link_index("k4").unwrap()];
    assert_eq!(full.chain().unwrap().node_name(k4.b), "cushion");
    let cushion =
        &full.chain().unwrap().links[full.chain().unwrap().link_index("cushion").unwrap()];
    assert_eq!(full.chain().unwrap().node_name(cushion.b), "seat_frame");
    assert_eq!(
        full.chain()
            .unwrap()
            .node_name(full.chain().unwrap().measure.seat),
        "cushion"
    );
    // Ad-hoc stacking from the command line gives the same model as the built-in file.
    let adhoc = catalog::resolve("seed001-table1+cushion-seed001+suspension-seed001").unwrap();
    assert_eq!(adhoc.chain().unwrap().masses, full.chain().unwrap().masses);
    assert_eq!(adhoc.chain().unwrap().links, full.chain().unwrap().links);
    assert!(catalog::resolve("cushion-seed001+seed001-table1").is_err());
}

/// A backrest force is the backrest link's share of the body's inertia: one mass m on a seat link
/// k_s and a backrest link k_b to the frame (both rigid to the base) moves as
/// X = −m/(k_s + k_b − ω²m) per unit base acceleration, and the backrest pushes it with
/// f_back_z = −k_b·X = m·k_b/(k_s + k_b − ω²m): m·k_b/(k_s + k_b) of the static inertial load.
#[test]
fn a_backrest_link_s_force_is_its_share_of_the_body_s_inertia() {
    // one_dof's mass of 50 kg on its seat link `l`, and a backrest link after it.
    let (m, ks, kb) = (50.0, 40_000.0, 10_000.0);
    let with_back = |between: &str| {
        format!(
            "type = \"kelvin-voigt\"\nk = {ks}\nc = 0.0\n[[link]]\nname = \"back\"\nbetween = {between}\nrole = \"backrest\"\ntype = \"kelvin-voigt\"\nk = {kb}\nc = 0.0"
        )
    };
    let model = one_dof(&with_back(r#"["m", "base"]"#));
    let s = model.system();
    let back = s
        .channel_index("f_back_z")
        .expect("a backrest link gives f_back_z");
    assert!(s.channels[back].measured);
    for f in [0.01, 1.0, 3.0, 10.0] {
        let w = 2.0 * PI * f;
        let (ch, _) = frf::solve_full(s, f).unwrap();
        let expect = Complex64::new(m * kb / (ks + kb - w * w * m), 0.0);
        assert!(
            close(ch[back], expect, 1e-10),
            "{f} Hz: {} vs {expect}",
            ch[back]
        );
    }
    // The seat-pan force carries the rest: f_seat + f_back = m·(a_base + ẍ), the body's inertia.
    let seat = s.channel_index("f_seat_z").unwrap();
    let (ch, x) = frf::solve_full(s, 3.0).unwrap();
    let w = 2.0 * PI * 3.0;
    let inertia = m * (1.0 - w * w * x[0]);
    assert!(close(ch[seat] + ch[back], inertia, 1e-10));
    // A backrest link written from the base up (a strap hanging from the seat back, the body its
    // lower node) is the same spring: its tension pushes the body, and f_back_z is the same force.
    let text = format!(
        "name = \"x\"\ndescription = \"x\"\n[[mass]]\nname = \"m\"\nm = {m}\n[[link]]\nname = \"l\"\nbetween = [\"m\", \"base\"]\n{}\n[measure]\nseat = \"base\"\ninterface = [\"l\"]\n",
        with_back(r#"["base", "m"]"#)
    );
    let reversed = catalog::parse(&text, "hanging.toml").unwrap();
    let r = reversed.system();
    let back_r = r.channel_index("f_back_z").unwrap();
    for f in [0.01, 1.0, 3.0, 10.0] {
        let (a, _) = frf::solve_full(s, f).unwrap();
        let (b, _) = frf::solve_full(r, f).unwrap();
        assert!(
            close(b[back_r], a[back], 1e-10),
            "{f} Hz: {} vs {}",
            b[back_r],
            a[back]
        );
    }
    // Without a backrest link there is no channel: recordings of other models are unchanged.
    assert!(
        one_dof("type = \"kelvin-voigt\"\nk = 1e4\nc = 10.0")
            .system()
            .channel_index("f_back_z")
            .is_none()
    );
}
