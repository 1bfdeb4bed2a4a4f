//! The element loop and the assembly into fixed-pattern global arrays.
//!
//! Everything that depends only on the mesh is computed once per
//! computation: the element list with its dof maps, the sparsity pattern of
//! the free equations, each element entry's position in that pattern, and
//! the consistent mass. Each Newton iteration then runs the element
//! integrations in parallel (rayon; each element is independent and pure)
//! and scatters them sequentially into arrays allocated once, so the
//! global vectors and matrices never reallocate.

use std::sync::Arc;

use rayon::prelude::*;

use super::behaviour::{BehaviourField, CellLaw};
use super::dofs::{DofNumbering, NONE};
use super::team::{Parts, Team};
use crate::element::{
    initial_states, internal_forces_to, mass, ElementBuffers, ElementFailure, Kinematics,
    PointState,
};
use crate::law::TangentKind;
use crate::mesh::Mesh;
use crate::model::spec::ElementSpec;
use crate::model::{CellRole, Model};
use crate::solver::{CscPattern, SparseMatrix};

/// Element count from which the element loop runs on the thread pool
/// (when it has more than one thread): on B (101 quadratic elements,
/// about 4 µs each with the tangent) a loop costs a wake-up of the other
/// thread, small against the half loop it saves (docs/performance.md).
/// Below, the loop is too short to share.
pub const PARALLEL_MIN_ELEMENTS: usize = 32;

/// The fewest elements rayon hands out as one piece of the loop. Rayon
/// splits a range in halves while each half keeps at least this many, and
/// splits again the pieces a thread takes from another, so a thread that
/// wakes late still takes its share of what is left. (The block was the
/// rounded-up share of each thread, 51 of B's 101 elements: no half could
/// hold that many, rayon never split, and the loop ran on one thread.)
const PARALLEL_MIN_BLOCK: usize = 8;

/// One element of the model with its precomputed maps.
#[derive(Debug, Clone)]
pub struct ElementData {
    pub cell: usize,
    pub spec: ElementSpec,
    pub kin: Kinematics,
    /// Index into [`Assembler::laws`].
    pub law: usize,
    pub coords: Vec<[f64; 3]>,
    /// Full dof index of each local dof (node-major).
    pub full: Vec<usize>,
    /// Position in the free pattern of local entry (a, b) at `a·ndof + b`,
    /// [`NONE`] when a or b is not free.
    pub pos: Vec<usize>,
    /// First Gauss-point state of the element in the flat state arrays.
    pub state_offset: usize,
    pub npg: usize,
}

/// The folds a run meets (element::fold: a cell whose Jacobian at a node
/// is not positive while its Gauss points are), as (cell, mesh node,
/// det F). They are alarms, not failures: code_aster computes on (it
/// checks the Gauss points only), and a distorted corner that folds a
/// little and stays so is what SDNV103 A's HEXS20 impact face does (its
/// explicit run meets folds from 5 us and det F = -1 at one node by
/// 28 us) where an under-integrated AXIS_SI bar at twice the speed goes on
/// to det F = -6 with its nodes thrown off. The first fold is an alarm
/// when met; the deepest is said at the end.
#[derive(Debug, Default)]
pub struct FoldWatch {
    seen: usize,
    deepest: Option<(f64, (usize, usize, f64))>,
}

impl FoldWatch {
    /// Takes the deepest fold of the state at instant `t`, if any.
    pub fn see(&mut self, t: f64, fold: Option<(usize, usize, f64)>, log: &mut dyn FnMut(&str)) {
        let Some(f) = fold else { return };
        if self.seen == 0 {
            log(&format!(
                "  alarm: at t = {t:e} cell M{} folds at its node N{}: det F = {:.3e} there while its Gauss points stay positive (a distorted corner, or the spurious mode of an under-integrated cell the Gauss points do not see: the mesh is tangling there); the computation goes on, the deepest fold is given at the end",
                f.0 + 1,
                f.1 + 1,
                f.2
            ));
        }
        self.seen += 1;
        if self.deepest.is_none_or(|(_, (_, _, d))| f.2 < d) {
            self.deepest = Some((t, f));
        }
    }

