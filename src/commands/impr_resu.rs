//! IMPR_RESU: writes meshes and results (MED files, readable listings).

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let mut acces = vec![
        text("TOUT_CHAM").into(&["OUI", "NON"]).kw(),
        text("NOM_CHAM")
            .many()
            .into(NOM_CHAM_RESU)
            .doc("fields written")
            .kw(),
        text("TOUT_ORDRE").into(&["OUI"]).kw(),
        int("NUME_ORDRE").many().kw(),
        real("INST").many().kw(),
        concept("LIST_INST", &[C::Listr8]).kw(),
    ];
    acces.extend(critere_precision(1e-6));
    let unit = |format: &'static str, unite: i64| {
        block(
            match format {
                "MED" => "b_format_med",
                "RESULTAT" => "b_format_resultat",
                "IDEAS" => "b_format_ideas",
                "ASTER" => "b_format_aster",
                _ => "b_format_gmsh",
            },
            eq("FORMAT", format),
            vec![int("UNITE")
                .default(i(unite))
                .doc("logical unit written")
                .kw()],
        )
        .kw()
    };
    let spec = command(
        "IMPR_RESU",
        Produces::Nothing,
        vec![
            text("FORMAT")
                .into(&["RESULTAT", "IDEAS", "ASTER", "MED", "GMSH"])
                .default(t("MED"))
                .kw(),
            unit("MED", 80),
            unit("RESULTAT", 8),
            unit("IDEAS", 30),
            unit("ASTER", 26),
            unit("GMSH", 37),
            block(
                "b_version_med",
                eq("FORMAT", "MED"),
                vec![text("VERSION_MED")
                    .default(t("3.3.1"))
                    .doc("version of the MED file format written")
                    .kw()],
            )
            .kw(),
            concept("MODELE", &[C::Modele]).kw(),
            fact(
                "RESU",
                vec![
                    concept("MAILLAGE", &[C::Maillage]).doc("mesh written too").kw(),
                    concept("CHAM_GD", &[C::ChamNo]).kw(),
                    concept("RESULTAT", &[C::EvolNoli]).kw(),
                    oui_non("INFO_MAILLAGE", "NON").kw(),
                    block("b_extrac", present("RESULTAT"), acces)
                        .rules(vec![
                            exclus(&["TOUT_CHAM", "NOM_CHAM"]),
                            exclus(&["TOUT_ORDRE", "NUME_ORDRE", "INST", "LIST_INST"]),
                        ])
                        .kw(),
                    text("TOUT_CMP").into(&["OUI"]).kw(),
                    text("NOM_CMP").many().kw(),
                    text("NOM_CHAM_MED")
                        .many()
                        .doc("MED field name; default: result name padded with '_' to 8, then the field name")
                        .kw(),
                    text("NOM_RESU_MED").kw(),
                    tout(),
                    group_no(),
                    noeud(),
                    group_ma(),
                    maille(),
                    text("VALE_MAX").into(&["OUI"]).kw(),
                    text("VALE_MIN").into(&["OUI"]).kw(),
                    real("BORNE_SUP").kw(),
                    real("BORNE_INF").kw(),
                    oui_non("IMPR_COOR", "NON").kw(),
                    text("FORMAT_R")
                        .default(t("1PE21.14"))
                        .doc("format of reals (RESULTAT/ASTER formats)")
                        .kw(),
                    text("SOUS_TITRE").many().kw(),
                ],
            )
            .required()
            .many()
            .rules(vec![
                au_moins_un(&["CHAM_GD", "RESULTAT", "MAILLAGE"]),
                exclus(&["CHAM_GD", "RESULTAT"]),
                exclus(&["TOUT_CMP", "NOM_CMP"]),
                exclus(&["NOM_CHAM_MED", "NOM_RESU_MED"]),
            ])
            .doc("what to write")
            .kw(),
            info(),
        ],
    )
    .doc("Writes a mesh and/or results in a file format.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
