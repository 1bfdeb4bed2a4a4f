//! Reference shape functions N(ξ) and their derivatives ∂N/∂ξ, one section
//! per cell family.
//!
//! Reference coordinates are code_aster's (`bibfor/elements/elrfno.F90`), so
//! that Gauss points, and later fields on Gauss points, sit where code_aster
//! puts them. Node order is the mesh's, i.e. MED order, which differs from
//! code_aster's internal order for every 3D cell: MED's 3D cells are the
//! mirror image of code_aster's reference elements (code_aster's MED reader
//! permutes them, `lrmtyp.F90`), and the quadratic ones also list the
//! mid-edge nodes in another order. The formulas below are written in the
//! internal order `L` (code_aster's vertex order, MED's mid-node order for
//! HEXA20/PENTA15); [`eval`] and [`reference_nodes`] map them to MED order
//! through [`crate::mesh::ops::med_to_aster`], the same permutation the mesh
//! generator uses, so a cell valid in MED has a positive Jacobian here.
//!
//! Two code_aster choices worth knowing because they look odd:
//! - TETRA4 has node 1 at (0,1,0), node 2 at (0,0,1), node 3 at the origin
//!   and node 4 at (1,0,0). The orientation (sign of the Jacobian) is the same
//!   as the textbook (0,0,0),(1,0,0),(0,1,0),(0,0,1) tetrahedron.
//! - Prisms (PENTA6/15) have their axis along ξ₁ ∈ [-1,1] and the triangle
//!   in (ξ₂, ξ₃): node 1 at (ξ₂,ξ₃) = (1,0), node 2 at (0,1), node 3 at (0,0).
//!
//! Coordinates not used by a cell of lower dimension are 0 and ignored.

use crate::mesh::CellType;

/// The largest number of nodes of a supported cell (HEXA20).
pub const MAX_NODES: usize = 20;

/// Shape functions and their reference derivatives at one point, stored on
/// the stack: element loops call this at every Gauss point of every cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeEval {
    nnodes: usize,
    n: [f64; MAX_NODES],
    dn: [[f64; 3]; MAX_NODES],
}

impl ShapeEval {
    /// N_i, one per node, in node order.
    pub fn n(&self) -> &[f64] {
        &self.n[..self.nnodes]
    }
    /// ∂N_i/∂ξ_k; k beyond the cell's dimension is 0.
    pub fn dn(&self) -> &[[f64; 3]] {
        &self.dn[..self.nnodes]
    }
    pub fn nnodes(&self) -> usize {
        self.nnodes
    }
}

/// Evaluates all shape functions of `cell` and their derivatives at `xi`,
/// in MED node order.
pub fn eval(cell: CellType, xi: [f64; 3]) -> ShapeEval {
    let raw = eval_internal(cell, xi);
    if cell.dim() < 3 {
        return raw;
    }
    let mut out = raw;
    for (&l, &m) in internal_to_aster(cell).iter().zip(aster_to_med(cell)) {
        out.n[m] = raw.n[l];
        out.dn[m] = raw.dn[l];
    }
    out
}

/// code_aster's index k -> index in the internal order `L` of this module
/// (identity except the mid-node blocks of HEXA20 and PENTA15).
fn internal_to_aster(cell: CellType) -> Vec<usize> {
    let mut p: Vec<usize> = (0..cell.nnodes()).collect();
    match cell {
        CellType::Hexa20 => {
            // aster 13-16 (verticals) are L 17-20; aster 17-20 (top) are L 13-16.
            for k in 0..4 {
                p[12 + k] = 16 + k;
                p[16 + k] = 12 + k;
            }
        }
        CellType::Penta15 => {
            for k in 0..3 {
                p[9 + k] = 12 + k;
                p[12 + k] = 9 + k;
            }
        }
        _ => {}
    }
    p
}

/// code_aster's index k -> MED index.
fn aster_to_med(cell: CellType) -> &'static [usize] {
    crate::mesh::ops::med_to_aster(cell)
}

