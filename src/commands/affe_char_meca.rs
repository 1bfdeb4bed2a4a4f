//! AFFE_CHAR_MECA: mechanical loads and boundary conditions.

use super::blocks::*;
use super::model_args::{load_model, select_cells, select_nodes, selection_label, LoadModel};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::model::spec::Formulation;
use crate::model::{
    CellRole, DistributedForce, DistributedKind, Dof, Gravity, ImposedDof, MechLoad, Pressure,
};
use crate::study::Study;

/// FACE_IMPO's cells and exclusions, the same in AFFE_CHAR_MECA and
/// AFFE_CHAR_MECA_F (only the values' type differs).
pub(super) fn face_impo_selection() -> Vec<Keyword> {
    vec![
        group_ma(),
        maille(),
        text("SANS_GROUP_MA").many().kw(),
        text("SANS_MAILLE").many().hidden().kw(),
        text("SANS_GROUP_NO")
            .many()
            .doc("nodes excluded from the selection")
            .kw(),
        text("SANS_NOEUD").many().hidden().kw(),
    ]
}

pub fn def() -> CommandDef {
    let mut ddl = ddl_selection();
    ddl.push(
        text("LIAISON")
            .into(&["ENCASTRE"])
            .doc("'ENCASTRE' blocks every dof")
            .kw(),
    );
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
            imposed_dofs(
                "DDL_IMPO",
                ddl,
                &cmp_or_liaison,
                "imposed dofs (dualised by Lagrange multipliers); GROUP_MA means all nodes of those cells",
            )
            .kw(),
            fact(
                "FACE_IMPO",
                [
                    face_impo_selection(),
                    vec![
                        real("DX").doc("imposed value of this component").kw(),
                        real("DY").doc("imposed value of this component").kw(),
                        real("DZ").doc("imposed value of this component").kw(),
                        real("DNOR")
                            .doc("imposed normal displacement u.n (n the mean unit normal of the selected cells at the node); where n is along x, y or z only")
                            .kw(),
                        real("DTAN").kw(),
                    ],
                ]
                .concat(),
            )
            .many()
            .rules(vec![
                un_parmi(&["GROUP_MA", "MAILLE"]),
                au_moins_un(&["DX", "DY", "DZ", "DNOR", "DTAN"]),
                exclus(&["DNOR", "DX"]),
                exclus(&["DNOR", "DY"]),
                exclus(&["DNOR", "DZ"]),
                exclus(&["DTAN", "DX"]),
                exclus(&["DTAN", "DY"]),
                exclus(&["DTAN", "DZ"]),
            ])
            .doc("imposed dofs on every node of the cells of the selection: DX, DY, DZ as DDL_IMPO; DNOR the normal displacement where the normal is along an axis (DTAN: not implemented yet)")
            .kw(),
            fact(
                "PESANTEUR",
                vec![
                    group_ma(),
                    maille(),
                    real("GRAVITE")
                        .required()
                        .doc("magnitude g of the acceleration of gravity (mm/s^2 in the N-mm-t system)")
                        .kw(),
                    real("DIRECTION")
                        .required()
                        .count(3, 3)
                        .doc("direction of gravity (3 components, normalised; the third is unused in AXIS)")
                        .kw(),
                ],
            )
            .doc("gravity: body force RHO*GRAVITE*DIRECTION/|DIRECTION| per unit volume on the volume elements of GROUP_MA (all of them without GROUP_MA); a dead load, scaled in time by EXCIT/FONC_MULT")
            .kw(),
            fact(
                "FORCE_NODALE",
                vec![
                    group_no(),
                    noeud(),
                    real("FX").doc("force along x on each node").kw(),
                    real("FY").doc("force along y on each node").kw(),
                    real("FZ").doc("force along z on each node").kw(),
                    real("MX").kw(),
                    real("MY").kw(),
                    real("MZ").kw(),
                    real("ANGL_NAUT").count(1, 3).kw(),
                ],
            )
            .many()
            .rules(vec![
                au_moins_un(&["GROUP_NO", "NOEUD"]),
                au_moins_un(&["FX", "FY", "FZ", "MX", "MY", "MZ"]),
            ])
            .doc("force on each node of the selection (not shared between them; per radian in AXIS), global frame; a dead load, scaled in time by EXCIT/FONC_MULT; a node given twice keeps its last value per component")
            .kw(),
            fact(
                "PRES_REP",
                vec![
                    tout(),
                    group_ma(),
                    maille(),
                    real("PRES")
                        .doc("pressure (MPa), positive against the normal of the skin cell")
                        .kw(),
                    real("CISA_2D").kw(),
                ],
            )
            .many()
            .rules(vec![
                au_moins_un(&["TOUT", "GROUP_MA", "MAILLE"]),
                au_moins_un(&["PRES", "CISA_2D"]),
            ])
            .doc("uniform pressure on the skin cells of the selection (SEG in AXIS, per radian; TRIA/QUAD in 3D): the force -PRES*n per unit area, n the cell's normal as its nodes orient it (outward after MODI_MAILLAGE ORIE_PEAU_2D/3D); a dead load on the initial geometry, scaled in time by EXCIT/FONC_MULT")
            .kw(),
            distributed_fact(
                "FORCE_FACE",
                &["FX", "FY", "FZ"],
                "force per unit area (MPa) on the TRIA3/TRIA6/QUAD4/QUAD8 skin cells of a 3D model, global frame, consistent nodal forces; a dead load on the initial geometry, scaled in time by EXCIT/FONC_MULT; a cell given again keeps the later occurrence",
            ),
            distributed_fact(
                "FORCE_ARETE",
                &["FX", "FY", "FZ", "MX", "MY", "MZ"],
                "force per unit length (N/mm) on the SEG2/SEG3 cells of a 3D model, global frame, consistent nodal forces; a dead load, scaled in time by EXCIT/FONC_MULT",
            ),
            distributed_fact(
                "FORCE_CONTOUR",
                &["FX", "FY", "FZ", "MX", "MY", "MZ"],
                "force per unit length (N/mm) on the SEG2/SEG3 edges of a 2D model; in AXIS per unit length of the meridian and per radian (the integral carries r), in D_PLAN per unit thickness; global frame, consistent nodal forces; a dead load, scaled in time by EXCIT/FONC_MULT",
            ),
            distributed_fact(
                "FORCE_INTERNE",
                &["FX", "FY", "FZ"],
                "force per unit volume (N/mm^3) on the volume elements of the selection (per radian in AXIS), integrated like PESANTEUR; a dead load, scaled in time by EXCIT/FONC_MULT",
            ),
            oui_non("VERI_NORM", "OUI")
                .doc("check the orientation of skin cells carrying loads")
                .kw(),
            oui_non("DOUBLE_LAGRANGE", "OUI")
                .doc("two Lagrange multipliers per constraint")
                .kw(),
            info(),
        ],
    )
    .rules(vec![au_moins_un(&[
        "DDL_IMPO",
        "FACE_IMPO",
        "PESANTEUR",
        "FORCE_NODALE",
        "PRES_REP",
        "FORCE_FACE",
        "FORCE_ARETE",
        "FORCE_CONTOUR",
        "FORCE_INTERNE",
    ])])
    .doc("Defines mechanical boundary conditions on a model.");
    CommandDef { spec, exec }
}

