//! Geometry of an open belt running over any number of pulleys.
//!
//! The path is the undeformed belt line of Ribaric (5.1)–(5.4): a closed curve made of straight
//! spans (common tangents of consecutive pulleys) and circular arcs (the wraps). It is
//! parametrised by the arc length `s ∈ [0, L)`, measured in the travel direction from the start
//! of the first span (the point where the belt leaves the first pulley). At every `s` it gives the
//! position `r(s)`, the unit tangent `e_t` (travel direction), the unit normal `e_n` pointing to the
//! centre of curvature, and the curvature `1/ρ` (`0` on spans), so that the acceleration of a
//! material point flowing with speed `v` along the path is `a e_t + (v²/ρ) e_n` (Ribaric (5.3)).
//!
//! Each pulley is wrapped either with the pulley inside the loop ([`WrapSide::Inside`], the belt
//! turns clockwise around it when the loop runs clockwise) or from the back ([`WrapSide::Outside`],
//! a back-side idler). Consecutive pulleys are joined by the tangent line that leaves the first
//! pulley and reaches the next one consistently with their wrap sides.
//!
//! For the two equal pulleys of Ribaric Table 6-1 (centres (0, 0) and (L_c, 0)) this reproduces the
//! parametrisation of the seed-000 note §10.1: upper span `y = R` to the right, arc on pulley 2,
//! lower span back to the left, arc on pulley 1; `L = 2 L_c + 2πR`.

use crate::pulley::{Pulley, WrapSide};
use mbd_core::validate::{InvalidField, check};
use std::f64::consts::PI;

/// One piece of the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Segment {
    /// Straight span from pulley `from` to the next pulley.
    Span {
        /// Index of the pulley the span leaves.
        from: usize,
        /// Start point \[m\].
        start: [f64; 2],
        /// Unit direction of travel.
        direction: [f64; 2],
    },
    /// Circular wrap on pulley `pulley`.
    Arc {
        /// Pulley index.
        pulley: usize,
        /// Polar angle of the arrival point measured at the pulley centre \[rad\].
        theta_start: f64,
        /// +1 when the belt turns clockwise on this pulley, −1 counter-clockwise.
        turn: f64,
    },
}

/// A located piece of the path: `s ∈ [s_start, s_start + length)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPiece {
    /// Arc length at the start of the piece \[m\].
    pub s_start: f64,
    /// Length of the piece \[m\].
    pub length: f64,
    /// Geometry.
    pub segment: Segment,
}

/// Geometry of the path at one arc-length position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// Arc length `s` (reduced to `[0, L)`) \[m\].
    pub s: f64,
    /// Position `r(s)` \[m\].
    pub position: [f64; 2],
    /// Unit tangent `e_t` (travel direction).
    pub tangent: [f64; 2],
    /// Unit normal `e_n` toward the centre of curvature (the left or right normal of the tangent
    /// on spans, chosen continuous with the preceding arc).
    pub normal: [f64; 2],
    /// Curvature `1/ρ` \[1/m\] (0 on spans).
    pub curvature: f64,
    /// Pulley index when on an arc.
    pub pulley: Option<usize>,
}

/// A line along which a span's force acts: a point on it and its unit travel direction.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LineOfAction {
    /// A point of the line \[m\].
    pub point: [f64; 2],
    /// Unit direction, in the belt's travel sense.
    pub direction: [f64; 2],
}

impl LineOfAction {
    /// The line of a planar force system with resultant `f` \[N\] and moment `m` \[N m\] about
    /// the origin (`m = Σ p × f_i`): the points `p` with `p × f = m`, the one nearest the
    /// origin `(m f_y, −m f_x)/|f|²`, directed in the travel sense `travel` (a unit vector), with
    /// the resultant's magnitude signed positive along it (a span in tension pulls along the
    /// travel direction, one in compression against it). `None` for a zero resultant.
    pub fn of_resultant(f: [f64; 2], m: f64, travel: [f64; 2]) -> Option<(f64, Self)> {
        let f2 = f[0] * f[0] + f[1] * f[1];
        if f2 == 0.0 {
            return None;
        }
        let s = if f[0] * travel[0] + f[1] * travel[1] >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let fl = f2.sqrt();
        Some((
            s * fl,
            Self {
                point: [m * f[1] / f2, -m * f[0] / f2],
                direction: [s * f[0] / fl, s * f[1] / fl],
            },
        ))
    }

    /// Lever arm \[m\] of a force along the line about `center`, positive when a pull in the
    /// travel direction turns a pulley wrapped with `turn` ([`crate::WrapSide::turn`]: `+1`
    /// clockwise) in its travel sense: `−turn (p − c) × e`. On the undeformed path it is the
    /// belt-line radius `R` of the pulleys the span joins (tangent to their belt-line circles).
    pub fn lever(&self, center: [f64; 2], turn: f64) -> f64 {
        let d = sub(self.point, center);
        -turn * (d[0] * self.direction[1] - d[1] * self.direction[0])
    }
}

