//! What the model-building commands share: fetching the model and mesh a
//! command works on, and turning `TOUT`/`GROUP_MA`/`GROUP_NO` selections
//! into cells and nodes with the same checks everywhere (unknown groups
//! named with a suggestion). The deprecated by-name selectors MAILLE,
//! NOEUD, SANS_MAILLE and SANS_NOEUD read code_aster's default names
//! (`M3`, `N12`: aster meshes carry no names, see post_args).

use super::mesh_args::{check_groups, GroupKind};
use super::post_args::{cell_by_name, node_by_name};
use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Diagnostic;
use crate::mesh::Mesh;
use crate::model::Model;
use crate::study::Study;

/// The model concept given under `key`, with its name.
pub fn model_of<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
) -> Result<(String, &'s Model), Diagnostic> {
    let name = args
        .concept(key)
        .ok_or_else(|| args.error(key, "a model concept is expected"))?;
    match study.concepts.data(name) {
        Some(ConceptData::Model(m)) => Ok((name.to_string(), m)),
        _ => Err(args.error(
            key,
            format!("the model {name} holds no data (its command did not run)"),
        )),
    }
}

/// The mesh a model was built on. `key` is the keyword that named the
/// model, for the message if the mesh concept is gone.
pub fn mesh_of_model<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
    model: &Model,
) -> Result<&'s Mesh, Diagnostic> {
    match study.concepts.data(&model.mesh) {
        // A mesh concept rebound (reuse=) to a mesh with other cells would
        // no longer match the model's per-cell roles.
        Some(ConceptData::Mesh(m)) if m.ncells() != model.cells.len() => Err(args.error(
            key,
            format!(
                "the mesh {} has {} cells but had {} when the model was built: rebuild the model",
                model.mesh,
                m.ncells(),
                model.cells.len()
            ),
        )),
        Some(ConceptData::Mesh(m)) => Ok(m),
        _ => Err(args.error(
            key,
            format!(
                "the mesh {} of this model holds no data (its command did not run)",
                model.mesh
            ),
        )),
    }
}

/// The cells an occurrence selects with `TOUT='OUI'` or `GROUP_MA`
/// (the union of the groups), in increasing order.
pub fn select_cells(mesh: &Mesh, occ: &Args) -> Result<Vec<usize>, Diagnostic> {
    if occ.has("TOUT") {
        return Ok((0..mesh.ncells()).collect());
    }
    if occ.has("GROUP_MA") || occ.has("MAILLE") {
        check_groups(mesh, occ, "GROUP_MA", GroupKind::Cells)?;
        let mut cells: Vec<usize> = occ
            .texts("GROUP_MA")
            .iter()
            .flat_map(|g| mesh.cell_groups[*g].iter().copied())
            .collect();
        for name in occ.texts("MAILLE") {
            cells.push(cell_by_name(mesh, occ, "MAILLE", name)?);
        }
        cells.sort_unstable();
        cells.dedup();
        return Ok(cells);
    }
    Err(occ.error("", "one of TOUT, GROUP_MA or MAILLE is required"))
}

