//! The whole chain of a file: every mass grounded, the seat component's top, and the measured
//! nodes (seat, head, interface links).

use super::Checker;
use super::spec::FileSpec;
use crate::error::Result;
use crate::model::chain::{Chain, Kind, Link, Mass, Measure, Node};

/// The chain of the checked `masses` and `links` of `spec` (model `kind`, file `text`).
pub(super) fn finish(
    cx: &Checker<'_>,
    spec: FileSpec,
    kind: Kind,
    masses: Vec<Mass>,
    links: Vec<Link>,
    text: &str,
) -> Result<Chain> {
    // Every mass needs a path to the base, or the static problem is singular.
    let mut grounded = vec![false; masses.len()];
    let mut changed = true;
    while changed {
        changed = false;
        for l in &links {
            if l.element.static_stiffness() <= 0.0 && l.element.locked_stiffness() <= 0.0 {
                continue;
            }
            for (x, y) in [(l.a, l.b), (l.b, l.a)] {
                let on = match y {
                    Node::Base => true,
                    Node::Mass(j) => grounded[j],
                };
                if let Node::Mass(i) = x
                    && !grounded[i]
                    && on
                {
                    grounded[i] = true;
                    changed = true;
                }
            }
        }
    }
    if let Some(i) = grounded.iter().position(|g| !g) {
        return Err(cx.err(
            format!("mass[{i}] ({})", masses[i].name),
            "has no path of links to the base; expected every mass to be connected".into(),
        ));
    }

    let top = match (kind, &spec.top) {
        (Kind::Seat, Some(t)) => match cx.node(&masses, "top".into(), t)? {
            Node::Mass(i) => Some(i),
            Node::Base => return Err(cx.err("top".into(), "expected a mass, not the base".into())),
        },
        (Kind::Seat, None) => {
            return Err(cx.err(
                "top".into(),
                "missing; a seat component names the mass the occupant sits on".into(),
            ));
        }
        (_, Some(_)) => {
            return Err(cx.err(
                "top".into(),
                "only a seat component (kind = \"seat\") has a top".into(),
            ));
        }
        (_, None) => None,
    };
    let measure_spec = match (&spec.measure, top) {
        (Some(m), _) => m,
        (None, Some(t)) => {
            return Ok(Chain {
                name: spec.name,
                description: spec.description,
                source: spec.source,
                masses,
                links,
                measure: Measure {
                    seat: Node::Mass(t),
                    head: None,
                    interface: Vec::new(),
                },
                kind,
                top,
                text: text.to_string(),
            });
        }
        (None, None) => {
            return Err(cx.err(
                "measure".into(),
                "missing [measure] table (seat, head, interface)".into(),
            ));
        }
    };
    if kind == Kind::Occupant && measure_spec.seat != "base" {
        return Err(cx.err(
            "measure.seat".into(),
            "an occupant sits on the base (\"base\"); put it on a seat with `stack`".into(),
        ));
    }
    let seat = cx.node(&masses, "measure.seat".into(), &measure_spec.seat)?;
    let head = match &measure_spec.head {
        None => None,
        Some(h) => match cx.node(&masses, "measure.head".into(), h)? {
            Node::Mass(i) => Some(i),
            Node::Base => {
                return Err(cx.err(
                    "measure.head".into(),
                    "expected a mass, not the base".into(),
                ));
            }
        },
    };
    let mut interface = Vec::new();
    for name in &measure_spec.interface {
        let li = links.iter().position(|l| l.name == *name).ok_or_else(|| {
            cx.err(
                "measure.interface".into(),
                format!("unknown link `{name}`; expected link names"),
            )
        })?;
        if links[li].b != seat {
            return Err(cx.err(
                "measure.interface".into(),
                format!(
                    "link `{name}` does not end on the seat node `{}`; expected links whose lower node is the seat",
                    measure_spec.seat
                ),
            ));
        }
        interface.push(li);
    }
    Ok(Chain {
        name: spec.name,
        description: spec.description,
        source: spec.source,
        masses,
        links,
        measure: Measure {
            seat,
            head,
            interface,
        },
        kind,
        top,
        text: text.to_string(),
    })
}
