//! The seat suspension (docs/gap.md §5): Coulomb friction in its guides and end-stops past its
//! free travel. Both act on the first suspension link.

use super::*;
use crate::system::Law;

/// The family's candidates, in report order.
pub static DEFINITIONS: &[Candidate] = &[&FRICTION, &END_STOP];

/// Reference velocity of the friction law in m/s (tanh regularisation width).
pub const FRICTION_V_REF: f64 = 0.01;

/// Whether the model has a suspension.
fn has_suspension(s: &System) -> bool {
    role_link(s, Role::Suspension).is_some()
}

/// Coulomb friction on the suspension, F_c tanh(v/v_ref). Its share of the force falls as the
/// magnitude rises, so its distortion does not grow with magnitude.
pub static FRICTION: Definition = Definition {
    id: "suspension-friction",
    family: Family::Suspension,
    params: || vec![Param::new("f_c_n", 0.5, 1000.0, &[5.0, 50.0], true)],
    applies_to: has_suspension,
    apply: |v, p| {
        let s = &mut v.system;
        let i = need(FRICTION.id, role_link(s, Role::Suspension), "suspension")?;
        s.links[i].law = Some(Law::Friction {
            f_c: p[0],
            v_ref: FRICTION_V_REF,
        });
        Ok(())
    },
    magnitude: Magnitude::Dependent {
        at: Place::Support,
        distortion_grows: false,
    },
    ..Definition::COMMON
};

/// End-stops on the suspension beyond ±gap (E6, `Law::EndStop`): a stop of stiffness
/// k_stop = ratio·k_s (both free) adds to the suspension spring past the free travel, so its
/// equivalent stiffness k_s + k_stop·erfc(gap/(σ√2)) grows with the stroke r.m.s. σ. The ratio is
/// free because a real bump stop is progressive rubber: its Gaussian-equivalent stiffness ratio is
/// anywhere from ~0.3 to 30 depending on how far the stroke penetrates, and a fixed ratio forces
/// the gap to absorb that spread.
pub static END_STOP: Definition = Definition {
    id: "end-stop",
    family: Family::Suspension,
    // Gap from 0.2 mm (a stiff suspension's stroke at low magnitude is ~0.5 mm r.m.s.) to 10 cm
    // (a soft suspension's free travel); the starts span a stiff seat's stroke to a soft one's.
    // The stop from a tenth of the suspension's stiffness (the first touch of a progressive rubber
    // stop) to thirty times it (a hard stop).
    params: || {
        vec![
            Param::new("gap_m", 2e-4, 0.1, &[0.0007, 0.002, 0.02], true),
            Param::new("k_stop_over_k", 0.1, 30.0, &[1.0, 5.0], true),
        ]
    },
    applies_to: has_suspension,
    apply: |v, p| {
        let s = &mut v.system;
        let i = need(END_STOP.id, role_link(s, Role::Suspension), "suspension")?;
        let k = s.links[i].element.static_stiffness();
        s.links[i].law = Some(Law::EndStop {
            gap: p[0],
            k_stop: p[1] * k,
        });
        Ok(())
    },
    magnitude: Magnitude::Dependent {
        at: Place::Support,
        distortion_grows: true,
    },
    ..Definition::COMMON
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;

    #[test]
    fn end_stop_scales_its_stop_with_the_suspension_stiffness() {
        // k_stop = ratio·k_s with both the gap and the ratio free (no fixed stop stiffness).
        let s = catalog::resolve("seed001-full").unwrap().system().clone();
        let i = role_link(&s, Role::Suspension).unwrap();
        let k = s.links[i].element.static_stiffness();
        for (gap, ratio) in [(0.0007, 0.3), (0.002, 25.0)] {
            let v = END_STOP.apply(&s, &[gap, ratio]).unwrap();
            assert_eq!(
                v.system.links[i].law,
                Some(Law::EndStop {
                    gap,
                    k_stop: ratio * k
                })
            );
        }
        let names: Vec<String> = END_STOP.params().into_iter().map(|p| p.name).collect();
        assert_eq!(names, ["gap_m", "k_stop_over_k"]);
    }
}
