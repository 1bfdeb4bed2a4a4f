//! CREA_CHAMP: creates a field (here nodal fields).

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let mut extr = vec![
        concept("RESULTAT", &[C::EvolNoli])
            .required()
            .doc("result to extract from")
            .kw(),
        text("NOM_CHAM").required().into(NOM_CHAM_RESU).kw(),
        int("NUME_ORDRE").kw(),
        real("INST").kw(),
    ];
    extr.extend(critere_precision(1e-6));
    let spec = command(
        "CREA_CHAMP",
        Produces::Concept(C::ChamNo),
        vec![
            text("TYPE_CHAM")
                .required()
                .into(&["NOEU_DEPL_R"])
                .doc("location and quantity of the field (nodal real displacement-like)")
                .kw(),
            text("OPERATION")
                .required()
                .into(&["AFFE", "EXTR"])
                .doc("assign values, or extract a field from a result")
                .kw(),
            block(
                "b_affe",
                eq("OPERATION", "AFFE"),
                vec![
                    concept("MAILLAGE", &[C::Maillage]).kw(),
                    concept("MODELE", &[C::Modele])
                        .doc("model: its dofs (including contact LAGS_C, LAGS_F1) define the allowed components")
                        .kw(),
                    fact(
                        "AFFE",
                        vec![
                            tout(),
                            group_ma(),
                            maille(),
                            group_no(),
                            noeud(),
                            text("NOM_CMP").required().many().doc("components").kw(),
                            real("VALE")
                                .many()
                                .doc("values, one per NOM_CMP")
                                .kw(),
                            int("VALE_I").many().kw(),
                            concept("VALE_F", &[C::Fonction]).many().kw(),
                        ],
                    )
                    .required()
                    .many()
                    .rules(vec![
                        au_moins_un(&["TOUT", "GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"]),
                        un_parmi(&["VALE", "VALE_I", "VALE_F"]),
                    ])
                    .doc("applied in order, later occurrences overwrite earlier ones; unassigned components are absent")
                    .kw(),
                ],
            )
            .rules(vec![un_parmi(&["MAILLAGE", "MODELE"])])
            .kw(),
            block("b_extr", eq("OPERATION", "EXTR"), extr)
                .rules(vec![exclus(&["NUME_ORDRE", "INST"])])
                .kw(),
            info(),
            titre(),
        ],
    )
    .doc("Creates a nodal field, e.g. an initial velocity for ETAT_INIT.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
