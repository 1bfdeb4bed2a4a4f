//! STAT_NON_LINE: quasi-static nonlinear analysis.
//!
//! Why a separate command on a shared executor: code_aster users verify an
//! element, a law or a unilateral condition statically (a patch test, a
//! cantilever, a floor), and their files call STAT_NON_LINE. The
//! computation is DYNA_NON_LINE's implicit engine with the inertia removed
//! (`time::Scheme::quasi_static`); the keywords both commands share are
//! parsed by `dyna_non_line::run`, so the two cannot drift.

use super::blocks::*;
use super::dyna_non_line::{run, Analysis};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "STAT_NON_LINE",
        Produces::Concept(C::EvolNoli),
        vec![
            concept("MODELE", &[C::Modele]).required().kw(),
            concept("CHAM_MATER", &[C::ChamMater])
                .doc("material field (needed by every element of this engine)")
                .kw(),
            fact(
                "EXCIT",
                vec![
                    text("TYPE_CHARGE")
                        .into(&["FIXE_CSTE", "FIXE_PILO", "SUIV", "DIDI"])
                        .not_built(
                            &["FIXE_PILO", "SUIV", "DIDI"],
                            "loads are dead, FIXE_CSTE, built on the initial geometry; no PILOTAGE",
                        )
                        .default(t("FIXE_CSTE"))
                        .doc("dead load (FIXE_CSTE); the others are not implemented yet")
                        .kw(),
                    concept("CHARGE", &[C::CharMeca, C::CharCineMeca]).required().kw(),
                    concept("FONC_MULT", &[C::Fonction, C::Formule])
                        .doc("multiplier of the load, a function (or FORMULE) of INST (pseudo-time)")
                        .kw(),
                ],
            )
            .many()
            .doc("loads and boundary conditions")
            .kw(),
            concept("CONTACT", &[C::CharContact])
                .doc("contact definition from DEFI_CONTACT (DISCRETE penalised, CONTINUE, LIAISON_UNIL)")
                .kw(),
            c_comportement(),
            c_etat_init_stat(),
            c_resultat_reuse(),
            c_increment(),
            text("METHODE")
                .into(&["NEWTON", "IMPLEX", "NEWTON_KRYLOV", "SNES", "RASPEN"])
                .default(t("NEWTON"))
                .kw(),
            c_newton(),
            c_rech_lineaire(),
            fact(
                "PILOTAGE",
                vec![
                    text("TYPE")
                        .required()
                        .into(&[
                            "DDL_IMPO",
                            "LONG_ARC",
                            "PRED_ELAS",
                            "DEFORMATION",
                            "ANA_LIM",
                            "SAUT_IMPO",
                            "SAUT_LONG_ARC",
                        ])
                        .kw(),
                    real("COEF_MULT").default(r(1.0)).kw(),
                    real("ETA_PILO_MAX").kw(),
                    real("ETA_PILO_MIN").kw(),
                    text("GROUP_NO").many().kw(),
                    text("GROUP_MA").many().kw(),
                    text("NOM_CMP").many().kw(),
                ],
            )
            .doc("continuation (not implemented yet)")
            .kw(),
            c_convergence(),
            c_solveur(),
            c_suivi_ddl(),
            c_observation(),
            c_energie(),
            c_affichage(),
            c_archivage(),
            info(),
            titre(),
        ],
    )
    .reentrant(Reentrant::Optional("ETAT_INIT/EVOL_NOLI"))
    .doc("Computes the quasi-static nonlinear evolution of a structure (evol_noli): equilibrium at each instant of the list, no inertia; with reuse= it continues a result.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    if let Some(m) = args.text("METHODE").filter(|m| *m != "NEWTON") {
        return Err(args.not_implemented(
            "METHODE",
            &format!("METHODE='{m}'; only 'NEWTON' is implemented"),
        ));
    }
    run(study, args, result, Analysis::Static)
}
