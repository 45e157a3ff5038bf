//! The belt drive as one [`SecondOrderSystem`]: ANCF belt coordinates followed by the rotation
//! angles of the free pulleys, coupled through distributed penalty contact with friction
//! (Kerkkänen (3.20)–(3.27)) and the pulley equations (3.26).

use super::friction::{BeltFriction, BeltNormal};
use super::spec::BeltDriveSpec;
use crate::element::{AncfElement, BeltElement};
use crate::error::{AncfError, invalid};
use crate::material::Material;
use crate::mesh::AncfMesh;
use crate::mounted::{AncfBeltDrive, PulleyCoordinates};
use crate::section::Section;
use crate::shape;
use crate::sparse::Pattern;
use belt::tensioner::cross;
use belt::{BeltPath, Tensioner};
use contact::{ContactRecord, Disk, ElementContact, GaussRule, LineContact};
use mbd_core::Workspace;
use mbd_core::system::ForceTangent;
use mbd_core::validate::Validate;
use mbd_core::{SecondOrderSystem, SysMatrix};
use nalgebra::{Point2, Vector2};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Coordinates of one element.
const NE: usize = 12;

/// The element coordinates of the centreline blocks (`r` and `r_x` of both nodes), the rows
/// and columns of the axial damping's local Jacobians that `element_damping` fills (`S_x` of
/// the slope blocks `r_y` vanishes on `y = 0`).
const CENTRE_COORDS: [usize; 8] = [0, 1, 2, 3, 6, 7, 8, 9];

/// Work buffers (kept so that the force and tangent loops do not allocate) and the elastic
/// tangent reused by [`BeltDrive::with_tangent_refresh`], in the caller's [`Workspace`] (see
/// [`BeltDrive::scratch`]).
struct Scratch {
    contact: ElementContact<2>,
    /// The active points' records of the last element–pulley pair of a pass that asked for
    /// them ([`BeltDrive::contact_pass`]).
    records: Vec<ContactRecord<2>>,
    /// The pulleys' disks of the current contact pass ([`BeltDrive::contact_pass`]).
    disks: Vec<Disk>,
    /// The transition-aware limit's slip velocities at the iterate, one per element, pulley
    /// and contact point (NaN: not in contact), and the corrected state `(q + Δq, v + Δv)`
    /// ([`SecondOrderSystem::correction_limit`]).
    slips: Vec<f64>,
    q1: Vec<f64>,
    v1: Vec<f64>,
    k_local: Vec<f64>,
    c_local: Vec<f64>,
    elastic: ElasticCache,
}

/// A planar belt drive (see the module documentation of [`super`]).
///
/// Coordinates: `q = [e; θ]`, `e` the belt's nodal coordinates (6 per node, closed loop with a
/// shared first node, Kerkkänen §2.3 option (b)), `θ` the travel-sense rotation angles of the
/// free pulleys in pulley order. The equations are `M ë = Q_e + Q_c` (2.27) with the contact
/// forces (3.27), and `I θ̈ = s τ − T_a(t)` for each free pulley, with `τ` the counter-clockwise
/// contact torque (3.26), `s = ±1` the travel-sense sign of the pulley
/// ([`belt::Pulley::ccw_sign`]) and `T_a` the load, which opposes the travel-sense rotation.
pub type BeltDrive = AncfBeltDrive<Planar>;

/// The planar discretisation of an [`AncfBeltDrive`] ([`BeltDrive`]): ANCF belt elements
/// (Kerkkänen §3.1) in a closed loop, the distributed contact on the pulleys' disks and the
/// optional tensioner arm.
pub struct Planar {
    pub(super) mesh: AncfMesh<BeltElement>,
    line: LineContact<Disk, BeltNormal, BeltFriction>,
    /// The friction law on each pulley, travel order (the spec's law on every pulley unless
    /// [`BeltDrive::with_pulley_friction`] set them; `line.friction` is the spec's law).
    friction: Vec<BeltFriction>,
    tangent_refresh: f64,
    /// Elastic tangent evaluations so far, over all workspaces (a statistic).
    elastic_evaluations: AtomicUsize,
    /// The tensioner arm, if any ([`BeltDrive::with_tensioner`]).
    arm: Option<BeltArm>,
    /// The axial damping's Gauss rule along an element (`belt.gauss_points`): weight and the
    /// cubic shape functions' `x` derivatives at each point (constant: built once).
    damping_points: Vec<(f64, [f64; 6])>,
}

/// A tensioner arm of a belt drive ([`BeltDrive::with_tensioner`], [`belt::tensioner`]):
/// its idler's centre is `c(θ) = p + L (cos θ, sin θ)` with the arm angle `θ` \[rad\] a
/// coordinate of the system, after the free pulleys' angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeltArm {
    /// The tensioner (spring, damper, dry friction, travel; `spec.pulley` is the idler).
    pub spec: Tensioner,
    /// Arm length `L` \[m\].
    pub length: f64,
    /// Arm angle of the installed idler centre (the spec's pulley centre) \[rad\].
    pub installed_angle: f64,
    /// Coordinate index of the arm angle.
    pub dof: usize,
}

/// The last elastic tangent and the coordinates it was evaluated at.
struct ElasticCache {
    q: Vec<f64>,
    k: Vec<f64>,
    valid: bool,
}

impl BeltDrive {
    /// Build the drive: validate `spec`, compute the open-belt path over the pulleys, mesh the
    /// belt with `belt.elements` equal straight elements of length `belt.length / n`, and set up
    /// the sparse pattern (element blocks and element–pulley coupling blocks) and the constant
    /// mass matrix (2.26) plus the pulley inertias.
    pub fn new(spec: BeltDriveSpec) -> Result<Self, AncfError> {
        Self::build(spec, None)
    }

    /// [`BeltDrive::new`] with an automatic tensioner (issue 17): pulley `tensioner.pulley`
    /// (free, an idler) rides on a pivoted arm whose angle `θ` \[rad\] is one more
    /// coordinate (the last), with the equation (counter-clockwise moments, [`belt::tensioner`])
    ///
    /// `J θ̈ = (c − p) × F_hub + M_s(θ) + M_d(θ̇) + M_f(θ̇)`,
    ///
    /// `F_hub` the resultant of the idler's contact forces (Kerkkänen (3.27) on a disk whose
    /// centre moves: the relative velocity (3.25) includes `ċ = c'(θ) θ̇`). The arm length and
    /// the installed angle follow from the idler's centre in `spec` and the pivot; the belt is
    /// placed on the path through that centre ([`BeltDrive::placed_coordinates`] starts the
    /// arm at the installed angle). The dry friction is the contact crate's law
    /// ([`Tensioner::dry_friction`]).
    pub fn with_tensioner(spec: BeltDriveSpec, tensioner: Tensioner) -> Result<Self, AncfError> {
        Self::build(spec, Some(tensioner))
    }

    fn build(spec: BeltDriveSpec, tensioner: Option<Tensioner>) -> Result<Self, AncfError> {
        spec.validate()?;
        if let Some(t) = &tensioner {
            t.validate_within("tensioner")?;
            match spec.pulleys.get(t.pulley) {
                Some(p) if p.is_free() => {}
                Some(p) => {
                    return Err(invalid(
                        "tensioner.pulley",
                        format!(
                            "the tensioner's idler \"{}\" must be free (not speed-driven)",
                            p.name
                        ),
                    ));
                }
                None => {
                    return Err(invalid(
                        "tensioner.pulley",
                        format!(
                            "no pulley {} (the drive has {})",
                            t.pulley,
                            spec.pulleys.len()
                        ),
                    ));
                }
            }
        }
        let path = BeltPath::new(&spec.pulleys)?;
        let lp = path.length();
        let lb = spec.belt.length;
        if !(0.9 * lp..=1.1 * lp).contains(&lb) {
            return Err(invalid(
                "belt.length",
                format!(
                    "{lb} m is not within 10 % of the belt path length {lp:.6} m over the pulleys"
                ),
            ));
        }
        let b = &spec.belt;
        let material = Material {
            young: b.young,
            poisson: b.poisson,
            density: b.density,
            shear_factor: b.shear_factor,
        };
        let section = Section::rectangle(b.width, b.thickness)?;
        let l = b.length / b.elements as f64;
        let el = BeltElement::new(l, material, section, b.alpha1, b.alpha2, b.gauss_points)?
            .with_law(b.law);
        let mesh = AncfMesh::closed_loop(vec![el; b.elements])?;
        let n_belt = mesh.n_dof();
        let n_free = PulleyCoordinates::new(&spec.pulleys, n_belt).count();
        let arm = tensioner.map(|t| {
            let (length, installed_angle) = t.arm(spec.pulleys[t.pulley].center);
            BeltArm {
                spec: t,
                length,
                installed_angle,
                dof: n_belt + n_free,
            }
        });
        let line = LineContact {
            surface: Disk::fixed(Point2::origin(), 1.0),
            normal: spec.contact.normal_law(),
            friction: spec.contact.friction,
            rule: GaussRule::new(spec.contact.points),
        };
        let arm_inertia: Vec<f64> = arm.iter().map(|a| a.spec.inertia).collect();
        let damping_points = GaussRule::new(b.gauss_points)
            .iter()
            .map(|(xi, w)| (w, shape::cubic(l, xi * l, 0.0).sx))
            .collect();
        let kind = Planar {
            damping_points,
            mesh,
            friction: vec![spec.contact.friction; spec.pulleys.len()],
            line,
            tangent_refresh: 0.02,
            elastic_evaluations: AtomicUsize::new(0),
            arm,
        };
        Ok(Self::assemble(spec, path, kind, &arm_inertia))
    }

    /// The belt mesh.
    pub fn mesh(&self) -> &AncfMesh<BeltElement> {
        &self.kind.mesh
    }
    /// The tensioner arm, if any ([`BeltDrive::with_tensioner`]).
    pub fn arm(&self) -> Option<&BeltArm> {
        self.kind.arm.as_ref()
    }

    /// Centre \[m\] and centre velocity \[m/s\] of pulley `p` at `(q, v)`: the spec's centre at
    /// rest, or for the tensioner's idler `c(θ)` and `c'(θ) θ̇` ([`belt::tensioner`]).
    pub fn pulley_center(&self, p: usize, q: &[f64], v: &[f64]) -> ([f64; 2], [f64; 2]) {
        match &self.kind.arm {
            Some(a) if a.spec.pulley == p => {
                let th = q.get(a.dof).copied().unwrap_or(a.installed_angle);
                let rate = v.get(a.dof).copied().unwrap_or(0.0);
                let (c, dc) = a.spec.center(a.length, th);
                (c, [dc[0] * rate, dc[1] * rate])
            }
            _ => (self.spec.pulleys[p].center, [0.0, 0.0]),
        }
    }

    /// Reference element length `l` \[m\].
    pub fn element_length(&self) -> f64 {
        self.kind.mesh.elements()[0].length()
    }
    /// Reuse the elastic part of the tangent stiffness in [`SecondOrderSystem::force_tangent`]
    /// until some element's relative node position `(r_J − r_I)/l` or nodal slope has changed
    /// by more than `tol` since it was evaluated (`0`: always re-evaluate, the exact Newton
    /// matrix). The contact tangent is always exact. With the inertia term `M/(h²β)` dominating
    /// the Newton matrix, a tangent that lags by a small rotation only slows the convergence of
    /// generalized-α's Newton iterations marginally, while the belt element's second
    /// derivatives (automatic differentiation) are by far the most expensive part of a step.
    pub fn with_tangent_refresh(mut self, tol: f64) -> Self {
        self.kind.tangent_refresh = tol.max(0.0);
        self
    }

