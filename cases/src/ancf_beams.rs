//! The static test set-ups of Kerkkänen §2.4 (Tables 2.1–2.4), shared by the validation tests
//! and the `flowmbd-beam` app.

use ancf::beam_mesh::{BeamElementKind, MAX_BEAM_ELEMENTS, beam_mesh};
use ancf::element::{AncfElement, OmarShabanaBeam, ProposedBeam};
use ancf::error::AncfError;
use ancf::material::Material;
use ancf::mesh::{AncfMesh, straight_coordinates};
use ancf::section::Section;
use ancf::statics::{AncfStaticOptions, solve_static};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// The typed input error of the ANCF crate for the field `item`.
pub(crate) fn invalid(item: impl Into<String>, reason: impl Into<String>) -> AncfError {
    AncfError::InvalidInput {
        item: item.into(),
        reason: reason.into(),
    }
}

/// A chapter-2 static beam (Kerkkänen §2.4): `E = 2.07·10¹¹ Pa`, `ρ = 7850 kg/m³`, `L = 2 m`,
/// width 0.1 m, `k_s = 5/6`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StaticBeamCase {
    /// Element type.
    pub element: BeamElementKind,
    /// Number of elements.
    pub elements: usize,
    /// Poisson's ratio \[-\].
    pub nu: f64,
    /// Section height (in-plane) \[m\].
    pub height: f64,
    /// Section width \[m\].
    pub width: f64,
    /// Beam length \[m\].
    pub length: f64,
    /// Young's modulus \[Pa\].
    pub young: f64,
    /// Density \[kg/m³\].
    pub density: f64,
    /// Load increments of the Newton solver.
    pub increments: usize,
}

impl StaticBeamCase {
    /// The thesis's data with the given element, mesh, `ν` and height.
    pub fn kerkkanen(element: BeamElementKind, elements: usize, nu: f64, height: f64) -> Self {
        Self {
            element,
            elements,
            nu,
            height,
            width: 0.1,
            length: 2.0,
            young: 2.07e11,
            density: 7850.0,
            increments: 1,
        }
    }

    fn material(&self) -> Result<Material, AncfError> {
        Material::new(self.young, self.nu, self.density)
    }

    fn section(&self) -> Result<Section, AncfError> {
        Section::rectangle(self.width, self.height)
    }
}

/// Most time steps `t_end / h` of a dynamic case (the pendulum's default takes 10⁴).
pub const MAX_TIME_STEPS: f64 = 1e8;

/// Most load increments of a static Newton solve.
pub const MAX_INCREMENTS: usize = 1_000_000;

/// `−1 < ν < 0.5` (positive definite isotropic elasticity).
pub(crate) fn check_poisson(nu: f64) -> Result<(), InvalidField> {
    if nu.is_finite() && nu > -1.0 && nu < 0.5 {
        Ok(())
    } else {
        Err(check::reject("nu", "in (-1, 0.5)", nu))
    }
}

/// `0 ≤ ρ∞ ≤ 1` (generalized-α spectral radius at infinity).
pub(crate) fn check_rho_inf(rho: f64) -> Result<(), InvalidField> {
    check::within("rho_inf", rho, 0.0, 1.0, "")
}

/// `1 ≤ elements ≤` [`MAX_BEAM_ELEMENTS`].
pub(crate) fn check_elements(n: usize) -> Result<(), InvalidField> {
    check::size("elements", n, 1, MAX_BEAM_ELEMENTS)
}

/// Smallest section dimension of a beam relative to its length: `10⁻⁶ L` (issue 35: a width
/// of `1e-300` m made the stiffness underflow against the load, and the deflection came back
/// as NaN).
pub const MIN_SECTION_RATIO: f64 = 1e-6;

/// Section dimensions `dims` (field, value \[m\]) of a beam of `length` \[m\] within
/// `[`[`MIN_SECTION_RATIO`]` L, L]`: a slender body, the assumption of the beam elements.
pub(crate) fn check_section(length: f64, dims: &[(&str, f64)]) -> Result<(), InvalidField> {
    for &(field, v) in dims {
        check::within(
            field,
            v,
            MIN_SECTION_RATIO * length,
            length,
            "m (a beam section between 1e-6 and 1 times its length)",
        )?;
    }
    Ok(())
}

