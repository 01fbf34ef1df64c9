//! End-stop contacts of a run: each time a link with an end-stop law passes its free travel, what
//! the impact does at the seat (its peak acceleration and the vibration dose value it adds), and
//! the suspension's travel over the run (its distribution and an envelope against time) for the
//! report.

use crate::analysis::Weighting;
use crate::analysis::filter::{FilterStream, WeightingFilter};
use crate::error::Result;
use crate::simulate::observer::{Layout, Observer, Step};
use crate::system::{Channel, Law, System};
use serde::Serialize;

/// Contact times kept per run in the document (the count is exact; the list stops here).
pub const TIMES_KEPT: usize = 20;

/// How long after the seat leaves the stop an impact's episode lasts, s [choice]: the
/// Wk-weighted seat acceleration of a stop struck at the suspension's ~1.5 Hz rings down in a
/// few tenths of a second (the body's 4–6 Hz mode, damped ~0.3); 0.5 s holds that ringing. The
/// episode's peak seat acceleration and fourth-power dose are the impact's.
pub const IMPACT_TAIL_S: f64 = 0.5;

/// Width of a bar of the travel distribution, a fraction of the free travel.
const BIN_OF_TRAVEL: f64 = 0.025;

/// The distribution spans ± this many free travels.
const SPAN_OF_TRAVEL: f64 = 1.5;

/// The travel envelope's slice, s (two points, minimum and maximum, per slice).
pub const TRACE_SLICE_S: f64 = 0.02;

/// The end-stop contacts of one run.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Contacts {
    /// Number of times a stop was struck (a deflection crossing out of the free travel).
    pub count: usize,
    /// When, s (the first [`TIMES_KEPT`]).
    pub times_s: Vec<f64>,
    /// Largest penetration past the free travel, m (0 without contact).
    pub max_overtravel_m: f64,
    /// Largest absolute (unweighted) seat-surface acceleration during an impact's episode
    /// (contact to [`IMPACT_TAIL_S`] after leaving the stop), m/s² (0 without contact).
    pub peak_seat_acceleration_m_s2: f64,
    /// Mean over the episodes of each one's peak seat acceleration, m/s² (0 without contact).
    pub mean_peak_seat_acceleration_m_s2: f64,
    /// The VDV the impacts add to the run's seat VDV, m/s^1.75 (ISO 2631-1 6.3.2, Wk):
    /// `VDV − (VDV⁴ − ∫_episodes a_w⁴ dt)^¼`, filled by the test from the run's VDV.
    pub vdv_added_m_s1_75: f64,
    /// `∫ a_w⁴ dt` over the episodes, (m/s²)⁴·s (the Wk-weighted seat acceleration, weighted from
    /// rest at the run's start).
    #[serde(skip)]
    pub episode_dose: f64,
    /// Every contact: (time s, +1 for the extension stop, −1 for the compression stop).
    #[serde(skip)]
    pub all: Vec<(f64, f64)>,
    /// The first stop's travel for the report ([`Travel`]).
    #[serde(skip)]
    pub travel: Option<Travel>,
}

/// The travel (deflection) of the first end-stop link over a run, for the report's charts.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Travel {
    /// Free travel either way, m.
    pub free_travel_m: f64,
    /// Lower edge of the first bar of the distribution, m.
    pub hist_from_m: f64,
    /// Width of a bar, m.
    pub bin_m: f64,
    /// Time spent in each bar, s (the ends take everything beyond them).
    pub time_s: Vec<f64>,
    /// Envelope against time: start of each [`TRACE_SLICE_S`] slice, s.
    pub slice_t_s: Vec<f64>,
    /// Smallest deflection in each slice, m.
    pub slice_min_m: Vec<f64>,
    /// Largest deflection in each slice, m.
    pub slice_max_m: Vec<f64>,
}

/// An [`Observer`] counting the contacts of every end-stop link of a system.
pub struct ContactObserver {
    /// (link index, free travel m) of each end-stop link.
    stops: Vec<(usize, f64)>,
    inside: Vec<bool>,
    contacts: Contacts,
    /// The seat-surface acceleration channel and the base influence, when the system has one.
    seat: Option<(Channel, Vec<f64>)>,
    /// Wk weighting of the seat acceleration, made at the second step (its rate is then known).
    wk: Option<FilterStream>,
    t_prev: Option<f64>,
    dt: f64,
    /// Time the current episode ends (`None` outside one) and its peak so far.
    episode: Option<(f64, f64)>,
    peaks: Vec<f64>,
    slice_steps: u64,
}

impl ContactObserver {
    /// Watches the end-stop links of `system` (none: counts nothing).
    pub fn new(system: &System) -> Self {
        let stops: Vec<(usize, f64)> = system
            .links
            .iter()
            .enumerate()
            .filter_map(|(i, l)| match l.law {
                Some(Law::EndStop { gap, .. }) => Some((i, gap)),
                _ => None,
            })
            .collect();
        let travel = stops.first().map(|&(_, gap)| {
            let bins = (2.0 * SPAN_OF_TRAVEL / BIN_OF_TRAVEL).round() as usize;
            Travel {
                free_travel_m: gap,
                hist_from_m: -SPAN_OF_TRAVEL * gap,
                bin_m: BIN_OF_TRAVEL * gap,
                time_s: vec![0.0; bins],
                ..Travel::default()
            }
        });
        let seat = system.channel_index("a_seat_z").map(|i| {
            (
                system.channels[i].clone(),
                system.r.iter().copied().collect(),
            )
        });
        ContactObserver {
            inside: vec![true; stops.len()],
            stops,
            contacts: Contacts {
                travel,
                ..Contacts::default()
            },
            seat,
            wk: None,
            t_prev: None,
            dt: 0.0,
            episode: None,
            peaks: Vec::new(),
            slice_steps: 1,
        }
    }

