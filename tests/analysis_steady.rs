//! ISO 2631-1 figures of recordings that start mid-vibration, against closed forms computed outside
//! wbv: `tools/input-fixtures/steady.py` (numpy/scipy, the standard's analog weightings) writes
//! steady sines at a random start phase with an offset, and random vibrations with and without an
//! offset held through a quiet first second; `tools/test` runs this with `WBV_INPUT_FIXTURES=DIR`.
//! Without that variable the test says so and checks nothing else.

mod common;

use wbv::analysis::{Options, Report};
use wbv::io::input::InputArgs;
use wbv::measurement::read;

fn report(dir: &std::path::Path, file: &str) -> Report {
    let opts = InputArgs::default().options().unwrap();
    let inp = read(&dir.join(file), &opts).unwrap_or_else(|e| panic!("{file}: {e}"));
    Report::from_signals(&inp.signals, &Options::default()).unwrap()
}

fn fixtures() -> Option<(std::path::PathBuf, serde_json::Value)> {
    let dir = common::input_fixtures()?.join("steady");
    let text = std::fs::read_to_string(dir.join("manifest.json")).unwrap();
    Some((dir, serde_json::from_str(&text).unwrap()))
}

/// Each figure of a steady sine within its tolerance of the closed form, whatever the start phase
/// and offset: a_w and VDV 3 %, MTVV 5 %, crest factor 10 %, MSDV 5 % or 0.02 m/s^1.5.
#[test]
fn steady_sines_match_their_closed_forms() {
    let Some((dir, manifest)) = fixtures() else {
        return;
    };
    let sines = manifest["sines"].as_array().unwrap();
    assert!(sines.len() >= 12);
    let mut failures = Vec::new();
    for s in sines {
        let file = s["file"].as_str().unwrap();
        let r = report(&dir, file);
        for (ch, want) in s["expect"].as_object().unwrap() {
            let c = r.channels.iter().find(|c| &c.name == ch).unwrap();
            let got = [
                ("a_w", c.a_w, 0.03),
                ("vdv", c.vdv, 0.03),
                ("mtvv", c.mtvv, 0.05),
                ("crest_factor", c.crest_factor, 0.10),
            ];
            for (key, g, tol) in got {
                let e = want[key].as_f64().unwrap();
                if (g / e - 1.0).abs() > tol {
                    failures.push(format!("{file} {ch} {key}: {g:.5} vs closed form {e:.5}"));
                }
            }
            if let Some(e) = want.get("msdv").and_then(|v| v.as_f64()) {
                let g = c.msdv.unwrap();
                if (g - e).abs() > (0.05 * e).max(0.02) {
                    failures.push(format!("{file} {ch} msdv: {g:.5} vs closed form {e:.5}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A sensor offset held through a quiet first second (a step at the recording's start) changes no
/// weighted figure: within 2 % of the same vibration without the offset.
#[test]
fn an_offset_step_at_the_start_changes_no_figure() {
    let Some((dir, manifest)) = fixtures() else {
        return;
    };
    let pairs = manifest["pairs"].as_array().unwrap();
    assert!(pairs.len() >= 4);
    for p in pairs {
        let rest = report(&dir, p["rest"].as_str().unwrap());
        let step = report(&dir, p["step"].as_str().unwrap());
        let (a, b) = (&rest.channels[0], &step.channels[0]);
        for (key, x, y) in [
            ("a_w", a.a_w, b.a_w),
            ("vdv", a.vdv, b.vdv),
            ("mtvv", a.mtvv, b.mtvv),
            ("crest_factor", a.crest_factor, b.crest_factor),
            ("msdv", a.msdv.unwrap(), b.msdv.unwrap()),
        ] {
            assert!(
                (y / x - 1.0).abs() < 0.02,
                "{}: {key} {y} vs {x} at rest",
                p["step"]
            );
        }
    }
}

/// A broadband record cut anywhere out of a longer vibration (a rotation of one periodic record at
/// 200 Hz and 1 kHz): its MSDV against the whole vibration's steady-state value computed outside
/// wbv (Parseval through the analog Wf). The past before a cut is unknown and the part of Wf's
/// state it leaves unpredictable sets the error's floor on content inside Wf's band (white, band:
/// 300 s, measured −2.2 % to +0.8 %, docs/exposure.md §MSDV), so 3 % there. A seat's vibration
/// (1–80 Hz) has almost no Wf dose of its own, and a start's transient once made it 10 % to
/// 10 times too high; the dose is now within 1 %.
#[test]
fn broadband_records_cut_anywhere_keep_their_msdv() {
    let Some((dir, manifest)) = fixtures() else {
        return;
    };
    let rotations = manifest["rotations"].as_array().unwrap();
    assert!(rotations.len() >= 32);
    let mut failures = Vec::new();
    for r in rotations {
        let file = r["file"].as_str().unwrap();
        let want = r["msdv"].as_f64().unwrap();
        let tolerance = if r["kind"] == "seat" { 0.01 } else { 0.03 };
        let got = report(&dir, file).channels[0].msdv.unwrap();
        eprintln!("{file}: MSDV {:+.2} %", 100.0 * (got / want - 1.0));
        if (got / want - 1.0).abs() > tolerance {
            failures.push(format!("{file}: MSDV {got:.5} vs steady state {want:.5}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
