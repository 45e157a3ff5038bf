//! The fallback of the contact solve: the normal LCP with the friction frozen, alternated with
//! block Gauss–Seidel sweeps on the friction forces (the law's exact one-contact solve).

use super::alart_curnier::ContactSolver;
use super::options::{ContactSolverOptions, ContactSolverReport};
use super::problem::DelassusSource;
use nalgebra::{Matrix2, Vector2};

impl ContactSolver {
    /// The fallback: normal LCP with the friction frozen, alternated with block Gauss–Seidel
    /// sweeps on the friction forces (exact local Coulomb / regularised solve per contact),
    /// until `‖Φ‖∞ ≤ tol · max λ` or `max_rounds`. Returns `‖Φ‖∞`.
    pub(super) fn alternation(
        &mut self, src: &mut dyn DelassusSource, diag: &[[f64; 2]], s: &ContactSolverOptions,
        rep: &mut ContactSolverReport,
    ) -> f64 {
        // x changes below without a residual: no linearisation at it
        self.lin_ok = false;
        let m = self.m;
        let n = 3 * m;
        for l in 0..m {
            self.ensure_col(src, l);
        }
        let mut norm = f64::INFINITY;
        for _round in 0..s.max_rounds {
            // normal problem: W = D_NN, q = b_N + D_NT f
            self.wn.resize_with(m, m, |_, _| 0.0);
            self.q.clear();
            self.warm.clear();
            for k in 0..m {
                let mut g = self.b[3 * k];
                for l in 0..m {
                    self.wn[(k, l)] = self.d[3 * l * n + 3 * k];
                    for a in 1..3 {
                        g += self.d[(3 * l + a) * n + 3 * k] * self.x[3 * l + a];
                    }
                }
                self.q.push(g);
                self.warm.push(self.x[3 * k] > 0.0);
            }
            let tol_gap = 1e-3 * s.tol * diag.iter().fold(0.0f64, |a, d| a.max(d[0])) * {
                let sc = self.scale();
                if sc > 0.0 { sc } else { 1.0 }
            };
            let _ = self
                .lcp
                .solve(self.wn.as_ref(), &self.q, &self.warm, tol_gap);
            rep.lcp_solves += 1;
            for k in 0..m {
                self.x[3 * k] = self.lcp.lambda[k];
                if self.x[3 * k] <= 0.0 {
                    self.x[3 * k + 1] = 0.0;
                    self.x[3 * k + 2] = 0.0;
                }
            }
            for k in 0..m {
                if self.need_slip && self.x[3 * k] > 0.0 {
                    self.ensure_b(src, k);
                }
            }
            let mut y = std::mem::take(&mut self.y);
            self.apply(&self.x, &mut y, true);
            // friction sweeps
            if s.law.coefficient() > 0.0 {
                for _ in 0..50 {
                    rep.sweeps += 1;
                    let mut change = 0.0f64;
                    for k in 0..m {
                        let lam = self.x[3 * k];
                        if lam <= 0.0 {
                            continue;
                        }
                        let bt = [
                            [
                                self.d[(3 * k + 1) * n + 3 * k + 1],
                                self.d[(3 * k + 2) * n + 3 * k + 1],
                            ],
                            [
                                self.d[(3 * k + 1) * n + 3 * k + 2],
                                self.d[(3 * k + 2) * n + 3 * k + 2],
                            ],
                        ];
                        let f = [self.x[3 * k + 1], self.x[3 * k + 2]];
                        // slip velocity without the contact's own friction
                        let r = [
                            y[3 * k + 1] - bt[0][0] * f[0] - bt[0][1] * f[1],
                            y[3 * k + 2] - bt[1][0] * f[0] - bt[1][1] * f[1],
                        ];
                        let new = s.law.local_force(
                            Matrix2::new(bt[0][0], bt[0][1], bt[1][0], bt[1][1]),
                            Vector2::new(r[0], r[1]),
                            lam,
                        );
                        let new = [new[0], new[1]];
                        let d = [new[0] - f[0], new[1] - f[1]];
                        if d == [0.0, 0.0] {
                            continue;
                        }
                        change = change.max(d[0].abs().max(d[1].abs()));
                        self.x[3 * k + 1] = new[0];
                        self.x[3 * k + 2] = new[1];
                        for a in 0..2 {
                            let col = &self.d[(3 * k + 1 + a) * n..(3 * k + 2 + a) * n];
                            for (yi, &c) in y.iter_mut().zip(col) {
                                *yi += d[a] * c;
                            }
                        }
                    }
                    if change <= 1e-3 * s.tol * self.scale() {
                        break;
                    }
                }
            }
            self.y = y;
            norm = self.evaluate(src, s);
            if norm <= s.tol * self.scale() {
                break;
            }
        }
        norm
    }
}
