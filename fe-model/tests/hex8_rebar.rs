//! Hexahedron with smeared fibre reinforcement (rebar): uniaxial stretch along and across the
//! fibre, patch test on a distorted mesh, rigid motions, symmetry and positive
//! semi-definiteness, rotation invariance, mass.

use faer::Mat;
use fe_model::element::{Elastic, Element, Fibre, Hex8, Hex8Integration, MassKind};
use fe_model::generate::hex_block;

const RUBBER: Elastic = Elastic {
    young: 8e6,
    poisson: 0.45,
    density: 1200.0,
};
/// Smeared fibre modulus E_f φ \[Pa\] (e.g. steel 200 GPa × 1 %).
const EF: f64 = 2e9;

const CUBE: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [0.0, 1.0, 1.0],
];

/// A skewed, tapered, warped hexahedron (positive Jacobian).
const DISTORTED: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.3, 0.1, -0.1],
    [1.1, 0.9, 0.2],
    [-0.2, 1.2, 0.1],
    [0.1, -0.1, 0.8],
    [1.2, 0.2, 1.1],
    [1.4, 1.3, 0.9],
    [0.2, 0.9, 1.2],
];

fn element(x: [[f64; 3]; 8], integ: Hex8Integration, fibres: Vec<Fibre>) -> Hex8 {
    let dofs = std::array::from_fn(|i| i);
    Hex8::new(dofs, x, RUBBER, integ, None)
        .unwrap()
        .with_fibres(fibres)
        .unwrap()
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = v.iter().map(|c| c * c).sum::<f64>().sqrt();
    v.map(|c| c / n)
}

/// Nodal displacements of the linear field `u = ε x` (ε a 3×3 matrix).
fn linear_field(x: &[[f64; 3]; 8], eps: [[f64; 3]; 3]) -> Vec<f64> {
    let mut u = vec![0.0; 24];
    for (a, p) in x.iter().enumerate() {
        for i in 0..3 {
            u[3 * a + i] = (0..3).map(|j| eps[i][j] * p[j]).sum();
        }
    }
    u
}

fn mat_vec(k: &Mat<f64>, u: &[f64]) -> Vec<f64> {
    (0..k.nrows())
        .map(|r| (0..k.ncols()).map(|c| k[(r, c)] * u[c]).sum())
        .collect()
}

