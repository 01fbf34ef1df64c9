//! The measuring chain under `wbv gap`: channels a sensor, a conditioner or a logger changed
//! (gravity read by DC-coupled accelerometers, a low-pass base channel, a force plate's own
//! response, an upside-down or AC-coupled accelerometer, dropouts and spikes), planted here by
//! hand, not by the candidates' code.

use super::*;

/// `s` with channel `name` replaced by `edit` of its samples (a sensor's or a lab's error).
fn with_channel(s: &Signals, name: &str, edit: impl Fn(&[f64]) -> Vec<f64>) -> Signals {
    let mut out = Signals::new(s.sample_rate_hz, s.source.clone());
    for (n, d) in s.names.iter().zip(&s.data) {
        let x = if n == name { edit(d) } else { d.clone() };
        out.push(n.clone(), x).unwrap();
    }
    out
}

/// `s` with `offset` added to every sample of the channels named in `names`.
fn with_offset(s: &Signals, names: &[&str], offset: f64) -> Signals {
    names.iter().fold(s.clone(), |s, n| {
        with_channel(&s, n, |d| d.iter().map(|v| v + offset).collect())
    })
}

#[test]
fn gravity_read_by_dc_coupled_accelerometers_changes_nothing_but_a_warning() {
    // A DC-coupled accelerometer reads +1 g at rest. The runs' magnitudes (which scale the
    // amplitude-dependent candidates) and the verdict must be those of the fluctuations alone.
    let case = null_case();
    let model = catalog::resolve("reference").unwrap();
    let g = 9.80665;
    let lift = |s: &Signals| with_offset(s, &["a_base_z", "a_head_z"], g);
    let train: Vec<Signals> = case.train.iter().map(lift).collect();
    let plain = diagnose(&model, &case.train, &case.check).unwrap();
    let d = diagnose(&model, &train, &lift(&case.check)).unwrap();
    assert_eq!(d.verdict, plain.verdict, "{}", d.verdict_text);
    for (a, b) in d.runs.iter().zip(&plain.runs) {
        assert!(
            (a.base_rms / b.base_rms - 1.0).abs() < 1e-6,
            "{} vs {}",
            a.base_rms,
            b.base_rms
        );
    }
    let gravity = d
        .warnings
        .iter()
        .filter(|w| w.contains("gravity seems to be included"))
        .count();
    assert_eq!(gravity, 2 * 3, "{:?}", d.warnings);
}

/// `s` with its seat-pan force passed through `edit` (the force plate's own response).
fn with_force(s: &Signals, edit: impl Fn(&mut Vec<f64>, &[f64])) -> Signals {
    let a_seat = s.require("a_seat_z").unwrap().to_vec();
    let mut out = Signals::new(s.sample_rate_hz, s.source.clone());
    for (n, d) in s.names.iter().zip(&s.data) {
        let mut x = d.clone();
        if n == "f_seat_z" {
            edit(&mut x, &a_seat);
        }
        out.push(n.clone(), x).unwrap();
    }
    out
}

#[test]
fn a_low_pass_on_the_base_channel_is_named_the_base_channels_own_and_closes_the_check_run() {
    // A ride logger recording the base filters it at 20–60 Hz, inside the ISO band: a 4-pole
    // Butterworth at 30 Hz on a_base_z alone (the bench's own IIR, not the candidate's 2-pole
    // section). The measured base is the input, so base→seat and base→head rise alike above
    // ~15 Hz and seat→head is untouched: a measuring-chain effect on the base, not a cushion or
    // body one, and the named model brings a_w and SEAT back to the measurement.
    use wbv::gap_bench::forms::Sensor;
    use wbv::gap_bench::sensor::apply;
    let case = null_case();
    let model = catalog::resolve("reference").unwrap();
    let fs = case.check.sample_rate_hz;
    let lowpass = |x: &[f64]| {
        let mut x = x.to_vec();
        let s = Sensor::LowPass {
            fc_hz: 30.0,
            bessel: false,
        };
        apply(&s, &mut x, fs);
        x
    };
    let on_base = |s: &Signals| with_channel(s, "a_base_z", lowpass);
    let train: Vec<Signals> = case.train.iter().map(on_base).collect();
    let d = diagnose(&model, &train, &on_base(&case.check)).unwrap();
    assert_eq!(
        d.verdict.as_str(),
        "sensor-lowpass-base",
        "{}",
        d.verdict_text
    );
    let named = d.named_stage().unwrap();
    assert!(named.chi2_red < 3.0, "{}", d.verdict_text);
    for (with, null) in [
        (
            named.weighted.aw_gap_percent,
            d.null.check.weighted.aw_gap_percent,
        ),
        (
            named.weighted.seat_gap_points(),
            d.null.check.weighted.seat_gap_points(),
        ),
    ] {
        assert!(with.abs() <= null.abs() + 0.1, "{}", d.verdict_text);
    }
}

