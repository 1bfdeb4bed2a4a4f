//! Numbering of the unknowns and Dirichlet conditions by elimination.
//!
//! Every engine vector is a *full* vector: `nnodes × ndpn` entries, node
//! major, so nodal results are read without any renumbering. Dofs of nodes
//! that belong to no element are inactive (always 0, absent in results).
//! Active dofs are either imposed (DDL_IMPO: their value is known, the
//! residual there is the support reaction) or free; only free dofs are
//! equations of the linear systems. Elimination instead of code_aster's
//! Lagrange multipliers gives the same solution and reactions with a
//! smaller, better-conditioned system.

use crate::mesh::Mesh;
use crate::model::{MechLoad, Model};
use crate::solver::{fmt_decimals, SolverError, OVERFLOW};

/// Marker of "no equation".
pub const NONE: usize = usize::MAX;

#[derive(Debug, Clone, PartialEq)]
pub struct DofNumbering {
    pub nnodes: usize,
    /// Components per node (2 AXIS, 3 in 3D).
    pub ndpn: usize,
    /// Node belongs to at least one element of the model.
    pub active_node: Vec<bool>,
    /// Equation number of each full dof, [`NONE`] for imposed or inactive.
    pub eq: Vec<usize>,
    /// Full index of each equation.
    pub free: Vec<usize>,
    /// (full index, value) of the imposed dofs.
    pub imposed: Vec<(usize, f64)>,
}

impl DofNumbering {
    /// Full dof -> its row in `imposed`, for the loads that update
    /// imposed values in place.
    pub fn imposed_index(&self) -> std::collections::HashMap<usize, usize> {
        self.imposed
            .iter()
            .enumerate()
            .map(|(k, &(f, _))| (f, k))
            .collect()
    }

    pub fn nfull(&self) -> usize {
        self.nnodes * self.ndpn
    }
    pub fn neq(&self) -> usize {
        self.free.len()
    }
    pub fn is_active(&self, full: usize) -> bool {
        self.active_node[full / self.ndpn]
    }

    /// Equation `e` for a message: its node (code_aster's default name)
    /// and component; past the displacement equations, an unknown the
    /// contact added (CONTINUE's multipliers).
    pub fn equation_name(&self, e: usize) -> String {
        match self.free.get(e) {
            Some(&f) => self.dof_name(f),
            None => format!(
                "the contact unknown {} (after the displacements)",
                e - self.neq() + 1
            ),
        }
    }

    /// Full dof `f` for a message: its node (code_aster's default name)
    /// and component.
    pub fn dof_name(&self, f: usize) -> String {
        format!(
            "node N{} component {}",
            f / self.ndpn + 1,
            ["DX", "DY", "DZ"].get(f % self.ndpn).unwrap_or(&"?")
        )
    }

    /// A failed factorization or solve of a system on these equations,
    /// for the user: the lost-decimals criterion names the dof where the
    /// pivot vanished and its likely causes.
    pub fn solver_failure(&self, e: &SolverError) -> String {
        match e {
            SolverError::LostDecimals {
                unknown,
                decimals,
                nprec,
            } => format!(
                "the matrix is singular: {} decimals lost at the pivot of {} (SOLVEUR NPREC = {nprec}, \
                 STOP_SINGULIER='OUI'); the structure has a mode without stiffness there: a missing support \
                 (DDL_IMPO), a zero-energy (spurious) mode of under-integrated elements \
                 (3D_SI, D_PLAN_SI, AXIS_SI) that the supports do not hold, a tangent that has lost \
                 its stiffness (a perfectly plastic structure at its limit load, under imposed forces), \
                 or a penalty (E_N, COEF_PENA) so much stiffer than its neighbours that they vanish \
                 against it at that pivot",
                fmt_decimals(*decimals),
                self.equation_name(*unknown)
            ),
            SolverError::NonFiniteRhs { unknown, value } => format!(
                "the right-hand side of the linear system is not finite at {} ({value}) before the solve: \
                 the external forces, or the stiffness times the imposed values, are {OVERFLOW}; \
                 the matrix is not at fault",
                self.equation_name(*unknown)
            ),
            SolverError::Overflow { unknown, log10 } => format!(
                "the solve overflows at {}: the matrix is regular (the same system scaled down \
                 solves, to about 1e{log10:.0} there once scaled back), but the values of this \
                 solve are {OVERFLOW}",
                self.equation_name(*unknown)
            ),
            // A system inconsistent in itself (a right-hand side of another
            // size than the matrix): aster's fault, not the structure's.
            SolverError::Usage(_) => format!(
                "{e}: {INTERNAL} (the linear system it built is inconsistent), \
                 not a property of the study; please report it with the command file"
            ),
            e => e.to_string(),
        }
    }
}

