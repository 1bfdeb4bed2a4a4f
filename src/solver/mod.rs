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

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::utils::{permute_self_adjoint_scratch, permute_self_adjoint_to_unsorted};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// A compressed-sparse-column pattern with sorted rows in each column.
#[derive(Debug, Clone, PartialEq)]
pub struct CscPattern {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    /// For entry k = (i, j), the position of (j, i), or [`NO_ENTRY`].
    transpose: Vec<usize>,
    /// Every (k, kt) of `transpose` with kt > k (an off-diagonal pair,
    /// from its first entry in column-major order): symmetrising and the
    /// symmetry test read the pairs without a branch per entry.
    upper_pairs: Vec<(usize, usize)>,
    /// The entries without a transposed entry.
    unpaired: Vec<usize>,
    /// Position of each diagonal entry (always in the pattern).
    diagonal: Vec<usize>,
}

/// No transposed entry in the pattern.
pub const NO_ENTRY: usize = usize::MAX;

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
        let mut p = CscPattern {
            n,
            col_ptr,
            row_idx,
            transpose: Vec::new(),
            upper_pairs: Vec::new(),
            unpaired: Vec::new(),
            diagonal: Vec::new(),
        };
        p.transpose = (0..p.n)
            .flat_map(|j| (p.col_ptr[j]..p.col_ptr[j + 1]).map(move |k| (k, j)))
            .map(|(k, j)| p.position(j, p.row_idx[k]).unwrap_or(NO_ENTRY))
            .collect();
        for (k, &kt) in p.transpose.iter().enumerate() {
            if kt == NO_ENTRY {
                p.unpaired.push(k);
            } else if kt > k {
                p.upper_pairs.push((k, kt));
            }
        }
        p.diagonal = (0..p.n)
            .map(|j| p.position(j, j).expect("the diagonal is in the pattern"))
            .collect();
        p
    }

    /// See the `transpose` field.
    pub fn transpose_map(&self) -> &[usize] {
        &self.transpose
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

    /// |A_ij − A_ji| ≤ rel·(|A_ij| + |A_ji|) for every entry. The test is
    /// symmetric in the pair, so each pair is read once.
    pub fn is_symmetric_within(&self, rel: f64) -> bool {
        let p = &self.pattern;
        let v = &self.values;
        p.upper_pairs.iter().all(|&(k, kt)| {
            let (a, b) = (v[k], v[kt]);
            (a - b).abs() <= rel * (a.abs() + b.abs())
        }) && p.unpaired.iter().all(|&k| v[k] == 0.0)
            // A diagonal entry against itself: |d − d| ≤ 2 rel |d| holds
            // exactly when d is finite.
            && p.diagonal.iter().all(|&k| v[k].is_finite())
    }

    /// |A_ij − A_ji| ≤ rel·max_k |A_kk| for every pair: symmetric up to
    /// round-off measured against the matrix's scale, where
    /// [`Self::is_symmetric_within`] compares each pair with itself (and
    /// refuses two round-off residues of opposite sign).
    pub fn is_symmetric_to_scale(&self, rel: f64) -> bool {
        let p = &self.pattern;
        let v = &self.values;
        let scale = p.diagonal.iter().map(|&k| v[k].abs()).fold(0.0, f64::max);
        let tol = rel * scale;
        p.upper_pairs
            .iter()
            .all(|&(k, kt)| (v[k] - v[kt]).abs() <= tol)
            && p.unpaired.iter().all(|&k| v[k].abs() <= tol)
    }

    /// Replaces A by (A + A^T)/2 in place (MATR_RIGI_SYME='OUI'); the
    /// pattern of a finite-element matrix is structurally symmetric.
    pub fn symmetrize(&mut self) {
        let p = self.pattern.clone();
        // Each pair once, from its upper entry.
        for &(k, kt) in &p.upper_pairs {
            let m = 0.5 * (self.values[k] + self.values[kt]);
            self.values[k] = m;
            self.values[kt] = m;
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
    /// code_aster's singularity criterion (SOLVEUR NPREC): the pivot of
    /// `unknown` lost `decimals` ≥ `nprec` decimals against the matrix's
    /// diagonal entry (infinity for a zero pivot).
    LostDecimals {
        unknown: usize,
        decimals: f64,
        nprec: i64,
    },
    /// The right-hand side handed to the solve is not finite at `unknown`:
    /// what overflowed is the load (or the product of the matrix with the
    /// imposed values), not the matrix, so "singular" would send the user
    /// looking for a missing support.
    NonFiniteRhs { unknown: usize, value: f64 },
    /// The matrix is regular (the same solve of the right-hand side scaled
    /// down by 2^-600 is finite) but the solve left the range of doubles
    /// at `unknown`, where the solution is about 10^`log10` (a solution
    /// near 1e306 overflows in the solve's own products).
    Overflow { unknown: usize, log10: f64 },
}

impl std::fmt::Display for SolverError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolverError::Singular(m) => write!(f, "singular matrix: {m}"),
            SolverError::Usage(m) => write!(f, "linear solver misuse: {m}"),
            SolverError::LostDecimals {
                unknown,
                decimals,
                nprec,
            } => write!(
                f,
                "singular matrix: {} decimals lost at the pivot of unknown {unknown} (NPREC = {nprec})",
                fmt_decimals(*decimals)
            ),
            SolverError::NonFiniteRhs { unknown, value } => write!(
                f,
                "the right-hand side is not finite at unknown {unknown} ({value}): a load, or the matrix times the imposed values, is {OVERFLOW}"
            ),
            SolverError::Overflow { unknown, log10 } => write!(
                f,
                "the solve overflows at unknown {unknown}: the matrix is regular (the system scaled down solves, to about 1e{log10:.0} there once scaled back), but the values of this solve are {OVERFLOW}"
            ),
        }
    }
}

impl std::error::Error for SolverError {}

