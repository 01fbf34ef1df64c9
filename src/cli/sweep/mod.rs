use std::path::{Path, PathBuf};
use wbv::error::Error;
use wbv::excitation::ExcitationArgs;
use wbv::io::atomic::{Overwrite, write_atomic};
use wbv::report::json::{Files, Written};
use wbv::response::frf;
use wbv::study::iso::IsoRun;
use wbv::study::param::{Param, parse_values};
use wbv::study::plan::Plan;
use wbv::study::shard::{self, Shard};
use wbv::study::sweep::{self, Spec};

mod plots;

use plots::{iso_plot, plot_paths, plots};

/// Arguments of `wbv sweep`.
#[derive(Debug, clap::Args)]
#[command(
    allow_negative_numbers = true,
    // The excitation's default applies only once another excitation option is given: without
    // any, the sweep has no ISO columns, so no default is shown.
    mut_arg("excitation", |a| a.hide_default_value(true).help(
        "Excitation of the ISO figures: a built-in name (`wbv excitations`), a TOML file, or \
         random | psd | road | recorded | sine | sweep built from the options below. Without any \
         excitation option the sweep gives responses and peaks only, no ISO figures"
    )),
)]
pub struct Args {
    #[command(flatten)]
    model: super::ModelArg,
    /// Swept parameter (repeat for a 2-D grid): `link.cushion.k`, or `link.cushion.zeta@60` for a
    /// damping ratio referred to 60 kg (`c = 2ζ√(k·60)`).
    #[arg(long = "param", required = true)]
    params: Vec<String>,
    /// Values of each parameter, in order: `from:to:count` or `a,b,c`.
    #[arg(long = "values", required = true, allow_hyphen_values = true)]
    values: Vec<String>,
    /// Response: stht, seat, apms, dpmi or t_<mass>; models with fore-and-aft motion also seat_x (v-h), head_z,
    /// head_x, apms_z, apms_x and t_<coordinate>.
    #[arg(long, default_value = "stht")]
    response: String,
    /// Lowest frequency in Hz.
    #[arg(long, default_value_t = 0.5)]
    from: f64,
    /// Highest frequency in Hz.
    #[arg(long, default_value_t = 20.0)]
    to: f64,
    /// Number of frequency points (linear grid).
    #[arg(long, default_value_t = 400)]
    points: usize,
    /// Long-format CSV `point,<params>,freq_hz,mag,phase_deg`; the peaks table goes to
    /// `<stem>-peaks.csv` beside it. Peaks are printed when omitted.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write plots into this directory: `curves` (every curve, coloured by value), `heatmap` and,
    /// with an excitation, `iso` (ISO 2631-1 figures with the Annex C comfort ranges).
    #[arg(long, value_name = "DIR")]
    plot: Option<PathBuf>,
    /// Plot file format.
    #[arg(long, default_value = "png", value_parser = ["png", "svg"])]
    plot_format: String,
    /// Run only shard K of N (`K/N`); merge the outputs with `wbv merge-shards`.
    #[arg(long)]
    shard: Option<String>,
    /// Replace existing output files.
    #[arg(long)]
    force: bool,
    /// Print the peaks table as JSON (`points`: values, peak, ISO `figures`; `path`; `written`;
    /// `elapsed_s` and `seconds_per_point`) instead of CSV.
    #[arg(long)]
    json: bool,
    /// Compute the ISO figures by simulating every point (batched, same seed at every point),
    /// which adds VDV, MTVV and crest factor of the seat; without it a linear model under a
    /// stationary excitation gets a_w, a_v, SEAT and comfort from the excitation's spectrum.
    #[arg(long)]
    time_domain: bool,
    /// With any excitation option, every point's ISO 2631-1 figures (a_w seat, a_v, SEAT,
    /// comfort) join the peaks table: from the spectrum for a linear model under a stationary
    /// excitation, else (or with --time-domain) simulated with the same seed at every point.
    #[command(
        flatten,
        next_help_heading = "ISO 2631-1 figures (given an excitation; from its spectrum for a \
                             linear model under a stationary excitation, else simulated)"
    )]
    excitation: Option<ExcitationArgs>,
    #[command(
        flatten,
        next_help_heading = "Simulated run of the ISO figures (with --time-domain, a nonlinear \
                             model or a non-stationary excitation)"
    )]
    time: Option<super::TimeArgs>,
}

/// Arguments of `wbv merge-shards`.
#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// Shard CSV files (any order).
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Merged output file.
    #[arg(long)]
    out: PathBuf,
    /// Replace an existing output file.
    #[arg(long)]
    force: bool,
    /// Print what was written as JSON (`written`, `shards`).
    #[arg(long)]
    json: bool,
}

fn overwrite(force: bool) -> Overwrite {
    if force {
        Overwrite::Allow
    } else {
        Overwrite::Refuse
    }
}

/// `<dir>/<stem><suffix>.<ext>` beside `path`.
pub(crate) fn sibling(path: &Path, suffix: &str) -> PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    path.with_file_name(format!("{stem}{suffix}{ext}"))
}

/// A progress bar on stderr, hidden when stderr is not a terminal.
pub(crate) fn progress(len: usize) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(len as u64),
        indicatif::ProgressDrawTarget::stderr(),
    );
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} points, {eta} left")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

