//! `VMIS_ISOT_LINE` under `DEFORMATION='SIMO_MIEHE'`: multiplicative
//! finite-strain von Mises plasticity with linear isotropic hardening
//! (code_aster's VMIS2ISOT_LINE path through `lcpivm`).
//!
//! Sources: J.C. Simo, "Algorithms for static and dynamic multiplicative
//! plasticity that preserve the classical return mapping schemes of the
//! infinitesimal theory", CMAME 99 (1992) 61-112; Simo & Miehe, CMAME 98
//! (1992); Simo & Hughes, *Computational Inelasticity* (1998), Box 9.1.
//!
//! Model. F = Fᵉ Fᵖ with det Fᵖ = 1. The state is b̄ᵉ = J^{-2/3} Fᵉ Fᵉᵀ
//! (det b̄ᵉ = 1) and p. Kirchhoff stress
//!   τ = ½K (J² − 1) 1 + μ dev b̄ᵉ,
//! yield ‖dev τ‖ ≤ √(2/3) (SY + H p).
//!
//! Step n → n+1 (Box 9.1):
//! 1. f̄ = (det f)^{-1/3} f with f = F_{n+1} F_n⁻¹; b̄ᵉ_tr = f̄ b̄ᵉ_n f̄ᵀ.
//! 2. s_tr = μ dev b̄ᵉ_tr; if ‖s_tr‖ ≤ √(2/3) R(p_n) the step is elastic.
//! 3. Otherwise, with μ̄ = μ tr(b̄ᵉ_tr)/3, the radial return of the small
//!    strain theory: Δγ = (‖s_tr‖ − √(2/3)R(p_n)) / (2μ̄ + 2H/3),
//!    s = s_tr − 2μ̄Δγ n, p_{n+1} = p_n + √(2/3)Δγ.
//! 4. b̄ᵉ_{n+1} = s/μ + x 1, where x is chosen so that det b̄ᵉ_{n+1} = 1
//!    (the "trace correction" of Simo 1992 §4: it keeps the plastic flow
//!    exactly isochoric; Box 9.1's x = tr(b̄ᵉ_tr)/3 does so only to first
//!    order). x does not enter τ.
//!
//! The tangent returned is ∂τ/∂F_{n+1} (9×9), derived in closed form from
//! the same chain (trial state, then the scalar return), because the
//! element needs ∂(τ ∇ₓN)/∂u and the Lie-derivative spatial tangent would
//! have to be converted back anyway. It is not symmetric in general.

use nalgebra::{Matrix3, SMatrix};

use super::vmis_isot_line::IsotropicHardening;
use super::vmis_isot_puis::PowerHardening;
use super::vmis_isot_trac::TractionCurve;
use super::voigt::{stress_to_tensor, tensor_to_stress};
use super::{
    EcroLineParams, ElasParams, IntegrationFailure, InternalVars, LawMetadata, Regime,
    StrainMeasure, TangentKind,
};

/// ∂τ_ij/∂F_kl at row 3i+j, column 3k+l.
pub type Mat9 = SMatrix<f64, 9, 9>;

/// V1 = EPSPEQ (p), V2 = INDIPLAS, V3..V8 = b̄ᵉ − 1 (xx, yy, zz, xy, xz, yz).
///
/// Storing b̄ᵉ − 1 rather than b̄ᵉ makes all-zero variables the virgin
/// state, as for every other law. code_aster's own extra variables for
/// SIMO_MIEHE are not settled (semantics.md §14); only V1 and V2 are meant
/// to compare with its VARI_ELGA.
pub static METADATA: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_LINE",
    internal_variables: &[
        "EPSPEQ", "INDIPLAS", "BE_XX", "BE_YY", "BE_ZZ", "BE_XY", "BE_XZ", "BE_YZ",
    ],
    strain_measures: &[StrainMeasure::SimoMiehe],
    tensor_variables: &[2],
};

/// Start-of-step state and the deformation gradients of the step.
#[derive(Debug, Clone, Copy)]
pub struct FiniteStrainInput<'a> {
    pub f_n: Matrix3<f64>,
    pub f_np1: Matrix3<f64>,
    pub internal: &'a [f64],
    pub dt: f64,
    pub tangent: TangentKind,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiniteStrainOutput {
    /// Kirchhoff stress τ.
    pub kirchhoff: Matrix3<f64>,
    /// Cauchy stress σ = τ/J (what SIEF_ELGA holds).
    pub cauchy: Matrix3<f64>,
    pub internal: InternalVars,
    /// ∂τ/∂F_{n+1}; `Elastic` gives the derivative of the trial state.
    pub dtau_df: Option<Mat9>,
    pub regime: Regime,
}

/// What the update needs from the start of the step alone (F_n and the
/// internal variables), the same at every Newton iteration of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepStart {
    /// det F_n.
    pub j_n: f64,
    /// A = F_n⁻¹ b̄ᵉ_n F_n⁻ᵀ.
    pub a: Matrix3<f64>,
}

