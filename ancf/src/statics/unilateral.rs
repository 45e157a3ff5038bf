//! Static equilibrium with frictionless unilateral contact of mesh nodes against a rigid
//! obstacle, by Lagrange multipliers and an active set (Ribaric §7.3 / seed-000 note U4; the
//! contact crate's [`ActiveSet`] rule with zero gap rates).
//!
//! For the active contacts `A` the Newton iteration solves the KKT system of
//! `Q_e(q) + λ_F F + Σ_{i∈A} λ_i ∇g_i = 0`, `g_i(q) = 0`:
//!
//! ```text
//! [ K − Σ λ_i ∂²g_i/∂q²   −Gᵀ ] [Δq]   [ R ]
//! [ −G                     0  ] [Δλ] = [ g ],    G = ∂g_A/∂q,  R = the residual above,
//! ```
//!
//! with `g` the signed distance of the node to the obstacle, `∇g = n` its outward normal and
//! `∂²g/∂r² = ∂n/∂r` (the contact crate's [`unilateral_row`] data), `λ_i ≥ 0` the compressive
//! contact force \[N\]. After convergence, contacts with `λ_i < 0` are released and the deepest
//! penetrating inactive node is activated; the increment is repeated until the set is stable
//! (the shared [`mbd_core::newton::solve`] with [`NewtonProblem::settle`]).

use super::{AncfStaticOptions, check_sizes, free_coordinates, run_newton};
use crate::element::AncfElement;
use crate::error::{AncfError, invalid};
use crate::mesh::AncfMesh;
use contact::{ActiveSet, Surface, unilateral_row};
use faer::Mat;
use faer::prelude::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, Triplet};
use mbd_core::newton::{self, NewtonOptions, NewtonProblem, Settle};
use nalgebra::{Point2, Vector2};

/// Options of the unilateral static solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnilateralOptions {
    /// Load increments, Newton iterations and tolerance (the line search is not used: the
    /// KKT iteration takes full steps).
    pub newton: AncfStaticOptions,
    /// An inactive node is activated when its gap is below `−gap_tolerance` \[m\].
    pub gap_tolerance: f64,
    /// Largest number of active-set passes per load increment.
    pub max_passes: usize,
}

impl Default for UnilateralOptions {
    fn default() -> Self {
        Self {
            newton: AncfStaticOptions::default(),
            gap_tolerance: 1e-12,
            max_passes: 100,
        }
    }
}

/// Result of [`solve_static_unilateral`].
#[derive(Debug, Clone)]
pub struct UnilateralSolution {
    /// Equilibrium coordinates.
    pub q: Vec<f64>,
    /// Contact force `λ_i ≥ 0` of every candidate node \[N\] (0 when inactive).
    pub multipliers: Vec<f64>,
    /// Whether each candidate node is in contact.
    pub active: Vec<bool>,
    /// Gap of every candidate node \[m\] (0 within the tolerance when active).
    pub gaps: Vec<f64>,
    /// Active-set passes per load increment.
    pub passes: Vec<usize>,
    /// Total Newton iterations.
    pub iterations: usize,
}

impl UnilateralSolution {
    /// Sum of the contact forces \[N\].
    pub fn total_force(&self) -> f64 {
        self.multipliers.iter().sum()
    }
}

