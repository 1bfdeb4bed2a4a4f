//! `DEFORMATION='GDEF_LOG'`: any small-strain law driven by the Lagrangian
//! logarithmic (Hencky) strain E = ½ ln C, C = FᵀF, in the framework of
//! Miehe, Apel & Lambrecht (CMAME 191, 2002) that code_aster implements in
//! `nmdlog` / `prelog` / `poslog` (shared/docs/notes/john-cook-gdef-log.md,
//! Part B).
//!
//! Pre-processing: ΔE = E(F_{n+1}) − E(F_n) and the stress at the start of
//! the step is T_n, the stress work-conjugate to E, read back from the six
//! extra internal variables (the Cauchy stress is not used by the law).
//! The small-strain law then integrates the step unchanged and returns T
//! and ∂T/∂E.
//!
//! Post-processing: the second Piola–Kirchhoff stress S = T : P with
//! P = ∂E/∂E_GL = 2∂E/∂C, and Cauchy σ = J⁻¹ F S Fᵀ (SIEF_ELGA). The
//! element (the total-Lagrangian arm shared with SIMO_MIEHE) takes the
//! Kirchhoff stress τ = F S Fᵀ and ∂τ/∂F, so the tangent returned here is
//! ∂τ/∂F = chain rule of τ = F S(E_GL(F)) Fᵀ with
//!   dS = P : D : P : dE_GL + T : L : dE_GL,   L = ∂²E/∂E_GL².
//!
//! P and T : L are computed in the principal basis of C with the
//! Daleckii–Krein formulas: for an isotropic function f(C) = Σ f(λᵢ)Nᵢ⊗Nᵢ,
//! (Df[H])ᵢⱼ = f[λᵢ,λⱼ] H̃ᵢⱼ and (D²f[H,K])ᵢⱼ = Σₖ f[λᵢ,λₖ,λⱼ](H̃ᵢₖK̃ₖⱼ +
//! K̃ᵢₖH̃ₖⱼ), with the divided differences f[·] of f = ln (H̃ = QᵀHQ). The
//! divided differences are evaluated without cancellation when eigenvalues
//! coincide (atanh form, and a Taylor expansion for a small spread), so
//! repeated eigenvalues — the undeformed state, any uniaxial state — need
//! no special case. This differs from code_aster's `deflg2` only on exact
//! ties in 3D, where the note found two inconsistent limits in code_aster.
//!
//! Internal variables: the law's own, then TXX, TYY, TZZ, TXY, TXZ, TYZ
//! holding T with √2-scaled shears (code_aster's VARI_ELGA layout; 2D
//! elements keep TXZ = TYZ = 0 since their F has no out-of-plane shear).

use nalgebra::{Matrix3, SymmetricEigen};

use super::john_cook;
use super::simo_miehe::{FiniteStrainInput, FiniteStrainOutput, Mat9};
use super::vmis_cine_line;
use super::vmis_isot_line;
use super::vmis_isot_puis;
use super::vmis_isot_trac;
use super::voigt::{stress_to_tensor, tensor_to_strain, tensor_to_stress};
use super::{
    IntegrationFailure, InternalVars, LawMetadata, SmallStrainBehaviour, SmallStrainInput,
    StrainMeasure, TangentKind, Vec6,
};

/// Names of the six extra variables.
pub const EXTRA: [&str; 6] = ["TXX", "TYY", "TZZ", "TXY", "TXZ", "TYZ"];

/// VMIS_ISOT_LINE + GDEF_LOG: V1..V2 then the six extra variables.
pub static ISOT_LINE_LOG: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_LINE",
    internal_variables: &[
        "EPSPEQ", "INDIPLAS", "TXX", "TYY", "TZZ", "TXY", "TXZ", "TYZ",
    ],
    strain_measures: &[StrainMeasure::GdefLog],
    tensor_variables: &[2],
};

/// VMIS_ISOT_TRAC + GDEF_LOG: as VMIS_ISOT_LINE.
pub static ISOT_TRAC_LOG: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_TRAC",
    internal_variables: &[
        "EPSPEQ", "INDIPLAS", "TXX", "TYY", "TZZ", "TXY", "TXZ", "TYZ",
    ],
    strain_measures: &[StrainMeasure::GdefLog],
    tensor_variables: &[2],
};

