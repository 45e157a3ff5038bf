//! Banded LU with a dense border for the small, chain-like Newton matrices of node-based
//! models (the closed ANCF belt: a cyclic block-tridiagonal matrix plus the free pulleys'
//! rows and columns, which couple to every belt element that may touch them).
//!
//! The pattern is reordered once ([`BandPlan::new`]): vertices of the symmetrised pattern
//! graph with many more neighbours than the average (pulley angles, multipliers of global
//! constraints) form a *border* ordered last; the rest is numbered by reverse Cuthill–McKee
//! (George & Liu, *Computer Solution of Large Sparse Positive Definite Systems*, 1981, §4.3,
//! from a pseudo-peripheral vertex), which turns a closed chain into a band of about two
//! levels. The numeric factorisation of the permuted matrix `[A₁₁ A₁₂; A₂₁ A₂₂]` is
//!
//! ```text
//!   A₁₁ = P L U                 banded LU with partial pivoting (LAPACK dgbtf2; Golub & Van Loan,
//!                               Matrix Computations, 4th ed., §4.3.5): U gets bandwidth kl + ku
//!   X   = A₁₁⁻¹ A₁₂             one banded solve per border column
//!   S   = A₂₂ − A₂₁ X           dense Schur complement, LU with partial pivoting
//! ```
//!
//! and a solve is `y₁ = A₁₁⁻¹ b₁`, `x₂ = S⁻¹ (b₂ − A₂₁ y₁)`, `x₁ = y₁ − X x₂`. Pivoting is
//! confined to the band and to the Schur complement: a zero pivot of `A₁₁` is reported as
//! singular (the caller then falls back to the general sparse LU).
//!
//! faer (0.24) has no banded factorisation; the kernels here are the textbook column
//! algorithms with contiguous inner loops.

/// Reordering and band sizes of one pattern (built once per pattern).
#[derive(Debug, Clone)]
pub(crate) struct BandPlan {
    /// `perm[new] = old`.
    perm: Vec<usize>,
    /// `inv[old] = new`.
    inv: Vec<usize>,
    /// Size of the banded part (the border is `n1..dim`).
    n1: usize,
    /// Lower and upper bandwidth of the permuted `A₁₁`.
    kl: usize,
    ku: usize,
}

/// A border vertex has more than this many times the average number of neighbours \[-\].
const BORDER_DEGREE_FACTOR: f64 = 4.0;
/// At most this fraction of the vertices may form the border \[-\].
const BORDER_MAX_FRACTION: f64 = 1.0 / 16.0;

impl BandPlan {
    /// The plan for the `dim × dim` pattern given column-wise (`col_ptr`, `row_idx`; the
    /// diagonal need not be stored).
    #[cfg(test)]
    pub(crate) fn new(dim: usize, col_ptr: &[usize], row_idx: &[usize]) -> Self {
        let mut plans = Self::candidates(dim, col_ptr, row_idx);
        plans.swap_remove(0)
    }

    /// The plans for the `dim × dim` pattern given column-wise (`col_ptr`, `row_idx`; the
    /// diagonal need not be stored), cheapest first: the border of highly coupled vertices
    /// alone, and that border plus one supervariable that cuts a closed chain (when it is
    /// allowed). Never empty. The later plans serve when the first one's pivoting, confined to
    /// its band, fails the backward-error check ([`BandLu::backward_error`]).
    pub(crate) fn candidates(dim: usize, col_ptr: &[usize], row_idx: &[usize]) -> Vec<Self> {
        // symmetrised adjacency without the diagonal
        let mut adj: Vec<Vec<usize>> = vec![Vec::new(); dim];
        for j in 0..dim {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                if i != j {
                    adj[i].push(j);
                    adj[j].push(i);
                }
            }
        }
        for a in &mut adj {
            a.sort_unstable();
            a.dedup();
        }
        let total: usize = adj.iter().map(Vec::len).sum();
        let mean = total as f64 / dim.max(1) as f64;
        let mut border: Vec<usize> = (0..dim)
            .filter(|&v| adj[v].len() as f64 > BORDER_DEGREE_FACTOR * mean)
            .collect();
        if border.len() as f64 > BORDER_MAX_FRACTION * dim as f64 {
            border.clear();
        }
        let plan = Self::with_border(dim, col_ptr, row_idx, &adj, &border);
        // A closed chain (a belt loop) numbered from one vertex has levels on both sides of
        // it, i.e. a band of two levels; moving the start vertex's supervariable (the
        // vertices with its closed neighbourhood: the coordinates of one node) to the border
        // cuts the loop into an open chain with half the band. Tried first when cheaper; on
        // the plate belt's Newton matrix it solved to a residual of 24 against a right-hand
        // side of 0.5 (faer's LU and the plan without the cut: 1e-12; issue 37), so both plans
        // are kept and the solver checks. (On the ANCF FEAD belt the same rejections, 2e-8 to
        // 3e-6 backward error, were the Schur complement's solve interleaving its row swaps,
        // fixed in `dense_solve` 2026-12-06: both plans then give 1e-16 there. Whether the
        // plate belt's residual had the same cause was not re-checked.)
        let Some(&root) = plan.perm[..plan.n1].last() else {
            return vec![plan];
        };
        let closed = |v: usize| {
            let mut c = adj[v].clone();
            c.push(v);
            c.sort_unstable();
            c
        };
        let root_closed = closed(root);
        let mut cut = border.clone();
        cut.extend(
            root_closed
                .iter()
                .copied()
                .filter(|&w| !border.contains(&w) && closed(w) == root_closed),
        );
        if cut.len() as f64 > BORDER_MAX_FRACTION * dim as f64 {
            return vec![plan];
        }
        let other = Self::with_border(dim, col_ptr, row_idx, &adj, &cut);
        let mut plans = vec![plan, other];
        plans.sort_by(|a, b| a.cost().total_cmp(&b.cost()));
        plans
    }

    /// Reverse Cuthill–McKee numbering of the vertices outside `border`, then `border`.
    fn with_border(
        dim: usize, col_ptr: &[usize], row_idx: &[usize], adj: &[Vec<usize>], border: &[usize],
    ) -> Self {
        let mut is_border = vec![false; dim];
        for &b in border {
            is_border[b] = true;
        }
        let degree = |v: usize, adj: &[Vec<usize>], is_border: &[bool]| {
            adj[v].iter().filter(|&&w| !is_border[w]).count()
        };
        // Cuthill–McKee over every component of the non-border graph
        let mut order: Vec<usize> = Vec::with_capacity(dim);
        let mut seen = is_border.clone();
        let mut level_of = vec![usize::MAX; dim];
        for root0 in 0..dim {
            if seen[root0] {
                continue;
            }
            // pseudo-peripheral start: repeat BFS from a minimum-degree vertex of the last level
            let mut root = root0;
            let mut ecc = 0;
            for _ in 0..8 {
                let (reached, last, depth) = bfs_levels(root, adj, &is_border, &mut level_of);
                for &v in &reached {
                    level_of[v] = usize::MAX;
                }
                if depth <= ecc && ecc > 0 {
                    break;
                }
                ecc = depth;
                root = last
                    .iter()
                    .copied()
                    .min_by_key(|&v| degree(v, adj, &is_border))
                    .unwrap_or(root);
            }
            let start = order.len();
            order.push(root);
            seen[root] = true;
            let mut head = start;
            let mut nb: Vec<usize> = Vec::new();
            while head < order.len() {
                let v = order[head];
                head += 1;
                nb.clear();
                nb.extend(adj[v].iter().copied().filter(|&w| !seen[w]));
                nb.sort_by_key(|&w| degree(w, adj, &is_border));
                for &w in &nb {
                    seen[w] = true;
                    order.push(w);
                }
            }
            order[start..].reverse();
        }
        let n1 = order.len();
        order.extend(border.iter().copied());
        let mut inv = vec![0; dim];
        for (new, &old) in order.iter().enumerate() {
            inv[old] = new;
        }
        let (mut kl, mut ku) = (0, 0);
        for j in 0..dim {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                let (pi, pj) = (inv[i], inv[j]);
                if pi < n1 && pj < n1 {
                    if pi > pj {
                        kl = kl.max(pi - pj);
                    } else {
                        ku = ku.max(pj - pi);
                    }
                }
            }
        }
        Self {
            perm: order,
            inv,
            n1,
            kl,
            ku,
        }
    }

    /// Estimated multiply–adds of one factorisation plus ten solves (the frozen Newton
    /// matrix of a time step is solved several times per factorisation).
    fn cost(&self) -> f64 {
        let (n1, nb) = (self.n1 as f64, self.border() as f64);
        let (kl, ku) = (self.kl as f64, self.ku as f64);
        let factor = n1 * kl * (kl + ku + 1.0)
            + nb * n1 * (3.0 * kl + 2.0 * ku + 1.0)
            + nb * nb * n1
            + nb.powi(3) / 3.0;
        let solve = n1 * (2.0 * kl + ku + 1.0) + 2.0 * nb * n1 + nb * nb;
        factor + 10.0 * solve
    }

    /// Number of border vertices.
    pub(crate) fn border(&self) -> usize {
        self.perm.len() - self.n1
    }

    /// Lower and upper bandwidth of the banded part.
    pub(crate) fn bandwidths(&self) -> (usize, usize) {
        (self.kl, self.ku)
    }
}

