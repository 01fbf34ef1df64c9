//! A case's runs as a lab would acquire them: simulated noise-free at the internal rate, the
//! sensors' own dynamics applied there, sampled at the acquisition rate with noise.

use super::*;

/// Simulates one noise-free run at the internal rate, applies the sensors there, and samples it at
/// `fs` (every `step`-th sample); channels in the collector's order.
pub(super) fn simulate(
    model: &Chain,
    exc: &ExcitationSpec,
    fs: f64,
    duration_s: f64,
    seed: u64,
    sensors: &[(String, Sensor)],
) -> Result<Signals> {
    let step = (SIM_RATE / fs).ceil().max(1.0) as usize;
    let fs_sim = fs * step as f64;
    let sc = Scenario {
        model: crate::model::Model::from_chain(model.clone()),
        excitation: exc.clone(),
        settings: Settings {
            dt: 1.0 / fs_sim,
            duration_s,
            method: Method::AVERAGE_ACCELERATION,
        },
        seed,
    };
    let full = sc.signals()?;
    let mut out = Signals::new(fs, format!("bench run (seed {seed})"));
    for (name, data) in full.names.iter().zip(&full.data) {
        let mut x = data.clone();
        for (ch, s) in sensors {
            if let (true, Sensor::Plate { m_kg, .. }) = (ch == name, s) {
                let a_seat = full.require("a_seat_z")?;
                x.iter_mut().zip(a_seat).for_each(|(f, a)| *f += m_kg * a);
            }
            if ch == name {
                crate::gap_bench::sensor::apply(s, &mut x, fs_sim);
            }
        }
        out.push(name.clone(), x.iter().step_by(step).copied().collect())?;
    }
    Ok(out)
}

/// Adds white noise of `level` × channel r.m.s. (the base: `base_floor` × its r.m.s. more, in
/// power), drops `f_seat_z` when `force.0` is false and keeps `f_back_z` only when `force.1` is
/// true.
pub(super) fn measure(
    s: &Signals,
    (level, base_floor): (f64, f64),
    force: (bool, bool),
    rng: &mut ChaCha8Rng,
    name: String,
) -> Result<Signals> {
    let mut out = Signals::new(s.sample_rate_hz, name);
    for (n, d) in s.names.iter().zip(&s.data) {
        if !matches!(
            n.as_str(),
            "a_base_z" | "a_seat_z" | "a_head_z" | "f_seat_z" | "f_back_z"
        ) {
            continue;
        }
        if (n == "f_seat_z" && !force.0) || (n == "f_back_z" && !force.1) {
            continue;
        }
        let extra = if n == "a_base_z" { base_floor } else { 0.0 };
        let sd = level.hypot(extra) * crate::analysis::figures::rms(d);
        out.push(
            n.clone(),
            d.iter()
                .map(|v| v + sd * rng.sample::<f64, _>(StandardNormal))
                .collect(),
        )?;
    }
    Ok(out)
}