/// The words of a failure caused by values too large for doubles, not by
/// a singular matrix: the time loop and the commands look for them to
/// name the load instead of advising supports.
pub const OVERFLOW: &str = "beyond the range of doubles (1.8e308)";

/// "12.3", or "all" for a zero pivot.
pub fn fmt_decimals(d: f64) -> String {
    if d.is_finite() {
        format!("{d:.1}")
    } else {
        "all".into()
    }
}

/// code_aster's detection of a singular matrix by its direct solvers
/// (SOLVEUR NPREC and STOP_SINGULIER, U4.50.01): a pivot that lost NPREC
/// decimals or more against the diagonal entry of its row before the
/// factorization, |a_ii / d_i| ≥ 10^NPREC, makes the matrix singular;
/// with STOP_SINGULIER='OUI' the factorization fails, with 'NON' the
/// solution is kept (the caller emits an alarm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularityCheck {
    /// The decimals whose loss is fatal; `None`: no test.
    pub limit: Option<i64>,
    pub stop: bool,
}

impl Default for SingularityCheck {
    fn default() -> Self {
        SingularityCheck {
            limit: Some(8),
            stop: true,
        }
    }
}

impl SingularityCheck {
    /// The check of SOLVEUR's METHODE, NPREC and STOP_SINGULIER. MUMPS
    /// reads the sign of NPREC (negative: no test); MULT_FRONT and LDLT
    /// take its absolute value; 0 means the default 8 for all.
    pub fn from_solveur(methode: &str, nprec: i64, stop: bool) -> SingularityCheck {
        let limit = match nprec {
            0 => Some(8),
            p if p < 0 && methode == "MUMPS" => None,
            p => Some(p.abs()),
        };
        SingularityCheck { limit, stop }
    }
}

/// The pivot that lost the most decimals in a factorization: |d_i| / |a_ii|
/// (the pivot of LDLᵀ, L_ii² of LLᵀ, over the diagonal entry of the
/// matrix), at the unknown i of the matrix's own numbering.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorstPivot {
    pub unknown: usize,
    pub ratio: f64,
}

impl WorstPivot {
    /// Decimals lost, log10(|a_ii| / |d_i|): infinite for a zero pivot.
    pub fn decimals(&self) -> f64 {
        -self.ratio.log10()
    }

    /// Keeps the smaller ratio; a NaN ratio counts as a zero pivot.
    fn update(worst: &mut Option<WorstPivot>, unknown: usize, pivot: f64, diagonal: f64) {
        if diagonal == 0.0 {
            // No reference: a row without diagonal term (a Lagrange-like
            // unknown) has no decimals to lose.
            return;
        }
        let r = pivot.abs() / diagonal.abs();
        let r = if r.is_nan() { 0.0 } else { r };
        if worst.is_none_or(|w| r < w.ratio) {
            *worst = Some(WorstPivot { unknown, ratio: r });
        }
    }
}

/// A linear solver: factorize once, solve many right-hand sides.
pub trait LinearSolver {
    fn factorize(&mut self, a: &SparseMatrix) -> Result<(), SolverError>;
    /// Solves A x = b in place (b becomes x).
    fn solve(&self, b: &mut [f64]) -> Result<(), SolverError>;
}

/// Sparse direct solver (faer, sequential), reusing the symbolic
/// factorization and every work array as long as the pattern is the same.
///
/// A symmetric matrix (discrete contact makes code_aster symmetrise the
/// stiffness, and K + M/(βΔt²) is then positive definite in practice) is
/// factorized by Cholesky LLᵀ (faer picks simplicial or supernodal),
/// about half the work of LU; if a
/// pivot is not positive the same matrix is factorized by LU with partial
/// pivoting instead, so an indefinite or singular matrix is handled (and
/// reported) exactly as before. A non-symmetric matrix goes to LU directly.
///
/// Sequential on purpose: the matrices of these studies have a few
/// thousand unknowns at most, where faer's thread pool costs more in
/// wake-ups than the factorization itself (measured, docs/performance.md).
#[derive(Default)]
pub struct DirectLu {
    pattern: Option<Arc<CscPattern>>,
    llt: Option<LltFactor>,
    lu: Option<LuFactor>,
    /// Which factor holds the current factorization.
    current: Option<Kind>,
    mem: Option<(MemBuffer, usize)>,
    /// How many symbolic factorizations were computed (for benchmarks and
    /// the test that reuse happens).
    pub symbolic_count: usize,
    pub numeric_count: usize,
    /// Factorizations that went to LU because Cholesky met a
    /// non-positive pivot (or the matrix was not symmetric).
    pub lu_count: usize,
    /// SOLVEUR NPREC / STOP_SINGULIER.
    pub check: SingularityCheck,
    /// The pivot that lost the most decimals in the last factorization
    /// of a symmetric matrix (`None` for a non-symmetric one: faer's LU
    /// does not show its pivots).
    pub worst: Option<WorstPivot>,
    /// With STOP_SINGULIER='NON', the worst pivot over NPREC met so far
    /// (the caller's alarm).
    pub tolerated: Option<WorstPivot>,
    /// LDLᵀ factor of a symmetric matrix that Cholesky refused, computed
    /// only to read its pivots (the solve uses LU).
    ldlt_values: Vec<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Llt,
    Lu,
}

struct LltFactor {
    symbolic: SymbolicCholesky<usize>,
    /// Set when faer chose its simplicial factorization (the matrices of
    /// the axisymmetric studies): the numeric factorization is then
    /// [`SimplicialPlan::factorize`].
    plan: Option<SimplicialPlan>,
    values: Vec<f64>,
    /// The matrix factorized, for one step of iterative refinement.
    matrix: Option<SparseMatrix>,
}

struct LuFactor {
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
}

impl DirectLu {
    pub fn new() -> Self {
        Self::default()
    }