/// A straight span of the path: start, unit travel direction, length and the pulleys it joins.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpanLine {
    /// Start point (where the span leaves pulley `from`) \[m\].
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
    /// Coordinates of `p` in the span's frame: `(u, w)` \[m\], `u` along the travel direction
    /// from the start, `w` to its left.
    pub fn local(&self, p: [f64; 2]) -> (f64, f64) {
        let d = sub(p, self.start);
        (
            d[0] * self.direction[0] + d[1] * self.direction[1],
            -d[0] * self.direction[1] + d[1] * self.direction[0],
        )
    }

    /// Whether `p` lies over the middle half of the span (a quarter length from either end)
    /// and within a quarter length of its line: the part of a span away from the pulleys
    /// where a belt's tension is the span tension.
    pub fn middle_half_contains(&self, p: [f64; 2]) -> bool {
        let (u, w) = self.local(p);
        u > 0.25 * self.length && u < 0.75 * self.length && w.abs() < 0.25 * self.length
    }

    /// Where the force of a deformed belt's span acts, away from the bending boundary layers
    /// at the pulleys: the least-squares line `w = w̄ + m (u − ū)` (span frame,
    /// [`Self::local`]) through the points of the closed polyline `points` (the deformed belt,
    /// in travel order) that run, without a break, over the span's middle half
    /// ([`Self::middle_half_contains`]) from where the polyline crosses the span's bisector
    /// ([`Self::bisector_crossing`]). `None` if it does not cross it or with fewer than two such
    /// points.
    pub fn line_of_action(&self, points: &[[f64; 2]]) -> Option<LineOfAction> {
        let n = points.len();
        let (i0, _) = self.bisector_segment(points)?;
        let inside = |k: usize| self.middle_half_contains(points[k % n]);
        let mut local = Vec::new();
        for k in (i0 + 1..i0 + 1 + n).take_while(|&k| inside(k)) {
            local.push(self.local(points[k % n]));
        }
        for k in (0..n).map(|j| (i0 + n - j) % n).take_while(|&k| inside(k)) {
            if local.len() >= n {
                break;
            }
            local.push(self.local(points[k]));
        }
        let n = local.len() as f64;
        if local.len() < 2 {
            return None;
        }
        let ub = local.iter().map(|p| p.0).sum::<f64>() / n;
        let wb = local.iter().map(|p| p.1).sum::<f64>() / n;
        let suu: f64 = local.iter().map(|p| (p.0 - ub).powi(2)).sum();
        if suu <= 1e-18 * self.length * self.length {
            return None;
        }
        let m = local.iter().map(|p| (p.0 - ub) * (p.1 - wb)).sum::<f64>() / suu;
        let (e, nrm) = (self.direction, [-self.direction[1], self.direction[0]]);
        let h = m.hypot(1.0);
        Some(LineOfAction {
            point: [
                self.start[0] + ub * e[0] + wb * nrm[0],
                self.start[1] + ub * e[1] + wb * nrm[1],
            ],
            direction: [(e[0] + m * nrm[0]) / h, (e[1] + m * nrm[1]) / h],
        })
    }

    /// Where the closed polyline `points` crosses the span's perpendicular bisector, closest
    /// to the span's mid-point and within half a span length of it (linear interpolation
    /// between consecutive points); `None` if it does not.
    pub fn bisector_crossing(&self, points: &[[f64; 2]]) -> Option<[f64; 2]> {
        self.bisector_segment(points).map(|(_, p)| p)
    }

    /// The segments `i → i+1` of the closed polyline `points` (the deformed belt, in travel
    /// order) that carry the span's force: those whose mid-points lie over the span's middle
    /// half ([`Self::middle_half_contains`]), running without a break from the one that crosses
    /// its bisector ([`Self::bisector_crossing`]). Empty if the polyline does not cross it.
    ///
    /// Contiguity matters where another part of the belt passes within a quarter span length
    /// of this span's line: on `apps/belt/examples/fead-three-pulley.toml` the slack span under
    /// the back-side idler, with the arm turned past −0.19 rad, lies in the tight span's middle
    /// band, and one of its elements was averaged into the tight span's force (issue 34: the
    /// 25 % torque residual at 1500 rpm).
    pub fn middle_run(&self, points: &[[f64; 2]]) -> Vec<usize> {
        let n = points.len();
        let Some((i0, _)) = self.bisector_segment(points) else {
            return Vec::new();
        };
        let inside = |i: usize| {
            let (a, b) = (points[i % n], points[(i + 1) % n]);
            self.middle_half_contains([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])])
        };
        let mut run: Vec<usize> = (i0..i0 + n)
            .take_while(|&i| inside(i))
            .map(|i| i % n)
            .collect();
        for i in (1..n).map(|j| (i0 + n - j) % n) {
            if run.len() >= n || !inside(i) {
                break;
            }
            run.push(i);
        }
        run
    }

    /// [`Self::bisector_crossing`] with the index `i` of the segment `i → i+1` it lies on.
    fn bisector_segment(&self, points: &[[f64; 2]]) -> Option<(usize, [f64; 2])> {
        let n = points.len();
        let g = |p: [f64; 2]| self.local(p).0 - 0.5 * self.length;
        let mut best: Option<(usize, [f64; 2], f64)> = None;
        for i in 0..n {
            let (a, b) = (points[i], points[(i + 1) % n]);
            let (ga, gb) = (g(a), g(b));
            if ga * gb > 0.0 || ga == gb {
                continue;
            }
            let f = ga / (ga - gb);
            let p = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
            let off = self.local(p).1.abs();
            if off < 0.5 * self.length && best.is_none_or(|(_, _, o)| off < o) {
                best = Some((i, p, off));
            }
        }
        best.map(|(i, p, _)| (i, p))
    }
}

