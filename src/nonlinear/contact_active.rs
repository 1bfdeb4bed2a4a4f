//! Discrete contact with `ALGO_CONT='CONTRAINTE'` in the Newton loop:
//! code_aster's `algoco`, the primal active set on the Schur complement
//! that LIAISON_UNIL's `algocu` was drawn from (docs/contact.md §7).
//!
//! Each link of the current pairing is the inequality g(u) ≥ 0, linear in
//! u at fixed pairing (`contact::discrete::link_constraint`); the QUAD8
//! mid-node ties of the definition are equalities carried as links
//! always active. After every linear solve, the prediction included, the
//! unconstrained increment is replaced by the one of the active-set
//! problem, whose multipliers are totals recomputed from scratch; their
//! force enters the residual and the RESI_GLOB_RELA denominator, not the
//! next right-hand side. The gaps are taken at the first solve after a
//! pairing from the current displacement and then updated by each
//! corrected increment, as `algoco` updates JEUITE.
//!
//! The force also lands on imposed dofs (a master surface held by
//! DDL_IMPO), so that the reactions there include the contact, as
//! code_aster's dualised conditions pick it up.

use super::contact::per_node;
use super::dofs::{DofNumbering, NONE};
use super::newton::{ContactIteration, IncrementCorrection};
use crate::contact::discrete::{link_constraint, link_gap};
use crate::contact::unilateral::{active_set_with_equalities, ActiveSetFailure, Row};
use crate::contact::{ContactDef, ContactState, LinkState, LinkStatus, Pairing};

/// Counters of a computation (the .mess reports them).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ActiveSetStats {
    /// Active-set calls (one per linear solve).
    pub calls: usize,
    /// Passes of those calls (the converging pass included).
    pub passes: usize,
    /// The most passes of one call.
    pub max_passes: usize,
}

/// One constraint on the full dofs and on the free equations.
struct Constraint {
    /// (full dof, coefficient), imposed dofs included.
    full: Vec<(usize, f64)>,
}

/// The active-set state of a discrete contact term.
pub struct ActiveSetContact {
    /// Ties first (equalities), then one row per link of the pairing.
    constraints: Vec<Constraint>,
    rows: Vec<Row>,
    ties: usize,
    /// Pseudo-gaps c − A u at the current iterate (None until the first
    /// solve after a pairing).
    gaps: Option<Vec<f64>>,
    /// Multiplier of every row at the last solve (0 when inactive).
    mu: Vec<f64>,
    /// Σ μ Aᵀ on the full dofs.
    force: Vec<f64>,
    /// Rows never tested again by the step length (zero rows), reset with
    /// the pairing that numbers them.
    zero_set: Vec<bool>,
    /// No solve since the last pairing: the multipliers belong to the
    /// previous links, so Newton must iterate once more (the geometric
    /// loop's new pairing is resolved, as code_aster's `cfalgo` runs after
    /// each solve of the loop).
    stale: bool,
    pub stats: ActiveSetStats,
}

impl ActiveSetContact {
    pub fn new(numbering: &DofNumbering) -> Self {
        ActiveSetContact {
            constraints: Vec::new(),
            rows: Vec::new(),
            ties: 0,
            gaps: None,
            mu: Vec::new(),
            force: vec![0.0; numbering.nfull()],
            zero_set: Vec::new(),
            stale: true,
            stats: ActiveSetStats::default(),
        }
    }

    /// The constraints of a new pairing (and of the ties, which do not
    /// change): called at every pairing; the gaps are then retaken.
    pub fn rebuild(&mut self, def: &ContactDef, pairing: &Pairing, numbering: &DofNumbering) {
        let ndpn = numbering.ndpn;
        let dim = def.dim.min(ndpn);
        let mut constraints = Vec::new();
        for t in &def.ties {
            for c in 0..dim {
                constraints.push(Constraint {
                    full: vec![
                        (t.mid * ndpn + c, 1.0),
                        (t.ends[0] * ndpn + c, -0.5),
                        (t.ends[1] * ndpn + c, -0.5),
                    ],
                });
            }
        }
        // A tie on imposed dofs only is no unknown's business: leave it out
        // (its zero row would make the Schur complement singular).
        constraints.retain(|k| k.full.iter().any(|&(f, _)| numbering.eq[f] != NONE));
        self.ties = constraints.len();
        for l in &pairing.links {
            constraints.push(Constraint {
                full: link_constraint(l, dim)
                    .into_iter()
                    .map(|((n, c), a)| (n * ndpn + c, a))
                    .collect(),
            });
        }
        self.rows = constraints
            .iter()
            .map(|k| Row {
                entries: k
                    .full
                    .iter()
                    .filter(|&&(f, _)| numbering.eq[f] != NONE)
                    .map(|&(f, a)| (numbering.eq[f], a))
                    .collect(),
                c: 0.0,
            })
            .collect();
        self.constraints = constraints;
        self.zero_set = vec![false; self.rows.len()];
        self.mu = vec![0.0; self.rows.len()];
        self.gaps = None;
        self.stale = true;
    }

    /// False until a solve has run the active set on the current pairing.
    pub fn settled(&self) -> bool {
        !self.stale
    }

