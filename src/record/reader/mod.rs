//! Reading a recorded run back: [`read_run`] (signals, provenance, results) and [`inspect`] (summary
//! only). A truncated or corrupt file gives one error line naming the file, never a panic: the
//! magic bytes, footer and every index offset are checked before the `mcap` crate slices with them.

mod decode;

use super::Provenance;
use super::meta::{self, Map};
use super::proto::ProtoTable;
use super::topics::channel_name;
use crate::error::{Error, Result};
use crate::io::mcap_stream::Records;
use crate::signals::Signals;
use decode::*;
use serde::de::{DeserializeSeed, Deserializer, Error as _, MapAccess, Visitor};
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// The time-series topics read into [`Signals`], in channel order.
const SIGNAL_TOPICS: [&str; 4] = ["/wbv/measured", "/wbv/state", "/wbv/links", "/wbv/base"];

/// One channel of the file.
#[derive(Debug, Clone, PartialEq)]
pub struct TopicSummary {
    /// Topic name, e.g. `/wbv/measured`.
    pub topic: String,
    /// Schema name, e.g. `wbv.State` or `foxglove.SceneUpdate`.
    pub schema: String,
    /// MCAP message encoding: `protobuf` or `json` for wbv's own topics.
    pub message_encoding: String,
    /// Messages on the channel, from the statistics record (0 if it lists none).
    pub messages: u64,
}

/// What [`inspect`] finds in a run without decoding its messages.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// The file that was read.
    pub path: PathBuf,
    /// Writer library from the MCAP header.
    pub library: String,
    /// Channels in channel-id order.
    pub topics: Vec<TopicSummary>,
    /// Log time of the first message, ns.
    pub start_ns: u64,
    /// Log time of the last message, ns.
    pub end_ns: u64,
    /// Metadata records by name.
    pub metadata: BTreeMap<String, Map>,
    /// Attachments: name, media type, size in bytes.
    pub attachments: Vec<(String, String, u64)>,
}

/// A run read back from its MCAP file.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordedRun {
    /// Measured-run channels (`a_base_z`, `a_seat_z`, `a_head_z`, `f_seat_z`) and state channels
    /// named like their plot paths without `/wbv/` (`state.head.a_abs`, `links.k1.force`, `base.a`).
    pub signals: Signals,
    /// How the run was made (model, excitation, integrator, step, seed, wbv version), from the
    /// file's metadata.
    pub provenance: Provenance,
    /// Results stored with `attach_results`, by name.
    pub results: BTreeMap<String, serde_json::Value>,
    /// What [`inspect`] reports for the same file.
    pub summary: RunSummary,
}

fn corrupt(path: &Path, what: impl fmt::Display) -> Error {
    Error::data(path, None, format!("corrupt or truncated MCAP run: {what}"))
}

/// Checks the framing of a whole-file buffer and reads its summary section.
fn summary(path: &Path, buf: &[u8]) -> Result<mcap::Summary> {
    if buf.len() < 8 || !buf.starts_with(mcap::MAGIC) {
        return Err(Error::data(
            path,
            None,
            "not an MCAP file (bad magic bytes)",
        ));
    }
    if buf.len() < 8 + 29 + 8 || !buf.ends_with(mcap::MAGIC) {
        return Err(Error::data(
            path,
            None,
            "incomplete MCAP run (no footer): the recording was interrupted or the file is truncated",
        ));
    }
    match mcap::Summary::read(buf) {
        Ok(Some(s)) => Ok(s),
        Ok(None) => Err(Error::data(path, None, "MCAP file has no summary section")),
        Err(e) => Err(corrupt(path, e)),
    }
}

/// The slice `offset..offset+length` of `buf`, if it lies inside it.
fn within(buf: &[u8], offset: u64, length: u64) -> bool {
    offset
        .checked_add(length)
        .is_some_and(|end| end <= buf.len() as u64)
}

fn summarize(path: &Path, buf: &[u8], s: &mcap::Summary) -> Result<RunSummary> {
    let library = match mcap::read::LinearReader::new(buf)
        .map_err(|e| corrupt(path, e))?
        .next()
    {
        Some(Ok(mcap::records::Record::Header(h))) => h.library,
        _ => return Err(corrupt(path, "no header record")),
    };
    let stats = s
        .stats
        .as_ref()
        .ok_or_else(|| corrupt(path, "no statistics record"))?;
    let mut ids: Vec<_> = s.channels.keys().copied().collect();
    ids.sort_unstable();
    let topics = ids
        .iter()
        .map(|id| {
            let c = &s.channels[id];
            TopicSummary {
                topic: c.topic.clone(),
                schema: c.schema.as_ref().map_or(String::new(), |x| x.name.clone()),
                message_encoding: c.message_encoding.clone(),
                messages: stats.channel_message_counts.get(id).copied().unwrap_or(0),
            }
        })
        .collect();
    let mut metadata = BTreeMap::new();
    for idx in &s.metadata_indexes {
        if !within(buf, idx.offset, idx.length) {
            return Err(corrupt(path, "metadata index points outside the file"));
        }
        let m = mcap::read::metadata(buf, idx).map_err(|e| corrupt(path, e))?;
        metadata.insert(m.name, m.metadata);
    }
    let attachments = s
        .attachment_indexes
        .iter()
        .map(|a| (a.name.clone(), a.media_type.clone(), a.data_size))
        .collect();
    Ok(RunSummary {
        path: path.to_path_buf(),
        library,
        topics,
        start_ns: stats.message_start_time,
        end_ns: stats.message_end_time,
        metadata,
        attachments,
    })
}

