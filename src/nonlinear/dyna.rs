//! The time loop of DYNA_NON_LINE and STAT_NON_LINE (the same loop on a
//! quasi-static engine, [`crate::time::Scheme::quasi_static`]): steps of
//! the time list, step cutting on failure (DEFI_LIST_INST ECHEC),
//! archiving, the step log and SUIVI_DDL.

use std::collections::{HashMap, HashSet};
use std::time::Instant;

use super::contact::DiscreteContact;
use super::energy::{EnergyBalance, GIVEN_MEANING};
use super::fields;
use super::newton::{ContactTerm, Engine, IterationRecord, State, StepFailure, StepReport};
use super::observation::Observer;
use super::unilateral::UnilateralContact;
use crate::result::{EvolNoli, Step};
use crate::time::list::{Action, Subdivision};

/// Which computed steps are stored (ARCHIVAGE).
#[derive(Debug, Clone, PartialEq)]
pub enum ArchivePolicy {
    /// PAS_ARCH (1 = every step, the default).
    Every(usize),
    /// LIST_INST / INST with CRITERE and PRECISION.
    Instants {
        instants: Vec<f64>,
        precision: f64,
        relative: bool,
    },
}

impl ArchivePolicy {
    /// Whether the `computed`-th step, ending at `t`, is archived.
    pub fn wants(&self, computed: usize, t: f64) -> bool {
        match self {
            ArchivePolicy::Every(p) => *p > 0 && computed.is_multiple_of(*p),
            ArchivePolicy::Instants {
                instants,
                precision,
                relative,
            } => instants.iter().any(|&s| {
                let tol = if *relative {
                    precision * s.abs()
                } else {
                    *precision
                };
                (s - t).abs() <= tol
            }),
        }
    }
}

/// The field a SUIVI_DDL column reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SuiviField {
    Depl,
    Vite,
    Acce,
    ForcNoda,
    SiefElga,
    VariElga,
}

/// EVAL_CHAM / EVAL_ELGA reductions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reduce {
    Min,
    Max,
    Moy,
    MaxiAbs,
    MiniAbs,
    /// The value itself: the first selected entity.
    Vale,
}

impl Reduce {
    pub fn from_name(s: &str) -> Option<Reduce> {
        Some(match s {
            "MIN" => Reduce::Min,
            "MAX" => Reduce::Max,
            "MOY" => Reduce::Moy,
            "MAXI_ABS" => Reduce::MaxiAbs,
            "MINI_ABS" => Reduce::MiniAbs,
            "VALE" => Reduce::Vale,
            _ => return None,
        })
    }
    fn apply(self, vals: impl Iterator<Item = f64>) -> f64 {
        let mut n = 0usize;
        let mut acc: Option<f64> = None;
        let mut sum = 0.0;
        for v in vals {
            n += 1;
            sum += v;
            acc = Some(match (self, acc) {
                (Reduce::Vale, Some(a)) => a,
                (_, None) => match self {
                    Reduce::MaxiAbs | Reduce::MiniAbs => v.abs(),
                    _ => v,
                },
                (Reduce::Min, Some(a)) => a.min(v),
                (Reduce::Max, Some(a)) => a.max(v),
                (Reduce::MaxiAbs, Some(a)) => a.max(v.abs()),
                (Reduce::MiniAbs, Some(a)) => a.min(v.abs()),
                (Reduce::Moy, Some(a)) => a,
            });
        }
        match self {
            Reduce::Moy if n > 0 => sum / n as f64,
            _ => acc.unwrap_or(f64::NAN),
        }
    }
}

/// One SUIVI_DDL column.
#[derive(Debug, Clone, PartialEq)]
pub struct Suivi {
    pub label: String,
    pub field: SuiviField,
    /// Component index (dof index for nodal fields, SIEF/VARI component).
    pub component: usize,
    /// Nodes (nodal fields) or cells (Gauss fields) selected.
    pub entities: Vec<usize>,
    pub eval: Reduce,
    /// EVAL_ELGA: MIN, MAX or VALE at `points` (1-based POINT values).
    pub eval_elga: Reduce,
    pub points: Vec<usize>,
}

impl Suivi {
    /// The value of the column on `state`.
    pub fn evaluate(&self, state: &State, ndpn: usize, rows: &fields::GaussRows) -> f64 {
        let nodal = |v: &[f64]| {
            self.eval
                .apply(self.entities.iter().map(|&n| v[n * ndpn + self.component]))
        };
        match self.field {
            SuiviField::Depl => nodal(&state.motion.u),
            SuiviField::Vite => nodal(&state.motion.v),
            SuiviField::Acce => nodal(&state.motion.a),
            SuiviField::ForcNoda => nodal(&state.fint),
            SuiviField::SiefElga | SuiviField::VariElga => {
                let per_cell = self.entities.iter().filter_map(|&c| {
                    let n = rows.npoints(c);
                    if n == 0 {
                        return None;
                    }
                    let value = |p: usize| {
                        if self.field == SuiviField::SiefElga {
                            rows.stress(&state.points, c, p, self.component)
                        } else {
                            rows.internal(&state.points, c, p, self.component)
                        }
                    };
                    Some(match self.eval_elga {
                        Reduce::Vale => self.eval.apply(
                            self.points
                                .iter()
                                .filter(|&&p| p >= 1 && p <= n)
                                .map(|&p| value(p - 1)),
                        ),
                        r => r.apply((0..n).map(value)),
                    })
                });
                self.eval.apply(per_cell)
            }
        }
    }
}

/// The contact events of the time list (DEFI_LIST_INST ECHEC) the loop
/// watches after each converged step (semantics.md §7.2).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactEvents {
    /// EVENEMENT='COLLISION', ACTION='DECOUPE', SUBD_METHODE='AUTO':
    /// (SUBD_INST, SUBD_DUREE).
    pub collision: Option<(f64, f64)>,
    /// EVENEMENT='INTERPENETRATION', ACTION='ADAPT_COEF_PENA':
    /// (PENE_MAXI, COEF_MAXI).
    pub interpenetration: Option<(f64, f64)>,
}

/// ECHEC EVENEMENT='DELTA_GRANDEUR' (code_aster's nmevdg): a converged
/// step whose increment of one component, in absolute value at any node
/// or Gauss point of the model, exceeds VALE_REF is redone in sub-steps by
/// the rule's own ACTION. It bounds what a step may change, where ERREUR
/// only reacts to what fails.
#[derive(Debug, Clone, PartialEq)]
pub struct DeltaGrandeur {
    /// "VARI_ELGA V1", for the messages.
    pub label: String,
    /// DEPL, SIEF_ELGA or VARI_ELGA.
    pub field: SuiviField,
    /// Dof index (DEPL) or SIEF/VARI component.
    pub component: usize,
    pub vale_ref: f64,
    pub action: Action,
}

