//! Nonlinear distortion located by its growth with magnitude (docs/gap.md §2 rows 3–5 and 13, §4:
//! "magnitude dependence for distortion").
//!
//! On a linear path the incoherent part of the output is noise: relative to the coherent response
//! it stays put (noise in proportion to the signal) or falls (a fixed noise floor) as the
//! magnitude A rises. A nonlinearity's distortion grows faster than the coherent response (a
//! quadratic term's power goes as A⁴ against A²), so the noise-to-signal ratio (1 − γ²)/γ² of every
//! path that crosses it rises with magnitude. A preloaded or bottoming foam or end-stops raise it
//! on base→seat and leave seat→head and the apparent mass alone (their input is the seat's own
//! motion); a softening body raises it on seat→head and the apparent mass too. Coulomb friction's
//! share of the force falls as the magnitude rises, so its distortion need not grow
//! ([`super::candidate::Candidate::distortion_grows`]).
//!
//! The candidates are statistically linearised, and a one-sided foam's best linear approximation
//! barely moves: the mean deflection shifts until E[f(d)] = 0, and for `k·d_e·(1 − e^(−d/d_e))` that
//! makes E[f′(d)] = k exactly — what the runs show is distortion, not a stiffer FRF. So the
//! distortion is evidence of its own: it says which group of candidates may be named.

use super::candidate::{Candidate, Place};
use super::measure::{MIN_COHERENCE, Path, RunSpectra, h1_sigma};
use crate::numeric::median;
use num_complex::Complex64;
use serde::{Deserialize, Serialize};

/// Rise of the noise-to-signal ratio (dB, lowest to highest magnitude) a path must show to count
/// as distorting. Linear paths on the truth bench stay within ±0.6 dB (median over bins; 60
/// cases of every linear family, proportional noise 0.5–3 %); a quadratic distortion over a 3:1
/// magnitude range gives ≈ 20·log10(3) = 9.5 dB.
pub const MIN_RISE_DB: f64 = 3.0;
/// Least exponent e of NSR ∝ A^(2e) for a distorting path (0: linear with proportional noise,
/// < 0: a fixed noise floor, ≈ 1: quadratic distortion).
pub const MIN_EXPONENT: f64 = 0.3;
/// Least ratio of the highest to the lowest run magnitude for the comparison to mean anything.
pub const MIN_MAGNITUDE_RATIO: f64 = 1.3;
/// A body path rising with a distorting base→seat puts the nonlinearity in the occupant when its
/// rise is at least this share of base→seat's and this many dB. A nonlinearity in the occupant
/// distorts seat→head about as much as base→seat (measured share 0.35–1.0); one between base and
/// seat leaves the body linear, so seat→head's incoherent share stays or falls (≤ 0: −0.1 to
/// −6.5 dB while base→seat rose 3.6–16 dB), except where a bottoming foam's impacts ring the body
/// (0.12–0.47). The ranges overlap; the share is set to keep the occupant's.
pub const BODY_SHARE: (f64, f64) = (0.3, 1.5);
/// Spread of a linear path's rise, dB: linear paths on the truth bench stay within ±0.6 dB (see
/// [`MIN_RISE_DB`]). A body path falling further contradicts a nonlinearity in the occupant, which
/// raises the incoherent share of every path that crosses it (a fault on one channel, a dropout or a
/// spike train, can raise one path's alone).
pub const LINEAR_SPREAD_DB: f64 = 0.6;
/// Frequency range compared, Hz: the body and cushion modes and their low harmonics.
pub const BAND_HZ: (f64, f64) = (1.0, 40.0);
/// Least share of base→seat's phase move with magnitude that a body path's must reach for a
/// distortion to be placed in the occupant. A nonlinearity in the body changes its statistically
/// linearised modes, which seat→head and the apparent mass show in full and base→seat only
/// through the body's load on the cushion: on 13 blind softening cases the body path's phase moved
/// 1.5–2.1 times base→seat's. One under the seat leaves the body's response to the seat's own
/// motion unchanged; incoherent seat content (a bottoming foam's impacts) biases the modulus of
/// H1 by a real factor and not its phase (0.2–0.5 of base→seat's, two cases near 1).
pub const BODY_PHASE_SHARE: f64 = 0.7;

