//! A belt drive of any layout and its resolution: N pulleys ([`Pulley`]) in travel order, an
//! optional automatic tensioner ([`Tensioner`]), the belt ([`Section`], [`BeltContact`],
//! [`BeltDamping`]) and its mounting (a target installation tension, or the unstretched belt
//! length). A [`Layout`] is what a user writes; [`Layout::resolve`] checks it and solves the
//! mounted drive once, by hand statics, into a [`Drive`] that every belt model is built from.
//!
//! Resolution (statics of the belt on frictionless pulleys at rest, equal tension `T` in
//! every span):
//!
//! - without a tensioner the path is fixed; with a given belt length `L_b` the tension is the
//!   force at stretch `λ = L_path / L_b` ([`Section::force`]), else the target `tension`
//!   (and `L_b = L_path / λ(T)`);
//! - with a tensioner the idler's centre moves on the arm, `c(θ) = p + L(cos θ, sin θ)`, and so
//!   do the path and its length `L_path(θ)`. The arm balances when
//!   `M_s(θ) + T (c − p) × (d_out − d_in) = 0` ([`crate::tensioner`]), `T` the target tension or
//!   `T(θ) = N(L_path(θ)/L_b)`. The root in the arm's travel is the laid-out arm angle; none is
//!   bad input ("tensioner outside its travel").
//!
//! Bad input, each naming the pulley or field: fewer than two or more than [`MAX_PULLEYS`]
//! pulleys, duplicate names, overlapping pulleys, a path that crosses itself, a belt too short
//! to wrap the layout (mounting strain above [`MAX_MOUNTING_STRAIN`]) or too long (slack), a
//! tensioner on a speed-driven pulley or whose static arm angle lies outside its travel, a wrap
//! angle below [`MIN_WRAP_DEG`].

use crate::motion::{Motion, Role};
use crate::path::{BeltPath, SpanLine};
use crate::pulley::Pulley;
use crate::section::{BeltContact, BeltDamping, Section};
use crate::tensioner::{Tensioner, cross};
use contact::friction::{FrictionLaw, FrictionSpec};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Most pulleys a layout may have (sizes from input are bounded before anything is built).
pub const MAX_PULLEYS: usize = 16;
/// Smallest wrap angle accepted on any pulley \[deg\] (a belt that barely touches a pulley
/// carries no torque and makes the contact set ill-defined).
pub const MIN_WRAP_DEG: f64 = 10.0;
/// Largest mounting strain `λ − 1` accepted: a belt stretched more than this is too short for
/// the layout (automotive V-ribbed belts are mounted at 0.1–0.5 %; flat test belts such as
/// Pechstein & Gerstmayr's at about 5 %).
pub const MAX_MOUNTING_STRAIN: f64 = 0.15;

/// The rules of a [`Layout`] read partially over a default one
/// ([`mbd_core::config::PartialRules`]), declared by every configuration that holds a layout:
/// the installation `tension` \[N\] and the unstretched `belt_length` \[m\] exclude each other
/// (the user's one drops the default's other); a new list of `pulleys` drops the default's
/// `tensioner`, whose `pulley` indexed the old list (a drive with new pulleys has a tensioner
/// only if the user gives one), and the default's `contact.friction`: a drive with new pulleys
/// is the user's drive, whose friction is the layouts' default ([`BeltContact::default`]: the
/// `tanh_slip` law near the Coulomb limit) unless the user gives one, not the seed's κ = 40 s/m
/// that the studies' default drives state to reproduce their figures (issue 34 item 3).
pub const PARTIAL_RULES: &[(&str, &str)] = &[
    ("tension", "belt_length"),
    ("belt_length", "tension"),
    ("pulleys", "tensioner"),
    ("pulleys", "contact.friction"),
];

/// A belt drive as a user describes it (module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Layout {
    /// Pulleys in travel order (the loop runs clockwise around the `inside` pulleys).
    pub pulleys: Vec<Pulley>,
    /// Automatic tensioner (its `pulley` indexes `pulleys`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tensioner: Option<Tensioner>,
    /// Belt section and material law.
    #[serde(default)]
    pub belt: Section,
    /// Target installation tension \[N\] (the force the mounted belt carries at rest); give
    /// this or `belt_length`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension: Option<f64>,
    /// Unstretched belt length \[m\]; give this or `tension`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub belt_length: Option<f64>,
    /// Belt–pulley contact and friction.
    #[serde(default)]
    pub contact: BeltContact,
    /// Rayleigh damping of the belt.
    #[serde(default)]
    pub damping: BeltDamping,
}

