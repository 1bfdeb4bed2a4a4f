//! One time step: Newmark/HHT predictor, Newton iterations on the
//! displacement increment, residual norms and convergence criteria
//! (semantics.md §8.4, §8.5).
//!
//! Residual on every active dof (full vectors):
//! R = w_i M a + F_int(u) − F_ext + w_p (F_int − F_ext)_n [+ contact],
//! with w_i, w_p the scheme's weights (1, 0 for Newmark). At imposed dofs
//! R is balanced by the support reaction λ = −R; the free dofs are the
//! equations. The iteration matrix is K_T + M/(β Δt²) (divided by 1+α for
//! full HHT), on the free equations.

use super::assembly::{Assembler, CellFailure};
use super::damping::Rayleigh;
use super::dofs::DofNumbering;
use crate::element::{ElementFailure, PointState};
use crate::law::TangentKind;
use crate::solver::{DirectLu, LinearSolver, SparseMatrix};
use crate::time::{Kinematics as Motion, Scheme};

/// NEWTON keywords.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonSettings {
    /// MATRICE: `Consistent` (TANGENTE) or `Elastic` (ELASTIQUE).
    pub matrix: TangentKind,
    /// PREDICTION (TANGENTE or ELASTIQUE; absent: MATRICE's): the matrix
    /// of the prediction, the iterations then use `matrix` (an elastic
    /// prediction lets a fully plastic point unload without the Newton
    /// cycle a plastic tangent prediction can start).
    pub prediction: TangentKind,
    /// Reassemble at the prediction every `reac_incr` steps (0: never).
    pub reac_incr: usize,
    /// Reassemble every `reac_iter` iterations (0: keep the prediction's).
    pub reac_iter: usize,
    /// MATR_RIGI_SYME='OUI': use (K + Kᵀ)/2.
    pub symmetrize: bool,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            matrix: TangentKind::Consistent,
            prediction: TangentKind::Consistent,
            reac_incr: 1,
            reac_iter: 1,
            symmetrize: false,
        }
    }
}

/// CONVERGENCE keywords (all criteria given must hold).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvergenceSettings {
    pub resi_glob_rela: Option<f64>,
    pub resi_glob_maxi: Option<f64>,
    pub iter_glob_maxi: usize,
    /// ARRET='NON' accepts a step not converged at ITER_GLOB_MAXI.
    pub arret: bool,
    /// The time list's Newton events (DEFI_LIST_INST ECHEC).
    pub events: NewtonEvents,
}

/// DEFI_LIST_INST events raised during the Newton iterations of a step
/// (code_aster's nmevdr, nmevrm), each a failure of the step that its
/// own ACTION treats.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NewtonEvents {
    /// RESI_MAXI: RESI_GLOB_MAXI above this value at an iteration.
    pub resi_maxi: Option<f64>,
    /// DIVE_RESI: RESI_GLOB_MAXI decreased at neither of the last two
    /// iterations, min(r_i, r_(i-1)) > r_(i-2).
    pub dive_resi: bool,
}

impl Default for ConvergenceSettings {
    fn default() -> Self {
        ConvergenceSettings {
            resi_glob_rela: Some(1e-6),
            resi_glob_maxi: None,
            iter_glob_maxi: 10,
            arret: true,
            events: NewtonEvents::default(),
        }
    }
}

/// The state of the structure at one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    pub t: f64,
    /// Full u, v, a.
    pub motion: Motion,
    /// Gauss-point states, element after element.
    pub points: Vec<PointState>,
    /// Internal forces of this state (full).
    pub fint: Vec<f64>,
}

/// What a contact term sees and fills at one Newton iteration.
pub struct ContactIteration<'a> {
    pub numbering: &'a DofNumbering,
    /// Current displacements (full).
    pub u: &'a [f64],
    /// The residual (full): the term adds its forces (on the F_int side).
    pub residual: &'a mut [f64],
    /// The same forces alone (full, zeroed before the call): they enter
    /// the RESI_GLOB_RELA denominator (semantics.md §8.5).
    pub force: &'a mut [f64],
    /// The iteration matrix (free equations) when it is reassembled; the
    /// pattern holds [`ContactTerm::pattern_entries`].
    pub matrix: Option<&'a mut SparseMatrix>,
    /// The last RESI_GLOB_RELA of this step (+inf before the first one):
    /// COEF_MATR_FROT applies while it is >= 1e-3.
    pub resi_glob_rela: f64,
    /// Forces (full, zeroed before the call) that the term also added to
    /// `residual` but that must stay out of the next right-hand side: the
    /// active-set multipliers are totals recomputed at every solve
    /// (liaison-unil.md §3).
    pub rhs_excluded: &'a mut [f64],
    /// Newton iteration (0: the prediction, before any solve of the step).
    pub iteration: usize,
}

/// What a term sees after each linear solve, before the fields are
/// updated: it may replace the increment (the active set of LIAISON_UNIL
/// does, code_aster's `nmunil` in `nmdepl`).
pub struct IncrementCorrection<'a> {
    pub numbering: &'a DofNumbering,
    /// Displacement before the increment (full).
    pub u: &'a [f64],
    /// The increment on the equations, as solved; the term may change it.
    pub delta: &'a mut [f64],
    /// The factorised iteration matrix (more solves with it are cheap).
    pub solver: &'a dyn LinearSolver,
    /// Newton iteration of the solve (0: the prediction).
    pub iteration: usize,
}

