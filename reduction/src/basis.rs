//! Reduction bases `δ = Ψ z` from dense `(M, K)` and a boundary DOF set (Lin ch. 6, Ribaric ch. 3).
//!
//! Every basis has its rows in the natural DOF order of the full model; the rows of the fixed
//! DOFs of the [`DofPartition`] are zero (clamped). Column order: first the boundary DOFs (in the
//! order of the [`DofPartition`]), then the kept normal modes in ascending frequency, except for
//! free-free modal truncation, which has only modes.
//!
//! These dense bases serve Lin's small models and are the second formulation against which the
//! partitioned sparse Craig–Bampton ([`crate::sparse::craig_bampton`]) is tested.

use crate::error::{ReductionError, Result};
use crate::linalg::{check_finite, check_square, select, solve_spd, sym_gen_eig};
use crate::partition::DofPartition;
use faer::{Mat, MatRef};
use serde::{Deserialize, Serialize};

/// Reduction method (Lin Table 7-1 and Table 7-2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Static condensation, `Ψ = [I; Ψs]`, `Ψs = −K_ii⁻¹K_ib` (Lin (6.3)–(6.5), Ribaric (3.5)).
    Guyan,
    /// Lin's "modal truncation": boundary DOFs kept plus fixed-interface normal modes, **no**
    /// static modes, `Ψ = [I 0; 0 Ψn^k]` (Lin (6.17)). Named for what it is.
    FixedInterfaceModalTruncation,
    /// Classical free-free modal truncation: the lowest modes of `(K, M)`, rigid-body modes
    /// included; no boundary DOFs are kept (with fixed DOFs: the modes of the unfixed block).
    FreeFreeModalTruncation,
    /// Craig–Bampton, `Ψ = [I 0; Ψs Ψn^k]` (Lin (6.19), Ribaric (3.15)).
    CraigBampton,
    /// Nikravesh's mode condensation, `Ψ = [I 0; Ψm Ψn^k]` with
    /// `Ψm = −Ψn^d (K̄n^d)⁻¹ Ψn^dᵀ K_ib` (Lin (6.29), (6.30); Ribaric (3.19)–(3.23)).
    ModeCondensation,
}

impl Method {
    /// Short name used in files and on the command line.
    pub fn short_name(self) -> &'static str {
        match self {
            Method::Guyan => "guyan",
            Method::FixedInterfaceModalTruncation => "fixed-interface-mt",
            Method::FreeFreeModalTruncation => "free-free-mt",
            Method::CraigBampton => "cb",
            Method::ModeCondensation => "mc",
        }
    }

    /// Whether the method keeps the boundary DOFs as physical coordinates.
    pub fn keeps_boundary(self) -> bool {
        !matches!(self, Method::FreeFreeModalTruncation)
    }

    /// Whether the method uses normal modes (so a mode count is meaningful).
    pub fn uses_modes(self) -> bool {
        !matches!(self, Method::Guyan)
    }
}

/// Which normal modes are kept.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub enum ModeSelection {
    /// The `n` modes of lowest frequency.
    Lowest(usize),
    /// Explicit 0-based mode indices in the ascending-frequency order (e.g. Lin §7.1 keeps the
    /// first and second bending modes).
    Indices(Vec<usize>),
}

impl ModeSelection {
    /// The kept indices, each below `available`; a count is checked before anything is
    /// allocated from it (issue 35: `--modes 99999999999` allocated 800 GB here).
    fn resolve(&self, available: usize) -> Result<Vec<usize>> {
        let idx: Vec<usize> = match self {
            ModeSelection::Lowest(n) if *n > available => {
                return Err(ReductionError::InvalidParameter {
                    name: "modes".into(),
                    reason: format!(
                        "{n} modes requested but only {available} normal modes exist for this partition"
                    ),
                });
            }
            ModeSelection::Lowest(n) => (0..*n).collect(),
            ModeSelection::Indices(v) => v.clone(),
        };
        for (p, &i) in idx.iter().enumerate() {
            if i >= available {
                return Err(ReductionError::InvalidParameter {
                    name: "modes".into(),
                    reason: format!(
                        "mode {i} requested but only {available} normal modes exist for this partition"
                    ),
                });
            }
            if idx[..p].contains(&i) {
                return Err(ReductionError::InvalidParameter {
                    name: "modes".into(),
                    reason: format!("mode {i} is listed twice"),
                });
            }
        }
        Ok(idx)
    }
}

