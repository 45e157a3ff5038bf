use ancf::mesh::straight_coordinates;
use ancf::*;
fn main() {
    for (nu, h) in [(0.3, 0.1), (0.0, 0.5)] {
        for n in [2usize, 4, 8] {
            for fixed in [
                vec![0usize, 1, 4, 5],
                vec![0, 1, 2, 3, 4, 5],
                vec![0, 1, 2, 3],
            ] {
                let mat = Material::new(2.07e11, nu, 7850.0).unwrap();
                let sec = Section::rectangle(0.1, h).unwrap();
                let le = 2.0 / n as f64;
                let els: Vec<_> = (0..n)
                    .map(|_| OmarShabanaBeam::new(le, mat, sec).unwrap())
                    .collect();
                let mesh = Mesh::chain(els).unwrap();
                let q0 = straight_coordinates(mesh.layout(), [0.0, 0.0], [2.0, 0.0], n);
                let mut f = vec![0.0; mesh.n_dof()];
                f[mesh.node_dof(n, 1)] = -5e8 * h * h * h;
                let s = solve_static(&mesh, &q0, &fixed, &f, &StaticOptions::default()).unwrap();
                println!(
                    "nu={nu} h={h} n={n} fixed={fixed:?} {:?}",
                    mesh.node_position(&s.q, n)
                );
            }
        }
    }
}