/// What a term sees in the prediction of a step whose imposed values
/// move (see [`ContactTerm::imposed_increment`]).
pub struct ImposedIncrement<'a> {
    pub numbering: &'a DofNumbering,
    /// The committed displacement (full): where the tangent is taken.
    pub u_start: &'a [f64],
    /// The increment of the imposed dofs (full, 0 at free dofs).
    pub du: &'a [f64],
    /// The prediction's matrix (free equations, then the term's unknowns).
    pub matrix: &'a mut SparseMatrix,
    /// Its right-hand side, of the matrix's order.
    pub rhs: &'a mut [f64],
}

/// A contact (or any extra) term of the equilibrium. This is the single
/// place where contact plugs into the Newton loop: it adds its forces to
/// the residual and its stiffness to the iteration matrix at each
/// iteration, and may ask for more iterations after convergence (a new
/// pairing: code_aster's geometric loop runs inside the Newton loop).
pub trait ContactTerm {
    /// Before the iterations of a step from `t` over `dt`; `u_start` is
    /// the committed displacement (full).
    fn begin_step(&mut self, numbering: &DofNumbering, u_start: &[f64], t: f64, dt: f64);
    /// The free-equation couplings the current pairing may fill (the
    /// engine extends the pattern when they change).
    fn pattern_entries(&self) -> &[(usize, usize)];
    /// Adds the contact forces and, when asked, the contact tangent.
    fn add(&mut self, it: ContactIteration) -> Result<(), String>;
    /// Called when Newton has converged at displacement `u` (full):
    /// `Ok(true)` accepts the step, `Ok(false)` means the term changed
    /// (e.g. re-paired) and the iterations continue; `Err` fails the step.
    fn accept(&mut self, numbering: &DofNumbering, u: &[f64]) -> Result<bool, String>;
    /// After each linear solve: may replace the increment. The default
    /// keeps it.
    fn correct(&mut self, _c: IncrementCorrection) -> Result<(), String> {
        Ok(())
    }
    /// Its part of the prediction of a step whose imposed values move
    /// ([`Engine::extend_imposed_increment`], called after
    /// [`ContactTerm::begin_step`]): a term with its own unknowns adds its
    /// tangent at the step's start to the matrix, whose order then counts
    /// them, and the opposite of its residual's change under the imposed
    /// increment to the right-hand side (free equations, then its own).
    /// The default adds nothing (LIAISON_UNIL, as code_aster's
    /// prediction); the penalised discrete contact adds its tangent at the
    /// step's start and the change of its forces (no unknowns of its own).
    fn imposed_increment(&mut self, _c: ImposedIncrement) -> Result<(), String> {
        Ok(())
    }
    /// Unknowns of the term besides the displacements (the Lagrange
    /// multipliers of continuous contact), numbered after the free
    /// equations: equation `neq + k` is the term's k-th. None by default.
    fn extra_unknowns(&self) -> usize {
        0
    }
    /// The residual of the extra equations at the last [`ContactTerm::add`].
    fn extra_residual(&self) -> &[f64] {
        &[]
    }
    /// Applies the solved correction of the extra unknowns.
    fn apply_extra(&mut self, _dx: &[f64]) {}
    /// The term's own convergence criteria (continuous contact: no status
    /// changed at the last iteration): while false, Newton goes on.
    fn settled(&self) -> bool {
        true
    }
}

/// A RESI_GLOB_RELA denominator below this fraction of the forces it is
/// the difference of is their round-off (a load carried whole by the
/// supports or stops).
const CANCELLED: f64 = 1e-9;

/// One row of the Newton table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IterationRecord {
    pub iteration: usize,
    /// RESI_GLOB_RELA (−1 when the denominator is zero).
    pub resi_rela: f64,
    pub resi_maxi: f64,
    /// The denominator of RESI_GLOB_RELA.
    pub denominator: f64,
    /// The largest of the terms the denominator is the difference of
    /// (|F_ext|, |reactions|, |contact forces|; the inertia term counts
    /// whole): a denominator at round-off of it means the supports carry
    /// the whole load, and RESI_GLOB_RELA cannot fall.
    pub denominator_scale: f64,
    /// The forces the step's displacement strains the model by, of order
    /// max |iteration matrix| × max |u − u_n|: a denominator and a
    /// [`Self::denominator_scale`] both at round-off of it mean that no
    /// load, reaction or contact force acts (a rigid motion imposed by
    /// DDL_IMPO before a stop is reached), and RESI_GLOB_RELA cannot fall.
    pub motion_scale: f64,
    /// RESI_GLOB_RELA replaced by RESI_GLOB_MAXI for this step.
    pub swapped: bool,
    /// The matrix was reassembled for the correction that follows.
    pub matrix_updated: bool,
}

/// A converged (or accepted) step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepReport {
    /// Index of the last row of the Newton table (prediction = 0).
    pub iterations: usize,
    pub resi_rela: f64,
    pub resi_maxi: f64,
    pub swapped: bool,
    /// ARRET='NON' accepted a step that did not converge.
    pub not_converged: bool,
    pub history: Vec<IterationRecord>,
    /// The deepest cell folded at a node of the converged state (cell,
    /// mesh node, det F): the alarm's matter.
    pub fold: Option<(usize, usize, f64)>,
}

