//! The MCAP writer of a run (<https://mcap.dev/spec>): records framed straight into a chunk buffer,
//! chunks compressed whole on worker threads and written in order, then the summary.
//!
//! Why not `mcap::Writer`: it passes every record to its compressor in seven small writes (opcode,
//! length, four header fields, data), and zstd's multi-threaded stream takes a lock on each call:
//! with three messages per step that was 5 of a full-rate hour's 14 CPU-s (`perf`, README
//! "Speed"). Here a message is one `extend_from_slice` of its 31-byte header and its data into
//! the open chunk, and a chunk is one `zstd::bulk` call on a compressor thread, the next chunk
//! filled meanwhile. The records themselves are the `mcap` crate's types written with its
//! `binrw` encoders; the file is read back by the `mcap` crate (`record::reader`), by the PyPI and
//! npm MCAP readers and by Rerun (`tools/validate-mcap`).

use super::Compression;
use binrw::BinWrite;
use mcap::McapResult;
use mcap::records::{self, MessageHeader, op};
use std::collections::BTreeMap;
use std::io::{Cursor, Write};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::thread::JoinHandle;

/// zstd level of the chunks: -1 (the first "fast" level: level 1's match finder stepping faster)
/// with [`ZSTD_MIN_MATCH`]. On the chunks of a per-sample run (10 min of the default scenario,
/// 4 MiB chunks, PyPI `zstandard` on the uncompressed file) level 1 kept 0.651 of the bytes at
/// 343 MB/s, level -1 with 4-byte matches 0.630 at 532 MB/s, level 3 0.624 at 218 MB/s.
const ZSTD_LEVEL: i32 = -1;

/// Shortest match zstd looks for, in bytes (level 1's is 6). The repeats in a run are short: the
/// sign and exponent bytes of doubles of one magnitude and the framing of consecutive messages.
const ZSTD_MIN_MATCH: u32 = 4;

/// Uncompressed chunk size: a few MiB, so that compressor threads work in parallel on
/// consecutive chunks, and small enough for viewers that decompress a chunk at a time.
pub const CHUNK_BYTES: usize = 4 << 20;

/// The MCAP file's first bytes (and last).
const MAGIC: &[u8] = mcap::MAGIC;

/// A chunk being filled: its records, uncompressed, and the index of its messages.
#[derive(Default)]
struct Chunk {
    records: Vec<u8>,
    start: u64,
    end: u64,
    /// Per channel id: (log time, offset in `records`) of each message.
    index: BTreeMap<u16, Vec<records::MessageIndexEntry>>,
}

/// A chunk compressed by a worker: the chunk and its compressed records with their CRC.
struct Compressed {
    chunk: Chunk,
    data: Vec<u8>,
    crc: u32,
}

/// The compressor threads: chunk `k` goes to thread `k mod n` and is collected in the same
/// order, so the file does not depend on thread timing or count.
struct Compressors {
    to: Vec<SyncSender<(Chunk, Vec<u8>)>>,
    from: Vec<Receiver<std::io::Result<Compressed>>>,
    handles: Vec<JoinHandle<()>>,
    /// Chunks sent, and how many of them have been collected.
    sent: usize,
    collected: usize,
    /// Buffers of written chunks, for the next ones (kept, not freed: a fresh multi-MiB buffer
    /// is a fresh mapping whose pages the kernel faults in and zeroes).
    spare_chunks: Vec<Chunk>,
    spare_data: Vec<Vec<u8>>,
}