    /// A work buffer of at least `req`, kept across calls.
    fn stack(mem: &mut Option<(MemBuffer, usize)>, req: StackReq) -> &mut MemStack {
        let bytes = req.unaligned_bytes_required();
        if mem.as_ref().is_none_or(|(_, have)| *have < bytes) {
            *mem = Some((MemBuffer::new(req), bytes));
        }
        MemStack::new(&mut mem.as_mut().expect("allocated above").0)
    }

    /// The symbolic Cholesky factorization of the pattern, once.
    fn llt_symbolic(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        if self.llt.is_none() {
            let symbolic = factorize_symbolic_cholesky(
                a.pattern.symbolic(),
                Side::Lower,
                SymmetricOrdering::Amd,
                Default::default(),
            )
            .map_err(|e| SolverError::Singular(format!("symbolic factorization: {e:?}")))?;
            let values = vec![0.0; symbolic.len_val()];
            let plan = SimplicialPlan::new(&symbolic, &a.pattern);
            self.llt = Some(LltFactor {
                symbolic,
                plan,
                values,
                matrix: None,
            });
            self.symbolic_count += 1;
        }
        Ok(())
    }

    fn factorize_llt(&mut self, a: &SparseMatrix) -> Result<bool, SolverError> {
        self.llt_symbolic(a)?;
        let f = self.llt.as_mut().expect("set above");
        let ok = if let Some(plan) = &mut f.plan {
            plan.factorize(&a.values, &mut f.values)
        } else {
            let req = f
                .symbolic
                .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
                .or(f.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
            let stack = Self::stack(&mut self.mem, req);
            f.symbolic
                .factorize_numeric_llt(
                    &mut f.values,
                    a.faer(),
                    Side::Lower,
                    LltRegularization::default(),
                    Par::Seq,
                    stack,
                    Default::default(),
                )
                .is_ok()
        };
        if ok {
            match &mut f.matrix {
                Some(m) if Arc::ptr_eq(&m.pattern, &a.pattern) => {
                    m.values.copy_from_slice(&a.values)
                }
                m => *m = Some(a.clone()),
            }
        }
        Ok(ok)
    }

    fn factorize_lu(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        if self.lu.is_none() {
            let symbolic = factorize_symbolic_lu(a.pattern.symbolic(), Default::default())
                .map_err(|e| SolverError::Singular(format!("symbolic factorization: {e:?}")))?;
            self.lu = Some(LuFactor {
                symbolic,
                numeric: NumericLu::new(),
            });
            self.symbolic_count += 1;
        }
        let f = self.lu.as_mut().expect("set above");
        let req = f
            .symbolic
            .factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default())
            .or(f.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        let stack = Self::stack(&mut self.mem, req);
        f.symbolic
            .factorize_numeric_lu(
                &mut f.numeric,
                a.faer(),
                Par::Seq,
                stack,
                Default::default(),
            )
            .map_err(|e| SolverError::Singular(format!("numeric factorization: {e:?}")))?;
        self.lu_count += 1;
        Ok(())
    }
}

impl DirectLu {
    /// The pivots of the LLᵀ factor just computed, L_kk².
    fn llt_pivots(&self, a: &SparseMatrix) -> Option<WorstPivot> {
        let f = self.llt.as_ref()?;
        worst_pivot(&f.symbolic, &f.values, a, |l| l * l)
    }

    /// The pivots D_kk of the LDLᵀ factorization of `a` (symmetric), in
    /// a buffer of its own: the factor that solves is not touched.
    fn ldlt_pivots(&mut self, a: &SparseMatrix) -> Result<Option<WorstPivot>, SolverError> {
        self.llt_symbolic(a)?;
        let f = self.llt.as_ref().expect("set above");
        self.ldlt_values.resize(f.symbolic.len_val(), 0.0);
        let req = f
            .symbolic
            .factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default());
        let stack = Self::stack(&mut self.mem, req);
        let done = f.symbolic.factorize_numeric_ldlt(
            &mut self.ldlt_values,
            a.faer(),
            Side::Lower,
            LdltRegularization::default(),
            Par::Seq,
            stack,
            Default::default(),
        );
        Ok(match done {
            Ok(_) => worst_pivot(&f.symbolic, &self.ldlt_values, a, |d| d),
            // faer counts this pivot from 1 (the pivots done before it).
            Err(LdltError::ZeroPivot { index }) => {
                let k = index.saturating_sub(1).min(a.n().saturating_sub(1));
                Some(WorstPivot {
                    unknown: f.symbolic.perm().map_or(k, |p| p.arrays().0[k]),
                    ratio: 0.0,
                })
            }
        })
    }

    /// Applies the singularity check to the factorization just made.
    fn judge(&mut self) -> Result<(), SolverError> {
        let Some(w) = self.worst else {
            return Ok(());
        };
        let Some(limit) = self.check.limit else {
            return Ok(());
        };
        if w.ratio > 10f64.powi(-(limit.min(400) as i32)) {
            return Ok(());
        }
        if self.check.stop {
            self.current = None;
            return Err(SolverError::LostDecimals {
                unknown: w.unknown,
                decimals: w.decimals(),
                nprec: limit,
            });
        }
        if self.tolerated.is_none_or(|t| w.ratio < t.ratio) {
            self.tolerated = Some(w);
        }
        Ok(())
    }
}

