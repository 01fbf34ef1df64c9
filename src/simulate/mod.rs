//! Time-domain simulation: drives a model with an excitation through an integrator and hands every
//! step to observers (the MCAP recorder, in-memory collectors for analysis, CSV writers).

pub mod observer;
