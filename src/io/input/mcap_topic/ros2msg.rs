//! ROS 2 message definitions (`ros2msg` schema text) and CDR decoding into JSON values.
//!
//! Hand-written: no maintained crate decodes CDR from a runtime schema.

use serde_json::{Map, Value};
use std::collections::HashMap;

#[derive(Debug, Clone)]
enum Ty {
    Prim(&'static str),
    Str,
    Msg(String),
}

#[derive(Debug, Clone)]
enum Len {
    One,
    Fixed(usize),
    Seq,
}

#[derive(Debug, Clone)]
struct Field {
    name: String,
    ty: Ty,
    len: Len,
}

/// A message type and the types it uses, by full name `pkg/msg/Name` or `pkg/Name`.
#[derive(Debug, Clone)]
pub struct Schema {
    root: String,
    types: HashMap<String, Vec<Field>>,
}

fn prim(t: &str) -> Option<&'static str> {
    Some(match t {
        "bool" => "bool",
        "byte" | "uint8" | "char" => "uint8",
        "int8" => "int8",
        "int16" => "int16",
        "uint16" => "uint16",
        "int32" => "int32",
        "uint32" => "uint32",
        "int64" => "int64",
        "uint64" => "uint64",
        "float32" => "float32",
        "float64" => "float64",
        _ => return None,
    })
}

fn short(name: &str) -> String {
    // `pkg/msg/Name` and `pkg/Name` are the same type.
    let parts: Vec<&str> = name.split('/').collect();
    match parts.as_slice() {
        [p, "msg", n] => format!("{p}/{n}"),
        _ => name.to_string(),
    }
}

impl Schema {
    /// Parses the schema text of message type `name`.
    pub fn parse(name: &str, text: &str) -> Result<Schema, String> {
        let root = short(name);
        let pkg = root.split('/').next().unwrap_or("").to_string();
        let mut types: HashMap<String, Vec<Field>> = HashMap::new();
        let mut current = root.clone();
        let mut cur_pkg = pkg;
        let mut fields = Vec::new();
        for line in text.lines() {
            let l = line.split('#').next().unwrap_or("").trim();
            if l.starts_with("===") {
                types.insert(std::mem::take(&mut current), std::mem::take(&mut fields));
                continue;
            }
            if let Some(n) = l.strip_prefix("MSG:") {
                current = short(n.trim());
                cur_pkg = current.split('/').next().unwrap_or("").to_string();
                continue;
            }
            if l.is_empty() {
                continue;
            }
            let mut it = l.split_whitespace();
            let (Some(t), Some(n)) = (it.next(), it.next()) else {
                return Err(format!("schema line `{l}`: expected TYPE NAME"));
            };
            if n.contains('=') || it.next().is_some_and(|x| x.starts_with('=')) {
                continue; // a constant
            }
            let (base, len) = match t.find('[') {
                Some(i) => {
                    let inner = t[i + 1..].trim_end_matches(']');
                    let len = if inner.is_empty() || inner.starts_with("<=") {
                        Len::Seq
                    } else {
                        Len::Fixed(
                            inner
                                .parse()
                                .ok()
                                .filter(|&n: &usize| n <= 1 << 20)
                                .ok_or_else(|| format!("array size in `{t}`"))?,
                        )
                    };
                    (&t[..i], len)
                }
                None => (t, Len::One),
            };
            let base = base.split("<=").next().unwrap_or(base);
            let ty = if let Some(p) = prim(base) {
                Ty::Prim(p)
            } else if base == "string" || base == "wstring" {
                Ty::Str
            } else if base == "Header" {
                Ty::Msg("std_msgs/Header".into())
            } else if base.contains('/') {
                Ty::Msg(short(base))
            } else {
                Ty::Msg(format!("{cur_pkg}/{base}"))
            };
            fields.push(Field {
                name: n.to_string(),
                ty,
                len,
            });
        }
        types.insert(current, fields);
        types
            .entry("builtin_interfaces/Time".into())
            .or_insert_with(|| {
                vec![
                    Field {
                        name: "sec".into(),
                        ty: Ty::Prim("int32"),
                        len: Len::One,
                    },
                    Field {
                        name: "nanosec".into(),
                        ty: Ty::Prim("uint32"),
                        len: Len::One,
                    },
                ]
            });
        Ok(Schema { root, types })
    }

