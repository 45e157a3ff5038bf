//! The steady-state analytical belt-drive model of Bechtel et al. \[5\] as summarised by
//! Kerkkänen §4.1 ((4.1)–(4.4), (4.48)), in the implementable form reconstructed in the
//! seed-001 reading note §6.2 (the thesis prints only the balance laws; the closure is the
//! note's): tension and belt speed along the belt, the driven-pulley speed, and the friction
//! and normal force distributions on the pulleys, with belt inertia (the "full" model) or
//! without it (the "capstan" simplification of Kerkkänen Figs 4.17–4.18).
//!
//! # Model
//!
//! A planar extensible belt runs steadily over two pulleys (radii `R₁` driver, `R₂` driven,
//! centre distance `C`, open-belt wraps `φ₁ = π − 2β`, `φ₂ = π + 2β`, `sin β = (R₂ − R₁)/C`,
//! spans `l_s = √(C² − (R₂ − R₁)²)`).
//!
//! * **Constitutive law (4.1)** with the unstretched belt as the reference state:
//!   `T = k (dl/dl_o − 1)` (`T` is the belt tension; the thesis calls it the "axial strain", a
//!   slip of the pen, seed note §11 item 28). Mass conservation in steady flow makes the mass flux
//!   `G = ρA v_o` constant (`ρA` per unstretched length, `v_o` the speed the belt would have
//!   unstretched), and the local speed is `v = v_o (1 + T/k)`, i.e. (4.1) with
//!   `T_o = 0`. (The printed (4.4) has a spurious `T_o`; the correct form `T = (k/v_o) v − k`
//!   is used, seed note §11 item 28.)
//! * **Free spans (4.3):** `T − G v` constant; with (4.1) both `T` and `v` are constant in a
//!   span (Kerkkänen's conclusion under (4.4)).
//! * **Pulleys:** the belt enters each pulley in an adhesion (stick) arc in which it moves
//!   with the pulley surface (`v = ωR`, hence `T` constant and no friction) and leaves through
//!   a slip arc of angle `φ` in which `d(T − Gv)/(T − Gv) = ±μ dθ` (4.2): `u = T − Gv` decays as
//!   `e^{−μθ}` on the driver and grows as `e^{μθ}` on the driven pulley. The normal force per
//!   unit length is `N = u/R` (normal momentum balance), the friction force on the belt per
//!   unit length is `f = −du/ds` (tangential momentum balance, `|f| = μN` in slip).
//! * **Speeds (4.48):** `ω₁ = v_tight/R₁`, `ω₂ = v_slack/R₂` (no slip in the entry arcs).
//! * **Moment balance** of the driven pulley: `R₂ (u_tight − u_slack) = M`. Since the two slip
//!   arcs see the same ratio `u_tight/u_slack`, their angles are equal,
//!   `φ = ln(u_tight/u_slack)/μ`, and must not exceed the smaller wrap angle (else the belt
//!   slips grossly: no steady solution).
//! * **Closure** (not stated in the thesis; the note's choice): the belt's material is
//!   conserved, `∫_path ds/(1 + T/k) = L_o`, the unstretched belt length. A belt that carries
//!   the initial tension `T₀` uniformly at rest on the path of length `L_p` has
//!   `L_o = L_p/(1 + T₀/k)` ([`SteadyDriveInput::with_pretension`]). The note shows the result
//!   is closure-sensitive (another closure moves Model 2's speed deficit from 15.2 % to 18.7 %).
//!
//! With `u = T − G v = a T − c`, `c = ρA v_o²`, `a = 1 − c/k`, one unknown is left (the tight
//! tension `T₁`): `v_o = ω₁R₁/(1 + T₁/k)` follows from (4.48), `T₂` from the moment balance,
//! `φ` from the slip law, and `T₁` solves the closure by bisection (the material length
//! decreases monotonically with `T₁`). The slip-arc integrals of the closure are in closed
//! form, `∫₀^φ dθ/(A + D e^{±μθ}) = [μφ ∓ ln((A + D e^{±μφ})/(A + D))]/(μA)`.
//!
//! The capstan simplification drops the inertia terms (`G → 0`): `T₁/T₂ = e^{μφ}`, the
//! Euler–Eytelwein relation, and `N = T/R`.