/// A distributed-force keyword: a cell selection and force components.
fn distributed_fact(name: &'static str, cmps: &[&'static str], doc: &'static str) -> Keyword {
    let mut kws = vec![tout(), group_ma(), maille()];
    for &c in cmps {
        kws.push(if c.starts_with('M') {
            real(c).kw()
        } else {
            real(c).doc("component of the force density").kw()
        });
    }
    fact(name, kws)
        .many()
        .rules(vec![
            au_moins_un(&["TOUT", "GROUP_MA", "MAILLE"]),
            au_moins_un(cmps),
        ])
        .doc(doc)
        .kw()
}

/// DDL_IMPO ([`ddl_impo`]), FACE_IMPO, then the loads.
fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let lm = load_model(study, args)?;
    let mut lines = Vec::new();
    let mut imposed = ddl_impo(args, "DDL_IMPO", &lm, &mut lines)?;
    let LoadModel {
        name: model_name,
        model,
        mesh,
        in_model,
        dof_names,
        ..
    } = lm;
    for (k, occ) in args.facts("FACE_IMPO").iter().enumerate() {
        face_impo(
            occ,
            k,
            mesh,
            &model,
            &model_name,
            &dof_names,
            &in_model,
            &mut imposed,
            &mut lines,
        )?;
    }
    let nodal_forces = nodal_forces_of(args, mesh, &model, &model_name, &in_model, &mut lines)?;
    let pressures = pressures_of(args, mesh, &model, &model_name, &mut lines)?;
    let distributed = distributed_of(args, mesh, &model, &model_name, &mut lines)?;
    let gravity = match args.fact("PESANTEUR") {
        Some(occ) => Some(gravity_of(occ, mesh, &model, &mut lines)?),
        None => None,
    };
    study.log(format!(
        "    load {} on model {model_name}: {} imposed dofs",
        result.unwrap_or("(unnamed)"),
        imposed.len()
    ));
    for l in lines {
        study.log(l);
    }
    Ok(Some(ConceptData::MechLoad(Box::new(MechLoad {
        model: model_name,
        imposed,
        gravity,
        nodal_forces,
        pressures,
        distributed,
        functions: Vec::new(),
        fields: Vec::new(),
    }))))
}

