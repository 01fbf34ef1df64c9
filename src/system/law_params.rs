//! The named parameters of every nonlinear [`Law`]: the one vocabulary that model files
//! (`[link.law]`, docs/models.md), parameter paths (`link.<name>.<key>`) and the written corrected
//! model of the gap diagnosis share, so that any law a candidate puts on a link can be written to a
//! file and read back into the same system.

use super::Law;

/// What values a law parameter may take (checked when a file or a parameter path sets it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Range {
    /// A finite number > 0.
    Positive,
    /// A finite number ≥ 0.
    NonNegative,
    /// A finite number ≥ 1 (an exponent of a stiffening power law).
    AtLeastOne,
}

impl Range {
    /// Whether `v` is allowed.
    pub fn allows(self, v: f64) -> bool {
        v.is_finite()
            && match self {
                Range::Positive => v > 0.0,
                Range::NonNegative => v >= 0.0,
                Range::AtLeastOne => v >= 1.0,
            }
    }

    /// The allowed range in words, for error messages (`> 0`, `≥ 0`).
    pub fn words(self) -> &'static str {
        match self {
            Range::Positive => "> 0",
            Range::NonNegative => "≥ 0",
            Range::AtLeastOne => "≥ 1",
        }
    }
}

/// One parameter of a law: its key in a model file and a parameter path, its unit and range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LawParam {
    /// Key in `[link.law]` and last part of the path `link.<name>.<key>`.
    pub key: &'static str,
    /// SI unit.
    pub unit: &'static str,
    /// Allowed values.
    pub range: Range,
}

const fn p(key: &'static str, unit: &'static str, range: Range) -> LawParam {
    LawParam { key, unit, range }
}

use Range::{AtLeastOne, NonNegative, Positive};

/// Every law's model-file word and parameters, in [`Law`]'s order: the table [`Law::word`],
/// [`Law::params`], [`Law::values`] and [`Law::from_values`] read.
pub const LAWS: &[(&str, &[LawParam])] = &[
    ("cubic", &[p("k3", "N/m³", NonNegative)]),
    ("softening", &[p("d_ref", "m", Positive)]),
    (
        "friction",
        &[p("f_c", "N", NonNegative), p("v_ref", "m/s", Positive)],
    ),
    (
        "end-stop",
        &[p("gap", "m", Positive), p("k_stop", "N/m", Positive)],
    ),
    ("contact", &[p("d0", "m", Positive)]),
    ("exponential", &[p("d0", "m", Positive)]),
    (
        "bilinear",
        &[p("d_knee", "m", Positive), p("ratio", "1", Positive)],
    ),
    (
        "bottoming",
        &[p("gap", "m", Positive), p("k_stop", "N/m", Positive)],
    ),
    (
        "hertz-stop",
        &[p("gap", "m", NonNegative), p("k_h", "N/m^1.5", Positive)],
    ),
    ("lift-off", &[p("travel", "m", Positive)]),
    ("hertz-pad", &[p("travel", "m", Positive)]),
    ("preload-exp", &[p("d_e", "m", Positive)]),
    (
        "power-foam",
        &[p("sag", "m", Positive), p("n", "1", AtLeastOne)],
    ),
];

impl Law {
    /// Position of this law in [`LAWS`].
    fn index(&self) -> usize {
        match self {
            Law::Cubic { .. } => 0,
            Law::Softening { .. } => 1,
            Law::Friction { .. } => 2,
            Law::EndStop { .. } => 3,
            Law::Contact { .. } => 4,
            Law::Exponential { .. } => 5,
            Law::Bilinear { .. } => 6,
            Law::Bottoming { .. } => 7,
            Law::HertzStop { .. } => 8,
            Law::LiftOff { .. } => 9,
            Law::HertzPad { .. } => 10,
            Law::PreloadExp { .. } => 11,
            Law::PowerFoam { .. } => 12,
        }
    }

