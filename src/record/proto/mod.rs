//! Protobuf encoding of the time-series topics (`--encoding protobuf`, the default): the messages
//! of `proto/wbv.proto`, its `FileDescriptorSet` (compiled by `protox` in `build.rs`) completed
//! per run with one field per mass / link, and the per-step encoder.
//!
//! The typed messages ([`Measured`], [`MassState`], [`LinkState`]) are `prost` derives that mirror
//! the `.proto` (a test checks them field by field against the compiled descriptor). The recorder
//! does not build a struct per step: [`ProtoTemplate`] writes the same bytes straight from the
//! value slice with `prost::encoding` (a test checks them equal to the derives' encoding), which
//! keeps a step at a few nanoseconds per value.
//!
//! Here: the typed messages and the descriptors; `encode`: the per-step and batched encoders;
//! `table`: the descriptor-driven reader ([`ProtoTable`]).

mod encode;
mod table;

pub use encode::{BatchTemplate, ProtoTemplate};
pub use table::ProtoTable;

use crate::error::{Error, Result};
use prost::Message;
use prost_types::field_descriptor_proto::{Label, Type};
use prost_types::{DescriptorProto, FieldDescriptorProto, FileDescriptorSet};

/// `proto/wbv.proto` compiled to a serialized `FileDescriptorSet` (see `build.rs`).
const WBV_FDS: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/wbv.fds"));

/// The `.proto` text itself, for the docs and the validation tooling.
pub const WBV_PROTO: &str = include_str!("../../../proto/wbv.proto");

/// `wbv.Measured` of `proto/wbv.proto`.
#[derive(Clone, PartialEq, Message)]
pub struct Measured {
    /// Simulation time, s (= the message's log time).
    #[prost(double, optional, tag = "1")]
    pub t: Option<f64>,
    /// Seat-base (input) vertical acceleration, m/s².
    #[prost(double, optional, tag = "2")]
    pub a_base_z: Option<f64>,
    /// Absolute vertical acceleration at the occupant–cushion interface, m/s².
    #[prost(double, optional, tag = "3")]
    pub a_seat_z: Option<f64>,
    /// Absolute vertical head acceleration, m/s².
    #[prost(double, optional, tag = "4")]
    pub a_head_z: Option<f64>,
    /// Dynamic seat-surface force on the body, N (compression positive, static weight removed).
    #[prost(double, optional, tag = "5")]
    pub f_seat_z: Option<f64>,
    /// Fore-and-aft acceleration at the occupant–cushion interface, m/s²; planar models only.
    #[prost(double, optional, tag = "6")]
    pub a_seat_x: Option<f64>,
    /// Absolute fore-and-aft head acceleration, m/s²; planar models only.
    #[prost(double, optional, tag = "7")]
    pub a_head_x: Option<f64>,
    /// Vertical backrest force on the body, N (up positive, static load removed); models with a
    /// backrest link only.
    #[prost(double, optional, tag = "8")]
    pub f_back_z: Option<f64>,
}

/// `wbv.MassState` of `proto/wbv.proto`.
#[derive(Clone, PartialEq, Message)]
pub struct MassState {
    /// Displacement relative to the base, m.
    #[prost(double, optional, tag = "1")]
    pub x: Option<f64>,
    /// Velocity relative to the base, m/s.
    #[prost(double, optional, tag = "2")]
    pub v: Option<f64>,
    /// Acceleration relative to the base, m/s².
    #[prost(double, optional, tag = "3")]
    pub a: Option<f64>,
    /// Absolute displacement, m.
    #[prost(double, optional, tag = "4")]
    pub x_abs: Option<f64>,
    /// Absolute velocity, m/s.
    #[prost(double, optional, tag = "5")]
    pub v_abs: Option<f64>,
    /// Absolute acceleration, m/s².
    #[prost(double, optional, tag = "6")]
    pub a_abs: Option<f64>,
}

