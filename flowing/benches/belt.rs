//! Wall time per simulated second of the flowing-material belt drive (Ribaric Table 6-1,
//! 62.8 rad/s, 5 N m), truncated (20 free-node modes) and untruncated, side by side.
//! Run: `cargo bench -p flowing --bench belt`.

use flowing::belt::{
    BeltDriveConfig, BeltFe, FlowingBelt, Schedule, SpeedLossSettings, speed_loss_sweep,
};
use std::time::Instant;

fn run(free_modes: Option<usize>) -> (usize, f64, f64, f64) {
    let mut cfg = BeltDriveConfig::default();
    cfg.reduction.free_modes = free_modes;
    let fe = BeltFe::new(&cfg).expect("default drive");
    let mut belt =
        FlowingBelt::new(fe, Schedule::constant(0.0), Schedule::constant(0.0)).expect("model");
    let dofs = belt.n_modes() + 2;
    let settings = SpeedLossSettings {
        torques: vec![0.0, 5.0],
        ..Default::default()
    };
    let start = Instant::now();
    let (points, stats) = speed_loss_sweep(&mut belt, &settings, |_, _| {}).expect("sweep");
    let wall = start.elapsed().as_secs_f64();
    (dofs, stats.simulated_time, wall, points[1].delta_omega)
}

fn main() {
    println!(
        "flowing belt, Table 6-1, 62.8 rad/s, torques 0 and 5 N m (generalized-α, h = 0.25 ms)"
    );
    println!(
        "{:<28} {:>6} {:>12} {:>10} {:>14} {:>12}",
        "model", "DOF", "simulated s", "wall s", "wall/sim s", "Δω(5) rad/s"
    );
    let mut rows = Vec::new();
    for (name, modes) in [
        ("flowing, 20 free modes", Some(20)),
        ("flowing, all modes", None),
    ] {
        let (dofs, sim, wall, dw) = run(modes);
        println!(
            "{name:<28} {dofs:>6} {sim:>12.3} {wall:>10.3} {:>14.3} {dw:>12.5}",
            wall / sim
        );
        rows.push(wall / sim);
    }
    println!(
        "ratio untruncated / truncated wall time per simulated second: {:.2}",
        rows[1] / rows[0]
    );
}
