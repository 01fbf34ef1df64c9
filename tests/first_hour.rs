//! A new user's first hour, on files written by other tools (`tools/input-fixtures/run`: Python's
//! csv module in a spreadsheet's export styles, numpy.savetxt) and `wbv` run as a user types it:
//! units that cannot be silently wrong, spreadsheets read as exported, a missing column's error
//! that lists the file's columns, and `--fs` that never contradicts the file's time column.
//! `tools/test` runs this with `WBV_INPUT_FIXTURES=DIR`; without it the test says so and checks
//! nothing else.

mod common;

use serde_json::Value;
use std::process::Command;

/// The fixture directory, or None (with a note) when `WBV_INPUT_FIXTURES` is not set.
/// `wbv args` in `cwd`: (success, stdout, stderr).
fn wbv(args: &[&str], cwd: &std::path::Path) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The one `wbv: error:` line of a failed command.
fn one_error_line(args: &[&str], cwd: &std::path::Path) -> String {
    let (ok, _, err) = wbv(args, cwd);
    assert!(!ok, "wbv {args:?} succeeded");
    assert_eq!(err.trim_end().lines().count(), 1, "wbv {args:?}: {err}");
    assert!(err.starts_with("wbv: error: "), "{err}");
    err
}

fn json(args: &[&str], cwd: &std::path::Path) -> Value {
    let (ok, out, err) = wbv(args, cwd);
    assert!(ok, "wbv {args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

fn seat_a_w(v: &Value) -> f64 {
    v["channels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "a_seat_z")
        .unwrap()["a_w"]
        .as_f64()
        .unwrap()
}

/// A seat channel in g without gravity and without a unit (numpy.savetxt): no number can tell g
/// from m/s², so the text's verdict lines, the JSON and the HTML report's verdict boxes all say
/// the figures assume m/s²; `--units g` removes the assumption and scales every figure by g_n.
#[test]
fn an_undeclared_unit_is_stated_beside_every_verdict() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    let (ok, text, err) = wbv(&["analyze", "g-seat.csv"], &dir);
    assert!(ok, "{err}");
    let verdicts: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("Comfort (") || l.starts_with("Health ("))
        .collect();
    assert_eq!(verdicts.len(), 2, "{text}");
    assert!(
        text.lines()
            .find(|l| l.starts_with("Comfort ("))
            .unwrap()
            .contains("assumes m/s²"),
        "{text}"
    );
    // The line after the health header says it too, and the top of the report names the channel.
    let lines: Vec<&str> = text.lines().collect();
    let h = lines
        .iter()
        .position(|l| l.starts_with("Health ("))
        .unwrap();
    assert!(lines[h + 1].contains("assumes m/s²"), "{text}");
    assert!(
        lines[1].starts_with("UNIT NOT DECLARED") && lines[1].contains("a_seat_z"),
        "{text}"
    );

    let assumed = json(&["analyze", "g-seat.csv", "--json"], &dir);
    assert_eq!(assumed["unit_assumed"], true);
    assert_eq!(
        assumed["unit_assumed_channels"],
        serde_json::json!(["a_seat_z"])
    );
    let declared = json(&["analyze", "g-seat.csv", "--units", "g", "--json"], &dir);
    assert_eq!(declared["unit_assumed"], false);
    assert_eq!(declared["unit_assumed_channels"], serde_json::json!([]));
    // The weighting is linear: declaring g multiplies a_w by g_n exactly (to rounding).
    let ratio = seat_a_w(&declared) / seat_a_w(&assumed);
    assert!((ratio / 9.80665 - 1.0).abs() < 1e-9, "{ratio}");
    let (ok, text, _) = wbv(&["analyze", "g-seat.csv", "--units", "g"], &dir);
    assert!(ok && !text.contains("assumes m/s²"), "{text}");

    // The HTML report: inside both verdict boxes (comfort paragraph, health block).
    let tmp = tempfile::tempdir().unwrap();
    let html = tmp.path().join("r.html");
    let (ok, _, err) = wbv(
        &["report", "g-seat.csv", "--out", html.to_str().unwrap()],
        &dir,
    );
    assert!(ok, "{err}");
    assert!(err.contains("UNIT NOT DECLARED"), "{err}");
    let page = std::fs::read_to_string(&html).unwrap();
    let boxes: Vec<&str> = page
        .split("class=\"verdict\"")
        .skip(1)
        .map(|b| &b[..b.find("</p>\n").or(b.find("</div>")).unwrap()])
        .collect();
    assert_eq!(boxes.len(), 2, "{page}");
    for b in boxes {
        assert!(b.contains("Assumes m/s²"), "{b}");
    }
    let summary = json(
        &[
            "report",
            "g-seat.csv",
            "--out",
            tmp.path().join("s.html").to_str().unwrap(),
            "--json",
        ],
        &dir,
    );
    assert_eq!(summary["unit_assumed"], true);
    // The working day too: its verdict says which operation's channel assumes m/s².
    let (ok, text, _) = wbv(&["exposure", "--operation", "g-seat.csv:4"], &dir);
    assert!(ok);
    let verdict: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("Working day"))
        .collect();
    assert!(
        verdict[1].contains("UNIT NOT DECLARED") && verdict[1].contains("g-seat.csv a_seat_z"),
        "{text}"
    );
    let day = json(&["exposure", "--operation", "g-seat.csv:4", "--json"], &dir);
    assert_eq!(day["unit_assumed"], true);
    assert_eq!(
        day["operations"][0]["unit_assumed_channels"],
        serde_json::json!(["a_seat_z"])
    );
    let declared = json(
        &[
            "exposure",
            "--operation",
            "g-seat.csv:4",
            "--units",
            "g",
            "--json",
        ],
        &dir,
    );
    assert_eq!(declared["unit_assumed"], false);
}

