//! Mesh builders and materials shared by the element tests. Meshes are
//! built in a parameter space (grid coordinates, or (r, θ, z) for rings)
//! from vertex lists; quadratic mid nodes sit at parameter midpoints, then
//! every node is mapped to physical space. Nodes are shared through their
//! parameter coordinates, so neighbouring cells are conforming.
#![allow(dead_code, clippy::needless_range_loop)]

use std::collections::HashMap;

use aster::law::simo_miehe::SimoMiehe;
use aster::law::{EcroLineParams, ElasParams};
use aster::mesh::shape::{eval, reference_nodes};
use aster::mesh::CellType;
use nalgebra::Matrix3;

pub const E: f64 = 117_000.0;
pub const NU: f64 = 0.35;

pub fn elas_params() -> ElasParams {
    ElasParams::new(E, NU, Some(8.93e-9)).unwrap()
}

/// Copper of the Taylor bar: SY = 400, E_T = 100.
pub fn copper_ecro() -> EcroLineParams {
    EcroLineParams::new(&elas_params(), 400.0, 100.0).unwrap()
}

/// A low yield stress (SY = 1) so that every point of a test step yields.
pub fn soft_ecro() -> EcroLineParams {
    EcroLineParams::new(&elas_params(), 1.0, 2_000.0).unwrap()
}

/// A yield stress no test reaches: SIMO_MIEHE stays elastic.
pub fn hard_ecro() -> EcroLineParams {
    EcroLineParams::new(&elas_params(), 1e12, 100.0).unwrap()
}

pub fn simo(ecro: EcroLineParams) -> SimoMiehe {
    SimoMiehe::new(elas_params(), ecro)
}

pub fn linear_of(cell: CellType) -> CellType {
    match cell {
        CellType::Hexa20 => CellType::Hexa8,
        CellType::Penta15 => CellType::Penta6,
        CellType::Quad8 => CellType::Quad4,
        CellType::Tria6 => CellType::Tria3,
        CellType::Tetra10 => CellType::Tetra4,
        c => c,
    }
}

/// Jacobian determinant of the affine/multilinear vertex map at the
/// reference centroid (2D cells use the first two coordinates).
pub fn vertex_jacobian(cell: CellType, verts: &[[f64; 3]]) -> f64 {
    let lin = linear_of(cell);
    let nv = lin.nnodes();
    let mut c = [0.0; 3];
    for x in reference_nodes(lin) {
        for k in 0..3 {
            c[k] += x[k] / nv as f64;
        }
    }
    let s = eval(lin, c);
    let mut j = Matrix3::<f64>::zeros();
    for a in 0..nv {
        for k in 0..3 {
            for l in 0..3 {
                j[(k, l)] += verts[a][k] * s.dn()[a][l];
            }
        }
    }
    if lin.dim() == 2 {
        j[(0, 0)] * j[(1, 1)] - j[(0, 1)] * j[(1, 0)]
    } else {
        j.determinant()
    }
}

/// Reorders vertices so that the cell has a positive Jacobian.
pub fn orient(cell: CellType, mut verts: Vec<[f64; 3]>) -> Vec<[f64; 3]> {
    if vertex_jacobian(cell, &verts) < 0.0 {
        match linear_of(cell) {
            CellType::Hexa8 => {
                verts.swap(1, 3);
                verts.swap(5, 7);
            }
            CellType::Penta6 => {
                verts.swap(0, 1);
                verts.swap(3, 4);
            }
            CellType::Tetra4 => verts.swap(0, 1),
            CellType::Quad4 => verts.swap(1, 3),
            CellType::Tria3 => verts.swap(1, 2),
            c => panic!("no orientation rule for {c:?}"),
        }
    }
    assert!(vertex_jacobian(cell, &verts) > 0.0);
    verts
}

/// All node positions (MED order) of a cell given its vertices: each mid
/// node is the midpoint of the two vertices whose reference midpoint it
/// is.
pub fn complete(cell: CellType, verts: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let refs = reference_nodes(cell);
    let nv = cell.nvertices();
    let mut out: Vec<[f64; 3]> = verts[..nv].to_vec();
    for m in nv..cell.nnodes() {
        let mut found = None;
        for p in 0..nv {
            for q in p + 1..nv {
                if (0..3).all(|k| (0.5 * (refs[p][k] + refs[q][k]) - refs[m][k]).abs() < 1e-12) {
                    found = Some((p, q));
                }
            }
        }
        let (p, q) = found.expect("mid node is an edge midpoint");
        out.push(std::array::from_fn(|k| 0.5 * (verts[p][k] + verts[q][k])));
    }
    out
}

/// The vertices of a reference cell mapped by ξ ↦ (ξ+1)/2 (HEXA) or as is.
pub fn unit_vertices(cell: CellType) -> Vec<[f64; 3]> {
    let lin = linear_of(cell);
    reference_nodes(lin)
        .iter()
        .map(|x| match lin {
            CellType::Hexa8 => x.map(|v| 0.5 * (v + 1.0)),
            _ => *x,
        })
        .collect()
}

