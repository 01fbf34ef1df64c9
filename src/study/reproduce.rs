//! The parameter-study rows of the reproduction table (`docs/reproduction.md`): paper 000 Table 4,
//! the foam-thickness study ([`super::foam`]), v-v and total columns, frequency and time domain.

use super::foam::{Foam, FoamPoint, PAPER_TABLE_4, PaperRow, paper_run, thickness_study};
use crate::error::Result;
use crate::model::catalog;
use crate::study::table::Row;

fn pct(a: f64, b: f64) -> f64 {
    100.0 * (b - a) / a
}

fn row(quantity: String, paper: f64, wbv: f64, unit: &'static str, note: String) -> Row {
    Row {
        source: "000 Table 4".into(),
        quantity,
        paper,
        wbv,
        unit,
        note,
    }
}

/// Appends the Table 4 rows: per thickness the v-v peak and its frequency (frequency domain), SEAT
/// and total WRMSA with the comfort class (time domain, [`paper_run`]), then the 60 → 100 mm trends.
pub fn rows(rows: &mut Vec<Row>) -> Result<()> {
    let foam = Foam::default();
    let model = catalog::resolve("reference")?;
    let run = paper_run()?;
    let study = thickness_study(
        &model,
        &foam,
        &PAPER_TABLE_4.map(|p| p.thickness_m),
        Some(&run),
    )?;
    let layer = format!(
        "FE seat in the paper; here the Boileau body on a foam layer, A = {} m², η = {} at {} Hz \
         (assumed)",
        foam.area_m2, foam.loss_factor, foam.f_ref_hz
    );
    let excitation = format!(
        "{} s of {}, seed {}",
        run.settings.duration_s, run.excitation.description, run.seed
    );
    for (p, s) in PAPER_TABLE_4.iter().zip(&study) {
        let mm = p.thickness_m * 1000.0;
        let kc = format!(
            "{layer}; k = {:.0} kN/m, c = {:.0} N·s/m",
            s.k / 1000.0,
            s.c
        );
        rows.push(row(
            format!("foam {mm:.0} mm: v-v seat transmissibility peak frequency"),
            p.peak_freq_hz,
            s.peak.freq_hz,
            "Hz",
            kc.clone(),
        ));
        rows.push(row(
            format!("foam {mm:.0} mm: v-v seat transmissibility peak"),
            p.peak,
            s.peak.value,
            "–",
            kc,
        ));
        let iso = s.iso.expect("run given");
        rows.push(row(
            format!("foam {mm:.0} mm: v-v SEAT (time domain)"),
            p.seat_pct,
            iso.seat_percent,
            "%",
            format!("Wk seat z / base z; {excitation}"),
        ));
        rows.push(row(
            format!("foam {mm:.0} mm: total WRMSA a_v (time domain)"),
            p.wrmsa_m_s2,
            iso.total_value,
            "m/s²",
            comfort_note(p, s),
        ));
    }
    trends(rows, &study);
    Ok(())
}

/// The comfort class next to the paper's, with whether it matches.
fn comfort_note(p: &PaperRow, s: &FoamPoint) -> String {
    let c = s.iso.expect("run given").comfort;
    format!(
        "comfort (Annex C): {c} — paper: {} ({}); 1-D model: a_v = a_w of seat z",
        p.comfort,
        if c == p.comfort { "same" } else { "differs" }
    )
}

fn trends(rows: &mut Vec<Row>, study: &[FoamPoint]) {
    let (p, q) = (&PAPER_TABLE_4[0], &PAPER_TABLE_4[2]);
    let (a, b) = (&study[0], &study[2]);
    let (ia, ib) = (a.iso.expect("run given"), b.iso.expect("run given"));
    let same_seed =
        "same seed at every thickness: the change is the foam's, not the random input's";
    let table: [(&str, [f64; 2], [f64; 2], &str); 4] = [
        (
            "v-v peak frequency",
            [p.peak_freq_hz, q.peak_freq_hz],
            [a.peak.freq_hz, b.peak.freq_hz],
            "trend: thicker foam, softer layer (k ∝ 1/t), lower resonance",
        ),
        (
            "v-v peak transmissibility",
            [p.peak, q.peak],
            [a.peak.value, b.peak.value],
            "trend: the layer's damping ratio falls as 1/√t, so the peak rises",
        ),
        (
            "v-v SEAT",
            [p.seat_pct, q.seat_pct],
            [ia.seat_percent, ib.seat_percent],
            same_seed,
        ),
        (
            "total WRMSA",
            [p.wrmsa_m_s2, q.wrmsa_m_s2],
            [ia.total_value, ib.total_value],
            same_seed,
        ),
    ];
    for (what, [p0, p1], [w0, w1], note) in table {
        rows.push(row(
            format!("foam 60→100 mm: change of the {what}"),
            pct(p0, p1),
            pct(w0, w1),
            "%",
            note.into(),
        ));
    }
}
