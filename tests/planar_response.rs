//! Planar model responses: cross-axis (v-h) response, the foam-thickness trend, and the reduction
//! to the 1-D chain with the backrest and footrest removed and the joints made rigid.

use num_complex::Complex64;
use std::f64::consts::PI;
use wbv::model::catalog;
use wbv::model::planar::Planar;
use wbv::model::planar::contact::Law;
use wbv::response::{frf, peak};

fn peak_of(model: &wbv::model::Model, name: &str) -> peak::Peak {
    let f = frf::grid(1.0, 12.0, 2201, false).unwrap();
    let set = frf::compute(model.system(), &f).unwrap();
    peak::global_peak(&f, &set.get(name).unwrap().magnitude()).unwrap()
}

#[test]
fn vertical_shaking_gives_a_fore_and_aft_seat_response() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let vh = peak_of(&model, "seat_x");
    assert!(vh.value > 0.1 && vh.freq_hz > 2.0, "{vh:?}");
    let am = peak_of(&model, "apms_x");
    assert!(am.value > 1.0, "{am:?}");
    // Static limits: the seat follows the base, the apparent mass is the body mass.
    let set = frf::compute(model.system(), &[0.01]).unwrap();
    let mass = model.planar().unwrap().spec.body_mass();
    assert!((set.get("seat").unwrap().values[0].norm() - 1.0).abs() < 1e-3);
    assert!(set.get("seat_x").unwrap().values[0].norm() < 1e-3);
    assert!((set.get("apms_z").unwrap().values[0].norm() - mass).abs() < 1e-3 * mass);
}

#[test]
fn thicker_foam_lowers_both_seat_resonances() {
    let mut last = (f64::INFINITY, f64::INFINITY);
    for t in [0.06, 0.08, 0.10] {
        let mut model = catalog::resolve("planar-occupant").unwrap();
        model.set("cushion.thickness", t).unwrap();
        let (vv, vh) = (peak_of(&model, "seat"), peak_of(&model, "seat_x"));
        assert!(
            vv.freq_hz < last.0 && vh.freq_hz < last.1,
            "{t} m: {vv:?} {vh:?}"
        );
        last = (vv.freq_hz, vh.freq_hz);
    }
}

#[test]
fn without_backrest_and_footrest_and_with_rigid_joints_it_is_the_1d_chain() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let mut spec = model.planar().unwrap().spec.clone();
    // Keep only the cushion under the seat point; make every joint 10⁷ times stiffer.
    spec.contacts.retain(|c| c.name == "ischial");
    spec.seat_contact = 0;
    for j in &mut spec.joints {
        j.k *= 1e7;
    }
    let Law::Cushion { .. } = spec.contacts[0].law else {
        panic!("ischial contact is a cushion share")
    };
    let p = Planar::build(spec).unwrap();
    let (k, _, c, _) = p.equilibrium.coefficients[0];
    let m = p.spec.body_mass();
    // The lone support carries the weight, under the centre of mass.
    assert!((p.equilibrium.loads[0].normal - m * 9.81).abs() < 1e-8 * m * 9.81);
    let one_d = catalog::parse(
        &format!(
            "name = \"chain\"\ndescription = \"body on cushion\"\n[[mass]]\nname = \"body\"\nm = {m}\n\
             [[link]]\nname = \"cushion\"\nbetween = [\"body\", \"base\"]\ntype = \"kelvin-voigt\"\nk = {k}\nc = {c}\n\
             [measure]\nseat = \"base\"\ninterface = [\"cushion\"]\n"
        ),
        "chain.toml",
    )
    .unwrap();
    let freq = frf::grid(0.5, 10.0, 80, false).unwrap();
    let planar = frf::compute(&p.system(), &freq).unwrap();
    let chain = frf::compute(one_d.system(), &freq).unwrap();
    for (i, f) in freq.iter().enumerate() {
        let w = 2.0 * PI * f;
        let closed = Complex64::new(k, w * c) / Complex64::new(k - w * w * m, w * c);
        let vv = planar.get("seat").unwrap().values[i];
        let t1 = chain.get("t_body").unwrap().values[i];
        // Tolerance 10⁻⁵: what is left of the joints' compliance, (f/f_joint)² with joint modes in
        // the 10 kHz, and the round-off of a dynamic stiffness with condition number ~10¹¹.
        assert!(
            (vv - closed).norm() < 1e-5 * closed.norm(),
            "{f} Hz: {vv} vs {closed}"
        );
        assert!((vv - t1).norm() < 1e-5 * closed.norm());
        let am = planar.get("apms_z").unwrap().values[i];
        let am1 = chain.get("apms").unwrap().values[i];
        assert!(
            (am - am1).norm() < 1e-5 * am1.norm(),
            "{f} Hz: {am} vs {am1}"
        );
    }
}
