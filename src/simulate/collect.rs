//! An observer that keeps the measured-run channels in memory, for analysis and tests.

use super::observer::{Layout, Observer, Step};
use crate::error::Result;
use crate::signals::Signals;

/// Collects the measured channels (`a_base_z`, `a_seat_z`, `a_head_z`, `f_seat_z`) of every step,
/// and with [`Collector::with_time`] the step times.
#[derive(Default)]
pub struct Collector {
    layout: Option<Layout>,
    names: Vec<String>,
    data: Vec<Vec<f64>>,
    scratch: Vec<f64>,
    time: Option<Vec<f64>>,
}

impl Collector {
    /// A collector of the measured channels.
    pub fn new() -> Self {
        Self::default()
    }

    /// A collector that also keeps every step's time t in s, the `t_s` column of the CSV that
    /// [`crate::record::csv::CsvWriter`] writes.
    pub fn with_time() -> Self {
        Collector {
            time: Some(Vec::new()),
            ..Self::default()
        }
    }

    /// The collected signals, sampled at 1/dt, and the step times in s (empty unless
    /// [`Collector::with_time`]).
    pub fn into_parts(mut self, source: &str) -> Result<(Signals, Vec<f64>)> {
        let time = self.time.take().unwrap_or_default();
        Ok((self.into_signals(source)?, time))
    }

    /// The collected signals, sampled at 1/dt.
    pub fn into_signals(self, source: &str) -> Result<Signals> {
        let dt = self.layout.as_ref().map_or(1.0, |l| l.dt);
        let mut s = Signals::new(1.0 / dt, source);
        for (n, d) in self.names.into_iter().zip(self.data) {
            s.push(n, d)?;
        }
        Ok(s)
    }
}

impl Observer for Collector {
    fn begin(&mut self, layout: &Layout) -> Result<()> {
        self.names = layout
            .measured_channels()
            .iter()
            .map(|s| s.to_string())
            .collect();
        let cap = usize::try_from(layout.steps).unwrap_or(0);
        self.data = vec![Vec::with_capacity(cap); self.names.len()];
        if let Some(t) = &mut self.time {
            t.reserve(cap);
        }
        self.layout = Some(layout.clone());
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        let layout = self.layout.as_ref().expect("begin() before step()");
        layout.measured(step, &mut self.scratch);
        for (d, v) in self.data.iter_mut().zip(&self.scratch) {
            d.push(*v);
        }
        if let Some(t) = &mut self.time {
            t.push(step.t);
        }
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        Ok(())
    }
}
