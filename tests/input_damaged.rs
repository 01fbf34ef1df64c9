//! Files written by independent tools (`tools/input-fixtures/run`: scipy's MAT writer, soundfile's
//! float WAV, pyuff's binary UFF58), damaged here as a cut copy or a corrupted transfer damages
//! them: each must be refused with an error naming the file and what is wrong, never read with a
//! channel dropped or an absurd sample. `tools/test` runs this with `WBV_INPUT_FIXTURES=DIR`;
//! without it the test says so and checks nothing else.

use std::path::{Path, PathBuf};
use wbv::io::input::{Options, read_bytes};

fn fixture(name: &str) -> Option<(PathBuf, Vec<u8>)> {
    let Ok(dir) = std::env::var("WBV_INPUT_FIXTURES") else {
        eprintln!(
            "WBV_INPUT_FIXTURES not set: run tools/input-fixtures/run DIR first (tools/test does)"
        );
        return None;
    };
    let path = Path::new(&dir).join(name);
    let bytes = std::fs::read(&path).unwrap();
    Some((path, bytes))
}

fn columns(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

/// The error of reading `bytes` as `path`; fails the test when the damaged file is read.
fn refused(bytes: &[u8], path: &Path, opts: &Options, case: &str) -> String {
    match read_bytes(bytes, path, opts) {
        Ok(inp) => panic!(
            "{case}: read without error ({} channels, {} samples, notes: {:?})",
            inp.signals.names.len(),
            inp.signals.len(),
            inp.notes
        ),
        Err(e) => {
            let e = e.to_string();
            assert!(e.contains(&path.display().to_string()), "{case}: {e}");
            e
        }
    }
}

#[test]
fn a_truncated_mat_file_is_refused() {
    for name in ["v5.mat", "v7.mat"] {
        let Some((path, bytes)) = fixture(name) else {
            return;
        };
        let opts = if name == "v5.mat" {
            Options {
                columns: columns(&[("a_seat_z", "acc_seat"), ("a_base_z", "acc_base")]),
                ..Options::default()
            }
        } else {
            Options {
                fs: Some(500.0),
                ..Options::default()
            }
        };
        read_bytes(&bytes, &path, &opts).unwrap();
        for cut in [1, 7, 100, bytes.len() / 3] {
            let e = refused(
                &bytes[..bytes.len() - cut],
                &path,
                &opts,
                &format!("{name} −{cut} B"),
            );
            assert!(e.contains("truncated"), "{name} −{cut} B: {e}");
        }
    }
}

#[test]
fn a_binary_uff58_with_bytes_inserted_is_refused() {
    let Some((path, bytes)) = fixture("binary.uff") else {
        return;
    };
    let opts = Options {
        columns: columns(&[("a_seat_z", "seat z"), ("a_base_z", "base z")]),
        ..Options::default()
    };
    read_bytes(&bytes, &path, &opts).unwrap();
    for at in [
        bytes.len() / 5,
        bytes.len() / 2,
        bytes.len() - 40,
        bytes.len() - 3,
    ] {
        for insert in [&b"\x00"[..], b"\x7f\x12\xa0", b"junk\n"] {
            let mut b = bytes.clone();
            b.splice(at..at, insert.iter().copied());
            refused(
                &b,
                &path,
                &opts,
                &format!("binary.uff +{} B at {at}", insert.len()),
            );
        }
    }
}

#[test]
fn a_float_wav_with_a_flipped_exponent_or_stray_bytes_is_refused() {
    let Some((path, bytes)) = fixture("float32.wav") else {
        return;
    };
    let opts = Options {
        columns: columns(&[("a_seat_z", "1"), ("a_base_z", "2")]),
        sensitivity: vec![("a_seat_z".into(), 1.0), ("a_base_z".into(), 1.0)],
        ..Options::default()
    };
    read_bytes(&bytes, &path, &opts).unwrap();
    let data = bytes.windows(4).position(|w| w == b"data").unwrap() + 8;
    // The exponent byte of one little-endian float: 0x7e makes it ~1e38, 0x7f inf or NaN.
    for (k, flip) in [(101usize, 0x7e_u8), (2003, 0x7f)] {
        let mut b = bytes.clone();
        b[data + 4 * k + 3] = flip;
        let e = refused(
            &b,
            &path,
            &opts,
            &format!("float32.wav sample {k} exponent {flip:#x}"),
        );
        assert!(e.contains("sample"), "{e}");
    }
    let mut appended = bytes.clone();
    appended.extend_from_slice(&[0u8; 37]);
    let e = refused(&appended, &path, &opts, "float32.wav + 37 B");
    assert!(e.contains("after the end"), "{e}");
    let e = refused(
        &bytes[..bytes.len() - 10],
        &path,
        &opts,
        "float32.wav − 10 B",
    );
    assert!(e.contains("truncated"), "{e}");
}

#[test]
fn an_absurd_sample_in_a_uff58_is_refused() {
    let Some((path, bytes)) = fixture("binary.uff") else {
        return;
    };
    let opts = Options {
        columns: columns(&[("a_seat_z", "seat z"), ("a_base_z", "base z")]),
        ..Options::default()
    };
    // pyuff writes double samples: replace the first one after the second header's data start.
    let marker = b"58b";
    let starts: Vec<usize> = bytes
        .windows(3)
        .enumerate()
        .filter(|(_, w)| *w == marker)
        .map(|(i, _)| i)
        .collect();
    let header_end = {
        let mut at = starts[0];
        for _ in 0..12 {
            at += bytes[at..].iter().position(|&c| c == b'\n').unwrap() + 1;
        }
        at
    };
    let mut b = bytes.clone();
    b[header_end + 80..header_end + 88].copy_from_slice(&1.1e244f64.to_le_bytes());
    let e = refused(&b, &path, &opts, "binary.uff sample 1.1e244");
    assert!(e.contains("sample 11") && e.contains("beyond"), "{e}");
}

#[test]
fn a_gap_in_the_time_stamps_is_refused_at_its_line() {
    // A logger that dropped 0.25 s of samples at 10 s, 500 Hz stamps printed to 0.1 ms; the text is
    // written here, not by wbv's writer.
    let mut text = String::from("t_s,a_base_z,a_seat_z\n");
    let mut line_after_gap = 0;
    for i in 0..10_000 {
        let mut t = i as f64 * 0.002;
        if i >= 5_000 {
            t += 0.25;
            if line_after_gap == 0 {
                line_after_gap = i + 2;
            }
        }
        let x = (2.0 * std::f64::consts::PI * 3.0 * t).sin();
        text += &format!("{t:.4},{x:.6},{:.6}\n", 1.1 * x);
    }
    let path = Path::new("logger-with-a-gap.csv");
    let e = refused(text.as_bytes(), path, &Options::default(), "gap");
    assert!(e.contains(&format!(":{line_after_gap}:")), "{e}");
    assert!(e.contains("gap in the record"), "{e}");
    assert!(e.contains("from 9.998 s to 10.25 s"), "{e}");
    // The same stamps without the gap are read.
    let whole: String = (0..10_000)
        .map(|i| format!("{:.4},0.1,0.1\n", i as f64 * 0.002))
        .collect();
    let ok = format!("t_s,a_base_z,a_seat_z\n{whole}");
    assert!(read_bytes(ok.as_bytes(), path, &Options::default()).is_ok());
}
