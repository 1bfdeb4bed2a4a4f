//! DEFI_GROUP: creates or deletes groups of cells and nodes in a mesh.

use super::blocks::*;
use super::mesh_args::{check_groups, log_report, mesh_error, mesh_of, GroupKind};
use super::post_args::{cell_by_name, node_by_name};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::mesh::ops::{self, CritNoeud, GroupSetOp, PlaneNormal};
use crate::mesh::Mesh;
use crate::study::Study;

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
    CommandDef { spec, exec }
}

/// Runs the occurrences as code_aster does: deletions first, then cell
/// groups, then node groups, each in the order written (a group created by
/// one occurrence can be used by the next).
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let mut mesh = mesh_of(study, args, "MAILLAGE")?.clone();
    for occ in args.facts("DETR_GROUP_MA") {
        for name in occ.texts("NOM") {
            if mesh.cell_groups.shift_remove(name).is_none() {
                study.log(format!(
                    "<A> <DEFI_GROUP> the cell group {name} to delete does not exist"
                ));
            }
        }
    }
    for occ in args.facts("DETR_GROUP_NO") {
        for name in occ.texts("NOM") {
            if mesh.node_groups.shift_remove(name).is_none() {
                study.log(format!(
                    "<A> <DEFI_GROUP> the node group {name} to delete does not exist"
                ));
            }
        }
    }
    for occ in args.facts("CREA_GROUP_MA") {
        run_crea_group_ma(study, &mut mesh, occ)?;
    }
    for occ in args.facts("CREA_GROUP_NO") {
        run_crea_group_no(study, &mut mesh, occ)?;
    }
    Ok(Some(ConceptData::Mesh(Box::new(mesh))))
}

fn run_crea_group_ma(study: &mut Study, mesh: &mut Mesh, occ: &Args) -> Result<(), Diagnostic> {
    let name = occ.text("NOM").unwrap_or_default().to_string();
    let type_maille = occ.text("TYPE_MAILLE").unwrap_or("TOUT");
    if occ.has("UNION") && type_maille == "TOUT" {
        check_groups(mesh, occ, "UNION", GroupKind::Cells)?;
        let r = ops::crea_group_ma_union(mesh, &occ.texts("UNION"), &name)
            .map_err(|e| mesh_error(occ, "UNION", e))?;
        log_report(study, "DEFI_GROUP", &r);
        return Ok(());
    }
    let mut cells: Vec<usize> = if occ.has("TOUT") {
        (0..mesh.ncells()).collect()
    } else if occ.has("GROUP_MA") {
        check_groups(mesh, occ, "GROUP_MA", GroupKind::Cells)?;
        let g = occ.text("GROUP_MA").unwrap_or_default();
        mesh.cell_groups[g].clone()
    } else if occ.has("MAILLE") {
        let mut seen = vec![false; mesh.ncells()];
        for m in occ.texts("MAILLE") {
            seen[cell_by_name(mesh, occ, "MAILLE", m)?] = true;
        }
        (0..mesh.ncells()).filter(|&c| seen[c]).collect()
    } else {
        let (key, op) = [
            ("UNION", GroupSetOp::Union),
            ("INTERSEC", GroupSetOp::Intersec),
            ("DIFFE", GroupSetOp::Diffe),
        ]
        .into_iter()
        .find(|(k, _)| occ.has(k))
        .unwrap_or(("DIFFE", GroupSetOp::Diffe));
        check_groups(mesh, occ, key, GroupKind::Cells)?;
        ops::cell_group_set(mesh, op, &occ.texts(key)).map_err(|e| mesh_error(occ, key, e))?
    };
    if mesh.cell_groups.contains_key(&name) {
        return Err(occ.error(
            "NOM",
            format!("the cell group {name} already exists (SOUSTRUC_37)"),
        ));
    }
    ops::cell_type_filter(mesh, &mut cells, type_maille);
    if cells.is_empty() {
        study.log(format!(
            "<A> <DEFI_GROUP> <SOUSTRUC_38> the cell group {name} would be empty: it is not created"
        ));
        return Ok(());
    }
    mesh.cell_groups.insert(name, cells);
    Ok(())
}