/// VMIS_ISOT_PUIS + GDEF_LOG: as VMIS_ISOT_LINE.
pub static ISOT_PUIS_LOG: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_PUIS",
    internal_variables: ISOT_LINE_LOG.internal_variables,
    strain_measures: &[StrainMeasure::GdefLog],
    tensor_variables: &[2],
};

/// VMIS_CINE_LINE + GDEF_LOG: the back stress X (of the log-strain
/// formulation) and INDIPLAS, then the six extra variables.
pub static CINE_LINE_LOG: LawMetadata = LawMetadata {
    name: "VMIS_CINE_LINE",
    internal_variables: &[
        "XCINXX", "XCINYY", "XCINZZ", "XCINXY", "XCINXZ", "XCINYZ", "INDIPLAS", "TXX", "TYY",
        "TZZ", "TXY", "TXZ", "TYZ",
    ],
    strain_measures: &[StrainMeasure::GdefLog],
    tensor_variables: &[0, 7],
};

/// VMIS_JOHN_COOK + GDEF_LOG: V1..V5 then the six extra variables.
pub static JOHN_COOK_LOG: LawMetadata = LawMetadata {
    name: "VMIS_JOHN_COOK",
    internal_variables: &[
        "EPSPEQ", "INDIPLAS", "DEPSPEQ", "DINSTM", "DDISSM", "TXX", "TYY", "TZZ", "TXY", "TXZ",
        "TYZ",
    ],
    strain_measures: &[StrainMeasure::GdefLog],
    tensor_variables: &[5],
};

/// A finite-strain law as the total-Lagrangian element sees it: F_n and
/// F_{n+1} in, Kirchhoff τ, Cauchy σ and ∂τ/∂F out.
pub trait FiniteStrainBehaviour: Send + Sync {
    fn metadata(&self) -> &'static LawMetadata;
    fn initial_internal(&self) -> InternalVars {
        InternalVars::zeros(self.metadata().internal_variables.len())
    }
    fn integrate(
        &self,
        input: &FiniteStrainInput,
    ) -> Result<FiniteStrainOutput, IntegrationFailure>;
}

/// A small-strain law wrapped in the logarithmic strain measure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GdefLog<L> {
    pub law: L,
}

const SQRT2: f64 = std::f64::consts::SQRT_2;

/// T from the six extra variables (√2-scaled shears).
pub fn stress_from_extra(v: &[f64]) -> Vec6 {
    Vec6::new(v[0], v[1], v[2], v[3] / SQRT2, v[4] / SQRT2, v[5] / SQRT2)
}

fn extra_from_stress(t: &Vec6) -> [f64; 6] {
    [t[0], t[1], t[2], t[3] * SQRT2, t[4] * SQRT2, t[5] * SQRT2]
}

/// ln[a, b] = (ln a − ln b)/(a − b), 1/a for a = b, without cancellation.
pub fn ln_dd1(a: f64, b: f64) -> f64 {
    let x = (a - b) / (a + b);
    if x.abs() < 1e-2 {
        // 2 atanh(x)/(x (a+b)) with atanh(x)/x = Σ x^{2k}/(2k+1).
        let x2 = x * x;
        let series = 1.0 + x2 * (1.0 / 3.0 + x2 * (1.0 / 5.0 + x2 * (1.0 / 7.0 + x2 / 9.0)));
        2.0 * series / (a + b)
    } else {
        2.0 * x.atanh() / (a - b)
    }
}

/// ln[a, b, c], symmetric in its arguments; −1/(2a²) when all are equal.
pub fn ln_dd2(a: f64, b: f64, c: f64) -> f64 {
    let mut x = [a, b, c];
    x.sort_by(|p, q| p.total_cmp(q));
    let m = (x[0] + x[1] + x[2]) / 3.0;
    if x[2] - x[0] <= 1e-3 * m {
        // Σ_k ln^{(2+k)}(m)/(2+k)! h_k(δ), δ = x − m (h₁ = 0).
        let d = [x[0] - m, x[1] - m, x[2] - m];
        let mut h2 = 0.0;
        let mut h3 = 0.0;
        for i in 0..3 {
            for j in i..3 {
                h2 += d[i] * d[j];
                for l in j..3 {
                    h3 += d[i] * d[j] * d[l];
                }
            }
        }
        let m2 = m * m;
        -1.0 / (2.0 * m2) - h2 / (4.0 * m2 * m2) + h3 / (5.0 * m2 * m2 * m)
    } else {
        (ln_dd1(x[1], x[2]) - ln_dd1(x[0], x[1])) / (x[2] - x[0])
    }
}

