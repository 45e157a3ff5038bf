//! Post-processing of a belt-drive state: tension along the belt (Kerkkänen (4.5)–(4.9)), span
//! tensions and mid-span positions (Figs 3.10–3.12), pulley arc coordinates of contact points
//! (Fig. 3.17).

use super::model::{BeltDrive, PointRecord};
use crate::element::AncfElement;
use crate::shape;
use belt::{PulleyState, Snapshot, SpanState, WrapPoint};

/// Axial state at one material point of the belt.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TensionSample {
    /// Material (unstretched) arc length from node 0 \[m\].
    pub s_material: f64,
    /// Position \[m\].
    pub position: [f64; 2],
    /// Engineering strain of the centreline `ε = ‖r_x‖ − 1`, Kerkkänen (4.9) (the reference
    /// elements are straight with `J₀ = I`, so `α = 2 t₀ᵀ ε^m t₀ = r_xᵀ r_x − 1`).
    pub strain: f64,
    /// Axial force the element carries at the point \[N\]: `N = ∂W/∂λ` of its material law
    /// ([`BeltElement::axial_force`](crate::element::BeltElement::axial_force); St Venant–Kirchhoff
    /// (3.18): `α₁EA λ(λ² − 1)/2` plus the bending–stretching coupling; linear:
    /// `α₁EA(λ − 1)`), the force that balances the contact forces (`dN/ds = −f_t`,
    /// `N κ = f_n`) and the pulley torques.
    pub tension: f64,
}

/// Centreline position \[m\] and slope `r_x` at `ξ` of an element with coordinates `e`.
fn centreline(e: &[f64; 12], l: f64, xi: f64) -> ([f64; 2], [f64; 2]) {
    let sh = shape::cubic(l, xi * l, 0.0);
    let mut r = [0.0; 2];
    let mut rx = [0.0; 2];
    for a in 0..6 {
        r[0] += sh.s[a] * e[2 * a];
        r[1] += sh.s[a] * e[2 * a + 1];
        rx[0] += sh.sx[a] * e[2 * a];
        rx[1] += sh.sx[a] * e[2 * a + 1];
    }
    (r, rx)
}

/// The [`TensionSample`] of element `el` at `ξ = x/l`.
pub fn tension_at(drive: &BeltDrive, q: &[f64], el: usize, xi: f64) -> TensionSample {
    let l = drive.element_length();
    let mut e = [0.0; 12];
    drive.mesh().gather(q, el, &mut e);
    let (r, rx) = centreline(&e, l, xi);
    let strain = (rx[0] * rx[0] + rx[1] * rx[1]).sqrt() - 1.0;
    TensionSample {
        s_material: (el as f64 + xi) * l,
        position: r,
        strain,
        tension: drive.mesh().elements()[el].axial_force(&e, xi),
    }
}

/// Mean material speed of the belt along its centreline \[m/s\]: the velocity `ṙ` at every
/// element's mid-point projected on the unit tangent `r_x/‖r_x‖` there (`ṙ = S(x) ė`, the
/// shape functions of Kerkkänen (3.1) applied to the velocities), averaged over the equal
/// elements. In a steady drive it is the belt speed `v` of the travelling-string formulas
/// (the speed of the flowing model's travel coordinate `ṡ_b`, Ribaric (5.14)).
pub fn belt_speed(drive: &BeltDrive, q: &[f64], v: &[f64]) -> f64 {
    let l = drive.element_length();
    let n_el = drive.mesh().elements().len();
    let (mut e, mut ev) = ([0.0; 12], [0.0; 12]);
    let mut sum = 0.0;
    for el in 0..n_el {
        drive.mesh().gather(q, el, &mut e);
        drive.mesh().gather(v, el, &mut ev);
        let (_, rx) = centreline(&e, l, 0.5);
        let (rdot, _) = centreline(&ev, l, 0.5);
        let norm = (rx[0] * rx[0] + rx[1] * rx[1]).sqrt();
        sum += (rdot[0] * rx[0] + rdot[1] * rx[1]) / norm;
    }
    sum / n_el.max(1) as f64
}

/// Tension at `per_element` equally spaced interior points of every element.
pub fn tension_samples(drive: &BeltDrive, q: &[f64], per_element: usize) -> Vec<TensionSample> {
    let n_el = drive.mesh().elements().len();
    let mut out = Vec::with_capacity(n_el * per_element);
    for el in 0..n_el {
        for k in 0..per_element {
            let xi = (k as f64 + 0.5) / per_element as f64;
            out.push(tension_at(drive, q, el, xi));
        }
    }
    out
}

