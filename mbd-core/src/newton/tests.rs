use super::*;

/// `R(x, μ)` into the slice.
type ResFn = Box<dyn FnMut(&[f64], f64, &mut [f64])>;
/// `J(x, μ)` (2×2 at most).
type JacFn = Box<dyn FnMut(&[f64], f64) -> [[f64; 2]; 2]>;

/// A small dense problem given by closures: `R(x, μ)` and `J(x, μ)` (2×2 at most, solved by
/// Cramer's rule). Records the residual norm of every linearisation.
struct Dense {
    n: usize,
    r: ResFn,
    j: JacFn,
    jac: [[f64; 2]; 2],
    history: Vec<f64>,
    factorisations: usize,
    modified: bool,
    /// Line-search trial evaluations ([`NewtonProblem::residual`]).
    trials: usize,
}

impl Dense {
    fn new(
        n: usize, r: impl FnMut(&[f64], f64, &mut [f64]) + 'static,
        j: impl FnMut(&[f64], f64) -> [[f64; 2]; 2] + 'static,
    ) -> Self {
        Self {
            n,
            r: Box::new(r),
            j: Box::new(j),
            jac: [[0.0; 2]; 2],
            history: Vec::new(),
            factorisations: 0,
            modified: false,
            trials: 0,
        }
    }
}

impl NewtonProblem for Dense {
    type Error = String;

    fn tangent_dim(&self) -> usize {
        self.n
    }

    fn linearize(&mut self, x: &[f64], load: f64, r: &mut [f64]) -> Result<(), String> {
        (self.r)(x, load, r);
        self.history.push(self.residual_norm(r));
        if !self.modified || self.factorisations == 0 {
            self.jac = (self.j)(x, load);
            self.factorisations += 1;
        }
        Ok(())
    }

    fn residual(&mut self, x: &[f64], load: f64, r: &mut [f64]) -> Result<(), String> {
        self.trials += 1;
        (self.r)(x, load, r);
        Ok(())
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), String> {
        let a = self.jac;
        if self.n == 1 {
            if a[0][0] == 0.0 {
                return Err("zero derivative".into());
            }
            dx[0] = -r[0] / a[0][0];
            return Ok(());
        }
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        if det == 0.0 {
            return Err("singular Jacobian".into());
        }
        dx[0] = -(a[1][1] * r[0] - a[0][1] * r[1]) / det;
        dx[1] = -(a[0][0] * r[1] - a[1][0] * r[0]) / det;
        Ok(())
    }
}

/// Circle `x² + y² = 4` cut by the line `x = y`.
fn circle_line() -> Dense {
    Dense::new(
        2,
        |x: &[f64], _: f64, r: &mut [f64]| {
            r[0] = x[0] * x[0] + x[1] * x[1] - 4.0;
            r[1] = x[0] - x[1];
        },
        |x: &[f64], _: f64| [[2.0 * x[0], 2.0 * x[1]], [1.0, -1.0]],
    )
}

// Reference: analytical root (√2, √2); Newton–Raphson converges quadratically near a simple
// root, ‖R_{k+1}‖ ≤ C ‖R_k‖² (Nocedal & Wright Thm. 11.2).
/// Solves [`circle_line`] from (3, 1) with `opts` and checks the root (√2, √2) to `tol`.
fn solve_circle_line(opts: &NewtonOptions, tol: f64) -> (Dense, NewtonReport) {
    let mut p = circle_line();
    let mut x = vec![3.0, 1.0];
    let rep = solve(&mut p, &mut x, opts, &mut NewtonWorkspace::new()).unwrap();
    let s = 2f64.sqrt();
    assert!((x[0] - s).abs() < tol && (x[1] - s).abs() < tol, "{x:?}");
    (p, rep)
}

#[test]
fn finds_the_analytic_root_quadratically() {
    let opts = NewtonOptions {
        tolerances: Tolerances::absolute(1e-14),
        ..Default::default()
    };
    let (p, rep) = solve_circle_line(&opts, 1e-14);
    assert!(rep.converged && rep.iterations() <= 7, "{rep:?}");
    // the constant ‖R_{k+1}‖/‖R_k‖² stays bounded while the residual falls from 1 to 1e-12
    let h = &p.history;
    let ratios: Vec<f64> = h
        .windows(2)
        .filter(|w| w[0] < 1.0 && w[1] > 1e-13)
        .map(|w| w[1] / (w[0] * w[0]))
        .collect();
    assert!(ratios.len() >= 2, "{h:?}");
    assert!(ratios.iter().all(|&c| c < 1.0), "{ratios:?} from {h:?}");
}