/// Vertices reached from `root` in breadth-first order (non-border only), the vertices of the
/// last level and its depth; `level_of` receives the levels (the caller resets it).
fn bfs_levels(
    root: usize, adj: &[Vec<usize>], is_border: &[bool], level_of: &mut [usize],
) -> (Vec<usize>, Vec<usize>, usize) {
    let mut out = vec![root];
    level_of[root] = 0;
    let mut head = 0;
    while head < out.len() {
        let v = out[head];
        head += 1;
        for &w in &adj[v] {
            if !is_border[w] && level_of[w] == usize::MAX {
                level_of[w] = level_of[v] + 1;
                out.push(w);
            }
        }
    }
    let last_level = out.last().map_or(0, |&v| level_of[v]);
    let last = out
        .iter()
        .copied()
        .filter(|&v| level_of[v] == last_level)
        .collect();
    (out, last, last_level)
}

/// The numeric banded-plus-border LU of one matrix.
#[derive(Debug, Clone)]
pub(crate) struct BandLu {
    plan: BandPlan,
    /// Band storage of `L` and `U` (LAPACK `ab`, leading dimension `2 kl + ku + 1`,
    /// column-major): `A₁₁(i, j)` at `ab[kl + ku + i − j + j·ld]`.
    ab: Vec<f64>,
    ld: usize,
    ipiv: Vec<usize>,
    /// `1 / U(j, j)` (a solve multiplies instead of dividing on its serial path).
    u_inv: Vec<f64>,
    /// `A₁₂`, overwritten by `X = A₁₁⁻¹ A₁₂` (`n1 × nb`, row-major: the `nb` border columns
    /// of one row side by side, so that one banded solve serves them all, [`Band::solve_rows`]).
    x: Vec<f64>,
    /// `A₂₁` (`nb × n1`, column-major).
    a21: Vec<f64>,
    /// `A₂₂`, overwritten by the LU of the Schur complement (`nb × nb`, column-major).
    s: Vec<f64>,
    s_piv: Vec<usize>,
    /// `A₂₁ X` (`nb × nb`, column-major) before it is subtracted from `A₂₂`.
    acc: Vec<f64>,
    /// Scratch of [`BandLu::backward_error`]: test solution, right-hand side, permuted work.
    check: [Vec<f64>; 3],
    /// Where each stored entry of the plan's pattern goes ([`BandScatter`]), built at the first
    /// factorisation.
    scatter: Option<BandScatter>,
    /// The scatter composed with a block's map into the pattern ([`BandLu::load_shared`]),
    /// built at its first use.
    direct: Option<DirectScatter>,
    /// Element growth of the current factors ([`Growth`]).
    growth: Growth,
    /// The last factorisation whose backward error was measured and accepted, and how many
    /// factorisations have taken its verdict since ([`BandLu::check_needed`]).
    verified: Option<Verified>,
}

/// Element growth of one factorisation, the factor `ρ` of Gaussian elimination's backward
/// error bound `|ΔA| ≤ γ_n |L̂||Û|` with `|l| ≤ 1` under partial pivoting (Higham, *Accuracy
/// and Stability of Numerical Algorithms*, 2nd ed., Thm 9.3 and §9.4; for the block
/// elimination of the border, Thm 13.6: `‖ΔA‖ ≤ c u (‖A‖ + ‖L̂‖‖Û‖)` with the block factors
/// `A₂₁A₁₁⁻¹`, `A₁₁⁻¹A₁₂` and `S`): `max |U| / max |A|` over the banded part `A₁₁` (the
/// entries of `U` in its band storage) and over the border's Schur complement `S` (its dense
/// LU), and `max |X|` of the border's columns `X = A₁₁⁻¹A₁₂` (in the units of `A₁₂/A₁₁`,
/// compared only with another factorisation of the same pattern).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Growth {
    band: f64,
    schur: f64,
    border: f64,
}

impl Growth {
    /// Whether every part grew at most `ratio` times that of `reference` (false for NaN).
    fn within(&self, reference: &Growth, ratio: f64) -> bool {
        self.band <= ratio * reference.band
            && self.schur <= ratio * reference.schur
            && self.border <= ratio * reference.border
    }
}

/// A factorisation whose backward error passed [`BandLu::backward_error`]: its growth and the
/// number of later factorisations that took its verdict.
#[derive(Debug, Clone, Copy)]
struct Verified {
    growth: Growth,
    reused: usize,
}

/// A factorisation takes the verdict of the last verified one ([`BandLu::check_needed`]) when
/// its growth is at most this multiple of that one's in every part \[-\].
const VERDICT_GROWTH_RATIO: f64 = 2.0;

/// At most this many factorisations in a row take a verified factorisation's verdict; the
/// next one is measured again ([`BandLu::check_needed`]) \[-\].
pub(crate) const VERDICT_REUSE_LIMIT: usize = 16;

/// The destinations of the stored entries of one pattern in the storage of [`BandLu`]: per
/// block of the permuted matrix (`A₁₁` in band storage, `A₁₂`, `A₂₁`, `A₂₂`) the pairs
/// `(position in the values, position in the block's array)`, in the pattern's column-major
/// order. Built once per pattern, so that a factorisation scatters its values without the
/// permutation look-ups and the block test of every entry.
#[derive(Debug, Clone)]
struct BandScatter {
    /// Length of the `col_ptr` and `row_idx` the map was built for.
    shape: (usize, usize),
    ab: Vec<(usize, usize)>,
    x: Vec<(usize, usize)>,
    a21: Vec<(usize, usize)>,
    s: Vec<(usize, usize)>,
}

impl BandScatter {
    /// The destinations of a block's entries whose positions in the pattern (of `nnz`
    /// entries) are `map` ([`DirectScatter`]); `None` unless `map` names distinct entries of
    /// the pattern.
    fn compose(&self, nnz: usize, map: &[usize]) -> Option<DirectScatter> {
        // where each of the pattern's entries goes: (array, slot)
        let mut dest = vec![(usize::MAX, 0); nnz];
        for (a, pairs) in [&self.ab, &self.x, &self.a21, &self.s]
            .into_iter()
            .enumerate()
        {
            for &(k, p) in pairs {
                dest[k] = (a, p);
            }
        }
        let mut lists: [Vec<(usize, usize)>; 4] = Default::default();
        let mut seen = vec![false; nnz];
        for (k, &u) in map.iter().enumerate() {
            let (a, p) = *dest.get(u)?;
            if a >= lists.len() || std::mem::replace(&mut seen[u], true) {
                return None;
            }
            lists[a].push((k, p));
        }
        let [ab, x, a21, s] = lists;
        Some(DirectScatter {
            shape: (nnz, map.len()),
            ab,
            x,
            a21,
            s,
        })
    }
}

