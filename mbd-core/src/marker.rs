//! Markers: a point and a frame attached to a rigid body, to the ground or to a node of a
//! floating-frame deformable body, and the kinematic terms that every joint equation is built
//! from (position or direction, its Jacobian with respect to the carrying body's velocity
//! coordinates, its rate and the velocity-quadratic part of its second derivative).
//!
//! Velocity coordinates of a carrying body are `(ṙ, ω', ż)`: frame origin velocity, body-frame
//! angular velocity and (for a floating body) elastic velocities; a rigid body has no `ż`.
//!
//! * Rigid body (Lin (2.1)–(2.3)): point `d = r + A s'`, `ḋ = ṙ − A s̃' ω'`,
//!   `d̈ = r̈ − A s̃' ω̇' + A ω̃'ω̃' s'`; direction `a = A a'`, `ȧ = −A ã' ω'`,
//!   `ä = −A ã' ω̇' + A ω̃'ω̃' a'`.
//! * Node `j` of a floating body (Lin (5.1)–(5.7), (5.12); Ribaric (2.21)–(2.27)) with local
//!   deformed position `b' = ū₀ + Φ_t z` (`Φ_t` the node's three rows of `Ψ'`):
//!   `d = r + A b'`, `ḋ = ṙ − A b̃' ω' + A Φ_t ż`,
//!   `d̈ = [I, −A b̃', A Φ_t] v̇ + A (ω̃'ω̃' b' + 2 ω̃' Φ_t ż)` (Lin (5.5): `w = ω̃ω̃b + 2ω̃δ̇`).
//!   The node frame is the floating frame rotated by the small elastic rotation `θ = Φ_θ z`
//!   (`C = I + θ̃`, linear in `z`, the usual floating-frame small-deformation assumption; the
//!   seeds have no rotational nodal coordinates) when the body provides the slopes `Φ_θ`
//!   ([`crate::floating::FlexBody::with_node_rotations`]), otherwise the floating frame itself.
//!   A direction `a'` of the node frame is `u' = C a' = a' + θ × a'`, `u̇' = −ã' Φ_θ ż`, and a
//!   marker offset `o'` from the node adds `C o'` to `b'`.
//!
//! In every case a vector `x = (r) + A y'` with local rate `ẏ'` (linear in `ż`) has
//! `ẋ = (ṙ) − A ỹ' ω' + A ẏ'` and the velocity-quadratic acceleration part
//! `A (ω̃'ω̃' y' + 2 ω̃' ẏ')`; the joint rows (Nikravesh's dot-1, dot-2 and spherical primitives)
//! combine these terms.

use crate::body::{BodyId, BodyKin, Jac3x6};
use crate::kinematics::tilde::tilde;
use faer::MatRef;
use nalgebra::{Matrix3, Matrix3xX, Vector3};

/// A joint frame: a point `s'` \[m\] and a unit axis `a'` on a body, on the ground or on a node of
/// a floating body.
///
/// * `body: None`: the ground; `point` and `axis` are global.
/// * `node: None`: rigid body `body`; `point` (from the mass centre) and `axis` in body
///   coordinates. In a [`crate::floating::FloatingSystem`] this is rigid body `body`.
/// * `node: Some(n)`: node `n` of floating body `body`; `point` is an offset from the node and
///   `axis` a direction, both in the node frame (the floating frame rotated by the node's small
///   elastic rotation, see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Marker {
    /// Body (`None` = ground).
    pub body: Option<BodyId>,
    /// Node of a floating body (`None` = a rigid body or the ground).
    pub node: Option<usize>,
    /// Point in body (or node) coordinates \[m\].
    pub point: Vector3<f64>,
    /// Unit axis in body (or node) coordinates.
    pub axis: Vector3<f64>,
}

impl Marker {
    /// Marker at `point` with axis `axis` on a rigid body or the ground (axis normalised; a
    /// zero axis is kept and rejected by the constraint's validation).
    pub fn new(body: Option<BodyId>, point: Vector3<f64>, axis: Vector3<f64>) -> Self {
        let n = axis.norm();
        Self {
            body,
            node: None,
            point,
            axis: if n > 0.0 { axis / n } else { axis },
        }
    }

    /// Marker at `point` (axis irrelevant, set to z) on a rigid body or the ground.
    pub fn point(body: Option<BodyId>, point: Vector3<f64>) -> Self {
        Self::new(body, point, Vector3::z())
    }