/// A closed belt path over pulleys listed in travel order (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct BeltPath {
    pulleys: Vec<Pulley>,
    pieces: Vec<PathPiece>,
    length: f64,
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

impl BeltPath {
    /// Build the path over `pulleys` (in travel order, at least two; the loop runs clockwise
    /// around the pulleys wrapped [`WrapSide::Inside`]).
    ///
    /// Errors: fewer than two pulleys, a non-positive radius, overlapping pulleys for which no
    /// common tangent exists, or a wrap of zero length.
    pub fn new(pulleys: &[Pulley]) -> Result<Self, InvalidField> {
        let n = pulleys.len();
        if n < 2 {
            return Err(InvalidField::new(
                "pulleys",
                format!("a belt needs at least two pulleys, got {n}"),
            ));
        }
        for (i, p) in pulleys.iter().enumerate() {
            check::positive(&format!("pulleys[{i}].radius"), p.radius, "m")?;
            check::finite(&format!("pulleys[{i}].center[0]"), p.center[0])?;
            check::finite(&format!("pulleys[{i}].center[1]"), p.center[1])?;
        }
        // Tangent line from pulley i to pulley i+1. With d = +1 for a clockwise wrap, the
        // contact point is p = c + d r m, where m is the left normal of the travel direction t.
        // Collinearity of the two contact points gives m·Δ = d_a r_a − d_b r_b; t·Δ > 0 picks the
        // root.
        let turn = |p: &Pulley| p.side.turn();
        let mut leave = Vec::with_capacity(n); // (departure point on i, arrival point on i+1, t)
        for i in 0..n {
            let (a, b) = (&pulleys[i], &pulleys[(i + 1) % n]);
            let delta = sub(b.center, a.center);
            let l = norm(delta);
            let c = turn(a) * a.radius - turn(b) * b.radius;
            if l <= c.abs() || l == 0.0 {
                return Err(InvalidField::new(
                    format!("pulleys[{}].center", (i + 1) % n),
                    format!(
                        "no common tangent between '{}' and '{}': centres {l:.4} m apart, too close for their radii and wrap sides",
                        a.name, b.name
                    ),
                ));
            }
            let phi = delta[1].atan2(delta[0]);
            let beta = (c / l).acos();
            let m = [(phi + beta).cos(), (phi + beta).sin()];
            let t = [m[1], -m[0]];
            let pa = [
                a.center[0] + turn(a) * a.radius * m[0],
                a.center[1] + turn(a) * a.radius * m[1],
            ];
            let pb = [
                b.center[0] + turn(b) * b.radius * m[0],
                b.center[1] + turn(b) * b.radius * m[1],
            ];
            leave.push((pa, pb, t));
        }
        let mut pieces = Vec::with_capacity(2 * n);
        let mut s = 0.0;
        // the travel direction turns clockwise by Σ d·wrap (d = +1 inside, −1 outside): 2π for
        // a simple closed loop, a multiple otherwise (a path that crosses itself)
        let mut turning = 0.0;
        for i in 0..n {
            let (pa, pb, t) = leave[i];
            let span = norm(sub(pb, pa));
            pieces.push(PathPiece {
                s_start: s,
                length: span,
                segment: Segment::Span {
                    from: i,
                    start: pa,
                    direction: t,
                },
            });
            s += span;
            // wrap on pulley j = i+1 from the arrival point pb to the departure point of the next span
            let j = (i + 1) % n;
            let pj = &pulleys[j];
            let depart = leave[j].0;
            let th0 = (pb[1] - pj.center[1]).atan2(pb[0] - pj.center[0]);
            let th1 = (depart[1] - pj.center[1]).atan2(depart[0] - pj.center[0]);
            let d = turn(pj);
            // clockwise: the angle decreases from th0 to th1
            let wrap = (d * (th0 - th1)).rem_euclid(2.0 * PI);
            if wrap <= 1e-12 {
                return Err(InvalidField::new(
                    format!("pulleys[{j}]"),
                    format!("the belt does not wrap '{}' (zero wrap angle)", pj.name),
                ));
            }
            turning += d * wrap;
            let len = wrap * pj.radius;
            pieces.push(PathPiece {
                s_start: s,
                length: len,
                segment: Segment::Arc {
                    pulley: j,
                    theta_start: th0,
                    turn: d,
                },
            });
            s += len;
        }
        if (turning - 2.0 * PI).abs() > 1e-6 {
            return Err(InvalidField::new(
                "pulleys",
                format!(
                    "the belt path crosses itself: its direction turns by {:.0}° instead of 360° round the loop (check the pulleys' order and wrap sides)",
                    turning.to_degrees()
                ),
            ));
        }
        Ok(Self {
            pulleys: pulleys.to_vec(),
            pieces,
            length: s,
        })
    }

