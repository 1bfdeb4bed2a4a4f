//! CALC_TABLE's operations on tables, besides FILTRE and TRI which
//! [`Table::filter`] and [`Table::sort_by`] already do for TEST_TABLE and
//! IMPR_TABLE: EXTR, SUPPRIME, RENOMME, COMB (code_aster's `merge`) and
//! OPER (a FORMULE of the columns).
//!
//! Errors carry the keyword of the ACTION occurrence they come from
//! (`NOM_PARA`, `TABLE`, `FORMULE`), for the command to point at.

use super::formula::Formula;
use super::table::{Cell, ColumnType, Table, TableError};

impl Table {
    /// EXTR: the columns `names`, in that order; a name that is not a
    /// column is an error (code_aster's TABLE0_2).
    pub fn extract(&self, names: &[&str]) -> Result<Table, TableError> {
        for n in names {
            self.index_or_error(n, "NOM_PARA")?;
        }
        Ok(self.select(names).0)
    }

    /// SUPPRIME: the table without the columns `names`; returns apart the
    /// names that were not columns (code_aster ignores them, the command
    /// warns).
    pub fn drop_columns(&self, names: &[&str]) -> (Table, Vec<String>) {
        let keep: Vec<&str> = self
            .columns
            .iter()
            .map(String::as_str)
            .filter(|c| !names.contains(c))
            .collect();
        let missing = names
            .iter()
            .filter(|n| self.column_index(n).is_none())
            .map(|n| n.to_string())
            .collect();
        (self.select(&keep).0, missing)
    }

    /// RENOMME: column `old` becomes `new`, which must not be a column
    /// already.
    pub fn rename(&mut self, old: &str, new: &str) -> Result<(), TableError> {
        let i = self.index_or_error(old, "NOM_PARA")?;
        if old != new && self.column_index(new).is_some() {
            return Err(TableError::new(format!(
                "cannot rename '{old}' to '{new}': the table already has a column '{new}'"
            ))
            .at("NOM_PARA"));
        }
        self.columns[i] = new.to_string();
        Ok(())
    }

    /// COMB: the rows of `other` merged into this table. Without `labels`
    /// they are appended. With `labels` (columns of both tables), a row of
    /// `other` whose label values are found in exactly one row here (and
    /// are unique in `other` too) overwrites that row's cells with its own
    /// present cells; any other row of `other` is appended, unless
    /// `restrict` (RESTREINT='OUI'). New columns come after this table's,
    /// with `other`'s types.
    pub fn merge(
        &self,
        other: &Table,
        labels: &[&str],
        restrict: bool,
    ) -> Result<Table, TableError> {
        for l in labels {
            self.index_or_error(l, "NOM_PARA")?;
            other
                .index_or_error(l, "NOM_PARA")
                .map_err(|e| TableError {
                    message: format!("the table of TABLE: {}", e.message),
                    ..e
                })?;
        }
        let mut columns = self.columns.clone();
        let mut types = self.all_types();
        let other_types = other.all_types();
        for (c, ty) in other.columns.iter().zip(&other_types) {
            if !columns.contains(c) {
                columns.push(c.clone());
                types.push(*ty);
            }
        }
        // Where each column of `other` lands.
        let target: Vec<usize> = other
            .columns
            .iter()
            .map(|c| columns.iter().position(|d| d == c).unwrap_or(0))
            .collect();
        let mut rows: Vec<Vec<Option<Cell>>> = self
            .rows
            .iter()
            .map(|r| {
                let mut r = r.clone();
                r.resize(columns.len(), None);
                r
            })
            .collect();
        let keys = |t: &Table| -> Vec<Option<Vec<Key>>> {
            let idx: Vec<usize> = labels.iter().filter_map(|l| t.column_index(l)).collect();
            let all: Vec<Vec<Key>> = t
                .rows
                .iter()
                .map(|r| {
                    idx.iter()
                        .map(|&i| Key::of(r.get(i).and_then(|c| c.as_ref())))
                        .collect()
                })
                .collect();
            // A key shared by two rows of one table matches nothing.
            all.iter()
                .map(|k| {
                    let unique = !k.is_empty() && all.iter().filter(|o| *o == k).count() == 1;
                    unique.then(|| k.clone())
                })
                .collect()
        };
        let mine = keys(self);
        let theirs = keys(other);
        for (r2, k2) in other.rows.iter().zip(&theirs) {
            let hit = k2
                .as_ref()
                .and_then(|k| mine.iter().position(|m| m.as_ref() == Some(k)));
            match hit {
                Some(i) => {
                    // The labels are equal already (an integer may equal a
                    // real): they keep this table's cells and types.
                    for (j, c) in r2.iter().enumerate() {
                        if labels.contains(&other.columns[j].as_str()) {
                            continue;
                        }
                        if let Some(c) = c {
                            rows[i][target[j]] = Some(c.clone());
                        }
                    }
                }
                None if restrict => {}
                None => {
                    let mut row = vec![None; columns.len()];
                    for (j, c) in r2.iter().enumerate() {
                        row[target[j]] = c.clone();
                    }
                    rows.push(row);
                }
            }
        }
        let mut title = self.title.clone();
        title.extend(other.title.iter().cloned());
        let quoted: Vec<String> = labels.iter().map(|l| format!("'{l}'")).collect();
        title.push(format!("MERGE avec labels=[{}]", quoted.join(", ")));
        let mut out = Table {
            title,
            columns,
            rows: Vec::new(),
            types,
        };
        for r in rows {
            out.push_row(r).map_err(|e| e.at("TABLE"))?;
        }
        Ok(out)
    }

