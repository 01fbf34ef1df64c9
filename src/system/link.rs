//! Constitutive laws of the spring–damper links between masses.
//!
//! Sign convention: a link joins an upper node `a` to a lower node `b` (a mass or the base). Its
//! deflection is `d = x_a − x_b` in m (positive = extension) and its rate `v = ẋ_a − ẋ_b` in m/s. The
//! link force `f` in N is the tension: it pulls `a` down with `−f` and `b` up with `+f`. Nonlinear laws
//! act on the dynamic deflection about the static (seated) equilibrium, where they are tangent to the
//! linear element, so that the frequency-domain responses are the small-amplitude linearisation.

use num_complex::Complex64;

/// The linear viscoelastic element of a link.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Element {
    /// Spring `k` (N/m) in parallel with dashpot `c` (N·s/m): `f = k·d + c·v`.
    KelvinVoigt {
        /// Parallel spring stiffness, N/m.
        k: f64,
        /// Parallel dashpot coefficient, N·s/m.
        c: f64,
    },
    /// Spring `k` (N/m) in series with dashpot `c` (N·s/m): `ḟ = k·(v − f/c)`; no static stiffness.
    Maxwell {
        /// Stiffness of the spring in series with the dashpot, N/m.
        k: f64,
        /// Coefficient of the dashpot in series with the spring, N·s/m.
        c: f64,
    },
    /// Standard linear solid: spring `k` (N/m) in parallel with a Maxwell arm (`k_m` N/m in series
    /// with `c_m` N·s/m): `f = k·d + q`, `q̇ = k_m·(v − q/c_m)`.
    Zener {
        /// Equilibrium (static) spring stiffness in parallel with the Maxwell arm, N/m.
        k: f64,
        /// Stiffness of the Maxwell arm's spring, N/m.
        k_m: f64,
        /// Coefficient of the Maxwell arm's dashpot, N·s/m.
        c_m: f64,
    },
}

impl Element {
    /// Complex dynamic stiffness `F/D` at angular frequency `omega` (rad/s), in N/m.
    ///
    /// Kelvin–Voigt `k + iωc`; Maxwell `k·iωc/(k + iωc)`; Zener `k + k_m·iωc_m/(k_m + iωc_m)`.
    pub fn dynamic_stiffness(&self, omega: f64) -> Complex64 {
        let series = |k: f64, c: f64| {
            let iwc = Complex64::new(0.0, omega * c);
            if c == 0.0 {
                Complex64::new(0.0, 0.0)
            } else {
                k * iwc / (k + iwc)
            }
        };
        match *self {
            Element::KelvinVoigt { k, c } => Complex64::new(k, omega * c),
            Element::Maxwell { k, c } => series(k, c),
            Element::Zener { k, k_m, c_m } => Complex64::new(k, 0.0) + series(k_m, c_m),
        }
    }

    /// Stiffness with every dashpot locked (the instantaneous or "glassy" stiffness), in N/m. Used for
    /// the undamped modes: for a Kelvin–Voigt link it is `k`, for a Maxwell link `k`, for Zener
    /// `k + k_m`.
    pub fn locked_stiffness(&self) -> f64 {
        match *self {
            Element::KelvinVoigt { k, .. } | Element::Maxwell { k, .. } => k,
            Element::Zener { k, k_m, .. } => k + k_m,
        }
    }

    /// Static stiffness (every dashpot free), in N/m: `k` for Kelvin–Voigt and Zener, 0 for Maxwell.
    pub fn static_stiffness(&self) -> f64 {
        match *self {
            Element::KelvinVoigt { k, .. } | Element::Zener { k, .. } => k,
            Element::Maxwell { .. } => 0.0,
        }
    }

    /// Parallel (Kelvin–Voigt) damping coefficient in N·s/m; series dashpots live in internal states.
    pub fn parallel_damping(&self) -> f64 {
        match *self {
            Element::KelvinVoigt { c, .. } => c,
            _ => 0.0,
        }
    }

