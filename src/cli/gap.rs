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
    /// Write the corrected model to this model file (TOML, docs/models.md): the base model as
    /// re-fitted with the named structural effects as model elements and a `[provenance]` table;
    /// effects of the measuring chain are listed there as corrections, not built in. With the
    /// verdict `unexplained` or `not-identifiable` the file is the re-fitted model with a warning.
    #[arg(long, value_name = "FILE.toml")]
    write_model: Option<PathBuf>,
    /// Replace existing plot files and the --write-model file.
    #[arg(long)]
    force: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    if args.force && args.plot.is_none() && args.write_model.is_none() {
        return Err(wbv::Error::parameter(
            "--force",
            "applies to the plots and the model file; give --plot DIR or --write-model FILE",
        ));
    }
    let ow = Overwrite::from_force(args.force);
    // Refuse an overwrite before the diagnosis runs.
    if let Some(path) = &args.write_model {
        wbv::io::atomic::check_overwrite(path, ow)?;
    }
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
    if let Some(path) = &args.write_model {
        let status = d.model_status.as_ref();
        let text = d.model.as_ref().ok_or_else(|| {
            let why = status.and_then(|s| s.not_written.clone());
            wbv::Error::parameter("--write-model", why.unwrap_or_default())
        })?;
        if let Some(w) = status.and_then(|s| s.warning.as_ref()) {
            eprintln!("warning: {w}");
        }
        wbv::io::atomic::write_atomic(path, ow, |out| {
            std::io::Write::write_all(out, text.as_bytes()).map_err(wbv::io::atomic::io_err(path))
        })?;
        eprintln!("wrote {}", path.display());
        written.extend(wbv::report::json::Written::existing(std::slice::from_ref(
            path,
        ))?);
    }
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
