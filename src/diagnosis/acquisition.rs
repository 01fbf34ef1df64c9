//! Which channels share a time base: the data loggers of a rig (docs/gap.md §5, acquisition
//! timing). A field rig often records the base on one logger (the vehicle's or the shaker's) and
//! the seat pad, head and force plate on another; each logger has its own trigger and clock, so a
//! trigger offset or a clock drift acts on *every* channel of the other logger, the force
//! included. The timing candidates ([`super::candidate::sensor::LOGGER_OFFSET`],
//! [`super::candidate::sensor::LOGGER_DRIFT`]) act on the channels [`Loggers::off_base`] returns.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// A transducer of a gap run: an accelerometer (triaxial at the seat and head: one time base for
/// its axes) or the seat-pan force plate. Written in JSON as its vertical channel's name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(into = "&'static str", try_from = "String")]
pub enum Transducer {
    /// The base (floor, platform) accelerometer, `a_base_z`.
    Base,
    /// The seat-pad accelerometer, `a_seat_z` (and `a_seat_x`).
    Seat,
    /// The head accelerometer, `a_head_z` (and `a_head_x`).
    Head,
    /// The seat-pan force plate, `f_seat_z`, and an instrumented backrest's load cells,
    /// `f_back_z`, taken as read through the same conditioning and logger.
    Force,
}

impl Transducer {
    /// Every transducer, in report order.
    pub const ALL: [Transducer; 4] = [
        Transducer::Base,
        Transducer::Seat,
        Transducer::Head,
        Transducer::Force,
    ];

    /// The transducer recording channel `name`, if it is one a gap run reads.
    pub fn of_channel(name: &str) -> Option<Transducer> {
        match name {
            "a_base_z" => Some(Transducer::Base),
            "a_seat_z" | "a_seat_x" => Some(Transducer::Seat),
            "a_head_z" | "a_head_x" => Some(Transducer::Head),
            "f_seat_z" | "f_back_z" => Some(Transducer::Force),
            _ => None,
        }
    }

    /// Its vertical channel's name.
    pub fn channel(self) -> &'static str {
        match self {
            Transducer::Base => "a_base_z",
            Transducer::Seat => "a_seat_z",
            Transducer::Head => "a_head_z",
            Transducer::Force => "f_seat_z",
        }
    }
}

impl From<Transducer> for &'static str {
    fn from(t: Transducer) -> Self {
        t.channel()
    }
}

impl TryFrom<String> for Transducer {
    type Error = String;
    fn try_from(name: String) -> std::result::Result<Self, String> {
        Transducer::of_channel(&name).ok_or_else(|| format!("unknown transducer channel `{name}`"))
    }
}

/// The transducers recorded on another logger than the base accelerometer: the ones a trigger
/// offset or a clock drift between the loggers retimes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct OffBase {
    /// The seat-pad accelerometer.
    pub seat: bool,
    /// The head accelerometer.
    pub head: bool,
    /// The seat-pan force plate.
    pub force: bool,
}

impl OffBase {
    /// Whether any transducer is off the base's logger.
    pub fn any(self) -> bool {
        self.seat || self.head || self.force
    }
}

/// One logger: a name and the transducers it records.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Logger {
    /// The name given with `--logger NAME:…`, or `base` / `occupant` when assumed.
    pub name: String,
    /// What it records (in JSON `channels`, by their vertical channels' names).
    #[serde(rename = "channels")]
    pub transducers: Vec<Transducer>,
}

/// Where a rig's loggers come from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Source {
    /// Stated by the user (`--logger`).
    Stated,
    /// Assumed ([`Loggers::default`]): nothing in the data said otherwise.
    Assumed,
    /// The force plate put on the base's logger because the data say so: the seat and head paths
    /// share a lag of `lag_s` that the force plate's does not ([`Loggers::force_on_base`]).
    Inferred {
        /// The occupant logger's lag behind the base's, s.
        lag_s: f64,
    },
}

/// The rig's loggers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Loggers {
    /// Every logger; the base accelerometer is on exactly one.
    pub loggers: Vec<Logger>,
    /// Whether the user stated them, the diagnosis assumed them or inferred them from the data.
    pub source: Source,
}

