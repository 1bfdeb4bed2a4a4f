//! Which finite element a cell gets under a modelisation, and with which
//! Gauss families: code_aster's element catalogue (`meca_3d.py`,
//! `meca_3d_si.py`, `meca_axis.py`, `meca_axis_si.py`; semantics.md §3.3)
//! reduced to the volume elements that carry stiffness and mass.
//!
//! Skin cells (QUAD8 in 3D, SEG3 in AXIS, ...) do get elements in
//! code_aster (MECA_FACE8, MEAXSE3), but those only carry loads and
//! contact; they are not stiffness elements, so [`element_spec`] returns
//! `None` for them and the model builder treats them separately.

use crate::mesh::quadrature::Fpg;
use crate::mesh::CellType;

/// The element name of 3D_SI on HEXA8 (element::hexs8), which carries
/// hourglass stresses in extra state rows.
pub const HEXS8_NAME: &str = "MECA_HEXS8";

/// The mechanical formulation shared by the elements of a modelisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Formulation {
    /// 2D axisymmetric: x is r, y is z, dofs (DX, DY) = (u_r, u_z);
    /// integrals per radian (r dr dz, no 2π).
    Axis,
    /// 2D plane strain (D_PLAN): dofs (DX, DY), ε_zz = 0, integrals per
    /// unit thickness along z. The element code is AXIS's without the
    /// hoop term and without the weight r: F_zz = 1 is the identity row
    /// of a 3D gradient, so every 3D law applies unchanged.
    PlaneStrain,
    /// 2D plane stress (C_PLAN): the geometry, dofs, Gauss families and
    /// integrals of [`Formulation::PlaneStrain`] (per unit thickness),
    /// with σ_zz = 0 instead of ε_zz = 0: at each Gauss point ε_zz is
    /// the unknown of a local Newton on σ_zz (`law::plane_stress`), and
    /// the tangent is the 3D one with the zz row and column condensed.
    PlaneStress,
    /// 3D continuum, dofs (DX, DY, DZ).
    Solid3d,
}

impl Formulation {
    /// The modelisation family a message names (AXIS, D_PLAN, 3D).
    pub fn label(self) -> &'static str {
        match self {
            Formulation::Axis => "AXIS",
            Formulation::PlaneStrain => "D_PLAN",
            Formulation::PlaneStress => "C_PLAN",
            Formulation::Solid3d => "3D",
        }
    }

    /// D_PLAN or C_PLAN: the two share every geometric code path (the
    /// Jacobian of the plane, no weight r, no hoop term).
    pub fn is_plane(self) -> bool {
        matches!(self, Formulation::PlaneStrain | Formulation::PlaneStress)
    }

    /// Degrees of freedom per node (2 for AXIS, 3 in 3D).
    pub fn dofs_per_node(self) -> usize {
        match self {
            Formulation::Axis | Formulation::PlaneStrain | Formulation::PlaneStress => 2,
            Formulation::Solid3d => 3,
        }
    }
}

/// A volume element: cell, formulation and the two Gauss families.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ElementSpec {
    /// code_aster's element name (MECA_HEXA20, MEAXQS8, ...), for messages.
    pub name: &'static str,
    pub cell: CellType,
    pub formulation: Formulation,
    /// Family of the stiffness, internal forces and SIEF_ELGA/VARI_ELGA.
    pub rigi: Fpg,
    /// Family of the consistent mass.
    pub mass: Fpg,
}

impl ElementSpec {
    /// MECA_HEXS8: one-point element with hourglass stresses carried in
    /// extra state rows (element::hexs8).
    pub fn is_hexs8(&self) -> bool {
        self.name == HEXS8_NAME
    }
    pub fn nnodes(&self) -> usize {
        self.cell.nnodes()
    }
    pub fn ndofs(&self) -> usize {
        self.nnodes() * self.formulation.dofs_per_node()
    }
}

