//! The command-line options shared by every study of every app.

use std::path::{Path, PathBuf};

/// Options every `flowmbd-<app> <study>` subcommand accepts (flatten into the study's clap args).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct CommonArgs {
    /// TOML configuration overriding the embedded defaults (see --print-config).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Print the effective configuration as TOML and exit.
    #[arg(long)]
    pub print_config: bool,
    // Plain text on purpose: clap prints this doc comment as the --help text.
    /// Output folder [default: out/<app>/<study>].
    #[allow(rustdoc::invalid_html_tags)]
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print the summary as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Raise every documented size ceiling (nodes, elements, time steps, samples, matrix
    /// sizes) 1000-fold (Matrix Market files: up to what a sparse matrix can index).
    #[arg(long)]
    pub allow_large: bool,
}

impl CommonArgs {
    /// The output folder: `--out`, or `out/<app>/<study>` relative to the working directory.
    pub fn out_dir(&self, app: &str, study: &str) -> PathBuf {
        self.out
            .clone()
            .unwrap_or_else(|| Path::new("out").join(app).join(study))
    }
}

/// Parse the command line of an app like `C::parse()`, with negative numbers accepted as
/// option values everywhere (`--speed -20`, not only `--speed=-20`): the value then reaches the
/// configuration check, which names the field if it is out of range (issue 20). clap's setting
/// is per command, so it is applied to every subcommand.
pub fn parse_args<C: clap::Parser>() -> C {
    fn allow(cmd: clap::Command) -> clap::Command {
        let names: Vec<String> = cmd
            .get_subcommands()
            .map(|s| s.get_name().to_string())
            .collect();
        // `--speed -inf`, `--speed -nan`, `--speed -1e3`: numeric options take any value
        // beginning with a hyphen (clap's negative-number test knows digits only), so the
        // value reaches the check that names the field (issue 35)
        let mut cmd = cmd.allow_negative_numbers(true).mut_args(|a| {
            if takes_number(&a) {
                a.allow_hyphen_values(true)
            } else {
                a
            }
        });
        for n in names {
            cmd = cmd.mut_subcommand(n, allow);
        }
        cmd
    }
    let matches = allow(C::command()).get_matches();
    C::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
}

/// Whether the option `a` takes a numeric value (its value parser yields a float or an
/// integer).
fn takes_number(a: &clap::Arg) -> bool {
    use std::any::TypeId;
    let id = a.get_value_parser().type_id();
    [
        TypeId::of::<f64>(),
        TypeId::of::<f32>(),
        TypeId::of::<usize>(),
        TypeId::of::<u64>(),
        TypeId::of::<u32>(),
        TypeId::of::<i64>(),
        TypeId::of::<i32>(),
        TypeId::of::<isize>(),
    ]
    .iter()
    .any(|t| id == *t)
}

/// A command-line override of a configuration key: `given` (a flag's value), when there is
/// one, replaces `key` ([`crate::Study::apply_overrides`]: `set_given(&mut c.speed, self.speed)`).
pub fn set_given<T>(key: &mut T, given: Option<T>) {
    if let Some(v) = given {
        *key = v;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::{CommandFactory, FromArgMatches, Parser};

    #[derive(Parser, Debug)]
    struct Demo {
        #[arg(long)]
        speed: Option<f64>,
        #[arg(long)]
        name: Option<String>,
        #[arg(long)]
        quiet: bool,
    }

    // issue 35: `--speed -inf` was taken as an unknown flag
    #[test]
    fn numeric_options_take_hyphen_values() {
        let cmd = Demo::command().mut_args(|a| {
            if takes_number(&a) {
                a.allow_hyphen_values(true)
            } else {
                a
            }
        });
        let m = cmd
            .clone()
            .try_get_matches_from(["demo", "--speed", "-inf", "--quiet"])
            .unwrap();
        let d = Demo::from_arg_matches(&m).unwrap();
        assert_eq!(d.speed, Some(f64::NEG_INFINITY));
        assert!(d.quiet);
        // a string option still refuses a flag as its value
        assert!(
            cmd.try_get_matches_from(["demo", "--name", "--quiet"])
                .is_err()
        );
    }
}
