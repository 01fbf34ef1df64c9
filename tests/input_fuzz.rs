//! Every reader fed arbitrary and mutated bytes: none may panic (an error is the right answer to
//! garbage). Seeds are valid files made here (CSV variants, WAV, UFF58 ASCII and binary, MCAP with
//! a JSON channel, model and excitation TOML) plus, when `WBV_INPUT_FIXTURES` names the fixtures of
//! `tools/input-fixtures/run`, the files written by independent tools (MAT v5/v7, MCAP with
//! protobuf and ROS 2 CDR channels, …). Cases per property: `FUZZ_CASES` (default 256), so the
//! normal test run is a short pass and a longer one is `FUZZ_CASES=100000 cargo test --release
//! --test input_fuzz`.

use proptest::prelude::*;
use std::path::Path;
use wbv::analysis::{Options as ReportOptions, Report};
use wbv::io::input::{Format, Options, read_bytes};

fn cases() -> u32 {
    std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(256)
}

fn csv_seed(delim: char, comma: bool) -> Vec<u8> {
    let mut s =
        format!("\u{feff}\"Time [s]\"{delim}a_seat_z{delim}Acc Z [g]\ns{delim}m/s2{delim}g\n");
    for i in 0..40 {
        let t = format!("{:.3}", i as f64 / 256.0);
        let v = format!("{}", (i as f64 * 0.3).sin());
        let (t, v) = if comma {
            (t.replace('.', ","), v.replace('.', ","))
        } else {
            (t, v)
        };
        s += &format!("{t}{delim}{v}{delim}{v}\n");
    }
    s.into_bytes()
}

fn wav_seed(bits: u16, float: bool) -> Vec<u8> {
    let spec = hound::WavSpec {
        channels: 2,
        sample_rate: 200,
        bits_per_sample: bits,
        sample_format: if float {
            hound::SampleFormat::Float
        } else {
            hound::SampleFormat::Int
        },
    };
    let mut buf = std::io::Cursor::new(Vec::new());
    let mut w = hound::WavWriter::new(&mut buf, spec).unwrap();
    for i in 0..64 {
        if float {
            w.write_sample((i as f32 * 0.1).sin()).unwrap();
        } else {
            w.write_sample(((i as f32 * 0.1).sin() * 1000.0) as i32)
                .unwrap();
        }
    }
    w.finalize().unwrap();
    buf.into_inner()
}

fn uff_seed(binary: bool) -> Vec<u8> {
    let n = 12;
    let mut s = String::from("    -1\n");
    s += if binary {
        "    58b     1     2          11          96     0     0           0           0\n"
    } else {
        "    58\n"
    };
    s += "seat z\nNONE\nNONE\nNONE\nNONE\n";
    s += "    1         0    0         0       NONE         1   3       NONE         0   0\n";
    s += &format!("         4{n:>10}         1  0.00000e+00  1.95312e-03  0.00000e+00\n");
    for _ in 0..4 {
        s += "        17    0    0    0 NONE                 NONE                \n";
    }
    let mut b = s.into_bytes();
    if binary {
        for i in 0..n {
            b.extend((i as f64 * 0.1).to_le_bytes());
        }
        b.extend(b"    -1\n");
    } else {
        for i in 0..n {
            b.extend(format!("{:20.11e}", i as f64 * 0.1).bytes());
            if i % 4 == 3 {
                b.push(b'\n');
            }
        }
        b.extend(b"    -1\n");
    }
    b
}

fn mcap_seed() -> Vec<u8> {
    let mut buf = std::io::Cursor::new(Vec::new());
    {
        let mut w = mcap::Writer::new(&mut buf).unwrap();
        let ch = w
            .add_channel(0, "/imu", "json", &std::collections::BTreeMap::new())
            .unwrap();
        for i in 0..20u64 {
            let data = format!("{{\"linear_acceleration\":{{\"z\":{}}}}}", i as f64 * 0.1);
            w.write_to_known_channel(
                &mcap::records::MessageHeader {
                    channel_id: ch,
                    sequence: i as u32,
                    log_time: i * 5_000_000,
                    publish_time: i * 5_000_000,
                },
                data.as_bytes(),
            )
            .unwrap();
        }
        w.finish().unwrap();
    }
    buf.into_inner()
}

