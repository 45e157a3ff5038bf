use ancf::belt::*;
use ancf::*;
fn main() {
    let mat = Material::new(1e8, 0.3, 1036.0).unwrap();
    let sec = Section::rectangle(0.01, 0.01).unwrap();
    let mesh = belt_loop(10, 1.276, mat, sec, 1.0, 0.01, 5).unwrap();
    let path = TwoPulleyPath::kerkkanen();
    let q0 = coordinates_on_path(&mesh, path.length(), |s| path.point(s));
    let fixed = [0, 1, mesh.node_dof(5, 1)];
    let opts = StaticOptions {
        increments: 1,
        max_iterations: 200,
        tolerance: 1e-10,
        line_search: true,
    };
    let t = std::time::Instant::now();
    let sol = solve_static(&mesh, &q0, &fixed, &vec![0.0; mesh.n_dof()], &opts).unwrap();
    println!("iterations {:?} in {:?}", sol.iterations, t.elapsed());
}
