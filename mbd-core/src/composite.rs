//! Composition of several [`SecondOrderSystem`]s into one model with coupling constraints
//! (e.g. an ANCF belt and rigid pulleys, a reduced flexible body and a rigid mechanism), so that
//! one integrator advances all of them together.
//!
//! The parts keep their own coordinates, stacked in the order they were added
//! ([`CompositeSystem::q_offset`], [`CompositeSystem::v_offset`]); their mass, force and
//! constraint blocks are assembled block-diagonally, followed by the rows of the couplings,
//! which act on the global vectors.

use crate::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix, Workspace};
use faer::sparse::Triplet;

/// Output of a [`Coupling`]: residuals, Jacobian entries (local row, global velocity column,
/// value), `ν` and `γ`, each of length `n_eq` (entries: any number).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CouplingEval {
    /// `Φ`.
    pub phi: Vec<f64>,
    /// Jacobian entries `(row, column, value)` w.r.t. the global velocities.
    pub jacobian: Vec<(usize, usize, f64)>,
    /// `ν = −Φ_t`.
    pub nu: Vec<f64>,
    /// `γ` of `D v̇ = γ`.
    pub gamma: Vec<f64>,
}

/// A constraint between parts, written on the global coordinates (extension point).
pub trait Coupling: Send + Sync {
    /// Name used in messages.
    fn name(&self) -> &str;
    /// Number of equations.
    fn n_eq(&self) -> usize;
    /// Evaluates at time `t` \[s\] on the global `q`, `v` (velocities zero when only `Φ` or `D`
    /// are needed).
    fn eval(&self, t: f64, q: &[f64], v: &[f64], out: &mut CouplingEval);
}

/// Several systems and their couplings as one [`SecondOrderSystem`].
#[derive(Default)]
pub struct CompositeSystem<'a> {
    parts: Vec<Box<dyn SecondOrderSystem + 'a>>,
    names: Vec<String>,
    couplings: Vec<Box<dyn Coupling + 'a>>,
    q_off: Vec<usize>,
    v_off: Vec<usize>,
    c_off: Vec<usize>,
    n_q: usize,
    n_v: usize,
    n_c_parts: usize,
    n_c_coupling: usize,
}

impl<'a> CompositeSystem<'a> {
    /// Empty composite.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a part (named for messages); returns its index.
    pub fn add_part(&mut self, name: &str, part: impl SecondOrderSystem + 'a) -> usize {
        self.q_off.push(self.n_q);
        self.v_off.push(self.n_v);
        self.c_off.push(self.n_c_parts);
        self.n_q += part.n_q();
        self.n_v += part.n_v();
        self.n_c_parts += part.n_c();
        self.parts.push(Box::new(part));
        self.names.push(name.into());
        self.parts.len() - 1
    }

    /// Adds a coupling constraint.
    pub fn add_coupling(&mut self, c: impl Coupling + 'a) {
        self.n_c_coupling += c.n_eq();
        self.couplings.push(Box::new(c));
    }

    /// Offset of part `k` in the global positions.
    pub fn q_offset(&self, k: usize) -> usize {
        self.q_off[k]
    }

    /// Offset of part `k` in the global velocities.
    pub fn v_offset(&self, k: usize) -> usize {
        self.v_off[k]
    }

    /// Offset of part `k`'s constraint rows (couplings follow all parts).
    pub fn c_offset(&self, k: usize) -> usize {
        self.c_off[k]
    }

