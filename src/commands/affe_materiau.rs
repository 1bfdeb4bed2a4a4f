//! AFFE_MATERIAU: assigns materials to cells.

use indexmap::IndexMap;

use super::blocks::*;
use super::mesh_args::mesh_of;
use super::model_args::{mesh_of_model, model_of, select_cells};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::model::{CellRole, MaterialField};
use crate::study::Study;

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
    CommandDef { spec, exec }
}

/// Builds the material field over the mesh (of MAILLAGE, or of MODELE);
/// occurrences are applied in order, so on a cell selected twice the last
/// one wins, as for every code_aster "carte".
fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let model = if args.has("MODELE") {
        let (name, m) = model_of(study, args, "MODELE")?;
        Some((name, m.clone()))
    } else {
        None
    };
    let (mesh_name, mesh) = match (&model, args.concept("MAILLAGE")) {
        (Some((mo, m)), Some(given)) if given != m.mesh => {
            return Err(args.error(
                "MAILLAGE",
                format!(
                    "the model {mo} is built on the mesh {}, not on {given}",
                    m.mesh
                ),
            ));
        }
        (Some((_, m)), _) => (
            m.mesh.clone(),
            mesh_of_model(study, args, "MODELE", m)?.clone(),
        ),
        (None, Some(name)) => (name.to_string(), mesh_of(study, args, "MAILLAGE")?.clone()),
        (None, None) => return Err(args.error("", "one of MAILLAGE or MODELE is required")),
    };
    let mut cell_material: Vec<Option<String>> = vec![None; mesh.ncells()];
    for occ in args.facts("AFFE") {
        let maters = occ.concepts("MATER");
        if maters.len() > 1 {
            return Err(occ.not_implemented(
                "MATER",
                "several materials on the same cells (coupled physics); give one",
            ));
        }
        let Some(mater) = maters.first() else {
            return Err(occ.error("MATER", "a material concept is expected"));
        };
        if !matches!(study.concepts.data(mater), Some(ConceptData::Material(_))) {
            return Err(occ.error(
                "MATER",
                format!("the material {mater} holds no data (its command did not run)"),
            ));
        }
        for c in select_cells(&mesh, occ)? {
            cell_material[c] = Some(mater.to_string());
        }
    }
    let mut counts: IndexMap<&str, usize> = IndexMap::new();
    for m in cell_material.iter().flatten() {
        *counts.entry(m).or_default() += 1;
    }
    study.log(format!(
        "    material field {} on mesh {mesh_name}: {}",
        result.unwrap_or("(unnamed)"),
        counts
            .iter()
            .map(|(m, n)| format!("{m} on {n} cells"))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    if let Some((mo, m)) = &model {
        let missing = m
            .cells
            .iter()
            .zip(&cell_material)
            .filter(|(r, mat)| matches!(r, CellRole::Element(_)) && mat.is_none())
            .count();
        if missing > 0 {
            study.log(format!(
                "<A> <AFFE_MATERIAU> {missing} element(s) of the model {mo} have no material"
            ));
        }
    }
    Ok(Some(ConceptData::MaterialField(Box::new(MaterialField {
        mesh: mesh_name,
        cell_material,
    }))))
}
