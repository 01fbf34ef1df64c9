//! Frequency-domain responses of a model: transmissibilities, apparent mass and impedance
//! ([`frf`]), its modes ([`modes`]), and the statistically linearised system of a nonlinear one
//! under a stationary input ([`linearise`]).

pub mod frf;
pub mod linearise;
pub mod modes;
pub mod peak;
