//! Surrogate 3D truck-tire carcass: a hexahedral mesh revolved from a parametric cross-section.
//!
//! Stands in for the confidential >60 000-DOF ABAQUS truck-tire model of Ribaric §8.1 (seed
//! note T1: geometry and material unpublished). Cross-section (radial distance ρ, axial y):
//! the carcass mid-line is the upper part of a super-ellipse (exponent 4, "boxy" like a tire)
//! centred at `ρ_c = R_rim + 0.35 H` (H = section height), cut at the rim radius, resampled to
//! equal arc length; the wall is offset ±t/2 along the mid-line normal with the thickness
//! blending from the sidewall value to the tread value over the crown (`w = max(0, sin φ)⁴`).
//! Zones: `bead` (the first and last `bead_elements` mid-line elements), `tread` (w ≥ 0.5),
//! `sidewall` (the rest). The section is revolved about the y axis:
//! `x = ρ sin θ, z = ρ cos θ` (θ = 0 at the top, θ = π at the road contact).
//!
//! Inflation prestress (thin-membrane estimate, per element, for the geometric stiffness):
//! meridional membrane force `N_s = p H/2`, hoop force `N_θ = p H/2` in the sidewall and
//! `N_θ = p R_o` in the tread (belt), divided by the local wall thickness; a documented
//! engineering approximation, not the seed's nonlinear ABAQUS inflation state.
//!
//! Cord reinforcement ([`TireConfig::belt`], [`TireConfig::carcass`]): smeared uniaxial fibre
//! families ([`Fibre`], ABAQUS `*REBAR`-like) on top of the zone materials: a circumferential
//! steel belt (direction `e_θ` at the element centre) in the tread zone (all layers, or only
//! the outer layer), and radial carcass cords (direction: the section mid-line tangent `e_s`,
//! meridional) in the sidewall and tread zones. The bead zone gets none. The default tire has
//! steel carcass cords and no separate belt layer (see [`TireConfig::default`]).

use crate::FeError;
use crate::element::{Elastic, Fibre, Hex8, Hex8Integration};
use crate::mesh::{Cell, CellKind, Mesh};
use crate::model::FeModel;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Tire generator parameters (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct TireConfig {
    /// Rim (bead seat) diameter \[m\].
    pub rim_diameter: f64,
    /// Outer (tread surface) diameter \[m\].
    pub outer_diameter: f64,
    /// Section width \[m\].
    pub width: f64,
    /// Tread (crown) wall thickness \[m\].
    pub tread_thickness: f64,
    /// Sidewall thickness \[m\].
    pub sidewall_thickness: f64,
    /// Elements around the circumference.
    pub circumferential_divisions: usize,
    /// Elements along the cross-section mid-line (bead to bead).
    pub section_divisions: usize,
    /// Elements through the wall thickness.
    pub thickness_divisions: usize,
    /// Mid-line elements at each end belonging to the bead zone.
    pub bead_elements: usize,
    /// Tread zone material.
    pub tread: Elastic,
    /// Sidewall zone material.
    pub sidewall: Elastic,
    /// Bead zone material.
    pub bead: Elastic,
    /// Inflation pressure p \[Pa\] for the prestress (0 = none).
    pub inflation_pressure: f64,
    /// Stiffness integration rule.
    pub integration: Hex8Integration,
    /// Half angle \[deg\] of the `contact_patch` node set around θ = π (bottom).
    pub patch_half_angle_deg: f64,
    /// Circumferential belt cords in the tread zone (direction `e_θ`); `None` (default) = none
    /// (a layer with `modulus = 0` is none as well).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub belt: Option<CordLayer>,
    /// Radial (meridional) carcass cords in the sidewall and tread zones (direction: the
    /// section mid-line tangent). Default: steel cords, `E_f φ` = 5 GPa with their mass
    /// (196 kg/m³). In a TOML file the default layer is switched off with `modulus = 0`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub carcass: Option<CordLayer>,
}

/// A smeared cord family of the generated tire (see [`Fibre`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CordLayer {
    /// Smeared cord modulus `E_f φ` \[Pa\] (cord Young's modulus × cord volume fraction of the
    /// reinforced elements), e.g. steel 200 GPa × 10 % = 20 GPa.
    pub modulus: f64,
    /// Smeared cord density `ρ_f φ` \[kg/m³\] added to the zone density (default 0: the zone
    /// densities are already homogenised rubber/cord values).
    #[serde(default)]
    pub density: f64,
    /// Only the outermost element layer through the thickness (`true`) or all layers (`false`,
    /// default).
    #[serde(default)]
    pub outer_layer_only: bool,
    /// Cord angle α \[deg\] from the layer's main direction (belt: `e_θ`, carcass: `e_s`) towards
    /// the other in-surface direction. 0 (default): one family along the main direction; α ≠ 0:
    /// two crossed families at ±α (like a pair of belt plies), each with half the modulus and
    /// density.
    #[serde(default)]
    pub angle_deg: f64,
}

