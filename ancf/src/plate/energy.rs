//! Analytic first and second derivatives of the thin plate's strain-energy density with respect
//! to the local kinematic quantities `u = [r_x, r_y, r_xx, r_xy, r_yy]` (15 values): the hot
//! path of the element forces and tangent (Kerkkänen (4.16)–(4.19)).
//!
//! Membrane (4.16, standard plane-stress form, see [`super::ThinPlate`]): with the Green
//! strains `ε = (ε_xx, ε_yy, ε_xy) = (½(r_x·r_x − 1), ½(r_y·r_y − 1), ½ r_x·r_y)`
//! the density is `W = c_m [ε_xx² + ε_yy² + 2ν ε_xx ε_yy + 2(1 − ν) ε_xy²]`,
//! `c_m = E h / (2(1 − ν²))`, so that with the resultants `N = ∂W/∂ε` and the strain–gradient
//! rows `b_a = ∂ε_a/∂(r_x, r_y)`:
//!
//! ```text
//!   ∂W/∂u = Σ_a N_a b_a,    ∂²W/∂u² = Σ_ab C_ab b_a b_bᵀ + Σ_a N_a ∂²ε_a/∂u²
//! ```
//!
//! with `C = c_m [[2, 2ν, 0], [2ν, 2, 0], [0, 0, 4(1 − ν)]]`; `∂²ε_xx = I` on the `r_x` block,
//! `∂²ε_yy = I` on the `r_y` block and `∂²ε_xy = ½ I` on the two off-diagonal blocks.
//!
//! Bending (4.17)–(4.18): `κ_a = p_a s_a` with the triple products `p_a = r_a · (r_x × r_y)`
//! (`r_a ∈ {r_xx, r_yy, r_xy}`) and the normalisation
//! `s_a = ‖n‖⁻¹ l_xx^{−α_a} l_yy^{−β_a}`, `‖n‖² = l_xx l_yy − m²` (Lagrange's identity),
//! `l_xx = r_x·r_x`, `l_yy = r_y·r_y`, `m = r_x·r_y`, `(α, β) = (1, 0), (0, 1), (½, ½)`.
//! `p_a` is trilinear (gradient `n`, `r_y × r_a`, `r_a × r_x`; constant cross-product
//! Hessian blocks), `s_a` is a function of the three quadratic invariants `(l_xx, l_yy, m)`
//! whose logarithmic derivatives are explicit, and
//! `W_b = (D/2) κᵀ C_κ κ`, `C_κ = [[1, ν, 0], [ν, 1, 0], [0, 0, 2(1 − ν)]]`.
//! The derivatives are checked against the automatic-differentiation reference
//! ([`super::ThinPlate::elastic_tangent_autodiff`]) in the tests.

/// Number of local kinematic quantities (`r_x, r_y, r_xx, r_xy, r_yy`).
pub(crate) const NU: usize = 15;

/// Offsets of the blocks of `u`.
const RX: usize = 0;
const RY: usize = 3;

/// Gradient and Hessian of the energy density with respect to `u`.
#[derive(Debug, Clone)]
pub(crate) struct LocalDerivatives {
    /// `∂W/∂u` \[J/m² per unit of u\].
    pub g: [f64; NU],
    /// `∂²W/∂u²` (only the first `6` rows and columns without bending).
    pub h: [[f64; NU]; NU],
}

impl LocalDerivatives {
    pub(crate) fn zero() -> Self {
        Self {
            g: [0.0; NU],
            h: [[0.0; NU]; NU],
        }
    }
}