/// [`FiniteStrainOutput`] without the tangent: what the explicit step
/// reads at each Gauss point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StressUpdate {
    pub kirchhoff: Matrix3<f64>,
    pub cauchy: Matrix3<f64>,
    pub internal: InternalVars,
    pub regime: Regime,
}

/// The trial state and the return's scalars, which the tangent derives.
struct Trial {
    b: Matrix3<f64>,
    c: f64,
    i_e: f64,
    s_tr: Matrix3<f64>,
    q: f64,
    c0: f64,
    plastic: bool,
    beta: f64,
    m: f64,
    /// R' at the end of the step (H for a line).
    h: f64,
}

/// VMIS_ISOT_TRAC under SIMO_MIEHE (code_aster's VMIS2ISOT_TRAC): the
/// same variables as VMIS_ISOT_LINE's.
pub static TRAC_METADATA: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_TRAC",
    internal_variables: METADATA.internal_variables,
    strain_measures: &[StrainMeasure::SimoMiehe],
    tensor_variables: &[2],
};

/// VMIS_ISOT_PUIS under SIMO_MIEHE (code_aster's catalogue lists
/// SIMO_MIEHE for it): the same variables as VMIS_ISOT_LINE's.
pub static PUIS_METADATA: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_PUIS",
    internal_variables: METADATA.internal_variables,
    strain_measures: &[StrainMeasure::SimoMiehe],
    tensor_variables: &[2],
};

/// The isotropic hardenings other than the line, whose return goes
/// through [`IsotropicHardening::return_map`] (the line keeps its closed
/// form, written as it always was).
#[derive(Debug, Clone, PartialEq)]
pub enum Hardening {
    /// VMIS_ISOT_TRAC.
    Traction(TractionCurve),
    /// VMIS_ISOT_PUIS.
    Power(PowerHardening),
}

impl Hardening {
    fn metadata(&self) -> &'static LawMetadata {
        match self {
            Hardening::Traction(_) => &TRAC_METADATA,
            Hardening::Power(_) => &PUIS_METADATA,
        }
    }
}

