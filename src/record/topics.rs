//! The time-series topics of a run, derived from the model [`Layout`]: which quantity goes into
//! which field, the field's unit, and how it is computed from a [`Step`].

use super::json::{Leaf, Template, schema};
use crate::error::{Error, Result};
use crate::simulate::observer::{Layout, Step};
use serde_json::Value;

/// A recorded quantity, evaluated from a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Quantity {
    /// Simulation time in s (never filtered).
    Time,
    BaseA,
    BaseV,
    BaseX,
    /// Relative displacement/velocity/acceleration of mass `i`.
    X(usize),
    V(usize),
    A(usize),
    /// Absolute (inertial) displacement/velocity/acceleration of mass `i` = relative + base.
    XAbs(usize),
    VAbs(usize),
    AAbs(usize),
    LinkDeflection(usize),
    LinkForce(usize),
    /// Measured-run channel `k` of [`Layout::measured_channels`], evaluated by [`Layout::measured`].
    Measured(usize),
}

impl Quantity {
    fn eval(self, s: &Step<'_>, measured: &[f64]) -> f64 {
        match self {
            Quantity::Time => s.t,
            Quantity::BaseA => s.a_base,
            Quantity::BaseV => s.v_base,
            Quantity::BaseX => s.x_base,
            Quantity::X(i) => s.x[i],
            Quantity::V(i) => s.v[i],
            Quantity::A(i) => s.a[i],
            Quantity::XAbs(i) => s.x[i] + s.x_base,
            Quantity::VAbs(i) => s.v[i] + s.v_base,
            Quantity::AAbs(i) => s.a[i] + s.a_base,
            Quantity::LinkDeflection(l) => s.link_deflection[l],
            Quantity::LinkForce(l) => s.link_force[l],
            Quantity::Measured(k) => measured[k],
        }
    }
}

/// One JSON topic: its name, schema and the quantities of its fields, in message order.
#[derive(Debug, Clone)]
pub struct Topic {
    pub topic: &'static str,
    pub schema_name: &'static str,
    pub schema: Value,
    pub template: Template,
    pub leaves: Vec<Leaf>,
    pub quantities: Vec<Quantity>,
}

/// A key a user can type into a plot path (`/wbv/state.upper_torso.a_abs`): ASCII letters, digits
/// and `_`; anything else becomes `_`.
pub fn plot_key(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

struct Builder {
    leaves: Vec<Leaf>,
    quantities: Vec<Quantity>,
}

impl Builder {
    fn new() -> Self {
        Builder {
            leaves: vec![Leaf::new(&["t"], "simulation time, s")],
            quantities: vec![Quantity::Time],
        }
    }
    fn add(&mut self, path: &[&str], q: Quantity, description: String) {
        self.leaves.push(Leaf::new(path, description));
        self.quantities.push(q);
    }
    fn finish(self, topic: &'static str, schema_name: &'static str, what: &str) -> Topic {
        Topic {
            topic,
            schema_name,
            schema: schema(schema_name, what, &self.leaves),
            template: Template::new(&self.leaves),
            leaves: self.leaves,
            quantities: self.quantities,
        }
    }
}

/// Unique plot keys for `names`, or an error naming the two names that collide.
fn keys(names: &[String], what: &str) -> Result<Vec<String>> {
    let keys: Vec<String> = names.iter().map(|n| plot_key(n)).collect();
    for (i, k) in keys.iter().enumerate() {
        if let Some(j) = keys[..i].iter().position(|o| o == k) {
            return Err(Error::parameter(
                format!("{what} names"),
                format!(
                    "`{}` and `{}` both become the plot key `{k}`",
                    names[j], names[i]
                ),
            ));
        }
        if k == "t" || k.is_empty() {
            return Err(Error::parameter(
                format!("{what} names"),
                format!("`{}` cannot be used as a plot key", names[i]),
            ));
        }
    }
    Ok(keys)
}

/// What a measured-run channel holds (`../shared/specs/measured-runs.md`).
fn measured_description(name: &str) -> &'static str {
    match name {
        "a_base_z" => "seat-base (input) acceleration, m/s²",
        "a_seat_z" => {
            "absolute acceleration at the occupant–cushion interface (the base for a rigid seat), m/s²"
        }
        "a_seat_x" => {
            "fore-and-aft acceleration at the occupant–cushion interface (the base moves vertically), m/s²"
        }
        "a_head_z" => "absolute vertical head acceleration, m/s²",
        "a_head_x" => "absolute fore-and-aft head acceleration, m/s²",
        "f_seat_z" => {
            "dynamic seat-surface force on the body (compression positive, static weight removed), N"
        }
        _ => "measured-run channel",
    }
}

