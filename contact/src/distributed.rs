//! Distributed contact over an element by quadrature, in the plane or in space: the generalized
//! contact force `Q_c = ∫ Sᵀ (f_n n + T f_t) ≈ Σ_q w_q S_qᵀ f_q` (Kerkkänen (3.27) along a line
//! element; its surface form over the thin-plate belt elements of his ch. 4, 81 points per
//! element, §4.5), its exact Jacobians with respect to the element coordinates `e`, velocities
//! `ė` and the obstacle's angular velocity `ω`, the reaction force and moment on the obstacle
//! (Kerkkänen (3.26): in the plane the torque about the pulley centre), and per-point records of
//! pressure, friction and slip for output.
//!
//! The element enters only through its quadrature points ([`QuadPoint`]): position `r = S e`,
//! velocity `ṙ = S ė`, the shape-function matrix `S = ∂r/∂e` ([`ShapeMatrix`]: a full
//! `D × N` matrix, or the blocks `S₀ = [N₁I, N₂I, …]` of a line element's centreline,
//! [`BlockShape`]) and the weight `w_q` (Gauss weight × length or area Jacobian). The point
//! forces and their derivatives are those of [`point_contact`], so the laws are the crate's
//! [`NormalLaw`] and [`FrictionLaw`] per unit length or area. One implementation,
//! [`element_contact`], serves [`LineContact`] (a Gauss rule along line elements) and
//! [`SurfaceContact`] (quadrature points supplied by the caller).

use crate::dim::{ContactDim, Dim, Moment, Slip};
use crate::friction::FrictionLaw;
use crate::geometry::{Surface, SurfaceValues};
use crate::normal::NormalLaw;
use crate::point::{point_contact, point_force};
use crate::quadrature::GaussRule;
use nalgebra::{Point, SMatrix, SVector};
use std::ops::{AddAssign, Mul};

/// Largest number of blocks of a [`BlockShape`] (12: the nodal position blocks of the ANCF
/// thin-plate element, Kerkkänen (4.1)).
pub const MAX_BLOCKS: usize = 12;

/// The shape-function matrix `S = ∂r/∂e` (`D × ndof`) of an element at one quadrature point.
pub trait ShapeMatrix<const D: usize> {
    /// Number of element coordinates.
    fn ndof(&self) -> usize;
    /// `out += w Sᵀ x` for the `D` values `x` (force components, or moment columns).
    fn add_transposed<M: Copy + AddAssign + Mul<f64, Output = M>>(
        &self, x: &[M; D], w: f64, out: &mut [M],
    );
    /// `k += w Sᵀ A S` (`k` column-major `ndof × ndof`).
    fn add_congruence(&self, a: &SMatrix<f64, D, D>, w: f64, k: &mut [f64]);
    /// The values `s_b` of a block shape `S = [s₁ I, s₂ I, …]` ([`BlockShape`]), whose
    /// congruences [`element_contact`] then sums over all points at once (see
    /// [`add_block_congruences`]); `None` (the default) for a general matrix.
    fn block_values(&self) -> Option<&[f64]> {
        None
    }
}

/// Block shape functions `S = [s₁ I, s₂ I, …]` (a line element's centreline, or the mid-surface
/// of an ANCF plate): coordinate
/// `D b + i` is component `i` of block `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockShape {
    /// Values `s_b` (the first `blocks` are used).
    pub values: [f64; MAX_BLOCKS],
    /// Number of blocks.
    pub blocks: usize,
}

impl<const D: usize> ShapeMatrix<D> for BlockShape {
    fn ndof(&self) -> usize {
        D * self.blocks
    }
    #[inline]
    fn add_transposed<M: Copy + AddAssign + Mul<f64, Output = M>>(
        &self, x: &[M; D], w: f64, out: &mut [M],
    ) {
        for (b, &s) in self.values[..self.blocks].iter().enumerate() {
            let ws = w * s;
            for i in 0..D {
                out[D * b + i] += x[i] * ws;
            }
        }
    }
    fn block_values(&self) -> Option<&[f64]> {
        Some(&self.values[..self.blocks])
    }
    #[inline]
    fn add_congruence(&self, a: &SMatrix<f64, D, D>, w: f64, k: &mut [f64]) {
        let ndof = D * self.blocks;
        let s = &self.values[..self.blocks];
        for j in 0..self.blocks {
            for b in 0..D {
                let col = D * j + b;
                for i in 0..self.blocks {
                    let sij = w * s[i] * s[j];
                    for r in 0..D {
                        k[D * i + r + col * ndof] += sij * a[(r, b)];
                    }
                }
            }
        }
    }
}

