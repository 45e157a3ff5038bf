//! The three speed-loss models of issue 8 in one run, side by side: wall time per simulated
//! second of the Ribaric Table 6-1 drive (62.8 rad/s, load 0 → 8 N m, steady-state detection
//! with 0.1 s windows), each at the step that keeps its Δω within 1 % of its own 0.25 ms (ANCF:
//! its default 0.1 ms) value (`flowing/benches/belt.rs` measured the step sweeps):
//! - flowing-material form (5.14), default 56-element stationary mesh, 20 free modes, h = 4 ms;
//! - nodal rotating mesh (5.7), uniform 216-element loop (its Δω within 2 % of the flowing form
//!   on the same loop), h = 0.5 ms;
//! - ANCF belt (Kerkkänen ch. 3), the `--model ancf` adapter (40 elements), h = 0.1 ms.
//!
//! Run: `cargo bench -p drives --bench speed_loss_models` (several minutes).

mod timed;

use drives::NodalConfig;
use drives::ancf_model::{AncfBelt, AncfConfig};
use flowing::belt::{FlowingBelt, FlowingSettings, NodalBelt};
use mbd_core::SecondOrderSystem;

fn main() {
    timed::header();
    let cfg = drives::table_6_1::drive();
    let mut flow = FlowingBelt::new(&cfg, &FlowingSettings::default()).expect("flowing model");
    let dofs = flow.n_q();
    let f = timed::run("flowing, 56 el., 20 free modes", dofs, &mut flow, 4e-3);
    let mut nodal = NodalBelt::new(&cfg, &NodalConfig::default().mesh).expect("nodal model");
    let dofs = nodal.n_q();
    let n = timed::run("nodal rotating mesh, 216 el.", dofs, &mut nodal, 5e-4);
    let a = AncfConfig::default();
    let mut ancf = AncfBelt::new(&cfg, &a).expect("ANCF model");
    let dofs = ancf.n_v();
    let an = timed::run(
        &format!("ANCF belt, {} el.", a.elements),
        dofs,
        &mut ancf,
        a.step,
    );
    for r in [&f, &n, &an].into_iter().flatten() {
        timed::print(r);
    }
    if let (Some(f), Some(n), Some(an)) = (f, n, an) {
        println!(
            "wall time per simulated second relative to flowing: nodal {:.0}x, ANCF {:.0}x; \
             Δω(8) relative to flowing: nodal {:+.1} %, ANCF {:+.1} %",
            n.rate() / f.rate(),
            an.rate() / f.rate(),
            100.0 * (n.delta_omega / f.delta_omega - 1.0),
            100.0 * (an.delta_omega / f.delta_omega - 1.0)
        );
    }
}
