//! The partitioned (fixed / boundary / interior) sparse Craig–Bampton of `reduction::sparse`
//! on a small FE model: a cantilevered Hex8 bar (fe-model's `hex_block`), clamped face `x = 0`
//! as the fixed set, the tip face `x = l` as the boundary. References: a dense Craig–Bampton
//! (second formulation: `reduction::basis::static_modes` and fe-model's dense shift-invert eigen
//! solver on the model with the fixed DOFs removed), the dense Craig–Bampton of
//! `reduction::basis::build_basis`, the dense eigen solution of the full clamped model
//! (Rayleigh–Ritz bounds), and the invariants of Lin (6.3), (6.11), (6.19)–(6.25).
//!
//! Dense eigenvalues are taken with `count ≤ n/2` (fe-model's shift-invert form, accurate to
//! round-off relative to each mode): the all-modes form (`M = LLᵀ`, used by
//! `build_basis`) has an absolute error `ε·λ_max`, 1e-4 relative on this bar's first mode.

use faer::Mat;
use faer::sparse::SparseColMat;
use fe_model::element::{Elastic, Hex8Integration};
use fe_model::generate::hex_block;
use fe_model::{MassKind, SparseEigenOptions};
use reduction::basis::{Method, ModeSelection, build_basis};
use reduction::sparse::{
    CraigBamptonOptions, craig_bampton_modes, craig_bampton_sparse, fixed_interface_modes_sparse,
};
use reduction::{DofPartition, ReducedModel};

struct Bar {
    k: SparseColMat<usize, f64>,
    m: SparseColMat<usize, f64>,
    part: DofPartition,
}

/// 12 × 2 × 2 steel bar 1.2 × 0.2 × 0.12 m (distinct bending stiffnesses: no degenerate pairs),
/// consistent mass, 351 DOFs: 27 fixed (x = 0), 27 boundary (x = l, given in reverse order to
/// exercise the user order of the boundary columns), 297 interior.
fn bar() -> Bar {
    let steel = Elastic {
        young: 2.1e11,
        poisson: 0.3,
        density: 7850.0,
    };
    let model = hex_block(
        [1.2, 0.2, 0.12],
        [12, 2, 2],
        steel,
        Hex8Integration::Full,
        None,
        |p| p,
    )
    .unwrap();
    let (k, m) = model.k_and_m(MassKind::Consistent, false).unwrap();
    let fixed = model.mesh.node_set_dofs("x0", None).unwrap();
    let mut boundary = model.mesh.node_set_dofs("x1", None).unwrap();
    boundary.reverse();
    let part = DofPartition::new(k.nrows(), &boundary, &fixed).unwrap();
    Bar { k, m, part }
}

/// Lanczos even on this small model (the dense fallback is tested through the tire).
fn lanczos(n_modes: usize) -> CraigBamptonOptions {
    CraigBamptonOptions {
        n_modes,
        eigen: SparseEigenOptions {
            dense_below: 0,
            ..Default::default()
        },
    }
}

fn max_abs(a: &Mat<f64>) -> f64 {
    (0..a.ncols())
        .flat_map(|j| (0..a.nrows()).map(move |i| (i, j)))
        .fold(0.0, |s, (i, j)| s.max(a[(i, j)].abs()))
}

/// K and M restricted to the unfixed DOFs (the clamped model), dense.
fn clamped_dense(b: &Bar) -> (Mat<f64>, Mat<f64>, Vec<usize>) {
    let free = b.part.unfixed();
    let sel = |a: &Mat<f64>| Mat::from_fn(free.len(), free.len(), |i, j| a[(free[i], free[j])]);
    (sel(&b.k.to_dense()), sel(&b.m.to_dense()), free)
}

