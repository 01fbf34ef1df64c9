//! `wbv seat-test`: the ISO 10326-1 seat test on an input spectral class, simulated on a model or
//! applied to a lab's measured runs ([`wbv::study::seat_test`]).

use std::path::PathBuf;
use wbv::error::Error;
use wbv::io::atomic::Overwrite;
use wbv::study::seat_test::{self, Limits, Occupant, SeatTest, SeatTests, Settings, Verdict};

/// Arguments of `wbv seat-test`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The occupant on the seat to test: a built-in name (e.g. `scissor-seat`), a TOML file, or
    /// components joined by `+`. Not with --run.
    #[arg(long)]
    model: Option<String>,
    /// Input spectral class: iso7096-em1 … em9, en13490-it1 … it4, iso5007-ag1 … ag3 (`wbv
    /// excitations`). Repeat it, or give a comma-separated list, to test the seat on several
    /// classes in one report (simulated tests only).
    #[arg(long = "class", value_name = "CLASS[,CLASS…]", required = true)]
    classes: Vec<String>,
    /// Test person: light or heavy (default: both, as the standard asks).
    #[arg(long)]
    occupant: Option<String>,
    /// The application standard's SEAT limit (no verdict without a limit).
    #[arg(long)]
    seat_limit: Option<f64>,
    /// The application standard's damping-test transmissibility limit.
    #[arg(long)]
    damping_limit: Option<f64>,
    /// Most end-stop contacts allowed per 10 min of run, each test person (over the three runs
    /// used: count × 600 s / their total duration). Without it, impacts make a WARNING verdict.
    #[arg(long, value_name = "N")]
    contact_limit: Option<f64>,
    /// Duration of each simulated run in s.
    #[arg(long, default_value_t = seat_test::RUN_DURATION_S)]
    duration: f64,
    /// Time step in s.
    #[arg(long, default_value_t = 1e-3)]
    dt: f64,
    /// Seed of the first run (run i uses seed + i).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Skip the damping test.
    #[arg(long)]
    no_damping: bool,
    /// A lab's measured run (platform `a_base_z`, seat `a_seat_z`), in the order made; give it
    /// three or more times. Replaces the simulation.
    #[arg(long = "run", value_name = "FILE")]
    runs: Vec<PathBuf>,
    #[command(flatten)]
    input: wbv::io::input::InputArgs,
    /// Write the HTML report of the test here.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Replace an existing report.
    #[arg(long)]
    force: bool,
    /// Print the test as JSON (`class`, `runs`, `a_wp`, `a_ws`, `seat`, `a_ws_corrected`,
    /// `psd_within_tolerance`, `damping`, `verdict`, `end_stop_contacts`, …).
    #[arg(long)]
    json: bool,
}

fn refuse_with_runs(args: &Args) -> wbv::Result<()> {
    let flags = [
        (args.model.is_some(), "--model"),
        (args.occupant.is_some(), "--occupant"),
        (args.duration != seat_test::RUN_DURATION_S, "--duration"),
        (args.dt != 1e-3, "--dt"),
        (args.seed != 1, "--seed"),
        (args.no_damping, "--no-damping"),
    ];
    for (set, flag) in flags {
        if set {
            return Err(Error::parameter(
                flag,
                "has no effect with --run (measured runs are not simulated)",
            ));
        }
    }
    Ok(())
}

pub fn run(args: Args) -> wbv::Result<()> {
    let overwrite = Overwrite::from_force(args.force);
    if let Some(r) = &args.report {
        wbv::io::atomic::check_overwrite(r, overwrite)?;
    }
    let classes = seat_test::find_classes(&args.classes)?;
    let limits = Limits {
        seat: args.seat_limit,
        damping: args.damping_limit,
        contacts_per_10_min: args.contact_limit,
    };
    limits.validate()?;
    let input = args.input.options()?;
    let test = if args.runs.is_empty() {
        if input != wbv::io::input::Options::default() {
            return Err(Error::parameter(
                "--column/--units/--format",
                "read options apply to measured runs (--run) only",
            ));
        }
        let name = args.model.as_deref().ok_or_else(|| {
            Error::parameter("--model", "required (or give measured runs with --run)")
        })?;
        let model = wbv::model::catalog::resolve(name)?;
        let occupants = match &args.occupant {
            Some(o) => vec![Occupant::parse(o)?],
            None => Occupant::BOTH.to_vec(),
        };
        let settings = Settings {
            occupants,
            run_duration_s: args.duration,
            dt: args.dt,
            seed: args.seed,
            limits,
            damping: !args.no_damping,
        };
        eprintln!(
            "seat test of `{}` on {}: {} s runs, {} test person(s){}",
            model.name,
            classes
                .iter()
                .map(|c| format!("{} {} ({})", c.standard.name(), c.code, c.name))
                .collect::<Vec<_>>()
                .join(", "),
            args.duration,
            settings.occupants.len(),
            if settings.damping {
                ", then the damping test"
            } else {
                ""
            }
        );
        seat_test::simulate(&model, &classes, &settings)?
    } else {
        refuse_with_runs(&args)?;
        let [class] = classes[..] else {
            return Err(Error::parameter(
                "--class",
                format!(
                    "{} classes with --run: a lab's runs were made on one class",
                    classes.len()
                ),
            ));
        };
        seat_test::measured::measured(&args.runs, class, &input, limits)?
    };
    let mut written = Vec::new();
    if let Some(r) = &args.report {
        wbv::report::seat_test::write(&test, r, overwrite)?;
        eprintln!("wrote {}", r.display());
        written.push(wbv::report::json::Written::of(r)?);
    }
    // The warnings (a run given twice) go to stderr as `wbv gap`'s do, and into the document.
    for w in &test.warnings {
        eprintln!("warning: {w}");
    }
    if args.json {
        super::print_document(&wbv::report::json::seat_test(&test, written)?);
        return Ok(());
    }
    print_all(&test);
    Ok(())
}

