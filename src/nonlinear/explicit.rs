//! Explicit dynamics: DYNA_NON_LINE with SCHEMA='DIFF_CENT' or 'TCHAMWA'
//! (FORMULATION='ACCELERATION'), code_aster's predictors and correctors
//! (notes/explicit.md §3), without Newton and without factorisation when
//! the mass is lumped (MASS_DIAG='OUI'): one internal-force evaluation per
//! step, the laws called with the strain increment of the step.
//!
//! One step from (u_n, v_n, a_n), c = ½ (DIFF_CENT) or φ (TCHAMWA):
//! 1. u_{n+1} = u_n + Δt v_n + c Δt² a_n on the free dofs, the imposed value
//!    on imposed ones;
//! 2. F_int(u_{n+1}) by one element pass (the law integrates u_n → u_{n+1});
//!    penalised contact adds its forces at u_{n+1};
//! 3. a_{n+1} = M⁻¹ (F_ext − F_int − F_c) on the free dofs (a division by
//!    the lumped mass; with the consistent mass, a solve with the mass
//!    factorised once, as code_aster does when MASS_DIAG is absent);
//! 4. DIFF_CENT: v_{n+1} = v_n + ½Δt (a_n + a_{n+1}); TCHAMWA: v_{n+1} =
//!    v_n + Δt a_n (no correction);
//! 5. kinematic contact corrects a_{n+1} (and, for DIFF_CENT, v_{n+1}) so
//!    that the next predicted positions do not penetrate
//!    (`nonlinear::explicit_contact`; LIAISON_UNIL's links likewise,
//!    `nonlinear::explicit_unilateral`, both behind [`ExplicitConstraint`]).
//!
//! Imposed dofs (DDL_IMPO, constant values) are prescribed kinematically,
//! as explicit codes do (notes/explicit.md §4, Belytschko, Liu & Moran
//! ch. 6): u = the value, v = a = 0. code_aster imposes the acceleration
//! through Lagrange rows instead, so a clamped dof given an initial
//! velocity drifts there; here it holds.
//!
//! Stable step: the element eigenvalue inequality (time::explicit) bounds
//! the assembled ω_max by the largest element one, so Δt ≤ f·2/ω_max,e is
//! stable (f the scheme's factor); a contact penalty k on a node of mass m
//! adds k/m to ω² (Weyl's inequality on the scaled matrices). The bound is
//! checked against the time list once (STOP_CFL, as code_aster) and, an
//! aster extension, re-estimated on the current geometry during the run:
//! when the mesh has shrunk below the list's step, that step is cut into
//! equal sub-steps (logged), since a crushed element's limit falls with its
//! size.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use std::sync::atomic::{AtomicBool, Ordering};

use super::assembly::{Assembler, CellFailure, PARALLEL_MIN_ELEMENTS};
use super::damping::Rayleigh;
use super::dofs::{DofNumbering, NONE};
use super::dyna::{archive, store_observations, Growth, RunSummary, Stopped, TimeLoop};
use super::energy::{EnergyBalance, GIVEN_MEANING};
use super::newton::Engine;
use super::observation::{Observer, TABLE_NAME as OBSERVATION_TABLE};
use super::team::{with_team, Parts, Team};
use crate::element::{internal_forces, mass, PointState, MAX_DOFS};
use crate::law::TangentKind;
use crate::result::{ContactHistory, EvolNoli};
use crate::solver::{DirectLu, LinearSolver, SparseMatrix};
use crate::time::explicit::{
    damped_step_factor, hrz_lumped, max_eigenvalue_consistent, max_eigenvalue_warm,
    penalty_rebound_range, scaled_lumped, top_eigenpair, ExplicitScheme,
};

/// What the explicit loop needs of a contact treatment: the discrete
/// contact (`explicit_contact`, a held or a penalised deformable master) and LIAISON_UNIL
/// (`explicit_unilateral`), both aster extensions. Either enforcement
/// plugs into the same two places: the penalty adds its forces at
/// u_{n+1} to the right-hand side of a_{n+1} (and k/m to ω²); the
/// kinematic one corrects a_{n+1} (and v_{n+1}) so that the next
/// predicted positions satisfy the conditions. `t` is the instant the
/// conditions are evaluated at (LIAISON_UNIL's coefficients are functions
/// of INST); an Err is the message of a stop.
pub trait ExplicitConstraint {
    fn kinematic(&self) -> bool;
    /// The largest k/m the penalty adds to ω² (0 for the kinematic one).
    fn penalty_omega2(&self, mass: &[f64]) -> f64;
    /// Makes the links of the state `u` at `t` (pairing, coefficients).
    fn prepare(&mut self, numbering: &DofNumbering, u: &[f64], t: f64) -> Result<(), String>;
    /// How many links the state `u` violates (the last prepared links),
    /// and the deepest violation.
    fn penetrations(&self, numbering: &DofNumbering, u: &[f64]) -> (usize, f64);
    /// How many links the initial state `u` violates under the conditions
    /// of the initial instant `t0` (those of a moving LIAISON_UNIL floor
    /// differ from the first step's end, where a floor that rises into
    /// the body is the motion, not an initial violation). The discrete
    /// contact's conditions do not depend on the instant.
    fn initial_penetrations(&self, numbering: &DofNumbering, u: &[f64], _t0: f64) -> (usize, f64) {
        self.penetrations(numbering, u)
    }
    /// Whether the conditions move with the instant (LIAISON_UNIL whose
    /// coefficients are functions of INST): the obstacle then works on
    /// the model, and TRAV_LIAI holds that work besides any energy the
    /// enforcement creates.
    fn moves_with_time(&self) -> bool {
        false
    }
    /// The .mess alarm for `n` links violated at the initial state.
    fn initial_alarm(&self, n: usize, depth: f64) -> String;
    /// The penalty forces at `u` (the step's end at `t`), the step
    /// starting at `u_n`.
    fn penalty(
        &mut self,
        numbering: &DofNumbering,
        u_n: &[f64],
        u: &[f64],
        t: f64,
    ) -> Result<(), String>;
    /// The kinematic correction of the state `m` (its a, and v by
    /// `kappa`·δa) so that u + dt v + c dt² a satisfies the conditions at
    /// `t_next`; `mass` the lumped mass of each full dof.
    #[allow(clippy::too_many_arguments)]
    fn correct(
        &mut self,
        numbering: &DofNumbering,
        mass: &[f64],
        m: &mut crate::time::Kinematics,
        dt: f64,
        kappa: f64,
        c: f64,
        t_next: f64,
    ) -> Result<(), String>;
    /// The initial state's forces start the first step's trapezoid.
    fn start(&mut self);
    /// After the step of `dt` ending at the committed `u`; `w` the weight
    /// of the step's end in the scheme's velocity update
    /// (`ExplicitScheme::end_weight`), for the impulse of the forces.
    fn commit(&mut self, u: &[f64], dt: f64, w: f64);
    /// The contact forces of the last state on the F_int side, full.
    fn force_on_fint_side(&self) -> &[f64];
    fn friction_dissipation(&self) -> f64;
    /// CONT_NOEU of the committed state `u` reached from `u_start` in
    /// `dt`, where the treatment has one.
    fn cont_noeu(&self, u: &[f64], u_start: &[f64], dt: f64) -> Option<crate::result::NodalField>;
    fn cont_noeu_initial(&self) -> Option<crate::result::NodalField>;
    /// The .mess line of the end of the run.
    fn summary_line(&self) -> String;
    /// The state of the last committed step (or the initial one) that the
    /// next step reads besides the motion: archived with the step, so that
    /// a continuation restarts from it (`result::ContactHistory`).
    fn history(&self) -> ContactHistory;
    /// Takes the archived `h` at the initial state of a continuation, after
    /// that state's own preparation and correction: the stored forces add
    /// to those of a correction made now (none for the penalty, which is
    /// not evaluated there). Err (nothing taken) when `h` does not fit
    /// this contact (another numbering, zones or slave nodes).
    fn restore(&mut self, h: &ContactHistory) -> Result<(), String>;
}

