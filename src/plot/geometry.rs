//! Cells as polygons in the drawing plane.
//!
//! A plane or axisymmetric mesh is drawn as it is: each 2D cell is one
//! polygon. A 3D mesh is drawn by its skin (the faces of volume cells that
//! belong to one cell only), projected on a coordinate plane and painted
//! from the farthest face to the nearest, so the picture shows the outline
//! of the body as seen from that side. For the quarter bar seen in xz from
//! the -y side the nearest faces are the symmetry plane y = 0: the picture
//! is the bar's meridian section, the same as the axisymmetric modelling.
//! Quadratic cells keep their mid-edge nodes in the polygon, so a curved
//! edge is drawn as two segments.

use std::collections::HashMap;

use crate::mesh::{CellType, Mesh};

/// The coordinate plane of a 3D picture: (horizontal, vertical) axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plane {
    Xy,
    Xz,
    Yz,
}

impl Plane {
    pub fn parse(s: &str) -> Option<Plane> {
        match s.to_ascii_lowercase().as_str() {
            "xy" => Some(Plane::Xy),
            "xz" => Some(Plane::Xz),
            "yz" => Some(Plane::Yz),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Plane::Xy => "xy",
            Plane::Xz => "xz",
            Plane::Yz => "yz",
        }
    }
    /// Indices of the horizontal, vertical and depth axes, and the sign
    /// that makes `sign * p[depth]` grow towards the viewer (the viewer
    /// stands on the side of horizontal x vertical, right-handed).
    fn axes(self) -> (usize, usize, usize, f64) {
        match self {
            Plane::Xy => (0, 1, 2, 1.0),
            Plane::Xz => (0, 2, 1, -1.0),
            Plane::Yz => (1, 2, 0, 1.0),
        }
    }
    /// Axis names, for labels.
    pub fn axis_names(self) -> (&'static str, &'static str) {
        match self {
            Plane::Xy => ("x", "y"),
            Plane::Xz => ("x", "z"),
            Plane::Yz => ("y", "z"),
        }
    }
    /// A point projected on the plane.
    pub fn project(self, p: [f64; 3]) -> [f64; 2] {
        let (h, v, _, _) = self.axes();
        [p[h], p[v]]
    }
    /// Distance towards the viewer (larger = nearer).
    pub fn nearness(self, p: [f64; 3]) -> f64 {
        let (_, _, d, s) = self.axes();
        s * p[d]
    }
}

/// A polygon to paint: the nodes around it, in order, and the cell whose
/// value colours it.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    pub cell: usize,
    pub nodes: Vec<usize>,
}

/// Vertex cycles of the faces of a volume cell (indices into its vertices).
fn volume_faces(t: CellType) -> &'static [&'static [usize]] {
    match t.linear() {
        CellType::Tetra4 => &[&[0, 1, 2], &[0, 1, 3], &[1, 2, 3], &[2, 0, 3]],
        CellType::Penta6 => &[
            &[0, 1, 2],
            &[3, 4, 5],
            &[0, 1, 4, 3],
            &[1, 2, 5, 4],
            &[2, 0, 3, 5],
        ],
        CellType::Hexa8 => &[
            &[0, 1, 2, 3],
            &[4, 5, 6, 7],
            &[0, 1, 5, 4],
            &[1, 2, 6, 5],
            &[2, 3, 7, 6],
            &[3, 0, 4, 7],
        ],
        _ => &[],
    }
}

/// The polygon through vertex cycle `cycle` of a cell, with the mid-edge
/// node of each edge inserted when the cell is quadratic.
fn polygon(t: CellType, nodes: &[usize], cycle: &[usize]) -> Vec<usize> {
    let mids = t.mid_edges();
    let mut out = Vec::with_capacity(2 * cycle.len());
    for (k, &a) in cycle.iter().enumerate() {
        let b = cycle[(k + 1) % cycle.len()];
        out.push(nodes[a]);
        if let Some(m) = mids
            .iter()
            .position(|&(p, q)| (p, q) == (a, b) || (p, q) == (b, a))
        {
            out.push(nodes[t.nvertices() + m]);
        }
    }
    out
}

/// True when the mesh has volume cells (then it is drawn by its skin).
pub fn is_volume(mesh: &Mesh) -> bool {
    mesh.cells.iter().any(|c| c.kind.dim() == 3)
}

/// The polygons of a mesh: its 2D cells, or the skin of its volume cells.
/// Lines and points (boundary cells of a 2D mesh, skin cells of a 3D one)
/// are not drawn: they would only repeat edges of the cells they border.
pub fn faces(mesh: &Mesh) -> Vec<Face> {
    if !is_volume(mesh) {
        return mesh
            .cells
            .iter()
            .enumerate()
            .filter(|(_, c)| c.kind.dim() == 2)
            .map(|(i, c)| {
                let cycle: Vec<usize> = (0..c.kind.nvertices()).collect();
                Face {
                    cell: i,
                    nodes: polygon(c.kind, &c.nodes, &cycle),
                }
            })
            .collect();
    }
    // A face belongs to the skin when no other volume cell has the same
    // vertices.
    let mut seen: HashMap<Vec<usize>, (usize, Face)> = HashMap::new();
    let mut order: Vec<Vec<usize>> = Vec::new();
    for (i, c) in mesh.cells.iter().enumerate() {
        if c.kind.dim() != 3 {
            continue;
        }
        for cycle in volume_faces(c.kind) {
            let mut key: Vec<usize> = cycle.iter().map(|&k| c.nodes[k]).collect();
            key.sort_unstable();
            let face = Face {
                cell: i,
                nodes: polygon(c.kind, &c.nodes, cycle),
            };
            match seen.get_mut(&key) {
                Some(entry) => entry.0 += 1,
                None => {
                    order.push(key.clone());
                    seen.insert(key, (1, face));
                }
            }
        }
    }
    order
        .into_iter()
        .filter_map(|k| {
            let (n, f) = seen.remove(&k)?;
            (n == 1).then_some(f)
        })
        .collect()
}

/// Sorts faces from the farthest to the nearest along the plane's normal
/// (painter's order), by the nearness of their centroid in `coords`.
pub fn painter_order(faces: &mut [Face], coords: &[[f64; 3]], plane: Plane) {
    let key = |f: &Face| {
        f.nodes
            .iter()
            .map(|&n| plane.nearness(coords[n]))
            .sum::<f64>()
            / f.nodes.len() as f64
    };
    faces.sort_by(|a, b| key(a).total_cmp(&key(b)));
}

/// Node coordinates moved by `scale` times the displacement `u` (node-major,
/// `ncomp` values per node, components in `names` order: DX, DY, DZ are
/// used, others ignored).
pub fn deformed(coords: &[[f64; 3]], u: &[f64], names: &[String], scale: f64) -> Vec<[f64; 3]> {
    let nc = names.len();
    let axis: Vec<Option<usize>> = names
        .iter()
        .map(|n| match n.trim().to_ascii_uppercase().as_str() {
            "DX" => Some(0),
            "DY" => Some(1),
            "DZ" => Some(2),
            _ => None,
        })
        .collect();
    coords
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut q = *p;
            for (k, a) in axis.iter().enumerate() {
                if let Some(a) = a {
                    let d = u[i * nc + k];
                    if d.is_finite() {
                        q[*a] += scale * d;
                    }
                }
            }
            q
        })
        .collect()
}
