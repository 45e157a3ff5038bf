//! Reduced FE tire (Ribaric §8.2): reduction exactness, truncation, statics, file round trip.

use flowing::tire::*;

fn small() -> TireFe {
    generated_tire(&coarse_tire_config(24, 8, 40.0)).expect("tire")
}

#[test]
fn explore() {
    let fe = small();
    println!("nodes {} dofs {} cand {} rim {} mass {}", fe.n_nodes(), fe.n_dofs(), fe.candidates.len(), fe.rim.len(), fe.total_mass());
    let full = full_frequencies_hz(&fe, 20).unwrap();
    println!("full {:?}", full);
    let cfg = ReductionConfig { contact_nodes: 12, free_modes: 10000, ..Default::default() };
    let t = std::time::Instant::now();
    let (red, tim) = reduce(&fe, &cfg).unwrap();
    println!("reduce {:?} {:?} nz {}", t.elapsed(), tim, red.n_z());
    let f = red.frequencies_hz().unwrap();
    println!("red {:?}", &f[..20]);
    let cfg = ReductionConfig { contact_nodes: 12, free_modes: 20, ..Default::default() };
    let (red, _) = reduce(&fe, &cfg).unwrap();
    let f = red.frequencies_hz().unwrap();
    println!("red20 {:?}", &f[..20]);
    let pl = preload(&red, &GroundConfig::default(), 4448.0).unwrap();
    println!("preload defl {} force {} lambda {:?}", pl.patch.deflection, pl.patch.force, pl.patch.lambda);
}
