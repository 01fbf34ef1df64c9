//! Frequency-domain responses of a model: transmissibilities, apparent mass and impedance
//! ([`frf`]), and its modes ([`modes`]).

pub mod frf;
pub mod modes;
pub mod peak;
