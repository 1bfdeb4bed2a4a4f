//! LIAISON_UNIL in the Newton loop: the [`ContactTerm`] that applies the
//! unilateral conditions of `contact::unilateral` step after step, as
//! code_aster's `nmunil`/`algocu`/`algocup` do (liaison-unil.md §3-§5).
//!
//! Active set (`'CONTRAINTE'`): after every linear solve, the prediction
//! included, the unconstrained increment δ⁰ is replaced by the increment
//! of the active-set problem C δ + Aᵀμ = r, g − Aδ ≥ 0, μ ≥ 0, with r the
//! right-hand side *without* the unilateral force, so that μ is the total
//! multiplier, recomputed from scratch at each iteration. The gaps are
//! taken at iteration 0 from the displacement at the start of the
//! iterations, then updated by each corrected increment. The force Aᵀμ
//! enters the convergence residual and the RESI_GLOB_RELA denominator.
//!
//! Penalty (`'PENALISATION'`): at each correction the force E·max(0, −g)
//! and the tangent E AᵀA are taken at the current iterate; the prediction
//! uses the force of the last iteration of the previous step and no
//! penalty matrix.

use super::dofs::{DofNumbering, NONE};
use super::newton::{ContactIteration, ContactTerm, IncrementCorrection};
use crate::contact::unilateral::{active_set, penalty, ActiveSetFailure, Row, UnilAlgo, UnilDef};

/// Counters of a computation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct UnilStats {
    /// Active-set calls (one per linear solve).
    pub calls: usize,
    /// Passes of those calls (converging passes included).
    pub passes: usize,
    /// The most passes of one call.
    pub max_passes: usize,
    /// Links active (or penetrating) at the last converged step.
    pub active: usize,
}

/// The unilateral term of one DYNA_NON_LINE computation.
pub struct UnilateralContact {
    pub def: UnilDef,
    ndpn: usize,
    rows: Vec<Row>,
    /// Why the coefficients could not be evaluated at this step's end.
    row_error: Option<String>,
    /// Pseudo-gaps c − A u of the step's iterate, from the first solve of
    /// the step on (None before), updated by the increments.
    gaps: Option<Vec<f64>>,
    /// Aᵀμ (active set) or Σ λ Aᵀ (penalty) of the last iteration, full.
    force: Vec<f64>,
    /// The penalty force of the last converged step (the prediction's).
    committed_force: Vec<f64>,
    /// Links never to be tested again by the step length (zero rows).
    zero_set: Vec<bool>,
    active_now: usize,
    pub stats: UnilStats,
    /// Links violated at the end of a converged step that nothing holds,
    /// with their most negative gap: a link whose every component is
    /// imposed (an empty row), or one dropped for a zero row of the Schur
    /// complement.
    pub unheld: std::collections::BTreeMap<usize, f64>,
}

impl UnilateralContact {
    pub fn new(def: UnilDef, numbering: &DofNumbering) -> Self {
        let nl = def.links.len();
        let n = numbering.nfull();
        UnilateralContact {
            def,
            ndpn: numbering.ndpn,
            rows: Vec::new(),
            row_error: None,
            gaps: None,
            force: vec![0.0; n],
            committed_force: vec![0.0; n],
            zero_set: vec![false; nl],
            active_now: 0,
            stats: UnilStats::default(),
            unheld: Default::default(),
        }
    }

    /// Accepts the last step: its force is the next prediction's.
    pub fn commit(&mut self) {
        self.committed_force.clone_from(&self.force);
        self.stats.active = self.active_now;
        for (i, row) in self.rows.iter().enumerate() {
            if !(row.entries.is_empty() || self.zero_set[i]) {
                continue;
            }
            // An empty row's gap is its c; a dropped one's was updated by
            // every corrected increment.
            let gap = match &self.gaps {
                Some(g) if !row.entries.is_empty() => g[i],
                _ => row.c,
            };
            if gap < 0.0 {
                let worst = self.unheld.entry(i).or_insert(gap);
                *worst = worst.min(gap);
            }
        }
    }

