//! Results: nodal fields (cham_no) and transient results (evol_noli).
//!
//! A transient result is a list of archived steps (NUME_ORDRE, INST), each
//! holding named fields: nodal ones (DEPL, VITE, ACCE, CONT_NOEU, FORC_NODA,
//! REAC_NODA) and Gauss-point ones (SIEF_ELGA, VARI_ELGA). Post-processing
//! commands (POST_RELEVE_T, TEST_RESU, RECU_FONCTION, IMPR_RESU) read them
//! through the accessors below and never see the solver.

pub mod criteria;
pub mod elno;
pub mod energy;

use indexmap::IndexMap;

/// A nodal field: `ncmp` components per node, node-major. A (node,
/// component) pair that was never assigned is absent, which is not the
/// same as zero (code_aster's CREA_CHAMP semantics): it is stored as NaN
/// and reported as absent by [`NodalField::get`].
#[derive(Debug, Clone, PartialEq)]
pub struct NodalField {
    pub components: Vec<String>,
    pub values: Vec<f64>,
}

impl NodalField {
    /// A field with every pair absent.
    pub fn absent(components: Vec<String>, nnodes: usize) -> Self {
        let n = components.len() * nnodes;
        NodalField {
            components,
            values: vec![f64::NAN; n],
        }
    }

    /// A field with every pair set to zero.
    pub fn zeros(components: Vec<String>, nnodes: usize) -> Self {
        let n = components.len() * nnodes;
        NodalField {
            components,
            values: vec![0.0; n],
        }
    }

    pub fn ncmp(&self) -> usize {
        self.components.len()
    }

    pub fn nnodes(&self) -> usize {
        if self.components.is_empty() {
            0
        } else {
            self.values.len() / self.components.len()
        }
    }

    pub fn component_index(&self, name: &str) -> Option<usize> {
        self.components.iter().position(|c| c == name)
    }

    /// The value of a component at a node, None if absent.
    pub fn get(&self, node: usize, cmp: &str) -> Option<f64> {
        let c = self.component_index(cmp)?;
        let v = *self.values.get(node * self.ncmp() + c)?;
        (!v.is_nan()).then_some(v)
    }

    pub fn set(&mut self, node: usize, cmp: usize, v: f64) {
        let n = self.ncmp();
        self.values[node * n + cmp] = v;
    }
}

/// The index k of an internal variable's component name "Vk" (1-based),
/// as CREA_CHAMP names them and ETAT_INIT VARI reads them.
pub fn vari_index(c: &str) -> Option<usize> {
    c.strip_prefix('V')
        .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()) && !d.starts_with('0'))
        .and_then(|d| d.parse().ok())
}

/// A field at Gauss points: for each cell, `npg[cell]` points of `ncmp`
/// components (cells outside the model have 0 points).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GaussField {
    pub components: Vec<String>,
    /// Offset of each cell's first value in `values`; `offsets[ncells]` is
    /// the total length.
    pub offsets: Vec<usize>,
    pub values: Vec<f64>,
}

impl GaussField {
    pub fn ncmp(&self) -> usize {
        self.components.len()
    }
    /// The values of one cell, point-major.
    pub fn cell(&self, cell: usize) -> &[f64] {
        &self.values[self.offsets[cell]..self.offsets[cell + 1]]
    }
    /// The same field on the cells where `keep` is true (others, and
    /// cells beyond `keep`, have no point): CALC_CHAMP's GROUP_MA.
    pub fn restricted(&self, keep: &[bool]) -> GaussField {
        let mut out = GaussField {
            components: self.components.clone(),
            offsets: Vec::with_capacity(self.offsets.len()),
            values: Vec::new(),
        };
        for c in 0..self.offsets.len().saturating_sub(1) {
            out.offsets.push(out.values.len());
            if keep.get(c).copied().unwrap_or(false) {
                out.values.extend_from_slice(self.cell(c));
            }
        }
        out.offsets.push(out.values.len());
        out
    }
    /// Number of Gauss points of a cell.
    pub fn npg(&self, cell: usize) -> usize {
        (self.offsets[cell + 1] - self.offsets[cell])
            .checked_div(self.ncmp())
            .unwrap_or(0)
    }
    /// The mean over the Gauss points of each of `ncells` cells, per
    /// component (NaN for cells without points, and for components absent
    /// at every point): what the MED writer stores of a Gauss field.
    pub fn cell_means(&self, ncells: usize) -> Vec<f64> {
        let nc = self.ncmp();
        let mut out = vec![f64::NAN; ncells * nc];
        for c in 0..ncells.min(self.offsets.len().saturating_sub(1)) {
            let npg = self.npg(c);
            if npg == 0 {
                continue;
            }
            let vals = self.cell(c);
            for k in 0..nc {
                let (sum, n) = (0..npg)
                    .map(|p| vals[p * nc + k])
                    .filter(|v| !v.is_nan())
                    .fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
                if n > 0 {
                    out[c * nc + k] = sum / n as f64;
                }
            }
        }
        out
    }
}

