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

/// `<path>.partial`, created and locked by this process until it is moved into place.
///
/// - Created with `create_new` and held with an exclusive lock (`File::try_lock`), so two
///   processes writing the same output cannot both proceed: the second one is refused at once.
/// - A `.partial` that exists but is not locked is the leftover of a process that was killed
///   (`kill -9`, power loss): it is reported on stderr and removed.
/// - [`Partial::commit`] syncs and moves the file to its final name without replacing a file
///   that appeared meanwhile (hard link, then unlink) unless overwriting is allowed.
/// - Dropped without a commit (an error on the way), the partial file is removed.
#[derive(Debug)]
pub struct Partial {
    path: PathBuf,
    tmp: PathBuf,
    done: bool,
}

impl Partial {
    /// Creates and locks `<path>.partial` (and the parent directory), refusing an existing
    /// `path` unless allowed; returns the guard and the open file.
    pub fn create(path: &Path, overwrite: Overwrite) -> Result<(Self, fs::File)> {
        Self::create_at(path, partial_path(path), overwrite)
    }

    /// [`Partial::create`] with the temporary name `tmp` beside `path` (for writers that pick the
    /// format from the extension, such as the plot backends).
    pub fn create_at(path: &Path, tmp: PathBuf, overwrite: Overwrite) -> Result<(Self, fs::File)> {
        check_overwrite(path, overwrite)?;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        }
        let busy = || {
            Error::parameter(
                path.display().to_string(),
                format!(
                    "another process is writing it ({} is locked); refusing to write it twice",
                    tmp.display()
                ),
            )
        };
        // Two rounds: a stale leftover is removed once, then the file must be ours.
        for _ in 0..2 {
            match fs::OpenOptions::new()
                .read(true)
                .write(true)
                .create_new(true)
                .open(&tmp)
            {
                Ok(file) => {
                    // Locked by nobody else yet: only a process that opened the same new file
                    // between our create and lock could hold it, and then it is theirs.
                    file.try_lock().map_err(|_| busy())?;
                    let guard = Partial {
                        path: path.to_path_buf(),
                        tmp,
                        done: false,
                    };
                    return Ok((guard, file));
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let old = fs::OpenOptions::new()
                        .read(true)
                        .write(true)
                        .open(&tmp)
                        .map_err(|e| Error::io(&tmp, e))?;
                    if old.try_lock().is_err() {
                        return Err(busy());
                    }
                    let bytes = old.metadata().map_or(0, |m| m.len());
                    eprintln!(
                        "removed {} ({bytes} bytes), left by an earlier run that was killed",
                        tmp.display()
                    );
                    fs::remove_file(&tmp).map_err(|e| Error::io(&tmp, e))?;
                }
                Err(e) => return Err(Error::io(&tmp, e)),
            }
        }
        Err(busy())
    }

    /// The final path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The `.partial` path being written.
    pub fn tmp(&self) -> &Path {
        &self.tmp
    }

    /// Syncs `file` (the one [`Partial::create`] returned) and moves it to the final path.
    pub fn commit(self, file: fs::File, overwrite: Overwrite) -> Result<()> {
        let dest = self.path.clone();
        self.commit_as(file, &dest, overwrite)
    }

    /// Like [`Partial::commit`], under another name (e.g. `run.interrupted.mcap`).
    pub fn commit_as(mut self, file: fs::File, dest: &Path, overwrite: Overwrite) -> Result<()> {
        file.sync_all().map_err(|e| Error::io(&self.tmp, e))?;
        match overwrite {
            Overwrite::Allow => fs::rename(&self.tmp, dest).map_err(|e| Error::io(dest, e))?,
            Overwrite::Refuse => match fs::hard_link(&self.tmp, dest) {
                Ok(()) => {
                    let _ = fs::remove_file(&self.tmp);
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    return Err(Error::parameter(
                        dest.display().to_string(),
                        "appeared while writing; refusing to overwrite it",
                    ));
                }
                Err(e) => return Err(Error::io(dest, e)),
            },
        }
        self.done = true;
        drop(file); // releases the lock
        Ok(())
    }
}

impl Drop for Partial {
    fn drop(&mut self) {
        if !self.done {
            let _ = fs::remove_file(&self.tmp);
        }
    }
}

/// A file being written under its `.partial` name (see [`Partial`]); [`AtomicFile::commit`]
/// moves it into place.
pub struct AtomicFile {
    partial: Partial,
    overwrite: Overwrite,
    out: BufWriter<fs::File>,
}

impl AtomicFile {
    /// Creates `<path>.partial` (and the parent directory), refusing an existing `path` unless
    /// allowed.
    pub fn create(path: &Path, overwrite: Overwrite) -> Result<Self> {
        let (partial, file) = Partial::create(path, overwrite)?;
        Ok(AtomicFile {
            partial,
            overwrite,
            out: BufWriter::new(file),
        })
    }

    /// The writer of the partial file.
    pub fn writer(&mut self) -> &mut BufWriter<fs::File> {
        &mut self.out
    }

    /// The final path.
    pub fn path(&self) -> &Path {
        self.partial.path()
    }

    /// Flushes, syncs and moves the partial file to its final name.
    pub fn commit(self) -> Result<()> {
        let file =
            (self.out.into_inner()).map_err(|e| Error::io(self.partial.tmp(), e.into_error()))?;
        self.partial.commit(file, self.overwrite)
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