/// [`BandScatter`] composed with the map of a block into the pattern: per array of
/// [`BandLu`] the pairs `(entry of the block, slot)` ([`BandLu::load_shared`]).
#[derive(Debug, Clone)]
struct DirectScatter {
    /// Entries of the pattern and of the block the map was built for.
    shape: (usize, usize),
    ab: Vec<(usize, usize)>,
    x: Vec<(usize, usize)>,
    a21: Vec<(usize, usize)>,
    s: Vec<(usize, usize)>,
}

/// The band widths the kernels are compiled for with constant lengths ([`sub_scaled`]): the
/// lower and upper bandwidth 11 of the planar ANCF belt's cut-loop plan (6 coordinates a node,
/// an element couples two nodes: `2·6 − 1`), and 12 border columns (the cut node's 6
/// coordinates and the default FEAD drive's five free pulleys and tensioner arm). Any other
/// width takes the run-time-length loops, with the same bits.
const SPECIALISED_KL: usize = 11;
/// See [`SPECIALISED_KL`].
const SPECIALISED_BORDER: usize = 12;

/// `t[i] −= u · l[i]` along `t` (as long as `l`); with `t` exactly `W` long (`W > 0`) the loop
/// has a constant length, which the compiler unrolls into whole vectors and a fixed remainder:
/// the same operations on every entry (the same bits), without the loop overhead of a short
/// run-time length (the band's `kl` = 11 of the planar ANCF belts, the border's 12 columns of
/// the FEAD drive).
#[inline(always)]
fn sub_scaled<const W: usize>(t: &mut [f64], l: &[f64], u: f64) {
    if W > 0
        && let (Ok(t), Ok(l)) = (<&mut [f64; W]>::try_from(&mut *t), <&[f64; W]>::try_from(l))
    {
        for i in 0..W {
            t[i] -= u * l[i];
        }
        return;
    }
    for (t, li) in t.iter_mut().zip(l) {
        *t -= u * li;
    }
}

/// [`dgbtf2`] as a [`crate::simd::Kernel`], with the constant lower bandwidth `KL` (0: any,
/// [`sub_scaled`]).
struct Dgbtf2<'a, const KL: usize> {
    ab: &'a mut [f64],
    ipiv: &'a mut [usize],
    n1: usize,
    kl: usize,
    ku: usize,
    ld: usize,
}

impl<const KL: usize> crate::simd::Kernel for Dgbtf2<'_, KL> {
    type Output = Result<(), BandError>;
    #[inline(always)]
    fn run(self) -> Self::Output {
        dgbtf2::<KL>(self.ab, self.ipiv, self.n1, self.kl, self.ku, self.ld)
    }
}

/// LAPACK dgbtf2 on the band storage `ab` (leading dimension `ld`, bandwidths `kl`, `ku`) of
/// an `n1 × n1` matrix: column `j` pivots among rows `j..=j + kl`, `U` fills up to column `ju`.
/// With `KL > 0` (equal to `kl`) the updates of whole columns run on constant lengths
/// ([`sub_scaled`], the same bits).
#[inline(always)]
fn dgbtf2<const KL: usize>(
    ab: &mut [f64], ipiv: &mut [usize], n1: usize, kl: usize, ku: usize, ld: usize,
) -> Result<(), BandError> {
    let kv = kl + ku;
    let mut ju = 0usize;
    for j in 0..n1 {
        let km = kl.min(n1 - 1 - j);
        let col = kv + j * ld;
        let mut jp = 0;
        let mut best = ab[col].abs();
        for i in 1..=km {
            let a = ab[col + i].abs();
            if a > best {
                best = a;
                jp = i;
            }
        }
        ipiv[j] = j + jp;
        if best == 0.0 || !best.is_finite() {
            return Err(BandError::ZeroPivot(j));
        }
        ju = ju.max((j + ku + jp).min(n1 - 1));
        if jp != 0 {
            // swap rows j and j + jp in columns j..=ju
            for c in j..=ju {
                let base = kv + c * ld;
                ab.swap(base + j - c, base + j + jp - c);
            }
        }
        if km > 0 {
            let inv = 1.0 / ab[col];
            for i in 1..=km {
                ab[col + i] *= inv;
            }
            for c in j + 1..=ju {
                // column j (multipliers) lies before column c in the storage
                let (lo, hi) = ab.split_at_mut(c * ld);
                let l = &lo[col + 1..=col + km];
                let top = kv + j - c;
                let ujc = hi[top];
                if ujc != 0.0 {
                    sub_scaled::<KL>(&mut hi[top + 1..=top + km], l, ujc);
                }
            }
        }
    }
    Ok(())
}

/// Why a banded factorisation failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum BandError {
    /// Zero pivot in column `usize` of the permuted matrix (band part or border).
    ZeroPivot(usize),
}

impl BandLu {
    pub(crate) fn new(plan: BandPlan) -> Self {
        let n1 = plan.n1;
        let nb = plan.border();
        let ld = 2 * plan.kl + plan.ku + 1;
        Self {
            ab: vec![0.0; ld * n1],
            ld,
            ipiv: vec![0; n1],
            u_inv: vec![0.0; n1],
            x: vec![0.0; n1 * nb],
            a21: vec![0.0; nb * n1],
            s: vec![0.0; nb * nb],
            s_piv: vec![0; nb],
            acc: vec![0.0; nb * nb],
            check: [vec![0.0; n1 + nb], vec![0.0; n1 + nb], vec![0.0; n1 + nb]],
            scatter: None,
            direct: None,
            growth: Growth::default(),
            verified: None,
            plan,
        }
    }

    /// The destinations of the entries of the pattern (`col_ptr`, `row_idx`) in the arrays
    /// `ab`, `x`, `a21` and `s` ([`BandScatter`]): the block test and index of the loop that
    /// scattered every entry before (kept as [`BandLu::scatter_reference`] in the tests).
    fn scatter_map(&self, col_ptr: &[usize], row_idx: &[usize]) -> BandScatter {
        let (n1, kl, ku, ld) = (self.plan.n1, self.plan.kl, self.plan.ku, self.ld);
        let nb = self.plan.border();
        let kv = kl + ku;
        let mut m = BandScatter {
            shape: (col_ptr.len(), row_idx.len()),
            ab: Vec::new(),
            x: Vec::new(),
            a21: Vec::new(),
            s: Vec::new(),
        };
        for j in 0..n1 + nb {
            let pj = self.plan.inv[j];
            for k in col_ptr[j]..col_ptr[j + 1] {
                let pi = self.plan.inv[row_idx[k]];
                match (pi < n1, pj < n1) {
                    (true, true) => m.ab.push((k, kv + pi - pj + pj * ld)),
                    (true, false) => m.x.push((k, pi * nb + (pj - n1))),
                    (false, true) => m.a21.push((k, (pi - n1) + pj * nb)),
                    (false, false) => m.s.push((k, (pi - n1) + (pj - n1) * nb)),
                }
            }
        }
        m
    }

    /// Factors the matrix with the plan's pattern whose values are `vals` (same column-wise
    /// storage as given to [`BandPlan::new`]).
    #[cfg(test)]
    pub(crate) fn factor(
        &mut self, col_ptr: &[usize], row_idx: &[usize], vals: &[f64],
    ) -> Result<(), BandError> {
        self.load(col_ptr, row_idx, vals);
        self.factor_loaded()
    }

