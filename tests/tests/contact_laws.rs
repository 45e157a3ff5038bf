//! Validation of the contact crate: penalty laws against F = k d, the tanh law's limit, the
//! quadrature independence of distributed contact (Kerkkänen §3.3: 5, 7 and 11 points gave
//! identical results), and the exactness of the contact Jacobians.

use ancf::element::{AncfElement, BeltElement};
use ancf::{Material, Section};
use contact::{
    ActiveSet, Coulomb, CoulombTanh, CreepRate, Disk, ElementContact, FrictionLaw, Frictionless,
    GaussRule, LineContact, LinearPenalty, PolynomialPenalty, point_contact, unilateral_row,
};
use nalgebra::{Point2, Vector2};

/// Newton solve of a node pushed onto a disk by `push` \[N\] (towards the centre along −n₀):
/// returns the equilibrium penetration.
fn pressed_node(law: &dyn contact::NormalLaw, push: f64) -> (f64, [f64; 2]) {
    let disk = Disk::fixed(Point2::new(0.1, -0.2), 0.08125);
    let dir = [0.6, 0.8];
    let load = [-push * dir[0], -push * dir[1]];
    let mut p = [0.1 + 0.08125 * dir[0], -0.2 + 0.08125 * dir[1]];
    let at = |p: [f64; 2]| {
        point_contact(
            &disk,
            law,
            &Frictionless,
            &Point2::from(p),
            &Vector2::zeros(),
        )
    };
    for _ in 0..50 {
        let (f, k) = match at(p) {
            Some(c) => (c.force, c.df_dp),
            None => (Vector2::zeros(), nalgebra::Matrix2::zeros()),
        };
        let r = [f[0] + load[0], f[1] + load[1]];
        // Newton: (−∂f/∂p) Δp = r ; add tiny regularisation for the tangential direction
        let a = [
            [-k[(0, 0)] + 1e-3, -k[(0, 1)]],
            [-k[(1, 0)], -k[(1, 1)] + 1e-3],
        ];
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        let dp = [
            (r[0] * a[1][1] - r[1] * a[0][1]) / det,
            (a[0][0] * r[1] - a[1][0] * r[0]) / det,
        ];
        p = [p[0] + dp[0], p[1] + dp[1]];
        if dp[0].abs() + dp[1].abs() < 1e-16 {
            break;
        }
    }
    let pc = at(p).expect("in contact");
    (pc.penetration, pc.surface.normal.into())
}

// Reference: a linear penalty node pressed on a circle carries F = k d (Kerkkänen (3.20)).
#[test]
fn penalty_node_on_circle_recovers_f_equals_k_d() {
    let k = 1e7;
    let law = LinearPenalty {
        stiffness: k,
        damping: 10.0,
    };
    for push in [1.0, 26.5, 1580.0] {
        let (d, n) = pressed_node(&law, push);
        assert!(
            (d - push / k).abs() < 1e-9 * (push / k),
            "d = {d}, F/k = {}",
            push / k
        );
        assert!((n[0] - 0.6).abs() < 1e-9 && (n[1] - 0.8).abs() < 1e-9);
    }
    // Ribaric (6.1): k₂ L d² + k₁ L d = F solved in closed form
    let law = PolynomialPenalty::ribaric(0.02);
    let push = 6200.0 * 0.02; // uniform pressure T0/R of Ribaric's belt on a 2 cm node
    let (d, _) = pressed_node(&law, push);
    let (a, b) = (law.quadratic * law.length, law.linear * law.length);
    let exact = (-b + (b * b + 4.0 * a * push).sqrt()) / (2.0 * a);
    assert!((d - exact).abs() < 1e-12 * exact, "d = {d}, exact {exact}");
    // seed note: δ_N ≈ 7.16e-5 m under 6200 N/m
    assert!((exact - 7.16e-5).abs() < 0.01e-5);
}

// Reference: tanh(κv) → sign(v): |F_tanh − F_sign| = μ|F_N|(1 − tanh(κ|v|)) ≤ 2μ|F_N| e^{−2κ|v|}.
#[test]
fn tanh_law_tends_to_sign_law() {
    let sign = Coulomb { mu: 1.2 };
    let mut prev = f64::INFINITY;
    for kappa in [10.0, 40.0, 100.0, 1e3, 1e4] {
        let law = CoulombTanh { mu: 1.2, kappa };
        let mut worst: f64 = 0.0;
        for v in [-1.0, -0.1, -0.01, 0.01, 0.1, 1.0] {
            let err = (law.friction(v, 500.0).force - sign.friction(v, 500.0).force).abs();
            assert!(err <= 2.0 * 1.2 * 500.0 * (-2.0 * kappa * f64::abs(v)).exp() + 1e-12);
            worst = worst.max(err);
        }
        assert!(worst < prev || worst == 0.0);
        prev = worst;
    }
    assert!(prev < 1e-9);
}

