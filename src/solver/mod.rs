//! Sparse linear algebra: a fixed-pattern sparse matrix and the direct
//! solver behind a small trait.
//!
//! The pattern of a finite-element matrix depends only on the mesh and the
//! contact pairing, so it is built once and reused: assembly adds into a
//! value array aligned with it, and the symbolic factorization (ordering,
//! elimination tree) is computed once per pattern and reused for every
//! Newton iteration and time step. code_aster's SOLVEUR METHODE
//! (MULT_FRONT, LDLT, MUMPS) all map to the same direct LU here: a direct
//! solve gives the same physics whichever is chosen.

use std::sync::Arc;

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::MatMut;

/// A compressed-sparse-column pattern with sorted rows in each column.
#[derive(Debug, Clone, PartialEq)]
pub struct CscPattern {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
}

impl CscPattern {
    /// Builds the pattern of an `n x n` matrix from (row, col) entries
    /// (duplicates allowed). Diagonal entries are always included, so that
    /// a row of zeros can be detected as a singular pivot rather than a
    /// structural hole.
    pub fn from_entries(n: usize, entries: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let mut cols: Vec<Vec<usize>> = (0..n).map(|j| vec![j]).collect();
        for (i, j) in entries {
            assert!(i < n && j < n, "entry ({i}, {j}) outside a {n}x{n} matrix");
            cols[j].push(i);
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for mut c in cols {
            c.sort_unstable();
            c.dedup();
            row_idx.extend(c);
            col_ptr.push(row_idx.len());
        }
        CscPattern {
            n,
            col_ptr,
            row_idx,
        }
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Position of entry (row, col) in the value array.
    #[inline]
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        let (a, b) = (self.col_ptr[col], self.col_ptr[col + 1]);
        self.row_idx[a..b].binary_search(&row).ok().map(|k| a + k)
    }

    fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        SymbolicSparseColMatRef::new_checked(self.n, self.n, &self.col_ptr, None, &self.row_idx)
    }
}

/// A square sparse matrix whose values follow a shared pattern.
#[derive(Debug, Clone)]
pub struct SparseMatrix {
    pub pattern: Arc<CscPattern>,
    pub values: Vec<f64>,
}

impl SparseMatrix {
    pub fn zeros(pattern: Arc<CscPattern>) -> Self {
        let values = vec![0.0; pattern.nnz()];
        SparseMatrix { pattern, values }
    }

    pub fn n(&self) -> usize {
        self.pattern.n
    }

    pub fn fill_zero(&mut self) {
        self.values.iter_mut().for_each(|v| *v = 0.0);
    }

    /// Adds `v` to entry (row, col); the entry must be in the pattern.
    #[inline]
    pub fn add(&mut self, row: usize, col: usize, v: f64) {
        match self.pattern.position(row, col) {
            Some(k) => self.values[k] += v,
            None => panic!("entry ({row}, {col}) is not in the sparsity pattern"),
        }
    }

    pub fn get(&self, row: usize, col: usize) -> f64 {
        self.pattern
            .position(row, col)
            .map(|k| self.values[k])
            .unwrap_or(0.0)
    }

    /// y = A x
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        let p = &self.pattern;
        for j in 0..p.n {
            let xj = x[j];
            for k in p.col_ptr[j]..p.col_ptr[j + 1] {
                y[p.row_idx[k]] += self.values[k] * xj;
            }
        }
    }

    /// Replaces A by (A + A^T)/2 in place (MATR_RIGI_SYME='OUI'); the
    /// pattern of a finite-element matrix is structurally symmetric.
    pub fn symmetrize(&mut self) {
        let p = self.pattern.clone();
        for j in 0..p.n {
            for k in p.col_ptr[j]..p.col_ptr[j + 1] {
                let i = p.row_idx[k];
                if i < j {
                    if let Some(kt) = p.position(j, i) {
                        let m = 0.5 * (self.values[k] + self.values[kt]);
                        self.values[k] = m;
                        self.values[kt] = m;
                    }
                }
            }
        }
    }

    fn faer(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(self.pattern.symbolic(), &self.values)
    }
}

/// Why a solve failed; the time-stepping layer turns these into a step cut.
#[derive(Debug, Clone, PartialEq)]
pub enum SolverError {
    /// The matrix is (numerically) singular: a zero pivot or a non-finite
    /// solution.
    Singular(String),
    /// `solve` before a successful `factorize`, or a size mismatch.
    Usage(String),
}

impl std::fmt::Display for SolverError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolverError::Singular(m) => write!(f, "singular matrix: {m}"),
            SolverError::Usage(m) => write!(f, "linear solver misuse: {m}"),
        }
    }
}

impl std::error::Error for SolverError {}

/// A linear solver: factorize once, solve many right-hand sides.
pub trait LinearSolver {
    fn factorize(&mut self, a: &SparseMatrix) -> Result<(), SolverError>;
    /// Solves A x = b in place (b becomes x).
    fn solve(&self, b: &mut [f64]) -> Result<(), SolverError>;
}

/// Sparse direct LU with partial pivoting (faer), reusing the symbolic
/// factorization as long as the pattern is the same object.
#[derive(Default)]
pub struct DirectLu {
    symbolic: Option<(Arc<CscPattern>, SymbolicLu<usize>)>,
    numeric: Option<Lu<usize, f64>>,
    /// How many symbolic factorizations were computed (for benchmarks and
    /// the test that reuse happens).
    pub symbolic_count: usize,
    pub numeric_count: usize,
}

impl DirectLu {
    pub fn new() -> Self {
        Self::default()
    }
}

