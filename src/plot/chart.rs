//! What a chart holds (series, reference lines, shaded ranges, notes) and the ranges and ticks
//! it is drawn with; [`envelope`] reduces a long signal to the points worth drawing.

use super::{ColourBar, Rgb, axis};

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Style {
    /// Solid line.
    #[default]
    Line,
    /// Dashed line (to tell apart curves that may coincide).
    Dashed,
    /// A filled circle at each point.
    Markers,
    /// A bar from the bottom of the axis to each y, spanning x/ratio … x·ratio (one-third-octave
    /// bands: ratio 10^(1/20)).
    Bars {
        /// Half-width ratio of a bar on the x axis (> 1).
        ratio: f64,
    },
    /// One horizontal bar per series from its first to its last x, centred on the first y,
    /// `half_height` (y units) thick: a range on a scale.
    Ribbon {
        /// Half the bar's thickness in y units.
        half_height: f64,
    },
}

/// One curve.
#[derive(Debug, Clone, Default)]
pub struct Series {
    /// Legend text; empty for no legend entry.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates; NaN leaves a gap (a masked point).
    pub y: Vec<f64>,
    /// Line, dashes, markers or bars.
    pub style: Style,
    /// Colour; the palette's next colour when `None`.
    pub colour: Option<Rgb>,
}

impl Series {
    /// A solid line.
    pub fn line(label: impl Into<String>, x: Vec<f64>, y: Vec<f64>) -> Series {
        Series {
            label: label.into(),
            x,
            y,
            ..Series::default()
        }
    }

    /// The same series drawn in `style`.
    pub fn styled(mut self, style: Style) -> Series {
        self.style = style;
        self
    }

    /// The same series in `colour`.
    pub fn coloured(mut self, colour: Rgb) -> Series {
        self.colour = Some(colour);
        self
    }
}

/// Which axis a reference line or range is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// A vertical line / range at x values.
    X,
    /// A horizontal line / range at y values.
    Y,
}

/// A labelled reference line (a limit, a boundary, a marked time).
#[derive(Debug, Clone, PartialEq)]
pub struct Rule {
    /// Whether the line is vertical (at an x value) or horizontal (at a y value).
    pub axis: Axis,
    /// Position in axis units; a line outside the axis range is not drawn.
    pub at: f64,
    /// Text placed beside the line where no curve passes.
    pub label: String,
    /// Colour of the dashed line and its label.
    pub colour: Rgb,
}

/// A labelled shaded range (a comfort class, a zone).
#[derive(Debug, Clone, PartialEq)]
pub struct Span {
    /// Whether the band is a range of x (vertical band) or of y (horizontal band).
    pub axis: Axis,
    /// Lower end of the range in axis units.
    pub from: f64,
    /// Upper end of the range in axis units; a band with `to ≤ from` after clipping to the axes
    /// is not drawn.
    pub to: f64,
    /// Text placed inside the band where no curve passes.
    pub label: String,
    /// Colour of the band (drawn at 16 % opacity) and of its label.
    pub colour: Rgb,
}

/// A text placed at data coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// Abscissa of the marked point, in x-axis units.
    pub x: f64,
    /// Ordinate of the marked point, in y-axis units.
    pub y: f64,
    /// The text shown beside the point.
    pub text: String,
    /// Pixel offset of the text's top below the point (negative: above).
    pub dy: i32,
}

