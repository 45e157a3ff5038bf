//! The plate-belt drive as one [`SecondOrderSystem`]: the belt's plate coordinates followed by
//! the rotation angles of the free pulleys, coupled through distributed penalty contact with
//! friction over the plate surface (Kerkkänen (4.43)–(4.45), laws (3.20), (3.23)) and the pulley
//! equations (3.26).

use super::spec::PlateDriveSpec;
use crate::belt_drive::BeltFriction;
use crate::belt_drive::friction::BeltNormal;
use crate::error::{AncfError, invalid};
use crate::material::Material;
use crate::mounted::{AncfBeltDrive, MAX_PULLEYS};
use crate::plate::mesh::{PLATE_NODE_COORDS, PlateCell, PlateMesh};
use crate::plate::{PLATE_NDOF, ThinPlate};
use crate::sparse::Pattern;
use belt::{BeltPath, Pulley};
use contact::distributed::MAX_BLOCKS;
use contact::spatial::{ContactRecord3, Cylinder, ElementContact3, FlangedCylinder, SurfacePoint3};
use contact::{BlockQuadrature, BlockShape, GaussRule, QuadPoint, Surface, SurfaceValues};
use faer::Mat;
use mbd_core::Workspace;
use mbd_core::system::ForceTangent;
use mbd_core::{SecondOrderSystem, SysMatrix};
use nalgebra::{Point3, Vector3};

/// Element coordinates.
const NE: usize = PLATE_NDOF;

/// A pulley's contact surface at one instant: a (crowned) cylinder, with or without flanges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PulleySurface {
    /// [`Cylinder`].
    Cylinder(Cylinder),
    /// [`FlangedCylinder`].
    Flanged(FlangedCylinder),
}

impl PulleySurface {
    /// The cylinder (of the flanged pulley).
    pub fn cylinder(&self) -> &Cylinder {
        match self {
            PulleySurface::Cylinder(c) => c,
            PulleySurface::Flanged(f) => &f.cylinder,
        }
    }
}

impl Surface<3> for PulleySurface {
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint3 {
        match self {
            PulleySurface::Cylinder(c) => c.closest(p),
            PulleySurface::Flanged(f) => f.closest(p),
        }
    }
    #[inline(always)]
    fn closest_value(&self, p: &Point3<f64>) -> SurfacePoint3 {
        match self {
            PulleySurface::Cylinder(c) => c.closest_value(p),
            PulleySurface::Flanged(f) => f.closest_value(p),
        }
    }
    fn closest_values(&self, p: &[Vec<f64>; 3], out: &mut SurfaceValues<3>) {
        match self {
            PulleySurface::Cylinder(c) => c.closest_values(p, out),
            PulleySurface::Flanged(f) => f.closest_values(p, out),
        }
    }
    fn center(&self) -> Point3<f64> {
        self.cylinder().center
    }
}

/// Per-call work buffers, kept in the caller's [`Workspace`] (see
/// [`PlateBeltDrive::scratch`]).
struct Scratch {
    /// The element contact buffer (taken during a contact pass; kept between calls so that
    /// the 20 kB buffer is not reallocated).
    ec: Option<ElementContact3>,
    k_local: Vec<f64>,
    c_local: Vec<f64>,
    fe: [f64; NE],
    ke: Mat<f64>,
    kl: Vec<f64>,
}

/// A three-dimensional belt drive with a thin-plate belt (see the module documentation of
/// [`super`]).
///
/// Coordinates `q = [e; θ]`: `e` the plate nodal coordinates (9 per node, 2 nodes per
/// cross-section — node `2i` on the edge `y = 0`, node `2i + 1` on `y = w` —, closed loop with a
/// shared first cross-section, Kerkkänen §2.3 option (b)), `θ` the travel-sense rotation
/// angles of the free pulleys in pulley order. Equations: `M ë = Q_e + Q_c` (2.27), (4.45), and
/// for each free pulley `I θ̈ = τ − T_a(t)` with `τ` the travel-sense contact torque, the
/// spatial (3.26). No gravity: the thesis never mentions it for its belt drives (seed note §11
/// item 27).
pub type PlateBeltDrive = AncfBeltDrive<Plate>;

