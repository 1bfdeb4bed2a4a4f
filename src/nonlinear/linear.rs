//! Linear elastic statics (MECA_STATIQUE): K u = F_ext at each instant,
//! solved once per instant on the quasi-static engine's discretization
//! (numbering with Dirichlet elimination, element list, pattern), with
//! the element stiffness code_aster's option RIGI_MECA gives.
//!
//! Why not Newton with an elastic law: for every element but MECA_HEXS8
//! the two are the same (the ELAS tangent at u = 0 is Hooke's, and one
//! iteration solves the linear system), but code_aster's linear HEXS8
//! matrix (te0392, `element::hexs8::rigi_meca`) is not the tangent of its
//! nonlinear element (te0407), which STAT_NON_LINE uses. So the element
//! matrices are computed once here, with that choice, and the same
//! matrices give the internal forces K u (FORC_NODA, the residual check):
//! forces and stiffness cannot disagree.

use rayon::prelude::*;

use super::assembly::{Assembler, CellFailure, ElementData};
use super::behaviour::CellLaw;
use super::dofs::NONE;
use crate::element::hexs8::{self, Variant};
use crate::element::{initial_states, internal_forces, ElementFailure, Kinematics, PointState};
use crate::law::TangentKind;
use crate::solver::{DirectLu, LinearSolver, SingularityCheck, SolverError, SparseMatrix};

/// Why a linear solve failed.
#[derive(Debug, Clone, PartialEq)]
pub enum LinearError {
    /// An element could not be computed (mesh or material).
    Cell(CellFailure),
    /// The stiffness of the free dofs is singular (a mechanism the
    /// rigid-mode check cannot see, such as an unstabilised hourglass).
    Singular(String),
    /// F_ext or an imposed value is not finite.
    BadInput(String),
}

impl std::fmt::Display for LinearError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LinearError::Cell(c) => write!(f, "cell M{}: {}", c.cell + 1, c.failure),
            LinearError::Singular(m) | LinearError::BadInput(m) => f.write_str(m),
        }
    }
}

/// One instant's solution.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearSolution {
    /// Displacements, full vector (imposed values included).
    pub u: Vec<f64>,
    /// K u, full vector: at the imposed dofs, minus F_ext, the reactions.
    pub fint: Vec<f64>,
    /// |K u − F_ext| on the free dofs over max(|F_ext|, |K u|) on all
    /// active dofs: the check that the solve is the exact linear solution.
    pub residual: f64,
}

/// E and ν of an element, from its law (MECA_STATIQUE builds every cell
/// with RELATION='ELAS').
fn elastic_constants(laws: &[CellLaw], e: &ElementData) -> Result<(f64, f64), ElementFailure> {
    match &laws[e.law] {
        CellLaw::Elas(l) => Ok((l.params.e, l.params.nu)),
        _ => Err(ElementFailure::BadInput {
            message: "the linear stiffness needs the ELAS law on every element".into(),
        }),
    }
}

/// Every element's linear stiffness, row-major (entry (a, b) at a·n + b):
/// RIGI_MECA of code_aster, i.e. te0392 for MECA_HEXS8 and the elastic
/// tangent at u = 0 (∫ Bᵀ C B) for every other element.
pub fn element_stiffnesses(
    asm: &Assembler,
    variant: Variant,
) -> Result<Vec<Vec<f64>>, CellFailure> {
    let laws = &asm.laws;
    asm.elements
        .par_iter()
        .map(|e| {
            let fail = |failure| CellFailure {
                cell: e.cell,
                failure,
            };
            let n = e.full.len();
            let k = if e.spec.is_hexs8() {
                let (young, nu) = elastic_constants(laws, e).map_err(fail)?;
                hexs8::rigi_meca(&e.coords, young, nu, variant).map_err(fail)?
            } else {
                let zeros = vec![0.0; n];
                let law = laws[e.law].law_ref();
                internal_forces(
                    &e.spec,
                    Kinematics::Petit,
                    &e.coords,
                    &zeros,
                    &zeros,
                    &initial_states(&e.spec, law),
                    law,
                    0.0,
                    TangentKind::Consistent,
                )
                .map_err(fail)?
                .stiffness
                .ok_or_else(|| {
                    fail(ElementFailure::BadInput {
                        message: "the element returned no stiffness".into(),
                    })
                })?
            };
            Ok((0..n * n).map(|i| k[(i / n, i % n)]).collect())
        })
        .collect()
}

