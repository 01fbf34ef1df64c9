//! One error type for the library: every variant names the file, line, key or parameter at fault and
//! what was expected, so that the command line can print it as a single clear line.

use std::path::Path;

/// Errors of the wbv library. `Display` gives one line suitable for a terminal.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A model definition (TOML) is invalid: `file`, the line where it is known, the dotted `key`
    /// and what was expected.
    #[error("{file}{}: {key}: {message}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Model {
        /// The model file as given.
        file: String,
        /// The line (1-based) of the key at fault, where it is known.
        line: Option<usize>,
        /// The dotted TOML key at fault, e.g. `seat.stiffness`.
        key: String,
        /// What was expected.
        message: String,
    },
    /// A data file (CSV, excitation table, MCAP run) is invalid at a line or record.
    #[error("{file}{}: {message}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Data {
        /// The data file as given.
        file: String,
        /// The 1-based line or record at fault, when one can be named.
        line: Option<usize>,
        /// What was expected.
        message: String,
    },
    /// A parameter given on the command line or through the API is out of its valid range.
    #[error("{parameter}: {message}")]
    Parameter {
        /// The option or field at fault.
        parameter: String,
        /// What was expected.
        message: String,
    },
    /// An operating-system I/O error on a named path.
    #[error("{path}: {source}")]
    Io {
        /// The path the operation failed on.
        path: String,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The work was stopped by SIGINT, SIGTERM or Python's `KeyboardInterrupt`
    /// ([`crate::cancel`]).
    #[error("interrupted during {during}")]
    Interrupted {
        /// What was running.
        during: String,
    },
}

/// Result alias used throughout the crate.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// A parameter error: `parameter` names the option or field, `message` says what was expected.
    pub fn parameter(parameter: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Parameter {
            parameter: parameter.into(),
            message: message.into(),
        }
    }

    /// A data-file error at an optional 1-based line.
    pub fn data(file: impl AsRef<Path>, line: Option<usize>, message: impl Into<String>) -> Self {
        Error::Data {
            file: file.as_ref().display().to_string(),
            line,
            message: message.into(),
        }
    }

    /// An I/O error on `path`.
    pub fn io(path: impl AsRef<Path>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.as_ref().display().to_string(),
            source,
        }
    }
}
