//! Which measurement tells two look-alike candidates apart (docs/gap.md §8): when two effects of
//! different families explain the runs equally well, the verdict names both and this measurement.
//! The pair rules read the candidates' marks ([`Look`]) and families, never their names, so a new
//! candidate enters them through the marks its definition carries.

use super::{Candidate, Family, Look};

/// One pair rule: the measurement that tells `a` and `b` apart, if the rule applies to them.
type Separation = fn(Candidate, Candidate) -> Option<&'static str>;

/// Whether {a, b} is one candidate marked `x` with one marked `y`.
fn pair(a: Candidate, b: Candidate, x: Look, y: Look) -> bool {
    (a.looks(x) && b.looks(y)) || (b.looks(x) && a.looks(y))
}

/// The measurement of its own of whichever of `a`, `b` is marked `look`.
fn own(a: Candidate, b: Candidate, look: Look) -> Option<&'static str> {
    [a, b]
        .into_iter()
        .find(|c| c.looks(look))
        .and_then(|c| c.told_apart_by)
}

/// Whether {a, b} are a one-sided and a two-sided support path onto the same place of the body
/// (the upper torso, the pelvis past the seat pan, the pelvis through the feet, or the head).
fn one_sided_beside_two_sided(a: Candidate, b: Candidate) -> bool {
    let same_place = [Look::UpperTorso, Look::Thighs, Look::Feet, Look::Head]
        .into_iter()
        .any(|place| a.looks(place) && b.looks(place));
    same_place && a.looks(Look::OneSided) != b.looks(Look::OneSided)
}

/// `m` when `applies`.
fn when(applies: bool, m: &'static str) -> Option<&'static str> {
    applies.then_some(m)
}

/// The pair rules, most specific first: the first that applies names the measurement.
const SEPARATIONS: [Separation; 13] = [
    |a, b| {
        when(
            pair(a, b, Look::GrowsWithMagnitude, Look::SameAtEveryMagnitude),
            "a run at a clearly different magnitude (stiffening grows with amplitude, viscoelasticity does not)",
        )
    },
    |a, b| {
        when(
            pair(a, b, Look::BodyPaths, Look::SeatPathOnly),
            "the seat-head path or the seat force (body effects move apparent mass and seat-head, cushion effects only base-seat)",
        )
    },
    |a, b| {
        when(
            pair(a, b, Look::Broadband, Look::FrameMode),
            "a base-seat measurement above 20 Hz or a frame accelerometer (a frame mode shows as a narrow peak)",
        )
    },
    |a, b| {
        when(
            a.family == Family::Sensor || b.family == Family::Sensor,
            "a sensor calibration: a shaker run against a reference accelerometer gives each channel's gain, group delay and mount response",
        )
    },
    |a, b| {
        when(
            pair(a, b, Look::Shoulders, Look::UpperTorso),
            "a run with the hands off the wheel or handle, or a wheel (hand) force: both paths reach the upper torso, only the hands' passes through the arms",
        )
    },
    |a, b| {
        when(
            pair(a, b, Look::Shoulders, Look::Feet) || pair(a, b, Look::Shoulders, Look::Thighs),
            "a head accelerometer with the seat-pan force f_seat_z (a path to the shoulders shapes seat-head, one to the pelvis the apparent mass), or a wheel (hand) force or accelerometer",
        )
    },
    |a, b| {
        when(
            one_sided_beside_two_sided(a, b),
            "a run at a clearly different magnitude, or the path's own force: a one-sided path's share changes with the magnitude (a strap pulls only past its slack, a foot carries only while it keeps contact), a two-sided path carries the same share at every magnitude",
        )
    },
    |a, b| own(a, b, Look::Head),
    |a, b| own(a, b, Look::UpperTorso),
    |a, b| own(a, b, Look::Thighs),
    |a, b| own(a, b, Look::Feet),
    |a, b| own(a, b, Look::Shoulders),
    |a, b| {
        when(
            pair(a, b, Look::FrameMode, Look::BodyMode),
            "a frame accelerometer (a frame mode moves base-seat and the frame, a body mode seat-head)",
        )
    },
];

/// Without a pair rule: more runs, at a third magnitude.
const REPEAT: &str = "a repeat run and a run at a third magnitude";

/// The measurement that separates candidates `a` and `b`.
pub fn separating_measurement(a: Candidate, b: Candidate) -> &'static str {
    SEPARATIONS.iter().find_map(|s| s(a, b)).unwrap_or(REPEAT)
}

