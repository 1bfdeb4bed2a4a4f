//! External forces that vary in time: each load's vector (PESANTEUR,
//! FORCE_NODALE, PRES_REP and the distributed forces,
//! `element::body_force::load_forces`) times its EXCIT
//! FONC_MULT evaluated at the instant, summed (code_aster's dead loads
//! "FIXE_CSTE" with a multiplier function). The engine asks for F_ext at
//! the instants it needs: the end of the step, and for HHT's previous-step
//! weight the start of it.
//!
//! The same multiplier scales the load's DDL_IMPO values (code_aster: an
//! imposed displacement u(t) = value × FONC_MULT(t), the usual way to
//! drive a displacement ramp): the engine sets the imposed values of the
//! numbering at the end instant of each step before solving it.

//!
//! AFFE_CHAR_MECA_F's values ([`FunctionPart`]) are functions of INST and
//! of the node's initial X, Y, Z: each is evaluated at the same instants,
//! node by node, times its FONC_MULT.

use crate::element::distributed::{cell_force, load_formulation, scatter};
use crate::element::pressure::pressure_forces_with;
use crate::mesh::{CellType, Mesh};
use crate::model::spec::Formulation;
use crate::model::{CellRole, FieldDensity, FieldFunction, Model};
use crate::post::formula::{eval_inst_xyz, Coef};

/// One AFFE_CHAR_MECA_F distributed load (PRES_REP, FORCE_FACE,
/// FORCE_ARETE, FORCE_CONTOUR, FORCE_INTERNE) with what its element
/// integrals need: the density's functions are evaluated at the Gauss
/// points of the initial geometry, at each instant (code_aster evaluates
/// them at the points of the load's elements with the instant).
#[derive(Debug, Clone)]
pub struct FieldPart {
    /// For messages: keyword and functions (`PRES_REP PRES = FP`).
    pub label: String,
    pub density: FieldDensity,
    /// The EXCIT FONC_MULT of the load (`None`: 1).
    pub mult: Option<Coef>,
    formulation: Formulation,
    ndpn: usize,
    cells: Vec<FieldCell>,
}

/// A loaded cell: mesh index, nodes, type, role in the model and initial
/// node positions.
#[derive(Debug, Clone)]
struct FieldCell {
    index: usize,
    nodes: Vec<usize>,
    kind: CellType,
    role: CellRole,
    coords: Vec<[f64; 3]>,
}

impl FieldPart {
    pub fn new(mesh: &Mesh, model: &Model, f: &FieldFunction, mult: Option<Coef>) -> FieldPart {
        let cells = f
            .cells
            .iter()
            .filter_map(|&c| {
                let role = model.cells.get(c)?.clone();
                let cell = &mesh.cells[c];
                Some(FieldCell {
                    index: c,
                    nodes: cell.nodes.clone(),
                    kind: cell.kind,
                    role,
                    coords: cell.nodes.iter().map(|&n| mesh.coords[n]).collect(),
                })
            })
            .collect();
        FieldPart {
            label: format!("{} {}", f.keyword(), f.names),
            density: f.density.clone(),
            mult,
            formulation: load_formulation(model),
            ndpn: model.ndof_per_node(),
            cells,
        }
    }

