//! Closed-form elastic forces and tangent of the belt element (Kerkkänen §3.1).
//!
//! With `t = r_{c,x}/‖r_{c,x}‖`, `n = Ĩ t` and the curvature-like scalar
//! `k = (r_{c,x} × r_{c,xx})/a`, `a = r_{c,x}ᵀr_{c,x}`, the derivative of the unit tangent is
//! `t_x = k n` and `n_x = −k t`, so the vectors of (3.8)–(3.10) reduce to
//! `r_s = n − sin γ t` and `r_{s,x} = −(k + (sin γ)_x) t − sin γ k n`. The four products of
//! (3.18)–(3.19) are then
//!
//! ```text
//!   b = r_{c,x}ᵀ r_{s,x} = −√a s,    c = r_{s,x}ᵀ r_{s,x} = s² + sin²γ k²,
//!   d = r_{c,x}ᵀ r_s     = −√a sin γ, f = r_{s,x}ᵀ r_s     = sin γ (sin γ)_x,   s = k + (sin γ)_x,
//! ```
//!
//! and the energy per unit length
//!
//! ```text
//!   W = C₁(a − 1)² + C₂(a s² + ½(a − 1)c) + C₃c² + C₄ a sin²γ + C₅ sin²γ (sin γ)_x² + C₆ ε_yy²
//! ```
//!
//! (`C₁ = Eα₁A/8`, `C₂ = Eα₂I₂/2`, `C₃ = Eα₂I₄/8`, `C₄ = k_sGα₂A/2`, `C₅ = k_sGα₂I₂/2`,
//! `C₆ = EA/2`) is a polynomial in `(a, k, sin γ, (sin γ)_x, ε_yy)`. At a Gauss point `a` and
//! `z = r_{c,x} × r_{c,xx}` are quadratic forms of the element coordinates with constant
//! shape-function products, and `sin γ`, `(sin γ)_x`, `ε_yy` are linear in the four nodal
//! scalars `sin γᴵ, sin γᴶ, ‖r_yᴵ‖, ‖r_yᴶ‖` (3.12), (4.36). Forces and the exact tangent are
//! therefore the chain rule through these few scalars: rank-two updates with the gradients of
//! `a` and `z`, constant matrices scaled by `∂W/∂a`, `∂W/∂z`, and the nodal functions' own
//! second derivatives — a few small dense contractions instead of automatic differentiation.
//! The automatic-differentiation energy of [`super::BeltElement`] is the reference it is tested
//! against (to 1e-10).
//!
//! The material law ([`MaterialLaw`]) chooses the energy. St Venant–Kirchhoff is `W` above
//! ((3.18)–(3.19): the Green strain (3.13) with `E`, integrated over the section). The linear
//! law replaces the axial and bending parts by those of a rod linear in the engineering strain
//! `λ − 1` (`λ = √a`) and in the bending strain `s` (the material curvature `k` plus the shear
//! angle's gradient, the curvature measure of Exudyn's `ANCFCable2D`):
//!
//! ```text
//!   W_lin = 4C₁(√a − 1)² + C₂ s² + C₄ a sin²γ + C₅ sin²γ (sin γ)_x² + C₆ ε_yy²
//! ```
//!
//! (`4C₁ = α₁EA/2`, `C₂ = α₂EI₂/2`), so that the axial force is `α₁EA(λ − 1)` at any curvature
//! and the bending moment `α₂EI s` at any stretch; the shear and `ε_yy` terms are the same.
//! Both are written as `W(a, k, sin γ, (sin γ)_x, ε_yy)` ([`density_u`]) and share the chain
//! rule through `k = z/a`.

use crate::shape::CUBIC_BLOCKS;
use ::belt::MaterialLaw;

/// Element coordinates.
pub(crate) const N: usize = 12;

/// Blocks of the centreline shape functions that do not vanish at `y = 0` (`r` and `r_x` of
/// both nodes; the `r_y` blocks carry a factor `y`).
const CENTRE_BLOCKS: [usize; 4] = [0, 1, 3, 4];

/// The element coordinates of [`CENTRE_BLOCKS`] (`a` and `z` depend on these only).
const CENTRE_COORDS: [usize; 8] = [0, 1, 2, 3, 6, 7, 8, 9];

/// Coordinates on which nodal scalar `nd` depends (`sin γᴵ`, `sin γᴶ`: `r_x`, `r_y` of the
/// node; `‖r_yᴵ‖`, `‖r_yᴶ‖`: its `r_y`).
fn support(nd: usize) -> std::ops::Range<usize> {
    match nd {
        0 => 2..6,
        1 => 8..12,
        2 => 4..6,
        _ => 10..12,
    }
}

