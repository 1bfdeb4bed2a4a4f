//! Behaviour laws, behind an MGIS-like contract.
//!
//! A law is metadata (its code_aster name, its internal variables, the
//! strain measures it accepts) plus one pure function that integrates a
//! step: state at the start of the step + strain increment → state at the
//! end + tangent. The caller owns the states; a law never keeps mutable
//! data, so rejecting a step (Newton failure, step cutting) is just a
//! matter of not committing its output.
//!
//! Integration failures are values, never panics: they carry a suggested
//! step factor so the time stepper (DEFI_LIST_INST's ERREUR cutting) can
//! retry with a smaller step. NaN or infinite inputs are refused the same
//! way, since they would otherwise flow silently into the stress field.
//!
//! Conventions (Voigt order, engineering shears) are in [`voigt`].

pub mod elas;
pub mod gdef_log;
pub mod john_cook;
pub mod plane_stress;
pub mod root1d;
pub mod simo_miehe;
pub mod vmis_cine_line;
pub mod vmis_isot_line;
pub mod vmis_isot_puis;
pub mod vmis_isot_trac;
pub mod voigt;

/// Checks a consistent tangent `d` column by column against central
/// differences (step 1e-8) of `stress_at`, the stress after the strain
/// increment it is given, around the increment `de`: every entry to
/// `tol`. The laws' unit tests share it.
#[cfg(test)]
pub(crate) fn assert_tangent_by_differences(
    d: &Mat6,
    de: Vec6,
    tol: f64,
    label: &str,
    stress_at: impl Fn(Vec6) -> Vec6,
) {
    let h = 1e-8;
    for j in 0..6 {
        let mut e = Vec6::zeros();
        e[j] = h;
        let col = (stress_at(de + e) - stress_at(de - e)) / (2.0 * h);
        for i in 0..6 {
            assert!(
                (col[i] - d[(i, j)]).abs() < tol,
                "{label}D[{i},{j}] = {} against {}",
                d[(i, j)],
                col[i]
            );
        }
    }
}

use std::fmt;

pub use voigt::{Mat6, Vec6};

/// code_aster's `DEFORMATION` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StrainMeasure {
    Petit,
    PetitReac,
    GrotGdep,
    SimoMiehe,
    GdefLog,
}

impl StrainMeasure {
    pub const ALL: [StrainMeasure; 5] = [
        StrainMeasure::Petit,
        StrainMeasure::PetitReac,
        StrainMeasure::GrotGdep,
        StrainMeasure::SimoMiehe,
        StrainMeasure::GdefLog,
    ];

    pub fn aster_name(self) -> &'static str {
        match self {
            StrainMeasure::Petit => "PETIT",
            StrainMeasure::PetitReac => "PETIT_REAC",
            StrainMeasure::GrotGdep => "GROT_GDEP",
            StrainMeasure::SimoMiehe => "SIMO_MIEHE",
            StrainMeasure::GdefLog => "GDEF_LOG",
        }
    }

    pub fn from_aster_name(name: &str) -> Option<StrainMeasure> {
        StrainMeasure::ALL
            .into_iter()
            .find(|m| m.aster_name() == name)
    }
}

/// What a law declares about itself (code_aster's `Behaviours/*.py`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LawMetadata {
    /// `RELATION` value, e.g. "VMIS_ISOT_LINE".
    pub name: &'static str,
    /// Internal variable names in V1, V2, ... order.
    pub internal_variables: &'static [&'static str],
    /// Accepted `DEFORMATION` values.
    pub strain_measures: &'static [StrainMeasure],
    /// The internal variables that are symmetric tensors stored as a
    /// stress is (six components xx, yy, zz, xy, xz, yz, tensor shears),
    /// by the index of their first component (VMIS_CINE_LINE's back stress
    /// XCINXX..XCINYZ: `&[0]`). An element that integrates the law in a
    /// frame of its own (MECA_HEXS8, `element::hexs8`) turns them into
    /// that frame and back as it turns the stress, so that VARI_ELGA holds
    /// them in global axes like SIEF_ELGA.
    pub tensor_variables: &'static [usize],
}

