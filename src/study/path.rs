//! Which way a study computes the ISO 2631-1 figures of its points, decided in one place
//! ([`choose`]) and returned as a type, so that the sweep, its output and its tests all read the
//! same decision.
//!
//! - [`Path::Spectral`]: a linear model under a stationary excitation with an analytic spectrum.
//!   The weighted r.m.s. of every channel follows from the excitation's one-sided PSD G(f), its
//!   steady lines and the model's frequency response H(f) (ISO 2631-1 eq. 1 by Parseval):
//!   `a_w² = ∫ |H(f)|² |W(f)|² G(f) df + Σ_lines |H(f_k)|² |W(f_k)|² A_k²/2`
//!   ([`super::spectral::SpectralIso`]); a_v (eq. 10), SEAT (ISO 10326-1 10.2.2) and the comfort
//!   class (Annex C) follow. VDV, MTVV and the crest factor depend on the time history, not on the
//!   PSD, so this path leaves them out.
//!   A recorded base is taken as stationary: G is the Welch estimate of its samples.
//! - [`Path::TimeDomain`]: every point simulated and analysed while it runs, many points stepped
//!   together over one shared excitation ([`super::batch::BatchIso`]): for nonlinear models,
//!   non-stationary inputs (a sweep), or when asked for (`--time-domain`), which also gives VDV,
//!   MTVV and the crest factor.

use crate::excitation::{ExcitationSpec, Kind};
use crate::model::Model;
use std::fmt;

/// Why the spectral path was taken.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SpectralReason {
    /// Linear model; stationary random excitation with an analytic one-sided PSD (`random`, `psd`,
    /// `helicopter`, `road`), plus its steady lines where it has them.
    StationaryRandom,
    /// Linear model; a steady sine (periodic: its figures are the steady state's, the fade-in is
    /// left out as a start-up, like the model's own start from rest).
    SteadySine,
    /// Linear model; a recorded base taken as stationary: its PSD is the Welch estimate of the
    /// samples that would drive the run.
    WelchEstimate,
}

/// Why the time-domain path was taken.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TimeDomainReason {
    /// `--time-domain` was given.
    Requested,
    /// The model has links with nonlinear laws (named): no frequency response describes it.
    Nonlinear {
        /// Names of the links that carry a nonlinear law.
        links: Vec<String>,
    },
    /// The excitation is not stationary (a sweep): its PSD changes with time.
    NonStationary {
        /// The excitation kind's name (`sweep`).
        kind: &'static str,
    },
}

/// How a study computes its ISO 2631-1 figures.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Path {
    /// In the frequency domain, from the excitation's spectrum and the model's FRF.
    Spectral {
        /// Which spectrum the excitation gives (stated PSD, steady sine or Welch estimate).
        reason: SpectralReason,
    },
    /// By simulating every point (batched) and analysing it as it runs.
    TimeDomain {
        /// Why no frequency-domain path applies (requested, nonlinear, non-stationary).
        reason: TimeDomainReason,
    },
}

/// Figure columns the spectral path computes (the others need a time history).
pub const SPECTRAL_FIGURES: [&str; 4] = ["a_w_seat_m_s2", "a_v_m_s2", "seat_pct", "comfort"];
/// Figure columns only the time-domain path computes.
pub const TIME_ONLY_FIGURES: [&str; 3] = ["vdv_seat_m_s1_75", "mtvv_seat_m_s2", "crest_seat"];

fn kind_name(kind: &Kind) -> &'static str {
    match kind {
        Kind::Random { .. } => "random",
        Kind::Psd { .. } => "psd",
        Kind::Helicopter(_) => "helicopter",
        Kind::Road { .. } => "road",
        Kind::InputClass { .. } => "input-class",
        Kind::Recorded { .. } => "recorded",
        Kind::Sine { .. } => "sine",
        Kind::Sweep { .. } => "sweep",
    }
}