/// Energy constants `C₁ … C₆` of the module documentation and the material law.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Constants {
    pub c: [f64; 6],
    pub law: MaterialLaw,
}

/// One Gauss point along the element: `ξ`, weight (times `l`), `S_x` and `S_xx` on `y = 0`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct KernelPoint {
    pub xi: f64,
    pub w: f64,
    pub sx: [f64; CUBIC_BLOCKS],
    pub sxx: [f64; CUBIC_BLOCKS],
}

/// Nodal shear angle `sin γ = −r_xᵀr_y/(‖r_x‖‖r_y‖)` and slope norm `‖r_y‖` of one node with
/// their derivatives with respect to `(r_x, r_y)` (4 coordinates) and `r_y` (2).
#[derive(Debug, Clone, Copy, Default)]
struct NodeScalars {
    sg: f64,
    ny: f64,
    dsg: [f64; 4],
    dny: [f64; 2],
    hsg: [[f64; 4]; 4],
    hny: [[f64; 2]; 2],
}

impl NodeScalars {
    fn new(u: [f64; 2], v: [f64; 2], hessian: bool) -> Self {
        let p = u[0] * v[0] + u[1] * v[1];
        let aa = (u[0] * u[0] + u[1] * u[1]).sqrt();
        let bb = (v[0] * v[0] + v[1] * v[1]).sqrt();
        let (ia, ib) = (1.0 / aa, 1.0 / bb);
        let c0 = p * ia * ib;
        let mut s = NodeScalars {
            sg: -c0,
            ny: bb,
            ..Default::default()
        };
        // ∂c₀/∂u = v/(AB) − c₀ u/A², ∂c₀/∂v = u/(AB) − c₀ v/B²
        for i in 0..2 {
            s.dsg[i] = -(v[i] * ia * ib - c0 * u[i] * ia * ia);
            s.dsg[2 + i] = -(u[i] * ia * ib - c0 * v[i] * ib * ib);
            s.dny[i] = v[i] * ib;
        }
        if hessian {
            let (ia3, ib3) = (ia * ia * ia, ib * ib * ib);
            for i in 0..2 {
                for j in 0..2 {
                    let d = if i == j { 1.0 } else { 0.0 };
                    // second derivatives of c₀ = p A⁻¹ B⁻¹
                    let uu = -(v[i] * u[j] + v[j] * u[i]) * ia3 * ib - p * d * ia3 * ib
                        + 3.0 * p * u[i] * u[j] * ia3 * ia * ia * ib;
                    let vv = -(u[i] * v[j] + u[j] * v[i]) * ia * ib3 - p * d * ia * ib3
                        + 3.0 * p * v[i] * v[j] * ia * ib3 * ib * ib;
                    let uv = d * ia * ib - v[i] * v[j] * ia * ib3 - u[i] * u[j] * ia3 * ib
                        + p * u[i] * v[j] * ia3 * ib3;
                    s.hsg[i][j] = -uu;
                    s.hsg[2 + i][2 + j] = -vv;
                    s.hsg[i][2 + j] = -uv;
                    s.hsg[2 + j][i] = -uv;
                    s.hny[i][j] = (d - v[i] * v[j] * ib * ib) * ib;
                }
            }
        }
        s
    }
}

/// Energy per unit length `W` and its first and second derivatives with respect to
/// `x = (a, z, sin γ, (sin γ)_x, ε_yy)` (module documentation).
struct Density {
    w: f64,
    g: [f64; 5],
    h: [[f64; 5]; 5],
}

