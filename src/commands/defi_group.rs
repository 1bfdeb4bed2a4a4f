//! DEFI_GROUP: creates or deletes groups of cells and nodes in a mesh.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_GROUP",
        Produces::Concept(C::Maillage),
        vec![
            concept("MAILLAGE", &[C::Maillage])
                .required()
                .doc("the mesh to modify (also the reused concept)")
                .kw(),
            fact("DETR_GROUP_MA", vec![text("NOM").required().many().kw()])
                .many()
                .doc("deletes cell groups")
                .kw(),
            fact("DETR_GROUP_NO", vec![text("NOM").required().many().kw()])
                .many()
                .doc("deletes node groups")
                .kw(),
            crea_group_ma(),
            crea_group_no(),
            oui_non("ALARME", "OUI")
                .doc("alarm when a group would be empty (it is then not created)")
                .kw(),
            info(),
        ],
    )
    .reentrant(Reentrant::Required("MAILLAGE"))
    .rules(vec![au_moins_un(&[
        "CREA_GROUP_MA",
        "CREA_GROUP_NO",
        "DETR_GROUP_NO",
        "DETR_GROUP_MA",
    ])])
    .doc("Adds or deletes groups in a mesh, in place (reuse compulsory); occurrences are processed in order.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}

fn crea_group_ma() -> Keyword {
    fact(
        "CREA_GROUP_MA",
        vec![
            text("NOM")
                .required()
                .doc("name of the new cell group")
                .kw(),
            tout(),
            text("GROUP_MA").doc("copy of this cell group").kw(),
            maille(),
            text("INTERSEC")
                .many()
                .doc("intersection of cell groups")
                .kw(),
            text("UNION").many().doc("union of cell groups").kw(),
            text("DIFFE")
                .many()
                .doc("first group minus the others")
                .kw(),
            text("TYPE_MAILLE")
                .into(&[
                    "TOUT", "1D", "2D", "3D", "POI1", "SEG2", "SEG3", "SEG4", "TRIA3", "TRIA6",
                    "TRIA7", "QUAD4", "QUAD8", "QUAD9", "TETRA4", "TETRA10", "PENTA6", "PENTA15",
                    "PENTA18", "HEXA8", "HEXA20", "HEXA27", "PYRAM5", "PYRAM13",
                ])
                .default(t("TOUT"))
                .doc("keep only cells of this type or dimension")
                .kw(),
        ],
    )
    .many()
    .rules(vec![un_parmi(&[
        "TOUT", "GROUP_MA", "MAILLE", "INTERSEC", "UNION", "DIFFE",
    ])])
    .doc("creates cell groups")
    .kw()
}

fn crea_group_no() -> Keyword {
    let nom = || {
        text("NOM")
            .required()
            .doc("name of the new node group")
            .kw()
    };
    let centre = || {
        vec![
            real("POINT")
                .count(2, 3)
                .doc("coordinates of the centre")
                .kw(),
            text("NOEUD_CENTRE").hidden().kw(),
            text("GROUP_NO_CENTRE").kw(),
        ]
    };
    let orient = || {
        vec![
            real("ANGL_NAUT")
                .count(1, 3)
                .doc("nautical angles of the axis, in degrees")
                .kw(),
            real("VECT_NORMALE")
                .count(2, 3)
                .doc("axis or normal vector")
                .kw(),
        ]
    };
    let prec = || {
        real("PRECISION")
            .required()
            .min_val(0.0)
            .doc("absolute distance tolerance")
            .kw()
    };
    fact(
        "CREA_GROUP_NO",
        vec![
            text("OPTION")
                .into(&["ENV_SPHERE", "ENV_CYLINDRE", "PLAN", "SEGM_DROI_ORDO", "NOEUD_ORDO"])
                .doc("geometric selection; absent: from groups")
                .kw(),
            block(
                "b_option",
                absent("OPTION"),
                vec![
                    text("TOUT_GROUP_MA")
                        .into(&["OUI"])
                        .doc("one node group per cell group, same name; existing names are kept")
                        .kw(),
                    group_ma(),
                    group_no(),
                    noeud(),
                    text("INTERSEC").many().kw(),
                    text("UNION").many().kw(),
                    text("DIFFE")
                        .many()
                        .doc("first group minus the others; not created when empty")
                        .kw(),
                    block(
                        "b_nom_group_ma",
                        present("GROUP_MA"),
                        vec![
                            text("NOM")
                                .many()
                                .doc("names of the node groups, one per GROUP_MA; absent: the cell groups' names")
                                .kw(),
                            text("CRIT_NOEUD")
                                .into(&["TOUS", "SOMMET", "MILIEU", "CENTRE"])
                                .default(t("TOUS"))
                                .doc("all nodes, vertices, mid-edge nodes or face/volume centres")
                                .kw(),
                        ],
                    )
                    .kw(),
                    block(
                        "b_group_no",
                        present("GROUP_NO"),
                        vec![
                            int("NUME_INIT").kw(),
                            text("POSITION").into(&["INIT", "FIN", "MILIEU"]).kw(),
                            block("b_nume_init", present("NUME_INIT"), vec![int("NUME_FIN").kw()])
                                .kw(),
                        ],
                    )
                    .rules(vec![exclus(&["POSITION", "NUME_INIT"])])
                    .kw(),
                    block(
                        "b_nom",
                        and(vec![absent("GROUP_MA"), absent("TOUT_GROUP_MA")]),
                        vec![nom()],
                    )
                    .kw(),
                ],
            )
            .rules(vec![un_parmi(&[
                "TOUT_GROUP_MA",
                "GROUP_MA",
                "GROUP_NO",
                "NOEUD",
                "INTERSEC",
                "UNION",
                "DIFFE",
            ])])
            .kw(),
            block(
                "b_env_sphere",
                eq("OPTION", "ENV_SPHERE"),
                [vec![nom()], centre(), vec![real("RAYON").required().kw(), prec()]].concat(),
            )
            .rules(vec![un_parmi(&["POINT", "NOEUD_CENTRE", "GROUP_NO_CENTRE"])])
            .kw(),
            block(
                "b_env_cylindre",
                eq("OPTION", "ENV_CYLINDRE"),
                [
                    vec![nom()],
                    centre(),
                    orient(),
                    vec![real("RAYON").required().kw(), prec()],
                ]
                .concat(),
            )
            .rules(vec![
                un_parmi(&["POINT", "NOEUD_CENTRE", "GROUP_NO_CENTRE"]),
                un_parmi(&["ANGL_NAUT", "VECT_NORMALE"]),
            ])
            .kw(),
            block(
                "b_env_plan",
                eq("OPTION", "PLAN"),
                [vec![nom()], centre(), orient(), vec![prec()]].concat(),
            )
            .rules(vec![
                un_parmi(&["POINT", "NOEUD_CENTRE", "GROUP_NO_CENTRE"]),
                un_parmi(&["ANGL_NAUT", "VECT_NORMALE"]),
            ])
            .kw(),
            block(
                "b_segm_droi_ordo",
                eq("OPTION", "SEGM_DROI_ORDO"),
                vec![
                    nom(),
                    noeud(),
                    group_no(),
                    text("NOEUD_ORIG").hidden().kw(),
                    text("GROUP_NO_ORIG").kw(),
                    text("NOEUD_EXTR").hidden().kw(),
                    text("GROUP_NO_EXTR").kw(),
                    prec(),
                    text("CRITERE").required().into(&["ABSOLU", "RELATIF"]).kw(),
                ],
            )
            .rules(vec![
                au_moins_un(&["NOEUD", "GROUP_NO"]),
                un_parmi(&["NOEUD_ORIG", "GROUP_NO_ORIG"]),
                un_parmi(&["NOEUD_EXTR", "GROUP_NO_EXTR"]),
            ])
            .kw(),
            block(
                "b_noeud_ordo",
                eq("OPTION", "NOEUD_ORDO"),
                vec![
                    nom(),
                    text("GROUP_MA").required().many().kw(),
                    text("NOEUD_ORIG").hidden().kw(),
                    text("GROUP_NO_ORIG").kw(),
                    text("NOEUD_EXTR").hidden().kw(),
                    text("GROUP_NO_EXTR").kw(),
                    real("VECT_ORIE").count(1, 3).kw(),
                    text("ORIGINE").into(&["SANS"]).kw(),
                ],
            )
            .rules(vec![
                exclus(&["NOEUD_ORIG", "GROUP_NO_ORIG"]),
                exclus(&["NOEUD_EXTR", "GROUP_NO_EXTR"]),
            ])
            .kw(),
        ],
    )
    .many()
    .doc("creates node groups; occurrences run in order, so a group can use the previous ones")
    .kw()
}
