//! The planar model file (`kind = "planar"`): segments, joints, cushion, contacts and measurement
//! points. Units: kg, kg·m², m, N/m, N·s/m, N·m/rad, N·m·s/rad, Pa, degrees for contact normals.
//! Positions are the design posture in the seat frame (x forward, z up), m. See
//! `models/planar-occupant.toml` for a commented example.

use super::contact::{Contact, Cushion, Law};
use super::posture::Posture;
use super::segment::{Segment, lookup};
use super::{Joint, Planar, Spec};
use crate::error::{Error, Result};
use crate::model::material::Foam;
use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSpec {
    name: String,
    description: String,
    #[serde(default)]
    source: String,
    #[allow(dead_code)]
    kind: String,
    body_mass: Option<f64>,
    gravity: Option<f64>,
    #[serde(rename = "segment", default)]
    segments: Vec<SegmentSpec>,
    #[serde(rename = "joint", default)]
    joints: Vec<JointSpec>,
    cushion: CushionSpec,
    #[serde(rename = "contact", default)]
    contacts: Vec<ContactSpec>,
    measure: MeasureSpec,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SegmentSpec {
    name: String,
    from: [f64; 2],
    to: [f64; 2],
    anthropometry: Option<String>,
    m: Option<f64>,
    inertia: Option<f64>,
    com: Option<[f64; 2]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct JointSpec {
    name: String,
    parent: String,
    child: String,
    k: f64,
    c: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CushionSpec {
    thickness: f64,
    area: f64,
    loss_factor: f64,
    f_ref: f64,
    tissue_mu: f64,
    tissue_loss_factor: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ContactSpec {
    name: String,
    segment: String,
    role: String,
    at: [f64; 2],
    normal_deg: f64,
    k_n: Option<f64>,
    k_t: Option<f64>,
    c_n: Option<f64>,
    c_t: Option<f64>,
    cushion_share: Option<f64>,
    tissue_thickness: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MeasureSpec {
    seat: String,
    head: Option<String>,
}

/// Parses a planar model file and builds the model (equilibrium and linearisation included),
/// with its `(name, description, source)`.
pub fn parse(text: &str, file: &str) -> Result<(Planar, (String, String, String))> {
    let (spec, head) = parse_spec(text, file)?;
    let planar = Planar::build(spec).map_err(|e| Error::Model {
        line: None,
        file: file.to_string(),
        key: "(equilibrium)".into(),
        message: e.to_string(),
    })?;
    Ok((planar, head))
}

/// Parses and validates a planar model file into its [`Spec`] and `(name, description, source)`.
pub fn parse_spec(text: &str, file: &str) -> Result<(Spec, (String, String, String))> {
    let ck = Check { file };
    let fs = deserialize(text, &ck)?;
    let gravity = ck.positive("gravity".into(), fs.gravity.unwrap_or(9.81), "m/s²")?;
    if fs.segments.is_empty() {
        return Err(ck.err(
            "segment".into(),
            "no [[segment]] entries; expected the root first".into(),
        ));
    }
    let (joints, parent) = joint_tree(&ck, &fs)?;
    let segments = fs
        .segments
        .iter()
        .enumerate()
        .map(|(i, s)| segment(&ck, &fs, i, s, parent[i]))
        .collect::<Result<Vec<_>>>()?;
    let cushion = cushion(&ck, &fs.cushion)?;
    let contacts = contacts(&ck, &fs)?;
    let seat_contact = seat_contact(&ck, &contacts, &fs.measure.seat)?;
    let head = match &fs.measure.head {
        None => None,
        Some(h) => Some(segment_index(&ck, &fs.segments, "measure.head".into(), h)?),
    };
    let spec = Spec {
        posture: Posture {
            reference: contacts[seat_contact].at,
            segments,
        },
        joints,
        contacts,
        cushion,
        gravity,
        seat_contact,
        head,
    };
    Ok((spec, (fs.name, fs.description, fs.source)))
}

/// The checks of a model file's values; each failure is an [`Error::Model`] naming the file and
/// the key (`segment[2] (thigh).m`) that holds the value.
struct Check<'a> {
    file: &'a str,
}

impl Check<'_> {
    /// The error of the value at `key`.
    fn err(&self, key: String, message: String) -> Error {
        Error::Model {
            line: None,
            file: self.file.to_string(),
            key,
            message,
        }
    }

    /// `v` when it is finite and > 0 (a mass, length, stiffness, … in `unit`).
    fn positive(&self, key: String, v: f64, unit: &str) -> Result<f64> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(
                key,
                format!("{v} is not allowed; expected a positive number in {unit}"),
            ))
        }
    }

    /// `v` when it is finite and ≥ 0 (a damping, loss factor, thickness, … in `unit`).
    fn non_negative(&self, key: String, v: f64, unit: &str) -> Result<f64> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(
                key,
                format!("{v} is not allowed; expected a number ≥ 0 in {unit}"),
            ))
        }
    }

    /// `v` when both coordinates `[x, z]` (m, seat frame) are finite.
    fn finite2(&self, key: String, v: [f64; 2]) -> Result<[f64; 2]> {
        if v.iter().all(|x| x.is_finite()) {
            Ok(v)
        } else {
            Err(self.err(key, "expected finite coordinates [x, z] in m".into()))
        }
    }
}

