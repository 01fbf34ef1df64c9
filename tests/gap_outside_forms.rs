//! The gap diagnosis on effects in forms outside its catalogue, simulated without wbv code
//! (tools/blind-gap/gen.py, numpy + scipy; `tools/input-fixtures/run DIR` writes them and
//! `tools/test` runs this test with `WBV_INPUT_FIXTURES=DIR`):
//! - a conditioner's high-pass of two to four poles (three RC stages, a Bessel, a Butterworth) on
//!   one accelerometer, and a low-pass of two poles (two RC stages, a Bessel): the measuring chain
//!   is named, with a filter whose −3 dB corner is the truth's and, for a Butterworth or RC
//!   truth, its order and design;
//! - a body that stiffens between runs (its resonance rises with magnitude): never named a
//!   softening, whatever else the diagnosis says;
//! - a pilot's harness (straps pulling the upper torso down only past their slack) and a lap belt
//!   (the same law on the pelvis): each named the one-sided support path at its own place;
//! - feet that lift off the floor (a preloaded pad under the pelvis that carries no tension):
//!   named a support path onto the pelvis;
//! - a head restraint the head leaves (the same preloaded pad from the seat back to the head):
//!   named the one-sided path onto the head;
//! - a cab floor panel of two plate modes under a seat frame: named missing structure, and the
//!   standard error of the fitted model's a_w and SEAT stays within the diagnosis's practical
//!   size when the model fits the check run within the noise;
//! - a base accelerometer 16.7 ms late on a field run (phase wrapping above 30 Hz): named a
//!   logger offset, read within a millisecond.

mod common;
use std::path::{Path, PathBuf};

fn read_json(p: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

/// Every case directory under `dir` with its truth and `wbv gap --json` document.
fn diagnosed(dir: &Path) -> Vec<(PathBuf, serde_json::Value, serde_json::Value)> {
    let mut cases: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("truth.json").is_file())
        .collect();
    cases.sort();
    assert!(!cases.is_empty(), "no cases in {}", dir.display());
    cases
        .into_iter()
        .map(|case| {
            let out = common::gap_case(&case);
            assert!(
                out.status.success(),
                "{}: {}",
                case.display(),
                String::from_utf8_lossy(&out.stderr)
            );
            let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            (case.clone(), read_json(&case.join("truth.json")), doc)
        })
        .collect()
}

/// The fitted value of parameter `name` of candidate `id` in a gap document.
fn fitted(doc: &serde_json::Value, id: &str, name: &str) -> f64 {
    let c = doc["candidates"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["id"] == id)
        .unwrap_or_else(|| panic!("{id} not among the candidates"));
    c["params"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == name)
        .unwrap_or_else(|| panic!("{id} has no {name}"))["value"]
        .as_f64()
        .unwrap()
}

/// The −3 dB corner (Hz) of the planted filter, from its design (the generator's `f_hz` is each
/// RC stage's corner; its Bessel is normalised to −3 dB at `f_hz`, as a Butterworth is): n equal
/// first-order stages are 3 dB down where (1 + r²)^n = 2, r = f_c/f for a high-pass and f/f_c for
/// a low-pass.
fn corner_3db(truth: &serde_json::Value) -> f64 {
    let p = &truth["params"];
    let f = p["f_hz"].as_f64().unwrap();
    if p["design"] != "rc" {
        return f;
    }
    let n = p["order"].as_f64().unwrap();
    let r = (2f64.powf(1.0 / n) - 1.0).sqrt();
    if truth["form"] == "highpass-multi" {
        f / r
    } else {
        f * r
    }
}

/// The generator's channel name as the candidate's parameter suffix.
fn place(truth: &serde_json::Value) -> &'static str {
    match truth["params"]["channel"].as_str().unwrap() {
        "a_base_z" => "base",
        "a_seat_z" => "seat",
        "a_head_z" => "head",
        other => panic!("unexpected channel {other}"),
    }
}

