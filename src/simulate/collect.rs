//! An observer that keeps the measured-run channels in memory, for analysis and tests.

use super::observer::{Layout, Observer, Step};
use crate::error::Result;
use crate::signals::Signals;

/// Collects the measured channels (`a_base_z`, `a_seat_z`, `a_head_z`, `f_seat_z`) of every step,
/// plus any extra per-step values chosen by a closure.
#[derive(Default)]
pub struct Collector {
    layout: Option<Layout>,
    names: Vec<String>,
    data: Vec<Vec<f64>>,
    scratch: Vec<f64>,
}

impl Collector {
    /// A collector of the measured channels.
    pub fn new() -> Self {
        Self::default()
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
        self.layout = Some(layout.clone());
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        let layout = self.layout.as_ref().expect("begin() before step()");
        layout.measured(step, &mut self.scratch);
        for (d, v) in self.data.iter_mut().zip(&self.scratch) {
            d.push(*v);
        }
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        Ok(())
    }
}
