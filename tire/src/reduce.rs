//! The reduction of Ribaric §8.2 (recipe R4/R9 of the seed note):
//!
//! 1. contact nodes (c-nodes): the `n_c` candidate patch nodes nearest the road point θ = π;
//! 2. free-node modes `Ψ^f`: the lowest modes of `(K^ff, M^ff)` with contact and rim nodes fixed;
//! 3. contact-node modes `Ψ^c`: all modes of `(K^cc, M^cc)` with free and rim nodes fixed;
//! 4. static modes `Ψ_s = −(K^ff)⁻¹ K^fc` (condensation onto the contact nodes), `Ψ_s^c = Ψ_s Ψ^c`
//!    (7.11);
//!
//! steps 2 and 4 are the partitioned Craig–Bampton of the `reduction` crate
//! ([`reduction::sparse::craig_bampton_modes`]) with the rim as the fixed set, the contact DOFs
//! as the boundary and the free DOFs as the interior; then
//! 5. circumferential derivatives `T_,θ`, `T_,θθ` of every column, per Cartesian component
//!    along each ring (App. A; periodic grids of the flowing crate);
//! 6. projection onto the matrices of [`ReducedTire`].
//!
//! With all free-node modes kept, `T` spans every deflection with fixed rim, so the reduced model
//! reproduces the FE model exactly (eigenfrequencies and statics); with truncation the static
//! modes keep the statics under contact-node loads exact (Craig–Bampton, Ribaric §3.3).

use crate::error::{TireError, invalid, linalg};
use crate::mesh::{TireFe, node_angle};
use crate::reduced::{ReducedTire, TreadBasis, VizBasis};
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Accum, Mat, Par};
use fe_model::SparseEigenOptions;
use fe_model::sparse::{sparse_times_dense, submatrix};
use flowing::derivative::{DerivativeMethod, FdScheme, FlowLine, mode_shape_derivatives};
use mbd_core::validate::{InvalidField, Validate, check};
use reduction::DofPartition;
use reduction::sparse::{CraigBamptonOptions, craig_bampton_modes, fixed_interface_modes_sparse};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::time::Instant;

/// Reduction settings (Ribaric §8.2 defaults: 95 contact nodes, 50 free-node modes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ReductionConfig {
    /// Number of contact nodes `n_c` (95 in Ribaric §8.2, 252 in §8.4.2).
    pub contact_nodes: usize,
    /// Number of kept free-node modes `n_f` (50 in Ribaric §8.2); more than exist = all.
    pub free_modes: usize,
    /// Circumferential derivative operator (App. A). Default: finite differences (A.1) with the
    /// 3-point second difference on the periodic ring grids.
    pub derivative: DerivativeMethod,
    /// Tolerance grouping nodes into rings by `(ρ, y)` \[m\].
    pub ring_tolerance: f64,
    /// Circumferential stations per ring kept for visualising the whole deforming tire (rows
    /// of `T` at every ring's nodes at these stations, see [`super::reduced::VizBasis`]);
    /// 0 = none.
    pub viz_stations: usize,
}

impl Default for ReductionConfig {
    fn default() -> Self {
        Self {
            contact_nodes: 95,
            free_modes: 50,
            derivative: DerivativeMethod::FiniteDifference(FdScheme::default()),
            ring_tolerance: 1e-6,
            viz_stations: 16,
        }
    }
}

impl Validate for ReductionConfig {
    /// At least one contact node and one free-node mode (their upper bounds are the tire's
    /// candidate patch and mode count, checked by [`reduce`]), a positive ring tolerance.
    fn validate(&self) -> Result<(), InvalidField> {
        check::count("contact_nodes", self.contact_nodes, 1, usize::MAX)?;
        check::count("free_modes", self.free_modes, 1, usize::MAX)?;
        check::positive("ring_tolerance", self.ring_tolerance, "m")
    }
}