    /// The drive with the friction law `laws[p]` on pulley `p` (travel order) instead of the
    /// spec's `contact.friction` on every pulley: a multi-ribbed belt's `μ/sin(β/2)` on its
    /// grooved pulleys ([`belt::Drive::wrap_friction_law`], which the layout adapter
    /// [`crate::belt_drive::belt_model`] hands over).
    ///
    /// # Errors
    /// Not one law per pulley, or a law with negative or non-finite parameters (a law scaled
    /// past the configuration bound [`contact::friction::spec::MAX_FRICTION_COEFFICIENT`] is
    /// accepted: it is an effective coefficient, not an input).
    pub fn with_pulley_friction(mut self, laws: Vec<BeltFriction>) -> Result<Self, AncfError> {
        if laws.len() != self.spec.pulleys.len() {
            return Err(invalid(
                "contact.friction",
                format!(
                    "{} friction laws for {} pulleys",
                    laws.len(),
                    self.spec.pulleys.len()
                ),
            ));
        }
        for (p, law) in laws.iter().enumerate() {
            let mu = contact::FrictionLaw::coefficient(law);
            if !(mu.is_finite() && mu >= 0.0) {
                return Err(invalid(
                    format!("contact.friction[{p}]"),
                    format!("friction coefficient must be finite and ≥ 0, got {mu}"),
                ));
            }
        }
        self.kind.friction = laws;
        Ok(self)
    }

    /// The friction law on pulley `p` (travel order; [`Self::with_pulley_friction`]).
    ///
    /// # Panics
    /// `p` is not a pulley of the drive.
    pub fn friction_law(&self, p: usize) -> &BeltFriction {
        &self.kind.friction[p]
    }

    /// Number of elastic tangent evaluations so far (for statistics).
    pub fn elastic_tangent_evaluations(&self) -> usize {
        self.kind.elastic_evaluations.load(Ordering::Relaxed)
    }

    /// Whether the cached elastic tangent at `q_ref` may be reused at `q`.
    fn tangent_still_valid(&self, q_ref: &[f64], q: &[f64]) -> bool {
        let tol = self.kind.tangent_refresh;
        if tol <= 0.0 {
            return false;
        }
        let l = self.element_length();
        for el in 0..self.kind.mesh.elements().len() {
            let i = self.kind.mesh.global_dof(el, 0);
            let j = self.kind.mesh.global_dof(el, 6);
            for a in 0..2 {
                let d = (q[j + a] - q[i + a]) - (q_ref[j + a] - q_ref[i + a]);
                if d.abs() > tol * l {
                    return false;
                }
            }
        }
        for node in 0..self.kind.mesh.n_nodes() {
            for k in 2..6 {
                let g = 6 * node + k;
                if (q[g] - q_ref[g]).abs() > tol {
                    return false;
                }
            }
        }
        true
    }

    /// Disk of pulley `p` spinning with travel-sense speed `omega` \[rad/s\] at `(q, v)`
    /// (centre and its velocity: [`Self::pulley_center`]).
    fn disk(&self, p: usize, omega: f64, q: &[f64], v: &[f64]) -> Disk {
        let pl = &self.spec.pulleys[p];
        let (c, cd) = self.pulley_center(p, q, v);
        Disk {
            center: Point2::from(c),
            radius: pl.radius,
            velocity: Vector2::from(cd),
            omega: pl.ccw_sign() * omega,
        }
    }

    /// Whether element `el` (nodes at `e`) may touch pulley `p`: a point of the element lies
    /// within one chord length of a node, so the element is skipped when both nodes are
    /// farther than that from the pulley surface (Kerkkänen §3.2's pre-check).
    #[inline]
    fn may_touch(&self, e: &[f64], p: usize, center: [f64; 2]) -> bool {
        let pl = &self.spec.pulleys[p];
        let d = |x: f64, y: f64| ((x - center[0]).powi(2) + (y - center[1]).powi(2)).sqrt();
        let chord = ((e[6] - e[0]).powi(2) + (e[7] - e[1]).powi(2)).sqrt();
        let gap = d(e[0], e[1]).min(d(e[6], e[7])) - pl.radius;
        gap <= chord
    }

    /// Runs the distributed contact of every element against every pulley at travel-sense
    /// pulley speeds `omegas` and hands each element–pulley pair with active points to `sink`.
    fn contact_pass(
        &self, q: &[f64], v: &[f64], omegas: &[f64], jacobian: bool, scratch: &mut Scratch,
        sink: impl FnMut(usize, usize, &ElementContact<2>, &mut Scratch),
    ) {
        self.contact_pass_on(
            &self.kind.line,
            q,
            v,
            omegas,
            jacobian,
            false,
            scratch,
            sink,
        );
    }

    /// [`Self::contact_pass`] with the contact quadrature of `line` (the drive's own or a
    /// sampling rule, [`Self::contact_records_sampled`]); with `records` the pair's active
    /// points' [`ContactRecord`]s are in `scratch.records` when `sink` sees it. The one loop
    /// over the element–pulley pairs of the forces, the tangent, the outputs and the
    /// transition-aware limit.
    #[allow(clippy::too_many_arguments)] // the state, the rule, the switches, scratch and sink
    fn contact_pass_on(
        &self, line: &LineContact<Disk, BeltNormal, BeltFriction>, q: &[f64], v: &[f64],
        omegas: &[f64], jacobian: bool, records: bool, scratch: &mut Scratch,
        mut sink: impl FnMut(usize, usize, &ElementContact<2>, &mut Scratch),
    ) {
        let l = self.element_length();
        let mut e = [0.0; NE];
        let mut ed = [0.0; NE];
        // the pulleys' disks at this state, once for all elements (in the scratch's buffer,
        // out of it for the pass as the contact buffers)
        let mut disks = std::mem::take(&mut scratch.disks);
        disks.clear();
        disks.extend(
            omegas
                .iter()
                .enumerate()
                .map(|(p, &omega)| self.disk(p, omega, q, v)),
        );
        // the pair's contact buffers, out of the scratch for the whole pass (the sink gets them
        // beside the scratch)
        let mut ec = std::mem::replace(&mut scratch.contact, ElementContact::new(0));
        for el in 0..self.kind.mesh.elements().len() {
            self.kind.mesh.gather(q, el, &mut e);
            let mut gathered_v = false;
            for (p, disk) in disks.iter().enumerate() {
                if !self.may_touch(&e, p, [disk.center.x, disk.center.y]) {
                    continue;
                }
                if !gathered_v {
                    self.kind.mesh.gather(v, el, &mut ed);
                    gathered_v = true;
                }
                scratch.records.clear();
                line.element_on(
                    disk,
                    &self.kind.friction[p],
                    l,
                    6,
                    |xi, s| s[..6].copy_from_slice(&shape::cubic(l, xi * l, 0.0).s),
                    &e,
                    &ed,
                    jacobian,
                    &mut ec,
                    records.then_some(&mut scratch.records),
                );
                if ec.active_points > 0 {
                    sink(el, p, &ec, scratch);
                }
            }
        }
        scratch.contact = ec;
        scratch.disks = disks;
    }

