//! Every subcommand that `wbv --help` lists runs with `--json` on small built-in inputs: stdout is
//! exactly one JSON document (nothing else: status lines and warnings go to stderr) with the
//! command's name, its expected top-level keys, a `warnings` array, sizes of the files it wrote,
//! and no `null` where a figure is expected. A subcommand added without a case here fails the test.

mod common;
use serde_json::Value;
use std::path::Path;

/// Runs `wbv args` and returns its stdout parsed as one JSON document, with its stderr.
fn json_of(args: &[String], cwd: &Path) -> (Value, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "wbv {}: {stderr}", args.join(" "));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "wbv {}: stdout is not one JSON document ({e}):\n{}",
            args.join(" "),
            String::from_utf8_lossy(&out.stdout)
        )
    });
    (v, stderr)
}

/// The subcommands `wbv --help` lists (the `Commands:` section, without `help`).
fn subcommands() -> Vec<String> {
    let out = common::wbv(&["--help"]);
    let text = String::from_utf8(out.stdout).unwrap();
    let mut names = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if line.starts_with("Commands:") {
            inside = true;
        } else if inside && line.trim().is_empty() {
            break;
        } else if inside
            && line.starts_with("  ")
            && !line.starts_with("   ")
            && let Some(name) = line.split_whitespace().next()
            && name != "help"
        {
            names.push(name.to_string());
        }
    }
    assert!(names.len() >= 20, "subcommands of wbv --help: {names:?}");
    names
}

/// Every number in `v` is finite (JSON has no NaN; a large exponent must not have overflowed)
/// and no key listed in `figures` is `null` anywhere in the document.
fn check_values(v: &Value, at: &str, figures: &[&str], command: &str) {
    match v {
        Value::Number(n) => {
            let x = n.as_f64().unwrap();
            assert!(x.is_finite(), "{command}: {at} = {n}");
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                check_values(x, &format!("{at}[{i}]"), figures, command);
            }
        }
        Value::Object(m) => {
            for (k, x) in m {
                if figures.contains(&k.as_str()) {
                    assert!(!x.is_null(), "{command}: {at}.{k} is null");
                }
                check_values(x, &format!("{at}.{k}"), figures, command);
            }
        }
        _ => {}
    }
}

/// Keys that are figures wherever they appear: never `null`.
const FIGURES: [&str; 12] = [
    "a_w",
    "vdv",
    "mtvv",
    "total_value",
    "rms",
    "peak_freq_hz",
    "peak_mag",
    "freq_hz",
    "duration_s",
    "bytes",
    "sample_rate_hz",
    "elapsed_s",
];

fn args(a: &[&str]) -> Vec<String> {
    a.iter().map(|x| x.to_string()).collect()
}

