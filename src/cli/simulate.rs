use crate::excitation::{ExcitationArgs, args::resolve};
use crate::io::atomic::Overwrite;
use crate::record::{Compression, RUN_FILE, RecordOptions};
use crate::scenario::{Outcome, Outputs, Scenario};
use std::path::{Path, PathBuf};

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
    /// Run directory; the recording is `<DIR>/run.mcap` (default `runs/<model>-s<seed>`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Do not write the MCAP recording (batch work).
    #[arg(long)]
    pub no_record: bool,
    /// Record the time series at this rate in Hz (low-pass filtered first); default: every step.
    #[arg(long)]
    pub record_rate: Option<f64>,
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
}

impl Args {
    /// The scenario these arguments describe.
    pub fn scenario(&self) -> crate::Result<Scenario> {
        let excitation = resolve(&self.excitation)?;
        let mut settings = self.time.settings()?;
        // A recording lasts as long as it lasts: its length is the default duration.
        if self.time.duration.is_none()
            && let crate::excitation::Kind::Recorded { csv, input } = &excitation.kind
        {
            let rec = crate::excitation::recorded::read_record(csv, input)?;
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

/// The command line as typed, for provenance.
pub fn command_line() -> String {
    std::env::args().collect::<Vec<_>>().join(" ")
}

/// Runs `scenario` into `dir` (unless `record` is false) and prints what it produced.
pub fn execute(
    scenario: &Scenario,
    dir: Option<&Path>,
    options: RecordOptions,
    csv: Option<PathBuf>,
) -> crate::Result<Outcome> {
    let outputs = Outputs {
        overwrite: options.overwrite,
        mcap: dir.map(|d| (d.join(RUN_FILE), options)),
        csv,
        command_line: command_line(),
    };
    let bar = progress(scenario.settings.steps());
    let outcome = scenario.execute(&outputs, Some(&bar))?;
    bar.finish_and_clear();
    let memory = crate::io::memory::peak_resident_bytes().map_or(String::new(), |b| {
        format!(", peak memory {:.0} MB", b as f64 / 1e6)
    });
    println!(
        "simulated {} s of `{}` under {} with {} in {:.2} s{memory}",
        scenario.settings.duration_s,
        scenario.model.name,
        scenario.excitation.summary(),
        scenario.settings.method.name(),
        outcome.elapsed_s
    );
    if let Some((p, _)) = &outputs.mcap {
        println!("recorded {}", p.display());
    }
    if let Some(p) = &outputs.csv {
        println!("wrote {}", p.display());
    }
    match (&outcome.report, &outcome.report_skipped) {
        (Some(r), _) => {
            println!();
            super::analyze::print_table(r);
        }
        (None, Some(why)) => println!("analysis skipped: {why}"),
        (None, None) => {}
    }
    Ok(outcome)
}

/// Times, in extra runs, generating the excitation alone and the simulation core (excitation +
/// integration, no observers), in s: what `scipy.signal.lsim` does, for `tools/bench-peers`.
fn time_core(scenario: &Scenario) -> crate::Result<(f64, f64)> {
    let s = &scenario.settings;
    let start = std::time::Instant::now();
    let mut exc = scenario
        .excitation
        .build(s.excitation_step(), s.duration_s, scenario.seed)?;
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

pub fn run(args: Args) -> crate::Result<()> {
    if args.no_record {
        for (set, flag) in [
            (args.record_rate.is_some(), "--record-rate"),
            (args.out.is_some(), "--out"),
        ] {
            if set {
                return Err(crate::Error::parameter(
                    flag,
                    "has no effect with --no-record (nothing is recorded)",
                ));
            }
        }
    }
    let scenario = args.scenario()?;
    let core = if args.timing {
        Some(time_core(&scenario)?)
    } else {
        None
    };
    let options = RecordOptions {
        compression: Compression::parse(&args.compression)?,
        record_rate_hz: args.record_rate,
        overwrite: Overwrite::from_force(args.force),
        ..RecordOptions::default()
    };
    let dir = args.out.clone().unwrap_or_else(|| {
        PathBuf::from("runs").join(format!(
            "{}-s{}",
            scenario.model.name.replace('+', "_"),
            scenario.seed
        ))
    });
    let outcome = execute(
        &scenario,
        (!args.no_record).then_some(dir.as_path()),
        options,
        args.csv.clone(),
    )?;
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
    Ok(())
}
