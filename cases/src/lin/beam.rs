//! Lin (2005) Appendix A: the 2-D five-node beam, and the studies run on it (ch. 6.2 Guyan
//! models (a)/(b), ch. 6.3 fixed-interface modes, ch. 7.1 profile tests, ch. 6.6.4 Eitelberg,
//! ch. 8.5 mean axes with mode condensation).

use faer::Mat;
use reduction::basis::{Method, ModeSelection, build_basis, fixed_interface_modes};
use reduction::error::Result;
use reduction::linalg::{eig_to_hz, lstsq, select, solve_general, sym_gen_eig};
use reduction::mean_axes_eval::{MeanAxesEvaluation, evaluate_mean_axes};
use reduction::partition::DofPartition;
use serde::Serialize;

/// Young's modulus \[Pa\] ("30e5", Lin Appendix A).
pub const E: f64 = 3.0e6;
/// Cross-section area b·h \[m²\].
pub const AREA: f64 = 0.005;
/// Second moment of area \[m⁴\], the **rounded** value 1.0417e-6 printed by Lin (the printed K and
/// every frequency follow from it, Lin note §10).
pub const I_AREA: f64 = 1.0417e-6;
/// Element length \[m\] (4 elements over 1 m).
pub const LE: f64 = 0.25;
/// Lumped nodal masses \[kg\] (Lin Appendix A).
pub const NODE_MASS: [f64; 5] = [0.1, 0.2, 0.2, 0.2, 0.1];
/// Assumed deformation of the profile tests, DOF order ξ1, η1, …, ξ5, η5 (Lin (7.1)) \[m\].
pub const PROFILE_DELTA: [f64; 10] = [0.0, 0.0, 0.05, 0.26, 0.10, 0.22, 0.11, 0.04, 0.25, 0.0];

/// The Appendix A beam: condensed stiffness (θ removed by static condensation), lumped mass and
/// node positions (2 DOFs per node: ξ axial, η transverse).
#[derive(Debug, Clone)]
pub struct LinBeam {
    /// 10×10 stiffness \[N/m\], DOF order ξ1, η1, …, ξ5, η5.
    pub k: Mat<f64>,
    /// 10×10 diagonal mass \[kg\].
    pub m: Mat<f64>,
    /// Node positions (ξ, η) relative to node 1 \[m\] (Lin Table A-1).
    pub s: Vec<f64>,
}

/// Parameters of the Appendix A beam; `Default` is Lin's model.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct LinBeamConfig {
    /// Young's modulus E \[Pa\].
    pub young_modulus_pa: f64,
    /// Cross-section area A \[m²\].
    pub area_m2: f64,
    /// Second moment of area I \[m⁴\].
    pub second_moment_m4: f64,
    /// Beam length \[m\] (4 equal elements).
    pub length_m: f64,
    /// Lumped masses of the 5 nodes \[kg\].
    pub node_masses_kg: [f64; 5],
}

impl Default for LinBeamConfig {
    fn default() -> Self {
        Self {
            young_modulus_pa: E,
            area_m2: AREA,
            second_moment_m4: I_AREA,
            length_m: 4.0 * LE,
            node_masses_kg: NODE_MASS,
        }
    }
}

/// Builds the Appendix A beam: fe-model's straight planar frame (4 Euler–Bernoulli elements,
/// EA = E·A, EI = E·I with the rounded I) with (u, v, θ) per node; the rotations are removed by
/// static condensation (Guyan with the translations as masters, `K = K_tt − K_tθ K_θθ⁻¹ K_θt`),
/// as Lin did with the FElt model; lumped masses 0.1/0.2/0.2/0.2/0.1 kg.
pub fn appendix_a_beam() -> Result<LinBeam> {
    beam_from(&LinBeamConfig::default())
}

/// Range of the beam's squared slenderness `A L² / I` (axial over bending stiffness of the
/// whole beam; Lin's beam: 4.8·10³). Outside `[10⁻⁶, 10¹²]` the condensed stiffness matrix's
/// condition number nears `1/ε` and its eigen solution loses every digit (issue 35:
/// `length_m = 1e9` or `area_m2 = 1e-300` came back with fewer modes than DOFs and failed
/// an index check deep in the basis).
pub const SLENDERNESS_RANGE: (f64, f64) = (1e-6, 1e12);