#[cfg(test)]
mod tests {
    use super::super::{
        all, missing_dof, sensor, softening, stiffening, support, suspension, viscoelastic,
    };
    use super::*;

    #[test]
    fn the_most_specific_rule_names_the_measurement() {
        let m = separating_measurement;
        // Symmetric in its arguments.
        for a in all() {
            for b in all() {
                assert_eq!(m(a, b), m(b, a), "{a:?} {b:?}");
            }
        }
        let (backrest, hands, feet, thigh) = (
            &support::BACKREST,
            &support::HANDS,
            &support::FEET,
            &support::THIGH,
        );
        assert!(
            m(
                &stiffening::CUSHION_CONTACT,
                &viscoelastic::CUSHION_VISCOELASTIC
            )
            .starts_with("a run at a clearly different magnitude")
        );
        assert!(
            m(&softening::BODY_SOFTENING, &stiffening::CUSHION_STIFFENING)
                .starts_with("the seat-head path")
        );
        assert!(
            m(&viscoelastic::CUSHION_VISCOELASTIC, &missing_dof::FRAME)
                .starts_with("a base-seat measurement above 20 Hz")
        );
        // A sensor pair rule comes before the support paths'.
        assert!(m(&sensor::DELAY, backrest).starts_with("a sensor calibration"));
        assert!(m(backrest, feet).starts_with("a run without backrest contact"));
        assert!(
            m(thigh, feet).starts_with("the seat-pan force f_seat_z, or a run with the thighs")
        );
        assert!(
            m(feet, &missing_dof::BODY_MODE).starts_with("a run with the feet on a fixed floor")
        );
        // The hands' path against the other support paths: by where it enters the body.
        assert!(m(hands, backrest).starts_with("a run with the hands off the wheel"));
        assert!(m(backrest, hands).contains("through the arms"));
        for lower in [feet, thigh] {
            assert!(m(lower, hands).starts_with("a head accelerometer with the seat-pan force"));
        }
        assert!(
            m(hands, &missing_dof::BODY_MODE).contains("the arms carry part of the upper torso")
        );
        assert!(m(&sensor::GAIN, hands).starts_with("a sensor calibration"));
        assert!(
            m(&missing_dof::FRAME, &missing_dof::BODY_MODE).starts_with("a frame accelerometer")
        );
        // A one-sided path against a two-sided one at its own place: by magnitude or the path's
        // force; against a path elsewhere, by the place's own measurement.
        let (harness, belt, lift) = (
            &support::HARNESS,
            &support::LAP_BELT,
            &support::FEET_LIFT_OFF,
        );
        for (one_sided, two_sided) in [(harness, backrest), (belt, thigh), (lift, feet)] {
            assert!(
                m(one_sided, two_sided)
                    .starts_with("a run at a clearly different magnitude, or the path's own force")
            );
        }
        assert!(m(lift, thigh).starts_with("the seat-pan force f_seat_z"));
        assert!(m(lift, hands).starts_with("a head accelerometer with the seat-pan force"));
        assert!(m(belt, backrest).starts_with("a run without backrest contact"));
        assert!(m(harness, belt).starts_with("a run with the harness slackened"));
        assert!(m(belt, feet).starts_with("a run with the lap belt slackened"));
        // A path onto the head against one onto the torso: by the head's own path.
        let head = &support::HEAD_RESTRAINT;
        for torso in [backrest, harness, hands] {
            assert!(m(head, torso).starts_with("a run with the head off the restraint"));
        }
        assert_eq!(
            m(&suspension::END_STOP, &viscoelastic::CUSHION_FRACTIONAL),
            REPEAT
        );
    }
}