/// Consistent nodal forces of a uniform stress σ by the surface integral
/// `f_a = ∮ N_a σ n dA` over the six faces (2×2 Gauss per face, exact for bilinear faces):
/// an independent reference for `K u` (divergence theorem, div σ = 0).
fn traction_forces(x: &[[f64; 3]; 8], sigma: [[f64; 3]; 3]) -> Vec<f64> {
    let xi_n = fe_model::element::hex8::NODE_XI;
    let g = 1.0 / 3f64.sqrt();
    let mut f = vec![0.0; 24];
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        for s in [-1.0, 1.0] {
            for (p, q) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
                let mut xi = [0.0; 3];
                xi[i] = s;
                xi[j] = p;
                xi[k] = q;
                // shape functions and tangents ∂x/∂ξ_j, ∂x/∂ξ_k
                let mut n = [0.0; 8];
                let (mut tj, mut tk) = ([0.0; 3], [0.0; 3]);
                for a in 0..8 {
                    let c = xi_n[a];
                    let fac = |d: usize| 1.0 + c[d] * xi[d];
                    n[a] = 0.125 * fac(0) * fac(1) * fac(2);
                    let dj = 0.125 * c[j] * fac(i) * fac(k);
                    let dk = 0.125 * c[k] * fac(i) * fac(j);
                    for d in 0..3 {
                        tj[d] += dj * x[a][d];
                        tk[d] += dk * x[a][d];
                    }
                }
                // outward area vector: s (t_j × t_k) (cyclic order, positive Jacobian)
                let da = [
                    s * (tj[1] * tk[2] - tj[2] * tk[1]),
                    s * (tj[2] * tk[0] - tj[0] * tk[2]),
                    s * (tj[0] * tk[1] - tj[1] * tk[0]),
                ];
                for a in 0..8 {
                    for r in 0..3 {
                        f[3 * a + r] += n[a] * (0..3).map(|c| sigma[r][c] * da[c]).sum::<f64>();
                    }
                }
            }
        }
    }
    f
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Uniaxial stress along the fibre: the strain `e [a⊗a − ν (I − a⊗a)]` (lateral contraction of
/// the isotropic matrix) carries `σ = (E + E_f φ) e a⊗a` (matrix uniaxial modulus plus the
/// smeared fibre modulus, rule of mixtures in the fibre direction). The element forces `K u`
/// equal the surface-traction forces of that stress (independent formulation), on the unit cube
/// (fibre along x) and on a distorted element (oblique fibre), for both integration rules; this
/// is the one-element patch test of the fibre term.
#[test]
fn stretch_along_fibre_carries_matrix_plus_fibre_modulus() {
    let e = 1e-3;
    let nu = RUBBER.poisson;
    for (x, a) in [(CUBE, [1.0, 0.0, 0.0]), (DISTORTED, unit([1.0, 0.4, -0.3]))] {
        for integ in [Hex8Integration::Full, Hex8Integration::SelectiveReduced] {
            let el = element(x, integ, vec![Fibre::new(a, EF, 0.0).unwrap()]);
            let eps = std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    let aa = a[i] * a[j];
                    let id = if i == j { 1.0 } else { 0.0 };
                    e * (aa - nu * (id - aa))
                })
            });
            let sigma = std::array::from_fn(|i| {
                std::array::from_fn(|j| (RUBBER.young + EF) * e * a[i] * a[j])
            });
            let u = linear_field(&x, eps);
            // the fibre term alone carries σ_f = E_f φ e a⊗a, exactly on any shape
            let sigma_f = std::array::from_fn(|i| std::array::from_fn(|j| EF * e * a[i] * a[j]));
            let ff = mat_vec(&el.fibre_stiffness(), &u);
            let fr = traction_forces(&x, sigma_f);
            let err = max_abs(&ff.iter().zip(&fr).map(|(p, q)| p - q).collect::<Vec<_>>());
            assert!(err < 1e-10 * max_abs(&fr), "{integ:?}: fibre err {err:e}");
            // matrix + fibre: exact for full integration on any shape; the selective-reduced
            // rubber's one-point volumetric term is exact on the parallelepiped only (on a
            // distorted single element the centre-point B differs from the mean B, Flanagan &
            // Belytschko 1981; it still passes the multi-element patch test below)
            let f = mat_vec(&el.stiffness(), &u);
            let fr = traction_forces(&x, sigma);
            if integ == Hex8Integration::Full || x == CUBE {
                let scale = max_abs(&fr);
                let err = max_abs(&f.iter().zip(&fr).map(|(p, q)| p - q).collect::<Vec<_>>());
                assert!(err < 1e-10 * scale, "{integ:?}: err {err:e} of {scale:e}");
            }
            // on the cube: the x-force on the face x = 1 is σ_xx · area = (E + E_f φ) e
            if x == CUBE {
                let fx: f64 = (0..8).filter(|&n| x[n][0] == 1.0).map(|n| f[3 * n]).sum();
                assert!((fx - (RUBBER.young + EF) * e).abs() < 1e-9 * fx);
            }
        }
    }
}

/// Any strain with zero fibre strain `a·ε·a = 0` (stretch across the fibre, shears in the
/// plane across it) gives the same forces with and without the fibre.
#[test]
fn stretch_across_fibre_is_unchanged() {
    let a = unit([1.0, 0.4, -0.3]);
    // b, c: an orthonormal pair across a
    let b = unit([0.4, -1.0, 0.0]);
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let eps: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            1e-3 * b[i] * b[j] - 4e-4 * c[i] * c[j] + 3e-4 * (b[i] * c[j] + c[i] * b[j])
        })
    });
    let eaa: f64 = (0..3)
        .map(|i| (0..3).map(|j| a[i] * eps[i][j] * a[j]).sum::<f64>())
        .sum();
    assert!(eaa.abs() < 1e-18);
    for integ in [Hex8Integration::Full, Hex8Integration::SelectiveReduced] {
        let u = linear_field(&DISTORTED, eps);
        let with = mat_vec(
            &element(DISTORTED, integ, vec![Fibre::new(a, EF, 0.0).unwrap()]).stiffness(),
            &u,
        );
        let without = mat_vec(&element(DISTORTED, integ, vec![]).stiffness(), &u);
        let d = max_abs(
            &with
                .iter()
                .zip(&without)
                .map(|(p, q)| p - q)
                .collect::<Vec<_>>(),
        );
        // the fibre term is 250× stiffer than the matrix: a leak would show at ~1e-1
        assert!(d < 1e-9 * max_abs(&without), "{integ:?}: {d:e}");
    }
}