/// The plate discretisation of an [`AncfBeltDrive`] ([`PlateBeltDrive`]): one row of thin-plate
/// elements (Kerkkänen (4.1)) in a closed loop and the distributed contact over the plate's
/// surface on the pulleys' cylinders.
pub struct Plate {
    pub(super) mesh: PlateMesh,
    /// Normal contact law per unit area (penalty (3.20) with damping).
    normal: BeltNormal,
    /// Friction law per unit area (creep-rate, §4.5).
    friction: BeltFriction,
    /// Contact quadrature: local `(x, y)` \[m\] and weight × area \[m²\] per point.
    quad: Vec<(f64, f64, f64)>,
    /// Shape-function values `S_k` at each contact point.
    quad_s: Vec<[f64; 12]>,
    /// Shape matrices `S = [S_k I₃]` (3 × 36) at each contact point.
    quad_shape: Vec<BlockShape>,
    /// The same quadrature as a batch (force-only contact evaluations).
    quad_blocks: BlockQuadrature,
}

/// Node index of cross-section `i` (mod `n`), edge `j` (0: `y = 0`, 1: `y = w`).
pub(crate) fn node(i: usize, j: usize, n: usize) -> usize {
    2 * (i % n) + j
}

impl PlateBeltDrive {
    /// Build the drive: validate `spec`, compute the path over the pulleys (initial centres),
    /// mesh the belt with `belt.elements` equal flat elements `length/n × width`, set up the
    /// sparse pattern (element blocks and element–pulley coupling blocks), the constant mass
    /// matrix (2.26) with the pulley inertias and the contact quadrature.
    pub fn new(spec: PlateDriveSpec) -> Result<Self, AncfError> {
        spec.validate()?;
        let path = BeltPath::new(&spec.pulleys)?;
        let (lp, lb) = (path.length(), spec.belt.length);
        if !(0.5 * lp..=1.5 * lp).contains(&lb) {
            return Err(invalid(
                "belt.length",
                format!("{lb} m is not within 50 % of the belt path length {lp:.6} m"),
            ));
        }
        let b = &spec.belt;
        let material = Material {
            young: b.young,
            poisson: b.poisson,
            density: b.density,
            shear_factor: 5.0 / 6.0,
        };
        let n = b.elements;
        let a = b.length / n as f64;
        let plate = ThinPlate::new(a, b.width, b.thickness, material, b.bending, b.gauss_points)?;
        let cells = (0..n)
            .map(|e| PlateCell {
                nodes: [
                    node(e, 0, n),
                    node(e + 1, 0, n),
                    node(e + 1, 1, n),
                    node(e, 1, n),
                ],
                plate: plate.clone(),
            })
            .collect();
        let mesh = PlateMesh {
            n_nodes: 2 * n,
            cells,
        };
        let rule = GaussRule::new(spec.contact.points);
        let across = GaussRule::new(spec.contact.points_across_for(&spec.pulleys));
        let mut quad = Vec::new();
        let mut quad_s = Vec::new();
        let mut quad_shape = Vec::new();
        for (eta, wy) in across.iter() {
            for (xi, wx) in rule.iter() {
                let (x, y) = (xi * a, eta * b.width);
                let s = plate.shape().eval(x, y).s;
                quad.push((x, y, wx * wy * a * b.width));
                quad_s.push(s);
                quad_shape.push(shape_matrix(&s));
            }
        }
        let normal = BeltNormal::penalty(spec.contact.stiffness, 0.0, spec.contact.damping);
        let friction = spec.contact.friction;
        let quad_blocks =
            BlockQuadrature::new(12, quad_s.iter().zip(&quad).map(|(s, q)| (&s[..], q.2)));
        let kind = Plate {
            mesh,
            normal,
            friction,
            quad,
            quad_s,
            quad_shape,
            quad_blocks,
        };
        Ok(Self::assemble(spec, path, kind, &[]))
    }

    /// The belt mesh.
    pub fn mesh(&self) -> &PlateMesh {
        &self.kind.mesh
    }
    /// Number of elements along the belt.
    pub fn n_elements(&self) -> usize {
        self.kind.mesh.cells.len()
    }
    /// Reference element length `a` \[m\].
    pub fn element_length(&self) -> f64 {
        self.kind.mesh.cells[0].plate.shape().a()
    }
    /// The contact surface of pulley `p` at time `t` \[s\] turning at the travel-sense speed
    /// `omega` \[rad/s\].
    pub fn surface(&self, p: usize, t: f64, omega: f64) -> PulleySurface {
        surface_of(&self.spec.pulleys[p], t, omega)
    }

