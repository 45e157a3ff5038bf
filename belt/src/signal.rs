//! Prescribed time histories of a belt drive: a pulley's speed \[rad/s\] or a load torque
//! \[N m\]. One type, [`Signal`], for every model and study: a mean part ([`Shape`]: constant,
//! linear ramp, Kerkkänen's cosine ramp, smooth schedule through knots, or a measured trace)
//! plus harmonics faded in over [`Signal::fade`],
//!
//! ```text
//!   y(t) = y_shape(t) + h(t/fade) Σ A_k sin(Ω_k t + φ_k),   h(τ) = 3τ² − 2τ³ (τ ≤ 1), 1 after
//! ```
//!
//! (a harmonic marked `fade_out` is weighted by `1 − h` instead: it fades out while the others
//! fade in)
//!
//! (the crankshaft's mean speed plus its firing orders; an accessory's load with its ripple).
//!
//! In a configuration file a signal is one table with a `kind`:
//!
//! ```toml
//! speed  = { kind = "constant", value = 62.8 }
//! speed  = { kind = "ramp", t_start = 0.05, t_end = 0.6, value = 12.0 }        # Kerkkänen (3.29)
//! torque = { kind = "cosine", t_start = 0.05, t_end = 0.6, value = 45.0 }      # Kerkkänen (3.30)
//! torque = { kind = "schedule", knots = [[0.0, 0.0], [0.1, 5.0]] }             # C¹ smooth steps
//! speed  = { kind = "trace", knots = [[0.0, 83.0], [0.01, 84.1]] }             # linear, measured
//! speed  = { kind = "constant", value = 83.8, fade = 0.1,
//!            harmonics = [{ amplitude = 1.7, frequency = 167.6 }] }
//! ```

use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Most knots of a schedule or trace (sizes from input are bounded before use).
pub const MAX_KNOTS: usize = 1_000_000;
/// Most harmonics of one signal.
pub const MAX_HARMONICS: usize = 1000;

/// The mean part of a [`Signal`].
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// `y(t) = value`.
    Constant(f64),
    /// Linear ramp, Kerkkänen (3.29) generalised: `from` for `t ≤ t_start`, linear to `value`
    /// at `t_end`, then `value` (the thesis: `t_start = 0.05 s`, `t_end = 0.6 s`, from 0 to
    /// 12 rad/s). The rate jumps at both ends, as printed.
    Ramp {
        /// End of the rest phase \[s\].
        t_start: f64,
        /// End of the ramp \[s\].
        t_end: f64,
        /// Value before the ramp.
        from: f64,
        /// Final value.
        value: f64,
    },
    /// Kerkkänen (3.30) as printed: `0` for `t ≤ t_start`, `(value/2)(1 − cos(π t/t_end))` for
    /// `t_start < t ≤ t_end`, `value` after (thesis: 0.05 s, 0.6 s, 45 N m; the printed form
    /// jumps by `(value/2)(1 − cos(π t_start/t_end))` at `t_start`, seed-001 note §5).
    Cosine {
        /// Start \[s\].
        t_start: f64,
        /// End of the ramp \[s\].
        t_end: f64,
        /// Final value.
        value: f64,
    },
    /// Knots `(t_k, y_k)` joined by C¹ smooth steps `y_k + (y_{k+1} − y_k)(3τ² − 2τ³)`,
    /// constant before the first and after the last knot (Ribaric's driver and load
    /// schedules, §6.4).
    Schedule(Vec<(f64, f64)>),
    /// Knots `(t_k, y_k)` joined linearly, constant outside: a measured trace (e.g. a
    /// crankshaft speed record).
    Trace(Vec<(f64, f64)>),
}

