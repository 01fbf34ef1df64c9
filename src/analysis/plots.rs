//! Figures of a run for `wbv analyze --plot DIR`: PSDs, weighted PSDs and the seat transmissibility
//! (H1 with coherence), drawn with [`crate::plot`].

use super::report::Report;
use super::spectrum::{Segment, Welch, WelchOptions};
use crate::error::Result;
use crate::io::atomic::Overwrite;
use crate::plot::{Chart, Series, draw};
use crate::signals::Signals;
use std::path::{Path, PathBuf};

/// Frequencies shown, Hz (ISO 2631-1 range with a margin).
const F_LO: f64 = 0.2;
const F_HI: f64 = 100.0;

fn series(label: &str, f: &[f64], y: impl Iterator<Item = f64>) -> Series {
    let (x, y): (Vec<f64>, Vec<f64>) = f
        .iter()
        .copied()
        .zip(y)
        .filter(|(f, _)| (F_LO..=F_HI).contains(f))
        .unzip();
    Series {
        label: label.to_string(),
        x,
        y,
    }
}

fn chart(title: &str, y_label: &str, log_y: bool, series: Vec<Series>) -> Chart {
    Chart {
        title: title.to_string(),
        x_label: "frequency [Hz]".to_string(),
        y_label: y_label.to_string(),
        log_x: true,
        log_y,
        series,
    }
}

/// Writes `psd.<ext>`, `weighted_psd.<ext>` and, with `a_seat_z` and `a_base_z`,
/// `transmissibility.<ext>` into `dir`. Returns the paths written.
pub fn write_plots(
    signals: &Signals,
    report: &Report,
    welch: &WelchOptions,
    dir: &Path,
    ext: &str,
    overwrite: Overwrite,
) -> Result<Vec<PathBuf>> {
    let mut opts = *welch;
    let mut engine = Welch::new(signals.sample_rate_hz, &opts)?;
    if engine.segment_len() > signals.len() {
        opts.segment = Segment::Samples(signals.len());
        engine = Welch::new(signals.sample_rate_hz, &opts)?;
    }
    let (mut raw, mut weighted) = (Vec::new(), Vec::new());
    for c in &report.channels {
        let psd = engine.psd(signals.require(&c.name)?)?;
        raw.push(series(&c.name, &psd.freq_hz, psd.density.iter().copied()));
        let w = psd
            .freq_hz
            .iter()
            .zip(&psd.density)
            .map(|(&f, &g)| c.weighting.magnitude(f).powi(2) * g);
        weighted.push(series(
            &format!("{} ({})", c.name, c.weighting.name()),
            &psd.freq_hz,
            w,
        ));
    }
    let mut written = Vec::new();
    let mut out = |name: &str, charts: Vec<Chart>| -> Result<()> {
        let path = dir.join(format!("{name}.{ext}"));
        draw(&charts, &path, overwrite)?;
        written.push(path);
        Ok(())
    };
    out(
        "psd",
        vec![chart(
            "Acceleration PSD (Welch)",
            "PSD [(m/s²)²/Hz]",
            true,
            raw,
        )],
    )?;
    out(
        "weighted_psd",
        vec![chart(
            "Weighted acceleration PSD (ISO 2631-1)",
            "PSD [(m/s²)²/Hz]",
            true,
            weighted,
        )],
    )?;
    if let (Some(base), Some(seat)) = (signals.get("a_base_z"), signals.get("a_seat_z")) {
        let cs = engine.cross(base, seat)?;
        let h1 = series(
            "|H1| seat z / base z",
            &cs.freq_hz,
            cs.h1().into_iter().map(|h| h.norm()),
        );
        let h2 = series(
            "|H2| seat z / base z",
            &cs.freq_hz,
            cs.h2().into_iter().map(|h| h.norm()),
        );
        let coh = series("coherence γ²", &cs.freq_hz, cs.coherence().into_iter());
        out(
            "transmissibility",
            vec![
                chart("Seat transmissibility", "|H| [-]", true, vec![h1, h2]),
                chart("Coherence", "γ² [-]", false, vec![coh]),
            ],
        )?;
    }
    Ok(written)
}
