//! LIRE_MAILLAGE: reads a mesh from a logical unit.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let spec = command(
        "LIRE_MAILLAGE",
        Produces::Concept(C::Maillage),
        vec![
            text("FORMAT")
                .into(&["ASTER", "GIBI", "GMSH", "IDEAS", "MED"])
                .default(t("MED"))
                .doc("file format")
                .kw(),
            int("UNITE")
                .default(i(20))
                .doc("logical unit of the mesh file (fort.20 by default)")
                .kw(),
            block(
                "b_format_med",
                eq("FORMAT", "MED"),
                vec![
                    text("NOM_MED")
                        .doc("name of the mesh in the MED file; absent: the first one")
                        .kw(),
                    int("INFO_MED").default(i(1)).into_ints(&[1, 2, 3]).kw(),
                    text("PARTITIONNEUR")
                        .into(&["SANS", "PTSCOTCH"])
                        .default(t("SANS"))
                        .kw(),
                ],
            )
            .kw(),
            fact(
                "VERI_MAIL",
                vec![
                    oui_non("VERIF", "OUI").doc("check the mesh").kw(),
                    real("APLAT")
                        .default(r(1e-3))
                        .doc("flatness threshold of the check")
                        .kw(),
                ],
            )
            .defaulted()
            .doc("mesh checks after reading")
            .kw(),
            info(),
        ],
    )
    .doc("Reads a mesh; MED cell groups become GROUP_MA, node groups GROUP_NO.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