/// Compresses `input` into `out` (cleared first); `zstd` is the thread's context, made once.
fn compress(
    compression: Compression,
    zstd: &mut Option<zstd::bulk::Compressor<'static>>,
    input: &[u8],
    out: &mut Vec<u8>,
) -> std::io::Result<()> {
    out.clear();
    match compression {
        Compression::Zstd => {
            let z = match zstd {
                Some(z) => z,
                None => {
                    let mut z = zstd::bulk::Compressor::new(ZSTD_LEVEL)?;
                    z.set_parameter(zstd::zstd_safe::CParameter::MinMatch(ZSTD_MIN_MATCH))?;
                    zstd.insert(z)
                }
            };
            out.reserve(zstd::zstd_safe::compress_bound(input.len()));
            z.compress_to_buffer(input, out)?;
        }
        Compression::Lz4 => {
            // The LZ4 frame format MCAP names `lz4`, without block checksums (the chunk has its
            // CRC), lz4's default (fast) mode.
            let mut enc = lz4::EncoderBuilder::new()
                .level(0)
                .block_checksum(lz4::liblz4::BlockChecksum::NoBlockChecksum)
                .build(std::mem::take(out))?;
            enc.write_all(input)?;
            let (buf, result) = enc.finish();
            *out = buf;
            result?;
        }
        Compression::None => out.extend_from_slice(input),
    }
    Ok(())
}

impl Compressors {
    fn spawn(compression: Compression, threads: usize) -> Self {
        let (mut to, mut from, mut handles) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..threads.max(1) {
            let (tx, rx) = sync_channel::<(Chunk, Vec<u8>)>(1);
            let (done_tx, done_rx) = sync_channel(1);
            handles.push(std::thread::spawn(move || {
                let mut zstd = None;
                for (chunk, mut data) in rx {
                    let crc = crc32fast::hash(&chunk.records);
                    let result = compress(compression, &mut zstd, &chunk.records, &mut data)
                        .map(|()| Compressed { chunk, data, crc });
                    if done_tx.send(result).is_err() {
                        return;
                    }
                }
            }));
            to.push(tx);
            from.push(done_rx);
        }
        Compressors {
            to,
            from,
            handles,
            sent: 0,
            collected: 0,
            spare_chunks: Vec::new(),
            spare_data: Vec::new(),
        }
    }

    fn in_flight(&self) -> usize {
        self.sent - self.collected
    }

    fn send(&mut self, chunk: Chunk) {
        let data = self.spare_data.pop().unwrap_or_default();
        let k = self.sent % self.to.len();
        self.sent += 1;
        // A compressor ends only when its sender is dropped.
        self.to[k]
            .send((chunk, data))
            .expect("compressor thread alive");
    }

    fn collect(&mut self) -> std::io::Result<Compressed> {
        let k = self.collected % self.from.len();
        self.collected += 1;
        self.from[k]
            .recv()
            .map_err(|_| std::io::Error::other("a chunk compressor thread stopped"))?
    }

    /// A cleared chunk to fill, reusing the buffers of a written one.
    fn empty_chunk(&mut self) -> Chunk {
        let mut c = self.spare_chunks.pop().unwrap_or_default();
        c.records.clear();
        c.index.values_mut().for_each(Vec::clear);
        c.records.reserve(CHUNK_BYTES + (64 << 10));
        c
    }
}

impl Drop for Compressors {
    fn drop(&mut self) {
        self.to.clear();
        for h in self.handles.drain(..) {
            let _ = h.join();
        }
    }
}

/// Writes an MCAP file: the header, then schemas, channels, metadata and attachments as they are
/// added, messages in chunks of about [`CHUNK_BYTES`], and at [`McapWriter::finish`] the summary
/// (schemas, channels, statistics, chunk, attachment and metadata indexes, with summary offsets).
/// The data-section and summary CRCs are written as 0 ("not computed", as the spec allows); every
/// chunk and attachment has its CRC.
pub struct McapWriter<W: Write> {
    out: W,
    /// Offset of the next byte written.
    pos: u64,
    compression: Compression,
    schemas: Vec<(records::SchemaHeader, Vec<u8>)>,
    channels: Vec<records::Channel>,
    chunk: Chunk,
    compressors: Compressors,
    statistics: records::Statistics,
    chunk_indexes: Vec<records::ChunkIndex>,
    attachment_indexes: Vec<records::AttachmentIndex>,
    metadata_indexes: Vec<records::MetadataIndex>,
    /// Scratch for a record's body.
    scratch: Vec<u8>,
}

