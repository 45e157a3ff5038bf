//! Axis (reference) conditions applied to reduction bases: nodal-fixed anchors (Lin Table 4-1,
//! (4.1)–(4.2), §5.4.1), mean axes (Lin Table 4-2, (8.2)–(8.3), (8.26)–(8.27)) and the chapter-8
//! preconditions for using a conventional basis with mean axes (Lin §8.2.1).

use crate::basis::{Basis, Column};
use crate::error::{ReductionError, Result};
use crate::linalg::{
    check_square, congruence, orth, rank, select_cols, solve_general, span_distance, sym_gen_eig,
};
use faer::{Mat, MatRef};
use serde::{Deserialize, Serialize};

/// A body-frame axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// ξ (local x).
    Xi,
    /// η (local y).
    Eta,
    /// ζ (local z).
    Zeta,
}

impl Axis {
    /// Component index 0, 1, 2.
    pub fn index(self) -> usize {
        match self {
            Axis::Xi => 0,
            Axis::Eta => 1,
            Axis::Zeta => 2,
        }
    }
}

/// A nodal-fixed frame in 3-D (Lin §4.1, Table 4-1): origin at node `origin` (3 zero local
/// deflections), `axis` passing through `axis_node` (2 zeros), and `plane_node` lying in the
/// plane spanned by `axis` and `plane_axis` (1 zero: the component normal to that plane).
///
/// Node indices are 0-based; each node has 3 translational DOFs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct NodalFixedFrame {
    /// Origin node.
    pub origin: usize,
    /// Node on the first axis.
    pub axis_node: usize,
    /// First axis (through `axis_node`).
    pub axis: Axis,
    /// Node in the coordinate plane.
    pub plane_node: usize,
    /// Second axis spanning the plane together with `axis`.
    pub plane_axis: Axis,
}

impl NodalFixedFrame {
    /// The six anchored (zero) local DOFs of Table 4-1, as full-model DOF indices.
    pub fn anchored_dofs(&self, n_nodes: usize) -> Result<Vec<usize>> {
        let nodes = [self.origin, self.axis_node, self.plane_node];
        for &j in &nodes {
            if j >= n_nodes {
                return Err(ReductionError::InvalidDofs {
                    what: "nodal-fixed frame".into(),
                    reason: format!("node {j} (0-based) is out of range ({n_nodes} nodes)"),
                });
            }
        }
        if self.origin == self.axis_node
            || self.origin == self.plane_node
            || self.axis_node == self.plane_node
        {
            return Err(ReductionError::InvalidDofs {
                what: "nodal-fixed frame".into(),
                reason: "origin, axis and plane nodes must be three distinct nodes".into(),
            });
        }
        if self.axis == self.plane_axis {
            return Err(ReductionError::InvalidParameter {
                name: "nodal-fixed frame plane_axis".into(),
                reason: "the plane axis must differ from the first axis".into(),
            });
        }
        let a = self.axis.index();
        let p = self.plane_axis.index();
        let normal = 3 - a - p;
        let mut dofs: Vec<usize> = (0..3).map(|c| 3 * self.origin + c).collect();
        dofs.extend((0..3).filter(|&c| c != a).map(|c| 3 * self.axis_node + c));
        dofs.push(3 * self.plane_node + normal);
        Ok(dofs)
    }
}

/// Nodal-fixed selection `Ψ = [0_ou; I_uu]` (Lin (4.1)–(4.2)) in natural row order:
/// `n × (n − n_o)` with the anchored DOFs `anchored` as zero rows.
pub fn nodal_fixed_selection(n: usize, anchored: &[usize]) -> Result<Mat<f64>> {
    for &d in anchored {
        if d >= n {
            return Err(ReductionError::InvalidDofs {
                what: "anchored DOF set".into(),
                reason: format!("DOF {d} out of range ({n} DOFs)"),
            });
        }
    }
    let free: Vec<usize> = (0..n).filter(|d| !anchored.contains(d)).collect();
    let mut psi = Mat::<f64>::zeros(n, free.len());
    for (c, &d) in free.iter().enumerate() {
        psi[(d, c)] = 1.0;
    }
    Ok(psi)
}