impl DeltaGrandeur {
    /// The largest |increment| of the component from `from` to `to`.
    pub fn max_increment(
        &self,
        from: &State,
        to: &State,
        ndpn: usize,
        rows: &fields::GaussRows,
    ) -> f64 {
        let c = self.component;
        match self.field {
            SuiviField::Depl => to
                .motion
                .u
                .iter()
                .zip(&from.motion.u)
                .skip(c)
                .step_by(ndpn)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max),
            SuiviField::SiefElga => (0..rows.ncells())
                .flat_map(|cell| (0..rows.npoints(cell)).map(move |p| (cell, p)))
                .map(|(cell, p)| {
                    let at = |s: &State| rows.stress(&s.points, cell, p, c);
                    (at(to) - at(from)).abs()
                })
                .fold(0.0, f64::max),
            _ => to
                .points
                .iter()
                .zip(&from.points)
                .filter_map(|(a, b)| {
                    let (a, b) = (a.internal.as_slice(), b.internal.as_slice());
                    Some((a.get(c)? - b.get(c)?).abs())
                })
                .fold(0.0, f64::max),
        }
    }
}

/// METHODE='AUTO': how the step grows back after a success.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Growth {
    /// Explicit loop: the step grows by at most `factor` (1 + PCENT_AUGM/100
    /// of MODE_CALCUL_TPLUS='FIXE'); the implicit loop applies
    /// `TimeLoop::adaptation` instead.
    pub factor: f64,
    /// PAS_MAXI, if given.
    pub pas_maxi: Option<f64>,
    /// PAS_MINI, if given: a step chosen after a success that falls below
    /// it stops the run (code_aster's ADAPTATION_11). It is the only limit
    /// on repeated cuts besides SUBD_PAS_MINI, since METHODE='AUTO' has no
    /// subdivision level; and a step that would end within PAS_MINI of the
    /// next instant of the list goes to that instant (nmadap).
    pub pas_mini: Option<f64>,
    /// NB_PAS_MAXI: the computation ends after this many computed steps,
    /// as at the list's last instant (code_aster's ADAPTATION_13, an
    /// information, not an error).
    pub max_steps: usize,
}

/// When an ADAPTATION occurrence proposes a next step (EVENEMENT).
#[derive(Debug, Clone, PartialEq)]
pub enum AdaptTrigger {
    /// 'AUCUN'.
    Never,
    /// 'TOUT_INST'.
    Always,
    /// 'SEUIL': once `count` Newton convergences with an iteration index
    /// (code_aster's, the prediction being 0) that compares to `vale` with
    /// `crit` have been counted since the last adaptation (`diadap`, which
    /// resets the count when it fires; `nmevdt` counts, and resets on a
    /// Newton failure only, so the counted steps need not be consecutive).
    Threshold {
        count: usize,
        crit: std::cmp::Ordering,
        /// CRIT_COMP 'LE' / 'GE': equality counts too.
        or_equal: bool,
        vale: usize,
    },
}

/// How an ADAPTATION occurrence computes the next step from the last one,
/// dt⁻ (MODE_CALCUL_TPLUS, code_aster's `nmcadt`).
#[derive(Debug, Clone, PartialEq)]
pub enum StepRule {
    /// 'FIXE': dt⁻ (1 + PCENT_AUGM/100), the factor given.
    Fixe(f64),
    /// 'DELTA_GRANDEUR': dt⁻ · VALE_REF / max |Δ| of one component over
    /// the step just done (no proposal when that is 0).
    DeltaGrandeur(DeltaGrandeur),
    /// 'ITER_NEWTON': dt⁻ · √(NB_ITER_NEWTON_REF / (iterations + 1)),
    /// iterations the index of the converged Newton iteration.
    IterNewton(usize),
}

/// One ADAPTATION occurrence of a METHODE='AUTO' list.
#[derive(Debug, Clone, PartialEq)]
pub struct StepAdaptation {
    pub trigger: AdaptTrigger,
    pub rule: StepRule,
}

/// The running state of METHODE='AUTO' (code_aster's `nmadat`): dt⁻, the
/// last step that counts as "the step", and the convergences counted for
/// each 'SEUIL' occurrence.
#[derive(Debug, Clone)]
struct Adapter {
    dt_prev: f64,
    counts: Vec<usize>,
    /// The instant of the step last chosen when it was shortened to reach
    /// an instant of the list: its length does not become dt⁻.
    truncated: Option<f64>,
}

impl Adapter {
    fn new(tl: &TimeLoop) -> Adapter {
        Adapter {
            dt_prev: tl.instants.get(1).map_or(0.0, |t| t - tl.instants[0]),
            counts: vec![0; tl.adaptation.len()],
            truncated: None,
        }
    }

    /// After each Newton solve of a step: a convergence at iteration index
    /// `index` counts for the thresholds it satisfies; a failure resets
    /// every count.
    fn newton(&mut self, tl: &TimeLoop, converged: Option<usize>) {
        for (a, n) in tl.adaptation.iter().zip(self.counts.iter_mut()) {
            let AdaptTrigger::Threshold {
                crit,
                or_equal,
                vale,
                ..
            } = &a.trigger
            else {
                continue;
            };
            match converged {
                Some(index) => {
                    let o = index.cmp(vale);
                    if o == *crit || (*or_equal && o == std::cmp::Ordering::Equal) {
                        *n += 1;
                    }
                }
                None => *n = 0,
            }
        }
    }

