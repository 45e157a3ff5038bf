//! The local Delassus matrix of the candidates ([`TireDelassus`]): the tire's side of the
//! shared contact solver ([`contact::DelassusSource`]), gathered lazily from the cached
//! contact-node responses, with the free slip velocities of the pressed nodes.

use super::blocks::{CandidateBlocks, Responses};
use super::kernels::dots3x2;
use crate::ground::GroundPoint;
use crate::reduced::ReducedTire;
use contact::DelassusSource;
use faer::Mat;
use mbd_core::linalg::col_slice;

pub(super) fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Tangent basis of a ground normal `n`: `t1 = ŷ × n/|ŷ × n| = [n_z, 0, −n_x]/√(n_x² + n_z²)`
/// (along the road in the travel direction), `t2 = n × t1`. For a normal in the wheel's
/// `(x, z)` plane (`n_y = 0`: the drum, the road and transverse obstacles, extruded along the
/// axis `y`) this is `t1 = [n_z, 0, −n_x]`, `t2 = ŷ`, computed as such (the arithmetic of the
/// planar ground, kept bit for bit). A normal along the axis (a pothole's side wall) takes
/// `t1 = x̂` projected onto the tangent plane.
pub(super) fn tangents(n: &[f64; 3]) -> ([f64; 3], [f64; 3]) {
    if n[1] == 0.0 {
        return ([n[2], 0.0, -n[0]], [0.0, 1.0, 0.0]);
    }
    let r = n[0].hypot(n[2]);
    let t1 = if r > 1e-6 {
        [n[2] / r, 0.0, -n[0] / r]
    } else {
        let a = [1.0 - n[0] * n[0], -n[0] * n[1], -n[0] * n[2]];
        let l = dot3(&a, &a).sqrt();
        [a[0] / l, a[1] / l, a[2] / l]
    };
    let t2 = [
        n[1] * t1[2] - n[2] * t1[1],
        n[2] * t1[0] - n[0] * t1[2],
        n[0] * t1[1] - n[1] * t1[0],
    ];
    (t1, t2)
}

/// The local Delassus matrix of the candidates, gathered lazily from the cached columns:
/// rows `(g_k, u1_k, u2_k)`, columns `(λ_l, f1_l, f2_l)`,
///
/// ```text
///   D_N,kl = β_N h² n_kᵀ Y_kl R_l (+ 1/k_penalty on the diagonal),
///   D_T,kl = γ_N h t_kᵀ (Y_kl + (η × s_k) X_θ,l + (Ω/γ_N h) Y_θ,kl) R_l,   R_l = [n_l t1_l t2_l],
/// ```
///
/// where `Y_kl` moves contact node k under a unit force on node l (end-of-step displacement per
/// unit `Δz̈`), `(η × s_k) X_θ,l` is the rigid spin part of the material velocity (E15) and
/// `Ω Y_θ,kl β_N h²` the change of the transported deflection `Ω T_c,θ z` (Ribaric (7.10),
/// upwind rows) with the displacement (the change of `Ω` itself in that product is left out:
/// `|T_c,θ z| ≪ |η × s|`).
/// While every candidate's normal lies in the wheel's `(x, z)` plane (`planar`) the products
/// use that each frame vector then has two (`n`, `t1`) or one (`t2 = ŷ`) non-zero component;
/// otherwise the full 3 × 3 products.
pub(super) struct TireDelassus<'b> {
    pub(super) fac: &'b Responses,
    /// The candidates' blocks of `Y` and `X_θ` (gathered on demand).
    pub(super) blocks: &'b mut CandidateBlocks,
    pub(super) red: &'b ReducedTire,
    pub(super) cand: &'b [usize],
    pub(super) gp: &'b [GroundPoint],
    /// Local frames `[n, t1, t2]` of the candidates, scaled by `β_N h²` (row n) and `γ_N h`
    /// (rows t1, t2).
    pub(super) frames: &'b [[[f64; 3]; 3]],
    /// `γ_N h t1ᵀ(η × s + T_c,θ z)` per candidate.
    pub(super) rig_t1: &'b [f64],
    /// `γ_N h t2ᵀ(η × s + T_c,θ z)` per candidate.
    pub(super) rig_t2: &'b [f64],
    /// Whether every candidate's normal lies in the wheel's `(x, z)` plane.
    pub(super) planar: bool,
    pub(super) penalty: f64,
    /// [`TireContact`]'s weight of each contact node (half model: 1 on the mid-plane).
    pub(super) weight: &'b [f64],
    /// Whether this is the half model of symmetric motion.
    pub(super) half: bool,
    /// `[(T_c ż)_k, (T_c,θ z)_k]` of the free end-of-step state per candidate (the upwind
    /// `T_c,θ` of the spin direction of `Y_θ`; [`candidate_frames`]).
    pub(super) free_rates: &'b [[[f64; 3]; 2]],
    /// `Ω/γ_N h` (free spin over the velocity factor): the weight of `Y_θ` in the tangential
    /// rows, whose frames carry `γ_N h`.
    pub(super) transport: f64,
    pub(super) spin_free: f64,
}