/// `W` and its first and second derivatives with respect to `u = (a, k, sin γ, (sin γ)_x,
/// ε_yy)` (`k = z/a` held fixed when `a` varies), for the material law of `cst`
/// ([`MaterialLaw`]); the second derivatives only with `hessian`.
fn density_u(cst: &Constants, u: [f64; 5], hessian: bool) -> Density {
    let [c1, c2, c3, c4, c5, c6] = cst.c;
    let [a, k, sg, sgx, eyy] = u;
    let s = k + sgx;
    let mut d = Density {
        w: 0.0,
        g: [0.0; 5],
        h: [[0.0; 5]; 5],
    };
    match cst.law {
        MaterialLaw::StVenantKirchhoff => {
            let c = s * s + sg * sg * k * k;
            let am1 = a - 1.0;
            d.w = c1 * am1 * am1
                + c2 * (a * s * s + 0.5 * am1 * c)
                + c3 * c * c
                + c4 * a * sg * sg
                + c5 * sg * sg * sgx * sgx
                + c6 * eyy * eyy;
            // derivatives of c with respect to (k, sin γ, (sin γ)_x)
            let c_k = 2.0 * s + 2.0 * sg * sg * k;
            let c_sg = 2.0 * sg * k * k;
            let c_sgx = 2.0 * s;
            d.g = [
                2.0 * c1 * am1 + c2 * (s * s + 0.5 * c) + c4 * sg * sg,
                2.0 * c2 * a * s + 0.5 * c2 * am1 * c_k + 2.0 * c3 * c * c_k,
                0.5 * c2 * am1 * c_sg
                    + 2.0 * c3 * c * c_sg
                    + 2.0 * c4 * a * sg
                    + 2.0 * c5 * sg * sgx * sgx,
                2.0 * c2 * a * s
                    + 0.5 * c2 * am1 * c_sgx
                    + 2.0 * c3 * c * c_sgx
                    + 2.0 * c5 * sg * sg * sgx,
                2.0 * c6 * eyy,
            ];
            if hessian {
                let c_kk = 2.0 + 2.0 * sg * sg;
                let c_ksg = 4.0 * sg * k;
                let c_ksgx = 2.0;
                let c_sgsg = 2.0 * k * k;
                let c_sgxsgx = 2.0;
                let h = &mut d.h;
                h[0][0] = 2.0 * c1;
                h[0][1] = 2.0 * c2 * s + 0.5 * c2 * c_k;
                h[0][2] = 0.5 * c2 * c_sg + 2.0 * c4 * sg;
                h[0][3] = 2.0 * c2 * s + 0.5 * c2 * c_sgx;
                h[1][1] = 2.0 * c2 * a + 0.5 * c2 * am1 * c_kk + 2.0 * c3 * (c_k * c_k + c * c_kk);
                h[1][2] = 0.5 * c2 * am1 * c_ksg + 2.0 * c3 * (c_k * c_sg + c * c_ksg);
                h[1][3] =
                    2.0 * c2 * a + 0.5 * c2 * am1 * c_ksgx + 2.0 * c3 * (c_k * c_sgx + c * c_ksgx);
                h[2][2] = 0.5 * c2 * am1 * c_sgsg
                    + 2.0 * c3 * (c_sg * c_sg + c * c_sgsg)
                    + 2.0 * c4 * a
                    + 2.0 * c5 * sgx * sgx;
                h[2][3] = 2.0 * c3 * c_sg * c_sgx + 4.0 * c5 * sg * sgx;
                h[3][3] = 2.0 * c2 * a
                    + 0.5 * c2 * am1 * c_sgxsgx
                    + 2.0 * c3 * (c_sgx * c_sgx + c * c_sgxsgx)
                    + 2.0 * c5 * sg * sg;
                h[4][4] = 2.0 * c6;
            }
        }
        MaterialLaw::Linear => {
            // W = ½α₁EA(λ − 1)² + ½α₂EI s² + shear + ε_yy, λ = √a: ½α₁EA = 4C₁
            let lam = a.sqrt();
            d.w = 4.0 * c1 * (lam - 1.0) * (lam - 1.0)
                + c2 * s * s
                + c4 * a * sg * sg
                + c5 * sg * sg * sgx * sgx
                + c6 * eyy * eyy;
            d.g = [
                4.0 * c1 * (1.0 - 1.0 / lam) + c4 * sg * sg,
                2.0 * c2 * s,
                2.0 * c4 * a * sg + 2.0 * c5 * sg * sgx * sgx,
                2.0 * c2 * s + 2.0 * c5 * sg * sg * sgx,
                2.0 * c6 * eyy,
            ];
            if hessian {
                let h = &mut d.h;
                h[0][0] = 2.0 * c1 / (lam * lam * lam);
                h[0][2] = 2.0 * c4 * sg;
                h[1][1] = 2.0 * c2;
                h[1][3] = 2.0 * c2;
                h[2][2] = 2.0 * c4 * a + 2.0 * c5 * sgx * sgx;
                h[2][3] = 4.0 * c5 * sg * sgx;
                h[3][3] = 2.0 * c2 + 2.0 * c5 * sg * sg;
                h[4][4] = 2.0 * c6;
            }
        }
    }
    if hessian {
        for i in 0..5 {
            for j in 0..i {
                d.h[i][j] = d.h[j][i];
            }
        }
    }
    d
}