    /// The next step after a success `(t, dt, index)` that took `dt` to
    /// `t` in Newton iteration index `index`, with `increment(d)` the
    /// step's largest change of a DELTA_GRANDEUR component; `jalon` is the
    /// next instant of the list.
    fn next(
        &mut self,
        tl: &TimeLoop,
        g: Growth,
        (t, dt, index): (f64, f64, usize),
        jalon: f64,
        increment: &dyn Fn(&DeltaGrandeur) -> f64,
    ) -> f64 {
        if self.truncated != Some(t) {
            self.dt_prev = dt;
        }
        let dtm = self.dt_prev;
        let mut best: Option<f64> = None;
        for (a, n) in tl.adaptation.iter().zip(self.counts.iter_mut()) {
            let fire = match a.trigger {
                AdaptTrigger::Never => false,
                AdaptTrigger::Always => true,
                AdaptTrigger::Threshold { count, .. } => {
                    let fire = *n >= count;
                    if fire {
                        *n = 0;
                    }
                    fire
                }
            };
            if !fire {
                continue;
            }
            let proposal = match &a.rule {
                StepRule::Fixe(f) => Some(dtm * f),
                StepRule::IterNewton(nref) => {
                    Some(dtm * (*nref as f64 / (index + 1) as f64).sqrt())
                }
                StepRule::DeltaGrandeur(d) => {
                    let m = increment(d);
                    (m != 0.0).then(|| dtm * d.vale_ref / m)
                }
            };
            if let Some(p) = proposal {
                best = Some(best.map_or(p, |b: f64| b.min(p)));
            }
        }
        let mut step = best.unwrap_or(dtm);
        if let Some(m) = g.pas_maxi {
            step = step.min(m);
        }
        // Reaching the next instant of the list (code_aster's `compr8`
        // with its precision 1e-12): a step past it is shortened and does
        // not become dt⁻; one that would end within PAS_MINI of it goes to
        // it and does.
        let prec = 1e-12 * jalon.abs().max(1e-300);
        let pas_mini = g.pas_mini.unwrap_or(0.0);
        self.truncated = None;
        if t + step > jalon + prec {
            step = jalon - t;
            self.truncated = Some(jalon);
        } else if t + step > jalon - pas_mini + prec {
            step = jalon - t;
            self.dt_prev = step;
        } else {
            self.dt_prev = step;
        }
        step
    }
}

/// What the time loop needs besides the engine.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeLoop {
    /// The instants to reach: the first is the initial instant.
    pub instants: Vec<f64>,
    /// The ERREUR rule of the time list.
    pub on_error: Action,
    pub archive: ArchivePolicy,
    /// ARCHIVAGE/CHAM_EXCLU: the fields left out of every archived
    /// instant of the call but the last one (code_aster's `diincl`,
    /// forced at the last step and at a stop).
    pub cham_exclu: Vec<String>,
    pub suivi: Vec<Suivi>,
    /// OBSERVATION occurrences (the result's table 'OBSERVATION').
    pub observations: Vec<super::observation::Observation>,
    /// Print the Newton table (INFO=2 or SUIVI_DDL present).
    pub newton_table: bool,
    /// Show an indicatif progress bar (the per-step lines then go to the
    /// message file only).
    pub progress: bool,
    /// Dof names of the model (DX, DY[, DZ]).
    pub dof_names: Vec<String>,
    pub ncells: usize,
    /// COLLISION / INTERPENETRATION (only with a contact term).
    pub events: ContactEvents,
    /// DELTA_GRANDEUR rules of the time list.
    pub deltas: Vec<DeltaGrandeur>,
    /// The ACTION of each Newton event of the time list (RESI_MAXI,
    /// DIVE_RESI) that the engine raises as `StepFailure::Event`.
    pub event_actions: Vec<(&'static str, Action)>,
    /// None: METHODE='MANUEL', the list is followed as given.
    pub growth: Option<Growth>,
    /// METHODE='AUTO' of the implicit loop: the ADAPTATION occurrences
    /// (the explicit loop uses `growth.factor` only).
    pub adaptation: Vec<StepAdaptation>,
    /// The subdivision level no cut may go beyond, whichever event cuts:
    /// code_aster keeps one level per step and compares it with the largest
    /// SUBD_NIVEAU of all the events (dfllec writes that maximum into every
    /// event). None: no level limit (METHODE='AUTO', where the level notion
    /// does not exist, or no MANUEL cutting rule).
    pub subd_niveau: Option<usize>,
    /// A known weakness of the model, appended to the message of a step
    /// that fails numerically (STAT_NON_LINE: rigid-body modes that only
    /// the contact holds).
    pub hint: Option<String>,
    /// The largest value of each load, named in the message of a step
    /// whose numbers left the range of doubles (a load of 1e308).
    pub load_peaks: Vec<super::loads::LoadPeak>,
    /// The energy table's values at the initial state (ETAT_INIT
    /// EVOL_NOLI), which the balance continues from.
    pub energy_start: super::energy::EnergyStart,
}

/// Totals of a run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunSummary {
    pub steps: usize,
    pub cuts: usize,
    pub newton_iterations: usize,
    pub archived: usize,
    pub seconds: f64,
}

impl RunSummary {
    /// Adds the totals of this time loop to the profiler's counters.
    fn count_profile(&self) {
        use crate::profile::{count, Counter};
        count(Counter::Steps, self.steps);
        count(Counter::StepCuts, self.cuts);
        count(Counter::NewtonIterations, self.newton_iterations);
    }
}

/// The computation stopped: `message` says where and why; the result
/// holds every step archived before (and the last converged state).
#[derive(Debug, Clone, PartialEq)]
pub struct Stopped {
    pub message: String,
    pub summary: RunSummary,
    /// The signal that asked for the stop ([`crate::interrupt`]), if the
    /// computation did not stop on a failure.
    pub signal: Option<i32>,
}

/// Appends the state to the result if its instant is after the last
/// stored one (an instant is never stored twice, which matters for reuse).
/// `contact`, when given, adds its CONT_NOEU (of its committed state).
///
/// Every state is archived whole; the fields of ARCHIVAGE/CHAM_EXCLU
/// are taken out of the previous instant of the same call when a later
/// one is archived: so the last instant of the call (its end, or where it
/// stopped) keeps them all, as code_aster forces the archiving of every
/// field there, and the initial state and the others lose them.
pub fn archive(
    engine: &Engine,
    tl: &TimeLoop,
    result: &mut EvolNoli,
    state: &State,
    contact: Option<&DiscreteContact>,
) -> bool {
    if let Some(last) = result.steps.last() {
        if state.t <= last.inst {
            return false;
        }
    }
    let run = result.current_run();
    if let Some(prev) = result.steps.last_mut().filter(|s| s.run == run) {
        exclude_fields(prev, &tl.cham_exclu);
    }
    let nume = result.steps.last().map_or(0, |s| s.nume_ordre + 1);
    let asm = &engine.asm;
    let mut step = Step {
        nume_ordre: nume,
        inst: state.t,
        run: result.current_run(),
        ..Step::default()
    };
    step.nodal.insert(
        "DEPL".into(),
        fields::nodal(asm, &tl.dof_names, &state.motion.u),
    );
    // A quasi-static result has no velocity or acceleration (code_aster's
    // STAT_NON_LINE stores neither).
    if engine.scheme.inertia {
        step.nodal.insert(
            "VITE".into(),
            fields::nodal(asm, &tl.dof_names, &state.motion.v),
        );
        step.nodal.insert(
            "ACCE".into(),
            fields::nodal(asm, &tl.dof_names, &state.motion.a),
        );
    }
    let (sief, vari) = fields::gauss(asm, tl.ncells, &state.points);
    if let Some(c) = contact {
        step.nodal.insert("CONT_NOEU".into(), c.cont_noeu());
        if let Some(depl) = step.nodal.get_mut("DEPL") {
            c.extend_depl(depl);
        }
    }
    step.gauss.insert("SIEF_ELGA".into(), sief);
    step.gauss.insert("VARI_ELGA".into(), vari);
    result.steps.push(step);
    true
}