impl<const D: usize, const N: usize> ShapeMatrix<D> for SMatrix<f64, D, N> {
    fn ndof(&self) -> usize {
        N
    }
    fn add_transposed<M: Copy + AddAssign + Mul<f64, Output = M>>(
        &self, x: &[M; D], w: f64, out: &mut [M],
    ) {
        for k in 0..N {
            for i in 0..D {
                let s = self[(i, k)];
                if s != 0.0 {
                    out[k] += x[i] * (w * s);
                }
            }
        }
    }
    fn add_congruence(&self, a: &SMatrix<f64, D, D>, w: f64, k: &mut [f64]) {
        let as_ = (a * self) * w;
        for col in 0..N {
            for row in 0..N {
                let mut sum = 0.0;
                for i in 0..D {
                    sum += self[(i, row)] * as_[(i, col)];
                }
                k[row + col * N] += sum;
            }
        }
    }
}

/// A shape matrix by reference (the caller keeps its precomputed shapes; a point need not copy
/// one).
impl<const D: usize, T: ShapeMatrix<D>> ShapeMatrix<D> for &T {
    fn ndof(&self) -> usize {
        (**self).ndof()
    }
    #[inline]
    fn add_transposed<M: Copy + AddAssign + Mul<f64, Output = M>>(
        &self, x: &[M; D], w: f64, out: &mut [M],
    ) {
        (**self).add_transposed(x, w, out)
    }
    fn add_congruence(&self, a: &SMatrix<f64, D, D>, w: f64, k: &mut [f64]) {
        (**self).add_congruence(a, w, k)
    }
    fn block_values(&self) -> Option<&[f64]> {
        (**self).block_values()
    }
}

/// `k_p += Σ_q Sᵀ_q A_q S_q` and `k_v += Σ_q Sᵀ_q B_q S_q` (column-major `ndof × ndof`,
/// `ndof = D·blocks`) for block shapes `S_q = [s_q1 I, s_q2 I, …]`, the Jacobian sums of
/// [`element_contact`]. `points` holds per point the `blocks` values `s_q`, then `A_q` and `B_q`
/// (`D × D` column-major each, the weight included). The `(i, j)` block of the sum is
/// `Σ_q s_qi s_qj A_q`, equal to the `(j, i)` block, so only the pairs `i ≤ j` are summed —
/// one 2D²-wide multiply–add per pair and point — and mirrored at the end; `acc` is the
/// caller's buffer for the pair sums.
pub fn add_block_congruences<const D: usize>(
    blocks: usize, points: &[f64], kp: &mut [f64], kv: &mut [f64], acc: &mut Vec<f64>,
) {
    let dd = D * D;
    let nc = 2 * dd;
    let ndof = D * blocks;
    let pairs = blocks * (blocks + 1) / 2;
    acc.clear();
    acc.resize(pairs * nc, 0.0);
    // the pair sums compiled for the machine's vector width (`mbd_core::simd`, the same bits)
    mbd_core::simd::dispatch(PairSums::<D> {
        blocks,
        points,
        acc,
    });
    let mut rows = acc.chunks_exact(nc);
    for j in 0..blocks {
        for i in 0..=j {
            let row = rows.next().expect("one row per pair");
            for b in 0..D {
                for r in 0..D {
                    let (va, vb) = (row[r + D * b], row[dd + r + D * b]);
                    let ij = D * i + r + (D * j + b) * ndof;
                    kp[ij] += va;
                    kv[ij] += vb;
                    if i != j {
                        let ji = D * j + r + (D * i + b) * ndof;
                        kp[ji] += va;
                        kv[ji] += vb;
                    }
                }
            }
        }
    }
}

/// [`pair_sums`] as a [`mbd_core::simd::Kernel`].
struct PairSums<'a, const D: usize> {
    blocks: usize,
    points: &'a [f64],
    acc: &'a mut [f64],
}

