//! The nonlinear dynamics engine of DYNA_NON_LINE (everything but
//! contact): dof numbering with Dirichlet elimination ([`dofs`]), the
//! behaviour field ([`behaviour`]), parallel element loop and fixed-pattern
//! assembly ([`assembly`]), the Newton step with code_aster's residual
//! norms ([`newton`]), the time loop with step cutting and archiving
//! ([`dyna`]) and the result fields ([`fields`]).
//!
//! The engine never reads keywords: `commands::dyna_non_line` turns the
//! checked arguments into the structures below. docs/dynamics.md states
//! the formulation and the verification.

pub mod assembly;
pub mod behaviour;
pub mod contact;
pub mod continuous;
pub mod dofs;
pub mod dyna;
pub mod energy;
pub mod fields;
pub mod newton;
pub mod unilateral;

use indexmap::IndexMap;

pub use assembly::{Assembler, CellFailure};
pub use behaviour::{BehaviourError, BehaviourField, CellLaw, Controls, Occurrence};
pub use contact::DiscreteContact;
pub use dofs::DofNumbering;
pub use dyna::{ArchivePolicy, Reduce, RunSummary, Stopped, Suivi, SuiviField, TimeLoop};
pub use newton::{
    ContactIteration, ContactTerm, ConvergenceSettings, Engine, IncrementCorrection,
    IterationRecord, NewtonSettings, State, StepFailure, StepReport,
};
pub use unilateral::{UnilStats, UnilateralContact};

use crate::mesh::Mesh;
use crate::model::{Material, MaterialField, MechLoad, Model};

/// Why the discretization could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum PrepareError {
    /// COMPORTEMENT or material problem.
    Behaviour(BehaviourError),
    /// DDL_IMPO problem.
    Load(String),
    /// Mesh error (inverted cell) found while building the mass.
    Mesh(String),
}

impl std::fmt::Display for PrepareError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PrepareError::Behaviour(b) => f.write_str(&b.message),
            PrepareError::Load(m) | PrepareError::Mesh(m) => f.write_str(m),
        }
    }
}

/// Builds the discretization of a model: behaviour field, numbering,
/// element list, pattern and mass. Returns it with the alarms to log.
pub fn discretize(
    mesh: &Mesh,
    model: &Model,
    matfield: &MaterialField,
    materials: &IndexMap<String, Material>,
    occurrences: &[Occurrence],
    loads: &[&MechLoad],
) -> Result<(Assembler, Vec<String>), PrepareError> {
    let beh = behaviour::build(model, matfield, materials, occurrences)
        .map_err(PrepareError::Behaviour)?;
    let alarms = beh.alarms.clone();
    let nb = dofs::number(mesh, model, loads).map_err(PrepareError::Load)?;
    let asm = Assembler::new(mesh, model, beh, nb).map_err(PrepareError::Mesh)?;
    Ok((asm, alarms))
}

/// A state at rest at `t` with virgin Gauss points, then `u`, `v`, `a`
/// (full vectors) when given.
pub fn initial_state(
    asm: &Assembler,
    t: f64,
    u: Option<Vec<f64>>,
    v: Option<Vec<f64>>,
    a: Option<Vec<f64>>,
) -> State {
    let n = asm.numbering.nfull();
    State {
        t,
        motion: crate::time::Kinematics {
            u: u.unwrap_or_else(|| vec![0.0; n]),
            v: v.unwrap_or_else(|| vec![0.0; n]),
            a: a.unwrap_or_else(|| vec![0.0; n]),
        },
        points: asm.initial_states(),
        fint: vec![0.0; n],
    }
}
