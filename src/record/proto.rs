//! Protobuf encoding of the time-series topics (`--encoding protobuf`, the default): the messages
//! of `proto/wbv.proto`, its `FileDescriptorSet` (compiled by `protox` in `build.rs`) completed
//! per run with one field per mass / link, and the per-step encoder.
//!
//! The typed messages ([`Measured`], [`MassState`], [`LinkState`]) are `prost` derives that mirror
//! the `.proto` (a test checks them field by field against the compiled descriptor). The recorder
//! does not build a struct per step: [`ProtoTemplate`] writes the same bytes straight from the
//! value slice with `prost::encoding` (a test checks them equal to the derives' encoding), which
//! keeps a step at a few nanoseconds per value.

use super::json::Leaf;
use crate::error::{Error, Result};
use prost::Message;
use prost::encoding::{WireType, encode_key, encode_varint, key_len};
use prost_types::field_descriptor_proto::{Label, Type};
use prost_types::{DescriptorProto, FieldDescriptorProto, FileDescriptorSet};

/// `proto/wbv.proto` compiled to a serialized `FileDescriptorSet` (see `build.rs`).
const WBV_FDS: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/wbv.fds"));

/// The `.proto` text itself, for the docs and the validation tooling.
pub const WBV_PROTO: &str = include_str!("../../proto/wbv.proto");

/// `wbv.Measured` of `proto/wbv.proto`.
#[derive(Clone, PartialEq, Message)]
pub struct Measured {
    #[prost(double, optional, tag = "1")]
    pub t: Option<f64>,
    #[prost(double, optional, tag = "2")]
    pub a_base_z: Option<f64>,
    #[prost(double, optional, tag = "3")]
    pub a_seat_z: Option<f64>,
    #[prost(double, optional, tag = "4")]
    pub a_head_z: Option<f64>,
    #[prost(double, optional, tag = "5")]
    pub f_seat_z: Option<f64>,
    #[prost(double, optional, tag = "6")]
    pub a_seat_x: Option<f64>,
    #[prost(double, optional, tag = "7")]
    pub a_head_x: Option<f64>,
}

/// `wbv.MassState` of `proto/wbv.proto`.
#[derive(Clone, PartialEq, Message)]
pub struct MassState {
    #[prost(double, optional, tag = "1")]
    pub x: Option<f64>,
    #[prost(double, optional, tag = "2")]
    pub v: Option<f64>,
    #[prost(double, optional, tag = "3")]
    pub a: Option<f64>,
    #[prost(double, optional, tag = "4")]
    pub x_abs: Option<f64>,
    #[prost(double, optional, tag = "5")]
    pub v_abs: Option<f64>,
    #[prost(double, optional, tag = "6")]
    pub a_abs: Option<f64>,
}

/// `wbv.LinkState` of `proto/wbv.proto`.
#[derive(Clone, PartialEq, Message)]
pub struct LinkState {
    #[prost(double, optional, tag = "1")]
    pub deflection: Option<f64>,
    #[prost(double, optional, tag = "2")]
    pub force: Option<f64>,
}

/// The compiled `proto/wbv.proto`.
pub fn base_descriptor() -> FileDescriptorSet {
    FileDescriptorSet::decode(WBV_FDS).expect("build.rs wrote a valid descriptor set")
}

fn message<'a>(fds: &'a FileDescriptorSet, full_name: &str) -> Option<&'a DescriptorProto> {
    fds.file.iter().find_map(|f| {
        let package = f.package();
        f.message_type.iter().find(|m| {
            let name = m.name();
            if package.is_empty() {
                name == full_name
            } else {
                full_name
                    .strip_prefix(package)
                    .and_then(|r| r.strip_prefix('.'))
                    == Some(name)
            }
        })
    })
}

/// Number of the field `name` of message `full_name` (e.g. `wbv.MassState`).
fn field_number(fds: &FileDescriptorSet, full_name: &str, name: &str) -> Option<u32> {
    message(fds, full_name)?
        .field
        .iter()
        .find(|f| f.name() == name)
        .map(|f| f.number() as u32)
}

