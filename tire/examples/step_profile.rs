//! Per-step cost of the full rolling tire model at the converged step (issue 37 item 2): loads a
//! saved reduced tire, starts the default rig (drum, cleat, 60 km/h) with `symmetry = "off"`,
//! `threads = 1`, h = 0.05 ms and no impact sub-steps, and runs a given number of steps;
//! prints the thread CPU time per step and per phase ([`StepStats::seconds`]) and the spindle
//! force history's sums (to compare two builds step for step).
//!
//! Run: `cargo run --release -p tire --example step_profile -- <reduced tire file> [steps]
//! [symmetry: off|auto]`. Under `valgrind --tool=callgrind --collect-atstart=no
//! --toggle-collect='*rig_step*'` it gives the instructions of the steps alone.

use tire::rig::thread_cpu_s;
use tire::*;

fn main() {
    let mut args = std::env::args().skip(1);
    let file = args.next().expect("reduced tire file");
    let steps: usize = args.next().map_or(4000, |s| s.parse().expect("steps"));
    let sym = args.next().unwrap_or_else(|| "off".into());
    let red = ReducedTire::load(std::path::Path::new(&file)).expect("reduced tire file");
    let mut cfg = RigConfig::default();
    cfg.rolling.time_step = 5e-5;
    cfg.impact.substeps = 1;
    cfg.rolling.threads = 1;
    cfg.rolling.symmetry = if sym == "off" {
        Symmetry::Off
    } else {
        Symmetry::Auto
    };
    let mut start = start_rolling(&red, &cfg).expect("start");
    let sim = &mut start.sim;
    let c0 = thread_cpu_s().unwrap_or(f64::NAN);
    let w0 = std::time::Instant::now();
    let (mut sx, mut sy, mut sxx, mut syy) = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..steps {
        rig_step(sim, &cfg).expect("step");
        let f = sim.spindle_force();
        sx += f.fx;
        sy += f.fy;
        sxx += f.fx * f.fx;
        syy += f.fy * f.fy;
    }
    let cpu = thread_cpu_s().unwrap_or(f64::NAN) - c0;
    let wall = w0.elapsed().as_secs_f64();
    let st = &sim.stats;
    let us = |s: f64| 1e6 * s / steps as f64;
    println!(
        "steps {steps} t_end {:.6} s; CPU {:.1} us/step ({:.3} CPU s per simulated s), wall {:.1} us/step",
        sim.state.t,
        us(cpu),
        cpu / (steps as f64 * cfg.rolling.time_step),
        us(wall)
    );
    println!(
        "phases [us/step, wall]: free {:.1}, candidates {:.1}, R {:.1}, contact {:.1}, inversion {:.1}; \
         {:.1} candidates, {:.1} contacts, {:.2} chord; force updates {}",
        us(st.seconds[0]),
        us(st.seconds[1]),
        us(st.seconds[2]),
        us(st.seconds[3]),
        us(st.seconds[4]),
        st.candidates as f64 / st.steps as f64,
        st.active as f64 / st.steps as f64,
        st.contact_chord as f64 / st.steps as f64,
        st.force_matrix_updates
    );
    println!(
        "spindle force sums: fx {sx:.12e} fy {sy:.12e} fx2 {sxx:.12e} fy2 {syy:.12e}; last fx {:.15e} fy {:.15e}",
        sim.spindle_force().fx,
        sim.spindle_force().fy
    );
}