/// Range of Young's modulus \[Pa\] of the beam cases: from soft foams (kPa) to diamond
/// (1.2·10¹² Pa) with margin (issue 35: `young = 1e-300` ran into a non-finite Newton
/// residual, exit 1, instead of an input error).
pub const YOUNG_RANGE: (f64, f64) = (1e3, 1e13);

/// Young's modulus within [`YOUNG_RANGE`].
pub(crate) fn check_young(young: f64) -> Result<(), InvalidField> {
    check::within("young", young, YOUNG_RANGE.0, YOUNG_RANGE.1, "Pa")
}

/// `t_end / h ≤` [`MAX_TIME_STEPS`] (both positive), `h ≤ t_end`.
pub(crate) fn check_time(t_end: f64, h: f64) -> Result<(), InvalidField> {
    check::positive("t_end", t_end, "s")?;
    check::positive("h", h, "s")?;
    check::step_fits("h", h, "t_end", t_end)?;
    let max = mbd_core::validate::limits::ceiling(MAX_TIME_STEPS);
    if t_end / h > max {
        return Err(InvalidField::new(
            "t_end",
            format!(
                "{} s in steps h = {} s is {:.3e} steps, more than the {max:e} a run may \
                 take{}",
                check::show(t_end),
                check::show(h),
                t_end / h,
                mbd_core::validate::limits::raise_hint()
            ),
        ));
    }
    Ok(())
}

/// Table 2.1's simply supported beam: 8 proposed elements, `ν = 0`, `h = 0.1 m` (the default
/// of `flowmbd-beam simply-supported`).
impl Default for StaticBeamCase {
    fn default() -> Self {
        Self::kerkkanen(BeamElementKind::Proposed, 8, 0.0, 0.1)
    }
}

impl mbd_core::config::PartialRules for StaticBeamCase {}

impl Validate for StaticBeamCase {
    /// `1 ≤ elements ≤` [`MAX_BEAM_ELEMENTS`], `1 ≤ increments ≤` [`MAX_INCREMENTS`],
    /// `−1 < ν < 0.5`, positive dimensions and modulus, non-negative density.
    fn validate(&self) -> Result<(), InvalidField> {
        check_elements(self.elements)?;
        check::size("increments", self.increments, 1, MAX_INCREMENTS)?;
        check_poisson(self.nu)?;
        check::positive("height", self.height, "m")?;
        check::positive("width", self.width, "m")?;
        check::positive("length", self.length, "m")?;
        check_section(
            self.length,
            &[("height", self.height), ("width", self.width)],
        )?;
        check_young(self.young)?;
        check::non_negative("density", self.density, "kg/m³")
    }
}

impl Validate for GroundContactCase {
    /// Element and increment counts as [`StaticBeamCase`], `−1 < ν < 0.5`, positive
    /// dimensions, modulus, gap and load factor.
    fn validate(&self) -> Result<(), InvalidField> {
        check_elements(self.elements)?;
        check::size("increments", self.increments, 1, MAX_INCREMENTS)?;
        for (f, v, unit) in [
            ("length", self.length, "m"),
            ("height", self.height, "m"),
            ("width", self.width, "m"),
            ("young", self.young, "Pa"),
            ("gap", self.gap, "m"),
            ("load_factor", self.load_factor, ""),
        ] {
            check::positive(f, v, unit)?;
        }
        check_section(
            self.length,
            &[("height", self.height), ("width", self.width)],
        )?;
        check_young(self.young)?;
        check_poisson(self.nu)
    }
}

/// Supports and load of a static study, expressed on a chain mesh.
trait Study {
    type Output;
    fn fixed<E: AncfElement>(&self, mesh: &AncfMesh<E>) -> Result<Vec<usize>, AncfError>;
    fn load<E: AncfElement>(&self, mesh: &AncfMesh<E>) -> Vec<f64>;
    fn output<E: AncfElement>(&self, mesh: &AncfMesh<E>, q: &[f64]) -> Self::Output;
}

