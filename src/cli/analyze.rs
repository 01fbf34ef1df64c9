use std::path::PathBuf;
use wbv::analysis::{Options, Report, Segment, WelchOptions, Window};
use wbv::io::atomic::Overwrite;
use wbv::report::json::Written;

/// Arguments of `wbv analyze`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Measurement or run to analyse: delimited text (CSV, TSV, `;`), WAV, MATLAB .mat (v5),
    /// UFF58, another logger's MCAP (with --topic), a wbv MCAP run or a run directory
    /// (docs/inputs.md). Whatever acceleration channels exist are analysed.
    path: PathBuf,
    #[command(flatten)]
    input: wbv::io::input::InputArgs,
    #[command(flatten)]
    shocks: super::exposure::ShockArgs,
    /// Print the report as JSON (keys `a_w`, `vdv`, `mtvv`, `crest_factor`, `seat_percent`,
    /// `comfort`, …; units under `units`).
    #[arg(long)]
    json: bool,
    /// Write the run's figures into this directory (time histories, PSDs, weighted bands, running
    /// r.m.s., transmissibilities, comfort and health).
    #[arg(long, value_name = "DIR")]
    plot: Option<PathBuf>,
    /// Plot file format.
    #[arg(long, default_value = "png", value_parser = ["png", "svg"])]
    plot_format: String,
    #[command(flatten)]
    exposure: super::ExposureArg,
    /// Spectral resolution of the Welch PSD in Hz.
    #[arg(long, default_value_t = 0.125)]
    resolution: f64,
    /// Replace existing plot files.
    #[arg(long)]
    force: bool,
    /// Print the time spent loading the run and analysing it to standard error (wall, and CPU
    /// seconds of every thread where the platform reports them).
    #[arg(long)]
    timing: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    if args.plot.is_none() {
        for (set, flag) in [
            (args.force, "--force"),
            (args.plot_format != "png", "--plot-format"),
        ] {
            if set {
                return Err(wbv::Error::parameter(
                    flag,
                    "applies to the plots; give --plot DIR",
                ));
            }
        }
    }
    let exposure_hours = args.exposure.hours()?;
    let ow = Overwrite::from_force(args.force);
    // Refuse an overwrite before any work.
    let plot = match &args.plot {
        Some(dir) => {
            let (dir, ext) = wbv::plot::plot_dir(dir, &args.plot_format)?;
            wbv::plot::check_targets(&wbv::plot::iso::plot_files(&dir, ext), ow)?;
            Some((dir, ext))
        }
        None => None,
    };
    let start = std::time::Instant::now();
    let cpu = wbv::io::memory::cpu_seconds;
    let cpu_start = cpu();
    let input = wbv::measurement::read(&args.path, &args.input.options()?)?;
    let signals = input.signals;
    let loaded = start.elapsed().as_secs_f64();
    let cpu_loaded = cpu();
    let welch = WelchOptions {
        window: Window::Hann,
        segment: Segment::ResolutionHz(args.resolution),
        ..WelchOptions::default()
    };
    let opts = Options {
        exposure_hours: Some(exposure_hours),
        welch,
        units_assumed: input.undeclared.clone(),
        shocks: args.shocks.settings()?,
        ..Options::default()
    };
    let report = Report::from_signals(&signals, &opts)?;
    // What the reader decided, once the run is known to analyse (an error stays one line); with
    // --json these are the document's warnings.
    if !args.json {
        for n in &input.notes {
            eprintln!("input: {n}");
        }
    }
    if args.timing {
        let cpu_s = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => format!(" ({:.4} CPU-s)", b - a),
            _ => String::new(),
        };
        eprintln!(
            "timing: load {loaded:.4} s{}, analysis {:.4} s{} ({} samples × {} channels)",
            cpu_s(cpu_start, cpu_loaded),
            start.elapsed().as_secs_f64() - loaded,
            cpu_s(cpu_loaded, cpu()),
            signals.len(),
            signals.names.len()
        );
    }
    let mut written = Vec::new();
    if let Some((dir, ext)) = &plot {
        for p in wbv::plot::iso::write_plots(&signals, &report, &welch, dir, ext, ow)? {
            eprintln!("wrote {}", p.display());
            written.push(Written::of(&p)?);
        }
    }
    if args.json {
        // The report's own warnings are already its document's `warnings`; on stderr too.
        for w in &report.warnings {
            eprintln!("warning: {w}");
        }
        super::print_document(&wbv::report::json::analyze(&report, written, &input.notes)?);
    } else {
        print_table(&report);
    }
    Ok(())
}

pub(crate) fn print_table(r: &Report) {
    for w in &r.warnings {
        println!("WARNING: {w}");
    }
    println!(
        "{}: {:.1} s at {} Hz",
        r.source, r.duration_s, r.sample_rate_hz
    );
    let assumed = r.unit_assumption();
    if let Some(a) = &assumed {
        println!("UNIT NOT DECLARED: every figure below {a}");
    }
    println!(
        "  {:<12} {:>4} {:>5} {:>10} {:>10} {:>11} {:>10} {:>8} {:>11}",
        "channel",
        "W",
        "k",
        "rms m/s²",
        "a_w m/s²",
        "VDV m/s^1.75",
        "MTVV m/s²",
        "CF",
        "MSDV m/s^1.5"
    );
    for c in &r.channels {
        // A channel whose unit was assumed is marked `*`: its figures assume m/s².
        let name = if r.unit_assumed_channels.contains(&c.name) {
            format!("{} *", c.name)
        } else {
            c.name.clone()
        };
        println!(
            "  {:<12} {:>4} {:>5.2} {:>10.4} {:>10.4} {:>11.4} {:>10.4} {:>8.2} {:>11}",
            name,
            c.weighting.name(),
            c.k,
            c.rms,
            c.a_w,
            c.vdv,
            c.mtvv,
            c.crest_factor,
            c.msdv.map_or("-".into(), |m| format!("{m:.4}"))
        );
    }
    if assumed.is_some() {
        println!("  * unit not declared: read as m/s²");
    }
    // Every verdict line carries the unit assumption when there is one.
    let assumes = if assumed.is_some() {
        " (assumes m/s²: unit not declared)"
    } else {
        ""
    };
    println!(
        "\nComfort ({}): a_v = {:.4} m/s², class: {}{}{assumes}",
        r.comfort_place,
        r.total_value,
        r.comfort,
        if r.verdict_doubtful {
            " (doubtful: see the WARNING above)"
        } else {
            ""
        }
    );
    println!("  {}", r.comfort_statement);
    if let Some(s) = r.seat_percent {
        println!("SEAT (a_seat_z / a_base_z, Wk): {s:.1} %");
    }
    if let Some(h) = &r.health {
        for (i, line) in h.statement().iter().enumerate() {
            println!("{line}");
            if i == 0 && assumed.is_some() {
                println!("  assumes m/s²: unit not declared (see UNIT NOT DECLARED above)");
            }
        }
        if r.verdict_doubtful {
            println!(
                "  doubtful: it rests on a channel whose unit looks wrong (see the WARNING above)"
            );
        }
    }
    if let Some(s) = &r.iso2631_5 {
        for line in s.statement() {
            println!("{line}");
        }
    }
    for n in &r.notes {
        println!("note: {n}");
    }
}
