//! Delimited text (CSV, TSV, `;`-separated with decimal commas) on the `csv` crate.
//!
//! - Encoding: UTF-8 with or without a byte-order mark; other bytes are read as Latin-1 (Windows
//!   loggers write `m/s²` so), said in a note. UTF-16 is refused with what to do.
//! - Delimiter: the first line's tab, else `;`, else `,` (outside quotes). A decimal comma
//!   (`0,125`) is read as a decimal point: with tab or `;` as written, with `,` inside quotes
//!   (`"0,125"`, a spreadsheet's export in a decimal-comma locale), where a comma cannot be a
//!   delimiter. A number with both a comma and a point, or two commas, is not read.
//! - Header: the first line; a unit in brackets or parentheses at its end (`Acc Z [m/s^2]`) is the
//!   column's unit. A second line none of whose cells looks like a number ([`looks_numeric`]) is
//!   a units row; a line of numbers is always data.
//! - Lines starting with `#` are comments.

use super::{Column, Options, Raw, TIME_NAMES, Timing};
use crate::error::{Error, Result};
use std::borrow::Cow;

/// Decodes bytes to text (see the module comment); returns the text (borrowed when it is UTF-8)
/// and a note when not UTF-8.
pub(crate) fn decode<'a>(bytes: &'a [u8], source: &str) -> Result<(Cow<'a, str>, Option<String>)> {
    if bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]) {
        return Err(Error::data(
            source,
            Some(1),
            "UTF-16 text; save the file as UTF-8 (or ASCII) and read it again",
        ));
    }
    let bytes = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(s) => Ok((Cow::Borrowed(s), None)),
        Err(_) => Ok((
            Cow::Owned(bytes.iter().map(|&b| b as char).collect()),
            Some(format!("{source}: not UTF-8; read as Latin-1")),
        )),
    }
}

/// The delimiter of a header line: tab, else `;`, else `,`, counted outside double quotes.
pub(crate) fn sniff_delimiter(line: &str) -> u8 {
    let mut quoted = false;
    let (mut tab, mut semi) = (0, 0);
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            '\t' if !quoted => tab += 1,
            ';' if !quoted => semi += 1,
            _ => {}
        }
    }
    if tab > 0 {
        b'\t'
    } else if semi > 0 {
        b';'
    } else {
        b','
    }
}

/// Splits `Acc Z [m/s^2]` or `Acc Z (g)` into the name and the unit.
pub(crate) fn split_unit(header: &str) -> (String, Option<String>) {
    let h = header.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if h.ends_with(close)
            && let Some(i) = h.rfind(open)
        {
            let name = h[..i].trim();
            let unit = h[i + 1..h.len() - 1].trim();
            if !name.is_empty() && !unit.is_empty() {
                return (name.to_string(), Some(unit.to_string()));
            }
        }
    }
    (h.to_string(), None)
}

/// Parses a number cell; with `decimal_comma` a single `,` (and no `.`) is the decimal point.
pub(crate) fn parse_number(cell: &str, decimal_comma: bool) -> Option<f64> {
    let c = cell.trim();
    if decimal_comma && c.contains(',') {
        if c.contains('.') || c.matches(',').count() > 1 {
            return None;
        }
        return c.replace(',', ".").parse().ok();
    }
    c.parse().ok()
}

/// Whether a cell looks like a number, read or not (`1.5`, `0,125`, `-3e-2`, `1.2.3`): digits
/// with only signs, points, commas, exponents and spaces around them. Such a row is data, never a
/// units row (`m/s^2` and `1/s` have letters or a slash).
pub(crate) fn looks_numeric(cell: &str) -> bool {
    let c = cell.trim();
    c.bytes().any(|b| b.is_ascii_digit())
        && c.bytes().all(|b| {
            b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b',' | b'e' | b'E' | b' ')
        })
}