/// Why a step failed: the time-step controller may cut it.
#[derive(Debug, Clone, PartialEq)]
pub enum StepFailure {
    NotConverged {
        history: Vec<IterationRecord>,
    },
    Element(CellFailure),
    Singular(String),
    NonFinite(String),
    Contact(String),
    /// A stop was requested (the signal's number, [`crate::interrupt`]):
    /// the step is abandoned, the committed state is what was done.
    Interrupted(i32),
    /// A Newton event of the time list (`RESI_MAXI`, `DIVE_RESI`): the
    /// event's name and what was seen.
    Event(&'static str, String),
}

impl StepFailure {
    /// A failure that no smaller step can cure (a mesh error).
    pub fn is_fatal(&self) -> bool {
        matches!(
            self,
            StepFailure::Element(CellFailure {
                failure: ElementFailure::BadGeometry { .. } | ElementFailure::StateCount { .. },
                ..
            })
        )
    }
}

impl std::fmt::Display for StepFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepFailure::NotConverged { history } => {
                write!(
                    f,
                    "Newton did not converge in {} iterations; residual history (RESI_GLOB_RELA / RESI_GLOB_MAXI):",
                    history.last().map_or(0, |r| r.iteration)
                )?;
                // The message is repeated (the step's failure line, the
                // stop, the error): a long history keeps its start and
                // its last rows, where a stall or a cycle shows.
                let n = history.len();
                for (k, r) in history.iter().enumerate() {
                    if n > 10 && (3..n - 5).contains(&k) {
                        if k == 3 {
                            write!(
                                f,
                                " [{} to {} omitted]",
                                r.iteration - 1,
                                history[n - 6].iteration - 1
                            )?;
                        }
                        continue;
                    }
                    // Labelled by code_aster's iteration index, as the
                    // Newton table (the prediction's residual is 0).
                    write!(
                        f,
                        " [{}] {:.3e} / {:.3e}",
                        r.iteration - 1,
                        r.resi_rela,
                        r.resi_maxi
                    )?;
                }
                if let Some(r) = history
                    .last()
                    .filter(|r| !r.swapped && r.denominator < CANCELLED * r.denominator_scale)
                {
                    write!(
                        f,
                        "; RESI_GLOB_RELA's denominator, max |reactions + contact forces - F_ext| = {:.3e}, is round-off of the forces it balances (up to {:.3e}): the supports or the stops carry the whole load, so RESI_GLOB_RELA stays at round-off over round-off; judge the step by RESI_GLOB_MAXI (here {:.3e}) with CONVERGENCE=_F(RESI_GLOB_MAXI=...) (code_aster's rule: RESI_GLOB_RELA gives way to RESI_GLOB_MAXI by itself only after a first converged step)",
                        r.denominator, r.denominator_scale, r.resi_maxi
                    )?;
                } else if let Some(r) = history.last().filter(|r| {
                    !r.swapped
                        && r.denominator < CANCELLED * r.motion_scale
                        && r.denominator_scale < CANCELLED * r.motion_scale
                }) {
                    write!(
                        f,
                        "; RESI_GLOB_RELA's denominator, max |reactions + contact forces - F_ext| = {:.3e}, is round-off: no load, no reaction and no contact force act in this step (the largest is {:.3e}, against forces of order {:.3e} that the step's displacement would strain the model by), as when DDL_IMPO moves the model rigidly before it reaches a stop, so RESI_GLOB_RELA stays at round-off over round-off; judge the step by RESI_GLOB_MAXI (here {:.3e}) with CONVERGENCE=_F(RESI_GLOB_MAXI=...) (code_aster's rule: RESI_GLOB_RELA gives way to RESI_GLOB_MAXI by itself only after a first converged step)",
                        r.denominator, r.denominator_scale, r.motion_scale, r.resi_maxi
                    )?;
                }
                Ok(())
            }
            StepFailure::Element(c) => write!(f, "cell M{}: {}", c.cell + 1, c.failure),
            StepFailure::Singular(m) => write!(f, "{m}"),
            StepFailure::NonFinite(m) => write!(f, "{m}"),
            StepFailure::Contact(m) => write!(f, "contact: {m}"),
            StepFailure::Interrupted(s) => write!(
                f,
                "{} received, the step is abandoned",
                crate::interrupt::name(*s)
            ),
            StepFailure::Event(name, m) => write!(f, "event {name}: {m}"),
        }
    }
}

/// The step solver: the discretization, the committed state and every
/// work array, allocated once.
pub struct Engine {
    pub asm: Assembler,
    pub scheme: Scheme,
    pub newton: NewtonSettings,
    pub conv: ConvergenceSettings,
    /// External forces (full) at the end of the step being solved (at
    /// the committed instant between steps).
    pub fext: Vec<f64>,
    /// Loads with a FONC_MULT: `fext` is re-evaluated at each step from
    /// them. `None`: `fext` is constant, as set by the caller.
    pub loads: Option<super::loads::LoadHistory>,
    pub committed: State,
    pub trial: State,
    /// Converged steps so far (REAC_INCR, the swap rule).
    pub steps_done: usize,
    /// Rayleigh damping (DYNA_NON_LINE with AMOR_ALPHA/AMOR_BETA).
    pub damping: Option<Rayleigh>,
    /// The damping force C·v of the last evaluation (full; zero without
    /// damping).
    dforce: Vec<f64>,
    resid: Vec<f64>,
    /// Contact forces of the last iteration (full).
    cforce: Vec<f64>,
    /// Of those, the part kept out of the right-hand side (full).
    excluded: Vec<f64>,
    prev_term: Vec<f64>,
    work: Vec<f64>,
    rhs: Vec<f64>,
    du: Vec<f64>,
    matrix: SparseMatrix,
    pub lu: DirectLu,
    matrix_dt: Option<f64>,
    min_denominator: Option<f64>,
    last_maxi: Option<f64>,
}

