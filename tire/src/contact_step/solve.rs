//! The contact problem of one step: the candidates' local Delassus matrix ([`TireDelassus`])
//! solved by the shared Alart–Curnier solver of the contact crate ([`contact::ContactSolver`]),
//! warm-started from the forces of the last two steps.

use super::TireContact;
use super::delassus::{TireDelassus, candidate_frames, dot3, tangents};
use crate::reduced::ReducedTire;
use crate::rolling_config::NormalContact;
use contact::ContactSolverOptions;
use mbd_core::MbdError;
use mbd_core::integrators::AlphaCorrection;

impl TireContact {
    /// The contact problem of the candidates in `work`: normal contact and friction coupled,
    /// solved by the semismooth Newton method of [`ContactSolver`] on the local Delassus
    /// matrix (gathered lazily from the copied blocks of `Y`, `X`), warm-started from the previous
    /// steps' forces; leaves the contact forces in `work.forces`.
    pub(super) fn solve_contact(
        &mut self, red: &ReducedTire, step: &AlphaCorrection<'_>,
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
        let planar = candidate_frames(
            red,
            &w.cand,
            &w.gp,
            (c1, c2),
            (&self.tct, &self.tct_theta[fac.dir]),
            (&step.q()[1..], &step.v()[1..]),
            &mut w.frames,
            &mut w.rig_t1,
            &mut w.rig_t2,
            &mut w.free_rates,
        );
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
            rig_t2: &w.rig_t2,
            planar,
            penalty,
            weight: &self.weight,
            half: self.mirror.is_some(),
            free_rates: &w.free_rates,
            transport: v[0] * step.gamma_prime().recip(),
            spin_free: v[0],
        };
        w.diag.clear();
        for k in 0..m {
            w.diag.push(src.diagonal(k));
        }
        w.solver.reset(&w.x0);
        w.solver.set_gaps(w.gp.iter().map(|g| g.gap));
        let settings = ContactSolverOptions {
            law,
            tol: self.cfg.contact_tolerance,
            ..ContactSolverOptions::default()
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