/// Solve `Q_e(q) + λ_F F + Σ λ_i n_i = 0` for `λ_F = 1/n, …, 1` with the nodes `nodes`
/// unilaterally constrained to stay outside `surface` (`g_i ≥ 0`, `λ_i ≥ 0`, `λ_i g_i = 0`),
/// keeping the coordinates `fixed` at their `q0` values. `q0` must be admissible (no node
/// penetrating by more than the tolerance).
pub fn solve_static_unilateral<E: AncfElement, S: Surface<2> + ?Sized>(
    mesh: &AncfMesh<E>, q0: &[f64], fixed: &[usize], load: &[f64], surface: &S, nodes: &[usize],
    opts: &UnilateralOptions,
) -> Result<UnilateralSolution, AncfError> {
    let n = mesh.n_dof();
    check_sizes("unilateral static solve", n, q0, load)?;
    if opts.newton.increments == 0 {
        return Err(invalid(
            "unilateral static solve: increments",
            "must be ≥ 1",
        ));
    }
    let (map, free) = free_coordinates("unilateral static solve", n, fixed)?;
    for (c, &node) in nodes.iter().enumerate() {
        if node >= mesh.n_nodes() {
            return Err(invalid(
                format!("unilateral static solve: contact node {c}"),
                format!("node {node} out of range 0..{}", mesh.n_nodes()),
            ));
        }
        if map[mesh.node_dof(node, 0)].is_none() && map[mesh.node_dof(node, 1)].is_none() {
            return Err(invalid(
                format!("unilateral static solve: contact node {c}"),
                format!("node {node} has both position coordinates fixed"),
            ));
        }
    }
    let nc = nodes.len();
    let mut problem = Unilateral {
        mesh,
        load,
        surface,
        nodes,
        map,
        free,
        set: ActiveSet::new(nc),
        act: Vec::new(),
        kvals: mesh.pattern().zeros(),
        f: vec![0.0; n],
        zeros: vec![0.0; nc],
        trip: Vec::new(),
        gap_tolerance: opts.gap_tolerance,
        lam: 0.0,
    };
    let gap0 = problem.gaps(q0);
    if let Some((c, g)) = gap0
        .iter()
        .enumerate()
        .find(|(_, g)| **g < -opts.gap_tolerance)
    {
        return Err(invalid(
            format!("unilateral static solve: contact node {}", nodes[c]),
            format!(
                "initial configuration penetrates the obstacle by {:e} m",
                -g
            ),
        ));
    }
    let newton = NewtonOptions {
        max_passes: opts.max_passes,
        ..opts.newton.newton(None)
    };
    let mut x = q0.to_vec();
    x.resize(n + nc, 0.0);
    let report = run_newton("unilateral static", &mut problem, &mut x, &newton)?;
    let multipliers = x.split_off(n);
    let gaps = problem.gaps(&x);
    Ok(UnilateralSolution {
        q: x,
        active: (0..nc).map(|c| problem.set.is_active(c)).collect(),
        multipliers,
        gaps,
        passes: report.increments.iter().map(|i| i.passes).collect(),
        iterations: report.iterations(),
    })
}

/// The KKT system of the module documentation: unknowns `x = (q, λ)` (all coordinates and
/// all candidate multipliers; fixed coordinates and inactive multipliers are never corrected),
/// residual `R = −(Q_e + λ_F F + Σ λ_i n_i)` on the free rows and `−g_i` on the active rows.
struct Unilateral<'a, E: AncfElement, S: Surface<2> + ?Sized> {
    mesh: &'a AncfMesh<E>,
    load: &'a [f64],
    surface: &'a S,
    nodes: &'a [usize],
    map: Vec<Option<usize>>,
    free: Vec<usize>,
    set: ActiveSet,
    /// Active candidates of the current pass, in KKT row order.
    act: Vec<usize>,
    kvals: Vec<f64>,
    f: Vec<f64>,
    zeros: Vec<f64>,
    trip: Vec<Triplet<usize, usize, f64>>,
    gap_tolerance: f64,
    /// Load factor of the last linearisation.
    lam: f64,
}

impl<E: AncfElement, S: Surface<2> + ?Sized> Unilateral<'_, E, S> {
    fn gaps(&self, q: &[f64]) -> Vec<f64> {
        self.nodes
            .iter()
            .map(|&nd| {
                self.surface
                    .closest(&Point2::from(self.mesh.node_position(q, nd)))
                    .gap
            })
            .collect()
    }

    fn n(&self) -> usize {
        self.f.len()
    }
}