/// The TOML text as a [`FileSpec`]; a syntax error or unknown key is reported at `line N` of where
/// it starts (or at `(file)` when the parser gives no position).
fn deserialize(text: &str, ck: &Check) -> Result<FileSpec> {
    toml::from_str(text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].lines().count().max(1));
        ck.err(
            line.map_or("(file)".into(), |l| format!("line {l}")),
            e.message().replace('\n', " ").trim().to_string(),
        )
    })
}

/// The index of the `[[segment]]` named `name` (the order of the file; 0 is the root).
fn segment_index(ck: &Check, segments: &[SegmentSpec], key: String, name: &str) -> Result<usize> {
    segments
        .iter()
        .position(|s| s.name == name)
        .ok_or_else(|| ck.err(key, format!("unknown segment `{name}`")))
}

/// The joints and each segment's parent index: the joints define the tree, each non-root segment
/// the child of exactly one joint listed after its parent. Stiffness in N·m/rad, damping in
/// N·m·s/rad.
fn joint_tree(ck: &Check, fs: &FileSpec) -> Result<(Vec<Joint>, Vec<Option<usize>>)> {
    let mut joints = Vec::new();
    let mut parent: Vec<Option<usize>> = vec![None; fs.segments.len()];
    for (i, j) in fs.joints.iter().enumerate() {
        let key = format!("joint[{i}] ({})", j.name);
        let p = segment_index(ck, &fs.segments, format!("{key}.parent"), &j.parent)?;
        let c = segment_index(ck, &fs.segments, format!("{key}.child"), &j.child)?;
        if c == 0 || parent[c].is_some() || c <= p {
            return Err(ck.err(
                format!("{key}.child"),
                "expected each non-root segment once as a child, listed after its parent (the first segment is the root)".into(),
            ));
        }
        parent[c] = Some(p);
        joints.push(Joint {
            name: j.name.clone(),
            parent: p,
            child: c,
            k: ck.non_negative(format!("{key}.k"), j.k, "N·m/rad")?,
            c: ck.non_negative(format!("{key}.c"), j.c, "N·m·s/rad")?,
        });
    }
    Ok((joints, parent))
}

/// Segment `i` of the file with its `parent` from [`joint_tree`]: ends `from`, `to` (m), then mass
/// (kg), inertia (kg·m²) and centre of mass (m) from anthropometry, each overridden by the file's
/// own `m`, `inertia`, `com`; all three must end up given.
fn segment(
    ck: &Check,
    fs: &FileSpec,
    i: usize,
    s: &SegmentSpec,
    parent: Option<usize>,
) -> Result<Segment> {
    let key = format!("segment[{i}] ({})", s.name);
    if i > 0 && parent.is_none() {
        return Err(ck.err(
            key,
            "no joint connects it to a parent; expected one [[joint]] with it as child".into(),
        ));
    }
    if fs.segments[..i].iter().any(|o| o.name == s.name) {
        return Err(ck.err(format!("{key}.name"), "duplicated segment name".into()));
    }
    let mut seg = Segment {
        name: s.name.clone(),
        parent,
        from: ck.finite2(format!("{key}.from"), s.from)?,
        to: ck.finite2(format!("{key}.to"), s.to)?,
        m: f64::NAN,
        inertia: f64::NAN,
        com: [f64::NAN; 2],
    };
    ck.positive(format!("{key}.to"), seg.length(), "m (segment length)")?;
    apply_anthropometry(ck, &key, s, fs.body_mass, &mut seg)?;
    if let Some(m) = s.m {
        seg.m = m;
    }
    if let Some(i) = s.inertia {
        seg.inertia = i;
    }
    if let Some(c) = s.com {
        seg.com = ck.finite2(format!("{key}.com"), c)?;
    }
    ck.positive(format!("{key}.m"), seg.m, "kg (or give anthropometry)")?;
    ck.positive(
        format!("{key}.inertia"),
        seg.inertia,
        "kg·m² (or give anthropometry)",
    )?;
    if !seg.com.iter().all(|v| v.is_finite()) {
        return Err(ck.err(
            format!("{key}.com"),
            "missing; expected [x, z] in m or anthropometry".into(),
        ));
    }
    Ok(seg)
}

/// Mass, inertia and centre of mass of `seg` from the segment's `anthropometry` table entry and
/// the file's `body_mass` (kg), which such a segment needs; nothing without `anthropometry`.
fn apply_anthropometry(
    ck: &Check,
    key: &str,
    s: &SegmentSpec,
    body_mass: Option<f64>,
    seg: &mut Segment,
) -> Result<()> {
    match (&s.anthropometry, body_mass) {
        (Some(a), Some(bm)) => {
            let a = lookup(a).map_err(|e| ck.err(format!("{key}.anthropometry"), e.to_string()))?;
            seg.from_anthropometry(ck.positive("body_mass".into(), bm, "kg")?, &a);
        }
        (Some(_), None) => {
            return Err(ck.err(
                "body_mass".into(),
                "missing; anthropometric segments need the body mass (kg)".into(),
            ));
        }
        (None, _) => {}
    }
    Ok(())
}

