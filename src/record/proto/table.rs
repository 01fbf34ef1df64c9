//! Reading protobuf channels back: messages decoded into columns of doubles, guided by the
//! channel's descriptor.

use super::message;
use prost::Message;
use prost::encoding::WireType;
use prost_types::FileDescriptorSet;
use prost_types::field_descriptor_proto::{Label, Type};

/// What a reader makes of one field of a message: a double leaf (its column) or a sub-message.
#[derive(Debug, Clone)]
enum Node {
    Leaf(usize),
    Message(Vec<(u32, Node)>),
}

/// Decodes the messages of one protobuf channel into columns of doubles, guided by the channel's
/// descriptor: every `double` field (at any depth) is a column named by its field path. Only
/// what wbv writes is accepted (doubles and sub-messages); other wire types are skipped with
/// prost's `skip_field`.
#[derive(Debug, Clone)]
pub struct ProtoTable {
    root: Vec<(u32, Node)>,
    /// Field paths, in descriptor order.
    pub names: Vec<Vec<String>>,
    /// One column per entry of `names`, one value per sample read, in the field's SI unit.
    pub columns: Vec<Vec<f64>>,
    /// Columns in the order their fields come in the first message.
    first: Vec<usize>,
    messages: usize,
    /// Samples read so far (= messages of the per-sample layout).
    rows: usize,
}

impl ProtoTable {
    /// The table of message `full_name` described by the serialized `FileDescriptorSet` `schema`.
    pub fn new(schema: &[u8], full_name: &str) -> std::result::Result<Self, String> {
        let fds = FileDescriptorSet::decode(schema)
            .map_err(|e| format!("schema is not a FileDescriptorSet: {e}"))?;
        let mut names = Vec::new();
        let root = Self::tree(&fds, full_name, &mut Vec::new(), &mut names, 0)?;
        let columns = vec![Vec::new(); names.len()];
        Ok(ProtoTable {
            root,
            names,
            columns,
            first: Vec::new(),
            messages: 0,
            rows: 0,
        })
    }

    fn tree(
        fds: &FileDescriptorSet,
        full_name: &str,
        path: &mut Vec<String>,
        names: &mut Vec<Vec<String>>,
        depth: usize,
    ) -> std::result::Result<Vec<(u32, Node)>, String> {
        if depth > 4 {
            return Err("messages nested too deeply".into());
        }
        let m = message(fds, full_name)
            .ok_or_else(|| format!("schema has no message `{full_name}`"))?;
        let mut out = Vec::new();
        for f in &m.field {
            path.push(f.name().to_string());
            match f.r#type() {
                Type::Double => {
                    out.push((f.number() as u32, Node::Leaf(names.len())));
                    names.push(path.clone());
                }
                Type::Message if f.label() != Label::Repeated => {
                    let t = f.type_name().trim_start_matches('.').to_string();
                    let sub = Self::tree(fds, &t, path, names, depth + 1)?;
                    out.push((f.number() as u32, Node::Message(sub)));
                }
                _ => {} // not a signal: skipped when read
            }
            path.pop();
        }
        Ok(out)
    }

    /// Adds one message: one sample (a double per field) or, batched, the same number of samples
    /// (a packed array per field) in every field.
    pub fn add(&mut self, mut data: &[u8]) -> std::result::Result<(), String> {
        Self::walk(&self.root, &mut data, &mut self.columns, &mut self.first)?;
        self.messages += 1;
        let rows = self.columns.iter().map(Vec::len).max().unwrap_or(0);
        let bad = |name: &[String], n: usize| {
            Err(format!(
                "field `{}` has {n} samples where others have {rows} after {} messages",
                name.join("."),
                self.messages
            ))
        };
        if rows <= self.rows && self.first.iter().any(|&k| !self.columns[k].is_empty()) {
            return bad(&self.names[self.first[0]], self.rows);
        }
        for (name, col) in self.names.iter().zip(&self.columns) {
            if !col.is_empty() && col.len() != rows {
                return bad(name, col.len());
            }
        }
        self.rows = rows;
        Ok(())
    }

    fn walk(
        fields: &[(u32, Node)],
        buf: &mut &[u8],
        columns: &mut [Vec<f64>],
        first: &mut Vec<usize>,
    ) -> std::result::Result<(), String> {
        use prost::encoding::{DecodeContext, decode_key, decode_varint, skip_field};
        let e = |e: prost::DecodeError| e.to_string();
        while !buf.is_empty() {
            let (tag, wire) = decode_key(buf).map_err(e)?;
            match (fields.iter().find(|(n, _)| *n == tag), wire) {
                (Some((_, Node::Leaf(col))), WireType::SixtyFourBit) => {
                    let (v, rest) = buf.split_first_chunk::<8>().ok_or("truncated double")?;
                    if columns[*col].is_empty() {
                        first.push(*col);
                    }
                    columns[*col].push(f64::from_le_bytes(*v));
                    *buf = rest;
                }
                (Some((_, Node::Leaf(col))), WireType::LengthDelimited) => {
                    // packed repeated doubles (the batched layout)
                    let len = decode_varint(buf).map_err(e)?;
                    if len > buf.len() as u64 || len % 8 != 0 {
                        return Err("truncated or misaligned packed doubles".into());
                    }
                    let (packed, rest) = buf.split_at(len as usize);
                    if columns[*col].is_empty() && !packed.is_empty() {
                        first.push(*col);
                    }
                    columns[*col].extend(
                        (packed.chunks_exact(8))
                            .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes"))),
                    );
                    *buf = rest;
                }
                (Some((_, Node::Message(sub))), WireType::LengthDelimited) => {
                    let len = decode_varint(buf).map_err(e)?;
                    if len > buf.len() as u64 {
                        return Err("truncated sub-message".into());
                    }
                    let (mut inner, rest) = buf.split_at(len as usize);
                    Self::walk(sub, &mut inner, columns, first)?;
                    *buf = rest;
                }
                (Some(_), _) => return Err(format!("field {tag}: unexpected wire type")),
                (None, _) => skip_field(wire, tag, buf, DecodeContext::default()).map_err(e)?,
            }
        }
        Ok(())
    }

    /// The columns present in every message, with their names, in the order of the bytes.
    pub fn into_columns(self) -> (Vec<Vec<String>>, Vec<Vec<f64>>) {
        let rows = self.rows;
        let (mut names, mut columns) = (self.names, self.columns);
        (self.first.iter())
            .map(|&k| {
                (
                    std::mem::take(&mut names[k]),
                    std::mem::take(&mut columns[k]),
                )
            })
            .filter(|(_, c)| rows > 0 && c.len() == rows)
            .unzip()
    }
}
