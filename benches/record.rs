//! Recording throughput of `McapRecorder` for the synthetic 5-mass layout at 1 kHz (3 messages
//! per step + the 30 Hz scene), protobuf (the default, batched: one message per topic per 1024
//! steps) and JSON (per sample), and what it is made of:
//! formatting the JSON floats alone and framing + compressing the rendered messages alone
//! (through the mcap writer, as the recorder does). Every figure is also printed per simulated hour (3.6 M steps), with the CPU time, so
//! that the cost on an idle machine (wall ≈ CPU / cores) can be told from a loaded one.
//!
//! `cargo bench --bench record`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Instant;
use wbv::record::{
    Compression, Encoding, McapRecorder, Overwrite, Provenance, RecordOptions, demo,
};

const FS: f64 = 1000.0;
/// Simulated seconds per criterion sample.
const SECONDS: u64 = 10;
/// Simulated seconds of the per-hour projection: long enough for the 10 ms CPU clock.
const LONG: u64 = 60;
const HOUR: f64 = 3600.0 / LONG as f64;
const COMPRESSIONS: [Compression; 3] = [Compression::Zstd, Compression::Lz4, Compression::None];
const ENCODINGS: [Encoding; 2] = [Encoding::Protobuf, Encoding::Json];

fn record(path: &std::path::Path, encoding: Encoding, compression: Compression, seconds: u64) {
    let options = RecordOptions {
        encoding,
        compression,
        overwrite: Overwrite::Allow,
        ..RecordOptions::default()
    };
    let mut rec = McapRecorder::create(path, Provenance::new(), options).expect("create");
    demo::drive(&mut rec, FS, seconds * 1000 + 1).expect("record");
}

/// CPU time of this process (all threads), s.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (ticks(11) + ticks(12)) / 100.0 // utime, stime in clock ticks (USER_HZ = 100)
}

/// Best of `n` runs of `f`: (wall s, CPU s).
fn best_of(n: usize, mut f: impl FnMut()) -> (f64, f64) {
    (0..n)
        .map(|_| {
            let (t0, c0) = (Instant::now(), cpu_seconds());
            f();
            (t0.elapsed().as_secs_f64(), cpu_seconds() - c0)
        })
        .fold((f64::MAX, f64::MAX), |(w, c), (a, b)| (w.min(a), c.min(b)))
}

fn per_hour(what: &str, (wall, cpu): (f64, f64), bytes: u64) {
    println!(
        "{what:<38} {:>6.2} s wall {:>6.2} s CPU per simulated hour, {:>5.0} kB per simulated second",
        wall * HOUR,
        cpu * HOUR,
        bytes as f64 / LONG as f64 / 1e3
    );
}

/// The messages of a recorded run, in file order: (channel topic, log time, data).
fn messages(path: &std::path::Path) -> Vec<(String, u64, Vec<u8>)> {
    let bytes = std::fs::read(path).expect("recorded run");
    mcap::MessageStream::new(&bytes)
        .expect("mcap")
        .map(|m| {
            let m = m.expect("message");
            (m.channel.topic.clone(), m.log_time, m.data.into_owned())
        })
        .collect()
}

/// Frames and compresses pre-rendered `messages` as the recorder's writer thread does.
fn write_messages(path: &std::path::Path, msgs: &[(String, u64, Vec<u8>)], c: Compression) {
    let (compression, level) = match c {
        Compression::Zstd => (Some(mcap::Compression::Zstd), 1),
        Compression::Lz4 => (Some(mcap::Compression::Lz4), 0),
        Compression::None => (None, 0),
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get().min(4));
    let file = std::fs::File::create(path).expect("file");
    let mut w = mcap::WriteOptions::new()
        .compression(compression)
        .compression_level(level)
        .compression_threads(threads as u32)
        .chunk_size(Some(8 << 20))
        .create(std::io::BufWriter::with_capacity(1 << 20, file))
        .expect("writer");
    let mut ids = std::collections::BTreeMap::new();
    for (topic, time, data) in msgs {
        let id = *ids.entry(topic.clone()).or_insert_with(|| {
            let sid = w.add_schema(topic, "jsonschema", b"{}").expect("schema");
            (w.add_channel(sid, topic, "json", &Default::default())).expect("channel")
        });
        let header = mcap::records::MessageHeader {
            channel_id: id,
            sequence: 0,
            log_time: *time,
            publish_time: *time,
        };
        w.write_to_known_channel(&header, data).expect("write");
    }
    w.finish().expect("finish");
}

