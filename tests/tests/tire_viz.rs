//! Visualisation rows of the reduced tire (VTK series of the whole deforming tire, issue 9):
//! with one station per ring node they are the rows of the basis `T` at every node, so at the
//! contact nodes they must equal the stored contact rows `T_c`, and at the rim they vanish (the
//! rim carries no deflection, Ribaric (7.11)); they survive the file round trip.

use tire::*;

#[test]
fn visualisation_rows_are_the_basis_rows() {
    let fe = generated_tire(&coarse_tire_config(24, 8, 40.0)).unwrap();
    let cfg = ReductionConfig {
        contact_nodes: 12,
        free_modes: 20,
        viz_stations: 24,
        ..Default::default()
    };
    let red = reduce(&fe, &cfg).unwrap().0;
    let viz = red.viz.as_ref().expect("viz rows");
    // every node of every ring, each ring a closed polyline
    assert_eq!(viz.nodes.len(), viz.lines.len());
    let nz = red.n_z();
    let mut found = 0;
    for (k, &node) in red.contact_nodes.iter().enumerate() {
        let v = viz
            .nodes
            .iter()
            .position(|&n| n == node)
            .expect("contact node drawn");
        for a in 0..3 {
            for j in 0..nz {
                assert_eq!(viz.rows[(3 * v + a, j)], red.tc[(3 * k + a, j)]);
            }
        }
        found += 1;
    }
    assert_eq!(found, 12);
    let rim = fe.rim_mask();
    for (v, &node) in viz.nodes.iter().enumerate() {
        if rim[node] {
            for j in 0..nz {
                assert_eq!(viz.rows[(3 * v, j)], 0.0);
            }
        }
    }
    // deformed shape at the preload on a flat road: the lowest contact node sits on the road
    let road = GroundConfig {
        kind: GroundKind::Road,
        cleat: false,
        ..GroundConfig::default()
    };
    let pre = preload(&red, &road, 4448.2).unwrap();
    let x = viz.deformed(&pre.z);
    let lowest = red
        .contact_nodes
        .iter()
        .map(|n| x[viz.nodes.iter().position(|m| m == n).unwrap()][2])
        .fold(f64::INFINITY, f64::min);
    assert!(
        (lowest - pre.patch.top).abs() < 1e-6,
        "lowest node {lowest} m vs ground top {} m",
        pre.patch.top
    );
    // file round trip (serde_json's default float parser is exact to about 1 ulp)
    let back = ReducedTire::from_json(&red.to_json().unwrap(), "memory").unwrap();
    let bv = back.viz.as_ref().expect("viz rows after the round trip");
    assert_eq!(bv.nodes, viz.nodes);
    assert_eq!(bv.lines, viz.lines);
    let scale = (0..viz.rows.nrows())
        .flat_map(|i| (0..nz).map(move |j| (i, j)))
        .fold(0.0f64, |m, (i, j)| m.max(viz.rows[(i, j)].abs()));
    for i in 0..viz.rows.nrows() {
        for j in 0..nz {
            assert!((bv.rows[(i, j)] - viz.rows[(i, j)]).abs() <= 1e-14 * scale);
        }
    }
}
