//! The ANCF thin (Kirchhoff) plate element: constant mass matrix, membrane and bending strain
//! energy with exact forces and tangent (Kerkkänen §4.3, (4.14)-(4.19)).

use super::energy::{self, LocalDerivatives, NU};
use super::shape::{PlateShape, ShapeValues};
use crate::autodiff::{Hyper, Real};
use crate::error::{AncfError, invalid};
use crate::material::Material;
use contact::GaussRule;
use faer::Mat;

/// Number of element coordinates: 4 nodes × `[r, r_x, r_y]` × 3 components (Kerkkänen (4.15)).
pub const PLATE_NDOF: usize = 36;

/// A rectangular four-node ANCF thin-plate element of size `a × b` \[m\], reference state flat and
/// stress-free in the element's `x, y` plane.
///
/// Element coordinates are ordered node by node (A, B, C, D) as `[r, r_x, r_y]` with three
/// Cartesian components each (Kerkkänen (4.14), (4.15)); index `9·node + 3·kind + component`.
///
/// Two choices follow the reading note (§3.6) rather than the print:
/// - the membrane energy (4.16) is the standard plane-stress form
///   `E h / (2(1 − ν²)) ∫ [(ε_xx + ε_yy)² − 2(1 − ν)(ε_xx ε_yy − ε_xy²)] dA` (the printed
///   `(ε_xx ε_yy − ¼ ε_xy)²` is a typo: it is not quadratic in the strains);
/// - the bending rigidity of (4.17) is Kirchhoff's `D = E h³ / (12(1 − ν²))` (the print omits
///   `1 − ν²`; the two agree for ν = 0).
#[derive(Debug, Clone, PartialEq)]
pub struct ThinPlate {
    shape: PlateShape,
    thickness: f64,
    material: Material,
    bending: bool,
    /// Gauss points of the energy quadrature: shape values and weight × area \[m²\].
    points: Vec<(ShapeValues, f64)>,
    /// The same points' `S_x`, `S_y` as structure of arrays (membrane forces).
    membrane: MembranePoints,
}

/// Points per group of [`ThinPlate`]'s membrane forces: one AVX2 vector of `f64`.
const LANES: usize = 4;

/// The energy quadrature's first derivatives laid out for [`ThinPlate`]'s membrane forces over
/// the Gauss points in groups of [`LANES`]: `dx[12 j + k][l] = ∂S_k/∂x` at point `g = 4j + l`
/// (the last group padded with zeros), `dy` the same for `∂S_k/∂y`, and `wd[2g + p][k] =
/// −w_g D_p[k]` (`D_0 = S_x`, `D_1 = S_y`, `w_g` the weight × area), the factor of the scatter
/// `Q_e += −w_g D_pᵀ ∂W/∂r_p` (Kerkkänen (2.20)).
#[derive(Debug, Clone, PartialEq)]
struct MembranePoints {
    dx: Vec<[f64; LANES]>,
    dy: Vec<[f64; LANES]>,
    wd: Vec<[f64; 12]>,
}

impl MembranePoints {
    fn new(points: &[(ShapeValues, f64)]) -> Self {
        let groups = points.len().div_ceil(LANES);
        let (mut dx, mut dy) = (
            vec![[0.0; LANES]; 12 * groups],
            vec![[0.0; LANES]; 12 * groups],
        );
        let mut wd = Vec::with_capacity(2 * points.len());
        for (g, (sv, w)) in points.iter().enumerate() {
            for k in 0..12 {
                dx[12 * (g / LANES) + k][g % LANES] = sv.sx[k];
                dy[12 * (g / LANES) + k][g % LANES] = sv.sy[k];
            }
            // the scatter's `scale · D_p[k]` with scale = −w, the same product
            wd.push(std::array::from_fn(|k| -w * sv.sx[k]));
            wd.push(std::array::from_fn(|k| -w * sv.sy[k]));
        }
        Self { dx, dy, wd }
    }
}

