//! Shared by the med_* tests: reference cells in MED node order and a mesh
//! holding every supported cell type. (Compiled as its own empty test
//! crate too, hence the allow.)
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::PathBuf;

use aster::mesh::{Cell, CellType, Mesh};
use indexmap::IndexMap;

/// MED edge tables of the quadratic cells: mid node `nv + k` sits on edge k.
pub fn med_edges(t: CellType) -> &'static [(usize, usize)] {
    t.mid_edges()
}

/// Corner coordinates of a reference cell of type `t`, MED order, shifted
/// by `x0` along x. MED turns the first face of a 3D cell clockwise seen
/// from the opposite face (or apex); 2D cells are counter-clockwise in xy.
pub fn med_corners(t: CellType, x0: f64) -> Vec<[f64; 3]> {
    let p = |x: f64, y: f64, z: f64| [x0 + x, y, z];
    match t.linear() {
        CellType::Poi1 => vec![p(0.0, 0.0, 0.0)],
        CellType::Seg2 => vec![p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0)],
        CellType::Tria3 => vec![p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)],
        CellType::Quad4 => vec![
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(1.0, 1.0, 0.0),
            p(0.0, 1.0, 0.0),
        ],
        CellType::Tetra4 => vec![
            p(0.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(0.0, 0.0, 1.0),
        ],
        CellType::Penta6 => {
            let base = [p(0.0, 0.0, 0.0), p(0.0, 1.0, 0.0), p(1.0, 0.0, 0.0)];
            let mut v = base.to_vec();
            v.extend(base.iter().map(|q| [q[0], q[1], 1.0]));
            v
        }
        CellType::Hexa8 => {
            let base = [
                p(0.0, 0.0, 0.0),
                p(0.0, 1.0, 0.0),
                p(1.0, 1.0, 0.0),
                p(1.0, 0.0, 0.0),
            ];
            let mut v = base.to_vec();
            v.extend(base.iter().map(|q| [q[0], q[1], 1.0]));
            v
        }
        _ => unreachable!("linear() returns a linear type"),
    }
}

/// Full reference cell (corners then mid-edge nodes), MED order.
pub fn med_cell(t: CellType, x0: f64) -> Vec<[f64; 3]> {
    let mut v = med_corners(t, x0);
    for &(a, b) in med_edges(t) {
        let (pa, pb) = (v[a], v[b]);
        v.push([
            (pa[0] + pb[0]) / 2.0,
            (pa[1] + pb[1]) / 2.0,
            (pa[2] + pb[2]) / 2.0,
        ]);
    }
    v
}

/// Cell types in increasing MED type code: the order cells are stored in.
pub fn types_in_med_order() -> Vec<CellType> {
    let mut t = CellType::ALL.to_vec();
    t.sort_by_key(|t| t.med_code());
    t
}

/// A 3D mesh with one cell of each of the 12 types side by side along x
/// (shared nodes merged), cells sorted by MED type code, and groups in
/// alphabetical order: overlapping groups, a group per dimension, an empty
/// cell group and an empty node group.
pub fn all_types_mesh() -> Mesh {
    let mut coords: Vec<[f64; 3]> = Vec::new();
    let mut index: HashMap<[i64; 3], usize> = HashMap::new();
    let mut cells = Vec::new();
    for (k, t) in types_in_med_order().into_iter().enumerate() {
        let nodes = med_cell(t, 2.0 * k as f64)
            .into_iter()
            .map(|q| {
                let key = q.map(|c| (c * 1000.0).round() as i64);
                *index.entry(key).or_insert_with(|| {
                    coords.push(q);
                    coords.len() - 1
                })
            })
            .collect();
        cells.push(Cell { kind: t, nodes });
    }
    let by_dim = |d: usize| -> Vec<usize> {
        (0..cells.len())
            .filter(|&c| cells[c].kind.dim() == d)
            .collect()
    };
    let mut cell_groups = IndexMap::new();
    cell_groups.insert("EDGES".to_string(), by_dim(1));
    cell_groups.insert("EMPTY".to_string(), vec![]);
    cell_groups.insert("FACES".to_string(), by_dim(2));
    cell_groups.insert("POINT".to_string(), by_dim(0));
    cell_groups.insert(
        "QUADRATIC".to_string(),
        (0..cells.len())
            .filter(|&c| cells[c].kind.is_quadratic())
            .collect(),
    );
    cell_groups.insert("VOLUMES".to_string(), by_dim(3));
    let n = coords.len();
    let mut node_groups = IndexMap::new();
    node_groups.insert("NEMPTY".to_string(), vec![]);
    node_groups.insert("NFIRST".to_string(), vec![0]);
    node_groups.insert(
        "NZ0".to_string(),
        (0..n).filter(|&i| coords[i][2] == 0.0).collect(),
    );
    node_groups.insert(
        "NZ1".to_string(),
        (0..n).filter(|&i| coords[i][2] == 1.0).collect(),
    );
    Mesh {
        name: "ALLTYPES".to_string(),
        dim: 3,
        coords,
        cells,
        cell_groups,
        node_groups,
    }
}

/// A fresh path in Cargo's per-test scratch directory.
pub fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("med_tests");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let p = dir.join(name);
    let _ = std::fs::remove_file(&p);
    p
}
