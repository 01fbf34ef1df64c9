//! One simulated hour at 1 kHz, end to end: `wbv simulate` with its defaults (reference seat, white
//! 0.5–80 Hz random) simulated, recorded to MCAP and analysed, as a whole process, in the same
//! run: recorded at full rate with protobuf per sample (the default) and batched, with JSON, at
//! `--record-rate 100`, and with `--no-record`; and the layout × compression table (per-sample and
//! batched, each with zstd, lz4 and none; `WBV_E2E_LAYOUTS=0` leaves it out). Prints wall time, CPU time (user + system of the process and its
//! threads), peak resident memory, file size and bytes per simulated second, so that memory
//! independent of duration shows directly (`WBV_E2E_HOURS=1,4` for 1 h and 4 h; a full-rate JSON
//! hour needs about 1.7 GB of free disk in the temp directory, `WBV_E2E_JSON=0` leaves it out).
//!
//! `cargo bench --bench end_to_end`. A plain timed run, not criterion: an hour-long sample cannot be
//! repeated the dozens of times criterion needs, and the figure of interest is one wall time.

use std::process::Command;
use std::time::Instant;

/// User + system CPU seconds of the children waited for so far.
fn children_cpu_s() -> f64 {
    // SAFETY: getrusage only writes the struct it is given.
    let mut r: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut r) };
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(r.ru_utime) + t(r.ru_stime)
}

fn main() {
    let hours: Vec<f64> = std::env::var("WBV_E2E_HOURS")
        .unwrap_or_else(|_| "1".into())
        .split(',')
        .filter_map(|h| h.trim().parse().ok())
        .collect();
    let json = std::env::var("WBV_E2E_JSON").map_or(true, |v| v != "0");
    let dir = tempfile::tempdir().expect("temp dir");
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average before: {}", load.trim());
    println!(
        "{:>5} {:<32} {:>8} {:>8} {:>12} {:>9} {:>12}",
        "hours", "run", "wall s", "CPU s", "peak memory", "file GB", "B/sim s"
    );
    let mut cases: Vec<(&str, Vec<&str>)> = vec![
        ("protobuf per-sample zstd (default)", vec![]),
        ("batched zstd", vec!["--layout", "batched"]),
        (
            "per-sample, --record-rate 100",
            vec!["--record-rate", "100"],
        ),
        ("per-sample, lz4", vec!["--compression", "lz4"]),
        ("per-sample, none", vec!["--compression", "none"]),
        (
            "batched, lz4",
            vec!["--layout", "batched", "--compression", "lz4"],
        ),
        (
            "batched, none",
            vec!["--layout", "batched", "--compression", "none"],
        ),
    ];
    if std::env::var("WBV_E2E_LAYOUTS").is_ok_and(|v| v == "0") {
        cases.truncate(3);
    }
    if json {
        cases.push(("json, full rate", vec!["--encoding", "json"]));
        cases.push((
            "json, --record-rate 100",
            vec!["--encoding", "json", "--record-rate", "100"],
        ));
    }
    cases.push(("--no-record", vec!["--no-record"]));
    for &h in &hours {
        for (k, (name, args)) in cases.iter().enumerate() {
            let out = dir.path().join(format!("run-{h}-{k}"));
            let mut cmd = Command::new(env!("CARGO_BIN_EXE_wbv"));
            cmd.args(["simulate", "--duration", &(h * 3600.0).to_string()])
                .args(args);
            if !args.contains(&"--no-record") {
                cmd.arg("--out").arg(&out);
            }
            let cpu0 = children_cpu_s();
            let start = Instant::now();
            let res = cmd.output().expect("run wbv");
            let wall = start.elapsed().as_secs_f64();
            let cpu = children_cpu_s() - cpu0;
            // The summary line ("… peak memory N MB") goes to stderr, the analysis to stdout.
            let text = String::from_utf8_lossy(&res.stderr);
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
                "{h:>5} {name:<32} {wall:>8.2} {cpu:>8.2} {memory:>12} {:>9.3} {:>12.0}",
                bytes as f64 / 1e9,
                bytes as f64 / (h * 3600.0)
            );
            let _ = std::fs::remove_dir_all(&out);
        }
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average after: {}", load.trim());
}
