//! Property tests of the reduction bases on random SPD models (independent references:
//! Lin §6.5.4 theorem, Rayleigh–Ritz bounds, static exactness of Guyan for boundary loads).
#![allow(clippy::needless_range_loop)] // index loops mirror the printed tables

use faer::Mat;
use proptest::prelude::*;
use reduction::basis::{Method, ModeSelection, build_basis, mode_condensation_matrices};
use reduction::linalg::{congruence, max_abs, span_distance, sym_gen_eig};
use reduction::{DofPartition, ReducedModel};

/// Random SPD stiffness `B Bᵀ + n I`, lumped or consistent SPD mass, boundary set.
fn model() -> impl Strategy<Value = (Mat<f64>, Mat<f64>, Vec<usize>, usize)> {
    (5usize..14).prop_flat_map(|n| {
        (
            prop::collection::vec(-1.0f64..1.0, n * n),
            prop::collection::vec(-1.0f64..1.0, n * n),
            prop::collection::vec(0.5f64..2.0, n),
            any::<bool>(),
            prop::sample::subsequence((0..n).collect::<Vec<_>>(), 1..n - 2),
            0usize..100,
        )
            .prop_map(move |(bk, bm, md, lumped, bnd, kr)| {
                let b = Mat::from_fn(n, n, |i, j| bk[i * n + j]);
                let k = &b * b.transpose() + Mat::<f64>::identity(n, n) * (n as f64 * 0.1);
                let m = if lumped {
                    Mat::from_fn(n, n, |i, j| if i == j { md[i] } else { 0.0 })
                } else {
                    let c = Mat::from_fn(n, n, |i, j| bm[i * n + j] * 0.3);
                    &c * c.transpose() + Mat::from_fn(n, n, |i, j| if i == j { md[i] } else { 0.0 })
                };
                let ni = n - bnd.len();
                let nk = 1 + kr % (ni - 1).max(1);
                (k, m, bnd, nk.min(ni))
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Lin §6.5.4: col-space(Ψ_MC) = col-space(Ψ_CB); identical reduced eigenvalues; the closed
    /// form of Ribaric (3.22)–(3.23) with the E9-corrected K_m equals the projection.
    #[test]
    fn cb_and_mc_span_the_same_space((k, m, bnd, nk) in model()) {
        let n = k.nrows();
        let part = DofPartition::from_boundary_dofs(n, &bnd).unwrap();
        let sel = ModeSelection::Lowest(nk);
        let cb = build_basis(k.as_ref(), m.as_ref(), &part, Method::CraigBampton, &sel).unwrap();
        let mc = build_basis(k.as_ref(), m.as_ref(), &part, Method::ModeCondensation, &sel).unwrap();
        prop_assert!(span_distance(cb.psi.as_ref(), mc.psi.as_ref()).unwrap() < 1e-8);
        let rcb = ReducedModel::from_basis(cb, k.as_ref(), m.as_ref(), None, 1).unwrap();
        let rmc = ReducedModel::from_basis(mc.clone(), k.as_ref(), m.as_ref(), None, 1).unwrap();
        let fcb = rcb.natural_frequencies_hz().unwrap();
        let fmc = rmc.natural_frequencies_hz().unwrap();
        for (a, b) in fcb.iter().zip(fmc.iter()) {
            prop_assert!((a - b).abs() <= 1e-8 * (1.0 + a.abs()), "{a} vs {b}");
        }
        let (mm, km) = mode_condensation_matrices(k.as_ref(), m.as_ref(), &part, &sel).unwrap();
        let dm = &mm - &rmc.mass;
        let dk = &km - &rmc.stiffness;
        prop_assert!(max_abs(dm.as_ref()) < 1e-9 * (1.0 + max_abs(mm.as_ref())));
        prop_assert!(max_abs(dk.as_ref()) < 1e-9 * (1.0 + max_abs(km.as_ref())));
    }

    /// Rayleigh–Ritz: every reduced eigenvalue bounds the full one from above, adding modes
    /// never raises them, and keeping all modes reproduces the full spectrum.
    #[test]
    fn reduced_eigenvalues_are_converging_upper_bounds((k, m, bnd, _nk) in model()) {
        let n = k.nrows();
        let part = DofPartition::from_boundary_dofs(n, &bnd).unwrap();
        let (full, _) = sym_gen_eig("full", k.as_ref(), m.as_ref()).unwrap();
        let ni = part.interior().len();
        let mut prev: Option<Vec<f64>> = None;
        for nk in 0..=ni {
            let method = if nk == 0 { Method::Guyan } else { Method::CraigBampton };
            let b = build_basis(k.as_ref(), m.as_ref(), &part, method, &ModeSelection::Lowest(nk)).unwrap();
            let kr = congruence(b.psi.as_ref(), k.as_ref(), b.psi.as_ref());
            let mr = congruence(b.psi.as_ref(), m.as_ref(), b.psi.as_ref());
            let (lam, _) = sym_gen_eig("reduced", kr.as_ref(), mr.as_ref()).unwrap();
            for (i, &l) in lam.iter().enumerate() {
                prop_assert!(l >= full[i] * (1.0 - 1e-9) - 1e-9, "mode {i}: {l} < {}", full[i]);
                if let Some(p) = &prev && i < p.len() {
                    prop_assert!(l <= p[i] * (1.0 + 1e-9) + 1e-9, "mode {i} rose with more modes");
                }
            }
            if nk == ni {
                for (a, b) in lam.iter().zip(full.iter()) {
                    prop_assert!((a - b).abs() <= 1e-8 * b.abs().max(1.0));
                }
            }
            prev = Some(lam);
        }
    }

    /// Guyan is statically exact for loads on boundary DOFs only (Lin §6.2; companion §16 item 17).
    #[test]
    fn guyan_is_statically_exact_for_boundary_loads(
        (k, m, bnd, _nk) in model(),
        load in prop::collection::vec(-10.0f64..10.0, 14),
    ) {
        let n = k.nrows();
        let part = DofPartition::from_boundary_dofs(n, &bnd).unwrap();
        let b = build_basis(k.as_ref(), m.as_ref(), &part, Method::Guyan, &ModeSelection::Lowest(0)).unwrap();
        let red = ReducedModel::from_basis(b, k.as_ref(), m.as_ref(), None, 1).unwrap();
        let mut f = vec![0.0; n];
        for (c, &d) in bnd.iter().enumerate() {
            f[d] = load[c];
        }
        let fr = red.reduce_load(&f).unwrap();
        let zr = reduction::linalg::solve_spd("K_G", red.stiffness.as_ref(), Mat::from_fn(fr.len(), 1, |i, _| fr[i]).as_ref()).unwrap();
        let z: Vec<f64> = (0..fr.len()).map(|i| zr[(i, 0)]).collect();
        let d_red = red.recover(&z).unwrap();
        let d_full = reduction::linalg::solve_spd("K", k.as_ref(), Mat::from_fn(n, 1, |i, _| f[i]).as_ref()).unwrap();
        for i in 0..n {
            prop_assert!((d_red[i] - d_full[(i, 0)]).abs() <= 1e-9 * (1.0 + d_full[(i, 0)].abs()));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// The sparse path (one Cholesky of K_ii for all static modes, sparse projection) equals
    /// the dense Guyan basis and reduced matrices.
    #[test]
    fn sparse_static_modes_equal_dense((k, m, bnd, _nk) in model()) {
        let n = k.nrows();
        let part = DofPartition::from_boundary_dofs(n, &bnd).unwrap();
        let ks = fe_model::sparse::from_dense(k.as_ref(), 0.0).unwrap();
        let ms = fe_model::sparse::from_dense(m.as_ref(), 0.0).unwrap();
        let bs = reduction::sparse::guyan_sparse(ks.as_ref(), &part).unwrap();
        let bd = build_basis(k.as_ref(), m.as_ref(), &part, Method::Guyan, &ModeSelection::Lowest(0)).unwrap();
        let d = &bs.psi - &bd.psi;
        prop_assert!(max_abs(d.as_ref()) < 1e-10 * (1.0 + max_abs(bd.psi.as_ref())));
        let rs = reduction::sparse::reduced_model_sparse(bs, ks.as_ref(), ms.as_ref(), 1).unwrap();
        let rd = ReducedModel::from_basis(bd, k.as_ref(), m.as_ref(), None, 1).unwrap();
        let dk = &rs.stiffness - &rd.stiffness;
        let dm = &rs.mass - &rd.mass;
        prop_assert!(max_abs(dk.as_ref()) < 1e-9 * (1.0 + max_abs(rd.stiffness.as_ref())));
        prop_assert!(max_abs(dm.as_ref()) < 1e-9 * (1.0 + max_abs(rd.mass.as_ref())));
    }
}
