//! The command line as a new user types it: a mistyped option is one `wbv: error:` line with the
//! parser's suggestion, for every command (help and version still print normally); one default
//! exposure for the health assessment in `analyze`, `report` and `run`, stated in each one's help;
//! `wbv sweep` times itself, prints no status line before an error and has help that tells the
//! truth; the README says how to get `wbv` on the PATH.

mod common;
use common::wbv;
use serde_json::Value;

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// The subcommands `wbv --help` lists (the `Commands:` section, without `help`).
fn subcommands() -> Vec<String> {
    let help = text(&wbv(&["--help"]).stdout);
    help.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .filter(|l| l.starts_with("  ") && !l.starts_with("   "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|n| *n != "help")
        .map(str::to_string)
        .collect()
}

#[test]
fn a_mistyped_option_is_one_error_line_with_the_suggestion_for_every_command() {
    let commands = subcommands();
    assert!(commands.len() >= 20, "{commands:?}");
    for c in &commands {
        // Every command takes --json: `--jsn` is a typo clap can suggest a fix for.
        let out = wbv(&[c.as_str(), "--jsn"]);
        let err = text(&out.stderr);
        assert!(!out.status.success(), "{c}");
        assert_eq!(out.status.code(), Some(2), "{c}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{c}: {err}");
        assert!(
            err.starts_with("wbv: error: --jsn: not an option of `wbv ")
                && err.contains("did you mean `--json`?"),
            "{c}: {err}"
        );
    }
    // The issue's own case, a missing value, a bad value and an unknown command.
    for (args, needle) in [
        (
            &["analyze", "x.csv", "--unit", "g"][..],
            "did you mean `--units`?",
        ),
        (
            &["report", "x.csv", "--exposure-hours"],
            "--exposure-hours: a value is required",
        ),
        (
            &["analyze", "x.csv", "--fs", "fast"],
            "--fs: `fast`: invalid float literal",
        ),
        (
            &["analyze", "x.csv", "--plot-format", "gif"],
            "`gif` is not one of png, svg",
        ),
        (&["anlyze", "x.csv"], "did you mean `analyze`?"),
        (&["analyze", "x.csv", "--ignore-time"], "needs --fs"),
        // A long option typed with one dash, as MATLAB and scipy users do.
        (
            &["analyze", "x.csv", "-fs", "1000"],
            "-fs: not an option of `wbv analyze` (long options take two dashes); did you mean `--fs`?",
        ),
        // A negative value reaches the option's own check, not "unknown option -1".
        (
            &["report", "x.csv", "--exposure-hours", "-1"],
            "--exposure-hours: -1 h; expected a daily exposure in hours > 0",
        ),
    ] {
        let out = wbv(args);
        let err = text(&out.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with("wbv: error: ") && err.contains(needle),
            "{args:?}: {err}"
        );
    }
    // Help and version print as usual, on stdout, with success.
    for args in [&["--help"][..], &["analyze", "--help"], &["--version"]] {
        let out = wbv(args);
        assert!(out.status.success(), "{args:?}");
        assert!(text(&out.stderr).is_empty(), "{args:?}");
        assert!(!text(&out.stdout).starts_with("wbv: error"), "{args:?}");
    }
    assert!(text(&wbv(&["analyze", "--help"]).stdout).lines().count() > 20);
}

/// Runs `wbv args` in `dir` and parses its JSON document.
fn json_in(dir: &std::path::Path, args: &[&str]) -> Value {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn analyze_report_and_run_assume_the_same_exposure() {
    for c in ["analyze", "report", "run"] {
        let help = text(&wbv(&[c, "--help"]).stdout);
        assert!(
            help.contains(
                "Default 8 h, a working day, in `wbv analyze`, `wbv report` and `wbv run` alike"
            ) && help.contains("[default: 8]"),
            "{c}: {help}"
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    json_in(
        d,
        &[
            "simulate",
            "--model",
            "reference",
            "--excitation",
            "bell-214",
            "--duration",
            "12",
            "--seed",
            "2",
            "--out",
            "r",
            "--json",
        ],
    );
    // Without --exposure-hours both assess health at 8 h, with the same figures.
    let analyze = json_in(d, &["analyze", "r", "--json"]);
    let report = json_in(d, &["report", "r", "--json"]);
    assert_eq!(analyze["health"]["exposure_hours"], 8.0);
    assert_eq!(analyze["health"], report["health"]);
    // A simulated run's units are SI by construction: nothing is assumed.
    assert_eq!(analyze["unit_assumed"], false);
    let four = json_in(d, &["analyze", "r", "--exposure-hours", "4", "--json"]);
    assert_eq!(four["health"]["exposure_hours"], 4.0);
    // `run` writes under runs/ of its working directory; its health assumes the same 8 h.
    let run = json_in(d, &["run", "--out", "default", "--json"]);
    assert_eq!(run["exposure_hours"], 8.0);
    assert_eq!(run["health"]["exposure_hours"], 8.0);
}

fn sweep_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut a = vec![
        "sweep",
        "--model",
        "reference",
        "--param",
        "link.cushion.k",
        "--values",
        "20000:40000:5",
        "--excitation",
        "bell-214",
    ];
    a.extend_from_slice(extra);
    a
}

#[test]
fn sweep_times_itself_and_its_help_tells_the_truth() {
    let out = wbv(&sweep_args(&["--json"]));
    assert!(out.status.success(), "{}", text(&out.stderr));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let (t, per) = (
        v["elapsed_s"].as_f64().unwrap(),
        v["seconds_per_point"].as_f64().unwrap(),
    );
    assert!(t > 0.0 && (per * 5.0 - t).abs() <= 1e-12 * t, "{t} {per}");
    let out = wbv(&sweep_args(&[]));
    let err = text(&out.stderr);
    assert!(
        err.contains("ISO figures: spectral") && err.contains("timing: 5 points in "),
        "{err}"
    );
    // An argument error found by the sweep itself is the only line printed.
    let out = wbv(&sweep_args(&["--response", "t_nowhere"]));
    let err = text(&out.stderr);
    assert!(!out.status.success());
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.starts_with("wbv: error: --response"), "{err}");
    // A negative start of a range is a value, not an option.
    let out = wbv(&["sweep", "--param", "link.cushion.k", "--values", "-1:3:3"]);
    let err = text(&out.stderr);
    assert!(
        err.contains("-1") && !err.contains("not an option"),
        "{err}"
    );
    let help = text(&wbv(&["sweep", "--help"]).stdout);
    assert!(!help.contains("[default: white-0.5-80]"), "{help}");
    assert!(!help.contains("Time-domain ISO 2631-1 figures"), "{help}");
    assert!(
        help.contains("ISO 2631-1 figures (given an excitation; from its spectrum"),
        "{help}"
    );
}

#[test]
fn the_readme_says_how_to_get_wbv_and_declares_units() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    assert!(readme.contains("cargo install --path ."), "install step");
    assert!(readme.contains("target/release/wbv"), "the built binary");
    assert!(
        readme.contains("first build"),
        "how long the first build takes"
    );
    // The first `wbv analyze` example a user copies declares its units.
    let first = readme
        .lines()
        .find(|l| l.trim_start().starts_with("wbv analyze "))
        .unwrap();
    assert!(first.contains("--units"), "{first}");
    // The command table is one table: a line between its rows ends it, and the rows after it
    // render as a paragraph of pipes.
    let rows: Vec<usize> = readme
        .lines()
        .enumerate()
        .filter(|(_, l)| l.starts_with("| `wbv "))
        .map(|(i, _)| i)
        .collect();
    assert!(rows.len() > 10, "the command table");
    assert!(
        rows.windows(2).all(|w| w[1] == w[0] + 1),
        "the command table is broken at README line {:?}",
        rows.windows(2).find(|w| w[1] != w[0] + 1).map(|w| w[0] + 2)
    );
}
