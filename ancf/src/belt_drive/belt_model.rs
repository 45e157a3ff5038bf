//! The ANCF belt (Kerkkänen ch. 3, [`crate::belt_drive`]) on any resolved drive
//! ([`belt::Drive`]): N pulleys speed-driven, loaded or idling, grooved or back side, the belt's
//! length given or mounted to the installation tension, an optional automatic tensioner
//! ([`belt::tensioner`]), meshed as a Lagrangian loop of ANCF belt elements — the
//! geometrically exact reference model of the belt studies.
//!
//! # Parameter mapping (drive → ANCF belt drive)
//!
//! | drive ([`belt::Drive`]) | ANCF ([`BeltDriveSpec`]) |
//! |---|---|
//! | pulleys at their mounted centres (a tensioner's idler at its hand-statics arm angle), belt-line radii `R` | the same pulleys with contact radius `R + p₀`, `p₀` the penalty penetration under the mounting pressure `T0/R` ([`belt::BeltContact::mounting_penetration`]), so that the belt centreline sinks by `p₀` onto the path of radius `R` |
//! | section EA, EI, ρA, material law | rectangular section of thickness `h = √(12 EI/EA)` and width `b` ([`AncfConfig::width`]); `E = EA/(b h)`, `ρ = ρA/(b h)`, `α₁ = α₂ = 1` (Kerkkänen (3.18)); the section's [`belt::MaterialLaw`] is the element's law ([`BeltSpec::law`]), so the reported and mounted forces are the axial force the elements carry ([`crate::BeltElement::axial_force`]) |
//! | installation tension `T0` | unstretched length `L_b = L_path/λ(T0)` ([`belt::Section::stretch`]), corrected by secant steps `L_b ← L_b (1 + (T̄ − T0)/EA)` until the mean static span force `T̄` of the ANCF belt ([`BeltDrive::initial_state`]) is `T0` within [`TENSION_TOLERANCE`], `T̄` the axial force of the belt's law; the first estimate lands a few per cent off: at rest the axial force on a wrap is the span's less `EI/(2R²)` (beam statics, 5.2 N on Table 6-1), and the contact pressure and penetration follow it; a given belt length is used as is |
//! | penalty (6.1) `k₂ d² + k₁ d` per unit length | the same law, distributed: `f_n = k₂ d² + k₁ d + c_p ḋ` (Kerkkänen (3.20) with the quadratic term), Gauss quadrature (3.27); `c_p` = [`AncfConfig::contact_damping`] |
//! | friction law of each pulley ([`belt::Drive::wrap_friction_law`]: `μ/sin(β/2)` on the grooved pulleys of a multi-ribbed belt) | the same law per unit length on that pulley ([`BeltDrive::with_pulley_friction`]; the spec's `contact.friction` is the contact's unscaled law) |
//! | Rayleigh `β` | Kelvin–Voigt damping of the axial strain rate, axial force `EA(ε + β ε̇)` ([`BeltSpec::axial_damping`]); the mass-proportional `α M` is dropped (on the absolute velocities of a Lagrangian mesh it would brake the moving belt); generalized-α's numerical damping damps the contact vibrations |
//! | tensioner | the arm a coordinate ([`BeltDrive::with_tensioner`]); its static angle re-solved with the ANCF belt (secant on the arm's moment balance to [`ARM_ANGLE_TOLERANCE`]) |
//!
//! Slip is measured against the surface speed `ω (R + p₀)` at the contact radius (Kerkkänen
//! (3.25)); a sticking belt sees a small negative slip `−ω p₀` on every pulley alike.

use super::model::Planar;
use super::{BeltDrive, BeltDriveSpec, BeltSpec, ContactSpec, InitialOptions, InitialState, post};
use crate::error::{AncfError, invalid};
use crate::mounted::{DriveKind, MountedBelt};
use belt::{Drive, ModelTraits, Snapshot};
use mbd_core::validate::{InvalidField, Validate, check};
use mbd_core::{MbdError, Workspace};
use serde::{Deserialize, Serialize};

/// Relative tolerance of the mounted mean span force against the target `T0` \[-\].
pub const TENSION_TOLERANCE: f64 = 1e-3;
/// Tolerance of the static arm angle \[rad\].
pub const ARM_ANGLE_TOLERANCE: f64 = 1e-7;
/// Most ANCF belt elements (sizes from input are bounded before anything is built).
pub const MAX_ELEMENTS: usize = 2000;