fn run_study<S: Study>(case: &StaticBeamCase, study: &S) -> Result<S::Output, AncfError> {
    let (mat, sec) = (case.material()?, case.section()?);
    match case.element {
        BeamElementKind::Proposed => {
            let mesh = beam_mesh(case.length, case.elements, |l| {
                ProposedBeam::new(l, mat, sec)
            })?;
            solve_study(case, &mesh, study)
        }
        BeamElementKind::OmarShabana => {
            let mesh = beam_mesh(case.length, case.elements, |l| {
                OmarShabanaBeam::new(l, mat, sec)
            })?;
            solve_study(case, &mesh, study)
        }
    }
}

fn solve_study<E: AncfElement, S: Study>(
    case: &StaticBeamCase, mesh: &AncfMesh<E>, study: &S,
) -> Result<S::Output, AncfError> {
    let q0 = straight_coordinates(mesh.layout(), [0.0, 0.0], [case.length, 0.0], case.elements);
    let opts = AncfStaticOptions {
        increments: case.increments,
        ..Default::default()
    };
    let sol = solve_static(mesh, &q0, &study.fixed(mesh)?, &study.load(mesh), &opts)?;
    Ok(study.output(mesh, &sol.q))
}

/// Simply supported beam of Kerkkänen §2.4 (Tables 2.1, 2.2): first node pinned, last node
/// vertically supported, slopes free, vertical force `force` \[N\] at the mid-point node.
#[derive(Debug, Clone, Copy)]
pub struct SimplySupported {
    /// Vertical mid-point force \[N\] (−1000 N in the thesis).
    pub force: f64,
}

impl Study for SimplySupported {
    type Output = f64;
    fn fixed<E: AncfElement>(&self, mesh: &AncfMesh<E>) -> Result<Vec<usize>, AncfError> {
        let n_el = mesh.elements().len();
        if !n_el.is_multiple_of(2) {
            return Err(invalid(
                "elements",
                format!("must be even so that a node sits at mid-span, got {n_el}"),
            ));
        }
        Ok(vec![
            mesh.node_dof(0, 0),
            mesh.node_dof(0, 1),
            mesh.node_dof(n_el, 1),
        ])
    }
    fn load<E: AncfElement>(&self, mesh: &AncfMesh<E>) -> Vec<f64> {
        let mut f = vec![0.0; mesh.n_dof()];
        f[mesh.node_dof(mesh.elements().len() / 2, 1)] = self.force;
        f
    }
    fn output<E: AncfElement>(&self, mesh: &AncfMesh<E>, q: &[f64]) -> f64 {
        mesh.node_position(q, mesh.elements().len() / 2)[1]
    }
}

/// Large-deflection cantilever of Kerkkänen §2.4 (Tables 2.3, 2.4): clamp of the position and
/// of the cross-section slope `r_y` at the first node, and for the 12-DOF element also of the
/// axial slope `r_x = (1, 0)`; tip force `force` \[N\] in `y` at the centroid of the tip node.
///
/// The thesis only names "displacements and the slopes `∂r/∂y`" (the proposed element has no
/// `r_x`). For the Omar–Shabana element the seed note (§7.2, App. A) claims that a free `r_x`
/// reproduces Tables 2.3/2.4; it does not (Table 2.4 rows then differ by up to 1.0e-3 m, both in
/// this crate and in an independent numpy oracle), whereas the fully clamped node (`r`, `r_x`
/// and `r_y` fixed) reproduces every printed Omar–Shabana row of both tables to the printed
/// digits (`tests/tests/ancf_tables.rs`). We follow the printed tables, not the note.
#[derive(Debug, Clone, Copy)]
pub struct Cantilever {
    /// Vertical tip force \[N\] (`−5·10⁸ h³` in the thesis).
    pub force: f64,
}

impl Study for Cantilever {
    type Output = [f64; 2];
    fn fixed<E: AncfElement>(&self, mesh: &AncfMesh<E>) -> Result<Vec<usize>, AncfError> {
        // every nodal coordinate of the root node: r, (r_x,) r_y
        Ok((0..mesh.coords_per_node())
            .map(|k| mesh.node_dof(0, k))
            .collect())
    }
    fn load<E: AncfElement>(&self, mesh: &AncfMesh<E>) -> Vec<f64> {
        let mut f = vec![0.0; mesh.n_dof()];
        f[mesh.node_dof(mesh.elements().len(), 1)] = self.force;
        f
    }
    fn output<E: AncfElement>(&self, mesh: &AncfMesh<E>, q: &[f64]) -> [f64; 2] {
        mesh.node_position(q, mesh.elements().len())
    }
}

