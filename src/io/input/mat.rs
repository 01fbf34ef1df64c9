//! MATLAB MAT-files, level 5 (`save -v6`, `save -v7` compressed, `scipy.io.savemat`), on the
//! `matfile` crate. Every real numeric vector (1×N or N×1, any numeric class) is a column named after
//! its variable; a time vector is a variable named `t_s`, `time` or `t` (or `--column t_s=NAME`).
//! Scalars, matrices, complex arrays, and structs or cells are listed in a note and skipped.
//!
//! MAT v7.3 files are HDF5 containers; reading them would need the HDF5 C library (the `hdf5`
//! crate), which wbv does not link. They are refused with the way out: `save(f, '-v7')` in MATLAB
//! or `scipy.io.savemat`.

use super::{Column, Raw, Timing};
use crate::error::{Error, Result};
use matfile::NumericData;

fn to_f64(d: &NumericData) -> Option<Vec<f64>> {
    macro_rules! real {
        ($r:expr, $i:expr) => {
            if $i.is_some() {
                None
            } else {
                Some($r.iter().map(|&v| v as f64).collect())
            }
        };
    }
    match d {
        NumericData::Int8 { real, imag } => real!(real, imag),
        NumericData::UInt8 { real, imag } => real!(real, imag),
        NumericData::Int16 { real, imag } => real!(real, imag),
        NumericData::UInt16 { real, imag } => real!(real, imag),
        NumericData::Int32 { real, imag } => real!(real, imag),
        NumericData::UInt32 { real, imag } => real!(real, imag),
        NumericData::Int64 { real, imag } => real!(real, imag),
        NumericData::UInt64 { real, imag } => real!(real, imag),
        NumericData::Single { real, imag } => real!(real, imag),
        NumericData::Double { real, imag } => real!(real, imag),
    }
}

/// Checks the top-level data elements of a level-5 MAT-file against its length, which the
/// `matfile` parser does not: it stops quietly at an element cut short, so a truncated copy would
/// lose its last variables without a word. Each element is an 8-byte tag (type, size in bytes)
/// and its data padded to 8 bytes (compressed elements are not padded), or a 'small' element
/// packed into 8 bytes (MAT-File Format, The MathWorks, 2019, pp. 1-6 to 1-9).
fn check_elements(bytes: &[u8], err: &dyn Fn(String) -> Error) -> Result<()> {
    let big = &bytes[126..128] == b"MI";
    let u32_at = |i: usize| {
        let a = [bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]];
        if big {
            u32::from_be_bytes(a)
        } else {
            u32::from_le_bytes(a)
        }
    };
    const COMPRESSED: u32 = 15;
    let mut at = 128;
    let mut k = 0;
    while at < bytes.len() {
        k += 1;
        if at + 8 > bytes.len() {
            return Err(err(format!(
                "truncated: {} stray bytes after the last complete variable (byte {at})",
                bytes.len() - at
            )));
        }
        let tag = u32_at(at);
        if tag >> 16 != 0 {
            at += 8; // small data element
            continue;
        }
        let size = u32_at(at + 4) as usize;
        let end = at + 8 + size;
        if end > bytes.len() {
            return Err(err(format!(
                "truncated: data element {k} at byte {at} states {size} bytes, {} remain (a cut \
                 copy; its variable would be lost)",
                bytes.len() - at - 8
            )));
        }
        at = if tag == COMPRESSED {
            end
        } else {
            end.div_ceil(8) * 8
        };
    }
    Ok(())
}

/// Reads the numeric vectors of a MAT-file.
pub(crate) fn read(bytes: &[u8], source: &str) -> Result<Raw> {
    let err = |m: String| Error::data(source, None, m);
    if bytes.len() >= 116 && bytes.starts_with(b"MATLAB 7.3") {
        return Err(err(
            "MAT v7.3 (HDF5) is not read; save with `save(file, '-v7')` in MATLAB or \
             scipy.io.savemat (level 5)"
                .into(),
        ));
    }
    if bytes.len() < 128 || !bytes.starts_with(b"MATLAB 5.0") {
        return Err(err(
            "not a MAT-file level 5 (expected the 128-byte header `MATLAB 5.0 MAT-file`)".into(),
        ));
    }
    check_elements(bytes, &err)?;
    let file = std::panic::catch_unwind(|| matfile::MatFile::parse(bytes))
        .map_err(|_| err("malformed MAT-file (the parser gave up)".into()))?
        .map_err(|e| err(format!("malformed MAT-file: {e}")))?;
    let mut columns = Vec::new();
    let mut skipped = Vec::new();
    for a in file.arrays() {
        let size = a.size();
        let n: usize = size.iter().product();
        let vector = size.iter().filter(|&&d| d > 1).count() == 1;
        match to_f64(a.data()).filter(|d| vector && d.len() == n) {
            Some(data) => columns.push(Column {
                name: a.name().to_string(),
                data,
                ..Column::default()
            }),
            None => skipped.push(format!(
                "`{}` ({})",
                a.name(),
                size.iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join("×")
            )),
        }
    }
    let mut notes = Vec::new();
    if !skipped.is_empty() {
        notes.push(format!(
            "{source}: variables {} are not real vectors; skipped",
            skipped.join(", ")
        ));
    }
    Ok(Raw {
        columns,
        timing: Timing::InColumns,
        lines: None,
        notes,
    })
}
