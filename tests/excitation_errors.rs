//! Bad excitation definitions give one clear error naming the file, line or key.

use wbv::excitation::{ExcitationArgs, ExcitationSpec, builtin, resolve};

fn parse_err(text: &str) -> String {
    ExcitationSpec::parse(text, "exc.toml", None)
        .unwrap_err()
        .to_string()
}

const HEAD: &str = "description = \"x\"\n[excitation]\n";

#[test]
fn every_builtin_loads_and_builds() {
    for name in builtin::names() {
        let spec = ExcitationSpec::load(name).unwrap();
        let mut exc = spec.build(0.001, 130.0, 1).unwrap();
        let mut x = vec![0.0; 2000];
        exc.fill(&mut x);
        assert!(x.iter().all(|v| v.is_finite()), "{name}");
        assert!(
            !spec.description.is_empty() && spec.source.is_some(),
            "{name}"
        );
    }
}

#[test]
fn unknown_type_key_and_malformed_toml() {
    let e = parse_err(&format!("{HEAD}type = \"earthquake\"\n"));
    assert!(
        e.starts_with("exc.toml:3:") && e.contains("earthquake"),
        "{e}"
    );
    let e = parse_err(&format!(
        "{HEAD}type = \"random\"\nrms_m_s2 = 1.0\nrms = 2\n"
    ));
    // serde buffers tagged enums, so toml reports the line of the `[excitation]` table.
    assert!(
        e.starts_with("exc.toml:2:") && e.contains("unknown field `rms`"),
        "{e}"
    );
    let e = parse_err(&format!("{HEAD}type = \"random\"\nrms_m_s2 = \n"));
    assert!(e.starts_with("exc.toml:4:"), "{e}");
    let e = parse_err(&format!("{HEAD}type = \"random\"\n"));
    assert!(e.contains("rms_m_s2"), "{e}");
    let e = parse_err(&format!("{HEAD}type = \"random\"\nrms_m_s2 = -1.0\n"));
    assert!(
        e.starts_with("exc.toml: excitation.rms_m_s2:") && e.contains("positive"),
        "{e}"
    );
    let e = parse_err(&format!(
        "{HEAD}type = \"random\"\nrms_m_s2 = 1.0\nband_hz = [80.0, 0.5]\n"
    ));
    assert!(e.contains("excitation.band_hz"), "{e}");
    let e = parse_err(&format!(
        "{HEAD}type = \"road\"\nclass = \"Z\"\nspeed_m_s = 10.0\n"
    ));
    assert!(e.contains("excitation.class") && e.contains("A–H"), "{e}");
}

#[test]
fn bad_psd_tables_name_key_file_and_line() {
    let e = parse_err(&format!(
        "{HEAD}type = \"psd\"\npoints = [[1.0, 0.1], [2.0, -0.1]]\n"
    ));
    assert!(
        e.contains("excitation.points") && e.contains("positive"),
        "{e}"
    );
    let e = parse_err(&format!(
        "{HEAD}type = \"psd\"\npoints = [[2.0, 0.1], [1.0, 0.1]]\n"
    ));
    assert!(e.contains("does not increase"), "{e}");
    let e = parse_err(&format!(
        "{HEAD}type = \"psd\"\npoints = [[1.0, nan], [2.0, 0.1]]\n"
    ));
    assert!(e.contains("excitation.points"), "{e}");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("p.csv"), "freq_hz,psd\n1,0.1\n2,0\n").unwrap();
    let toml = dir.path().join("e.toml");
    std::fs::write(&toml, format!("{HEAD}type = \"psd\"\ncsv = \"p.csv\"\n")).unwrap();
    let e = ExcitationSpec::load(toml.to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(e.contains("p.csv:3:") && e.contains("positive"), "{e}");
    let e = ExcitationSpec::load(dir.path().join("missing.toml").to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing.toml"), "{e}");
    let e = ExcitationSpec::load("no-such-builtin")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no-such-builtin") && e.contains("bell-214"),
        "{e}"
    );
}

#[test]
fn command_line_choices() {
    use clap::Parser;
    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        exc: ExcitationArgs,
    }
    let spec = |args: &[&str]| resolve(&Cli::parse_from([&["wbv"], args].concat()).exc);
    let s = spec(&["--excitation", "random", "--rms", "1.0", "--band", "1,40"]).unwrap();
    assert!((s.psd(10.0) - 1.0 / 39.0).abs() < 1e-15 && s.psd(50.0) == 0.0);
    let s = spec(&["--excitation", "sine", "--freq", "4", "--amplitude", "1"]).unwrap();
    assert_eq!(s.tones(), vec![(4.0, 1.0)]);
    let s = spec(&["--excitation", "bell-214"]).unwrap();
    assert_eq!(s.tones().len(), 4);
    let s = spec(&["--excitation", "road", "--road-class", "D", "--speed", "15"]).unwrap();
    assert_eq!(s.band_hz().unwrap()[1], 2.83 * 15.0);
    let e = spec(&["--excitation", "random"]).unwrap_err().to_string();
    assert!(e.starts_with("--rms:"), "{e}");
    let e = spec(&["--excitation", "sine", "--freq=-4", "--amplitude", "1"])
        .unwrap_err()
        .to_string();
    assert!(e.contains("frequency_hz"), "{e}");
}