    /// OPER: a new real column `name` holding `formula` of each row; the
    /// formula's parameters are the columns of the same names, or the
    /// columns `map` in the order of its NOM_PARA. A row missing one of
    /// them (or holding a text there) gets an empty cell.
    pub fn add_formula_column(
        &mut self,
        name: &str,
        formula: &Formula,
        map: Option<&[&str]>,
    ) -> Result<(), TableError> {
        let cols: Vec<&str> = match map {
            Some(m) => {
                if m.len() != formula.params.len() {
                    return Err(TableError::new(format!(
                        "NOM_COLONNE gives {} columns for the {} parameters of the formula ({})",
                        m.len(),
                        formula.params.len(),
                        formula.params.join(", ")
                    ))
                    .at("NOM_COLONNE"));
                }
                m.to_vec()
            }
            None => formula.params.iter().map(String::as_str).collect(),
        };
        let key = if map.is_some() {
            "NOM_COLONNE"
        } else {
            "FORMULE"
        };
        let idx: Vec<usize> = cols
            .iter()
            .map(|c| {
                self.index_or_error(c, key).map_err(|e| TableError {
                    message: format!(
                        "the formula '{}' needs a column: {}",
                        formula.text, e.message
                    ),
                    ..e
                })
            })
            .collect::<Result<_, _>>()?;
        let mut values = Vec::with_capacity(self.rows.len());
        for r in &self.rows {
            let args: Option<Vec<(&str, f64)>> = formula
                .params
                .iter()
                .zip(&idx)
                .map(|(p, &i)| {
                    let v = r.get(i).and_then(|c| c.as_ref()).and_then(Cell::as_f64)?;
                    Some((p.as_str(), v))
                })
                .collect();
            values.push(match args {
                Some(a) => Some(Cell::Real(
                    formula
                        .eval(&a)
                        .map_err(|e| TableError::new(e).at("FORMULE"))?,
                )),
                None => None,
            });
        }
        let j = self
            .add_column(name, ColumnType::Real)
            .map_err(|e| e.at("NOM_PARA"))?;
        for (r, v) in self.rows.iter_mut().zip(values) {
            r[j] = v;
        }
        Ok(())
    }
}

/// A cell as a merge label: numbers compare by value (an integer equals
/// the same real, as in Python), texts without trailing blanks.
#[derive(Debug, Clone, PartialEq)]
enum Key {
    Missing,
    Num(f64),
    Text(String),
}