/// The volume element of `modelisation` (an AFFE_MODELE MODELISATION
/// value) on `cell`, or `None` when that modelisation defines no volume
/// element there (the cell then keeps an earlier assignment, semantics.md
/// §3.2) **or when the element is not implemented** — check
/// [`unimplemented_element`] before concluding the former.
pub fn element_spec(modelisation: &str, cell: CellType) -> Option<ElementSpec> {
    use CellType::*;
    use Formulation::*;
    use Fpg::*;
    let (name, formulation, rigi, mass) = match (modelisation, cell) {
        ("3D", Hexa8) => ("MECA_HEXA8", Solid3d, Fpg8, Fpg8),
        ("3D", Hexa20) => ("MECA_HEXA20", Solid3d, Fpg27, Fpg27),
        ("3D", Penta6) => ("MECA_PENTA6", Solid3d, Fpg6, Fpg6),
        ("3D", Penta15) => ("MECA_PENTA15", Solid3d, Fpg21, Fpg21),
        // One point is exact for the constant strain of TETRA4; the mass
        // (degree 2) needs four.
        ("3D", Tetra4) => ("MECA_TETRA4", Solid3d, Fpg1, Fpg4),
        // semantics.md §3.3: five points for the stiffness, fifteen for
        // the mass; 3D_SI's MECA_TETRS10 takes four.
        ("3D", Tetra10) => ("MECA_TETRA10", Solid3d, Fpg5, Fpg15),
        ("3D_SI", Tetra10) => ("MECA_TETRS10", Solid3d, Fpg4, Fpg15),
        ("3D_SI", Hexa20) => ("MECA_HEXS20", Solid3d, Fpg8, Fpg27),
        // One point plus hourglass stabilisation (element::hexs8).
        ("3D_SI", Hexa8) => (HEXS8_NAME, Solid3d, Fpg1, Fpg8),
        ("AXIS", Quad8) => ("MEAXQU8", Axis, Fpg9, Fpg9),
        ("AXIS", Quad4) => ("MEAXQU4", Axis, Fpg4, Fpg4),
        ("AXIS", Tria6) => ("MEAXTR6", Axis, Fpg6, Fpg6),
        ("AXIS", Tria3) => ("MEAXTR3", Axis, Fpg1, Fpg3),
        ("AXIS_SI", Quad8) => ("MEAXQS8", Axis, Fpg4, Fpg9),
        // code_aster's plane elements take the Gauss families of the
        // axisymmetric ones on each cell.
        ("D_PLAN", Quad8) => ("MEDPQU8", PlaneStrain, Fpg9, Fpg9),
        ("D_PLAN", Quad4) => ("MEDPQU4", PlaneStrain, Fpg4, Fpg4),
        ("D_PLAN", Tria6) => ("MEDPTR6", PlaneStrain, Fpg6, Fpg6),
        ("D_PLAN", Tria3) => ("MEDPTR3", PlaneStrain, Fpg1, Fpg3),
        ("D_PLAN_SI", Quad8) => ("MEDPQS8", PlaneStrain, Fpg4, Fpg9),
        // code_aster's C_PLAN and C_PLAN_SI elements (phenomenon
        // catalogue): the cells of D_PLAN's, with its Gauss families
        // [mem: the element catalogue's C_PLAN families not re-read].
        ("C_PLAN", Quad8) => ("MECPQU8", PlaneStress, Fpg9, Fpg9),
        ("C_PLAN", Quad4) => ("MECPQU4", PlaneStress, Fpg4, Fpg4),
        ("C_PLAN", Tria6) => ("MECPTR6", PlaneStress, Fpg6, Fpg6),
        ("C_PLAN", Tria3) => ("MECPTR3", PlaneStress, Fpg1, Fpg3),
        ("C_PLAN_SI", Quad8) => ("MECPQS8", PlaneStress, Fpg4, Fpg9),
        _ => return None,
    };
    Some(ElementSpec {
        name,
        cell,
        formulation,
        rigi,
        mass,
    })
}

/// code_aster elements that exist but are not implemented here, by name.
/// The model builder must turn these into an error: treating them as "no
/// element" would silently keep an earlier (e.g. fully integrated)
/// element on the cell, or report a mesh without cells of the dimension.
/// code_aster's D_PLAN_SI has MEDPQS4 on QUAD4 beside MEDPQS8 (its
/// phenomenon catalogue), C_PLAN_SI likewise MECPQS4; its AXIS_SI is
/// QUAD8 only.
pub fn unimplemented_element(modelisation: &str, cell: CellType) -> Option<&'static str> {
    match (modelisation, cell) {
        ("D_PLAN_SI", CellType::Quad4) => Some("MEDPQS4"),
        ("C_PLAN_SI", CellType::Quad4) => Some("MECPQS4"),
        _ => None,
    }
}

/// The cell types on which `modelisation` defines a volume element here.
pub fn element_cells(modelisation: &str) -> Vec<CellType> {
    CellType::ALL
        .into_iter()
        .filter(|&c| element_spec(modelisation, c).is_some())
        .collect()
}
