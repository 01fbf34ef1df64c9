//! `wbv fmu`: an FMI 2.0 Co-Simulation FMU of a model ([`wbv::fmu::package`], docs/fmu.md).

use std::path::{Path, PathBuf};
use wbv::error::Error;
use wbv::io::atomic::Overwrite;

/// The compiled FMI library's file name.
const LIBRARY: &str = "libwbv_fmu.so";

/// Arguments of `wbv fmu`.
#[derive(Debug, clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    #[command(flatten)]
    model: super::ModelArg,
    /// The FMU to write (`seat.fmu`).
    #[arg(long)]
    out: PathBuf,
    /// Set a parameter (a path of `wbv models --params`) to a value in SI units, e.g.
    /// `--param mass.head.m=5.2`; repeatable. It becomes the FMI parameter's start value.
    #[arg(long = "param", value_name = "PATH=VALUE")]
    params: Vec<String>,
    /// Internal fixed step in s (at most 1/320 s: the running Wk-weighted output needs 320 Hz).
    #[arg(long, default_value_t = 1e-3)]
    dt: f64,
    /// Integrator: newmark, newmark-linear or rk4.
    #[arg(long, default_value = "newmark")]
    integrator: String,
    /// The compiled FMI library to pack (default: libwbv_fmu.so next to the wbv executable).
    #[arg(long, value_name = "FILE")]
    library: Option<PathBuf>,
    /// Replace an existing FMU.
    #[arg(long)]
    force: bool,
    /// Print what was written as JSON (`written`, `guid`, `model_identifier`, `variables`).
    #[arg(long)]
    json: bool,
}

/// `PATH=VALUE` as `(path, value)`.
fn parse_param(text: &str) -> wbv::Result<(String, f64)> {
    let bad = || {
        Error::parameter(
            "--param",
            format!("`{text}`; expected PATH=VALUE with a number, e.g. mass.head.m=5.2"),
        )
    };
    let (path, value) = text.split_once('=').ok_or_else(bad)?;
    let value: f64 = value.trim().parse().map_err(|_| bad())?;
    Ok((path.trim().to_string(), value))
}

/// The compiled library: `--library`, else `libwbv_fmu.so` next to the executable, else in the
/// `target/release` of the checkout this `wbv` was built from (after `cargo install --path .`).
fn library(given: Option<&Path>) -> wbv::Result<PathBuf> {
    if let Some(p) = given {
        return if p.is_file() {
            Ok(p.to_path_buf())
        } else {
            Err(Error::parameter(
                "--library",
                format!("{} does not exist", p.display()),
            ))
        };
    }
    let exe = std::env::current_exe().map_err(|e| Error::io("wbv executable", e))?;
    let candidates = [
        exe.parent().map(|d| d.join(LIBRARY)),
        Some(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("target/release")
                .join(LIBRARY),
        ),
    ];
    candidates
        .into_iter()
        .flatten()
        .find(|p| p.is_file())
        .ok_or_else(|| {
            Error::parameter(
                "fmu",
                format!(
                    "the FMI library {LIBRARY} is not next to {}; build it with `cargo build --release -p wbv-fmu` in the wbv checkout (or pass --library FILE)",
                    exe.display()
                ),
            )
        })
}

/// Writes the FMU.
pub fn run(args: Args) -> wbv::Result<()> {
    let overwrite = Overwrite::from_force(args.force);
    // Refuse an overwrite before any work.
    wbv::io::atomic::check_overwrite(&args.out, overwrite)?;
    let params = args
        .params
        .iter()
        .map(|p| parse_param(p))
        .collect::<wbv::Result<Vec<_>>>()?;
    let lib = library(args.library.as_deref())?;
    let request = wbv::fmu::package::Request {
        model: &args.model.name,
        params: &params,
        dt: args.dt,
        integrator: &args.integrator,
        library: &lib,
    };
    let written = wbv::fmu::package::write(&args.out, &request, overwrite)?;
    eprintln!(
        "wrote {} (FMI 2.0 Co-Simulation, {} variables of which {} parameters, GUID {})",
        args.out.display(),
        written.variables,
        written.parameters,
        written.guid
    );
    if args.json {
        let files = wbv::report::json::Files::new(vec![wbv::report::json::Written::of(&args.out)?])
            .with("model", &args.model.name)
            .with("guid", &written.guid)
            .with("model_identifier", &written.model_identifier)
            .with("variables", written.variables)
            .with("parameters", written.parameters);
        super::print_json("fmu", &files, &[])?;
    }
    Ok(())
}
