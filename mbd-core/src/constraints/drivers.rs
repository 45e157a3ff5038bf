//! Rheonomic drivers: prescribed functions of time ([`DriverLaw`]) imposed on the relative
//! rotation of two markers ([`RotationDriver`]) or on one global coordinate of a marker point
//! ([`PointDriver`], Lin (7.7)–(7.9)).

use super::{Constraint, Equation, check_markers, check_reference, check_vec};
use crate::MbdError;
use crate::marker::{Carrier, Marker, Term};
use nalgebra::Vector3;
use std::sync::Arc;

/// Prescribed coordinate of a driver as a function of time: an angle \[rad\] for a
/// [`RotationDriver`], a position \[m\] for a [`PointDriver`] (the doc below speaks of angles).
#[derive(Clone)]
pub enum DriverLaw {
    /// `θ = θ₀ + ω t` \[rad\], ω \[rad/s\].
    ConstantSpeed {
        /// Initial angle \[rad\].
        theta0: f64,
        /// Angular speed \[rad/s\].
        omega: f64,
    },
    /// Smooth start to speed ω \[rad/s\] over `ramp` \[s\] (cubic speed ramp
    /// `ω(t) = ω (3τ² − 2τ³)`, τ = t/ramp), then constant speed.
    SpeedRamp {
        /// Initial angle \[rad\].
        theta0: f64,
        /// Final angular speed \[rad/s\].
        omega: f64,
        /// Ramp duration \[s\].
        ramp: f64,
    },
    /// Piecewise-linear angular speed through the points `(times[k], speeds[k])` \[s, rad/s\]
    /// (constant before the first and after the last point); θ is its exact integral.
    SpeedTable {
        /// Angle at t = 0 \[rad\].
        theta0: f64,
        /// Strictly increasing times \[s\].
        times: Vec<f64>,
        /// Angular speeds \[rad/s\].
        speeds: Vec<f64>,
    },
    /// User function `t ↦ (θ, θ̇, θ̈)` \[rad, rad/s, rad/s²\].
    Custom(Arc<dyn Fn(f64) -> (f64, f64, f64) + Send + Sync>),
}

impl std::fmt::Debug for DriverLaw {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DriverLaw::ConstantSpeed { theta0, omega } => {
                write!(f, "ConstantSpeed {{ theta0: {theta0}, omega: {omega} }}")
            }
            DriverLaw::SpeedRamp {
                theta0,
                omega,
                ramp,
            } => {
                write!(
                    f,
                    "SpeedRamp {{ theta0: {theta0}, omega: {omega}, ramp: {ramp} }}"
                )
            }
            DriverLaw::SpeedTable {
                theta0,
                times,
                speeds,
            } => write!(
                f,
                "SpeedTable {{ theta0: {theta0}, times: {times:?}, speeds: {speeds:?} }}"
            ),
            DriverLaw::Custom(_) => write!(f, "Custom(..)"),
        }
    }
}

impl DriverLaw {
    /// `(θ, θ̇, θ̈)` at time `t` \[s\].
    pub fn eval(&self, t: f64) -> (f64, f64, f64) {
        match self {
            DriverLaw::ConstantSpeed { theta0, omega } => (theta0 + omega * t, *omega, 0.0),
            DriverLaw::SpeedRamp {
                theta0,
                omega,
                ramp,
            } => {
                if *ramp <= 0.0 || t >= *ramp {
                    let r = ramp.max(0.0);
                    // angle accumulated during the ramp: ∫ ω(3τ²−2τ³) dt = ω r / 2
                    (theta0 + omega * (0.5 * r + (t - r)), *omega, 0.0)
                } else if t <= 0.0 {
                    (*theta0, 0.0, 0.0)
                } else {
                    let tau = t / ramp;
                    let th = theta0 + omega * ramp * (tau.powi(3) - 0.5 * tau.powi(4));
                    let w = omega * (3.0 * tau * tau - 2.0 * tau.powi(3));
                    let a = omega / ramp * (6.0 * tau - 6.0 * tau * tau);
                    (th, w, a)
                }
            }
            DriverLaw::SpeedTable {
                theta0,
                times,
                speeds,
            } => speed_table(*theta0, times, speeds, t),
            DriverLaw::Custom(f) => f(t),
        }
    }

