//! The dynamic test cases of Kerkkänen §2.4 — the falling flexible pendulum (Figs 2.5–2.8)
//! and the spinning beam with centrifugal stiffening (Figs 2.9–2.11, Wu & Haug) — integrated by
//! mbd-core's generalized-α method.

use crate::ancf_beams::{
    check_elements, check_poisson, check_rho_inf, check_section, check_time, check_young, invalid,
};
use ancf::AncfError;
use ancf::beam_mesh::{BeamElementKind, beam_mesh};
use ancf::element::{AncfElement, OmarShabanaBeam, ProposedBeam};
use ancf::material::Material;
use ancf::mesh::AncfMesh;
use ancf::mesh::straight_coordinates;
use ancf::section::Section;
use ancf::system::{AncfSystem, Energies, Prescribed};
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, Proceed, State};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;
use std::sync::Arc;

/// Falling flexible pendulum (Kerkkänen §2.4, Fig. 2.5): `L = 2 m`, 0.1 m square section,
/// `E = 2.07·10⁷ Pa`, `ν = 0`, `ρ = 7850 kg/m³`, `g = 9.81 m/s²`, pinned at one end (nodal
/// position fixed, slopes free), released from rest in the horizontal position.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct PendulumCase {
    /// Element type (the thesis compares both in Fig. 2.8 and Table 2.5).
    pub element: BeamElementKind,
    /// Number of elements.
    pub elements: usize,
    /// Beam length \[m\].
    pub length: f64,
    /// Section width and height \[m\].
    pub side: f64,
    /// Young's modulus \[Pa\].
    pub young: f64,
    /// Poisson's ratio \[-\].
    pub nu: f64,
    /// Density \[kg/m³\].
    pub density: f64,
    /// Gravity \[m/s²\].
    pub gravity: f64,
    /// End time \[s\] (not stated in the thesis).
    pub t_end: f64,
    /// Step size \[s\].
    pub h: f64,
    /// Generalized-α spectral radius ρ∞ \[-\] (1: no numerical dissipation).
    pub rho_inf: f64,
}

impl Default for PendulumCase {
    fn default() -> Self {
        Self {
            element: BeamElementKind::Proposed,
            elements: 4,
            length: 2.0,
            side: 0.1,
            young: 2.07e7,
            nu: 0.0,
            density: 7850.0,
            gravity: 9.81,
            t_end: 1.0,
            h: 5e-5,
            rho_inf: 1.0,
        }
    }
}

impl mbd_core::config::PartialRules for PendulumCase {}

impl Validate for PendulumCase {
    /// `1 ≤ elements ≤` [`ancf::beam_mesh::MAX_BEAM_ELEMENTS`], positive dimensions, modulus,
    /// end time and step with at most [`crate::ancf_beams::MAX_TIME_STEPS`] steps,
    /// `−1 < ν < 0.5`, `0 ≤ ρ∞ ≤ 1`.
    fn validate(&self) -> Result<(), InvalidField> {
        check_elements(self.elements)?;
        check::positive("length", self.length, "m")?;
        check::positive("side", self.side, "m")?;
        check_section(self.length, &[("side", self.side)])?;
        check_young(self.young)?;
        // a massless pendulum has no dynamics: the mass matrix is singular (issue 35)
        check::positive("density", self.density, "kg/m³")?;
        check::finite("gravity", self.gravity)?;
        check_time(self.t_end, self.h)?;
        check_poisson(self.nu)?;
        check_rho_inf(self.rho_inf)
    }
}

/// One output sample of a dynamic study.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Sample {
    /// Time \[s\].
    pub t: f64,
    /// Tip position \[m\].
    pub tip: [f64; 2],
    /// Energies \[J\].
    pub energy: Energies,
    /// Study-specific scalar (pendulum: tip vertical displacement \[m\]; spinning beam: axial
    /// extension \[m\]).
    pub value: f64,
    /// Second study-specific scalar (spinning beam: tip transverse offset from the rigid
    /// shadow beam \[m\]).
    pub value2: f64,
}

