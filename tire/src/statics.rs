//! The preload: the tire pressed statically onto the drum or road by the vertical load
//! (1000 lb = 4448 N, Ribaric §8.3/§8.5) with Lagrange-multiplier contact at the contact nodes
//! (§7.3) and the wheel fixed.
//!
//! Only the contact-node flexibility `Y = ∂δ^c/∂f^c` enters: `δ^c = Y f^c` with
//! `f^c = Σ nᵢ λᵢ`. For the reduced tire `Y = T_c K_z⁻¹ T_cᵀ`, for the full FE model
//! `Y = E_cᵀ K⁻¹ E_c` (rim fixed), so both are solved by the same routine, which is what the
//! "static patch force and deflection within 1 %" validation compares. The ground height is
//! found by a safeguarded secant iteration on the total vertical force; for a given height the
//! contact problem (normals re-linearised at the deformed positions) is a complementarity
//! problem solved by [`contact::solver::solve_lcp`].

use crate::error::{TireError, invalid, linalg};
use crate::ground::{Ground, GroundConfig};
use crate::mesh::TireFe;
use crate::reduce::TirePartition;
use crate::reduced::ReducedTire;
use contact::solver::solve_lcp;
use faer::prelude::*;
use faer::{Mat, Side};
use mbd_core::roots::{FalsePositionStop, false_position};
use mbd_core::validate::{Validate, check};
use serde::Serialize;

/// Static contact solution of the patch.
#[derive(Debug, Clone, Serialize)]
pub struct PatchSolution {
    /// Ground top height in the wheel frame \[m\].
    pub top: f64,
    /// Vertical deflection: unloaded outer radius + top \[m\] (the ground's travel past first
    /// touch).
    pub deflection: f64,
    /// Total vertical contact force \[N\] (with camber: along the road normal).
    pub force: f64,
    /// Normal multiplier per contact node \[N\] (contact force magnitude).
    pub lambda: Vec<f64>,
    /// Contact-node deflections `δ^c` (3 n_c) \[m\].
    pub delta_c: Vec<f64>,
    /// Contact-node forces `f^c` (3 n_c) \[N\].
    pub f_c: Vec<f64>,
}

/// Multipliers λ, contact-node forces f^c and deflections δ^c of one contact state.
pub(crate) type ContactState = (Vec<f64>, Vec<f64>, Vec<f64>);

/// Contact state for a fixed ground height: returns (λ, f^c, δ^c).
pub(crate) fn contact_at(
    y: &Mat<f64>, s_c: &[[f64; 3]], ground: &Ground,
) -> Result<ContactState, TireError> {
    let nc = s_c.len();
    let mut delta = vec![0.0; 3 * nc];
    let mut lambda = vec![0.0; nc];
    let mut f_c = vec![0.0; 3 * nc];
    let mut active = vec![false; nc];
    for _pass in 0..6 {
        let mut q = vec![0.0; nc];
        let mut nrm = vec![[0.0; 3]; nc];
        for i in 0..nc {
            let p = [
                s_c[i][0] + delta[3 * i],
                s_c[i][1] + delta[3 * i + 1],
                s_c[i][2] + delta[3 * i + 2],
            ];
            let gp = ground.query(0.0, p);
            nrm[i] = gp.normal;
            // linearised gap at δ = 0 reference: g + n·(δ' − δ)
            q[i] = gp.gap - (0..3).map(|a| gp.normal[a] * delta[3 * i + a]).sum::<f64>();
        }
        let w = Mat::from_fn(nc, nc, |i, j| {
            let mut s = 0.0;
            for a in 0..3 {
                for b in 0..3 {
                    s += nrm[i][a] * y[(3 * i + a, 3 * j + b)] * nrm[j][b];
                }
            }
            s
        });
        let sol = solve_lcp(&w, &q, &active, 1e-12);
        if !sol.converged {
            return Err(TireError::Simulation {
                time: 0.0,
                reason: "static contact active set did not converge".into(),
            });
        }
        let new_f: Vec<f64> = (0..3 * nc)
            .map(|k| nrm[k / 3][k % 3] * sol.lambda[k / 3])
            .collect();
        let new_delta: Vec<f64> = (0..3 * nc)
            .map(|r| (0..3 * nc).map(|k| y[(r, k)] * new_f[k]).sum())
            .collect();
        let change = new_delta
            .iter()
            .zip(&delta)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        delta = new_delta;
        f_c = new_f;
        lambda = sol.lambda;
        active = lambda.iter().map(|&l| l > 0.0).collect();
        if change < 1e-12 {
            break;
        }
    }
    Ok((lambda, f_c, delta))
}

/// Press the contact nodes (positions `s_c`, flexibility `y`) onto the ground until the
/// vertical force equals `load` \[N\] ([`solve_patch_cambered`] upright).
pub fn solve_patch(
    y: &Mat<f64>, s_c: &[[f64; 3]], ground_cfg: &GroundConfig, load: f64,
) -> Result<PatchSolution, TireError> {
    solve_patch_cambered(y, s_c, ground_cfg, 0.0, load)
}

