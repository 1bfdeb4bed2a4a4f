//! Result tables (table_sdaster): ordered, typed columns of optional cells,
//! with code_aster's FILTRE semantics and the IMPR_TABLE printers.
//!
//! A column keeps its code_aster type (I, R, K8/K16/K24/K80) because the
//! type decides how a cell is printed and which FILTRE value keyword
//! (VALE, VALE_I, VALE_K) may select on it. Layouts follow
//! `code_aster/Objects/table_py.py` (`ReprTable`, `FMT`) and
//! `impr_table_ops.py`; see `docs/testing-report.md`.

use super::test_report::{py_repr, Critere};

/// One cell of a table; a missing cell is `None` in [`Table::rows`].
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Int(i64),
    Real(f64),
    Text(String),
}

impl Cell {
    /// The numeric value of an I or R cell.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Cell::Int(i) => Some(*i as f64),
            Cell::Real(x) => Some(*x),
            Cell::Text(_) => None,
        }
    }

    /// Python's `str()` of the cell (used in FILTRE traces).
    pub fn py_str(&self) -> String {
        match self {
            Cell::Int(i) => i.to_string(),
            Cell::Real(x) => py_repr(*x),
            Cell::Text(s) => s.clone(),
        }
    }

    fn natural_type(&self) -> ColumnType {
        match self {
            Cell::Int(_) => ColumnType::Int,
            Cell::Real(_) => ColumnType::Real,
            Cell::Text(_) => ColumnType::Text(24),
        }
    }
}

/// code_aster's column types: `I`, `R` and `Kn` (strings of at most n
/// characters; n is 8, 16, 24 or 80 in practice).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColumnType {
    Int,
    Real,
    Text(usize),
}

impl ColumnType {
    /// `I`, `R`, `K8`, `K16`...
    pub fn aster_name(self) -> String {
        match self {
            ColumnType::Int => "I".to_string(),
            ColumnType::Real => "R".to_string(),
            ColumnType::Text(n) => format!("K{n}"),
        }
    }

    pub fn parse(text: &str) -> Option<ColumnType> {
        match text {
            "I" => Some(ColumnType::Int),
            "R" => Some(ColumnType::Real),
            _ => {
                let n: usize = text.strip_prefix('K')?.parse().ok()?;
                (n > 0).then_some(ColumnType::Text(n))
            }
        }
    }
}

/// An error on a table operation. `keyword` names the keyword the caller
/// should point at (e.g. `FILTRE/VALE_I`), when the error comes from one.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TableError {
    pub keyword: Option<String>,
    pub message: String,
}

impl TableError {
    pub(crate) fn new(message: impl Into<String>) -> TableError {
        TableError {
            keyword: None,
            message: message.into(),
        }
    }

    pub(crate) fn at(mut self, keyword: &str) -> TableError {
        self.keyword = Some(keyword.to_string());
        self
    }
}

impl std::fmt::Display for TableError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for TableError {}

/// A table as code_aster builds it: named columns, rows of optional cells.
///
/// `types[i]` is the type of `columns[i]`; when `types` is shorter (a table
/// built field by field), the type is inferred from the first cell, as
/// code_aster's Python tables do (`I`, `R`, or `K24` for texts).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    pub title: Vec<String>,
    pub columns: Vec<String>,
    pub rows: Vec<Vec<Option<Cell>>>,
    pub types: Vec<ColumnType>,
}

/// FILTRE's CRIT_COMP.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CritComp {
    Eq,
    Ne,
    Lt,
    Gt,
    Le,
    Ge,
    Vide,
    NonVide,
    Maxi,
    MaxiAbs,
    Mini,
    MiniAbs,
}

impl CritComp {
    pub fn parse(text: &str) -> Option<CritComp> {
        Some(match text {
            "EQ" => CritComp::Eq,
            "NE" => CritComp::Ne,
            "LT" => CritComp::Lt,
            "GT" => CritComp::Gt,
            "LE" => CritComp::Le,
            "GE" => CritComp::Ge,
            "VIDE" => CritComp::Vide,
            "NON_VIDE" => CritComp::NonVide,
            "MAXI" => CritComp::Maxi,
            "MAXI_ABS" => CritComp::MaxiAbs,
            "MINI" => CritComp::Mini,
            "MINI_ABS" => CritComp::MiniAbs,
            _ => return None,
        })
    }

