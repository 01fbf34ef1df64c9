//! The per-step and batched protobuf encoders of the time-series topics: message bytes written
//! straight from the recorder's values, equal to what the `prost` derives encode.

use super::{field_number, message};
use crate::error::{Error, Result};
use crate::record::json::Leaf;
use prost::encoding::{WireType, encode_key, encode_varint, key_len};
use prost_types::FileDescriptorSet;

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
/// precomputed: `fragments[0] v0 fragments[1] v1 …` (the JSON [`Template`](crate::record::json::Template)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::proto::{LinkState, MassState, Measured, ProtoTable, run_descriptor};
    use prost::Message;

    #[test]
    fn template_bytes_equal_the_prost_derive_encoding() {
        let masses = vec!["head".to_string(), "seat_1".to_string()];
        let links = vec![("k1".to_string(), false)];
        let measured = ["a_base_z", "a_seat_z", "a_seat_x", "a_head_z", "f_seat_z"];
        let fds = run_descriptor(&measured, &masses, &links).unwrap();
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
        let fds = run_descriptor(&[], &masses, &[]).unwrap();
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
}
