//! Flow grids: nodal positions along a flow coordinate (Ribaric App. A, Fig. A-1).
//!
//! The flow coordinate is `x` for the string, the path length `s` for the belt and the
//! circumferential angle `θ` for the tire (Ribaric A.5). A grid is either **open** (a line
//! with two ends; each end either carries a known zero value at a position outside the node set,
//! as for the fixed string of Ribaric (A.2), or is free, in which case one-sided stencils are used)
//! or **closed** (a loop of given period; positions wrap around).

use crate::error::{FlowError, invalid};

/// What is known at one end of an open grid.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
pub enum End {
    /// The field is zero at this position (a fixed end, Ribaric (A.2)); the position lies
    /// outside the node range \[m or rad\].
    Zero(f64),
    /// Nothing is known beyond the last node: one-sided stencils.
    Free,
}

/// Topology of a flow grid.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
pub enum Topology {
    /// A line with two ends.
    Open {
        /// End before the first node.
        start: End,
        /// End after the last node.
        end: End,
    },
    /// A closed loop (belt path, tire ring) of the given period \[m or rad\].
    Closed {
        /// Period of the flow coordinate (loop length or 2π).
        period: f64,
    },
}

/// Nodal positions along a flow coordinate, strictly increasing, with a topology.
#[derive(Debug, Clone, PartialEq)]
pub struct FlowGrid {
    positions: Vec<f64>,
    topology: Topology,
}

impl FlowGrid {
    /// Builds a grid from strictly increasing positions \[m or rad\].
    ///
    /// For an open grid a `Zero` end must lie strictly outside `[s_first, s_last]`; for a closed
    /// grid all positions must lie in `[s_0, s_0 + period)`.
    pub fn new(positions: Vec<f64>, topology: Topology) -> Result<Self, FlowError> {
        if positions.is_empty() {
            return Err(invalid("flow grid", "no nodes"));
        }
        for (j, s) in positions.iter().enumerate() {
            if !s.is_finite() {
                return Err(invalid(
                    format!("flow grid: node {j} position"),
                    "not finite",
                ));
            }
        }
        for j in 1..positions.len() {
            if positions[j] <= positions[j - 1] {
                return Err(invalid(
                    format!("flow grid: node {j} position"),
                    format!(
                        "positions must increase strictly ({} after {})",
                        positions[j],
                        positions[j - 1]
                    ),
                ));
            }
        }
        let first = positions[0];
        let last = positions[positions.len() - 1];
        match topology {
            Topology::Open { start, end } => {
                if let End::Zero(a) = start
                    && !(a.is_finite() && a < first)
                {
                    {
                        return Err(invalid(
                            "flow grid: start end",
                            format!("zero-value end at {a} must lie before the first node {first}"),
                        ));
                    }
                }
                if let End::Zero(b) = end
                    && !(b.is_finite() && b > last)
                {
                    {
                        return Err(invalid(
                            "flow grid: end end",
                            format!("zero-value end at {b} must lie after the last node {last}"),
                        ));
                    }
                }
            }
            Topology::Closed { period } => {
                if !(period.is_finite() && period > 0.0) {
                    return Err(invalid(
                        "flow grid: period",
                        format!("{period} is not positive"),
                    ));
                }
                if last - first >= period {
                    return Err(invalid(
                        "flow grid: period",
                        format!(
                            "nodes span {} which is not less than the period {period}",
                            last - first
                        ),
                    ));
                }
            }
        }
        Ok(Self {
            positions,
            topology,
        })
    }

    /// `n` equally spaced interior nodes of a line `[a, b]` with zero values at both ends
    /// (the fixed string of Ribaric (4.1): `h = L/(n+1)`).
    pub fn uniform_fixed(a: f64, b: f64, n: usize) -> Result<Self, FlowError> {
        if n == 0 || a.is_nan() || b.is_nan() || b <= a {
            return Err(invalid(
                "flow grid",
                format!("need n > 0 and b > a (n = {n}, a = {a}, b = {b})"),
            ));
        }
        let h = (b - a) / (n + 1) as f64;
        let pos = (1..=n).map(|j| a + j as f64 * h).collect();
        Self::new(
            pos,
            Topology::Open {
                start: End::Zero(a),
                end: End::Zero(b),
            },
        )
    }