impl<const D: usize> mbd_core::simd::Kernel for PairSums<'_, D> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        pair_sums::<D>(self.blocks, self.points, self.acc)
    }
}

/// `acc[pair] += s_i s_j m` over the point records of [`add_block_congruences`]: for each pair
/// `(i ≤ j)` the `2D²` sums run over the points in their order, held in registers (one pass
/// over the records per pair instead of one load and store of every pair sum per point; each
/// sum adds the same products in the same order, so the same bits).
#[inline(always)]
fn pair_sums<const D: usize>(blocks: usize, points: &[f64], acc: &mut [f64]) {
    /// `2D²` for `D = 3` (the largest dimension).
    const MAX_NC: usize = 18;
    let nc = 2 * D * D;
    debug_assert!(nc <= MAX_NC);
    let stride = blocks + nc;
    let mut rows = acc.chunks_exact_mut(nc);
    for j in 0..blocks {
        for i in 0..=j {
            let row = rows.next().expect("one row per pair");
            let mut sum = [0.0; MAX_NC];
            for rec in points.chunks_exact(stride) {
                let t = rec[i] * rec[j];
                for (r, v) in sum[..nc].iter_mut().zip(&rec[blocks..]) {
                    *r += t * v;
                }
            }
            for (r, v) in row.iter_mut().zip(&sum[..nc]) {
                *r += v;
            }
        }
    }
}

/// One quadrature point of an element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadPoint<const D: usize, Sh> {
    /// Position `r = S e` \[m\].
    pub position: Point<f64, D>,
    /// Velocity `ṙ = S ė` \[m/s\].
    pub velocity: SVector<f64, D>,
    /// Shape-function matrix `S = ∂r/∂e`.
    pub shape: Sh,
    /// Quadrature weight × length or area Jacobian `w_q` \[m or m²\].
    pub weight: f64,
}

/// Contact state at one quadrature point in contact, for output (force distributions, slip
/// zones).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRecord<const D: usize>
where
    Dim<D>: ContactDim<D>,
{
    /// Index of the quadrature point in the element's sequence (for a [`LineContact`], in its
    /// Gauss rule: the point sits at `ξ = rule.points[index]`).
    pub index: usize,
    /// Position of the point \[m\].
    pub position: Point<f64, D>,
    /// Penetration \[m\].
    pub penetration: f64,
    /// Normal force per unit length or area \[N/m or N/m²\].
    pub normal_force: f64,
    /// Friction force per unit length or area in the tangent basis (in the plane along
    /// `t = Ĩ n`) \[N/m or N/m²\].
    pub friction_force: Slip<D>,
    /// Slip velocity in the tangent basis \[m/s\].
    pub slip: Slip<D>,
}

/// Reusable output buffers of the distributed contact of an element with `ndof` coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementContact<const D: usize>
where
    Dim<D>: ContactDim<D>,
{
    /// Number of element coordinates.
    pub ndof: usize,
    /// Generalized contact force `Q_c` \[N\].
    pub q: Vec<f64>,
    /// `∂Q_c/∂e` (column-major `ndof × ndof`) \[N/m\].
    pub dq_de: Vec<f64>,
    /// `∂Q_c/∂ė` (column-major) \[N·s/m\].
    pub dq_dedot: Vec<f64>,
    /// `∂Q_c/∂ω` \[N·s\].
    pub dq_domega: Vec<f64>,
    /// Moment of the contact forces on the obstacle about its [`Surface::center`],
    /// `M = Σ w (r − r_o) × (−f)` \[N·m\]: in the plane the counter-clockwise torque of
    /// Kerkkänen (3.26), in space a vector (its component along a pulley axis is that torque).
    pub moment: Moment<D>,
    /// `∂M/∂e` (one moment per coordinate).
    pub dmoment_de: Vec<Moment<D>>,
    /// `∂M/∂ė`.
    pub dmoment_dedot: Vec<Moment<D>>,
    /// `∂M/∂ω`.
    pub dmoment_domega: Moment<D>,
    /// Resultant force on the obstacle `F = −Σ w f` \[N\].
    pub reaction: SVector<f64, D>,
    /// Number of quadrature points in contact.
    pub active_points: usize,
    /// Per-point block values and weighted Jacobians of the current call, summed by
    /// [`add_block_congruences`] at its end.
    batch: Vec<f64>,
    /// Pair sums of [`add_block_congruences`].
    pairs: Vec<f64>,
    /// Positions and velocities of the points of [`element_forces_blocks`] (structure of
    /// arrays), and their surface values.
    soa: BatchScratch<D>,
}

