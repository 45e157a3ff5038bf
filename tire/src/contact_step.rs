//! The rolling tire's contact (seed note E15: unilateral gaps with Lagrange multipliers and
//! friction) as the [`StepCorrection`] of mbd-core's generalized-α stepper.
//!
//! After the smooth end-of-step solution (`[θ̈; z̈]` free of contact, [`super::dynamics`]) a
//! contact node `i` at `xᵢ = sᵢ + (T_c z)ᵢ` is a candidate when its gap on the ground is below
//! `contact_margin` (plus `h v` in front of the cleat, whose faces approach at the surface
//! speed; nodes whose gap is certainly above that by a lower bound from their last evaluation
//! are not evaluated, `GapBound`). Contact forces `fⱼ` (wheel frame) on the candidates change
//! the end-of-step accelerations by `Δv̇ = X Σ fⱼ` with the responses `X = S⁻¹ [0; T_cᵀ]` of all contact nodes
//! to unit forces and the node displacements by `Y = T_c X_z / β'` ([`AlphaCorrection`]: the
//! Delassus operator `W = J S⁻¹ Jᵀ`). `X` and `Y` are computed with the stepper's factored
//! iteration matrix ([`AlphaCorrection::solve_columns`]) once per factorisation and cached by
//! [`AlphaCorrection::factor_id`] (two entries: the rig alternates between two step sizes).
//! The normal and friction problems are solved together by the semismooth Newton method of
//! [`ContactSolver`] on the Alart–Curnier equations in the local frames, warm-started from the
//! forces of the last two steps; the result is applied with [`AlphaCorrection::apply`].
//!
//! Per step the work is kept to what changes: `T_c z` only of the nodes the bound does not
//! skip, the local Delassus matrix from a copy of the candidates' blocks of `Y` and `X_θ` that
//! is kept while the candidates and the factorisation stay the same (`CandidateBlocks`), the
//! free slip velocities only of the contacts that are pressed, and the vector loops (`D x`,
//! `X Σ fⱼ`, the free slip products) with AVX2 when the machine has it (`kernels`: the same
//! operations in the same order, so the results do not depend on the machine).

use crate::contact_solve::{ContactSolver, DelassusSource, SolveOptions};
use crate::dynamics::TireDynamics;
use crate::ground::{Ground, GroundPoint};
use crate::kernels::{axpy_cols, col_slice, dots3x2};
use crate::mirror::MirrorHalf;
use crate::reduced::ReducedTire;
use crate::rolling::{NormalContact, RollingConfig, StepStats};
use contact::friction::FrictionLaw;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};
use mbd_core::MbdError;
use mbd_core::integrators::{AlphaCorrection, StepCorrection};
use std::sync::Arc;

/// The contact-node responses of one factorisation of the iteration matrix.
pub(super) struct Responses {
    /// [`AlphaCorrection::factor_id`] of the factorisation.
    id: usize,
    /// `X = S⁻¹ [0; T_cᵀ]`: response of `[θ̈; z̈]` to unit forces on the contact-node DOF
    /// (n × 3 n_c).
    x: Mat<f64>,
    /// `Y = T_c X_z`: contact-node displacement response (3 n_c × 3 n_c, columns of node j at
    /// 3j..3j+3).
    y: Mat<f64>,
}

/// The contact of the rolling tire with the ground: the step correction and the contact state
/// (forces of the last two steps, candidates), see the module documentation.
pub struct TireContact {
    /// The ground.
    pub ground: Ground,
    cfg: RollingConfig,
    /// The friction law of `cfg` (built once).
    law: Arc<dyn FrictionLaw>,
    /// `[0; T_cᵀ]` (n × 3 n_c), the right-hand sides of the responses.
    load: Mat<f64>,
    /// `T_cᵀ` and `T_c,θᵀ` (n_z × 3 n_c): contiguous rows of the contact-node maps.
    tct: Mat<f64>,
    tct_theta: Mat<f64>,
    /// Responses of the current and of the other step size's factorisation.
    responses: [Option<Responses>; 2],
    /// Normal multiplier per contact node \[N\] (last step).
    pub lambda: Vec<f64>,
    /// Friction force per contact node (wheel frame) \[N\] (last step).
    pub friction: Vec<[f64; 3]>,
    /// Net force of the ground on the tire (wheel frame) \[N\] (last step).
    pub contact_force: [f64; 3],
    /// Contact nodes pressed onto the cleat in the last step.
    pub cleat_contacts: usize,
    /// Work counters (contact part).
    pub stats: StepStats,
    /// The image of each contact node in the half model of symmetric motion (see
    /// [`TireContact::new`]).
    mirror: Option<Vec<usize>>,
    /// Weight of each contact node's force in the generalised force (1; half model: 2 for a
    /// pair's representative, 0 for its image).
    weight: Vec<f64>,
    work: Work,
}

