//! The model commands work on every built-in model and fail with one clear line on bad input.

use std::process::Command;

fn wbv(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn frf_and_modes_work_on_every_builtin_model() {
    let dir = tempfile::tempdir().unwrap();
    let listing = String::from_utf8(wbv(&["models"]).stdout).unwrap();
    for (name, _) in wbv::model::catalog::BUILTIN {
        assert!(listing.contains(name), "`wbv models` lists {name}");
        let out = dir.path().join(format!("{name}.csv"));
        let plot = dir.path().join(format!("{name}.svg"));
        let r = wbv(&[
            "frf",
            "--model",
            name,
            "--points",
            "50",
            "--out",
            out.to_str().unwrap(),
            "--plot",
            plot.to_str().unwrap(),
        ]);
        assert!(
            r.status.success(),
            "frf {name}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
        let csv = std::fs::read_to_string(&out).unwrap();
        let header = csv.lines().next().unwrap();
        assert!(
            header.starts_with("freq_hz,") && header.contains("seat_mag"),
            "{header}"
        );
        assert_eq!(csv.lines().count(), 51);
        assert!(plot.exists());
        let r = wbv(&["modes", "--model", name, "--json"]);
        assert!(r.status.success(), "modes {name}");
        let json: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
        assert!(!json["undamped"].as_array().unwrap().is_empty());
    }
}

#[test]
fn png_plots_need_no_system_font() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("ref.png");
    let r = wbv(&[
        "frf",
        "--points",
        "40",
        "--plot",
        plot.to_str().unwrap(),
        "--out",
        dir.path().join("a.csv").to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let bytes = std::fs::read(&plot).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn bad_model_file_gives_one_clear_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(
        &path,
        "name = \"b\"\ndescription = \"d\"\n[[mass]]\nname = \"m\"\nm = -1.0\n[[link]]\nname = \"l\"\nbetween = [\"m\", \"base\"]\ntype = \"kelvin-voigt\"\nk = 1.0\nc = 1.0\n[measure]\nseat = \"base\"\n",
    )
    .unwrap();
    let r = wbv(&["modes", "--model", path.to_str().unwrap()]);
    assert!(!r.status.success());
    let err = String::from_utf8(r.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("bad.toml") && err.contains("mass[0] (m).m") && err.contains("positive"),
        "{err}"
    );
    let r = wbv(&["frf", "--model", "no-such-model"]);
    assert!(!r.status.success());
    let r = wbv(&["frf", "--from", "10", "--to", "1"]);
    let err = String::from_utf8(r.stderr).unwrap();
    assert!(!r.status.success() && err.contains("--from/--to"), "{err}");
}

#[test]
fn existing_output_is_not_overwritten_without_force() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("f.csv");
    std::fs::write(&out, "keep").unwrap();
    let r = wbv(&["frf", "--points", "10", "--out", out.to_str().unwrap()]);
    assert!(!r.status.success());
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "keep");
    let r = wbv(&[
        "frf",
        "--points",
        "10",
        "--out",
        out.to_str().unwrap(),
        "--force",
    ]);
    assert!(r.status.success());
}
