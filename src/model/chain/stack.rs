//! Putting an occupant on a seat: stacking model components from the occupant down to the base.
//!
//! The occupant's links to the base are re-attached to the top mass of the first seat component,
//! whose links to the base go to the next component's top, and so on; the last component stands on
//! the base. The seat surface of the result is the top of the first seat component, and the
//! occupant's interface links stay the force path of the apparent mass.

use super::{Chain, Kind, Link, Measure, Node};

/// Stacks `parts` (an occupant followed by seat components, top to bottom) into one system.
pub fn stack(parts: &[Chain]) -> Result<Chain, String> {
    let (occupant, seats) = parts
        .split_first()
        .ok_or_else(|| "empty stack; expected an occupant and seat components".to_string())?;
    if occupant.kind != Kind::Occupant {
        return Err(format!(
            "`{}` is not an occupant (kind = \"occupant\"); a stack starts with the occupant",
            occupant.name
        ));
    }
    let mut model = occupant.clone();
    model.kind = Kind::System;
    model.top = None;
    // Index where the masses of the component stacked last begin; its links to the base get
    // re-attached to the top of the next component.
    let mut prev_links = 0..model.links.len();
    for seat in seats {
        if seat.kind != Kind::Seat {
            return Err(format!(
                "`{}` is not a seat component (kind = \"seat\"); only seats go below the occupant",
                seat.name
            ));
        }
        let offset = model.masses.len();
        for m in &seat.masses {
            if model.masses.iter().any(|x| x.name == m.name) {
                return Err(format!(
                    "mass `{}` of `{}` duplicates a name above it",
                    m.name, seat.name
                ));
            }
        }
        for l in &seat.links {
            if model.links.iter().any(|x| x.name == l.name) {
                return Err(format!(
                    "link `{}` of `{}` duplicates a name above it",
                    l.name, seat.name
                ));
            }
        }
        let top = Node::Mass(offset + seat.top.expect("seat components have a top"));
        for li in prev_links.clone() {
            let l = &mut model.links[li];
            if l.b == Node::Base {
                l.b = top;
            }
            if l.a == Node::Base {
                l.a = top;
            }
        }
        if model.measure.seat == Node::Base {
            model.measure.seat = top;
        }
        let shift = |n: Node| match n {
            Node::Base => Node::Base,
            Node::Mass(i) => Node::Mass(i + offset),
        };
        let first_link = model.links.len();
        model.masses.extend(seat.masses.iter().cloned());
        model.links.extend(seat.links.iter().map(|l| Link {
            a: shift(l.a),
            b: shift(l.b),
            ..l.clone()
        }));
        prev_links = first_link..model.links.len();
        model.text = format!("{}\n# --- {} ---\n{}", model.text, seat.name, seat.text);
    }
    model.measure = Measure {
        seat: model.measure.seat,
        head: model.measure.head,
        interface: model.measure.interface.clone(),
    };
    model.name = parts
        .iter()
        .map(|p| p.name.as_str())
        .collect::<Vec<_>>()
        .join("+");
    model.description = format!(
        "{} on {}",
        occupant.name,
        seats
            .iter()
            .map(|s| s.name.as_str())
            .collect::<Vec<_>>()
            .join(" on ")
    );
    Ok(model)
}