/// Subcells of `cell` type filling the unit cube at `o`: 1 hexahedron,
/// 2 prisms (axis along z) or 6 Kuhn tetrahedra.
pub fn fill_cube(cell: CellType, o: [f64; 3]) -> Vec<Vec<[f64; 3]>> {
    let at = |v: [f64; 3]| [o[0] + v[0], o[1] + v[1], o[2] + v[2]];
    let out: Vec<Vec<[f64; 3]>> = match linear_of(cell) {
        CellType::Hexa8 => vec![unit_vertices(CellType::Hexa8)],
        CellType::Penta6 => {
            let tris = [
                [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
                [[0.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            ];
            tris.iter()
                .map(|t| {
                    let mut v: Vec<[f64; 3]> = t.iter().map(|p| [p[0], p[1], 0.0]).collect();
                    v.extend(t.iter().map(|p| [p[0], p[1], 1.0]));
                    v
                })
                .collect()
        }
        CellType::Tetra4 => {
            let perms = [
                [0, 1, 2],
                [0, 2, 1],
                [1, 0, 2],
                [1, 2, 0],
                [2, 0, 1],
                [2, 1, 0],
            ];
            perms
                .iter()
                .map(|p| {
                    let mut v = vec![[0.0; 3]];
                    let mut c = [0.0; 3];
                    for &k in p {
                        c[k] = 1.0;
                        v.push(c);
                    }
                    v
                })
                .collect()
        }
        c => panic!("fill_cube: {c:?}"),
    };
    out.into_iter()
        .map(|v| orient(cell, v.into_iter().map(at).collect()))
        .collect()
}

/// A mesh: node coordinates and cells (type, node indices).
#[derive(Debug, Clone)]
pub struct TestMesh {
    pub nodes: Vec<[f64; 3]>,
    /// Parameter coordinates of each node.
    pub params: Vec<[f64; 3]>,
    pub cells: Vec<(CellType, Vec<usize>)>,
}

impl TestMesh {
    pub fn cell_coords(&self, c: usize) -> Vec<[f64; 3]> {
        self.cells[c].1.iter().map(|&n| self.nodes[n]).collect()
    }
    /// The values of a nodal field (d per node) on cell c.
    pub fn gather(&self, c: usize, field: &[f64], d: usize) -> Vec<f64> {
        let mut out = Vec::new();
        for &n in &self.cells[c].1 {
            out.extend_from_slice(&field[n * d..n * d + d]);
        }
        out
    }
    pub fn scatter_add(&self, c: usize, local: &[f64], d: usize, field: &mut [f64]) {
        for (k, &n) in self.cells[c].1.iter().enumerate() {
            for i in 0..d {
                field[n * d + i] += local[k * d + i];
            }
        }
    }
}

/// Builds a conforming mesh from cells given by their vertices in
/// parameter space, mapping every node with `map`.
pub fn build(
    cell: CellType,
    vertex_lists: &[Vec<[f64; 3]>],
    map: impl Fn([f64; 3]) -> [f64; 3],
) -> TestMesh {
    let mut index: HashMap<[i64; 3], usize> = HashMap::new();
    let mut mesh = TestMesh {
        nodes: Vec::new(),
        params: Vec::new(),
        cells: Vec::new(),
    };
    for verts in vertex_lists {
        let mut ids = Vec::new();
        for p in complete(cell, verts) {
            let key = p.map(|v| (v * 1e6).round() as i64);
            let id = *index.entry(key).or_insert_with(|| {
                mesh.nodes.push(map(p));
                mesh.params.push(p);
                mesh.nodes.len() - 1
            });
            ids.push(id);
        }
        mesh.cells.push((cell, ids));
    }
    mesh
}

/// A 2×2×2 block of cubes on [0,2]³ filled with `cell`, every node strictly
/// inside moved by a deterministic pseudo-random offset of size `amp`.
pub fn distorted_patch(cell: CellType, amp: f64) -> TestMesh {
    let mut lists = Vec::new();
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                lists.extend(fill_cube(cell, [i as f64, j as f64, k as f64]));
            }
        }
    }
    build(cell, &lists, |p| {
        if p.iter().all(|&v| v > 1e-9 && v < 2.0 - 1e-9) {
            let s = 3.1 * p[0] + 7.7 * p[1] + 13.3 * p[2];
            [
                p[0] + amp * (s * 1.7).sin(),
                p[1] + amp * (s * 2.3 + 1.0).sin(),
                p[2] + amp * (s * 0.9 + 2.0).sin(),
            ]
        } else {
            p
        }
    })
}

/// One cell of each type, distorted (curved for quadratic cells), for
/// derivative checks; 2D cells sit at r ∈ [1, 2].
pub fn distorted_cell(cell: CellType) -> Vec<[f64; 3]> {
    let verts = if cell.dim() == 2 {
        let v: Vec<[f64; 3]> = match linear_of(cell) {
            CellType::Quad4 => vec![
                [1.0, 0.0, 0.0],
                [2.1, 0.1, 0.0],
                [2.0, 1.2, 0.0],
                [0.9, 1.0, 0.0],
            ],
            _ => vec![[1.0, 0.0, 0.0], [2.1, 0.2, 0.0], [1.2, 1.1, 0.0]],
        };
        orient(cell, v)
    } else {
        fill_cube(cell, [0.0; 3]).remove(0)
    };
    complete(cell, &verts)
        .into_iter()
        .enumerate()
        .map(|(k, p)| {
            let t = k as f64;
            if cell.dim() == 2 {
                [
                    p[0] + 0.03 * (1.3 * t).sin() + 0.05 * p[1] * p[1],
                    p[1] + 0.03 * (2.1 * t).cos(),
                    0.0,
                ]
            } else {
                [
                    p[0] + 0.04 * (1.3 * t).sin() + 0.1 * p[1] * p[2],
                    p[1] + 0.04 * (2.1 * t).cos() - 0.05 * p[0],
                    p[2] + 0.04 * (0.7 * t + 1.0).sin(),
                ]
            }
        })
        .collect()
}