/// Removes the columns of `basis` that carry the anchored coordinates (Lin §5.4.1, Table 7-2:
/// "six columns of Ψ are removed").
///
/// Each anchored DOF must be a boundary coordinate with an identity-type row in Ψ (row = unit
/// vector `e_c`), so that `δ'_o = z_c = 0` is exactly the removal of column `c`. Otherwise the
/// rule is undefined (Lin note §16 item 10) and an error names the DOF.
pub fn remove_anchor_columns(basis: &Basis, anchored: &[usize]) -> Result<Basis> {
    let psi = &basis.psi;
    let mut remove = Vec::with_capacity(anchored.len());
    for &d in anchored {
        if d >= psi.nrows() {
            return Err(ReductionError::InvalidDofs {
                what: "anchored DOF set".into(),
                reason: format!("DOF {d} out of range ({} DOFs)", psi.nrows()),
            });
        }
        let nz: Vec<usize> = (0..psi.ncols()).filter(|&c| psi[(d, c)] != 0.0).collect();
        if nz.len() != 1 || (psi[(d, nz[0])] - 1.0).abs() > 1e-12 {
            return Err(ReductionError::InvalidDofs {
                what: "anchored DOF set".into(),
                reason: format!(
                    "DOF {d} is not a boundary coordinate of the basis (its row is not a unit vector); \
                     anchor the nodal-fixed frame at boundary nodes"
                ),
            });
        }
        remove.push(nz[0]);
    }
    let keep: Vec<usize> = (0..psi.ncols()).filter(|c| !remove.contains(c)).collect();
    Ok(Basis {
        method: basis.method,
        psi: select_cols(psi.as_ref(), &keep),
        columns: keep
            .iter()
            .map(|&c| basis.columns[c])
            .collect::<Vec<Column>>(),
    })
}

/// Rigid-body displacement fields `P = [Ih  ω×s]` for node positions `s` (relative to the
/// frame origin): `dim` translations, then the infinitesimal rotations (3 in 3-D, about ξ, η, ζ:
/// columns `−s~` of Lin (8.18); 1 in 2-D: `s̆ = (−sη, sξ)` of Lin (8.40)).
///
/// `s` has `dim` entries per node; the result is `n × 6` (3-D) or `n × 3` (2-D).
pub fn rigid_body_modes(s: &[f64], dim: usize) -> Result<Mat<f64>> {
    match dim {
        2 => Ok(Mat::from_fn(s.len(), 3, |i, j| {
            let (node, c) = (i / 2, i % 2);
            let (x, y) = (s[2 * node], s[2 * node + 1]);
            match j {
                0 => (c == 0) as u8 as f64,
                1 => (c == 1) as u8 as f64,
                _ if c == 0 => -y,
                _ => x,
            }
        })),
        3 => Ok(Mat::from_fn(s.len(), 6, |i, j| {
            let (node, c) = (i / 3, i % 3);
            if j < 3 {
                return (c == j) as u8 as f64;
            }
            let p = [s[3 * node], s[3 * node + 1], s[3 * node + 2]];
            // e_k × p
            let k = j - 3;
            let mut e = [0.0; 3];
            e[k] = 1.0;
            let cross = [
                e[1] * p[2] - e[2] * p[1],
                e[2] * p[0] - e[0] * p[2],
                e[0] * p[1] - e[1] * p[0],
            ];
            cross[c]
        })),
        _ => Err(ReductionError::InvalidParameter {
            name: "dim".into(),
            reason: format!("{dim}: only 2-D and 3-D bodies are supported"),
        }),
    }
}