impl LawMetadata {
    pub fn accepts(&self, m: StrainMeasure) -> bool {
        self.strain_measures.contains(&m)
    }
}

/// Room for internal variables, kept on the stack: laws are called at every
/// Gauss point of every step, and a heap allocation there would dominate.
pub const MAX_INTERNAL: usize = 16;

/// Internal variables of one Gauss point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InternalVars {
    len: usize,
    v: [f64; MAX_INTERNAL],
}

impl InternalVars {
    /// `len` zeros (`len` is clamped to [`MAX_INTERNAL`]).
    pub fn zeros(len: usize) -> InternalVars {
        InternalVars {
            len: len.min(MAX_INTERNAL),
            v: [0.0; MAX_INTERNAL],
        }
    }
    /// Copies a slice; `None` when it is longer than [`MAX_INTERNAL`].
    pub fn from_slice(s: &[f64]) -> Option<InternalVars> {
        if s.len() > MAX_INTERNAL {
            return None;
        }
        let mut out = InternalVars::zeros(s.len());
        out.v[..s.len()].copy_from_slice(s);
        Some(out)
    }
    pub fn as_slice(&self) -> &[f64] {
        &self.v[..self.len]
    }
    pub fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.v[..self.len]
    }
    /// `*self = *other`, copying only the `len` values when the lengths
    /// agree (the values past `len` are zeros in every InternalVars):
    /// the explicit element pass writes each point's variables once per
    /// step, where the 136-byte move was a `memcpy` call.
    #[inline]
    pub fn assign(&mut self, other: &InternalVars) {
        if self.len == other.len {
            self.v[..self.len].copy_from_slice(&other.v[..other.len]);
        } else {
            *self = *other;
        }
    }
}

/// Which tangent the caller wants (code_aster's RAPH_MECA, RIGI_MECA_ELAS,
/// FULL_MECA).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TangentKind {
    None,
    /// The elastic stiffness (prediction, explicit stable-step estimates).
    Elastic,
    /// The consistent (algorithmic) tangent of the update, for Newton.
    Consistent,
}

/// Whether the step stayed elastic (V2 = 0) or yielded (V2 = 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Regime {
    Elastic,
    Plastic,
}

/// State at the start of a small-strain step and the strain increment.
#[derive(Debug, Clone, Copy)]
pub struct SmallStrainInput<'a> {
    /// σ_n, tensor components (see [`voigt`]).
    pub stress: Vec6,
    /// Internal variables at the start of the step, V1, V2, ...
    pub internal: &'a [f64],
    /// Δε, engineering shears (see [`voigt`]).
    pub strain_increment: Vec6,
    /// Time step (rate-dependent laws only; must be finite and ≥ 0).
    pub dt: f64,
    pub tangent: TangentKind,
}

/// State at the end of a small-strain step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmallStrainOutput {
    pub stress: Vec6,
    pub internal: InternalVars,
    /// dσ/dΔε as requested (`None` for [`TangentKind::None`]).
    pub tangent: Option<Mat6>,
    pub regime: Regime,
}

/// Why a step could not be integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FailureKind {
    /// NaN/infinite values, wrong internal-variable count, negative dt...
    InvalidInput,
    /// A local iteration did not converge: retry with a smaller step.
    NotConverged,
}

/// An integration failure; `dt_factor` (< 1) is the suggested step ratio
/// for a retry (0 when retrying cannot help, e.g. invalid input).
#[derive(Debug, Clone, PartialEq)]
pub struct IntegrationFailure {
    pub kind: FailureKind,
    pub dt_factor: f64,
    pub message: String,
}