/// Meaning of one column of a basis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Column {
    /// Unit displacement of a boundary DOF (physical coordinate; identity row in Ψ).
    Boundary {
        /// Full-model DOF index.
        dof: usize,
    },
    /// A normal mode (fixed-interface or free-free).
    Mode {
        /// 0-based index in ascending frequency.
        index: usize,
        /// Eigenvalue `ω²` \[rad²/s²\].
        eigenvalue: f64,
    },
}

/// A reduction basis `δ = Ψ z` with the meaning of each column.
#[derive(Debug, Clone)]
pub struct Basis {
    /// Method that produced it.
    pub method: Method,
    /// `n × n_z` transformation, rows in natural DOF order.
    pub psi: Mat<f64>,
    /// Meaning of each column.
    pub columns: Vec<Column>,
}

/// Fixed-interface normal modes: all eigenpairs of `(K_ii, M_ii)` (Lin (6.11), Ribaric (3.11)),
/// ascending, M-normalized.
pub fn fixed_interface_modes(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, part: &DofPartition,
) -> Result<(Vec<f64>, Mat<f64>)> {
    check_inputs(k, m, part)?;
    let kii = select(k, part.interior(), part.interior());
    let mii = select(m, part.interior(), part.interior());
    sym_gen_eig(
        "fixed-interface problem (K_ii, M_ii)",
        kii.as_ref(),
        mii.as_ref(),
    )
}

/// Static (constraint) modes `Ψs = −K_ii⁻¹ K_ib` (Lin (6.3), Ribaric (3.5)); `n_i × n_b`.
pub fn static_modes(k: MatRef<'_, f64>, part: &DofPartition) -> Result<Mat<f64>> {
    let n = part.n();
    check_square("stiffness matrix", k, n)?;
    check_finite("stiffness matrix", k)?;
    let kii = select(k, part.interior(), part.interior());
    let kib = select(k, part.interior(), part.boundary());
    let mut x = solve_spd("interior stiffness K_ii", kii.as_ref(), kib.as_ref())?;
    for j in 0..x.ncols() {
        for i in 0..x.nrows() {
            x[(i, j)] = -x[(i, j)];
        }
    }
    Ok(x)
}

/// Builds the basis of `method` (see [`Method`]) from dense `(M, K)`.
///
/// `modes` is ignored by [`Method::Guyan`]. For [`Method::FreeFreeModalTruncation`] the modes are
/// those of the whole `(K, M)` restricted to the unfixed DOFs; the boundary set is not used.
pub fn build_basis(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, part: &DofPartition, method: Method,
    modes: &ModeSelection,
) -> Result<Basis> {
    check_inputs(k, m, part)?;
    match method {
        Method::Guyan => {
            let psi_s = static_modes(k, part)?;
            Ok(assemble(part, method, Some(&psi_s), None, &[], &[]))
        }
        Method::FreeFreeModalTruncation => {
            let free = part.unfixed();
            // the request is checked before the eigen solve
            modes.resolve(free.len())?;
            let (lam, phi) = if part.fixed().is_empty() {
                sym_gen_eig("free-free problem (K, M)", k, m)?
            } else {
                let (kf, mf) = (select(k, &free, &free), select(m, &free, &free));
                sym_gen_eig("unfixed problem (K, M)", kf.as_ref(), mf.as_ref())?
            };
            let idx = modes.resolve(lam.len())?;
            let mut psi = Mat::zeros(part.n(), idx.len());
            for (j, &mi) in idx.iter().enumerate() {
                for (r, &d) in free.iter().enumerate() {
                    psi[(d, j)] = phi[(r, mi)];
                }
            }
            let columns = idx
                .iter()
                .map(|&i| Column::Mode {
                    index: i,
                    eigenvalue: lam[i],
                })
                .collect();
            Ok(Basis {
                method,
                psi,
                columns,
            })
        }
        Method::FixedInterfaceModalTruncation | Method::CraigBampton | Method::ModeCondensation => {
            modes.resolve(part.interior().len())?;
            let (lam, phi) = fixed_interface_modes(k, m, part)?;
            let idx = modes.resolve(lam.len())?;
            let coupling = match method {
                Method::FixedInterfaceModalTruncation => None,
                Method::CraigBampton => Some(static_modes(k, part)?),
                _ => Some(condensed_modes(k, part, &lam, &phi, &idx)?),
            };
            Ok(assemble(
                part,
                method,
                coupling.as_ref(),
                Some(&phi),
                &lam,
                &idx,
            ))
        }
    }
}