impl mbd_core::Validate for CordLayer {
    /// `modulus, density ≥ 0`, `|angle_deg| ≤ 90`.
    fn validate(&self) -> Result<(), InvalidField> {
        check::non_negative("modulus", self.modulus, "Pa")?;
        check::non_negative("density", self.density, "kg/m³")?;
        check::within("angle_deg", self.angle_deg, -90.0, 90.0, "deg")
    }
}

impl CordLayer {
    /// The fibre families of this layer with main direction `p` and in-surface direction `q`
    /// (both unit, orthogonal): `cos α p ± sin α q`.
    fn fibres(&self, p: [f64; 3], q: [f64; 3]) -> Result<Vec<Fibre>, FeError> {
        if self.angle_deg == 0.0 {
            return Ok(vec![Fibre::new(p, self.modulus, self.density)?]);
        }
        let (s, c) = self.angle_deg.to_radians().sin_cos();
        [1.0, -1.0]
            .iter()
            .map(|sg| {
                let a = std::array::from_fn(|i| c * p[i] + sg * s * q[i]);
                Fibre::new(a, 0.5 * self.modulus, 0.5 * self.density)
            })
            .collect()
    }
}

impl Default for TireConfig {
    /// A 295/80 R22.5-class truck tire (rim 22.5 in), inflation 38 psi = 262 kPa (Ribaric
    /// §8.1 test): 63 936 DOFs (≥ 60 000 as the seed's model). Rubber zones (tread 50 MPa,
    /// sidewall 25 MPa, homogenised with the non-carcass reinforcement) and steel carcass
    /// cords (`E_f φ` = 200 GPa × 2.5 % = 5 GPa, `ρ_f φ` = 7850 kg/m³ × 2.5 % = 196 kg/m³).
    ///
    /// The cords are what give the tire a spectrum like Ribaric's (§8.2: 50 free-node modes
    /// reach 240 Hz): an isotropic tire stiff enough in the sidewalls to thin its spectrum
    /// lifts the lowest modes out of the realistic range (BENCHMARKS.md, "tire": 95 modes
    /// below 240 Hz for the isotropic tire of earlier versions, 49 with the cords; rim-fixed
    /// 5th mode 64.2 Hz as Ribaric's, loaded vertical mode 75.9 Hz on the drum).
    fn default() -> Self {
        Self {
            rim_diameter: 0.5715,
            outer_diameter: 1.044,
            width: 0.295,
            tread_thickness: 0.022,
            sidewall_thickness: 0.012,
            circumferential_divisions: 192,
            section_divisions: 36,
            thickness_divisions: 2,
            bead_elements: 2,
            tread: Elastic {
                young: 50e6,
                poisson: 0.45,
                density: 1500.0,
            },
            sidewall: Elastic {
                young: 25e6,
                poisson: 0.45,
                density: 1200.0,
            },
            bead: Elastic {
                young: 1.0e9,
                poisson: 0.3,
                density: 3000.0,
            },
            inflation_pressure: 262e3,
            integration: Hex8Integration::SelectiveReduced,
            patch_half_angle_deg: 8.0,
            belt: None,
            carcass: Some(CordLayer {
                modulus: 5e9,
                density: 196.0,
                outer_layer_only: false,
                angle_deg: 0.0,
            }),
        }
    }
}

