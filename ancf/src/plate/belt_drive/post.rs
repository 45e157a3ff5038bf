//! Post-processing of a plate-belt state (Kerkkänen §4.2): strain by the three measures
//! (4.9)–(4.11) and tension along a material line of the belt, belt speed (4.12)–(4.13), the
//! area ratio of Fig. 4.13, span tensions and membrane forces, contact torques, path
//! coordinates for comparisons with the analytical model, and the belt surface for VTK output.

use super::model::PlateBeltDrive;
use crate::plate::strain::{StrainMeasure, area_ratio};
use belt::{BeltPath, Segment, SpanLine};

/// Kinematics and strain at one material point of the belt.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BeltSample {
    /// Element index.
    pub element: usize,
    /// Material (unstretched) coordinate along the belt from cross-section 0 \[m\].
    pub s_material: f64,
    /// Material coordinate across the belt \[m\].
    pub y: f64,
    /// Position \[m\].
    pub position: [f64; 3],
    /// Fibre strain along the belt by the measures Green (4.9), true (4.10), Almansi (4.11), in
    /// the order of [`StrainMeasure::ALL`].
    pub strain: [f64; 3],
    /// Tension `k ε` \[N\] for the three strains, `k = E w h` (Kerkkänen §4.2: longitudinal
    /// stiffness times strain).
    pub tension: [f64; 3],
    /// Area ratio `√det(JᵀJ)` (Fig. 4.13's "determinant of the Jacobian").
    pub area_ratio: f64,
    /// Belt speed `v = t_tᵀ ṙ` (4.12)–(4.13), `t_t = r_x/‖r_x‖` \[m/s\].
    pub speed: f64,
}

impl BeltSample {
    /// The tension \[N\] by `measure`.
    pub fn tension_by(&self, measure: StrainMeasure) -> f64 {
        self.tension[measure as usize]
    }
}

/// Samples at `per_element` equally spaced points `x = (k + ½) a / per_element` of every
/// element along the material line `y` \[m\] (Kerkkänen: 20 points per element on the edge
/// `y = 0` for Figs 4.12–4.15).
pub fn line_samples(
    drive: &PlateBeltDrive, q: &[f64], v: &[f64], y: f64, per_element: usize,
) -> Vec<BeltSample> {
    let k_axial = drive.spec().belt.axial_stiffness();
    let a = drive.element_length();
    let n = per_element.max(1);
    let mut e = [0.0; 36];
    let mut ed = [0.0; 36];
    let mut out = Vec::with_capacity(drive.n_elements() * n);
    for el in 0..drive.n_elements() {
        drive.gather(q, el, &mut e);
        drive.gather(v, el, &mut ed);
        let plate = &drive.mesh().cells[el].plate;
        for k in 0..n {
            let x = (k as f64 + 0.5) * a / n as f64;
            let [r, rx, ry] = plate.kinematics(&e, x, y);
            let [rd, _, _] = plate.kinematics(&ed, x, y);
            let strain = StrainMeasure::ALL.map(|m| m.fibre_strain(rx, ry));
            let lx = (rx[0] * rx[0] + rx[1] * rx[1] + rx[2] * rx[2]).sqrt();
            let speed = (rx[0] * rd[0] + rx[1] * rd[1] + rx[2] * rd[2]) / lx;
            out.push(BeltSample {
                element: el,
                s_material: el as f64 * a + x,
                y,
                position: r,
                strain,
                tension: strain.map(|s| k_axial * s),
                area_ratio: area_ratio(rx, ry),
                speed,
            });
        }
    }
    out
}

/// The straight spans of the drive's (initial) path in travel order.
pub fn spans(drive: &PlateBeltDrive) -> Vec<SpanLine> {
    drive.path().spans()
}

/// Axial belt state of one span: means over the belt points lying over its middle half.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpanState {
    /// Tension `k ε` by the three measures \[N\] (order of [`StrainMeasure::ALL`]).
    pub tension: [f64; 3],
    /// Membrane force along the belt \[N\] ([`crate::plate::ThinPlate::membrane_section_force`]
    /// projected on `t_t`).
    pub membrane_force: f64,
    /// Belt speed \[m/s\].
    pub speed: f64,
}

/// [`SpanState`] of every span (NaN where no belt point lies over the span's middle half),
/// sampled on the centreline `y = w/2` at 4 points per element.
pub fn span_states(drive: &PlateBeltDrive, q: &[f64], v: &[f64]) -> Vec<SpanState> {
    let w = drive.spec().belt.width;
    let samples = line_samples(drive, q, v, 0.5 * w, 4);
    let mut e = [0.0; 36];
    let a = drive.element_length();
    spans(drive)
        .iter()
        .map(|sp| {
            let mut acc = SpanState {
                tension: [0.0; 3],
                membrane_force: 0.0,
                speed: 0.0,
            };
            let mut n = 0usize;
            for s in &samples {
                if !sp.middle_half_contains([s.position[0], s.position[1]]) {
                    continue;
                }
                drive.gather(q, s.element, &mut e);
                let plate = &drive.mesh().cells[s.element].plate;
                let x = s.s_material - s.element as f64 * a;
                let f = plate.membrane_section_force(&e, x, 5);
                let [_, rx, _] = plate.kinematics(&e, x, s.y);
                let lx = (rx[0] * rx[0] + rx[1] * rx[1] + rx[2] * rx[2]).sqrt();
                for m in 0..3 {
                    acc.tension[m] += s.tension[m];
                }
                acc.membrane_force += (f[0] * rx[0] + f[1] * rx[1] + f[2] * rx[2]) / lx;
                acc.speed += s.speed;
                n += 1;
            }
            if n == 0 {
                return SpanState {
                    tension: [f64::NAN; 3],
                    membrane_force: f64::NAN,
                    speed: f64::NAN,
                };
            }
            let k = 1.0 / n as f64;
            SpanState {
                tension: acc.tension.map(|t| t * k),
                membrane_force: acc.membrane_force * k,
                speed: acc.speed * k,
            }
        })
        .collect()
}

