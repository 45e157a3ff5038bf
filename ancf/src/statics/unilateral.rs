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
//! penetrating inactive node is activated; the increment is repeated until the set is stable.

use super::{StaticOptions, check_sizes, free_coordinates};
use crate::element::Element;
use crate::error::{AncfError, invalid};
use crate::mesh::Mesh;
use contact::{ActiveSet, Surface, unilateral_row};
use faer::Mat;
use faer::prelude::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, Triplet};

/// Options of the unilateral static solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnilateralOptions {
    /// Load increments, Newton iterations and tolerance (the line search is not used: the
    /// KKT iteration takes full steps).
    pub newton: StaticOptions,
    /// An inactive node is activated when its gap is below `−gap_tolerance` \[m\].
    pub gap_tolerance: f64,
    /// Largest number of active-set passes per load increment.
    pub max_passes: usize,
}

impl Default for UnilateralOptions {
    fn default() -> Self {
        Self {
            newton: StaticOptions::default(),
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
pub fn solve_static_unilateral<E: Element, S: Surface + ?Sized>(
    mesh: &Mesh<E>,
    q0: &[f64],
    fixed: &[usize],
    load: &[f64],
    surface: &S,
    nodes: &[usize],
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
    let nf = free.len();
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
    let node_dofs = |node: usize| [mesh.node_dof(node, 0), mesh.node_dof(node, 1)];
    let gaps_of = |q: &[f64]| -> Vec<f64> {
        nodes
            .iter()
            .map(|&nd| surface.closest(mesh.node_position(q, nd)).gap)
            .collect()
    };

    let nc = nodes.len();
    let mut q = q0.to_vec();
    let mut lambda = vec![0.0; nc];
    let mut set = ActiveSet::new(nc);
    let mut passes = Vec::with_capacity(opts.newton.increments);
    let mut iterations = 0;
    let mut f = vec![0.0; n];
    let pattern = mesh.pattern();
    let mut kvals = pattern.zeros();
    let zeros = vec![0.0; nc];
    let gap0 = gaps_of(&q);
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

    for inc in 1..=opts.newton.increments {
        let lf = inc as f64 / opts.newton.increments as f64;
        let mut pass = 0;
        loop {
            pass += 1;
            let act: Vec<usize> = set.active().collect();
            let na = act.len();
            let dim = nf + na;
            let mut converged = false;
            let mut last = f64::INFINITY;
            for _ in 0..opts.newton.max_iterations {
                iterations += 1;
                kvals.fill(0.0);
                mesh.elastic_tangent_into(&q, &mut f, pattern, &mut kvals, 1.0);
                let mut trip = Vec::with_capacity(kvals.len() + 6 * na);
                for (i, j, p) in pattern.entries() {
                    if let (Some(a), Some(b)) = (map[i], map[j]) {
                        trip.push(Triplet::new(a, b, kvals[p]));
                    }
                }
                let mut rhs = Mat::<f64>::zeros(dim, 1);
                for (r, &c) in act.iter().enumerate() {
                    let nd = nodes[c];
                    let row = unilateral_row(surface, mesh.node_position(&q, nd), [0.0; 2]);
                    let sp = surface.closest(mesh.node_position(&q, nd));
                    let d = node_dofs(nd);
                    for a in 0..2 {
                        f[d[a]] += lambda[c] * row.normal[a];
                        if let Some(ia) = map[d[a]] {
                            trip.push(Triplet::new(ia, nf + r, -row.normal[a]));
                            trip.push(Triplet::new(nf + r, ia, -row.normal[a]));
                            for b in 0..2 {
                                if let Some(ib) = map[d[b]] {
                                    trip.push(Triplet::new(ia, ib, -lambda[c] * sp.dn_dp[a][b]));
                                }
                            }
                        }
                    }
                    rhs[(nf + r, 0)] = row.gap;
                }
                let mut res = 0.0;
                for (i, &k) in free.iter().enumerate() {
                    let r = f[k] + lf * load[k];
                    rhs[(i, 0)] = r;
                    res += r * r;
                }
                last = res.sqrt();
                if !last.is_finite() {
                    return Err(AncfError::NonFinite {
                        what: format!("unilateral static residual at load factor {lf}"),
                    });
                }
                let kkt = SparseColMat::try_new_from_triplets(dim, dim, &trip).map_err(|e| {
                    AncfError::Singular {
                        load_factor: lf,
                        detail: format!("KKT assembly: {e:?}"),
                    }
                })?;
                let singular = |e: String| AncfError::Singular {
                    load_factor: lf,
                    detail: format!("KKT matrix with {na} active contacts: {e}"),
                };
                let sym =
                    SymbolicLu::try_new(kkt.symbolic()).map_err(|e| singular(format!("{e:?}")))?;
                let lu = Lu::try_new_with_symbolic(sym, kkt.as_ref())
                    .map_err(|e| singular(format!("{e:?}")))?;
                let dx = lu.solve(&rhs);
                let mut step = 0.0f64;
                for (i, &k) in free.iter().enumerate() {
                    q[k] += dx[(i, 0)];
                    step = step.max(dx[(i, 0)].abs());
                }
                let mut dl = 0.0f64;
                for (r, &c) in act.iter().enumerate() {
                    lambda[c] += dx[(nf + r, 0)];
                    dl = dl.max(dx[(nf + r, 0)].abs());
                }
                if !(step.is_finite() && dl.is_finite()) {
                    return Err(AncfError::NonFinite {
                        what: format!("unilateral Newton step at load factor {lf}"),
                    });
                }
                let qmax = q.iter().map(|v| v.abs()).fold(0.0, f64::max);
                let lmax = lambda.iter().map(|v| v.abs()).fold(0.0, f64::max);
                // the multipliers come out of force balances whose round-off is ~EA·1e-16
                // per element, so they are checked relatively, at 1e-6
                if step <= opts.newton.tolerance * (1.0 + qmax) && dl <= 1e-6 * (1.0 + lmax) {
                    converged = true;
                    break;
                }
            }
            if !converged {
                return Err(AncfError::NoConvergence {
                    load_factor: lf,
                    iterations: opts.newton.max_iterations,
                    residual: last,
                });
            }
            // activate at most the deepest penetrating node per pass (activating every
            // penetrating node at once over-constrains the body and then releases the excess
            // one layer per pass: 49 instead of 2 passes for a beam settling on its tip)
            let mut gaps = gaps_of(&q);
            let deepest = (0..nc)
                .filter(|&c| !set.is_active(c))
                .min_by(|&a, &b| gaps[a].total_cmp(&gaps[b]));
            for c in 0..nc {
                if !set.is_active(c) && Some(c) != deepest {
                    gaps[c] = f64::INFINITY;
                }
            }
            let changed = set.update(&gaps, &zeros, &lambda, -opts.gap_tolerance);
            for (c, l) in lambda.iter_mut().enumerate() {
                if !set.is_active(c) {
                    *l = 0.0;
                }
            }
            if !changed {
                break;
            }
            if pass >= opts.max_passes {
                return Err(AncfError::ActiveSet {
                    load_factor: lf,
                    passes: pass,
                });
            }
        }
        passes.push(pass);
    }
    let gaps = gaps_of(&q);
    Ok(UnilateralSolution {
        q,
        active: (0..nc).map(|c| set.is_active(c)).collect(),
        multipliers: lambda,
        gaps,
        passes,
        iterations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::ProposedBeam;
    use crate::material::Material;
    use crate::mesh::straight_coordinates;
    use crate::section::Section;
    use contact::HalfPlane;

    fn bar() -> (Mesh<ProposedBeam>, Vec<f64>, Vec<usize>) {
        let mat = Material::new(2.0e9, 0.0, 1000.0).unwrap();
        let sec = Section::rectangle(0.05, 0.01).unwrap();
        let els = (0..2)
            .map(|_| ProposedBeam::new(0.5, mat, sec))
            .collect::<Result<Vec<_>, _>>()
            .unwrap();
        let mesh = Mesh::chain(els).unwrap();
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
        let e = solve_static_unilateral(
            &mesh,
            &q0,
            &fixed,
            &load,
            &HalfPlane::ground(-1.0),
            &[7],
            &opts,
        )
        .unwrap_err();
        assert!(e.to_string().contains("contact node 0"), "{e}");
        let e = solve_static_unilateral(
            &mesh,
            &q0,
            &fixed,
            &load,
            &HalfPlane::ground(0.1),
            &[2],
            &opts,
        )
        .unwrap_err();
        assert!(e.to_string().contains("penetrates"), "{e}");
        let e = solve_static_unilateral(
            &mesh,
            &q0,
            &fixed,
            &load,
            &HalfPlane::ground(-1.0),
            &[0],
            &opts,
        )
        .unwrap_err();
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
