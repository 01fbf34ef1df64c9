//! The model commands work on every built-in model and fail with one clear line on bad input.

mod common;
use common::wbv;

#[test]
fn frf_and_modes_work_on_every_builtin_model() {
    let dir = tempfile::tempdir().unwrap();
    let listing = String::from_utf8(wbv(&["models"]).stdout).unwrap();
    for (name, _) in wbv::model::catalog::BUILTIN {
        assert!(listing.contains(name), "`wbv models` lists {name}");
        let out = dir.path().join(format!("{name}.csv"));
        let plot = dir.path().join(name);
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
            "--plot-format",
            "svg",
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
        assert!(plot.join("frf.svg").exists());
        let r = wbv(&["modes", "--model", name, "--json"]);
        assert!(r.status.success(), "modes {name}");
        let json: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
        assert!(!json["undamped"].as_array().unwrap().is_empty());
    }
}

#[test]
fn png_plots_need_no_system_font() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("plots");
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
    let bytes = std::fs::read(plot.join("frf.png")).unwrap();
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

/// `wbv modes --json` on the planar model reports the static equilibrium: the support loads carry
/// the body weight (ΣF_z = m g, ΣF_x = 0) and balance its pitch moment, as the table does.
#[test]
fn planar_modes_json_reports_the_equilibrium() {
    let r = wbv(&["modes", "--model", "planar-occupant", "--json"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let v: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    let eq = &v["equilibrium"];
    let weight = eq["body_weight_n"].as_f64().unwrap();
    let loads = eq["loads"].as_array().unwrap();
    let fz: f64 = loads.iter().map(|l| l["fz_n"].as_f64().unwrap()).sum();
    let fx: f64 = loads.iter().map(|l| l["fx_n"].as_f64().unwrap()).sum();
    let moment: f64 = loads
        .iter()
        .map(|l| {
            l["z_m"].as_f64().unwrap() * l["fx_n"].as_f64().unwrap()
                - l["x_m"].as_f64().unwrap() * l["fz_n"].as_f64().unwrap()
        })
        .sum();
    // 70 kg nominal occupant; the weight comes from the segment table, not from this test.
    assert!(weight > 400.0 && weight < 1200.0, "weight {weight} N");
    assert!((fz - weight).abs() < 1e-6 * weight, "ΣFz {fz} vs {weight}");
    assert!(fx.abs() < 1e-6 * weight, "ΣFx {fx}");
    let gravity = eq["gravity_moment_nm"].as_f64().unwrap();
    assert!(
        (moment + gravity).abs() < 1e-6 * weight,
        "{moment} + {gravity}"
    );
    let described = v["described"].as_array().unwrap();
    assert_eq!(described.len(), v["undamped"].as_array().unwrap().len());
    assert!(
        described
            .iter()
            .any(|d| d["motions"].to_string().contains("fore-and-aft head"))
    );
}
