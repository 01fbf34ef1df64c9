//! Parameter sweeps: one or two parameters on a grid, one response per point over a frequency grid,
//! with its global peak (parabola-refined, [`crate::response::peak::global_peak`]).
//!
//! Output is long-format CSV (`point,<params…>,freq_hz,mag,phase_deg`) and a peaks table
//! (`point,<params…>,peak_freq_hz,peak_mag[,extra…]`); both merge across shards
//! ([`super::shard::merge`]). Extra figures per point (the ISO 2631-1 figures of a time-domain run,
//! [`super::iso::IsoRun`]) plug in through [`PointFigures`].

use super::evaluate::Evaluator;
use super::param::{Param, apply};
use super::shard::Shard;
use crate::error::Result;
use crate::model::Model;
use crate::response::peak::{Peak, global_peak};
use num_complex::Complex64;
use rayon::prelude::*;
use std::io::Write;

/// Extra scalar figures computed for every sweep point from the point's model (hook for
/// time-domain or ISO 2631-1 quantities; must be deterministic).
pub trait PointFigures: Sync {
    /// Column names (with unit), e.g. `seat_pct`.
    fn names(&self) -> Vec<String>;
    /// The figures for one model, in the order of [`Self::names`].
    fn compute(&self, model: &Model) -> Result<Vec<f64>>;
    /// The figures of several models, in order (a hook that shares work across points, such as
    /// the batched time-domain path, overrides it); by default [`Self::compute`] on each.
    fn compute_many(&self, models: &[Model]) -> Result<Vec<Vec<f64>>> {
        models.iter().map(|m| self.compute(m)).collect()
    }
    /// How figure `column` (index into [`Self::names`]) is written to CSV.
    fn format(&self, column: usize, value: f64) -> String {
        let _ = column;
        value.to_string()
    }
}

/// What to sweep.
#[derive(Debug, Clone)]
pub struct Spec {
    /// Swept parameters (one or two make a grid; more are allowed).
    pub params: Vec<Param>,
    /// Values of each parameter.
    pub values: Vec<Vec<f64>>,
    /// Response name (`stht`, `seat`, `apms`, `dpmi`, `t_<mass>`).
    pub response: String,
    /// Frequencies in Hz.
    pub freq_hz: Vec<f64>,
}

impl Spec {
    /// The unit of the response's magnitude: kg for an apparent mass (`apms…`), N·s/m for a
    /// driving-point mechanical impedance (`dpmi…`), `-` for a transmissibility.
    pub fn response_unit(&self) -> &'static str {
        if self.response.starts_with("apms") {
            "kg"
        } else if self.response.starts_with("dpmi") {
            "N·s/m"
        } else {
            "-"
        }
    }

    /// Every grid point's parameter values, the first parameter varying slowest.
    pub fn grid(&self) -> Vec<Vec<f64>> {
        self.values.iter().fold(vec![vec![]], |acc, vals| {
            acc.iter()
                .flat_map(|prefix| {
                    vals.iter().map(move |v| {
                        let mut p = prefix.clone();
                        p.push(*v);
                        p
                    })
                })
                .collect()
        })
    }
}

/// The result at one grid point.
#[derive(Debug, Clone)]
pub struct Point {
    /// Global point index (row-major over the grid).
    pub index: usize,
    /// Parameter values.
    pub values: Vec<f64>,
    /// Complex response at each frequency.
    pub response: Vec<Complex64>,
    /// Global peak of the magnitude.
    pub peak: Peak,
    /// Figures from the [`PointFigures`] hooks, in hook order.
    pub extra: Vec<f64>,
}

/// Points handed to the hooks together ([`PointFigures::compute_many`]); chunks run in
/// parallel, so memory holds a chunk's models per thread, not the grid's.
const CHUNK: usize = 64;