/// Wall-clock times of the reduction stages \[s\] (for the benchmark record).
#[derive(Debug, Clone, Default, Serialize)]
pub struct ReductionTimings {
    /// Free-node and contact-node eigen problems.
    pub modes_s: f64,
    /// Of which: the free-node modes' factorisation of `K^ff`, Lanczos iteration and Sturm
    /// check (0 when solved densely).
    pub modes_factor_s: f64,
    /// See [`ReductionTimings::modes_factor_s`].
    pub modes_lanczos_s: f64,
    /// See [`ReductionTimings::modes_factor_s`].
    pub modes_sturm_s: f64,
    /// Static modes (sparse Cholesky of `K^ff` and solves, computed alongside the free-node
    /// modes, so the two overlap) and their product with `Ψ^c`.
    pub static_modes_s: f64,
    /// Circumferential derivatives.
    pub derivatives_s: f64,
    /// Projections onto the reduced matrices.
    pub projection_s: f64,
    /// Total.
    pub total_s: f64,
}

/// DOF partition of the tire: free (f), contact (c) and rim DOFs.
#[derive(Debug, Clone)]
pub struct TirePartition {
    /// Contact nodes in c-order.
    pub contact_nodes: Vec<usize>,
    /// Free DOFs (ascending).
    pub f: Vec<usize>,
    /// Contact DOFs (3 per contact node, node order).
    pub c: Vec<usize>,
    /// Rim DOFs.
    pub rim: Vec<usize>,
}

/// The `n` candidate nodes nearest the road point θ = π (angular distance first, then `|y|`),
/// i.e. whole cross-section rows of the patch grown from its centre.
pub fn select_contact_nodes(fe: &TireFe, n: usize) -> Result<Vec<usize>, TireError> {
    if n == 0 || n > fe.candidates.len() {
        return Err(invalid(
            "contact_nodes",
            format!(
                "{n} requested but the candidate patch set has {} nodes",
                fe.candidates.len()
            ),
        ));
    }
    let key = |i: usize| {
        let d = (node_angle(&fe.nodes[i]) - PI).abs();
        ((d * 1e6).round() as i64, fe.nodes[i][1].abs())
    };
    let mut c = fe.candidates.clone();
    c.sort_by(|&a, &b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1)).then(a.cmp(&b))
    });
    c.truncate(n);
    Ok(c)
}

impl TirePartition {
    /// Partition for the given contact nodes.
    pub fn new(fe: &TireFe, contact_nodes: Vec<usize>) -> Self {
        let rim = fe.rim_mask();
        let mut is_c = vec![false; fe.n_nodes()];
        for &c in &contact_nodes {
            is_c[c] = true;
        }
        let mut f = Vec::new();
        let mut r = Vec::new();
        for i in 0..fe.n_nodes() {
            let d = [3 * i, 3 * i + 1, 3 * i + 2];
            if rim[i] {
                r.extend(d);
            } else if !is_c[i] {
                f.extend(d);
            }
        }
        let c = contact_nodes
            .iter()
            .flat_map(|&i| [3 * i, 3 * i + 1, 3 * i + 2])
            .collect();
        Self {
            contact_nodes,
            f,
            c,
            rim: r,
        }
    }

    /// The same split as a `reduction` partition: rim = fixed, contact = boundary (c-order),
    /// free = interior (ascending, equal to [`TirePartition::f`]).
    pub fn dof_partition(&self, n_dofs: usize) -> Result<DofPartition, TireError> {
        let p = DofPartition::new(n_dofs, &self.c, &self.rim)?;
        debug_assert_eq!(p.interior(), self.f.as_slice());
        Ok(p)
    }
}

fn diag_block(mass: &[f64], dofs: &[usize]) -> Mat<f64> {
    Mat::from_fn(dofs.len(), dofs.len(), |i, j| {
        if i == j { mass[dofs[i]] } else { 0.0 }
    })
}

/// The lumped mass as a sparse diagonal matrix.
fn sparse_mass(fe: &TireFe) -> Result<SparseColMat<usize, f64>, TireError> {
    let t: Vec<Triplet<usize, usize, f64>> = (fe.mass.iter().enumerate())
        .map(|(i, &m)| Triplet::new(i, i, m))
        .collect();
    SparseColMat::try_new_from_triplets(fe.n_dofs(), fe.n_dofs(), &t)
        .map_err(|e| linalg("lumped mass matrix", e))
}

