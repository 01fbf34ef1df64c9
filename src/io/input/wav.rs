//! RIFF WAVE on `hound`: 8/16/24/32-bit integer and 32-bit float PCM, any number of channels.
//!
//! Samples are read relative to full scale (integers divided by 2^(bits−1), floats as stored), so a
//! channel needs its calibration, `--sensitivity a_seat_z=VALUE` (the channel's value at full scale
//! in its unit), as vibration meters state it; without one the channel is refused, never read as
//! m/s². Columns are `channel 1`, `channel 2`, … (also `1`, `2`, … in `--column`).

use super::{Column, Raw, Timing};
use crate::error::{Error, Result};

/// Reads every channel of a WAV file as fractions of full scale.
pub(crate) fn read(bytes: &[u8], source: &str) -> Result<Raw> {
    let err = |m: String| Error::data(source, None, m);
    let mut r = hound::WavReader::new(std::io::Cursor::new(bytes))
        .map_err(|e| err(format!("not a readable WAV file: {e}")))?;
    let spec = r.spec();
    let nch = spec.channels as usize;
    if nch == 0 || spec.sample_rate == 0 {
        return Err(err(
            "WAV header states no channels or a zero sample rate".into()
        ));
    }
    let frames = r.duration() as usize;
    // Refuse lengths the data chunk cannot hold before allocating for them.
    if frames.saturating_mul(nch) > bytes.len() {
        return Err(err(format!(
            "header states {frames} frames, more than the file holds"
        )));
    }
    let mut data = vec![Vec::with_capacity(frames); nch];
    let bad = |e: hound::Error| err(format!("WAV samples unreadable: {e}"));
    match spec.sample_format {
        hound::SampleFormat::Float => {
            if spec.bits_per_sample != 32 {
                return Err(err(format!(
                    "{}-bit float samples; 32-bit float or 8–32-bit integer expected",
                    spec.bits_per_sample
                )));
            }
            for (i, s) in r.samples::<f32>().enumerate() {
                data[i % nch].push(s.map_err(bad)? as f64);
            }
        }
        hound::SampleFormat::Int => {
            if !(1..=32).contains(&spec.bits_per_sample) {
                return Err(err(format!(
                    "{}-bit integer samples; 8–32 bits expected",
                    spec.bits_per_sample
                )));
            }
            let full = 2f64.powi(spec.bits_per_sample as i32 - 1);
            for (i, s) in r.samples::<i32>().enumerate() {
                data[i % nch].push(s.map_err(bad)? as f64 / full);
            }
        }
    }
    let len = data.iter().map(Vec::len).min().unwrap_or(0);
    data.iter_mut().for_each(|d| d.truncate(len));
    let columns = data
        .into_iter()
        .enumerate()
        .map(|(i, d)| Column {
            name: format!("channel {}", i + 1),
            aliases: vec![(i + 1).to_string()],
            unit: Some(super::FULL_SCALE.into()),
            data: d,
            ..Column::default()
        })
        .collect();
    Ok(Raw {
        columns,
        timing: Timing::Rate {
            fs: spec.sample_rate as f64,
            what: "the WAV header".into(),
        },
        lines: None,
        notes: vec![format!(
            "{source}: WAV, {nch} channel(s), {}-bit {:?}, samples relative to full scale",
            spec.bits_per_sample, spec.sample_format
        )],
    })
}
