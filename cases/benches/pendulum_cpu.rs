//! Kerkkänen Table 2.5: relative CPU time of the falling pendulum, proposed element vs
//! Omar–Shabana (thesis: 65 % with 4 elements, 68 % with 8). Same integrator (generalized-α,
//! ρ∞ = 1, h = 1e-4 s, 0.5 s) for both; prints wall times and the ratio (best of 3 runs).

use ancf::beam_mesh::BeamElementKind;
use flowmbd_cases::ancf_dynamics::{PendulumCase, pendulum};
use std::time::Instant;

fn best_time(case: &PendulumCase) -> f64 {
    (0..3)
        .map(|_| {
            let t = Instant::now();
            let s = pendulum(case, 1000, |_| {}).expect("pendulum run");
            std::hint::black_box(s);
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    // `cargo bench` passes `--bench`; ignore arguments.
    println!("Table 2.5 (falling pendulum, generalized-alpha h = 1e-4 s, 0.5 s)");
    println!("elements  proposed [s]  Omar-Shabana [s]  ratio (thesis)");
    for (n, thesis) in [(4, 0.65), (8, 0.68)] {
        let mk = |element| PendulumCase {
            element,
            elements: n,
            t_end: 0.5,
            h: 1e-4,
            ..Default::default()
        };
        let tp = best_time(&mk(BeamElementKind::Proposed));
        let to = best_time(&mk(BeamElementKind::OmarShabana));
        println!(
            "{n:>8}  {tp:>12.3}  {to:>16.3}  {:>5.2} ({thesis:.2})",
            tp / to
        );
    }
}