/// Work arrays of [`element_forces_blocks`].
#[derive(Debug, Clone, PartialEq)]
struct BatchScratch<const D: usize> {
    position: [Vec<f64>; D],
    velocity: [Vec<f64>; D],
    values: SurfaceValues<D>,
    /// Force per point (zero where separated), [`ContactDim::batch_forces`].
    force: [Vec<f64>; D],
    /// Work buffer of [`ContactDim::batch_forces`].
    work: Vec<f64>,
    /// Points in contact.
    active: Vec<usize>,
    /// `Q_c` by component: `acc[i · blocks + b]`.
    acc: Vec<f64>,
}

impl<const D: usize> Default for BatchScratch<D> {
    fn default() -> Self {
        Self {
            position: std::array::from_fn(|_| Vec::new()),
            velocity: std::array::from_fn(|_| Vec::new()),
            values: SurfaceValues::default(),
            force: std::array::from_fn(|_| Vec::new()),
            work: Vec::new(),
            active: Vec::new(),
            acc: Vec::new(),
        }
    }
}

impl<const D: usize> ElementContact<D>
where
    Dim<D>: ContactDim<D>,
{
    /// Zeroed buffers for an element with `ndof` coordinates.
    pub fn new(ndof: usize) -> Self {
        Self {
            ndof,
            q: vec![0.0; ndof],
            dq_de: vec![0.0; ndof * ndof],
            dq_dedot: vec![0.0; ndof * ndof],
            dq_domega: vec![0.0; ndof],
            moment: Moment::<D>::default(),
            dmoment_de: vec![Moment::<D>::default(); ndof],
            dmoment_dedot: vec![Moment::<D>::default(); ndof],
            dmoment_domega: Moment::<D>::default(),
            reaction: SVector::zeros(),
            active_points: 0,
            batch: Vec::new(),
            pairs: Vec::new(),
            soa: BatchScratch::default(),
        }
    }

    fn clear(&mut self, jac: bool) {
        self.q.fill(0.0);
        if jac {
            self.dq_de.fill(0.0);
            self.dq_dedot.fill(0.0);
            self.dq_domega.fill(0.0);
            self.dmoment_de.fill(Moment::<D>::default());
            self.dmoment_dedot.fill(Moment::<D>::default());
        }
        self.moment = Moment::<D>::default();
        self.dmoment_domega = Moment::<D>::default();
        self.reaction.fill(0.0);
        self.active_points = 0;
        self.batch.clear();
    }
}

