//! Error types of the app layer and their exit codes.

use std::path::PathBuf;
use thiserror::Error;

/// A semantic error in user input: which field, and why it is rejected. This is the
/// workspace's one validation shape, [`mbd_core::InvalidField`]: library configurations and app
/// configurations reject fields with the same type and the same messages.
pub use mbd_core::InvalidField as InputError;

/// Errors of the app plumbing (configuration, output files).
#[derive(Debug, Error)]
pub enum CliError {
    /// The configuration file could not be read.
    #[error("{path}: cannot read configuration: {source}")]
    ReadConfig {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The configuration file is not valid TOML or does not match the schema.
    #[error("{path}:{line}:{column}: {message}")]
    ParseConfig {
        /// The file.
        path: PathBuf,
        /// 1-based line of the error.
        line: usize,
        /// 1-based column of the error.
        column: usize,
        /// What the parser reported (names the field where it can).
        message: String,
    },
    /// A field has a value the study cannot accept.
    #[error("{origin}: {error}")]
    Invalid {
        /// Where the configuration came from (file name or "defaults").
        origin: String,
        /// The field and reason.
        error: InputError,
    },
    /// The configuration file is not a regular file or is larger than
    /// [`MAX_CONFIG_BYTES`](crate::config::MAX_CONFIG_BYTES).
    #[error("{path}: {message}")]
    ConfigFile {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The output folder (`--out`) exists as a file, or cannot be created or written.
    #[error("--out {path}: {message}")]
    OutDir {
        /// The folder given.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// An output file could not be written.
    #[error("{path}: cannot write: {message}")]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// The underlying error.
        message: String,
    },
}

impl CliError {
    /// The output file or folder `path` could not be written: `error` says why.
    pub fn write(path: impl Into<PathBuf>, error: impl std::fmt::Display) -> Self {
        CliError::Write {
            path: path.into(),
            message: error.to_string(),
        }
    }

    /// The process exit code for this error: 2 for bad input, 1 for output failures.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::ReadConfig { .. }
            | CliError::ParseConfig { .. }
            | CliError::Invalid { .. }
            | CliError::ConfigFile { .. }
            | CliError::OutDir { .. } => 2,
            CliError::Write { .. } => 1,
        }
    }
}
