//! The reproduction table of papers 000–002 (`docs/reproduction.md`): every headline number,
//! the value the stated model gives here, and a verdict. Regenerate with `wbv reproduce`.
//!
//! The models are the papers' tables as printed (`models/seed00*.toml`); nothing is tuned to hit a
//! paper's number. Where a number is not reproduced, the row says what the stated model gives and
//! the likely reason (see also `../shared/seeds/ERRATA.md`).

use crate::error::Result;
use crate::model::{Model, catalog, file::damping_from_ratio, params};
use crate::response::{frf, modes, peak};

/// Relative tolerance for "reproduced".
pub const TOLERANCE: f64 = 0.05;

/// One headline number of a paper next to what wbv computes.
#[derive(Debug, Clone)]
pub struct Row {
    /// Paper and place (section, figure, table).
    pub source: String,
    /// The quantity, with the configuration.
    pub quantity: String,
    /// The paper's value.
    pub paper: f64,
    /// wbv's value for the stated model.
    pub wbv: f64,
    /// Unit of both values.
    pub unit: &'static str,
    /// Why it differs (or how it was computed), shown next to the verdict.
    pub note: String,
}

impl Row {
    /// True when wbv's value is within [`TOLERANCE`] of the paper's.
    pub fn reproduced(&self) -> bool {
        (self.wbv - self.paper).abs() <= TOLERANCE * self.paper.abs()
    }
}

/// Frequency grid for peak searches: 0.5–20 Hz in 0.005 Hz steps (peaks refined by a parabola).
fn fine_grid() -> Vec<f64> {
    frf::grid(0.5, 20.0, 3901, false).expect("valid grid")
}

fn peak_of(model: &Model, response: &str, first_local: bool) -> Result<peak::Peak> {
    let grid = fine_grid();
    let set = frf::compute(model, &grid)?;
    let mag = set.get(response).map(|r| r.magnitude()).unwrap_or_default();
    let p = if first_local {
        peak::local_peaks(&grid, &mag).into_iter().next()
    } else {
        None
    };
    Ok(p.or_else(|| peak::global_peak(&grid, &mag))
        .expect("non-empty response"))
}

fn magnitude_at(model: &Model, response: &str, f: f64) -> Result<f64> {
    let set = frf::compute(model, &[f])?;
    Ok(set
        .get(response)
        .map(|r| r.values[0].norm())
        .unwrap_or(f64::NAN))
}

fn with(model: &Model, path: &str, value: f64) -> Result<Model> {
    let mut m = model.clone();
    params::set(&mut m, path, value)?;
    Ok(m)
}

fn pct(a: f64, b: f64) -> f64 {
    100.0 * (b - a) / a
}

