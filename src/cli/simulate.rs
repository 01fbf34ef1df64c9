use crate::excitation::{ExcitationArgs, args::resolve};
use crate::integrator::Method;
use crate::io::atomic::Overwrite;
use crate::io::csv_run::CsvWriter;
use crate::model::catalog;
use crate::scenario::Scenario;
use crate::simulate::Settings;
use crate::simulate::observer::Observer;
use std::path::PathBuf;

/// Arguments of `wbv simulate`.
#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Model: a built-in name, a TOML file, or components joined by `+`.
    #[arg(long, default_value = catalog::DEFAULT)]
    pub model: String,
    #[command(flatten)]
    pub excitation: ExcitationArgs,
    /// Simulated duration in s.
    #[arg(long, default_value_t = 60.0)]
    pub duration: f64,
    /// Time step in s.
    #[arg(long, default_value_t = 1e-3)]
    pub dt: f64,
    /// Seed of the random excitation.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Integrator: newmark (average acceleration), newmark-linear or rk4.
    #[arg(long, default_value = "newmark")]
    pub integrator: String,
    /// Also write the measured-run channels (t_s, a_base_z, a_seat_z, a_head_z, f_seat_z) as CSV.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Replace existing outputs.
    #[arg(long)]
    pub force: bool,
}

impl Args {
    /// The scenario these arguments describe.
    pub fn scenario(&self) -> crate::Result<Scenario> {
        Ok(Scenario {
            model: catalog::resolve(&self.model)?,
            excitation: resolve(&self.excitation)?,
            settings: Settings {
                dt: self.dt,
                duration_s: self.duration,
                method: Method::parse(&self.integrator)?,
            },
            seed: self.seed,
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

pub fn run(args: Args) -> crate::Result<()> {
    let scenario = args.scenario()?;
    let overwrite = Overwrite::from_force(args.force);
    let mut csv = match &args.csv {
        Some(p) => Some(CsvWriter::create(p, overwrite)?),
        None => None,
    };
    let mut observers: Vec<&mut dyn Observer> = Vec::new();
    if let Some(c) = csv.as_mut() {
        observers.push(c);
    }
    let bar = progress(scenario.settings.steps());
    let start = std::time::Instant::now();
    scenario.simulate(&mut observers, Some(&bar))?;
    for o in observers.iter_mut() {
        o.end()?;
    }
    bar.finish_and_clear();
    println!(
        "simulated {} s of `{}` under {} with {} in {:.2} s",
        scenario.settings.duration_s,
        scenario.model.name,
        scenario.excitation.summary(),
        scenario.settings.method.name(),
        start.elapsed().as_secs_f64()
    );
    if let Some(p) = &args.csv {
        println!("wrote {}", p.display());
    }
    Ok(())
}