impl IntegrationFailure {
    pub fn invalid(law: &str, message: impl fmt::Display) -> IntegrationFailure {
        IntegrationFailure {
            kind: FailureKind::InvalidInput,
            dt_factor: 0.0,
            message: format!("{law}: {message}"),
        }
    }
    pub fn not_converged(law: &str, message: impl fmt::Display) -> IntegrationFailure {
        IntegrationFailure {
            kind: FailureKind::NotConverged,
            dt_factor: 0.5,
            message: format!("{law}: {message}; a smaller step is needed"),
        }
    }
}

impl fmt::Display for IntegrationFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for IntegrationFailure {}

/// A small-strain law (PETIT, PETIT_REAC).
pub trait SmallStrainBehaviour: Send + Sync {
    fn metadata(&self) -> &'static LawMetadata;
    /// Internal variables of a virgin material point.
    fn initial_internal(&self) -> InternalVars {
        InternalVars::zeros(self.metadata().internal_variables.len())
    }
    fn integrate(&self, input: &SmallStrainInput) -> Result<SmallStrainOutput, IntegrationFailure>;
    /// The law's elastic constants, for elements that need them beside
    /// the tangent (the ASQBI hourglass projection of HEXS8 reads ν).
    fn elastic_params(&self) -> Option<ElasParams> {
        None
    }
}

/// A material parameter that DEFI_MATERIAU would refuse; `keyword` is the
/// keyword path (e.g. "ECRO_LINE/D_SIGM_EPSI") for the diagnostic.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialError {
    pub keyword: &'static str,
    pub message: String,
}

impl fmt::Display for MaterialError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.keyword, self.message)
    }
}

impl std::error::Error for MaterialError {}

/// The `ELAS` block of DEFI_MATERIAU (the part the laws and elements use).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasParams {
    pub e: f64,
    pub nu: f64,
    /// Needed by the mass matrix only.
    pub rho: Option<f64>,
}

impl ElasParams {
    /// Checks E > 0 and ν in (−1, 0.5): the catalogue allows E = 0 and the
    /// closed interval, but both make the elastic tangent singular.
    pub fn new(e: f64, nu: f64, rho: Option<f64>) -> Result<ElasParams, MaterialError> {
        if !(e.is_finite() && e > 0.0) {
            return Err(MaterialError {
                keyword: "ELAS/E",
                message: format!("E must be finite and > 0, got {e}"),
            });
        }
        if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
            return Err(MaterialError {
                keyword: "ELAS/NU",
                message: format!("NU must be in (-1, 0.5), got {nu}"),
            });
        }
        if let Some(r) = rho {
            if !(r.is_finite() && r >= 0.0) {
                return Err(MaterialError {
                    keyword: "ELAS/RHO",
                    message: format!("RHO must be finite and >= 0, got {r}"),
                });
            }
        }
        Ok(ElasParams { e, nu, rho })
    }
    /// Shear modulus μ = E / (2(1+ν)).
    pub fn mu(&self) -> f64 {
        self.e / (2.0 * (1.0 + self.nu))
    }
    /// Bulk modulus K = E / (3(1−2ν)).
    pub fn bulk(&self) -> f64 {
        self.e / (3.0 * (1.0 - 2.0 * self.nu))
    }
}

/// The `ECRO_LINE` block: yield stress and **tangent** modulus E_T.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EcroLineParams {
    pub sy: f64,
    pub d_sigm_epsi: f64,
}

impl EcroLineParams {
    /// Checks SY ≥ 0 and E_T < E (code_aster's COMPOR1_54 for E_T ≥ E).
    pub fn new(
        elas: &ElasParams,
        sy: f64,
        d_sigm_epsi: f64,
    ) -> Result<EcroLineParams, MaterialError> {
        if !(sy.is_finite() && sy >= 0.0) {
            return Err(MaterialError {
                keyword: "ECRO_LINE/SY",
                message: format!("SY must be finite and >= 0, got {sy}"),
            });
        }
        if !d_sigm_epsi.is_finite() || d_sigm_epsi >= elas.e {
            return Err(MaterialError {
                keyword: "ECRO_LINE/D_SIGM_EPSI",
                message: format!(
                    "the tangent modulus D_SIGM_EPSI = {d_sigm_epsi} must be below E = {}",
                    elas.e
                ),
            });
        }
        Ok(EcroLineParams { sy, d_sigm_epsi })
    }
    /// Plastic modulus H = E·E_T/(E − E_T) of R(p) = SY + H p.
    pub fn hardening(&self, elas: &ElasParams) -> f64 {
        elas.e * self.d_sigm_epsi / (elas.e - self.d_sigm_epsi)
    }
}