/// Eigen-solver options of the tire: dense up to 1200 DOFs (the coarse test tires), sparse
/// shift-invert Lanczos with the Sturm check above.
fn eigen_options() -> SparseEigenOptions {
    SparseEigenOptions {
        dense_below: 1200,
        ..Default::default()
    }
}

/// Reduce the tire (Ribaric §8.2). Returns the reduced tire and the stage timings.
pub fn reduce(
    fe: &TireFe, cfg: &ReductionConfig,
) -> Result<(ReducedTire, ReductionTimings), TireError> {
    reduce_with(fe, cfg, Projection::Blocks)
}

/// How the reduced stiffness `Tᵀ K T` is formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Projection {
    /// From its analytic blocks (Lin (6.20)): `diag(Λ)` for the mass-normalised free-node
    /// modes, `Ψ^cᵀ K_G Ψ^c` with the Schur complement `K_G = K^cc + K^cf Ψ_s` for the
    /// static modes, zero coupling (`K^ff Ψ_s + K^fc = 0`); `K T` only at the rim rows.
    Blocks,
    /// The plain product `Tᵀ (K T)` (the reference of the block form in the tests).
    #[cfg_attr(not(test), allow(dead_code))]
    Plain,
}

fn reduce_with(
    fe: &TireFe, cfg: &ReductionConfig, projection: Projection,
) -> Result<(ReducedTire, ReductionTimings), TireError> {
    let t0 = Instant::now();
    fe.validate()?;
    cfg.validate()?;
    let contact = select_contact_nodes(fe, cfg.contact_nodes)?;
    let part = TirePartition::new(fe, contact.clone());
    let (nf_dofs, nc3) = (part.f.len(), part.c.len());
    if nf_dofs == 0 {
        return Err(invalid("contact_nodes", "leave no free nodes"));
    }
    let mut tim = ReductionTimings::default();

    // free-node modes and static modes (steps 2 and 4): the partitioned Craig-Bampton with the
    // rim fixed and the contact DOFs as boundary
    let m_sparse = sparse_mass(fe)?;
    let cb = craig_bampton_modes(
        fe.stiffness.as_ref(),
        m_sparse.as_ref(),
        &part.dof_partition(fe.n_dofs())?,
        &CraigBamptonOptions {
            n_modes: cfg.free_modes,
            eigen: eigen_options(),
        },
    )?;
    drop(m_sparse);
    let fmodes = cb.normal_modes;
    // contact-node modes (step 3)
    let ts = Instant::now();
    let k_cc = submatrix(fe.stiffness.as_ref(), &part.c, &part.c)?.to_dense();
    let cmodes = fe_model::dense_modes(k_cc.as_ref(), diag_block(&fe.mass, &part.c).as_ref(), nc3)?;
    tim.modes_s = cb.report.normal_modes_s + ts.elapsed().as_secs_f64();
    if let Some(e) = &cb.report.eigen {
        tim.modes_factor_s = e.seconds_factor;
        tim.modes_lanczos_s = e.seconds_lanczos;
        tim.modes_sturm_s = e.seconds_sturm;
    }
    let ts = Instant::now();
    let psi_sc = &cb.static_modes * &cmodes.vectors;
    // the static-mode block of Tᵀ K T (Lin (6.20)): Ψ^cᵀ K_G Ψ^c, K_G = K^cc + K^cf Ψ_s
    let k_static = {
        let k_cf = submatrix(fe.stiffness.as_ref(), &part.c, &part.f)?;
        let k_g = k_cc + sparse_times_dense(k_cf.as_ref(), cb.static_modes.as_ref());
        cmodes.vectors.transpose() * k_g * &cmodes.vectors
    };
    drop(cb.static_modes);
    tim.static_modes_s = cb.report.static_modes_s + ts.elapsed().as_secs_f64();

    // basis T on all DOFs (rim rows zero)
    let nfm = fmodes.values.len();
    let nz = nfm + nc3;
    let n = fe.n_dofs();
    let mut t = Mat::<f64>::zeros(n, nz);
    for (r, &d) in part.f.iter().enumerate() {
        for j in 0..nfm {
            t[(d, j)] = fmodes.vectors[(r, j)];
        }
        for j in 0..nc3 {
            t[(d, nfm + j)] = psi_sc[(r, j)];
        }
    }
    for (r, &d) in part.c.iter().enumerate() {
        for j in 0..nc3 {
            t[(d, nfm + j)] = cmodes.vectors[(r, j)];
        }
    }
    drop(psi_sc);

    // derivatives (step 5)
    let ts = Instant::now();
    let rings = fe.rings(cfg.ring_tolerance)?;
    let mut lines = Vec::with_capacity(3 * rings.len());
    for ring in &rings {
        let grid = ring.grid()?;
        lines.extend(FlowLine::per_component(&grid, &ring.nodes, 3)?);
    }
    let der = mode_shape_derivatives(&lines, cfg.derivative, t.as_ref())?;
    tim.derivatives_s = ts.elapsed().as_secs_f64();
    // visualisation rows: every ring at `viz_stations` equally spaced stations, closed
    // circumferential polylines
    let viz = (cfg.viz_stations > 0).then(|| {
        let (mut nodes, mut segs) = (Vec::new(), Vec::new());
        for ring in &rings {
            let len = ring.nodes.len();
            let ns = cfg.viz_stations.min(len);
            let first = nodes.len();
            for s in 0..ns {
                nodes.push(ring.nodes[s * len / ns]);
            }
            for s in 0..ns {
                segs.push([first + s, first + (s + 1) % ns]);
            }
        }
        VizBasis {
            rows: Mat::from_fn(3 * nodes.len(), nz, |i, j| t[(3 * nodes[i / 3] + i % 3, j)]),
            positions: nodes.iter().map(|&i| fe.nodes[i]).collect(),
            lines: segs,
            nodes,
        }
    });
    let tread = tread_basis(fe, &rings, &t);

    // projections (step 6)
    let ts = Instant::now();
    let mut mt = t.clone();
    for i in 0..n {
        let m = fe.mass[i];
        for j in 0..nz {
            mt[(i, j)] *= m;
        }
    }
    let mtt = mt.transpose();
    let sym =
        |a: Mat<f64>| Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    // The large dense products (n × nz by n × nz) run as two sequential tasks side by side
    // (coarse-grained: on a busy machine faer's fine-grained parallel products spent much of
    // their time waiting for each other). Tᵀ M T is symmetric: its lower triangle only (half
    // the product), mirrored.
    let product = |a: faer::MatRef<'_, f64>, b: faer::MatRef<'_, f64>| {
        let mut out = Mat::<f64>::zeros(a.nrows(), b.ncols());
        faer::linalg::matmul::matmul(out.as_mut(), Accum::Replace, a, b, 1.0, Par::Seq);
        out
    };
    let ((m_z, g1), (g2, ktd, k1)) = rayon::join(
        || {
            let mut low = Mat::<f64>::zeros(nz, nz);
            triangular::matmul(
                low.as_mut(),
                BlockStructure::TriangularLower,
                Accum::Replace,
                mtt,
                BlockStructure::Rectangular,
                t.as_ref(),
                BlockStructure::Rectangular,
                1.0,
                Par::Seq,
            );
            let m_z = Mat::from_fn(nz, nz, |i, j| low[(i.max(j), i.min(j))]);
            (m_z, product(mtt, der.d1.as_ref()))
        },
        || {
            let ktd = sparse_times_dense(fe.stiffness.as_ref(), der.d1.as_ref());
            let k1 = product(t.transpose(), ktd.as_ref());
            (product(mtt, der.d2.as_ref()), ktd, k1)
        },
    );
    let mut s_th = Mat::<f64>::zeros(n, 2);
    for (i, x) in fe.nodes.iter().enumerate() {
        // η = ŷ: η × s = (z, 0, −x); η × (η × s) = (−x, 0, −z)
        s_th[(3 * i, 0)] = x[2];
        s_th[(3 * i + 2, 0)] = -x[0];
        s_th[(3 * i, 1)] = -x[0];
        s_th[(3 * i + 2, 1)] = -x[2];
    }
    let ms = mtt * &s_th;
    // K T: all rows for the plain projection, only the rim's for the block form (the rim
    // reactions below)
    let rim_dofs: Vec<usize> = fe
        .rim
        .iter()
        .flat_map(|&r| [3 * r, 3 * r + 1, 3 * r + 2])
        .collect();
    let (kt_rows, k_z) = match projection {
        Projection::Plain => {
            let kt_full = sparse_times_dense(fe.stiffness.as_ref(), t.as_ref());
            let k_z = sym(t.transpose() * &kt_full);
            (
                Mat::from_fn(rim_dofs.len(), nz, |i, j| kt_full[(rim_dofs[i], j)]),
                k_z,
            )
        }
        Projection::Blocks => {
            let all: Vec<usize> = (0..n).collect();
            let k_rim = submatrix(fe.stiffness.as_ref(), &rim_dofs, &all)?;
            let mut k_z = Mat::<f64>::zeros(nz, nz);
            for (j, &l) in fmodes.values.iter().enumerate() {
                k_z[(j, j)] = l;
            }
            let ks = sym(k_static);
            for j in 0..nc3 {
                for i in 0..nc3 {
                    k_z[(nfm + i, nfm + j)] = ks[(i, j)];
                }
            }
            (sparse_times_dense(k_rim.as_ref(), t.as_ref()), k_z)
        }
    };
    // net force and moment on the rim: sums over the rim nodes of rows (3r, 3r+1, 3r+2),
    // `row(k, c, j)` the entry of the k-th rim node's DOF c
    let rim_sum = |row: &dyn Fn(usize, usize, usize) -> f64| {
        let mut f = Mat::<f64>::zeros(3, nz);
        let mut mo = Mat::<f64>::zeros(3, nz);
        for (k, &r) in fe.rim.iter().enumerate() {
            let s = fe.nodes[r];
            for j in 0..nz {
                let v = [row(k, 0, j), row(k, 1, j), row(k, 2, j)];
                for c in 0..3 {
                    f[(c, j)] += v[c];
                }
                mo[(0, j)] += s[1] * v[2] - s[2] * v[1];
                mo[(1, j)] += s[2] * v[0] - s[0] * v[2];
                mo[(2, j)] += s[0] * v[1] - s[1] * v[0];
            }
        }
        (f, mo)
    };
    let (kr, kt) = rim_sum(&|k, c, j| kt_rows[(3 * k + c, j)]);
    let (kr1, kt1) = rim_sum(&|k, c, j| ktd[(3 * fe.rim[k] + c, j)]);
    let tc = Mat::from_fn(nc3, nz, |i, j| t[(part.c[i], j)]);
    let tc_theta = Mat::from_fn(nc3, nz, |i, j| der.d1[(part.c[i], j)]);
    let tc_theta_upwind = upwind_rows(&rings, &part.c, t.as_ref())?;
    // translational momentum of the tire (non-rim nodes; the rim's rows of T and its
    // derivatives are zero): eᵀM T, eᵀM T_,θ, eᵀM T_,θθ per Cartesian direction e, and eᵀM s_,θ,
    // eᵀM s_,θθ of the rigid rotation
    let rim_nodes = fe.rim_mask();
    let momentum = |a: &Mat<f64>| {
        Mat::from_fn(3, a.ncols(), |c, j| {
            (0..n / 3)
                .filter(|&i| !rim_nodes[i])
                .map(|i| fe.mass[3 * i + c] * a[(3 * i + c, j)])
                .sum()
        })
    };
    let (p_e, p_e1, p_e2) = (momentum(&t), momentum(&der.d1), momentum(&der.d2));
    let p_s = momentum(&s_th);
    tim.projection_s = ts.elapsed().as_secs_f64();

    let rim = fe.rim_mask();
    let mut tire_mass = 0.0;
    let mut rim_mass = 0.0;
    let mut rim_j = 0.0;
    for (i, x) in fe.nodes.iter().enumerate() {
        let m = fe.mass[3 * i];
        if rim[i] {
            rim_mass += m;
            rim_j += m * (x[0] * x[0] + x[2] * x[2]);
        } else {
            tire_mass += m;
        }
    }
    let contact_positions: Vec<[f64; 3]> = contact.iter().map(|&i| fe.nodes[i]).collect();
    let outer_radius = contact_positions
        .iter()
        .map(|x| (x[0] * x[0] + x[2] * x[2]).sqrt())
        .fold(0.0, f64::max);
    tim.total_s = t0.elapsed().as_secs_f64();
    Ok((
        ReducedTire {
            n_free_modes: nfm,
            contact_nodes: contact,
            contact_positions,
            free_mode_hz: fmodes.frequencies_hz,
            contact_mode_hz: cmodes.frequencies_hz.clone(),
            tire_mass,
            rim_mass,
            rim_spin_inertia: rim_j,
            outer_radius,
            derivative: cfg.derivative,
            m: m_z,
            k: k_z,
            g1,
            g2,
            k1,
            m_theta: (0..nz).map(|j| ms[(j, 0)]).collect(),
            c_s: (0..nz).map(|j| ms[(j, 1)]).collect(),
            kr,
            kr1,
            kt,
            kt1,
            tc,
            tc_theta,
            tc_theta_upwind,
            p_e,
            p_e1,
            p_e2,
            p_s: [
                [p_s[(0, 0)], p_s[(1, 0)], p_s[(2, 0)]],
                [p_s[(0, 1)], p_s[(1, 1)], p_s[(2, 1)]],
            ],
            viz,
            tread,
            source: String::new(),
            code_version: crate::CODE_VERSION.to_string(),
        },
        tim,
    ))
}