/// The principal data of C: eigenvalues, eigenvectors (columns), and the
/// first and second divided differences of ln at them.
pub struct LogSpectrum {
    pub lambda: [f64; 3],
    pub q: Matrix3<f64>,
    dd1: Matrix3<f64>,
    dd2: [[[f64; 3]; 3]; 3],
}

impl LogSpectrum {
    /// Fails (None) when C is not positive definite to machine precision.
    pub fn new(c: &Matrix3<f64>) -> Option<LogSpectrum> {
        let eig = SymmetricEigen::new(*c);
        let lambda = [eig.eigenvalues[0], eig.eigenvalues[1], eig.eigenvalues[2]];
        if lambda.iter().any(|l| !(l.is_finite() && *l > f64::EPSILON)) {
            return None;
        }
        let dd1 = Matrix3::from_fn(|i, j| ln_dd1(lambda[i], lambda[j]));
        let mut dd2 = [[[0.0; 3]; 3]; 3];
        for (i, di) in dd2.iter_mut().enumerate() {
            for (k, dik) in di.iter_mut().enumerate() {
                for (j, v) in dik.iter_mut().enumerate() {
                    *v = ln_dd2(lambda[i], lambda[k], lambda[j]);
                }
            }
        }
        Some(LogSpectrum {
            lambda,
            q: eig.eigenvectors,
            dd1,
            dd2,
        })
    }

    /// E = ½ ln C.
    pub fn log_strain(&self) -> Matrix3<f64> {
        let d = Matrix3::from_diagonal(&nalgebra::Vector3::new(
            0.5 * self.lambda[0].ln(),
            0.5 * self.lambda[1].ln(),
            0.5 * self.lambda[2].ln(),
        ));
        let e = self.q * d * self.q.transpose();
        0.5 * (e + e.transpose())
    }

    /// P : H = D ln(C)[H] (P = 2∂E/∂C is self-adjoint, so also Pᵀ : H).
    pub fn project(&self, h: &Matrix3<f64>) -> Matrix3<f64> {
        let ht = self.q.transpose() * h * self.q;
        let m = ht.component_mul(&self.dd1);
        let out = self.q * m * self.q.transpose();
        0.5 * (out + out.transpose())
    }

    /// D² ln(C)[T, H].
    pub fn second(&self, t: &Matrix3<f64>, h: &Matrix3<f64>) -> Matrix3<f64> {
        let tt = self.q.transpose() * t * self.q;
        let ht = self.q.transpose() * h * self.q;
        let mut m = Matrix3::zeros();
        for i in 0..3 {
            for j in i..3 {
                let mut v = 0.0;
                for k in 0..3 {
                    v += self.dd2[i][k][j] * (tt[(i, k)] * ht[(k, j)] + ht[(i, k)] * tt[(k, j)]);
                }
                m[(i, j)] = v;
                m[(j, i)] = v;
            }
        }
        self.q * m * self.q.transpose()
    }
}

impl<L: SmallStrainBehaviour> GdefLog<L> {
    pub fn new(law: L) -> GdefLog<L> {
        GdefLog { law }
    }

    fn inner_count(&self) -> usize {
        self.law.metadata().internal_variables.len()
    }

    fn fail(&self, message: impl std::fmt::Display) -> IntegrationFailure {
        IntegrationFailure::not_converged(self.law.metadata().name, message)
    }
}