// Reference: the root 0 of atan; plain Newton from |x0| > 1.3917 oscillates outwards
// (x_{k+1} = x_k − (1 + x_k²) atan x_k) until the derivative underflows, the Armijo line search on |R| makes it converge.
#[test]
fn line_search_rescues_an_overshooting_newton() {
    let atan = || {
        Dense::new(
            1,
            |x: &[f64], _: f64, r: &mut [f64]| r[0] = x[0].atan(),
            |x: &[f64], _: f64| [[1.0 / (1.0 + x[0] * x[0]), 0.0], [0.0; 2]],
        )
    };
    let plain = NewtonOptions {
        max_iterations: 20,
        tolerances: Tolerances::absolute(1e-12),
        ..Default::default()
    };
    let mut x = vec![2.0];
    let e = solve(&mut atan(), &mut x, &plain, &mut NewtonWorkspace::new()).unwrap_err();
    assert!(
        matches!(
            e,
            NewtonError::NoConvergence { .. }
                | NewtonError::NonFinite { .. }
                | NewtonError::Problem(_)
        ),
        "{e}"
    );
    let searched = NewtonOptions {
        line_search: Some(LineSearch::default()),
        ..plain
    };
    let mut x = vec![2.0];
    let rep = solve(&mut atan(), &mut x, &searched, &mut NewtonWorkspace::new()).unwrap();
    assert!(x[0].abs() < 1e-12, "{x:?} {rep:?}");
}

// Reference: analytical root (√2, √2). With a line search every correction but the last is
// tried (one residual evaluation each, all full steps near the root); the last one passes the
// correction test in full and is taken without a trial, whose residual nobody would use.
#[test]
fn a_converged_full_correction_needs_no_line_search_trial() {
    let opts = NewtonOptions {
        tolerances: Tolerances::absolute(1e-12),
        line_search: Some(LineSearch::default()),
        ..Default::default()
    };
    let (p, rep) = solve_circle_line(&opts, 1e-12);
    assert!(rep.iterations() >= 3, "{rep:?}");
    assert_eq!(p.trials, rep.iterations() - 1, "{rep:?}");
}

/// Hardening spring `k u + c u³ = μ F`.
fn spring(k: f64, c: f64, f: f64) -> Dense {
    Dense::new(
        1,
        move |x: &[f64], mu: f64, r: &mut [f64]| r[0] = k * x[0] + c * x[0].powi(3) - mu * f,
        move |x: &[f64], _: f64| [[k + 3.0 * c * x[0] * x[0], 0.0], [0.0; 2]],
    )
}

/// The real root of `c u³ + k u − F = 0` (Cardano, one real root for k, c > 0).
fn cardano(k: f64, c: f64, f: f64) -> f64 {
    let (p, q) = (k / c, -f / c);
    let d = (q * q / 4.0 + p * p * p / 27.0).sqrt();
    (-q / 2.0 + d).cbrt() + (-q / 2.0 - d).cbrt()
}

/// The spring of `k`, `c`, `f` solved from `u = 0` with `opts`: the point reached and the
/// report or error.
fn solve_spring(
    k: f64, c: f64, f: f64, opts: &NewtonOptions,
) -> (
    f64,
    Result<NewtonReport, NewtonError<<Dense as NewtonProblem>::Error>>,
) {
    let mut x = vec![0.0];
    let r = solve(
        &mut spring(k, c, f),
        &mut x,
        opts,
        &mut NewtonWorkspace::new(),
    );
    (x[0], r)
}

/// `u` is the spring's equilibrium (Cardano) to 10⁻¹² relative.
fn assert_cardano(u: f64, k: f64, c: f64, f: f64) {
    let want = cardano(k, c, f);
    assert!((u - want).abs() < 1e-12 * want, "{u} vs {want}");
}

