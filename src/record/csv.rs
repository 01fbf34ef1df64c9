//! A simulation's measured-run channels streamed to a CSV file as it runs (an observer), in the
//! measured-run format that [`crate::io::csv_run`] reads.

use crate::error::{Error, Result};
use crate::io::atomic::{AtomicFile, Overwrite, io_err};
use crate::simulate::observer::{Layout, Observer, Step};
use std::io::Write;
use std::path::Path;

/// Streams the measured-run channels of a simulation to a CSV file as it runs (an observer), so a
/// simulated run can stand wherever a measurement can. Atomic: the file appears complete at `end`.
pub struct CsvWriter {
    file: Option<AtomicFile>,
    layout: Option<Layout>,
    scratch: Vec<f64>,
}

impl CsvWriter {
    /// Opens `<path>.partial`; refuses an existing `path` unless allowed.
    pub fn create(path: &Path, overwrite: Overwrite) -> Result<Self> {
        Ok(CsvWriter {
            file: Some(AtomicFile::create(path, overwrite)?),
            layout: None,
            scratch: Vec::new(),
        })
    }
}

impl Observer for CsvWriter {
    fn begin(&mut self, layout: &Layout) -> Result<()> {
        let file = self.file.as_mut().expect("open");
        let path = file.path().to_path_buf();
        let w = file.writer();
        write!(w, "t_s").map_err(io_err(&path))?;
        for n in layout.measured_channels() {
            write!(w, ",{n}").map_err(io_err(&path))?;
        }
        writeln!(w).map_err(io_err(&path))?;
        self.layout = Some(layout.clone());
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        let layout = self.layout.as_ref().expect("begin() before step()");
        layout.measured(step, &mut self.scratch);
        let file = self.file.as_mut().expect("open");
        let path = file.path().to_path_buf();
        let w = file.writer();
        write!(w, "{}", step.t).map_err(io_err(&path))?;
        for v in &self.scratch {
            if !v.is_finite() {
                return Err(Error::data(
                    &path,
                    None,
                    format!("non-finite value at t = {} s", step.t),
                ));
            }
            write!(w, ",{v}").map_err(io_err(&path))?;
        }
        writeln!(w).map_err(io_err(&path))
    }

    fn end(&mut self) -> Result<()> {
        match self.file.take() {
            Some(f) => f.commit(),
            None => Ok(()),
        }
    }
}
