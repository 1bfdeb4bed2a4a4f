//! Discrete penalised contact with Coulomb friction in the Newton loop:
//! the [`ContactTerm`] that drives the `contact` library (pairing,
//! evaluation, CONT_NOEU) step after step (docs/contact.md §6).
//!
//! The geometric loop (REAC_GEOM, semantics.md §6.3) runs inside the
//! Newton loop, as code_aster's discrete method does: the first pairing is
//! made on the geometry at the start of the step, each further one after
//! Newton has converged, and the iterations then continue with the new
//! pairing at the same displacement (the same ITER_GLOB_MAXI counter).

use super::contact_active::ActiveSetContact;
use super::continuous::ContinuousContact;
use super::dofs::{DofNumbering, NONE};
use super::newton::{ContactIteration, ContactTerm, ImposedIncrement, IncrementCorrection};
use crate::contact::{
    evaluate, evaluate_armed, pair, ContactDef, ContactState, DiscreteAlgo, IterationInput,
    LinkStatus, Pairing, ReacGeom,
};
use crate::mesh::Mesh;
use crate::result::NodalField;

/// The contact term of one DYNA_NON_LINE computation: the discrete
/// penalised method, or, when `continuous` is set, the continuous
/// formulation (`nonlinear::continuous`), which this type then delegates
/// to so that the time loop and its events handle both the same way.
pub struct DiscreteContact {
    /// FORMULATION='CONTINUE': the term that does the work.
    pub continuous: Option<ContinuousContact>,
    /// ALGO_CONT='CONTRAINTE': the active set, which replaces the
    /// penalised forces.
    pub active: Option<ActiveSetContact>,
    pub def: ContactDef,
    mesh: Mesh,
    ndpn: usize,
    pairing: Option<Pairing>,
    /// Pairings made in the current step (REAC_GEOM counters).
    pairings_in_step: usize,
    /// Displacements (per node) at the start of the step: the origin of
    /// the friction slip.
    u_start: Vec<[f64; 3]>,
    /// Full displacement at the last pairing (REAC_GEOM='AUTOMATIQUE').
    u_paired: Vec<f64>,
    entries: Vec<(usize, usize)>,
    /// State of the last evaluation (the trial step).
    pub trial: ContactState,
    /// State of the last committed step, percussion included.
    pub committed: ContactState,
    /// Pairings made in total (for the log and the tests).
    pub pairings: usize,
    /// Converged steps committed so far: before the first one CONT_NOEU
    /// is code_aster's initial field (zeros on the slave nodes).
    pub steps_committed: usize,
    /// Per evaluation since the step's start (or its last pairing): the
    /// RESI_GLOB_RELA the iteration was given and the links' statuses, for
    /// [`newton_cycle`].
    iterates: Vec<(f64, Vec<LinkIterate>)>,
    /// code_aster's friction flag per slave node (`cffpfo`, `cffpm2`;
    /// [`crate::contact::evaluate_armed`]): the node's link was in contact
    /// at the previous evaluation. Never reset between steps, at a cut or
    /// at a pairing (code_aster's `cfinit` and pairing leave it).
    armed: Vec<bool>,
}

/// Relative agreement of two RESI_GLOB_RELA for [`newton_cycle`] to call
/// them the same iterate.
const CYCLE_RESI_TOLERANCE: f64 = 1e-6;

/// One link in one evaluation, as [`newton_cycle`] compares them: the
/// slave node, its status, and for a sliding link the sign (+1 or -1) of
/// its slip along each tangent (0 otherwise). The signs matter because a
/// sliding link's friction force jumps with the slip direction while its
/// status stays "slip": a body whose friction should hold it can be thrown
/// from one slip direction to the other at every iteration (the 2D slip
/// tangent is zero with COEF_MATR_FROT = 1, docs/contact.md §3).
pub type LinkIterate = (usize, LinkStatus, [i8; 2]);

/// The [`LinkIterate`] of a link state.
pub fn link_iterate(l: &crate::contact::LinkState) -> LinkIterate {
    let sign = |k: usize| -> i8 {
        if l.status != LinkStatus::Slip || k >= l.ntangents || l.slip[k] == 0.0 {
            0
        } else if l.slip[k] > 0.0 {
            1
        } else {
            -1
        }
    };
    (l.slave, l.status, [sign(0), sign(1)])
}