/// The nodes an occurrence selects: the union of `TOUT` (the nodes given
/// in `tout`), all nodes of the cells of `GROUP_MA` and `MAILLE` and the
/// nodes of `GROUP_NO` and `NOEUD`, minus those of `SANS_GROUP_NO`,
/// `SANS_NOEUD` and of the cells of `SANS_GROUP_MA`, `SANS_MAILLE` when
/// the level declares them. Increasing order, no duplicates.
pub fn select_nodes(mesh: &Mesh, occ: &Args, tout: &[usize]) -> Result<Vec<usize>, Diagnostic> {
    let mut mask = vec![false; mesh.nnodes()];
    if occ.has("TOUT") {
        for &n in tout {
            mask[n] = true;
        }
    }
    if occ.has("GROUP_MA") {
        check_groups(mesh, occ, "GROUP_MA", GroupKind::Cells)?;
        for g in occ.texts("GROUP_MA") {
            for &c in &mesh.cell_groups[g] {
                for &n in &mesh.cells[c].nodes {
                    mask[n] = true;
                }
            }
        }
    }
    if occ.has("GROUP_NO") {
        check_groups(mesh, occ, "GROUP_NO", GroupKind::Nodes)?;
        for g in occ.texts("GROUP_NO") {
            for &n in &mesh.node_groups[g] {
                mask[n] = true;
            }
        }
    }
    for name in occ.texts("MAILLE") {
        for &n in &mesh.cells[cell_by_name(mesh, occ, "MAILLE", name)?].nodes {
            mask[n] = true;
        }
    }
    for name in occ.texts("NOEUD") {
        mask[node_by_name(mesh, occ, "NOEUD", name)?] = true;
    }
    if occ.has("SANS_GROUP_MA") {
        check_groups(mesh, occ, "SANS_GROUP_MA", GroupKind::Cells)?;
        for g in occ.texts("SANS_GROUP_MA") {
            for &c in &mesh.cell_groups[g] {
                for &n in &mesh.cells[c].nodes {
                    mask[n] = false;
                }
            }
        }
    }
    if occ.has("SANS_GROUP_NO") {
        check_groups(mesh, occ, "SANS_GROUP_NO", GroupKind::Nodes)?;
        for g in occ.texts("SANS_GROUP_NO") {
            for &n in &mesh.node_groups[g] {
                mask[n] = false;
            }
        }
    }
    for name in occ.texts("SANS_MAILLE") {
        for &n in &mesh.cells[cell_by_name(mesh, occ, "SANS_MAILLE", name)?].nodes {
            mask[n] = false;
        }
    }
    for name in occ.texts("SANS_NOEUD") {
        mask[node_by_name(mesh, occ, "SANS_NOEUD", name)?] = false;
    }
    Ok(mask
        .iter()
        .enumerate()
        .filter_map(|(i, &s)| s.then_some(i))
        .collect())
}

/// The names of the mesh's cell groups that contain at least one of
/// `cells`, for messages that must say where offending cells are.
pub fn groups_containing(mesh: &Mesh, cells: &[usize]) -> Vec<String> {
    mesh.groups_containing(cells)
}

/// "the selected nodes" or the names of the selecting groups, for messages.
pub fn selection_label(occ: &Args) -> String {
    let mut parts = Vec::new();
    if occ.has("TOUT") {
        parts.push("TOUT='OUI'".to_string());
    }
    for key in ["GROUP_MA", "GROUP_NO", "MAILLE", "NOEUD"] {
        let g = occ.texts(key);
        if !g.is_empty() {
            parts.push(format!("{key}={}", g.join(",")));
        }
    }
    if parts.is_empty() {
        "the selection".into()
    } else {
        parts.join(" ")
    }
}

/// A real for the message file: plain when of moderate size, otherwise in
/// exponent notation (Rust's plain `{}` writes 8.93e-9 as 0.00000000893).
pub fn real_text(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e7).contains(&a) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// The model a load is defined on (MODELE of AFFE_CHAR_MECA and
/// AFFE_CHAR_MECA_F): its name, a copy, its mesh, which nodes carry dofs
/// (as a mask and a list) and the names of those dofs for messages.
pub struct LoadModel<'s> {
    pub name: String,
    pub model: Model,
    pub mesh: &'s Mesh,
    pub in_model: Vec<bool>,
    pub nodes: Vec<usize>,
    pub dof_names: String,
}

pub fn load_model<'s>(study: &'s Study, args: &Args) -> Result<LoadModel<'s>, Diagnostic> {
    let (name, model) = model_of(study, args, "MODELE")?;
    let model = model.clone();
    let mesh = mesh_of_model(study, args, "MODELE", &model)?;
    let in_model = model.node_mask(mesh);
    let nodes: Vec<usize> = (0..mesh.nnodes()).filter(|&n| in_model[n]).collect();
    let dof_names = model
        .dofs
        .iter()
        .map(|d| d.name())
        .collect::<Vec<_>>()
        .join(", ");
    Ok(LoadModel {
        name,
        model,
        mesh,
        in_model,
        nodes,
        dof_names,
    })
}
