use std::io::Write;
use std::path::PathBuf;
use wbv::error::Error;
use wbv::io::atomic::{Overwrite, write_atomic};

/// Arguments of `wbv reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output Markdown file.
    #[arg(long, default_value = "docs/reproduction.md")]
    out: PathBuf,
    /// Replace the existing file.
    #[arg(long)]
    force: bool,
    /// Print every row and what was written as JSON (`rows`, `reproduced`, `total`, `written`).
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> wbv::Result<()> {
    let overwrite = Overwrite::from_force(args.force);
    // Refuse an overwrite before the studies run.
    wbv::io::atomic::check_overwrite(&args.out, overwrite)?;
    let rows = wbv::reproduce::rows()?;
    let md = wbv::reproduce::markdown(&rows);
    write_atomic(&args.out, overwrite, |w| {
        w.write_all(md.as_bytes())
            .map_err(|e| Error::io(&args.out, e))
    })?;
    if args.json {
        let written = vec![wbv::report::json::Written::of(&args.out)?];
        let table = wbv::report::json::Reproduction::of(&rows, written);
        return super::print_json("reproduce", &table, &[]);
    }
    let n = rows.iter().filter(|r| r.reproduced()).count();
    println!(
        "{}: {n} of {} numbers reproduced within 5 %",
        args.out.display(),
        rows.len()
    );
    Ok(())
}