    pub fn as_str(self) -> &'static str {
        match self {
            CritComp::Eq => "EQ",
            CritComp::Ne => "NE",
            CritComp::Lt => "LT",
            CritComp::Gt => "GT",
            CritComp::Le => "LE",
            CritComp::Ge => "GE",
            CritComp::Vide => "VIDE",
            CritComp::NonVide => "NON_VIDE",
            CritComp::Maxi => "MAXI",
            CritComp::MaxiAbs => "MAXI_ABS",
            CritComp::Mini => "MINI",
            CritComp::MiniAbs => "MINI_ABS",
        }
    }

    fn needs_values(self) -> bool {
        matches!(
            self,
            CritComp::Eq | CritComp::Ne | CritComp::Lt | CritComp::Gt | CritComp::Le | CritComp::Ge
        )
    }
}

/// The values of a FILTRE occurrence: VALE, VALE_I or VALE_K.
#[derive(Debug, Clone, PartialEq)]
pub enum FilterValues {
    None,
    Real(Vec<f64>),
    Int(Vec<i64>),
    Text(Vec<String>),
}

impl FilterValues {
    fn keyword(&self) -> &'static str {
        match self {
            FilterValues::None => "VALE",
            FilterValues::Real(_) => "VALE",
            FilterValues::Int(_) => "VALE_I",
            FilterValues::Text(_) => "VALE_K",
        }
    }

    fn is_empty(&self) -> bool {
        match self {
            FilterValues::None => true,
            FilterValues::Real(v) => v.is_empty(),
            FilterValues::Int(v) => v.is_empty(),
            FilterValues::Text(v) => v.is_empty(),
        }
    }

    fn py_strs(&self) -> Vec<String> {
        match self {
            FilterValues::None => vec![],
            FilterValues::Real(v) => v.iter().map(|x| py_repr(*x)).collect(),
            FilterValues::Int(v) => v.iter().map(|x| x.to_string()).collect(),
            FilterValues::Text(v) => v.clone(),
        }
    }
}

/// One FILTRE occurrence.
#[derive(Debug, Clone, PartialEq)]
pub struct Filter {
    pub nom_para: String,
    pub crit_comp: CritComp,
    pub values: FilterValues,
    /// For EQ/NE on reals: RELATIF (default) or ABSOLU.
    pub critere: Critere,
    /// For EQ/NE on reals, default 1e-3.
    pub precision: f64,
}

impl Filter {
    /// A filter with code_aster's defaults (RELATIF, PRECISION=1e-3).
    pub fn new(nom_para: &str, crit_comp: CritComp, values: FilterValues) -> Filter {
        Filter {
            nom_para: nom_para.to_string(),
            crit_comp,
            values,
            critere: Critere::Relatif,
            precision: 1e-3,
        }
    }
}

impl Filter {
    /// Appends the line code_aster writes in the title of a filtered table
    /// (impr_table_ops and calc_table_ops trace their FILTRE the same way).
    pub fn trace_in_title(&self, title: &mut Vec<String>) {
        if title.is_empty() {
            title.push(String::new());
        }
        title.push(format!(
            "FILTRE -> NOM_PARA: {:<16} CRIT_COMP: {:<4} VALE: {}",
            self.nom_para,
            self.crit_comp.as_str(),
            self.values.py_strs().join(" ")
        ));
    }
}

impl Table {
    pub fn new() -> Table {
        Table::default()
    }

    pub fn n_rows(&self) -> usize {
        self.rows.len()
    }

    pub fn column_index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// The declared type of column `index`, or the type of its first cell,
    /// or `R` for a column without any cell.
    pub fn column_type(&self, index: usize) -> ColumnType {
        if let Some(t) = self.types.get(index) {
            return *t;
        }
        self.rows
            .iter()
            .find_map(|r| r.get(index).and_then(|c| c.as_ref()))
            .map(Cell::natural_type)
            .unwrap_or(ColumnType::Real)
    }

    /// Declared or inferred types of all the columns.
    pub(crate) fn all_types(&self) -> Vec<ColumnType> {
        (0..self.columns.len())
            .map(|i| self.column_type(i))
            .collect()
    }

    /// Adds an empty column; existing rows get a missing cell.
    pub fn add_column(&mut self, name: &str, ty: ColumnType) -> Result<usize, TableError> {
        if self.column_index(name).is_some() {
            return Err(TableError::new(format!(
                "the table already has a column named '{name}'"
            )));
        }
        self.types = self.all_types();
        self.columns.push(name.to_string());
        self.types.push(ty);
        for r in &mut self.rows {
            r.resize(self.columns.len(), None);
        }
        Ok(self.columns.len() - 1)
    }