    /// The coordinates of element `el`.
    fn element_dofs(&self, el: usize) -> [usize; NE] {
        let mesh = &self.kind.mesh;
        mesh.cell_dofs(&mesh.cells[el])
    }

    /// Mesh coordinates of element `el`.
    pub fn gather(&self, q: &[f64], el: usize, e: &mut [f64; NE]) {
        for (k, d) in self.element_dofs(el).iter().enumerate() {
            e[k] = q[*d];
        }
    }

    fn scatter_add(&self, f: &mut [f64], el: usize, qe: &[f64], scale: f64) {
        for (k, d) in self.element_dofs(el).iter().enumerate() {
            f[*d] += scale * qe[k];
        }
    }

    /// Whether element `e` may touch the surface of `pulley` (axis point `c`, radius `r`): the
    /// element is skipped when all four corner nodes lie farther than the element's chord from
    /// the cylinder (Kerkkänen §3.2's pre-check).
    fn may_touch(&self, e: &[f64; NE], surf: &PulleySurface) -> bool {
        let cyl = surf.cylinder();
        let axis = cyl.axis;
        let corner = |k: usize| Vector3::new(e[9 * k], e[9 * k + 1], e[9 * k + 2]);
        let mut gap = f64::INFINITY;
        for k in 0..4 {
            let d = Point3::from(corner(k)) - cyl.center;
            let radial = d - axis * axis.dot(&d);
            gap = gap.min(radial.norm() - cyl.radius);
        }
        let chord = (corner(1) - corner(0)).norm();
        gap <= chord
    }