/// The printed resolution of a number: 1e-3 for `0.125`, 1e-4 for `1.5e-3`, 1 for `12`.
pub(crate) fn printed_resolution(cell: &str) -> f64 {
    let c = cell.trim();
    let (mantissa, exp) = match c.find(['e', 'E']) {
        Some(i) => (&c[..i], c[i + 1..].parse::<i32>().unwrap_or(0)),
        None => (c, 0),
    };
    let decimals = mantissa
        .find(['.', ','])
        .map_or(0, |i| mantissa.len() - i - 1) as i32;
    10f64.powi(exp.saturating_sub(decimals))
}

/// `text` with Windows line ends (`\r\n`) read as `\n`, for [`csv_records`]: the `csv` crate's
/// line numbers count a CRLF record end short.
pub(crate) fn lf_line_ends(text: String) -> String {
    match lf(&text) {
        Cow::Borrowed(_) => text,
        Cow::Owned(t) => t,
    }
}

/// [`lf_line_ends`] of borrowed text: copied only when it has a `\r`.
fn lf(text: &str) -> Cow<'_, str> {
    if text.contains('\r') {
        Cow::Owned(text.replace("\r\n", "\n"))
    } else {
        Cow::Borrowed(text)
    }
}

/// The `csv` crate's reader as wbv reads every CSV text ([`csv_records`], the data rows of a
/// measurement): rows of any length, `delimiter` between fields, lines starting with `comment`
/// skipped, fields trimmed of ASCII white space by the crate (`trim`: `csv::Trim::All`) or by the
/// caller (`csv::Trim::None`, then `str::trim_ascii`, the same trim without the crate's copy of
/// every record).
fn reader(text: &str, delimiter: u8, comment: Option<u8>, trim: csv::Trim) -> csv::Reader<&[u8]> {
    csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter)
        .comment(comment)
        .trim(trim)
        .from_reader(text.as_bytes())
}

/// The one way wbv reads CSV text (measurements here, PSD tables in `crate::excitation::table`)
/// on the `csv` crate: fields trimmed, rows of any length (the caller checks them), `delimiter`
/// between fields, lines starting with `comment` skipped; `text` has `\n` line ends
/// ([`lf_line_ends`]). Returns the first record (the header) and the records after it, whose
/// errors name `source` and the line (`malformed line: …`). `empty` is the error of text without
/// a header, `unreadable` the start of the error of a header the crate cannot read (both line 1).
pub(crate) fn csv_records<'a>(
    text: &'a str,
    source: &'a str,
    delimiter: u8,
    comment: Option<u8>,
    empty: &str,
    unreadable: &str,
) -> Result<(
    csv::StringRecord,
    impl Iterator<Item = Result<csv::StringRecord>> + 'a,
)> {
    let mut records = reader(text, delimiter, comment, csv::Trim::All).into_records();
    let header = match records.next() {
        Some(Ok(h)) => h,
        Some(Err(e)) => {
            return Err(Error::data(source, Some(1), format!("{unreadable}: {e}")));
        }
        None => return Err(Error::data(source, Some(1), empty)),
    };
    let records = records.map(move |r| {
        r.map_err(|e| {
            let line = e.position().map(|p| p.line() as usize);
            Error::data(source, line, format!("malformed line: {e}"))
        })
    });
    Ok((header, records))
}

