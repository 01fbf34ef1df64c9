//! End-stop contacts of a run: each time a link with an end-stop law passes its free travel.

use crate::error::Result;
use crate::simulate::observer::{Layout, Observer, Step};
use crate::system::{Law, System};
use serde::Serialize;

/// Contact times kept per run (the count is exact; the list stops here).
pub const TIMES_KEPT: usize = 20;

/// The end-stop contacts of one run.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Contacts {
    /// Number of times a stop was struck (a deflection crossing out of the free travel).
    pub count: usize,
    /// When, s (the first [`TIMES_KEPT`]).
    pub times_s: Vec<f64>,
    /// Largest penetration past the free travel, m (0 without contact).
    pub max_overtravel_m: f64,
}

/// An [`Observer`] counting the contacts of every end-stop link of a system.
pub struct ContactObserver {
    /// (link index, free travel m) of each end-stop link.
    stops: Vec<(usize, f64)>,
    inside: Vec<bool>,
    contacts: Contacts,
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
        ContactObserver {
            inside: vec![true; stops.len()],
            stops,
            contacts: Contacts::default(),
        }
    }

    /// Whether the system has end stops.
    pub fn has_stops(&self) -> bool {
        !self.stops.is_empty()
    }

    /// The contacts counted.
    pub fn into_contacts(self) -> Contacts {
        self.contacts
    }
}

impl Observer for ContactObserver {
    fn begin(&mut self, _layout: &Layout) -> Result<()> {
        Ok(())
    }

    fn step(&mut self, step: &Step<'_>) -> Result<()> {
        for ((li, gap), inside) in self.stops.iter().zip(self.inside.iter_mut()) {
            let over = step.link_deflection[*li].abs() - gap;
            let now_inside = over <= 0.0;
            if *inside && !now_inside {
                self.contacts.count += 1;
                if self.contacts.times_s.len() < TIMES_KEPT {
                    self.contacts.times_s.push(step.t);
                }
            }
            if over > self.contacts.max_overtravel_m {
                self.contacts.max_overtravel_m = over;
            }
            *inside = now_inside;
        }
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        Ok(())
    }
}
