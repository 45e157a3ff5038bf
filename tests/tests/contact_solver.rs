//! The shared coupled normal + friction contact solve (`contact::solver`, written for the tire's
//! patch in issue #9):
//! the semismooth Newton method on the Alart–Curnier equations against
//! * the analytical solution of one node pressed onto a plane and sliding or sticking,
//! * an independent reference on 2–3 node problems: the alternation of the normal LCP (solved
//!   here by enumerating the active sets) and block Gauss–Seidel on the friction forces with the
//!   exact local Coulomb solve, run to convergence (this file's helper, not the production code),
//! * the complementarity and friction-cone invariants on random positive definite Delassus
//!   problems (proptest), for the Coulomb and the regularised law (Ribaric seed note U20).

use contact::{ContactSolver, ContactSolverOptions, ContactSolverReport, DenseProblem};
use contact::{Coulomb, SlipRegularized};
use proptest::prelude::*;
use std::sync::Arc;
use tire::TireFriction;

/// Column-major 3m × 3m matrix from row-major rows.
fn col_major(rows: &[Vec<f64>]) -> Vec<f64> {
    let n = rows.len();
    let mut d = vec![0.0; n * n];
    for (i, r) in rows.iter().enumerate() {
        for (j, v) in r.iter().enumerate() {
            d[j * n + i] = *v;
        }
    }
    d
}

fn diag_of(d: &[f64], m: usize) -> Vec<[f64; 2]> {
    let n = 3 * m;
    (0..m)
        .map(|k| {
            [
                d[3 * k * n + 3 * k],
                0.5 * (d[(3 * k + 1) * n + 3 * k + 1] + d[(3 * k + 2) * n + 3 * k + 2]),
            ]
        })
        .collect()
}

fn solve(
    d: &[f64], b: &[f64], warm: &[f64], s: &ContactSolverOptions,
) -> (Vec<f64>, ContactSolverReport) {
    let mut solver = ContactSolver::default();
    let rep = solver.solve_dense(&mut DenseProblem { d, b }, warm, s);
    (solver.x().to_vec(), rep)
}

fn outputs(d: &[f64], b: &[f64], x: &[f64]) -> Vec<f64> {
    let n = b.len();
    (0..n)
        .map(|i| b[i] + (0..n).map(|j| d[j * n + i] * x[j]).sum::<f64>())
        .collect()
}

fn coulomb(mu: f64) -> ContactSolverOptions {
    ContactSolverOptions {
        law: Arc::new(Coulomb { mu }),
        ..ContactSolverOptions::default()
    }
}

/// One node on a plane with normal compliance `dn`, isotropic tangential compliance `dt`,
/// free gap `g < 0` and free slip `v`: `λ = −g/dn`; stick `f = −v/dt` when `|v|/dt ≤ μλ`,
/// else `f = −μλ v/|v|` (analytical).
#[test]
fn single_node_stick_and_slip_analytical() {
    let (dn, dt, g, mu) = (2e-7, 4e-3, -1e-4, 0.85);
    let lam = -g / dn; // 500 N
    for (v, stick) in [
        ([0.5, -0.3], true),    // |v|/dt = 146 N < μλ = 425 N
        ([1.2, 1.0], true),     // 390 N: inside the cone
        ([3.0, -4.0], false),   // 1250 N: slides
        ([-16.0, 0.0], false),  // rolling-speed slip
        ([0.0, 1.7005], false), // just outside (425.1 N)
        ([1e-9, -2e-9], true),  // nearly no slip
    ] {
        let d = col_major(&[vec![dn, 0.0, 0.0], vec![0.0, dt, 0.0], vec![0.0, 0.0, dt]]);
        let b = [g, v[0], v[1]];
        let (x, rep) = solve(&d, &b, &[0.0; 3], &coulomb(mu));
        assert!(rep.converged && !rep.fallback, "{rep:?}");
        assert!((x[0] - lam).abs() <= 1e-9 * lam, "λ {} vs {lam}", x[0]);
        let vn = v[0].hypot(v[1]);
        let f = if stick {
            [-v[0] / dt, -v[1] / dt]
        } else {
            [-mu * lam * v[0] / vn, -mu * lam * v[1] / vn]
        };
        for a in 0..2 {
            assert!(
                (x[1 + a] - f[a]).abs() <= 1e-9 * lam,
                "v {v:?}: f {:?} vs {f:?}",
                &x[1..]
            );
        }
        let fm = x[1].hypot(x[2]);
        assert!(fm <= mu * x[0] * (1.0 + 1e-12), "outside the cone");
        // a warm start from the answer needs no Newton iteration
        let (x2, rep2) = solve(&d, &b, &x, &coulomb(mu));
        assert_eq!(rep2.newton_iterations, 0);
        assert!((x2[0] - x[0]).abs() <= 1e-12 * lam);
    }
    // a node with a positive free gap carries nothing
    let d = col_major(&[vec![dn, 0.0, 0.0], vec![0.0, dt, 0.0], vec![0.0, 0.0, dt]]);
    let (x, rep) = solve(&d, &[1e-5, 3.0, 0.0], &[100.0, 10.0, 0.0], &coulomb(mu));
    assert!(rep.converged);
    assert_eq!(x, vec![0.0; 3]);
}

