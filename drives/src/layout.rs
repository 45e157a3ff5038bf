//! Any belt-drive layout (issue 17 item 4): N pulleys given in TOML (position, radius, wrap
//! side, how each turns), the belt's unstretched length given or computed from a target
//! pre-tension, and an optional automatic tensioner ([`mbd_core::tensioner`]), built into the
//! flowing-material belt model ([`FlowingBelt::with_layout`], the mesh fixed in space along the
//! layout's path: Ribaric's flowing material carried over to any path).
//!
//! Resolving a layout ([`LayoutConfig::resolve`]) is a statics problem solved by hand before
//! any model is built:
//!
//! - without a tensioner the path is fixed; the tension of the mounted belt is
//!   `T0 = EA (L_path / L_belt − 1)` when the belt length `L_belt` is given, else the target
//!   `belt.tension` (and `L_belt = L_path / (1 + T0/EA)`);
//! - with a tensioner, the idler's centre moves on the arm, `c(θ) = p + L(cos θ, sin θ)`, and
//!   so do the path and its length `L_path(θ)`. With equal tension `T` in every span (the
//!   static belt on frictionless pulleys) the arm balances when
//!   `M_s(θ) + T (c − p) × (d_out − d_in) = 0` ([`mbd_core::tensioner`]), with `T` the target
//!   tension or `T(θ) = EA (L_path(θ)/L_belt − 1)` for a given belt length. The root in the
//!   arm's travel is the laid-out arm angle; none is a bad input ("tensioner outside its
//!   travel").
//!
//! Bad input, each naming the pulley or field: overlapping pulleys, a belt too short to wrap
//! the layout (stretch above [`MAX_MOUNTING_STRAIN`]) or too long (slack), a tensioner whose
//! static arm angle lies outside its travel, a wrap angle below [`MIN_WRAP_DEG`].

use contact::friction::FrictionSpec;
use fe_model::generate::belt_path::{BeltPath, PathPulley, Segment, WrapSide};
use flowing::belt::config::{BeltContact, BeltDamping, BeltReduction, BeltSection};
use flowing::belt::nodal::NodalBelt;
use flowing::belt::{ArmModel, BeltDriveConfig, BeltFe, FlowingBelt, PulleyMotion, Signal};
use mbd_core::tensioner::{TensionerSpec, cross};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Most pulleys a layout may have (sizes from input are bounded before anything is built).
pub const MAX_PULLEYS: usize = 12;
/// Smallest wrap angle accepted on any pulley \[deg\] (a belt that barely touches a pulley
/// carries no torque and makes the contact set ill-defined).
pub const MIN_WRAP_DEG: f64 = 10.0;
/// Largest mounting strain `T0/EA` accepted: a belt stretched more than this is too short for
/// the layout (automotive V-ribbed belts are mounted at 0.1–0.5 %).
pub const MAX_MOUNTING_STRAIN: f64 = 0.05;
/// Most belt elements a layout's mesh may have.
pub const MAX_ELEMENTS: usize = 600;

/// How a pulley of the layout turns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum MotionSpec {
    /// Speed prescribed (the crankshaft): `speed` \[rad/s\] in the travel sense.
    Speed {
        /// Speed history (mean schedule plus harmonics).
        speed: Signal,
    },
    /// Free with inertia against a load torque (an accessory): `torque` \[N m\] opposes the
    /// travel sense.
    Load {
        /// Moment of inertia about the axle \[kg m²\].
        inertia: f64,
        /// Load torque history.
        torque: Signal,
    },
    /// Free with inertia and no load (an idler).
    Idler {
        /// Moment of inertia about the axle \[kg m²\].
        inertia: f64,
    },
}

/// One pulley of a layout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayoutPulley {
    /// Name (used in messages and outputs).
    pub name: String,
    /// Centre (x, y) \[m\] (for the tensioner's idler: its installed position, which fixes the
    /// arm length; the arm angle is then solved).
    pub center: [f64; 2],
    /// Radius of the belt line \[m\].
    pub radius: f64,
    /// `inside` (grooved side, pulley inside the loop) or `outside` (back side).
    #[serde(default)]
    pub side: WrapSide,
    /// How it turns.
    pub motion: MotionSpec,
}