    /// Total path length `L` \[m\].
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The pulleys, in travel order.
    pub fn pulleys(&self) -> &[Pulley] {
        &self.pulleys
    }

    /// Replace pulley `k`'s motion (the geometry does not depend on it).
    pub(crate) fn set_motion(&mut self, k: usize, motion: crate::motion::Motion) {
        self.pulleys[k].motion = motion;
    }

    /// Spans and arcs in travel order (span 0 leaves pulley 0; arc `k` follows span `k`).
    pub fn pieces(&self) -> &[PathPiece] {
        &self.pieces
    }

    /// The straight spans in travel order (span `k` leaves pulley `k`).
    pub fn spans(&self) -> Vec<SpanLine> {
        let np = self.pulleys.len();
        self.pieces
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

    /// Index into [`Self::spans`] of the span over whose middle half `p` lies
    /// ([`SpanLine::middle_half_contains`]), the one whose line is nearest when several do
    /// (the two spans of a two-pulley drive with small pulleys lie closer to each other than a
    /// quarter span length); `None` off every span's middle.
    pub fn span_middle_of(spans: &[SpanLine], p: [f64; 2]) -> Option<usize> {
        spans
            .iter()
            .enumerate()
            .filter(|(_, s)| s.middle_half_contains(p))
            .min_by(|a, b| a.1.local(p).1.abs().total_cmp(&b.1.local(p).1.abs()))
            .map(|(k, _)| k)
    }

    /// The line of action of every span ([`SpanLine::line_of_action`]) of the deformed belt
    /// `points` (a closed polyline in travel order), in span order.
    pub fn lines_of_action(&self, points: &[[f64; 2]]) -> Vec<Option<LineOfAction>> {
        self.spans()
            .iter()
            .map(|sp| sp.line_of_action(points))
            .collect()
    }

    /// The arc on pulley `k`: (s at arrival, wrap length) \[m\].
    pub fn arc_of(&self, pulley: usize) -> Option<(f64, f64)> {
        self.pieces.iter().find_map(|p| match p.segment {
            Segment::Arc { pulley: k, .. } if k == pulley => Some((p.s_start, p.length)),
            _ => None,
        })
    }

    /// Wrap angle on pulley `k` \[rad\].
    pub fn wrap_angle(&self, pulley: usize) -> Option<f64> {
        self.arc_of(pulley)
            .map(|(_, l)| l / self.pulleys[pulley].radius)
    }

    /// Angle \[rad\] of `position` about the centre of `pulley`, measured in the travel
    /// direction from the point where the path arrives on the pulley (the inlet of its wrap), in
    /// `[−π/2, 3π/2)`: `turn·(θ_arrival − θ)` with `θ` the polar angle of `position` and `turn`
    /// the pulley's sense of wrap ([`Segment::Arc`]). `None` if the pulley index has no arc.
    pub fn angle_from_inlet(&self, pulley: usize, position: [f64; 2]) -> Option<f64> {
        let (theta_start, turn) = self.pieces.iter().find_map(|p| match p.segment {
            Segment::Arc {
                pulley: k,
                theta_start,
                turn,
            } if k == pulley => Some((theta_start, turn)),
            _ => None,
        })?;
        let c = self.pulleys[pulley].center;
        let th = (position[1] - c[1]).atan2(position[0] - c[0]);
        let lo = -0.5 * PI;
        Some((turn * (theta_start - th) - lo).rem_euclid(2.0 * PI) + lo)
    }

    /// `s` reduced to `[0, L)`.
    pub fn wrap_s(&self, s: f64) -> f64 {
        let r = s.rem_euclid(self.length);
        if r >= self.length { 0.0 } else { r }
    }

    /// Geometry at arc length `s` (any real `s`: the path is periodic).
    pub fn point(&self, s: f64) -> PathPoint {
        let s = self.wrap_s(s);
        let idx = self
            .pieces
            .partition_point(|p| p.s_start <= s)
            .saturating_sub(1);
        let piece = &self.pieces[idx];
        let u = s - piece.s_start;
        match piece.segment {
            Segment::Span {
                start,
                direction,
                from,
            } => {
                // normal continuous with the arc the span leaves (toward the side of pulley `from`)
                let d = match self.pulleys[from].side {
                    WrapSide::Inside => 1.0,
                    WrapSide::Outside => -1.0,
                };
                PathPoint {
                    s,
                    position: [start[0] + u * direction[0], start[1] + u * direction[1]],
                    tangent: direction,
                    normal: [d * direction[1], -d * direction[0]],
                    curvature: 0.0,
                    pulley: None,
                }
            }
            Segment::Arc {
                pulley,
                theta_start,
                turn,
            } => {
                let p = &self.pulleys[pulley];
                let th = theta_start - turn * u / p.radius;
                let (sn, cs) = th.sin_cos();
                PathPoint {
                    s,
                    position: [p.center[0] + p.radius * cs, p.center[1] + p.radius * sn],
                    tangent: [turn * sn, -turn * cs],
                    normal: [-cs, -sn],
                    curvature: 1.0 / p.radius,
                    pulley: Some(pulley),
                }
            }
        }
    }

    /// Node positions `s_i` for a mesh with element length close to `span_h` on spans and
    /// `arc_h` on arcs \[m\]; every span and arc end is a node, each piece gets at least one
    /// element. The result is increasing, starts at 0 and excludes `L` (closed loop).
    pub fn mesh_positions(&self, span_h: f64, arc_h: f64) -> Result<Vec<f64>, InvalidField> {
        check::positive("span_element_length", span_h, "m")?;
        check::positive("arc_element_length", arc_h, "m")?;
        let mut s = Vec::new();
        for piece in &self.pieces {
            let h = match piece.segment {
                Segment::Span { .. } => span_h,
                Segment::Arc { .. } => arc_h,
            };
            let n = ((piece.length / h).round() as usize).max(1);
            for k in 0..n {
                s.push(piece.s_start + piece.length * k as f64 / n as f64);
            }
        }
        Ok(s)
    }

    /// Indices of the nodes `s_nodes` lying on the arc of `pulley` or within `margin` \[m\] of it
    /// (measured along the path, periodically): the contact-node set of Ribaric 5.2 / 6.1.
    pub fn contact_nodes(&self, s_nodes: &[f64], pulley: usize, margin: f64) -> Vec<usize> {
        let Some((a, len)) = self.arc_of(pulley) else {
            return Vec::new();
        };
        let l = self.length;
        s_nodes
            .iter()
            .enumerate()
            .filter(|&(_, &s)| {
                // distance from s to the interval [a - margin, a + len + margin] on the loop
                let u = (s - (a - margin)).rem_euclid(l);
                u <= len + 2.0 * margin + 1e-12
            })
            .map(|(i, _)| i)
            .collect()
    }
}

/// Tributary length of each node of a closed loop with nodes at `s_nodes` (increasing, in
/// `[0, L)`): half the sum of the adjacent element lengths \[m\] (seed-000 note §10.1, used to scale
/// the penalty law (6.1)).
pub fn tributary_lengths(s_nodes: &[f64], loop_length: f64) -> Vec<f64> {
    let n = s_nodes.len();
    (0..n)
        .map(|i| {
            let next = if i + 1 < n {
                s_nodes[i + 1]
            } else {
                s_nodes[0] + loop_length
            };
            let prev = if i > 0 {
                s_nodes[i - 1]
            } else {
                s_nodes[n - 1] - loop_length
            };
            0.5 * (next - prev)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Motion;

    fn wheel(center: [f64; 2], radius: f64, side: WrapSide) -> Pulley {
        Pulley::new("p", center, radius, side, Motion::idler(1e-3))
    }

    /// An inside, a back-side and an inside pulley of different radii.
    fn three_pulleys() -> [Pulley; 3] {
        [
            wheel([0.0, 0.0], 0.05, WrapSide::Inside),
            wheel([0.25, 0.08], 0.03, WrapSide::Outside),
            wheel([0.5, 0.0], 0.07, WrapSide::Inside),
        ]
    }

    /// The mid-point of the span `sp` \[m\].
    fn span_midpoint(sp: &SpanLine) -> [f64; 2] {
        [
            sp.start[0] + 0.5 * sp.length * sp.direction[0],
            sp.start[1] + 0.5 * sp.length * sp.direction[1],
        ]
    }

    /// `n` points of `path` equally spaced along its length, from `s = 0`.
    fn polyline(path: &BeltPath, n: usize) -> Vec<[f64; 2]> {
        (0..n)
            .map(|k| path.point(path.length() * k as f64 / n as f64).position)
            .collect()
    }

    impl BeltPath {
        /// Two pulleys at (0, 0) and (`center_distance`, 0) (Ribaric Table 6-1's geometry).
        fn two_pulleys(center_distance: f64, r1: f64, r2: f64) -> Result<Self, InvalidField> {
            Self::new(&[
                wheel([0.0, 0.0], r1, WrapSide::Inside),
                wheel([center_distance, 0.0], r2, WrapSide::Inside),
            ])
        }
    }

    // the span frame: the mid-point of each span is (L/2, 0) and the straight path's polyline
    // crosses the bisector there (definition of the span geometry)
    #[test]
    fn span_lines_and_bisector_crossing() {
        let path = BeltPath::two_pulleys(0.45, 0.05, 0.08).unwrap();
        let spans = path.spans();
        assert_eq!(spans.len(), 2);
        assert_eq!(
            (spans[0].from, spans[0].to, spans[1].from, spans[1].to),
            (0, 1, 1, 0)
        );
        let pts = polyline(&path, 400);
        for sp in &spans {
            let m = span_midpoint(sp);
            let (u, w) = sp.local(m);
            assert!((u - 0.5 * sp.length).abs() < 1e-12 && w.abs() < 1e-12);
            assert!(sp.middle_half_contains(m));
            let c = sp.bisector_crossing(&pts).unwrap();
            assert!((c[0] - m[0]).hypot(c[1] - m[1]) < 1e-12);
        }
        // the spans of this drive lie 0.13 m apart, closer than a quarter span (0.11 m) from
        // each other's middle band: each mid-point is still assigned to its own span
        for (k, sp) in spans.iter().enumerate() {
            let m = span_midpoint(sp);
            assert_eq!(BeltPath::span_middle_of(&spans, m), Some(k));
        }
    }

    // The elements that carry a span's force (SpanLine::middle_run; reference: the path's own
    // arc lengths). On a two-pulley path whose spans lie 0.09 m apart, inside each other's
    // middle band (a quarter span, 0.1125 m), each span's run is exactly the polyline's
    // segments with both ends on that span's middle half, and the runs are disjoint.
    #[test]
    fn a_resultant_s_line_carries_its_moment() {
        // Reference: statics. Two parallel forces of 3 N and 1 N along +x at heights 0.2 and
        // 0.6 m: resultant 4 N along +x on the line y = (3·0.2 + 1·0.6)/4 = 0.3 m; the moment
        // about the origin of a force (f, 0) at height y is −y f.
        let m = -(3.0 * 0.2 + 1.0 * 0.6);
        let (t, line) = LineOfAction::of_resultant([4.0, 0.0], m, [1.0, 0.0]).unwrap();
        assert!((t - 4.0).abs() < 1e-15 && (line.point[1] - 0.3).abs() < 1e-15);
        assert_eq!(line.direction, [1.0, 0.0]);
        // against the travel sense: negative, the same line directed along the travel
        let (c, back) = LineOfAction::of_resultant([-4.0, 0.0], -m, [1.0, 0.0]).unwrap();
        assert!((c + 4.0).abs() < 1e-15 && (back.point[1] - 0.3).abs() < 1e-15);
        assert_eq!(back.direction, [1.0, 0.0]);
        assert!(LineOfAction::of_resultant([0.0, 0.0], 1.0, [1.0, 0.0]).is_none());
    }

    #[test]
    fn middle_run_is_the_span_s_own_middle_half() {
        let path = BeltPath::two_pulleys(0.45, 0.05, 0.04).unwrap();
        let spans = path.spans();
        let n = 400;
        let pts = polyline(&path, n);
        let mut seen = vec![false; n];
        for sp in &spans {
            let run = sp.middle_run(&pts);
            assert!(run.len() > 50, "{}", run.len());
            for &i in &run {
                assert!(!seen[i], "segment {i} in two runs");
                seen[i] = true;
                let (a, b) = (pts[i], pts[(i + 1) % n]);
                for p in [a, b] {
                    let (u, w) = sp.local(p);
                    assert!(w.abs() < 1e-9, "segment {i} off the span's line by {w} m");
                    assert!(u > 0.24 * sp.length && u < 0.76 * sp.length);
                }
            }
        }
    }

    // Lines of action (reference: tangent geometry). On the undeformed path every span is
    // tangent to the belt-line circles of the pulleys it joins, so the lever of its line about
    // either pulley is that pulley's radius R, with the travel-sense sign of the wrap: here on
    // an inside, a back-side and an inside pulley of different radii. A span shifted by e to
    // the left of travel has the lever R + turn·e about both ends (the left of travel is the
    // outside of a clockwise wrap), and a span turned about its mid-point by a small angle φ
    // changes the two levers by ∓φ L/2.
    #[test]
    fn lines_of_action_have_the_radius_as_lever_on_the_path() {
        let pulleys = three_pulleys();
        let path = BeltPath::new(&pulleys).unwrap();
        let pts = polyline(&path, 2000);
        let turn = |k: usize| pulleys[k].side.turn();
        let lines = path.lines_of_action(&pts);
        let spans = path.spans();
        assert_eq!(lines.len(), spans.len());
        for (sp, line) in spans.iter().zip(&lines) {
            let l = line.expect("points over every middle half");
            for k in [sp.from, sp.to] {
                let lever = l.lever(pulleys[k].center, turn(k));
                assert!(
                    (lever - pulleys[k].radius).abs() < 1e-12,
                    "span {}→{} about {k}: {lever}",
                    sp.from,
                    sp.to
                );
            }
            let (e, phi) = (2e-4, 1e-4);
            let n = [-sp.direction[1], sp.direction[0]];
            let mid = span_midpoint(sp);
            let moved: Vec<[f64; 2]> = pts
                .iter()
                .filter(|&&p| sp.middle_half_contains(p) && sp.local(p).1.abs() < 1e-9)
                .map(|&p| {
                    let u = sp.local(p).0 - 0.5 * sp.length;
                    [
                        mid[0] + u * sp.direction[0] + (e + phi * u) * n[0],
                        mid[1] + u * sp.direction[1] + (e + phi * u) * n[1],
                    ]
                })
                .collect();
            let l = sp.line_of_action(&moved).unwrap();
            for (k, end) in [(sp.from, -1.0), (sp.to, 1.0)] {
                let want = pulleys[k].radius
                    + turn(k) * (e + end * phi * 0.5 * sp.length) / (1.0 + phi * phi).sqrt();
                let lever = l.lever(pulleys[k].center, turn(k));
                assert!((lever - want).abs() < 1e-9, "{lever} vs {want}");
            }
        }
    }

    // the angle from the inlet of a point on the arc is its path length from the arrival point
    // over R (definition of the path's arcs), on an inside and a back-side pulley
    #[test]
    fn angle_from_inlet_follows_the_arc_length() {
        let pulleys = three_pulleys();
        let path = BeltPath::new(&pulleys).unwrap();
        for (k, pulley) in pulleys.iter().enumerate() {
            let (a, len) = path.arc_of(k).unwrap();
            for f in [0.0, 0.3, 0.9] {
                let p = path.point(a + f * len).position;
                let phi = path.angle_from_inlet(k, p).unwrap();
                let expect = f * len / pulley.radius;
                assert!(
                    (phi - expect).abs() < 1e-12,
                    "pulley {k}: {phi} vs {expect}"
                );
            }
        }
        assert!(path.angle_from_inlet(3, [0.0, 0.0]).is_none());
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    // seed-000 note §10.1 (Ribaric Table 6-1 geometry): L = 2 L_c + 2πR, upper span y = R to the right
    #[test]
    fn two_equal_pulleys_match_the_closed_form_path() {
        let (lc, r) = (0.45, 0.05);
        let p = BeltPath::two_pulleys(lc, r, r).unwrap();
        assert!(close(p.length(), 2.0 * lc + 2.0 * PI * r, 1e-12));
        let a = p.point(0.1);
        assert!(close(a.position[0], 0.1, 1e-12) && close(a.position[1], r, 1e-12));
        assert!(close(a.tangent[0], 1.0, 1e-15) && close(a.tangent[1], 0.0, 1e-15));
        assert_eq!(a.curvature, 0.0);
        // middle of the arc on pulley 2: rightmost point, moving down, normal to the left
        let m = p.point(lc + 0.5 * PI * r);
        assert!(close(m.position[0], lc + r, 1e-12) && close(m.position[1], 0.0, 1e-12));
        assert!(close(m.tangent[1], -1.0, 1e-12) && close(m.normal[0], -1.0, 1e-12));
        assert_eq!(m.pulley, Some(1));
        // lower span moves left at y = -R
        let b = p.point(lc + PI * r + 0.2);
        assert!(close(b.position[0], lc - 0.2, 1e-12) && close(b.position[1], -r, 1e-12));
        assert!(close(b.tangent[0], -1.0, 1e-12));
        assert!(close(p.wrap_angle(0).unwrap(), PI, 1e-12));
    }

    // Geometry invariants: tangent continuity, |e_t| = 1, e_t ⟂ e_n, dr/ds = e_t (finite differences)
    #[test]
    fn path_is_c1_and_tangent_is_the_derivative() {
        let p = BeltPath::new(&[
            wheel([0.0, 0.0], 0.1, WrapSide::Inside),
            wheel([0.5, 0.1], 0.05, WrapSide::Inside),
            wheel([0.25, -0.05], 0.04, WrapSide::Outside),
        ])
        .unwrap();
        let l = p.length();
        let h = 1e-6;
        for k in 0..2000 {
            let s = l * k as f64 / 2000.0;
            let q = p.point(s);
            let (a, b) = (p.point(s - h), p.point(s + h));
            let fd = [
                (b.position[0] - a.position[0]) / (2.0 * h),
                (b.position[1] - a.position[1]) / (2.0 * h),
            ];
            assert!(
                close(fd[0], q.tangent[0], 1e-5) && close(fd[1], q.tangent[1], 1e-5),
                "s = {s}"
            );
            assert!(close(norm(q.tangent), 1.0, 1e-12));
            assert!(close(
                q.tangent[0] * q.normal[0] + q.tangent[1] * q.normal[1],
                0.0,
                1e-12
            ));
        }
        // wrap angles of a closed convex-plus-idler loop: inside wraps minus outside wraps = 2π
        let total = p.wrap_angle(0).unwrap() + p.wrap_angle(1).unwrap() - p.wrap_angle(2).unwrap();
        let w: Vec<f64> = (0..3).map(|k| p.wrap_angle(k).unwrap()).collect();
        assert!(close(total, 2.0 * PI, 1e-9), "{total} {w:?}");
    }

    // Unequal pulleys: wrap angles π ± 2 asin((R2 − R1)/L_c) (seed-000 note §10.1)
    #[test]
    fn unequal_pulleys_wrap_angles() {
        let (lc, r1, r2) = (0.3, 0.05, 0.1218 / 2.0 + 0.03);
        let p = BeltPath::two_pulleys(lc, r1, r2).unwrap();
        let g = ((r2 - r1) / lc).asin();
        assert!(close(p.wrap_angle(0).unwrap(), PI - 2.0 * g, 1e-12));
        assert!(close(p.wrap_angle(1).unwrap(), PI + 2.0 * g, 1e-12));
        let span = (lc * lc - (r2 - r1).powi(2)).sqrt();
        assert!(close(
            p.length(),
            2.0 * span + r1 * (PI - 2.0 * g) + r2 * (PI + 2.0 * g),
            1e-12
        ));
    }

    #[test]
    fn mesh_positions_contact_sets_and_tributary_lengths() {
        let p = BeltPath::two_pulleys(0.45, 0.05, 0.05).unwrap();
        let s = p.mesh_positions(0.045, 0.0157).unwrap();
        assert_eq!(s.len(), 10 + 10 + 10 + 10);
        let trib = tributary_lengths(&s, p.length());
        assert!(close(trib.iter().sum::<f64>(), p.length(), 1e-12));
        let c1 = p.contact_nodes(&s, 1, 0.05);
        // arc of pulley 2 has 11 nodes on [L_c, L_c + πR] (both ends) plus one span node each side
        assert_eq!(c1.len(), 13);
        let c0 = p.contact_nodes(&s, 0, 0.0);
        assert!(
            c0.contains(&0),
            "node 0 (end of arc 0 / start of span 0) is on pulley 1's arc"
        );
    }

    #[test]
    fn bad_geometry_is_a_typed_error() {
        assert!(BeltPath::two_pulleys(0.05, 0.1, 0.2).is_err());
        assert!(BeltPath::two_pulleys(0.45, -0.1, 0.05).is_err());
        assert!(BeltPath::new(&[]).is_err());
        let e = BeltPath::two_pulleys(0.45, 0.05, 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("pulleys[1].radius"), "{e}");
    }

    // three collinear pulleys with a smaller middle one, all wrapped inside: the common
    // tangents make the belt cross itself (wraps summing to 720°) — refused
    #[test]
    fn a_self_crossing_path_is_refused() {
        let p = [
            wheel([0.0, 0.0], 0.05, WrapSide::Inside),
            wheel([0.2, 0.0], 0.02, WrapSide::Inside),
            wheel([0.4, 0.0], 0.05, WrapSide::Inside),
        ];
        let e = BeltPath::new(&p).unwrap_err();
        assert!(e.reason.contains("crosses itself"), "{e}");
    }
}