impl Engine {
    /// An engine at `initial` (whose `fint` is recomputed here).
    pub fn new(
        asm: Assembler,
        scheme: Scheme,
        newton: NewtonSettings,
        conv: ConvergenceSettings,
        initial: State,
    ) -> Engine {
        let nfull = asm.numbering.nfull();
        let neq = asm.numbering.neq();
        let matrix = SparseMatrix::zeros(asm.pattern.clone());
        Engine {
            scheme,
            newton,
            conv,
            fext: vec![0.0; nfull],
            loads: None,
            trial: initial.clone(),
            committed: initial,
            steps_done: 0,
            damping: None,
            dforce: vec![0.0; nfull],
            resid: vec![0.0; nfull],
            cforce: vec![0.0; nfull],
            excluded: vec![0.0; nfull],
            prev_term: vec![0.0; nfull],
            work: vec![0.0; nfull],
            rhs: vec![0.0; neq],
            du: vec![0.0; nfull],
            matrix,
            lu: DirectLu::new(),
            matrix_dt: None,
            min_denominator: None,
            last_maxi: None,
            asm,
        }
    }

    /// Internal forces of the committed state (a zero increment from it),
    /// then, when `solve_acceleration`, code_aster's accel0: M a₀ = F_ext −
    /// F_int(u₀) on the free dofs, a₀ = 0 on imposed ones. Returns an alarm
    /// when that solve fails (a₀ is then 0, as code_aster does).
    pub fn initialize(&mut self, solve_acceleration: bool) -> Result<Option<String>, StepFailure> {
        let c = &mut self.committed;
        self.asm
            .compute(
                &c.motion.u,
                &c.motion.u,
                &c.points,
                &mut self.trial.points,
                // Zero time: an evaluation of the stored state, in which a
                // rate-dependent law cannot flow (VMIS_JOHN_COOK: the
                // limit of infinite rate is elastic).
                0.0,
                TangentKind::None,
                &mut c.fint,
                None,
            )
            .map_err(StepFailure::Element)?;
        // C v₀: in the initial equilibrium and the first step's damping work.
        if let Some(d) = self.damping {
            d.force(
                &mut self.asm,
                &c.motion.u,
                &c.points,
                0.0,
                &c.motion.v,
                &mut self.dforce,
            )
            .map_err(StepFailure::Element)?;
        }
        if !solve_acceleration {
            return Ok(None);
        }
        let nb = &self.asm.numbering;
        for (e, &f) in nb.free.iter().enumerate() {
            self.rhs[e] = self.fext[f] - c.fint[f] - self.dforce[f];
        }
        self.matrix.values.copy_from_slice(&self.asm.mass_free);
        c.motion.a.iter_mut().for_each(|v| *v = 0.0);
        let solved = self
            .lu
            .factorize(&self.matrix)
            .and_then(|_| self.lu.solve(&mut self.rhs));
        self.matrix_dt = None;
        match solved {
            Ok(()) => {
                for (e, &f) in nb.free.iter().enumerate() {
                    c.motion.a[f] = self.rhs[e];
                }
                Ok(None)
            }
            Err(e) => Ok(Some(format!(
                "alarm: the initial acceleration could not be solved ({e}); it is set to 0"
            ))),
        }
    }