/// The rows of `T` at the tread's crown ring (the candidate-patch ring of smallest `|y|`) and
/// its two edge rings (smallest and largest `y`), see [`TreadBasis`]; `None` when no ring holds
/// a candidate node.
fn tread_basis(fe: &TireFe, rings: &[super::mesh::Ring], t: &Mat<f64>) -> Option<TreadBasis> {
    let mut cand = vec![false; fe.n_nodes()];
    for &c in &fe.candidates {
        cand[c] = true;
    }
    let y = |r: &super::mesh::Ring| fe.nodes[r.nodes[0]][1];
    let tread: Vec<&super::mesh::Ring> = rings
        .iter()
        .filter(|r| r.nodes.iter().any(|&i| cand[i]))
        .collect();
    let pick = |key: &dyn Fn(&super::mesh::Ring) -> f64| {
        (0..tread.len()).min_by(|&a, &b| key(tread[a]).total_cmp(&key(tread[b])))
    };
    let mut chosen = vec![pick(&|r| y(r).abs())?, pick(&|r| y(r))?, pick(&|r| -y(r))?];
    chosen.sort_unstable();
    chosen.dedup();
    let (mut nodes, mut theta, mut ring) = (Vec::new(), Vec::new(), Vec::new());
    for (k, &c) in chosen.iter().enumerate() {
        nodes.extend(&tread[c].nodes);
        theta.extend(&tread[c].theta);
        ring.extend(std::iter::repeat_n(k, tread[c].nodes.len()));
    }
    Some(TreadBasis {
        rows: Mat::from_fn(3 * nodes.len(), t.ncols(), |i, j| {
            t[(3 * nodes[i / 3] + i % 3, j)]
        }),
        nodes,
        theta,
        ring,
    })
}

