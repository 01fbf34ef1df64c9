use std::path::PathBuf;
use wbv::io::atomic::Overwrite;
use wbv::report::{Settings, default_path, write};

/// Arguments of `wbv report`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Run or measurement: a wbv MCAP run or run directory, or any file `wbv analyze` reads
    /// (delimited text, WAV, MAT, UFF58, another logger's MCAP with --topic; docs/inputs.md).
    run: PathBuf,
    #[command(flatten)]
    input: wbv::io::input::InputArgs,
    #[command(flatten)]
    shocks: super::exposure::ShockArgs,
    /// Add a working-day section from these operations (`FILE_OR_RUN:HOURS`, repeat; as for
    /// `wbv exposure`); list the reported run too if it is one of them.
    #[arg(long = "operation", value_name = "FILE_OR_RUN:HOURS")]
    operations: Vec<String>,
    /// Output HTML file (default: `report.html` beside the run's MCAP, `<stem>-report.html`
    /// beside a CSV).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    exposure: super::ExposureArg,
    /// Replace an existing report.
    #[arg(long)]
    force: bool,
    /// Add a gap section from this sim-to-real gap diagnosis (the output of `wbv gap --json`);
    /// without it, a `gap.json` in the run directory is used when there is one.
    #[arg(long, value_name = "FILE")]
    gap: Option<PathBuf>,
    /// Print a JSON summary (`report_html`, `bytes`, `total_value`, `comfort`, `health`, `gap`,
    /// `iso2631_5`, `exposure`, `units`) on stdout instead of the path.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    let out = args.out.clone().unwrap_or_else(|| default_path(&args.run));
    let settings = Settings {
        exposure_hours: args.exposure.hours()?,
        gap: args.gap.clone(),
        input: args.input.options()?,
        operations: args
            .operations
            .iter()
            .map(|s| wbv::report::exposure::OperationSpec::parse(s))
            .collect::<wbv::Result<Vec<_>>>()?,
        shocks: args.shocks.settings()?,
    };
    let built = write(
        &args.run,
        &out,
        &settings,
        Overwrite::from_force(args.force),
    )?;
    if args.json {
        let summary = wbv::report::json::ReportSummary::of(&out, &built)?;
        let warnings: Vec<String> = built
            .report
            .warnings
            .iter()
            .cloned()
            .chain(built.input_notes.iter().map(|n| format!("input: {n}")))
            .collect();
        return super::print_json("report", &summary, &warnings);
    }
    for w in &built.report.warnings {
        eprintln!("WARNING: {w}");
    }
    if let Some(a) = built.report.unit_assumption() {
        eprintln!("UNIT NOT DECLARED: every figure and verdict of the report {a}");
    }
    for n in &built.input_notes {
        eprintln!("input: {n}");
    }
    println!("{}", out.display());
    Ok(())
}