/// Reads delimited text into raw columns (time, when present, is one of them).
///
/// The data rows are read on several threads when the file is large and has no quotes (so that
/// every line end ends a record): the text is cut at line ends into [`CHUNK_BYTES`] pieces, each
/// read by its own `csv` reader, and the pieces joined in order ([`Rows::join`]) to exactly what
/// one reader gives: the same samples, notes and first error.
pub(crate) fn read(bytes: &[u8], source: &str, opts: &Options) -> Result<Raw> {
    let (text, enc_note) = decode(bytes, source)?;
    let text = lf(&text);
    let first = text
        .lines()
        .find(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .ok_or_else(|| Error::data(source, Some(1), "empty file; expected a header line"))?;
    let delim = sniff_delimiter(first);
    let mut head = reader(&text, delim, Some(b'#'), csv::Trim::All);
    let mut header = csv::StringRecord::new();
    match head.read_record(&mut header) {
        Ok(true) => {}
        Ok(false) => return Err(Error::data(source, Some(1), "empty file")),
        Err(e) => {
            return Err(Error::data(
                source,
                Some(1),
                format!("cannot read the header: {e}"),
            ));
        }
    }
    let header_line = line_of(&header).max(1);
    // Where the data rows start: the byte and line after the header record.
    let (data_at, data_line) = (head.position().byte() as usize, head.position().line());
    let (mut columns, trailing_empty) = header_columns(&header, source, header_line)?;
    let layout = Layout {
        source,
        delim,
        trailing_empty,
        names: columns.iter().map(|c| c.name.clone()).collect(),
        timed: columns.iter().map(|c| is_time(c, opts)).collect(),
    };
    let data = &text[data_at.min(text.len())..];
    let pieces = pieces(data);
    let rows: Vec<Rows> = if pieces.len() > 1 {
        use rayon::prelude::*;
        // Each piece's first file line: the line ends before it.
        let ends: Vec<usize> = pieces
            .par_iter()
            .map(|p| p.bytes().filter(|&b| b == b'\n').count())
            .collect();
        let firsts: Vec<usize> = ends
            .iter()
            .scan(data_line as usize, |line, n| {
                let first = *line;
                *line += n;
                Some(first)
            })
            .collect();
        pieces
            .par_iter()
            .zip(firsts)
            .enumerate()
            .map(|(i, (p, line))| Rows::read(p, line, i == 0, &layout))
            .collect()
    } else {
        vec![Rows::read(data, data_line as usize, true, &layout)]
    };
    let (res, lines, decimal_commas) = Rows::join(rows, &mut columns, source)?;
    for (c, r) in columns.iter_mut().zip(res) {
        c.resolution = r;
    }
    let mut notes = Vec::new();
    notes.extend(enc_note);
    notes.extend(layout_note(source, delim, decimal_commas));
    Ok(Raw {
        columns,
        timing: Timing::InColumns,
        lines: Some(lines),
        notes,
    })
}

/// Least bytes of data rows one thread reads (below twice this a file is read on one thread).
pub const CHUNK_BYTES: usize = 4 << 20;

/// The data text cut at line ends into pieces of about [`CHUNK_BYTES`] or more, enough to keep
/// every thread busy; one piece when the text is small or has a quote (a quoted
/// field may hold a line end).
fn pieces(data: &str) -> Vec<&str> {
    let threads = rayon::current_num_threads().max(1);
    if data.len() < 2 * CHUNK_BYTES || threads == 1 || data.contains('"') {
        return vec![data];
    }
    let size = (data.len() / (4 * threads)).max(CHUNK_BYTES);
    let mut out = Vec::new();
    let mut at = 0;
    while at < data.len() {
        let mut end = (at + size).min(data.len());
        if end < data.len() {
            end = data[end..].find('\n').map_or(data.len(), |i| end + i + 1);
        }
        out.push(&data[at..end]);
        at = end;
    }
    out
}

/// The joined pieces: the time columns' resolutions, every data row's line, whether a decimal
/// comma was read.
type Joined = (Vec<Option<Vec<f64>>>, Vec<usize>, bool);

/// What every piece's reader needs of the header: the file's name for errors, the delimiter,
/// whether lines end in one, the columns' names and which are time columns.
struct Layout<'a> {
    source: &'a str,
    delim: u8,
    trailing_empty: bool,
    names: Vec<String>,
    timed: Vec<bool>,
}

/// The data rows of one piece of the text, read as one reader reads them after the header: the
/// samples of each column, the time columns' printed resolutions, each row's file line, and the
/// first unreadable cell of each column.
struct Rows {
    /// Samples per column (those before the column's first unreadable cell in this piece).
    data: Vec<Vec<f64>>,
    /// Printed resolution of each sample of a time column.
    res: Vec<Option<Vec<f64>>>,
    /// The file line of each data row.
    lines: Vec<usize>,
    /// The first cell of each column that is not a number.
    bad: Vec<Option<Error>>,
    /// Whether a number of the column was read with a decimal comma (before its bad cell).
    comma: Vec<bool>,
    /// The units row (first piece only) and its line.
    units: Option<(csv::StringRecord, usize)>,
    /// The error that stopped the reading of this piece (a malformed line).
    error: Option<Error>,
}