/// Takes the fields of CHAM_EXCLU out of an archived step, recording
/// those it held.
fn exclude_fields(step: &mut Step, cham_exclu: &[String]) {
    for name in cham_exclu {
        let held =
            step.nodal.shift_remove(name).is_some() | step.gauss.shift_remove(name).is_some();
        if held && !step.excluded.contains(name) {
            step.excluded.push(name.clone());
        }
    }
}

/// A step failure for the log. A singular quasi-static stiffness is
/// almost always a rigid-body mode that nothing holds (without inertia
/// nothing else can): the message says so.
fn describe(engine: &Engine, tl: &TimeLoop, failure: &StepFailure) -> String {
    let text = match failure {
        // The lost-decimals message names its dof and causes already.
        StepFailure::Singular(m)
            if !engine.scheme.inertia
                && !m.contains("NPREC")
                && !m.contains(crate::solver::OVERFLOW)
                && !m.contains(crate::nonlinear::dofs::INTERNAL) =>
        {
            format!(
            "{m}: the stiffness of STAT_NON_LINE is singular, a rigid-body mode (or a mechanism) of the structure is not held; \
             add the missing DDL_IMPO (or a contact that holds it)"
            )
        }
        StepFailure::Singular(m) | StepFailure::NonFinite(m)
            if m.contains(crate::solver::OVERFLOW) =>
        {
            match super::loads::largest_load(&tl.load_peaks, engine.trial.t) {
                Some(w) => format!("{m}; {w}"),
                None => m.clone(),
            }
        }
        f => f.to_string(),
    };
    match (&tl.hint, failure) {
        (
            Some(h),
            StepFailure::NotConverged { .. } | StepFailure::Singular(_) | StepFailure::NonFinite(_),
        ) => format!("{text} ({h})"),
        _ => text,
    }
}

/// The command whose time loop this is, for messages.
fn command(engine: &Engine) -> &'static str {
    if engine.scheme.inertia {
        "DYNA_NON_LINE"
    } else {
        "STAT_NON_LINE"
    }
}

fn header(tl: &TimeLoop) -> String {
    let mut h = format!(
        "  {:>6}  {:>13}  {:>10}  {:>4}  {:>14}  {:>14}  {:>5}",
        "step", "INST", "dt", "iter", "RESI_GLOB_RELA", "RESI_GLOB_MAXI", "level"
    );
    for s in &tl.suivi {
        h.push_str(&format!("  {:>14}", s.label));
    }
    h
}