    /// Fills the band, border and Schur arrays with the matrix of the plan's pattern whose
    /// values are `vals` (zero where the pattern has no entry).
    pub(crate) fn load(&mut self, col_ptr: &[usize], row_idx: &[usize], vals: &[f64]) {
        self.clear();
        // every slot receives at most one entry (the pattern's entries are distinct), so the
        // order of the scatter does not change a bit
        self.ensure_scatter(col_ptr, row_idx);
        if let Some(m) = &self.scatter {
            for (dst, map) in [
                (&mut self.ab, &m.ab),
                (&mut self.x, &m.x),
                (&mut self.a21, &m.a21),
                (&mut self.s, &m.s),
            ] {
                for &(k, p) in map {
                    dst[p] += vals[k];
                }
            }
        }
    }

    /// [`BandLu::load`] of the sum `Σ sᵢ vᵢ` of blocks that share one pattern, straight from
    /// the blocks: `terms` are the scales `sᵢ` and the blocks' stored values `vᵢ`, `map[k]` the
    /// position of a block's entry `k` in the plan's pattern (`col_ptr`, `row_idx`), which may
    /// hold more entries (those stay zero). Each slot gets `0 + ((0 + s₀v₀) + s₁v₁) + …`, the
    /// operations of the sum into the pattern's values followed by [`BandLu::load`], so the
    /// same bits without the pattern-sized array between. `Some(false)` when a value is not
    /// finite, `None` (nothing loaded) unless `map` names distinct entries of the pattern.
    pub(crate) fn load_shared(
        &mut self, col_ptr: &[usize], row_idx: &[usize], terms: &[(f64, &[f64])], map: &[usize],
    ) -> Option<bool> {
        self.clear();
        self.ensure_scatter(col_ptr, row_idx);
        if self
            .direct
            .as_ref()
            .is_none_or(|d| d.shape != (row_idx.len(), map.len()))
        {
            self.direct = self
                .scatter
                .as_ref()
                .and_then(|m| m.compose(row_idx.len(), map));
        }
        let d = self.direct.as_ref()?;
        // every slot receives at most one sum (the map names distinct entries, the scatter
        // distinct slots) onto the cleared zero, so the arrays are finite exactly when every
        // sum is: checked on the sums instead of over the arrays afterwards
        let mut finite = true;
        for (dst, pairs) in [
            (&mut self.ab, &d.ab),
            (&mut self.x, &d.x),
            (&mut self.a21, &d.a21),
            (&mut self.s, &d.s),
        ] {
            match *terms {
                [(s0, v0), (s1, v1), (s2, v2)] => {
                    for &(k, p) in pairs {
                        let mut a = 0.0;
                        a += s0 * v0[k];
                        a += s1 * v1[k];
                        a += s2 * v2[k];
                        finite &= a.is_finite();
                        dst[p] += a;
                    }
                }
                _ => {
                    for &(k, p) in pairs {
                        let mut a = 0.0;
                        for (s, v) in terms {
                            a += s * v[k];
                        }
                        finite &= a.is_finite();
                        dst[p] += a;
                    }
                }
            }
        }
        Some(finite)
    }

    /// Zeroes the band, border and Schur arrays.
    fn clear(&mut self) {
        self.ab.fill(0.0);
        self.x.fill(0.0);
        self.a21.fill(0.0);
        self.s.fill(0.0);
    }

    /// Builds the [`BandScatter`] of the pattern unless the one at hand fits it.
    fn ensure_scatter(&mut self, col_ptr: &[usize], row_idx: &[usize]) {
        if self
            .scatter
            .as_ref()
            .is_none_or(|m| m.shape != (col_ptr.len(), row_idx.len()))
        {
            self.scatter = Some(self.scatter_map(col_ptr, row_idx));
            self.direct = None;
        }
    }

    /// Factors the matrix put in place by [`BandLu::load`] or [`BandLu::load_shared`].
    pub(crate) fn factor_loaded(&mut self) -> Result<(), BandError> {
        let (n1, kl, ku, ld) = (self.plan.n1, self.plan.kl, self.plan.ku, self.ld);
        let nb = self.plan.border();
        let kv = kl + ku;
        let a_max = max_abs(&self.ab);
        // dgbtf2: column j, pivot among rows j..=j+km, U fill up to column ju (compiled for the
        // machine's vector width: `crate::simd`, the same bits)
        let (ab, ipiv) = (&mut self.ab, &mut self.ipiv);
        match kl {
            SPECIALISED_KL => crate::simd::dispatch(Dgbtf2::<SPECIALISED_KL> {
                ab,
                ipiv,
                n1,
                kl,
                ku,
                ld,
            }),
            _ => crate::simd::dispatch(Dgbtf2::<0> {
                ab,
                ipiv,
                n1,
                kl,
                ku,
                ld,
            }),
        }?;
        for (j, u) in self.u_inv.iter_mut().enumerate() {
            *u = 1.0 / self.ab[kv + j * ld];
        }
        // U occupies the rows 0..=kv of every column of the band storage
        let u_max = self
            .ab
            .chunks_exact(ld)
            .fold(0.0f64, |m, col| m.max(max_abs(&col[..=kv])));
        self.growth.band = growth(u_max, a_max);
        // X = A11^-1 A12 (all border columns in one pass over the band), Schur complement
        // S = A22 - A21 X and its LU
        if nb > 0 {
            let mut x = std::mem::take(&mut self.x);
            self.band().solve_rows(&mut x, nb);
            self.x = x;
            self.growth.border = max_abs(&self.x);
            let mut acc = std::mem::take(&mut self.acc);
            crate::simd::dispatch(SchurProduct {
                a21: &self.a21,
                x: &self.x,
                acc: &mut acc,
                nb,
            });
            for (s, a) in self.s.iter_mut().zip(&acc) {
                *s -= a;
            }
            self.acc = acc;
        }
        let s_max = max_abs(&self.s);
        dense_lu(&mut self.s, nb, &mut self.s_piv).map_err(|c| BandError::ZeroPivot(n1 + c))?;
        let su_max = (0..nb).fold(0.0f64, |m, c| m.max(max_abs(&self.s[c * nb..=c + c * nb])));
        self.growth.schur = growth(su_max, s_max);
        Ok(())
    }

    /// Whether the factors just made need their backward error measured
    /// ([`BandLu::backward_error`]) before they are used: yes unless the last verified
    /// factorisation ([`BandLu::verdict`] after a passed check) is at most
    /// [`VERDICT_REUSE_LIMIT`] factorisations old and this one's element growth ([`Growth`])
    /// is at most [`VERDICT_GROWTH_RATIO`] times that one's in every part.
    ///
    /// Why: the check guards against pivoting confined to the band (and the border's Schur
    /// complement) that lacks the rows it needs, which shows as element growth: the backward
    /// error bound of the elimination is proportional to `ρ` (Higham Thm 9.3; the band's rows
    /// have at most `kl + ku + 1` entries of `U` and `kl + 1` of `L`, so
    /// `‖|L̂||Û|‖∞ ≤ (kl + 1)(kl + ku + 1) ρ max|A|`), so factors whose growth stays within a
    /// factor of two of a measured one's have a bound within a factor of two of its bound.
    /// It is a bound, not the measured error, so the measurement is repeated at least every
    /// [`VERDICT_REUSE_LIMIT`] + 1 factorisations. The pivot rows themselves change from one
    /// Newton matrix to the next (the FEAD belt: 5–20 of about 380 pivoted rows of 478) at a
    /// growth of 1.00–1.16.
    pub(crate) fn check_needed(&self) -> bool {
        self.verified.is_none_or(|v| {
            v.reused >= VERDICT_REUSE_LIMIT || !self.growth.within(&v.growth, VERDICT_GROWTH_RATIO)
        })
    }

    /// Records the verdict on the factors just made: `measured` after a backward error within
    /// the limit (they become the verified factorisation), else taken from the verified one
    /// ([`BandLu::check_needed`] was `false`).
    pub(crate) fn verdict(&mut self, measured: bool) {
        if measured {
            self.verified = Some(Verified {
                growth: self.growth,
                reused: 0,
            });
        } else if let Some(v) = &mut self.verified {
            v.reused += 1;
        }
    }