    /// The closing alarm: how many checked states had a fold, and the
    /// deepest one.
    pub fn summary(&self) -> Option<String> {
        let (t, (cell, node, det_f)) = self.deepest?;
        Some(format!(
            "  alarm: {} checked states had a folded cell; the deepest fold: det F = {det_f:.3e} at node N{} of cell M{} at t = {t:e}",
            self.seen,
            node + 1,
            cell + 1
        ))
    }
}

/// An element failure with the mesh cell where it happened.
#[derive(Debug, Clone, PartialEq)]
pub struct CellFailure {
    pub cell: usize,
    pub failure: ElementFailure,
}

pub struct Assembler {
    pub numbering: DofNumbering,
    pub elements: Vec<ElementData>,
    pub laws: Vec<CellLaw>,
    /// Pattern of the free equations (stiffness and iteration matrix).
    pub pattern: Arc<CscPattern>,
    /// The mass restricted to the free equations, aligned with `pattern`.
    pub mass_free: Vec<f64>,
    /// The mass on all full dofs (inertia forces, reactions, REAC_NODA).
    pub mass_full: SparseMatrix,
    /// Total number of Gauss-point states.
    pub nstates: usize,
    /// Offset of each mesh cell's states (cells without element: empty
    /// range), `ncells + 1` entries.
    pub cell_state_offsets: Vec<usize>,
    /// Extra free entries beyond the elements' (sorted, unique).
    extra: Vec<(usize, usize)>,
    /// One output buffer per element, reused by every evaluation.
    buffers: Vec<ElementBuffers>,
    results: Vec<Result<(), ElementFailure>>,
    /// Which elements [`Assembler::tangent_action_on`] integrated (its
    /// buffer, kept between calls).
    tangent_done: Vec<Result<bool, CellFailure>>,
    /// For each full dof, the positions in `flat_forces` of the element
    /// terms that add to it, in element order (`gather_ptr` its CSR
    /// offsets): the forces are assembled dof by dof (`assemble_forces`),
    /// each dof's sum in the order of the element loop's scatter. Built by
    /// `prepare_gather`.
    gather_ptr: Vec<usize>,
    gather_src: Vec<u32>,
    /// Every element's forces of the last `integrate_explicit`, one after
    /// the other in element order.
    flat_forces: Vec<f64>,
    /// The shape derivatives at the nodes of each cell type met
    /// (element::fold), and per element the index of its table with the
    /// initial det J at its nodes; `None` under PETIT, where a folded
    /// deformed mesh means nothing.
    fold_tables: Vec<crate::element::fold::NodeDerivatives>,
    fold_refs: Vec<Option<(usize, Vec<f64>)>>,
}

impl Assembler {
    /// The deepest fold of the deformed cells at the full displacement
    /// `u` (element::fold): the smallest det F at a node among the cells
    /// folded there, as (cell, mesh node, det F), None when no cell is.
    /// The Gauss points cannot see it for an under-integrated element.
    /// Elements under PETIT are not checked.
    pub fn deepest_fold(&self, u: &[f64]) -> Option<(usize, usize, f64)> {
        let d = self.numbering.ndpn;
        let mut deepest: Option<(usize, usize, f64)> = None;
        for (e, r) in self.elements.iter().zip(&self.fold_refs) {
            let Some((t, j0)) = r else { continue };
            let disp = |a: usize, k: usize| u[e.full[a * d + k]];
            if let Some((p, det_f)) =
                crate::element::fold::deepest_fold(&self.fold_tables[*t], &e.coords, j0, disp)
            {
                if deepest.is_none_or(|(_, _, m)| det_f < m) {
                    deepest = Some((e.cell, e.full[p * d] / d, det_f));
                }
            }
        }
        deepest
    }

