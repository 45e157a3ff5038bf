//! What the chain examples share: their command line `[N] [X]` and the chain it asks for.

use flowmbd_cases::chain::spherical_chain;
use mbd_core::MultibodySystem;
use mbd_core::integrators::State;
use std::str::FromStr;

/// The spherical chain of `N` links (the first argument, default 100) with its initial state,
/// and the second argument (`default` when absent or unreadable). Exits with code 2 and the
/// error when the chain cannot be built.
pub fn chain_from_args<T: FromStr>(default: T) -> (usize, T, MultibodySystem, State) {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100);
    let x: T = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(default);
    match spherical_chain(n, 0.1) {
        Ok((sys, s0)) => (n, x, sys, s0),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    }
}
