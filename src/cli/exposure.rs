use wbv::analysis::exposure::ShockSettings;
use wbv::analysis::spine::{History, Sex};
use wbv::report::exposure::OperationSpec;

/// ISO 2631-5 options shared by `analyze`, `report` and `exposure`.
#[derive(Debug, Clone, clap::Args)]
pub struct ShockArgs {
    /// Assess shocks by ISO 2631-5:2018 (spinal dose D_z, D_zd, S_ed, R) even when the seat's crest
    /// factor is not above 9 (above 9 they are always assessed).
    #[arg(long = "iso2631-5")]
    pub iso2631_5: bool,
    /// ISO 2631-5 Annex C person: male (82 kg, m_z 0.029 MPa per m/s²) or female (64 kg, 0.025).
    #[arg(long, default_value = "male")]
    pub spine_sex: String,
    /// ISO 2631-5 Annex C: age at which the exposure began, years.
    #[arg(long, default_value_t = History::default().start_age_years)]
    pub spine_start_age: f64,
    /// ISO 2631-5 Annex C: years of exposure.
    #[arg(long, default_value_t = History::default().years)]
    pub spine_years: u32,
    /// ISO 2631-5 Annex C: exposure days a year.
    #[arg(long, default_value_t = History::default().days_per_year)]
    pub spine_days_per_year: f64,
}

impl ShockArgs {
    /// The library's settings, or the option that is wrong.
    pub fn settings(&self) -> wbv::Result<ShockSettings> {
        let history = History {
            sex: Sex::parse(&self.spine_sex)?,
            start_age_years: self.spine_start_age,
            years: self.spine_years,
            days_per_year: self.spine_days_per_year,
        };
        history.validate()?;
        Ok(ShockSettings {
            requested: self.iso2631_5,
            history,
        })
    }
}

/// Arguments of `wbv exposure`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// One operation of the day: a measurement or run (any file `wbv analyze` reads) and its hours
    /// a day, `FILE_OR_RUN:HOURS`. Repeat for each operation.
    #[arg(long = "operation", value_name = "FILE_OR_RUN:HOURS", required = true)]
    operations: Vec<String>,
    #[command(flatten)]
    input: wbv::io::input::InputArgs,
    #[command(flatten)]
    shocks: ShockArgs,
    /// Print the day as JSON (`a8`, `vdv_day`, `zone`, `operations`, `axes`, `iso2631_5`, units).
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    let specs = args
        .operations
        .iter()
        .map(|s| OperationSpec::parse(s))
        .collect::<wbv::Result<Vec<_>>>()?;
    let shocks = args.shocks.settings()?;
    let (day, notes) = wbv::report::exposure::day(&specs, &args.input.options()?, &shocks)?;
    if args.json {
        super::print_document(&wbv::report::json::exposure(day, notes)?);
        return Ok(());
    }
    for n in &notes {
        eprintln!("input: {n}");
    }
    print_day(&day);
    Ok(())
}

fn print_day(day: &wbv::analysis::exposure::Day) {
    let t = wbv::analysis::health::hours_text;
    println!(
        "  {:<28} {:>6} {:>9} {:>23} {:>23} {:>7} {:>9}",
        "operation",
        "hours",
        "measured",
        "k·a_w x/y/z m/s²",
        "k·VDV x/y/z m/s^1.75",
        "A(8)² %",
        "alone: EAV"
    );
    for r in &day.operations {
        println!(
            "  {:<28} {:>6.2} {:>8.0}s {:>23} {:>23} {:>6.0}% {:>9}",
            r.name,
            r.hours,
            r.measured_s,
            r.per_axis(|a| a.k_a_w, 3, "/"),
            r.per_axis(|a| a.k_vdv, 2, "/"),
            100.0 * r.a8_share,
            t(r.hours_to_a8_action)
        );
    }
    println!();
    println!(
        "  {:<4} {:>4} {:>12} {:>15}",
        "axis", "k", "A(8) m/s²", "VDV m/s^1.75"
    );
    for a in &day.axes {
        println!(
            "  {:<4} {:>4.1} {:>12.3} {:>15.2}",
            a.axis, a.k, a.a8, a.vdv
        );
    }
    println!();
    for line in day.statement() {
        println!("{line}");
    }
    for n in &day.notes {
        println!("note: {n}");
    }
}