    fn check_cell(&self, index: usize, cell: &Cell) -> Result<Cell, TableError> {
        let name = &self.columns[index];
        match (self.column_type(index), cell) {
            (ColumnType::Int, Cell::Int(_)) | (ColumnType::Real, Cell::Real(_)) => Ok(cell.clone()),
            // An integer in a real column is a real (code_aster's "R envelope").
            (ColumnType::Real, Cell::Int(i)) => Ok(Cell::Real(*i as f64)),
            (ColumnType::Text(n), Cell::Text(s)) => {
                if s.chars().count() > n {
                    Err(TableError::new(format!(
                        "the text '{s}' is longer than the {n} characters of column '{name}' (K{n})"
                    )))
                } else {
                    Ok(cell.clone())
                }
            }
            (ty, _) => Err(TableError::new(format!(
                "column '{name}' holds {} values ({}): cannot store {}",
                type_words(ty),
                ty.aster_name(),
                cell_words(cell)
            ))),
        }
    }

    /// Appends a row given in column order (`None` = missing cell).
    pub fn push_row(&mut self, cells: Vec<Option<Cell>>) -> Result<(), TableError> {
        if cells.len() != self.columns.len() {
            return Err(TableError::new(format!(
                "a row of {} cells cannot be added to a table of {} columns",
                cells.len(),
                self.columns.len()
            )));
        }
        let mut row = Vec::with_capacity(cells.len());
        for (i, c) in cells.iter().enumerate() {
            row.push(match c {
                Some(c) => Some(self.check_cell(i, c)?),
                None => None,
            });
        }
        self.rows.push(row);
        Ok(())
    }

    /// Appends a row given by column name; unknown columns are created with
    /// the type of their value (I, R or K24), the others stay missing.
    pub fn add_row(&mut self, cells: &[(&str, Cell)]) -> Result<(), TableError> {
        for (name, cell) in cells {
            if self.column_index(name).is_none() {
                self.add_column(name, cell.natural_type())?;
            }
        }
        let mut row = vec![None; self.columns.len()];
        for (name, cell) in cells {
            let i = self.column_index(name).unwrap_or(0);
            row[i] = Some(cell.clone());
        }
        self.push_row(row)
    }

    pub(crate) fn index_or_error(&self, name: &str, keyword: &str) -> Result<usize, TableError> {
        self.column_index(name).ok_or_else(|| {
            let mut msg = format!("the table has no column '{name}'");
            if let Some(c) = crate::diag::closest(name, &self.columns) {
                msg.push_str(&format!("; did you mean '{c}'?"));
            }
            msg.push_str(&format!(" (columns: {})", self.columns.join(", ")));
            TableError::new(msg).at(keyword)
        })
    }

    /// The cells of a column, in row order.
    pub fn column(&self, name: &str) -> Result<Vec<Option<&Cell>>, TableError> {
        let i = self.index_or_error(name, "NOM_PARA")?;
        Ok(self
            .rows
            .iter()
            .map(|r| r.get(i).and_then(|c| c.as_ref()))
            .collect())
    }

    /// The cell of column `name` in row `row`.
    pub fn cell(&self, row: usize, name: &str) -> Option<&Cell> {
        let i = self.column_index(name)?;
        self.rows.get(row)?.get(i)?.as_ref()
    }

    /// The value TEST_TABLE tests: the cell of column `name` when exactly
    /// one row is left (code_aster's CALCULEL6_3..6 otherwise).
    pub fn single_value(&self, name: &str) -> Result<&Cell, TableError> {
        let i = self.index_or_error(name, "NOM_PARA")?;
        match self.rows.len() {
            0 => Err(TableError::new(format!(
                "no row is left after filtering: cannot read '{name}' (exactly one row is needed)"
            ))
            .at("FILTRE")),
            1 => self.rows[0].get(i).and_then(|c| c.as_ref()).ok_or_else(|| {
                TableError::new(format!("the cell of '{name}' in the selected row is empty"))
                    .at("NOM_PARA")
            }),
            n => Err(TableError::new(format!(
                "{n} rows are left after filtering: cannot read '{name}' (exactly one row is \
                 needed; add FILTRE occurrences or use TYPE_TEST)"
            ))
            .at("FILTRE")),
        }
    }

