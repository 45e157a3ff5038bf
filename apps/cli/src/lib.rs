//! # flowmbd-cli
//!
//! Shared plumbing for the `flowmbd-*` binaries, so that every app follows the same conventions
//! and stays thin:
//!
//! - [`CommonArgs`]: `--config FILE`, `--print-config`, `--out DIR`, `--json`, `--quiet`;
//! - [`config`]: TOML configuration with embedded defaults, one-line errors naming file, line and
//!   field, and semantic validation through [`Validate`];
//! - [`commented`]: the printed configuration with every key commented (unit and meaning) from
//!   the doc comments of the configuration types;
//! - [`Study`] / [`run_study`]: the exit-code policy (0 ok, 2 bad input, 1 numerical failure with
//!   the results so far kept in `summary.json`);
//! - [`OutputDir`]: the study's output folder (`summary.json`, CSV tables);
//! - [`plot`]: line plots written as PNG and SVG;
//! - [`Progress`]: a progress bar on stderr, hidden with `--quiet` or without a terminal;
//! - [`print_stdout`]: `--json` / `--print-config` output that exits quietly into a closed pipe;
//! - [`check_input_file`]: input paths reported as missing, a directory or unreadable;
//! - [`limits`]: the documented size ceilings, raised by every study's `--allow-large`;
//! - [`Cancel`]: SIGINT / SIGTERM stop a study at its next step, results so far kept and
//!   marked incomplete (exit 130 / 143).

pub mod args;
pub mod cancel;
pub mod commented;
pub mod config;
pub mod error;
pub mod files;
pub mod mutation;
pub mod output;
pub mod plot;
pub mod progress;
pub mod series;
pub mod stdout;
pub mod study;
pub mod testing;

pub use args::{CommonArgs, parse_args, set_given};
pub use cancel::Cancel;
pub use config::{PartialRules, Validate, load_config, read_config};
pub use error::{CliError, InputError};
pub use files::check_input_file;
pub use mbd_core::validate::limits;
pub use output::OutputDir;
pub use progress::Progress;
pub use series::VtkSeries;
pub use stdout::print_stdout;
pub use study::{Study, StudyContext, StudyError, run_study};
