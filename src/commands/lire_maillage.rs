//! LIRE_MAILLAGE: reads a mesh from a logical unit.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "LIRE_MAILLAGE",
        Produces::Concept(C::Maillage),
        vec![
            text("FORMAT")
                .into(&["ASTER", "GIBI", "GMSH", "IDEAS", "MED"])
                .default(t("MED"))
                .doc("file format: MED, or code_aster's own (.mail) with ASTER; GIBI, GMSH, IDEAS are not read")
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
    .compat(other_formats)
    .doc("Reads a mesh; MED cell groups become GROUP_MA, node groups GROUP_NO.");
    CommandDef { spec, exec }
}

/// FORMAT other than 'MED' is code_aster's but not read here: said when
/// the file is checked (`aster check`, and before a run starts), not when
/// the command runs (probe s8c: `check` passed files whose run then
/// stopped at their first command).
// The type of every compat hook (which may add or drop keywords).
#[allow(clippy::ptr_arg)]
fn other_formats(
    given: &mut Vec<(crate::lang::ast::Ident, crate::catalog::eval::SpVal)>,
) -> Vec<crate::diag::Diagnostic> {
    use crate::catalog::eval::PyVal;
    given
        .iter()
        .filter(|(k, _)| k.name == "FORMAT")
        .filter_map(|(_, v)| match &v.v {
            PyVal::Str(f) if ["GIBI", "GMSH", "IDEAS"].contains(&f.as_str()) => Some(
                crate::diag::Diagnostic::error(format!(
                    "not implemented yet: LIRE_MAILLAGE/FORMAT='{f}' (FORMAT='MED' and 'ASTER' are read)"
                ))
                .at(v.span)
                .in_command("LIRE_MAILLAGE")
                .keyword("FORMAT")
                .note("convert the mesh to MED (SALOME's mesh module, or gmsh's MED export) and read it with FORMAT='MED'"),
            ),
            _ => None,
        })
        .collect()
}

/// Reads the MED or code_aster (`.mail`) file behind the logical unit.
fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let aster = match args.text("FORMAT") {
        Some("MED") => false,
        Some("ASTER") => true,
        _ => return Err(args.not_implemented("FORMAT", "FORMAT='MED' and 'ASTER' are read")),
    };
    let unit = args.int("UNITE").unwrap_or(20);
    let path = study.unit_path(unit);
    if !path.is_file() {
        let mapped = study.units.path(unit).is_some();
        let mut d = args.error(
            "UNITE",
            format!(
                "logical unit {unit} {} '{}', which does not exist",
                if mapped {
                    "is mapped to"
                } else {
                    "is not mapped; its default file is"
                },
                path.display()
            ),
        );
        if !mapped {
            d = d.note(format!(
                "map it with a line 'F mmed <path> D {unit}' in the study's .export file, or with --unit {unit}=<path>"
            ));
        }
        return Err(d);
    }
    let (mesh, undescribed) = if aster {
        let bytes = std::fs::read(&path)
            .map_err(|e| args.error("UNITE", format!("cannot read '{}': {e}", path.display())))?;
        let text = String::from_utf8_lossy(&bytes);
        let (mesh, alarms) =
            crate::mesh::mail::parse(&text, result.unwrap_or("MAIL")).map_err(|e| {
                args.error(
                    "FORMAT",
                    format!("the code_aster mesh file '{}', {e}", path.display()),
                )
            })?;
        for a in alarms {
            study.log(format!("<A> <LIRE_MAILLAGE> {a}"));
        }
        (mesh, Vec::new())
    } else {
        crate::medio::read_mesh_with_notes(&path, args.text("NOM_MED")).map_err(|e| {
            let d = args.error(
                if args.given("NOM_MED") {
                    "NOM_MED"
                } else {
                    "UNITE"
                },
                e.to_string(),
            );
            // code_aster up to version 12 read LIRE_MAILLAGE() as
            // FORMAT='ASTER': its old files meet a .mail here.
            if looks_like_mail(&path) {
                d.note("the file is a code_aster mesh in its own text format (.mail): read it with LIRE_MAILLAGE(FORMAT='ASTER'), the default of code_aster up to version 12")
            } else {
                d
            }
        })?
    };
    study.log(format!(
        "    mesh '{}' read from {}: {} nodes, {} cells",
        mesh.name,
        path.display(),
        mesh.nnodes(),
        mesh.ncells()
    ));
    for (t, n) in mesh.count_by_type() {
        study.log(format!("      {:<8} {n}", t.aster_name()));
    }
    // A family number /FAS does not describe is a writer's bug: the
    // entities stay in the mesh, but whatever groups they were meant to
    // be in do not hold them (code_aster 13 dropped them as silently;
    // its later readers stop on an internal assertion).
    for u in &undescribed {
        let (what, prefix) = if u.cells {
            ("cell", 'M')
        } else {
            ("node", 'N')
        };
        study.log(format!(
            "<A> <LIRE_MAILLAGE> {} {what}(s) of mesh '{}' (first: {prefix}{}) refer to the family {}, \
             which the file's /FAS/{}/{} does not describe: they belong to no group, and a group \
             they were meant to be in lacks them; check the program that wrote {}",
            u.count,
            mesh.name,
            u.first + 1,
            u.family,
            mesh.name,
            if u.cells { "ELEME" } else { "NOEUD" },
            path.display()
        ));
    }
    Ok(Some(ConceptData::Mesh(Box::new(mesh))))
}

/// Whether a file is text that opens like a code_aster `.mail` (a TITRE
/// or COOR_ sub-file among its first lines).
fn looks_like_mail(path: &std::path::Path) -> bool {
    let Ok(bytes) = std::fs::read(path) else {
        return false;
    };
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]);
    head.lines()
        .map(|l| l.split('%').next().unwrap_or("").trim())
        .filter(|l| !l.is_empty())
        .take(50)
        .any(|l| {
            let w = l
                .split_whitespace()
                .next()
                .unwrap_or("")
                .to_ascii_uppercase();
            w == "TITRE" || w.starts_with("COOR_")
        })
}