fn eval_internal(cell: CellType, xi: [f64; 3]) -> ShapeEval {
    let mut out = ShapeEval {
        nnodes: cell.nnodes(),
        n: [0.0; MAX_NODES],
        dn: [[0.0; 3]; MAX_NODES],
    };
    let nodes = internal_nodes(cell);
    match cell {
        CellType::Poi1 => out.n[0] = 1.0,
        CellType::Seg2 | CellType::Quad4 | CellType::Hexa8 => {
            let d = cell.dim();
            for (i, a) in nodes.iter().enumerate() {
                tensor_linear(d, xi, *a, &mut out.n[i], &mut out.dn[i]);
            }
        }
        CellType::Seg3 => segment3(xi[0], &mut out),
        CellType::Quad8 | CellType::Hexa20 => {
            let d = cell.dim();
            for (i, a) in nodes.iter().enumerate() {
                serendipity(d, xi, *a, &mut out.n[i], &mut out.dn[i]);
            }
        }
        CellType::Tria3 => triangle(1, xi, &mut out),
        CellType::Tria6 => triangle(2, xi, &mut out),
        CellType::Tetra4 => tetra4(xi, &mut out),
        CellType::Tetra10 => tetra10(xi, &mut out),
        CellType::Penta6 => prism6(xi, &mut out),
        CellType::Penta15 => prism15(xi, &mut out),
    }
    out
}

/// Reference coordinates of the nodes, in MED node order (see module doc).
pub fn reference_nodes(cell: CellType) -> &'static [[f64; 3]] {
    use std::sync::OnceLock;
    static MED: OnceLock<Vec<Vec<[f64; 3]>>> = OnceLock::new();
    if cell.dim() < 3 {
        return internal_nodes(cell);
    }
    let all = MED.get_or_init(|| {
        CellType::ALL
            .iter()
            .map(|&c| {
                let int = internal_nodes(c);
                let mut med = int.to_vec();
                if c.dim() == 3 {
                    for (&l, &m) in internal_to_aster(c).iter().zip(aster_to_med(c)) {
                        med[m] = int[l];
                    }
                }
                med
            })
            .collect()
    });
    let i = CellType::ALL
        .iter()
        .position(|&c| c == cell)
        .expect("every cell type is in ALL");
    &all[i]
}

/// Reference coordinates in the internal order `L` of the formulas.
fn internal_nodes(cell: CellType) -> &'static [[f64; 3]] {
    match cell {
        CellType::Poi1 => &[[0.0; 3]],
        CellType::Seg2 => &SEG3_NODES[..2],
        CellType::Seg3 => &SEG3_NODES,
        CellType::Tria3 => &TRIA6_NODES[..3],
        CellType::Tria6 => &TRIA6_NODES,
        CellType::Quad4 => &QUAD8_NODES[..4],
        CellType::Quad8 => &QUAD8_NODES,
        CellType::Tetra4 => &TETRA10_NODES[..4],
        CellType::Tetra10 => &TETRA10_NODES,
        CellType::Penta6 => &PENTA15_NODES[..6],
        CellType::Penta15 => &PENTA15_NODES,
        CellType::Hexa8 => &HEXA20_NODES[..8],
        CellType::Hexa20 => &HEXA20_NODES,
    }
}

/// Measure of the reference cell (length, area or volume).
pub fn reference_measure(cell: CellType) -> f64 {
    match cell {
        CellType::Poi1 => 1.0,
        CellType::Seg2 | CellType::Seg3 => 2.0,
        CellType::Tria3 | CellType::Tria6 => 0.5,
        CellType::Quad4 | CellType::Quad8 => 4.0,
        CellType::Tetra4 | CellType::Tetra10 => 1.0 / 6.0,
        CellType::Penta6 | CellType::Penta15 => 1.0,
        CellType::Hexa8 | CellType::Hexa20 => 8.0,
    }
}

/// Permutation from MED node order to code_aster's internal order:
/// `aster[k] = med[med_to_aster(cell)[k]]`. Needed to compare per-node
/// values with code_aster listings.
pub fn med_to_aster(cell: CellType) -> Vec<usize> {
    aster_to_med(cell).to_vec()
}

// ---------------------------------------------------------------- segments

const SEG3_NODES: [[f64; 3]; 3] = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]];

fn segment3(x: f64, out: &mut ShapeEval) {
    out.n[0] = 0.5 * x * (x - 1.0);
    out.n[1] = 0.5 * x * (x + 1.0);
    out.n[2] = 1.0 - x * x;
    out.dn[0][0] = x - 0.5;
    out.dn[1][0] = x + 0.5;
    out.dn[2][0] = -2.0 * x;
}

// ------------------------------------------- quadrangles and hexahedra

const QUAD8_NODES: [[f64; 3]; 8] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, -1.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
];