    /// The drive's work buffers and tangent cache in the caller's workspace `ws`, created on
    /// first use (and anew if `ws` held those of a drive with other sizes).
    fn scratch<'w>(&self, ws: &'w mut Workspace) -> &'w mut Scratch {
        let m = NE + self.pulley_dofs.count() + usize::from(self.kind.arm.is_some());
        let fresh = || Scratch {
            contact: ElementContact::new(NE),
            records: Vec::new(),
            disks: Vec::new(),
            slips: Vec::new(),
            q1: Vec::new(),
            v1: Vec::new(),
            k_local: vec![0.0; m * m],
            c_local: vec![0.0; m * m],
            elastic: ElasticCache {
                q: Vec::new(),
                k: Vec::new(),
                valid: false,
            },
        };
        let s = ws.get_or_insert_with(fresh);
        if s.k_local.len() != m * m {
            *s = fresh();
        }
        s
    }

    /// Belt forces `Q_e + Q_c` (length `n_belt`) and the travel-sense contact torques on every
    /// pulley `s τ` \[N·m\], with the pulleys spinning at `omegas` (travel sense, rad/s).
    pub fn belt_forces(
        &self, q: &[f64], v: &[f64], omegas: &[f64], f: &mut [f64], torques: &mut [f64],
        ws: &mut Workspace,
    ) {
        let nb = self.n_belt;
        self.kind.mesh.elastic_forces(&q[..nb], &mut f[..nb]);
        torques.fill(0.0);
        let scratch = self.scratch(ws);
        self.contact_pass(q, v, omegas, false, scratch, |el, p, ec, _| {
            self.kind.mesh.scatter_add(f, el, &ec.q, 1.0);
            torques[p] += self.spec.pulleys[p].ccw_sign() * ec.moment;
        });
    }

    /// Belt tangent `K = −∂(Q_e + Q_c)/∂e` restricted to the belt coordinates with the pulleys
    /// held at `omegas`, assembled into `pat` (whose first groups are the mesh elements, in
    /// order); `f` receives the forces.
    pub(crate) fn belt_stiffness(
        &self, q: &[f64], omegas: &[f64], pat: &Pattern, f: &mut [f64], k_vals: &mut [f64],
        ws: &mut Workspace,
    ) {
        let nb = self.n_belt;
        k_vals.fill(0.0);
        self.kind
            .mesh
            .elastic_tangent_into(&q[..nb], &mut f[..nb], pat, k_vals, 1.0);
        let zero = vec![0.0; q.len()];
        let scratch = self.scratch(ws);
        self.contact_pass(q, &zero, omegas, true, scratch, |el, _, ec, _| {
            self.kind.mesh.scatter_add(f, el, &ec.q, 1.0);
            pat.add_element(k_vals, el, &ec.dq_de, -1.0);
        });
    }

    /// Force of the belt on every pulley (the hub load, the resultant of the contact forces
    /// (3.20)–(3.23) integrated by (3.27)) \[N\] and its torque about the pulley centre in the
    /// pulley's travel sense \[N·m\] (Kerkkänen (3.26)), at `(t, q, v)`.
    pub fn pulley_loads(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<PulleyLoad> {
        self.pulley_loads_with(q, v, &self.speeds(t, v))
    }

    /// [`Self::pulley_loads`] with the pulleys spinning at the travel-sense speeds `omegas`
    /// \[rad/s\] (one per pulley; see [`Self::forces_with`]).
    pub fn pulley_loads_with(&self, q: &[f64], v: &[f64], omegas: &[f64]) -> Vec<PulleyLoad> {
        let mut out = vec![PulleyLoad::default(); self.spec.pulleys.len()];
        // an output (sampled, not per step): a scratch of its own
        let mut ws = Workspace::new();
        let scratch = self.scratch(&mut ws);
        self.contact_pass(q, v, omegas, false, scratch, |_, p, ec, _| {
            out[p].force[0] += ec.reaction[0];
            out[p].force[1] += ec.reaction[1];
            out[p].torque += self.spec.pulleys[p].ccw_sign() * ec.moment;
        });
        out
    }

    /// Contact state at every active quadrature point, for output (force distributions and
    /// belt–pulley relative velocity, Kerkkänen Figs 3.13–3.20).
    pub fn contact_records(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<PointRecord> {
        self.records_on(&self.kind.line, q, v, &self.speeds(t, v))
    }

    /// [`Self::contact_records`] with the pulleys spinning at the travel-sense speeds `omegas`
    /// \[rad/s\] (one per pulley; see [`Self::forces_with`]).
    pub fn contact_records_with(&self, q: &[f64], v: &[f64], omegas: &[f64]) -> Vec<PointRecord> {
        self.records_on(&self.kind.line, q, v, omegas)
    }

    /// Contact state sampled at `per_element` equally spaced points of every element (at
    /// `ξ = (k + ½)/per_element`), independent of the quadrature rule of the contact forces.
    ///
    /// The relative velocity (3.25) and the penetration are pointwise fields of the solution;
    /// the quadrature points, ~8 mm apart with 5 points on 41 mm elements, are too sparse to
    /// resolve the few-millimetre inlet and exit zones of a contact arc where the belt's
    /// velocity turns away from the pulley tangent (Kerkkänen Fig. 3.17). The force values of
    /// these records are the force densities (3.20), (3.23) at the sampled points.
    pub fn contact_records_sampled(
        &self, t: f64, q: &[f64], v: &[f64], per_element: usize,
    ) -> Vec<PointRecord> {
        self.contact_records_sampled_with(q, v, &self.speeds(t, v), per_element)
    }

    /// [`Self::contact_records_sampled`] with the pulleys spinning at the travel-sense speeds
    /// `omegas` \[rad/s\] (one per pulley; see [`Self::forces_with`]).
    pub fn contact_records_sampled_with(
        &self, q: &[f64], v: &[f64], omegas: &[f64], per_element: usize,
    ) -> Vec<PointRecord> {
        let n = per_element.max(1);
        let line = LineContact {
            surface: self.kind.line.surface,
            normal: self.kind.line.normal,
            friction: self.kind.line.friction,
            rule: GaussRule {
                points: (0..n).map(|k| (k as f64 + 0.5) / n as f64).collect(),
                weights: vec![1.0 / n as f64; n],
            },
        };
        self.records_on(&line, q, v, omegas)
    }

    fn records_on(
        &self, line: &LineContact<Disk, BeltNormal, BeltFriction>, q: &[f64], v: &[f64],
        omegas: &[f64],
    ) -> Vec<PointRecord> {
        let l = self.element_length();
        let mut out = Vec::new();
        // an output (sampled, not per step): a scratch of its own
        let mut ws = Workspace::new();
        let scratch = self.scratch(&mut ws);
        self.contact_pass_on(line, q, v, omegas, false, true, scratch, |el, p, _, s| {
            let sgn = self.spec.pulleys[p].ccw_sign();
            for r in &s.records {
                let k = r.index;
                out.push(PointRecord {
                    weight: line.rule.weights.get(k).copied().unwrap_or(0.0) * l,
                    pulley: p,
                    element: el,
                    s_material: (el as f64 + line.rule.points[r.index]) * l,
                    position: r.position.into(),
                    penetration: r.penetration,
                    normal_force: r.normal_force,
                    friction_force: sgn * r.friction_force,
                    slip: sgn * r.slip,
                });
            }
        });
        out
    }
}

/// The tangent entries of one element's contact with the tensioner's idler that the arm adds
/// (local columns/rows `NE + nf` for the arm, `NE + kp` for the idler's spin, `m` the local
/// size), written into `s.k_local = −∂f/∂q` and `s.c_local = −∂f/∂v`, at the arm angle and
/// rate `(θ, θ̇)` \[rad, rad/s\].
///
/// The contact forces depend on the disk's centre `c` only through `r − c` and `ṙ − ċ`, so
/// moving the centre by `δ` equals moving the element by `−δ`: with the cubic shape functions'
/// partition of unity on the nodal positions (`S₁ + S₄ = 1`, element coordinates 0, 6 for x
/// and 1, 7 for y), `∂X/∂c_x = −(∂X/∂e₀ + ∂X/∂e₆)` and likewise for `ċ` with `ė`. With
/// `c = c(θ)`, `ċ = c'θ̇` and `c'' = −(c − p)`: `∂X/∂θ = ∂X/∂c·c' + ∂X/∂ċ·c''θ̇`,
/// `∂X/∂θ̇ = ∂X/∂ċ·c'`. The arm's moment is `(c − p) × F` with `F` = `ec.reaction`
/// `= −(Q₀ + Q₆, Q₁ + Q₇)` (the same partition of unity), so `∂F/∂e` follows from `∂Q/∂e`.
fn arm_contact_tangent(
    a: &BeltArm, lever: [f64; 2], (angle, rate): (f64, f64), ec: &ElementContact<2>,
    spin: Option<(usize, f64)>, nf: usize, s: &mut Scratch,
) {
    let m = NE + nf + 1;
    let ca = NE + nf;
    let (_, dc) = a.spec.center(a.length, angle);
    let cdd = [-lever[0], -lever[1]];
    // (∂X/∂θ, ∂X/∂θ̇) of a quantity X with element derivatives d(b) = ∂X/∂e_b, dd(b) = ∂X/∂ė_b
    let chain = |d: &dyn Fn(usize) -> f64, dd: &dyn Fn(usize) -> f64| {
        let dcx = -(d(0) + d(6));
        let dcy = -(d(1) + d(7));
        let dvx = -(dd(0) + dd(6));
        let dvy = -(dd(1) + dd(7));
        (
            dcx * dc[0] + dcy * dc[1] + (dvx * cdd[0] + dvy * cdd[1]) * rate,
            dvx * dc[0] + dvy * dc[1],
        )
    };
    // belt rows
    for r in 0..NE {
        let (kt, ct) = chain(&|b| ec.dq_de[r + b * NE], &|b| ec.dq_dedot[r + b * NE]);
        s.k_local[r + ca * m] = -kt;
        s.c_local[r + ca * m] = -ct;
    }
    // the idler's spin row: s τ
    if let Some((kp, sg)) = spin {
        let row = NE + kp;
        let (kt, ct) = chain(&|b| sg * ec.dmoment_de[b], &|b| sg * ec.dmoment_dedot[b]);
        s.k_local[row + ca * m] = -kt;
        s.c_local[row + ca * m] = -ct;
    }
    // the arm's row: (c − p) × F, F = −(Q₀ + Q₆, Q₁ + Q₇)
    let df_de = |c: usize, b: usize| -(ec.dq_de[c + b * NE] + ec.dq_de[c + 6 + b * NE]);
    let df_dedot = |c: usize, b: usize| -(ec.dq_dedot[c + b * NE] + ec.dq_dedot[c + 6 + b * NE]);
    for b in 0..NE {
        s.k_local[ca + b * m] = -cross(lever, [df_de(0, b), df_de(1, b)]);
        s.c_local[ca + b * m] = -cross(lever, [df_dedot(0, b), df_dedot(1, b)]);
    }
    if let Some((kp, sg)) = spin {
        let col = NE + kp;
        let dw = [
            -(ec.dq_domega[0] + ec.dq_domega[6]),
            -(ec.dq_domega[1] + ec.dq_domega[7]),
        ];
        s.c_local[ca + col * m] = -sg * cross(lever, dw);
    }
    let (kx, cx) = chain(&|b| df_de(0, b), &|b| df_dedot(0, b));
    let (ky, cy) = chain(&|b| df_de(1, b), &|b| df_dedot(1, b));
    let f = [ec.reaction[0], ec.reaction[1]];
    s.k_local[ca + ca * m] = -(cross(dc, f) + cross(lever, [kx, ky]));
    s.c_local[ca + ca * m] = -cross(lever, [cx, cy]);
}

/// The belt's load on one pulley ([`BeltDrive::pulley_loads`]).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct PulleyLoad {
    /// Resultant force of the belt on the pulley (hub load) \[N\].
    pub force: [f64; 2],
    /// Torque of the belt's contact forces on the pulley in its travel sense \[N·m\].
    pub torque: f64,
}

/// Contact state at one quadrature point, in the travel sense of the pulley.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PointRecord {
    /// Pulley index.
    pub pulley: usize,
    /// Element index.
    pub element: usize,
    /// Material (unstretched) arc length along the belt from node 0 \[m\].
    pub s_material: f64,
    /// Quadrature weight of the point times the element length \[m\]: the belt length the
    /// point's force densities stand for (3.27).
    pub weight: f64,
    /// Position \[m\].
    pub position: [f64; 2],
    /// Penetration `d` (3.21) \[m\].
    pub penetration: f64,
    /// Normal force per unit length `k_p d + c_p ḋ` (3.20) \[N/m\].
    pub normal_force: f64,
    /// Friction force per unit length on the belt, positive in the travel direction \[N/m\].
    pub friction_force: f64,
    /// Relative velocity of the belt with respect to the pulley surface (3.25), positive when
    /// the belt is faster in the travel direction \[m/s\].
    pub slip: f64,
}

impl SecondOrderSystem for BeltDrive {
    fn n_q(&self) -> usize {
        self.n_belt + self.pulley_dofs.count() + usize::from(self.kind.arm.is_some())
    }
    fn dof_name(&self, dof: usize) -> String {
        if dof < self.n_belt {
            let names = ["r_x", "r_y", "r,x_x", "r,x_y", "r,y_x", "r,y_y"];
            format!("belt node {} {}", dof / 6, names[dof % 6])
        } else if let Some(name) = self.pulley_dofs.dof_name(&self.spec.pulleys, dof) {
            name
        } else if self.kind.arm.is_some_and(|a| a.dof == dof) {
            "tensioner arm angle".into()
        } else {
            format!("coordinate {dof}")
        }
    }
    crate::mounted::ancf_equations!();

    /// The belt convected along itself ([`BeltDrive::convected_increment`]); the pulley and
    /// arm coordinates keep the integrator's prediction.
    fn predict_increment(
        &self, _t: f64, q: &[f64], v: &[f64], vdot: &[f64], h: f64, dq: &mut [f64],
    ) -> bool {
        self.convected_increment(q, v, vdot, h, dq)
    }

    /// The transition-aware limit of the contact points' slip velocities
    /// ([`BeltDrive::transition_limit`]).
    fn correction_limit(
        &self, t: f64, q: &[f64], v: &[f64], dq: &[f64], dv: &[f64], ws: &mut Workspace,
    ) -> Result<f64, mbd_core::MbdError> {
        Ok(self.transition_limit(t, q, v, dq, dv, ws))
    }
}

impl BeltDrive {
    /// Largest fraction `α ∈ (0, 1]` of a Newton correction `(Δq, Δv)` from the state
    /// `(t, q, v)` that keeps every contact point's slip velocity from crossing its friction
    /// law's steep band in one iteration: the transition-aware limit of Castro et al. (2019)
    /// (`contact::friction::transition_limit`, width `w` = the law's
    /// [`transition_width`](contact::FrictionLaw::transition_width), `1/κ` of the tanh law
    /// Ribaric (6.2)), the smallest over the points.
    ///
    /// The slip velocity is Kerkkänen (3.25)'s `v_t = tᵀ(ṙ − u_s)` of every contact quadrature
    /// point, evaluated exactly at both ends: at `(q, v)` and at the fully corrected state
    /// `(q + Δq, v + Δv)` with the pulleys' speeds (and a tensioner idler's centre) of each
    /// state, by the contact loop of the forces (the same kinematics, two force-only contact
    /// evaluations without the belt's elastic forces); the change `v_t(q + Δq, v + Δv) −
    /// v_t(q, v)` is then taken as linear in `α`. At 27 m/s belt speed the convective part of
    /// the change (the point moving along the wrap and its tangent turning with `Δq`) is not
    /// small against the `γ' Δq` of the velocity, which is why the change is not linearised.
    /// Only points in contact (penetration ≥ 0) at both ends are limited: a point entering or
    /// leaving the wrap within the correction has no friction at one end, and its friction
    /// force, `∝ f_n`, vanishes continuously with the penalty force (3.20) at the wrap's edge.
    /// `1` without a law that has a band (the creep-rate law, Coulomb).
    pub fn transition_limit(
        &self, t: f64, q: &[f64], v: &[f64], dq: &[f64], dv: &[f64], ws: &mut Workspace,
    ) -> f64 {
        let widths: Vec<Option<f64>> = self
            .kind
            .friction
            .iter()
            .map(contact::FrictionLaw::transition_width)
            .collect();
        if widths.iter().all(Option::is_none) {
            return 1.0;
        }
        let np = widths.len();
        let npts = self.kind.line.rule.points.len();
        let n_el = self.kind.mesh.elements().len();
        let line = &self.kind.line;
        let scratch = self.scratch(ws);
        let mut slips = std::mem::take(&mut scratch.slips);
        slips.clear();
        slips.resize(n_el * np * npts, f64::NAN);
        let at = |el: usize, p: usize, k: usize| (el * np + p) * npts + k;
        let omegas = self.speeds(t, v);
        self.contact_pass_on(line, q, v, &omegas, false, true, scratch, |el, p, _, s| {
            if widths[p].is_some() {
                for r in &s.records {
                    slips[at(el, p, r.index)] = r.slip;
                }
            }
        });
        let (mut q1, mut v1) = (
            std::mem::take(&mut scratch.q1),
            std::mem::take(&mut scratch.v1),
        );
        q1.clear();
        q1.extend(q.iter().zip(dq).map(|(a, b)| a + b));
        v1.clear();
        v1.extend(v.iter().zip(dv).map(|(a, b)| a + b));
        let omegas1 = self.speeds(t, &v1);
        let mut alpha = 1.0_f64;
        self.contact_pass_on(
            line,
            &q1,
            &v1,
            &omegas1,
            false,
            true,
            scratch,
            |el, p, _, s| {
                let Some(w) = widths[p] else { return };
                for r in &s.records {
                    let s0 = slips[at(el, p, r.index)];
                    if !s0.is_nan() {
                        alpha = alpha.min(contact::friction::transition_limit(s0, r.slip - s0, w));
                    }
                }
            },
        );
        scratch.slips = slips;
        scratch.q1 = q1;
        scratch.v1 = v1;
        alpha
    }
}

