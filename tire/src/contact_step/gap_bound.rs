//! The skip bound of the candidate search ([`GapBound`]).

use faer::Mat;
use mbd_core::linalg::col_slice;

/// A lower bound on the free gaps of the contact nodes from their last evaluation, so that the
/// candidate search evaluates `T_c z` and the ground only for the nodes that may be within the
/// margin (issue #16: the 3 n_c × n_z product `T_c z` of all nodes and their ground queries
/// were a fixed cost per step).
///
/// Every ground query returns two lower-bound values `[b_s, b_m]` ([`GroundPoint::bound`],
/// argued per surface in the module documentation of [`crate::ground`]) with
/// `g(p', t') ≥ min(b_s − |p' − p|, b_m − |p' − p| − r |t' − t|)` wherever the right-hand side
/// is not negative: a static part (the drum or road, which do not depend on time; the gap
/// itself for the drum and road with the cleat, whose distances are 1-Lipschitz) and a moving
/// part (the cleat's and obstacles' distances, or a height grid's 1-Lipschitz lower bound)
/// that changes at a fixed point by at most the rate `r` ([`Ground::bound_rate`]: the surface
/// speed `v` for the cleat). Node `i` evaluated at time `tᵢ` with the values `sᵢ`, `mᵢ` and
/// reduced coordinates `zᵢ` moves by `|(T_c)ᵢ (z − zᵢ)| ≤ Lᵢ ‖z − zᵢ‖` (`Lᵢ` the spectral norm
/// of its three rows, at most their Frobenius norm), and `‖z − zᵢ‖ ≤ ‖z − z_ref‖ + eᵢ` with
/// `eᵢ ≥ ‖zᵢ − z_ref‖` (`‖zᵢ − z_ref‖` at the evaluation) for a common reference `z_ref`, so
/// with `Δ = Lᵢ (‖z − z_ref‖ + eᵢ)`
///
/// ```text
///   g(t, z) ≥ min(sᵢ − Δ, mᵢ − Δ − 1.01 r |t − tᵢ|) − 1e-9 m,
/// ```
///
/// and the node is skipped when this is at least the largest margin `contact_margin + h v`
/// (positive, so the bound's condition holds): its free gap is then certainly above the
/// margin, so the candidates are exactly those of a search over all nodes. The reference moves
/// to the current `z` when `L_max ‖z − z_ref‖` exceeds 0.1 mm, each `eᵢ` growing by the
/// distance moved ([`GapBound::distance`]), without evaluating the nodes again. On the cleat
/// run at h = 0.05 ms (31 candidates a step) this evaluates 47 nodes a step; a reset that
/// evaluated every node at 1 mm, with the Frobenius norm for `Lᵢ`, evaluated 61.
///
/// [`GroundPoint::bound`]: crate::ground::GroundPoint::bound
/// [`Ground::bound_rate`]: crate::ground::Ground::bound_rate
pub(super) struct GapBound {
    /// `Lᵢ` (with relative allowances for the round-off of the norms).
    pub(super) lip: Vec<f64>,
    pub(super) l_max: f64,
    pub(super) z_ref: Vec<f64>,
    pub(super) valid: bool,
    /// Per node: the last evaluated static and moving bound values \[m\], their time \[s\]
    /// and `eᵢ`.
    pub(super) stat: Vec<f64>,
    pub(super) moving: Vec<f64>,
    pub(super) time: Vec<f64>,
    pub(super) e: Vec<f64>,
}

impl GapBound {
    pub(super) fn new(tct: &Mat<f64>) -> Self {
        let nc = tct.ncols() / 3;
        let lip: Vec<f64> = (0..nc)
            .map(|i| {
                // ‖(T_c)ᵢ‖₂ = √λ_max of the 3 × 3 Gram matrix of node i's rows
                let c = |b| col_slice(tct, 3 * i + b);
                let gram = nalgebra::Matrix3::from_fn(|a, b| {
                    c(a).iter().zip(c(b)).map(|(x, y)| x * y).sum::<f64>()
                });
                let frob = gram.trace().sqrt();
                let spec = gram.symmetric_eigenvalues().max().max(0.0).sqrt();
                // (allowances for the round-off of the eigenvalue and of the sums; the
                // Frobenius norm bounds it too)
                (spec * (1.0 + 1e-10)).min(frob) * (1.0 + 1e-12)
            })
            .collect();
        let l_max = lip.iter().fold(0.0f64, |a, &b| a.max(b));
        Self {
            lip,
            l_max,
            z_ref: vec![0.0; tct.nrows()],
            valid: false,
            stat: vec![0.0; nc],
            moving: vec![0.0; nc],
            time: vec![0.0; nc],
            e: vec![0.0; nc],
        }
    }

