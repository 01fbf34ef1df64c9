//! Acquisition faults in a sampled channel, found before any spectrum is taken: values a logger
//! held (a dropout repeats the last sample), values held at the channel's range limit (clipping) and
//! isolated spikes (a transmission or ADC error in one or two samples).
//!
//! A continuous vibration signal sampled by an ADC repeats a value exactly only by quantisation,
//! with a probability p per sample pair that the channel itself shows (pairs of equal samples); a
//! run of k equal samples then has probability ≈ p^(k−1) per start, so a run whose expected count
//! over the record, N·p^(k−1), is below [`HELD_FALSE_ALARMS`] is a held value, not a coincidence.
//! A spike is a sample whose distance from the median of its four neighbours is many times that
//! distance's robust spread (1.4826 × its median absolute value, in blocks of
//! [`SPREAD_BLOCK_S`]): a band-limited signal sampled above twice its bandwidth moves smoothly
//! from sample to sample, so one or two samples far off their neighbours did not come from the
//! transducer (Hampel identifier; Pearson, *Mining Imperfect Data*, 2005, §4.3).
//!
//! Time stamps off the uniform grid (a logger's gaps) are refused by the readers
//! ([`crate::io::input`]), which name the sample.

use std::ops::Range;

/// Expected number of chance repeats, over the whole record, below which a run of equal samples
/// is held rather than quantisation (a false alarm in one record of a hundred).
pub const HELD_FALSE_ALARMS: f64 = 0.01;
/// Fewest equal samples in a row that can be held: two equal samples are a quantisation step.
pub const HELD_MIN: usize = 3;
/// Fewest samples at a channel's extreme value that can mark it as clipped: a continuous signal
/// reaches its maximum once, and even a 1e-4 m/s² CSV resolution repeats a peak value only a few
/// times in a long run; an amplifier or ADC at its rail holds it for whole flat tops.
pub const CLIPPED_SAMPLES: usize = 10;
/// How many times more samples a rail holds than the code next inward. A smooth peak that reaches
/// a depth ε into its top code of step q spends 2√(2ε/a) there against 2(√(2(ε+q)/a) − √(2ε/a))
/// crossing the next code (a the curvature), at most 1/(√2 − 1) ≈ 2.4 times as long, and other
/// peaks cross the inner code only; a rail collects every sample beyond it.
pub const CLIPPED_PILE_UP: f64 = 3.0;
/// Fewest separate visits to a rail: clipping flattens every peak that reaches the range, where a
/// coarsely quantised channel can dwell on its top code at one or two slow peaks.
pub const CLIPPED_VISITS: usize = 3;
/// Least distance of a rail inside a channel's range from its median, in robust standard
/// deviations: a range limit lies at the distribution's edge.
pub const CLIPPED_EDGE_SIGMAS: f64 = 1.5;
/// Distance from the neighbours' median, in robust standard deviations, above which a sample is a
/// spike: ≈ 1e−22 for a Gaussian sample, so a clean record of any length has none.
pub const SPIKE_SIGMAS: f64 = 12.0;
/// How many times the largest neighbour difference 3–8 samples away a spike's must be: a real
/// event (a shock, a ring) moves its neighbours too.
pub const SPIKE_ALONE: f64 = 4.0;
/// A spike stands this many times the signal's own r.m.s. (in its block) off its neighbours: far
/// outside the local distribution of values, not only off the local curve (a law's kink in an
/// oversampled acceleration is off the curve by a fraction of the r.m.s.).
pub const SPIKE_LEVEL: f64 = 3.0;
/// Share of a spike's height by which the lines through its two neighbours on either side must
/// both miss it.
pub const SPIKE_NEITHER_SIDE: f64 = 0.5;
/// Most consecutive samples a spike spans: longer excursions have the shape of a real event.
pub const SPIKE_MAX_SAMPLES: usize = 2;
/// Length of the blocks in which the spread of the neighbour differences is estimated, s: short
/// enough that a rough stretch of a road run gets its own scale, long enough for a stable median.
pub const SPREAD_BLOCK_S: f64 = 1.0;

