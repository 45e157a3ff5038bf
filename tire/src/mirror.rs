//! Mirror symmetry of the rolling tire about its mid-plane `y = 0` (the plane normal to the
//! wheel axis `η = ŷ`): the half model of symmetric motion.
//!
//! A tire whose mesh, materials and contact nodes are symmetric about the mid-plane, rolling
//! straight (camber and steer locked, U22) on a ground extruded along the axis (drum, road and
//! transverse cleat, [`super::ground`]) with an isotropic friction law, has mirror-symmetric
//! motion from a symmetric start: the mirror `R: (x, y, z) ↦ (x, −y, z)` maps a solution onto a
//! solution, and the spin about `ŷ` (an axial vector normal to the mirror plane) is kept. The
//! reduced matrices commute with `R` (`Rᵀ G₁ R = G₁` etc.), so in the mass-normalised modal
//! coordinates of [`ReducedTire::modal`] — the eigenvectors of `R`-invariant `M`, `K` with
//! distinct frequencies — every coordinate is either symmetric (`R T φ = T φ`) or antisymmetric
//! (`R T φ = −T φ`), and the equations (7.17) decouple into the two sets. Symmetric motion keeps
//! the antisymmetric coordinates at zero: the half model steps the symmetric ones only (172 of
//! the default tire's 335), the classical symmetry boundary condition of structural analysis
//! applied to the reduced model.
//!
//! Contact: a node `i` on the mid-plane carries a force without lateral component; a node off it
//! and its mirror image `i'` carry mirrored forces, `f_{i'} = R f_i`, whose generalised force
//! on the symmetric coordinates is `T_{c,i}ᵀ f_i + T_{c,i'}ᵀ R f_i = 2 T_{c,i}ᵀ f_i`. The half
//! model's contact problem has one representative per pair (weight 2) and the mid-plane nodes
//! (weight 1) as unknowns ([`MirrorHalf::weight`]), half the size of the full one. The result
//! equals the full model's symmetric solution; the full model itself departs from it only by
//! the growth of antisymmetric round-off.

use crate::reduced::ReducedTire;
use faer::Mat;

/// Relative tolerance of the symmetry tests (the default tire's reduced matrices commute with
/// the mirror to 2·10⁻¹³ of their largest entry).
pub const MIRROR_TOLERANCE: f64 = 1e-8;

/// The symmetric half of a reduced tire in modal coordinates (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct MirrorHalf {
    /// The symmetric coordinates kept, ascending.
    pub kept: Vec<usize>,
    /// The mirror image of each contact node (the node itself on the mid-plane).
    pub partner: Vec<usize>,
    /// Number of coordinates of the full model.
    pub n_full: usize,
}

impl MirrorHalf {
    /// Weight of contact node `i` in the half model's contact problem: 1 on the mid-plane, 2 for
    /// the representative (lower index) of a mirrored pair, 0 for its image (not a contact
    /// unknown: its force is the mirror of the representative's).
    pub fn weight(&self, i: usize) -> f64 {
        let p = self.partner[i];
        if p == i {
            1.0
        } else if i < p {
            2.0
        } else {
            0.0
        }
    }

    /// Whether contact node `i` lies on the mid-plane.
    pub fn on_mid_plane(&self, i: usize) -> bool {
        self.partner[i] == i
    }
}

/// The mirror image of each contact node (`None` if a node has no image within
/// [`MIRROR_TOLERANCE`] of the tire's radius).
fn partners(red: &ReducedTire) -> Option<Vec<usize>> {
    let pos = &red.contact_positions;
    let scale = red.outer_radius.abs().max(1e-300);
    pos.iter()
        .map(|p| {
            let img = [p[0], -p[1], p[2]];
            pos.iter().position(|q| {
                let d = (0..3).map(|a| (q[a] - img[a]).powi(2)).sum::<f64>().sqrt();
                d <= MIRROR_TOLERANCE * scale
            })
        })
        .collect()
}

/// `R v` for contact-node rows `v` (3 n_c): the image node's values, lateral component negated.
fn mirrored(v: &[f64], partner: &[usize], out: &mut [f64]) {
    for (i, &p) in partner.iter().enumerate() {
        out[3 * p] = v[3 * i];
        out[3 * p + 1] = -v[3 * i + 1];
        out[3 * p + 2] = v[3 * i + 2];
    }
}

fn max_abs(m: &Mat<f64>) -> f64 {
    let mut a = 0.0f64;
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            a = a.max(m[(i, j)].abs());
        }
    }
    a
}

