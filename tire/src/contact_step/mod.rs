//! The rolling tire's contact (seed note E15: unilateral gaps with Lagrange multipliers and
//! friction) as the [`StepCorrection`] of mbd-core's generalized-α stepper.
//!
//! After the smooth end-of-step solution (`[θ̈; z̈]` free of contact, [`super::dynamics`]) a
//! contact node `i` at `xᵢ = sᵢ + (T_c z)ᵢ` is a candidate when its gap on the ground is below
//! `contact_margin` (plus `h v` in front of the cleat or an obstacle, whose faces approach at the
//! surface speed: [`GroundPoint::approach`]; nodes whose gap is certainly above that by a lower
//! bound from their last evaluation are not evaluated, `GapBound`). The ground's normals may
//! point anywhere (obstacles, height grids, camber): the tangent bases and the local Delassus
//! matrix are formed in 3-D, with shorter products while every candidate's normal lies in the
//! wheel's `(x, z)` plane (`delassus`). Contact forces `fⱼ` (wheel frame) on the candidates change
//! the end-of-step accelerations by `Δv̇ = X Σ fⱼ` with the responses `X = S⁻¹ [0; T_cᵀ]` of all contact nodes
//! to unit forces and the node displacements by `Y = T_c X_z / β'` ([`AlphaCorrection`]: the
//! Delassus operator `W = J S⁻¹ Jᵀ`). The slip velocity of a contact node carries the transport
//! of the deflection through the patch, `Ω T_c,θ z` (Ribaric (7.10)), taken with the upwind
//! rows of `T_c,θ` ([`ReducedTire::tc_theta_upwind`]); its response `Ω Y_θ/β'` with
//! `Y_θ = T_c,θ X_z` enters the tangential rows of the Delassus matrix, so that a sticking node
//! holds zero material slip, not only zero `T_c ż`. `X`, `Y` and `Y_θ` are computed with the stepper's factored
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

mod blocks;
mod delassus;
mod gap_bound;
mod kernels;
mod solve;

