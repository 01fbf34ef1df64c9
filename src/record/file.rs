//! The run file under the MCAP writer (`chunks`): its early write-back to the disk, and the
//! channels' schemas.

use super::Compression;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};

pub type McapWriter = super::chunks::McapWriter<BufWriter<RunFile>>;

/// Bytes written between two write-back requests of [`RunFile`].
const WRITEBACK_BYTES: u64 = 32 << 20;

/// The run file under the MCAP writer. Every [`WRITEBACK_BYTES`] written it asks the kernel to
/// start writing them to the disk (Linux `sync_file_range(…, SYNC_FILE_RANGE_WRITE)`, which
/// queues the dirty pages and does not wait for them), so that the disk works while the run is
/// simulated. Without it the kernel keeps a recorded hour (≈ 1.1 GB) in the page cache until the
/// `fsync` that commits the finished file (`io::atomic`), and that `fsync` alone waited 1.9 s for
/// the disk (≈ 230 MB/s) after the run; with it, 0.26 s. Durability is unchanged: the `fsync`
/// still runs and reports any write error; the request is a hint whose failure is ignored. (The
/// chunk headers the mcap writer patches after a chunk may be rewritten after their page went to
/// the disk; the `fsync` writes them again.)
pub struct RunFile {
    file: File,
    /// Current position and end of what was written (the writer seeks back to patch headers).
    position: u64,
    end: u64,
    /// Everything before this offset has been handed to the disk.
    requested: u64,
}

impl RunFile {
    pub fn new(file: File) -> Self {
        RunFile {
            file,
            position: 0,
            end: 0,
            requested: 0,
        }
    }

    /// The file, to be committed.
    pub fn into_file(self) -> File {
        self.file
    }

    #[cfg(target_os = "linux")]
    fn start_writeback(&self, offset: u64, len: u64) {
        use std::os::fd::AsRawFd;
        let (Ok(offset), Ok(len)) = (i64::try_from(offset), i64::try_from(len)) else {
            return;
        };
        // SAFETY: a plain system call on a file descriptor this struct owns; no memory is
        // passed. Its result is ignored on purpose (see the type's docs).
        unsafe {
            libc::sync_file_range(
                self.file.as_raw_fd(),
                offset,
                len,
                libc::SYNC_FILE_RANGE_WRITE,
            );
        }
    }

    #[cfg(not(target_os = "linux"))]
    fn start_writeback(&self, _offset: u64, _len: u64) {}
}

impl Write for RunFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.file.write(buf)?;
        self.position += n as u64;
        self.end = self.end.max(self.position);
        if self.end - self.requested >= WRITEBACK_BYTES {
            self.start_writeback(self.requested, self.end - self.requested);
            self.requested = self.end;
        }
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

impl Seek for RunFile {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        self.position = self.file.seek(pos)?;
        Ok(self.position)
    }
}

/// Opens the MCAP writer of `file`: chunked, compressed on `threads` threads, with message
/// indexes, chunk indexes and summary.
pub fn open(
    file: File,
    compression: Compression,
    threads: usize,
    library: String,
) -> mcap::McapResult<McapWriter> {
    let out = BufWriter::with_capacity(1 << 20, RunFile::new(file));
    McapWriter::new(out, compression, threads, library)
}

/// Adds a `json` channel on `topic` with its `jsonschema` schema; returns the channel id.
pub fn json_channel(
    w: &mut McapWriter,
    topic: &str,
    schema_name: &str,
    schema: &[u8],
) -> mcap::McapResult<u16> {
    let sid = w.add_schema(schema_name, "jsonschema", schema)?;
    w.add_channel(sid, topic, "json", &BTreeMap::new())
}

/// Adds a `protobuf` channel on `topic` whose schema is the message `schema_name` (fully
/// qualified) of the serialized `FileDescriptorSet` `descriptor`; returns the channel id.
pub fn protobuf_channel(
    w: &mut McapWriter,
    topic: &str,
    schema_name: &str,
    descriptor: &[u8],
) -> mcap::McapResult<u16> {
    let sid = w.add_schema(schema_name, "protobuf", descriptor)?;
    w.add_channel(sid, topic, "protobuf", &BTreeMap::new())
}
