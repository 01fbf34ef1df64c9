//! Every input format read from files written by independent tools (scipy, soundfile, pyuff, the
//! PyPI mcap writers, Python's csv module): `tools/input-fixtures/run DIR` writes them with a
//! manifest of the exact samples, and `tools/test` runs this test with `WBV_INPUT_FIXTURES=DIR`.
//! Without that variable the test says so and checks nothing else.

use wbv::analysis::{Options, Report};
use wbv::io::input::InputArgs;
use wbv::measurement::read;

fn strings(v: &serde_json::Value, key: &str) -> Vec<String> {
    v.get(key)
        .and_then(|x| x.as_array())
        .map(|a| a.iter().map(|s| s.as_str().unwrap().to_string()).collect())
        .unwrap_or_default()
}

#[test]
fn every_format_reads_the_samples_its_writer_wrote() {
    let Ok(dir) = std::env::var("WBV_INPUT_FIXTURES") else {
        eprintln!(
            "WBV_INPUT_FIXTURES not set: run tools/input-fixtures/run DIR first (tools/test does)"
        );
        return;
    };
    let dir = std::path::PathBuf::from(dir);
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).unwrap()).unwrap();
    let entries = manifest.as_array().unwrap();
    assert!(entries.len() >= 13, "{} fixtures", entries.len());
    let mut failures = Vec::new();
    for e in entries {
        let file = e["file"].as_str().unwrap();
        let o = &e["options"];
        let args = InputArgs {
            columns: strings(o, "column"),
            units: strings(o, "units"),
            sensitivity: strings(o, "sensitivity"),
            fs: o.get("fs_option").and_then(|v| v.as_f64()),
            topic: o.get("topic").and_then(|v| v.as_str()).map(str::to_string),
            ignore_time: o.get("ignore_time").and_then(|v| v.as_bool()) == Some(true),
            format: None,
        };
        // Text formats printed with 12 significant digits (UFF58 ASCII) hold to 5e-12 relative;
        // everything else to a few ulps of float64.
        let exact = o.get("exact").and_then(|v| v.as_bool()).unwrap_or(true);
        let rel = if exact { 1e-14 } else { 1e-11 };
        let inp = match read(&dir.join(file), &args.options().unwrap()) {
            Ok(i) => i,
            Err(err) => {
                failures.push(format!("{file}: {err}"));
                continue;
            }
        };
        let s = &inp.signals;
        assert_eq!(s.sample_rate_hz, e["fs"].as_f64().unwrap(), "{file}");
        let want = e["channels"].as_object().unwrap();
        let mut names: Vec<&String> = s.names.iter().collect();
        names.sort();
        let mut wanted: Vec<&String> = want.keys().collect();
        wanted.sort();
        assert_eq!(names, wanted, "{file}");
        for (name, truth) in want {
            let truth: Vec<f64> = truth
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            let got = s.get(name).unwrap();
            assert_eq!(got.len(), truth.len(), "{file} {name}");
            let worst = got
                .iter()
                .zip(&truth)
                .map(|(g, t)| (g - t).abs() / t.abs().max(1e-3))
                .fold(0.0, f64::max);
            assert!(
                worst <= rel,
                "{file} {name}: worst relative error {worst:e} > {rel:e}"
            );
        }
        // Each reading analyses (rates from 200 Hz up).
        let r = Report::from_signals(s, &Options::default()).unwrap();
        assert!(r.channels.iter().all(|c| c.a_w > 0.0), "{file}");
        eprintln!(
            "{file}: {} channels at {} Hz, {} samples: equal",
            s.names.len(),
            s.sample_rate_hz,
            s.len()
        );
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
