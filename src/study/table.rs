//! One row of the reproduction table (`docs/reproduction.md`): a paper's headline number next to
//! what wbv computes. Each study adds its rows ([`crate::reproduce`] gathers them).

/// Relative tolerance for "reproduced".
pub const TOLERANCE: f64 = 0.05;

/// One headline number of a paper next to what wbv computes.
#[derive(Debug, Clone)]
pub struct Row {
    /// Paper and place (section, figure, table).
    pub source: String,
    /// The quantity, with the configuration.
    pub quantity: String,
    /// The paper's value.
    pub paper: f64,
    /// wbv's value for the stated model.
    pub wbv: f64,
    /// Unit of both values.
    pub unit: &'static str,
    /// Why it differs (or how it was computed), shown next to the verdict.
    pub note: String,
}

impl Row {
    /// True when wbv's value is within [`TOLERANCE`] of the paper's.
    pub fn reproduced(&self) -> bool {
        (self.wbv - self.paper).abs() <= TOLERANCE * self.paper.abs()
    }
}