/// [`density_u`] in the variables `x = (a, z, …)` of the element (chain rule through
/// `k = z/a`).
fn density(cst: &Constants, x: [f64; 5], hessian: bool) -> Density {
    let [a, z, sg, sgx, eyy] = x;
    let k = z / a;
    let du = density_u(cst, [a, k, sg, sgx, eyy], hessian);
    let (ia, k_a) = (1.0 / a, -k / a);
    let gu = du.g;
    let mut out = Density {
        w: du.w,
        g: [gu[0] + gu[1] * k_a, gu[1] * ia, gu[2], gu[3], gu[4]],
        h: [[0.0; 5]; 5],
    };
    if hessian {
        let hu = &du.h;
        let (k_z, k_aa, k_az) = (ia, 2.0 * k * ia * ia, -ia * ia);
        let h = &mut out.h;
        h[0][0] = hu[0][0] + 2.0 * hu[0][1] * k_a + hu[1][1] * k_a * k_a + gu[1] * k_aa;
        h[0][1] = hu[0][1] * k_z + hu[1][1] * k_a * k_z + gu[1] * k_az;
        h[1][1] = hu[1][1] * k_z * k_z;
        h[0][2] = hu[0][2] + hu[1][2] * k_a;
        h[0][3] = hu[0][3] + hu[1][3] * k_a;
        h[1][2] = hu[1][2] * k_z;
        h[1][3] = hu[1][3] * k_z;
        h[2][2] = hu[2][2];
        h[2][3] = hu[2][3];
        h[3][3] = hu[3][3];
        h[4][4] = hu[4][4];
        for i in 0..5 {
            for j in 0..i {
                h[i][j] = h[j][i];
            }
        }
    }
    out
}

/// Axial force \[N\] the element carries at `ξ` of the point `p` (its `sx`, `sxx` at `ξ`), from
/// the element's own energy: `N = ∂W/∂λ` at fixed `k`, `sin γ`, `(sin γ)_x`, `ε_yy`, with the
/// centreline stretch `λ = ‖r_{c,x}‖ = √a`, i.e. `N = 2λ ∂W/∂a|_k` (module documentation).
///
/// Holding `k = t_x·n` (the curvature per unit reference length) fixed while `λ` varies is
/// stretching the section without bending it; `N` is then the tangential component of the
/// section force `n = ∂W/∂r_x − (∂W/∂r_{xx})_x` of a rod with energy `W(r_x, r_xx)` (the
/// `(∂W/∂r_{xx})_x` part contributes `∂W/∂z · z/λ`), and for St Venant–Kirchhoff it equals
/// `∫ S_xx (r_{p,x}·t) dA`, the first Piola–Kirchhoff traction of (3.13) over the section.
/// St Venant–Kirchhoff (3.18)–(3.19):
/// `N = α₁EA λ ε_G + α₂EI₂ λ (s² + ½c) + k_sGα₂A λ sin²γ`, `ε_G = (λ² − 1)/2`, `s`, `c` of the
/// module documentation (the second term is (3.18)'s bending–stretching coupling, ≈ 1.5 EI κ²
/// on a wrap); linear law: `N = α₁EA(λ − 1) + k_sGα₂A λ sin²γ`.
pub(crate) fn axial_force(cst: &Constants, length: f64, p: &KernelPoint, e: &[f64]) -> f64 {
    let nodes = [
        NodeScalars::new([e[2], e[3]], [e[4], e[5]], false),
        NodeScalars::new([e[8], e[9]], [e[10], e[11]], false),
    ];
    let (_, _, x) = point_scalars(p, e, &nodes, 1.0 / length);
    let [a, z, sg, sgx, eyy] = x;
    let d = density_u(cst, [a, z / a, sg, sgx, eyy], false);
    2.0 * a.sqrt() * d.g[0]
}