/// What the ANCF belt reports as the belt's force.
pub const ANCF_FORCE_MEASURE: &str = "axial force of the belt's material law (St Venant–Kirchhoff \
α₁EA λ(λ²−1)/2 with the bending–stretching coupling of Kerkkänen (3.18), or linear α₁EA(λ−1)) \
carried by the elements, with the Kelvin–Voigt viscous part; spans: mean over each span's middle half";

/// Discretisation choices of the ANCF belt that the drive does not fix.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct AncfConfig {
    /// Number of equal belt elements.
    pub elements: usize,
    /// Contact quadrature points per element.
    pub contact_points: usize,
    /// Section width `b` \[m\] (planar model: only `b h` and `b h³` matter, through EA and EI).
    pub width: f64,
    /// Penalty damping `c_p` \[N s/m²\] (default 0, as in (6.1)). A damped law is
    /// discontinuous where a quadrature point enters or leaves contact.
    pub contact_damping: f64,
    /// Generalized-α step \[s\] (replaces the procedure's step for this model).
    pub step: f64,
    /// Reuse tolerance of the elastic tangent \[-\] (`BeltDrive::with_tangent_refresh`); `0` (exact
    /// tangent) by default.
    pub tangent_refresh: f64,
}

impl Default for AncfConfig {
    /// 40 elements (30 mm on Table 6-1's 1.214 m belt, about five per wrap), 5 contact points,
    /// width 20 mm, no penalty damping, 0.1 ms steps, exact tangent.
    fn default() -> Self {
        Self {
            elements: 40,
            contact_points: 5,
            width: 0.02,
            contact_damping: 0.0,
            step: 1e-4,
            tangent_refresh: 0.0,
        }
    }
}

impl Validate for AncfConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        check::count("elements", self.elements, 8, MAX_ELEMENTS)?;
        check::count("contact_points", self.contact_points, 1, 20)?;
        check::within("width", self.width, 1e-5, 10.0, "m")?;
        check::within("step", self.step, 1e-9, 1.0, "s")?;
        check::non_negative("contact_damping", self.contact_damping, "N s/m²")?;
        check::non_negative("tangent_refresh", self.tangent_refresh, "")
    }
}

/// The derived quantities of the mapping (for reports).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AncfMapping {
    /// Penalty penetration under the mounting pressure `T0/R` of each pulley \[m\].
    pub penetration: Vec<f64>,
    /// Path length over the belt-line radii \[m\].
    pub path_length: f64,
    /// Unstretched belt length \[m\] (after the mounting correction).
    pub belt_length: f64,
    /// Mean static span force of the mounted belt \[N\].
    pub mounted_tension: f64,
    /// Section thickness \[m\].
    pub thickness: f64,
    /// Young's modulus \[Pa\].
    pub young: f64,
    /// Density \[kg/m³\].
    pub density: f64,
    /// Penalty damping \[N s/m²\].
    pub contact_damping: f64,
}

/// The ANCF belt model of a drive (module documentation): the shared shell
/// ([`crate::mounted::MountedBelt`]) around the planar [`BeltDrive`].
pub type AncfBelt = MountedBelt<BeltDrive>;

/// The ANCF belt-drive spec of `drive` (module documentation): pulleys at the mounted centres
/// with contact radii `R + p₀`, the belt at `L_path/λ(T0)` (or the given length), and the
/// mapping.
pub fn ancf_spec(drive: &Drive, s: &AncfConfig) -> Result<(BeltDriveSpec, AncfMapping), AncfError> {
    s.validate_within("ancf")?;
    crate::mounted::refuse_decouplers(drive, "ANCF")?;
    let b = drive.belt();
    let m = crate::mounted::MappedDrive::of(drive, s.width);
    let contact = drive.contact();
    let spec = BeltDriveSpec {
        pulleys: m.pulleys,
        belt: BeltSpec {
            length: drive.belt_length(),
            elements: s.elements,
            width: s.width,
            thickness: m.thickness,
            young: m.young,
            poisson: 0.3,
            density: m.density,
            shear_factor: 5.0 / 6.0,
            alpha1: 1.0,
            alpha2: 1.0,
            gauss_points: 5,
            axial_damping: drive.damping().beta,
            law: b.law,
        },
        contact: ContactSpec {
            stiffness: contact.penalty_linear,
            quadratic: contact.penalty_quadratic,
            damping: s.contact_damping,
            friction: contact.friction,
            points: s.contact_points,
        },
    };
    let mapping = AncfMapping {
        penetration: m.penetration,
        path_length: drive.path().length(),
        belt_length: drive.belt_length(),
        mounted_tension: f64::NAN,
        thickness: m.thickness,
        young: spec.belt.young,
        density: spec.belt.density,
        contact_damping: s.contact_damping,
    };
    Ok((spec, mapping))
}

