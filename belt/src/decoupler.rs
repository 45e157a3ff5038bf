//! A decoupler between an accessory pulley and its accessory (issue 36 item 4): a torsional
//! spring with a damper, and optionally a one-way clutch (an overrunning alternator
//! decoupler; without the clutch, an isolator pulley).
//!
//! The chain, every angle and speed in the belt's travel sense ([`crate::pulley`]):
//!
//! ```text
//!   pulley hub (J_p, φ_p) ─ spring k, damper c_s ─ carrier (J_r, φ_r) ─ one-way clutch ─ accessory (J_a, φ_a)
//!
//!   S = k (φ_p − φ_r) + c_s (ω_p − ω_r)                spring torque            (D1)
//!   C = c_l · ½ (x + √(x² + ε²)),   x = ω_r − ω_a         clutch torque            (D2)
//!   J_p ω̇_p = τ_belt − S
//!   J_r ω̇_r = S − C
//!   J_a ω̇_a = C − M_load(t) − c ω_a                                             (D3)
//! ```
//!
//! Without the clutch the spring acts on the accessory directly (`φ_r ≡ φ_a`, no carrier):
//! `J_p ω̇_p = τ_belt − S`, `J_a ω̇_a = S − M_load(t) − c ω_a`.
//!
//! **The clutch law (D2) is a smooth regularisation, not an event.** An ideal one-way clutch
//! locks the carrier to the accessory while the carrier would run ahead of it (the pulley
//! drives the accessory: `S ≥ 0` transmitted) and lets the accessory overrun freely otherwise.
//! (D2) replaces the lock by a stiff viscous coupling `c_l` acting only in the driving sense,
//! its kink at `x = 0` rounded over `ε` (`C = c_l x` for `x ≫ ε`, `C → c_l ε²/(4|x|) → 0`
//! overrunning): engaged, the carrier creeps ahead of the accessory by `x ≈ C/c_l`; open, the
//! clutch transmits less than `c_l ε²/(4|x|)`. The light carrier between spring and clutch is
//! what lets the spring unwind while the accessory overruns (a clutch acting on the spring's
//! own angle `k (φ_p − φ_a) ≥ 0` would keep the overrun angle and re-engage only once the
//! pulley had caught it up). The clutch is [`ClutchState::Engaged`] while `x > 0` (the carrier
//! drives the accessory), [`ClutchState::Overrunning`] otherwise.
//!
//! The accessory's own load `M_load`, damping `c` and inertia `J_a` are those of
//! [`crate::Motion::Load`]; a decoupler adds the carrier's and the accessory's rotation
//! coordinates (only the accessory's without the clutch) to a model that supports it.

use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// A decoupler between a loaded pulley and its accessory (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Decoupler {
    /// Moment of inertia of the pulley hub `J_p` \[kg m²\] (the belt's side of the spring).
    pub pulley_inertia: f64,
    /// Torsional stiffness of the spring `k` \[N m/rad\] (D1).
    pub stiffness: f64,
    /// Viscous damping of the spring `c_s` \[N m s/rad\] (D1).
    #[serde(default)]
    pub damping: f64,
    /// With a one-way clutch between spring and accessory (an overrunning decoupler; `false`:
    /// an isolator, the spring drives the accessory both ways).
    #[serde(default = "yes")]
    pub clutch: bool,
    /// Moment of inertia of the carrier between spring and clutch `J_r` \[kg m²\] (default
    /// 2·10⁻⁵: a steel clutch race and spring end of about 50 g at 20 mm radius, `m r²`;
    /// an estimate, not a datasheet value).
    #[serde(default = "default_carrier")]
    pub carrier_inertia: f64,
    /// Regularising viscous coefficient of the engaged clutch `c_l` \[N m s/rad\] (D2;
    /// default 1000: an engaged clutch carrying 5 N m creeps by 5 mrad/s, under 0.01 % of an
    /// accessory's speed; the carrier's time constant `J_r/c_l` is then far below any step,
    /// a stiff, damped coordinate for the implicit steppers).
    #[serde(default = "default_lock_damping")]
    pub lock_damping: f64,
    /// Rounding `ε` of the clutch's kink \[rad/s\] (D2; default 10⁻³: an overrunning clutch
    /// 10 rad/s behind drags by `c_l ε²/(4|x|)` = 2.5·10⁻⁵ N m).
    #[serde(default = "default_lock_speed")]
    pub lock_speed: f64,
}

