//! One time step of an N-body spherical-joint chain (N = 10, 100, 1000), KKT solve included:
//! generalized-α (index 3, Newton with sparse LU for N > 12) and RK4 (four index-1 KKT solves).

use criterion::{Criterion, criterion_group, criterion_main};
use flowmbd_cases::chain::spherical_chain;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, Rk4, Stepper};
use std::hint::black_box;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("chain_step");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for n in [10usize, 100, 1000] {
        let (sys, s0) = spherical_chain(n, 0.1).unwrap();
        let h = 1e-3;
        let ga = GeneralizedAlpha::new(AlphaConfig {
            h,
            rho_inf: 0.8,
            ..Default::default()
        });
        let mut st = ga.stepper(&sys, s0.clone()).unwrap();
        g.bench_function(format!("gen_alpha/N={n}"), |b| {
            b.iter(|| {
                st.step(&sys, Some(h)).unwrap();
                black_box(st.state().t)
            })
        });
        println!(
            "gen_alpha N={n}: newton iterations per step {:.2}",
            st.stats.newton_iterations as f64 / st.stats.steps.max(1) as f64
        );
        let rk = Rk4::new(h);
        let mut state = s0.clone();
        g.bench_function(format!("rk4/N={n}"), |b| {
            b.iter(|| {
                let t_end = state.t + h;
                let sol = rk.integrate(&sys, state.clone(), t_end, |_| {}).unwrap();
                state = sol.state;
                black_box(state.t)
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