/// Linearised mean-axis condition rows `Pᵀ M Ψ` (Lin (8.26)–(8.27); `IhᵀMΨ Δz = 0`,
/// `s~ᵀMΨ Δz = 0`), `n_rigid × n_z`.
pub fn mean_axis_rows(
    m: MatRef<'_, f64>, s: &[f64], dim: usize, psi: MatRef<'_, f64>,
) -> Result<Mat<f64>> {
    let p = rigid_body_modes(s, dim)?;
    check_square("mass matrix M", m, p.nrows())?;
    Ok(congruence(p.as_ref(), m, psi))
}

/// Split of each basis column into rigid translation/rotation and mean-axes deformation
/// (Lin (8.4)–(8.7)): `Ψ = P [Δr#; Δθ#] + [Δδ#]` with `PᵀM[Δδ#] = 0`.
///
/// Returns `(rigid amplitudes (n_rigid × n_z), deformation part (n × n_z))`.
pub fn mean_axes_decomposition(
    m: MatRef<'_, f64>, s: &[f64], dim: usize, psi: MatRef<'_, f64>,
) -> Result<(Mat<f64>, Mat<f64>)> {
    let p = rigid_body_modes(s, dim)?;
    let ptmp = congruence(p.as_ref(), m, p.as_ref());
    let ptmpsi = congruence(p.as_ref(), m, psi);
    let a = solve_general("rigid-body mass PᵀMP", ptmp.as_ref(), ptmpsi.as_ref())?;
    let def = psi - &p * &a;
    Ok((a, def))
}

/// Result of the chapter-8 precondition check (Lin §8.2.1).
#[derive(Debug, Clone, Serialize)]
pub struct MeanAxesPreconditions {
    /// Number of columns of Ψ.
    pub n_cols: usize,
    /// Numerical rank of Ψ.
    pub rank: usize,
    /// Number of (numerically) zero eigenvalues of `eig(ΨᵀKΨ, ΨᵀMΨ)` (Lin (8.14)).
    pub n_zero_eigenvalues: usize,
    /// Expected number of rigid-body modes (6 in 3-D, 3 in 2-D).
    pub n_rigid: usize,
    /// Sine of the largest principal angle between `Ψ0 = ΨV0` and `P = [Ih −s~]`
    /// (0 when `R` of (8.18) is invertible and exact).
    pub span_defect: f64,
    /// All three conditions hold: full column rank, exactly `n_rigid` zero eigenvalues,
    /// `Ψ0` spans the rigid-body modes.
    pub passes: bool,
}

/// The rigid-body modes `P` of [`rigid_body_modes`] after checking that `K` and `M` are square
/// of the order of `Ψ`'s rows and that `s` has one entry per DOF (the input checks shared by
/// [`check_mean_axes_preconditions`] and [`crate::mean_axes_eval::evaluate_mean_axes`]).
pub(crate) fn checked_rigid_body_modes(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, psi: MatRef<'_, f64>, s: &[f64], dim: usize,
) -> Result<Mat<f64>> {
    let n = psi.nrows();
    check_square("stiffness matrix K", k, n)?;
    check_square("mass matrix M", m, n)?;
    let p = rigid_body_modes(s, dim)?;
    if p.nrows() != n {
        return Err(ReductionError::Shape {
            what: "node positions s".into(),
            expected: format!("{n} values"),
            rows: p.nrows(),
            cols: 1,
        });
    }
    Ok(p)
}

/// `V0`: the eigenvectors of `eig(ΨᵀKΨ, ΨᵀMΨ)` whose eigenvalues are (numerically) zero,
/// `|λ| ≤ 1e-9 max|λ|` (Lin (8.14)), as columns (none when the pencil has no zero eigenvalue).
fn zero_eigenvectors(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, psi: MatRef<'_, f64>,
) -> Result<Mat<f64>> {
    let kr = congruence(psi, k, psi);
    let mr = congruence(psi, m, psi);
    let (lam, v) = sym_gen_eig("reduced model (ΨᵀKΨ, ΨᵀMΨ)", kr.as_ref(), mr.as_ref())?;
    let lmax = lam.iter().fold(0.0_f64, |a, &l| a.max(l.abs()));
    let zero: Vec<usize> = (0..lam.len())
        .filter(|&i| lam[i].abs() <= 1e-9 * lmax.max(f64::MIN_POSITIVE))
        .collect();
    Ok(select_cols(v.as_ref(), &zero))
}

