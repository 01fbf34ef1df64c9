//! `wbv state-space` and `wbv weighting`: the linear operators wbv uses, as JSON, so that another
//! tool (scipy, MATLAB, a DAQ) can run exactly the same model or filter — `tools/bench-peers` uses
//! them to compare wbv with scipy on identical work.

use serde_json::json;
use std::io::Write;
use std::path::PathBuf;
use wbv::analysis::{Weighting, WeightingFilter};
use wbv::error::Error;
use wbv::io::atomic::{Overwrite, write_atomic};
use wbv::report::json::{Files, Written};

/// Arguments of `wbv state-space`.
#[derive(Debug, clap::Args)]
pub struct StateSpaceArgs {
    #[command(flatten)]
    model: super::ModelArg,
    /// Write the JSON here instead of standard output.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Replace an existing output file.
    #[arg(long)]
    force: bool,
    /// The one JSON document of every command: the matrices with `command` and `warnings` added,
    /// or with --out, what was written (`written`, `model`, `states`).
    #[arg(long)]
    json: bool,
}

/// Arguments of `wbv weighting`.
#[derive(Debug, clap::Args)]
pub struct WeightingArgs {
    /// ISO 2631-1 / ISO 8041 weighting: Wk, Wd, Wf, Wc, We, Wj, Wb, Wm or band-limiting.
    #[arg(long, default_value = "wk")]
    weighting: String,
    /// Sample rate in Hz.
    #[arg(long, default_value_t = 1000.0)]
    fs: f64,
    /// The output is JSON either way; with --json it also has the `command` and `warnings` keys
    /// of every command's document.
    #[arg(long)]
    json: bool,
}

/// Writes `value` to `out` (then, with `json`, prints what was written) or prints it (as the
/// command's JSON document with `json`).
fn emit(
    command: &str,
    value: &serde_json::Value,
    out: &Option<PathBuf>,
    force: bool,
    json: bool,
) -> wbv::Result<()> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::parameter(command, e.to_string()))?;
    match out {
        Some(p) => {
            write_atomic(p, Overwrite::from_force(force), |w| {
                w.write_all(text.as_bytes()).map_err(|e| Error::io(p, e))
            })?;
            eprintln!("wrote {}", p.display());
            if json {
                let files = Files::new(vec![Written::of(p)?])
                    .with("model", &value["model"])
                    .with("states", value["states"].as_array().map_or(0, |s| s.len()));
                super::print_json(command, &files, &[])?;
            }
        }
        None if json => super::print_json(command, value, &[])?,
        None => println!("{text}"),
    }
    Ok(())
}

/// Prints `ẏ = A·y + B·a_base`, `a_abs = C·y` (absolute mass accelerations; D = 0) of the model
/// linearised at rest ([`wbv::system::System::state_space`]).
pub fn state_space(args: StateSpaceArgs) -> wbv::Result<()> {
    if let Some(out) = &args.out {
        // Refuse an overwrite before any work.
        wbv::io::atomic::check_overwrite(out, Overwrite::from_force(args.force))?;
    }
    let model = args.model.resolve()?;
    let system = model.system();
    let ss = system.state_space();
    let n = ss.n;
    let rows = |m: &nalgebra::DMatrix<f64>, r: std::ops::Range<usize>| -> Vec<Vec<f64>> {
        r.map(|i| m.row(i).iter().copied().collect()).collect()
    };
    // Absolute acceleration of mass i = ẍ_i + a_base = A[n+i,:]·y + (B[n+i] + 1)·a_base, and
    // B[n+i] = −1, so the feed-through is zero.
    let c = rows(&ss.a, n..2 * n);
    let mut states: Vec<String> = Vec::new();
    for prefix in ["x", "v"] {
        states.extend(system.dofs.iter().map(|m| format!("{prefix}_{}", m.name)));
    }
    states.extend(
        ss.arms
            .iter()
            .map(|&l| format!("q_{}", system.links[l].name)),
    );
    // The coordinate a channel reads alone (a mass's absolute acceleration), if it does.
    let name_of = |channel: &str| {
        let c = &system.channels[system.channel_index(channel)?];
        match &c.rule {
            wbv::system::Rule::Kinematic { row, base } if *base == 0.0 && row.len() == 1 => {
                Some(system.dofs[row[0].0].name.clone())
            }
            _ => None,
        }
    };
    let text = json!({
        "model": model.name,
        "description": "xdot = A x + B u, y = C x (+ D u, D = 0); u = base acceleration (m/s^2); \
                        states: displacements (m) and velocities (m/s) relative to the base, then \
                        relaxing-arm forces (N); outputs: absolute accelerations of the masses (m/s^2)",
        "states": states,
        "outputs": system.dofs.iter().map(|m| format!("a_{}", m.name)).collect::<Vec<_>>(),
        "seat_mass": name_of("a_seat_z"),
        "head_mass": name_of("a_head_z"),
        "A": rows(&ss.a, 0..ss.a.nrows()),
        "B": ss.b.iter().collect::<Vec<_>>(),
        "C": c,
    });
    emit("state-space", &text, &args.out, args.force, args.json)
}

/// Prints the digital filter of a weighting as second-order sections in scipy's `sos` layout
/// `[b0, b1, b2, 1, a1, a2]` ([`wbv::analysis::filter`]).
pub fn weighting(args: WeightingArgs) -> wbv::Result<()> {
    let w = Weighting::parse(&args.weighting).ok_or_else(|| {
        Error::parameter(
            "weighting",
            format!(
                "`{}`: expected one of {}",
                args.weighting,
                Weighting::ALL.map(Weighting::name).join(", ")
            ),
        )
    })?;
    let f = WeightingFilter::new(w, args.fs)?;
    let sos: Vec<[f64; 6]> = f
        .sections
        .iter()
        .map(|s| [s.b[0], s.b[1], s.b[2], 1.0, s.a[0], s.a[1]])
        .collect();
    let text = json!({"weighting": w.name(), "fs_hz": args.fs, "sos": sos});
    emit("weighting", &text, &None, false, args.json)
}
