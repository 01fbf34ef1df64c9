//! A scenario: one model shaken by one excitation with given integrator settings and seed — the
//! unit that `wbv simulate`, `wbv run` and the gap benchmark execute.

use crate::error::Result;
use crate::excitation::ExcitationSpec;
use crate::integrator::Method;
use crate::model::{Model, catalog};
use crate::signals::Signals;
use crate::simulate::collect::Collector;
use crate::simulate::observer::Observer;
use crate::simulate::{self, Settings};

/// Model, excitation, settings and seed of a run.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The occupant–seat model.
    pub model: Model,
    /// The base excitation.
    pub excitation: ExcitationSpec,
    /// Step, duration and integrator.
    pub settings: Settings,
    /// Seed of the random parts of the excitation.
    pub seed: u64,
}

/// The built-in default scenario of `wbv run`: the reference setup (shared/specs/measured-runs.md)
/// in the Bell 214 family helicopter spectrum for 60 s at 1 kHz, Newmark average acceleration.
pub fn default_scenario() -> Result<Scenario> {
    Ok(Scenario {
        model: catalog::resolve(catalog::DEFAULT)?,
        excitation: ExcitationSpec::load("bell-214")?,
        settings: Settings {
            dt: 1e-3,
            duration_s: 60.0,
            method: Method::AVERAGE_ACCELERATION,
        },
        seed: 1,
    })
}

impl Scenario {
    /// Runs the simulation through `observers` (their `end` is left to the caller).
    pub fn simulate(
        &self,
        observers: &mut [&mut dyn Observer],
        progress: Option<&indicatif::ProgressBar>,
    ) -> Result<()> {
        self.settings.validate()?;
        let mut exc = self.excitation.build(
            self.settings.excitation_step(),
            self.settings.duration_s,
            self.seed,
        )?;
        simulate::run(
            &self.model,
            exc.as_mut(),
            &self.settings,
            observers,
            progress,
        )
    }

    /// Runs the simulation and returns the measured-run channels in memory.
    pub fn signals(&self) -> Result<Signals> {
        let mut collector = Collector::new();
        self.simulate(&mut [&mut collector], None)?;
        collector.into_signals(&format!("simulated {}", self.model.name))
    }
}