/// The pivot of a Cholesky-shaped factor (`values` laid out by
/// `symbolic`, diagonal entry l of each column turned into the pivot by
/// `pivot`) that lost the most decimals against the diagonal of `a`,
/// named in `a`'s numbering (faer's permutation: the k-th pivot is the
/// unknown fwd[k]).
fn worst_pivot(
    symbolic: &SymbolicCholesky<usize>,
    values: &[f64],
    a: &SparseMatrix,
    pivot: impl Fn(f64) -> f64,
) -> Option<WorstPivot> {
    let fwd = symbolic.perm().map(|p| p.arrays().0);
    let unknown = |k: usize| fwd.map_or(k, |f| f[k]);
    let diag = &a.pattern.diagonal;
    let mut worst = None;
    let mut see = |k: usize, l: f64| {
        let i = unknown(k);
        WorstPivot::update(&mut worst, i, pivot(l), a.values[diag[i]]);
    };
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            // Column k of L starts with its diagonal entry.
            let cp = s.col_ptr();
            for k in 0..a.n() {
                see(k, values[cp[k]]);
            }
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let l = SupernodalLltRef::new(s, values);
            for q in 0..s.n_supernodes() {
                let node = l.supernode(q);
                let (start, m) = (node.start(), node.val());
                for j in 0..m.ncols() {
                    see(start + j, m[(j, j)]);
                }
            }
        }
    }
    worst
}

/// faer's simplicial up-looking LLᵀ (`factorize_simplicial_numeric_llt`,
/// which faer's `factorize_numeric_llt` runs on its permuted upper
/// triangle), replayed with everything that depends only on the pattern
/// computed once per pattern instead of at every factorization: the
/// permutation of the matrix (here a map from its entries to ours) and the
/// elimination reach of every row (the order in which the columns of L
/// update row k, with the position of each L(k, j)). The arithmetic is
/// faer's, operation for operation and in the same order, so the factor is
/// the same to the last bit; faer's own solve then reads it.
struct SimplicialPlan {
    /// Column k of the permuted upper triangle: rows `a_row[e]`, values
    /// `a[a_src[e]]`, for e in `a_ptr[k]..a_ptr[k + 1]`.
    a_ptr: Vec<usize>,
    a_row: Vec<usize>,
    a_src: Vec<usize>,
    /// faer's structure of L (column-major, diagonal first).
    l_ptr: Vec<usize>,
    l_row: Vec<usize>,
    /// Reach of row k, in faer's order, cut into runs: run q (for q in
    /// `run_ptr[k]..run_ptr[k + 1]`) is the `run_len[q]` consecutive
    /// columns from `run_col[q]`, a chain of the elimination tree with
    /// nested structures (a piece of a supernode), and `run_cnt[q]` rows
    /// of their common structure lie between them and k. A single column
    /// is a run of one.
    run_ptr: Vec<usize>,
    run_col: Vec<u32>,
    run_len: Vec<u8>,
    run_cnt: Vec<u32>,
    /// 1 / L(j, j), set when column j is finished.
    inv_diag: Vec<f64>,
    /// Dense work row, all zeros between calls.
    x: Vec<f64>,
}

/// The longest run of columns the factorization fuses.
const MAX_RUN: usize = 16;

impl SimplicialPlan {
    /// `None` when faer chose a supernodal factorization or no ordering.
    fn new(symbolic: &SymbolicCholesky<usize>, pattern: &CscPattern) -> Option<SimplicialPlan> {
        let SymbolicCholeskyRaw::Simplicial(simp) = symbolic.raw() else {
            return None;
        };
        let perm = symbolic.perm()?;
        let n = pattern.n;
        let nnz = pattern.nnz();
        // Permute the entry numbers exactly as faer permutes the values:
        // the result says which of our entries lands where.
        let ids: Vec<f64> = (0..nnz).map(|k| k as f64).collect();
        let mut new_val = vec![0.0; nnz];
        let mut new_ptr = vec![0usize; n + 1];
        let mut new_row = vec![0usize; nnz];
        let mut mem = MemBuffer::new(permute_self_adjoint_scratch::<usize>(n));
        // The result lands in new_ptr/new_row/new_val (compressed).
        permute_self_adjoint_to_unsorted(
            &mut new_val,
            &mut new_ptr,
            &mut new_row,
            SparseColMatRef::new(pattern.symbolic(), &ids),
            perm,
            Side::Lower,
            Side::Upper,
            MemStack::new(&mut mem),
        );
        let a_ptr = new_ptr;
        let a_row = new_row[..a_ptr[n]].to_vec();
        let a_src: Vec<usize> = new_val[..a_ptr[n]].iter().map(|&v| v as usize).collect();
        let l_ptr = simp.col_ptr().to_vec();
        let l_row = simp.row_idx().to_vec();
        // The elimination tree: the parent of j is the first row below the
        // diagonal in column j of L.
        let parent: Vec<usize> = (0..n)
            .map(|j| {
                if l_ptr[j + 1] - l_ptr[j] > 1 {
                    l_row[l_ptr[j] + 1]
                } else {
                    usize::MAX
                }
            })
            .collect();
        // faer's `ereach`, row by row.
        let mut visited = vec![usize::MAX; n];
        let mut stack = vec![0usize; n];
        let mut next = l_ptr[..n].to_vec();
        let mut r_ptr = Vec::with_capacity(n + 1);
        let mut r_col = Vec::new();
        let mut r_pos = Vec::new();
        r_ptr.push(0);
        for k in 0..n {
            let mut top = n;
            visited[k] = k;
            for &i0 in &a_row[a_ptr[k]..a_ptr[k + 1]] {
                if i0 >= k {
                    continue;
                }
                let mut i = i0;
                let mut len = 0;
                while visited[i] != k {
                    stack[len] = i;
                    len += 1;
                    visited[i] = k;
                    i = parent[i];
                }
                stack.copy_within(..len, top - len);
                top -= len;
            }
            for &j in &stack[top..] {
                next[j] += 1;
                if l_row.get(next[j]) != Some(&k) {
                    return None;
                }
                r_col.push(j);
                r_pos.push(next[j]);
            }
            r_ptr.push(r_col.len());
        }
        // Column c and c + 1 chain when c + 1 is the parent of c and the
        // structure of c is that of c + 1 plus c itself.
        let chains = |c: usize| {
            c + 1 < n
                && parent[c] == c + 1
                && l_ptr[c + 1] - l_ptr[c] == l_ptr[c + 2] - l_ptr[c + 1] + 1
        };
        let mut run_ptr = Vec::with_capacity(n + 1);
        let (mut run_col, mut run_len, mut run_cnt) = (Vec::new(), Vec::new(), Vec::new());
        run_ptr.push(0);
        for k in 0..n {
            let reach = r_ptr[k]..r_ptr[k + 1];
            let mut t = reach.start;
            while t < reach.end {
                let j = r_col[t];
                let mut m = 1;
                while t + m < reach.end && m < MAX_RUN && r_col[t + m] == j + m && chains(j + m - 1)
                {
                    m += 1;
                }
                // k's position in each column of the run, as the fused
                // loop computes it, must be the one the reach found.
                let last = j + m - 1;
                let cnt = r_pos[t + m - 1] - l_ptr[last] - 1;
                if (0..m).any(|a| r_pos[t + a] != l_ptr[j + a] + m - a + cnt) {
                    return None;
                }
                run_col.push(u32::try_from(j).ok()?);
                run_len.push(m as u8);
                run_cnt.push(u32::try_from(cnt).ok()?);
                t += m;
            }
            run_ptr.push(run_col.len());
        }
        Some(SimplicialPlan {
            a_ptr,
            a_row,
            a_src,
            l_ptr,
            l_row,
            run_ptr,
            run_col,
            run_len,
            run_cnt,
            inv_diag: vec![0.0; n],
            x: vec![0.0; n],
        })
    }