    /// Builds the element list, the patterns and the mass. Errors are mesh
    /// errors (an inverted cell) or a negative density.
    pub fn new(
        mesh: &Mesh,
        model: &Model,
        behaviour: BehaviourField,
        numbering: DofNumbering,
    ) -> Result<Assembler, String> {
        let d = numbering.ndpn;
        let mut elements = Vec::new();
        let mut nstates = 0;
        let mut cell_state_offsets = Vec::with_capacity(mesh.ncells() + 1);
        let mut rhos = Vec::new();
        for (cell, role) in model.cells.iter().enumerate() {
            cell_state_offsets.push(nstates);
            let CellRole::Element(spec) = role else {
                continue;
            };
            let Some(b) = behaviour.cells[cell] else {
                continue;
            };
            let nodes = &mesh.cells[cell].nodes;
            let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
            let full: Vec<usize> = nodes
                .iter()
                .flat_map(|&n| (0..d).map(move |i| n * d + i))
                .collect();
            let npg = crate::element::rigi_points(spec);
            elements.push(ElementData {
                cell,
                spec: *spec,
                kin: b.kinematics,
                law: b.law,
                coords,
                full,
                pos: Vec::new(),
                state_offset: nstates,
                npg,
            });
            rhos.push(b.rho);
            nstates += npg;
        }
        cell_state_offsets.push(nstates);

        // Patterns: free equations (all couplings of an element) and full
        // dofs (mass couples equal directions only).
        let mut full_entries = Vec::new();
        for e in &elements {
            for &fa in &e.full {
                for &fb in &e.full {
                    if fa % d == fb % d {
                        full_entries.push((fa, fb));
                    }
                }
            }
        }
        let pattern = free_pattern(&numbering, &mut elements, &[]);
        let full_pattern = Arc::new(CscPattern::from_entries(numbering.nfull(), full_entries));
        // Consistent mass, on the initial geometry (ρ₀ dV₀ is conserved).
        let masses: Vec<Result<nalgebra::DMatrix<f64>, ElementFailure>> = elements
            .par_iter()
            .zip(&rhos)
            .map(|(e, &rho)| mass(&e.spec, &e.coords, rho))
            .collect();
        let mut mass_free = vec![0.0; pattern.nnz()];
        let mut mass_full = SparseMatrix::zeros(full_pattern);
        for (e, m) in elements.iter().zip(masses) {
            let m = m.map_err(|f| format!("cell M{}: mass matrix: {f}", e.cell + 1))?;
            let n = e.full.len();
            for a in 0..n {
                for b in 0..n {
                    let v = m[(a, b)];
                    if v == 0.0 {
                        continue;
                    }
                    mass_full.add(e.full[a], e.full[b], v);
                    let p = e.pos[a * n + b];
                    if p != NONE {
                        mass_free[p] += v;
                    }
                }
            }
        }
        // One buffer per element, whose coordinates never change.
        let mut buffers = vec![ElementBuffers::default(); elements.len()];
        buffers
            .iter_mut()
            .for_each(ElementBuffers::set_fixed_coordinates);
        let mut fold_tables: Vec<crate::element::fold::NodeDerivatives> = Vec::new();
        let fold_refs = elements
            .iter()
            .map(|e| {
                if e.kin == Kinematics::Petit {
                    return None;
                }
                let t = match fold_tables.iter().position(|t| t.kind == e.spec.cell) {
                    Some(t) => t,
                    None => {
                        fold_tables.push(crate::element::fold::NodeDerivatives::new(e.spec.cell));
                        fold_tables.len() - 1
                    }
                };
                Some((
                    t,
                    crate::element::fold::initial_dets(&fold_tables[t], &e.coords),
                ))
            })
            .collect();
        Ok(Assembler {
            fold_tables,
            fold_refs,
            numbering,
            elements,
            laws: behaviour.laws,
            pattern,
            mass_free,
            mass_full,
            nstates,
            cell_state_offsets,
            extra: Vec::new(),
            buffers,
            results: Vec::new(),
            tangent_done: Vec::new(),
            gather_ptr: Vec::new(),
            gather_src: Vec::new(),
            flat_forces: Vec::new(),
        })
    }

