//! Issue 34 item 3: convergence of the speed loss in the friction law's slip-velocity scale
//! `v_s` (`law = "tanh_slip"`, `f_t = −μ tanh(v_t/v_s)|f_n|`) towards its Coulomb limit, on
//! Ribaric's Table 6-1 drive (flowing model, speed-loss procedure at 62.8 rad/s, 10, 20 and
//! 30 N·m in one sweep, settled to 2·10⁻⁵ rad/s) and on the Pechstein–Gerstmayr drive of
//! `apps/belt/examples/pechstein-gerstmayr.toml` (flowing model, 20 mm elements, the crank at
//! 12 rad/s). Prints one row per `v_s`; the default-mesh columns of the table in BENCHMARKS.md
//! ("friction regularisation") are its output (there measured through `flowmbd-belt
//! speed-loss`, the same procedure).
//!
//! `cargo run --release -p drives --example friction_convergence [table|pg]`

use contact::friction::{FrictionLaw, FrictionSpec};
use drives::fead::{FeadConfig, run_fead};
use drives::{SpeedLossConfig, speed_loss_sweep, table_6_1};
use flowing::belt::{BeltMesh, FlowingBelt, FlowingSettings};

const SCALES: [f64; 9] = [
    0.025, 0.0016, 0.0008, 0.0004, 0.0002, 0.0001, 0.00005, 0.000025, 0.0000125,
];

fn table_6_1_case() {
    let torques = [10.0, 20.0, 30.0];
    println!("Table 6-1, flowing model, {torques:?} N m at 62.8 rad/s");
    println!("| v_s [m/s] | Δω [rad/s] at each torque | steps |");
    for vs in SCALES {
        let mut layout = table_6_1::layout();
        layout.contact.friction = FrictionSpec::TanhSlip {
            mu: layout.contact.friction.coefficient(),
            slip_velocity: vs,
        };
        let drive = layout.resolve().expect("Table 6-1 resolves");
        let mut model = FlowingBelt::new(&drive, &FlowingSettings::default()).expect("model");
        let settings = SpeedLossConfig {
            torques: torques.to_vec(),
            tolerance: 2e-5,
            ..SpeedLossConfig::default()
        };
        match speed_loss_sweep(&mut model, &settings, |_, _| {}) {
            Ok((points, stats)) => {
                let dw: Vec<String> = points
                    .iter()
                    .map(|p| format!("{:.5}", p.delta_omega))
                    .collect();
                println!("| {vs} | {} | {} |", dw.join(" | "), stats.steps);
            }
            Err(e) => println!("| {vs} | failed: {} | |", e.error),
        }
    }
}

fn pechstein_gerstmayr() {
    println!("Pechstein–Gerstmayr, flowing model, 20 mm elements, 12 rad/s");
    println!("| v_s [m/s] | ω_driven [rad/s] | speed loss [%] | steady | steps |");
    let text = include_str!("../../apps/belt/examples/pechstein-gerstmayr.toml");
    for vs in SCALES {
        let mut c: FeadConfig = toml::from_str(text).expect("the shipped example parses");
        c.drive.contact.friction = FrictionSpec::TanhSlip {
            mu: c.drive.contact.friction.coefficient(),
            slip_velocity: vs,
        };
        c.models.flowing.mesh = BeltMesh {
            span_element: 0.02,
            arc_element: 0.02,
            contact_margin_nodes: 1,
        };
        c.run.step = 2.5e-4;
        match run_fead(&c, |_| {}) {
            Ok(s) => {
                let p = &s.points[0];
                println!(
                    "| {vs} | {:.5} | {:.4} | {} | {} |",
                    p.pulley_speed[1].mean, p.speed_loss_percent[1], p.steady, s.steps
                );
            }
            Err(e) => println!("| {vs} | failed: {e:?} | | | |"),
        }
    }
}

fn main() {
    let which = std::env::args().nth(1).unwrap_or_else(|| "table".into());
    match which.as_str() {
        "pg" => pechstein_gerstmayr(),
        _ => table_6_1_case(),
    }
}
