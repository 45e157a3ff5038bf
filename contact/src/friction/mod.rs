//! Friction laws behind one trait, [`FrictionLaw`], for planar (scalar tangential slip) and
//! spatial (slip 2-vector in the tangent plane) contact, smooth or set-valued.
//!
//! * Smooth (regularised) laws give the force `f_t(v_t, f_n)` and its derivatives with respect to
//!   the slip velocity and the normal force, for implicit integrators and Newton tangents. The
//!   force opposes the slip: `f_t·v_t ≤ 0`.
//! * A set-valued law (Coulomb with stick, `|f_t| ≤ μ f_n`) also answers the Alart–Curnier
//!   projection [`FrictionLaw::augmented`] (Alart & Curnier 1991) and its generalised
//!   derivative, used by semismooth Newton contact solvers, and the exact one-contact solve
//!   [`FrictionLaw::local_force`] used by block Gauss–Seidel.
//!
//! A new law is one file with one `impl FrictionLaw` (see [`stribeck`]); [`FrictionSpec`] maps
//! configuration tables (`law = "tanh"`, …) to the laws.

use nalgebra::{Matrix2, Vector2};
use std::fmt::Debug;

pub mod coulomb;
pub mod coulomb_tanh;
pub mod creep_rate;
pub mod frictionless;
pub mod slip_regularized;
pub mod spec;
pub mod stribeck;
pub mod transition;

pub use coulomb::Coulomb;
pub use coulomb_tanh::CoulombTanh;
pub use creep_rate::CreepRate;
pub use frictionless::Frictionless;
pub use slip_regularized::SlipRegularized;
pub use spec::FrictionSpec;
pub use stribeck::Stribeck;
pub use transition::transition_limit;

/// Tangential force of a planar contact and its partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FrictionForce {
    /// Signed force along the tangent `t` \[N or N/m\].
    pub force: f64,
    /// `∂force/∂v_t`.
    pub d_slip: f64,
    /// `∂force/∂f_n`.
    pub d_normal: f64,
}

/// Tangential force of a spatial contact (components in a tangent-plane basis `(t₁, t₂)`) and
/// its partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentFriction {
    /// Force `f_t` \[N or N/m\].
    pub force: Vector2<f64>,
    /// `∂f_t/∂v_t` (2 × 2).
    pub d_slip: Matrix2<f64>,
    /// `∂f_t/∂f_n`.
    pub d_normal: Vector2<f64>,
}

/// The Alart–Curnier tangential target `p(f, u, λ̂)` of one contact and its generalised
/// derivative: the friction equation is `Φ_T = f − p = 0` (Alart & Curnier 1991), where `f` is
/// the friction force, `u` the slip velocity and `λ̂ = max(0, λ − r_N g)` the augmented normal
/// force. For a smooth law `p = f_t(u, λ̂)`; for Coulomb `p = proj_{disk(μλ̂)}(f − r_T u)`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Augmented {
    /// Target `p` \[N\].
    pub target: Vector2<f64>,
    /// `∂p/∂f`.
    pub d_force: Matrix2<f64>,
    /// `∂p/∂u`.
    pub d_slip: Matrix2<f64>,
    /// `∂p/∂λ̂`.
    pub d_normal: Vector2<f64>,
    /// Whether the contact sticks (the projection is inside the disk of a set-valued law).
    pub stick: bool,
}

/// A friction law `f_t(v_t, f_n)` (planar: scalar slip; spatial: slip 2-vector), optionally
/// set-valued at zero slip.
pub trait FrictionLaw: Debug + Send + Sync {
    /// Planar law: force along `t` for slip velocity `v_t` \[m/s\] and normal force `f_n`
    /// (the magnitude `|f_n|` bounds the force, Kerkkänen (3.23)). A set-valued law returns its
    /// slip branch here, with `sign(0) = 0`.
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce;

    /// Largest friction coefficient of the law, `|f_t| ≤ μ |f_n|` (0: frictionless; a solver
    /// may then skip the slip velocities).
    fn coefficient(&self) -> f64;

    /// Width `w` \[m/s\] of the slip-velocity band in which a regularised law is steep
    /// (`1/κ` of the tanh law, `ε` of the square-root law), for the transition-aware limit on
    /// Newton corrections ([`transition_limit`]); `None` (the default) for a law without one
    /// (set-valued, piecewise linear or frictionless).
    fn transition_width(&self) -> Option<f64> {
        None
    }

    /// Spatial law for the slip 2-vector `v_t` \[m/s\] in the tangent plane. The default is the
    /// isotropic extension of the planar law, `f_t = f(|v_t|, f_n) v_t/|v_t|`, with
    /// `∂f_t/∂v_t = f' e eᵀ + (f/|v_t|)(I − e eᵀ)`, `e = v_t/|v_t|` (and `f'(0) I` at rest).
    fn friction_tangent(&self, slip: Vector2<f64>, normal: f64) -> TangentFriction {
        let s = slip.norm();
        if s == 0.0 {
            let f0 = self.friction(0.0, normal);
            return TangentFriction {
                force: Vector2::zeros(),
                d_slip: Matrix2::identity() * f0.d_slip,
                d_normal: Vector2::zeros(),
            };
        }
        let e = slip / s;
        let f = self.friction(s, normal);
        let eet = e * e.transpose();
        TangentFriction {
            force: e * f.force,
            d_slip: eet * f.d_slip + (Matrix2::identity() - eet) * (f.force / s),
            d_normal: e * f.d_normal,
        }
    }

