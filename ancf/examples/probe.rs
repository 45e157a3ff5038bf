use ancf::dynamics::*;
use ancf::studies::BeamElementKind;
fn main() {
    for el in [BeamElementKind::Proposed, BeamElementKind::OmarShabana] {
        for n in [4, 8] {
            let c = PendulumCase {
                element: el,
                elements: n,
                t_end: 1.0,
                h: 5e-5,
                ..Default::default()
            };
            let t = std::time::Instant::now();
            let s = pendulum(&c, 2000, |_| {}).unwrap();
            println!(
                "{el:?} n={n} {:?} drift {:e} tip(0.5s) {:?} tip(1s) {:?}",
                t.elapsed(),
                energy_drift(&s),
                s[s.len() / 2].tip,
                s.last().unwrap().tip
            );
        }
    }
}
