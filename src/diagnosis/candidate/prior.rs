//! The null candidate's base parameters and their priors (a subject's and a seat's scatter).

use super::*;

/// Bound of the base-parameter re-fit: ±30 % around nominal (physical prior width).
pub const BASE_BOUND: f64 = 1.3;

/// The base parameters re-fitted by the null candidate, `(path, nominal value, quantity)`: the
/// parameters in which a subject and a seat scatter about the model (each model kind says which,
/// [`crate::model::Model::scatter_params`]), those with a non-zero nominal value. A real occupant's
/// masses are never the model's; with `f_seat_z` measured the apparent mass's static limit (the
/// supported mass) pins their sum, otherwise only the prior does.
pub fn base_params(model: &Model) -> Vec<(String, f64, Quantity)> {
    model
        .scatter_params()
        .into_iter()
        .filter_map(|(path, q)| {
            let v = model.get(&path).ok()?;
            (v > 0.0).then_some((path, v, q))
        })
        .collect()
}

/// Standard deviation of the Gaussian prior on ln(value/nominal) of a base parameter: 0.10 for
/// masses, 0.25 for dampers, 0.15 for springs (a subject's and a seat's scatter about the model).
pub fn prior_sigma(q: Quantity) -> f64 {
    match q {
        Quantity::Mass => 0.10,
        Quantity::Damping => 0.25,
        Quantity::Stiffness => 0.15,
    }
}

/// The system of `model` with base parameters scaled by `exp(u)` (rebuilt once).
pub fn scaled(model: &Model, base: &[(String, f64, Quantity)], u: &[f64]) -> Result<System> {
    let values: Vec<(String, f64)> = base
        .iter()
        .zip(u)
        .map(|((path, nominal, _), ui)| (path.clone(), nominal * ui.exp()))
        .collect();
    Ok(model.with_values(&values)?.system().clone())
}