#[test]
fn the_force_plates_own_response_is_named_a_force_sensor_effect() {
    // One channel's dynamics on the seat-pan force alone: a 4-pole Bessel anti-alias filter at
    // 25 Hz (not the candidate's Butterworth), and an uncancelled 4 kg top plate on load cells
    // resonating at 200 Hz. Only the apparent mass changes; the transmissibilities do not, so
    // naming a body or cushion effect (which would move them) is wrong.
    use wbv::gap_bench::forms::Sensor;
    use wbv::gap_bench::sensor::apply;
    let case = null_case();
    let model = catalog::resolve("reference").unwrap();
    let fs = case.check.sample_rate_hz;
    let lowpass = |x: &mut Vec<f64>, _: &[f64]| {
        let s = Sensor::LowPass {
            fc_hz: 25.0,
            bessel: true,
        };
        apply(&s, x, fs);
    };
    let plate = |x: &mut Vec<f64>, a: &[f64]| {
        x.iter_mut().zip(a).for_each(|(f, a)| *f += 4.0 * a);
        let s = Sensor::Plate {
            m_kg: 4.0,
            f_hz: 200.0,
            zeta: 0.05,
        };
        apply(&s, x, fs);
    };
    for (what, edit) in [
        ("low-pass", &lowpass as &dyn Fn(&mut Vec<f64>, &[f64])),
        ("plate", &plate),
    ] {
        let train: Vec<Signals> = case.train.iter().map(|s| with_force(s, edit)).collect();
        let d = diagnose(&model, &train, &with_force(&case.check, edit)).unwrap();
        assert!(
            d.verdict.as_str().starts_with("sensor-") && d.verdict.as_str().contains("force"),
            "{what}: {} — {}",
            d.verdict,
            d.verdict_text
        );
        if what == "plate" {
            let m = d.candidates[0]
                .params
                .iter()
                .find(|p| p.name == "m_plate_kg")
                .expect("sensor-force names the plate mass");
            assert!((m.value - 4.0).abs() < 0.8, "m_plate {} kg", m.value);
        }
    }
}

fn inverted(s: &Signals, name: &str) -> Signals {
    with_channel(s, name, |d| d.iter().map(|v| -v).collect())
}