/// The summary table, the damping test, each class's tables and the verdict.
fn print_all(t: &SeatTests) {
    println!(
        "  {:<12} {:<8} {:>7} {:>8} {:>22} {:>9}  verdict",
        "class", "person", "SEAT", "a*_wS", "end-stop contacts", "damping T"
    );
    for r in &t.summary {
        println!(
            "  {:<12} {:<8} {:>7.3} {:>8.3} {:>22} {:>9}  {}",
            r.class,
            r.occupant,
            r.seat,
            r.a_ws_corrected,
            match (r.end_stop_contacts, r.contacts_per_10_min) {
                (Some(n), Some(p)) => format!("{n} ({p:.1} per 10 min)"),
                (Some(n), None) => n.to_string(),
                _ => "-".into(),
            },
            r.damping_transmissibility
                .map_or("-".into(), |d| format!("{d:.2}")),
            Verdict::cell(r.verdict)
        );
    }
    match (&t.damping, &t.damping_skipped) {
        (Some(d), _) => println!(
            "\n  damping test ({} kg): resonance {:.2} Hz, T = {:.3} (platform ±{:.1} mm, {} end-stop contact(s))",
            d.mass_kg,
            d.f_r_hz,
            d.transmissibility,
            1e3 * d.platform_amplitude_m,
            d.end_stop_contacts
        ),
        (None, Some(why)) => println!("\n  no damping test: {why}"),
        _ => {}
    }
    for c in &t.classes {
        println!();
        print_text(c);
    }
    println!(
        "\n  verdict: {}",
        t.verdict.map_or(
            "none (give --seat-limit, --damping-limit and/or --contact-limit from the application standard)",
            Verdict::word
        )
    );
    for l in &t.verdict_lines {
        println!("    {l}");
    }
    let mut seen: Vec<&String> = Vec::new();
    for u in t.classes.iter().flat_map(|c| &c.unverified) {
        if !seen.contains(&u) {
            seen.push(u);
        }
    }
    println!(
        "\n  not verified against the standards' text: {}",
        seen.iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("; ")
    );
}

fn print_text(t: &SeatTest) {
    println!(
        "{} {} ({}, {} {}): intended input a*_wP = {:.3} m/s² (Wk)",
        t.standard,
        t.class_code,
        t.machine,
        t.defining,
        t.scope.mark(),
        t.intended_a_wp
    );
    println!(
        "\n  {:<8} {:>9} {:>9} {:>9} {:>7} {:>10} {:>8} {:>9}",
        "person", "mass kg", "a_wP", "a_wS", "SEAT", "a*_wS", "PSD ok", "contacts"
    );
    for o in &t.occupants {
        println!(
            "  {:<8} {:>9} {:>9.3} {:>9.3} {:>7.3} {:>10.3} {:>8} {:>9}",
            o.label(),
            o.mass_cell(),
            o.a_wp,
            o.a_ws,
            o.seat,
            o.a_ws_corrected,
            o.psd_cell(),
            o.contacts_cell()
        );
        for r in &o.runs {
            println!(
                "    run {:<14} a_wP {:.3}  a_wS {:.3}  SEAT {:.3}",
                r.id, r.a_wp, r.a_ws, r.seat
            );
        }
    }
    for n in &t.notes {
        println!("  note: {n}");
    }
    println!("  {}", t.verdict_line);
    for r in &t.verdict_reasons {
        println!("    {r}");
    }
}