/// The symmetric half of `red` (a tire in the modal coordinates of [`ReducedTire::modal`]):
/// the parity of every coordinate from its contact-node rows `T_c`, `T_c,θ`, and the test that
/// the matrices of (7.17) (`M`, `K`, `G₁`, `G₂`, `K₁`, `m_θ`, `c_s` and the spin row of `K_θ`,
/// `K_θ,θ`) do not couple the symmetric to the antisymmetric coordinates. `Err` with the reason when the tire is not mirror-symmetric to
/// [`MIRROR_TOLERANCE`] (e.g. angled belt cords, an unsymmetric contact-node set, a coordinate
/// with no contact-node motion or equal frequencies of a symmetric and an antisymmetric mode).
pub fn mirror_half(red: &ReducedTire) -> Result<MirrorHalf, String> {
    let n = red.n_z();
    let nc = red.n_contact();
    let partner = partners(red).ok_or("a contact node has no mirror image about the mid-plane")?;
    let tol = MIRROR_TOLERANCE;
    let mut parity = vec![0i8; n];
    let mut img = vec![0.0; 3 * nc];
    let col_scale = |m: &Mat<f64>| {
        (0..n)
            .map(|j| m.col(j).iter().map(|v| v * v).sum::<f64>().sqrt())
            .fold(0.0f64, f64::max)
    };
    let (sc, st) = (col_scale(&red.tc), col_scale(&red.tc_theta));
    for (j, pj) in parity.iter_mut().enumerate() {
        let t: Vec<f64> = red.tc.col(j).iter().copied().collect();
        let norm = t.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm <= 1e-6 * sc {
            return Err(format!(
                "coordinate {j} hardly moves the contact nodes: its parity is unknown"
            ));
        }
        mirrored(&t, &partner, &mut img);
        let dev = |s: f64, v: &[f64], w: &[f64]| {
            v.iter()
                .zip(w)
                .map(|(a, b)| (a - s * b).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        let s = if dev(1.0, &img, &t) <= tol * norm {
            1.0
        } else if dev(-1.0, &img, &t) <= tol * norm {
            -1.0
        } else {
            return Err(format!(
                "coordinate {j} is neither symmetric nor antisymmetric about the mid-plane"
            ));
        };
        let tt: Vec<f64> = red.tc_theta.col(j).iter().copied().collect();
        mirrored(&tt, &partner, &mut img);
        if dev(s, &img, &tt) > tol * st {
            return Err(format!(
                "the circumferential derivative of coordinate {j} breaks the mirror symmetry"
            ));
        }
        *pj = if s > 0.0 { 1 } else { -1 };
    }
    let kept: Vec<usize> = (0..n).filter(|&j| parity[j] > 0).collect();
    let anti: Vec<usize> = (0..n).filter(|&j| parity[j] < 0).collect();
    // square matrices: no coupling between the two sets
    for (name, m) in [
        ("M", &red.m),
        ("K", &red.k),
        ("G1", &red.g1),
        ("G2", &red.g2),
        ("K1", &red.k1),
    ] {
        let bound = tol * max_abs(m);
        for &i in &kept {
            for &j in &anti {
                if m[(i, j)].abs() > bound || m[(j, i)].abs() > bound {
                    return Err(format!(
                        "{name} couples symmetric coordinate {i} and antisymmetric {j}"
                    ));
                }
            }
        }
    }
    // the spin equation (moment about ŷ, an axial vector normal to the mirror plane) sees no
    // antisymmetric coordinate (the outputs, e.g. the spindle force rows, need no test: with
    // the antisymmetric coordinates at zero their columns do not enter)
    let row_check = |name: &str, m: &Mat<f64>, r: usize| -> Result<(), String> {
        let bound = tol * max_abs(m);
        match anti.iter().find(|&&j| m[(r, j)].abs() > bound) {
            Some(&j) => Err(format!(
                "row {r} of {name} sees antisymmetric coordinate {j}"
            )),
            None => Ok(()),
        }
    };
    row_check("K_theta", &red.kt, 1)?;
    row_check("K_theta,theta", &red.kt1, 1)?;
    for (name, v) in [("m_theta", &red.m_theta), ("c_s", &red.c_s)] {
        let bound = tol * v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        if let Some(&j) = anti.iter().find(|&&j| v[j].abs() > bound) {
            return Err(format!("{name} loads antisymmetric coordinate {j}"));
        }
    }
    Ok(MirrorHalf {
        kept,
        partner,
        n_full: n,
    })
}

/// The reduced tire of the symmetric coordinates `half.kept` of `red` (the rows and columns of
/// every matrix taken at them); the lateral rows of `T_c`, `T_c,θ` (and its upwind rows) of the mid-plane nodes, zero
/// by symmetry, are set to zero exactly (the half model's contact problem then has no lateral
/// force at these nodes, see [`super::contact_step`]).
pub fn half_tire(red: &ReducedTire, half: &MirrorHalf) -> ReducedTire {
    let k = &half.kept;
    let ns = k.len();
    let square = |m: &Mat<f64>| Mat::from_fn(ns, ns, |i, j| m[(k[i], k[j])]);
    let cols = |m: &Mat<f64>| Mat::from_fn(m.nrows(), ns, |i, j| m[(i, k[j])]);
    let sub = |v: &[f64]| k.iter().map(|&j| v[j]).collect::<Vec<f64>>();
    let mut out = red.with_coordinates(square, cols, sub);
    for i in (0..red.n_contact()).filter(|&i| half.on_mid_plane(i)) {
        for j in 0..ns {
            out.tc[(3 * i + 1, j)] = 0.0;
            out.tc_theta[(3 * i + 1, j)] = 0.0;
            out.tc_theta_upwind[0][(3 * i + 1, j)] = 0.0;
            out.tc_theta_upwind[1][(3 * i + 1, j)] = 0.0;
        }
    }
    out
}