/// What went wrong in a stretch of samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FaultKind {
    /// The same value repeated longer than quantisation explains (a logger dropout).
    Held,
    /// The channel's extreme value repeated (the transducer or the ADC at its range).
    Clipped,
    /// One or two samples far outside their neighbours.
    Spike,
}

impl FaultKind {
    /// Words for reports.
    pub fn describe(self) -> &'static str {
        match self {
            FaultKind::Held => "held value (a dropout?)",
            FaultKind::Clipped => "clipped at the channel's extreme",
            FaultKind::Spike => "spike",
        }
    }
}

/// One faulty stretch of one channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Fault {
    /// What it is.
    pub kind: FaultKind,
    /// The samples it covers.
    pub samples: Range<usize>,
}

/// Every fault of channel `x`, in sample order.
pub fn find(x: &[f64], fs: f64) -> Vec<Fault> {
    let (runs, long, spikes) = survey(x, fs);
    let rails: Vec<f64> = rails(x, &spikes, &long)
        .into_iter()
        .map(|(v, _)| v)
        .collect();
    let mut out = held(x, &runs, long, &rails);
    out.extend(spikes);
    out.sort_by_key(|f| f.samples.start);
    out
}

/// The values at which channel `x` (sampled at `fs`) is clipped, with the number of samples at
/// each (see [`rails`]).
pub fn clipping(x: &[f64], fs: f64) -> Vec<(f64, usize)> {
    let (_, long, spikes) = survey(x, fs);
    rails(x, &spikes, &long)
}

/// The runs of equal samples of `x`, those too long for chance, and its spikes.
fn survey(x: &[f64], fs: f64) -> (Vec<Range<usize>>, Vec<Range<usize>>, Vec<Fault>) {
    let runs = equal_runs(x);
    let long = long_runs(x.len(), &runs);
    let spikes = spikes(x, fs, &long);
    (runs, long, spikes)
}

/// The runs of equal samples `runs` (of a record of `len` samples) too long for quantisation to
/// repeat them by chance (see the module's statistics), before their exit and level are looked at.
fn long_runs(len: usize, runs: &[Range<usize>]) -> Vec<Range<usize>> {
    let count = |k: usize| runs.iter().filter(|r| r.len() == k).count() as f64;
    let (c2, c3) = (count(2), count(3));
    let n = len.max(2) as f64;
    // Expected number of chance runs of ≥ k equal samples. With few repeats, from the pair
    // probability p = c₂/N: N·p^(k−1). With many (a quantised, oversampled channel lingers at its
    // turning points), from the geometric tail the run lengths themselves show, r = c₃/c₂:
    // c₂·r^(k−2). Runs of exactly two and three are counted, so a few long held stretches do not
    // inflate the estimate they are judged by.
    let expected = |k: usize| {
        if c2 >= 10.0 {
            c2 * (c3 / c2).min(0.9).powi(k as i32 - 2)
        } else {
            n * (c2 / (n - 1.0)).powi(k as i32 - 1)
        }
    };
    runs.iter()
        .filter(|r| r.len() >= HELD_MIN && expected(r.len()) < HELD_FALSE_ALARMS)
        .cloned()
        .collect()
}

/// The held and clipped stretches of `x`. Every run of equal samples at a rail (see [`rails`])
/// is [`FaultKind::Clipped`]. A long run elsewhere (`long`) is [`FaultKind::Held`] unless the
/// channel leaves it for a neighbouring code: a quantised signal lingers on a code while it moves
/// less than one step, and leaves it for the code next to it, where a logger that held a value
/// while the signal moved on resumes wherever the signal has got to. A dropout on a signal that
/// moved less than one code meanwhile is indistinguishable from quantisation, and lost nothing. A
/// run the record ends in has no exit: it is held when it is longer than any the channel left for
/// a neighbouring code (the longest dwell its quantisation shows).
fn held(x: &[f64], runs: &[Range<usize>], long: Vec<Range<usize>>, rails: &[f64]) -> Vec<Fault> {
    let at_rail = |r: &Range<usize>| rails.contains(&x[r.start]);
    let clipped = runs.iter().filter(|r| at_rail(r)).map(|r| Fault {
        kind: FaultKind::Clipped,
        samples: r.clone(),
    });
    let long: Vec<Range<usize>> = long.into_iter().filter(|r| !at_rail(r)).collect();
    let codes = if long.is_empty() {
        Vec::new()
    } else {
        codes(x)
    };
    let dwells =
        |r: &Range<usize>| r.end < x.len() && neighbouring_codes(&codes, x[r.start], x[r.end]);
    let longest_dwell = || runs.iter().filter(|r| dwells(r)).map(|r| r.len()).max();
    let held = long
        .iter()
        .filter(|r| {
            if r.end == x.len() {
                longest_dwell().is_none_or(|d| r.len() > d)
            } else {
                !dwells(r)
            }
        })
        .map(|r| Fault {
            kind: FaultKind::Held,
            samples: r.clone(),
        });
    clipped.chain(held).collect()
}