/// One archived step of a transient result.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Step {
    pub nume_ordre: usize,
    pub inst: f64,
    pub nodal: IndexMap<String, NodalField>,
    pub gauss: IndexMap<String, GaussField>,
    /// Element fields at nodes (SIEF_ELNO, SIGM_ELNO, SIEQ_ELNO, VARI_ELNO
    /// of CALC_CHAMP): a [`GaussField`] whose "points" of a cell are its
    /// nodes, MED order.
    pub elno: IndexMap<String, GaussField>,
    /// The explicit contact's state of this instant beyond the motion
    /// (None without explicit contact): what a continuation needs to
    /// restart from here as the run in one call would go on.
    pub contact_history: Option<ContactHistory>,
    /// Index in [`EvolNoli::runs`] of the call that computed this step:
    /// a result filled by calls chained with reuse= holds steps computed
    /// with different loads and masses, and CALC_CHAMP's REAC_NODA must
    /// take each step's own (code_aster keeps them per NUME_ORDRE).
    pub run: usize,
    /// The fields ARCHIVAGE/CHAM_EXCLU left out of this step (every
    /// archived instant of the call but its last one): named in the
    /// message of a command that asks for one of them.
    pub excluded: Vec<String>,
}

impl Step {
    /// Why the field `name` is not in this step, for an error message
    /// that already says it is missing: its exclusion by CHAM_EXCLU, or
    /// nothing.
    pub fn exclusion_note(&self, name: &str) -> String {
        exclusion_note(&self.excluded, name)
    }
}

/// [`Step::exclusion_note`] from the step's `excluded` list.
pub fn exclusion_note(excluded: &[String], name: &str) -> String {
    if excluded.iter().any(|e| e == name) {
        format!(
            " ({name} was excluded from this instant by ARCHIVAGE/CHAM_EXCLU of the command that computed it: only the last instant of the call keeps every field)"
        )
    } else {
        String::new()
    }
}

/// What one call (DYNA_NON_LINE, STAT_NON_LINE, MECA_STATIQUE) computed
/// its steps with beyond the model and material: code_aster's per-order
/// parameters (EXCIT) and, an aster addition, the kind of mass. CALC_CHAMP
/// rebuilds each step's F_ext and M·a from the run of that step, so that
/// REAC_NODA stays that step's residual in a result chained through calls
/// with other loads or another mass (both were taken from the last call:
/// spurious forces of (M_other − M_last)·a and of the missing loads at
/// free nodes).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunData {
    /// The loads (EXCIT/CHARGE) of the call.
    pub loads: Vec<String>,
    /// Their EXCIT/FONC_MULT function concepts (parallel to `loads`),
    /// which CALC_CHAMP applies again when it rebuilds F_ext.
    pub load_mults: Vec<Option<String>>,
    /// The call used the lumped (HRZ) mass of MASS_DIAG='OUI' (its M·a,
    /// and its PESANTEUR, the lumped mass times g).
    pub mass_diag: bool,
}