/// DX, DY, DZ given in an occurrence, each a dof of the model.
/// DDL_IMPO's occurrences under `key` (also AFFE_CHAR_CINE's MECA_IMPO,
/// the same selection and components): every selected node gets each
/// given component; `GROUP_MA` means all nodes of those cells and `TOUT`
/// all nodes of the model. Entries are kept in occurrence order,
/// duplicates included (the engine keeps the last value and fails if two
/// differ).
pub(super) fn ddl_impo(
    args: &Args,
    key: &str,
    lm: &LoadModel,
    lines: &mut Vec<String>,
) -> Result<Vec<ImposedDof>, Diagnostic> {
    let LoadModel {
        name: model_name,
        model,
        mesh,
        in_model,
        nodes: model_nodes,
        dof_names,
    } = lm;
    let mut imposed = Vec::new();
    for (k, occ) in args.facts(key).iter().enumerate() {
        let mut dofs: Vec<(Dof, f64)> = Vec::new();
        if occ.has("LIAISON") {
            dofs.extend(model.dofs.iter().map(|&d| (d, 0.0)));
        }
        for (d, v) in given_components(occ, model, model_name, dof_names)? {
            dofs.retain(|(e, _)| *e != d);
            dofs.push((d, v));
        }
        let nodes = select_nodes(mesh, occ, model_nodes)?;
        impose(occ, key, k, &nodes, in_model, model_name, lines)?;
        for &n in &nodes {
            for &(dof, value) in &dofs {
                imposed.push(ImposedDof {
                    node: n,
                    dof,
                    value,
                });
            }
        }
        lines.push(format!(
            "      {key} {}: {} nodes of {}, {}",
            k + 1,
            nodes.len(),
            selection_label(occ),
            dofs.iter()
                .map(|(d, v)| format!("{}={v}", d.name()))
                .collect::<Vec<_>>()
                .join(" ")
        ));
    }
    Ok(imposed)
}

fn given_components(
    occ: &Args,
    model: &crate::model::Model,
    model_name: &str,
    dof_names: &str,
) -> Result<Vec<(Dof, f64)>, Diagnostic> {
    let mut out = Vec::new();
    for &c in CMP_DEPL {
        let Some(v) = occ.real(c) else { continue };
        match Dof::from_name(c).filter(|d| model.has_dof(*d)) {
            Some(d) => out.push((d, v)),
            None => {
                return Err(occ.error(
                    c,
                    format!(
                        "{c} is not a degree of freedom of the model {model_name}, whose nodes carry {dof_names}"
                    ),
                ));
            }
        }
    }
    Ok(out)
}

/// The checks of an imposed-dof selection: every node carries dofs of
/// the model; an empty selection is an alarm.
fn impose(
    occ: &Args,
    key: &str,
    k: usize,
    nodes: &[usize],
    in_model: &[bool],
    model_name: &str,
    lines: &mut Vec<String>,
) -> Result<(), Diagnostic> {
    let outside: Vec<usize> = nodes.iter().copied().filter(|&n| !in_model[n]).collect();
    if let Some(&n0) = outside.first() {
        return Err(occ.error(
            "",
            format!(
                "{} of the nodes of {} (node N{} first) belong to no cell of the model {model_name}: they carry no degree of freedom",
                outside.len(),
                selection_label(occ),
                n0 + 1
            ),
        ));
    }
    if nodes.is_empty() {
        lines.push(format!(
            "<A> <{}> occurrence {} of {key} selects no node",
            occ.command,
            k + 1
        ));
    }
    Ok(())
}