    /// Checks the parameters (finite values; speed table sorted and of matching lengths).
    pub fn validate(&self, name: &str) -> Result<(), MbdError> {
        let bad = |reason: String| MbdError::InvalidInput {
            item: format!("driver \"{name}\""),
            reason,
        };
        match self {
            DriverLaw::ConstantSpeed { theta0, omega } => {
                if !(theta0.is_finite() && omega.is_finite()) {
                    return Err(bad("theta0 and omega must be finite".into()));
                }
            }
            DriverLaw::SpeedRamp {
                theta0,
                omega,
                ramp,
            } => {
                if !(theta0.is_finite() && omega.is_finite() && ramp.is_finite() && *ramp >= 0.0) {
                    return Err(bad("theta0, omega finite and ramp >= 0 required".into()));
                }
            }
            DriverLaw::SpeedTable {
                theta0,
                times,
                speeds,
            } => {
                if times.is_empty() || times.len() != speeds.len() {
                    return Err(bad(format!(
                        "speed table needs as many times ({}) as speeds ({}), at least one",
                        times.len(),
                        speeds.len()
                    )));
                }
                if !theta0.is_finite() || times.iter().chain(speeds).any(|x| !x.is_finite()) {
                    return Err(bad("non-finite value in the speed table".into()));
                }
                if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
                    return Err(bad(format!(
                        "times must increase strictly (entry {} = {} s)",
                        k + 1,
                        times[k + 1]
                    )));
                }
            }
            DriverLaw::Custom(_) => {}
        }
        Ok(())
    }
}

/// θ, θ̇, θ̈ of a piecewise-linear speed table (exact integral: trapezoids between breakpoints).
fn speed_table(theta0: f64, times: &[f64], speeds: &[f64], t: f64) -> (f64, f64, f64) {
    let n = times.len();
    if n == 0 || n != speeds.len() {
        return (theta0, 0.0, 0.0);
    }
    let speed = |x: f64| -> (f64, f64) {
        if x <= times[0] {
            (speeds[0], 0.0)
        } else if x >= times[n - 1] {
            (speeds[n - 1], 0.0)
        } else {
            let k = times.partition_point(|&tk| tk <= x) - 1;
            let slope = (speeds[k + 1] - speeds[k]) / (times[k + 1] - times[k]);
            (speeds[k] + slope * (x - times[k]), slope)
        }
    };
    let (a, b, sign) = if t >= 0.0 {
        (0.0, t, 1.0)
    } else {
        (t, 0.0, -1.0)
    };
    let mut acc = 0.0;
    let mut x0 = a;
    for x1 in times.iter().copied().filter(|&x| x > a && x < b).chain([b]) {
        acc += 0.5 * (speed(x0).0 + speed(x1).0) * (x1 - x0);
        x0 = x1;
    }
    let (w, alpha) = speed(t);
    (theta0 + sign * acc, w, alpha)
}

/// Rheonomic rotation driver: the angle θ(t) of body j relative to body i about the axis
/// `i.axis`, measured from `reference_i` (body i, ⊥ axis) to `reference_j` (body j).
/// Use together with a revolute joint (it fixes only the angle):
/// `Φ = cos θ_d (x_j·y_i) − sin θ_d (x_j·x_i) = 0`, i.e. `sin(θ − θ_d) = 0` (1 equation; no
/// angle wrap-around).
#[derive(Debug, Clone)]
pub struct RotationDriver {
    /// Name.
    pub name: String,
    /// Frame on body i (the axis).
    pub i: Marker,
    /// Body j (point and axis unused).
    pub j: Marker,
    /// Zero-angle direction on body i (⊥ `i.axis`).
    pub reference_i: Vector3<f64>,
    /// Direction on body j that is rotated by θ from `reference_i`.
    pub reference_j: Vector3<f64>,
    /// Prescribed angle.
    pub law: DriverLaw,
}