impl BeltDrive {
    /// The steady-flow prediction of a step of `h` \[s\] for the belt coordinates, written into
    /// `dq[..n_belt]` (the rest untouched): in a steady drive the belt's shape is stationary
    /// and its material flows through it, so that the material point `s` is at `t + h` where
    /// the point `s + c h` is at `t`, `r(s, t + h) = r(s + c h, t)`, with `c` the rate of the
    /// material coordinate through a fixed point, the same at every point of a steady loop
    /// (mass conservation). `c` is the mean over the nodes of `ṙ·r_x/|r_x|²` (the tangential
    /// speed over the stretch), the shift `Δs = c h + ½ ċ h²` with `ċ` the same mean of
    /// `r̈·r_x/|r_x|²`. Each node takes the centreline `r` and slope `r_x` of Kerkkänen's
    /// cubic shape functions (3.11) at `s_k + Δs`, and the cross-section vector `r_y` with its
    /// components along and across the interpolated slope interpolated linearly (a plain
    /// linear interpolation of `r_y` would shorten it on a wrap, by `1 − cos(l/2R)`).
    /// Returns `false` (no prediction) when the shift is not below one element or not
    /// finite.
    pub fn convected_increment(
        &self, q: &[f64], v: &[f64], vdot: &[f64], h: f64, dq: &mut [f64],
    ) -> bool {
        let mesh = &self.kind.mesh;
        let nodes = mesh.n_nodes();
        let n_el = mesh.elements().len();
        if nodes != n_el || nodes == 0 || mesh.coords_per_node() != 6 {
            return false;
        }
        let l = self.element_length();
        let (mut c, mut cd) = (0.0, 0.0);
        for k in 0..nodes {
            let i = 6 * k;
            let rx = [q[i + 2], q[i + 3]];
            let a = rx[0] * rx[0] + rx[1] * rx[1];
            c += (v[i] * rx[0] + v[i + 1] * rx[1]) / a;
            cd += (vdot[i] * rx[0] + vdot[i + 1] * rx[1]) / a;
        }
        c /= nodes as f64;
        cd /= nodes as f64;
        let shift = c * h + 0.5 * cd * h * h;
        if !(shift.is_finite() && shift.abs() < l) {
            return false;
        }
        // the local frame (t, n) of a slope and the components of r_y in it
        let frame = |rx: [f64; 2]| {
            let norm = (rx[0] * rx[0] + rx[1] * rx[1]).sqrt();
            let t = [rx[0] / norm, rx[1] / norm];
            (t, [-t[1], t[0]])
        };
        let local = |i: usize| {
            let (t, n) = frame([q[i + 2], q[i + 3]]);
            let ry = [q[i + 4], q[i + 5]];
            [ry[0] * t[0] + ry[1] * t[1], ry[0] * n[0] + ry[1] * n[1]]
        };
        let mut e = [0.0; NE];
        for k in 0..nodes {
            let s = k as f64 + shift / l;
            let base = s.floor();
            let xi = s - base;
            let el = (base as i64).rem_euclid(n_el as i64) as usize;
            mesh.gather(q, el, &mut e);
            let sh = shape::cubic(l, xi * l, 0.0);
            let (mut r, mut rx) = ([0.0; 2], [0.0; 2]);
            for a in [0, 1, 3, 4] {
                for d in 0..2 {
                    r[d] += sh.s[a] * e[2 * a + d];
                    rx[d] += sh.sx[a] * e[2 * a + d];
                }
            }
            let (ci, cj) = (mesh.global_dof(el, 0), mesh.global_dof(el, 6));
            let (yi, yj) = (local(ci), local(cj));
            let y = [
                (1.0 - xi) * yi[0] + xi * yj[0],
                (1.0 - xi) * yi[1] + xi * yj[1],
            ];
            let (t, n) = frame(rx);
            let ry = [y[0] * t[0] + y[1] * n[0], y[0] * t[1] + y[1] * n[1]];
            let i = 6 * k;
            for (j, x) in [r[0], r[1], rx[0], rx[1], ry[0], ry[1]]
                .into_iter()
                .enumerate()
            {
                dq[i + j] = x - q[i + j];
            }
        }
        true
    }
}

impl BeltDrive {
    /// Generalized forces `Q_e + Q_c` (2.27), (3.27) and the free pulleys' right-hand sides
    /// `s τ − T_a` (3.26) with the pulleys spinning at the travel-sense speeds `omegas`
    /// \[rad/s\] and load torques `loads` \[N·m\] (one per pulley; ignored for speed-driven
    /// pulleys): the [`SecondOrderSystem::forces`] of the drive with externally supplied inputs
    /// (used by adapters that schedule the driver speed and the load themselves); `ws` is the
    /// caller's scratch for this drive. The time `t` \[s\] is the plate drive's argument
    /// (its pulley surfaces move); the planar contact does not depend on it.
    #[allow(clippy::too_many_arguments)] // the state, the pulley inputs, outputs, and the workspace
    pub fn forces_with(
        &self, _t: f64, q: &[f64], v: &[f64], omegas: &[f64], loads: &[f64], f: &mut [f64],
        ws: &mut Workspace,
    ) {
        let nb = self.n_belt;
        self.kind.mesh.elastic_forces(&q[..nb], &mut f[..nb]);
        f[nb..].fill(0.0);
        self.axial_damping(q, v, f, None);
        let scratch = self.scratch(ws);
        let arm = self.kind.arm.map(|a| (a, self.arm_lever(&a, q)));
        self.contact_pass(q, v, omegas, false, scratch, |el, p, ec, _| {
            self.kind.mesh.scatter_add(f, el, &ec.q, 1.0);
            if let Some(j) = self.pulley_dofs.dof(p) {
                f[j] += self.spec.pulleys[p].ccw_sign() * ec.moment;
            }
            if let Some((a, lever)) = arm
                && a.spec.pulley == p
            {
                f[a.dof] += cross(lever, [ec.reaction[0], ec.reaction[1]]);
            }
        });
        self.pulley_dofs.subtract_loads(loads, f);
        if let Some(a) = &self.kind.arm {
            f[a.dof] += self.arm_moment(a, q, v);
        }
    }

    /// Lever `c(θ) − p` \[m\] of the arm at `q`.
    fn arm_lever(&self, a: &BeltArm, q: &[f64]) -> [f64; 2] {
        let (c, _) = self.pulley_center(a.spec.pulley, q, &[]);
        [c[0] - a.spec.pivot[0], c[1] - a.spec.pivot[1]]
    }

    /// Spring, damper and dry-friction moments on the arm `M_s + M_d + M_f` \[N·m\]
    /// ([`belt::tensioner`]).
    fn arm_moment(&self, a: &BeltArm, q: &[f64], v: &[f64]) -> f64 {
        let (th, rate) = (q[a.dof], v[a.dof]);
        a.spec.moment(th, rate).0
    }

    /// [`SecondOrderSystem::force_tangent`] with the pulleys spinning at the travel-sense
    /// speeds `omegas` \[rad/s\] (one per pulley; for a free pulley it must equal its velocity
    /// coordinate, whose column receives the speed coupling); `ws` is the caller's scratch for
    /// this drive (it keeps the reused elastic tangent). The time `t` \[s\] as in
    /// [`Self::forces_with`].
    pub fn force_tangent_with(
        &self, _t: f64, q: &[f64], v: &[f64], omegas: &[f64], ws: &mut Workspace,
    ) -> ForceTangent {
        let nb = self.n_belt;
        let pat = &self.pattern;
        let scratch = self.scratch(ws);
        let mut k = if self.kind.tangent_refresh <= 0.0 {
            // no reuse (the default): the tangent itself, without the cache's copies
            let mut fbuf = vec![0.0; nb];
            let mut kv = pat.zeros();
            self.kind
                .mesh
                .elastic_tangent_into(&q[..nb], &mut fbuf, pat, &mut kv, 1.0);
            self.kind
                .elastic_evaluations
                .fetch_add(1, Ordering::Relaxed);
            kv
        } else {
            let cache = &mut scratch.elastic;
            if !(cache.valid && cache.q.len() == q.len() && self.tangent_still_valid(&cache.q, q)) {
                let mut fbuf = vec![0.0; nb];
                let mut kv = pat.zeros();
                self.kind
                    .mesh
                    .elastic_tangent_into(&q[..nb], &mut fbuf, pat, &mut kv, 1.0);
                cache.k = kv;
                cache.q = q.to_vec();
                cache.valid = true;
                self.kind
                    .elastic_evaluations
                    .fetch_add(1, Ordering::Relaxed);
            }
            cache.k.clone()
        };
        let mut c = pat.zeros();
        self.axial_damping(q, v, &mut [], Some((&mut k, &mut c)));
        let n_el = self.kind.mesh.elements().len();
        let arm = self.kind.arm.map(|a| (a, self.arm_lever(&a, q)));
        self.contact_pass(q, v, omegas, true, scratch, |el, p, ec, s| {
            let (local, n_local) = self.contact_local_matrices(p, ec, arm, q, v, s);
            let local = &local[..n_local];
            pat.add_element_on(&mut k, n_el + el, &s.k_local, 1.0, local);
            pat.add_element_on(&mut c, n_el + el, &s.c_local, 1.0, local);
        });
        if let Some(a) = &self.kind.arm {
            let (th, rate) = (q[a.dof], v[a.dof]);
            let d = pat.diagonal_position(a.dof);
            let (_, ks, cs) = a.spec.moment(th, rate);
            k[d] -= ks;
            c[d] -= cs;
        }
        // the free pulleys' viscous dampers: −c ω
        crate::mounted::pulleys::add_damping(&self.pulley_dofs, &self.spec.pulleys, pat, &mut c);
        ForceTangent {
            stiffness: SysMatrix::Sparse(pat.to_matrix(k)),
            damping: SysMatrix::Sparse(pat.to_matrix(c)),
        }
    }