/// Runs the time loop from the engine's committed state (which must be at
/// `tl.instants[0]` and already initialized), archiving into `result`.
/// `contact` is the discrete contact, `unil` the LIAISON_UNIL conditions
/// (at most one of them: DEFI_CONTACT gives one formulation).
pub fn run(
    engine: &mut Engine,
    mut contact: Option<&mut DiscreteContact>,
    mut unil: Option<&mut UnilateralContact>,
    tl: &TimeLoop,
    result: &mut EvolNoli,
    log: &mut dyn FnMut(&str),
) -> Result<RunSummary, Stopped> {
    let started = Instant::now();
    let mut summary = RunSummary::default();
    let ndpn = engine.asm.numbering.ndpn;
    let offsets = fields::GaussRows::of(&engine.asm);
    let mut energy = EnergyBalance::new(
        engine,
        result.tables.get(super::energy::TABLE_NAME),
        tl.energy_start,
    );
    let mut folds = super::assembly::FoldWatch::default();
    let mut contact_energy_alarmed = false;
    // Moving LIAISON_UNIL conditions work on the model: the energy they
    // give is the obstacle's, not the scheme's, so no alarm blames it.
    let unil_moves = unil.as_deref().is_some_and(|u| u.def.moves_with_time());
    let mut energy_overflow_alarmed = false;
    let mut observer = (!tl.observations.is_empty()).then(|| {
        let mut o = Observer::new(result.tables.get(super::observation::TABLE_NAME));
        o.observe(&tl.observations, &engine.committed, None, ndpn, &offsets);
        o
    });
    let has_term = contact.is_some() || unil.is_some();
    if archive(
        engine,
        tl,
        result,
        &engine.committed.clone(),
        contact.as_deref(),
    ) {
        summary.archived += 1;
        log_energy(&mut energy, result, log);
    }
    let bar = tl.progress.then(|| {
        let pb = indicatif::ProgressBar::new(tl.instants.len().saturating_sub(1) as u64);
        pb.set_style(
            indicatif::ProgressStyle::with_template(&format!(
                "{} [{{bar:40}}] {{pos}}/{{len}} steps {{msg}} ({{elapsed}}, eta {{eta}})",
                command(engine)
            ))
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        pb
    });
    log(&header(tl));
    // Pending targets (instant, level, is an instant of the list), last
    // first; level 1 = a step of the list.
    let mut pending: Vec<(f64, usize, bool)> = tl.instants[1..]
        .iter()
        .rev()
        .map(|&t| (t, 1, true))
        .collect();
    let mut last_archived_t = result.steps.last().map(|s| s.inst);
    // COLLISION: the end of the running collision of each (zone, slave
    // node) link, and the end of the refinement window (the latest one).
    let mut collisions: HashMap<(usize, usize), f64> = HashMap::new();
    let mut refine_until: Option<f64> = None;
    // METHODE='AUTO': the instant that the step chosen after the last
    // success reaches (the one PAS_MINI applies to).
    let mut adapted: Option<f64> = None;
    let mut adapter = Adapter::new(tl);
    while let Some((t_end, level, list_end)) = pending.pop() {
        let t0 = engine.committed.t;
        if let Some(signal) = crate::interrupt::requested() {
            let mut stop = StopState {
                energy: &mut energy,
                summary: &mut summary,
                last_archived_t,
                started,
                bar: bar.as_ref(),
                observer: observer.take(),
            };
            return Err(stop_on_signal(
                signal,
                None,
                engine,
                contact.as_deref(),
                tl,
                result,
                &mut stop,
                log,
            ));
        }
        if let (Some((subd_inst, _)), Some(until)) = (tl.events.collision, refine_until) {
            // Inside a collision window every step is made of sub-steps
            // of about SUBD_INST, up to the end of the window.
            let eps = 1e-6 * subd_inst;
            if until - t0 > eps {
                let horizon = t_end.min(until);
                let n = ((horizon - t0) / subd_inst).round().max(1.0) as usize;
                let split = horizon < t_end - eps;
                if n > 1 || split {
                    if split {
                        pending.push((t_end, level, list_end));
                    }
                    let ends = equal_steps(t0, horizon, n, level + 1, list_end && !split);
                    pending.extend(ends.into_iter().rev());
                    continue;
                }
            }
        }
        let dt = t_end - t0;
        let below_pas_mini = match (adapted.take(), tl.growth.and_then(|g| g.pas_mini)) {
            (Some(t), Some(m)) if t == t_end && dt < m * (1.0 - 1e-9) => Some(m),
            _ => None,
        };
        let suivi = &tl.suivi;
        let table = tl.newton_table;
        let mut rows: Vec<String> = Vec::new();
        let term: Option<&mut dyn ContactTerm> = match (contact.as_deref_mut(), unil.as_deref_mut())
        {
            (Some(c), _) => Some(c),
            (None, Some(u)) => Some(u),
            (None, None) => None,
        };
        let mut record = |rec: &IterationRecord, st: &State| {
            if table {
                let mut line = format!(
                    "      iter {:>2}  RESI_GLOB_RELA {:>10.3e}{}  RESI_GLOB_MAXI {:>10.3e}{}",
                    // code_aster's iteration index: the residual after the
                    // prediction is iteration 0.
                    rec.iteration - 1,
                    rec.resi_rela,
                    if rec.swapped { "*" } else { " " },
                    rec.resi_maxi,
                    if rec.matrix_updated { "  matrix" } else { "" }
                );
                for s in suivi {
                    line.push_str(&format!("  {:>14.6e}", s.evaluate(st, ndpn, &offsets)));
                }
                rows.push(line);
            }
        };
        // The ACTION of the Newton event that failed this step, if one did.
        let mut event_action: Option<Action> = None;
        // A step that does not advance the time (a PAS_MAXI below the
        // resolution of the instants) fails as what it is, not as the
        // non-finite residual a zero step gives.
        let outcome = if t_end > t0 && below_pas_mini.is_none() {
            engine.solve_step(dt, term, &mut record).map_err(Some)
        } else {
            Err(None)
        };
        for r in &rows {
            log(r);
        }
        // The ADAPTATION thresholds count Newton convergences (iteration
        // index: code_aster's, the prediction 0) and forget them at a
        // Newton failure (nmevdt).
        match &outcome {
            Ok(rep) if !rep.not_converged => {
                adapter.newton(tl, Some(rep.iterations.saturating_sub(1)))
            }
            Err(Some(StepFailure::Interrupted(_))) | Err(None) => {}
            _ => adapter.newton(tl, None),
        }
        // ARRET='NON' forces the convergence of a step only when the ERREUR
        // rule's action fails (code_aster's nmactn: the action first, the
        // alarm MECANONLINE2_37 when it returns "failed"): a step that the
        // rule can cut is cut, as if ARRET were 'OUI'.
        let mut forced_why: Option<String> = None;
        if let Ok(rep) = &outcome {
            if rep.not_converged && tl.on_error != Action::Arret {
                match cut_step(&tl.on_error, t0, t_end, level, list_end, tl.subd_niveau) {
                    Ok(subs) => {
                        log(&format!(
                            "  step failure from t = {t0:e} to {t_end:e} (dt = {dt:.3e}, level {level}): not converged in ITER_GLOB_MAXI = {} iterations; ARRET='NON' applies only when the ERREUR action fails: the step is cut into {}",
                            rep.iterations,
                            sub_steps(subs.len(), dt, level)
                        ));
                        summary.cuts += 1;
                        pending.extend(subs.into_iter().rev());
                        continue;
                    }
                    Err(why) => forced_why = Some(why),
                }
            }
        }
        let outcome = match outcome {
            Err(None) => Err((
                match below_pas_mini {
                    Some(m) => format!(
                        "METHODE='AUTO': the step chosen after the last success, {dt:.3e}, is below PAS_MINI = {m:e} (code_aster ADAPTATION_11); it is not computed"
                    ),
                    None => "the step does not advance the time (PAS_MAXI below the resolution of the instants?)"
                        .to_string(),
                },
                true,
            )),
            Err(Some(StepFailure::Interrupted(signal))) => {
                let mut stop = StopState {
                    energy: &mut energy,
                    summary: &mut summary,
                    last_archived_t,
                    started,
                    bar: bar.as_ref(),
                    observer: observer.take(),
                };
                return Err(stop_on_signal(
                    signal,
                    Some(t_end),
                    engine,
                    contact.as_deref(),
                    tl,
                    result,
                    &mut stop,
                    log,
                ));
            }
            Err(Some(failure)) => {
                if let StepFailure::Event(name, _) = &failure {
                    event_action = tl
                        .event_actions
                        .iter()
                        .find(|(n, _)| n == name)
                        .map(|(_, a)| a.clone());
                }
                Err((describe(engine, tl, &failure), failure.is_fatal()))
            }
            Ok(rep) => match contact.as_deref_mut() {
                Some(c) => match check_events(
                    c,
                    &tl.events,
                    &mut collisions,
                    &mut refine_until,
                    (t0, t_end, level, list_end),
                ) {
                    EventOutcome::Accept => Ok(rep),
                    EventOutcome::Redo { note, steps } => {
                        log(&format!(
                            "  step from t = {t0:e} to {t_end:e} (dt = {dt:.3e}) converged in {} iterations, redone: {note}",
                            rep.iterations
                        ));
                        summary.cuts += 1;
                        pending.extend(steps.into_iter().rev());
                        continue;
                    }
                    EventOutcome::Fail(why) => Err((why, false)),
                },
                None => Ok(rep),
            },
        };
        let mut outcome = outcome;
        if outcome.is_ok() {
            let over = tl.deltas.iter().find_map(|d| {
                let m = d.max_increment(&engine.committed, &engine.trial, ndpn, &offsets);
                (m > d.vale_ref).then_some((d, m))
            });
            if let Some((d, m)) = over {
                let why = format!(
                    "DELTA_GRANDEUR: the increment of {} reaches {m:.6e} > VALE_REF = {:e}",
                    d.label, d.vale_ref
                );
                let cut = match d.action {
                    Action::Arret => Err("its ACTION is ARRET".to_string()),
                    _ => cut_step(&d.action, t0, t_end, level, list_end, tl.subd_niveau),
                };
                match cut {
                    Ok(subs) => {
                        summary.cuts += 1;
                        log(&format!(
                            "  step from t = {t0:e} to {t_end:e} (dt = {dt:.3e}) converged, redone: {why}; cut into {}",
                            sub_steps(subs.len(), dt, level)
                        ));
                        pending.extend(subs.into_iter().rev());
                        continue;
                    }
                    Err(e) => outcome = Err((format!("{why}; {e}"), true)),
                }
            }
        }
        match outcome {
            Ok(rep) => {
                engine.commit();
                if let Some(c) = contact.as_deref_mut() {
                    c.commit(dt);
                }
                if let Some(u) = unil.as_deref_mut() {
                    u.commit();
                }
                energy.step(engine, contact.as_deref(), has_term);
                if !energy_overflow_alarmed {
                    if let Some(bad) = energy.not_finite() {
                        log(&format!(
                            "  alarm: at t = {t_end:e} the energy balance is not finite ({bad}): the motion has grown beyond what double precision can square (½ v·M v, F·Δu) although the equilibrium still solves; the loads are far too large for the model (look at their values and FONC_MULT); this alarm is given once"
                        ));
                        energy_overflow_alarmed = true;
                    }
                }
                if !contact_energy_alarmed && !unil_moves && command(engine) == "DYNA_NON_LINE" {
                    if let Some(m) = contact_energy_alarm(&energy, t_end, engine.scheme.gamma) {
                        log(&m);
                        contact_energy_alarmed = true;
                    }
                }
                summary.steps += 1;
                summary.newton_iterations += rep.iterations;
                log(&step_line(
                    summary.steps,
                    t_end,
                    dt,
                    &rep,
                    level,
                    tl,
                    engine,
                    ndpn,
                    &offsets,
                ));
                folds.see(t_end, rep.fold, log);
                if rep.not_converged {
                    log(&format!(
                        "  alarm: the step to t = {t_end:e} did not converge in ITER_GLOB_MAXI = {} iterations and is accepted (ARRET='NON'){}",
                        rep.iterations,
                        forced_why.as_deref().map_or(String::new(), |w| format!(
                            " because the ERREUR action failed: {w}"
                        ))
                    ));
                }
                if !pending.is_empty() && tl.growth.is_some_and(|g| summary.steps >= g.max_steps) {
                    log(&nb_pas_maxi_line(summary.steps, t_end, tl));
                    pending.clear();
                }
                let last = pending.is_empty();
                if let Some(o) = observer.as_mut() {
                    o.observe(
                        &tl.observations,
                        &engine.committed,
                        Some(summary.steps),
                        ndpn,
                        &offsets,
                    );
                }
                if (tl.archive.wants(summary.steps, t_end) || last)
                    && archive(
                        engine,
                        tl,
                        result,
                        &engine.committed.clone(),
                        contact.as_deref(),
                    )
                {
                    summary.archived += 1;
                    last_archived_t = Some(t_end);
                    log_energy(&mut energy, result, log);
                }
                if let (Some(pb), true) = (&bar, list_end) {
                    pb.inc(1);
                    pb.set_message(format!("t = {t_end:.4e}"));
                }
                if let Some(g) = tl.growth {
                    let index = rep.iterations.saturating_sub(1);
                    // After the commit the trial state is the step's start.
                    let (from, to) = (&engine.trial, &engine.committed);
                    let increment = |d: &DeltaGrandeur| d.max_increment(from, to, ndpn, &offsets);
                    adapted = grow(&mut pending, t_end, |jalon| {
                        adapter.next(tl, g, (t_end, dt, index), jalon, &increment)
                    });
                }
            }
            Err((reason, fatal)) => {
                log(&format!(
                    "  step failure from t = {t0:e} to {t_end:e} (dt = {dt:.3e}, level {level}): {reason}"
                ));
                let action = event_action.take().unwrap_or_else(|| tl.on_error.clone());
                let cut = if fatal {
                    Err("cutting the step cannot cure it".to_string())
                } else if action == Action::Arret && !matches!(tl.on_error, Action::Arret) {
                    Err("the event's ACTION is ARRET".to_string())
                } else {
                    cut_step(&action, t0, t_end, level, list_end, tl.subd_niveau)
                };
                match cut {
                    Ok(subs) => {
                        summary.cuts += 1;
                        log(&format!(
                            "  the step is cut into {}",
                            sub_steps(subs.len(), dt, level)
                        ));
                        pending.extend(subs.into_iter().rev());
                    }
                    Err(why) => {
                        if last_archived_t != Some(engine.committed.t)
                            && archive(
                                engine,
                                tl,
                                result,
                                &engine.committed.clone(),
                                contact.as_deref(),
                            )
                        {
                            summary.archived += 1;
                            log_energy(&mut energy, result, log);
                        }
                        store_energy(engine, &energy, result);
                        store_observations(observer.take(), result);
                        if let Some(m) = folds.summary() {
                            log(&m);
                        }
                        if let Some(pb) = &bar {
                            pb.abandon();
                        }
                        summary.seconds = started.elapsed().as_secs_f64();
                        let message = format!(
                            "{} stopped at the step from t = {t0:e} to t = {t_end:e}: {reason}; {why}. The {} steps archived so far (last instant {:e}) are kept in the result.",
                            command(engine),
                            result.steps.len(),
                            result.steps.last().map_or(t0, |s| s.inst)
                        );
                        log(&message);
                        summary.count_profile();
                        return Err(Stopped {
                            message,
                            summary,
                            signal: None,
                        });
                    }
                }
            }
        }
    }
    if let Some(pb) = &bar {
        pb.finish_and_clear();
    }
    store_energy(engine, &energy, result);
    store_observations(observer, result);
    if let Some(m) = folds.summary() {
        log(&m);
    }
    summary.seconds = started.elapsed().as_secs_f64();
    log(&format!(
        "  {} steps ({} cuts), {} Newton iterations, {} archived, {:.3} s ({:.3e} s per step)",
        summary.steps,
        summary.cuts,
        summary.newton_iterations,
        summary.archived,
        summary.seconds,
        summary.seconds / summary.steps.max(1) as f64
    ));
    summary.count_profile();
    Ok(summary)
}

/// The information that NB_PAS_MAXI ends a METHODE='AUTO' computation
/// after `steps` steps, at `t`.
pub(crate) fn nb_pas_maxi_line(steps: usize, t: f64, tl: &TimeLoop) -> String {
    format!(
        "  NB_PAS_MAXI = {steps} steps reached at t = {t:e}: the computation ends here, as at the list's last instant ({:e} not reached; code_aster ADAPTATION_13)",
        tl.instants.last().copied().unwrap_or(t)
    )
}

/// The loop's bookkeeping that a stop on a signal closes.
struct StopState<'a> {
    energy: &'a mut EnergyBalance,
    summary: &'a mut RunSummary,
    last_archived_t: Option<f64>,
    started: Instant,
    bar: Option<&'a indicatif::ProgressBar>,
    observer: Option<Observer>,
}