fn alpha(h: f64, rho_inf: f64) -> GeneralizedAlpha {
    GeneralizedAlpha::new(AlphaConfig {
        rho_inf,
        h,
        newton_atol: 1e-12,
        newton_rtol: 1e-12,
        max_newton_iterations: 30,
        ..Default::default()
    })
}

/// `Continue` or `Break` for an observer.
fn flow(go_on: bool) -> ControlFlow<()> {
    if go_on {
        ControlFlow::Continue(())
    } else {
        ControlFlow::Break(())
    }
}

fn check_run(h: f64, t_end: f64, every: usize) -> Result<(), AncfError> {
    if !(h.is_finite() && h > 0.0) {
        return Err(invalid("h", format!("step must be > 0 s, got {h}")));
    }
    if !(t_end.is_finite() && t_end > 0.0) {
        return Err(invalid("t_end", format!("must be > 0 s, got {t_end}")));
    }
    if every == 0 {
        return Err(invalid("output_every", "must be ≥ 1"));
    }
    Ok(())
}

/// Run the falling pendulum; `every`-th step is recorded (the initial state always).
/// `progress` gets the fraction done at every sample; answering `ControlFlow::Break(())`
/// ([`mbd_core::integrators::Proceed`]) stops the run there, returning the samples so far.
pub fn pendulum<R: Proceed>(
    case: &PendulumCase, every: usize, progress: impl FnMut(f64) -> R,
) -> Result<Vec<Sample>, AncfError> {
    check_run(case.h, case.t_end, every)?;
    let mat = Material::new(case.young, case.nu, case.density)?;
    let sec = Section::rectangle(case.side, case.side)?;
    match case.element {
        BeamElementKind::Proposed => {
            let mesh = beam_mesh(case.length, case.elements, |l| {
                ProposedBeam::new(l, mat, sec)
            })?;
            pendulum_run(case, mesh, every, progress)
        }
        BeamElementKind::OmarShabana => {
            let mesh = beam_mesh(case.length, case.elements, |l| {
                OmarShabanaBeam::new(l, mat, sec)
            })?;
            pendulum_run(case, mesh, every, progress)
        }
    }
}

fn pendulum_run<E: AncfElement, R: Proceed>(
    case: &PendulumCase, mesh: AncfMesh<E>, every: usize, mut progress: impl FnMut(f64) -> R,
) -> Result<Vec<Sample>, AncfError> {
    let q0 = straight_coordinates(mesh.layout(), [0.0, 0.0], [case.length, 0.0], case.elements);
    let pins = vec![
        Prescribed::fixed(0, "pin x", 0.0),
        Prescribed::fixed(1, "pin y", 0.0),
    ];
    let n = case.elements;
    let sys = AncfSystem::new(mesh)
        .with_gravity([0.0, -case.gravity])
        .with_prescribed(pins)?;
    let v0 = vec![0.0; q0.len()];
    let mut out = Vec::new();
    let mut k = 0usize;
    let tip0 = case.length;
    let record = |st: &State, out: &mut Vec<Sample>| {
        let tip = sys.mesh().node_position(&st.q, n);
        out.push(Sample {
            t: st.t,
            tip,
            energy: sys.energies(&st.q, &st.v),
            value: tip[1],
            value2: tip[0] - tip0,
        });
    };
    alpha(case.h, case.rho_inf).integrate(&sys, State::new(0.0, q0, v0), case.t_end, |st| {
        let mut go_on = true;
        if k.is_multiple_of(every) || st.t >= case.t_end - 1e-12 {
            record(st, &mut out);
            go_on = progress(st.t / case.t_end).proceed();
        }
        k += 1;
        flow(go_on)
    })?;
    Ok(out)
}

