//! Universal file format (UFF/UNV) dataset 58, "function at nodal DOF", ASCII and binary (58b): the
//! time-history exchange format of test-and-measurement suites. Hand-written because no maintained
//! Rust crate reads it; the layout follows the I-DEAS dataset 58 description as written by PyPI
//! `pyuff` (the test fixtures' independent writer):
//!
//! ```text
//!     -1
//!     58            (binary: `58b` byte-order fp-format n-ascii-lines n-bytes …)
//! records 1–5       five ID lines (record 1, `id1`, names the column)
//! record 6          function type (1 = time response), …, response node and direction
//! record 7          ordinate data type (2 real single, 4 real double), points, even (1),
//!                   abscissa minimum, abscissa increment (s), z value
//! records 8–11      abscissa, ordinate, denominator, z-axis characteristics (record 9: units label)
//! record 12         the samples: ASCII E13.5 ×6 (single) or E20.12 ×4 (double) per line; binary
//!                   little- or big-endian IEEE floats
//!     -1
//! ```
//!
//! Every real, evenly spaced time response (types 0 general and 1 time response) is a column, named
//! by its `id1` line and by its 1-based position among them; other datasets are skipped with a note.
//! All must share one increment and length. The increment is printed with 6 significant digits
//! (E13.5), so a rate within that precision of a whole number of Hz is taken as that number.

use super::delimited::printed_resolution;
use super::{Column, Raw, Timing};
use crate::error::{Error, Result};

/// True when the first non-blank lines are `-1` and a dataset number.
pub(crate) fn looks_like(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(200)];
    let text = String::from_utf8_lossy(head);
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    lines.next() == Some("-1")
        && lines
            .next()
            .and_then(|l| l.split_whitespace().next())
            .is_some_and(|t| t.trim_end_matches('b').parse::<u32>().is_ok())
}

struct Cursor<'a> {
    b: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Cursor<'a> {
    /// The next line without its end of line, or None at the end.
    fn line(&mut self) -> Option<&'a str> {
        if self.pos >= self.b.len() {
            return None;
        }
        let rest = &self.b[self.pos..];
        let end = rest.iter().position(|&c| c == b'\n').unwrap_or(rest.len());
        self.pos += (end + 1).min(rest.len());
        self.line += 1;
        let l = &rest[..end];
        let l = l.strip_suffix(b"\r").unwrap_or(l);
        Some(std::str::from_utf8(l).unwrap_or(""))
    }
}

/// Fixed-width field `[from, to)` (0-based chars) of a record line, trimmed.
fn field(line: &str, from: usize, to: usize) -> &str {
    let from = from.min(line.len());
    let to = to.min(line.len());
    line.get(from..to).unwrap_or("").trim()
}

fn num(s: &str) -> Option<f64> {
    s.replace(['D', 'd'], "E").parse().ok()
}

struct Header {
    func_type: i64,
    ord_type: i64,
    n: usize,
    even: bool,
    dx: f64,
    dx_text: String,
    id1: String,
    unit: Option<String>,
}

fn header(rec: &[&str], source: &str, line: usize) -> Result<Header> {
    let err = |k: usize, m: &str| Error::data(source, Some(line + k), m.to_string());
    let r6 = rec[5];
    let r7 = rec[6];
    let int = |s: &str, k: usize, what: &str| -> Result<i64> {
        s.parse().map_err(|_| {
            err(
                k,
                &format!("record {}: {what} `{s}` is not an integer", k + 1),
            )
        })
    };
    let func_type = int(field(r6, 0, 5), 5, "function type")?;
    // Record 7 is fixed width (3I10, 3E13.5); fall back to fields separated by blanks.
    let fixed = [
        field(r7, 0, 10),
        field(r7, 10, 20),
        field(r7, 20, 30),
        field(r7, 30, 43),
        field(r7, 43, 56),
    ];
    let free: Vec<&str> = r7.split_whitespace().collect();
    let f7: Vec<&str> = if fixed.iter().all(|f| !f.is_empty()) {
        fixed.to_vec()
    } else {
        free
    };
    if f7.len() < 5 {
        return Err(err(
            6,
            "record 7: expected ordinate type, points, spacing, minimum, increment",
        ));
    }
    let ord_type = int(f7[0], 6, "ordinate data type")?;
    let n = int(f7[1], 6, "number of points")?;
    let even = int(f7[2], 6, "spacing")? == 1;
    let dx = num(f7[4]).ok_or_else(|| err(6, "record 7: abscissa increment is not a number"))?;
    if n < 0 {
        return Err(err(6, "record 7: negative number of points"));
    }
    let unit = rec
        .get(8)
        .map(|r9| field(r9, 47, 67))
        .filter(|u| !u.is_empty() && !u.eq_ignore_ascii_case("NONE"))
        .map(str::to_string);
    Ok(Header {
        func_type,
        ord_type,
        n: n as usize,
        even,
        dx,
        dx_text: f7[4].to_string(),
        id1: rec[0].trim().to_string(),
        unit,
    })
}

