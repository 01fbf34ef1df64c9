//! Tick positions and labels. plotters' own key points on a log axis are computed by repeated
//! multiplication and printed with `{}` (`1.0000000000000002e-14`), and it labels a short log range
//! at one or two points only; here every tick is the f64 nearest a short decimal (parsed from its
//! text), so its label is that text. The labels of one axis share one [`Notation`]: all plain
//! decimals or all `m e k`, never `80000` beside `1e5` or `0.001` beside `1e-4`.

use plotters::coord::ranged1d::{AsRangedCoord, DefaultFormatting, KeyPointHint, Ranged};
use std::ops::Range;

/// A plotters coordinate (linear or log) with the ticks computed here. plotters' own
/// `with_key_points` wrapper loses the axis's formatting trait, so a mesh could not be drawn on it;
/// this one keeps the default formatting, which the charts replace by [`label`].
pub struct Ticked<R: Ranged<ValueType = f64>> {
    inner: R,
    major: Vec<f64>,
    minor: Vec<f64>,
}

/// `coord` with labelled ticks `major` and unlabelled grid lines `minor`.
pub fn ticked<C: AsRangedCoord<Value = f64>>(
    coord: C,
    major: Vec<f64>,
    minor: Vec<f64>,
) -> Ticked<C::CoordDescType>
where
    C::CoordDescType: Ranged<ValueType = f64>,
{
    Ticked {
        inner: coord.into(),
        major,
        minor,
    }
}

impl<R: Ranged<ValueType = f64>> Ranged for Ticked<R> {
    type ValueType = f64;
    type FormatOption = DefaultFormatting;

    fn range(&self) -> Range<f64> {
        self.inner.range()
    }

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.major.clone()
        }
    }

    fn axis_pixel_range(&self, limit: (i32, i32)) -> Range<i32> {
        self.inner.axis_pixel_range(limit)
    }
}

/// Largest number of labelled ticks on an axis.
const MAX_TICKS: usize = 9;

/// The f64 nearest `m`·10^`e`, read from its decimal text so that 0.1·10⁻³ is exactly `1e-4`.
fn decimal(m: u32, e: i32) -> f64 {
    format!("{m}e{e}").parse().unwrap_or(f64::NAN)
}

/// Ticks of a log axis over `lo..=hi` (both > 0): `(labelled, unlabelled)`.
///
/// Up to two and a half decades: 1, 2, 5 × 10^k labelled and every integer multiple as a minor tick; up to
/// nine decades: the decades labelled and 2…9 × 10^k minor; wider: every n-th decade labelled so
/// that at most [`MAX_TICKS`] remain, the other decades minor.
pub fn log_ticks(lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return (vec![], vec![]);
    }
    let (e0, e1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let decades = (hi / lo).log10();
    let inside = |v: &f64| *v >= lo * (1.0 - 1e-12) && *v <= hi * (1.0 + 1e-12);
    let all = |ms: &[u32]| -> Vec<f64> {
        (e0..=e1)
            .flat_map(|e| ms.iter().map(move |&m| decimal(m, e)))
            .filter(inside)
            .collect()
    };
    let (major, minor) = if decades <= 2.5 {
        (all(&[1, 2, 5]), all(&[1, 2, 3, 4, 5, 6, 7, 8, 9]))
    } else if decades <= MAX_TICKS as f64 {
        (all(&[1]), all(&[2, 3, 4, 5, 6, 7, 8, 9]))
    } else {
        let step = (decades / MAX_TICKS as f64).ceil() as i32;
        let every: Vec<f64> = all(&[1]);
        let major = every
            .iter()
            .copied()
            .filter(|v| (v.log10().round() as i32).rem_euclid(step) == 0)
            .collect();
        (major, every)
    };
    let major: Vec<f64> = if major.len() < 2 {
        // Less than a decade without a 1-2-5 value: label the ends.
        vec![lo, hi]
    } else {
        major
    };
    let minor = minor
        .into_iter()
        .filter(|v| !major.iter().any(|m| (m - v).abs() <= 1e-12 * v))
        .collect();
    (major, minor)
}

/// Ticks of a linear axis over `lo..=hi`: multiples of the 1, 2 or 5 × 10^k step that gives at
/// most [`MAX_TICKS`] ticks.
pub fn linear_ticks(lo: f64, hi: f64) -> Vec<f64> {
    if !(hi > lo && lo.is_finite() && hi.is_finite()) {
        return vec![];
    }
    let raw = (hi - lo) / (MAX_TICKS as f64 - 1.0);
    let e = raw.log10().floor() as i32;
    let (m, e) = [1, 2, 5, 10]
        .iter()
        .map(|&m| if m == 10 { (1, e + 1) } else { (m, e) })
        .find(|&(m, e)| decimal(m, e) >= raw * (1.0 - 1e-9))
        .unwrap_or((1, e + 1));
    let step = decimal(m, e);
    let (k0, k1) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
    (k0..=k1)
        .map(|k| {
            // k·step rebuilt from its decimal text, so 3 × 0.1 is 0.3 and not 0.30000000000000004.
            let v = k as f64 * step;
            label(v).parse::<f64>().unwrap_or(v)
        })
        .collect()
}

/// How every tick label of one axis is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Notation {
    /// Plain decimals (`0.005`, `150000`): every non-zero tick within 10⁻³ ≤ |v| < 10⁶.
    Plain,
    /// `m e k` (`5e4`, `1.5e5`, `1e-4`) for every tick, when any lies outside that range.
    Exponent,
}

