//! A simulation's measured-run channels streamed to a CSV file as it runs (an observer), in the
//! measured-run format that [`crate::io::csv_run`] reads, written through the `csv` crate.

use crate::error::{Error, Result};
use crate::io::atomic::{AtomicFile, Overwrite};
use crate::io::csv_run::num;
use crate::simulate::observer::{Layout, Observer, Step};
use std::path::Path;

/// The partial file of a [`CsvWriter`] as an `io::Write`, so a `csv::Writer` can own it.
struct Sink(AtomicFile);

impl std::io::Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.writer().write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.0.writer().flush()
    }
}

/// Streams the measured-run channels of a simulation to a CSV file as it runs (an observer), so a
/// simulated run can stand wherever a measurement can. Atomic: the file appears complete at `end`.
pub struct CsvWriter {
    path: std::path::PathBuf,
    out: Option<csv::Writer<Sink>>,
    layout: Option<Layout>,
    scratch: Vec<f64>,
    row: Vec<String>,
}

impl CsvWriter {
    /// Opens `<path>.partial`; refuses an existing `path` unless allowed.
    pub fn create(path: &Path, overwrite: Overwrite) -> Result<Self> {
        let file = AtomicFile::create(path, overwrite)?;
        Ok(CsvWriter {
            path: path.to_path_buf(),
            out: Some(csv::Writer::from_writer(Sink(file))),
            layout: None,
            scratch: Vec::new(),
            row: Vec::new(),
        })
    }

    fn write_row(&mut self) -> Result<()> {
        let path = &self.path;
        self.out
            .as_mut()
            .expect("open")
            .write_record(&self.row)
            .map_err(|e| Error::data(path, None, format!("cannot write CSV: {e}")))
    }
}

impl Observer for CsvWriter {
    fn begin(&mut self, layout: &Layout) -> Result<()> {
        self.row.clear();
        self.row.push("t_s".into());
        self.row
            .extend(layout.measured_channels().iter().map(|n| n.to_string()));
        self.write_row()?;
        self.layout = Some(layout.clone());
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        let layout = self.layout.as_ref().expect("begin() before step()");
        layout.measured(step, &mut self.scratch);
        if !self.scratch.iter().all(|v| v.is_finite()) {
            return Err(Error::data(
                &self.path,
                None,
                format!("non-finite value at t = {:.6} s", step.t),
            ));
        }
        self.row.clear();
        self.row.push(num(step.t));
        self.row.extend(self.scratch.iter().map(|&v| num(v)));
        self.write_row()
    }

    fn end(&mut self) -> Result<()> {
        match self.out.take() {
            Some(w) => {
                let sink = w
                    .into_inner()
                    .map_err(|e| Error::io(&self.path, e.into_error()))?;
                sink.0.commit()
            }
            None => Ok(()),
        }
    }
}
