//! The text `aster info FILE.mmed` prints about a mesh.

use std::fmt::Write;

use crate::mesh::{CellType, Mesh};

/// Summary of a mesh: name, dimensions, node count, cells per type (in MED
/// type order, as stored), groups with their sizes (mesh order), bounding
/// box. One item per line, values aligned, so that it diffs well.
pub fn mesh_info(mesh: &Mesh) -> String {
    let mut s = String::new();
    let mdim = mesh.cells.iter().map(|c| c.kind.dim()).max().unwrap_or(0);
    let _ = writeln!(s, "mesh            {}", mesh.name);
    let _ = writeln!(s, "space dimension {}", mesh.dim);
    let _ = writeln!(s, "mesh dimension  {mdim}");
    let _ = writeln!(s, "nodes           {}", mesh.nnodes());
    let _ = writeln!(s, "cells           {}", mesh.ncells());
    let mut types: Vec<CellType> = CellType::ALL.to_vec();
    types.sort_by_key(|t| t.med_code());
    for t in types {
        let n = mesh.cells.iter().filter(|c| c.kind == t).count();
        if n > 0 {
            let _ = writeln!(s, "  {:<9} {n:>8}", t.aster_name());
        }
    }
    for (title, groups, unit) in [
        ("cell groups", &mesh.cell_groups, "cells"),
        ("node groups", &mesh.node_groups, "nodes"),
    ] {
        let _ = writeln!(s, "{title:<15} {}", groups.len());
        let w = groups.keys().map(|k| k.len()).max().unwrap_or(0).max(9);
        for (g, members) in groups {
            let _ = writeln!(s, "  {g:<w$} {:>8} {unit}", members.len());
        }
    }
    if mesh.nnodes() > 0 {
        let (lo, hi) = mesh.bounding_box();
        let _ = writeln!(s, "bounding box");
        for (k, axis) in ["x", "y", "z"].iter().enumerate().take(mesh.dim.min(3)) {
            let _ = writeln!(s, "  {axis}  {} .. {}", fmt_num(lo[k]), fmt_num(hi[k]));
        }
    }
    s
}

/// Shortest exact representation: 2 stays "2", 0.1 stays "0.1".
fn fmt_num(v: f64) -> String {
    format!("{v}")
}
