//! POST_RELEVE_T: extracts field values into a table.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let mut extrac = vec![
        text("NOM_CHAM").required().into(NOM_CHAM_RESU).kw(),
        text("TOUT_ORDRE").into(&["OUI"]).kw(),
        int("NUME_ORDRE").many().kw(),
        real("INST").many().kw(),
        concept("LIST_INST", &[C::Listr8]).kw(),
    ];
    extrac.extend(critere_precision(1e-6));
    let other = ["EXTREMA", "MOYENNE_ARITH"];
    let spec = command(
        "POST_RELEVE_T",
        Produces::Concept(C::Table),
        vec![
            fact(
                "ACTION",
                vec![
                    text("OPERATION")
                        .required()
                        .count(1, 2)
                        .into(&["EXTRACTION", "MOYENNE", "MOYENNE_ARITH", "EXTREMA"])
                        .kw(),
                    text("INTITULE")
                        .required()
                        .doc("label of the rows, first column of the table")
                        .kw(),
                    concept("CHAM_GD", &[C::ChamNo]).kw(),
                    concept("RESULTAT", &[C::EvolNoli])
                        .doc("all stored indices unless restricted")
                        .kw(),
                    block("b_extrac", present("RESULTAT"), extrac)
                        .rules(vec![exclus(&["TOUT_ORDRE", "NUME_ORDRE", "INST", "LIST_INST"])])
                        .kw(),
                    tout(),
                    group_ma(),
                    maille(),
                    group_no(),
                    noeud(),
                    text("TOUT_CMP").into(&["OUI"]).doc("every component").kw(),
                    text("NOM_CMP").many().kw(),
                    text("INVARIANT").into(&["OUI"]).kw(),
                    text("ELEM_PRINCIPAUX").into(&["OUI"]).kw(),
                    text("RESULTANTE")
                        .many()
                        .into(&["DX", "DY", "DZ"])
                        .doc("sum of these components over the nodes")
                        .kw(),
                    text("MOMENT").many().into(&["DRX", "DRY", "DRZ"]).kw(),
                    real("POINT").many().kw(),
                    text("REPERE")
                        .into(&["GLOBAL", "LOCAL", "POLAIRE", "UTILISATEUR", "CYLINDRIQUE"])
                        .default(t("GLOBAL"))
                        .kw(),
                    real("ANGL_NAUT").count(3, 3).kw(),
                    real("ORIGINE").count(3, 3).kw(),
                    real("AXE_Z").count(3, 3).kw(),
                    text("TRAC_NOR").into(&["OUI"]).kw(),
                    text("TRAC_DIR").into(&["OUI"]).kw(),
                    real("DIRECTION").many().kw(),
                    real("VECT_Y").many().kw(),
                    oui_non("MOYE_NOEUD", "OUI")
                        .doc("average element-node fields at nodes")
                        .kw(),
                    text("FORMAT_C")
                        .into(&["MODULE", "REEL", "IMAG"])
                        .default(t("MODULE"))
                        .kw(),
                    block("b_autre", not(is_in("OPERATION", &other)), vec![])
                        .rules(vec![
                            au_moins_un(&["GROUP_NO", "NOEUD"]),
                            un_parmi(&[
                                "TOUT_CMP",
                                "NOM_CMP",
                                "INVARIANT",
                                "ELEM_PRINCIPAUX",
                                "RESULTANTE",
                            ]),
                            present_present("TRAC_DIR", &["DIRECTION"]),
                            ensemble(&["MOMENT", "POINT"]),
                            present_present("MOMENT", &["RESULTANTE"]),
                            present_absent("TOUT_CMP", &["TRAC_DIR", "TRAC_NOR"]),
                            exclus(&["TRAC_DIR", "TRAC_NOR"]),
                            present_present("ORIGINE", &["AXE_Z"]),
                        ])
                        .kw(),
                    block("b_extrema", is_in("OPERATION", &other), vec![])
                        .rules(vec![exclus(&["TOUT_CMP", "NOM_CMP"])])
                        .kw(),
                ],
            )
            .required()
            .many()
            .rules(vec![un_parmi(&["RESULTAT", "CHAM_GD"])])
            .doc("one extraction per occurrence; one row per (stored index, node)")
            .kw(),
            info(),
            titre(),
        ],
    )
    .doc("Extracts values of fields into a table (columns INTITULE, RESU, NOM_CHAM, NUME_ORDRE, INST, NOEUD, COOR_*, components).");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
