//! Paper 000 rows of the reproduction table for its segment model (issue 8): the four modes and
//! the v-v / v-h seat-transmissibility peaks per foam thickness, for the model as stated and after
//! the calibration of [`super::calibrate`]. Kept here so the table's other rows merge cleanly.

use super::calibrate::{Calibration, Figures, PAPER_MODES, PAPER_TABLE4, calibrate, figures};
use crate::error::Result;
use crate::model::{Model, catalog};
use crate::response::modes::describe;
use crate::study::table::Row;

/// Grid points from 1 to 12 Hz for the table's peaks (0.005 Hz steps, parabola-refined).
const POINTS: usize = 2201;

fn pct(a: f64, b: f64) -> f64 {
    100.0 * (b - a) / a
}

/// Worded shapes of the lowest four modes on a rigid seat pan.
fn words(model: &Model) -> Result<Vec<String>> {
    let mut rigid = model.clone();
    rigid.set("cushion.thickness", 0.0)?;
    Ok(describe(rigid.system())?
        .iter()
        .take(4)
        .map(|d| d.words())
        .collect())
}

fn rows_of(rows: &mut Vec<Row>, tag: &str, model: &Model, f: &Figures, note: &str) -> Result<()> {
    let paper_words = [
        "fore-and-aft head and buttocks",
        "fore-and-aft lower body, spine bending",
        "vertical whole body, pelvis pitch",
        "pelvis pitch, vertical buttocks",
    ];
    for (i, ((m, p), w)) in f
        .modes
        .iter()
        .zip(PAPER_MODES)
        .zip(words(model)?)
        .enumerate()
    {
        rows.push(Row {
            source: "000 §3, Fig. 5".into(),
            quantity: format!("segment model{tag}: mode {} (rigid seat pan)", i + 1),
            paper: p,
            wbv: *m,
            unit: "Hz",
            note: format!("paper: {}; wbv: {w}. {note}", paper_words[i]),
        });
    }
    for ((vv, vh), (t, vf, vp, hf, hp)) in f.peaks.iter().zip(PAPER_TABLE4) {
        let mm = t * 1000.0;
        for (what, paper, wbv, unit) in [
            ("v-v peak frequency", vf, vv.freq_hz, "Hz"),
            ("v-v peak", vp, vv.value, "–"),
            ("v-h peak frequency", hf, vh.freq_hz, "Hz"),
            ("v-h peak", hp, vh.value, "–"),
        ] {
            rows.push(Row {
                source: "000 Table 4".into(),
                quantity: format!("segment model{tag}, foam {mm:.0} mm: {what}"),
                paper,
                wbv,
                unit,
                note: note.into(),
            });
        }
    }
    let (a, b) = (&f.peaks[0], &f.peaks[2]);
    for (what, paper, wbv) in [
        ("v-v", pct(4.11, 3.75), pct(a.0.freq_hz, b.0.freq_hz)),
        ("v-h", pct(4.69, 3.30), pct(a.1.freq_hz, b.1.freq_hz)),
    ] {
        rows.push(Row {
            source: "000 Table 4".into(),
            quantity: format!("segment model{tag}, foam 60→100 mm: change of the {what} peak frequency"),
            paper,
            wbv,
            unit: "%",
            note: "trend: falls with thickness in both; the foam of paper 000 §2 (E₀ = 330 kPa) is far stiffer than the seated tissue in series with it, so thickness moves the resonance little".into(),
        });
    }
    Ok(())
}

/// The rows of paper 000's segment model: stated model, then calibrated.
pub fn rows(rows: &mut Vec<Row>) -> Result<()> {
    let model = catalog::resolve(catalog::PAPER_000)?;
    let stated = figures(&model, POINTS)?;
    rows_of(
        rows,
        "",
        &model,
        &stated,
        &format!(
            "models/{}.toml as stated (posture, contact areas, tissue, backrest and footrest assumed)",
            catalog::PAPER_000
        ),
    )?;
    let Calibration {
        model: cal,
        values,
        se_before,
        se_after,
        evaluations,
    } = calibrate(&model)?;
    let fitted = values
        .iter()
        .map(|(p, s, f)| format!("{p} {s:.3}→{f:.3}"))
        .collect::<Vec<_>>()
        .join(", ");
    let note = format!(
        "after Levenberg–Marquardt on the 16 relative errors (SE {se_before:.3} → {se_after:.3}, {evaluations} evaluations): {fitted}"
    );
    rows_of(rows, " calibrated", &cal, &figures(&cal, POINTS)?, &note)
}