    /// The local stiffness and damping `−∂Q/∂(e, θ̇, α)`, `−∂Q/∂(ė, θ̇, α̇)` of one element's
    /// contact `ec` with pulley `p` into `s.k_local`, `s.c_local` (`m × m`, `m` = element, free
    /// pulleys', arm's coordinates): the element block, the pulley's spin row and column (a
    /// free pulley) and the arm's (the arm's pulley, [`arm_contact_tangent`]). Returns the
    /// local rows and columns these fill (`local[..n]`: the element's, the spin's, the arm's);
    /// the entries among them are cleared first, the others are left as they were (the
    /// matrices are zero there: `Pattern::add_element_on` adds only `local`).
    fn contact_local_matrices(
        &self, p: usize, ec: &ElementContact<2>, arm: Option<(BeltArm, [f64; 2])>, q: &[f64],
        v: &[f64], s: &mut Scratch,
    ) -> ([usize; NE + 2], usize) {
        let nb = self.n_belt;
        let nf = self.pulley_dofs.count();
        let m = NE + nf + usize::from(self.kind.arm.is_some());
        let mut local = [0usize; NE + 2];
        let mut n_local = NE;
        for (i, l) in local.iter_mut().enumerate().take(NE) {
            *l = i;
        }
        if let Some(j) = self.pulley_dofs.dof(p) {
            local[n_local] = NE + (j - nb);
            n_local += 1;
        }
        if arm.is_some_and(|(a, _)| a.spec.pulley == p) {
            local[n_local] = NE + nf;
            n_local += 1;
        }
        for &b in &local[..n_local] {
            for &a in &local[..n_local] {
                s.k_local[a + b * m] = 0.0;
                s.c_local[a + b * m] = 0.0;
            }
        }
        for b in 0..NE {
            for a in 0..NE {
                s.k_local[a + b * m] = -ec.dq_de[a + b * NE];
                s.c_local[a + b * m] = -ec.dq_dedot[a + b * NE];
            }
        }
        if let Some(j) = self.pulley_dofs.dof(p) {
            let kp = j - nb;
            let sg = self.spec.pulleys[p].ccw_sign();
            let col = NE + kp;
            for a in 0..NE {
                // f_belt depends on ω_ccw = s θ̇
                s.c_local[a + col * m] = -sg * ec.dq_domega[a];
                // pulley row: s τ
                s.k_local[col + a * m] = -sg * ec.dmoment_de[a];
                s.c_local[col + a * m] = -sg * ec.dmoment_dedot[a];
            }
            s.c_local[col + col * m] = -ec.dmoment_domega;
        }
        if let Some((a, lever)) = arm
            && a.spec.pulley == p
        {
            arm_contact_tangent(
                &a,
                lever,
                (q[a.dof], v[a.dof]),
                ec,
                self.pulley_dofs
                    .dof(p)
                    .map(|j| (j - nb, self.spec.pulleys[p].ccw_sign())),
                nf,
                s,
            );
        }
        (local, n_local)
    }

    /// Kelvin–Voigt damping of the axial strain rate ([`super::BeltSpec::axial_damping`]) in the
    /// strain measure of the material law ([`super::BeltSpec::law`]): the viscous axial force
    /// is `N_d = β α₁EA λ ε̇_G` (St Venant–Kirchhoff, `ε_G = (a − 1)/2`, `ε̇_G = r_xᵀṙ_x`) or
    /// `β α₁EA λ̇` (linear, `λ̇ = r_xᵀṙ_x/λ`), i.e. `Q_d = −β α₁EA ∫ S_xᵀ r_x (r_xᵀ ṙ_x) g dx`
    /// with `g = 1` or `g = 1/a`, added to `f` (when not empty). With `tangent = Some((k, c))`
    /// its Jacobians `−∂Q_d/∂e = β α₁EA ∫ S_xᵀ g((r_xᵀṙ_x) I + r_x ṙ_xᵀ + (g'/g)(r_xᵀṙ_x) r_x 2r_xᵀ) S_x dx`
    /// (`g'/g = 0` or `−1/a`) and `−∂Q_d/∂ė = β α₁EA ∫ S_xᵀ g r_x r_xᵀ S_x dx` are added to the
    /// element blocks.
    fn axial_damping(
        &self, q: &[f64], v: &[f64], f: &mut [f64],
        mut tangent: Option<(&mut Vec<f64>, &mut Vec<f64>)>,
    ) {
        if self.spec.belt.axial_damping <= 0.0 {
            return;
        }
        let mut e = [0.0; NE];
        let mut ed = [0.0; NE];
        let mut qd = [0.0; NE];
        let mut kl = [0.0; NE * NE];
        let mut cl = [0.0; NE * NE];
        for el in 0..self.kind.mesh.elements().len() {
            self.kind.mesh.gather(q, el, &mut e);
            self.kind.mesh.gather(v, el, &mut ed);
            let local = tangent.is_some().then_some((&mut kl, &mut cl));
            self.element_damping(&e, &ed, &mut qd, local);
            if !f.is_empty() {
                self.kind.mesh.scatter_add(f, el, &qd, 1.0);
            }
            if let Some((k, c)) = tangent.as_mut() {
                // `element_damping` leaves the slope (`r_y`) rows and columns zero
                self.pattern.add_element_on(k, el, &kl, 1.0, &CENTRE_COORDS);
                self.pattern.add_element_on(c, el, &cl, 1.0, &CENTRE_COORDS);
            }
        }
    }

    /// The line of action of each span's section force, in span order (`None` where the belt
    /// does not cross the span's bisector): the resultant `F` and its moment `m` about the
    /// origin, `m = p × F + M`, averaged over both end sections of the elements over the span's
    /// middle half ([`belt::SpanLine::middle_run`] of the nodes), each from the element's own
    /// consistent end forces (elastic forces (2.20) and axial damping on the position rows for
    /// `F`, on the slope rows for the moment `M = r_x × P_x + r_y × P_y`, the work of a rigid
    /// rotation of the nodal frame; as [`SectionForces`] recovers `F`). The line passes through
    /// `p' = m (F_y, −F_x)/|F|²` along `F`.
    ///
    /// Why not the belt's centreline: a span carries its force along its centreline only where
    /// the bending moment is constant. On a short span between small pulleys the moments of the
    /// two bending boundary layers (`EI/R` at the wraps, decaying over `√(EI/T)`) leave a shear
    /// force `Q = −dM/ds` over the whole span, and the resultant `N t + Q n` turns away from the
    /// centreline: on the default FEAD drive's 57 mm alternator → tensioner span (28 and 35 mm
    /// pulleys, `√(EI/T)` = 8 mm) the lines fitted through the centreline over the middle half
    /// missed the alternator's contact torque by 0.12 N m at 800 rpm and 0.16 N m at 2500 rpm,
    /// the section forces' lines by 0.03 and 0.07 N m (issue 34).
    ///
    /// With each line comes the momentum the belt carries through the same sections, `ṁ ṙ`
    /// (mass flow `ṁ = ρ b h (ṙ·t)/‖r_x‖` through a fixed section, `ṙ` the material velocity;
    /// the private `mass_flow`),
    /// averaged the same way: the balance this gives a pulley is the moment balance of the belt
    /// between the middle of one span and the middle of the next, the contact torque against the
    /// moments of the section forces less the angular momentum carried out (the fluxes of the
    /// two spans cancel only where their levers are equal: at 3500 rpm `ρA v²` is 73 N on the
    /// default FEAD drive).
    pub fn span_force_lines(&self, q: &[f64], v: &[f64]) -> Vec<SpanSection> {
        let mesh = &self.kind.mesh;
        let cpn = mesh.coords_per_node();
        let nodes: Vec<[f64; 2]> = (0..mesh.n_nodes())
            .map(|k| [q[cpn * k], q[cpn * k + 1]])
            .collect();
        let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
        let b = &self.spec.belt;
        let rho_a = b.density * b.width * b.thickness;
        let (mut e, mut ed, mut qe, mut qd) = ([0.0; NE], [0.0; NE], [0.0; NE], [0.0; NE]);
        self.path()
            .spans()
            .iter()
            .map(|sp| {
                let run = sp.middle_run(&nodes);
                if run.is_empty() {
                    return (None, None);
                }
                let (mut f, mut m) = ([0.0; 2], 0.0);
                let (mut flux, mut mflux) = ([0.0; 2], 0.0);
                for &el in &run {
                    mesh.gather(q, el, &mut e);
                    mesh.gather(v, el, &mut ed);
                    mesh.elements()[el].elastic_forces(&e, &mut qe);
                    self.element_damping(&e, &ed, &mut qd, None);
                    let g = |i: usize| [qe[i] + qd[i], qe[i + 1] + qd[i + 1]];
                    let at = |i: usize| [e[i], e[i + 1]];
                    // the force the material ahead exerts on the material behind: the element's
                    // own at its start, minus the element's own at its end
                    for (sign, o) in [(1.0, 0), (-1.0, 6)] {
                        let (fo, p) = (g(o), at(o));
                        let mo = cross(at(o + 2), g(o + 2)) + cross(at(o + 4), g(o + 4));
                        f[0] += sign * fo[0];
                        f[1] += sign * fo[1];
                        m += sign * (cross(p, fo) + mo);
                        // ṁ ṙ through a fixed section at this node
                        let (rd, rx) = ([ed[o], ed[o + 1]], at(o + 2));
                        let mdot = mass_flow(rho_a, rd, rx);
                        let phi = [mdot * rd[0], mdot * rd[1]];
                        flux[0] += phi[0];
                        flux[1] += phi[1];
                        mflux += cross(p, phi);
                    }
                }
                let n = 2.0 * run.len() as f64;
                let line = |g: [f64; 2], m: f64| {
                    belt::LineOfAction::of_resultant([g[0] / n, g[1] / n], m / n, sp.direction)
                };
                (line(f, m).map(|l| l.1), line(flux, mflux))
            })
            .collect()
    }

    /// The axial damping forces of one element with coordinates `e` and rates `ed`
    /// ([`Self::axial_damping`]) written into `qd`, and with `tangent` its local Jacobians
    /// (both overwritten).
    fn element_damping(
        &self, e: &[f64; NE], ed: &[f64; NE], qd: &mut [f64; NE],
        mut tangent: Option<(&mut [f64; NE * NE], &mut [f64; NE * NE])>,
    ) {
        qd.fill(0.0);
        if let Some((kl, cl)) = tangent.as_mut() {
            kl.fill(0.0);
            cl.fill(0.0);
        }
        let b = &self.spec.belt;
        if b.axial_damping <= 0.0 {
            return;
        }
        let coef = b.axial_damping * b.alpha1 * b.young * b.width * b.thickness;
        let l = self.element_length();
        // `S_x` of the slope blocks `r_y` vanishes on the centreline (`y = 0`): only the
        // centre blocks contribute, the others' rows and columns stay zero
        const CENTRE: [usize; 4] = [0, 1, 3, 4];
        for &(w, sx) in &self.kind.damping_points {
            let (mut rx, mut rxd) = ([0.0; 2], [0.0; 2]);
            for a in CENTRE {
                for c in 0..2 {
                    rx[c] += sx[a] * e[2 * a + c];
                    rxd[c] += sx[a] * ed[2 * a + c];
                }
            }
            let rate = rx[0] * rxd[0] + rx[1] * rxd[1];
            // g = 1/a and g'/g = −1/a for the linear law (doc of `axial_damping`)
            let (g, dlog) = match b.law {
                ::belt::MaterialLaw::StVenantKirchhoff => (1.0, 0.0),
                ::belt::MaterialLaw::Linear => {
                    let a = rx[0] * rx[0] + rx[1] * rx[1];
                    (1.0 / a, -1.0 / a)
                }
            };
            let wl = w * l * coef * g;
            for a in CENTRE {
                for c in 0..2 {
                    qd[2 * a + c] -= wl * sx[a] * rx[c] * rate;
                }
            }
            if let Some((kl, cl)) = tangent.as_mut() {
                // the 2 × 2 factors of the point, each product formed as before
                let mut kf = [[0.0; 2]; 2];
                for (c, kc) in kf.iter_mut().enumerate() {
                    for (d, k) in kc.iter_mut().enumerate() {
                        let delta = if c == d { rate } else { 0.0 };
                        *k = delta + rx[c] * rxd[d] + 2.0 * dlog * rate * rx[c] * rx[d];
                    }
                }
                for bb in CENTRE {
                    for a in CENTRE {
                        let ss = wl * sx[a] * sx[bb];
                        for d in 0..2 {
                            let col = 2 * bb + d;
                            for c in 0..2 {
                                let row = 2 * a + c;
                                kl[row + col * NE] += ss * kf[c][d];
                                cl[row + col * NE] += ss * rx[c] * rx[d];
                            }
                        }
                    }
                }
            }
        }
    }