/// Mean of the finite span forces \[N\].
fn mean_span_tension(drive: &BeltDrive, q: &[f64]) -> f64 {
    let t: Vec<f64> = post::span_tensions(drive, q)
        .into_iter()
        .filter(|t| t.is_finite())
        .collect();
    t.iter().sum::<f64>() / t.len().max(1) as f64
}

impl MountedBelt<BeltDrive> {
    /// Build and mount the ANCF belt of `drive` with the discretisation `s` (module
    /// documentation: belt length correction, then the tensioner's static arm angle).
    pub fn new(drive: &Drive, s: &AncfConfig) -> Result<Self, AncfError> {
        let (mut spec, mut mapping) = ancf_spec(drive, s)?;
        let tensioner = drive.arm().map(|a| a.tensioner);
        let build = |spec: &BeltDriveSpec| -> Result<BeltDrive, AncfError> {
            let d = match tensioner {
                Some(t) => BeltDrive::with_tensioner(spec.clone(), t)?,
                None => BeltDrive::new(spec.clone())?,
            };
            d.with_tangent_refresh(s.tangent_refresh)
                .with_pulley_friction(drive.wrap_friction_laws())
        };
        let opts = InitialOptions::default();
        let t0 = drive.tension();
        let ea = drive.belt().ea;
        let mut belt = build(&spec)?;
        let mut init = belt.initial_state(&opts)?;
        if drive.layout().belt_length.is_none() {
            for _ in 0..8 {
                let t = mean_span_tension(&belt, &init.q);
                if !t.is_finite() || (t - t0).abs() <= TENSION_TOLERANCE * t0 {
                    break;
                }
                spec.belt.length *= 1.0 + (t - t0) / ea;
                belt = build(&spec)?;
                init = belt.initial_state(&opts)?;
            }
        }
        if let Some(a) = belt.arm().copied() {
            // secant on the arm's static moment balance, the belt re-solved at each angle
            let residual = |q: &[f64]| -> f64 {
                let n = q.len();
                let mut f = vec![0.0; n];
                let omegas = vec![0.0; belt.pulleys().len()];
                belt.forces_with(
                    0.0,
                    q,
                    &vec![0.0; n],
                    &omegas,
                    &omegas,
                    &mut f,
                    &mut Workspace::new(),
                );
                f[a.dof]
            };
            let (th0, g0) = (init.q[a.dof], residual(&init.q));
            // first trial: the spring's stiffness alone as the slope
            let converged = mbd_core::roots::secant(
                |th| {
                    let mut q = init.q.clone();
                    q[a.dof] = th;
                    init = belt.initial_state_from(q, &opts)?;
                    Ok::<f64, AncfError>(residual(&init.q))
                },
                th0,
                g0,
                th0 + g0 / a.spec.stiffness,
                mbd_core::roots::SecantStop {
                    max_iterations: 40,
                    step: ARM_ANGLE_TOLERANCE,
                },
            )?
            .converged;
            if !converged || !a.spec.within_travel(init.q[a.dof]) {
                return Err(invalid(
                    "tensioner",
                    format!(
                        "outside its travel: the ANCF belt's arm of pulley '{}' finds no static angle in [{:.3}, {:.3}] rad (last {:.4} rad)",
                        drive.pulleys()[a.spec.pulley].name,
                        a.spec.travel[0],
                        a.spec.travel[1],
                        init.q[a.dof]
                    ),
                ));
            }
        }
        mapping.belt_length = spec.belt.length;
        mapping.mounted_tension = mean_span_tension(&belt, &init.q);
        Ok(Self::from_parts(belt, drive, init, mapping))
    }
}