/// One harmonic `A sin(Ω t + φ)` of a [`Signal`] (a crankshaft firing order, a load ripple).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Harmonic {
    /// Amplitude `A` \[unit of the signal: rad/s for a speed, N m for a torque\].
    pub amplitude: f64,
    /// Circular frequency `Ω` \[rad/s\].
    pub frequency: f64,
    /// Phase `φ` \[rad\].
    #[serde(default)]
    pub phase: f64,
    /// Faded out instead of in: weighted by `1 − h(t/fade)` (a study that restarts time at an
    /// operating point carries the previous point's harmonics on, with their phases
    /// continued, while the new ones fade in, so the signal stays C¹ across the restart).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub fade_out: bool,
}

/// A prescribed history (module documentation): a [`Shape`] plus harmonics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(try_from = "RawSignal", into = "RawSignal")]
pub struct Signal {
    /// The mean part.
    pub shape: Shape,
    /// Harmonics added to it.
    pub harmonics: Vec<Harmonic>,
    /// Fade-in time of the harmonics \[s\] (`0`: applied at once).
    pub fade: f64,
}

impl Default for Signal {
    /// Zero.
    fn default() -> Self {
        Self::constant(0.0)
    }
}

impl From<Shape> for Signal {
    fn from(shape: Shape) -> Self {
        Self {
            shape,
            harmonics: Vec::new(),
            fade: 0.0,
        }
    }
}

/// C¹ step `s(τ) = 3τ² − 2τ³` and `ds/dτ`.
fn smoothstep(tau: f64) -> (f64, f64) {
    (tau * tau * (3.0 - 2.0 * tau), 6.0 * tau * (1.0 - tau))
}

/// Value and rate through `knots` (sorted), `blend` giving `(s, ds/dτ)` on each interval.
fn through(knots: &[(f64, f64)], t: f64, blend: fn(f64) -> (f64, f64)) -> (f64, f64) {
    match knots.len() {
        0 => (0.0, 0.0),
        _ if t <= knots[0].0 => (knots[0].1, 0.0),
        n if t >= knots[n - 1].0 => (knots[n - 1].1, 0.0),
        _ => {
            let j = knots.partition_point(|p| p.0 <= t) - 1;
            let ((t0, y0), (t1, y1)) = (knots[j], knots[j + 1]);
            let (s, ds) = blend((t - t0) / (t1 - t0));
            let ds = ds / (t1 - t0);
            (y0 + (y1 - y0) * s, (y1 - y0) * ds)
        }
    }
}

impl Shape {
    /// Value and rate `(y, ẏ)` at `t`.
    pub fn eval(&self, t: f64) -> (f64, f64) {
        match self {
            Shape::Constant(y) => (*y, 0.0),
            &Shape::Ramp {
                t_start,
                t_end,
                from,
                value,
            } => {
                if t <= t_start {
                    (from, 0.0)
                } else if t <= t_end {
                    let r = (value - from) / (t_end - t_start);
                    (from + r * (t - t_start), r)
                } else {
                    (value, 0.0)
                }
            }
            &Shape::Cosine {
                t_start,
                t_end,
                value,
            } => {
                if t <= t_start {
                    (0.0, 0.0)
                } else if t <= t_end {
                    let phase = PI * t / t_end;
                    (
                        0.5 * value * (1.0 - phase.cos()),
                        0.5 * value * PI / t_end * phase.sin(),
                    )
                } else {
                    (value, 0.0)
                }
            }
            Shape::Schedule(k) => through(k, t, smoothstep),
            Shape::Trace(k) => through(k, t, |tau| (tau, 1.0)),
        }
    }

    /// The final (steady) value.
    pub fn final_value(&self) -> f64 {
        match self {
            Shape::Constant(y) => *y,
            Shape::Ramp { value, .. } | Shape::Cosine { value, .. } => *value,
            Shape::Schedule(k) | Shape::Trace(k) => k.last().map_or(0.0, |p| p.1),
        }
    }

    /// The knots of a schedule or trace.
    pub fn knots(&self) -> Option<&[(f64, f64)]> {
        match self {
            Shape::Schedule(k) | Shape::Trace(k) => Some(k),
            _ => None,
        }
    }
}