    /// `n` equally spaced nodes on a closed loop of the given period, starting at `s0`.
    pub fn uniform_closed(s0: f64, period: f64, n: usize) -> Result<Self, FlowError> {
        if n == 0 {
            return Err(invalid("flow grid", "no nodes"));
        }
        let h = period / n as f64;
        let pos = (0..n).map(|j| s0 + j as f64 * h).collect();
        Self::new(pos, Topology::Closed { period })
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether the grid has no nodes (never true for a constructed grid).
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Node positions \[m or rad\].
    pub fn positions(&self) -> &[f64] {
        &self.positions
    }

    /// Topology.
    pub fn topology(&self) -> Topology {
        self.topology
    }

    /// Whether the grid is closed (periodic).
    pub fn is_closed(&self) -> bool {
        matches!(self.topology, Topology::Closed { .. })
    }

    /// Uniform spacing `h` if all gaps (including the gaps to zero-value ends and the wrap-around
    /// gap of a closed grid) agree to a relative tolerance `rel_tol`; `None` otherwise.
    pub fn uniform_spacing(&self, rel_tol: f64) -> Option<f64> {
        let mut gaps = Vec::with_capacity(self.len() + 1);
        match self.topology {
            Topology::Open { start, end } => {
                if let End::Zero(a) = start {
                    gaps.push(self.positions[0] - a);
                }
                gaps.extend(self.positions.windows(2).map(|w| w[1] - w[0]));
                if let End::Zero(b) = end {
                    gaps.push(b - self.positions[self.len() - 1]);
                }
            }
            Topology::Closed { period } => {
                gaps.extend(self.positions.windows(2).map(|w| w[1] - w[0]));
                gaps.push(self.positions[0] + period - self.positions[self.len() - 1]);
            }
        }
        let h = gaps.iter().sum::<f64>() / gaps.len() as f64;
        gaps.iter()
            .all(|g| (g - h).abs() <= rel_tol * h)
            .then_some(h)
    }

    /// The two nearest neighbours of node `j` (wrapping around on a closed grid; a zero-value end
    /// or nothing at the ends of an open grid), as used by the 3-point stencils of Ribaric (A.1).
    pub fn neighbours(&self, j: usize) -> Neighbours {
        let n = self.len();
        let s = self.positions[j];
        let (left, right) = match self.topology {
            Topology::Open { start, end } => {
                let left = if j > 0 {
                    Node::Value(j - 1, self.positions[j - 1])
                } else {
                    match start {
                        End::Zero(a) => Node::Zero(a),
                        End::Free => Node::None,
                    }
                };
                let right = if j + 1 < n {
                    Node::Value(j + 1, self.positions[j + 1])
                } else {
                    match end {
                        End::Zero(b) => Node::Zero(b),
                        End::Free => Node::None,
                    }
                };
                (left, right)
            }
            Topology::Closed { period } => {
                if n < 3 {
                    (Node::None, Node::None)
                } else {
                    let l = if j == 0 { n - 1 } else { j - 1 };
                    let r = if j + 1 == n { 0 } else { j + 1 };
                    let sl = if j == 0 {
                        self.positions[l] - period
                    } else {
                        self.positions[l]
                    };
                    let sr = if j + 1 == n {
                        self.positions[r] + period
                    } else {
                        self.positions[r]
                    };
                    (Node::Value(l, sl), Node::Value(r, sr))
                }
            }
        };
        Neighbours { s, left, right }
    }
}

/// A neighbour of a node in a stencil.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Node {
    /// A grid node: index and (unwrapped) position.
    Value(usize, f64),
    /// A known zero value at a position (fixed end).
    Zero(f64),
    /// No neighbour (free end).
    None,
}

/// The two nearest neighbours of a node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbours {
    /// Position of the node itself.
    pub s: f64,
    /// Left neighbour.
    pub left: Node,
    /// Right neighbour.
    pub right: Node,
}

impl Node {
    /// Position of the neighbour, if any.
    pub fn position(&self) -> Option<f64> {
        match *self {
            Node::Value(_, s) | Node::Zero(s) => Some(s),
            Node::None => None,
        }
    }
}

/// Rejects a grid with fewer than `min` nodes for `what`.
pub(crate) fn require_nodes(grid: &FlowGrid, min: usize, what: &str) -> Result<(), FlowError> {
    if grid.len() < min {
        Err(invalid(
            what,
            format!("needs at least {min} nodes, the grid has {}", grid.len()),
        ))
    } else {
        Ok(())
    }
}
