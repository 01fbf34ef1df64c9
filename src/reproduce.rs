//! The reproduction table of papers 001 and 002 (`docs/reproduction.md`).
