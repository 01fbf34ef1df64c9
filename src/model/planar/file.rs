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
        file: file.to_string(),
        key: "(equilibrium)".into(),
        message: e.to_string(),
    })?;
    Ok((planar, head))
}

/// Parses and validates a planar model file into its [`Spec`] and `(name, description, source)`.
pub fn parse_spec(text: &str, file: &str) -> Result<(Spec, (String, String, String))> {
    let err = |key: String, message: String| Error::Model {
        file: file.to_string(),
        key,
        message,
    };
    let fs: FileSpec = toml::from_str(text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].lines().count().max(1));
        err(
            line.map_or("(file)".into(), |l| format!("line {l}")),
            e.message().replace('\n', " ").trim().to_string(),
        )
    })?;
    let positive = |key: String, v: f64, unit: &str| -> Result<f64> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(err(
                key,
                format!("{v} is not allowed; expected a positive number in {unit}"),
            ))
        }
    };
    let non_negative = |key: String, v: f64, unit: &str| -> Result<f64> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(err(
                key,
                format!("{v} is not allowed; expected a number ≥ 0 in {unit}"),
            ))
        }
    };
    let finite2 = |key: String, v: [f64; 2]| -> Result<[f64; 2]> {
        if v.iter().all(|x| x.is_finite()) {
            Ok(v)
        } else {
            Err(err(key, "expected finite coordinates [x, z] in m".into()))
        }
    };
    let gravity = positive("gravity".into(), fs.gravity.unwrap_or(9.81), "m/s²")?;
    if fs.segments.is_empty() {
        return Err(err(
            "segment".into(),
            "no [[segment]] entries; expected the root first".into(),
        ));
    }
    let seg_index = |key: String, name: &str| -> Result<usize> {
        fs.segments
            .iter()
            .position(|s| s.name == name)
            .ok_or_else(|| err(key, format!("unknown segment `{name}`")))
    };
    // Joints define the tree: each non-root segment is the child of exactly one joint.
    let mut joints = Vec::new();
    let mut parent: Vec<Option<usize>> = vec![None; fs.segments.len()];
    for (i, j) in fs.joints.iter().enumerate() {
        let key = format!("joint[{i}] ({})", j.name);
        let p = seg_index(format!("{key}.parent"), &j.parent)?;
        let c = seg_index(format!("{key}.child"), &j.child)?;
        if c == 0 || parent[c].is_some() || c <= p {
            return Err(err(
                format!("{key}.child"),
                "expected each non-root segment once as a child, listed after its parent (the first segment is the root)".into(),
            ));
        }
        parent[c] = Some(p);
        joints.push(Joint {
            name: j.name.clone(),
            parent: p,
            child: c,
            k: non_negative(format!("{key}.k"), j.k, "N·m/rad")?,
            c: non_negative(format!("{key}.c"), j.c, "N·m·s/rad")?,
        });
    }
    let mut segments = Vec::new();
    for (i, s) in fs.segments.iter().enumerate() {
        let key = format!("segment[{i}] ({})", s.name);
        if i > 0 && parent[i].is_none() {
            return Err(err(
                key,
                "no joint connects it to a parent; expected one [[joint]] with it as child".into(),
            ));
        }
        if fs.segments[..i].iter().any(|o| o.name == s.name) {
            return Err(err(format!("{key}.name"), "duplicated segment name".into()));
        }
        let mut seg = Segment {
            name: s.name.clone(),
            parent: parent[i],
            from: finite2(format!("{key}.from"), s.from)?,
            to: finite2(format!("{key}.to"), s.to)?,
            m: f64::NAN,
            inertia: f64::NAN,
            com: [f64::NAN; 2],
        };
        positive(format!("{key}.to"), seg.length(), "m (segment length)")?;
        match (&s.anthropometry, fs.body_mass) {
            (Some(a), Some(bm)) => {
                let a =
                    lookup(a).map_err(|e| err(format!("{key}.anthropometry"), e.to_string()))?;
                seg.from_anthropometry(positive("body_mass".into(), bm, "kg")?, &a);
            }
            (Some(_), None) => {
                return Err(err(
                    "body_mass".into(),
                    "missing; anthropometric segments need the body mass (kg)".into(),
                ));
            }
            (None, _) => {}
        }
        if let Some(m) = s.m {
            seg.m = m;
        }
        if let Some(i) = s.inertia {
            seg.inertia = i;
        }
        if let Some(c) = s.com {
            seg.com = finite2(format!("{key}.com"), c)?;
        }
        positive(format!("{key}.m"), seg.m, "kg (or give anthropometry)")?;
        positive(
            format!("{key}.inertia"),
            seg.inertia,
            "kg·m² (or give anthropometry)",
        )?;
        if !seg.com.iter().all(|v| v.is_finite()) {
            return Err(err(
                format!("{key}.com"),
                "missing; expected [x, z] in m or anthropometry".into(),
            ));
        }
        segments.push(seg);
    }
    let cs = &fs.cushion;
    let foam = Foam {
        area_m2: positive("cushion.area".into(), cs.area, "m²")?,
        loss_factor: non_negative(
            "cushion.loss_factor".into(),
            cs.loss_factor,
            "(dimensionless)",
        )?,
        f_ref_hz: positive("cushion.f_ref".into(), cs.f_ref, "Hz")?,
        ..Foam::default()
    };
    let cushion = Cushion {
        foam,
        thickness: non_negative(
            "cushion.thickness".into(),
            cs.thickness,
            "m (0: rigid seat pan)",
        )?,
        tissue_mu: positive("cushion.tissue_mu".into(), cs.tissue_mu, "Pa")?,
        tissue_loss_factor: non_negative(
            "cushion.tissue_loss_factor".into(),
            cs.tissue_loss_factor,
            "(dimensionless)",
        )?,
    };
    let mut contacts = Vec::new();
    let mut share = 0.0;
    for (i, c) in fs.contacts.iter().enumerate() {
        let key = format!("contact[{i}] ({})", c.name);
        if fs.contacts[..i].iter().any(|o| o.name == c.name) {
            return Err(err(format!("{key}.name"), "duplicated contact name".into()));
        }
        if !["cushion", "backrest", "footrest"].contains(&c.role.as_str()) {
            return Err(err(
                format!("{key}.role"),
                format!(
                    "unknown role `{}`; expected cushion, backrest or footrest",
                    c.role
                ),
            ));
        }
        let law = match (
            c.cushion_share,
            c.tissue_thickness,
            c.k_n,
            c.k_t,
            c.c_n,
            c.c_t,
        ) {
            (Some(a), Some(h), None, None, None, None) => {
                share += a;
                Law::Cushion {
                    area_fraction: positive(
                        format!("{key}.cushion_share"),
                        a,
                        "(fraction of the cushion area)",
                    )?,
                    tissue_thickness: positive(format!("{key}.tissue_thickness"), h, "m")?,
                }
            }
            (None, None, Some(k_n), Some(k_t), Some(c_n), Some(c_t)) => Law::Given {
                k_n: non_negative(format!("{key}.k_n"), k_n, "N/m")?,
                k_t: non_negative(format!("{key}.k_t"), k_t, "N/m")?,
                c_n: non_negative(format!("{key}.c_n"), c_n, "N·s/m")?,
                c_t: non_negative(format!("{key}.c_t"), c_t, "N·s/m")?,
            },
            _ => {
                return Err(err(
                    key,
                    "expected either cushion_share + tissue_thickness or all of k_n, k_t, c_n, c_t"
                        .into(),
                ));
            }
        };
        if !c.normal_deg.is_finite() {
            return Err(err(
                format!("{key}.normal_deg"),
                "expected an angle in degrees".into(),
            ));
        }
        contacts.push(Contact {
            name: c.name.clone(),
            segment: seg_index(format!("{key}.segment"), &c.segment)?,
            at: finite2(format!("{key}.at"), c.at)?,
            normal_deg: c.normal_deg,
            law,
            role: c.role.clone(),
        });
    }
    if share > 1.0 + 1e-9 {
        return Err(err(
            "contact".into(),
            format!("cushion shares add up to {share}; expected at most 1"),
        ));
    }
    let seat_contact = contacts
        .iter()
        .position(|c| c.name == fs.measure.seat)
        .ok_or_else(|| {
            err(
                "measure.seat".into(),
                format!(
                    "unknown contact `{}`; expected the contact at the seat point",
                    fs.measure.seat
                ),
            )
        })?;
    if contacts[seat_contact].segment != 0 {
        return Err(err(
            "measure.seat".into(),
            "the seat contact must act on the root (first) segment".into(),
        ));
    }
    let head = match &fs.measure.head {
        None => None,
        Some(h) => Some(seg_index("measure.head".into(), h)?),
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