/// Mid-point vertical position \[m\] of the simply supported beam under −1000 N
/// (Kerkkänen Tables 2.1/2.2 print it in mm).
pub fn simply_supported_deflection(case: &StaticBeamCase) -> Result<f64, AncfError> {
    run_study(case, &SimplySupported { force: -1000.0 })
}

/// Tip position `(x, y)` \[m\] of the cantilever under the tip force `−5·10⁸ h³` N
/// (Kerkkänen Tables 2.3/2.4).
pub fn cantilever_tip(case: &StaticBeamCase) -> Result<[f64; 2], AncfError> {
    let force = -5.0e8 * case.height.powi(3);
    run_study(case, &Cantilever { force })
}

/// The cantilever's deformed centreline sampled at `per_element + 1` points per element \[m\].
#[derive(Debug, Clone, Copy)]
struct CantileverLine {
    force: f64,
    per_element: usize,
}

impl Study for CantileverLine {
    type Output = Vec<[f64; 2]>;
    fn fixed<E: AncfElement>(&self, mesh: &AncfMesh<E>) -> Result<Vec<usize>, AncfError> {
        Cantilever { force: self.force }.fixed(mesh)
    }
    fn load<E: AncfElement>(&self, mesh: &AncfMesh<E>) -> Vec<f64> {
        Cantilever { force: self.force }.load(mesh)
    }
    fn output<E: AncfElement>(&self, mesh: &AncfMesh<E>, q: &[f64]) -> Vec<[f64; 2]> {
        let mut pts = Vec::new();
        for (i, el) in mesh.elements().iter().enumerate() {
            let start = if i == 0 { 0 } else { 1 };
            for k in start..=self.per_element {
                let x = el.length() * k as f64 / self.per_element as f64;
                pts.push(mesh.position(q, i, x, 0.0));
            }
        }
        pts
    }
}

/// Deformed centreline of the cantilever of [`cantilever_tip`], `per_element` segments per
/// element (for plots and VTK output).
pub fn cantilever_centreline(
    case: &StaticBeamCase, per_element: usize,
) -> Result<Vec<[f64; 2]>, AncfError> {
    if per_element == 0 {
        return Err(invalid("per_element", "must be ≥ 1"));
    }
    let force = -5.0e8 * case.height.powi(3);
    run_study(case, &CantileverLine { force, per_element })
}

/// A slender cantilever under a uniform line load resting on rigid ground `y = −gap`
/// (frictionless unilateral Lagrange contact of every free node, [`ancf::solve_static_unilateral`]),
/// with the Euler–Bernoulli references: critical load `q* = 72 EI g₀/L⁴`; for `q ≤ q*` the tip
/// alone touches with `R = 3qL/8 − 3EI g₀/L³`; for `q > q*` the beam lies flat on `[a, L]`,
/// `a = (72 EI g₀/q)^{1/4}`, total contact force `qL − 2qa/3`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GroundContactCase {
    /// Element type.
    pub element: BeamElementKind,
    /// Number of elements.
    pub elements: usize,
    /// Beam length \[m\].
    pub length: f64,
    /// Section height \[m\].
    pub height: f64,
    /// Section width \[m\].
    pub width: f64,
    /// Young's modulus \[Pa\].
    pub young: f64,
    /// Poisson's ratio \[-\].
    pub nu: f64,
    /// Initial gap between the straight beam and the ground \[m\].
    pub gap: f64,
    /// Line load as a multiple of the critical load `q*` \[-\].
    pub load_factor: f64,
    /// Load increments.
    pub increments: usize,
}

impl mbd_core::config::PartialRules for GroundContactCase {}

impl Default for GroundContactCase {
    fn default() -> Self {
        Self {
            element: BeamElementKind::Proposed,
            elements: 64,
            length: 1.0,
            height: 0.01,
            width: 0.1,
            young: 2.07e11,
            nu: 0.0,
            gap: 1e-3,
            load_factor: 4.0,
            increments: 5,
        }
    }
}

