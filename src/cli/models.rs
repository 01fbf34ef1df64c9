use wbv::model::{Kind, catalog};

/// Arguments of `wbv models`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Also list each model's parameter paths (for sweeps and calibration).
    #[arg(long)]
    params: bool,
    /// Print the list as JSON (`models`: name, kind, dof, description, params).
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    let models = catalog::all()?;
    if args.json {
        super::print_document(&wbv::report::json::models(&models)?);
        return Ok(());
    }
    let width = models.iter().map(|m| m.name.len()).max().unwrap_or(0);
    for kind in Kind::ALL {
        println!("{}", kind.title());
        for m in models.iter().filter(|m| m.kind() == kind) {
            println!("  {:width$}  {:>2} DOF  {}", m.name, m.dof(), m.description);
            if args.params {
                println!("  {:width$}          {}", "", m.params().join(" "));
            }
        }
    }
    println!(
        "\nUse a name, a path to a model TOML file, or stack components: `--model wan-schimmels-4dof+cushion-zener`."
    );
    Ok(())
}
