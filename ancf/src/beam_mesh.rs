//! Straight beam meshes of the chapter-2 elements (Kerkkänen §2.1), used by the dynamics module
//! and the paper cases (`flowmbd-cases`).

use crate::element::Element;
use crate::error::{AncfError, invalid};
use crate::mesh::Mesh;
use serde::{Deserialize, Serialize};

/// Which beam element a study uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BeamElementKind {
    /// Kerkkänen's proposed 8-DOF linear element (§2.1.1).
    Proposed,
    /// The Omar–Shabana 12-DOF element (§2.1).
    OmarShabana,
}

/// Build a straight chain of `n_el` equal elements with `make(element_length)`.
pub fn beam_mesh<E, F>(length: f64, n_el: usize, make: F) -> Result<Mesh<E>, AncfError>
where
    E: Element,
    F: Fn(f64) -> Result<E, AncfError>,
{
    if n_el == 0 {
        return Err(invalid("elements", "must be ≥ 1"));
    }
    if !(length.is_finite() && length > 0.0) {
        return Err(invalid("length", format!("must be > 0 m, got {length}")));
    }
    let le = length / n_el as f64;
    let els = (0..n_el).map(|_| make(le)).collect::<Result<Vec<_>, _>>()?;
    Mesh::chain(els)
}