/// Normal–tangential coupling `u = v + c λ + dt f` and anisotropic tangential compliance:
/// `λ = −g/dn` still (no tangential-to-normal coupling), the slip at `f = 0` is `v + cλ`, and
/// in slip `f = −μλ u/|u|` with `u = v + cλ + B f` (checked as the Coulomb conditions), in stick
/// `f = −B⁻¹(v + cλ)`.
#[test]
fn single_node_coupled_anisotropic() {
    let (dn, g, mu) = (2e-7, -1e-4, 0.6);
    let lam = -g / dn;
    let bt = [[4e-3, 1e-3], [0.5e-3, 9e-3]];
    let c = [2e-3, -1e-3];
    for v in [[0.1, 0.1], [-2.0, -1.0], [0.0, 5.0], [-0.9, 0.2]] {
        let d = col_major(&[
            vec![dn, 0.0, 0.0],
            vec![c[0], bt[0][0], bt[0][1]],
            vec![c[1], bt[1][0], bt[1][1]],
        ]);
        let b = [g, v[0], v[1]];
        let (x, rep) = solve(&d, &b, &[0.0; 3], &coulomb(mu));
        assert!(rep.converged, "{rep:?}");
        assert!((x[0] - lam).abs() <= 1e-9 * lam);
        let r = [v[0] + c[0] * lam, v[1] + c[1] * lam];
        let det = bt[0][0] * bt[1][1] - bt[0][1] * bt[1][0];
        let fs = [
            -(bt[1][1] * r[0] - bt[0][1] * r[1]) / det,
            -(-bt[1][0] * r[0] + bt[0][0] * r[1]) / det,
        ];
        let y = outputs(&d, &b, &x);
        let fm = x[1].hypot(x[2]);
        if fs[0].hypot(fs[1]) <= mu * lam {
            assert!((x[1] - fs[0]).abs() + (x[2] - fs[1]).abs() <= 1e-9 * lam);
        } else {
            let um = y[1].hypot(y[2]);
            assert!((fm - mu * lam).abs() <= 1e-9 * lam, "on the cone");
            assert!(um > 0.0);
            // f anti-parallel to u
            assert!((x[1] / fm + y[1] / um).abs() < 1e-8);
            assert!((x[2] / fm + y[2] / um).abs() < 1e-8);
        }
    }
}

// ----- independent reference: enumeration LCP + Gauss–Seidel with exact local Coulomb -------