/// Most hexahedra a generated tire may have (`circumferential × section × thickness
/// divisions`): 18 times the default tire (13 824). Each element adds 576 stiffness entries to
/// the assembly, so the ceiling keeps the assembly below about 4 GB; a larger count is refused
/// before anything is allocated.
pub const MAX_TIRE_ELEMENTS: usize = 250_000;

impl mbd_core::config::PartialRules for TireConfig {}

impl mbd_core::Validate for TireConfig {
    /// Every field, the first offending one named by its path (`tread.young`,
    /// `circumferential_divisions`): positive dimensions with room for the walls, materials
    /// ([`Elastic`]), cord layers, non-negative pressure, a patch half angle in \[0, 180\]°, mesh
    /// divisions at least 8 × 4 × 1 and at most [`MAX_TIRE_ELEMENTS`] elements in all.
    fn validate(&self) -> Result<(), InvalidField> {
        for (zone, m) in [
            ("tread", &self.tread),
            ("sidewall", &self.sidewall),
            ("bead", &self.bead),
        ] {
            m.validate_within(zone)?;
        }
        if let Some(b) = &self.belt {
            b.validate_within("belt")?;
        }
        if let Some(c) = &self.carcass {
            c.validate_within("carcass")?;
        }
        check::positive("rim_diameter", self.rim_diameter, "m")?;
        check::positive("outer_diameter", self.outer_diameter, "m")?;
        check::positive("width", self.width, "m")?;
        check::positive("tread_thickness", self.tread_thickness, "m")?;
        check::positive("sidewall_thickness", self.sidewall_thickness, "m")?;
        check::non_negative("inflation_pressure", self.inflation_pressure, "Pa")?;
        check::within(
            "patch_half_angle_deg",
            self.patch_half_angle_deg,
            0.0,
            180.0,
            "deg",
        )?;
        if self.outer_diameter <= self.rim_diameter + 2.0 * self.tread_thickness {
            return Err(InvalidField::new(
                "outer_diameter",
                format!(
                    "must exceed rim_diameter + 2·tread_thickness = {} m, got {} m",
                    check::show(self.rim_diameter + 2.0 * self.tread_thickness),
                    check::show(self.outer_diameter)
                ),
            ));
        }
        if self.width <= 2.0 * self.sidewall_thickness {
            return Err(InvalidField::new(
                "width",
                format!(
                    "must exceed 2·sidewall_thickness = {} m, got {} m",
                    check::show(2.0 * self.sidewall_thickness),
                    check::show(self.width)
                ),
            ));
        }
        let max = MAX_TIRE_ELEMENTS;
        check::size(
            "circumferential_divisions",
            self.circumferential_divisions,
            8,
            max,
        )?;
        check::size("section_divisions", self.section_divisions, 4, max)?;
        check::size("thickness_divisions", self.thickness_divisions, 1, max)?;
        let max = mbd_core::validate::limits::ceiling_count(max);
        // each factor is at most 2.5·10⁸ (the raised ceiling), so the product fits in a u128
        let elements = self.circumferential_divisions as u128
            * self.section_divisions as u128
            * self.thickness_divisions as u128;
        if elements > max as u128 {
            return Err(InvalidField::new(
                "circumferential_divisions",
                format!(
                    "{} × {} × {} divisions (circumferential × section × thickness) are {elements} \
                     elements, more than the {max} a generated tire may have{}",
                    self.circumferential_divisions,
                    self.section_divisions,
                    self.thickness_divisions,
                    mbd_core::validate::limits::raise_hint()
                ),
            ));
        }
        if self.bead_elements >= self.section_divisions / 2 + self.section_divisions % 2 {
            return Err(InvalidField::new(
                "bead_elements",
                format!(
                    "must be < section_divisions / 2 = {}, got {}",
                    self.section_divisions as f64 / 2.0,
                    self.bead_elements
                ),
            ));
        }
        Ok(())
    }
}