/// Per-step work arrays, allocated once.
struct Work {
    /// Contact-node displacements `T_c z` (3 n_c; only the entries of the nodes evaluated in
    /// this step are current).
    dc: Vec<f64>,
    /// The skip bound of the candidate search ([`GapBound`]).
    bound: GapBound,
    /// The nodes evaluated by the candidate search in this step.
    eval: Vec<usize>,
    /// Acceleration increment `X Σ fⱼ` (n).
    dvdot: Vec<f64>,
    /// The contact forces as coefficients of the columns of `X` (3 n_c, zero between steps).
    coef: Vec<f64>,
    cand: Vec<usize>,
    /// Whether each contact node was a candidate in the previous step.
    was_cand: Vec<bool>,
    gp: Vec<GroundPoint>,
    lambda: Vec<f64>,
    ft: Vec<[f64; 3]>,
    forces: Vec<[f64; 3]>,
    /// Warm starts `(λ, f1, f2)` per candidate (3m; from the last step, the one before and
    /// their extrapolation).
    x0: Vec<f64>,
    x1: Vec<f64>,
    x2: Vec<f64>,
    /// Normal and friction forces per contact node two steps back \[N\].
    lambda2: Vec<f64>,
    friction2: Vec<[f64; 3]>,
    diag: Vec<[f64; 2]>,
    /// Scaled local frames and rigid-spin coefficients of the candidates ([`TireDelassus`]).
    frames: Vec<[[f64; 3]; 3]>,
    rig_t1: Vec<f64>,
    /// The coupled normal + friction solver (buffers reused).
    solver: ContactSolver,
    /// The candidates' blocks of `Y` and `X_θ` gathered so far (kept while the candidates and
    /// the factorisation are those of the last step).
    blocks: CandidateBlocks,
}

/// The blocks of the cached responses that the local Delassus matrix of the candidates reads
/// ([`TireDelassus`]), gathered once per candidate set and factorisation instead of once per
/// step: `Y` of candidate `l`'s three unit forces at every candidate `k` (3m × 3m, column
/// `3l + r`, rows `3k..3k+3`) and `X_θ` (row 0 of `X`). The values are copies, so the matrix
/// is the same as gathered from `Y` directly.
#[derive(Default)]
struct CandidateBlocks {
    /// [`AlphaCorrection::factor_id`] and the candidates the blocks belong to.
    id: usize,
    cand: Vec<usize>,
    /// Whether the columns of candidate `l` are gathered.
    have: Vec<bool>,
    y: Vec<f64>,
    /// Per candidate (all gathered at once): `X_θ` of its three unit forces and its own block
    /// of `Y` (`diag[k][r][a]` = row `a`, unit force `r`).
    x_theta: Vec<[f64; 3]>,
    diag: Vec<[[f64; 3]; 3]>,
}

impl CandidateBlocks {
    /// Keeps the blocks if `cand` and `id` are those they were gathered for, else starts
    /// empty for them.
    fn prepare(&mut self, fac: &Responses, cand: &[usize]) {
        if self.id == fac.id && self.cand == cand {
            return;
        }
        let m = cand.len();
        self.id = fac.id;
        self.cand.clear();
        self.cand.extend_from_slice(cand);
        self.have.clear();
        self.have.resize(m, false);
        self.y.resize(9 * m * m, 0.0);
        self.x_theta.clear();
        self.diag.clear();
        for &i in cand {
            let mut xth = [0.0; 3];
            let mut d = [[0.0; 3]; 3];
            for r in 0..3 {
                xth[r] = fac.x[(0, 3 * i + r)];
                d[r].copy_from_slice(&col_slice(&fac.y, 3 * i + r)[3 * i..3 * i + 3]);
            }
            self.x_theta.push(xth);
            self.diag.push(d);
        }
    }

    /// Gathers the columns of candidate `l` from `fac` if not yet done.
    fn gather(&mut self, fac: &Responses, l: usize) {
        if self.have[l] {
            return;
        }
        let ld = 3 * self.cand.len();
        let j = self.cand[l];
        for r in 0..3 {
            let col = col_slice(&fac.y, 3 * j + r);
            let out = &mut self.y[(3 * l + r) * ld..(3 * l + r + 1) * ld];
            for (k, &i) in self.cand.iter().enumerate() {
                out[3 * k..3 * k + 3].copy_from_slice(&col[3 * i..3 * i + 3]);
            }
        }
        self.have[l] = true;
    }
}

impl TireContact {
    /// The contact of `red` with `ground` under the settings `cfg` (friction law, tolerances,
    /// margins), no contact forces yet.
    ///
    /// With `mirror` ([`MirrorHalf`]: the image of each contact node and its weight) `red` is
    /// the half model of symmetric motion: the contact unknowns are the mid-plane nodes
    /// (no lateral force) and one representative per mirrored pair, whose force also acts,
    /// mirrored, on its image (generalised force `2 T_cᵀ f`); the image's force is the mirror
    /// of the representative's.
    pub fn new(
        red: &ReducedTire,
        cfg: RollingConfig,
        ground: Ground,
        mirror: Option<&MirrorHalf>,
    ) -> Self {
        let nz = red.n_z();
        let nc = red.n_contact();
        let tct = red.tc.transpose().to_owned();
        let bound = GapBound::new(&tct);
        let weight: Vec<f64> = match mirror {
            Some(h) => (0..nc).map(|i| h.weight(i)).collect(),
            None => vec![1.0; nc],
        };
        let mirror = mirror.map(|h| h.partner.clone());
        let mut load = Mat::<f64>::zeros(nz + 1, 3 * nc);
        load.as_mut().subrows_mut(1, nz).copy_from(&tct);
        for (c, &wc) in weight.iter().enumerate() {
            if wc != 1.0 {
                for r in 0..3 {
                    load.col_mut(3 * c + r).iter_mut().for_each(|v| *v *= wc);
                }
            }
        }
        let law = cfg.friction_law.law(cfg.friction, cfg.slip_regularization);
        Self {
            ground,
            cfg,
            law,
            load,
            tct,
            tct_theta: red.tc_theta.transpose().to_owned(),
            responses: [None, None],
            lambda: vec![0.0; nc],
            friction: vec![[0.0; 3]; nc],
            contact_force: [0.0; 3],
            cleat_contacts: 0,
            stats: StepStats::default(),
            mirror,
            weight,
            work: Work {
                dc: vec![0.0; 3 * nc],
                bound,
                eval: Vec::with_capacity(nc),
                dvdot: vec![0.0; nz + 1],
                coef: vec![0.0; 3 * nc],
                cand: Vec::with_capacity(nc),
                was_cand: vec![true; nc],
                gp: Vec::with_capacity(nc),
                lambda: Vec::with_capacity(nc),
                ft: Vec::with_capacity(nc),
                forces: Vec::with_capacity(nc),
                x0: Vec::with_capacity(3 * nc),
                x1: Vec::with_capacity(3 * nc),
                x2: Vec::with_capacity(3 * nc),
                lambda2: vec![0.0; nc],
                friction2: vec![[0.0; 3]; nc],
                diag: Vec::with_capacity(nc),
                frames: Vec::with_capacity(nc),
                rig_t1: Vec::with_capacity(nc),
                solver: ContactSolver::default(),
                blocks: CandidateBlocks {
                    id: usize::MAX,
                    ..CandidateBlocks::default()
                },
            },
        }
    }

