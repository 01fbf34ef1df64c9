//! A logger's acquisition faults planted on the measured runs of a share of the cases, drawn from a
//! stream of their own (so the other draws of a case stay as they were) and written without the
//! detector's code (`analysis::faults`): dropouts (the logger repeats its last value for
//! 0.05–0.5 s, one to four times per run, on the seat-side channels it records), a spike train
//! (one sample off by 10–50 × the channel's r.m.s., every 1–10 s, on one channel), or clipping (one
//! channel's converter range at 2.5–4 × the middle run's r.m.s., reached most by the loudest run).

use super::*;

/// Share of the cases with a logger fault.
pub const FAULT_FRACTION: f64 = 0.25;

/// The kinds of fault planted.
pub const FAULTS: [&str; 3] = ["dropouts", "spikes", "clipping"];

/// Draws whether case seed `cseed` has a logger fault and plants it on `runs` (training runs,
/// then the check run). Returns its kind.
pub(super) fn plant(cseed: u64, runs: &mut [Signals]) -> Result<Option<&'static str>> {
    let mut rng = ChaCha8Rng::seed_from_u64(cseed ^ 0x1099_e2f0_0000_0003);
    if rng.random::<f64>() >= FAULT_FRACTION {
        return Ok(None);
    }
    let kind = FAULTS[(rng.random::<f64>() * 3.0) as usize % 3];
    let seat_side: Vec<String> = runs[0]
        .names
        .iter()
        .filter(|n| *n != "a_base_z")
        .cloned()
        .collect();
    let one = seat_side[(rng.random::<f64>() * seat_side.len() as f64) as usize % seat_side.len()]
        .clone();
    let rms_of = |s: &Signals, n: &str| crate::analysis::figures::rms(s.get(n).unwrap_or(&[]));
    let range = uniform(&mut rng, 2.5, 4.0) * rms_of(&runs[1.min(runs.len() - 1)], &one);
    for run in runs.iter_mut() {
        let fs = run.sample_rate_hz;
        let n = run.len();
        let mut data = run.data.clone();
        match kind {
            "dropouts" => {
                let count = 1 + (rng.random::<f64>() * 4.0) as usize;
                for _ in 0..count {
                    let len = (uniform(&mut rng, 0.05, 0.5) * fs).round() as usize;
                    let at = (rng.random::<f64>() * (n - len - 1) as f64) as usize;
                    for (name, x) in run.names.iter().zip(&mut data) {
                        if name != "a_base_z" {
                            let v = x[at];
                            x[at..at + len].iter_mut().for_each(|s| *s = v);
                        }
                    }
                }
            }
            "spikes" => {
                let every = uniform(&mut rng, 1.0, 10.0) * fs;
                let size = uniform(&mut rng, 10.0, 50.0);
                let i = run.names.iter().position(|m| *m == one).expect("channel");
                let r = crate::analysis::figures::rms(&data[i]);
                let mut t = rng.random::<f64>() * every;
                while (t as usize) < n {
                    let sign = if rng.random::<f64>() < 0.5 { -1.0 } else { 1.0 };
                    data[i][t as usize] += sign * size * r;
                    t += every * uniform(&mut rng, 0.5, 1.5);
                }
            }
            _ => {
                let i = run.names.iter().position(|m| *m == one).expect("channel");
                data[i].iter_mut().for_each(|v| *v = v.clamp(-range, range));
            }
        }
        let mut out = Signals::new(fs, run.source.clone());
        for (name, x) in run.names.iter().zip(data) {
            out.push(name.clone(), x)?;
        }
        *run = out;
    }
    Ok(Some(kind))
}
