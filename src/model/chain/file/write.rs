//! A chain model written as a model file: the inverse of [`super::parse`], so that any chain —
//! a built-in, a stack, or a system the gap diagnosis corrected — can be saved and read back into
//! the same [`crate::system::System`]. Numbers are written in Rust's shortest round-trip form, so
//! reading the file back gives every value bit for bit.

use crate::model::chain::{Chain, Element, Kind, Node};
use std::fmt::Write;

/// A TOML basic string (quoted and escaped).
fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// A finite number as a TOML float that reads back to the same `f64` (`{:?}` is Rust's shortest
/// round-trip form and always has a `.` or an exponent, so TOML reads a float, never an integer).
fn num(v: f64) -> String {
    format!("{v:?}")
}

/// The model file of `chain`: name, description, source, kind (and `top` for a seat component),
/// every `[[mass]]`, every `[[link]]` with its element, role and `[link.law]`, and `[measure]`.
/// `header` is written first as `#` comment lines. A stacked chain is written flat (its masses and
/// links, not its `stack` list).
pub fn write(chain: &Chain, header: &str) -> String {
    let mut out = String::new();
    for line in header.lines() {
        let _ = writeln!(out, "#{}{line}", if line.is_empty() { "" } else { " " });
    }
    let _ = writeln!(out, "name = {}", quoted(&chain.name));
    let _ = writeln!(out, "description = {}", quoted(&chain.description));
    let _ = writeln!(out, "source = {}", quoted(&chain.source));
    let kind = match chain.kind {
        Kind::System => "system",
        Kind::Occupant => "occupant",
        Kind::Seat => "seat",
    };
    let _ = writeln!(out, "kind = {}", quoted(kind));
    if let Some(t) = chain.top {
        let _ = writeln!(out, "top = {}", quoted(&chain.masses[t].name));
    }
    for m in &chain.masses {
        let _ = write!(
            out,
            "\n[[mass]]\nname = {}\nm = {}  # kg\nrole = {}\n",
            quoted(&m.name),
            num(m.m),
            quoted(m.role.as_str())
        );
    }
    for l in &chain.links {
        let _ = write!(
            out,
            "\n[[link]]\nname = {}\nbetween = [{}, {}]\nrole = {}\n",
            quoted(&l.name),
            quoted(chain.node_name(l.a)),
            quoted(chain.node_name(l.b)),
            quoted(l.role.as_str())
        );
        let _ = match l.element {
            Element::KelvinVoigt { k, c } => write!(
                out,
                "type = \"kelvin-voigt\"\nk = {}  # N/m\nc = {}  # N·s/m\n",
                num(k),
                num(c)
            ),
            Element::Maxwell { k, c } => write!(
                out,
                "type = \"maxwell\"\nk = {}  # N/m\nc = {}  # N·s/m\n",
                num(k),
                num(c)
            ),
            Element::Zener { k, k_m, c_m } => write!(
                out,
                "type = \"zener\"\nk = {}  # N/m\nk_m = {}  # N/m\nc_m = {}  # N·s/m\n",
                num(k),
                num(k_m),
                num(c_m)
            ),
        };
        if let Some(law) = l.law {
            let _ = write!(out, "[link.law]\ntype = {}\n", quoted(law.word()));
            for (p, v) in law.params().iter().zip(law.values()) {
                let _ = writeln!(out, "{} = {}  # {}", p.key, num(v), p.unit);
            }
        }
    }
    let m = &chain.measure;
    if chain.kind != Kind::Seat || !m.interface.is_empty() || m.head.is_some() {
        let seat = match m.seat {
            Node::Base => "base",
            Node::Mass(i) => &chain.masses[i].name,
        };
        let _ = write!(out, "\n[measure]\nseat = {}\n", quoted(seat));
        if let Some(h) = m.head {
            let _ = writeln!(out, "head = {}", quoted(&chain.masses[h].name));
        }
        let names: Vec<String> = m
            .interface
            .iter()
            .map(|&i| quoted(&chain.links[i].name))
            .collect();
        let _ = writeln!(out, "interface = [{}]", names.join(", "));
    }
    out
}
