//! What the mesh commands share: fetching a mesh concept, checking group
//! names against it, and logging the alarms of mesh operations.

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::{closest, Diagnostic};
use crate::mesh::ops::{MeshError, Report};
use crate::mesh::Mesh;
use crate::study::Study;

/// The mesh of the concept given under `key`.
pub fn mesh_of<'s>(study: &'s Study, args: &Args, key: &str) -> Result<&'s Mesh, Diagnostic> {
    let name = args
        .concept(key)
        .ok_or_else(|| args.error(key, "a mesh concept is expected"))?;
    match study.concepts.get(name).map(|c| &c.data) {
        Some(ConceptData::Mesh(m)) => Ok(m),
        _ => Err(args.error(
            key,
            format!("the mesh {name} holds no data (its command did not run)"),
        )),
    }
}

pub enum GroupKind {
    Cells,
    Nodes,
}

/// Checks that every group named under `key` exists in the mesh; the
/// error names the group, lists the existing ones and suggests the closest.
pub fn check_groups(
    mesh: &Mesh,
    args: &Args,
    key: &str,
    kind: GroupKind,
) -> Result<(), Diagnostic> {
    let (known, what): (Vec<&str>, &str) = match kind {
        GroupKind::Cells => (
            mesh.cell_groups.keys().map(String::as_str).collect(),
            "cell group (GROUP_MA)",
        ),
        GroupKind::Nodes => (
            mesh.node_groups.keys().map(String::as_str).collect(),
            "node group (GROUP_NO)",
        ),
    };
    for g in args.texts(key) {
        if !known.contains(&g) {
            let mut d = args.error(
                key,
                format!(
                    "the mesh {} has no {what} '{g}'",
                    if mesh.name.is_empty() {
                        "read"
                    } else {
                        &mesh.name
                    }
                ),
            );
            d.suggestion = closest(g, &known);
            d.choices = known.iter().map(|s| s.to_string()).collect();
            return Err(d);
        }
    }
    Ok(())
}

/// Logs the alarms and information lines of a mesh operation.
pub fn log_report(study: &mut Study, command: &str, report: &Report) {
    for a in &report.alarms {
        study.log(format!("<A> <{command}> <{}> {}", a.id, a.text));
    }
    for i in &report.infos {
        study.log(format!("    {i}"));
    }
}

/// A mesh-operation error as a diagnostic on `key`.
pub fn mesh_error(args: &Args, key: &str, e: MeshError) -> Diagnostic {
    args.error(key, format!("{} ({})", e.text, e.id))
}