    /// The relaxing arm `(k_m, c_m)` that carries an internal force state, if any.
    pub fn relaxing_arm(&self) -> Option<(f64, f64)> {
        match *self {
            Element::KelvinVoigt { .. } => None,
            Element::Maxwell { k, c } => Some((k, c)),
            Element::Zener { k_m, c_m, .. } => Some((k_m, c_m)),
        }
    }

    /// Stiffness of the spring acting in parallel with `d` (not through an internal state), in N/m.
    pub fn parallel_stiffness(&self) -> f64 {
        match *self {
            Element::KelvinVoigt { k, .. } | Element::Zener { k, .. } => k,
            Element::Maxwell { .. } => 0.0,
        }
    }
}

/// A nonlinear law added to a Kelvin–Voigt link. Each is tangent to the linear element at `d = v = 0`
/// except `Friction`, whose smoothed tangent `f_c/v_ref` adds viscous damping at rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// Hardening spring: extra force `k3·d³`, `k3` in N/m³ (foam that stiffens as it is compressed).
    Cubic {
        /// Cubic stiffness coefficient of the hardening term `k3·d³`, N/m³.
        k3: f64,
    },
    /// Saturating (softening) spring: the linear spring force `k·d` becomes `k·d_ref·tanh(d/d_ref)`,
    /// `d_ref` in m; the stiffness falls as amplitude grows.
    Softening {
        /// Reference deflection of the `tanh` saturation, m; the force saturates at `k·d_ref`.
        d_ref: f64,
    },
    /// Smoothed Coulomb friction: extra force `f_c·tanh(v/v_ref)`, `f_c` in N, `v_ref` in m/s.
    Friction {
        /// Coulomb (sliding) friction force amplitude, N.
        f_c: f64,
        /// Smoothing rate of the `tanh` regularisation, m/s; the tangent at rest is `f_c/v_ref` N·s/m.
        v_ref: f64,
    },
    /// End stop: beyond a free travel `gap` (m) either way a contact spring `k_stop` (N/m) engages:
    /// extra force `k_stop·(|d| − gap)·sign(d)` for `|d| > gap`.
    EndStop {
        /// Free travel either side of the static equilibrium before the stop engages, m.
        gap: f64,
        /// Contact stiffness of the stop once engaged, N/m.
        k_stop: f64,
    },
    /// Quadratic contact stiffening: the spring force `k·d` becomes `k·d·(1 + |d|/d0)`, `d0` in m
    /// (foam whose contact area grows with deflection). Used by the gap bench's truth forms.
    Contact {
        /// Deflection at which the contact stiffening doubles the spring force, m.
        d0: f64,
    },
    /// Exponential stiffening: the spring force `k·d` becomes `k·d0·sinh(d/d0)`, `d0` in m (tangent
    /// `k·cosh(d/d0)`). Used by the gap bench's truth forms.
    Exponential {
        /// Characteristic deflection of the `sinh` stiffening, m.
        d0: f64,
    },
    /// Bilinear softening: stiffness `k` for `|d| ≤ d_knee` (m), `ratio·k` beyond. Used by the gap
    /// bench's truth forms.
    Bilinear {
        /// Deflection magnitude at the knee where the stiffness changes, m.
        d_knee: f64,
        /// Stiffness beyond the knee as a fraction of `k` (dimensionless; < 1 softens).
        ratio: f64,
    },
    /// Bottoming (compression-only stop): past a free travel `gap` (m) of compression beyond the
    /// static equilibrium a second, stiffer layer `k_stop` (N/m) touches: extra force
    /// `k_stop·(d + gap)` for `d < −gap`, none in extension. A seat foam that bottoms out on its
    /// pan or a denser layer under the occupant's preload stiffens on one side only (docs/gap.md §5).
    Bottoming {
        /// Free compression travel past the static equilibrium before the second layer touches, m.
        gap: f64,
        /// Stiffness of the second (bottoming) layer once touched, N/m.
        k_stop: f64,
    },
    /// A denser layer touching `gap` (m) of compression past the static equilibrium, with
    /// Hertzian contact: extra force `−k_h·(−d − gap)^(3/2)` for `d < −gap` (`k_h` in N/m^1.5),
    /// none in extension. A foam bottoming on a second layer, smooth where `Bottoming`'s stop
    /// steps (Johnson, *Contact Mechanics*, 1985, eq. 4.23). Used by the gap bench's truth forms.
    HertzStop {
        /// Free compression travel past the static equilibrium before the denser layer touches, m.
        gap: f64,
        /// Hertzian contact coefficient of the `(−d − gap)^(3/2)` force, N/m^1.5 (Johnson 1985, eq. 4.23).
        k_h: f64,
    },
    /// A preloaded contact that can separate (feet on a floor, a heel pad): linear about its
    /// static compression until the contact force k·travel it carries at rest is used up, then no
    /// force at all: `f = min(k·d + c·v, k·travel)`, `travel` in m of extension (d > 0) before it
    /// lifts off. Stiffness and damping both vanish while it is off, so the path carries less the
    /// larger the motion.
    LiftOff {
        /// Extension past the static equilibrium at which the preloaded contact unloads, m (the
        /// static compression of the contact).
        travel: f64,
    },
    /// A preloaded Hertzian pad that can separate (Johnson, *Contact Mechanics*, 1985, eq. 4.23):
    /// contact force ∝ (travel − d)^(3/2), so the deviation about rest is
    /// `f = (2/3)·k·travel·[1 − (1 − d/travel)^(3/2)]` with tangent `k·√(1 − d/travel)` (k at
    /// rest), damping `c·(1 − d/travel)^(3/2)` (Hunt & Crossley, J. Appl. Mech. 42 (1975) 440:
    /// damping with the contact force's own power of the compression), and `f = (2/3)·k·travel`
    /// once off (d ≥ travel). Used by the gap bench's truth forms.
    HertzPad {
        /// Extension past the static equilibrium at which the pad unloads, m (its static
        /// compression).
        travel: f64,
    },
    /// Preloaded exponential foam about its static sag: the spring force `k·d` becomes
    /// `k·d_e·(1 − e^(−d/d_e))`, `d_e` in m (tangent `k·e^(−d/d_e)`): the deviation about the sag of
    /// a foam force `F₀(e^(D/d_e) − 1)` in the total compression D (Deng, Davies & Bajaj 2003
    /// [W13]), stiffer in compression, softer in extension. Used by the gap bench's truth forms.
    PreloadExp {
        /// Characteristic compression of the exponential foam law, m (Deng, Davies & Bajaj 2003 [W13]).
        d_e: f64,
    },
    /// A preloaded foam whose force is a power of its total compression, F = F₀·(D/D₀)ⁿ, about its
    /// static sag D₀ (m), with F₀ = k·D₀/n so that it is tangent to `k` at rest: the deviation
    /// `f = min(F₀·[1 − (1 − d/D₀)ⁿ] + c·v, F₀)`: tangent `k·(1 − d/D₀)^(n−1)` and damping `c`
    /// while the foam pushes on the occupant, and no force at all once it would pull (risen past
    /// the sag, or leaving it faster than it relaxes: the preload F₀ used up). For n > 1 it is stiffer in compression and softer in extension,
    /// the asymmetry of a foam loaded by the body's weight (the power law of a flexible foam's
    /// densifying compression, Gibson & Ashby, *Cellular Solids*, 2nd ed. 1997, §5.3).
    PowerFoam {
        /// Static compression of the foam under the occupant, m.
        sag: f64,
        /// Exponent of the force's power law in the compression (≥ 1; 1 is linear up to lift-off).
        n: f64,
    },
}