impl LayoutPulley {
    /// A pulley named `name` at `center` \[m\] with belt-line radius `radius` \[m\].
    pub fn new(
        name: &str,
        center: [f64; 2],
        radius: f64,
        side: WrapSide,
        motion: MotionSpec,
    ) -> Self {
        Self {
            name: name.into(),
            center,
            radius,
            side,
            motion,
        }
    }
}

/// Target element lengths of the layout's mesh.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LayoutMesh {
    /// Element length on the spans \[m\] (at least 4 elements per span).
    pub span_element: f64,
    /// Element length on the wraps \[m\] (at least 3 elements per wrap).
    pub arc_element: f64,
    /// Extra contact nodes beyond each wrap end, on the spans.
    pub contact_margin_nodes: usize,
}

impl Default for LayoutMesh {
    /// 45 mm on spans and 8.7 mm on wraps: the element lengths of Ribaric §6.1's 56-element
    /// loop; one margin node.
    fn default() -> Self {
        Self {
            span_element: 0.045,
            arc_element: 0.0087,
            contact_margin_nodes: 1,
        }
    }
}

/// A belt drive of any layout (see the module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayoutConfig {
    /// Pulleys in travel order (the loop runs clockwise around the `inside` pulleys).
    pub pulleys: Vec<LayoutPulley>,
    /// Automatic tensioner (its `pulley` indexes `pulleys`).
    #[serde(default)]
    pub tensioner: Option<TensionerSpec>,
    /// Belt section; `tension` is the target pre-tension \[N\] when `belt_length` is not given.
    pub belt: BeltSection,
    /// Unstretched belt length \[m\]; when given, the pre-tension follows from it.
    #[serde(default)]
    pub belt_length: Option<f64>,
    /// Mesh.
    #[serde(default)]
    pub mesh: LayoutMesh,
    /// Contact and friction.
    #[serde(default)]
    pub contact: BeltContact,
    /// Rayleigh damping.
    #[serde(default)]
    pub damping: BeltDamping,
    /// Reduction of the flowing model.
    #[serde(default)]
    pub reduction: BeltReduction,
}

/// A resolved layout: the path of the mounted belt, its tension and the tensioner's arm.
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedLayout {
    /// The belt path (idler at the static arm angle).
    pub path: BeltPath,
    /// Pre-tension of the mounted belt \[N\] (equal in every span at rest).
    pub tension: f64,
    /// Unstretched belt length \[m\].
    pub belt_length: f64,
    /// Tensioner arm `(length, static angle)` \[m, rad\].
    pub arm: Option<(f64, f64)>,
    /// Wrap angle on each pulley \[rad\].
    pub wraps: Vec<f64>,
}

fn path_pulleys(cfg: &LayoutConfig) -> Vec<PathPulley> {
    cfg.pulleys
        .iter()
        .map(|p| PathPulley {
            center: p.center,
            radius: p.radius,
            side: p.side,
        })
        .collect()
}

/// The path over `pulleys`; a failing pair is named by the pulleys' names.
fn build_path(pulleys: &[PathPulley]) -> Result<BeltPath, InvalidField> {
    BeltPath::new(pulleys).map_err(|e| {
        InvalidField::new("pulleys", format!("no open-belt path over the layout: {e}"))
    })
}

/// Moment per unit span tension \[m\] of the belt on the tensioner's idler about the pivot:
/// `(c − p) × (d_out − d_in)`, with `d_in`, `d_out` the travel directions of the spans
/// arriving at and leaving the idler (hand statics of the arm, [`mbd_core::tensioner`]).
pub fn arm_lever(path: &BeltPath, spec: &TensionerSpec) -> f64 {
    let k = spec.pulley;
    let spans = path.spans();
    let d_in = spans.iter().find(|s| s.to == k).map(|s| s.direction);
    let d_out = spans.iter().find(|s| s.from == k).map(|s| s.direction);
    let (Some(di), Some(dout)) = (d_in, d_out) else {
        return f64::NAN;
    };
    let c = path.pulleys()[k].center;
    cross(
        [c[0] - spec.pivot[0], c[1] - spec.pivot[1]],
        [dout[0] - di[0], dout[1] - di[1]],
    )
}

