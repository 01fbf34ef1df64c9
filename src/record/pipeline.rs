//! The recording pipeline behind [`McapRecorder`](super::McapRecorder): the simulation thread
//! collects the values of each step into [`Block`]s, formatter threads render blocks into JSON
//! messages in parallel, and one writer thread hands the messages to the MCAP writer (`chunks`,
//! which frames them into chunks and compresses each chunk whole on its compressor threads).
//!
//! Block `i` always goes to formatter `i mod n` and the writer takes the rendered batches in the
//! same round-robin order, so the message order — and the file — depends neither on thread timing
//! nor on the number of formatters. Buffers travel back to where they are filled, so a long run
//! reuses the same few megabytes instead of faulting in fresh pages.

use super::file::McapWriter;
use super::json::Template;
use super::proto::{BatchTemplate, ProtoTemplate};
use mcap::records::MessageHeader;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, SyncSender, channel, sync_channel};
use std::thread::JoinHandle;

/// What the writer thread returns: the writer, or the writer with the error that stopped it.
pub type WriterResult = std::result::Result<McapWriter, Box<(McapWriter, mcap::McapError)>>;

/// How a time-series message is written from its values.
#[derive(Debug, Clone)]
pub enum Encoder {
    Json(Template),
    Protobuf(ProtoTemplate),
    /// One message per block (`--layout batched`).
    Batched(BatchTemplate),
}

impl Encoder {
    /// Number of values a message takes.
    pub fn len(&self) -> usize {
        match self {
            Encoder::Json(t) => t.len(),
            Encoder::Protobuf(t) => t.len(),
            Encoder::Batched(t) => t.len(),
        }
    }

    /// Appends the message of finite `values`.
    pub(super) fn render(&self, values: &[f64], out: &mut Vec<u8>) {
        match self {
            Encoder::Json(t) => t.render_finite(values, out),
            Encoder::Protobuf(t) => t.render(values, out),
            Encoder::Batched(_) => unreachable!("batched channels are rendered per block"),
        }
    }
}

/// Steps per block: about 1.5 MB of JSON for a 6-mass model, enough to amortise the hand-overs.
pub const BLOCK_STEPS: usize = 1024;

/// Blocks queued before the formatters and after them, over all formatters: about one 8 MiB
/// chunk of the default scenario (≈ 24 blocks), so that the simulation keeps going while the
/// writer thread waits for zstd to finish a chunk. Measured on the default hour (idle, separate
/// runs alternated): 2 per formatter 4.5 s mean wall (10 runs), 16–32 per formatter 4.0 s (13
/// runs), for ≈ 24 MB more memory.
const QUEUE_BLOCKS: usize = 32;

/// Distance between two columns of a [`Block`]: a cache line more than a column, so that the
/// values of one step, written one per column, fall into different cache sets (8 KiB apart,
/// they all map to the same set and evict each other: this store was 6 % of a run's CPU).
const COLUMN: usize = BLOCK_STEPS + 8;

/// One time-series topic as the formatters see it.
#[derive(Debug, Clone)]
pub struct Channel {
    pub template: Encoder,
    pub id: u16,
}

/// The values of up to [`BLOCK_STEPS`] recorded steps, and messages rendered on the simulation
/// thread (the 3-D scene) that follow a step.
#[derive(Default)]
pub struct Block {
    /// Column-major: value `j` of step `k` (the values of every channel's template, channel after
    /// channel) at `j * COLUMN + k`, so that a batched message copies each field's samples from
    /// one contiguous run (gathering them from rows was 10 % of a batched run's CPU).
    values: Vec<f64>,
    /// Per step: sequence number and log time in ns.
    pub steps: Vec<(u32, u64)>,
    /// Pre-rendered messages: header, number of steps they follow (the length of `steps` when
    /// they were added) and end offset in `extra`.
    pub extra_messages: Vec<(MessageHeader, usize, usize)>,
    pub extra: Vec<u8>,
}

impl Block {
    /// Adds a step's `values` (the same number every step), numbered `sequence`, at `time_ns`.
    pub fn push(&mut self, values: &[f64], sequence: u32, time_ns: u64) {
        let k = self.steps.len();
        assert!(k < BLOCK_STEPS, "a full block is sent before the next step");
        if self.values.len() != values.len() * COLUMN {
            self.values.clear();
            self.values.resize(values.len() * COLUMN, 0.0);
        }
        for (column, &v) in self.values.chunks_exact_mut(COLUMN).zip(values) {
            column[k] = v;
        }
        self.steps.push((sequence, time_ns));
    }

    /// Value `j` of every step, in step order.
    fn column(&self, j: usize) -> &[f64] {
        &self.values[j * COLUMN..][..self.steps.len()]
    }

    /// Empties the block; its buffers are kept for the next one.
    fn clear(&mut self) {
        self.steps.clear();
        self.extra_messages.clear();
        self.extra.clear();
    }

    pub fn is_empty(&self) -> bool {
        self.steps.is_empty() && self.extra_messages.is_empty()
    }
}

/// Rendered messages in file order.
#[derive(Default)]
struct Batch {
    data: Vec<u8>,
    /// Header and end offset in `data` of each message (the start is the previous end).
    messages: Vec<(MessageHeader, usize)>,
    /// The values of one step's message (per-sample layouts), gathered from the block.
    row: Vec<f64>,
}