impl mbd_core::config::PartialRules for LinBeamConfig {}

impl mbd_core::Validate for LinBeamConfig {
    /// Positive finite E, A, I, L and node masses; `A L² / I` within [`SLENDERNESS_RANGE`].
    fn validate(&self) -> std::result::Result<(), mbd_core::InvalidField> {
        use mbd_core::validate::check;
        check::positive("young_modulus_pa", self.young_modulus_pa, "Pa")?;
        check::positive("area_m2", self.area_m2, "m²")?;
        check::positive("second_moment_m4", self.second_moment_m4, "m⁴")?;
        check::positive("length_m", self.length_m, "m")?;
        for (i, m) in self.node_masses_kg.iter().enumerate() {
            check::positive(&format!("node_masses_kg[{i}]"), *m, "kg")?;
        }
        let ratio = self.area_m2 * self.length_m * self.length_m / self.second_moment_m4;
        let (lo, hi) = SLENDERNESS_RANGE;
        if !(lo..=hi).contains(&ratio) {
            // too slender: a long beam; too stocky: a tiny area (the message gives the ratio)
            let field = if ratio > hi { "length_m" } else { "area_m2" };
            return Err(mbd_core::InvalidField::new(
                field,
                format!(
                    "A L^2 / I = {} is outside [{}, {}] (axial against bending stiffness: \
                     the eigen solution would lose every digit)",
                    check::show(ratio),
                    check::show(lo),
                    check::show(hi)
                ),
            ));
        }
        Ok(())
    }
}

/// The Appendix A beam with other parameters (same topology: 5 nodes, 4 elements).
pub fn beam_from(p: &LinBeamConfig) -> Result<LinBeam> {
    mbd_core::Validate::validate(p).map_err(|e| reduction::ReductionError::InvalidParameter {
        name: e.field,
        reason: e.reason,
    })?;
    let nn = 5;
    for (name, v) in [
        ("young_modulus_pa", p.young_modulus_pa),
        ("area_m2", p.area_m2),
        ("second_moment_m4", p.second_moment_m4),
        ("length_m", p.length_m),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(reduction::ReductionError::InvalidParameter {
                name: name.into(),
                reason: format!("must be positive and finite, got {v}"),
            });
        }
    }
    if let Some(m) = p
        .node_masses_kg
        .iter()
        .find(|m| !(m.is_finite() && **m > 0.0))
    {
        return Err(reduction::ReductionError::InvalidParameter {
            name: "node_masses_kg".into(),
            reason: format!("every mass must be positive and finite, got {m}"),
        });
    }
    let section = fe_model::element::Frame2dSection {
        ea: p.young_modulus_pa * p.area_m2,
        ei: p.young_modulus_pa * p.second_moment_m4,
        mass_per_length: 0.0,
    };
    let fe = fe_model::generate::straight_beam_2d(p.length_m, 4, section, 0.0).map_err(|e| {
        reduction::ReductionError::InvalidParameter {
            name: "Appendix A beam".into(),
            reason: e.to_string(),
        }
    })?;
    let k15 = fe
        .stiffness()
        .map_err(|e| reduction::ReductionError::Numerical {
            what: "Appendix A beam assembly".into(),
            detail: e.to_string(),
        })?
        .to_dense();
    let t: Vec<usize> = (0..nn).flat_map(|j| [3 * j, 3 * j + 1]).collect();
    let part = DofPartition::from_boundary_dofs(3 * nn, &t)?;
    let psi_s = reduction::basis::static_modes(k15.as_ref(), &part)?;
    // K = K_tt + K_tθ Ψs (Lin (6.8))
    let ktq = select(k15.as_ref(), &t, part.interior());
    let k = select(k15.as_ref(), &t, &t) + &ktq * &psi_s;
    let k = reduction::linalg::symmetrize(&k);
    let m = Mat::from_fn(2 * nn, 2 * nn, |i, j| {
        if i == j { p.node_masses_kg[i / 2] } else { 0.0 }
    });
    let le = p.length_m / 4.0;
    let s = (0..nn).flat_map(|j| [le * j as f64, 0.0]).collect();
    Ok(LinBeam { k, m, s })
}

