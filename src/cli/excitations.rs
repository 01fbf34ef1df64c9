//! `wbv excitations` (list the built-ins) and `wbv excitation-export` (write a base input to CSV).

use crate::error::Error;
use crate::excitation::{ExcitationArgs, ExcitationSpec, builtin, resolve};
use crate::io::atomic::Overwrite;
use crate::io::csv_run;
use crate::signals::Signals;
use std::path::PathBuf;

/// Arguments of `wbv excitations`.
#[derive(Debug, clap::Args)]
pub struct ListArgs {}

/// Arguments of `wbv excitation-export`.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    #[command(flatten)]
    excitation: ExcitationArgs,
    /// Duration in s.
    #[arg(long)]
    duration: f64,
    /// Sample step in s.
    #[arg(long, default_value_t = 0.001)]
    dt: f64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Output measured-run CSV (`t_s`, `a_base_z` in m/s²).
    #[arg(long)]
    out: PathBuf,
    /// Replace an existing output file.
    #[arg(long)]
    force: bool,
}

pub fn list(_args: ListArgs) -> crate::Result<()> {
    let names = builtin::names();
    let width = names.iter().map(|n| n.len()).max().unwrap_or(0);
    for name in names {
        let spec = ExcitationSpec::load(name)?;
        let rms = spec
            .rms_m_s2()
            .map(|r| format!(" [{r:.3} m/s² r.m.s.]"))
            .unwrap_or_default();
        println!("  {name:width$}  {}{rms}", spec.description);
    }
    println!(
        "\nUse a name, a TOML file, or build one: `--excitation random --rms 1.0 --band 0.5,80`, \
         `--excitation sine --freq 4 --amplitude 1`, `--excitation road --road-class C --speed 20`, \
         `--excitation recorded --input run.csv`, `--excitation psd --input psd.csv`."
    );
    Ok(())
}

pub fn export(args: ExportArgs) -> crate::Result<()> {
    let spec = resolve(&args.excitation)?;
    if !(args.duration.is_finite() && args.duration > 0.0) {
        return Err(Error::parameter(
            "--duration",
            format!("{} s must be positive", args.duration),
        ));
    }
    let n = (args.duration / args.dt).round() as usize;
    let mut exc = crate::measurement::excitation(&spec, args.dt, args.duration, args.seed)?;
    let mut samples = vec![0.0; n];
    exc.fill(&mut samples);
    let mut signals = Signals::new(1.0 / args.dt, exc.describe());
    signals.push("a_base_z", samples)?;
    let overwrite = if args.force {
        Overwrite::Allow
    } else {
        Overwrite::Refuse
    };
    csv_run::write(&args.out, &signals, overwrite)?;
    eprintln!(
        "wrote {} samples of {} to {}",
        n,
        exc.describe(),
        args.out.display()
    );
    Ok(())
}