    /// The prediction of a step whose imposed values move (a DDL_IMPO
    /// under a FONC_MULT): the increment `du` of the imposed dofs is
    /// carried into the free ones by the linear solve
    /// (K(u_n) + c_M M)_ff δ = −(K(u_n) + c_M M)_fi du_i, as code_aster's
    /// prediction does with the Dirichlet increment. Without it the first
    /// iterate moves the imposed nodes alone: the elements next to them
    /// take the whole increment, far beyond yield on a plastic ramp, and
    /// Newton from there can cycle between elastic and plastic states
    /// (tests/studies/hexs8_compression.comm stalled so with HEXS8).
    ///
    /// A continuous contact's multipliers are unknowns of that solve too
    /// (its tangent at the step's start, [`ContactTerm::imposed_increment`]):
    /// code_aster's prediction solves for every dof at once. Without it the
    /// matrix, whose pattern counts the multipliers from the second step
    /// on, met a right-hand side of the displacement equations alone (the
    /// solver refused: "right-hand side of length 22 for a matrix of order
    /// 27"), and a block held by the contact alone would be singular.
    fn extend_imposed_increment<'c>(
        &mut self,
        dt: f64,
        contact: Option<&mut (dyn ContactTerm + 'c)>,
    ) -> Result<(), StepFailure> {
        let s = self.scheme;
        // The iteration matrix (1 + c_C α) K + (c_M + c_C β) M of Rayleigh
        // damping C = α K + β M (c_C its coefficient), K + c_M M without.
        let (ck, cm) = self.matrix_coefficients(dt);
        self.asm.mass_mul(&self.du, &mut self.work);
        for v in self.work.iter_mut() {
            *v *= cm;
        }
        let scaled: Vec<f64> = self.du.iter().map(|x| x * ck).collect();
        self.asm
            .tangent_action(
                &self.committed.motion.u,
                &self.committed.points,
                dt,
                &scaled,
                TangentKind::Consistent,
                &mut self.work,
            )
            .map_err(StepFailure::Element)?;
        self.asm
            .compute(
                &self.committed.motion.u,
                &self.committed.motion.u,
                &self.committed.points,
                &mut self.trial.points,
                dt,
                TangentKind::Consistent,
                &mut self.trial.fint,
                Some(&mut self.matrix),
            )
            .map_err(StepFailure::Element)?;
        if self.newton.symmetrize {
            self.matrix.symmetrize();
        }
        for (v, m) in self.matrix.values.iter_mut().zip(&self.asm.mass_free) {
            *v = ck * *v + cm * m;
        }
        // the iteration matrix must be rebuilt at the first iterate
        self.matrix_dt = None;
        let nb = &self.asm.numbering;
        let mut rhs: Vec<f64> = nb.free.iter().map(|&f| -self.work[f]).collect();
        rhs.resize(self.matrix.n(), 0.0);
        if let Some(c) = contact {
            c.imposed_increment(ImposedIncrement {
                numbering: nb,
                u_start: &self.committed.motion.u,
                du: &self.du,
                matrix: &mut self.matrix,
                rhs: &mut rhs,
            })
            .map_err(StepFailure::Contact)?;
        }
        self.lu
            .factorize(&self.matrix)
            .map_err(|e| StepFailure::Singular(self.asm.numbering.solver_failure(&e)))?;
        self.lu
            .solve(&mut rhs)
            .map_err(|e| StepFailure::Singular(self.asm.numbering.solver_failure(&e)))?;
        // The multipliers' part is dropped: they restart from 0 at every
        // step, and the first iteration finds them (contact-continue.md §3).
        self.du.iter_mut().for_each(|v| *v = 0.0);
        for (e, &f) in nb.free.iter().enumerate() {
            self.du[f] = rhs[e];
        }
        s.correct(dt, &self.du, &mut self.trial.motion);
        Ok(())
    }