/// What a solver failure that is aster's own bug says (the step's
/// description then blames no rigid-body mode: probe s8g D2 was told to
/// "add the missing DDL_IMPO" for a right-hand side of the wrong length).
pub const INTERNAL: &str = "an internal error of aster";

/// Numbers the dofs of `model` on `mesh`, with the DDL_IMPO of `loads`.
/// A dof imposed twice must get the same value; a dof outside the model
/// is an error (it could not be honoured).
pub fn number(mesh: &Mesh, model: &Model, loads: &[&MechLoad]) -> Result<DofNumbering, String> {
    let nnodes = mesh.nnodes();
    let ndpn = model.ndof_per_node();
    let mut active_node = vec![false; nnodes];
    for (c, _) in model.element_cells() {
        for &n in &mesh.cells[c].nodes {
            active_node[n] = true;
        }
    }
    let mut value: Vec<Option<f64>> = vec![None; nnodes * ndpn];
    for load in loads {
        for imp in &load.imposed {
            let Some(k) = model.dofs.iter().position(|d| *d == imp.dof) else {
                return Err(format!(
                    "DDL_IMPO of the load on {} at node N{}: the model has no such component (components: {})",
                    imp.dof.name(),
                    imp.node + 1,
                    model.dofs.iter().map(|d| d.name()).collect::<Vec<_>>().join(", ")
                ));
            };
            if imp.node >= nnodes || !active_node[imp.node] {
                return Err(format!(
                    "DDL_IMPO on {} at node N{}: the node belongs to no element of the model",
                    imp.dof.name(),
                    imp.node + 1
                ));
            }
            if !imp.value.is_finite() {
                return Err(format!("DDL_IMPO value {} is not finite", imp.value));
            }
            let f = imp.node * ndpn + k;
            match value[f] {
                Some(v) if v != imp.value => {
                    return Err(format!(
                        "{} of node N{} is imposed twice with different values ({v} and {})",
                        imp.dof.name(),
                        imp.node + 1,
                        imp.value
                    ))
                }
                _ => value[f] = Some(imp.value),
            }
        }
    }
    let mut eq = vec![NONE; nnodes * ndpn];
    let mut free = Vec::new();
    let mut imposed = Vec::new();
    for f in 0..nnodes * ndpn {
        if !active_node[f / ndpn] {
            continue;
        }
        match value[f] {
            Some(v) => imposed.push((f, v)),
            None => {
                eq[f] = free.len();
                free.push(f);
            }
        }
    }
    Ok(DofNumbering {
        nnodes,
        ndpn,
        active_node,
        eq,
        free,
        imposed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A solver misuse (a right-hand side of another size than the matrix)
    /// is said to be aster's error; the quasi-static step's description
    /// (nonlinear::dyna) then does not send the user after a missing
    /// DDL_IMPO, which it did for probe s8g's D2.
    #[test]
    fn a_solver_misuse_is_reported_as_an_internal_error() {
        let nb = DofNumbering {
            nnodes: 1,
            ndpn: 2,
            active_node: vec![true],
            eq: vec![0, 1],
            free: vec![0, 1],
            imposed: Vec::new(),
        };
        let m = nb.solver_failure(&SolverError::Usage(
            "right-hand side of length 22 for a matrix of order 27".into(),
        ));
        assert!(
            m.starts_with("linear solver misuse: right-hand side of length 22")
                && m.contains(INTERNAL)
                && m.contains("report it"),
            "{m}"
        );
    }
}
