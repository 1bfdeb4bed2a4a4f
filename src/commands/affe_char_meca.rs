//! AFFE_CHAR_MECA: mechanical loads and boundary conditions.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let mut ddl = vec![
        tout(),
        group_ma(),
        maille(),
        group_no(),
        noeud(),
        text("SANS_GROUP_MA").many().kw(),
        text("SANS_MAILLE").many().hidden().kw(),
        text("SANS_GROUP_NO")
            .many()
            .doc("nodes excluded from the selection")
            .kw(),
        text("SANS_NOEUD").many().hidden().kw(),
        text("LIAISON")
            .into(&["ENCASTRE"])
            .doc("'ENCASTRE' blocks every dof")
            .kw(),
    ];
    for &c in CMP_DEPL {
        ddl.push(real(c).doc("imposed value of this component").kw());
    }
    let mut cmp_or_liaison = CMP_DEPL.to_vec();
    cmp_or_liaison.push("LIAISON");
    let spec = command(
        "AFFE_CHAR_MECA",
        Produces::Concept(C::CharMeca),
        vec![
            concept("MODELE", &[C::Modele]).required().kw(),
            fact("DDL_IMPO", ddl)
                .many()
                .rules(vec![
                    au_moins_un(&["TOUT", "GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"]),
                    Rule::AtLeastOne(cmp_or_liaison),
                ])
                .doc("imposed dofs (dualised by Lagrange multipliers); GROUP_MA means all nodes of those cells")
                .kw(),
            oui_non("VERI_NORM", "OUI")
                .doc("check the orientation of skin cells carrying loads")
                .kw(),
            oui_non("DOUBLE_LAGRANGE", "OUI")
                .doc("two Lagrange multipliers per constraint")
                .kw(),
            info(),
        ],
    )
    .rules(vec![au_moins_un(&["DDL_IMPO"])])
    .doc("Defines mechanical boundary conditions on a model.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