    /// Power dissipated by the belt's Kelvin–Voigt axial damping at `(q, v)` \[W\]:
    /// `−Σ Q_dᵀ ė` over the elements (`axial_damping`), `∫ N_d ε̇ dx ≥ 0` (the belt's
    /// only non-conservative force besides the contact; issue 34 power balance). Zero without
    /// axial damping.
    pub fn damping_dissipation(&self, q: &[f64], v: &[f64]) -> f64 {
        if self.spec.belt.axial_damping <= 0.0 {
            return 0.0;
        }
        let (mut e, mut ed, mut qd) = ([0.0; NE], [0.0; NE], [0.0; NE]);
        let mut p = 0.0;
        for el in 0..self.kind.mesh.elements().len() {
            self.kind.mesh.gather(q, el, &mut e);
            self.kind.mesh.gather(v, el, &mut ed);
            self.element_damping(&e, &ed, &mut qd, None);
            p -= qd.iter().zip(&ed).map(|(a, b)| a * b).sum::<f64>();
        }
        p
    }

    /// Viscous axial force \[N\] of the Kelvin–Voigt axial damping
    /// ([`super::BeltSpec::axial_damping`]) at `ξ` of element `el` at
    /// `(q, v)`: `N_d = β α₁EA λ ε̇_G = β α₁EA λ (r_xᵀṙ_x)` (St Venant–Kirchhoff) or
    /// `β α₁EA λ̇ = β α₁EA (r_xᵀṙ_x)/λ` (linear law). It adds to the elastic force
    /// ([`crate::element::BeltElement::axial_force`]) wherever the belt's strain changes in time:
    /// in a steady drive along the slip arcs (`ε̇ = v dε/ds`, ≈ 45 N on Table 6-1's driver wrap
    /// at 42 N·m with β = 1.8 ms), not in the spans.
    pub fn viscous_axial_force(&self, q: &[f64], v: &[f64], el: usize, xi: f64) -> f64 {
        let b = &self.spec.belt;
        if b.axial_damping <= 0.0 {
            return 0.0;
        }
        let coef = b.axial_damping * b.alpha1 * b.young * b.width * b.thickness;
        let l = self.element_length();
        let sx = shape::cubic(l, xi * l, 0.0).sx;
        let mut e = [0.0; NE];
        let mut ed = [0.0; NE];
        self.kind.mesh.gather(q, el, &mut e);
        self.kind.mesh.gather(v, el, &mut ed);
        let (mut rx, mut rxd) = ([0.0; 2], [0.0; 2]);
        for a in 0..6 {
            for c in 0..2 {
                rx[c] += sx[a] * e[2 * a + c];
                rxd[c] += sx[a] * ed[2 * a + c];
            }
        }
        let lam = rx[0].hypot(rx[1]);
        let rate = rx[0] * rxd[0] + rx[1] * rxd[1];
        match b.law {
            ::belt::MaterialLaw::StVenantKirchhoff => coef * lam * rate,
            ::belt::MaterialLaw::Linear => coef * rate / lam,
        }
    }

    /// Generalized contact force `Q_c` (3.27) of element `el` (coordinates `e`, rates `ed`) on
    /// every pulley, at the pulleys' travel-sense speeds `omegas`, integrated with `line`'s
    /// rule (summed over the pulleys into `out`).
    fn element_contact_force(
        &self, line: &LineContact<Disk, BeltNormal, BeltFriction>, (q, v): (&[f64], &[f64]),
        omegas: &[f64], (e, ed): (&[f64; NE], &[f64; NE]), ec: &mut ElementContact<2>,
        out: &mut [f64; NE],
    ) {
        let l = self.element_length();
        out.fill(0.0);
        for (p, &omega) in omegas.iter().enumerate() {
            let disk = self.disk(p, omega, q, v);
            if !self.may_touch(e, p, [disk.center.x, disk.center.y]) {
                continue;
            }
            line.element_on(
                &disk,
                &self.kind.friction[p],
                l,
                6,
                |xi, s| s[..6].copy_from_slice(&shape::cubic(l, xi * l, 0.0).s),
                e,
                ed,
                false,
                ec,
                None,
            );
            if ec.active_points > 0 {
                for (o, qc) in out.iter_mut().zip(&ec.q) {
                    *o += qc;
                }
            }
        }
    }

    /// The belt's section force recovered from equilibrium at `(q, v)` with the pulleys at the
    /// travel-sense speeds `omegas` \[rad/s\] ([`SectionForces`]: issue 34, a smooth axial force
    /// along the wraps).
    pub fn section_forces<'a>(
        &'a self, q: &'a [f64], v: &'a [f64], omegas: &[f64],
    ) -> SectionForces<'a> {
        SectionForces::new(self, q, v, omegas)
    }
}

/// The belt's section force `F(x)` (the force the material ahead of a section exerts on the
/// material behind it \[N\]; tension is `N = F·t > 0`) recovered from equilibrium, a stress
/// recovery for the axial force along the wraps (issue 34).
///
/// The axial strain of the cubic elements (Kerkkänen (3.11)) oscillates within an element
/// where the belt wraps a pulley under the penalty contact (3.20): the element cannot follow
/// the jump of curvature at the inlet and exit of a wrap without stretching, and with an
/// axially stiff belt (`EA` ≫ `k_p l²`) a few µm of radial ripple mean a few hundred newtons
/// of axial force. The element's own force ([`crate::element::BeltElement::axial_force`]) at a
/// point carries that ripple; the forces the element transmits do not, because they are fixed
/// by equilibrium:
///
/// 1. **Nodes.** The section force at the ends of element `k` follows from its weak
///    equilibrium with the shape functions as virtual displacements (the consistent end forces
///    of the position rows, as reactions are recovered in finite elements):
///    `F_k(0) = (Q_e + Q_d + Q_c)_{r_I}`, `F_k(l) = −(Q_e + Q_d + Q_c)_{r_J}` (elastic forces
///    (2.20), axial damping, contact (3.27) with the model's Gauss rule; the belt's inertia is
///    neglected: at most `ρA v² κ l` ≈ 0.6 N on Table 6-1, normal to the belt). Where the
///    equations of motion hold, `F_{k−1}(l) = F_k(0)` up to that inertia; their mean is the
///    nodal force `F_n`.
/// 2. **Inside an element.** `F' = −f` (the contact force density on the belt per unit
///    material length, Kerkkänen (3.20)–(3.23)), integrated from the left node with the
///    midpoint rule on [`SECTION_CELLS`] cells per element, plus the linear share `ξ Δ_k` of
///    the element's equilibrium defect `Δ_k = F_n(J) − F_n(I) + ∫₀ˡ f dx` (the difference of
///    the model's Gauss rule and the fine integral, and the neglected inertia), so that the
///    field is continuous and takes the nodal values at the nodes.
///
/// The axial force is `N = F·t`, `t = r_x/‖r_x‖`. In a straight span without contact it
/// equals the element's own force; along a wrap it satisfies the tangential equilibrium
/// `dN/ds = −f_t + Q κ` pointwise (`Q` the shear force, only in the bending boundary layers),
/// so the capstan law can be checked point by point.
pub struct SectionForces<'a> {
    drive: &'a BeltDrive,
    q: &'a [f64],
    v: &'a [f64],
    omegas: Vec<f64>,
    nodal: Vec<[f64; 2]>,
    defect: Vec<[f64; 2]>,
}

/// Mass flow \[kg/s\] of the belt through a section fixed in space at a material point with
/// velocity `rd` \[m/s\] and slope `rx` (`∂r/∂x`, `x` the unstretched arc length), for a mass
/// `rho_a` \[kg/m\] per unstretched length: the material label passes the section at
/// `ẋ = (ṙ·t)/‖r_x‖` (from `(r_x ẋ + ṙ)·t = 0`), so `ṁ = ρA (ṙ·r_x)/‖r_x‖²`, `ρA v/λ` for a
/// belt stretched by `λ` moving at `v` along itself.
fn mass_flow(rho_a: f64, rd: [f64; 2], rx: [f64; 2]) -> f64 {
    rho_a * (rd[0] * rx[0] + rd[1] * rx[1]) / (rx[0] * rx[0] + rx[1] * rx[1])
}

/// What [`BeltDrive::span_force_lines`] gives per span: the line of action of the section
/// force (`None` where the belt does not cross the span's bisector) and the momentum flux `ṁ v`
/// \[N\] with its line ([`belt::SpanState::momentum_flux`]).
pub type SpanSection = (
    Option<belt::LineOfAction>,
    Option<(f64, belt::LineOfAction)>,
);

/// Midpoint cells per element of the fine integral of the contact force density in
/// [`SectionForces`].
pub const SECTION_CELLS: usize = 96;

impl<'a> SectionForces<'a> {
    fn new(drive: &'a BeltDrive, q: &'a [f64], v: &'a [f64], omegas: &[f64]) -> Self {
        let n_el = drive.kind.mesh.elements().len();
        let mut e = [0.0; NE];
        let mut ed = [0.0; NE];
        let mut qe = [0.0; NE];
        let mut qd = [0.0; NE];
        let mut qc = [0.0; NE];
        let mut ec = ElementContact::new(NE);
        let mut ends = vec![[[0.0; 2]; 2]; n_el];
        for (el, end) in ends.iter_mut().enumerate() {
            drive.kind.mesh.gather(q, el, &mut e);
            drive.kind.mesh.gather(v, el, &mut ed);
            drive.kind.mesh.elements()[el].elastic_forces(&e, &mut qe);
            drive.element_damping(&e, &ed, &mut qd, None);
            drive.element_contact_force(
                &drive.kind.line,
                (q, v),
                omegas,
                (&e, &ed),
                &mut ec,
                &mut qc,
            );
            for c in 0..2 {
                end[0][c] = qe[c] + qd[c] + qc[c];
                end[1][c] = -(qe[6 + c] + qd[6 + c] + qc[6 + c]);
            }
        }
        let nodal: Vec<[f64; 2]> = (0..n_el)
            .map(|k| {
                let prev = ends[(k + n_el - 1) % n_el][1];
                let next = ends[k][0];
                [0.5 * (prev[0] + next[0]), 0.5 * (prev[1] + next[1])]
            })
            .collect();
        let mut out = Self {
            drive,
            q,
            v,
            omegas: omegas.to_vec(),
            nodal,
            defect: vec![[0.0; 2]; n_el],
        };
        for k in 0..n_el {
            let g = out.integral(k, 1.0);
            let (fi, fj) = (out.nodal[k], out.nodal[(k + 1) % n_el]);
            out.defect[k] = [fj[0] - fi[0] + g[0], fj[1] - fi[1] + g[1]];
        }
        out
    }

    /// `∫₀^{ξl} f dx` \[N\] over element `el` (midpoint rule, `⌈SECTION_CELLS ξ⌉` cells).
    fn integral(&self, el: usize, xi: f64) -> [f64; 2] {
        let d = self.drive;
        let m = (SECTION_CELLS as f64 * xi).ceil().max(1.0) as usize;
        let mut e = [0.0; NE];
        let mut ed = [0.0; NE];
        d.kind.mesh.gather(self.q, el, &mut e);
        d.kind.mesh.gather(self.v, el, &mut ed);
        let line = LineContact {
            surface: d.kind.line.surface,
            normal: d.kind.line.normal,
            friction: d.kind.line.friction,
            rule: GaussRule {
                points: (0..m).map(|c| (c as f64 + 0.5) * xi / m as f64).collect(),
                weights: vec![xi / m as f64; m],
            },
        };
        let mut ec = ElementContact::new(NE);
        let mut qc = [0.0; NE];
        d.element_contact_force(
            &line,
            (self.q, self.v),
            &self.omegas,
            (&e, &ed),
            &mut ec,
            &mut qc,
        );
        // the cubic shape functions' partition of unity on the positions (S₁ + S₄ = 1 at y = 0)
        [qc[0] + qc[6], qc[1] + qc[7]]
    }