    /// The settings.
    pub fn config(&self) -> &RollingConfig {
        &self.cfg
    }

    /// Makes the responses of the factorisation `step.factor_id()` the current entry (computed
    /// once per factorisation; the entry of the other step size is kept).
    fn ensure_responses(
        &mut self,
        red: &ReducedTire,
        step: &AlphaCorrection<'_>,
    ) -> Result<(), MbdError> {
        let id = step.factor_id();
        if self.responses[0].as_ref().is_some_and(|r| r.id == id) {
            return Ok(());
        }
        self.responses.swap(0, 1);
        if self.responses[0].as_ref().is_some_and(|r| r.id == id) {
            return Ok(());
        }
        let (n, nc3) = (self.load.nrows(), self.load.ncols());
        let nz = n - 1;
        let mut r = self.responses[0].take().unwrap_or_else(|| Responses {
            id,
            x: Mat::zeros(n, nc3),
            y: Mat::zeros(nc3, nc3),
        });
        r.id = id;
        step.solve_columns(self.load.as_ref(), r.x.as_mut())?;
        matmul(
            r.y.as_mut(),
            Accum::Replace,
            red.tc.as_ref(),
            r.x.as_ref().subrows(1, nz),
            1.0,
            Par::Seq,
        );
        self.responses[0] = Some(r);
        self.stats.columns += red.n_contact();
        Ok(())
    }
}