impl Batch {
    fn push(&mut self, channel_id: u16, sequence: u32, time_ns: u64) {
        let header = MessageHeader {
            channel_id,
            sequence,
            log_time: time_ns,
            publish_time: time_ns,
        };
        self.messages.push((header, self.data.len()));
    }

    /// Renders `block`: per step its channels in order, each pre-rendered message right after the
    /// step it follows; batched channels as one message each, stamped with the block's first
    /// step, before the block's first step.
    fn render(&mut self, channels: &[Channel], block: &Block) {
        self.data.clear();
        self.messages.clear();
        let mut extra = block.extra_messages.iter().peekable();
        let mut extra_start = 0;
        for k in 0..=block.steps.len() {
            while let Some(&&(header, _, end)) = extra.peek().filter(|e| e.1 == k) {
                self.data.extend_from_slice(&block.extra[extra_start..end]);
                self.messages.push((header, self.data.len()));
                extra_start = end;
                extra.next();
            }
            let Some(&(sequence, time_ns)) = block.steps.get(k) else {
                break;
            };
            let mut offset = 0;
            for c in channels {
                let n = c.template.len();
                match &c.template {
                    Encoder::Batched(t) if k == 0 => {
                        t.render(|j| block.column(offset + j), &mut self.data);
                        self.push(c.id, sequence, time_ns);
                    }
                    Encoder::Batched(_) => {}
                    t => {
                        self.row.clear();
                        (self.row).extend((offset..offset + n).map(|j| block.column(j)[k]));
                        t.render(&self.row, &mut self.data);
                        self.push(c.id, sequence, time_ns);
                    }
                }
                offset += n;
            }
        }
    }
}

/// The running threads; dropping the senders ends them in order.
pub struct Pipeline {
    to_format: Vec<SyncSender<Block>>,
    recycled: Receiver<Block>,
    next: usize,
    formatters: Vec<JoinHandle<()>>,
    writer: JoinHandle<WriterResult>,
}

impl Pipeline {
    /// Starts `formatters` formatter threads (at least one) and the writer thread.
    pub fn spawn(writer: McapWriter, channels: Vec<Channel>, formatters: usize) -> Self {
        let channels = Arc::new(channels);
        let (recycle_block, recycled) = channel::<Block>();
        let mut to_format = Vec::new();
        let mut from_format = Vec::new();
        let mut batch_returns = Vec::new();
        let mut handles = Vec::new();
        let formatters = formatters.max(1);
        let depth = (QUEUE_BLOCKS / formatters).max(2);
        for _ in 0..formatters {
            let (tx_block, rx_block) = sync_channel::<Block>(depth);
            let (tx_batch, rx_batch) = sync_channel::<Batch>(depth);
            let (tx_return, rx_return) = channel::<Batch>();
            let channels = Arc::clone(&channels);
            let recycle_block = recycle_block.clone();
            handles.push(std::thread::spawn(move || {
                for mut block in rx_block {
                    let mut batch = rx_return.try_recv().unwrap_or_default();
                    batch.render(&channels, &block);
                    if tx_batch.send(batch).is_err() {
                        return; // the writer stopped on an error
                    }
                    block.clear();
                    let _ = recycle_block.send(block);
                }
            }));
            to_format.push(tx_block);
            from_format.push(rx_batch);
            batch_returns.push(tx_return);
        }
        let writer = std::thread::spawn(move || write_batches(writer, from_format, batch_returns));
        Pipeline {
            to_format,
            recycled,
            next: 0,
            formatters: handles,
            writer,
        }
    }

    /// An empty block to fill, reusing a returned one when there is one.
    pub fn empty_block(&self) -> Block {
        self.recycled.try_recv().unwrap_or_default()
    }

    /// Hands `block` to the next formatter; `false` when the pipeline stopped on an error.
    pub fn send(&mut self, block: Block) -> bool {
        let k = self.next % self.to_format.len();
        self.next += 1;
        self.to_format[k].send(block).is_ok()
    }

    /// Waits for every block sent to be written and returns the writer. If a thread panicked,
    /// the writer is abandoned without its summary (a file that cannot look complete).
    pub fn finish(self) -> std::thread::Result<WriterResult> {
        drop(self.to_format);
        let mut panicked = None;
        for h in self.formatters {
            if let Err(e) = h.join() {
                panicked.get_or_insert(e);
            }
        }
        let written = self.writer.join();
        match (panicked, written) {
            (None, written) => written,
            (Some(e), Ok(Ok(w))) => {
                drop(w.into_inner());
                Err(e)
            }
            (Some(e), _) => Err(e),
        }
    }
}

/// The writer thread: batches in round-robin order until the formatter due next has finished.
fn write_batches(
    mut writer: McapWriter,
    from_format: Vec<Receiver<Batch>>,
    batch_returns: Vec<Sender<Batch>>,
) -> WriterResult {
    for k in (0..from_format.len()).cycle() {
        let Ok(batch) = from_format[k].recv() else {
            break;
        };
        let mut start = 0;
        for (header, end) in &batch.messages {
            if let Err(e) = writer.write_to_known_channel(header, &batch.data[start..*end]) {
                return Err(Box::new((writer, e)));
            }
            start = *end;
        }
        let _ = batch_returns[k].send(batch);
    }
    Ok(writer)
}