impl LayoutConfig {
    /// The two-pulley config carrying this layout's belt, contact, damping and reduction (its
    /// geometry is not used: [`BeltFe::on_path`]).
    pub fn belt_config(&self, tension: f64) -> BeltDriveConfig {
        let mut c = BeltDriveConfig {
            belt: self.belt,
            contact: self.contact,
            damping: self.damping,
            reduction: self.reduction,
            ..Default::default()
        };
        c.belt.tension = tension;
        c.mesh.contact_margin_nodes = self.mesh.contact_margin_nodes;
        c
    }

    /// Solve the mounted layout (module documentation): path, tension, belt length, arm.
    pub fn resolve(&self) -> Result<ResolvedLayout, InvalidField> {
        let ea = self.belt.ea;
        let mut pulleys = path_pulleys(self);
        let (path, tension, arm) = match &self.tensioner {
            None => {
                let path = build_path(&pulleys)?;
                let t = match self.belt_length {
                    Some(lb) => ea * (path.length() / lb - 1.0),
                    None => self.belt.tension,
                };
                (path, t, None)
            }
            Some(spec) => {
                let (length, _) = spec.arm(pulleys[spec.pulley].center);
                let at = |theta: f64| -> Option<(BeltPath, f64)> {
                    let mut pp = pulleys.clone();
                    pp[spec.pulley].center = spec.center(length, theta).0;
                    let path = BeltPath::new(&pp).ok()?;
                    let t = match self.belt_length {
                        Some(lb) => ea * (path.length() / lb - 1.0),
                        None => self.belt.tension,
                    };
                    Some((path, t))
                };
                let moment = |theta: f64| match at(theta) {
                    Some((path, t)) => t * arm_lever(&path, spec),
                    None => f64::NAN,
                };
                let theta = spec.static_angle(moment);
                if let (None, Some(_)) = (theta, self.belt_length) {
                    // name the belt when it, not the spring, is out of range over the travel
                    let ts: Vec<f64> = spec
                        .travel
                        .iter()
                        .filter_map(|&a| at(a).map(|(_, t)| t))
                        .collect();
                    if !ts.is_empty() && ts.iter().all(|t| t / ea > MAX_MOUNTING_STRAIN) {
                        return Err(InvalidField::new(
                            "belt_length",
                            format!(
                                "too short to wrap the layout: over the tensioner's whole travel the mounting strain exceeds {:.0} %",
                                100.0 * MAX_MOUNTING_STRAIN
                            ),
                        ));
                    }
                    if !ts.is_empty() && ts.iter().all(|&t| t <= 0.0) {
                        return Err(InvalidField::new(
                            "belt_length",
                            "longer than the path over the tensioner's whole travel: the belt would hang slack",
                        ));
                    }
                }
                let theta = theta.ok_or_else(|| {
                    InvalidField::new(
                        "tensioner",
                        format!(
                            "outside its travel: the arm of pulley '{}' finds no static angle in [{:.3}, {:.3}] rad \
                             (spring against the belt's hub force; check preload, belt length or tension)",
                            self.pulleys[spec.pulley].name, spec.travel[0], spec.travel[1]
                        ),
                    )
                })?;
                let (path, t) = at(theta).ok_or_else(|| {
                    InvalidField::new("tensioner", "no open-belt path at the static arm angle")
                })?;
                pulleys[spec.pulley].center = spec.center(length, theta).0;
                (path, t, Some((length, theta)))
            }
        };
        if self.belt_length.is_some() {
            if tension <= 0.0 {
                return Err(InvalidField::new(
                    "belt_length",
                    format!(
                        "longer than the path ({:.4} m): the belt would hang slack",
                        path.length()
                    ),
                ));
            }
            if tension / ea > MAX_MOUNTING_STRAIN {
                return Err(InvalidField::new(
                    "belt_length",
                    format!(
                        "too short to wrap the layout: the path is {:.4} m, a mounting strain of {:.1} % (max {:.0} %)",
                        path.length(),
                        100.0 * tension / ea,
                        100.0 * MAX_MOUNTING_STRAIN
                    ),
                ));
            }
        }
        let wraps: Vec<f64> = (0..pulleys.len())
            .map(|k| path.wrap_angle(k).unwrap_or(0.0))
            .collect();
        for (k, w) in wraps.iter().enumerate() {
            if w.to_degrees() < MIN_WRAP_DEG {
                return Err(InvalidField::new(
                    format!("pulleys[{k}]"),
                    format!(
                        "'{}': wrap angle {:.1}° below {MIN_WRAP_DEG}°",
                        self.pulleys[k].name,
                        w.to_degrees()
                    ),
                ));
            }
        }
        Ok(ResolvedLayout {
            belt_length: path.length() / (1.0 + tension / ea),
            path,
            tension,
            arm,
            wraps,
        })
    }