/// What an explicit contact treatment (discrete contact or LIAISON_UNIL,
/// both aster extensions) carries from one step to the next besides the
/// motion: the penalised friction's tangential force of each link, which
/// the next step's elastic predictor starts from, and the contact forces
/// of the state, which start the next step's trapezoids (impulse,
/// TRAV_LIAI, DISS_FROT). Archived with each step so that ETAT_INIT
/// EVOL_NOLI restarts from it: without it a continuation in the middle of
/// a sticking contact started its friction from zero (measured: the slave
/// corner's DX 149 % off the one-call run). Kept in memory only (MED has
/// no place for it, and code_aster, which has no explicit contact, no
/// such field).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactHistory {
    /// Dofs per node of the full numbering the dofs below index.
    pub ndpn: usize,
    /// The contact forces of the state on the F_int side (the opposite of
    /// the force on the nodes), nonzero entries, as (full dof, value).
    pub force: Vec<(usize, f64)>,
    /// The sum of the contact forces on the slave nodes (the impulse's).
    pub body_force: [f64; 3],
    /// The tangential force on the slave node of each frictional link in
    /// contact, by (zone, slave node) ascending (the penalised friction's
    /// history; for the kinematic friction the force of the correction).
    pub friction: Vec<((usize, usize), [f64; 3])>,
    /// Against a deformable master: the master nodes and shape functions
    /// of each frictional link, by (zone, slave node) ascending (the
    /// master side of the friction's work).
    pub friction_master: Vec<MasterLink>,
}

impl ContactHistory {
    /// Whether this history can be restored into a model numbered with
    /// `ndpn` dofs per node and `nfull` dofs in all: a restart on another
    /// model (or after another AFFE_MODELE) must be refused, not indexed
    /// out of bounds. The message completes "the contact history ...".
    pub fn check_fits(&self, ndpn: usize, nfull: usize) -> Result<(), String> {
        if self.ndpn != ndpn {
            return Err(format!(
                "it was stored with {} dofs per node, this model has {ndpn}",
                self.ndpn
            ));
        }
        if let Some(&(f, _)) = self.force.iter().find(|&&(f, _)| f >= nfull) {
            return Err(format!("its dof {f} is outside this model's {nfull} dofs"));
        }
        Ok(())
    }
}

/// A frictional link's (zone, slave node), master nodes and their shape
/// functions at the projection.
pub type MasterLink = ((usize, usize), Vec<usize>, Vec<f64>);

/// A transient nonlinear result (evol_noli).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EvolNoli {
    /// The mesh concept the fields live on.
    pub mesh: String,
    /// The model concept, if any.
    pub model: String,
    /// The material field the result was computed with (CALC_CHAMP
    /// re-derives nodal forces from it, as code_aster keeps it in the
    /// result).
    pub cham_mater: String,
    /// The calls that filled the result, in order; each step names its
    /// own ([`Step::run`]).
    pub runs: Vec<RunData>,
    /// (RELATION, DEFORMATION) of each mesh cell with an element.
    pub comportement: Vec<Option<(String, String)>>,
    pub steps: Vec<Step>,
    /// Tables attached to the result, by RECU_TABLE's NOM_TABLE (the
    /// energy balance is PARA_CALC).
    pub tables: IndexMap<String, crate::post::table::Table>,
}

/// How a step is selected (TEST_RESU, POST_RELEVE_T, CALC_CHAMP...).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Access {
    NumeOrdre(usize),
    /// INST with its search tolerance: RELATIF (|t - t_k| <= prec |t|) or
    /// ABSOLU (|t - t_k| <= prec).
    Inst {
        inst: f64,
        precision: f64,
        relative: bool,
    },
}

impl EvolNoli {
    /// Records a new call filling the result; the steps it archives take
    /// its index ([`EvolNoli::current_run`]).
    pub fn start_run(&mut self, run: RunData) {
        self.runs.push(run);
    }

    /// The index the steps archived now take: the last call's.
    pub fn current_run(&self) -> usize {
        self.runs.len().saturating_sub(1)
    }

    /// The call that computed a step; None for a result built without
    /// any (no loads, the consistent mass).
    pub fn run_of(&self, step: &Step) -> Option<&RunData> {
        self.runs.get(step.run)
    }