impl IsotropicHardening for Hardening {
    fn yield_stress(&self, p: f64) -> f64 {
        match self {
            Hardening::Traction(c) => c.yield_stress(p),
            Hardening::Power(c) => c.yield_stress(p),
        }
    }
    fn return_map(
        &self,
        q_tr: f64,
        p_n: f64,
        three_mu: f64,
    ) -> Result<(f64, f64), IntegrationFailure> {
        match self {
            Hardening::Traction(c) => c.return_map(q_tr, p_n, three_mu),
            Hardening::Power(c) => c.return_map(q_tr, p_n, three_mu),
        }
    }
    fn slope(&self, p: f64) -> f64 {
        match self {
            Hardening::Traction(c) => c.slope(p),
            Hardening::Power(c) => c.slope(p),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct SimoMiehe {
    pub elas: ElasParams,
    /// SY and E_T of a line; for another hardening SY = R(0), E_T unused.
    pub ecro: EcroLineParams,
    mu: f64,
    bulk: f64,
    h: f64,
    /// R(p) of VMIS_ISOT_TRAC or VMIS_ISOT_PUIS; None: the line SY + H p.
    curve: Option<Hardening>,
}

impl SimoMiehe {
    pub fn new(elas: ElasParams, ecro: EcroLineParams) -> SimoMiehe {
        SimoMiehe {
            elas,
            ecro,
            mu: elas.mu(),
            bulk: elas.bulk(),
            h: ecro.hardening(&elas),
            curve: None,
        }
    }

    /// VMIS_ISOT_TRAC: `elas` holds the curve's Young's modulus
    /// ([`VmisIsotTrac::new`](super::vmis_isot_trac::VmisIsotTrac::new)).
    pub fn with_curve(elas: ElasParams, curve: TractionCurve) -> SimoMiehe {
        SimoMiehe::with_hardening(elas, Hardening::Traction(curve))
    }

    /// Any hardening of [`Hardening`] (VMIS_ISOT_PUIS: `elas` is ELAS's).
    pub fn with_hardening(elas: ElasParams, hardening: Hardening) -> SimoMiehe {
        SimoMiehe {
            elas,
            ecro: EcroLineParams {
                sy: hardening.yield_stress(0.0),
                d_sigm_epsi: 0.0,
            },
            mu: elas.mu(),
            bulk: elas.bulk(),
            h: 0.0,
            curve: Some(hardening),
        }
    }

    pub fn metadata(&self) -> &'static LawMetadata {
        match &self.curve {
            Some(h) => h.metadata(),
            None => &METADATA,
        }
    }

    /// The plastic multiplier Δγ of the return (‖s‖ = ‖s_tr‖ − 2μ̄Δγ =
    /// √(2/3) R(p_n + √(2/3) Δγ), q = ‖s_tr‖, c0 = √(2/3) R(p_n)), R' at
    /// its end, and the c0 of R's tangent line at the end point
    /// (Δγ = (q − c0)/(2μ̄ + 2R'/3) with it, the form the tangent
    /// differentiates: its derivatives in q and μ̄ are those of the exact
    /// equation for any R smooth at the end point; c0 itself for a
    /// segment the step did not leave). For a line it is the closed form
    /// written as it always was (B's answer to the bit); a traction curve
    /// or a power law solves the same equation in terms of the equivalent
    /// stress √(3/2) q, whose multiplier is 3μ̄.
    fn plastic_multiplier(
        &self,
        q: f64,
        c0: f64,
        p_n: f64,
        mu_bar: f64,
    ) -> Result<(f64, f64, f64), IntegrationFailure> {
        match &self.curve {
            None => Ok(((q - c0) / (2.0 * mu_bar + 2.0 * self.h / 3.0), self.h, c0)),
            Some(curve) => {
                let (dp, h) = curve.return_map(1.5f64.sqrt() * q, p_n, 3.0 * mu_bar)?;
                let dgamma = dp * 1.5f64.sqrt();
                Ok((dgamma, h, q - (2.0 * mu_bar + 2.0 * h / 3.0) * dgamma))
            }
        }
    }

    /// R' on the right of `p` (H for a line).
    fn slope(&self, p: f64) -> f64 {
        match &self.curve {
            None => self.h,
            Some(curve) => curve.slope(p),
        }
    }

    pub fn initial_internal(&self) -> InternalVars {
        InternalVars::zeros(METADATA.internal_variables.len())
    }

    /// Plastic modulus H = E·E_T/(E − E_T).
    pub fn hardening_modulus(&self) -> f64 {
        self.h
    }

    /// Yield stress R(p) = SY + H p, or the traction curve's or the
    /// power law's (a Kirchhoff equivalent stress).
    pub fn yield_stress(&self, p: f64) -> f64 {
        match &self.curve {
            None => self.ecro.sy + self.h * p,
            Some(c) => c.yield_stress(p),
        }
    }

    /// b̄ᵉ stored in internal variables V3..V8.
    pub fn elastic_left_cauchy_green(internal: &[f64]) -> Matrix3<f64> {
        let v = super::Vec6::from_column_slice(&internal[2..8]);
        stress_to_tensor(&v) + Matrix3::identity()
    }

    pub fn integrate(
        &self,
        input: &FiniteStrainInput,
    ) -> Result<FiniteStrainOutput, IntegrationFailure> {
        self.integrate_columns(input, 0x1ff)
    }

    /// [`SimoMiehe::integrate`] computing only the columns 3k + l of
    /// ∂τ/∂F whose bit is set in `columns` (the others are zero): an
    /// axisymmetric element reads 5 of the 9, and each column costs as
    /// much as the stress update.
    pub fn integrate_columns(
        &self,
        input: &FiniteStrainInput,
        columns: u16,
    ) -> Result<FiniteStrainOutput, IntegrationFailure> {
        // Computed once: the checks read them too.
        let j = input.f_np1.determinant();
        let j_n = input.f_n.determinant();
        self.check(input, j_n, j)?;
        let start = Self::start(input, j_n)?;
        self.finish(input, j, &start, columns)
    }

    /// The quantities of the start of the step, after every check of
    /// [`SimoMiehe::integrate_columns`] on `input`: an element keeps them
    /// per Gauss point for the Newton iterations of a step (F_n and the
    /// internal variables do not change there) and passes them to
    /// [`SimoMiehe::integrate_with_start`].
    pub fn step_start(&self, input: &FiniteStrainInput) -> Result<StepStart, IntegrationFailure> {
        let j = input.f_np1.determinant();
        let j_n = input.f_n.determinant();
        self.check(input, j_n, j)?;
        Self::start(input, j_n)
    }

    /// [`SimoMiehe::integrate_columns`] with the start of the step
    /// `start` computed by [`SimoMiehe::step_start`] from the same F_n and
    /// internal variables as `input`'s: the same result to the bit, and
    /// the same failures (those of the start of the step were checked
    /// when `start` was computed; these are F's and the time step's, in
    /// the order of the full check).
    pub fn integrate_with_start(
        &self,
        input: &FiniteStrainInput,
        start: &StepStart,
        columns: u16,
    ) -> Result<FiniteStrainOutput, IntegrationFailure> {
        let name = self.metadata().name;
        let j = input.f_np1.determinant();
        if input.f_np1.iter().any(|v| !v.is_finite()) {
            return Err(IntegrationFailure::invalid(
                name,
                "non-finite deformation gradient",
            ));
        }
        if !(input.dt.is_finite() && input.dt >= 0.0) {
            return Err(IntegrationFailure::invalid(
                name,
                format!("invalid time step {}", input.dt),
            ));
        }
        if j <= 0.0 {
            return Err(IntegrationFailure::not_converged(
                name,
                "non-positive volume change J",
            ));
        }
        self.finish(input, j, start, columns)
    }

    /// b̄ᵉ_n, F_n⁻¹ and A = F_n⁻¹ b̄ᵉ_n F_n⁻ᵀ (`input` checked).
    fn start(input: &FiniteStrainInput, j_n: f64) -> Result<StepStart, IntegrationFailure> {
        let be_n = Self::elastic_left_cauchy_green(input.internal);
        let fn_inv = input.f_n.try_inverse().ok_or_else(|| {
            IntegrationFailure::invalid(
                METADATA.name,
                "singular deformation gradient at the start of the step",
            )
        })?;
        Ok(StepStart {
            j_n,
            a: fn_inv * be_n * fn_inv.transpose(),
        })
    }

    /// The stress update alone, for the explicit step (one evaluation per
    /// step, no tangent): the same checks and the same arithmetic as
    /// [`SimoMiehe::integrate_columns`] with [`TangentKind::None`], so the
    /// same result to the bit, without the 9 × 9 tangent slot in the
    /// output. `j_n` and `j` are `f_n.determinant()` and
    /// `f_np1.determinant()` of `input` (the element computed them for its
    /// own check); `fn_inv`, when given, is `f_n.try_inverse()` (the
    /// element's F⁻¹ of the previous step, whose F is this step's F_n).
    pub fn integrate_stress(
        &self,
        input: &FiniteStrainInput,
        j_n: f64,
        j: f64,
        fn_inv: Option<&Matrix3<f64>>,
    ) -> Result<StressUpdate, IntegrationFailure> {
        debug_assert_eq!(j_n.to_bits(), input.f_n.determinant().to_bits());
        debug_assert_eq!(j.to_bits(), input.f_np1.determinant().to_bits());
        self.check(input, j_n, j)?;
        let start = match fn_inv {
            Some(fn_inv) => {
                let be_n = Self::elastic_left_cauchy_green(input.internal);
                StepStart {
                    j_n,
                    a: fn_inv * be_n * fn_inv.transpose(),
                }
            }
            None => Self::start(input, j_n)?,
        };
        self.update(input, j, &start).map(|(out, _)| out)
    }

    /// The stress update from the start of the step (`j` = det F), with
    /// what the tangent is derived from.
    fn update(
        &self,
        input: &FiniteStrainInput,
        j: f64,
        start: &StepStart,
    ) -> Result<(StressUpdate, Trial), IntegrationFailure> {
        let name = self.metadata().name;
        let f = input.f_np1;
        let (j_n, a) = (start.j_n, start.a);
        let (mu, k) = (self.mu, self.bulk);
        let p_n = input.internal[0];
        // b̄ᵉ_tr = (J_n/J)^{2/3} F A Fᵀ with A = F_n⁻¹ b̄ᵉ_n F_n⁻ᵀ.
        let b = f * a * f.transpose();
        let c = (j_n / j).powf(2.0 / 3.0);
        let be_tr = b * c;
        let i_e = be_tr.trace() / 3.0;
        let s_tr = (be_tr - Matrix3::identity() * i_e) * mu;
        let q = s_tr.norm();
        let c0 = (2.0f64 / 3.0).sqrt() * self.yield_stress(p_n);
        let pressure_part = Matrix3::identity() * (0.5 * k * (j * j - 1.0));

        // The prediction of a step (a tangent asked at F = F_n, code_aster's
        // RIGI_MECA_TANG) takes its regime from the previous step's
        // indicator V2, as `lcpivm` does (`line = nint(vim(2))`), and a
        // plastic one gets the tangent of a zero multiplier (`lcpitg` with
        // dp = 0). The sign of q − c0 there is round-off of the converged
        // return: points of one cell split between the regimes, and in
        // perfect plasticity the plastic ones have no stiffness along n, so
        // the predicted increment could invert the cell.
        let prediction = input.tangent != TangentKind::None && input.f_np1 == input.f_n;
        let plastic = if prediction {
            input.internal[1] >= 0.5 && q > 0.0
        } else {
            q > c0
        };
        let mut h = self.h;
        let mut c0_segment = c0;
        let (s, be_new, p_new, beta, m) = if prediction {
            if plastic {
                let mu_bar = mu * i_e;
                h = self.slope(p_n);
                c0_segment = q;
                (s_tr, be_tr, p_n, 1.0, mu_bar / (mu_bar + h / 3.0))
            } else {
                (s_tr, be_tr, p_n, 1.0, 0.0)
            }
        } else if plastic {
            let mu_bar = mu * i_e;
            let dgamma;
            (dgamma, h, c0_segment) = self.plastic_multiplier(q, c0, p_n, mu_bar)?;
            let m = mu_bar / (mu_bar + h / 3.0);
            let beta = 1.0 - 2.0 * mu_bar * dgamma / q;
            let s = s_tr * beta;
            let dev_be = s / mu;
            let x = unit_determinant_shift(&dev_be, i_e).ok_or_else(|| {
                IntegrationFailure::not_converged(name, "trace correction of b̄ᵉ did not converge")
            })?;
            let p = p_n + (2.0f64 / 3.0).sqrt() * dgamma;
            (s, dev_be + Matrix3::identity() * x, p, beta, m)
        } else {
            (s_tr, be_tr, p_n, 1.0, 0.0)
        };
        let tau = pressure_part + s;

        let mut internal = self.initial_internal();
        let v = internal.as_mut_slice();
        v[0] = p_new;
        v[1] = if plastic { 1.0 } else { 0.0 };
        v[2..8].copy_from_slice(tensor_to_stress(&(be_new - Matrix3::identity())).as_slice());
        Ok((
            StressUpdate {
                kirchhoff: tau,
                cauchy: tau / j,
                internal,
                regime: if plastic {
                    Regime::Plastic
                } else {
                    Regime::Elastic
                },
            },
            Trial {
                b,
                c,
                i_e,
                s_tr,
                q,
                c0: c0_segment,
                plastic,
                beta,
                m,
                h,
            },
        ))
    }

    /// The update and its tangent from the start of the step (`j` = det F).
    fn finish(
        &self,
        input: &FiniteStrainInput,
        j: f64,
        start: &StepStart,
        columns: u16,
    ) -> Result<FiniteStrainOutput, IntegrationFailure> {
        let name = self.metadata().name;
        let f = input.f_np1;
        let a = start.a;
        let (mu, k) = (self.mu, self.bulk);
        let (out, trial) = self.update(input, j, start)?;
        let Trial {
            b,
            c,
            i_e,
            s_tr,
            q,
            c0,
            plastic,
            beta,
            m,
            h,
        } = trial;

        let dtau_df = match input.tangent {
            TangentKind::None => None,
            kind => {
                // F⁻¹ only here: the stress does not need it (J > 0 was
                // checked, so F is invertible).
                let f_inv = f.try_inverse().ok_or_else(|| {
                    IntegrationFailure::invalid(
                        name,
                        "singular deformation gradient at the end of the step",
                    )
                })?;
                let with_return = plastic && kind == TangentKind::Consistent;
                let mut d = Mat9::zeros();
                // dF = e_k ⊗ e_l: dF A Fᵀ = e_k ⊗ (A Fᵀ)_{l·}, and
                // F A dFᵀ is its transpose (A symmetric).
                let aft = a * f.transpose();
                for kk in 0..3 {
                    for ll in 0..3 {
                        if columns & (1 << (3 * kk + ll)) == 0 {
                            continue;
                        }
                        // F⁻ᵀ : dF, i.e. dJ/J.
                        let tr_df = f_inv[(ll, kk)];
                        let mut dbe = b * (-2.0 / 3.0 * tr_df);
                        for j in 0..3 {
                            dbe[(kk, j)] += aft[(ll, j)];
                            dbe[(j, kk)] += aft[(ll, j)];
                        }
                        let dbe = dbe * c;
                        let dtr = dbe.trace() / 3.0;
                        let ds_tr = (dbe - Matrix3::identity() * dtr) * mu;
                        let ds = if with_return {
                            let mu_bar = mu * i_e;
                            let dmu_bar = mu * dtr;
                            let dm = dmu_bar * (h / 3.0) / (mu_bar + h / 3.0).powi(2);
                            let dq = s_tr.component_mul(&ds_tr).sum() / q;
                            let dbeta = dm * (c0 / q - 1.0) - m * c0 * dq / (q * q);
                            ds_tr * beta + s_tr * dbeta
                        } else {
                            ds_tr
                        };
                        let dtau = Matrix3::identity() * (k * j * j * tr_df) + ds;
                        for ii in 0..3 {
                            for jj in 0..3 {
                                d[(3 * ii + jj, 3 * kk + ll)] = dtau[(ii, jj)];
                            }
                        }
                    }
                }
                Some(d)
            }
        };

        Ok(FiniteStrainOutput {
            kirchhoff: out.kirchhoff,
            cauchy: out.cauchy,
            internal: out.internal,
            dtau_df,
            regime: out.regime,
        })
    }

    /// `j_n`, `j`: det F_n and det F of `input`.
    fn check(&self, input: &FiniteStrainInput, j_n: f64, j: f64) -> Result<(), IntegrationFailure> {
        let name = self.metadata().name;
        if input
            .f_n
            .iter()
            .chain(input.f_np1.iter())
            .any(|v| !v.is_finite())
        {
            return Err(IntegrationFailure::invalid(
                name,
                "non-finite deformation gradient",
            ));
        }
        if input.internal.iter().any(|v| !v.is_finite()) {
            return Err(IntegrationFailure::invalid(
                name,
                "non-finite internal variable",
            ));
        }
        if !(input.dt.is_finite() && input.dt >= 0.0) {
            return Err(IntegrationFailure::invalid(
                name,
                format!("invalid time step {}", input.dt),
            ));
        }
        if input.internal.len() != METADATA.internal_variables.len() {
            return Err(IntegrationFailure::invalid(
                name,
                format!(
                    "{} internal variables given, {} expected",
                    input.internal.len(),
                    METADATA.internal_variables.len()
                ),
            ));
        }
        if input.internal[0] < 0.0 {
            return Err(IntegrationFailure::invalid(
                name,
                "negative cumulative plastic strain V1",
            ));
        }
        // An inverted element (J ≤ 0) is a step that went too far, not a
        // material state: ask for a smaller step.
        if j_n <= 0.0 || j <= 0.0 {
            return Err(IntegrationFailure::not_converged(
                name,
                "non-positive volume change J",
            ));
        }
        let be = Self::elastic_left_cauchy_green(input.internal);
        if be.determinant() <= 0.0 {
            return Err(IntegrationFailure::invalid(
                name,
                "b̄ᵉ in V3..V8 is not positive definite",
            ));
        }
        Ok(())
    }
}

/// The x with det(D + x 1) = 1 for a deviatoric D, by Newton from x0 (≈ 1
/// for metals): det(D + x1) = x³ − ½ tr(D²) x + det D.
fn unit_determinant_shift(d: &Matrix3<f64>, x0: f64) -> Option<f64> {
    let i2 = -0.5 * (d * d).trace();
    let i3 = d.determinant();
    shift_newton(i2, i3, x0)
}

/// r^(2/3) for the explicit step, where r = J_n/J differs from 1 by the
/// volume change of one step (10⁻⁸ to 10⁻⁴ in the Taylor bar): there the
/// binomial series (1 + e)^(2/3) = Σ C(2/3, k) eᵏ, e = r − 1 exact
/// (Sterbenz), is summed to k = 5 (the remainder C(2/3, 6) e⁶ below 4·10⁻²⁴
/// relative for |e| ≤ 2⁻¹²), within one unit in the last place of libm's `pow`, at a
/// fraction of its cost (`pow` was 13 % of the explicit run's time).
/// Farther from 1, `pow`.
#[inline(always)]
pub fn two_thirds_power(r: f64) -> f64 {
    let e = r - 1.0;
    if e.abs() > TWO_THIRDS_SERIES_RANGE {
        return r.powf(2.0 / 3.0);
    }
    const C: [f64; 5] = [
        2.0 / 3.0,
        -1.0 / 9.0,
        4.0 / 81.0,
        -7.0 / 243.0,
        14.0 / 729.0,
    ];
    let mut s = C[4];
    for c in C[..4].iter().rev() {
        s = s * e + c;
    }
    1.0 + e * s
}

/// |r − 1| up to which [`two_thirds_power`] sums the series.
pub const TWO_THIRDS_SERIES_RANGE: f64 = 1.0 / 4096.0;

/// The Newton iteration of [`unit_determinant_shift`] on the invariants.
fn shift_newton(i2: f64, i3: f64, x0: f64) -> Option<f64> {
    let mut x = x0;
    for _ in 0..50 {
        let g = x * x * x + i2 * x + i3 - 1.0;
        let dg = 3.0 * x * x + i2;
        if dg <= 0.0 {
            return None;
        }
        let dx = g / dg;
        x -= dx;
        if dx.abs() <= 1e-15 * x.abs() {
            return Some(x);
        }
    }
    None
}

/// An axisymmetric tensor: its (r, z) block `m` and its hoop component
/// `t` (θθ); the rθ and zθ components are zero. The explicit AXIS step
/// computes with these instead of 3 × 3 matrices: each operation below
/// sums the same nonzero terms in the order nalgebra sums them for the
/// 3 × 3 matrix (products column by column with k = 0, 1, 2, traces and
/// norms from the first entry, the cofactor determinant and inverse),
/// the terms dropped being products with the exact zeros of the θ
/// coupling, so the nonzero components are the 3 × 3 ones to the bit
/// (only the sign of a component that is exactly zero may differ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axi {
    pub m: [[f64; 2]; 2],
    pub t: f64,
}

impl Axi {
    /// The (r, z) block and θθ of a 3 × 3 matrix.
    pub fn of(a: &Matrix3<f64>) -> Axi {
        Axi {
            m: [[a[(0, 0)], a[(0, 1)]], [a[(1, 0)], a[(1, 1)]]],
            t: a[(2, 2)],
        }
    }

