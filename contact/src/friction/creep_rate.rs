//! Kerkkänen's tri-linear creep-rate friction law (Fig. 3.3, (3.23); ch. 4.5 for the plate belt).

use super::{FrictionForce, FrictionLaw};
use serde::{Deserialize, Serialize};

/// Kerkkänen's tri-linear creep-rate friction law (Fig. 3.3, seed note §4.3):
/// `|f_t| = min(ν_s |v_t|, μ |f_n|)`, `f_t = −sign(v_t) |f_t|` — a line of slope `ν_s`
/// \[kg/(m·s) per unit length\] through the origin saturated at the Coulomb bound.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct CreepRate {
    /// Friction coefficient `μ` \[-\].
    pub mu: f64,
    /// Creep-rate factor `ν_s` \[N·s/m per unit length\].
    pub creep: f64,
}

impl FrictionLaw for CreepRate {
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        let lin = self.creep * slip;
        let cap = self.mu * normal.abs();
        if lin.abs() <= cap {
            FrictionForce {
                force: -lin,
                d_slip: -self.creep,
                d_normal: 0.0,
            }
        } else {
            FrictionForce {
                force: -slip.signum() * cap,
                d_slip: 0.0,
                d_normal: -slip.signum() * self.mu * normal.signum(),
            }
        }
    }
    fn coefficient(&self) -> f64 {
        self.mu
    }
    /// The isotropic extension's force `f_t = −min(ν_s s, μ|f_n|) v_t/s`, `s = |v_t|` (zero at
    /// rest), of every point in one branch-free loop: the operations of the default
    /// [`FrictionLaw::friction_tangent_force`] with [`CreepRate::friction`] per point (for
    /// `s > 0`, `−sign(s) μ|f_n| = −μ|f_n|`), so the same values, vectorised.
    #[inline(always)]
    fn friction_tangent_forces(&self, slip: [&[f64]; 2], normal: &[f64], out: [&mut [f64]; 2]) {
        let n = normal.len();
        let (s1, s2) = (&slip[0][..n], &slip[1][..n]);
        let [o1, o2] = out;
        let (o1, o2) = (&mut o1[..n], &mut o2[..n]);
        for q in 0..n {
            let s = (s1[q] * s1[q] + s2[q] * s2[q]).sqrt();
            let lin = self.creep * s;
            let cap = self.mu * normal[q].abs();
            let f = if lin.abs() <= cap { -lin } else { -cap };
            let moving = s != 0.0;
            o1[q] = if moving { s1[q] / s * f } else { 0.0 };
            o2[q] = if moving { s2[q] / s * f } else { 0.0 };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: the tri-linear law's three branches (Kerkkänen Fig. 3.3).
    #[test]
    fn creep_rate_branches() {
        let law = CreepRate {
            mu: 1.2,
            creep: 1e4,
        };
        assert_eq!(law.friction(1e-3, 100.0).force, -10.0);
        assert_eq!(law.friction(1.0, 100.0).force, -120.0);
        assert_eq!(law.friction(-1.0, 100.0).force, 120.0);
    }

    // Reference: the default point-by-point `friction_tangent_force` (isotropic extension of
    // the planar law): the batch gives the same bits on both branches, at rest and for
    // negative normal forces.
    #[test]
    fn batch_forces_equal_the_point_by_point_law() {
        use nalgebra::Vector2;
        let law = CreepRate {
            mu: 0.6,
            creep: 2e5,
        };
        let s1 = [0.0, 1e-4, -3e-3, 0.2, -1e-7, 0.0];
        let s2 = [0.0, -2e-4, 1e-3, 0.0, 5e-8, 1e-2];
        let fnm = [10.0, 50.0, 800.0, 30.0, -20.0, 0.0];
        let (mut o1, mut o2) = ([9.0; 6], [9.0; 6]);
        law.friction_tangent_forces([&s1, &s2], &fnm, [&mut o1, &mut o2]);
        for q in 0..6 {
            let f = law.friction_tangent_force(Vector2::new(s1[q], s2[q]), fnm[q]);
            assert_eq!((o1[q], o2[q]), (f[0], f[1]), "point {q}");
        }
        assert!(o1[1] != 0.0 && o1[3] == -0.6 * 30.0);
    }
}
