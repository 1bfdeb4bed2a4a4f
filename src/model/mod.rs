//! The data of the model-building concepts: the finite-element model
//! (AFFE_MODELE), materials (DEFI_MATERIAU), the material field
//! (AFFE_MATERIAU) and mechanical loads (AFFE_CHAR_MECA).
//!
//! These are what the commands produce and what the engine consumes; the
//! engine never reads keywords.

use indexmap::IndexMap;

use crate::mesh::Mesh;
use crate::model::spec::ElementSpec;

pub mod spec;

/// A degree of freedom of the displacement quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Dof {
    Dx,
    Dy,
    Dz,
}

impl Dof {
    pub const ALL: [Dof; 3] = [Dof::Dx, Dof::Dy, Dof::Dz];
    pub fn name(self) -> &'static str {
        match self {
            Dof::Dx => "DX",
            Dof::Dy => "DY",
            Dof::Dz => "DZ",
        }
    }
    pub fn from_name(s: &str) -> Option<Dof> {
        Dof::ALL.into_iter().find(|d| d.name() == s)
    }
    pub fn index(self) -> usize {
        self as usize
    }
}

/// How a cell takes part in the model.
#[derive(Debug, Clone, PartialEq)]
pub enum CellRole {
    /// Not in the model.
    None,
    /// A volume (3D) or surface (AXIS) element with stiffness and mass.
    Element(ElementSpec),
    /// A boundary cell of the model (SEG in AXIS, TRIA/QUAD in 3D): it
    /// carries no stiffness but belongs to the model (loads, contact).
    Skin { modelisation: String },
}

/// The result of AFFE_MODELE.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// The mesh concept.
    pub mesh: String,
    /// Displacement components per node: [DX, DY] for AXIS, [DX, DY, DZ] for 3D.
    pub dofs: Vec<Dof>,
    /// One entry per mesh cell.
    pub cells: Vec<CellRole>,
}

impl Model {
    /// The number of components per node.
    pub fn ndof_per_node(&self) -> usize {
        self.dofs.len()
    }
    /// Indices of the cells that are elements.
    pub fn element_cells(&self) -> impl Iterator<Item = (usize, &ElementSpec)> {
        self.cells.iter().enumerate().filter_map(|(i, r)| match r {
            CellRole::Element(s) => Some((i, s)),
            _ => None,
        })
    }

    /// The formulation of the model's elements (AFFE_MODELE refuses a
    /// mix of families), `None` for a model without elements.
    pub fn formulation(&self) -> Option<spec::Formulation> {
        self.element_cells().map(|(_, s)| s.formulation).next()
    }

    /// True if the model carries this component (DZ is absent in AXIS).
    pub fn has_dof(&self, dof: Dof) -> bool {
        self.dofs.contains(&dof)
    }

    /// Per mesh node, whether it carries the model's dofs: a node does
    /// when it belongs to a cell of the model (element or skin). Loads and
    /// fields on other nodes would have no unknown to act on.
    pub fn node_mask(&self, mesh: &Mesh) -> Vec<bool> {
        let mut mask = vec![false; mesh.nnodes()];
        for (c, role) in self.cells.iter().enumerate() {
            if *role != CellRole::None {
                for &n in &mesh.cells[c].nodes {
                    mask[n] = true;
                }
            }
        }
        mask
    }
}

/// The result of DEFI_MATERIAU: named blocks (ELAS, ECRO_LINE, ECRO_COOK)
/// of named real parameters, as the user gave them plus defaults, and the
/// parameters that are functions (TRACTION/SIGM), by "BLOCK/PARAM".
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Material {
    pub blocks: IndexMap<String, IndexMap<String, f64>>,
    pub curves: IndexMap<String, MaterialCurve>,
}

/// A material parameter given as a tabulated function of one variable
/// (the law decides what it means: TRACTION/SIGM is σ(ε)).
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialCurve {
    pub abscissas: Vec<f64>,
    pub ordinates: Vec<f64>,
    /// The function's PROL_DROITE.
    pub right: crate::post::function::Extrapolation,
}

impl Material {
    /// A parameter, e.g. `get("ELAS", "E")`.
    pub fn get(&self, block: &str, param: &str) -> Option<f64> {
        self.blocks.get(block)?.get(param).copied()
    }
    /// A function parameter, e.g. `curve("TRACTION", "SIGM")`.
    pub fn curve(&self, block: &str, param: &str) -> Option<&MaterialCurve> {
        self.curves.get(&format!("{block}/{param}"))
    }
}

/// The result of AFFE_MATERIAU: the material concept of each cell (later
/// occurrences win on overlapping cells).
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialField {
    pub mesh: String,
    pub cell_material: Vec<Option<String>>,
}

/// One imposed degree of freedom (DDL_IMPO).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImposedDof {
    pub node: usize,
    pub dof: Dof,
    pub value: f64,
}

