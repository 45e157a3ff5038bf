//! The reduced-tire file: versioned JSON whose body carries a SHA-256 checksum,
//!
//! ```text
//!   {"format":"flowmbd-reduced-tire","version":4,"checksum":"sha256:<hex>","tire":{…}}
//! ```
//!
//! the checksum being that of the bytes of the `tire` value as they stand in the file. A file
//! changed after it was written (a doubled `k`, a truncated or damaged copy) is refused on load
//! with the reason; the JSON numbers round-trip exactly (serde_json's `float_roundtrip`), so a
//! loaded tire is bit-identical to the saved one. Files are read only when they are regular
//! files within [`MAX_REDUCED_TIRE_BYTES`] and written to a temporary file renamed on
//! completion.

use super::{ReducedTire, TreadBasis, VizBasis};
use crate::error::{TireError, invalid};
use crate::files::{read_text_bounded, sha256_hex, write_atomic};
use faer::Mat;
use flowing::derivative::DerivativeMethod;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::path::Path;

/// File format name of a saved reduced tire.
pub const FORMAT: &str = "flowmbd-reduced-tire";
/// Current file format version (2: the momentum projections `p_e`, `p_e1`, `p_e2`, `p_s`; 3:
/// the body in `tire` with its SHA-256 `checksum`, and `code_version`; 4: the upwind transport
/// rows `tc_theta_upwind`).
pub const VERSION: u32 = 4;
/// Largest reduced-tire file read \[bytes\] (1 GiB; the default 341-DOF tire's file is 65 MB):
/// a documented ceiling, raised 1000-fold by `--allow-large`
/// ([`mbd_core::validate::limits`]).
pub const MAX_REDUCED_TIRE_BYTES: u64 = 1 << 30;

