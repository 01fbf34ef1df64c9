//! Cushion stiffening (docs/gap.md §5): the foam stiffens with its deflection, in three forms so
//! that the report names the form that fits better. Each acts on every Kelvin–Voigt cushion link
//! (a segment model's foam under each contact, in both axes) with one relative law.

use super::*;
use crate::system::Law;

/// The family's candidates, in report order.
pub static DEFINITIONS: &[Candidate] = &[
    &CUSHION_STIFFENING,
    &CUSHION_CONTACT,
    &CUSHION_BOTTOMING,
    &CUSHION_POWER_FOAM,
];

/// A nonlinearity between base and seat whose distortion grows with magnitude.
const SUPPORT_NONLINEAR: Magnitude = Magnitude::Dependent {
    at: Place::Support,
    distortion_grows: true,
};

/// Cubic stiffening, F = k d + k3 d³. k3 is stated for the first cushion link and scaled by each
/// link's stiffness, so every link stiffens at the same deflection.
pub static CUSHION_STIFFENING: Definition = Definition {
    id: "cushion-stiffening",
    family: Family::CushionStiffening,
    params: || vec![Param::new("k3_n_m3", 1e6, 1e12, &[1e8, 3e9, 1e11], true)],
    applies_to: |s| !cushion_links(s).is_empty(),
    apply: |v, p| {
        let s = &mut v.system;
        let c = cushion_or_err(CUSHION_STIFFENING.id, s)?;
        let k_first = s.links[c[0]].element.static_stiffness();
        for i in c {
            let k3 = p[0] * s.links[i].element.static_stiffness() / k_first;
            s.links[i].law = Some(Law::Cubic { k3 });
        }
        Ok(())
    },
    magnitude: SUPPORT_NONLINEAR,
    looks: &[
        Look::GrowsWithMagnitude,
        Look::SeatPathOnly,
        Look::Broadband,
    ],
    ..Definition::COMMON
};

/// Quadratic contact stiffening, F = k d (1 + |d|/d0): the second stiffening form.
pub static CUSHION_CONTACT: Definition = Definition {
    id: "cushion-contact",
    family: Family::CushionStiffening,
    params: || vec![Param::new("d0_m", 1e-4, 1.0, &[0.002, 0.02, 0.2], true)],
    applies_to: |s| !cushion_links(s).is_empty(),
    apply: |v, p| {
        let s = &mut v.system;
        for i in cushion_or_err(CUSHION_CONTACT.id, s)? {
            s.links[i].law = Some(Law::Contact { d0: p[0] });
        }
        Ok(())
    },
    magnitude: SUPPORT_NONLINEAR,
    looks: &[Look::GrowsWithMagnitude],
    ..Definition::COMMON
};

/// Bottoming of the cushion under the occupant's preload: a compression-only stop, a second layer
/// of stiffness k_stop = ratio·k that touches `gap` (m) past the static sag (`Law::Bottoming`).
/// Unlike the symmetric laws it stiffens on one side only, so its equivalent stiffness
/// k + k_stop·P(compression > gap) grows with the run's r.m.s. and the pad motion turns asymmetric
/// — the signature of foam loaded by the body's weight. One gap for every cushion link (they share
/// the seat's deflection); each link's stop in proportion to its own stiffness.
pub static CUSHION_BOTTOMING: Definition = Definition {
    id: "cushion-bottoming",
    family: Family::CushionStiffening,
    // Gap from 0.1 mm (a layer touching at the sag) to 5 cm; the stop from a tenth of the
    // cushion's stiffness to thirty times it. The starts bracket the cushion's r.m.s. deflection
    // at 0.25–2 m/s² (about 1–5 mm on the reference seat).
    params: || {
        vec![
            Param::new("gap_m", 1e-4, 0.05, &[0.001, 0.004], true),
            Param::new("k_stop_over_k", 0.1, 30.0, &[1.0], true),
        ]
    },
    applies_to: |s| !cushion_links(s).is_empty(),
    apply: |v, p| {
        let s = &mut v.system;
        for i in cushion_or_err(CUSHION_BOTTOMING.id, s)? {
            let k_stop = p[1] * s.links[i].element.static_stiffness();
            s.links[i].law = Some(Law::Bottoming { gap: p[0], k_stop });
        }
        Ok(())
    },
    magnitude: SUPPORT_NONLINEAR,
    ..Definition::COMMON
};

