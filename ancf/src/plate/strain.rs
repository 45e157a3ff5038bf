//! Fibre strain of the plate along its material `x` direction by the three measures of
//! Kerkkänen §4.2, (4.5)–(4.11), used to turn a finite-element solution into the belt tension of
//! the analytical model (tension = longitudinal stiffness `k = E A` × strain).
//!
//! The reference element is flat with `J₀ = I` and its `x` axis along the belt, so the
//! reference tangent of (4.5) is `t_o = e₁` in the element's material frame and the in-plane
//! Green–Lagrange tensor is `ε^m = ½(G − I)`, `G = Jᵀ J` the 2 × 2 metric of `J = [r_x r_y]`.

use serde::{Deserialize, Serialize};

/// The strain measure used for the belt tension (Kerkkänen Fig. 4.12).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "snake_case")]
pub enum StrainMeasure {
    /// (4.9): `ε = −1 + √(1 + α)`, `α = 2 t_oᵀ ε^m t_o = ‖r_x‖² − 1`, i.e. the engineering
    /// strain `dl/dl_o − 1` obtained from the Green–Lagrange tensor ("Green" in Fig. 4.12).
    #[default]
    Green,
    /// (4.10): the true strain `(dl − dl_o)/dl = 1 − 1/‖r_x‖`.
    True,
    /// (4.11) as printed: `ε^A = −1 + √(1 + α_A)`, `α_A = 2 t_tᵀ ε^e t_t`, with the
    /// Euler–Almansi tensor `ε^e = ½(I − D⁻ᵀ D⁻¹)` on the current tangent plane and the current
    /// tangent `t_t = r_x/‖r_x‖`.
    ///
    /// Two readings had to be decided (seed note §4.2 and §11 item 30):
    /// * `D` is the 3 × 2 surface gradient `J` of the plate, not invertible; `D⁻¹` is read as
    ///   its pseudo-inverse `G⁻¹ Jᵀ` onto the current tangent plane, so that
    ///   `t_tᵀ D⁻ᵀ D⁻¹ t_t = wᵀ G⁻² w`, `w = Jᵀ t_t`; for any in-plane deformation this is
    ///   `1/‖r_x‖²`, the 1-D Almansi fibre value `α_A = 1 − (dl_o/dl)²`.
    /// * The printed formula is kept. The note observes that the consistent inversion of the
    ///   1-D Almansi strain would be `(1 − α_A)^{−1/2} − 1`, which equals the Green-based
    ///   engineering strain and so would not give the third, distinct curve of Fig. 4.12 nor
    ///   the thesis' remark that the measures other than Green predict "even smaller" torques;
    ///   the printed `−1 + √(1 + α_A)` does both (at `‖r_x‖ = 1.25`: Green 0.25, true 0.20,
    ///   printed Almansi 0.166).
    Almansi,
}

impl StrainMeasure {
    /// All three, in the order of Fig. 4.12.
    pub const ALL: [StrainMeasure; 3] = [
        StrainMeasure::Green,
        StrainMeasure::True,
        StrainMeasure::Almansi,
    ];

    /// Name used in output columns (`green`, `true`, `almansi`).
    pub fn name(self) -> &'static str {
        match self {
            StrainMeasure::Green => "green",
            StrainMeasure::True => "true",
            StrainMeasure::Almansi => "almansi",
        }
    }

    /// The fibre strain along the material `x` direction from the gradients `r_x`, `r_y` of a
    /// point of the mid-surface (see the variants for the formulas).
    pub fn fibre_strain(self, rx: [f64; 3], ry: [f64; 3]) -> f64 {
        let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let g = [
            [dot(&rx, &rx), dot(&rx, &ry)],
            [dot(&rx, &ry), dot(&ry, &ry)],
        ];
        match self {
            StrainMeasure::Green => {
                // (4.7)–(4.9): α = 2 e₁ᵀ ½(G − I) e₁
                let alpha = g[0][0] - 1.0;
                -1.0 + (1.0 + alpha).sqrt()
            }
            StrainMeasure::True => {
                let stretch = g[0][0].sqrt();
                (stretch - 1.0) / stretch
            }
            StrainMeasure::Almansi => {
                let det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
                let inv = [
                    [g[1][1] / det, -g[0][1] / det],
                    [-g[1][0] / det, g[0][0] / det],
                ];
                // w = Jᵀ t_t = G e₁ / ‖r_x‖, then t_tᵀ D⁻ᵀD⁻¹ t_t = ‖G⁻¹ w‖²
                let l = g[0][0].sqrt();
                let w = [g[0][0] / l, g[1][0] / l];
                let y = [
                    inv[0][0] * w[0] + inv[0][1] * w[1],
                    inv[1][0] * w[0] + inv[1][1] * w[1],
                ];
                let alpha_a = 1.0 - (y[0] * y[0] + y[1] * y[1]);
                -1.0 + (1.0 + alpha_a).sqrt()
            }
        }
    }
}

/// Area ratio `√det(Jᵀ J)` of the mid-surface (current area per reference area): the
/// "determinant of the Jacobian" of Kerkkänen Fig. 4.13 (the thesis does not define it for the
/// 3 × 2 plate gradient; this is the surface Jacobian, 1 for a rigid motion, seed note §6.3).
pub fn area_ratio(rx: [f64; 3], ry: [f64; 3]) -> f64 {
    let n = [
        rx[1] * ry[2] - rx[2] * ry[1],
        rx[2] * ry[0] - rx[0] * ry[2],
        rx[0] * ry[1] - rx[1] * ry[0],
    ];
    (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    // Analytical: a fibre stretched by λ with lateral contraction μ and a shear of the width
    // direction: Green (4.9) = λ − 1, true (4.10) = 1 − 1/λ, printed Almansi (4.11) =
    // √(2 − 1/λ²) − 1; the area ratio is λ μ sin(angle between r_x and r_y).
    #[test]
    fn strain_measures_of_a_stretched_fibre() {
        let (lam, mu) = (1.25, 0.9);
        let rx = [0.6 * lam, 0.8 * lam, 0.0];
        // r_y at 80° from r_x in the plane spanned by r_x and z
        let th = 80f64.to_radians();
        let t = [0.6, 0.8, 0.0];
        let ry = [
            mu * (th.cos() * t[0]),
            mu * (th.cos() * t[1]),
            mu * th.sin(),
        ];
        let g = StrainMeasure::Green.fibre_strain(rx, ry);
        let tr = StrainMeasure::True.fibre_strain(rx, ry);
        let al = StrainMeasure::Almansi.fibre_strain(rx, ry);
        assert!((g - 0.25).abs() < 1e-15);
        assert!((tr - 0.2).abs() < 1e-15);
        assert!((al - (2.0 - 1.0 / (lam * lam)).sqrt() + 1.0).abs() < 1e-14);
        assert!((area_ratio(rx, ry) - lam * mu * th.sin()).abs() < 1e-14);
        // rigid motion: every measure vanishes
        let ry1 = [-0.8, 0.6, 0.0];
        for m in StrainMeasure::ALL {
            assert!(m.fibre_strain([0.6, 0.8, 0.0], ry1).abs() < 1e-15);
        }
    }
}
