//! [`McapRecorder`]: an [`Observer`] that records every step of a run to an MCAP file.
//!
//! The simulation thread only evaluates and checks each step's values and renders the 3-D scene;
//! JSON formatting, framing and compression run on other threads (see [`super::pipeline`]), in an
//! order fixed by the step index, so the file does not depend on thread timing or count.

use super::lowpass::{LowPass, decimation};
use super::meta;
use super::pipeline::{self, BLOCK_STEPS, Block, Channel, McapWriter, Pipeline, json_channel};
use super::scene::{FRAME_TRANSFORMS_SCHEMA, SCENE_UPDATE_SCHEMA, Scene};
use super::topics::{Quantity, Topic, channel_name, eval, topics};
use super::{Provenance, RecordOptions};
use crate::error::{Error, Result};
use crate::io::atomic::{Overwrite, partial_path};
use crate::simulate::observer::{Layout, Observer, Step};
use mcap::records::{MessageHeader, Metadata};
use std::collections::BTreeMap;
use std::fs::{self, File};
use std::path::{Path, PathBuf};

/// Formatter threads and zstd workers: [`RecordOptions::threads`], else one per core (at most 4).
/// The file is the same for any count: blocks are written in step order, and zstd's output does
/// not depend on its number of workers once there is at least one (`tests/record_threads.rs`).
fn threads(options: &RecordOptions) -> usize {
    options
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get().min(4)))
        .max(1)
}