/// Strain energy `U = Σ w W` \[J\], elastic forces `q = −∂U/∂e` and, with `k = Some`, the
/// tangent `∂²U/∂e²` (column-major 12 × 12) of the belt element with coordinates `e`
/// (module documentation).
pub(crate) fn evaluate(
    cst: &Constants, length: f64, points: &[KernelPoint], e: &[f64], q: &mut [f64],
    k: Option<&mut [f64]>,
) -> f64 {
    let Some(kout) = k else {
        return forces(cst, length, points, e, q);
    };
    let nodes = [
        NodeScalars::new([e[2], e[3]], [e[4], e[5]], true),
        NodeScalars::new([e[8], e[9]], [e[10], e[11]], true),
    ];
    let il = 1.0 / length;
    let mut energy = 0.0;
    let mut grad = [0.0; N];
    // ∂U/∂(sin γᴵ, sin γᴶ, ‖r_yᴵ‖, ‖r_yᴶ‖)
    let mut du_nodal = [0.0; 4];
    // tangent accumulators
    let mut h = [[0.0; N]; N];
    let mut ka = [[0.0; CUBIC_BLOCKS]; CUBIC_BLOCKS];
    let mut kz = [[0.0; CUBIC_BLOCKS]; CUBIC_BLOCKS];
    let mut cross = [[0.0; N]; 4];
    let mut y = [[0.0; 4]; 4];
    for p in points {
        let xi = p.xi;
        let (rcx, rcxx, x) = point_scalars(p, e, &nodes, il);
        let d = density(cst, x, true);
        let w = p.w;
        energy += w * d.w;
        // gradients of a and z
        let mut ga = [0.0; N];
        let mut gz = [0.0; N];
        for &b in &CENTRE_BLOCKS {
            ga[2 * b] = 2.0 * p.sx[b] * rcx[0];
            ga[2 * b + 1] = 2.0 * p.sx[b] * rcx[1];
            gz[2 * b] = p.sx[b] * rcxx[1] - p.sxx[b] * rcx[1];
            gz[2 * b + 1] = -p.sx[b] * rcxx[0] + p.sxx[b] * rcx[0];
        }
        for c in 0..N {
            grad[c] += w * (d.g[0] * ga[c] + d.g[1] * gz[c]);
        }
        // point scalars (sin γ, (sin γ)_x, ε_yy) as rows over the nodal scalars
        let m = [
            [1.0 - xi, xi, 0.0, 0.0],
            [-il, il, 0.0, 0.0],
            [0.0, 0.0, 1.0 - xi, xi],
        ];
        for nd in 0..4 {
            du_nodal[nd] += w * (d.g[2] * m[0][nd] + d.g[3] * m[1][nd] + d.g[4] * m[2][nd]);
        }
        {
            let hd = &d.h;
            // rank-two part in (a, z)
            for r in 0..N {
                let (gar, gzr) = (ga[r], gz[r]);
                if gar == 0.0 && gzr == 0.0 {
                    continue;
                }
                let ua = w * (hd[0][0] * gar + hd[0][1] * gzr);
                let uz = w * (hd[0][1] * gar + hd[1][1] * gzr);
                for c in CENTRE_COORDS {
                    h[r][c] += ua * ga[c] + uz * gz[c];
                }
            }
            // ∂W/∂a ∂²a + ∂W/∂z ∂²z (block coefficients)
            let (wa, wz) = (w * d.g[0], w * d.g[1]);
            for &i in &CENTRE_BLOCKS {
                for &j in &CENTRE_BLOCKS {
                    ka[i][j] += 2.0 * wa * p.sx[i] * p.sx[j];
                    kz[i][j] += wz * (p.sx[i] * p.sxx[j] - p.sx[j] * p.sxx[i]);
                }
            }
            // cross terms (a, z) × nodal scalars and nodal × nodal
            // (the rows of `m` that do not vanish for a nodal scalar: `sin γ`, `(sin γ)_x` for
            // the shear angles, `ε_yy` for the slope norms; a sum skips only its zero terms)
            let rows = |nd: usize| if nd < 2 { 0..2 } else { 2..3 };
            for nd in 0..4 {
                let xa = rows(nd).map(|s| hd[0][2 + s] * m[s][nd]).sum::<f64>();
                let xz = rows(nd).map(|s| hd[1][2 + s] * m[s][nd]).sum::<f64>();
                for c in CENTRE_COORDS {
                    cross[nd][c] += w * (xa * ga[c] + xz * gz[c]);
                }
                for md in 0..4 {
                    let mut acc = 0.0;
                    for s in rows(nd) {
                        for t in rows(md) {
                            acc += m[s][nd] * hd[2 + s][2 + t] * m[t][md];
                        }
                    }
                    y[nd][md] += w * acc;
                }
            }
        }
    }
    // nodal scalars as 12-vectors: sin γᴵ on (r_xᴵ, r_yᴵ) = e[2..6], ‖r_yᴵ‖ on e[4..6]
    let mut gn = [[0.0; N]; 4];
    for (node, off) in [(0usize, 2usize), (1, 8)] {
        gn[node][off..off + 4].copy_from_slice(&nodes[node].dsg);
        gn[2 + node][off + 2..off + 4].copy_from_slice(&nodes[node].dny);
    }
    for (nd, g) in gn.iter().enumerate() {
        for c in 0..N {
            grad[c] += du_nodal[nd] * g[c];
        }
    }
    for c in 0..N {
        q[c] = -grad[c];
    }
    {
        for i in 0..CUBIC_BLOCKS {
            for j in 0..CUBIC_BLOCKS {
                h[2 * i][2 * j] += ka[i][j];
                h[2 * i + 1][2 * j + 1] += ka[i][j];
                h[2 * i][2 * j + 1] += kz[i][j];
                h[2 * i + 1][2 * j] -= kz[i][j];
            }
        }
        for nd in 0..4 {
            // `gn[nd]` vanishes outside its node's coordinates `sn`: an entry outside
            // `sn × all ∪ all × sn` would add zero
            let sn = support(nd);
            for r in 0..N {
                let inside = sn.contains(&r);
                for c in 0..N {
                    if inside || sn.contains(&c) {
                        h[r][c] += cross[nd][r] * gn[nd][c] + gn[nd][r] * cross[nd][c];
                    }
                }
            }
            for md in 0..4 {
                let ynm = y[nd][md];
                if ynm == 0.0 {
                    continue;
                }
                for r in support(nd) {
                    if gn[nd][r] == 0.0 {
                        continue;
                    }
                    for c in support(md) {
                        h[r][c] += ynm * gn[nd][r] * gn[md][c];
                    }
                }
            }
        }
        // the nodal functions' own second derivatives
        for (node, off) in [(0usize, 2usize), (1, 8)] {
            let (fs, fy) = (du_nodal[node], du_nodal[2 + node]);
            for i in 0..4 {
                for j in 0..4 {
                    h[off + i][off + j] += fs * nodes[node].hsg[i][j];
                }
            }
            for i in 0..2 {
                for j in 0..2 {
                    h[off + 2 + i][off + 2 + j] += fy * nodes[node].hny[i][j];
                }
            }
        }
        for r in 0..N {
            for c in 0..N {
                kout[r + c * N] = h[r][c];
            }
        }
    }
    energy
}

