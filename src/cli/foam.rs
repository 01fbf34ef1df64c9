use wbv::error::Error;
use wbv::excitation::ExcitationArgs;
use wbv::study::foam::{Foam, FoamPoint, PAPER_TABLE_4, paper_run, thickness_study};
use wbv::study::iso::IsoRun;

/// Arguments of `wbv foam`.
#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    #[command(flatten)]
    model: super::ModelArg,
    /// Foam thicknesses in mm (paper 000 Table 4: 60, 80, 100).
    #[arg(long = "thickness", value_delimiter = ',', default_values_t = [60.0, 80.0, 100.0])]
    thickness_mm: Vec<f64>,
    /// Effective contact area of the buttocks on the foam in m² (default: 0.09, assumed).
    #[arg(long)]
    area: Option<f64>,
    /// Loss factor η of the foam (default: 0.2, assumed).
    #[arg(long)]
    loss_factor: Option<f64>,
    /// Frequency in Hz at which the viscous damping matches the loss factor (default: 4).
    #[arg(long)]
    f_ref: Option<f64>,
    /// Frequency domain only: skip the time-domain SEAT, a_v and comfort class.
    #[arg(long)]
    no_time_domain: bool,
    /// Print the table as JSON (`points` with the paper's values under `paper`).
    #[arg(long)]
    json: bool,
    /// Excitation of the time-domain figures (default: random 0.5–20 Hz, 0.4 m/s² r.m.s., the
    /// magnitude paper 000 states).
    #[command(flatten, next_help_heading = "Time-domain run")]
    excitation: Option<ExcitationArgs>,
    #[command(flatten, next_help_heading = "Time-domain run")]
    time: Option<super::TimeArgs>,
}

fn positive(v: Option<f64>, default: f64, flag: &str) -> wbv::Result<f64> {
    match v {
        None => Ok(default),
        Some(x) if x.is_finite() && x > 0.0 => Ok(x),
        Some(x) => Err(Error::parameter(flag, format!("{x}; expected > 0"))),
    }
}

/// The paper's value for thickness `t_m`, formatted, or `–`.
fn paper(t_m: f64, f: impl Fn(&wbv::study::foam::PaperRow) -> String) -> String {
    PAPER_TABLE_4
        .iter()
        .find(|p| (p.thickness_m - t_m).abs() < 1e-9)
        .map_or("–".into(), f)
}

fn print(points: &[FoamPoint]) {
    println!(
        "{:>6} {:>9} {:>9} {:>15} {:>13} {:>15} {:>17}  comfort (paper)",
        "t [mm]", "k [kN/m]", "c [Ns/m]", "f_peak [Hz]", "peak", "SEAT [%]", "a_v [m/s²]"
    );
    for s in points {
        let t = s.thickness_m;
        let (seat, av, comfort) = match &s.iso {
            Some(i) => (
                format!("{:.1}", i.seat_percent),
                format!("{:.3}", i.total_value),
                i.comfort.to_string(),
            ),
            None => ("–".into(), "–".into(), "–".into()),
        };
        println!(
            "{:>6.0} {:>9.1} {:>9.0} {:>6.2} ({:>6}) {:>5.2} ({:>5}) {:>6} ({:>6}) {:>7} ({:>7})  {comfort} ({})",
            t * 1000.0,
            s.k / 1000.0,
            s.c,
            s.peak.freq_hz,
            paper(t, |p| format!("{:.2}", p.peak_freq_hz)),
            s.peak.value,
            paper(t, |p| format!("{:.2}", p.peak)),
            seat,
            paper(t, |p| format!("{:.1}", p.seat_pct)),
            av,
            paper(t, |p| format!("{:.3}", p.wrmsa_m_s2)),
            paper(t, |p| p.comfort.to_string()),
        );
    }
}

pub fn run(args: Args) -> wbv::Result<()> {
    let model = args.model.resolve()?;
    let d = Foam::default();
    let foam = Foam {
        area_m2: positive(args.area, d.area_m2, "--area")?,
        loss_factor: positive(args.loss_factor, d.loss_factor, "--loss-factor")?,
        f_ref_hz: positive(args.f_ref, d.f_ref_hz, "--f-ref")?,
        ..d
    };
    let thicknesses: Vec<f64> = args.thickness_mm.iter().map(|t| t / 1000.0).collect();
    let iso = if args.no_time_domain {
        None
    } else {
        // Defaults: the documented Table 4 run.
        let paper = paper_run()?;
        let (settings, seed) = match &args.time {
            Some(t) => (t.settings()?, t.seed),
            None => (paper.settings, paper.seed),
        };
        Some(IsoRun {
            excitation: match &args.excitation {
                Some(e) => wbv::excitation::resolve(e)?,
                None => paper.excitation,
            },
            settings,
            seed,
        })
    };
    let points = thickness_study(&model, &foam, &thicknesses, iso.as_ref())?;
    if args.json {
        let table = wbv::report::json::Foam::of(&model.name, &foam, iso.as_ref(), &points);
        return super::print_json("foam", &table, &[]);
    }
    println!(
        "foam thickness study (paper 000 Table 4, v-v): `{}` on a hyperfoam layer, A = {} m², \
         η = {} at {} Hz; paper values in parentheses",
        model.name, foam.area_m2, foam.loss_factor, foam.f_ref_hz
    );
    if let Some(r) = &iso {
        println!(
            "time domain: {} s of {} (seed {}, same at every thickness)",
            r.settings.duration_s,
            r.excitation.summary(),
            r.seed
        );
    }
    print(&points);
    Ok(())
}
