use std::path::PathBuf;
use wbv::record::inspect;

/// Arguments of `wbv inspect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// A run recorded by wbv: its directory under `runs/` or the `.mcap` file.
    run: PathBuf,
    /// Print the summary as JSON (`path`, `duration_s`, `topics`, `provenance`, `results`,
    /// `attachments`).
    #[arg(long)]
    json: bool,
}

/// Metadata keys shown first, in this order; the model TOML is summarised, not printed.
const RUN_KEYS: [&str; 12] = [
    "model",
    "excitation",
    "integrator",
    "dt_s",
    "seed",
    "duration_s",
    "sample_rate_hz",
    "anti_alias",
    "scene_rate_hz",
    "display_magnification",
    "wbv_version",
    "command_line",
];

pub fn run(args: Args) -> wbv::Result<()> {
    let s = inspect(&wbv::record::run_file(&args.run))?;
    if args.json {
        return super::print_json("inspect", &wbv::report::json::Inspected::of(&s), &[]);
    }
    println!("{}  ({})", s.path.display(), s.library);
    // Divided, not multiplied by 1e-9: 6e10 ns prints as 60, not 60.00000000000001.
    let duration = s.end_ns.saturating_sub(s.start_ns) as f64 / 1e9;
    println!(
        "duration: {duration} s (log time {} … {} ns)",
        s.start_ns, s.end_ns
    );
    println!("channels:");
    let width = s.topics.iter().map(|t| t.topic.len()).max().unwrap_or(0);
    for t in &s.topics {
        println!(
            "  {:width$}  {:>9} msgs  {} ({})",
            t.topic, t.messages, t.schema, t.message_encoding
        );
    }
    if let Some(run) = s.metadata.get("wbv.run") {
        println!("provenance:");
        for k in RUN_KEYS {
            if let Some(v) = run.get(k) {
                println!("  {k}: {v}");
            }
        }
    }
    if let Some(model) = s.metadata.get("wbv.model") {
        let lines = model.get("toml").map_or(0, |t| t.lines().count());
        println!("  model TOML: {lines} lines (attachment model.toml)");
    }
    if let Some(results) = s.metadata.get("wbv.results") {
        let names: Vec<&str> = results.keys().map(String::as_str).collect();
        println!("results: {}", names.join(", "));
    }
    println!("attachments:");
    for (name, media, size) in &s.attachments {
        println!("  {name}  {media}  {size} bytes");
    }
    Ok(())
}