use crate::dynamics::TireDynamics;
use crate::ground::{Ground, GroundPoint};
use crate::mirror::MirrorHalf;
use crate::reduced::ReducedTire;
use crate::rolling_config::RollingConfig;
use crate::stats::StepStats;
use blocks::{CandidateBlocks, Responses};
use contact::ContactSolver;
use contact::friction::FrictionLaw;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};
use gap_bound::GapBound;
use mbd_core::MbdError;
use mbd_core::integrators::{AlphaCorrection, StepCorrection};
use mbd_core::linalg::{axpy_cols, col_slice, matvec};
use std::sync::Arc;

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
    /// `T_cᵀ` and the upwind `T_c,θᵀ` of both spin directions (n_z × 3 n_c): contiguous rows
    /// of the contact-node maps.
    tct: Mat<f64>,
    tct_theta: [Mat<f64>; 2],
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
    /// Acceleration increment `X Σ fⱼ` (n, then the multiplier increment of a prescribed
    /// spin).
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
    rig_t2: Vec<f64>,
    /// `[(T_c ż)ᵢ, (T_c,θ z)ᵢ]` of the free state per candidate ([`TireDelassus`]).
    free_rates: Vec<[[f64; 3]; 2]>,
    /// The coupled normal + friction solver (buffers reused).
    solver: ContactSolver,
    /// The candidates' blocks of `Y` and `X_θ` gathered so far (kept while the candidates and
    /// the factorisation are those of the last step).
    blocks: CandidateBlocks,
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
        red: &ReducedTire, cfg: RollingConfig, ground: Ground, mirror: Option<&MirrorHalf>,
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
            tct_theta: [
                red.tc_theta_upwind[0].transpose().to_owned(),
                red.tc_theta_upwind[1].transpose().to_owned(),
            ],
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
                rig_t2: Vec::with_capacity(nc),
                free_rates: Vec::with_capacity(nc),
                solver: ContactSolver::default(),
                blocks: CandidateBlocks {
                    id: usize::MAX,
                    ..CandidateBlocks::default()
                },
            },
        }
    }

    /// Restart from the contact forces `lambda` \[N\] and `friction` \[N\] of a saved state
    /// ([`crate::RollingTire::set_state`]): they become the warm start of the next solve, with
    /// no older history (the start two steps back is the same one), every node is searched
    /// again and counts as a candidate of the previous step, so that the restarted steps do
    /// not depend on the steps this contact took before. Lengths are the caller's to check.
    pub(crate) fn restart(&mut self, lambda: &[f64], friction: &[[f64; 3]]) {
        self.lambda.copy_from_slice(lambda);
        self.friction.copy_from_slice(friction);
        let w = &mut self.work;
        w.lambda2.copy_from_slice(lambda);
        w.friction2.copy_from_slice(friction);
        w.was_cand.iter_mut().for_each(|c| *c = true);
        w.bound.valid = false;
    }

    /// Replaces the ground (e.g. its height, speed or lateral velocity set per step by a
    /// prescribed wheel-centre motion, [`crate::RollingTire::set_ground`]). The skip bound of
    /// the candidate search assumes a ground fixed but for the cleat's travel, so it is reset
    /// when anything but the velocities changes (every node is searched at the next step).
    pub fn set_ground(&mut self, ground: Ground) {
        if ground.cfg != self.ground.cfg
            || ground.top != self.ground.top
            || ground.cleat_time != self.ground.cleat_time
        {
            self.work.bound.valid = false;
        }
        self.ground = ground;
    }

    /// The settings.
    pub fn config(&self) -> &RollingConfig {
        &self.cfg
    }

    /// Makes the responses of the factorisation `step.factor_id()` the current entry (computed
    /// once per factorisation; the entry of the other step size is kept), with `Y_θ` of the
    /// spin direction `dir`.
    fn ensure_responses(
        &mut self, red: &ReducedTire, step: &AlphaCorrection<'_>, dir: usize,
    ) -> Result<(), MbdError> {
        let id = step.factor_id();
        let nz = self.load.nrows() - 1;
        let transported = |r: &mut Responses| {
            if r.dir != dir {
                r.dir = dir;
                matmul(
                    r.yt.as_mut(),
                    Accum::Replace,
                    red.tc_theta_upwind[dir].as_ref(),
                    r.x.as_ref().subrows(1, nz),
                    1.0,
                    Par::Seq,
                );
            }
        };
        if let Some(r) = self.responses[0].as_mut().filter(|r| r.id == id) {
            transported(r);
            return Ok(());
        }
        self.responses.swap(0, 1);
        if let Some(r) = self.responses[0].as_mut().filter(|r| r.id == id) {
            transported(r);
            return Ok(());
        }
        let (n, nc3) = (self.load.nrows(), self.load.ncols());
        // (with a prescribed spin the responses carry the reaction's multiplier in their last
        // row: `S⁻¹` on the bilateral constraint, [`AlphaCorrection::solve_columns`])
        let rows = n + step.lambda().len();
        let mut r = self.responses[0]
            .take()
            .filter(|r| r.x.nrows() == rows)
            .unwrap_or_else(|| Responses {
                id,
                x: Mat::zeros(rows, nc3),
                y: Mat::zeros(nc3, nc3),
                yt: Mat::zeros(nc3, nc3),
                dir,
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
        r.dir = usize::MAX;
        transported(&mut r);
        self.responses[0] = Some(r);
        self.stats.columns += red.n_contact();
        Ok(())
    }
}

impl StepCorrection<TireDynamics<'_>> for TireContact {
    /// Candidates from the free end-of-step gaps, the coupled normal and friction problem on
    /// the local Delassus matrix, and `Δv̇ = X Σ fⱼ` applied to the step.
    fn correct(
        &mut self, sys: &TireDynamics<'_>, step: &mut AlphaCorrection<'_>,
    ) -> Result<(), MbdError> {
        let red = sys.reduced();
        let nc = red.n_contact();
        let t1 = step.t();
        let h = step.h();
        let clk = std::time::Instant::now();
        // the upwind side of the transport: material flows towards +θ for a positive spin
        let dir = usize::from(step.v()[0] < 0.0);
        self.ensure_responses(red, step, dir)?;
        let c0 = clk.elapsed().as_secs_f64();
        let w = &mut self.work;
        let z_free = &step.q()[1..];
        // candidates: the nodes whose free gap is below the margin; a node whose gap is
        // certainly above it (by the bound of `GapBound`) is not evaluated
        let margin_max = self.cfg.contact_margin + h * self.ground.max_approach();
        let rate = self.ground.bound_rate();
        let dist = w.bound.distance(z_free);
        w.cand.clear();
        w.gp.clear();
        w.eval.clear();
        let weight = &self.weight;
        w.eval.extend(
            (0..nc).filter(|&i| weight[i] > 0.0 && !w.bound.skip(i, t1, dist, rate, margin_max)),
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
            // (the bound values: for the skip test only, the candidates do not depend on them)
            w.bound.record(i, g.bound, t1, dist);
            // an obstacle's faces approach the nodes at up to the surface speed
            let margin = if g.approach > 0.0 {
                self.cfg.contact_margin + h * g.approach
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
        // contact correction Δv̇ = X Σ fⱼ (and the reaction's Δλ with a prescribed spin)
        // (the columns in increasing order, as the candidates are)
        w.dvdot.resize(fac.x.nrows(), 0.0);
        w.dvdot.iter_mut().for_each(|x| *x = 0.0);
        for (k, &j) in w.cand.iter().enumerate() {
            w.coef[3 * j..3 * j + 3].copy_from_slice(&w.forces[k]);
        }
        axpy_cols(|c| col_slice(&fac.x, c), &w.coef, &mut w.dvdot);
        for &j in &w.cand {
            w.coef[3 * j..3 * j + 3].copy_from_slice(&[0.0; 3]);
        }
        let n = self.load.nrows();
        step.apply(&w.dvdot[..n], &w.dvdot[n..]);
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
