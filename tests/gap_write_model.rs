//! `wbv gap --write-model` (docs/gap.md §10) on cases simulated without wbv code
//! (tools/blind-gap/gen.py, written by `tools/input-fixtures/run DIR`; `tools/test` sets
//! `WBV_INPUT_FIXTURES=DIR`):
//! - a seat frame on a cab floor panel (missing structure): the written model holds the named
//!   frame as a mass and a link, every command runs it (`frf`, `modes`, `seat-test`), and
//!   diagnosing it on the runs it came from finds no missing structure again;
//! - a foam that stiffens under the preload: the written law explains the runs it came from
//!   (diagnosed again: `none`);
//! - a conditioner's low-pass on one accelerometer: the measuring chain is not built into the
//!   seat but listed as a correction of the measurement;
//! - an existing file is refused before the diagnosis runs, and replaced with `--force`.

mod common;
use std::path::{Path, PathBuf};

fn only_case(dir: &Path) -> PathBuf {
    let mut cases: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("truth.json").is_file())
        .collect();
    cases.sort();
    cases.remove(0)
}

/// Diagnoses `case` with `model`, writing the corrected model to `out`; the JSON document.
fn diagnose(case: &Path, model: &str, out: &Path) -> serde_json::Value {
    let o = common::gap_case_with(
        case,
        model,
        &["--write-model", out.to_str().unwrap(), "--force"],
    );
    assert!(
        o.status.success(),
        "{}: {}",
        case.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn a_diagnosed_frame_is_written_runs_everywhere_and_is_not_missing_again() {
    let Some(fx) = common::input_fixtures() else {
        return;
    };
    let case = only_case(&fx.join("floor-panel"));
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("corrected.toml");
    let doc = diagnose(&case, "reference", &file);
    assert_eq!(doc["verdict"], "missing-dof", "{}", doc["verdict_text"]);
    let text = std::fs::read_to_string(&file).unwrap();
    assert_eq!(
        doc["model"].as_str(),
        Some(text.as_str()),
        "the file is the JSON's model"
    );
    assert_eq!(doc["model_status"]["accepted"], true);
    // The frame is a mass and a frame link of the file; the provenance names the effect.
    assert!(text.contains("role = \"frame\""), "{text}");
    assert!(text.contains("effects = [\"missing-dof\""), "{text}");
    assert!(text.contains("[provenance.parameters]") && text.contains("sigma = "));
    let path = file.to_str().unwrap();
    for args in [
        vec!["frf", "--model", path, "--json"],
        vec!["modes", "--model", path, "--json"],
        vec![
            "seat-test",
            "--model",
            path,
            "--class",
            "iso7096-em3",
            "--occupant",
            "light",
            "--duration",
            "30",
            "--no-damping",
            "--json",
        ],
    ] {
        let o = common::wbv(&args);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    // The written frame is the diagnosed one: diagnosed again, no structure is missing. (The
    // all-run rule then names a small amplitude-dependent path on this case, a lap belt of
    // −0.1 % a_w: issue 73 keeps that open.)
    let again = diagnose(&case, path, &dir.path().join("again.toml"));
    let named: Vec<&str> = again["named"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|n| n.as_str())
        .collect();
    assert!(
        !named
            .iter()
            .any(|n| ["missing-dof", "frame-side-mode"].contains(n)),
        "{}",
        again["verdict_text"]
    );
}

#[test]
fn a_written_stiffening_law_explains_the_runs_it_came_from() {
    let Some(fx) = common::input_fixtures() else {
        return;
    };
    let case = only_case(&fx.join("stiffening"));
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("corrected.toml");
    let doc = diagnose(&case, "reference", &file);
    let verdict = doc["verdict"].as_str().unwrap().to_string();
    assert!(verdict.starts_with("cushion-"), "{}", doc["verdict_text"]);
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.contains("[link.law]"), "{text}");
    let again = diagnose(
        &case,
        file.to_str().unwrap(),
        &dir.path().join("again.toml"),
    );
    assert_eq!(again["verdict"], "none", "{}", again["verdict_text"]);
}

#[test]
fn a_measuring_chain_effect_is_a_correction_of_the_measurement_not_a_part_of_the_seat() {
    let Some(fx) = common::input_fixtures() else {
        return;
    };
    let case = only_case(&fx.join("conditioner-lowpass"));
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("corrected.toml");
    let doc = diagnose(&case, "reference", &file);
    let named: Vec<String> = doc["named"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect();
    assert!(named[0].starts_with("sensor-"), "{}", doc["verdict_text"]);
    let text = std::fs::read_to_string(&file).unwrap();
    let quoted = |ids: &[&String]| {
        ids.iter()
            .map(|n| format!("\"{n}\""))
            .collect::<Vec<_>>()
            .join(", ")
    };
    // The sensor is a correction; structural effects forward selection added beside it, if any,
    // are the seat's.
    let (sensors, structure): (Vec<&String>, Vec<&String>) =
        named.iter().partition(|n| n.starts_with("sensor-"));
    assert!(
        text.contains(&format!("measurement_corrections = [{}]", quoted(&sensors))),
        "{text}"
    );
    assert!(
        text.contains(&format!("effects = [{}]", quoted(&structure))),
        "{text}"
    );
    // Every part of the base seat is there, and nothing of the sensor is.
    let base = wbv::model::catalog::resolve("reference").unwrap();
    let written = wbv::model::catalog::resolve(file.to_str().unwrap()).unwrap();
    let names = |m: &wbv::model::Model| -> Vec<String> {
        m.system().links.iter().map(|l| l.name.clone()).collect()
    };
    let (b, w) = (names(&base), names(&written));
    assert!(b.iter().all(|l| w.contains(l)), "{w:?}");
    assert!(!w.iter().any(|l| l.contains("sensor")), "{w:?}");
}

#[test]
fn an_existing_model_file_is_refused_before_the_diagnosis_runs() {
    let Some(fx) = common::input_fixtures() else {
        return;
    };
    let case = only_case(&fx.join("floor-panel"));
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("kept.toml");
    std::fs::write(&file, "keep me").unwrap();
    let o = common::gap_case_with(
        &case,
        "reference",
        &["--write-model", file.to_str().unwrap()],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("--force"), "{err}");
    // Refused before the work: one error line, no diagnosis printed, the file as it was.
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(o.stdout.is_empty());
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep me");
}
