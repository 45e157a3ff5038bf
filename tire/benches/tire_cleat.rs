//! The issue-9 real-time benchmark: the default 341-DOF reduced truck tire (63 936-DOF generated
//! tire, 95 contact nodes, 50 free-node modes) rolling over the 10 mm cleat on the drum at
//! 60 km/h (0.4 s settle + 0.3 s record, h = 0.2 ms), wall and CPU seconds per simulated second
//! for the default step and its variants side by side in one run:
//! * default: generalized-α ρ∞ = 0.5, S inverted once per 10 % spin drift, Newton contact,
//!   4 sub-steps through the cleat impact;
//! * without the 4 sub-steps through the cleat impact (`impact.substeps = 1`);
//! * generalized-α ρ∞ = 0.9 (the default of earlier versions);
//! * S re-inverted at every 1 % spin drift (`matrix_tolerance = 0.01`, the session-2 policy);
//! * the trapezoidal rule (ρ∞ = 1);
//! * a penalty normal law (1e9 N/m) instead of Lagrange multipliers;
//! * no friction (μ = 0).
//!
//! * the converged reference step h = 0.05 ms without sub-steps (issue #16: real time there),
//!   with the default `threads` (1) and with 2, and with the full model (`symmetry = "off"`;
//!   every other variant steps the default mirror half model).
//!
//! Run: `cargo bench --profile release --workspace --bench tire_cleat` (the reduction takes about
//! 30 s first). With `FLOWMBD_REDUCED_TIRE=<file>` a saved reduced tire (e.g. the cache file of
//! `flowmbd-tire cleat`) is loaded instead of reducing; `FLOWMBD_CLEAT_VARIANTS=a,b` runs only the
//! variants whose names start with one of the given prefixes.

use fe_model::generate::TireConfig;
use std::time::Instant;
use tire::*;

fn main() {
    let t0 = Instant::now();
    let red = match std::env::var("FLOWMBD_REDUCED_TIRE") {
        Ok(file) => {
            let red = ReducedTire::load(std::path::Path::new(&file)).expect("reduced tire file");
            println!("reduced tire {file} ({} DOF) loaded", red.dof());
            red
        }
        Err(_) => {
            let fe = generated_tire(&TireConfig::default()).expect("generated tire");
            let (red, tim) = reduce(&fe, &ReductionConfig::default()).expect("reduction");
            println!(
                "reduction of the {}-DOF tire to {} DOF: {:.1} s (modes {:.1} s, static modes \
                 {:.1} s, derivatives {:.1} s, projections {:.1} s); setup total {:.1} s",
                fe.n_dofs(),
                red.dof(),
                tim.total_s,
                tim.modes_s,
                tim.static_modes_s,
                tim.derivatives_s,
                tim.projection_s,
                t0.elapsed().as_secs_f64()
            );
            red
        }
    };
    let only: Vec<String> = std::env::var("FLOWMBD_CLEAT_VARIANTS")
        .map(|v| v.split(',').map(str::to_owned).collect())
        .unwrap_or_default();
    let base = RigConfig::default();
    // the default rig with `change` applied
    let variant = |name, change: fn(&mut RigConfig)| {
        let mut c = base.clone();
        change(&mut c);
        (name, c)
    };
    let variants: Vec<(&str, RigConfig)> = vec![
        ("default (gen-alpha 0.5, S once)", base.clone()),
        variant("no impact sub-steps", |c| c.impact.substeps = 1),
        variant("gen-alpha rho 0.9", |c| {
            c.rolling = c.rolling.clone().generalized_alpha(0.9)
        }),
        variant("S re-inverted at 1 % drift", |c| {
            c.rolling.matrix_tolerance = 0.01
        }),
        variant("trapezoidal rule (rho 1)", |c| {
            c.rolling = c.rolling.clone().generalized_alpha(1.0)
        }),
        variant("penalty normal law 1e9 N/m", |c| {
            c.rolling.normal = NormalContact::Penalty { stiffness: 1e9 }
        }),
        variant("no friction (mu 0)", |c| c.rolling.friction = 0.0),
        variant("h 0.05 ms, no sub-steps (reference)", |c| {
            c.rolling.time_step = 5e-5;
            c.impact.substeps = 1;
        }),
        variant("h 0.05 ms, no sub-steps, 2 threads", |c| {
            c.rolling.time_step = 5e-5;
            c.impact.substeps = 1;
            c.rolling.threads = 2;
        }),
        variant("h 0.05 ms, full model (symmetry off)", |c| {
            c.rolling.time_step = 5e-5;
            c.impact.substeps = 1;
            c.rolling.symmetry = Symmetry::Off;
        }),
    ];
    println!(
        "{:<34} {:>10} {:>10} {:>8} {:>10} {:>10}",
        "variant", "wall s/s", "CPU s/s", "ratio", "Fy rms N", "Fx rms N"
    );
    let mut first = None;
    for (name, cfg) in &variants {
        if !only.is_empty() && !only.iter().any(|p| name.starts_with(p.as_str())) {
            continue;
        }
        let r = run_cleat(&red, cfg, &mut |_| {}).expect("cleat run");
        let wall = r.wall_time_s / r.simulated_s;
        let cpu = r.cpu_time_s.map_or(f64::NAN, |c| c / r.simulated_s);
        let f = *first.get_or_insert(wall);
        let (fx, fy) = r.rms();
        println!(
            "{name:<34} {wall:>10.3} {cpu:>10.3} {:>8.2} {fy:>10.1} {fx:>10.1}",
            wall / f
        );
        let us = |k: usize| 1e6 * r.stats.seconds[k] / r.stats.steps as f64;
        println!(
            "    per step [us]: free {:.1}, candidates {:.1}, R {:.1}, contact {:.1}, inversion \
             {:.1}; {:.1} candidates, {:.1} contacts, {:.2} Newton + {:.2} chord iterations",
            us(0),
            us(1),
            us(2),
            us(3),
            us(4),
            r.stats.candidates as f64 / r.stats.steps as f64,
            r.stats.active as f64 / r.stats.steps as f64,
            r.stats.contact_newton as f64 / r.stats.steps as f64,
            r.stats.contact_chord as f64 / r.stats.steps as f64,
        );
    }
}