    /// Normwise relative backward error of one solve with the current factors (Rigal &
    /// Gaches 1967; Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., Thm 7.1):
    /// `‖A x̂ − b‖∞ / (‖A‖∞ ‖x̂‖∞ + ‖b‖∞)` for `b = A x` with a fixed test vector `x` of
    /// entries in \[1, 2\). A backward-stable LU gives a small multiple of the unit roundoff;
    /// pivoting confined to a band that lacks the rows it needs gives orders more. `vals` are
    /// the values just factored, in the pattern `(col_ptr, row_idx)`.
    pub(crate) fn backward_error(
        &mut self, col_ptr: &[usize], row_idx: &[usize], vals: &[f64],
    ) -> f64 {
        let [mut x, mut b, mut w] = std::mem::take(&mut self.check);
        let dim = x.len();
        for (i, xi) in x.iter_mut().enumerate() {
            *xi = 1.0 + ((i * 7) % 11) as f64 / 11.0;
        }
        // b = A x and the row sums of |A| (in w)
        b.fill(0.0);
        w.fill(0.0);
        for j in 0..dim {
            for k in col_ptr[j]..col_ptr[j + 1] {
                let i = row_idx[k];
                b[i] += vals[k] * x[j];
                w[i] += vals[k].abs();
            }
        }
        let a_norm = w.iter().fold(0.0f64, |m, v| m.max(*v));
        let b_norm = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        x.copy_from_slice(&b);
        self.solve(&mut x, &mut w);
        // w = A x̂ − b
        w.iter_mut().zip(&b).for_each(|(r, bi)| *r = -bi);
        for j in 0..dim {
            for k in col_ptr[j]..col_ptr[j + 1] {
                w[row_idx[k]] += vals[k] * x[j];
            }
        }
        let r_norm = w.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let x_norm = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        self.check = [x, b, w];
        let den = a_norm * x_norm + b_norm;
        if r_norm.is_finite() && den > 0.0 {
            r_norm / den
        } else {
            f64::INFINITY
        }
    }

    /// The factors of the banded part.
    fn band(&self) -> Band<'_> {
        Band {
            ab: &self.ab,
            ld: self.ld,
            kl: self.plan.kl,
            ku: self.plan.ku,
            ipiv: &self.ipiv,
            u_inv: &self.u_inv,
        }
    }

    /// Solves `A x = b` in place (`b` in the original numbering); `w` is scratch of the same
    /// length.
    pub(crate) fn solve(&self, b: &mut [f64], w: &mut [f64]) {
        let n1 = self.plan.n1;
        let nb = self.plan.border();
        for (new, &old) in self.plan.perm.iter().enumerate() {
            w[new] = b[old];
        }
        let (y1, y2) = w.split_at_mut(n1);
        let band = self.band();
        band.solve(y1);
        if nb > 0 {
            crate::simd::dispatch(BorderProduct {
                a21: &self.a21,
                y1,
                y2,
                nb,
            });
            dense_solve(&self.s, nb, &self.s_piv, y2);
            // y1 -= X x2, each row's border columns in the order of the columns
            for (y, xr) in y1.iter_mut().zip(self.x.chunks_exact(nb)) {
                for (x, v) in xr.iter().zip(y2.iter()) {
                    *y -= x * v;
                }
            }
        }
        for (new, &old) in self.plan.perm.iter().enumerate() {
            b[old] = w[new];
        }
    }
}

/// `max |a|` over `a` (0 for an empty slice).
fn max_abs(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// The growth `u / a` of [`Growth`] (1 when `A` is zero: nothing grew).
fn growth(u: f64, a: f64) -> f64 {
    if a > 0.0 { u / a } else { 1.0 }
}

/// The factors of the banded part.
struct Band<'a> {
    ab: &'a [f64],
    ld: usize,
    kl: usize,
    ku: usize,
    ipiv: &'a [usize],
    u_inv: &'a [f64],
}

impl Band<'_> {
    /// Solves with the banded LU (dgbtrs, no transpose) in place; `b` has the band's size
    /// (compiled for the machine's vector width: [`crate::simd`], the same bits).
    fn solve(&self, b: &mut [f64]) {
        match (self.kl, self.ku) {
            (SPECIALISED_KL, SPECIALISED_KL) => {
                crate::simd::dispatch(BandSolve::<SPECIALISED_KL, { 2 * SPECIALISED_KL }> {
                    band: self,
                    b,
                })
            }
            _ => crate::simd::dispatch(BandSolve::<0, 0> { band: self, b }),
        }
    }

    /// The body of [`Band::solve`]; with `KL > 0` and `KV > 0` (equal to `kl` and `kl + ku`)
    /// the full-length columns of `L` and `U` run on constant lengths ([`sub_scaled`], the same
    /// bits).
    #[inline(always)]
    fn solve_kernel<const KL: usize, const KV: usize>(&self, b: &mut [f64]) {
        let (ab, ld, kl) = (self.ab, self.ld, self.kl);
        let kv = kl + self.ku;
        let n = b.len();
        // L y = P b
        for j in 0..n {
            let p = self.ipiv[j];
            if p != j {
                b.swap(p, j);
            }
            let km = kl.min(n - 1 - j);
            let bj = b[j];
            if km > 0 && bj != 0.0 {
                let l = &ab[kv + 1 + j * ld..=kv + km + j * ld];
                sub_scaled::<KL>(&mut b[j + 1..=j + km], l, bj);
            }
        }
        // U x = y (U has upper bandwidth kv), column by column from the last
        for j in (0..n).rev() {
            let xj = b[j] * self.u_inv[j];
            b[j] = xj;
            let top = j.saturating_sub(kv);
            let len = j - top;
            if len > 0 && xj != 0.0 {
                let u = &ab[kv - len + j * ld..kv + j * ld];
                sub_scaled::<KV>(&mut b[top..j], u, xj);
            }
        }
    }
}

impl Band<'_> {
    /// Solves with the banded LU for the `k` right-hand sides stored row-major in `b`
    /// (`n × k`: row `i` of all of them at `b[i k..(i + 1) k]`), in place: every column
    /// undergoes exactly the operations of [`Band::solve`] in the same order, so each gives
    /// the same bits as its own solve, but the inner loops run along the `k` columns of a row
    /// (contiguous, vectorised) instead of along the band (at most `kl` or `kl + ku` long).
    fn solve_rows(&self, b: &mut [f64], k: usize) {
        match k {
            SPECIALISED_BORDER => {
                crate::simd::dispatch(BandSolveRows::<SPECIALISED_BORDER> { band: self, b, k })
            }
            _ => crate::simd::dispatch(BandSolveRows::<0> { band: self, b, k }),
        }
    }

    /// The body of [`Band::solve_rows`]; with `K > 0` (equal to `k`) the rows run on a
    /// constant length ([`sub_scaled`], the same bits).
    #[inline(always)]
    fn solve_rows_kernel<const K: usize>(&self, b: &mut [f64], k: usize) {
        let (ab, ld, kl) = (self.ab, self.ld, self.kl);
        let kv = kl + self.ku;
        let n = b.len() / k;
        // L y = P b
        for j in 0..n {
            let p = self.ipiv[j];
            if p != j {
                let (lo, hi) = b.split_at_mut(p * k);
                lo[j * k..(j + 1) * k].swap_with_slice(&mut hi[..k]);
            }
            let km = kl.min(n - 1 - j);
            let (head, tail) = b.split_at_mut((j + 1) * k);
            let bj = &head[j * k..];
            // (`Band::solve` skips a zero `b_j`; here a zero entry subtracts `l·0`, which
            // leaves `t` equal, and a row of zeros is skipped)
            if bj.iter().all(|&v| v == 0.0) {
                continue;
            }
            for (i, row) in tail.chunks_exact_mut(k).take(km).enumerate() {
                let li = ab[kv + 1 + i + j * ld];
                sub_scaled::<K>(row, bj, li);
            }
        }
        // U x = y, column by column from the last
        for j in (0..n).rev() {
            let uj = self.u_inv[j];
            let (head, tail) = b.split_at_mut(j * k);
            let xj = &mut tail[..k];
            for v in xj.iter_mut() {
                *v *= uj;
            }
            if xj.iter().all(|&v| v == 0.0) {
                continue;
            }
            let top = j.saturating_sub(kv);
            let len = j - top;
            for (i, row) in head[top * k..].chunks_exact_mut(k).enumerate().take(len) {
                let ui = ab[kv - len + i + j * ld];
                sub_scaled::<K>(row, xj, ui);
            }
        }
    }
}