    /// Keeps the rows that satisfy one FILTRE occurrence.
    ///
    /// EQ/NE with VALE compare reals with PRECISION (relative by default:
    /// |v - x| <= PRECISION·|x|); integers and texts compare exactly (texts
    /// without trailing blanks). Several values: EQ keeps a row equal to one
    /// of them, NE a row equal to none, LT/LE compare with the largest and
    /// GT/GE with the smallest. Missing cells never match, except VIDE.
    /// MAXI/MINI (and _ABS) keep exactly one row: the first extreme one.
    pub fn filter(&self, f: &Filter) -> Result<Table, TableError> {
        let col = self.index_or_error(&f.nom_para, "FILTRE/NOM_PARA")?;
        let ty = self.column_type(col);
        let kw = format!("FILTRE/{}", f.values.keyword());
        if f.crit_comp.needs_values() {
            if f.values.is_empty() {
                return Err(TableError::new(format!(
                    "CRIT_COMP='{}' needs a value (VALE, VALE_I or VALE_K)",
                    f.crit_comp.as_str()
                ))
                .at("FILTRE/CRIT_COMP"));
            }
            let ok = matches!(
                (&f.values, ty),
                (FilterValues::Real(_), ColumnType::Real)
                    | (FilterValues::Int(_), ColumnType::Int)
                    | (FilterValues::Text(_), ColumnType::Text(_))
            );
            if !ok {
                let right = match ty {
                    ColumnType::Int => "VALE_I",
                    ColumnType::Real => "VALE",
                    ColumnType::Text(_) => "VALE_K",
                };
                return Err(TableError::new(format!(
                    "FILTRE on '{}': the column holds {} values ({}), so the value must be given \
                     with {right}, not {}",
                    f.nom_para,
                    type_words(ty),
                    ty.aster_name(),
                    f.values.keyword()
                ))
                .at(&kw));
            }
        }
        fn cell_at(r: &[Option<Cell>], col: usize) -> Option<&Cell> {
            r.get(col).and_then(|c| c.as_ref())
        }
        let keep: Vec<bool> = match f.crit_comp {
            CritComp::Vide => self
                .rows
                .iter()
                .map(|r| cell_at(r, col).is_none())
                .collect(),
            CritComp::NonVide => self
                .rows
                .iter()
                .map(|r| cell_at(r, col).is_some())
                .collect(),
            CritComp::Maxi | CritComp::MaxiAbs | CritComp::Mini | CritComp::MiniAbs => {
                if let ColumnType::Text(_) = ty {
                    return Err(TableError::new(format!(
                        "CRIT_COMP='{}' needs a numeric column, '{}' holds texts",
                        f.crit_comp.as_str(),
                        f.nom_para
                    ))
                    .at("FILTRE/CRIT_COMP"));
                }
                let value = |r: &Vec<Option<Cell>>| {
                    let v = cell_at(r, col).and_then(Cell::as_f64)?;
                    Some(match f.crit_comp {
                        CritComp::MaxiAbs | CritComp::MiniAbs => v.abs(),
                        _ => v,
                    })
                };
                let want_max = matches!(f.crit_comp, CritComp::Maxi | CritComp::MaxiAbs);
                let mut best: Option<(usize, f64)> = None;
                for (i, r) in self.rows.iter().enumerate() {
                    if let Some(v) = value(r) {
                        let better = match best {
                            None => true,
                            Some((_, b)) => (want_max && v > b) || (!want_max && v < b),
                        };
                        if better {
                            best = Some((i, v));
                        }
                    }
                }
                (0..self.rows.len())
                    .map(|i| Some(i) == best.map(|b| b.0))
                    .collect()
            }
            op => self
                .rows
                .iter()
                .map(|r| cell_at(r, col).is_some_and(|c| compare(op, c, f)))
                .collect(),
        };
        let mut out = Table {
            title: self.title.clone(),
            columns: self.columns.clone(),
            rows: Vec::new(),
            types: self.all_types(),
        };
        out.rows = self
            .rows
            .iter()
            .zip(keep)
            .filter(|(_, k)| *k)
            .map(|(r, _)| r.clone())
            .collect();
        Ok(out)
    }

    /// Applies FILTRE occurrences one after the other (they are ANDed).
    pub fn filter_all(&self, filters: &[Filter]) -> Result<Table, TableError> {
        let mut t = self.clone();
        for f in filters {
            t = t.filter(f)?;
        }
        Ok(t)
    }

    /// The columns `names`, in that order; names that are not columns are
    /// returned apart (IMPR_TABLE alarms TABLE0_7 on them).
    pub fn select(&self, names: &[&str]) -> (Table, Vec<String>) {
        let mut idx = Vec::new();
        let mut missing = Vec::new();
        for n in names {
            match self.column_index(n) {
                Some(i) => idx.push(i),
                None => missing.push(n.to_string()),
            }
        }
        let out = Table {
            title: self.title.clone(),
            columns: idx.iter().map(|&i| self.columns[i].clone()).collect(),
            types: idx.iter().map(|&i| self.column_type(i)).collect(),
            rows: self
                .rows
                .iter()
                .map(|r| idx.iter().map(|&i| r.get(i).cloned().flatten()).collect())
                .collect(),
        };
        (out, missing)
    }