/// DOFs (ξ, η) of 1-based node numbers, as used by Lin.
pub fn node_dofs(nodes_1based: &[usize]) -> Vec<usize> {
    nodes_1based
        .iter()
        .flat_map(|&j| [2 * (j - 1), 2 * (j - 1) + 1])
        .collect()
}

/// The 10×10 basis of Lin (7.2): `{δo; δu} = [I 0; 0 Ψu]{δo; zu}` with `o = {ξ1, η1, η5}`
/// (simply supported beam) and `Ψu` the M-normalized modes of `eig(K_uu, M_uu)`, rows in natural
/// DOF order, columns z1..z3 = ξ1, η1, η5, then the 7 modes in ascending frequency.
pub fn simply_supported_basis(beam: &LinBeam) -> Result<Mat<f64>> {
    let o = [0usize, 1, 9];
    let u: Vec<usize> = (0..10).filter(|d| !o.contains(d)).collect();
    let kuu = select(beam.k.as_ref(), &u, &u);
    let muu = select(beam.m.as_ref(), &u, &u);
    let (_, psiu) = sym_gen_eig(
        "simply supported beam (K_uu, M_uu)",
        kuu.as_ref(),
        muu.as_ref(),
    )?;
    if psiu.ncols() < 7 {
        return Err(reduction::ReductionError::Numerical {
            what: "simply supported beam (K_uu, M_uu)".into(),
            detail: format!("{} of its 7 modes found", psiu.ncols()),
        });
    }
    let mut psi_ss = Mat::<f64>::zeros(10, 10);
    for (c, &d) in o.iter().enumerate() {
        psi_ss[(d, c)] = 1.0;
    }
    for (r, &d) in u.iter().enumerate() {
        for c in 0..7 {
            psi_ss[(d, 3 + c)] = psiu[(r, c)];
        }
    }
    Ok(psi_ss)
}

/// Results of the ch. 7.1 profile tests for one method.
#[derive(Debug, Clone, Serialize)]
pub struct ProfileResult {
    /// Reduced coordinates z* (boundary DOFs ξ1, η1, ξ5, η5, then the two kept modes).
    pub z: Vec<f64>,
    /// Reconstructed nodal deflections δ* (natural DOF order).
    pub delta: Vec<f64>,
    /// Euclidean error ‖δ* − δ‖₂ over all 10 DOFs.
    pub error: f64,
}

/// All ch. 7.1 results: for each of MT, CB, MC (in that order) profile 1 and profile 2.
#[derive(Debug, Clone, Serialize)]
pub struct ProfileStudy {
    /// Modal coordinates `z = Ψ⁻¹δ` of the simply supported basis (Lin (7.3)).
    pub z_simply_supported: Vec<f64>,
    /// Profile 1 (same z*, Lin §7.1.1): MT, CB, MC.
    pub profile1: Vec<ProfileResult>,
    /// Profile 2 (least-squares fit, Lin §7.1.2): MT, CB, MC.
    pub profile2: Vec<ProfileResult>,
    /// The three bases (10 × 6) MT, CB, MC, with the library's sign convention.
    pub bases: Vec<Vec<Vec<f64>>>,
}

/// The ch. 7.1 profile tests on the Appendix A beam (boundary nodes 1 and 5, two kept
/// fixed-interface modes = first and second bending).
pub fn profile_study(beam: &LinBeam) -> Result<ProfileStudy> {
    profile_study_with(beam, &PROFILE_DELTA)
}

