//! The belt's finite-element loop and its flowing-material reduction basis (Ribaric 5.2–5.4).
//!
//! [`BeltFe`] holds what both formulations share: the path (fe-model's [`BeltPath`]), the node
//! positions `r_i` at arc lengths `s_i` (56 non-uniform elements by default: short on the arcs),
//! the stacked unit tangents `e_t` and discrete curvature vectors `ε_n`, the lumped mass, the
//! stiffness `K = K_e + K_g(T0)` (the geometric stiffness of the pre-tension is what gives the
//! spans their ≈ 63 Hz first mode, seed-000 note U7), the Rayleigh damping `C = αM + βK`, the
//! pre-tension force `f0` of the reference state and the contact-node sets (each arc plus a
//! lift-off margin).
//!
//! Choices the seed leaves open (documented here, seed-000 note U6, U8, U29, §10.1):
//! - rotational entries of `e_t` and `ε_n` are zero: θ is a deflection field;
//! - lumped mass (HRZ: `ρA L/2` per translation, `ρA L³/78` per rotation), so that
//!   `e_tᵀ M e_t = m_belt` holds exactly;
//! - `ε_n,i = (u_i − u_{i−1}) / L_i` with `u_i` the unit chord of element `i` and `L_i` the
//!   tributary length: the discrete curvature of the chord polygon (→ `e_n/ρ` as the mesh is
//!   refined). With it the centrifugal load `m_i v² ε_n,i` is exactly `ρv²/T0` times the
//!   pre-tension force `f0,i = T0 (u_i − u_{i−1})`, the classical belt result;
//! - Rayleigh damping `C = αM + βK_e` on the elastic stiffness (see [`BeltFe::damping`]), its
//!   β part acting on the co-rotated (frame-invariant) deformation rate of each element (see
//!   [`BeltFe::frame_turn`] and [`corotational_rate_block`]);
//! - the reference state is the belt mounted on the path with tension T0 (the printed 1.2 m
//!   belt length is inconsistent with the path, note U8).

use super::config::BeltMesh;
use crate::derivative::{DerivativeMethod, FdScheme, FirstDifference, SecondDifference};
use crate::error::{FlowError, invalid};
use crate::grid::{FlowGrid, Topology};
use crate::{FlowLine, mode_shape_derivatives};
use belt::{BeltPath, Drive, tributary_lengths};
use faer::{Mat, MatRef};
use fe_model::element::{Element, Frame2d, Frame2dSection, MassKind, MatrixKind};
use reduction::{DofPartition, Method, ModeSelection, build_basis};

/// DOFs per belt node (u, v, θ).
pub const NODE_DOFS: usize = 3;

/// The belt loop shared by the nodal and the flowing-material formulations.
#[derive(Debug, Clone)]
pub struct BeltFe {
    /// The resolved drive it was built on (path, belt, mounting tension `T0`).
    pub drive: Drive,
    /// The element lengths it was built with.
    pub mesh: BeltMesh,
    /// Arc length of each node \[m\] (increasing, in `[0, L)`).
    pub s: Vec<f64>,
    /// Node positions `r_i` \[m\].
    pub position: Vec<[f64; 2]>,
    /// Path unit tangent at each node.
    pub tangent: Vec<[f64; 2]>,
    /// Discrete curvature vector `ε_n,i` \[1/m\].
    pub curvature: Vec<[f64; 2]>,
    /// Tributary length of each node \[m\].
    pub tributary: Vec<f64>,
    /// Diagonal of the lumped mass matrix (`3N`) \[kg, kg m²\].
    pub mass: Vec<f64>,
    /// Stiffness `K_e + K_g(T0)` (`3N × 3N`).
    pub stiffness: Mat<f64>,
    /// Rayleigh damping `αM + βK_e`. The stiffness-proportional part models the rubber's
    /// viscoelasticity, so it uses the elastic stiffness only: the geometric stiffness of the
    /// pre-tension is not a material property, and `β K_g` acting on the advected deflection rate
    /// `v T_,s z` would exert spurious forces on the arcs (a rigid slide of the mounted belt along
    /// an arc is not a deformation). With `β K`, the unloaded driven pulley ran 5·10⁻⁶ (relative)
    /// faster than the driver; with `β K_e` the two agree to 10⁻⁷.
    pub damping: Mat<f64>,
    /// `Σ_e ψ'_e K_e,e J_e` (`3N × 3N`) \[N/m²\]: the elastic stiffness of each element times
    /// the rate `ψ'_e = dψ_e/ds` \[1/m\] at which the chord of the material occupying it turns
    /// as the material moves along the path ([`chord_turn_rate`]), applied to the nodal
    /// translations turned by +90° (`J (x, y) = (−y, x)`, rotations untouched).
    ///
    /// Why: Ribaric (5.5) writes the damping as `C δ̇` on the global deflection components.
    /// The viscoelastic stress follows the material strain rate, the rate of the element's
    /// deformation in its own (co-rotating) frame `d/dt (R_e δ_e) = R_e (δ̇_e − ψ̇_e J δ_e)`
    /// (`R_e` the element rotation, `Ṙ_e = −ψ̇_e R_e J`); `β K_e δ̇` alone counts the turning of
    /// an unchanged deflection around an arc as a strain rate: a belt displaced tangentially by
    /// `u` along an arc of curvature κ (a rigid rotation, no strain) gave an axial damping force
    /// `β EA v κ² u`, ≈ 100 N per 0.3 mm at 62.8 rad/s for Table 6-1. The frame-invariant form
    /// is `β K_e (δ̇ − v ψ' J δ)` with `δ̇` the material deflection rate, i.e. the damping force
    /// `−β K_e δ̇ + β v frame_turn δ`.
    pub frame_turn: Mat<f64>,
    /// `Σ_e ψ'_e² J_eᵀ K_e,e J_e` (`3N × 3N`) \[N/m³\]: the elastic stiffness of each element
    /// applied to the co-rotation of its nodal translations from both sides, so that the
    /// Kelvin–Voigt dissipation of the co-rotated material rate `w_e = δ̇ − v ψ'_e J δ` of
    /// every element ([`Self::frame_turn`]) sums to
    /// `Σ_e w_eᵀ β K_e,e w_e = β (δ̇ᵀ K_e δ̇ − 2 v δ̇ᵀ frame_turn δ + v² δᵀ frame_turn2 δ)`
    /// (the Rayleigh dissipation function of the flowing model, [`super::FlowingBelt`]).
    pub frame_turn2: Mat<f64>,
    /// Pre-tension force of the reference state (`3N`) \[N\].
    pub pretension: Vec<f64>,
    /// Contact nodes of each pulley (two-pulley drive: pulley 0 = driver, 1 = driven).
    pub contact_nodes: Vec<Vec<usize>>,
    /// Radius of each pulley's contact surface \[m\]: the path radius plus the penalty
    /// penetration `p0` under the mounting pressure `T0/R`, so that the belt mounted with
    /// tension T0 has its line exactly on the path (the role of Ribaric §6.4 step 1, "move the
    /// pulleys apart until T0").
    pub contact_radius: Vec<f64>,
}

