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

impl Overwrite {
    /// `Allow` when `force` is set.
    pub fn from_force(force: bool) -> Self {
        if force {
            Overwrite::Allow
        } else {
            Overwrite::Refuse
        }
    }
}

/// The temporary name used while `path` is being written: `<name>.partial` beside it.
pub fn partial_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    path.with_file_name(name)
}

/// Refuses an existing `path` unless overwriting is allowed.
pub fn check_overwrite(path: &Path, overwrite: Overwrite) -> Result<()> {
    if overwrite == Overwrite::Refuse && path.exists() {
        return Err(Error::parameter(
            path.display().to_string(),
            "already exists; refusing to overwrite it (pass --force to replace it)",
        ));
    }
    Ok(())
}

/// A file being written under its `.partial` name; [`AtomicFile::commit`] renames it into place.
/// Dropped without a commit (an error on the way), it removes the partial file.
pub struct AtomicFile {
    path: PathBuf,
    tmp: PathBuf,
    out: Option<BufWriter<fs::File>>,
}

impl AtomicFile {
    /// Creates `<path>.partial` (and the parent directory), refusing an existing `path` unless
    /// allowed.
    pub fn create(path: &Path, overwrite: Overwrite) -> Result<Self> {
        check_overwrite(path, overwrite)?;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        }
        let tmp = partial_path(path);
        let file = fs::File::create(&tmp).map_err(|e| Error::io(&tmp, e))?;
        Ok(AtomicFile {
            path: path.to_path_buf(),
            tmp,
            out: Some(BufWriter::new(file)),
        })
    }

    /// The writer of the partial file.
    pub fn writer(&mut self) -> &mut BufWriter<fs::File> {
        self.out.as_mut().expect("not committed")
    }

    /// The final path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Flushes, syncs and renames the partial file to its final name.
    pub fn commit(mut self) -> Result<()> {
        let out = self.out.take().expect("not committed");
        let file = out
            .into_inner()
            .map_err(|e| Error::io(&self.tmp, e.into_error()))?;
        file.sync_all().map_err(|e| Error::io(&self.tmp, e))?;
        fs::rename(&self.tmp, &self.path).map_err(|e| Error::io(&self.path, e))
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.out.take().is_some() {
            let _ = fs::remove_file(&self.tmp);
        }
    }
}

/// Writes `path` through `write`, atomically (see [`AtomicFile`]).
pub fn write_atomic<F>(path: &Path, overwrite: Overwrite, write: F) -> Result<()>
where
    F: FnOnce(&mut BufWriter<fs::File>) -> Result<()>,
{
    let mut file = AtomicFile::create(path, overwrite)?;
    write(file.writer())?;
    file.commit()
}

/// Maps an I/O error on `path` into the crate's error.
pub fn io_err(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |e| Error::io(path, e)
}
