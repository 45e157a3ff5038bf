use ancf::dynamics::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args[1] == "p" {
        let mut c = PendulumCase::default();
        c.h = args[2].parse().unwrap();
        c.t_end = args[3].parse().unwrap();
        let t0 = std::time::Instant::now();
        let s = pendulum(&c, 100, |_| {}).unwrap();
        println!(
            "drift {:e} J, time {:?}, last {:?}",
            energy_drift(&s),
            t0.elapsed(),
            s.last().unwrap()
        );
    } else {
        let mut c = SpinningCase::default();
        c.h = args[2].parse().unwrap();
        c.rho_inf = args[3].parse().unwrap();
        let t0 = std::time::Instant::now();
        let s = spinning(&c, 500, |_| {}).unwrap();
        for x in s.iter().step_by(4) {
            println!("t={:.2} ext={:.5e} off={:.3e}", x.t, x.value, x.value2);
        }
        println!(
            "time {:?}, exact {:e}",
            t0.elapsed(),
            spinning_extension(8.0, 2766.67, 6.895e10, 4.0)
        );
    }
}