/// A stop requested by `signal` ([`crate::interrupt`]) before the step to
/// `abandoned` (None: between steps): the last committed state is archived
/// if it is not yet, so the result holds everything computed, and the
/// message says where the run stopped and what is kept.
#[allow(clippy::too_many_arguments)]
fn stop_on_signal(
    signal: i32,
    abandoned: Option<f64>,
    engine: &Engine,
    contact: Option<&DiscreteContact>,
    tl: &TimeLoop,
    result: &mut EvolNoli,
    stop: &mut StopState,
    log: &mut dyn FnMut(&str),
) -> Stopped {
    if let Some(pb) = stop.bar {
        pb.abandon();
    }
    let t = engine.committed.t;
    if stop.last_archived_t != Some(t)
        && archive(engine, tl, result, &engine.committed.clone(), contact)
    {
        stop.summary.archived += 1;
        log_energy(stop.energy, result, log);
    }
    store_energy(engine, stop.energy, result);
    store_observations(stop.observer.take(), result);
    stop.summary.seconds = stop.started.elapsed().as_secs_f64();
    let end = tl.instants.last().copied().unwrap_or(t);
    let first = result.steps.first().map_or(t, |s| s.inst);
    let last = result.steps.last().map_or(t, |s| s.inst);
    let message = format!(
        "{} stopped by {} at t = {t:e}{}, after {} converged steps: the {} archived instants (t = {first:e} to {last:e}, the last converged state included) are kept in the result; the computation up to t = {end:e} was not done.",
        command(engine),
        crate::interrupt::name(signal),
        abandoned.map_or(String::new(), |te| format!(
            " (the step to t = {te:e} was abandoned)"
        )),
        stop.summary.steps,
        result.steps.len(),
    );
    log(&message);
    stop.summary.count_profile();
    Stopped {
        message,
        summary: stop.summary.clone(),
        signal: Some(signal),
    }
}

