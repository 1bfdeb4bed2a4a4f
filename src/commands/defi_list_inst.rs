//! DEFI_LIST_INST: a time list with step-cutting and adaptation rules.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_LIST_INST",
        Produces::Concept(C::ListInst),
        vec![
            text("METHODE")
                .into(&["MANUEL", "AUTO"])
                .default(t("MANUEL"))
                .doc("fixed list, or steps that grow on success (AUTO)")
                .kw(),
            block(
                "b_manuel",
                eq("METHODE", "MANUEL"),
                vec![fact(
                    "DEFI_LIST",
                    vec![
                        real("VALE").many().kw(),
                        concept("LIST_INST", &[C::Listr8]).kw(),
                        concept("RESULTAT", &[C::EvolNoli])
                            .doc("take the instants of a result")
                            .kw(),
                        int("SUBD_PAS")
                            .min_val(1.0)
                            .doc("split each step of RESULTAT")
                            .kw(),
                    ],
                )
                .required()
                .rules(vec![
                    un_parmi(&["LIST_INST", "VALE", "RESULTAT"]),
                    present_present("RESULTAT", &["SUBD_PAS"]),
                ])
                .doc("the instants")
                .kw()],
            )
            .kw(),
            block(
                "b_auto",
                eq("METHODE", "AUTO"),
                vec![
                    fact(
                        "DEFI_LIST",
                        vec![
                            real("VALE").many().kw(),
                            concept("LIST_INST", &[C::Listr8]).kw(),
                            real("PAS_MINI").min_val(1e-12).doc("smallest step").kw(),
                            real("PAS_MAXI").doc("largest step").kw(),
                            int("NB_PAS_MAXI")
                                .default(i(1000000))
                                .max_val(1e6)
                                .kw(),
                        ],
                    )
                    .required()
                    .rules(vec![un_parmi(&["LIST_INST", "VALE"])])
                    .doc("the initial instants")
                    .kw(),
                    adaptation(),
                ],
            )
            .kw(),
            echec(),
            info(),
        ],
    )
    .doc("Defines a time list for INCREMENT/LIST_INST with failure handling (step cutting) and adaptation.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}

/// Manual cutting: equal sub-steps, a maximum level, a minimum step.
fn bloc_manu() -> Keyword {
    block(
        "b_deco_manu",
        eq("SUBD_METHODE", "MANUEL"),
        vec![
            int("SUBD_PAS")
                .default(i(4))
                .min_val(2.0)
                .doc("number of equal sub-steps a failed step is cut into")
                .kw(),
            int("SUBD_NIVEAU")
                .default(i(3))
                .min_val(2.0)
                .doc("maximum subdivision level (the original steps are level 1)")
                .kw(),
            real("SUBD_PAS_MINI")
                .default(r(0.0))
                .min_val(0.0)
                .doc("cutting fails below this step")
                .kw(),
        ],
    )
    .rules(vec![au_moins_un(&["SUBD_NIVEAU", "SUBD_PAS_MINI"])])
    .kw()
}

/// Automatic cutting (extrapolation of the residuals).
fn bloc_auto() -> Keyword {
    block(
        "b_deco_auto",
        eq("SUBD_METHODE", "AUTO"),
        vec![real("SUBD_PAS_MINI")
            .default(r(0.0))
            .min_val(0.0)
            .doc("cutting fails below this step")
            .kw()],
    )
    .kw()
}

/// DECOUPE for the failure events: method defaults to MANUEL.
fn bloc_deco(cond: Cond) -> Keyword {
    block(
        "b_deco",
        cond,
        vec![
            text("SUBD_METHODE")
                .into(&["MANUEL", "AUTO"])
                .default(t("MANUEL"))
                .doc("how the failed step is cut")
                .kw(),
            bloc_manu(),
            bloc_auto(),
        ],
    )
    .kw()
}

fn echec() -> Keyword {
    let action = |choices: &[&'static str], default: &'static str| {
        text("ACTION")
            .into(choices)
            .default(t(default))
            .doc("what to do when the event occurs")
            .kw()
    };
    fact(
        "ECHEC",
        vec![
            text("EVENEMENT")
                .into(&[
                    "ERREUR",
                    "DELTA_GRANDEUR",
                    "COLLISION",
                    "RESI_MAXI",
                    "INTERPENETRATION",
                    "DIVE_RESI",
                    "INSTABILITE",
                ])
                .default(t("ERREUR"))
                .doc("ERREUR is any failure of a step (Newton not converged, law failure, singular matrix...)")
                .kw(),
            block(
                "b_erreur",
                eq("EVENEMENT", "ERREUR"),
                vec![
                    action(&["ARRET", "DECOUPE", "ITER_SUPPL", "AUTRE_PILOTAGE"], "DECOUPE"),
                    bloc_deco(is_in("ACTION", &["DECOUPE", "AUTRE_PILOTAGE"])),
                    block(
                        "b_supp",
                        eq("ACTION", "ITER_SUPPL"),
                        vec![
                            int("PCENT_ITER_PLUS")
                                .default(i(50))
                                .min_val(20.0)
                                .doc("extra Newton iterations allowed, in percent")
                                .kw(),
                            text("SUBD_METHODE")
                                .into(&["MANUEL", "AUTO"])
                                .default(t("MANUEL"))
                                .kw(),
                            bloc_manu(),
                            bloc_auto(),
                        ],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_edelta",
                eq("EVENEMENT", "DELTA_GRANDEUR"),
                vec![
                    real("VALE_REF").required().doc("threshold on the increment").kw(),
                    text("NOM_CHAM")
                        .required()
                        .into(&["DEPL", "VARI_ELGA", "SIEF_ELGA"])
                        .kw(),
                    text("NOM_CMP").required().kw(),
                    action(&["ARRET", "DECOUPE"], "DECOUPE"),
                    bloc_deco(eq("ACTION", "DECOUPE")),
                ],
            )
            .kw(),
            block(
                "b_colli",
                eq("EVENEMENT", "COLLISION"),
                vec![
                    action(&["ARRET", "DECOUPE"], "DECOUPE"),
                    block(
                        "b_deco2",
                        eq("ACTION", "DECOUPE"),
                        vec![
                            text("SUBD_METHODE")
                                .into(&["MANUEL", "AUTO"])
                                .default(t("AUTO"))
                                .doc("for a collision AUTO refines the steps for SUBD_DUREE")
                                .kw(),
                            bloc_manu(),
                            block(
                                "b_deco_auto",
                                eq("SUBD_METHODE", "AUTO"),
                                vec![
                                    real("SUBD_INST")
                                        .required()
                                        .min_val(0.0)
                                        .doc("target step during the collision")
                                        .kw(),
                                    real("SUBD_DUREE")
                                        .required()
                                        .min_val(0.0)
                                        .doc("duration of the refinement after a collision starts")
                                        .kw(),
                                ],
                            )
                            .kw(),
                        ],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_resi_maxi",
                eq("EVENEMENT", "RESI_MAXI"),
                vec![
                    real("RESI_GLOB_MAXI")
                        .required()
                        .doc("residual above which the step is cut")
                        .kw(),
                    action(&["ARRET", "DECOUPE"], "DECOUPE"),
                    bloc_deco(eq("ACTION", "DECOUPE")),
                ],
            )
            .kw(),
            block(
                "b_penetration",
                eq("EVENEMENT", "INTERPENETRATION"),
                vec![
                    real("PENE_MAXI")
                        .required()
                        .doc("largest allowed penetration of discrete contact")
                        .kw(),
                    action(&["ARRET", "ADAPT_COEF_PENA"], "ADAPT_COEF_PENA"),
                    block(
                        "b_pene",
                        eq("ACTION", "ADAPT_COEF_PENA"),
                        vec![real("COEF_MAXI")
                            .default(r(1e12))
                            .min_val(1.0)
                            .doc("cap of E_N, doubled at each event")
                            .kw()],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_dive_resi",
                eq("EVENEMENT", "DIVE_RESI"),
                vec![
                    action(&["DECOUPE"], "DECOUPE"),
                    bloc_deco(eq("ACTION", "DECOUPE")),
                ],
            )
            .kw(),
            block(
                "b_instabilite",
                eq("EVENEMENT", "INSTABILITE"),
                vec![action(&["ARRET", "CONTINUE"], "CONTINUE")],
            )
            .kw(),
        ],
    )
    .defaulted()
    .many()
    .doc("failure events and actions; an ERREUR event (DECOUPE, 4 sub-steps, 3 levels) always exists")
    .kw()
}

fn adaptation() -> Keyword {
    fact(
        "ADAPTATION",
        vec![
            text("EVENEMENT")
                .into(&["SEUIL", "TOUT_INST", "AUCUN"])
                .default(t("SEUIL"))
                .doc("when the next step may grow")
                .kw(),
            block(
                "b_adap_seuil",
                eq("EVENEMENT", "SEUIL"),
                vec![
                    int("NB_INCR_SEUIL").default(i(2)).kw(),
                    text("NOM_PARA")
                        .into(&["NB_ITER_NEWTON"])
                        .default(t("NB_ITER_NEWTON"))
                        .kw(),
                    text("CRIT_COMP")
                        .into(&["LT", "GT", "LE", "GE"])
                        .default(t("LE"))
                        .kw(),
                    block(
                        "b_vale_I",
                        eq("NOM_PARA", "NB_ITER_NEWTON"),
                        vec![int("VALE_I").kw()],
                    )
                    .kw(),
                ],
            )
            .kw(),
            text("MODE_CALCUL_TPLUS")
                .into(&["FIXE", "DELTA_GRANDEUR", "ITER_NEWTON", "IMPLEX"])
                .default(t("FIXE"))
                .doc("how the next step is computed")
                .kw(),
            block(
                "b_mfixe",
                eq("MODE_CALCUL_TPLUS", "FIXE"),
                vec![real("PCENT_AUGM")
                    .default(r(100.0))
                    .min_val(-100.0)
                    .doc("growth of the step, in percent")
                    .kw()],
            )
            .kw(),
            block(
                "b_mdelta",
                eq("MODE_CALCUL_TPLUS", "DELTA_GRANDEUR"),
                vec![
                    real("VALE_REF").required().kw(),
                    text("NOM_CHAM")
                        .required()
                        .into(&["DEPL", "VARI_ELGA", "SIEF_ELGA"])
                        .kw(),
                    text("NOM_CMP").required().kw(),
                ],
            )
            .kw(),
            block(
                "b_mitnew",
                eq("MODE_CALCUL_TPLUS", "ITER_NEWTON"),
                vec![int("NB_ITER_NEWTON_REF").required().kw()],
            )
            .kw(),
        ],
    )
    .defaulted()
    .many()
    .doc("step growth after successful steps (METHODE='AUTO')")
    .kw()
}
