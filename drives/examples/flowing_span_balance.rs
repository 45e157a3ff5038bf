//! Issue 34 item 2 diagnosis: the flowing belt's torque balance at speed, term by term.
//!
//! The default FEAD drive with a steady crank (no engine orders) at `rpm`, run with the
//! flowing model (Ribaric (5.14)) to `t_end`; at the final state, for each pulley, the moment
//! balance of the belt segment from the middle of the span reaching it to the middle of the
//! span leaving it (moments about the pulley's centre, counter-clockwise, of the nodal forces
//! on the segment's nodes at their deformed positions):
//!
//! ```text
//!   contact + internal = inertia + nodal residual,   residual r = g − M d̈
//! ```
//!
//! `internal` the moment of the elastic and damping nodal forces `f0 − K δ − damping` on the
//! segment (what the cut elements carry into it, plus the moment the elements inside the
//! segment fail to balance), `inertia` that of `M d̈` with the steady accelerations
//! `v² ε_n + v² T_,ss z + 2 v T_,s ż` of Ribaric (5.10)–(5.13), and `r` what the projection on
//! `[e_t | T]` leaves unbalanced at the nodes. Printed beside the report's torque residual
//! and its span moments, so that the residual splits into: span measure against internal
//! moment, momentum flux against inertia, and the projection's nodal residual. Then the
//! report's residuals with three other span measures: the spans' elastic force alone, the
//! length-weighted mean of the elements between each span's bounding contact nodes, and the
//! lines of action of the elements' own end forces (resultant and moment of
//! `f0 − (K_e + K_g) δ − β K_e w`, as `ancf::belt_drive::BeltDrive::span_force_lines`).
//! The measurements of BENCHMARKS.md "Found: the truncated basis leaves the spans' interior
//! unbalanced at speed" (issue 34 item 2, h-v2) are its output.
//!
//! `cargo run --release -p drives --example flowing_span_balance -- [key=value ...]` with keys
//! `rpm` (default 3500), `t_end` \[s\] (0.6), `ramp` \[s\] (0.2), `modes` (free modes,
//! default 12; 0: all), `ei` (factor on EI), `rho` (factor on the mass per length), `arc`,
//! `span` (element lengths \[m\]), `dump` (1: print every element's force along the loop).

use belt::BeltModel;
use drives::fead::FeadConfig;
use drives::simulation::BeltSimulation;
use flowing::belt::FlowingBelt;

mod common;

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// One line of a report's per-pulley torque residuals and their relative maximum.
fn print_residuals(label: &str, rep: &belt::Report) {
    let per_pulley: Vec<String> = rep
        .pulleys
        .iter()
        .map(|p| format!("{:+.4}", p.torque_residual_n_m))
        .collect();
    println!(
        "{label}: residuals {per_pulley:?} N m, {:.3} %",
        100.0 * rep.balances.torque_residual_rel
    );
}