    /// The numeric factorization of `a` (values on the plan's pattern)
    /// into `l`; false on a pivot that is not positive.
    ///
    /// faer's loop updates the work row column by column of the reach:
    /// x(i) -= L(i, j) L(k, j) for the rows i of column j above k. A run
    /// of chained columns j..j+m shares its rows below the run, so those
    /// rows are read and written once per run, each receiving the same
    /// subtractions in the same order (column j first); the rows inside
    /// the run (the triangle) are updated column by column as before.
    /// Every value is therefore the same to the bit.
    fn factorize(&mut self, a: &[f64], l: &mut [f64]) -> bool {
        let n = self.x.len();
        let x = &mut self.x;
        let (l_ptr, l_row, inv) = (&self.l_ptr, &self.l_row, &mut self.inv_diag);
        for k in 0..n {
            for e in self.a_ptr[k]..self.a_ptr[k + 1] {
                x[self.a_row[e]] += a[self.a_src[e]];
            }
            let mut d = x[k];
            x[k] = 0.0;
            for q in self.run_ptr[k]..self.run_ptr[k + 1] {
                let j = self.run_col[q] as usize;
                let m = self.run_len[q] as usize;
                let cnt = self.run_cnt[q] as usize;
                let mut lk = [0.0; MAX_RUN];
                let mut base = [0usize; MAX_RUN];
                for a in 0..m {
                    let c = j + a;
                    let cs = l_ptr[c];
                    let lkc = x[c] * inv[c];
                    x[c] = 0.0;
                    // The triangle: rows c + 1 .. j + m of column c.
                    let tri = &l[cs + 1..cs + m - a];
                    for (xv, &lv) in x[c + 1..j + m].iter_mut().zip(tri) {
                        *xv -= lv * lkc;
                    }
                    d -= lkc * lkc;
                    base[a] = cs + m - a;
                    l[base[a] + cnt] = lkc;
                    lk[a] = lkc;
                }
                let rows = &l_row[base[m - 1]..base[m - 1] + cnt];
                // Blocks of up to four columns, in column order: each row
                // still sees column j first.
                let col = |a: usize| &l[base[a]..base[a] + cnt];
                let mut a = 0;
                while a < m {
                    match m - a {
                        1 => {
                            let (l0, k0) = (col(a), lk[a]);
                            for (&r, &v0) in rows.iter().zip(l0) {
                                x[r] -= v0 * k0;
                            }
                            a += 1;
                        }
                        2 => {
                            let (l0, k0) = (col(a), lk[a]);
                            let (l1, k1) = (col(a + 1), lk[a + 1]);
                            for ((&r, &v0), &v1) in rows.iter().zip(l0).zip(l1) {
                                x[r] = (x[r] - v0 * k0) - v1 * k1;
                            }
                            a += 2;
                        }
                        3 => {
                            let (l0, k0) = (col(a), lk[a]);
                            let (l1, k1) = (col(a + 1), lk[a + 1]);
                            let (l2, k2) = (col(a + 2), lk[a + 2]);
                            for (((&r, &v0), &v1), &v2) in rows.iter().zip(l0).zip(l1).zip(l2) {
                                x[r] = ((x[r] - v0 * k0) - v1 * k1) - v2 * k2;
                            }
                            a += 3;
                        }
                        _ => {
                            let (l0, k0) = (col(a), lk[a]);
                            let (l1, k1) = (col(a + 1), lk[a + 1]);
                            let (l2, k2) = (col(a + 2), lk[a + 2]);
                            let (l3, k3) = (col(a + 3), lk[a + 3]);
                            for ((((&r, &v0), &v1), &v2), &v3) in
                                rows.iter().zip(l0).zip(l1).zip(l2).zip(l3)
                            {
                                x[r] = (((x[r] - v0 * k0) - v1 * k1) - v2 * k2) - v3 * k3;
                            }
                            a += 4;
                        }
                    }
                }
            }
            // `!(d > 0)`: NaN is not a positive pivot either.
            if d.is_nan() || d <= 0.0 {
                x.iter_mut().for_each(|v| *v = 0.0);
                return false;
            }
            let lkk = d.sqrt();
            l[l_ptr[k]] = lkk;
            inv[k] = 1.0 / lkk;
        }
        true
    }
}