/// `0 ≤ λ ⊥ W λ + q ≥ 0` by trying every active set (m ≤ 3), Gaussian elimination.
fn lcp_enumerate(w: &[Vec<f64>], q: &[f64]) -> Vec<f64> {
    let m = q.len();
    let mut best: Option<(f64, Vec<f64>)> = None;
    for mask in 0..(1usize << m) {
        let idx: Vec<usize> = (0..m).filter(|&i| mask & (1 << i) != 0).collect();
        let k = idx.len();
        let mut a: Vec<Vec<f64>> = idx
            .iter()
            .map(|&i| {
                let mut r: Vec<f64> = idx.iter().map(|&j| w[i][j]).collect();
                r.push(-q[i]);
                r
            })
            .collect();
        let mut ok = true;
        for c in 0..k {
            let p = (c..k)
                .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
                .unwrap_or(c);
            a.swap(c, p);
            if a[c][c].abs() < 1e-300 {
                ok = false;
                break;
            }
            let pivot_row = a[c].clone();
            for (r, row) in a.iter_mut().enumerate() {
                if r != c {
                    let f = row[c] / pivot_row[c];
                    for (x, p) in row.iter_mut().zip(&pivot_row).skip(c) {
                        *x -= f * p;
                    }
                }
            }
        }
        if !ok {
            continue;
        }
        let mut lam = vec![0.0; m];
        for (c, &i) in idx.iter().enumerate() {
            lam[i] = a[c][k] / a[c][c];
        }
        // violation measure
        let mut viol = 0.0f64;
        for i in 0..m {
            let g = q[i] + (0..m).map(|j| w[i][j] * lam[j]).sum::<f64>();
            viol = viol
                .max((-lam[i]).max(0.0) / (1.0 + lam.iter().fold(0.0f64, |a, l| a.max(l.abs()))));
            viol = viol.max((-g).max(0.0) / w[i][i]);
        }
        if best.as_ref().is_none_or(|(v, _)| viol < *v) {
            best = Some((viol, lam));
        }
    }
    best.map(|b| b.1).unwrap_or_else(|| vec![0.0; m])
}

