//! Lin (2005) Appendix B: the 3-D 30-node slab (4 × 2 × 1 m, 8 brick elements), the reduction
//! set-ups of ch. 7.2 (Table 7-2) and the linearised gravity statics of simulation 1.
//!
//! The brick element is not specified by Lin (companion §16 item 8); fe-model's 8-node
//! trilinear hexahedron with full 2×2×2 Gauss integration is used (the companion's assumption),
//! with E = 0.2 MPa, ν = 0.33 and density 7.8 kg/m³ lumped ρV/8 per element corner, which
//! reproduces the nodal masses of Table B-1.

use faer::Mat;
use reduction::axes::{Axis, NodalFixedFrame, nodal_fixed_selection, remove_anchor_columns};
use reduction::basis::{Basis, Column, Method, ModeSelection, build_basis};
use reduction::error::{ReductionError, Result};
use reduction::linalg::{congruence, solve_general};
use reduction::partition::DofPartition;
use serde::{Deserialize, Serialize};

/// Young's modulus \[Pa\] (Appendix B).
pub const E: f64 = 0.2e6;
/// Poisson's ratio (Appendix B).
pub const NU: f64 = 0.33;
/// Density \[kg/m³\] implied by the total mass 62.4 kg of Table B-1.
pub const DENSITY: f64 = 7.8;
/// Standard gravity \[m/s²\] (Lin §3.2.2 footnote), acting in −z.
pub const G: f64 = 9.80665;

/// The Appendix B slab in Lin's node numbering (node j = 1..30 → DOFs 3(j−1)..3(j−1)+2).
#[derive(Debug, Clone)]
pub struct LinSlab {
    /// 90×90 stiffness \[N/m\].
    pub k: Mat<f64>,
    /// 90×90 lumped mass \[kg\].
    pub m: Mat<f64>,
    /// Node positions relative to node 16 (Appendix B frame) \[m\], 3 per node.
    pub s: Vec<f64>,
}

/// Position of 1-based Lin node `j` (Table B-1): `j ≤ 15` at z = 1 with k = j − 1, otherwise
/// z = 0 with k = j − 16; x = ⌊k/3⌋, y = k mod 3.
pub fn node_position(j: usize) -> [f64; 3] {
    let (k, z) = if j <= 15 { (j - 1, 1.0) } else { (j - 16, 0.0) };
    [(k / 3) as f64, (k % 3) as f64, z]
}

/// DOFs of 1-based Lin nodes.
pub fn node_dofs(nodes: &[usize]) -> Vec<usize> {
    nodes
        .iter()
        .flat_map(|&j| [3 * (j - 1), 3 * (j - 1) + 1, 3 * (j - 1) + 2])
        .collect()
}

/// Builds the slab from fe-model's hexahedral block, renumbered to Lin's node order.
pub fn appendix_b_slab() -> Result<LinSlab> {
    let material = fe_model::element::Elastic {
        young: E,
        poisson: NU,
        density: DENSITY,
    };
    let fe = fe_model::generate::hex_block(
        [4.0, 2.0, 1.0],
        [4, 2, 1],
        material,
        fe_model::element::Hex8Integration::Full,
        None,
        |p| p,
    )
    .map_err(|e| ReductionError::InvalidParameter {
        name: "Appendix B slab".into(),
        reason: e.to_string(),
    })?;
    let num = |what: &str| {
        let what = what.to_string();
        move |e: fe_model::FeError| ReductionError::Numerical {
            what: what.clone(),
            detail: e.to_string(),
        }
    };
    let kb = fe.stiffness().map_err(num("slab stiffness"))?.to_dense();
    let mb = fe
        .mass(fe_model::element::MassKind::Lumped)
        .map_err(num("slab mass"))?
        .to_dense();
    // block node (i, j, k) has index (k·3 + j)·5 + i
    let perm: Vec<usize> = (1..=30)
        .flat_map(|j| {
            let p = node_position(j);
            let b = (p[2] as usize * 3 + p[1] as usize) * 5 + p[0] as usize;
            [3 * b, 3 * b + 1, 3 * b + 2]
        })
        .collect();
    let k = Mat::from_fn(90, 90, |i, j| kb[(perm[i], perm[j])]);
    let m = Mat::from_fn(90, 90, |i, j| mb[(perm[i], perm[j])]);
    let s = (1..=30).flat_map(node_position).collect();
    Ok(LinSlab { k, m, s })
}

/// The five models compared in Lin ch. 7.2 (Table 7-2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum SlabMethod {
    /// No reduction (NR): all 90 nodal coordinates.
    NoReduction,
    /// Guyan (GR): boundary nodes 16, 18, 28, 30 plus 5 and 11.
    Guyan,
    /// Lin's "modal truncation" (MT): boundary DOFs + 6 fixed-interface modes, no static modes.
    FixedInterfaceModalTruncation,
    /// Craig–Bampton (CB): boundary nodes 16, 18, 28, 30 + 6 fixed-interface modes.
    CraigBampton,
    /// Mode condensation (MC): same set as CB.
    ModeCondensation,
}

