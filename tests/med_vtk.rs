//! vtk_permutation against VTK's own definition of its cells, written here
//! from the VTK documentation independently of the permutation tables:
//! corners 0..3 (or 0..2) form the base turning counter-clockwise seen
//! from the opposite face or apex, node k+4 (hexa) / k+3 (wedge) sits above
//! node k, and each mid-edge node of a quadratic cell is the middle of the
//! VTK edge it is listed for.

#[path = "med_common.rs"]
mod common;

use aster::medio::{vtk_cell_type, vtk_permutation};
use aster::mesh::CellType;
use common::med_cell;

type P = [f64; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: P, b: P) -> P {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn centroid(ps: &[P]) -> P {
    let n = ps.len() as f64;
    let mut c = [0.0; 3];
    for p in ps {
        for k in 0..3 {
            c[k] += p[k] / n;
        }
    }
    c
}
fn close(a: P, b: P) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
}

/// VTK edge lists of the quadratic cells (mid node = nvertices + k).
fn vtk_edges(t: CellType) -> Vec<(usize, usize)> {
    match t {
        CellType::Seg3 => vec![(0, 1)],
        CellType::Tria6 => vec![(0, 1), (1, 2), (2, 0)],
        CellType::Quad8 => vec![(0, 1), (1, 2), (2, 3), (3, 0)],
        // VTK_QUADRATIC_TETRA: base triangle, then the edges to the apex
        CellType::Tetra10 => vec![(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
        // VTK_QUADRATIC_WEDGE: bottom triangle, top triangle, verticals
        CellType::Penta15 => vec![
            (0, 1),
            (1, 2),
            (2, 0),
            (3, 4),
            (4, 5),
            (5, 3),
            (0, 3),
            (1, 4),
            (2, 5),
        ],
        // VTK_QUADRATIC_HEXAHEDRON: bottom, top, verticals
        CellType::Hexa20 => vec![
            (0, 1),
            (1, 2),
            (2, 3),
            (3, 0),
            (4, 5),
            (5, 6),
            (6, 7),
            (7, 4),
            (0, 4),
            (1, 5),
            (2, 6),
            (3, 7),
        ],
        _ => vec![],
    }
}

/// The cell in VTK order, from the MED reference cell and the permutation.
fn to_vtk(t: CellType) -> Vec<P> {
    let med = med_cell(t, 0.0);
    let p = vtk_permutation(t);
    assert_eq!(p.len(), t.nnodes(), "{t:?}");
    let mut seen = vec![false; p.len()];
    for &i in p {
        assert!(!seen[i], "{t:?}: MED node {i} used twice");
        seen[i] = true;
    }
    p.iter().map(|&i| med[i]).collect()
}

/// Base of a 3D VTK cell turns counter-clockwise seen from the rest of the
/// cell: its right-hand normal points to the opposite face or apex.
fn check_base_orientation(t: CellType, v: &[P], base: &[usize], rest: &[usize]) {
    let b: Vec<P> = base.iter().map(|&i| v[i]).collect();
    let r: Vec<P> = rest.iter().map(|&i| v[i]).collect();
    let c = centroid(&b);
    let up = sub(centroid(&r), c);
    // every consecutive pair of base corners turns the same way
    for k in 0..b.len() {
        let n = cross(sub(b[k], c), sub(b[(k + 1) % b.len()], c));
        assert!(dot(n, up) > 0.0, "{t:?}: base corner {k} turns clockwise");
    }
}

fn check_vtk_cell(t: CellType) {
    let v = to_vtk(t);
    match t.linear() {
        CellType::Tetra4 => check_base_orientation(t, &v, &[0, 1, 2], &[3]),
        CellType::Penta6 => {
            check_base_orientation(t, &v, &[0, 1, 2], &[3, 4, 5]);
            for k in 0..3 {
                // node k+3 straight above node k (the reference prism is
                // a right prism along z)
                let d = sub(v[k + 3], v[k]);
                assert!(
                    d[0] == 0.0 && d[1] == 0.0 && d[2] > 0.0,
                    "{t:?} vertical {k}"
                );
            }
        }
        CellType::Hexa8 => {
            check_base_orientation(t, &v, &[0, 1, 2, 3], &[4, 5, 6, 7]);
            for k in 0..4 {
                let d = sub(v[k + 4], v[k]);
                assert!(
                    d[0] == 0.0 && d[1] == 0.0 && d[2] > 0.0,
                    "{t:?} vertical {k}"
                );
            }
        }
        CellType::Tria3 | CellType::Quad4 => {
            // 2D: counter-clockwise in the xy plane, same as MED
            let nv = t.nvertices();
            let c = centroid(&v[..nv]);
            for k in 0..nv {
                let n = cross(sub(v[k], c), sub(v[(k + 1) % nv], c));
                assert!(n[2] > 0.0, "{t:?}");
            }
        }
        _ => {}
    }
    let nv = t.nvertices();
    for (k, (a, b)) in vtk_edges(t).into_iter().enumerate() {
        let m = [
            (v[a][0] + v[b][0]) / 2.0,
            (v[a][1] + v[b][1]) / 2.0,
            (v[a][2] + v[b][2]) / 2.0,
        ];
        assert!(
            close(v[nv + k], m),
            "{t:?}: VTK mid node {} not on edge {a}-{b}",
            nv + k
        );
    }
}

#[test]
fn every_type_matches_vtk_conventions() {
    for t in CellType::ALL {
        check_vtk_cell(t);
    }
}

#[test]
fn low_dimension_cells_are_not_permuted() {
    for t in CellType::ALL.into_iter().filter(|t| t.dim() < 3) {
        let p = vtk_permutation(t);
        assert!(p.iter().enumerate().all(|(i, &j)| i == j), "{t:?}");
    }
}

#[test]
fn the_med_cells_themselves_are_not_vtk_valid() {
    // guards the test above: without the permutation the MED-ordered
    // reference cells have the base turning the wrong way for VTK
    for t in [CellType::Tetra4, CellType::Penta6, CellType::Hexa8] {
        let v = med_cell(t, 0.0);
        let (base, rest): (&[usize], &[usize]) = match t {
            CellType::Tetra4 => (&[0, 1, 2], &[3]),
            CellType::Penta6 => (&[0, 1, 2], &[3, 4, 5]),
            _ => (&[0, 1, 2, 3], &[4, 5, 6, 7]),
        };
        let b: Vec<P> = base.iter().map(|&i| v[i]).collect();
        let r: Vec<P> = rest.iter().map(|&i| v[i]).collect();
        let c = centroid(&b);
        let n = cross(sub(b[0], c), sub(b[1], c));
        assert!(dot(n, sub(centroid(&r), c)) < 0.0, "{t:?}");
    }
}

#[test]
fn vtk_type_ids() {
    let ids: Vec<u8> = CellType::ALL.into_iter().map(vtk_cell_type).collect();
    // POI1 SEG2 SEG3 TRIA3 TRIA6 QUAD4 QUAD8 TETRA4 TETRA10 PENTA6 PENTA15 HEXA8 HEXA20
    assert_eq!(ids, [1, 3, 21, 5, 22, 9, 23, 10, 24, 13, 26, 12, 25]);
}