/// Spinning beam (Kerkkänen §2.4, Fig. 2.9; Wu & Haug): `L = 8 m`, width `1.986·10⁻³ m`, height
/// `3.675·10⁻² m`, `E = 6.895·10¹⁰ Pa`, `ρ = 2766.67 kg/m³`, 3 proposed elements, no gravity,
/// hub angle (2.35) with `ω_s = 4 rad/s`, `T_s = 15 s`, 20 s. `ν` is not stated (0.3 here).
/// The clamp to the hub prescribes `r = 0` and `r_y = (−sin θ, cos θ)` at node 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SpinningCase {
    /// Number of proposed elements.
    pub elements: usize,
    /// Beam length \[m\].
    pub length: f64,
    /// Section width (out of plane) \[m\].
    pub width: f64,
    /// Section height (in plane) \[m\].
    pub height: f64,
    /// Young's modulus \[Pa\].
    pub young: f64,
    /// Poisson's ratio \[-\] (not stated in the thesis).
    pub nu: f64,
    /// Density \[kg/m³\].
    pub density: f64,
    /// Final hub speed `ω_s` \[rad/s\].
    pub omega: f64,
    /// Spin-up time `T_s` \[s\].
    pub spin_up: f64,
    /// End time \[s\].
    pub t_end: f64,
    /// Step size \[s\].
    pub h: f64,
    /// Generalized-α spectral radius ρ∞ \[-\].
    pub rho_inf: f64,
}

impl Default for SpinningCase {
    fn default() -> Self {
        Self {
            elements: 3,
            length: 8.0,
            width: 1.986e-3,
            height: 3.675e-2,
            young: 6.895e10,
            nu: 0.3,
            density: 2766.67,
            omega: 4.0,
            spin_up: 15.0,
            t_end: 20.0,
            h: 2e-3,
            rho_inf: 0.6,
        }
    }
}

impl mbd_core::config::PartialRules for SpinningCase {}

impl Validate for SpinningCase {
    /// As [`PendulumCase`], plus positive density and spin-up time and a finite hub speed.
    fn validate(&self) -> Result<(), InvalidField> {
        check_elements(self.elements)?;
        for (f, v, unit) in [
            ("length", self.length, "m"),
            ("width", self.width, "m"),
            ("height", self.height, "m"),
            ("young", self.young, "Pa"),
            ("density", self.density, "kg/m³"),
            ("spin_up", self.spin_up, "s"),
        ] {
            check::positive(f, v, unit)?;
        }
        check_section(
            self.length,
            &[("width", self.width), ("height", self.height)],
        )?;
        check_young(self.young)?;
        check_time(self.t_end, self.h)?;
        check_poisson(self.nu)?;
        check::finite("omega", self.omega)?;
        // (2.37) holds below the first critical speed a L = π/2, where the steady extension
        // grows without bound; above it the linear bar has no steady state (issue 35: omega =
        // 1e5 gave an extension of -8 m)
        let critical = spinning_critical_speed(self.length, self.density, self.young);
        if self.omega.abs() >= critical {
            return Err(InvalidField::new(
                "omega",
                format!(
                    "{} rad/s is at or above the critical speed {} rad/s \
                     (pi/(2L) sqrt(E/rho), Kerkkanen (2.37)), where the centrifugal \
                     extension grows without bound",
                    check::show(self.omega),
                    check::show(critical)
                ),
            ));
        }
        check_rho_inf(self.rho_inf)
    }
}

/// Hub angle of Kerkkänen (2.35) and its first two derivatives `[θ, θ̇, θ̈]`.
pub fn hub_angle(t: f64, omega: f64, ts: f64) -> [f64; 3] {
    let tau = std::f64::consts::TAU;
    if t < ts {
        let a = tau * t / ts;
        [
            omega / ts * (0.5 * t * t + (ts / tau).powi(2) * (a.cos() - 1.0)),
            omega / ts * (t - ts / tau * a.sin()),
            omega / ts * (1.0 - a.cos()),
        ]
    } else {
        [omega * (t - 0.5 * ts), omega, 0.0]
    }
}

/// The speed \[rad/s\] at which the steady extension (2.37) of a bar spinning about one end
/// grows without bound: `a L = π/2`, `ω_c = π/(2L) √(E/ρ)` (Kerkkänen (2.36)–(2.37)).
pub fn spinning_critical_speed(length: f64, density: f64, young: f64) -> f64 {
    std::f64::consts::FRAC_PI_2 / length * (young / density).sqrt()
}

