use flowing::belt::*;
use mbd_core::SecondOrderSystem;
fn main() {
    let mut cfg = BeltDriveConfig::default();
    if let Ok(m) = std::env::var("MODES") {
        cfg.reduction.free_modes = if m == "all" {
            None
        } else {
            Some(m.parse().unwrap())
        };
    }
    if let Ok(k) = std::env::var("KAPPA") {
        cfg.contact.kappa = k.parse().unwrap();
    }
    if let Ok(k) = std::env::var("PEN") {
        let f: f64 = k.parse().unwrap();
        cfg.contact.penalty_linear *= f;
        cfg.contact.penalty_quadratic *= f;
    }
    if let Ok(k) = std::env::var("ALPHA") {
        cfg.damping.alpha = k.parse().unwrap();
    }
    if let Ok(k) = std::env::var("BETA") {
        cfg.damping.beta = k.parse().unwrap();
    }
    let fe = BeltFe::new(&cfg).unwrap();
    println!("nodes {} contact {:?}", fe.n_nodes(), fe.contact_nodes);
    println!(
        "s {:?}",
        fe.s.iter().map(|x| format!("{x:.4}")).collect::<Vec<_>>()
    );
    let t0 = std::time::Instant::now();
    let mut belt = FlowingBelt::new(fe, Schedule::constant(0.0), Schedule::constant(0.0)).unwrap();
    println!("modes {} build {:?}", belt.n_modes(), t0.elapsed());
    let z = belt.static_equilibrium().unwrap();
    let rep = belt.contact_report(
        0.0,
        &[&[0.0][..], &z, &[0.0]].concat(),
        &vec![0.0; belt.n_q()],
    );
    let pen: Vec<f64> = rep.iter().map(|r| r.contact.penetration * 1e6).collect();
    println!(
        "penetration um {:?}",
        pen.iter().map(|p| format!("{p:.1}")).collect::<Vec<_>>()
    );
    let ten = belt.element_tensions(&z);
    println!(
        "tensions {:?}",
        ten.iter().map(|p| format!("{p:.1}")).collect::<Vec<_>>()
    );
    let omega: f64 = std::env::var("OMEGA")
        .map(|s| s.parse().unwrap())
        .unwrap_or(62.8);
    let torques: Vec<f64> = std::env::var("TORQUES")
        .map(|s| s.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![0.0, 5.0]);
    let step: f64 = std::env::var("STEP")
        .map(|s| s.parse().unwrap())
        .unwrap_or(2.5e-4);
    let tol: f64 = std::env::var("TOL")
        .map(|s| s.parse().unwrap())
        .unwrap_or(2e-4);
    let mut settings = SpeedLossSettings {
        omega_driver: omega,
        torques: torques.clone(),
        step,
        tolerance: tol,
        ..Default::default()
    };
    if let Ok(w) = std::env::var("WINDOW") {
        settings.window = w.parse().unwrap();
    }
    let t0 = std::time::Instant::now();
    let mut last = 0.0;
    let res = speed_loss_sweep(&mut belt, &settings, |st, s| {
        if st.t - last > 0.05 {
            last = st.t;
            println!(
                "t {:.3} w1 {:.4} w2 {:.5} v {:.5} load {:.2}",
                st.t, s.omega_driver, s.omega_driven, st.v[0], s.load
            );
        }
    });
    match res {
        Ok((pts, stats)) => {
            for p in &pts {
                println!(
                    "T {:5.1} dw {:.5} bechtel {:.5} drift {:.1e} t {:.2}",
                    p.torque,
                    p.delta_omega,
                    analytical_speed_loss(0.05, 310.0, 152000.0, p.torque, omega),
                    p.drift,
                    p.time
                );
            }
            println!("{stats:?} wall {:?}", t0.elapsed());
        }
        Err(e) => println!("FAIL {:?} {:?}", e.error, e.points),
    }
}