    /// Element counts per path piece from the target element lengths.
    fn element_counts(&self, path: &BeltPath) -> Vec<usize> {
        path.pieces()
            .iter()
            .map(|p| match p.segment {
                Segment::Span { .. } => ((p.length / self.mesh.span_element).ceil() as usize)
                    .max(2 * self.mesh.contact_margin_nodes + 2)
                    .max(4),
                Segment::Arc { .. } => ((p.length / self.mesh.arc_element).ceil() as usize).max(3),
            })
            .collect()
    }

    /// The flowing-material model of the layout (validated first), with the resolved layout.
    pub fn flowing_model(&self) -> Result<(FlowingBelt, ResolvedLayout), crate::DriveError> {
        let (fe, motions, arm, res) = self.model_parts()?;
        let belt = FlowingBelt::with_layout(fe, motions, arm)?;
        Ok((belt, res))
    }

    /// The layout with a uniform mesh of the shorter of `mesh.span_element` and
    /// `mesh.arc_element` on spans and wraps: what the rotating-mesh nodal model needs
    /// ([`Self::nodal_model`]; [`crate::fead`] runs it on this mesh).
    pub fn uniform_mesh(&self) -> LayoutConfig {
        let h = self.mesh.span_element.min(self.mesh.arc_element);
        let mut out = self.clone();
        out.mesh.span_element = h;
        out.mesh.arc_element = h;
        out
    }

    /// The rotating-mesh nodal model of the layout (Ribaric (5.7), [`NodalBelt::with_layout`];
    /// validated first), with the resolved layout: the same mesh, pulleys and motions as
    /// [`Self::flowing_model`] (tensioner included), so one TOML layout runs with either
    /// model. Its material nodes travel over spans and wraps, so give it near-uniform elements
    /// (`mesh.span_element ≈ mesh.arc_element`): long span elements landing on a wrap excite
    /// it at the element-passing frequency.
    pub fn nodal_model(&self) -> Result<(NodalBelt, ResolvedLayout), crate::DriveError> {
        let (fe, motions, arm, res) = self.model_parts()?;
        let belt = NodalBelt::with_layout(fe, motions, arm)?;
        Ok((belt, res))
    }

    /// The loop on the resolved path, one motion per pulley and the tensioner arm: what both
    /// models are built from (validated first).
    #[allow(clippy::type_complexity)]
    fn model_parts(
        &self,
    ) -> Result<(BeltFe, Vec<PulleyMotion>, Option<ArmModel>, ResolvedLayout), crate::DriveError>
    {
        self.validate()
            .map_err(|e| crate::DriveError::Invalid(e.to_string()))?;
        let res = self
            .resolve()
            .map_err(|e| crate::DriveError::Invalid(e.to_string()))?;
        let counts = self.element_counts(&res.path);
        let fe = BeltFe::on_path(&self.belt_config(res.tension), res.path.clone(), &counts)?;
        let motions = self
            .pulleys
            .iter()
            .map(|p| match &p.motion {
                MotionSpec::Speed { speed } => PulleyMotion::Speed(speed.clone()),
                MotionSpec::Load { inertia, torque } => PulleyMotion::Free {
                    inertia: *inertia,
                    load: torque.clone(),
                },
                MotionSpec::Idler { inertia } => PulleyMotion::Free {
                    inertia: *inertia,
                    load: Signal::constant(0.0),
                },
            })
            .collect();
        let arm = match (self.tensioner, res.arm) {
            (Some(spec), Some((length, angle))) => Some(ArmModel {
                spec,
                length,
                angle,
            }),
            _ => None,
        };
        Ok((fe, motions, arm, res))
    }

    /// Each pulley's name and role for the reports ([`crate::report`]): speed-driven the
    /// driver, loaded driven, idler an idler.
    pub fn roles(&self) -> Vec<(String, crate::report::PulleyRole)> {
        use crate::report::PulleyRole;
        self.pulleys
            .iter()
            .map(|p| {
                let role = match p.motion {
                    MotionSpec::Speed { .. } => PulleyRole::Driver,
                    MotionSpec::Load { .. } => PulleyRole::Driven,
                    MotionSpec::Idler { .. } => PulleyRole::Idler,
                };
                (p.name.clone(), role)
            })
            .collect()
    }

