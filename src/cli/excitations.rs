//! `wbv excitations` (list the built-ins) and `wbv excitation-export` (write a base input to CSV).

use std::path::PathBuf;
use wbv::error::Error;
use wbv::excitation::{ExcitationArgs, ExcitationSpec, builtin, resolve};
use wbv::io::atomic::Overwrite;
use wbv::io::csv_run;
use wbv::report::json::{Files, Written};
use wbv::signals::Signals;

/// Arguments of `wbv excitations`.
#[derive(Debug, clap::Args)]
pub struct ListArgs {
    /// Print the list as JSON (`excitations`: name, description, origin, rms_m_s2; for the seat-test
    /// input classes also standard, class, machine).
    #[arg(long)]
    json: bool,
}

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
    /// Print what was written as JSON (`written`, `samples`, `sample_rate_hz`, `excitation`).
    #[arg(long)]
    json: bool,
}

pub fn list(args: ListArgs) -> wbv::Result<()> {
    let names = builtin::names();
    if args.json {
        super::print_document(&wbv::report::json::excitations()?);
        return Ok(());
    }
    let width = names.iter().map(|n| n.len()).max().unwrap_or(0);
    let mut classes = Vec::new();
    for name in names {
        let spec = ExcitationSpec::load(name)?;
        let rms = spec
            .rms_m_s2()
            .map(|r| format!(" [{r:.3} m/s² r.m.s.]"))
            .unwrap_or_default();
        match spec.input_class_def() {
            Some(c) => classes.push((name, c, rms)),
            None => println!("  {name:width$}  {}{rms}", spec.description),
        }
    }
    println!(
        "\nSeat-test input spectral classes (ISO 10326-1 test; `wbv seat-test --class NAME`):"
    );
    for (name, c, rms) in classes {
        println!(
            "  {name:width$}  {} {}: {}{rms}",
            c.standard.name(),
            c.code,
            c.scope_label()
        );
    }
    println!(
        "  [U]: not verified against the standard's text (its class table could not be read); \
         [V]: read in a public source."
    );
    println!(
        "\nUse a name, a TOML file, or build one: `--excitation random --rms 1.0 --band 0.5,80`, \
         `--excitation sine --freq 4 --amplitude 1`, `--excitation road --road-class C --speed 20`, \
         `--excitation recorded --input run.csv`, `--excitation psd --input psd.csv`."
    );
    Ok(())
}

pub fn export(args: ExportArgs) -> wbv::Result<()> {
    let overwrite = Overwrite::from_force(args.force);
    // Refuse an overwrite before any work.
    wbv::io::atomic::check_overwrite(&args.out, overwrite)?;
    let spec = resolve(&args.excitation)?;
    if !(args.duration.is_finite() && args.duration > 0.0) {
        return Err(Error::parameter(
            "--duration",
            format!("{} s must be positive", args.duration),
        ));
    }
    let n = (args.duration / args.dt).round() as usize;
    let mut exc = wbv::measurement::excitation(&spec, args.dt, args.duration, args.seed)?;
    let mut samples = vec![0.0; n];
    exc.fill(&mut samples);
    let mut signals = Signals::new(1.0 / args.dt, exc.describe());
    signals.push("a_base_z", samples)?;
    csv_run::write(&args.out, &signals, overwrite)?;
    eprintln!(
        "wrote {} samples of {} to {}",
        n,
        exc.describe(),
        args.out.display()
    );
    if args.json {
        let files = Files::new(vec![Written::of(&args.out)?])
            .with("samples", n)
            .with("sample_rate_hz", 1.0 / args.dt)
            .with("duration_s", args.duration)
            .with("seed", args.seed)
            .with("excitation", exc.describe());
        super::print_json("excitation-export", &files, &[])?;
    }
    Ok(())
}