fn belt_element() -> BeltElement {
    let mat = Material::new(1e8, 0.3, 1036.0).unwrap();
    let sec = Section::rectangle(0.01, 0.01).unwrap();
    BeltElement::new(0.06, mat, sec, 1.0, 0.01, 5).unwrap()
}

/// Element lying on the pulley of radius R along an arc of radius R − δ (penetration δ), moving
/// tangentially with speed `speed`.
fn wrapped_state(r: f64, delta: f64, speed: f64, l: f64) -> (Vec<f64>, Vec<f64>) {
    let rr = r - delta;
    let (a0, a1) = (0.3, 0.3 + l / rr);
    let node = |a: f64| {
        let n = [a.cos(), a.sin()];
        let t = [-n[1], n[0]];
        ([rr * n[0], rr * n[1]], t, n)
    };
    let (p0, t0, n0) = node(a0);
    let (p1, t1, n1) = node(a1);
    let e = vec![
        p0[0], p0[1], t0[0], t0[1], n0[0], n0[1], p1[0], p1[1], t1[0], t1[1], n1[0], n1[1],
    ];
    // rigid rotation about the pulley centre with angular speed speed/rr
    let w = speed / rr;
    let ed: Vec<f64> = (0..6)
        .flat_map(|b| [-w * e[2 * b + 1], w * e[2 * b]])
        .collect();
    (e, ed)
}

fn contact_with(points: usize, friction: CreepRate) -> LineContact<Disk, LinearPenalty, CreepRate> {
    LineContact {
        surface: Disk {
            center: Point2::origin(),
            radius: 0.08125,
            velocity: Vector2::zeros(),
            omega: 12.0,
        },
        normal: LinearPenalty {
            stiffness: 1e7,
            damping: 10.0,
        },
        friction,
        rule: GaussRule::new(points),
    }
}

// Kerkkänen §3.3: "5, 7 and 11 contact integration points per element gave identical solutions"
// — for a smooth contact load the generalized forces agree to 2e-5 of their largest entry
// (the residual is the quadrature error of the non-polynomial penetration of a cubic arc).
#[test]
fn quadrature_5_7_11_points_agree_for_smooth_loads() {
    let el = belt_element();
    let shape = |xi: f64, s: &mut [f64]| el.shape(xi * el.length(), 0.0, s);
    let (e, ed) = wrapped_state(0.08125, 2e-4, 0.97, el.length());
    let mut results = Vec::new();
    for n in [5, 7, 11] {
        let c = contact_with(
            n,
            CreepRate {
                mu: 1.2,
                creep: 1e5,
            },
        );
        let mut out = ElementContact::<2>::new(12);
        c.element(el.length(), 6, shape, &e, &ed, false, &mut out, None);
        assert_eq!(out.active_points, n);
        results.push((out.q.clone(), out.moment));
    }
    let scale = results[2].0.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for (q, tau) in &results[..2] {
        for (a, b) in q.iter().zip(&results[2].0) {
            assert!((a - b).abs() < 2e-5 * scale, "{a} vs {b}");
        }
        assert!((tau - results[2].1).abs() < 2e-5 * results[2].1.abs());
    }
}

