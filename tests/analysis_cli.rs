//! `wbv analyze` end to end: bad input gives one clear error line and a non-zero exit.

use std::io::Write;
use std::process::Command;

fn write_csv(
    dir: &std::path::Path,
    name: &str,
    fs: f64,
    seconds: f64,
    cols: &[&str],
    value: impl Fn(usize, usize) -> String,
) -> std::path::PathBuf {
    let path = dir.join(name);
    let mut f = std::fs::File::create(&path).unwrap();
    writeln!(f, "t_s,{}", cols.join(",")).unwrap();
    for i in 0..(fs * seconds) as usize {
        let row: Vec<String> = (0..cols.len()).map(|c| value(i, c)).collect();
        writeln!(f, "{},{}", i as f64 / fs, row.join(",")).unwrap();
    }
    path
}

fn analyze(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_wbv"))
        .arg("analyze")
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn assert_one_line_error(args: &[&str], needle: &str) {
    let (ok, _, err) = analyze(args);
    assert!(!ok, "expected failure for {args:?}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one line expected: {err}"
    );
    assert!(
        err.starts_with("wbv: error:") && err.contains(needle),
        "{err}"
    );
}

fn sine(i: usize, c: usize) -> String {
    format!("{:.6}", (1.0 + c as f64) * (i as f64 * 0.05).sin())
}

#[test]
fn bad_inputs_give_one_clear_error_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    assert_one_line_error(&[d.join("missing.csv").to_str().unwrap()], "missing.csv");
    let empty = d.join("empty.csv");
    std::fs::write(&empty, "").unwrap();
    assert_one_line_error(&[empty.to_str().unwrap()], "empty.csv");
    let forces = write_csv(d, "forces.csv", 500.0, 12.0, &["f_seat_z"], sine);
    assert_one_line_error(&[forces.to_str().unwrap()], "no acceleration channel");
    let slow = write_csv(d, "slow.csv", 100.0, 12.0, &["a_base_z"], sine);
    assert_one_line_error(&[slow.to_str().unwrap()], "160");
    let nan = write_csv(d, "nan.csv", 500.0, 12.0, &["a_base_z"], |i, c| {
        if i == 700 { "NaN".into() } else { sine(i, c) }
    });
    assert_one_line_error(&[nan.to_str().unwrap()], "nan.csv");
    let good = write_csv(d, "good.csv", 500.0, 12.0, &["a_base_z"], sine);
    assert_one_line_error(
        &[good.to_str().unwrap(), "--exposure-hours=-1"],
        "exposure-hours",
    );
}

#[test]
fn json_report_and_plots() {
    let dir = tempfile::tempdir().unwrap();
    let run = write_csv(
        dir.path(),
        "run.csv",
        500.0,
        20.0,
        &["a_base_z", "a_seat_z", "a_seat_x"],
        sine,
    );
    let plots = dir.path().join("plots");
    let (ok, out, err) = analyze(&[
        run.to_str().unwrap(),
        "--json",
        "--plot",
        plots.to_str().unwrap(),
        "--exposure-hours",
        "4",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let seat = v["channels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "a_seat_z")
        .unwrap();
    for key in ["a_w", "vdv", "mtvv", "crest_factor"] {
        assert!(seat[key].as_f64().unwrap() > 0.0, "{key}");
    }
    // Seat = 2 × base; each channel's start is predicted from its own 6-digit samples, so the
    // ratio holds to the rounding, not to the last bit.
    assert!((v["seat_percent"].as_f64().unwrap() - 200.0).abs() < 1e-3);
    assert!(v["comfort"].is_string() && v["units"]["vdv"] == "m/s^1.75");
    for f in ["psd.png", "weighted_psd.png", "transmissibility.png"] {
        assert!(plots.join(f).is_file(), "{f}");
    }
    let (ok, table, _) = analyze(&[run.to_str().unwrap()]);
    assert!(ok && table.contains("a_seat_z") && table.contains("SEAT"));
}