/// One path's distortion trend.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PathDistortion {
    /// Path name.
    #[serde(deserialize_with = "super::json::path")]
    pub path: super::json::Name,
    /// Median over the bins in [`BAND_HZ`] of the rise of the noise-to-signal ratio (1 − γ²)/γ²
    /// from the lowest- to the highest-magnitude run, dB.
    #[serde(deserialize_with = "super::json::f64")]
    pub rise_db: f64,
    /// Exponent e of NSR ∝ A^(2e) between those runs: `rise_db / (20·log10(A_hi/A_lo))`.
    #[serde(deserialize_with = "super::json::f64")]
    pub exponent: f64,
    /// Whether the ratio rises at every step of magnitude (with three or more runs, one drifting
    /// run cannot make a trend).
    pub monotone: bool,
    /// R.m.s. over the bins coherent (γ² ≥ 0.8) in both runs of the change of the phase of H1 from
    /// the lowest- to the highest-magnitude run, its random error taken out, degrees
    /// ([`phase_move`]); NaN without such bins.
    #[serde(default = "nan", deserialize_with = "super::json::f64")]
    pub phase_move_deg: f64,
}

/// NaN, for a number an earlier file did not write.
fn nan() -> f64 {
    f64::NAN
}

impl PathDistortion {
    /// Whether this path shows distortion growing with magnitude.
    pub fn distorts(&self) -> bool {
        self.rise_db >= MIN_RISE_DB && self.exponent >= MIN_EXPONENT && self.monotone
    }
}

/// Where a nonlinearity sits, from which paths distort.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Site {
    /// Between base and seat (cushion, suspension): base→seat distorts, the body paths do not.
    Support,
    /// In the occupant: seat→head or the apparent mass distorts.
    Body,
    /// Base→seat distorts and no body path was measured.
    Unlocated,
}

impl Site {
    /// Whether candidate `c` is a nonlinearity at this site.
    pub fn admits(self, c: Candidate) -> bool {
        match self {
            Site::Support => matches!(c.nonlinear_at(), Some(Place::Support | Place::SeatToBody)),
            Site::Body => matches!(c.nonlinear_at(), Some(Place::Body | Place::SeatToBody)),
            Site::Unlocated => c.amplitude_dependent(),
        }
    }

    /// Whether `system` already holds a nonlinear law at this site: on a seat link (cushion,
    /// suspension, frame) for the support, on a body link for the occupant, anywhere where the
    /// site is not located. A model with its own law there distorts the runs as they do.
    pub fn modelled_in(self, system: &crate::system::System) -> bool {
        use crate::system::Role;
        system
            .links
            .iter()
            .filter(|l| l.law.is_some())
            .any(|l| match self {
                Site::Support => matches!(l.role, Role::Cushion | Role::Suspension | Role::Frame),
                Site::Body => l.role == Role::Body,
                Site::Unlocated => true,
            })
    }

    /// Words for reports.
    pub fn describe(self) -> &'static str {
        match self {
            Site::Support => "between base and seat (cushion or suspension)",
            Site::Body => "in the occupant",
            Site::Unlocated => "between base and seat or in the occupant (no body path measured)",
        }
    }
}

/// The distortion trend of every path over the runs.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Distortion {
    /// Lowest and highest run magnitude compared, m/s² r.m.s.
    #[serde(deserialize_with = "super::json::f64_pair")]
    pub magnitudes: (f64, f64),
    /// Per path measured in every run.
    pub paths: Vec<PathDistortion>,
    /// Where the nonlinearity sits, when a path distorts.
    pub site: Option<Site>,
    /// A body path whose distortion rose in step with base→seat's but whose phase did not move
    /// with magnitude ([`BODY_PHASE_SHARE`]): the reason the occupant was not the site.
    #[serde(default, deserialize_with = "super::json::optional_path")]
    pub phase_stays: Option<super::json::Name>,
    /// Whether the model under diagnosis already holds a nonlinear law at [`Distortion::site`]
    /// ([`Site::modelled_in`]): the growth is then what the model itself predicts, not evidence of
    /// an unmodelled effect (a corrected model diagnosed on the runs it came from).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub site_in_model: bool,
}

impl Distortion {
    /// The site of a nonlinearity the model does not hold: [`Distortion::site`] unless the model
    /// already has a law there ([`Distortion::site_in_model`]).
    pub fn unmodelled_site(&self) -> Option<Site> {
        self.site.filter(|_| !self.site_in_model)
    }
}

