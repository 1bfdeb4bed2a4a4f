//! Result tables (table_sdaster): ordered columns of typed cells.

/// One cell of a table; a missing cell is `None` in [`Table::rows`].
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Int(i64),
    Real(f64),
    Text(String),
}

/// A table as code_aster builds it: named columns, rows of optional cells.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    pub title: Vec<String>,
    pub columns: Vec<String>,
    pub rows: Vec<Vec<Option<Cell>>>,
}