/// Material zone of a tire element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TireZone {
    /// Bead (rim contact).
    Bead,
    /// Sidewall.
    Sidewall,
    /// Tread / crown.
    Tread,
}

/// A generated tire: the FE model plus per-element zones and the cross-section mid-line.
#[derive(Debug)]
pub struct Tire {
    /// Mesh and elements (DOFs u, v, w per node).
    pub model: FeModel,
    /// Zone of each element (same order as `model.elements`).
    pub zones: Vec<TireZone>,
    /// Cord families of each element (same order; empty without cords), as given to the
    /// element ([`Hex8::fibres`]).
    pub fibres: Vec<Vec<Fibre>>,
}

struct Section {
    /// (ρ, y) of each mid-line point, equal arc length.
    mid: Vec<[f64; 2]>,
    /// Unit outward normal (ρ, y) at each point.
    normal: Vec<[f64; 2]>,
    /// Crown weight w ∈ \[0, 1\] at each point.
    crown: Vec<f64>,
}

fn section(cfg: &TireConfig) -> Section {
    let r_rim = cfg.rim_diameter / 2.0;
    let r_o = cfg.outer_diameter / 2.0;
    let h = r_o - r_rim;
    let rho_c = r_rim + 0.35 * h;
    let a_rho = r_o - cfg.tread_thickness / 2.0 - rho_c;
    let a_y = cfg.width / 2.0 - cfg.sidewall_thickness / 2.0;
    let sp = |x: f64| x.signum() * x.abs().sqrt(); // exponent 2/p with p = 4
    let curve = |phi: f64| [rho_c + a_rho * sp(phi.sin()), a_y * sp(phi.cos())];
    // φ at the rim cut: ρ = R_rim ⇒ sp(sin φ) = (R_rim − ρ_c)/a_rho
    let s0 = ((r_rim - rho_c) / a_rho).clamp(-1.0, 0.0);
    let phi0 = -(s0 * s0).asin(); // sin φ0 = −s0², φ0 < 0
    let (pa, pb) = (PI - phi0, phi0); // left bead → top → right bead
    // dense polyline, then resample at equal arc length
    let nd = 4000;
    let dense: Vec<[f64; 2]> = (0..=nd)
        .map(|i| curve(pa + (pb - pa) * i as f64 / nd as f64))
        .collect();
    let mut cum = vec![0.0];
    for w in dense.windows(2) {
        let d = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
        cum.push(cum.last().copied().unwrap_or(0.0) + d);
    }
    let total = *cum.last().unwrap_or(&1.0);
    let ns = cfg.section_divisions;
    let mut mid = Vec::with_capacity(ns + 1);
    let mut crown = Vec::with_capacity(ns + 1);
    let mut seg = 0usize;
    for i in 0..=ns {
        let target = total * i as f64 / ns as f64;
        while seg + 1 < cum.len() - 1 && cum[seg + 1] < target {
            seg += 1;
        }
        let t = ((target - cum[seg]) / (cum[seg + 1] - cum[seg])).clamp(0.0, 1.0);
        let p = [
            dense[seg][0] + t * (dense[seg + 1][0] - dense[seg][0]),
            dense[seg][1] + t * (dense[seg + 1][1] - dense[seg][1]),
        ];
        mid.push(p);
        let phi = pa + (pb - pa) * (seg as f64 + t) / nd as f64;
        crown.push(phi.sin().max(0.0).powi(4));
    }
    // outward normal: rotate the tangent (dρ, dy) so that it points away from (ρ_c, 0)
    let mut normal = Vec::with_capacity(ns + 1);
    for i in 0..=ns {
        let (a, b) = (mid[i.saturating_sub(1)], mid[(i + 1).min(ns)]);
        let t = [b[0] - a[0], b[1] - a[1]];
        let l = (t[0] * t[0] + t[1] * t[1]).sqrt();
        let mut n = [-t[1] / l, t[0] / l];
        let out = [mid[i][0] - rho_c, mid[i][1]];
        if n[0] * out[0] + n[1] * out[1] < 0.0 {
            n = [-n[0], -n[1]];
        }
        normal.push(n);
    }
    Section { mid, normal, crown }
}