/// The scaled frames and spin coefficients of the candidates for [`TireDelassus`];
/// returns whether every candidate's normal lies in the wheel's `(x, z)` plane.
/// (`(c1, c2)` = `(γ_N h, β_N h²)` scale the tangent and normal rows.) A change `ΔΩ` of the
/// spin moves a node's material velocity by `ΔΩ (η × s + T_c,θ z)` (Ribaric (7.10): the rigid
/// rotation and the transported deflection, `tct_theta` the upwind `T_c,θᵀ`, `z` the free
/// end-of-step coordinates); its tangential components are the coefficients. `free_rates`
/// receives each candidate's `[(T_c ż)ᵢ, (T_c,θ z)ᵢ]` (six dot products of length n_z in one
/// pass), which the free slip ([`TireDelassus`]) reads.
#[allow(clippy::too_many_arguments)]
pub(super) fn candidate_frames(
    red: &ReducedTire, cand: &[usize], gp: &[GroundPoint], (c1, c2): (f64, f64),
    (tct, tct_theta): (&Mat<f64>, &Mat<f64>), (z, zd): (&[f64], &[f64]),
    frames: &mut Vec<[[f64; 3]; 3]>, rig_t1: &mut Vec<f64>, rig_t2: &mut Vec<f64>,
    free_rates: &mut Vec<[[f64; 3]; 2]>,
) -> bool {
    frames.clear();
    rig_t1.clear();
    rig_t2.clear();
    free_rates.clear();
    let mut planar = true;
    for (k, &i) in cand.iter().enumerate() {
        let n = gp[k].normal;
        planar &= n[1] == 0.0;
        let (t1, t2) = tangents(&n);
        frames.push([
            [c2 * n[0], c2 * n[1], c2 * n[2]],
            [c1 * t1[0], c1 * t1[1], c1 * t1[2]],
            [c1 * t2[0], c1 * t2[1], c1 * t2[2]],
        ]);
        // η × s = (s_z, 0, −s_x) for the spin axis η = ŷ
        let s = red.contact_positions[i];
        let (tc, tt) = (
            |a| col_slice(tct, 3 * i + a),
            |a| col_slice(tct_theta, 3 * i + a),
        );
        let [vc, vt] = dots3x2([tc(0), tc(1), tc(2)], zd, [tt(0), tt(1), tt(2)], z);
        free_rates.push([vc, vt]);
        let a = [s[2] + vt[0], vt[1], -s[0] + vt[2]];
        rig_t1.push(c1 * dot3(&t1, &a));
        rig_t2.push(c1 * dot3(&t2, &a));
    }
    planar
}

/// The unit forces along `n = (n_x, 0, n_z)`, `t1 = (n_z, 0, −n_x)` and `ŷ` applied to the three
/// response columns `a`, `b`, `c` (unit forces along x, y, z) of one node: `n_x a + n_z c`,
/// `n_z a − n_x c`, `b` (the planar frame of [`tangents`]). Always inlined: as a closure it was
/// a call per candidate and direction (7 % of the full model's step instructions).
#[inline(always)]
fn along_planar(nx: f64, nz: f64, a: &[f64], b: &[f64], c: &[f64]) -> [[f64; 3]; 3] {
    [
        [
            nx * a[0] + nz * c[0],
            nx * a[1] + nz * c[1],
            nx * a[2] + nz * c[2],
        ],
        [
            nz * a[0] - nx * c[0],
            nz * a[1] - nx * c[1],
            nz * a[2] - nx * c[2],
        ],
        [b[0], b[1], b[2]],
    ]
}