/// Coordinates: the belt nodes (Kerkkänen (3.1)), the free pulleys' angles and the tensioner
/// arm angle.
impl DriveKind for Planar {
    type Belt = BeltSpec;
    type Contact = ContactSpec;
    type Initial = InitialState;
    type Mapping = AncfMapping;
    const NAME: &'static str = "BeltDrive";
    /// Not linearised (the ANCF belt is geometrically exact, Kerkkänen (3.18)).
    const TRAITS: ModelTraits = ModelTraits {
        name: "ancf",
        linearised: false,
        force_measure: ANCF_FORCE_MEASURE,
        near_coulomb_creep: true,
        balance_defect: None,
    };

    fn elements(&self) -> usize {
        self.mesh.elements().len()
    }

    fn belt_coordinates(&self) -> usize {
        self.mesh.n_dof()
    }

    /// The 12 coordinates of each element (Kerkkänen (3.1)).
    fn element_dofs(&self) -> Vec<Vec<Option<usize>>> {
        (0..self.elements())
            .map(|e| (0..12).map(|k| Some(self.mesh.global_dof(e, k))).collect())
            .collect()
    }

    fn element_mass(&self, e: usize) -> Vec<f64> {
        self.mesh.element_mass(e).to_vec()
    }

    fn initial_q(initial: &InitialState) -> &[f64] {
        &initial.q
    }

    fn arm_angle_at(d: &BeltDrive, q: &[f64]) -> Option<f64> {
        d.arm().map(|a| q[a.dof])
    }

    /// The mean material speed along the centreline ([`post::belt_speed`]).
    fn mean_belt_speed(d: &BeltDrive, q: &[f64], v: &[f64]) -> f64 {
        post::belt_speed(d, q, v)
    }

    /// [`post::snapshot`] of the drive's state.
    fn snapshot_at(d: &BeltDrive, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        Ok(post::snapshot(d, t, q, v, &d.speeds(t, v)))
    }

    /// [`post::snapshot_with`] without the wrap points' section-force recovery.
    fn report_snapshot_at(
        d: &BeltDrive, t: f64, q: &[f64], v: &[f64],
    ) -> Result<Snapshot, MbdError> {
        Ok(post::snapshot_with(d, t, q, v, &d.speeds(t, v), false))
    }

    fn span_offsets(d: &BeltDrive, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        Ok(post::span_transverse(d, q))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use belt::{Layout, MaterialLaw, Section};

    // Issue 34 item 1 (reference: the laws' definitions, belt::MaterialLaw::force): the layout's
    // law reaches the elements, the span forces the model reports are that law's force at the
    // element's stretch (linear: EA(λ − 1) exactly; St Venant–Kirchhoff: EA λ(λ² − 1)/2 plus the
    // bending–stretching coupling, negligible in a straight span), and the belt is mounted to
    // T0 in that force (Table 6-1's drive, T0 = 310 N).
    #[test]
    fn the_layouts_material_law_is_the_elements_and_the_mounted_force() {
        for law in [MaterialLaw::Linear, MaterialLaw::StVenantKirchhoff] {
            let section = Section {
                law,
                ..Section::default()
            };
            let drive = Layout {
                belt: section,
                ..Layout::table_6_1()
            }
            .resolve()
            .unwrap();
            let m = AncfBelt::new(&drive, &AncfConfig::default()).unwrap();
            assert_eq!(m.belt_drive().spec().belt.law, law);
            let t = m.mapping().mounted_tension;
            assert!(
                (t - 310.0).abs() <= TENSION_TOLERANCE * 310.0,
                "{law:?}: {t} N"
            );
            // the element's axial force at mid-span points against the law at its stretch
            let q = &m.initial().q;
            let spans = m.belt_drive().path().spans();
            let mut checked = 0;
            for el in 0..m.belt_drive().mesh().elements().len() {
                let s = post::tension_at(m.belt_drive(), q, el, 0.5);
                if belt::BeltPath::span_middle_of(&spans, s.position).is_none() {
                    continue;
                }
                let (n, _) = law.force(section.ea, 1.0 + s.strain);
                assert!(
                    (s.tension - n).abs() < 5e-4 * n,
                    "{law:?}: {} vs {n}",
                    s.tension
                );
                checked += 1;
            }
            assert!(checked > 4);
        }
    }
}