    /// Makes the free pattern hold the elements' entries plus exactly
    /// `extra` (free equation pairs, e.g. the couplings of a contact
    /// pairing). Indices at or beyond `neq` are extra unknowns of a
    /// contact term (Lagrange multipliers numbered after the equations):
    /// the pattern then grows to the largest index + 1. Returns true when the pattern was rebuilt: the caller must
    /// then reallocate its matrices on the new pattern (and the solver
    /// recomputes its symbolic factorization). Rebuilding only when the
    /// set changes keeps the symbolic factorization across steps whose
    /// pairing couples the same dofs.
    pub fn set_extra_entries(&mut self, extra: &[(usize, usize)]) -> bool {
        let mut wanted: Vec<(usize, usize)> = extra.to_vec();
        wanted.sort_unstable();
        wanted.dedup();
        if wanted == self.extra {
            return false;
        }
        let old = self.pattern.clone();
        let pattern = free_pattern(&self.numbering, &mut self.elements, &wanted);
        let mut mass_free = vec![0.0; pattern.nnz()];
        for j in 0..old.n {
            for k in old.col_ptr[j]..old.col_ptr[j + 1] {
                // The element entries are in every pattern; an old entry
                // that is not is a coupling of the previous pairing that
                // this one drops (a slave node paired to another master
                // cell), and carries no mass.
                if let Some(p) = pattern.position(old.row_idx[k], j) {
                    mass_free[p] = self.mass_free[k];
                }
            }
        }
        self.extra = wanted;
        self.pattern = pattern;
        self.mass_free = mass_free;
        true
    }

    /// Virgin Gauss-point states of every element.
    pub fn initial_states(&self) -> Vec<PointState> {
        let mut out = Vec::with_capacity(self.nstates);
        for e in &self.elements {
            out.extend(initial_states(&e.spec, self.laws[e.law].law_ref()));
        }
        out
    }

    /// Starts the Gauss points of the COMP_ELAS elements (RELATION='ELAS'
    /// with DEFORMATION='PETIT') at the stress of the displacement `u0`,
    /// σ0 = D ε(u0), leaving every other element's `states` as they are;
    /// returns how many elements were started so.
    ///
    /// code_aster's ELAS is of type COMP_ELAS unless DEFORMATION is
    /// PETIT_REAC or the initial state carries stresses (ETAT_INIT SIGM or
    /// EVOL_NOLI) [comp_meca_incr.F90, nmdata.F90]: its elements then
    /// integrate the total displacement u_n + Δu, so an initial
    /// ETAT_INIT DEPL is stressed. aster's ELAS is written incrementally
    /// (σ_n + D Δε, law/elas.rs); started at σ0 = D ε(u0) it gives the same
    /// stress D ε(u0 + Σ Δu) at every later step, to round-off, because D
    /// is constant and PETIT's B is the reference one. This keeps one law,
    /// one element path and one state format for both types (a total path
    /// would be threaded through every element family, the implicit and
    /// explicit loops and the restarts), and the stored stress of step 0 is
    /// then the one its internal forces come from. The incremental laws
    /// (VMIS_*) and ELAS/PETIT_REAC are incremental in code_aster too: u0
    /// stays stress-free for them. ELAS/GROT_GDEP is COMP_ELAS too
    /// (S = D E_GL(u), code_aster's nmelnl): started at S0 = D E_GL(u0)
    /// (stored as its Cauchy push-forward) the increments D ΔE_GL add up
    /// to D E_GL(u0 + Σ Δu) likewise. MECA_HEXS8 is left out: code_aster
    /// refuses COMP_ELAS there (checked before, `behaviour::check_hexs8`).
    pub fn start_comp_elas(
        &mut self,
        u0: &[f64],
        states: &mut [PointState],
    ) -> Result<usize, CellFailure> {
        let mut started = 0;
        for (e, buf) in self.elements.iter().zip(self.buffers.iter_mut()) {
            if !matches!(self.laws[e.law], CellLaw::Elas(_))
                || !matches!(e.kin, Kinematics::Petit | Kinematics::GrotGdep)
                || e.spec.is_hexs8()
            {
                continue;
            }
            let virgin = initial_states(&e.spec, self.laws[e.law].law_ref());
            let zeros = vec![0.0; e.full.len()];
            let lu: Vec<f64> = e.full.iter().map(|&f| u0[f]).collect();
            internal_forces_to(
                &e.spec,
                e.kin,
                &e.coords,
                &zeros,
                &lu,
                &virgin,
                self.laws[e.law].law_ref(),
                0.0,
                TangentKind::None,
                buf,
                &mut states[e.state_offset..e.state_offset + e.npg],
            )
            .map_err(|failure| CellFailure {
                cell: e.cell,
                failure,
            })?;
            started += 1;
        }
        Ok(started)
    }