/// Paper 001 (Bell 214 pilot): the four configurations and the cushion sweeps.
fn paper_001(rows: &mut Vec<Row>) -> Result<()> {
    let body_note = "STHT and apparent mass at the seat surface depend on the body only; the Table 1 chain gives a higher, later peak (ERRATA)";
    let configs = [
        (
            "seed001-bare",
            "3-3, Fig. 5",
            1.58,
            4.0,
            2300.0,
            4.5,
            81.0,
            4.0,
        ),
        (
            "seed001-suspension",
            "3-4, Fig. 7",
            1.52,
            4.85,
            2200.0,
            4.5,
            81.0,
            4.0,
        ),
        (
            "seed001-cushion",
            "3-5, Fig. 9",
            1.43,
            5.0,
            2050.0,
            4.5,
            81.0,
            4.0,
        ),
        (
            "seed001-full",
            "3-6, Fig. 11",
            1.41,
            5.5,
            1950.0,
            4.5,
            78.0,
            4.0,
        ),
    ];
    for (name, place, t, tf, z, zf, am, amf) in configs {
        let model = catalog::resolve(name)?;
        let src = format!("001 §{place}");
        // The paper's curves change with the seat, so its "STHT" must be measured from the
        // excitation point (base) to the head; the seat-surface STHT cannot change with the seat.
        let head = peak_of(&model, "t_head", false)?;
        let stht = peak_of(&model, "stht", false)?;
        let dpmi = peak_of(&model, "dpmi", true)?;
        let apms = peak_of(&model, "apms", false)?;
        let seat_note = if name == "seed001-bare" {
            body_note.to_string()
        } else {
            format!(
                "base→head of the stated model; seat-surface STHT stays {:.2} at {:.2} Hz. with this seat the whole-body mode is near {:.1} Hz (ERRATA)",
                stht.value, stht.freq_hz, head.freq_hz
            )
        };
        rows.push(Row {
            source: src.clone(),
            quantity: format!("{name}: transmissibility peak"),
            paper: t,
            wbv: head.value,
            unit: "–",
            note: seat_note.clone(),
        });
        rows.push(Row {
            source: src.clone(),
            quantity: format!("{name}: transmissibility peak frequency"),
            paper: tf,
            wbv: head.freq_hz,
            unit: "Hz",
            note: seat_note,
        });
        rows.push(Row {
            source: src.clone(),
            quantity: format!("{name}: DPMI first peak"),
            paper: z,
            wbv: dpmi.value,
            unit: "N·s/m",
            note: format!(
                "at {:.2} Hz (paper {zf} Hz); impedance at the seat surface",
                dpmi.freq_hz
            ),
        });
        rows.push(Row {
            source: src.clone(),
            quantity: format!("{name}: apparent mass peak"),
            paper: am,
            wbv: apms.value,
            unit: "kg",
            note: format!(
                "at {:.2} Hz (paper {amf} Hz); static limit {:.1} kg = supported mass",
                apms.freq_hz,
                model.supported_mass()
            ),
        });
    }

    // §3-7: cushion stiffness 18.5 → 22.5 kN/m, m_c = 0.7 kg, c = 210 N·s/m, 6 DOF.
    let full = with(&catalog::resolve("seed001-full")?, "link.cushion.c", 210.0)?;
    let soft = with(&full, "link.cushion.k", 18_500.0)?;
    let stiff = with(&full, "link.cushion.k", 22_500.0)?;
    for (f, paper, what) in [
        (4.0, 33.0, "rises"),
        (4.9, 0.0, "stays about constant"),
        (10.0, -7.0, "falls"),
    ] {
        let a = magnitude_at(&soft, "t_head", f)?;
        let b = magnitude_at(&stiff, "t_head", f)?;
        rows.push(Row {
            source: "001 §3-7, Fig. 12a".into(),
            quantity: format!("k_c 18.5→22.5 kN/m: change of transmissibility at {f} Hz"),
            paper,
            wbv: pct(a, b),
            unit: "%",
            note: format!("paper: {what}; base→head {a:.2} → {b:.2}"),
        });
    }
    let (ps, pt) = (
        peak_of(&soft, "t_head", false)?,
        peak_of(&stiff, "t_head", false)?,
    );
    rows.push(Row {
        source: "001 §3-7, Fig. 12b".into(),
        quantity: "k_c 18.5→22.5 kN/m: shift of the transmissibility peak frequency".into(),
        paper: 5.0,
        wbv: pct(ps.freq_hz, pt.freq_hz),
        unit: "%",
        note: format!("{:.2} → {:.2} Hz", ps.freq_hz, pt.freq_hz),
    });
    for (resp, paper, fig) in [("dpmi", 17.0, "12c"), ("apms", 3.7, "12d")] {
        let a = peak_of(&soft, resp, true)?.value;
        let b = peak_of(&stiff, resp, true)?.value;
        rows.push(Row {
            source: format!("001 §3-7, Fig. {fig}"),
            quantity: format!("k_c 18.5→22.5 kN/m: change of the {resp} peak"),
            paper,
            wbv: pct(a, b),
            unit: "%",
            note: "seat-surface quantity: a body property, unaffected by the cushion".into(),
        });
    }

    // §3-8: damping ratio 0.06 → 0.10 at k_c = 20 kN/m. Reference mass: the 60 kg seated body.
    let m_ref = 60.0;
    let base = catalog::resolve("seed001-full")?;
    let c = |z| damping_from_ratio(z, 20_000.0, m_ref);
    let lo = with(&base, "link.cushion.c", c(0.06))?;
    let hi = with(&base, "link.cushion.c", c(0.10))?;
    let (pl, ph) = (
        peak_of(&lo, "t_head", false)?,
        peak_of(&hi, "t_head", false)?,
    );
    rows.push(Row {
        source: "001 §3-8, Fig. 13b".into(),
        quantity: "ζ_c 0.06→0.10: change of the transmissibility peak".into(),
        paper: -29.4,
        wbv: pct(pl.value, ph.value),
        unit: "%",
        note: format!(
            "ζ of the 60 kg body (c = {:.0}–{:.0} N·s/m); peak {:.2} → {:.2} (paper: −0.5 unit)",
            c(0.06),
            c(0.10),
            pl.value,
            ph.value
        ),
    });
    let (dl, dh) = (
        magnitude_at(&lo, "dpmi", 5.0)?,
        magnitude_at(&hi, "dpmi", 5.0)?,
    );
    rows.push(Row {
        source: "001 §3-8, Fig. 13c".into(),
        quantity: "ζ_c 0.06→0.10: change of DPMI at 5 Hz".into(),
        paper: -17.0,
        wbv: pct(dl, dh),
        unit: "%",
        note: "seat-surface impedance is a body property, unaffected by the cushion".into(),
    });
    Ok(())
}