    /// The contact quadrature points of element `el` with coordinates `e` and velocities `ed`.
    fn points<'a>(
        &'a self, e: &'a [f64; NE], ed: &'a [f64; NE],
    ) -> impl Iterator<Item = QuadPoint<3, &'a BlockShape>> + 'a {
        self.kind
            .quad
            .iter()
            .zip(&self.kind.quad_s)
            .zip(&self.kind.quad_shape)
            .map(move |((&(_, _, w), s), shape)| quad_point(s, shape, w, e, ed))
    }

    /// The pulley surfaces at time `t` with the travel-sense speeds `omegas`.
    fn surfaces(&self, t: f64, omegas: &[f64]) -> Vec<PulleySurface> {
        omegas
            .iter()
            .enumerate()
            .map(|(p, &w)| self.surface(p, t, w))
            .collect()
    }

    /// Runs the distributed contact of every element against every pulley surface at time `t`
    /// with the travel-sense speeds `omegas` and hands each element–pulley pair with active
    /// points to `sink` (with the pulley's rotation axis). The element contact buffer is the
    /// one in `slot` (created there if empty).
    fn contact_pass(
        &self, (t, omegas): (f64, &[f64]), q: &[f64], v: &[f64], jacobian: bool,
        slot: &mut Option<ElementContact3>,
        mut sink: impl FnMut(usize, usize, &Vector3<f64>, &ElementContact3),
    ) {
        let surfaces = self.surfaces(t, omegas);
        let ec = slot.get_or_insert_with(|| ElementContact3::new(NE));
        let mut e = [0.0; NE];
        let mut ed = [0.0; NE];
        for el in 0..self.n_elements() {
            self.gather(q, el, &mut e);
            let mut gathered_v = false;
            for (p, surf) in surfaces.iter().enumerate() {
                if !self.may_touch(&e, surf) {
                    continue;
                }
                if !gathered_v {
                    self.gather(v, el, &mut ed);
                    gathered_v = true;
                }
                if jacobian {
                    contact::element_contact(
                        surf,
                        &self.kind.normal,
                        &self.kind.friction,
                        self.points(&e, &ed),
                        true,
                        ec,
                        None,
                    );
                } else {
                    contact::element_forces_blocks(
                        surf,
                        &self.kind.normal,
                        &self.kind.friction,
                        &self.kind.quad_blocks,
                        &e,
                        &ed,
                        ec,
                    );
                }
                if ec.active_points > 0 {
                    sink(el, p, &surf.cylinder().axis, ec);
                }
            }
        }
    }

    /// The drive's work buffers in the caller's workspace `ws`, created on first use (and
    /// anew if `ws` held the buffers of a drive with another number of free pulleys).
    fn scratch<'w>(&self, ws: &'w mut Workspace) -> &'w mut Scratch {
        let mm = NE + self.pulley_dofs.count();
        let fresh = || Scratch {
            ec: Some(ElementContact3::new(NE)),
            k_local: vec![0.0; mm * mm],
            c_local: vec![0.0; mm * mm],
            fe: [0.0; NE],
            ke: Mat::zeros(NE, NE),
            kl: vec![0.0; NE * NE],
        };
        let s = ws.get_or_insert_with(fresh);
        if s.k_local.len() != mm * mm {
            *s = fresh();
        }
        s
    }

    /// Elastic forces `Q_e` (2.20) of the belt into `f[..n_belt]` (overwritten).
    fn elastic_forces_into(&self, q: &[f64], f: &mut [f64], s: &mut Scratch) {
        f[..self.n_belt].fill(0.0);
        let mut e = [0.0; NE];
        for el in 0..self.n_elements() {
            self.gather(q, el, &mut e);
            self.kind.mesh.cells[el].plate.elastic_forces(&e, &mut s.fe);
            let fe = s.fe;
            self.scatter_add(f, el, &fe, 1.0);
        }
    }

    /// Belt forces `Q_e + Q_c` (length `n_belt`) and the travel-sense contact torques on every
    /// pulley \[N·m\] at time `t` with the pulleys turning at `omegas` (travel sense, rad/s).
    #[allow(clippy::too_many_arguments)] // the state, the pulley speeds, outputs, and the workspace
    pub fn belt_forces(
        &self, t: f64, q: &[f64], v: &[f64], omegas: &[f64], f: &mut [f64], torques: &mut [f64],
        ws: &mut Workspace,
    ) {
        let s = self.scratch(ws);
        self.elastic_forces_into(q, f, s);
        torques.fill(0.0);
        self.contact_pass((t, omegas), q, v, false, &mut s.ec, |el, p, axis, c| {
            self.scatter_add(f, el, &c.q, 1.0);
            torques[p] += c.moment.dot(axis);
        });
    }

    /// Resultant contact force on every pulley \[N\] and travel-sense contact torque \[N·m\]
    /// at `(t, q, v)` (the reaction of (4.45) and the moment of the spatial (3.26)).
    pub fn pulley_loads(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<([f64; 3], f64)> {
        let omegas = self.speeds(t, v);
        let mut out = vec![([0.0; 3], 0.0); omegas.len()];
        self.contact_pass((t, &omegas), q, v, false, &mut None, |_, p, axis, c| {
            for k in 0..3 {
                out[p].0[k] += c.reaction[k];
            }
            out[p].1 += c.moment.dot(axis);
        });
        out
    }

    /// Belt tangent `K = −∂(Q_e + Q_c)/∂e` (contact velocities and pulley speeds held) into the
    /// value array `k_vals` of `pat` (whose first groups are the elements, in order: the
    /// drive's [`PlateBeltDrive::pattern`] or the belt's alone), forces into `f`.
    #[allow(clippy::too_many_arguments)] // the state, the pulley speeds, outputs, and the workspace
    pub(crate) fn belt_stiffness(
        &self, t: f64, q: &[f64], v: &[f64], omegas: &[f64], pat: &Pattern, f: &mut [f64],
        k_vals: &mut [f64], ws: &mut Workspace,
    ) {
        let s = self.scratch(ws);
        k_vals.fill(0.0);
        self.elastic_tangent_into(q, f, (pat, k_vals), s);
        self.contact_pass((t, omegas), q, v, true, &mut s.ec, |el, _, _, c| {
            self.scatter_add(f, el, &c.q, 1.0);
            pat.add_element(k_vals, el, c.dq_de.as_slice(), -1.0);
        });
    }

    /// Elastic forces into `f[..n_belt]` (overwritten) and the elastic tangent added to the
    /// element blocks of the values `k_vals` of `pat` (its first groups the elements).
    fn elastic_tangent_into(
        &self, q: &[f64], f: &mut [f64], (pat, k_vals): (&Pattern, &mut [f64]), s: &mut Scratch,
    ) {
        f[..self.n_belt].fill(0.0);
        let mut e = [0.0; NE];
        for el in 0..self.n_elements() {
            self.gather(q, el, &mut e);
            self.kind.mesh.cells[el]
                .plate
                .elastic_tangent(&e, &mut s.fe, &mut s.ke);
            let fe = s.fe;
            self.scatter_add(f, el, &fe, 1.0);
            for j in 0..NE {
                for i in 0..NE {
                    s.kl[i + j * NE] = s.ke[(i, j)];
                }
            }
            pat.add_element(k_vals, el, &s.kl, 1.0);
        }
    }

    /// Contact records of every active quadrature point (or of the points given by `line`, see
    /// [`PlateBeltDrive::contact_records_on`]) with the element and pulley they belong to.
    pub fn contact_records(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<PlateContactRecord> {
        self.contact_records_on(t, q, v, &self.kind.quad)
    }

    /// Contact state at the local points `(x, y, weight)` of every element (e.g. a line of
    /// points along the centreline `y = w/2`, Kerkkänen Figs 4.17–4.18), for output.
    pub fn contact_records_on(
        &self, t: f64, q: &[f64], v: &[f64], local: &[(f64, f64, f64)],
    ) -> Vec<PlateContactRecord> {
        let omegas = self.speeds(t, v);
        let plate = &self.kind.mesh.cells[0].plate;
        let shapes: Vec<[f64; 12]> = local
            .iter()
            .map(|&(x, y, _)| plate.shape().eval(x, y).s)
            .collect();
        let mut out = Vec::new();
        let mut recs: Vec<ContactRecord3> = Vec::new();
        let mut ec = ElementContact3::new(NE);
        let (mut e, mut ed) = ([0.0; NE], [0.0; NE]);
        let a = self.element_length();
        for el in 0..self.n_elements() {
            self.gather(q, el, &mut e);
            self.gather(v, el, &mut ed);
            for (p, &omega) in omegas.iter().enumerate() {
                let surf = self.surface(p, t, omega);
                if !self.may_touch(&e, &surf) {
                    continue;
                }
                recs.clear();
                let pts = local
                    .iter()
                    .zip(&shapes)
                    .map(|(&(_, _, w), s)| quad_point(s, shape_matrix(s), w, &e, &ed));
                contact::element_contact(
                    &surf,
                    &self.kind.normal,
                    &self.kind.friction,
                    pts,
                    false,
                    &mut ec,
                    Some(&mut recs),
                );
                for r in &recs {
                    let (x, y, _) = local[r.index];
                    out.push(PlateContactRecord {
                        pulley: p,
                        element: el,
                        s_material: el as f64 * a + x,
                        y,
                        position: [r.position.x, r.position.y, r.position.z],
                        penetration: r.penetration,
                        pressure: r.normal_force,
                        friction: [r.friction_force.x, r.friction_force.y],
                        slip: [r.slip.x, r.slip.y],
                    });
                }
            }
        }
        out
    }

    /// The contact quadrature of one element: local `(x, y)` \[m\] and weight × area \[m²\].
    pub fn contact_quadrature(&self) -> &[(f64, f64, f64)] {
        &self.kind.quad
    }

    /// [`SecondOrderSystem::forces`] with externally supplied pulley speeds `omegas` (travel
    /// sense; for a free pulley equal to its velocity coordinate) and load torques `loads`
    /// (one per pulley).
    #[allow(clippy::too_many_arguments)] // the state, the pulley speeds, outputs, and the workspace
    pub fn forces_with(
        &self, t: f64, q: &[f64], v: &[f64], omegas: &[f64], loads: &[f64], f: &mut [f64],
        ws: &mut Workspace,
    ) {
        let np = self.spec.pulleys.len();
        let mut torques = [0.0; MAX_PULLEYS];
        self.belt_forces(t, q, v, omegas, f, &mut torques[..np], ws);
        f[self.n_belt..].fill(0.0);
        for (p, j) in self.pulley_dofs.free() {
            f[j] = torques[p];
        }
        self.pulley_dofs.subtract_loads(loads, f);
    }
}

/// Contact state at one point, in the travel sense of the pulley.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PlateContactRecord {
    /// Pulley index.
    pub pulley: usize,
    /// Element index.
    pub element: usize,
    /// Material (unstretched) coordinate along the belt from cross-section 0 \[m\].
    pub s_material: f64,
    /// Material coordinate across the belt \[m\] (0 on one edge, `w` on the other).
    pub y: f64,
    /// Position \[m\].
    pub position: [f64; 3],
    /// Penetration `d` (4.43) \[m\].
    pub penetration: f64,
    /// Normal force per unit area `k_p d + c_p ḋ` (3.20) \[N/m²\].
    pub pressure: f64,
    /// Friction per unit area on the belt: circumferential (positive in the travel direction)
    /// and axial components \[N/m²\].
    pub friction: [f64; 2],
    /// Slip velocity of the belt relative to the pulley surface, circumferential (positive
    /// when the belt is faster in the travel direction) and axial \[m/s\].
    pub slip: [f64; 2],
}

