//! The timed speed-loss run of Ribaric's Table 6-1 drive (load 0 → 8 N m, 0.1 s windows) that
//! the belt-model benches share, and its table row.

use belt::BeltModel;
use drives::{SpeedLossConfig, speed_loss_sweep};
use std::time::Instant;

/// One timed run.
pub struct Run {
    pub name: String,
    pub dofs: usize,
    /// Step \[s\].
    pub step: f64,
    /// Simulated time \[s\].
    pub simulated: f64,
    /// Wall time \[s\].
    pub wall: f64,
    /// Speed loss at 8 N m \[rad/s\].
    pub delta_omega: f64,
}

impl Run {
    /// Wall time per simulated second.
    pub fn rate(&self) -> f64 {
        self.wall / self.simulated
    }
}

/// The table's header line.
pub fn header() {
    println!("belt drive, Table 6-1, 62.8 rad/s, load 0 -> 8 N m (generalized-alpha, rho = 0.6)");
    println!(
        "{:<34} {:>5} {:>8} {:>9} {:>8} {:>11} {:>11}",
        "model", "DOF", "h [ms]", "sim [s]", "wall [s]", "wall/sim", "dw(8) rad/s"
    );
}

/// The run's table row.
pub fn print(r: &Run) {
    println!(
        "{:<34} {:>5} {:>8.2} {:>9.3} {:>8.2} {:>11.3} {:>11.5}",
        r.name,
        r.dofs,
        1e3 * r.step,
        r.simulated,
        r.wall,
        r.rate(),
        r.delta_omega
    )
}

/// Sweep the load 0 → 8 N m on `model` at step `step` \[s\], timed; a failure is printed and
/// gives `None`.
pub fn run<M: BeltModel>(name: &str, dofs: usize, model: &mut M, step: f64) -> Option<Run> {
    let settings = SpeedLossConfig {
        torques: vec![0.0, 8.0],
        window: 0.1,
        tolerance: 1e-3,
        max_hold: 3.0,
        step,
        ..Default::default()
    };
    let start = Instant::now();
    match speed_loss_sweep(model, &settings, |_, _| {}) {
        Ok((points, stats)) => Some(Run {
            name: name.into(),
            dofs,
            step,
            simulated: stats.simulated_time,
            wall: start.elapsed().as_secs_f64(),
            delta_omega: points[1].delta_omega,
        }),
        Err(f) => {
            println!("{name:<34} h = {step:.2e}: failed ({})", f.error);
            None
        }
    }
}