/// Runs the points of `spec` that belong to `shard`, in parallel chunks; `tick` is called once per
/// point (progress). Points come back in index order, and each point's figures do not depend on
/// the chunk it falls in.
pub fn run(
    model: &Model,
    spec: &Spec,
    shard: Shard,
    hooks: &[&dyn PointFigures],
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<Point>> {
    let grid = spec.grid();
    let base = Evaluator::new(model.system(), &spec.response, &spec.freq_hz)?;
    let chunks = shard
        .points(grid.len())
        .par_chunks(CHUNK)
        .map_init(
            || base.clone(),
            |ev, chunk| {
                let mut models = Vec::with_capacity(chunk.len());
                let mut points = Vec::with_capacity(chunk.len());
                for &index in chunk {
                    crate::cancel::check("a sweep")?;
                    let mut m = model.clone();
                    apply(&mut m, &spec.params, &grid[index])?;
                    let (response, peak) = evaluate_model(&m, ev, &spec.freq_hz)?;
                    models.push(m);
                    points.push(Point {
                        index,
                        values: grid[index].clone(),
                        response,
                        peak,
                        extra: Vec::new(),
                    });
                }
                for h in hooks {
                    for (p, extra) in points.iter_mut().zip(h.compute_many(&models)?) {
                        p.extra.extend(extra);
                    }
                }
                chunk.iter().for_each(|_| tick());
                Ok(points)
            },
        )
        .collect::<Result<Vec<_>>>()?;
    Ok(chunks.into_iter().flatten().collect())
}

/// Sets `values` of `params` on a copy of `model` held in `scratch`, evaluates the response at
/// `freq_hz` and its global peak (NaN when the magnitude has no finite sample).
pub fn evaluate_point(
    model: &Model,
    scratch: &mut Model,
    ev: &mut Evaluator,
    params: &[Param],
    values: &[f64],
    freq_hz: &[f64],
) -> Result<(Vec<Complex64>, Peak)> {
    scratch.clone_from(model);
    apply(scratch, params, values)?;
    evaluate_model(scratch, ev, freq_hz)
}

/// The response of `model` at `freq_hz` and its global peak (NaN when the magnitude has no finite
/// sample).
fn evaluate_model(
    model: &Model,
    ev: &mut Evaluator,
    freq_hz: &[f64],
) -> Result<(Vec<Complex64>, Peak)> {
    let mut response = vec![Complex64::default(); freq_hz.len()];
    ev.eval(model.system(), &mut response)?;
    let mag: Vec<f64> = response.iter().map(|v| v.norm()).collect();
    let peak = global_peak(freq_hz, &mag).unwrap_or(Peak {
        freq_hz: f64::NAN,
        value: f64::NAN,
    });
    Ok((response, peak))
}

fn header(spec: &Spec, tail: &str) -> String {
    let names: Vec<&str> = spec.params.iter().map(|p| p.spec.as_str()).collect();
    format!("point,{},{tail}\n", names.join(","))
}

fn prefix(p: &Point) -> String {
    let v: Vec<String> = p.values.iter().map(|v| v.to_string()).collect();
    format!("{},{}", p.index, v.join(","))
}

/// Writes the long-format table: one row per point and frequency (magnitude, phase in degrees).
pub fn write_long(spec: &Spec, points: &[Point], w: &mut dyn Write) -> std::io::Result<()> {
    w.write_all(header(spec, "freq_hz,mag,phase_deg").as_bytes())?;
    for p in points {
        let pre = prefix(p);
        for (f, v) in spec.freq_hz.iter().zip(&p.response) {
            writeln!(w, "{pre},{f},{},{}", v.norm(), v.arg().to_degrees())?;
        }
    }
    Ok(())
}

/// Writes the peaks table: one row per point, then the columns of each of `hooks` (the hooks
/// [`run`] was given, in the same order).
pub fn write_peaks(
    spec: &Spec,
    points: &[Point],
    hooks: &[&dyn PointFigures],
    w: &mut dyn Write,
) -> std::io::Result<()> {
    let mut tail = String::from("peak_freq_hz,peak_mag");
    let mut columns = Vec::new();
    for h in hooks {
        for (i, name) in h.names().into_iter().enumerate() {
            tail += ",";
            tail += &name;
            columns.push((*h, i));
        }
    }
    w.write_all(header(spec, &tail).as_bytes())?;
    for p in points {
        write!(w, "{},{},{}", prefix(p), p.peak.freq_hz, p.peak.value)?;
        for ((h, i), v) in columns.iter().zip(&p.extra) {
            write!(w, ",{}", h.format(*i, *v))?;
        }
        writeln!(w)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;
    use crate::response::frf;

    #[test]
    fn grid_is_row_major_and_points_match_the_frf() {
        let model = catalog::resolve("seed001-full").unwrap();
        let spec = Spec {
            params: vec![
                Param::parse("link.cushion.k", &model).unwrap(),
                Param::parse("link.cushion.c", &model).unwrap(),
            ],
            values: vec![vec![18_500.0, 22_500.0], vec![150.0, 200.0, 250.0]],
            response: "t_head".into(),
            freq_hz: frf::grid(1.0, 10.0, 30, false).unwrap(),
        };
        assert_eq!(spec.grid()[1], vec![18_500.0, 200.0]);
        let pts = run(&model, &spec, Shard::default(), &[], &|| {}).unwrap();
        assert_eq!(pts.len(), 6);
        let mut m = model.clone();
        apply(&mut m, &spec.params, &pts[4].values).unwrap();
        let direct = frf::compute(m.system(), &spec.freq_hz).unwrap();
        let r = direct.get("t_head").unwrap();
        for (a, b) in pts[4].response.iter().zip(&r.values) {
            assert!((a - b).norm() < 1e-9);
        }
    }
}
