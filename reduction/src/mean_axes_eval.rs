//! Evaluation of a reduction basis with mean axes without time simulation (Lin §8.4):
//! constraint modes from the static problem (8.30)/(8.44) and fixed-constraint normal modes from
//! the eigenproblem (8.33)/(8.45).
//!
//! Unknowns `q = {Δr; Δθ; Δz}`, absolute displacement `Δd = G q` with `G = [P  Ψ]`,
//! `P = [Ih  ω×s]` (see [`crate::axes::rigid_body_modes`]). Conditions: the linearised mean-axis
//! rows `[0  PᵀMΨ] q = 0` and the boundary rows `G_b q = Δd_b`.

use crate::axes::checked_rigid_body_modes;
use crate::error::{ReductionError, Result};
use crate::linalg::{congruence, null_space, solve_general, sym_gen_eig, symmetrize};
use faer::{Mat, MatRef};

/// Result of the mean-axes evaluation of a basis (Lin §8.4, §8.5).
#[derive(Debug, Clone)]
pub struct MeanAxesEvaluation {
    /// `[Δr; Δθ; Δz]^c` per unit boundary displacement (Lin (8.30), (8.44)):
    /// `(n_rigid + n_z) × n_b`.
    pub constraint_coordinates: Mat<f64>,
    /// `[Δd]^c = G [Δr; Δθ; Δz]^c` (Lin (8.32)): `n × n_b`.
    pub constraint_modes: Mat<f64>,
    /// Non-zero natural frequencies of (8.33)/(8.45) \[Hz\], ascending.
    pub normal_frequencies_hz: Vec<f64>,
    /// `[Δr; Δθ; Δz]^n`, each column scaled to unit max-abs entry (MATLAB QZ convention of the
    /// printed vectors; sign free).
    pub normal_coordinates: Mat<f64>,
    /// `[Δd]^n = G [Δr; Δθ; Δz]^n` (Lin (8.35)).
    pub normal_modes: Mat<f64>,
}

/// Runs the static (8.30) and eigen (8.33) evaluations of basis `psi` with mean axes.
///
/// `s`: undeformed node positions relative to the mass centre (`dim` per node, Lin (8.39));
/// `boundary`: the boundary DOFs `d_b` that are displaced / fixed.
///
/// The eigenproblem is solved by projecting onto the null space of the constraint rows, which
/// gives a symmetric-definite problem equivalent to the singular pencil (8.33) for `ω ≠ 0`
/// (Lin note §13.2).
pub fn evaluate_mean_axes(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, psi: MatRef<'_, f64>, s: &[f64], dim: usize,
    boundary: &[usize],
) -> Result<MeanAxesEvaluation> {
    let n = psi.nrows();
    let p = checked_rigid_body_modes(k, m, psi, s, dim)?;
    for &d in boundary {
        if d >= n {
            return Err(ReductionError::InvalidDofs {
                what: "boundary DOF set".into(),
                reason: format!("DOF {d} out of range ({n} DOFs)"),
            });
        }
    }
    let nr = p.ncols();
    let nz = psi.ncols();
    let nq = nr + nz;
    let nb = boundary.len();
    // G = [P Ψ]
    let g = Mat::from_fn(
        n,
        nq,
        |i, j| if j < nr { p[(i, j)] } else { psi[(i, j - nr)] },
    );
    // A = blockdiag(0, ΨᵀKΨ)
    let kr = congruence(psi, k, psi);
    let mut a = Mat::<f64>::zeros(nq, nq);
    for i in 0..nz {
        for j in 0..nz {
            a[(nr + i, nr + j)] = kr[(i, j)];
        }
    }
    // constraint rows: mean axes [0 PᵀMΨ], boundary G_b
    let mac = congruence(p.as_ref(), m, psi);
    let nc = nr + nb;
    let mut c = Mat::<f64>::zeros(nc, nq);
    for i in 0..nr {
        for j in 0..nz {
            c[(i, nr + j)] = mac[(i, j)];
        }
    }
    for (r, &d) in boundary.iter().enumerate() {
        for j in 0..nq {
            c[(nr + r, j)] = g[(d, j)];
        }
    }
    // static problem (8.30): [A Cᵀ; C 0] {q; λ} = {0; 0; i_l}
    let nk = nq + nc;
    let mut kkt = Mat::<f64>::zeros(nk, nk);
    for i in 0..nq {
        for j in 0..nq {
            kkt[(i, j)] = a[(i, j)];
        }
    }
    for i in 0..nc {
        for j in 0..nq {
            kkt[(nq + i, j)] = c[(i, j)];
            kkt[(j, nq + i)] = c[(i, j)];
        }
    }
    let rhs = Mat::from_fn(nk, nb, |i, l| (i == nq + nr + l) as u8 as f64);
    let sol = solve_general(
        "mean-axes static problem (8.30)",
        kkt.as_ref(),
        rhs.as_ref(),
    )?;
    let cq = sol.subrows(0, nq).to_owned();
    let cmodes = &g * &cq;

    // eigenproblem (8.33) on the null space of C
    let nsp = null_space(c.as_ref(), 1e-10)?;
    let an = symmetrize(&congruence(nsp.as_ref(), a.as_ref(), nsp.as_ref()));
    let gn = &g * &nsp;
    let bn = symmetrize(&congruence(gn.as_ref(), m, gn.as_ref()));
    let (lam, y) = sym_gen_eig("mean-axes eigenproblem (8.33)", an.as_ref(), bn.as_ref())?;
    let lmax = lam.iter().fold(0.0_f64, |x, &l| x.max(l.abs()));
    let keep: Vec<usize> = (0..lam.len())
        .filter(|&i| lam[i] > 1e-9 * lmax.max(f64::MIN_POSITIVE))
        .collect();
    let mut nq_mat = Mat::<f64>::zeros(nq, keep.len());
    for (c2, &i) in keep.iter().enumerate() {
        let mut amax = 0.0_f64;
        let mut col = vec![0.0; nq];
        for (r, v) in col.iter_mut().enumerate() {
            *v = (0..nsp.ncols()).map(|t| nsp[(r, t)] * y[(t, i)]).sum();
            if v.abs() > amax.abs() {
                amax = *v;
            }
        }
        for r in 0..nq {
            nq_mat[(r, c2)] = col[r] / amax;
        }
    }
    let nmodes = &g * &nq_mat;
    let hz = keep
        .iter()
        .map(|&i| lam[i].sqrt() / (2.0 * std::f64::consts::PI))
        .collect();
    Ok(MeanAxesEvaluation {
        constraint_coordinates: cq,
        constraint_modes: cmodes,
        normal_frequencies_hz: hz,
        normal_coordinates: nq_mat,
        normal_modes: nmodes,
    })
}