    /// The force of [`FrictionLaw::friction_tangent`] alone (force-only evaluations). The
    /// default is the isotropic extension's `f(|v_t|, f_n) v_t/|v_t|` (zero at rest), equal to
    /// the default `friction_tangent`'s force; a law that overrides `friction_tangent` overrides
    /// this too.
    fn friction_tangent_force(&self, slip: Vector2<f64>, normal: f64) -> Vector2<f64> {
        let s = slip.norm();
        if s == 0.0 {
            return Vector2::zeros();
        }
        let e = slip / s;
        e * self.friction(s, normal).force
    }

    /// [`FrictionLaw::friction_tangent_force`] of a batch of points (structure of arrays):
    /// `(out[0][q], out[1][q]) = f_t((slip[0][q], slip[1][q]), normal[q])` for every `q` of
    /// `normal`. The default calls the law point by point; a law whose force is branch-free
    /// overrides it with one loop that the compiler vectorises (the same operations per point,
    /// so the same values).
    #[inline(always)]
    fn friction_tangent_forces(&self, slip: [&[f64]; 2], normal: &[f64], out: [&mut [f64]; 2]) {
        let [o1, o2] = out;
        for (q, &fn_) in normal.iter().enumerate() {
            let f = self.friction_tangent_force(Vector2::new(slip[0][q], slip[1][q]), fn_);
            o1[q] = f[0];
            o2[q] = f[1];
        }
    }

    /// Whether the law is set-valued at zero slip (Coulomb with stick): a solver must then use
    /// [`FrictionLaw::augmented`] rather than the single-valued [`FrictionLaw::friction`].
    fn is_set_valued(&self) -> bool {
        false
    }

    /// Alart–Curnier target of a contact with friction force `f`, slip `u`, augmented normal
    /// force `normal = λ̂ > 0` and tangential augmentation `r_t` \[N·s/m\] (see [`Augmented`]).
    /// Derivatives are filled when `jacobian`. The default (smooth laws) is `p = f_t(u, λ̂)`.
    fn augmented(
        &self, _force: Vector2<f64>, slip: Vector2<f64>, normal: f64, _r_t: f64, _jacobian: bool,
    ) -> Augmented {
        let t = self.friction_tangent(slip, normal);
        Augmented {
            target: t.force,
            d_force: Matrix2::zeros(),
            d_slip: t.d_slip,
            d_normal: t.d_normal,
            stick: false,
        }
    }

    /// Exact friction force of one contact with the others frozen: the slip is `u = r + B f`
    /// (`B` the 2 × 2 tangential compliance block, positive definite), the normal force is
    /// `normal > 0`. The default (smooth laws) is Newton on `Ψ(f) = f − f_t(r + B f)` with
    /// `∂Ψ/∂f = I − (∂f_t/∂u) B`, from `f = 0`, to `|Δf| ≤ 10⁻¹⁵ μ λ`; a step that increases
    /// `|Ψ|` is halved (steep regularisations overshoot from `f = 0`).
    fn local_force(&self, b: Matrix2<f64>, r: Vector2<f64>, normal: f64) -> Vector2<f64> {
        let tol = 1e-15 * self.coefficient() * normal;
        let psi_at = |f: Vector2<f64>| f - self.friction_tangent(r + b * f, normal).force;
        let mut f = Vector2::zeros();
        let mut psi = psi_at(f);
        for _ in 0..200 {
            let t = self.friction_tangent(r + b * f, normal);
            let j = Matrix2::identity() - t.d_slip * b;
            let Some(mut d) = j.lu().solve(&(-psi)) else {
                break;
            };
            let mut next = psi_at(f + d);
            for _ in 0..60 {
                if next.norm() <= psi.norm() {
                    break;
                }
                d *= 0.5;
                next = psi_at(f + d);
            }
            f += d;
            psi = next;
            if d.amax() <= tol {
                break;
            }
        }
        f
    }
}

