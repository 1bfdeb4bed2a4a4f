//! Rayleigh damping of the implicit schemes: C = AMOR_ALPHA·K + AMOR_BETA·M
//! (DEFI_MATERIAU/ELAS, semantics.md §4.1), switched on in DYNA_NON_LINE by
//! the presence of the coefficients.
//!
//! As in code_aster (ndnpas), the damping force C·v enters the equilibrium
//! beside the inertia, with the same weight: with full HHT both are divided
//! by 1 + α (coeamo = γ/(β Δt)/(1+α), coemas = 1/(β Δt²)/(1+α)), so the
//! damping is not part of the α-averaged forces.
//!
//! Which K: AMOR_RAYL_RIGI='TANGENTE' (code_aster's default) the tangent,
//! 'ELASTIQUE' the elastic stiffness. aster evaluates it at the start of the
//! step (the committed state), applied element by element to the current
//! velocity, so C is fixed during a step's Newton iterations and the
//! converged answer does not depend on the iterates; for an elastic body
//! the two choices and code_aster's coincide. The iteration matrix takes
//! the current tangent for K (only the convergence rate depends on it).
//!
//! In explicit dynamics (DIFF_CENT, TCHAMWA) the force is C·v* of the
//! predicted velocity, on the right-hand side of M a = r (code_aster's
//! explicit step, notes/explicit.md §2), with the mass of the run (the
//! lumped one under MASS_DIAG='OUI') and K as above; it lowers the critical
//! step by √(1 + ξ²) − ξ (`time::explicit::damped_step_factor`).
//!
//! Limit (refused where the study is read, not ignored): one pair
//! (AMOR_ALPHA, AMOR_BETA) for the whole model (a per-material C needs the
//! element mass matrices, which the assembler does not keep).

use super::assembly::{Assembler, CellFailure};
use super::team::Team;
use crate::element::PointState;
use crate::law::TangentKind;

/// The damping coefficients of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rayleigh {
    /// AMOR_ALPHA: the factor of the stiffness.
    pub stiffness: f64,
    /// AMOR_BETA: the factor of the mass.
    pub mass: f64,
    /// The stiffness of C: [`TangentKind::Consistent`] ('TANGENTE') or
    /// [`TangentKind::Elastic`] ('ELASTIQUE').
    pub kind: TangentKind,
}

impl Rayleigh {
    /// The damping ratio ξ = (α ω + β/ω)/2 that C gives the mode ω of
    /// K x = ω² M x.
    pub fn ratio(&self, w: f64) -> f64 {
        0.5 * (self.stiffness * w + self.mass / w)
    }

    /// C·v into `out` (full, overwritten), K evaluated at the state
    /// (`u_n`, `states_n`) over a step `dt`.
    pub fn force(
        &self,
        asm: &mut Assembler,
        u_n: &[f64],
        states_n: &[PointState],
        dt: f64,
        v: &[f64],
        out: &mut [f64],
    ) -> Result<(), CellFailure> {
        asm.mass_mul(v, out);
        out.iter_mut().for_each(|x| *x *= self.mass);
        self.add_stiffness_part(asm, None, (u_n, states_n), dt, v, out)
    }

    /// The explicit step's C·v: the lumped mass `diag` (the assembled mass
    /// is that diagonal; a product dof by dof gives the same numbers
    /// without a pass over the sparse pattern) and the elements' tangents
    /// on the explicit loop's `team`.
    #[allow(clippy::too_many_arguments)]
    pub fn force_explicit(
        &self,
        asm: &mut Assembler,
        team: &Team,
        diag: Option<&[f64]>,
        (u_n, states_n): (&[f64], &[PointState]),
        dt: f64,
        v: &[f64],
        out: &mut [f64],
    ) -> Result<(), CellFailure> {
        match diag {
            Some(m) => {
                for ((o, &x), &mf) in out.iter_mut().zip(v).zip(m) {
                    *o = (mf * x) * self.mass;
                }
            }
            None => {
                asm.mass_mul(v, out);
                out.iter_mut().for_each(|x| *x *= self.mass);
            }
        }
        self.add_stiffness_part(asm, Some(team), (u_n, states_n), dt, v, out)
    }

    /// out += α K v, K the tangent or elastic stiffness at (u_n, states_n).
    fn add_stiffness_part(
        &self,
        asm: &mut Assembler,
        team: Option<&Team>,
        (u_n, states_n): (&[f64], &[PointState]),
        dt: f64,
        v: &[f64],
        out: &mut [f64],
    ) -> Result<(), CellFailure> {
        if self.stiffness != 0.0 {
            let scaled: Vec<f64> = v.iter().map(|x| x * self.stiffness).collect();
            asm.tangent_action_on(team, u_n, states_n, dt, &scaled, self.kind, out)?;
        }
        Ok(())
    }
}