    /// A copy without the columns that have no cell (code_aster's
    /// `SansColonneVide`).
    pub fn without_empty_columns(&self) -> Table {
        let keep: Vec<&str> = (0..self.columns.len())
            .filter(|&i| {
                self.rows
                    .iter()
                    .any(|r| r.get(i).is_some_and(|c| c.is_some()))
            })
            .map(|i| self.columns[i].as_str())
            .collect();
        self.select(&keep).0
    }

    /// Sorts the rows on `keys` (TRI). A missing cell sorts as 0 or as an
    /// empty text; the sort is stable.
    pub fn sort_by(&mut self, keys: &[&str], descending: bool) -> Result<(), TableError> {
        let mut idx = Vec::new();
        for k in keys {
            idx.push(self.index_or_error(k, "TRI/NOM_PARA")?);
        }
        let types = self.all_types();
        self.rows.sort_by(|a, b| {
            for &i in &idx {
                let ord = cmp_cells(
                    a.get(i).and_then(|c| c.as_ref()),
                    b.get(i).and_then(|c| c.as_ref()),
                    types[i],
                );
                let ord = if descending { ord.reverse() } else { ord };
                if ord != std::cmp::Ordering::Equal {
                    return ord;
                }
            }
            std::cmp::Ordering::Equal
        });
        Ok(())
    }

    /// The text IMPR_TABLE writes (FORMAT TABLEAU or AGRAF), after FILTRE,
    /// TRI, NOM_PARA and the removal of empty columns. Returns the text and
    /// the warnings to log (unknown NOM_PARA, TABLE0_7).
    pub fn impr_table(&self, opts: &PrintOptions) -> Result<(String, Vec<String>), TableError> {
        let mut t = self.clone();
        if !opts.titre.is_empty() {
            let mut title = opts.titre.clone();
            title.extend(t.title.iter().cloned());
            t.title = title;
        }
        for f in &opts.filters {
            t = t.filter(f)?;
            f.trace_in_title(&mut t.title);
        }
        if let Some((keys, descending)) = &opts.tri {
            let keys: Vec<&str> = keys.iter().map(String::as_str).collect();
            t.sort_by(&keys, *descending)?;
        }
        let mut warnings = Vec::new();
        let t = match &opts.nom_para {
            Some(names) => {
                let names: Vec<&str> = names.iter().map(String::as_str).collect();
                let (sel, missing) = t.select(&names);
                for m in missing {
                    warnings.push(format!(
                        "TABLE0_7: the parameter '{m}' is not a column of the table: it is not printed"
                    ));
                }
                sel
            }
            None => t,
        };
        let t = t.without_empty_columns();
        Ok((t.print(opts)?, warnings))
    }