impl StepCorrection<TireDynamics<'_>> for TireContact {
    /// Candidates from the free end-of-step gaps, the coupled normal and friction problem on
    /// the local Delassus matrix, and `Δv̇ = X Σ fⱼ` applied to the step.
    fn correct(
        &mut self,
        sys: &TireDynamics<'_>,
        step: &mut AlphaCorrection<'_>,
    ) -> Result<(), MbdError> {
        let red = sys.reduced();
        let nc = red.n_contact();
        let t1 = step.t();
        let h = step.h();
        let clk = std::time::Instant::now();
        self.ensure_responses(red, step)?;
        let c0 = clk.elapsed().as_secs_f64();
        let w = &mut self.work;
        let z_free = &step.q()[1..];
        // candidates: the nodes whose free gap is below the margin; a node whose gap is
        // certainly above it (by the bound of `GapBound`) is not evaluated
        let speed = self.ground.speed.abs();
        let margin_max = self.cfg.contact_margin + h * speed;
        let dist = w.bound.distance(z_free);
        let cleat = self.ground.cleat_center(t1);
        let cleat_r = self.ground.cfg.cleat_radius;
        w.cand.clear();
        w.gp.clear();
        w.eval.clear();
        let weight = &self.weight;
        w.eval.extend(
            (0..nc).filter(|&i| weight[i] > 0.0 && !w.bound.skip(i, t1, dist, speed, margin_max)),
        );
        // `T_c z` of the evaluated nodes: one product per run of consecutive nodes instead of
        // one three-row product per node (fewer calls; each entry is the same dot product of
        // faer's row-major kernel either way, so the values are unchanged)
        let mut k = 0;
        while k < w.eval.len() {
            let start = w.eval[k];
            let mut end = start + 1;
            k += 1;
            while k < w.eval.len() && w.eval[k] == end {
                end += 1;
                k += 1;
            }
            matvec(
                self.tct
                    .as_ref()
                    .subcols(3 * start, 3 * (end - start))
                    .transpose(),
                z_free,
                &mut w.dc[3 * start..3 * end],
            );
        }
        for &i in &w.eval {
            let s = red.contact_positions[i];
            let p = [
                s[0] + w.dc[3 * i],
                s[1] + w.dc[3 * i + 1],
                s[2] + w.dc[3 * i + 2],
            ];
            let g = self.ground.query(t1, p);
            // (for the skip bound only, whose 1e-9 m allowance covers the few ulps by which
            // √(x² + z²) can differ from `hypot`: the candidates do not depend on it)
            let cleat_gap = cleat.map(|c| {
                let (dx, dz) = (p[0] - c[0], p[2] - c[1]);
                (dx * dx + dz * dz).sqrt() - cleat_r
            });
            w.bound.record(i, g.gap, cleat_gap, t1, dist);
            // the cleat's faces approach the nodes at up to the surface speed
            let margin = if g.on_cleat {
                self.cfg.contact_margin + h * self.ground.speed.abs()
            } else {
                self.cfg.contact_margin
            };
            if g.gap < margin {
                if g.gap < -self.cfg.contact_margin && !w.was_cand[i] {
                    self.stats.late_contacts += 1;
                }
                w.cand.push(i);
                w.gp.push(g);
            }
        }
        w.bound.set_valid();
        let c1 = clk.elapsed().as_secs_f64();
        self.solve_contact(red, step)?;
        let c2 = clk.elapsed().as_secs_f64();
        self.stats.seconds[1] += c1 - c0;
        self.stats.seconds[3] += c2 - c1;
        self.stats.seconds[4] += c0;
        let w = &mut self.work;
        let Some(fac) = self.responses[0].as_ref() else {
            return Err(MbdError::Model {
                t: t1,
                message: "no contact responses".into(),
            });
        };
        // contact correction Δv̇ = X Σ fⱼ
        // (the columns in increasing order, as the candidates are)
        w.dvdot.iter_mut().for_each(|x| *x = 0.0);
        for (k, &j) in w.cand.iter().enumerate() {
            w.coef[3 * j..3 * j + 3].copy_from_slice(&w.forces[k]);
        }
        axpy_cols(|c| col_slice(&fac.x, c), &w.coef, &mut w.dvdot);
        for &j in &w.cand {
            w.coef[3 * j..3 * j + 3].copy_from_slice(&[0.0; 3]);
        }
        step.apply(&w.dvdot, &[]);
        self.lambda.iter_mut().for_each(|l| *l = 0.0);
        self.friction.iter_mut().for_each(|f| *f = [0.0; 3]);
        self.contact_force = [0.0; 3];
        for (f, &i) in w.forces.iter().zip(&w.cand) {
            // half model: a pair's lateral forces cancel, the others count twice
            let wi = self.weight[i];
            if wi == 2.0 {
                self.contact_force[0] += f[0] + f[0];
                self.contact_force[2] += f[2] + f[2];
            } else {
                for b in 0..3 {
                    self.contact_force[b] += f[b];
                }
            }
        }
        w.was_cand.iter_mut().for_each(|c| *c = false);
        for &i in &w.cand {
            w.was_cand[i] = true;
        }
        for (k, &i) in w.cand.iter().enumerate() {
            self.lambda[i] = w.lambda[k];
            self.friction[i] = w.ft[k];
            if let Some(p) = self.mirror.as_ref().map(|p| p[i]).filter(|&p| p != i) {
                let f = w.ft[k];
                self.lambda[p] = w.lambda[k];
                self.friction[p] = [f[0], -f[1], f[2]];
            }
        }
        // (physical nodes: a pair's representative counts for both)
        let count = |k: usize| self.weight[w.cand[k]] as usize;
        self.stats.steps += 1;
        self.stats.candidates += (0..w.cand.len()).map(count).sum::<usize>();
        self.stats.active += (0..w.cand.len())
            .filter(|&k| w.lambda[k] > 0.0)
            .map(count)
            .sum::<usize>();
        self.cleat_contacts = (0..w.cand.len())
            .filter(|&k| w.lambda[k] > 0.0 && w.gp[k].on_cleat)
            .map(count)
            .sum();
        Ok(())
    }
}