/// One contact quadrature point on a wrap with the belt tension there.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct WrapRecord {
    /// The contact state (force densities, relative velocity, quadrature weight).
    pub contact: PointRecord,
    /// Angle \[rad\] from the inlet of the pulley's wrap in the travel direction
    /// ([`belt::BeltPath::angle_from_inlet`]).
    pub angle: f64,
    /// Axial force at the point recovered from equilibrium \[N\]
    /// ([`BeltDrive::section_forces`](super::BeltDrive::section_forces): smooth along the wrap,
    /// `dN/ds = −f_t` pointwise).
    pub tension: f64,
    /// The element's own axial force at the point \[N\]: the force of its material law at the
    /// local strain ([`tension_at`]) plus the viscous force of the axial damping
    /// ([`BeltDrive::viscous_axial_force`](super::BeltDrive::viscous_axial_force)). It ripples
    /// within the elements on a wrap (the axial strain of the cubic elements oscillates under
    /// the penalty contact) and converges slowly with the element count.
    pub element_tension: f64,
}

/// Every active contact quadrature point of `(q, v)` with the pulleys at the travel-sense
/// speeds `omegas` \[rad/s\] ([`BeltDrive::contact_records_with`]), with its angle on the pulley
/// and the belt tension there (recovered from equilibrium, and the element's own): the
/// tension, pressure and friction along every wrap, at the points where the contact forces are
/// integrated (3.27).
pub fn wrap_records(drive: &BeltDrive, q: &[f64], v: &[f64], omegas: &[f64]) -> Vec<WrapRecord> {
    let l = drive.element_length();
    let sections = drive.section_forces(q, v, omegas);
    drive
        .contact_records_with(q, v, omegas)
        .into_iter()
        .map(|c| {
            let xi = c.s_material / l - c.element as f64;
            WrapRecord {
                angle: drive
                    .path()
                    .angle_from_inlet(c.pulley, c.position)
                    .unwrap_or(f64::NAN),
                tension: sections.axial(c.element, xi),
                element_tension: tension_at(drive, q, c.element, xi).tension
                    + drive.viscous_axial_force(q, v, c.element, xi),
                contact: c,
            }
        })
        .collect()
}

pub use belt::SpanLine;

/// The straight spans of the drive's path in travel order.
pub fn spans(drive: &BeltDrive) -> Vec<SpanLine> {
    drive.path().spans()
}

/// Mean tension \[N\] of the belt points over the middle half of each span that run without a
/// break from the span's bisector ([`SpanLine::middle_run`]), in span order; `NaN` when the belt
/// does not cross the bisector.
pub fn span_tensions(drive: &BeltDrive, q: &[f64]) -> Vec<f64> {
    span_tensions_of(drive, &tension_samples(drive, q, 4))
}

/// [`span_tensions`] from the samples `samples` of [`tension_samples`] (in belt order): per
/// span the mean over the samples over its middle half that run without a break from its
/// bisector ([`SpanLine::middle_run`], the rule of the flowing and nodal reports: a part of the
/// belt that passes within the span's middle band, such as the slack span under a back-side
/// idler, is not averaged in); NaN where the belt does not cross the span's bisector.
fn span_tensions_of(drive: &BeltDrive, samples: &[TensionSample]) -> Vec<f64> {
    let points: Vec<[f64; 2]> = samples.iter().map(|s| s.position).collect();
    spans(drive)
        .iter()
        .map(|sp| {
            let run = sp.middle_run(&points);
            if run.is_empty() {
                f64::NAN
            } else {
                run.iter().map(|&i| samples[i].tension).sum::<f64>() / run.len() as f64
            }
        })
        .collect()
}

/// Position \[m\] of the belt point crossing the perpendicular bisector of each undeformed span
/// (the span mid-point of Kerkkänen Figs 3.10–3.11), in span order; `None` if the belt does
/// not cross it within half a span length of the span line.
pub fn span_midpoints(drive: &BeltDrive, q: &[f64]) -> Vec<Option<[f64; 2]>> {
    let mesh = drive.mesh();
    let l = drive.element_length();
    let mut e = [0.0; 12];
    spans(drive)
        .iter()
        .map(|sp| {
            let m = [
                sp.start[0] + 0.5 * sp.length * sp.direction[0],
                sp.start[1] + 0.5 * sp.length * sp.direction[1],
            ];
            let g = |r: [f64; 2]| (r[0] - m[0]) * sp.direction[0] + (r[1] - m[1]) * sp.direction[1];
            let mut best: Option<[f64; 2]> = None;
            for el in 0..mesh.elements().len() {
                mesh.gather(q, el, &mut e);
                let pos = |xi: f64| mesh.elements()[el].position(&e, xi * l, 0.0);
                let (ga, gb) = (g(pos(0.0)), g(pos(1.0)));
                if ga * gb > 0.0 || ga == gb {
                    continue;
                }
                let (a, b) = mbd_core::roots::bisect(
                    0.0,
                    1.0,
                    |c| (g(pos(c)) < 0.0) != (ga < 0.0),
                    mbd_core::roots::Stop::iterations(60),
                );
                let r = pos(0.5 * (a + b));
                let off = ((r[0] - m[0]).powi(2) + (r[1] - m[1]).powi(2)).sqrt();
                if off < 0.5 * sp.length {
                    let better = best.is_none_or(|o| {
                        off < ((o[0] - m[0]).powi(2) + (o[1] - m[1]).powi(2)).sqrt()
                    });
                    if better {
                        best = Some(r);
                    }
                }
            }
            best
        })
        .collect()
}

