//! Every simulation run recorded to MCAP (<https://mcap.dev/spec>), readable by Foxglove, Lichtblick,
//! PlotJuggler and Rerun, and read back by [`read_run`] so that a recorded run stands in for a
//! measurement.
//!
//! Encoding ([`Encoding`]): **protobuf** by default — schema encoding `protobuf`, a serialized
//! `FileDescriptorSet` in each schema record, fully qualified names: `wbv.Measured`, `wbv.State`,
//! `wbv.Links` of `proto/wbv.proto` (see [`proto`]) and the Foxglove SDK's `foxglove.SceneUpdate`
//! / `foxglove.FrameTransforms`; 8 bytes per f64, so a run reads back bit-identically at a fraction
//! of the JSON cost. `--encoding json`: `json` messages with a `jsonschema` schema (PlotJuggler skips
//! schemaless channels and Lichtblick only parses single-`type` JSON-schema properties), as before.
//! The field paths are the same in both (`/wbv/state.head.a_abs`).
//!
//! | topic | content (SI units) |
//! |---|---|
//! | `/wbv/measured` | `t`, `a_base_z`, `a_seat_z`, `a_head_z`, `f_seat_z`: the measured-run channel names |
//! | `/wbv/state` | per mass: `x`, `v`, `a` relative to the base and `x_abs`, `v_abs`, `a_abs` |
//! | `/wbv/links` | per link: `force` (N, tension positive); cushion and suspension links also `deflection` (m) |
//! | `/wbv/scene` | `foxglove.SceneUpdate`, 3-D replay at the scene rate, displacements magnified |
//!
//! Every value is recorded once (but the measured-run names, see `topics.rs`): the
//! base motion is `a_base_z` (its integrals are `x_abs − x` of any mass), a body link's
//! deflection is the difference of two `/wbv/state` displacements, and only `/wbv/measured`
//! carries `t`. Floats are written at full precision (protobuf `double`, or the shortest round-trip
//! text in JSON), so a run reads back bit-identically; see `benches/record.rs` for the costs.
//!
//! Time: `log_time = publish_time = round(t·1e9)` ns from 0 (Foxglove plays by log time, PlotJuggler
//! plots publish time), `sequence` = step index. No wall-clock time is written anywhere, so the same
//! inputs give a byte-identical file, wherever it is written: the stored command line is normalised
//! (program `wbv`, no `--out`/`--csv`/`--force`). Provenance is stored in metadata records
//! (`wbv.run`, `wbv.model`, `wbv.excitation` with a definition that loads again) and the exact model
//! TOML as an attachment; `wbv simulate --from RUN` re-runs it byte for byte. Analysis results given
//! to [`McapRecorder::attach_results`] go to `wbv.results` metadata and `<name>.json` attachments.
//! SIGINT/SIGTERM close what was simulated as `run.interrupted.mcap` (metadata `wbv.interrupted`)
//! unless the host process keeps its own handlers ([`OnSignal`]).
//! With the feature `live`, [`live::LiveView`] streams the same channels to Foxglove or Lichtblick
//! over the Foxglove WebSocket protocol while a run is simulated (`wbv simulate --serve`).

mod channels;
mod chunks;
pub mod csv;
pub mod demo;
mod file;
mod interrupt;
mod json;
#[cfg(feature = "live")]
pub mod live;
mod lowpass;
mod meta;
mod pipeline;
pub mod proto;
mod reader;
mod scene;
mod topics;
pub mod viewer;
mod writer;

pub use json::check_lichtblick_subset;
pub use lowpass::LowPass;
pub use meta::{excitation_definition, load_excitation};
pub use reader::{RecordedRun, RunSummary, TopicSummary, inspect, read_provenance, read_run};
pub use writer::McapRecorder;

pub use crate::io::atomic::Overwrite;

/// File name of the recording inside a run directory (`runs/<name>/run.mcap`).
pub const RUN_FILE: &str = "run.mcap";

/// The MCAP file a path names: a run directory stands for its [`RUN_FILE`], a file for itself.
pub fn run_file(path: &std::path::Path) -> std::path::PathBuf {
    if path.is_dir() {
        path.join(RUN_FILE)
    } else {
        path.to_path_buf()
    }
}

