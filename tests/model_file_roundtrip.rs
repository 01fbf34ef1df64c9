//! One physical vocabulary for model files and the gap diagnosis's candidates (issue 73): every
//! edit a structural candidate makes to a chain model (added masses, frames and side modes, Maxwell
//! arms and relaxation spectra, every nonlinear law, every support path) is written as a model
//! file (`model::chain::file::write`) and read back (`file::parse`) into the same system: the same
//! masses, links, elements and laws bit for bit, the same frequency responses, and the same
//! time-domain run.

use wbv::diagnosis::candidate::{self, Family};
use wbv::excitation::spec::{ExcitationSpec, Kind};
use wbv::integrator::Method;
use wbv::model::catalog;
use wbv::model::chain::Chain;
use wbv::model::chain::file::{parse, write};
use wbv::simulate::{self, Settings, collect::Collector};
use wbv::system::System;

/// The chain models the candidates act on: the reference seat (a body on a cushion), the
/// suspension seat of paper 001 and a seat with a backrest-leaning occupant's parts.
const BASES: &[&str] = &["reference", "seed001-full", "scissor-seat"];

/// The effect parameter values of a candidate's edit: each parameter's first start, which lies
/// inside its bounds, so every edit is exercised at a physical value.
fn values(c: candidate::Candidate) -> Vec<f64> {
    c.params()
        .iter()
        .map(|p| {
            p.starts
                .first()
                .copied()
                .unwrap_or(0.5 * (p.bounds.0 + p.bounds.1))
        })
        .collect()
}

/// Writes `system` as a model file and reads it back.
fn round_trip(system: &System) -> (String, System) {
    let chain = Chain::from_system(system, "round trip", "test").expect("a chain system");
    let text = write(&chain, "written by the round-trip test");
    let back = parse(&text, "roundtrip.toml", &catalog::resolve_chain)
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    (text, back.system())
}

/// Frequency responses of `s` at 0.5–60 Hz, by response name.
fn frf(s: &System) -> Vec<(String, Vec<num_complex::Complex64>)> {
    let f: Vec<f64> = (0..120)
        .map(|i| 0.5 * 1.04f64.powi(i))
        .filter(|f| *f < 60.0)
        .collect();
    let set = wbv::response::frf::compute(s, &f).unwrap();
    set.responses
        .into_iter()
        .map(|r| (r.name, r.values))
        .collect()
}

/// `a_seat_z` and `a_head_z` of 4 s of a random base at 1.5 m/s² r.m.s.: large enough that stops,
/// contacts and lift-off engage.
fn run(s: &System) -> Vec<Vec<f64>> {
    let spec = ExcitationSpec::new(
        Kind::Random {
            rms_m_s2: 1.5,
            band_hz: [0.5, 40.0],
        },
        "round-trip base",
    )
    .unwrap();
    let settings = Settings {
        dt: 1e-3,
        duration_s: 4.0,
        method: Method::AVERAGE_ACCELERATION,
    };
    let mut exc = spec.build(settings.dt, settings.duration_s, 7).unwrap();
    let mut col = Collector::new();
    simulate::run(s, exc.as_mut(), &settings, &mut [&mut col], None).unwrap();
    let sig = col.into_signals("run").unwrap();
    ["a_seat_z", "a_head_z"]
        .iter()
        .filter_map(|n| {
            sig.names
                .iter()
                .position(|m| m == n)
                .map(|i| sig.data[i].clone())
        })
        .collect()
}

#[test]
fn every_structural_candidate_round_trips_through_a_model_file() {
    let mut checked = Vec::new();
    let mut families = std::collections::BTreeSet::new();
    for name in BASES {
        let model = catalog::resolve(name).unwrap();
        let nominal = model.system().clone();
        // Forms that need a part another effect adds (a side mode hung on a frame, a riser under a
        // frame) are checked on the model with a frame.
        let frame = candidate::from_id("missing-dof").unwrap();
        let mut bases = vec![nominal.clone()];
        if frame.applies_to(&nominal) {
            bases.push(frame.apply(&nominal, &values(frame)).unwrap().system);
        }
        for (base, c) in bases.iter().enumerate().flat_map(|(i, b)| {
            candidate::all()
                .filter(move |c| c.family != Family::Sensor && c.applies_to(b))
                .filter(move |c| i == 0 || c.family == Family::MissingDof)
                .map(move |c| (b, c))
        }) {
            let v = c.apply(base, &values(c)).unwrap();
            // A magnitude schedule is written at one magnitude (docs/models.md).
            let system = match v.schedule {
                Some(s) => s.at(&v.system, 0.8),
                None => v.system.clone(),
            };
            let (text, back) = round_trip(&system);
            let what = format!("{} on {name} ({} masses)", c.id, base.dof());
            assert_eq!(back.dof(), system.dof(), "{what}");
            assert_eq!(back.m, system.m, "{what}: masses");
            assert_eq!(back.r, system.r, "{what}");
            assert_eq!(back.links.len(), system.links.len(), "{what}");
            for (a, b) in system.links.iter().zip(&back.links) {
                assert_eq!(
                    (&a.name, a.role, &a.nodes, &a.row, a.element, a.law),
                    (&b.name, b.role, &b.nodes, &b.row, b.element, b.law),
                    "{what}: link {}\n{text}",
                    a.name
                );
            }
            for (ra, rb) in frf(&system).iter().zip(frf(&back)) {
                assert_eq!(ra.0, rb.0, "{what}");
                for (x, y) in ra.1.iter().zip(&rb.1) {
                    assert!(
                        (x - y).norm() <= 1e-9 * x.norm().max(1e-12),
                        "{what}: {} {x} vs {y}",
                        ra.0
                    );
                }
            }
            if system.is_nonlinear() {
                assert_eq!(run(&system), run(&back), "{what}: time-domain run");
            }
            families.insert(format!("{:?}", c.family));
            checked.push(what);
        }
    }
    // Every structural family has at least one candidate checked.
    for f in [
        "BodySoftening",
        "CushionStiffening",
        "CushionViscoelasticity",
        "Suspension",
        "MissingDof",
        "SupportPath",
    ] {
        assert!(
            families.contains(f),
            "no {f} candidate checked: {checked:?}"
        );
    }
    eprintln!(
        "{} candidate edits round-tripped: {checked:?}",
        checked.len()
    );
}

#[test]
fn a_planar_system_is_refused_by_name() {
    let model = catalog::resolve("planar-occupant").unwrap();
    let e = Chain::from_system(model.system(), "", "")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("not a chain of masses") && e.contains("planar"),
        "{e}"
    );
}