impl Signal {
    /// A constant value.
    pub fn constant(y: f64) -> Self {
        Shape::Constant(y).into()
    }

    /// C¹ smooth steps through `knots` `(t_k, y_k)` (times strictly increasing).
    pub fn schedule(knots: Vec<(f64, f64)>) -> Self {
        Shape::Schedule(knots).into()
    }

    /// Kerkkänen's driver ramp (3.29): 0 until 0.05 s, linear to `value` at 0.6 s.
    pub fn kerkkanen_ramp(value: f64) -> Self {
        Shape::Ramp {
            t_start: 0.05,
            t_end: 0.6,
            from: 0.0,
            value,
        }
        .into()
    }

    /// Kerkkänen's load ramp (3.30) as printed: 0 until 0.05 s, `(value/2)(1 − cos(π t/0.6))`
    /// until 0.6 s, then `value`.
    pub fn kerkkanen_cosine(value: f64) -> Self {
        Shape::Cosine {
            t_start: 0.05,
            t_end: 0.6,
            value,
        }
        .into()
    }

    /// Value and rate `(y, ẏ)` at `t`.
    pub fn eval(&self, t: f64) -> (f64, f64) {
        let (mut y, mut dy) = self.shape.eval(t);
        if self.harmonics.is_empty() {
            return (y, dy);
        }
        let (h, dh) = if self.fade > 0.0 && t < self.fade {
            let (s, ds) = smoothstep(t.max(0.0) / self.fade);
            (s, ds / self.fade)
        } else {
            (1.0, 0.0)
        };
        for k in &self.harmonics {
            let (w, dw) = if k.fade_out { (1.0 - h, -dh) } else { (h, dh) };
            let (s, c) = (k.frequency * t + k.phase).sin_cos();
            y += w * k.amplitude * s;
            dy += w * k.amplitude * k.frequency * c + dw * k.amplitude * s;
        }
        (y, dy)
    }

    /// Value at `t`.
    pub fn value(&self, t: f64) -> f64 {
        self.eval(t).0
    }

    /// The final (steady) value of the mean part.
    pub fn final_value(&self) -> f64 {
        self.shape.final_value()
    }

    /// The same signal with its mean part held at its final value (harmonics kept): a study
    /// that restarts time at every operating point keeps the loads it ramped to.
    pub fn held(&self) -> Self {
        Self {
            shape: Shape::Constant(self.final_value()),
            harmonics: self.harmonics.clone(),
            fade: self.fade,
        }
    }

    /// The lowest circular frequency among the harmonics \[rad/s\] (`None`: no harmonics).
    pub fn lowest_frequency(&self) -> Option<f64> {
        self.harmonics
            .iter()
            .map(|h| h.frequency.abs())
            .filter(|w| *w > 0.0)
            .min_by(f64::total_cmp)
    }
}