/// Press the contact nodes (positions `s_c`, flexibility `y`) onto the plain ground of
/// `ground_cfg` ([`GroundConfig::plain`]: no cleat, obstacles or grid) tilted for the camber
/// angle `camber` \[rad\] ([`Ground::with_camber`]: the road's normal `n = (0, sin γ, cos γ)`)
/// until the contact force along the road normal, `Σ nᵀ fᶜ`, equals `load` \[N\]: the preload
/// along the road normal. The ground's position is its top `top` (the contact centre
/// `(0, 0, top)` about which it is tilted); the first touch is at `top = minᵢ nᵀsᵢ / n_z`, and
/// [`PatchSolution::deflection`] is the road's travel along its normal past it. Upright
/// (`camber = 0`) the normal is `ẑ` and the force the vertical one.
pub fn solve_patch_cambered(
    y: &Mat<f64>, s_c: &[[f64; 3]], ground_cfg: &GroundConfig, camber: f64, load: f64,
) -> Result<PatchSolution, TireError> {
    check::positive("load", load, "N")?;
    ground_cfg.validate_within("ground")?;
    let cfg = ground_cfg.plain();
    let (sg, cg) = camber.sin_cos();
    // first touch: the lowest contact node on the ground
    let touch = if camber == 0.0 {
        s_c.iter().map(|s| s[2]).fold(f64::INFINITY, f64::min)
    } else {
        s_c.iter()
            .map(|s| (sg * s[1] + cg * s[2]) / cg)
            .fold(f64::INFINITY, f64::min)
    };
    let outer = -s_c.iter().map(|s| s[2]).fold(f64::INFINITY, f64::min);
    let ground_at =
        |top: f64| Ground::without_grid(cfg.clone(), top, 0.0, 0.0, 0.0).with_camber(camber);
    let force = |top: f64| -> Result<(f64, ContactState), TireError> {
        let (l, f, d) = contact_at(y, s_c, &ground_at(top))?;
        let fz: f64 = if camber == 0.0 {
            (0..s_c.len()).map(|i| f[3 * i + 2]).sum()
        } else {
            (0..s_c.len())
                .map(|i| sg * f[3 * i + 1] + cg * f[3 * i + 2])
                .sum()
        };
        Ok((fz, (l, f, d)))
    };
    // bracket: e in (0, e_hi]
    let (mut lo, mut f_lo) = (0.0, 0.0);
    let mut hi = 1e-3;
    let mut f_hi = force(touch + hi)?.0;
    while f_hi < load {
        lo = hi;
        f_lo = f_hi;
        hi *= 2.0;
        if hi > 0.5 * outer {
            return Err(invalid(
                "load",
                format!("{load} N is not carried by the contact nodes within half the radius"),
            ));
        }
        f_hi = force(touch + hi)?.0;
    }
    // Illinois false position on g(e) = F_z(e) − load, to |g| ≤ 1e-9 load or a bracket of
    // 1e-14 m (mbd_core::roots)
    let stop = FalsePositionStop {
        max_iterations: 100,
        width: 1e-14,
        residual: 1e-9 * load,
    };
    let g = |e: f64| force(touch + e).map(|(f, _)| f - load);
    let e = false_position(g, lo, hi, f_lo - load, f_hi - load, stop)?.last;
    let (fz, (lambda, f_c, delta_c)) = force(touch + e)?;
    Ok(PatchSolution {
        top: touch + e,
        deflection: if camber == 0.0 { e } else { e * cg },
        force: fz,
        lambda,
        delta_c,
        f_c,
    })
}

/// Contact-node flexibility of the reduced tire `Y = T_c K_z⁻¹ T_cᵀ` and `K_z⁻¹ T_cᵀ`.
pub fn reduced_flexibility(red: &ReducedTire) -> Result<(Mat<f64>, Mat<f64>), TireError> {
    let llt = red
        .k
        .llt(Side::Lower)
        .map_err(|e| linalg("Cholesky of the reduced stiffness K_z", e))?;
    let x = llt.solve(red.tc.transpose().to_owned());
    let y = &red.tc * &x;
    Ok((y, x))
}

/// Contact-node flexibility of the full FE tire with the rim fixed: `Y = E_cᵀ K⁻¹ E_c`.
pub fn full_flexibility(fe: &TireFe, contact_nodes: &[usize]) -> Result<Mat<f64>, TireError> {
    let part = TirePartition::new(fe, contact_nodes.to_vec());
    let rim = fe.rim_mask();
    let dofs: Vec<usize> = (0..fe.n_dofs()).filter(|d| !rim[d / 3]).collect();
    let mut pos = vec![usize::MAX; fe.n_dofs()];
    for (k, &d) in dofs.iter().enumerate() {
        pos[d] = k;
    }
    let k = fe_model::sparse::submatrix(fe.stiffness.as_ref(), &dofs, &dofs)?;
    let llt = k
        .sp_cholesky(Side::Lower)
        .map_err(|e| linalg("Cholesky of the full tire stiffness (rim fixed)", e))?;
    let nc3 = part.c.len();
    let mut rhs = Mat::<f64>::zeros(dofs.len(), nc3);
    for (j, &d) in part.c.iter().enumerate() {
        rhs[(pos[d], j)] = 1.0;
    }
    llt.solve_in_place(rhs.as_mut());
    Ok(Mat::from_fn(nc3, nc3, |i, j| rhs[(pos[part.c[i]], j)]))
}

