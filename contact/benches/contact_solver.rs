//! The shared coupled normal + friction contact solve (`contact::solver`, written for the tire's
//! patch, issue 9): time per solve of a synthetic patch like the 95-node truck tire's (25 candidates, ~16
//! pressed, μ = 0.85, tire-like normal/tangential compliances coupled by a decaying kernel),
//! solved as in time stepping (slowly varying free gaps and slips, warm start from the last
//! solve, Newton matrices reused) and cold, against the alternation fallback (normal LCP ⇄
//! friction Gauss–Seidel, exact local Coulomb) run to the same tolerance.
//! Run: `cargo bench -p contact --bench contact_solver`.

use contact::{ContactSolver, ContactSolverOptions, DenseProblem};
use std::time::Instant;

/// A patch of `m` nodes along x: normal compliance ~1e-7 m/N with 60 % coupling to the
/// neighbours, tangential (velocity level) ~4e-3 m/s/N, weak normal–tangential coupling.
fn patch(m: usize, t: f64) -> (Vec<f64>, Vec<f64>) {
    let n = 3 * m;
    let mut d = vec![0.0; n * n];
    for k in 0..m {
        for l in 0..m {
            let kern = (-(k as f64 - l as f64).abs() / 1.5).exp();
            let mut set = |r: usize, c: usize, v: f64| d[(3 * l + c) * n + 3 * k + r] = v;
            set(0, 0, 2e-7 * kern);
            set(1, 1, 4e-3 * kern);
            set(2, 2, 7e-3 * kern);
            set(1, 2, 0.4e-3 * kern);
            set(2, 1, 0.4e-3 * kern);
            set(1, 0, 1e-4 * kern);
            set(0, 1, 3e-9 * kern);
        }
    }
    let mut b = vec![0.0; n];
    for k in 0..m {
        let x = k as f64 / (m - 1) as f64 - 0.5;
        // a pressed band in the middle (~2/3 of the nodes), slip growing to the rear
        b[3 * k] = -3e-4 * (1.0 - 9.0 * x * x) + 2e-5 * (40.0 * t).sin();
        b[3 * k + 1] = 0.8 * x + 0.05 * (25.0 * t + x).cos();
        b[3 * k + 2] = 0.05 * x;
    }
    (d, b)
}

fn main() {
    let m = 25;
    let steps = 2000;
    let h = 2e-4;
    for (name, settings, warm) in [
        (
            "Newton, warm + reuse",
            ContactSolverOptions {
                law: std::sync::Arc::new(contact::Coulomb { mu: 0.85 }),
                ..ContactSolverOptions::default()
            },
            true,
        ),
        (
            "Newton, cold",
            ContactSolverOptions {
                law: std::sync::Arc::new(contact::Coulomb { mu: 0.85 }),
                ..ContactSolverOptions::default()
            },
            false,
        ),
        (
            "alternation (fallback), warm",
            ContactSolverOptions {
                law: std::sync::Arc::new(contact::Coulomb { mu: 0.85 }),
                max_newton: 0,
                max_rounds: 5000,
                ..ContactSolverOptions::default()
            },
            true,
        ),
    ] {
        let mut solver = ContactSolver::default();
        let mut prev = vec![0.0; 3 * m];
        let mut prev2 = vec![0.0; 3 * m];
        let (mut lus, mut chords, mut pressed, mut unconverged) = (0, 0, 0, 0);
        let mut wall = 0.0;
        for step in 0..steps {
            let (d, b) = patch(m, step as f64 * h);
            let dg = DenseProblem { d: &d, b: &b }.diagonal();
            let start = Instant::now();
            solver.reset(if warm { &prev } else { &[0.0; 75][..] });
            solver.set_gaps((0..m).map(|k| b[3 * k]));
            let mut src = DenseProblem { d: &d, b: &b };
            let alts: [&[f64]; 1] = [&prev2];
            let rep = solver.solve(
                &mut src,
                &dg,
                &settings,
                warm && step > 0,
                if warm { &alts } else { &[] },
            );
            wall += start.elapsed().as_secs_f64();
            lus += rep.newton_iterations;
            chords += rep.chord_iterations;
            unconverged += usize::from(!rep.converged);
            let x = solver.x().to_vec();
            pressed += (0..m).filter(|&k| x[3 * k] > 0.0).count();
            prev2 = std::mem::replace(&mut prev, x);
        }
        let s = steps as f64;
        println!(
            "{name:32} {:8.1} µs/solve  LU {:.2}  chord {:.2}  pressed {:.1}  unconverged {unconverged}",
            wall / s * 1e6,
            lus as f64 / s,
            chords as f64 / s,
            pressed as f64 / s
        );
    }
}
