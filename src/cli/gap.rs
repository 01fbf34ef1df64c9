use crate::diagnosis::{diagnose, plot, report};
use crate::io::atomic::Overwrite;
use crate::model::catalog;
use std::path::PathBuf;

/// Arguments of `wbv gap`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Model name or TOML file (e.g. `reference`).
    #[arg(long)]
    model: String,
    /// Training run (measured-run CSV or MCAP); repeat for runs at different magnitudes.
    #[arg(long = "run", required = true)]
    runs: Vec<PathBuf>,
    /// Held-out run used only to score the candidates.
    #[arg(long)]
    check: PathBuf,
    /// Print the report as JSON (top-level `verdict`).
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

pub fn run(args: Args) -> crate::Result<()> {
    let ow = Overwrite::from_force(args.force);
    let plot = match &args.plot {
        // Refuse an overwrite before the diagnosis runs.
        Some(dir) => {
            let (dir, ext) = crate::plot::plot_dir(dir, &args.plot_format)?;
            crate::plot::check_targets(&plot::files(&dir, ext), ow)?;
            Some((dir, ext))
        }
        None => None,
    };
    let model = catalog::resolve(&args.model)?;
    // The candidate effects edit a chain's masses and links (issue 15 brings them onto the system).
    let model = model.chain().cloned().ok_or_else(|| {
        crate::Error::parameter(
            "--model",
            format!(
                "`{}` is not a chain of masses; the gap diagnosis's candidate effects modify chain links",
                model.name
            ),
        )
    })?;
    let train = args
        .runs
        .iter()
        .map(|p| crate::analysis::load_signals(p))
        .collect::<crate::Result<Vec<_>>>()?;
    let check = crate::analysis::load_signals(&args.check)?;
    let d = diagnose(&model, &train, &check)?;
    if let Some((dir, ext)) = &plot {
        plot::write_as(&d, dir, ext, ow)?;
        eprintln!("wrote {}", dir.display());
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report::json(&d)).expect("JSON value serializes")
        );
    } else {
        print!("{}", report::text(&d));
    }
    Ok(())
}