/// Appends `value` (a record body of the `mcap` crate) to `buf` with its `binrw` encoder.
fn encode<T: for<'a> BinWrite<Args<'a> = ()>>(value: &T, buf: &mut Vec<u8>) -> McapResult<()> {
    let mut cursor = Cursor::new(buf);
    cursor.set_position(cursor.get_ref().len() as u64);
    value.write_le(&mut cursor)?;
    Ok(())
}

/// The MCAP name of a chunk compression.
fn compression_name(c: Compression) -> &'static str {
    match c {
        Compression::Zstd => "zstd",
        Compression::Lz4 => "lz4",
        Compression::None => "",
    }
}

impl<W: Write> McapWriter<W> {
    /// Starts the file: magic and header record (profile none, `library`); chunks compressed
    /// with `compression` on `threads` threads.
    pub fn new(
        out: W,
        compression: Compression,
        threads: usize,
        library: String,
    ) -> McapResult<Self> {
        let mut w = McapWriter {
            out,
            pos: 0,
            compression,
            schemas: Vec::new(),
            channels: Vec::new(),
            chunk: Chunk::default(),
            compressors: Compressors::spawn(compression, threads),
            statistics: records::Statistics::default(),
            chunk_indexes: Vec::new(),
            attachment_indexes: Vec::new(),
            metadata_indexes: Vec::new(),
            scratch: Vec::new(),
        };
        w.chunk = w.compressors.empty_chunk();
        w.write_raw(MAGIC)?;
        let header = records::Header {
            profile: String::new(),
            library,
        };
        w.record(op::HEADER, |b| encode(&header, b))?;
        // On the disk at once: a file cut short reads as an incomplete MCAP file, not as another
        // kind of file.
        w.out.flush()?;
        Ok(w)
    }

    fn write_raw(&mut self, bytes: &[u8]) -> McapResult<()> {
        self.out.write_all(bytes)?;
        self.pos += bytes.len() as u64;
        Ok(())
    }

    /// Writes a record whose body `body` appends to a buffer; returns its offset and length
    /// (opcode and length prefix included).
    fn record(
        &mut self,
        opcode: u8,
        body: impl FnOnce(&mut Vec<u8>) -> McapResult<()>,
    ) -> McapResult<(u64, u64)> {
        let mut buf = std::mem::take(&mut self.scratch);
        buf.clear();
        let result = body(&mut buf).and_then(|()| {
            let start = self.pos;
            self.write_raw(&[opcode])?;
            self.write_raw(&(buf.len() as u64).to_le_bytes())?;
            self.write_raw(&buf)?;
            Ok((start, self.pos - start))
        });
        self.scratch = buf;
        result
    }

    /// Adds a schema; returns its id (from 1).
    pub fn add_schema(&mut self, name: &str, encoding: &str, data: &[u8]) -> McapResult<u16> {
        let header = records::SchemaHeader {
            id: self.schemas.len() as u16 + 1,
            name: name.into(),
            encoding: encoding.into(),
        };
        self.write_schema(&header, data)?;
        self.schemas.push((header.clone(), data.to_vec()));
        Ok(header.id)
    }

    fn write_schema(&mut self, header: &records::SchemaHeader, data: &[u8]) -> McapResult<u64> {
        let (_, len) = self.record(op::SCHEMA, |b| {
            encode(header, b)?;
            b.extend_from_slice(&(data.len() as u32).to_le_bytes());
            b.extend_from_slice(data);
            Ok(())
        })?;
        Ok(len)
    }

    /// Adds a channel on `topic` of schema `schema_id`; returns its id (from 0).
    pub fn add_channel(
        &mut self,
        schema_id: u16,
        topic: &str,
        message_encoding: &str,
        metadata: &BTreeMap<String, String>,
    ) -> McapResult<u16> {
        let channel = records::Channel {
            id: self.channels.len() as u16,
            schema_id,
            topic: topic.into(),
            message_encoding: message_encoding.into(),
            metadata: metadata.clone(),
        };
        self.record(op::CHANNEL, |b| encode(&channel, b))?;
        self.statistics.channel_message_counts.insert(channel.id, 0);
        self.channels.push(channel);
        Ok(self.channels.len() as u16 - 1)
    }