    /// `‖z − z_ref‖`; when `L_max ‖z − z_ref‖` exceeds 0.1 mm the reference moves to `z` and
    /// every node's `eᵢ` grows by the distance moved (`‖zᵢ − z‖ ≤ ‖zᵢ − z_ref‖ + ‖z_ref − z‖`,
    /// so the bound still holds without evaluating the nodes again; a node is evaluated again
    /// when its bound comes within the margin, which resets its `eᵢ`). Without a reference
    /// yet, `z` becomes it and every node is to be evaluated.
    pub(super) fn distance(&mut self, z: &[f64]) -> f64 {
        if self.valid {
            let d = self
                .z_ref
                .iter()
                .zip(z)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt()
                * (1.0 + 1e-12);
            if self.l_max * d <= 1e-4 {
                return d;
            }
            // (1 + 1e-12): allowance for the round-off of the sums eᵢ + d
            self.e
                .iter_mut()
                .for_each(|e| *e = (*e + d) * (1.0 + 1e-12));
        }
        self.z_ref.copy_from_slice(z);
        0.0
    }

    /// Whether node `i`'s free gap at time `t` is certainly at least `margin` \[m\] (`dist` =
    /// [`GapBound::distance`], `rate` the moving bound value's rate \[m/s\],
    /// [`Ground::bound_rate`](crate::ground::Ground::bound_rate)).
    pub(super) fn skip(&self, i: usize, t: f64, dist: f64, rate: f64, margin: f64) -> bool {
        if !self.valid {
            return false;
        }
        let moved = self.lip[i] * (dist + self.e[i]);
        let moving = self.moving[i] - moved - 1.01 * rate * (t - self.time[i]).abs();
        (self.stat[i] - moved).min(moving) - 1e-9 >= margin
    }

    /// Node `i` evaluated: the bound values `[b_s, b_m]` \[m\]
    /// ([`GroundPoint::bound`](crate::ground::GroundPoint::bound)) at time `t` \[s\], `dist` =
    /// [`GapBound::distance`].
    pub(super) fn record(&mut self, i: usize, bound: [f64; 2], t: f64, dist: f64) {
        self.stat[i] = bound[0];
        self.moving[i] = bound[1];
        self.time[i] = t;
        self.e[i] = dist;
    }

    /// All nodes were evaluated in this step: the bound holds from now on.
    pub(super) fn set_valid(&mut self) {
        self.valid = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact_step::kernels::{dots3x2, uniform};

    /// Invariant of [`GapBound`]: a skipped node's gap is at least the margin, so the
    /// candidates are those of a search over all nodes. Synthetic ground (1-Lipschitz in the
    /// node position like `contact::geometry`): the smaller of the distance to a plane and to
    /// a circle moving at `v`; random `T_c` and a random walk of `z` with jumps, small and
    /// large steps (reference moves and fresh evaluations).
    #[test]
    fn skipped_nodes_are_beyond_the_margin() {
        let mut rnd = uniform(0x2545_f491_4f6c_dd1d);
        let (nz, nc) = (40, 30);
        let tct = Mat::from_fn(nz, 3 * nc, |_, _| 0.2 * rnd());
        let pos: Vec<[f64; 3]> = (0..nc)
            .map(|i| {
                // an arc of ±0.3 rad about the bottom: many nodes near the plane
                let a = (i as f64 / nc as f64 - 0.5) * 0.6;
                [0.3 * a.sin(), 0.0, -0.3 * a.cos()]
            })
            .collect();
        let (v, r, margin, h) = (16.7, 0.01, 1e-3, 5e-5);
        let gaps = |z: &[f64], t: f64| -> Vec<(f64, f64)> {
            (0..nc)
                .map(|i| {
                    let c = |b| col_slice(&tct, 3 * i + b);
                    let [d, _] = dots3x2([c(0), c(1), c(2)], z, [c(0), c(1), c(2)], z);
                    let p = [pos[i][0] + d[0], pos[i][1] + d[1], pos[i][2] + d[2]];
                    let plane = p[2] + 0.295;
                    let c = [-0.05 + v * t, -0.3 - 0.004];
                    let cleat = (p[0] - c[0]).hypot(p[2] - c[1]) - r;
                    (plane.min(cleat), cleat)
                })
                .collect()
        };
        let mut bound = GapBound::new(&tct);
        let mut z = vec![0.0; nz];
        // a drift (nodes approach or leave the ground steadily) plus noise
        let drift: Vec<f64> = (0..nz).map(|_| rnd()).collect();
        let (mut skipped, mut evaluated) = (0, 0);
        for step in 0..4000 {
            let t = step as f64 * h;
            let size = match step % 500 {
                0 => 0.02,
                s if s < 250 => 2e-4,
                _ => 2e-3,
            };
            let sign = if (step / 500) % 2 == 0 { 1.0 } else { -1.0 };
            for (x, d) in z.iter_mut().zip(&drift) {
                *x += size * (sign * d + 0.3 * rnd());
            }
            let dist = bound.distance(&z);
            let g = gaps(&z, t);
            for (i, &(gap, cleat)) in g.iter().enumerate() {
                if bound.skip(i, t, dist, v, margin + h * v) {
                    assert!(gap >= margin, "step {step} node {i}: gap {gap} skipped");
                    skipped += 1;
                } else {
                    bound.record(i, [gap, cleat], t, dist);
                    evaluated += 1;
                }
            }
            bound.set_valid();
        }
        // the bound must skip something, else the test is vacuous
        assert!(
            skipped > evaluated / 4,
            "{skipped} skipped, {evaluated} evaluated"
        );
    }
}
