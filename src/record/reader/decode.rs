//! Decoding a run's messages (protobuf or JSON, per-sample or batched) into named columns.

use super::*;

/// A signal topic being decoded: JSON (field names learnt from the first message) or protobuf
/// (field names from the channel's descriptor).
pub(super) enum Decoded {
    Json(Table),
    Protobuf(ProtoTable),
}

impl Decoded {
    pub(super) fn new(channel: &mcap::Channel<'_>) -> std::result::Result<Self, String> {
        match channel.message_encoding.as_str() {
            "json" => Ok(Decoded::Json(Table::default())),
            "protobuf" => {
                let schema = (channel.schema.as_ref())
                    .filter(|s| s.encoding == "protobuf")
                    .ok_or("protobuf channel without a protobuf schema")?;
                Ok(Decoded::Protobuf(ProtoTable::new(
                    &schema.data,
                    &schema.name,
                )?))
            }
            other => Err(format!(
                "message encoding `{other}`: expected protobuf or json"
            )),
        }
    }

    pub(super) fn add(&mut self, data: &[u8]) -> std::result::Result<(), String> {
        match self {
            Decoded::Json(t) => t.add(data),
            Decoded::Protobuf(t) => t.add(data),
        }
    }

    pub(super) fn into_table(self) -> Table {
        match self {
            Decoded::Json(t) => t,
            Decoded::Protobuf(t) => {
                let (names, columns) = t.into_columns();
                Table { names, columns }
            }
        }
    }
}

/// The numeric fields of one topic's messages, flattened in document order.
#[derive(Default)]
pub(super) struct Table {
    /// Field paths, learnt from the first message.
    pub(super) names: Vec<Vec<String>>,
    pub(super) columns: Vec<Vec<f64>>,
}

impl Table {
    pub(super) fn add(&mut self, data: &[u8]) -> std::result::Result<(), String> {
        let learning = self.names.is_empty();
        let mut st = Flat {
            table: self,
            learning,
            path: Vec::new(),
            depth: 0,
            k: 0,
        };
        let mut de = serde_json::Deserializer::from_slice(data);
        ObjectSeed(&mut st)
            .deserialize(&mut de)
            .and_then(|()| de.end())
            .map_err(|e| e.to_string())?;
        let k = st.k;
        if k != self.names.len() {
            return Err(format!(
                "{k} fields where the first message had {}",
                self.names.len()
            ));
        }
        Ok(())
    }

    /// Sample times must be `i / fs` (uniform sampling from 0), to 0.1 % of a sample. A topic
    /// without `t` (all but `/wbv/measured`) is timed by its log time only.
    pub(super) fn check_time(&self, fs: f64) -> std::result::Result<(), String> {
        let Some(t) = self.names.iter().position(|n| n.len() == 1 && n[0] == "t") else {
            return Ok(());
        };
        for (i, &ti) in self.columns[t].iter().enumerate() {
            if (ti * fs - i as f64).abs() > 1e-3 {
                return Err(format!(
                    "message {i} has t = {ti} s, expected {} s",
                    i as f64 / fs
                ));
            }
        }
        Ok(())
    }
}

pub(super) struct Flat<'a> {
    pub(super) table: &'a mut Table,
    pub(super) learning: bool,
    pub(super) path: Vec<String>,
    pub(super) depth: usize,
    pub(super) k: usize,
}

impl Flat<'_> {
    pub(super) fn number<E: serde::de::Error>(
        &mut self,
        key: &str,
        v: f64,
    ) -> std::result::Result<(), E> {
        if self.learning {
            let mut p = self.path.clone();
            p.push(key.to_string());
            self.table.names.push(p);
            self.table.columns.push(Vec::new());
        } else if self
            .table
            .names
            .get(self.k)
            .and_then(|n| n.last())
            .map(String::as_str)
            != Some(key)
        {
            return Err(E::custom(format!("unexpected field `{key}`")));
        }
        self.table.columns[self.k].push(v);
        self.k += 1;
        Ok(())
    }
}

pub(super) struct ObjectSeed<'a, 'b>(&'a mut Flat<'b>);

impl<'de> DeserializeSeed<'de> for ObjectSeed<'_, '_> {
    type Value = ();
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<(), D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for ObjectSeed<'_, '_> {
    type Value = ();
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a JSON object of numbers")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> std::result::Result<(), A::Error> {
        while let Some(key) = map.next_key::<&'de str>()? {
            map.next_value_seed(FieldSeed(&mut *self.0, key))?;
        }
        Ok(())
    }
}

pub(super) struct FieldSeed<'a, 'b, 'k>(&'a mut Flat<'b>, &'k str);

impl<'de> DeserializeSeed<'de> for FieldSeed<'_, '_, '_> {
    type Value = ();
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<(), D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for FieldSeed<'_, '_, '_> {
    type Value = ();
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "a number or an object for `{}`", self.1)
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> std::result::Result<(), E> {
        self.0.number(self.1, v)
    }
    fn visit_i64<E: serde::de::Error>(self, v: i64) -> std::result::Result<(), E> {
        self.0.number(self.1, v as f64)
    }
    fn visit_u64<E: serde::de::Error>(self, v: u64) -> std::result::Result<(), E> {
        self.0.number(self.1, v as f64)
    }
    fn visit_map<A: MapAccess<'de>>(self, map: A) -> std::result::Result<(), A::Error> {
        if self.0.depth >= 4 {
            return Err(A::Error::custom("objects nested too deeply"));
        }
        // Paths are only needed while learning the field names from the first message.
        if self.0.learning {
            self.0.path.push(self.1.to_string());
        }
        self.0.depth += 1;
        let r = ObjectSeed(&mut *self.0).visit_map(map);
        self.0.depth -= 1;
        if self.0.learning {
            self.0.path.pop();
        }
        r
    }
}