    fn qs<'s>(&self, k: usize, q: &'s [f64]) -> &'s [f64] {
        &q[self.q_off[k]..self.q_off[k] + self.parts[k].n_q()]
    }

    fn vs<'s>(&self, k: usize, v: &'s [f64]) -> &'s [f64] {
        &v[self.v_off[k]..self.v_off[k] + self.parts[k].n_v()]
    }

    /// The couplings evaluated at `(t, q, v)` (`v = 0` when `None`), checked by
    /// [`Self::check_eval`].
    fn couplings_eval(
        &self, t: f64, q: &[f64], v: Option<&[f64]>,
    ) -> Result<Vec<CouplingEval>, MbdError> {
        let zero;
        let v = match v {
            Some(v) => v,
            None => {
                zero = vec![0.0; self.n_v];
                &zero
            }
        };
        let evals = self
            .couplings
            .iter()
            .map(|c| {
                let mut e = CouplingEval {
                    phi: vec![0.0; c.n_eq()],
                    jacobian: Vec::new(),
                    nu: vec![0.0; c.n_eq()],
                    gamma: vec![0.0; c.n_eq()],
                };
                c.eval(t, q, v, &mut e);
                e
            })
            .collect::<Vec<_>>();
        self.check_eval(t, &evals)?;
        Ok(evals)
    }

    /// Write the couplings' rows of one constraint vector (`Φ`, `ν` or `γ`, picked by `field`)
    /// into `out` below the parts' rows.
    fn put_couplings(
        &self, t: f64, q: &[f64], v: Option<&[f64]>, out: &mut [f64],
        field: fn(&CouplingEval) -> &[f64],
    ) -> Result<(), MbdError> {
        let mut r = self.n_c_parts;
        for e in self.couplings_eval(t, q, v)? {
            let x = field(&e);
            out[r..r + x.len()].copy_from_slice(x);
            r += x.len();
        }
        Ok(())
    }

    fn check_eval(&self, t: f64, evals: &[CouplingEval]) -> Result<(), MbdError> {
        for (c, e) in self.couplings.iter().zip(evals) {
            let n = c.n_eq();
            if e.phi.len() != n || e.nu.len() != n || e.gamma.len() != n {
                return Err(MbdError::Model {
                    t,
                    message: format!("coupling \"{}\" returned wrong lengths", c.name()),
                });
            }
            if e.jacobian
                .iter()
                .any(|&(r, col, _)| r >= n || col >= self.n_v)
            {
                return Err(MbdError::Model {
                    t,
                    message: format!("coupling \"{}\": Jacobian entry out of range", c.name()),
                });
            }
        }
        Ok(())
    }

    /// Block-diagonal assembly (rows/columns offset per part), sparse if any block is or the
    /// matrix is large ([`SysMatrix::assemble`]).
    fn block_diag(
        &self, blocks: Vec<(usize, usize, SysMatrix)>, extra: Vec<Triplet<usize, usize, f64>>,
        nr: usize, nc: usize, t: f64,
    ) -> Result<SysMatrix, MbdError> {
        SysMatrix::assemble(&blocks, extra, nr, nc, nr.max(nc) > 600, t)
    }

    fn part_of_v(&self, dof: usize) -> usize {
        self.v_off.partition_point(|&o| o <= dof).saturating_sub(1)
    }
}

