//! DEFI_MATERIAU: material parameters, by behaviour block.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_MATERIAU",
        Produces::Concept(C::Mater),
        vec![
            fact(
                "ELAS",
                vec![
                    real("E").required().min_val(0.0).doc("Young's modulus").kw(),
                    real("NU")
                        .required()
                        .min_val(-1.0)
                        .max_val(0.5)
                        .doc("Poisson's ratio")
                        .kw(),
                    real("RHO").doc("density, needed for the mass matrix").kw(),
                    real("ALPHA").doc("thermal expansion coefficient").kw(),
                    real("AMOR_ALPHA")
                        .doc("Rayleigh damping coefficient on the stiffness")
                        .kw(),
                    real("AMOR_BETA")
                        .doc("Rayleigh damping coefficient on the mass")
                        .kw(),
                    real("AMOR_HYST").kw(),
                    real("LONG_CARA").kw(),
                    real("COEF_AMOR").default(r(1.0)).kw(),
                ],
            )
            .doc("isotropic linear elasticity")
            .kw(),
            fact(
                "ECRO_LINE",
                vec![
                    real("D_SIGM_EPSI")
                        .required()
                        .doc("tangent slope E_T of the uniaxial curve (not the plastic modulus: H = E.E_T/(E-E_T))")
                        .kw(),
                    real("SY").required().doc("yield stress").kw(),
                    real("SIGM_LIM").kw(),
                    real("EPSI_LIM").kw(),
                ],
            )
            .doc("linear isotropic hardening (VMIS_ISOT_LINE)")
            .kw(),
            fact(
                "ECRO_COOK",
                vec![
                    real("A").required().min_val(0.0).doc("initial yield stress").kw(),
                    real("B").required().min_val(0.0).doc("hardening modulus").kw(),
                    real("C").min_val(0.0).doc("strain-rate coefficient").kw(),
                    real("N_PUIS").required().min_val(0.0).doc("hardening exponent").kw(),
                    real("M_PUIS").min_val(0.0).doc("thermal softening exponent").kw(),
                    real("EPSP0")
                        .min_val(1e-6)
                        .doc("reference strain rate; the rate term acts only above it")
                        .kw(),
                    real("TROOM").min_val(0.0).doc("room temperature").kw(),
                    real("TMELT").min_val(0.0).doc("melting temperature").kw(),
                ],
            )
            .rules(vec![
                ensemble(&["C", "EPSP0"]),
                ensemble(&["M_PUIS", "TROOM", "TMELT"]),
            ])
            .doc("Johnson-Cook hardening (VMIS_JOHN_COOK); no thermal softening without a temperature field")
            .kw(),
            titre(),
            info(),
        ],
    )
    .rules(vec![
        au_moins_un(&["ELAS", "ECRO_LINE", "ECRO_COOK"]),
        exclus(&["ECRO_LINE", "ECRO_COOK"]),
    ])
    .doc("Defines a material: one factor keyword per behaviour ingredient.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