impl TireDelassus<'_> {
    /// Unit force directions `[n, t1, t2]` of candidate `l`.
    fn directions(&self, l: usize) -> [[f64; 3]; 3] {
        let n = self.gp[l].normal;
        let (t1, t2) = tangents(&n);
        [n, t1, t2]
    }

    /// Local outputs of node `k` for a unit force `e` (wheel frame) on itself.
    fn response(&self, k: usize, e: &[f64; 3]) -> [f64; 3] {
        let (d, dt, x_theta) = (
            &self.blocks.diag[k],
            &self.blocks.diag_t[k],
            &self.blocks.x_theta[k],
        );
        let mut v = [0.0; 3];
        let mut vt = [0.0; 3];
        let mut xth = 0.0;
        for (r, er) in e.iter().enumerate() {
            for a in 0..3 {
                v[a] += er * d[r][a];
                vt[a] += er * dt[r][a];
            }
            xth += er * x_theta[r];
        }
        let f = &self.frames[k];
        let w = self.transport;
        // (tangential rows: the material velocity, the transport term added to it)
        let u = [v[0] + w * vt[0], v[1] + w * vt[1], v[2] + w * vt[2]];
        [
            dot3(&f[0], &v),
            dot3(&f[1], &u) + self.rig_t1[k] * xth,
            dot3(&f[2], &u) + self.rig_t2[k] * xth,
        ]
    }

    /// The diagonal compliances `[D_N,kk, (D_T,kk,11 + D_T,kk,22)/2]` of node `k`.
    pub(super) fn diagonal(&self, k: usize) -> [f64; 2] {
        let e = self.directions(k);
        let dn = self.response(k, &e[0])[0] + self.penalty;
        let d1 = self.response(k, &e[1])[1];
        let d2 = self.response(k, &e[2])[2] + self.lateral_compliance(k, d1);
        [dn, 0.5 * (d1 + d2)]
    }

    /// In the half model, a mid-plane node's lateral force moves nothing (an antisymmetric
    /// load: its rows of `T_c` are zero), so its Delassus row is zero and the force would be
    /// undetermined in stick; the symmetric solution has it zero. A compliance `d1` (the node's
    /// own longitudinal one) on its diagonal makes `u2 = d1 f2 = 0`, i.e. `f2 = 0`, without
    /// changing anything else. Zero for the other nodes.
    fn lateral_compliance(&self, k: usize, d1: f64) -> f64 {
        if self.half && self.weight[self.cand[k]] == 1.0 {
            d1
        } else {
            0.0
        }
    }
}

impl TireDelassus<'_> {
    /// [`DelassusSource::columns`] for any normals: the three `Y` columns of node `l`
    /// combined along its unit force directions `e` (`X_θ e` in `xth`), projected on each
    /// candidate's scaled frame, with the rigid spin terms of both tangents.
    fn columns_3d(&mut self, l: usize, e: &[[f64; 3]; 3], xth: &[f64; 3], cols: &mut [f64]) {
        let ld = 3 * self.cand.len();
        let w = self.transport;
        let yb = &self.blocks.y[3 * l * ld..(3 * l + 3) * ld];
        let tb = &self.blocks.yt[3 * l * ld..(3 * l + 3) * ld];
        // unit force e_c on node l: the displacement Y e_c and the transport Y_θ e_c at node k
        let combine = |blk: &[f64], k: usize, ec: &[f64; 3]| {
            let (a, b, c) = (
                &blk[3 * k..3 * k + 3],
                &blk[ld + 3 * k..ld + 3 * k + 3],
                &blk[2 * ld + 3 * k..2 * ld + 3 * k + 3],
            );
            [
                ec[0] * a[0] + ec[1] * b[0] + ec[2] * c[0],
                ec[0] * a[1] + ec[1] * b[1] + ec[2] * c[1],
                ec[0] * a[2] + ec[1] * b[2] + ec[2] * c[2],
            ]
        };
        for k in 0..self.cand.len() {
            let f = &self.frames[k];
            for (col, ec) in e.iter().enumerate() {
                let v = combine(yb, k, ec);
                let vt = combine(tb, k, ec);
                let u = [v[0] + w * vt[0], v[1] + w * vt[1], v[2] + w * vt[2]];
                let o = &mut cols[col * ld + 3 * k..col * ld + 3 * k + 3];
                o[0] = dot3(&f[0], &v);
                o[1] = dot3(&f[1], &u) + self.rig_t1[k] * xth[col];
                o[2] = dot3(&f[2], &u) + self.rig_t2[k] * xth[col];
            }
        }
        cols[3 * l] += self.penalty;
        let d1 = cols[ld + 3 * l + 1];
        cols[2 * ld + 3 * l + 2] += self.lateral_compliance(l, d1);
    }
}