fn run_crea_group_no(study: &mut Study, mesh: &mut Mesh, occ: &Args) -> Result<(), Diagnostic> {
    let nom = occ.text("NOM").unwrap_or_default().to_string();
    match occ.text("OPTION") {
        None => {}
        Some("PLAN") => return plan(study, mesh, occ, &nom),
        Some(option @ ("ENV_SPHERE" | "ENV_CYLINDRE")) => {
            return envelope(study, mesh, occ, &nom, option)
        }
        Some("SEGM_DROI_ORDO") => return segm_droi_ordo(study, mesh, occ, &nom),
        Some(_) => {
            return Err(occ.not_implemented(
                "OPTION",
                "OPTION='PLAN', 'ENV_SPHERE', 'ENV_CYLINDRE' and 'SEGM_DROI_ORDO' are built",
            ))
        }
    }
    let report = if occ.has("TOUT_GROUP_MA") {
        ops::crea_group_no_tout_group_ma(mesh)
    } else if occ.has("GROUP_MA") {
        check_groups(mesh, occ, "GROUP_MA", GroupKind::Cells)?;
        let crit = match occ.text("CRIT_NOEUD").unwrap_or("TOUS") {
            "SOMMET" => CritNoeud::Sommet,
            "MILIEU" => CritNoeud::Milieu,
            "CENTRE" => CritNoeud::Centre,
            _ => CritNoeud::Tous,
        };
        let names = occ.texts("NOM");
        let names = (!names.is_empty()).then_some(names.as_slice());
        ops::crea_group_no_from_group_ma(mesh, &occ.texts("GROUP_MA"), names, crit)
            .map_err(|e| mesh_error(occ, "GROUP_MA", e))?
    } else if let Some((key, op)) = [
        ("UNION", GroupSetOp::Union),
        ("INTERSEC", GroupSetOp::Intersec),
        ("DIFFE", GroupSetOp::Diffe),
    ]
    .into_iter()
    .find(|(k, _)| occ.has(k))
    {
        check_groups(mesh, occ, key, GroupKind::Nodes)?;
        ops::crea_group_no_set(mesh, op, &occ.texts(key), &nom)
            .map_err(|e| mesh_error(occ, key, e))?
    } else if occ.has("GROUP_NO") {
        if occ.has("NUME_INIT") || occ.has("POSITION") {
            return Err(occ.not_implemented("NUME_INIT", "sub-ranges of a node group"));
        }
        check_groups(mesh, occ, "GROUP_NO", GroupKind::Nodes)?;
        ops::crea_group_no_set(mesh, GroupSetOp::Union, &occ.texts("GROUP_NO")[..1], &nom)
            .map_err(|e| mesh_error(occ, "NOM", e))?
    } else {
        let nodes = occ
            .texts("NOEUD")
            .iter()
            .map(|n| node_by_name(mesh, occ, "NOEUD", n))
            .collect::<Result<Vec<_>, _>>()?;
        ops::crea_group_no_nodes(mesh, &nodes, &nom).map_err(|e| mesh_error(occ, "NOM", e))?
    };
    log_report(study, "DEFI_GROUP", &report);
    Ok(())
}

/// The centre of PLAN, ENV_SPHERE and ENV_CYLINDRE: POINT, or the first
/// node of GROUP_NO_CENTRE in the mesh's dimension.
fn centre(mesh: &Mesh, occ: &Args) -> Result<Vec<f64>, Diagnostic> {
    Ok(if occ.has("POINT") {
        occ.reals("POINT")
    } else if occ.has("GROUP_NO_CENTRE") {
        check_groups(mesh, occ, "GROUP_NO_CENTRE", GroupKind::Nodes)?;
        let g = &mesh.node_groups[occ.text("GROUP_NO_CENTRE").unwrap_or_default()];
        let Some(&n) = g.first() else {
            return Err(occ.error("GROUP_NO_CENTRE", "the node group is empty"));
        };
        let d = if ops::is_z_constant(mesh) { 2 } else { 3 };
        mesh.coords[n][..d].to_vec()
    } else {
        return Err(occ.not_implemented("NOEUD_CENTRE", "use POINT or GROUP_NO_CENTRE"));
    })
}

