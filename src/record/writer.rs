//! [`McapRecorder`]: an [`Observer`] that records every step of a run to an MCAP file.
//!
//! The simulation thread only evaluates and checks each step's values and renders the 3-D scene;
//! JSON formatting, framing and compression run on other threads (see `pipeline`), in an
//! order fixed by the step index, so the file does not depend on thread timing or count.

use super::channels;
use super::file::{self, McapWriter};
use super::interrupt;
use super::lowpass::{LowPass, decimation};
use super::meta;
use super::pipeline::{BLOCK_STEPS, Block, Channel, Encoder, Pipeline};
use super::scene::Scene;
use super::topics::{Quantity, Topic, eval, field_name, topics};
use super::{Encoding, MessageLayout, OnSignal, Provenance, RecordOptions};
use crate::error::{Error, Result};
use crate::io::atomic::{Overwrite, Partial};
use crate::simulate::observer::{Layout, Observer, Step};
use mcap::records::{MessageHeader, Metadata};
use std::path::{Path, PathBuf};

/// Formatter threads and chunk compressors: [`RecordOptions::threads`], else one per core (at
/// most 4). The file is the same for any count: blocks and chunks are written in step order, and
/// each chunk is compressed whole by one thread (`tests/record_threads.rs`).
fn threads(options: &RecordOptions) -> usize {
    options
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get().min(4)))
        .max(1)
}

/// Records a run to `<path>` (through `<path>.partial`, moved into place only once complete;
/// see [`Partial`]).
pub struct McapRecorder {
    path: PathBuf,
    partial: PathBuf,
    guard: Option<Partial>,
    provenance: Provenance,
    options: RecordOptions,
    /// The MCAP writer before `begin` (then owned by the pipeline).
    writer: Option<McapWriter>,
    pipeline: Option<Pipeline>,
    /// The block being filled on the simulation thread.
    block: Block,
    topics: Vec<(Topic, u16)>,
    /// How each topic's messages are written, in `topics` order.
    encoders: Vec<Encoder>,
    scene: Option<(Scene, u16, u16)>,
    /// The run's layout (measured channels) and the scratch for them.
    layout: Option<Layout>,
    measured: Vec<f64>,
    quantities: Vec<Quantity>,
    /// Indices of `Quantity::Time` in `quantities`: written exactly, never filtered.
    time_slots: Vec<usize>,
    values: Vec<f64>,
    lowpass: Option<LowPass>,
    every: u64,
    next_scene_frame: u64,
    last_time_ns: u64,
    results: Vec<(String, serde_json::Value)>,
    ended: bool,
    /// The file was renamed into place.
    completed: bool,
}

fn mcap_err(path: &Path) -> impl Fn(mcap::McapError) -> Error + '_ {
    move |e| Error::data(path, None, format!("MCAP write failed: {e}"))
}

impl McapRecorder {
    /// Opens `<path>.partial` for a new run; refuses an existing `path` unless
    /// `options.overwrite` allows it.
    pub fn create(path: &Path, provenance: Provenance, options: RecordOptions) -> Result<Self> {
        if options.overwrite == Overwrite::Refuse && path.exists() {
            return Err(Error::parameter(
                path.display().to_string(),
                "already exists; refusing to overwrite it (pass --force to replace it)",
            ));
        }
        options.check()?;
        if options.on_signal == OnSignal::CloseRecording {
            interrupt::install();
        }
        let (guard, file) = Partial::create(path, options.overwrite)?;
        let partial = guard.tmp().to_path_buf();
        let library = format!("wbv/{}", provenance.version);
        let writer = file::open(file, options.compression, threads(&options), library)
            .map_err(mcap_err(&partial))?;
        Ok(McapRecorder {
            path: path.to_path_buf(),
            partial,
            guard: Some(guard),
            provenance,
            options,
            writer: Some(writer),
            pipeline: None,
            block: Block::default(),
            topics: Vec::new(),
            encoders: Vec::new(),
            scene: None,
            layout: None,
            measured: Vec::new(),
            quantities: Vec::new(),
            time_slots: Vec::new(),
            values: Vec::new(),
            lowpass: None,
            every: 1,
            next_scene_frame: 0,
            last_time_ns: 0,
            results: Vec::new(),
            ended: false,
            completed: false,
        })
    }