    /// Whether the system has end stops.
    pub fn has_stops(&self) -> bool {
        !self.stops.is_empty()
    }

    /// The contacts counted.
    pub fn into_contacts(mut self) -> Contacts {
        self.close_episode();
        let c = &mut self.contacts;
        c.peak_seat_acceleration_m_s2 = self.peaks.iter().copied().fold(0.0, f64::max);
        if !self.peaks.is_empty() {
            c.mean_peak_seat_acceleration_m_s2 =
                self.peaks.iter().sum::<f64>() / self.peaks.len() as f64;
        }
        self.contacts
    }

    fn close_episode(&mut self) {
        if let Some((_, peak)) = self.episode.take() {
            self.peaks.push(peak);
        }
    }

    /// The absolute and the Wk-weighted seat acceleration at `step`, m/s².
    fn seat_acceleration(&mut self, step: &Step<'_>) -> Option<(f64, f64)> {
        let (ch, r) = self.seat.as_ref()?;
        let a = ch.value(step.a, step.a_base, r, step.link_force);
        let mut w = [a];
        if let Some(f) = &mut self.wk {
            f.process(&mut w);
        }
        Some((a, w[0]))
    }

    fn track(&mut self, step: &Step<'_>, d: f64) {
        let dt = self.dt;
        let slice = self.slice_steps;
        let Some(tr) = &mut self.contacts.travel else {
            return;
        };
        if dt > 0.0 {
            let k = ((d - tr.hist_from_m) / tr.bin_m).floor();
            let k = k.clamp(0.0, (tr.time_s.len() - 1) as f64) as usize;
            tr.time_s[k] += dt;
        }
        if step.index.is_multiple_of(slice) || tr.slice_t_s.is_empty() {
            tr.slice_t_s.push(step.t);
            tr.slice_min_m.push(d);
            tr.slice_max_m.push(d);
        } else if let (Some(lo), Some(hi)) = (tr.slice_min_m.last_mut(), tr.slice_max_m.last_mut())
        {
            *lo = lo.min(d);
            *hi = hi.max(d);
        }
    }
}

impl Observer for ContactObserver {
    fn begin(&mut self, _layout: &Layout) -> Result<()> {
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        if self.stops.is_empty() {
            return Ok(());
        }
        if let Some(t0) = self.t_prev
            && self.wk.is_none()
            && step.t > t0
        {
            self.dt = step.t - t0;
            self.slice_steps = ((TRACE_SLICE_S / self.dt).round() as u64).max(1);
            // Too coarse a step for the weighting: no weighted dose (it stays 0).
            self.wk = WeightingFilter::new(Weighting::Wk, 1.0 / self.dt)
                .ok()
                .map(|f| f.stream());
        }
        self.t_prev = Some(step.t);
        let seat = self.seat_acceleration(step);
        let mut struck = false;
        let mut touching = false;
        for ((li, gap), inside) in self.stops.iter().zip(self.inside.iter_mut()) {
            let d = step.link_deflection[*li];
            let over = d.abs() - gap;
            let now_inside = over <= 0.0;
            if *inside && !now_inside {
                self.contacts.count += 1;
                self.contacts.all.push((step.t, d.signum()));
                if self.contacts.times_s.len() < TIMES_KEPT {
                    self.contacts.times_s.push(step.t);
                }
                struck = true;
            }
            touching |= !now_inside;
            if over > self.contacts.max_overtravel_m {
                self.contacts.max_overtravel_m = over;
            }
            *inside = now_inside;
        }
        if let Some(&(li, _)) = self.stops.first() {
            self.track(step, step.link_deflection[li]);
        }
        if struck && self.episode.is_none() {
            self.episode = Some((step.t, 0.0));
        }
        if let Some((end, peak)) = &mut self.episode {
            if touching {
                *end = step.t + IMPACT_TAIL_S;
            }
            if let Some((a, aw)) = seat {
                *peak = peak.max(a.abs());
                self.contacts.episode_dose += aw.powi(4) * self.dt;
            }
            if step.t >= *end {
                self.close_episode();
            }
        }
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        Ok(())
    }
}

/// The VDV the impacts add to a run whose seat VDV is `vdv` m/s^1.75, with `episode_dose` the
/// fourth-power dose of their episodes: `VDV − (VDV⁴ − dose)^¼` (0 when the dose is 0; the dose
/// is clamped to the VDV's own, the two being weighted from slightly different starts).
pub fn vdv_added(vdv: f64, episode_dose: f64) -> f64 {
    if !(vdv.is_finite() && episode_dose > 0.0) {
        return 0.0;
    }
    let total = vdv.powi(4);
    vdv - (total - episode_dose.min(total)).powf(0.25)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_vdv_added_is_what_removing_the_dose_takes_away() {
        // VDV 2: dose 16; an episode of dose 15 leaves 1, VDV 1: 1 added.
        assert!((vdv_added(2.0, 15.0) - 1.0).abs() < 1e-12);
        assert_eq!(vdv_added(2.0, 0.0), 0.0);
        // All of it: everything added.
        assert!((vdv_added(2.0, 16.0) - 2.0).abs() < 1e-12);
        assert!((vdv_added(2.0, 20.0) - 2.0).abs() < 1e-12);
    }
}
