//! The mesh: nodes, cells and named groups, in one internal convention.
//!
//! Node order inside a cell follows MED everywhere in
//! the engine; readers and writers of other formats convert at the border.
//! Indices are 0-based internally; MED files are 1-based.

use indexmap::IndexMap;

/// Cell types supported, named as code_aster names them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellType {
    Poi1,
    Seg2,
    Seg3,
    Tria3,
    Tria6,
    Quad4,
    Quad8,
    Tetra4,
    Tetra10,
    Penta6,
    Penta15,
    Hexa8,
    Hexa20,
}

impl CellType {
    pub const ALL: [CellType; 13] = [
        CellType::Poi1,
        CellType::Seg2,
        CellType::Seg3,
        CellType::Tria3,
        CellType::Tria6,
        CellType::Quad4,
        CellType::Quad8,
        CellType::Tetra4,
        CellType::Tetra10,
        CellType::Penta6,
        CellType::Penta15,
        CellType::Hexa8,
        CellType::Hexa20,
    ];

    /// Number of nodes.
    pub fn nnodes(self) -> usize {
        match self {
            CellType::Poi1 => 1,
            CellType::Seg2 => 2,
            CellType::Seg3 => 3,
            CellType::Tria3 => 3,
            CellType::Tria6 => 6,
            CellType::Quad4 => 4,
            CellType::Quad8 => 8,
            CellType::Tetra4 => 4,
            CellType::Tetra10 => 10,
            CellType::Penta6 => 6,
            CellType::Penta15 => 15,
            CellType::Hexa8 => 8,
            CellType::Hexa20 => 20,
        }
    }

    /// Number of vertex (corner) nodes; they come first in MED order.
    pub fn nvertices(self) -> usize {
        match self {
            CellType::Seg3 => 2,
            CellType::Tria6 => 3,
            CellType::Quad8 => 4,
            CellType::Tetra10 => 4,
            CellType::Penta15 => 6,
            CellType::Hexa20 => 8,
            t => t.nnodes(),
        }
    }

    /// Topological dimension.
    pub fn dim(self) -> usize {
        match self {
            CellType::Poi1 => 0,
            CellType::Seg2 | CellType::Seg3 => 1,
            CellType::Tria3 | CellType::Tria6 | CellType::Quad4 | CellType::Quad8 => 2,
            _ => 3,
        }
    }

    pub fn is_quadratic(self) -> bool {
        self.nvertices() != self.nnodes()
    }

    /// The edges carrying the mid-nodes of a quadratic cell, in MED order:
    /// mid-node `nvertices() + k` sits on the edge between the two vertices
    /// of entry k. Empty for linear cells.
    pub fn mid_edges(self) -> &'static [(usize, usize)] {
        const QUAD: [(usize, usize); 4] = [(0, 1), (1, 2), (2, 3), (3, 0)];
        const PENTA: [(usize, usize); 9] = [
            (0, 1),
            (1, 2),
            (2, 0),
            (3, 4),
            (4, 5),
            (5, 3),
            (0, 3),
            (1, 4),
            (2, 5),
        ];
        const HEXA: [(usize, usize); 12] = [
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
        ];
        match self {
            CellType::Seg3 => &[(0, 1)],
            CellType::Tria6 => &[(0, 1), (1, 2), (2, 0)],
            CellType::Quad8 => &QUAD,
            CellType::Tetra10 => &[(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
            CellType::Penta15 => &PENTA,
            CellType::Hexa20 => &HEXA,
            _ => &[],
        }
    }

    /// The linear cell with the same vertices (QUAD_LINE).
    pub fn linear(self) -> CellType {
        match self {
            CellType::Seg3 => CellType::Seg2,
            CellType::Tria6 => CellType::Tria3,
            CellType::Quad8 => CellType::Quad4,
            CellType::Tetra10 => CellType::Tetra4,
            CellType::Penta15 => CellType::Penta6,
            CellType::Hexa20 => CellType::Hexa8,
            t => t,
        }
    }

    /// The quadratic cell CREA_MAILLAGE LINE_QUAD makes of a linear one
    /// (serendipity: QUAD4 gives QUAD8, HEXA8 gives HEXA20); `None` for a
    /// cell that is already quadratic or has no edge.
    pub fn quadratic(self) -> Option<CellType> {
        match self {
            CellType::Seg2 => Some(CellType::Seg3),
            CellType::Tria3 => Some(CellType::Tria6),
            CellType::Quad4 => Some(CellType::Quad8),
            CellType::Tetra4 => Some(CellType::Tetra10),
            CellType::Penta6 => Some(CellType::Penta15),
            CellType::Hexa8 => Some(CellType::Hexa20),
            _ => None,
        }
    }

    /// code_aster's name (QUAD8, HEXA20, ...).
    pub fn aster_name(self) -> &'static str {
        match self {
            CellType::Poi1 => "POI1",
            CellType::Seg2 => "SEG2",
            CellType::Seg3 => "SEG3",
            CellType::Tria3 => "TRIA3",
            CellType::Tria6 => "TRIA6",
            CellType::Quad4 => "QUAD4",
            CellType::Quad8 => "QUAD8",
            CellType::Tetra4 => "TETRA4",
            CellType::Tetra10 => "TETRA10",
            CellType::Penta6 => "PENTA6",
            CellType::Penta15 => "PENTA15",
            CellType::Hexa8 => "HEXA8",
            CellType::Hexa20 => "HEXA20",
        }
    }

