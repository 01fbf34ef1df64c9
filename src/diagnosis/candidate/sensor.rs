//! The measuring chain (docs/gap.md §5): the accelerometers, their mounts, the acquisition's
//! filters and timing, and the seat-pan force plate. These edit the [`Variant`]'s channels, not the
//! mechanical system; all are linear.

use super::*;

/// A measuring-chain effect: linear, in the sensor family.
const fn sensor(
    id: &'static str,
    params: fn() -> Vec<Param>,
    applies_to: fn(&System) -> bool,
    apply: fn(&mut Variant, &[f64]) -> Result<()>,
) -> Definition {
    Definition {
        id,
        family: Family::Sensor,
        params,
        applies_to,
        apply,
        ..Definition::COMMON
    }
}

/// A measuring-chain effect of the seat-pan force plate alone: without a measured `f_seat_z` it
/// changes nothing and is not fitted.
const fn force_sensor(
    id: &'static str,
    params: fn() -> Vec<Param>,
    apply: fn(&mut Variant, &[f64]) -> Result<()>,
) -> Definition {
    Definition {
        reads_force_only: true,
        ..sensor(id, params, has_force, apply)
    }
}

/// The family's candidates, in report order.
pub static DEFINITIONS: &[Candidate] = &[
    &DELAY,
    &LOGGER_OFFSET,
    &LOGGER_DRIFT,
    &LOWPASS,
    &HIGHPASS,
    &GAIN,
    &MOUNT_SEAT,
    &MOUNT_HEAD,
    &MOUNT_BASE,
    &LOWPASS_BASE,
    &FORCE,
    &MOUNT_FORCE,
];

/// Every model has base and seat accelerometers.
fn always(_: &System) -> bool {
    true
}

/// Whether the model has the head channel.
fn has_head(s: &System) -> bool {
    s.channel_index("a_head_z").is_some()
}

/// Whether the model has the seat-pan force channel.
fn has_force(s: &System) -> bool {
    s.channel_index("f_seat_z").is_some()
}

/// A mount resonance's parameters: frequency 8–300 Hz and damping ratio up to `zeta_max`.
fn mount_params(zeta_max: f64, zeta_starts: &[f64]) -> Vec<Param> {
    vec![
        Param::new("f_mount_hz", 8.0, 300.0, &[15.0, 40.0, 120.0], true),
        Param::new("zeta_mount", 0.01, zeta_max, zeta_starts, true),
    ]
}

/// Lag on the seat and/or head channel (phase gap linear in frequency). Relative to the base
/// channel, so a lag on the base accelerometer is a negative delay of both outputs.
pub static DELAY: Definition = sensor(
    "sensor-delay",
    || {
        vec![
            Param::new("delay_seat_s", -0.05, 0.05, &[0.0], false),
            Param::new("delay_head_s", -0.05, 0.05, &[0.0], false),
        ]
    },
    always,
    |v, p| {
        v.chain.seat.delay_s += p[0];
        v.chain.head.delay_s += p[1];
        Ok(())
    },
);

/// Adds a lag growing as `offset + drift·t` through the run to every transducer off the base
/// accelerometer's logger ([`crate::diagnosis::acquisition`]): the seat pad, head and force plate
/// retimed together, not one channel at a time.
fn retime_off_base(v: &mut Variant, offset_s: f64, drift: f64) {
    let off = v.chain.off_base;
    for (on, ch) in [
        (off.seat, &mut v.chain.seat),
        (off.head, &mut v.chain.head),
        (off.force, &mut v.chain.force),
    ] {
        if on {
            ch.delay_s += offset_s;
            ch.drift += drift;
        }
    }
}

/// A trigger offset between two data loggers: every channel of the logger that does not record
/// the base is late (or early) by the same `offset_s`, the seat-pan force included, so all its
/// paths from the base show the same phase slope −2πf·offset while seat→head and the apparent
/// mass (both on one logger) show none. With one logger this is a lag of the base accelerometer
/// of opposite sign.
pub static LOGGER_OFFSET: Definition = Definition {
    retiming: Some(Retiming::Offset),
    ..sensor(
        "logger-offset",
        || vec![Param::new("offset_s", -0.05, 0.05, &[0.0], false)],
        always,
        |v, p| {
            retime_off_base(v, p[0], 0.0);
            Ok(())
        },
    )
};

