//! The one plain-data description of an ANCF belt drive (issue 33 item 2): the pulleys in
//! travel order, the belt and the contact. The planar drive (Kerkkänen §3.3, Table 3.1,
//! [`crate::belt_drive::BeltDriveSpec`]) and the plate drive (§4.6, Table 4.1,
//! [`crate::plate::belt_drive::PlateDriveSpec`]) are this description with their own belt and
//! contact parameters.

use belt::{Motion, Pulley};
use serde::{Deserialize, Serialize};

/// A complete ANCF belt drive: pulleys in travel order, the belt `B` and the contact `C`
/// (module documentation). Fields missing from a configuration take the drive's default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(
    deny_unknown_fields,
    default,
    bound(
        serialize = "B: Serialize, C: Serialize",
        deserialize = "B: Deserialize<'de>, C: Deserialize<'de>, DriveSpec<B, C>: Default"
    )
)]
#[schemars(bound = "B: schemars::JsonSchema, C: schemars::JsonSchema, DriveSpec<B, C>: Default")]
pub struct DriveSpec<B, C> {
    /// Pulleys in travel order (the belt runs from pulley 0 to pulley 1, …); the plate belt
    /// also meets their crowns, flanges and centre shifts (Kerkkänen (4.43)–(4.46)).
    pub pulleys: Vec<Pulley>,
    /// Belt.
    pub belt: B,
    /// Contact.
    pub contact: C,
}

impl<B, C> DriveSpec<B, C> {
    /// The pulleys in travel order.
    pub fn pulleys(&self) -> &[Pulley] {
        &self.pulleys
    }

    /// The motion of pulley `p` (its signals may be replaced between runs; its kind and
    /// inertia must stay: a drive's coordinates and mass matrix depend on them).
    pub fn motion_mut(&mut self, p: usize) -> Option<&mut Motion> {
        self.pulleys.get_mut(p).map(|p| &mut p.motion)
    }
}