    /// The TABLEAU / AGRAF text of the table as it is (no filtering):
    /// `ReprTable` of code_aster plus the newline `ImprTableau` adds.
    pub fn print(&self, opts: &PrintOptions) -> Result<String, TableError> {
        let form_r = match opts.format {
            PrintFormat::Agraf if opts.format_r.is_none() => RealFormat::default(),
            _ => match &opts.format_r {
                Some(f) => RealFormat::from_fortran(f).ok_or_else(|| {
                    TableError::new(format!(
                        "FORMAT_R='{f}' is not a Fortran real format such as E12.5"
                    ))
                    .at("FORMAT_R")
                })?,
                None => RealFormat::default(),
            },
        };
        let form_i = IntFormat { width: 12 };
        let sep = opts.separator.as_str();
        let types = self.all_types();
        // Column widths and formats as table_py.FMT computes them.
        struct Col {
            width: usize,
            k_lead: usize,
            k_width: usize,
        }
        let mut cols = Vec::new();
        for (name, ty) in self.columns.iter().zip(&types) {
            let (k_lead, k_width) = match ty {
                ColumnType::Real => (form_r.leading, form_r.width),
                ColumnType::Int => (0, form_i.width),
                ColumnType::Text(n) => (0, *n),
            };
            let k_len = k_lead + k_width.max(1);
            let width = match ty {
                ColumnType::Text(_) => name.chars().count().max(k_len),
                _ => name
                    .chars()
                    .count()
                    .max(k_len)
                    .max(form_r.format(0.0).len())
                    .max(form_i.format(0).len()),
            };
            cols.push(Col {
                width,
                k_lead,
                k_width,
            });
        }
        let k_cell = |c: &Col, s: &str, val_len: usize| -> String {
            let fmt_len = c.k_lead + c.k_width.max(1);
            let blanks = (c.width as isize - val_len as isize)
                .min(c.width as isize - fmt_len as isize)
                .max(0) as usize;
            format!(
                "{}{}{:<w$}",
                " ".repeat(blanks),
                " ".repeat(c.k_lead),
                s,
                w = c.k_width
            )
        };
        let mut lines: Vec<String> = Vec::new();
        for t in &self.title {
            lines.push(format!("{}{}", opts.comment, t));
        }
        let mut heads: Vec<String> = self
            .columns
            .iter()
            .zip(&cols)
            .map(|(n, c)| k_cell(c, n, n.chars().count()))
            .collect();
        if !sep.contains(' ') {
            heads = heads.iter().map(|h| h.trim().to_string()).collect();
        }
        lines.push(format!("{}{}", opts.comm_para, heads.join(sep)));
        for row in &self.rows {
            if row.iter().all(|c| c.is_none()) {
                continue;
            }
            let mut cells = Vec::new();
            for (i, c) in cols.iter().enumerate() {
                let text = match row.get(i).and_then(|x| x.as_ref()) {
                    Some(cell) => {
                        let s = match (types[i], cell) {
                            (ColumnType::Int, Cell::Int(v)) => form_i.format(*v),
                            (ColumnType::Text(_), Cell::Text(s)) => {
                                format!("{:<w$}", s, w = c.k_width)
                            }
                            (_, cell) => match cell.as_f64() {
                                Some(x) => form_r.format(x),
                                None => format!("{:<w$}", cell.py_str(), w = c.k_width),
                            },
                        };
                        let fmt_len = match types[i] {
                            ColumnType::Int => form_i.format(0).len(),
                            ColumnType::Real => form_r.format(0.0).len(),
                            ColumnType::Text(n) => n.max(1),
                        };
                        format!("{}{}", " ".repeat(c.width.saturating_sub(fmt_len)), s)
                    }
                    None => {
                        let s = k_cell(c, "-", 0);
                        if opts.format == PrintFormat::Agraf {
                            format!("\\{s}")
                        } else {
                            s
                        }
                    }
                };
                cells.push(text.lines().collect::<Vec<_>>().join(";"));
            }
            lines.push(cells.join(sep));
        }
        let head = match &opts.debut_table {
            Some(h) => h.clone(),
            None => format!("{c}\n{c}{}\n{c}\n", "-".repeat(80), c = opts.comment),
        };
        let mut out = head;
        for l in lines {
            out.push_str(&opts.debut_ligne);
            out.push_str(&l);
            out.push_str(&opts.fin_ligne);
        }
        out.push_str(&opts.fin_table);
        out.push('\n');
        Ok(out)
    }

    /// IMPR_TABLE FORMAT='XMGRACE': the table must have exactly two columns
    /// (after NOM_PARA); rows with an empty cell are left out.
    pub fn xmgrace(
        &self,
        graph: &super::function::GraphOptions,
        legend: &str,
    ) -> Result<String, TableError> {
        if self.columns.len() != 2 {
            return Err(TableError::new(format!(
                "FORMAT='XMGRACE' needs a table of exactly 2 columns (use NOM_PARA), this one has {}: {}",
                self.columns.len(),
                self.columns.join(", ")
            ))
            .at("NOM_PARA"));
        }
        let mut x = Vec::new();
        let mut y = Vec::new();
        for r in &self.rows {
            let a = r.first().and_then(|c| c.as_ref()).and_then(Cell::as_f64);
            let b = r.get(1).and_then(|c| c.as_ref()).and_then(Cell::as_f64);
            if let (Some(a), Some(b)) = (a, b) {
                x.push(a);
                y.push(b);
            }
        }
        let curve = super::function::XyCurve {
            x,
            y,
            legend: legend.to_string(),
            ..Default::default()
        };
        Ok(super::function::grace_project(&[curve], graph))
    }
}

fn type_words(ty: ColumnType) -> &'static str {
    match ty {
        ColumnType::Int => "integer",
        ColumnType::Real => "real",
        ColumnType::Text(_) => "text",
    }
}