    /// Finds the step an access designates. Several matches or none are
    /// errors, as in code_aster (the message lists the nearest instants).
    pub fn find(&self, access: Access) -> Result<&Step, String> {
        match access {
            Access::NumeOrdre(n) => {
                self.steps
                    .iter()
                    .find(|s| s.nume_ordre == n)
                    .ok_or_else(|| {
                        format!(
                            "NUME_ORDRE {n} is not stored in the result (stored: {})",
                            self.describe_orders()
                        )
                    })
            }
            Access::Inst {
                inst,
                precision,
                relative,
            } => {
                let tol = if relative {
                    precision * inst.abs()
                } else {
                    precision
                };
                let hits: Vec<&Step> = self
                    .steps
                    .iter()
                    .filter(|s| (s.inst - inst).abs() <= tol)
                    .collect();
                match hits.as_slice() {
                    [one] => Ok(one),
                    [] => {
                        let near = self
                            .steps
                            .iter()
                            .min_by(|a, b| (a.inst - inst).abs().total_cmp(&(b.inst - inst).abs()));
                        Err(format!(
                            "no stored instant matches INST={inst:e} (tolerance {tol:e}){}; stored instants: {}",
                            near.map(|s| format!(
                                "; the nearest is {:e} (NUME_ORDRE {})",
                                s.inst, s.nume_ordre
                            ))
                            .unwrap_or_default(),
                            self.describe_instants()
                        ))
                    }
                    many => Err(format!(
                        "{} stored instants match INST={inst:e} within {tol:e}: reduce PRECISION",
                        many.len()
                    )),
                }
            }
        }
    }

    /// The stored instants, all of them up to 12, else the first and
    /// last five around the count.
    fn describe_instants(&self) -> String {
        let t: Vec<String> = self.steps.iter().map(|s| format!("{:e}", s.inst)).collect();
        match t.len() {
            0 => "none".into(),
            n if n <= 12 => t.join(", "),
            n => format!(
                "{}, ... ({n} in all), {}",
                t[..5].join(", "),
                t[n - 5..].join(", ")
            ),
        }
    }

    fn describe_orders(&self) -> String {
        match (self.steps.first(), self.steps.last()) {
            (Some(a), Some(b)) => format!(
                "{} steps, NUME_ORDRE {} to {}",
                self.steps.len(),
                a.nume_ordre,
                b.nume_ordre
            ),
            _ => "none".into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn result() -> EvolNoli {
        let mut r = EvolNoli::default();
        for (k, t) in [(0, -1e-5), (1, 0.0), (2, 2.5e-7)] {
            r.steps.push(Step {
                nume_ordre: k,
                inst: t,
                ..Step::default()
            });
        }
        r
    }

    #[test]
    fn instant_search_follows_the_criterion() {
        let r = result();
        let rel = |t| Access::Inst {
            inst: t,
            precision: 1e-6,
            relative: true,
        };
        assert_eq!(r.find(rel(2.5e-7)).unwrap().nume_ordre, 2);
        assert_eq!(r.find(rel(0.0)).unwrap().nume_ordre, 1);
        assert!(r.find(rel(2.6e-7)).unwrap_err().contains("nearest"));
        assert_eq!(r.find(Access::NumeOrdre(0)).unwrap().inst, -1e-5);
        assert!(r.find(Access::NumeOrdre(9)).is_err());
    }

    /// Cutting a field to cells keeps their points and leaves the others
    /// (and cells beyond the mask) without any.
    #[test]
    fn restricted_fields_keep_the_selected_cells_only() {
        let f = GaussField {
            components: vec!["A".into(), "B".into()],
            offsets: vec![0, 4, 6, 10],
            values: (0..10).map(f64::from).collect(),
        };
        let r = f.restricted(&[false, true]);
        assert_eq!(r.offsets, vec![0, 0, 2, 2]);
        assert_eq!(r.values, vec![4.0, 5.0]);
        assert_eq!((r.npg(0), r.npg(1), r.npg(2)), (0, 1, 0));
    }

    #[test]
    fn absent_components_are_not_zero() {
        let mut f = NodalField::absent(vec!["DX".into(), "DY".into()], 3);
        f.set(1, 1, -227000.0);
        assert_eq!(f.get(1, "DY"), Some(-227000.0));
        assert_eq!(f.get(1, "DX"), None);
        assert_eq!(f.get(0, "DZ"), None);
    }
}