impl Notation {
    /// The one notation of an axis with labelled ticks `ticks`: plain when every finite,
    /// non-zero tick has at most six integer digits and its first significant digit at most
    /// three places after the point, else exponent for all of them.
    pub fn of(ticks: &[f64]) -> Notation {
        let plain = ticks
            .iter()
            .filter(|v| v.is_finite() && v.abs() >= 1e-300)
            .all(|v| (1e-3..1e6).contains(&v.abs()));
        if plain {
            Notation::Plain
        } else {
            Notation::Exponent
        }
    }

    /// A short label of tick value `v`: at most four significant digits, no float noise, `0`
    /// for zero and never `-0`.
    pub fn label(self, v: f64) -> String {
        if !v.is_finite() {
            return String::new();
        }
        if v == 0.0 || v.abs() < 1e-300 {
            return "0".into();
        }
        let a = v.abs();
        match self {
            Notation::Plain => {
                // Fewest decimals that give back v to 4 significant digits.
                let digits = (4 - 1 - a.log10().floor() as i32).max(0) as usize;
                let text = format!("{v:.digits$}");
                let text = if text.contains('.') {
                    text.trim_end_matches('0').trim_end_matches('.').to_string()
                } else {
                    text
                };
                if text == "-0" { "0".into() } else { text }
            }
            Notation::Exponent => {
                let e = a.log10().floor() as i32;
                let m = v / 10f64.powi(e);
                let mut mt = format!("{m:.3}");
                mt = mt.trim_end_matches('0').trim_end_matches('.').to_string();
                // Rounding can reach 10 (9.9996 → "10.000").
                if mt == "10" || mt == "-10" {
                    return format!("{}e{}", if v < 0.0 { "-1" } else { "1" }, e + 1);
                }
                format!("{mt}e{e}")
            }
        }
    }
}

/// A short decimal label of one value on its own (a tick without its axis): plain within
/// 10⁻³ ≤ |v| < 10⁵, else `e` notation (`1e-14`, `2.5e6`); see [`Notation::label`].
pub fn label(v: f64) -> String {
    let a = v.abs();
    if (1e5..1e6).contains(&a) {
        Notation::Exponent.label(v)
    } else {
        Notation::of(&[v]).label(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_are_short_decimals() {
        // Expected texts written by hand.
        assert_eq!(label(1.0000000000000002e-14), "1e-14");
        assert_eq!(label(0.00010000000000000002), "1e-4");
        assert_eq!(label(0.30000000000000004), "0.3");
        assert_eq!(label(-0.0), "0");
        assert_eq!(label(60.00000000000001), "60");
        assert_eq!(label(2500000.0), "2.5e6");
        assert_eq!(label(0.315), "0.315");
        assert_eq!(label(-180.0), "-180");
        assert_eq!(label(1234.6), "1235");
    }

    #[test]
    fn one_notation_per_axis() {
        // Expected texts written by hand: a stiffness axis, a PSD axis, a plain axis.
        let n = Notation::of(&[50000.0, 100000.0, 150000.0, 200000.0]);
        let t: Vec<String> = [50000.0, 100000.0, 150000.0, 200000.0]
            .iter()
            .map(|v| n.label(*v))
            .collect();
        assert_eq!(t, ["50000", "100000", "150000", "200000"]);
        let ticks = [1e-4, 1e-3, 1e-2, 0.1];
        let n = Notation::of(&ticks);
        let t: Vec<String> = ticks.iter().map(|v| n.label(*v)).collect();
        assert_eq!(t, ["1e-4", "1e-3", "1e-2", "1e-1"]);
        let ticks = [0.0, 2e5, 4e5, 6e5, 8e5, 1e6];
        let n = Notation::of(&ticks);
        let t: Vec<String> = ticks.iter().map(|v| n.label(*v)).collect();
        assert_eq!(t, ["0", "2e5", "4e5", "6e5", "8e5", "1e6"]);
        assert_eq!(Notation::of(&[0.0, 0.5, 1.0]), Notation::Plain);
    }

    #[test]
    fn log_ticks_label_decades_and_sub_decades() {
        let (major, minor) = log_ticks(0.2, 100.0);
        let text: Vec<String> = major.iter().map(|v| label(*v)).collect();
        assert_eq!(text, ["1", "10", "100"]);
        assert!(minor.contains(&0.2) && minor.contains(&30.0));
        let (major, _) = log_ticks(0.5, 20.0);
        let text: Vec<String> = major.iter().map(|v| label(*v)).collect();
        assert_eq!(text, ["0.5", "1", "2", "5", "10", "20"]);
        let (major, _) = log_ticks(1e-14, 1.0);
        assert!(major.len() <= MAX_TICKS && major.len() >= 4);
        assert!(major.iter().all(|v| !label(*v).contains("0000")));
        // Less than a 1-2-5 step: the ends are labelled.
        assert_eq!(log_ticks(1.1, 1.9).0, vec![1.1, 1.9]);
    }

    #[test]
    fn linear_ticks_are_round() {
        assert_eq!(
            linear_ticks(-180.0, 180.0),
            [-150.0, -100.0, -50.0, 0.0, 50.0, 100.0, 150.0]
        );
        let t = linear_ticks(0.0, 0.9);
        assert_eq!(t, [0.0, 0.2, 0.4, 0.6, 0.8]);
        assert_eq!(
            linear_ticks(0.25, 1.0),
            [0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]
        );
    }
}
