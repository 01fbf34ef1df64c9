//! One simulated hour at 1 kHz, end to end: `wbv simulate` of the default scenario (reference seat,
//! Bell 214 spectrum) simulated, recorded to MCAP at full rate and analysed, as a whole process;
//! with `--no-record` for comparison. Prints wall time and peak resident memory for each duration,
//! so that memory independent of duration shows directly (`WBV_E2E_HOURS=1,4` for 1 h and 4 h;
//! a recorded hour needs about 3.5 GB of free disk in the temp directory).
//!
//! `cargo bench --bench end_to_end`. A plain timed run, not criterion: an hour-long sample cannot be
//! repeated the dozens of times criterion needs, and the figure of interest is one wall time.

use std::process::Command;
use std::time::Instant;

fn main() {
    let hours: Vec<f64> = std::env::var("WBV_E2E_HOURS")
        .unwrap_or_else(|_| "1".into())
        .split(',')
        .filter_map(|h| h.trim().parse().ok())
        .collect();
    let dir = tempfile::tempdir().expect("temp dir");
    println!(
        "{:>6} {:>10} {:>10} {:>14} {:>12}",
        "hours", "record", "wall s", "peak memory", "file GB"
    );
    for &h in &hours {
        for record in [true, false] {
            let out = dir.path().join(format!("run-{h}-{record}"));
            let mut cmd = Command::new(env!("CARGO_BIN_EXE_wbv"));
            cmd.args(["simulate", "--duration", &(h * 3600.0).to_string()]);
            if record {
                cmd.arg("--out").arg(&out);
            } else {
                cmd.arg("--no-record");
            }
            let start = Instant::now();
            let res = cmd.output().expect("run wbv");
            let wall = start.elapsed().as_secs_f64();
            let text = String::from_utf8_lossy(&res.stdout);
            assert!(
                res.status.success(),
                "{}",
                String::from_utf8_lossy(&res.stderr)
            );
            let memory = text
                .split("peak memory ")
                .nth(1)
                .and_then(|s| s.lines().next())
                .unwrap_or("?");
            let bytes = std::fs::metadata(out.join("run.mcap")).map_or(0, |m| m.len());
            println!(
                "{h:>6} {record:>10} {wall:>10.2} {memory:>14} {:>12.2}",
                bytes as f64 / 1e9
            );
            let _ = std::fs::remove_dir_all(&out);
        }
    }
}
