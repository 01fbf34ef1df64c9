use std::path::PathBuf;
use wbv::diagnosis::acquisition::Loggers;
use wbv::diagnosis::{diagnose_with, plot, report};
use wbv::io::atomic::Overwrite;
use wbv::model::catalog;

/// Arguments of `wbv gap`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Model name or TOML file (e.g. `reference`).
    #[arg(long)]
    model: String,
    /// Training run: a measurement with channels a_base_z and a_seat_z in any input format
    /// (docs/inputs.md) or a wbv run; repeat for runs at different magnitudes.
    #[arg(long = "run", required = true)]
    runs: Vec<PathBuf>,
    /// Held-out run used only to score the candidates.
    #[arg(long)]
    check: PathBuf,
    /// A data logger and the channels it records, `NAME:CH[,CH…]`; repeat for each logger, e.g.
    /// `--logger base:a_base_z --logger cab:a_seat_z,a_head_z,f_seat_z`. A trigger offset or a
    /// clock drift between loggers retimes every channel of the loggers other than the base's.
    /// Without it the base accelerometer is assumed on one logger and the rest on another, unless
    /// the data show the force plate on the base's logger (the report says which).
    #[arg(long = "logger", value_name = "NAME:CHANNELS")]
    loggers: Vec<String>,
    /// How to read the runs (applies to every --run and --check).
    #[command(flatten)]
    input: wbv::io::input::InputArgs,
    /// Print the report as JSON (top-level `verdict`, `named`, `warnings`, `written`); `wbv report
    /// RUN --gap FILE` shows it as the report's gap section.
    #[arg(long)]
    json: bool,
    /// Write the gap-map and before/after plots into this directory.
    #[arg(long, value_name = "DIR")]
    plot: Option<PathBuf>,
    /// Plot file format.
    #[arg(long, default_value = "png", value_parser = ["png", "svg"])]
    plot_format: String,
    /// Replace existing plot files.
    #[arg(long)]
    force: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    if args.force && args.plot.is_none() {
        return Err(wbv::Error::parameter(
            "--force",
            "applies to the plots; give --plot DIR",
        ));
    }
    let ow = Overwrite::from_force(args.force);
    let plot = match &args.plot {
        // Refuse an overwrite before the diagnosis runs.
        Some(dir) => {
            let (dir, ext) = wbv::plot::plot_dir(dir, &args.plot_format)?;
            wbv::plot::check_targets(&plot::files(&dir, ext), ow)?;
            Some((dir, ext))
        }
        None => None,
    };
    let model = catalog::resolve(&args.model)?;
    let loggers = Loggers::parse(&args.loggers)?;
    let opts = args.input.options()?;
    let load = |p: &PathBuf| -> wbv::Result<wbv::signals::Signals> {
        let s = wbv::measurement::read(p, &opts)?.signals;
        wbv::diagnosis::require_channels(&s, &p.display().to_string())?;
        Ok(s)
    };
    let train = args
        .runs
        .iter()
        .map(load)
        .collect::<wbv::Result<Vec<_>>>()?;
    let check = load(&args.check)?;
    let d = diagnose_with(&model, &train, &check, &loggers)?;
    let mut written = Vec::new();
    if let Some((dir, ext)) = &plot {
        plot::write_as(&d, dir, ext, ow)?;
        eprintln!("wrote {}", dir.display());
        written = wbv::report::json::Written::existing(&plot::files(dir, ext))?;
    }
    if args.json {
        // The diagnosis's own `warnings` are the document's; they go to stderr too.
        for w in &d.warnings {
            eprintln!("warning: {w}");
        }
        super::print_document(&wbv::report::json::gap(&d, written)?);
    } else {
        print!("{}", report::text(&d));
    }
    Ok(())
}