    /// Stores analysis results under `name` (letters, digits, `_`, `-`, `.`): written at `end()` as
    /// the attachment `<name>.json` and as key `name` of the `wbv.results` metadata record.
    pub fn attach_results(&mut self, name: &str, json: &serde_json::Value) -> Result<()> {
        let ok = !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c));
        if !ok || self.results.iter().any(|(n, _)| n == name) {
            return Err(Error::parameter(
                "results name",
                format!(
                    "`{name}`: expected a new non-empty name of letters, digits, `_`, `-`, `.`"
                ),
            ));
        }
        if self.ended {
            return Err(Error::parameter("results", "the run has already ended"));
        }
        self.results.push((name.to_string(), json.clone()));
        Ok(())
    }

    /// The final path of the run.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The message layout of the time series (see [`RecordOptions::layout`]).
    fn layout_kind(&self) -> MessageLayout {
        self.options.layout.unwrap_or_default()
    }

    fn setup(&mut self, layout: &Layout) -> Result<()> {
        let partial = self.partial.clone();
        let err = mcap_err(&partial);
        let kind = self.layout_kind();
        let w = self
            .writer
            .as_mut()
            .ok_or_else(|| Error::parameter("recorder", "begin() called twice"))?;
        let fs = 1.0 / layout.dt;
        let rate = self.options.record_rate_hz.unwrap_or(fs);
        self.every = decimation(fs, rate)?;
        let batched = kind == MessageLayout::Batched;
        let topics: Vec<Topic> = (topics(layout)?.into_iter())
            .map(|t| if batched { t.timed() } else { t })
            .collect();
        self.quantities = topics.iter().flat_map(|t| t.quantities.clone()).collect();
        self.time_slots = (self.quantities.iter().enumerate())
            .filter(|(_, q)| **q == Quantity::Time)
            .map(|(i, _)| i)
            .collect();
        if self.every > 1 {
            let fc = LowPass::CUTOFF_FRACTION * rate;
            self.lowpass = Some(LowPass::new(fs, fc, self.quantities.len())?);
        }
        self.layout = Some(layout.clone());

        let mut run = meta::run_record(&self.provenance);
        let anti_alias_hz = self
            .lowpass
            .as_ref()
            .map(|_| LowPass::CUTOFF_FRACTION * rate);
        let settings = meta::Settings {
            options: &self.options,
            layout_kind: kind,
            layout,
            decimation: self.every,
            anti_alias_hz,
        };
        run.extend(settings.entries());
        let mut records = vec![(meta::RUN, run)];
        records.extend(meta::records(&self.provenance));
        for (name, metadata) in records {
            w.write_metadata(&Metadata {
                name: name.to_string(),
                metadata,
            })
            .map_err(&err)?;
        }
        w.attach(&mcap::Attachment {
            log_time: 0,
            create_time: 0,
            name: "model.toml".into(),
            media_type: "application/toml".into(),
            data: self.provenance.model_toml.as_bytes().into(),
        })
        .map_err(&err)?;

        let scene = Scene::new(layout, self.options.magnification);
        let mut sink = channels::McapSink {
            writer: w,
            err: &err,
        };
        let c = channels::add(&mut sink, layout, topics, self.options.encoding, batched)?;
        (self.topics, self.encoders) = (c.topics, c.encoders);
        self.scene = Some((scene, c.scene, c.transforms));
        let writer = self.writer.take().expect("checked above");
        let channels = (self.topics.iter().zip(&self.encoders))
            .map(|((_, id), template)| Channel {
                template: template.clone(),
                id: *id,
            })
            .collect();
        self.pipeline = Some(Pipeline::spawn(writer, channels, threads(&self.options)));
        Ok(())
    }

    /// Hands the filled block to the pipeline.
    fn send_block(&mut self) -> Result<()> {
        let p = self.pipeline.as_mut().expect("recording");
        let block = std::mem::replace(&mut self.block, p.empty_block());
        if !p.send(block) {
            // The writer thread stopped on an error: collect it.
            return Err(self.stop().err().unwrap_or_else(|| {
                Error::data(&self.partial, None, "MCAP writer stopped unexpectedly")
            }));
        }
        Ok(())
    }

    /// Stops the pipeline threads and returns the writer.
    fn stop(&mut self) -> Result<McapWriter> {
        let p = self
            .pipeline
            .take()
            .ok_or_else(|| Error::parameter("recorder", "not recording"))?;
        match p.finish() {
            Ok(Ok(w)) => Ok(w),
            Ok(Err(failed)) => {
                let (w, e) = *failed;
                self.writer = Some(w);
                Err(mcap_err(&self.partial)(e))
            }
            Err(_) => Err(Error::data(
                &self.partial,
                None,
                "MCAP recording thread panicked",
            )),
        }
    }

    fn record(&mut self, s: &Step<'_>) -> Result<()> {
        if let Some(l) = &self.layout {
            l.measured(s, &mut self.measured);
        }
        eval(&self.quantities, s, &self.measured, &mut self.values);
        if let Some(i) = self.values.iter().position(|v| !v.is_finite()) {
            return Err(self.non_finite(s, i));
        }
        if let Some(lp) = self.lowpass.as_mut() {
            lp.process(&mut self.values);
        }
        if !s.index.is_multiple_of(self.every) {
            return Ok(());
        }
        let sequence = u32::try_from(s.index).map_err(|_| {
            Error::parameter("steps", "more than 2³² steps cannot be numbered in MCAP")
        })?;
        let time_ns = (s.t * 1e9).round() as u64;
        for &i in &self.time_slots {
            self.values[i] = s.t; // time is exact, never filtered
        }
        // Finite before filtering stays finite through a stable low-pass.
        self.block.push(&self.values, sequence, time_ns);
        self.last_time_ns = time_ns;
        Ok(())
    }

    fn non_finite(&self, s: &Step<'_>, i: usize) -> Error {
        Error::parameter(
            field_name(&self.topics, i),
            format!(
                "is not finite at step {} (t = {:.6} s); refusing to record NaN or infinity",
                s.index, s.t
            ),
        )
    }

    fn record_scene(&mut self, s: &Step<'_>) -> Result<()> {
        let Some(sequence) =
            super::scene::frame_due(&mut self.next_scene_frame, self.options.scene_rate_hz, s.t)
        else {
            return Ok(());
        };
        let time_ns = (s.t * 1e9).round() as u64;
        let (scene, scene_id, tf_id) = self.scene.as_ref().expect("recording");
        let b = &mut self.block;
        type Render = fn(&Scene, &Step<'_>, &mut Vec<u8>);
        let (update, transforms): (Render, Render) = match self.options.encoding {
            Encoding::Json => (Scene::scene_update, Scene::frame_transforms),
            Encoding::Protobuf => (Scene::scene_update_pb, Scene::frame_transforms_pb),
        };
        for (channel_id, render) in [(*scene_id, update), (*tf_id, transforms)] {
            render(scene, s, &mut b.extra);
            let header = MessageHeader {
                channel_id,
                sequence,
                log_time: time_ns,
                publish_time: time_ns,
            };
            b.extra_messages
                .push((header, b.steps.len(), b.extra.len()));
        }
        self.last_time_ns = self.last_time_ns.max(time_ns);
        Ok(())
    }

    /// Completes the file and moves it into place: at `path`, or, for a run interrupted after
    /// the step at `interrupted_at` s, at [`interrupted_path`] with a `wbv.interrupted` record.
    fn finish(&mut self, interrupted_at: Option<f64>) -> Result<PathBuf> {
        if !self.block.is_empty() {
            self.send_block()?;
        }
        let mut w = self.stop()?;
        let err = mcap_err(&self.partial);
        meta::write_results(&mut w, &self.results, self.last_time_ns).map_err(&err)?;
        if let Some(t) = interrupted_at {
            w.write_metadata(&interrupt::record(t)).map_err(&err)?;
        }
        w.finish().map_err(&err)?;
        let file = w
            .into_inner()
            .into_inner()
            .map_err(|e| Error::io(&self.partial, e.into_error()))?
            .into_file();
        let guard = self
            .guard
            .take()
            .expect("the partial file is held until finished");
        let dest = match interrupted_at {
            None => self.path.clone(),
            Some(_) => interrupt::interrupted_path(&self.path),
        };
        // An interrupted recording replaces an earlier interrupted one: it is the latest state.
        let overwrite = match interrupted_at {
            None => self.options.overwrite,
            Some(_) => Overwrite::Allow,
        };
        guard.commit_as(file, &dest, overwrite)?;
        self.completed = true;
        Ok(dest)
    }

    /// Closes the recording of an interrupted run; the error that stops the run.
    fn interrupt(&mut self, t: f64) -> Error {
        self.ended = true;
        let what = match self.finish(Some(t)) {
            Ok(p) => format!("the run up to then is recorded in {}", p.display()),
            Err(e) => format!("the recording could not be closed: {e}"),
        };
        Error::parameter(
            "run",
            format!("interrupted by a signal at t = {t:.3} s; {what}"),
        )
    }
}