/// K u into `out` (full, overwritten) from the element matrices of
/// [`element_stiffnesses`]: the internal forces of a linear result.
pub fn linear_forces(asm: &Assembler, ks: &[Vec<f64>], u: &[f64], out: &mut [f64]) {
    out.iter_mut().for_each(|v| *v = 0.0);
    for (e, k) in asm.elements.iter().zip(ks) {
        let n = e.full.len();
        for (a, &fa) in e.full.iter().enumerate() {
            out[fa] += k[a * n..(a + 1) * n]
                .iter()
                .zip(&e.full)
                .map(|(kab, &fb)| kab * u[fb])
                .sum::<f64>();
        }
    }
}

/// The Gauss-point states of a displacement: the elastic stress at every
/// RIGI point (the law evaluated from the virgin state), and for
/// MECA_HEXS8 code_aster's linear SIEF_ELGA, C B0 u at the centre with
/// no hourglass stress (te0022).
pub fn linear_stresses(asm: &Assembler, u: &[f64]) -> Result<Vec<PointState>, CellFailure> {
    let laws = &asm.laws;
    let per_element: Vec<Vec<PointState>> = asm
        .elements
        .par_iter()
        .map(|e| {
            let fail = |failure| CellFailure {
                cell: e.cell,
                failure,
            };
            let ue: Vec<f64> = e.full.iter().map(|&f| u[f]).collect();
            let law = laws[e.law].law_ref();
            let mut states = initial_states(&e.spec, law);
            if e.spec.is_hexs8() {
                let (young, nu) = elastic_constants(laws, e).map_err(fail)?;
                states[0].stress =
                    hexs8::rigi_meca_stress(&e.coords, young, nu, &ue).map_err(fail)?;
                return Ok(states);
            }
            let zeros = vec![0.0; ue.len()];
            Ok(internal_forces(
                &e.spec,
                Kinematics::Petit,
                &e.coords,
                &zeros,
                &ue,
                &states,
                law,
                0.0,
                TangentKind::None,
            )
            .map_err(fail)?
            .states)
        })
        .collect::<Result<_, _>>()?;
    Ok(per_element.into_iter().flatten().collect())
}

/// The linear static problem of a discretization: element matrices
/// computed once, the free-dof stiffness factorized at the first solve.
pub struct LinearStatics {
    pub asm: Assembler,
    pub variant: Variant,
    ks: Vec<Vec<f64>>,
    solver: Option<DirectLu>,
    /// SOLVEUR NPREC / STOP_SINGULIER.
    pub check: SingularityCheck,
}

impl LinearStatics {
    /// The element matrices of `asm` (whose laws are ELAS).
    pub fn new(asm: Assembler, variant: Variant) -> Result<LinearStatics, LinearError> {
        let ks = element_stiffnesses(&asm, variant).map_err(LinearError::Cell)?;
        Ok(LinearStatics {
            asm,
            variant,
            ks,
            solver: None,
            check: SingularityCheck::default(),
        })
    }

    /// K_ff assembled on the free pattern and factorized.
    fn factorize(&mut self) -> Result<&DirectLu, LinearError> {
        if self.solver.is_none() {
            let mut k = SparseMatrix::zeros(self.asm.pattern.clone());
            for (e, ke) in self.asm.elements.iter().zip(&self.ks) {
                for (&p, &v) in e.pos.iter().zip(ke) {
                    if p != NONE {
                        k.values[p] += v;
                    }
                }
            }
            let mut solver = DirectLu::new();
            solver.check = self.check;
            solver.factorize(&k).map_err(|e| {
                LinearError::Singular(match e {
                    SolverError::LostDecimals { .. } => self.asm.numbering.solver_failure(&e),
                    e => format!(
                        "the stiffness of the free dofs cannot be factorized ({e}): a part of the model can move without deforming"
                    ),
                })
            })?;
            self.solver = Some(solver);
        }
        Ok(self.solver.as_ref().expect("factorized above"))
    }

