use ancf::belt_drive::*;
use mbd_core::SecondOrderSystem;
use std::time::Instant;

#[test]
#[ignore]
fn probe() {
    let spec = BeltDriveSpec::default();
    let tol: f64 = std::env::var("TOL")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.0);
    let d = BeltDrive::new(spec).unwrap().with_tangent_refresh(tol);
    println!("path {} n_q {}", d.path().length(), d.n_q());
    let t0 = Instant::now();
    let init = d.initial_state(&InitialOptions::default()).unwrap();
    println!(
        "init {:?} it {} res {:e} hold {} T {}",
        t0.elapsed(),
        init.iterations,
        init.residual,
        init.holding_force,
        init.mean_tension
    );
    let t_end: f64 = std::env::var("TEND")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.05);
    let h: f64 = std::env::var("H")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1e-4);
    let full = std::env::var("FULL").is_ok();
    let atol: f64 = std::env::var("ATOL")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1e-9);
    let opts = SimulationOptions {
        h,
        full_newton: full,
        newton_atol: atol,
        ..Default::default()
    };
    let t0 = Instant::now();
    let j = d.pulley_dof(1).unwrap();
    let mut last = 0.0;
    let sol = simulate(&d, &init.q, t_end, &opts, |s| {
        if s.t - last >= 0.1 - 1e-9 {
            last = s.t;
            println!(
                "t {:.3} w_driven {:.5} T {:?}",
                s.t,
                s.v[j],
                post::span_tensions(&d, &s.q)
            );
        }
    })
    .unwrap();
    println!(
        "wall {:?} stats {:?} elastic tangents {}",
        t0.elapsed(),
        sol.stats,
        d.elastic_tangent_evaluations()
    );
}

#[test]
#[ignore]
fn probe_cost() {
    let d = BeltDrive::new(BeltDriveSpec::default()).unwrap();
    let init = d.initial_state(&InitialOptions::default()).unwrap();
    let q = init.q.clone();
    let v = vec![0.0; q.len()];
    let mut f = vec![0.0; q.len()];
    let n = 200;
    let t0 = Instant::now();
    for _ in 0..n {
        d.forces(0.3, &q, &v, &mut f).unwrap();
    }
    println!("forces {:?}", t0.elapsed() / n);
    let t0 = Instant::now();
    for _ in 0..n {
        let _ = d.force_tangent(0.3, &q, &v).unwrap();
    }
    println!("tangent {:?}", t0.elapsed() / n);
    let t0 = Instant::now();
    let mut fb = vec![0.0; d.n_belt()];
    let mut k = d.mesh().pattern().zeros();
    for _ in 0..n {
        d.mesh()
            .elastic_tangent_into(&q[..d.n_belt()], &mut fb, d.mesh().pattern(), &mut k, 1.0);
    }
    println!("elastic tangent {:?}", t0.elapsed() / n);
}