// Reference: analytic (Cardano) equilibrium of a hardening spring at every load factor.
#[test]
fn load_stepping_follows_the_analytic_path() {
    let (k, c, f) = (2.0e3, 5.0e5, 4.0e3);
    let mut p = spring(k, c, f);
    let opts = NewtonOptions {
        tolerances: Tolerances::relative(1e-14),
        load: LoadStepping {
            increments: 4,
            max_cuts: 0,
        },
        ..Default::default()
    };
    let mut x = vec![0.0];
    let rep = solve(&mut p, &mut x, &opts, &mut NewtonWorkspace::new()).unwrap();
    let loads: Vec<f64> = rep.increments.iter().map(|i| i.load).collect();
    assert_eq!(loads, vec![0.25, 0.5, 0.75, 1.0]);
    assert_cardano(x[0], k, c, f);
}

// Reference: analytic (Cardano) equilibrium; a single increment with few iterations fails and
// the halved increments reach it.
#[test]
fn step_cutting_recovers_a_failed_increment() {
    let (k, c, f) = (1.0, 1.0, 100.0);
    let opts = NewtonOptions {
        max_iterations: 10,
        tolerances: Tolerances::relative(1e-13),
        ..Default::default()
    };
    let e = solve_spring(k, c, f, &opts).1.unwrap_err();
    assert!(matches!(e, NewtonError::NoConvergence { .. }), "{e}");
    let cut = NewtonOptions {
        load: LoadStepping {
            increments: 1,
            max_cuts: 10,
        },
        ..opts
    };
    let (u, rep) = solve_spring(k, c, f, &cut);
    let rep = rep.unwrap();
    assert!(rep.cuts > 0, "{rep:?}");
    assert_eq!(rep.increments.last().unwrap().load, 1.0);
    assert_cardano(u, k, c, f);
}

// Reference: the analytic root of the circle problem; a tangent factored once (modified
// Newton) converges linearly to the same root with a single factorisation.
#[test]
fn modified_newton_reuses_one_factorisation() {
    let mut p = circle_line();
    p.modified = true;
    let mut x = vec![1.6, 1.3];
    let opts = NewtonOptions {
        max_iterations: 200,
        tolerances: Tolerances::absolute(1e-13),
        ..Default::default()
    };
    let rep = solve(&mut p, &mut x, &opts, &mut NewtonWorkspace::new()).unwrap();
    let s = 2f64.sqrt();
    assert!(
        (x[0] - s).abs() < 1e-12 && (x[1] - s).abs() < 1e-12,
        "{x:?}"
    );
    assert_eq!(p.factorisations, 1);
    let mut full = circle_line();
    let mut y = vec![1.6, 1.3];
    let full_rep = solve(&mut full, &mut y, &opts, &mut NewtonWorkspace::new()).unwrap();
    assert!(
        rep.iterations() > full_rep.iterations(),
        "{rep:?} {full_rep:?}"
    );
}

// Reference: the analytic root; with `max_step` the iteration is damped (never converged on a
// damped step) and still reaches the root, each correction bounded by `max_step`.
#[test]
fn damping_bounds_every_correction() {
    let mut p = spring(1.0, 1.0, 10.0);
    let mut x = vec![0.0];
    let opts = NewtonOptions {
        max_step: 0.5,
        tolerances: Tolerances::absolute(1e-13),
        ..Default::default()
    };
    let rep = solve(&mut p, &mut x, &opts, &mut NewtonWorkspace::new()).unwrap();
    let u = cardano(1.0, 1.0, 10.0);
    assert!((x[0] - u).abs() < 1e-12, "{} vs {u}", x[0]);
    // u ≈ 2.0 needs at least four steps of 0.5
    assert!(rep.iterations() >= 4, "{rep:?}");
}

/// A spring `k u = F` against a wall at `u = 1` (unilateral, multiplier `λ ≥ 0`), unknowns
/// `(u, λ)`; the active set starts empty.
struct Wall {
    k: f64,
    f: f64,
    active: bool,
}

