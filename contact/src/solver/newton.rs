//! The Newton (or chord) direction of the Alart–Curnier equations: the Jacobian of the pressed
//! contacts, its faer LU (the last few kept by classification for chord steps) and the solve.

use super::alart_curnier::{ContactSolver, State};
use super::options::ContactSolverOptions;
use super::problem::DelassusSource;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::factor::{lu_in_place, lu_in_place_scratch};
use faer::prelude::*;
use faer::{Mat, Par};
use mbd_core::linalg::{col_slice, lu_solve_in_place};

/// A factorised Newton matrix and the classification of the contacts it was built for.
pub(super) struct LuSlot {
    pub(super) pattern: Vec<u8>,
    pub(super) n: usize,
    /// Packed LU factors `P J = L U`.
    pub(super) lu: Mat<f64>,
    pub(super) perm: Vec<usize>,
    pub(super) perm_inv: Vec<usize>,
    pub(super) valid: bool,
    /// Clock of the last use (least recently used slot is refactorised).
    pub(super) used: u64,
}

impl LuSlot {
    /// An empty slot.
    pub(super) fn empty() -> Self {
        Self {
            pattern: Vec::new(),
            n: 0,
            lu: Mat::zeros(0, 0),
            perm: Vec::new(),
            perm_inv: Vec::new(),
            valid: false,
            used: 0,
        }
    }
}

impl ContactSolver {
    /// The Newton direction `dx` (and `dy = D dx`) at `x`; `None` if the Jacobian is singular
    /// or (`chord`) the classification changed since the last LU, else whether an LU was made.
    /// With `chord`, the last LU replaces the Jacobian (simplified Newton).
    pub(super) fn newton_direction(
        &mut self, src: &mut dyn DelassusSource, s: &ContactSolverOptions, chord: bool,
    ) -> Option<bool> {
        let m = self.m;
        let n = 3 * m;
        // the linearisation at (x, y): formed with the residual there (evaluation or line
        // search), else now
        if !self.lin_ok {
            let (x, y) = (std::mem::take(&mut self.x), std::mem::take(&mut self.y));
            let (mut lin, mut phi) = (std::mem::take(&mut self.lin), std::mem::take(&mut self.tmp));
            phi.resize(n, 0.0);
            self.residual(s, &x, &y, &mut phi, Some(&mut lin));
            (self.x, self.y, self.lin, self.tmp) = (x, y, lin, phi);
            self.lin_ok = true;
        }
        self.act.clear();
        for k in 0..m {
            if self.lin.pattern[k] == 0 {
                self.state[k] = State::Open;
            } else {
                self.state[k] = State::Pressed;
                self.act.push(k);
            }
        }
        for i in 0..self.act.len() {
            let k = self.act[i];
            self.ensure_col(src, k);
        }
        let na = 3 * self.act.len();
        // open contacts: dx_k = −x_k; their effect on the pressed rows goes to the rhs
        for k in 0..m {
            if self.state[k] == State::Open {
                for a in 0..3 {
                    self.dx[3 * k + a] = -self.x[3 * k + a];
                }
            } else {
                for a in 0..3 {
                    self.dx[3 * k + a] = 0.0;
                }
            }
        }
        // dy_open = D dx_open (columns available: x_k ≠ 0 had its column)
        let mut dy = std::mem::take(&mut self.dy);
        self.apply(&self.dx, &mut dy, false);
        // a cached LU of the same classification (chord), or the slot to factor into
        let found = self
            .slots
            .iter()
            .position(|sl| sl.valid && sl.pattern == self.lin.pattern);
        let chord = chord && found.is_some();
        self.clock += 1;
        let cur = match found {
            Some(i) => i,
            None => {
                let mut best = 0;
                for (i, sl) in self.slots.iter().enumerate() {
                    if !sl.valid || sl.used < self.slots[best].used {
                        best = i;
                        if !sl.valid {
                            break;
                        }
                    }
                }
                best
            }
        };
        self.slots[cur].used = self.clock;
        if !chord {
            // the slot's old factors are overwritten: valid again only once refactorised
            self.slots[cur].valid = false;
            self.slots[cur].lu.resize_with(na, na, |_, _| 0.0);
        }
        self.rhs.clear();
        for &k in self.act.iter() {
            let g = &self.lin.gk[k];
            for r in 0..3 {
                let mut v = -self.phi[3 * k + r];
                for c in 0..3 {
                    v -= g[r][c] * dy[3 * k + c];
                }
                self.rhs.push(v);
            }
        }
        if !chord {
            // J_kl = δ_kl L_k + G_k D_kl, column by column
            for (ja, &l) in self.act.iter().enumerate() {
                for c in 0..3 {
                    let dcol = &self.d[(3 * l + c) * n..(3 * l + c + 1) * n];
                    let mut jc = self.slots[cur].lu.col_mut(3 * ja + c);
                    let Some(jcol) = jc.rb_mut().try_as_col_major_mut() else {
                        self.dy = dy;
                        return None;
                    };
                    let jcol = jcol.as_slice_mut();
                    for (ia, &k) in self.act.iter().enumerate() {
                        let g = &self.lin.gk[k];
                        let d3 = &dcol[3 * k..3 * k + 3];
                        for r in 0..3 {
                            jcol[3 * ia + r] = g[r][0] * d3[0] + g[r][1] * d3[1] + g[r][2] * d3[2];
                        }
                        if k == l {
                            for r in 0..3 {
                                jcol[3 * ia + r] += self.lin.lk[k][r][c];
                            }
                        }
                    }
                }
            }
        }
        let slot = &mut self.slots[cur];
        if chord && slot.n != na {
            self.dy = dy;
            return None;
        }
        if na > 0 && !chord {
            slot.valid = false;
            if self.mem_n < na {
                self.mem = Some(MemBuffer::new(lu_in_place_scratch::<usize, f64>(
                    na,
                    na,
                    Par::Seq,
                    Default::default(),
                )));
                self.mem_n = na;
            }
            slot.perm.resize(na, 0);
            slot.perm_inv.resize(na, 0);
            let Some(mem) = self.mem.as_mut() else {
                self.dy = dy;
                return None;
            };
            let _ = lu_in_place(
                slot.lu.as_mut(),
                &mut slot.perm,
                &mut slot.perm_inv,
                Par::Seq,
                MemStack::new(mem),
                Default::default(),
            );
            let singular = (0..na).any(|i| {
                let d = slot.lu[(i, i)];
                !(d.is_finite() && d != 0.0)
            });
            if singular {
                self.dy = dy;
                return None;
            }
            slot.valid = true;
            slot.n = na;
            slot.pattern.clear();
            slot.pattern.extend_from_slice(&self.lin.pattern);
        }
        if na > 0 {
            self.tmp.clear();
            self.tmp.extend(slot.perm.iter().map(|&p| self.rhs[p]));
            // (faer's two triangular solves, bitwise, without their per-block dispatch)
            let lu = &slot.lu;
            lu_solve_in_place(|j| col_slice(lu, j), na, &mut self.tmp[..na]);
            for (ia, &k) in self.act.iter().enumerate() {
                for a in 0..3 {
                    self.dx[3 * k + a] = self.tmp[3 * ia + a];
                }
            }
            self.tmp.resize(n, 0.0);
        }
        self.apply(&self.dx, &mut dy, false);
        self.dy = dy;
        self.dx.iter().all(|v| v.is_finite()).then_some(!chord)
    }
}