    /// The alarm of the links left violated ([`Self::unheld`]), if any:
    /// code_aster drops such a link from its active set silently but for
    /// a "PIVOT NUL" line (`cupivo`), and its penalty acts on a blocked
    /// dof: the imposed value wins, the condition is not enforced.
    pub fn unheld_alarm(&self) -> Option<String> {
        if self.unheld.is_empty() {
            return None;
        }
        let names = ["DX", "DY", "DZ"];
        let list: Vec<String> = self
            .unheld
            .iter()
            .take(5)
            .map(|(&i, &g)| {
                let l = &self.def.links[i];
                let cmps: Vec<&str> = self.def.zones[l.zone]
                    .components
                    .iter()
                    .map(|(k, _)| *names.get(*k).unwrap_or(&"?"))
                    .collect();
                format!(
                    "link {} (zone {}, node N{}, {}) violated by {:.3e}",
                    i + 1,
                    l.zone + 1,
                    l.node + 1,
                    cmps.join("+"),
                    -g
                )
            })
            .collect();
        Some(format!(
            "alarm: LIAISON_UNIL: {} link(s) violated at the end of a step are held by nothing: {}{}; \
             a link whose components are all imposed by DDL_IMPO, or whose COEF_MULT are all zero, \
             has no unknown and the imposed values win: code_aster drops it from its active set (a zero pivot of the contact matrix, \
             `LIAISON i (node - cmp): PIVOT NUL` in its message file) and its penalty acts on a blocked dof; \
             the condition is not enforced there",
            self.unheld.len(),
            list.join(", "),
            if self.unheld.len() > 5 { ", ..." } else { "" }
        ))
    }

    /// The unilateral force of the last iteration (full, on the
    /// internal-force side: the reaction on the structure is its opposite).
    pub fn force(&self) -> &[f64] {
        &self.force
    }

    fn full_force(&mut self, numbering: &DofNumbering, weights: &[(usize, f64)]) {
        self.force.iter_mut().for_each(|v| *v = 0.0);
        let mut eqf = vec![0.0; numbering.neq()];
        for &(i, s) in weights {
            self.rows[i].add_transpose(s, &mut eqf);
        }
        for (e, &f) in numbering.free.iter().enumerate() {
            self.force[f] = eqf[e];
        }
    }
}

/// The pseudo-gaps c − A u of `rows` at the full displacement `u`.
fn gaps_of(rows: &[Row], nb: &DofNumbering, u: &[f64]) -> Vec<f64> {
    let mut ueq = vec![0.0; nb.neq()];
    for (e, &f) in nb.free.iter().enumerate() {
        ueq[e] = u[f];
    }
    rows.iter().map(|r| r.c - r.dot(&ueq)).collect()
}

/// The DDL_IMPO value of a full dof, if it is imposed.
pub fn imposed_value(numbering: &DofNumbering) -> impl Fn(usize) -> Option<f64> {
    let map: std::collections::HashMap<usize, f64> = numbering.imposed.iter().copied().collect();
    move |f| map.get(&f).copied()
}

impl ContactTerm for UnilateralContact {
    fn begin_step(&mut self, numbering: &DofNumbering, _u_start: &[f64], t: f64, dt: f64) {
        // Coefficients frozen at the end of the step for the whole step.
        let eq = |f: usize| (numbering.eq[f] != NONE).then(|| numbering.eq[f]);
        match self
            .def
            .rows(t + dt, self.ndpn, eq, imposed_value(numbering))
        {
            Ok(r) => {
                self.rows = r;
                self.row_error = None;
            }
            Err(e) => {
                self.rows.clear();
                self.row_error = Some(format!("LIAISON_UNIL at INST = {:e}: {e}", t + dt));
            }
        }
        self.gaps = None;
    }

    fn pattern_entries(&self) -> &[(usize, usize)] {
        // A link couples the components of one node, already coupled by
        // any element holding it.
        &[]
    }

