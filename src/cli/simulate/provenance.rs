//! The command line a run records (normalised for provenance), and re-running a recorded run
//! from it (`wbv simulate --from RUN`).

use std::path::Path;
use wbv::record::{Compression, Encoding, MessageLayout, RecordOptions};
use wbv::scenario::Scenario;

/// The command line for provenance, normalised so that the same run gives the same bytes
/// wherever it is written and whichever binary ran it: program name `wbv`, and without the
/// output options `--out`, `--csv` (their values are paths of this machine), `--force` and
/// `--json` (how the result is printed).
pub fn command_line() -> String {
    normalise(std::env::args().skip(1))
}

/// Options that say where outputs go, not what is simulated or recorded; with their value.
const OUTPUT_OPTIONS: [&str; 2] = ["--out", "--csv"];

fn normalise(args: impl Iterator<Item = String>) -> String {
    let mut out = vec!["wbv".to_string()];
    let mut args = args.peekable();
    while let Some(a) = args.next() {
        let name = a.split('=').next().unwrap_or_default();
        if OUTPUT_OPTIONS.contains(&name) {
            if !a.contains('=') {
                args.next();
            }
        } else if a != "--force" && a != "--json" {
            out.push(a);
        }
    }
    out.join(" ")
}

/// The options `--from` accepts beside itself: outputs and timing, nothing that changes the run.
pub(super) fn check_from_alone(args: impl Iterator<Item = String>) -> wbv::Result<()> {
    let mut args = args.peekable();
    while let Some(a) = args.next() {
        let name = a.split('=').next().unwrap_or_default();
        let takes_value = OUTPUT_OPTIONS.contains(&name) || name == "--from";
        if takes_value {
            if !a.contains('=') {
                args.next();
            }
        } else if !["simulate", "--force", "--timing", "--json"].contains(&a.as_str()) {
            return Err(wbv::Error::parameter(
                a,
                "cannot be given with --from, which re-runs the recorded run exactly (only --out, \
                 --force, --csv and --timing may be added)",
            ));
        }
    }
    Ok(())
}

/// The integrator option value of a provenance's integrator name (`Method::name`).
fn integrator_option(name: &str) -> &str {
    if name.starts_with("newmark (linear") {
        "newmark-linear"
    } else if name.starts_with("rk4") {
        "rk4"
    } else {
        "newmark"
    }
}

/// The scenario, recording options and command line of a recorded run, for `--from`.
pub fn from_run(run: &Path) -> wbv::Result<(Scenario, RecordOptions, String)> {
    let path = wbv::record::run_file(run);
    let (p, meta) = wbv::record::read_provenance(&path)?;
    let bad = |key: &str| {
        wbv::Error::data(
            &path,
            None,
            format!("metadata `wbv.run.{key}` missing or invalid: cannot re-run"),
        )
    };
    let get = |key: &str| meta.get(key).ok_or_else(|| bad(key));
    let num = |key: &str| get(key)?.parse::<f64>().map_err(|_| bad(key));
    // A single model file is its TOML; a stack (`stack = [...]`) stores the texts of its parts,
    // which load again through the catalogue name, checked to give the same text.
    let model = match wbv::model::catalog::parse(&p.model_toml, &p.model) {
        Ok(mut m) => {
            m.name = p.model.clone();
            m
        }
        Err(e) => match wbv::model::catalog::resolve(&p.model) {
            Ok(m) if m.text == p.model_toml => m,
            _ => {
                return Err(wbv::Error::data(
                    &path,
                    None,
                    format!(
                        "the stored model TOML does not load again ({e}) and `{}` no longer \
                         resolves to the same text: cannot re-run exactly",
                        p.model
                    ),
                ));
            }
        },
    };
    let excitation = wbv::record::load_excitation(&p.excitation_origin, &p.excitation_definition)?;
    let settings = wbv::simulate::Settings {
        dt: p.dt,
        duration_s: p.duration,
        method: wbv::integrator::Method::parse(integrator_option(&p.integrator))?,
    };
    let (fs, rate) = (num("simulation_rate_hz")?, num("sample_rate_hz")?);
    let options = RecordOptions {
        encoding: Encoding::parse(get("encoding").map_or("json", |s| s.as_str()))?,
        compression: Compression::parse(get("compression")?)?,
        // runs from before the option were recorded per sample
        layout: Some(MessageLayout::parse(
            get("layout").map_or("per-sample", |s| s.as_str()),
        )?),
        record_rate_hz: (rate != fs).then_some(rate),
        scene_rate_hz: num("scene_rate_hz")?,
        magnification: num("display_magnification")?,
        ..RecordOptions::default()
    };
    let scenario = Scenario {
        model,
        excitation,
        settings,
        seed: p.seed.ok_or_else(|| bad("seed"))?,
    };
    Ok((scenario, options, p.command_line))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_command_line_leaves_out_where_outputs_go() {
        let args = |s: &str| {
            s.split(' ')
                .map(String::from)
                .collect::<Vec<_>>()
                .into_iter()
        };
        assert_eq!(
            normalise(args(
                "simulate --out /tmp/a --model reference --force --csv=x.csv --seed 2 --json"
            )),
            "wbv simulate --model reference --seed 2"
        );
        assert!(check_from_alone(args("simulate --from r --out x --force --timing")).is_ok());
        let e = check_from_alone(args("simulate --from r --out x --seed 3")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("--seed: cannot be given with --from"),
            "{e}"
        );
    }
}