impl ThinPlate {
    /// An `a × b` element \[m\] of thickness `h` \[m\]; `bending = false` keeps only the membrane
    /// energy (Kerkkänen's Model 2); `gauss` points per direction for the energy (≥ 2; the
    /// thesis does not state its rule, 5 is a safe default).
    pub fn new(
        a: f64, b: f64, thickness: f64, material: Material, bending: bool, gauss: usize,
    ) -> Result<Self, AncfError> {
        let shape = PlateShape::new(a, b)?;
        material.validate()?;
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(invalid(
                "plate element: thickness",
                format!("must be a positive length in m, got {thickness}"),
            ));
        }
        if !(2..=20).contains(&gauss) {
            return Err(invalid(
                "plate element: gauss",
                format!("needs 2 to 20 points per direction, got {gauss}"),
            ));
        }
        let rule = GaussRule::new(gauss);
        let mut points = Vec::with_capacity(gauss * gauss);
        for (xi, wx) in rule.iter() {
            for (eta, wy) in rule.iter() {
                points.push((shape.eval(xi * a, eta * b), wx * wy * a * b));
            }
        }
        let membrane = MembranePoints::new(&points);
        Ok(Self {
            shape,
            thickness,
            material,
            bending,
            points,
            membrane,
        })
    }

    /// Shape functions of the element.
    pub fn shape(&self) -> &PlateShape {
        &self.shape
    }

    /// Thickness `h` \[m\].
    pub fn thickness(&self) -> f64 {
        self.thickness
    }

    /// Material.
    pub fn material(&self) -> &Material {
        &self.material
    }

    /// Whether the bending energy (4.17) is included.
    pub fn bending(&self) -> bool {
        self.bending
    }

    /// Position `r(x, y) = S(x, y) e` \[m\] of the mid-surface point at local `(x, y)` \[m\].
    pub fn position(&self, e: &[f64], x: f64, y: f64) -> [f64; 3] {
        let s = self.shape.eval(x, y).s;
        let mut r = [0.0; 3];
        for k in 0..12 {
            for c in 0..3 {
                r[c] += s[k] * e[3 * k + c];
            }
        }
        r
    }

    /// Constant consistent mass matrix `M = ρ h ∫_A SᵀS dA` (Kerkkänen (2.26) with `dV = h dA`),
    /// 36 × 36, integrated exactly (4 × 4 Gauss points for the degree-6 products).
    pub fn mass_matrix(&self) -> Mat<f64> {
        let (a, b) = (self.shape.a(), self.shape.b());
        let rule = GaussRule::new(4);
        let rho_h = self.material.density * self.thickness;
        let mut m = Mat::<f64>::zeros(PLATE_NDOF, PLATE_NDOF);
        for (xi, wx) in rule.iter() {
            for (eta, wy) in rule.iter() {
                let s = self.shape.eval(xi * a, eta * b).s;
                let w = rho_h * wx * wy * a * b;
                for k in 0..12 {
                    for l in 0..12 {
                        let v = w * s[k] * s[l];
                        for c in 0..3 {
                            m[(3 * k + c, 3 * l + c)] += v;
                        }
                    }
                }
            }
        }
        m
    }

    /// Generalized gravity force `Q_g = ρ h ∫_A Sᵀ g dA` \[N\] for the acceleration `g` \[m/s²\].
    pub fn gravity_forces(&self, g: [f64; 3]) -> [f64; PLATE_NDOF] {
        let rho_h = self.material.density * self.thickness;
        let mut q = [0.0; PLATE_NDOF];
        for (sv, w) in &self.points {
            for k in 0..12 {
                for c in 0..3 {
                    q[3 * k + c] += rho_h * w * sv.s[k] * g[c];
                }
            }
        }
        q
    }

    /// Strain energy `U = U^ε + U^κ` \[J\], Kerkkänen (4.16), (4.17), (4.19).
    pub fn strain_energy(&self, e: &[f64]) -> f64 {
        let mut u = 0.0;
        for (sv, w) in &self.points {
            let k: [f64; NU] = gather(sv, e);
            u += w * self.density(&k);
        }
        u
    }

    /// Elastic forces `Q_e = −(∂U/∂e)ᵀ` \[N\] (Kerkkänen (2.20)) into `q` (36 entries), from the
    /// analytic gradient of the energy density ([`super::energy`]).
    pub fn elastic_forces(&self, e: &[f64], q: &mut [f64]) {
        // compiled for the machine's vector width (`mbd_core::simd`, the same bits)
        mbd_core::simd::dispatch(PlateForces { plate: self, e, q });
    }

    /// The body of [`ThinPlate::elastic_forces`] ([`PlateForces`]): the membrane-only plate by
    /// [`ThinPlate::membrane_forces_batch`], the plate with bending point by point.
    #[inline(always)]
    fn elastic_forces_kernel(&self, e: &[f64], q: &mut [f64]) {
        if self.bending {
            self.elastic_forces_pointwise(e, q);
        } else {
            self.membrane_forces_batch(e, q);
        }
    }

    /// Membrane forces `Q_e = −Σ_g w_g [S_x; S_y]ᵀ ∂W_m/∂(r_x, r_y)` (Kerkkänen (2.20) with the
    /// membrane density (4.16)) over the Gauss points in groups of [`LANES`]: per group the
    /// gathers `r_x = S_x e`, `r_y = S_y e` and the density's gradient (`N_x r_x + ½ N_xy r_y`,
    /// `N_y r_y + ½ N_xy r_x` with `N_x = C(2ε_xx + 2ν ε_yy)`, `N_y = C(2ε_yy + 2ν ε_xx)`,
    /// `N_xy = 4C(1 − ν) ε_xy`, `C = E h / (2(1 − ν²))`) one point per vector lane, eight
    /// groups at a time, then their scatter into the `3 × 12` force sums, held as nine vectors
    /// that stay in registers over all the points (the earlier chunked loop of this kernel kept
    /// its sums and the gathered slopes in memory, a load and a store per term). Each point's quantities and each force entry's sum over the
    /// points come out of the same operations in the same order as the point-by-point pass
    /// (`ThinPlate::elastic_forces_pointwise`): the gathers over `k = 0..12`, the sums over the
    /// points, then `S_x` before `S_y`; so the two give the same bits.
    #[inline(always)]
    fn membrane_forces_batch(&self, e: &[f64], q: &mut [f64]) {
        let m = &self.membrane;
        let np = self.points.len();
        let (ym, nu, h) = (self.material.young, self.material.poisson, self.thickness);
        let cm = ym * h / (2.0 * (1.0 - nu * nu));
        let e: &[f64; PLATE_NDOF] = e[..PLATE_NDOF].try_into().expect("36 coordinates");
        // the force sums, q transposed in vectors: qt[c][v][i] = Q[3(4v + i) + c]
        let mut qt = [[[0.0; LANES]; 3]; 3];
        let groups = m.dx.len() / 12;
        // CHUNK groups at a time: their gradients first, then their scatter
        const CHUNK: usize = 8;
        for j0 in (0..groups).step_by(CHUNK) {
            let nj = (groups - j0).min(CHUNK);
            let mut grs = [[[0.0; LANES]; 6]; CHUNK];
            for (jj, gr) in grs.iter_mut().enumerate().take(nj) {
                let j = j0 + jj;
                let (gx, gy) = (&m.dx[12 * j..12 * j + 12], &m.dy[12 * j..12 * j + 12]);
                // r_x, r_y of the group's points: u[c] = r_x[c], u[3 + c] = r_y[c], one per lane
                let mut u = [[0.0; LANES]; 6];
                for k in 0..12 {
                    let (dxk, dyk) = (&gx[k], &gy[k]);
                    for c in 0..3 {
                        let ek = e[3 * k + c];
                        for l in 0..LANES {
                            u[c][l] += dxk[l] * ek;
                            u[3 + c][l] += dyk[l] * ek;
                        }
                    }
                }
                for l in 0..LANES {
                    let rx = [u[0][l], u[1][l], u[2][l]];
                    let ry = [u[3][l], u[4][l], u[5][l]];
                    let [nx, ny, nxy] = energy::membrane_resultants(&rx, &ry, cm, nu);
                    for c in 0..3 {
                        // `0.0 +`: the pointwise pass adds into a zeroed gradient
                        gr[c][l] = 0.0 + (nx * rx[c] + 0.5 * nxy * ry[c]);
                        gr[3 + c][l] = 0.0 + (ny * ry[c] + 0.5 * nxy * rx[c]);
                    }
                }
            }
            // the scatter, point by point and S_x before S_y, into the 3 × 3 vector sums
            #[cfg(target_arch = "x86_64")]
            if let Some(simd) = pulp::x86::V3::try_new() {
                scatter_v3(simd, &m.wd, &grs[..nj], j0, np, &mut qt);
                continue;
            }
            for (jj, gr) in grs.iter().enumerate().take(nj) {
                let j = j0 + jj;
                for l in 0..LANES.min(np - LANES * j) {
                    let g = LANES * j + l;
                    for p in 0..2 {
                        let wd = &m.wd[2 * g + p];
                        // constant indices, so that the sums stay in registers
                        #[allow(clippy::needless_range_loop)]
                        for c in 0..3 {
                            let gv = gr[3 * p + c][l];
                            for v in 0..3 {
                                for i in 0..LANES {
                                    qt[c][v][i] += wd[LANES * v + i] * gv;
                                }
                            }
                        }
                    }
                }
            }
        }
        for k in 0..12 {
            for c in 0..3 {
                q[3 * k + c] = qt[c][k / LANES][k % LANES];
            }
        }
    }

    /// Elastic forces point by point (gather, density gradient, scatter at each Gauss point):
    /// the plate with bending, and the membrane batch's reference in the tests.
    #[inline(always)]
    fn elastic_forces_pointwise(&self, e: &[f64], q: &mut [f64]) {
        q[..PLATE_NDOF].fill(0.0);
        let mut ld = LocalDerivatives::zero();
        let blocks = self.derivative_blocks();
        for (sv, w) in &self.points {
            let u: [f64; NU] = gather_blocks(sv, e, blocks);
            ld.g = [0.0; NU];
            self.local_derivatives(&u, false, &mut ld);
            scatter_gradient_blocks(sv, -w, &ld.g, q, blocks);
        }
    }

    /// Elastic forces into `q` and the tangent stiffness `K = ∂²U/∂e²` \[N/m\] into `k`
    /// (36 × 36), exact: analytic gradient and Hessian of the energy density with respect to
    /// the 15 local kinematic quantities ([`super::energy`]), chained through the constant
    /// shape-function derivatives, `K = Σ_g w_g Bᵀ H B` with `B = [S_x; S_y; S_xx; S_xy; S_yy] ⊗ I₃`
    /// (only `S_x`, `S_y` without bending).
    pub fn elastic_tangent(&self, e: &[f64], q: &mut [f64], k: &mut Mat<f64>) {
        // compiled for the machine's vector width (`mbd_core::simd`, the same bits)
        mbd_core::simd::dispatch(PlateTangent {
            plate: self,
            e,
            q,
            k,
        });
    }

    /// The body of [`ThinPlate::elastic_tangent`] ([`PlateTangent`]): `K = Σ_g w_g Bᵀ H B`
    /// row by row. Per Gauss point, `T = H B` (`3·blocks × 36`, `T[r][3l + d] =
    /// Σ_q D_q[l] H[r][3q + d]`, `D = [S_x; S_y; S_xx; S_xy; S_yy]`), then each row `3k + c` of
    /// the upper block triangle gains `w D_p[k] T[3p + c][3k..36]` for every block `p`: one
    /// contiguous multiply–add over up to 36 columns (vectorised) where the earlier loop
    /// (`ThinPlate::elastic_tangent_blockwise`, kept as the tests' reference) added 3 columns at a time. Every entry receives
    /// the same products in the same order (points, then `p`), so the two give the same bits.
    #[inline(always)]
    fn elastic_tangent_kernel(&self, e: &[f64], q: &mut [f64], k: &mut Mat<f64>) {
        q[..PLATE_NDOF].fill(0.0);
        let blocks = self.derivative_blocks();
        let nr = 3 * blocks;
        let mut ld = LocalDerivatives::zero();
        let mut kl = [[0.0; PLATE_NDOF]; PLATE_NDOF];
        // T = H B, row r, column 3l + d
        let mut t = [[0.0; PLATE_NDOF]; NU];
        for (sv, w) in &self.points {
            let u: [f64; NU] = gather_blocks(sv, e, blocks);
            ld.g = [0.0; NU];
            for row in ld.h.iter_mut().take(nr) {
                row[..nr].fill(0.0);
            }
            self.local_derivatives(&u, true, &mut ld);
            scatter_gradient_blocks(sv, -w, &ld.g, q, blocks);
            let d = [&sv.sx, &sv.sy, &sv.sxx, &sv.sxy, &sv.syy];
            for (tr, hr) in t.iter_mut().zip(ld.h.iter()).take(nr) {
                for l in 0..12 {
                    let mut a = [0.0; 3];
                    for (qq, dq) in d.iter().enumerate().take(blocks) {
                        let f = dq[l];
                        if f == 0.0 {
                            continue;
                        }
                        for dd in 0..3 {
                            a[dd] += f * hr[3 * qq + dd];
                        }
                    }
                    tr[3 * l..3 * l + 3].copy_from_slice(&a);
                }
            }
            for kk in 0..12 {
                for (p, dp) in d.iter().enumerate().take(blocks) {
                    let f = w * dp[kk];
                    if f == 0.0 {
                        continue;
                    }
                    for c in 0..3 {
                        let row = &mut kl[3 * kk + c][3 * kk..];
                        let src = &t[3 * p + c][3 * kk..];
                        for (r, s) in row.iter_mut().zip(src) {
                            *r += f * s;
                        }
                    }
                }
            }
        }
        for (i, row) in kl.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                // upper block triangle as summed; the lower one its transpose
                let v = if i / 3 <= j / 3 { *v } else { kl[j][i] };
                k[(i, j)] = v;
            }
        }
    }

    /// The earlier body of [`ThinPlate::elastic_tangent`], summing 3 × 3 blocks `(k, l)`,
    /// `k ≤ l`, three columns at a time: the reference the row-wise kernel is tested against
    /// (same bits). Not used on the simulation path.
    #[cfg(test)]
    fn elastic_tangent_blockwise(&self, e: &[f64], q: &mut [f64], k: &mut Mat<f64>) {
        q[..PLATE_NDOF].fill(0.0);
        k.fill(0.0);
        let blocks = self.derivative_blocks();
        let nr = 3 * blocks;
        let mut ld = LocalDerivatives::zero();
        let mut kl = [[0.0; PLATE_NDOF]; PLATE_NDOF];
        // A_l = Σ_q d_q[l] H[:, 3q..3q+3] for one shape function l (nr × 3)
        let mut al = [[0.0; 3]; NU];
        for (sv, w) in &self.points {
            let u: [f64; NU] = gather_blocks(sv, e, blocks);
            ld.g = [0.0; NU];
            for row in ld.h.iter_mut().take(nr) {
                row[..nr].fill(0.0);
            }
            self.local_derivatives(&u, true, &mut ld);
            scatter_gradient_blocks(sv, -w, &ld.g, q, blocks);
            let d = [&sv.sx, &sv.sy, &sv.sxx, &sv.sxy, &sv.syy];
            for l in 0..12 {
                for (r, a) in al.iter_mut().enumerate().take(nr) {
                    *a = [0.0; 3];
                    for (qq, dq) in d.iter().enumerate().take(blocks) {
                        let f = dq[l];
                        if f == 0.0 {
                            continue;
                        }
                        for dd in 0..3 {
                            a[dd] += f * ld.h[r][3 * qq + dd];
                        }
                    }
                }
                // the blocks (kk, l) with kk ≤ l only: K is symmetric (a Hessian), the blocks
                // below the diagonal are mirrored at the end
                for kk in 0..=l {
                    for (p, dp) in d.iter().enumerate().take(blocks) {
                        let f = w * dp[kk];
                        if f == 0.0 {
                            continue;
                        }
                        for c in 0..3 {
                            let a = &al[3 * p + c];
                            let row = &mut kl[3 * kk + c];
                            for dd in 0..3 {
                                row[3 * l + dd] += f * a[dd];
                            }
                        }
                    }
                }
            }
        }
        for (i, row) in kl.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                // upper block triangle as summed; the lower one its transpose
                let v = if i / 3 <= j / 3 { *v } else { kl[j][i] };
                k[(i, j)] = v;
            }
        }
    }

    /// The tangent of [`ThinPlate::elastic_tangent`] by second-order automatic differentiation
    /// of the energy density ([`crate::autodiff::Hyper`]): the independent reference the
    /// analytic derivatives are tested against (not used on the simulation path).
    pub fn elastic_tangent_autodiff(&self, e: &[f64], q: &mut [f64], k: &mut Mat<f64>) {
        q[..PLATE_NDOF].fill(0.0);
        k.fill(0.0);
        let mut d = [[0.0; 12]; 5];
        for (sv, w) in &self.points {
            let kin: [f64; NU] = gather(sv, e);
            let vars: [Hyper<NU>; NU] = std::array::from_fn(|i| Hyper::linear(kin[i], &[(i, 1.0)]));
            let h = self.density(&vars);
            scatter_gradient(sv, -w, &h.g, q);
            d[0] = sv.sx;
            d[1] = sv.sy;
            d[2] = sv.sxx;
            d[3] = sv.sxy;
            d[4] = sv.syy;
            let blocks = if self.bending { 5 } else { 2 };
            for kk in 0..12 {
                for ll in 0..12 {
                    let mut blk = [[0.0; 3]; 3];
                    for p in 0..blocks {
                        let dpk = d[p][kk];
                        if dpk == 0.0 {
                            continue;
                        }
                        for qq in 0..blocks {
                            let f = dpk * d[qq][ll];
                            for c in 0..3 {
                                for dd in 0..3 {
                                    blk[c][dd] += f * h.h[3 * p + c][3 * qq + dd];
                                }
                            }
                        }
                    }
                    for c in 0..3 {
                        for dd in 0..3 {
                            k[(3 * kk + c, 3 * ll + dd)] += w * blk[c][dd];
                        }
                    }
                }
            }
        }
    }

    /// Analytic derivatives of the energy density at the local kinematics `u` added into `out`
    /// (gradient; Hessian when `jac`).
    #[inline(always)]
    fn local_derivatives(&self, u: &[f64; NU], jac: bool, out: &mut LocalDerivatives) {
        let (e, nu, h) = (self.material.young, self.material.poisson, self.thickness);
        energy::membrane(u, e * h / (2.0 * (1.0 - nu * nu)), nu, jac, out);
        if self.bending {
            energy::bending(u, self.rigidity(), nu, jac, out);
        }
    }

    /// Number of shape-derivative blocks the energy density depends on: `r_x`, `r_y` (membrane,
    /// (4.16)), and `r_xx`, `r_xy`, `r_yy` with bending (4.17).
    fn derivative_blocks(&self) -> usize {
        if self.bending { 5 } else { 2 }
    }

    /// Bending rigidity `D = E h³ / (12 (1 − ν²))` \[N·m\] (see the type documentation).
    pub fn rigidity(&self) -> f64 {
        let (e, nu, h) = (self.material.young, self.material.poisson, self.thickness);
        e * h * h * h / (12.0 * (1.0 - nu * nu))
    }

    /// Membrane section force \[N\] transmitted across the material line `x = const` of the
    /// element, `F = ∫_0^b ∂W_m/∂r_x dy` (the first Piola–Kirchhoff membrane resultant times the
    /// reference width, `W_m` the membrane density of (4.16)), by `points`-point Gauss
    /// quadrature over the width. Its component along the belt tangent is the axial force the
    /// belt actually carries, which the strain-based tensions (4.9)–(4.11) approximate.
    pub fn membrane_section_force(&self, e: &[f64], x: f64, points: usize) -> [f64; 3] {
        let (ym, nu, h) = (self.material.young, self.material.poisson, self.thickness);
        let cm = ym * h / (2.0 * (1.0 - nu * nu));
        let b = self.shape.b();
        let mut f = [0.0; 3];
        let mut ld = LocalDerivatives::zero();
        for (eta, w) in GaussRule::new(points.max(1)).iter() {
            let sv = self.shape.eval(x, eta * b);
            let u: [f64; NU] = gather(&sv, e);
            ld.g = [0.0; NU];
            energy::membrane(&u, cm, nu, false, &mut ld);
            for c in 0..3 {
                f[c] += w * b * ld.g[c];
            }
        }
        f
    }

    /// The local gradients `(r, r_x, r_y)` at `(x, y)` \[m, -, -\].
    pub fn kinematics(&self, e: &[f64], x: f64, y: f64) -> [[f64; 3]; 3] {
        let sv = self.shape.eval(x, y);
        let mut out = [[0.0; 3]; 3];
        for k in 0..12 {
            for c in 0..3 {
                out[0][c] += sv.s[k] * e[3 * k + c];
                out[1][c] += sv.sx[k] * e[3 * k + c];
                out[2][c] += sv.sy[k] * e[3 * k + c];
            }
        }
        out
    }

    /// Strain-energy density per unit area \[J/m²\] from `u = [r_x, r_y, r_xx, r_xy, r_yy]`:
    /// membrane (4.16, standard form) plus bending (4.17) with the curvatures (4.18)
    /// `κ_ij = r_,ijᵀ n / (‖n‖ ‖r_,i‖ ‖r_,j‖)`, `n = r_,x × r_,y`.
    fn density<T: Real>(&self, u: &[T; NU]) -> T {
        let nu = self.material.poisson;
        let e = self.material.young;
        let h = self.thickness;
        let rx = [u[0], u[1], u[2]];
        let ry = [u[3], u[4], u[5]];
        let half = T::cst(0.5);
        let one = T::cst(1.0);
        let exx = (dot(&rx, &rx) - one) * half;
        let eyy = (dot(&ry, &ry) - one) * half;
        let exy = dot(&rx, &ry) * half;
        let cm = e * h / (2.0 * (1.0 - nu * nu));
        let tr = exx + eyy;
        let mut w = (tr * tr - (exx * eyy - exy * exy).scale(2.0 * (1.0 - nu))).scale(cm);
        if self.bending {
            let rxx = [u[6], u[7], u[8]];
            let rxy = [u[9], u[10], u[11]];
            let ryy = [u[12], u[13], u[14]];
            let n = cross(&rx, &ry);
            let inv_n = dot(&n, &n).sqrt().recip();
            let lxx = dot(&rx, &rx);
            let lyy = dot(&ry, &ry);
            let kxx = dot(&rxx, &n) * inv_n * lxx.recip();
            let kyy = dot(&ryy, &n) * inv_n * lyy.recip();
            let kxy = dot(&rxy, &n) * inv_n * (lxx * lyy).sqrt().recip();
            let dflex = e * h * h * h / (12.0 * (1.0 - nu * nu));
            let tk = kxx + kyy;
            w = w + (tk * tk - (kxx * kyy - kxy * kxy).scale(2.0 * (1.0 - nu))).scale(0.5 * dflex);
        }
        w
    }
}