// Exactness of the Jacobians ∂Q/∂e, ∂Q/∂ė, ∂Q/∂ω and of the torque derivatives (central
// differences), in the viscous branch of the creep-rate law and with damping.
#[test]
fn distributed_contact_jacobians_match_finite_differences() {
    let el = belt_element();
    let shape = |xi: f64, s: &mut [f64]| el.shape(xi * el.length(), 0.0, s);
    let (mut e, mut ed) = wrapped_state(0.08125, 2e-4, 0.9, el.length());
    // perturb so that the state is generic (slip varies along the element)
    for (k, v) in e.iter_mut().enumerate() {
        *v += 2e-5 * (k as f64 * 0.7).sin();
    }
    for (k, v) in ed.iter_mut().enumerate() {
        *v += 1e-3 * (k as f64 * 1.3).cos();
    }
    let c = contact_with(
        7,
        CreepRate {
            mu: 1.2,
            creep: 1e3,
        },
    );
    let mut out = ElementContact::<2>::new(12);
    c.element(el.length(), 6, shape, &e, &ed, true, &mut out, None);
    let mut tmp = ElementContact::<2>::new(12);
    let eval = |c: &LineContact<Disk, LinearPenalty, CreepRate>,
                e: &[f64],
                ed: &[f64],
                tmp: &mut ElementContact<2>| {
        c.element(el.length(), 6, shape, e, ed, false, tmp, None);
        (tmp.q.clone(), tmp.moment)
    };
    let qs = out.q.iter().map(|v| v.abs()).fold(0.0, f64::max);
    let js = out.dq_de.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for j in 0..12 {
        let h = 1e-8;
        let (mut ep, mut em) = (e.clone(), e.clone());
        ep[j] += h;
        em[j] -= h;
        let (qp, tp) = eval(&c, &ep, &ed, &mut tmp);
        let (qm, tm) = eval(&c, &em, &ed, &mut tmp);
        for i in 0..12 {
            let fd = (qp[i] - qm[i]) / (2.0 * h);
            assert!(
                (fd - out.dq_de[i + 12 * j]).abs() < 1e-5 * js,
                "dQ{i}/de{j}: {fd} vs {}",
                out.dq_de[i + 12 * j]
            );
        }
        let fdt = (tp - tm) / (2.0 * h);
        assert!(
            (fdt - out.dmoment_de[j]).abs() < 1e-5 * js * 0.1,
            "dtau/de{j}: {fdt} vs {}",
            out.dmoment_de[j]
        );
        let hv = 1e-6;
        let (mut vp, mut vm) = (ed.clone(), ed.clone());
        vp[j] += hv;
        vm[j] -= hv;
        let (qp, tp) = eval(&c, &e, &vp, &mut tmp);
        let (qm, tm) = eval(&c, &e, &vm, &mut tmp);
        for i in 0..12 {
            let fd = (qp[i] - qm[i]) / (2.0 * hv);
            assert!(
                (fd - out.dq_dedot[i + 12 * j]).abs() < 1e-6 * (1.0 + fd.abs()),
                "dQ/dedot"
            );
        }
        assert!(
            ((tp - tm) / (2.0 * hv) - out.dmoment_dedot[j]).abs()
                < 1e-6 * (1.0 + out.dmoment_dedot[j].abs())
        );
    }
    let hw = 1e-6;
    let mut cp = c.clone();
    cp.surface.omega += hw;
    let mut cm = c.clone();
    cm.surface.omega -= hw;
    let (qp, tp) = eval(&cp, &e, &ed, &mut tmp);
    let (qm, tm) = eval(&cm, &e, &ed, &mut tmp);
    for i in 0..12 {
        let fd = (qp[i] - qm[i]) / (2.0 * hw);
        assert!((fd - out.dq_domega[i]).abs() < 1e-6 * (1.0 + fd.abs()));
    }
    assert!(
        ((tp - tm) / (2.0 * hw) - out.dmoment_domega).abs()
            < 1e-6 * (1.0 + out.dmoment_domega.abs())
    );
    assert!(qs > 0.0);
}

// Kerkkänen (3.26): the torque on the pulley is ∫(R − d) n × (−f_t) dx = −∫(R − d) f_t dx
// (the normal force has no moment), compared with the per-point records.
#[test]
fn torque_matches_kerkkanen_3_26_and_records() {
    let el = belt_element();
    let shape = |xi: f64, s: &mut [f64]| el.shape(xi * el.length(), 0.0, s);
    let (e, ed) = wrapped_state(0.08125, 3e-4, 0.8, el.length());
    let c = contact_with(
        11,
        CreepRate {
            mu: 1.2,
            creep: 1e4,
        },
    );
    let mut out = ElementContact::<2>::new(12);
    let mut rec = Vec::new();
    c.element(
        el.length(),
        6,
        shape,
        &e,
        &ed,
        false,
        &mut out,
        Some(&mut rec),
    );
    assert_eq!(rec.len(), 11);
    let rule = GaussRule::new(11);
    let tau: f64 = rec
        .iter()
        .zip(&rule.weights)
        .map(|(r, w)| -w * el.length() * (0.08125 - r.penetration) * r.friction_force)
        .sum();
    assert!(
        (tau - out.moment).abs() < 1e-12 * tau.abs(),
        "{tau} vs {}",
        out.moment
    );
    // belt slower than the pulley surface (0.8 < 12·0.08125 m/s): friction drives the belt
    // forward (+t) and brakes the pulley (negative torque)
    assert!(rec.iter().all(|r| r.slip < 0.0 && r.friction_force > 0.0));
    assert!(out.moment < 0.0);
}

// Active-set rule of the unilateral constraints and the flat-road constraint row.
#[test]
fn unilateral_active_set_rule() {
    let road = contact::HalfPlane::ground(0.0);
    let row = unilateral_row(&road, &Point2::new(0.3, -1e-4), &Vector2::new(1.0, -0.5));
    assert!((row.gap + 1e-4).abs() < 1e-18 && row.gap_rate == -0.5 && row.gamma == 0.0);
    // circle: γ = −|w_t|²/ρ for a node sliding on a fixed disk
    let disk = Disk::fixed(Point2::origin(), 1.0);
    let row = unilateral_row(&disk, &Point2::new(0.0, 1.0), &Vector2::new(2.0, 0.0));
    assert!((row.gamma + 4.0).abs() < 1e-12);
    let mut set = ActiveSet::new(3);
    assert!(set.update(&[-1e-6, 1e-3, 0.0], &[-0.1, -0.1, 0.2], &[0.0; 3], 0.0));
    assert!(set.is_active(0) && !set.is_active(1) && !set.is_active(2));
    // tensile multiplier releases, compressive keeps
    assert!(set.update(&[0.0; 3], &[0.0; 3], &[-5.0, 0.0, 0.0], 0.0) || !set.is_active(0));
    assert!(!set.is_active(0));
}