/// FACE_IMPO: the nodes of the cells of GROUP_MA/MAILLE (less SANS_*)
/// get DX, DY, DZ as with DDL_IMPO. DNOR imposes u·n, n the unit normal
/// at the node (the mean of the normals of its selected cells, oriented
/// as their nodes turn, code_aster's `canort`); aster imposes it where n
/// is along an axis (|n_k| = 1 to 1e-9: the plane faces of a box, a
/// symmetry plane), as u_k = DNOR·n_k. Elsewhere u·n = DNOR is a linear
/// relation between dofs, which aster's elimination of imposed dofs does
/// not hold: a located `not implemented yet`, as for DTAN.
#[allow(clippy::too_many_arguments)]
fn face_impo(
    occ: &Args,
    k: usize,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    model_name: &str,
    dof_names: &str,
    in_model: &[bool],
    imposed: &mut Vec<ImposedDof>,
    lines: &mut Vec<String>,
) -> Result<(), Diagnostic> {
    if occ.has("DTAN") {
        return Err(occ.not_implemented(
            "DTAN",
            "a tangential displacement is a linear relation between dofs (FACE_IMPO takes DX, DY, DZ, and DNOR on faces along an axis)",
        ));
    }
    let nodes = select_nodes(mesh, occ, &[])?;
    impose(occ, "FACE_IMPO", k, &nodes, in_model, model_name, lines)?;
    let dofs = given_components(occ, model, model_name, dof_names)?;
    for &n in &nodes {
        for &(dof, value) in &dofs {
            imposed.push(ImposedDof {
                node: n,
                dof,
                value,
            });
        }
    }
    let mut what: Vec<String> = dofs
        .iter()
        .map(|(d, v)| format!("{}={v}", d.name()))
        .collect();
    if let Some(dnor) = occ.real("DNOR") {
        let normals = node_normals(mesh, occ, &select_cells(mesh, occ)?, model)?;
        let axes = [Dof::Dx, Dof::Dy, Dof::Dz];
        for &n in &nodes {
            let Some(nv) = normals.get(&n) else { continue };
            let Some(i) = (0..3).find(|&i| (nv[i].abs() - 1.0).abs() <= 1e-9) else {
                return Err(occ.not_implemented(
                    "DNOR",
                    &format!(
                        "the normal at node N{} is ({:.6}, {:.6}, {:.6}), along no axis: u.n = DNOR there is a linear relation between dofs, which aster does not hold (it imposes DNOR where the normal is along x, y or z)",
                        n + 1,
                        nv[0],
                        nv[1],
                        nv[2]
                    ),
                ));
            };
            imposed.push(ImposedDof {
                node: n,
                dof: axes[i],
                value: dnor * nv[i].signum(),
            });
        }
        what.push(format!("DNOR={dnor}"));
    }
    lines.push(format!(
        "      FACE_IMPO {}: {} nodes of {}, {}",
        k + 1,
        nodes.len(),
        selection_label(occ),
        what.join(" ")
    ));
    Ok(())
}