/// Dofs per piece of the step's dof-wise phase (forces, acceleration,
/// velocity) on the team.
const DOF_PIECE: usize = 512;

/// The mass of one element as the step estimate uses it.
enum ElemMass {
    Lumped(Vec<f64>),
    Consistent(DMatrix<f64>),
}

/// The element critical step bound of a state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepBound {
    /// f·2/ω_max over the elements (penalty included when `with_contact`).
    pub dt: f64,
    /// The same without the contact penalty.
    pub dt_elements: f64,
    /// The mesh cell (0-based) with the largest element ω.
    pub cell: usize,
    /// Cells left out because every dof of theirs is imposed: with no free
    /// dof they carry no motion the scheme integrates (code_aster's
    /// `pascou` counts them; a held foundation finer than the body then
    /// set the step).
    pub held_cells: usize,
    /// The factor of Rayleigh damping in `dt` ([`damped_step_factor`]; 1
    /// without damping).
    pub damping_factor: f64,
}

/// The explicit integrator of one computation: the scheme, the mass and
/// the element masses of the step estimates.
pub struct Explicit {
    pub scheme: ExplicitScheme,
    /// MASS_DIAG='OUI'.
    pub lumped: bool,
    /// Lumped mass of each full dof (0 outside the model); with the
    /// consistent mass, its HRZ lumping, used by the contact only.
    pub mass: Vec<f64>,
    elem_mass: Vec<ElemMass>,
    /// Each element's top eigenvector of the last estimate (lumped mass):
    /// the warm start of the next one.
    eigvecs: Vec<DVector<f64>>,
    /// Estimates of the critical step made, and their total time (s).
    pub estimates: usize,
    pub estimate_seconds: f64,
    /// The consistent mass of the free equations, factorised once.
    solver: Option<DirectLu>,
    rhs: Vec<f64>,
    /// External forces with the reactions and contact forces of the
    /// step's start (the energy balance's trapezoid; its u and F_int are
    /// the engine's trial state after the commit).
    prev_ext: Vec<f64>,
    prev_fc: Vec<f64>,
    work: Vec<f64>,
    /// M a of the committed state (consistent mass only; the lumped
    /// product is taken dof by dof).
    ma: Vec<f64>,
    /// Zero contact forces (a run without contact), allocated once.
    zero: Vec<f64>,
    /// Rayleigh damping (AMOR_ALPHA, AMOR_BETA of the materials): the force
    /// C·v* of the predicted velocity on the right-hand side, as code_aster's
    /// explicit step (notes/explicit.md §2, §3.1).
    pub damping: Option<Rayleigh>,
    /// C·v* of the last step computed (the trial state's; after the
    /// commit, the committed state's), and of the step's start for the
    /// energy balance's trapezoid.
    dforce: Vec<f64>,
    prev_df: Vec<f64>,
    /// The predicted velocity v* of the step.
    vstar: Vec<f64>,
}

/// The explicit run's settings besides the time loop's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitSettings {
    /// STOP_CFL='OUI': the bound is enforced (list check, sub-steps when
    /// the mesh shrinks); 'NON': the list is followed as given.
    pub stop_cfl: bool,
    /// Re-estimate the bound about every this many computed steps (0:
    /// never); the interval adapts to how fast the bound moves.
    pub recheck: usize,
    /// METHODE='AUTO' (an aster extension in explicit): every step is the
    /// current bound (PAS_MAXI and the growth factor permitting), the
    /// list's instants only the instants to land on. Steps of the bound
    /// itself instead of equal cuts of each list step: a list step just
    /// above the bound costs two steps where one of the bound's would do.
    pub auto: Option<Growth>,
}

impl Explicit {
    /// Builds the masses: HRZ lumping of each element's consistent mass
    /// (`rho[cell]` the density of each mesh cell) when `lumped`, the
    /// consistent mass factorised once otherwise. With `lumped`, the
    /// assembler's mass arrays are replaced by the diagonal, so that every
    /// later use (kinetic energy, reactions) sees the mass of the run.
    pub fn new(
        asm: &mut Assembler,
        rho: &[f64],
        scheme: ExplicitScheme,
        lumped: bool,
    ) -> Result<Explicit, String> {
        let nfull = asm.numbering.nfull();
        let d = asm.numbering.ndpn;
        asm.set_conjugate_forces(true);
        asm.prepare_gather();
        let mut diag = vec![0.0; nfull];
        let mut elem_mass = Vec::with_capacity(asm.elements.len());
        let eq = &asm.numbering.eq;
        for e in &asm.elements {
            let m = mass(&e.spec, &e.coords, rho[e.cell])
                .map_err(|f| format!("cell M{}: mass matrix: {f}", e.cell + 1))?;
            // A massless cell (RHO = 0) whose dofs are all imposed moves
            // with its supports: no mass, no critical step (`step_bound`
            // skips held cells). With a free dof it would give that dof
            // no inertia in an explicit step: refused below.
            let held = e.full.iter().all(|&f| eq[f] == NONE);
            let l = if rho[e.cell] == 0.0 && held {
                Some(vec![0.0; e.full.len()])
            } else {
                hrz_lumped(&m, d)
            };
            let l = l.ok_or_else(|| {
                format!(
                    "cell M{}: the lumped (HRZ) mass is not positive (zero density or volume); an explicit scheme needs a mass at every free dof (RHO = 0 is accepted on a cell whose dofs are all imposed)",
                    e.cell + 1
                )
            })?;
            for (k, &f) in e.full.iter().enumerate() {
                diag[f] += l[k];
            }
            elem_mass.push(if lumped {
                ElemMass::Lumped(l)
            } else {
                ElemMass::Consistent(m)
            });
        }
        let mut solver = None;
        if lumped {
            let mf = &mut asm.mass_full;
            let pat = mf.pattern.clone();
            for j in 0..pat.n {
                for k in pat.col_ptr[j]..pat.col_ptr[j + 1] {
                    mf.values[k] = if pat.row_idx[k] == j { diag[j] } else { 0.0 };
                }
            }
            let nb = &asm.numbering;
            let pat = asm.pattern.clone();
            for j in 0..pat.n {
                for k in pat.col_ptr[j]..pat.col_ptr[j + 1] {
                    asm.mass_free[k] = if pat.row_idx[k] == j && j < nb.neq() {
                        diag[nb.free[j]]
                    } else {
                        0.0
                    };
                }
            }
        } else {
            let mut m = SparseMatrix::zeros(asm.pattern.clone());
            m.values.copy_from_slice(&asm.mass_free);
            let mut lu = DirectLu::new();
            lu.factorize(&m)
                .map_err(|e| format!("the consistent mass cannot be factorised: {e}"))?;
            solver = Some(lu);
        }
        Ok(Explicit {
            scheme,
            lumped,
            mass: diag,
            eigvecs: vec![DVector::zeros(0); elem_mass.len()],
            estimates: 0,
            estimate_seconds: 0.0,
            elem_mass,
            solver,
            rhs: vec![0.0; asm.numbering.neq()],
            prev_ext: vec![0.0; nfull],
            prev_fc: vec![0.0; nfull],
            work: vec![0.0; nfull],
            ma: vec![0.0; nfull],
            zero: vec![0.0; nfull],
            damping: None,
            dforce: vec![0.0; nfull],
            prev_df: vec![0.0; nfull],
            vstar: Vec::new(),
        })
    }