/// Mode-condensation boundary modes `Ψm = Ψn^d Θ`, `Θ = −(K̄n^d)⁻¹ Ψn^dᵀ K_ib`
/// (Lin (6.27), (6.29); Ribaric (3.20)); `kept` lists the kept mode indices, all others are
/// deleted. `lam`, `phi` must be the complete, M-normalized fixed-interface eigensolution.
pub fn condensed_modes(
    k: MatRef<'_, f64>, part: &DofPartition, lam: &[f64], phi: &Mat<f64>, kept: &[usize],
) -> Result<Mat<f64>> {
    let theta = theta_matrix(k, part, lam, phi, kept)?;
    let deleted = deleted_modes(lam.len(), kept);
    let phid = Mat::from_fn(phi.nrows(), deleted.len(), |i, j| phi[(i, deleted[j])]);
    Ok(&phid * &theta)
}

/// `Θ = −(K̄n^d)⁻¹ Ψn^dᵀ K_ib` (Lin (6.27), Ribaric (3.20)): deleted-mode amplitudes per unit
/// boundary displacement; `n_d × n_b`, rows in ascending order of the deleted modes.
pub fn theta_matrix(
    k: MatRef<'_, f64>, part: &DofPartition, lam: &[f64], phi: &Mat<f64>, kept: &[usize],
) -> Result<Mat<f64>> {
    let deleted = deleted_modes(lam.len(), kept);
    // K̄n^d = φdᵀ K_ii φd = λ_d (M-normalized)
    modal_coupling(k, part, lam, phi, &deleted, "deleted")
}

/// The coordinate change `X = −(K̄n^k)⁻¹ Ψn^kᵀ K_ib` of Lin (6.34), with `Ψs = Ψm + Ψn^k X`:
/// `Ψ_CB = Ψ_MC T`, `T = [I 0; X I]`, so `z_MC = T z_CB` (Lin §6.5.4). `n_k × n_b`.
pub fn cb_to_mc_x(
    k: MatRef<'_, f64>, part: &DofPartition, lam: &[f64], phi: &Mat<f64>, kept: &[usize],
) -> Result<Mat<f64>> {
    modal_coupling(k, part, lam, phi, kept, "kept")
}

/// The deleted fixed-interface modes (Lin §6.5.3): the indices `0..n_modes` not in `kept`,
/// ascending.
fn deleted_modes(n_modes: usize, kept: &[usize]) -> Vec<usize> {
    (0..n_modes).filter(|i| !kept.contains(i)).collect()
}

/// `−λ_j⁻¹ φ_jᵀ K_ib` for the fixed-interface modes `modes` (rows), the common kernel of Θ
/// (Lin (6.29)) and X (Lin (6.34)); `which` names the mode set in errors.
fn modal_coupling(
    k: MatRef<'_, f64>, part: &DofPartition, lam: &[f64], phi: &Mat<f64>, modes: &[usize],
    which: &str,
) -> Result<Mat<f64>> {
    let kib = select(k, part.interior(), part.boundary());
    let mut out = Mat::<f64>::zeros(modes.len(), part.boundary().len());
    for (r, &j) in modes.iter().enumerate() {
        if lam[j] <= 0.0 {
            return Err(ReductionError::NotPositiveDefinite {
                what: "interior stiffness K_ii".into(),
                hint: format!("{which} fixed-interface mode {j} has eigenvalue {}", lam[j]),
            });
        }
        for c in 0..part.boundary().len() {
            let mut s = 0.0;
            for i in 0..phi.nrows() {
                s += phi[(i, j)] * kib[(i, c)];
            }
            out[(r, c)] = -s / lam[j];
        }
    }
    Ok(out)
}