/// The unit normal at each node of `cells` (faces in 3D, edges in 2D):
/// the normalised sum of the unit normals of the cells around it, each
/// cell's from its first corners as its nodes turn.
fn node_normals(
    mesh: &crate::mesh::Mesh,
    occ: &Args,
    cells: &[usize],
    model: &crate::model::Model,
) -> Result<std::collections::HashMap<usize, [f64; 3]>, Diagnostic> {
    let plane = model.ndof_per_node() == 2;
    let mut sum: std::collections::HashMap<usize, [f64; 3]> = std::collections::HashMap::new();
    for &c in cells {
        let cell = &mesh.cells[c];
        let p = |a: usize| mesh.coords[cell.nodes[a]];
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let nv = match (cell.kind.dim(), plane) {
            (1, true) => {
                let t = sub(p(1), p(0));
                [t[1], -t[0], 0.0]
            }
            (2, false) => {
                let (u, v) = (sub(p(1), p(0)), sub(p(2), p(0)));
                [
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                ]
            }
            _ => {
                return Err(occ.error(
                    "DNOR",
                    format!(
                        "cell {} of {} is a {}: DNOR needs the {} of the model's boundary",
                        c + 1,
                        selection_label(occ),
                        cell.kind.aster_name(),
                        if plane {
                            "SEG2/SEG3 edges"
                        } else {
                            "TRIA/QUAD faces"
                        }
                    ),
                ))
            }
        };
        let len = (nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]).sqrt();
        if len.is_nan() || len <= 0.0 {
            return Err(occ.error(
                "DNOR",
                format!("cell {} is degenerate: it has no normal", c + 1),
            ));
        }
        for &n in &cell.nodes {
            let e = sum.entry(n).or_insert([0.0; 3]);
            for i in 0..3 {
                e[i] += nv[i] / len;
            }
        }
    }
    for v in sum.values_mut() {
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if len > 0.0 {
            v.iter_mut().for_each(|x| *x /= len);
        }
    }
    Ok(sum)
}

/// FORCE_NODALE: every node of an occurrence gets each given component
/// (not shared out between the nodes); a node given again by a later
/// occurrence keeps the later value of the components that occurrence
/// gives. Moments and ANGL_NAUT need rotational dofs or a local frame,
/// which no element here has.
fn nodal_forces_of(
    args: &Args,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    model_name: &str,
    in_model: &[bool],
    lines: &mut Vec<String>,
) -> Result<Vec<(usize, Dof, f64)>, Diagnostic> {
    let mut forces: Vec<(usize, Dof, f64)> = Vec::new();
    for (k, occ) in args.facts("FORCE_NODALE").iter().enumerate() {
        for key in ["MX", "MY", "MZ"] {
            if occ.has(key) {
                return Err(occ.not_implemented(
                    key,
                    "nodal moments (no element of aster has rotational dofs)",
                ));
            }
        }
        if occ.has("ANGL_NAUT") {
            return Err(occ.not_implemented("ANGL_NAUT", "forces are given in the global frame"));
        }
        let mut given: Vec<(Dof, f64)> = Vec::new();
        for (key, dof) in [("FX", Dof::Dx), ("FY", Dof::Dy), ("FZ", Dof::Dz)] {
            let Some(v) = occ.real(key) else { continue };
            if !model.has_dof(dof) {
                return Err(occ.error(
                    key,
                    format!(
                        "{key} acts along {}, which is not a degree of freedom of the model {model_name}",
                        dof.name()
                    ),
                ));
            }
            given.push((dof, v));
        }
        let nodes = select_nodes(mesh, occ, &[])?;
        if let Some(&n0) = nodes.iter().find(|&&n| !in_model[n]) {
            return Err(occ.error(
                "",
                format!(
                    "node N{} of {} belongs to no cell of the model {model_name}: a force there acts on nothing",
                    n0 + 1,
                    selection_label(occ)
                ),
            ));
        }
        for &n in &nodes {
            for &(dof, v) in &given {
                forces.retain(|&(m, d, _)| !(m == n && d == dof));
                forces.push((n, dof, v));
            }
        }
        lines.push(format!(
            "      FORCE_NODALE {}: {} nodes of {}, {}",
            k + 1,
            nodes.len(),
            selection_label(occ),
            given
                .iter()
                .map(|(d, v)| format!("F{}={v}", &d.name()[1..]))
                .collect::<Vec<_>>()
                .join(" ")
        ));
    }
    Ok(forces)
}

