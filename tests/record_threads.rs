//! The recording does not depend on how many threads format and compress it: formatted blocks
//! are written in step order, and zstd's output is the same for any number of workers ≥ 1. Runs
//! span several blocks, several chunks and the scene messages interleaved with them.

use std::path::Path;
use wbv::record::{
    BATCH_SAMPLES, Compression, McapRecorder, MessageLayout, Overwrite, Provenance, RecordOptions,
    demo, read_run,
};

const FS: f64 = 1000.0;

fn record(
    path: &Path,
    (compression, layout): (Compression, MessageLayout),
    rate: Option<f64>,
    threads: usize,
    steps: u64,
) {
    let options = RecordOptions {
        compression,
        layout: Some(layout),
        record_rate_hz: rate,
        overwrite: Overwrite::Allow,
        threads: Some(threads),
        ..RecordOptions::default()
    };
    let mut rec = McapRecorder::create(path, Provenance::new(), options).unwrap();
    demo::drive(&mut rec, FS, steps).unwrap();
}

#[test]
fn the_file_is_byte_identical_for_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    // 20 001 steps per sample: 20 blocks, and more than one 8 MiB chunk of protobuf (≈ 0.5 kB
    // per step).
    let (batched, per_sample) = (MessageLayout::Batched, MessageLayout::PerSample);
    for (compression, layout, rate, steps) in [
        (Compression::Zstd, per_sample, None, 20_001),
        (Compression::Zstd, batched, None, 5_001),
        (Compression::Lz4, batched, None, 3_001),
        (Compression::None, batched, Some(250.0), 5_001),
    ] {
        let files: Vec<Vec<u8>> = [1, 2, 3]
            .iter()
            .map(|&threads| {
                let path = dir.path().join(format!(
                    "{}-{}-{threads}.mcap",
                    compression.as_str(),
                    layout.as_str()
                ));
                record(&path, (compression, layout), rate, threads, steps);
                std::fs::read(&path).unwrap()
            })
            .collect();
        let name = format!("{} {}", compression.as_str(), layout.as_str());
        assert!(files[0] == files[1], "{name}: 1 and 2 threads differ");
        assert!(files[0] == files[2], "{name}: 1 and 3 threads differ");
    }
    let run = read_run(&dir.path().join("zstd-per-sample-2.mcap")).unwrap();
    assert_eq!(run.signals.len(), 20_001);
    let chunks =
        mcap::Summary::read(&std::fs::read(dir.path().join("zstd-per-sample-2.mcap")).unwrap())
            .unwrap()
            .unwrap()
            .chunk_indexes;
    assert!(chunks.len() >= 2, "{} chunk(s)", chunks.len());
    assert!(chunks.iter().all(|c| c.compression == "zstd"));
}

#[test]
fn messages_are_in_time_order_with_the_scene_interleaved() {
    let dir = tempfile::tempdir().unwrap();
    for layout in [MessageLayout::PerSample, MessageLayout::Batched] {
        let path = dir.path().join(format!("{}.mcap", layout.as_str()));
        record(&path, (Compression::Zstd, layout), None, 3, 2_500);
        in_time_order(&path, layout);
    }
}

fn in_time_order(path: &Path, layout: MessageLayout) {
    let bytes = std::fs::read(path).unwrap();
    let mut last = 0;
    let mut per_topic = std::collections::BTreeMap::<String, u64>::new();
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        assert!(
            m.log_time >= last,
            "{} at {} after {last}",
            m.channel.topic,
            m.log_time
        );
        assert_eq!(m.log_time, m.publish_time);
        last = m.log_time;
        *per_topic.entry(m.channel.topic.clone()).or_default() += 1;
    }
    // 2 500 steps at 1 kHz: t = 0 … 2.499 s; the scene at 30 Hz from t = 0.
    let messages = match layout {
        MessageLayout::PerSample => 2_500,
        MessageLayout::Batched => 2_500usize.div_ceil(BATCH_SAMPLES) as u64,
    };
    assert_eq!(per_topic["/wbv/measured"], messages);
    assert_eq!(per_topic["/wbv/state"], messages);
    assert_eq!(per_topic["/wbv/links"], messages);
    assert_eq!(per_topic["/wbv/scene"], 75);
    assert_eq!(per_topic["/tf"], 75);
    assert_eq!(per_topic.len(), 5, "{per_topic:?}");
}
