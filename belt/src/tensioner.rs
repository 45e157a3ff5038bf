//! An automatic belt tensioner: a pivoted arm carrying an idler pulley, loaded by a torsional
//! spring with preload, a viscous damper and optional dry (Coulomb) friction at the pivot.
//!
//! The arm turns about its pivot `p`; its angle `θ` \[rad\] is measured counter-clockwise from
//! the x axis to the line from the pivot to the idler centre, so the idler centre is
//!
//! ```text
//!   c(θ) = p + L (cos θ, sin θ),   c'(θ) = L (−sin θ, cos θ),   c''(θ) = −(c − p)
//! ```
//!
//! and the arm's equation of motion (counter-clockwise moments positive) is
//!
//! ```text
//!   J θ̈ = M_s(θ) + M_d(θ̇) + M_f(θ̇) + (c − p) × F_hub
//!   M_s = M_0 − k (θ − θ_0)        (torsional spring with preload M_0 at θ_0)
//!   M_d = −c_d θ̇                   (viscous damper)
//!   M_f = −M_c tanh(θ̇ / ω_f)       (dry friction, regularised as Ribaric (6.2))
//! ```
//!
//! with `F_hub` the force of the belt on the idler. A belt model evaluates the dry friction
//! with the contact crate's friction law (`contact::friction::CoulombTanh` with `μ = 1`,
//! `κ = 1/ω_f` and normal force `M_c`; see [`Tensioner::dry_friction`]), so the
//! regularisation is the one of the belt–pulley contact. The end stops of the arm's travel are
//! not modelled as impacts: a static arm angle outside the travel is rejected as bad input, and
//! studies report the arm's excursion against the travel.
//!
//! Statics by hand (the validation reference): with equal tension `T` in the two spans at the
//! idler, arriving along the unit travel direction `d_in` and leaving along `d_out`, the belt
//! pulls the idler with `F_hub = T (d_out − d_in)`, and the static arm angle solves
//! `M_s(θ) + (c(θ) − p) × F_hub(θ) = 0` ([`Tensioner::static_angle`]).

use contact::friction::{CoulombTanh, FrictionForce, FrictionLaw};
use mbd_core::roots::{Stop, bisect};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// A pivoted-arm tensioner (see the module documentation). The idler is a pulley of the
/// layout, named by index; the arm length and the arm's installed angle follow from the
/// idler's centre in the layout and the pivot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Tensioner {
    /// Index of the idler pulley (in the layout's pulley list) carried by the arm.
    pub pulley: usize,
    /// Pivot position (x, y) \[m\].
    #[serde(deserialize_with = "mbd_core::validate::exact_array")]
    pub pivot: [f64; 2],
    /// Torsional spring stiffness `k` \[N m/rad\].
    pub stiffness: f64,
    /// Spring moment `M_0` at the angle `preload_angle` \[N m\], counter-clockwise positive.
    pub preload: f64,
    /// Arm angle `θ_0` at which the spring moment is `preload` \[rad\] (counter-clockwise from x).
    pub preload_angle: f64,
    /// Viscous damping coefficient `c_d` \[N m s/rad\].
    #[serde(default)]
    pub damping: f64,
    /// Dry-friction moment `M_c` at the pivot \[N m\] (0: none).
    #[serde(default)]
    pub dry_friction: f64,
    /// Regularisation rate `ω_f` of the dry friction \[rad/s\] (moment `M_c tanh(θ̇/ω_f)`).
    #[serde(default = "default_friction_rate")]
    pub friction_rate: f64,
    /// Moment of inertia of arm and idler about the pivot \[kg m²\].
    pub inertia: f64,
    /// Allowed arm travel `[θ_min, θ_max]` \[rad\] (counter-clockwise from x).
    #[serde(deserialize_with = "mbd_core::validate::exact_array")]
    pub travel: [f64; 2],
}

fn default_friction_rate() -> f64 {
    0.01
}