impl TireContact {
    /// The contact problem of the candidates in `work`: normal contact and friction coupled,
    /// solved by the semismooth Newton method of [`ContactSolver`] on the local Delassus
    /// matrix (gathered lazily from the copied blocks of `Y`, `X`), warm-started from the previous
    /// steps' forces; leaves the contact forces in `work.forces`.
    fn solve_contact(
        &mut self,
        red: &ReducedTire,
        step: &AlphaCorrection<'_>,
    ) -> Result<(), MbdError> {
        let t1 = step.t();
        // Δq = Δv̇/β', Δv = (γ'/β') Δv̇
        let (c2, c1) = (
            1.0 / step.beta_prime(),
            step.gamma_prime() / step.beta_prime(),
        );
        let Some(fac) = self.responses[0].as_ref() else {
            return Ok(());
        };
        let w = &mut self.work;
        let m = w.cand.len();
        let law = self.law.clone();
        let mu = law.coefficient();
        w.lambda.clear();
        w.ft.clear();
        w.forces.clear();
        if m == 0 {
            return Ok(());
        }
        // warm starts: the forces of the last step and of the one before (contact nodes at the
        // patch edges chatter with period two), in the local frames (n, t1, t2)
        w.x0.clear();
        w.x1.clear();
        for (k, &i) in w.cand.iter().enumerate() {
            let (t1v, t2v) = tangents(&w.gp[k].normal);
            for (x, lam, f) in [
                (&mut w.x0, self.lambda[i], self.friction[i]),
                (&mut w.x1, w.lambda2[i], w.friction2[i]),
            ] {
                let f = if mu > 0.0 { f } else { [0.0; 3] };
                x.extend([lam, dot3(&t1v, &f), dot3(&t2v, &f)]);
            }
        }
        // and the linear extrapolation of the last two
        w.x2.clear();
        w.x2.extend(w.x0.iter().zip(&w.x1).map(|(a, b)| 2.0 * a - b));
        w.lambda2.copy_from_slice(&self.lambda);
        w.friction2.copy_from_slice(&self.friction);
        let penalty = match self.cfg.normal {
            NormalContact::Penalty { stiffness } => 1.0 / stiffness,
            NormalContact::Lagrange => 0.0,
        };
        candidate_frames(red, &w.cand, &w.gp, c1, c2, &mut w.frames, &mut w.rig_t1);
        let v = step.v();
        w.blocks.prepare(fac, &w.cand);
        let mut src = TireDelassus {
            fac,
            blocks: &mut w.blocks,
            red,
            cand: &w.cand,
            gp: &w.gp,
            frames: &w.frames,
            rig_t1: &w.rig_t1,
            penalty,
            weight: &self.weight,
            half: self.mirror.is_some(),
            tct: &self.tct,
            tct_theta: &self.tct_theta,
            z_free: &step.q()[1..],
            zd_free: &v[1..],
            spin_free: v[0],
        };
        w.diag.clear();
        for k in 0..m {
            w.diag.push(src.diagonal(k));
        }
        w.solver.reset(&w.x0);
        w.solver.set_gaps(w.gp.iter().map(|g| g.gap));
        let settings = SolveOptions {
            law,
            tol: self.cfg.contact_tolerance,
            ..SolveOptions::default()
        };
        // same candidates as in the last step: its Newton matrix may serve for chord steps
        let same = w.cand.iter().all(|&i| w.was_cand[i])
            && w.cand.len() == w.was_cand.iter().filter(|&&c| c).count();
        let alts = [&w.x1[..], &w.x2[..]];
        let rep = w.solver.solve(
            &mut src,
            &w.diag,
            &settings,
            same,
            if same { &alts[..] } else { &[] },
        );
        self.stats.contact_newton += rep.newton_iterations;
        self.stats.contact_chord += rep.chord_iterations;
        self.stats.lcp_solves += rep.lcp_solves;
        self.stats.friction_sweeps += rep.sweeps;
        if rep.fallback {
            self.stats.contact_fallbacks += 1;
        }
        if !rep.converged {
            self.stats.contact_unconverged += 1;
        }
        let x = w.solver.x();
        if !x.iter().all(|v| v.is_finite()) {
            return Err(MbdError::NonFinite {
                what: "tire contact forces".into(),
                t: t1,
            });
        }
        for k in 0..m {
            let n = w.gp[k].normal;
            let (t1v, t2v) = tangents(&n);
            let (l, f1, f2) = (x[3 * k], x[3 * k + 1], x[3 * k + 2]);
            let ft = [
                f1 * t1v[0] + f2 * t2v[0],
                f1 * t1v[1] + f2 * t2v[1],
                f1 * t1v[2] + f2 * t2v[2],
            ];
            w.lambda.push(l);
            w.ft.push(ft);
            w.forces
                .push([n[0] * l + ft[0], n[1] * l + ft[1], n[2] * l + ft[2]]);
        }
        Ok(())
    }
}

/// A lower bound on the free gaps of the contact nodes from their last evaluation, so that the
/// candidate search evaluates `T_c z` and the ground only for the nodes that may be within the
/// margin (issue #16: the 3 n_c × n_z product `T_c z` of all nodes and their ground queries
/// were a fixed cost per step).
///
/// The gap is the smaller of the distances to the drum or road and to the cleat
/// (`contact::geometry`: distances to circles and a line, each 1-Lipschitz in the node
/// position); the first does not depend on time (the drum turns about its centre), the second
/// moves by at most the surface speed `v` per unit time ([`Ground::cleat_center`]). Node `i`
/// evaluated at time `tᵢ` with gap `gᵢ`, cleat gap `cᵢ` and reduced coordinates `zᵢ` moves
/// by `|(T_c)ᵢ (z − zᵢ)| ≤ Lᵢ ‖z − zᵢ‖` (`Lᵢ` the spectral norm of its three rows, at most
/// their Frobenius norm), and `‖z − zᵢ‖ ≤ ‖z − z_ref‖ + eᵢ` with `eᵢ ≥ ‖zᵢ − z_ref‖` (`‖zᵢ −
/// z_ref‖` at the evaluation) for a common reference `z_ref`, so
/// with `Δ = Lᵢ (‖z − z_ref‖ + eᵢ)`
///
/// ```text
///   g(t, z) ≥ min(gᵢ − Δ, cᵢ − Δ − 1.01 v |t − tᵢ|) − 1e-9 m,
/// ```
///
/// and the node is skipped when this is at least the largest margin `contact_margin + h v`: its
/// free gap is then certainly above the margin, so the candidates are exactly those of a
/// search over all nodes. The reference moves to the current `z` when `L_max ‖z − z_ref‖`
/// exceeds 0.1 mm, each `eᵢ` growing by the distance moved ([`GapBound::distance`]), without
/// evaluating the nodes again. On the cleat run at h = 0.05 ms (31 candidates a step) this
/// evaluates 47 nodes a step; a reset that evaluated every node at 1 mm, with the Frobenius
/// norm for `Lᵢ`, evaluated 61.
struct GapBound {
    /// `Lᵢ` (with relative allowances for the round-off of the norms).
    lip: Vec<f64>,
    l_max: f64,
    z_ref: Vec<f64>,
    valid: bool,
    /// Per node: last evaluated gap and cleat gap \[m\], their time \[s\] and `eᵢ`.
    gap: Vec<f64>,
    cleat: Vec<f64>,
    time: Vec<f64>,
    e: Vec<f64>,
}