#[test]
fn a_conditioners_multi_pole_high_pass_is_named_with_its_corner_and_order() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, truth, doc) in diagnosed(&dir.join("conditioner-highpass")) {
        let order = truth["params"]["order"].as_f64().unwrap();
        assert!(
            order >= 2.0,
            "{}: the set plants two to four poles",
            case.display()
        );
        assert_eq!(
            doc["verdict"],
            "sensor-highpass",
            "{}: {}",
            case.display(),
            doc["verdict_text"]
        );
        let want = corner_3db(&truth);
        let got = fitted(
            &doc,
            "sensor-highpass",
            &format!("highpass_{}_hz", place(&truth)),
        );
        assert!(
            (got / want - 1.0).abs() < 0.2,
            "{}: corner {got:.3} Hz against the truth's −3 dB corner {want:.3} Hz",
            case.display()
        );
        // A design the candidate has (Butterworth poles, identical RC stages) is named with its
        // order; a Bessel lies between them and is named by the nearer.
        let rc = match truth["params"]["design"].as_str().unwrap() {
            "butter" => Some(0.0),
            "rc" => Some(1.0),
            _ => None,
        };
        if let Some(rc) = rc {
            assert_eq!(
                fitted(&doc, "sensor-highpass", "highpass_order"),
                order,
                "{}",
                case.display()
            );
            assert_eq!(
                fitted(&doc, "sensor-highpass", "highpass_rc_stages"),
                rc,
                "{}",
                case.display()
            );
        }
    }
}

#[test]
fn a_conditioners_low_pass_of_other_orders_is_named_a_low_pass() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, truth, doc) in diagnosed(&dir.join("conditioner-lowpass")) {
        assert_eq!(
            doc["verdict"],
            "sensor-lowpass",
            "{} ({} of order {}): {}",
            case.display(),
            truth["params"]["design"],
            truth["params"]["order"],
            doc["verdict_text"]
        );
        let want = corner_3db(&truth);
        let got = fitted(
            &doc,
            "sensor-lowpass",
            &format!("lowpass_{}_hz", place(&truth)),
        );
        // A Butterworth's corner stands in for another design's: same −3 dB point within the
        // phase and roll-off the designs differ by.
        assert!(
            (got / want - 1.0).abs() < 0.5,
            "{}: corner {got:.1} Hz against the truth's −3 dB corner {want:.1} Hz",
            case.display()
        );
    }
}

#[test]
fn a_body_stiffening_between_runs_is_never_named_a_softening() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, _, doc) in diagnosed(&dir.join("body-stiffening")) {
        let named: Vec<String> = doc["named"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap().to_string())
            .collect();
        assert!(
            named.iter().all(|n| !n.starts_with("body-softening")),
            "{}: {named:?}: {}",
            case.display(),
            doc["verdict_text"]
        );
    }
}

#[test]
fn a_base_accelerometer_delay_of_many_milliseconds_is_named_timing_with_its_lag() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, truth, doc) in diagnosed(&dir.join("base-delay")) {
        assert_eq!(truth["params"]["channel"], "a_base_z", "{}", case.display());
        let delay = truth["params"]["delay_s"].as_f64().unwrap();
        // A late base accelerometer is an early occupant logger: the offset is −delay. Above
        // 1/(2·delay) the paths' phase wraps, so a fit started at zero lag misses it.
        assert_eq!(
            doc["verdict"],
            "logger-offset",
            "{}: {}",
            case.display(),
            doc["verdict_text"]
        );
        let got = fitted(&doc, "logger-offset", "offset_s");
        assert!(
            (got + delay).abs() < 1e-3,
            "{}: offset {got:.4} s against a base delay of {delay:.4} s",
            case.display()
        );
    }
}

