//! Heat maps (a value over two axes, e.g. |T| over frequency × swept parameter), PNG or SVG, drawn
//! with [`crate::plot`]: viridis from dark purple (lowest) to yellow (highest), with a colour bar
//! labelled with the quantity and its unit, and clean tick labels.

use crate::error::{Error, Result};
use crate::io::atomic::Overwrite;
use crate::plot::{ColourBar, axis};
use plotters::prelude::*;
use std::path::Path;

/// A value `z[iy][ix]` on the cell centres `x[ix]`, `y[iy]` (increasing, possibly uneven).
#[derive(Debug, Clone, Default)]
pub struct HeatMap {
    /// Title.
    pub title: String,
    /// X-axis label with unit.
    pub x_label: String,
    /// Y-axis label with unit.
    pub y_label: String,
    /// Label of the coloured quantity with unit.
    pub z_label: String,
    /// Cell centres along x.
    pub x: Vec<f64>,
    /// Cell centres along y.
    pub y: Vec<f64>,
    /// Values, one row per y.
    pub z: Vec<Vec<f64>>,
}

fn edges(c: &[f64]) -> Vec<f64> {
    match c.len() {
        0 => vec![],
        1 => vec![
            c[0] - 0.5 * c[0].abs().max(1.0),
            c[0] + 0.5 * c[0].abs().max(1.0),
        ],
        n => {
            let mut e = vec![c[0] - 0.5 * (c[1] - c[0])];
            e.extend(c.windows(2).map(|w| 0.5 * (w[0] + w[1])));
            e.push(c[n - 1] + 0.5 * (c[n - 1] - c[n - 2]));
            e
        }
    }
}

fn render<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    h: &HeatMap,
) -> std::result::Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (xe, ye) = (edges(&h.x), edges(&h.y));
    let finite = h.z.iter().flatten().copied().filter(|v| v.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    let bar = ColourBar {
        label: h.z_label.clone(),
        lo: if lo.is_finite() { lo } else { 0.0 },
        hi: if hi.is_finite() { hi } else { 1.0 },
    };
    let (w, _) = root.dim_in_pixel();
    let (main, strip) = root.split_horizontally(w.saturating_sub(120));
    bar.draw(&strip)?;
    let (x0, x1, y0, y1) = (xe[0], xe[xe.len() - 1], ye[0], ye[ye.len() - 1]);
    let (xt, yt) = (axis::linear_ticks(x0, x1), axis::linear_ticks(y0, y1));
    let (xn, yn) = (axis::Notation::of(&xt), axis::Notation::of(&yt));
    let mut ctx = ChartBuilder::on(&main)
        .caption(&h.title, ("sans-serif", 17))
        .margin(12)
        .x_label_area_size(42)
        .y_label_area_size(80)
        .build_cartesian_2d(
            axis::ticked(x0..x1, xt, vec![]),
            axis::ticked(y0..y1, yt, vec![]),
        )
        .map_err(e)?;
    ctx.configure_mesh()
        .disable_mesh()
        .x_desc(h.x_label.as_str())
        .y_desc(h.y_label.as_str())
        .x_label_formatter(&|v| xn.label(*v))
        .y_label_formatter(&|v| yn.label(*v))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .draw()
        .map_err(e)?;
    let cells = h.z.iter().enumerate().flat_map(|(iy, row)| {
        let (xe, ye, bar) = (&xe, &ye, &bar);
        row.iter().enumerate().map(move |(ix, v)| {
            // A cell without a value is grey, not the low end of the scale.
            let (r, g, b) = if v.is_finite() {
                bar.colour(*v)
            } else {
                (200, 200, 200)
            };
            Rectangle::new(
                [(xe[ix], ye[iy]), (xe[ix + 1], ye[iy + 1])],
                RGBColor(r, g, b).filled(),
            )
        })
    });
    ctx.draw_series(cells).map_err(e)?;
    root.present().map_err(e)
}

/// Draws `h` to `path` (`.png` or `.svg`), written beside the target and renamed when complete.
pub fn draw(h: &HeatMap, path: &Path, overwrite: Overwrite) -> Result<()> {
    if h.x.is_empty()
        || h.y.is_empty()
        || h.z.len() != h.y.len()
        || h.z.iter().any(|r| r.len() != h.x.len())
    {
        return Err(Error::parameter("heat map", "empty or ragged grid"));
    }
    crate::plot::write_figure(&Drawing(h), (960, 560), path, overwrite)
}

struct Drawing<'a>(&'a HeatMap);

impl crate::plot::Figure for Drawing<'_> {
    fn render<DB: DrawingBackend>(
        &self,
        root: DrawingArea<DB, plotters::coord::Shift>,
    ) -> std::result::Result<(), String> {
        render(root, self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_bracket_uneven_centres() {
        assert_eq!(edges(&[1.0, 2.0, 4.0]), vec![0.5, 1.5, 3.0, 5.0]);
    }

    #[test]
    fn draws_svg_and_refuses_ragged_grids() {
        let dir = tempfile::tempdir().unwrap();
        let mut h = HeatMap {
            x: vec![1.0, 2.0],
            y: vec![10.0, 20.0, 30.0],
            z: vec![vec![0.0, 1.0], vec![2.0, 3.0], vec![4.0, 5.0]],
            ..HeatMap::default()
        };
        let p = dir.path().join("h.svg");
        draw(&h, &p, Overwrite::Refuse).unwrap();
        assert!(std::fs::read_to_string(&p).unwrap().contains("<svg"));
        h.z.pop();
        assert!(draw(&h, &dir.path().join("g.svg"), Overwrite::Refuse).is_err());
    }
}
