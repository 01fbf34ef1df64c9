//! Paper 000 (sagittal segment model with a foam cushion): calibration of the assumed quantities
//! against the paper's modes and Table 4 peaks ([`calibrate`]), and its reproduction-table rows
//! ([`rows`]).

pub mod calibrate;
pub mod rows;