impl Law {
    /// Force and tangents `(f, ∂f/∂d, ∂f/∂v)` of the parallel part of a Kelvin–Voigt link with spring
    /// `k` and dashpot `c` under this law, at deflection `d` and rate `v`.
    pub fn force(&self, k: f64, c: f64, d: f64, v: f64) -> (f64, f64, f64) {
        match *self {
            Law::Cubic { k3 } => (k * d + k3 * d * d * d + c * v, k + 3.0 * k3 * d * d, c),
            Law::Softening { d_ref } => {
                let th = (d / d_ref).tanh();
                (k * d_ref * th + c * v, k * (1.0 - th * th), c)
            }
            Law::Friction { f_c, v_ref } => {
                let th = (v / v_ref).tanh();
                (
                    k * d + c * v + f_c * th,
                    k,
                    c + f_c / v_ref * (1.0 - th * th),
                )
            }
            Law::EndStop { gap, k_stop } => {
                let over = d.abs() - gap;
                if over > 0.0 {
                    (k * d + c * v + k_stop * over * d.signum(), k + k_stop, c)
                } else {
                    (k * d + c * v, k, c)
                }
            }
            Law::Contact { d0 } => (
                k * d * (1.0 + d.abs() / d0) + c * v,
                k * (1.0 + 2.0 * d.abs() / d0),
                c,
            ),
            Law::Exponential { d0 } => {
                // Capped argument keeps a diverging Newton trial finite (cosh(60) ≈ 6e25).
                let x = (d / d0).clamp(-60.0, 60.0);
                (k * d0 * x.sinh() + c * v, k * x.cosh(), c)
            }
            Law::Bottoming { gap, k_stop } => {
                let over = d + gap;
                if over < 0.0 {
                    (k * d + c * v + k_stop * over, k + k_stop, c)
                } else {
                    (k * d + c * v, k, c)
                }
            }
            Law::HertzStop { gap, k_h } => {
                let over = -d - gap;
                if over > 0.0 {
                    let r = over.sqrt();
                    (k * d + c * v - k_h * over * r, k + 1.5 * k_h * r, c)
                } else {
                    (k * d + c * v, k, c)
                }
            }
            Law::LiftOff { travel } => {
                let f = k * d + c * v;
                if f < k * travel {
                    (f, k, c)
                } else {
                    (k * travel, 0.0, 0.0)
                }
            }
            Law::HertzPad { travel } => {
                let r = (1.0 - d / travel).max(0.0).sqrt();
                let (f0, r3) = (2.0 / 3.0 * k * travel, r * r * r);
                (
                    f0 * (1.0 - r3) + c * r3 * v,
                    k * r - 1.5 * c * v * r / travel,
                    c * r3,
                )
            }
            Law::PreloadExp { d_e } => {
                // Capped argument as for `Exponential` (compression is d < 0).
                let e = (-d / d_e).clamp(-60.0, 60.0).exp();
                (k * d_e * (1.0 - e) + c * v, k * e, c)
            }
            Law::PowerFoam { sag, n } => {
                // The foam pushes while its force F₀·restⁿ − c·v is positive: the deviation is
                // the smaller of its contact law and F₀ (as `LiftOff`'s), continuous at lift-off.
                let f0 = k * sag / n;
                let rest = (1.0 - d / sag).max(0.0);
                let tangent = k * rest.powf(n - 1.0);
                let f = f0 * (1.0 - rest * tangent / k) + c * v;
                if f < f0 {
                    (f, tangent, c)
                } else {
                    (f0, 0.0, 0.0)
                }
            }
            Law::Bilinear { d_knee, ratio } => {
                if d.abs() <= d_knee {
                    (k * d + c * v, k, c)
                } else {
                    let f = k * (d_knee + ratio * (d.abs() - d_knee)) * d.signum();
                    (f + c * v, ratio * k, c)
                }
            }
        }
    }