impl DelassusSource for TireDelassus<'_> {
    fn columns(&mut self, l: usize, cols: &mut [f64]) {
        let ld = 3 * self.cand.len();
        let e = self.directions(l);
        self.blocks.gather(self.fac, l);
        // the three Y columns of node l (rows of the candidates) combined along the unit force
        // directions: Y e_c = Σ_r e_c[r] Y[:, 3j + r], and X_θ e_c
        let yb = &self.blocks.y[3 * l * ld..(3 * l + 3) * ld];
        let (y0, y1, y2) = (&yb[..ld], &yb[ld..2 * ld], &yb[2 * ld..]);
        let tb = &self.blocks.yt[3 * l * ld..(3 * l + 3) * ld];
        let (t0, t1, t2) = (&tb[..ld], &tb[ld..2 * ld], &tb[2 * ld..]);
        let w = self.transport;
        let x_theta = self.blocks.x_theta[l];
        let mut xth = [0.0; 3];
        for (c, ec) in e.iter().enumerate() {
            for (r, er) in ec.iter().enumerate() {
                xth[c] += er * x_theta[r];
            }
        }
        if !self.planar {
            self.columns_3d(l, &e, &xth, cols);
            return;
        }
        // planar ground (n_y = 0): n and t1 lie in the (x, z) plane, t2 = ŷ, so each frame
        // vector has two (n, t1) or one (t2) nonzero component
        let (nx, nz) = (e[0][0], e[0][2]);
        // (iterators over the candidates' triples: no bounds checks in the loop)
        let (c0, rest) = cols.split_at_mut(ld);
        let (c1, c2) = rest.split_at_mut(ld);
        let rows = y0
            .chunks_exact(3)
            .zip(y1.chunks_exact(3))
            .zip(y2.chunks_exact(3))
            .zip(self.frames.iter().zip(self.rig_t1.iter().zip(self.rig_t2)));
        let trows = t0
            .chunks_exact(3)
            .zip(t1.chunks_exact(3))
            .zip(t2.chunks_exact(3));
        let outs = c0
            .chunks_exact_mut(3)
            .zip(c1.chunks_exact_mut(3))
            .zip(c2.chunks_exact_mut(3));
        // unit force along n, t1 (combinations of columns 0 and 2) and ŷ (column 1)
        let along = |a: &[f64], b: &[f64], c: &[f64]| along_planar(nx, nz, a, b, c);
        for (((((a, b), c3), (f, (&rig, &rig2))), ((ta, tb), tc)), ((o0, o1), o2)) in
            rows.zip(trows).zip(outs)
        {
            let (fnx, fnz, ftx, ftz, fy) = (f[0][0], f[0][2], f[1][0], f[1][2], f[2][1]);
            let vs = along(a, b, c3);
            let vts = along(ta, tb, tc);
            for (((v, vt), o), xc) in vs.iter().zip(&vts).zip([o0, o1, o2]).zip(xth) {
                o[0] = fnx * v[0] + fnz * v[2];
                o[1] = ftx * (v[0] + w * vt[0]) + ftz * (v[2] + w * vt[2]) + rig * xc;
                o[2] = fy * (v[1] + w * vt[1]) + rig2 * xc;
            }
        }
        cols[3 * l] += self.penalty;
        let d1 = cols[ld + 3 * l + 1];
        cols[2 * ld + 3 * l + 2] += self.lateral_compliance(l, d1);
    }

    fn free_slip(&mut self, k: usize) -> [f64; 2] {
        let i = self.cand[k];
        let s = self.red.contact_positions[i];
        let sf = self.spin_free;
        let rig = [sf * s[2], 0.0, -sf * s[0]];
        let [vc, vt] = self.free_rates[k];
        let mut v = [0.0; 3];
        for (a, va) in v.iter_mut().enumerate() {
            *va = rig[a] + vc[a] + sf * vt[a] - self.gp[k].velocity[a];
        }
        let (t1, t2) = tangents(&self.gp[k].normal);
        [dot3(&t1, &v), dot3(&t2, &v)]
    }
}