    /// A new step: no multiplier yet (the prediction is solved without the
    /// contact force, as `nmassp` leaves it out); the gaps are retaken at
    /// the first solve.
    pub fn begin_step(&mut self) {
        self.gaps = None;
        self.mu.iter_mut().for_each(|m| *m = 0.0);
        self.force.iter_mut().for_each(|f| *f = 0.0);
    }

    /// Gaps of every row at the full displacement `u`: c − A u, with c = 0
    /// for a tie and g_ref for a link.
    fn gaps_at(&self, pairing: &Pairing, u: &[f64], ndpn: usize) -> Vec<f64> {
        let un = per_node(ndpn, u);
        let mut g: Vec<f64> = self.constraints[..self.ties]
            .iter()
            .map(|k| -k.full.iter().map(|&(f, a)| a * u[f]).sum::<f64>())
            .collect();
        g.extend(pairing.links.iter().map(|l| link_gap(l, &un)));
        g
    }

    /// Adds the multipliers' force of the last solve and returns the state
    /// of the links at `it.u` (CONT_NOEU, the events).
    pub fn add(
        &mut self,
        def: &ContactDef,
        pairing: &Pairing,
        it: ContactIteration,
    ) -> ContactState {
        if it.iteration > 0 {
            for (f, &v) in self.force.iter().enumerate() {
                if v != 0.0 {
                    it.residual[f] += v;
                    it.force[f] += v;
                    it.rhs_excluded[f] += v;
                }
            }
        }
        let un = per_node(it.numbering.ndpn, it.u);
        let mut state = ContactState {
            dim: def.dim,
            links: Vec::with_capacity(pairing.links.len()),
            unpaired: pairing.unpaired.clone(),
        };
        for (i, l) in pairing.links.iter().enumerate() {
            let mu = if it.iteration > 0 {
                self.mu[self.ties + i]
            } else {
                0.0
            };
            state.links.push(LinkState {
                zone: l.zone,
                slave: l.slave,
                // Frictionless contact is reported as sliding (CONT = 2),
                // as the penalised method does.
                status: if mu > 0.0 {
                    LinkStatus::Slip
                } else {
                    LinkStatus::Open
                },
                gap: link_gap(l, &un),
                lambda_n: mu,
                normal: l.normal,
                tangents: l.tangents,
                ntangents: l.ntangents,
                frictional: false,
                slip: [0.0; 2],
                friction: [0.0; 2],
                proj: l.proj,
                percussion: [0.0; 4],
            });
        }
        state
    }

    /// Replaces the solved increment by the active set's.
    pub fn correct(&mut self, pairing: &Pairing, c: IncrementCorrection) -> Result<(), String> {
        let nb = c.numbering;
        if self.gaps.is_none() {
            self.gaps = Some(self.gaps_at(pairing, c.u, nb.ndpn));
        }
        let gaps = self.gaps.as_mut().expect("set above");
        let solver = c.solver;
        let mut solve = |b: &mut [f64]| solver.solve(b).map_err(|e| e.to_string());
        let r = active_set_with_equalities(
            &self.rows,
            self.ties,
            gaps,
            c.delta,
            &mut solve,
            &mut self.zero_set,
        )
        .map_err(|e| failure(e, self.ties))?;
        self.stale = false;
        self.stats.calls += 1;
        self.stats.passes += r.passes + 1;
        self.stats.max_passes = self.stats.max_passes.max(r.passes + 1);
        self.mu.iter_mut().for_each(|m| *m = 0.0);
        self.force.iter_mut().for_each(|f| *f = 0.0);
        for (&j, &m) in r.active.iter().zip(&r.mu) {
            self.mu[j] = m;
            for &(f, a) in &self.constraints[j].full {
                self.force[f] += m * a;
            }
        }
        Ok(())
    }

    /// Active links (ties left out) at the last solve.
    pub fn active_links(&self) -> usize {
        self.mu[self.ties..].iter().filter(|&&m| m > 0.0).count()
    }
}

/// The failure in the words of discrete contact (the same events as
/// LIAISON_UNIL's: the step may be cut).
fn failure(e: ActiveSetFailure, ties: usize) -> String {
    match e {
        ActiveSetFailure::Cycling { passes, links } => format!(
            "DEFI_CONTACT ALGO_CONT='CONTRAINTE': the active set did not converge in {passes} passes (limit 2 x {links} links + 1): it cycles (MECANONLINE9_5)"
        ),
        ActiveSetFailure::Singular { link } if link < ties => format!(
            "DEFI_CONTACT ALGO_CONT='CONTRAINTE': the contact matrix is singular at the tie of a QUAD8 mid-side node (row {}): the node is held otherwise too (MECANONLINE9_6)",
            link + 1
        ),
        ActiveSetFailure::Singular { link } => format!(
            "DEFI_CONTACT ALGO_CONT='CONTRAINTE': the contact matrix is singular at link {} (redundant or blocked conditions: a slave node on imposed dofs, or paired twice, MECANONLINE9_6)",
            link - ties + 1
        ),
        ActiveSetFailure::Solve(m) => format!("DEFI_CONTACT ALGO_CONT='CONTRAINTE': solve with the iteration matrix: {m}"),
    }
}
