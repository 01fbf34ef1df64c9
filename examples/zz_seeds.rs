use wbv::excitation::ExcitationSpec;
use wbv::integrator::Method;
use wbv::model::catalog;
use wbv::simulate::Settings;
use wbv::study::batch::BatchIso;
use wbv::study::iso::IsoRun;
use wbv::study::spectral::SpectralIso;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model = catalog::resolve(&args[1]).unwrap();
    let exc = &args[2];
    let dt: f64 = args[3].parse().unwrap();
    let dur: f64 = args[4].parse().unwrap();
    let e = ExcitationSpec::load(exc).unwrap();
    let s = SpectralIso::new(&model, &e)
        .unwrap()
        .figures(&model)
        .unwrap();
    for seed in 1..=4 {
        let r = IsoRun {
            excitation: e.clone(),
            settings: Settings {
                dt,
                duration_s: dur,
                method: Method::AVERAGE_ACCELERATION,
            },
            seed,
        };
        let t = BatchIso::new(&r)
            .unwrap()
            .figures(std::slice::from_ref(&model))
            .unwrap()[0]
            .0;
        println!(
            "seed {seed}: spectral {:.5} time {:.5} diff {:+.2}%",
            s.a_w_seat,
            t.a_w_seat,
            100.0 * (s.a_w_seat / t.a_w_seat - 1.0)
        );
    }
}
