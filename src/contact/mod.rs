//! Discrete frictional contact (`DEFI_CONTACT` with `FORMULATION='DISCRETE'`,
//! penalised contact and penalised Coulomb friction, or the exact
//! conditions of the active set, `ALGO_CONT='CONTRAINTE'`), as a library the
//! Newton loop of DYNA_NON_LINE calls (docs/contact.md, semantics.md §6).
//!
//! The flow of one time step is:
//! 1. [`pairing::pair`] projects every slave node on the master surface in
//!    the current geometry and freezes the result in [`Link`]s (as many
//!    times per step as `REAC_GEOM` asks);
//! 2. at every Newton iteration [`discrete::evaluate`] gives, at fixed
//!    pairing, the contact contribution to the residual and to the tangent
//!    matrix, and the [`ContactState`] of every link;
//! 3. after convergence, [`ContactState::step_percussion`] (or, for the
//!    continuous formulation, [`ContactState::accumulate_percussion`]) and
//!    [`ContactState::cont_noeu`] give the `CONT_NOEU` field, and
//!    [`collision_started`] / [`ContactState::max_interpenetration`] feed the
//!    `COLLISION` and `INTERPENETRATION` events of DEFI_LIST_INST.
//!
//! The checked keywords of DEFI_CONTACT become a [`ContactDef`] in
//! `commands::contact_def` (the engine does not read keywords); what the
//! engine does not implement (LIAISON_UNIL there, NODAL pairing,
//! smoothing, ...) is refused there with a clear error rather than
//! silently ignored.

pub mod cont_noeu;
pub mod continuous;
pub mod continuous3d;
pub mod discrete;
pub mod pairing;
pub mod unilateral;

pub use cont_noeu::{collision_started, ContactState, LinkState, LinkStatus, CONT_NOEU_COMPONENTS};
pub use discrete::{
    evaluate, evaluate_armed, initial_penetration_alarm, penetrations, roundoff_gap, Contribution,
    IterationInput, RESI_COEF_MATR_FROT,
};
pub use pairing::{pair, project, Link, Pairing, Projection};

/// The geometric update (`REAC_GEOM`), i.e. when pairing is redone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ReacGeom {
    /// Re-pair after each Newton convergence until
    /// max|Δu since the last pairing| / max|u| < `resi_geom`, at most
    /// `iter_geom_maxi` times (reaching it is an error event).
    Automatique {
        iter_geom_maxi: usize,
        resi_geom: f64,
    },
    /// Exactly `nb_iter_geom` (≥ 1) pairings per time step, the first at
    /// the start of the step.
    Controle { nb_iter_geom: usize },
    /// Pairing once (`NB_ITER_GEOM=0` means the same).
    Sans,
}

/// Penalised Coulomb friction of a zone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coulomb {
    /// Friction coefficient μ (`COULOMB`).
    pub mu: f64,
    /// Tangential penalty stiffness (`E_T`), a nodal stiffness (N/mm).
    pub e_t: f64,
    /// Weight of the slip tangent while RESI_GLOB_RELA ≥ 1e-3
    /// (`COEF_MATR_FROT`).
    pub coef_matr_frot: f64,
}

/// One `ZONE` occurrence, resolved on the mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactZone {
    pub master_group: String,
    pub slave_group: String,
    /// Master cells (SEG2/SEG3 in 2D, TRIA3/TRIA6/QUAD4/QUAD8 in 3D).
    pub master_cells: Vec<usize>,
    /// Slave nodes: nodes of GROUP_MA_ESCL minus SANS_GROUP_NO and the
    /// nodes of SANS_GROUP_MA, ascending.
    pub slave_nodes: Vec<usize>,
    /// Normal penalty stiffness (`E_N`), a nodal stiffness (N/mm). Public
    /// and mutable because the INTERPENETRATION event's ADAPT_COEF_PENA
    /// doubles it between attempts of a step.
    pub e_n: f64,
    pub friction: Option<Coulomb>,
    /// Allowed projection outside a master cell, in parametric units;
    /// None: no limit (a negative `TOLE_PROJ_EXT`).
    pub tole_proj_ext: Option<f64>,
    /// Slave nodes farther than this from their projection are not paired
    /// (`DIST_APPA`; None for the default −1).
    pub dist_appa: Option<f64>,
    /// The fictitious thickness DIST_MAIT + DIST_ESCL of each slave node
    /// (code_aster's `cfdist`), subtracted from its geometric gap: the
    /// bodies touch when their surfaces are that far apart (half
    /// thicknesses of shells modelled by their mid-surface). Empty: none.
    pub user_gap: std::collections::HashMap<usize, f64>,
}

/// How the discrete formulation enforces non-penetration (`ALGO_CONT`,
/// the same in every zone).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiscreteAlgo {
    /// `'PENALISATION'`: the force E_N·(−g) and its tangent.
    Penalty,
    /// `'CONTRAINTE'` (the catalogue default) in implicit dynamics and
    /// statics: exact conditions g ≥ 0 by code_aster's active set on the
    /// Schur complement (`algoco`, the algorithm LIAISON_UNIL's `algocu`
    /// was drawn from), frictionless. Explicit schemes enforce
    /// 'CONTRAINTE' kinematically instead (`nonlinear::explicit_contact`).
    ActiveSet,
}

/// A mid-side node of a QUAD8 slave cell tied to its edge,
/// u_mid = ½ (u_a + u_b) on every component: code_aster's `cacoeq`
/// relations of the active-set discrete method (docs/contact.md §2).
/// The tied node is no slave node: the face's normal motion becomes
/// bilinear, driven by its vertices, which is what lets a node-wise
/// unilateral condition carry a uniform pressure on a QUAD8 face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MidTie {
    pub mid: usize,
    pub ends: [usize; 2],
}

/// A checked `DEFI_CONTACT` with `FORMULATION='DISCRETE'`, ready for the
/// solver.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactDef {
    /// Space dimension of the model (2 or 3): the number of displacement
    /// components a link couples.
    pub dim: usize,
    /// `FROTTEMENT='COULOMB'`.
    pub friction: bool,
    pub reac_geom: ReacGeom,
    pub algo: DiscreteAlgo,
    /// The QUAD8 mid-node ties ([`DiscreteAlgo::ActiveSet`] in 3D only).
    pub ties: Vec<MidTie>,
    pub zones: Vec<ContactZone>,
    /// FORMULATION='CONTINUE': the continuous keywords (the zones above
    /// then carry only the groups, the pairing options and the slave
    /// nodes; `e_n` and `friction` are unused).
    pub continuous: Option<continuous::ContinuousDef>,
}

impl ContactDef {
    /// All slave nodes of all zones (with repetitions if zones share one).
    pub fn slave_nodes(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.zones
            .iter()
            .enumerate()
            .flat_map(|(z, zone)| zone.slave_nodes.iter().map(move |&n| (z, n)))
    }
}

/// The cells a contact surface of a `dim`-dimensional model is made of:
/// SEG2/SEG3 in the x-y plane in 2D, TRIA3/TRIA6/QUAD4/QUAD8 in 3D.
pub fn is_contact_surface(kind: crate::mesh::CellType, dim: usize) -> bool {
    use crate::mesh::CellType as T;
    matches!(
        (dim, kind),
        (2, T::Seg2 | T::Seg3) | (3, T::Tria3 | T::Tria6 | T::Quad4 | T::Quad8)
    )
}