/// The OBSERVATION rows as the result's table (kept with the steps
/// computed when the run stops early).
pub(crate) fn store_observations(observer: Option<Observer>, result: &mut EvolNoli) {
    if let Some(o) = observer {
        result
            .tables
            .insert(super::observation::TABLE_NAME.to_string(), o.into_table());
    }
}

/// The alarm once the contact (or the unilateral links) has created
/// energy ([`EnergyBalance::contact_created_energy`]): in an implicit run
/// a link that closes or opens within a step does work the time scheme
/// does not balance; the trapezoidal rule (NEWMARK 1/4, 1/2) has no
/// dissipation to take it out (tests/unilateral.rs: a mass stopped at +V
/// leaves the floor at 3V), and a bar that lands and rebounds keeps it
/// (probe s7a: TRAV_LIAI -39 against 15 of initial kinetic energy,
/// without a word). The advice depends on whether the scheme dissipates
/// (GAMMA > 1/2, which HHT implies). The explicit loop has its own alarm
/// for the penalty (nonlinear::explicit).
fn contact_energy_alarm(energy: &EnergyBalance, t: f64, gamma: f64) -> Option<String> {
    if !energy.contact_created_energy() {
        return None;
    }
    let given = energy.given();
    let surplus = energy.surplus();
    let why = if gamma > 0.5 + 1e-12 {
        format!(
            "links that close or open within a step did more work on the model than the numerical dissipation of the scheme (GAMMA = {gamma}) took out; a smaller step does not always reduce it (node-wise constraints in a Newmark-type scheme give each closing node the velocity jump of the scheme's rule at every impact: docs/contact.md §7a)"
        )
    } else {
        "a scheme without numerical dissipation (NEWMARK BETA = 1/4, GAMMA = 1/2) creates energy when the contact stops a node from within a step, and the kinetic energy keeps it once the bodies separate; HHT (ALPHA < 0) or NEWMARK with GAMMA > 1/2 dissipates it".to_string()
    };
    Some(format!(
        "  alarm: at t = {t:e} the contact has returned {:.4e} more energy than it absorbed (TRAV_LIAI = {:.4e}, {:.2} % of the energy given to the model, {given:.4e} = {GIVEN_MEANING}) and the model holds {surplus:.4e} more than it was given ({:.2} %: ENER_CIN + ENER_TOT + TRAV_AMOR - TRAV_EXT): {why}; this alarm is given once",
        -energy.contact,
        energy.contact,
        -100.0 * energy.contact / given,
        100.0 * surplus / given,
    ))
}

/// The energy row of the step just archived, into the balance and the log.
fn log_energy(energy: &mut EnergyBalance, result: &EvolNoli, log: &mut dyn FnMut(&str)) {
    if let Some(s) = result.steps.last() {
        log(&energy.archive(s.nume_ordre, s.inst));
    }
}

/// The balance as the result's PARA_CALC table (RECU_TABLE). A
/// continuation (reuse=) continues the balance from its initial state's
/// row and appends its rows, NUME_REUSE one more, to the table (code_aster's
/// nonlinDSEnergyInitValues, nmarpc, nmarnr).
fn store_energy(engine: &Engine, energy: &EnergyBalance, result: &mut EvolNoli) {
    result.tables.insert(
        super::energy::TABLE_NAME.to_string(),
        energy.table(&format!("energy balance of {}", command(engine))),
    );
}

#[allow(clippy::too_many_arguments)]
fn step_line(
    n: usize,
    t: f64,
    dt: f64,
    rep: &StepReport,
    level: usize,
    tl: &TimeLoop,
    engine: &Engine,
    ndpn: usize,
    offsets: &fields::GaussRows,
) -> String {
    let mut line = format!(
        "  {n:>6}  {t:>13.6e}  {dt:>10.3e}  {:>4}  {:>13.3e}{}  {:>14.3e}  {level:>5}",
        rep.iterations,
        rep.resi_rela,
        if rep.swapped { "*" } else { " " },
        rep.resi_maxi
    );
    for s in &tl.suivi {
        line.push_str(&format!(
            "  {:>14.6e}",
            s.evaluate(&engine.committed, ndpn, offsets)
        ));
    }
    line
}

/// `n` equal steps from `t0` to `t1` as pending targets (the last one
/// exactly `t1`).
fn equal_steps(
    t0: f64,
    t1: f64,
    n: usize,
    level: usize,
    list_end: bool,
) -> Vec<(f64, usize, bool)> {
    let h = (t1 - t0) / n as f64;
    (1..=n)
        .map(|k| {
            if k == n {
                (t1, level, list_end)
            } else {
                (t0 + k as f64 * h, level, false)
            }
        })
        .collect()
}