/// Seeds: (bytes, file name, options), in-code and, when present, the independent fixtures.
fn seeds() -> Vec<(Vec<u8>, String, Options)> {
    let col = |c: &[(&str, &str)]| {
        c.iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect::<Vec<_>>()
    };
    let mut v = vec![
        (csv_seed(',', false), "a.csv".into(), Options::default()),
        (csv_seed(';', true), "b.csv".into(), Options::default()),
        (
            csv_seed('\t', true),
            "c.tsv".into(),
            Options {
                columns: col(&[("a_seat_z", "Acc Z")]),
                ..Options::default()
            },
        ),
        (
            wav_seed(16, false),
            "a.wav".into(),
            Options {
                columns: col(&[("a_seat_z", "1")]),
                sensitivity: vec![("a_seat_z".into(), 9.81)],
                ..Options::default()
            },
        ),
        (
            wav_seed(24, false),
            "b.wav".into(),
            Options {
                columns: col(&[("a_seat_z", "2")]),
                sensitivity: vec![("a_seat_z".into(), 1.0)],
                ..Options::default()
            },
        ),
        (
            wav_seed(32, true),
            "c.wav".into(),
            Options {
                columns: col(&[("a_seat_z", "1")]),
                sensitivity: vec![("a_seat_z".into(), 1.0)],
                ..Options::default()
            },
        ),
        (
            uff_seed(false),
            "a.uff".into(),
            Options {
                columns: col(&[("a_seat_z", "1")]),
                ..Options::default()
            },
        ),
        (
            uff_seed(true),
            "b.uff".into(),
            Options {
                columns: col(&[("a_seat_z", "seat z")]),
                ..Options::default()
            },
        ),
        (
            mcap_seed(),
            "a.mcap".into(),
            Options {
                topic: Some("/imu".into()),
                columns: col(&[("a_seat_z", "linear_acceleration.z")]),
                ..Options::default()
            },
        ),
    ];
    if let Ok(dir) = std::env::var("WBV_INPUT_FIXTURES") {
        let dir = std::path::PathBuf::from(dir);
        let manifest: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).unwrap())
                .unwrap();
        for e in manifest.as_array().unwrap() {
            let file = e["file"].as_str().unwrap();
            let o = &e["options"];
            let strs = |k: &str| -> Vec<String> {
                o.get(k)
                    .and_then(|x| x.as_array())
                    .map(|a| a.iter().map(|s| s.as_str().unwrap().to_string()).collect())
                    .unwrap_or_default()
            };
            let args = wbv::io::input::InputArgs {
                columns: strs("column"),
                units: strs("units"),
                sensitivity: strs("sensitivity"),
                fs: o.get("fs_option").and_then(|v| v.as_f64()),
                topic: o.get("topic").and_then(|v| v.as_str()).map(str::to_string),
                ignore_time: o.get("ignore_time").and_then(|v| v.as_bool()) == Some(true),
                format: None,
            };
            // Keep seeds small: the first 64 KiB (a truncated file is a mutation of its own).
            let mut bytes = std::fs::read(dir.join(file)).unwrap();
            bytes.truncate(1 << 16);
            v.push((bytes, file.to_string(), args.options().unwrap()));
        }
    }
    v
}

/// A file that reads must give a report with finite, physically possible figures, or an error:
/// never a silent absurd verdict (a flipped byte read as 10³⁶ m/s², a NaN comfort value).
fn figures_are_plausible(bytes: &[u8], name: &str, opts: &Options) {
    let Ok(inp) = read_bytes(bytes, Path::new(name), opts) else {
        return;
    };
    let Ok(r) = Report::from_signals(&inp.signals, &ReportOptions::default()) else {
        return;
    };
    let bound = wbv::io::input::MAX_ACCELERATION_M_S2;
    assert!(
        r.total_value.is_finite() && r.total_value <= 2.0 * bound,
        "{name}: a_v {}",
        r.total_value
    );
    for c in &r.channels {
        for (key, v) in [
            ("a_w", c.a_w),
            ("vdv", c.vdv),
            ("mtvv", c.mtvv),
            ("crest_factor", c.crest_factor),
        ] {
            assert!(v.is_finite() && v >= 0.0, "{name} {}: {key} {v}", c.name);
        }
        assert!(
            c.a_w <= bound && c.peak <= 10.0 * bound,
            "{name} {}: a_w {} peak {}",
            c.name,
            c.a_w,
            c.peak
        );
        assert!(c.msdv.is_none_or(f64::is_finite), "{name} {}: msdv", c.name);
    }
    if let Some(s) = r.seat_percent {
        assert!(s.is_finite(), "{name}: SEAT {s}");
    }
}

