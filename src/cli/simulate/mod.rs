use std::path::{Path, PathBuf};
use wbv::excitation::{ExcitationArgs, args::resolve};
use wbv::io::atomic::Overwrite;
use wbv::record::{Compression, Encoding, MessageLayout, RUN_FILE, RecordOptions};
use wbv::scenario::{Outcome, Outputs, Scenario};

mod provenance;

use provenance::check_from_alone;
pub use provenance::{command_line, from_run};

/// Arguments of `wbv simulate`.
#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    #[command(flatten)]
    pub model: super::ModelArg,
    #[command(flatten)]
    pub excitation: ExcitationArgs,
    #[command(flatten)]
    pub time: super::TimeArgs,
    /// Re-run a recorded run exactly (an MCAP file or run directory): its model TOML, excitation
    /// definition, integrator, step, duration, seed and recording options; only --out, --force,
    /// --csv, --timing and --json may be given with it. The new recording is byte-identical.
    #[arg(long)]
    pub from: Option<PathBuf>,
    /// Run directory; the recording is `<DIR>/run.mcap` (default `runs/<model>-s<seed>`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Do not write the MCAP recording (batch work).
    #[arg(long)]
    pub no_record: bool,
    /// Record the time series at this rate in Hz (low-pass filtered first); default: every step.
    #[arg(long)]
    pub record_rate: Option<f64>,
    /// Message encoding of every recorded channel: protobuf (compact, plotted by Foxglove,
    /// Lichtblick, PlotJuggler and Rerun) or json (text).
    #[arg(long, default_value = "protobuf")]
    pub encoding: String,
    /// Message layout of the time series: per-sample (the default: one message per sample, every
    /// field a time series in every viewer) or batched (protobuf only: one message per topic per
    /// 1024 samples, packed arrays; the smallest file). See docs/viewing.md.
    #[arg(long)]
    pub layout: Option<String>,
    /// MCAP chunk compression: zstd, lz4 or none.
    #[arg(long, default_value = "zstd")]
    pub compression: String,
    /// Also write the measured-run channels (t_s, a_base_z, a_seat_z, a_head_z, f_seat_z) as CSV.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Replace existing outputs.
    #[arg(long)]
    pub force: bool,
    /// Also time the simulation core alone (excitation + integration, no analysis or recording) in
    /// an extra run before the real one, and print both times on stderr.
    #[arg(long)]
    pub timing: bool,
    /// Live view: stream the run to the Foxglove app or Lichtblick over the Foxglove WebSocket
    /// protocol while simulating, on ADDR (host:port, default 127.0.0.1:8765; port 0 picks a free
    /// one, printed on stderr). The run starts once a viewer subscribes to a topic (see
    /// --serve-wait); with or without recording.
    #[cfg(feature = "live")]
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = wbv::record::live::DEFAULT_ADDR)]
    pub serve: Option<String>,
    /// With --serve: pace the simulation to wall-clock time (1 s simulated per s).
    #[cfg(feature = "live")]
    #[arg(long, requires = "serve")]
    pub realtime: bool,
    /// With --serve: seconds to wait for a viewer to subscribe before simulating (0: start at once).
    #[cfg(feature = "live")]
    #[arg(long, requires = "serve", default_value_t = 30.0)]
    pub serve_wait: f64,
    /// Print the result as JSON on stdout (`analysis`, `written`, `elapsed_s`, …); status lines
    /// stay on stderr.
    #[arg(long)]
    pub json: bool,
}

impl Args {
    /// The scenario these arguments describe.
    pub fn scenario(&self) -> wbv::Result<Scenario> {
        let excitation = resolve(&self.excitation)?;
        let mut settings = self.time.settings()?;
        // A recording lasts as long as it lasts: its length is the default duration.
        if self.time.duration.is_none()
            && let wbv::excitation::Kind::Recorded { csv, input } = &excitation.kind
        {
            let rec = wbv::measurement::read_record(csv, input)?;
            settings.duration_s = rec.samples.len() as f64 / rec.sample_rate_hz;
        }
        Ok(Scenario {
            model: self.model.resolve()?,
            excitation,
            settings,
            seed: self.time.seed,
        })
    }
}

/// A progress bar on a terminal for long runs, hidden otherwise.
pub fn progress(steps: u64) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(steps);
    if steps < 200_000 {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:40} {percent:>3}% {elapsed} / {eta} left")
            .expect("valid template"),
    );
    bar
}

/// Runs `scenario` into `dir` (unless `record` is false); its status lines go to stderr.
pub fn execute(
    scenario: &Scenario,
    dir: Option<&Path>,
    options: RecordOptions,
    csv: Option<PathBuf>,
) -> wbv::Result<Outcome> {
    execute_as(scenario, dir, options, csv, command_line(), &mut [])
}