/// A Newton cycle of the discrete penalised contact: the last `3p`
/// evaluations (p = 2, 3 or 4) repeat with period p, each its statuses
/// (with the slip directions) exactly and its RESI_GLOB_RELA to
/// [`CYCLE_RESI_TOLERANCE`], and at least one link changes status or slip
/// direction within the period. Newton's map is then back where it was
/// and goes round forever: the message names the period, the repeated
/// residuals and the slave nodes that switch (with their statuses over
/// one period, CONT codes: 0 open, 1 stick, 2 slip, followed for a slip
/// by the signs of its components along the tangents). Each entry of
/// `iterates` is (RESI_GLOB_RELA given to the iteration, one
/// [`LinkIterate`] per link).
pub fn newton_cycle(iterates: &[(f64, Vec<LinkIterate>)]) -> Option<String> {
    let n = iterates.len();
    let same = |a: &(f64, Vec<LinkIterate>), b: &(f64, Vec<LinkIterate>)| {
        a.0.is_finite()
            && b.0.is_finite()
            && (a.0 - b.0).abs() <= CYCLE_RESI_TOLERANCE * a.0.abs().max(b.0.abs())
            && a.1 == b.1
    };
    for p in 2..=4 {
        if n < 3 * p || !(n - 2 * p..n).all(|k| same(&iterates[k], &iterates[k - p])) {
            continue;
        }
        let period = &iterates[n - p..];
        let nlinks = period[0].1.len();
        let code = |(_, s, d): LinkIterate| {
            let base = match s {
                LinkStatus::Unpaired => "-1",
                LinkStatus::Open => "0",
                LinkStatus::Stick => "1",
                LinkStatus::Slip => "2",
            };
            let signs: String = d
                .iter()
                .filter(|&&x| x != 0)
                .map(|&x| if x > 0 { '+' } else { '-' })
                .collect();
            format!("{base}{signs}")
        };
        let switching: Vec<String> = (0..nlinks)
            .filter(|&l| period.iter().any(|it| it.1[l] != period[0].1[l]))
            .map(|l| {
                let seq: Vec<String> = period.iter().map(|it| code(it.1[l])).collect();
                format!("N{} ({})", period[0].1[l].0 + 1, seq.join(" -> "))
            })
            .collect();
        if switching.is_empty() {
            continue;
        }
        let status = |l: usize, s: LinkStatus| period.iter().any(|it| it.1[l].1 == s);
        let contact = (0..nlinks).any(|l| {
            status(l, LinkStatus::Open) && period.iter().any(|it| it.1[l].1 != LinkStatus::Open)
        });
        let friction =
            (0..nlinks).any(|l| status(l, LinkStatus::Stick) && status(l, LinkStatus::Slip));
        let direction = (0..nlinks).any(|l| {
            period.iter().any(|a| {
                period.iter().any(|b| {
                    a.1[l].1 == LinkStatus::Slip
                        && b.1[l].1 == LinkStatus::Slip
                        && a.1[l].2 != b.1[l].2
                })
            })
        });
        let mut what = Vec::new();
        if contact {
            what.push("between contact and open");
        }
        if friction {
            what.push("between stick and slip");
        }
        if direction {
            what.push("between slip directions");
        }
        if what.is_empty() {
            what.push("status");
        }
        let resi: Vec<String> = period.iter().map(|it| format!("{:.4e}", it.0)).collect();
        let shown = switching.len().min(12);
        return Some(format!(
            "discrete contact: Newton cycles with period {p} (RESI_GLOB_RELA {} repeated over the last {} iterations): {} slave node(s) switch {} and come back: {}{}; the step is abandoned now instead of after ITER_GLOB_MAXI (DEFI_LIST_INST ECHEC/EVENEMENT='ERREUR' ACTION='DECOUPE' cuts it)",
            resi.join(", "),
            3 * p,
            switching.len(),
            what.join(" and "),
            switching[..shown].join(", "),
            if shown < switching.len() { ", ..." } else { "" },
        ));
    }
    None
}

pub(super) fn per_node(ndpn: usize, u: &[f64]) -> Vec<[f64; 3]> {
    u.chunks(ndpn)
        .map(|c| {
            let mut v = [0.0; 3];
            v[..ndpn].copy_from_slice(c);
            v
        })
        .collect()
}

