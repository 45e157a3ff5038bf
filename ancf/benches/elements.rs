//! Cost of the element kernels and of one assembled tangent of a 20-element belt (the inner
//! loop of implicit belt-drive integration, Kerkkänen ch. 3).

use ancf::belt::{belt_loop, coordinates_on_belt_path, kerkkanen_path};
use ancf::element::{AncfElement, BeltElement, OmarShabanaBeam, ProposedBeam};
use ancf::mesh::straight_coordinates;
use ancf::system::MeshForce;
use ancf::{Material, PulleyContact, Section};
use contact::{CreepRate, Disk, GaussRule, LineContact, LinearPenalty};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn deformed(el: &dyn AncfElement) -> Vec<f64> {
    let mut e = straight_coordinates(el.layout(), [0.0, 0.0], [el.length(), 0.0], 1);
    for (k, v) in e.iter_mut().enumerate() {
        *v += 0.01 * (k as f64).sin();
    }
    e
}

fn element_kernels(c: &mut Criterion) {
    let mat = Material::new(1e8, 0.3, 1036.0).unwrap();
    let sec = Section::rectangle(0.01, 0.01).unwrap();
    let els: Vec<(&str, Box<dyn AncfElement>)> = vec![
        (
            "proposed",
            Box::new(ProposedBeam::new(0.06, mat, sec).unwrap()),
        ),
        (
            "omar_shabana",
            Box::new(OmarShabanaBeam::new(0.06, mat, sec).unwrap()),
        ),
        (
            "belt_5gp",
            Box::new(BeltElement::new(0.06, mat, sec, 1.0, 0.01, 5).unwrap()),
        ),
    ];
    for (name, el) in &els {
        let e = deformed(el.as_ref());
        let n = el.ndof();
        let mut q = vec![0.0; n];
        let mut k = vec![0.0; n * n];
        c.bench_function(&format!("forces/{name}"), |b| {
            b.iter(|| el.elastic_forces(black_box(&e), &mut q))
        });
        c.bench_function(&format!("tangent/{name}"), |b| {
            b.iter(|| el.elastic_tangent(black_box(&e), &mut q, &mut k))
        });
    }
}

fn belt_assembly(c: &mut Criterion) {
    let mat = Material::new(1e8, 0.3, 1036.0).unwrap();
    let sec = Section::rectangle(0.01, 0.01).unwrap();
    let mesh = belt_loop(20, 1.2727, mat, sec, 1.0, 0.01, 5).unwrap();
    let path = kerkkanen_path();
    let q = coordinates_on_belt_path(&mesh, &path);
    let v: Vec<f64> = (0..q.len()).map(|i| 0.01 * (i as f64).cos()).collect();
    let pat = mesh.pattern();
    let mut kv = pat.zeros();
    let mut cv = pat.zeros();
    let mut f = vec![0.0; mesh.n_dof()];
    c.bench_function("belt20/elastic_tangent_assembly", |b| {
        b.iter(|| {
            kv.fill(0.0);
            mesh.elastic_tangent_into(black_box(&q), &mut f, pat, &mut kv, 1.0)
        })
    });
    let pulleys: Vec<_> = [path.pulleys()[0].center, path.pulleys()[1].center]
        .iter()
        .map(|&c| PulleyContact {
            contact: LineContact {
                surface: Disk {
                    center: nalgebra::Point2::from(c),
                    radius: path.pulleys()[0].radius,
                    velocity: nalgebra::Vector2::zeros(),
                    omega: 12.0,
                },
                normal: LinearPenalty {
                    stiffness: 1e7,
                    damping: 10.0,
                },
                friction: CreepRate {
                    mu: 1.2,
                    creep: 1e5,
                },
                rule: GaussRule::new(5),
            },
        })
        .collect();
    c.bench_function("belt20/contact_forces_2_pulleys", |b| {
        b.iter(|| {
            f.fill(0.0);
            for p in &pulleys {
                p.add_forces(&mesh, 0.0, black_box(&q), &v, &mut f);
            }
        })
    });
    c.bench_function("belt20/contact_tangent_2_pulleys", |b| {
        b.iter(|| {
            kv.fill(0.0);
            cv.fill(0.0);
            for p in &pulleys {
                p.add_tangent(&mesh, 0.0, black_box(&q), &v, &mut kv, &mut cv);
            }
        })
    });
}

criterion_group!(benches, element_kernels, belt_assembly);
criterion_main!(benches);