impl Rows {
    /// Reads `piece`, whose first line is file line `line`; `first` for the piece right after the
    /// header (whose first row may be a units row).
    fn read(piece: &str, line: usize, first: bool, layout: &Layout) -> Rows {
        let (ncol, source) = (layout.names.len(), layout.source);
        let mut rows = Rows {
            data: vec![Vec::new(); ncol],
            res: layout.timed.iter().map(|&t| t.then(Vec::new)).collect(),
            lines: Vec::new(),
            bad: (0..ncol).map(|_| None).collect(),
            comma: vec![false; ncol],
            units: None,
            error: None,
        };
        let mut rd = reader(piece, layout.delim, Some(b'#'), csv::Trim::None);
        let mut rec = csv::StringRecord::new();
        let mut first_data = first;
        loop {
            match rd.read_record(&mut rec) {
                Ok(true) => {}
                Ok(false) => break,
                Err(e) => {
                    let at = e.position().map(|p| p.line() as usize + line - 1);
                    rows.error = Some(Error::data(source, at, format!("malformed line: {e}")));
                    break;
                }
            }
            let at = line_of(&rec) + line - 1;
            let field = |i: usize| rec.get(i).map(str::trim_ascii);
            let Some(n) = field_count(rec.len(), field, ncol, layout.trailing_empty) else {
                continue; // blank line
            };
            if n != ncol {
                rows.error = Some(Error::data(
                    source,
                    Some(at),
                    format!("{n} fields, expected {ncol} as in the header"),
                ));
                break;
            }
            if first_data && rec.iter().take(n).all(|c| !looks_numeric(c)) {
                first_data = false;
                let mut units: csv::StringRecord = rec.iter().map(str::trim_ascii).collect();
                units.set_position(rec.position().cloned());
                rows.units = Some((units, at));
                continue;
            }
            first_data = false;
            rows.push(&rec, n, at, layout);
            rows.lines.push(at);
        }
        rows
    }

    /// Appends the cells of a data row at file line `at` to their columns (with their printed
    /// resolution to a time column's). A cell that is not a number marks its column bad, which
    /// then takes no more samples.
    fn push(&mut self, rec: &csv::StringRecord, n: usize, at: usize, layout: &Layout) {
        for (k, cell) in rec.iter().map(str::trim_ascii).take(n).enumerate() {
            if self.bad[k].is_some() {
                continue;
            }
            // With `,` between fields a cell holds a comma only inside quotes: a decimal comma
            // there as with tab or `;`.
            match parse_number(cell, true) {
                Some(v) => {
                    self.comma[k] |= cell.contains(',');
                    self.data[k].push(v);
                    if let Some(r) = self.res[k].as_mut() {
                        r.push(printed_resolution(cell));
                    }
                }
                None => {
                    self.bad[k] = Some(Error::data(
                        layout.source,
                        Some(at),
                        format!(
                            "column `{}`: `{cell}` is not a number (expected a decimal point or a \
                             decimal comma, not both)",
                            layout.names[k]
                        ),
                    ));
                }
            }
        }
    }

