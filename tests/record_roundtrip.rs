//! A run recorded from synthetic steps reads back bit-identically, deterministically, with its
//! provenance and results; truncated/corrupt files and overwrites are refused with one clear line.

use std::path::Path;
use wbv::record::demo::{self, State};
use wbv::record::{
    Compression, Encoding, McapRecorder, MessageLayout, Overwrite, Provenance, RecordOptions,
    check_lichtblick_subset, inspect, read_run,
};
use wbv::simulate::observer::Observer;

const FS: f64 = 1000.0;

fn provenance() -> Provenance {
    Provenance {
        model: "demo-5dof".into(),
        model_toml: "name = \"demo-5dof\"\n[masses]\nhead = 5.31\n".into(),
        excitation: "sum of sines".into(),
        excitation_definition: "kind = \"sines\"\nf = [4.0]\n".into(),
        integrator: "newmark".into(),
        dt: 1.0 / FS,
        seed: Some(42),
        duration: 2.0,
        command_line: "wbv simulate --model demo-5dof".into(),
        ..Provenance::new()
    }
}

fn record(path: &Path, options: RecordOptions, steps: u64) -> wbv::Result<()> {
    let mut rec = McapRecorder::create(path, provenance(), options)?;
    rec.attach_results(
        "iso2631",
        &serde_json::json!({"aw_z": 0.123456789, "vdv_z": [1.5, 2.5]}),
    )?;
    demo::drive(&mut rec, FS, steps)
}

fn opts(compression: Compression, encoding: Encoding) -> RecordOptions {
    RecordOptions {
        compression,
        encoding,
        ..RecordOptions::default()
    }
}

#[test]
fn recorded_signals_read_back_bit_identically() {
    let dir = tempfile::tempdir().unwrap();
    let (batched, per_sample) = (Some(MessageLayout::Batched), Some(MessageLayout::PerSample));
    let cases = [
        (Compression::Zstd, Encoding::Protobuf, None),
        (Compression::Lz4, Encoding::Protobuf, batched),
        (Compression::None, Encoding::Protobuf, batched),
        (Compression::Zstd, Encoding::Protobuf, batched),
        (Compression::None, Encoding::Protobuf, per_sample),
        (Compression::Zstd, Encoding::Json, None),
        (Compression::None, Encoding::Json, per_sample),
    ];
    for (c, e, layout) in cases {
        let kind = layout.unwrap_or_default();
        let name = format!("run-{}-{}-{}", c.as_str(), e.as_str(), kind.as_str());
        let path = dir.path().join(format!("{name}.mcap"));
        record(
            &path,
            RecordOptions {
                layout,
                ..opts(c, e)
            },
            2001,
        )
        .unwrap();
        let run = read_run(&path).unwrap();
        let s = &run.signals;
        assert_eq!(s.len(), 2001);
        assert_eq!(s.sample_rate_hz, FS);
        for i in 0..2001u64 {
            let st = State::at(i, 1.0 / FS);
            let k = i as usize;
            let same = |name: &str, v: f64| {
                let got = s.require(name).unwrap()[k];
                assert_eq!(
                    got.to_bits(),
                    v.to_bits(),
                    "{name} at step {i}: {got} vs {v}"
                );
            };
            same("a_base_z", st.base[0]);
            same("a_seat_z", st.a[4] + st.base[0]);
            same("a_head_z", st.a[0] + st.base[0]);
            same("f_seat_z", -st.force[3]);
            same("state.head.x", st.x[0]);
            same("state.upper_torso.v_abs", st.v[1] + st.base[1]);
            same("state.cushion.a", st.a[4]);
            same("links.cushion.deflection", st.deflection[4]);
            same("links.k2.force", st.force[1]);
            same("links.cushion.force", st.force[4]);
            // Recorded once: the base motion is a_base_z and x_abs − x, a body link's deflection
            // the difference of two displacements.
            let base_x = s.require("state.pelvis.x_abs").unwrap()[k]
                - s.require("state.pelvis.x").unwrap()[k];
            assert!(
                (base_x - st.base[2]).abs() <= 1e-15,
                "{base_x} vs {}",
                st.base[2]
            );
        }
        for absent in [
            "base.a",
            "base.x",
            "links.k2.deflection",
            "state.t",
            "links.t",
        ] {
            assert!(s.require(absent).is_err(), "{absent} is recorded twice");
        }
        assert_eq!(run.provenance, provenance());
        assert_eq!(run.results["iso2631"]["vdv_z"][1], 2.5);
        assert!(!dir.path().join(format!("{name}.mcap.partial")).exists());
    }
}

#[test]
fn batched_layout_is_one_message_per_topic_per_block_and_protobuf_only() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    // 2001 samples: blocks of 1024 and 977
    let batched = RecordOptions {
        layout: Some(MessageLayout::Batched),
        ..opts(Compression::Zstd, Encoding::Protobuf)
    };
    record(&path, batched, 2001).unwrap();
    let summary = wbv::record::inspect(&path).unwrap();
    let expected = 2001usize.div_ceil(wbv::record::BATCH_SAMPLES) as u64;
    for topic in ["/wbv/measured", "/wbv/state", "/wbv/links"] {
        let t = summary.topics.iter().find(|t| t.topic == topic).unwrap();
        assert_eq!(t.messages, expected, "{topic}");
        assert!(t.schema.ends_with("Batch"), "{}", t.schema);
    }
    assert_eq!(summary.metadata["wbv.run"]["layout"], "batched");
    let json = RecordOptions {
        layout: Some(MessageLayout::Batched),
        ..opts(Compression::Zstd, Encoding::Json)
    };
    let e = McapRecorder::create(&dir.path().join("json.mcap"), provenance(), json)
        .err()
        .expect("batched JSON is refused");
    assert!(e.to_string().contains("protobuf only"), "{e}");
    assert!(!dir.path().join("json.mcap.partial").exists());
}

