//! Normal (penalty) laws named in configuration files: a `law = "…"` table per law, mapped to
//! its [`NormalLaw`] by enum dispatch (no allocation, `Copy`) — the normal-law counterpart of
//! [`crate::FrictionSpec`].

use super::{LinearPenalty, NormalForce, NormalLaw, PolynomialPenalty};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// A penalty law chosen in a configuration table, e.g.
/// `{ law = "linear", stiffness = 1e7, damping = 10 }`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
pub enum NormalSpec {
    /// [`LinearPenalty`]: `f_n = k_p d + c_p ḋ` (Kerkkänen (3.20)).
    Linear {
        /// Stiffness `k_p` \[N/m²\] (per unit length; \[N/m³\] per unit area).
        stiffness: f64,
        /// Damping `c_p` \[N·s/m²\].
        damping: f64,
    },
    /// [`PolynomialPenalty`] of unit tributary length plus damping:
    /// `f_n = k₂ d² + k₁ d + c_p ḋ` (Ribaric (6.1), per unit length).
    Polynomial {
        /// Quadratic coefficient `k₂` \[N/m³\].
        quadratic: f64,
        /// Linear coefficient `k₁` \[N/m²\].
        linear: f64,
        /// Damping `c_p` \[N·s/m²\].
        damping: f64,
    },
}

impl NormalSpec {
    /// The law `f_n = k₂ d² + k_p d + c_p ḋ` from its coefficients: [`NormalSpec::Linear`]
    /// (Kerkkänen (3.20)) when `k₂ = 0`, [`NormalSpec::Polynomial`] (Ribaric (6.1)) otherwise.
    pub fn penalty(stiffness: f64, quadratic: f64, damping: f64) -> Self {
        if quadratic == 0.0 {
            Self::Linear { stiffness, damping }
        } else {
            Self::Polynomial {
                quadratic,
                linear: stiffness,
                damping,
            }
        }
    }
}

impl Validate for NormalSpec {
    /// Check the parameters: all coefficients finite and `≥ 0` (field paths relative to the
    /// normal-law table, e.g. `stiffness`).
    fn validate(&self) -> Result<(), InvalidField> {
        let fields: &[(&'static str, f64)] = match *self {
            Self::Linear { stiffness, damping } => {
                &[("stiffness", stiffness), ("damping", damping)]
            }
            Self::Polynomial {
                quadratic,
                linear,
                damping,
            } => &[
                ("quadratic", quadratic),
                ("linear", linear),
                ("damping", damping),
            ],
        };
        for &(field, v) in fields {
            if !(v.is_finite() && v >= 0.0) {
                return Err(InvalidField::new(
                    field,
                    format!("must be finite and ≥ 0, got {v}"),
                ));
            }
        }
        Ok(())
    }
}

impl NormalLaw for NormalSpec {
    #[inline]
    fn normal(&self, pen: f64, pen_rate: f64) -> NormalForce {
        match *self {
            Self::Linear { stiffness, damping } => {
                LinearPenalty { stiffness, damping }.normal(pen, pen_rate)
            }
            Self::Polynomial {
                quadratic,
                linear,
                damping,
            } => {
                let mut f = PolynomialPenalty {
                    quadratic,
                    linear,
                    length: 1.0,
                }
                .normal(pen, pen_rate);
                f.force += damping * pen_rate;
                f.d_rate = damping;
                f
            }
        }
    }
    /// The linear law `k_p d + c_p ḋ` (3.20) in one loop over the batch (the same operations
    /// as [`NormalLaw::normal`], vectorised); the polynomial law point by point.
    #[inline(always)]
    fn normal_forces(&self, pen: &[f64], pen_rate: &[f64], out: &mut [f64]) {
        match *self {
            Self::Linear { stiffness, damping } => {
                let n = out.len();
                let (pen, rate) = (&pen[..n], &pen_rate[..n]);
                for q in 0..n {
                    out[q] = stiffness * pen[q] + damping * rate[q];
                }
            }
            Self::Polynomial { .. } => {
                for (q, o) in out.iter_mut().enumerate() {
                    *o = self.normal(pen[q], pen_rate[q]).force;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: analytical values of k₂d² + k_p d + c_p ḋ and its derivatives; TOML tables.
    #[test]
    fn laws_and_configuration() {
        let (d, r) = (2e-4, -0.03);
        let lin = NormalSpec::penalty(1e7, 0.0, 10.0);
        assert_eq!(
            lin,
            NormalSpec::Linear {
                stiffness: 1e7,
                damping: 10.0
            }
        );
        let f = lin.normal(d, r);
        assert_eq!(f.force, 1e7 * d + 10.0 * r);
        assert_eq!((f.d_pen, f.d_rate), (1e7, 10.0));
        let poly = NormalSpec::penalty(6.5e7, 3025.6e8, 5.0);
        let f = poly.normal(d, r);
        let exact = 3025.6e8 * d * d + 6.5e7 * d + 5.0 * r;
        assert!((f.force - exact).abs() < 1e-12 * exact.abs());
        assert!((f.d_pen - (2.0 * 3025.6e8 * d + 6.5e7)).abs() < 1e-6);
        assert_eq!(f.d_rate, 5.0);
        let t: NormalSpec = serde_json::from_str(
            r#"{"law":"polynomial","quadratic":1.0,"linear":2.0,"damping":0.5}"#,
        )
        .unwrap();
        assert_eq!(t, NormalSpec::penalty(2.0, 1.0, 0.5));
        assert!(serde_json::from_str::<NormalSpec>(r#"{"law":"linear","stiffness":1.0}"#).is_err());
        let bad = NormalSpec::penalty(-1.0, 0.0, 1.0).validate().unwrap_err();
        assert_eq!(bad.field, "stiffness");
        assert!(NormalSpec::penalty(1.0, 2.0, f64::NAN).validate().is_err());
        assert!(poly.validate().is_ok());
    }
}