impl mbd_core::config::PartialRules for Layout {
    const DROPPED_BY: &'static [(&'static str, &'static str)] = PARTIAL_RULES;
}

/// A tensioner arm of a resolved drive: its length and static angle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Arm {
    /// The tensioner.
    pub tensioner: Tensioner,
    /// Arm length `L` \[m\].
    pub length: f64,
    /// Static arm angle of the mounted belt \[rad\] (counter-clockwise from x).
    pub angle: f64,
}

/// A resolved layout: the mounted belt's path, tension and length, the tensioner's static arm
/// and the wraps. Built once by [`Layout::resolve`]; every belt model is built from it.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    layout: Layout,
    path: BeltPath,
    tension: f64,
    belt_length: f64,
    arm: Option<Arm>,
    wraps: Vec<f64>,
}

/// Moment per unit span tension \[m\] of the belt on the tensioner's idler about the pivot:
/// `(c − p) × (d_out − d_in)`, with `d_in`, `d_out` the travel directions of the spans
/// arriving at and leaving the idler (hand statics of the arm, [`crate::tensioner`]).
pub fn arm_lever(path: &BeltPath, t: &Tensioner) -> f64 {
    let k = t.pulley;
    let spans = path.spans();
    let d_in = spans.iter().find(|s| s.to == k).map(|s| s.direction);
    let d_out = spans.iter().find(|s| s.from == k).map(|s| s.direction);
    let (Some(di), Some(dout)) = (d_in, d_out) else {
        return f64::NAN;
    };
    let c = path.pulleys()[k].center;
    cross(
        [c[0] - t.pivot[0], c[1] - t.pivot[1]],
        [dout[0] - di[0], dout[1] - di[1]],
    )
}

impl Layout {
    /// A layout of `pulleys` with `belt` mounted at `tension` \[N\] (no tensioner; default
    /// contact and damping).
    pub fn new(pulleys: Vec<Pulley>, belt: Section, tension: f64) -> Self {
        Self {
            pulleys,
            tensioner: None,
            belt,
            tension: Some(tension),
            belt_length: None,
            contact: BeltContact::default(),
            damping: BeltDamping::default(),
        }
    }

    /// The mounted tension for a belt of unstretched length `lb` on a path of length `lp`
    /// \[N\]: the force at stretch `lp/lb`.
    fn tension_of(&self, lp: f64, lb: f64) -> f64 {
        self.belt.force(lp / lb).0
    }

