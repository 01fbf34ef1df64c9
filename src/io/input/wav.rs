//! RIFF WAVE on `hound`: 8/16/24/32-bit integer and 32-bit float PCM, any number of channels.
//!
//! Samples are read relative to full scale (integers divided by 2^(bits−1), floats as stored), so a
//! channel needs its calibration, `--sensitivity a_seat_z=VALUE` (the channel's value at full scale
//! in its unit), as vibration meters state it; without one the channel is refused, never read as
//! m/s². Columns are `channel 1`, `channel 2`, … (also `1`, `2`, … in `--column`).

use super::{Column, Raw, Timing};
use crate::error::{Error, Result};

/// Checks the RIFF structure that `hound` does not: the RIFF size against the file's length (a cut
/// copy, or bytes appended after the RIFF chunk), every chunk inside it, and a data chunk holding a
/// whole number of frames of `block_align` bytes. RF64 (sizes in a `ds64` chunk) is left to `hound`.
fn check_riff(bytes: &[u8], err: &dyn Fn(String) -> Error) -> Result<()> {
    if !bytes.starts_with(b"RIFF") || bytes.len() < 12 {
        return Ok(());
    }
    let u32_at =
        |i: usize| u32::from_le_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    let end = u32_at(4) as usize + 8;
    if bytes.len() < end {
        return Err(err(format!(
            "truncated: the RIFF header states {end} bytes, the file has {}",
            bytes.len()
        )));
    }
    // One pad byte after an odd-sized RIFF chunk is tolerated.
    if bytes.len() > end + 1 {
        return Err(err(format!(
            "{} bytes after the end of the RIFF chunk (byte {end}): a damaged or concatenated file",
            bytes.len() - end
        )));
    }
    let mut at = 12;
    let mut block_align = None;
    while at < end {
        if at + 8 > end {
            return Err(err(format!(
                "{} stray bytes at byte {at}, too few for a chunk header",
                end - at
            )));
        }
        let id = String::from_utf8_lossy(&bytes[at..at + 4]).into_owned();
        let size = u32_at(at + 4) as usize;
        let body = at + 8;
        if body + size > end {
            return Err(err(format!(
                "truncated: chunk `{id}` at byte {at} states {size} bytes, {} remain",
                end - body
            )));
        }
        if id == "fmt " && size >= 14 {
            block_align = Some(u16::from_le_bytes([bytes[body + 12], bytes[body + 13]]) as usize);
        }
        if let Some(b) = block_align.filter(|&b| id == "data" && b > 0 && !size.is_multiple_of(b)) {
            return Err(err(format!(
                "the data chunk's {size} bytes are not a whole number of {b}-byte frames"
            )));
        }
        at = body + size + size % 2;
    }
    Ok(())
}

/// Reads every channel of a WAV file as fractions of full scale.
pub(crate) fn read(bytes: &[u8], source: &str) -> Result<Raw> {
    let err = |m: String| Error::data(source, None, m);
    check_riff(bytes, &err)?;
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