/// Mean ln NSR of path `p` in `r` around each frequency of `grid` (within ± `half` Hz: the
/// coarsest run's bins, so runs of other lengths or rates compare on one grid); `None` where `r`
/// has no bin there. Coherence is clamped to [1e-4, 1 − 1e-6] so a perfectly coherent or empty bin
/// stays finite. Bins, not bands, are compared: distortion products land where the input is weak
/// (a road spectrum's upper bands), which one-third-octave bands would weigh like any other.
fn levels(r: &RunSpectra, p: Path, grid: &[f64], half: f64) -> Option<Vec<Option<f64>>> {
    let e = r.path(p)?;
    Some(
        grid.iter()
            .map(|&f| {
                mean(near(r, f, half).map(|b| {
                    let g = e.coherence[b].clamp(1e-4, 1.0 - 1e-6);
                    ((1.0 - g) / g).ln()
                }))
            })
            .collect(),
    )
}

/// The bins of `r` within ± `half` Hz of `f`: one grid point of [`levels`] and [`responses`].
fn near(r: &RunSpectra, f: f64, half: f64) -> impl Iterator<Item = usize> + '_ {
    (0..r.freq_hz.len()).filter(move |&b| (r.freq_hz[b] - f).abs() <= half)
}

/// Mean of the values, `None` for none.
fn mean<T: std::iter::Sum<T> + std::ops::Div<f64, Output = T>>(
    v: impl Iterator<Item = T>,
) -> Option<T> {
    let v: Vec<T> = v.collect();
    let n = v.len() as f64;
    (n > 0.0).then(|| v.into_iter().sum::<T>() / n)
}

/// Mean H1 and coherence of path `p` in `r` around each frequency of `grid` (as [`levels`]).
fn responses(
    r: &RunSpectra,
    p: Path,
    grid: &[f64],
    half: f64,
) -> Option<Vec<Option<(Complex64, f64)>>> {
    let e = r.path(p)?;
    Some(
        grid.iter()
            .map(|&f| {
                Some((
                    mean(near(r, f, half).map(|b| e.h1[b]))?,
                    mean(near(r, f, half).map(|b| e.coherence[b]))?,
                ))
            })
            .collect(),
    )
}

/// How far the phase of path `p`'s H1 moves from run `lo` to run `hi`, degrees: the r.m.s. of
/// arg(H_hi/H_lo) over the grid bins coherent in both, with the mean square of its random error
/// σ² = σ_lo² + σ_hi² (σ from [`h1_sigma`], Bendat & Piersol Table 9.6) subtracted, so that a path
/// that does not change reads about 0 whatever its coherence. NaN without coherent bins.
fn phase_move(lo: &RunSpectra, hi: &RunSpectra, p: Path, grid: &[f64], half: f64) -> f64 {
    let (Some(a), Some(b)) = (responses(lo, p, grid, half), responses(hi, p, grid, half)) else {
        return f64::NAN;
    };
    let (mut change, mut noise, mut n) = (0.0, 0.0, 0usize);
    for (x, y) in a.iter().zip(&b) {
        let (Some((ha, ca)), Some((hb, cb))) = (x, y) else {
            continue;
        };
        if *ca < MIN_COHERENCE || *cb < MIN_COHERENCE || ha.norm() == 0.0 {
            continue;
        }
        change += (hb / ha).arg().powi(2);
        noise += h1_sigma(*ca, lo.segments).powi(2) + h1_sigma(*cb, hi.segments).powi(2);
        n += 1;
    }
    if n == 0 {
        return f64::NAN;
    }
    ((change - noise).max(0.0) / n as f64).sqrt().to_degrees()
}

