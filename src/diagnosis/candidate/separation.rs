//! Which measurement tells two look-alike candidates apart (docs/gap.md §8): when two effects of
//! different families explain the runs equally well, the verdict names both and this measurement.

use super::Candidate::{self, *};
use super::Family;

/// One pair rule: the candidates it tells apart and the measurement that does.
struct Separation {
    applies: fn(Candidate, Candidate) -> bool,
    measurement: &'static str,
}

/// Whether {a, b} is one of `x` with one of `y`.
fn pair(a: Candidate, b: Candidate, x: &[Candidate], y: &[Candidate]) -> bool {
    (x.contains(&a) && y.contains(&b)) || (x.contains(&b) && y.contains(&a))
}

/// Whether `a` or `b` is `c`.
fn either(a: Candidate, b: Candidate, c: Candidate) -> bool {
    a == c || b == c
}

/// The pair rules, most specific first: the first that applies names the measurement.
const SEPARATIONS: [Separation; 11] = [
    Separation {
        applies: |a, b| {
            pair(
                a,
                b,
                &[CushionStiffening, CushionContact],
                &[CushionViscoelastic],
            )
        },
        measurement: "a run at a clearly different magnitude (stiffening grows with amplitude, viscoelasticity does not)",
    },
    Separation {
        applies: |a, b| {
            pair(
                a,
                b,
                &[BodySoftening, BodySofteningMagnitude],
                &[CushionStiffening, CushionViscoelastic],
            )
        },
        measurement: "the seat-head path or the seat force (body effects move apparent mass and seat-head, cushion effects only base-seat)",
    },
    Separation {
        applies: |a, b| {
            pair(
                a,
                b,
                &[CushionViscoelastic, CushionStiffening],
                &[MissingDof],
            )
        },
        measurement: "a base-seat measurement above 20 Hz or a frame accelerometer (a frame mode shows as a narrow peak)",
    },
    Separation {
        applies: |a, b| a.family() == Family::Sensor || b.family() == Family::Sensor,
        measurement: "a sensor calibration: a shaker run against a reference accelerometer gives each channel's gain, group delay and mount response",
    },
    Separation {
        applies: |a, b| pair(a, b, &[HandsSupport], &[Backrest]),
        measurement: "a run with the hands off the wheel or handle, or a wheel (hand) force: both paths reach the upper torso, only the hands' passes through the arms",
    },
    Separation {
        applies: |a, b| pair(a, b, &[HandsSupport], &[FeetSupport, ThighSupport]),
        measurement: "a head accelerometer with the seat-pan force f_seat_z (a path to the shoulders shapes seat-head, one to the pelvis the apparent mass), or a wheel (hand) force or accelerometer",
    },
    Separation {
        applies: |a, b| either(a, b, Backrest),
        measurement: "a run without backrest contact, or the backrest's vertical force f_back_z (only a backrest carries it: it drives the torso past the seat pan)",
    },
    Separation {
        applies: |a, b| either(a, b, ThighSupport),
        measurement: "the seat-pan force f_seat_z, or a run with the thighs clear of the seat's front edge (a thigh path carries weight past the seat pan; without the force it looks like a stiffer cushion)",
    },
    Separation {
        applies: |a, b| either(a, b, FeetSupport),
        measurement: "a run with the feet on a fixed floor, or a footrest force (the feet carry part of the thighs past the seat pan)",
    },
    Separation {
        applies: |a, b| either(a, b, HandsSupport),
        measurement: "a run with the hands off the wheel or handle, or a wheel (hand) force (the arms carry part of the upper torso past the seat pan)",
    },
    Separation {
        applies: |a, b| pair(a, b, &[MissingDof], &[BodyMode]),
        measurement: "a frame accelerometer (a frame mode moves base-seat and the frame, a body mode seat-head)",
    },
];

/// Without a pair rule: more runs, at a third magnitude.
const REPEAT: &str = "a repeat run and a run at a third magnitude";

/// The measurement that separates candidates `a` and `b`.
pub fn separating_measurement(a: Candidate, b: Candidate) -> &'static str {
    SEPARATIONS
        .iter()
        .find(|s| (s.applies)(a, b))
        .map_or(REPEAT, |s| s.measurement)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_most_specific_rule_names_the_measurement() {
        let m = separating_measurement;
        // Symmetric in its arguments.
        for a in Candidate::ALL {
            for b in Candidate::ALL {
                assert_eq!(m(a, b), m(b, a), "{a:?} {b:?}");
            }
        }
        assert!(
            m(CushionContact, CushionViscoelastic)
                .starts_with("a run at a clearly different magnitude")
        );
        // A sensor pair rule comes before the support paths'.
        assert!(m(SensorDelay, Backrest).starts_with("a sensor calibration"));
        assert!(m(Backrest, FeetSupport).starts_with("a run without backrest contact"));
        assert!(m(FeetSupport, BodyMode).starts_with("a run with the feet on a fixed floor"));
        // The hands' path against the other support paths: by where it enters the body.
        assert!(m(HandsSupport, Backrest).starts_with("a run with the hands off the wheel"));
        assert!(m(Backrest, HandsSupport).contains("through the arms"));
        for lower in [FeetSupport, ThighSupport] {
            assert!(
                m(lower, HandsSupport).starts_with("a head accelerometer with the seat-pan force")
            );
        }
        assert!(m(HandsSupport, BodyMode).contains("the arms carry part of the upper torso"));
        assert!(m(SensorGain, HandsSupport).starts_with("a sensor calibration"));
        assert_eq!(m(EndStop, CushionFractional), REPEAT);
    }
}
