//! The planar ANCF element abstraction (Kerkkänen §2.3): `r = S(x, y) e` with a constant mass
//! matrix, elastic forces `Q_e = −(∂U/∂e)ᵀ` (2.20) and their tangent `∂²U/∂e²`.

mod belt;
mod belt_kernel;
mod body;
mod kernel;
mod omar_shabana;
mod proposed;

pub use belt::BeltElement;
pub use body::ElementBody;
pub use kernel::QuadraticStrainBeam;
pub use omar_shabana::OmarShabanaBeam;
pub use proposed::ProposedBeam;

use crate::section::Section;
use crate::shape::{self, CUBIC_BLOCKS, LINEAR_BLOCKS};
use contact::GaussRule;

/// Largest number of element coordinates of the planar elements (12).
pub const MAX_NDOF: usize = 12;

/// Which nodal coordinates an element carries (2-vectors per node, Kerkkänen (2.3), (2.11)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeLayout {
    /// `[r, r_y]` per node (the proposed linear element, 4 coordinates per node).
    PositionCrossSlope,
    /// `[r, r_x, r_y]` per node (Omar–Shabana and belt elements, 6 coordinates per node).
    PositionBothSlopes,
}

impl NodeLayout {
    /// Number of scalar coordinates per node.
    pub fn coords_per_node(self) -> usize {
        match self {
            NodeLayout::PositionCrossSlope => 4,
            NodeLayout::PositionBothSlopes => 6,
        }
    }

    /// Nodal coordinates of a material point at `position` \[m\] whose (unit) axial direction is
    /// `tangent`, with axial stretch `stretch` (`r_x = stretch·t`) and unit `r_y = Ĩ t`.
    pub fn node_coordinates(self, position: [f64; 2], tangent: [f64; 2], stretch: f64) -> Vec<f64> {
        let n = [-tangent[1], tangent[0]];
        match self {
            NodeLayout::PositionCrossSlope => vec![position[0], position[1], n[0], n[1]],
            NodeLayout::PositionBothSlopes => vec![
                position[0],
                position[1],
                stretch * tangent[0],
                stretch * tangent[1],
                n[0],
                n[1],
            ],
        }
    }

    /// Scalar shape functions `Sₖ(x, y)` of the layout's element family at `x ∈ [0, l]`,
    /// `y` transverse, into `s[..blocks]`: the linear functions (2.12) of `[r, r_y]` nodes,
    /// the cubic ones (3.11) with the corrected `S₅` of `[r, r_x, r_y]` nodes.
    pub fn shape(self, length: f64, x: f64, y: f64, s: &mut [f64]) {
        match self {
            NodeLayout::PositionCrossSlope => {
                s[..LINEAR_BLOCKS].copy_from_slice(&shape::linear(length, x, y).s);
            }
            NodeLayout::PositionBothSlopes => {
                s[..CUBIC_BLOCKS].copy_from_slice(&shape::cubic(length, x, y).s);
            }
        }
    }

    /// Offset of the position `r` within a node's coordinates (always 0) and of `r_y`.
    pub fn cross_slope_offset(self) -> usize {
        match self {
            NodeLayout::PositionCrossSlope => 2,
            NodeLayout::PositionBothSlopes => 4,
        }
    }
}

/// A planar two-node ANCF element. Implementors are plain data; all methods are
/// allocation-free (buffers are supplied by the caller) so that mesh loops can run every
/// Newton iteration without touching the heap.
///
/// Element vectors `e` hold `ndof = 2·blocks` coordinates ordered node by node; matrices are
/// `ndof × ndof`, column-major.
pub trait AncfElement: Send + Sync {
    /// Layout, length, material and section of the element.
    fn body(&self) -> &ElementBody;
    /// Nodal layout.
    fn layout(&self) -> NodeLayout {
        self.body().layout
    }
    /// Number of element coordinates.
    fn ndof(&self) -> usize {
        2 * self.layout().coords_per_node()
    }
    /// Reference (stress-free, straight) length `l` \[m\].
    fn length(&self) -> f64 {
        self.body().length
    }
    /// Density \[kg/m³\].
    fn density(&self) -> f64 {
        self.body().material.density
    }
    /// Cross-section.
    fn section(&self) -> &Section {
        &self.body().section
    }
    /// Scalar shape functions `Sₖ(x, y)` (`x ∈ [0, l]`, `y` transverse) into `s[..ndof/2]`
    /// ([`NodeLayout::shape`] of the layout).
    fn shape(&self, x: f64, y: f64, s: &mut [f64]) {
        self.layout().shape(self.length(), x, y, s);
    }
    /// Strain energy `U(e)` \[J\].
    fn strain_energy(&self, e: &[f64]) -> f64;
    /// Elastic forces `Q_e = −(∂U/∂e)ᵀ` (Kerkkänen (2.20)) written into `q` \[N\].
    fn elastic_forces(&self, e: &[f64], q: &mut [f64]);
    /// Elastic forces into `q` and the tangent stiffness `K = ∂²U/∂e²` (column-major) into `k`.
    fn elastic_tangent(&self, e: &[f64], q: &mut [f64], k: &mut [f64]);

    /// Constant consistent mass matrix `M = ∫_V ρ SᵀS dV`, Kerkkänen (2.26), integrated exactly
    /// (5 Gauss points along `x`, the exact section rule in `y`), written into `m` (column-major).
    fn mass_matrix(&self, m: &mut [f64]) {
        let n = self.ndof();
        let nb = n / 2;
        m[..n * n].fill(0.0);
        let rule = GaussRule::new(5);
        let l = self.length();
        let rho = self.density();
        let mut s = [0.0; MAX_NDOF / 2];
        for (xi, wx) in rule.iter() {
            for (y, wy) in self.section().y_rule() {
                self.shape(xi * l, y, &mut s[..nb]);
                let w = rho * wx * l * wy;
                for i in 0..nb {
                    for j in 0..nb {
                        let v = w * s[i] * s[j];
                        m[2 * i + 2 * j * n] += v;
                        m[2 * i + 1 + (2 * j + 1) * n] += v;
                    }
                }
            }
        }
    }

    /// Generalized gravity force `Q_g = ∫_V ρ Sᵀ g dV` for the acceleration `g` \[m/s²\] into `q`.
    fn gravity_forces(&self, g: [f64; 2], q: &mut [f64]) {
        let n = self.ndof();
        let nb = n / 2;
        q[..n].fill(0.0);
        let rule = GaussRule::new(3);
        let l = self.length();
        let mut s = [0.0; MAX_NDOF / 2];
        for (xi, wx) in rule.iter() {
            for (y, wy) in self.section().y_rule() {
                self.shape(xi * l, y, &mut s[..nb]);
                let w = self.density() * wx * l * wy;
                for i in 0..nb {
                    q[2 * i] += w * s[i] * g[0];
                    q[2 * i + 1] += w * s[i] * g[1];
                }
            }
        }
    }

    /// Position `r(x, y) = S(x, y) e` of a material point \[m\].
    fn position(&self, e: &[f64], x: f64, y: f64) -> [f64; 2] {
        let nb = self.ndof() / 2;
        let mut s = [0.0; MAX_NDOF / 2];
        self.shape(x, y, &mut s[..nb]);
        let mut r = [0.0; 2];
        for k in 0..nb {
            r[0] += s[k] * e[2 * k];
            r[1] += s[k] * e[2 * k + 1];
        }
        r
    }
}