impl BeltFe {
    /// Build the loop on the mounted path of `drive`, each span and wrap divided into equal
    /// elements of at most `mesh`'s lengths ([`BeltMesh::counts`]). The section, mounting
    /// tension `T0`, contact and damping are the drive's.
    pub fn new(drive: &Drive, mesh: &BeltMesh) -> Result<Self, FlowError> {
        mesh.check_on(drive.path()).map_err(|e| e.within("mesh"))?;
        let elements = mesh.counts(drive.path());
        let path = drive.path();
        let mut s = Vec::new();
        for (piece, &n) in path.pieces().iter().zip(&elements) {
            for k in 0..n {
                s.push(piece.s_start + piece.length * k as f64 / n as f64);
            }
        }
        let n_nodes = s.len();
        let l = path.length();
        let points: Vec<_> = s.iter().map(|&si| path.point(si)).collect();
        let position: Vec<[f64; 2]> = points.iter().map(|p| p.position).collect();
        let tangent: Vec<[f64; 2]> = points.iter().map(|p| p.tangent).collect();
        let tributary = tributary_lengths(&s, l);
        // unit chords u_i from node i to node i+1
        let chords: Vec<[f64; 2]> = (0..n_nodes)
            .map(|i| {
                let (a, b) = (position[i], position[(i + 1) % n_nodes]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let h = dx.hypot(dy);
                [dx / h, dy / h]
            })
            .collect();
        let t0 = drive.tension();
        let mut curvature = vec![[0.0; 2]; n_nodes];
        let mut pretension = vec![0.0; NODE_DOFS * n_nodes];
        for i in 0..n_nodes {
            let (u, up) = (chords[i], chords[(i + n_nodes - 1) % n_nodes]);
            for c in 0..2 {
                curvature[i][c] = (u[c] - up[c]) / tributary[i];
                pretension[NODE_DOFS * i + c] = t0 * (u[c] - up[c]);
            }
        }
        let section = Frame2dSection {
            ea: drive.belt().ea,
            ei: drive.belt().ei,
            mass_per_length: drive.belt().mass_per_length,
        };
        let ndof = NODE_DOFS * n_nodes;
        let mut stiffness = Mat::<f64>::zeros(ndof, ndof);
        let mut elastic = Mat::<f64>::zeros(ndof, ndof);
        let mut frame_turn = Mat::<f64>::zeros(ndof, ndof);
        let mut frame_turn2 = Mat::<f64>::zeros(ndof, ndof);
        let mut mass = vec![0.0; ndof];
        for i in 0..n_nodes {
            let j = (i + 1) % n_nodes;
            let dofs = [3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2];
            let e = Frame2d::new(dofs, position[i], position[j], section, t0)?;
            let k = e.stiffness();
            let turn = chord_turn_rate(position[i], position[j], tangent[i], tangent[j]);
            let kj = corotational_rate_block(&std::array::from_fn(|a| {
                std::array::from_fn(|b| k[(a, b)])
            }));
            // Jᵀ K J = (K J)ᵀ J (K symmetric)
            let jkj = corotational_rate_block(&transposed(&kj));
            let kg = e
                .matrix(MatrixKind::Geometric)
                .unwrap_or_else(|| Mat::zeros(6, 6));
            let m = e.mass(MassKind::Lumped);
            for a in 0..6 {
                mass[dofs[a]] += m[(a, a)];
                for b in 0..6 {
                    stiffness[(dofs[a], dofs[b])] += k[(a, b)] + kg[(a, b)];
                    elastic[(dofs[a], dofs[b])] += k[(a, b)];
                    frame_turn[(dofs[a], dofs[b])] += turn * kj[a][b];
                    frame_turn2[(dofs[a], dofs[b])] += turn * turn * jkj[a][b];
                }
            }
        }
        let (alpha, beta) = (drive.damping().alpha, drive.damping().beta);
        let damping = Mat::from_fn(ndof, ndof, |i, j| {
            beta * elastic[(i, j)] + if i == j { alpha * mass[i] } else { 0.0 }
        });
        let margin = mesh.contact_margin_nodes;
        let contact_nodes = (0..path.pulleys().len())
            .map(|p| {
                let (a, len) = path.arc_of(p).unwrap_or((0.0, 0.0));
                // nodes on the arc (both ends) plus `margin` nodes beyond each end
                let on: Vec<usize> = (0..n_nodes)
                    .filter(|&i| (s[i] - a).rem_euclid(l) <= len + 1e-9 * l)
                    .collect();
                // first and last along the path (the arc of pulley 0 wraps past node 0)
                let along = |i: &usize| (s[*i] - a).rem_euclid(l);
                let first = *on
                    .iter()
                    .min_by(|x, y| along(x).total_cmp(&along(y)))
                    .unwrap_or(&0);
                let last = *on
                    .iter()
                    .max_by(|x, y| along(x).total_cmp(&along(y)))
                    .unwrap_or(&0);
                let mut set: Vec<usize> = on.clone();
                for k in 1..=margin {
                    set.push((first + n_nodes - k) % n_nodes);
                    set.push((last + k) % n_nodes);
                }
                set.sort_unstable();
                set.dedup();
                set
            })
            .collect();
        let contact_radius = path
            .pulleys()
            .iter()
            .map(|p| p.radius + drive.contact().mounting_penetration(t0, p.radius))
            .collect();
        Ok(Self {
            contact_radius,
            drive: drive.clone(),
            mesh: *mesh,
            s,
            position,
            tangent,
            curvature,
            tributary,
            mass,
            stiffness,
            damping,
            frame_turn,
            frame_turn2,
            pretension,
            contact_nodes,
        })
    }

    /// The undeformed belt path (the drive's).
    pub fn path(&self) -> &BeltPath {
        self.drive.path()
    }

    /// Mounting tension `T0` of the reference state \[N\].
    pub fn tension(&self) -> f64 {
        self.drive.tension()
    }

    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.s.len()
    }

    /// Number of nodal DOFs (`3N`).
    pub fn n_dofs(&self) -> usize {
        NODE_DOFS * self.s.len()
    }

    /// Belt mass `e_tᵀ M e_t` \[kg\].
    pub fn belt_mass(&self) -> f64 {
        self.mass
            .chunks(NODE_DOFS)
            .zip(&self.tangent)
            .map(|(m, t)| m[0] * t[0] * t[0] + m[1] * t[1] * t[1])
            .sum()
    }

    /// Stacked tangents `e_t` (`3N`, zero rotational entries), Ribaric (5.4).
    pub fn stacked_tangent(&self) -> Vec<f64> {
        let mut e = vec![0.0; self.n_dofs()];
        for (i, t) in self.tangent.iter().enumerate() {
            e[NODE_DOFS * i] = t[0];
            e[NODE_DOFS * i + 1] = t[1];
        }
        e
    }

    /// Stacked curvature vectors `ε_n` (`3N`), Ribaric (5.4).
    pub fn stacked_curvature(&self) -> Vec<f64> {
        let mut e = vec![0.0; self.n_dofs()];
        for (i, k) in self.curvature.iter().enumerate() {
            e[NODE_DOFS * i] = k[0];
            e[NODE_DOFS * i + 1] = k[1];
        }
        e
    }

    /// The path derivative of the deflection field `t` (`3N × m`, columns in the node DOFs
    /// `(x, y, θ)`) at `node`, taken on the node's two elements' chords: the `(x, y)` rows
    /// (`2 × m`) of `δ_,s` for [`super::ContactVelocity::Chord`].
    ///
    /// For each element `e` at the node (chord `û_e`, normal `n̂_e = ẑ × û_e`, length `l_e`) the
    /// difference quotient `g_e = (δ_j − δ_i)/l_e` splits into its stretch `û_e·g_e` (the
    /// element's linear axial strain, Ribaric (5.5)) and its turn `n̂_e·g_e`; both are averaged
    /// with the tributary weights `l_e/(l₋ + l₊)` and set in the node's frame `(t̂, ẑ × t̂)`:
    /// `δ_,s = ε̄ t̂ + φ̄ (ẑ × t̂)`. So the tangential material rate `v (1 + t̂·δ_,s)` of Ribaric
    /// (5.10) is `v (1 + ε̄)`, the mean strain the elements carry (mass conservation on the
    /// mesh), also at a tangent point, where the Cartesian difference of App. A rotates the
    /// wrap's radial deflection into the tangent. Exact (zero) for a rigid translation; equal
    /// to App. A's three-point difference on a straight uniform run.
    pub fn chord_rate_rows(&self, t: MatRef<'_, f64>, node: usize) -> Mat<f64> {
        let nn = self.n_nodes();
        let (prev, next) = ((node + nn - 1) % nn, (node + 1) % nn);
        let chord = |a: usize, b: usize| {
            let (pa, pb) = (self.position[a], self.position[b]);
            let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
            let l = dx.hypot(dy);
            ([dx / l, dy / l], l)
        };
        let sides = [
            (prev, node, chord(prev, node)),
            (node, next, chord(node, next)),
        ];
        let total: f64 = sides.iter().map(|s| s.2.1).sum();
        let tan = self.tangent[node];
        let nrm = [-tan[1], tan[0]];
        Mat::from_fn(2, t.ncols(), |r, j| {
            let (mut stretch, mut turn) = (0.0, 0.0);
            for &(a, b, (u, l)) in &sides {
                let g = [
                    (t[(NODE_DOFS * b, j)] - t[(NODE_DOFS * a, j)]) / l,
                    (t[(NODE_DOFS * b + 1, j)] - t[(NODE_DOFS * a + 1, j)]) / l,
                ];
                let w = l / total;
                stretch += w * (u[0] * g[0] + u[1] * g[1]);
                turn += w * (u[0] * g[1] - u[1] * g[0]);
            }
            stretch * tan[r] + turn * nrm[r]
        })
    }