impl DiscreteContact {
    /// A contact term at the state `u0` (full): the first pairing is made
    /// there, and its evaluation is the state of the initial instant (its
    /// CONT_NOEU gives the initial gaps).
    pub fn new(def: ContactDef, mesh: &Mesh, numbering: &DofNumbering, u0: &[f64]) -> Self {
        let ndpn = numbering.ndpn;
        let mut c = DiscreteContact {
            continuous: None,
            active: (def.algo == DiscreteAlgo::ActiveSet).then(|| ActiveSetContact::new(numbering)),
            def,
            mesh: mesh.clone(),
            ndpn,
            pairing: None,
            pairings_in_step: 0,
            u_start: per_node(ndpn, u0),
            u_paired: u0.to_vec(),
            entries: Vec::new(),
            trial: ContactState::default(),
            committed: ContactState::default(),
            pairings: 0,
            steps_committed: 0,
            iterates: Vec::new(),
            armed: vec![false; mesh.nnodes()],
        };
        c.repair(numbering, u0);
        let u = c.u_start.clone();
        let (_, st) = evaluate(
            &c.def,
            c.pairing.as_ref().expect("paired above"),
            &IterationInput {
                u: &u,
                u_start: &u,
                resi_glob_rela: f64::INFINITY,
                symmetrise: true,
            },
            |_, _| None,
        );
        // The evaluation of the initial state counts as the previous
        // contact call: a body that starts in contact (ETAT_INIT) has its
        // friction from the first iteration, as it would have had in the
        // run that computed that state.
        for l in &st.links {
            c.armed[l.slave] = l.status != LinkStatus::Open;
        }
        c.committed = st.clone();
        c.trial = st;
        c
    }

    /// The contact term of `def`, continuous when `def.continuous` is set
    /// (`axis`: AXIS model, the continuous points' weights carry r).
    /// Errors: what the continuous formulation does not implement.
    pub fn build(
        def: ContactDef,
        mesh: &Mesh,
        numbering: &DofNumbering,
        u0: &[f64],
        axis: bool,
    ) -> Result<Self, String> {
        let Some(cdef) = def.continuous.clone() else {
            return Ok(Self::new(def, mesh, numbering, u0));
        };
        let cc = ContinuousContact::new(def.clone(), cdef, mesh, numbering, u0, axis)?;
        Ok(DiscreteContact {
            trial: cc.trial.clone(),
            committed: cc.committed.clone(),
            continuous: Some(cc),
            active: None,
            def,
            mesh: mesh.clone(),
            ndpn: numbering.ndpn,
            pairing: None,
            pairings_in_step: 0,
            u_start: Vec::new(),
            u_paired: Vec::new(),
            entries: Vec::new(),
            pairings: 0,
            steps_committed: 0,
            iterates: Vec::new(),
            armed: Vec::new(),
        })
    }

    /// The alarm of slave nodes that penetrate their master at the state
    /// the term was built on (its first pairing), as the explicit run
    /// gives it; None when none does, or for the continuous formulation
    /// (no discrete links).
    pub fn initial_penetration_alarm(&self) -> Option<String> {
        let p = self.pairing.as_ref()?;
        let (n, depth) = crate::contact::penetrations(p, |k| self.u_start[k]);
        let how = match self.def.algo {
            crate::contact::DiscreteAlgo::ActiveSet => {
                "ALGO_CONT='CONTRAINTE': the active set puts them back on the surface"
            }
            crate::contact::DiscreteAlgo::Penalty => "penalty: a force E_N times the depth",
        };
        (n > 0).then(|| crate::contact::initial_penetration_alarm(n, depth, how))
    }

    /// Adds the contact multipliers (LAGS_C, LAGS_F1) of the committed
    /// step to a DEPL field (continuous formulation only).
    pub fn extend_depl(&self, depl: &mut NodalField) {
        if let Some(c) = &self.continuous {
            c.extend_depl(depl);
        }
    }

    /// Pairs on the geometry of `u` (full) and lists the couplings.
    fn repair(&mut self, numbering: &DofNumbering, u: &[f64]) {
        let un = per_node(self.ndpn, u);
        let p = pair(&self.def, &self.mesh, &un);
        let d = self.def.dim.min(self.ndpn);
        let mut entries = Vec::new();
        // The active set adds no stiffness (it works on the Schur
        // complement of the factorised matrix): no couplings to list.
        let stiff_links = if self.active.is_some() {
            &[][..]
        } else {
            &p.links[..]
        };
        for l in stiff_links {
            let eqs: Vec<usize> = std::iter::once(l.slave)
                .chain(l.master_nodes.iter().copied())
                .flat_map(|n| (0..d).map(move |c| n * numbering.ndpn + c))
                .map(|f| numbering.eq[f])
                .filter(|&e| e != NONE)
                .collect();
            for &a in &eqs {
                for &b in &eqs {
                    entries.push((a, b));
                }
            }
        }
        if let Some(a) = self.active.as_mut() {
            a.rebuild(&self.def, &p, numbering);
        }
        entries.sort_unstable();
        entries.dedup();
        self.entries = entries;
        self.pairing = Some(p);
        self.u_paired.clear();
        self.u_paired.extend_from_slice(u);
        self.pairings_in_step += 1;
        self.pairings += 1;
        self.iterates.clear();
        crate::profile::count(crate::profile::Counter::Pairings, 1);
    }