/// Result of [`ground_contact`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroundContactResult {
    /// Line load `q` \[N/m\].
    pub line_load: f64,
    /// Euler–Bernoulli critical load `q*` \[N/m\].
    pub critical_load: f64,
    /// Deformed node positions \[m\] (root first).
    pub positions: Vec<[f64; 2]>,
    /// Contact force of every node \[N\] (0 at the clamp and at open nodes).
    pub forces: Vec<f64>,
    /// Sum of the contact forces \[N\].
    pub total_force: f64,
    /// Reference position `x` of the first node in contact \[m\].
    pub first_contact_x: Option<f64>,
    /// Euler–Bernoulli total contact force \[N\].
    pub euler_bernoulli_total_force: f64,
    /// Euler–Bernoulli start of the contact zone \[m\] (`L` when only the tip touches).
    pub euler_bernoulli_contact_start: f64,
}

/// Solve [`GroundContactCase`].
pub fn ground_contact(case: &GroundContactCase) -> Result<GroundContactResult, AncfError> {
    for (item, v) in [
        ("gap", case.gap),
        ("load_factor", case.load_factor),
        ("length", case.length),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(item, format!("must be > 0, got {v}")));
        }
    }
    let density = 7850.0;
    let mat = Material::new(case.young, case.nu, density)?;
    let sec = Section::rectangle(case.width, case.height)?;
    let (l, g0) = (case.length, case.gap);
    let ei = case.young * sec.i2;
    let q_star = 72.0 * ei * g0 / l.powi(4);
    let q = case.load_factor * q_star;
    let (total_eb, start_eb) = if q <= q_star {
        (3.0 * q * l / 8.0 - 3.0 * ei * g0 / l.powi(3), l)
    } else {
        let a = (72.0 * ei * g0 / q).powf(0.25);
        (q * l - 2.0 * q * a / 3.0, a)
    };
    let g_eff = [0.0, -q / (density * sec.area)];
    match case.element {
        BeamElementKind::Proposed => {
            let mesh = beam_mesh(l, case.elements, |le| ProposedBeam::new(le, mat, sec))?;
            solve_ground(case, &mesh, g_eff, q, q_star, total_eb, start_eb)
        }
        BeamElementKind::OmarShabana => {
            let mesh = beam_mesh(l, case.elements, |le| OmarShabanaBeam::new(le, mat, sec))?;
            solve_ground(case, &mesh, g_eff, q, q_star, total_eb, start_eb)
        }
    }
}

fn solve_ground<E: AncfElement>(
    case: &GroundContactCase, mesh: &AncfMesh<E>, g_eff: [f64; 2], q: f64, q_star: f64,
    total_eb: f64, start_eb: f64,
) -> Result<GroundContactResult, AncfError> {
    let n = case.elements;
    let q0 = straight_coordinates(mesh.layout(), [0.0, 0.0], [case.length, 0.0], n);
    let fixed: Vec<usize> = (0..mesh.coords_per_node())
        .map(|k| mesh.node_dof(0, k))
        .collect();
    let load = mesh.gravity_forces(g_eff);
    let nodes: Vec<usize> = (1..=n).collect();
    let opts = ancf::statics::UnilateralOptions {
        newton: AncfStaticOptions {
            increments: case.increments,
            ..Default::default()
        },
        ..Default::default()
    };
    let ground = contact::HalfPlane::ground(-case.gap);
    let sol =
        ancf::statics::solve_static_unilateral(mesh, &q0, &fixed, &load, &ground, &nodes, &opts)?;
    let le = case.length / n as f64;
    let mut forces = vec![0.0];
    forces.extend(&sol.multipliers);
    Ok(GroundContactResult {
        line_load: q,
        critical_load: q_star,
        positions: (0..=n).map(|i| mesh.node_position(&sol.q, i)).collect(),
        total_force: sol.total_force(),
        first_contact_x: (0..n)
            .find(|&c| sol.active[c])
            .map(|c| nodes[c] as f64 * le),
        forces,
        euler_bernoulli_total_force: total_eb,
        euler_bernoulli_contact_start: start_eb,
    })
}