impl Key {
    fn of(c: Option<&Cell>) -> Key {
        match c {
            None => Key::Missing,
            Some(Cell::Text(s)) => Key::Text(s.trim_end().to_string()),
            Some(c) => Key::Num(c.as_f64().unwrap_or(f64::NAN)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::post::formula::{Node, Op};

    fn table(cols: &[&str], rows: &[&[Option<Cell>]]) -> Table {
        let mut t = Table::new();
        for c in cols {
            t.columns.push(c.to_string());
        }
        for r in rows {
            t.rows.push(r.to_vec());
        }
        t
    }

    fn k(s: &str) -> Option<Cell> {
        Some(Cell::Text(s.into()))
    }
    fn r(x: f64) -> Option<Cell> {
        Some(Cell::Real(x))
    }
    fn i(x: i64) -> Option<Cell> {
        Some(Cell::Int(x))
    }

    #[test]
    fn extract_drop_and_rename() {
        let t = table(&["NOEUD", "DX", "DY"], &[&[k("N1"), r(1.0), r(2.0)]]);
        let e = t.extract(&["DY", "NOEUD"]).unwrap();
        assert_eq!(e.columns, vec!["DY", "NOEUD"]);
        assert_eq!(e.rows[0], vec![r(2.0), k("N1")]);
        let err = t.extract(&["DZ"]).unwrap_err();
        assert_eq!(err.keyword.as_deref(), Some("NOM_PARA"));
        assert!(err.message.contains("no column 'DZ'"));
        let (d, missing) = t.drop_columns(&["DX", "DZ"]);
        assert_eq!(d.columns, vec!["NOEUD", "DY"]);
        assert_eq!(missing, vec!["DZ"]);
        let mut m = t.clone();
        m.rename("DY", "UY").unwrap();
        assert_eq!(m.columns, vec!["NOEUD", "DX", "UY"]);
        assert!(m
            .rename("DX", "UY")
            .unwrap_err()
            .message
            .contains("already"));
        assert!(m.rename("DZ", "W").is_err());
    }

    #[test]
    fn merge_overwrites_unique_matches_and_appends_the_rest() {
        let a = table(
            &["NOEUD", "DX"],
            &[&[k("N1"), r(1.0)], &[k("N2"), r(2.0)], &[k("N2"), r(2.5)]],
        );
        let b = table(
            &["NOEUD", "DY"],
            &[
                &[k("N1"), r(10.0)],
                &[k("N2"), r(20.0)],
                &[k("N3"), r(30.0)],
            ],
        );
        let m = a.merge(&b, &["NOEUD"], false).unwrap();
        assert_eq!(m.columns, vec!["NOEUD", "DX", "DY"]);
        // N1 matched; N2 is twice in `a` so it matches nothing; N3 new.
        assert_eq!(
            m.rows,
            vec![
                vec![k("N1"), r(1.0), r(10.0)],
                vec![k("N2"), r(2.0), None],
                vec![k("N2"), r(2.5), None],
                vec![k("N2"), None, r(20.0)],
                vec![k("N3"), None, r(30.0)],
            ]
        );
        assert_eq!(m.title.last().unwrap(), "MERGE avec labels=['NOEUD']");
        let restricted = a.merge(&b, &["NOEUD"], true).unwrap();
        assert_eq!(restricted.n_rows(), 3);
        let appended = a.merge(&b, &[], false).unwrap();
        assert_eq!(appended.n_rows(), 6);
        // An integer label equals the same real.
        let c = table(&["NUME_ORDRE", "V"], &[&[i(1), r(5.0)]]);
        let d = table(&["NUME_ORDRE", "W"], &[&[r(1.0), r(6.0)]]);
        let cd = c.merge(&d, &["NUME_ORDRE"], false).unwrap();
        assert_eq!(cd.rows, vec![vec![i(1), r(5.0), r(6.0)]]);
        let e = a.merge(&b, &["DY"], false).unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("NOM_PARA"));
        // A real cell cannot land in an integer column.
        let bad = d.merge(&c, &[], false).unwrap();
        assert_eq!(bad.n_rows(), 2);
        let bad = c.merge(&d, &[], false).unwrap_err();
        assert!(bad.message.contains("integer"), "{}", bad.message);
    }

    #[test]
    fn formula_columns() {
        // Y = DY / 2 (parameter DY), and the same through NOM_COLONNE.
        let f = Formula {
            params: vec!["DY".into()],
            text: "DY / 2".into(),
            node: Node::Bin(Op::Div, Box::new(Node::Param(0)), Box::new(Node::Num(2.0))),
            callees: Vec::new(),
        };
        let mut t = table(
            &["NOEUD", "DY", "V"],
            &[&[k("N1"), r(3.0), r(8.0)], &[k("N2"), None, i(4)]],
        );
        t.add_formula_column("Y", &f, None).unwrap();
        assert_eq!(t.rows[0][3], r(1.5));
        assert_eq!(t.rows[1][3], None);
        t.add_formula_column("Z", &f, Some(&["V"])).unwrap();
        assert_eq!(t.rows[1][4], r(2.0));
        assert!(t.add_formula_column("Y", &f, None).is_err());
        let e = t
            .add_formula_column("W", &f, Some(&["V", "DY"]))
            .unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("NOM_COLONNE"));
        let e = t.add_formula_column("W", &f, Some(&["Q"])).unwrap_err();
        assert!(e.message.contains("no column 'Q'"), "{}", e.message);
    }
}