    /// Joins the pieces, in order, into the columns: each column's samples up to its first
    /// unreadable cell (then none, and that cell's error), and returns the time columns'
    /// resolutions, every row's line and whether a decimal comma was read; the first error that
    /// stopped a piece (after the units row's, which comes before it) is the file's.
    fn join(pieces: Vec<Rows>, columns: &mut [Column], source: &str) -> Result<Joined> {
        let ncol = columns.len();
        let mut res: Vec<Option<Vec<f64>>> = vec![None; ncol];
        let mut lines = Vec::with_capacity(pieces.iter().map(|p| p.lines.len()).sum());
        let total: usize = pieces.iter().map(|p| p.lines.len()).sum();
        for c in columns.iter_mut() {
            c.data = Vec::with_capacity(total);
        }
        let mut comma = false;
        for mut p in pieces {
            if let Some((rec, at)) = p.units.take() {
                units_row(columns, &rec, source, at)?;
            }
            for k in 0..ncol {
                let c = &mut columns[k];
                if c.bad.is_some() {
                    continue;
                }
                comma |= p.comma[k];
                if let Some(r) = p.res[k].take() {
                    res[k].get_or_insert_with(Vec::new).extend(r);
                }
                match p.bad[k].take() {
                    Some(e) => {
                        c.bad = Some(e);
                        c.data = Vec::new();
                    }
                    None => c.data.extend_from_slice(&p.data[k]),
                }
            }
            lines.extend_from_slice(&p.lines);
            if let Some(e) = p.error {
                return Err(e);
            }
        }
        Ok((res, lines, comma))
    }
}

/// The 1-based file line a record starts on (0 when the `csv` crate gives none).
fn line_of(r: &csv::StringRecord) -> usize {
    r.position().map_or(0, |p| p.line() as usize)
}

/// The columns the header row names (a unit at the end of a header, `Acc Z [m/s^2]`, is the
/// column's), each answering to its 1-based index and full header too, and whether every line
/// ends in a delimiter: the empty last column that makes is dropped. Headers must be non-empty
/// and names distinct.
fn header_columns(
    header: &csv::StringRecord,
    source: &str,
    header_line: usize,
) -> Result<(Vec<Column>, bool)> {
    let mut cells: Vec<String> = header.iter().map(str::to_string).collect();
    // A trailing delimiter on every line makes an empty last column: drop it.
    let trailing_empty = cells.len() > 1 && cells.last().is_some_and(|c| c.is_empty());
    if trailing_empty {
        cells.pop();
    }
    let mut columns: Vec<Column> = Vec::with_capacity(cells.len());
    for (i, h) in cells.iter().enumerate() {
        if h.is_empty() {
            return Err(Error::data(
                source,
                Some(header_line),
                format!("column {} has an empty header", i + 1),
            ));
        }
        let (name, unit) = split_unit(h);
        if columns.iter().any(|c| c.name == name) {
            return Err(Error::data(
                source,
                Some(header_line),
                format!("column `{name}` appears twice"),
            ));
        }
        let mut aliases = vec![(i + 1).to_string()];
        if name != *h {
            aliases.push(h.clone());
        }
        columns.push(Column {
            name,
            aliases,
            unit,
            ..Column::default()
        });
    }
    Ok((columns, trailing_empty))
}

/// True for the time column: named like time ([`TIME_NAMES`]) or mapped by `--column t_s=…`; its
/// printed resolution is kept for fitting the rate.
fn is_time(c: &Column, opts: &Options) -> bool {
    TIME_NAMES.iter().any(|n| c.name.eq_ignore_ascii_case(n))
        || opts
            .columns
            .iter()
            .any(|(ch, src)| ch == "t_s" && (c.name == *src || c.aliases.contains(src)))
}

/// The number of fields of a record of `len` (trimmed) fields `field(i)`, not counting the empty
/// one after a trailing delimiter (`ncol + 1` of them when the header had one too); None for a
/// blank line.
fn field_count<'r>(
    len: usize,
    field: impl Fn(usize) -> Option<&'r str>,
    ncol: usize,
    trailing_empty: bool,
) -> Option<usize> {
    let mut n = len;
    if trailing_empty && n == ncol + 1 && field(ncol).is_some_and(str::is_empty) {
        n = ncol;
    }
    if n == 1 && field(0).is_some_and(str::is_empty) {
        None
    } else {
        Some(n)
    }
}