#[test]
fn an_upside_down_seat_accelerometer_is_named_and_the_seat_still_judged() {
    // The clean case with a_seat_z inverted in every run (was: `sensor-delay` at ΔBIC −3.8e7 on a
    // lab case): the channel is named as a gain of −1, and with the sign corrected the seat is
    // judged clean as before, its a_w as without the error. The check run repeated as a training
    // run is named too.
    let case = null_case();
    let model = catalog::resolve("reference").unwrap();
    let train: Vec<Signals> = case.train.iter().map(|s| inverted(s, "a_seat_z")).collect();
    let check = inverted(&case.check, "a_seat_z");
    let d = diagnose(&model, &train, &check).unwrap();
    let upright = diagnose(&model, &case.train, &case.check).unwrap();
    assert_eq!(
        d.verdict.effect().map(|c| c.id),
        Some("sensor-gain"),
        "{}",
        d.verdict_text
    );
    assert_eq!(
        d.null.check.weighted.aw_gap_percent,
        upright.null.check.weighted.aw_gap_percent
    );
    assert_eq!(d.channel_errors.len(), 1, "{:?}", d.channel_errors);
    assert_eq!(d.channel_errors[0].channels, "a_seat_z");
    assert_eq!(d.channel_errors[0].factor, -1.0);
    assert_eq!(d.channel_errors[0].runs.len(), train.len() + 1);
    assert!(
        d.verdict_text
            .contains("with it corrected, no effect is detected"),
        "{}",
        d.verdict_text
    );
    // A seat accelerometer in g read as m/s²: named as a unit slip, corrected, a_w as upright.
    let g = 9.80665;
    let slip = |s: &Signals| with_channel(s, "a_seat_z", |d| d.iter().map(|v| v / g).collect());
    let slipped: Vec<Signals> = case.train.iter().map(slip).collect();
    let d = diagnose(&model, &slipped, &slip(&case.check)).unwrap();
    assert_eq!(
        d.verdict.effect().map(|c| c.id),
        Some("sensor-gain"),
        "{}",
        d.verdict_text
    );
    assert!(
        d.verdict_text.contains("g read as m/s²"),
        "{}",
        d.verdict_text
    );
    assert!(
        (d.null.check.weighted.aw_gap_percent - upright.null.check.weighted.aw_gap_percent).abs()
            < 0.05,
        "{} vs {}",
        d.null.check.weighted.aw_gap_percent,
        upright.null.check.weighted.aw_gap_percent
    );
    let mut again = train.clone();
    again.push(check.clone());
    let d = diagnose(&model, &again, &check).unwrap();
    assert!(
        d.warnings
            .iter()
            .any(|w| w.contains("is the same recording as training run")),
        "{:?}",
        d.warnings
    );
}

/// `x` through an analog RC high-pass of corner `fc` Hz, discretised by the backward difference
/// y[n] = a·(y[n−1] + x[n] − x[n−1]), a = RC/(RC + Δt) (not the candidate's frequency response).
fn rc_highpass(x: &[f64], fs: f64, fc: f64) -> Vec<f64> {
    let rc = 1.0 / (2.0 * std::f64::consts::PI * fc);
    let a = rc / (rc + 1.0 / fs);
    let mut y = vec![0.0; x.len()];
    for n in 1..x.len() {
        y[n] = a * (y[n - 1] + x[n] - x[n - 1]);
    }
    y
}

#[test]
fn an_ac_coupled_seat_accelerometer_is_named_a_sensor_high_pass() {
    // The clean case with the seat accelerometer AC-coupled at 0.8 Hz (an IEPE conditioner) in
    // every run: a low-frequency gap on the seat's paths only, named a sensor effect, not a
    // structural one.
    let case = null_case();
    let model = catalog::resolve("reference").unwrap();
    let ac = |s: &Signals| with_channel(s, "a_seat_z", |d| rc_highpass(d, s.sample_rate_hz, 0.8));
    let train: Vec<Signals> = case.train.iter().map(ac).collect();
    let d = diagnose(&model, &train, &ac(&case.check)).unwrap();
    assert_eq!(
        d.verdict.effect().map(|c| c.id),
        Some("sensor-highpass"),
        "{}",
        d.verdict_text
    );
    let hp = d
        .candidates
        .iter()
        .find(|c| c.id.to_string() == "sensor-highpass")
        .unwrap();
    let seat = hp
        .params
        .iter()
        .find(|p| p.name == "highpass_seat_hz")
        .unwrap();
    assert!((seat.value / 0.8 - 1.0).abs() < 0.15, "{seat:?}");
}