    pub fn matrix(&self) -> Matrix3<f64> {
        Matrix3::new(
            self.m[0][0],
            self.m[0][1],
            0.0,
            self.m[1][0],
            self.m[1][1],
            0.0,
            0.0,
            0.0,
            self.t,
        )
    }

    /// self · o
    #[inline(always)]
    pub fn mul(&self, o: &Axi) -> Axi {
        let (a, b) = (&self.m, &o.m);
        Axi {
            m: [
                [
                    a[0][0] * b[0][0] + a[0][1] * b[1][0],
                    a[0][0] * b[0][1] + a[0][1] * b[1][1],
                ],
                [
                    a[1][0] * b[0][0] + a[1][1] * b[1][0],
                    a[1][0] * b[0][1] + a[1][1] * b[1][1],
                ],
            ],
            t: self.t * o.t,
        }
    }

    /// self · oᵀ
    #[inline(always)]
    pub fn mul_t(&self, o: &Axi) -> Axi {
        let (a, b) = (&self.m, &o.m);
        Axi {
            m: [
                [
                    a[0][0] * b[0][0] + a[0][1] * b[0][1],
                    a[0][0] * b[1][0] + a[0][1] * b[1][1],
                ],
                [
                    a[1][0] * b[0][0] + a[1][1] * b[0][1],
                    a[1][0] * b[1][0] + a[1][1] * b[1][1],
                ],
            ],
            t: self.t * o.t,
        }
    }