impl<L: FrictionLaw + ?Sized> FrictionLaw for &L {
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        (**self).friction(slip, normal)
    }
    fn coefficient(&self) -> f64 {
        (**self).coefficient()
    }
    fn transition_width(&self) -> Option<f64> {
        (**self).transition_width()
    }
    fn friction_tangent(&self, slip: Vector2<f64>, normal: f64) -> TangentFriction {
        (**self).friction_tangent(slip, normal)
    }
    fn friction_tangent_force(&self, slip: Vector2<f64>, normal: f64) -> Vector2<f64> {
        (**self).friction_tangent_force(slip, normal)
    }
    #[inline(always)]
    fn friction_tangent_forces(&self, slip: [&[f64]; 2], normal: &[f64], out: [&mut [f64]; 2]) {
        (**self).friction_tangent_forces(slip, normal, out)
    }
    fn is_set_valued(&self) -> bool {
        (**self).is_set_valued()
    }
    fn augmented(
        &self, force: Vector2<f64>, slip: Vector2<f64>, normal: f64, r_t: f64, jacobian: bool,
    ) -> Augmented {
        (**self).augmented(force, slip, normal, r_t, jacobian)
    }
    fn local_force(&self, b: Matrix2<f64>, r: Vector2<f64>, normal: f64) -> Vector2<f64> {
        (**self).local_force(b, r, normal)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Central differences of the planar law in `v_t` and `f_n` against its derivatives.
    pub(crate) fn fd(law: &dyn FrictionLaw, v: f64, n: f64) {
        let h = 1e-7;
        let f = law.friction(v, n);
        let dv = (law.friction(v + h, n).force - law.friction(v - h, n).force) / (2.0 * h);
        let dn = (law.friction(v, n + h).force - law.friction(v, n - h).force) / (2.0 * h);
        assert!(
            (dv - f.d_slip).abs() < 1e-5 * (1.0 + dv.abs()),
            "d/dv {dv} vs {}",
            f.d_slip
        );
        assert!(
            (dn - f.d_normal).abs() < 1e-6,
            "d/dfn {dn} vs {}",
            f.d_normal
        );
    }

    /// Central differences of the spatial law against its derivatives.
    pub(crate) fn fd_tangent(law: &dyn FrictionLaw, v: Vector2<f64>, n: f64) {
        let h = (1e-3 * v.amax()).min(1e-7);
        let f = law.friction_tangent(v, n);
        for j in 0..2 {
            let mut e = Vector2::zeros();
            e[j] = h;
            let d = (law.friction_tangent(v + e, n).force - law.friction_tangent(v - e, n).force)
                / (2.0 * h);
            for i in 0..2 {
                assert!(
                    (d[i] - f.d_slip[(i, j)]).abs() < 1e-5 * (1.0 + d[i].abs()),
                    "∂f{i}/∂v{j}: {} vs {}",
                    d[i],
                    f.d_slip[(i, j)]
                );
            }
        }
        let h = 1e-7;
        let d = (law.friction_tangent(v, n + h).force - law.friction_tangent(v, n - h).force)
            / (2.0 * h);
        assert!((d - f.d_normal).amax() < 1e-6);
        // dissipation f_t·v_t ≤ 0
        assert!(f.force.dot(&v) <= 0.0);
    }

    fn laws() -> Vec<Box<dyn FrictionLaw>> {
        vec![
            Box::new(CoulombTanh {
                mu: 1.2,
                kappa: 40.0,
            }),
            Box::new(CreepRate {
                mu: 1.2,
                creep: 1e5,
            }),
            Box::new(Coulomb { mu: 0.85 }),
            Box::new(SlipRegularized {
                mu: 0.85,
                epsilon: 0.05,
            }),
            Box::new(Stribeck {
                mu_static: 0.6,
                mu_kinetic: 0.4,
                stribeck_velocity: 0.02,
                kappa: 200.0,
            }),
        ]
    }

    // Reference: finite differences away from the kinks; dissipativity f_t v_t ≤ 0.
    #[test]
    fn derivatives_and_dissipation() {
        for law in laws() {
            for (v, n) in [
                (0.003, 100.0),
                (-0.01, 50.0),
                (0.5, 20.0),
                (-2.0, 80.0),
                (1e-6, 300.0),
            ] {
                fd(law.as_ref(), v, n);
                assert!(law.friction(v, n).force * v <= 0.0);
                fd_tangent(law.as_ref(), Vector2::new(v, 0.3 * v), n);
                fd_tangent(law.as_ref(), Vector2::new(-0.7 * v, v), n);
            }
        }
    }

    // Reference: the spatial law along a tangent axis is the planar law (isotropy).
    #[test]
    fn spatial_law_reduces_to_planar() {
        for law in laws() {
            for v in [0.004, -0.3, 1.5] {
                let p = law.friction(v, 70.0).force;
                let s = law.friction_tangent(Vector2::new(0.0, v), 70.0).force;
                assert!(s[0].abs() < 1e-15 && (s[1] - p).abs() <= 1e-13 * p.abs());
            }
        }
    }

    // Reference: the one-contact solve satisfies its own equation f = f_t(r + B f) (smooth
    // laws) — the residual of the definition, independent of the Newton iteration.
    #[test]
    fn local_force_solves_its_equation() {
        let b = Matrix2::new(4e-3, 1e-3, 1e-3, 3e-3);
        for law in laws().into_iter().filter(|l| !l.is_set_valued()) {
            for r in [Vector2::new(0.2, -0.1), Vector2::new(-3.0, 0.5)] {
                let f = law.local_force(b, r, 200.0);
                let res = f - law.friction_tangent(r + b * f, 200.0).force;
                assert!(res.amax() <= 1e-9 * 200.0, "{law:?}: {res}");
            }
        }
    }
}