    /// Solves the step from the committed state over `dt` into `trial`.
    /// `on_iteration` sees each row of the Newton table with the trial
    /// state. The committed state is untouched: a failed step is rolled
    /// back by simply not calling [`Engine::commit`].
    pub fn solve_step(
        &mut self,
        dt: f64,
        mut contact: Option<&mut dyn ContactTerm>,
        on_iteration: &mut dyn FnMut(&IterationRecord, &State),
    ) -> Result<StepReport, StepFailure> {
        let s = self.scheme;
        self.trial.t = self.committed.t + dt;
        if let Some(h) = &self.loads {
            h.set_imposed(self.trial.t, &mut self.asm.numbering.imposed)
                .map_err(StepFailure::NonFinite)?;
        }
        s.predict(dt, &self.committed.motion, &mut self.trial.motion);
        // The contact term starts its step (pairing, statuses, multipliers)
        // before the prediction, which may need its unknowns.
        if let Some(c) = contact.as_deref_mut() {
            let nb = &self.asm.numbering;
            c.begin_step(nb, &self.committed.motion.u, self.committed.t, dt);
            if self.asm.set_extra_entries(c.pattern_entries()) {
                self.matrix = SparseMatrix::zeros(self.asm.pattern.clone());
                self.matrix_dt = None;
            }
        }
        // Imposed values the initial state does not satisfy are reached
        // in this step, through the Newmark relations.
        self.du.iter_mut().for_each(|v| *v = 0.0);
        let mut any = false;
        for &(f, val) in &self.asm.numbering.imposed {
            let d = val - self.trial.motion.u[f];
            if d != 0.0 {
                self.du[f] = d;
                any = true;
            }
        }
        if any {
            s.correct(dt, &self.du, &mut self.trial.motion);
            self.extend_imposed_increment(dt, contact.as_deref_mut())?;
        }
        let nb = &self.asm.numbering;
        let wp = s.previous_weight();
        let wi = s.inertia_weight();
        // Time-varying loads: HHT's previous-step term takes F_ext at the
        // step's start, the equilibrium at its end.
        if let Some(h) = self.loads.as_ref().filter(|h| h.varies()) {
            h.at(self.committed.t, &mut self.fext)
                .map_err(StepFailure::NonFinite)?;
        }
        for f in 0..self.prev_term.len() {
            self.prev_term[f] = wp * (self.committed.fint[f] - self.fext[f]);
        }
        if let Some(h) = self.loads.as_ref().filter(|h| h.varies()) {
            h.at(self.trial.t, &mut self.fext)
                .map_err(StepFailure::NonFinite)?;
        }
        let neq = nb.neq();
        let nx = contact.as_deref().map_or(0, |c| c.extra_unknowns());
        self.rhs.resize(neq + nx, 0.0);
        let mut history = Vec::new();
        let swap = self.steps_done > 0;
        let mut last_rela = f64::INFINITY;
        // The pattern was set before the prediction.
        let mut check_pattern = false;
        for it in 0..=self.conv.iter_glob_maxi {
            // A stop request abandons the step: an iteration of a large
            // model can take seconds, and the committed state is intact.
            if let Some(signal) = crate::interrupt::requested() {
                return Err(StepFailure::Interrupted(signal));
            }
            let mut new_pattern = false;
            if check_pattern {
                check_pattern = false;
                if let Some(c) = contact.as_deref() {
                    if self.asm.set_extra_entries(c.pattern_entries()) {
                        self.matrix = SparseMatrix::zeros(self.asm.pattern.clone());
                        self.matrix_dt = None;
                        new_pattern = true;
                    }
                }
            }
            let reassemble = new_pattern
                || if it == 0 {
                    self.matrix_dt != Some(dt)
                        || (self.newton.reac_incr > 0
                            && self.steps_done.is_multiple_of(self.newton.reac_incr))
                } else {
                    self.matrix_dt != Some(dt)
                        || (self.newton.reac_iter > 0 && it % self.newton.reac_iter == 0)
                };
            let tangent = if !reassemble {
                TangentKind::None
            } else if it == 0 {
                self.newton.prediction
            } else if self.newton.prediction != self.newton.matrix && self.newton.reac_iter == 0 {
                // REAC_ITER=0 keeps the prediction's matrix: a step whose
                // first iteration reassembles anyway (a new pattern or
                // step size) assembles that same kind.
                self.newton.prediction
            } else {
                self.newton.matrix
            };
            self.asm
                .compute(
                    &self.committed.motion.u,
                    &self.trial.motion.u,
                    &self.committed.points,
                    &mut self.trial.points,
                    dt,
                    tangent,
                    &mut self.trial.fint,
                    reassemble.then_some(&mut self.matrix),
                )
                .map_err(StepFailure::Element)?;
            if reassemble {
                if self.newton.symmetrize {
                    self.matrix.symmetrize();
                }
                let (ck, cm) = self.matrix_coefficients(dt);
                if ck == 1.0 {
                    for (v, m) in self.matrix.values.iter_mut().zip(&self.asm.mass_free) {
                        *v += cm * m;
                    }
                } else {
                    for (v, m) in self.matrix.values.iter_mut().zip(&self.asm.mass_free) {
                        *v = ck * *v + cm * m;
                    }
                }
            }
            if let Some(d) = self.damping {
                d.force(
                    &mut self.asm,
                    &self.committed.motion.u,
                    &self.committed.points,
                    dt,
                    &self.trial.motion.v,
                    &mut self.dforce,
                )
                .map_err(StepFailure::Element)?;
            }
            self.asm.mass_mul(&self.trial.motion.a, &mut self.work);
            let nb = &self.asm.numbering;
            for f in 0..self.resid.len() {
                self.resid[f] = if nb.is_active(f) {
                    wi * (self.work[f] + self.dforce[f]) + self.trial.fint[f] - self.fext[f]
                        + self.prev_term[f]
                } else {
                    0.0
                };
            }
            if let Some(c) = contact.as_deref_mut() {
                self.cforce.iter_mut().for_each(|v| *v = 0.0);
                self.excluded.iter_mut().for_each(|v| *v = 0.0);
                c.add(ContactIteration {
                    numbering: nb,
                    u: &self.trial.motion.u,
                    residual: &mut self.resid,
                    force: &mut self.cforce,
                    matrix: reassemble.then_some(&mut self.matrix),
                    resi_glob_rela: last_rela,
                    rhs_excluded: &mut self.excluded,
                    iteration: it,
                })
                .map_err(StepFailure::Contact)?;
            }
            if let Some(c) = contact.as_deref() {
                if c.extra_residual().iter().any(|v| !v.is_finite()) {
                    return Err(StepFailure::NonFinite(
                        "the residual of the contact multipliers is not finite".into(),
                    ));
                }
            }
            if let Some(f) = self.resid.iter().position(|v| !v.is_finite()) {
                return Err(StepFailure::NonFinite(format!(
                    "the residual is not finite at {}",
                    nb.dof_name(f)
                )));
            }
            if it > 0 {
                let rec = self.norms(dt, it, swap, reassemble);
                // nmresi: the first step's row 0 sets the smallest
                // denominator, converged or not.
                if self.steps_done == 0 && it == 1 {
                    self.min_denominator = Some(rec.denominator);
                }
                last_rela = rec.resi_rela;
                history.push(rec);
                on_iteration(&rec, &self.trial);
                let ok_rela = match self.conv.resi_glob_rela {
                    None => true,
                    Some(_) if rec.swapped => rec.resi_maxi <= self.last_maxi.unwrap_or(0.0),
                    Some(r) => rec.resi_rela <= r,
                };
                let ok_maxi = self.conv.resi_glob_maxi.is_none_or(|m| rec.resi_maxi <= m);
                let converged =
                    ok_rela && ok_maxi && contact.as_deref().is_none_or(|c| c.settled());
                if converged {
                    if let Some(c) = contact.as_deref_mut() {
                        let nb = &self.asm.numbering;
                        if !c
                            .accept(nb, &self.trial.motion.u)
                            .map_err(StepFailure::Contact)?
                        {
                            if it == self.conv.iter_glob_maxi {
                                return Err(StepFailure::NotConverged { history });
                            }
                            // A new pairing: the residual is re-evaluated
                            // at the same displacement before any solve.
                            check_pattern = true;
                            continue;
                        }
                    }
                }
                if converged || (it == self.conv.iter_glob_maxi && !self.conv.arret) {
                    // A cell folded between its Gauss points: the alarm's
                    // matter (nonlinear::assembly::FoldWatch).
                    let fold = self.asm.deepest_fold(&self.trial.motion.u);
                    // code_aster's nmresi: the smallest denominator is
                    // lowered by converged rows only, and not by a row
                    // converged on the swapped criterion, whose
                    // denominator is round-off (lowering it there kept a
                    // second zero-load instant from swapping); the last
                    // converged residual is kept from every converged row.
                    if converged && !rec.swapped {
                        self.min_denominator = Some(
                            self.min_denominator
                                .map_or(rec.denominator, |m| m.min(rec.denominator)),
                        );
                    }
                    if converged {
                        self.last_maxi = Some(rec.resi_maxi);
                    }
                    return Ok(StepReport {
                        iterations: it,
                        resi_rela: rec.resi_rela,
                        resi_maxi: rec.resi_maxi,
                        swapped: rec.swapped,
                        not_converged: !converged,
                        history,
                        fold,
                    });
                }
                if let Some(v) = self.conv.events.resi_maxi.filter(|v| rec.resi_maxi > *v) {
                    return Err(StepFailure::Event(
                        "RESI_MAXI",
                        format!(
                            "RESI_GLOB_MAXI = {:.3e} at iteration {} exceeds the event's RESI_GLOB_MAXI = {v:e}",
                            rec.resi_maxi,
                            it - 1
                        ),
                    ));
                }
                if self.conv.events.dive_resi && history.len() >= 3 {
                    let r: Vec<f64> = history[history.len() - 3..]
                        .iter()
                        .map(|h| h.resi_maxi)
                        .collect();
                    if r[1].min(r[2]) > r[0] {
                        return Err(StepFailure::Event(
                            "DIVE_RESI",
                            format!(
                                "RESI_GLOB_MAXI {:.3e}, {:.3e}, {:.3e} at iterations {}..{}: it decreased at neither of the last two",
                                r[0],
                                r[1],
                                r[2],
                                it - 3,
                                it - 1
                            ),
                        ));
                    }
                }
                if it == self.conv.iter_glob_maxi {
                    return Err(StepFailure::NotConverged { history });
                }
            }
            if reassemble {
                self.lu
                    .factorize(&self.matrix)
                    .map_err(|e| StepFailure::Singular(self.asm.numbering.solver_failure(&e)))?;
                self.matrix_dt = Some(dt);
            }
            let nb = &self.asm.numbering;
            for (e, &f) in nb.free.iter().enumerate() {
                self.rhs[e] = -(self.resid[f] - self.excluded[f]);
            }
            if let Some(c) = contact.as_deref() {
                for (r, x) in self.rhs[neq..].iter_mut().zip(c.extra_residual()) {
                    *r = -x;
                }
            }
            self.lu
                .solve(&mut self.rhs)
                .map_err(|e| StepFailure::Singular(self.asm.numbering.solver_failure(&e)))?;
            if let Some(c) = contact.as_deref_mut() {
                c.correct(IncrementCorrection {
                    numbering: nb,
                    u: &self.trial.motion.u,
                    delta: &mut self.rhs,
                    solver: &self.lu,
                    iteration: it,
                })
                .map_err(StepFailure::Contact)?;
                c.apply_extra(&self.rhs[neq..]);
            }
            self.du.iter_mut().for_each(|v| *v = 0.0);
            for (e, &f) in nb.free.iter().enumerate() {
                self.du[f] = self.rhs[e];
            }
            s.correct(dt, &self.du, &mut self.trial.motion);
        }
        unreachable!("the loop returns at it == iter_glob_maxi")
    }