    /// Exact Gaussian mean of the stiffness `E[∂f/∂d]` (N/m) for a zero-mean Gaussian deflection of
    /// r.m.s. `sigma` (m), for the laws whose tangent steps where a stop touches: `EndStop`
    /// `k + k_stop·P(|d| > gap) = k + k_stop·erfc(gap/(σ√2))`, `Bottoming`
    /// `k + k_stop·P(d < −gap) = k + k_stop·erfc(gap/(σ√2))/2`, `LiftOff`
    /// `k·P(d < travel) = k·(1 − erfc(travel/(σ√2))/2)`. A quadrature on a fixed grid is
    /// piecewise constant in `gap` for these, so a fit could not move the gap; `None` for the
    /// smooth laws (their quadrature is accurate and smooth).
    pub fn gaussian_stiffness(&self, k: f64, sigma: f64) -> Option<f64> {
        let exceed = |gap: f64| {
            if sigma > 0.0 {
                libm::erfc(gap / (sigma * std::f64::consts::SQRT_2))
            } else {
                0.0
            }
        };
        match *self {
            Law::EndStop { gap, k_stop } => Some(k + k_stop * exceed(gap)),
            Law::Bottoming { gap, k_stop } => Some(k + 0.5 * k_stop * exceed(gap)),
            Law::LiftOff { travel } => Some(k * (1.0 - 0.5 * exceed(travel))),
            _ => None,
        }
    }