/// The result of AFFE_CHAR_MECA. The same dof may be imposed several times
/// (sdnv103a blocks the nodes shared by RIGID and VOL_RIG twice); the engine
/// keeps the last value and fails if two differ.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MechLoad {
    pub model: String,
    pub imposed: Vec<ImposedDof>,
    /// PESANTEUR, if given (at most once per load, as in code_aster).
    pub gravity: Option<Gravity>,
    /// FORCE_NODALE: (node, dof, force) in the model's global frame, a
    /// force on each node listed (per radian in AXIS, like every nodal
    /// quantity there); a dead load.
    pub nodal_forces: Vec<(usize, Dof, f64)>,
    /// PRES_REP: a uniform pressure on skin cells of the model, a dead
    /// load on the initial geometry (`element::pressure`).
    pub pressures: Vec<Pressure>,
    /// FORCE_FACE, FORCE_ARETE, FORCE_CONTOUR and FORCE_INTERNE: uniform
    /// forces per unit area, length or volume, dead loads on the initial
    /// geometry (`element::distributed`).
    pub distributed: Vec<DistributedForce>,
    /// AFFE_CHAR_MECA_F: values that are functions of the instant and of
    /// the node's initial coordinates, evaluated at each step's end
    /// instant. Their DDL_IMPO dofs are also in `imposed` (value 0) so
    /// that the numbering holds them; the engine overwrites the value.
    pub functions: Vec<NodalFunction>,
    /// AFFE_CHAR_MECA_F's PRES_REP, FORCE_FACE, FORCE_ARETE,
    /// FORCE_CONTOUR and FORCE_INTERNE: densities that are functions of
    /// the instant and of the position, integrated at the Gauss points of
    /// the initial geometry at each instant the engine needs.
    pub fields: Vec<FieldFunction>,
}

/// What an AFFE_CHAR_MECA_F density is.
#[derive(Debug, Clone, PartialEq)]
pub enum FieldDensity {
    /// PRES_REP: the pressure.
    Pressure(crate::post::formula::Coef),
    /// FORCE_*: the components FX, FY, FZ (absent ones are zero).
    Force(
        DistributedKind,
        Box<[Option<crate::post::formula::Coef>; 3]>,
    ),
}

/// One AFFE_CHAR_MECA_F occurrence of a distributed load: `density` (the
/// concepts `names`, for messages) on `cells`. A cell is in at most one
/// entry per keyword of a load: a later occurrence takes it.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldFunction {
    pub density: FieldDensity,
    pub names: String,
    pub cells: Vec<usize>,
}

impl FieldFunction {
    /// The AFFE_CHAR_MECA_F keyword.
    pub fn keyword(&self) -> &'static str {
        match &self.density {
            FieldDensity::Pressure(_) => "PRES_REP",
            FieldDensity::Force(kind, _) => kind.keyword(),
        }
    }
}

/// What an AFFE_CHAR_MECA_F value gives at its nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FunctionTarget {
    /// DDL_IMPO: the displacement of the component.
    Imposed,
    /// FORCE_NODALE: a force along the component, on each node.
    Force,
}

/// One component of one AFFE_CHAR_MECA_F occurrence: `coef` (the concept
/// `name`) evaluated at each node of `nodes` at its initial coordinates.
/// A node is in at most one entry per (target, dof) of a load: a later
/// occurrence takes it from the earlier ones.
#[derive(Debug, Clone, PartialEq)]
pub struct NodalFunction {
    pub target: FunctionTarget,
    pub dof: Dof,
    pub name: String,
    pub coef: crate::post::formula::Coef,
    pub nodes: Vec<usize>,
}

/// Which AFFE_CHAR_MECA keyword a [`DistributedForce`] came from: it
/// fixes the measure the force density is per.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DistributedKind {
    /// FORCE_FACE: per unit area of TRIA/QUAD skin cells of a 3D model.
    Face,
    /// FORCE_ARETE: per unit length of SEG cells of a 3D model.
    Edge,
    /// FORCE_CONTOUR: per unit length of SEG cells of a 2D model (in
    /// AXIS per unit length and per radian: the integral carries r).
    Contour,
    /// FORCE_INTERNE: per unit volume of the volume elements (per radian
    /// in AXIS).
    Internal,
}

impl DistributedKind {
    pub fn keyword(self) -> &'static str {
        match self {
            DistributedKind::Face => "FORCE_FACE",
            DistributedKind::Edge => "FORCE_ARETE",
            DistributedKind::Contour => "FORCE_CONTOUR",
            DistributedKind::Internal => "FORCE_INTERNE",
        }
    }
}

/// A uniform force density `force` (global frame, components absent
/// from the keyword are 0) on each of `cells`.
#[derive(Debug, Clone, PartialEq)]
pub struct DistributedForce {
    pub kind: DistributedKind,
    pub force: [f64; 3],
    pub cells: Vec<usize>,
}

/// PRES_REP: the pressure `p` on each of `cells` (skin cells of the model:
/// SEG in AXIS, TRIA/QUAD in 3D), pushing against the cell's normal.
#[derive(Debug, Clone, PartialEq)]
pub struct Pressure {
    pub p: f64,
    pub cells: Vec<usize>,
}

/// PESANTEUR: the body force ρ·g·d per unit volume of the element cells
/// `cells` (every element cell of the model when `None`). code_aster
/// normalises DIRECTION (`capesa`), so `direction` is a unit vector and
/// `g` carries the magnitude.
#[derive(Debug, Clone, PartialEq)]
pub struct Gravity {
    pub g: f64,
    pub direction: [f64; 3],
    pub cells: Option<Vec<usize>>,
}
