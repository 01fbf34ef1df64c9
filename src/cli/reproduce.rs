use crate::error::Error;
use crate::io::atomic::{Overwrite, write_atomic};
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `wbv reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output Markdown file.
    #[arg(long, default_value = "docs/reproduction.md")]
    out: PathBuf,
    /// Replace the existing file.
    #[arg(long)]
    force: bool,
}

pub fn run(args: Args) -> crate::Result<()> {
    let rows = crate::reproduce::rows()?;
    let md = crate::reproduce::markdown(&rows);
    let overwrite = if args.force {
        Overwrite::Allow
    } else {
        Overwrite::Refuse
    };
    write_atomic(&args.out, overwrite, |w| {
        w.write_all(md.as_bytes())
            .map_err(|e| Error::io(&args.out, e))
    })?;
    let n = rows.iter().filter(|r| r.reproduced()).count();
    println!(
        "{}: {n} of {} numbers reproduced within 5 %",
        args.out.display(),
        rows.len()
    );
    Ok(())
}