    /// Recovered section force `F` \[N\] at `ξ ∈ [0, 1]` of element `el`.
    pub fn force(&self, el: usize, xi: f64) -> [f64; 2] {
        let fi = self.nodal[el];
        let g = self.integral(el, xi);
        let dk = self.defect[el];
        [fi[0] - g[0] + xi * dk[0], fi[1] - g[1] + xi * dk[1]]
    }

    /// Recovered axial force `N = F·t` \[N\] at `ξ` of element `el`.
    pub fn axial(&self, el: usize, xi: f64) -> f64 {
        let f = self.force(el, xi);
        let l = self.drive.element_length();
        let sx = shape::cubic(l, xi * l, 0.0).sx;
        let mut e = [0.0; NE];
        self.drive.kind.mesh.gather(self.q, el, &mut e);
        let mut rx = [0.0; 2];
        for a in 0..6 {
            rx[0] += sx[a] * e[2 * a];
            rx[1] += sx[a] * e[2 * a + 1];
        }
        let n = rx[0].hypot(rx[1]);
        (f[0] * rx[0] + f[1] * rx[1]) / n
    }

    /// Section force at every node \[N\] (the mean of the two elements' end forces).
    pub fn nodal(&self) -> &[[f64; 2]] {
        &self.nodal
    }