    /// MED's three-letter name (QU8, HE20 is "H20", ...).
    pub fn med_name(self) -> &'static str {
        match self {
            CellType::Poi1 => "PO1",
            CellType::Seg2 => "SE2",
            CellType::Seg3 => "SE3",
            CellType::Tria3 => "TR3",
            CellType::Tria6 => "TR6",
            CellType::Quad4 => "QU4",
            CellType::Quad8 => "QU8",
            CellType::Tetra4 => "TE4",
            CellType::Tetra10 => "T10",
            CellType::Penta6 => "PE6",
            CellType::Penta15 => "P15",
            CellType::Hexa8 => "HE8",
            CellType::Hexa20 => "H20",
        }
    }

    /// MED's integer geometry code (`@GEO`).
    pub fn med_code(self) -> i32 {
        match self {
            CellType::Poi1 => 1,
            CellType::Seg2 => 102,
            CellType::Seg3 => 103,
            CellType::Tria3 => 203,
            CellType::Tria6 => 206,
            CellType::Quad4 => 204,
            CellType::Quad8 => 208,
            CellType::Tetra4 => 304,
            CellType::Tetra10 => 310,
            CellType::Penta6 => 306,
            CellType::Penta15 => 315,
            CellType::Hexa8 => 308,
            CellType::Hexa20 => 320,
        }
    }

    pub fn from_med_name(name: &str) -> Option<CellType> {
        CellType::ALL.into_iter().find(|t| t.med_name() == name)
    }

    pub fn from_med_code(code: i32) -> Option<CellType> {
        CellType::ALL.into_iter().find(|t| t.med_code() == code)
    }
}

/// One cell: its type and its node indices (0-based, MED order).
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    pub kind: CellType,
    pub nodes: Vec<usize>,
}

/// An unstructured mesh with named cell groups (GROUP_MA) and node groups
/// (GROUP_NO). Groups keep insertion order, as code_aster lists them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    pub name: String,
    /// Space dimension of the coordinates stored (2 or 3).
    pub dim: usize,
    /// Node coordinates, always stored with 3 components (z = 0 in 2D).
    pub coords: Vec<[f64; 3]>,
    pub cells: Vec<Cell>,
    /// Cell groups: name -> sorted cell indices.
    pub cell_groups: IndexMap<String, Vec<usize>>,
    /// Node groups: name -> node indices (order as built, no duplicates).
    pub node_groups: IndexMap<String, Vec<usize>>,
}

impl Mesh {
    pub fn nnodes(&self) -> usize {
        self.coords.len()
    }
    pub fn ncells(&self) -> usize {
        self.cells.len()
    }

    /// Number of cells of each type, in [`CellType::ALL`] order.
    pub fn count_by_type(&self) -> Vec<(CellType, usize)> {
        CellType::ALL
            .into_iter()
            .map(|t| (t, self.cells.iter().filter(|c| c.kind == t).count()))
            .filter(|(_, n)| *n > 0)
            .collect()
    }

    /// The cell groups holding at least one of `cells`, in group order
    /// (to say where a cell named in a message is).
    pub fn groups_containing(&self, cells: &[usize]) -> Vec<String> {
        let mut set = vec![false; self.ncells()];
        for &c in cells {
            set[c] = true;
        }
        self.cell_groups
            .iter()
            .filter(|(_, g)| g.iter().any(|&c| set[c]))
            .map(|(n, _)| n.clone())
            .collect()
    }

    /// All distinct nodes of a set of cells, in increasing node order.
    pub fn nodes_of_cells(&self, cells: &[usize]) -> Vec<usize> {
        let mut seen = vec![false; self.nnodes()];
        for &c in cells {
            for &n in &self.cells[c].nodes {
                seen[n] = true;
            }
        }
        seen.iter()
            .enumerate()
            .filter_map(|(i, &s)| s.then_some(i))
            .collect()
    }

    /// Axis-aligned bounding box (min, max).
    pub fn bounding_box(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in &self.coords {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }
}

pub mod mail;
pub mod ops;
pub mod quadrature;
pub mod shape;
pub mod taylor;
pub mod vec3;