fn try_all(bytes: &[u8], name: &str, opts: &Options) {
    figures_are_plausible(bytes, name, opts);
    for f in [Format::Csv, Format::Wav, Format::Mat, Format::Uff] {
        let o = Options {
            format: Some(f),
            topic: None,
            sensitivity: Vec::new(),
            ..opts.clone()
        };
        let _ = read_bytes(bytes, Path::new(name), &o);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), failure_persistence: None, ..ProptestConfig::default() })]

    /// Mutated valid files: bytes overwritten, a range deleted or duplicated, the end cut.
    #[test]
    fn mutated_files_never_panic(
        which in 0usize..64,
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..8),
        cut in any::<prop::sample::Index>(),
        dup in any::<prop::sample::Index>(),
        mode in 0u8..4,
    ) {
        let seeds = seeds_cached();
        let (seed, name, opts) = &seeds[which % seeds.len()];
        let mut b = seed.clone();
        for (i, v) in &edits {
            if !b.is_empty() {
                let k = i.index(b.len());
                b[k] = *v;
            }
        }
        if !b.is_empty() {
            let c = cut.index(b.len());
            let d = dup.index(b.len());
            match mode {
                1 => b.truncate(c),
                2 => { let (lo, hi) = (c.min(d), c.max(d)); b.drain(lo..hi); }
                3 => { let (lo, hi) = (c.min(d), c.max(d)); let r = b[lo..hi].to_vec(); b.splice(hi..hi, r); }
                _ => {}
            }
        }
        try_all(&b, name, opts);
    }

    /// Arbitrary bytes behind each format's magic, and arbitrary text as TOML.
    #[test]
    fn arbitrary_bytes_never_panic(
        body in proptest::collection::vec(any::<u8>(), 0..600),
        magic in 0usize..6,
    ) {
        let heads: [&[u8]; 6] = [b"", b"RIFF", b"MATLAB 5.0 MAT-file", b"\x89MCAP0\r\n", b"    -1\n    58\n", b"t_s,a_seat_z\n"];
        let mut b = heads[magic].to_vec();
        b.extend(&body);
        let opts = Options { topic: Some("/imu".into()), columns: vec![("a_seat_z".into(), "z".into())], ..Options::default() };
        let _ = read_bytes(&b, Path::new("x.mcap"), &opts);
        try_all(&b, "x.bin", &Options::default());
        let text = String::from_utf8_lossy(&body);
        let _ = wbv::excitation::ExcitationSpec::parse(&text, "fuzz.toml", None);
        let _ = wbv::model::catalog::parse(&text, "fuzz.toml");
    }

    /// Mutated model and excitation TOML (built-in files as seeds).
    #[test]
    fn mutated_toml_never_panics(
        which in 0usize..64,
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..6),
    ) {
        let seeds = toml_seeds();
        let mut b = seeds[which % seeds.len()].clone().into_bytes();
        for (i, v) in &edits {
            let k = i.index(b.len());
            b[k] = *v;
        }
        let text = String::from_utf8_lossy(&b);
        let _ = wbv::excitation::ExcitationSpec::parse(&text, "fuzz.toml", None);
        let _ = wbv::model::catalog::parse(&text, "fuzz.toml");
    }
}

fn seeds_cached() -> &'static Vec<(Vec<u8>, String, Options)> {
    static S: std::sync::OnceLock<Vec<(Vec<u8>, String, Options)>> = std::sync::OnceLock::new();
    S.get_or_init(seeds)
}

fn toml_seeds() -> Vec<String> {
    let mut v = Vec::new();
    for dir in ["models", "excitations"] {
        let mut files: Vec<_> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(dir))
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        files.sort();
        v.extend(files.iter().map(|p| std::fs::read_to_string(p).unwrap()));
    }
    assert!(!v.is_empty());
    v
}