    /// Pulley index of each contact node (`None` for free nodes).
    pub fn node_pulley(&self) -> Vec<Option<usize>> {
        let mut out = vec![None; self.n_nodes()];
        for (p, set) in self.contact_nodes.iter().enumerate() {
            for &i in set {
                out[i] = Some(p);
            }
        }
        out
    }

    /// The flow grid of the closed loop (node arc lengths, period `L`).
    pub fn grid(&self) -> Result<FlowGrid, FlowError> {
        FlowGrid::new(
            self.s.clone(),
            Topology::Closed {
                period: self.path().length(),
            },
        )
    }
}

/// Rate `dψ/ds` \[1/m\] at which the chord of an element turns when its two material nodes,
/// at `a` and `b` with path tangents `ta` and `tb`, move along the path: with `d = b − a`,
/// `ψ = atan2(d_y, d_x)` and `ḋ = v (tb − ta)`, `dψ/ds = (d × (tb − ta)) / |d|²`. Exactly `1/R`
/// for a chord on an arc of radius R, 0 on a span. Used by the frame-invariant damping of both
/// belt formulations ([`BeltFe::frame_turn`]).
pub fn chord_turn_rate(a: [f64; 2], b: [f64; 2], ta: [f64; 2], tb: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let dt = [tb[0] - ta[0], tb[1] - ta[1]];
    (d[0] * dt[1] - d[1] * dt[0]) / (d[0] * d[0] + d[1] * d[1])
}

/// `K J` for a 6×6 frame-element matrix `K` in global axes (DOFs `x, y, θ` of two nodes), with
/// `J` turning each node's translation by +90° (`J (x, y, θ) = (−y, x, 0)`): the map from the
/// deflections to the elastic force of their co-rotation, `Ṙ_e = −ψ̇ R_e J` (see
/// [`BeltFe::frame_turn`]).
pub fn corotational_rate_block(k: &[[f64; 6]; 6]) -> [[f64; 6]; 6] {
    let mut out = [[0.0; 6]; 6];
    for (o, r) in out.iter_mut().zip(k) {
        for n in [0, 3] {
            // (K J)[·][x_n] = K[·][y_n], (K J)[·][y_n] = −K[·][x_n]
            o[n] = r[n + 1];
            o[n + 1] = -r[n];
        }
    }
    out
}

/// The transpose of a 6×6 block.
fn transposed(k: &[[f64; 6]; 6]) -> [[f64; 6]; 6] {
    std::array::from_fn(|a| std::array::from_fn(|b| k[b][a]))
}

/// Axial tension \[N\] of each element `i → i+1` of the closed loop of nodes at `position`
/// \[m\] deflected by `d` (`x, y, θ` per node): `T0 + EA Δl/l` with the chord's linear stretch
/// `Δl = u·(d_j − d_i)` (`u` the unit chord) — the tension of the belt models linearised about
/// the mounted state (pre-tension `t0` \[N\], axial stiffness `ea` \[N\]).
pub fn chord_tensions(position: &[[f64; 2]], d: &[f64], t0: f64, ea: f64) -> Vec<f64> {
    loop_chords(position)
        .map(|(i, j, [dx, dy], l)| {
            let dl = (dx * (d[3 * j] - d[3 * i]) + dy * (d[3 * j + 1] - d[3 * i + 1])) / l;
            t0 + ea * dl / l
        })
        .collect()
}

/// Viscous axial force \[N\] of each element `i → i+1` of the closed loop of nodes at
/// `position` with path tangents `tangent` \[m\], deflected by `d` at the material rate `rate`
/// (`x, y, θ` per node) while the material moves along the path at `speed` \[m/s\]: the axial
/// part of the stiffness-proportional damping force `β K_e (δ̇ − v ψ′ J δ)` of both belt
/// formulations ([`BeltFe::frame_turn`]),
///
/// ```text
///   N_v = β EA u·(w_j − w_i)/l,   w = δ̇ − v ψ′_e J δ,   J (x, y) = (−y, x)
/// ```
///
/// (`u` the unit chord, `l` its length, `ψ′_e` [`chord_turn_rate`]): `β EA` times the
/// co-rotated material stretch rate of the element, the Kelvin–Voigt force `β EA Dε/Dt` that
/// the element carries beside its elastic force (the frame element's `K_e` couples no bending
/// into the axial stretch, so this is the whole axial damping force). `beta_ea = β EA` \[N s\].
/// In a steady drive `Dε/Dt = v dε/ds` (Ribaric (5.10)'s convective part): the force is zero
/// where the strain is uniform and carries the tension change `β v dT/ds` wherever it varies,
/// over the wraps and over a layer of length `β v` beyond each wrap where the elastic strain
/// relaxes to the span's (issue 34).
pub fn chord_viscous_forces(
    position: &[[f64; 2]], tangent: &[[f64; 2]], d: &[f64], rate: &[f64], speed: f64, beta_ea: f64,
) -> Vec<f64> {
    loop_chords(position)
        .map(|(i, j, [dx, dy], l)| {
            let turn = speed * chord_turn_rate(position[i], position[j], tangent[i], tangent[j]);
            let w = |k: usize| {
                [
                    rate[3 * k] + turn * d[3 * k + 1],
                    rate[3 * k + 1] - turn * d[3 * k],
                ]
            };
            let (wi, wj) = (w(i), w(j));
            beta_ea * (dx * (wj[0] - wi[0]) + dy * (wj[1] - wi[1])) / (l * l)
        })
        .collect()
}

/// The axial parts of [`BeltFe::damping`]'s `K_e`, [`BeltFe::frame_turn`] and
/// [`BeltFe::frame_turn2`] (`3N × 3N` each, without `β`): per element the bar stiffness
/// `K_a = (EA/l) [u uᵀ, −u uᵀ; −u uᵀ, u uᵀ]` on the translations (the axial block of the frame
/// element), `ψ'_e K_a J` and `ψ'_e² Jᵀ K_a J`. The flowing model's chord damping
/// ([`super::ViscousForce::Chord`]) removes them from the linear damping and carries the
/// axial viscous force itself, along the deformed chord.
pub(crate) fn axial_damping_parts(fe: &BeltFe) -> (Mat<f64>, Mat<f64>, Mat<f64>) {
    let n = fe.n_dofs();
    let ea = fe.drive.belt().ea;
    let (mut k, mut t1, mut t2) = (
        Mat::<f64>::zeros(n, n),
        Mat::<f64>::zeros(n, n),
        Mat::<f64>::zeros(n, n),
    );
    for (i, j, [dx, dy], l) in loop_chords(&fe.position) {
        let u = [dx / l, dy / l];
        let dofs = [3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2];
        let mut ka = [[0.0; 6]; 6];
        for a in 0..2 {
            for b in 0..2 {
                let x = ea / l * u[a] * u[b];
                ka[a][b] = x;
                ka[a + 3][b + 3] = x;
                ka[a][b + 3] = -x;
                ka[a + 3][b] = -x;
            }
        }
        let turn = chord_turn_rate(fe.position[i], fe.position[j], fe.tangent[i], fe.tangent[j]);
        let kj = corotational_rate_block(&ka);
        let jkj = corotational_rate_block(&transposed(&kj));
        for a in 0..6 {
            for b in 0..6 {
                k[(dofs[a], dofs[b])] += ka[a][b];
                t1[(dofs[a], dofs[b])] += turn * kj[a][b];
                t2[(dofs[a], dofs[b])] += turn * turn * jkj[a][b];
            }
        }
    }
    (k, t1, t2)
}