/// Multi-element patch test: a distorted 3×3×3 block, every element with the same two fibre
/// families (an oblique one and a weaker one across it),
/// under a general linear displacement field: the interior nodes are in equilibrium (zero
/// force: the constant strain state is reproduced exactly, MacNeal & Harder 1985).
#[test]
fn distorted_block_patch_test_with_fibres() {
    for integ in [Hex8Integration::Full, Hex8Integration::SelectiveReduced] {
        let model = hex_block([1.0, 1.0, 1.0], [3, 3, 3], RUBBER, integ, None, |p| {
            let s = |v: f64| (v * 3.0 * std::f64::consts::PI).sin();
            let d = 0.06 * s(p[0]) * s(p[1]) * s(p[2]);
            [p[0] + d, p[1] - 0.7 * d, p[2] + 0.4 * d]
        })
        .unwrap();
        let mut fm = fe_model::FeModel::new(model.mesh.clone());
        for cell in &model.mesh.cells {
            let x: [[f64; 3]; 8] = std::array::from_fn(|a| model.mesh.nodes[cell.nodes[a]]);
            let dofs = std::array::from_fn(|d| 3 * cell.nodes[d / 3] + d % 3);
            let fibres = vec![
                Fibre::new([1.0, 0.3, 0.2], EF, 0.0).unwrap(),
                Fibre::new([0.1, 1.0, -0.5], 0.3 * EF, 0.0).unwrap(),
            ];
            fm.push(
                Hex8::new(dofs, x, RUBBER, integ, None)
                    .unwrap()
                    .with_fibres(fibres)
                    .unwrap(),
            );
        }
        let k = fm.stiffness().unwrap().to_dense();
        let lin = |x: [f64; 3]| {
            [
                1e-3 * (1.0 + 2.0 * x[0] - x[1] + 0.5 * x[2]),
                1e-3 * (-0.5 + 0.3 * x[0] + 1.5 * x[1] - x[2]),
                1e-3 * (0.2 - x[0] + 0.7 * x[1] + 0.9 * x[2]),
            ]
        };
        let u: Vec<f64> = (0..fm.n_dofs())
            .map(|d| lin(fm.mesh.nodes[d / 3])[d % 3])
            .collect();
        let f = mat_vec(&k, &u);
        let mut boundary = vec![false; fm.mesh.n_nodes()];
        for set in ["x0", "x1", "y0", "y1", "z0", "z1"] {
            for &n in fm.mesh.node_set(set).unwrap() {
                boundary[n] = true;
            }
        }
        let interior: Vec<f64> = (0..fm.n_dofs())
            .filter(|d| !boundary[d / 3])
            .map(|d| f[d])
            .collect();
        assert_eq!(interior.len(), 3 * 8);
        assert!(
            max_abs(&interior) < 1e-10 * max_abs(&f),
            "{integ:?}: {:e} of {:e}",
            max_abs(&interior),
            max_abs(&f)
        );
    }
}

/// The fibre stiffness alone is symmetric, positive semi-definite, of rank ≤ 8 (one rank-one
/// term per Gauss point) and gives zero force for the six rigid motions (`u = c + ω × x`).
#[test]
fn fibre_stiffness_symmetric_psd_rigid_free() {
    let el = element(
        DISTORTED,
        Hex8Integration::SelectiveReduced,
        vec![Fibre::new([0.2, 1.0, 0.5], EF, 0.0).unwrap()],
    );
    let kf = el.fibre_stiffness();
    let kmax = (0..24)
        .flat_map(|r| (0..24).map(move |c| (r, c)))
        .fold(0.0f64, |m, (r, c)| m.max(kf[(r, c)].abs()));
    assert!(kmax > 0.0);
    for r in 0..24 {
        for c in 0..24 {
            assert!((kf[(r, c)] - kf[(c, r)]).abs() <= 1e-13 * kmax);
        }
    }
    let eig = kf.self_adjoint_eigen(faer::Side::Lower).unwrap();
    let s = eig.S().column_vector();
    let lmax = s[23];
    assert!(s[0] > -1e-12 * lmax, "negative eigenvalue {}", s[0]);
    let rank = (0..24).filter(|&i| s[i] > 1e-10 * lmax).count();
    assert!((1..=8).contains(&rank), "rank {rank}");
    let k = el.stiffness();
    for mode in 0..6 {
        let u: Vec<f64> = (0..24)
            .map(|d| {
                let (x, i) = (DISTORTED[d / 3], d % 3);
                if mode < 3 {
                    if i == mode { 1.0 } else { 0.0 }
                } else {
                    // ω = e_(mode−3): (ω × x)_i
                    let w = mode - 3;
                    let (j, k) = ((w + 1) % 3, (w + 2) % 3);
                    if i == j {
                        -x[k]
                    } else if i == k {
                        x[j]
                    } else {
                        0.0
                    }
                }
            })
            .collect();
        assert!(
            max_abs(&mat_vec(&kf, &u)) < 1e-12 * kmax,
            "rigid mode {mode}"
        );
        assert!(
            max_abs(&mat_vec(&k, &u)) < 1e-12 * kmax,
            "rigid mode {mode}"
        );
    }
}