impl GapBound {
    fn new(tct: &Mat<f64>) -> Self {
        let nc = tct.ncols() / 3;
        let lip: Vec<f64> = (0..nc)
            .map(|i| {
                // ‖(T_c)ᵢ‖₂ = √λ_max of the 3 × 3 Gram matrix of node i's rows
                let c = |b| col_slice(tct, 3 * i + b);
                let gram = nalgebra::Matrix3::from_fn(|a, b| {
                    c(a).iter().zip(c(b)).map(|(x, y)| x * y).sum::<f64>()
                });
                let frob = gram.trace().sqrt();
                let spec = gram.symmetric_eigenvalues().max().max(0.0).sqrt();
                // (allowances for the round-off of the eigenvalue and of the sums; the
                // Frobenius norm bounds it too)
                (spec * (1.0 + 1e-10)).min(frob) * (1.0 + 1e-12)
            })
            .collect();
        let l_max = lip.iter().fold(0.0f64, |a, &b| a.max(b));
        Self {
            lip,
            l_max,
            z_ref: vec![0.0; tct.nrows()],
            valid: false,
            gap: vec![0.0; nc],
            cleat: vec![0.0; nc],
            time: vec![0.0; nc],
            e: vec![0.0; nc],
        }
    }

    /// `‖z − z_ref‖`; when `L_max ‖z − z_ref‖` exceeds 0.1 mm the reference moves to `z` and
    /// every node's `eᵢ` grows by the distance moved (`‖zᵢ − z‖ ≤ ‖zᵢ − z_ref‖ + ‖z_ref − z‖`,
    /// so the bound still holds without evaluating the nodes again; a node is evaluated again
    /// when its bound comes within the margin, which resets its `eᵢ`). Without a reference
    /// yet, `z` becomes it and every node is to be evaluated.
    fn distance(&mut self, z: &[f64]) -> f64 {
        if self.valid {
            let d = self
                .z_ref
                .iter()
                .zip(z)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt()
                * (1.0 + 1e-12);
            if self.l_max * d <= 1e-4 {
                return d;
            }
            // (1 + 1e-12): allowance for the round-off of the sums eᵢ + d
            self.e
                .iter_mut()
                .for_each(|e| *e = (*e + d) * (1.0 + 1e-12));
        }
        self.z_ref.copy_from_slice(z);
        0.0
    }

    /// Whether node `i`'s free gap at time `t` is certainly at least `margin` \[m\] (`dist` =
    /// [`GapBound::distance`], `speed` the ground's surface speed \[m/s\]).
    fn skip(&self, i: usize, t: f64, dist: f64, speed: f64, margin: f64) -> bool {
        if !self.valid {
            return false;
        }
        let moved = self.lip[i] * (dist + self.e[i]);
        let cleat = self.cleat[i] - moved - 1.01 * speed * (t - self.time[i]).abs();
        (self.gap[i] - moved).min(cleat) - 1e-9 >= margin
    }

    /// Node `i` evaluated: gap `g` and cleat gap `cleat` ([`Ground::cleat_center`]) \[m\] at time
    /// `t` \[s\], `dist` = [`GapBound::distance`].
    fn record(&mut self, i: usize, g: f64, cleat: Option<f64>, t: f64, dist: f64) {
        self.gap[i] = g;
        self.cleat[i] = cleat.unwrap_or(f64::INFINITY);
        self.time[i] = t;
        self.e[i] = dist;
    }

    /// All nodes were evaluated in this step: the bound holds from now on.
    fn set_valid(&mut self) {
        self.valid = true;
    }
}

pub(crate) use mbd_core::linalg::matvec;

fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Tangent basis `t1 = [n_z, 0, −n_x]`, `t2 = ŷ` of a ground normal in the wheel's `(x, z)`
/// plane (the ground is extruded along the axis `y`, so `n_y = 0`).
fn tangents(n: &[f64; 3]) -> ([f64; 3], [f64; 3]) {
    ([n[2], 0.0, -n[0]], [0.0, 1.0, 0.0])
}

/// The local Delassus matrix of the candidates, gathered lazily from the cached columns:
/// rows `(g_k, u1_k, u2_k)`, columns `(λ_l, f1_l, f2_l)`,
///
/// ```text
///   D_N,kl = β_N h² n_kᵀ Y_kl R_l (+ 1/k_penalty on the diagonal),
///   D_T,kl = γ_N h t_kᵀ (Y_kl + (η × s_k) X_θ,l) R_l,     R_l = [n_l t1_l t2_l],
/// ```
///
/// where `Y_kl` moves contact node k under a unit force on node l (end-of-step displacement per
/// unit `Δz̈`) and `(η × s_k) X_θ,l` is the rigid spin part of the material velocity (E15).
struct TireDelassus<'b> {
    fac: &'b Responses,
    /// The candidates' blocks of `Y` and `X_θ` (gathered on demand).
    blocks: &'b mut CandidateBlocks,
    red: &'b ReducedTire,
    cand: &'b [usize],
    gp: &'b [GroundPoint],
    /// Local frames `[n, t1, t2]` of the candidates, scaled by `β_N h²` (row n) and `γ_N h`
    /// (rows t1, t2).
    frames: &'b [[[f64; 3]; 3]],
    /// `γ_N h t1ᵀ(η × s)` per candidate (`t2ᵀ(η × s) = 0`).
    rig_t1: &'b [f64],
    penalty: f64,
    /// [`TireContact`]'s weight of each contact node (half model: 1 on the mid-plane).
    weight: &'b [f64],
    /// Whether this is the half model of symmetric motion.
    half: bool,
    tct: &'b Mat<f64>,
    tct_theta: &'b Mat<f64>,
    z_free: &'b [f64],
    zd_free: &'b [f64],
    spin_free: f64,
}