    /// Largest element equilibrium defect `|Δ_k|` \[N\] (see the type's documentation).
    pub fn max_defect(&self) -> f64 {
        self.defect
            .iter()
            .map(|d| d[0].hypot(d[1]))
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: the loops of `element_damping` before they skipped the slope blocks (all six
    // blocks of `S_x`, the 2 × 2 factor formed inside the innermost loop), bit for bit.
    #[test]
    fn element_damping_without_slope_blocks_is_the_full_loops_bit_for_bit() {
        for law in [
            ::belt::MaterialLaw::StVenantKirchhoff,
            ::belt::MaterialLaw::Linear,
        ] {
            let mut spec = BeltDriveSpec::default();
            spec.belt.law = law;
            if spec.belt.axial_damping <= 0.0 {
                spec.belt.axial_damping = 1e-4;
            }
            let drive = BeltDrive::new(spec).unwrap();
            let e: [f64; NE] = std::array::from_fn(|i| 0.3 * (i as f64 * 0.7).sin() + 0.9);
            let ed: [f64; NE] = std::array::from_fn(|i| 2.0 * (i as f64 * 1.3).cos());
            let (mut qd, mut kl, mut cl) = ([0.0; NE], [0.0; NE * NE], [0.0; NE * NE]);
            drive.element_damping(&e, &ed, &mut qd, Some((&mut kl, &mut cl)));
            let b = &drive.spec.belt;
            let coef = b.axial_damping * b.alpha1 * b.young * b.width * b.thickness;
            let l = drive.element_length();
            let (mut q0, mut k0, mut c0) = ([0.0; NE], [0.0; NE * NE], [0.0; NE * NE]);
            for &(w, sx) in &drive.kind.damping_points {
                let (mut rx, mut rxd) = ([0.0; 2], [0.0; 2]);
                for a in 0..6 {
                    for c in 0..2 {
                        rx[c] += sx[a] * e[2 * a + c];
                        rxd[c] += sx[a] * ed[2 * a + c];
                    }
                }
                let rate = rx[0] * rxd[0] + rx[1] * rxd[1];
                let (g, dlog) = match law {
                    ::belt::MaterialLaw::StVenantKirchhoff => (1.0, 0.0),
                    ::belt::MaterialLaw::Linear => {
                        let a = rx[0] * rx[0] + rx[1] * rx[1];
                        (1.0 / a, -1.0 / a)
                    }
                };
                let wl = w * l * coef * g;
                for a in 0..6 {
                    for c in 0..2 {
                        q0[2 * a + c] -= wl * sx[a] * rx[c] * rate;
                    }
                }
                for bb in 0..6 {
                    for d in 0..2 {
                        for a in 0..6 {
                            for c in 0..2 {
                                let (row, col) = (2 * a + c, 2 * bb + d);
                                let ss = wl * sx[a] * sx[bb];
                                let delta = if c == d { rate } else { 0.0 };
                                k0[row + col * NE] += ss
                                    * (delta + rx[c] * rxd[d] + 2.0 * dlog * rate * rx[c] * rx[d]);
                                c0[row + col * NE] += ss * rx[c] * rx[d];
                            }
                        }
                    }
                }
            }
            assert!(q0.iter().zip(&qd).all(|(a, b)| a == b), "{law:?} forces");
            assert!(k0.iter().zip(&kl).all(|(a, b)| a == b), "{law:?} stiffness");
            assert!(c0.iter().zip(&cl).all(|(a, b)| a == b), "{law:?} damping");
            assert!(k0.iter().any(|&v| v != 0.0) && c0.iter().any(|&v| v != 0.0));
        }
    }

    // Invariant behind `axial_damping`'s `Pattern::add_element_on`: the local Jacobians of
    // `element_damping` are zero (`+0`) in the rows and columns outside `CENTRE_COORDS` (the
    // slope blocks), for both laws, so adding only the centre entries gives the full add's bits.
    #[test]
    fn element_damping_jacobians_vanish_outside_the_centre_coordinates() {
        for law in [
            ::belt::MaterialLaw::StVenantKirchhoff,
            ::belt::MaterialLaw::Linear,
        ] {
            let mut spec = BeltDriveSpec::default();
            spec.belt.law = law;
            spec.belt.axial_damping = spec.belt.axial_damping.max(1e-4);
            let drive = BeltDrive::new(spec).unwrap();
            let e: [f64; NE] = std::array::from_fn(|i| 0.3 * (i as f64 * 0.7).sin() + 0.9);
            let ed: [f64; NE] = std::array::from_fn(|i| 2.0 * (i as f64 * 1.3).cos());
            let (mut qd, mut kl, mut cl) = ([0.0; NE], [1.0; NE * NE], [1.0; NE * NE]);
            drive.element_damping(&e, &ed, &mut qd, Some((&mut kl, &mut cl)));
            for col in 0..NE {
                for row in 0..NE {
                    let inside = CENTRE_COORDS.contains(&row) && CENTRE_COORDS.contains(&col);
                    for (name, m) in [("stiffness", &kl), ("damping", &cl)] {
                        let v = m[row + col * NE];
                        if inside {
                            continue;
                        }
                        assert_eq!(
                            v.to_bits(),
                            0.0f64.to_bits(),
                            "{law:?} {name} ({row}, {col})"
                        );
                    }
                }
            }
            assert!(CENTRE_COORDS.iter().any(|&i| kl[i + i * NE] != 0.0));
        }
    }

    // Reference: the local matrices as filled before (all `m × m` entries cleared, then the
    // pair's entries written). `contact_local_matrices` clears and fills only its `local` rows
    // and columns: on a drive with a free idler on a tensioner arm and a free driven pulley,
    // in every element–pulley pair of a sliding state, (1) the old fill is `+0` outside
    // `local × local` (so `Pattern::add_element_on` adds the same bits as the full add) and
    // (2) inside it the new fill, started from garbage, has the old fill's bits.
    #[test]
    fn contact_local_matrices_fill_only_their_rows_and_columns() {
        let mut spec = BeltDriveSpec::two_pulley(
            0.08125,
            0.06,
            ::belt::Signal::constant(0.0),
            ::belt::Signal::constant(0.0),
        );
        spec.contact.friction = BeltFriction::Tanh {
            mu: 0.5,
            kappa: 40.0,
        };
        let c1 = spec.pulleys[1].center;
        let tensioner = Tensioner {
            pulley: 1,
            pivot: [c1[0] + 0.05, c1[1] - 0.04],
            stiffness: 20.0,
            preload: 0.0,
            preload_angle: 0.0,
            damping: 0.1,
            dry_friction: 0.0,
            friction_rate: 0.01,
            inertia: 1e-3,
            travel: [1.5, 3.5],
        };
        let drive = BeltDrive::with_tensioner(spec, tensioner).unwrap();
        let q = drive.placed_coordinates();
        let n = q.len();
        // pressed into the wraps: every belt coordinate pulled towards the pulleys' centres
        // would need a solve; a small radial scale of the placed belt does it exactly
        let cx = 0.5 * (drive.spec.pulleys[0].center[0] + c1[0]);
        let mut q = q;
        let cpn = drive.mesh().coords_per_node();
        for node in 0..drive.mesh().n_nodes() {
            let i = cpn * node;
            q[i] = cx + 0.999 * (q[i] - cx);
            q[i + 1] *= 0.995;
        }
        let v: Vec<f64> = (0..n).map(|i| 0.05 * ((i as f64) * 0.37).sin()).collect();
        let omegas = [30.0, 29.0];
        let arm = drive.kind.arm.map(|a| (a, drive.arm_lever(&a, &q)));
        assert!(arm.is_some() && drive.pulley_dofs.dof(1).is_some());
        let mut ws = Workspace::new();
        let scratch = drive.scratch(&mut ws);
        let m = scratch.k_local.len().isqrt();
        let mut pairs = [0usize; 2];
        drive.contact_pass(&q, &v, &omegas, true, scratch, |_, p, ec, s| {
            pairs[p] += 1;
            s.k_local.fill(0.0);
            s.c_local.fill(0.0);
            let (local, nl) = drive.contact_local_matrices(p, ec, arm, &q, &v, s);
            let (old_k, old_c) = (s.k_local.clone(), s.c_local.clone());
            let local = &local[..nl];
            assert_eq!(nl, if p == 1 { NE + 2 } else { NE });
            for b in 0..m {
                for a in 0..m {
                    if !(local.contains(&a) && local.contains(&b)) {
                        assert_eq!(old_k[a + b * m].to_bits(), 0.0f64.to_bits());
                        assert_eq!(old_c[a + b * m].to_bits(), 0.0f64.to_bits());
                    }
                }
            }
            s.k_local.fill(f64::NAN);
            s.c_local.fill(f64::NAN);
            let (again, _) = drive.contact_local_matrices(p, ec, arm, &q, &v, s);
            assert_eq!(&again[..nl], local);
            for &b in local {
                for &a in local {
                    let i = a + b * m;
                    assert_eq!(
                        s.k_local[i].to_bits(),
                        old_k[i].to_bits(),
                        "p {p} ({a}, {b})"
                    );
                    assert_eq!(
                        s.c_local[i].to_bits(),
                        old_c[i].to_bits(),
                        "p {p} ({a}, {b})"
                    );
                }
            }
        });
        assert!(
            pairs[0] > 0 && pairs[1] > 0,
            "contact on both pulleys: {pairs:?}"
        );
    }

    // Reference: the closed form of a rigid rotation. A belt on a circle of its own length
    // (radius R = N l/2π, unstretched) spinning at ω is a steady flow of its material: over h
    // every node turns by ωh, r = R(cos φ, sin φ), r_x = (−sin φ, cos φ), r_y = (cos φ, sin φ).
    // The convected prediction lands there within the cubic interpolation error (l/R = 2π/N).
    // Reference: mass conservation in closed form. A belt stretched by λ whose material moves
    // at v along itself carries ρA/λ per metre of its length past a fixed section, ṁ = ρA v/λ;
    // a velocity across the belt carries none.
    #[test]
    fn mass_flow_through_a_fixed_section_is_rho_a_v_over_lambda() {
        let (rho_a, v, lambda) = (0.096, 19.6, 1.0028);
        let t = [0.6, 0.8];
        let rx = [lambda * t[0], lambda * t[1]];
        let along = mass_flow(rho_a, [v * t[0], v * t[1]], rx);
        assert!(
            (along - rho_a * v / lambda).abs() < 1e-15 * rho_a * v,
            "{along}"
        );
        let across = mass_flow(rho_a, [-v * t[1], v * t[0]], rx);
        assert!(across.abs() < 1e-15 * rho_a * v, "{across}");
    }

    #[test]
    fn convected_increment_reproduces_a_rigid_rotation() {
        let drive = BeltDrive::new(BeltDriveSpec::default()).unwrap();
        let nb = drive.n_belt();
        let nodes = nb / 6;
        let l = drive.element_length();
        let radius = nodes as f64 * l / std::f64::consts::TAU;
        let (omega, h) = (400.0, 2.5e-4);
        let node = |phi: f64, rate: f64, accel: f64| {
            let (s, c) = phi.sin_cos();
            // position, slope and section vectors and their time derivatives at speed `rate`
            [
                [radius * c, radius * s, -s, c, c, s],
                [-rate * radius * s, rate * radius * c, 0.0, 0.0, 0.0, 0.0],
                [-accel * radius * c, -accel * radius * s, 0.0, 0.0, 0.0, 0.0],
            ]
        };
        let n = drive.n_q();
        let (mut q, mut v, mut vdot, mut exact) =
            (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for k in 0..nodes {
            let phi = k as f64 * l / radius;
            let [a, b, c] = node(phi, omega, omega * omega);
            let end = node(phi + omega * h, omega, omega * omega)[0];
            q[6 * k..6 * k + 6].copy_from_slice(&a);
            v[6 * k..6 * k + 6].copy_from_slice(&b);
            vdot[6 * k..6 * k + 6].copy_from_slice(&c);
            exact[6 * k..6 * k + 6].copy_from_slice(&end);
        }
        // the integrator's own prediction stays on the pulley coordinates
        let mut dq = vec![7.0; n];
        assert!(drive.convected_increment(&q, &v, &vdot, h, &mut dq));
        assert!(dq[nb..].iter().all(|&x| x == 7.0));
        let (mut pos, mut slope) = (0.0f64, 0.0f64);
        for i in 0..nb {
            let err = (q[i] + dq[i] - exact[i]).abs();
            if i % 6 < 2 {
                pos = pos.max(err);
            } else {
                slope = slope.max(err);
            }
        }
        // the step moves the belt by ωRh (a third of an element); the prediction errs by the
        // cubic Hermite interpolation error of a circle of the element angle θ = l/R, at most
        // R θ⁴/384 in position and about θ³/72 in slope, where the constant-acceleration
        // predictor misses the slopes' turn ωh (0.1 rad) entirely
        let travel = omega * radius * h;
        let theta = l / radius;
        assert!(travel > 0.2 * l && travel < l, "{travel} of {l}");
        assert!(
            pos < radius * theta.powi(4) / 384.0,
            "position error {pos} m, R = {radius} m"
        );
        assert!(
            slope < theta.powi(3) / 72.0 && slope < 0.01 * omega * h,
            "slope error {slope}, turn {}",
            omega * h
        );
        // standing belt: no shift, no increment
        let mut dq0 = vec![0.0; n];
        assert!(drive.convected_increment(&q, &vec![0.0; n], &vec![0.0; n], h, &mut dq0));
        assert!(dq0.iter().all(|x| x.abs() < 1e-15));
    }

    /// The two-pulley drive of Kerkkänen Table 3.1 with the tanh law (κ = 40 s/m, the FEAD
    /// study's) and the driver held at rest, in its static equilibrium (the belt pressed into
    /// both wraps): `(drive, q, free pulley's coordinate, its radius, the law's width)`.
    fn tanh_drive_at_rest() -> (BeltDrive, Vec<f64>, usize, f64, f64) {
        let mut spec = BeltDriveSpec::two_pulley(
            0.08125,
            0.08125,
            ::belt::Signal::constant(0.0),
            ::belt::Signal::constant(0.0),
        );
        spec.contact.friction = BeltFriction::Tanh {
            mu: 0.5,
            kappa: 40.0,
        };
        let drive = BeltDrive::new(spec).unwrap();
        let q = drive
            .initial_state(&crate::mounted::InitialOptions::default())
            .unwrap()
            .q;
        let j = drive.pulley_dofs.dof(1).unwrap();
        let w = contact::FrictionLaw::transition_width(drive.friction_law(1)).unwrap();
        let r = drive.spec.pulleys[1].radius;
        (drive, q, j, r, w)
    }

    // Reference: the full snapshot (`post::snapshot`). The report's snapshot leaves out only
    // the wrap points' recovered tension: pulleys, spans and every other field of every wrap
    // point are the same to the bit, on a moving state with the belt sliding on both wraps.
    #[test]
    fn report_snapshot_is_the_snapshot_without_wrap_tensions() {
        let (drive, q, _, _, _) = tanh_drive_at_rest();
        let n = q.len();
        let v: Vec<f64> = (0..n).map(|i| 0.01 * ((i as f64) * 0.37).sin()).collect();
        let omegas = [30.0, 29.5];
        let full = super::super::post::snapshot(&drive, 0.1, &q, &v, &omegas);
        let lean = super::super::post::snapshot_with(&drive, 0.1, &q, &v, &omegas, false);
        assert_eq!(full.pulleys, lean.pulleys);
        assert_eq!(full.spans, lean.spans);
        assert_eq!(full.belt_dissipation, lean.belt_dissipation);
        assert!(!full.wrap.is_empty());
        assert_eq!(full.wrap.len(), lean.wrap.len());
        for (a, b) in full.wrap.iter().zip(&lean.wrap) {
            assert!(a.tension.is_finite() && b.tension.is_nan());
            let strip = |w: &::belt::WrapPoint| ::belt::WrapPoint { tension: 0.0, ..*w };
            assert_eq!(strip(a), strip(b));
        }
    }

    // Reference: the closed form. With the belt and the driver at rest every slip velocity is
    // zero, and spinning the free pulley by Δω changes the slip of every point on its wrap by
    // exactly Δω R (the disk's surface speed) and of no other point: a point inside the band
    // leaving it stops at 2w, α = 2w/(|Δω| R); a point sliding at ω₀R reversed by −2ω₀ lands
    // at w/2 on its own side, α = (|ω₀| R − w/2)/(2|ω₀| R).
    #[test]
    fn transition_limit_of_a_spinning_pulley_is_the_closed_form() {
        let (drive, q, j, r, w) = tanh_drive_at_rest();
        let n = q.len();
        let on_wrap = drive
            .contact_records_with(&q, &vec![0.0; n], &[0.0, 0.0])
            .iter()
            .filter(|p| p.pulley == 1)
            .count();
        assert!(on_wrap > 5, "{on_wrap} points on the free pulley's wrap");
        let mut ws = Workspace::new();
        let zero = vec![0.0; n];
        // inside the band, leaving it
        for dw in [3.0, -1.7, 40.0] {
            let mut dv = vec![0.0; n];
            dv[j] = dw;
            let a = drive.transition_limit(0.0, &q, &zero, &zero, &dv, &mut ws);
            let want = 2.0 * w / (dw.abs() * r);
            assert!((a - want).abs() < 1e-12 * want, "{dw}: {a} against {want}");
            assert_eq!(
                <BeltDrive as SecondOrderSystem>::correction_limit(
                    &drive, 0.0, &q, &zero, &zero, &dv, &mut ws
                )
                .unwrap(),
                a
            );
        }
        // inside the band, staying within 2w: the whole correction
        let mut dv = vec![0.0; n];
        dv[j] = 1.9 * w / r;
        assert_eq!(
            drive.transition_limit(0.0, &q, &zero, &zero, &dv, &mut ws),
            1.0
        );
        // sliding, reversed across the band
        for w0 in [2.0, -5.0] {
            let mut v = vec![0.0; n];
            v[j] = w0;
            let mut dv = vec![0.0; n];
            dv[j] = -2.0 * w0;
            let a = drive.transition_limit(0.0, &q, &v, &zero, &dv, &mut ws);
            let want = (w0.abs() * r - 0.5 * w) / (2.0 * w0.abs() * r);
            assert!((a - want).abs() < 1e-12, "{w0}: {a} against {want}");
        }
        // a law without a band is not limited
        let creep = drive
            .with_pulley_friction(vec![
                BeltFriction::CreepRate {
                    mu: 0.5,
                    creep: 1e4,
                };
                2
            ])
            .unwrap();
        assert_eq!(
            creep.transition_limit(0.0, &q, &zero, &zero, &dv, &mut ws),
            1.0
        );
    }

    // Reference: the invariant the limit stands for, checked on the slip velocities of the
    // limited state read from the output path (`contact_records_with`). With `Δq = 0` the
    // contact set and the tangents are fixed and the slip is affine in `v`, so at
    // `v + αΔv`: no point sliding at the iterate (|v_t| > w) is past `w/2` on the other side
    // of zero, no point inside the band is beyond `2w`, and one point sits on its bound (α is
    // the largest such fraction).
    #[test]
    fn limited_slip_velocities_stop_at_the_band() {
        let (drive, q, j, r, w) = tanh_drive_at_rest();
        let n = q.len();
        let nb = drive.n_belt;
        let mut ws = Workspace::new();
        // belt travelling at 10 m/s over the driver at rest (sliding) and the free pulley
        // rolling with its wrap's median slip zero (the interpolated belt velocity is not
        // tangent between the nodes: half its points inside the band)
        let mut v = drive.travelling_velocity(&q, 10.0);
        let omegas = |v: &[f64]| [0.0, v[j]];
        let mut wrap: Vec<f64> = drive
            .contact_records_with(&q, &v, &omegas(&v))
            .iter()
            .filter(|p| p.pulley == 1)
            .map(|p| p.slip)
            .collect();
        wrap.sort_by(f64::total_cmp);
        v[j] += wrap[wrap.len() / 2] / r;
        let before = drive.contact_records_with(&q, &v, &omegas(&v));
        let sliding = before.iter().filter(|p| p.slip.abs() > w).count();
        let inside = before.len() - sliding;
        assert!(
            sliding > 10 && inside > 0,
            "{sliding} sliding, {inside} inside"
        );
        for seed in 0..4_u32 {
            let mut dv = vec![0.0; n];
            for (i, d) in dv.iter_mut().enumerate().take(nb) {
                *d = 0.3 * (((i as u32 * 7 + seed * 13) % 11) as f64 - 5.0);
            }
            dv[j] = -0.5 * v[j] * (seed as f64 - 1.5);
            let a = drive.transition_limit(0.0, &q, &v, &vec![0.0; n], &dv, &mut ws);
            assert!(a > 0.0 && a < 1.0, "{seed}: α = {a}");
            let va: Vec<f64> = v.iter().zip(&dv).map(|(x, d)| x + a * d).collect();
            let after = drive.contact_records_with(&q, &va, &omegas(&va));
            assert_eq!(after.len(), before.len());
            let mut slack = f64::INFINITY;
            for (p0, p1) in before.iter().zip(&after) {
                assert_eq!((p0.element, p0.pulley), (p1.element, p1.pulley));
                let (s0, s1) = (p0.slip, p1.slip);
                let (valid, gap) = if s0.abs() > w {
                    // sliding: on its own side beyond w/2, or (its full correction ending
                    // inside the band) within the band
                    let own = s0.signum() * s1;
                    (
                        own >= 0.5 * w - 1e-12 || s1.abs() <= w,
                        (own - 0.5 * w).abs(),
                    )
                } else {
                    (s1.abs() <= 2.0 * w + 1e-12, (s1.abs() - 2.0 * w).abs())
                };
                assert!(valid, "{seed}: {s0} → {s1} (w = {w})");
                slack = slack.min(gap);
            }
            assert!(slack < 1e-12, "{seed}: no point on its bound ({slack})");
        }
    }
}