/// [`Band::solve_rows`] as a [`crate::simd::Kernel`].
struct BandSolveRows<'a, 'b, const K: usize> {
    band: &'a Band<'b>,
    b: &'a mut [f64],
    k: usize,
}

impl<const K: usize> crate::simd::Kernel for BandSolveRows<'_, '_, K> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        self.band.solve_rows_kernel::<K>(self.b, self.k)
    }
}

/// `acc = A₂₁ X` (`A₂₁` column-major `nb × n1`, `X` row-major `n1 × nb`, `acc` column-major
/// `nb × nb`) as rank-one updates over `k = 0, 1, …`: each entry is summed in the order of the
/// inner products `Σₖ A₂₁(r, k) X(k, c)` it replaces (the same bits), the loops run along the
/// `nb` rows of a column.
struct SchurProduct<'a> {
    a21: &'a [f64],
    x: &'a [f64],
    acc: &'a mut [f64],
    nb: usize,
}

impl crate::simd::Kernel for SchurProduct<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        let nb = self.nb;
        self.acc.fill(0.0);
        for (a, xr) in self.a21.chunks_exact(nb).zip(self.x.chunks_exact(nb)) {
            for (col, &xv) in self.acc.chunks_exact_mut(nb).zip(xr) {
                for (t, &av) in col.iter_mut().zip(a) {
                    *t += av * xv;
                }
            }
        }
    }
}

/// Rows of the border taken together by [`BorderProduct`] (its accumulators on the stack).
const BORDER_ROWS: usize = 16;

/// `y₂ −= A₂₁ y₁` of [`BandLu::solve`] (`A₂₁` stored `a21[r + k nb]`): each row's inner
/// product `Σₖ a₂₁[r, k] y₁[k]` summed from 0 in the order of `k` and then subtracted, as the
/// row-by-row loop it replaces (kept as `border_product_reference` in the tests), so the same
/// bits; the rows' sums run side by side (up to [`BORDER_ROWS`] at a time), along the
/// contiguous rows of `a21`, instead of one strided dependency chain after the other.
struct BorderProduct<'a> {
    a21: &'a [f64],
    y1: &'a [f64],
    y2: &'a mut [f64],
    nb: usize,
}

impl crate::simd::Kernel for BorderProduct<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        let nb = self.nb;
        for r0 in (0..nb).step_by(BORDER_ROWS) {
            let m = (nb - r0).min(BORDER_ROWS);
            let mut acc = [0.0; BORDER_ROWS];
            for (a, &yk) in self.a21.chunks_exact(nb).zip(self.y1) {
                for (t, &av) in acc[..m].iter_mut().zip(&a[r0..r0 + m]) {
                    *t += av * yk;
                }
            }
            for (y, a) in self.y2[r0..r0 + m].iter_mut().zip(&acc) {
                *y -= a;
            }
        }
    }
}

/// [`Band::solve`] as a [`crate::simd::Kernel`].
struct BandSolve<'a, 'b, const KL: usize, const KV: usize> {
    band: &'a Band<'b>,
    b: &'a mut [f64],
}

impl<const KL: usize, const KV: usize> crate::simd::Kernel for BandSolve<'_, '_, KL, KV> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        self.band.solve_kernel::<KL, KV>(self.b)
    }
}

/// LU with partial pivoting of the dense `n × n` column-major `a` in place; `Err(column)` at
/// a zero pivot.
fn dense_lu(a: &mut [f64], n: usize, piv: &mut [usize]) -> Result<(), usize> {
    for j in 0..n {
        let mut p = j;
        for i in j + 1..n {
            if a[i + j * n].abs() > a[p + j * n].abs() {
                p = i;
            }
        }
        piv[j] = p;
        let d = a[p + j * n];
        if d == 0.0 || !d.is_finite() {
            return Err(j);
        }
        if p != j {
            for c in 0..n {
                a.swap(j + c * n, p + c * n);
            }
        }
        for i in j + 1..n {
            a[i + j * n] /= d;
        }
        for c in j + 1..n {
            let u = a[j + c * n];
            for i in j + 1..n {
                a[i + c * n] -= a[i + j * n] * u;
            }
        }
    }
    Ok(())
}