    /// Adds a message of a channel added before to the open chunk (framed as a Message record:
    /// opcode, length, channel id, sequence, log and publish time, data).
    pub fn write_to_known_channel(
        &mut self,
        header: &MessageHeader,
        data: &[u8],
    ) -> McapResult<()> {
        let c = &mut self.chunk;
        let Some(count) = (self.statistics.channel_message_counts).get_mut(&header.channel_id)
        else {
            return Err(mcap::McapError::UnknownChannel(
                header.sequence,
                header.channel_id,
            ));
        };
        *count += 1;
        let t = header.log_time;
        if c.records.is_empty() {
            (c.start, c.end) = (t, t);
        }
        (c.start, c.end) = (c.start.min(t), c.end.max(t));
        c.index
            .entry(header.channel_id)
            .or_default()
            .push(records::MessageIndexEntry {
                log_time: t,
                offset: c.records.len() as u64,
            });
        let r = &mut c.records;
        r.push(op::MESSAGE);
        r.extend_from_slice(&(22 + data.len() as u64).to_le_bytes());
        r.extend_from_slice(&header.channel_id.to_le_bytes());
        r.extend_from_slice(&header.sequence.to_le_bytes());
        r.extend_from_slice(&t.to_le_bytes());
        r.extend_from_slice(&header.publish_time.to_le_bytes());
        r.extend_from_slice(data);
        let s = &mut self.statistics;
        if s.message_count == 0 {
            (s.message_start_time, s.message_end_time) = (t, t);
        }
        s.message_count += 1;
        (s.message_start_time, s.message_end_time) =
            (s.message_start_time.min(t), s.message_end_time.max(t));
        if r.len() >= CHUNK_BYTES {
            self.close_chunk()?;
        }
        Ok(())
    }

    /// Hands the open chunk to a compressor, first writing the oldest compressed chunk when every
    /// compressor is busy.
    fn close_chunk(&mut self) -> McapResult<()> {
        if self.chunk.records.is_empty() {
            return Ok(());
        }
        if self.compressors.in_flight() == self.compressors.to.len() {
            let done = self.compressors.collect()?;
            self.write_chunk(done)?;
        }
        let next = self.compressors.empty_chunk();
        let chunk = std::mem::replace(&mut self.chunk, next);
        self.compressors.send(chunk);
        Ok(())
    }

    /// Closes the open chunk and writes every chunk in flight: what is written next follows them.
    fn drain(&mut self) -> McapResult<()> {
        self.close_chunk()?;
        while self.compressors.in_flight() > 0 {
            let done = self.compressors.collect()?;
            self.write_chunk(done)?;
        }
        Ok(())
    }