    /// With STOP_SINGULIER='NON', the alarm of a stiffness that lost NPREC
    /// decimals or more at a pivot (the solution was kept).
    pub fn tolerated_singularity(&self) -> Option<String> {
        let s = self.solver.as_ref()?;
        let w = s.tolerated?;
        Some(singularity_alarm(&self.asm.numbering, w, self.check))
    }

    /// Solves K u = F_ext (full vector) with the imposed values of the
    /// numbering: the imposed part moved to the right-hand side, the free
    /// dofs solved, the residual measured on the full element matrices.
    pub fn solve(&mut self, fext: &[f64]) -> Result<LinearSolution, LinearError> {
        let nb = &self.asm.numbering;
        let nfull = nb.nfull();
        if fext.len() != nfull || fext.iter().any(|v| !v.is_finite()) {
            return Err(LinearError::BadInput(
                "the applied forces are not finite".into(),
            ));
        }
        let mut u = vec![0.0; nfull];
        for &(f, v) in &nb.imposed {
            if !v.is_finite() {
                return Err(LinearError::BadInput(format!(
                    "the imposed value of dof {f} is not finite"
                )));
            }
            u[f] = v;
        }
        let mut fint = vec![0.0; nfull];
        linear_forces(&self.asm, &self.ks, &u, &mut fint);
        let mut x: Vec<f64> = nb.free.iter().map(|&f| fext[f] - fint[f]).collect();
        let free = nb.free.clone();
        if !free.is_empty() {
            self.factorize()?.solve(&mut x).map_err(|e| {
                LinearError::Singular(match e {
                    SolverError::NonFiniteRhs { .. } | SolverError::Overflow { .. } => {
                        self.asm.numbering.solver_failure(&e)
                    }
                    e => format!("the linear solve failed: {e}"),
                })
            })?;
        }
        for (&f, &v) in free.iter().zip(&x) {
            u[f] = v;
        }
        linear_forces(&self.asm, &self.ks, &u, &mut fint);
        // Scaled by the largest entry: the squares of forces near 1e200
        // overflow where the forces themselves do not.
        let norm = |v: &mut dyn Iterator<Item = f64>| {
            let v: Vec<f64> = v.collect();
            let big = v.iter().fold(0.0f64, |m, a| m.max(a.abs()));
            if big == 0.0 || !big.is_finite() {
                return big;
            }
            big * v.iter().map(|a| (a / big) * (a / big)).sum::<f64>().sqrt()
        };
        let res = norm(&mut free.iter().map(|&f| fint[f] - fext[f]));
        let active = |f: &usize| self.asm.numbering.is_active(*f);
        let scale = norm(&mut (0..nfull).filter(active).map(|f| fext[f]))
            .max(norm(&mut (0..nfull).filter(active).map(|f| fint[f])));
        let residual = if scale > 0.0 { res / scale } else { res };
        if !residual.is_finite() {
            return Err(LinearError::Singular(
                "the solution is not finite: the stiffness is singular".into(),
            ));
        }
        Ok(LinearSolution { u, fint, residual })
    }

    /// The Gauss-point states of `u` ([`linear_stresses`]).
    pub fn stresses(&self, u: &[f64]) -> Result<Vec<PointState>, LinearError> {
        linear_stresses(&self.asm, u).map_err(LinearError::Cell)
    }
}

/// The alarm of STOP_SINGULIER='NON' when a pivot lost NPREC decimals or
/// more: code_aster goes on with the solution, which is then unreliable.
pub fn singularity_alarm(
    nb: &crate::nonlinear::dofs::DofNumbering,
    w: crate::solver::WorstPivot,
    check: SingularityCheck,
) -> String {
    format!(
        "alarm: the matrix is singular or nearly: {} decimals lost at the pivot of {} (SOLVEUR NPREC = {}); \
         STOP_SINGULIER='NON' keeps the solution, which may be wrong (a missing support, or a zero-energy \
         mode of under-integrated elements)",
        crate::solver::fmt_decimals(w.decimals()),
        nb.equation_name(w.unknown),
        check.limit.unwrap_or(8)
    )
}
