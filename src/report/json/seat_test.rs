//! `wbv seat-test`: the ISO 10326-1 seat test.

use super::{Document, WithFiles, Written};
use crate::error::Result;
use crate::study::seat_test::SeatTests;

/// The document of `wbv seat-test --json` (and of the Python binding's `wbv.seat_test`): the
/// test's keys ([`SeatTests`]: `summary`, `verdict`, `verdict_lines`, `damping`, one entry per
/// class in `classes`, its `units` map) and the report file `written`, if any.
pub fn seat_test(test: &SeatTests, written: Vec<Written>) -> Result<Document> {
    Document::new(
        "seat-test",
        &WithFiles {
            result: test,
            written,
        },
        Vec::new(),
    )
}