impl SlabMethod {
    /// All five, in the order NR, GR, MT, CB, MC.
    pub const ALL: [SlabMethod; 5] = [
        SlabMethod::NoReduction,
        SlabMethod::Guyan,
        SlabMethod::FixedInterfaceModalTruncation,
        SlabMethod::CraigBampton,
        SlabMethod::ModeCondensation,
    ];

    /// Short label (NR, GR, MT, CB, MC).
    pub fn label(self) -> &'static str {
        match self {
            SlabMethod::NoReduction => "NR",
            SlabMethod::Guyan => "GR",
            SlabMethod::FixedInterfaceModalTruncation => "MT",
            SlabMethod::CraigBampton => "CB",
            SlabMethod::ModeCondensation => "MC",
        }
    }
}

/// The nodal-fixed frame of Lin Fig. 7-3: origin 16, ξ through 28, node 18 in the ξη plane.
pub fn nodal_fixed_frame() -> NodalFixedFrame {
    NodalFixedFrame {
        origin: 15,
        axis_node: 27,
        axis: Axis::Xi,
        plane_node: 17,
        plane_axis: Axis::Eta,
    }
}

/// Basis of `method` with the six anchored columns removed (Lin Table 7-2, third column):
/// 90×84 for NR, 90×12 otherwise; `n_modes` fixed-interface modes (Lin: 6).
pub fn slab_basis(slab: &LinSlab, method: SlabMethod, n_modes: usize) -> Result<Basis> {
    let anchors = nodal_fixed_frame().anchored_dofs(30)?;
    if method == SlabMethod::NoReduction {
        let psi = nodal_fixed_selection(90, &anchors)?;
        let columns = (0..90)
            .filter(|d| !anchors.contains(d))
            .map(|dof| Column::Boundary { dof })
            .collect();
        return Ok(Basis {
            method: Method::Guyan,
            psi,
            columns,
        });
    }
    let (nodes, m): (&[usize], Method) = match method {
        SlabMethod::Guyan => (&[16, 18, 28, 30, 5, 11], Method::Guyan),
        SlabMethod::FixedInterfaceModalTruncation => {
            (&[16, 18, 28, 30], Method::FixedInterfaceModalTruncation)
        }
        SlabMethod::CraigBampton => (&[16, 18, 28, 30], Method::CraigBampton),
        SlabMethod::ModeCondensation => (&[16, 18, 28, 30], Method::ModeCondensation),
        SlabMethod::NoReduction => unreachable!("handled above"),
    };
    let part = DofPartition::from_boundary_dofs(90, &node_dofs(nodes))?;
    let b = build_basis(
        slab.k.as_ref(),
        slab.m.as_ref(),
        &part,
        m,
        &ModeSelection::Lowest(n_modes),
    )?;
    remove_anchor_columns(&b, &anchors)
}

/// Linearised gravity statics of simulation 1 (Lin §7.2.2 supports: node 16 fixed, 18 in x,
/// 28 and 30 in z; nodal-fixed frame 16/28/18): the local deflection `δ'` of node 8 \[m\].
///
/// Unknowns: frame translation Δr, small rotation Δθ and the basis coordinates z; absolute
/// displacement `Δd = Ih Δr + (Δθ × s) + Ψ z`; minimise `½zᵀΨᵀKΨz − (Mĝ)ᵀΔd` subject to the six
/// support conditions (KKT solve).
pub fn sim1_statics(slab: &LinSlab, basis: &Basis) -> Result<[f64; 3]> {
    let p = reduction::axes::rigid_body_modes(&slab.s, 3)?;
    let psi = &basis.psi;
    let nz = psi.ncols();
    let nq = 6 + nz;
    let g = Mat::from_fn(
        90,
        nq,
        |i, j| if j < 6 { p[(i, j)] } else { psi[(i, j - 6)] },
    );
    let kr = congruence(psi.as_ref(), slab.k.as_ref(), psi.as_ref());
    let supports = [
        3 * 15,
        3 * 15 + 1,
        3 * 15 + 2,
        3 * 17,
        3 * 27 + 2,
        3 * 29 + 2,
    ];
    let nk = nq + supports.len();
    let mut a = Mat::<f64>::zeros(nk, nk);
    for i in 0..nz {
        for j in 0..nz {
            a[(6 + i, 6 + j)] = kr[(i, j)];
        }
    }
    for (r, &d) in supports.iter().enumerate() {
        for j in 0..nq {
            a[(nq + r, j)] = g[(d, j)];
            a[(j, nq + r)] = g[(d, j)];
        }
    }
    let mut rhs = Mat::<f64>::zeros(nk, 1);
    for i in 0..90 {
        if i % 3 == 2 {
            let fi = -G * slab.m[(i, i)];
            for j in 0..nq {
                rhs[(j, 0)] += g[(i, j)] * fi;
            }
        }
    }
    let x = solve_general("simulation-1 statics", a.as_ref(), rhs.as_ref())?;
    let node8 = 3 * 7;
    let mut d = [0.0; 3];
    for (c, dc) in d.iter_mut().enumerate() {
        *dc = (0..nz).map(|j| psi[(node8 + c, j)] * x[(6 + j, 0)]).sum();
    }
    Ok(d)
}