    /// Adds the nodal forces at `t` (FONC_MULT included) to `out`.
    fn add(&self, t: f64, out: &mut [f64]) -> Result<(), String> {
        let m = match &self.mult {
            None => 1.0,
            Some(f) => f
                .eval(t)
                .map_err(|e| format!("FONC_MULT at INST = {t:e}: {e}"))?,
        };
        if m == 0.0 {
            return Ok(());
        }
        let label = &self.label;
        let value = |c: &Coef, x: [f64; 3]| {
            eval_inst_xyz(c, t, x, label)
                .map_err(|e| format!("at the point ({:e}, {:e}, {:e}): {e}", x[0], x[1], x[2]))
        };
        for cell in &self.cells {
            let f = match &self.density {
                FieldDensity::Pressure(c) => Some(pressure_forces_with(
                    cell.kind,
                    self.formulation,
                    &cell.coords,
                    |x| value(c, x),
                )),
                FieldDensity::Force(kind, cs) => cell_force(
                    *kind,
                    &cell.role,
                    cell.kind,
                    self.formulation,
                    &cell.coords,
                    |x| {
                        let mut v = [0.0; 3];
                        for (vi, c) in v.iter_mut().zip(cs.iter()) {
                            if let Some(c) = c {
                                *vi = value(c, x)?;
                            }
                        }
                        Ok(v)
                    },
                ),
            };
            let Some(f) = f else { continue };
            let f =
                f.map_err(|e| format!("{label} at INST = {t:e}, cell M{}: {e}", cell.index + 1))?;
            let scaled: Vec<f64> = f.iter().map(|v| m * v).collect();
            scatter(&cell.nodes, self.ndpn, &scaled, out);
        }
        Ok(())
    }
}

/// One AFFE_CHAR_MECA_F value resolved on the numbering.
#[derive(Debug, Clone)]
pub struct FunctionPart {
    /// For messages: keyword, component and function (`DDL_IMPO DX = FDX`).
    pub label: String,
    pub coef: Coef,
    /// The EXCIT FONC_MULT of the load (`None`: 1).
    pub mult: Option<Coef>,
    /// DDL_IMPO (the entries index the numbering's `imposed` list) or
    /// FORCE_NODALE (the entries are full dofs).
    pub imposed: bool,
    /// (index, node, initial coordinates of the node).
    pub entries: Vec<(usize, usize, [f64; 3])>,
}

impl FunctionPart {
    /// The value of each entry at `t`, FONC_MULT included.
    fn values(&self, t: f64) -> Result<Vec<(usize, f64)>, String> {
        let m = match &self.mult {
            None => 1.0,
            Some(f) => f
                .eval(t)
                .map_err(|e| format!("FONC_MULT at INST = {t:e}: {e}"))?,
        };
        self.entries
            .iter()
            .map(|&(k, node, x)| {
                let v = eval_inst_xyz(&self.coef, t, x, &self.label).map_err(|e| {
                    format!("{} at INST = {t:e}, node N{}: {e}", self.label, node + 1)
                })?;
                if !v.is_finite() {
                    return Err(format!(
                        "{} at INST = {t:e}, node N{}: the value {v} is not finite",
                        self.label,
                        node + 1
                    ));
                }
                Ok((k, m * v))
            })
            .collect()
    }
}

/// The loads of a run as (forces, multiplier): a `None` multiplier is 1.
#[derive(Debug, Clone, Default)]
pub struct LoadHistory {
    parts: Vec<(Vec<f64>, Option<Coef>)>,
    /// Imposed values under a multiplier: (index in the numbering's
    /// `imposed` list, value at multiplier 1) and the multiplier.
    imposed: Vec<(Vec<(usize, f64)>, Coef)>,
    functions: Vec<FunctionPart>,
    fields: Vec<FieldPart>,
}

impl LoadHistory {
    pub fn new(parts: Vec<(Vec<f64>, Option<Coef>)>) -> LoadHistory {
        LoadHistory {
            parts,
            imposed: Vec::new(),
            functions: Vec::new(),
            fields: Vec::new(),
        }
    }

    /// Adds AFFE_CHAR_MECA_F values.
    pub fn with_functions(mut self, parts: Vec<FunctionPart>) -> LoadHistory {
        self.functions
            .extend(parts.into_iter().filter(|p| !p.entries.is_empty()));
        self
    }

    /// Adds AFFE_CHAR_MECA_F distributed loads.
    pub fn with_fields(mut self, parts: Vec<FieldPart>) -> LoadHistory {
        self.fields
            .extend(parts.into_iter().filter(|p| !p.cells.is_empty()));
        self
    }