/// The distinct values of `x` in ascending order: the codes its converter used (every sample's
/// own value, for a record of floats).
fn codes(x: &[f64]) -> Vec<f64> {
    let mut c = x.to_vec();
    c.sort_by(f64::total_cmp);
    c.dedup();
    c
}

/// Whether `a` and `b` are the same or neighbouring entries of the ascending `codes`: no sample of
/// the channel lies strictly between them.
fn neighbouring_codes(codes: &[f64], a: f64, b: f64) -> bool {
    let rank = |v: f64| codes.partition_point(|&c| c < v);
    rank(a).abs_diff(rank(b)) <= 1
}

/// The values at which channel `x` is clipped, with the samples at each. A rail is a value
/// (outside `spikes`) held by at least [`CLIPPED_SAMPLES`] samples, reached in at least
/// [`CLIPPED_VISITS`] separate stretches, and holding [`CLIPPED_PILE_UP`] times as many samples as
/// each neighbouring code. A distribution's tail thins towards its extreme, so an unclipped
/// channel, however coarsely quantised, has few samples on its outermost code against the one
/// inside it; a transducer or converter at its range collects on one code every sample that would
/// have gone beyond it. Clipping is a value held at the range limit: a quantised signal that
/// revisits its codes is not clipped.
///
/// The candidates are the channel's two extremes and the values of its `long` runs of equal
/// samples (a record whose range was exceeded in part of it only, beside louder unclipped
/// stretches, or a gain changed mid-record); a candidate inside the range must lie at the
/// distribution's edge, [`CLIPPED_EDGE_SIGMAS`] robust standard deviations from its median, since
/// a converter using only a few codes piles up on the code at its centre.
pub fn rails(x: &[f64], spikes: &[Fault], long: &[Range<usize>]) -> Vec<(f64, usize)> {
    let in_spike = |i: usize| spikes.iter().any(|f| f.samples.contains(&i));
    let clean = || (0..x.len()).filter(move |&i| !in_spike(i)).map(|i| x[i]);
    // The extremes and how many samples equal each, in one pass.
    let (lo, n_lo, hi, n_hi) = clean().fold(
        (f64::INFINITY, 0usize, f64::NEG_INFINITY, 0usize),
        |(lo, n_lo, hi, n_hi), v| {
            let n_lo = if v < lo {
                1
            } else {
                n_lo + usize::from(v == lo)
            };
            let n_hi = if v > hi {
                1
            } else {
                n_hi + usize::from(v == hi)
            };
            (lo.min(v), n_lo, hi.max(v), n_hi)
        },
    );
    if lo >= hi {
        return Vec::new();
    }
    let mut candidates: Vec<f64> = long.iter().map(|r| x[r.start]).collect();
    candidates.sort_by(f64::total_cmp);
    candidates.dedup();
    let interior = candidates.iter().any(|&v| v != lo && v != hi);
    candidates.retain(|&v| v != lo && v != hi);
    // Median and robust spread (1.4826 × median absolute deviation), for candidates inside.
    let edge = if interior {
        let mut c: Vec<f64> = clean().collect();
        let mid = c.len() / 2;
        let median = *c.select_nth_unstable_by(mid, f64::total_cmp).1;
        let mut d: Vec<f64> = c.iter().map(|v| (v - median).abs()).collect();
        let sigma = 1.4826 * *d.select_nth_unstable_by(mid, f64::total_cmp).1;
        Some((median, sigma))
    } else {
        None
    };
    let at_edge = |v: f64| {
        edge.is_none_or(|(median, sigma)| (v - median).abs() >= CLIPPED_EDGE_SIGMAS * sigma)
    };
    let count = |v: f64| {
        if v == lo {
            n_lo
        } else if v == hi {
            n_hi
        } else {
            clean().filter(|&y| y == v).count()
        }
    };
    // Separate stretches at `v`: samples at `v` whose predecessor is not.
    let visits = |v: f64| {
        (0..x.len())
            .filter(|&i| x[i] == v && (i == 0 || x[i - 1] != v))
            .count()
    };
    let below = |v: f64| {
        clean()
            .filter(|&y| y < v)
            .fold(None, |m: Option<f64>, y| Some(m.map_or(y, |m| m.max(y))))
    };
    let above = |v: f64| {
        clean()
            .filter(|&y| y > v)
            .fold(None, |m: Option<f64>, y| Some(m.map_or(y, |m| m.min(y))))
    };
    [hi, lo]
        .into_iter()
        .chain(candidates.into_iter().filter(|&v| at_edge(v)))
        .filter_map(|v| {
            let n = count(v);
            // The cheap tests first: most channels' extremes are one sample each.
            let piles_up = || {
                [below(v), above(v)]
                    .into_iter()
                    .flatten()
                    .all(|w| n as f64 > CLIPPED_PILE_UP * count(w) as f64)
            };
            (n >= CLIPPED_SAMPLES && visits(v) >= CLIPPED_VISITS && piles_up()).then_some((v, n))
        })
        .collect()
}

