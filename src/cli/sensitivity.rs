use super::sweep::{progress, sibling};
use std::path::PathBuf;
use wbv::error::Error;
use wbv::io::atomic::{Overwrite, write_atomic};
use wbv::report::json::{Sensitivity, Written};
use wbv::response::frf;
use wbv::study::param::{Param, parse_values};
use wbv::study::sensitivity;
use wbv::study::shard::Shard;

/// Arguments of `wbv sensitivity`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    model: super::ModelArg,
    /// Parameter to perturb (repeat).
    #[arg(long = "param", required = true)]
    params: Vec<String>,
    /// Levels in % of the model's value (paper 000: −30, 0, +30).
    #[arg(long, default_value = "-30,0,30", allow_hyphen_values = true)]
    levels: String,
    /// Response: stht, seat, apms, dpmi or t_<mass>; models with fore-and-aft motion also seat_x (v-h), head_z,
    /// head_x, apms_z, apms_x and t_<coordinate>.
    #[arg(long, default_value = "seat")]
    response: String,
    /// Lowest frequency in Hz.
    #[arg(long, default_value_t = 0.5)]
    from: f64,
    /// Highest frequency in Hz.
    #[arg(long, default_value_t = 20.0)]
    to: f64,
    /// Number of frequency points (linear grid).
    #[arg(long, default_value_t = 800)]
    points: usize,
    /// CSV `point,param,level_pct,value,peak_freq_hz,peak_mag`; the weights go to
    /// `<stem>-weights.csv` (not for shards: merge first, then `--weights-of`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Run only shard K of N.
    #[arg(long)]
    shard: Option<String>,
    /// Replace existing output files.
    #[arg(long)]
    force: bool,
    /// Print the rows and influence weights as JSON (`rows`, `influence`, `written`) instead of
    /// CSV.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    let ow = Overwrite::from_force(args.force);
    // Refuse an overwrite before any work (the weights file is written for unsharded runs only).
    if let Some(out) = &args.out {
        wbv::io::atomic::check_overwrite(out, ow)?;
        if args.shard.is_none() {
            wbv::io::atomic::check_overwrite(&sibling(out, "-weights"), ow)?;
        }
    }
    let model = args.model.resolve()?;
    let params = args
        .params
        .iter()
        .map(|p| Param::parse(p, &model))
        .collect::<wbv::Result<Vec<_>>>()?;
    let levels = parse_values(&args.levels, "--levels")?;
    let freq = frf::grid(args.from, args.to, args.points, false)?;
    let shard = args
        .shard
        .as_deref()
        .map(Shard::parse)
        .transpose()?
        .unwrap_or_default();
    let bar = progress(shard.points(params.len() * levels.len()).len());
    bar.set_position(0);
    let rows = sensitivity::run(&model, &params, &levels, &args.response, &freq, shard)?;
    bar.finish_and_clear();
    let mut written = Vec::new();
    if let Some(out) = &args.out {
        write_atomic(out, ow, |w| {
            sensitivity::write(&rows, w).map_err(|e| Error::io(out, e))
        })?;
        written.push(Written::of(out)?);
    }
    let inf = if shard.count > 1 {
        Vec::new()
    } else {
        sensitivity::influence(&rows)
    };
    if shard.count > 1 && !args.json {
        return Ok(());
    }
    let mut table = String::from("param,peak_freq_range_pct,peak_mag_range_pct,weight\n");
    for i in &inf {
        table += &format!(
            "{},{:.4},{:.4},{:.4}\n",
            i.param, i.freq_range_pct, i.mag_range_pct, i.weight
        );
    }
    match &args.out {
        Some(out) if shard.count <= 1 => {
            let p = sibling(out, "-weights");
            write_atomic(&p, ow, |w| {
                std::io::Write::write_all(w, table.as_bytes()).map_err(|e| Error::io(&p, e))
            })?;
            written.push(Written::of(&p)?);
        }
        _ if args.json => {}
        Some(_) => {}
        None => {
            let mut so = std::io::stdout().lock();
            sensitivity::write(&rows, &mut so).map_err(|e| Error::io("stdout", e))?;
            std::io::Write::write_all(&mut so, format!("\n{table}").as_bytes())
                .map_err(|e| Error::io("stdout", e))?;
        }
    }
    if args.json {
        let mut out = Sensitivity::of(&model.name, &args.response, &rows, &inf);
        out.written = written;
        super::print_json("sensitivity", &out, &[])?;
    }
    Ok(())
}