#[test]
fn every_subcommand_prints_one_json_document() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Inputs: a short simulated run (MCAP + CSV), three 20 s measured-run CSVs for the gap
    // diagnosis (two magnitudes to train on, one to check), a calibration target (the closed-form
    // transmissibility of a 4 Hz, ζ = 0.3 single-degree-of-freedom system) and two sweep shards.
    let (_, _) = json_of(
        &args(&[
            "simulate",
            "--model",
            "reference",
            "--excitation",
            "bell-214",
            "--duration",
            "6",
            "--seed",
            "2",
            "--out",
            "run",
            "--json",
        ]),
        d,
    );
    for (name, rms, seed) in [("a", "0.5", "3"), ("b", "1.0", "4"), ("c", "0.7", "5")] {
        json_of(
            &args(&[
                "simulate",
                "--model",
                "reference",
                "--excitation",
                "random",
                "--rms",
                rms,
                "--band",
                "0.5,40",
                "--duration",
                "20",
                "--dt",
                "0.002",
                "--seed",
                seed,
                "--no-record",
                "--csv",
                &format!("{name}.csv"),
                "--json",
            ]),
            d,
        );
    }
    let mut target = String::from("freq_hz,mag\n");
    for i in 0..30 {
        let f = 1.0 + 0.3 * f64::from(i);
        let (r, z) = (f / 4.0, 0.3);
        let num = 1.0 + (2.0 * z * r).powi(2);
        let den = (1.0 - r * r).powi(2) + (2.0 * z * r).powi(2);
        target += &format!("{f},{}\n", (num / den).sqrt());
    }
    std::fs::write(d.join("target.csv"), target).unwrap();
    let sweep = |extra: &[&str]| {
        let mut a = args(&[
            "sweep",
            "--model",
            "seed001-full",
            "--param",
            "link.cushion.k",
            "--values",
            "18500:22500:3",
            "--points",
            "40",
        ]);
        a.extend(args(extra));
        a
    };
    for k in ["1", "2"] {
        json_of(
            &sweep(&[
                "--shard",
                &format!("{k}/2"),
                "--out",
                &format!("shard{k}.csv"),
                "--json",
            ]),
            d,
        );
    }
    let gap = args(&[
        "gap",
        "--model",
        "reference",
        "--run",
        "a.csv",
        "--run",
        "b.csv",
        "--check",
        "c.csv",
        "--json",
    ]);
    let (diagnosis, _) = json_of(&gap, d);
    std::fs::write(d.join("gap.json"), diagnosis.to_string()).unwrap();

    // Every subcommand: arguments and the top-level keys its document must have.
    let cases: Vec<(&str, Vec<String>, &[&str])> = vec![
        (
            "analyze",
            args(&["analyze", "run", "--json"]),
            &[
                "channels",
                "total_value",
                "comfort",
                "units",
                "written",
                "unit_assumed",
                "unit_assumed_channels",
                "health",
            ],
        ),
        (
            "exposure",
            args(&[
                "exposure",
                "--operation",
                "a.csv:4",
                "--operation",
                "run:2.5",
                "--iso2631-5",
                "--json",
            ]),
            &[
                "a8",
                "vdv_day",
                "zone",
                "operations",
                "axes",
                "iso2631_5",
                "units",
            ],
        ),
        ("models", args(&["models", "--json"]), &["models"]),
        (
            "frf",
            args(&["frf", "--points", "50", "--json"]),
            &["model", "freq_hz", "responses", "written"],
        ),
        (
            "modes",
            args(&["modes", "--json"]),
            &["model", "undamped", "damped"],
        ),
        (
            "run",
            args(&["run", "--out", "default-run", "--json"]),
            &["run_dir", "analysis", "health", "written", "report_html"],
        ),
        (
            "report",
            args(&["report", "run", "--gap", "gap.json", "--json"]),
            &[
                "report_html",
                "bytes",
                "total_value",
                "comfort",
                "gap",
                "units",
                "unit_assumed",
            ],
        ),
        (
            "replay",
            args(&["replay", "run", "--json"]),
            &["analysis", "stored", "differences"],
        ),
        (
            "simulate",
            args(&["simulate", "--duration", "2", "--no-record", "--json"]),
            &["model", "excitation", "analysis", "written", "elapsed_s"],
        ),
        (
            "reproduce",
            args(&["reproduce", "--out", "reproduction.md", "--json"]),
            &["rows", "reproduced", "total", "written"],
        ),
        (
            "state-space",
            args(&["state-space", "--json"]),
            &["A", "B", "C", "states"],
        ),
        (
            "weighting",
            args(&["weighting", "--json"]),
            &["weighting", "fs_hz", "sos"],
        ),
        (
            "excitations",
            args(&["excitations", "--json"]),
            &["excitations"],
        ),
        (
            "excitation-export",
            args(&[
                "excitation-export",
                "--excitation",
                "sine-4hz",
                "--duration",
                "1",
                "--out",
                "sine.csv",
                "--json",
            ]),
            &["written", "samples", "sample_rate_hz"],
        ),
        (
            "fmu",
            args(&["fmu", "--out", "seat.fmu", "--json"]),
            &["written", "guid", "variables", "parameters"],
        ),
        (
            "inspect",
            args(&["inspect", "run", "--json"]),
            &["topics", "provenance", "attachments", "duration_s"],
        ),
        (
            "sweep",
            sweep(&["--excitation", "sine-4hz", "--duration", "2", "--json"]),
            &[
                "params",
                "points",
                "written",
                "elapsed_s",
                "seconds_per_point",
            ],
        ),
        (
            "merge-shards",
            args(&[
                "merge-shards",
                "shard1.csv",
                "shard2.csv",
                "--out",
                "merged.csv",
                "--json",
            ]),
            &["written", "shards"],
        ),
        (
            "sensitivity",
            args(&[
                "sensitivity",
                "--model",
                "seed001-full",
                "--param",
                "link.cushion.k",
                "--points",
                "60",
                "--json",
            ]),
            &["rows", "influence", "written"],
        ),
        (
            "foam",
            args(&["foam", "--duration", "2", "--json"]),
            &["points", "area_m2", "time_domain"],
        ),
        (
            "calibrate",
            args(&[
                "calibrate",
                "--model",
                "seed001-full",
                "--param",
                "link.cushion.k",
                "--bounds",
                "5000:80000",
                "--target",
                "target.csv",
                "--method",
                "lm",
                "--json",
            ]),
            &["fits", "model", "response"],
        ),
        (
            "gap",
            gap.clone(),
            &["verdict", "named", "nominal", "candidates"],
        ),
        (
            "gap-bench",
            args(&["gap-bench", "--cases", "1", "--json"]),
            &["cases", "summary"],
        ),
        (
            "seat-test",
            args(&[
                "seat-test",
                "--class",
                "iso7096-em3",
                "--run",
                "a.csv",
                "--run",
                "b.csv",
                "--run",
                "c.csv",
                "--report",
                "seat.html",
                "--json",
            ]),
            &[
                "summary",
                "classes",
                "damping",
                "verdict",
                "verdict_lines",
                "warnings",
                "written",
            ],
        ),
    ];
    let listed = subcommands();
    let missing: Vec<&String> = listed
        .iter()
        .filter(|n| !cases.iter().any(|(c, _, _)| c == n))
        .collect();
    assert!(
        missing.is_empty(),
        "subcommands of `wbv --help` without a --json case here: {missing:?}"
    );
    for (name, a, keys) in &cases {
        assert!(
            listed.iter().any(|n| n == name),
            "{name} is not in wbv --help"
        );
        // The diagnosis already ran once (for the report's gap section).
        let v = if *name == "gap" {
            diagnosis.clone()
        } else {
            json_of(a, d).0
        };
        assert_eq!(v["command"], *name, "{name}: command key");
        assert!(v["warnings"].is_array(), "{name}: warnings array");
        for k in *keys {
            assert!(v.get(*k).is_some(), "{name}: no top-level `{k}` in {v}");
        }
        check_values(&v, name, &FIGURES, name);
        if let Some(w) = v.get("written").and_then(Value::as_array) {
            for f in w {
                let p = d.join(f["path"].as_str().unwrap());
                let bytes = std::fs::metadata(&p).unwrap().len();
                assert_eq!(f["bytes"].as_u64(), Some(bytes), "{name}: {}", p.display());
            }
        }
    }
    // A sweep's comfort column is spelled as in every JSON document.
    let (v, _) = json_of(
        &sweep(&["--excitation", "sine-4hz", "--duration", "2", "--json"]),
        d,
    );
    let comfort = &v["points"][0]["figures"]["comfort"];
    assert!(
        comfort
            .as_str()
            .is_some_and(|c| c.ends_with("uncomfortable")),
        "{comfort}"
    );
    // The report shows the gap section read from the diagnosis.
    let html = std::fs::read_to_string(d.join("run/report.html")).unwrap();
    assert!(html.contains("id=\"gap\"") && html.contains("id=\"gap_map\""));
}
