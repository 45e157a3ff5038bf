//! The pulleys of an ANCF belt system, shared by the planar and the plate drive (issue 33
//! item 2): the checks of a drive's pulley list, and the free pulleys' inertias and dampers on
//! the diagonal of the system matrices. Their coordinates are the belt crate's
//! ([`belt::coordinates::PulleyCoordinates`], Kerkkänen (3.26)).

use crate::sparse::Pattern;
use belt::Pulley;
use mbd_core::validate::{InvalidField, Validate};

pub use belt::MAX_PULLEYS;
pub use belt::coordinates::PulleyCoordinates;

/// The checks of a drive's pulley list shared by the planar and the plate drive: 2 to
/// [`MAX_PULLEYS`] pulleys, each valid ([`belt::Pulley`]'s own checks, named
/// `pulleys[i]…`), no name used twice (`pulleys[i].name`).
pub fn validate_pulleys(pulleys: &[Pulley]) -> Result<(), InvalidField> {
    if pulleys.len() < 2 {
        return Err(InvalidField::new(
            "pulleys",
            format!("need at least 2, got {}", pulleys.len()),
        ));
    }
    if pulleys.len() > MAX_PULLEYS {
        return Err(InvalidField::new(
            "pulleys",
            format!("at most {MAX_PULLEYS} supported, got {}", pulleys.len()),
        ));
    }
    for (i, p) in pulleys.iter().enumerate() {
        p.validate_within(&format!("pulleys[{i}]"))?;
        if pulleys[..i].iter().any(|o| o.name == p.name) {
            return Err(InvalidField::new(
                format!("pulleys[{i}].name"),
                format!("'{}' is used twice", p.name),
            ));
        }
    }
    Ok(())
}

/// Add the free pulleys' inertias to the diagonal of the mass values `m` of `pattern`.
pub(crate) fn add_inertias(
    pc: &PulleyCoordinates, pulleys: &[Pulley], pattern: &Pattern, m: &mut [f64],
) {
    for (p, j) in pc.free() {
        if let Some(inertia) = pulleys[p].motion.inertia() {
            m[pattern.diagonal_position(j)] += inertia;
        }
    }
}

/// Add the free pulleys' viscous damping `c` of `−c ω` to the diagonal of the damping
/// values `c` of `pattern`.
pub(crate) fn add_damping(
    pc: &PulleyCoordinates, pulleys: &[Pulley], pattern: &Pattern, c: &mut [f64],
) {
    for (p, j) in pc.free() {
        let damping = pulleys[p].motion.damping();
        if damping > 0.0 {
            c[pattern.diagonal_position(j)] += damping;
        }
    }
}
