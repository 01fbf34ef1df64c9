use crate::response::modes;

/// Arguments of `wbv modes`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    model: super::ModelArg,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> crate::Result<()> {
    let model = args.model.resolve()?;
    let und = modes::undamped(&model)?;
    let dam = modes::damped(&model)?;
    let names: Vec<&str> = model.masses.iter().map(|m| m.name.as_str()).collect();
    if args.json {
        let json = serde_json::json!({
            "model": model.name,
            "masses": names,
            "undamped": und.iter().map(|m| serde_json::json!({
                "freq_hz": m.freq_hz, "shape": m.shape,
            })).collect::<Vec<_>>(),
            "damped": dam.iter().map(|m| serde_json::json!({
                "damped_hz": m.damped_hz, "natural_hz": m.natural_hz, "zeta": m.zeta,
                "overdamped": m.overdamped, "shape_mag": m.shape_mag,
                "shape_phase_deg": m.shape_phase_deg,
            })).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&json).expect("json"));
        return Ok(());
    }
    println!("Model {} ({} DOF)", model.name, model.dof());
    println!("\nUndamped modes (dashpots locked): frequency [Hz] and shape (largest = 1)");
    println!(
        "  {:>9}  {}",
        "f [Hz]",
        names.iter().map(|n| format!("{n:>12}")).collect::<String>()
    );
    for m in &und {
        println!(
            "  {:9.3}  {}",
            m.freq_hz,
            m.shape
                .iter()
                .map(|v| format!("{v:12.4}"))
                .collect::<String>()
        );
    }
    println!("\nDamped modes (state-space eigenvalues): |shape| (phase°)");
    println!(
        "  {:>9} {:>9} {:>7}  {}",
        "fd [Hz]",
        "fn [Hz]",
        "zeta",
        names.iter().map(|n| format!("{n:>16}")).collect::<String>()
    );
    for m in &dam {
        let fd = if m.overdamped {
            "overdamped".to_string()
        } else {
            format!("{:9.3}", m.damped_hz)
        };
        println!(
            "  {:>9} {:9.3} {:7.3}  {}",
            fd,
            m.natural_hz,
            m.zeta,
            m.shape_mag
                .iter()
                .zip(&m.shape_phase_deg)
                .map(|(a, p)| format!("{:>16}", format!("{a:.3} ({p:.0}°)")))
                .collect::<String>()
        );
    }
    Ok(())
}