impl Observer for McapRecorder {
    fn begin(&mut self, layout: &Layout) -> Result<()> {
        self.setup(layout)
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        if self.pipeline.is_none() {
            return Err(Error::parameter("recorder", "step() outside begin()/end()"));
        }
        self.record(step)?;
        self.record_scene(step)?;
        // A host that keeps its own handlers (Python) stops the run through the library's
        // cancellation check instead, and the unfinished recording is removed.
        if self.options.on_signal == OnSignal::CloseRecording
            && step.index.is_multiple_of(interrupt::CHECK_STEPS)
            && interrupt::requested()
        {
            return Err(self.interrupt(step.t));
        }
        if self.block.steps.len() >= BLOCK_STEPS {
            self.send_block()?;
        }
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        if self.ended || self.pipeline.is_none() {
            return Err(Error::parameter(
                "recorder",
                "end() without a recording in progress",
            ));
        }
        self.ended = true;
        self.finish(None).map(|_| ())
    }
}

impl Drop for McapRecorder {
    /// A run that did not end successfully leaves no file that looks complete: the writer is
    /// abandoned without writing its summary and the partial file is removed.
    fn drop(&mut self) {
        if self.completed {
            return;
        }
        if self.pipeline.is_some()
            && let Ok(w) = self.stop()
        {
            self.writer = Some(w);
        }
        if let Some(w) = self.writer.take() {
            drop(w.into_inner());
        }
        // Dropping the guard removes the partial file.
        self.guard.take();
    }
}
