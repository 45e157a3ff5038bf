//! Distributed spatial contact over an element by quadrature: the generalized contact force
//! `Q_c = ∫_A Sᵀ (f_n n + T f_t) dA ≈ Σ_q w_q A_q S_qᵀ f_q` — the surface form of Kerkkänen
//! (3.27) used for the thin-plate belt of his ch. 4 (81 points per plate element, §4.5) —, its
//! exact Jacobians with respect to the element coordinates `e`, velocities `ė` and the obstacle's
//! angular velocity `ω`, and the reaction force and moment on the obstacle (the spatial
//! Kerkkänen (3.26)).
//!
//! The element enters only through its quadrature points ([`SurfaceQuadPoint`]): position
//! `r = S e`, velocity `ṙ = S ė`, the `3 × N` shape-function matrix `S = ∂r/∂e` and the weight
//! `w_q A_q` (Gauss weight × area Jacobian). The point forces and their derivatives are those
//! of [`point_contact_3d`], so the laws are the crate's [`NormalLaw`] (per unit area) and
//! [`FrictionLaw`] (per unit area).

use super::geometry::Surface3;
use super::point::point_contact_3d;
use crate::friction::FrictionLaw;
use crate::normal::NormalLaw;
use nalgebra::{Point3, SMatrix, SVector, Vector2, Vector3};

/// One quadrature point of an element with `N` coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceQuadPoint<const N: usize> {
    /// Position `r = S e` \[m\].
    pub position: Point3<f64>,
    /// Velocity `ṙ = S ė` \[m/s\].
    pub velocity: Vector3<f64>,
    /// Shape-function matrix `S = ∂r/∂e` (3 × N).
    pub shape: SMatrix<f64, 3, N>,
    /// Quadrature weight × area (or length) Jacobian `w_q A_q` \[m²\].
    pub weight: f64,
}

/// Contact state at one quadrature point in contact, for output (pressure and friction maps).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRecord3 {
    /// Index of the quadrature point in the element's sequence.
    pub index: usize,
    /// Position \[m\].
    pub position: Point3<f64>,
    /// Penetration \[m\].
    pub penetration: f64,
    /// Normal pressure (normal force per unit area) \[N/m²\].
    pub normal_force: f64,
    /// Friction traction in the tangent basis `(t₁, t₂)` \[N/m²\].
    pub friction_force: Vector2<f64>,
    /// Slip velocity in the tangent basis \[m/s\].
    pub slip: Vector2<f64>,
}

/// Element contact force, Jacobians and obstacle reaction for `N` element coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementContact3<const N: usize> {
    /// Generalized contact force `Q_c` \[N\].
    pub q: SVector<f64, N>,
    /// `∂Q_c/∂e` \[N/m\].
    pub dq_de: SMatrix<f64, N, N>,
    /// `∂Q_c/∂ė` \[N·s/m\].
    pub dq_dedot: SMatrix<f64, N, N>,
    /// `∂Q_c/∂ω` \[N·s\].
    pub dq_domega: SVector<f64, N>,
    /// Resultant force on the obstacle `F = −Σ w f` \[N\].
    pub reaction: Vector3<f64>,
    /// Moment on the obstacle about [`Surface3::center`], `M = Σ w (r − r_o) × (−f)` \[N·m\]
    /// (its component along a pulley axis is the torque of Kerkkänen (3.26)).
    pub moment: Vector3<f64>,
    /// `∂M/∂e`.
    pub dmoment_de: SMatrix<f64, 3, N>,
    /// `∂M/∂ė`.
    pub dmoment_dedot: SMatrix<f64, 3, N>,
    /// `∂M/∂ω`.
    pub dmoment_domega: Vector3<f64>,
    /// Number of quadrature points in contact.
    pub active_points: usize,
}

impl<const N: usize> Default for ElementContact3<N> {
    fn default() -> Self {
        Self {
            q: SVector::zeros(),
            dq_de: SMatrix::zeros(),
            dq_dedot: SMatrix::zeros(),
            dq_domega: SVector::zeros(),
            reaction: Vector3::zeros(),
            moment: Vector3::zeros(),
            dmoment_de: SMatrix::zeros(),
            dmoment_dedot: SMatrix::zeros(),
            dmoment_domega: Vector3::zeros(),
            active_points: 0,
        }
    }
}