/// One panel of a figure.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Panel title.
    pub title: String,
    /// X-axis label with unit.
    pub x_label: String,
    /// Y-axis label with unit.
    pub y_label: String,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Curves.
    pub series: Vec<Series>,
    /// X range; from the data when `None`. Also the band from which the y range is taken.
    pub x_range: Option<(f64, f64)>,
    /// Y range; from the data when `None`.
    pub y_range: Option<(f64, f64)>,
    /// Log y axis: lowest value shown, in decades below the largest (e.g. 6 for a PSD).
    pub floor_decades: Option<f64>,
    /// Labelled y ticks replacing the automatic ones (e.g. phase every 90°).
    pub y_ticks: Option<Vec<f64>>,
    /// Labelled x ticks replacing the automatic ones (e.g. whole run numbers).
    pub x_ticks: Option<Vec<f64>>,
    /// Reference lines.
    pub rules: Vec<Rule>,
    /// Shaded ranges, drawn under the curves.
    pub spans: Vec<Span>,
    /// Texts at data coordinates.
    pub notes: Vec<Note>,
    /// A line of small text under the title (e.g. "showing 12 of 42 curves").
    pub subtitle: Option<String>,
    /// The colour bar of curves coloured by value, drawn right of the panel.
    pub colour_bar: Option<ColourBar>,
    /// Legend in the lower right corner instead of the upper right.
    pub legend_low: bool,
}
/// (lo, hi) of finite `values` (> 0 on a log axis), padded; a fixed default when there are none.
fn data_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return if log { (0.1, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        if hi <= lo {
            return (lo / 2.0, hi * 2.0);
        }
        (lo / 1.15, hi * 1.15)
    } else {
        if hi <= lo {
            let d = lo.abs().max(1.0) * 0.5;
            return (lo - d, hi + d);
        }
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

impl Chart {
    /// The x and y ranges drawn: the explicit ones, else the data's (y from the points inside the
    /// x range, floored on a log axis), bars reaching down to the axis.
    pub fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let x = self.x_range.unwrap_or_else(|| {
            let xs = self.series.iter().flat_map(|s| {
                let r = match s.style {
                    Style::Bars { ratio } => ratio,
                    _ => 1.0,
                };
                s.x.iter().flat_map(move |x| [x / r, x * r])
            });
            let (lo, hi) = data_range(xs, self.log_x);
            if self.log_x {
                // Curves end at the axis; the padding is only for points and bars.
                let raw = data_range(self.series.iter().flat_map(|s| s.x.iter().copied()), true);
                (raw.0.max(lo) * 1.0, raw.1.min(hi))
            } else {
                (lo, hi)
            }
        });
        let y = self.y_range.unwrap_or_else(|| {
            let ys = self.series.iter().flat_map(|s| {
                s.x.iter()
                    .zip(&s.y)
                    .filter(|(xv, _)| **xv >= x.0 && **xv <= x.1)
                    .map(|(_, y)| *y)
            });
            let (mut lo, hi) = data_range(ys, self.log_y);
            if self.log_y
                && let Some(d) = self.floor_decades
            {
                lo = lo.max(hi / 10f64.powf(d));
            }
            if !self.log_y
                && self
                    .series
                    .iter()
                    .any(|s| matches!(s.style, Style::Bars { .. }))
            {
                lo = lo.min(0.0);
            }
            (lo, hi)
        });
        (x, y)
    }

    /// The labelled ticks of (x, y) as drawn.
    pub fn ticks(&self) -> (Vec<f64>, Vec<f64>) {
        let ((x0, x1), (y0, y1)) = self.ranges();
        let t = |lo, hi, log| {
            if log {
                axis::log_ticks(lo, hi).0
            } else {
                axis::linear_ticks(lo, hi)
            }
        };
        let y = self
            .y_ticks
            .clone()
            .unwrap_or_else(|| t(y0, y1, self.log_y));
        let x = self
            .x_ticks
            .clone()
            .unwrap_or_else(|| t(x0, x1, self.log_x));
        (x, y)
    }
}
/// A long signal reduced to at most `buckets` × 2 points: the minimum and maximum of each of
/// `buckets` equal slices, in time order. A plot at a few hundred pixels shows the same envelope
/// as the full signal, in a file a thousand times smaller (plotters draws every point given).
pub fn envelope(t: &[f64], y: &[f64], buckets: usize) -> (Vec<f64>, Vec<f64>) {
    let n = t.len().min(y.len());
    if n <= 2 * buckets.max(1) {
        return (t[..n].to_vec(), y[..n].to_vec());
    }
    let (mut tx, mut yx) = (
        Vec::with_capacity(2 * buckets),
        Vec::with_capacity(2 * buckets),
    );
    for b in 0..buckets {
        let (i0, i1) = (
            b * n / buckets,
            ((b + 1) * n / buckets).max(b * n / buckets + 1),
        );
        let slice = &y[i0..i1];
        let (mut lo, mut hi) = (0, 0);
        for (i, v) in slice.iter().enumerate() {
            if *v < slice[lo] {
                lo = i;
            }
            if *v > slice[hi] {
                hi = i;
            }
        }
        for i in if lo <= hi { [lo, hi] } else { [hi, lo] } {
            tx.push(t[i0 + i]);
            yx.push(slice[i]);
        }
    }
    (tx, yx)
}
