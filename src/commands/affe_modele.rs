//! AFFE_MODELE: assigns finite elements to the cells of a mesh.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let spec = command(
        "AFFE_MODELE",
        Produces::Concept(C::Modele),
        vec![
            concept("MAILLAGE", &[C::Maillage]).required().kw(),
            fact(
                "AFFE",
                vec![
                    tout(),
                    group_ma(),
                    maille(),
                    text("PHENOMENE")
                        .required()
                        .into(&["MECANIQUE"])
                        .doc("physics; only MECANIQUE in aster")
                        .kw(),
                    block(
                        "b_mecanique",
                        eq("PHENOMENE", "MECANIQUE"),
                        vec![text("MODELISATION")
                            .required()
                            .into(MODELISATIONS)
                            .doc("element family; _SI is reduced integration")
                            .kw()],
                    )
                    .kw(),
                ],
            )
            .required()
            .many()
            .rules(vec![un_parmi(&["TOUT", "GROUP_MA", "MAILLE"])])
            .doc("applied in order: a later occurrence replaces the element wherever its modelisation has one for the cell type")
            .kw(),
            oui_non("VERI_JACOBIEN", "OUI")
                .doc("check element Jacobians")
                .kw(),
            info(),
        ],
    )
    .doc("Defines the model: physics and element type per cell.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
