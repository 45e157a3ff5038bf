//! Straight beam meshes of the chapter-2 elements (Kerkkänen §2.1), used by the dynamics module
//! and the paper cases (`flowmbd-cases`).

use crate::element::AncfElement;
use crate::error::{AncfError, invalid};
use crate::mesh::AncfMesh;
use serde::{Deserialize, Serialize};

/// Which beam element a study uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum BeamElementKind {
    /// Kerkkänen's proposed 8-DOF linear element (§2.1.1).
    Proposed,
    /// The Omar–Shabana 12-DOF element (§2.1).
    OmarShabana,
}

/// Most elements of a generated beam: 10⁴ times the 8–32 elements of Kerkkänen's §2.4 cases
/// (the static and dynamic solvers assemble `6 (n + 1)` coordinates); a larger count is refused
/// before the mesh is allocated (`--elements 1e9` aborted on the allocation, issue 20).
pub const MAX_BEAM_ELEMENTS: usize = 100_000;

/// Build a straight chain of `n_el` equal elements with `make(element_length)`.
pub fn beam_mesh<E, F>(length: f64, n_el: usize, make: F) -> Result<AncfMesh<E>, AncfError>
where
    E: AncfElement,
    F: Fn(f64) -> Result<E, AncfError>,
{
    mbd_core::validate::check::size("elements", n_el, 1, MAX_BEAM_ELEMENTS)
        .map_err(|e| invalid("elements", e.reason))?;
    if !(length.is_finite() && length > 0.0) {
        return Err(invalid("length", format!("must be > 0 m, got {length}")));
    }
    let le = length / n_el as f64;
    let els = (0..n_el).map(|_| make(le)).collect::<Result<Vec<_>, _>>()?;
    AncfMesh::chain(els)
}