/// `wbv.LinkState` of `proto/wbv.proto`.
#[derive(Clone, PartialEq, Message)]
pub struct LinkState {
    /// Deflection `x_upper − x_lower`, m (extension positive); cushion, suspension and planar
    /// contact links only.
    #[prost(double, optional, tag = "1")]
    pub deflection: Option<f64>,
    /// Tension, N (positive pulls the two nodes together).
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
/// per entry of `masses` and `wbv.Links` one field per entry of `links` (plot keys, model order,
/// numbered from 1): a `LinkState` where the link's deflection is recorded (`links[i].1`), else a
/// `LinkForce`; and `wbv.Measured` (and its batch) cut to `t` and the `measured` channels of the
/// model. Viewers list every field a schema declares (PlotJuggler draws an absent optional field
/// as zeros), so a run's schema declares only what it records; the kept fields keep their
/// numbers, so a reader of the full `.proto` still reads every run.
pub fn run_descriptor(
    measured: &[&str],
    masses: &[String],
    links: &[(String, bool)],
) -> Result<FileDescriptorSet> {
    let mut fds = base_descriptor();
    let file = (fds.file.iter_mut())
        .find(|f| f.package() == "wbv")
        .expect("wbv.proto declares package wbv");
    for m in (file.message_type.iter_mut()).filter(|m| m.name().starts_with("Measured")) {
        m.field
            .retain(|f| f.name() == "t" || measured.contains(&f.name()));
        // Each proto3 `optional` field has its synthetic oneof (`_a_seat_x`): keep those of the
        // kept fields, renumbered (protobuf runtimes refuse a oneof without fields).
        let oneofs = std::mem::take(&mut m.oneof_decl);
        for f in &mut m.field {
            if let Some(i) = f.oneof_index {
                m.oneof_decl.push(oneofs[i as usize].clone());
                f.oneof_index = Some(m.oneof_decl.len() as i32 - 1);
            }
        }
    }
    let masses: Vec<(&str, &str)> = masses.iter().map(|k| (k.as_str(), "MassState")).collect();
    let links: Vec<(&str, &str)> = (links.iter())
        .map(|(k, deflection)| {
            (
                k.as_str(),
                if *deflection {
                    "LinkState"
                } else {
                    "LinkForce"
                },
            )
        })
        .collect();
    for (shell, batch, keys) in [
        ("State", "", &masses),
        ("Links", "", &links),
        ("StateBatch", "Batch", &masses),
        ("LinksBatch", "Batch", &links),
    ] {
        let m = (file.message_type.iter_mut())
            .find(|m| m.name() == shell)
            .expect("wbv.proto declares the shells");
        // After the shell's own fields (the batches' `t = 1`).
        let first = m.field.len() as i32 + 1;
        for (i, (key, item)) in keys.iter().enumerate() {
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
                name: Some(key.to_string()),
                number: Some(first + i as i32),
                label: Some(Label::Optional as i32),
                r#type: Some(Type::Message as i32),
                type_name: Some(format!(".wbv.{item}{batch}")),
                json_name: Some(key.to_string()),
                ..Default::default()
            });
        }
    }
    Ok(fds)
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
                "f_back_z",
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
            f_back_z: Some(8.0),
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
    fn measured_declares_only_the_model_channels_under_their_numbers() {
        let fds = run_descriptor(&["a_base_z", "a_seat_z", "f_seat_z"], &[], &[]).unwrap();
        for name in ["wbv.Measured", "wbv.MeasuredBatch"] {
            let got: Vec<(String, i32)> = (fields(&fds, name).into_iter())
                .map(|(n, k, _, _)| (n, k))
                .collect();
            let want = [("t", 1), ("a_base_z", 2), ("a_seat_z", 3), ("f_seat_z", 5)];
            assert_eq!(got, want.map(|(n, k)| (n.to_string(), k)), "{name}");
        }
        let m = message(&fds, "wbv.Measured").unwrap();
        let oneofs: Vec<&str> = m.oneof_decl.iter().map(|o| o.name()).collect();
        assert_eq!(oneofs, ["_t", "_a_base_z", "_a_seat_z", "_f_seat_z"]);
        prost_reflect::DescriptorPool::from_file_descriptor_set(fds).unwrap();
    }

    #[test]
    fn a_link_without_recorded_deflection_declares_only_its_force() {
        let links = [("k1".to_string(), false), ("cushion".to_string(), true)];
        let fds = run_descriptor(&[], &[], &links).unwrap();
        let types: Vec<String> = (message(&fds, "wbv.Links").unwrap().field.iter())
            .map(|f| format!("{} {}", f.name(), f.type_name()))
            .collect();
        assert_eq!(types, ["k1 .wbv.LinkForce", "cushion .wbv.LinkState"]);
        let batch = message(&fds, "wbv.LinksBatch").unwrap();
        assert_eq!(batch.field[1].type_name(), ".wbv.LinkForceBatch");
        assert_eq!(
            fields(&fds, "wbv.LinkForce")[0].1,
            2,
            "force keeps its number"
        );
    }

    #[test]
    fn a_name_that_is_no_protobuf_identifier_is_refused() {
        let e = run_descriptor(&[], &["1st".to_string()], &[]).unwrap_err();
        assert!(e.to_string().contains("mass name `1st`"), "{e}");
    }
}
