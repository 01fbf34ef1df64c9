//! Genetic algorithm of paper 000 §5.2: population 200, 300 generations, intermediate crossover
//! with crossover fraction 0.8, adaptive feasible mutation, elitism — the settings of MATLAB's `ga`
//! that the paper names. Works in normalised coordinates `u ∈ [0, 1]^d`.
//!
//! Choices the paper leaves open (MATLAB defaults where they exist): elite count 5 % of the
//! population; parents by binary tournament; intermediate crossover `c = p₁ + r⊙(p₂ − p₁)`,
//! `r ~ U(0,1)` per gene (ratio 1, so children stay in the box); adaptive feasible mutation moves a
//! parent along a random unit direction by `s·U(0,1)`, shortened to stay feasible, with the step `s`
//! grown ×2 after a generation that improved the best fitness and halved otherwise (bounded to
//! [1e-6, 1]). The random stream is ChaCha8 from `seed`; fitness is evaluated in parallel but the
//! stream is only used serially, so the result does not depend on the thread count.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// GA settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Population size (paper 000: 200).
    pub population: usize,
    /// Generations (paper 000: 300).
    pub generations: usize,
    /// Fraction of non-elite children made by crossover (paper 000: 0.8).
    pub crossover: f64,
    /// Elite children copied unchanged.
    pub elite: usize,
    /// Seed of the ChaCha8 stream.
    pub seed: u64,
}

impl Settings {
    /// Paper 000's settings with `seed`.
    pub fn paper(seed: u64) -> Settings {
        Settings {
            population: 200,
            generations: 300,
            crossover: 0.8,
            elite: 10,
            seed,
        }
    }
}

/// Best point found and how many evaluations it took.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Best normalised coordinates.
    pub u: Vec<f64>,
    /// Its fitness (lower is better).
    pub fitness: f64,
    /// Fitness evaluations.
    pub evaluations: usize,
}

/// Minimises `fitness` over `[0, 1]^dim`; `start` (if any) is put in the initial population.
/// `fitness` runs in parallel with per-job scratch state from `init` and must be a pure function of
/// its argument.
pub fn minimise<S, I, F>(
    dim: usize,
    start: Option<&[f64]>,
    s: Settings,
    init: I,
    fitness: F,
) -> Outcome
where
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, &[f64]) -> f64 + Sync + Send,
{
    let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
    let n = s.population.max(4);
    let elite = s.elite.min(n / 2);
    let mut pop: Vec<Vec<f64>> = (0..n)
        .map(|_| (0..dim).map(|_| rng.random::<f64>()).collect())
        .collect();
    if let Some(st) = start {
        pop[0] = st.iter().map(|v| v.clamp(0.0, 1.0)).collect();
    }
    let eval = |pop: &[Vec<f64>]| -> Vec<f64> {
        pop.par_iter()
            .map_init(&init, |state, u| {
                let f = fitness(state, u);
                if f.is_nan() { f64::INFINITY } else { f }
            })
            .collect()
    };
    let mut fit = eval(&pop);
    let mut evaluations = n;
    let mut step = 1.0f64;
    let mut best = fit.iter().copied().fold(f64::INFINITY, f64::min);
    for _ in 0..s.generations {
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| fit[a].total_cmp(&fit[b]).then(a.cmp(&b)));
        let pick = |rng: &mut ChaCha8Rng| {
            let (a, b) = (rng.random_range(0..n), rng.random_range(0..n));
            if fit[a] <= fit[b] { a } else { b }
        };
        let n_cross = ((n - elite) as f64 * s.crossover).round() as usize;
        let mut next: Vec<Vec<f64>> = order[..elite].iter().map(|&i| pop[i].clone()).collect();
        for k in 0..n - elite {
            let p1 = pick(&mut rng);
            let child = if k < n_cross {
                let p2 = pick(&mut rng);
                (0..dim)
                    .map(|g| pop[p1][g] + rng.random::<f64>() * (pop[p2][g] - pop[p1][g]))
                    .collect()
            } else {
                mutate(&pop[p1], step, &mut rng)
            };
            next.push(child);
        }
        pop = next;
        fit = eval(&pop);
        evaluations += n;
        let now = fit.iter().copied().fold(f64::INFINITY, f64::min);
        step = if now < best {
            (step * 2.0).min(1.0)
        } else {
            (step * 0.5).max(1e-6)
        };
        best = best.min(now);
    }
    let i = (0..n)
        .min_by(|&a, &b| fit[a].total_cmp(&fit[b]))
        .unwrap_or(0);
    Outcome {
        u: pop[i].clone(),
        fitness: fit[i],
        evaluations,
    }
}

/// Adaptive feasible mutation: a random direction, a random length up to `step`, shortened so the
/// child stays in the unit box.
fn mutate(parent: &[f64], step: f64, rng: &mut ChaCha8Rng) -> Vec<f64> {
    let mut d: Vec<f64> = parent
        .iter()
        .map(|_| rng.random::<f64>() * 2.0 - 1.0)
        .collect();
    let norm = d.iter().map(|v| v * v).sum::<f64>().sqrt().max(1e-300);
    d.iter_mut().for_each(|v| *v /= norm);
    let mut t = step * rng.random::<f64>();
    for (p, v) in parent.iter().zip(&d) {
        if *v > 0.0 {
            t = t.min((1.0 - p) / v);
        } else if *v < 0.0 {
            t = t.min(-p / v);
        }
    }
    parent
        .iter()
        .zip(&d)
        .map(|(p, v)| (p + t * v).clamp(0.0, 1.0))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small(seed: u64) -> Settings {
        Settings {
            population: 40,
            generations: 60,
            crossover: 0.8,
            elite: 2,
            seed,
        }
    }

    #[test]
    fn finds_the_minimum_of_a_shifted_bowl_and_is_deterministic() {
        let f = |_: &mut (), u: &[f64]| {
            (u[0] - 0.3).powi(2) + 10.0 * (u[1] - 0.8).powi(2) + (u[2] - 0.05).powi(2)
        };
        let a = minimise(3, None, small(7), || (), f);
        assert!(
            (a.u[0] - 0.3).abs() < 1e-3 && (a.u[1] - 0.8).abs() < 1e-3,
            "{a:?}"
        );
        assert!((a.u[2] - 0.05).abs() < 1e-3, "{a:?}");
        assert_eq!(a, minimise(3, None, small(7), || (), f));
        assert_eq!(a.evaluations, 40 * 61);
    }

    #[test]
    fn mutation_stays_feasible() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..1000 {
            let c = mutate(&[0.99, 0.01], 1.0, &mut rng);
            assert!(c.iter().all(|v| (0.0..=1.0).contains(v)));
        }
    }
}