/// Exact local Coulomb: `u = r + B f`, stick `f = −B⁻¹r` if inside the disk, else
/// `f = −(B + νI)⁻¹ r` with `|f| = ρ`, `ν` by bisection (then `u = −ν f`).
fn local_coulomb(b: [[f64; 2]; 2], r: [f64; 2], rho: f64) -> [f64; 2] {
    let sol = |nu: f64| {
        let a = [[b[0][0] + nu, b[0][1]], [b[1][0], b[1][1] + nu]];
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        [
            -(a[1][1] * r[0] - a[0][1] * r[1]) / det,
            -(-a[1][0] * r[0] + a[0][0] * r[1]) / det,
        ]
    };
    if rho <= 0.0 {
        return [0.0, 0.0];
    }
    let f0 = sol(0.0);
    if f0[0].hypot(f0[1]) <= rho {
        return f0;
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    while sol(hi)[0].hypot(sol(hi)[1]) > rho {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        let f = sol(mid);
        if f[0].hypot(f[1]) > rho {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let f = sol(hi);
    let n = f[0].hypot(f[1]);
    [rho * f[0] / n, rho * f[1] / n]
}

/// The alternation (normal LCP with friction frozen, friction Gauss–Seidel with λ frozen) run
/// for many rounds.
fn reference(d: &[f64], b: &[f64], mu: f64, rounds: usize) -> Vec<f64> {
    let n = b.len();
    let m = n / 3;
    let dd = |i: usize, j: usize| d[j * n + i];
    let mut x = vec![0.0; n];
    for _ in 0..rounds {
        let w: Vec<Vec<f64>> = (0..m)
            .map(|k| (0..m).map(|l| dd(3 * k, 3 * l)).collect())
            .collect();
        let q: Vec<f64> = (0..m)
            .map(|k| {
                b[3 * k]
                    + (0..m)
                        .map(|l| {
                            dd(3 * k, 3 * l + 1) * x[3 * l + 1]
                                + dd(3 * k, 3 * l + 2) * x[3 * l + 2]
                        })
                        .sum::<f64>()
            })
            .collect();
        let lam = lcp_enumerate(&w, &q);
        for k in 0..m {
            x[3 * k] = lam[k];
        }
        for _ in 0..20 {
            for k in 0..m {
                let y = outputs(d, b, &x);
                let bt = [
                    [dd(3 * k + 1, 3 * k + 1), dd(3 * k + 1, 3 * k + 2)],
                    [dd(3 * k + 2, 3 * k + 1), dd(3 * k + 2, 3 * k + 2)],
                ];
                let f = [x[3 * k + 1], x[3 * k + 2]];
                let r = [
                    y[3 * k + 1] - bt[0][0] * f[0] - bt[0][1] * f[1],
                    y[3 * k + 2] - bt[1][0] * f[0] - bt[1][1] * f[1],
                ];
                let nf = local_coulomb(bt, r, mu * x[3 * k].max(0.0));
                x[3 * k + 1] = nf[0];
                x[3 * k + 2] = nf[1];
            }
        }
    }
    x
}

/// Three nodes of a patch (tire-like scales: normal compliance ~1e-7 m/N, tangential
/// ~4e-3 m/s/N, coupled through a decaying kernel and a weak normal–tangential coupling),
/// pressed and sliding at different rates: Newton against the converged alternation.
#[test]
fn three_nodes_against_converged_alternation() {
    let m = 3;
    let n = 3 * m;
    for case in 0..4 {
        let mut rows = vec![vec![0.0; n]; n];
        for k in 0..m {
            for l in 0..m {
                let dist = (k as f64 - l as f64).abs();
                let kern = (-dist).exp();
                rows[3 * k][3 * l] = 2e-7 * kern * if k == l { 1.0 } else { 0.6 };
                rows[3 * k + 1][3 * l + 1] = 4e-3 * kern;
                rows[3 * k + 2][3 * l + 2] = 7e-3 * kern;
                rows[3 * k + 1][3 * l + 2] = 0.5e-3 * kern;
                rows[3 * k + 2][3 * l + 1] = 0.5e-3 * kern;
                // weak normal–tangential coupling (β_N h² vs γ_N h rows), nonsymmetric
                rows[3 * k + 1][3 * l] = 1e-4 * kern;
                rows[3 * k][3 * l + 1] = 2e-9 * kern;
            }
        }
        let d = col_major(&rows);
        let gaps = [
            [-1e-4, -2e-4, 5e-5],
            [-3e-4, -1e-4, -2e-4],
            [-1e-4, 1e-5, -1e-4],
            [-2e-4, -2e-4, -2e-4],
        ][case];
        let slips = [
            [[0.5, 0.1], [2.0, -0.3], [-1.0, 0.0]],
            [[0.2, 0.2], [0.1, -0.1], [3.0, 1.0]],
            [[-5.0, 0.0], [0.0, 0.0], [0.3, -0.2]],
            [[1.0, 1.0], [-1.0, 1.0], [0.1, 0.05]],
        ][case];
        let mut b = vec![0.0; n];
        for k in 0..m {
            b[3 * k] = gaps[k];
            b[3 * k + 1] = slips[k][0];
            b[3 * k + 2] = slips[k][1];
        }
        let mu = 0.85;
        let xr = reference(&d, &b, mu, 200);
        let (x, rep) = solve(&d, &b, &[0.0; 9], &coulomb(mu));
        assert!(rep.converged, "case {case}: {rep:?}");
        let scale = xr.iter().step_by(3).fold(0.0f64, |a, l| a.max(*l));
        for i in 0..n {
            assert!(
                (x[i] - xr[i]).abs() <= 1e-7 * scale,
                "case {case} entry {i}: Newton {} vs reference {}",
                x[i],
                xr[i]
            );
        }
    }
}

/// The natural residuals of a solution: complementarity `|min(λ, g/d_N)|`, the cone
/// `|f| − μλ`, and the Coulomb direction `|f + μλ u/|u||` for slipping contacts (forces, N).
fn check_coulomb(d: &[f64], b: &[f64], x: &[f64], mu: f64, tol: f64) -> Result<(), TestCaseError> {
    let m = b.len() / 3;
    let y = outputs(d, b, x);
    let diag = diag_of(d, m);
    let scale = (0..m).fold(1e-12f64, |a, k| a.max(x[3 * k]));
    for k in 0..m {
        let (lam, g) = (x[3 * k], y[3 * k]);
        prop_assert!(lam >= 0.0);
        prop_assert!(g >= -tol * scale * diag[k][0], "gap {g} at {k}");
        prop_assert!(
            lam.min(g / diag[k][0]).abs() <= tol * scale,
            "complementarity at {k}"
        );
        let f = [x[3 * k + 1], x[3 * k + 2]];
        let fm = f[0].hypot(f[1]);
        prop_assert!(
            fm <= mu * lam + tol * scale,
            "cone at {k}: {fm} > {}",
            mu * lam
        );
        let u = [y[3 * k + 1], y[3 * k + 2]];
        let um = u[0].hypot(u[1]);
        if lam > tol * scale && um / diag[k][1] > 1e-4 * scale {
            // slipping: on the cone, opposite to the slip. The direction of a small slip is
            // ill-conditioned: a force residual e of the Alart–Curnier friction equation
            // f = proj_{μλ}(f − u/D_TT) turns f by about e (1 + μλ D_TT/|u|) (the fixed point's
            // amplification near the stick boundary), so the direction is checked to the
            // tolerance times that factor
            prop_assert!(
                (fm - mu * lam).abs() <= tol * scale,
                "slip not on the cone at {k}"
            );
            let amplification = 1.0 + mu * lam * diag[k][1] / um;
            let off = (f[0] + mu * lam * u[0] / um).abs() + (f[1] + mu * lam * u[1] / um).abs();
            prop_assert!(
                off <= 2.0 * tol * scale * amplification,
                "friction not opposite to the slip at {k}: {off:.3e} N off, slip {um:.3e}, \
                 amplification {amplification:.1}"
            );
        }
    }
    Ok(())
}

/// A random (nonsymmetric) local Delassus matrix with a positive definite symmetric part of the
/// tangential blocks and tire-like scaling of the normal and tangential rows.
fn random_problem(m: usize, seed: &[f64], gaps: &[f64], slips: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = 3 * m;
    let mut bmat = vec![vec![0.0; n]; n];
    for i in 0..n {
        for j in 0..n {
            bmat[i][j] = seed[(i * n + j) % seed.len()]
                * if (i + 2 * j).is_multiple_of(3) {
                    1.0
                } else {
                    0.5
                };
        }
    }
    // A = B Bᵀ / n + I + skew (positive definite symmetric part), scaled by rows/columns
    let sc = |i: usize| -> f64 { if i.is_multiple_of(3) { 1e-3 } else { 1.0 } };
    let mut rows = vec![vec![0.0; n]; n];
    for i in 0..n {
        for j in 0..n {
            let mut v = (0..n).map(|k| bmat[i][k] * bmat[j][k]).sum::<f64>() / n as f64;
            if i == j {
                v += 1.0;
            }
            v += 0.1 * (bmat[i][j] - bmat[j][i]);
            // normal–tangential coupling kept moderate (|D_NT| μ < |D_NN|: beyond it the
            // frictional problem may have no solution, Painlevé-like)
            let cross = if i.is_multiple_of(3) != j.is_multiple_of(3) {
                0.1
            } else {
                1.0
            };
            rows[i][j] = cross * v * sc(i).sqrt() * sc(j).sqrt();
        }
    }
    let mut b = vec![0.0; n];
    for k in 0..m {
        b[3 * k] = gaps[k] * 1e-3f64.sqrt();
        b[3 * k + 1] = slips[2 * k];
        b[3 * k + 2] = slips[2 * k + 1];
    }
    (col_major(&rows), b)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Complementarity and Coulomb cone invariants on random problems (Alart–Curnier zeros are
    /// exactly the Signorini–Coulomb conditions).
    #[test]
    fn random_problems_satisfy_signorini_coulomb(
        m in 1usize..7,
        seed in prop::collection::vec(-1.0f64..1.0, 50),
        gaps in prop::collection::vec(-2.0f64..1.0, 6),
        slips in prop::collection::vec(-3.0f64..3.0, 12),
        mu in 0.0f64..1.0,
        warm in prop::bool::ANY,
    ) {
        let (d, b) = random_problem(m, &seed, &gaps, &slips);
        let x0 = if warm { reference(&d, &b, mu, 1).iter().map(|v| v * 0.9).collect() } else { vec![0.0; 3 * m] };
        let (x, rep) = solve(&d, &b, &x0[..3 * m], &coulomb(mu));
        prop_assert!(rep.converged, "{rep:?}");
        check_coulomb(&d, &b, &x, mu, 1e-8)?;
    }

    /// The regularised law `f = −μλ u/√(|u|²+ε²)` (Ribaric, seed note U20) with the same
    /// normal complementarity.
    #[test]
    fn random_problems_regularized_law(
        m in 1usize..7,
        seed in prop::collection::vec(-1.0f64..1.0, 50),
        gaps in prop::collection::vec(-2.0f64..1.0, 6),
        slips in prop::collection::vec(-3.0f64..3.0, 12),
        mu in 0.0f64..1.0,
        eps in 0.05f64..1.0,
    ) {
        let (d, b) = random_problem(m, &seed, &gaps, &slips);
        let s = ContactSolverOptions { law: Arc::new(SlipRegularized { mu, epsilon: eps }), ..ContactSolverOptions::default() };
        let (x, rep) = solve(&d, &b, &vec![0.0; 3 * m], &s);
        prop_assert!(rep.converged, "{rep:?}");
        let y = outputs(&d, &b, &x);
        let scale = (0..m).fold(1e-12f64, |a, k| a.max(x[3 * k]));
        for k in 0..m {
            let lam = x[3 * k];
            prop_assert!(lam >= 0.0);
            prop_assert!(lam.min(y[3 * k] / d[3 * k * 3 * m + 3 * k]).abs() <= 1e-8 * scale);
            let u = [y[3 * k + 1], y[3 * k + 2]];
            let r = (u[0] * u[0] + u[1] * u[1] + eps * eps).sqrt();
            for a in 0..2 {
                prop_assert!((x[3 * k + 1 + a] + mu * lam * u[a] / r).abs() <= 1e-8 * scale);
            }
        }
    }
}

/// Reusing the previous solve's Newton matrices (chord steps, `reuse = true`) and a second
/// warm start must not change the answer: a sequence of slowly varying problems (as in time
/// stepping) solved with reuse against fresh solves (second route to the same zeros of Φ).
#[test]
fn reuse_of_newton_matrices_gives_the_fresh_solution() {
    let m = 4;
    let seed: Vec<f64> = (0..50)
        .map(|i| ((i * 37 % 23) as f64 / 11.5) - 1.0)
        .collect();
    let gaps = [-1.5, -0.5, 0.3, -1.0, 0.0, 0.0];
    let slips = [1.0, 0.5, -2.0, 0.2, 0.1, -0.1, 0.5, 0.5, 0.0, 0.0, 0.0, 0.0];
    let mut solver = ContactSolver::default();
    let mut prev: Vec<f64> = vec![0.0; 3 * m];
    let mut prev2: Vec<f64> = vec![0.0; 3 * m];
    let mut chords = 0;
    for step in 0..40 {
        let t = step as f64 * 0.05;
        let g: Vec<f64> = gaps.iter().map(|g| g + 0.3 * (3.0 * t).sin()).collect();
        let u: Vec<f64> = slips.iter().map(|v| v * (1.0 + 0.5 * t.cos())).collect();
        let (d, b) = random_problem(m, &seed, &g, &u);
        let s = coulomb(0.7);
        solver.reset(&prev);
        solver.set_gaps((0..m).map(|k| b[3 * k]));
        let mut src = DenseProblem { d: &d, b: &b };
        let rep = solver.solve(&mut src, &diag_of(&d, m), &s, step > 0, &[&prev2]);
        assert!(rep.converged, "step {step}: {rep:?}");
        chords += rep.chord_iterations;
        let x = solver.x().to_vec();
        let (xf, repf) = solve(&d, &b, &vec![0.0; 3 * m], &s);
        assert!(repf.converged);
        let scale = xf.iter().step_by(3).fold(1e-12f64, |a, l| a.max(*l));
        for i in 0..3 * m {
            assert!(
                (x[i] - xf[i]).abs() <= 1e-8 * scale,
                "step {step} entry {i}: reuse {} vs fresh {}",
                x[i],
                xf[i]
            );
        }
        prev2 = std::mem::replace(&mut prev, x);
    }
    assert!(chords > 0, "the chord path was not exercised");
}

/// Configs: `friction_law` is `coulomb` (default) or `regularized`; configs that set
/// `slip_regularization` (session 2 files) still load; an unknown law is rejected by name.
#[test]
fn rolling_config_friction_law_parses() {
    use tire::RollingConfig;
    // the rolling settings' checks are the workspace's one validation trait (issue 20)
    use mbd_core::Validate;
    let old: RollingConfig =
        toml::from_str("friction = 0.85\nslip_regularization = 0.05\n").unwrap();
    assert_eq!(old.friction_law, TireFriction::Coulomb);
    let reg: RollingConfig =
        toml::from_str("friction_law = \"regularized\"\nslip_regularization = 0.02\n").unwrap();
    assert_eq!(reg.friction_law, TireFriction::Regularized);
    assert!(reg.validate().is_ok());
    let bad = toml::from_str::<RollingConfig>("friction_law = \"sticky\"\n").unwrap_err();
    assert!(bad.to_string().contains("sticky"), "{bad}");
    let neg = RollingConfig {
        contact_tolerance: 0.0,
        ..RollingConfig::default()
    };
    assert!(
        neg.validate()
            .unwrap_err()
            .to_string()
            .contains("contact_tolerance")
    );
}