use crate::error::DriveError;
use serde::Serialize;
use std::f64::consts::PI;

/// Inputs of the steady analytical model (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SteadyDriveInput {
    /// Driver radius `R₁` \[m\].
    pub radius_driver: f64,
    /// Driven radius `R₂` \[m\].
    pub radius_driven: f64,
    /// Centre distance `C` \[m\].
    pub center_distance: f64,
    /// Longitudinal stiffness `k = EA` \[N\].
    pub stiffness: f64,
    /// Mass per unstretched length `ρA` \[kg/m\].
    pub mass_per_length: f64,
    /// Friction coefficient `μ`.
    pub mu: f64,
    /// Driver speed `ω₁` \[rad/s\].
    pub omega_driver: f64,
    /// Transmitted moment `M` (load torque on the driven pulley) \[N·m\].
    pub torque: f64,
    /// Unstretched belt length `L_o` \[m\].
    pub unstretched_length: f64,
    /// Belt inertia on (full model) or off (capstan simplification, `G → 0`).
    pub inertia: bool,
}

impl SteadyDriveInput {
    /// Open-belt path length `2 l_s + φ₁ R₁ + φ₂ R₂` \[m\].
    pub fn path_length(&self) -> f64 {
        let g = self.geometry();
        2.0 * g.span + g.wrap[0] * self.radius_driver + g.wrap[1] * self.radius_driven
    }

    /// The unstretched length of a belt that carries the tension `t0` \[N\] uniformly when it
    /// lies on the path at rest: `L_o = L_p/(1 + T₀/k)`; returns `self` with it.
    pub fn with_pretension(mut self, t0: f64) -> Self {
        self.unstretched_length = self.path_length() / (1.0 + t0 / self.stiffness);
        self
    }

    fn geometry(&self) -> Geometry {
        let dr = self.radius_driven - self.radius_driver;
        let beta = (dr / self.center_distance).asin();
        Geometry {
            span: (self.center_distance * self.center_distance - dr * dr).sqrt(),
            wrap: [PI - 2.0 * beta, PI + 2.0 * beta],
        }
    }

    fn check(&self) -> Result<(), DriveError> {
        let pos = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(DriveError::Invalid(format!(
                    "steady belt model: {name} must be > 0, got {v}"
                )))
            }
        };
        pos("radius_driver", self.radius_driver)?;
        pos("radius_driven", self.radius_driven)?;
        pos("stiffness", self.stiffness)?;
        pos("mu", self.mu)?;
        pos("unstretched_length", self.unstretched_length)?;
        if !(self.mass_per_length.is_finite() && self.mass_per_length >= 0.0) {
            return Err(DriveError::Invalid(format!(
                "steady belt model: mass_per_length must be ≥ 0, got {}",
                self.mass_per_length
            )));
        }
        if !(self.omega_driver.is_finite() && self.torque.is_finite() && self.torque >= 0.0) {
            return Err(DriveError::Invalid(
                "steady belt model: omega_driver must be finite and torque ≥ 0".into(),
            ));
        }
        let dr = (self.radius_driven - self.radius_driver).abs();
        if !(self.center_distance.is_finite() && self.center_distance > dr) {
            return Err(DriveError::Invalid(format!(
                "steady belt model: center_distance must exceed |R₂ − R₁| = {dr} m, got {}",
                self.center_distance
            )));
        }
        Ok(())
    }
}

#[derive(Debug, Clone, Copy)]
struct Geometry {
    span: f64,
    wrap: [f64; 2],
}

/// Where a point of the path lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Zone {
    /// The slack span (leaving the driver).
    SlackSpan,
    /// Adhesion arc on the driven pulley.
    DrivenStick,
    /// Slip arc on the driven pulley.
    DrivenSlip,
    /// The tight span (leaving the driven pulley).
    TightSpan,
    /// Adhesion arc on the driver.
    DriverStick,
    /// Slip arc on the driver.
    DriverSlip,
}