impl<L: SmallStrainBehaviour> FiniteStrainBehaviour for GdefLog<L> {
    fn metadata(&self) -> &'static LawMetadata {
        match self.law.metadata().name {
            "VMIS_JOHN_COOK" => &JOHN_COOK_LOG,
            "VMIS_ISOT_TRAC" => &ISOT_TRAC_LOG,
            "VMIS_ISOT_PUIS" => &ISOT_PUIS_LOG,
            "VMIS_CINE_LINE" => &CINE_LINE_LOG,
            _ => &ISOT_LINE_LOG,
        }
    }

    fn integrate(
        &self,
        input: &FiniteStrainInput,
    ) -> Result<FiniteStrainOutput, IntegrationFailure> {
        let name = self.law.metadata().name;
        let ni = self.inner_count();
        if input.internal.len() != ni + 6 {
            return Err(IntegrationFailure::invalid(
                name,
                format!(
                    "{} internal variables given, {} expected under GDEF_LOG",
                    input.internal.len(),
                    ni + 6
                ),
            ));
        }
        let (f_n, f) = (input.f_n, input.f_np1);
        if f_n.iter().chain(f.iter()).any(|v| !v.is_finite()) {
            return Err(IntegrationFailure::invalid(
                name,
                "non-finite deformation gradient",
            ));
        }
        let (j_n, j) = (f_n.determinant(), f.determinant());
        if j_n <= f64::EPSILON || j <= f64::EPSILON {
            return Err(self.fail(format!("det F = {j:e} (start of step {j_n:e})")));
        }
        let spec_n = LogSpectrum::new(&(f_n.transpose() * f_n))
            .ok_or_else(|| self.fail("C = FᵀF not positive definite at the start of the step"))?;
        let spec = LogSpectrum::new(&(f.transpose() * f))
            .ok_or_else(|| self.fail("C = FᵀF not positive definite"))?;
        let e_n = spec_n.log_strain();
        let e = spec.log_strain();
        let t_n = stress_from_extra(&input.internal[ni..]);
        let out = self.law.integrate(&SmallStrainInput {
            stress: t_n,
            internal: &input.internal[..ni],
            strain_increment: tensor_to_strain(&(e - e_n)),
            dt: input.dt,
            tangent: input.tangent,
        })?;
        let t = stress_to_tensor(&out.stress);
        let s = spec.project(&t);
        let tau = f * s * f.transpose();
        let tau = 0.5 * (tau + tau.transpose());
        let mut internal = InternalVars::zeros(ni + 6);
        internal.as_mut_slice()[..ni].copy_from_slice(out.internal.as_slice());
        internal.as_mut_slice()[ni..].copy_from_slice(&extra_from_stress(&out.stress));
        let dtau_df = match input.tangent {
            TangentKind::None => None,
            _ => {
                let d = out.tangent.ok_or_else(|| {
                    IntegrationFailure::invalid(name, "the law returned no tangent")
                })?;
                let mut c = Mat9::zeros();
                for k in 0..3 {
                    for l in 0..3 {
                        let mut df = Matrix3::zeros();
                        df[(k, l)] = 1.0;
                        let ft_df = f.transpose() * df;
                        let de_gl = 0.5 * (ft_df + ft_df.transpose());
                        let de = spec.project(&de_gl);
                        let dt_ = stress_to_tensor(&(d * tensor_to_strain(&de)));
                        let ds = spec.project(&dt_) + spec.second(&t, &(2.0 * de_gl));
                        let dtau = df * s * f.transpose()
                            + f * s * df.transpose()
                            + f * ds * f.transpose();
                        for a in 0..3 {
                            for b in 0..3 {
                                c[(3 * a + b, 3 * k + l)] = dtau[(a, b)];
                            }
                        }
                    }
                }
                Some(c)
            }
        };
        Ok(FiniteStrainOutput {
            kirchhoff: tau,
            cauchy: tau / j,
            internal,
            dtau_df,
            regime: out.regime,
        })
    }
}

/// The laws that accept GDEF_LOG in aster.
pub type IsotLineLog = GdefLog<vmis_isot_line::VmisIsotLine>;
pub type IsotTracLog = GdefLog<vmis_isot_trac::VmisIsotTrac>;
pub type IsotPuisLog = GdefLog<vmis_isot_puis::VmisIsotPuis>;
pub type CineLineLog = GdefLog<vmis_cine_line::VmisCineLine>;
pub type JohnCookLog = GdefLog<john_cook::VmisJohnCook>;

/// The Cauchy stress of a T state at F (post-processing alone).
pub fn cauchy_of(f: &Matrix3<f64>, t: &Vec6) -> Option<Vec6> {
    let spec = LogSpectrum::new(&(f.transpose() * f))?;
    let s = spec.project(&stress_to_tensor(t));
    Some(tensor_to_stress(&(f * s * f.transpose() / f.determinant())))
}