/// PRES_REP: each occurrence loads the skin cells of its selection (SEG
/// in AXIS, TRIA/QUAD in 3D, assigned to the model by AFFE_MODELE);
/// the volume cells of a TOUT or GROUP_MA selection carry no pressure and
/// are skipped, as code_aster's volume elements have no PRES_REP option.
/// A selected cell outside the model is an error (its nodes may carry no
/// dof), and so is a selection with no skin cell. With VERI_NORM='OUI'
/// (the default) a cell whose normal points into the body it bounds is an
/// error: its pressure would pull.
fn pressures_of(
    args: &Args,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    model_name: &str,
    lines: &mut Vec<String>,
) -> Result<Vec<Pressure>, Diagnostic> {
    let mut out = Vec::new();
    for (k, occ) in args.facts("PRES_REP").iter().enumerate() {
        if occ.has("CISA_2D") {
            return Err(occ.not_implemented("CISA_2D", "only a normal pressure PRES"));
        }
        let p = occ.real("PRES").unwrap_or(0.0);
        if !p.is_finite() {
            return Err(occ.error("PRES", "PRES must be finite"));
        }
        let cells = pressure_cells(args, occ, k, mesh, model, model_name)?;
        lines.push(format!(
            "      PRES_REP {}: PRES = {p:e} on {} skin cells of {}",
            k + 1,
            cells.len(),
            selection_label(occ)
        ));
        out.push(Pressure { p, cells });
    }
    Ok(out)
}

/// The skin cells occurrence `k` of PRES_REP loads (AFFE_CHAR_MECA and
/// AFFE_CHAR_MECA_F): see [`pressures_of`] for the rules.
pub(super) fn pressure_cells(
    args: &Args,
    occ: &Args,
    k: usize,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    model_name: &str,
) -> Result<Vec<usize>, Diagnostic> {
    let skin_dim = if model.ndof_per_node() == 2 { 1 } else { 2 };
    let selected = select_cells(mesh, occ)?;
    let mut cells = Vec::new();
    for &c in &selected {
        match model.cells.get(c) {
            Some(CellRole::Skin { .. }) => {
                let kind = mesh.cells[c].kind;
                if kind.dim() != skin_dim {
                    return Err(occ.error(
                        "",
                        format!(
                            "cell {} of {} is a {}: a pressure on the model {model_name} acts on {} cells",
                            c + 1,
                            selection_label(occ),
                            kind.aster_name(),
                            if skin_dim == 1 { "SEG2/SEG3" } else { "TRIA3/TRIA6/QUAD4/QUAD8" }
                        ),
                    ));
                }
                cells.push(c);
            }
            Some(CellRole::Element(_)) => {}
            _ if occ.has("TOUT") => {}
            _ => return Err(outside_model(occ, c, model_name, "the skin")),
        }
    }
    if cells.is_empty() {
        return Err(occ.error(
            "",
            format!(
                "{} has no skin cell of the model {model_name} ({} in AXIS, {} in 3D): a pressure acts on nothing",
                selection_label(occ),
                "SEG2/SEG3",
                "TRIA3/TRIA6/QUAD4/QUAD8"
            ),
        ));
    }
    if args.text("VERI_NORM") != Some("NON") {
        let inward = crate::mesh::ops::inward_skin_cells(mesh, &cells);
        if let Some(first) = inward.first() {
            let orie = if skin_dim == 1 {
                "ORIE_PEAU_2D"
            } else {
                "ORIE_PEAU_3D"
            };
            return Err(occ.error(
                "",
                format!(
                    "PRES_REP {}: the normals of {} of the {} cells of {} point into the body \
                     (first: cell M{}, on cell M{}); a positive PRES pushes against the normal, \
                     so it would pull: orient the skin with MODI_MAILLAGE(reuse=MAIL, \
                     MAILLAGE=MAIL, {orie}=_F(GROUP_MA=...)) before {} \
                     (VERI_NORM='NON' skips this check)",
                    k + 1,
                    inward.len(),
                    cells.len(),
                    selection_label(occ),
                    first.cell + 1,
                    first.support + 1,
                    args.command
                ),
            ));
        }
    }
    Ok(cells)
}

