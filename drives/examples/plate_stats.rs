//! Diagnostic: the stepper counters of a short plate-belt run (Model 2 defaults).
use drives::ancf_run::{Sampling, run_drive};
use drives::plate_study::{PlateStudyConfig, plate_setup};

fn main() {
    let t_end: f64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(0.02);
    let c = PlateStudyConfig::default();
    let (drive, init) = plate_setup(&c).expect("setup");
    let mut last = 0.0;
    let run = run_drive(
        &drive,
        &init.q,
        t_end,
        &c.integrator,
        Sampling {
            history: 1e-3,
            frame: 1.0,
        },
        |s, _| -> Result<(), ()> {
            last = s.t;
            Ok(())
        },
    )
    .unwrap();
    println!("t {last} failure {:?}", run.failure);
    println!("{:#?}", run.stats);
}