/// OPTION='ENV_SPHERE' / 'ENV_CYLINDRE': the nodes at RAYON from the
/// centre (the axis) within PRECISION ([`ops::Envelope`]).
fn envelope(
    study: &mut Study,
    mesh: &mut Mesh,
    occ: &Args,
    nom: &str,
    option: &str,
) -> Result<(), Diagnostic> {
    let point = centre(mesh, occ)?;
    let vect = occ.reals("VECT_NORMALE");
    let angl = occ.reals("ANGL_NAUT");
    let shape = if option == "ENV_SPHERE" {
        ops::Envelope::Sphere
    } else if occ.has("VECT_NORMALE") {
        ops::Envelope::Cylinder(PlaneNormal::Vect(&vect))
    } else {
        ops::Envelope::Cylinder(PlaneNormal::AnglNaut(&angl))
    };
    let radius = occ.real("RAYON").unwrap_or(0.0);
    let prec = occ.real("PRECISION").unwrap_or(0.0);
    let key = |e: &ops::MeshError| match e.id {
        "MODELISA3_83" => "RAYON",
        "MODELISA3_91" => "PRECISION",
        "MODELISA3_86" => "VECT_NORMALE",
        "MODELISA3_87" => "ANGL_NAUT",
        "ASTER_RS_PLAN_DIM" if occ.has("POINT") => "POINT",
        _ => "OPTION",
    };
    let r = ops::crea_group_no_envelope(mesh, nom, &point, shape, radius, prec)
        .map_err(|e| mesh_error(occ, key(&e), e))?;
    log_report(study, "DEFI_GROUP", &r);
    Ok(())
}

/// OPTION='SEGM_DROI_ORDO': the nodes of GROUP_NO / NOEUD ordered along
/// the segment from GROUP_NO_ORIG to GROUP_NO_EXTR (each the first node of
/// its group, as code_aster's `utreno`).
fn segm_droi_ordo(
    study: &mut Study,
    mesh: &mut Mesh,
    occ: &Args,
    nom: &str,
) -> Result<(), Diagnostic> {
    let mut nodes = Vec::new();
    if occ.has("GROUP_NO") {
        check_groups(mesh, occ, "GROUP_NO", GroupKind::Nodes)?;
        for g in occ.texts("GROUP_NO") {
            nodes.extend_from_slice(&mesh.node_groups[g]);
        }
    }
    for n in occ.texts("NOEUD") {
        nodes.push(node_by_name(mesh, occ, "NOEUD", n)?);
    }
    let mut end = |key: &str| -> Result<usize, Diagnostic> {
        if !occ.has(key) {
            let hidden = key.replace("GROUP_NO", "NOEUD");
            return Err(occ.not_implemented(&hidden, &format!("use {key}")));
        }
        check_groups(mesh, occ, key, GroupKind::Nodes)?;
        let g = occ.text(key).unwrap_or_default();
        match mesh.node_groups[g].as_slice() {
            [] => Err(occ.error(key, format!("the node group {g} is empty"))),
            [one] => Ok(*one),
            [first, ..] => {
                study.log(format!(
                    "<A> <DEFI_GROUP> {key}: the node group {g} holds {} nodes; its first, N{}, is taken",
                    mesh.node_groups[g].len(),
                    first + 1
                ));
                Ok(*first)
            }
        }
    };
    let ends = (end("GROUP_NO_ORIG")?, end("GROUP_NO_EXTR")?);
    let prec = occ.real("PRECISION").unwrap_or(0.0);
    let relative = occ.text("CRITERE") == Some("RELATIF");
    let r = ops::crea_group_no_segm_droi_ordo(mesh, nom, &nodes, ends, prec, relative)
        .map_err(|e| mesh_error(occ, "OPTION", e))?;
    log_report(study, "DEFI_GROUP", &r);
    Ok(())
}

/// OPTION='PLAN': nodes within PRECISION of a plane (a line in 2D).
fn plan(study: &mut Study, mesh: &mut Mesh, occ: &Args, nom: &str) -> Result<(), Diagnostic> {
    let point = centre(mesh, occ)?;
    let vect = occ.reals("VECT_NORMALE");
    let angl = occ.reals("ANGL_NAUT");
    let normal = if occ.has("VECT_NORMALE") {
        PlaneNormal::Vect(&vect)
    } else {
        PlaneNormal::AnglNaut(&angl)
    };
    let prec = occ.real("PRECISION").unwrap_or(0.0);
    let r = ops::crea_group_no_plan(mesh, nom, &point, normal, prec)
        .map_err(|e| mesh_error(occ, "NOM", e))?;
    log_report(study, "DEFI_GROUP", &r);
    Ok(())
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
                .doc("geometric selection (PLAN, ENV_SPHERE, ENV_CYLINDRE, SEGM_DROI_ORDO built; NOEUD_ORDO not yet); absent: from groups")
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