/// The quadrature point with shape values `s` (matrix `shape`) and weight `w` of an element with
/// coordinates `e` and velocities `ed`: `r = S e`, `ṙ = S ė`.
fn quad_point<Sh>(
    s: &[f64; 12], shape: Sh, w: f64, e: &[f64; NE], ed: &[f64; NE],
) -> QuadPoint<3, Sh> {
    let (mut r, mut v) = (Vector3::zeros(), Vector3::zeros());
    for k in 0..12 {
        for c in 0..3 {
            r[c] += s[k] * e[3 * k + c];
            v[c] += s[k] * ed[3 * k + c];
        }
    }
    QuadPoint {
        position: Point3::from(r),
        velocity: v,
        shape,
        weight: w,
    }
}

/// The 3 × 36 block shape matrix `[S_k I₃]` of the shape values `s` (Kerkkänen (4.1)).
fn shape_matrix(s: &[f64; 12]) -> BlockShape {
    let mut values = [0.0; MAX_BLOCKS];
    values[..12].copy_from_slice(s);
    BlockShape { values, blocks: 12 }
}

/// The contact surface of `pl` at `t` turning at the travel-sense speed `omega`: axis
/// `∓e_z` through the (shifted, (4.46)) centre, so that positive `omega` is the travel sense.
fn surface_of(pl: &Pulley, t: f64, omega: f64) -> PulleySurface {
    let [u, ud] = pl.shift.map(|s| s.eval(t)).unwrap_or([0.0, 0.0]);
    let dir = pl.shift.map(|s| s.direction).unwrap_or([0.0, 0.0]);
    let sgn = pl.ccw_sign();
    let cyl = Cylinder {
        center: Point3::new(pl.center[0] + u * dir[0], pl.center[1] + u * dir[1], 0.0),
        axis: Vector3::new(0.0, 0.0, sgn),
        radius: pl.radius,
        crown: pl.crown,
        velocity: Vector3::new(ud * dir[0], ud * dir[1], 0.0),
        omega,
    };
    match pl.flanges {
        None => PulleySurface::Cylinder(cyl),
        // axial coordinate ζ = axis · (p − r_o) = sgn z
        Some([lo, hi]) => PulleySurface::Flanged(FlangedCylinder {
            cylinder: cyl,
            flanges: if sgn > 0.0 { [lo, hi] } else { [-hi, -lo] },
        }),
    }
}

