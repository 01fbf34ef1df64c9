//! The one bounded MCAP record stream: every record of a file held in memory, inside chunks too, in
//! file order, with every record length bounded so that corrupt or hostile bytes give an error, never
//! a huge allocation. Both MCAP readers use it: another logger's topic (`io::input::mcap_topic`) and
//! wbv's own runs (`record::reader`).
//!
//! Written over `mcap::sans_io::LinearReader` instead of `mcap::MessageStream` because that stream
//! sets no record-length limit inside chunks (mcap 0.26), so a corrupt length in a compressed chunk
//! makes it allocate the stated size and abort the process (found by fuzzing).

use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};

/// Largest ratio of a chunk's stated uncompressed size to its compressed size that is believed
/// (zstd and lz4 stay far below it on sensor data); a larger one is a corrupt or hostile header,
/// refused before the `mcap` crate would allocate its stated size.
const MAX_CHUNK_RATIO: u64 = 1024;

/// Checks every chunk's stated uncompressed size against its data before the messages are read;
/// returns the largest believed record length (bytes) for [`Records::new`].
pub fn check_chunks(bytes: &[u8]) -> std::result::Result<usize, String> {
    let reader = mcap::read::LinearReader::new(bytes).map_err(|e| e.to_string())?;
    let mut largest = bytes.len();
    for rec in reader {
        match rec {
            Ok(mcap::records::Record::Chunk { header, data }) => {
                let stated = header.uncompressed_size;
                let limit = (data.len() as u64)
                    .saturating_mul(MAX_CHUNK_RATIO)
                    .max(1 << 20);
                if stated > limit {
                    return Err(format!(
                        "a chunk states {stated} bytes uncompressed from {} bytes",
                        data.len()
                    ));
                }
                largest = largest.max(usize::try_from(stated).unwrap_or(usize::MAX));
            }
            Ok(_) => {}
            Err(e) => return Err(e.to_string()),
        }
    }
    Ok(largest)
}

/// The records of an MCAP file with every record — inside chunks too — bounded to `record_limit`
/// bytes.
pub struct Records<'a> {
    buf: &'a [u8],
    reader: LinearReader,
}

impl<'a> Records<'a> {
    /// The records of `buf`, none longer than `record_limit` bytes.
    pub fn new(buf: &'a [u8], record_limit: usize) -> Self {
        Self::with_options(buf, record_limit, false)
    }

    /// [`Records::new`] that also checks every chunk's CRC before any record of the chunk is
    /// parsed, and the data section's CRC.
    pub fn with_crcs(buf: &'a [u8], record_limit: usize) -> Self {
        Self::with_options(buf, record_limit, true)
    }

    fn with_options(buf: &'a [u8], record_limit: usize, crcs: bool) -> Self {
        let options = LinearReaderOptions::default().with_record_length_limit(record_limit);
        let options = if crcs {
            options
                .with_prevalidate_chunk_crcs(true)
                .with_validate_data_section_crc(true)
        } else {
            options
        };
        Records {
            buf,
            reader: LinearReader::new_with_options(options),
        }
    }

    /// Reads on to the next record that `take` takes: `take(opcode, body)` is called with each
    /// record in turn until it returns `Some`, which is returned; `None` at the end of the file.
    /// (A callback rather than an iterator of borrowed records: the body lives in the reader's
    /// buffer, which the next read overwrites.)
    pub fn next_taken<T>(
        &mut self,
        mut take: impl FnMut(u8, &[u8]) -> Option<T>,
    ) -> Option<std::result::Result<T, mcap::McapError>> {
        loop {
            match self.reader.next_event()? {
                Err(e) => return Some(Err(e)),
                Ok(LinearReadEvent::ReadRequest(need)) => {
                    let len = need.min(self.buf.len());
                    self.reader.insert(len).copy_from_slice(&self.buf[..len]);
                    self.reader.notify_read(len);
                    self.buf = &self.buf[len..];
                }
                Ok(LinearReadEvent::Record { data, opcode }) => {
                    if let Some(t) = take(opcode, data) {
                        return Some(Ok(t));
                    }
                }
            }
        }
    }
}
