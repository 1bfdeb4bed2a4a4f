//! DYNA_NON_LINE: nonlinear transient dynamics.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let spec = command(
        "DYNA_NON_LINE",
        Produces::Concept(C::EvolNoli),
        vec![
            concept("MODELE", &[C::Modele]).required().kw(),
            concept("CHAM_MATER", &[C::ChamMater]).required().kw(),
            text("MASS_DIAG")
                .into(&["OUI", "NON"])
                .doc("lumped mass (explicit schemes only)")
                .kw(),
            fact(
                "EXCIT",
                vec![
                    text("TYPE_CHARGE")
                        .into(&["FIXE_CSTE", "SUIV", "DIDI"])
                        .default(t("FIXE_CSTE"))
                        .doc("dead load, follower load, or differential imposed displacement")
                        .kw(),
                    concept("CHARGE", &[C::CharMeca]).required().kw(),
                    concept("FONC_MULT", &[C::Fonction])
                        .doc("time multiplier of the load")
                        .kw(),
                ],
            )
            .many()
            .doc("loads and boundary conditions")
            .kw(),
            concept("CONTACT", &[C::CharContact])
                .doc("contact definition from DEFI_CONTACT (not with explicit schemes)")
                .kw(),
            text("AMOR_RAYL_RIGI")
                .into(&["TANGENTE", "ELASTIQUE"])
                .default(t("TANGENTE"))
                .doc("stiffness used in Rayleigh damping")
                .kw(),
            c_comportement(),
            c_etat_init(),
            c_increment(),
            schema_temps(),
            text("METHODE")
                .into(&["NEWTON", "NEWTON_KRYLOV"])
                .default(t("NEWTON"))
                .kw(),
            c_newton(),
            c_rech_lineaire(),
            c_convergence(),
            c_solveur(),
            c_suivi_ddl(),
            fact(
                "ENERGIE",
                vec![text("CALCUL").into(&["OUI"]).default(t("OUI")).kw()],
            )
            .doc("energy balance table")
            .kw(),
            c_affichage(),
            c_archivage(),
            info(),
            titre(),
        ],
    )
    // code_aster's 'f:ETAT_INIT:EVOL_NOLI': the continued result is the one
    // given as initial state, as in `R = DYNA_NON_LINE(reuse=R, ETAT_INIT=_F(EVOL_NOLI=R), ...)`.
    .reentrant(Reentrant::Optional("ETAT_INIT/EVOL_NOLI"))
    .doc("Computes the nonlinear dynamic evolution of a structure (evol_noli); with reuse= it continues a result.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}

fn schema_temps() -> Keyword {
    let explicit = ["TCHAMWA", "DIFF_CENT"];
    fact(
        "SCHEMA_TEMPS",
        vec![
            text("SCHEMA")
                .required()
                .into(&[
                    "DIFF_CENT",
                    "TCHAMWA",
                    "NEWMARK",
                    "HHT",
                    "THETA_METHODE",
                    "KRENK",
                ])
                .doc("time integration scheme (DIFF_CENT, TCHAMWA explicit; the others implicit)")
                .kw(),
            real("COEF_MASS_SHIFT").default(r(0.0)).kw(),
            block(
                "b_tchamwa",
                eq("SCHEMA", "TCHAMWA"),
                vec![real("PHI").default(r(1.05)).doc("Tchamwa dissipation").kw()],
            )
            .kw(),
            block(
                "b_newmark",
                eq("SCHEMA", "NEWMARK"),
                vec![
                    real("BETA")
                        .default(r(0.25))
                        .doc("Newmark beta (must be > 0)")
                        .kw(),
                    real("GAMMA").default(r(0.5)).doc("Newmark gamma").kw(),
                ],
            )
            .kw(),
            block(
                "b_hht",
                eq("SCHEMA", "HHT"),
                vec![
                    real("ALPHA")
                        .default(r(-0.1))
                        .doc("HHT alpha <= 0: beta = (1-alpha)^2/4, gamma = 1/2 - alpha")
                        .kw(),
                    oui_non("MODI_EQUI", "OUI")
                        .doc("'OUI': true alpha-method (equilibrium weighted between steps); 'NON': only beta, gamma change")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_theta",
                eq("SCHEMA", "THETA_METHODE"),
                vec![real("THETA")
                    .default(r(1.0))
                    .min_val(0.5)
                    .max_val(100.0)
                    .kw()],
            )
            .kw(),
            block(
                "b_krenk",
                eq("SCHEMA", "KRENK"),
                vec![real("KAPPA")
                    .default(r(1.0))
                    .min_val(1.0)
                    .max_val(100.0)
                    .kw()],
            )
            .kw(),
            block(
                "b_explicit",
                is_in("SCHEMA", &explicit),
                vec![
                    oui_non("STOP_CFL", "OUI")
                        .doc("stop when a step exceeds the critical (CFL) step")
                        .kw(),
                    text("FORMULATION")
                        .required()
                        .into(&["ACCELERATION"])
                        .doc("primary unknown: acceleration")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_implicit",
                not(is_in("SCHEMA", &explicit)),
                vec![text("FORMULATION")
                    .required()
                    .into(&["DEPLACEMENT", "VITESSE", "ACCELERATION"])
                    .doc("primary unknown (VITESSE is forbidden with NEWMARK/HHT)")
                    .kw()],
            )
            .kw(),
        ],
    )
    .required()
    .doc("time integration scheme")
    .kw()
}