impl Validate for Tensioner {
    fn validate(&self) -> Result<(), InvalidField> {
        check::finite("pivot[0]", self.pivot[0])?;
        check::finite("pivot[1]", self.pivot[1])?;
        check::positive("stiffness", self.stiffness, "N m/rad")?;
        check::finite("preload", self.preload)?;
        check::finite("preload_angle", self.preload_angle)?;
        check::non_negative("damping", self.damping, "N m s/rad")?;
        check::non_negative("dry_friction", self.dry_friction, "N m")?;
        check::positive("friction_rate", self.friction_rate, "rad/s")?;
        check::positive("inertia", self.inertia, "kg m²")?;
        check::finite("travel[0]", self.travel[0])?;
        check::finite("travel[1]", self.travel[1])?;
        if self.travel[1] <= self.travel[0] {
            return Err(InvalidField::new(
                "travel",
                format!(
                    "must be [min, max] with min < max, got [{}, {}]",
                    self.travel[0], self.travel[1]
                ),
            ));
        }
        if self.travel[1] - self.travel[0] >= std::f64::consts::PI {
            return Err(InvalidField::new(
                "travel",
                "must span less than π rad (an arm does not swing half a turn)",
            ));
        }
        Ok(())
    }
}

/// `a × b` of planar vectors.
pub fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

impl Tensioner {
    /// A tensioner on pulley `pulley` pivoting about `pivot` \[m\] with spring rate
    /// `stiffness` \[N m/rad\] and moment `preload` \[N m\] at the arm angle `preload_angle`
    /// \[rad\]; damper 0.5 N m s/rad, no dry friction, arm inertia 2·10⁻³ kg m², travel
    /// ±0.6 rad about `preload_angle` (a typical automotive tensioner: Beikmann, Perkins &
    /// Ulsoy 1997).
    pub fn new(
        pulley: usize, pivot: [f64; 2], stiffness: f64, preload: f64, preload_angle: f64,
    ) -> Self {
        Self {
            pulley,
            pivot,
            stiffness,
            preload,
            preload_angle,
            damping: 0.5,
            dry_friction: 0.0,
            friction_rate: default_friction_rate(),
            inertia: 2e-3,
            travel: [preload_angle - 0.6, preload_angle + 0.6],
        }
    }

    /// Arm length `L` \[m\] and angle `θ` \[rad\] of an idler centred at `center`.
    pub fn arm(&self, center: [f64; 2]) -> (f64, f64) {
        let r = [center[0] - self.pivot[0], center[1] - self.pivot[1]];
        (r[0].hypot(r[1]), r[1].atan2(r[0]))
    }

    /// Idler centre `c(θ)` \[m\] and `c'(θ) = dc/dθ` \[m/rad\] for an arm of length `length`.
    pub fn center(&self, length: f64, angle: f64) -> ([f64; 2], [f64; 2]) {
        let (s, c) = angle.sin_cos();
        (
            [self.pivot[0] + length * c, self.pivot[1] + length * s],
            [-length * s, length * c],
        )
    }

    /// Spring moment `M_s = M_0 − k (θ − θ_0)` \[N m\] and `dM_s/dθ` \[N m/rad\].
    pub fn spring_moment(&self, angle: f64) -> (f64, f64) {
        (
            self.preload - self.stiffness * (angle - self.preload_angle),
            -self.stiffness,
        )
    }

    /// Damper moment `M_d = −c_d θ̇` \[N m\] and `dM_d/dθ̇`.
    pub fn damper_moment(&self, rate: f64) -> (f64, f64) {
        (-self.damping * rate, -self.damping)
    }

    /// Dry-friction moment at the pivot \[N m\] and its derivative with respect to the arm
    /// rate \[N m s/rad\]: the contact crate's tanh law (Ribaric (6.2)) with `μ = 1`,
    /// `κ = 1/ω_f`, normal force `M_c` and the arm rate `θ̇` \[rad/s\] as slip, i.e.
    /// `−M_c tanh(θ̇/ω_f)`. Shared by every belt model that carries a tensioner arm.
    pub fn dry_friction(&self, rate: f64) -> FrictionForce {
        CoulombTanh {
            mu: 1.0,
            kappa: 1.0 / self.friction_rate,
        }
        .friction(rate, self.dry_friction)
    }

