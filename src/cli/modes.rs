use wbv::response::modes;
use wbv::system::System;

/// Arguments of `wbv modes`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    model: super::ModelArg,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
    /// Planar models: foam thickness of the cushion in m (paper 000: 0.06, 0.08, 0.10).
    #[arg(long)]
    foam_thickness: Option<f64>,
}

/// The static equilibrium (when the model solves one) and the worded mode shapes (when the
/// system names its motions).
fn print_statics_and_words(system: &System) -> wbv::Result<()> {
    if let Some(eq) = &system.statics {
        println!(
            "Model {}: static seated equilibrium ({} Newton iterations)",
            system.name, eq.iterations
        );
        println!(
            "  {:>10} {:>9} {:>9} {:>10} {:>10} {:>9} {:>9}",
            "contact", "role", "N [N]", "T [N]", "Fx [N]", "Fz [N]", "x, z [m]"
        );
        for l in &eq.loads {
            println!(
                "  {:>10} {:>9} {:>9.1} {:>10.1} {:>10.1} {:>9.1}   {:.3}, {:.3}",
                l.name,
                l.role,
                l.normal,
                l.tangential,
                l.force[0],
                l.force[1],
                l.point[0],
                l.point[1]
            );
        }
        let f = eq.total_force();
        println!(
            "  sum of support forces: Fx = {:.3e} N, Fz = {:.2} N; body weight {:.2} N",
            f[0], f[1], eq.weight
        );
        println!(
            "  pitch moments about the seat origin: supports {:.3} N·m, gravity {:.3} N·m (sum {:.2e})",
            eq.support_moment,
            eq.gravity_moment,
            eq.support_moment + eq.gravity_moment
        );
    }
    let described = modes::describe(system)?;
    if described.is_empty() {
        return Ok(());
    }
    println!(
        "\nUndamped modes described (dominant motions; effective vertical / fore-and-aft mass %)"
    );
    for d in described {
        println!(
            "  {:7.3} Hz  {:5.1} % {:5.1} %  {}",
            d.mode.freq_hz,
            100.0 * d.vertical_mass_fraction,
            100.0 * d.fore_aft_mass_fraction,
            d.words()
        );
    }
    println!();
    Ok(())
}

pub fn run(args: Args) -> wbv::Result<()> {
    let mut model = args.model.resolve()?;
    if let Some(t) = args.foam_thickness {
        model.set_foam_thickness(t)?;
    }
    if args.json {
        super::print_document(&wbv::report::json::modes(&model)?);
        return Ok(());
    }
    let system = model.system();
    print_statics_and_words(system)?;
    let und = modes::undamped(system)?;
    let dam = modes::damped(system)?;
    let names: Vec<&str> = system.dofs.iter().map(|m| m.name.as_str()).collect();
    println!("Model {} ({} DOF)", model.name, model.dof());
    println!("\nUndamped modes (dashpots locked): frequency [Hz] and shape (largest = 1)");
    let w = names.iter().map(|n| n.len() + 2).max().unwrap_or(0).max(12);
    println!(
        "  {:>9}  {}",
        "f [Hz]",
        names.iter().map(|n| format!("{n:>w$}")).collect::<String>()
    );
    for m in &und {
        println!(
            "  {:9.3}  {}",
            m.freq_hz,
            m.shape
                .iter()
                .map(|v| format!("{v:w$.4}"))
                .collect::<String>()
        );
    }
    let shape = |m: &wbv::response::modes::DampedMode| -> String {
        m.shape_mag
            .iter()
            .zip(&m.shape_phase_deg)
            .map(|(a, p)| format!("{:>16}", format!("{a:.3} ({p:.0}°)")))
            .collect()
    };
    println!("\nDamped modes (state-space eigenvalues): |shape| (phase°)");
    println!(
        "  {:>9} {:>9} {:>7}  {}",
        "fd [Hz]",
        "fn [Hz]",
        "zeta",
        names.iter().map(|n| format!("{n:>16}")).collect::<String>()
    );
    for m in dam.iter().filter(|m| !m.overdamped) {
        println!(
            "  {:9.3} {:9.3} {:7.3}  {}",
            m.damped_hz,
            m.natural_hz,
            m.zeta,
            shape(m)
        );
    }
    if dam.iter().any(|m| m.overdamped) {
        // A real eigenvalue λ is no mode: the motion it carries decays as e^{λt} without
        // oscillating; its corner |λ|/2π is where it shapes the frequency response.
        println!("\nReal poles (overdamped: decay without oscillation): |shape| (phase°)");
        println!(
            "  {:>9} {:>9}  {}",
            "f [Hz]",
            "tau [ms]",
            names.iter().map(|n| format!("{n:>16}")).collect::<String>()
        );
        for m in dam.iter().filter(|m| m.overdamped) {
            println!(
                "  {:9.3} {:9.3}  {}",
                m.natural_hz,
                1e3 / (2.0 * std::f64::consts::PI * m.natural_hz),
                shape(m)
            );
        }
    }
    Ok(())
}