/// Records a run to `<path>` (through `<path>.partial`, renamed only once complete).
pub struct McapRecorder {
    path: PathBuf,
    partial: PathBuf,
    provenance: Provenance,
    options: RecordOptions,
    /// The MCAP writer before `begin` (then owned by the pipeline).
    writer: Option<McapWriter>,
    pipeline: Option<Pipeline>,
    /// The block being filled on the simulation thread.
    block: Block,
    topics: Vec<(Topic, u16)>,
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
        if !(15.0..=120.0).contains(&options.scene_rate_hz) {
            return Err(Error::parameter(
                "scene rate",
                format!(
                    "{} Hz: expected 15–120 Hz (30–60 is typical)",
                    options.scene_rate_hz
                ),
            ));
        }
        if !(options.magnification.is_finite() && options.magnification > 0.0) {
            return Err(Error::parameter(
                "display magnification",
                format!("{}: expected a positive factor", options.magnification),
            ));
        }
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        }
        let partial = partial_path(path);
        let file = File::create(&partial).map_err(|e| Error::io(&partial, e))?;
        let library = format!("wbv/{} mcap-rust/0.26", provenance.version);
        let writer = pipeline::open(file, options.compression, threads(&options), library)
            .map_err(mcap_err(&partial))?;
        Ok(McapRecorder {
            path: path.to_path_buf(),
            partial,
            provenance,
            options,
            writer: Some(writer),
            pipeline: None,
            block: Block::default(),
            topics: Vec::new(),
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

    fn setup(&mut self, layout: &Layout) -> Result<()> {
        let partial = self.partial.clone();
        let err = mcap_err(&partial);
        let w = self
            .writer
            .as_mut()
            .ok_or_else(|| Error::parameter("recorder", "begin() called twice"))?;
        let fs = 1.0 / layout.dt;
        let rate = self.options.record_rate_hz.unwrap_or(fs);
        self.every = decimation(fs, rate)?;
        let topics = topics(layout)?;
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
        let o = &self.options;
        for (k, v) in [
            ("simulation_rate_hz", fs.to_string()),
            ("sample_rate_hz", (fs / self.every as f64).to_string()),
            ("decimation", self.every.to_string()),
            (
                "anti_alias",
                self.lowpass
                    .as_ref()
                    .map_or("none (full rate)".into(), |_| {
                        format!(
                            "4th-order Butterworth low-pass, -3 dB at {} Hz, before decimation",
                            LowPass::CUTOFF_FRACTION * rate
                        )
                    }),
            ),
            ("scene_rate_hz", o.scene_rate_hz.to_string()),
            ("display_magnification", o.magnification.to_string()),
            ("compression", o.compression.as_str().to_string()),
            ("steps", layout.steps.to_string()),
            ("masses", layout.masses.join(",")),
            ("links", layout.links.join(",")),
        ] {
            run.insert(k.to_string(), v);
        }
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

        for t in topics {
            let schema = serde_json::to_vec(&t.schema).expect("schema serialises");
            let cid = json_channel(w, t.topic, t.schema_name, &schema).map_err(&err)?;
            self.topics.push((t, cid));
        }
        let scene = Scene::new(layout, self.options.magnification);
        let (scene_schema, tf_schema) = (SCENE_UPDATE_SCHEMA, FRAME_TRANSFORMS_SCHEMA);
        let scene_id = json_channel(
            w,
            "/wbv/scene",
            "foxglove.SceneUpdate",
            scene_schema.as_bytes(),
        )
        .map_err(&err)?;
        let tf_id = json_channel(w, "/tf", "foxglove.FrameTransforms", tf_schema.as_bytes())
            .map_err(&err)?;
        self.scene = Some((scene, scene_id, tf_id));
        let writer = self.writer.take().expect("checked above");
        let channels = (self.topics.iter())
            .map(|(t, id)| Channel {
                template: t.template.clone(),
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
        self.block.values.extend_from_slice(&self.values);
        self.block.steps.push((sequence, time_ns));
        self.last_time_ns = time_ns;
        Ok(())
    }

    fn non_finite(&self, s: &Step<'_>, mut i: usize) -> Error {
        let mut field = String::new();
        for (t, _) in &self.topics {
            if i < t.leaves.len() {
                field = channel_name(t.topic, &t.leaves[i].path);
                break;
            }
            i -= t.leaves.len();
        }
        Error::parameter(
            field,
            format!(
                "is not finite at step {} (t = {} s); refusing to record NaN or infinity",
                s.index, s.t
            ),
        )
    }

    fn record_scene(&mut self, s: &Step<'_>) -> Result<()> {
        let rate = self.options.scene_rate_hz;
        if (self.next_scene_frame as f64) / rate > s.t + 1e-9 {
            return Ok(());
        }
        self.next_scene_frame = (s.t * rate + 1e-9).floor() as u64 + 1;
        let sequence = u32::try_from(self.next_scene_frame - 1).unwrap_or(u32::MAX);
        let time_ns = (s.t * 1e9).round() as u64;
        let (scene, scene_id, tf_id) = self.scene.as_ref().expect("recording");
        let b = &mut self.block;
        for (channel_id, render) in [
            (
                *scene_id,
                Scene::scene_update as fn(&Scene, &Step<'_>, &mut Vec<u8>),
            ),
            (*tf_id, Scene::frame_transforms),
        ] {
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

    fn finish(&mut self) -> Result<()> {
        if !self.block.is_empty() {
            self.send_block()?;
        }
        let mut w = self.stop()?;
        let err = mcap_err(&self.partial);
        let mut results = BTreeMap::new();
        for (name, json) in &self.results {
            let text = serde_json::to_string_pretty(json).expect("a JSON value serialises");
            w.attach(&mcap::Attachment {
                log_time: self.last_time_ns,
                create_time: 0,
                name: format!("{name}.json"),
                media_type: "application/json".into(),
                data: text.as_bytes().into(),
            })
            .map_err(&err)?;
            results.insert(name.clone(), json.to_string());
        }
        if !results.is_empty() {
            w.write_metadata(&Metadata {
                name: meta::RESULTS.into(),
                metadata: results,
            })
            .map_err(&err)?;
        }
        w.finish().map_err(&err)?;
        let file = w
            .into_inner()
            .into_inner()
            .map_err(|e| Error::io(&self.partial, e.into_error()))?;
        file.sync_all().map_err(|e| Error::io(&self.partial, e))?;
        drop(file);
        if self.options.overwrite == Overwrite::Refuse && self.path.exists() {
            return Err(Error::parameter(
                self.path.display().to_string(),
                "appeared while recording; refusing to overwrite it",
            ));
        }
        fs::rename(&self.partial, &self.path).map_err(|e| Error::io(&self.path, e))?;
        self.completed = true;
        Ok(())
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
        self.finish()
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
        let _ = fs::remove_file(&self.partial);
    }
}