/// The chords of the elements `i → j = i + 1` (the last closing on node 0) of the closed loop
/// of nodes at `position` \[m\]: `(i, j, [dx, dy], l)` with the chord vector and its length
/// \[m\].
fn loop_chords(position: &[[f64; 2]]) -> impl Iterator<Item = (usize, usize, [f64; 2], f64)> {
    let n = position.len();
    (0..n).map(move |i| {
        let j = (i + 1) % n;
        let (a, b) = (position[i], position[j]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        (i, j, [dx, dy], dx.hypot(dy))
    })
}

/// The axial force of a co-rotated belt element (issue 34) as a function of its length ratio
/// `r = l/l₀` to its mounted length `l₀`: `N(r) = F(λ₀ r)`, with `F` the belt's
/// [`belt::MaterialLaw`] (stretch measured from the unstretched belt, as the ANCF element's)
/// and `λ₀ = F⁻¹(T₀)` the mounted stretch, so `N(1) = T₀`. `ea` is also the stiffness of the
/// linear model `K_e` whose linearisation the correction replaces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarLaw {
    /// Mounting tension `T₀` \[N\].
    pub t0: f64,
    /// Axial stiffness `EA` \[N\].
    pub ea: f64,
    /// The material law.
    pub law: belt::MaterialLaw,
    /// Mounted stretch `λ₀` \[-\].
    pub lambda0: f64,
}

impl BarLaw {
    /// The law of `drive`'s belt at its mounting tension.
    pub fn of(drive: &belt::Drive) -> Self {
        let s = drive.belt();
        let t0 = drive.tension();
        Self {
            t0,
            ea: s.ea,
            law: s.law,
            lambda0: s.stretch(t0),
        }
    }

    /// `(N, dN/dr)` \[N\] at the length ratio `r`.
    pub fn force(&self, r: f64) -> (f64, f64) {
        let (n, k) = self.law.force(self.ea, self.lambda0 * r);
        (n, k * self.lambda0)
    }
}

/// The chord of one element `i → j` of a closed loop, for the co-rotated axial force (issue 34):
/// the force `N` of [`BarLaw`] along the deformed chord `û = (l0 u + Δd)/l`, `Δd = d_j − d_i`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bar {
    /// First node.
    pub i: usize,
    /// Second node.
    pub j: usize,
    /// Unit reference chord.
    pub u: [f64; 2],
    /// Reference chord length `l0` \[m\].
    pub l: f64,
}

impl Bar {
    /// The elements of the closed loop of nodes at `position` \[m\].
    pub fn loop_of(position: &[[f64; 2]]) -> Vec<Self> {
        loop_chords(position)
            .map(|(i, j, [dx, dy], l)| Self {
                i,
                j,
                u: [dx / l, dy / l],
                l,
            })
            .collect()
    }

    /// Deformed chord `(û, l)` under the deflections `d` (3 per node).
    fn chord(&self, d: &[f64]) -> ([f64; 2], f64) {
        let a = [
            self.l * self.u[0] + d[3 * self.j] - d[3 * self.i],
            self.l * self.u[1] + d[3 * self.j + 1] - d[3 * self.i + 1],
        ];
        let l = a[0].hypot(a[1]);
        ([a[0] / l, a[1] / l], l)
    }

    /// Axial force `N(l/l0)` \[N\] of the deformed chord ([`BarLaw`]).
    pub fn force(&self, d: &[f64], law: &BarLaw) -> f64 {
        law.force(self.chord(d).1 / self.l).0
    }

    /// The co-rotated bar force on node `j` minus its linearisation about the reference chord
    /// (the axial `K_e` and string `K_g(T0)` parts of the linear model, Ribaric (5.5)):
    /// `c_j = −N û + T0 u + (EA/l0)(u·Δd) u + (T0/l0)(Δd − (u·Δd) u)` (on node `i`: `−c_j`),
    /// and, with `tangent`, `G = K(δ) − K(0)`, `K(δ) = N′ û ûᵀ + (N/l)(I − û ûᵀ)`
    /// (`N′ = dN/dl`), so that `∂c_j/∂Δd = −G`.
    pub fn correction(&self, d: &[f64], law: &BarLaw, tangent: bool) -> ([f64; 2], [[f64; 2]; 2]) {
        let (uh, l) = self.chord(d);
        let (n, dn) = law.force(l / self.l);
        let dn = dn / self.l;
        let t0 = law.t0;
        let u = self.u;
        let dd = [
            d[3 * self.j] - d[3 * self.i],
            d[3 * self.j + 1] - d[3 * self.i + 1],
        ];
        let ud = u[0] * dd[0] + u[1] * dd[1];
        let (ka, kg) = (law.ea / self.l, t0 / self.l);
        let c = std::array::from_fn(|a| {
            -n * uh[a] + t0 * u[a] + ka * ud * u[a] + kg * (dd[a] - ud * u[a])
        });
        let mut g = [[0.0; 2]; 2];
        if tangent {
            for (a, row) in g.iter_mut().enumerate() {
                for (b, x) in row.iter_mut().enumerate() {
                    let id = if a == b { 1.0 } else { 0.0 };
                    *x = dn * uh[a] * uh[b] + n / l * (id - uh[a] * uh[b])
                        - (ka * u[a] * u[b] + kg * (id - u[a] * u[b]));
                }
            }
        }
        (c, g)
    }
}

/// A naturally straight, co-rotated Euler–Bernoulli bending element `i → j` of the closed loop
/// (issue 34 item 2, [`super::BendingForce::CoRotated`]). Its bending energy is that of a belt
/// that is straight when unstressed,
///
/// ```text
///   U_e = ½ θ̄ᵀ B θ̄ = (2 EI/l₀)(θ̄_i² + θ̄_i θ̄_j + θ̄_j²),   B = (EI/l₀) [4 2; 2 4]
///   θ̄_k = θ̄₀,k + θ_k − Δψ,   Δψ = atan2(u × c, u · c),   c = l₀ u + d_j − d_i
/// ```
///
/// with `θ̄_k` the end rotations relative to the deformed chord `c` (the Hermite cubic's
/// bending block of Ribaric (5.5) written in the co-rotated frame; Crisfield, *Non-linear
/// Finite Element Analysis of Solids and Structures*, vol. 1, §7.2), `θ̄₀,k` the angle from the
/// mounted chord `u` to the path tangent at node `k` (`∓Δ/2` on an arc element of angle `Δ`,
/// 0 on a span) and `θ_k` the nodal rotation deflections. On a circular arc of radius `R` the
/// element's energy is `EI Δ²/(2 l₀)`, the constant curvature `Δ/l₀` of its cubic over its chord
/// (`EI l₀/(2R²)` to `O(Δ²)`: `(Δ/2)/sin(Δ/2)`), so the loop carries `½ ∫ EI κ² ds` of its
/// true curvature: the energy depends on the shape only, not on which material fills it, and the
/// material flowing through a wrap does no bending work at the tangent points (Ribaric (5.5)'s
/// frame elements are stress-free on the mounted polygon, a natural curvature that jumps by `1/R`
/// there). The linear model's bending block `Gᵀ B G` at the mounted state (`θ̄₀ = 0`) is
/// [`Self::linear_stiffness`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BendElement {
    /// First node.
    pub i: usize,
    /// Second node.
    pub j: usize,
    /// Unit mounted chord `u`.
    pub u: [f64; 2],
    /// Mounted chord length `l₀` \[m\].
    pub l: f64,
    /// Mounted end rotations relative to the chord `θ̄₀` \[rad\].
    pub theta0: [f64; 2],
    /// Bending stiffness `EI` \[N m²\].
    pub ei: f64,
}