/// Contact of one element given by its quadrature `points` against `surface` with the laws
/// `normal` and `friction` (per unit length or area). Fills `out` (forces always; Jacobians when
/// `jacobian`) and appends point records to `records` when given. With `f` the point force
/// ([`point_contact`]) and `S` the shape matrix: `Q_c = Σ w Sᵀ f`,
/// `∂Q_c/∂e = Σ w Sᵀ (∂f/∂r) S`, `∂Q_c/∂ė = Σ w Sᵀ (∂f/∂ṙ) S`, `∂Q_c/∂ω = Σ w Sᵀ ∂f/∂ω`; with the
/// arm `a = r − r_o`, `∂M/∂r_b = −(e_b × f + a × ∂f/∂r_b)` (Kerkkänen (3.26)–(3.27)).
#[allow(clippy::too_many_arguments)]
pub fn element_contact<const D: usize, S, NL, FL, Sh>(
    surface: &S, normal: &NL, friction: &FL, points: impl IntoIterator<Item = QuadPoint<D, Sh>>,
    jacobian: bool, out: &mut ElementContact<D>, mut records: Option<&mut Vec<ContactRecord<D>>>,
) where
    Dim<D>: ContactDim<D>,
    S: Surface<D> + ?Sized,
    NL: NormalLaw + ?Sized,
    FL: FrictionLaw + ?Sized,
    Sh: ShapeMatrix<D>,
{
    out.clear(jacobian);
    let c = surface.center();
    for (index, qp) in points.into_iter().enumerate() {
        debug_assert_eq!(qp.shape.ndof(), out.ndof);
        // a force-only evaluation forms none of the Jacobian terms (`point_force`)
        let (pf, pc) = if jacobian {
            let Some(pc) = point_contact(surface, normal, friction, &qp.position, &qp.velocity)
            else {
                continue;
            };
            (pc.value(), Some(pc))
        } else {
            let Some(pf) = point_force(surface, normal, friction, &qp.position, &qp.velocity)
            else {
                continue;
            };
            (pf, None)
        };
        out.active_points += 1;
        let w = qp.weight;
        let f = pf.force;
        let arm = qp.position - c;
        qp.shape.add_transposed(&f.into(), w, &mut out.q);
        out.reaction -= f * w;
        out.moment -= <Dim<D>>::cross(&arm, &f) * w;
        if let Some(pc) = pc {
            if let Some(s) = qp.shape.block_values() {
                out.batch.extend_from_slice(s);
                out.batch.extend(pc.df_dp.iter().map(|x| x * w));
                out.batch.extend(pc.df_dv.iter().map(|x| x * w));
            } else {
                qp.shape.add_congruence(&pc.df_dp, w, &mut out.dq_de);
                qp.shape.add_congruence(&pc.df_dv, w, &mut out.dq_dedot);
            }
            qp.shape
                .add_transposed(&pc.df_domega.into(), w, &mut out.dq_domega);
            let mut dm_dp = [Moment::<D>::default(); D];
            let mut dm_dv = [Moment::<D>::default(); D];
            for b in 0..D {
                let mut e_b = SVector::<f64, D>::zeros();
                e_b[b] = 1.0;
                let dfp: SVector<f64, D> = pc.df_dp.column(b).into_owned();
                let dfv: SVector<f64, D> = pc.df_dv.column(b).into_owned();
                dm_dp[b] = -(<Dim<D>>::cross(&arm, &dfp) + <Dim<D>>::cross(&e_b, &f));
                dm_dv[b] = -<Dim<D>>::cross(&arm, &dfv);
            }
            qp.shape.add_transposed(&dm_dp, w, &mut out.dmoment_de);
            qp.shape.add_transposed(&dm_dv, w, &mut out.dmoment_dedot);
            out.dmoment_domega -= <Dim<D>>::cross(&arm, &pc.df_domega) * w;
        }
        if let Some(r) = records.as_deref_mut() {
            r.push(ContactRecord {
                index,
                position: qp.position,
                penetration: pf.penetration,
                normal_force: pf.normal_force,
                friction_force: pf.friction_force,
                slip: pf.slip,
            });
        }
    }
    if !out.batch.is_empty() {
        add_block_congruences::<D>(
            out.ndof / D,
            &out.batch,
            &mut out.dq_de,
            &mut out.dq_dedot,
            &mut out.pairs,
        );
    }
}

/// The contact quadrature of an element with block shape functions `S = [s₁ I, s₂ I, …]`
/// ([`BlockShape`]) in structure-of-arrays form, for [`element_forces_blocks`].
#[derive(Debug, Clone, PartialEq)]
pub struct BlockQuadrature {
    blocks: usize,
    /// `s_b` at the points `4j..4j + 4` in `shape4[j · blocks + b]` (the last group padded
    /// with zeros): the points in groups of [`LANES`], summed in registers by
    /// [`BlockPositions`].
    shape4: Vec<[f64; LANES]>,
    /// `w_q s_b` at point `q` in `weighted_by_point[q · blocks + b]`.
    weighted_by_point: Vec<f64>,
    /// Weights `w_q` \[m or m²\].
    weight: Vec<f64>,
}

/// Points per group of the batch kernels ([`BlockPositions`]): one AVX2 vector of `f64`.
const LANES: usize = 4;

