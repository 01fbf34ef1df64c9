//! Random excitation through the whole chain: generated input → simulation → Welch estimate of the
//! transmissibility, against the analytic FRF of the same model.

use wbv::analysis::{Segment, Welch, WelchOptions, Window};
use wbv::excitation::{ExcitationSpec, Kind};
use wbv::integrator::Method;
use wbv::model::catalog;
use wbv::response::frf;
use wbv::scenario::Scenario;
use wbv::simulate::Settings;

#[test]
fn ten_minutes_of_random_input_give_the_analytic_transmissibility() {
    let model = catalog::resolve("reference").unwrap();
    let excitation = ExcitationSpec::new(
        Kind::Random {
            rms_m_s2: 1.0,
            band_hz: [0.5, 80.0],
        },
        "test random",
    )
    .unwrap();
    for method in [Method::AVERAGE_ACCELERATION, Method::Rk4] {
        let scenario = Scenario {
            model: model.clone(),
            excitation: excitation.clone(),
            settings: Settings {
                dt: 1e-3,
                duration_s: 600.0,
                method,
            },
            seed: 11,
        };
        let signals = scenario.signals().unwrap();
        let fs = signals.sample_rate_hz;
        let mut welch = Welch::new(
            fs,
            &WelchOptions {
                window: Window::Hann,
                segment: Segment::ResolutionHz(0.25),
                ..WelchOptions::default()
            },
        )
        .unwrap();
        let base = signals.require("a_base_z").unwrap();
        let mut worst: f64 = 0.0;
        let mut checked = 0;
        for (channel, response) in [("a_seat_z", "seat"), ("a_head_z", "t_head")] {
            let cross = welch
                .cross(base, signals.require(channel).unwrap())
                .unwrap();
            let h1 = cross.h1();
            let coh = cross.coherence();
            let freqs = welch.frequencies();
            for (i, &f) in freqs.iter().enumerate() {
                if !(1.0..=20.0).contains(&f) || coh[i] <= 0.99 {
                    continue;
                }
                let exact = frf::compute(model.system(), &[f])
                    .unwrap()
                    .get(response)
                    .unwrap()
                    .values[0];
                let db = 20.0 * (h1[i].norm() / exact.norm()).log10();
                worst = worst.max(db.abs());
                checked += 1;
            }
        }
        eprintln!("{method:?}: worst |gap| {worst:.3} dB over {checked} coherent bins, 1–20 Hz");
        assert!(checked > 100, "too few coherent bins: {checked}");
        assert!(worst < 0.3, "{method:?}: worst gap {worst:.3} dB");
    }
}

#[test]
fn a_seat_team_can_assert_comfort_in_their_own_tests() {
    // The default scenario (reference seat in the Bell 214 spectrum), shortened to 20 s.
    let mut scenario = wbv::scenario::default_scenario().unwrap();
    scenario.settings.duration_s = 20.0;
    let report = wbv::analysis::Report::from_signals(
        &scenario.signals().unwrap(),
        &wbv::analysis::Options::default(),
    )
    .unwrap();
    use wbv::analysis::Comfort;
    assert!(report.comfort() <= Comfort::FairlyUncomfortable);
    report.assert_comfort_at_most(Comfort::FairlyUncomfortable);
    // The cushion isolates: less than the base reaches the seat surface in the weighted sense.
    assert!(report.seat_percent().unwrap() < 100.0);
}