    /// Gaussian-equivalent stiffness and damping `(k_eq, c_eq)` of this law on a Kelvin–Voigt link
    /// of spring `k` and dashpot `c`, for independent zero-mean Gaussian deflection of r.m.s.
    /// `sigma_d` (m) and rate of r.m.s. `sigma_v` (m/s): `k_eq = E[∂f/∂d]`, `c_eq = E[∂f/∂v]`, the
    /// mean-square-optimal linear link under stationary Gaussian response (Atalik & Utku, Earthquake
    /// Eng. Struct. Dyn. 4 (1976) 411–420; Roberts & Spanos, *Random Vibration and Statistical
    /// Linearization*, 1990, §5.3). The stops' stiffness is the closed form of
    /// [`Law::gaussian_stiffness`], so a fitted gap moves it smoothly; the rest by quadrature.
    pub fn equivalent(&self, k: f64, c: f64, sigma_d: f64, sigma_v: f64) -> (f64, f64) {
        let k_eq = self
            .gaussian_stiffness(k, sigma_d)
            .unwrap_or_else(|| gauss_mean(sigma_d, |d| self.force(k, c, d, 0.0).1));
        let c_eq = gauss_mean(sigma_v, |v| self.force(k, c, 0.0, v).2);
        (k_eq, c_eq)
    }

    /// Small-amplitude tangent `(∂f/∂d, ∂f/∂v)` at rest, used by the frequency-domain responses.
    pub fn tangent_at_rest(&self, k: f64, c: f64) -> (f64, f64) {
        let (_, kd, cv) = self.force(k, c, 0.0, 0.0);
        (kd, cv)
    }
}

