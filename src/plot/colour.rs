//! Colours: the viridis map (plotters' `ViridisRGB`, the matplotlib default, perceptually uniform
//! and readable with colour-vision deficiency) for values, a fixed qualitative palette for curves,
//! and the colour bar that states what a colour means.

use super::axis;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};

/// An RGB colour.
pub type Rgb = (u8, u8, u8);

/// Curve colours (Okabe–Ito, distinguishable with colour-vision deficiency), used in order.
pub const PALETTE: [Rgb; 8] = [
    (0, 114, 178),
    (213, 94, 0),
    (0, 158, 115),
    (204, 121, 167),
    (86, 180, 233),
    (230, 159, 0),
    (0, 0, 0),
    (240, 228, 66),
];

/// The `i`-th palette colour (cycling).
pub fn pick(i: usize) -> Rgb {
    PALETTE[i % PALETTE.len()]
}

/// Viridis at `t` in 0…1 (clamped; NaN gives the low end).
pub fn viridis(t: f64) -> Rgb {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let c: RGBColor = ViridisRGB.get_color(t as f32);
    (c.0, c.1, c.2)
}

/// What a colour means: `label` (with unit) from `lo` to `hi`.
#[derive(Debug, Clone, PartialEq)]
pub struct ColourBar {
    /// Quantity and unit, e.g. `link.cushion.k [N/m]`.
    pub label: String,
    /// Value at the dark end.
    pub lo: f64,
    /// Value at the bright end.
    pub hi: f64,
}

impl ColourBar {
    /// The colour of `v`.
    pub fn colour(&self, v: f64) -> Rgb {
        let span = self.hi - self.lo;
        viridis(if span > 0.0 {
            (v - self.lo) / span
        } else {
            0.5
        })
    }

    /// Draws the bar with labelled ticks on `area` (a narrow strip right of a chart).
    pub fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let (lo, hi) = if self.hi > self.lo {
            (self.lo, self.hi)
        } else {
            (self.lo - 0.5, self.lo + 0.5)
        };
        let ticks = axis::linear_ticks(lo, hi);
        let notation = axis::Notation::of(&ticks);
        let mut ctx = ChartBuilder::on(area)
            .margin_top(40)
            .margin_bottom(48)
            .margin_right(4)
            .y_label_area_size(0)
            .right_y_label_area_size(62)
            .build_cartesian_2d(0.0..1.0, axis::ticked(lo..hi, ticks, vec![]))
            .map_err(|e| e.to_string())?;
        ctx.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(self.label.as_str())
            .y_label_formatter(&|v| notation.label(*v))
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(|e| e.to_string())?;
        const STEPS: usize = 96;
        let dy = (hi - lo) / STEPS as f64;
        ctx.draw_series((0..STEPS).map(|i| {
            let y = lo + i as f64 * dy;
            let (r, g, b) = viridis((i as f64 + 0.5) / STEPS as f64);
            Rectangle::new([(0.0, y), (1.0, y + dy)], RGBColor(r, g, b).filled())
        }))
        .map_err(|e| e.to_string())?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_runs_from_purple_to_yellow() {
        // End colours of matplotlib's viridis (#440154, #fde725), within plotters' rounding.
        let (r, g, b) = viridis(0.0);
        assert!(r == 68 && g <= 2 && b == 84);
        let (r, g, b) = viridis(1.0);
        assert!(r >= 250 && g >= 230 && b <= 40);
        assert_eq!(viridis(f64::NAN), viridis(0.0));
    }
}