const HEXA20_NODES: [[f64; 3]; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    // bottom edges 1-2, 2-3, 3-4, 4-1
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    // top edges 5-6, 6-7, 7-8, 8-5
    [0.0, -1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [-1.0, 0.0, 1.0],
    // vertical edges 1-5, 2-6, 3-7, 4-8
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// 1 + ξ_k a_k for k < d (1 beyond), on the stack.
fn factors(d: usize, xi: [f64; 3], a: [f64; 3]) -> [f64; 3] {
    let mut f = [1.0; 3];
    for (k, fk) in f.iter_mut().enumerate().take(d) {
        *fk = 1.0 + xi[k] * a[k];
    }
    f
}

/// Π_k (1 + ξ_k a_k) / 2^d: the multilinear Lagrange function of vertex a.
fn tensor_linear(d: usize, xi: [f64; 3], a: [f64; 3], n: &mut f64, dn: &mut [f64; 3]) {
    let f = factors(d, xi, a);
    let scale = 0.5f64.powi(d as i32);
    *n = scale * f.iter().product::<f64>();
    for j in 0..d {
        let others: f64 = (0..d).filter(|&k| k != j).map(|k| f[k]).product();
        dn[j] = scale * a[j] * others;
    }
}

/// Serendipity (QUAD8, HEXA20) function of node a: a vertex has all |a_k| = 1,
/// a mid-edge node has exactly one a_m = 0.
fn serendipity(d: usize, xi: [f64; 3], a: [f64; 3], n: &mut f64, dn: &mut [f64; 3]) {
    let f = factors(d, xi, a);
    match (0..d).find(|&k| a[k] == 0.0) {
        None => {
            // Π(1+ξa) (Σ ξa − (d−1)) / 2^d
            let scale = 0.5f64.powi(d as i32);
            let s: f64 = (0..d).map(|k| xi[k] * a[k]).sum::<f64>() - (d as f64 - 1.0);
            let prod: f64 = f.iter().product();
            *n = scale * prod * s;
            for j in 0..d {
                let others: f64 = (0..d).filter(|&k| k != j).map(|k| f[k]).product();
                dn[j] = scale * a[j] * others * (s + f[j]);
            }
        }
        Some(m) => {
            // (1 − ξ_m²) Π_{k≠m}(1+ξa) / 2^(d−1)
            let scale = 0.5f64.powi(d as i32 - 1);
            let bubble = 1.0 - xi[m] * xi[m];
            let prod: f64 = (0..d).filter(|&k| k != m).map(|k| f[k]).product();
            *n = scale * bubble * prod;
            for j in 0..d {
                dn[j] = if j == m {
                    -2.0 * xi[m] * scale * prod
                } else {
                    let others: f64 = (0..d).filter(|&k| k != j && k != m).map(|k| f[k]).product();
                    scale * bubble * a[j] * others
                };
            }
        }
    }
}

// ------------------------------------------------------------- triangles

const TRIA6_NODES: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.5, 0.0, 0.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.0],
];

/// Triangle in area coordinates L1 = 1−ξ−η (node 1 at the origin), L2 = ξ,
/// L3 = η; order 1 (TRIA3) or 2 (TRIA6, mid nodes on edges 1-2, 2-3, 3-1).
fn triangle(order: u8, xi: [f64; 3], out: &mut ShapeEval) {
    let l = [1.0 - xi[0] - xi[1], xi[0], xi[1]];
    let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
    if order == 1 {
        for i in 0..3 {
            out.n[i] = l[i];
            out.dn[i] = [dl[i][0], dl[i][1], 0.0];
        }
        return;
    }
    for i in 0..3 {
        out.n[i] = l[i] * (2.0 * l[i] - 1.0);
        let c = 4.0 * l[i] - 1.0;
        out.dn[i] = [c * dl[i][0], c * dl[i][1], 0.0];
    }
    for (m, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
        out.n[3 + m] = 4.0 * l[i] * l[j];
        let d = |k: usize| 4.0 * (dl[i][k] * l[j] + l[i] * dl[j][k]);
        out.dn[3 + m] = [d(0), d(1), 0.0];
    }
}

// ------------------------------------------------------------ tetrahedra

const TETRA10_NODES: [[f64; 3]; 10] = [
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    // mid-edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4 (code_aster's TE10)
    [0.0, 0.5, 0.5],
    [0.0, 0.0, 0.5],
    [0.0, 0.5, 0.0],
    [0.5, 0.5, 0.0],
    [0.5, 0.0, 0.5],
    [0.5, 0.0, 0.0],
];

/// The volume coordinates of code_aster's tetrahedron (L1 = ξ₂, L2 = ξ₃,
/// L3 = 1 − ξ₁ − ξ₂ − ξ₃, L4 = ξ₁) and their constant derivatives.
const TETRA_DL: [[f64; 3]; 4] = [
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [-1.0, -1.0, -1.0],
    [1.0, 0.0, 0.0],
];