/// The preloaded reduced tire: patch solution and the reduced coordinates `z = K_z⁻¹ T_cᵀ f^c`.
#[derive(Debug, Clone)]
pub struct Preload {
    /// Patch solution.
    pub patch: PatchSolution,
    /// Reduced coordinates at the preload.
    pub z: Vec<f64>,
}

/// Preload the reduced tire onto the ground with `load` \[N\] (not rolling).
pub fn preload(red: &ReducedTire, ground: &GroundConfig, load: f64) -> Result<Preload, TireError> {
    preload_cambered(red, ground, 0.0, load)
}

/// [`preload`] on the ground tilted for the camber angle `camber` \[rad\], `load` along the
/// road normal ([`solve_patch_cambered`]).
pub fn preload_cambered(
    red: &ReducedTire, ground: &GroundConfig, camber: f64, load: f64,
) -> Result<Preload, TireError> {
    let (y, x) = reduced_flexibility(red)?;
    let patch = solve_patch_cambered(&y, &red.contact_positions, ground, camber, load)?;
    let z = (0..red.n_z())
        .map(|r| (0..patch.f_c.len()).map(|k| x[(r, k)] * patch.f_c[k]).sum())
        .collect();
    Ok(Preload { patch, z })
}

/// Preload of the steadily rolling tire (spin rate `spin` \[rad/s\], Rayleigh `beta` \[s\]): the
/// Eulerian steady state `ż = 0` of the rolling equations,
/// `(K_z + θ̇² G₂ + β θ̇ K₁) z + θ̇² c_s = T_cᵀ f^c`, with the normal contact forces carrying
/// `load` (friction neglected in the preload). With the spindle fixed at this position the
/// rolling tire starts in equilibrium, so the vertical spindle force equals the load.
pub fn preload_rolling(
    red: &ReducedTire, ground: &GroundConfig, load: f64, spin: f64, beta: f64,
) -> Result<Preload, TireError> {
    preload_rolling_cambered(red, ground, 0.0, load, spin, beta)
}

/// [`preload_rolling`] on the ground tilted for the camber angle `camber` \[rad\], `load`
/// along the road normal ([`solve_patch_cambered`]).
pub fn preload_rolling_cambered(
    red: &ReducedTire, ground: &GroundConfig, camber: f64, load: f64, spin: f64, beta: f64,
) -> Result<Preload, TireError> {
    let nz = red.n_z();
    let keff = Mat::from_fn(nz, nz, |i, j| {
        red.k[(i, j)] + spin * spin * red.g2[(i, j)] + beta * spin * red.k1[(i, j)]
    });
    let lu = keff.partial_piv_lu();
    let mut rhs = Mat::<f64>::zeros(nz, red.tc.nrows() + 1);
    for j in 0..red.tc.nrows() {
        for i in 0..nz {
            rhs[(i, j)] = red.tc[(j, i)];
        }
    }
    for i in 0..nz {
        rhs[(i, red.tc.nrows())] = -spin * spin * red.c_s[i];
    }
    let sol = lu.solve(&rhs);
    if !sol.as_ref().is_all_finite() {
        return Err(linalg("steady rolling stiffness", "singular"));
    }
    let nc3 = red.tc.nrows();
    let x = sol.subcols(0, nc3).to_owned();
    let z0: Vec<f64> = (0..nz).map(|i| sol[(i, nc3)]).collect();
    let y = &red.tc * &x;
    let shifted: Vec<[f64; 3]> = red
        .contact_positions
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let mut p = *s;
            for (a, pa) in p.iter_mut().enumerate() {
                *pa += (0..nz).map(|j| red.tc[(3 * i + a, j)] * z0[j]).sum::<f64>();
            }
            p
        })
        .collect();
    let mut patch = solve_patch_cambered(&y, &shifted, ground, camber, load)?;
    // deflection measured from the unloaded, non-rolling outer radius
    let touch = red
        .contact_positions
        .iter()
        .map(|s| s[2])
        .fold(f64::INFINITY, f64::min);
    patch.deflection = if camber == 0.0 {
        patch.top - touch
    } else {
        // along the road normal from the first touch of the unloaded, non-rolling tire
        let (sg, cg) = camber.sin_cos();
        let touch_n = red
            .contact_positions
            .iter()
            .map(|s| (sg * s[1] + cg * s[2]) / cg)
            .fold(f64::INFINITY, f64::min);
        (patch.top - touch_n) * cg
    };
    for i in 0..nc3 {
        patch.delta_c[i] += (0..nz).map(|j| red.tc[(i, j)] * z0[j]).sum::<f64>();
    }
    let z = (0..nz)
        .map(|r| z0[r] + (0..nc3).map(|k| x[(r, k)] * patch.f_c[k]).sum::<f64>())
        .collect();
    Ok(Preload { patch, z })
}