impl NewtonProblem for Wall {
    type Error = String;
    fn tangent_dim(&self) -> usize {
        2
    }
    fn linearize(&mut self, x: &[f64], load: f64, r: &mut [f64]) -> Result<(), String> {
        r[0] = self.k * x[0] + x[1] - load * self.f;
        r[1] = if self.active { x[0] - 1.0 } else { x[1] };
        Ok(())
    }
    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), String> {
        if self.active {
            dx[0] = -r[1];
            dx[1] = -r[0] - self.k * dx[0];
        } else {
            dx[1] = -r[1];
            dx[0] = -(r[0] + dx[1]) / self.k;
        }
        Ok(())
    }
    fn settle(&mut self, x: &mut [f64], _load: f64) -> Result<Settle, String> {
        if !self.active && x[0] > 1.0 {
            self.active = true;
            return Ok(Settle::Changed);
        }
        if self.active && x[1] < 0.0 {
            self.active = false;
            x[1] = 0.0;
            return Ok(Settle::Changed);
        }
        Ok(Settle::Settled)
    }
}

// Reference: force balance, u = 1 and λ = F − k when F/k > 1 (the wall carries the excess).
#[test]
fn active_set_changes_are_iterated_at_the_same_load() {
    let mut p = Wall {
        k: 100.0,
        f: 250.0,
        active: false,
    };
    let mut x = vec![0.0, 0.0];
    let rep = solve(
        &mut p,
        &mut x,
        &NewtonOptions::default(),
        &mut NewtonWorkspace::new(),
    )
    .unwrap();
    assert!(
        (x[0] - 1.0).abs() < 1e-14 && (x[1] - 150.0).abs() < 1e-12,
        "{x:?}"
    );
    assert_eq!(rep.increments[0].passes, 2);
    let opts = NewtonOptions {
        max_passes: 1,
        ..Default::default()
    };
    let mut p = Wall {
        k: 100.0,
        f: 250.0,
        active: false,
    };
    let mut x = vec![0.0, 0.0];
    let e = solve(&mut p, &mut x, &opts, &mut NewtonWorkspace::new()).unwrap_err();
    assert!(
        matches!(e, NewtonError::NotSettled { passes: 1, .. }),
        "{e}"
    );
}

/// `Π = ¼ x⁴ − x` (root of `R = ∇Π = x³ − 1` at 1), with the potential as merit.
struct Quartic {
    slope: f64,
}

impl NewtonProblem for Quartic {
    type Error = String;
    fn tangent_dim(&self) -> usize {
        1
    }
    fn linearize(&mut self, x: &[f64], _: f64, r: &mut [f64]) -> Result<(), String> {
        r[0] = x[0].powi(3) - 1.0;
        self.slope = 3.0 * x[0] * x[0];
        Ok(())
    }
    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), String> {
        if self.slope == 0.0 {
            return Err("solve: zero tangent".into());
        }
        dx[0] = -r[0] / self.slope;
        Ok(())
    }
    fn potential(&mut self, x: &[f64], _: f64) -> Result<Option<f64>, String> {
        Ok(Some(0.25 * x[0].powi(4) - x[0]))
    }
}

// Reference: analytic root x = 1 of ∇Π = x³ − 1. From x₀ = 0.1 the Newton step overshoots to
// 33.4 where Π ≈ 3·10⁵ > Π(x₀); the Armijo search on Π halves it until Π decreases, and the
// iteration needs fewer steps than plain Newton.
#[test]
fn potential_line_search_descends_the_energy() {
    let opts = NewtonOptions {
        tolerances: Tolerances::absolute(1e-13),
        ..Default::default()
    };
    let ls = NewtonOptions {
        line_search: Some(LineSearch {
            fallback: Fallback::LastTrial,
            ..LineSearch::default()
        }),
        ..opts
    };
    let mut q = Quartic { slope: 0.0 };
    let mut x = vec![0.1];
    let with = solve(&mut q, &mut x, &ls, &mut NewtonWorkspace::new()).unwrap();
    assert!((x[0] - 1.0).abs() < 1e-13, "{x:?}");
    let mut x = vec![0.1];
    let plain = solve(&mut q, &mut x, &opts, &mut NewtonWorkspace::new()).unwrap();
    assert!((x[0] - 1.0).abs() < 1e-13, "{x:?}");
    assert!(with.iterations() < plain.iterations(), "{with:?} {plain:?}");
}