/// The scaled frames and rigid-spin coefficients of the candidates for [`TireDelassus`].
fn candidate_frames(
    red: &ReducedTire,
    cand: &[usize],
    gp: &[GroundPoint],
    c1: f64,
    c2: f64,
    frames: &mut Vec<[[f64; 3]; 3]>,
    rig_t1: &mut Vec<f64>,
) {
    frames.clear();
    rig_t1.clear();
    for (k, &i) in cand.iter().enumerate() {
        let n = gp[k].normal;
        let (t1, t2) = tangents(&n);
        frames.push([
            [c2 * n[0], c2 * n[1], c2 * n[2]],
            [c1 * t1[0], c1 * t1[1], c1 * t1[2]],
            [c1 * t2[0], c1 * t2[1], c1 * t2[2]],
        ]);
        let s = red.contact_positions[i];
        rig_t1.push(c1 * (t1[0] * s[2] - t1[2] * s[0]));
    }
}

impl TireDelassus<'_> {
    /// Unit force directions `[n, t1, t2]` of candidate `l`.
    fn directions(&self, l: usize) -> [[f64; 3]; 3] {
        let n = self.gp[l].normal;
        let (t1, t2) = tangents(&n);
        [n, t1, t2]
    }

    /// Local outputs of node `k` for a unit force `e` (wheel frame) on itself.
    fn response(&self, k: usize, e: &[f64; 3]) -> [f64; 3] {
        let (d, x_theta) = (&self.blocks.diag[k], &self.blocks.x_theta[k]);
        let mut v = [0.0; 3];
        let mut xth = 0.0;
        for (r, er) in e.iter().enumerate() {
            v[0] += er * d[r][0];
            v[1] += er * d[r][1];
            v[2] += er * d[r][2];
            xth += er * x_theta[r];
        }
        let f = &self.frames[k];
        [
            dot3(&f[0], &v),
            dot3(&f[1], &v) + self.rig_t1[k] * xth,
            dot3(&f[2], &v),
        ]
    }

    /// The diagonal compliances `[D_N,kk, (D_T,kk,11 + D_T,kk,22)/2]` of node `k`.
    fn diagonal(&self, k: usize) -> [f64; 2] {
        let e = self.directions(k);
        let dn = self.response(k, &e[0])[0] + self.penalty;
        let d1 = self.response(k, &e[1])[1];
        let d2 = self.response(k, &e[2])[2] + self.lateral_compliance(k, d1);
        [dn, 0.5 * (d1 + d2)]
    }

    /// In the half model, a mid-plane node's lateral force moves nothing (an antisymmetric
    /// load: its rows of `T_c` are zero), so its Delassus row is zero and the force would be
    /// undetermined in stick; the symmetric solution has it zero. A compliance `d1` (the node's
    /// own longitudinal one) on its diagonal makes `u2 = d1 f2 = 0`, i.e. `f2 = 0`, without
    /// changing anything else. Zero for the other nodes.
    fn lateral_compliance(&self, k: usize, d1: f64) -> f64 {
        if self.half && self.weight[self.cand[k]] == 1.0 {
            d1
        } else {
            0.0
        }
    }
}

