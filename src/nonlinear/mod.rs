//! The nonlinear engine of DYNA_NON_LINE and STAT_NON_LINE (everything but
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
pub mod contact_active;
pub mod continuous;
pub mod cycling;
pub mod damping;
pub mod dofs;
pub mod dyna;
pub mod energy;
pub mod explicit;
pub mod explicit_contact;
pub mod explicit_unilateral;
pub mod fields;
pub mod linear;
pub mod loads;
pub mod newton;
pub mod observation;
pub mod result_table;
pub mod rigid;
pub mod team;
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
    /// Mesh error (inverted cell) found before the first step.
    Mesh(String),
    /// A material value the dynamics cannot use (RHO <= 0).
    Material(String),
}

impl std::fmt::Display for PrepareError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PrepareError::Behaviour(b) => f.write_str(&b.message),
            PrepareError::Load(m) | PrepareError::Mesh(m) | PrepareError::Material(m) => {
                f.write_str(m)
            }
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
    discretize_for(mesh, model, matfield, materials, occurrences, loads, true)
}

/// [`discretize`] for a dynamic (`inertia`) or quasi-static computation:
/// without inertia no density is needed (STAT_NON_LINE reads no RHO; a
/// RHO given is used for PESANTEUR only) and the mass matrix is zero.
pub fn discretize_for(
    mesh: &Mesh,
    model: &Model,
    matfield: &MaterialField,
    materials: &IndexMap<String, Material>,
    occurrences: &[Occurrence],
    loads: &[&MechLoad],
    inertia: bool,
) -> Result<(Assembler, Vec<String>), PrepareError> {
    check_geometry(mesh, model)?;
    let nb = dofs::number(mesh, model, loads).map_err(PrepareError::Load)?;
    if inertia {
        let held = |c: usize| {
            mesh.cells[c]
                .nodes
                .iter()
                .all(|&n| (0..nb.ndpn).all(|k| nb.eq[n * nb.ndpn + k] == dofs::NONE))
        };
        check_density(mesh, model, matfield, materials, &held)?;
    }
    let beh = behaviour::build_for(model, matfield, materials, occurrences, inertia)
        .map_err(PrepareError::Behaviour)?;
    let alarms = beh.alarms.clone();
    let asm = Assembler::new(mesh, model, beh, nb).map_err(PrepareError::Mesh)?;
    Ok((asm, alarms))
}

/// Every element's initial geometry at the Gauss points it will use: an
/// inverted or degenerate cell would give NaN in every field, so it is
/// refused before the first step, named as code_aster names it (M + its
/// number), with its groups, the point and the value.
fn check_geometry(mesh: &Mesh, model: &Model) -> Result<(), PrepareError> {
    for (cell, role) in model.cells.iter().enumerate() {
        let crate::model::CellRole::Element(spec) = role else {
            continue;
        };
        let coords: Vec<[f64; 3]> = mesh.cells[cell]
            .nodes
            .iter()
            .map(|&n| mesh.coords[n])
            .collect();
        if let Err(bad) = crate::element::check_initial_geometry(spec, &coords) {
            return Err(PrepareError::Mesh(format!(
                "cell M{} ({} {}, group(s) {}): {} at Gauss point {} of its {} family, on the initial mesh; \
                 the cell is inverted or degenerate (the nodes turn the wrong way, or a node is misplaced): \
                 correct the mesh before the first step (AFFE_MODELE VERI_JACOBIEN='OUI' lists such cells)",
                cell + 1,
                spec.name,
                mesh.cells[cell].kind.aster_name(),
                group_list(mesh, cell),
                bad.message,
                bad.point + 1,
                bad.family.name()
            )));
        }
        // A cell of (almost) no volume passes the sign test when rounding
        // leaves its det J a hair above 0: refused as well, named alike.
        let c = &mesh.cells[cell];
        if let Some((point, ratio, h)) = crate::mesh::ops::degeneracy(mesh, c) {
            if ratio < crate::mesh::ops::DEGENERATE_RATIO {
                let d = c.kind.dim();
                return Err(PrepareError::Mesh(format!(
                    "cell M{} ({} {}, group(s) {}): degenerate on the initial mesh: its Jacobian determinant \
                     at point {} of its {}-point check rule, times the reference element's {what} and over \
                     h{} (h = {h:e}, its largest extent), is {ratio:.1e} (1 for a cube), below {:e}: the \
                     cell has (almost) no {what} (a flat cell, or merged nodes), so a stiffness, a mass or \
                     a stable step computed on it means nothing; correct the mesh before the first step \
                     (AFFE_MODELE VERI_JACOBIEN='OUI' lists such cells)",
                    cell + 1,
                    spec.name,
                    c.kind.aster_name(),
                    group_list(mesh, cell),
                    point + 1,
                    crate::mesh::ops::check_point_count(c.kind),
                    if d == 3 { "³" } else { "²" },
                    crate::mesh::ops::DEGENERATE_RATIO,
                    what = if d == 3 { "volume" } else { "area" },
                )));
            }
        }
    }
    Ok(())
}