// Reference: bad options and failing problem evaluations come back as typed errors.
#[test]
fn errors_are_typed() {
    let mut x = vec![0.0];
    let opts = NewtonOptions {
        load: LoadStepping {
            increments: 0,
            max_cuts: 0,
        },
        ..Default::default()
    };
    let mut q = Quartic { slope: 0.0 };
    let e = solve(&mut q, &mut x, &opts, &mut NewtonWorkspace::new()).unwrap_err();
    assert!(e.to_string().contains("load.increments"), "{e}");
    // x = 0: zero tangent, reported by the problem
    let e = solve(
        &mut q,
        &mut x,
        &NewtonOptions::default(),
        &mut NewtonWorkspace::new(),
    )
    .unwrap_err();
    assert!(
        matches!(e, NewtonError::Problem(ref m) if m.contains("solve")),
        "{e}"
    );
    let mbd = NewtonError::<crate::MbdError>::NoConvergence {
        load: 1.0,
        iterations: 3,
        residual: 2.0,
        correction: 1.0,
    }
    .into_mbd(0.5);
    assert_eq!(
        mbd,
        crate::MbdError::NoConvergence {
            t: 0.5,
            iterations: 3,
            residual: 2.0
        }
    );
}

/// `R(x) = x + sat(100 x) − ½`, `sat` clipped at ±1 (the S-shaped residual of a mass with a
/// saturating creep-rate friction force, Kerkkänen Fig. 3.3): monotone, one root `½/101`.
fn saturating() -> Dense {
    let sat = |x: f64| (100.0 * x).clamp(-1.0, 1.0);
    let slope = |x: f64| if (100.0 * x).abs() <= 1.0 { 101.0 } else { 1.0 };
    Dense::new(
        1,
        move |x, _, r| r[0] = x[0] + sat(x[0]) - 0.5,
        move |x, _| [[slope(x[0]), 0.0], [0.0, 1.0]],
    )
}

// Reference: from x₀ = 10 plain Newton jumps between the two flat branches (x = −½ ↔ 1.5, a
// two-cycle of constant corrections) and never converges; the stall exit stops it after the
// given number of non-contracting iterations, and with backtracking after the first stall it
// converges to the analytic root ½/101.
#[test]
fn stall_exit_and_backtracking_at_a_saturating_law() {
    let base = NewtonOptions {
        max_iterations: 40,
        tolerances: Tolerances::absolute(1e-12),
        ..Default::default()
    };
    let mut ws = NewtonWorkspace::new();
    let mut x = vec![10.0];
    let r = solve(&mut saturating(), &mut x, &base, &mut ws);
    assert!(matches!(
        r,
        Err(NewtonError::NoConvergence { iterations: 40, .. })
    ));
    assert!(
        (x[0] + 0.5).abs() < 1e-12 || (x[0] - 1.5).abs() < 1e-12,
        "{x:?}"
    );
    let stall = Stall {
        ratio: 0.9,
        iterations: 3,
        backtrack: false,
    };
    let mut x = vec![10.0];
    let opts = NewtonOptions {
        stall: Some(stall),
        ..base
    };
    match solve(&mut saturating(), &mut x, &opts, &mut ws) {
        Err(NewtonError::NoConvergence { iterations, .. }) => assert!(iterations <= 6),
        other => panic!("expected an early exit, got {other:?}"),
    }
    let mut x = vec![10.0];
    let opts = NewtonOptions {
        stall: Some(Stall {
            backtrack: true,
            ..stall
        }),
        ..base
    };
    let rep = solve(&mut saturating(), &mut x, &opts, &mut ws).unwrap();
    assert!((x[0] - 0.5 / 101.0).abs() < 1e-12, "{x:?}");
    assert!(rep.iterations() < 15, "{rep:?}");
    let bad = NewtonOptions {
        stall: Some(Stall {
            iterations: 0,
            ..stall
        }),
        ..base
    };
    assert!(matches!(
        solve(&mut saturating(), &mut [1.0], &bad, &mut ws),
        Err(NewtonError::InvalidOption { field: "stall", .. })
    ));
}