/// A protobuf identifier: a letter or `_`, then letters, digits or `_`.
fn is_identifier(s: &str) -> bool {
    let mut c = s.chars();
    c.next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && c.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The descriptor set of a run: `proto/wbv.proto` with `wbv.State` given one `MassState` field
/// per entry of `masses` and `wbv.Links` one `LinkState` field per entry of `links` (plot keys,
/// model order, numbered from 1).
pub fn run_descriptor(masses: &[String], links: &[String]) -> Result<FileDescriptorSet> {
    let mut fds = base_descriptor();
    let file = (fds.file.iter_mut())
        .find(|f| f.package() == "wbv")
        .expect("wbv.proto declares package wbv");
    for (shell, item, keys) in [
        ("State", ".wbv.MassState", masses),
        ("Links", ".wbv.LinkState", links),
        ("StateBatch", ".wbv.MassStateBatch", masses),
        ("LinksBatch", ".wbv.LinkStateBatch", links),
    ] {
        let m = (file.message_type.iter_mut())
            .find(|m| m.name() == shell)
            .expect("wbv.proto declares the shells");
        // After the shell's own fields (the batches' `t = 1`).
        let first = m.field.len() as i32 + 1;
        for (i, key) in keys.iter().enumerate() {
            if !is_identifier(key) {
                return Err(Error::parameter(
                    format!(
                        "{} name `{key}`",
                        if shell.starts_with("State") {
                            "mass"
                        } else {
                            "link"
                        }
                    ),
                    "is not a protobuf field name (it must start with a letter or `_`); rename it \
                     or record with --encoding json",
                ));
            }
            m.field.push(FieldDescriptorProto {
                name: Some(key.clone()),
                number: Some(first + i as i32),
                label: Some(Label::Optional as i32),
                r#type: Some(Type::Message as i32),
                type_name: Some(item.to_string()),
                json_name: Some(key.clone()),
                ..Default::default()
            });
        }
    }
    Ok(fds)
}

/// The leaves of message `full_name` of `fds` grouped by parent (see [`ProtoTemplate::new`]): per run
/// of leaves sharing a parent, the parent's field number (`None`: top level) and the field number
/// and leaf index of each.
/// Per run of leaves sharing a parent: the parent's field number and (field number, leaf index).
type LeafGroups = Vec<(Option<u32>, Vec<(u32, usize)>)>;

fn leaf_groups(fds: &FileDescriptorSet, full_name: &str, leaves: &[Leaf]) -> Result<LeafGroups> {
    let missing = |what: String| {
        Error::parameter(
            "protobuf schema",
            format!("`{full_name}` has no field {what} (proto/wbv.proto)"),
        )
    };
    let msg = message(fds, full_name).ok_or_else(|| missing(String::new()))?;
    // (parent field number, [(leaf field number)]) per run of leaves sharing a parent
    let mut groups: Vec<Group> = Vec::new();
    for (index, leaf) in leaves.iter().enumerate() {
        let (parent, name, inner_type) = match leaf.path.as_slice() {
            [name] => (None, name.as_str(), full_name.to_string()),
            [parent, name] => {
                let f = (msg.field.iter())
                    .find(|f| f.name() == parent)
                    .ok_or_else(|| missing(format!("`{parent}`")))?;
                let t = f.type_name().trim_start_matches('.').to_string();
                (Some(parent.as_str()), name.as_str(), t)
            }
            _ => return Err(missing(format!("`{}`", leaf.path.join(".")))),
        };
        let number = field_number(fds, &inner_type, name)
            .ok_or_else(|| missing(format!("`{}`", leaf.path.join("."))))?;
        match groups.last_mut() {
            Some((p, _, fields)) if *p == parent => fields.push((number, index)),
            _ => {
                let outer = match parent {
                    None => None,
                    Some(p) => Some(
                        field_number(fds, full_name, p).ok_or_else(|| missing(format!("`{p}`")))?,
                    ),
                };
                groups.push((parent, outer, vec![(number, index)]));
            }
        }
    }
    Ok(groups.into_iter().map(|(_, o, f)| (o, f)).collect())
}

/// Leaves sharing a parent: the parent's name and field number (`None` at the top level) and
/// the field number and leaf index of each.
type Group<'a> = (Option<&'a str>, Option<u32>, Vec<(u32, usize)>);

