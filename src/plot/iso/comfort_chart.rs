//! The ISO 2631-1 Annex C comfort chart and its shaded ranges.

use super::*;

/// The ISO 2631-1 Annex C classes as non-overlapping shaded ranges by wbv's rule (the class is the
/// highest range whose lower bound is ≤ a_v, [`crate::analysis::comfort`]), for charts of a_w or a_v.
pub fn comfort_spans() -> Vec<Span> {
    let lows: Vec<f64> = RANGES.iter().map(|r| r.1.unwrap_or(0.0)).collect();
    RANGES
        .iter()
        .enumerate()
        .map(|(i, (c, _, _))| Span {
            axis: Axis::Y,
            from: lows[i],
            to: lows.get(i + 1).copied().unwrap_or(1e3),
            label: c.text().into(),
            colour: comfort_colour(i),
        })
        .collect()
}

/// Green to dark red over the six classes.
fn comfort_colour(i: usize) -> (u8, u8, u8) {
    [
        (26, 152, 80),
        (145, 191, 60),
        (230, 200, 40),
        (244, 140, 50),
        (215, 48, 39),
        (140, 20, 30),
    ][i.min(5)]
}
/// The comfort-scale chart: each Annex C range a bar on its own row (they overlap), its label in
/// the gap above it (never on or into a bar: the plot places texts off the bars), the run's a_v a
/// vertical line.
pub fn comfort_chart(a_v: f64) -> Chart {
    // Half a bar's height in rows: the gap between bars (0.4 row) holds a label.
    const BAR_HALF: f64 = 0.28;
    let (x0, x1) = (0.1f64.min(a_v / 1.5), 4f64.max(a_v * 1.5));
    let n = RANGES.len();
    let mut series = vec![];
    let mut notes = vec![];
    for (i, (c, lo, hi)) in RANGES.iter().enumerate() {
        let row = (n - 1 - i) as f64;
        let (l, h) = (lo.unwrap_or(x0), hi.unwrap_or(x1));
        series.push(
            Series::line("", vec![l, h], vec![row + 0.5; 2])
                .styled(Style::Ribbon {
                    half_height: BAR_HALF,
                })
                .coloured(comfort_colour(i)),
        );
        let range = match (lo, hi) {
            (None, Some(h)) => format!("< {h}"),
            (Some(l), None) => format!("> {l}"),
            (Some(l), Some(h)) => format!("{l} – {h}"),
            (None, None) => String::new(),
        };
        // At the bar's top edge, the text's top 17 px above it: in the gap between rows.
        notes.push(Note {
            x: x0,
            y: row + 0.5 + BAR_HALF,
            text: format!("{} ({range} m/s²)", c.text()),
            dy: -17,
        });
    }
    Chart {
        title: format!(
            "ISO 2631-1 Annex C comfort reactions: a_v = {a_v:.3} m/s² is {}",
            crate::analysis::comfort::Comfort::from_total_value(a_v)
        ),
        x_label: "vibration total value a_v [m/s²]".into(),
        y_label: "Annex C reaction".into(),
        log_x: true,
        x_range: Some((x0, x1)),
        // Room above the top bar for its label.
        y_range: Some((0.0, n as f64 + 0.2)),
        y_ticks: Some(vec![]),
        series,
        notes,
        rules: vec![Rule {
            axis: Axis::X,
            at: a_v,
            label: format!("this run: a_v = {a_v:.3} m/s²"),
            colour: (0, 0, 0),
        }],
        ..Chart::default()
    }
}
