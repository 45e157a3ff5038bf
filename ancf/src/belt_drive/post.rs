//! Post-processing of a belt-drive state: tension along the belt (Kerkkänen (4.5)–(4.9)), span
//! tensions and mid-span positions (Figs 3.10–3.12), pulley arc coordinates of contact points
//! (Fig. 3.17).

use super::model::BeltDrive;
use crate::element::Element;
use crate::shape;
use fe_model::generate::belt_path::{BeltPath, Segment};

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
    /// Tension `α₁ E A ε` \[N\] (longitudinal stiffness times strain, Kerkkänen §4.2).
    pub tension: f64,
}

/// Tension at `per_element` equally spaced interior points of every element.
pub fn tension_samples(drive: &BeltDrive, q: &[f64], per_element: usize) -> Vec<TensionSample> {
    let mesh = drive.mesh();
    let b = &drive.spec().belt;
    let ea = b.alpha1 * b.young * b.width * b.thickness;
    let l = drive.element_length();
    let mut e = [0.0; 12];
    let mut out = Vec::with_capacity(mesh.elements().len() * per_element);
    for el in 0..mesh.elements().len() {
        mesh.gather(q, el, &mut e);
        for k in 0..per_element {
            let xi = (k as f64 + 0.5) / per_element as f64;
            let sh = shape::cubic(l, xi * l, 0.0);
            let mut r = [0.0; 2];
            let mut rx = [0.0; 2];
            for a in 0..6 {
                r[0] += sh.s[a] * e[2 * a];
                r[1] += sh.s[a] * e[2 * a + 1];
                rx[0] += sh.sx[a] * e[2 * a];
                rx[1] += sh.sx[a] * e[2 * a + 1];
            }
            let strain = (rx[0] * rx[0] + rx[1] * rx[1]).sqrt() - 1.0;
            out.push(TensionSample {
                s_material: (el as f64 + xi) * l,
                position: r,
                strain,
                tension: ea * strain,
            });
        }
    }
    out
}

/// Geometry of span `k` of the undeformed path: start \[m\], unit direction, length \[m\], and the
/// pulleys it leaves and reaches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpanLine {
    /// Start point \[m\].
    pub start: [f64; 2],
    /// Unit travel direction.
    pub direction: [f64; 2],
    /// Length \[m\].
    pub length: f64,
    /// Pulley the span leaves.
    pub from: usize,
    /// Pulley the span reaches.
    pub to: usize,
}

impl SpanLine {
    /// Whether `position` \[m\] lies over the middle half of the span (within a quarter span
    /// length of the span line): the region where span tensions are averaged.
    pub fn middle_half_contains(&self, position: [f64; 2]) -> bool {
        let d = [position[0] - self.start[0], position[1] - self.start[1]];
        let u = d[0] * self.direction[0] + d[1] * self.direction[1];
        let w = -d[0] * self.direction[1] + d[1] * self.direction[0];
        u > 0.25 * self.length && u < 0.75 * self.length && w.abs() < 0.25 * self.length
    }
}

/// The straight spans of the drive's path in travel order.
pub fn spans(drive: &BeltDrive) -> Vec<SpanLine> {
    path_spans(drive.path())
}

/// The straight spans of a belt path in travel order (shared with the plate-belt drive,
/// [`crate::plate::belt_drive`]).
pub fn path_spans(path: &BeltPath) -> Vec<SpanLine> {
    let np = path.pulleys().len();
    path.pieces()
        .iter()
        .filter_map(|pc| match pc.segment {
            Segment::Span {
                from,
                start,
                direction,
            } => Some(SpanLine {
                start,
                direction,
                length: pc.length,
                from,
                to: (from + 1) % np,
            }),
            _ => None,
        })
        .collect()
}

/// Mean tension \[N\] of the belt points that currently lie over the middle half of each span
/// (within a quarter span length of the undeformed span line), in span order; `NaN` when no
/// sample lies there.
pub fn span_tensions(drive: &BeltDrive, q: &[f64]) -> Vec<f64> {
    let samples = tension_samples(drive, q, 4);
    spans(drive)
        .iter()
        .map(|sp| {
            let (mut sum, mut n) = (0.0, 0usize);
            for s in &samples {
                if sp.middle_half_contains(s.position) {
                    sum += s.tension;
                    n += 1;
                }
            }
            if n == 0 { f64::NAN } else { sum / n as f64 }
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
                let (mut a, mut b) = (0.0, 1.0);
                let (ga, gb) = (g(pos(a)), g(pos(b)));
                if ga * gb > 0.0 || ga == gb {
                    continue;
                }
                let mut fa = ga;
                for _ in 0..60 {
                    let c = 0.5 * (a + b);
                    let fc = g(pos(c));
                    if (fc < 0.0) == (fa < 0.0) {
                        a = c;
                        fa = fc;
                    } else {
                        b = c;
                    }
                }
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

/// Arc coordinate \[m\] of `position` on pulley `p`, measured in the travel direction from the
/// point where the undeformed path arrives on the pulley (the inlet; Kerkkänen Fig. 3.17
/// measures from the inlet contact point), in `[−πR/2, 2πR − πR/2)`.
pub fn pulley_arc_coordinate(drive: &BeltDrive, p: usize, position: [f64; 2]) -> f64 {
    let pl = &drive.pulleys()[p];
    let c = pl.center;
    let arrival = match drive.path().arc_of(p) {
        Some((s, _)) => drive.path().point(s).position,
        None => [c[0] + pl.radius, c[1]],
    };
    let a = [arrival[0] - c[0], arrival[1] - c[1]];
    let b = [position[0] - c[0], position[1] - c[1]];
    let ccw = (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1]);
    // travel sense: clockwise for pulleys inside the loop
    let mut ang = ccw * pl.ccw_sign();
    let lo = -0.25 * std::f64::consts::TAU;
    while ang < lo {
        ang += std::f64::consts::TAU;
    }
    while ang >= lo + std::f64::consts::TAU {
        ang -= std::f64::consts::TAU;
    }
    pl.radius * ang
}