/// What [`read`] has gathered from the datasets so far.
#[derive(Default)]
struct Found {
    columns: Vec<Column>,
    /// One description per dataset not read as a column, for the note (or the error when none is).
    skipped: Vec<String>,
    /// The abscissa increment (s), as printed, and the line of the first dataset that stated it.
    rate: Option<(f64, String, usize)>,
    /// Datasets of any number seen.
    datasets: usize,
}

/// Reads the dataset-58 time responses of a UFF file.
pub(crate) fn read(bytes: &[u8], source: &str) -> Result<Raw> {
    let mut c = Cursor {
        b: bytes,
        pos: 0,
        line: 0,
    };
    let mut found = Found::default();
    while let Some(h) = dataset_start(&mut c, source)? {
        let start = c.line;
        let tokens: Vec<&str> = h.split_whitespace().collect();
        let Some(kind) = tokens.first().copied() else {
            continue;
        };
        found.datasets += 1;
        let binary = kind.ends_with('b');
        if kind.trim_end_matches('b') != "58" {
            found
                .skipped
                .push(format!("dataset {kind} at line {start}"));
            skip_dataset(&mut c, source, kind, binary, start)?;
            continue;
        }
        let mut rec = Vec::with_capacity(11);
        for _ in 0..11 {
            rec.push(c.line().ok_or_else(|| {
                Error::data(source, Some(c.line), "dataset 58 ends inside its header")
            })?);
        }
        let hd = header(&rec, source, start + 1)?;
        let data: Vec<f64> = if binary {
            binary_samples(&mut c, &tokens, &hd, source, start)?
        } else {
            ascii_samples(&mut c, &hd, source)?
        };
        add_column(&mut found, hd, data, source, start)?;
    }
    finish(found, source)
}

/// The dataset-number line after the next `-1`, or None at the end of the file. Between datasets
/// only blank lines may stand: anything else is a damaged file (bytes inserted, a cut), and
/// skipping to the next `-1` would silently drop a dataset.
fn dataset_start<'a>(c: &mut Cursor<'a>, source: &str) -> Result<Option<&'a str>> {
    while let Some(l) = c.line() {
        if l.trim().is_empty() {
            continue;
        }
        if l.trim() != "-1" {
            let shown: String = l.chars().filter(|c| !c.is_control()).take(24).collect();
            return Err(Error::data(
                source,
                Some(c.line),
                format!(
                    "`{shown}` stands outside any dataset (a dataset starts with `-1`): the file \
                     is damaged"
                ),
            ));
        }
        return Ok(c.line());
    }
    Ok(None)
}

/// Passes over a dataset other than 58 (ASCII: up to its closing `-1`); a binary one is refused,
/// as its length is not known here.
fn skip_dataset(
    c: &mut Cursor,
    source: &str,
    kind: &str,
    binary: bool,
    start: usize,
) -> Result<()> {
    if binary {
        return Err(Error::data(
            source,
            Some(start),
            format!("binary dataset {kind}: only datasets 58/58b are read"),
        ));
    }
    while let Some(l) = c.line() {
        if l.trim() == "-1" {
            break;
        }
    }
    Ok(())
}

/// True when the dataset holds real (single or double), evenly spaced ordinates: the only ones
/// whose samples are read.
fn readable(hd: &Header) -> bool {
    matches!(hd.ord_type, 2 | 4) && hd.even
}