/// The four time-series topics of a run of `layout`.
pub fn topics(layout: &Layout) -> Result<Vec<Topic>> {
    let masses = keys(&layout.masses, "mass")?;
    let links = keys(&layout.links, "link")?;

    let mut m = Builder::new();
    for (k, name) in layout.measured_channels().into_iter().enumerate() {
        m.add(
            &[name],
            Quantity::Measured(k),
            measured_description(name).into(),
        );
    }

    let mut s = Builder::new();
    for (i, k) in masses.iter().enumerate() {
        let name = &layout.masses[i];
        // A planar coordinate that the vertical base does not move is absolute already.
        let fixed = layout
            .planar
            .as_ref()
            .is_some_and(|p| p.influence[i] == 0.0);
        let (xa, va, aa) = if fixed {
            (Quantity::X(i), Quantity::V(i), Quantity::A(i))
        } else {
            (Quantity::XAbs(i), Quantity::VAbs(i), Quantity::AAbs(i))
        };
        for (field, q, what) in [
            ("x", Quantity::X(i), "displacement relative to the base, m"),
            ("v", Quantity::V(i), "velocity relative to the base, m/s"),
            (
                "a",
                Quantity::A(i),
                "acceleration relative to the base, m/s²",
            ),
            ("x_abs", xa, "absolute displacement, m"),
            ("v_abs", va, "absolute velocity, m/s"),
            ("a_abs", aa, "absolute acceleration, m/s²"),
        ] {
            s.add(&[k, field], q, format!("{name}: {what}"));
        }
    }

    let mut l = Builder::new();
    for (i, k) in links.iter().enumerate() {
        let name = &layout.links[i];
        let role = layout.link_roles.get(i).map_or("", String::as_str);
        l.add(
            &[k, "deflection"],
            Quantity::LinkDeflection(i),
            format!("{name} ({role}): deflection x_upper − x_lower, m (extension positive)"),
        );
        l.add(
            &[k, "force"],
            Quantity::LinkForce(i),
            format!("{name} ({role}): tension, N (positive pulls the nodes together)"),
        );
    }

    let mut b = Builder::new();
    b.add(&["a"], Quantity::BaseA, "base acceleration, m/s²".into());
    b.add(&["v"], Quantity::BaseV, "base velocity, m/s".into());
    b.add(&["x"], Quantity::BaseX, "base displacement, m".into());

    Ok(vec![
        m.finish(
            "/wbv/measured",
            "wbv.Measured",
            "measured-run channels (shared/specs/measured-runs.md)",
        ),
        s.finish("/wbv/state", "wbv.State", "state of every mass"),
        l.finish(
            "/wbv/links",
            "wbv.Links",
            "deflection and force of every link",
        ),
        b.finish("/wbv/base", "wbv.Base", "base (input) motion"),
    ])
}

/// Evaluates `quantities` of step `s` into `out` (cleared first); `measured` holds
/// [`Layout::measured`] of the step.
pub fn eval(quantities: &[Quantity], s: &Step<'_>, measured: &[f64], out: &mut Vec<f64>) {
    out.clear();
    out.extend(quantities.iter().map(|q| q.eval(s, measured)));
}

/// The [`Signals`](crate::signals::Signals) channel name of a field of `topic`: the measured-run
/// names as they are, the others as the plot path without the `/wbv/` prefix (`state.head.a_abs`).
pub fn channel_name(topic: &str, path: &[String]) -> String {
    let joined = path.join(".");
    match topic.strip_prefix("/wbv/") {
        Some("measured") | None => joined,
        Some(rest) => format!("{rest}.{joined}"),
    }
}