/// [`execute`] with the command line stored in the provenance given.
fn execute_as(
    scenario: &Scenario,
    dir: Option<&Path>,
    options: RecordOptions,
    csv: Option<PathBuf>,
    command_line: String,
    extra: &mut [&mut dyn wbv::simulate::observer::Observer],
) -> wbv::Result<Outcome> {
    let outputs = Outputs {
        overwrite: options.overwrite,
        mcap: dir.map(|d| (d.join(RUN_FILE), options)),
        csv,
        command_line,
    };
    let bar = progress(scenario.settings.steps());
    let outcome = scenario.execute_with(&outputs, extra, Some(&|n| bar.set_position(n)))?;
    bar.finish_and_clear();
    let memory = wbv::io::memory::peak_resident_bytes().map_or(String::new(), |b| {
        format!(", peak memory {:.0} MB", b as f64 / 1e6)
    });
    eprintln!(
        "simulated {} s of `{}` under {} with {} in {:.2} s{memory}",
        scenario.settings.duration_s,
        scenario.model.name,
        scenario.excitation.summary(),
        scenario.settings.method.name(),
        outcome.elapsed_s
    );
    if let Some((p, _)) = &outputs.mcap {
        eprintln!("recorded {}", p.display());
    }
    if let Some(p) = &outputs.csv {
        eprintln!("wrote {}", p.display());
    }
    Ok(outcome)
}

/// How to open the recording `run` in each viewer, with the set-up files written beside it.
pub fn viewer_hint(run: &Path) -> String {
    let [layout, blueprint] = [
        wbv::record::viewer::LAYOUT_FILE,
        wbv::record::viewer::BLUEPRINT_FILE,
    ]
    .map(|f| run.with_file_name(f).display().to_string());
    let rrd = run.with_extension("rrd");
    format!(
        "Open {run} in Foxglove or Lichtblick (import the layout {layout}) or PlotJuggler; in \
         Rerun: rerun mcap convert {run} --application-id {id} --timeline-type duration -o {rrd} && \
         rerun {rrd} {blueprint}",
        run = run.display(),
        id = wbv::record::viewer::RERUN_APPLICATION_ID,
        rrd = rrd.display(),
    )
}

/// The result of a run on stdout: its ISO 2631-1 table, or with `json` the JSON document.
fn print_result(
    scenario: &Scenario,
    outcome: &Outcome,
    dir: Option<&Path>,
    csv: Option<&Path>,
    json: bool,
) -> wbv::Result<()> {
    if json {
        let written = wbv::report::json::Written::of_run(dir, csv)?;
        super::print_document(&wbv::report::json::simulate(scenario, outcome, written)?);
        return Ok(());
    }
    print_table(outcome);
    Ok(())
}

/// The ISO 2631-1 table of a run on stdout (or why there is none, on stderr), and for a seat-test
/// input class the platform PSD check.
pub fn print_table(outcome: &Outcome) {
    match (&outcome.report, &outcome.report_skipped) {
        (Some(r), _) => super::analyze::print_table(r),
        (None, Some(why)) => eprintln!("analysis skipped: {why}"),
        (None, None) => {}
    }
    if let Some(c) = &outcome.platform_psd {
        println!("\n{}", c.sentence());
    }
    if let Some(why) = &outcome.platform_psd_skipped {
        eprintln!("platform PSD not checked: {why}");
    }
}

/// The live view `--serve` asks for, started (so a bad address fails before any work).
#[cfg(feature = "live")]
fn live_view(
    args: &Args,
    options: &RecordOptions,
) -> wbv::Result<Option<wbv::record::live::LiveView>> {
    use wbv::record::live::{LiveOptions, LiveView};
    let Some(addr) = &args.serve else {
        return Ok(None);
    };
    if !(args.serve_wait.is_finite() && args.serve_wait >= 0.0) {
        return Err(wbv::Error::parameter(
            "--serve-wait",
            format!("{}: expected a duration in s ≥ 0", args.serve_wait),
        ));
    }
    let live = LiveView::start(LiveOptions {
        addr: addr.clone(),
        realtime: args.realtime,
        wait: std::time::Duration::from_secs_f64(args.serve_wait),
        scene_rate_hz: options.scene_rate_hz,
        magnification: options.magnification,
    })?;
    eprintln!(
        "live view on {} (Foxglove or Lichtblick: Open connection → Foxglove WebSocket){}",
        live.url(),
        if args.realtime {
            ", paced to wall-clock time"
        } else {
            ""
        }
    );
    Ok(Some(live))
}