fn bench_record(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = |e: Encoding, c: Compression| {
        dir.path()
            .join(format!("{}-{}.mcap", e.as_str(), c.as_str()))
    };
    let mut g = c.benchmark_group("record_10s_at_1kHz_5_masses");
    g.sample_size(10);
    g.throughput(Throughput::Elements(SECONDS * 1000 + 1));
    for e in ENCODINGS {
        for compression in COMPRESSIONS {
            let p = path(e, compression);
            g.bench_function(format!("{}_{}", e.as_str(), compression.as_str()), |b| {
                b.iter(|| record(&p, e, compression, SECONDS))
            });
        }
    }
    g.finish();

    // The synthetic state alone (what the recorder is fed), to subtract from the above.
    let mut g = c.benchmark_group("synthetic_steps_only");
    g.throughput(Throughput::Elements(1000));
    g.bench_function("1000_steps", |b| {
        b.iter(|| {
            for i in 0..1000 {
                black_box(demo::State::at(black_box(i), 1e-3));
            }
        })
    });
    g.finish();

    // Per simulated hour, and its parts. The floats of the run, formatted alone.
    println!("\nper simulated hour at 1 kHz (best of 3; load {})", load());
    for e in ENCODINGS {
        for compression in COMPRESSIONS {
            let p = path(e, compression);
            let t = best_of(3, || record(&p, e, compression, LONG));
            let size = std::fs::metadata(&p).map_or(0, |m| m.len());
            per_hour(
                &format!("record, {}, {}", e.as_str(), compression.as_str()),
                t,
                size,
            );
        }
    }
    let msgs = messages(&path(Encoding::Json, Compression::None));
    let floats: Vec<f64> = msgs
        .iter()
        .filter(|(t, _, _)| !matches!(t.as_str(), "/wbv/scene" | "/tf"))
        .flat_map(|(_, _, d)| numbers(d))
        .collect();
    let mut out = Vec::with_capacity(64 << 20);
    let format = best_of(3, || {
        out.clear();
        for v in &floats {
            use serde_json::ser::{CompactFormatter, Formatter};
            CompactFormatter.write_f64(&mut out, *v).expect("vec");
        }
        black_box(out.len());
    });
    let per_step = floats.len() as f64 / (LONG * 1000 + 1) as f64;
    per_hour(
        &format!("format {per_step:.0} floats/step (1 thread)"),
        format,
        0,
    );
    let synthetic = best_of(3, || {
        for i in 0..LONG * 1000 {
            black_box(demo::State::at(black_box(i), 1e-3));
        }
    });
    per_hour("synthetic steps (subtract)", synthetic, 0);
    let proto = messages(&path(Encoding::Protobuf, Compression::None));
    for (e, msgs) in [("json", &msgs), ("protobuf", &proto)] {
        for compression in COMPRESSIONS {
            let p = dir.path().join("framing.mcap");
            let t = best_of(3, || write_messages(&p, msgs, compression));
            let size = std::fs::metadata(&p).map_or(0, |m| m.len());
            per_hour(
                &format!("mcap writer only, {e}, {}", compression.as_str()),
                t,
                size,
            );
        }
    }
}

/// The numbers of a flat or nested JSON object of numbers.
fn numbers(data: &[u8]) -> Vec<f64> {
    fn walk(v: &serde_json::Value, out: &mut Vec<f64>) {
        match v {
            serde_json::Value::Number(n) => out.extend(n.as_f64()),
            serde_json::Value::Object(m) => m.values().for_each(|x| walk(x, out)),
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(&serde_json::from_slice(data).expect("json"), &mut out);
    out
}

fn load() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|l| l.split_whitespace().next().unwrap_or("?").to_string())
        .unwrap_or_else(|_| "?".into())
}

criterion_group!(benches, bench_record);
criterion_main!(benches);
