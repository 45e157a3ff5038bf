//! RK4 on the spherical-joint chain (profiling aid): `cargo run --release -p flowmbd-cases --example
//! chain_rk4 -- [N] [steps]`.

mod common;

use mbd_core::integrators::Rk4;

fn main() {
    let (n, steps, sys, s0) = common::chain_from_args::<usize>(100);
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