fn yes() -> bool {
    true
}
fn default_carrier() -> f64 {
    2e-5
}
fn default_lock_damping() -> f64 {
    1000.0
}
fn default_lock_speed() -> f64 {
    1e-3
}

/// Whether a one-way clutch transmits (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ClutchState {
    /// The carrier drives the accessory (`ω_r > ω_a`).
    Engaged,
    /// The accessory runs ahead of the carrier (`ω_r ≤ ω_a`): the clutch is open.
    Overrunning,
}

/// A decoupler's state at one instant, for the outputs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DecouplerState {
    /// Accessory speed `ω_a` \[rad/s\] (travel sense).
    pub accessory_speed: f64,
    /// Spring torque `S` \[N m\] (D1).
    pub spring_torque: f64,
    /// Torque the clutch transmits to the accessory `C` \[N m\] (D2; the spring torque
    /// without a clutch).
    pub clutch_torque: f64,
    /// The clutch's state (`None`: no clutch).
    pub clutch: Option<ClutchState>,
}

/// Generalized forces of a decoupler on its local coordinates `[φ_p, φ_r, φ_a]` (`[φ_p, φ_a]`
/// without a clutch) and their derivatives.
#[derive(Debug, Clone, PartialEq)]
pub struct DecouplerForces {
    /// Forces `f` \[N m\] (right-hand sides of (D3) without the belt's torque).
    pub f: Vec<f64>,
    /// `∂f_i/∂q_j` \[N m/rad\].
    pub df_dq: Vec<Vec<f64>>,
    /// `∂f_i/∂v_j` \[N m s/rad\].
    pub df_dv: Vec<Vec<f64>>,
}

impl Decoupler {
    /// Number of local coordinates: 3 with the clutch (pulley, carrier, accessory), 2 without.
    pub fn n_local(&self) -> usize {
        if self.clutch { 3 } else { 2 }
    }

    /// Rotation coordinates the decoupler adds to a model besides the pulley's own.
    pub fn n_extra(&self) -> usize {
        self.n_local() - 1
    }

    /// Moments of inertia of the local coordinates \[kg m²\] with the accessory's
    /// `accessory_inertia`.
    pub fn inertias(&self, accessory_inertia: f64) -> Vec<f64> {
        let mut j = vec![self.pulley_inertia];
        if self.clutch {
            j.push(self.carrier_inertia);
        }
        j.push(accessory_inertia);
        j
    }

    /// Clutch torque `C` (D2) and `dC/dx` at the slip speed `x = ω_r − ω_a` \[rad/s\].
    pub fn clutch_torque(&self, x: f64) -> (f64, f64) {
        let r = x.hypot(self.lock_speed);
        (
            0.5 * self.lock_damping * (x + r),
            0.5 * self.lock_damping * (1.0 + x / r),
        )
    }

    /// Forces (D3) on the local coordinates at angles `q` \[rad\] and speeds `v` \[rad/s\]
    /// with the accessory's applied torque `(−M_load − c ω_a, −c)`
    /// ([`crate::Motion::applied_torque`] at `ω_a`).
    pub fn forces(&self, q: &[f64], v: &[f64], accessory: (f64, f64)) -> DecouplerForces {
        let n = self.n_local();
        let (k, cs) = (self.stiffness, self.damping);
        let mut f = vec![0.0; n];
        let mut kq = vec![vec![0.0; n]; n];
        let mut cv = vec![vec![0.0; n]; n];
        // the spring between the pulley (0) and the carrier or accessory (1)
        let s = k * (q[0] - q[1]) + cs * (v[0] - v[1]);
        f[0] -= s;
        f[1] += s;
        for (a, sa) in [(0, -1.0), (1, 1.0)] {
            kq[a][0] += sa * k;
            kq[a][1] -= sa * k;
            cv[a][0] += sa * cs;
            cv[a][1] -= sa * cs;
        }
        if self.clutch {
            let (c, dc) = self.clutch_torque(v[1] - v[2]);
            f[1] -= c;
            f[2] += c;
            for (a, sa) in [(1, -1.0), (2, 1.0)] {
                cv[a][1] += sa * dc;
                cv[a][2] -= sa * dc;
            }
        }
        f[n - 1] += accessory.0;
        cv[n - 1][n - 1] += accessory.1;
        DecouplerForces {
            f,
            df_dq: kq,
            df_dv: cv,
        }
    }