/// PESANTEUR: GRAVITE and DIRECTION normalised as code_aster's `capesa`
/// does (a zero DIRECTION is its fatal CHARGES2_53); GROUP_MA restricts
/// the cells, its cells that are not volume elements of the model are
/// skipped when the forces are built (they have no mass).
fn gravity_of(
    occ: &Args,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    lines: &mut Vec<String>,
) -> Result<Gravity, Diagnostic> {
    let g = occ.real("GRAVITE").unwrap_or(0.0);
    let d = occ.reals("DIRECTION");
    let norm = d.iter().map(|c| c * c).sum::<f64>().sqrt();
    if d.len() != 3 || !norm.is_finite() || norm <= f64::MIN_POSITIVE {
        return Err(occ.error(
            "DIRECTION",
            "DIRECTION must be a non-zero vector of 3 finite components",
        ));
    }
    if !g.is_finite() {
        return Err(occ.error("GRAVITE", "GRAVITE must be finite"));
    }
    let direction = [d[0] / norm, d[1] / norm, d[2] / norm];
    let cells = if occ.has("GROUP_MA") || occ.has("MAILLE") {
        Some(select_cells(mesh, occ)?)
    } else {
        None
    };
    let nvol = match &cells {
        Some(c) => c
            .iter()
            .filter(|&&c| matches!(model.cells.get(c), Some(CellRole::Element(_))))
            .count(),
        None => model.element_cells().count(),
    };
    if nvol == 0 {
        return Err(occ.error(
            if cells.is_some() { "GROUP_MA" } else { "" },
            "PESANTEUR applies to no volume element of the model",
        ));
    }
    if !model.has_dof(Dof::Dz) && direction[2] != 0.0 {
        lines.push(format!(
            "<A> <AFFE_CHAR_MECA> PESANTEUR: the model has no DZ; the third component of the normalised DIRECTION ({:e}) is ignored",
            direction[2]
        ));
    }
    lines.push(format!(
        "      PESANTEUR: g = {g:e} along ({:e}, {:e}, {:e}) on {nvol} volume elements",
        direction[0], direction[1], direction[2]
    ));
    Ok(Gravity {
        g,
        direction,
        cells,
    })
}

/// FORCE_FACE, FORCE_ARETE, FORCE_CONTOUR, FORCE_INTERNE: each occurrence
/// gives a uniform force density to the cells of its selection that can
/// carry it: skin faces (FORCE_FACE, 3D), skin edges (FORCE_ARETE in 3D,
/// FORCE_CONTOUR in AXIS and D_PLAN), volume elements (FORCE_INTERNE). As for
/// PRES_REP, the other cells of the model in the selection are skipped,
/// a selected cell outside the model is an error (unless by TOUT), and so
/// is a selection with no cell to load. A keyword meant for the other
/// model dimension, or a component the model does not carry (FZ in 2D),
/// is an error giving the valid choices. A cell given again by a later
/// occurrence of the same keyword keeps the later density (code_aster's
/// load card is assigned occurrence by occurrence, every component,
/// absent ones 0).
fn distributed_of(
    args: &Args,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    model_name: &str,
    lines: &mut Vec<String>,
) -> Result<Vec<DistributedForce>, Diagnostic> {
    let mut out: Vec<DistributedForce> = Vec::new();
    for kind in DISTRIBUTED_KINDS {
        let key = kind.keyword();
        for (k, occ) in args.facts(key).iter().enumerate() {
            let mut force = [0.0; 3];
            for (i, c) in force_components(occ, kind, model, model_name)? {
                let Some(v) = occ.real(c) else { continue };
                if !v.is_finite() {
                    return Err(occ.error(c, format!("{c} must be finite")));
                }
                force[i] = v;
            }
            let cells = distributed_cells(occ, kind, mesh, model, model_name)?;
            for earlier in out.iter_mut().filter(|d| d.kind == kind) {
                earlier.cells.retain(|c| !cells.contains(c));
            }
            lines.push(format!(
                "      {key} {}: ({:e}, {:e}, {:e}) on {} cells of {}",
                k + 1,
                force[0],
                force[1],
                force[2],
                cells.len(),
                selection_label(occ)
            ));
            out.push(DistributedForce { kind, force, cells });
        }
    }
    out.retain(|d| !d.cells.is_empty());
    Ok(out)
}

/// The distributed-load keywords, in the order they are read.
pub(super) const DISTRIBUTED_KINDS: [DistributedKind; 4] = [
    DistributedKind::Face,
    DistributedKind::Edge,
    DistributedKind::Contour,
    DistributedKind::Internal,
];

/// "AXIS", "D_PLAN", "C_PLAN", "2D" or "3D": the model as the messages
/// name it.
fn model_kind(model: &crate::model::Model) -> &'static str {
    match model.formulation() {
        Some(Formulation::Axis) => "AXIS",
        Some(Formulation::PlaneStrain) => "D_PLAN",
        Some(Formulation::PlaneStress) => "C_PLAN",
        _ if model.ndof_per_node() == 2 => "2D",
        _ => "3D",
    }
}

