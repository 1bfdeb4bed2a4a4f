//! IMPR_TABLE: prints a table.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let tableau = ["TABLEAU", "AGRAF"];
    let spec = command(
        "IMPR_TABLE",
        Produces::Nothing,
        vec![
            concept("TABLE", &[C::Table]).required().kw(),
            text("FORMAT")
                .into(&[
                    "TABLEAU",
                    "ASTER",
                    "TABLEAU_CROISE",
                    "AGRAF",
                    "XMGRACE",
                    "NUMPY",
                ])
                .default(t("TABLEAU"))
                .kw(),
            block(
                "b_unite_xmgrace",
                eq("FORMAT", "XMGRACE"),
                vec![
                    int("UNITE").default(i(29)).doc("logical unit written").kw(),
                    text("PILOTE")
                        .default(t(""))
                        .into(&[
                            "",
                            "POSTSCRIPT",
                            "EPS",
                            "MIF",
                            "SVG",
                            "PNM",
                            "PNG",
                            "JPEG",
                            "PDF",
                            "INTERACTIF",
                        ])
                        .doc("'' writes the .agr project text")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_unite",
                not(eq("FORMAT", "XMGRACE")),
                vec![int("UNITE")
                    .default(i(8))
                    .doc("logical unit written (8 is the .resu file)")
                    .kw()],
            )
            .kw(),
            text("NOM_PARA")
                .many()
                .doc("columns printed, in this order; columns left empty are dropped")
                .kw(),
            c_filtre(),
            fact(
                "TRI",
                vec![
                    text("NOM_PARA").required().many().kw(),
                    text("ORDRE")
                        .into(&["CROISSANT", "DECROISSANT"])
                        .default(t("CROISSANT"))
                        .kw(),
                ],
            )
            .doc("row sorting")
            .kw(),
            text("FORMAT_R")
                .default(t("E12.5"))
                .doc("Fortran-like format of reals")
                .kw(),
            fact("PAGINATION", vec![text("NOM_PARA").required().many().kw()]).kw(),
            block(
                "b_tableau",
                is_in("FORMAT", &tableau),
                vec![
                    text("SEPARATEUR").default(t(" ")).kw(),
                    text("COMMENTAIRE").default(t("#")).kw(),
                    text("COMM_PARA").default(t("")).kw(),
                    text("DEBUT_LIGNE").default(t("")).kw(),
                    text("FIN_LIGNE").default(t("\n")).kw(),
                    text("DEBUT_TABLE").kw(),
                    text("FIN_TABLE").kw(),
                ],
            )
            .kw(),
            text("TITRE").many().kw(),
            info(),
        ],
    )
    .doc("Prints a table to a logical unit.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
