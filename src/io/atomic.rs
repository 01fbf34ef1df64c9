//! Atomic file output: write to a temporary sibling, rename into place only once complete, so an
//! interrupted command never leaves a file that looks finished.

use crate::error::{Error, Result};
use std::fs;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// Whether an existing file at the destination may be replaced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Overwrite {
    /// Refuse to replace an existing file (the default for runs).
    Refuse,
    /// Replace it (`--force`).
    Allow,
}

/// The temporary name used while `path` is being written: `<name>.partial` beside it.
pub fn partial_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    path.with_file_name(name)
}

/// Writes `path` through `write`, atomically: the bytes go to `<path>.partial`, which is synced and
/// renamed over `path` only when `write` returned `Ok`. On error the partial file is removed.
pub fn write_atomic<F>(path: &Path, overwrite: Overwrite, write: F) -> Result<()>
where
    F: FnOnce(&mut BufWriter<fs::File>) -> Result<()>,
{
    if overwrite == Overwrite::Refuse && path.exists() {
        return Err(Error::parameter(
            path.display().to_string(),
            "already exists; refusing to overwrite it (pass --force to replace it)",
        ));
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    let tmp = partial_path(path);
    let file = fs::File::create(&tmp).map_err(|e| Error::io(&tmp, e))?;
    let mut out = BufWriter::new(file);
    let result = write(&mut out).and_then(|()| {
        let file = out
            .into_inner()
            .map_err(|e| Error::io(&tmp, e.into_error()))?;
        file.sync_all().map_err(|e| Error::io(&tmp, e))
    });
    match result {
        Ok(()) => fs::rename(&tmp, path).map_err(|e| Error::io(path, e)),
        Err(e) => {
            let _ = fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// Maps an I/O error on `path` into the crate's error.
pub fn io_err(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |e| Error::io(path, e)
}
