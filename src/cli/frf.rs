use crate::error::Error;
use crate::io::atomic::{Overwrite, write_atomic};
use crate::response::frf;
use std::io::Write;
use std::path::PathBuf;

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
    /// Also draw the magnitudes to a PNG or SVG file.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Replace existing output files.
    #[arg(long)]
    force: bool,
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

pub fn run(args: Args) -> crate::Result<()> {
    let mut model = args.model.resolve()?;
    if let Some(t) = args.foam_thickness {
        model.set_foam_thickness(t)?;
    }
    let freqs = frf::grid(args.from, args.to, args.points, args.log)?;
    let set = frf::compute(model.system(), &freqs)?;
    let overwrite = if args.force {
        Overwrite::Allow
    } else {
        Overwrite::Refuse
    };
    match &args.out {
        Some(path) => write_atomic(path, overwrite, |w| {
            write_csv(&set, w).map_err(|e| Error::io(path, e))
        })?,
        None => {
            write_csv(&set, &mut std::io::stdout().lock()).map_err(|e| Error::io("stdout", e))?
        }
    }
    if let Some(path) = &args.plot {
        crate::plot::frf_plot(&set, &model.name, path, overwrite)?;
    }
    Ok(())
}