    /// Writes a compressed chunk and its message indexes.
    fn write_chunk(&mut self, done: Compressed) -> McapResult<()> {
        let Compressed { chunk, data, crc } = done;
        let compression = compression_name(self.compression);
        let header = records::ChunkHeader {
            message_start_time: chunk.start,
            message_end_time: chunk.end,
            uncompressed_size: chunk.records.len() as u64,
            uncompressed_crc: crc,
            compression: compression.into(),
            compressed_size: data.len() as u64,
        };
        let mut head = Vec::with_capacity(64);
        encode(&header, &mut head)?;
        let chunk_start = self.pos;
        self.write_raw(&[op::CHUNK])?;
        self.write_raw(&((head.len() + data.len()) as u64).to_le_bytes())?;
        self.write_raw(&head)?;
        self.write_raw(&data)?;
        let chunk_length = self.pos - chunk_start;
        let mut offsets = BTreeMap::new();
        let index_start = self.pos;
        for (&channel_id, entries) in chunk.index.iter().filter(|(_, e)| !e.is_empty()) {
            let (offset, _) = self.record(op::MESSAGE_INDEX, |b| {
                b.extend_from_slice(&channel_id.to_le_bytes());
                b.extend_from_slice(&(16 * entries.len() as u32).to_le_bytes());
                for e in entries {
                    b.extend_from_slice(&e.log_time.to_le_bytes());
                    b.extend_from_slice(&e.offset.to_le_bytes());
                }
                Ok(())
            })?;
            offsets.insert(channel_id, offset);
        }
        self.chunk_indexes.push(records::ChunkIndex {
            message_start_time: chunk.start,
            message_end_time: chunk.end,
            chunk_start_offset: chunk_start,
            chunk_length,
            message_index_offsets: offsets,
            message_index_length: self.pos - index_start,
            compression: compression.into(),
            compressed_size: data.len() as u64,
            uncompressed_size: chunk.records.len() as u64,
        });
        self.statistics.chunk_count += 1;
        self.compressors.spare_chunks.push(chunk);
        self.compressors.spare_data.push(data);
        Ok(())
    }

    /// Writes a metadata record (after every message written so far).
    pub fn write_metadata(&mut self, metadata: &records::Metadata) -> McapResult<()> {
        self.drain()?;
        let (offset, length) = self.record(op::METADATA, |b| encode(metadata, b))?;
        self.metadata_indexes.push(records::MetadataIndex {
            offset,
            length,
            name: metadata.name.clone(),
        });
        self.statistics.metadata_count += 1;
        Ok(())
    }

    /// Writes an attachment record with its CRC (after every message written so far).
    pub fn attach(&mut self, a: &mcap::Attachment<'_>) -> McapResult<()> {
        self.drain()?;
        let header = records::AttachmentHeader {
            log_time: a.log_time,
            create_time: a.create_time,
            name: a.name.clone(),
            media_type: a.media_type.clone(),
        };
        let (offset, length) = self.record(op::ATTACHMENT, |b| {
            encode(&header, b)?;
            b.extend_from_slice(&(a.data.len() as u64).to_le_bytes());
            b.extend_from_slice(&a.data);
            let crc = crc32fast::hash(b);
            b.extend_from_slice(&crc.to_le_bytes());
            Ok(())
        })?;
        self.attachment_indexes.push(records::AttachmentIndex {
            offset,
            length,
            log_time: a.log_time,
            create_time: a.create_time,
            data_size: a.data.len() as u64,
            name: a.name.clone(),
            media_type: a.media_type.clone(),
        });
        self.statistics.attachment_count += 1;
        Ok(())
    }

    /// Writes the last chunks, the data end, the summary and the footer, and flushes.
    pub fn finish(&mut self) -> McapResult<()> {
        self.drain()?;
        self.record(op::DATA_END, |b| encode(&records::DataEnd::default(), b))?;
        let summary_start = self.pos;
        let mut groups = Vec::new();
        let schemas = std::mem::take(&mut self.schemas);
        let start = self.pos;
        for (header, data) in &schemas {
            self.write_schema(header, data)?;
        }
        groups.push((op::SCHEMA, start));
        self.statistics.schema_count = schemas.len() as u16;
        self.statistics.channel_count = self.statistics.channel_message_counts.len() as u32;
        let channels = std::mem::take(&mut self.channels);
        groups.push(self.group(op::CHANNEL, &channels)?);
        let statistics = [self.statistics.clone()];
        groups.push(self.group(op::STATISTICS, &statistics)?);
        let chunks = std::mem::take(&mut self.chunk_indexes);
        groups.push(self.group(op::CHUNK_INDEX, &chunks)?);
        let attachments = std::mem::take(&mut self.attachment_indexes);
        groups.push(self.group(op::ATTACHMENT_INDEX, &attachments)?);
        let metadata = std::mem::take(&mut self.metadata_indexes);
        groups.push(self.group(op::METADATA_INDEX, &metadata)?);
        let ends: Vec<u64> = (groups.iter().skip(1).map(|g| g.1))
            .chain([self.pos])
            .collect();
        let summary_offset_start = self.pos;
        for ((group_opcode, group_start), end) in groups.into_iter().zip(ends) {
            if end > group_start {
                let offset = records::SummaryOffset {
                    group_opcode,
                    group_start,
                    group_length: end - group_start,
                };
                self.record(op::SUMMARY_OFFSET, |b| encode(&offset, b))?;
            }
        }
        let footer = records::Footer {
            summary_start,
            summary_offset_start,
            summary_crc: 0,
        };
        self.record(op::FOOTER, |b| encode(&footer, b))?;
        self.write_raw(MAGIC)?;
        self.out.flush()?;
        Ok(())
    }