impl Validate for Signal {
    /// Finite values, increasing times (the error names the field relative to the signal).
    fn validate(&self) -> Result<(), InvalidField> {
        match &self.shape {
            Shape::Constant(y) => check::finite("value", *y)?,
            &Shape::Ramp {
                t_start,
                t_end,
                from,
                value,
            } => {
                check::finite("t_start", t_start)?;
                check::finite("from", from)?;
                check::finite("value", value)?;
                if !(t_end.is_finite() && t_end > t_start) {
                    return Err(InvalidField::new(
                        "t_end",
                        format!("must exceed t_start ({t_start} s), got {t_end} s"),
                    ));
                }
            }
            &Shape::Cosine {
                t_start,
                t_end,
                value,
            } => {
                check::finite("t_start", t_start)?;
                check::finite("value", value)?;
                if !(t_end.is_finite() && t_end > t_start && t_end > 0.0) {
                    return Err(InvalidField::new(
                        "t_end",
                        format!("must be > 0 s and exceed t_start ({t_start} s), got {t_end} s"),
                    ));
                }
            }
            Shape::Schedule(k) | Shape::Trace(k) => {
                check::count("knots", k.len(), 1, MAX_KNOTS)?;
                for (i, (t, y)) in k.iter().enumerate() {
                    check::finite(&format!("knots[{i}][0]"), *t)?;
                    check::finite(&format!("knots[{i}][1]"), *y)?;
                }
                for (i, w) in k.windows(2).enumerate() {
                    if w[1].0 <= w[0].0 {
                        return Err(InvalidField::new(
                            format!("knots[{}]", i + 1),
                            "times must increase strictly",
                        ));
                    }
                }
            }
        }
        check::count("harmonics", self.harmonics.len(), 0, MAX_HARMONICS)?;
        for (i, k) in self.harmonics.iter().enumerate() {
            check::finite(&format!("harmonics[{i}].amplitude"), k.amplitude)?;
            check::finite(&format!("harmonics[{i}].frequency"), k.frequency)?;
            check::finite(&format!("harmonics[{i}].phase"), k.phase)?;
        }
        check::non_negative("fade", self.fade, "s")
    }
}

/// The kinds of [`Shape`] as named in configuration files.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
enum Kind {
    /// `y = value`.
    Constant,
    /// Linear ramp from `from` at `t_start` to `value` at `t_end` (Kerkkänen (3.29)).
    Ramp,
    /// Kerkkänen's cosine ramp (3.30) to `value` between `t_start` and `t_end`.
    Cosine,
    /// C¹ smooth steps through `knots`.
    Schedule,
    /// Linear through `knots` (a measured trace).
    Trace,
}

/// The configuration-file form of a [`Signal`] (module documentation): one table, the
/// fields a kind does not use rejected by name.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawSignal {
    /// The shape of the mean part.
    kind: Kind,
    /// The constant value, or the final value of a ramp \[rad/s for a speed, N m for a
    /// torque\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    value: Option<f64>,
    /// Start of a ramp \[s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    t_start: Option<f64>,
    /// End of a ramp \[s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    t_end: Option<f64>,
    /// Value before a linear ramp \[rad/s for a speed, N m for a torque\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    from: Option<f64>,
    /// Knots `[t, y]` of a schedule or trace, times ascending \[s, rad/s for a speed or N m
    /// for a torque\].
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "mbd_core::validate::exact_pairs_opt"
    )]
    knots: Option<Vec<(f64, f64)>>,
    /// Harmonics added to the mean part, faded in over `fade`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    harmonics: Vec<Harmonic>,
    /// Fade-in time of the harmonics \[s\] (`0`: applied at once).
    #[serde(default, skip_serializing_if = "is_zero")]
    fade: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl TryFrom<RawSignal> for Signal {
    type Error = String;

    fn try_from(r: RawSignal) -> Result<Self, String> {
        let name = match r.kind {
            Kind::Constant => "constant",
            Kind::Ramp => "ramp",
            Kind::Cosine => "cosine",
            Kind::Schedule => "schedule",
            Kind::Trace => "trace",
        };
        let need =
            |v: Option<f64>, f: &str| v.ok_or_else(|| format!("a {name} signal needs `{f}`"));
        let unused = |present: bool, f: &str| {
            if present {
                Err(format!("a {name} signal has no field `{f}`"))
            } else {
                Ok(())
            }
        };
        let shape = match r.kind {
            Kind::Constant => {
                unused(r.t_start.is_some(), "t_start")?;
                unused(r.t_end.is_some(), "t_end")?;
                unused(r.from.is_some(), "from")?;
                unused(r.knots.is_some(), "knots")?;
                Shape::Constant(need(r.value, "value")?)
            }
            Kind::Ramp => {
                unused(r.knots.is_some(), "knots")?;
                Shape::Ramp {
                    t_start: need(r.t_start, "t_start")?,
                    t_end: need(r.t_end, "t_end")?,
                    from: r.from.unwrap_or(0.0),
                    value: need(r.value, "value")?,
                }
            }
            Kind::Cosine => {
                unused(r.knots.is_some(), "knots")?;
                unused(r.from.is_some(), "from")?;
                Shape::Cosine {
                    t_start: need(r.t_start, "t_start")?,
                    t_end: need(r.t_end, "t_end")?,
                    value: need(r.value, "value")?,
                }
            }
            Kind::Schedule | Kind::Trace => {
                unused(r.value.is_some(), "value")?;
                unused(r.t_start.is_some(), "t_start")?;
                unused(r.t_end.is_some(), "t_end")?;
                unused(r.from.is_some(), "from")?;
                let k = r
                    .knots
                    .ok_or_else(|| format!("a {name} signal needs `knots`"))?;
                if r.kind == Kind::Schedule {
                    Shape::Schedule(k)
                } else {
                    Shape::Trace(k)
                }
            }
        };
        Ok(Self {
            shape,
            harmonics: r.harmonics,
            fade: r.fade,
        })
    }
}

