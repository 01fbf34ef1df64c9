//! JSON messages and their JSON schemas, built once per topic from a list of field paths.
//!
//! A message is rendered from precomputed text fragments and the values in between, so a step costs
//! only the float formatting. Floats use the shortest text that parses back to the same `f64`
//! (serde_json's formatter), so a recorded run reads back bit-identically; NaN and ±∞ have no JSON
//! representation (serde_json would write `null`, which breaks plots and schemas): the recorder
//! refuses them before rendering.

use serde_json::{Map, Value, json};

/// One numeric field of a topic: its path inside the message and its unit/meaning for the schema.
#[derive(Debug, Clone, PartialEq)]
pub struct Leaf {
    /// Path of object keys, e.g. `["head", "a_abs"]`.
    pub path: Vec<String>,
    /// Schema description: meaning and unit.
    pub description: String,
}

impl Leaf {
    pub fn new(path: &[&str], description: impl Into<String>) -> Self {
        Leaf {
            path: path.iter().map(|s| s.to_string()).collect(),
            description: description.into(),
        }
    }
}

/// Precomputed message text around the values: `fragments[0] v0 fragments[1] v1 … fragments[n]`.
#[derive(Debug, Clone)]
pub struct Template {
    fragments: Vec<Vec<u8>>,
}

impl Template {
    /// Builds the fragments for `leaves`; leaves sharing a parent object must be adjacent.
    pub fn new(leaves: &[Leaf]) -> Self {
        let mut fragments = Vec::with_capacity(leaves.len() + 1);
        let mut cur = b"{".to_vec();
        let mut open: Vec<&str> = Vec::new();
        let mut first = true;
        for leaf in leaves {
            let (name, parents) = leaf.path.split_last().expect("a leaf has a name");
            let common = open
                .iter()
                .zip(parents)
                .take_while(|(a, b)| **a == b.as_str())
                .count();
            while open.len() > common {
                cur.push(b'}');
                open.pop();
                first = false;
            }
            for p in &parents[common..] {
                if !first {
                    cur.push(b',');
                }
                cur.extend_from_slice(format!("\"{p}\":{{").as_bytes());
                open.push(p);
                first = true;
            }
            if !first {
                cur.push(b',');
            }
            cur.extend_from_slice(format!("\"{name}\":").as_bytes());
            fragments.push(std::mem::take(&mut cur));
            first = false;
        }
        cur.extend(std::iter::repeat_n(b'}', open.len() + 1));
        fragments.push(cur);
        Template { fragments }
    }

    /// Number of values a message takes.
    pub fn len(&self) -> usize {
        self.fragments.len() - 1
    }

    /// Appends the message for `values`, which the caller has checked finite (a non-finite
    /// value would be written as `null`).
    pub fn render_finite(&self, values: &[f64], out: &mut Vec<u8>) {
        use serde_json::ser::{CompactFormatter, Formatter};
        debug_assert_eq!(values.len(), self.len());
        debug_assert!(values.iter().all(|v| v.is_finite()));
        for (frag, &v) in self.fragments.iter().zip(values) {
            out.extend_from_slice(frag);
            CompactFormatter
                .write_f64(out, v)
                .expect("writing to a Vec cannot fail");
        }
        out.extend_from_slice(self.fragments.last().expect("closing fragment"));
    }
}

/// Writes the shortest round-trip text of a finite `v`; refuses NaN and ±∞.
pub fn write_f64(out: &mut Vec<u8>, v: f64) -> Result<(), ()> {
    use serde_json::ser::{CompactFormatter, Formatter};
    if !v.is_finite() {
        return Err(());
    }
    CompactFormatter
        .write_f64(out, v)
        .expect("writing to a Vec cannot fail");
    Ok(())
}

/// The JSON schema (draft 2020-12 subset that Lichtblick parses) of a topic with `leaves`.
pub fn schema(title: &str, description: &str, leaves: &[Leaf]) -> Value {
    let mut root = object_schema(description);
    for leaf in leaves {
        let (name, parents) = leaf.path.split_last().expect("a leaf has a name");
        let mut node = &mut root;
        for p in parents {
            let props = node["properties"].as_object_mut().expect("object schema");
            if !props.contains_key(p) {
                props.insert(p.clone(), object_schema(&format!("`{p}`")));
                push_required(node, p);
            }
            node = &mut node["properties"][p.as_str()];
        }
        node["properties"]
            .as_object_mut()
            .expect("object schema")
            .insert(
                name.clone(),
                json!({"type": "number", "description": leaf.description}),
            );
        push_required(node, name);
    }
    root["title"] = Value::String(title.to_string());
    root
}

fn object_schema(description: &str) -> Value {
    json!({"type": "object", "description": description, "properties": Map::new(),
           "required": [], "additionalProperties": false})
}