    /// RESI_GLOB_MAXI over the free dofs and RESI_GLOB_RELA with the
    /// denominator of semantics.md §8.5: the largest of |λ_i + c_i − F_ext,i|
    /// (λ the reaction, −R at imposed dofs, 0 elsewhere; c the discrete
    /// contact forces) and of the
    /// reference inertia |M v_{n+1}|_i/(β Δt) (absent in quasi-statics).
    fn norms(&mut self, dt: f64, it: usize, swap_allowed: bool, updated: bool) -> IterationRecord {
        let nb = &self.asm.numbering;
        let mut maxi: f64 = 0.0;
        for &f in &nb.free {
            maxi = maxi.max(self.resid[f].abs());
        }
        let mut denom: f64 = 0.0;
        let mut scale: f64 = 0.0;
        // λ_i + c_i − F_ext,i, with λ = −R at imposed dofs (R holds the
        // contact forces c) and λ = 0 at free ones.
        for &f in &nb.free {
            denom = denom.max((self.cforce[f] - self.fext[f]).abs());
            scale = scale.max(self.cforce[f].abs()).max(self.fext[f].abs());
        }
        for &(f, _) in &nb.imposed {
            denom = denom.max((-self.resid[f] + self.cforce[f] - self.fext[f]).abs());
            scale = scale
                .max(self.resid[f].abs())
                .max(self.cforce[f].abs())
                .max(self.fext[f].abs());
        }
        // Quasi-static (STAT_NON_LINE): no inertia term, code_aster's
        // denominator is the reactions and loads alone.
        if self.scheme.inertia {
            self.asm.mass_mul(&self.trial.motion.v, &mut self.work);
            let inv = 1.0 / (self.scheme.beta * dt);
            for f in 0..self.work.len() {
                denom = denom.max(self.work[f].abs() * inv);
            }
            scale = scale.max(denom);
        }
        // Only the failure message reads it (no value of it decides).
        let stiffness = self
            .matrix
            .values
            .iter()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let moved = self
            .trial
            .motion
            .u
            .iter()
            .zip(&self.committed.motion.u)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        let swapped = swap_allowed
            && self.conv.resi_glob_rela.is_some()
            && self.min_denominator.is_some_and(|m| denom <= 1e-6 * m);
        IterationRecord {
            iteration: it,
            resi_rela: if denom > 0.0 { maxi / denom } else { -1.0 },
            resi_maxi: maxi,
            denominator: denom,
            denominator_scale: scale,
            motion_scale: stiffness * moved,
            swapped,
            matrix_updated: updated,
        }
    }

