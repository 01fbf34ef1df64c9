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
        progress: Option<&dyn Fn(u64)>,
    ) -> Result<()> {
        self.settings.validate()?;
        let mut exc = crate::measurement::excitation(
            &self.excitation,
            self.settings.excitation_step(),
            self.settings.duration_s,
            self.seed,
        )?;
        simulate::run(
            self.model.system(),
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

/// Where a scenario's run goes.
#[derive(Debug, Clone)]
pub struct Outputs {
    /// The MCAP recording and how to write it; `None` for `--no-record`. The viewer files of
    /// [`crate::record::viewer`] are written beside it.
    pub mcap: Option<(std::path::PathBuf, crate::record::RecordOptions)>,
    /// A measured-run CSV of the simulated channels.
    pub csv: Option<std::path::PathBuf>,
    /// Whether existing outputs (the CSV; the MCAP follows its own options) may be replaced.
    pub overwrite: crate::io::atomic::Overwrite,
    /// The command line, for the run's provenance.
    pub command_line: String,
}

/// What a recorded run produced.
#[derive(Debug)]
pub struct Outcome {
    /// The ISO 2631-1 report of the simulated measured channels, when the sample rate allows it.
    pub report: Option<crate::analysis::Report>,
    /// Why there is no report.
    pub report_skipped: Option<String>,
    /// For an input spectral class of the seat tests: the realised platform PSD judged against
    /// the class's tolerance ([`crate::excitation::classes::InputClass::check`]).
    pub platform_psd: Option<crate::excitation::classes::PsdCheck>,
    /// Why an input-class run has no PSD check (a run shorter than one Welch segment).
    pub platform_psd_skipped: Option<String>,
    /// Wall-clock time of simulation, recording and analysis in s.
    pub elapsed_s: f64,
}

impl Scenario {
    /// The provenance stored with a recording of this scenario.
    pub fn provenance(&self, command_line: &str) -> crate::record::Provenance {
        crate::record::Provenance {
            model: self.model.name.clone(),
            model_toml: self.model.text.clone(),
            excitation: self.excitation.summary(),
            excitation_definition: crate::record::excitation_definition(&self.excitation),
            excitation_origin: self.excitation.origin.clone(),
            integrator: self.settings.method.name(),
            dt: self.settings.dt,
            seed: Some(self.seed),
            duration: self.settings.duration_s,
            command_line: command_line.to_string(),
            ..crate::record::Provenance::new()
        }
    }

    /// Simulates, records (MCAP and/or CSV, each written atomically) and analyses the run; the
    /// analysis results are stored in the recording before it is completed.
    pub fn execute(&self, outputs: &Outputs, progress: Option<&dyn Fn(u64)>) -> Result<Outcome> {
        self.execute_with(outputs, &mut [], progress)
    }

    /// [`Scenario::execute`] with `extra` observers (e.g. the live view) after the recorders;
    /// their `end` is left to the caller.
    pub fn execute_with(
        &self,
        outputs: &Outputs,
        extra: &mut [&mut dyn Observer],
        progress: Option<&dyn Fn(u64)>,
    ) -> Result<Outcome> {
        let start = std::time::Instant::now();
        let mut recorder = match &outputs.mcap {
            Some((path, options)) => Some(crate::record::McapRecorder::create(
                path,
                self.provenance(&outputs.command_line),
                options.clone(),
            )?),
            None => None,
        };
        let mut csv = match &outputs.csv {
            Some(p) => Some(crate::record::csv::CsvWriter::create(p, outputs.overwrite)?),
            None => None,
        };
        let mut analysis = crate::analysis::AnalysisObserver::new(
            &format!("simulated {}", self.model.name),
            Default::default(),
        );
        let class = self.excitation.input_class_def();
        let mut spectra = class.map(|_| {
            crate::analysis::SpectraObserver::new(
                &["a_base_z"],
                crate::excitation::classes::CHECK_RESOLUTION_HZ,
            )
        });
        {
            let mut observers: Vec<&mut dyn Observer> = vec![&mut analysis];
            if let Some(s) = spectra.as_mut() {
                observers.push(s);
            }
            if let Some(r) = recorder.as_mut() {
                observers.push(r);
            }
            if let Some(c) = csv.as_mut() {
                observers.push(c);
            }
            for o in extra.iter_mut() {
                observers.push(&mut **o);
            }
            self.simulate(&mut observers, progress)?;
        }
        let (report, report_skipped) = match analysis.into_report() {
            Ok(r) => (Some(r), None),
            Err(e) => (None, Some(e.to_string())),
        };
        let (platform_psd, platform_psd_skipped) = match (class, spectra) {
            (Some(c), Some(s)) => match s.finish() {
                Ok(v) => {
                    let sp = &v[0].1;
                    (
                        Some(c.check(&sp.freq_hz, &sp.density, sp.df_hz, sp.segments)),
                        None,
                    )
                }
                Err(e) => (None, Some(e.to_string())),
            },
            _ => (None, None),
        };
        if let Some(mut r) = recorder {
            if let Some(rep) = &report {
                let json = serde_json::to_value(rep).expect("report serializes");
                r.attach_results("analysis", &json)?;
            }
            r.end()?;
            crate::record::viewer::write_beside(r.path(), outputs.overwrite)?;
        }
        if let Some(mut c) = csv {
            c.end()?;
        }
        Ok(Outcome {
            report,
            report_skipped,
            platform_psd,
            platform_psd_skipped,
            elapsed_s: start.elapsed().as_secs_f64(),
        })
    }
}