/// Chunk compression of the MCAP file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Compression {
    /// Zstandard (level -1 with 4-byte matches, see `chunks.rs`), the default: the smallest
    /// file for the CPU time (see `benches/record.rs`).
    Zstd,
    /// LZ4 frames.
    Lz4,
    /// No compression (largest files, fastest to write).
    None,
}

impl Compression {
    /// Parses `zstd`, `lz4` or `none`.
    pub fn parse(s: &str) -> crate::Result<Self> {
        match s {
            "zstd" => Ok(Compression::Zstd),
            "lz4" => Ok(Compression::Lz4),
            "none" => Ok(Compression::None),
            _ => Err(crate::Error::parameter(
                "compression",
                format!("`{s}` is not one of zstd, lz4, none"),
            )),
        }
    }

    /// The name used on the command line and in the metadata.
    pub fn as_str(&self) -> &'static str {
        match self {
            Compression::Zstd => "zstd",
            Compression::Lz4 => "lz4",
            Compression::None => "none",
        }
    }
}

/// Message encoding of every channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Encoding {
    /// Protobuf (`proto/wbv.proto`; the scene as the Foxglove SDK's `foxglove.*` types): schema
    /// encoding `protobuf` with a serialized `FileDescriptorSet`, fully qualified names. The
    /// default: 8 bytes per f64 instead of ≈ 20 characters, decoded without plug-ins by
    /// Foxglove, Lichtblick, PlotJuggler and Rerun.
    #[default]
    Protobuf,
    /// JSON messages with a `jsonschema` schema: text, readable anywhere.
    Json,
}

impl Encoding {
    /// Parses `protobuf` or `json`.
    pub fn parse(s: &str) -> crate::Result<Self> {
        match s {
            "protobuf" => Ok(Encoding::Protobuf),
            "json" => Ok(Encoding::Json),
            _ => Err(crate::Error::parameter(
                "encoding",
                format!("`{s}` is not one of protobuf, json"),
            )),
        }
    }

    /// The name used on the command line and in the metadata (= the MCAP message encoding).
    pub fn as_str(&self) -> &'static str {
        match self {
            Encoding::Protobuf => "protobuf",
            Encoding::Json => "json",
        }
    }
}

/// How the time-series topics (`/wbv/measured`, `/wbv/state`, `/wbv/links`) are cut into
/// messages. The 3-D scene is one message per frame in both.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MessageLayout {
    /// One message per topic per recorded sample (`wbv.Measured`, `wbv.State`, `wbv.Links`):
    /// every field a time series in every viewer (`/wbv/state.head.a_abs`) without configuration,
    /// so it is the default. Three MCAP messages per step (README, "Speed" for the cost).
    #[default]
    PerSample,
    /// One message per topic per block of up to [`BATCH_SAMPLES`] samples with a packed array per
    /// field (`wbv.MeasuredBatch`, `wbv.StateBatch`, `wbv.LinksBatch`; protobuf only): a
    /// thousandth of the messages, the smallest and fastest record. Viewers see arrays
    /// (`/wbv/state.head.a_abs[:]`, against `/wbv/state.t[:]`); every wbv command reads it.
    Batched,
}

/// Samples per message of the batched layout (the recorder's block of steps).
pub const BATCH_SAMPLES: usize = pipeline::BLOCK_STEPS;

impl MessageLayout {
    /// Parses `per-sample` or `batched`.
    pub fn parse(s: &str) -> crate::Result<Self> {
        match s {
            "per-sample" => Ok(MessageLayout::PerSample),
            "batched" => Ok(MessageLayout::Batched),
            _ => Err(crate::Error::parameter(
                "layout",
                format!("`{s}` is not one of batched, per-sample"),
            )),
        }
    }

    /// The name used on the command line and in the metadata.
    pub fn as_str(&self) -> &'static str {
        match self {
            MessageLayout::PerSample => "per-sample",
            MessageLayout::Batched => "batched",
        }
    }
}