/// Times, in extra runs, generating the excitation alone and the simulation core (excitation +
/// integration, no observers), in s: what `scipy.signal.lsim` does, for `tools/bench-peers`.
fn time_core(scenario: &Scenario) -> wbv::Result<(f64, f64)> {
    let s = &scenario.settings;
    let start = std::time::Instant::now();
    let mut exc = wbv::measurement::excitation(
        &scenario.excitation,
        s.excitation_step(),
        s.duration_s,
        scenario.seed,
    )?;
    let mut buf = vec![0.0; 4096];
    let mut left = s.steps() as usize * s.method.substeps() + 1;
    while left > 0 {
        let k = left.min(buf.len());
        exc.fill(&mut buf[..k]);
        left -= k;
    }
    std::hint::black_box(&buf);
    let excitation = start.elapsed().as_secs_f64();
    let start = std::time::Instant::now();
    scenario.simulate(&mut [], None)?;
    Ok((excitation, start.elapsed().as_secs_f64()))
}

/// Refuses existing outputs before any input is read or anything simulated: the recording in
/// `dir` and the CSV.
fn refuse_existing(dir: Option<&Path>, csv: Option<&Path>, force: bool) -> wbv::Result<()> {
    let ow = Overwrite::from_force(force);
    if let Some(d) = dir {
        wbv::io::atomic::check_overwrite(&d.join(RUN_FILE), ow)?;
    }
    if let Some(c) = csv {
        wbv::io::atomic::check_overwrite(c, ow)?;
    }
    Ok(())
}

/// The default run directory of `model` and `seed`: `runs/<model>-s<seed>`.
fn default_dir(model: &str, seed: u64) -> PathBuf {
    PathBuf::from("runs").join(format!("{}-s{seed}", model.replace('+', "_")))
}

pub fn run(args: Args) -> wbv::Result<()> {
    if let Some(run) = &args.from {
        check_from_alone(std::env::args().skip(1))?;
        refuse_existing(args.out.as_deref(), args.csv.as_deref(), args.force)?;
        let (scenario, options, line) = from_run(run)?;
        let options = RecordOptions {
            overwrite: Overwrite::from_force(args.force),
            ..options
        };
        let dir = args.out.clone().ok_or_else(|| {
            wbv::Error::parameter("--out", "required with --from (a new run directory)")
        })?;
        let outcome = execute_as(
            &scenario,
            Some(&dir),
            options,
            args.csv.clone(),
            line,
            &mut [],
        )?;
        return print_result(
            &scenario,
            &outcome,
            Some(&dir),
            args.csv.as_deref(),
            args.json,
        );
    }
    if args.no_record {
        for (set, flag) in [
            (args.record_rate.is_some(), "--record-rate"),
            (args.layout.is_some(), "--layout"),
            (args.out.is_some(), "--out"),
        ] {
            if set {
                return Err(wbv::Error::parameter(
                    flag,
                    "has no effect with --no-record (nothing is recorded)",
                ));
            }
        }
    }
    let dir = match &args.out {
        Some(d) => d.clone(),
        None => default_dir(&args.model.resolve()?.name, args.time.seed),
    };
    refuse_existing(
        (!args.no_record).then_some(dir.as_path()),
        args.csv.as_deref(),
        args.force,
    )?;
    #[cfg(feature = "live")]
    if let Some(addr) = &args.serve {
        wbv::record::live::parse_addr(addr)?;
    }
    let scenario = args.scenario()?;
    let core = if args.timing {
        Some(time_core(&scenario)?)
    } else {
        None
    };
    let options = RecordOptions {
        encoding: Encoding::parse(&args.encoding)?,
        compression: Compression::parse(&args.compression)?,
        layout: args
            .layout
            .as_deref()
            .map(MessageLayout::parse)
            .transpose()?,
        record_rate_hz: args.record_rate,
        overwrite: Overwrite::from_force(args.force),
        ..RecordOptions::default()
    };
    #[cfg(feature = "live")]
    let mut live = live_view(&args, &options)?;
    #[cfg(not(feature = "live"))]
    let live: Option<std::convert::Infallible> = None;
    let mut extra: Vec<&mut dyn wbv::simulate::observer::Observer> = Vec::new();
    #[cfg(feature = "live")]
    if let Some(l) = live.as_mut() {
        extra.push(l);
    }
    let outcome = execute_as(
        &scenario,
        (!args.no_record).then_some(dir.as_path()),
        options,
        args.csv.clone(),
        command_line(),
        &mut extra,
    )?;
    drop(extra);
    #[cfg(feature = "live")]
    if let Some(mut l) = live {
        wbv::simulate::observer::Observer::end(&mut l)?;
    }
    #[cfg(not(feature = "live"))]
    let _ = live;
    if let Some((excitation, core)) = core {
        let ns = 1e9 / scenario.settings.steps() as f64;
        eprintln!(
            "timing: excitation {excitation:.4} s, core {core:.4} s ({:.1} ns per step, of which integration {:.1} ns), run {:.4} s (with analysis{})",
            core * ns,
            (core - excitation) * ns,
            outcome.elapsed_s,
            if args.no_record { "" } else { " and recording" }
        );
    }
    print_result(
        &scenario,
        &outcome,
        (!args.no_record).then_some(dir.as_path()),
        args.csv.as_deref(),
        args.json,
    )
}
