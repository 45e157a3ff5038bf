//! Element-level validation of the ANCF elements (Kerkkänen ch. 2 and §3.1): rigid-body
//! invariants, exact kinetic energy, closed-form energies and mass, and tangent consistency.

use ancf::element::{AncfElement, BeltElement, OmarShabanaBeam, ProposedBeam};
use ancf::mesh::{AncfMesh, straight_coordinates};
use ancf::{Material, Section};

fn steel() -> Material {
    Material::new(2.07e11, 0.3, 7850.0).unwrap()
}

fn rotate(v: [f64; 2], th: f64) -> [f64; 2] {
    let (s, c) = th.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// Apply the rigid motion `r ↦ R(θ) r + d` to every 2-vector block (gradients are rotated only).
fn rigid(e: &[f64], positions: &[usize], th: f64, d: [f64; 2]) -> Vec<f64> {
    let mut out = e.to_vec();
    for b in 0..e.len() / 2 {
        let v = rotate([e[2 * b], e[2 * b + 1]], th);
        let p = positions.contains(&b);
        out[2 * b] = v[0] + if p { d[0] } else { 0.0 };
        out[2 * b + 1] = v[1] + if p { d[1] } else { 0.0 };
    }
    out
}

fn elements() -> Vec<(Box<dyn AncfElement>, Vec<usize>)> {
    let sec = Section::rectangle(0.1, 0.05).unwrap();
    vec![
        (
            Box::new(ProposedBeam::new(0.7, steel(), sec).unwrap()),
            vec![0, 2],
        ),
        (
            Box::new(OmarShabanaBeam::new(0.7, steel(), sec).unwrap()),
            vec![0, 3],
        ),
        (
            Box::new(BeltElement::new(0.7, steel(), sec, 1.0, 0.01, 5).unwrap()),
            vec![0, 3],
        ),
    ]
}

fn reference(el: &dyn AncfElement) -> Vec<f64> {
    straight_coordinates(el.layout(), [0.0, 0.0], [el.length(), 0.0], 1)
}

fn perturbed(el: &dyn AncfElement, amp: f64) -> Vec<f64> {
    let mut e = reference(el);
    for (k, v) in e.iter_mut().enumerate() {
        *v += amp * ((k as f64 * 1.7 + 0.3).sin());
    }
    e
}

// Invariant (Kerkkänen §1, requirement 1): any rigid motion gives zero strain and zero elastic
// forces.
#[test]
fn rigid_motion_gives_zero_strain_energy_and_forces() {
    for (el, pos) in elements() {
        let e0 = reference(el.as_ref());
        for (th, d) in [(0.3, [1.0, -2.0]), (2.5, [0.0, 5.0]), (-1.2, [-3.0, 0.1])] {
            let e = rigid(&e0, &pos, th, d);
            let u = el.strain_energy(&e);
            assert!(u.abs() < 1e-12, "U = {u} J after rigid motion");
            let mut q = vec![0.0; el.ndof()];
            el.elastic_forces(&e, &mut q);
            let qmax = q.iter().map(|v| v.abs()).fold(0.0, f64::max);
            assert!(
                qmax < 1e-4,
                "|Q_e| = {qmax} N after rigid motion (EA = 1e9 N)"
            );
        }
    }
}

// Invariant: the kinetic energy ½ vᵀMv of a rigid motion (translation v₀ + rotation ω about the
// centroid) equals ½ m |v₀|² + ½ J ω², J = ρ(A L³/12 + L I₂), exactly (3-element meshes).
#[test]
fn rigid_motion_kinetic_energy_is_exact() {
    let sec = Section::rectangle(0.1, 0.05).unwrap();
    let (l, n) = (2.1, 3);
    let (v0, w) = ([0.7, -1.3], 2.9);
    let rho = steel().density;
    let m = rho * sec.area * l;
    let j = rho * (sec.area * l.powi(3) / 12.0 + l * sec.i2);
    let exact = 0.5 * m * (v0[0] * v0[0] + v0[1] * v0[1]) + 0.5 * j * w * w;
    let check = |layout: ancf::NodeLayout, mass: &dyn Fn(&[f64]) -> f64| {
        // beam rotated by 0.4 rad, centroid at c
        let th = 0.4;
        let c = [0.3, 0.2];
        let t = rotate([1.0, 0.0], th);
        let a = [c[0] - 0.5 * l * t[0], c[1] - 0.5 * l * t[1]];
        let b = [c[0] + 0.5 * l * t[0], c[1] + 0.5 * l * t[1]];
        let q = straight_coordinates(layout, a, b, n);
        // velocity: position blocks get v0 + ω Ĩ (r − c), gradient blocks ω Ĩ r_g
        let cpn = layout.coords_per_node();
        let mut v = vec![0.0; q.len()];
        for node in 0..=n {
            for blk in 0..cpn / 2 {
                let k = node * cpn + 2 * blk;
                let (x, y) = if blk == 0 {
                    (q[k] - c[0], q[k + 1] - c[1])
                } else {
                    (q[k], q[k + 1])
                };
                let base = if blk == 0 { v0 } else { [0.0, 0.0] };
                v[k] = base[0] - w * y;
                v[k + 1] = base[1] + w * x;
            }
        }
        let t_num = mass(&v);
        assert!(
            (t_num - exact).abs() < 1e-10 * exact,
            "T = {t_num} J, exact {exact} J"
        );
    };
    let le = l / n as f64;
    let p = AncfMesh::chain(
        (0..n)
            .map(|_| ProposedBeam::new(le, steel(), sec).unwrap())
            .collect(),
    )
    .unwrap();
    check(p.layout(), &|v| p.kinetic_energy(v));
    let o = AncfMesh::chain(
        (0..n)
            .map(|_| OmarShabanaBeam::new(le, steel(), sec).unwrap())
            .collect(),
    )
    .unwrap();
    check(o.layout(), &|v| o.kinetic_energy(v));
    let bl = AncfMesh::chain(
        (0..n)
            .map(|_| BeltElement::new(le, steel(), sec, 1.0, 0.01, 5).unwrap())
            .collect(),
    )
    .unwrap();
    check(bl.layout(), &|v| bl.kinetic_energy(v));
}

// Second formulation: the closed-form energy of the proposed element (seed note §3.2.6, a, b, c
// vectors at the single Gauss point) and its closed-form mass matrix (§3.2.5).
#[test]
fn proposed_element_matches_closed_form_energy_and_mass() {
    let sec = Section::rectangle(0.1, 0.05).unwrap();
    let mat = Material::new(2.07e11, 0.3, 7850.0).unwrap();
    let l = 0.7;
    let el = ProposedBeam::new(l, mat, sec).unwrap();
    let e = perturbed(&el, 0.05);
    let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
    let a = [(e[4] - e[0]) / l, (e[5] - e[1]) / l];
    let b = [(e[6] - e[2]) / l, (e[7] - e[3]) / l];
    let c = [(e[2] + e[6]) / 2.0, (e[3] + e[7]) / 2.0];
    let (aa, ab, bb, ac, bc, cc) = (
        dot(a, a),
        dot(a, b),
        dot(b, b),
        dot(a, c),
        dot(b, c),
        dot(c, c),
    );
    let (ar, i2, i4) = (sec.area, sec.i2, sec.i4);
    let exx =
        ar / 4.0 * (aa - 1.0).powi(2) + i2 * (ab * ab + 0.5 * (aa - 1.0) * bb) + i4 / 4.0 * bb * bb;
    let eyy = ar * (0.5 * (cc - 1.0)).powi(2);
    let exy = 0.25 * (ar * ac * ac + i2 * bc * bc);
    let g = mat.young / (2.0 * (1.0 + mat.poisson));
    let u = l * (mat.young / 2.0 * exx + mat.young / 2.0 * eyy + 2.0 * (5.0 / 6.0) * g * exy);
    let un = el.strain_energy(&e);
    assert!(
        (un - u).abs() < 1e-11 * u.abs(),
        "U = {un}, closed form {u}"
    );

    let mut m = vec![0.0; 64];
    el.mass_matrix(&mut m);
    let blk = [
        [ar / 3.0, 0.0, ar / 6.0, 0.0],
        [0.0, i2 / 3.0, 0.0, i2 / 6.0],
        [ar / 6.0, 0.0, ar / 3.0, 0.0],
        [0.0, i2 / 6.0, 0.0, i2 / 3.0],
    ];
    for i in 0..8 {
        for j in 0..8 {
            let ex = if i % 2 == j % 2 {
                mat.density * l * blk[i / 2][j / 2]
            } else {
                0.0
            };
            assert!(
                (m[i + 8 * j] - ex).abs() < 1e-12 * mat.density * l * ar,
                "M[{i},{j}]"
            );
        }
    }
}

// Consistency: elastic forces are −∂U/∂e (central differences of the energy) and the tangent is
// ∂²U/∂e² (central differences of the forces), for all three elements in a deformed state.
#[test]
fn forces_and_tangent_match_finite_differences() {
    for (el, _) in elements() {
        let n = el.ndof();
        let e = perturbed(el.as_ref(), 0.03);
        let mut q = vec![0.0; n];
        let mut k = vec![0.0; n * n];
        el.elastic_tangent(&e, &mut q, &mut k);
        let mut q2 = vec![0.0; n];
        el.elastic_forces(&e, &mut q2);
        let qscale = q.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let kscale = k.iter().map(|v| v.abs()).fold(0.0, f64::max);
        for i in 0..n {
            assert!((q[i] - q2[i]).abs() < 1e-9 * qscale);
            let h = 1e-6;
            let mut ep = e.clone();
            let mut em = e.clone();
            ep[i] += h;
            em[i] -= h;
            let du = (el.strain_energy(&ep) - el.strain_energy(&em)) / (2.0 * h);
            assert!(
                (du + q[i]).abs() < 1e-6 * qscale,
                "dof {i}: FD {du}, -Q {}",
                -q[i]
            );
            let mut qp = vec![0.0; n];
            let mut qm = vec![0.0; n];
            el.elastic_forces(&ep, &mut qp);
            el.elastic_forces(&em, &mut qm);
            for j in 0..n {
                let fd = -(qp[j] - qm[j]) / (2.0 * h);
                assert!(
                    (fd - k[j + i * n]).abs() < 1e-6 * kscale,
                    "K[{j},{i}]: FD {fd}, {}",
                    k[j + i * n]
                );
                assert!(
                    (k[j + i * n] - k[i + j * n]).abs() < 1e-9 * kscale,
                    "K symmetric"
                );
            }
        }
    }
}

// Analytic reference: a belt element whose centreline follows a circular arc of radius R with
// unsheared unit cross-section slopes stores the Euler–Bernoulli bending energy
// ½ α₂ E I κ² l (plus O(κ⁴ h²) terms and the small axial error of the cubic arc).
#[test]
fn belt_element_bending_energy_of_an_arc() {
    let sec = Section::rectangle(0.01, 0.01).unwrap();
    let mat = Material::new(1e8, 0.3, 1036.0).unwrap();
    let (r, l, alpha2) = (0.2, 0.1, 0.01);
    let el = BeltElement::new(l, mat, sec, 1.0, alpha2, 5).unwrap();
    let phi = l / r;
    // cubic Hermite data of the arc: positions and unit tangents scaled to the arc speed
    let p = |s: f64| [r * (s / r).sin(), r * (1.0 - (s / r).cos())];
    let t = |s: f64| [(s / r).cos(), (s / r).sin()];
    let nrm = |s: f64| [-(s / r).sin(), (s / r).cos()];
    let (p0, p1, t0, t1, n0, n1) = (p(0.0), p(l), t(0.0), t(l), nrm(0.0), nrm(l));
    let e = [
        p0[0], p0[1], t0[0], t0[1], n0[0], n0[1], p1[0], p1[1], t1[0], t1[1], n1[0], n1[1],
    ];
    let u = el.strain_energy(&e);
    let exact = 0.5 * alpha2 * mat.young * sec.i2 * l / (r * r);
    assert!(phi < 1.0);
    assert!(
        (u - exact).abs() < 0.01 * exact,
        "U = {u} J, Euler–Bernoulli {exact} J"
    );
    // and the axial energy of a uniform stretch s: E α₁ A/8 ((1+s)²−1)² l
    let s = 1e-3;
    let mut e2 = straight_coordinates(el.layout(), [0.0, 0.0], [l * (1.0 + s), 0.0], 1);
    e2[2] = 1.0 + s;
    e2[8] = 1.0 + s;
    let ua = el.strain_energy(&e2);
    let exact_a = mat.young * sec.area / 8.0 * ((1.0 + s).powi(2) - 1.0).powi(2) * l;
    assert!(
        (ua - exact_a).abs() < 1e-10 * exact_a,
        "axial U = {ua}, exact {exact_a}"
    );
}

// Second formulation: the belt element's closed-form energy, forces and tangent (a polynomial
// in five scalars per Gauss point) equal the energy (3.18)–(3.19) written term by term with
// first- and second-order AD over all 12 coordinates, to 1e-10, in strongly deformed, sheared
// states (stretched, compressed, bent both ways, slopes of unequal length) and in the belt
// drive's pre-strained wrap.
#[test]
fn belt_closed_form_matches_full_ad() {
    let sec = Section::rectangle(0.01, 0.01).unwrap();
    let mat = Material::new(1e8, 0.3, 1036.0).unwrap();
    let el = BeltElement::new(0.13, mat, sec, 1.0, 0.01, 5).unwrap();
    let el7 = BeltElement::new(0.064, mat, sec, 1.0, 0.001, 7).unwrap();
    let mut states = vec![
        (el.clone(), perturbed(&el, 0.08)),
        (el.clone(), perturbed(&el, -0.2)),
        (el7.clone(), perturbed(&el7, 0.03)),
    ];
    // a wrapped, pre-stretched element on a pulley of radius 0.08125 m (Table 3.1)
    let (r, l, lam): (f64, f64, f64) = (0.08125, 0.064, 1.0028);
    let phi = lam * l / r;
    let e_arc = vec![
        0.0,
        r,
        lam,
        0.0,
        0.0,
        1.0,
        r * phi.sin(),
        r * phi.cos(),
        lam * phi.cos(),
        -lam * phi.sin(),
        phi.sin(),
        phi.cos(),
    ];
    states.push((el7.clone(), e_arc));
    for (el, e) in &states {
        let (mut q1, mut q2, mut q3) = (vec![0.0; 12], vec![0.0; 12], vec![0.0; 12]);
        let (mut k1, mut k2) = (vec![0.0; 144], vec![0.0; 144]);
        el.elastic_tangent(e, &mut q1, &mut k1);
        el.elastic_tangent_reference(e, &mut q2, &mut k2);
        el.elastic_forces(e, &mut q3);
        let mut q4 = vec![0.0; 12];
        el.elastic_forces_reference(e, &mut q4);
        let (u1, u2) = (el.strain_energy(e), el.strain_energy_reference(e));
        assert!((u1 - u2).abs() < 1e-10 * u2.abs(), "U {u1} vs {u2}");
        let ks = k2.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let qs = q2.iter().map(|v| v.abs()).fold(0.0, f64::max);
        for i in 0..12 {
            assert!(
                (q1[i] - q2[i]).abs() < 1e-10 * qs,
                "q[{i}]: {} vs {}",
                q1[i],
                q2[i]
            );
            assert!(
                (q3[i] - q4[i]).abs() < 1e-10 * qs,
                "q[{i}]: {} vs {}",
                q3[i],
                q4[i]
            );
        }
        for i in 0..144 {
            assert!(
                (k1[i] - k2[i]).abs() < 1e-10 * ks,
                "K[{i}]: {} vs {}",
                k1[i],
                k2[i]
            );
        }
    }
}