/// The samples of a 58b dataset: the byte count of its `58b byte-order fp-format n-ascii-lines
/// n-bytes` line (`tokens`), then that many bytes of IEEE floats, 4 (single) or 8 (double) each,
/// in little- (1) or big-endian (2) order, then the closing `-1`. Empty when not [`readable`].
fn binary_samples(
    c: &mut Cursor,
    tokens: &[&str],
    hd: &Header,
    source: &str,
    start: usize,
) -> Result<Vec<f64>> {
    let order = tokens.get(1).and_then(|t| t.parse::<u32>().ok());
    let fp = tokens.get(2).and_then(|t| t.parse::<u32>().ok());
    let nbytes = tokens.get(4).and_then(|t| t.parse::<usize>().ok());
    let (Some(order @ (1 | 2)), Some(2), Some(nbytes)) = (order, fp, nbytes) else {
        return Err(Error::data(
            source,
            Some(start),
            "58b header: expected byte order 1 or 2, IEEE format 2 and a byte count",
        ));
    };
    let body =
        c.b.get(c.pos..c.pos.saturating_add(nbytes))
            .ok_or_else(|| {
                Error::data(
                    source,
                    Some(start),
                    format!("58b states {nbytes} bytes of data; the file ends before"),
                )
            })?;
    c.pos += nbytes;
    let width = if hd.ord_type == 2 { 4 } else { 8 };
    if readable(hd) && Some(body.len()) != hd.n.checked_mul(width) {
        return Err(Error::data(
            source,
            Some(start),
            format!(
                "58b: {} points of {width} bytes expected, {nbytes} bytes stated",
                hd.n
            ),
        ));
    }
    binary_end(c, source)?;
    Ok(if !readable(hd) {
        Vec::new()
    } else {
        decode_floats(body, width, order == 1)
    })
}

/// Passes the closing `-1` of binary data, on the same line as the data's end or the next
/// (blank lines between allowed).
fn binary_end(c: &mut Cursor, source: &str) -> Result<()> {
    loop {
        match c.line() {
            Some(l) if l.trim() == "-1" => return Ok(()),
            Some(l) if l.trim().is_empty() => continue,
            _ => {
                return Err(Error::data(
                    source,
                    Some(c.line),
                    "58b: expected `-1` after the binary data",
                ));
            }
        }
    }
}

/// IEEE floats of `width` bytes (4: single, else double), little-endian when `le`, as f64.
fn decode_floats(body: &[u8], width: usize, le: bool) -> Vec<f64> {
    if width == 4 {
        body.chunks_exact(4)
            .map(|b| {
                let a = [b[0], b[1], b[2], b[3]];
                let v = if le {
                    f32::from_le_bytes(a)
                } else {
                    f32::from_be_bytes(a)
                };
                v as f64
            })
            .collect()
    } else {
        body.chunks_exact(8)
            .map(|b| {
                let a: [u8; 8] = b.try_into().expect("8 bytes");
                if le {
                    f64::from_le_bytes(a)
                } else {
                    f64::from_be_bytes(a)
                }
            })
            .collect()
    }
}

/// The samples of an ASCII dataset 58 up to its closing `-1`: fixed-width fields of 13 (E13.5,
/// single) or 20 (E20.12, double) characters. Empty when not [`readable`].
fn ascii_samples(c: &mut Cursor, hd: &Header, source: &str) -> Result<Vec<f64>> {
    let width = if hd.ord_type == 2 || hd.ord_type == 5 {
        13
    } else {
        20
    };
    let mut v = Vec::with_capacity(hd.n.min(c.b.len() / 8));
    loop {
        let Some(l) = c.line() else {
            return Err(Error::data(
                source,
                Some(c.line),
                "dataset 58 ends without its closing `-1`",
            ));
        };
        if l.trim() == "-1" {
            break;
        }
        if !readable(hd) {
            continue;
        }
        let mut k = 0;
        while k < l.len() {
            let cell = l.get(k..(k + width).min(l.len())).unwrap_or("").trim();
            k += width;
            if cell.is_empty() {
                continue;
            }
            v.push(num(cell).ok_or_else(|| {
                Error::data(
                    source,
                    Some(c.line),
                    format!("`{cell}` is not a number (E{width} fields expected)"),
                )
            })?);
        }
    }
    Ok(v)
}