/// The ch. 7.1 profile tests for an arbitrary assumed deformation `delta` (10 values, DOF order
/// ξ1, η1, …, ξ5, η5) \[m\].
pub fn profile_study_with(beam: &LinBeam, delta: &[f64; 10]) -> Result<ProfileStudy> {
    let delta = *delta;
    let part = DofPartition::from_boundary_dofs(10, &node_dofs(&[1, 5]))?;
    let kept = ModeSelection::Lowest(2);
    let methods = [
        Method::FixedInterfaceModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
    ];
    let bases: Vec<Mat<f64>> = methods
        .iter()
        .map(|&me| build_basis(beam.k.as_ref(), beam.m.as_ref(), &part, me, &kept).map(|b| b.psi))
        .collect::<Result<_>>()?;
    let psi_ss = simply_supported_basis(beam)?;
    let dcol = Mat::from_fn(10, 1, |i, _| delta[i]);
    let z = solve_general("simply supported basis Ψ", psi_ss.as_ref(), dcol.as_ref())?;
    // kept modal coordinates z4, z5; match the sign of the kept modes of the bases
    let part_i = part.interior();
    let mut zk = [z[(3, 0)], z[(4, 0)]];
    for (j, zkj) in zk.iter_mut().enumerate() {
        let dot: f64 = part_i
            .iter()
            .map(|&d| psi_ss[(d, 3 + j)] * bases[1][(d, 4 + j)])
            .sum();
        if dot < 0.0 {
            *zkj = -*zkj;
        }
    }
    let b = node_dofs(&[1, 5]);
    let zstar: Vec<f64> = b.iter().map(|&d| delta[d]).chain(zk).collect();
    let eval = |psi: &Mat<f64>, z: Vec<f64>| -> ProfileResult {
        let d: Vec<f64> = (0..10)
            .map(|i| (0..z.len()).map(|j| psi[(i, j)] * z[j]).sum())
            .collect();
        let error = d
            .iter()
            .zip(delta.iter())
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt();
        ProfileResult { z, delta: d, error }
    };
    let profile1 = bases.iter().map(|p| eval(p, zstar.clone())).collect();
    let profile2 = bases
        .iter()
        .map(|p| {
            let zls = lstsq(p.as_ref(), dcol.as_ref())?;
            Ok(eval(p, (0..p.ncols()).map(|j| zls[(j, 0)]).collect()))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(ProfileStudy {
        z_simply_supported: (0..10).map(|i| z[(i, 0)]).collect(),
        profile1,
        profile2,
        bases: bases
            .iter()
            .map(|p| {
                (0..p.nrows())
                    .map(|i| (0..p.ncols()).map(|j| p[(i, j)]).collect())
                    .collect()
            })
            .collect(),
    })
}

/// Natural frequencies \[Hz\] of the full beam, free-free, ascending (Lin §6.2.1).
pub fn free_free_hz(beam: &LinBeam) -> Result<Vec<f64>> {
    let (lam, _) = sym_gen_eig("free-free beam", beam.k.as_ref(), beam.m.as_ref())?;
    Ok(eig_to_hz(&lam))
}

/// Deformation frequencies \[Hz\] of a Guyan-reduced beam with the given 1-based master nodes
/// (the three rigid-body zeros dropped) (Lin §6.2.1 models (a) and (b)).
pub fn guyan_hz(beam: &LinBeam, masters_1based: &[usize]) -> Result<Vec<f64>> {
    let part = DofPartition::from_boundary_dofs(10, &node_dofs(masters_1based))?;
    let b = build_basis(
        beam.k.as_ref(),
        beam.m.as_ref(),
        &part,
        Method::Guyan,
        &ModeSelection::Lowest(0),
    )?;
    let red =
        reduction::reduced::ReducedModel::from_basis(b, beam.k.as_ref(), beam.m.as_ref(), None, 2)?;
    Ok(red.natural_frequencies_hz()?.into_iter().skip(3).collect())
}

/// Fixed-interface frequencies \[Hz\] with boundary nodes 1 and 5 (Lin §6.3, Fig. 6-7).
pub fn fixed_interface_hz(beam: &LinBeam) -> Result<Vec<f64>> {
    let part = DofPartition::from_boundary_dofs(10, &node_dofs(&[1, 5]))?;
    let (lam, _) = fixed_interface_modes(beam.k.as_ref(), beam.m.as_ref(), &part)?;
    Ok(eig_to_hz(&lam))
}

/// Node positions relative to the mass centre (Lin (8.39): ξ shifted by −0.5 m for Lin's beam).
pub fn mass_centre_positions(beam: &LinBeam) -> Vec<f64> {
    let m: Vec<f64> = (0..beam.s.len() / 2)
        .map(|j| beam.m[(2 * j, 2 * j)])
        .collect();
    let mt: f64 = m.iter().sum();
    let cx: f64 = (0..m.len()).map(|j| m[j] * beam.s[2 * j]).sum::<f64>() / mt;
    let cy: f64 = (0..m.len()).map(|j| m[j] * beam.s[2 * j + 1]).sum::<f64>() / mt;
    beam.s
        .iter()
        .enumerate()
        .map(|(i, &x)| if i % 2 == 0 { x - cx } else { x - cy })
        .collect()
}

/// Lin §8.5: mean axes with the mode-condensation (or another) basis, boundary nodes 1 and 5,
/// two kept modes; static (8.44) and eigen (8.45) evaluation.
pub fn mean_axes_study(beam: &LinBeam, method: Method) -> Result<MeanAxesEvaluation> {
    let b = node_dofs(&[1, 5]);
    let part = DofPartition::from_boundary_dofs(10, &b)?;
    let basis = build_basis(
        beam.k.as_ref(),
        beam.m.as_ref(),
        &part,
        method,
        &ModeSelection::Lowest(2),
    )?;
    evaluate_mean_axes(
        beam.k.as_ref(),
        beam.m.as_ref(),
        basis.psi.as_ref(),
        &mass_centre_positions(beam),
        2,
        &b,
    )
}

/// The summary printed by `flowmbd-reduce lin-beam --json`.
#[derive(Debug, Clone, Serialize)]
pub struct LinBeamSummary {
    /// Free-free frequencies of the full beam \[Hz\] (10, three rigid zeros first).
    pub free_free_hz: Vec<f64>,
    /// Guyan model (a), masters 1, 3, 5: deformation frequencies \[Hz\].
    pub guyan_a_hz: Vec<f64>,
    /// Guyan model (b), masters 1, 2, 5: deformation frequencies \[Hz\].
    pub guyan_b_hz: Vec<f64>,
    /// Fixed-interface frequencies, boundary nodes 1 and 5 \[Hz\].
    pub fixed_interface_hz: Vec<f64>,
    /// Profile 1 errors ‖δ* − δ‖: fixed-interface MT, CB, MC.
    pub profile1_errors: Vec<f64>,
    /// Profile 2 errors: fixed-interface MT, CB, MC.
    pub profile2_errors: Vec<f64>,
    /// Non-zero frequencies of the mean-axes eigenproblem (8.45) with mode condensation \[Hz\].
    pub mean_axes_normal_hz: Vec<f64>,
    /// What the numbers mean ([`LIN_BEAM_MEANING`]).
    pub meaning: String,
}

/// The `meaning` of the `lin-beam` summary.
pub const LIN_BEAM_MEANING: &str = "Lin ch. 6-8 on the Appendix A beam: the frequencies of the full model and of the \
     reduced models (Guyan, modal truncation, Craig-Bampton, mode condensation) compared \
     with Lin's tables, the deflection profiles of the profile tests [m] and the \
     mean-axis frame: how well each reduction reproduces the full model.";

/// Runs every beam study of Lin ch. 6-8 and collects the summary.
pub fn summary(beam: &LinBeam) -> Result<LinBeamSummary> {
    summary_with(beam, &PROFILE_DELTA)
}

/// [`summary`] with another assumed profile deformation.
pub fn summary_with(beam: &LinBeam, delta: &[f64; 10]) -> Result<LinBeamSummary> {
    let prof = profile_study_with(beam, delta)?;
    Ok(LinBeamSummary {
        free_free_hz: free_free_hz(beam)?,
        guyan_a_hz: guyan_hz(beam, &[1, 3, 5])?,
        guyan_b_hz: guyan_hz(beam, &[1, 2, 5])?,
        fixed_interface_hz: fixed_interface_hz(beam)?,
        profile1_errors: prof.profile1.iter().map(|p| p.error).collect(),
        profile2_errors: prof.profile2.iter().map(|p| p.error).collect(),
        mean_axes_normal_hz: mean_axes_study(beam, Method::ModeCondensation)?.normal_frequencies_hz,
        meaning: LIN_BEAM_MEANING.to_string(),
    })
}