fn cell_words(c: &Cell) -> String {
    match c {
        Cell::Int(i) => format!("the integer {i}"),
        Cell::Real(x) => format!("the real {}", py_repr(*x)),
        Cell::Text(s) => format!("the text '{s}'"),
    }
}

fn cmp_cells(a: Option<&Cell>, b: Option<&Cell>, ty: ColumnType) -> std::cmp::Ordering {
    match ty {
        ColumnType::Text(_) => {
            let s = |c: Option<&Cell>| c.map(Cell::py_str).unwrap_or_default();
            s(a).cmp(&s(b))
        }
        _ => {
            let v = |c: Option<&Cell>| c.and_then(Cell::as_f64).unwrap_or(0.0);
            v(a).total_cmp(&v(b))
        }
    }
}

/// EQ/NE/LT/GT/LE/GE on one present cell.
fn compare(op: CritComp, cell: &Cell, f: &Filter) -> bool {
    match (&f.values, cell) {
        (FilterValues::Text(vals), Cell::Text(s)) => {
            let s = s.trim();
            let any_eq = vals.iter().any(|v| v.trim() == s);
            match op {
                CritComp::Eq => any_eq,
                CritComp::Ne => !any_eq,
                _ => {
                    let (lo, hi) = (
                        vals.iter().map(|v| v.trim()).min().unwrap_or(""),
                        vals.iter().map(|v| v.trim()).max().unwrap_or(""),
                    );
                    ordered(op, s.cmp(lo), s.cmp(hi))
                }
            }
        }
        (FilterValues::Int(vals), Cell::Int(i)) => {
            let any_eq = vals.contains(i);
            match op {
                CritComp::Eq => any_eq,
                CritComp::Ne => !any_eq,
                _ => {
                    let lo = vals.iter().min().copied().unwrap_or(0);
                    let hi = vals.iter().max().copied().unwrap_or(0);
                    ordered(op, i.cmp(&lo), i.cmp(&hi))
                }
            }
        }
        (FilterValues::Real(vals), cell) => {
            let Some(v) = cell.as_f64() else { return false };
            let close = |x: f64| match f.critere {
                Critere::Relatif => (v - x).abs() <= f.precision * x.abs(),
                Critere::Absolu => (v - x).abs() <= f.precision,
            };
            let any_eq = vals.iter().any(|&x| close(x));
            match op {
                CritComp::Eq => any_eq,
                CritComp::Ne => !any_eq,
                _ => {
                    let lo = vals.iter().copied().fold(f64::INFINITY, f64::min);
                    let hi = vals.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    match op {
                        CritComp::Lt => v < hi,
                        CritComp::Le => v <= hi,
                        CritComp::Gt => v > lo,
                        CritComp::Ge => v >= lo,
                        _ => false,
                    }
                }
            }
        }
        _ => false,
    }
}

/// LT/LE compare with the largest value, GT/GE with the smallest.
fn ordered(op: CritComp, vs_lo: std::cmp::Ordering, vs_hi: std::cmp::Ordering) -> bool {
    use std::cmp::Ordering::*;
    match op {
        CritComp::Lt => vs_hi == Less,
        CritComp::Le => vs_hi != Greater,
        CritComp::Gt => vs_lo == Greater,
        CritComp::Ge => vs_lo != Less,
        _ => false,
    }
}

/// IMPR_TABLE's FORMAT (those printed here).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PrintFormat {
    #[default]
    Tableau,
    /// TABLEAU with missing cells printed `\-`.
    Agraf,
}

/// The printing keywords of IMPR_TABLE, with their defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct PrintOptions {
    pub format: PrintFormat,
    /// FORMAT_R as a Fortran format (`E12.5`, `1PE13.6`, `F10.3`).
    pub format_r: Option<String>,
    /// NOM_PARA: the columns to print, in that order.
    pub nom_para: Option<Vec<String>>,
    pub filters: Vec<Filter>,
    /// TRI: keys and DECROISSANT.
    pub tri: Option<(Vec<String>, bool)>,
    /// TITRE lines, printed before the table's own title.
    pub titre: Vec<String>,
    pub separator: String,
    pub comment: String,
    pub comm_para: String,
    pub debut_ligne: String,
    pub fin_ligne: String,
    /// DEBUT_TABLE replaces the 3-line header when given.
    pub debut_table: Option<String>,
    pub fin_table: String,
}

impl Default for PrintOptions {
    fn default() -> PrintOptions {
        PrintOptions {
            format: PrintFormat::Tableau,
            format_r: None,
            nom_para: None,
            filters: Vec::new(),
            tri: None,
            titre: Vec::new(),
            separator: " ".to_string(),
            comment: "#".to_string(),
            comm_para: String::new(),
            debut_ligne: String::new(),
            fin_ligne: "\n".to_string(),
            debut_table: None,
            fin_table: String::new(),
        }
    }
}