/// Dense Craig–Bampton `Ψ = [I 0; Ψs Φk]` (Lin (6.19)) of the bar with the fixed DOFs removed:
/// dense static modes of `reduction::basis`, fe-model's dense shift-invert modes of
/// `(K_ii, M_ii)`, dense projection; Ψ scattered back to all DOFs (fixed rows zero).
/// Returns `(Ψ, M_r, K_r)`.
fn dense_reference(b: &Bar, n_modes: usize) -> (Mat<f64>, Mat<f64>, Mat<f64>) {
    let (kf, mf, free) = clamped_dense(b);
    let pos = |d: usize| free.iter().position(|&f| f == d).unwrap();
    let bpos: Vec<usize> = b.part.boundary().iter().map(|&d| pos(d)).collect();
    let p2 = DofPartition::from_boundary_dofs(free.len(), &bpos).unwrap();
    let ps = reduction::basis::static_modes(kf.as_ref(), &p2).unwrap();
    let ii = p2.interior();
    let sel = |a: &Mat<f64>| Mat::from_fn(ii.len(), ii.len(), |i, j| a[(ii[i], ii[j])]);
    let modes = fe_model::dense_modes(sel(&kf).as_ref(), sel(&mf).as_ref(), n_modes).unwrap();
    let nb = bpos.len();
    let mut psi_f = Mat::<f64>::zeros(free.len(), nb + n_modes);
    for (c, &d) in bpos.iter().enumerate() {
        psi_f[(d, c)] = 1.0;
        for (r, &di) in ii.iter().enumerate() {
            psi_f[(di, c)] = ps[(r, c)];
        }
    }
    for j in 0..n_modes {
        for (r, &di) in ii.iter().enumerate() {
            psi_f[(di, nb + j)] = modes.vectors[(r, j)];
        }
    }
    let mr = psi_f.transpose() * (&mf * &psi_f);
    let kr = psi_f.transpose() * (&kf * &psi_f);
    let mut psi = Mat::zeros(b.part.n(), nb + n_modes);
    for (r, &d) in free.iter().enumerate() {
        for j in 0..psi.ncols() {
            psi[(d, j)] = psi_f[(r, j)];
        }
    }
    (psi, mr, kr)
}

/// The `count` lowest eigenvalues of a (reduced) pencil, fe-model's accurate dense form.
fn lowest(k: &Mat<f64>, m: &Mat<f64>, count: usize) -> Vec<f64> {
    assert!(2 * count <= k.nrows());
    fe_model::dense_modes(k.as_ref(), m.as_ref(), count)
        .unwrap()
        .values
}

/// `a ≈ s b s` entrywise, `s` = the column signs, within `tol · √(|b_ii b_jj|)`.
fn same_reduced(a: &Mat<f64>, b: &Mat<f64>, s: &[f64], tol: f64, what: &str) {
    for i in 0..b.nrows() {
        for j in 0..b.ncols() {
            let scale = (b[(i, i)] * b[(j, j)]).abs().sqrt();
            let d = (a[(i, j)] - s[i] * s[j] * b[(i, j)]).abs();
            assert!(
                d <= tol * scale,
                "{what}[{i},{j}]: {} vs {}",
                a[(i, j)],
                b[(i, j)]
            );
        }
    }
}

