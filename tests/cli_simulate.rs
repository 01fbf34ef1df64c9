//! `wbv simulate` end to end: a recorded run that analyses and replays, deterministic bytes, and one
//! clear error line (nothing half-written) for bad input.

mod common;
use common::wbv;
use std::path::Path;
use std::process::Command;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_run_is_recorded_analysed_replayed_and_byte_identical() {
    // The command line is part of the provenance: run it identically in two working directories.
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    let mut runs = Vec::new();
    for d in &dirs {
        let r = Command::new(env!("CARGO_BIN_EXE_wbv"))
            .args([
                "simulate",
                "--excitation",
                "bell-214",
                "--duration",
                "12",
                "--seed",
                "5",
            ])
            .args(["--out", "run"])
            .current_dir(d.path())
            .output()
            .unwrap();
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let text = String::from_utf8(r.stdout).unwrap();
        assert!(text.contains("SEAT") && text.contains("Comfort"), "{text}");
        runs.push(std::fs::read(d.path().join("run/run.mcap")).unwrap());
    }
    assert!(runs[0] == runs[1], "same inputs and seed, same bytes");
    let a = dirs[0].path().join("run");
    let bytes_a = runs.pop().unwrap();
    let r = wbv(&["replay", s(&a)]);
    let text = String::from_utf8(r.stdout).unwrap();
    assert!(
        r.status.success() && text.contains("equal those stored"),
        "{text}"
    );
    // An existing run is not overwritten without --force.
    let r = wbv(&["simulate", "--duration", "11", "--out", s(&a)]);
    assert!(!r.status.success());
    assert_eq!(std::fs::read(a.join("run.mcap")).unwrap(), bytes_a);
    // The recorded run stands in for a measurement.
    let r = wbv(&["analyze", s(&a.join("run.mcap")), "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert!(json["seat_percent"].as_f64().unwrap() > 0.0);
}

#[test]
fn bad_input_gives_one_error_line_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let neg = dir.path().join("neg.csv");
    std::fs::write(&neg, "freq_hz,psd\n1,0.1\n10,-0.2\n").unwrap();
    let bad_toml = dir.path().join("bad.toml");
    std::fs::write(
        &bad_toml,
        "description = \"x\"\n[excitation]\ntype = \"random\"\nrms_m_s2 = \n",
    )
    .unwrap();
    let out = dir.path().join("run");
    let cases: Vec<Vec<&str>> = vec![
        vec!["--duration", "0"],
        vec!["--duration", "-5"],
        vec!["--integrator", "rk4", "--dt", "0.005"],
        vec!["--excitation", "missing-file.toml"],
        vec!["--excitation", s(&bad_toml)],
        vec!["--excitation", "psd", "--input", s(&neg)],
        vec!["--dt", "0"],
    ];
    for case in cases {
        let mut args = vec!["simulate", "--out", s(&out)];
        args.extend(&case);
        let r = wbv(&args);
        let err = String::from_utf8(r.stderr).unwrap();
        assert!(!r.status.success(), "{case:?} should fail");
        assert_eq!(err.lines().count(), 1, "{case:?}: {err}");
        assert!(err.starts_with("wbv: error: "), "{case:?}: {err}");
        assert!(!out.join("run.mcap").exists() && !out.join("run.mcap.partial").exists());
    }
}

/// A CSV written by `--no-record` is never replaced silently, and `--force` replaces it.
#[test]
fn force_replaces_a_csv_also_without_recording() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("m.csv");
    let args = |seed: &'static str, force: bool| {
        let mut a = vec![
            "simulate",
            "--duration",
            "2",
            "--seed",
            seed,
            "--no-record",
            "--csv",
            s(&csv),
        ];
        if force {
            a.push("--force");
        }
        wbv(&a)
    };
    assert!(args("1", false).status.success());
    let first = std::fs::read(&csv).unwrap();
    let refused = args("2", false);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--force"));
    assert_eq!(std::fs::read(&csv).unwrap(), first, "kept without --force");
    assert!(args("2", true).status.success());
    assert_ne!(std::fs::read(&csv).unwrap(), first, "replaced with --force");
}
