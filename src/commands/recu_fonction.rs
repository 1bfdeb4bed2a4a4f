//! RECU_FONCTION: a function of time extracted from a result or a table.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let mut prec = critere_precision(1e-6);
    prec.push(text("INTERP_NUME").into(&["NON", "LIN"]).kw());
    let spec = command(
        "RECU_FONCTION",
        Produces::Concept(C::Fonction),
        vec![
            concept("RESULTAT", &[C::EvolNoli]).kw(),
            concept("TABLE", &[C::Table]).kw(),
            block(
                "b_acces",
                present("RESULTAT"),
                vec![
                    text("TOUT_ORDRE").into(&["OUI"]).kw(),
                    int("NUME_ORDRE").many().kw(),
                    text("TOUT_INST").into(&["OUI"]).kw(),
                    real("INST").many().kw(),
                    concept("LIST_INST", &[C::Listr8]).kw(),
                    block(
                        "b_prec",
                        or(vec![present("INST"), present("LIST_INST")]),
                        prec,
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_resu",
                present("RESULTAT"),
                vec![
                    text("NOM_CHAM").into(NOM_CHAM_RESU).kw(),
                    text("NOM_PARA_RESU")
                        .doc("a result parameter instead of a field")
                        .kw(),
                    block(
                        "b_cham",
                        present("NOM_CHAM"),
                        vec![
                            text("NOM_CMP").required().kw(),
                            text("MAILLE").hidden().kw(),
                            text("GROUP_MA").kw(),
                            text("NOEUD").hidden().kw(),
                            text("GROUP_NO")
                                .doc("with several nodes the first one is used, with an alarm")
                                .kw(),
                            int("POINT").kw(),
                            int("SOUS_POINT").kw(),
                        ],
                    )
                    .rules(vec![
                        au_moins_un(&["MAILLE", "GROUP_MA", "GROUP_NO", "NOEUD"]),
                        present_absent("POINT", &["NOEUD", "GROUP_NO"]),
                        present_absent("SOUS_POINT", &["NOEUD", "GROUP_NO"]),
                        exclus(&["GROUP_MA", "MAILLE"]),
                        exclus(&["GROUP_NO", "NOEUD"]),
                    ])
                    .kw(),
                ],
            )
            .rules(vec![un_parmi(&["NOM_CHAM", "NOM_PARA_RESU"])])
            .kw(),
            block(
                "b_table",
                present("TABLE"),
                vec![
                    text("PARA_X").doc("column of the abscissas").kw(),
                    text("PARA_Y").doc("column of the ordinates").kw(),
                    text("NOM_PARA_TABL").into(&["FONCTION", "FONCTION_C"]).kw(),
                    c_filtre(),
                ],
            )
            .rules(vec![
                un_parmi(&["PARA_X", "NOM_PARA_TABL"]),
                present_present("PARA_X", &["PARA_Y"]),
            ])
            .kw(),
            text("NOM_PARA")
                .into(&["INST", "X", "Y", "Z", "FREQ", "ABSC"])
                .doc("overrides the parameter name (default INST for a result)")
                .kw(),
            text("NOM_RESU").doc("overrides the value name (default: the component)").kw(),
            text("INTERPOL")
                .count(1, 2)
                .into(&["NON", "LIN", "LOG"])
                .doc("interpolation, default 'LIN LIN'")
                .kw(),
            text("PROL_DROITE")
                .into(&["CONSTANT", "LINEAIRE", "EXCLU"])
                .doc("extrapolation on the right, default EXCLU")
                .kw(),
            text("PROL_GAUCHE")
                .into(&["CONSTANT", "LINEAIRE", "EXCLU"])
                .doc("extrapolation on the left, default EXCLU")
                .kw(),
            titre(),
            info(),
        ],
    )
    .rules(vec![un_parmi(&["RESULTAT", "TABLE"])])
    .doc("Extracts the evolution of one component at one node over all stored instants (or columns of a table) as a function.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