/// Reduced matrices of mode condensation in closed form, Ribaric (3.22)–(3.23) with the
/// **corrected** `K_m = K_bb + K_bi Ψn^d Θ` (Ribaric erratum E9: the printed `K^cc + K^cf Ψ^d` is
/// dimensionally inconsistent), generalised to a non-lumped `M` (extra `M_bi Ψm` terms).
///
/// Coordinates `[δb; zn^k]` (the column order of [`Method::ModeCondensation`] bases); returns
/// `(M_MC, K_MC)`. Equals `Ψ_MCᵀ M Ψ_MC`, `Ψ_MCᵀ K Ψ_MC` (tested).
pub fn mode_condensation_matrices(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, part: &DofPartition, kept: &ModeSelection,
) -> Result<(Mat<f64>, Mat<f64>)> {
    let (lam, phi) = fixed_interface_modes(k, m, part)?;
    let idx = kept.resolve(lam.len())?;
    let theta = theta_matrix(k, part, &lam, &phi, &idx)?;
    let deleted = deleted_modes(lam.len(), &idx);
    let b = part.boundary();
    let ii = part.interior();
    let nb = b.len();
    let nk = idx.len();
    let kbb = select(k, b, b);
    let kbi = select(k, b, ii);
    let mbb = select(m, b, b);
    let mbi = select(m, b, ii);
    let phik = Mat::from_fn(ii.len(), nk, |i, j| phi[(i, idx[j])]);
    let phid = Mat::from_fn(ii.len(), deleted.len(), |i, j| phi[(i, deleted[j])]);
    let psim = &phid * &theta;
    // K_m = K_bb + K_bi Ψd Θ   (E9-corrected)
    let km = &kbb + &kbi * &psim;
    let kbk = &kbi * &phik;
    // M_m = M_bb + M_bi Ψm + Ψmᵀ M_ib + Θᵀ Θ   (M̄n^d = I); M_bk = M_bi Ψk (Ψmᵀ M_ii Ψk = 0)
    let mm = &mbb + &mbi * &psim + psim.transpose() * mbi.transpose() + theta.transpose() * &theta;
    let mbk = &mbi * &phik;
    let nz = nb + nk;
    let mut mr = Mat::<f64>::zeros(nz, nz);
    let mut kr = Mat::<f64>::zeros(nz, nz);
    for i in 0..nb {
        for j in 0..nb {
            mr[(i, j)] = mm[(i, j)];
            kr[(i, j)] = km[(i, j)];
        }
        for j in 0..nk {
            mr[(i, nb + j)] = mbk[(i, j)];
            mr[(nb + j, i)] = mbk[(i, j)];
            kr[(i, nb + j)] = kbk[(i, j)];
            kr[(nb + j, i)] = kbk[(i, j)];
        }
    }
    for j in 0..nk {
        mr[(nb + j, nb + j)] = 1.0;
        kr[(nb + j, nb + j)] = lam[idx[j]];
    }
    Ok((mr, kr))
}

fn check_inputs(k: MatRef<'_, f64>, m: MatRef<'_, f64>, part: &DofPartition) -> Result<()> {
    let n = part.n();
    check_square("stiffness matrix K", k, n)?;
    check_square("mass matrix M", m, n)?;
    check_finite("stiffness matrix K", k)?;
    check_finite("mass matrix M", m)?;
    Ok(())
}

/// `Ψ = [I 0; C Φk]` in natural row order (fixed rows zero); `coupling` = interior block of the
/// boundary columns, `phi` the interior rows of the modes, `kept` the mode indices taken.
pub(crate) fn assemble(
    part: &DofPartition, method: Method, coupling: Option<&Mat<f64>>, phi: Option<&Mat<f64>>,
    lam: &[f64], kept: &[usize],
) -> Basis {
    let b = part.boundary();
    let ii = part.interior();
    let nb = b.len();
    let nz = nb + kept.len();
    let mut psi = Mat::<f64>::zeros(part.n(), nz);
    let mut columns = Vec::with_capacity(nz);
    for (c, &d) in b.iter().enumerate() {
        psi[(d, c)] = 1.0;
        if let Some(cp) = coupling {
            for (r, &di) in ii.iter().enumerate() {
                psi[(di, c)] = cp[(r, c)];
            }
        }
        columns.push(Column::Boundary { dof: d });
    }
    if let Some(phi) = phi {
        for (j, &mi) in kept.iter().enumerate() {
            for (r, &di) in ii.iter().enumerate() {
                psi[(di, nb + j)] = phi[(r, mi)];
            }
            columns.push(Column::Mode {
                index: mi,
                eigenvalue: lam[mi],
            });
        }
    }
    Basis {
        method,
        psi,
        columns,
    }
}