/// Expectation of `g(σ·z)` for z ~ N(0, 1), trapezoid rule on |z| ≤ 6 with step 0.01 (error
/// < 1e-8 for smooth integrands, ≤ 0.01·φ for a step such as an end-stop's).
fn gauss_mean(sigma: f64, g: impl Fn(f64) -> f64) -> f64 {
    const N: usize = 1201;
    const H: f64 = 12.0 / (N - 1) as f64;
    // Weights normalised to sum to one, so constants are reproduced exactly; computed once (the
    // gap diagnosis's fits call this per link, per run and per iteration).
    static WEIGHTS: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    let w = WEIGHTS.get_or_init(|| {
        let raw: Vec<f64> = (0..N)
            .map(|i| {
                let z = -6.0 + i as f64 * H;
                (if i == 0 || i == N - 1 { 0.5 } else { 1.0 }) * (-0.5 * z * z).exp()
            })
            .collect();
        let den: f64 = raw.iter().sum();
        raw.iter().map(|x| x / den).collect()
    });
    w.iter()
        .enumerate()
        .map(|(i, wi)| wi * g(sigma * (-6.0 + i as f64 * H)))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maxwell_limits() {
        let e = Element::Maxwell { k: 1e4, c: 100.0 };
        // Low frequency: dashpot dominates, F/D → iωc. High frequency: spring dominates, → k.
        let lo = e.dynamic_stiffness(1e-3);
        assert!((lo.im - 1e-3 * 100.0).abs() < 1e-6 && lo.re.abs() < 1e-6);
        let hi = e.dynamic_stiffness(1e7);
        assert!((hi.re - 1e4).abs() / 1e4 < 1e-6);
    }

    #[test]
    fn zener_between_its_static_and_glassy_stiffness() {
        let e = Element::Zener {
            k: 1e4,
            k_m: 2e4,
            c_m: 300.0,
        };
        assert!((e.dynamic_stiffness(0.0).re - 1e4).abs() < 1e-9);
        assert!((e.dynamic_stiffness(1e8).re - 3e4).abs() < 1e-2);
    }

    #[test]
    fn bottoming_acts_in_compression_past_its_gap_only() {
        // Closed form: f = k d + c v + k_stop·min(0, d + gap); tangent k (+ k_stop when touching).
        let law = Law::Bottoming {
            gap: 0.002,
            k_stop: 1e5,
        };
        let (k, c) = (5e4, 300.0);
        assert_eq!(law.tangent_at_rest(k, c), (k, c));
        // Extension and compression inside the gap: the linear element alone.
        assert_eq!(law.force(k, c, 0.01, 0.0).0, k * 0.01);
        assert_eq!(law.force(k, c, -0.0019, 0.0).0, -k * 0.0019);
        // 1 mm past the gap in compression: −k·3 mm − k_stop·1 mm = −150 N − 100 N.
        let (f, kd, _) = law.force(k, c, -0.003, 0.0);
        assert!((f + 250.0).abs() < 1e-9, "{f}");
        assert_eq!(kd, k + 1e5);
    }

    #[test]
    fn stop_laws_gaussian_stiffness_is_the_exceedance_probability() {
        // With gap = σ: P(|z| > 1) = 0.317310507862914 (two-sided), half of it one-sided.
        let (k, gap, k_stop) = (1e4, 0.002, 1e6);
        let two = Law::EndStop { gap, k_stop }
            .gaussian_stiffness(k, gap)
            .unwrap();
        let one = Law::Bottoming { gap, k_stop }
            .gaussian_stiffness(k, gap)
            .unwrap();
        assert!((two - (k + k_stop * 0.317310507862914)).abs() < 1e-9 * two);
        assert!((one - (k + k_stop * 0.158655253931457)).abs() < 1e-9 * one);
        // At rest the stop does not touch; smooth laws defer to quadrature.
        assert_eq!(
            Law::Bottoming { gap, k_stop }.gaussian_stiffness(k, 0.0),
            Some(k)
        );
        assert_eq!(Law::Cubic { k3: 1e9 }.gaussian_stiffness(k, gap), None);
    }

    #[test]
    fn a_lifting_contact_carries_its_preload_and_no_more() {
        let (k, c, travel) = (4e4, 200.0, 0.003);
        let law = Law::LiftOff { travel };
        // In contact: the linear link; the contact force k·travel − f stays ≥ 0.
        assert_eq!(law.force(k, c, 0.001, 0.1), (k * 0.001 + c * 0.1, k, c));
        assert_eq!(law.force(k, c, -0.01, 0.0), (-k * 0.01, k, c));
        // Off (f would exceed the preload): the preload released, no stiffness, no damping.
        assert_eq!(law.force(k, c, 0.004, 0.0), (k * travel, 0.0, 0.0));
        assert_eq!(law.force(k, c, 0.002, 0.6), (k * travel, 0.0, 0.0));
        // Gaussian mean stiffness k·P(d < travel): at σ = travel, Φ(1) = 0.841344746068543.
        let g = law.gaussian_stiffness(k, travel).unwrap();
        assert!((g / (k * 0.841344746068543) - 1.0).abs() < 1e-12, "{g}");
        assert_eq!(law.gaussian_stiffness(k, 0.0), Some(k));
    }

    #[test]
    fn a_hertzian_pad_softens_as_it_unloads_and_lifts_off() {
        let (k, c, travel) = (4e4, 200.0, 0.003);
        let law = Law::HertzPad { travel };
        // At rest: the linear link's tangents.
        assert_eq!(law.tangent_at_rest(k, c), (k, c));
        // The contact force F(d) = F0·(1 − d/travel)^(3/2), F0 = (2/3)·k·travel (so that its
        // tangent at rest is k), against the deviation F0 − F(d), computed from F directly.
        let f0 = 2.0 / 3.0 * k * travel;
        for d in [-0.004, -0.001, 0.0, 0.0015, 0.0029] {
            let contact = f0 * (1.0 - d / travel).powf(1.5);
            let got = law.force(k, 0.0, d, 0.0).0;
            assert!((got - (f0 - contact)).abs() < 1e-9 * f0, "d {d}: {got}");
        }
        // Off: the preload released, nothing else.
        assert_eq!(law.force(k, c, 0.005, 0.3), (f0, 0.0, 0.0));
    }

    #[test]
    fn preload_exponential_is_the_foam_law_about_its_sag() {
        // F(D) = F0 (e^(D/d_e) − 1) with tangent k at the sag D0: F(D0 + x) − F(D0) = k d_e (e^(x/d_e) − 1)
        // for a compression x = −d; checked against F evaluated directly.
        let (k, d_e, w): (f64, f64, f64) = (5e4, 0.02, 700.0);
        let f0 = k * d_e - w; // tangent k at the sag and F(D0) = w
        let d0 = d_e * (1.0 + w / f0).ln();
        let foam = |dd: f64| f0 * ((dd / d_e).exp() - 1.0);
        let law = Law::PreloadExp { d_e };
        for d in [-0.006, -0.001, 0.0, 0.002, 0.008] {
            let want = -(foam(d0 - d) - foam(d0));
            let got = law.force(k, 0.0, d, 0.0).0;
            assert!((got - want).abs() < 1e-9 * w, "d {d}: {got} vs {want}");
        }
        assert_eq!(law.tangent_at_rest(k, 0.0), (k, 0.0));
    }

    #[test]
    fn law_tangents_match_finite_differences() {
        let laws = [
            Law::Cubic { k3: 1e9 },
            Law::Softening { d_ref: 0.004 },
            Law::Friction {
                f_c: 20.0,
                v_ref: 0.01,
            },
            Law::EndStop {
                gap: 0.002,
                k_stop: 1e6,
            },
            Law::Contact { d0: 0.004 },
            Law::Exponential { d0: 0.004 },
            Law::Bilinear {
                d_knee: 0.002,
                ratio: 0.5,
            },
            Law::Bottoming {
                gap: 0.002,
                k_stop: 1e5,
            },
            Law::PreloadExp { d_e: 0.004 },
            Law::HertzPad { travel: 0.004 },
            Law::HertzStop {
                gap: 0.002,
                k_h: 3e7,
            },
        ];
        for law in laws {
            for &(d, v) in &[(0.0011, 0.02), (-0.0031, -0.005), (0.005, 0.0)] {
                let (_, kd, cv) = law.force(5e4, 300.0, d, v);
                let h = 1e-8;
                let fd = (law.force(5e4, 300.0, d + h, v).0 - law.force(5e4, 300.0, d - h, v).0)
                    / (2.0 * h);
                let fv = (law.force(5e4, 300.0, d, v + h).0 - law.force(5e4, 300.0, d, v - h).0)
                    / (2.0 * h);
                assert!(
                    (kd - fd).abs() <= 1e-5 * kd.abs().max(1.0),
                    "{law:?} {kd} {fd}"
                );
                assert!(
                    (cv - fv).abs() <= 1e-4 * cv.abs().max(1.0),
                    "{law:?} {cv} {fv}"
                );
            }
        }
    }

    #[test]
    fn cubic_equivalent_stiffness_is_k_plus_3k3_sigma2() {
        // E[k + 3 k3 d²] = k + 3 k3 σ² exactly for Gaussian d.
        let (k, k3, s) = (8e4, 2e9, 0.003);
        let (ke, ce) = Law::Cubic { k3 }.equivalent(k, 500.0, s, 0.1);
        assert!((ke - (k + 3.0 * k3 * s * s)).abs() < 1e-6 * ke, "{ke}");
        assert!((ce - 500.0).abs() < 1e-9, "{ce}");
    }

    #[test]
    fn end_stop_equivalent_stiffness_is_k_plus_k_stop_times_exceedance() {
        // ∂F/∂d = k + k_stop·1{|d|>gap}; E = k + k_stop·P(|d| > gap) = k + k_stop·erfc(gap/(σ√2)).
        // With gap = σ: P(|z| > 1) = 0.317310507862914.
        let stop = Law::EndStop {
            gap: 0.002,
            k_stop: 1e6,
        };
        let (ke, _) = stop.equivalent(1e4, 0.0, 0.002, 0.1);
        let expect = 1e4 + 1e6 * 0.317310507862914;
        assert!((ke - expect).abs() < 1e-2 * expect, "{ke} vs {expect}");
    }
}