fn main() {
    let arg = common::numeric_args();
    let rpm = arg("rpm", 3500.0);
    let mut cfg = FeadConfig::default();
    cfg.drive.belt.ei *= arg("ei", 1.0);
    cfg.drive.belt.mass_per_length *= arg("rho", 1.0);
    let fs = &mut cfg.models.flowing;
    let modes = arg("modes", 12.0) as usize;
    fs.reduction.free_modes = (modes > 0).then_some(modes);
    fs.mesh.span_element = arg("span", fs.mesh.span_element);
    fs.mesh.arc_element = arg("arc", fs.mesh.arc_element);
    let omega = rpm * std::f64::consts::PI / 30.0;
    let ramp = arg("ramp", 0.2);
    cfg.drive.pulleys[0].motion =
        belt::Motion::speed(belt::Signal::schedule(vec![(0.0, 0.0), (ramp, omega)]));
    let drive = cfg.drive.resolve().expect("drive");
    let model = FlowingBelt::new(&drive, &cfg.models.flowing).expect("model");
    let alpha = drives::fead::belt_alpha(&cfg);
    let mut sim = BeltSimulation::new(model, alpha).expect("simulation");
    sim.run_to(arg("t_end", 0.6), |_, _| {}).expect("run");
    let st = sim.state().clone();
    let b = sim.model();
    let rep = sim.report().expect("report");
    let (q, v) = (&st.q, &st.v);
    let m = b.n_modes();
    let (z, zd, vb) = (&q[1..=m], &v[1..=m], v[0]);
    let fe = &b.fe;
    let nn = fe.n_nodes();
    let n = fe.n_dofs();
    println!(
        "rpm {rpm}, t {:.3} s, belt speed {vb:.3} m/s, rho A v^2 {:.2} N, {} nodes, {m} modes",
        st.t,
        drive.belt().mass_per_length * vb * vb,
        nn
    );
    let d = b.deflection(z);
    let nodes: Vec<[f64; 2]> = (0..nn)
        .map(|i| {
            [
                fe.position[i][0] + d[3 * i],
                fe.position[i][1] + d[3 * i + 1],
            ]
        })
        .collect();
    let forces = b.element_forces(q, v);
    let elastic = b.element_tensions(z);
    // internal nodal forces f0 − K δ − (α M T ż + β K_e (δ̇_m − v ψ' J δ))
    let (alpha_d, beta_d) = (drive.damping().alpha, drive.damping().beta);
    let rate = b.material_rate(q, v);
    let mut tzd = vec![0.0; n];
    for (j, &x) in zd.iter().enumerate() {
        for (i, y) in tzd.iter_mut().enumerate() {
            *y += b.basis.t[(i, j)] * x;
        }
    }
    let mut fint = fe.pretension.clone();
    for i in 0..n {
        let mut acc = 0.0;
        for j in 0..n {
            let ke = fe.damping[(i, j)] - if i == j { alpha_d * fe.mass[i] } else { 0.0 };
            acc += fe.stiffness[(i, j)] * d[j] + ke * rate[j]
                - beta_d * vb * fe.frame_turn[(i, j)] * d[j];
        }
        fint[i] -= acc + alpha_d * fe.mass[i] * tzd[i];
    }
    // steady accelerations v² ε_n + v² T_,ss z + 2 v T_,s ż
    let mut acc = vec![0.0; n];
    for i in 0..nn {
        acc[3 * i] = vb * vb * fe.curvature[i][0];
        acc[3 * i + 1] = vb * vb * fe.curvature[i][1];
    }
    for j in 0..m {
        for (i, a) in acc.iter_mut().enumerate() {
            *a += vb * vb * b.basis.tss[(i, j)] * z[j] + 2.0 * vb * b.basis.ts[(i, j)] * zd[j];
        }
    }
    // contact forces on the belt
    let mut fc = vec![0.0; n];
    let mut tau = vec![0.0; drive.pulleys().len()];
    for r in b.contact_report(st.t, q, v) {
        fc[3 * r.node] += r.contact.force[0];
        fc[3 * r.node + 1] += r.contact.force[1];
        tau[r.pulley] += r.contact.torque;
    }
    let resid: Vec<f64> = (0..n)
        .map(|i| fc[i] + fint[i] - fe.mass[i] * acc[i])
        .collect();
    // projection check: e_tᵀ r and |Tᵀ r|
    let et = fe.stacked_tangent();
    let er: f64 = (0..n).map(|i| et[i] * resid[i]).sum();
    let tr: f64 = (0..m)
        .map(|j| {
            (0..n)
                .map(|i| b.basis.t[(i, j)] * resid[i])
                .sum::<f64>()
                .powi(2)
        })
        .sum::<f64>()
        .sqrt();
    println!("projection of the nodal residual: e_t^T r = {er:.3e} N, |T^T r| = {tr:.3e}");
    let path = fe.path();
    let spans = path.spans();
    let names = drive.names();
    // element (node i → i+1) nearest each span's middle
    let mid: Vec<usize> = spans
        .iter()
        .map(|sp| {
            let c = [
                sp.start[0] + 0.5 * sp.length * sp.direction[0],
                sp.start[1] + 0.5 * sp.length * sp.direction[1],
            ];
            (0..nn)
                .min_by(|&a, &bb| {
                    let h = |e: usize| {
                        let p = fe.position[e];
                        let p2 = fe.position[(e + 1) % nn];
                        let mp = [0.5 * (p[0] + p2[0]), 0.5 * (p[1] + p2[1])];
                        (mp[0] - c[0]).hypot(mp[1] - c[1])
                    };
                    h(a).total_cmp(&h(bb))
                })
                .unwrap()
        })
        .collect();
    if arg("dump", 0.0) > 0.0 {
        println!("e s x y N_elastic N_total");
        for e in 0..nn {
            println!(
                "{e} {:.5} {:.6} {:.6} {:.3} {:.3}",
                fe.s[e], nodes[e][0], nodes[e][1], elastic[e], forces[e]
            );
        }
    }
    for (k, sp) in spans.iter().enumerate() {
        let run = sp.middle_run(&nodes);
        let f: Vec<String> = run.iter().map(|&e| format!("{:.2}", forces[e])).collect();
        println!(
            "span {} -> {} ({:.1} mm): report {:.3} N, middle-half elements {:?}, mid element {}",
            names[sp.from],
            names[sp.to],
            1e3 * sp.length,
            rep.spans[k].tension_n,
            f,
            mid[k]
        );
    }
    let snap = b.snapshot(st.t, q, v).expect("snapshot");
    let ma_i: Vec<f64> = (0..n).map(|j| fe.mass[j] * acc[j]).collect();
    println!(
        "pulley: tau | report span torque, residual | segment: contact, internal, inertia, r (CCW N m)"
    );
    for (k, p) in drive.pulleys().iter().enumerate() {
        let si = spans.iter().position(|s| s.to == k).unwrap();
        let so = spans.iter().position(|s| s.from == k).unwrap();
        // segment nodes: from the end node of the middle element of the span in to the start
        // node of the middle element of the span out
        let (a, e) = ((mid[si] + 1) % nn, mid[so]);
        let c = snap.pulleys[k].center;
        let (mut mc, mut mi, mut ma, mut mr) = (0.0, 0.0, 0.0, 0.0);
        let mut i = a;
        loop {
            let x = [nodes[i][0] - c[0], nodes[i][1] - c[1]];
            let mom = |f: &[f64]| cross(x, [f[3 * i], f[3 * i + 1]]) + f[3 * i + 2];
            mc += mom(&fc);
            mi += mom(&fint);
            ma += mom(&ma_i);
            mr += mom(&resid);
            if i == e {
                break;
            }
            i = (i + 1) % nn;
        }
        let pr = &rep.pulleys[k];
        let turn = p.side.turn();
        let parts = |s: &belt::SpanState| {
            let lever = s.line.map_or(p.radius, |l| l.lever(c, turn));
            let flux = s.momentum_flux.map_or(0.0, |(f, l)| f * l.lever(c, turn));
            (
                s.tension * lever,
                flux,
                lever,
                s.momentum_flux.map_or(0.0, |x| x.0),
            )
        };
        let (ti, fi, li, phi_i) = parts(&snap.spans[si]);
        let (to, fo, lo, phi_o) = parts(&snap.spans[so]);
        println!(
            "   T ell: in {ti:+.4} out {to:+.4} (levers {:.4} {:.4} mm off R), flux moments in {fi:+.4} out {fo:+.4} (flux {phi_i:.2} {phi_o:.2} N, levers {:.4} {:.4} mm off R)",
            1e3 * (li - p.radius),
            1e3 * (lo - p.radius),
            1e3 * (snap.spans[si]
                .momentum_flux
                .map_or(0.0, |(_, l)| l.lever(c, turn))
                - p.radius),
            1e3 * (snap.spans[so]
                .momentum_flux
                .map_or(0.0, |(_, l)| l.lever(c, turn))
                - p.radius),
        );
        println!(
            "{:>16} ({:+}): tau {:+.4} | {:+.4}, {:+.4} | {:+.4}, {:+.4}, {:+.4}, {:+.4}",
            p.name,
            p.side.turn(),
            tau[k],
            pr.span_torque_n_m,
            pr.torque_residual_n_m,
            mc,
            mi,
            ma,
            mr
        );
    }
    // the same report with the spans' elastic force only (middle half)
    let mut snap_e = snap.clone();
    for (k, sp) in spans.iter().enumerate() {
        let run = sp.middle_run(&nodes);
        snap_e.spans[k].tension = run.iter().map(|&e| elastic[e]).sum::<f64>() / run.len() as f64;
    }
    let rep_e = belt::Report::new(&drive, &snap_e);
    // the same report with each span's force the length-weighted mean of its elements between
    // the contact nodes that bound it (the static modes' ramp)
    let contact: Vec<bool> = {
        let mut c = vec![false; nn];
        for set in &fe.contact_nodes {
            for &i in set {
                c[i] = true;
            }
        }
        c
    };
    let mut snap_w = snap.clone();
    for (k, &mk) in mid.iter().enumerate() {
        let mut a = mk;
        while !contact[a] {
            a = (a + nn - 1) % nn;
        }
        let mut e = (mk + 1) % nn;
        while !contact[e] {
            e = (e + 1) % nn;
        }
        let (mut sum, mut len) = (0.0, 0.0);
        let mut i = a;
        let mut els = Vec::new();
        while i != e {
            let j = (i + 1) % nn;
            let l = (fe.position[j][0] - fe.position[i][0])
                .hypot(fe.position[j][1] - fe.position[i][1]);
            sum += forces[i] * l;
            len += l;
            els.push(i);
            i = j;
        }
        snap_w.spans[k].tension = sum / len;
        println!(
            "span {k}: elements {els:?}: weighted mean {:.3} N",
            sum / len
        );
    }
    let rep_w = belt::Report::new(&drive, &snap_w);
    // section-force lines: the resultant and moment of the elements' own end forces
    // (f0 − (K_e + K_g) δ − β K_e w) over the middle half, both ends averaged
    let section = fe_model::element::Frame2dSection {
        ea: drive.belt().ea,
        ei: drive.belt().ei,
        mass_per_length: drive.belt().mass_per_length,
    };
    let t0 = drive.tension();
    let elem_forces = |e: usize| -> [f64; 6] {
        use fe_model::element::{Element, MatrixKind};
        let (i, j) = (e, (e + 1) % nn);
        let dofs = [3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2];
        let el = fe_model::element::Frame2d::new(dofs, fe.position[i], fe.position[j], section, t0)
            .unwrap();
        let k = el.stiffness();
        let kg = el.matrix(MatrixKind::Geometric).unwrap();
        let turn = vb
            * flowing::belt::model::chord_turn_rate(
                fe.position[i],
                fe.position[j],
                fe.tangent[i],
                fe.tangent[j],
            );
        let w: Vec<f64> = dofs
            .iter()
            .map(|&g| {
                let node = g / 3;
                match g % 3 {
                    0 => rate[g] + turn * d[3 * node + 1],
                    1 => rate[g] - turn * d[3 * node],
                    _ => rate[g],
                }
            })
            .collect();
        let (dx, dy) = (
            fe.position[j][0] - fe.position[i][0],
            fe.position[j][1] - fe.position[i][1],
        );
        let l = dx.hypot(dy);
        let u = [dx / l, dy / l];
        let mut f = [t0 * u[0], t0 * u[1], 0.0, -t0 * u[0], -t0 * u[1], 0.0];
        for a in 0..6 {
            for b2 in 0..6 {
                f[a] -= (k[(a, b2)] + kg[(a, b2)]) * d[dofs[b2]] + beta_d * k[(a, b2)] * w[b2];
            }
        }
        f
    };
    let mut snap_l = snap.clone();
    for (k, sp) in spans.iter().enumerate() {
        let run = sp.middle_run(&nodes);
        let (mut f, mut mo) = ([0.0; 2], 0.0);
        for &e in &run {
            let g = elem_forces(e);
            for (sign, o, node) in [(1.0, 0, e), (-1.0, 3, (e + 1) % nn)] {
                let fo = [g[o], g[o + 1]];
                f[0] += sign * fo[0];
                f[1] += sign * fo[1];
                mo += sign * (cross(nodes[node], fo) + g[o + 2]);
            }
        }
        let n2 = 2.0 * run.len() as f64;
        if let Some((t, line)) =
            belt::LineOfAction::of_resultant([f[0] / n2, f[1] / n2], mo / n2, sp.direction)
        {
            println!(
                "span {k}: section force {t:.3} N (elastic+viscous mean {:.3})",
                snap.spans[k].tension
            );
            snap_l.spans[k].line = Some(line);
        }
    }
    // the segments' internal moment split: the elements inside each segment (their own
    // moment imbalance about the deformed nodes) and the two cut elements' forces on it
    for (k, p) in drive.pulleys().iter().enumerate() {
        let si = spans.iter().position(|s| s.to == k).unwrap();
        let so = spans.iter().position(|s| s.from == k).unwrap();
        let (a, e_out) = ((mid[si] + 1) % nn, mid[so]);
        let c = snap.pulleys[k].center;
        let mom = |node: usize, g: &[f64; 6], o: usize| {
            let x = [nodes[node][0] - c[0], nodes[node][1] - c[1]];
            cross(x, [g[o], g[o + 1]]) + g[o + 2]
        };
        let g_in = elem_forces(mid[si]);
        let cut_in = mom(a, &g_in, 3);
        let g_out = elem_forces(e_out);
        let cut_out = mom(e_out, &g_out, 0);
        let mut imb = 0.0;
        let mut e = a;
        while e != e_out {
            let g = elem_forces(e);
            imb += mom(e, &g, 0) + mom((e + 1) % nn, &g, 3);
            e = (e + 1) % nn;
        }
        println!(
            "{:>16}: cut in {cut_in:+.4}, cut out {cut_out:+.4}, elements' imbalance {imb:+.4} N m",
            p.name
        );
    }
    let rep_l = belt::Report::new(&drive, &snap_l);
    print_residuals("section-force lines", &rep_l);
    print_residuals("bounded-span means", &rep_w);
    print_residuals("elastic span forces", &rep_e);
    println!(
        "report: torque residual {:.3} %, power {:.3} %",
        100.0 * rep.balances.torque_residual_rel,
        100.0 * rep.balances.power_residual_rel
    );
}
