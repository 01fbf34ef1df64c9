//! Parameter studies on the frequency-domain responses (and, with an excitation, the time-domain
//! ISO 2631-1 figures of every point, [`iso`]): sweeps (1-D and 2-D grids), single-factor
//! sensitivity (paper 000 §5.1), calibration against a measured response (paper 000 §5.2: GA,
//! cubic surrogate; plus Levenberg–Marquardt), the foam-thickness study (paper 000 Table 4) and
//! sharding of every grid over processes (`--shard K/N`, merged by [`shard::merge`]).
//!
//! Every study evaluates responses through [`evaluate::Evaluator`], which solves the complex
//! dynamic-stiffness system only at the requested frequencies without allocating.

pub mod batch;
pub mod calibrate;
pub mod evaluate;
pub mod foam;
#[cfg(feature = "plot")]
pub mod heatmap;
pub mod iso;
pub mod paper000;
pub mod papers;
pub mod param;
pub mod path;
pub mod plan;
pub mod reproduce;
pub mod seat_test;
pub mod sensitivity;
pub mod shard;
pub mod spectral;
pub mod sweep;
pub mod table;
