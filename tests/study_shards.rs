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