/// Maximal runs of ≥ 2 equal consecutive samples.
fn equal_runs(x: &[f64]) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    for i in 1..=x.len() {
        if i == x.len() || x[i] != x[start] {
            if i - start >= 2 {
                out.push(start..i);
            }
            start = i;
        }
    }
    out
}

/// Isolated samples far from the median of their four neighbours (see the module's statistics),
/// outside the held stretches `held` (whose zero differences say nothing of the spread).
fn spikes(x: &[f64], fs: f64, held: &[Range<usize>]) -> Vec<Fault> {
    let n = x.len();
    if n < 5 {
        return Vec::new();
    }
    // The median of the neighbours: inside, of four on the stack (the two middle ones of the four
    // sorted); at the ends, of the two or three that exist.
    let edge = |i: usize| {
        let mut nb: Vec<f64> = [i.wrapping_sub(2), i.wrapping_sub(1), i + 1, i + 2]
            .into_iter()
            .filter(|&j| j < n)
            .map(|j| x[j])
            .collect();
        nb.sort_by(f64::total_cmp);
        let m = nb.len();
        let med = if m.is_multiple_of(2) {
            0.5 * (nb[m / 2 - 1] + nb[m / 2])
        } else {
            nb[m / 2]
        };
        x[i] - med
    };
    // The two middle ones of four: the larger of the two pairs' minima and the smaller of their
    // maxima (their sum does not depend on their order; a zero's sign may differ from a sort's,
    // which no |d| sees).
    let inside = |i: usize| {
        let (a, b) = (x[i - 2].min(x[i - 1]), x[i - 2].max(x[i - 1]));
        let (c, e) = (x[i + 1].min(x[i + 2]), x[i + 1].max(x[i + 2]));
        x[i] - 0.5 * (a.max(c) + b.min(e))
    };
    let d: Vec<f64> = (0..n)
        .map(|i| {
            if (2..n - 2).contains(&i) {
                inside(i)
            } else {
                edge(i)
            }
        })
        .collect();
    // 1.4826 × the median |v| (the upper median of an even count): selected, not sorted.
    let spread = |v: &[f64]| {
        let mut a: Vec<f64> = v.iter().map(|e| e.abs()).collect();
        let mid = a.len() / 2;
        if a.is_empty() {
            return 0.0;
        }
        1.4826 * *a.select_nth_unstable_by(mid, f64::total_cmp).1
    };
    let global = spread(&d);
    if global <= 0.0 {
        return Vec::new();
    }
    let block = ((SPREAD_BLOCK_S * fs).round() as usize).max(64);
    let scales: Vec<f64> = d
        .chunks(block)
        .map(|c| spread(c).max(0.1 * global))
        .collect();
    // Held stretches and the two samples either side (a dropout ends in a jump) say nothing.
    let near_held = |i: usize| held.iter().any(|r| i + 2 >= r.start && i < r.end + 2);
    // An event rings: the differences 3–8 samples away are as large. A spike stands alone.
    let alone = |i: usize| {
        let around = (i.saturating_sub(8)..i.saturating_sub(2))
            .chain((i + 3..i + 9).filter(|&j| j < n))
            .map(|j| d[j].abs())
            .fold(0.0, f64::max);
        d[i].abs() > SPIKE_ALONE * around
    };
    // The signal's own spread (r.m.s. about the block's mean) in each block.
    let levels: Vec<f64> = x
        .chunks(block)
        .map(|c| {
            let m = c.iter().sum::<f64>() / c.len() as f64;
            // (v − m)² as a product: what `powi(2)` computes, without its call.
            (c.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / c.len() as f64).sqrt()
        })
        .collect();
    let far = |i: usize| {
        (2..n - 3).contains(&i)
            && !near_held(i)
            && d[i].abs() > SPIKE_SIGMAS * scales[i / block]
            && d[i].abs() > SPIKE_LEVEL * levels[i / block]
            && alone(i)
    };
    // A spike belongs to neither side: the lines through the two samples before it and through
    // the two after it both miss it by about its height. A step (a law's kink, a shock's edge)
    // lies on one of them.
    let neither_side = |r: &Range<usize>| {
        let (a, b) = (r.start, r.end);
        r.clone().all(|i| {
            let left = x[a - 1] + (x[a - 1] - x[a - 2]) * (i + 1 - a) as f64;
            let right = x[b] + (x[b] - x[b + 1]) * (b - i) as f64;
            (x[i] - left).abs().min((x[i] - right).abs()) > SPIKE_NEITHER_SIDE * d[i].abs()
        })
    };
    let mut out = Vec::new();
    let mut i = 0;
    while i < n {
        if far(i) {
            let start = i;
            while i < n && far(i) {
                i += 1;
            }
            if i - start <= SPIKE_MAX_SAMPLES && neither_side(&(start..i)) {
                out.push(Fault {
                    kind: FaultKind::Spike,
                    samples: start..i,
                });
            }
        } else {
            i += 1;
        }
    }
    out
}