    /// Decodes one CDR-encoded message (4-byte encapsulation header, then the fields).
    pub fn decode(&self, data: &[u8]) -> Result<Value, String> {
        if data.len() < 4 {
            return Err("shorter than the CDR encapsulation header".into());
        }
        let le = match data[1] {
            0 | 2 => false,
            1 | 3 => true,
            k => return Err(format!("CDR encapsulation kind {k}")),
        };
        let mut r = Reader {
            b: &data[4..],
            pos: 0,
            le,
            // Values a message may hold: bounds fixed arrays of empty types.
            budget: 64 * data.len() + 1024,
        };
        self.message(&self.root, &mut r, 0)
    }

    fn message(&self, name: &str, r: &mut Reader<'_>, depth: usize) -> Result<Value, String> {
        if depth > 32 {
            return Err("message types nest too deep".into());
        }
        let fields = self
            .types
            .get(name)
            .ok_or_else(|| format!("type `{name}` is not defined in the schema"))?;
        let mut out = Map::new();
        for f in fields {
            let one = |r: &mut Reader<'_>| -> Result<Value, String> {
                r.budget = r
                    .budget
                    .checked_sub(1)
                    .ok_or("more values than the message can hold")?;
                match &f.ty {
                    Ty::Prim(p) => r.prim(p),
                    Ty::Str => r.string(),
                    Ty::Msg(m) => self.message(m, r, depth + 1),
                }
            };
            let v = match f.len {
                Len::One => one(r)?,
                Len::Fixed(n) => Value::Array((0..n).map(|_| one(r)).collect::<Result<_, _>>()?),
                Len::Seq => {
                    let n = r.u32()? as usize;
                    if n > r.b.len() {
                        return Err(format!("sequence `{}` of {n} elements overruns", f.name));
                    }
                    Value::Array((0..n).map(|_| one(r)).collect::<Result<_, _>>()?)
                }
            };
            out.insert(f.name.clone(), v);
        }
        Ok(Value::Object(out))
    }
}

struct Reader<'a> {
    b: &'a [u8],
    pos: usize,
    le: bool,
    budget: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        // CDR aligns each primitive to its size, counted from after the header.
        let pad = (n - self.pos % n) % n;
        let start = self.pos + pad;
        let end = start + n;
        let s = self
            .b
            .get(start..end)
            .ok_or_else(|| "message ends inside a field".to_string())?;
        self.pos = end;
        Ok(s)
    }

    fn u32(&mut self) -> Result<u32, String> {
        let b: [u8; 4] = self.take(4)?.try_into().expect("4");
        Ok(if self.le {
            u32::from_le_bytes(b)
        } else {
            u32::from_be_bytes(b)
        })
    }

    fn string(&mut self) -> Result<Value, String> {
        let n = self.u32()? as usize;
        let s = self
            .b
            .get(self.pos..self.pos.saturating_add(n))
            .ok_or_else(|| "string overruns the message".to_string())?;
        self.pos += n;
        Ok(Value::String(
            String::from_utf8_lossy(s.strip_suffix(&[0]).unwrap_or(s)).into_owned(),
        ))
    }

    fn prim(&mut self, p: &str) -> Result<Value, String> {
        macro_rules! num {
            ($t:ty, $n:expr) => {{
                let b: [u8; $n] = self.take($n)?.try_into().expect("size");
                if self.le {
                    <$t>::from_le_bytes(b)
                } else {
                    <$t>::from_be_bytes(b)
                }
            }};
        }
        let f = |x: f64| serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number);
        Ok(match p {
            "bool" => Value::Bool(num!(u8, 1) != 0),
            "uint8" => Value::from(num!(u8, 1)),
            "int8" => Value::from(num!(i8, 1)),
            "int16" => Value::from(num!(i16, 2)),
            "uint16" => Value::from(num!(u16, 2)),
            "int32" => Value::from(num!(i32, 4)),
            "uint32" => Value::from(num!(u32, 4)),
            "int64" => Value::from(num!(i64, 8)),
            "uint64" => Value::from(num!(u64, 8)),
            "float32" => f(num!(f32, 4) as f64),
            _ => f(num!(f64, 8)),
        })
    }
}
