//! `VMIS_ISOT_LINE`: von Mises plasticity with linear isotropic hardening,
//! small strains, integrated by the radial return (code_aster `nmisot.F90`;
//! Simo & Hughes, *Computational Inelasticity*, 1998, Box 3.2 for the
//! return and eq. (3.3.11)-(3.3.13) for the consistent tangent).
//!
//! Hardening R(p) = SY + H p with H = E·E_T/(E − E_T) (E_T = D_SIGM_EPSI).
//! For linear hardening the return is closed-form: no local iteration, so
//! this law never fails on valid input.

use super::voigt::{deviator, deviatoric_projector, double_dot, isotropic_elastic, one_one, trace};
use super::{
    check_small_strain_input, EcroLineParams, ElasParams, IntegrationFailure, InternalVars,
    LawMetadata, Regime, SmallStrainBehaviour, SmallStrainInput, SmallStrainOutput, StrainMeasure,
    TangentKind, Vec6,
};

/// V1 = EPSPEQ (cumulative plastic strain p), V2 = INDIPLAS (0/1).
/// SIMO_MIEHE is accepted through the separate finite-strain law
/// [`super::simo_miehe`] (code_aster's VMIS2ISOT_LINE switch).
pub static METADATA: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_LINE",
    internal_variables: &["EPSPEQ", "INDIPLAS"],
    strain_measures: &[
        StrainMeasure::Petit,
        StrainMeasure::PetitReac,
        StrainMeasure::GrotGdep,
        StrainMeasure::SimoMiehe,
        StrainMeasure::GdefLog,
    ],
    tensor_variables: &[],
};

/// Relative distance to the yield surface under which a zero increment
/// is taken as on it (see `integrate`).
const ON_SURFACE: f64 = 1e-10;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VmisIsotLine {
    pub elas: ElasParams,
    pub ecro: EcroLineParams,
    mu: f64,
    bulk: f64,
    h: f64,
}

impl VmisIsotLine {
    pub fn new(elas: ElasParams, ecro: EcroLineParams) -> VmisIsotLine {
        VmisIsotLine {
            elas,
            ecro,
            mu: elas.mu(),
            bulk: elas.bulk(),
            h: ecro.hardening(&elas),
        }
    }
    /// Plastic modulus H.
    pub fn hardening(&self) -> f64 {
        self.h
    }
    /// Yield stress R(p).
    pub fn yield_stress(&self, p: f64) -> f64 {
        self.ecro.sy + self.h * p
    }
}

impl IsotropicHardening for VmisIsotLine {
    fn yield_stress(&self, p: f64) -> f64 {
        VmisIsotLine::yield_stress(self, p)
    }
    fn return_map(
        &self,
        q_tr: f64,
        p_n: f64,
        three_mu: f64,
    ) -> Result<(f64, f64), IntegrationFailure> {
        Ok((
            (q_tr - self.yield_stress(p_n)) / (three_mu + self.h),
            self.h,
        ))
    }
    fn slope(&self, _p: f64) -> f64 {
        self.h
    }
}

impl SmallStrainBehaviour for VmisIsotLine {
    fn metadata(&self) -> &'static LawMetadata {
        &METADATA
    }

    fn elastic_params(&self) -> Option<crate::law::ElasParams> {
        Some(self.elas)
    }

    fn integrate(&self, input: &SmallStrainInput) -> Result<SmallStrainOutput, IntegrationFailure> {
        radial_return(&METADATA, input, self.mu, self.bulk, self)
    }
}

/// What the radial return needs of an isotropic hardening R(p): the
/// return is the same for every R, only the scalar equation differs
/// (closed form for a line, a walk along the segments for a traction
/// curve).
pub(crate) trait IsotropicHardening {
    /// R(p).
    fn yield_stress(&self, p: f64) -> f64;
    /// Δp ≥ 0 solving q_tr − 3μ Δp = R(p_n + Δp) when q_tr > R(p_n), and
    /// R' at p_n + Δp (the consistent tangent reads it).
    fn return_map(
        &self,
        q_tr: f64,
        p_n: f64,
        three_mu: f64,
    ) -> Result<(f64, f64), IntegrationFailure>;
    /// R' on the right of p: the tangent of a zero increment on the
    /// surface.
    fn slope(&self, p: f64) -> f64;
}

