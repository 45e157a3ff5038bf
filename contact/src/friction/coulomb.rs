//! Set-valued Coulomb friction with stick (Ribaric §7.3, §8.4.3), with the Alart–Curnier
//! projection onto the friction disk (Alart & Curnier 1991).

use super::{Augmented, FrictionForce, FrictionLaw};
use mbd_core::roots::{Stop, bisect};
use nalgebra::{Matrix2, Vector2};
use serde::{Deserialize, Serialize};

/// Coulomb friction `|f_t| ≤ μ f_n`, `f_t = −μ f_n v_t/|v_t|` when slipping (stick inside the
/// disk). Its single-valued slip branch ([`FrictionLaw::friction`]) is Ribaric's §8.4.3 node
/// law `F_T = −μ |F_N| sign(v_t)` with `sign(0) = 0` and `∂F_T/∂v_t = 0`; a semismooth solver
/// uses the projection [`FrictionLaw::augmented`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Coulomb {
    /// Friction coefficient `μ` \[-\] (Ribaric: 0.85 nominal, 0 for pure slip).
    pub mu: f64,
}

impl FrictionLaw for Coulomb {
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        let s = if slip > 0.0 {
            1.0
        } else if slip < 0.0 {
            -1.0
        } else {
            0.0
        };
        FrictionForce {
            force: -self.mu * normal.abs() * s,
            d_slip: 0.0,
            d_normal: -self.mu * s * normal.signum(),
        }
    }
    fn coefficient(&self) -> f64 {
        self.mu
    }
    fn is_set_valued(&self) -> bool {
        true
    }

    /// `p = proj_{disk(ρ)}(z)`, `z = f − r_T u`, `ρ = μ λ̂` (Alart & Curnier 1991). Inside the
    /// disk (stick) `p = z`: `∂p/∂f = I`, `∂p/∂u = −r_T I`. Outside (slip) `p = ρ ẑ`:
    /// `∂p/∂f = a Q`, `∂p/∂u = −a r_T Q`, `∂p/∂λ̂ = μ ẑ` with `a = ρ/|z|`, `Q = I − ẑ ẑᵀ`.
    /// With `ρ ≤ 0` the disk is a point: `p = 0` whatever the slip.
    fn augmented(
        &self, f: Vector2<f64>, u: Vector2<f64>, normal: f64, rt: f64, jacobian: bool,
    ) -> Augmented {
        let rho = self.mu * normal;
        let z = Vector2::new(f[0] - rt * u[0], f[1] - rt * u[1]);
        let nz = z[0].hypot(z[1]);
        if rho <= 0.0 {
            Augmented::default()
        } else if nz <= rho {
            Augmented {
                target: z,
                d_force: Matrix2::identity(),
                d_slip: Matrix2::identity() * (-rt),
                d_normal: Vector2::zeros(),
                stick: true,
            }
        } else {
            let target = Vector2::new(rho * z[0] / nz, rho * z[1] / nz);
            if !jacobian {
                return Augmented {
                    target,
                    ..Augmented::default()
                };
            }
            let zh = Vector2::new(z[0] / nz, z[1] / nz);
            let a = rho / nz;
            let q = Matrix2::identity() - zh * zh.transpose();
            Augmented {
                target,
                d_force: q * a,
                d_slip: -(q * (a * rt)),
                d_normal: zh * self.mu,
                stick: false,
            }
        }
    }

    /// Stick `f = −B⁻¹ r` if `|B⁻¹ r| ≤ ρ`, else `f = −(B + νI)⁻¹ r` with `ν > 0` such that
    /// `|f| = ρ` (then `u = −ν f`: slip opposite to the force), by bisection on `ν`.
    fn local_force(&self, b: Matrix2<f64>, r: Vector2<f64>, normal: f64) -> Vector2<f64> {
        let rho = self.mu * normal;
        if rho <= 0.0 {
            return Vector2::zeros();
        }
        let solve = |nu: f64| {
            let a = [[b[(0, 0)] + nu, b[(0, 1)]], [b[(1, 0)], b[(1, 1)] + nu]];
            let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
            Vector2::new(
                -(a[1][1] * r[0] - a[0][1] * r[1]) / det,
                -(-a[1][0] * r[0] + a[0][0] * r[1]) / det,
            )
        };
        let f0 = solve(0.0);
        if f0[0].hypot(f0[1]) <= rho {
            return f0;
        }
        let bn =
            (b[(0, 0)].powi(2) + b[(0, 1)].powi(2) + b[(1, 0)].powi(2) + b[(1, 1)].powi(2)).sqrt();
        let inside = |s: f64| {
            let f = solve(s);
            // not outside the disc (a NaN norm counts as inside, as before)
            f[0].hypot(f[1]).partial_cmp(&rho) != Some(std::cmp::Ordering::Greater)
        };
        let hi = bisect(
            0.0,
            bn + r[0].hypot(r[1]) / rho,
            inside,
            Stop::iterations(200),
        )
        .1;
        let f = solve(hi);
        let nf = f[0].hypot(f[1]);
        if nf > 0.0 {
            Vector2::new(rho * f[0] / nf, rho * f[1] / nf)
        } else {
            f
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: central differences of the projection off the disk boundary (the generalised
    // derivative is the classical one there), and the stick/slip split by |z| vs ρ.
    #[test]
    fn projection_derivatives() {
        let law = Coulomb { mu: 0.85 };
        let (rt, lam) = (50.0, 10.0);
        for (f, u) in [
            (Vector2::new(3.0, -1.0), Vector2::new(0.4, 0.2)),
            (Vector2::new(1.0, 0.5), Vector2::new(0.01, -0.02)),
        ] {
            let a = law.augmented(f, u, lam, rt, true);
            let z = f - u * rt;
            assert_eq!(a.stick, z.norm() <= 0.85 * lam);
            let h = 1e-7;
            for j in 0..2 {
                let mut e = Vector2::zeros();
                e[j] = h;
                let df = (law.augmented(f + e, u, lam, rt, false).target
                    - law.augmented(f - e, u, lam, rt, false).target)
                    / (2.0 * h);
                let du = (law.augmented(f, u + e, lam, rt, false).target
                    - law.augmented(f, u - e, lam, rt, false).target)
                    / (2.0 * h);
                for i in 0..2 {
                    assert!((df[i] - a.d_force[(i, j)]).abs() < 1e-6);
                    assert!((du[i] - a.d_slip[(i, j)]).abs() < 1e-5 * rt);
                }
            }
            let dl = (law.augmented(f, u, lam + h, rt, false).target
                - law.augmented(f, u, lam - h, rt, false).target)
                / (2.0 * h);
            assert!((dl - a.d_normal).amax() < 1e-6);
        }
    }

    // Reference: the one-contact solve meets the Coulomb conditions (stick: u = 0; slip:
    // |f| = μλ and u = −ν f with ν > 0).
    #[test]
    fn local_force_meets_coulomb() {
        let law = Coulomb { mu: 0.5 };
        let b = Matrix2::new(2e-3, 5e-4, 5e-4, 1e-3);
        let stick = law.local_force(b, Vector2::new(1e-3, 0.0), 10.0);
        assert!((b * stick + Vector2::new(1e-3, 0.0)).amax() < 1e-15);
        let r = Vector2::new(0.3, -0.2);
        let f = law.local_force(b, r, 10.0);
        let u = r + b * f;
        assert!((f.norm() - 5.0).abs() < 1e-12);
        assert!(u.dot(&f) < 0.0 && (u.perp(&f)).abs() < 1e-9 * u.norm() * f.norm());
    }
}