    /// Spring, damper and dry-friction moment on the arm \[N m\] at angle `angle` \[rad\] and
    /// rate `rate` \[rad/s\], with its derivatives `(∂/∂θ, ∂/∂θ̇)` (module documentation).
    pub fn moment(&self, angle: f64, rate: f64) -> (f64, f64, f64) {
        let (ms, ks) = self.spring_moment(angle);
        let (md, cd) = self.damper_moment(rate);
        let fr = self.dry_friction(rate);
        (ms + md + fr.force, ks, cd + fr.d_slip)
    }

    /// Whether `angle` \[rad\] lies within the travel.
    pub fn within_travel(&self, angle: f64) -> bool {
        (self.travel[0]..=self.travel[1]).contains(&angle)
    }

    /// Static arm angle: the root of `M_s(θ) + belt_moment(θ) = 0` in the travel, where
    /// `belt_moment(θ)` \[N m\] is the moment of the belt's hub force on the idler about the
    /// pivot with the arm at `θ` (`(c − p) × F_hub`, see the module documentation). Bisection
    /// over the travel (the spring moment decreases with θ; the belt moment is assumed to
    /// make the sum change sign once). `None` when the sum has the same sign at both ends of
    /// the travel: the arm would rest on a stop.
    pub fn static_angle(&self, belt_moment: impl Fn(f64) -> f64) -> Option<f64> {
        let g = |a: f64| self.spring_moment(a).0 + belt_moment(a);
        let (lo, hi) = (self.travel[0], self.travel[1]);
        let (glo, ghi) = (g(lo), g(hi));
        if !(glo.is_finite() && ghi.is_finite()) || glo * ghi > 0.0 {
            return None;
        }
        let s = glo.signum();
        let (lo, hi) = bisect(
            lo,
            hi,
            |a| (g(a) * s).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater),
            Stop::absolute(200, 1e-14),
        );
        Some(0.5 * (lo + hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> Tensioner {
        Tensioner {
            pulley: 2,
            pivot: [0.1, 0.0],
            stiffness: 40.0,
            preload: 20.0,
            preload_angle: 1.0,
            damping: 0.5,
            dry_friction: 1.0,
            friction_rate: 0.01,
            inertia: 1e-3,
            travel: [0.5, 1.5],
        }
    }

    // Closed form (independent of the bisection): with a belt moment linear in the angle,
    // −B (θ − θ_b), the root of M_0 − k (θ − θ_0) − B (θ − θ_b) = 0 is
    // θ = (M_0 + k θ_0 + B θ_b)/(k + B).
    #[test]
    fn static_angle_of_a_linear_moment_is_exact() {
        let s = spec();
        let (b, tb) = (25.0, 0.9);
        let th = s.static_angle(|a| -b * (a - tb)).unwrap();
        let exact = (s.preload + s.stiffness * s.preload_angle + b * tb) / (s.stiffness + b);
        assert!((th - exact).abs() < 1e-12, "{th} vs {exact}");
        // a belt moment that never balances the spring (M_s ≥ 0 over the travel, belt
        // moment +5 N m): the arm rests on its stop, no root in the travel
        assert!(s.static_angle(|_| 5.0).is_none());
    }

    // Geometry: c(θ) on the circle of radius L about the pivot; c' the derivative (central
    // difference, an independent evaluation).
    #[test]
    fn arm_geometry_round_trips() {
        let s = spec();
        let (c, dc) = s.center(0.08, 0.7);
        let (l, a) = s.arm(c);
        assert!((l - 0.08).abs() < 1e-15 && (a - 0.7).abs() < 1e-14);
        let h = 1e-7;
        let (cp, _) = s.center(0.08, 0.7 + h);
        let (cm, _) = s.center(0.08, 0.7 - h);
        for k in 0..2 {
            assert!(((cp[k] - cm[k]) / (2.0 * h) - dc[k]).abs() < 1e-8);
        }
        assert_eq!(s.spring_moment(1.0).0, 20.0);
        assert_eq!(s.spring_moment(1.5).0, 0.0);
        assert_eq!(s.damper_moment(2.0).0, -1.0);
    }

    #[test]
    fn validation_names_the_field() {
        let mut s = spec();
        s.travel = [1.0, 0.5];
        assert_eq!(s.validate().unwrap_err().field, "travel");
        let mut s = spec();
        s.stiffness = -1.0;
        assert_eq!(s.validate().unwrap_err().field, "stiffness");
        assert!(spec().validate().is_ok());
    }
}