/// One sentence for the stretches `(start_s, duration_s)` of one kind of fault on `channel`: how
/// many, what, and where (the first six).
pub fn summary(channel: &str, kind: FaultKind, stretches: &[(f64, f64)]) -> String {
    let times: Vec<String> = stretches
        .iter()
        .take(6)
        .map(|&(t, d)| match kind {
            FaultKind::Spike => format!("{t:.3} s"),
            _ => format!("{t:.3}–{:.3} s", t + d),
        })
        .collect();
    let more = match stretches.len().saturating_sub(6) {
        0 => String::new(),
        m => format!(" and {m} more"),
    };
    format!(
        "{channel}: {} × {} at {}{more}",
        stretches.len(),
        kind.describe(),
        times.join(", ")
    )
}

/// The [`summary`] of every kind of fault found in channel `x` sampled at `fs`.
pub fn summaries(channel: &str, x: &[f64], fs: f64) -> Vec<String> {
    let found = find(x, fs);
    [FaultKind::Held, FaultKind::Clipped, FaultKind::Spike]
        .into_iter()
        .filter_map(|kind| {
            let st: Vec<(f64, f64)> = found
                .iter()
                .filter(|f| f.kind == kind)
                .map(|f| (f.samples.start as f64 / fs, f.samples.len() as f64 / fs))
                .collect();
            (!st.is_empty()).then(|| summary(channel, kind, &st))
        })
        .collect()
}