impl BlockQuadrature {
    /// The quadrature of the points `(s, w)`: the `blocks` shape values `s` and the weight × length
    /// or area Jacobian `w` of each point, in order.
    pub fn new<'a>(blocks: usize, points: impl IntoIterator<Item = (&'a [f64], f64)>) -> Self {
        let pts: Vec<(&[f64], f64)> = points.into_iter().collect();
        let np = pts.len();
        let groups = np.div_ceil(LANES);
        let mut shape4 = vec![[0.0; LANES]; blocks * groups];
        let mut weighted_by_point = vec![0.0; blocks * np];
        for (q, (s, w)) in pts.iter().enumerate() {
            for b in 0..blocks {
                shape4[(q / LANES) * blocks + b][q % LANES] = s[b];
                weighted_by_point[q * blocks + b] = w * s[b];
            }
        }
        Self {
            blocks,
            shape4,
            weighted_by_point,
            weight: pts.iter().map(|p| p.1).collect(),
        }
    }

    /// Number of points.
    pub fn points(&self) -> usize {
        self.weight.len()
    }

    /// Number of blocks.
    pub fn blocks(&self) -> usize {
        self.blocks
    }
}

/// The sums `x_q = Σ_b s_b(q) e_b` (`D` components) of every point of a [`BlockQuadrature`]
/// into `out` (structure of arrays, one `Vec` per component, sized to the points), as a
/// [`mbd_core::simd::Kernel`]: the positions `r_q` for `e` the element coordinates, the
/// velocities `ṙ_q` for `e = ė`. The points go in groups of [`LANES`] whose `D` sums stay in
/// registers over the blocks (the earlier loop added each block's term into the stored arrays,
/// a load and a store per term); every sum takes its terms in the same order, block by block
/// from `b = 0`, so both give the same bits.
struct BlockPositions<'a, const D: usize> {
    quad: &'a BlockQuadrature,
    e: &'a [f64],
    out: &'a mut [Vec<f64>; D],
}

impl<const D: usize> mbd_core::simd::Kernel for BlockPositions<'_, D> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        let (nb, np) = (self.quad.blocks, self.quad.points());
        for (j, sg) in self.quad.shape4.chunks_exact(nb).enumerate() {
            let mut acc = [[0.0; LANES]; D];
            for (b, s) in sg.iter().enumerate() {
                for (i, a) in acc.iter_mut().enumerate() {
                    let eb = self.e[D * b + i];
                    for l in 0..LANES {
                        a[l] += s[l] * eb;
                    }
                }
            }
            let (q0, q1) = (j * LANES, ((j + 1) * LANES).min(np));
            for (o, a) in self.out.iter_mut().zip(&acc) {
                o[q0..q1].copy_from_slice(&a[..q1 - q0]);
            }
        }
    }
}