/// Generate the tire. Node sets: `rim` (all nodes of the first and last mid-line stations,
/// bonded to the wheel), `tread_outer` (outer-surface nodes of the tread zone),
/// `contact_patch` (the part of `tread_outer` within ±`patch_half_angle_deg` of θ = π),
/// `all`.
pub fn tire(cfg: &TireConfig) -> Result<Tire, FeError> {
    cfg.validate()?;
    let sec = section(cfg);
    let (ns, nt, nc) = (
        cfg.section_divisions,
        cfg.thickness_divisions,
        cfg.circumferential_divisions,
    );
    let thick = |i: usize| {
        cfg.sidewall_thickness + (cfg.tread_thickness - cfg.sidewall_thickness) * sec.crown[i]
    };
    let id = |j: usize, i: usize, k: usize| (j % nc) * (ns + 1) * (nt + 1) + i * (nt + 1) + k;
    let mut mesh = Mesh::new(3);
    for j in 0..nc {
        let th = 2.0 * PI * j as f64 / nc as f64;
        for i in 0..=ns {
            for k in 0..=nt {
                let off = (-0.5 + k as f64 / nt as f64) * thick(i);
                let rho = sec.mid[i][0] + off * sec.normal[i][0];
                let y = sec.mid[i][1] + off * sec.normal[i][1];
                mesh.add_node([rho * th.sin(), y, rho * th.cos()]);
            }
        }
    }
    let h_sec = (cfg.outer_diameter - cfg.rim_diameter) / 2.0;
    let p = cfg.inflation_pressure;
    let mut els = Vec::with_capacity(nc * ns * nt);
    let mut zones = Vec::with_capacity(nc * ns * nt);
    let mut fibres = Vec::with_capacity(nc * ns * nt);
    let mut flip: Option<bool> = None;
    for j in 0..nc {
        for i in 0..ns {
            let w = 0.5 * (sec.crown[i] + sec.crown[i + 1]);
            let zone = if i < cfg.bead_elements || i >= ns - cfg.bead_elements {
                TireZone::Bead
            } else if w >= 0.5 {
                TireZone::Tread
            } else {
                TireZone::Sidewall
            };
            let mat = match zone {
                TireZone::Bead => cfg.bead,
                TireZone::Sidewall => cfg.sidewall,
                TireZone::Tread => cfg.tread,
            };
            // membrane prestress in (meridional s, hoop θ) directions at the element centre
            let t_loc = 0.5 * (thick(i) + thick(i + 1));
            let n_s = p * h_sec / 2.0;
            let n_th = if zone == TireZone::Tread {
                p * cfg.outer_diameter / 2.0
            } else {
                p * h_sec / 2.0
            };
            let thc = 2.0 * PI * (j as f64 + 0.5) / nc as f64;
            let ds = [
                sec.mid[i + 1][0] - sec.mid[i][0],
                sec.mid[i + 1][1] - sec.mid[i][1],
            ];
            let dl = (ds[0] * ds[0] + ds[1] * ds[1]).sqrt();
            let s_vec = [ds[0] / dl * thc.sin(), ds[1] / dl, ds[0] / dl * thc.cos()];
            let e_th = [thc.cos(), 0.0, -thc.sin()];
            let (ss, st) = (n_s / t_loc, n_th / t_loc);
            let mut sigma = [[0.0; 3]; 3];
            for a in 0..3 {
                for b in 0..3 {
                    sigma[a][b] = ss * s_vec[a] * s_vec[b] + st * e_th[a] * e_th[b];
                }
            }
            let prestress = if p > 0.0 { Some(sigma) } else { None };
            // cord families of this element (belt: e_θ in the tread; carcass: e_s outside the
            // beads), per layer k
            let cords = |k: usize| -> Result<Vec<Fibre>, FeError> {
                let mut f = Vec::new();
                let layer_ok = |c: &CordLayer| !c.outer_layer_only || k + 1 == nt;
                let belt = cfg.belt.filter(|c| layer_ok(c) && zone == TireZone::Tread);
                if let Some(c) = belt {
                    f.extend(c.fibres(e_th, s_vec)?);
                }
                let carcass = cfg
                    .carcass
                    .filter(|c| layer_ok(c) && zone != TireZone::Bead);
                if let Some(c) = carcass {
                    f.extend(c.fibres(s_vec, e_th)?);
                }
                Ok(f)
            };
            for k in 0..nt {
                let fib = cords(k)?;
                let base = [
                    id(j, i, k),
                    id(j, i + 1, k),
                    id(j, i + 1, k + 1),
                    id(j, i, k + 1),
                ];
                let next = [
                    id(j + 1, i, k),
                    id(j + 1, i + 1, k),
                    id(j + 1, i + 1, k + 1),
                    id(j + 1, i, k + 1),
                ];
                let build = |f: bool| -> Result<Hex8, FeError> {
                    let (lo, hi) = if f { (next, base) } else { (base, next) };
                    let nodes = [lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]];
                    let mut dofs = [0usize; 24];
                    let mut x = [[0.0; 3]; 8];
                    for (a, &nd) in nodes.iter().enumerate() {
                        x[a] = mesh.nodes[nd];
                        for d in 0..3 {
                            dofs[3 * a + d] = 3 * nd + d;
                        }
                    }
                    Hex8::new(dofs, x, mat, cfg.integration, prestress)?.with_fibres(fib.clone())
                };
                let el = match flip {
                    Some(f) => build(f)?,
                    None => match build(false) {
                        Ok(e) => {
                            flip = Some(false);
                            e
                        }
                        Err(_) => {
                            flip = Some(true);
                            build(true)?
                        }
                    },
                };
                let nodes = el.dofs.iter().step_by(3).map(|d| d / 3).collect();
                mesh.cells.push(Cell {
                    kind: CellKind::Hexahedron,
                    nodes,
                });
                els.push(el);
                zones.push(zone);
                fibres.push(fib);
            }
        }
    }
    let mut rim = Vec::new();
    let mut tread_outer = Vec::new();
    let mut patch = Vec::new();
    let half = cfg.patch_half_angle_deg.to_radians();
    for j in 0..nc {
        let th = 2.0 * PI * j as f64 / nc as f64;
        for k in 0..=nt {
            rim.push(id(j, 0, k));
            rim.push(id(j, ns, k));
        }
        for i in 0..=ns {
            if sec.crown[i] >= 0.5 {
                let n = id(j, i, nt);
                tread_outer.push(n);
                if (th - PI).abs() <= half + 1e-12 {
                    patch.push(n);
                }
            }
        }
    }
    mesh.set_node_set("rim", rim)?;
    mesh.set_node_set("tread_outer", tread_outer)?;
    mesh.set_node_set("contact_patch", patch)?;
    mesh.set_node_set("all", (0..mesh.n_nodes()).collect())?;
    let mut model = FeModel::new(mesh);
    for e in els {
        model.push(e);
    }
    Ok(Tire {
        model,
        zones,
        fibres,
    })
}