    /// The element bound of the critical step at the state (`u`, `points`):
    /// each element's elastic stiffness there (finite-strain elements on
    /// their current geometry) against its mass; `contact_omega2` is the
    /// contact penalty's k/m (0 without).
    pub fn step_bound(
        &mut self,
        asm: &Assembler,
        u: &[f64],
        points: &[PointState],
        contact_omega2: f64,
    ) -> Result<StepBound, CellFailure> {
        let started = std::time::Instant::now();
        let laws = &asm.laws;
        let first = self.estimates == 0;
        let eq = &asm.numbering.eq;
        let held = |e: &super::assembly::ElementData| e.full.iter().all(|&f| eq[f] == NONE);
        let per: Vec<Result<f64, CellFailure>> = asm
            .elements
            .par_iter()
            .zip(&self.elem_mass)
            .zip(self.eigvecs.par_iter_mut())
            .map(|((e, m), x)| {
                if held(e) {
                    return Ok(0.0);
                }
                let n = e.full.len();
                let mut lu = [0.0; MAX_DOFS];
                for k in 0..n {
                    lu[k] = u[e.full[k]];
                }
                let fail = |failure| CellFailure {
                    cell: e.cell,
                    failure,
                };
                let r = internal_forces(
                    &e.spec,
                    e.kin,
                    &e.coords,
                    &lu[..n],
                    &lu[..n],
                    &points[e.state_offset..e.state_offset + e.npg],
                    laws[e.law].law_ref(),
                    0.0,
                    TangentKind::Elastic,
                )
                .map_err(fail)?;
                let Some(k) = r.stiffness else {
                    return Ok(0.0);
                };
                Ok(match m {
                    // The first estimate (the CFL check of the list) is the
                    // exact decomposition; the run's re-estimates start
                    // from its eigenvectors. The power iteration's upper
                    // estimate is at or above the top eigenvalue when its
                    // vector is the top mode's; below it, the vector is a
                    // lower mode's and would stay one (`top_eigenpair`):
                    // the top eigenvector replaces it.
                    ElemMass::Lumped(l) if first => {
                        let a = scaled_lumped(&k, l);
                        let (w, top) = top_eigenpair(&a);
                        let warm = max_eigenvalue_warm(&a, x, 1e-3);
                        if warm < w {
                            *x = top;
                        }
                        warm.max(w)
                    }
                    ElemMass::Lumped(l) => max_eigenvalue_warm(&scaled_lumped(&k, l), x, 1e-3),
                    ElemMass::Consistent(mc) => {
                        max_eigenvalue_consistent(&k, mc).unwrap_or(f64::INFINITY)
                    }
                })
            })
            .collect();
        let (mut w2, mut cell) = (0.0f64, asm.elements.first().map_or(0, |e| e.cell));
        for (e, r) in asm.elements.iter().zip(per) {
            let v = r?;
            if v > w2 {
                w2 = v;
                cell = e.cell;
            }
        }
        self.estimates += 1;
        self.estimate_seconds += started.elapsed().as_secs_f64();
        let f = self.scheme.stability_factor().unwrap_or(0.0);
        let damping = self.damping;
        let dt_of = |w2: f64| {
            if w2 > 0.0 {
                let w = w2.sqrt();
                f * 2.0 / w * damping.map_or(1.0, |d| damped_step_factor(d.ratio(w)))
            } else {
                f64::INFINITY
            }
        };
        let wt = (w2 + contact_omega2).sqrt();
        Ok(StepBound {
            dt: dt_of(w2 + contact_omega2),
            dt_elements: dt_of(w2),
            cell,
            held_cells: asm.elements.iter().filter(|e| held(e)).count(),
            damping_factor: match damping {
                Some(d) if wt > 0.0 => damped_step_factor(d.ratio(wt)),
                _ => 1.0,
            },
        })
    }

    /// The initial acceleration when ETAT_INIT gives none (code_aster's
    /// accel0): a₀ = M⁻¹(F_ext − F_int(u₀) − F_c) on the free dofs, with
    /// the state's internal forces already computed (`Engine::initialize`).
    pub fn initial_acceleration(&mut self, engine: &mut Engine, fc: &[f64]) -> Result<(), String> {
        let st = &engine.committed;
        let nb = &engine.asm.numbering;
        // C v₀ (`Engine::initialize` computed it; zero without damping).
        let d = engine.damping_force();
        for (e, &f) in nb.free.iter().enumerate() {
            self.rhs[e] = engine.fext[f] - st.fint[f] - fc[f] - d[f];
        }
        self.solve_into(&mut engine.committed.motion.a, &engine.asm)
    }

    /// a = M⁻¹ rhs on the free dofs, 0 elsewhere.
    fn solve_into(&mut self, a: &mut [f64], asm: &Assembler) -> Result<(), String> {
        let nb = &asm.numbering;
        if let Some(lu) = &self.solver {
            lu.solve(&mut self.rhs)
                .map_err(|e| format!("the mass solve failed: {e}"))?;
            a.iter_mut().for_each(|x| *x = 0.0);
            for (e, &f) in nb.free.iter().enumerate() {
                a[f] = self.rhs[e];
            }
        } else {
            a.iter_mut().for_each(|x| *x = 0.0);
            for (e, &f) in nb.free.iter().enumerate() {
                a[f] = self.rhs[e] / self.mass[f];
            }
        }
        // A force too large for its node's mass (the rhs itself finite:
        // the loads are checked): named here, before the predictor turns
        // it into a non-finite displacement an element would report.
        match nb.free.iter().find(|&&f| !a[f].is_finite()) {
            Some(&f) => Err(format!(
                "the acceleration is not finite at {} (a = {}, lumped mass {:e}): a force there is too large for the node's mass (F/M overflows): look at the loads and their FONC_MULT at that node",
                nb.dof_name(f),
                a[f],
                self.mass[f]
            )),
            None => Ok(()),
        }
    }

    /// Imposed dofs take their value; a held one (a constant value) gets
    /// v = a = 0 (the clamp holds it), a driven one (under a FONC_MULT or
    /// a function of INST) keeps the initial velocity of the state, which
    /// the step's first mean velocity Δu/Δt then follows (it was set to 0
    /// as well: a support moving with the body at V lost V at t₀, and
    /// Rayleigh damping braked the body; the kinetic energy at t₀ missed
    /// its nodes). Returns how many held dofs had a nonzero velocity.
    pub fn impose_initial(&self, engine: &mut Engine) -> usize {
        let n = engine.asm.numbering.imposed.len();
        let driven = engine
            .loads
            .as_ref()
            .map_or_else(|| vec![false; n], |h| h.driven(n));
        let st = &mut engine.committed;
        let mut moved = 0;
        for (&(f, val), &driven) in engine.asm.numbering.imposed.iter().zip(&driven) {
            st.motion.u[f] = val;
            st.motion.a[f] = 0.0;
            if driven {
                continue;
            }
            if st.motion.v[f] != 0.0 {
                moved += 1;
            }
            st.motion.v[f] = 0.0;
        }
        moved
    }