impl LinearSolver for DirectLu {
    fn factorize(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        let _factor = crate::bench::span(crate::bench::Phase::FactorSolve);
        if let Some(v) = a.values.iter().find(|v| !v.is_finite()) {
            return Err(SolverError::Singular(format!(
                "the matrix holds a non-finite value ({v})"
            )));
        }
        let reuse = matches!(&self.symbolic, Some((p, _)) if Arc::ptr_eq(p, &a.pattern) || **p == *a.pattern);
        if !reuse {
            let sym = SymbolicLu::try_new(a.pattern.symbolic())
                .map_err(|e| SolverError::Singular(format!("symbolic factorization: {e:?}")))?;
            self.symbolic = Some((a.pattern.clone(), sym));
            self.symbolic_count += 1;
        }
        let sym = self
            .symbolic
            .as_ref()
            .map(|(_, s)| s.clone())
            .expect("set above");
        let lu = Lu::try_new_with_symbolic(sym, a.faer())
            .map_err(|e| SolverError::Singular(format!("numeric factorization: {e:?}")))?;
        self.numeric = Some(lu);
        self.numeric_count += 1;
        Ok(())
    }

    fn solve(&self, b: &mut [f64]) -> Result<(), SolverError> {
        let _solve = crate::bench::span(crate::bench::Phase::FactorSolve);
        let lu = self
            .numeric
            .as_ref()
            .ok_or_else(|| SolverError::Usage("solve called before factorize".into()))?;
        let n = self.symbolic.as_ref().map(|(p, _)| p.n).unwrap_or(0);
        if b.len() != n {
            return Err(SolverError::Usage(format!(
                "right-hand side of length {} for a matrix of order {n}",
                b.len()
            )));
        }
        lu.solve_in_place(MatMut::from_column_major_slice_mut(b, n, 1));
        // A zero pivot does not stop faer: it shows up as inf/NaN here
        // (and NaN compares false, so check explicitly).
        if let Some(i) = b.iter().position(|v| !v.is_finite()) {
            return Err(SolverError::Singular(format!(
                "the solution is not finite at unknown {i}"
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dense_solve(a: &[Vec<f64>], b: &[f64]) -> Vec<f64> {
        // Gaussian elimination with partial pivoting, as an independent check.
        let n = b.len();
        let mut m: Vec<Vec<f64>> = a.to_vec();
        let mut x = b.to_vec();
        for k in 0..n {
            let p = (k..n)
                .max_by(|&i, &j| m[i][k].abs().total_cmp(&m[j][k].abs()))
                .unwrap();
            m.swap(k, p);
            x.swap(k, p);
            for i in k + 1..n {
                let f = m[i][k] / m[k][k];
                for j in k..n {
                    m[i][j] -= f * m[k][j];
                }
                x[i] -= f * x[k];
            }
        }
        for k in (0..n).rev() {
            for j in k + 1..n {
                x[k] -= m[k][j] * x[j];
            }
            x[k] /= m[k][k];
        }
        x
    }

    fn build(a: &[Vec<f64>]) -> SparseMatrix {
        let n = a.len();
        let entries = (0..n).flat_map(|i| (0..n).map(move |j| (i, j)));
        let entries: Vec<_> = entries.filter(|&(i, j)| a[i][j] != 0.0).collect();
        let mut m = SparseMatrix::zeros(Arc::new(CscPattern::from_entries(n, entries)));
        for i in 0..n {
            for j in 0..n {
                if a[i][j] != 0.0 {
                    m.add(i, j, a[i][j]);
                }
            }
        }
        m
    }

    #[test]
    fn nonsymmetric_system_matches_dense_elimination() {
        let a = vec![
            vec![4.0, -1.0, 0.0, 0.5],
            vec![-2.0, 5.0, 1.0, 0.0],
            vec![0.0, 1.5, 3.0, -1.0],
            vec![0.3, 0.0, -1.0, 2.0],
        ];
        let b = vec![1.0, -2.0, 0.5, 3.0];
        let m = build(&a);
        let mut s = DirectLu::new();
        s.factorize(&m).unwrap();
        let mut x = b.clone();
        s.solve(&mut x).unwrap();
        let xd = dense_solve(&a, &b);
        for (u, v) in x.iter().zip(&xd) {
            assert!((u - v).abs() < 1e-12, "{x:?} vs {xd:?}");
        }
        let mut r = vec![0.0; 4];
        m.mul_vec(&x, &mut r);
        for (ri, bi) in r.iter().zip(&b) {
            assert!((ri - bi).abs() < 1e-12);
        }
    }

    #[test]
    fn symbolic_factorization_is_reused_for_new_values() {
        let a = vec![
            vec![2.0, -1.0, 0.0],
            vec![-1.0, 2.0, -1.0],
            vec![0.0, -1.0, 2.0],
        ];
        let mut m = build(&a);
        let mut s = DirectLu::new();
        s.factorize(&m).unwrap();
        m.values.iter_mut().for_each(|v| *v *= 3.0);
        s.factorize(&m).unwrap();
        assert_eq!((s.symbolic_count, s.numeric_count), (1, 2));
        let mut x = vec![3.0, 0.0, 3.0];
        s.solve(&mut x).unwrap();
        for v in x {
            assert!((v - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn singular_matrix_is_reported_not_returned_as_nan() {
        let a = vec![vec![1.0, 2.0], vec![2.0, 4.0]];
        let m = build(&a);
        let mut s = DirectLu::new();
        let r = s.factorize(&m).and_then(|_| s.solve(&mut [1.0, 1.0]));
        assert!(matches!(r, Err(SolverError::Singular(_))), "{r:?}");
    }

    #[test]
    fn symmetrize_averages_off_diagonal_pairs() {
        let mut m = build(&[vec![1.0, 2.0], vec![4.0, 1.0]]);
        m.symmetrize();
        assert_eq!((m.get(0, 1), m.get(1, 0)), (3.0, 3.0));
    }
}
