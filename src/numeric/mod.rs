//! Numerical tools shared by calibration and the gap diagnosis, independent of any model.

pub mod lm;