impl Default for Loggers {
    /// The assumption when none are stated: the base accelerometer on one logger, the occupant's
    /// transducers on another. A timing effect on the occupant's logger is then the same as a lag
    /// of the base accelerometer of opposite sign, so the assumption also covers a single logger
    /// whose base channel is delayed; a rig with one time base for all simply shows no timing
    /// effect.
    fn default() -> Self {
        Loggers {
            loggers: vec![
                Logger {
                    name: "base".into(),
                    transducers: vec![Transducer::Base],
                },
                Logger {
                    name: "occupant".into(),
                    transducers: vec![Transducer::Seat, Transducer::Head, Transducer::Force],
                },
            ],
            source: Source::Assumed,
        }
    }
}

impl Loggers {
    /// Parses `--logger NAME:CH[,CH…]` values, one per logger, e.g. `base:a_base_z` and
    /// `cab:a_seat_z,a_head_z,f_seat_z`. Every transducer the runs carry must be on exactly one
    /// logger ([`Loggers::check_covers`]); an empty list gives the assumed default.
    pub fn parse(specs: &[String]) -> Result<Loggers> {
        if specs.is_empty() {
            return Ok(Loggers::default());
        }
        let mut loggers: Vec<Logger> = Vec::new();
        for spec in specs {
            let bad = |what: String| Error::parameter("--logger", format!("`{spec}`: {what}"));
            let (name, channels) = spec.split_once(':').ok_or_else(|| {
                bad("expected NAME:CHANNEL[,CHANNEL…], e.g. cab:a_seat_z,a_head_z,f_seat_z".into())
            })?;
            let name = name.trim();
            if name.is_empty() {
                return Err(bad("the logger has no name before `:`".into()));
            }
            if loggers.iter().any(|l| l.name == name) {
                return Err(bad(format!("logger `{name}` is given twice")));
            }
            let mut transducers = Vec::new();
            for ch in channels.split(',').map(str::trim).filter(|c| !c.is_empty()) {
                let t = Transducer::of_channel(ch).ok_or_else(|| {
                    bad(format!(
                        "unknown channel `{ch}` (expected a_base_z, a_seat_z, a_seat_x, a_head_z, a_head_x, f_seat_z or f_back_z)"
                    ))
                })?;
                if let Some(other) = loggers.iter().find(|l| l.transducers.contains(&t)) {
                    return Err(bad(format!(
                        "`{ch}` is already on logger `{}` through its transducer (a triaxial accelerometer's axes, or the seat and backrest force cells, which wbv reads through one conditioning): a transducer has one time base",
                        other.name
                    )));
                }
                if !transducers.contains(&t) {
                    transducers.push(t);
                }
            }
            if transducers.is_empty() {
                return Err(bad("the logger records no channel".into()));
            }
            loggers.push(Logger {
                name: name.to_string(),
                transducers,
            });
        }
        if !loggers
            .iter()
            .any(|l| l.transducers.contains(&Transducer::Base))
        {
            return Err(Error::parameter(
                "--logger",
                "no logger records a_base_z: name the logger of the base accelerometer too",
            ));
        }
        Ok(Loggers {
            loggers,
            source: Source::Stated,
        })
    }

    /// The loggers of a report line [`Loggers::describe`] wrote (the JSON of wbv before the
    /// loggers were written as a structure): `NAME: CH, CH; NAME: CH` and, unless stated, a
    /// parenthesis saying `assumed` or `inferred … by X ms`. `None` for an empty or foreign line.
    pub fn from_description(text: &str) -> Option<Loggers> {
        let (list, note) = match text.split_once(" (") {
            Some((l, n)) => (l, Some(n)),
            None => (text, None),
        };
        let loggers = list
            .split("; ")
            .map(|l| {
                let (name, chans) = l.split_once(": ")?;
                let transducers = chans
                    .split(", ")
                    .map(Transducer::of_channel)
                    .collect::<Option<Vec<_>>>()?;
                Some(Logger {
                    name: name.to_string(),
                    transducers,
                })
            })
            .collect::<Option<Vec<_>>>()?;
        let source = match note {
            None => Source::Stated,
            Some(n) if n.starts_with("inferred") => {
                let ms = n
                    .split(" by ")
                    .nth(1)
                    .and_then(|r| r.split(" ms").next())
                    .and_then(|v| v.parse::<f64>().ok())?;
                let sign = if n.contains(" lead ") { -1.0 } else { 1.0 };
                Source::Inferred {
                    lag_s: sign * ms / 1e3,
                }
            }
            Some(_) => Source::Assumed,
        };
        Some(Loggers { loggers, source })
    }