    /// Accepts the trial state of a converged step of length `dt`: the
    /// percussion is R·dt of this step (code_aster's `cfresu`; the
    /// continuous formulation accumulates it, `ContinuousContact::commit`).
    pub fn commit(&mut self, dt: f64) {
        if let Some(c) = self.continuous.as_mut() {
            c.commit(dt);
            self.committed = c.committed.clone();
            self.steps_committed += 1;
            return;
        }
        let mut st = self.trial.clone();
        st.step_percussion(dt);
        self.committed = st;
        self.steps_committed += 1;
    }

    /// CONT_NOEU of the committed state; at the initial instant (no step
    /// committed yet) all its components are 0 on the slave nodes, as in
    /// code_aster (`ContactState::cont_noeu_initial`).
    pub fn cont_noeu(&self) -> NodalField {
        if self.steps_committed == 0 {
            self.committed.cont_noeu_initial(self.mesh.nnodes())
        } else if let Some(c) = &self.continuous {
            c.cont_noeu()
        } else {
            self.committed.cont_noeu(self.mesh.nnodes())
        }
    }
}

impl ContactTerm for DiscreteContact {
    fn begin_step(&mut self, numbering: &DofNumbering, u_start: &[f64], _t: f64, _dt: f64) {
        if let Some(c) = self.continuous.as_mut() {
            c.begin_step(u_start);
            return;
        }
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        self.u_start = per_node(self.ndpn, u_start);
        self.pairings_in_step = 0;
        self.iterates.clear();
        if let Some(a) = self.active.as_mut() {
            a.begin_step();
        }
        // REAC_GEOM='SANS' keeps the first pairing of the computation
        // (semantics.md §14 leaves "once per step" open; docs/contact.md).
        if self.def.reac_geom != ReacGeom::Sans || self.pairing.is_none() {
            self.repair(numbering, u_start);
        }
    }

    fn pattern_entries(&self) -> &[(usize, usize)] {
        if let Some(c) = &self.continuous {
            return c.pattern_entries();
        }
        &self.entries
    }

    fn imposed_increment(&mut self, it: ImposedIncrement) -> Result<(), String> {
        if let Some(c) = self.continuous.as_ref() {
            c.imposed_increment(it.numbering, it.u_start, it.du, it.matrix, it.rhs);
            return Ok(());
        }
        // The active set adds no stiffness: nothing to add.
        if self.active.is_some() {
            return Ok(());
        }
        // Penalised contact: its tangent at the step's start (the links
        // in contact there, sticking: the slip origin is that state) joins
        // the prediction's matrix, and the change of its forces under the
        // imposed increment its right-hand side. Without it a body that
        // only the contact holds (a block pressed on a support, then
        // dragged by a DDL_IMPO under a FONC_MULT) made the prediction of
        // STAT_NON_LINE singular at the first step whose imposed values
        // move, though every iteration's matrix has the contact (probe11
        // p5: "the matrix is singular ... translation DZ of the part").
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        let Some(pairing) = self.pairing.as_ref() else {
            return Ok(());
        };
        let nb = it.numbering;
        let u0 = per_node(self.ndpn, it.u_start);
        let moved: Vec<f64> = it.u_start.iter().zip(it.du).map(|(a, b)| a + b).collect();
        let u1 = per_node(self.ndpn, &moved);
        let dof = |n: usize, c: usize| {
            let e = nb.eq[n * nb.ndpn + c];
            (c < nb.ndpn && e != NONE).then_some(e)
        };
        let eval = |u: &[[f64; 3]]| {
            evaluate_armed(
                &self.def,
                pairing,
                &IterationInput {
                    u,
                    u_start: &u0,
                    resi_glob_rela: f64::INFINITY,
                    symmetrise: true,
                },
                Some(&self.armed),
                dof,
            )
            .0
        };
        let at_start = eval(&u0);
        let at_moved = eval(&u1);
        for &(a, b, v) in &at_start.tangent {
            let p = it.matrix.pattern.position(a, b).ok_or_else(|| {
                format!("the matrix pattern lacks the contact coupling ({a}, {b})")
            })?;
            it.matrix.values[p] += v;
        }
        for &(e, v) in &at_moved.residual {
            it.rhs[e] -= v;
        }
        for &(e, v) in &at_start.residual {
            it.rhs[e] += v;
        }
        Ok(())
    }