/// Steady axial extension of a bar spinning at `ω` \[rad/s\], Kerkkänen (2.36)–(2.37):
/// `u_x = l (tan(al)/(al) − 1)`, `a = ω √(ρA/EA)`.
pub fn spinning_extension(length: f64, density: f64, young: f64, omega: f64) -> f64 {
    let al = omega * (density / young).sqrt() * length;
    length * (al.tan() / al - 1.0)
}

/// Run the spinning beam; `value` of each sample is the axial extension (sum of the nodal chord
/// lengths minus `L`) \[m\], `value2` the tip's transverse offset from the rigid shadow beam \[m\].
/// `progress` as for [`pendulum`] (a `Break` stops the run, keeping the samples so far).
pub fn spinning<R: Proceed>(
    case: &SpinningCase, every: usize, mut progress: impl FnMut(f64) -> R,
) -> Result<Vec<Sample>, AncfError> {
    check_run(case.h, case.t_end, every)?;
    if case.spin_up.is_nan() || case.spin_up <= 0.0 {
        return Err(invalid(
            "spin_up",
            format!("must be > 0 s, got {}", case.spin_up),
        ));
    }
    let mat = Material::new(case.young, case.nu, case.density)?;
    let sec = Section::rectangle(case.width, case.height)?;
    let mesh = beam_mesh(case.length, case.elements, |l| {
        ProposedBeam::new(l, mat, sec)
    })?;
    let q0 = straight_coordinates(mesh.layout(), [0.0, 0.0], [case.length, 0.0], case.elements);
    let (w, ts) = (case.omega, case.spin_up);
    let ry_x: Arc<dyn Fn(f64) -> [f64; 3] + Send + Sync> = Arc::new(move |t| {
        let [th, thd, thdd] = hub_angle(t, w, ts);
        let (s, c) = th.sin_cos();
        [-s, -c * thd, -c * thdd + s * thd * thd]
    });
    let ry_y: Arc<dyn Fn(f64) -> [f64; 3] + Send + Sync> = Arc::new(move |t| {
        let [th, thd, thdd] = hub_angle(t, w, ts);
        let (s, c) = th.sin_cos();
        [c, -s * thd, -s * thdd - c * thd * thd]
    });
    let hub = vec![
        Prescribed::fixed(0, "hub x", 0.0),
        Prescribed::fixed(1, "hub y", 0.0),
        Prescribed {
            dof: 2,
            name: "hub slope r_y,x".into(),
            motion: ry_x,
        },
        Prescribed {
            dof: 3,
            name: "hub slope r_y,y".into(),
            motion: ry_y,
        },
    ];
    let n = case.elements;
    let sys = AncfSystem::new(mesh).with_prescribed(hub)?;
    let v0 = sys.consistent_velocity(0.0);
    let mut out = Vec::new();
    let mut k = 0usize;
    let l = case.length;
    alpha(case.h, case.rho_inf).integrate(&sys, State::new(0.0, q0, v0), case.t_end, |st| {
        let mut go_on = true;
        if k.is_multiple_of(every) || st.t >= case.t_end - 1e-12 {
            let m = sys.mesh();
            let chord: f64 = (0..n)
                .map(|i| {
                    let a = m.node_position(&st.q, i);
                    let b = m.node_position(&st.q, i + 1);
                    ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
                })
                .sum();
            let tip = m.node_position(&st.q, n);
            let th = hub_angle(st.t, w, ts)[0];
            let (s, c) = th.sin_cos();
            out.push(Sample {
                t: st.t,
                tip,
                energy: sys.energies(&st.q, &st.v),
                value: chord - l,
                value2: -s * tip[0] + c * tip[1],
            });
            go_on = progress(st.t / case.t_end).proceed();
        }
        k += 1;
        flow(go_on)
    })?;
    Ok(out)
}

/// Largest deviation of the total energy from its initial value \[J\].
pub fn energy_drift(samples: &[Sample]) -> f64 {
    let e0 = samples.first().map(|s| s.energy.total).unwrap_or(0.0);
    samples
        .iter()
        .map(|s| (s.energy.total - e0).abs())
        .fold(0.0, f64::max)
}
