//! DEFI_CONTACT: contact zones, formulation and algorithms.
//!
//! As in code_aster, the global keywords and the keywords of `ZONE` depend
//! on FORMULATION and FROTTEMENT, so `ZONE` is declared once per case in
//! mutually exclusive blocks. XFEM and the mortar LAC method of code_aster
//! are not offered (they need concepts aster does not have).

use super::blocks::*;
use super::mesh_args::{check_groups, GroupKind};
use super::model_args::{mesh_of_model, model_of, select_nodes};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::mesh::Mesh;
use crate::model::{Dof, Model};
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_CONTACT",
        Produces::Concept(C::CharContact),
        vec![
            concept("MODELE", &[C::Modele]).required().kw(),
            int("INFO").into_ints(&[1, 2]).kw(),
            text("FORMULATION")
                .into(&["DISCRETE", "CONTINUE", "LIAISON_UNIL"])
                .default(t("DISCRETE"))
                .doc("discrete (node-to-segment, active set or penalty), continuous (augmented Lagrangian) or unilateral linear constraints")
                .kw(),
            text("FROTTEMENT")
                .into(&["COULOMB", "SANS"])
                .default(t("SANS"))
                .doc("friction model (contact formulations only)")
                .kw(),
            block(
                "b_contact_mail",
                is_in("FORMULATION", &["CONTINUE", "DISCRETE"]),
                vec![
                    oui_non("STOP_INTERP", "NON")
                        .doc("with RESOLUTION='NON', stop at the first interpenetration")
                        .kw(),
                    oui_non("LISSAGE", "NON")
                        .doc("smooth normals by nodal averaging")
                        .kw(),
                    oui_non("VERI_NORM", "OUI")
                        .doc("check that the skins' normals point outwards")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_bouc_geom_maild",
                eq("FORMULATION", "DISCRETE"),
                [
                    vec![text("ALGO_RESO_GEOM")
                        .into(&["POINT_FIXE"])
                        .default(t("POINT_FIXE"))
                        .kw()],
                    reac_geom(),
                ]
                .concat(),
            )
            .kw(),
            block(
                "b_bouc_geom_mailc",
                eq("FORMULATION", "CONTINUE"),
                vec![
                    text("ALGO_RESO_GEOM")
                        .into(&["POINT_FIXE", "NEWTON"])
                        .default(t("POINT_FIXE"))
                        .doc("geometric non-linearity by fixed point (pairing loop) or inside Newton")
                        .kw(),
                    block(
                        "b_algo_reso_geomNE",
                        eq("ALGO_RESO_GEOM", "NEWTON"),
                        vec![real("RESI_GEOM").default(r(1e-6)).kw()],
                    )
                    .kw(),
                    block(
                        "b_algo_reso_geomPF",
                        eq("ALGO_RESO_GEOM", "POINT_FIXE"),
                        reac_geom(),
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_bouc_cont_disc",
                eq("FORMULATION", "DISCRETE"),
                vec![int("ITER_CONT_MULT")
                    .default(i(4))
                    .doc("multiplier of the maximum number of active-set iterations")
                    .kw()],
            )
            .kw(),
            block(
                "b_bouc_cont_cont",
                eq("FORMULATION", "CONTINUE"),
                vec![
                    text("ALGO_RESO_CONT")
                        .into(&["POINT_FIXE", "NEWTON"])
                        .default(t("NEWTON"))
                        .doc("contact status inside Newton (generalised Newton) or by fixed point")
                        .kw(),
                    real("RESI_CONT").default(r(-1.0)).kw(),
                    block(
                        "b_algo_reso_contPF",
                        eq("ALGO_RESO_CONT", "POINT_FIXE"),
                        vec![
                            text("ITER_CONT_TYPE")
                                .into(&["MULT", "MAXI"])
                                .default(t("MAXI"))
                                .kw(),
                            block(
                                "b_bouc_cont_mult",
                                eq("ITER_CONT_TYPE", "MULT"),
                                vec![int("ITER_CONT_MULT").default(i(4)).kw()],
                            )
                            .kw(),
                            block(
                                "b_bouc_cont_maxi",
                                eq("ITER_CONT_TYPE", "MAXI"),
                                vec![int("ITER_CONT_MAXI").default(i(30)).kw()],
                            )
                            .kw(),
                        ],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_bouc_frot_cont",
                and(vec![eq("FROTTEMENT", "COULOMB"), eq("FORMULATION", "CONTINUE")]),
                vec![
                    text("ALGO_RESO_FROT")
                        .into(&["POINT_FIXE", "NEWTON"])
                        .default(t("NEWTON"))
                        .doc("friction threshold inside Newton or by fixed point")
                        .kw(),
                    block(
                        "b_algo_reso_frotPF",
                        eq("ALGO_RESO_FROT", "POINT_FIXE"),
                        vec![
                            int("ITER_FROT_MAXI").default(i(10)).kw(),
                            real("RESI_FROT").default(r(1e-4)).kw(),
                        ],
                    )
                    .kw(),
                    block(
                        "b_algo_reso_frotNE",
                        eq("ALGO_RESO_FROT", "NEWTON"),
                        vec![real("RESI_FROT").default(r(1e-4)).kw()],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_para_discret",
                eq("FORMULATION", "DISCRETE"),
                vec![
                    oui_non("STOP_SINGULIER", "OUI").kw(),
                    int("NB_RESOL")
                        .default(i(10))
                        .doc("simultaneous solves when building the Schur complement")
                        .kw(),
                    real("RESI_ABSO").doc("GCP: allowed interpenetration").kw(),
                    int("ITER_GCP_MAXI").default(i(0)).kw(),
                    text("RECH_LINEAIRE")
                        .into(&["ADMISSIBLE", "NON_ADMISSIBLE"])
                        .default(t("ADMISSIBLE"))
                        .kw(),
                    text("PRE_COND")
                        .into(&["DIRICHLET", "SANS"])
                        .default(t("SANS"))
                        .kw(),
                    block(
                        "b_dirichlet",
                        eq("PRE_COND", "DIRICHLET"),
                        vec![
                            real("COEF_RESI").default(r(-1.0)).kw(),
                            int("ITER_PRE_MAXI").default(i(0)).kw(),
                        ],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_affe_unil",
                eq("FORMULATION", "LIAISON_UNIL"),
                vec![zone_unil()],
            )
            .kw(),
            block(
                "b_affe_discret",
                and(vec![eq("FORMULATION", "DISCRETE"), eq("FROTTEMENT", "COULOMB")]),
                vec![zone_discrete(true)],
            )
            .kw(),
            block(
                "b_affe_discret_frot",
                and(vec![
                    eq("FORMULATION", "DISCRETE"),
                    not(eq("FROTTEMENT", "COULOMB")),
                ]),
                vec![zone_discrete(false)],
            )
            .kw(),
            block(
                "b_affe_continue_frot",
                and(vec![eq("FORMULATION", "CONTINUE"), eq("FROTTEMENT", "COULOMB")]),
                vec![zone_continue(true)],
            )
            .kw(),
            block(
                "b_affe_continue",
                and(vec![
                    eq("FORMULATION", "CONTINUE"),
                    not(eq("FROTTEMENT", "COULOMB")),
                ]),
                vec![zone_continue(false)],
            )
            .kw(),
        ],
    )
    .doc("Defines contact (or unilateral) conditions, given to DYNA_NON_LINE by CONTACT.");
    CommandDef { spec, exec }
}

/// Keeps the checked keywords for the contact engine and does, now, the
/// checks code_aster does when the contact is defined: names, surfaces,
/// and the algorithm combinations it refuses.
/// DIST_MAIT / DIST_ESCL, the fictitious thicknesses code_aster adds to
/// the gap (shells' half thicknesses; its sdnv100a gives DIST_ESCL a
/// DEFI_CONSTANTE of 0): a function equal to 0 everywhere changes nothing
/// and is said so; another is taken by the discrete formulation
/// (`contact_def::set_user_gaps`, when the contact is used) and named in
/// the .mess.
fn zero_thickness(study: &Study, zone: &Args, key: &str) -> Result<Option<String>, Diagnostic> {
    let Some(name) = zone.concept(key) else {
        return Ok(None);
    };
    match study.concepts.data(name) {
        Some(ConceptData::Function(f)) if f.ordinates.iter().all(|&y| y == 0.0) => Ok(Some(
            format!("    {key} = {name}: 0 everywhere, no thickness added to the gap"),
        )),
        Some(ConceptData::Function(f)) => Ok(Some(format!(
            "    {key} = {name}: a thickness (function of {}) taken off the gap of every slave node",
            f.para
        ))),
        _ => Err(zone.error(key, format!("the function {name} holds no data"))),
    }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let (model_name, model) = model_of(study, args, "MODELE")?;
    let mesh = mesh_of_model(study, args, "MODELE", model)?;
    let formulation = args.text("FORMULATION").unwrap_or("DISCRETE");
    let friction = args.text("FROTTEMENT") == Some("COULOMB");
    let zones = args.facts("ZONE");
    let mut lines = Vec::new();
    for (k, zone) in zones.iter().enumerate() {
        // A LIAISON_UNIL zone selects its nodes like DDL_IMPO does, names
        // included (select_nodes); the pairing of the contact formulations
        // works on cell groups only.
        let by_name: &[&str] = if formulation == "LIAISON_UNIL" {
            &[]
        } else {
            &[
                "MAILLE_MAIT",
                "MAILLE_ESCL",
                "MAILLE",
                "NOEUD",
                "SANS_NOEUD",
                "SANS_MAILLE",
                "SANS_NOEUD_FR",
            ]
        };
        for &key in by_name {
            if zone.has(key) {
                return Err(zone.not_implemented(key, "cells and nodes by name; use groups"));
            }
        }
        for key in ["SANS_GROUP_MA"] {
            if zone.has(key) {
                check_groups(mesh, zone, key, GroupKind::Cells)?;
            }
        }
        for key in ["SANS_GROUP_NO", "SANS_GROUP_NO_FR"] {
            if zone.has(key) {
                check_groups(mesh, zone, key, GroupKind::Nodes)?;
            }
        }
        if formulation == "LIAISON_UNIL" {
            lines.push(unil_zone(mesh, model, &model_name, zone, k)?);
            continue;
        }
        for key in ["GROUP_MA_MAIT", "GROUP_MA_ESCL"] {
            check_surface(mesh, model, &model_name, zone, key)?;
        }
        for key in ["DIST_MAIT", "DIST_ESCL"] {
            if let Some(line) = zero_thickness(study, zone, key)? {
                lines.push(line);
            }
        }
        let (mait, escl) = (
            zone.text("GROUP_MA_MAIT").unwrap_or_default(),
            zone.text("GROUP_MA_ESCL").unwrap_or_default(),
        );
        if mait == escl {
            return Err(zone.error(
                "GROUP_MA_ESCL",
                format!("the slave surface {escl} is also the master surface"),
            ));
        }
        let algo = zone.text("ALGO_CONT").unwrap_or_default();
        if formulation == "DISCRETE" && friction && algo != "PENALISATION" {
            // code_aster stops here (CONTACT3_3); aster accepts it for the
            // kinematic contact of explicit dynamics, its extension, and
            // an implicit DYNA_NON_LINE refuses it with CONTACT3_3.
            lines.push(format!(
                "      zone {}: Coulomb friction with ALGO_CONT='{algo}': only for an explicit DYNA_NON_LINE (kinematic contact, an aster extension); implicit schemes need ALGO_CONT='PENALISATION' (code_aster CONTACT3_3)",
                k + 1
            ));
        }
        if args.text("VERI_NORM") != Some("NON") {
            for key in ["GROUP_MA_ESCL", "GROUP_MA_MAIT"] {
                check_outward(mesh, zone, key, k)?;
            }
        }
        lines.push(format!(
            "      zone {}: slave {escl} ({} cells) on master {mait} ({} cells), ALGO_CONT={algo}",
            k + 1,
            mesh.cell_groups.get(escl).map_or(0, Vec::len),
            mesh.cell_groups.get(mait).map_or(0, Vec::len)
        ));
    }
    if formulation != "CONTINUE" {
        same_algorithm(zones)?;
    }
    study.log(format!(
        "    contact {} on model {model_name}: FORMULATION='{formulation}', FROTTEMENT='{}', {} zone(s)",
        result.unwrap_or("(unnamed)"),
        args.text("FROTTEMENT").unwrap_or("SANS"),
        zones.len()
    ));
    if formulation == "LIAISON_UNIL" && friction {
        // code_aster's caliun never reads FROTTEMENT: the conditions stay
        // frictionless.
        lines.push(
            "      FROTTEMENT='COULOMB' has no effect on LIAISON_UNIL (linear inequalities, no friction): ignored, as code_aster does".into(),
        );
    }
    for l in lines {
        study.log(l);
    }
    Ok(Some(ConceptData::Contact(Box::new(args.clone()))))
}

/// VERI_NORM='OUI': the normals of a contact surface must point out of
/// the body it bounds. The contact engine measures the gap along them, so
/// an inward normal turns a closing gap into an opening one and the bodies
/// go through each other without any error.
fn check_outward(mesh: &Mesh, zone: &Args, key: &str, k: usize) -> Result<(), Diagnostic> {
    let Some(group) = zone.text(key) else {
        return Ok(());
    };
    let Some(cells) = mesh.cell_groups.get(group) else {
        return Ok(());
    };
    let inward = crate::mesh::ops::inward_skin_cells(mesh, cells);
    let Some(first) = inward.first() else {
        return Ok(());
    };
    let orie = if crate::mesh::ops::is_z_constant(mesh) {
        "ORIE_PEAU_2D"
    } else {
        "ORIE_PEAU_3D"
    };
    Err(zone.error(
        key,
        format!(
            "zone {}: the normals of {} of the {} cells of {key}='{group}' point into the body \
             (first: cell M{}, on cell M{}); contact needs outward normals: orient the skin with \
             MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, {orie}=_F(GROUP_MA='{group}')) before \
             DEFI_CONTACT (VERI_NORM='NON' skips this check)",
            k + 1,
            inward.len(),
            cells.len(),
            first.cell + 1,
            first.support + 1
        ),
    ))
}

/// A contact surface is one cell group of boundary cells (edges in 2D,
/// faces in 3D) whose nodes all move with the model. The cells themselves
/// need not be in AFFE_MODELE: as in code_aster (zzzz237a models only its
/// two blocks), a surface is geometry, the contact terms act on the dofs
/// of its nodes.
fn check_surface(
    mesh: &Mesh,
    model: &Model,
    model_name: &str,
    zone: &Args,
    key: &str,
) -> Result<(), Diagnostic> {
    check_groups(mesh, zone, key, GroupKind::Cells)?;
    let Some(group) = zone.text(key) else {
        return Err(zone.error(key, "one cell group is expected"));
    };
    let dim = model.dofs.len() - 1;
    let moves = model.node_mask(mesh);
    for &c in &mesh.cell_groups[group] {
        let kind = mesh.cells[c].kind;
        if kind.dim() != dim {
            return Err(zone.error(
                key,
                format!(
                    "the contact surface {group} holds a {} cell: a surface of this model is made of cells of dimension {dim}",
                    kind.aster_name()
                ),
            ));
        }
        if let Some(&n) = mesh.cells[c].nodes.iter().find(|&&n| !moves[n]) {
            return Err(zone.error(
                key,
                format!(
                    "the node N{} of the contact surface {group} (cell M{}) is on no cell of the model {model_name}: contact acts on the displacements of the surface's nodes; add the body under it to an AFFE of AFFE_MODELE",
                    n + 1,
                    c + 1
                ),
            ));
        }
    }
    Ok(())
}

/// LIAISON_UNIL: the nodes must carry the named components, and each
/// component has its coefficient.
fn unil_zone(
    mesh: &Mesh,
    model: &Model,
    model_name: &str,
    zone: &Args,
    k: usize,
) -> Result<String, Diagnostic> {
    let in_model = model.node_mask(mesh);
    // Nodes without degrees of freedom are dropped (code_aster's elimun);
    // a zone left empty is an error.
    let selected = select_nodes(mesh, zone, &[])?;
    let given = selected.len();
    let nodes: Vec<usize> = selected.into_iter().filter(|&n| in_model[n]).collect();
    if nodes.is_empty() {
        return Err(zone.error(
            "",
            format!(
                "zone {} keeps no node carrying degrees of freedom of the model {model_name} (UNILATER_48)",
                k + 1
            ),
        ));
    }
    // Checked here too, not only when a computation turns the zone into
    // its term: a contact defined and never used is still a wrong input.
    if let Some(e) = zone
        .real("COEF_PENA")
        .filter(|e| !(e.is_finite() && *e > 0.0))
    {
        return Err(zone.error("COEF_PENA", format!("COEF_PENA must be > 0, got {e:e}")));
    }
    let cmps = zone.texts("NOM_CMP");
    let mult = zone.concepts("COEF_MULT");
    if cmps.len() != mult.len() {
        return Err(zone.error(
            "COEF_MULT",
            format!(
                "NOM_CMP gives {} component(s) and COEF_MULT {} coefficient(s): they must have the same length",
                cmps.len(),
                mult.len()
            ),
        ));
    }
    // A component the model does not carry is dropped from the links
    // (code_aster's creaun, info UNILATER_75); none left empties the zone.
    let (kept, absent): (Vec<&str>, Vec<&str>) = cmps
        .iter()
        .copied()
        .partition(|c| Dof::from_name(c).is_some_and(|d| model.has_dof(d)));
    if kept.is_empty() {
        let names: Vec<&str> = model.dofs.iter().map(|d| d.name()).collect();
        return Err(zone
            .error(
                "NOM_CMP",
                format!(
                    "none of NOM_CMP ({}) is a degree of freedom of the model {model_name}: zone {} keeps no node (UNILATER_48)",
                    cmps.join(", "),
                    k + 1
                ),
            )
            .choices(cmps[0], &names));
    }
    let mut line = format!(
        "      zone {}: {} nodes, sum of COEF_MULT x ({}) <= COEF_IMPO",
        k + 1,
        nodes.len(),
        kept.join(", ")
    );
    if nodes.len() < given {
        line.push_str(&format!(
            "\n      zone {}: {} of its {given} nodes dropped: they carry no degree of freedom of the model {model_name} (as code_aster's elimun)",
            k + 1,
            given - nodes.len()
        ));
    }
    if !absent.is_empty() {
        line.push_str(&format!(
            "\n      zone {}: NOM_CMP {} dropped: not a degree of freedom of the model {model_name} (UNILATER_75)",
            k + 1,
            absent.join(", ")
        ));
    }
    Ok(line)
}

/// DISCRETE and LIAISON_UNIL solve all zones with one algorithm, so the
/// zones must agree on it (code_aster's CONTACT3_4).
pub(super) fn same_algorithm(zones: &[Args]) -> Result<(), Diagnostic> {
    let Some(first) = zones.first().and_then(|z| z.text("ALGO_CONT")) else {
        return Ok(());
    };
    for (k, z) in zones.iter().enumerate().skip(1) {
        let a = z.text("ALGO_CONT").unwrap_or_default();
        if a != first {
            return Err(z.error(
                "ALGO_CONT",
                format!(
                    "all zones must use the same ALGO_CONT: zone 1 uses '{first}', zone {} '{a}' (code_aster CONTACT3_4)",
                    k + 1
                ),
            ));
        }
    }
    Ok(())
}

/// The pairing loop of the fixed-point geometric method.
fn reac_geom() -> Vec<Keyword> {
    vec![
        text("REAC_GEOM")
            .into(&["AUTOMATIQUE", "CONTROLE", "SANS"])
            .default(t("AUTOMATIQUE"))
            .doc("geometric update: until RESI_GEOM, exactly NB_ITER_GEOM pairings per step, or none")
            .kw(),
        block(
            "b_automatique",
            eq("REAC_GEOM", "AUTOMATIQUE"),
            vec![
                int("ITER_GEOM_MAXI").default(i(10)).kw(),
                real("RESI_GEOM")
                    .default(r(0.01))
                    .doc("displacement since the last pairing, relative to the total")
                    .kw(),
            ],
        )
        .kw(),
        block(
            "b_controle",
            eq("REAC_GEOM", "CONTROLE"),
            vec![int("NB_ITER_GEOM")
                .default(i(2))
                .doc("pairings per time step (1: frozen during the step)")
                .kw()],
        )
        .kw(),
    ]
}

/// Master/slave pairing keywords common to DISCRETE and CONTINUE zones.
fn pairing(appariement: &[&'static str]) -> Vec<Keyword> {
    let vect = |name: &'static str, fixe: &'static str, vecty: &'static str| {
        vec![
            text(name)
                .into(&["AUTO", "FIXE", "VECT_Y"])
                .not_built(&["FIXE", "VECT_Y"], "the normal is the cells' own, AUTO")
                .default(t("AUTO"))
                .doc("normal of the surface")
                .kw(),
            block(
                if name == "VECT_MAIT" {
                    "b_nmait_fixe"
                } else {
                    "b_nescl_fixe"
                },
                eq(name, "FIXE"),
                vec![real(fixe).required().count(3, 3).kw()],
            )
            .kw(),
            block(
                if name == "VECT_MAIT" {
                    "b_nmait_vecty"
                } else {
                    "b_nescl_vecty"
                },
                eq(name, "VECT_Y"),
                vec![real(vecty).required().count(3, 3).kw()],
            )
            .kw(),
        ]
    };
    [
        vec![
            text("APPARIEMENT")
                .into(appariement)
                .not_built(
                    &["NODAL"],
                    "slave nodes are projected on master cells, MAIT_ESCL",
                )
                .default(t("MAIT_ESCL"))
                .doc("slave nodes projected on master cells")
                .kw(),
            text("GROUP_MA_MAIT").doc("master surface (one group)").kw(),
            text("MAILLE_MAIT").many().hidden().kw(),
            text("GROUP_MA_ESCL").doc("slave surface (one group)").kw(),
            text("MAILLE_ESCL").many().hidden().kw(),
            text("NORMALE")
                .into(&["MAIT", "MAIT_ESCL", "ESCL"])
                .not_built(&["MAIT_ESCL", "ESCL"], "the normal is the master's, MAIT")
                .default(t("MAIT"))
                .doc("surface giving the normal")
                .kw(),
        ],
        vect("VECT_MAIT", "MAIT_FIXE", "MAIT_VECT_Y"),
        vect("VECT_ESCL", "ESCL_FIXE", "ESCL_VECT_Y"),
        vec![
            text("TYPE_PROJECTION")
                .into(&["ORTHOGONALE", "FIXE"])
                .not_built(&["FIXE"], "the projection is ORTHOGONALE")
                .default(t("ORTHOGONALE"))
                .doc("projection of the slave nodes")
                .kw(),
            block(
                "b_appa_fixe",
                eq("TYPE_PROJECTION", "FIXE"),
                vec![real("DIRE_APPA").count(3, 3).kw()],
            )
            .kw(),
            concept("DIST_MAIT", &[C::Fonction])
                .doc("fictitious thickness on the master side, taken off the gap (DISCRETE: a constant or a function of X, Y, Z, read at the slave node's initial position)")
                .kw(),
            concept("DIST_ESCL", &[C::Fonction])
                .doc("fictitious thickness on the slave side, taken off the gap (DISCRETE: a constant or a function of X, Y, Z, read at the slave node's initial position)")
                .kw(),
            real("DIST_APPA")
                .default(r(-1.0))
                .doc("maximum pairing distance (negative: none)")
                .kw(),
            real("TOLE_PROJ_EXT")
                .default(r(0.5))
                .doc("allowed projection outside a master cell, in parametric units")
                .kw(),
            text("SANS_NOEUD").many().hidden().kw(),
            text("SANS_GROUP_NO")
                .many()
                .doc("slave nodes excluded (e.g. those with imposed dofs)")
                .kw(),
            text("SANS_MAILLE").many().hidden().kw(),
            text("SANS_GROUP_MA").many().kw(),
            oui_non("RESOLUTION", "OUI")
                .doc("'NON' (pairing and interpenetration check only): not implemented yet")
                .kw(),
            block(
                "b_verif",
                eq("RESOLUTION", "NON"),
                vec![real("TOLE_INTERP").default(r(0.0)).min_val(0.0).kw()],
            )
            .kw(),
        ],
    ]
    .concat()
}

fn pairing_rules() -> Vec<Rule> {
    vec![
        un_parmi(&["GROUP_MA_ESCL", "MAILLE_ESCL"]),
        un_parmi(&["GROUP_MA_MAIT", "MAILLE_MAIT"]),
    ]
}

fn zone_unil() -> Keyword {
    fact(
        "ZONE",
        vec![
            group_ma(),
            maille(),
            group_no(),
            noeud(),
            text("NOM_CMP")
                .required()
                .many()
                .doc("components c_i of sum COEF_MULT_i(t).u_ci <= COEF_IMPO")
                .kw(),
            concept("COEF_IMPO", &[C::Fonction, C::Formule])
                .required()
                .doc("right-hand side, function of INST and the initial X, Y, Z")
                .kw(),
            concept("COEF_MULT", &[C::Fonction, C::Formule])
                .required()
                .many()
                .doc("coefficients, one per NOM_CMP, functions of INST")
                .kw(),
            text("SANS_NOEUD").many().hidden().kw(),
            text("SANS_GROUP_NO").many().kw(),
            text("ALGO_CONT")
                .into(&["CONTRAINTE", "PENALISATION"])
                .default(t("CONTRAINTE"))
                .doc("active set on the Schur complement, or penalty")
                .kw(),
            block(
                "b_penalisation",
                eq("ALGO_CONT", "PENALISATION"),
                vec![real("COEF_PENA")
                    .required()
                    .doc("penalty coefficient on the violation")
                    .kw()],
            )
            .kw(),
        ],
    )
    .required()
    .many()
    .rules(vec![un_parmi(&["GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"])])
    .doc("unilateral linear conditions at each node of the zone (no pairing)")
    .kw()
}

fn zone_discrete(friction: bool) -> Keyword {
    let mut kws = pairing(&["NODAL", "MAIT_ESCL"]);
    kws.extend([
        text("ALGO_CONT")
            .into(&["CONTRAINTE", "PENALISATION", "GCP"])
            .default(t("CONTRAINTE"))
            .doc(if friction {
                "contact algorithm; with COULOMB friction it must be PENALISATION (checked when run)"
            } else {
                "active set (Lagrange), penalty or conjugate gradient"
            })
            .kw(),
        block(
            "b_active",
            eq("ALGO_CONT", "CONTRAINTE"),
            vec![
                oui_non("GLISSIERE", "NON")
                    .doc("bilateral sliding: once in contact, always")
                    .kw(),
                block(
                    "b_glissiere",
                    eq("GLISSIERE", "OUI"),
                    vec![real("ALARME_JEU").default(r(0.0)).kw()],
                )
                .kw(),
            ],
        )
        .kw(),
        block(
            "b_penal_contact",
            eq("ALGO_CONT", "PENALISATION"),
            vec![real("E_N")
                .required()
                .doc("normal penalty stiffness: force E_N times the penetration")
                .kw()],
        )
        .kw(),
    ]);
    if friction {
        kws.extend([
            real("COULOMB")
                .required()
                .doc("Coulomb friction coefficient")
                .kw(),
            real("COEF_MATR_FROT")
                .default(r(0.0))
                .doc("weight of the slip part of the friction tangent while RESI_GLOB_RELA >= 1e-3")
                .kw(),
            text("ALGO_FROT")
                .into(&["PENALISATION"])
                .default(t("PENALISATION"))
                .kw(),
            real("E_T")
                .required()
                .doc("tangential penalty stiffness (stick)")
                .kw(),
        ]);
    }
    fact("ZONE", kws)
        .required()
        .many()
        .rules(pairing_rules())
        .doc("contact zones; the algorithm must be the same in all zones")
        .kw()
}

fn zone_continue(friction: bool) -> Keyword {
    let mut kws = vec![
        text("ALGO_CONT")
            .into(&["STANDARD", "PENALISATION"])
            .default(t("STANDARD"))
            .doc("augmented Lagrangian or penalty")
            .kw(),
        text("ADAPTATION")
            .into(&["ADAPT_COEF", "CYCLAGE", "TOUT", "NON"])
            .default(t("CYCLAGE"))
            .doc("automatic penalty adaptation and/or anti-cycling treatment")
            .kw(),
        block(
            "b_cont_std",
            eq("ALGO_CONT", "STANDARD"),
            vec![real("COEF_CONT")
                .default(r(100.0))
                .doc("augmentation coefficient rho_n")
                .kw()],
        )
        .kw(),
        block(
            "b_cont_pena_noadapt",
            and(vec![
                eq("ALGO_CONT", "PENALISATION"),
                is_in("ADAPTATION", &["NON", "CYCLAGE"]),
            ]),
            vec![
                real("COEF_PENA_CONT").required().kw(),
                real("PENE_MAXI").min_val(0.0).kw(),
            ],
        )
        .kw(),
        block(
            "b_cont_pena_adapt",
            and(vec![
                eq("ALGO_CONT", "PENALISATION"),
                is_in("ADAPTATION", &["ADAPT_COEF", "TOUT"]),
            ]),
            vec![
                real("COEF_PENA_CONT").kw(),
                real("PENE_MAXI")
                    .min_val(0.0)
                    .doc("largest penetration allowed by the adaptation")
                    .kw(),
            ],
        )
        .kw(),
    ];
    kws.extend(pairing(&["MAIT_ESCL"]));
    kws.extend([
        text("INTEGRATION")
            .into(&["AUTO", "GAUSS", "SIMPSON", "NCOTES"])
            .default(t("AUTO"))
            .doc("contact points: AUTO puts them at the slave nodes")
            .kw(),
        block(
            "b_gauss",
            eq("INTEGRATION", "GAUSS"),
            vec![int("ORDRE_INT")
                .default(i(3))
                .min_val(1.0)
                .max_val(6.0)
                .kw()],
        )
        .kw(),
        block(
            "b_simpson",
            eq("INTEGRATION", "SIMPSON"),
            vec![int("ORDRE_INT")
                .default(i(1))
                .min_val(1.0)
                .max_val(4.0)
                .kw()],
        )
        .kw(),
        block(
            "b_ncotes",
            eq("INTEGRATION", "NCOTES"),
            vec![int("ORDRE_INT")
                .default(i(3))
                .min_val(3.0)
                .max_val(8.0)
                .kw()],
        )
        .kw(),
        text("CONTACT_INIT")
            .into(&["OUI", "INTERPENETRE", "NON"])
            .default(t("INTERPENETRE"))
            .doc("initial status: all in contact, only interpenetrating points, or none")
            .kw(),
        oui_non("GLISSIERE", "NON").kw(),
    ]);
    let mut rules = pairing_rules();
    if friction {
        kws.extend([
            real("COULOMB")
                .required()
                .doc("Coulomb friction coefficient")
                .kw(),
            real("SEUIL_INIT")
                .doc("initial friction threshold; absent: automatic")
                .kw(),
            text("SANS_NOEUD_FR").many().hidden().kw(),
            text("SANS_GROUP_NO_FR").many().kw(),
            block(
                "b_sans_group_no_frot",
                or(vec![present("SANS_GROUP_NO_FR"), present("SANS_NOEUD_FR")]),
                vec![real("DIRE_EXCL_FROT").count(3, 3).kw()],
            )
            .kw(),
            text("ALGO_FROT")
                .into(&["STANDARD", "PENALISATION"])
                .default(t("STANDARD"))
                .kw(),
            block(
                "b_frot_std",
                eq("ALGO_FROT", "STANDARD"),
                vec![real("COEF_FROT")
                    .default(r(100.0))
                    .doc("friction augmentation coefficient")
                    .kw()],
            )
            .kw(),
            block(
                "b_frot_pena",
                eq("ALGO_FROT", "PENALISATION"),
                vec![real("COEF_PENA_FROT").required().kw()],
            )
            .kw(),
        ]);
        rules.push(exclus(&["SANS_NOEUD_FR", "SANS_GROUP_NO_FR"]));
    }
    fact("ZONE", kws)
        .required()
        .many()
        .rules(rules)
        .doc("contact zones")
        .kw()
}
