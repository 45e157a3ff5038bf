//! The shared non-smooth contact solver: the coupled normal + friction problem of many point
//! contacts that interact through a compliance (Delassus) operator, solved by a semismooth
//! (generalised) Newton method on the Alart–Curnier augmented-Lagrangian equations, with the
//! alternation of a normal LCP and a friction Gauss–Seidel as the fallback. Any model that can
//! say how its contact points move under unit contact forces uses it: the rolling tire's
//! end-of-step contact (`tire::TireContact`, one problem per time step) and a string pressed
//! onto pulleys (`tests/tests/string_wrap_contact_solver.rs`) are two.
//!
//! # Problem (local frames)
//! Contact `k` has the unknowns `x_k = (λ_k, f1_k, f2_k)` (normal multiplier and the two
//! tangential friction components \[N\]) and the outputs `y_k = (g_k, u1_k, u2_k)` (gap \[m\] and
//! tangential slip velocity \[m/s\] — or slip increment \[m\] in a quasi-static problem: the
//! tangential compliances then carry \[m/N\]), linear in the forces through the local Delassus
//! matrix `D` (3m × 3m) and the free values `b`:
//!
//! ```text
//!   y = D x + b,
//!   0 ≤ λ_k ⊥ g_k ≥ 0                                  (Ribaric §7.3, unilateral contact)
//!   Coulomb:     |f_k| ≤ μ λ_k,  u_k = −ν f_k with ν ≥ 0 (stick if |f_k| < μλ_k)
//!   regularised: f_k = −μ λ_k u_k / √(|u_k|² + ε²)      (Ribaric's slip-only law, seed note U20)
//! ```
//!
//! The friction law is any [`FrictionLaw`] ([`ContactSolverOptions::law`]); a frictionless
//! problem (μ = 0) needs no tangential data beyond positive tangential compliances on the
//! diagonal of `D` (its tangential unknowns are then zero).
//!
//! # Alart–Curnier equations
//! With per-contact augmentation parameters `r_N` \[N/m\] and `r_T` \[N·s/m\] (any positive value:
//! the solution does not depend on them; they are set to the inverse diagonal compliances so that
//! Newton is well scaled), the conditions above are the zeros of (Alart & Curnier 1991)
//!
//! ```text
//!   Φ_N = λ − max(0, λ − r_N g)                          = min(λ, r_N g)
//!   Φ_T = f − proj_{disk(μ λ̂)}(f − r_T u),   λ̂ = max(0, λ − r_N g)        (Coulomb)
//!   Φ_T = f + μ λ̂ u / √(|u|² + ε²)                                       (regularised)
//! ```
//!
//! (the law's target `p(f, u, λ̂)` of [`FrictionLaw::augmented`]). `Φ` is piecewise smooth;
//! Newton uses one element of its generalised Jacobian. A contact with `λ − r_N g ≤ 0` has
//! identity rows (`x_k = 0` after the step), so only the contacts that are pressed enter the
//! small dense system, which is solved by a faer LU (sequential, buffers reused; its triangular
//! solves by faer's algorithm without the per-block dispatch,
//! [`mbd_core::linalg::lu_solve_in_place`]). A backtracking (Armijo) line search on `½‖Φ‖²`
//! globalises the method; if it stalls, the alternation of the normal LCP ([`LcpWork`],
//! friction frozen) and a block Gauss–Seidel on the friction forces (exact one-contact solve
//! [`FrictionLaw::local_force`] of the law) is run to the same tolerance.
//!
//! The columns of `D` and the tangential free values are supplied lazily by the caller
//! ([`DelassusSource`]; [`DenseProblem`] for a matrix at hand): only contacts that carry a force
//! or are pressed need them. The linearisation of `Φ` (classification, derivatives of the
//! friction law's target) is formed together with the residual at each evaluated or accepted
//! point and reused by the Newton or chord direction from there. Warm starts: the initial
//! forces ([`ContactSolver::reset`]), further candidates (`alts` of [`ContactSolver::solve`])
//! and the Newton matrices of the previous solve when the caller says the contacts are the
//! same (`reuse`: chord steps).
//!
//! [`FrictionLaw`]: crate::FrictionLaw
//! [`FrictionLaw::augmented`]: crate::FrictionLaw::augmented
//! [`FrictionLaw::local_force`]: crate::FrictionLaw::local_force

mod alart_curnier;
mod fallback;
mod lcp;
mod newton;
mod options;
mod problem;

pub use alart_curnier::ContactSolver;
pub use lcp::{LcpSolution, LcpWork, solve_lcp};
pub use options::{ContactSolverOptions, ContactSolverReport};
pub use problem::{DelassusSource, DenseProblem};