fn v3(u: &[f64; NU], o: usize) -> [f64; 3] {
    [u[o], u[o + 1], u[o + 2]]
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `[a]×` (the matrix of `x ↦ a × x`).
fn skew(a: &[f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]
}

/// The plane stress resultants `(N_x, N_y, N_xy)` \[N/m\] of the Green strains of the
/// mid-surface slopes `(r_x, r_y)` for the St Venant–Kirchhoff membrane with
/// `cm = E h / (2(1 − ν²))` (Kerkkänen ch. 4, the thin plate), shared by [`membrane`] and the plate
/// element's batched membrane forces.
#[inline(always)]
pub(crate) fn membrane_resultants(rx: &[f64; 3], ry: &[f64; 3], cm: f64, nu: f64) -> [f64; 3] {
    let exx = 0.5 * (dot(rx, rx) - 1.0);
    let eyy = 0.5 * (dot(ry, ry) - 1.0);
    let exy = 0.5 * dot(rx, ry);
    let nx = cm * (2.0 * exx + 2.0 * nu * eyy);
    let ny = cm * (2.0 * eyy + 2.0 * nu * exx);
    let nxy = cm * 4.0 * (1.0 - nu) * exy;
    [nx, ny, nxy]
}

/// Membrane energy density \[J/m²\] and its derivatives with respect to `(r_x, r_y)` added into
/// `out` (`jac`: also the Hessian). `cm = E h / (2(1 − ν²))`.
#[inline(always)]
pub(crate) fn membrane(u: &[f64; NU], cm: f64, nu: f64, jac: bool, out: &mut LocalDerivatives) {
    let rx = v3(u, RX);
    let ry = v3(u, RY);
    let [nx, ny, nxy] = membrane_resultants(&rx, &ry, cm, nu);
    for c in 0..3 {
        out.g[RX + c] += nx * rx[c] + 0.5 * nxy * ry[c];
        out.g[RY + c] += ny * ry[c] + 0.5 * nxy * rx[c];
    }
    if !jac {
        return;
    }
    // strain–gradient rows b_a over (r_x, r_y)
    let mut b = [[0.0; 6]; 3];
    for c in 0..3 {
        b[0][c] = rx[c];
        b[1][3 + c] = ry[c];
        b[2][c] = 0.5 * ry[c];
        b[2][3 + c] = 0.5 * rx[c];
    }
    let cmat = [
        [2.0 * cm, 2.0 * nu * cm, 0.0],
        [2.0 * nu * cm, 2.0 * cm, 0.0],
        [0.0, 0.0, 4.0 * (1.0 - nu) * cm],
    ];
    // C b (3 × 6)
    let mut cb = [[0.0; 6]; 3];
    for a in 0..3 {
        for j in 0..6 {
            cb[a][j] = (0..3).map(|k| cmat[a][k] * b[k][j]).sum();
        }
    }
    for i in 0..6 {
        for j in 0..6 {
            let mut v = 0.0;
            for a in 0..3 {
                v += b[a][i] * cb[a][j];
            }
            out.h[i][j] += v;
        }
    }
    for c in 0..3 {
        out.h[RX + c][RX + c] += nx;
        out.h[RY + c][RY + c] += ny;
        out.h[RX + c][RY + c] += 0.5 * nxy;
        out.h[RY + c][RX + c] += 0.5 * nxy;
    }
}

/// One curvature `κ = p s` with its gradient and Hessian over `u`.
struct Curvature {
    value: f64,
    g: [f64; NU],
    h: [[f64; NU]; NU],
}

/// The curvature of the second derivative stored at offset `o` of `u` (6: `r_xx`, 9: `r_xy`,
/// 12: `r_yy`) with the normalisation exponents `(α, β)` of (4.18).
fn curvature(u: &[f64; NU], o: usize, alpha: f64, beta: f64) -> Curvature {
    let rx = v3(u, RX);
    let ry = v3(u, RY);
    let ra = v3(u, o);
    let n = cross(&rx, &ry);
    // p = r_a · (r_x × r_y): gradient and Hessian
    let p = dot(&ra, &n);
    let mut gp = [0.0; NU];
    let gx = cross(&ry, &ra);
    let gy = cross(&ra, &rx);
    gp[o..o + 3].copy_from_slice(&n);
    gp[RX..RX + 3].copy_from_slice(&gx);
    gp[RY..RY + 3].copy_from_slice(&gy);
    // ∂n/∂r_x = −[r_y]×, ∂n/∂r_y = [r_x]×, ∂(r_y × r_a)/∂r_y = −[r_a]×
    let (sy, sx, sa) = (skew(&ry), skew(&rx), skew(&ra));
    let mut hp = [[0.0; NU]; NU];
    for i in 0..3 {
        for j in 0..3 {
            hp[o + i][RX + j] = -sy[i][j];
            hp[RX + j][o + i] = -sy[i][j];
            hp[o + i][RY + j] = sx[i][j];
            hp[RY + j][o + i] = sx[i][j];
            hp[RX + i][RY + j] = -sa[i][j];
            hp[RY + j][RX + i] = -sa[i][j];
        }
    }
    // s = φ(l_xx, l_yy, m) = (l_xx l_yy − m²)^{−½} l_xx^{−α} l_yy^{−β}
    let lxx = dot(&rx, &rx);
    let lyy = dot(&ry, &ry);
    let m = dot(&rx, &ry);
    let nn = lxx * lyy - m * m;
    let s = nn.powf(-0.5) * lxx.powf(-alpha) * lyy.powf(-beta);
    // logarithmic derivatives L = ln φ
    let dl = [
        -0.5 * lyy / nn - alpha / lxx,
        -0.5 * lxx / nn - beta / lyy,
        m / nn,
    ];
    let nn2 = nn * nn;
    let ddl = [
        [
            0.5 * lyy * lyy / nn2 + alpha / (lxx * lxx),
            0.5 * m * m / nn2,
            -lyy * m / nn2,
        ],
        [
            0.5 * m * m / nn2,
            0.5 * lxx * lxx / nn2 + beta / (lyy * lyy),
            -lxx * m / nn2,
        ],
        [-lyy * m / nn2, -lxx * m / nn2, (nn + 2.0 * m * m) / nn2],
    ];
    // φ' = φ L', φ'' = φ (L' L'ᵀ + L'')
    let dphi = [s * dl[0], s * dl[1], s * dl[2]];
    let mut ddphi = [[0.0; 3]; 3];
    for a in 0..3 {
        for b in 0..3 {
            ddphi[a][b] = s * (dl[a] * dl[b] + ddl[a][b]);
        }
    }
    // gradients of the invariants over (r_x, r_y) (6 entries) and their constant Hessians
    let mut gi = [[0.0; 6]; 3];
    for c in 0..3 {
        gi[0][c] = 2.0 * rx[c];
        gi[1][3 + c] = 2.0 * ry[c];
        gi[2][c] = ry[c];
        gi[2][3 + c] = rx[c];
    }
    let mut gs = [0.0; NU];
    for j in 0..6 {
        gs[j] = (0..3).map(|a| dphi[a] * gi[a][j]).sum();
    }
    let mut hs = [[0.0; NU]; NU];
    for i in 0..6 {
        for j in 0..6 {
            let mut v = 0.0;
            for a in 0..3 {
                for b in 0..3 {
                    v += ddphi[a][b] * gi[a][i] * gi[b][j];
                }
            }
            hs[i][j] = v;
        }
    }
    for c in 0..3 {
        hs[RX + c][RX + c] += 2.0 * dphi[0];
        hs[RY + c][RY + c] += 2.0 * dphi[1];
        hs[RX + c][RY + c] += dphi[2];
        hs[RY + c][RX + c] += dphi[2];
    }
    // κ = p s
    let mut g = [0.0; NU];
    for i in 0..NU {
        g[i] = s * gp[i] + p * gs[i];
    }
    let mut h = [[0.0; NU]; NU];
    for i in 0..NU {
        for j in 0..NU {
            h[i][j] = s * hp[i][j] + gp[i] * gs[j] + gs[i] * gp[j] + p * hs[i][j];
        }
    }
    Curvature { value: p * s, g, h }
}

/// Bending energy density (4.17) with the curvatures (4.18) and its derivatives added into
/// `out`; `d` is the bending rigidity \[N·m\].
pub(crate) fn bending(u: &[f64; NU], d: f64, nu: f64, jac: bool, out: &mut LocalDerivatives) {
    let k = [
        curvature(u, 6, 1.0, 0.0),
        curvature(u, 12, 0.0, 1.0),
        curvature(u, 9, 0.5, 0.5),
    ];
    let ck = [[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 2.0 * (1.0 - nu)]];
    let kv = [k[0].value, k[1].value, k[2].value];
    let m: [f64; 3] = std::array::from_fn(|a| d * (0..3).map(|b| ck[a][b] * kv[b]).sum::<f64>());
    for a in 0..3 {
        for i in 0..NU {
            out.g[i] += m[a] * k[a].g[i];
        }
    }
    if !jac {
        return;
    }
    for i in 0..NU {
        for j in 0..NU {
            let mut v = 0.0;
            for a in 0..3 {
                v += m[a] * k[a].h[i][j];
                for b in 0..3 {
                    v += d * ck[a][b] * k[a].g[i] * k[b].g[j];
                }
            }
            out.h[i][j] += v;
        }
    }
}
