//! A model variant: the (possibly nonlinear) mechanical system a candidate stack builds, with the
//! body's magnitude schedule and the measuring chain it is read through.

use super::chain::Chain;
use crate::system::{Element, Role, System};

/// Body stiffness and damping scheduled with a run's magnitude (docs/gap.md §5, E1): linear within a
/// run, softer between runs, as the seated body's apparent-mass resonance falls with magnitude
/// (Mansfield & Griffin, J. Biomech. 33 (2000) 933–941; Matsumoto & Griffin, JSV 215 (1998) 743–762).
/// Every Kelvin–Voigt body link's `k` is multiplied by `(A/A_ref)^(−alpha_k)` and its `c` by
/// `(A/A_ref)^(−alpha_c)`, A the run's unweighted base r.m.s. (m/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MagnitudeSchedule {
    /// Stiffness exponent (> 0 softens as magnitude rises).
    pub alpha_k: f64,
    /// Damping exponent.
    pub alpha_c: f64,
    /// Reference magnitude A_ref (m/s²): the geometric mean of the training runs' base r.m.s., so
    /// the base parameters keep their meaning at the training runs' centre.
    pub rms_ref: f64,
}

impl MagnitudeSchedule {
    /// `system` as it behaves in a run of base r.m.s. `rms` (m/s²).
    pub fn at(&self, system: &System, rms: f64) -> System {
        let r = (rms / self.rms_ref).max(1e-9);
        let (fk, fc) = (r.powf(-self.alpha_k), r.powf(-self.alpha_c));
        let mut m = system.clone();
        for l in &mut m.links {
            if l.role == Role::Body
                && let Element::KelvinVoigt { k, c } = l.element
            {
                l.element = Element::KelvinVoigt {
                    k: k * fk,
                    c: c * fc,
                };
            }
        }
        m
    }
}

/// A model's system plus the measuring chain: the thing a candidate evaluates.
#[derive(Debug, Clone)]
pub struct Variant {
    /// The (possibly nonlinear) mechanical system.
    pub system: System,
    /// Magnitude schedule of the body between runs, if any.
    pub schedule: Option<MagnitudeSchedule>,
    /// Reference magnitude for a schedule (m/s²): the training runs' geometric-mean base r.m.s.
    pub rms_ref: f64,
    /// The transducers the paths are read through.
    pub chain: Chain,
}

impl Variant {
    /// A variant with ideal sensors.
    pub fn plain(system: System) -> Self {
        Variant {
            system,
            schedule: None,
            rms_ref: 1.0,
            chain: Chain::default(),
        }
    }

    /// The variant with every channel's clock drift removed, when any channel has one
    /// ([`Chain::without_drift`]).
    pub fn without_drift(&self) -> Option<Variant> {
        self.chain.drifts().then(|| Variant {
            chain: self.chain.without_drift(),
            ..self.clone()
        })
    }

    /// The linear system this variant is in a run of base r.m.s. `rms` (m/s²) and base PSD
    /// `base_psd` ((Hz, (m/s²)²/Hz) bins): the magnitude schedule applied, then every nonlinear
    /// law statistically linearised ([`crate::response::linearise`]).
    pub fn linear_in(&self, rms: f64, base_psd: &(Vec<f64>, Vec<f64>)) -> crate::Result<System> {
        let scheduled = self.schedule.map(|s| s.at(&self.system, rms));
        crate::response::linearise::linearise(scheduled.as_ref().unwrap_or(&self.system), base_psd)
    }
}
