//! Node order conversion between MED (the internal order) and VTK.
//!
//! 0D, 1D and 2D cells have the same node order in both. For 3D cells MED
//! turns the first face the other way (clockwise seen from the opposite
//! face or apex, where VTK is counter-clockwise), and for quadratic prisms
//! and hexahedra the mid-edge nodes follow the corners they sit between.

use crate::mesh::CellType;

const ID1: [usize; 1] = [0];
const ID2: [usize; 2] = [0, 1];
const ID3: [usize; 3] = [0, 1, 2];
const ID4: [usize; 4] = [0, 1, 2, 3];
const ID6: [usize; 6] = [0, 1, 2, 3, 4, 5];
const ID8: [usize; 8] = [0, 1, 2, 3, 4, 5, 6, 7];
const TETRA4: [usize; 4] = [0, 2, 1, 3];
const TETRA10: [usize; 10] = [0, 2, 1, 3, 6, 5, 4, 7, 9, 8];
const PENTA6: [usize; 6] = [0, 2, 1, 3, 5, 4];
const HEXA8: [usize; 8] = [0, 3, 2, 1, 4, 7, 6, 5];
const PENTA15: [usize; 15] = [0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13];
const HEXA20: [usize; 20] = [
    0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 15, 14, 13, 12, 16, 19, 18, 17,
];

/// VTK node order from MED node order: `vtk_nodes[i] = med_nodes[p[i]]`
/// where `p = vtk_permutation(t)` (entry i is the MED index of VTK node i).
/// To go back, `med_nodes[p[i]] = vtk_nodes[i]`.
pub fn vtk_permutation(t: CellType) -> &'static [usize] {
    match t {
        CellType::Poi1 => &ID1,
        CellType::Seg2 => &ID2,
        CellType::Seg3 | CellType::Tria3 => &ID3,
        CellType::Quad4 => &ID4,
        CellType::Tria6 => &ID6,
        CellType::Quad8 => &ID8,
        CellType::Tetra4 => &TETRA4,
        CellType::Tetra10 => &TETRA10,
        CellType::Penta6 => &PENTA6,
        CellType::Penta15 => &PENTA15,
        CellType::Hexa8 => &HEXA8,
        CellType::Hexa20 => &HEXA20,
    }
}

/// VTK cell type id (VTK_HEXAHEDRON = 12, VTK_QUADRATIC_HEXAHEDRON = 25...).
pub fn vtk_cell_type(t: CellType) -> u8 {
    match t {
        CellType::Poi1 => 1,
        CellType::Seg2 => 3,
        CellType::Seg3 => 21,
        CellType::Tria3 => 5,
        CellType::Tria6 => 22,
        CellType::Quad4 => 9,
        CellType::Quad8 => 23,
        CellType::Tetra4 => 10,
        CellType::Tetra10 => 24,
        CellType::Penta6 => 13,
        CellType::Penta15 => 26,
        CellType::Hexa8 => 12,
        CellType::Hexa20 => 25,
    }
}