/// `x` with every spike in `faults` replaced by the line between the samples on either side: a
/// spike is one or two wrong samples whose true values the smooth band-limited signal around them
/// predicts.
pub fn despiked(x: &[f64], faults: &[Fault]) -> Vec<f64> {
    let mut y = x.to_vec();
    for f in faults.iter().filter(|f| f.kind == FaultKind::Spike) {
        let (a, b) = (f.samples.start, f.samples.end);
        let left = a.checked_sub(1).map(|j| x[j]);
        let right = x.get(b).copied();
        for (k, v) in y[a..b].iter_mut().enumerate() {
            *v = match (left, right) {
                (Some(l), Some(r)) => l + (r - l) * (k + 1) as f64 / (b - a + 1) as f64,
                (Some(l), None) => l,
                (None, Some(r)) => r,
                (None, None) => 0.0,
            };
        }
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rand_distr::{Distribution, StandardNormal};

    /// Band-limited random vibration: white noise through a 2-pole resonance at `f_hz`.
    fn vibration(n: usize, fs: f64, f_hz: f64, seed: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let w = 2.0 * std::f64::consts::PI * f_hz / fs;
        let r: f64 = 0.97;
        let (a1, a2) = (2.0 * r * w.cos(), -r * r);
        let (mut y1, mut y2) = (0.0, 0.0);
        (0..n)
            .map(|_| {
                let e: f64 = StandardNormal.sample(&mut rng);
                let y = a1 * y1 + a2 * y2 + e;
                (y2, y1) = (y1, y);
                y
            })
            .collect()
    }

    /// Rounded to a 16-bit converter's step over ±`range`.
    fn quantised(x: &[f64], range: f64) -> Vec<f64> {
        let q = 2.0 * range / 65536.0;
        x.iter().map(|v| (v / q).round() * q).collect()
    }

    #[test]
    fn clean_records_have_no_fault() {
        // Float samples, and a 16-bit converter at a low level (many exact repeats).
        for (seed, fs, f) in [
            (1, 500.0, 5.0),
            (2, 200.0, 30.0),
            (3, 2000.0, 8.0),
            (4, 2000.0, 1.0),
        ] {
            let x = vibration(300 * fs as usize, fs, f, seed);
            assert_eq!(find(&x, fs), vec![], "float, seed {seed}");
            let peak = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let q = quantised(&x, 40.0 * peak);
            assert_eq!(find(&q, fs), vec![], "16 bit, seed {seed}");
            // Printed with three decimals of its peak: an oversampled channel lingers on one
            // printed value at every turning point.
            let printed = quantised(&x, 32.768 * peak);
            assert_eq!(find(&printed, fs), vec![], "printed, seed {seed}");
        }
    }

    #[test]
    fn a_dropout_a_spike_train_and_clipping_are_found_where_they_were_made() {
        let fs = 500.0;
        let mut x = vibration(120 * 500, fs, 6.0, 9);
        // A dropout: 0.2 s of the value at 40 s held.
        for i in 20_001..20_100 {
            x[i] = x[20_000];
        }
        // Spikes of 15 standard deviations every 7.3 s.
        let sd = (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt();
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let at: Vec<usize> = (1..13)
            .map(|k| k * 3650 + rng.random_range(0..50))
            .collect();
        for &i in &at {
            x[i] += 15.0 * sd;
        }
        // Clipping past 2 standard deviations after 100 s.
        for v in &mut x[50_000..] {
            *v = v.clamp(-2.0 * sd, 2.0 * sd);
        }
        let f = find(&x, fs);
        let held: Vec<_> = f.iter().filter(|f| f.kind == FaultKind::Held).collect();
        assert_eq!(held.len(), 1, "{f:?}");
        assert_eq!(held[0].samples, 20_000..20_100);
        let spikes: Vec<&Range<usize>> = f
            .iter()
            .filter(|f| f.kind == FaultKind::Spike)
            .map(|f| &f.samples)
            .collect();
        assert_eq!(spikes.len(), at.len(), "{f:?}");
        for (r, &i) in spikes.iter().zip(&at) {
            assert!(r.contains(&i), "spike at {i} found as {r:?}");
        }
        assert!(f.iter().any(|f| f.kind == FaultKind::Clipped));
        assert!(
            f.iter()
                .all(|f| f.kind != FaultKind::Clipped || f.samples.start >= 50_000)
        );
        // Despiking puts each spike back near its neighbours.
        let y = despiked(&x, &f);
        for &i in &at {
            assert!((y[i] - 0.5 * (y[i - 1] + y[i + 1])).abs() < 3.0 * sd);
        }
    }

    /// Rounded to a step `q`.
    fn coded(x: &[f64], q: f64) -> Vec<f64> {
        x.iter().map(|v| (v / q).round() * q).collect()
    }

    fn rms(x: &[f64]) -> f64 {
        (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
    }

    #[test]
    fn a_quiet_run_on_a_coarse_converter_is_neither_clipped_nor_held() {
        // An 8-bit logger on a quiet run uses about ten codes: the signal dwells on each code for
        // many samples and revisits every one of them, its extremes included.
        for (seed, fs, f) in [
            (11, 500.0, 2.0),
            (12, 1000.0, 1.0),
            (13, 256.0, 6.0),
            (14, 2000.0, 4.0),
            (15, 512.0, 0.7),
        ] {
            let x = vibration(180 * fs as usize, fs, f, seed);
            for codes in [8.0, 10.0, 14.0] {
                let y = coded(&x, 8.0 * rms(&x) / codes);
                let f = find(&y, fs);
                assert!(
                    f.iter().all(|f| f.kind == FaultKind::Spike),
                    "seed {seed}, {codes} codes: {} faults, first {:?}",
                    f.len(),
                    f.first()
                );
                assert_eq!(clipping(&y, fs), vec![], "seed {seed}, {codes} codes");
            }
        }
    }

    #[test]
    fn a_coarse_converter_at_its_range_is_clipped_and_its_dropout_held() {
        // 8 bits over ±2.2 σ: the converter's range clips the larger peaks.
        let fs = 500.0;
        let x = vibration(120 * 500, fs, 3.0, 21);
        let range = 2.2 * rms(&x);
        let q = 2.0 * range / 256.0;
        let mut y: Vec<f64> = x
            .iter()
            .map(|v| (v / q).round().clamp(-128.0, 127.0) * q)
            .collect();
        // A dropout of 0.3 s from 30 s: the logger repeats one sample while the signal moves on.
        let at = 15_000;
        let hold = y[at];
        for v in &mut y[at + 1..at + 150] {
            *v = hold;
        }
        let f = find(&y, fs);
        let held: Vec<_> = f.iter().filter(|f| f.kind == FaultKind::Held).collect();
        assert_eq!(held.len(), 1, "{held:?}");
        assert_eq!(held[0].samples, at..at + 150);
        let rails = clipping(&y, fs);
        assert_eq!(rails.len(), 2, "{rails:?}");
        assert!(
            rails
                .iter()
                .all(|&(v, _)| (v.abs() - 128.0 * q).abs() <= q + 1e-12)
        );
        assert!(f.iter().any(|f| f.kind == FaultKind::Clipped));
    }

    #[test]
    fn a_step_and_the_record_s_first_samples_are_not_spikes() {
        // A jump of 30 standard deviations that stays (a law's kink in an acceleration), and a
        // record that starts from rest with a jump at its first step.
        let fs = 2000.0;
        let mut x = vibration(60 * 2000, fs, 3.0, 6);
        let sd = (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt();
        for v in &mut x[40_000..] {
            *v += 30.0 * sd;
        }
        x[0] = 0.0;
        x[1] = 20.0 * sd;
        assert!(find(&x, fs).iter().all(|f| f.kind != FaultKind::Spike));
    }

    #[test]
    fn a_shock_that_spans_several_samples_is_not_a_spike() {
        // A decaying 20 Hz ring of 30 standard deviations sampled at 500 Hz: an event.
        let fs = 500.0;
        let mut x = vibration(60 * 500, fs, 6.0, 5);
        for k in 0..200 {
            let t = k as f64 / fs;
            x[10_000 + k] +=
                30.0 * (-t * 15.0).exp() * (2.0 * std::f64::consts::PI * 20.0 * t).sin() * 5.0;
        }
        assert!(find(&x, fs).iter().all(|f| f.kind != FaultKind::Spike));
    }
}
