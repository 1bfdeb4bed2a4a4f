//! The tables a nonlinear run keeps in its result (the energy balance
//! PARA_CALC, the OBSERVATION rows) and that a continuation with reuse=
//! extends rather than replaces.
//!
//! code_aster creates such a table only when the result holds none
//! (`nonlinDSTableIOCreate`), appends one line per archived step or
//! observation (`tbajli`), and tags each line with NUME_REUSE, the number
//! of the call: 0 for the first, then one more than the largest value
//! already in the table (`nmarnr`). Both tables share this here so that
//! they number the calls the same way.

use crate::post::table::{ColumnType, Table};

/// The column numbering the calls.
pub const NUME_REUSE: &str = "NUME_REUSE";

/// A result table being filled by one call.
#[derive(Debug, Clone)]
pub struct ContinuedTable {
    /// The previous calls' rows (none for a new table), then this call's.
    pub table: Table,
    /// This call's NUME_REUSE.
    pub nume_reuse: i64,
}

impl ContinuedTable {
    /// Continues `previous`, the table of that name the result holds, or
    /// starts a new one with `title` and `columns` when there is none (or
    /// one without a NUME_REUSE column, which no run of ours writes).
    pub fn new(previous: Option<&Table>, title: &str, columns: &[(&str, ColumnType)]) -> Self {
        if let Some(t) = previous.filter(|t| t.column_index(NUME_REUSE).is_some()) {
            let nume_reuse = if t.n_rows() == 0 {
                0
            } else {
                largest(t, NUME_REUSE).map_or(0, |n| n + 1)
            };
            return ContinuedTable {
                table: t.clone(),
                nume_reuse,
            };
        }
        let mut table = Table::new();
        table.title = vec![title.to_string()];
        for &(name, ty) in columns {
            // The names are distinct: adding cannot fail.
            let _ = table.add_column(name, ty);
        }
        ContinuedTable {
            table,
            nume_reuse: 0,
        }
    }

    /// The largest value of an integer column over the rows (None when
    /// it has none), e.g. the last NUME_OBSE of the previous calls.
    pub fn largest(&self, column: &str) -> Option<i64> {
        largest(&self.table, column)
    }
}

fn largest(t: &Table, column: &str) -> Option<i64> {
    t.column(column)
        .ok()?
        .into_iter()
        .flatten()
        .filter_map(|c| c.as_f64())
        .map(|x| x as i64)
        .max()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::post::table::Cell;

    const COLUMNS: [(&str, ColumnType); 2] =
        [(NUME_REUSE, ColumnType::Int), ("X", ColumnType::Real)];

    /// The first call starts a table at 0; each continuation appends to
    /// it with one more than the largest NUME_REUSE present (nmarnr).
    #[test]
    fn calls_are_numbered_from_the_rows_already_there() {
        let first = ContinuedTable::new(None, "t", &COLUMNS);
        assert_eq!(first.nume_reuse, 0);
        assert_eq!(first.table.columns, vec![NUME_REUSE, "X"]);
        let mut t = first.table;
        for n in [0, 0, 3, 1] {
            t.add_row(&[(NUME_REUSE, Cell::Int(n)), ("X", Cell::Real(1.0))])
                .unwrap();
        }
        let next = ContinuedTable::new(Some(&t), "ignored", &COLUMNS);
        assert_eq!(next.nume_reuse, 4);
        assert_eq!(next.table.n_rows(), 4);
        assert_eq!(next.table.title, vec!["t".to_string()]);
        // A table without rows, or without the column, starts at 0.
        let empty = ContinuedTable::new(None, "t", &COLUMNS).table;
        assert_eq!(
            ContinuedTable::new(Some(&empty), "t", &COLUMNS).nume_reuse,
            0
        );
        let mut other = Table::new();
        let _ = other.add_column("Y", ColumnType::Int);
        let fresh = ContinuedTable::new(Some(&other), "new", &COLUMNS);
        assert_eq!((fresh.nume_reuse, fresh.table.columns.len()), (0, 2));
    }
}