#[test]
fn same_inputs_give_a_byte_identical_file() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.mcap");
    let b = dir.path().join("b.mcap");
    let per_sample = Some(MessageLayout::PerSample);
    for (e, layout) in [
        (Encoding::Protobuf, None),
        (Encoding::Protobuf, per_sample),
        (Encoding::Json, None),
    ] {
        let o = RecordOptions {
            layout,
            ..opts(Compression::Zstd, e)
        };
        record(&a, o.clone(), 5000).unwrap();
        record(&b, o, 5000).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        std::fs::remove_file(&a).unwrap();
        std::fs::remove_file(&b).unwrap();
    }
}

#[test]
fn existing_file_is_refused_unless_overwrite_is_allowed() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    std::fs::write(&path, b"keep me").unwrap();
    let err = McapRecorder::create(&path, provenance(), RecordOptions::default())
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("refusing to overwrite"), "{err}");
    assert_eq!(std::fs::read(&path).unwrap(), b"keep me");
    let allow = RecordOptions {
        overwrite: Overwrite::Allow,
        ..RecordOptions::default()
    };
    record(&path, allow, 100).unwrap();
    assert_eq!(read_run(&path).unwrap().signals.len(), 100);
}

#[test]
fn truncated_file_gives_one_clear_error_at_every_offset() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    record(&path, opts(Compression::Zstd, Encoding::Protobuf), 3000).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let cut = dir.path().join("cut.mcap");
    let n = bytes.len();
    let mut offsets: Vec<usize> = (0..64).chain((0..n).step_by(n / 300)).collect();
    offsets.extend(n - 64..n);
    for len in offsets {
        std::fs::write(&cut, &bytes[..len]).unwrap();
        let err = read_run(&cut).expect_err("a truncated file must not read");
        let line = err.to_string();
        assert!(
            !line.contains('\n') && line.contains("cut.mcap"),
            "{len}: {line}"
        );
        assert!(inspect(&cut).is_err());
    }
}

#[test]
fn corrupt_bytes_never_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    record(&path, opts(Compression::Lz4, Encoding::Protobuf), 1500).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let bad = dir.path().join("bad.mcap");
    // deterministic positions over the whole file, including header, chunks and summary
    for k in 0..400usize {
        let pos = (k * 7919 + 13) % bytes.len();
        let mut b = bytes.clone();
        b[pos] ^= 0x5a;
        std::fs::write(&bad, &b).unwrap();
        if let Err(e) = read_run(&bad) {
            assert!(!e.to_string().contains('\n'));
        }
    }
}

#[test]
fn interrupted_run_leaves_only_an_incomplete_partial_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    let mut rec = McapRecorder::create(&path, provenance(), RecordOptions::default()).unwrap();
    rec.begin(&demo::layout(FS, 10)).unwrap();
    rec.step(&State::at(0, 1.0 / FS).step()).unwrap();
    let partial = dir.path().join("run.mcap.partial");
    assert!(partial.exists() && !path.exists());
    let err = read_run(&partial).err().unwrap().to_string();
    assert!(
        err.contains("incomplete") || err.contains("corrupt"),
        "{err}"
    );
    drop(rec); // an error path: nothing that looks complete is left
    assert!(!path.exists() && !partial.exists());
}

#[test]
fn non_finite_value_is_an_error_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    let mut rec = McapRecorder::create(&path, provenance(), RecordOptions::default()).unwrap();
    rec.begin(&demo::layout(FS, 10)).unwrap();
    let mut st = State::at(0, 1.0 / FS);
    st.v[1] = f64::NAN;
    let err = rec.step(&st.step()).err().unwrap().to_string();
    assert!(
        err.contains("state.upper_torso.v") && err.contains("not finite"),
        "{err}"
    );
}

#[test]
fn decimated_record_is_low_passed_and_at_the_record_rate() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    let options = RecordOptions {
        record_rate_hz: Some(250.0),
        ..RecordOptions::default()
    };
    record(&path, options, 4000).unwrap();
    let run = read_run(&path).unwrap();
    assert_eq!(run.signals.sample_rate_hz, 250.0);
    assert_eq!(run.signals.len(), 1000);
    // 4 Hz base motion is far below the 62.5 Hz cut-off: amplitude kept within 0.1 %
    let a = run.signals.require("a_base_z").unwrap();
    let peak = a[500..].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let expected = 1e-3 * (2.0 * std::f64::consts::PI * 4.0f64).powi(2);
    assert!((peak / expected - 1.0).abs() < 2e-3, "{peak} vs {expected}");
}

#[test]
fn every_channel_schema_is_in_the_lichtblick_subset() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.mcap");
    record(&path, opts(Compression::Zstd, Encoding::Json), 50).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    assert_eq!(
        summary.channels.len(),
        5,
        "measured, state, links, scene, tf"
    );
    for c in summary.channels.values() {
        let schema = c.schema.as_ref().expect("every channel has a schema");
        assert_eq!(schema.encoding, "jsonschema");
        assert_eq!(c.message_encoding, "json");
        let v: serde_json::Value = serde_json::from_slice(&schema.data).unwrap();
        check_lichtblick_subset(&v).unwrap_or_else(|e| panic!("{}: {e}", c.topic));
    }
    let stats = summary.stats.unwrap();
    assert!(!summary.chunk_indexes.is_empty());
    assert!(
        summary
            .chunk_indexes
            .iter()
            .all(|c| !c.message_index_offsets.is_empty())
    );
    assert_eq!(stats.message_start_time, 0);
    assert_eq!(stats.message_end_time, 49_000_000);
}
