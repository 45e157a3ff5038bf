//! The contact-node responses of a factorisation of the iteration matrix ([`Responses`]) and
//! the copies of their blocks that the candidates' local Delassus matrix reads
//! ([`CandidateBlocks`]).

use faer::Mat;
use mbd_core::linalg::col_slice;

/// The contact-node responses of one factorisation of the iteration matrix.
pub(super) struct Responses {
    /// [`AlphaCorrection::factor_id`] of the factorisation.
    pub(super) id: usize,
    /// `X = S⁻¹ [0; T_cᵀ]`: response of `[θ̈; z̈]` to unit forces on the contact-node DOF
    /// (n × 3 n_c).
    pub(super) x: Mat<f64>,
    /// `Y = T_c X_z`: contact-node displacement response (3 n_c × 3 n_c, columns of node j at
    /// 3j..3j+3).
    pub(super) y: Mat<f64>,
    /// `Y_θ = T_c,θ X_z` with the upwind rows of the spin direction `dir`
    /// ([`crate::ReducedTire::tc_theta_upwind`]): the response of the transported deflection
    /// `T_c,θ z` in the slip velocity (3 n_c × 3 n_c).
    pub(super) yt: Mat<f64>,
    /// The direction (`0`: spin ≥ 0, `1`: spin < 0) `yt` belongs to.
    pub(super) dir: usize,
}

/// The blocks of the cached responses that the local Delassus matrix of the candidates reads
/// ([`TireDelassus`]), gathered once per candidate set and factorisation instead of once per
/// step: `Y` and `Y_θ` of candidate `l`'s three unit forces at every candidate `k` (3m × 3m,
/// column `3l + r`, rows `3k..3k+3`) and `X_θ` (row 0 of `X`). The values are copies, so the
/// matrix is the same as gathered from `Y`, `Y_θ` directly.
#[derive(Default)]
pub(super) struct CandidateBlocks {
    /// [`AlphaCorrection::factor_id`], the spin direction of `Y_θ` and the candidates the
    /// blocks belong to.
    pub(super) id: usize,
    pub(super) dir: usize,
    pub(super) cand: Vec<usize>,
    /// Whether the columns of candidate `l` are gathered.
    pub(super) have: Vec<bool>,
    pub(super) y: Vec<f64>,
    pub(super) yt: Vec<f64>,
    /// Per candidate (all gathered at once): `X_θ` of its three unit forces and its own blocks
    /// of `Y` and `Y_θ` (`diag[k][r][a]` = row `a`, unit force `r`).
    pub(super) x_theta: Vec<[f64; 3]>,
    pub(super) diag: Vec<[[f64; 3]; 3]>,
    pub(super) diag_t: Vec<[[f64; 3]; 3]>,
}

impl CandidateBlocks {
    /// Keeps the blocks if `cand` and `id` are those they were gathered for, else starts
    /// empty for them.
    pub(super) fn prepare(&mut self, fac: &Responses, cand: &[usize]) {
        if self.id == fac.id && self.dir == fac.dir && self.cand == cand {
            return;
        }
        let m = cand.len();
        self.id = fac.id;
        self.dir = fac.dir;
        self.cand.clear();
        self.cand.extend_from_slice(cand);
        self.have.clear();
        self.have.resize(m, false);
        self.y.resize(9 * m * m, 0.0);
        self.yt.resize(9 * m * m, 0.0);
        self.x_theta.clear();
        self.diag.clear();
        self.diag_t.clear();
        for &i in cand {
            let mut xth = [0.0; 3];
            let mut d = [[0.0; 3]; 3];
            let mut dt = [[0.0; 3]; 3];
            for r in 0..3 {
                xth[r] = fac.x[(0, 3 * i + r)];
                d[r].copy_from_slice(&col_slice(&fac.y, 3 * i + r)[3 * i..3 * i + 3]);
                dt[r].copy_from_slice(&col_slice(&fac.yt, 3 * i + r)[3 * i..3 * i + 3]);
            }
            self.x_theta.push(xth);
            self.diag.push(d);
            self.diag_t.push(dt);
        }
    }

    /// Gathers the columns of candidate `l` from `fac` if not yet done.
    pub(super) fn gather(&mut self, fac: &Responses, l: usize) {
        if self.have[l] {
            return;
        }
        let ld = 3 * self.cand.len();
        let j = self.cand[l];
        for (src, dst) in [(&fac.y, &mut self.y), (&fac.yt, &mut self.yt)] {
            for r in 0..3 {
                let col = col_slice(src, 3 * j + r);
                let out = &mut dst[(3 * l + r) * ld..(3 * l + r + 1) * ld];
                for (k, &i) in self.cand.iter().enumerate() {
                    out[3 * k..3 * k + 3].copy_from_slice(&col[3 * i..3 * i + 3]);
                }
            }
        }
        self.have[l] = true;
    }
}