#[test]
fn partitioned_cb_equals_the_dense_craig_bampton() {
    // second formulation: the dense Craig–Bampton of `reduction::basis` on the model with the
    // fixed DOFs removed; the same reduction up to the sign of each mode column
    let b = bar();
    let nk = 8;
    let (red, rep) =
        craig_bampton_sparse(b.k.as_ref(), b.m.as_ref(), &b.part, &lanczos(nk), 3).unwrap();
    let eig = rep.eigen.as_ref().unwrap();
    assert!(!eig.dense_fallback);
    assert_eq!(eig.sturm_count, eig.found_below_cut);
    assert_eq!((rep.n_fixed, rep.n_boundary, rep.n_modes), (27, 27, nk));
    assert_eq!(red.method, Method::CraigBampton);
    let (psi_d, mr_d, kr_d) = dense_reference(&b, nk);
    assert_eq!(red.psi.ncols(), psi_d.ncols());
    let nb = b.part.boundary().len();
    let mut s = vec![1.0; nb + nk];
    for j in nb..nb + nk {
        let dot: f64 = (0..b.part.n())
            .map(|i| red.psi[(i, j)] * psi_d[(i, j)])
            .sum();
        s[j] = dot.signum();
    }
    let scale = max_abs(&psi_d);
    for j in 0..nb + nk {
        for i in 0..b.part.n() {
            let d = (red.psi[(i, j)] - s[j] * psi_d[(i, j)]).abs();
            assert!(
                d <= 1e-9 * scale,
                "Ψ[{i},{j}]: {} vs {}",
                red.psi[(i, j)],
                psi_d[(i, j)]
            );
        }
    }
    same_reduced(&red.stiffness, &kr_d, &s, 1e-9, "K_r");
    same_reduced(&red.mass, &mr_d, &s, 1e-9, "M_r");
    // the existing dense Craig–Bampton (`build_basis`, two-set partition on the clamped model,
    // and the generalised three-set partition on the whole model): the same static modes to
    // round-off, and the same kept-mode span within the accuracy of its all-modes eigen solve
    let (kf, mf, free) = clamped_dense(&b);
    let pos = |d: usize| free.iter().position(|&f| f == d).unwrap();
    let bpos: Vec<usize> = b.part.boundary().iter().map(|&d| pos(d)).collect();
    let p2 = DofPartition::from_boundary_dofs(free.len(), &bpos).unwrap();
    let sel = ModeSelection::Lowest(nk);
    let two = build_basis(kf.as_ref(), mf.as_ref(), &p2, Method::CraigBampton, &sel).unwrap();
    let (kd, md) = (b.k.to_dense(), b.m.to_dense());
    let three = build_basis(
        kd.as_ref(),
        md.as_ref(),
        &b.part,
        Method::CraigBampton,
        &sel,
    )
    .unwrap();
    for j in 0..nb + nk {
        for (r, &d) in free.iter().enumerate() {
            assert_eq!(
                three.psi[(d, j)],
                two.psi[(r, j)],
                "three-set vs two-set Ψ[{d},{j}]"
            );
        }
        for &d in b.part.fixed() {
            assert_eq!(three.psi[(d, j)], 0.0);
        }
    }
    for j in 0..nb {
        for i in 0..b.part.n() {
            assert!(
                (three.psi[(i, j)] - red.psi[(i, j)]).abs() <= 1e-9 * scale,
                "Ψs[{i},{j}]"
            );
        }
    }
    let lin = ReducedModel::from_basis(three, kd.as_ref(), md.as_ref(), None, 3).unwrap();
    let (a, c) = (
        lowest(&red.stiffness, &red.mass, 15),
        lowest(&lin.stiffness, &lin.mass, 15),
    );
    for (i, (x, y)) in a.iter().zip(&c).enumerate() {
        assert!(
            (x - y).abs() <= 1e-3 * y,
            "reduced eigenvalue {i}: {x} vs build_basis {y}"
        );
    }
}

#[test]
fn static_and_fixed_interface_modes_satisfy_their_definitions() {
    // invariants: Lin (6.3) static modes give unit boundary displacements with zero interior
    // force; Lin (6.11) modes are M_ii-orthonormal and K_ii-diagonal; Lin (6.20) K_r is block
    // diagonal; fixed rows of Ψ are zero; Ψᵀ M Ψ and Ψᵀ K Ψ are symmetric before symmetrisation
    let b = bar();
    let nk = 10;
    let cb = craig_bampton_modes(b.k.as_ref(), b.m.as_ref(), &b.part, &lanczos(nk)).unwrap();
    let basis = cb.basis(&b.part);
    let psi = &basis.psi;
    let (bd, fx, ii) = (b.part.boundary(), b.part.fixed(), b.part.interior());
    let nb = bd.len();
    for c in 0..nb + nk {
        for (r, &d) in bd.iter().enumerate() {
            let unit = if c == r { 1.0 } else { 0.0 };
            assert_eq!(psi[(d, c)], unit, "boundary row {d}, column {c}");
        }
        for &d in fx {
            assert_eq!(psi[(d, c)], 0.0, "fixed row {d}, column {c}");
        }
    }
    let (kd, md) = (b.k.to_dense(), b.m.to_dense());
    let kpsi = &kd * psi;
    for c in 0..nb {
        let reaction = bd.iter().fold(0.0f64, |s, &d| s.max(kpsi[(d, c)].abs()));
        for &d in ii {
            assert!(
                kpsi[(d, c)].abs() <= 1e-9 * reaction,
                "static mode {c}: interior force {} at DOF {d}",
                kpsi[(d, c)]
            );
        }
    }
    let mpsi = &md * psi;
    let mr = psi.transpose() * &mpsi;
    let kr = psi.transpose() * &kpsi;
    let lam = &cb.normal_modes.values;
    for i in 0..nk {
        for j in 0..nk {
            let unit = if i == j { 1.0 } else { 0.0 };
            assert!((mr[(nb + i, nb + j)] - unit).abs() < 1e-10, "ΦᵀMΦ[{i},{j}]");
            let kij = if i == j { lam[i] } else { 0.0 };
            assert!(
                (kr[(nb + i, nb + j)] - kij).abs() < 1e-9 * lam[nk - 1],
                "ΦᵀKΦ[{i},{j}]"
            );
        }
    }
    for c in 0..nb {
        for j in 0..nk {
            let scale = (kr[(c, c)] * lam[j]).sqrt();
            assert!(
                kr[(c, nb + j)].abs() < 1e-9 * scale,
                "K_r coupling [{c},{j}]"
            );
        }
    }
    for (a, what) in [(&mr, "M_r"), (&kr, "K_r")] {
        let scale = max_abs(a);
        for i in 0..a.nrows() {
            for j in 0..i {
                assert!(
                    (a[(i, j)] - a[(j, i)]).abs() <= 1e-12 * scale,
                    "{what}[{i},{j}]"
                );
            }
        }
    }
}