impl BendElement {
    /// The elements of the closed loop of nodes at `position` with path tangents `tangent`
    /// (bending stiffness `ei` \[N m²\]).
    pub fn loop_of(position: &[[f64; 2]], tangent: &[[f64; 2]], ei: f64) -> Vec<Self> {
        loop_chords(position)
            .map(|(i, j, [dx, dy], l)| {
                let u = [dx / l, dy / l];
                let angle =
                    |t: [f64; 2]| (u[0] * t[1] - u[1] * t[0]).atan2(u[0] * t[0] + u[1] * t[1]);
                Self {
                    i,
                    j,
                    u,
                    l,
                    theta0: [angle(tangent[i]), angle(tangent[j])],
                    ei,
                }
            })
            .collect()
    }

    /// `B = (EI/l₀) [4 2; 2 4]`.
    fn b(&self) -> [[f64; 2]; 2] {
        let k = self.ei / self.l;
        [[4.0 * k, 2.0 * k], [2.0 * k, 4.0 * k]]
    }

    /// The deformed chord `c` under the deflections `d` (3 per node).
    fn chord(&self, d: &[f64]) -> [f64; 2] {
        [
            self.l * self.u[0] + d[3 * self.j] - d[3 * self.i],
            self.l * self.u[1] + d[3 * self.j + 1] - d[3 * self.i + 1],
        ]
    }

    /// End rotations `θ̄` relative to the deformed chord \[rad\].
    pub fn rotations(&self, d: &[f64]) -> [f64; 2] {
        let (u, c) = (self.u, self.chord(d));
        let dpsi = (u[0] * c[1] - u[1] * c[0]).atan2(u[0] * c[0] + u[1] * c[1]);
        [
            self.theta0[0] + d[3 * self.i + 2] - dpsi,
            self.theta0[1] + d[3 * self.j + 2] - dpsi,
        ]
    }

    /// Bending energy `U_e = ½ θ̄ᵀ B θ̄` \[J\].
    pub fn energy(&self, d: &[f64]) -> f64 {
        let (t, b) = (self.rotations(d), self.b());
        0.5 * (b[0][0] * t[0] * t[0] + 2.0 * b[0][1] * t[0] * t[1] + b[1][1] * t[1] * t[1])
    }

    /// The element's forces on its nodes, `−∂U_e/∂(x_i, y_i, θ_i, x_j, y_j, θ_j)`, and with
    /// `tangent` the stiffness `∂²U_e/∂(…)²`: with the end moments `m = B θ̄`, `n̂ = J c/|c|`,
    ///
    /// ```text
    ///   −∂U/∂θ_k = −m_k,   −∂U/∂d_i = −(m_i + m_j) n̂/l,   −∂U/∂d_j = +(m_i + m_j) n̂/l
    ///   K = Gᵀ B G − (m_i + m_j) [H −H; −H H],   H = ∂²ψ/∂c² = [2c_x c_y, c_y² − c_x²; ·, −2c_x c_y]/l⁴
    /// ```
    ///
    /// (`G = ∂θ̄/∂(…)`, rows `[n̂/l, 1, −n̂/l, 0]` and `[n̂/l, 0, −n̂/l, 1]`, `l = |c|`).
    pub fn forces(&self, d: &[f64], tangent: bool) -> ([f64; 6], [[f64; 6]; 6]) {
        let c = self.chord(d);
        let l2 = c[0] * c[0] + c[1] * c[1];
        // ∂ψ/∂c = n̂/l = (−c_y, c_x)/l²
        let p = [-c[1] / l2, c[0] / l2];
        let (t, b) = (self.rotations(d), self.b());
        let m = [
            b[0][0] * t[0] + b[0][1] * t[1],
            b[1][0] * t[0] + b[1][1] * t[1],
        ];
        let s = m[0] + m[1];
        let f = [-s * p[0], -s * p[1], -m[0], s * p[0], s * p[1], -m[1]];
        let mut k = [[0.0; 6]; 6];
        if tangent {
            let g = [
                [p[0], p[1], 1.0, -p[0], -p[1], 0.0],
                [p[0], p[1], 0.0, -p[0], -p[1], 1.0],
            ];
            let l4 = l2 * l2;
            let h = [
                [2.0 * c[0] * c[1] / l4, (c[1] * c[1] - c[0] * c[0]) / l4],
                [(c[1] * c[1] - c[0] * c[0]) / l4, -2.0 * c[0] * c[1] / l4],
            ];
            for (a, row) in k.iter_mut().enumerate() {
                for (e, x) in row.iter_mut().enumerate() {
                    *x = (0..2)
                        .map(|r| (0..2).map(|q| g[r][a] * b[r][q] * g[q][e]).sum::<f64>())
                        .sum();
                }
            }
            // −(m_i + m_j) ∂²ψ/∂d²: translations (0, 1) of i and (3, 4) of j
            for (ai, sa) in [(0, -1.0), (3, 1.0)] {
                for (ei, se) in [(0, -1.0), (3, 1.0)] {
                    for r in 0..2 {
                        for q in 0..2 {
                            k[ai + r][ei + q] -= s * sa * se * h[r][q];
                        }
                    }
                }
            }
        }
        (f, k)
    }

    /// The linear model's bending block at the mounted state, stress-free there
    /// (`θ̄₀ = 0`): `G₀ᵀ B G₀` with `G₀` of the mounted chord — the Hermite bending block of the
    /// frame element of Ribaric (5.5) in global axes (6 × 6, `x, y, θ` per node).
    pub fn linear_stiffness(&self) -> [[f64; 6]; 6] {
        let straight = Self {
            theta0: [0.0; 2],
            ..*self
        };
        let zero = vec![0.0; 3 * (self.i.max(self.j) + 1)];
        straight.forces(&zero, true).1
    }
}

/// The flowing-material basis `δ = T z` with its periodic derivatives along s (Ribaric
/// (5.9)–(5.13)).
///
/// Columns: first the boundary (contact-node translation) columns, i.e. the static modes
/// `[Ψ_s; I]` of Ribaric (5.9) with `Ψ^c = I`, then the kept fixed-interface (free-node) modes `Ψ^f`.
/// The contact-node rotations belong to the interior set, so they are represented by the static
/// and free-node modes (their stiff rotary-inertia modes are what truncation removes).
///
/// Reference condition (Ribaric 5.3, note U5): the tangential deflection of node 0 (where the
/// belt leaves the driver) is zero in every column — node 0's two boundary columns are merged
/// into one along its path normal. This removes the rank deficiency of (5.6): without it, a
/// uniform tangential deflection is indistinguishable from a change of the belt speed.
#[derive(Debug, Clone)]
pub struct FlowingBasis {
    /// `T` (`3N × m`).
    pub t: Mat<f64>,
    /// `T_,s`.
    pub ts: Mat<f64>,
    /// `T_,ss`.
    pub tss: Mat<f64>,
    /// Number of boundary (static-mode) columns; the remaining columns are free-node modes.
    pub n_boundary: usize,
}