/// The `[cushion]` table: foam area (m²), loss factor and reference frequency (Hz), thickness (m,
/// 0 for a rigid seat pan) and the tissue's shear modulus (Pa) and loss factor.
fn cushion(ck: &Check, cs: &CushionSpec) -> Result<Cushion> {
    let foam = Foam {
        area_m2: ck.positive("cushion.area".into(), cs.area, "m²")?,
        loss_factor: ck.non_negative(
            "cushion.loss_factor".into(),
            cs.loss_factor,
            "(dimensionless)",
        )?,
        f_ref_hz: ck.positive("cushion.f_ref".into(), cs.f_ref, "Hz")?,
        ..Foam::default()
    };
    Ok(Cushion {
        foam,
        thickness: ck.non_negative(
            "cushion.thickness".into(),
            cs.thickness,
            "m (0: rigid seat pan)",
        )?,
        tissue_mu: ck.positive("cushion.tissue_mu".into(), cs.tissue_mu, "Pa")?,
        tissue_loss_factor: ck.non_negative(
            "cushion.tissue_loss_factor".into(),
            cs.tissue_loss_factor,
            "(dimensionless)",
        )?,
    })
}

/// The `[[contact]]` entries; the cushion shares of those on the cushion add up to at most 1.
fn contacts(ck: &Check, fs: &FileSpec) -> Result<Vec<Contact>> {
    let mut contacts = Vec::new();
    let mut share = 0.0;
    for (i, c) in fs.contacts.iter().enumerate() {
        let key = format!("contact[{i}] ({})", c.name);
        if fs.contacts[..i].iter().any(|o| o.name == c.name) {
            return Err(ck.err(format!("{key}.name"), "duplicated contact name".into()));
        }
        if !["cushion", "backrest", "footrest"].contains(&c.role.as_str()) {
            return Err(ck.err(
                format!("{key}.role"),
                format!(
                    "unknown role `{}`; expected cushion, backrest or footrest",
                    c.role
                ),
            ));
        }
        let (law, a) = contact_law(ck, &key, c)?;
        share += a;
        if !c.normal_deg.is_finite() {
            return Err(ck.err(
                format!("{key}.normal_deg"),
                "expected an angle in degrees".into(),
            ));
        }
        contacts.push(Contact {
            name: c.name.clone(),
            segment: segment_index(ck, &fs.segments, format!("{key}.segment"), &c.segment)?,
            at: ck.finite2(format!("{key}.at"), c.at)?,
            normal_deg: c.normal_deg,
            law,
            role: c.role.clone(),
        });
    }
    if share > 1.0 + 1e-9 {
        return Err(ck.err(
            "contact".into(),
            format!("cushion shares add up to {share}; expected at most 1"),
        ));
    }
    Ok(contacts)
}

/// A contact's force law and its share of the cushion area (0 unless on the cushion): either
/// `cushion_share` + `tissue_thickness` (m), the law then following from the cushion, or all of
/// `k_n`, `k_t` (N/m), `c_n`, `c_t` (N·s/m) given.
fn contact_law(ck: &Check, key: &str, c: &ContactSpec) -> Result<(Law, f64)> {
    match (
        c.cushion_share,
        c.tissue_thickness,
        c.k_n,
        c.k_t,
        c.c_n,
        c.c_t,
    ) {
        (Some(a), Some(h), None, None, None, None) => Ok((
            Law::Cushion {
                area_fraction: ck.positive(
                    format!("{key}.cushion_share"),
                    a,
                    "(fraction of the cushion area)",
                )?,
                tissue_thickness: ck.positive(format!("{key}.tissue_thickness"), h, "m")?,
            },
            a,
        )),
        (None, None, Some(k_n), Some(k_t), Some(c_n), Some(c_t)) => Ok((
            Law::Given {
                k_n: ck.non_negative(format!("{key}.k_n"), k_n, "N/m")?,
                k_t: ck.non_negative(format!("{key}.k_t"), k_t, "N/m")?,
                c_n: ck.non_negative(format!("{key}.c_n"), c_n, "N·s/m")?,
                c_t: ck.non_negative(format!("{key}.c_t"), c_t, "N·s/m")?,
            },
            0.0,
        )),
        _ => Err(ck.err(
            key.to_string(),
            "expected either cushion_share + tissue_thickness or all of k_n, k_t, c_n, c_t".into(),
        )),
    }
}

/// The index of the contact `measure.seat` names: the seat point, which must act on the root
/// (first) segment.
fn seat_contact(ck: &Check, contacts: &[Contact], seat: &str) -> Result<usize> {
    let i = contacts
        .iter()
        .position(|c| c.name == seat)
        .ok_or_else(|| {
            ck.err(
                "measure.seat".into(),
                format!("unknown contact `{seat}`; expected the contact at the seat point"),
            )
        })?;
    if contacts[i].segment != 0 {
        return Err(ck.err(
            "measure.seat".into(),
            "the seat contact must act on the root (first) segment".into(),
        ));
    }
    Ok(i)
}