impl<E: AncfElement, S: Surface<2> + ?Sized> NewtonProblem for Unilateral<'_, E, S> {
    type Error = AncfError;

    fn tangent_dim(&self) -> usize {
        self.n() + self.nodes.len()
    }

    fn linearize(&mut self, x: &[f64], lf: f64, r: &mut [f64]) -> Result<(), AncfError> {
        self.lam = lf;
        let (mesh, n, nf) = (self.mesh, self.n(), self.free.len());
        let (q, lambda) = x.split_at(n);
        self.act.clear();
        self.act.extend(self.set.active());
        let pattern = mesh.pattern();
        self.kvals.fill(0.0);
        mesh.elastic_tangent_into(q, &mut self.f, pattern, &mut self.kvals, 1.0);
        self.trip.clear();
        for (i, j, p) in pattern.entries() {
            if let (Some(a), Some(b)) = (self.map[i], self.map[j]) {
                self.trip.push(Triplet::new(a, b, self.kvals[p]));
            }
        }
        r.fill(0.0);
        for (row, &c) in self.act.iter().enumerate() {
            let nd = self.nodes[c];
            let p = Point2::from(mesh.node_position(q, nd));
            let crow = unilateral_row(self.surface, &p, &Vector2::zeros());
            let sp = self.surface.closest(&p);
            let d = [mesh.node_dof(nd, 0), mesh.node_dof(nd, 1)];
            for a in 0..2 {
                self.f[d[a]] += lambda[c] * crow.normal[a];
                if let Some(ia) = self.map[d[a]] {
                    self.trip.push(Triplet::new(ia, nf + row, -crow.normal[a]));
                    self.trip.push(Triplet::new(nf + row, ia, -crow.normal[a]));
                    for b in 0..2 {
                        if let Some(ib) = self.map[d[b]] {
                            self.trip
                                .push(Triplet::new(ia, ib, -lambda[c] * sp.dn_dp[(a, b)]));
                        }
                    }
                }
            }
            r[n + c] = -crow.gap;
        }
        for &k in &self.free {
            r[k] = -(self.f[k] + lf * self.load[k]);
        }
        Ok(())
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), AncfError> {
        let (n, nf, na) = (self.n(), self.free.len(), self.act.len());
        let dim = nf + na;
        let lf = self.lam;
        let kkt = SparseColMat::try_new_from_triplets(dim, dim, &self.trip).map_err(|e| {
            AncfError::Singular {
                load_factor: lf,
                detail: format!("KKT assembly: {e:?}"),
            }
        })?;
        let singular = |e: String| AncfError::Singular {
            load_factor: lf,
            detail: format!("KKT matrix with {na} active contacts: {e}"),
        };
        let sym = SymbolicLu::try_new(kkt.symbolic()).map_err(|e| singular(format!("{e:?}")))?;
        let lu =
            Lu::try_new_with_symbolic(sym, kkt.as_ref()).map_err(|e| singular(format!("{e:?}")))?;
        let rhs = Mat::<f64>::from_fn(dim, 1, |i, _| {
            if i < nf {
                -r[self.free[i]]
            } else {
                -r[n + self.act[i - nf]]
            }
        });
        let sol = lu.solve(&rhs);
        dx.fill(0.0);
        for (i, &k) in self.free.iter().enumerate() {
            dx[k] = sol[(i, 0)];
        }
        for (row, &c) in self.act.iter().enumerate() {
            dx[n + c] = sol[(nf + row, 0)];
        }
        Ok(())
    }

    /// `‖R‖₂` over the force rows.
    fn residual_norm(&self, r: &[f64]) -> f64 {
        r[..self.n()].iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    /// `‖Δq‖∞` (the multipliers are tested in [`Self::converged`]).
    fn correction_norm(&self, dx: &[f64]) -> f64 {
        newton::max_abs(&dx[..self.n()])
    }

    /// `‖q‖∞` after the update.
    fn scale(&self, _x_old: &[f64], x_new: &[f64]) -> f64 {
        newton::max_abs(&x_new[..self.n()])
    }

    /// The multipliers come out of force balances whose round-off is ~EA·1e-16 per element,
    /// so they are checked relatively, at 1e-6.
    fn converged(&self, _x_old: &[f64], x_new: &[f64], dx: &[f64]) -> bool {
        let n = self.n();
        newton::max_abs(&dx[n..]) <= 1e-6 * (1.0 + newton::max_abs(&x_new[n..]))
    }

    /// Activate at most the deepest penetrating node per pass (activating every penetrating
    /// node at once over-constrains the body and then releases the excess one layer per
    /// pass: 49 instead of 2 passes for a beam settling on its tip); release tensile contacts.
    fn settle(&mut self, x: &mut [f64], _lf: f64) -> Result<Settle, AncfError> {
        let n = self.n();
        let nc = self.nodes.len();
        let mut gaps = self.gaps(&x[..n]);
        let deepest = (0..nc)
            .filter(|&c| !self.set.is_active(c))
            .min_by(|&a, &b| gaps[a].total_cmp(&gaps[b]));
        for c in 0..nc {
            if !self.set.is_active(c) && Some(c) != deepest {
                gaps[c] = f64::INFINITY;
            }
        }
        let lambda = &mut x[n..];
        let changed = self
            .set
            .update(&gaps, &self.zeros, lambda, -self.gap_tolerance);
        for (c, l) in lambda.iter_mut().enumerate() {
            if !self.set.is_active(c) {
                *l = 0.0;
            }
        }
        Ok(if changed {
            Settle::Changed
        } else {
            Settle::Settled
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::ProposedBeam;
    use crate::material::Material;
    use crate::mesh::straight_coordinates;
    use crate::section::Section;
    use contact::HalfPlane;

    fn bar() -> (AncfMesh<ProposedBeam>, Vec<f64>, Vec<usize>) {
        let mat = Material::new(2.0e9, 0.0, 1000.0).unwrap();
        let sec = Section::rectangle(0.05, 0.01).unwrap();
        let els = (0..2)
            .map(|_| ProposedBeam::new(0.5, mat, sec))
            .collect::<Result<Vec<_>, _>>()
            .unwrap();
        let mesh = AncfMesh::chain(els).unwrap();
        let q0 = straight_coordinates(mesh.layout(), [0.0, 0.0], [1.0, 0.0], 2);
        let fixed = (0..4).map(|k| mesh.node_dof(0, k)).collect();
        (mesh, q0, fixed)
    }

    // Reference: bad input gives typed errors naming the item, never a panic.
    #[test]
    fn bad_input_is_reported() {
        let (mesh, q0, fixed) = bar();
        let load = vec![0.0; mesh.n_dof()];
        let opts = UnilateralOptions::default();
        let error = |height: f64, nodes: &[usize]| {
            solve_static_unilateral(
                &mesh,
                &q0,
                &fixed,
                &load,
                &HalfPlane::ground(height),
                nodes,
                &opts,
            )
            .unwrap_err()
        };
        let e = error(-1.0, &[7]);
        assert!(e.to_string().contains("contact node 0"), "{e}");
        let e = error(0.1, &[2]);
        assert!(e.to_string().contains("penetrates"), "{e}");
        let e = error(-1.0, &[0]);
        assert!(
            e.to_string().contains("both position coordinates fixed"),
            "{e}"
        );
    }

    // Reference: force balance of a rigid-support problem. A cantilever bar whose tip rests
    // on the ground at its own height carries any downward tip force F by the contact alone
    // (λ = |F|, no deflection); an upward force lifts it off (λ = 0, active set released).
    #[test]
    fn tip_on_ground_carries_the_load() {
        let (mesh, q0, fixed) = bar();
        let tip = mesh.node_dof(2, 1);
        let ground = HalfPlane::ground(0.0);
        let opts = UnilateralOptions::default();
        let mut load = vec![0.0; mesh.n_dof()];
        load[tip] = -100.0;
        let s =
            solve_static_unilateral(&mesh, &q0, &fixed, &load, &ground, &[1, 2], &opts).unwrap();
        assert_eq!(s.active, vec![false, true]);
        assert!(
            (s.multipliers[1] - 100.0).abs() < 1e-6,
            "{:?}",
            s.multipliers
        );
        assert!(s.q[tip].abs() < 1e-12);
        load[tip] = 100.0;
        let s =
            solve_static_unilateral(&mesh, &q0, &fixed, &load, &ground, &[1, 2], &opts).unwrap();
        assert_eq!(s.active, vec![false, false]);
        assert!(s.q[tip] > 0.0 && s.total_force() == 0.0);
    }
}