impl FlowingBasis {
    /// Build the basis for `fe` keeping `free_modes` free-node modes (`None`: all).
    pub fn new(fe: &BeltFe, free_modes: Option<usize>) -> Result<Self, FlowError> {
        let n = fe.n_dofs();
        let pulley = fe.node_pulley();
        let mut boundary = Vec::new();
        for (i, p) in pulley.iter().enumerate() {
            if p.is_some() {
                boundary.push(NODE_DOFS * i);
                boundary.push(NODE_DOFS * i + 1);
            }
        }
        if pulley[0].is_none() {
            return Err(invalid(
                "belt basis",
                "node 0 (reference node) must be a contact node",
            ));
        }
        let part = DofPartition::from_boundary_dofs(n, &boundary).map_err(red)?;
        let n_interior = part.interior().len();
        let keep = free_modes.unwrap_or(n_interior).min(n_interior);
        let mass = Mat::from_fn(n, n, |i, j| if i == j { fe.mass[i] } else { 0.0 });
        let basis = build_basis(
            fe.stiffness.as_ref(),
            mass.as_ref(),
            &part,
            Method::CraigBampton,
            &ModeSelection::Lowest(keep),
        )
        .map_err(red)?;
        let psi = &basis.psi;
        let nb = part.boundary().len();
        // merge node 0's (x, y) columns (boundary positions 0 and 1) into its normal direction
        debug_assert_eq!((part.boundary()[0], part.boundary()[1]), (0, 1));
        let tan = fe.tangent[0];
        let nrm = [-tan[1], tan[0]];
        let m = psi.ncols() - 1;
        let t = Mat::from_fn(n, m, |i, j| {
            if j == 0 {
                nrm[0] * psi[(i, 0)] + nrm[1] * psi[(i, 1)]
            } else {
                psi[(i, j + 1)]
            }
        });
        let lines = FlowLine::per_component(
            &fe.grid()?,
            &(0..fe.n_nodes()).collect::<Vec<_>>(),
            NODE_DOFS,
        )?;
        let method = DerivativeMethod::FiniteDifference(FdScheme {
            first: FirstDifference::ThreePoint,
            second: SecondDifference::ThreePoint,
        });
        let d = mode_shape_derivatives(&lines, method, t.as_ref())?;
        Ok(Self {
            t,
            ts: d.d1,
            tss: d.d2,
            n_boundary: nb - 1,
        })
    }

    /// Number of modal coordinates `m`.
    pub fn len(&self) -> usize {
        self.t.ncols()
    }

    /// Whether the basis is empty (never for a constructed basis).
    pub fn is_empty(&self) -> bool {
        self.t.ncols() == 0
    }
}