/// The state of the belt at one point of the path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SteadyPoint {
    /// Arc length along the undeformed path from the point where the belt leaves the driver
    /// (the start of the slack span, as
    /// [`BeltPath`](belt::BeltPath) with the driver first) \[m\].
    pub s: f64,
    /// Zone.
    pub zone: Zone,
    /// Tension `T` \[N\].
    pub tension: f64,
    /// Belt speed `v = v_o (1 + T/k)` \[m/s\].
    pub speed: f64,
    /// Normal force per unit length on the belt `N = (T − G v)/R` \[N/m\] (0 on spans).
    pub normal: f64,
    /// Friction force per unit length on the belt, positive in the travel direction \[N/m\].
    pub friction: f64,
}

/// The steady solution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SteadySolution {
    /// The inputs.
    pub input: SteadyDriveInput,
    /// Tight-span tension `T₁` \[N\].
    pub tension_tight: f64,
    /// Slack-span tension `T₂` \[N\].
    pub tension_slack: f64,
    /// Tight-span speed \[m/s\] (`= ω₁ R₁`).
    pub speed_tight: f64,
    /// Slack-span speed \[m/s\].
    pub speed_slack: f64,
    /// Driven speed `ω₂ = v_slack/R₂` (4.48) \[rad/s\].
    pub omega_driven: f64,
    /// `ω₂ R₂ / (ω₁ R₁)`.
    pub speed_ratio: f64,
    /// Slip angle `φ` on each pulley \[rad\].
    pub slip_angle: f64,
    /// Unstretched reference speed `v_o` \[m/s\].
    pub reference_speed: f64,
    /// Mass flux `G = ρA v_o` \[kg/s\] (0 for the capstan model).
    pub mass_flow: f64,
    /// Span length \[m\].
    pub span: f64,
    /// Wrap angles on driver and driven \[rad\].
    pub wrap: [f64; 2],
}

impl SteadySolution {
    /// Path length \[m\].
    pub fn path_length(&self) -> f64 {
        2.0 * self.span
            + self.wrap[0] * self.input.radius_driver
            + self.wrap[1] * self.input.radius_driven
    }

    /// `(a, c)` of `u = T − G v = a T − c`.
    fn inertia_terms(&self) -> (f64, f64) {
        let c = self.mass_flow * self.reference_speed;
        (1.0 - c / self.input.stiffness, c)
    }

    /// The state at arc length `s` \[m\] (any real `s`: the path is periodic).
    pub fn at(&self, s: f64) -> SteadyPoint {
        let inp = &self.input;
        let l = self.path_length();
        let s = s.rem_euclid(l);
        let (a, c) = self.inertia_terms();
        let u_of = |t: f64| a * t - c;
        let t_of = |u: f64| (u + c) / a;
        let (r1, r2) = (inp.radius_driver, inp.radius_driven);
        let (u1, u2) = (u_of(self.tension_tight), u_of(self.tension_slack));
        let phi = self.slip_angle;
        let l_slack = self.span;
        let l_dn_stick = l_slack + (self.wrap[1] - phi) * r2;
        let l_dn = l_slack + self.wrap[1] * r2;
        let l_tight = l_dn + self.span;
        let l_dr_stick = l_tight + (self.wrap[0] - phi) * r1;
        let (zone, tension, normal, friction) = if s < l_slack {
            (Zone::SlackSpan, self.tension_slack, 0.0, 0.0)
        } else if s < l_dn_stick {
            (Zone::DrivenStick, self.tension_slack, u2 / r2, 0.0)
        } else if s < l_dn {
            let u = u2 * (inp.mu * (s - l_dn_stick) / r2).exp();
            (Zone::DrivenSlip, t_of(u), u / r2, -inp.mu * u / r2)
        } else if s < l_tight {
            (Zone::TightSpan, self.tension_tight, 0.0, 0.0)
        } else if s < l_dr_stick {
            (Zone::DriverStick, self.tension_tight, u1 / r1, 0.0)
        } else {
            let u = u1 * (-inp.mu * (s - l_dr_stick) / r1).exp();
            (Zone::DriverSlip, t_of(u), u / r1, inp.mu * u / r1)
        };
        SteadyPoint {
            s,
            zone,
            tension,
            speed: self.reference_speed * (1.0 + tension / inp.stiffness),
            normal,
            friction,
        }
    }