/// Chooses the path for `model` under `excitation`; `time_domain` is `--time-domain`. The only
/// place the decision is made.
pub fn choose(model: &Model, excitation: &ExcitationSpec, time_domain: bool) -> Path {
    let links: Vec<String> = model
        .system()
        .links
        .iter()
        .filter(|l| l.law.is_some())
        .map(|l| l.name.clone())
        .collect();
    let reason = if time_domain {
        TimeDomainReason::Requested
    } else if !links.is_empty() {
        TimeDomainReason::Nonlinear { links }
    } else {
        match &excitation.kind {
            Kind::Random { .. }
            | Kind::Psd { .. }
            | Kind::Helicopter(_)
            | Kind::Road { .. }
            | Kind::InputClass { .. } => {
                return Path::Spectral {
                    reason: SpectralReason::StationaryRandom,
                };
            }
            Kind::Sine { .. } => {
                return Path::Spectral {
                    reason: SpectralReason::SteadySine,
                };
            }
            Kind::Recorded { .. } => {
                return Path::Spectral {
                    reason: SpectralReason::WelchEstimate,
                };
            }
            k @ Kind::Sweep { .. } => TimeDomainReason::NonStationary { kind: kind_name(k) },
        }
    };
    Path::TimeDomain { reason }
}

impl Path {
    /// True for [`Path::Spectral`].
    pub fn is_spectral(&self) -> bool {
        matches!(self, Path::Spectral { .. })
    }

    /// The figure columns this path computes.
    pub fn figures(&self) -> Vec<&'static str> {
        let mut v = SPECTRAL_FIGURES.to_vec();
        if !self.is_spectral() {
            v.extend(TIME_ONLY_FIGURES);
        }
        v
    }

    /// Short name: `spectral` or `time-domain`.
    pub fn name(&self) -> &'static str {
        match self {
            Path::Spectral { .. } => "spectral",
            Path::TimeDomain { .. } => "time-domain",
        }
    }
}

impl fmt::Display for SpectralReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpectralReason::StationaryRandom => write!(
                f,
                "linear model under a stationary excitation: a_w, a_v and SEAT from the \
                 excitation's PSD and lines × |H(f)|² × |W(f)|²"
            ),
            SpectralReason::WelchEstimate => write!(
                f,
                "linear model under a recorded base taken as stationary: a_w, a_v and SEAT from \
                 the Welch PSD of the base samples of the run × |H(f)|² × |W(f)|²"
            ),
            SpectralReason::SteadySine => write!(
                f,
                "linear model under a steady sine: a_w, a_v and SEAT of the steady state \
                 (|H(f)|·|W(f)|·A/√2)"
            ),
        }
    }
}

impl fmt::Display for TimeDomainReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TimeDomainReason::Requested => write!(f, "--time-domain was given"),
            TimeDomainReason::Nonlinear { links } => write!(
                f,
                "the model is nonlinear (links {}): no frequency response describes it",
                links.join(", ")
            ),
            TimeDomainReason::NonStationary { kind } => write!(
                f,
                "the {kind} excitation is not stationary: its spectrum changes with time"
            ),
        }
    }
}

impl fmt::Display for Path {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Path::Spectral { reason } => write!(
                f,
                "spectral ({reason}); VDV, MTVV and crest factor need a time history: \
                 --time-domain computes them"
            ),
            Path::TimeDomain { reason } => write!(
                f,
                "time-domain, batched ({reason}): every figure from simulated time histories"
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;

    #[test]
    fn linear_models_under_stationary_inputs_go_spectral() {
        let model = catalog::resolve("reference").unwrap();
        let exc = |n: &str| ExcitationSpec::load(n).unwrap();
        for n in ["bell-214", "white-0.5-80", "road-c-72kmh"] {
            assert_eq!(
                choose(&model, &exc(n), false),
                Path::Spectral {
                    reason: SpectralReason::StationaryRandom
                },
                "{n}"
            );
        }
        assert!(choose(&model, &exc("sine-4hz"), false).is_spectral());
        assert_eq!(
            choose(&model, &exc("sweep-0.5-20"), false),
            Path::TimeDomain {
                reason: TimeDomainReason::NonStationary { kind: "sweep" }
            }
        );
        assert_eq!(
            choose(&model, &exc("bell-214"), true),
            Path::TimeDomain {
                reason: TimeDomainReason::Requested
            }
        );
        assert_eq!(
            Path::TimeDomain {
                reason: TimeDomainReason::Requested
            }
            .figures()
            .len(),
            7
        );
    }
}