/// Takes the units of a units row (the first data line, no cell like a number) at `line`: a cell's
/// unit, brackets or parentheses stripped, must agree with one the header gives.
fn units_row(
    columns: &mut [Column],
    rec: &csv::StringRecord,
    source: &str,
    line: usize,
) -> Result<()> {
    for (c, u) in columns.iter_mut().zip(rec.iter()) {
        let u = u
            .trim_matches(|ch| matches!(ch, '[' | ']' | '(' | ')'))
            .trim();
        if u.is_empty() {
            continue;
        }
        match &c.unit {
            Some(h) if h != u => {
                return Err(Error::data(
                    source,
                    Some(line),
                    format!(
                        "column `{}`: units row says `{u}`, header says `{h}`",
                        c.name
                    ),
                ));
            }
            _ => c.unit = Some(u.to_string()),
        }
    }
    Ok(())
}

/// The note on a tab- or semicolon-separated file, and on decimal commas read as points (quoted
/// ones in a comma-separated file); None for comma-separated text with decimal points.
fn layout_note(source: &str, delim: u8, decimal_commas: bool) -> Option<String> {
    let layout = match delim {
        b'\t' => "tab-separated",
        b';' => "semicolon-separated",
        _ if decimal_commas => "comma-separated",
        _ => return None,
    };
    Some(format!(
        "{source}: {layout}{}",
        match (decimal_commas, delim) {
            (true, b',') => ", quoted decimal commas (\"0,125\") read as points",
            (true, _) => ", decimal commas read as points",
            _ => "",
        }
    ))
}

#[cfg(test)]
mod tests {
    use super::super::{Options, assemble};
    use super::*;
    use std::fmt::Write as _;

    fn run(text: &str, opts: &Options) -> Result<super::super::Input> {
        assemble(read(text.as_bytes(), "x.csv", opts)?, "x.csv", opts)
    }

    fn logger_text(delim: &str, comma: bool, n: usize) -> String {
        let mut s = String::from("\u{feff}\"Time [s]\"");
        s += &format!("{delim}\"Acc Z\"{delim}Temp\n");
        s += &format!("s{delim}g{delim}degC\n");
        for i in 0..n {
            let t = format!("{:.3}", i as f64 / 200.0);
            let a = format!("{:.6}", 1.0 + 0.01 * (i as f64 * 0.1).sin());
            let (t, a) = if comma {
                (t.replace('.', ","), a.replace('.', ","))
            } else {
                (t, a)
            };
            s += &format!("{t}{delim}{a}{delim}21\r\n");
        }
        s
    }

    #[test]
    fn logger_layouts_with_units_row_decimal_comma_and_bom() {
        let opts = Options {
            columns: vec![("a_seat_z".into(), "Acc Z".into())],
            ..Options::default()
        };
        for (d, comma) in [(",", false), (";", true), ("\t", false), ("\t", true)] {
            let inp = run(&logger_text(d, comma, 2400), &opts).unwrap();
            assert_eq!(inp.signals.sample_rate_hz, 200.0, "{d:?}");
            let z = inp.signals.get("a_seat_z").unwrap();
            assert!((z[0] - 9.80665).abs() < 1e-9, "{}", z[0]);
            assert!(
                inp.notes.iter().any(|n| n.contains("Temp")),
                "{:?}",
                inp.notes
            );
        }
    }

    #[test]
    fn seat_only_and_fs_without_time() {
        let mut s = String::from("t_s,a_seat_z\n");
        for i in 0..2100 {
            s += &format!("{},{}\n", i as f64 / 200.0, (i as f64).sin());
        }
        let inp = run(&s, &Options::default()).unwrap();
        assert_eq!(inp.signals.names, vec!["a_seat_z"]);
        let mut s = String::from("a_seat_z;a_back_x\n");
        for i in 0..2100 {
            s += &format!("{},5;1\n", i % 7);
        }
        let e = run(&s, &Options::default()).unwrap_err().to_string();
        assert!(e.contains("--fs"), "{e}");
        let o = Options {
            fs: Some(210.0),
            ..Options::default()
        };
        let inp = run(&s, &o).unwrap();
        assert_eq!(inp.signals.sample_rate_hz, 210.0);
        assert_eq!(inp.signals.get("a_seat_z").unwrap()[1], 1.5);
    }