/// A spreadsheet's export with `,` between fields and quoted decimal commas (`"0,001953"`), with
/// and without a BOM and a units row: read at its rate, its second line data (a line of numbers
/// is never a units row), the decimal commas said in a note.
#[test]
fn a_spreadsheet_with_quoted_decimal_commas_is_read() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    let v = json(
        &[
            "analyze",
            "sheet-comma.csv",
            "--column",
            "a_seat_z=Acc Z seat",
            "--column",
            "a_base_z=Acc Z base",
            "--json",
        ],
        &dir,
    );
    assert_eq!(v["sample_rate_hz"], 512.0);
    let warnings = v["warnings"].to_string();
    assert!(warnings.contains("quoted decimal commas"), "{warnings}");
    // 12 s at 512 Hz: every line after the header is a sample (none taken as units).
    assert!((v["duration_s"].as_f64().unwrap() - 12.0).abs() < 1e-9);
    let v = json(&["analyze", "sheet-comma-units.csv", "--json"], &dir);
    assert_eq!(v["sample_rate_hz"], 512.0);
    assert_eq!(v["unit_assumed"], false);
}

/// `--column` naming no column, or one already taken, lists every column of the file.
#[test]
fn a_missing_column_lists_the_files_columns() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    let e = one_error_line(
        &["analyze", "logger.csv", "--column", "a_seat_z=Acc Z"],
        &dir,
    );
    for c in ["`Time`", "`Acc Z seat`", "`Acc Z base`", "`Status`"] {
        assert!(e.contains(c), "{e}");
    }
    // Every column already taken: the list is still the file's.
    let e = one_error_line(
        &[
            "analyze",
            "g-seat.csv",
            "--column",
            "a_seat_z=a_seat_z",
            "--column",
            "a_base_z=a_seat_z",
        ],
        &dir,
    );
    assert!(
        e.contains("already taken") && e.contains("`t_s`, `a_seat_z`"),
        "{e}"
    );
}

/// `--fs` that disagrees with the time column is an error naming both rates; one that agrees is
/// noted; `--ignore-time` takes it over the time column; on a file without time it is stated
/// with the duration it gives.
#[test]
fn fs_never_contradicts_the_time_column() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    let e = one_error_line(&["analyze", "g-seat.csv", "--fs", "1000"], &dir);
    assert!(
        e.contains("1000 Hz") && e.contains("512 Hz") && e.contains("--ignore-time"),
        "{e}"
    );
    let v = json(&["analyze", "g-seat.csv", "--fs", "512", "--json"], &dir);
    assert_eq!(v["sample_rate_hz"], 512.0);
    assert!(
        v["warnings"].to_string().contains("agrees"),
        "{}",
        v["warnings"]
    );
    let v = json(
        &[
            "analyze",
            "g-seat.csv",
            "--fs",
            "1000",
            "--ignore-time",
            "--json",
        ],
        &dir,
    );
    assert_eq!(v["sample_rate_hz"], 1000.0);
    assert!(
        v["warnings"].to_string().contains("ignored"),
        "{}",
        v["warnings"]
    );
    // The file without time (320 Hz, 10 s): the rate and the duration it gives are stated.
    let (ok, _, err) = wbv(&["analyze", "no-time.tsv", "--fs", "320"], &dir);
    assert!(ok, "{err}");
    assert!(
        err.contains("320 Hz from --fs") && err.contains("last 10.000 s"),
        "{err}"
    );
    // A file that states its rate refuses both.
    let e = one_error_line(
        &[
            "analyze",
            "float32.wav",
            "--column",
            "a_seat_z=1",
            "--sensitivity",
            "a_seat_z=1",
            "--fs",
            "512",
        ],
        &dir,
    );
    assert!(e.contains("states its sample rate"), "{e}");
}