/// Rotating the element together with its fibre direction (`x' = R x`, `a' = R a`) rotates its
/// stiffness: `K' = T K Tᵀ` with `T = diag(R, …, R)` (objectivity of the fibre term).
#[test]
fn rotated_element_with_rotated_fibre() {
    let a = unit([1.0, 0.4, -0.3]);
    let rot = nalgebra::Rotation3::from_axis_angle(
        &nalgebra::Unit::new_normalize(nalgebra::Vector3::new(0.3, -0.5, 0.8)),
        0.9,
    );
    let r = rot.matrix();
    let apply = |v: [f64; 3]| {
        let w = r * nalgebra::Vector3::new(v[0], v[1], v[2]);
        [w[0], w[1], w[2]]
    };
    for integ in [Hex8Integration::Full, Hex8Integration::SelectiveReduced] {
        let k = element(DISTORTED, integ, vec![Fibre::new(a, EF, 0.0).unwrap()]).stiffness();
        let kr = element(
            DISTORTED.map(apply),
            integ,
            vec![Fibre::new(apply(a), EF, 0.0).unwrap()],
        )
        .stiffness();
        let t = Mat::from_fn(24, 24, |i, j| {
            if i / 3 == j / 3 {
                r[(i % 3, j % 3)]
            } else {
                0.0
            }
        });
        let expect = &t * &k * t.transpose();
        let kmax = (0..24)
            .flat_map(|i| (0..24).map(move |j| (i, j)))
            .fold(0.0f64, |m, (i, j)| m.max(k[(i, j)].abs()));
        for i in 0..24 {
            for j in 0..24 {
                assert!((kr[(i, j)] - expect[(i, j)]).abs() < 1e-10 * kmax);
            }
        }
    }
}

/// The smeared fibre density adds `ρ_f φ V` to the element mass (consistent and lumped), and
/// invalid fibre input gives a typed error naming the field.
#[test]
fn fibre_mass_and_input_errors() {
    let el = element(
        DISTORTED,
        Hex8Integration::Full,
        vec![
            Fibre::new([0.0, 0.0, 2.0], EF, 300.0).unwrap(),
            Fibre::new([1.0, 0.0, 0.0], EF, 100.0).unwrap(),
        ],
    );
    let v = el.volume();
    for kind in [MassKind::Consistent, MassKind::Lumped] {
        let m = el.mass(kind);
        let total: f64 = (0..24)
            .flat_map(|i| (0..24).map(move |j| (i, j)))
            .map(|(i, j)| m[(i, j)])
            .sum::<f64>()
            / 3.0;
        let expect = (RUBBER.density + 400.0) * v;
        assert!((total - expect).abs() < 1e-12 * expect, "{kind:?}");
    }
    assert!(
        Fibre::new([0.0; 3], EF, 0.0)
            .unwrap_err()
            .to_string()
            .contains("fibre direction")
    );
    assert!(
        Fibre::new([1.0, 0.0, 0.0], -1.0, 0.0)
            .unwrap_err()
            .to_string()
            .contains("fibre modulus")
    );
    let bad = Fibre {
        direction: [1.0, 1.0, 0.0],
        modulus: EF,
        density: 0.0,
    };
    assert!(
        Hex8::new(
            std::array::from_fn(|i| i),
            CUBE,
            RUBBER,
            Hex8Integration::Full,
            None
        )
        .unwrap()
        .with_fibres(vec![bad])
        .unwrap_err()
        .to_string()
        .contains("fibre direction")
    );
}