impl SecondOrderSystem for PlateBeltDrive {
    fn n_q(&self) -> usize {
        self.n_belt + self.pulley_dofs.count()
    }
    fn dof_name(&self, dof: usize) -> String {
        if dof < self.n_belt {
            let names = ["r", "r_x", "r_y"];
            let local = dof % PLATE_NODE_COORDS;
            let nd = dof / PLATE_NODE_COORDS;
            format!(
                "belt cross-section {} edge {} {}[{}]",
                nd / 2,
                nd % 2,
                names[local / 3],
                ["x", "y", "z"][local % 3]
            )
        } else if let Some(name) = self.pulley_dofs.dof_name(&self.spec.pulleys, dof) {
            name
        } else {
            format!("coordinate {dof}")
        }
    }
    crate::mounted::ancf_equations!();
}

impl PlateBeltDrive {
    /// [`SecondOrderSystem::force_tangent`] with the pulleys turning at the travel-sense speeds
    /// `omegas` (for a free pulley equal to its velocity coordinate, whose column receives the
    /// speed coupling): `K = −∂f/∂q`, `C = −∂f/∂v` with the analytic elastic tangent and the
    /// exact contact Jacobians of [`contact::element_contact`].
    pub fn force_tangent_with(
        &self, t: f64, q: &[f64], v: &[f64], omegas: &[f64], ws: &mut Workspace,
    ) -> ForceTangent {
        let nb = self.n_belt;
        let pat = &self.pattern;
        let mut k = pat.zeros();
        let mut c = pat.zeros();
        let mut fbuf = vec![0.0; nb];
        let s = self.scratch(ws);
        self.elastic_tangent_into(q, &mut fbuf, (pat, &mut k), s);
        let n_el = self.n_elements();
        let nf = self.pulley_dofs.count();
        let m = NE + nf;
        let (k_local, c_local) = (&mut s.k_local, &mut s.c_local);
        self.contact_pass((t, omegas), q, v, true, &mut s.ec, |el, p, axis, ec| {
            k_local.fill(0.0);
            c_local.fill(0.0);
            for b in 0..NE {
                for a in 0..NE {
                    k_local[a + b * m] = -ec.dq_de[a + b * NE];
                    c_local[a + b * m] = -ec.dq_dedot[a + b * NE];
                }
            }
            if let Some(j) = self.pulley_dofs.dof(p) {
                let col = NE + (j - nb);
                for a in 0..NE {
                    let (dmde, dmdv) =
                        (axis.dot(&ec.dmoment_de[a]), axis.dot(&ec.dmoment_dedot[a]));
                    // the belt forces depend on the pulley speed θ̇
                    c_local[a + col * m] = -ec.dq_domega[a];
                    // pulley row: τ = aᵀ M
                    k_local[col + a * m] = -dmde;
                    c_local[col + a * m] = -dmdv;
                }
                c_local[col + col * m] = -axis.dot(&ec.dmoment_domega);
            }
            pat.add_element(&mut k, n_el + el, k_local, 1.0);
            pat.add_element(&mut c, n_el + el, c_local, 1.0);
        });
        // the free pulleys' viscous dampers: −c ω
        crate::mounted::pulleys::add_damping(&self.pulley_dofs, &self.spec.pulleys, pat, &mut c);
        ForceTangent {
            stiffness: SysMatrix::Sparse(pat.to_matrix(k)),
            damping: SysMatrix::Sparse(pat.to_matrix(c)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // The contact quadrature `points × points_across` (Gauss–Legendre in both directions):
    // its weights sum to the element area a·w (closed form), and since the plate's shape
    // functions are at most cubic across the width, 3 Gauss points (exact to degree 5)
    // integrate every S_k as the 9 × 9 rule does (second rule as the reference, to
    // round-off). `points_across = None` is 3 across on flat pulleys (Model 2: the same points
    // as `Some(3)`) and the square rule on a crowned pulley.
    #[test]
    fn contact_quadrature_across_the_width() {
        let mut spec = PlateDriveSpec::kerkkanen_model2();
        spec.contact.points_across = Some(9);
        let square = PlateBeltDrive::new(spec.clone()).unwrap();
        assert_eq!(square.contact_quadrature().len(), 81);
        spec.contact.points_across = Some(3);
        let narrow = PlateBeltDrive::new(spec).unwrap();
        assert_eq!(narrow.contact_quadrature().len(), 27);
        let default = PlateBeltDrive::new(PlateDriveSpec::kerkkanen_model2()).unwrap();
        assert_eq!(default.contact_quadrature(), narrow.contact_quadrature());
        let mut crowned = PlateDriveSpec::kerkkanen_model2();
        crowned.pulleys[1].crown = 0.5;
        let crowned = PlateBeltDrive::new(crowned).unwrap();
        assert_eq!(crowned.contact_quadrature(), square.contact_quadrature());
        let (a, w) = (square.element_length(), square.spec().belt.width);
        let integrals = |d: &PlateBeltDrive| {
            let mut s = [0.0; 12];
            let mut area = 0.0;
            for (x, y, wq) in d.contact_quadrature() {
                area += wq;
                let sv = d.mesh().cells[0].plate.shape().eval(*x, *y).s;
                for k in 0..12 {
                    s[k] += wq * sv[k];
                }
            }
            (area, s)
        };
        let (area9, s9) = integrals(&square);
        let (area3, s3) = integrals(&narrow);
        assert!(
            (area9 - a * w).abs() < 1e-13 * a * w,
            "{area9} vs {}",
            a * w
        );
        assert!(
            (area3 - a * w).abs() < 1e-13 * a * w,
            "{area3} vs {}",
            a * w
        );
        for k in 0..12 {
            assert!(
                (s9[k] - s3[k]).abs() < 1e-15,
                "S_{k}: {} vs {}",
                s9[k],
                s3[k]
            );
        }
    }

    // A rule of 0 or more than 20 points across is rejected and named.
    #[test]
    fn points_across_is_checked() {
        for n in [0, 21] {
            let mut spec = PlateDriveSpec::kerkkanen_model2();
            spec.contact.points_across = Some(n);
            let e = PlateBeltDrive::new(spec).err().unwrap().to_string();
            assert!(e.contains("contact.points_across"), "{e}");
        }
    }
}