/// Paper 002 (helicopter pilot, Boileau–Rakheja body, Kelvin–Voigt vs Maxwell cushion).
fn paper_002(rows: &mut Vec<Row>) -> Result<()> {
    let br = catalog::resolve("boileau-rakheja-4dof")?;
    let und = modes::undamped(&br)?;
    let dam = modes::damped(&br)?;
    let oscillating: Vec<_> = dam.iter().filter(|m| !m.overdamped).collect();
    rows.push(Row {
        source: "002 Table 1".into(),
        quantity: "Boileau–Rakheja body: first natural frequency".into(),
        paper: 4.98,
        wbv: und[0].freq_hz,
        unit: "Hz",
        note: format!(
            "undamped; the damped mode is at {:.2} Hz (ζ = {:.2})",
            oscillating[0].damped_hz, oscillating[0].zeta
        ),
    });
    let second = oscillating.get(1).map_or(f64::NAN, |m| m.damped_hz);
    rows.push(Row {
        source: "002 Table 1".into(),
        quantity: "Boileau–Rakheja body: second natural frequency".into(),
        paper: 8.3,
        wbv: und[1].freq_hz,
        unit: "Hz",
        note: format!(
            "no mode near 8.3 Hz: the next undamped mode is {:.1} Hz, the other modes are overdamped except one at {second:.1} Hz (ERRATA)",
            und[1].freq_hz
        ),
    });
    let stht = peak_of(&br, "stht", false)?;
    rows.push(Row {
        source: "002 Fig. 8".into(),
        quantity: "4-DOF analytical STHT peak (1.6–1.7)".into(),
        paper: 1.65,
        wbv: stht.value,
        unit: "–",
        note: format!("at {:.2} Hz (paper 5–6 Hz)", stht.freq_hz),
    });
    rows.push(Row {
        source: "002 Fig. 8".into(),
        quantity: "4-DOF analytical STHT peak frequency (5–6 Hz)".into(),
        paper: 5.5,
        wbv: stht.freq_hz,
        unit: "Hz",
        note: "midpoint of the paper's range".into(),
    });
    let kv = catalog::resolve("seed002-kelvin-voigt")?;
    let mx = catalog::resolve("seed002-maxwell")?;
    for (model, label) in [(&kv, "Kelvin–Voigt"), (&mx, "Maxwell")] {
        let p = peak_of(model, "t_head", false)?;
        rows.push(Row {
            source: "002 Figs. 10–14".into(),
            quantity: format!("{label} cushion 230 kN/m, ζ 0.04: base→head peak vs Boileau (≈1.7)"),
            paper: 1.7,
            wbv: p.value,
            unit: "–",
            note: format!(
                "at {:.2} Hz; paper reads its best fit off a figure; ζ refers to the 55.2 kg body (c = {:.0} N·s/m)",
                p.freq_hz,
                damping_from_ratio(0.04, 230_000.0, 55.2)
            ),
        });
    }
    Ok(())
}

/// Computes every row.
pub fn rows() -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    paper_001(&mut rows)?;
    paper_002(&mut rows)?;
    crate::study::reproduce::rows(&mut rows)?;
    crate::planar::reproduce::rows(&mut rows)?;
    Ok(rows)
}

fn fmt(v: f64) -> String {
    if !v.is_finite() {
        "n/a".into()
    } else if v.abs() >= 100.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.2}")
    }
}

/// Renders the table as Markdown.
pub fn markdown(rows: &[Row]) -> String {
    let mut s = String::from(
        "# Reproduction of the source papers\n\n\
         Generated by `wbv reproduce` from the models as the papers' tables state them (`models/`);\n\
         nothing is tuned to hit a paper's number. Verdict: *reproduced* when within 5 %.\n\
         Transmissibilities are ratios of absolute accelerations; STHT = head/seat surface;\n\
         apparent mass and impedance are taken at the seat surface (the occupant–cushion interface).\n\n\
         | source | quantity | paper | wbv | unit | verdict | note |\n|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s += &format!(
            "| {} | {} | {} | {} | {} | {} | {} |\n",
            r.source,
            r.quantity,
            fmt(r.paper),
            fmt(r.wbv),
            r.unit,
            if r.reproduced() {
                "reproduced"
            } else {
                "**not reproduced**"
            },
            r.note
        );
    }
    let n = rows.iter().filter(|r| r.reproduced()).count();
    s += &format!("\n{n} of {} numbers reproduced within 5 %.\n", rows.len());
    s += NOTES;
    s
}

const NOTES: &str = "
## Findings