    /// The state at `n` equally spaced points `s_k = (k + ½) L/n` of the path.
    pub fn distribution(&self, n: usize) -> Vec<SteadyPoint> {
        let l = self.path_length();
        (0..n)
            .map(|k| self.at((k as f64 + 0.5) * l / n as f64))
            .collect()
    }
}

/// `∫₀^φ dθ / (A + D e^{σμθ})`, `σ = ±1` (closed form, module documentation).
fn slip_integral(a: f64, d: f64, mu: f64, phi: f64, sigma: f64) -> f64 {
    (mu * phi - sigma * ((a + d * (sigma * mu * phi).exp()) / (a + d)).ln()) / (mu * a)
}

/// Solve the steady model (see the module documentation). Errors: invalid input, a belt
/// faster than its longitudinal wave speed (`ρA v_o² ≥ k`), no tension that balances the
/// moment with the given belt length, or gross slip (slip angle above the wrap angle).
pub fn solve_steady(input: &SteadyDriveInput) -> Result<SteadySolution, DriveError> {
    input.check()?;
    let g = input.geometry();
    let (k, r1, r2, mu) = (
        input.stiffness,
        input.radius_driver,
        input.radius_driven,
        input.mu,
    );
    let v1 = input.omega_driver.abs() * r1;
    let rho_a = if input.inertia {
        input.mass_per_length
    } else {
        0.0
    };
    // all quantities from the tight tension T₁
    let state = |t1: f64| -> Option<(f64, f64, f64, f64, f64)> {
        let vo = v1 / (1.0 + t1 / k);
        let c = rho_a * vo * vo;
        let a = 1.0 - c / k;
        if a <= 0.0 {
            return None;
        }
        let u1 = a * t1 - c;
        let u2 = u1 - input.torque / r2;
        if u2 <= 0.0 {
            return None;
        }
        let t2 = (u2 + c) / a;
        let phi = (u1 / u2).ln() / mu;
        // material length ∫ ds/(1 + T/k), 1 + T/k = A + B u
        let (aa, bb) = (1.0 + c / (a * k), 1.0 / (a * k));
        let stretch = |t: f64| 1.0 + t / k;
        let slip = slip_integral(aa, bb * u1, mu, phi, -1.0);
        let length = g.span / stretch(t1)
            + g.span / stretch(t2)
            + ((g.wrap[0] - phi).max(0.0) * r1) / stretch(t1)
            + ((g.wrap[1] - phi).max(0.0) * r2) / stretch(t2)
            + slip * (r1 + r2);
        Some((length, t2, phi, vo, c))
    };
    // bracket: smallest admissible T₁ (u₂ > 0), then grow until the belt is long enough
    let mut lo = input.torque / r2;
    let mut tries = 0;
    while state(lo).is_none() {
        lo = 1.05 * lo + 1e-9 * k;
        tries += 1;
        if tries > 2000 {
            return Err(DriveError::Numerical(
                "steady belt model: no admissible tension (belt faster than its wave speed?)"
                    .into(),
            ));
        }
    }
    let residual = |t1: f64| state(t1).map(|s| s.0 - input.unstretched_length);
    if residual(lo).is_some_and(|r| r < 0.0) {
        return Err(DriveError::Numerical(format!(
            "steady belt model: the belt ({} m) is too long to transmit {} N·m without gross slip",
            input.unstretched_length, input.torque
        )));
    }
    let mut hi = lo.max(1.0) * 2.0;
    while residual(hi).is_some_and(|r| r > 0.0) {
        hi *= 2.0;
        if hi > 1e6 * k {
            return Err(DriveError::Numerical(
                "steady belt model: no tension reaches the belt length".into(),
            ));
        }
    }
    // T₁ above the root: the residual defined and not positive
    let above = |t1: f64| {
        residual(t1).is_some_and(|r| r.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
    };
    let (lo, hi) =
        mbd_core::roots::bisect(lo, hi, above, mbd_core::roots::Stop::relative(200, 1e-14));
    let t1 = 0.5 * (lo + hi);
    let Some((_, t2, phi, vo, _)) = state(t1) else {
        return Err(DriveError::Numerical(
            "steady belt model: bisection left the admissible range".into(),
        ));
    };
    let wrap_min = g.wrap[0].min(g.wrap[1]);
    if phi > wrap_min {
        return Err(DriveError::Numerical(format!(
            "steady belt model: gross slip (slip angle {:.1}° exceeds the wrap {:.1}°)",
            phi.to_degrees(),
            wrap_min.to_degrees()
        )));
    }
    let v2 = vo * (1.0 + t2 / k);
    Ok(SteadySolution {
        input: *input,
        tension_tight: t1,
        tension_slack: t2,
        speed_tight: vo * (1.0 + t1 / k),
        speed_slack: v2,
        omega_driven: input.omega_driver.signum() * v2 / r2,
        speed_ratio: v2 / v1,
        slip_angle: phi,
        reference_speed: vo,
        mass_flow: rho_a * vo,
        span: g.span,
        wrap: g.wrap,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytical::analytical_speed_loss;

    /// Kerkkänen Model 2 (Table 4.1) with the initial tension 50 N of Bechtel et al.
    fn model2(inertia: bool) -> SteadyDriveInput {
        SteadyDriveInput {
            radius_driver: 0.05,
            radius_driven: 0.05,
            center_distance: PI * 0.05,
            stiffness: 200.0,
            mass_per_length: 0.02,
            mu: 0.6,
            omega_driver: 500.0,
            torque: 2.0,
            unstretched_length: 1.0,
            inertia,
        }
        .with_pretension(50.0)
    }

    // Reading note seed-001 §6.2: the note's Model 2 solve with this closure gives
    // T₁ ≈ 73.0 N, T₂ ≈ 31.6 N, v_tight = 25.0 m/s, v_slack ≈ 21.2 m/s, slip arc ≈ 94°,
    // ω₂/ω₁ ≈ 0.848 (Kerkkänen reads ≈ 14.6 % below the driver off Fig. 4.14).
    #[test]
    fn model_2_matches_the_reading_note() {
        let s = solve_steady(&model2(true)).unwrap();
        assert!((s.input.unstretched_length - 4.0 * PI * 0.05 / 1.25).abs() < 1e-12);
        assert!((s.tension_tight - 73.0).abs() < 0.1, "{}", s.tension_tight);
        assert!((s.tension_slack - 31.6).abs() < 0.1, "{}", s.tension_slack);
        assert!((s.speed_tight - 25.0).abs() < 1e-9);
        assert!((s.speed_slack - 21.2).abs() < 0.05, "{}", s.speed_slack);
        assert!((s.slip_angle.to_degrees() - 94.0).abs() < 1.0);
        assert!((s.speed_ratio - 0.848).abs() < 1e-3, "{}", s.speed_ratio);
        assert!((s.omega_driven - 500.0 * s.speed_ratio).abs() < 1e-9);
    }

    // Invariants: the closure (material length = L_o) by numerical quadrature of the
    // distribution, the moment balance (friction × R over the driven arc = M, over the driver
    // arc = M R₁/R₂), and the slip law |f| = μ N in the slip arcs, f = 0 in the stick arcs.
    #[test]
    fn closure_moment_balance_and_slip_law() {
        for inertia in [true, false] {
            let inp = SteadyDriveInput {
                radius_driven: 0.07,
                ..model2(inertia)
            }
            .with_pretension(60.0);
            let s = solve_steady(&inp).unwrap();
            let n = 200_000;
            let pts = s.distribution(n);
            let ds = s.path_length() / n as f64;
            let material: f64 = pts
                .iter()
                .map(|p| ds / (1.0 + p.tension / inp.stiffness))
                .sum();
            assert!(
                (material - inp.unstretched_length).abs() < 1e-7,
                "{material}"
            );
            let on = |z: &[Zone]| -> f64 {
                pts.iter()
                    .filter(|p| z.contains(&p.zone))
                    .map(|p| p.friction * ds)
                    .sum()
            };
            let driven = on(&[Zone::DrivenStick, Zone::DrivenSlip]);
            let driver = on(&[Zone::DriverStick, Zone::DriverSlip]);
            // friction on the belt: backwards on the driven pulley, forwards on the driver
            assert!((-driven * inp.radius_driven - inp.torque).abs() < 1e-3 * inp.torque);
            assert!(
                (driver * inp.radius_driver - inp.torque * inp.radius_driver / inp.radius_driven)
                    .abs()
                    < 1e-3 * inp.torque
            );
            for p in &pts {
                match p.zone {
                    Zone::DrivenSlip | Zone::DriverSlip => {
                        assert!((p.friction.abs() - inp.mu * p.normal).abs() < 1e-9 * p.normal)
                    }
                    _ => assert_eq!(p.friction, 0.0),
                }
            }
        }
    }

    // Analytical: without belt inertia (G → 0) the slip arcs obey Euler–Eytelwein,
    // T₁/T₂ = e^{μφ}, with T₁ − T₂ = M/R₂, N R = T; with inertia (T₁ − Gv₁)/(T₂ − Gv₂) = e^{μφ}.
    // A vanishing belt mass makes the full model the capstan model.
    #[test]
    fn capstan_limit_is_euler_eytelwein() {
        let s = solve_steady(&model2(false)).unwrap();
        let ee = (0.6 * s.slip_angle).exp();
        assert!((s.tension_tight / s.tension_slack - ee).abs() < 1e-12 * ee);
        assert!((s.tension_tight - s.tension_slack - 2.0 / 0.05).abs() < 1e-9);
        let p = s.at(s.span + 1e-3);
        assert!((p.normal * 0.05 - p.tension).abs() < 1e-9 * p.tension);
        let full = solve_steady(&model2(true)).unwrap();
        let gv = |t: f64, v: f64| t - full.mass_flow * v;
        let ratio =
            gv(full.tension_tight, full.speed_tight) / gv(full.tension_slack, full.speed_slack);
        assert!((ratio - (0.6 * full.slip_angle).exp()).abs() < 1e-12 * ratio);
        let light = solve_steady(&SteadyDriveInput {
            mass_per_length: 1e-12,
            ..model2(true)
        })
        .unwrap();
        assert!((light.omega_driven - s.omega_driven).abs() < 1e-9);
    }

    // Second formulation: for a stiff belt (k = 25 kN, Kerkkänen Figs 4.4–4.5) without inertia
    // the speed loss is Bechtel's line, Ribaric (6.3), Δω = 2Mω/(2R(T₀ + k) + M), up to the
    // closure's second-order difference (relative O(T/k)).
    #[test]
    fn stiff_belt_speed_loss_is_bechtels_line() {
        let inp = SteadyDriveInput {
            stiffness: 25_000.0,
            ..model2(false)
        }
        .with_pretension(50.0);
        let s = solve_steady(&inp).unwrap();
        let dw = 500.0 - s.omega_driven;
        let line = analytical_speed_loss(0.05, 50.0, 25_000.0, 2.0, 500.0);
        assert!((dw - line).abs() < 3e-3 * line, "{dw} vs {line}");
    }

    // Bad input and impossible operating points are errors, never panics.
    #[test]
    fn gross_slip_and_bad_input_are_errors() {
        let e = solve_steady(&SteadyDriveInput {
            torque: 20.0,
            ..model2(true)
        })
        .unwrap_err();
        assert!(e.to_string().contains("slip"), "{e}");
        assert!(
            solve_steady(&SteadyDriveInput {
                mu: -1.0,
                ..model2(true)
            })
            .is_err()
        );
    }
}
