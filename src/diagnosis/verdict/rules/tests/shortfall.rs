//! The shortfall rule (docs/gap.md §7 rule 11): when the named effect(s) explain the check run,
//! read on its reduced χ² (the linearisation's or the replay's) and its ISO figures.

use super::*;

#[test]
fn a_named_effect_that_leaves_the_check_run_far_from_the_measurement_is_partial() {
    use crate::diagnosis::thresholds::{EXPLAINED_CHI2, ISO_AWAY};
    use crate::diagnosis::verdict::{Shortfall, shortfall};
    let null = ranked("null", 30.0, 300.0, 0.0, 0.0, 0.0).check;
    let stage = |chi2: f64, aw: f64, seat: f64| {
        let mut s = null.clone();
        s.chi2_red = chi2;
        s.weighted.aw_gap_percent = aw;
        s.weighted.seat_model = s.weighted.seat_meas + seat;
        s
    };
    // Within the noise's reach and the ISO figures unmoved: explained.
    assert_eq!(
        shortfall(&null, &stage(EXPLAINED_CHI2 * 0.9, 0.0, 0.0)),
        None
    );
    // Far above the noise: the χ² rule, whatever the ISO figures do.
    assert_eq!(
        shortfall(&null, &stage(EXPLAINED_CHI2 * 1.1, 0.0, 0.0)),
        Some(Shortfall::FarAboveNoise {
            chi2_red: EXPLAINED_CHI2 * 1.1
        })
    );
    // The a_w gap alone, or the SEAT gap alone, moving away by the threshold.
    for (aw, seat) in [(ISO_AWAY.0, 0.0), (0.0, -ISO_AWAY.1)] {
        assert!(matches!(
            shortfall(&null, &stage(3.0, aw, seat)),
            Some(Shortfall::IsoAway { .. })
        ));
    }
    // Moving toward the measurement from a gap is not moving away.
    let mut from = null.clone();
    from.weighted.aw_gap_percent = 5.0;
    assert_eq!(shortfall(&from, &stage(3.0, -2.0, 0.0)), None);
    // A move inside twice the standard error the fitted parameters give is their scatter; the
    // same move with a tight fit is the form's.
    let with_sigma = |aw_sigma: f64| {
        let mut s = stage(3.0, 2.0 * ISO_AWAY.0, 0.0);
        s.iso_sigma = Some(crate::diagnosis::outcome::IsoSigma {
            aw_percent: aw_sigma,
            seat_points: 0.1,
        });
        s
    };
    assert_eq!(shortfall(&null, &with_sigma(1.2 * ISO_AWAY.0)), None);
    assert!(matches!(
        shortfall(&null, &with_sigma(0.5 * ISO_AWAY.0)),
        Some(Shortfall::IsoAway { sigma: Some(_), .. })
    ));
}

#[test]
fn a_law_whose_replay_explains_the_check_run_is_not_far_above_the_noise() {
    use crate::diagnosis::thresholds::EXPLAINED_CHI2;
    use crate::diagnosis::verdict::{Shortfall, shortfall};
    let null = ranked("null", 30.0, 300.0, 0.0, 0.0, 0.0).check;
    let stage = |linearised: f64, replayed: Option<f64>| {
        let mut s = null.clone();
        s.chi2_red = linearised;
        s.replayed_chi2_red = replayed;
        s
    };
    // A strong strap: its statistical linearisation far above the noise, its replay within.
    let strap = stage(4.0 * EXPLAINED_CHI2, Some(0.9 * EXPLAINED_CHI2));
    assert_eq!(strap.explained_chi2_red(), 0.9 * EXPLAINED_CHI2);
    assert_eq!(shortfall(&null, &strap), None);
    // Both far above: structure is missing, and the lower of the two is what is reported.
    let both = stage(4.0 * EXPLAINED_CHI2, Some(1.5 * EXPLAINED_CHI2));
    assert_eq!(
        shortfall(&null, &both),
        Some(Shortfall::FarAboveNoise {
            chi2_red: 1.5 * EXPLAINED_CHI2
        })
    );
    // A replay worse than the linearisation does not undo a fit the linearisation explains.
    assert_eq!(
        shortfall(
            &null,
            &stage(0.5 * EXPLAINED_CHI2, Some(3.0 * EXPLAINED_CHI2))
        ),
        None
    );
    // Not replayed (a linear effect): its own χ².
    assert!(matches!(
        shortfall(&null, &stage(1.1 * EXPLAINED_CHI2, None)),
        Some(Shortfall::FarAboveNoise { .. })
    ));
}

#[test]
fn the_iso_figures_decide_only_for_linear_effects() {
    use crate::diagnosis::verdict::Shortfall;
    let far = Shortfall::FarAboveNoise { chi2_red: 300.0 };
    let away = Shortfall::IsoAway {
        aw_gap_percent: (0.1, 2.0),
        seat_gap_points: (0.1, 1.5),
        sigma: None,
    };
    // A residual far above the noise is structure missing, whatever the effect.
    assert!(far.decides(true) && far.decides(false));
    // A linear effect's model predicts the seat PSD in full; an equivalent-linear one does not.
    assert!(away.decides(true));
    assert!(!away.decides(false));
}
