//! The 4×4 Hermite bending blocks shared by the planar and the spatial frame elements.
//!
//! All blocks act on the four DOFs of one bending plane, `(v₁, θ₁, v₂, θ₂)` with `θ = v'`, of a
//! two-node element of length `L` with cubic Hermite interpolation of the deflection
//! (Przemieniecki, *Theory of Matrix Structural Analysis*, §5.6 and §11; Cook et al., *Concepts
//! and Applications of FEA*, ch. 2, 11 and 18). The frame elements scatter them into their local
//! matrices (with sign flips where the rotation is `−v'`).

/// Bending stiffness of one plane with the shear-flexibility parameter `Φ = 12 EI/(κGA L²)`
/// (`Φ = 0`: Euler–Bernoulli):
/// `EI/((1+Φ)L³) [12 6L −12 6L; 6L (4+Φ)L² −6L (2−Φ)L²; −12 −6L 12 −6L; 6L (2−Φ)L² −6L (4+Φ)L²]`
/// (Przemieniecki §5.6; Cook et al. ch. 2 and 11). `ei` is EI \[N·m²\], `l` is L \[m\].
///
/// With `Φ = 0` every factor `1 + Φ`, `4 + Φ`, `2 − Φ` is an exact integer, so the entries are
/// bit-identical to the Euler–Bernoulli form `EI/L³ [12 6L …]`.
pub(crate) fn bending_stiffness(ei: f64, l: f64, phi: f64) -> [[f64; 4]; 4] {
    let a = ei / ((1.0 + phi) * l * l * l);
    [
        [12.0 * a, 6.0 * l * a, -12.0 * a, 6.0 * l * a],
        [
            6.0 * l * a,
            (4.0 + phi) * l * l * a,
            -6.0 * l * a,
            (2.0 - phi) * l * l * a,
        ],
        [-12.0 * a, -6.0 * l * a, 12.0 * a, -6.0 * l * a],
        [
            6.0 * l * a,
            (2.0 - phi) * l * l * a,
            -6.0 * l * a,
            (4.0 + phi) * l * l * a,
        ],
    ]
}

/// Geometric (initial-stress) stiffness of one bending plane for the axial force `N` \[N\]
/// (tension > 0), consistent with the cubic deflection field:
/// `N/(30L) [36 3L −36 3L; 3L 4L² −3L −L²; −36 −3L 36 −3L; 3L −L² −3L 4L²]` (Cook et al.
/// ch. 18). `l` is L \[m\].
pub(crate) fn geometric_stiffness(axial_force: f64, l: f64) -> [[f64; 4]; 4] {
    let g = axial_force / (30.0 * l);
    [
        [36.0 * g, 3.0 * l * g, -36.0 * g, 3.0 * l * g],
        [3.0 * l * g, 4.0 * l * l * g, -3.0 * l * g, -l * l * g],
        [-36.0 * g, -3.0 * l * g, 36.0 * g, -3.0 * l * g],
        [3.0 * l * g, -l * l * g, -3.0 * l * g, 4.0 * l * l * g],
    ]
}

/// Consistent translational mass of one bending plane for the element mass `m = ρA L` \[kg\]:
/// `m/420 [156 22L 54 −13L; 22L 4L² 13L −3L²; 54 13L 156 −22L; −13L −3L² −22L 4L²]`
/// (Przemieniecki §11). `l` is L \[m\].
pub(crate) fn consistent_mass(m: f64, l: f64) -> [[f64; 4]; 4] {
    let b = m / 420.0;
    [
        [156.0 * b, 22.0 * l * b, 54.0 * b, -13.0 * l * b],
        [
            22.0 * l * b,
            4.0 * l * l * b,
            13.0 * l * b,
            -3.0 * l * l * b,
        ],
        [54.0 * b, 13.0 * l * b, 156.0 * b, -22.0 * l * b],
        [
            -13.0 * l * b,
            -3.0 * l * l * b,
            -22.0 * l * b,
            4.0 * l * l * b,
        ],
    ]
}