    /// Adds imposed values scaled by `mult` (see [`LoadHistory::set_imposed`]).
    pub fn with_imposed(mut self, entries: Vec<(usize, f64)>, mult: Coef) -> LoadHistory {
        if !entries.is_empty() {
            self.imposed.push((entries, mult));
        }
        self
    }

    /// Whether some load has a multiplier (otherwise F_ext is constant and
    /// set once).
    pub fn varies(&self) -> bool {
        self.parts.iter().any(|(_, f)| f.is_some())
            || !self.imposed.is_empty()
            || !self.functions.is_empty()
            || !self.fields.is_empty()
    }

    /// Which entries of the numbering's `imposed` list (of length `n`)
    /// move with time: a DDL_IMPO value under a FONC_MULT (a zero value
    /// stays 0) or given by a function (AFFE_CHAR_MECA_F).
    pub fn driven(&self, n: usize) -> Vec<bool> {
        let mut d = vec![false; n];
        for (entries, _) in &self.imposed {
            for &(k, v) in entries {
                if v != 0.0 {
                    d[k] = true;
                }
            }
        }
        for part in self.functions.iter().filter(|p| p.imposed) {
            for &(k, _, _) in &part.entries {
                d[k] = true;
            }
        }
        d
    }

    /// Writes the imposed values of instant `t` into the numbering's list
    /// `imposed` ((full dof, value) pairs); entries without a multiplier
    /// keep their constant value.
    pub fn set_imposed(&self, t: f64, imposed: &mut [(usize, f64)]) -> Result<(), String> {
        for (entries, mult) in &self.imposed {
            let m = mult
                .eval(t)
                .map_err(|e| format!("FONC_MULT at INST = {t:e}: {e}"))?;
            for &(k, v) in entries {
                imposed[k].1 = m * v;
            }
        }
        for part in self.functions.iter().filter(|p| p.imposed) {
            for (k, v) in part.values(t)? {
                imposed[k].1 = v;
            }
        }
        Ok(())
    }

    /// F_ext(t) into `out` (full vector). A multiplier that cannot be
    /// evaluated at `t` (outside its abscissas with PROL 'EXCLU') gives
    /// an error naming the instant.
    pub fn at(&self, t: f64, out: &mut [f64]) -> Result<(), String> {
        out.iter_mut().for_each(|v| *v = 0.0);
        for (forces, mult) in &self.parts {
            let m = match mult {
                None => 1.0,
                Some(f) => f
                    .eval(t)
                    .map_err(|e| format!("FONC_MULT at INST = {t:e}: {e}"))?,
            };
            if m == 0.0 {
                continue;
            }
            for (o, &f) in out.iter_mut().zip(forces) {
                *o += m * f;
            }
        }
        for part in self.functions.iter().filter(|p| !p.imposed) {
            for (f, v) in part.values(t)? {
                out[f] += v;
            }
        }
        for part in &self.fields {
            part.add(t, out)?;
        }
        Ok(())
    }
}

/// The largest value of one kind (DDL_IMPO, FORCE_NODALE, the other dead
/// loads) of one EXCIT load, before its FONC_MULT: a solve whose numbers
/// left the range of doubles names the largest of these at its instant.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadPeak {
    /// "DDL_IMPO DZ at node N5 of load TR (EXCIT 2)".
    pub what: String,
    pub value: f64,
    /// The FONC_MULT's name and function.
    pub mult: Option<(String, Coef)>,
}