    #[inline]
    fn map(&self, f: impl Fn(f64) -> f64) -> Axi {
        Axi {
            m: [
                [f(self.m[0][0]), f(self.m[0][1])],
                [f(self.m[1][0]), f(self.m[1][1])],
            ],
            t: f(self.t),
        }
    }

    pub fn trace(&self) -> f64 {
        (self.m[0][0] + self.m[1][1]) + self.t
    }

    /// nalgebra's cofactor determinant.
    pub fn determinant(&self) -> f64 {
        let m = &self.m;
        m[0][0] * (m[1][1] * self.t) - m[0][1] * (m[1][0] * self.t)
    }

    /// nalgebra's `try_inverse` with its determinant `det` (nonzero).
    pub fn inverse(&self, det: f64) -> Axi {
        let m = &self.m;
        Axi {
            m: [
                [(m[1][1] * self.t) / det, -(self.t * m[0][1]) / det],
                [-(m[1][0] * self.t) / det, (m[0][0] * self.t) / det],
            ],
            t: (m[0][0] * m[1][1] - m[1][0] * m[0][1]) / det,
        }
    }

    fn norm_squared(&self) -> f64 {
        let m = &self.m;
        let c0 = m[0][0] * m[0][0] + m[1][0] * m[1][0];
        let c1 = m[0][1] * m[0][1] + m[1][1] * m[1][1];
        (c0 + c1) + self.t * self.t
    }

