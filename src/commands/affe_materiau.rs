//! AFFE_MATERIAU: assigns materials to cells.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let spec = command(
        "AFFE_MATERIAU",
        Produces::Concept(C::ChamMater),
        vec![
            concept("MAILLAGE", &[C::Maillage]).kw(),
            concept("MODELE", &[C::Modele]).kw(),
            fact(
                "AFFE",
                vec![
                    tout(),
                    group_ma(),
                    maille(),
                    concept("MATER", &[C::Mater])
                        .required()
                        .count(1, 30)
                        .doc("material of these cells")
                        .kw(),
                ],
            )
            .required()
            .many()
            .rules(vec![un_parmi(&["TOUT", "GROUP_MA", "MAILLE"])])
            .doc("material per cell group; on a cell given twice the last occurrence wins")
            .kw(),
            info(),
        ],
    )
    .rules(vec![au_moins_un(&["MAILLAGE", "MODELE"])])
    .doc("Builds the material field (cham_mater) over the mesh.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