fn dot<T: Real>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross<T: Real>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Local kinematic quantities `[r_x, r_y, r_xx, r_xy, r_yy]` from the element coordinates.
fn gather(sv: &ShapeValues, e: &[f64]) -> [f64; NU] {
    gather_blocks(sv, e, 5)
}

/// [`ThinPlate::elastic_tangent`] as a [`mbd_core::simd::Kernel`].
struct PlateTangent<'a> {
    plate: &'a ThinPlate,
    e: &'a [f64],
    q: &'a mut [f64],
    k: &'a mut Mat<f64>,
}

impl mbd_core::simd::Kernel for PlateTangent<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        self.plate.elastic_tangent_kernel(self.e, self.q, self.k)
    }
}

/// [`ThinPlate::elastic_forces`] as a [`mbd_core::simd::Kernel`].
struct PlateForces<'a> {
    plate: &'a ThinPlate,
    e: &'a [f64],
    q: &'a mut [f64],
}

impl mbd_core::simd::Kernel for PlateForces<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        self.plate.elastic_forces_kernel(self.e, self.q)
    }
}

/// The scatter of [`ThinPlate::membrane_forces_batch`] with the nine sums held as AVX2 vectors
/// (`pulp`'s `f64x4`), so that they stay in registers over the groups' points: the same
/// products and additions in the same order as the scalar loop (no fused multiply–add), hence
/// the same bits. `grs` are the gradients of the groups `j0, j0 + 1, …` (one point per lane).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn scatter_v3(
    simd: pulp::x86::V3, wd: &[[f64; 12]], grs: &[[[f64; LANES]; 6]], j0: usize, np: usize,
    qt: &mut [[[f64; LANES]; 3]; 3],
) {
    use pulp::f64x4;
    let v = |a: [f64; LANES]| f64x4(a[0], a[1], a[2], a[3]);
    let mut acc = qt.map(|row| row.map(v));
    for (jj, gr) in grs.iter().enumerate() {
        let j = j0 + jj;
        for l in 0..LANES.min(np - LANES * j) {
            let g = LANES * j + l;
            for p in 0..2 {
                let w = &wd[2 * g + p];
                let wv = [
                    f64x4(w[0], w[1], w[2], w[3]),
                    f64x4(w[4], w[5], w[6], w[7]),
                    f64x4(w[8], w[9], w[10], w[11]),
                ];
                for (c, row) in acc.iter_mut().enumerate() {
                    let gv = simd.splat_f64x4(gr[3 * p + c][l]);
                    for (a, w) in row.iter_mut().zip(&wv) {
                        *a = simd.add_f64x4(*a, simd.mul_f64x4(*w, gv));
                    }
                }
            }
        }
    }
    *qt = acc.map(|row| row.map(|a| [a.0, a.1, a.2, a.3]));
}

