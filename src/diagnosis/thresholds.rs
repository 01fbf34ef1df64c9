//! The thresholds of the diagnosis's decisions (docs/gap.md §6 and §7), in one place.

/// ΔBIC (held-out) an effect must reach against the null re-fit to be *detected* (docs/gap.md §6.3:
/// "strong evidence", Kass & Raftery, JASA 90 (1995) 773–795).
pub const ACCEPT_DELTA_BIC: f64 = -10.0;
/// ΔBIC (held-out) an effect must reach to be named when the null re-fit already fits the check
/// run within the noise (reduced χ² within its own scatter of 1,
/// [`super::score::chi2_within_noise`]): with ~10³ residuals a systematic error far below the noise
/// (the base floor's bias, imperfectly undone; a sampling lag) reaches −10. Set from clean field-like
/// cases (road and helicopter bases, 200–500 Hz loggers, a base accelerometer floor of 3–4 % of its
/// r.m.s., with and without a force plate; 80 cases): at −10 12 of 80 named an effect (10 of 30 on
/// road at 200 Hz with a force plate), at −30 2 of 80 (2 of 30), the rate the issue allows being 0.10.
pub const ACCEPT_WITHIN_NOISE_DELTA_BIC: f64 = -30.0;
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
/// Reduced χ² on the check run that a named effect (with any second effect) must bring the model
/// below to be the explanation: the residual's variance is then within this factor of the noise
/// estimate's. A named form only close to the truth's (one Maxwell arm for a power-law foam) leaves
/// a few times the noise; a structure missing more than the effect adds leaves hundreds.
pub const EXPLAINED_CHI2: f64 = 50.0;
/// Growth of the check run's a_w gap (%) or SEAT gap (points) with the named effect(s), against
/// the re-fitted base model, at which the effect does not explain the runs as the user judges
/// them (ISO 2631-1 a_w, SEAT).
pub const ISO_AWAY: (f64, f64) = (1.0, 1.0);
/// BIC margin below which the two best candidates are not distinguishable (a likelihood ratio of
/// e³ ≈ 20).
pub const IDENTIFIABLE_MARGIN: f64 = 6.0;
/// Fewest coherent bins a path needs in a run to be judged there.
pub const MIN_PATH_BINS: usize = 6;