/// The distortion trend over `runs` (any order; compared in order of magnitude), or `None` with
/// fewer than two runs or a magnitude range under [`MIN_MAGNITUDE_RATIO`]. Call it on the raw
/// estimates, before incoherent paths are masked.
pub fn trend(runs: &[&RunSpectra]) -> Option<Distortion> {
    let mut rs: Vec<&RunSpectra> = runs.to_vec();
    rs.sort_by(|a, b| a.base_rms.total_cmp(&b.base_rms));
    let (lo, hi) = (rs.first()?.base_rms, rs.last()?.base_rms);
    if rs.len() < 2 || lo.is_nan() || lo <= 0.0 || hi / lo < MIN_MAGNITUDE_RATIO {
        return None;
    }
    let db = 10.0 / std::f64::consts::LN_10;
    let coarse = rs.iter().max_by(|a, b| a.df_hz.total_cmp(&b.df_hz))?;
    let grid: Vec<f64> = coarse
        .freq_hz
        .iter()
        .copied()
        .filter(|f| (BAND_HZ.0..=BAND_HZ.1).contains(f))
        .collect();
    let half = 0.5 * coarse.df_hz * 1.001;
    let paths: Vec<PathDistortion> = Path::ALL
        .iter()
        .filter_map(|&p| {
            let levels: Vec<Vec<Option<f64>>> = rs
                .iter()
                .map(|r| levels(r, p, &grid, half))
                .collect::<Option<_>>()?;
            // Median over the bins every run has of the level change between two runs.
            let step = |a: usize, b: usize| {
                median(
                    (0..levels[a].len())
                        .filter_map(|n| Some(levels[b][n]? - levels[a][n]?))
                        .collect(),
                )
            };
            let rise = step(0, rs.len() - 1)? * db;
            let monotone = (1..rs.len()).all(|i| step(i - 1, i).is_some_and(|s| s > 0.0));
            Some(PathDistortion {
                path: p.name(),
                rise_db: rise,
                exponent: rise / (20.0 * (hi / lo).log10()),
                monotone,
                phase_move_deg: phase_move(rs[0], rs[rs.len() - 1], p, &grid, half),
            })
        })
        .collect();
    let of = |p: Path| paths.iter().find(|d| d.path == p.name());
    let seat = of(Path::BaseSeat).filter(|d| d.distorts());
    // With base→seat distorting, a body path must rise in step with it (a softening body's
    // distortion is generated at the body–seat interface and shows on both; a cushion's leaves
    // seat→head flat or falling, its input being the seat's own motion, and a bottoming layer's
    // impacts ring the body a little) and its phase must move with magnitude as base→seat's does
    // ([`BODY_PHASE_SHARE`]; NaN, no coherent bins, does not object); without, a body path that
    // distorts on its own.
    let rises_in_step = |d: &PathDistortion| match seat {
        Some(s) => d.monotone && d.rise_db >= BODY_SHARE.1.max(BODY_SHARE.0 * s.rise_db),
        None => d.distorts(),
    };
    let follows = |d: &PathDistortion| {
        seat.is_none_or(|s| {
            d.phase_move_deg
                .partial_cmp(&(BODY_PHASE_SHARE * s.phase_move_deg))
                != Some(std::cmp::Ordering::Less)
        })
    };
    let body = |p: Path| of(p).is_some_and(|d| rises_in_step(d) && follows(d));
    let measured = |p: Path| of(p).is_some();
    let falls = |p: Path| of(p).is_some_and(|d| d.rise_db < -LINEAR_SPREAD_DB);
    // The occupant only when the body paths agree: one rising and another falling is not a
    // nonlinearity both cross.
    let in_body = (body(Path::SeatHead) || body(Path::ApparentMass))
        && !falls(Path::SeatHead)
        && !falls(Path::ApparentMass);
    let site = if in_body {
        Some(Site::Body)
    } else if seat.is_some() {
        Some(
            if measured(Path::SeatHead) || measured(Path::ApparentMass) {
                Site::Support
            } else {
                Site::Unlocated
            },
        )
    } else {
        None
    };
    let phase_stays = (site != Some(Site::Body))
        .then(|| {
            [Path::SeatHead, Path::ApparentMass]
                .into_iter()
                .filter_map(of)
                .find(|d| rises_in_step(d) && !follows(d))
                .map(|d| d.path)
        })
        .flatten();
    Some(Distortion {
        magnitudes: (lo, hi),
        paths,
        site,
        phase_stays,
        site_in_model: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnosis::measure::PathEstimate;
    use num_complex::Complex64;

    /// A run whose paths have the given constant coherence on 0.25 Hz bins from 0.5 to 50 Hz.
    fn run(rms: f64, coh: &[(Path, f64)]) -> RunSpectra {
        let unit: Vec<(Path, f64, f64)> = coh.iter().map(|&(p, g)| (p, g, 0.0)).collect();
        phased(rms, &unit)
    }

    /// As [`run`], each path's H1 a unit phasor at the given phase (degrees) on every bin.
    fn phased(rms: f64, coh: &[(Path, f64, f64)]) -> RunSpectra {
        let freq_hz: Vec<f64> = (2..=200).map(|i| 0.25 * i as f64).collect();
        let paths = coh
            .iter()
            .map(|&(path, g, deg)| PathEstimate {
                path,
                h1: vec![Complex64::from_polar(1.0, deg.to_radians()); freq_hz.len()],
                coherence: vec![g; freq_hz.len()],
                quadrature: Vec::new(),
            })
            .collect();
        RunSpectra::closed_form(&format!("run at {rms}"), freq_hz, rms, paths)
    }

    /// NSR for a coherence γ²: (1 − γ²)/γ²; the coherence that gives `nsr`.
    fn coh(nsr: f64) -> f64 {
        1.0 / (1.0 + nsr)
    }

    #[test]
    fn quadratic_distortion_on_the_seat_path_locates_the_support() {
        // NSR ∝ A² on base→seat (exponent 1), constant on seat→head: a nonlinear cushion.
        let runs: Vec<RunSpectra> = [0.5, 1.0, 1.5]
            .iter()
            .map(|&a| {
                run(
                    a,
                    &[
                        (Path::BaseSeat, coh(0.01 * (a / 0.5f64).powi(2))),
                        (Path::SeatHead, coh(0.01)),
                    ],
                )
            })
            .collect();
        let d = trend(&runs.iter().collect::<Vec<_>>()).unwrap();
        let bs = &d.paths[0];
        // Closed form: 10·log10(NSR ratio) = 10·log10(9) = 9.54 dB, e = 1.
        assert!((bs.rise_db - 10.0 * 9f64.log10()).abs() < 0.05, "{bs:?}");
        assert!((bs.exponent - 1.0).abs() < 0.01 && bs.monotone);
        assert!(!d.paths[1].distorts());
        assert_eq!(d.site, Some(Site::Support));
        use crate::diagnosis::candidate::{softening, stiffening, support, viscoelastic};
        assert!(Site::Support.admits(&stiffening::CUSHION_BOTTOMING));
        assert!(!Site::Body.admits(&stiffening::CUSHION_BOTTOMING));
        assert!(!Site::Support.admits(&viscoelastic::CUSHION_VISCOELASTIC));
        // A strap from the seat frame to a body mass is beside the cushion: either site.
        for strap in [&support::HARNESS, &support::LAP_BELT] {
            assert!(Site::Support.admits(strap) && Site::Body.admits(strap));
        }
        let softening = &softening::BODY_SOFTENING_MAGNITUDE;
        assert!(Site::Body.admits(softening) && !Site::Support.admits(softening));
    }

    #[test]
    fn a_fixed_noise_floor_or_a_drifting_middle_run_is_not_distortion() {
        // Fixed floor: NSR ∝ A⁻² (coherence improves with magnitude).
        let floor: Vec<RunSpectra> = [0.5, 1.5]
            .iter()
            .map(|&a| run(a, &[(Path::BaseSeat, coh(0.05 * (0.5 / a).powi(2)))]))
            .collect();
        let d = trend(&floor.iter().collect::<Vec<_>>()).unwrap();
        assert!(d.paths[0].rise_db < -9.0 && d.site.is_none());
        // One drifting run in the middle: rises then falls, not a trend.
        let drift: Vec<RunSpectra> = [(0.5, 0.01), (1.0, 0.2), (1.5, 0.05)]
            .iter()
            .map(|&(a, n)| run(a, &[(Path::BaseSeat, coh(n)), (Path::SeatHead, coh(0.01))]))
            .collect();
        let d = trend(&drift.iter().collect::<Vec<_>>()).unwrap();
        assert!(d.paths[0].rise_db > MIN_RISE_DB && !d.paths[0].monotone);
        assert!(d.site.is_none());
    }

    #[test]
    fn body_distortion_and_an_unmeasured_body_and_a_narrow_magnitude_range() {
        let body: Vec<RunSpectra> = [0.5, 1.5]
            .iter()
            .map(|&a| {
                let n = coh(0.01 * (a / 0.5f64).powi(2));
                run(a, &[(Path::BaseSeat, n), (Path::SeatHead, n)])
            })
            .collect();
        assert_eq!(
            trend(&body.iter().collect::<Vec<_>>()).unwrap().site,
            Some(Site::Body)
        );
        let seat_only: Vec<RunSpectra> = [0.5, 1.5]
            .iter()
            .map(|&a| run(a, &[(Path::BaseSeat, coh(0.01 * (a / 0.5f64).powi(2)))]))
            .collect();
        assert_eq!(
            trend(&seat_only.iter().collect::<Vec<_>>()).unwrap().site,
            Some(Site::Unlocated)
        );
        let narrow = [run(1.0, &[]), run(1.2, &[])];
        assert!(trend(&narrow.iter().collect::<Vec<_>>()).is_none());
    }

    #[test]
    fn a_body_path_rising_in_step_with_the_seat_path_is_the_body() {
        // Base→seat NSR ×9 (9.5 dB); seat→head ×2 (3.0 dB ≥ 0.3 × 9.5 = 2.9): the body. With
        // seat→head ×1.8 (2.6 dB, under 2.9 dB): the support.
        let site = |head: f64| {
            let runs: Vec<RunSpectra> = [(0.5, 1.0, 1.0), (1.5, 9.0, head)]
                .iter()
                .map(|&(a, s, h)| {
                    run(
                        a,
                        &[
                            (Path::BaseSeat, coh(0.01 * s)),
                            (Path::SeatHead, coh(0.01 * h)),
                        ],
                    )
                })
                .collect();
            trend(&runs.iter().collect::<Vec<_>>()).unwrap().site
        };
        assert_eq!(site(2.0), Some(Site::Body));
        assert_eq!(site(1.8), Some(Site::Support));
    }

    #[test]
    fn body_paths_that_disagree_do_not_place_the_nonlinearity_in_the_occupant() {
        // The apparent mass's NSR ×9 (a channel fault can do that) while seat→head's falls ×0.5
        // (−3 dB, beyond a linear path's ±0.6 dB): not the occupant. With seat→head flat: the body.
        let site = |head: f64| {
            let runs: Vec<RunSpectra> = [(0.5, 1.0), (1.5, head)]
                .iter()
                .map(|&(a, h)| {
                    let m = coh(0.01 * (a / 0.5f64).powi(2));
                    run(
                        a,
                        &[
                            (Path::BaseSeat, coh(0.01)),
                            (Path::SeatHead, coh(0.01 * h)),
                            (Path::ApparentMass, m),
                        ],
                    )
                })
                .collect();
            trend(&runs.iter().collect::<Vec<_>>()).unwrap().site
        };
        assert_eq!(site(0.5), None);
        assert_eq!(site(1.0), Some(Site::Body));
    }

    #[test]
    fn a_body_path_whose_phase_stays_put_does_not_place_the_nonlinearity_in_the_occupant() {
        // Base→seat NSR ×9 and its phase 4° later at the higher magnitude; seat→head NSR ×4 (6 dB,
        // in step) with its phase moving 0° (a linear body behind a bottoming foam), 2° (half) or
        // 6° (1.5×, a softening body).
        let site = |head_deg: f64| {
            let runs: Vec<RunSpectra> = [(0.5, 1.0, 0.0, 1.0, 0.0), (1.5, 9.0, 4.0, 4.0, head_deg)]
                .iter()
                .map(|&(a, s, sd, h, hd)| {
                    phased(
                        a,
                        &[
                            (Path::BaseSeat, coh(0.01 * s), sd),
                            (Path::SeatHead, coh(0.001 * h), hd),
                        ],
                    )
                })
                .collect();
            trend(&runs.iter().collect::<Vec<_>>()).unwrap()
        };
        let d = site(0.0);
        // Closed form: arg(H_hi/H_lo) = 4° on every bin; its random error over 59 averages at
        // NSR 0.01 and 0.09, √((0.01 + 0.09)/(2·59)) = 1.67°, comes off in quadrature:
        // √(4² − 1.67²) = 3.63°.
        let bs = &d.paths[0];
        assert!((bs.phase_move_deg - 3.63).abs() < 0.02, "{bs:?}");
        assert_eq!(d.paths[1].phase_move_deg, 0.0);
        assert_eq!(d.site, Some(Site::Support));
        assert_eq!(site(2.0).site, Some(Site::Support));
        assert_eq!(site(6.0).site, Some(Site::Body));
    }
}