/// Travel-sense contact torque on every pulley at `(t, q, v)` \[N·m\] (the spatial
/// (3.26): the moment of the contact forces about the pulley axis).
pub fn pulley_torques(drive: &PlateBeltDrive, t: f64, q: &[f64], v: &[f64]) -> Vec<f64> {
    drive
        .pulley_loads(t, q, v)
        .into_iter()
        .map(|(_, tau)| tau)
        .collect()
}

/// Arc-length coordinate \[m\] of the point of `path` closest to `position` (the drive-plane
/// projection of a belt point): the abscissa on which finite-element distributions are
/// compared with the analytical model's (which lives on the undeformed path).
pub fn path_coordinate(path: &BeltPath, position: [f64; 2]) -> f64 {
    let mut best = (f64::INFINITY, 0.0);
    for pc in path.pieces() {
        let (d, u) = match pc.segment {
            Segment::Span {
                start, direction, ..
            } => {
                let rel = [position[0] - start[0], position[1] - start[1]];
                let u = (rel[0] * direction[0] + rel[1] * direction[1]).clamp(0.0, pc.length);
                let p = [start[0] + u * direction[0], start[1] + u * direction[1]];
                ((position[0] - p[0]).hypot(position[1] - p[1]), u)
            }
            Segment::Arc {
                pulley,
                theta_start,
                turn,
            } => {
                let pl = &path.pulleys()[pulley];
                let th = (position[1] - pl.center[1]).atan2(position[0] - pl.center[0]);
                // angle travelled from the arrival point, in the turning sense
                let mut u = (theta_start - th) * turn * pl.radius;
                let full = std::f64::consts::TAU * pl.radius;
                u = u.rem_euclid(full);
                // beyond the arc: the nearer end
                if u > pc.length {
                    u = if u - pc.length < full - u {
                        pc.length
                    } else {
                        0.0
                    };
                }
                let p = path.point(pc.s_start + u).position;
                ((position[0] - p[0]).hypot(position[1] - p[1]), u)
            }
        };
        if d < best.0 {
            best = (d, pc.s_start + u);
        }
    }
    path.wrap_s(best.1)
}

/// The deformed belt surface as a grid of `(per_element + 1) × 2` points per element
/// (element-wise, shared edges duplicated) and its quadrilaterals, with the point fields
/// (tension \[N\] by a strain measure, velocity \[m/s\]), for VTK output.
pub struct SurfaceGrid {
    /// Points \[m\].
    pub points: Vec<[f64; 3]>,
    /// Quadrilaterals (point indices, counter-clockwise in the material plane).
    pub quads: Vec<[usize; 4]>,
    /// Tension `k ε` at each point \[N\].
    pub tension: Vec<f64>,
    /// Velocity at each point \[m/s\].
    pub velocity: Vec<[f64; 3]>,
}

/// See [`SurfaceGrid`]; the tension with the strain `measure`.
pub fn surface_grid(
    drive: &PlateBeltDrive, q: &[f64], v: &[f64], per_element: usize, measure: StrainMeasure,
) -> SurfaceGrid {
    let n = per_element.max(1);
    let a = drive.element_length();
    let w = drive.spec().belt.width;
    let k_axial = drive.spec().belt.axial_stiffness();
    let mut g = SurfaceGrid {
        points: Vec::new(),
        quads: Vec::new(),
        tension: Vec::new(),
        velocity: Vec::new(),
    };
    let (mut e, mut ed) = ([0.0; 36], [0.0; 36]);
    for el in 0..drive.n_elements() {
        drive.gather(q, el, &mut e);
        drive.gather(v, el, &mut ed);
        let plate = &drive.mesh().cells[el].plate;
        let base = g.points.len();
        for k in 0..=n {
            let x = k as f64 * a / n as f64;
            for y in [0.0, w] {
                let [r, rx, ry] = plate.kinematics(&e, x, y);
                g.points.push(r);
                g.tension.push(k_axial * measure.fibre_strain(rx, ry));
                g.velocity.push(plate.kinematics(&ed, x, y)[0]);
            }
        }
        for k in 0..n {
            let i = base + 2 * k;
            g.quads.push([i, i + 2, i + 3, i + 1]);
        }
    }
    g
}