impl LinearSolver for DirectLu {
    fn factorize(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        let _factor = crate::profile::span(crate::profile::Phase::FactorSolve);
        if let Some(v) = a.values.iter().find(|v| !v.is_finite()) {
            return Err(SolverError::Singular(format!(
                "the matrix holds a non-finite value ({v})"
            )));
        }
        if !matches!(&self.pattern, Some(p) if Arc::ptr_eq(p, &a.pattern)) {
            // A new pattern object, often equal to the one factorised
            // (a contact pairing that couples the same dofs): keep the
            // symbolic factorization then, and hold the new object so that
            // the next calls compare pointers, not patterns.
            let same = matches!(&self.pattern, Some(p) if **p == *a.pattern);
            self.pattern = Some(a.pattern.clone());
            if !same {
                self.llt = None;
                self.lu = None;
            }
        }
        self.current = None;
        self.numeric_count += 1;
        // Symmetric up to round-off (the contact tangent is summed in a
        // different order for (i, j) and (j, i)): Cholesky reads the lower
        // triangle, a relative perturbation of 1e-12 at most.
        let symmetric = a.is_symmetric_within(1e-12);
        if symmetric && self.factorize_llt(a)? {
            self.current = Some(Kind::Llt);
            self.worst = self.llt_pivots(a);
            return self.judge();
        }
        // Cholesky refused a pivot, or the matrix is symmetric but for
        // round-off on entries that should be zero (a few 1e-16 of the
        // largest: HEXS20's stiffness) and LU solves it: the LDLᵀ of the
        // same ordering (the factorization of code_aster's MULT_FRONT and
        // LDLT, which takes negative pivots) gives the pivots to judge.
        // A truly non-symmetric matrix (friction) is not judged: faer's LU
        // does not show its pivots.
        // A row with a zero diagonal entry (the contact multipliers of
        // CONTINUE: a saddle point) is not judged either: LDLᵀ without
        // pivoting meets a zero pivot there in faer's ordering, which
        // says nothing about the matrix (code_aster orders its Lagrange
        // rows around the constrained dofs for that reason).
        let zero_diagonal = a.pattern.diagonal.iter().any(|&k| a.values[k] == 0.0);
        self.worst = if !zero_diagonal && (symmetric || a.is_symmetric_to_scale(1e-12)) {
            self.ldlt_pivots(a)?
        } else {
            None
        };
        self.factorize_lu(a)?;
        self.current = Some(Kind::Lu);
        self.judge()
    }

    fn solve(&self, b: &mut [f64]) -> Result<(), SolverError> {
        let _solve = crate::profile::span(crate::profile::Phase::FactorSolve);
        let kind = self
            .current
            .ok_or_else(|| SolverError::Usage("solve called before factorize".into()))?;
        let n = self.pattern.as_ref().map(|p| p.n).unwrap_or(0);
        if b.len() != n {
            return Err(SolverError::Usage(format!(
                "right-hand side of length {} for a matrix of order {n}",
                b.len()
            )));
        }
        if let Some(i) = b.iter().position(|v| !v.is_finite()) {
            return Err(SolverError::NonFiniteRhs {
                unknown: i,
                value: b[i],
            });
        }
        let input = b.to_vec();
        self.solve_with(kind, b);
        // A zero pivot does not stop faer: it shows up as inf/NaN here
        // (and NaN compares false, so check explicitly).
        if let Some(i) = b.iter().position(|v| !v.is_finite()) {
            // By linearity the solution of b·2^-600 is x·2^-600: finite
            // there, the matrix is regular and x only exceeds the range
            // of doubles (a load of 1e308), which is no singularity.
            const DOWN: i32 = -600;
            let mut scaled: Vec<f64> = input.iter().map(|v| v * 2f64.powi(DOWN)).collect();
            self.solve_with(kind, &mut scaled);
            if scaled.iter().all(|v| v.is_finite()) {
                return Err(SolverError::Overflow {
                    unknown: i,
                    log10: scaled[i].abs().log10() - f64::from(DOWN) * std::f64::consts::LOG10_2,
                });
            }
            return Err(SolverError::Singular(format!(
                "the solution is not finite at unknown {i}"
            )));
        }
        Ok(())
    }
}