/// `r_{c,x}`, `r_{c,xx}` and the five scalars `(a, z, sin γ, (sin γ)_x, ε_yy)` at a point.
fn point_scalars(
    p: &KernelPoint, e: &[f64], nodes: &[NodeScalars; 2], il: f64,
) -> ([f64; 2], [f64; 2], [f64; 5]) {
    let xi = p.xi;
    let mut rcx = [0.0; 2];
    let mut rcxx = [0.0; 2];
    for &b in &CENTRE_BLOCKS {
        rcx[0] += p.sx[b] * e[2 * b];
        rcx[1] += p.sx[b] * e[2 * b + 1];
        rcxx[0] += p.sxx[b] * e[2 * b];
        rcxx[1] += p.sxx[b] * e[2 * b + 1];
    }
    let a = rcx[0] * rcx[0] + rcx[1] * rcx[1];
    let z = rcx[0] * rcxx[1] - rcx[1] * rcxx[0];
    let sg = (1.0 - xi) * nodes[0].sg + xi * nodes[1].sg;
    let sgx = (nodes[1].sg - nodes[0].sg) * il;
    let eyy = (1.0 - xi) * nodes[0].ny + xi * nodes[1].ny - 1.0;
    (rcx, rcxx, [a, z, sg, sgx, eyy])
}

