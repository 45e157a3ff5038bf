//! Wall time per simulated second of the belt drive (Ribaric Table 6-1, 62.8 rad/s, load
//! 0 → 8 N m), side by side at equal Δω accuracy (issue 8):
//!
//! - flowing-material form (5.14) on the default 56-element stationary mesh, 20 free-node
//!   modes (truncated) and all modes (untruncated), and on the nodal model's 216-element loop
//!   (20 free modes), at generalized-α steps 0.25 to 4 ms;
//! - nodal rotating-mesh form (5.7) on the coarsest uniform loop on which its Δω agrees with
//!   the flowing form's within 2 % (216 elements, `tests/tests/flowing_belt_nodal.rs`; on the
//!   56-element mesh its polygonal ripple keeps it from any steady state), at 0.25, 0.5 and 1 ms.
//!
//! A step counts as accurate when its Δω(8 N m) lies within 1 % of the same model's Δω at
//! 0.25 ms. The printed ratio compares the fastest accurate run of each form.
//! Run: `cargo bench -p drives --bench belt_models` (several minutes: the nodal model is slow).

mod timed;

use flowing::belt::{BeltMesh, BeltReduction, FlowingBelt, FlowingSettings, NodalBelt};
use timed::{Run, print, run};

fn flowing(mesh: Option<(usize, usize)>, free_modes: Option<usize>, step: f64) -> Option<Run> {
    let mut settings = FlowingSettings {
        reduction: BeltReduction { free_modes },
        ..Default::default()
    };
    if let Some((span, arc)) = mesh {
        settings.mesh = uniform(span, arc);
    }
    let mut belt = FlowingBelt::new(&drives::table_6_1::drive(), &settings).expect("model");
    let n_el = belt.fe.n_nodes();
    let dofs = belt.n_modes() + 2;
    let name = match free_modes {
        Some(k) => format!("flowing, {n_el} el., {k} free modes"),
        None => format!("flowing, {n_el} el., all modes"),
    };
    run(&name, dofs, &mut belt, step)
}

fn nodal(span: usize, arc: usize, step: f64) -> Option<Run> {
    let mut belt = NodalBelt::new(&drives::table_6_1::drive(), &uniform(span, arc)).expect("model");
    let n_el = belt.fe.n_nodes();
    let dofs = belt.n_nodal() + 2;
    run(
        &format!("nodal rotating mesh, {n_el} el."),
        dofs,
        &mut belt,
        step,
    )
}

/// Table 6-1's loop with `span` elements per span and `arc` per wrap.
fn uniform(span: usize, arc: usize) -> BeltMesh {
    BeltMesh {
        span_element: 0.45 / span as f64,
        arc_element: std::f64::consts::PI * 0.05 / arc as f64,
        contact_margin_nodes: 1,
    }
}

/// The fastest run whose Δω is within 1 % of the first (finest-step) run of its group.
fn best(group: &[Run]) -> Option<&Run> {
    let reference = group.first()?;
    group
        .iter()
        .filter(|r| (r.delta_omega / reference.delta_omega - 1.0).abs() < 0.01)
        .min_by(|a, b| a.rate().total_cmp(&b.rate()))
}

fn main() {
    timed::header();
    let mut groups: Vec<Vec<Run>> = Vec::new();
    for (mesh, modes) in [(None, Some(20)), (None, None), (Some((80, 28)), Some(20))] {
        let mut g = Vec::new();
        for h in [2.5e-4, 5e-4, 1e-3, 2e-3, 4e-3] {
            if let Some(r) = flowing(mesh, modes, h) {
                print(&r);
                g.push(r);
            }
        }
        groups.push(g);
    }
    let mut g = Vec::new();
    for h in [2.5e-4, 5e-4, 1e-3] {
        if let Some(r) = nodal(80, 28, h) {
            print(&r);
            g.push(r);
        }
    }
    groups.push(g);
    let picks: Vec<Option<&Run>> = groups.iter().map(|g| best(g)).collect();
    println!("fastest run within 1 % of its model's 0.25 ms Δω:");
    for r in picks.iter().flatten() {
        print(r);
    }
    if let [Some(tr), Some(un), Some(same), Some(no)] = picks[..] {
        let rate = Run::rate;
        println!(
            "ratios of wall time per simulated second: nodal / flowing truncated (56 el.) = {:.1}, \
             nodal / flowing truncated (same 216-el. mesh) = {:.1}, \
             untruncated / truncated = {:.2}, nodal / flowing untruncated = {:.1}",
            rate(no) / rate(tr),
            rate(no) / rate(same),
            rate(un) / rate(tr),
            rate(no) / rate(un)
        );
        for f in [tr, same] {
            println!(
                "Δω(8 N m): nodal {:.5} vs {} {:.5} ({:+.2} %)",
                no.delta_omega,
                f.name,
                f.delta_omega,
                100.0 * (no.delta_omega / f.delta_omega - 1.0)
            );
        }
    }
}