    /// The law's word in a model file (`type` of `[link.law]`).
    pub fn word(&self) -> &'static str {
        LAWS[self.index()].0
    }

    /// The law's parameters, in the order of [`Law::values`].
    pub fn params(&self) -> &'static [LawParam] {
        LAWS[self.index()].1
    }

    /// Mutable references to the law's parameter values, in [`Law::params`] order.
    pub fn values_mut(&mut self) -> Vec<&mut f64> {
        match self {
            Law::Cubic { k3 } => vec![k3],
            Law::Softening { d_ref } => vec![d_ref],
            Law::Friction { f_c, v_ref } => vec![f_c, v_ref],
            Law::EndStop { gap, k_stop } | Law::Bottoming { gap, k_stop } => vec![gap, k_stop],
            Law::Contact { d0 } | Law::Exponential { d0 } => vec![d0],
            Law::Bilinear { d_knee, ratio } => vec![d_knee, ratio],
            Law::HertzStop { gap, k_h } => vec![gap, k_h],
            Law::LiftOff { travel } | Law::HertzPad { travel } => vec![travel],
            Law::PreloadExp { d_e } => vec![d_e],
            Law::PowerFoam { sag, n } => vec![sag, n],
        }
    }

    /// The law's parameter values, in [`Law::params`] order.
    pub fn values(&self) -> Vec<f64> {
        let mut l = *self;
        l.values_mut().into_iter().map(|v| *v).collect()
    }

    /// The law called `word` with parameter `values` in the order of its [`LAWS`] entry; `None`
    /// for an unknown word or a wrong number of values (ranges are the caller's to check).
    pub fn from_values(word: &str, values: &[f64]) -> Option<Law> {
        let at = |i: usize| values[i];
        let (_, params) = LAWS.iter().find(|(w, _)| *w == word)?;
        if params.len() != values.len() {
            return None;
        }
        Some(match word {
            "cubic" => Law::Cubic { k3: at(0) },
            "softening" => Law::Softening { d_ref: at(0) },
            "friction" => Law::Friction {
                f_c: at(0),
                v_ref: at(1),
            },
            "end-stop" => Law::EndStop {
                gap: at(0),
                k_stop: at(1),
            },
            "contact" => Law::Contact { d0: at(0) },
            "exponential" => Law::Exponential { d0: at(0) },
            "bilinear" => Law::Bilinear {
                d_knee: at(0),
                ratio: at(1),
            },
            "bottoming" => Law::Bottoming {
                gap: at(0),
                k_stop: at(1),
            },
            "hertz-stop" => Law::HertzStop {
                gap: at(0),
                k_h: at(1),
            },
            "lift-off" => Law::LiftOff { travel: at(0) },
            "hertz-pad" => Law::HertzPad { travel: at(0) },
            "preload-exp" => Law::PreloadExp { d_e: at(0) },
            "power-foam" => Law::PowerFoam {
                sag: at(0),
                n: at(1),
            },
            _ => return None,
        })
    }

    /// The model-file words of every law, for error messages.
    pub fn words() -> String {
        LAWS.iter().map(|(w, _)| *w).collect::<Vec<_>>().join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One law of each kind with distinct parameter values.
    fn every_law() -> Vec<Law> {
        vec![
            Law::Cubic { k3: 1.0e7 },
            Law::Softening { d_ref: 0.01 },
            Law::Friction {
                f_c: 40.0,
                v_ref: 0.02,
            },
            Law::EndStop {
                gap: 0.03,
                k_stop: 5.0e5,
            },
            Law::Contact { d0: 0.02 },
            Law::Exponential { d0: 0.015 },
            Law::Bilinear {
                d_knee: 0.004,
                ratio: 0.5,
            },
            Law::Bottoming {
                gap: 0.006,
                k_stop: 2.0e5,
            },
            Law::HertzStop {
                gap: 0.005,
                k_h: 3.0e6,
            },
            Law::LiftOff { travel: 0.002 },
            Law::HertzPad { travel: 0.003 },
            Law::PreloadExp { d_e: 0.02 },
            Law::PowerFoam { sag: 0.01, n: 2.5 },
        ]
    }

    #[test]
    fn every_law_has_one_word_and_reads_back_from_its_values() {
        let laws = every_law();
        assert_eq!(laws.len(), LAWS.len(), "a law missing from the test");
        let mut words: Vec<&str> = laws.iter().map(Law::word).collect();
        words.sort_unstable();
        words.dedup();
        assert_eq!(words.len(), LAWS.len(), "two laws share a word");
        for l in laws {
            assert_eq!(l.values().len(), l.params().len(), "{}", l.word());
            assert_eq!(Law::from_values(l.word(), &l.values()), Some(l));
        }
        assert_eq!(Law::from_values("cubic", &[1.0, 2.0]), None);
        assert_eq!(Law::from_values("quartic", &[1.0]), None);
    }
}