/// Quadratic Lagrange tetrahedron: L(2L − 1) at the vertices, 4 Lᵢ Lⱼ at
/// the mid-edges.
fn tetra10(xi: [f64; 3], out: &mut ShapeEval) {
    let l = [xi[1], xi[2], 1.0 - xi[0] - xi[1] - xi[2], xi[0]];
    for i in 0..4 {
        out.n[i] = l[i] * (2.0 * l[i] - 1.0);
        let c = 4.0 * l[i] - 1.0;
        out.dn[i] = TETRA_DL[i].map(|d| c * d);
    }
    for (m, (i, j)) in [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
        .into_iter()
        .enumerate()
    {
        out.n[4 + m] = 4.0 * l[i] * l[j];
        for k in 0..3 {
            out.dn[4 + m][k] = 4.0 * (TETRA_DL[i][k] * l[j] + l[i] * TETRA_DL[j][k]);
        }
    }
}

fn tetra4(xi: [f64; 3], out: &mut ShapeEval) {
    out.n[0] = xi[1];
    out.n[1] = xi[2];
    out.n[2] = 1.0 - xi[0] - xi[1] - xi[2];
    out.n[3] = xi[0];
    out.dn[0] = [0.0, 1.0, 0.0];
    out.dn[1] = [0.0, 0.0, 1.0];
    out.dn[2] = [-1.0, -1.0, -1.0];
    out.dn[3] = [1.0, 0.0, 0.0];
}

// ---------------------------------------------------------------- prisms

const PENTA15_NODES: [[f64; 3]; 15] = [
    [-1.0, 1.0, 0.0],
    [-1.0, 0.0, 1.0],
    [-1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [1.0, 0.0, 1.0],
    [1.0, 0.0, 0.0],
    // bottom edges 1-2, 2-3, 3-1
    [-1.0, 0.5, 0.5],
    [-1.0, 0.0, 0.5],
    [-1.0, 0.5, 0.0],
    // top edges 4-5, 5-6, 6-4
    [1.0, 0.5, 0.5],
    [1.0, 0.0, 0.5],
    [1.0, 0.5, 0.0],
    // vertical edges 1-4, 2-5, 3-6
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, 0.0],
];

/// Area coordinates of the prism's triangle: L1 = ξ₂, L2 = ξ₃, L3 = 1−ξ₂−ξ₃,
/// with their (constant) derivatives in (ξ₁, ξ₂, ξ₃).
fn prism_area(xi: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    (
        [xi[1], xi[2], 1.0 - xi[1] - xi[2]],
        [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, -1.0]],
    )
}

fn prism6(xi: [f64; 3], out: &mut ShapeEval) {
    let (l, dl) = prism_area(xi);
    let x = xi[0];
    for i in 0..3 {
        for (node, side) in [(i, -1.0), (i + 3, 1.0)] {
            let h = 0.5 * (1.0 + side * x);
            out.n[node] = l[i] * h;
            out.dn[node] = [l[i] * 0.5 * side, dl[i][1] * h, dl[i][2] * h];
        }
    }
}

fn prism15(xi: [f64; 3], out: &mut ShapeEval) {
    let (l, dl) = prism_area(xi);
    let x = xi[0];
    // Vertex on side s = ∓1: ½ L (2L − 1)(1 + s x) − ½ L (1 − x²).
    for i in 0..3 {
        for (node, s) in [(i, -1.0), (i + 3, 1.0)] {
            let g = 1.0 + s * x;
            let b = 1.0 - x * x;
            out.n[node] = 0.5 * l[i] * (2.0 * l[i] - 1.0) * g - 0.5 * l[i] * b;
            let dndl = 0.5 * (4.0 * l[i] - 1.0) * g - 0.5 * b;
            out.dn[node] = [
                0.5 * l[i] * (2.0 * l[i] - 1.0) * s + l[i] * x,
                dndl * dl[i][1],
                dndl * dl[i][2],
            ];
        }
    }
    // Mid-edge of a triangle face: 2 L_i L_j (1 + s x).
    for (m, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
        for (node, s) in [(6 + m, -1.0), (9 + m, 1.0)] {
            let g = 1.0 + s * x;
            out.n[node] = 2.0 * l[i] * l[j] * g;
            out.dn[node] = [
                2.0 * l[i] * l[j] * s,
                2.0 * g * (dl[i][1] * l[j] + l[i] * dl[j][1]),
                2.0 * g * (dl[i][2] * l[j] + l[i] * dl[j][2]),
            ];
        }
    }
    // Vertical mid-edge: L_i (1 − x²).
    for i in 0..3 {
        let b = 1.0 - x * x;
        out.n[12 + i] = l[i] * b;
        out.dn[12 + i] = [-2.0 * x * l[i], dl[i][1] * b, dl[i][2] * b];
    }
}
