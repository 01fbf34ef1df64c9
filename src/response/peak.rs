//! Peaks of sampled response magnitudes.

/// A resonance peak: frequency in Hz and magnitude in the response's unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peak {
    /// Frequency of the peak in Hz.
    pub freq_hz: f64,
    /// Magnitude at the peak.
    pub value: f64,
}

/// The global maximum of `mag` over `freq`, refined by a parabola through the three samples around
/// it (exact for a locally quadratic curve; the grid should resolve the peak).
pub fn global_peak(freq: &[f64], mag: &[f64]) -> Option<Peak> {
    let (i, _) = mag
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_finite())
        .max_by(|a, b| a.1.total_cmp(b.1))?;
    Some(refine(freq, mag, i))
}

/// Every interior local maximum of `mag`, refined, in frequency order.
pub fn local_peaks(freq: &[f64], mag: &[f64]) -> Vec<Peak> {
    (1..mag.len().saturating_sub(1))
        .filter(|&i| mag[i] > mag[i - 1] && mag[i] >= mag[i + 1])
        .map(|i| refine(freq, mag, i))
        .collect()
}

fn refine(freq: &[f64], mag: &[f64], i: usize) -> Peak {
    if i == 0 || i + 1 >= mag.len() {
        return Peak {
            freq_hz: freq[i],
            value: mag[i],
        };
    }
    let (x0, x1, x2) = (freq[i - 1], freq[i], freq[i + 1]);
    let (y0, y1, y2) = (mag[i - 1], mag[i], mag[i + 1]);
    // Parabola through three (possibly unequally spaced) points.
    let d = (x0 - x1) * (x0 - x2) * (x1 - x2);
    let a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / d;
    let b = (x2 * x2 * (y0 - y1) + x1 * x1 * (y2 - y0) + x0 * x0 * (y1 - y2)) / d;
    if a >= 0.0 || !a.is_finite() {
        return Peak {
            freq_hz: x1,
            value: y1,
        };
    }
    let xv = -b / (2.0 * a);
    let c = y1 - a * x1 * x1 - b * x1;
    Peak {
        freq_hz: xv.clamp(x0, x2),
        value: (a * xv * xv + b * xv + c).max(y1),
    }
}