/// Transverse displacement \[m\] of each span's mid-point ([`span_midpoints`]) from the
/// undeformed span line, positive to the left of the travel direction; `NaN` where the belt
/// does not cross the span's bisector.
pub fn span_transverse(drive: &BeltDrive, q: &[f64]) -> Vec<f64> {
    spans(drive)
        .iter()
        .zip(span_midpoints(drive, q))
        .map(|(sp, m)| m.map_or(f64::NAN, |p| sp.local(p).1))
        .collect()
}

/// Arc coordinate \[m\] of `position` on pulley `p`, measured in the travel direction from the
/// point where the undeformed path arrives on the pulley (the inlet; Kerkkänen Fig. 3.17
/// measures from the inlet contact point), in `[−πR/2, 2πR − πR/2)`: `R` times
/// [`BeltPath::angle_from_inlet`](belt::BeltPath::angle_from_inlet).
pub fn pulley_arc_coordinate(drive: &BeltDrive, p: usize, position: [f64; 2]) -> f64 {
    let pl = &drive.pulleys()[p];
    pl.radius
        * drive
            .path()
            .angle_from_inlet(p, position)
            .unwrap_or(f64::NAN)
}

/// The snapshot ([`belt::report`]) of the ANCF drive at `(t, q, v)` with the pulleys spinning
/// at the travel-sense speeds `omegas` \[rad/s\]: the contact quadrature points of every wrap
/// ([`wrap_records`]), hub loads and torques ([`BeltDrive::pulley_loads_with`]), span
/// forces (as [`span_tensions`], plus the viscous force of the axial damping,
/// [`BeltDrive::viscous_axial_force`](super::BeltDrive::viscous_axial_force): the whole axial
/// force the belt carries), the axial damping's dissipation
/// ([`BeltDrive::damping_dissipation`](super::BeltDrive::damping_dissipation)), mid-point
/// offsets ([`span_transverse`]) and the lines of action of the spans' section forces
/// ([`BeltDrive::span_force_lines`]).
pub fn snapshot(drive: &BeltDrive, t: f64, q: &[f64], v: &[f64], omegas: &[f64]) -> Snapshot {
    snapshot_with(drive, t, q, v, omegas, true)
}

/// [`snapshot`], with the wrap points' tension recovered from equilibrium
/// ([`BeltDrive::section_forces`](super::BeltDrive::section_forces), a fine contact integral
/// per wrap point) only when `wrap_tension` (otherwise `NaN`: what
/// [`belt::BeltModel::report_snapshot`] may leave out; every other field is the same).
pub fn snapshot_with(
    drive: &BeltDrive, t: f64, q: &[f64], v: &[f64], omegas: &[f64], wrap_tension: bool,
) -> Snapshot {
    let loads = drive.pulley_loads_with(q, v, omegas);
    let pulleys = (0..drive.pulleys().len())
        .map(|k| {
            let (center, center_velocity) = drive.pulley_center(k, q, v);
            PulleyState {
                omega: omegas[k],
                hub_load: loads[k].force,
                torque: loads[k].torque,
                center_velocity,
                center,
            }
        })
        .collect();
    let wrap = if wrap_tension {
        wrap_records(drive, q, v, omegas)
            .into_iter()
            .filter(|w| w.contact.normal_force > 0.0)
            .map(|w| WrapPoint {
                pulley: w.contact.pulley,
                angle: w.angle,
                length: w.contact.weight,
                tension: w.tension,
                pressure: w.contact.normal_force,
                friction: w.contact.friction_force,
                slip: w.contact.slip,
            })
            .collect()
    } else {
        // the same contact records and angles, without the recovery
        drive
            .contact_records_with(q, v, omegas)
            .into_iter()
            .filter(|c| c.normal_force > 0.0)
            .map(|c| WrapPoint {
                pulley: c.pulley,
                angle: drive
                    .path()
                    .angle_from_inlet(c.pulley, c.position)
                    .unwrap_or(f64::NAN),
                length: c.weight,
                tension: f64::NAN,
                pressure: c.normal_force,
                friction: c.friction_force,
                slip: c.slip,
            })
            .collect()
    };
    // the whole axial force: elastic plus the axial damping's viscous force (issue 34)
    let mut samples = tension_samples(drive, q, 4);
    for (k, smp) in samples.iter_mut().enumerate() {
        smp.tension += drive.viscous_axial_force(q, v, k / 4, (k % 4) as f64 / 4.0 + 0.125);
    }
    let tensions = span_tensions_of(drive, &samples);
    let offsets = span_transverse(drive, q);
    let lines = drive.span_force_lines(q, v);
    let spans = spans(drive)
        .iter()
        .enumerate()
        .map(|(k, sp)| SpanState {
            from: sp.from,
            to: sp.to,
            tension: tensions[k],
            transverse: offsets[k],
            line: lines[k].0,
            momentum_flux: lines[k].1,
        })
        .collect();
    Snapshot {
        time: t,
        pulleys,
        spans,
        wrap,
        belt_dissipation: Some(drive.damping_dissipation(q, v)),
    }
}