/// Adds the dataset starting at line `start` as a column when it is a real, evenly spaced time
/// response ([`check_timing`]); notes it as skipped otherwise. `k` and `dataset k` (its 1-based
/// position among the columns) are its aliases.
fn add_column(
    found: &mut Found,
    hd: Header,
    data: Vec<f64>,
    source: &str,
    start: usize,
) -> Result<()> {
    let timed = matches!(hd.func_type, 0 | 1);
    if !(readable(&hd) && timed) {
        found.skipped.push(format!(
            "`{}` (function type {}, ordinate type {}, {} spacing)",
            hd.id1,
            hd.func_type,
            hd.ord_type,
            if hd.even { "even" } else { "uneven" }
        ));
        return Ok(());
    }
    check_timing(&mut found.rate, &hd, data.len(), source, start)?;
    let k = found.columns.len() + 1;
    let name = column_name(&found.columns, &hd.id1, k);
    found.columns.push(Column {
        name,
        aliases: vec![k.to_string(), format!("dataset {k}")],
        unit: hd.unit,
        data,
        ..Column::default()
    });
    Ok(())
}

/// Checks a time response's `points` samples against its record 7: as many as stated, an
/// abscissa increment (s) > 0, and the same increment as the first column's, which `rate` keeps
/// (set here by the first).
fn check_timing(
    rate: &mut Option<(f64, String, usize)>,
    hd: &Header,
    points: usize,
    source: &str,
    start: usize,
) -> Result<()> {
    if points != hd.n {
        return Err(Error::data(
            source,
            Some(start),
            format!(
                "dataset `{}`: record 7 states {} points, {} found",
                hd.id1, hd.n, points
            ),
        ));
    }
    if !(hd.dx.is_finite() && hd.dx > 0.0) {
        return Err(Error::data(
            source,
            Some(start + 7),
            format!("abscissa increment {} s must be positive", hd.dx),
        ));
    }
    match rate {
        None => *rate = Some((hd.dx, hd.dx_text.clone(), start)),
        Some((dx, _, first)) if *dx != hd.dx => {
            return Err(Error::data(
                source,
                Some(start + 7),
                format!(
                    "increment {} s differs from {dx} s of the dataset at line {first}",
                    hd.dx
                ),
            ));
        }
        _ => {}
    }
    Ok(())
}

/// The `k`-th column's name: its `id1` line, else (blank, `NONE` or already taken) `dataset k`.
fn column_name(columns: &[Column], id1: &str, k: usize) -> String {
    if id1.is_empty() || id1.eq_ignore_ascii_case("NONE") || columns.iter().any(|c| c.name == id1) {
        format!("dataset {k}")
    } else {
        id1.to_string()
    }
}

/// The columns with their sample rate (Hz): 1 / increment, or the whole number of Hz within the
/// increment's printed precision (E13.5); an error when no dataset made a column.
fn finish(found: Found, source: &str) -> Result<Raw> {
    let Found {
        columns,
        skipped,
        rate,
        datasets,
    } = found;
    let Some((dx, dx_text, _)) = rate else {
        return Err(Error::data(
            source,
            None,
            format!(
                "no real, evenly spaced time response in dataset 58 ({datasets} datasets; \
                 skipped: {})",
                if skipped.is_empty() {
                    "none".into()
                } else {
                    skipped.join(", ")
                }
            ),
        ));
    };
    let whole = (1.0 / dx).round();
    let fs = if whole >= 1.0 && (1.0 / whole - dx).abs() <= 0.5 * printed_resolution(&dx_text) {
        whole
    } else {
        1.0 / dx
    };
    let mut notes = Vec::new();
    if !skipped.is_empty() {
        notes.push(format!("{source}: skipped {}", skipped.join(", ")));
    }
    Ok(Raw {
        columns,
        timing: Timing::Rate {
            fs,
            what: format!("the UFF58 abscissa increment {dx_text} s"),
        },
        lines: None,
        notes,
    })
}