/// The message naming the load value of largest magnitude at `t`, its
/// FONC_MULT included (None without loads).
pub fn largest_load(peaks: &[LoadPeak], t: f64) -> Option<String> {
    let scaled = |p: &LoadPeak| match &p.mult {
        None => Some(p.value),
        Some((_, f)) => f.eval(t).ok().map(|m| m * p.value),
    };
    let (peak, v) = peaks
        .iter()
        .filter_map(|p| Some((p, scaled(p)?)))
        .filter(|(_, v)| v.is_finite())
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
    let text = match &peak.mult {
        None => format!("{} = {:e}", peak.what, peak.value),
        Some((name, _)) => format!(
            "{} = {:e} times FONC_MULT {name} = {:e}",
            peak.what,
            peak.value,
            v / peak.value
        ),
    };
    Some(format!(
        "the largest load value at INST = {t:e} is {text}: values of this size times the stiffness \
         (or over the mass) leave the range of doubles; check the load's value and its units"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::post::function::Function;

    #[test]
    fn forces_are_scaled_by_their_multiplier_and_summed() {
        let ramp = Function::new("INST", "TOUTRESU", vec![0.0, 2.0], vec![0.0, 4.0]).unwrap();
        let h = LoadHistory::new(vec![
            (vec![1.0, 0.0], Some(ramp.into())),
            (vec![0.0, 3.0], None),
        ]);
        assert!(h.varies());
        let mut out = vec![9.0; 2];
        h.at(0.5, &mut out).unwrap();
        assert_eq!(out, vec![1.0, 3.0]);
        let e = h.at(3.0, &mut out).unwrap_err();
        assert!(e.contains("FONC_MULT at INST = 3e0"), "{e}");
        assert!(!LoadHistory::new(vec![(vec![1.0], None)]).varies());
    }

    #[test]
    fn imposed_values_follow_their_multiplier() {
        let ramp = Function::new("INST", "TOUTRESU", vec![0.0, 2.0], vec![0.0, 4.0]).unwrap();
        let h = LoadHistory::new(vec![]).with_imposed(vec![(1, -0.5)], ramp.into());
        assert!(h.varies());
        let mut imposed = vec![(3, 7.0), (8, 0.0)];
        h.set_imposed(1.5, &mut imposed).unwrap();
        assert_eq!(imposed, vec![(3, 7.0), (8, -1.5)]);
    }

    #[test]
    fn function_values_are_evaluated_per_node_and_instant() {
        let g = crate::post::formula::Formula {
            params: vec!["INST".into(), "X".into()],
            text: "INST * X".into(),
            node: crate::post::formula::Node::Bin(
                crate::post::formula::Op::Mul,
                Box::new(crate::post::formula::Node::Param(0)),
                Box::new(crate::post::formula::Node::Param(1)),
            ),
            callees: Vec::new(),
        };
        let two = Function::constant(2.0, "TOUTRESU");
        let part = |imposed| FunctionPart {
            label: "DDL_IMPO DX = F".into(),
            coef: Coef::Formula(g.clone()),
            mult: Some(two.clone().into()),
            imposed,
            entries: vec![(1, 0, [3.0, 0.0, 0.0]), (0, 4, [-1.0, 0.0, 0.0])],
        };
        let h = LoadHistory::new(vec![]).with_functions(vec![part(true), part(false)]);
        assert!(h.varies());
        let mut imposed = vec![(5, 9.0), (6, 9.0)];
        h.set_imposed(0.5, &mut imposed).unwrap();
        assert_eq!(imposed, vec![(5, -1.0), (6, 3.0)]);
        let mut out = vec![7.0; 2];
        h.at(0.5, &mut out).unwrap();
        assert_eq!(out, vec![-1.0, 3.0]);
        let temp = Function::new("TEMP", "TOUTRESU", vec![0.0, 1.0], vec![0.0, 1.0]).unwrap();
        let bad = LoadHistory::new(vec![]).with_functions(vec![FunctionPart {
            coef: Coef::Function(temp),
            ..part(true)
        }]);
        let e = bad.set_imposed(0.5, &mut imposed).unwrap_err();
        assert!(
            e.contains("DDL_IMPO DX = F at INST = 5e-1, node N1") && e.contains("TEMP"),
            "{e}"
        );
    }
}
