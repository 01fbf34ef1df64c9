//! A sweep run as 3 shards in separate processes merges into the unsharded output byte for byte.

use std::path::Path;
use std::process::Command;

fn wbv(args: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The sweep of the shard test: a 5 × 3 grid, with time-domain ISO figures per point (a short
/// random run) so that those columns travel through the shards too.
fn sweep(out: &Path, shard: Option<&str>) {
    let mut args = vec![
        "sweep",
        "--model",
        "seed001-full",
        "--param",
        "link.cushion.k",
        "--values",
        "18500:22500:5",
        "--param",
        "link.cushion.zeta@60",
        "--values",
        "0.06,0.08,0.1",
        "--response",
        "t_head",
        "--from",
        "1",
        "--to",
        "10",
        "--points",
        "40",
        "--excitation",
        "random",
        "--rms",
        "0.4",
        "--duration",
        "4",
        "--out",
        out.to_str().unwrap(),
    ];
    if let Some(s) = shard {
        args.extend(["--shard", s]);
    }
    wbv(&args);
}

#[test]
fn three_shards_merge_to_the_unsharded_output() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    sweep(&d.join("all.csv"), None);
    let handles: Vec<_> = (1..=3)
        .map(|k| {
            let out = d.join(format!("s{k}.csv"));
            std::thread::spawn(move || sweep(&out, Some(&format!("{k}/3"))))
        })
        .collect();
    handles.into_iter().for_each(|h| h.join().unwrap());
    for suffix in ["", "-peaks"] {
        let shards: Vec<String> = [3, 1, 2]
            .iter()
            .map(|k| {
                d.join(format!("s{k}{suffix}.csv"))
                    .to_str()
                    .unwrap()
                    .to_string()
            })
            .collect();
        let merged = d.join(format!("merged{suffix}.csv"));
        let mut args = vec!["merge-shards", "--out", merged.to_str().unwrap()];
        args.extend(shards.iter().map(|s| s.as_str()));
        wbv(&args);
        let a = std::fs::read(d.join(format!("all{suffix}.csv"))).unwrap();
        assert_eq!(std::fs::read(&merged).unwrap(), a, "{suffix}");
    }
    let peaks = std::fs::read_to_string(d.join("all-peaks.csv")).unwrap();
    assert!(
        peaks.starts_with(
            "point,link.cushion.k,link.cushion.zeta@60,peak_freq_hz,peak_mag,\
             a_w_seat_m_s2,a_v_m_s2,seat_pct,comfort\n"
        ),
        "{peaks}"
    );
    assert_eq!(peaks.lines().count(), 16);
    assert!(peaks.contains("uncomfortable"));
    // A missing shard is an error, not a silently short table.
    let out = Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args([
            "merge-shards",
            "--out",
            d.join("bad.csv").to_str().unwrap(),
            d.join("s1.csv").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).starts_with("wbv: error:"));
}

#[test]
fn sweep_is_deterministic_and_plots_curves_heat_map_and_iso_figures() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    sweep(&a, None);
    sweep(&b, None);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    let plot = dir.path().join("p");
    wbv(&[
        "sweep",
        "--model",
        "seed001-full",
        "--param",
        "link.cushion.k",
        "--values",
        "18500:22500:3",
        "--response",
        "t_head",
        "--points",
        "50",
        "--plot",
        plot.to_str().unwrap(),
        "--plot-format",
        "svg",
        "--excitation",
        "sine-4hz",
        "--duration",
        "4",
    ]);
    for name in ["curves.svg", "heatmap.svg", "iso.svg"] {
        assert!(plot.join(name).exists(), "{name}");
    }
}

/// The ISO figures' path: spectral by default for a linear model under a stationary excitation
/// (said on stderr and in JSON), batched time domain with `--time-domain` (VDV, MTVV, crest
/// columns); both byte-identical run to run, across `--shard` and thread counts;
/// `--time-domain` without an excitation is refused.
#[test]
fn both_paths_are_stated_deterministic_and_shard_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let run = |out: &Path, extra: &[&str], threads: &str| {
        let mut args = vec![
            "sweep",
            "--model",
            "reference",
            "--param",
            "link.cushion.k",
            "--values",
            "40000:120000:7",
            "--response",
            "seat",
            "--points",
            "20",
            "--excitation",
            "bell-214",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        let o = Command::new(env!("CARGO_BIN_EXE_wbv"))
            .args(&args)
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    for (name, extra) in [
        ("spectral", vec![]),
        ("time", vec!["--time-domain", "--duration", "20"]),
    ] {
        let all = d.join(format!("{name}.csv"));
        let stderr = run(&all, &extra, "2");
        let path = if name == "spectral" {
            "ISO figures: spectral"
        } else {
            "ISO figures: time-domain"
        };
        assert!(stderr.contains(path), "{stderr}");
        let again = d.join(format!("{name}-again.csv"));
        run(&again, &extra, "1");
        let peaks = |p: &Path| std::fs::read(super_peaks(p)).unwrap();
        assert_eq!(peaks(&all), peaks(&again), "{name}: threads");
        let mut shards = Vec::new();
        for k in 1..=2 {
            let out = d.join(format!("{name}-s{k}.csv"));
            let mut e = extra.clone();
            let shard = format!("{k}/2");
            e.extend(["--shard", shard.as_str()]);
            run(&out, &e, "2");
            shards.push(super_peaks(&out));
        }
        let merged = d.join(format!("{name}-merged.csv"));
        let mut args = vec!["merge-shards", "--out", merged.to_str().unwrap()];
        args.extend(shards.iter().map(|s| s.to_str().unwrap()));
        wbv(&args);
        assert_eq!(
            std::fs::read(&merged).unwrap(),
            peaks(&all),
            "{name}: shards"
        );
        let text = String::from_utf8(peaks(&all)).unwrap();
        assert_eq!(
            text.lines().next().unwrap().ends_with("crest_seat"),
            name == "time",
            "{text}"
        );
    }
    let one_point = |extra: &[&str]| {
        let mut args = vec![
            "sweep",
            "--model",
            "reference",
            "--param",
            "link.cushion.k",
            "--values",
            "40000",
        ];
        args.extend(extra);
        Command::new(env!("CARGO_BIN_EXE_wbv"))
            .args(&args)
            .output()
            .unwrap()
    };
    let out = one_point(&["--time-domain"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("--time-domain"),
        "{err}"
    );
    let json = one_point(&["--excitation", "bell-214", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(v["path"]["kind"], "spectral", "{v}");
    assert_eq!(v["path"]["spectral_figures"][0], "a_w_seat_m_s2");
}

/// `<stem>-peaks.csv` beside `p`.
fn super_peaks(p: &Path) -> std::path::PathBuf {
    let stem = p.file_stem().unwrap().to_str().unwrap();
    p.with_file_name(format!("{stem}-peaks.csv"))
}