/// Eigenfrequencies of the full FE tire with the rim fixed, `K φ = ω² M φ` on all non-rim DOFs
/// \[Hz\] (the reference of the reduction tests): the fixed-interface modes of the partition
/// with the rim fixed and no boundary (dense up to 1200 DOFs, sparse shift-invert above).
pub fn full_frequencies_hz(fe: &TireFe, count: usize) -> Result<Vec<f64>, TireError> {
    let mask = fe.rim_mask();
    let rim: Vec<usize> = (0..fe.n_dofs()).filter(|d| mask[d / 3]).collect();
    let part = DofPartition::new(fe.n_dofs(), &[], &rim)?;
    let m = sparse_mass(fe)?;
    let (modes, _) = fixed_interface_modes_sparse(
        fe.stiffness.as_ref(),
        m.as_ref(),
        &part,
        count,
        &eigen_options(),
    )?;
    Ok(modes.frequencies_hz)
}

/// The one-sided (upwind) circumferential differences of the rows `dofs` of `t` along their
/// rings, for the material transport of the contact nodes' slip velocity, Ribaric (7.10)
/// (`v = … + Ω T_c,θ z`): `[0]` from each node's predecessor in θ,
/// `(T_j − T_{j−1})/(θ_j − θ_{j−1})` (upwind when the material flows towards increasing θ,
/// spin `Ω ≥ 0`), `[1]` towards its successor (`Ω < 0`) \[1/rad\].
///
/// Why not the derivative operator of `T_,θ` itself: the central difference (A.1) of a contact
/// node ignores the node, so a stick condition on `v` leaves the patch's even and odd nodes
/// decoupled (a zig-zag of the tangential displacement that sticks at zero central slip while
/// the nodes slide); the upwind difference couples each node to the one the material comes
/// from. First order in the node spacing; the rest of the model keeps the operator of
/// [`ReductionConfig::derivative`].
fn upwind_rows(
    rings: &[crate::mesh::Ring], dofs: &[usize], t: faer::MatRef<'_, f64>,
) -> Result<[Mat<f64>; 2], TireError> {
    // each node's ring and place on it
    let mut place = std::collections::HashMap::new();
    let mut grids = Vec::with_capacity(rings.len());
    for (r, ring) in rings.iter().enumerate() {
        for (j, &node) in ring.nodes.iter().enumerate() {
            place.insert(node, (r, j));
        }
        grids.push(ring.grid()?);
    }
    let nz = t.ncols();
    let mut out = [
        Mat::<f64>::zeros(dofs.len(), nz),
        Mat::<f64>::zeros(dofs.len(), nz),
    ];
    for (i, &d) in dofs.iter().enumerate() {
        let (node, comp) = (d / 3, d % 3);
        let &(r, j) = place.get(&node).ok_or_else(|| {
            invalid(
                "contact nodes",
                format!(
                    "contact node {node} lies on no circumferential ring (no transport derivative)"
                ),
            )
        })?;
        let nb = grids[r].neighbours(j);
        for (side, other) in [nb.left, nb.right].into_iter().enumerate() {
            let flowing::grid::Node::Value(k, s) = other else {
                return Err(invalid(
                    "contact nodes",
                    format!("the ring of contact node {node} has fewer than 3 nodes"),
                ));
            };
            let dk = 3 * rings[r].nodes[k] + comp;
            let h = nb.s - s;
            for c in 0..nz {
                out[side][(i, c)] = (t[(d, c)] - t[(dk, c)]) / h;
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{coarse_tire_config, generated_tire};

    /// The block form of `Tᵀ K T` (Lin (6.20): `diag(Λ)` for the mass-normalised free-node
    /// modes, the Schur complement on the static modes, no coupling) against the plain
    /// product `Tᵀ (K T)` on a coarse tire (second formulation): equal to round-off, and
    /// every other reduced matrix identical.
    #[test]
    fn block_stiffness_projection_matches_the_plain_product() {
        let fe = generated_tire(&coarse_tire_config(24, 8, 40.0)).unwrap();
        let cfg = ReductionConfig {
            contact_nodes: 12,
            free_modes: 20,
            ..Default::default()
        };
        let (b, _) = reduce_with(&fe, &cfg, Projection::Blocks).unwrap();
        let (p, _) = reduce_with(&fe, &cfg, Projection::Plain).unwrap();
        let scale = p.k.norm_max();
        assert!(scale > 0.0);
        let dk = (&b.k - &p.k).norm_max();
        assert!(dk <= 1e-10 * scale, "|ΔK| = {dk:e} of {scale:e}");
        // the coupling block is exactly zero in the block form, round-off in the plain one
        let nfm = b.n_free_modes;
        for i in 0..nfm {
            for j in nfm..b.k.ncols() {
                assert_eq!(b.k[(i, j)], 0.0);
                assert!(p.k[(i, j)].abs() <= 1e-10 * scale);
            }
        }
        for (x, y) in [(&b.m, &p.m), (&b.k1, &p.k1), (&b.kr, &p.kr), (&b.kt, &p.kt)] {
            assert_eq!(x, y);
        }
        for (x, y) in [(&b.kr1, &p.kr1), (&b.kt1, &p.kt1), (&b.g1, &p.g1)] {
            assert_eq!(x, y);
        }
    }
}