    /// The friction law of the belt–pulley contact.
    pub fn friction_law(&self) -> FrictionSpec {
        self.contact.friction_law()
    }
}

impl Validate for LayoutConfig {
    /// Field checks, then the layout's statics ([`LayoutConfig::resolve`]): every bad input of
    /// issue 17 is reported here with the pulley or field it concerns.
    fn validate(&self) -> Result<(), InvalidField> {
        let n = self.pulleys.len();
        check::count("pulleys", n, 2, MAX_PULLEYS)?;
        for (k, p) in self.pulleys.iter().enumerate() {
            let f = |s: &str| format!("pulleys[{k}].{s}");
            check::finite(&f("center[0]"), p.center[0])?;
            check::finite(&f("center[1]"), p.center[1])?;
            check::positive(&f("radius"), p.radius, "m")?;
            match &p.motion {
                MotionSpec::Speed { speed } => {
                    speed.validate().map_err(|e| e.within(&f("motion.speed")))?
                }
                MotionSpec::Load { inertia, torque } => {
                    check::positive(&f("motion.inertia"), *inertia, "kg m²")?;
                    torque
                        .validate()
                        .map_err(|e| e.within(&f("motion.torque")))?;
                }
                MotionSpec::Idler { inertia } => {
                    check::positive(&f("motion.inertia"), *inertia, "kg m²")?
                }
            }
        }
        for j in 0..n {
            for i in 0..j {
                let (a, b) = (&self.pulleys[i], &self.pulleys[j]);
                let d = (a.center[0] - b.center[0]).hypot(a.center[1] - b.center[1]);
                if d < a.radius + b.radius {
                    return Err(InvalidField::new(
                        format!("pulleys[{j}]"),
                        format!(
                            "'{}' overlaps pulleys[{i}] '{}': centres {:.4} m apart, radii sum {:.4} m",
                            b.name,
                            a.name,
                            d,
                            a.radius + b.radius
                        ),
                    ));
                }
            }
        }
        if let Some(t) = &self.tensioner {
            t.validate_within("tensioner")?;
            if t.pulley >= n {
                return Err(InvalidField::new(
                    "tensioner.pulley",
                    format!("no pulley {} (the layout has {n})", t.pulley),
                ));
            }
            if matches!(self.pulleys[t.pulley].motion, MotionSpec::Speed { .. }) {
                return Err(InvalidField::new(
                    "tensioner.pulley",
                    "the tensioner's idler must turn freely (motion kind idler or load)",
                ));
            }
            let (len, _) = t.arm(self.pulleys[t.pulley].center);
            check::positive("tensioner.pivot (arm length)", len, "m")?;
        }
        check::positive("belt.ea", self.belt.ea, "N")?;
        check::positive("belt.ei", self.belt.ei, "N m²")?;
        check::positive("belt.mass_per_length", self.belt.mass_per_length, "kg/m")?;
        match self.belt_length {
            Some(l) => check::positive("belt_length", l, "m")?,
            None => check::positive("belt.tension", self.belt.tension, "N")?,
        }
        check::positive("mesh.span_element", self.mesh.span_element, "m")?;
        check::positive("mesh.arc_element", self.mesh.arc_element, "m")?;
        check::positive(
            "contact.penalty_linear",
            self.contact.penalty_linear,
            "N/m²",
        )?;
        check::non_negative(
            "contact.penalty_quadratic",
            self.contact.penalty_quadratic,
            "N/m³",
        )?;
        check::non_negative("contact.mu", self.contact.mu, "")?;
        check::non_negative("contact.kappa", self.contact.kappa, "s/m")?;
        if let Some(f) = self.contact.friction {
            f.validate_within("contact.friction")?;
        }
        check::non_negative("damping.alpha", self.damping.alpha, "1/s")?;
        check::non_negative("damping.beta", self.damping.beta, "s")?;
        let res = self.resolve()?;
        let elements: usize = self.element_counts(&res.path).iter().sum();
        check::count(
            "mesh.span_element (elements of the loop)",
            elements,
            4,
            MAX_ELEMENTS,
        )?;
        Ok(())
    }
}