/// A real format converted from Fortran as code_aster's `fmtF2PY` does:
/// `E12.5` -> `%12.5E`, `1PE13.6` -> ` %13.6E`, `D12.5` -> `%12.5E`,
/// `F10.3` -> `%10.3F`, `G14.6` -> `%14.6G`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RealFormat {
    /// Blanks printed before the number (the `nP` scale factor count).
    pub leading: usize,
    pub width: usize,
    pub precision: usize,
    /// `E`, `e`, `F`, `f`, `G` or `g`.
    pub kind: char,
}

impl Default for RealFormat {
    /// `%12.5E`.
    fn default() -> RealFormat {
        RealFormat {
            leading: 0,
            width: 12,
            precision: 5,
            kind: 'E',
        }
    }
}

impl RealFormat {
    pub fn from_fortran(text: &str) -> Option<RealFormat> {
        let text = text.trim();
        let bytes: Vec<char> = text.chars().collect();
        // nP scale factor: only its count of blanks matters here.
        let mut leading = 0;
        if let Some(p) = text.find(['P', 'p']) {
            leading = text[..p].parse().ok()?;
        }
        let pos = bytes.iter().position(|c| "eEdDfFgG".contains(*c))?;
        let spec: String = bytes[pos + 1..]
            .iter()
            .take_while(|c| c.is_ascii_digit() || **c == '.')
            .collect();
        let (w, p) = spec.split_once('.').unwrap_or((spec.as_str(), "6"));
        let width = if w.is_empty() { 0 } else { w.parse().ok()? };
        let precision = if p.is_empty() { 0 } else { p.parse().ok()? };
        let kind = match bytes[pos] {
            'd' | 'D' => 'E',
            c => c,
        };
        Some(RealFormat {
            leading,
            width,
            precision,
            kind,
        })
    }

    /// Formats like C's printf, leading blanks included.
    pub fn format(&self, x: f64) -> String {
        let body = match self.kind {
            'E' | 'e' => super::test_report::c_exp(x, 0, self.precision, self.kind == 'E'),
            'F' | 'f' => {
                let s = if x.is_finite() {
                    format!("{:.*}", self.precision, x)
                } else {
                    py_repr(x)
                };
                if self.kind == 'F' {
                    s.to_uppercase()
                } else {
                    s
                }
            }
            _ => c_general(x, self.precision, self.kind == 'G'),
        };
        format!("{}{:>w$}", " ".repeat(self.leading), body, w = self.width)
    }
}

/// `%Wd`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct IntFormat {
    width: usize,
}

impl IntFormat {
    fn format(&self, i: i64) -> String {
        format!("{:>w$}", i, w = self.width)
    }
}

/// C's `%.Pg` (`%.PG` with `upper`): P significant digits, fixed notation
/// when the exponent is in [-4, P), trailing zeros removed.
pub fn c_general(x: f64, precision: usize, upper: bool) -> String {
    if !x.is_finite() {
        let s = py_repr(x);
        return if upper { s.to_uppercase() } else { s };
    }
    let p = precision.max(1);
    let sci = format!("{:.*e}", p - 1, x);
    let (mant, exp) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let strip = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    let out = if exp < -4 || exp >= p as i32 {
        let esign = if exp < 0 { '-' } else { '+' };
        format!("{}e{esign}{:02}", strip(mant), exp.abs())
    } else {
        let decimals = (p as i32 - 1 - exp).max(0) as usize;
        strip(&format!("{:.*}", decimals, x))
    };
    if upper {
        out.to_uppercase()
    } else {
        out
    }
}

/// code_aster's automatic title of a concept: "ASTER <version> CONCEPT
/// <name> CALCULE LE <date> A <time> DE TYPE <TYPE>" cut into lines of at
/// most 80 characters at blanks. `date` is `MM/DD/YYYY` as code_aster's
/// `time.strftime("%m/%d/%Y")` writes it, `time` is `HH:MM:SS`.
pub fn default_title(
    version: &str,
    concept: &str,
    date: &str,
    time: &str,
    ty: &str,
) -> Vec<String> {
    let text = format!(
        "ASTER {version} CONCEPT {concept} CALCULE LE {date} A {time} DE TYPE {}",
        ty.to_uppercase()
    );
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(l) if l.len() + 1 + word.len() <= 80 => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}