/// A preloaded foam whose force is a power of its total compression (`Law::PowerFoam`): stiffer
/// in compression and softer in extension about the static sag, and off once the occupant rises
/// past it. A foam loaded by the body's weight is asymmetric this way (a symmetric law, cubic or
/// contact, stiffens on both sides); at the magnitudes where the pad nearly unloads its equivalent
/// stiffness falls again, which no stiffening-only law can follow. One sag and exponent for every
/// cushion link (they share the seat's deflection).
pub static CUSHION_POWER_FOAM: Definition = Definition {
    id: "cushion-power-foam",
    family: Family::CushionStiffening,
    // The sag from 2 mm to 10 cm (a seat foam sags 5–40 mm under a seated body); the exponent
    // from linear (1) to 4, a densifying foam's stiffness at twice its sag 27 times its tangent
    // at rest (steeper laws turn a run's deepest compressions into stiffnesses no step resolves).
    params: || {
        vec![
            Param::new("sag_m", 2e-3, 0.1, &[0.004, 0.02], true),
            Param::new("n", 1.0, 4.0, &[2.0], false),
        ]
    },
    applies_to: |s| !cushion_links(s).is_empty(),
    apply: |v, p| {
        let s = &mut v.system;
        for i in cushion_or_err(CUSHION_POWER_FOAM.id, s)? {
            s.links[i].law = Some(Law::PowerFoam { sag: p[0], n: p[1] });
        }
        Ok(())
    },
    magnitude: SUPPORT_NONLINEAR,
    looks: &[Look::GrowsWithMagnitude, Look::SeatPathOnly],
    ..Definition::COMMON
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;

    #[test]
    fn bottoming_puts_a_compression_stop_on_every_cushion_link() {
        let s = catalog::resolve("reference").unwrap().system().clone();
        let v = CUSHION_BOTTOMING.apply(&s, &[0.002, 1.5]).unwrap();
        let cushion = cushion_links(&s);
        assert!(!cushion.is_empty());
        for &i in &cushion {
            let k = s.links[i].element.static_stiffness();
            assert_eq!(
                v.system.links[i].law,
                Some(Law::Bottoming {
                    gap: 0.002,
                    k_stop: 1.5 * k
                })
            );
        }
        assert_eq!(CUSHION_BOTTOMING.family, Family::CushionStiffening);
        assert!(CUSHION_BOTTOMING.amplitude_dependent());
    }

    #[test]
    fn a_power_foam_is_tangent_at_rest_stiffer_in_compression_and_off_past_its_sag() {
        let (k, c, sag, n) = (80e3, 500.0, 0.01, 3.0);
        let law = Law::PowerFoam { sag, n };
        // Closed form of F₀·[1 − (1 − d/D₀)ⁿ], F₀ = k·D₀/n.
        let f = |d: f64| k * sag / n * (1.0 - (1.0 - d / sag).powf(n));
        // Compressing (v < 0), the foam pushes at every deflection short of the sag.
        for d in [-0.02, -0.005, 0.0, 0.004, 0.009] {
            let (got, kd, cv) = law.force(k, c, d, -0.1);
            assert!((got - (f(d) - c * 0.1)).abs() < 1e-9 * k * sag, "{d}");
            assert!((kd - k * (1.0 - d / sag).powf(n - 1.0)).abs() < 1e-9 * k);
            assert_eq!(cv, c);
        }
        assert_eq!(law.tangent_at_rest(k, c), (k, c));
        assert!(law.force(k, c, -0.005, 0.0).1 > k && law.force(k, c, 0.005, 0.0).1 < k);
        assert_eq!(law.force(k, c, 0.012, 0.3), (k * sag / n, 0.0, 0.0));
        // Continuous where it lets go: leaving fast enough unloads it before the sag.
        let v_off = (k * sag / n - f(0.009)) / c;
        assert_eq!(
            law.force(k, c, 0.009, v_off * 1.01),
            (k * sag / n, 0.0, 0.0)
        );
        assert!((law.force(k, c, 0.009, v_off * 0.99).0 - k * sag / n).abs() < 0.02 * k * sag / n);
        let s = catalog::resolve("reference").unwrap().system().clone();
        let v = CUSHION_POWER_FOAM.apply(&s, &[sag, n]).unwrap();
        for i in cushion_links(&s) {
            assert_eq!(v.system.links[i].law, Some(law));
        }
    }
}