/// The head of a file: read first, so that another format or version is named as such (a
/// version-2 file has its fields at the top level and no checksum).
#[derive(Deserialize)]
struct Envelope<'a> {
    #[serde(default)]
    format: Option<String>,
    #[serde(default)]
    version: Option<u64>,
    #[serde(default)]
    checksum: Option<String>,
    #[serde(borrow, default)]
    tire: Option<&'a RawValue>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct TreadFile {
    nodes: Vec<usize>,
    theta: Vec<f64>,
    ring: Vec<usize>,
    rows: Dense,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct VizFile {
    nodes: Vec<usize>,
    positions: Vec<[f64; 3]>,
    lines: Vec<[usize; 2]>,
    rows: Dense,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Dense {
    rows: usize,
    cols: usize,
    data: Vec<f64>,
}

impl Dense {
    fn from(m: &Mat<f64>) -> Self {
        let mut data = Vec::with_capacity(m.nrows() * m.ncols());
        for j in 0..m.ncols() {
            for i in 0..m.nrows() {
                data.push(m[(i, j)]);
            }
        }
        Self {
            rows: m.nrows(),
            cols: m.ncols(),
            data,
        }
    }
    fn to(&self, name: &str, rows: usize, cols: usize) -> Result<Mat<f64>, TireError> {
        if self.rows != rows || self.cols != cols || self.data.len() != rows * cols {
            return Err(invalid(
                format!("reduced tire field `{name}`"),
                format!(
                    "is {}×{} with {} values, expected {rows}×{cols}",
                    self.rows,
                    self.cols,
                    self.data.len()
                ),
            ));
        }
        Ok(Mat::from_fn(rows, cols, |i, j| self.data[j * rows + i]))
    }
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Body {
    n_free_modes: usize,
    contact_nodes: Vec<usize>,
    contact_positions: Vec<[f64; 3]>,
    free_mode_hz: Vec<f64>,
    contact_mode_hz: Vec<f64>,
    tire_mass: f64,
    rim_mass: f64,
    rim_spin_inertia: f64,
    outer_radius: f64,
    derivative: DerivativeMethod,
    m: Dense,
    k: Dense,
    g1: Dense,
    g2: Dense,
    k1: Dense,
    m_theta: Vec<f64>,
    c_s: Vec<f64>,
    kr: Dense,
    kr1: Dense,
    kt: Dense,
    kt1: Dense,
    tc: Dense,
    tc_theta: Dense,
    tc_theta_upwind: [Dense; 2],
    p_e: Dense,
    p_e1: Dense,
    p_e2: Dense,
    p_s: [[f64; 3]; 2],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    viz: Option<VizFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tread: Option<TreadFile>,
    source: String,
    code_version: String,
}

impl ReducedTire {
    /// Serialise to the versioned JSON text (module documentation: the body and its checksum).
    pub fn to_json(&self) -> Result<String, TireError> {
        let body = Body {
            n_free_modes: self.n_free_modes,
            contact_nodes: self.contact_nodes.clone(),
            contact_positions: self.contact_positions.clone(),
            free_mode_hz: self.free_mode_hz.clone(),
            contact_mode_hz: self.contact_mode_hz.clone(),
            tire_mass: self.tire_mass,
            rim_mass: self.rim_mass,
            rim_spin_inertia: self.rim_spin_inertia,
            outer_radius: self.outer_radius,
            derivative: self.derivative,
            m: Dense::from(&self.m),
            k: Dense::from(&self.k),
            g1: Dense::from(&self.g1),
            g2: Dense::from(&self.g2),
            k1: Dense::from(&self.k1),
            m_theta: self.m_theta.clone(),
            c_s: self.c_s.clone(),
            kr: Dense::from(&self.kr),
            kr1: Dense::from(&self.kr1),
            kt: Dense::from(&self.kt),
            kt1: Dense::from(&self.kt1),
            tc: Dense::from(&self.tc),
            tc_theta: Dense::from(&self.tc_theta),
            tc_theta_upwind: [
                Dense::from(&self.tc_theta_upwind[0]),
                Dense::from(&self.tc_theta_upwind[1]),
            ],
            p_e: Dense::from(&self.p_e),
            p_e1: Dense::from(&self.p_e1),
            p_e2: Dense::from(&self.p_e2),
            p_s: self.p_s,
            viz: self.viz.as_ref().map(|v| VizFile {
                nodes: v.nodes.clone(),
                positions: v.positions.clone(),
                lines: v.lines.clone(),
                rows: Dense::from(&v.rows),
            }),
            tread: self.tread.as_ref().map(|t| TreadFile {
                nodes: t.nodes.clone(),
                theta: t.theta.clone(),
                ring: t.ring.clone(),
                rows: Dense::from(&t.rows),
            }),
            source: self.source.clone(),
            code_version: self.code_version.clone(),
        };
        let body =
            serde_json::to_string(&body).map_err(|e| invalid("reduced tire", e.to_string()))?;
        Ok(format!(
            "{{\"format\":\"{FORMAT}\",\"version\":{VERSION},\"checksum\":\"sha256:{}\",\"tire\":{body}}}",
            sha256_hex(body.as_bytes())
        ))
    }

    /// Parse the versioned JSON text; `origin` names the source in errors. Refused: another
    /// format or version, a missing or wrong checksum (the body changed after it was written),
    /// inconsistent sizes.
    pub fn from_json(text: &str, origin: &str) -> Result<Self, TireError> {
        let file_err = |reason: String| TireError::File {
            path: origin.to_string(),
            reason,
        };
        let head: Envelope<'_> =
            serde_json::from_str(text).map_err(|e| file_err(format!("not JSON: {e}")))?;
        let format = head.format.as_deref().unwrap_or("");
        if format != FORMAT {
            return Err(file_err(format!(
                "field `format` is `{format}`, expected `{FORMAT}`"
            )));
        }
        let version = head.version.unwrap_or(0);
        if version != u64::from(VERSION) {
            return Err(file_err(format!(
                "field `version` is {version}; this build reads version {VERSION} (reduce the \
                 tire again)"
            )));
        }
        let (Some(checksum), Some(raw)) = (head.checksum, head.tire) else {
            return Err(file_err("has no `checksum` or no `tire` body".into()));
        };
        let actual = format!("sha256:{}", sha256_hex(raw.get().as_bytes()));
        if checksum != actual {
            return Err(file_err(format!(
                "checksum mismatch: the file was changed or damaged after it was written \
                 (stored {checksum}, content {actual})"
            )));
        }
        let f: Body = serde_json::from_str(raw.get()).map_err(|e| file_err(e.to_string()))?;
        let nc = f.contact_nodes.len();
        let nz = f.m.rows;
        if nz != f.n_free_modes + 3 * nc {
            return Err(file_err(format!(
                "{nz} coordinates but n_free_modes + 3·contact nodes = {}",
                f.n_free_modes + 3 * nc
            )));
        }
        if f.contact_positions.len() != nc || f.m_theta.len() != nz || f.c_s.len() != nz {
            return Err(file_err("inconsistent vector lengths".into()));
        }
        let sq = |d: &Dense, n: &str| d.to(n, nz, nz);
        let viz = match f.viz {
            None => None,
            Some(v) => {
                let nv = v.nodes.len();
                if v.positions.len() != nv || v.lines.iter().flatten().any(|&i| i >= nv) {
                    return Err(file_err("inconsistent visualisation basis `viz`".into()));
                }
                Some(VizBasis {
                    rows: v.rows.to("viz.rows", 3 * nv, nz)?,
                    nodes: v.nodes,
                    positions: v.positions,
                    lines: v.lines,
                })
            }
        };
        let tread = match f.tread {
            None => None,
            Some(t) => {
                let nt = t.nodes.len();
                if t.theta.len() != nt || t.ring.len() != nt {
                    return Err(file_err("inconsistent tread basis `tread`".into()));
                }
                Some(TreadBasis {
                    rows: t.rows.to("tread.rows", 3 * nt, nz)?,
                    nodes: t.nodes,
                    theta: t.theta,
                    ring: t.ring,
                })
            }
        };
        Ok(Self {
            n_free_modes: f.n_free_modes,
            contact_positions: f.contact_positions,
            free_mode_hz: f.free_mode_hz,
            contact_mode_hz: f.contact_mode_hz,
            tire_mass: f.tire_mass,
            rim_mass: f.rim_mass,
            rim_spin_inertia: f.rim_spin_inertia,
            outer_radius: f.outer_radius,
            derivative: f.derivative,
            m: sq(&f.m, "m")?,
            k: sq(&f.k, "k")?,
            g1: sq(&f.g1, "g1")?,
            g2: sq(&f.g2, "g2")?,
            k1: sq(&f.k1, "k1")?,
            m_theta: f.m_theta,
            c_s: f.c_s,
            kr: f.kr.to("kr", 3, nz)?,
            kr1: f.kr1.to("kr1", 3, nz)?,
            kt: f.kt.to("kt", 3, nz)?,
            kt1: f.kt1.to("kt1", 3, nz)?,
            tc: f.tc.to("tc", 3 * nc, nz)?,
            tc_theta: f.tc_theta.to("tc_theta", 3 * nc, nz)?,
            tc_theta_upwind: [
                f.tc_theta_upwind[0].to("tc_theta_upwind[0]", 3 * nc, nz)?,
                f.tc_theta_upwind[1].to("tc_theta_upwind[1]", 3 * nc, nz)?,
            ],
            p_e: f.p_e.to("p_e", 3, nz)?,
            p_e1: f.p_e1.to("p_e1", 3, nz)?,
            p_e2: f.p_e2.to("p_e2", 3, nz)?,
            p_s: f.p_s,
            viz,
            tread,
            contact_nodes: f.contact_nodes,
            source: f.source,
            code_version: f.code_version,
        })
    }

    /// Save to `path` (JSON, module documentation): written to a temporary file in the same
    /// folder (created if missing) and renamed onto `path` when complete.
    pub fn save(&self, path: &Path) -> Result<(), TireError> {
        let text = self.to_json()?;
        write_atomic(path, text.as_bytes()).map_err(|reason| TireError::File {
            path: path.display().to_string(),
            reason,
        })
    }

    /// Load from `path`: a regular file of at most [`MAX_REDUCED_TIRE_BYTES`] (the ceiling in
    /// force, [`mbd_core::validate::limits::ceiling_count`]), checked before reading.
    pub fn load(path: &Path) -> Result<Self, TireError> {
        let max = mbd_core::validate::limits::ceiling_count(MAX_REDUCED_TIRE_BYTES as usize) as u64;
        let text = read_text_bounded(path, max).map_err(|reason| TireError::File {
            path: path.display().to_string(),
            reason: if reason.contains("ceiling") {
                format!("{reason}{}", mbd_core::validate::limits::raise_hint())
            } else {
                reason
            },
        })?;
        Self::from_json(&text, &path.display().to_string())
    }
}