/// METHODE='AUTO': after a successful step ending at `t`, the pending
/// sub-steps before the next instant of the list are replaced by one step,
/// `choose(next list instant)` ([`Adapter::next`]: the ADAPTATION rules,
/// PAS_MAXI, never beyond that instant: the list's instants are the upper
/// bounds of the steps, and the step reaches them again after a cut).
/// Returns the instant the chosen step reaches (None at the end of the
/// list).
fn grow(
    pending: &mut Vec<(f64, usize, bool)>,
    t: f64,
    choose: impl FnOnce(f64) -> f64,
) -> Option<f64> {
    let &(t_list, level, _) = pending.iter().rev().find(|p| p.2)?;
    while pending.last().is_some_and(|p| !p.2) {
        pending.pop();
    }
    let step = choose(t_list);
    // A remainder below the precision of the instants is not a step.
    if t + step < t_list - 1e-9 * step {
        pending.push((t + step, level, false));
        Some(t + step)
    } else {
        Some(t_list)
    }
}

/// What the contact events say about a converged step.
enum EventOutcome {
    Accept,
    /// Roll the step back and compute `steps` (pending targets) instead.
    Redo {
        note: String,
        steps: Vec<(f64, usize, bool)>,
    },
    /// A failure of the step (handled by the ERREUR rule).
    Fail(String),
}

/// The INTERPENETRATION and COLLISION events after a converged step
/// `(t0, t1, level, list_end)` (semantics.md §7.2). INTERPENETRATION is
/// checked first: a step redone with a stiffer penalty may close other
/// gaps. E_N stays doubled for the rest of the computation, as code_aster
/// keeps the adapted coefficient.
fn check_events(
    c: &mut DiscreteContact,
    ev: &ContactEvents,
    collisions: &mut HashMap<(usize, usize), f64>,
    refine_until: &mut Option<f64>,
    (t0, t1, level, list_end): (f64, f64, usize, bool),
) -> EventOutcome {
    if let Some((pene_maxi, coef_maxi)) = ev.interpenetration {
        let pen = c.trial.max_interpenetration();
        if pen > pene_maxi {
            let zones: HashSet<usize> = c
                .trial
                .links
                .iter()
                .filter(|l| l.gap <= 0.0 && -l.gap > pene_maxi)
                .map(|l| l.zone)
                .collect();
            let mut changed = Vec::new();
            for &z in &zones {
                let zone = &mut c.def.zones[z];
                if zone.e_n < coef_maxi {
                    let old = zone.e_n;
                    zone.e_n = (2.0 * old).min(coef_maxi);
                    changed.push(format!("zone {} E_N {old:e} -> {:e}", z + 1, zone.e_n));
                }
            }
            if changed.is_empty() {
                return EventOutcome::Fail(format!(
                    "INTERPENETRATION: the penetration {pen:.3e} exceeds PENE_MAXI = {pene_maxi:e} with E_N already at COEF_MAXI = {coef_maxi:e}"
                ));
            }
            return EventOutcome::Redo {
                note: format!(
                    "INTERPENETRATION (penetration {pen:.3e} > PENE_MAXI = {pene_maxi:e}), ADAPT_COEF_PENA: {}",
                    changed.join(", ")
                ),
                steps: vec![(t1, level, list_end)],
            };
        }
    }
    if let Some((subd_inst, subd_duree)) = ev.collision {
        let eps = 1e-6 * subd_inst;
        let started = crate::contact::collision_started(&c.committed, &c.trial);
        let mut new = 0usize;
        for (l, s) in c.trial.links.iter().zip(started) {
            let key = (l.zone, l.slave);
            let running = collisions.get(&key).is_some_and(|&end| end > t0 + eps);
            if s && !running {
                collisions.insert(key, t0 + subd_duree);
                new += 1;
            }
        }
        if new > 0 {
            let until = t0 + subd_duree;
            *refine_until = Some(refine_until.map_or(until, |u| u.max(until)));
            let n = ((t1 - t0) / subd_inst).round().max(1.0) as usize;
            if n > 1 {
                return EventOutcome::Redo {
                    note: format!(
                        "COLLISION of {new} link(s), cut into {n} sub-steps of {:.3e} (SUBD_INST = {subd_inst:e}) until t = {until:e}",
                        (t1 - t0) / n as f64
                    ),
                    steps: equal_steps(t0, t1, n, level + 1, list_end),
                };
            }
        }
    }
    EventOutcome::Accept
}

/// "n sub-steps of dt/n (level l+1)", for the messages of a cut.
fn sub_steps(n: usize, dt: f64, level: usize) -> String {
    format!(
        "{n} sub-steps of {:.3e} (level {})",
        dt / n as f64,
        level + 1
    )
}

/// The sub-steps replacing a failed step, or why it cannot be cut.
/// `max_level` is the level limit shared by all the events
/// ([`TimeLoop::subd_niveau`]), not the rule's own SUBD_NIVEAU.
fn cut_step(
    action: &Action,
    t0: f64,
    t_end: f64,
    level: usize,
    list_end: bool,
    max_level: Option<usize>,
) -> Result<Vec<(f64, usize, bool)>, String> {
    let dt = t_end - t0;
    let (n, max_level, mini) = match action {
        Action::Arret => return Err(
            "the time list's ERREUR rule is ARRET (a plain DEFI_LIST_REEL list has no other rule)"
                .into(),
        ),
        Action::Decoupe(Subdivision::Manuel {
            subd_pas,
            subd_pas_mini,
            ..
        }) => (*subd_pas, max_level.unwrap_or(usize::MAX), *subd_pas_mini),
        Action::Decoupe(Subdivision::AutoExtrapole { subd_pas_mini }) => {
            (4, usize::MAX, subd_pas_mini.max(1e-12))
        }
        other => return Err(format!("the ACTION {other} is not implemented")),
    };
    if n < 2 {
        return Err(format!("SUBD_PAS = {n} cannot cut a step"));
    }
    if level >= max_level {
        return Err(format!(
            "the step is already at the maximum subdivision level SUBD_NIVEAU = {max_level} (the largest over the time list's events)"
        ));
    }
    let sub = dt / n as f64;
    if sub < mini || sub <= f64::EPSILON * t_end.abs().max(t0.abs()) {
        return Err(format!(
            "a sub-step of {sub:.3e} would be below SUBD_PAS_MINI = {mini:e}"
        ));
    }
    Ok((1..=n)
        .map(|k| {
            if k == n {
                (t_end, level + 1, list_end)
            } else {
                (t0 + k as f64 * sub, level + 1, false)
            }
        })
        .collect())
}