/// Largest record (or decompressed chunk) accepted; the recorder writes 1 MiB chunks.
const MAX_RECORD_BYTES: usize = 64 << 20;

/// Calls `f(topic, sequence, data)` for every message, in file order, from the bounded record
/// stream of [`crate::io::mcap_stream`]: chunk CRCs are checked before any record of a chunk is
/// parsed and record lengths are bounded, so corrupt bytes give an error rather than a huge
/// allocation inside the `mcap` crate.
fn for_each_message(
    path: &Path,
    buf: &[u8],
    s: &mcap::Summary,
    mut f: impl FnMut(&mcap::Channel<'_>, u32, &[u8]) -> Result<()>,
) -> Result<()> {
    let mut records = Records::with_crcs(buf, MAX_RECORD_BYTES);
    let mut message = |opcode: u8, data: &[u8]| -> Result<()> {
        match mcap::parse_record(opcode, data).map_err(|e| corrupt(path, e))? {
            mcap::records::Record::Message { header, data } => {
                let channel = s.channels.get(&header.channel_id).ok_or_else(|| {
                    corrupt(path, format!("unknown channel {}", header.channel_id))
                })?;
                f(channel, header.sequence, &data)
            }
            _ => Err(corrupt(path, "message record expected")),
        }
    };
    while let Some(done) = records.next_taken(|opcode, data| {
        (opcode == mcap::records::op::MESSAGE).then(|| message(opcode, data))
    }) {
        done.map_err(|e| corrupt(path, e))??;
    }
    Ok(())
}

fn read_file(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| Error::io(path, e))
}

/// Channels, message counts, duration, metadata and attachments of a run, from its summary section.
pub fn inspect(path: &Path) -> Result<RunSummary> {
    let buf = read_file(path)?;
    let s = summary(path, &buf)?;
    summarize(path, &buf, &s)
}

/// The provenance of a recorded run and its `wbv.run` metadata record, from the summary only.
pub fn read_provenance(path: &Path) -> Result<(Provenance, Map)> {
    let s = inspect(path)?;
    let p = meta::provenance(path, &s.metadata)?;
    let run = s.metadata.get(meta::RUN).cloned().unwrap_or_default();
    Ok((p, run))
}

/// Reads a run recorded by [`McapRecorder`](super::McapRecorder): every time-series message (CRCs
/// checked), its provenance and its stored results.
pub fn read_run(path: &Path) -> Result<RecordedRun> {
    let buf = read_file(path)?;
    let s = summary(path, &buf)?;
    let summary = summarize(path, &buf, &s)?;
    let provenance = meta::provenance(path, &summary.metadata)?;
    let run = &summary.metadata[meta::RUN];
    let fs: f64 = run
        .get("sample_rate_hz")
        .and_then(|r| r.parse().ok())
        .filter(|r: &f64| r.is_finite() && *r > 0.0)
        .ok_or_else(|| corrupt(path, "metadata `wbv.run.sample_rate_hz` missing or invalid"))?;

    // Per signal topic: its table, made from the channel's encoding (and descriptor) on first use.
    let mut tables: Vec<Option<Decoded>> = SIGNAL_TOPICS.iter().map(|_| None).collect();
    for_each_message(path, &buf, &s, |channel, sequence, data| {
        let topic = channel.topic.as_str();
        let Some(k) = SIGNAL_TOPICS.iter().position(|t| *t == topic) else {
            return Ok(());
        };
        let err = |e: String| Error::data(path, None, format!("{topic} message {sequence}: {e}"));
        let table = match &mut tables[k] {
            Some(t) => t,
            empty => empty.insert(Decoded::new(channel).map_err(err)?),
        };
        table.add(data).map_err(err)
    })?;

    let mut signals = Signals::new(fs, path.display().to_string());
    for (topic, table) in SIGNAL_TOPICS.iter().zip(tables) {
        let table = table.map(Decoded::into_table).unwrap_or_default();
        if table.names.is_empty() {
            if *topic == SIGNAL_TOPICS[0] {
                return Err(Error::data(
                    path,
                    None,
                    "not a wbv run: no /wbv/measured messages",
                ));
            }
            continue;
        }
        table
            .check_time(fs)
            .map_err(|e| Error::data(path, None, format!("{topic}: {e}")))?;
        for (name, col) in table.names.into_iter().zip(table.columns) {
            if name.len() != 1 || name[0] != "t" {
                signals.push(channel_name(topic, &name), col)?;
            }
        }
    }
    let mut results = BTreeMap::new();
    for (name, text) in summary.metadata.get(meta::RESULTS).into_iter().flatten() {
        let v = serde_json::from_str(text)
            .map_err(|e| corrupt(path, format!("results `{name}` are not JSON: {e}")))?;
        results.insert(name.clone(), v);
    }
    Ok(RecordedRun {
        signals,
        provenance,
        results,
        summary,
    })
}
