//! The 6-component convention shared by every small-strain law and element.
//!
//! Component order is code_aster's: xx, yy, zz, xy, xz, yz.
//! - Stresses hold tensor components (σ_xy is the shear stress).
//! - Strains hold **engineering** shears (γ_xy = 2 ε_xy), so that the B
//!   matrix of an element gives them directly and the work density is the
//!   plain dot product σ·ε.
//! - A tangent `D` maps an engineering strain increment to a stress
//!   increment, dσ = D dε; for isotropic elasticity it is the textbook
//!   Voigt matrix with G on the shear diagonal.
//!
//! code_aster's laws work internally with √2-scaled (Mandel) shears; the
//! conversion happens here, at the border, and nowhere else.

use nalgebra::{Matrix3, SMatrix, SVector};

pub type Vec6 = SVector<f64, 6>;
pub type Mat6 = SMatrix<f64, 6, 6>;

/// Index pairs of the six components, in order.
pub const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];

/// Symmetric tensor from stress-like components.
pub fn stress_to_tensor(s: &Vec6) -> Matrix3<f64> {
    Matrix3::new(s[0], s[3], s[4], s[3], s[1], s[5], s[4], s[5], s[2])
}

/// Stress-like components of a (symmetrised) tensor.
pub fn tensor_to_stress(t: &Matrix3<f64>) -> Vec6 {
    let m = 0.5 * (t + t.transpose());
    Vec6::new(
        m[(0, 0)],
        m[(1, 1)],
        m[(2, 2)],
        m[(0, 1)],
        m[(0, 2)],
        m[(1, 2)],
    )
}

/// Tensor from engineering-strain components (shears halved).
pub fn strain_to_tensor(e: &Vec6) -> Matrix3<f64> {
    stress_to_tensor(&Vec6::new(
        e[0],
        e[1],
        e[2],
        0.5 * e[3],
        0.5 * e[4],
        0.5 * e[5],
    ))
}

/// Engineering-strain components of a tensor (shears doubled).
pub fn tensor_to_strain(t: &Matrix3<f64>) -> Vec6 {
    let s = tensor_to_stress(t);
    Vec6::new(s[0], s[1], s[2], 2.0 * s[3], 2.0 * s[4], 2.0 * s[5])
}

/// Trace of a stress-like vector.
pub fn trace(s: &Vec6) -> f64 {
    s[0] + s[1] + s[2]
}

/// Deviator of a stress-like vector.
pub fn deviator(s: &Vec6) -> Vec6 {
    let m = trace(s) / 3.0;
    Vec6::new(s[0] - m, s[1] - m, s[2] - m, s[3], s[4], s[5])
}

/// s:s for a stress-like (tensor-component) vector.
pub fn double_dot(a: &Vec6, b: &Vec6) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5])
}

/// Von Mises equivalent stress √(3/2 s:s).
pub fn von_mises(s: &Vec6) -> f64 {
    let d = deviator(s);
    (1.5 * double_dot(&d, &d)).sqrt()
}

/// 1 ⊗ 1 in this convention.
pub fn one_one() -> Mat6 {
    let mut m = Mat6::zeros();
    for i in 0..3 {
        for j in 0..3 {
            m[(i, j)] = 1.0;
        }
    }
    m
}

/// The deviatoric projector I_dev = I_sym − ⅓ 1⊗1 mapping engineering
/// strains to tensor-component deviators (½ on the shear diagonal).
pub fn deviatoric_projector() -> Mat6 {
    let mut m = Mat6::zeros();
    for i in 0..3 {
        m[(i, i)] = 1.0;
        m[(i + 3, i + 3)] = 0.5;
    }
    m - one_one() / 3.0
}

/// Isotropic elastic tangent K 1⊗1 + 2μ I_dev.
pub fn isotropic_elastic(k: f64, mu: f64) -> Mat6 {
    one_one() * k + deviatoric_projector() * (2.0 * mu)
}