    /// Writes a summary group: a record of `opcode` per item; returns the opcode and the start.
    fn group<T: for<'a> BinWrite<Args<'a> = ()>>(
        &mut self,
        opcode: u8,
        items: &[T],
    ) -> McapResult<(u8, u64)> {
        let start = self.pos;
        for item in items {
            self.record(opcode, |b| encode(item, b))?;
        }
        Ok((opcode, start))
    }

    /// The file, after [`McapWriter::finish`] (or abandoned without a summary).
    pub fn into_inner(self) -> W {
        let McapWriter {
            out, compressors, ..
        } = self;
        drop(compressors);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `mcap` crate's reader (CRCs checked) reads back what the writer wrote, in every
    /// compression, across several chunks with metadata and an attachment after them.
    #[test]
    fn the_mcap_crate_reads_back_every_record() {
        for compression in [Compression::Zstd, Compression::Lz4, Compression::None] {
            let mut w = McapWriter::new(Vec::new(), compression, 2, "test".into()).unwrap();
            let s = w.add_schema("wbv.Test", "protobuf", b"descriptor").unwrap();
            let none = BTreeMap::new();
            let ids = [
                w.add_channel(s, "/a", "protobuf", &none).unwrap(),
                w.add_channel(s, "/b", "protobuf", &none).unwrap(),
            ];
            let n = 3 * CHUNK_BYTES / 1000;
            for i in 0..n {
                let header = MessageHeader {
                    channel_id: ids[i % 2],
                    sequence: i as u32,
                    log_time: 1000 * i as u64,
                    publish_time: 1000 * i as u64,
                };
                w.write_to_known_channel(&header, &[i as u8; 969]).unwrap();
            }
            let metadata = records::Metadata {
                name: "wbv.test".into(),
                metadata: BTreeMap::from([("k".into(), "v".into())]),
            };
            w.write_metadata(&metadata).unwrap();
            w.attach(&mcap::Attachment {
                log_time: 5,
                create_time: 0,
                name: "a.json".into(),
                media_type: "application/json".into(),
                data: b"{}".as_slice().into(),
            })
            .unwrap();
            w.finish().unwrap();
            let bytes = w.into_inner();
            let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
            let stats = summary.stats.as_ref().unwrap();
            assert_eq!(stats.message_count, n as u64);
            assert!(stats.chunk_count >= 3, "{compression:?}: {stats:?}");
            assert_eq!(summary.chunk_indexes.len(), stats.chunk_count as usize);
            assert_eq!(summary.channels.len(), 2);
            for (i, m) in mcap::MessageStream::new(&bytes).unwrap().enumerate() {
                let m = m.unwrap();
                assert_eq!((m.sequence, m.channel.id), (i as u32, ids[i % 2]));
                assert_eq!(&*m.data, &[i as u8; 969]);
            }
            let a = mcap::read::attachment(&bytes, &summary.attachment_indexes[0]).unwrap();
            assert_eq!(&*a.data, b"{}");
            let m = mcap::read::metadata(&bytes, &summary.metadata_indexes[0]).unwrap();
            assert_eq!(m, metadata);
        }
    }
}