/// The components FX, FY, FZ an occurrence of `kind` may give, as (index,
/// name), after the checks every distributed load shares: the keyword
/// fits the model's dimension, no moment, no component the model does
/// not carry (FZ in 2D) among those given.
pub(super) fn force_components(
    occ: &Args,
    kind: DistributedKind,
    model: &crate::model::Model,
    model_name: &str,
) -> Result<Vec<(usize, &'static str)>, Diagnostic> {
    let plane = model.ndof_per_node() == 2;
    let key = kind.keyword();
    let wrong_model = match kind {
        DistributedKind::Face | DistributedKind::Edge => plane,
        DistributedKind::Contour => !plane,
        DistributedKind::Internal => false,
    };
    if wrong_model {
        return Err(occ.error(
            "",
            format!(
                "{key} does not apply to the {} model {model_name}: {}",
                model_kind(model),
                if plane {
                    "on a 2D model, FORCE_CONTOUR loads the SEG2/SEG3 edges, FORCE_INTERNE the surface elements, PRES_REP presses on edges"
                } else {
                    "on a 3D model, FORCE_FACE loads the TRIA/QUAD faces, FORCE_ARETE the SEG2/SEG3 edges, FORCE_INTERNE the volume elements, PRES_REP presses on faces"
                }
            ),
        ));
    }
    for m in ["MX", "MY", "MZ"] {
        if occ.has(m) {
            return Err(occ.not_implemented(
                m,
                "distributed moments (no element of aster has rotational dofs)",
            ));
        }
    }
    let mut out = Vec::new();
    for (i, (c, dof)) in [("FX", Dof::Dx), ("FY", Dof::Dy), ("FZ", Dof::Dz)]
        .into_iter()
        .enumerate()
    {
        if !occ.has(c) {
            continue;
        }
        if !model.has_dof(dof) {
            return Err(occ.error(
                c,
                format!(
                    "{c} acts along {}, which is not a degree of freedom of the model {model_name} (valid: {})",
                    dof.name(),
                    if plane { "FX, FY" } else { "FX, FY, FZ" }
                ),
            ));
        }
        out.push((i, c));
    }
    Ok(out)
}

/// The cells an occurrence of `kind` loads (AFFE_CHAR_MECA and
/// AFFE_CHAR_MECA_F): see [`distributed_of`] for the rules.
pub(super) fn distributed_cells(
    occ: &Args,
    kind: DistributedKind,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    model_name: &str,
) -> Result<Vec<usize>, Diagnostic> {
    let plane = model.ndof_per_node() == 2;
    let key = kind.keyword();
    // (cell dimension, role wanted, what the valid cells are)
    let (dim, skin, cells_text) = match kind {
        DistributedKind::Face => (2, true, "TRIA3/TRIA6/QUAD4/QUAD8 faces"),
        DistributedKind::Edge | DistributedKind::Contour => (1, true, "SEG2/SEG3 edges"),
        DistributedKind::Internal => (if plane { 2 } else { 3 }, false, "volume elements"),
    };
    let selected = select_cells(mesh, occ)?;
    let mut cells = Vec::new();
    for &c in &selected {
        let fits = mesh.cells[c].kind.dim() == dim;
        match model.cells.get(c) {
            Some(CellRole::Skin { .. }) if skin && fits => cells.push(c),
            Some(CellRole::Element(_)) if !skin => cells.push(c),
            Some(CellRole::Skin { .. }) | Some(CellRole::Element(_)) => {}
            _ if occ.has("TOUT") => {}
            _ => return Err(outside_model(occ, c, model_name, "it")),
        }
    }
    if cells.is_empty() {
        return Err(occ.error(
            "",
            format!(
                "{} has no cell that {key} loads: on the {} model {model_name} it acts on {cells_text} of the model",
                selection_label(occ),
                model_kind(model),
            ),
        ));
    }
    Ok(cells)
}

/// A selected cell outside the model: its nodes may carry no dof.
fn outside_model(occ: &Args, c: usize, model_name: &str, what: &str) -> Diagnostic {
    occ.error(
        "",
        format!(
            "cell {} of {} belongs to no element of the model {model_name}: assign {what} to the model (AFFE_MODELE) to load it",
            c + 1,
            selection_label(occ)
        ),
    )
}