/// [`gather`] of the first `blocks` derivatives only (2: `r_x`, `r_y`, all the membrane energy
/// needs; the rest stay zero).
#[inline(always)]
fn gather_blocks(sv: &ShapeValues, e: &[f64], blocks: usize) -> [f64; NU] {
    let mut u = [0.0; NU];
    let d = [&sv.sx, &sv.sy, &sv.sxx, &sv.sxy, &sv.syy];
    for (p, dp) in d.iter().enumerate().take(blocks) {
        for k in 0..12 {
            for c in 0..3 {
                u[3 * p + c] += dp[k] * e[3 * k + c];
            }
        }
    }
    u
}

/// `q += scale · Bᵀ g` with `B` the map of [`gather`].
fn scatter_gradient(sv: &ShapeValues, scale: f64, g: &[f64; NU], q: &mut [f64]) {
    scatter_gradient_blocks(sv, scale, g, q, 5)
}

/// [`scatter_gradient`] of the first `blocks` gradient blocks only (the others must be zero:
/// without bending the membrane density has no gradient in `r_xx`, `r_xy`, `r_yy`).
#[inline(always)]
fn scatter_gradient_blocks(
    sv: &ShapeValues, scale: f64, g: &[f64; NU], q: &mut [f64], blocks: usize,
) {
    let d = [&sv.sx, &sv.sy, &sv.sxx, &sv.sxy, &sv.syy];
    for (p, dp) in d.iter().enumerate().take(blocks) {
        for k in 0..12 {
            for c in 0..3 {
                q[3 * k + c] += scale * dp[k] * g[3 * p + c];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strongly deformed, doubly curved state of an `a × b` element.
    fn deformed(a: f64, b: f64) -> [f64; PLATE_NDOF] {
        let mut e = [0.0; PLATE_NDOF];
        for (n, (x, y)) in [(0.0, 0.0), (a, 0.0), (a, b), (0.0, b)].iter().enumerate() {
            e[9 * n] = *x;
            e[9 * n + 1] = *y;
            e[9 * n + 3] = 1.0;
            e[9 * n + 7] = 1.0;
        }
        for (i, v) in e.iter_mut().enumerate() {
            *v += 0.05 * ((1.3 * i as f64).sin() + 0.5 * (0.7 * i as f64).cos());
        }
        e
    }

    // Old formulation: the membrane forces over all points at once give the point-by-point
    // pass's forces to the last bit, for 5 × 5 points (one chunk) and 7 × 7 (two chunks).
    #[test]
    fn membrane_batch_equals_the_pointwise_pass_bit_for_bit() {
        for gauss in [5, 7] {
            let m = Material::new(1.6667e6, 0.3, 166.667).unwrap();
            let el = ThinPlate::new(0.025, 0.04, 0.003, m, false, gauss).unwrap();
            let e = deformed(0.025, 0.04);
            let (mut qn, mut qo) = ([0.0; PLATE_NDOF], [0.0; PLATE_NDOF]);
            el.elastic_forces(&e, &mut qn);
            el.elastic_forces_pointwise(&e, &mut qo);
            for i in 0..PLATE_NDOF {
                assert_eq!(qn[i].to_bits(), qo[i].to_bits(), "gauss {gauss}: Q[{i}]");
            }
        }
    }

    // Old formulation: the row-wise tangent kernel gives the blockwise loop's forces and
    // tangent to the last bit (the same products in the same order), membrane only and with
    // bending, on a strongly deformed element.
    #[test]
    fn row_wise_tangent_equals_the_blockwise_loop_bit_for_bit() {
        for bending in [false, true] {
            let m = Material::new(1.6667e6, 0.3, 166.667).unwrap();
            let el = ThinPlate::new(0.025, 0.04, 0.003, m, bending, 5).unwrap();
            let e = deformed(0.025, 0.04);
            let (mut qn, mut qo) = ([0.0; PLATE_NDOF], [0.0; PLATE_NDOF]);
            let mut kn = Mat::<f64>::zeros(PLATE_NDOF, PLATE_NDOF);
            let mut ko = Mat::<f64>::zeros(PLATE_NDOF, PLATE_NDOF);
            el.elastic_tangent(&e, &mut qn, &mut kn);
            el.elastic_tangent_blockwise(&e, &mut qo, &mut ko);
            for i in 0..PLATE_NDOF {
                assert_eq!(
                    qn[i].to_bits(),
                    qo[i].to_bits(),
                    "bending {bending}: Q[{i}]"
                );
                for j in 0..PLATE_NDOF {
                    assert_eq!(
                        kn[(i, j)].to_bits(),
                        ko[(i, j)].to_bits(),
                        "bending {bending}: K[{i},{j}] = {} vs {}",
                        kn[(i, j)],
                        ko[(i, j)]
                    );
                }
            }
        }
    }

    // Second formulation: the analytic forces and tangent equal the automatic-differentiation
    // derivatives of the same energy density (membrane only and with bending).
    #[test]
    fn analytic_tangent_equals_automatic_differentiation() {
        for bending in [false, true] {
            let m = Material::new(2.1e9, 0.3, 1000.0).unwrap();
            let el = ThinPlate::new(0.3, 0.2, 0.01, m, bending, 4).unwrap();
            let e = deformed(0.3, 0.2);
            let (mut qa, mut qd) = ([0.0; PLATE_NDOF], [0.0; PLATE_NDOF]);
            let mut ka = Mat::<f64>::zeros(PLATE_NDOF, PLATE_NDOF);
            let mut kd = Mat::<f64>::zeros(PLATE_NDOF, PLATE_NDOF);
            el.elastic_tangent(&e, &mut qa, &mut ka);
            el.elastic_tangent_autodiff(&e, &mut qd, &mut kd);
            let mut qf = [0.0; PLATE_NDOF];
            el.elastic_forces(&e, &mut qf);
            let qmax = qd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let kmax = (0..PLATE_NDOF * PLATE_NDOF).fold(0.0f64, |m, k| {
                m.max(kd[(k % PLATE_NDOF, k / PLATE_NDOF)].abs())
            });
            for i in 0..PLATE_NDOF {
                assert!(
                    (qa[i] - qd[i]).abs() < 1e-11 * qmax,
                    "bending {bending}: Q[{i}]"
                );
                assert!(
                    (qf[i] - qd[i]).abs() < 1e-11 * qmax,
                    "bending {bending}: Q[{i}]"
                );
                for j in 0..PLATE_NDOF {
                    assert!(
                        (ka[(i, j)] - kd[(i, j)]).abs() < 1e-11 * kmax,
                        "bending {bending}: K[{i},{j}] = {} vs {}",
                        ka[(i, j)],
                        kd[(i, j)]
                    );
                }
            }
        }
    }
}