impl From<Signal> for RawSignal {
    fn from(s: Signal) -> Self {
        let mut r = RawSignal {
            kind: Kind::Constant,
            value: None,
            t_start: None,
            t_end: None,
            from: None,
            knots: None,
            harmonics: s.harmonics,
            fade: s.fade,
        };
        match s.shape {
            Shape::Constant(y) => r.value = Some(y),
            Shape::Ramp {
                t_start,
                t_end,
                from,
                value,
            } => {
                r.kind = Kind::Ramp;
                (r.t_start, r.t_end, r.value) = (Some(t_start), Some(t_end), Some(value));
                r.from = (from != 0.0).then_some(from);
            }
            Shape::Cosine {
                t_start,
                t_end,
                value,
            } => {
                r.kind = Kind::Cosine;
                (r.t_start, r.t_end, r.value) = (Some(t_start), Some(t_end), Some(value));
            }
            Shape::Schedule(k) => {
                r.kind = Kind::Schedule;
                r.knots = Some(k);
            }
            Shape::Trace(k) => {
                r.kind = Kind::Trace;
                r.knots = Some(k);
            }
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rate_matches_differences(s: &Signal, times: &[f64]) {
        for &t in times {
            let h = 1e-6;
            let fd = (s.value(t + h) - s.value(t - h)) / (2.0 * h);
            assert!(
                (fd - s.eval(t).1).abs() < 1e-5 * fd.abs().max(1.0),
                "t = {t}"
            );
        }
    }

    // Kerkkänen (3.29) and (3.30) evaluated by hand.
    #[test]
    fn kerkkanen_ramps() {
        let w = Signal::kerkkanen_ramp(12.0);
        assert_eq!(w.eval(0.04), (0.0, 0.0));
        let (o, a) = w.eval(0.325);
        assert!((o - 6.0).abs() < 1e-12 && (a - 12.0 / 0.55).abs() < 1e-12);
        assert_eq!(w.eval(1.0), (12.0, 0.0));
        let t = Signal::kerkkanen_cosine(45.0);
        assert_eq!(t.value(0.05), 0.0);
        assert!((t.value(0.3) - 22.5).abs() < 1e-12);
        assert!((t.value(0.6) - 45.0).abs() < 1e-12);
        // the printed form jumps by 22.5 (1 − cos(π·0.05/0.6)) just after t_start
        assert!((t.value(0.050_000_001) - 0.7670).abs() < 1e-3);
        rate_matches_differences(&t, &[0.1, 0.3, 0.55]);
    }

    // The C¹ schedule hits its knots; rates against central differences.
    #[test]
    fn schedule_hits_knots_and_rates_match_differences() {
        let s = Signal::schedule(vec![(0.0, 0.0), (0.5, 60.0), (1.0, 60.0), (1.2, 10.0)]);
        assert_eq!(s.value(-1.0), 0.0);
        assert_eq!(s.value(0.5), 60.0);
        assert_eq!(s.value(0.75), 60.0);
        assert_eq!(s.value(5.0), 10.0);
        rate_matches_differences(&s, &[0.1, 0.37, 1.05, 1.19]);
        let tr = Signal::from(Shape::Trace(vec![(0.0, 1.0), (2.0, 5.0)]));
        assert_eq!(tr.eval(0.5), (2.0, 2.0));
    }

    // Harmonics faded in: after the fade mean plus the full harmonic (definition).
    #[test]
    fn harmonics_fade_in() {
        let s = Signal {
            shape: Shape::Schedule(vec![(0.0, 10.0), (0.3, 20.0)]),
            harmonics: vec![Harmonic {
                amplitude: 2.0,
                frequency: 40.0,
                phase: 0.3,
                fade_out: false,
            }],
            fade: 0.2,
        };
        rate_matches_differences(&s, &[0.05, 0.15, 0.25, 0.5]);
        let t = 0.7;
        assert!((s.value(t) - 20.0 - 2.0 * (40.0 * t + 0.3).sin()).abs() < 1e-12);
        assert_eq!(s.held().value(0.0), 20.0 + 2.0 * 0.3f64.sin() * 0.0);
        assert_eq!(s.lowest_frequency(), Some(40.0));
    }

    // A harmonic faded out carries a previous signal on: at t = 0 the value and rate are the
    // faded-out harmonic's alone (reference: its closed form), after the fade it is gone.
    #[test]
    fn harmonics_fade_out_while_others_fade_in() {
        let old = Harmonic {
            amplitude: 1.5,
            frequency: 30.0,
            phase: 0.7,
            fade_out: true,
        };
        let new = Harmonic {
            amplitude: 2.0,
            frequency: 55.0,
            phase: 0.1,
            fade_out: false,
        };
        let s = Signal {
            shape: Shape::Constant(5.0),
            harmonics: vec![old, new],
            fade: 0.2,
        };
        let (y, dy) = s.eval(0.0);
        assert!((y - (5.0 + 1.5 * 0.7f64.sin())).abs() < 1e-14);
        assert!((dy - 1.5 * 30.0 * 0.7f64.cos()).abs() < 1e-12);
        rate_matches_differences(&s, &[0.05, 0.1, 0.15, 0.3]);
        let t = 0.4;
        assert!((s.value(t) - 5.0 - 2.0 * (55.0 * t + 0.1).sin()).abs() < 1e-12);
    }

    // Every kind reads back from its TOML form; unused and missing fields are named.
    #[test]
    fn toml_round_trip_and_errors() {
        #[derive(Deserialize, schemars::JsonSchema, Serialize)]
        struct W {
            s: Signal,
        }
        for s in [
            Signal::constant(3.0),
            Signal::kerkkanen_ramp(12.0),
            Signal::kerkkanen_cosine(45.0),
            Signal::schedule(vec![(0.0, 0.0), (0.1, 5.0)]),
            Signal::from(Shape::Trace(vec![(0.0, 1.0), (1.0, 2.0)])),
        ] {
            let text = toml::to_string(&W { s: s.clone() }).unwrap();
            let back: W = toml::from_str(&text).unwrap();
            assert_eq!(back.s, s, "{text}");
        }
        let bad = |t: &str| toml::from_str::<W>(t).err().unwrap().to_string();
        assert!(bad("s = { kind = \"constant\" }").contains("needs `value`"));
        assert!(bad("s = { kind = \"constant\", value = 1.0, t_end = 2.0 }").contains("`t_end`"));
        assert!(bad("s = { kind = \"constant\", value = 1.0, speed = 2.0 }").contains("speed"));
        let s: W =
            toml::from_str("s = { kind = \"ramp\", t_start = 1.0, t_end = 0.5, value = 2.0 }")
                .unwrap();
        assert_eq!(s.s.validate().unwrap_err().field, "t_end");
    }
}
