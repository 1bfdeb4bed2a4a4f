//! `ELAS`: isotropic linear elasticity, small strains.
//!
//! Written incrementally, σ = σ_n + D Δε, which equals code_aster's total
//! form σ = D ε whenever σ_n came from this law, and is what PETIT_REAC
//! needs.

use super::voigt::isotropic_elastic;
use super::{
    check_small_strain_input, ElasParams, IntegrationFailure, InternalVars, LawMetadata, Mat6,
    Regime, SmallStrainBehaviour, SmallStrainInput, SmallStrainOutput, StrainMeasure, TangentKind,
};

/// code_aster declares one dummy variable (`VIDE`) for ELAS.
pub static METADATA: LawMetadata = LawMetadata {
    name: "ELAS",
    internal_variables: &["VIDE"],
    strain_measures: &[
        StrainMeasure::Petit,
        StrainMeasure::PetitReac,
        StrainMeasure::GrotGdep,
    ],
    tensor_variables: &[],
};

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elas {
    pub params: ElasParams,
    stiffness: Mat6,
}

impl Elas {
    pub fn new(params: ElasParams) -> Elas {
        Elas {
            params,
            stiffness: isotropic_elastic(params.bulk(), params.mu()),
        }
    }
    /// The Voigt stiffness D (engineering shears).
    pub fn stiffness(&self) -> &Mat6 {
        &self.stiffness
    }
}

impl SmallStrainBehaviour for Elas {
    fn metadata(&self) -> &'static LawMetadata {
        &METADATA
    }

    fn elastic_params(&self) -> Option<crate::law::ElasParams> {
        Some(self.params)
    }

    fn integrate(&self, input: &SmallStrainInput) -> Result<SmallStrainOutput, IntegrationFailure> {
        check_small_strain_input(&METADATA, input)?;
        Ok(SmallStrainOutput {
            stress: input.stress + self.stiffness * input.strain_increment,
            internal: InternalVars::zeros(1),
            tangent: match input.tangent {
                TangentKind::None => None,
                _ => Some(self.stiffness),
            },
            regime: Regime::Elastic,
        })
    }
}