/// How a run is recorded.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordOptions {
    /// Message encoding of every channel.
    pub encoding: Encoding,
    /// Chunk compression.
    pub compression: Compression,
    /// Message layout of the time series; `None`: the default ([`MessageLayout::PerSample`]).
    /// `Batched` is protobuf only.
    pub layout: Option<MessageLayout>,
    /// Rate of the time-series topics in Hz; `None` records every step. A lower rate must divide
    /// the simulation rate `1/dt` by an integer `N`; the signals then pass a 4th-order Butterworth
    /// low-pass at [`LowPass::CUTOFF_FRACTION`]` · record_rate_hz` before keeping every `N`-th step,
    /// so that nothing above the new Nyquist frequency aliases into the record.
    pub record_rate_hz: Option<f64>,
    /// Rate of the 3-D scene in Hz (30–60): a video rate is enough to watch the motion.
    pub scene_rate_hz: f64,
    /// Factor by which displacements are magnified in the 3-D scene only (vibration amplitudes are
    /// millimetres); stated in the scene and in the `wbv.run` metadata. Recorded signals are never
    /// scaled.
    pub magnification: f64,
    /// Whether an existing file may be replaced.
    pub overwrite: Overwrite,
    /// Threads that format messages, and that compress chunks; `None`: one per core, at most 4.
    /// The file does not depend on it.
    pub threads: Option<usize>,
    /// What SIGINT and SIGTERM do while the run is recorded.
    pub on_signal: OnSignal,
}

/// What SIGINT and SIGTERM do to a recording in progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OnSignal {
    /// wbv's handlers (installed by the first such recorder of the process) close the recording
    /// as `run.interrupted.mcap` and stop the run; a second signal ends the process. For the
    /// `wbv` command, which owns its process.
    CloseRecording,
    /// The process keeps its own handlers: a host such as the Python interpreter, where Ctrl-C
    /// raises `KeyboardInterrupt` and the binding stops the run itself (an observer that returns
    /// an error), so the recording is dropped unfinished and no file appears.
    LeaveToHost,
}

impl RecordOptions {
    /// Checks the options that do not depend on the run (rates, factors, combinations).
    pub fn check(&self) -> crate::error::Result<()> {
        if !(15.0..=120.0).contains(&self.scene_rate_hz) {
            return Err(crate::Error::parameter(
                "scene rate",
                format!(
                    "{} Hz: expected 15–120 Hz (30–60 is typical)",
                    self.scene_rate_hz
                ),
            ));
        }
        if !(self.magnification.is_finite() && self.magnification > 0.0) {
            return Err(crate::Error::parameter(
                "display magnification",
                format!("{}: expected a positive factor", self.magnification),
            ));
        }
        if self.encoding == Encoding::Json && self.layout == Some(MessageLayout::Batched) {
            return Err(crate::Error::parameter(
                "layout",
                "`batched` is protobuf only: JSON runs are recorded per sample (drop --layout \
             or record with --encoding protobuf)",
            ));
        }
        Ok(())
    }
}

impl Default for RecordOptions {
    fn default() -> Self {
        RecordOptions {
            encoding: Encoding::Protobuf,
            compression: Compression::Zstd,
            layout: None,
            record_rate_hz: None,
            scene_rate_hz: 30.0,
            magnification: 20.0,
            overwrite: Overwrite::Refuse,
            threads: None,
            on_signal: OnSignal::CloseRecording,
        }
    }
}

/// Where a run came from: everything needed to reproduce it, stored in the file's metadata.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Provenance {
    /// Model name (catalogue name or path).
    pub model: String,
    /// The exact model TOML text that was simulated.
    pub model_toml: String,
    /// One-line description of the excitation.
    pub excitation: String,
    /// The excitation definition in the TOML format of `excitations/*.toml`
    /// ([`excitation_definition`]), loaded again by [`load_excitation`].
    pub excitation_definition: String,
    /// Where the excitation came from: a built-in name, a file path or `command line`.
    pub excitation_origin: String,
    /// Integrator name, e.g. `newmark`.
    pub integrator: String,
    /// Integration step in s.
    pub dt: f64,
    /// Random seed, if the excitation is random.
    pub seed: Option<u64>,
    /// Simulated duration in s.
    pub duration: f64,
    /// wbv version that wrote the run (`env!("CARGO_PKG_VERSION")`).
    pub version: String,
    /// The command line that produced the run, normalised so that it does not depend on where
    /// the run was written or from where wbv was started: program name `wbv`, no `--out` and
    /// no `--force` (see `cli::simulate::command_line`).
    pub command_line: String,
}

impl Provenance {
    /// A provenance with the running wbv version filled in.
    pub fn new() -> Self {
        Provenance {
            version: env!("CARGO_PKG_VERSION").to_string(),
            ..Provenance::default()
        }
    }
}
