//! Where a chart's texts go: every label (legend, shaded range, reference line, note) is put at
//! the first of its candidate places that covers no curve, bar, marker or earlier label, else at
//! the one that covers least. Pure pixel geometry, so every chart gets the same rule and the rule
//! is tested without drawing.

/// An axis-aligned box in pixels, `x0 ≤ x1`, `y0 ≤ y1` (y down).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Rect {
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
}

impl Rect {
    /// The box from `(x, y)` (top left), `w` wide and `h` high.
    pub fn at(x: i32, y: i32, w: i32, h: i32) -> Rect {
        Rect {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + h,
        }
    }

    /// The box through two corners in any order.
    pub fn spanning((ax, ay): (i32, i32), (bx, by): (i32, i32)) -> Rect {
        Rect {
            x0: ax.min(bx),
            y0: ay.min(by),
            x1: ax.max(bx),
            y1: ay.max(by),
        }
    }

    /// The box grown by `m` pixels on every side.
    pub fn grown(self, m: i32) -> Rect {
        Rect {
            x0: self.x0 - m,
            y0: self.y0 - m,
            x1: self.x1 + m,
            y1: self.y1 + m,
        }
    }

    fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    fn inside(&self, o: &Rect) -> bool {
        self.x0 >= o.x0 && self.x1 <= o.x1 && self.y0 >= o.y0 && self.y1 <= o.y1
    }

    /// Whether the segment `a`–`b` passes through the box (Liang–Barsky clipping: the segment's
    /// parameter interval inside each of the four half-planes is intersected).
    fn crossed_by(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-dx, a.0 - self.x0 as f64),
            (dx, self.x1 as f64 - a.0),
            (-dy, a.1 - self.y0 as f64),
            (dy, self.y1 as f64 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }
}

/// What a label must not cover: the pixels of the curves (segments) and of bars, markers and the
/// labels already placed (boxes).
#[derive(Debug, Clone, Default)]
pub(crate) struct Obstacles {
    segments: Vec<((f64, f64), (f64, f64))>,
    boxes: Vec<Rect>,
}

impl Obstacles {
    /// A curve through `points` (pixels).
    pub fn polyline(&mut self, points: &[(i32, i32)]) {
        let f = |(x, y): (i32, i32)| (x as f64, y as f64);
        self.segments
            .extend(points.windows(2).map(|w| (f(w[0]), f(w[1]))));
        if let [p] = points {
            self.boxes.push(Rect::at(p.0 - 1, p.1 - 1, 2, 2));
        }
    }

    /// A filled box (a bar, a marker, a placed label).
    pub fn add(&mut self, r: Rect) {
        self.boxes.push(r);
    }

    /// How much of the chart `r` would cover: the segments through it plus the boxes it overlaps.
    pub fn cost(&self, r: &Rect) -> usize {
        self.segments
            .iter()
            .filter(|(a, b)| r.crossed_by(*a, *b))
            .count()
            + self.boxes.iter().filter(|b| r.overlaps(b)).count()
    }

    /// The index of the first of `candidates` that lies inside `within` and covers nothing, else
    /// of the one inside `within` that covers least (the first of equals), else 0. `None` when
    /// there are no candidates.
    pub fn best(&self, candidates: &[Rect], within: &Rect) -> Option<usize> {
        let mut best: Option<(usize, usize)> = None;
        for (i, c) in candidates.iter().enumerate() {
            if !c.inside(within) {
                continue;
            }
            let cost = self.cost(c);
            if cost == 0 {
                return Some(i);
            }
            if best.is_none_or(|(_, b)| cost < b) {
                best = Some((i, cost));
            }
        }
        best.map(|(i, _)| i)
            .or_else(|| (!candidates.is_empty()).then_some(0))
    }
}

/// The pixel box of a one-line text `w` × `size` px whose anchor `(x, y)` is its left end at mid
/// height, as drawn by either backend: plotters' bitmap text (ab_glyph) puts the baseline
/// 0.1·size below a centre anchor, its SVG text 0.27·size below it (`dy="0.5ex"`); the box holds
/// both, with the cap height above and the descenders below. A browser's sans-serif may be wider
/// than the DejaVu Sans the width was measured with: 8 % is added.
pub(crate) fn text_box(x: i32, y: i32, w: u32, size: u32) -> Rect {
    let s = size as f64;
    Rect {
        x0: x,
        y0: y - (0.68 * s).round() as i32,
        x1: x + (w as f64 * 1.08).ceil() as i32,
        y1: y + (0.52 * s).round() as i32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_crossing_boxes() {
        let r = Rect::at(10, 10, 10, 10);
        // Through, along an edge inside, ending inside, missing, and passing a corner.
        assert!(r.crossed_by((0.0, 15.0), (30.0, 15.0)));
        assert!(r.crossed_by((15.0, 0.0), (15.0, 12.0)));
        assert!(!r.crossed_by((0.0, 0.0), (30.0, 5.0)));
        assert!(!r.crossed_by((0.0, 25.0), (5.0, 40.0)));
        assert!(!r.crossed_by((0.0, 21.0), (9.0, 30.0)));
        assert!(r.crossed_by((5.0, 25.0), (25.0, 5.0)));
    }

    #[test]
    fn the_first_free_candidate_wins() {
        let mut o = Obstacles::default();
        // A rising diagonal from the lower left to the upper right of a 200 × 100 area.
        o.polyline(&[(0, 100), (100, 50), (200, 0)]);
        let area = Rect::at(0, 0, 200, 100);
        let upper_right = Rect::at(140, 5, 55, 30);
        let upper_left = Rect::at(5, 5, 55, 30);
        let lower_right = Rect::at(140, 65, 55, 30);
        // The curve ends in the upper right: the legend goes to the upper left.
        assert_eq!(
            o.best(&[upper_right, upper_left, lower_right], &area),
            Some(1)
        );
        // A box outside the area is never chosen while one inside is.
        let outside = Rect::at(190, 5, 55, 30);
        assert_eq!(o.best(&[outside, upper_right], &area), Some(1));
        // A placed label is an obstacle for the next.
        o.add(upper_left);
        assert_eq!(o.best(&[upper_left, lower_right], &area), Some(1));
        assert_eq!(o.best(&[], &area), None);
    }
}