    /// Marker at node `node` of floating body `body` (no offset, axis z of the node frame).
    pub fn node(body: usize, node: usize) -> Self {
        Self::node_frame(body, node, Vector3::zeros(), Vector3::z())
    }

    /// Marker at offset `offset` \[m\] from node `node` of floating body `body` with axis `axis`,
    /// both in the node frame (axis normalised).
    pub fn node_frame(body: usize, node: usize, offset: Vector3<f64>, axis: Vector3<f64>) -> Self {
        Self {
            node: Some(node),
            ..Self::new(Some(body), offset, axis)
        }
    }

    /// The ground origin.
    pub fn ground() -> Self {
        Self::point(None, Vector3::zeros())
    }
}

/// Small elastic rotations of the nodes of a floating body: `θ_j = Φ_θ,j z` and `θ̇_j = Φ_θ,j ż`
/// (body-frame components \[rad\], \[rad/s\]) with the slopes `Φ_θ` (3 rows per node).
#[derive(Debug, Clone, Copy)]
pub struct NodeRotations<'a> {
    /// `θ` per node \[rad\].
    pub theta: &'a [Vector3<f64>],
    /// `θ̇` per node \[rad/s\].
    pub theta_dot: &'a [Vector3<f64>],
    /// `Φ_θ` (3 n × n_z) \[rad per unit z\].
    pub slopes: MatRef<'a, f64>,
}

/// Nodal kinematics of a floating body at the current state, in body-frame components.
#[derive(Debug, Clone, Copy)]
pub struct FlexNodes<'a> {
    /// Deformed node positions `b' = ū₀ + Φ_t z` \[m\] (Lin (5.12)).
    pub b: &'a [Vector3<f64>],
    /// Deflection rates `δ̇' = Φ_t ż` \[m/s\].
    pub bdot: &'a [Vector3<f64>],
    /// Translational basis `Ψ'` (3 n × n_z).
    pub psi: MatRef<'a, f64>,
    /// Node rotations, if the body provides slopes.
    pub rot: Option<NodeRotations<'a>>,
}

/// The body that carries a marker: its frame kinematics and, for a floating body, its nodes.
#[derive(Debug, Clone, Copy)]
pub struct Carrier<'a> {
    /// Frame position, orientation and velocities (the mass centre for a rigid body).
    pub frame: BodyKin,
    /// Nodes of a floating body (`None` for a rigid body or the ground).
    pub flex: Option<FlexNodes<'a>>,
}

impl Carrier<'_> {
    /// A rigid body (or ground) carrier.
    pub fn rigid(frame: BodyKin) -> Self {
        Self { frame, flex: None }
    }

    /// The ground.
    pub fn ground() -> Self {
        Self::rigid(BodyKin::ground())
    }

    /// Number of elastic velocity coordinates (0 for a rigid body).
    pub fn n_elastic(&self) -> usize {
        self.flex.map(|f| f.psi.ncols()).unwrap_or(0)
    }

    /// Global position of the marker point \[m\].
    pub fn position(&self, m: &Marker) -> Vector3<f64> {
        Term::point(self, m, 0).x
    }

    /// Rotation matrix of the marker frame (body or node frame; global from local): `A` for a
    /// rigid body, `A (I + θ̃)` for a node with slopes (not exactly orthogonal: first order in θ).
    pub fn orientation(&self, m: &Marker) -> Matrix3<f64> {
        match (m.node, self.flex.and_then(|f| f.rot)) {
            (Some(n), Some(rot)) => self.frame.a * (Matrix3::identity() + tilde(&rot.theta[n])),
            _ => self.frame.a,
        }
    }

    /// Local (body-frame) vector `y'`, its rate `ẏ'` and `∂ẏ'/∂ż` of the marker point
    /// (`vector = None`) or of the marker-frame direction `vector`.
    fn local(&self, m: &Marker, vector: Option<&Vector3<f64>>) -> Local {
        let (Some(n), Some(f)) = (m.node, self.flex) else {
            return Local {
                y: *vector.unwrap_or(&m.point),
                rate: None,
            };
        };
        let nz = f.psi.ncols();
        let mut y = Vector3::zeros();
        let mut ydot = Vector3::zeros();
        let mut e = Matrix3xX::zeros(nz);
        // the part carried by the node frame: offset (point) or direction (vector)
        let c = match vector {
            Some(a) => *a,
            None => {
                y = f.b[n];
                ydot = f.bdot[n];
                for k in 0..nz {
                    for r in 0..3 {
                        e[(r, k)] = f.psi[(3 * n + r, k)];
                    }
                }
                m.point
            }
        };
        if vector.is_some() || c != Vector3::zeros() {
            y += c;
            if let Some(rot) = f.rot {
                // C c = c + θ × c, d/dt = θ̇ × c = −c̃ Φ_θ ż
                y += rot.theta[n].cross(&c);
                ydot += rot.theta_dot[n].cross(&c);
                for k in 0..nz {
                    let s = Vector3::new(
                        rot.slopes[(3 * n, k)],
                        rot.slopes[(3 * n + 1, k)],
                        rot.slopes[(3 * n + 2, k)],
                    );
                    let col = s.cross(&c);
                    for r in 0..3 {
                        e[(r, k)] += col[r];
                    }
                }
            }
        }
        Local {
            y,
            rate: Some((ydot, e)),
        }
    }
}

