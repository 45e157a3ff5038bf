//! The shared contact solver of the contact crate (`contact::solver`, the tire's Alart–Curnier
//! solve) used by a second model: the travelling string pressed onto two pulleys (Ribaric
//! ch. 4, (4.10), (4.11), (4.40)). The static wrap is a frictionless contact problem over the
//! string's compliance: with the candidate nodes' rows `C` of the basis (`u_c = C y`), the
//! effective stiffness `K_eff = TᵀKT + ẋ² TᵀMT_,ss` at axial speed `ẋ` and upward contact
//! forces `p ≥ 0`,
//!
//! ```text
//!   K_eff y = Cᵀ p,   g = C y − s = (C K_eff⁻¹ Cᵀ) p − s ≥ 0,   p ⊥ g,
//! ```
//!
//! i.e. the Delassus matrix `W = C K_eff⁻¹ Cᵀ` and the free gaps `−s` (the string straight at
//! `y = 0`, `s` the pulley surface under each candidate). Reference (second formulation):
//! `ContactString::static_equilibrium`, the active-set iteration on the saddle-point system
//! `[K_eff Cᵀ; C 0]` of the flowing crate, which never forms `W`.
#![allow(clippy::needless_range_loop)] // index loops mirror the matrix equations

use contact::{ContactSolver, ContactSolverOptions, DenseProblem, Frictionless};
use faer::Mat;
use faer::linalg::solvers::Solve;
use flowing::contact::candidates;
use flowing::{
    AxialMotion, ContactString, DerivativeMethod, PulleyObstacle, StringConfig, StringMesh,
};
use std::sync::Arc;

/// The wrap of `tests/tests/flowing_contact.rs`: a 1.2 m string (1000 N) over two pulleys of
/// radius 0.25 m whose tops are 15 mm above the line of the ends.
fn wrapped(n: usize, speed: f64, craig_bampton: bool) -> ContactString {
    let mesh = StringMesh::uniform(
        StringConfig {
            length: 1.2,
            ..StringConfig::default()
        },
        n,
    )
    .unwrap();
    let pulleys = [0.1, 1.1].map(|center_x| PulleyObstacle {
        center_x,
        top: 0.015,
        radius: 0.25,
    });
    let cand = candidates(&mesh, &pulleys, 0.08).unwrap();
    let motion = AxialMotion::Constant { speed };
    let method = DerivativeMethod::default();
    if craig_bampton {
        ContactString::craig_bampton(&mesh, cand, 20, method, motion, None).unwrap()
    } else {
        ContactString::nodal(&mesh, cand, method, motion, None).unwrap()
    }
}

/// The static wrap by the shared solver: contact forces `p` (per candidate) and coordinates `y`.
fn wrap_by_contact_solver(s: &ContactString, speed: f64) -> (Vec<f64>, Vec<f64>) {
    let r = s.dim();
    let m = s.candidates.len();
    let k = Mat::from_fn(r, r, |i, j| s.k_r[(i, j)] + speed * speed * s.mxx_r[(i, j)]);
    let ct = Mat::from_fn(r, m, |i, c| s.t[(s.candidates[c].node, i)]);
    let lu = k.partial_piv_lu();
    // K_eff⁻¹ Cᵀ: the coordinates' response to a unit upward force on each candidate
    let x = lu.solve(&ct);
    let w = ct.transpose() * &x;
    // D (3m × 3m, column-major): W on the normal rows and columns; frictionless, so the
    // tangential unknowns only need a positive compliance (each contact's own, uncoupled)
    let n = 3 * m;
    let mut d = vec![0.0; n * n];
    let mut b = vec![0.0; n];
    for k in 0..m {
        for l in 0..m {
            d[3 * l * n + 3 * k] = w[(k, l)];
        }
        for a in 1..3 {
            d[(3 * k + a) * n + 3 * k + a] = w[(k, k)];
        }
        b[3 * k] = -s.candidates[k].surface;
    }
    let options = ContactSolverOptions {
        law: Arc::new(Frictionless),
        tol: 1e-12,
        ..ContactSolverOptions::default()
    };
    let mut solver = ContactSolver::default();
    let rep = solver.solve_dense(&mut DenseProblem { d: &d, b: &b }, &vec![0.0; n], &options);
    assert!(rep.converged && !rep.fallback, "{rep:?}");
    let x_sol = solver.x();
    let p: Vec<f64> = (0..m).map(|k| x_sol[3 * k]).collect();
    for k in 0..m {
        assert_eq!([x_sol[3 * k + 1], x_sol[3 * k + 2]], [0.0; 2], "friction");
    }
    let y = (0..r)
        .map(|i| (0..m).map(|c| x[(i, c)] * p[c]).sum())
        .collect();
    (p, y)
}

/// Both forms of the wrap (nodal (4.10) at rest, Craig–Bampton (4.11) travelling at 20 m/s,
/// below the critical speed √(T/ρA) of the default string): the shared solver's contact
/// forces, active set and deflection equal the active-set saddle-point solution of the flowing
/// crate to round-off.
#[test]
fn string_wrap_by_the_shared_solver_equals_the_active_set_solution() {
    for (craig_bampton, speed) in [(false, 0.0), (true, 20.0)] {
        let mut s = wrapped(59, speed, craig_bampton);
        let (p, y) = wrap_by_contact_solver(&s, speed);
        let y_ref = s.static_equilibrium().unwrap();
        // the reference's forces from the equilibrium of each active node: K_eff y = Cᵀ p
        // (nodal form: one row per node; Craig–Bampton: the normal equations of Cᵀ p = K_eff y
        // on the active candidates)
        let r = s.dim();
        let k_eff = |i: usize, j: usize| s.k_r[(i, j)] + speed * speed * s.mxx_r[(i, j)];
        let ky: Vec<f64> = (0..r)
            .map(|i| (0..r).map(|j| k_eff(i, j) * y_ref[j]).sum())
            .collect();
        let act: Vec<usize> = (0..s.candidates.len()).filter(|&c| s.active[c]).collect();
        let a = Mat::from_fn(r, act.len(), |i, c| s.t[(s.candidates[act[c]].node, i)]);
        let rhs = Mat::from_fn(r, 1, |i, _| ky[i]);
        let p_act = (a.transpose() * &a)
            .partial_piv_lu()
            .solve(a.transpose() * &rhs);
        let mut p_ref = vec![0.0; s.candidates.len()];
        for (c, &cand) in act.iter().enumerate() {
            p_ref[cand] = p_act[(c, 0)];
        }
        let p_max = p_ref.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let y_max = y_ref.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(
            p_max > 1.0 && y_max > 1e-3,
            "a real wrap: {p_max} N, {y_max}"
        );
        for c in 0..s.candidates.len() {
            assert_eq!(p[c] > 0.0, s.active[c], "candidate {c}: {} N", p[c]);
            assert!(
                (p[c] - p_ref[c]).abs() <= 1e-8 * p_max,
                "form {craig_bampton}, candidate {c}: {} vs {} N",
                p[c],
                p_ref[c]
            );
        }
        for i in 0..y.len() {
            assert!(
                (y[i] - y_ref[i]).abs() <= 1e-9 * y_max,
                "form {craig_bampton}, coordinate {i}: {} vs {}",
                y[i],
                y_ref[i]
            );
        }
    }
}