impl DelassusSource for TireDelassus<'_> {
    fn columns(&mut self, l: usize, cols: &mut [f64]) {
        let ld = 3 * self.cand.len();
        let e = self.directions(l);
        self.blocks.gather(self.fac, l);
        // the three Y columns of node l (rows of the candidates) combined along the unit force
        // directions: Y e_c = Σ_r e_c[r] Y[:, 3j + r], and X_θ e_c
        let yb = &self.blocks.y[3 * l * ld..(3 * l + 3) * ld];
        let (y0, y1, y2) = (&yb[..ld], &yb[ld..2 * ld], &yb[2 * ld..]);
        let x_theta = self.blocks.x_theta[l];
        let mut xth = [0.0; 3];
        for (c, ec) in e.iter().enumerate() {
            for (r, er) in ec.iter().enumerate() {
                xth[c] += er * x_theta[r];
            }
        }
        // planar ground (n_y = 0): n and t1 lie in the (x, z) plane, t2 = ŷ, so each frame
        // vector has two (n, t1) or one (t2) nonzero component
        let (nx, nz) = (e[0][0], e[0][2]);
        // (iterators over the candidates' triples: no bounds checks in the loop)
        let (c0, rest) = cols.split_at_mut(ld);
        let (c1, c2) = rest.split_at_mut(ld);
        let rows = y0
            .chunks_exact(3)
            .zip(y1.chunks_exact(3))
            .zip(y2.chunks_exact(3))
            .zip(self.frames.iter().zip(self.rig_t1));
        let outs = c0
            .chunks_exact_mut(3)
            .zip(c1.chunks_exact_mut(3))
            .zip(c2.chunks_exact_mut(3));
        for ((((a, b), c3), (f, &rig)), ((o0, o1), o2)) in rows.zip(outs) {
            let (fnx, fnz, ftx, ftz, fy) = (f[0][0], f[0][2], f[1][0], f[1][2], f[2][1]);
            // unit force along n, t1 (combinations of Y columns 0 and 2) and ŷ (column 1)
            let vs = [
                [
                    nx * a[0] + nz * c3[0],
                    nx * a[1] + nz * c3[1],
                    nx * a[2] + nz * c3[2],
                ],
                [
                    nz * a[0] - nx * c3[0],
                    nz * a[1] - nx * c3[1],
                    nz * a[2] - nx * c3[2],
                ],
                [b[0], b[1], b[2]],
            ];
            for ((v, o), xc) in vs.iter().zip([o0, o1, o2]).zip(xth) {
                o[0] = fnx * v[0] + fnz * v[2];
                o[1] = ftx * v[0] + ftz * v[2] + rig * xc;
                o[2] = fy * v[1];
            }
        }
        cols[3 * l] += self.penalty;
        let d1 = cols[ld + 3 * l + 1];
        cols[2 * ld + 3 * l + 2] += self.lateral_compliance(l, d1);
    }

    fn free_slip(&mut self, k: usize) -> [f64; 2] {
        let i = self.cand[k];
        let s = self.red.contact_positions[i];
        let sf = self.spin_free;
        let rig = [sf * s[2], 0.0, -sf * s[0]];
        // (T_c ż)ᵢ and (T_c,θ z)ᵢ: six dot products of length n_z in one pass
        let (tc, tt) = (
            |a| col_slice(self.tct, 3 * i + a),
            |a| col_slice(self.tct_theta, 3 * i + a),
        );
        let (zd, z) = (self.zd_free, self.z_free);
        let [vc, vt] = dots3x2([tc(0), tc(1), tc(2)], zd, [tt(0), tt(1), tt(2)], z);
        let mut v = [0.0; 3];
        for (a, va) in v.iter_mut().enumerate() {
            *va = rig[a] + vc[a] + sf * vt[a] - self.gp[k].velocity[a];
        }
        let (t1, t2) = tangents(&self.gp[k].normal);
        [dot3(&t1, &v), dot3(&t2, &v)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Invariant of [`GapBound`]: a skipped node's gap is at least the margin, so the
    /// candidates are those of a search over all nodes. Synthetic ground (1-Lipschitz in the
    /// node position like `contact::geometry`): the smaller of the distance to a plane and to
    /// a circle moving at `v`; random `T_c` and a random walk of `z` with jumps, small and
    /// large steps (reference moves and fresh evaluations).
    #[test]
    fn skipped_nodes_are_beyond_the_margin() {
        let mut rnd = super::super::kernels::uniform(0x2545_f491_4f6c_dd1d);
        let (nz, nc) = (40, 30);
        let tct = Mat::from_fn(nz, 3 * nc, |_, _| 0.2 * rnd());
        let pos: Vec<[f64; 3]> = (0..nc)
            .map(|i| {
                // an arc of ±0.3 rad about the bottom: many nodes near the plane
                let a = (i as f64 / nc as f64 - 0.5) * 0.6;
                [0.3 * a.sin(), 0.0, -0.3 * a.cos()]
            })
            .collect();
        let (v, r, margin, h) = (16.7, 0.01, 1e-3, 5e-5);
        let gaps = |z: &[f64], t: f64| -> Vec<(f64, f64)> {
            (0..nc)
                .map(|i| {
                    let c = |b| col_slice(&tct, 3 * i + b);
                    let [d, _] = dots3x2([c(0), c(1), c(2)], z, [c(0), c(1), c(2)], z);
                    let p = [pos[i][0] + d[0], pos[i][1] + d[1], pos[i][2] + d[2]];
                    let plane = p[2] + 0.295;
                    let c = [-0.05 + v * t, -0.3 - 0.004];
                    let cleat = (p[0] - c[0]).hypot(p[2] - c[1]) - r;
                    (plane.min(cleat), cleat)
                })
                .collect()
        };
        let mut bound = GapBound::new(&tct);
        let mut z = vec![0.0; nz];
        // a drift (nodes approach or leave the ground steadily) plus noise
        let drift: Vec<f64> = (0..nz).map(|_| rnd()).collect();
        let (mut skipped, mut evaluated) = (0, 0);
        for step in 0..4000 {
            let t = step as f64 * h;
            let size = match step % 500 {
                0 => 0.02,
                s if s < 250 => 2e-4,
                _ => 2e-3,
            };
            let sign = if (step / 500) % 2 == 0 { 1.0 } else { -1.0 };
            for (x, d) in z.iter_mut().zip(&drift) {
                *x += size * (sign * d + 0.3 * rnd());
            }
            let dist = bound.distance(&z);
            let g = gaps(&z, t);
            for (i, &(gap, cleat)) in g.iter().enumerate() {
                if bound.skip(i, t, dist, v, margin + h * v) {
                    assert!(gap >= margin, "step {step} node {i}: gap {gap} skipped");
                    skipped += 1;
                } else {
                    bound.record(i, gap, Some(cleat), t, dist);
                    evaluated += 1;
                }
            }
            bound.set_valid();
        }
        // the bound must skip something, else the test is vacuous
        assert!(
            skipped > evaluated / 4,
            "{skipped} skipped, {evaluated} evaluated"
        );
    }
}