    /// Accepts the trial state as the new committed state. A swap: the
    /// trial then holds the state committed before, which the explicit
    /// loop's energy balance reads as the step's start.
    pub fn commit(&mut self) {
        std::mem::swap(&mut self.committed, &mut self.trial);
        self.steps_done += 1;
    }

    /// The factors of K and M in the iteration matrix: (1, c_M) without
    /// damping, (1 + c_C α, c_M + c_C β) with Rayleigh damping α K + β M
    /// (c_C = γ/(β Δt), divided by 1 + α for full HHT, as c_M).
    fn matrix_coefficients(&self, dt: f64) -> (f64, f64) {
        let s = self.scheme;
        let cm = s.mass_coefficient(dt);
        match self.damping {
            Some(d) if s.inertia => {
                let cc = s.damping_coefficient(dt);
                (1.0 + cc * d.stiffness, cm + cc * d.mass)
            }
            _ => (1.0, cm),
        }
    }

    /// The damping force C·v of the last evaluation (full; zero without
    /// Rayleigh damping).
    pub fn damping_force(&self) -> &[f64] {
        &self.dforce
    }

    /// The contact forces of the last evaluation (full, on the F_int side;
    /// zero without a contact term).
    pub fn contact_force(&self) -> &[f64] {
        &self.cforce
    }

    /// The residual of the last evaluation (full; reactions at imposed dofs
    /// are its opposite).
    pub fn residual(&self) -> &[f64] {
        &self.resid
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn history(n: usize) -> Vec<IterationRecord> {
        (1..=n)
            .map(|i| IterationRecord {
                iteration: i,
                resi_rela: 1.0 / i as f64,
                resi_maxi: 2.0,
                denominator: 1.0,
                denominator_scale: 1.0,
                motion_scale: 1.0,
                swapped: false,
                matrix_updated: true,
            })
            .collect()
    }

    /// A long history keeps its first three and last five rows (the
    /// message is printed three times: it was 6 kB for 50 iterations).
    #[test]
    fn a_long_residual_history_is_shortened_in_the_middle() {
        let long = StepFailure::NotConverged {
            history: history(30),
        }
        .to_string();
        assert!(long.starts_with("Newton did not converge in 30 iterations"));
        // Rows labelled from 0 (the prediction's residual), as the table.
        for kept in [
            "[0] 1.000e0",
            "[2] 3.333e-1",
            "[3 to 24 omitted]",
            "[25] 3.846e-2",
            "[29] 3.333e-2",
        ] {
            assert!(long.contains(kept), "{kept}: {long}");
        }
        assert!(!long.contains("[9]") && !long.contains("[24]"), "{long}");
        let short = StepFailure::NotConverged {
            history: history(10),
        }
        .to_string();
        assert!(
            short.contains("[4] 2.000e-1") && !short.contains("omitted"),
            "{short}"
        );
    }

    /// A step that moves the model rigidly (DDL_IMPO before a stop is
    /// reached, probe13): loads, reactions and contact forces all at
    /// round-off, so the "supports carry the load" test (denominator
    /// against them) cannot see it; against the forces the motion would
    /// strain the model by, it can, and the message says what to do.
    #[test]
    fn a_step_without_any_force_points_to_resi_glob_maxi() {
        let mut h = history(3);
        for r in &mut h {
            r.denominator = 2.0e-11;
            r.denominator_scale = 2.2e-11;
            r.motion_scale = 5.0e4;
            r.resi_maxi = 2.9e-11;
        }
        let m = StepFailure::NotConverged { history: h.clone() }.to_string();
        assert!(
            m.contains("no load, no reaction and no contact force act in this step")
                && m.contains("CONVERGENCE=_F(RESI_GLOB_MAXI=...)"),
            "{m}"
        );
        // A step that strains the model has forces of the motion's order:
        // no hint.
        for r in &mut h {
            r.denominator = 1.0e4;
            r.denominator_scale = 1.0e4;
        }
        let m = StepFailure::NotConverged { history: h.clone() }.to_string();
        assert!(!m.contains("round-off"), "{m}");
        // The supports carrying the load keep their own message.
        for r in &mut h {
            r.denominator = 1.0e-13;
            r.denominator_scale = 2.0e-3;
        }
        let m = StepFailure::NotConverged { history: h }.to_string();
        assert!(
            m.contains("the supports or the stops carry the whole load"),
            "{m}"
        );
    }
}