/// Energy and forces only (the [`evaluate`] gradient without the tangent's accumulators).
fn forces(cst: &Constants, length: f64, points: &[KernelPoint], e: &[f64], q: &mut [f64]) -> f64 {
    let nodes = [
        NodeScalars::new([e[2], e[3]], [e[4], e[5]], false),
        NodeScalars::new([e[8], e[9]], [e[10], e[11]], false),
    ];
    let il = 1.0 / length;
    let mut energy = 0.0;
    let mut grad = [0.0; N];
    let mut du_nodal = [0.0; 4];
    for p in points {
        let xi = p.xi;
        let (rcx, rcxx, x) = point_scalars(p, e, &nodes, il);
        let d = density(cst, x, false);
        let w = p.w;
        energy += w * d.w;
        // w (∂W/∂a ∂a/∂e + ∂W/∂z ∂z/∂e)
        let (wa, wz) = (w * d.g[0], w * d.g[1]);
        for &b in &CENTRE_BLOCKS {
            grad[2 * b] +=
                wa * 2.0 * p.sx[b] * rcx[0] + wz * (p.sx[b] * rcxx[1] - p.sxx[b] * rcx[1]);
            grad[2 * b + 1] +=
                wa * 2.0 * p.sx[b] * rcx[1] + wz * (-p.sx[b] * rcxx[0] + p.sxx[b] * rcx[0]);
        }
        let (gsg, gsgx, geyy) = (w * d.g[2], w * d.g[3], w * d.g[4]);
        du_nodal[0] += gsg * (1.0 - xi) - gsgx * il;
        du_nodal[1] += gsg * xi + gsgx * il;
        du_nodal[2] += geyy * (1.0 - xi);
        du_nodal[3] += geyy * xi;
    }
    for (node, off) in [(0usize, 2usize), (1, 8)] {
        for i in 0..4 {
            grad[off + i] += du_nodal[node] * nodes[node].dsg[i];
        }
        for i in 0..2 {
            grad[off + 2 + i] += du_nodal[2 + node] * nodes[node].dny[i];
        }
    }
    for c in 0..N {
        q[c] = -grad[c];
    }
    energy
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`evaluate`] as it was before it skipped the structural zeros (2026-12-06): the
    /// reference its tangent is compared with, bit for bit.
    fn evaluate_before(
        cst: &Constants, length: f64, points: &[KernelPoint], e: &[f64], q: &mut [f64],
        k: Option<&mut [f64]>,
    ) -> f64 {
        let Some(kout) = k else {
            return forces(cst, length, points, e, q);
        };
        let nodes = [
            NodeScalars::new([e[2], e[3]], [e[4], e[5]], true),
            NodeScalars::new([e[8], e[9]], [e[10], e[11]], true),
        ];
        let il = 1.0 / length;
        let mut energy = 0.0;
        let mut grad = [0.0; N];
        // ∂U/∂(sin γᴵ, sin γᴶ, ‖r_yᴵ‖, ‖r_yᴶ‖)
        let mut du_nodal = [0.0; 4];
        // tangent accumulators
        let mut h = [[0.0; N]; N];
        let mut ka = [[0.0; CUBIC_BLOCKS]; CUBIC_BLOCKS];
        let mut kz = [[0.0; CUBIC_BLOCKS]; CUBIC_BLOCKS];
        let mut cross = [[0.0; N]; 4];
        let mut y = [[0.0; 4]; 4];
        for p in points {
            let xi = p.xi;
            let (rcx, rcxx, x) = point_scalars(p, e, &nodes, il);
            let d = density(cst, x, true);
            let w = p.w;
            energy += w * d.w;
            // gradients of a and z
            let mut ga = [0.0; N];
            let mut gz = [0.0; N];
            for &b in &CENTRE_BLOCKS {
                ga[2 * b] = 2.0 * p.sx[b] * rcx[0];
                ga[2 * b + 1] = 2.0 * p.sx[b] * rcx[1];
                gz[2 * b] = p.sx[b] * rcxx[1] - p.sxx[b] * rcx[1];
                gz[2 * b + 1] = -p.sx[b] * rcxx[0] + p.sxx[b] * rcx[0];
            }
            for c in 0..N {
                grad[c] += w * (d.g[0] * ga[c] + d.g[1] * gz[c]);
            }
            // point scalars (sin γ, (sin γ)_x, ε_yy) as rows over the nodal scalars
            let m = [
                [1.0 - xi, xi, 0.0, 0.0],
                [-il, il, 0.0, 0.0],
                [0.0, 0.0, 1.0 - xi, xi],
            ];
            for nd in 0..4 {
                du_nodal[nd] += w * (d.g[2] * m[0][nd] + d.g[3] * m[1][nd] + d.g[4] * m[2][nd]);
            }
            {
                let hd = &d.h;
                // rank-two part in (a, z)
                for r in 0..N {
                    let (gar, gzr) = (ga[r], gz[r]);
                    if gar == 0.0 && gzr == 0.0 {
                        continue;
                    }
                    let ua = w * (hd[0][0] * gar + hd[0][1] * gzr);
                    let uz = w * (hd[0][1] * gar + hd[1][1] * gzr);
                    for c in 0..N {
                        h[r][c] += ua * ga[c] + uz * gz[c];
                    }
                }
                // ∂W/∂a ∂²a + ∂W/∂z ∂²z (block coefficients)
                let (wa, wz) = (w * d.g[0], w * d.g[1]);
                for &i in &CENTRE_BLOCKS {
                    for &j in &CENTRE_BLOCKS {
                        ka[i][j] += 2.0 * wa * p.sx[i] * p.sx[j];
                        kz[i][j] += wz * (p.sx[i] * p.sxx[j] - p.sx[j] * p.sxx[i]);
                    }
                }
                // cross terms (a, z) × nodal scalars and nodal × nodal
                for nd in 0..4 {
                    let xa = (2..5).map(|s| hd[0][s] * m[s - 2][nd]).sum::<f64>();
                    let xz = (2..5).map(|s| hd[1][s] * m[s - 2][nd]).sum::<f64>();
                    for c in 0..N {
                        cross[nd][c] += w * (xa * ga[c] + xz * gz[c]);
                    }
                    for md in 0..4 {
                        let mut acc = 0.0;
                        for s in 0..3 {
                            for t in 0..3 {
                                acc += m[s][nd] * hd[2 + s][2 + t] * m[t][md];
                            }
                        }
                        y[nd][md] += w * acc;
                    }
                }
            }
        }
        // nodal scalars as 12-vectors: sin γᴵ on (r_xᴵ, r_yᴵ) = e[2..6], ‖r_yᴵ‖ on e[4..6]
        let mut gn = [[0.0; N]; 4];
        for (node, off) in [(0usize, 2usize), (1, 8)] {
            gn[node][off..off + 4].copy_from_slice(&nodes[node].dsg);
            gn[2 + node][off + 2..off + 4].copy_from_slice(&nodes[node].dny);
        }
        for (nd, g) in gn.iter().enumerate() {
            for c in 0..N {
                grad[c] += du_nodal[nd] * g[c];
            }
        }
        for c in 0..N {
            q[c] = -grad[c];
        }
        {
            for i in 0..CUBIC_BLOCKS {
                for j in 0..CUBIC_BLOCKS {
                    h[2 * i][2 * j] += ka[i][j];
                    h[2 * i + 1][2 * j + 1] += ka[i][j];
                    h[2 * i][2 * j + 1] += kz[i][j];
                    h[2 * i + 1][2 * j] -= kz[i][j];
                }
            }
            for nd in 0..4 {
                for r in 0..N {
                    for c in 0..N {
                        h[r][c] += cross[nd][r] * gn[nd][c] + gn[nd][r] * cross[nd][c];
                    }
                }
                for md in 0..4 {
                    let ynm = y[nd][md];
                    if ynm == 0.0 {
                        continue;
                    }
                    for r in 0..N {
                        if gn[nd][r] == 0.0 {
                            continue;
                        }
                        for c in 0..N {
                            h[r][c] += ynm * gn[nd][r] * gn[md][c];
                        }
                    }
                }
            }
            // the nodal functions' own second derivatives
            for (node, off) in [(0usize, 2usize), (1, 8)] {
                let (fs, fy) = (du_nodal[node], du_nodal[2 + node]);
                for i in 0..4 {
                    for j in 0..4 {
                        h[off + i][off + j] += fs * nodes[node].hsg[i][j];
                    }
                }
                for i in 0..2 {
                    for j in 0..2 {
                        h[off + 2 + i][off + 2 + j] += fy * nodes[node].hny[i][j];
                    }
                }
            }
            for r in 0..N {
                for c in 0..N {
                    kout[r + c * N] = h[r][c];
                }
            }
        }
        energy
    }

    /// The tangent that skips the structural zeros (the `r_y` blocks of `a` and `z`, the
    /// coordinates a nodal scalar does not depend on) is the old full loops' bit for bit
    /// (reference: [`evaluate_before`], itself tested against the automatic-differentiation
    /// energy), for both material laws on a bent, sheared, stretched element.
    #[test]
    fn tangent_without_structural_zeros_is_the_full_loops_bit_for_bit() {
        let l = 0.0125;
        let points: Vec<KernelPoint> = [0.0469, 0.2308, 0.5, 0.7692, 0.9531]
            .iter()
            .zip([0.1185, 0.2393, 0.2844, 0.2393, 0.1185])
            .map(|(&xi, w)| KernelPoint {
                xi,
                w: w * l,
                sx: crate::shape::cubic(l, xi * l, 0.0).sx,
                sxx: crate::shape::cubic_xx(l, xi * l),
            })
            .collect();
        let e = [
            0.01, 0.002, 1.003, 0.05, -0.04, 0.998, //
            0.0226, 0.0031, 0.996, 0.11, -0.12, 1.004,
        ];
        for law in [MaterialLaw::StVenantKirchhoff, MaterialLaw::Linear] {
            let cst = Constants {
                c: [2.1e5, 0.37, 1.3e-6, 4.4e3, 0.21, 8.8e5],
                law,
            };
            let (mut q0, mut q1) = ([0.0; N], [0.0; N]);
            let (mut k0, mut k1) = ([0.0; N * N], [0.0; N * N]);
            let u0 = evaluate_before(&cst, l, &points, &e, &mut q0, Some(&mut k0));
            let u1 = evaluate(&cst, l, &points, &e, &mut q1, Some(&mut k1));
            assert_eq!(u0.to_bits(), u1.to_bits());
            assert!(q0.iter().zip(&q1).all(|(a, b)| a == b));
            assert!(k0.iter().any(|&v| v != 0.0));
            for (i, (a, b)) in k0.iter().zip(&k1).enumerate() {
                assert!(a == b, "entry {i}: {a} against {b}");
            }
        }
    }
}