/// Writes the protobuf message of a topic straight from its values (in leaf order): every leaf
/// a `double` field (key, then 8 bytes little-endian), nested leaves inside a length-delimited
/// sub-message. Every value has a fixed size, so all the bytes but the values are constant and
/// precomputed: `fragments[0] v0 fragments[1] v1 …` (the JSON [`Template`](super::json::Template)
/// works the same way). The bytes equal what the `prost` derives encode for the same values.
#[derive(Debug, Clone, PartialEq)]
pub struct ProtoTemplate {
    /// Before each value: the sub-message header where a group starts, and the field key.
    /// Fields go out in leaf order, which is the field-number order prost writes except for the
    /// fore-and-aft measured channels (`a_seat_x` before `a_head_z`): protobuf readers take fields in
    /// any order, and [`ProtoTable`] keeps the order of the bytes so that a run reads back with
    /// its channels in the same order in both encodings.
    fragments: Vec<Vec<u8>>,
}

impl ProtoTemplate {
    /// The encoder of the message `full_name` of `fds` for `leaves`: a one-element path is a
    /// double field of the message; a two-element path `[key, field]` is `field` of the
    /// sub-message field `key`; leaves of one sub-message are adjacent. Every name must exist in
    /// the descriptor.
    pub fn new(fds: &FileDescriptorSet, full_name: &str, leaves: &[Leaf]) -> Result<Self> {
        let groups = leaf_groups(fds, full_name, leaves)?;
        let mut fragments = Vec::with_capacity(leaves.len());
        for (outer, fields) in groups {
            for (k, &(f, index)) in fields.iter().enumerate() {
                let mut frag = Vec::new();
                if let (0, Some(outer)) = (k, outer) {
                    encode_key(outer, WireType::LengthDelimited, &mut frag);
                    let body: usize = fields.iter().map(|&(f, _)| key_len(f) + 8).sum();
                    encode_varint(body as u64, &mut frag);
                }
                encode_key(f, WireType::SixtyFourBit, &mut frag);
                debug_assert_eq!(index, fragments.len());
                fragments.push(frag);
            }
        }
        Ok(ProtoTemplate { fragments })
    }

    /// Number of values a message takes.
    pub fn len(&self) -> usize {
        self.fragments.len()
    }

    /// Whether a message takes no values.
    pub fn is_empty(&self) -> bool {
        self.fragments.is_empty()
    }

    /// Appends the message for `values` (any f64 is representable; the recorder refuses
    /// non-finite values before this, for the JSON encoding's sake and for the plots').
    pub fn render(&self, values: &[f64], out: &mut Vec<u8>) {
        debug_assert_eq!(values.len(), self.fragments.len());
        for (frag, v) in self.fragments.iter().zip(values) {
            out.extend_from_slice(frag);
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
}

/// Writes the batched message of a topic (`wbv.*Batch`, `--layout batched`) for `n` samples:
/// every leaf a packed `repeated double` (key, byte length, the `n` values little-endian), nested
/// leaves inside a length-delimited sub-message, in the leaf order of [`ProtoTemplate`]. Only the
/// lengths depend on `n`, so the keys are kept and the lengths written per message.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchTemplate {
    /// Per run of leaves sharing a parent: the parent's field number (`None`: top level) and the
    /// field number of each leaf, in leaf order.
    groups: Vec<(Option<u32>, Vec<u32>)>,
    len: usize,
}

impl BatchTemplate {
    /// The encoder of the batched message `full_name` of `fds` for `leaves` (paths as for
    /// [`ProtoTemplate::new`]).
    pub fn new(fds: &FileDescriptorSet, full_name: &str, leaves: &[Leaf]) -> Result<Self> {
        let groups = leaf_groups(fds, full_name, leaves)?;
        Ok(BatchTemplate {
            groups: (groups.into_iter())
                .map(|(outer, fields)| (outer, fields.into_iter().map(|(f, _)| f).collect()))
                .collect(),
            len: leaves.len(),
        })
    }

