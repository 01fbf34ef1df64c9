//! The Welch auto-spectrum fed block by block.

use super::{Spectrum, Welch};
use crate::error::Result;

/// A Welch auto-spectrum fed in blocks of any size: segment `s` is transformed as soon as samples
/// `s·step … s·step + N` have arrived, so memory is one segment whatever the duration, and the
/// result equals [`Welch::psd`] of the concatenated blocks bit for bit.
#[derive(Debug, Clone)]
pub struct PsdAccumulator {
    /// The last N samples received, oldest first once full.
    ring: Vec<f64>,
    /// Contiguous copy of the current segment.
    segment: Vec<f64>,
    /// Samples received.
    received: usize,
    /// Sample index at which the next segment starts.
    next_start: usize,
    acc: Vec<f64>,
    count: usize,
}

impl PsdAccumulator {
    /// An empty accumulator for the segmentation of `welch`.
    pub fn new(welch: &Welch) -> Self {
        PsdAccumulator {
            ring: vec![0.0; welch.n],
            segment: vec![0.0; welch.n],
            received: 0,
            next_start: 0,
            acc: vec![0.0; welch.n / 2 + 1],
            count: 0,
        }
    }

    /// Appends `x` and transforms every segment it completes.
    pub fn push(&mut self, welch: &mut Welch, x: &[f64]) {
        let n = welch.n;
        for &v in x {
            self.ring[self.received % n] = v;
            self.received += 1;
            if self.received == self.next_start + n {
                let head = self.received % n;
                let (newer, older) = self.ring.split_at(head);
                self.segment[..older.len()].copy_from_slice(older);
                self.segment[older.len()..].copy_from_slice(newer);
                welch.transform(&self.segment, false);
                for (a, c) in self.acc.iter_mut().zip(&welch.out_x) {
                    *a += c.norm_sqr();
                }
                self.count += 1;
                self.next_start += welch.step;
            }
        }
    }

    /// The averaged density; an error when not even one segment was completed.
    pub fn finish(mut self, welch: &Welch) -> Result<Spectrum> {
        if self.count == 0 {
            welch.segment_count(self.received)?;
        }
        for (k, a) in self.acc.iter_mut().enumerate() {
            *a *= welch.one_sided_scale(k) / self.count as f64;
        }
        Ok(Spectrum {
            freq_hz: welch.frequencies(),
            density: self.acc,
            df_hz: welch.df_hz(),
            segments: self.count,
        })
    }
}