    /// Field checks (module documentation), before the statics of [`Self::resolve`].
    fn check_fields(&self) -> Result<(), InvalidField> {
        let n = self.pulleys.len();
        check::count("pulleys", n, 2, MAX_PULLEYS)?;
        for (k, p) in self.pulleys.iter().enumerate() {
            p.validate_within(&format!("pulleys[{k}]"))?;
            if let Some(i) = self.pulleys[..k].iter().position(|q| q.name == p.name) {
                return Err(InvalidField::new(
                    format!("pulleys[{k}].name"),
                    format!(
                        "'{}' is also the name of pulleys[{i}]: names must be unique",
                        p.name
                    ),
                ));
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
            if !self.pulleys[t.pulley].is_free() {
                return Err(InvalidField::new(
                    "tensioner.pulley",
                    "the tensioner's idler must turn freely (motion kind idler or load)",
                ));
            }
            let (len, _) = t.arm(self.pulleys[t.pulley].center);
            if len.is_nan() || len <= self.pulleys[t.pulley].radius * 1e-3 {
                return Err(InvalidField::new(
                    "tensioner.pivot",
                    "coincides with the idler's centre: no arm",
                ));
            }
        }
        self.belt.validate_within("belt")?;
        match (self.tension, self.belt_length) {
            (Some(_), Some(_)) => {
                return Err(InvalidField::new(
                    "belt_length",
                    "give either tension or belt_length, not both",
                ));
            }
            (None, None) => {
                return Err(InvalidField::new(
                    "tension",
                    "give the installation tension [N] or the belt_length [m]",
                ));
            }
            (Some(t), None) => check::within(
                "tension",
                t,
                1e-6 * self.belt.ea,
                MAX_MOUNTING_STRAIN * self.belt.ea,
                "N",
            )?,
            (None, Some(l)) => check::within("belt_length", l, 1e-3, 1e3, "m")?,
        }
        self.contact.validate_within("contact")?;
        self.damping.validate_within("damping")
    }

    /// Check the layout and solve the mounted drive (module documentation).
    pub fn resolve(&self) -> Result<Drive, InvalidField> {
        self.check_fields()?;
        let mut pulleys = self.pulleys.clone();
        let (path, tension, arm) = match &self.tensioner {
            None => {
                let path = BeltPath::new(&pulleys)?;
                let t = match self.belt_length {
                    Some(lb) => self.tension_of(path.length(), lb),
                    None => self.tension.unwrap_or(f64::NAN),
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
                        Some(lb) => self.tension_of(path.length(), lb),
                        None => self.tension.unwrap_or(f64::NAN),
                    };
                    Some((path, t))
                };
                // the installed position must give a valid path: its error names the pulley
                BeltPath::new(&pulleys)?;
                // no open-belt path with the idler at θ (swung off the belt, which would have
                // to wrap its back the long way round): the belt does not touch it, no moment
                let moment = |theta: f64| match at(theta) {
                    Some((path, t)) => t * arm_lever(&path, spec),
                    None => 0.0,
                };
                let theta = spec.static_angle(moment);
                if let (None, Some(_)) = (theta, self.belt_length) {
                    // name the belt when it, not the spring, is out of range over the travel
                    let ts: Vec<f64> = spec
                        .travel
                        .iter()
                        .filter_map(|&a| at(a).map(|(_, t)| t))
                        .collect();
                    let too_tight = |t: f64| self.belt.stretch(t) - 1.0 > MAX_MOUNTING_STRAIN;
                    if !ts.is_empty() && ts.iter().all(|&t| too_tight(t)) {
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
                (
                    path,
                    t,
                    Some(Arm {
                        tensioner: *spec,
                        length,
                        angle: theta,
                    }),
                )
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
            let strain = self.belt.stretch(tension) - 1.0;
            if strain > MAX_MOUNTING_STRAIN {
                return Err(InvalidField::new(
                    "belt_length",
                    format!(
                        "too short to wrap the layout: the path is {:.4} m, a mounting strain of {:.1} % (max {:.0} %)",
                        path.length(),
                        100.0 * strain,
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
        Ok(Drive {
            belt_length: path.length() / self.belt.stretch(tension),
            layout: self.clone(),
            path,
            tension,
            arm,
            wraps,
        })
    }
}

impl Validate for Layout {
    /// Field checks, then the layout's statics ([`Layout::resolve`]).
    fn validate(&self) -> Result<(), InvalidField> {
        self.resolve().map(|_| ())
    }
}

impl Drive {
    /// The layout it was resolved from.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// The belt path of the mounted drive (a tensioner's idler at its static arm angle).
    pub fn path(&self) -> &BeltPath {
        &self.path
    }

    /// The pulleys in travel order, at their mounted positions.
    pub fn pulleys(&self) -> &[Pulley] {
        self.path.pulleys()
    }

    /// The pulley motions, in travel order.
    pub fn motions(&self) -> Vec<Motion> {
        self.layout
            .pulleys
            .iter()
            .map(|p| p.motion.clone())
            .collect()
    }

    /// Installation tension of the mounted belt at rest \[N\] (equal in every span).
    pub fn tension(&self) -> f64 {
        self.tension
    }

    /// Unstretched belt length \[m\].
    pub fn belt_length(&self) -> f64 {
        self.belt_length
    }

    /// The tensioner's arm at its static angle (`None`: no tensioner).
    pub fn arm(&self) -> Option<&Arm> {
        self.arm.as_ref()
    }

    /// Wrap angle of every pulley \[rad\], travel order.
    pub fn wraps(&self) -> &[f64] {
        &self.wraps
    }

    /// The belt section.
    pub fn belt(&self) -> &Section {
        &self.layout.belt
    }

    /// The belt–pulley contact.
    pub fn contact(&self) -> &BeltContact {
        &self.layout.contact
    }

    /// The friction law of the belt on pulley `pulley` (travel order): the contact's law with
    /// `μ` scaled by the section's factor for the pulley's wrap side,
    /// `μ/sin(β/2)` where a multi-ribbed belt runs its ribs in a grooved pulley
    /// ([`crate::pulley::WrapSide::Inside`]) and `μ` on a flat back-side pulley or for a flat
    /// belt ([`Section::friction_factor`], [`FrictionSpec::scaled`]; Johnson, *Contact
    /// Mechanics* §8.6). The one place the per-pulley law is made: every time-stepped model
    /// contacts pulley `pulley` with it, the report measures its friction utilisation against
    /// its `μ`, and the design study's capacity check uses the same `μ`.
    ///
    /// # Panics
    /// `pulley` is not a pulley of the drive.
    pub fn wrap_friction_law(&self, pulley: usize) -> FrictionSpec {
        let side = self.layout.pulleys[pulley].side;
        self.layout
            .contact
            .friction
            .scaled(self.layout.belt.friction_factor(side))
    }

    /// [`Self::wrap_friction_law`] of every pulley, travel order.
    pub fn wrap_friction_laws(&self) -> Vec<FrictionSpec> {
        (0..self.layout.pulleys.len())
            .map(|k| self.wrap_friction_law(k))
            .collect()
    }

    /// The friction coefficient `μ` of every pulley's wrap, travel order
    /// ([`Self::wrap_friction_law`], [`FrictionLaw::coefficient`]: the largest one of a
    /// Stribeck law).
    pub fn wrap_friction_coefficients(&self) -> Vec<f64> {
        self.wrap_friction_laws()
            .iter()
            .map(FrictionLaw::coefficient)
            .collect()
    }

    /// The belt's damping.
    pub fn damping(&self) -> &BeltDamping {
        &self.layout.damping
    }

    /// The straight spans in travel order (span `k` leaves pulley `k`).
    pub fn spans(&self) -> Vec<SpanLine> {
        self.path.spans()
    }

    /// Pulley names, travel order.
    pub fn names(&self) -> Vec<String> {
        self.layout.pulleys.iter().map(|p| p.name.clone()).collect()
    }

    /// Pulley roles, travel order ([`Motion::role`]).
    pub fn roles(&self) -> Vec<Role> {
        self.layout
            .pulleys
            .iter()
            .map(|p| p.motion.role())
            .collect()
    }

    /// The driver of a speed-loss run: the first speed-driven pulley.
    pub fn driver(&self) -> Option<usize> {
        self.layout.pulleys.iter().position(|p| !p.is_free())
    }

    /// The driven pulley of a speed-loss run: the first loaded pulley, else the first idler.
    pub fn driven(&self) -> Option<usize> {
        let first = |f: fn(&Motion) -> bool| self.layout.pulleys.iter().position(|p| f(&p.motion));
        first(|m| matches!(m, Motion::Load { .. }))
            .or_else(|| first(|m| matches!(m, Motion::Idler { .. })))
    }

    /// The same drive with other pulley motions (same geometry and mounting: the statics do
    /// not depend on the motions).
    ///
    /// # Errors
    /// The number of motions differs from the number of pulleys, a motion is invalid, or a
    /// tensioner's idler would become speed-driven.
    pub fn with_motions(&self, motions: Vec<Motion>) -> Result<Self, InvalidField> {
        if motions.len() != self.layout.pulleys.len() {
            return Err(InvalidField::new(
                "pulleys",
                format!(
                    "{} motions for {} pulleys",
                    motions.len(),
                    self.layout.pulleys.len()
                ),
            ));
        }
        let mut out = self.clone();
        for (k, m) in motions.into_iter().enumerate() {
            m.validate_within(&format!("pulleys[{k}].motion"))?;
            out.layout.pulleys[k].motion = m.clone();
            out.path.set_motion(k, m);
        }
        if let Some(t) = &self.layout.tensioner
            && !out.layout.pulleys[t.pulley].is_free()
        {
            return Err(InvalidField::new(
                "tensioner.pulley",
                "the tensioner's idler must turn freely",
            ));
        }
        Ok(out)
    }
}

impl Layout {
    /// The open-belt drive of two pulleys inside the loop (Ribaric Table 6-1's and Kerkkänen
    /// Table 3.1's geometry): `"driver"` at (0, 0) with belt-line radius `r_driver` \[m\]
    /// turning at `speed` \[rad/s\], `"driven"` at (`center_distance`, 0) with radius
    /// `r_driven` \[m\], inertia `inertia` \[kg m²\] and load `torque` \[N m\]; `belt` mounted at
    /// `tension` \[N\], default contact and damping.
    #[allow(clippy::too_many_arguments)]
    pub fn two_pulley(
        center_distance: f64, r_driver: f64, r_driven: f64, speed: crate::signal::Signal,
        inertia: f64, torque: crate::signal::Signal, belt: Section, tension: f64,
    ) -> Self {
        use crate::pulley::WrapSide;
        Self::new(
            vec![
                Pulley::new(
                    "driver",
                    [0.0, 0.0],
                    r_driver,
                    WrapSide::Inside,
                    Motion::speed(speed),
                ),
                Pulley::new(
                    "driven",
                    [center_distance, 0.0],
                    r_driven,
                    WrapSide::Inside,
                    Motion::load(inertia, torque),
                ),
            ],
            belt,
            tension,
        )
    }

    /// Ribaric's Table 6-1 drive (§6.1, §6.4) as a [`Layout::two_pulley`]: centres 0.45 m
    /// apart, both belt-line radii 0.05 m, the driver at rest, the driven pulley of
    /// 0.013 kg m² without load, the default [`Section`] mounted at T0 = 310 N, Ribaric's
    /// contact with κ = 40 s/m ([`BeltContact::ribaric`], stated: the seed's figures are taken
    /// with it; not the layouts' default friction, [`BeltContact::default`]).
    pub fn table_6_1() -> Self {
        Self {
            contact: BeltContact::ribaric(),
            ..Self::two_pulley(
                0.45,
                0.05,
                0.05,
                crate::signal::Signal::constant(0.0),
                0.013,
                crate::signal::Signal::constant(0.0),
                Section::default(),
                310.0,
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pulley::WrapSide;
    use crate::section::MaterialLaw;

    fn table_6_1() -> Layout {
        Layout::table_6_1()
    }

    // Mounting by hand: a belt of unstretched length L_b on the path of length L carries the
    // force of the stretch L/L_b (linear law: EA (L/L_b − 1)); given the tension, the belt is
    // L/λ(T0) long (the inverse); both laws round-trip (definition of the mounting).
    #[test]
    fn mounting_by_tension_or_by_length() {
        let d = table_6_1().resolve().unwrap();
        let lp = 2.0 * 0.45 + 2.0 * std::f64::consts::PI * 0.05;
        assert!((d.path().length() - lp).abs() < 1e-12);
        assert_eq!(d.tension(), 310.0);
        for law in [MaterialLaw::Linear, MaterialLaw::StVenantKirchhoff] {
            let mut c = table_6_1();
            c.belt.law = law;
            let d = c.resolve().unwrap();
            assert!((c.belt.force(lp / d.belt_length()).0 - 310.0).abs() < 1e-6);
            c.tension = None;
            c.belt_length = Some(d.belt_length());
            let back = c.resolve().unwrap();
            assert!((back.tension() - 310.0).abs() < 1e-6, "{law:?}");
        }
        let mut c = table_6_1();
        c.belt.law = MaterialLaw::Linear;
        c.tension = None;
        c.belt_length = Some(lp / 1.01);
        let t = c.resolve().unwrap().tension();
        assert!((t - 0.01 * 152_000.0).abs() < 1e-6, "{t}");
    }

    // Bad input names the field (issue 35: duplicate names, a slack or over-stretched belt,
    // both mountings, a tensioner on a speed-driven pulley).
    #[test]
    fn bad_layouts_name_the_field() {
        let field = |c: &Layout| c.resolve().unwrap_err().field;
        let mut c = table_6_1();
        c.pulleys[1].name = "driver".into();
        assert_eq!(field(&c), "pulleys[1].name");
        let mut c = table_6_1();
        c.tension = None;
        c.belt_length = Some(1.3);
        assert_eq!(field(&c), "belt_length");
        c.belt_length = Some(0.9);
        assert_eq!(field(&c), "belt_length");
        let mut c = table_6_1();
        c.belt_length = Some(1.2);
        assert_eq!(field(&c), "belt_length");
        let mut c = table_6_1();
        c.tension = None;
        assert_eq!(field(&c), "tension");
        let mut c = table_6_1();
        c.pulleys[1].radius = 1e-9;
        assert_eq!(field(&c), "pulleys[1].radius");
        let mut c = table_6_1();
        c.pulleys[1].center = [0.08, 0.0];
        assert_eq!(field(&c), "pulleys[1]");
        let mut c = table_6_1();
        c.tensioner = Some(Tensioner {
            pulley: 0,
            pivot: [0.1, 0.1],
            stiffness: 10.0,
            preload: 1.0,
            preload_angle: 0.0,
            damping: 0.0,
            dry_friction: 0.0,
            friction_rate: 0.01,
            inertia: 1e-3,
            travel: [-1.0, 1.0],
        });
        assert_eq!(field(&c), "tensioner.pulley");
        // a back-side pulley between the two, a third pulley in the loop: fine; the roles
        let mut c = table_6_1();
        c.pulleys.insert(
            1,
            Pulley::new(
                "idler",
                [0.225, 0.055],
                0.03,
                WrapSide::Outside,
                Motion::idler(1e-4),
            ),
        );
        let d = c.resolve().unwrap();
        assert_eq!(d.roles(), vec![Role::Driver, Role::Idler, Role::Driven]);
        assert_eq!((d.driver(), d.driven()), (Some(0), Some(2)));
    }
}