    /// Number of values a sample takes.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether a sample takes no values.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Appends the message of the samples `column(j)` of each leaf `j` (every column as long
    /// as the first): headers, then each column's doubles copied in one run.
    pub fn render<'a>(&self, column: impl Fn(usize) -> &'a [f64], out: &mut Vec<u8>) {
        use prost::encoding::encoded_len_varint;
        let n = if self.len == 0 { 0 } else { column(0).len() };
        let bytes = 8 * n as u64;
        let packed = |f: u32| key_len(f) + encoded_len_varint(bytes) + 8 * n;
        let mut j = 0;
        for (outer, fields) in &self.groups {
            if let Some(outer) = outer {
                encode_key(*outer, WireType::LengthDelimited, out);
                let body: usize = fields.iter().map(|&f| packed(f)).sum();
                encode_varint(body as u64, out);
            }
            for &f in fields {
                encode_key(f, WireType::LengthDelimited, out);
                encode_varint(bytes, out);
                let values = column(j);
                assert_eq!(values.len(), n, "every column has the same samples");
                out.reserve(8 * n);
                for v in values {
                    out.extend_from_slice(&v.to_le_bytes());
                }
                j += 1;
            }
        }
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    fn fields(fds: &FileDescriptorSet, name: &str) -> Vec<(String, i32, Type, Label)> {
        message(fds, name)
            .unwrap()
            .field
            .iter()
            .map(|f| (f.name().to_string(), f.number(), f.r#type(), f.label()))
            .collect()
    }

    /// The derives mirror the compiled `.proto`: the descriptor prost would generate from the
    /// derive attributes is compared through the encoding of a message with every field set to
    /// its field number, decoded back by the descriptor-driven reader.
    #[test]
    fn derives_match_the_compiled_proto() {
        let fds = base_descriptor();
        let expect = |name: &str, names: &[&str]| {
            let f = fields(&fds, name);
            let got: Vec<&str> = f.iter().map(|x| x.0.as_str()).collect();
            assert_eq!(got, names, "{name}");
            for (i, (_, number, ty, label)) in f.iter().enumerate() {
                assert_eq!(*number, i as i32 + 1);
                assert_eq!(*ty, Type::Double);
                assert_eq!(*label, Label::Optional);
            }
        };
        expect(
            "wbv.Measured",
            &[
                "t", "a_base_z", "a_seat_z", "a_head_z", "f_seat_z", "a_seat_x", "a_head_x",
            ],
        );
        expect("wbv.MassState", &["x", "v", "a", "x_abs", "v_abs", "a_abs"]);
        expect("wbv.LinkState", &["deflection", "force"]);
        // Each derive field set to its number decodes, through the descriptor, to that number
        // under the descriptor's name for it.
        let m = Measured {
            t: Some(1.0),
            a_base_z: Some(2.0),
            a_seat_z: Some(3.0),
            a_head_z: Some(4.0),
            f_seat_z: Some(5.0),
            a_seat_x: Some(6.0),
            a_head_x: Some(7.0),
        };
        let mut table = ProtoTable::new(WBV_FDS, "wbv.Measured").unwrap();
        table.add(&m.encode_to_vec()).unwrap();
        let (names, cols) = table.into_columns();
        for (k, (n, c)) in names.iter().zip(&cols).enumerate() {
            assert_eq!(c, &[k as f64 + 1.0], "{n:?}");
        }
        let s = MassState {
            x: Some(1.0),
            v: Some(2.0),
            a: Some(3.0),
            x_abs: Some(4.0),
            v_abs: Some(5.0),
            a_abs: Some(6.0),
        };
        let mut table = ProtoTable::new(WBV_FDS, "wbv.MassState").unwrap();
        table.add(&s.encode_to_vec()).unwrap();
        let (_, cols) = table.into_columns();
        assert_eq!(cols.concat(), [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        let l = LinkState {
            deflection: Some(1.0),
            force: Some(2.0),
        };
        let mut table = ProtoTable::new(WBV_FDS, "wbv.LinkState").unwrap();
        table.add(&l.encode_to_vec()).unwrap();
        assert_eq!(table.into_columns().1.concat(), [1.0, 2.0]);
    }

    #[test]
    fn template_bytes_equal_the_prost_derive_encoding() {
        let masses = vec!["head".to_string(), "seat_1".to_string()];
        let links = vec!["k1".to_string()];
        let fds = run_descriptor(&masses, &links).unwrap();
        let v = [-0.0, 1e-300, -2.5, f64::MAX, 3.0, 0.1];
        // Measured in a fore-and-aft run's leaf order (not field-number order)
        let leaves: Vec<Leaf> = [
            "t", "a_base_z", "a_seat_z", "a_seat_x", "a_head_z", "f_seat_z",
        ]
        .iter()
        .map(|n| Leaf::new(&[n], ""))
        .collect();
        let t = ProtoTemplate::new(&fds, "wbv.Measured", &leaves).unwrap();
        let mut out = Vec::new();
        t.render(&v, &mut out);
        // the reader keeps the order of the bytes
        let mut table = ProtoTable::new(&fds.encode_to_vec(), "wbv.Measured").unwrap();
        table.add(&out).unwrap();
        let names: Vec<String> = table.into_columns().0.concat();
        assert_eq!(
            names,
            [
                "t", "a_base_z", "a_seat_z", "a_seat_x", "a_head_z", "f_seat_z"
            ]
        );
        let m = Measured {
            t: Some(v[0]),
            a_base_z: Some(v[1]),
            a_seat_z: Some(v[2]),
            a_seat_x: Some(v[3]),
            a_head_z: Some(v[4]),
            f_seat_z: Some(v[5]),
            ..Default::default()
        };
        // same fields and bits as prost's encoding (which writes in field-number order)
        let back = Measured::decode(out.as_slice()).unwrap();
        assert_eq!(format!("{back:?}"), format!("{m:?}"));
        assert_eq!(out.len(), m.encode_to_vec().len());
        // State: head and seat_1, all six fields each
        let fields = ["x", "v", "a", "x_abs", "v_abs", "a_abs"];
        let leaves: Vec<Leaf> = (masses.iter())
            .flat_map(|m| fields.iter().map(move |f| Leaf::new(&[m, f], "")))
            .collect();
        let t = ProtoTemplate::new(&fds, "wbv.State", &leaves).unwrap();
        let vals: Vec<f64> = (0..12).map(|i| v[i % 6] * (i as f64 + 1.0)).collect();
        let mut out = Vec::new();
        t.render(&vals, &mut out);
        let mut expected = Vec::new();
        for (i, c) in vals.chunks(6).enumerate() {
            let s = MassState {
                x: Some(c[0]),
                v: Some(c[1]),
                a: Some(c[2]),
                x_abs: Some(c[3]),
                v_abs: Some(c[4]),
                a_abs: Some(c[5]),
            };
            prost::encoding::message::encode(i as u32 + 1, &s, &mut expected);
        }
        assert_eq!(out, expected);
        // Links: k1 force only (a body link)
        let t = ProtoTemplate::new(&fds, "wbv.Links", &[Leaf::new(&["k1", "force"], "")]).unwrap();
        let mut out = Vec::new();
        t.render(&[-0.0], &mut out);
        let mut expected = Vec::new();
        let l = LinkState {
            deflection: None,
            force: Some(-0.0),
        };
        prost::encoding::message::encode(1, &l, &mut expected);
        assert_eq!(out, expected);
        // and the reader gives the values back bit for bit, -0.0 included
        let mut table = ProtoTable::new(&fds.encode_to_vec(), "wbv.State").unwrap();
        let mut out = Vec::new();
        t_state(&fds, &masses).render(&vals, &mut out);
        table.add(&out).unwrap();
        let (names, cols) = table.into_columns();
        assert_eq!(names[7], ["seat_1", "v"]);
        let bits: Vec<u64> = cols.iter().map(|c| c[0].to_bits()).collect();
        assert_eq!(bits, vals.iter().map(|v| v.to_bits()).collect::<Vec<_>>());
    }

    fn t_state(fds: &FileDescriptorSet, masses: &[String]) -> ProtoTemplate {
        let fields = ["x", "v", "a", "x_abs", "v_abs", "a_abs"];
        let leaves: Vec<Leaf> = (masses.iter())
            .flat_map(|m| fields.iter().map(move |f| Leaf::new(&[m, f], "")))
            .collect();
        ProtoTemplate::new(fds, "wbv.State", &leaves).unwrap()
    }

    /// `wbv.MassStateBatch` as prost derives it (packed `repeated double`), the independent
    /// encoder the batched bytes are compared with.
    #[derive(Clone, PartialEq, Message)]
    struct MassStateBatch {
        #[prost(double, repeated, tag = "1")]
        x: Vec<f64>,
        #[prost(double, repeated, tag = "2")]
        v: Vec<f64>,
        #[prost(double, repeated, tag = "3")]
        a: Vec<f64>,
        #[prost(double, repeated, tag = "4")]
        x_abs: Vec<f64>,
        #[prost(double, repeated, tag = "5")]
        v_abs: Vec<f64>,
        #[prost(double, repeated, tag = "6")]
        a_abs: Vec<f64>,
    }

    #[test]
    fn batched_state_equals_the_prost_encoding_and_reads_back() {
        let masses = vec!["head".to_string(), "seat_1".to_string()];
        let fds = run_descriptor(&masses, &[]).unwrap();
        let fields = ["x", "v", "a", "x_abs", "v_abs", "a_abs"];
        let mut leaves = vec![Leaf::new(&["t"], "")];
        leaves.extend(
            (masses.iter()).flat_map(|m| fields.iter().map(move |f| Leaf::new(&[m, f], ""))),
        );
        let t = BatchTemplate::new(&fds, "wbv.StateBatch", &leaves).unwrap();
        // 3 samples of [t, 12 values]
        let n = 3;
        let block: Vec<f64> = (0..13 * n).map(|i| i as f64 * -0.25 + 1e-300).collect();
        let col = |j: usize| -> Vec<f64> { block[j * n..(j + 1) * n].to_vec() };
        let mut out = Vec::new();
        t.render(|j| &block[j * n..(j + 1) * n], &mut out);
        let mut expected = Vec::new();
        prost::encoding::double::encode_packed(1, &col(0), &mut expected);
        for (i, _) in masses.iter().enumerate() {
            let c = |f: usize| col(1 + 6 * i + f);
            let m = MassStateBatch {
                x: c(0),
                v: c(1),
                a: c(2),
                x_abs: c(3),
                v_abs: c(4),
                a_abs: c(5),
            };
            // masses are numbered from 2 after `t = 1`
            prost::encoding::message::encode(i as u32 + 2, &m, &mut expected);
        }
        assert_eq!(out, expected);
        let mut table = ProtoTable::new(&fds.encode_to_vec(), "wbv.StateBatch").unwrap();
        table.add(&out).unwrap();
        table.add(&out[..0]).unwrap_err(); // a message without samples
        let (names, cols) = table.into_columns();
        assert_eq!(names[0], ["t"]);
        assert_eq!(names[7], ["seat_1", "x"]);
        assert_eq!(cols[7], col(7));
    }

    #[test]
    fn a_name_that_is_no_protobuf_identifier_is_refused() {
        let e = run_descriptor(&["1st".to_string()], &[]).unwrap_err();
        assert!(e.to_string().contains("mass name `1st`"), "{e}");
    }
}
