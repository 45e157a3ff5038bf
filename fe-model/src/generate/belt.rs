//! Closed two-pulley belt loop of planar frame elements (Ribaric Ch. 5–6 belt drive).
//!
//! Path (seed-000 note, belt path parametrisation): pulley 1 centred at (0, 0), pulley 2 at
//! (L_c, 0), both of radius R; upper span y = R from x = 0 to L_c (s increasing), arc around
//! pulley 2, lower span y = −R back to x = 0, arc around pulley 1. All spans and arcs are
//! divided uniformly; arcs are usually given shorter elements than spans. The loop is closed:
//! the last element connects back to node 0. Every element carries the axial force `tension`
//! for its geometric stiffness. DOFs per node: (u, v, θ).

use super::beam::frame2d_line;
use crate::FeError;
use crate::element::Frame2dSection;
use crate::mesh::Mesh;
use crate::model::FeModel;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Parameters of the belt loop (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BeltLoopConfig {
    /// Pulley centre distance L_c \[m\] (0 gives a circular ring).
    pub center_distance: f64,
    /// Pulley (pitch) radius R \[m\].
    pub radius: f64,
    /// Elements per straight span.
    pub span_elements: usize,
    /// Elements per half-circle arc.
    pub arc_elements: usize,
    /// Section (EA, EI, ρA).
    pub section: Frame2dSection,
    /// Belt tension T0 \[N\] used for the geometric stiffness.
    pub tension: f64,
}

impl Default for BeltLoopConfig {
    /// Ribaric §6.1 belt: R = 0.05 m, EA = 152 000 N, EI = 0.026 N m², ρA = 0.096 kg/m,
    /// T0 = 310 N; L_c = 0.45 m (span length of the seed's first span), 5 mm span elements and
    /// 2.5 mm-class arc elements (arc length πR/64 ≈ 2.45 mm).
    fn default() -> Self {
        Self {
            center_distance: 0.45,
            radius: 0.05,
            span_elements: 90,
            arc_elements: 64,
            section: Frame2dSection {
                ea: 152_000.0,
                ei: 2.6e-2,
                mass_per_length: 0.096,
            },
            tension: 310.0,
        }
    }
}

/// Generate the belt loop. Node sets: `upper_span`, `lower_span`, `arc_pulley1`,
/// `arc_pulley2` (arc nodes including the tangent points), `all`.
pub fn belt_loop(cfg: &BeltLoopConfig) -> Result<FeModel, FeError> {
    FeError::check_non_negative("center_distance", cfg.center_distance)?;
    FeError::check_positive("radius", cfg.radius)?;
    cfg.section.validate()?;
    if cfg.arc_elements < 2 {
        return Err(FeError::param(
            "arc_elements",
            cfg.arc_elements as f64,
            "must be >= 2",
        ));
    }
    if cfg.center_distance > 0.0 && cfg.span_elements == 0 {
        return Err(FeError::param(
            "span_elements",
            0.0,
            "must be >= 1 when center_distance > 0",
        ));
    }
    let (lc, r) = (cfg.center_distance, cfg.radius);
    let ns = if lc > 0.0 { cfg.span_elements } else { 0 };
    let na = cfg.arc_elements;
    let mut mesh = Mesh::new(3);
    let (mut upper, mut lower, mut arc1, mut arc2) = (vec![], vec![], vec![], vec![]);
    // upper span: x from 0 to L_c (excluding end, which starts arc 2)
    for i in 0..ns {
        let id = mesh.add_node([lc * i as f64 / ns as f64, r, 0.0]);
        upper.push(id);
    }
    // arc around pulley 2: φ from π/2 down to −π/2
    for i in 0..na {
        let phi = PI / 2.0 - PI * i as f64 / na as f64;
        let id = mesh.add_node([lc + r * phi.cos(), r * phi.sin(), 0.0]);
        arc2.push(id);
    }
    // lower span: x from L_c back to 0
    for i in 0..ns {
        let id = mesh.add_node([lc - lc * i as f64 / ns as f64, -r, 0.0]);
        lower.push(id);
    }
    // arc around pulley 1: φ from −π/2 down to −3π/2
    for i in 0..na {
        let phi = -PI / 2.0 - PI * i as f64 / na as f64;
        let id = mesh.add_node([r * phi.cos(), r * phi.sin(), 0.0]);
        arc1.push(id);
    }
    let nn = mesh.n_nodes();
    // tangent points belong to both the span and the arc sets
    if ns > 0 {
        arc2.push(ns + na); // arc 2 → lower span
        upper.push(ns); // upper span → arc 2
        lower.push(2 * ns + na); // lower span → arc 1
        arc1.push(0); // arc 1 → upper span
    } else {
        arc2.push(na % nn);
        arc1.push(0);
    }
    let mut els = Vec::with_capacity(nn);
    for a in 0..nn {
        els.push(frame2d_line(
            &mut mesh,
            a,
            (a + 1) % nn,
            cfg.section,
            cfg.tension,
        )?);
    }
    mesh.set_node_set("upper_span", upper)?;
    mesh.set_node_set("lower_span", lower)?;
    mesh.set_node_set("arc_pulley1", arc1)?;
    mesh.set_node_set("arc_pulley2", arc2)?;
    mesh.set_node_set("all", (0..nn).collect())?;
    let mut model = FeModel::new(mesh);
    for e in els {
        model.push(e);
    }
    Ok(model)
}