- **Planar model (paper 000, issue 8).** `planar-occupant` is a 7-coordinate sagittal model (paper
  000's five segments, its Table 2 joints, de Leva 1996 segment inertia, hyperfoam cushion in series
  with seated tissue, backrest, footrest). Paper 000's modes are those of its body model before it
  is put on the seat (§3), so they are compared with the model on a rigid seat pan; its Table 4
  peaks with the foam seat. As stated, the model's modes come within 1–5 % (modes 2, 3) and ~18 %
  (modes 1, 4) and its v-h peak is 0.42–0.53 (paper 0.39–0.58), but its peaks sit near 5.2 Hz
  instead of 3.3–4.7 Hz. The calibration (Levenberg–Marquardt on assumed quantities only: tissue
  modulus and loss factors, backrest and footrest stiffness) matches modes 1 and 4 and the 80 mm
  peak frequencies, but pulls modes 2 and 3 down to 3.6 and 4.4 Hz: in this model the vertical
  mode on a rigid pan (paper 6.01 Hz) and the v-v peak on foam (3.93 Hz) cannot both match, and the
  peaks barely move with foam thickness. With the paper's own hyperfoam constants (small-strain
  modulus 2Σaᵢ = 330 kPa) an 80 mm layer is five to ten times stiffer than the tissue on it, so the
  tissue sets the resonance; the paper's FE trend (−30 % v-h peak frequency from 60 to 100 mm)
  needs a much softer foam than its §2 constants describe.

- **Paper 001's configurations cannot differ in STHT at the seat surface.** The seat-to-head
  transmissibility and the apparent mass measured at the occupant–cushion interface are properties of
  the body alone; a cushion or a suspension below it changes how the seat surface moves, not the ratio
  of head to seat-surface motion. The paper's falling peaks (1.58 → 1.41) must therefore be
  base-to-head ratios, and with its Table 2 and 3 parameters the stated model gives much higher,
  lower-frequency peaks: a 20 kN/m cushion under a 60 kg body puts the whole-body mode near 2.5 Hz.
- **Table 1 as a plain chain** peaks at about 1.8 near 4.5 Hz, not 1.58 at 4 Hz. The coupling k5, c5 of
  its eqs. (3) and (5) has no value in Table 1 and is left out.
- **Paper 002's second natural frequency (8.3 Hz)** does not exist in the Boileau–Rakheja model: its
  modes are 5.1 Hz (lightly damped) and 18.6, 35.4, 42.5 Hz undamped, most of them overdamped once
  damping is included.
- **Damping ratios of cushions** need a reference mass that neither paper states: here the supported
  body (60 kg for paper 001, 55.2 kg for paper 002), `c = 2ζ√(k·m)`. With it, paper 001's 200 N·s/m is
  ζ = 0.091 and its 0.06–0.10 sweep is 131–219 N·s/m.
- **A Maxwell cushion has no static stiffness**: it cannot carry the occupant's weight, so its
  transmissibility falls to zero towards 0 Hz. Paper 002's Maxwell results are reported as the model
  gives them.
- **Wan–Schimmels (1995)** parameters could not be checked against the original paper or the Liang &
  Chiang (2006) review in this session; the values in `models/wan-schimmels-4dof.toml` are recalled
  ones (head 4.17, upper torso 15, viscera 5.5, pelvis 36 kg; k5 between upper torso and pelvis) and
  remain unverified. With them the STHT peaks at 1.37 near 4 Hz and stays high (0.74) at 20 Hz, above
  measured rigid-seat data (≈ 0.3–0.5), which suggests a value or the k5 attachment is wrong.
- **Paper 000 Table 4 with a 1-D body on a linearised foam layer** (`wbv foam`) follows the direction
  of every trend (thicker foam: lower peak frequency, higher peak, lower SEAT and a_v) but not its
  size. The paper's hyperfoam (E₀ = 2Σa_i ≈ 330 kPa) under the assumed 0.09 m² contact gives
  265–442 kN/m, so stiff that the body's own mode near 4.2–4.3 Hz dominates and the seat peak stays
  near 1.1–1.2 against the FE model's 2.0–2.5. The 60 mm SEAT and the 80 mm a_v land within 5 % by
  coincidence, not agreement. The absolute a_v and the comfort class depend on the excitation band,
  which the paper does not state (0.5–20 Hz assumed at its 0.4 m/s² r.m.s.); the 80 mm a_v sits on
  the 0.315 m/s² Annex C boundary, hence \"a little uncomfortable\" where the paper says \"not
  uncomfortable\". The v-h columns need the planar model.
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_finite_and_cover_both_papers() {
        let rows = rows().unwrap();
        assert!(rows.iter().any(|r| r.source.starts_with("001")));
        assert!(rows.iter().any(|r| r.source.starts_with("002")));
        assert!(rows.iter().all(|r| r.wbv.is_finite()), "{rows:?}");
    }

    #[test]
    fn committed_table_is_up_to_date() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/reproduction.md");
        let committed = std::fs::read_to_string(path).unwrap_or_default();
        assert_eq!(
            committed,
            markdown(&rows().unwrap()),
            "docs/reproduction.md is stale: run `cargo run --release -- reproduce --force`"
        );
    }
}