#[test]
fn a_pilots_harness_is_named_a_one_sided_support_path() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, truth, doc) in diagnosed(&dir.join("harness")) {
        assert_eq!(truth["form"], "harness", "{}", case.display());
        // Every two-sided path fits it worse: the strap's share grows with the magnitude. Which
        // strap is not always told apart: on this case the held-out run favours a lap belt (ΔBIC
        // −1518 against −1178) where all runs favour the shoulder straps; the blind harness sets
        // name the place right in 18 of 22 cases (tools/blind-gap/README.md).
        let verdict = doc["verdict"].as_str().unwrap_or_default();
        assert!(
            ["harness", "lap-belt"].contains(&verdict),
            "{}: {}",
            case.display(),
            doc["verdict_text"]
        );
    }
}

#[test]
fn a_lap_belt_is_named_the_one_sided_path_on_the_pelvis() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, truth, doc) in diagnosed(&dir.join("lap-belt")) {
        assert_eq!(truth["form"], "lap-belt", "{}", case.display());
        // The shoulder harness fits it worse: the belt's pull enters at the pelvis, under the
        // body's modes that a pull on the upper torso shapes.
        assert_eq!(
            doc["verdict"],
            "lap-belt",
            "{}: {}",
            case.display(),
            doc["verdict_text"]
        );
    }
}

#[test]
fn feet_that_lift_off_are_named_a_support_path_onto_the_pelvis() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, truth, doc) in diagnosed(&dir.join("feet-lift-off")) {
        assert_eq!(truth["form"], "feet-lift-off", "{}", case.display());
        // gen.py's pad runs straight from the floor to the pelvis with its damper always on: the
        // two-sided thigh path or the legs with or without lift-off are all its place; the blind
        // sets name the lift-off in 10 of 16 and the thigh path in the rest
        // (tools/blind-gap/README.md). Never a cushion law, a body effect or the upper torso.
        let verdict = doc["verdict"].as_str().unwrap_or_default();
        assert!(
            ["feet-lift-off", "thigh-support", "feet-support"].contains(&verdict),
            "{}: {}",
            case.display(),
            doc["verdict_text"]
        );
    }
}

#[test]
fn a_head_restraint_the_head_leaves_is_named_the_path_onto_the_head() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, truth, doc) in diagnosed(&dir.join("head-restraint")) {
        assert_eq!(truth["form"], "head-restraint", "{}", case.display());
        // gen.py's pad keeps its damper on past the lift-off and gives back its spring's pull
        // alone, where the candidate's contact drops both: not the candidate's law. A path onto
        // the head shapes seat→head above the neck, which no path onto the torso or the pelvis
        // can, so the place is named, not only the family.
        assert_eq!(
            doc["verdict"],
            "head-restraint",
            "{}: {}",
            case.display(),
            doc["verdict_text"]
        );
    }
}

#[test]
fn a_floor_panel_is_named_missing_structure_with_iso_errors_the_fit_allows() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    for (case, truth, doc) in diagnosed(&dir.join("floor-panel")) {
        assert_eq!(truth["form"], "floor-panel", "{}", case.display());
        assert_eq!(
            doc["verdict"],
            "missing-dof",
            "{}: {}",
            case.display(),
            doc["verdict_text"]
        );
        // The named model with the second mode forward selection adds fits the check run within
        // the noise; its a_w and SEAT then rest on bands the runs pin (4–16 Hz), so their
        // standard errors are below the 1 % / 1 point the diagnosis calls practical. The
        // second mode's parameters are pinned only near their optimum (a light mode above the
        // judged band): moved by their first-order σ they would enter the band, which the runs
        // exclude, and the first-order propagation said ±34 %.
        let st = &doc["second"]["check"];
        assert!(
            st["chi2_red"].as_f64().unwrap() < 2.0,
            "{}: {st}",
            case.display()
        );
        let sigma = &st["iso_sigma"];
        for (k, limit) in [("aw_percent", 1.0), ("seat_points", 1.0)] {
            let s = sigma[k].as_f64().unwrap();
            assert!(s > 0.0 && s < limit, "{}: σ {k} = {s}", case.display());
        }
    }
}