/// `x` with a logger's faults planted independently of the detector: dropouts (the value at each
/// start held for `hold` samples) and single-sample spikes of `spike` standard deviations.
fn with_faults(
    x: &[f64],
    drop_at: &[usize],
    hold: usize,
    spikes_at: &[usize],
    spike: f64,
) -> Vec<f64> {
    let mut y = x.to_vec();
    for &a in drop_at {
        let v = y[a];
        for s in &mut y[a..a + hold] {
            *s = v;
        }
    }
    let sd = (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt();
    for &i in spikes_at {
        y[i] += spike * sd;
    }
    y
}

#[test]
fn logger_dropouts_and_a_spike_train_are_screened_out_before_the_fit() {
    // A no-effect case whose seat and head channels come from a logger that drops out for 0.3 s a
    // few times per run and adds a spike every 2.7 s. The faults are reported with their times,
    // and the verdict is the clean data's.
    let case = null_case();
    let model = catalog::resolve("reference").unwrap();
    let fs = case.check.sample_rate_hz;
    let hold = (0.3 * fs) as usize;
    // Run k of n samples: dropouts at a quarter, half and three quarters, spikes every 2.7 s
    // where the logger is recording (none inside a dropout).
    let plan = |n: usize, k: usize| {
        let drops: Vec<usize> = (1..4).map(|j| (j * n) / 4 + 37 * k).collect();
        let spikes: Vec<usize> = (1..)
            .map(|j| j * (2.7 * fs) as usize + 11 * k)
            .take_while(|&i| i < n)
            .filter(|&i| drops.iter().all(|&a| i + 3 < a || i > a + hold + 3))
            .collect();
        (drops, spikes)
    };
    let plant = |s: &Signals, k: usize| {
        let (drops, spikes) = plan(s.len(), k);
        let s = with_channel(s, "a_seat_z", |x| {
            with_faults(x, &drops, hold, &spikes, 20.0)
        });
        with_channel(&s, "a_head_z", |x| with_faults(x, &drops, hold, &[], 0.0))
    };
    let train: Vec<Signals> = case
        .train
        .iter()
        .enumerate()
        .map(|(k, s)| plant(s, k))
        .collect();
    let check = plant(&case.check, 7);
    let clean = diagnose(&model, &case.train, &case.check).unwrap();
    let d = diagnose(&model, &train, &check).unwrap();
    assert_eq!(d.verdict, clean.verdict, "{}", d.verdict_text);
    let runs = train.len() + 1;
    let held = d
        .data_faults
        .iter()
        .filter(|f| f.kind == FaultKind::Held)
        .count();
    assert_eq!(held, runs * 3 * 2, "{:#?}", d.data_faults);
    let spikes = d
        .data_faults
        .iter()
        .filter(|f| f.kind == FaultKind::Spike)
        .count();
    let planted: usize = case
        .train
        .iter()
        .enumerate()
        .chain([(7, &case.check)])
        .map(|(k, s)| plan(s.len(), k).1.len())
        .sum();
    assert_eq!(spikes, planted, "{:#?}", d.data_faults);
    // Each dropout is reported where it was made, to the sample.
    let first = d
        .data_faults
        .iter()
        .find(|f| f.kind == FaultKind::Held && f.channel == "a_seat_z")
        .unwrap();
    let n = case.train[0].len();
    assert!(
        (first.start_s - (n / 4) as f64 / fs).abs() < 1e-9,
        "{first:?}"
    );
    assert!((first.duration_s - 0.3).abs() < 1.5 / fs, "{first:?}");
    assert!(
        d.warnings
            .iter()
            .any(|w| w.contains("held value") && w.contains("left out")),
        "{:?}",
        d.warnings
    );
    // A logger that drops out every few seconds leaves too few clean segments: refused, with the
    // faults named.
    let dead = |s: &Signals| {
        let drops: Vec<usize> = (0..s.len() - fs as usize)
            .step_by((3.0 * fs) as usize)
            .skip(1)
            .collect();
        with_channel(s, "a_seat_z", |x| {
            with_faults(x, &drops, (0.2 * fs) as usize, &[], 0.0)
        })
    };
    let e = diagnose(&model, &case.train, &dead(&case.check))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("spectral segments clean") && e.contains("held value"),
        "{e}"
    );
}
