//! The FMU's cost per 1 ms communication step, all FMI calls included (`fmi2SetReal` of the input,
//! `fmi2DoStep`, `fmi2GetReal` of five outputs), against `wbv simulate --no-record` per step (the
//! scenario's run with its streaming ISO 2631-1 analysis, no recording) on the same model, in the
//! same run: the reference seat (linear) and the scissor seat (end stops, friction). docs/speed.md.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::ffi::{CString, c_void};
use std::hint::black_box;
use wbv::fmu::package::{Request, prepare};
use wbv_fmu as fmi;

/// Communication steps per measured iteration (20 s at 1 ms).
const STEPS: usize = 20_000;
const DT: f64 = 1e-3;

/// A floor acceleration with broadband content (sum of incommensurate sines), m/s².
fn input(k: usize) -> f64 {
    let t = k as f64 * DT;
    (7.1 * t).sin() + 0.5 * (31.7 * t).sin() + 0.25 * (83.3 * t).sin()
}

/// Runs one FMU instance of `resources` for [`STEPS`] steps through the C API.
fn fmu_run(uri: &CString, outs: &[u32]) -> f64 {
    let name = c"bench";
    let guid = c"";
    // SAFETY: the FMI calling sequence on one instance, arrays of the stated lengths.
    unsafe {
        let c: *mut c_void = fmi::fmi2Instantiate(
            name.as_ptr(),
            1,
            guid.as_ptr(),
            uri.as_ptr(),
            std::ptr::null(),
            0,
            0,
        );
        assert!(!c.is_null());
        fmi::fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0);
        fmi::fmi2EnterInitializationMode(c);
        fmi::fmi2ExitInitializationMode(c);
        let mut values = vec![0.0; outs.len()];
        let mut sum = 0.0;
        for k in 0..STEPS {
            let a = input(k);
            fmi::fmi2SetReal(c, [0u32].as_ptr(), 1, &a);
            let status = fmi::fmi2DoStep(c, k as f64 * DT, DT, 1);
            assert_eq!(status, fmi::OK);
            fmi::fmi2GetReal(c, outs.as_ptr(), outs.len(), values.as_mut_ptr());
            sum += values[0];
        }
        fmi::fmi2FreeInstance(c);
        sum
    }
}

/// The same model run as `wbv simulate --no-record` runs it.
fn simulate_run(model: &str) -> wbv::Result<f64> {
    let mut scenario = wbv::scenario::default_scenario()?;
    scenario.model = wbv::model::catalog::resolve(model)?;
    scenario.settings.duration_s = STEPS as f64 * DT;
    let outputs = wbv::scenario::Outputs {
        mcap: None,
        csv: None,
        overwrite: wbv::io::atomic::Overwrite::Refuse,
        command_line: "bench".into(),
    };
    let outcome = scenario.execute_with(&outputs, &mut [], None)?;
    Ok(outcome.elapsed_s)
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("fmu_step_1ms");
    group.throughput(Throughput::Elements(STEPS as u64));
    group.sample_size(10);
    for model in ["reference", "scissor-seat"] {
        let dir = tempfile::tempdir().expect("temporary directory");
        let request = Request {
            model,
            params: &[],
            dt: DT,
            integrator: "newmark",
            library: std::path::Path::new(""),
        };
        let (config, texts) = prepare(&request).expect("the model builds");
        config.write(dir.path(), &texts).expect("resources written");
        let uri = CString::new(format!("file://{}", dir.path().display())).expect("a path");
        let vars = wbv::fmu::variables(&config.model(&texts).expect("model")).expect("variables");
        let outs: Vec<u32> = [
            "f_floor_z",
            "a_seat_z",
            "a_head_z",
            "a_w_seat_z",
            "vdv_seat_z",
        ]
        .iter()
        .map(|n| vars.iter().find(|v| v.name == *n).expect("output").vr)
        .collect();
        group.bench_function(format!("fmu/{model}"), |b| {
            b.iter(|| black_box(fmu_run(&uri, &outs)))
        });
        group.bench_function(format!("simulate_no_record/{model}"), |b| {
            b.iter(|| black_box(simulate_run(model).expect("runs")))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