#[test]
fn reduced_eigenvalues_bound_the_full_ones_from_above() {
    // Rayleigh–Ritz: the CB subspace is a subspace of the clamped model's DOFs, so the k-th
    // reduced eigenvalue is ≥ the k-th full one; nested subspaces (more modes) lower them; with
    // every interior mode kept the reduction is exact. Reference: dense eigen solution of the
    // full clamped model.
    let b = bar();
    let (kf, mf, _) = clamped_dense(&b);
    let full = lowest(&kf, &mf, 40);
    // the same reference through the partitioned routine (empty boundary: clamped-model modes,
    // sparse Lanczos with the Sturm check)
    let clamped = DofPartition::new(b.part.n(), &[], b.part.fixed()).unwrap();
    let (low, rep) =
        fixed_interface_modes_sparse(b.k.as_ref(), b.m.as_ref(), &clamped, 12, &lanczos(0).eigen)
            .unwrap();
    let rep = rep.unwrap();
    assert!(!rep.dense_fallback && rep.sturm_count == Some(12));
    for (i, l) in low.values.iter().enumerate() {
        assert!(
            (l - full[i]).abs() <= 1e-9 * full[i],
            "clamped mode {i}: {l} vs {}",
            full[i]
        );
    }
    let mut previous: Option<Vec<f64>> = None;
    for nk in [0, 3, 12] {
        let (red, _) =
            craig_bampton_sparse(b.k.as_ref(), b.m.as_ref(), &b.part, &lanczos(nk), 3).unwrap();
        assert_eq!(red.n_reduced(), 27 + nk);
        let l = lowest(&red.stiffness, &red.mass, (27 + nk) / 2);
        for (i, li) in l.iter().enumerate() {
            assert!(
                *li >= full[i] * (1.0 - 1e-9),
                "{nk} modes, mode {i}: {li} < {}",
                full[i]
            );
        }
        if let Some(p) = &previous {
            for (i, (li, pi)) in l.iter().zip(p).enumerate() {
                assert!(
                    *li <= pi * (1.0 + 1e-9),
                    "{nk} modes, mode {i}: {li} > {pi}"
                );
            }
        }
        previous = Some(l);
    }
    let all = CraigBamptonOptions::with_modes(usize::MAX);
    let (red, rep) = craig_bampton_sparse(b.k.as_ref(), b.m.as_ref(), &b.part, &all, 3).unwrap();
    assert_eq!(rep.n_modes, b.part.interior().len());
    let l = lowest(&red.stiffness, &red.mass, 40);
    for (i, (li, r)) in l.iter().zip(&full).enumerate() {
        assert!(
            (li - r).abs() <= 1e-8 * r,
            "untruncated mode {i}: {li} vs {r}"
        );
    }
}

#[test]
fn unrestrained_interior_and_bad_partitions_are_named() {
    let b = bar();
    // nothing fixed, no boundary: K_ii is the free-free stiffness
    let free = DofPartition::new(b.part.n(), &[], &[]).unwrap();
    let e = craig_bampton_modes(b.k.as_ref(), b.m.as_ref(), &free, &lanczos(2))
        .unwrap_err()
        .to_string();
    assert!(e.contains("K_ii") && e.contains("fixed"), "{e}");
    let e = DofPartition::new(b.part.n(), &[3, 4], &[4])
        .unwrap_err()
        .to_string();
    assert!(e.contains("DOF 4"), "{e}");
    // a mass matrix of the wrong size
    let small = fe_model::sparse::from_dense(Mat::<f64>::identity(6, 6).as_ref(), 0.0).unwrap();
    let e = craig_bampton_modes(b.k.as_ref(), small.as_ref(), &b.part, &lanczos(2))
        .unwrap_err()
        .to_string();
    assert!(e.contains("mass matrix M") && e.contains("6x6"), "{e}");
}