    fn add(&mut self, it: ContactIteration) -> Result<(), String> {
        if let Some(e) = &self.row_error {
            return Err(e.clone());
        }
        match self.def.algo {
            UnilAlgo::ActiveSet => {
                if it.iteration == 0 {
                    return Ok(());
                }
                for (f, &v) in self.force.iter().enumerate() {
                    if v != 0.0 {
                        it.residual[f] += v;
                        it.force[f] += v;
                        it.rhs_excluded[f] += v;
                    }
                }
            }
            UnilAlgo::Penalty => {
                if it.iteration == 0 {
                    self.force.clone_from(&self.committed_force);
                } else {
                    let nb = it.numbering;
                    // Kept by `correct` after every solve; from u only if
                    // no solve of the step came first.
                    let fresh;
                    let gaps: &[f64] = match &self.gaps {
                        Some(g) => g,
                        None => {
                            fresh = gaps_of(&self.rows, nb, it.u);
                            &fresh
                        }
                    };
                    let mut weights = Vec::new();
                    let mut matrix = it.matrix;
                    for (i, row) in self.rows.iter().enumerate() {
                        let z = self.def.links[i].zone;
                        let e = self.def.zones[z].coef_pena.unwrap_or(0.0);
                        let gap = gaps[i];
                        if let Some(lambda) = penalty(gap, e) {
                            weights.push((i, lambda));
                            if let Some(m) = matrix.as_deref_mut() {
                                for &(a, ca) in &row.entries {
                                    for &(b, cb) in &row.entries {
                                        m.add(a, b, e * ca * cb);
                                    }
                                }
                            }
                        }
                    }
                    self.active_now = weights.len();
                    self.full_force(nb, &weights);
                }
                for (f, &v) in self.force.iter().enumerate() {
                    if v != 0.0 {
                        it.residual[f] += v;
                        it.force[f] += v;
                    }
                }
            }
        }
        Ok(())
    }

    fn accept(&mut self, _numbering: &DofNumbering, _u: &[f64]) -> Result<bool, String> {
        Ok(true)
    }

    fn correct(&mut self, c: IncrementCorrection) -> Result<(), String> {
        let nb = c.numbering;
        let rows = &self.rows;
        let gaps = self.gaps.get_or_insert_with(|| gaps_of(rows, nb, c.u));
        if self.def.algo == UnilAlgo::Penalty {
            // The penalty reads the gap of the new iterate, c − A(u + δ)
            // (liaison-unil.md §5), kept here as the step's first gap
            // minus the increments. From the total displacement it would
            // be known only to the ulp of u (4.4e-16 at u = −2.27), i.e.
            // the force to COEF_PENA × 4.4e-16 = 0.044 N per link at
            // COEF_PENA = 1e14: a floor under which the residual of K's
            // impact stalled (RESI_GLOB_RELA 1.17e-6 for 1e-6). The
            // increments' sum is known to the ulp of the step's motion.
            for (g, r) in gaps.iter_mut().zip(rows) {
                *g -= r.dot(c.delta);
            }
            return Ok(());
        }
        let solver = c.solver;
        let mut solve = |b: &mut [f64]| solver.solve(b).map_err(|e| e.to_string());
        let links = &self.def.links;
        let r = active_set(rows, gaps, c.delta, &mut solve, &mut self.zero_set).map_err(|e| {
            match e {
                // The link number alone makes the user count links.
                ActiveSetFailure::Singular { link } => {
                    let l = &links[link];
                    format!(
                        "{e}: zone {} of LIAISON_UNIL, node N{} at ({}, {}, {})",
                        l.zone + 1,
                        l.node + 1,
                        l.coords[0],
                        l.coords[1],
                        l.coords[2]
                    )
                }
                _ => e.to_string(),
            }
        })?;
        self.stats.calls += 1;
        self.stats.passes += r.passes + 1;
        self.stats.max_passes = self.stats.max_passes.max(r.passes + 1);
        self.active_now = r.active.len();
        let weights: Vec<(usize, f64)> = r.active.iter().copied().zip(r.mu).collect();
        self.full_force(nb, &weights);
        Ok(())
    }
}