impl<const N: usize> ElementContact3<N> {
    fn clear(&mut self, jac: bool) {
        self.q.fill(0.0);
        if jac {
            self.dq_de.fill(0.0);
            self.dq_dedot.fill(0.0);
            self.dq_domega.fill(0.0);
            self.dmoment_de.fill(0.0);
            self.dmoment_dedot.fill(0.0);
            self.dmoment_domega.fill(0.0);
        }
        self.reaction.fill(0.0);
        self.moment.fill(0.0);
        self.active_points = 0;
    }
}

/// A distributed spatial contact pairing: obstacle and laws (per unit area).
#[derive(Debug, Clone)]
pub struct SurfaceContact<S, NL, FL> {
    /// Obstacle.
    pub surface: S,
    /// Normal law (pressure: penalty \[N/m³\], damping \[N·s/m³\]).
    pub normal: NL,
    /// Friction law (traction per unit area).
    pub friction: FL,
}

impl<S: Surface3, NL: NormalLaw, FL: FrictionLaw> SurfaceContact<S, NL, FL> {
    /// Contact of one element against `self.surface`; see [`SurfaceContact::element_on`].
    pub fn element<const N: usize>(
        &self,
        points: impl IntoIterator<Item = SurfaceQuadPoint<N>>,
        jacobian: bool,
        out: &mut ElementContact3<N>,
        records: Option<&mut Vec<ContactRecord3>>,
    ) {
        self.element_on(&self.surface, points, jacobian, out, records);
    }

    /// Contact of one element given by its quadrature `points` against `surface` (an obstacle
    /// whose state changes between calls). Fills `out` (forces always; Jacobians when
    /// `jacobian`), appends point records to `records` when given. With `f` the point force
    /// and `S` the shape matrix: `Q_c = Σ w Sᵀ f`, `∂Q_c/∂e = Σ w Sᵀ (∂f/∂r) S`,
    /// `∂Q_c/∂ė = Σ w Sᵀ (∂f/∂ṙ) S`, `∂Q_c/∂ω = Σ w Sᵀ ∂f/∂ω`; with the arm `a = r − r_o`,
    /// `∂M/∂r = [f]× − [a]× ∂f/∂r`.
    pub fn element_on<const N: usize>(
        &self,
        surface: &S,
        points: impl IntoIterator<Item = SurfaceQuadPoint<N>>,
        jacobian: bool,
        out: &mut ElementContact3<N>,
        mut records: Option<&mut Vec<ContactRecord3>>,
    ) {
        out.clear(jacobian);
        let c = surface.center();
        for (index, qp) in points.into_iter().enumerate() {
            let Some(pc) = point_contact_3d(
                surface,
                &self.normal,
                &self.friction,
                &qp.position,
                &qp.velocity,
            ) else {
                continue;
            };
            out.active_points += 1;
            let w = qp.weight;
            let f = pc.force;
            let st = qp.shape.transpose();
            out.q += st * (f * w);
            out.reaction -= f * w;
            let arm = qp.position - c;
            out.moment -= arm.cross(&f) * w;
            if jacobian {
                out.dq_de += st * (pc.df_dp * w) * qp.shape;
                out.dq_dedot += st * (pc.df_dv * w) * qp.shape;
                out.dq_domega += st * (pc.df_domega * w);
                let ax = arm.cross_matrix();
                let dm_dp = (f.cross_matrix() - ax * pc.df_dp) * w;
                out.dmoment_de += dm_dp * qp.shape;
                out.dmoment_dedot -= ax * (pc.df_dv * w) * qp.shape;
                out.dmoment_domega -= ax * (pc.df_domega * w);
            }
            if let Some(r) = records.as_deref_mut() {
                r.push(ContactRecord3 {
                    index,
                    position: qp.position,
                    penetration: pc.penetration,
                    normal_force: pc.normal.force,
                    friction_force: pc.friction.force,
                    slip: pc.slip,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests;