/// Parts per million, the unit a logger's clock tolerance is quoted in.
const PPM: f64 = 1e-6;

/// A drifting clock between two data loggers: the late logger's lag grows linearly through the
/// run, `offset_s + drift_ppm·10⁻⁶·t` (a quartz clock's rate error of tens to hundreds of ppm). A
/// whole run's H1 averages the growing lag over its segments: the mid-run lag and a loss of
/// magnitude rising with frequency and run length ([`crate::diagnosis::predict::Channel::response_in`]),
/// which a low-pass mimics on one run length but not on runs of different lengths or on the
/// run's halves.
pub static LOGGER_DRIFT: Definition = Definition {
    retiming: Some(Retiming::Drift),
    // The runs' halves measure the rate directly (docs/gap.md §5, loggers).
    prior: Some(Prior::ClockDrift { param: 1 }),
    ..sensor(
        "logger-drift",
        || {
            vec![
                Param::new("offset_s", -0.05, 0.05, &[0.0], false),
                Param::new("drift_ppm", -2000.0, 2000.0, &[-100.0, 100.0], false),
            ]
        },
        always,
        |v, p| {
            retime_off_base(v, p[0], p[1] * PPM);
            Ok(())
        },
    )
};

/// The orders a conditioner's Butterworth filter is tried at, chosen by evidence: one pole (an
/// RC coupling) to four (a logger's or charge amplifier's filter).
const FILTER_ORDERS: &[f64] = &[1.0, 2.0, 3.0, 4.0];

/// A filter order from its fitted choice (one of [`FILTER_ORDERS`]).
fn order(p: f64) -> u8 {
    p.round().clamp(1.0, 4.0) as u8
}

/// Butterworth low-pass (an anti-alias or conditioner filter) on the seat and/or head channel,
/// of one to four poles, the order chosen by evidence (one order for the rig's conditioners).
pub static LOWPASS: Definition = sensor(
    "sensor-lowpass",
    || {
        vec![
            Param::new("lowpass_seat_hz", 10.0, 5000.0, &[150.0], true),
            Param::new("lowpass_head_hz", 10.0, 5000.0, &[150.0], true),
            Param::choice("lowpass_order", FILTER_ORDERS),
        ]
    },
    always,
    |v, p| {
        v.chain.seat.lowpass_hz = p[0];
        v.chain.head.lowpass_hz = p[1];
        v.chain.seat.lowpass_order = order(p[2]);
        v.chain.head.lowpass_order = order(p[2]);
        Ok(())
    },
);

/// High-pass on the base, seat and/or head channel: the AC coupling of an IEPE accelerometer (one
/// pole) or a charge amplifier's or conditioner's high-pass (two to four), with Butterworth poles
/// or as identical RC stages; order and design chosen by evidence (one for the rig's
/// conditioners), each channel's −3 dB corner fitted. A gap below a few Hz on the
/// paths of one channel, with a phase lead rising to n·90° below the corner.
pub static HIGHPASS: Definition = sensor(
    "sensor-highpass",
    || {
        vec![
            Param::new("highpass_base_hz", 0.01, 5.0, &[0.1], true),
            Param::new("highpass_seat_hz", 0.01, 5.0, &[0.1], true),
            Param::new("highpass_head_hz", 0.01, 5.0, &[0.1], true),
            Param::choice("highpass_order", FILTER_ORDERS),
            // 0: Butterworth poles; 1: identical RC stages (a real n-fold pole). Two designs
            // that bracket the damping of a conditioner's poles (a Bessel lies between).
            Param::choice("highpass_rc_stages", &[0.0, 1.0]),
        ]
    },
    always,
    |v, p| {
        let n = order(p[3]);
        for (ch, f) in [
            (&mut v.chain.base, p[0]),
            (&mut v.chain.seat, p[1]),
            (&mut v.chain.head, p[2]),
        ] {
            ch.highpass_hz = f;
            ch.highpass_order = n;
            ch.highpass_rc = p[4] > 0.5;
        }
        Ok(())
    },
);