impl DirectLu {
    /// The solve of the current factorization (`kind`) in place, without
    /// checks: `b` has the matrix's order.
    fn solve_with(&self, kind: Kind, b: &mut [f64]) {
        let n = b.len();
        // `solve` takes &self, so its (small, O(n)) work buffer is local.
        // The right-hand side, kept for the refinement of a Cholesky solve.
        let b0 = (kind == Kind::Llt).then(|| b.to_vec());
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        match kind {
            Kind::Llt => {
                let f = self.llt.as_ref().expect("current is Llt");
                let req = f.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq);
                let mut mem = MemBuffer::new(req);
                let llt = LltRef::new(&f.symbolic, &f.values);
                llt.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut mem));
                // One step of iterative refinement against the full matrix:
                // without pivoting, the penalty rows (E_N ~ 1e10 next to
                // mass terms ~ 1e3) leave Cholesky's solution a few digits
                // short of LU's, enough to stall Newton near 1e-8.
                if let (Some(m), Some(b0)) = (&f.matrix, &b0) {
                    let mut r = vec![0.0; n];
                    m.mul_vec(b, &mut r);
                    for (ri, bi) in r.iter_mut().zip(b0) {
                        *ri = bi - *ri;
                    }
                    let dr = MatMut::from_column_major_slice_mut(&mut r, n, 1);
                    llt.solve_in_place_with_conj(Conj::No, dr, Par::Seq, MemStack::new(&mut mem));
                    for (x, d) in b.iter_mut().zip(&r) {
                        *x += d;
                    }
                }
            }
            Kind::Lu => {
                let f = self.lu.as_ref().expect("current is Lu");
                let req = f.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq);
                let mut mem = MemBuffer::new(req);
                // Both halves live in the same LuFactor, filled together.
                let lu = LuRef::new_unchecked(&f.symbolic, &f.numeric);
                lu.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut mem));
            }
        }
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
        s.check.limit = None;
        let r = s.factorize(&m).and_then(|_| s.solve(&mut [1.0, 1.0]));
        assert!(matches!(r, Err(SolverError::Singular(_))), "{r:?}");
        // With the check (the default), the factorization itself refuses it.
        let mut s = DirectLu::new();
        let r = s.factorize(&m);
        assert!(
            matches!(r, Err(SolverError::LostDecimals { nprec: 8, .. })),
            "{r:?}"
        );
    }

    /// A regular matrix with a solution too large for doubles is no
    /// singular matrix: 1e-10 x = 1e308 gives x = 1e318, an overflow whose
    /// magnitude the scaled solve recovers; an infinite entry of b is the
    /// right-hand side's fault, and the same factor still solves a
    /// finite b ([[2, -1], [-1, 2]] x = (1, 0): x = (2/3, 1/3)).
    #[test]
    fn overflow_and_non_finite_right_hand_side_are_not_singular() {
        let mut s = DirectLu::new();
        s.factorize(&build(&[vec![1e-10]])).unwrap();
        let r = s.solve(&mut [1e308]);
        let Err(SolverError::Overflow { unknown: 0, log10 }) = r else {
            panic!("{r:?}");
        };
        // 1e308 / 1e-10 = 1e318, to the rounding of the scaling.
        assert!((log10 - 318.0).abs() < 1e-9, "{log10}");
        let mut s = DirectLu::new();
        s.factorize(&build(&[vec![2.0, -1.0], vec![-1.0, 2.0]]))
            .unwrap();
        let r = s.solve(&mut [f64::INFINITY, 0.0]);
        assert!(
            matches!(r, Err(SolverError::NonFiniteRhs { unknown: 0, value }) if value == f64::INFINITY),
            "{r:?}"
        );
        let mut x = [1.0, 0.0];
        s.solve(&mut x).unwrap();
        assert!((x[0] - 2.0 / 3.0).abs() < 1e-15 && (x[1] - 1.0 / 3.0).abs() < 1e-15);
        let text = SolverError::Overflow {
            unknown: 0,
            log10: 318.0,
        }
        .to_string();
        assert!(
            text.contains(OVERFLOW) && !text.contains("singular"),
            "{text}"
        );
    }

    /// The pivot ratio against a hand LDLᵀ: in [[4, 2, 0], [2, 3, 0], [0,
    /// 0, ±7]] the 2 x 2 block has pivots (4, 3 − 1) or (3, 4 − 4/3)
    /// whichever unknown comes first, a worst ratio 2/3 either way (the
    /// unknown 1, resp. 0); the third pivot is its diagonal. With +7 it
    /// is Cholesky's L_kk², with −7 Cholesky fails and LDLᵀ gives it.
    #[test]
    fn pivot_ratio_matches_a_hand_factorization() {
        for (d, lu) in [(7.0, 0), (-7.0, 1)] {
            let a = vec![vec![4.0, 2.0, 0.0], vec![2.0, 3.0, 0.0], vec![0.0, 0.0, d]];
            let mut s = DirectLu::new();
            s.factorize(&build(&a)).unwrap();
            assert_eq!(s.lu_count, lu);
            let w = s.worst.expect("a symmetric matrix is judged");
            assert!((w.ratio - 2.0 / 3.0).abs() < 1e-15, "{w:?}");
            assert!(w.unknown < 2, "{w:?}");
        }
    }

    /// A zero-energy mode of unknowns 2 and 3 (a free spring pair) in an
    /// otherwise stiff matrix: the pivot at one of them vanishes (exactly
    /// or to round-off), over any NPREC; the check names that unknown,
    /// through faer's permutation. STOP_SINGULIER='NON' keeps the
    /// factorization and records the pivot; NPREC < 0 (MUMPS) skips it.
    #[test]
    fn zero_energy_mode_loses_every_decimal_at_its_unknown() {
        let a = vec![
            vec![5.0, -1.0, 0.0, 0.0],
            vec![-1.0, 5.0, 0.0, 0.0],
            vec![0.0, 0.0, 3.0, -3.0],
            vec![0.0, 0.0, -3.0, 3.0],
        ];
        let m = build(&a);
        let mut s = DirectLu::new();
        match s.factorize(&m) {
            Err(SolverError::LostDecimals {
                unknown, decimals, ..
            }) => {
                assert!(unknown == 2 || unknown == 3, "{unknown}");
                assert!(decimals > 14.0, "{decimals}");
            }
            r => panic!("{r:?}"),
        }
        assert!(s.solve(&mut [1.0; 4]).is_err(), "no factor after a refusal");
        s.check = SingularityCheck::from_solveur("MUMPS", 8, false);
        s.factorize(&m).unwrap();
        assert!(s.tolerated.is_some_and(|w| w.unknown >= 2));
        let mut s = DirectLu::new();
        s.check = SingularityCheck::from_solveur("MUMPS", -1, true);
        s.factorize(&m).unwrap();
        assert!(s.tolerated.is_none());
    }

    #[test]
    fn nprec_is_read_as_each_method_reads_it() {
        let c = SingularityCheck::from_solveur;
        assert_eq!(c("MUMPS", -1, true).limit, None);
        assert_eq!(c("MULT_FRONT", -6, true).limit, Some(6));
        assert_eq!(c("LDLT", 0, true).limit, Some(8));
        assert_eq!(c("MUMPS", 0, true).limit, Some(8));
        assert_eq!(
            c("MUMPS", 12, false),
            SingularityCheck {
                limit: Some(12),
                stop: false
            }
        );
    }

    /// A symmetric matrix whose zero entries carry round-off of opposite
    /// signs (1e-16 of the diagonal) goes to LU, but is still judged by
    /// LDLᵀ; a truly non-symmetric one is not.
    #[test]
    fn round_off_asymmetry_is_judged_a_true_one_is_not() {
        let mut a = vec![
            vec![5.0, -1.0, 1e-16, 0.0],
            vec![-1.0, 5.0, 0.0, 0.0],
            vec![-1e-16, 0.0, 3.0, -3.0],
            vec![0.0, 0.0, -3.0, 3.0],
        ];
        let mut s = DirectLu::new();
        let r = s.factorize(&build(&a));
        assert!(matches!(r, Err(SolverError::LostDecimals { .. })), "{r:?}");
        assert_eq!(s.lu_count, 1);
        a[0][1] = -2.0;
        let mut s = DirectLu::new();
        s.factorize(&build(&a)).unwrap();
        assert_eq!(s.worst, None);
    }

    #[test]
    fn symmetric_positive_matrix_uses_cholesky_and_indefinite_falls_back_to_lu() {
        let spd = vec![
            vec![4.0, -1.0, 0.0],
            vec![-1.0, 4.0, -1.0],
            vec![0.0, -1.0, 4.0],
        ];
        // Same pattern as `spd`; the second pivot of LLᵀ is 1 − 4 < 0.
        let indefinite = vec![
            vec![1.0, 2.0, 0.0],
            vec![2.0, 1.0, -1.0],
            vec![0.0, -1.0, -3.0],
        ];
        let b = [1.0, -2.0, 0.5];
        let mut s = DirectLu::new();
        for (a, lu_after) in [(&spd, 0), (&indefinite, 1)] {
            let m = build(a);
            s.factorize(&m).unwrap();
            assert_eq!(s.lu_count, lu_after);
            let mut x = b.to_vec();
            s.solve(&mut x).unwrap();
            let xd = dense_solve(a, &b);
            for (u, v) in x.iter().zip(&xd) {
                assert!((u - v).abs() < 1e-12, "{x:?} vs {xd:?}");
            }
        }
        // One pattern: one symbolic Cholesky, then one symbolic LU.
        assert_eq!(s.symbolic_count, 2);
    }

    /// An SPD matrix on a 14 x 14 grid (9-point couplings, values varied
    /// so that every entry's rounding matters), the pattern symmetric,
    /// with `d` coupled unknowns per grid node (as the two or three
    /// displacements of a mesh node: chains of columns appear).
    fn grid_spd_dofs(d: usize) -> SparseMatrix {
        let m = 14;
        let n = m * m * d;
        let mut entries = Vec::new();
        for i in 0..m {
            for j in 0..m {
                for (di, dj) in [(0i64, 0i64), (0, 1), (1, 0), (1, 1), (1, -1)] {
                    let (i2, j2) = (i as i64 + di, j as i64 + dj);
                    if i2 < m as i64 && j2 >= 0 && j2 < m as i64 {
                        let (a, b) = (i * m + j, (i2 * m as i64 + j2) as usize);
                        for (p, q) in (0..d).flat_map(|p| (0..d).map(move |q| (p, q))) {
                            entries.push((a * d + p, b * d + q));
                            entries.push((b * d + q, a * d + p));
                        }
                    }
                }
            }
        }
        let mut a = SparseMatrix::zeros(Arc::new(CscPattern::from_entries(n, entries)));
        let p = a.pattern.clone();
        for j in 0..n {
            for k in p.col_ptr[j]..p.col_ptr[j + 1] {
                let i = p.row_idx[k];
                let (lo, hi) = (i.min(j) as f64, i.max(j) as f64);
                a.values[k] = if i == j {
                    9.0 * d as f64 + (0.37 * lo).sin()
                } else {
                    -0.5 - 0.3 * (0.11 * lo + 0.07 * hi).cos()
                };
            }
        }
        a
    }

    #[test]
    fn simplicial_plan_gives_faers_factor_to_the_bit() {
        for d in [1, 2, 3] {
            plan_matches_faer(grid_spd_dofs(d), d);
        }
    }

    fn plan_matches_faer(a: SparseMatrix, d: usize) {
        let symbolic = factorize_symbolic_cholesky(
            a.pattern.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .unwrap();
        let mut plan = SimplicialPlan::new(&symbolic, &a.pattern)
            .expect("faer is simplicial on this matrix, so the plan applies");
        // With several unknowns per node the fused runs are exercised,
        // including those longer than one block of four columns.
        let longest = plan.run_len.iter().copied().max().unwrap_or(0);
        assert!(d == 1 || longest > 4, "d = {d}: longest run {longest}");
        let mut ours = vec![0.0; symbolic.len_val()];
        assert!(plan.factorize(&a.values, &mut ours));
        let mut theirs = vec![0.0; symbolic.len_val()];
        let req = symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default());
        let mut mem = MemBuffer::new(req);
        symbolic
            .factorize_numeric_llt(
                &mut theirs,
                a.faer(),
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .unwrap();
        assert!(ours
            .iter()
            .zip(&theirs)
            .all(|(x, y)| x.to_bits() == y.to_bits()));
        // A matrix that is not positive definite is refused, and the work
        // row is left clean for the next call.
        let mut bad = a.clone();
        bad.values.iter_mut().for_each(|v| *v = -*v);
        assert!(!plan.factorize(&bad.values, &mut ours));
        assert!(plan.factorize(&a.values, &mut ours));
        assert!(ours
            .iter()
            .zip(&theirs)
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    }

    #[test]
    fn symmetrize_averages_off_diagonal_pairs() {
        let mut m = build(&[vec![1.0, 2.0], vec![4.0, 1.0]]);
        m.symmetrize();
        assert_eq!((m.get(0, 1), m.get(1, 0)), (3.0, 3.0));
    }
}