/// Checks the chapter-8 preconditions for using basis `psi` with mean axes (Lin §8.1, §8.2.1):
/// full column rank, exactly 6 (3 in 2-D) zero eigenvalues of `eig(ΨᵀKΨ, ΨᵀMΨ)`, and
/// `col-space(Ψ0) = col-space(P)` (R of (8.18) invertible).
pub fn check_mean_axes_preconditions(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, psi: MatRef<'_, f64>, s: &[f64], dim: usize,
) -> Result<MeanAxesPreconditions> {
    let p = checked_rigid_body_modes(k, m, psi, s, dim)?;
    let n_rigid = p.ncols();
    let r = rank(psi, 1e-10)?;
    let mut out = MeanAxesPreconditions {
        n_cols: psi.ncols(),
        rank: r,
        n_zero_eigenvalues: 0,
        n_rigid,
        span_defect: 1.0,
        passes: false,
    };
    if r < psi.ncols() {
        return Ok(out);
    }
    let v0 = zero_eigenvectors(k, m, psi)?;
    out.n_zero_eigenvalues = v0.ncols();
    if v0.ncols() > 0 {
        let psi0 = psi * &v0;
        out.span_defect = span_distance(psi0.as_ref(), p.as_ref())?;
    }
    out.passes = out.rank == out.n_cols
        && out.n_zero_eigenvalues == n_rigid
        && out.span_defect < 1e-6
        && orth(p.as_ref(), 1e-10)?.ncols() == n_rigid;
    Ok(out)
}

/// Adapting vector of the modal coordinates (Lin (8.12)–(8.21)): for a frame translation and
/// small rotation `{Δr; Δθ}` (6 values in 3-D, 3 in 2-D), the `x` with `Ψ x = −P {Δr; Δθ}`,
/// `x = −V0 R⁻¹ {Δr; Δθ}`, `Ψ0 = Ψ V0 = P R` (V0: the zero-eigenvalue vectors of
/// `eig(ΨᵀKΨ, ΨᵀMΨ)`). Requires the chapter-8 preconditions
/// ([`check_mean_axes_preconditions`]).
pub fn adapting_vector(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, psi: MatRef<'_, f64>, s: &[f64], dim: usize,
    rigid: &[f64],
) -> Result<Vec<f64>> {
    let pre = check_mean_axes_preconditions(k, m, psi, s, dim)?;
    if !pre.passes {
        return Err(ReductionError::InvalidParameter {
            name: "basis".into(),
            reason: format!(
                "violates the chapter-8 preconditions (rank {}/{}, {} zero eigenvalues for {} rigid modes)",
                pre.rank, pre.n_cols, pre.n_zero_eigenvalues, pre.n_rigid
            ),
        });
    }
    let p = rigid_body_modes(s, dim)?;
    if rigid.len() != p.ncols() {
        return Err(ReductionError::InvalidParameter {
            name: "rigid".into(),
            reason: format!("expected {} values, got {}", p.ncols(), rigid.len()),
        });
    }
    let v0 = zero_eigenvectors(k, m, psi)?;
    let psi0 = psi * &v0;
    // R = (PᵀP)⁻¹ Pᵀ Ψ0   (8.18)
    let ptp = p.transpose() * &p;
    let ptpsi0 = p.transpose() * &psi0;
    let r = solve_general("PᵀP", ptp.as_ref(), ptpsi0.as_ref())?;
    let rhs = Mat::from_fn(rigid.len(), 1, |i, _| rigid[i]);
    let y = solve_general("R of (8.18)", r.as_ref(), rhs.as_ref())?;
    let x = &v0 * &y;
    Ok((0..x.nrows()).map(|i| -x[(i, 0)]).collect())
}