fn red(e: reduction::ReductionError) -> FlowError {
    FlowError::LinearAlgebra {
        what: "belt reduction basis".into(),
        reason: e.to_string(),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Rigid rotation by `phi` about `c` of the mounted belt at the nodes `pos` with path
    /// tangents `tan`: deflections `δ_i = φ J (r_i − c)`, `θ_i = φ`, and the rate of their
    /// global components as the material flows along the path at unit speed, `φ J t_i`.
    pub(crate) fn rigid_rotation(
        pos: &[[f64; 2]], tan: &[[f64; 2]], c: [f64; 2], phi: f64,
    ) -> (Vec<f64>, Vec<f64>) {
        let n = 3 * pos.len();
        let (mut delta, mut rate) = (vec![0.0; n], vec![0.0; n]);
        for i in 0..pos.len() {
            let r = [pos[i][0] - c[0], pos[i][1] - c[1]];
            delta[3 * i] = -phi * r[1];
            delta[3 * i + 1] = phi * r[0];
            delta[3 * i + 2] = phi;
            rate[3 * i] = -phi * tan[i][1];
            rate[3 * i + 1] = phi * tan[i][0];
        }
        (delta, rate)
    }

    // chord_rate_rows against a second formulation: the strain and the turn of the deformed
    // chords themselves. A deflection field `ε δ` (every node moved, wrap and span nodes
    // alike) changes each element's length by `l ε û·g` and turns it by `ε n̂·g` to first order,
    // so the rows' tangential part must be the tributary mean of the chords' stretches
    // `(|Δx + ε Δδ| − l)/(ε l)` and the normal part the mean of their turns, to O(ε); a rigid
    // translation gives exactly zero, and on a straight uniform run the rows are App. A's
    // three-point difference (FlowingBasis::ts) to round-off.
    #[test]
    fn chord_rates_are_the_elements_stretch_and_turn() {
        let fe = BeltFe::new(&crate::belt::table_6_1(0.0, 0.0), &BeltMesh::default()).unwrap();
        let n = fe.n_nodes();
        // a smooth field with a penetration-like radial step on the wraps, and a translation
        let field = Mat::from_fn(3 * n, 2, |r, j| {
            let (i, c) = (r / 3, r % 3);
            if c == 2 {
                return 0.0;
            }
            let s = fe.s[i];
            let (t, nrm) = (fe.tangent[i], [-fe.tangent[i][1], fe.tangent[i][0]]);
            match j {
                0 => {
                    let u = 1e-3 * (7.0 * s).sin();
                    let w = if fe.curvature[i] != [0.0, 0.0] {
                        -8e-5
                    } else {
                        0.0
                    };
                    u * t[c] + w * nrm[c]
                }
                _ => [0.3, -0.7][c],
            }
        });
        let eps = 1e-6;
        let mut worst: f64 = 0.0;
        for i in 0..n {
            let rows = fe.chord_rate_rows(field.as_ref(), i);
            // translation: exactly zero
            assert_eq!((rows[(0, 1)], rows[(1, 1)]), (0.0, 0.0), "node {i}");
            let (t, nrm) = (fe.tangent[i], [-fe.tangent[i][1], fe.tangent[i][0]]);
            let (mut stretch, mut turn, mut total) = (0.0, 0.0, 0.0);
            for (a, b) in [((i + n - 1) % n, i), (i, (i + 1) % n)] {
                let d0 = [
                    fe.position[b][0] - fe.position[a][0],
                    fe.position[b][1] - fe.position[a][1],
                ];
                let d1 = [
                    d0[0] + eps * (field[(3 * b, 0)] - field[(3 * a, 0)]),
                    d0[1] + eps * (field[(3 * b + 1, 0)] - field[(3 * a + 1, 0)]),
                ];
                let l = d0[0].hypot(d0[1]);
                let angle = (d0[0] * d1[1] - d0[1] * d1[0]).atan2(d0[0] * d1[0] + d0[1] * d1[1]);
                stretch += (d1[0].hypot(d1[1]) - l) / eps;
                turn += angle * l / eps;
                total += l;
            }
            let (stretch, turn) = (stretch / total, turn / total);
            let got_t = t[0] * rows[(0, 0)] + t[1] * rows[(1, 0)];
            let got_n = nrm[0] * rows[(0, 0)] + nrm[1] * rows[(1, 0)];
            worst = worst.max((got_t - stretch).abs()).max((got_n - turn).abs());
        }
        // the field's rates are up to 7e-3 (1e-3·7) and 9e-3 (the 8e-5 step over 8.73 mm)
        assert!(
            worst < 1e-8,
            "largest difference from the chords: {worst:e}"
        );
        // straight uniform run: the middle of the first span against App. A's difference
        let basis = FlowingBasis::new(&fe, Some(4)).unwrap();
        let span: Vec<usize> = (0..n).filter(|&i| fe.node_pulley()[i].is_none()).collect();
        let mid = span[span.len() / 4];
        let rows = fe.chord_rate_rows(basis.t.as_ref(), mid);
        for j in 0..basis.len() {
            for r in 0..2 {
                let fd = basis.ts[(3 * mid + r, j)];
                assert!(
                    (rows[(r, j)] - fd).abs() <= 1e-9 * (1.0 + fd.abs()),
                    "node {mid} column {j} row {r}: {} vs {fd}",
                    rows[(r, j)]
                );
            }
        }
    }

    // The viscous axial force of chord_viscous_forces against the Kelvin–Voigt law in a steady
    // flow (analytical reference: N_v = β EA Dε/Dt = β EA v dε/ds): the tangential deflection
    // u(s) = a s²/2 along Table 6-1's loop (strain ε = u' = a s on the spans, advected at v, so
    // that the material rate of δ is v u' e_t plus the turn of e_t on the arcs) gives
    // N_v = β EA v a on every span element; a rigid rotation carried by the material gives 0.
    #[test]
    fn viscous_force_is_kelvin_voigt_on_the_material_rate() {
        let fe = BeltFe::new(&crate::belt::table_6_1(0.0, 0.0), &BeltMesh::default()).unwrap();
        let (beta_ea, v, a) = (1.8e-3 * 1.0e5, 3.0, 2e-3);
        let n = fe.n_nodes();
        let mut delta = vec![0.0; 3 * n];
        let mut rate = vec![0.0; 3 * n];
        for i in 0..n {
            let (s, t) = (fe.s[i], fe.tangent[i]);
            for c in 0..2 {
                delta[3 * i + c] = 0.5 * a * s * s * t[c];
                // D/Dt of u e_t at speed v: v (u' e_t + u κ e_n); on the spans κ = 0
                rate[3 * i + c] = v * a * s * t[c];
            }
        }
        let on_span = |i: usize| {
            let j = (i + 1) % n;
            let (ti, tj) = (fe.tangent[i], fe.tangent[j]);
            (ti[0] - tj[0]).abs() + (ti[1] - tj[1]).abs() < 1e-12 && fe.s[j] > fe.s[i]
        };
        let nv = chord_viscous_forces(&fe.position, &fe.tangent, &delta, &rate, v, beta_ea);
        let mut spans = 0;
        for (i, f) in nv.iter().enumerate().filter(|(i, _)| on_span(*i)) {
            assert!(
                (f - beta_ea * v * a).abs() < 1e-9 * beta_ea,
                "element {i}: {f} N"
            );
            spans += 1;
        }
        assert!(spans > 10, "{spans} span elements");
        for c in [[0.0, 0.0], [0.45, 0.0], [0.17, -0.3]] {
            let (delta, rate) = rigid_rotation(&fe.position, &fe.tangent, c, 1e-3);
            let rate: Vec<f64> = rate.iter().map(|r| v * r).collect();
            let nv = chord_viscous_forces(&fe.position, &fe.tangent, &delta, &rate, v, beta_ea);
            let big = nv.iter().fold(0.0f64, |m, f| m.max(f.abs()));
            assert!(big < 1e-9 * beta_ea, "rigid rotation about {c:?}: {big} N");
        }
    }

    // Frame invariance of the β damping (BeltFe::frame_turn): a rigid rotation of the mounted
    // belt about any point carried along by the flowing material has no strain rate, so
    // β K_e (δ_,s − ψ' J δ) vanishes (invariant); Ribaric (5.5)'s β K_e δ̇ on the global
    // components alone does not (≈ 30 N at the arc nodes for φ = 1 mrad at 3 m/s).
    #[test]
    fn damping_of_a_rigid_rotation_vanishes() {
        let fe = BeltFe::new(&crate::belt::table_6_1(0.0, 0.0), &BeltMesh::default()).unwrap();
        let n = fe.n_dofs();
        let (alpha, beta) = (fe.drive.damping().alpha, fe.drive.damping().beta);
        for c in [[0.0, 0.0], [0.45, 0.0], [0.17, -0.3]] {
            let (delta, rate) = rigid_rotation(&fe.position, &fe.tangent, c, 1e-3);
            let v = 3.0;
            let global: Vec<f64> = (0..n)
                .map(|a| {
                    (0..n)
                        .map(|b| {
                            let bk =
                                fe.damping[(a, b)] - if a == b { alpha * fe.mass[a] } else { 0.0 };
                            bk * v * rate[b]
                        })
                        .sum()
                })
                .collect();
            let corot: Vec<f64> = (0..n)
                .map(|a| {
                    global[a]
                        - (0..n)
                            .map(|b| beta * v * fe.frame_turn[(a, b)] * delta[b])
                            .sum::<f64>()
                })
                .collect();
            let big = global.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let small = corot.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(big > 10.0, "global-component damping {big} N");
            assert!(
                small < 1e-9 * big,
                "co-rotated damping {small} N vs {big} N"
            );
        }
    }

    // Issue 34: the co-rotated bar force on node j, the linear model's axial + string force plus
    // Bar::correction, lies along the deformed chord (no moment about any point: the element
    // balances angular momentum at finite rotation) with the magnitude N of the material law (BarLaw)
    // (invariant); the linear force alone has the moment ≈ N1·Δv about node i.
    #[test]
    fn co_rotated_bar_force_is_along_the_deformed_chord() {
        let (t0, ea) = (400.0, 8000.0);
        for law in [
            belt::MaterialLaw::Linear,
            belt::MaterialLaw::StVenantKirchhoff,
        ] {
            let bl = BarLaw {
                t0,
                ea,
                law,
                lambda0: law.stretch(ea, t0),
            };
            // N(1) = T0: the mounted bar carries the mounting tension
            assert!((bl.force(1.0).0 - t0).abs() < 1e-9 * t0);
            let pos = [[0.0, 0.0], [0.012, 0.003], [0.02, 0.01]];
            let bars = Bar::loop_of(&pos);
            let bar = bars[0];
            let d = [0.0, 0.0, 0.0, 1e-3, 1.5e-3, 0.0, 0.0, 0.0, 0.0];
            let (u, l) = (bar.u, bar.l);
            let dd = [d[3] - d[0], d[4] - d[1]];
            let ud = u[0] * dd[0] + u[1] * dd[1];
            let lin: [f64; 2] = std::array::from_fn(|a| {
                -(t0 * u[a] + ea / l * ud * u[a] + t0 / l * (dd[a] - ud * u[a]))
            });
            let (c, g) = bar.correction(&d, &bl, true);
            let f = [lin[0] + c[0], lin[1] + c[1]];
            let chord = [l * u[0] + dd[0], l * u[1] + dd[1]];
            let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
            let n = bar.force(&d, &bl);
            // the material law's force at the chord's stretch, along the chord
            let lc = chord[0].hypot(chord[1]);
            let expect = law.force(ea, bl.lambda0 * lc / l).0;
            assert!((n - expect).abs() < 1e-9 * n);
            assert!(cross(chord, f).abs() < 1e-9 * n * l, "{}", cross(chord, f));
            assert!((f[0].hypot(f[1]) - n).abs() < 1e-9 * n);
            // the linear force is off the chord: its moment about node i is Δv Δa (EA − T0)/l
            // (Δa = u·Δd, Δv = (Ju)·Δd): N1·Δv (1 − T0/EA), second order
            let dv = -u[1] * dd[0] + u[0] * dd[1];
            let m = dv * ud * (ea - t0) / l;
            assert!(m.abs() > 1e-3 && (cross(chord, lin) - m).abs() < 1e-9 * m.abs());
            // G = ∂(−c_j)/∂Δd by central differences
            for b in 0..2 {
                let h = 1e-8;
                let (mut dp, mut dm) = (d, d);
                dp[3 + b] += h;
                dm[3 + b] -= h;
                let (cp, _) = bar.correction(&dp, &bl, false);
                let (cm, _) = bar.correction(&dm, &bl, false);
                for a in 0..2 {
                    let fd = -(cp[a] - cm[a]) / (2.0 * h);
                    assert!(
                        (fd - g[a][b]).abs() < 1e-5 * ea / l,
                        "G[{a}][{b}] {fd} vs {}",
                        g[a][b]
                    );
                }
            }
            // at δ = 0 the correction vanishes; its derivative is the law's stiffness at the
            // mounted stretch minus the linear model's EA, along the chord
            let (c0, g0) = bar.correction(&[0.0; 9], &bl, true);
            assert!(c0.iter().all(|x| x.abs() < 1e-9));
            let k = (bl.force(1.0).1 - ea) / l;
            for (a, row) in g0.iter().enumerate() {
                for (b, x) in row.iter().enumerate() {
                    assert!((x - k * u[a] * u[b]).abs() < 1e-9 * ea / l);
                }
            }
        }
    }

    // The naturally straight co-rotated bending element (issue 34 item 2) against three
    // independent references: (1) closed form, a ring of n elements on a circle of radius R
    // stores EI Δ²/(2 l₀) per element (Δ = 2π/n, l₀ = 2R sin(Δ/2)), → π EI/R = ½ ∫ EI κ² ds,
    // and is in equilibrium (a straight ring closed on itself, no nodal force); (2) invariance,
    // a finite rigid rotation and translation of a deflected loop leaves the energy unchanged;
    // (3) central differences of the energy give the forces, and of the forces the tangent;
    // (4) at the mounted state without its natural curvature the tangent is the Hermite bending
    // block of fe-model's Frame2d (K_e minus its axial bar).
    #[test]
    fn co_rotated_bending_element_against_closed_forms() {
        let (ei, r) = (0.026, 0.028);
        for n in [8usize, 32, 128] {
            let dphi = 2.0 * std::f64::consts::PI / n as f64;
            let pos: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let a = dphi * k as f64;
                    [r * a.cos(), r * a.sin()]
                })
                .collect();
            let tan: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let a = dphi * k as f64;
                    [-a.sin(), a.cos()]
                })
                .collect();
            let els = BendElement::loop_of(&pos, &tan, ei);
            let d = vec![0.0; 3 * n];
            let u: f64 = els.iter().map(|e| e.energy(&d)).sum();
            let l0 = 2.0 * r * (0.5 * dphi).sin();
            let exact = n as f64 * ei * dphi * dphi / (2.0 * l0);
            assert!((u - exact).abs() < 1e-12 * exact, "n = {n}: {u} vs {exact}");
            let ring = std::f64::consts::PI * ei / r;
            let rel = (0.5 * dphi) / (0.5 * dphi).sin() - 1.0;
            assert!(((u - ring) / ring - rel).abs() < 1e-12, "n = {n}");
            let mut f = vec![0.0; 3 * n];
            for e in &els {
                let (fe, _) = e.forces(&d, false);
                for (a, x) in fe.iter().enumerate() {
                    let k = if a < 3 { 3 * e.i + a } else { 3 * e.j + a - 3 };
                    f[k] += x;
                }
            }
            let big = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(big < 1e-9 * ei / (r * r), "n = {n}: ring force {big} N");
        }
        // a four-node loop with a span and an arc, deflected, then moved rigidly
        let pos = [[0.0, 0.0], [0.02, 0.0], [0.03, 0.01], [0.01, 0.015]];
        let tan = [[1.0, 0.0], [1.0, 0.0], [0.6, 0.8], [-0.8, 0.6]];
        let els = BendElement::loop_of(&pos, &tan, ei);
        let d0: Vec<f64> = (0..12)
            .map(|k| 1e-3 * ((k as f64 * 1.7).sin() + if k % 3 == 2 { 50.0 } else { 0.0 }))
            .collect();
        let energy = |d: &[f64]| els.iter().map(|e| e.energy(d)).sum::<f64>();
        let (phi, c, shift) = (0.7f64, [0.01, -0.02], [0.003, -0.001]);
        let (cs, sn) = (phi.cos(), phi.sin());
        let moved: Vec<f64> = (0..12)
            .map(|k| {
                let (i, a) = (k / 3, k % 3);
                if a == 2 {
                    return d0[k] + phi;
                }
                let x = [
                    pos[i][0] + d0[3 * i] - c[0],
                    pos[i][1] + d0[3 * i + 1] - c[1],
                ];
                let y = [cs * x[0] - sn * x[1], sn * x[0] + cs * x[1]];
                c[a] + y[a] + shift[a] - pos[i][a]
            })
            .collect();
        let (u0, u1) = (energy(&d0), energy(&moved));
        assert!(u0 > 1e-3 && (u1 - u0).abs() < 1e-12 * u0, "{u0} vs {u1}");
        for e in &els {
            let (f, k) = e.forces(&d0, true);
            let dofs = [
                3 * e.i,
                3 * e.i + 1,
                3 * e.i + 2,
                3 * e.j,
                3 * e.j + 1,
                3 * e.j + 2,
            ];
            for b in 0..6 {
                let h = 1e-7;
                let (mut dp, mut dm) = (d0.clone(), d0.clone());
                dp[dofs[b]] += h;
                dm[dofs[b]] -= h;
                let fd = -(e.energy(&dp) - e.energy(&dm)) / (2.0 * h);
                assert!(
                    (fd - f[b]).abs() < 1e-6 * (1.0 + f[b].abs()),
                    "f[{b}] {fd} vs {}",
                    f[b]
                );
                let (fp, _) = e.forces(&dp, false);
                let (fm, _) = e.forces(&dm, false);
                for a in 0..6 {
                    let kd = -(fp[a] - fm[a]) / (2.0 * h);
                    let scale = ei / (e.l * e.l * e.l);
                    assert!(
                        (kd - k[a][b]).abs() < 1e-5 * scale,
                        "K[{a}][{b}] {kd} vs {}",
                        k[a][b]
                    );
                }
            }
        }
        // the mounted linear block against Frame2d (independent assembly of Ribaric (5.5))
        let section = Frame2dSection {
            ea: 1.0e5,
            ei,
            mass_per_length: 0.1,
        };
        for e in &els {
            let fr = Frame2d::new([0, 1, 2, 3, 4, 5], pos[e.i], pos[e.j], section, 0.0).unwrap();
            let ke = fr.stiffness();
            let kb = e.linear_stiffness();
            for a in 0..6 {
                for b in 0..6 {
                    let (ta, tb) = (a % 3 < 2, b % 3 < 2);
                    let sa = if a < 3 { -1.0 } else { 1.0 };
                    let sb = if b < 3 { -1.0 } else { 1.0 };
                    let bar = if ta && tb {
                        sa * sb * 1.0e5 / e.l * e.u[a % 3] * e.u[b % 3]
                    } else {
                        0.0
                    };
                    let x = ke[(a, b)] - bar;
                    assert!((x - kb[a][b]).abs() < 1e-9 * ei / e.l.powi(3), "[{a}][{b}]");
                }
            }
        }
    }

    // seed-000 note BELT-1: e_tᵀ M e_t = m_belt = ρ L_path, e_tᵀ M ε_n ≈ 0, ε_n → e_n/R on arcs.
    #[test]
    fn path_kinematics_with_lumped_mass() {
        let fe = BeltFe::new(&crate::belt::table_6_1(0.0, 0.0), &BeltMesh::default()).unwrap();
        assert_eq!(fe.n_nodes(), 56);
        // exact: e_tᵀ M e_t = Σ m_i = ρ Σ chords (lumped, |e_t| = 1); the chord polygon is
        // O(h²) shorter than the path: within 0.05 % for 56 elements
        let chords: f64 = (0..56)
            .map(|i| {
                let (a, b) = (fe.position[i], fe.position[(i + 1) % 56]);
                (b[0] - a[0]).hypot(b[1] - a[1])
            })
            .sum();
        assert!((fe.belt_mass() - 0.096 * chords).abs() < 1e-12);
        let l = 2.0 * 0.45 + 2.0 * std::f64::consts::PI * 0.05;
        assert!((fe.belt_mass() / (0.096 * l) - 1.0).abs() < 5e-4);
        let (et, en) = (fe.stacked_tangent(), fe.stacked_curvature());
        let dot: f64 = (0..fe.n_dofs()).map(|i| et[i] * fe.mass[i] * en[i]).sum();
        assert!(dot.abs() < 1e-9, "e_tᵀ M ε_n = {dot}");
        // an interior arc node: |ε_n| = 1/R to O(h²)
        let k = fe.curvature[fe.contact_nodes[1][5]];
        assert!((k[0].hypot(k[1]) * 0.05 - 1.0).abs() < 2e-3);
        // the pre-tension force of an arc node is T0·L_i/R toward the centre
        let i = fe.contact_nodes[1][5];
        let f = (fe.pretension[3 * i], fe.pretension[3 * i + 1]);
        assert!(
            (f.0.hypot(f.1) - 310.0 * fe.tributary[i] / 0.05).abs()
                < 1e-2 * 310.0 * fe.tributary[i] / 0.05
        );
    }
}
