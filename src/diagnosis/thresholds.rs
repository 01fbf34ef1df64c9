//! The thresholds of the diagnosis's decisions (docs/gap.md §6 and §7), in one place.

/// ΔBIC (held-out) an effect must reach against the null re-fit to be *detected* (docs/gap.md §6.3:
/// "strong evidence", Kass & Raftery, JASA 90 (1995) 773–795).
pub const ACCEPT_DELTA_BIC: f64 = -10.0;
/// Reduced χ² of the null re-fit on the held-out run above which a structural gap is declared.
pub const GAP_CHI2: f64 = 2.0;
/// Fraction of the structural gap a detected effect must close to be named as its explanation.
pub const MIN_CLOSED: f64 = 0.25;
/// Band-gap RMS (dB) and phase-gap RMS (degrees) below which a remaining gap that *no candidate
/// explains* is of no practical size (noise-free data make χ² arbitrarily large). It never hides a
/// detected effect.
pub const PRACTICAL_GAP: (f64, f64) = (0.2, 2.0);
/// Sizes below which a detected effect is called practically small: 1 % of a_w, 1 SEAT point,
/// 0.5 dB band-gap RMS.
pub const PRACTICAL_SIZE: (f64, f64, f64) = (1.0, 1.0, 0.5);
/// Change of the check run's a_w gap (%) and SEAT gap (points) above which a named effect is
/// said to move the ISO figures away from the measurement: half the practically-small sizes.
pub const VISIBLE_SIZE: (f64, f64) = (0.5, 0.5);
/// BIC margin below which the two best candidates are not distinguishable (a likelihood ratio of
/// e³ ≈ 20).
pub const IDENTIFIABLE_MARGIN: f64 = 6.0;
/// Fewest coherent bins a path needs in a run to be judged there.
pub const MIN_PATH_BINS: usize = 6;