/// Calibration gain error on the base, seat and head accelerometers. A channel's calibration error
/// found before the fit (an inverted sign, a unit slip) is this effect too.
pub static GAIN: Definition = Definition {
    calibration: true,
    ..sensor(
        "sensor-gain",
        || {
            vec![
                Param::new("gain_base", 0.7, 1.4, &[1.0], true),
                Param::new("gain_seat", 0.7, 1.4, &[1.0], true),
                Param::new("gain_head", 0.7, 1.4, &[1.0], true),
            ]
        },
        always,
        |v, p| {
            v.chain.base.gain *= p[0];
            v.chain.seat.gain *= p[1];
            v.chain.head.gain *= p[2];
            Ok(())
        },
    )
};

/// Mount resonance of the seat-pad accelerometer.
pub static MOUNT_SEAT: Definition = sensor(
    "sensor-mount-seat",
    || mount_params(0.7, &[0.08]),
    always,
    |v, p| {
        v.chain.seat.mount = Some((p[0], p[1]));
        Ok(())
    },
);

/// Mount resonance of the head accelerometer.
pub static MOUNT_HEAD: Definition = sensor(
    "sensor-mount-head",
    || mount_params(0.7, &[0.08]),
    has_head,
    |v, p| {
        v.chain.head.mount = Some((p[0], p[1]));
        Ok(())
    },
);

/// The base accelerometer's mount resonance: the measured base is the input, so it divides
/// base→seat and base→head alike and leaves seat→head alone. Damping up to 1 and a heavily damped
/// start: a soft, lossy mount (a magnet on a painted floor, a pad) is as likely as a resonant one.
/// A low-pass of the base's conditioner or logger is [`LOWPASS_BASE`].
pub static MOUNT_BASE: Definition = sensor(
    "sensor-mount-base",
    || mount_params(1.0, &[0.08, 0.6]),
    always,
    |v, p| {
        v.chain.base.mount = Some((p[0], p[1]));
        Ok(())
    },
);

/// A low-pass on the base channel: its signal conditioner's filter, or the anti-alias filter of
/// the logger that records it set low (a ride logger at 100–200 Hz filters at 20–60 Hz), of two
/// to four poles: two second-order sections, the second at `ratio` ≥ 1 times the first's
/// frequency (a 4-pole Butterworth is ratio 1, ζ 0.38 and 0.92; a 2-pole puts the second far
/// out). The measured base is the input, so it raises base→seat and base→head alike above a few
/// Hz with a lag and leaves seat→head alone; unlike a mount it has no numerator lead.
pub static LOWPASS_BASE: Definition = sensor(
    "sensor-lowpass-base",
    || {
        vec![
            Param::new("lowpass_base_hz", 5.0, 5000.0, &[20.0, 60.0], true),
            Param::new("zeta_1", 0.3, 1.2, &[0.6], true),
            Param::new("ratio_2", 1.0, 100.0, &[1.0, 100.0], true),
            Param::new("zeta_2", 0.3, 1.2, &[0.9], true),
        ]
    },
    always,
    |v, p| {
        v.chain.base.sections = [Some((p[0], p[1])), Some((p[0] * p[2], p[3]))];
        Ok(())
    },
);

/// The seat-pan force plate's own response (E11/E13 and the ISO 5982 mass cancellation): a delay
/// and a 4-pole low-pass of the load cells, and the top plate's uncancelled mass,
/// AM_meas = l_f(f)·(AM + m_plate). Its gain is not a parameter: a force gain is the same as
/// scaling every body mass, which the null re-fit already does.
pub static FORCE: Definition = force_sensor(
    "sensor-force",
    || {
        vec![
            Param::new("delay_force_s", -0.05, 0.05, &[0.0], false),
            Param::new("lowpass_force_hz", 10.0, 5000.0, &[150.0], true),
            Param::new("m_plate_kg", -10.0, 40.0, &[0.0, 5.0], false),
        ]
    },
    |v, p| {
        v.chain.force.delay_s += p[0];
        v.chain.force.lowpass_hz = p[1];
        v.chain.force_mass_kg += p[2];
        Ok(())
    },
);

/// Mount (load-cell) resonance of the seat-pan force plate.
pub static MOUNT_FORCE: Definition = force_sensor(
    "sensor-mount-force",
    || mount_params(0.7, &[0.08]),
    |v, p| {
        v.chain.force.mount = Some((p[0], p[1]));
        Ok(())
    },
);