fn push_required(node: &mut Value, name: &str) {
    node["required"]
        .as_array_mut()
        .expect("required list")
        .push(Value::String(name.to_string()));
}

/// Checks that a channel schema stays inside the JSON-schema subset Lichtblick parses
/// (`packages/mcap-support/src/parseJsonSchema.ts`): an object root, every property with one string
/// `type` (or a `oneOf` of numeric `const`s), array `items` likewise, and no `$ref`/`$defs`.
/// Returns the path of the first offending property.
pub fn check_lichtblick_subset(schema: &Value) -> Result<(), String> {
    if schema.get("type").and_then(Value::as_str) != Some("object") {
        return Err("root: `type` must be \"object\"".into());
    }
    check_node(schema, "root")
}

fn check_node(node: &Value, at: &str) -> Result<(), String> {
    if node.get("$ref").is_some() || node.get("$defs").is_some() {
        return Err(format!("{at}: `$ref`/`$defs` are not supported"));
    }
    if let Some(one_of) = node.get("oneOf") {
        let numeric = one_of.as_array().is_some_and(|alts| {
            alts.iter()
                .all(|a| a.get("const").is_some_and(Value::is_number))
        });
        return if numeric {
            Ok(())
        } else {
            Err(format!("{at}: `oneOf` must list numeric `const`s"))
        };
    }
    let ty = match node.get("type") {
        Some(Value::String(t)) => t.as_str(),
        _ => return Err(format!("{at}: needs exactly one string `type`")),
    };
    match ty {
        "object" => {
            if let Some(props) = node.get("properties").and_then(Value::as_object) {
                for (k, v) in props {
                    check_node(v, &format!("{at}.{k}"))?;
                }
            }
            Ok(())
        }
        "array" => match node.get("items") {
            Some(items) => check_node(items, &format!("{at}[]")),
            None => Err(format!("{at}: array without `items`")),
        },
        "boolean" | "string" | "number" | "integer" => Ok(()),
        other => Err(format!("{at}: unsupported type `{other}`")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leaves() -> Vec<Leaf> {
        vec![
            Leaf::new(&["t"], "s"),
            Leaf::new(&["head", "x"], "m"),
            Leaf::new(&["head", "a_abs"], "m/s²"),
            Leaf::new(&["seat", "x"], "m"),
            Leaf::new(&["f"], "N"),
        ]
    }

    #[test]
    fn template_renders_valid_json_that_parses_back_exactly() {
        let t = Template::new(&leaves());
        let vals = [0.001, -1.234_567_890_123_456_7e-7, 9.81, 1e300, -0.0];
        let mut out = Vec::new();
        t.render_finite(&vals, &mut out);
        let v: Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(
            std::str::from_utf8(&out).unwrap().matches('{').count(),
            3,
            "{}",
            String::from_utf8_lossy(&out)
        );
        let got = [
            v["t"].as_f64().unwrap(),
            v["head"]["x"].as_f64().unwrap(),
            v["head"]["a_abs"].as_f64().unwrap(),
            v["seat"]["x"].as_f64().unwrap(),
            v["f"].as_f64().unwrap(),
        ];
        for (a, b) in vals.iter().zip(got) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }

    #[test]
    fn a_template_may_start_inside_an_object() {
        let leaves = [
            Leaf::new(&["head", "x"], "m"),
            Leaf::new(&["head", "v"], "m/s"),
            Leaf::new(&["k1", "force"], "N"),
        ];
        let mut out = Vec::new();
        Template::new(&leaves).render_finite(&[1.5, -2.0, 3e-7], &mut out);
        assert_eq!(
            std::str::from_utf8(&out).unwrap(),
            r#"{"head":{"x":1.5,"v":-2.0},"k1":{"force":3e-7}}"#
        );
    }

    #[test]
    fn schema_is_in_the_lichtblick_subset_and_validates_the_message_shape() {
        let s = schema("wbv.Test", "test", &leaves());
        check_lichtblick_subset(&s).unwrap();
        assert_eq!(s["properties"]["head"]["required"], json!(["x", "a_abs"]));
        assert_eq!(s["required"], json!(["t", "head", "seat", "f"]));
    }

    #[test]
    fn subset_check_rejects_what_lichtblick_rejects() {
        let nullable = json!({"type":"object","properties":{"x":{"type":["number","null"]}}});
        assert!(check_lichtblick_subset(&nullable).is_err());
        let refd = json!({"type":"object","properties":{"x":{"$ref":"#/$defs/X"}}});
        assert!(check_lichtblick_subset(&refd).is_err());
        let untyped = json!({"type":"object","properties":{"x":{"description":"?"}}});
        assert!(check_lichtblick_subset(&untyped).is_err());
    }
}
