//! A sweep as `wbv sweep` and the Python binding's `wbv.sweep` ask for it: the grid ([`Spec`])
//! and, given an excitation, every point's ISO 2631-1 figures by the path [`choose`] takes, with
//! the hook that computes them (spectral: [`SpectralIso`]; time domain: [`BatchIso`]).

use super::batch::BatchIso;
use super::iso::IsoRun;
use super::path::{Path, choose};
use super::shard::Shard;
use super::spectral::SpectralIso;
use super::sweep::{self, Point, PointFigures, Spec};
use crate::error::{Error, Result};
use crate::model::Model;

/// A sweep ready to run.
pub struct Plan {
    /// The grid, the response and its frequencies.
    pub spec: Spec,
    /// With an excitation: the path of the ISO figures and the hook that computes them.
    figures: Option<(Path, Box<dyn PointFigures>)>,
}

impl Plan {
    /// The sweep `spec` of `model`; with `iso`, every point also gets the ISO figures of that
    /// run, in the time domain when `time_domain` (which needs `iso`) or when [`choose`] says so.
    pub fn new(model: &Model, spec: Spec, iso: Option<&IsoRun>, time_domain: bool) -> Result<Plan> {
        let figures = match iso {
            Some(iso) => {
                let path = choose(model, &iso.excitation, time_domain);
                let hook: Box<dyn PointFigures> = if path.is_spectral() {
                    Box::new(SpectralIso::for_run(model, iso)?)
                } else {
                    Box::new(BatchIso::new(iso)?)
                };
                Some((path, hook))
            }
            None if time_domain => {
                return Err(Error::parameter(
                    "--time-domain",
                    "it chooses how the ISO figures of an excitation are computed; give an \
                     excitation too",
                ));
            }
            None => None,
        };
        Ok(Plan { spec, figures })
    }

    /// How the ISO figures are computed, with an excitation.
    pub fn path(&self) -> Option<&Path> {
        self.figures.as_ref().map(|(p, _)| p)
    }

    /// The hooks every point's figures come from (none without an excitation).
    pub fn hooks(&self) -> Vec<&dyn PointFigures> {
        self.figures.iter().map(|(_, h)| h.as_ref()).collect()
    }

    /// Runs the points of `shard` ([`sweep::run`]); `tick` is called once per point.
    pub fn run(&self, model: &Model, shard: Shard, tick: &(dyn Fn() + Sync)) -> Result<Vec<Point>> {
        sweep::run(model, &self.spec, shard, &self.hooks(), tick)
    }
}
