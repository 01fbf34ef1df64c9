//! `wbv simulate` recordings as files: byte-identical wherever they are written and from `--from`,
//! protobuf and JSON reading back the same signals, clean interruption, leftovers and two writers.

mod common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const RUN: [&str; 11] = [
    "simulate",
    "--model",
    "reference",
    "--excitation",
    "random",
    "--rms",
    "0.8",
    "--duration",
    "3",
    "--seed",
    "7",
];

fn simulate(cwd: &Path, extra: &[&str]) -> std::process::Output {
    let out = Command::new(env!("CARGO_BIN_EXE_wbv"))
        .current_dir(cwd)
        .args(RUN)
        .args(extra)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

#[test]
fn the_same_run_is_byte_identical_from_any_directory_and_from_its_recording() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("deeper/b"));
    std::fs::create_dir_all(&b).unwrap();
    // different working directories, an absolute and a relative output, `--force` on one
    simulate(tmp.path(), &["--out", a.join("run").to_str().unwrap()]);
    simulate(&b, &["--out", "run", "--force"]);
    let first = std::fs::read(a.join("run/run.mcap")).unwrap();
    assert_eq!(first, std::fs::read(b.join("run/run.mcap")).unwrap());

    let again = tmp.path().join("again");
    let out = common::wbv(&[
        "simulate",
        "--from",
        a.join("run").to_str().unwrap(),
        "--out",
        again.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(first, std::fs::read(again.join("run.mcap")).unwrap());

    let meta = wbv::record::inspect(&again.join("run.mcap"))
        .unwrap()
        .metadata;
    assert_eq!(
        meta["wbv.run"]["command_line"],
        "wbv simulate --model reference --excitation random --rms 0.8 --duration 3 --seed 7"
    );
    // the stored excitation is a definition that loads again
    let e = &meta["wbv.excitation"];
    let spec = wbv::record::load_excitation(&e["origin"], &e["definition"]).unwrap();
    assert_eq!(spec.summary(), e["description"]);

    // --from takes no scenario options
    let out = common::wbv(&[
        "simulate",
        "--from",
        a.join("run").to_str().unwrap(),
        "--seed",
        "8",
        "--out",
        tmp.path().join("x").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--seed: cannot be given with --from"));
}

#[test]
fn protobuf_and_json_runs_read_back_the_same_signals_and_replay_their_figures() {
    let tmp = tempfile::tempdir().unwrap();
    let (p, j) = (tmp.path().join("p"), tmp.path().join("j"));
    simulate(tmp.path(), &["--out", p.to_str().unwrap()]);
    simulate(
        tmp.path(),
        &["--out", j.to_str().unwrap(), "--encoding", "json"],
    );
    let rp = wbv::record::read_run(&p.join("run.mcap")).unwrap();
    let rj = wbv::record::read_run(&j.join("run.mcap")).unwrap();
    let enc = |r: &wbv::record::RecordedRun| {
        r.summary
            .topics
            .iter()
            .map(|t| t.message_encoding.clone())
            .collect::<Vec<_>>()
    };
    assert!(enc(&rp).iter().all(|e| e == "protobuf"), "{:?}", enc(&rp));
    assert!(enc(&rj).iter().all(|e| e == "json"));
    assert_eq!(rp.signals.names, rj.signals.names);
    assert!(rp.signals.names.len() > 20, "{:?}", rp.signals.names);
    for name in &rp.signals.names {
        let (a, b) = (
            rp.signals.require(name).unwrap(),
            rj.signals.require(name).unwrap(),
        );
        assert!(
            a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()),
            "{name}"
        );
    }
    assert_eq!(rp.results, rj.results);
    // and both replay to the stored figures
    for dir in [&p, &j] {
        let out = common::wbv(&["replay", dir.to_str().unwrap()]);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success() && text.contains("replayed figures equal"),
            "{text}{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let protobuf = std::fs::metadata(p.join("run.mcap")).unwrap().len();
    let json = std::fs::metadata(j.join("run.mcap")).unwrap().len();
    assert!(protobuf < json, "{protobuf} vs {json} bytes");
}

#[test]
fn sigint_closes_a_valid_interrupted_recording_and_exits_non_zero() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let mut child = Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args(["simulate", "--duration", "36000", "--out"])
        .arg(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let partial = dir.join("run.mcap.partial");
    let start = Instant::now();
    while !partial.exists() && start.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(1000));
    let signalled = Instant::now();
    // SAFETY: sending a signal to our own child process.
    unsafe { libc::kill(child.id() as i32, libc::SIGINT) };
    let status = child.wait().unwrap();
    let stopped = signalled.elapsed();
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    assert!(!status.success(), "{stderr}");
    assert!(stopped < Duration::from_secs(2), "{stopped:?}");
    assert!(stderr.contains("interrupted"), "{stderr}");
    assert!(!dir.join("run.mcap").exists() && !partial.exists());
    let file = dir.join("run.interrupted.mcap");
    let run = wbv::record::read_run(&file).unwrap();
    let at: f64 = run.summary.metadata["wbv.interrupted"]["interrupted_at_s"]
        .parse()
        .unwrap();
    assert!(at > 0.0 && at < 36000.0);
    // every step up to the interruption is there
    assert_eq!(run.signals.len() as f64, (at * 1000.0).round() + 1.0);
}

#[test]
fn a_leftover_partial_is_removed_and_a_live_one_refuses_a_second_writer() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    std::fs::create_dir_all(&dir).unwrap();
    let partial = dir.join("run.mcap.partial");
    std::fs::write(&partial, b"left by kill -9").unwrap();
    let out = simulate(tmp.path(), &["--out", dir.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("left by an earlier run"), "{stderr}");
    assert!(dir.join("run.mcap").exists() && !partial.exists());

    // a partial file held (locked) by a live writer: the second writer is refused at once
    let live = tmp.path().join("live");
    std::fs::create_dir_all(&live).unwrap();
    let held = std::fs::File::create(live.join("run.mcap.partial")).unwrap();
    held.lock().unwrap();
    let out = common::wbv(&[
        "simulate",
        "--duration",
        "1",
        "--out",
        live.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("another process is writing"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!live.join("run.mcap").exists());
}
