//! RK4 on the spherical-joint chain (profiling aid): `cargo run --release -p flowmbd-cases --example
//! chain_rk4 -- [N] [steps]`.

use flowmbd_cases::chain::spherical_chain;
use mbd_core::integrators::Rk4;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100);
    let (sys, s0) = match spherical_chain(n, 0.1) {
        Ok(x) => x,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let start = std::time::Instant::now();
    match Rk4::new(1e-3).integrate(&sys, s0, steps as f64 * 1e-3, |_| {}) {
        Ok(sol) => println!(
            "N = {n}: {:?} in {:.3} s",
            sol.stats,
            start.elapsed().as_secs_f64()
        ),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
