//! Rolling reduced tire (Ribaric ch. 7-8): steady rolling and the cleat test on a small tire.

use flowing::tire::*;

#[test]
fn explore_roll() {
    let fe = generated_tire(&coarse_tire_config(96, 8, 20.0)).expect("tire");
    println!("cand {}", fe.candidates.len());
    let cfg = ReductionConfig { contact_nodes: 33, free_modes: 30, ..Default::default() };
    let (red, tim) = reduce(&fe, &cfg).unwrap();
    println!("nz {} {:?}", red.n_z(), tim);
    println!("f {:?}", &red.frequencies_hz().unwrap()[..15]);
    for (kind, cleat) in [(GroundKind::Road, false), (GroundKind::Drum, true)] {
        let mut rc = RigConfig::default();
        rc.ground.kind = kind;
        rc.ground.cleat = cleat;
        rc.rolling.friction = std::env::var("MU").ok().and_then(|v| v.parse().ok()).unwrap_or(0.0);
        let r = run_cleat(&red, &rc, &mut |_| {}).unwrap();
        println!("{kind:?} preload defl {} lam {:?}", r.preload.deflection, r.preload.lambda);
        println!("wall {} sim {} refac {}", r.wall_time_s, r.simulated_s, r.refactors);
        for s in r.samples.iter().step_by(100) {
            println!("{:.4} fx {:.2} fy {:.2} fz {:.2} spin {:.4} act {} n {:.1}", s.t, s.fx, s.fy, s.fz, s.spin, s.active, s.normal_sum);
        }
        let (sx, sy) = r.spectra();
        println!("peaks fx {:?} fy {:?} rms {:?}", sx.peak(5.0, 500.0), sy.peak(5.0, 500.0), r.rms());
    }
}
