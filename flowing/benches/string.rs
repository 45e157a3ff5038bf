//! Benchmarks of the string models: the wrapped string with variable contact in nodal
//! coordinates (4.10) vs the reduced Craig–Bampton / flowing-material coordinates (4.11), and
//! the eigen analysis of the travelling string (4.20) vs the Galerkin model (4.29).

use criterion::{Criterion, criterion_group, criterion_main};
use flowing::contact::candidates;
use flowing::string_wrap::WrapConfig;
use flowing::{
    AxialMotion, ContactConfig, ContactString, DerivativeMethod, FlowingString, GalerkinString,
    StringConfig, StringMesh, simulate_contact,
};
use mbd_core::integrators::State;
use std::hint::black_box;

fn wrapped(c: &mut Criterion) {
    // the `flowmbd-string wrap` study's default string, pulleys and load
    let w = WrapConfig::default();
    let mesh = StringMesh::uniform(w.string, w.nodes).unwrap();
    let cands = candidates(&mesh, &w.pulleys, w.candidate_half_width).unwrap();
    let load = Some(w.load);
    let motion = AxialMotion::Constant { speed: 0.0 };
    let nodal = ContactString::nodal(
        &mesh,
        cands.clone(),
        DerivativeMethod::default(),
        motion,
        load,
    )
    .unwrap();
    let cb =
        ContactString::craig_bampton(&mesh, cands, 20, DerivativeMethod::default(), motion, load)
            .unwrap();
    let mut g = c.benchmark_group("wrapped string 0.01 s (119 nodes, 15 N at 20 Hz)");
    g.sample_size(10);
    for (name, model) in [
        ("nodal (4.10), 119 coordinates", nodal),
        ("Craig-Bampton (4.11), 20 f-modes + 33 c-modes", cb),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut s = model.clone();
                let y = s.static_equilibrium().unwrap();
                let n = y.len();
                let run = simulate_contact(
                    &mut s,
                    State::new(0.0, y, vec![0.0; n]),
                    0.01,
                    &ContactConfig::default(),
                    |_, _| {},
                )
                .unwrap();
                black_box(run.state.q[0])
            })
        });
    }
    g.finish();
}

fn eigen(c: &mut Criterion) {
    let p = StringConfig::default();
    let mut g = c.benchmark_group("moving-string frequencies at v = 20 m/s");
    g.sample_size(10);
    g.bench_function("Galerkin (4.29), 40 terms", |b| {
        b.iter(|| {
            black_box(
                GalerkinString::new(p, 20.0, 40)
                    .unwrap()
                    .system()
                    .state_eigen()
                    .unwrap()
                    .values
                    .len(),
            )
        })
    });
    let mesh = StringMesh::uniform(p, 99).unwrap();
    g.bench_function(
        "flowing (4.20), n = 99, modes + derivatives + 20-mode state EVD",
        |b| {
            b.iter(|| {
                let s = FlowingString::new(
                    &mesh.mass_sys(),
                    mesh.modes(20).unwrap(),
                    &[mesh.flow_line()],
                    DerivativeMethod::default(),
                    AxialMotion::Constant { speed: 20.0 },
                )
                .unwrap();
                black_box(s.frozen(20.0, 0.0).state_eigen().unwrap().values.len())
            })
        },
    );
    g.finish();
}

criterion_group!(benches, wrapped, eigen);
criterion_main!(benches);