    /// Internal variables count of each mesh cell's law (0 outside).
    pub fn nvari_of_cell(&self, ncells: usize) -> Vec<usize> {
        let mut out = vec![0; ncells];
        for e in &self.elements {
            out[e.cell] = self.laws[e.law].nvari();
        }
        out
    }

    /// Integrates every element for the step `u_n → u` (full vectors),
    /// writes the new states into `states_out`, the internal forces into
    /// `fint` (full, overwritten) and, when `stiffness` is given, the
    /// assembled tangent of the free equations into it (overwritten).
    #[allow(clippy::too_many_arguments)]
    pub fn compute(
        &mut self,
        u_n: &[f64],
        u: &[f64],
        states_n: &[PointState],
        states_out: &mut [PointState],
        dt: f64,
        tangent: TangentKind,
        fint: &mut [f64],
        stiffness: Option<&mut SparseMatrix>,
    ) -> Result<(), CellFailure> {
        let _elements = crate::profile::span(crate::profile::Phase::ElementAssembly);
        let laws = &self.laws;
        // Each element's slice of the new states (the elements hold
        // consecutive ranges in order): the states are copied there by the
        // thread that computed them, while they are in its cache.
        let mut chunks: Vec<&mut [PointState]> = Vec::with_capacity(self.elements.len());
        let mut rest = states_out;
        let mut at = 0;
        for e in &self.elements {
            let (_, tail) = std::mem::take(&mut rest).split_at_mut(e.state_offset - at);
            let (mine, tail) = tail.split_at_mut(e.npg);
            chunks.push(mine);
            rest = tail;
            at = e.state_offset + e.npg;
        }
        let integrate =
            |((e, out), chunk): ((&ElementData, &mut ElementBuffers), &mut &mut [PointState])| {
                integrate_one(e, laws, (u_n, u), states_n, dt, tangent, out, chunk)
            };
        // Below PARALLEL_MIN_ELEMENTS the thread pool's wake-ups cost more
        // than the work they share (docs/performance.md). The elements
        // are integrated in parallel into their own buffers and assembled
        // below in element order, so the sums, hence the results, are the
        // same to the bit whatever the thread count.
        let threads = rayon::current_num_threads();
        if threads > 1 && self.elements.len() >= PARALLEL_MIN_ELEMENTS {
            self.elements
                .par_iter()
                .zip(self.buffers.par_iter_mut())
                .zip(chunks.par_iter_mut())
                .with_min_len(PARALLEL_MIN_BLOCK)
                .map(integrate)
                .collect_into_vec(&mut self.results);
        } else {
            self.results.clear();
            self.results.extend(
                self.elements
                    .iter()
                    .zip(self.buffers.iter_mut())
                    .zip(chunks.iter_mut())
                    .map(integrate),
            );
        }
        fint.iter_mut().for_each(|v| *v = 0.0);
        let mut stiffness = stiffness;
        if let Some(k) = stiffness.as_deref_mut() {
            k.fill_zero();
        }
        for ((e, r), out) in self.elements.iter().zip(&self.results).zip(&self.buffers) {
            r.as_ref().map_err(|f| CellFailure {
                cell: e.cell,
                failure: f.clone(),
            })?;
            for (&f, &v) in e.full.iter().zip(&out.forces) {
                fint[f] += v;
            }
            if let Some(kmat) = stiffness.as_deref_mut() {
                if !out.stiffness.is_empty() {
                    // Both row-major: entry (a, b) at a·n + b. Each global
                    // entry receives one term per element, so the order of
                    // the entries does not change the sums.
                    for (&p, &v) in e.pos.iter().zip(&out.stiffness) {
                        if p != NONE {
                            kmat.values[p] += v;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The element pass of an explicit step (no tangent) on the team's
    /// threads: the new states into `states_out`, each element's forces
    /// left in its buffer for [`Assembler::assemble_forces`]. Blocks of
    /// [`PARALLEL_MIN_BLOCK`] elements are the pieces the threads take.
    /// The first failing element in element order is the one reported,
    /// as in `compute`.
    pub fn integrate_explicit(
        &mut self,
        team: &Team,
        u_n: &[f64],
        u: &[f64],
        states_n: &[PointState],
        states_out: &mut [PointState],
        dt: f64,
    ) -> Result<(), CellFailure> {
        let _elements = crate::profile::span(crate::profile::Phase::ElementAssembly);
        self.prepare_gather();
        let laws = &self.laws;
        let n = self.elements.len();
        self.results.clear();
        self.results.resize_with(n, || Ok(()));
        let mut pieces = Vec::with_capacity(n.div_ceil(PARALLEL_MIN_BLOCK));
        let mut rest = states_out;
        let mut at = 0;
        let mut flat_rest = &mut self.flat_forces[..];
        for ((els, bufs), res) in self
            .elements
            .chunks(PARALLEL_MIN_BLOCK)
            .zip(self.buffers.chunks_mut(PARALLEL_MIN_BLOCK))
            .zip(self.results.chunks_mut(PARALLEL_MIN_BLOCK))
        {
            // The elements hold consecutive ranges of states in order.
            let first = els[0].state_offset;
            let last = &els[els.len() - 1];
            let end = last.state_offset + last.npg;
            let (_, tail) = std::mem::take(&mut rest).split_at_mut(first - at);
            let (mine, tail) = tail.split_at_mut(end - first);
            rest = tail;
            at = end;
            let nflat = els.iter().map(|e| e.full.len()).sum();
            let (flat, tail) = std::mem::take(&mut flat_rest).split_at_mut(nflat);
            flat_rest = tail;
            pieces.push((els, bufs, res, mine, flat));
        }
        let parts = Parts::new(pieces);
        team.for_each(parts.len(), &|i| {
            let (els, bufs, res, states, mut flat) = parts.take(i);
            let base = els[0].state_offset;
            for (i, (e, r)) in els.iter().zip(res.iter_mut()).enumerate() {
                // The next element's kept data is asked for while this
                // one computes (the pass is latency-bound).
                if let Some(next) = bufs.get(i + 1) {
                    next.prefetch();
                }
                let out = &mut bufs[i];
                let chunk = &mut states[e.state_offset - base..e.state_offset - base + e.npg];
                *r = integrate_one(
                    e,
                    laws,
                    (u_n, u),
                    states_n,
                    dt,
                    TangentKind::None,
                    out,
                    chunk,
                );
                // The forces where the assembly reads them (a failed
                // element's are never assembled: the step stops).
                let (mine, tail) = std::mem::take(&mut flat).split_at_mut(e.full.len());
                if r.is_ok() {
                    mine.copy_from_slice(&out.forces);
                }
                flat = tail;
            }
        });
        for (e, r) in self.elements.iter().zip(&self.results) {
            r.as_ref().map_err(|f| CellFailure {
                cell: e.cell,
                failure: f.clone(),
            })?;
        }
        Ok(())
    }

    /// Builds the table of [`Assembler::assemble_forces`] (once).
    pub fn prepare_gather(&mut self) {
        if !self.gather_ptr.is_empty() {
            return;
        }
        let nfull = self.numbering.nfull();
        let mut count = vec![0usize; nfull + 1];
        for e in &self.elements {
            for &f in &e.full {
                count[f + 1] += 1;
            }
        }
        for f in 0..nfull {
            count[f + 1] += count[f];
        }
        let mut src = vec![0u32; count[nfull]];
        let mut fill = count.clone();
        let mut at = 0usize;
        for e in &self.elements {
            for (k, &f) in e.full.iter().enumerate() {
                src[fill[f]] = u32::try_from(at + k).expect("fewer than 2^32 element dofs");
                fill[f] += 1;
            }
            at += e.full.len();
        }
        self.gather_ptr = count;
        self.gather_src = src;
        self.flat_forces = vec![0.0; at];
    }

    /// The internal forces of the full dofs `first..first + out.len()`
    /// from the element forces of the last `integrate_explicit`: each
    /// dof's terms summed from +0 in element order, as the scatter of
    /// `compute` sums them (the same value to the bit), so that dof
    /// ranges can be assembled on different threads.
    pub fn assemble_forces(&self, first: usize, out: &mut [f64]) {
        let ptr = &self.gather_ptr[first..first + out.len() + 1];
        for (o, w) in out.iter_mut().zip(ptr.windows(2)) {
            let mut s = 0.0;
            for &k in &self.gather_src[w[0]..w[1]] {
                s += self.flat_forces[k as usize];
            }
            *o = s;
        }
    }

    /// Finite-strain internal forces without a tangent through τF⁻ᵀ
    /// (`ElementBuffers::conjugate_forces`): the explicit time loop, whose
    /// step is one such evaluation, turns it on.
    pub fn set_conjugate_forces(&mut self, on: bool) {
        for b in &mut self.buffers {
            b.conjugate_forces = on;
        }
    }

    /// y = M x on full vectors.
    pub fn mass_mul(&self, x: &[f64], y: &mut [f64]) {
        self.mass_full.mul_vec(x, y);
    }

    /// K(u_n)·du added into `out` (full): the tangent (`kind`: consistent
    /// or elastic) of each element that `du` touches, evaluated at the
    /// start of the step (zero increment from `states_n`), applied to its
    /// part of `du`. The prediction of a step whose imposed values move
    /// uses it to carry their increment into the free dofs, Rayleigh
    /// damping to apply its stiffness part to the velocity.
    pub fn tangent_action(
        &mut self,
        u_n: &[f64],
        states_n: &[PointState],
        dt: f64,
        du: &[f64],
        kind: TangentKind,
        out: &mut [f64],
    ) -> Result<(), CellFailure> {
        self.tangent_action_on(None, u_n, states_n, dt, du, kind, out)
    }

    /// [`Self::tangent_action`], the elements' tangents computed by `team`
    /// when given (the explicit loop's; each element into its own buffer,
    /// then the products summed here in element order, so the result is
    /// the same to the bit whatever the team).
    #[allow(clippy::too_many_arguments)]
    pub fn tangent_action_on(
        &mut self,
        team: Option<&Team>,
        u_n: &[f64],
        states_n: &[PointState],
        dt: f64,
        du: &[f64],
        kind: TangentKind,
        out: &mut [f64],
    ) -> Result<(), CellFailure> {
        let laws = &self.laws;
        let one = |e: &ElementData, buf: &mut ElementBuffers| -> Result<bool, CellFailure> {
            if e.full.iter().all(|&f| du[f] == 0.0) {
                return Ok(false);
            }
            let mut chunk: Vec<PointState> =
                states_n[e.state_offset..e.state_offset + e.npg].to_vec();
            integrate_one(e, laws, (u_n, u_n), states_n, dt, kind, buf, &mut chunk).map_err(
                |failure| CellFailure {
                    cell: e.cell,
                    failure,
                },
            )?;
            Ok(true)
        };
        let done: Vec<Result<bool, CellFailure>> = match team {
            Some(team) if self.elements.len() >= PARALLEL_MIN_ELEMENTS => {
                self.tangent_done.clear();
                self.tangent_done.resize(self.elements.len(), Ok(false));
                let pieces = Parts::new(
                    self.elements
                        .chunks(PARALLEL_MIN_BLOCK)
                        .zip(self.buffers.chunks_mut(PARALLEL_MIN_BLOCK))
                        .zip(self.tangent_done.chunks_mut(PARALLEL_MIN_BLOCK)),
                );
                team.for_each(pieces.len(), &|i| {
                    let ((els, bufs), res) = pieces.take(i);
                    for ((e, buf), r) in els.iter().zip(bufs.iter_mut()).zip(res.iter_mut()) {
                        *r = one(e, buf);
                    }
                });
                std::mem::take(&mut self.tangent_done)
            }
            _ => self
                .elements
                .iter()
                .zip(self.buffers.iter_mut())
                .map(|(e, buf)| one(e, buf))
                .collect(),
        };
        for ((e, buf), r) in self.elements.iter().zip(&self.buffers).zip(&done) {
            if !r.clone()? {
                continue;
            }
            let n = e.full.len();
            for (a, &fa) in e.full.iter().enumerate() {
                let row = &buf.stiffness[a * n..(a + 1) * n];
                out[fa] += row
                    .iter()
                    .zip(&e.full)
                    .map(|(k, &fb)| k * du[fb])
                    .sum::<f64>();
            }
        }
        self.tangent_done = done;
        Ok(())
    }
}

/// One element's integration into its buffer and its slice of the new
/// states, its dofs gathered into the buffer's own vectors (no 2 x
/// MAX_DOFS arrays zeroed per element).
#[allow(clippy::too_many_arguments)]
fn integrate_one(
    e: &ElementData,
    laws: &[CellLaw],
    (u_n, u): (&[f64], &[f64]),
    states_n: &[PointState],
    dt: f64,
    tangent: TangentKind,
    out: &mut ElementBuffers,
    chunk: &mut [PointState],
) -> Result<(), ElementFailure> {
    let mut lu_n = std::mem::take(&mut out.gather_n);
    let mut lu = std::mem::take(&mut out.gather);
    lu_n.clear();
    lu.clear();
    lu_n.extend(e.full.iter().map(|&f| u_n[f]));
    lu.extend(e.full.iter().map(|&f| u[f]));
    let r = internal_forces_to(
        &e.spec,
        e.kin,
        &e.coords,
        &lu_n,
        &lu,
        &states_n[e.state_offset..e.state_offset + e.npg],
        laws[e.law].law_ref(),
        dt,
        tangent,
        out,
        chunk,
    );
    out.gather_n = lu_n;
    out.gather = lu;
    r
}

/// The pattern of the free equations: every coupling of an element plus
/// `extra`; sets each element's entry positions in it.
fn free_pattern(
    numbering: &DofNumbering,
    elements: &mut [ElementData],
    extra: &[(usize, usize)],
) -> Arc<CscPattern> {
    let mut entries = Vec::new();
    let n = extra
        .iter()
        .map(|&(a, b)| a.max(b) + 1)
        .fold(numbering.neq(), usize::max);
    for e in elements.iter() {
        for &fa in &e.full {
            for &fb in &e.full {
                let (ea, eb) = (numbering.eq[fa], numbering.eq[fb]);
                if ea != NONE && eb != NONE {
                    entries.push((ea, eb));
                }
            }
        }
    }
    entries.extend_from_slice(extra);
    let pattern = Arc::new(CscPattern::from_entries(n, entries));
    for e in elements.iter_mut() {
        let n = e.full.len();
        e.pos = vec![NONE; n * n];
        for a in 0..n {
            for b in 0..n {
                let (ea, eb) = (numbering.eq[e.full[a]], numbering.eq[e.full[b]]);
                if ea != NONE && eb != NONE {
                    e.pos[a * n + b] = pattern.position(ea, eb).expect("entry in pattern");
                }
            }
        }
    }
    pattern
}