pub fn run(args: Args) -> wbv::Result<()> {
    let ow = overwrite(args.force);
    // Every output is checked before the sweep runs, so a refusal costs nothing.
    let plot_files = match &args.plot {
        Some(dir) => {
            let (dir, ext) = wbv::plot::plot_dir(dir, &args.plot_format)?;
            let files = plot_paths(&dir, ext, args.excitation.is_some());
            wbv::plot::check_targets(&files, ow)?;
            Some(files)
        }
        None => None,
    };
    if let Some(out) = &args.out {
        wbv::io::atomic::check_overwrite(out, ow)?;
        wbv::io::atomic::check_overwrite(&sibling(out, "-peaks"), ow)?;
    }
    if args.plot.is_some() && args.shard.is_some() {
        return Err(Error::parameter(
            "--plot",
            "plot the merged output, not a shard",
        ));
    }
    let model = args.model.resolve()?;
    if args.params.len() != args.values.len() {
        return Err(Error::parameter(
            "--values",
            "give one --values per --param, in the same order",
        ));
    }
    let params = args
        .params
        .iter()
        .map(|p| Param::parse(p, &model))
        .collect::<wbv::Result<Vec<_>>>()?;
    let values = args
        .values
        .iter()
        .map(|v| parse_values(v, "--values"))
        .collect::<wbv::Result<Vec<_>>>()?;
    let spec = Spec {
        params,
        values,
        response: args.response.clone(),
        freq_hz: frf::grid(args.from, args.to, args.points, false)?,
    };
    let shard = args
        .shard
        .as_deref()
        .map(Shard::parse)
        .transpose()?
        .unwrap_or_default();
    let iso = match (&args.excitation, &args.time) {
        (Some(e), time) => {
            let time = time.clone().unwrap_or_default();
            Some(IsoRun {
                excitation: wbv::excitation::resolve(e)?,
                settings: time.settings()?,
                seed: time.seed,
            })
        }
        (None, Some(_)) => {
            return Err(Error::parameter(
                "--excitation",
                "--duration, --dt, --seed and --integrator set the time-domain run; give an \
                 excitation too",
            ));
        }
        (None, None) => None,
    };
    let plan = Plan::new(&model, spec, iso.as_ref(), args.time_domain)?;
    let spec = &plan.spec;
    let bar = progress(shard.points(spec.grid().len()).len());
    let start = std::time::Instant::now();
    let pts = plan.run(&model, shard, &|| bar.inc(1))?;
    let elapsed_s = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let hooks = plan.hooks();
    // Status lines once the sweep has run, so that an error is the only line of a failed one.
    if let Some(p) = plan.path() {
        let ignored = if p.is_spectral() && args.time.is_some() {
            "; --duration, --dt, --seed and --integrator set a simulation, which the spectral \
             figures do not need (give --time-domain to simulate)"
        } else {
            ""
        };
        eprintln!("ISO figures: {p}{ignored}");
    }
    let per_point_s = elapsed_s / pts.len().max(1) as f64;
    eprintln!(
        "timing: {} points in {elapsed_s:.3} s ({:.3} ms a point, {} threads)",
        pts.len(),
        1e3 * per_point_s,
        rayon::current_num_threads()
    );
    let mut written = Vec::new();
    match &args.out {
        Some(out) => {
            write_atomic(out, ow, |w| {
                sweep::write_long(spec, &pts, w).map_err(|e| Error::io(out, e))
            })?;
            let peaks = sibling(out, "-peaks");
            write_atomic(&peaks, ow, |w| {
                sweep::write_peaks(spec, &pts, &hooks, w).map_err(|e| Error::io(&peaks, e))
            })?;
            written = Written::existing(&[out.clone(), peaks])?;
        }
        None if args.json => {}
        None => sweep::write_peaks(spec, &pts, &hooks, &mut std::io::stdout().lock())
            .map_err(|e| Error::io("stdout", e))?,
    }
    if let Some(files) = &plot_files {
        plots(spec, &pts, &model.name, files, ow)?;
        if let (Some(iso), Some(path)) = (&iso, files.get(2)) {
            iso_plot(spec, &pts, &model.name, iso, path, ow)?;
        }
        for f in files.iter().filter(|f| f.exists()) {
            eprintln!("wrote {}", f.display());
        }
        written.extend(Written::existing(files)?);
    }
    if args.json {
        super::print_document(&wbv::report::json::sweep(
            &model.name,
            &plan,
            &pts,
            written,
            elapsed_s,
        )?);
    }
    Ok(())
}

pub fn merge(args: MergeArgs) -> wbv::Result<()> {
    // Refuse an overwrite before reading the shards.
    wbv::io::atomic::check_overwrite(&args.out, overwrite(args.force))?;
    let files: Vec<&Path> = args.files.iter().map(|p| p.as_path()).collect();
    let text = shard::merge(&files)?;
    write_atomic(&args.out, overwrite(args.force), |w| {
        std::io::Write::write_all(w, text.as_bytes()).map_err(|e| Error::io(&args.out, e))
    })?;
    if args.json {
        let files = Files::new(vec![Written::of(&args.out)?])
            .with("shards", args.files.len())
            .with("rows", text.lines().count().saturating_sub(1));
        super::print_json("merge-shards", &files, &[])?;
    }
    Ok(())
}
