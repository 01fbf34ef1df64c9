//! Writes a demo run recorded from synthetic steps of a 5-mass layout (not a simulation), e.g. to
//! try the viewers or `tools/validate-mcap/run`:
//!
//! `cargo run --release --example record_demo -- demo.mcap [seconds] [zstd|lz4|none]`

use std::path::PathBuf;
use wbv::record::{Compression, McapRecorder, Overwrite, Provenance, RecordOptions, demo};

fn main() -> std::process::ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = (|| -> wbv::Result<()> {
        let path = PathBuf::from(args.first().map_or("demo.mcap", String::as_str));
        let seconds: f64 = match args.get(1) {
            Some(s) => s
                .parse()
                .map_err(|_| wbv::Error::parameter("seconds", format!("`{s}` is not a number")))?,
            None => 10.0,
        };
        let compression = Compression::parse(args.get(2).map_or("lz4", String::as_str))?;
        let fs = 1000.0;
        let provenance = Provenance {
            model: "demo-5dof".into(),
            model_toml: "# synthetic layout, see src/record/demo.rs\n".into(),
            excitation: "sum of sines (synthetic)".into(),
            excitation_definition: "base: 1 mm at 4 Hz; masses: 0.1–0.5 mm at 3–9.8 Hz".into(),
            integrator: "none (synthetic steps)".into(),
            dt: 1.0 / fs,
            seed: None,
            duration: seconds,
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
            ..Provenance::new()
        };
        let options = RecordOptions {
            compression,
            overwrite: Overwrite::Allow,
            ..RecordOptions::default()
        };
        let mut rec = McapRecorder::create(&path, provenance, options)?;
        rec.attach_results(
            "demo",
            &serde_json::json!({"note": "synthetic", "aw_z": 1.0}),
        )?;
        demo::drive(&mut rec, fs, (seconds * fs).round() as u64 + 1)?;
        println!("wrote {}", path.display());
        Ok(())
    })();
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("record_demo: error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
