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

impl Topic {
    /// The topic with the simulation time `t` as its first field, if it has none: the batched
    /// layout gives every batch its sample times, so that each topic plots on its own. (Batched
    /// topics are protobuf only; the JSON schema is left as it was.)
    pub fn timed(mut self) -> Self {
        if self.quantities.first() != Some(&Quantity::Time) {
            self.leaves
                .insert(0, Leaf::new(&["t"], "simulation time, s"));
            self.quantities.insert(0, Quantity::Time);
            self.template = Template::new(&self.leaves);
        }
        self
    }
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
    /// A topic whose messages start with the simulation time `t`.
    fn timed() -> Self {
        Builder {
            leaves: vec![Leaf::new(&["t"], "simulation time, s")],
            quantities: vec![Quantity::Time],
        }
    }
    /// A topic without `t`: its time is the message `log_time` (= `publish_time`).
    fn untimed() -> Self {
        Builder {
            leaves: Vec::new(),
            quantities: Vec::new(),
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
        "f_back_z" => {
            "dynamic vertical backrest force on the body (up positive, static load removed), N"
        }
        _ => "measured-run channel",
    }
}

/// The time-series topics of a run of `layout`: `/wbv/measured`, `/wbv/state` and, for a model
/// with links, `/wbv/links`. Every field is recorded once, except the measured-run channels
/// `a_seat_z` and `a_head_z` (also `a_abs` of their masses) and `f_seat_z` (also the negated
/// force of a single interface link), kept under model-independent names for the viewer layout
/// and the measured-run readers, and a cushion or suspension deflection equal to a mass's `x`.
/// Only `/wbv/measured` carries `t`: it equals the log time.
pub fn topics(layout: &Layout) -> Result<Vec<Topic>> {
    let masses = keys(&layout.masses, "mass")?;
    let links = keys(&layout.links, "link")?;

    let mut m = Builder::timed();
    for (k, name) in layout.measured_channels().into_iter().enumerate() {
        m.add(
            &[name],
            Quantity::Measured(k),
            measured_description(name).into(),
        );
    }

    let mut s = Builder::untimed();
    for (i, k) in masses.iter().enumerate() {
        let name = &layout.masses[i];
        // A coordinate that the vertical base does not move (a fore-and-aft translation, a
        // pitch) is absolute already.
        let fixed = layout.influence[i] == 0.0;
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

    let mut l = Builder::untimed();
    for (i, k) in links.iter().enumerate() {
        let name = &layout.links[i];
        let role = layout.link_roles.get(i).map_or("", String::as_str);
        // Recorded where the system says so ([`crate::system::Link::record_deflection`]): a seat
        // component's stroke, or a deflection that is not a difference of two recorded
        // displacements a viewer could plot (a contact's Jacobian row times the coordinates).
        if layout.link_deflection[i] {
            l.add(
                &[k, "deflection"],
                Quantity::LinkDeflection(i),
                format!("{name} ({role}): deflection x_upper − x_lower, m (extension positive)"),
            );
        }
        l.add(
            &[k, "force"],
            Quantity::LinkForce(i),
            format!("{name} ({role}): tension, N (positive pulls the nodes together)"),
        );
    }

    let mut topics = vec![
        m.finish(
            "/wbv/measured",
            "wbv.Measured",
            "measured-run channels (shared/specs/measured-runs.md)",
        ),
        s.finish("/wbv/state", "wbv.State", "state of every mass"),
    ];
    if !l.leaves.is_empty() {
        topics.push(l.finish(
            "/wbv/links",
            "wbv.Links",
            "force of every link; deflection of the cushion and suspension links",
        ));
    }
    Ok(topics)
}

/// Evaluates `quantities` of step `s` into `out` (cleared first); `measured` holds
/// [`Layout::measured`] of the step.
pub fn eval(quantities: &[Quantity], s: &Step<'_>, measured: &[f64], out: &mut Vec<f64>) {
    out.clear();
    out.extend(quantities.iter().map(|q| q.eval(s, measured)));
}

/// The channel name of value `i` of a step (the values of `topics`' fields, topic after topic).
pub fn field_name(topics: &[(Topic, u16)], mut i: usize) -> String {
    for (t, _) in topics {
        if i < t.leaves.len() {
            return channel_name(t.topic, &t.leaves[i].path);
        }
        i -= t.leaves.len();
    }
    String::new()
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::demo;

    fn all(layout: &Layout) -> Vec<(String, Quantity)> {
        let topics = topics(layout).unwrap();
        let mut out = Vec::new();
        for t in &topics {
            for (leaf, q) in t.leaves.iter().zip(&t.quantities) {
                out.push((channel_name(t.topic, &leaf.path), *q));
            }
        }
        out
    }

    #[test]
    fn every_signal_the_issue_lists_is_recorded() {
        let layout = demo::layout(1000.0, 10);
        let fields = all(&layout);
        let has = |q: Quantity| fields.iter().any(|(_, f)| *f == q);
        let names: Vec<&str> = fields.iter().map(|(n, _)| n.as_str()).collect();
        assert!(names.contains(&"a_base_z") && names.contains(&"f_seat_z"));
        for i in 0..layout.masses.len() {
            for q in [Quantity::X(i), Quantity::V(i), Quantity::A(i)] {
                assert!(has(q), "{q:?}");
            }
            for q in [Quantity::XAbs(i), Quantity::VAbs(i), Quantity::AAbs(i)] {
                assert!(has(q), "{q:?}");
            }
        }
        for l in 0..layout.links.len() {
            assert!(has(Quantity::LinkForce(l)));
        }
        // the cushion link (index 4): its deflection; the body links' are differences of `x`
        assert!(has(Quantity::LinkDeflection(4)));
        assert!(!has(Quantity::LinkDeflection(1)));
    }

    #[test]
    fn only_the_measured_run_names_repeat_a_value() {
        let layout = demo::layout(1000.0, 10);
        let (fields, topics) = (all(&layout), topics(&layout).unwrap());
        let quantities: Vec<Quantity> = topics.iter().flat_map(|t| t.quantities.clone()).collect();
        let state = demo::State::at(1234, 1e-3);
        let (mut measured, mut values) = (Vec::new(), Vec::new());
        layout.measured(&state.step(), &mut measured);
        eval(&quantities, &state.step(), &measured, &mut values);
        // a_seat_z, a_head_z: a_abs of the cushion and head; f_seat_z: −force of k4; the cushion
        // link's deflection is the cushion's `x` (its lower node is the base)
        let repeats = [
            "state.cushion.a_abs",
            "state.head.a_abs",
            "links.k4.force",
            "links.cushion.deflection",
        ];
        for (j, (name, _)) in fields.iter().enumerate() {
            if let Some(i) = (0..j).find(|&i| values[i].abs() == values[j].abs()) {
                assert!(
                    repeats.contains(&name.as_str()),
                    "{name} repeats {}",
                    fields[i].0
                );
            }
        }
        let times: Vec<&String> = (fields.iter())
            .filter(|(_, q)| *q == Quantity::Time)
            .map(|(n, _)| n)
            .collect();
        assert_eq!(times, ["t"], "only /wbv/measured carries t");
    }
}
