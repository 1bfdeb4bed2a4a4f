//! MODI_MAILLAGE: modifies a mesh in place (skin orientation, moves).

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let spec = command(
        "MODI_MAILLAGE",
        Produces::Concept(C::Maillage),
        vec![
            concept("MAILLAGE", &[C::Maillage])
                .required()
                .doc("the mesh to modify (also the reused concept)")
                .kw(),
            fact(
                "ORIE_PEAU_2D",
                vec![
                    text("GROUP_MA")
                        .required()
                        .many()
                        .doc("SEG2/SEG3 skin cells to orient")
                        .kw(),
                    text("GROUP_MA_SURF")
                        .many()
                        .doc("restricts the support cells searched")
                        .kw(),
                ],
            )
            .many()
            .doc("orients 2D skin cells so that their normal points out of their support cell")
            .kw(),
            fact(
                "ORIE_PEAU_3D",
                vec![
                    text("GROUP_MA")
                        .required()
                        .many()
                        .doc("TRIA/QUAD skin cells to orient")
                        .kw(),
                    text("GROUP_MA_VOLU")
                        .many()
                        .doc("restricts the support cells searched")
                        .kw(),
                ],
            )
            .many()
            .doc("orients 3D skin cells so that their normal points out of their support cell")
            .kw(),
            real("TRANSLATION").count(2, 3).doc("translation vector").kw(),
            fact(
                "ROTATION",
                vec![
                    real("POIN_1").required().count(2, 3).kw(),
                    real("ANGLE").default(r(0.0)).doc("in degrees").kw(),
                    real("POIN_2").count(2, 3).kw(),
                    real("DIR").count(2, 3).kw(),
                ],
            )
            .many()
            .rules(vec![exclus(&["DIR", "POIN_2"])])
            .doc("rotation about the axis through POIN_1")
            .kw(),
            real("ECHELLE").doc("scale factor on coordinates").kw(),
            info(),
        ],
    )
    .reentrant(Reentrant::Required("MAILLAGE"))
    .rules(vec![
        au_moins_un(&["ORIE_PEAU_2D", "ORIE_PEAU_3D", "TRANSLATION", "ROTATION", "ECHELLE"]),
        present_absent("ORIE_PEAU_2D", &["ORIE_PEAU_3D"]),
    ])
    .doc("Modifies a mesh in place (reuse compulsory): skin orientation before contact or pressure, or geometric moves.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