/// The force-only [`element_contact`] (no Jacobians, no records) of an element with block shape
/// functions and coordinates `e`, velocities `edot` (`D` per block), evaluated as a batch: the
/// positions `r_q = Σ_b s_b(q) e_b` of all points and the surface's
/// [`Surface::closest_values`] for all of them; when none is in contact (`gap ≤ 0`) the element
/// ends there, with `Q_c`, the moment and the reaction zero and no active point, as
/// [`element_contact`] ends it. Otherwise the velocities, the forces of
/// [`crate::point_force_at`] of all points as structure-of-arrays loops
/// ([`ContactDim::batch_forces`]), then `Q_c = Σ w Sᵀ f` over the points in contact
/// (vectorised over the blocks) with the moment and the reaction as in [`element_contact`]
/// (Kerkkänen (4.43)–(4.45)). The same operations per point, and every sum over the points in
/// the same order as [`element_contact`] with the points' [`BlockShape`]s.
pub fn element_forces_blocks<const D: usize, S, NL, FL>(
    surface: &S, normal: &NL, friction: &FL, quad: &BlockQuadrature, e: &[f64], edot: &[f64],
    out: &mut ElementContact<D>,
) where
    Dim<D>: ContactDim<D>,
    S: Surface<D> + ?Sized,
    NL: NormalLaw + ?Sized,
    FL: FrictionLaw + ?Sized,
{
    debug_assert_eq!(D * quad.blocks, out.ndof);
    out.clear(false);
    let (nb, np) = (quad.blocks, quad.points());
    let sc = &mut out.soa;
    for i in 0..D {
        sc.position[i].resize(np, 0.0);
        sc.velocity[i].resize(np, 0.0);
    }
    mbd_core::simd::dispatch(BlockPositions {
        quad,
        e,
        out: &mut sc.position,
    });
    surface.closest_values(&sc.position, &mut sc.values);
    sc.active.clear();
    sc.active
        .extend((0..np).filter(|&q| sc.values.gap[q] <= 0.0));
    if sc.active.is_empty() {
        // no point in contact: `out` stays as cleared (Q_c = 0, no moment, no reaction)
        return;
    }
    mbd_core::simd::dispatch(BlockPositions {
        quad,
        e: edot,
        out: &mut sc.velocity,
    });
    <Dim<D>>::batch_forces(
        normal,
        friction,
        &sc.values,
        &sc.velocity,
        &mut sc.work,
        &mut sc.force,
    );
    // Q_c = Σ_q w_q Sᵀ f_q over the points in contact, in point order for every entry (so the
    // sums of the point-by-point loop), vectorised over the blocks
    sc.acc.clear();
    sc.acc.resize(D * nb, 0.0);
    mbd_core::simd::dispatch(BlockScatter::<D> {
        quad,
        active: &sc.active,
        force: &sc.force,
        acc: &mut sc.acc,
    });
    for b in 0..nb {
        for i in 0..D {
            out.q[D * b + i] = sc.acc[i * nb + b];
        }
    }
    let c = surface.center();
    out.active_points = sc.active.len();
    for &q in &sc.active {
        let col = |a: &[Vec<f64>; D]| SVector::<f64, D>::from_fn(|i, _| a[i][q]);
        let (f, w) = (col(&sc.force), quad.weight[q]);
        out.reaction -= f * w;
        let arm = Point::<f64, D>::from(col(&sc.position)) - c;
        out.moment -= <Dim<D>>::cross(&arm, &f) * w;
    }
}

/// `acc[i · blocks + b] = Σ_q w_q s_b(q) f_i(q)` over the `active` points in their order, as
/// a [`mbd_core::simd::Kernel`] (the innermost loop runs over the blocks). With
/// [`MAX_BLOCKS`] blocks (the plate) the `D × MAX_BLOCKS` sums stay in registers over the
/// points (the general loop adds each point's term into the stored sums, component by
/// component); every sum takes its terms in the same order, point by point, so both give the
/// same bits.
struct BlockScatter<'a, const D: usize> {
    quad: &'a BlockQuadrature,
    active: &'a [usize],
    force: &'a [Vec<f64>; D],
    acc: &'a mut [f64],
}

impl<const D: usize> mbd_core::simd::Kernel for BlockScatter<'_, D> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        let nb = self.quad.blocks;
        if nb == MAX_BLOCKS {
            let mut sums = [[0.0; MAX_BLOCKS]; D];
            for &q in self.active {
                let ws: &[f64; MAX_BLOCKS] = self.quad.weighted_by_point
                    [q * MAX_BLOCKS..(q + 1) * MAX_BLOCKS]
                    .try_into()
                    .expect("MAX_BLOCKS values");
                for (s, fi) in sums.iter_mut().zip(self.force) {
                    let f = fi[q];
                    for (a, &w) in s.iter_mut().zip(ws) {
                        *a += f * w;
                    }
                }
            }
            for (acc, s) in self.acc.chunks_exact_mut(nb).zip(&sums) {
                acc.copy_from_slice(s);
            }
            return;
        }
        for (i, acc) in self.acc.chunks_exact_mut(nb).enumerate() {
            let fi = &self.force[i];
            for &q in self.active {
                let f = fi[q];
                let ws = &self.quad.weighted_by_point[q * nb..(q + 1) * nb];
                for (a, &w) in acc.iter_mut().zip(ws) {
                    *a += f * w;
                }
            }
        }
    }
}

/// A distributed contact pairing along line elements: obstacle, laws (per unit length) and
/// Gauss rule.
#[derive(Debug, Clone)]
pub struct LineContact<S, NL, FL> {
    /// Obstacle.
    pub surface: S,
    /// Normal law (per unit length).
    pub normal: NL,
    /// Friction law (per unit length).
    pub friction: FL,
    /// Gauss rule along the element (Kerkkänen: 5, 7 or 11 points give identical results).
    pub rule: GaussRule,
}

