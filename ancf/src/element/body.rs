//! [`ElementBody`]: the reference data every planar ANCF element carries (Kerkkänen §2.3).

use super::NodeLayout;
use crate::material::Material;
use crate::section::Section;

/// What the elements of this crate share before their strain energy: the nodal layout (which
/// fixes the shape functions, [`NodeLayout::shape`]), the reference (stress-free, straight)
/// length `l`, the material and the cross-section; [`super::AncfElement`]'s accessors and its
/// mass matrix (2.26) and gravity forces read them from here.
#[derive(Debug, Clone)]
pub struct ElementBody {
    /// Nodal layout (and with it the shape functions).
    pub layout: NodeLayout,
    /// Reference length `l` \[m\].
    pub length: f64,
    /// Material.
    pub material: Material,
    /// Cross-section.
    pub section: Section,
}
