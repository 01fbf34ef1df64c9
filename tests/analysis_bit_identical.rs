//! The figures of fixed records are bit for bit those the analysis gave before it was made faster
//! (issue 75): `wbv analyze --json` and `wbv exposure --json` of two generated CSV records — one
//! with a crest factor of about 4 (no ISO 2631-5), one with shocks (crest factor above 9, so the
//! spinal response is assessed) and a planted spike and dropout (acquisition warnings) — compared
//! with the documents the code before the speed work printed for the same files, stored in
//! `tests/golden/` (written by that binary, `target/release/wbv` of commit baef02b, from the CSVs
//! this test writes; `WBV_GOLDEN_INPUTS=DIR` keeps them in DIR to regenerate the documents).

mod common;

use std::fmt::Write as _;
use std::path::Path;

/// Deterministic uniform noise in [−0.5, 0.5) (xorshift64).
fn noise(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}

/// A 90 s, 1 kHz record: base z, seat x and seat z (a 4 Hz resonance of the base), every value
/// printed in its shortest round-trip form, so the file reads back to the same doubles.
fn record(shocks: bool) -> String {
    let (fs, n) = (1000.0, 90_000);
    let base: Vec<f64> = {
        let w = noise(n + 8, 7);
        (0..n)
            .map(|i| w[i..i + 8].iter().sum::<f64>() * 0.4)
            .collect()
    };
    let (r, th) = (0.995f64, 2.0 * std::f64::consts::PI * 4.0 / fs);
    let (mut y1, mut y2) = (0.0, 0.0);
    let mut seat_z: Vec<f64> = base
        .iter()
        .map(|&u| {
            let y = 2.0 * r * th.cos() * y1 - r * r * y2 + 0.02 * u;
            (y2, y1) = (y1, y);
            y + 0.2 * u
        })
        .collect();
    let seat_x: Vec<f64> = noise(n, 11).iter().map(|v| 0.3 * v).collect();
    if shocks {
        for k in 0..12 {
            let at = 5_000 + k * 7_000;
            for j in 0..40 {
                seat_z[at + j] += 90.0 * (std::f64::consts::PI * j as f64 / 40.0).sin();
            }
        }
        seat_z[40_123] += 9.0; // a spike
        let held = seat_z[61_000];
        for v in &mut seat_z[61_000..61_060] {
            *v = held; // a dropout
        }
    }
    let mut s = String::from("t_s,a_base_z,a_seat_x,a_seat_z\n");
    for i in 0..n {
        let _ = writeln!(
            s,
            "{:?},{:?},{:?},{:?}",
            i as f64 / fs,
            base[i],
            seat_x[i],
            seat_z[i]
        );
    }
    s
}

fn golden(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn stdout(args: &[&str]) -> String {
    let out = common::wbv(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn figures_are_those_before_the_speed_work_bit_for_bit() {
    let keep = std::env::var("WBV_GOLDEN_INPUTS").ok();
    let tmp = tempfile::tempdir().unwrap();
    let dir = keep.as_deref().map_or(tmp.path(), Path::new);
    std::fs::create_dir_all(dir).unwrap();
    let calm = dir.join("calm.csv");
    let shocks = dir.join("shocks.csv");
    std::fs::write(&calm, record(false)).unwrap();
    std::fs::write(&shocks, record(true)).unwrap();
    // The documents name the files as given: run where they are.
    std::env::set_current_dir(dir).unwrap();
    for (file, doc) in [
        ("calm.csv", "analyze-calm.json"),
        ("shocks.csv", "analyze-shocks.json"),
    ] {
        let got = stdout(&["analyze", file, "--json"]);
        assert!(
            got == golden(doc),
            "{file}: differs from tests/golden/{doc}"
        );
    }
    let got = stdout(&[
        "exposure",
        "--operation",
        "calm.csv:5",
        "--operation",
        "shocks.csv:2",
        "--json",
    ]);
    assert!(
        got == golden("exposure-day.json"),
        "exposure: differs from tests/golden/exposure-day.json"
    );
}