    #[test]
    fn errors_name_the_line() {
        let mut s = String::from("t_s,a_seat_z\n");
        for i in 0..2100 {
            s += &format!("{},{}\n", i as f64 / 200.0, 1);
        }
        let bad = s.replacen(",1\n", ",x\n", 5).replace('\n', "\r\n");
        let e = run(&bad, &Options::default()).unwrap_err().to_string();
        assert!(e.starts_with("x.csv:2:") && e.contains("`x`"), "{e}");
        let short = s.replacen(",1\n", ",1,2\n", 1);
        let e = run(&short, &Options::default()).unwrap_err().to_string();
        assert!(e.starts_with("x.csv:2:") && e.contains("3 fields"), "{e}");
        let e = run("t_s,a_seat_z\n0,1\n", &Options::default()).unwrap_err();
        assert!(e.to_string().contains("fewer than two"), "{e}");
    }

    /// A file large enough to be read in pieces, read on four threads and on one.
    fn both_ways(text: &str) -> (Result<super::super::Input>, Result<super::super::Input>) {
        let pool = |n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
        };
        let opts = Options::default();
        (
            pool(4).install(|| run(text, &opts)),
            pool(1).install(|| run(text, &opts)),
        )
    }

    #[test]
    fn pieces_read_what_one_reader_reads() {
        let mut s = String::from("# logger export\nt_s;a_seat_z;a_seat_x\n");
        for i in 0..400_000 {
            let (z, x) = ((i as f64 * 0.37).sin(), (i as f64 * 0.11).cos());
            let _ = writeln!(
                s,
                "{:.3};{z:.6};{}",
                i as f64 / 500.0,
                format!("{x:.5}").replace('.', ",")
            );
            if i == 200_000 {
                s.push_str("# a comment in the middle\n\n");
            }
        }
        assert!(s.len() > 2 * CHUNK_BYTES);
        let (many, one) = both_ways(&s);
        let (many, one) = (many.unwrap(), one.unwrap());
        assert_eq!(many.signals.data, one.signals.data);
        assert_eq!(many.notes, one.notes);
        assert_eq!(many.signals.len(), 400_000);
        // A bad cell deep in the file: the same error, with its line.
        let lines: Vec<&str> = s.lines().collect();
        let mut bad = lines.clone();
        let cell = bad[300_003].replacen(';', ";x", 1);
        bad[300_003] = &cell;
        let bad = bad.join("\n");
        let (many, one) = both_ways(&bad);
        let (many, one) = (many.unwrap_err().to_string(), one.unwrap_err().to_string());
        assert_eq!(many, one);
        assert!(
            many.contains("x.csv:300004:") && many.contains("`a_seat_z`"),
            "{many}"
        );
        bad_field_count(&s);
    }

    /// Only a short line, deep in the file: the error names it, read either way.
    fn bad_field_count(s: &str) {
        let mut lines: Vec<&str> = s.lines().collect();
        lines[390_000] = "1;2";
        let (many, one) = both_ways(&lines.join("\n"));
        let (many, one) = (many.unwrap_err().to_string(), one.unwrap_err().to_string());
        assert_eq!(many, one);
        assert!(
            many.contains("x.csv:390001:") && many.contains("2 fields"),
            "{many}"
        );
    }

    #[test]
    fn resolution_of_printed_numbers() {
        assert_eq!(printed_resolution("0.125"), 1e-3);
        assert!((printed_resolution("1.5e-3") - 1e-4).abs() < 1e-18);
        assert_eq!(printed_resolution("12"), 1.0);
        assert_eq!(split_unit("Acc Z [m/s^2]").1.as_deref(), Some("m/s^2"));
        assert_eq!(parse_number("0,5", true), Some(0.5));
        assert_eq!(parse_number("0,5", false), None);
    }
}