/// The radial return of von Mises plasticity with isotropic hardening
/// (Simo & Hughes Box 3.2), its consistent tangent (3.3.11)-(3.3.13), and
/// the rule for a zero increment on the surface.
pub(crate) fn radial_return(
    meta: &'static LawMetadata,
    input: &SmallStrainInput,
    mu: f64,
    k: f64,
    hardening: &impl IsotropicHardening,
) -> Result<SmallStrainOutput, IntegrationFailure> {
    check_small_strain_input(meta, input)?;
    let p_n = input.internal[0];
    if p_n < 0.0 {
        return Err(IntegrationFailure::invalid(
            meta.name,
            format!("negative cumulative plastic strain V1 = {p_n}"),
        ));
    }
    let de = input.strain_increment;
    // Elastic predictor: deviator s_n + 2μ Δe; pressure always elastic.
    let s_tr = deviator(&input.stress) + deviatoric_projector() * de * (2.0 * mu);
    let sigma_m = trace(&input.stress) / 3.0 + k * trace(&de);
    let q_tr = (1.5 * double_dot(&s_tr, &s_tr)).sqrt();
    let r_n = hardening.yield_stress(p_n);
    let elastic_d = isotropic_elastic(k, mu);
    let mut internal = InternalVars::zeros(2);
    let hydro = Vec6::new(sigma_m, sigma_m, sigma_m, 0.0, 0.0, 0.0);
    // A zero increment is the prediction of a step (code_aster's
    // RIGI_MECA_TANG). On the yield surface the choice between the
    // elastic and the plastic tangent must not be left to the last bit
    // of q − R: after a plastic step q = R(p) up to round-off, and a
    // coin flip per point mixes stiff and softened points in one
    // prediction matrix, which throws the predicted increment into the
    // soft points (a stalled unloading of MECA_HEXS8, docs/laws-elements.md).
    // So a stress on the surface to 1e-10 takes the plastic tangent
    // with Δp = 0, as code_aster does after a plastic step (V2 = 1);
    // unlike its V2 test, an elastic step that ended on the surface
    // also does.
    let on_surface = de.iter().all(|v| *v == 0.0) && q_tr > 0.0 && q_tr >= r_n * (1.0 - ON_SURFACE);
    if q_tr <= r_n && !on_surface {
        internal.as_mut_slice()[0] = p_n;
        return Ok(SmallStrainOutput {
            stress: s_tr + hydro,
            internal,
            tangent: match input.tangent {
                TangentKind::None => None,
                _ => Some(elastic_d),
            },
            regime: Regime::Elastic,
        });
    }
    // Plastic corrector: q_tr − 3μΔp − R(p_n + Δp) = 0.
    let (dp, h) = if on_surface {
        (0.0, hardening.slope(p_n))
    } else {
        hardening.return_map(q_tr, p_n, 3.0 * mu)?
    };
    let theta = 1.0 - 3.0 * mu * dp / q_tr;
    let s = s_tr * theta;
    internal.as_mut_slice()[0] = p_n + dp;
    internal.as_mut_slice()[1] = 1.0;
    let tangent = match input.tangent {
        TangentKind::None => None,
        TangentKind::Elastic => Some(elastic_d),
        TangentKind::Consistent => {
            // D = K 1⊗1 + 2μθ I_dev − 2μ θ̄ n⊗n, n = s_tr/|s_tr|,
            // θ̄ = 3μ/(3μ+H) − (1 − θ).
            let norm = double_dot(&s_tr, &s_tr).sqrt();
            let n = s_tr / norm;
            let theta_bar = 3.0 * mu / (3.0 * mu + h) - (1.0 - theta);
            Some(
                one_one() * k + deviatoric_projector() * (2.0 * mu * theta)
                    - n * n.transpose() * (2.0 * mu * theta_bar),
            )
        }
    };
    Ok(SmallStrainOutput {
        stress: s + hydro,
        internal,
        tangent,
        regime: Regime::Plastic,
    })
}