    /// Whether the user stated the loggers.
    pub fn stated(&self) -> bool {
        self.source == Source::Stated
    }

    /// The assumed rig with the seat-pan force plate on the base accelerometer's logger (a plate
    /// wired to the shaker controller's or the vehicle's logger), inferred from the data with a
    /// lag of `lag_s` on the occupant's logger.
    pub fn force_on_base(lag_s: f64) -> Loggers {
        Loggers {
            loggers: vec![
                Logger {
                    name: "base".into(),
                    transducers: vec![Transducer::Base, Transducer::Force],
                },
                Logger {
                    name: "occupant".into(),
                    transducers: vec![Transducer::Seat, Transducer::Head],
                },
            ],
            source: Source::Inferred { lag_s },
        }
    }

    /// Checks that stated loggers name every transducer in `channels` (the runs' channel names),
    /// so that no channel's time base is silently assumed.
    pub fn check_covers<'a>(&self, channels: impl IntoIterator<Item = &'a str>) -> Result<()> {
        if !self.stated() {
            return Ok(());
        }
        for ch in channels {
            if let Some(t) = Transducer::of_channel(ch)
                && self.logger_of(t).is_none()
            {
                return Err(Error::parameter(
                    "--logger",
                    format!("the runs record `{ch}` but no --logger names it"),
                ));
            }
        }
        Ok(())
    }

    /// The loggers as far as the runs record them: transducers `channels` does not carry left
    /// out, and loggers left with none dropped (so the report does not list a force plate the
    /// runs do not have).
    pub fn recording<'a>(&self, channels: impl IntoIterator<Item = &'a str>) -> Loggers {
        let have: Vec<Transducer> = channels
            .into_iter()
            .filter_map(Transducer::of_channel)
            .collect();
        Loggers {
            loggers: (self.loggers.iter())
                .map(|l| Logger {
                    name: l.name.clone(),
                    transducers: (l.transducers.iter())
                        .filter(|t| have.contains(t))
                        .copied()
                        .collect(),
                })
                .filter(|l| !l.transducers.is_empty())
                .collect(),
            source: self.source,
        }
    }

    /// The logger recording `t`.
    pub fn logger_of(&self, t: Transducer) -> Option<&Logger> {
        self.loggers.iter().find(|l| l.transducers.contains(&t))
    }

    /// The transducers on another logger than the base accelerometer's (a transducer no logger
    /// names is not recorded: [`Loggers::check_covers`]).
    pub fn off_base(&self) -> OffBase {
        let base = self.logger_of(Transducer::Base).map(|l| l.name.as_str());
        let off = |t| {
            self.logger_of(t)
                .is_some_and(|l| Some(l.name.as_str()) != base)
        };
        OffBase {
            seat: off(Transducer::Seat),
            head: off(Transducer::Head),
            force: off(Transducer::Force),
        }
    }

    /// One line for the report: which logger records what.
    pub fn describe(&self) -> String {
        let list = self
            .loggers
            .iter()
            .map(|l| {
                let chans: Vec<&str> = l.transducers.iter().map(|t| t.channel()).collect();
                format!("{}: {}", l.name, chans.join(", "))
            })
            .collect::<Vec<_>>()
            .join("; ");
        match self.source {
            Source::Stated => list,
            Source::Assumed => format!("{list} (assumed; state them with --logger)"),
            Source::Inferred { lag_s } => format!(
                "{list} (inferred: the seat and head {} the base by {:.1} ms and the force plate does not; state them with --logger)",
                if lag_s < 0.0 { "lead" } else { "lag" },
                lag_s.abs() * 1e3
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn specs(s: &[&str]) -> Vec<String> {
        s.iter().map(|x| x.to_string()).collect()
    }

    #[test]
    fn a_cab_logger_puts_seat_head_and_force_off_the_base() {
        let l =
            Loggers::parse(&specs(&["base:a_base_z", "cab:a_seat_z,a_head_z,f_seat_z"])).unwrap();
        assert_eq!(
            l.off_base(),
            OffBase {
                seat: true,
                head: true,
                force: true
            }
        );
        // The force plate on the base's logger is not retimed.
        let l = Loggers::parse(&specs(&["a:a_base_z,f_seat_z", "b:a_seat_z,a_head_z"])).unwrap();
        assert_eq!(
            l.off_base(),
            OffBase {
                seat: true,
                head: true,
                force: false
            }
        );
        // One logger for all: nothing to retime.
        let l = Loggers::parse(&specs(&["all:a_base_z,a_seat_z,a_head_z"])).unwrap();
        assert!(!l.off_base().any());
        assert!(Loggers::default().off_base().any());
    }

    #[test]
    fn an_inferred_rig_puts_the_force_plate_on_the_base_and_says_why() {
        // The same wiring as a rig stated with the plate on the base's logger.
        let l = Loggers::force_on_base(-0.0082);
        let stated =
            Loggers::parse(&specs(&["a:a_base_z,f_seat_z", "b:a_seat_z,a_head_z"])).unwrap();
        assert_eq!(l.off_base(), stated.off_base());
        assert!(!l.stated());
        assert_eq!(
            l.describe(),
            "base: a_base_z, f_seat_z; occupant: a_seat_z, a_head_z (inferred: the seat and head lead the base by 8.2 ms and the force plate does not; state them with --logger)"
        );
    }

    #[test]
    fn the_report_lists_only_the_transducers_the_runs_record() {
        let l = Loggers::default().recording(["time", "a_base_z", "a_seat_z", "a_head_z"]);
        assert_eq!(
            l.describe(),
            "base: a_base_z; occupant: a_seat_z, a_head_z (assumed; state them with --logger)"
        );
        let l = Loggers::force_on_base(0.0031).recording(["a_base_z", "a_seat_z"]);
        assert_eq!(l.loggers.len(), 2);
        assert_eq!(l.loggers[1].transducers, vec![Transducer::Seat]);
        // A seat channel alone on its logger: that logger is dropped when the run lacks it.
        let l = Loggers::parse(&specs(&["a:a_base_z,a_head_z", "b:a_seat_z"])).unwrap();
        assert_eq!(l.recording(["a_base_z", "a_head_z"]).loggers.len(), 1);
    }

    #[test]
    fn loggers_read_back_from_json_and_from_the_report_line_of_earlier_files() {
        let rigs = [
            Loggers::default(),
            Loggers::force_on_base(-0.0082),
            Loggers::force_on_base(0.0031),
            Loggers::parse(&specs(&["rig:a_base_z,f_seat_z", "cab:a_seat_z,a_head_z"])).unwrap(),
        ];
        for l in rigs {
            let json = serde_json::to_string(&l).unwrap();
            assert_eq!(serde_json::from_str::<Loggers>(&json).unwrap(), l, "{json}");
            // The line keeps the lag to 0.1 ms.
            let back = Loggers::from_description(&l.describe()).expect("a report line");
            assert_eq!((&back.loggers, back.describe()), (&l.loggers, l.describe()));
        }
        let json = serde_json::to_value(Loggers::force_on_base(-0.0082)).unwrap();
        assert_eq!(json["loggers"][0]["channels"][1], "f_seat_z");
        assert_eq!(json["source"]["inferred"]["lag_s"], -0.0082);
        assert_eq!(Loggers::from_description(""), None);
        assert_eq!(Loggers::from_description("rig: a_knee_z"), None);
    }

    #[test]
    fn a_channel_on_two_loggers_an_unknown_one_or_a_missing_base_is_refused() {
        let err = |s: &[&str]| Loggers::parse(&specs(s)).unwrap_err().to_string();
        assert!(err(&["a:a_base_z,a_seat_z", "b:a_seat_z"]).contains("already on logger `a`"));
        assert!(err(&["a:a_base_z,a_knee_z"]).contains("unknown channel `a_knee_z`"));
        assert!(err(&["cab:a_seat_z"]).contains("no logger records a_base_z"));
        assert!(err(&["a_base_z"]).contains("expected NAME:CHANNEL"));
        let l = Loggers::parse(&specs(&["a:a_base_z", "b:a_seat_z"])).unwrap();
        let e = l
            .check_covers(["a_base_z", "a_seat_z", "f_seat_z"])
            .unwrap_err()
            .to_string();
        assert!(e.contains("`f_seat_z` but no --logger names it"), "{e}");
    }
}
