use std::io::Write;
use std::path::PathBuf;
use wbv::error::Error;
use wbv::io::atomic::{Overwrite, write_atomic};
use wbv::report::json::Written;
use wbv::response::frf;

/// Arguments of `wbv frf`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    model: super::ModelArg,
    /// Lowest frequency in Hz.
    #[arg(long, default_value_t = 0.1)]
    from: f64,
    /// Highest frequency in Hz.
    #[arg(long, default_value_t = 40.0)]
    to: f64,
    /// Number of frequency points.
    #[arg(long, default_value_t = 800)]
    points: usize,
    /// Logarithmic frequency spacing instead of linear.
    #[arg(long)]
    log: bool,
    /// Output CSV (`freq_hz`, then `<response>_mag`, `<response>_phase_deg`); stdout if omitted.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Also draw magnitude and phase as `DIR/frf.<format>` (log frequency axis with `--log`).
    #[arg(long, value_name = "DIR")]
    plot: Option<PathBuf>,
    /// Plot file format.
    #[arg(long, default_value = "png", value_parser = ["png", "svg"])]
    plot_format: String,
    /// Replace existing output files.
    #[arg(long)]
    force: bool,
    /// Print a JSON summary on stdout instead of the CSV: every response's unit and peak, the
    /// files written, and the curves (`freq_hz`, `mag`, `phase_deg`) when there is no `--out`.
    #[arg(long)]
    json: bool,
    /// Planar models: foam thickness of the cushion in m (paper 000: 0.06, 0.08, 0.10).
    #[arg(long)]
    foam_thickness: Option<f64>,
}

fn write_csv(set: &frf::FrfSet, out: &mut dyn Write) -> std::io::Result<()> {
    write!(out, "freq_hz")?;
    for r in &set.responses {
        write!(out, ",{0}_mag,{0}_phase_deg", r.name)?;
    }
    writeln!(out)?;
    let mags: Vec<Vec<f64>> = set.responses.iter().map(|r| r.magnitude()).collect();
    let phases: Vec<Vec<f64>> = set.responses.iter().map(|r| r.phase_deg()).collect();
    for (i, f) in set.freq_hz.iter().enumerate() {
        write!(out, "{f}")?;
        for (m, p) in mags.iter().zip(&phases) {
            write!(out, ",{},{}", m[i], p[i])?;
        }
        writeln!(out)?;
    }
    Ok(())
}

pub fn run(args: Args) -> wbv::Result<()> {
    let overwrite = Overwrite::from_force(args.force);
    // Refuse an overwrite before any work.
    let plot = match &args.plot {
        Some(dir) => {
            let (dir, ext) = wbv::plot::plot_dir(dir, &args.plot_format)?;
            let path = dir.join(format!("frf.{ext}"));
            wbv::plot::check_targets(std::slice::from_ref(&path), overwrite)?;
            Some(path)
        }
        None => None,
    };
    if let Some(out) = &args.out {
        wbv::io::atomic::check_overwrite(out, overwrite)?;
    }
    let mut model = args.model.resolve()?;
    if let Some(t) = args.foam_thickness {
        model.set_foam_thickness(t)?;
    }
    let freqs = frf::grid(args.from, args.to, args.points, args.log)?;
    let set = frf::compute(model.system(), &freqs)?;
    let mut written = Vec::new();
    match &args.out {
        Some(path) => {
            write_atomic(path, overwrite, |w| {
                write_csv(&set, w).map_err(|e| Error::io(path, e))
            })?;
            written.push(Written::of(path)?);
        }
        None if args.json => {}
        None => {
            write_csv(&set, &mut std::io::stdout().lock()).map_err(|e| Error::io("stdout", e))?
        }
    }
    if let Some(path) = &plot {
        wbv::plot::frf_plot(&set, &model.name, args.log, path, overwrite)?;
        eprintln!("wrote {}", path.display());
        written.push(Written::of(path)?);
    }
    if args.json {
        let mut summary =
            wbv::report::json::Frf::of(&model.name, &set, args.log, args.out.is_none());
        summary.written = written;
        super::print_json("frf", &summary, &[])?;
    }
    Ok(())
}