    /// One step of `dt` from `engine.committed` into `engine.trial`
    /// (not committed). Penalised contact adds its forces at u_{n+1}.
    pub fn step(
        &mut self,
        engine: &mut Engine,
        dt: f64,
        contact: Option<&mut (dyn ExplicitConstraint + '_)>,
        team: &Team,
    ) -> Result<(), String> {
        let c = self.scheme.displacement_coefficient();
        let Engine {
            asm,
            committed: cm,
            trial: tr,
            fext,
            loads,
            ..
        } = engine;
        tr.t = cm.t + dt;
        // a_{n+1} balances the loads at t_{n+1}.
        if let Some(h) = loads.as_ref().filter(|h| h.varies()) {
            h.at(tr.t, fext)?;
            h.set_imposed(tr.t, &mut asm.numbering.imposed)?;
        }
        let nb = &asm.numbering;
        let n = cm.motion.u.len();
        tr.motion.u.resize(n, 0.0);
        tr.motion.v.resize(n, 0.0);
        tr.motion.a.resize(n, 0.0);
        for &f in &nb.free {
            tr.motion.u[f] = cm.motion.u[f] + dt * cm.motion.v[f] + c * dt * dt * cm.motion.a[f];
        }
        for &(f, val) in &nb.imposed {
            tr.motion.u[f] = val;
        }
        // C·v*, with K of the step's start: computed before the step's
        // element pass, whose buffers the internal forces are assembled
        // from below.
        if let Some(d) = self.damping {
            let kv = match self.scheme {
                ExplicitScheme::DiffCent => 0.5 * dt,
                ExplicitScheme::Tchamwa { .. } => dt,
            };
            self.vstar.clear();
            self.vstar.extend(
                cm.motion
                    .v
                    .iter()
                    .zip(&cm.motion.a)
                    .map(|(v, a)| v + kv * a),
            );
            d.force_explicit(
                asm,
                team,
                self.lumped.then_some(&self.mass[..]),
                (&cm.motion.u, &cm.points),
                dt,
                &self.vstar,
                &mut self.dforce,
            )
            .map_err(|f| format!("cell M{}: damping: {}", f.cell + 1, f.failure))?;
        }
        asm.integrate_explicit(
            team,
            &cm.motion.u,
            &tr.motion.u,
            &cm.points,
            &mut tr.points,
            dt,
        )
        .map_err(|f| format!("cell M{}: {}", f.cell + 1, f.failure))?;
        let asm: &Assembler = asm;
        let nb = &asm.numbering;
        let fc: &[f64] = match contact {
            Some(ct) if !ct.kinematic() => {
                ct.penalty(nb, &cm.motion.u, &tr.motion.u, tr.t)?;
                ct.force_on_fint_side()
            }
            // No contact force: the same sums with a zero term.
            _ => &self.zero,
        };
        tr.fint.resize(n, 0.0);
        // Set when a free dof's u + a is not finite (found again in the
        // order of the free dofs below, for the message).
        let diverged = AtomicBool::new(false);
        if self.solver.is_none() {
            // The lumped mass: each range of dofs assembles its forces,
            // then the right-hand side, the division by the mass and the
            // velocity update of each free dof (the expressions of the
            // consistent-mass branch below), in one pass on the team.
            let pieces = Parts::new(
                tr.fint
                    .chunks_mut(DOF_PIECE)
                    .zip(tr.motion.a.chunks_mut(DOF_PIECE))
                    .zip(tr.motion.v.chunks_mut(DOF_PIECE)),
            );
            let (m, a_n, v_n, u, eq, df) = (
                &self.mass,
                &cm.motion.a,
                &cm.motion.v,
                &tr.motion.u,
                &nb.eq,
                &self.dforce,
            );
            let diff_cent = matches!(self.scheme, ExplicitScheme::DiffCent);
            let fext: &[f64] = fext;
            team.for_each(pieces.len(), &|i| {
                let ((fint, a), v) = pieces.take(i);
                let first = i * DOF_PIECE;
                asm.assemble_forces(first, fint);
                let mut finite = true;
                for (k, (a, v)) in a.iter_mut().zip(v.iter_mut()).enumerate() {
                    let f = first + k;
                    if eq[f] == NONE {
                        *a = 0.0;
                        continue;
                    }
                    let rhs = fext[f] - fint[k] - fc[f] - df[f];
                    *a = rhs / m[f];
                    *v = if diff_cent {
                        v_n[f] + 0.5 * dt * (a_n[f] + *a)
                    } else {
                        v_n[f] + dt * a_n[f]
                    };
                    finite &= (u[f] + *a).is_finite();
                }
                if !finite {
                    diverged.store(true, Ordering::Relaxed);
                }
            });
        } else {
            let pieces = Parts::new(tr.fint.chunks_mut(DOF_PIECE));
            team.for_each(pieces.len(), &|i| {
                asm.assemble_forces(i * DOF_PIECE, pieces.take(i));
            });
            for (e, &f) in nb.free.iter().enumerate() {
                self.rhs[e] = fext[f] - tr.fint[f] - fc[f] - self.dforce[f];
            }
            self.solve_into(&mut tr.motion.a, asm)?;
            match self.scheme {
                ExplicitScheme::DiffCent => {
                    for &f in &nb.free {
                        tr.motion.v[f] =
                            cm.motion.v[f] + 0.5 * dt * (cm.motion.a[f] + tr.motion.a[f]);
                    }
                }
                ExplicitScheme::Tchamwa { .. } => {
                    for &f in &nb.free {
                        tr.motion.v[f] = cm.motion.v[f] + dt * cm.motion.a[f];
                    }
                }
            }
            diverged.store(true, Ordering::Relaxed);
        }
        // An imposed dof that moved over the step (a DDL_IMPO under a
        // FONC_MULT, or an initial state off its imposed value) moves at the
        // step's mean velocity, exact for a ramp, with the backward
        // difference of the velocities as acceleration (the support force
        // M a + F_int − F_ext then includes the impulse that sets the
        // node's mass moving); a held one has v = a = 0. Without this the
        // driven nodes showed VITE 0 and their kinetic energy was missing.
        for &(f, val) in &nb.imposed {
            let du = val - cm.motion.u[f];
            if du == 0.0 {
                tr.motion.v[f] = 0.0;
                tr.motion.a[f] = 0.0;
            } else {
                tr.motion.v[f] = du / dt;
                tr.motion.a[f] = (tr.motion.v[f] - cm.motion.v[f]) / dt;
            }
        }
        let diverged = diverged.into_inner();
        if let Some((f, x)) = nb
            .free
            .iter()
            .filter(|_| diverged)
            .map(|&f| (f, tr.motion.u[f] + tr.motion.a[f]))
            .find(|(_, x)| !x.is_finite())
        {
            // A force too large for its node's mass overflows at once; a
            // step above the stable one grows over many steps (and is
            // usually stopped earlier by the runaway test of the balance).
            let (fe, fi) = (fext[f], tr.fint[f]);
            let cause = if !(fe / self.mass[f]).is_finite() || !(fi / self.mass[f]).is_finite() {
                "a force there is too large for the node's mass (F/M overflows): look at the loads and their FONC_MULT at that node"
            } else {
                "the step exceeds the stability limit (STOP_CFL='NON' lets such a step run) or a cell has degenerated"
            };
            return Err(format!(
                "the motion is not finite at {} (u + a = {x}; F_ext = {fe:e}, F_int = {fi:e} there): {cause}",
                nb.dof_name(f)
            ));
        }
        Ok(())
    }

    /// The kinematic contact correction of the trial state (its a and, for
    /// DIFF_CENT, its v) before the next step of `dt_next`; `dt_prev` is the
    /// step that led to the trial state (0 at the initial state, whose
    /// velocity is given and not corrected). The links are those of the
    /// next step's end, or of `t_links` when given.
    pub fn correct(
        &self,
        engine: &mut Engine,
        contact: &mut (dyn ExplicitConstraint + '_),
        dt_prev: f64,
        dt_next: f64,
        t_links: Option<f64>,
        state_is_trial: bool,
    ) -> Result<(), String> {
        let kappa = match self.scheme {
            ExplicitScheme::DiffCent => 0.5 * dt_prev,
            ExplicitScheme::Tchamwa { .. } => 0.0,
        };
        let c = self.scheme.displacement_coefficient();
        let st = if state_is_trial {
            &mut engine.trial
        } else {
            &mut engine.committed
        };
        let t_next = t_links.unwrap_or(st.t + dt_next);
        contact.correct(
            &engine.asm.numbering,
            &self.mass,
            &mut st.motion,
            dt_next,
            kappa,
            c,
            t_next,
        )
    }

    /// Starts the energy balance at the committed state (after the initial
    /// acceleration and correction): the trapezoid's state n.
    fn start_energy(
        &mut self,
        engine: &Engine,
        fc: &[f64],
        previous: Option<&crate::post::table::Table>,
        start: super::energy::EnergyStart,
    ) -> EnergyBalance {
        let e = EnergyBalance::new(engine, previous, start);
        self.prev_fc.copy_from_slice(fc);
        self.dforce.copy_from_slice(engine.damping_force());
        self.prev_df.copy_from_slice(engine.damping_force());
        self.external_of(engine, fc);
        self.prev_ext.copy_from_slice(&self.work);
        e
    }

    /// F_ext + λ of the committed state into `work`, without the inertia
    /// of the imposed dofs: λ the support reactions at imposed dofs,
    /// F_int + F_c + C_R v there. Their inertial part, M a, is counted by
    /// `energy_step` as the change of those dofs' kinetic energy.
    fn external_of(&mut self, engine: &Engine, fc: &[f64]) {
        let st = &engine.committed;
        self.work.copy_from_slice(&engine.fext);
        for &(f, _) in &engine.asm.numbering.imposed {
            self.work[f] = st.fint[f] + fc[f] + self.dforce[f];
        }
    }

    /// Adds the works of the step just committed (trapezoidal rule, as
    /// code_aster's nmener): internal, external with the reactions, contact.
    fn energy_step(&mut self, energy: &mut EnergyBalance, engine: &Engine, fc: &[f64]) {
        self.external_of(engine, fc);
        // The step's start is the engine's trial state: `Engine::commit`
        // swaps the two, so after it the trial holds the state committed
        // before, u and F_int as they were (the contact correction
        // changes a and v only).
        let (st, prev) = (&engine.committed, &engine.trial);
        let (mut wi, mut we, mut wc, mut wd) = (0.0, 0.0, 0.0, 0.0);
        for f in 0..st.motion.u.len() {
            let du = st.motion.u[f] - prev.motion.u[f];
            if du == 0.0 {
                continue;
            }
            wi += 0.5 * du * (prev.fint[f] + st.fint[f]);
            we += 0.5 * du * (self.prev_ext[f] + self.work[f]);
            wc += 0.5 * du * (self.prev_fc[f] + fc[f]);
            wd += 0.5 * du * (self.prev_df[f] + self.dforce[f]);
        }
        // The inertial part M a of the reactions at the imposed dofs that
        // moved: its work is v̄·M Δv, the change of their kinetic energy
        // (v̄ the step's mean velocity), not the trapezoid Δu·M(a_n +
        // a_{n+1})/2: a driven dof jumps to the step's mean velocity Δu/Δt
        // with the backward difference as acceleration, whose impulse the
        // trapezoid counted twice (once in each of the two steps it spans):
        // a bar pulled at U̇ from rest showed DISS_SCH = +½ m U̇² of its
        // driven nodes (probe15b: 1.875e-2 of TRAV_EXT 0.566, 3.3 %).
        let moved = engine.asm.numbering.imposed.iter().any(|&(f, _)| {
            st.motion.u[f] != prev.motion.u[f] || st.motion.v[f] != prev.motion.v[f]
        });
        if moved {
            if self.lumped {
                for &(f, _) in &engine.asm.numbering.imposed {
                    let (v1, v0) = (st.motion.v[f], prev.motion.v[f]);
                    we += 0.5 * (v1 + v0) * self.mass[f] * (v1 - v0);
                }
            } else {
                let dv: Vec<f64> = st
                    .motion
                    .v
                    .iter()
                    .zip(&prev.motion.v)
                    .map(|(a, b)| a - b)
                    .collect();
                engine.asm.mass_mul(&dv, &mut self.ma);
                for &(f, _) in &engine.asm.numbering.imposed {
                    we += 0.5 * (st.motion.v[f] + prev.motion.v[f]) * self.ma[f];
                }
            }
        }
        energy.internal += wi;
        energy.external += we;
        energy.contact += wc;
        energy.damping += wd;
        self.prev_fc.copy_from_slice(fc);
        if self.damping.is_some() {
            self.prev_df.copy_from_slice(&self.dforce);
        }
        // `work` is rewritten whole by the next `external_of`.
        std::mem::swap(&mut self.prev_ext, &mut self.work);
        energy.kinetic = 0.5 * self.kinetic_sum(engine);
    }

    /// Σ v·(M v) of the committed state, the lumped product dof by dof
    /// (the same terms in the same order as the sparse product over the
    /// diagonal pattern).
    fn kinetic_sum(&mut self, engine: &Engine) -> f64 {
        let v = &engine.committed.motion.v;
        if self.lumped {
            v.iter().zip(&self.mass).map(|(x, m)| x * (m * x)).sum()
        } else {
            engine.asm.mass_mul(v, &mut self.work);
            v.iter().zip(&self.work).map(|(a, b)| a * b).sum()
        }
    }
}

/// Above this ω_pen dt (ω_pen² the penalty's k/m, `penalty_omega2`) a
/// penalised contact is not energy-conserving at the accuracy of a
/// balance: one closing lasts a few steps and returns between
/// [`penalty_rebound_range`] times the energy it received, depending on
/// where in the step the contact closed (±4.5 % at 0.5, a penalty period
/// resolved by 4π ≈ 12.6 steps; 0.49 to 2.06 at 1.56). Measured on a bar
/// bouncing off a rigid wall through E_N (docs/contact.md): TRAV_LIAI
/// 3.4e-4 of EK0 = 4 at ω_pen dt = 0.45 (26 closings of 8 to 10 steps),
/// −0.051 at 1.12, −2.56 at 1.57 (18 closings of 1 or 2 steps).
pub const PENALTY_WDT_MAX: f64 = 0.5;

/// The start-of-run alarm of a penalised contact whose penalty is
/// resolved by too few steps (ω_pen `dt` above [`PENALTY_WDT_MAX`], `dt`
/// the largest step the run will take), with the contact's own bound
/// f·2/ω_pen (`factor` the scheme's f) against the elements'; None when
/// the step resolves it.
pub fn penalty_step_alarm(w2c: f64, bound: &StepBound, dt: f64, factor: f64) -> Option<String> {
    if w2c <= 0.0 || !dt.is_finite() {
        return None;
    }
    let w = w2c.sqrt();
    let wdt = w * dt;
    if wdt <= PENALTY_WDT_MAX {
        return None;
    }
    let contact = factor * 2.0 / w;
    let (lo, hi) = penalty_rebound_range(wdt.min(1.999));
    Some(format!(
        "alarm: penalised contact with a step of {dt:.4e} s, {:.3} of the contact's own bound 2/w_pen = {contact:.4e} s ({} the elements' {:.4e} s{}): w_pen dt = {wdt:.3}, a penalty period 2 pi/w_pen resolved by {:.1} steps. Penalised contact is then not energy-conserving: its force is switched on at a penetration anywhere between 0 and v dt and a closing lasts {} step(s), so a node bouncing off the penalty alone leaves with {lo:.3} to {hi:.3} times the kinetic energy it came with, depending on where in the step it closed; TRAV_LIAI below zero in the energy table is the energy the contact created. Keep w_pen dt at most {PENALTY_WDT_MAX} (a step of at most {:.4e} s) or lower E_N (or COEF_PENA) by a factor {:.3}",
        dt / contact,
        if contact < bound.dt_elements { "below" } else { "above" },
        bound.dt_elements,
        if contact < bound.dt_elements {
            ": the penalty governs the stable step"
        } else {
            ""
        },
        2.0 * std::f64::consts::PI / wdt,
        contact_steps(wdt),
        PENALTY_WDT_MAX / w,
        (PENALTY_WDT_MAX / wdt).powi(2),
    ))
}

/// The number of steps (a range "a to b") during which a node bouncing
/// off the penalty alone is in contact at `wdt` (the single-node
/// recurrence of [`penalty_rebound_range`], over the entry depth).
fn contact_steps(wdt: f64) -> String {
    let w2 = wdt * wdt;
    let (mut lo, mut hi) = (usize::MAX, 0);
    for i in 1..=100 {
        let (mut a, mut b) = (i as f64 / 100.0 - 1.0, i as f64 / 100.0);
        let mut n = 0;
        while b > 0.0 && n < 10_000 {
            let c = 2.0 * b - a - w2 * b;
            a = b;
            b = c;
            n += 1;
        }
        lo = lo.min(n);
        hi = hi.max(n);
    }
    if lo == hi {
        format!("{lo}")
    } else {
        format!("{lo} to {hi}")
    }
}

/// The alarm once a penalised contact has returned more energy than it
/// absorbed by more than 1 % of the energy given to the model (the
/// initial kinetic energy or the external work, whichever is larger): at
/// the archived instant `t`, with the last step `dt` and ω_pen² `w2c`.
/// None while the balance holds, or without penalty or energy given.
pub fn contact_energy_alarm(energy: &EnergyBalance, t: f64, dt: f64, w2c: f64) -> Option<String> {
    if w2c <= 0.0 || !energy.contact_created_energy() {
        return None;
    }
    let given = energy.given();
    let w = w2c.sqrt();
    let wdt = w * dt;
    Some(format!(
        "  alarm: at t = {t:e} the penalised contact has returned {:.4e} more energy than it absorbed (TRAV_LIAI = {:.4e}, {:.2} % of the energy given to the model, {given:.4e} = {GIVEN_MEANING}): energy created by the penalty switched on and off at the step instants (w_pen dt = {wdt:.3}; ENER_CIN is that much too high once the bodies separate, and DISS_SCH does not show it). Take a step of at most {:.4e} s (w_pen dt <= {PENALTY_WDT_MAX}) or lower E_N (or COEF_PENA) by a factor {:.3}; this alarm is given once",
        -energy.contact,
        energy.contact,
        -100.0 * energy.contact / given,
        PENALTY_WDT_MAX / w,
        (PENALTY_WDT_MAX / wdt).min(1.0).powi(2),
    ))
}

/// How many times the energy given to the model the scheme may create
/// before the run is called unstable.
const RUNAWAY: f64 = 100.0;

/// The stop of a run whose scheme creates energy without bound: a step
/// above the stable one (STOP_CFL='NON' lets it run; a cell crushed to a
/// sliver between two estimates of the bound) makes the highest mode grow
/// by a large factor per step, and the values went on to 1e160 before
/// anything overflowed. The balance error DISS_SCH of a stable explicit
/// run is a small fraction of the energy given (the trapezoid of the
/// works against the scheme's own rule, TCHAMWA's dissipation); energy
/// created beyond a hundred times the energy given (the largest of the
/// kinetic energy at the start, |TRAV_EXT| and the internal energy of the
/// initial state, [`EnergyBalance::given`]) is a runaway (this call's
/// values: a continuation is judged on its own). Not checked when the
/// model holds and is given no energy at all (u₀ = v₀ = 0 and no load).
fn runaway(energy: &EnergyBalance) -> Option<String> {
    if let Some(bad) = energy.not_finite() {
        return Some(format!(
            "the energy balance is not finite ({bad}): the motion has grown beyond what double precision can hold; the loads are far too large for the masses (look at their values and FONC_MULT), or the step is above the stable one (STOP_CFL='NON' lets such a step run)"
        ));
    }
    let v = energy.own_values();
    let created = -v[6];
    let given = energy.given();
    (given > 0.0 && created > RUNAWAY * given).then(|| {
        format!(
            "the explicit scheme is unstable: it has created {created:.4e} of energy (DISS_SCH = {:.4e}, kinetic energy {:.4e}), more than {RUNAWAY} times the energy given to the model ({given:.4e}, {GIVEN_MEANING}); the step is above the stable one (STOP_CFL='NON' lets such a step run) or a cell has degenerated",
            v[6], energy.kinetic
        )
    })
}

/// The first list step above `bound` (index of the step, its start, its
/// length), if any; equality passes, as in code_aster's `pascou`.
pub fn first_step_above(instants: &[f64], bound: f64) -> Option<(usize, f64, f64)> {
    instants
        .windows(2)
        .enumerate()
        .map(|(k, w)| (k + 1, w[0], w[1] - w[0]))
        .find(|&(_, _, dt)| dt > bound)
}

/// Steps between two checks of folded cells in the explicit loop.
const FOLD_EVERY: usize = 16;

/// Runs the explicit loop over the instants of `tl` from the engine's
/// committed state (internal forces computed; `has_acce`: ETAT_INIT gave
/// the acceleration; `history`: the contact history archived with an
/// EVOL_NOLI initial state), archiving into `result`.
#[allow(clippy::too_many_arguments)]
pub fn run(
    engine: &mut Engine,
    ex: &mut Explicit,
    contact: Option<&mut (dyn ExplicitConstraint + '_)>,
    tl: &TimeLoop,
    settings: &ExplicitSettings,
    has_acce: bool,
    history: Option<&ContactHistory>,
    result: &mut EvolNoli,
    log: &mut dyn FnMut(&str),
) -> Result<RunSummary, Stopped> {
    // The steps' parallel phases run on a team kept for the whole loop
    // (`nonlinear::team`), as many threads as the pool has; below
    // PARALLEL_MIN_ELEMENTS elements the loop is too short to share.
    let threads = if engine.asm.elements.len() >= PARALLEL_MIN_ELEMENTS {
        rayon::current_num_threads()
    } else {
        1
    };
    with_team(threads, |team| {
        run_on(
            team, engine, ex, contact, tl, settings, has_acce, history, result, log,
        )
    })
}

#[allow(clippy::too_many_arguments)]
fn run_on(
    team: &Team,
    engine: &mut Engine,
    ex: &mut Explicit,
    mut contact: Option<&mut (dyn ExplicitConstraint + '_)>,
    tl: &TimeLoop,
    settings: &ExplicitSettings,
    has_acce: bool,
    history: Option<&ContactHistory>,
    result: &mut EvolNoli,
    log: &mut dyn FnMut(&str),
) -> Result<RunSummary, Stopped> {
    let started = std::time::Instant::now();
    let mut summary = RunSummary::default();
    let nfull = engine.asm.numbering.nfull();
    let zero = vec![0.0; nfull];
    let stop = |message: String, summary: &RunSummary| Stopped {
        message,
        summary: summary.clone(),
        signal: None,
    };
    let contact_w2 = contact
        .as_deref()
        .map_or(0.0, |c| c.penalty_omega2(&ex.mass));
    let mut bound = ex
        .step_bound(
            &engine.asm,
            &engine.committed.motion.u,
            &engine.committed.points,
            contact_w2,
        )
        .map_err(|f| {
            stop(
                format!("step estimate: cell M{}: {}", f.cell + 1, f.failure),
                &summary,
            )
        })?;
    // The step plan: list instants, each reached by equal sub-steps no
    // longer than the current bound (STOP_CFL='OUI' or METHODE='AUTO'),
    // with AUTO also no longer than PAS_MAXI and the growth of the
    // previous step `prev`.
    let plan = |t: f64, target: f64, bound: &StepBound, prev: f64| -> f64 {
        let span = target - t;
        let cap = match settings.auto {
            Some(g) => {
                let c = bound.dt.min(prev * g.factor);
                g.pas_maxi.map_or(c, |m| c.min(m))
            }
            None if settings.stop_cfl => bound.dt,
            None => return span,
        };
        if span <= cap {
            return span;
        }
        span / (span / cap).ceil().max(1.0)
    };
    let mut next = 1usize;
    let first_dt = plan(tl.instants[0], tl.instants[1], &bound, f64::INFINITY);
    // The conditions of the initial state are those of the first step's
    // end, as LIAISON_UNIL's coefficients are evaluated at the step ends
    // only (t+, never at the initial instant, as code_aster).
    let t_first = engine.committed.t + first_dt;
    // A continuation's stored history is the state's own contact forces and
    // friction: the penalty is not evaluated again at the initial state (it
    // would restart the friction's predictor from zero). It only goes with
    // the stored acceleration, which those forces produced.
    let restored = history.filter(|_| has_acce);
    if let Some(ct) = contact.as_deref_mut() {
        ct.prepare(&engine.asm.numbering, &engine.committed.motion.u, t_first)
            .map_err(|m| stop(m, &summary))?;
        // An initial state that already penetrates is removed in the
        // first step (kinematic: the nodes are put back on the surface
        // within one step, i.e. at a speed depth/dt; penalty: a force
        // E_N depth), an impulse the user did not model.
        // A continuation's penetrations are the penalty's own, balanced by
        // the stored forces: no alarm there.
        let (n, depth) = ct.initial_penetrations(
            &engine.asm.numbering,
            &engine.committed.motion.u,
            engine.committed.t,
        );
        if n > 0 && restored.is_none() {
            log(&ct.initial_alarm(n, depth));
        }
        // Without a history the penalty of the initial state is evaluated
        // even when ETAT_INIT gives the acceleration: it does not change a,
        // but it starts the first step's trapezoids (impulse, TRAV_LIAI).
        if restored.is_none() && !ct.kinematic() {
            ct.penalty(
                &engine.asm.numbering,
                &engine.committed.motion.u,
                &engine.committed.motion.u,
                t_first,
            )
            .map_err(|m| stop(m, &summary))?;
        }
    }
    if !has_acce {
        let fc = contact
            .as_deref()
            .map_or(&zero[..], |c| c.force_on_fint_side());
        let fc = fc.to_vec();
        ex.initial_acceleration(engine, &fc)
            .map_err(|m| stop(m, &summary))?;
        for &(f, _) in &engine.asm.numbering.imposed {
            engine.committed.motion.a[f] = 0.0;
        }
    }
    if let Some(ct) = contact.as_deref_mut() {
        if ct.kinematic() {
            ex.correct(engine, ct, 0.0, first_dt, None, false)
                .map_err(|m| stop(m, &summary))?;
        }
        if let Some(h) = restored {
            match ct.restore(h) {
                Ok(()) => log(&format!(
                    "  continuation: the contact forces and the friction history of the initial state are those stored with it ({} nonzero force components, {} frictional links)",
                    h.force.len(),
                    h.friction.len()
                )),
                Err(why) => log(&format!(
                    "  alarm: the contact history stored with the initial state is not taken ({why}): the continuation starts its friction and the first step's contact work from zero, unlike the run in one call"
                )),
            }
        }
        ct.start();
    }
    let p0 = momentum(engine);
    let fc0 = contact
        .as_deref()
        .map_or(zero.clone(), |c| c.force_on_fint_side().to_vec());
    let mut energy = ex.start_energy(
        engine,
        &fc0,
        result.tables.get(super::energy::TABLE_NAME),
        tl.energy_start,
    );
    if archive_with_contact(engine, tl, result, contact.as_deref(), None) {
        summary.archived += 1;
        archive_line(&mut energy, result, &summary, first_dt, log);
    }
    // OBSERVATION: the initial state, then the steps that end on an
    // instant of the list (the sub-steps of the critical step are not
    // instants of the computation, as for ARCHIVAGE).
    let ndpn = engine.asm.numbering.ndpn;
    let offsets = super::fields::GaussRows::of(&engine.asm);
    let mut observer = (!tl.observations.is_empty()).then(|| {
        let mut o = Observer::new(result.tables.get(OBSERVATION_TABLE));
        o.observe(&tl.observations, &engine.committed, None, ndpn, &offsets);
        o
    });
    // SUIVI_DDL: no Newton table in explicit, so one line per instant of
    // the list (the sub-steps of the critical step are not instants of
    // the computation), from the initial state on.
    if !tl.suivi.is_empty() {
        log(&suivi_header(tl));
        log(&suivi_line(tl, &engine.committed, 0, ndpn, &offsets));
    }
    let mut dt = first_dt;
    // The length of the last step done (for CONT_NOEU's percussion).
    let mut last_dt = 0.0;
    let mut interval = settings.recheck;
    let mut next_estimate = interval;
    let mut alarmed_sub = false;
    let mut energy_alarmed = false;
    let mut folds = super::assembly::FoldWatch::default();
    let mut list_steps = 0usize;
    // A failed step (or a failed contact correction of its end state):
    // the last converged state is archived first, so that the message
    // counts what the result really keeps. The failed step overwrote the
    // trial state: GLI* of its CONT_NOEU are 0.
    macro_rules! fail {
        ($why:expr, $t0:expr, $dt:expr) => {{
            let (why, t0, dt) = ($why, $t0, $dt);
            let last = (summary.steps > 0).then_some((&engine.committed.motion.u[..], last_dt));
            if archive_with_contact(engine, tl, result, contact.as_deref(), last) {
                summary.archived += 1;
            }
            store_energy(&energy, result);
            store_observations(observer.take(), result);
            if let Some(m) = folds.summary() {
                log(&m);
            }
            let message = format!(
                "DYNA_NON_LINE stopped at the step from t = {t0:e} to t = {:e}: {why}. The {} steps archived so far (last instant {:e}) are kept in the result.",
                t0 + dt,
                result.steps.len(),
                result.steps.last().map_or(t0, |s| s.inst)
            );
            log(&message);
            summary.seconds = started.elapsed().as_secs_f64();
            crate::profile::count(crate::profile::Counter::Steps, summary.steps);
            return Err(stop(message, &summary));
        }};
    }
    while next < tl.instants.len() {
        let target = tl.instants[next];
        let t0 = engine.committed.t;
        // SIGINT/SIGTERM (crate::interrupt): stop between two steps, the
        // last state archived, as the implicit loop does.
        if let Some(signal) = crate::interrupt::requested() {
            // After a commit the trial state is the one committed before.
            let last = (summary.steps > 0).then_some((&engine.trial.motion.u[..], last_dt));
            if archive_with_contact(engine, tl, result, contact.as_deref(), last) {
                summary.archived += 1;
                archive_line(&mut energy, result, &summary, dt, log);
            }
            store_energy(&energy, result);
            store_observations(observer.take(), result);
            summary.seconds = started.elapsed().as_secs_f64();
            let message = format!(
                "DYNA_NON_LINE stopped by {} at t = {t0:e}, after {} explicit steps: the {} archived instants are kept in the result; the computation up to t = {:e} was not done.",
                crate::interrupt::name(signal),
                summary.steps,
                result.steps.len(),
                tl.instants[tl.instants.len() - 1]
            );
            log(&message);
            crate::profile::count(crate::profile::Counter::Steps, summary.steps);
            return Err(Stopped {
                message,
                summary,
                signal: Some(signal),
            });
        }
        // The penalty needs the pairing of the step's start. The kinematic
        // enforcement pairs at the end of each step (below) and before the
        // loop, on the u that is the next step's start (its correction
        // changes a and v, not u): pairing again here would give the same
        // pairing.
        if let Some(ct) = contact.as_deref_mut() {
            if !ct.kinematic() {
                let prepared =
                    ct.prepare(&engine.asm.numbering, &engine.committed.motion.u, t0 + dt);
                if let Err(why) = prepared {
                    fail!(why, t0, dt);
                }
            }
        }
        // A bound that collapsed (a cell crushed to nothing) or a PAS_MAXI
        // below the instants' resolution would loop without end.
        let outcome = if dt.is_finite() && t0 + dt > t0 {
            ex.step(engine, dt, contact.as_deref_mut(), team)
        } else {
            Err(format!(
                "the planned step {dt:e} does not advance the time (critical step bound {:e}, cell {})",
                bound.dt,
                bound.cell + 1
            ))
        };
        if let Err(why) = outcome {
            fail!(why, t0, dt);
        }
        summary.steps += 1;
        let t1 = engine.trial.t;
        let at_list = (target - t1).abs() <= 1e-9 * dt;
        // A cell folded between its Gauss points (element::fold) tangles
        // the mesh without any other sign. Checked at every list instant
        // and every FOLD_EVERY steps: every step would cost a fifth of B's
        // explicit run (measured on the 10 x 40 mesh).
        if summary.steps % FOLD_EVERY == 0 || at_list {
            folds.see(
                engine.trial.t,
                engine.asm.deepest_fold(&engine.trial.motion.u),
                log,
            );
        }
        if at_list {
            engine.trial.t = target;
            next += 1;
            list_steps += 1;
        }
        // The interval between estimates adapts: doubled (up to 8 times
        // `recheck`) while the bound moves by less than 1 % between two,
        // halved (down to `recheck`/4) when it moves by more than 4 %.
        if interval > 0 && summary.steps >= next_estimate {
            let b = ex.step_bound(
                &engine.asm,
                &engine.trial.motion.u,
                &engine.trial.points,
                contact_w2,
            );
            if let Ok(b) = b {
                let change = (b.dt - bound.dt).abs() / bound.dt;
                if change < 0.01 {
                    interval = (2 * interval).min(8 * settings.recheck);
                } else if change > 0.04 {
                    interval = (interval / 2).max(settings.recheck / 4).max(1);
                }
                bound = b;
            }
            next_estimate = summary.steps + interval;
        }
        let dt_next = if next < tl.instants.len() {
            plan(engine.trial.t, tl.instants[next], &bound, dt)
        } else {
            0.0
        };
        if settings.stop_cfl && settings.auto.is_none() && next < tl.instants.len() {
            let list_dt = tl.instants[next] - tl.instants[next - 1];
            if dt_next < list_dt * (1.0 - 1e-9) && !alarmed_sub {
                alarmed_sub = true;
                log(&format!(
                    "  alarm: at t = {:e} the critical step on the current geometry is {:.4e} (cell M{}), below the list's step {:.4e}: the list's steps are cut into equal sub-steps from now on while needed (an aster extension; code_aster checks the list once)",
                    engine.trial.t,
                    bound.dt,
                    bound.cell + 1,
                    list_dt
                ));
            }
        }
        // The correction makes the state's a and v those that keep the
        // next step out of the obstacle, so it needs a next step even
        // after the last one: without it (dt_next = 0 predicts no motion,
        // hence nothing to correct) the last state of a call kept the
        // uncorrected velocity (a node resting on the wall stored with
        // −V/2 or more), which a continuation then started from. The
        // step just taken stands for the next one, as in a one-call run
        // going on with the same step; LIAISON_UNIL's coefficients are
        // taken at its end when defined there, else (PROL_DROITE='EXCLU'
        // at the list's end) as they are at the last instant.
        let dt_ahead = if dt_next > 0.0 { dt_next } else { dt };
        if let Some(ct) = contact.as_deref_mut() {
            if ct.kinematic() {
                let corrected = ct
                    .prepare(
                        &engine.asm.numbering,
                        &engine.trial.motion.u,
                        engine.trial.t,
                    )
                    .and_then(
                        |()| match ex.correct(engine, ct, dt, dt_ahead, None, true) {
                            Err(_) if dt_next <= 0.0 => {
                                let t_end = engine.trial.t;
                                ex.correct(engine, ct, dt, dt_ahead, Some(t_end), true)
                            }
                            r => r,
                        },
                    );
                if let Err(why) = corrected {
                    fail!(why, t0, dt);
                }
            }
        }
        engine.commit();
        if let Some(ct) = contact.as_deref_mut() {
            ct.commit(&engine.committed.motion.u, dt, ex.scheme.end_weight());
        }
        let fc = contact
            .as_deref()
            .map_or(&zero[..], |c| c.force_on_fint_side());
        ex.energy_step(&mut energy, engine, fc);
        if let Some(ct) = contact.as_deref() {
            energy.friction = ct.friction_dissipation();
        }
        if let Some(why) = runaway(&energy) {
            fail!(why, t0, dt);
        }
        if at_list && !tl.suivi.is_empty() {
            log(&suivi_line(
                tl,
                &engine.committed,
                list_steps,
                ndpn,
                &offsets,
            ));
        }
        if let (true, Some(o)) = (at_list, observer.as_mut()) {
            o.observe(
                &tl.observations,
                &engine.committed,
                Some(list_steps),
                ndpn,
                &offsets,
            );
        }
        let last = next >= tl.instants.len();
        let capped = !last && settings.auto.is_some_and(|g| summary.steps >= g.max_steps);
        if capped {
            log(&super::dyna::nb_pas_maxi_line(
                summary.steps,
                engine.committed.t,
                tl,
            ));
        }
        if ((at_list && (tl.archive.wants(list_steps, engine.committed.t) || last)) || capped)
            && archive_with_contact(
                engine,
                tl,
                result,
                contact.as_deref(),
                Some((&engine.trial.motion.u, dt)),
            )
        {
            summary.archived += 1;
            archive_line(&mut energy, result, &summary, dt, log);
            if !energy_alarmed && !contact.as_deref().is_some_and(|c| c.moves_with_time()) {
                if let Some(m) = contact_energy_alarm(&energy, engine.committed.t, dt, contact_w2) {
                    log(&m);
                    energy_alarmed = true;
                }
            }
        }
        if capped {
            break;
        }
        last_dt = dt;
        dt = dt_next;
    }
    store_energy(&energy, result);
    store_observations(observer, result);
    if let Some(m) = folds.summary() {
        log(&m);
    }
    summary.seconds = started.elapsed().as_secs_f64();
    log(&format!(
        "  {} explicit steps ({} of the list), {} archived, {:.3} s ({:.3e} s per step); {} estimates of the critical step ({:.3} s)",
        summary.steps,
        list_steps,
        summary.archived,
        summary.seconds,
        summary.seconds / summary.steps.max(1) as f64,
        ex.estimates,
        ex.estimate_seconds
    ));
    if let Some(ct) = contact.as_deref() {
        log(&ct.summary_line());
        let p1 = momentum(engine);
        let dp: Vec<String> = p0
            .iter()
            .zip(&p1)
            .map(|(a, b)| format!("{:.9e}", b - a))
            .collect();
        log(&format!(
            "  momentum of the model (M v): change over the run ({})",
            dp.join(", ")
        ));
    }
    crate::profile::count(crate::profile::Counter::Steps, summary.steps);
    Ok(summary)
}

/// Archives the committed state (as [`archive`]) and, with contact, its
/// `CONT_NOEU`: zeros on the slave nodes at the initial state (`last`
/// None), else the state reached by a step of `last.1` from the
/// displacement `last.0` ([`ExplicitConstraint::cont_noeu`]).
fn archive_with_contact(
    engine: &Engine,
    tl: &TimeLoop,
    result: &mut EvolNoli,
    contact: Option<&(dyn ExplicitConstraint + '_)>,
    last: Option<(&[f64], f64)>,
) -> bool {
    if !archive(engine, tl, result, &engine.committed.clone(), None) {
        return false;
    }
    if let (Some(ct), Some(step)) = (contact, result.steps.last_mut()) {
        let field = match last {
            None => ct.cont_noeu_initial(),
            Some((u_start, dt)) => ct.cont_noeu(&engine.committed.motion.u, u_start, dt),
        };
        if let Some(field) = field {
            step.nodal.insert("CONT_NOEU".into(), field);
        }
        step.contact_history = Some(ct.history());
    }
    true
}

fn suivi_header(tl: &TimeLoop) -> String {
    let mut h = format!("  SUIVI_DDL  {:>6}  {:>13}", "step", "INST");
    for s in &tl.suivi {
        h.push_str(&format!("  {:>14}", s.label));
    }
    h
}

/// The SUIVI_DDL columns on the committed state after `step` steps of the
/// list.
fn suivi_line(
    tl: &TimeLoop,
    state: &super::State,
    step: usize,
    ndpn: usize,
    offsets: &super::fields::GaussRows,
) -> String {
    let mut line = format!("  SUIVI_DDL  {step:>6}  {:>13.6e}", state.t);
    for s in &tl.suivi {
        line.push_str(&format!("  {:>14.6e}", s.evaluate(state, ndpn, offsets)));
    }
    line
}

fn archive_line(
    energy: &mut EnergyBalance,
    result: &EvolNoli,
    summary: &RunSummary,
    dt: f64,
    log: &mut dyn FnMut(&str),
) {
    if let Some(s) = result.steps.last() {
        log(&format!(
            "  archived NUME_ORDRE {} at t = {:e} after {} steps (dt = {:.4e})",
            s.nume_ordre, s.inst, summary.steps, dt
        ));
        log(&energy.archive(s.nume_ordre, s.inst));
    }
}

fn store_energy(energy: &EnergyBalance, result: &mut EvolNoli) {
    result.tables.insert(
        super::energy::TABLE_NAME.to_string(),
        energy.table("energy balance of DYNA_NON_LINE"),
    );
}

/// Density of each mesh cell of the model (0 elsewhere): the lumped mass
/// is built from the element masses, which need it.
pub fn cell_densities(
    model: &crate::model::Model,
    matfield: &crate::model::MaterialField,
    materials: &indexmap::IndexMap<String, crate::model::Material>,
    occurrences: &[super::Occurrence],
) -> Result<Vec<f64>, super::BehaviourError> {
    let beh = super::behaviour::build(model, matfield, materials, occurrences)?;
    Ok(beh.cells.iter().map(|c| c.map_or(0.0, |b| b.rho)).collect())
}

/// Σ (M v) per direction over the whole model.
fn momentum(engine: &Engine) -> Vec<f64> {
    let nd = engine.asm.numbering.ndpn;
    let v = &engine.committed.motion.v;
    let mut mv = vec![0.0; v.len()];
    engine.asm.mass_mul(v, &mut mv);
    (0..nd)
        .map(|k| mv.iter().skip(k).step_by(nd).sum())
        .collect()
}