/// A local vector `y'` and, on a floating body, its rate `ẏ'` and `∂ẏ'/∂ż`.
struct Local {
    y: Vector3<f64>,
    rate: Option<(Vector3<f64>, Matrix3xX<f64>)>,
}

/// A vector-valued kinematic expression with its derivatives: value `x`, Jacobians with respect
/// to the velocities `(ṙ, ω')` and `ż` of the two bodies of a joint, rate `ẋ`, and the
/// velocity-quadratic part `ẍ − (∂ẋ/∂v) v̇` of its second derivative (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Term {
    /// Value.
    pub x: Vector3<f64>,
    /// `∂ẋ/∂(ṙ_i, ω'_i)` (body i).
    pub ji: Jac3x6,
    /// `∂ẋ/∂(ṙ_j, ω'_j)` (body j).
    pub jj: Jac3x6,
    /// `∂ẋ/∂ż_i` (no columns unless body i is a floating body).
    pub ei: Matrix3xX<f64>,
    /// `∂ẋ/∂ż_j` (no columns unless body j is a floating body).
    pub ej: Matrix3xX<f64>,
    /// Rate `ẋ`.
    pub xdot: Vector3<f64>,
    /// Quadratic velocity part of `ẍ`.
    pub quad: Vector3<f64>,
}

impl Term {
    /// The marker point of carrier `c` on side `side` (0 = i, 1 = j): `d = r + A y'`.
    pub fn point(c: &Carrier, m: &Marker, side: usize) -> Self {
        Self::build(c, c.local(m, None), true, side)
    }

    /// The direction `a'` fixed in the marker frame of carrier `c` on side `side`: `A C a'`.
    pub fn vector(c: &Carrier, m: &Marker, a: &Vector3<f64>, side: usize) -> Self {
        Self::build(c, c.local(m, Some(a)), false, side)
    }

    fn build(c: &Carrier, l: Local, point: bool, side: usize) -> Self {
        let k = &c.frame;
        let mut jac = Jac3x6::zeros();
        if point {
            jac.fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&Matrix3::identity());
        }
        jac.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-k.a * tilde(&l.y)));
        let (x0, v0) = if point {
            (k.r, k.rdot)
        } else {
            (Vector3::zeros(), Vector3::zeros())
        };
        let (x, xdot, quad, e) = match l.rate {
            // rigid body: Lin (2.1)–(2.3)
            None => (
                if point { k.point(&l.y) } else { k.a * l.y },
                if point {
                    k.point_velocity(&l.y)
                } else {
                    k.a * k.w.cross(&l.y)
                },
                k.a * k.w.cross(&k.w.cross(&l.y)),
                Matrix3xX::zeros(0),
            ),
            // floating body: Lin (5.2), (5.5)
            Some((ydot, e)) => (
                x0 + k.a * l.y,
                v0 + k.a * (k.w.cross(&l.y) + ydot),
                k.a * (k.w.cross(&k.w.cross(&l.y)) + 2.0 * k.w.cross(&ydot)),
                k.a * e,
            ),
        };
        let none = || Matrix3xX::zeros(0);
        let (ji, jj, ei, ej) = if side == 0 {
            (jac, Jac3x6::zeros(), e, none())
        } else {
            (Jac3x6::zeros(), jac, none(), e)
        };
        Self {
            x,
            ji,
            jj,
            ei,
            ej,
            xdot,
            quad,
        }
    }

    /// `self − o`.
    pub fn sub(&self, o: &Term) -> Term {
        Term {
            x: self.x - o.x,
            ji: self.ji - o.ji,
            jj: self.jj - o.jj,
            ei: combine(&self.ei, &o.ei, -1.0),
            ej: combine(&self.ej, &o.ej, -1.0),
            xdot: self.xdot - o.xdot,
            quad: self.quad - o.quad,
        }
    }

    /// Row `k` of the term as a scalar constraint row.
    pub fn component(&self, k: usize) -> Row {
        let mut di = [0.0; 6];
        let mut dj = [0.0; 6];
        for c in 0..6 {
            di[c] = self.ji[(k, c)];
            dj[c] = self.jj[(k, c)];
        }
        Row {
            phi: self.x[k],
            di,
            dj,
            ei: self.ei.row(k).iter().copied().collect(),
            ej: self.ej.row(k).iter().copied().collect(),
            rate: self.xdot[k],
            quad: self.quad[k],
        }
    }

    /// Scalar product `self · o` as a constraint row (Nikravesh's dot-1/dot-2 constraints).
    pub fn dot(&self, o: &Term) -> Row {
        let gi = self.ji.transpose() * o.x + o.ji.transpose() * self.x;
        let gj = self.jj.transpose() * o.x + o.jj.transpose() * self.x;
        let elastic = |a: &Matrix3xX<f64>, b: &Matrix3xX<f64>| {
            add_vecs(
                (a.transpose() * o.x).iter().copied().collect(),
                (b.transpose() * self.x).iter().copied().collect(),
                1.0,
            )
        };
        Row {
            phi: self.x.dot(&o.x),
            di: gi.into(),
            dj: gj.into(),
            ei: elastic(&self.ei, &o.ei),
            ej: elastic(&self.ej, &o.ej),
            rate: self.xdot.dot(&o.x) + self.x.dot(&o.xdot),
            quad: self.quad.dot(&o.x) + self.x.dot(&o.quad) + 2.0 * self.xdot.dot(&o.xdot),
        }
    }
}

