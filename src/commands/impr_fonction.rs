//! IMPR_FONCTION: prints curves.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let echelle = |n: &'static str| text(n).into(&["LIN", "LOG"]).default(t("LIN")).kw();
    let spec = command(
        "IMPR_FONCTION",
        Produces::Nothing,
        vec![
            text("FORMAT")
                .into(&["TABLEAU", "AGRAF", "XMGRACE", "LISS_ENVELOP"])
                .default(t("TABLEAU"))
                .kw(),
            block(
                "b_xmgrace",
                eq("FORMAT", "XMGRACE"),
                vec![
                    int("UNITE")
                        .default(i(29))
                        .doc("logical unit of the .agr file")
                        .kw(),
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
                        .doc("'' writes the Grace project text; the others need xmgrace")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_unite",
                not(eq("FORMAT", "XMGRACE")),
                vec![int("UNITE").default(i(8)).doc("logical unit written").kw()],
            )
            .kw(),
            fact(
                "COURBE",
                vec![
                    concept("FONCTION", &[C::Fonction])
                        .required()
                        .doc("function plotted")
                        .kw(),
                    text("LEGENDE").doc("curve legend").kw(),
                    int("STYLE").kw(),
                    int("COULEUR").kw(),
                    int("MARQUEUR").kw(),
                    int("FREQ_MARQUEUR").default(i(0)).kw(),
                    text("TRI")
                        .into(&["N", "X", "Y", "XY", "YX"])
                        .default(t("N"))
                        .doc("sorting of the points")
                        .kw(),
                ],
            )
            .required()
            .many()
            .doc("one curve per occurrence")
            .kw(),
            text("TITRE").doc("graph title").kw(),
            text("SOUS_TITRE").kw(),
            real("BORNE_X").count(2, 2).kw(),
            real("BORNE_Y").count(2, 2).kw(),
            echelle("ECHELLE_X"),
            echelle("ECHELLE_Y"),
            real("GRILLE_X").kw(),
            real("GRILLE_Y").kw(),
            text("LEGENDE_X").kw(),
            text("LEGENDE_Y").kw(),
            info(),
        ],
    )
    .doc("Prints functions as curves (table, Agraf or Grace project).");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