    fn add(&mut self, it: ContactIteration) -> Result<(), String> {
        if let Some(c) = self.continuous.as_mut() {
            c.add(it)?;
            self.trial = c.trial.clone();
            return Ok(());
        }
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        let Some(pairing) = self.pairing.as_ref() else {
            return Err("no pairing before the first iteration".into());
        };
        if let Some(a) = self.active.as_mut() {
            self.trial = a.add(&self.def, pairing, it);
            return Ok(());
        }
        let nb = it.numbering;
        let u = per_node(self.ndpn, it.u);
        let (contrib, state) = evaluate_armed(
            &self.def,
            pairing,
            &IterationInput {
                u: &u,
                u_start: &self.u_start,
                resi_glob_rela: it.resi_glob_rela,
                symmetrise: true,
            },
            Some(&self.armed),
            |n, c| {
                let e = nb.eq[n * nb.ndpn + c];
                (c < nb.ndpn && e != NONE).then_some(e)
            },
        );
        for l in &state.links {
            self.armed[l.slave] = l.status != LinkStatus::Open;
        }
        for (n, v) in &contrib.nodal {
            for (c, x) in v.iter().enumerate().take(self.ndpn) {
                let f = n * self.ndpn + c;
                it.residual[f] += x;
                it.force[f] += x;
            }
        }
        if let Some(m) = it.matrix {
            for &(a, b, v) in &contrib.tangent {
                let p = m.pattern.position(a, b).ok_or_else(|| {
                    format!("the matrix pattern lacks the contact coupling ({a}, {b})")
                })?;
                m.values[p] += v;
            }
        }
        self.iterates.push((
            it.resi_glob_rela,
            state.links.iter().map(link_iterate).collect(),
        ));
        self.trial = state;
        match newton_cycle(&self.iterates) {
            Some(m) => Err(m),
            None => Ok(()),
        }
    }

    fn accept(&mut self, numbering: &DofNumbering, u: &[f64]) -> Result<bool, String> {
        if let Some(c) = self.continuous.as_mut() {
            return c.accept(u);
        }
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        match self.def.reac_geom {
            ReacGeom::Sans => Ok(true),
            ReacGeom::Controle { nb_iter_geom } => {
                if self.pairings_in_step >= nb_iter_geom {
                    Ok(true)
                } else {
                    self.repair(numbering, u);
                    Ok(false)
                }
            }
            ReacGeom::Automatique {
                iter_geom_maxi,
                resi_geom,
            } => {
                let mut du: f64 = 0.0;
                let mut um: f64 = 0.0;
                for (a, b) in u.iter().zip(&self.u_paired) {
                    du = du.max((a - b).abs());
                    um = um.max(a.abs());
                }
                if um == 0.0 || du / um < resi_geom {
                    return Ok(true);
                }
                if self.pairings_in_step > iter_geom_maxi {
                    return Err(format!(
                        "the geometric loop (REAC_GEOM='AUTOMATIQUE') did not converge in ITER_GEOM_MAXI = {iter_geom_maxi} pairings: max|du| / max|u| = {:.3e} > RESI_GEOM = {resi_geom:e}",
                        du / um
                    ));
                }
                self.repair(numbering, u);
                Ok(false)
            }
        }
    }

    fn correct(&mut self, c: IncrementCorrection) -> Result<(), String> {
        let (Some(a), Some(p)) = (self.active.as_mut(), self.pairing.as_ref()) else {
            return Ok(());
        };
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        a.correct(p, c)
    }

    fn extra_unknowns(&self) -> usize {
        self.continuous
            .as_ref()
            .map_or(0, ContinuousContact::extra_unknowns)
    }

    fn extra_residual(&self) -> &[f64] {
        self.continuous
            .as_ref()
            .map_or(&[], ContinuousContact::extra_residual)
    }

    fn apply_extra(&mut self, dx: &[f64]) {
        if let Some(c) = self.continuous.as_mut() {
            c.apply_extra(dx);
        }
    }

    fn settled(&self) -> bool {
        self.continuous
            .as_ref()
            .is_none_or(ContinuousContact::settled)
            && self.active.as_ref().is_none_or(ActiveSetContact::settled)
    }
}
