//! Validation of the planar ANCF belt drive (Kerkkänen ch. 3): quick checks. The long
//! simulations of the issue are `#[ignore]`d; run them with
//! `cargo test --release -p flowmbd-validation --test ancf_belt_drive -- --ignored`.

use ancf::belt_drive::*;
use mbd_core::SecondOrderSystem;

/// A moving state near the steady run: the equilibrium on the pulleys with the belt travelling
/// at `speed` [m/s] along the path plus a small perturbation, pulleys spinning.
fn moving_state(d: &BeltDrive, speed: f64) -> (Vec<f64>, Vec<f64>) {
    let init = d.initial_state(&InitialOptions::default()).unwrap();
    let q = init.q.clone();
    let mut v = vec![0.0; q.len()];
    for node in 0..d.mesh().n_nodes() {
        let k = 6 * node;
        let rx = [q[k + 2], q[k + 3]];
        let n = (rx[0] * rx[0] + rx[1] * rx[1]).sqrt();
        // 1 % speed variation along the belt so that some points slip and some creep
        let s = speed * (1.0 + 0.01 * (node as f64).sin());
        v[k] = s * rx[0] / n;
        v[k + 1] = s * rx[1] / n;
    }
    for p in 0..d.pulleys().len() {
        if let Some(j) = d.pulley_dof(p) {
            v[j] = 0.995 * speed / d.pulleys()[p].radius;
        }
    }
    (q, v)
}

// Reference: central finite differences of the generalized forces (the analytic tangent must
// be −∂f/∂q, −∂f/∂v including the belt–pulley coupling through the free pulley's speed).
#[test]
fn analytic_tangent_matches_finite_differences() {
    let d = BeltDrive::new(BeltDriveSpec::default())
        .unwrap()
        .with_tangent_refresh(0.0);
    let (q, v) = moving_state(&d, 0.9);
    let t = 0.5;
    let n = d.n_q();
    let tg = d.force_tangent(t, &q, &v).unwrap().unwrap();
    let k = tg.stiffness.to_dense();
    let c = tg.damping.to_dense();
    let mut fp = vec![0.0; n];
    let mut fm = vec![0.0; n];
    let mut worst_k = 0.0f64;
    let mut worst_c = 0.0f64;
    let kmax = (0..n).map(|i| k[(i, i)].abs()).fold(0.0, f64::max);
    let cmax = (0..n).map(|i| c[(i, i)].abs()).fold(0.0, f64::max);
    for j in 0..n {
        let h = 1e-8;
        let mut qp = q.clone();
        qp[j] += h;
        d.forces(t, &qp, &v, &mut fp).unwrap();
        qp[j] -= 2.0 * h;
        d.forces(t, &qp, &v, &mut fm).unwrap();
        for i in 0..n {
            let fd = -(fp[i] - fm[i]) / (2.0 * h);
            worst_k = worst_k.max((fd - k[(i, j)]).abs());
        }
        let hv = 1e-7;
        let mut vp = v.clone();
        vp[j] += hv;
        d.forces(t, &q, &vp, &mut fp).unwrap();
        vp[j] -= 2.0 * hv;
        d.forces(t, &q, &vp, &mut fm).unwrap();
        for i in 0..n {
            let fd = -(fp[i] - fm[i]) / (2.0 * hv);
            worst_c = worst_c.max((fd - c[(i, j)]).abs());
        }
    }
    println!("tangent check: |ΔK| {worst_k:e} of {kmax:e}, |ΔC| {worst_c:e} of {cmax:e}");
    assert!(worst_k < 1e-5 * kmax, "stiffness {worst_k:e} vs {kmax:e}");
    assert!(worst_c < 1e-5 * cmax, "damping {worst_c:e} vs {cmax:e}");
}

// Reference: Kerkkänen example 3.3-A (seed note §7.5): a free belt of 10 stress-free elements
// closes to a circle of circumference equal to its length, radius 1.276273/(2π) = 0.20313 m.
#[test]
fn static_closure_of_free_belt_is_a_circle() {
    let mut spec = BeltDriveSpec::default();
    spec.belt.elements = 10;
    let d = BeltDrive::new(spec.clone()).unwrap();
    spec.belt.length = d.path().length();
    let r = free_belt_closure(&spec).unwrap();
    let expected = spec.belt.length / std::f64::consts::TAU;
    let var = (r.radius_range[1] - r.radius_range[0]) / r.mean_radius;
    println!(
        "closure: mean radius {:.6} m (expected {expected:.6}), variation {var:.2e}, {} iterations",
        r.mean_radius, r.iterations
    );
    assert!(
        (r.mean_radius - 0.2031).abs() < 5e-4,
        "radius {}",
        r.mean_radius
    );
    assert!((r.mean_radius - expected).abs() < 2e-3 * expected);
    assert!(var < 5e-3, "not a circle: variation {var}");
}

// Reference: closed-form pre-tension of a belt of length L_b on a path of length L_p with a
// linear penalty foundation k_p on a total wrap of 2π: the loop shortens by 2π d with
// d = T/(R k_p), so T = EA (L_p/L_b − 1) / (1 + 2π EA/(R k_p L_b)) = 26.32 N for Table 3.1.
#[test]
fn initial_pretension_matches_closed_form() {
    let spec = BeltDriveSpec::default();
    let d = BeltDrive::new(spec.clone()).unwrap();
    let init = d.initial_state(&InitialOptions::default()).unwrap();
    let b = &spec.belt;
    let ea = b.young * b.width * b.thickness;
    let r = spec.pulleys[0].radius;
    let lp = d.path().length();
    let expected = ea * (lp / b.length - 1.0)
        / (1.0 + std::f64::consts::TAU * ea / (r * spec.contact.stiffness * b.length));
    let spans = post::span_tensions(&d, &init.q);
    println!(
        "pre-tension: spans {spans:?}, belt mean {:.3} N, closed form {expected:.3} N, holding force {:.2e} N, {} iterations",
        init.mean_tension, init.holding_force, init.iterations
    );
    for t in spans {
        assert!(
            (t - expected).abs() < 0.03 * expected,
            "span tension {t} vs {expected}"
        );
    }
    assert!(init.holding_force.abs() < 1e-3 * expected);
    // equal spans by symmetry (up to the holding spring)
    let s = post::span_tensions(&d, &init.q);
    assert!((s[0] - s[1]).abs() < 1e-3 * expected);
}

// Reference: invalid user input is reported with the offending field, never a panic.
#[test]
fn bad_input_names_the_field() {
    let mut spec = BeltDriveSpec::default();
    spec.pulleys[1].radius = -1.0;
    let e = BeltDrive::new(spec).unwrap_err().to_string();
    assert!(e.contains("driven") && e.contains("radius"), "{e}");
    let mut spec = BeltDriveSpec::default();
    spec.belt.length = 2.0;
    let e = BeltDrive::new(spec).unwrap_err().to_string();
    assert!(e.contains("belt.length"), "{e}");
    let mut spec = BeltDriveSpec::default();
    spec.contact.points = 0;
    let e = BeltDrive::new(spec).unwrap_err().to_string();
    assert!(e.contains("contact.points"), "{e}");
}
