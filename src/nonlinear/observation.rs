//! OBSERVATION of STAT_NON_LINE / DYNA_NON_LINE: values of fields at
//! chosen nodes or cells, at chosen instants, written as rows of the
//! result's table 'OBSERVATION' (RECU_TABLE), without archiving the fields
//! themselves. The selection and the reductions are SUIVI_DDL's
//! ([`Suivi`]); the rows and columns are code_aster's (`nmobsz`): one row
//! per component, and with EVAL_CHAM='VALE' per node or cell (and per
//! Gauss point with EVAL_ELGA='VALE'); NUME_OBSE counts the rows of the
//! table from 1, NUME_REUSE the continuations (reuse=) from 0.

use super::dyna::{ArchivePolicy, Reduce, Suivi, SuiviField};
use super::newton::State;
use super::result_table::ContinuedTable;
use crate::post::table::{Cell, ColumnType, Table};

/// The result table's name (RECU_TABLE NOM_TABLE).
pub const TABLE_NAME: &str = "OBSERVATION";

/// One OBSERVATION occurrence.
#[derive(Debug, Clone, PartialEq)]
pub struct Observation {
    /// TITRE, or OBSERVATION_<occurrence>.
    pub title: String,
    /// NOM_CHAM as given.
    pub field_name: String,
    /// One column per NOM_CMP, with its name.
    pub columns: Vec<(String, Suivi)>,
    /// EVAL_CHAM, EVAL_ELGA as given.
    pub eval_name: String,
    pub eval_elga_name: String,
    /// Names of the selected entities (nodes or cells), aligned with each
    /// column's `entities`.
    pub entity_names: Vec<String>,
    /// When: every PAS_OBSE computed steps, or at LIST_INST / INST.
    pub when: ArchivePolicy,
    /// OBSE_ETAT_INIT='OUI'.
    pub initial: bool,
}

impl Observation {
    fn nodal(&self) -> bool {
        self.columns.first().is_some_and(|(_, s)| {
            matches!(
                s.field,
                SuiviField::Depl | SuiviField::Vite | SuiviField::Acce | SuiviField::ForcNoda
            )
        })
    }
}

/// The table being filled, continued from a previous run's when the
/// result is continued.
#[derive(Debug, Clone)]
pub struct Observer {
    table: Table,
    next: i64,
    reuse: i64,
}

const COLUMNS: [(&str, ColumnType); 16] = [
    ("NOM_OBSERVATION", ColumnType::Text(16)),
    ("TYPE_OBJET", ColumnType::Text(16)),
    (super::result_table::NUME_REUSE, ColumnType::Int),
    ("NUME_OBSE", ColumnType::Int),
    ("INST", ColumnType::Real),
    ("NOM_CHAM", ColumnType::Text(16)),
    ("EVAL_CHAM", ColumnType::Text(8)),
    ("NOM_CMP", ColumnType::Text(8)),
    ("NOM_VARI", ColumnType::Text(16)),
    ("EVAL_CMP", ColumnType::Text(8)),
    ("NOEUD", ColumnType::Text(8)),
    ("MAILLE", ColumnType::Text(8)),
    ("EVAL_ELGA", ColumnType::Text(8)),
    ("POINT", ColumnType::Int),
    ("SOUS_POINT", ColumnType::Int),
    ("VALE", ColumnType::Real),
];

impl Observer {
    /// A new table, or the continuation of `previous` (NUME_REUSE + 1,
    /// NUME_OBSE going on).
    pub fn new(previous: Option<&Table>) -> Observer {
        let c = ContinuedTable::new(previous, "observations of the computation", &COLUMNS);
        Observer {
            next: c.largest("NUME_OBSE").map_or(1, |n| n + 1),
            reuse: c.nume_reuse,
            table: c.table,
        }
    }

    /// The rows of every observation due at this state: the initial one
    /// (`computed` = None) or the `computed`-th step.
    pub fn observe(
        &mut self,
        observations: &[Observation],
        state: &State,
        computed: Option<usize>,
        ndpn: usize,
        cell_offsets: &super::fields::GaussRows,
    ) {
        for o in observations {
            let due = match computed {
                None => o.initial,
                Some(k) => o.when.wants(k, state.t),
            };
            if due {
                self.rows(o, state, ndpn, cell_offsets);
            }
        }
    }

    fn rows(
        &mut self,
        o: &Observation,
        state: &State,
        ndpn: usize,
        cell_offsets: &super::fields::GaussRows,
    ) {
        let nodal = o.nodal();
        for (cmp, s) in &o.columns {
            let mut base: Vec<(&str, Cell)> = vec![
                ("NOM_OBSERVATION", Cell::Text(o.title.clone())),
                ("TYPE_OBJET", Cell::Text("R".into())),
                ("NUME_REUSE", Cell::Int(self.reuse)),
                ("INST", Cell::Real(state.t)),
                ("NOM_CHAM", Cell::Text(o.field_name.clone())),
                ("EVAL_CHAM", Cell::Text(o.eval_name.clone())),
                ("NOM_CMP", Cell::Text(cmp.clone())),
            ];
            if !nodal && o.eval_elga_name != "VALE" {
                base.push(("EVAL_ELGA", Cell::Text(o.eval_elga_name.clone())));
            }
            if s.eval != Reduce::Vale {
                self.push(&base, s.evaluate(state, ndpn, cell_offsets));
                continue;
            }
            for (i, name) in o.entity_names.iter().enumerate() {
                let one = Suivi {
                    entities: vec![s.entities[i]],
                    ..s.clone()
                };
                let entity = if nodal { "NOEUD" } else { "MAILLE" };
                let mut row = base.clone();
                row.push((entity, Cell::Text(name.clone())));
                if nodal || o.eval_elga_name != "VALE" {
                    self.push(&row, one.evaluate(state, ndpn, cell_offsets));
                    continue;
                }
                let c = s.entities[i];
                let npoints = cell_offsets.npoints(c);
                for &p in s.points.iter().filter(|&&p| p >= 1 && p <= npoints) {
                    let at = Suivi {
                        points: vec![p],
                        ..one.clone()
                    };
                    let mut r = row.clone();
                    r.push(("POINT", Cell::Int(p as i64)));
                    r.push(("SOUS_POINT", Cell::Int(1)));
                    self.push(&r, at.evaluate(state, ndpn, cell_offsets));
                }
            }
        }
    }

    fn push(&mut self, row: &[(&str, Cell)], value: f64) {
        let mut r = row.to_vec();
        r.push(("NUME_OBSE", Cell::Int(self.next)));
        r.push(("VALE", Cell::Real(value)));
        // Every column exists with the type of its value.
        let _ = self.table.add_row(&r);
        self.next += 1;
    }

    pub fn rows_written(&self) -> usize {
        self.table.n_rows()
    }

    pub fn into_table(self) -> Table {
        self.table
    }

    pub fn table(&self) -> &Table {
        &self.table
    }
}
