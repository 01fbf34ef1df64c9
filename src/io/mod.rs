//! Reading and writing runs as files other tools understand.

pub mod atomic;
pub mod csv_run;
pub mod input;
pub mod mcap_stream;
pub mod memory;