    /// The state at local angles `q` and speeds `v` (outputs).
    pub fn state(&self, q: &[f64], v: &[f64]) -> DecouplerState {
        let s = self.stiffness * (q[0] - q[1]) + self.damping * (v[0] - v[1]);
        let n = self.n_local();
        let (c, clutch) = if self.clutch {
            let x = v[1] - v[2];
            let state = if x > 0.0 {
                ClutchState::Engaged
            } else {
                ClutchState::Overrunning
            };
            (self.clutch_torque(x).0, Some(state))
        } else {
            (s, None)
        };
        DecouplerState {
            accessory_speed: v[n - 1],
            spring_torque: s,
            clutch_torque: c,
            clutch,
        }
    }
}

impl Validate for Decoupler {
    fn validate(&self) -> Result<(), InvalidField> {
        check::positive("pulley_inertia", self.pulley_inertia, "kg m²")?;
        check::positive("stiffness", self.stiffness, "N m/rad")?;
        check::non_negative("damping", self.damping, "N m s/rad")?;
        check::positive("carrier_inertia", self.carrier_inertia, "kg m²")?;
        check::positive("lock_damping", self.lock_damping, "N m s/rad")?;
        check::positive("lock_speed", self.lock_speed, "rad/s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn d(clutch: bool) -> Decoupler {
        Decoupler {
            pulley_inertia: 3e-4,
            stiffness: 25.0,
            damping: 0.02,
            clutch,
            carrier_inertia: 2e-5,
            lock_damping: 20.0,
            lock_speed: 0.01,
        }
    }

    // The analytic derivatives of (D1)–(D3) against central differences (a second evaluation
    // of the same forces), engaged, at the kink and overrunning.
    #[test]
    fn derivatives_match_finite_differences() {
        for clutch in [true, false] {
            let dc = d(clutch);
            let n = dc.n_local();
            for x in [3.0, 0.004, -2.0] {
                let q = [0.1, 0.07, -0.3][..n].to_vec();
                let mut v = vec![50.0, 50.0, 50.0 - x];
                v.truncate(n);
                let acc = |w: f64| (-1.5 - 0.01 * w, -0.01);
                let fr = dc.forces(&q, &v, acc(v[n - 1]));
                for j in 0..n {
                    let h = 1e-7;
                    let (mut qp, mut qm, mut vp, mut vm) =
                        (q.clone(), q.clone(), v.clone(), v.clone());
                    qp[j] += h;
                    qm[j] -= h;
                    vp[j] += h;
                    vm[j] -= h;
                    let fq = (
                        dc.forces(&qp, &v, acc(v[n - 1])),
                        dc.forces(&qm, &v, acc(v[n - 1])),
                    );
                    let fv = (
                        dc.forces(&q, &vp, acc(vp[n - 1])),
                        dc.forces(&q, &vm, acc(vm[n - 1])),
                    );
                    for i in 0..n {
                        let dq = (fq.0.f[i] - fq.1.f[i]) / (2.0 * h);
                        let dv = (fv.0.f[i] - fv.1.f[i]) / (2.0 * h);
                        assert!((dq - fr.df_dq[i][j]).abs() < 1e-5, "q {i} {j}");
                        assert!((dv - fr.df_dv[i][j]).abs() < 1e-4, "v {i} {j} x {x}");
                    }
                }
            }
        }
    }

    // (D2) by hand: engaged C ≈ c_l x; open C ≈ c_l ε²/(4|x|); the spring pair balances
    // (the chain's internal torques sum to the accessory's applied torque alone).
    #[test]
    fn clutch_law_limits_and_internal_balance() {
        let dc = d(true);
        assert!((dc.clutch_torque(1.0).0 - 20.0).abs() < 1e-3);
        let open = dc.clutch_torque(-2.0).0;
        assert!((open - 20.0 * 1e-4 / 8.0).abs() < 1e-8, "{open}");
        let f = dc.forces(&[0.2, 0.1, 0.0], &[40.0, 39.0, 38.0], (-3.0, 0.0));
        assert!((f.f.iter().sum::<f64>() + 3.0).abs() < 1e-12);
        assert_eq!(
            dc.state(&[0.2, 0.1, 0.0], &[40.0, 39.0, 41.0]).clutch,
            Some(ClutchState::Overrunning)
        );
    }
}