impl<S, NL: NormalLaw, FL: FrictionLaw> LineContact<S, NL, FL> {
    /// Contact of one line element of length `length` \[m\] whose centreline shape functions are
    /// `shape(ξ, N)` (`blocks` values, `ξ = x/l`), with coordinates `e` and velocities `edot`
    /// (`D` per block). Fills `out` (forces always; Jacobians when `jacobian`), appends point
    /// records to `records` when given.
    #[allow(clippy::too_many_arguments)]
    pub fn element<const D: usize>(
        &self, length: f64, blocks: usize, shape: impl Fn(f64, &mut [f64]), e: &[f64],
        edot: &[f64], jacobian: bool, out: &mut ElementContact<D>,
        records: Option<&mut Vec<ContactRecord<D>>>,
    ) where
        Dim<D>: ContactDim<D>,
        S: Surface<D>,
    {
        self.element_on(
            &self.surface,
            &self.friction,
            length,
            blocks,
            shape,
            e,
            edot,
            jacobian,
            out,
            records,
        );
    }

    /// As [`LineContact::element`] but against `surface` with the friction law `friction`
    /// instead of `self.surface` and `self.friction`: an obstacle whose state (e.g. a pulley's
    /// angular velocity) changes between calls, or with a friction law of its own (e.g. the
    /// grooved pulleys of a multi-ribbed belt), without rebuilding the pairing.
    #[allow(clippy::too_many_arguments)]
    pub fn element_on<const D: usize>(
        &self, surface: &S, friction: &FL, length: f64, blocks: usize,
        shape: impl Fn(f64, &mut [f64]), e: &[f64], edot: &[f64], jacobian: bool,
        out: &mut ElementContact<D>, records: Option<&mut Vec<ContactRecord<D>>>,
    ) where
        Dim<D>: ContactDim<D>,
        S: Surface<D>,
    {
        debug_assert!(blocks <= MAX_BLOCKS && out.ndof == D * blocks);
        let points = self.rule.iter().map(|(xi, wq)| {
            let mut s = BlockShape {
                values: [0.0; MAX_BLOCKS],
                blocks,
            };
            shape(xi, &mut s.values[..blocks]);
            let mut p = Point::<f64, D>::origin();
            let mut v = SVector::<f64, D>::zeros();
            for k in 0..blocks {
                for i in 0..D {
                    p[i] += s.values[k] * e[D * k + i];
                    v[i] += s.values[k] * edot[D * k + i];
                }
            }
            QuadPoint {
                position: p,
                velocity: v,
                shape: s,
                weight: wq * length,
            }
        });
        element_contact(
            surface,
            &self.normal,
            friction,
            points,
            jacobian,
            out,
            records,
        );
    }
}

/// A distributed contact pairing whose quadrature points the caller supplies (surface elements,
/// e.g. the thin-plate belt of Kerkkänen ch. 4): obstacle and laws (per unit area).
#[derive(Debug, Clone)]
pub struct SurfaceContact<S, NL, FL> {
    /// Obstacle.
    pub surface: S,
    /// Normal law (pressure: penalty \[N/m³\], damping \[N·s/m³\]).
    pub normal: NL,
    /// Friction law (traction per unit area).
    pub friction: FL,
}

impl<S, NL: NormalLaw, FL: FrictionLaw> SurfaceContact<S, NL, FL> {
    /// Contact of one element given by its quadrature `points` against `self.surface`; see
    /// [`element_contact`] (which takes the obstacle separately, for an obstacle whose state
    /// changes between calls).
    pub fn element<const D: usize, Sh: ShapeMatrix<D>>(
        &self, points: impl IntoIterator<Item = QuadPoint<D, Sh>>, jacobian: bool,
        out: &mut ElementContact<D>, records: Option<&mut Vec<ContactRecord<D>>>,
    ) where
        Dim<D>: ContactDim<D>,
        S: Surface<D>,
    {
        element_contact(
            &self.surface,
            &self.normal,
            &self.friction,
            points,
            jacobian,
            out,
            records,
        );
    }
}

#[cfg(test)]
mod tests;