    /// [`tensor_to_stress`] (rr, zz, θθ, rz, 0, 0).
    pub fn to_stress(&self) -> super::Vec6 {
        let m = &self.m;
        super::Vec6::new(
            0.5 * (m[0][0] + m[0][0]),
            0.5 * (m[1][1] + m[1][1]),
            0.5 * (self.t + self.t),
            0.5 * (m[0][1] + m[1][0]),
            0.0,
            0.0,
        )
    }
}

/// [`StressUpdate`] of an axisymmetric point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxiUpdate {
    pub kirchhoff: Axi,
    pub cauchy: Axi,
    pub internal: InternalVars,
    pub regime: Regime,
}

impl SimoMiehe {
    /// [`SimoMiehe::integrate_stress`] for an axisymmetric point (F and
    /// F_n without θ coupling, b̄ᵉ_n without rθ, zθ components), computed
    /// on the (r, z) block and θθ ([`Axi`]): the same checks, the same
    /// nonzero results to the bit, except that (J_n/J)^(2/3) is
    /// [`two_thirds_power`]'s (within one unit in the last place of the
    /// 3 × 3 update's `pow` where J_n/J is within 2⁻¹² of 1, the same bits
    /// elsewhere). `fn_inv` is F_n⁻¹ (`f_n.inverse(j_n)`).
    /// `None` when the internal variables hold rθ or zθ components of
    /// b̄ᵉ (not an axisymmetric state: the caller takes the 3 × 3 path).
    ///
    /// Always inlined, with [`SimoMiehe::update_axi`] and the [`Axi`]
    /// products: the explicit element pass calls it at every Gauss point
    /// of every step, and as a call its update returned by value went
    /// through memory. Inlining changes no operation (no contraction).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn integrate_stress_axi(
        &self,
        f_n: &Axi,
        f: &Axi,
        j_n: f64,
        j: f64,
        fn_inv: &Axi,
        internal: &[f64],
        dt: f64,
    ) -> Option<Result<AxiUpdate, IntegrationFailure>> {
        let name = self.metadata().name;
        if internal.len() != METADATA.internal_variables.len()
            || internal[6] != 0.0
            || internal[7] != 0.0
        {
            return None;
        }
        let finite = |a: &Axi| a.m.iter().flatten().all(|v| v.is_finite()) && a.t.is_finite();
        if !(finite(f_n) && finite(f)) {
            return Some(Err(IntegrationFailure::invalid(
                name,
                "non-finite deformation gradient",
            )));
        }
        if internal.iter().any(|v| !v.is_finite()) {
            return Some(Err(IntegrationFailure::invalid(
                name,
                "non-finite internal variable",
            )));
        }
        if !(dt.is_finite() && dt >= 0.0) {
            return Some(Err(IntegrationFailure::invalid(
                name,
                format!("invalid time step {dt}"),
            )));
        }
        if internal[0] < 0.0 {
            return Some(Err(IntegrationFailure::invalid(
                name,
                "negative cumulative plastic strain V1",
            )));
        }
        if j_n <= 0.0 || j <= 0.0 {
            return Some(Err(IntegrationFailure::not_converged(
                name,
                "non-positive volume change J",
            )));
        }
        // b̄ᵉ_n = stress_to_tensor(V3..V8) + 1.
        let be_n = Axi {
            m: [
                [internal[2] + 1.0, internal[5]],
                [internal[5], internal[3] + 1.0],
            ],
            t: internal[4] + 1.0,
        };
        if be_n.determinant() <= 0.0 {
            return Some(Err(IntegrationFailure::invalid(
                name,
                "b̄ᵉ in V3..V8 is not positive definite",
            )));
        }
        Some(self.update_axi(f, j_n, j, &fn_inv.mul(&be_n).mul_t(fn_inv), internal))
    }

    /// [`SimoMiehe::update`]'s stress on [`Axi`] tensors (`a` = F_n⁻¹ b̄ᵉ_n F_n⁻ᵀ).
    #[inline(always)]
    fn update_axi(
        &self,
        f: &Axi,
        j_n: f64,
        j: f64,
        a: &Axi,
        internal: &[f64],
    ) -> Result<AxiUpdate, IntegrationFailure> {
        let (mu, k) = (self.mu, self.bulk);
        let p_n = internal[0];
        let b = f.mul(a).mul_t(f);
        let c = two_thirds_power(j_n / j);
        let be_tr = b.map(|x| x * c);
        let i_e = be_tr.trace() / 3.0;
        let s_tr = Axi {
            m: [
                [(be_tr.m[0][0] - i_e) * mu, be_tr.m[0][1] * mu],
                [be_tr.m[1][0] * mu, (be_tr.m[1][1] - i_e) * mu],
            ],
            t: (be_tr.t - i_e) * mu,
        };
        let q = s_tr.norm_squared().sqrt();
        let c0 = (2.0f64 / 3.0).sqrt() * self.yield_stress(p_n);
        let pressure = 0.5 * k * (j * j - 1.0);
        let plastic = q > c0;
        let (s, be_new, p_new) = if plastic {
            let mu_bar = mu * i_e;
            let (dgamma, _, _) = self.plastic_multiplier(q, c0, p_n, mu_bar)?;
            let beta = 1.0 - 2.0 * mu_bar * dgamma / q;
            let s = s_tr.map(|x| x * beta);
            let dev_be = s.map(|x| x / mu);
            let i2 = -0.5 * dev_be.mul(&dev_be).trace();
            let x = shift_newton(i2, dev_be.determinant(), i_e).ok_or_else(|| {
                IntegrationFailure::not_converged(
                    METADATA.name,
                    "trace correction of b̄ᵉ did not converge",
                )
            })?;
            let p = p_n + (2.0f64 / 3.0).sqrt() * dgamma;
            let mut be_new = dev_be;
            be_new.m[0][0] += x;
            be_new.m[1][1] += x;
            be_new.t += x;
            (s, be_new, p)
        } else {
            (s_tr, be_tr, p_n)
        };
        let mut tau = s;
        tau.m[0][0] = pressure + s.m[0][0];
        tau.m[1][1] = pressure + s.m[1][1];
        tau.t = pressure + s.t;
        let mut out = self.initial_internal();
        let v = out.as_mut_slice();
        v[0] = p_new;
        v[1] = if plastic { 1.0 } else { 0.0 };
        let mut e = be_new;
        e.m[0][0] -= 1.0;
        e.m[1][1] -= 1.0;
        e.t -= 1.0;
        v[2..8].copy_from_slice(e.to_stress().as_slice());
        Ok(AxiUpdate {
            kirchhoff: tau,
            cauchy: tau.map(|x| x / j),
            internal: out,
            regime: if plastic {
                Regime::Plastic
            } else {
                Regime::Elastic
            },
        })
    }
}