/// Solves with the LU of [`dense_lu`] in place.
///
/// [`dense_lu`] swaps whole rows (LAPACK dgetf2: the multipliers of the earlier columns move
/// with their rows), so its factors are those of `P A = L U` with `P` the product of all the
/// swaps: `b` is permuted by every swap first, then `L y = P b` is solved (LAPACK dgetrs:
/// dlaswp, then dtrsm). Interleaving the swaps with the elimination, as the banded solve does
/// ([`Band::solve`], whose dgbtf2 leaves the multipliers in place), pairs a later-swapped row
/// with the other row's multipliers.
fn dense_solve(a: &[f64], n: usize, piv: &[usize], b: &mut [f64]) {
    for (j, &p) in piv.iter().enumerate().take(n) {
        b.swap(j, p);
    }
    for j in 0..n {
        let bj = b[j];
        for i in j + 1..n {
            b[i] -= a[i + j * n] * bj;
        }
    }
    for j in (0..n).rev() {
        b[j] /= a[j + j * n];
        for i in 0..j {
            b[i] -= a[i + j * n] * b[j];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pattern of a closed loop of `nodes` nodes with `b` coupled coordinates each (node `k`
    /// couples to `k ± 1` cyclically) plus one coordinate coupled to all: the ANCF belt with
    /// a free pulley.
    fn ring(b: usize, nodes: usize) -> (usize, Vec<usize>, Vec<usize>) {
        let n = b * nodes;
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for j in 0..=n {
            let mut rows: Vec<usize> = if j == n {
                (0..=n).collect()
            } else {
                let node = j / b;
                let mut r: Vec<usize> = [node + nodes - 1, node, node + 1]
                    .iter()
                    .flat_map(|&k| (0..b).map(move |c| (k % nodes) * b + c))
                    .collect();
                r.push(n);
                r
            };
            rows.sort_unstable();
            rows.dedup();
            row_idx.extend(rows);
            col_ptr.push(row_idx.len());
        }
        (n + 1, col_ptr, row_idx)
    }

    /// One pass of [`Band::solve_rows`] over several right-hand sides gives every column the
    /// value of its own [`Band::solve`] (reference: the single-column solve, the kernel the
    /// border columns were solved with before), on a factored ring whose band pivots, with
    /// columns that start with zero rows.
    #[test]
    fn row_major_solve_matches_the_single_column_solves() {
        let (dim, cp, ri) = ring(6, 20);
        let plan = BandPlan::new(dim, &cp, &ri);
        let mut vals = vec![0.0; ri.len()];
        for j in 0..dim {
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                // weak diagonal: the band's partial pivoting swaps rows
                vals[p] = ((i * 31 + j * 17) as f64 * 0.37).sin() + if i == j { 0.3 } else { 0.0 };
            }
        }
        let mut lu = BandLu::new(plan);
        lu.factor(&cp, &ri, &vals).expect("regular");
        assert!(
            lu.ipiv.iter().enumerate().any(|(j, &p)| p != j),
            "the band pivots"
        );
        let n1 = lu.plan.n1;
        let k = 5;
        let mut rows = vec![0.0; n1 * k];
        for i in 0..n1 {
            for c in 0..k {
                rows[i * k + c] = if i < 3 * c {
                    0.0
                } else {
                    ((i * 7 + c * 3) as f64).cos()
                };
            }
        }
        let mut cols: Vec<Vec<f64>> = (0..k)
            .map(|c| (0..n1).map(|i| rows[i * k + c]).collect())
            .collect();
        let band = lu.band();
        band.solve_rows(&mut rows, k);
        for (c, col) in cols.iter_mut().enumerate() {
            band.solve(col);
            for i in 0..n1 {
                assert!(rows[i * k + c] == col[i], "row {i}, column {c}");
            }
        }
    }

    /// The kernels compiled for constant widths (`dgbtf2::<11>`, `BandSolve::<11, 22>`,
    /// `BandSolveRows::<12>`, [`sub_scaled`]) give the bits of the run-time-width kernels
    /// (reference: the same kernels with width 0, `to_bits` on every entry), on a ring of six
    /// coordinates per node (`kl = ku = 11`) whose band pivots, for one and twelve right-hand
    /// sides.
    #[test]
    fn constant_width_kernels_are_the_run_time_width_kernels_bit_for_bit() {
        let (dim, cp, ri) = ring(6, 24);
        let plan = BandPlan::new(dim, &cp, &ri);
        let vals = ring_values(dim, &cp, &ri, 0.3);
        let mut lu = BandLu::new(plan);
        lu.load(&cp, &ri, &vals);
        let (n1, kl, ku, ld) = (lu.plan.n1, lu.plan.kl, lu.plan.ku, lu.ld);
        assert_eq!(
            (kl, ku),
            (11, 11),
            "the widths the kernels are compiled for"
        );
        let (mut ab0, mut ipiv0) = (lu.ab.clone(), lu.ipiv.clone());
        dgbtf2::<0>(&mut ab0, &mut ipiv0, n1, kl, ku, ld).expect("regular");
        lu.factor_loaded().expect("regular");
        assert!(
            lu.ipiv.iter().enumerate().any(|(j, &p)| p != j),
            "the band pivots"
        );
        assert_eq!(lu.ipiv, ipiv0);
        assert!(
            lu.ab
                .iter()
                .zip(&ab0)
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
        let band = lu.band();
        let rhs: Vec<f64> = (0..n1).map(|i| ((i * 5 + 2) as f64 * 0.83).sin()).collect();
        let (mut fast, mut slow) = (rhs.clone(), rhs.clone());
        band.solve(&mut fast);
        band.solve_kernel::<0, 0>(&mut slow);
        assert!(
            fast.iter()
                .zip(&slow)
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
        let k = 12;
        let rows: Vec<f64> = (0..n1 * k)
            .map(|i| {
                if i < 3 * k {
                    0.0
                } else {
                    ((i * 7) as f64 * 0.29).cos()
                }
            })
            .collect();
        let (mut fast, mut slow) = (rows.clone(), rows);
        band.solve_rows(&mut fast, k);
        band.solve_rows_kernel::<0>(&mut slow, k);
        assert!(
            fast.iter()
                .zip(&slow)
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
    }

    /// The border's `y₂ −= A₂₁ y₁` as the row-by-row loop that [`BorderProduct`] replaced.
    fn border_product_reference(a21: &[f64], y1: &[f64], y2: &mut [f64], nb: usize) {
        let n1 = y1.len();
        for r in 0..nb {
            let mut acc = 0.0;
            for k in 0..n1 {
                acc += a21[r + k * nb] * y1[k];
            }
            y2[r] -= acc;
        }
    }

    /// [`BorderProduct`] (rows side by side, dispatched) gives the bits of the row-by-row
    /// inner products it replaced (reference: `border_product_reference`, `to_bits` on every
    /// entry), for borders narrower and wider than [`BORDER_ROWS`] and values of mixed
    /// magnitude whose sums depend on the order of the additions.
    #[test]
    fn border_product_is_the_row_by_row_inner_products_bit_for_bit() {
        for nb in [1, 6, 12, 16, 19, 40] {
            let n1 = 257;
            let a21: Vec<f64> = (0..nb * n1)
                .map(|k| ((k * 13 + 5) as f64 * 0.71).sin() * 10f64.powi((k % 7) as i32 - 3))
                .collect();
            let y1: Vec<f64> = (0..n1).map(|k| ((k * 3 + 1) as f64 * 0.29).cos()).collect();
            let y2: Vec<f64> = (0..nb).map(|r| (r as f64 * 1.3).sin()).collect();
            let mut reference = y2.clone();
            border_product_reference(&a21, &y1, &mut reference, nb);
            let mut got = y2.clone();
            crate::simd::dispatch(BorderProduct {
                a21: &a21,
                y1: &y1,
                y2: &mut got,
                nb,
            });
            for r in 0..nb {
                assert_eq!(got[r].to_bits(), reference[r].to_bits(), "nb {nb}, row {r}");
            }
        }
    }

    /// Values of the ring pattern with a weak diagonal (the band's partial pivoting swaps
    /// rows), varied by `seed`.
    fn ring_values(dim: usize, cp: &[usize], ri: &[usize], seed: f64) -> Vec<f64> {
        let mut vals = vec![0.0; ri.len()];
        for j in 0..dim {
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                vals[p] =
                    ((i * 31 + j * 17) as f64 * 0.37 + seed).sin() + if i == j { 0.3 } else { 0.0 };
            }
        }
        vals
    }

    // Reference: the sum of the shared blocks into the pattern's values (the operations of
    // `linalg::scatter_shared`) followed by `BandLu::load`; `load_shared` must give the same
    // band, border and Schur arrays and factors to the bit, the entries of the pattern that no
    // block has staying zero.
    #[test]
    fn blocks_loaded_straight_into_the_band_are_the_summed_values_bit_for_bit() {
        let (dim, cp, ri) = ring(6, 20);
        let plan = BandPlan::new(dim, &cp, &ri);
        // the blocks hold every entry of the pattern but every seventh
        let map: Vec<usize> = (0..ri.len()).filter(|k| k % 7 != 3).collect();
        let blocks: Vec<Vec<f64>> = (0..3)
            .map(|b| {
                let v = ring_values(dim, &cp, &ri, b as f64);
                map.iter().map(|&u| v[u] * (1.0 + b as f64)).collect()
            })
            .collect();
        let scales = [1.7e7, 3.1e2, 0.37];
        let mut vals = vec![0.0; ri.len()];
        for (k, &u) in map.iter().enumerate() {
            let mut a = vals[u];
            for (s, v) in scales.iter().zip(&blocks) {
                a += s * v[k];
            }
            vals[u] = a;
        }
        let mut reference = BandLu::new(plan.clone());
        reference.factor(&cp, &ri, &vals).expect("regular");
        let terms: Vec<(f64, &[f64])> = scales
            .iter()
            .zip(&blocks)
            .map(|(s, v)| (*s, v.as_slice()))
            .collect();
        for _ in 0..2 {
            let mut lu = BandLu::new(plan.clone());
            assert_eq!(lu.load_shared(&cp, &ri, &terms, &map), Some(true));
            lu.factor_loaded().expect("regular");
            let bits = |a: &[f64]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&lu.ab), bits(&reference.ab));
            assert_eq!(bits(&lu.x), bits(&reference.x));
            assert_eq!(bits(&lu.a21), bits(&reference.a21));
            assert_eq!(bits(&lu.s), bits(&reference.s));
            assert_eq!(lu.ipiv, reference.ipiv);
            assert_eq!(lu.s_piv, reference.s_piv);
            assert!(
                lu.ipiv.iter().enumerate().any(|(j, &p)| p != j),
                "the band pivots"
            );
        }
        // a value that is not finite is reported; a map that names an entry twice is refused
        let mut bad = blocks[1].clone();
        bad[5] = f64::NAN;
        let nan_terms = [terms[0], (scales[1], bad.as_slice()), terms[2]];
        let mut lu = BandLu::new(plan.clone());
        assert_eq!(lu.load_shared(&cp, &ri, &nan_terms, &map), Some(false));
        let mut twice = map.clone();
        twice[1] = twice[0];
        let mut lu = BandLu::new(plan);
        assert_eq!(lu.load_shared(&cp, &ri, &terms, &twice), None);
    }

    // Reference: the rule of `check_needed` itself. The first factors and every seventeenth
    // in a row are measured; factors whose growth exceeds twice the verified one's in any
    // part are measured; otherwise the verdict is taken. The ring's factors grow by about 1
    // (partial pivoting, Higham §9.4).
    #[test]
    fn the_backward_error_is_measured_unless_the_growth_repeats_a_measured_one() {
        let (dim, cp, ri) = ring(6, 20);
        let plan = BandPlan::new(dim, &cp, &ri);
        let mut lu = BandLu::new(plan);
        lu.factor(&cp, &ri, &ring_values(dim, &cp, &ri, 0.0))
            .expect("regular");
        assert!(lu.check_needed(), "nothing verified yet");
        assert!(lu.backward_error(&cp, &ri, &ring_values(dim, &cp, &ri, 0.0)) < 1e-14);
        lu.verdict(true);
        let g0 = lu.growth;
        assert!(g0.band > 0.5 && g0.band < 10.0 && g0.schur > 0.5, "{g0:?}");
        let mut taken = 0;
        for k in 1..=40 {
            let vals = ring_values(dim, &cp, &ri, 1e-3 * k as f64);
            lu.factor(&cp, &ri, &vals).expect("regular");
            let measured = lu.check_needed();
            if measured {
                assert_eq!(taken, VERDICT_REUSE_LIMIT, "factorisation {k}");
                assert!(lu.backward_error(&cp, &ri, &vals) < 1e-14);
                taken = 0;
            } else {
                taken += 1;
            }
            lu.verdict(measured);
        }
        // growth beyond the ratio in any part: measured
        for part in 0..3 {
            let saved = lu.growth;
            let g = match part {
                0 => &mut lu.growth.band,
                1 => &mut lu.growth.schur,
                _ => &mut lu.growth.border,
            };
            *g *= 2.5;
            assert!(lu.check_needed(), "part {part}");
            lu.growth.band = f64::NAN;
            assert!(lu.check_needed(), "NaN");
            lu.growth = saved;
        }
    }

    impl BandLu {
        /// The scatter of every entry with its block test and permutation look-ups, as
        /// [`BandLu::factor`] did it before [`BandScatter`] (the reference of
        /// `scatter_map_places_every_entry_as_the_entrywise_loop`).
        fn scatter_reference(
            &self, col_ptr: &[usize], row_idx: &[usize], vals: &[f64],
        ) -> [Vec<f64>; 4] {
            let (n1, kl, ku, ld) = (self.plan.n1, self.plan.kl, self.plan.ku, self.ld);
            let nb = self.plan.border();
            let kv = kl + ku;
            let mut ab = vec![0.0; self.ab.len()];
            let mut x = vec![0.0; self.x.len()];
            let mut a21 = vec![0.0; self.a21.len()];
            let mut s = vec![0.0; self.s.len()];
            for j in 0..n1 + nb {
                let pj = self.plan.inv[j];
                for k in col_ptr[j]..col_ptr[j + 1] {
                    let pi = self.plan.inv[row_idx[k]];
                    let v = vals[k];
                    match (pi < n1, pj < n1) {
                        (true, true) => ab[kv + pi - pj + pj * ld] += v,
                        (true, false) => x[pi * nb + (pj - n1)] += v,
                        (false, true) => a21[(pi - n1) + pj * nb] += v,
                        (false, false) => s[(pi - n1) + (pj - n1) * nb] += v,
                    }
                }
            }
            [ab, x, a21, s]
        }
    }

    /// The precomputed scatter ([`BandScatter`]) fills the band, the border blocks and `A₂₂`
    /// with the same bits as the entry-by-entry loop it replaced (reference:
    /// `BandLu::scatter_reference`, `==` on every stored number, negative zeros included), and
    /// the factors of a second factorisation with other values are those of a fresh `BandLu`.
    #[test]
    fn scatter_map_places_every_entry_as_the_entrywise_loop() {
        let (dim, cp, ri) = ring(6, 20);
        let plan = BandPlan::new(dim, &cp, &ri);
        let values = |seed: f64| -> Vec<f64> {
            let mut vals = vec![0.0; ri.len()];
            for j in 0..dim {
                for p in cp[j]..cp[j + 1] {
                    let i = ri[p];
                    vals[p] =
                        ((i * 31 + j * 17) as f64 * seed).sin() + if i == j { 0.3 } else { 0.0 };
                }
            }
            vals[1] = -0.0;
            vals
        };
        let mut lu = BandLu::new(plan.clone());
        for seed in [0.37, 0.91] {
            let vals = values(seed);
            let reference = lu.scatter_reference(&cp, &ri, &vals);
            // the scatter alone: the factorisation's first step, before dgbtf2 overwrites it
            let map = lu.scatter_map(&cp, &ri);
            let mut got = [
                vec![0.0; lu.ab.len()],
                vec![0.0; lu.x.len()],
                vec![0.0; lu.a21.len()],
                vec![0.0; lu.s.len()],
            ];
            for (dst, m) in got.iter_mut().zip([&map.ab, &map.x, &map.a21, &map.s]) {
                for &(k, p) in m {
                    dst[p] += vals[k];
                }
            }
            for (g, r) in got.iter().zip(&reference) {
                assert!(
                    g.iter().zip(r).all(|(a, b)| a.to_bits() == b.to_bits()),
                    "seed {seed}"
                );
            }
            lu.factor(&cp, &ri, &vals).expect("regular");
            let mut fresh = BandLu::new(plan.clone());
            fresh.factor(&cp, &ri, &vals).expect("regular");
            assert!(
                lu.ab == fresh.ab && lu.x == fresh.x && lu.s == fresh.s,
                "seed {seed}"
            );
        }
    }

    /// The loop is cut at one node: the pulley and that node's six coordinates form the
    /// border and the open chain has the band of neighbouring nodes, `2b − 1` on each side
    /// (against `4b − 2` for the loop numbered from one node outwards on both sides).
    #[test]
    fn closed_loop_is_cut_into_a_chain() {
        let (dim, cp, ri) = ring(6, 20);
        let plan = BandPlan::new(dim, &cp, &ri);
        assert_eq!(plan.border(), 7);
        assert_eq!(plan.bandwidths(), (11, 11));
        // a permutation of all coordinates
        let mut seen = vec![false; dim];
        for &v in &plan.perm {
            assert!(!seen[v]);
            seen[v] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }

    /// The dense LU of the border's Schur complement and its solve on a 3 × 3 matrix whose
    /// second column pivots (after the first column's elimination, 0.1 − 1/4 against 5 − 2/4)
    /// between rows with different multipliers (1/4, 1/2): the solve recovers the `x` that made
    /// `b = A x` (reference: the product), which interleaving the swaps with the forward
    /// substitution did not (issue 37 item 4).
    #[test]
    fn dense_solve_applies_every_row_swap_first() {
        let rows = [[4.0, 1.0, 0.0], [1.0, 0.1, 3.0], [2.0, 5.0, 1.0]];
        let n = 3;
        let mut a: Vec<f64> = (0..n * n).map(|k| rows[k % n][k / n]).collect();
        let x = [1.5, -2.0, 0.75];
        let mut b: Vec<f64> = rows
            .iter()
            .map(|r| r.iter().zip(&x).map(|(p, q)| p * q).sum())
            .collect();
        let mut piv = vec![0; n];
        dense_lu(&mut a, n, &mut piv).expect("regular");
        assert_eq!(piv, [0, 2, 2], "the second column pivots");
        dense_solve(&a, n, &piv, &mut b);
        for (bi, xi) in b.iter().zip(&x) {
            assert!((bi - xi).abs() <= 1e-14, "{b:?} against {x:?}");
        }
    }
}