/// Common input checks for small-strain laws.
pub(crate) fn check_small_strain_input(
    law: &LawMetadata,
    input: &SmallStrainInput,
) -> Result<(), IntegrationFailure> {
    if input.stress.iter().any(|v| !v.is_finite()) {
        return Err(IntegrationFailure::invalid(
            law.name,
            "non-finite stress at the start of the step",
        ));
    }
    if input.strain_increment.iter().any(|v| !v.is_finite()) {
        return Err(IntegrationFailure::invalid(
            law.name,
            "non-finite strain increment",
        ));
    }
    if input.internal.iter().any(|v| !v.is_finite()) {
        return Err(IntegrationFailure::invalid(
            law.name,
            "non-finite internal variable",
        ));
    }
    if !(input.dt.is_finite() && input.dt >= 0.0) {
        return Err(IntegrationFailure::invalid(
            law.name,
            format!("invalid time step {}", input.dt),
        ));
    }
    if input.internal.len() != law.internal_variables.len() {
        return Err(IntegrationFailure::invalid(
            law.name,
            format!(
                "{} internal variables given, {} expected",
                input.internal.len(),
                law.internal_variables.len()
            ),
        ));
    }
    Ok(())
}

/// The names of the internal variables V1, V2, ... of a COMPORTEMENT
/// (RELATION, DEFORMATION), as code_aster names them (TEST_RESU
/// NOM_VARI); None for a combination that is not built.
pub fn internal_variable_names(
    relation: &str,
    deformation: &str,
) -> Option<&'static [&'static str]> {
    Some(match (relation, deformation) {
        ("ELAS", _) => &[],
        ("VMIS_ISOT_LINE", "PETIT" | "PETIT_REAC") => vmis_isot_line::METADATA.internal_variables,
        ("VMIS_ISOT_LINE", "SIMO_MIEHE") => simo_miehe::METADATA.internal_variables,
        ("VMIS_ISOT_LINE", "GDEF_LOG") => gdef_log::ISOT_LINE_LOG.internal_variables,
        ("VMIS_ISOT_TRAC", "PETIT" | "PETIT_REAC") => vmis_isot_trac::METADATA.internal_variables,
        ("VMIS_ISOT_TRAC", "SIMO_MIEHE") => simo_miehe::METADATA.internal_variables,
        ("VMIS_ISOT_TRAC", "GDEF_LOG") => gdef_log::ISOT_TRAC_LOG.internal_variables,
        ("VMIS_ISOT_PUIS", "PETIT" | "PETIT_REAC") => vmis_isot_puis::METADATA.internal_variables,
        ("VMIS_ISOT_PUIS", "SIMO_MIEHE") => simo_miehe::METADATA.internal_variables,
        ("VMIS_ISOT_PUIS", "GDEF_LOG") => gdef_log::ISOT_PUIS_LOG.internal_variables,
        ("VMIS_CINE_LINE", "PETIT" | "PETIT_REAC") => vmis_cine_line::METADATA.internal_variables,
        ("VMIS_CINE_LINE", "GDEF_LOG") => gdef_log::CINE_LINE_LOG.internal_variables,
        ("VMIS_JOHN_COOK", "GDEF_LOG") => gdef_log::JOHN_COOK_LOG.internal_variables,
        ("VMIS_JOHN_COOK", _) => john_cook::METADATA.internal_variables,
        _ => return None,
    })
}