impl SecondOrderSystem for CompositeSystem<'_> {
    fn n_q(&self) -> usize {
        self.n_q
    }
    fn n_v(&self) -> usize {
        self.n_v
    }
    fn n_c(&self) -> usize {
        self.n_c_parts + self.n_c_coupling
    }

    fn position_rate(&self, q: &[f64], v: &[f64], qdot: &mut [f64]) {
        for (k, p) in self.parts.iter().enumerate() {
            let o = self.q_off[k];
            p.position_rate(self.qs(k, q), self.vs(k, v), &mut qdot[o..o + p.n_q()]);
        }
    }

    fn normalize(&self, q: &mut [f64]) {
        for (k, p) in self.parts.iter().enumerate() {
            let o = self.q_off[k];
            p.normalize(&mut q[o..o + p.n_q()]);
        }
    }

    fn integrate_position(&self, q: &[f64], dq: &[f64], q_new: &mut [f64]) {
        for (k, p) in self.parts.iter().enumerate() {
            let o = self.q_off[k];
            p.integrate_position(self.qs(k, q), self.vs(k, dq), &mut q_new[o..o + p.n_q()]);
        }
    }

    fn mass_is_constant(&self) -> bool {
        self.parts.iter().all(|p| p.mass_is_constant())
    }

    fn check_state(&self, t: f64, q: &[f64], v: &[f64]) -> Result<(), MbdError> {
        for (k, p) in self.parts.iter().enumerate() {
            p.check_state(t, self.qs(k, q), self.vs(k, v))
                .map_err(|e| prefix(&self.names[k], e))?;
        }
        Ok(())
    }

    fn mass(&self, t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let mut blocks = Vec::new();
        for (k, p) in self.parts.iter().enumerate() {
            let m = p
                .mass(t, self.qs(k, q))
                .map_err(|e| prefix(&self.names[k], e))?;
            blocks.push((self.v_off[k], self.v_off[k], m));
        }
        self.block_diag(blocks, Vec::new(), self.n_v, self.n_v, t)
    }

    /// The parts' forces, each with its own workspace ([`Workspace::parts`]).
    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        let part_ws = ws.parts(self.parts.len());
        for (k, p) in self.parts.iter().enumerate() {
            let o = self.v_off[k];
            p.forces(
                t,
                self.qs(k, q),
                self.vs(k, v),
                &mut f[o..o + p.n_v()],
                &mut part_ws[k],
            )
            .map_err(|e| prefix(&self.names[k], e))?;
        }
        Ok(())
    }

    /// Block-diagonal tangent; parts without an analytic tangent get a local forward-difference
    /// block.
    fn force_tangent(
        &self, t: f64, q: &[f64], v: &[f64], ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let mut kb = Vec::new();
        let mut cb = Vec::new();
        let part_ws = ws.parts(self.parts.len());
        for (k, p) in self.parts.iter().enumerate() {
            let (qk, vk) = (self.qs(k, q), self.vs(k, v));
            let tg = match p.force_tangent(t, qk, vk, &mut part_ws[k])? {
                Some(tg) => tg,
                None => fd_tangent(p.as_ref(), t, qk, vk, &mut part_ws[k])?,
            };
            kb.push((self.v_off[k], self.v_off[k], tg.stiffness));
            cb.push((self.v_off[k], self.v_off[k], tg.damping));
        }
        Ok(Some(ForceTangent {
            stiffness: self.block_diag(kb, Vec::new(), self.n_v, self.n_v, t)?,
            damping: self.block_diag(cb, Vec::new(), self.n_v, self.n_v, t)?,
        }))
    }

    fn constraint_force_tangent(
        &self, t: f64, q: &[f64], lambda: &[f64],
    ) -> Result<Option<SysMatrix>, MbdError> {
        let mut blocks = Vec::new();
        for (k, p) in self.parts.iter().enumerate() {
            if p.n_c() == 0 {
                continue;
            }
            let l = &lambda[self.c_off[k]..self.c_off[k] + p.n_c()];
            if let Some(m) = p.constraint_force_tangent(t, self.qs(k, q), l)? {
                blocks.push((self.v_off[k], self.v_off[k], m));
            }
        }
        if blocks.is_empty() {
            return Ok(None);
        }
        Ok(Some(self.block_diag(
            blocks,
            Vec::new(),
            self.n_v,
            self.n_v,
            t,
        )?))
    }

    fn constraint_residual(&self, t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        for (k, p) in self.parts.iter().enumerate() {
            let o = self.c_off[k];
            p.constraint_residual(t, self.qs(k, q), &mut phi[o..o + p.n_c()])?;
        }
        self.put_couplings(t, q, None, phi, |e| &e.phi)
    }

    fn constraint_jacobian(&self, t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let mut blocks = Vec::new();
        for (k, p) in self.parts.iter().enumerate() {
            if p.n_c() > 0 {
                blocks.push((
                    self.c_off[k],
                    self.v_off[k],
                    p.constraint_jacobian(t, self.qs(k, q))?,
                ));
            }
        }
        let ev = self.couplings_eval(t, q, None)?;
        let mut extra = Vec::new();
        let mut r = self.n_c_parts;
        for e in ev {
            for &(i, j, val) in &e.jacobian {
                extra.push(Triplet::new(r + i, j, val));
            }
            r += e.phi.len();
        }
        self.block_diag(blocks, extra, self.n_c(), self.n_v, t)
    }

    fn constraint_velocity_rhs(&self, t: f64, q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        for (k, p) in self.parts.iter().enumerate() {
            let o = self.c_off[k];
            p.constraint_velocity_rhs(t, self.qs(k, q), &mut nu[o..o + p.n_c()])?;
        }
        self.put_couplings(t, q, None, nu, |e| &e.nu)
    }

    fn constraint_gamma(
        &self, t: f64, q: &[f64], v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        for (k, p) in self.parts.iter().enumerate() {
            let o = self.c_off[k];
            p.constraint_gamma(t, self.qs(k, q), self.vs(k, v), &mut gamma[o..o + p.n_c()])?;
        }
        self.put_couplings(t, q, Some(v), gamma, |e| &e.gamma)
    }

    fn constraint_name(&self, row: usize) -> String {
        if row < self.n_c_parts {
            let k = self.c_off.partition_point(|&o| o <= row).saturating_sub(1);
            // skip parts without constraints that share the offset
            let k = (0..=k)
                .rev()
                .find(|&k| row < self.c_off[k] + self.parts[k].n_c())
                .unwrap_or(k);
            format!(
                "{}: {}",
                self.names[k],
                self.parts[k].constraint_name(row - self.c_off[k])
            )
        } else {
            let mut r = self.n_c_parts;
            for c in &self.couplings {
                if row < r + c.n_eq() {
                    return format!("coupling \"{}\" (equation {})", c.name(), row - r);
                }
                r += c.n_eq();
            }
            format!("constraint row {row}")
        }
    }

    fn dof_name(&self, dof: usize) -> String {
        let k = self.part_of_v(dof);
        match self.parts.get(k) {
            Some(p) => format!("{}: {}", self.names[k], p.dof_name(dof - self.v_off[k])),
            None => format!("coordinate {dof}"),
        }
    }
}

fn prefix(name: &str, e: MbdError) -> MbdError {
    match e {
        MbdError::Model { t, message } => MbdError::Model {
            t,
            message: format!("{name}: {message}"),
        },
        MbdError::NonFinite { what, t } => MbdError::NonFinite {
            what: format!("{name}: {what}"),
            t,
        },
        MbdError::InvalidInput { item, reason } => MbdError::InvalidInput {
            item: format!("{name}: {item}"),
            reason,
        },
        other => other,
    }
}

/// Dense forward-difference tangent of one part (through its `⊕`).
fn fd_tangent(
    p: &dyn SecondOrderSystem, t: f64, q: &[f64], v: &[f64], ws: &mut Workspace,
) -> Result<ForceTangent, MbdError> {
    crate::system::finite_difference_tangent(p, t, q, v, ws)
}