/// ELAS/RHO of the material of every element, where it is given (a
/// missing RHO is the behaviour field's error): the mass matrix of a
/// dynamic computation needs a positive density, and a zero one leaves the
/// accelerations undefined.
fn check_density(
    mesh: &Mesh,
    model: &Model,
    matfield: &MaterialField,
    materials: &IndexMap<String, Material>,
    held: &dyn Fn(usize) -> bool,
) -> Result<(), PrepareError> {
    for (cell, role) in model.cells.iter().enumerate() {
        if !matches!(role, crate::model::CellRole::Element(_)) {
            continue;
        }
        let Some(Some(name)) = matfield.cell_material.get(cell) else {
            continue;
        };
        let Some(rho) = materials.get(name).and_then(|m| m.get("ELAS", "RHO")) else {
            continue;
        };
        // RHO = 0 on a cell whose dofs are all imposed is code_aster's
        // massless clamped part (its sdnv100a's rigid block): no inertia
        // is lost. Elsewhere a massless cell leaves a dof without inertia
        // (a body in flight without mass is singular).
        let massive = rho > 0.0 && rho.is_finite();
        let massless_and_held = rho == 0.0 && held(cell);
        if !(massive || massless_and_held) {
            let cells: Vec<usize> = (0..model.cells.len())
                .filter(|&c| {
                    matches!(model.cells[c], crate::model::CellRole::Element(_))
                        && matfield.cell_material.get(c).and_then(|m| m.as_deref())
                            == Some(name.as_str())
                })
                .collect();
            return Err(PrepareError::Material(format!(
                "the material {name} (DEFI_MATERIAU, ELAS/RHO = {rho:e}) is assigned to {} element(s) of group(s) {} (first: M{}); \
                 the mass matrix of DYNA_NON_LINE needs a density RHO > 0 (RHO = 0 only on cells whose dofs are all imposed)",
                cells.len(),
                mesh.groups_containing(&cells).join(", "),
                cell + 1
            )));
        }
    }
    Ok(())
}

/// The groups of a cell for a message ("none" when it is in no group).
/// A mesh cell of the model for a message, as code_aster names it (M +
/// its number), with its element and cell type and its groups:
/// `M3 (MECA_HEXA8 HEXA8, group(s) FOND)`.
pub fn cell_label(mesh: &Mesh, model: &Model, cell: usize) -> String {
    let element = match model.cells.get(cell) {
        Some(crate::model::CellRole::Element(spec)) => format!("{} ", spec.name),
        _ => String::new(),
    };
    format!(
        "M{} ({element}{}, group(s) {})",
        cell + 1,
        mesh.cells[cell].kind.aster_name(),
        group_list(mesh, cell)
    )
}

fn group_list(mesh: &Mesh, cell: usize) -> String {
    let g = mesh.groups_containing(&[cell]);
    if g.is_empty() {
        "none".into()
    } else {
        g.join(", ")
    }
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
