//! CREA_MAILLAGE: builds a new mesh from an existing one.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let selection = || vec![tout(), maille(), group_ma()];
    let rule = || vec![au_moins_un(&["TOUT", "MAILLE", "GROUP_MA"])];
    let spec = command(
        "CREA_MAILLAGE",
        Produces::Concept(C::Maillage),
        vec![
            concept("MAILLAGE", &[C::Maillage])
                .required()
                .doc("the source mesh (left unchanged)")
                .kw(),
            fact("QUAD_LINE", selection())
                .rules(rule())
                .doc("quadratic to linear cells; mid-nodes used only by converted cells are deleted, empty node groups vanish")
                .kw(),
            fact(
                "LINE_QUAD",
                [
                    selection(),
                    vec![
                        text("PREF_NOEUD").default(t("NS")).kw(),
                        int("PREF_NUME").default(i(1)).kw(),
                    ],
                ]
                .concat(),
            )
            .rules(rule())
            .doc("linear to quadratic cells")
            .kw(),
            fact(
                "RESTREINT",
                vec![
                    group_ma(),
                    maille(),
                    oui_non("TOUT_GROUP_MA", "NON").kw(),
                    group_no(),
                    oui_non("TOUT_GROUP_NO", "NON").kw(),
                ],
            )
            .rules(vec![au_moins_un(&["GROUP_MA", "MAILLE"])])
            .doc("restricts the mesh to some cell groups")
            .kw(),
            titre(),
            info(),
        ],
    )
    .rules(vec![un_parmi(&["QUAD_LINE", "LINE_QUAD", "RESTREINT"])])
    .doc("Creates a new mesh from MAILLAGE (never in place).");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