impl RotationDriver {
    fn validate_extra(&self) -> Result<(), MbdError> {
        check_reference(&self.name, "reference_i", &self.i.axis, &self.reference_i)?;
        check_vec(&self.name, "reference_j", &self.reference_j, true)?;
        self.law.validate(&self.name)
    }
}

impl Constraint for RotationDriver {
    common!(1);
    fn eval(&self, t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let a = self.i.axis;
        let xi = (self.reference_i - a * a.dot(&self.reference_i)).normalize();
        let yi = a.cross(&xi);
        let xj = Term::vector(cj, &self.j, &self.reference_j, 1);
        let c1 = Term::vector(ci, &self.i, &yi, 0).dot(&xj); // sin θ
        let c2 = Term::vector(ci, &self.i, &xi, 0).dot(&xj); // cos θ
        let (th, thd, thdd) = self.law.eval(t);
        let (s, c) = th.sin_cos();
        let row = c1.scaled(c).add(&c2.scaled(-s));
        // Φ = C c1 − S c2; Φ_t = −θ̇ (S c1 + C c2)
        let sc = s * c1.phi + c * c2.phi;
        let scdot = s * c1.rate + c * c2.rate;
        let nu = thd * sc;
        // Φ̈ = C c̈1 − S c̈2 − 2θ̇ (S ċ1 + C ċ2) − θ̈ (S c1 + C c2) − θ̇² (C c1 − S c2)
        let gamma = -row.quad + 2.0 * thd * scdot + thdd * sc + thd * thd * row.phi;
        let mut row = row;
        row.rate -= thd * sc; // total Φ̇
        out.push(Equation { row, nu, gamma });
    }
}

/// Rheonomic point driver (Lin (7.7)–(7.9)): the global component `component` (0, 1, 2 = x, y,
/// z) of the marker point follows the law, `Φ = d_c − x(t) = 0`, `ν = ẋ(t)`,
/// `γ = ẍ(t) − (velocity-quadratic part of d̈_c)` (1 equation).
#[derive(Debug, Clone)]
pub struct PointDriver {
    /// Name.
    pub name: String,
    /// The driven marker point.
    pub point: Marker,
    /// Global component 0, 1, 2 (x, y, z).
    pub component: usize,
    /// Prescribed position `x(t)` \[m\] (with `ẋ` \[m/s\] and `ẍ` \[m/s²\]).
    pub law: DriverLaw,
}

impl Constraint for PointDriver {
    fn name(&self) -> &str {
        &self.name
    }
    fn n_eq(&self) -> usize {
        1
    }
    fn markers(&self) -> [Marker; 2] {
        [self.point, Marker::ground()]
    }
    fn validate(&self) -> Result<(), MbdError> {
        check_vec(&self.name, "point.point", &self.point.point, false)?;
        if self.component > 2 {
            return Err(MbdError::InvalidInput {
                item: format!("constraint \"{}\": component", self.name),
                reason: format!("{} is not 0, 1 or 2", self.component),
            });
        }
        self.law.validate(&self.name)
    }
    fn eval(&self, t: f64, ci: &Carrier, _cj: &Carrier, out: &mut Vec<Equation>) {
        let d = Term::point(ci, &self.point, 0);
        let mut row = d.component(self.component);
        let (x, xd, xdd) = self.law.eval(t);
        row.phi -= x;
        let gamma = xdd - row.quad;
        row.rate -= xd; // total Φ̇
        out.push(Equation { row, nu: xd, gamma });
    }
}