/// `a + s b` for elastic Jacobian blocks, either of which may have no columns.
fn combine(a: &Matrix3xX<f64>, b: &Matrix3xX<f64>, s: f64) -> Matrix3xX<f64> {
    match (a.ncols(), b.ncols()) {
        (_, 0) => a.clone(),
        (0, _) => b * s,
        _ => a + b * s,
    }
}

/// `a + s b` for elastic row entries, either of which may be empty.
fn add_vecs(mut a: Vec<f64>, b: Vec<f64>, s: f64) -> Vec<f64> {
    if a.is_empty() {
        return b.into_iter().map(|x| s * x).collect();
    }
    for (x, y) in a.iter_mut().zip(b) {
        *x += s * y;
    }
    a
}

/// One scalar constraint equation: residual, Jacobian blocks with respect to `(ṙ, ω')` and `ż`
/// of bodies i and j, rate `Φ̇` at the current velocities (scleronomic part) and the
/// velocity-quadratic part of `Φ̈` (so that `γ = −quad` for a scleronomic row).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Residual `Φ`.
    pub phi: f64,
    /// `∂Φ̇/∂(ṙ_i, ω'_i)`.
    pub di: [f64; 6],
    /// `∂Φ̇/∂(ṙ_j, ω'_j)`.
    pub dj: [f64; 6],
    /// `∂Φ̇/∂ż_i` (empty unless body i is a floating body).
    pub ei: Vec<f64>,
    /// `∂Φ̇/∂ż_j` (empty unless body j is a floating body).
    pub ej: Vec<f64>,
    /// `Φ̇ = D v` at the current velocities.
    pub rate: f64,
    /// Velocity-quadratic part of `Φ̈`.
    pub quad: f64,
}

impl Row {
    /// `c · self` (linear combination helper for drivers).
    pub fn scaled(&self, c: f64) -> Row {
        let mut r = self.clone();
        r.phi *= c;
        r.rate *= c;
        r.quad *= c;
        r.di.iter_mut().for_each(|x| *x *= c);
        r.dj.iter_mut().for_each(|x| *x *= c);
        r.ei.iter_mut().for_each(|x| *x *= c);
        r.ej.iter_mut().for_each(|x| *x *= c);
        r
    }

    /// `self + o`.
    pub fn add(&self, o: &Row) -> Row {
        let mut r = self.clone();
        r.phi += o.phi;
        r.rate += o.rate;
        r.quad += o.quad;
        for k in 0..6 {
            r.di[k] += o.di[k];
            r.dj[k] += o.dj[k];
        }
        r.ei = add_vecs(r.ei, o.ei.clone(), 1.0);
        r.ej = add_vecs(r.ej, o.ej.clone(), 1.0);
        r
    }
}
