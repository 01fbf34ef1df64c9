//! `wbv gap`: the sim-to-real gap diagnosis.

use super::{Document, WithFiles, Written};
use crate::error::Result;

/// The document of `wbv gap --json`: the diagnosis `d` ([`crate::diagnosis::report::json`], whose
/// `warnings` are the diagnosis's own) and the plot files `written`.
pub fn gap(d: &crate::diagnosis::Diagnosis, written: Vec<Written>) -> Result<Document> {
    let body = WithFiles {
        result: crate::diagnosis::report::json(d),
        written,
    };
    Document::new("gap", &body, Vec::new())
}
