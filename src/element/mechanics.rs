//! The one element interface of the nonlinear mechanics engine: internal
//! forces, tangent stiffness and new Gauss-point states for every cell,
//! formulation (AXIS, 3D) and strain measure (PETIT, PETIT_REAC,
//! SIMO_MIEHE, GDEF_LOG, GROT_GDEP), and the consistent mass.
//!
//! # One code path for 2D axisymmetric and 3D
//! Everything is written with 3×3 tensors. In AXIS the third index is the
//! hoop direction θ: a displacement gradient is
//! `[[∂u_r/∂r, ∂u_r/∂z, 0], [∂u_z/∂r, ∂u_z/∂z, 0], [0, 0, u_r/r]]`, so the
//! 6-vector (xx, yy, zz, xy, xz, yz) reads (rr, zz, θθ, rz, 0, 0) as
//! code_aster's AXIS SIEF_ELGA does, and the finite-strain law sees
//! F = diag-block(F_rz, F_θθ = (R + u_r)/R). Gauss points are interior,
//! so R > 0 there for any valid mesh even when nodes lie on the axis.
//!
//! For each dof α = (node a, direction i) the element uses the *virtual
//! gradient* G_α = ∇(N_a e_i) (3×3; in AXIS, i = r adds N_a/r in θθ), or
//! A_α = G⁰_α F⁻¹ for SIMO_MIEHE. With S the stress conjugate to it,
//! f_α = ∫ S : A_α, and the tangent is K_αβ = ∫ A_α : M_β with one 3×3 M_β
//! per dof (docs/laws-elements.md §4.2 derives M_β for each strain
//! measure). A Gauss point then costs O(9·ndof²) flops with no
//! allocation: all per-point data live in stack arrays sized by
//! [`MAX_DOFS`].
//!
//! # Strain measures
//! - PETIT: G on the initial geometry, Δε = sym ∇Δu, S = σ, ∫ dV₀.
//! - PETIT_REAC: G on x = X + u (start-of-step u_n plus increment), Δε =
//!   sym ∇ₓΔu added to σ_n by the law, **no objective rotation**, ∫ dv
//!   (semantics.md §4.5). The tangent is the exact derivative, including
//!   the change of geometry with u. code_aster keeps only ∫Bᵀ D B on the
//!   updated geometry (from memory of te0139/nmpl3d, not re-read); the
//!   residual, hence the converged solution, is the same.
//! - SIMO_MIEHE: F = 1 + Grad_X u on the initial geometry; the law gives
//!   Kirchhoff τ and ∂τ/∂F; f_α = ∫ τ : (G⁰_α F⁻¹) dV₀ = ∫ P : G⁰_α dV₀.
//!   SIEF is Cauchy σ = τ/J. The tangent is not symmetric.
//! - GROT_GDEP: F on the initial geometry, the small-strain law fed the
//!   Green-Lagrange increment E(F) − E(F_n) and S_n = J_n F_n⁻¹ σ_n F_n⁻ᵀ;
//!   f_α = ∫ (F S) : G⁰_α dV₀, tangent G⁰_β S + F D (Fᵀ G⁰_β); SIEF is
//!   Cauchy σ = F S Fᵀ/J, as code_aster's nmgr3d / nmgrla store it.
//!
//! Failures are values: a non-positive Jacobian on the initial mesh is a
//! mesh error ([`ElementFailure::BadGeometry`]); on the deformed
//! configuration, or det F ≤ 0, it is a step that went too far
//! ([`ElementFailure::Inverted`], retry with a smaller step), as is a law
//! that did not converge.

use std::fmt;
use std::sync::OnceLock;

use nalgebra::{DMatrix, DVector, Matrix3, SMatrix};

use crate::law::gdef_log::FiniteStrainBehaviour;
use crate::law::plane_stress;
use crate::law::simo_miehe::{Axi, FiniteStrainInput, SimoMiehe, StepStart};
use crate::law::voigt::{stress_to_tensor, tensor_to_strain, tensor_to_stress};
use crate::law::{
    IntegrationFailure, InternalVars, SmallStrainBehaviour, SmallStrainInput, StrainMeasure,
    TangentKind, Vec6,
};
use crate::mesh::quadrature::{families, rule, Fpg};
use crate::mesh::shape::{eval, ShapeEval, MAX_NODES};
use crate::mesh::CellType;
use crate::model::spec::{ElementSpec, Formulation};

/// The largest number of dofs of an element (HEXA20 in 3D).
pub const MAX_DOFS: usize = 3 * MAX_NODES;

/// code_aster's `DEFORMATION` values the element implements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Kinematics {
    Petit,
    PetitReac,
    SimoMiehe,
    GdefLog,
    /// Total Lagrangian with the Green-Lagrange strain, a small-strain
    /// law fed ΔE and the second Piola-Kirchhoff stress S_n.
    GrotGdep,
}

impl Kinematics {
    pub fn from_strain_measure(m: StrainMeasure) -> Kinematics {
        match m {
            StrainMeasure::Petit => Kinematics::Petit,
            StrainMeasure::PetitReac => Kinematics::PetitReac,
            StrainMeasure::SimoMiehe => Kinematics::SimoMiehe,
            StrainMeasure::GdefLog => Kinematics::GdefLog,
            StrainMeasure::GrotGdep => Kinematics::GrotGdep,
        }
    }
    pub fn strain_measure(self) -> StrainMeasure {
        match self {
            Kinematics::Petit => StrainMeasure::Petit,
            Kinematics::PetitReac => StrainMeasure::PetitReac,
            Kinematics::SimoMiehe => StrainMeasure::SimoMiehe,
            Kinematics::GdefLog => StrainMeasure::GdefLog,
            Kinematics::GrotGdep => StrainMeasure::GrotGdep,
        }
    }
}

/// The law of a cell: a small-strain law (PETIT, PETIT_REAC: strain
/// increment in, σ and dσ/dΔε out) or the finite-strain SIMO_MIEHE law
/// (F_n, F_{n+1} in, τ and ∂τ/∂F out). The two contracts differ in kind,
/// hence an enum rather than one trait.
#[derive(Clone, Copy)]
pub enum LawRef<'a> {
    Small(&'a dyn SmallStrainBehaviour),
    SimoMiehe(&'a SimoMiehe),
    /// A small-strain law in GDEF_LOG (same contract as SIMO_MIEHE).
    GdefLog(&'a dyn FiniteStrainBehaviour),
}

impl LawRef<'_> {
    /// Internal variables of a virgin material point.
    pub fn initial_internal(&self) -> InternalVars {
        match self {
            LawRef::Small(l) => l.initial_internal(),
            LawRef::SimoMiehe(l) => l.initial_internal(),
            LawRef::GdefLog(l) => l.initial_internal(),
        }
    }
    fn name(&self) -> &'static str {
        match self {
            LawRef::Small(l) => l.metadata().name,
            LawRef::SimoMiehe(l) => l.metadata().name,
            LawRef::GdefLog(l) => l.metadata().name,
        }
    }
}

/// Stress and internal variables of one Gauss point. The stress is the
/// Cauchy stress (SIEF_ELGA) in the order xx, yy, zz, xy, xz, yz; in AXIS
/// (rr, zz, θθ, rz, 0, 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointState {
    pub stress: Vec6,
    pub internal: InternalVars,
}

/// Why an element computation failed.
#[derive(Debug, Clone, PartialEq)]
pub enum ElementFailure {
    /// Non-positive Jacobian or a Gauss point at r ≤ 0 on the initial
    /// mesh: a mesh error, retrying cannot help.
    BadGeometry { point: usize, message: String },
    /// Non-positive Jacobian, radius or det F on the deformed
    /// configuration: the step went too far.
    Inverted { point: usize, message: String },
    /// The caller passed states for another Gauss family.
    StateCount { expected: usize, got: usize },
    /// Inconsistent call: array sizes, non-finite values, a law that does
    /// not support the strain measure.
    BadInput { message: String },
    /// The law failed at Gauss point `point`.
    Law {
        point: usize,
        failure: IntegrationFailure,
    },
}

impl ElementFailure {
    /// Suggested step ratio for a retry; 0 when retrying cannot help.
    pub fn dt_factor(&self) -> f64 {
        match self {
            ElementFailure::Inverted { .. } => 0.5,
            ElementFailure::Law { failure, .. } => failure.dt_factor,
            _ => 0.0,
        }
    }
}

impl fmt::Display for ElementFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ElementFailure::BadGeometry { point, message } => {
                write!(
                    f,
                    "invalid element geometry at Gauss point {}: {message}",
                    point + 1
                )
            }
            ElementFailure::Inverted { point, message } => write!(
                f,
                "element inverted at Gauss point {}: {message}; a smaller step is needed",
                point + 1
            ),
            ElementFailure::StateCount { expected, got } => {
                write!(f, "{got} Gauss-point states given, {expected} expected")
            }
            ElementFailure::BadInput { message } => f.write_str(message),
            ElementFailure::Law { point, failure } => {
                write!(f, "at Gauss point {}: {failure}", point + 1)
            }
        }
    }
}

impl std::error::Error for ElementFailure {}

/// Internal forces, optional tangent and the new Gauss-point states.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementResponse {
    /// f_int, dof order node-major (node a, direction i at `a·d + i`).
    pub forces: DVector<f64>,
    /// ∂f_int/∂u, same order; `None` for [`TangentKind::None`].
    pub stiffness: Option<DMatrix<f64>>,
    /// One per RIGI Gauss point, in code_aster's point order.
    pub states: Vec<PointState>,
}

/// Virgin states (zero stress, the law's initial internal variables) for
/// the RIGI points of `spec`.
pub fn initial_states(spec: &ElementSpec, law: LawRef) -> Vec<PointState> {
    if spec.is_hexs8() {
        return super::hexs8::initial_states(law);
    }
    let n = tabulated(spec.cell, spec.rigi).map_or(0, |t| t.weights.len());
    vec![
        PointState {
            stress: Vec6::zeros(),
            internal: law.initial_internal(),
        };
        n
    ]
}

/// Number of state rows of `spec` (length of its state arrays): its RIGI
/// Gauss points, plus the 12 rows of hourglass stresses of HEXS8.
pub fn rigi_points(spec: &ElementSpec) -> usize {
    if spec.is_hexs8() {
        return super::hexs8::STATE_ROWS;
    }
    tabulated(spec.cell, spec.rigi).map_or(0, |t| t.weights.len())
}

/// Number of Gauss points of `spec` in SIEF_ELGA/VARI_ELGA (1 for HEXS8,
/// whose extra state rows appear as components FSTAB1..72).
pub fn output_points(spec: &ElementSpec) -> usize {
    tabulated(spec.cell, spec.rigi).map_or(0, |t| t.weights.len())
}

/// The displacement gradient Grad_X u on the initial geometry `x` at each
/// point of the element's SIEF_ELGA (its RIGI points; HEXS8's one centre
/// point, [`super::hexs8::centre_gradient`]), for the nodal displacements
/// `u` (`dofs_per_node` per node, node order of the cell). In AXIS the
/// θθ entry is u_r/r, so that the strain measures of CALC_CHAMP
/// (EPSI/EPSG/EPSL) read (rr, zz, θθ, rz) like SIEF_ELGA. A point the
/// geometry makes invalid (folded cell, radius ≤ 0) is an error naming it.
pub fn displacement_gradients(
    spec: &ElementSpec,
    x: &[[f64; 3]],
    u: &[f64],
) -> Result<Vec<Matrix3<f64>>, String> {
    if spec.is_hexs8() {
        let xs: &[[f64; 3]; 8] = x
            .try_into()
            .map_err(|_| format!("{} needs 8 nodes, got {}", spec.name, x.len()))?;
        return Ok(vec![super::hexs8::centre_gradient(xs, u)?]);
    }
    let t = table(spec, spec.rigi).map_err(|e| e.to_string())?;
    let d = spec.formulation.dofs_per_node();
    t.shapes
        .iter()
        .zip(&t.weights)
        .enumerate()
        .map(|(g, (s, &w))| {
            let pg = point_geometry(spec.formulation, s, x, w)
                .map_err(|m| format!("point {}: {m}", g + 1))?;
            Ok(pg.gradient(u, d))
        })
        .collect()
}

/// Reusable output of [`internal_forces_into`]: the engine keeps one per
/// element, so that an iteration of the element loop allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct ElementBuffers {
    /// f_int, dof order node-major.
    pub forces: Vec<f64>,
    /// ∂f_int/∂u, row-major (entry (a, b) at `a·ndof + b`); empty for
    /// [`TangentKind::None`].
    pub stiffness: Vec<f64>,
    /// One per state row, as [`ElementResponse::states`].
    pub states: Vec<PointState>,
    /// The tangent partners M_b by component: `partners[3r + c][b]` is
    /// M_b(r, c). One contiguous row per component lets the ndof² loop of
    /// the tangent run over b in SIMD lanes.
    partners: Vec<[f64; MAX_DOFS]>,
    geometry: GeometryCache,
    starts: StartCache,
    /// Finite-strain forces without a tangent through τF⁻ᵀ, one product
    /// per Gauss point, instead of the spatial gradient G⁰F⁻¹ of every
    /// dof (explicit dynamics, where this evaluation is the whole step).
    /// The two sums differ by round-off only; the implicit runs keep the
    /// per-dof form, so that their recorded answers stay bit-identical.
    pub conjugate_forces: bool,
    /// Room for the element's u_n and u, gathered by the engine.
    pub gather_n: Vec<f64>,
    pub gather: Vec<f64>,
    /// The deformation gradients of the last explicit evaluation
    /// (`conjugate_forces` with SIMO_MIEHE): the next step's F_n.
    previous: PreviousGradients,
}

/// F, det F and F⁻¹ at each Gauss point of the last explicit evaluation,
/// with the u and the geometry they were computed from: in explicit
/// dynamics the next step starts where this one ends, so its F_n, det F_n
/// and F_n⁻¹ are these to the bit (the same sums on the same u) and are
/// not recomputed (`u_n` is compared to the bit, as [`StartCache`] does).
#[derive(Debug, Clone, Default)]
struct PreviousGradients {
    u: Vec<f64>,
    geometry: u64,
    /// Every formulation but AXIS.
    points: Vec<(Matrix3<f64>, f64, Matrix3<f64>)>,
    /// AXIS: 96 bytes a point where the 3 × 3 matrices took 152, read
    /// back at the next step from a cache they have left by then.
    axi: Vec<KeptAxi>,
}

/// An AXIS point's F (whose θ coupling is exact +0, so `f.matrix()` is
/// F to the bit), det F and F⁻¹ on the (r, z) block and θθ. `general`:
/// F⁻¹ came from the 3 × 3 path (`try_inverse`), whose zeros' signs are
/// not kept here: that path's next step takes F_n⁻¹ from F_n again (the
/// law's own `try_inverse` of the same F, the same bits).
#[derive(Debug, Clone, Copy)]
struct KeptAxi {
    f: Axi,
    j: f64,
    f_inv: Axi,
    general: bool,
}

impl KeptAxi {
    const ZERO: KeptAxi = KeptAxi {
        f: Axi {
            m: [[0.0; 2]; 2],
            t: 0.0,
        },
        j: 0.0,
        f_inv: Axi {
            m: [[0.0; 2]; 2],
            t: 0.0,
        },
        general: false,
    };
}

impl PreviousGradients {
    /// Whether `u_n` is the kept u to the bit.
    fn same_u(&self, u_n: &[f64]) -> bool {
        self.u.len() == u_n.len()
            && self
                .u
                .iter()
                .zip(u_n)
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }

    /// Whether the kept points are those of `geometry`, given
    /// [`PreviousGradients::same_u`].
    fn holds(&self, geometry: u64, npoints: usize, axis: bool) -> bool {
        let kept = if axis {
            self.axi.len()
        } else {
            self.points.len()
        };
        self.geometry == geometry && kept == npoints
    }
}

impl ElementBuffers {
    /// Hints the cache with what the next explicit SIMO_MIEHE evaluation
    /// of this buffer reads first: the kept u and AXIS gradients (heap
    /// blocks that the other elements of the step have evicted, whose
    /// first loads were the pass's largest stalls). Changes no value.
    #[inline]
    pub fn prefetch(&self) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
            fn lines<T>(v: &[T]) {
                let p = v.as_ptr().cast::<i8>();
                for off in (0..std::mem::size_of_val(v)).step_by(64) {
                    // SAFETY: SSE is in every x86_64 target, and a
                    // prefetch never faults nor reads into the program.
                    unsafe { _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(off)) };
                }
            }
            lines(&self.previous.u);
            lines(&self.previous.axi);
        }
    }

    /// Promises that every later evaluation with this buffer passes the
    /// same node coordinates (the engine keeps one buffer per element of
    /// a computation, whose initial coordinates never change): they are
    /// checked and the geometry computed at the first evaluation, and
    /// later ones skip the finiteness check and the comparison to the bit
    /// that a buffer shared between cells needs.
    pub fn set_fixed_coordinates(&mut self) {
        self.geometry.fixed = true;
    }
}

/// The Gauss-point geometry on the initial configuration of the last
/// element a buffer served, with what it was computed from: the engine
/// gives each element its own buffer, so the geometry (Jacobian, ∇N, dV)
/// is computed once instead of at every iteration.
#[derive(Debug, Clone, Default)]
struct GeometryCache {
    /// The owner passes the same coordinates at every evaluation
    /// ([`ElementBuffers::set_fixed_coordinates`]): once the points are
    /// computed, the coordinates are neither compared nor checked again.
    fixed: bool,
    /// The table of the last evaluation's RIGI family (looked up once
    /// when `fixed`).
    table: Option<&'static Tabulated>,
    key: Option<(CellType, Fpg, Formulation)>,
    coords: Vec<[f64; 3]>,
    points: Vec<Result<PointGeometry, String>>,
    /// Counts the recomputations, so that what was derived from the
    /// points ([`StartCache`]) knows whether they changed.
    generation: u64,
}

/// SIMO_MIEHE's quantities of the start of the step at each Gauss point
/// (F_n, det F_n, A = F_n⁻¹ b̄ᵉ_n F_n⁻ᵀ), kept for the Newton iterations of
/// the step with what they were computed from: the element's u_n and
/// geometry, and each point's internal variables, compared to the bit.
#[derive(Debug, Clone, Default)]
struct StartCache {
    u_n: Vec<f64>,
    geometry: u64,
    points: Vec<Option<PointStart>>,
}

#[derive(Debug, Clone)]
struct PointStart {
    internal: InternalVars,
    f_n: Matrix3<f64>,
    start: StepStart,
}

impl StartCache {
    /// Forgets every point unless `u_n` and the geometry are those the
    /// points were computed with.
    fn validate(&mut self, u_n: &[f64], geometry: u64, npoints: usize) {
        let same = self.geometry == geometry
            && self.u_n.len() == u_n.len()
            && self
                .u_n
                .iter()
                .zip(u_n)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        if !same {
            self.u_n.clear();
            self.u_n.extend_from_slice(u_n);
            self.geometry = geometry;
            self.points.clear();
        }
        self.points.resize(npoints, None);
    }

    /// The start of point `p` if it was computed from `internal`.
    fn get(&self, p: usize, internal: &[f64]) -> Option<&PointStart> {
        self.points[p].as_ref().filter(|s| {
            let held = s.internal.as_slice();
            held.len() == internal.len()
                && held
                    .iter()
                    .zip(internal)
                    .all(|(a, b)| a.to_bits() == b.to_bits())
        })
    }
}

impl GeometryCache {
    /// The points of `tab` for `coords`, computed unless they are the
    /// ones held (same cell, family, formulation, and coordinates to the
    /// bit).
    fn points(
        &mut self,
        tab: &Tabulated,
        formulation: Formulation,
        coords: &[[f64; 3]],
    ) -> (&[Result<PointGeometry, String>], u64) {
        let key = Some((tab.cell, tab.fpg, formulation));
        let same = self.key == key
            && self.coords.len() == coords.len()
            && (self.fixed
                || self
                    .coords
                    .iter()
                    .zip(coords)
                    .all(|(a, b)| a.map(f64::to_bits) == b.map(f64::to_bits)));
        if !same {
            self.key = key;
            self.coords.clear();
            self.coords.extend_from_slice(coords);
            self.points.clear();
            self.points.extend(
                tab.shapes
                    .iter()
                    .zip(&tab.weights)
                    .map(|(shape, w)| point_geometry(formulation, shape, coords, *w)),
            );
            self.generation += 1;
        }
        (&self.points, self.generation)
    }
}

/// Integrates the law at every RIGI point for the step u_n → u and
/// assembles the internal forces and, unless `tangent` is
/// [`TangentKind::None`], their derivative with respect to u.
///
/// `coords` are the initial node coordinates (3 components; AXIS reads
/// x = r and y = z), MED node order. `u_n` and `u` are the nodal
/// displacements at the start of the step and now, node-major, 2 (AXIS) or
/// 3 per node. `states_n` are the Gauss-point states at the start of the
/// step. `dt` is passed to rate-dependent laws.
#[allow(clippy::too_many_arguments)]
pub fn internal_forces(
    spec: &ElementSpec,
    kin: Kinematics,
    coords: &[[f64; 3]],
    u_n: &[f64],
    u: &[f64],
    states_n: &[PointState],
    law: LawRef,
    dt: f64,
    tangent: TangentKind,
) -> Result<ElementResponse, ElementFailure> {
    if spec.is_hexs8() {
        return super::hexs8::internal_forces(
            spec, kin, coords, u_n, u, states_n, law, dt, tangent,
        );
    }
    let mut out = ElementBuffers::default();
    internal_forces_into(
        spec, kin, coords, u_n, u, states_n, law, dt, tangent, &mut out,
    )?;
    let n = out.forces.len();
    Ok(ElementResponse {
        forces: DVector::from_vec(out.forces),
        stiffness: (tangent != TangentKind::None)
            .then(|| DMatrix::from_row_slice(n, n, &out.stiffness)),
        states: out.states,
    })
}

/// [`internal_forces`] into reusable buffers (same contract; the tangent
/// row-major in `out.stiffness`).
#[allow(clippy::too_many_arguments)]
pub fn internal_forces_into(
    spec: &ElementSpec,
    kin: Kinematics,
    coords: &[[f64; 3]],
    u_n: &[f64],
    u: &[f64],
    states_n: &[PointState],
    law: LawRef,
    dt: f64,
    tangent: TangentKind,
    buf: &mut ElementBuffers,
) -> Result<(), ElementFailure> {
    evaluate(
        spec, kin, coords, u_n, u, states_n, law, dt, tangent, buf, None,
    )
    .map(|_| ())
}

/// [`internal_forces_into`] with the new states written into
/// `states_out` (one per state row) instead of `buf.states`, which is
/// left empty: the engine's element loop gives each element its slice of
/// the state array, so the states are written once.
#[allow(clippy::too_many_arguments)]
pub fn internal_forces_to(
    spec: &ElementSpec,
    kin: Kinematics,
    coords: &[[f64; 3]],
    u_n: &[f64],
    u: &[f64],
    states_n: &[PointState],
    law: LawRef,
    dt: f64,
    tangent: TangentKind,
    buf: &mut ElementBuffers,
    states_out: &mut [PointState],
) -> Result<(), ElementFailure> {
    let direct = evaluate(
        spec,
        kin,
        coords,
        u_n,
        u,
        states_n,
        law,
        dt,
        tangent,
        buf,
        Some(&mut *states_out),
    )?;
    if !direct {
        if buf.states.len() != states_out.len() {
            return Err(ElementFailure::StateCount {
                expected: states_out.len(),
                got: buf.states.len(),
            });
        }
        states_out.copy_from_slice(&buf.states);
        buf.states.clear();
    }
    Ok(())
}

/// The body of [`internal_forces_into`]; true when the states were
/// written into `direct` (the explicit SIMO_MIEHE path), else they are in
/// `buf.states`.
#[allow(clippy::too_many_arguments)]
fn evaluate(
    spec: &ElementSpec,
    kin: Kinematics,
    coords: &[[f64; 3]],
    u_n: &[f64],
    u: &[f64],
    states_n: &[PointState],
    law: LawRef,
    dt: f64,
    tangent: TangentKind,
    buf: &mut ElementBuffers,
    direct: Option<&mut [PointState]>,
) -> Result<bool, ElementFailure> {
    let ElementBuffers {
        forces,
        stiffness,
        states,
        partners,
        geometry,
        starts,
        conjugate_forces,
        previous,
        ..
    } = buf;
    if spec.is_hexs8() {
        let r =
            super::hexs8::internal_forces(spec, kin, coords, u_n, u, states_n, law, dt, tangent)?;
        forces.clear();
        forces.extend_from_slice(r.forces.as_slice());
        stiffness.clear();
        if let Some(k) = &r.stiffness {
            let n = k.nrows();
            stiffness.extend((0..n * n).map(|ab| k[(ab / n, ab % n)]));
        }
        states.clear();
        states.extend_from_slice(&r.states);
        return Ok(false);
    }
    let tab = match geometry.table {
        Some(t) if geometry.fixed && t.cell == spec.cell && t.fpg == spec.rigi => t,
        _ => {
            let t = table(spec, spec.rigi)?;
            geometry.table = Some(t);
            t
        }
    };
    let nn = spec.nnodes();
    let d = spec.formulation.dofs_per_node();
    let ndof = nn * d;
    let known = geometry.fixed && geometry.key.is_some() && kin != Kinematics::PetitReac;
    let want_k = tangent != TangentKind::None;
    let explicit = matches!(
        (kin, law, want_k, *conjugate_forces),
        (Kinematics::SimoMiehe, LawRef::SimoMiehe(_), false, true)
    );
    // In explicit dynamics u_n is the u of the previous evaluation, kept
    // because it was checked finite then: its finiteness is known.
    let kept_u_n = explicit && previous.same_u(u_n);
    check_sizes(
        spec,
        coords,
        !known,
        ndof,
        &[("u_n", u_n, !kept_u_n), ("u", u, true)],
    )?;
    if states_n.len() != tab.weights.len() {
        return Err(ElementFailure::StateCount {
            expected: tab.weights.len(),
            got: states_n.len(),
        });
    }
    check_law(kin, law)?;
    if spec.formulation == Formulation::PlaneStress
        && !matches!(kin, Kinematics::Petit | Kinematics::PetitReac)
    {
        // The behaviour field refuses it first (nonlinear::behaviour).
        return Err(ElementFailure::BadInput {
            message: format!(
                "{}: plane stress is built for DEFORMATION='PETIT' and 'PETIT_REAC' only",
                spec.name
            ),
        });
    }

    forces.clear();
    forces.resize(ndof, 0.0);
    stiffness.clear();
    if want_k {
        stiffness.resize(ndof * ndof, 0.0);
    }
    states.clear();
    if let (true, LawRef::SimoMiehe(l)) = (explicit, law) {
        let (initial, generation) = geometry.points(tab, spec.formulation, coords);
        let out = match direct {
            Some(o) if o.len() == states_n.len() => StatesOut::Slice(o),
            _ => StatesOut::Vec(states),
        };
        let direct = matches!(out, StatesOut::Slice(_));
        simo_miehe_explicit(
            l,
            initial,
            generation,
            (nn, d),
            (&u_n[..ndof], &u[..ndof]),
            states_n,
            dt,
            forces,
            out,
            (previous, kept_u_n),
        )?;
        return Ok(direct);
    }
    partners.resize(9, [0.0; MAX_DOFS]);
    let mt = &mut partners[..];
    let axis = spec.formulation == Formulation::Axis;
    let plane_stress = spec.formulation == Formulation::PlaneStress;

    let mut du = [0.0; MAX_DOFS];
    for k in 0..ndof {
        du[k] = u[k] - u_n[k];
    }
    // Current node positions (PETIT_REAC only).
    let mut x = [[0.0; 3]; MAX_NODES];
    for a in 0..nn {
        x[a] = coords[a];
        if kin == Kinematics::PetitReac {
            for i in 0..d {
                x[a][i] += u[a * d + i];
            }
        }
    }
    // Per-dof virtual gradients G_α (or G⁰_α F⁻¹) and tangent partners M_α.
    let mut g = [VGrad::ZERO; MAX_DOFS];

    // The initial geometry, for every strain measure but PETIT_REAC.
    let (initial, generation): (&[Result<PointGeometry, String>], u64) =
        if kin == Kinematics::PetitReac {
            (&[], 0)
        } else {
            geometry.points(tab, spec.formulation, coords)
        };
    // SIMO_MIEHE keeps the start of the step per point (F_n and the
    // internal variables are those of every iteration of a step).
    // Not in explicit dynamics (`conjugate_forces`), where every
    // evaluation starts a new step.
    let keep_start =
        kin == Kinematics::SimoMiehe && matches!(law, LawRef::SimoMiehe(_)) && !*conjugate_forces;
    if keep_start {
        starts.validate(&u_n[..ndof], generation, tab.weights.len());
    }
    let mut current;
    for (p, (shape, w)) in tab.shapes.iter().zip(&tab.weights).enumerate() {
        let st = &states_n[p];
        let geom = match kin {
            Kinematics::PetitReac => {
                current = point_geometry(spec.formulation, shape, &x[..nn], *w)
                    .map_err(|message| ElementFailure::Inverted { point: p, message })?;
                &current
            }
            _ => initial[p]
                .as_ref()
                .map_err(|message| ElementFailure::BadGeometry {
                    point: p,
                    message: message.clone(),
                })?,
        };
        // Without a tangent, the finite-strain forces read ∇N directly
        // (below): the per-dof gradients are not built.
        let finite = matches!(kin, Kinematics::SimoMiehe | Kinematics::GdefLog);
        let use_g = want_k || !finite || !*conjugate_forces;
        if use_g {
            for a in 0..nn {
                for i in 0..d {
                    g[a * d + i] = geom.virtual_gradient(a, i);
                }
            }
        }
        // S: the stress conjugate to the virtual gradients g.
        let (s, new_state) = match (kin, law) {
            (Kinematics::Petit | Kinematics::PetitReac, LawRef::Small(l)) => {
                let grad_du = geom.gradient(&du[..ndof], d);
                let law_span = crate::profile::span(crate::profile::Phase::LawIntegration);
                let input = SmallStrainInput {
                    stress: st.stress,
                    internal: st.internal.as_slice(),
                    strain_increment: tensor_to_strain(&grad_du),
                    dt,
                    tangent,
                };
                // C_PLAN: the same element with σ_zz = 0 solved at the
                // point (Δε_zz does not enter the in-plane virtual work,
                // whose G have no zz entry) and the condensed tangent.
                let out = if plane_stress {
                    plane_stress::integrate(l, &input).map(|o| o.output)
                } else {
                    l.integrate(&input)
                }
                .map_err(|failure| ElementFailure::Law { point: p, failure })?;
                drop(law_span);
                let s = stress_to_tensor(&out.stress);
                if want_k {
                    let dmat = out.tangent.ok_or_else(|| missing_tangent(law))?;
                    for k in 0..ndof {
                        let gk = g[k].matrix();
                        // δ(Δε) = sym δG on the initial geometry; on the
                        // moving one the gradient of Δu also changes:
                        // δL = G − L G, and dv and G change (last terms).
                        let dl = if kin == Kinematics::PetitReac {
                            gk - grad_du * gk
                        } else {
                            gk
                        };
                        let mut mk = stress_to_tensor(&(dmat * tensor_to_strain(&dl)));
                        if kin == Kinematics::PetitReac {
                            mk += s * gk.trace() - s * gk.transpose();
                        }
                        for r in 0..3 {
                            for c in 0..3 {
                                mt[3 * r + c][k] = mk[(r, c)];
                            }
                        }
                    }
                }
                (
                    s,
                    PointState {
                        stress: out.stress,
                        internal: out.internal,
                    },
                )
            }
            (Kinematics::GrotGdep, LawRef::Small(l)) => {
                // code_aster's nmgr3d / nmgrla: F_n and F on the initial
                // geometry, the law fed E_GL(F) − E_GL(F_n) and S_n, the
                // PK2 pull-back of the stored Cauchy stress (pk2sig, −1);
                // its S pushed forward to Cauchy for SIEF_ELGA (pk2sig, 1).
                let (h_n, h) = geom.gradients(&u_n[..ndof], &u[..ndof], d);
                let f_n = Matrix3::identity() + h_n;
                let f = Matrix3::identity() + h;
                let (j_n, j) = (f_n.determinant(), f.determinant());
                check_jacobians(p, j_n, j)?;
                let fn_inv = f_n.try_inverse().ok_or_else(|| ElementFailure::Inverted {
                    point: p,
                    message: "singular deformation gradient at the start of the step".into(),
                })?;
                let s_n = j_n * fn_inv * stress_to_tensor(&st.stress) * fn_inv.transpose();
                let law_span = crate::profile::span(crate::profile::Phase::LawIntegration);
                let input = SmallStrainInput {
                    stress: tensor_to_stress(&s_n),
                    internal: st.internal.as_slice(),
                    strain_increment: tensor_to_strain(
                        &(green_lagrange(&h) - green_lagrange(&h_n)),
                    ),
                    dt,
                    tangent,
                };
                let out = l
                    .integrate(&input)
                    .map_err(|failure| ElementFailure::Law { point: p, failure })?;
                drop(law_span);
                let s = stress_to_tensor(&out.stress);
                if want_k {
                    // δP = δF S + F (D : sym(Fᵀ δF)), δF = G⁰_β: the
                    // geometric part and the material part F D Fᵀ.
                    let dmat = out.tangent.ok_or_else(|| missing_tangent(law))?;
                    for k in 0..ndof {
                        let gk = g[k].matrix();
                        let ds =
                            stress_to_tensor(&(dmat * tensor_to_strain(&(f.transpose() * gk))));
                        let mk = gk * s + f * ds;
                        for r in 0..3 {
                            for c in 0..3 {
                                mt[3 * r + c][k] = mk[(r, c)];
                            }
                        }
                    }
                }
                let cauchy = f * s * f.transpose() / j;
                (
                    // P = F S, the first Piola-Kirchhoff stress, conjugate
                    // to the initial virtual gradients G⁰.
                    f * s,
                    PointState {
                        stress: tensor_to_stress(&cauchy),
                        internal: out.internal,
                    },
                )
            }
            (
                Kinematics::SimoMiehe | Kinematics::GdefLog,
                LawRef::SimoMiehe(_) | LawRef::GdefLog(_),
            ) => {
                let held = if keep_start {
                    starts
                        .get(p, st.internal.as_slice())
                        .map(|k| (k.f_n, k.start))
                } else {
                    None
                };
                // F_n and det F_n as computed when the start was kept
                // (each gradient's sums are those of `gradients`).
                let (f_n, f, j_n) = match &held {
                    Some((f_n, start)) => (
                        *f_n,
                        Matrix3::identity() + geom.gradient(&u[..ndof], d),
                        start.j_n,
                    ),
                    None => {
                        let (h_n, h) = geom.gradients(&u_n[..ndof], &u[..ndof], d);
                        let f_n = Matrix3::identity() + h_n;
                        (f_n, Matrix3::identity() + h, f_n.determinant())
                    }
                };
                let j = f.determinant();
                check_jacobians(p, j_n, j)?;
                let f_inv = f.try_inverse().ok_or_else(|| ElementFailure::Inverted {
                    point: p,
                    message: "singular deformation gradient".into(),
                })?;
                let law_span = crate::profile::span(crate::profile::Phase::LawIntegration);
                let input = FiniteStrainInput {
                    f_n,
                    f_np1: f,
                    internal: st.internal.as_slice(),
                    dt,
                    tangent,
                };
                let result = match law {
                    LawRef::SimoMiehe(l) if keep_start => {
                        let start = match &held {
                            Some((_, start)) => Ok(*start),
                            None => l.step_start(&input).inspect(|start| {
                                starts.points[p] = Some(PointStart {
                                    internal: st.internal,
                                    f_n,
                                    start: *start,
                                });
                            }),
                        };
                        start.and_then(|start| {
                            l.integrate_with_start(&input, &start, tangent_columns(axis))
                        })
                    }
                    LawRef::SimoMiehe(l) => l.integrate_columns(&input, tangent_columns(axis)),
                    LawRef::GdefLog(l) => l.integrate(&input),
                    LawRef::Small(_) => unreachable!("check_law rejects small laws here"),
                };
                // Read in place: the output holds the 9 × 9 tangent slot,
                // which moving it out of the Result would copy at every
                // point.
                let out = match &result {
                    Ok(out) => out,
                    Err(failure) => {
                        return Err(ElementFailure::Law {
                            point: p,
                            failure: failure.clone(),
                        })
                    }
                };
                drop(law_span);
                let tau = out.kirchhoff;
                let conjugate = if use_g {
                    let c = if want_k {
                        Some(out.dtau_df.as_ref().ok_or_else(|| missing_tangent(law))?)
                    } else {
                        None
                    };
                    for k in 0..ndof {
                        let sp = g[k].times(&f_inv, geom.axis);
                        if let Some(c) = c {
                            g[k].tangent_partner_into(&sp, c, &tau, axis, mt, k);
                        }
                        g[k] = sp;
                    }
                    tau
                } else {
                    // Without a tangent the spatial gradients G⁰F⁻¹ are
                    // not needed: (G⁰F⁻¹) : τ = G⁰ : (τF⁻ᵀ), one product
                    // per point instead of one per dof (the same sum up
                    // to round-off).
                    tau * f_inv.transpose()
                };
                (
                    conjugate,
                    PointState {
                        stress: tensor_to_stress(&out.cauchy),
                        internal: out.internal,
                    },
                )
            }
            _ => unreachable!("check_law rejects other pairs"),
        };
        if use_g {
            for k in 0..ndof {
                forces[k] += geom.dv * g[k].dot(&s);
            }
        } else {
            // G⁰ : S with G⁰ = e_i ⊗ ∇N_a (+ N_a/r e_θ ⊗ e_θ for the
            // radial dof of AXIS), the terms in the order of VGrad::dot.
            for a in 0..nn {
                let ga = &geom.grad[a];
                for i in 0..d {
                    let mut v = ga[0] * s[(i, 0)] + ga[1] * s[(i, 1)] + ga[2] * s[(i, 2)];
                    v += if geom.axis && i == 0 {
                        geom.n_over_r[a] * s[(2, 2)]
                    } else {
                        0.0 * s[(2, 2)]
                    };
                    forces[a * d + i] += geom.dv * v;
                }
            }
        }
        if want_k {
            add_tangent(stiffness, &g[..ndof], mt, geom.dv, axis);
        }
        states.push(new_state);
    }
    Ok(false)
}

/// Where [`simo_miehe_explicit`] writes the new states.
enum StatesOut<'a> {
    Vec(&'a mut Vec<PointState>),
    Slice(&'a mut [PointState]),
}

/// The explicit step's SIMO_MIEHE evaluation (no tangent, forces through
/// τF⁻ᵀ): the arithmetic of the general loop of [`internal_forces_into`]
/// for this case, to the bit, without its per-dof gradients, with the
/// law's stress update alone ([`SimoMiehe::integrate_stress`]) and F_n,
/// det F_n, F_n⁻¹ taken from the previous evaluation when it ended at
/// this u_n ([`PreviousGradients`]).
#[allow(clippy::too_many_arguments)]
fn simo_miehe_explicit(
    law: &SimoMiehe,
    initial: &[Result<PointGeometry, String>],
    generation: u64,
    (nn, d): (usize, usize),
    (u_n, u): (&[f64], &[f64]),
    states_n: &[PointState],
    dt: f64,
    forces: &mut [f64],
    mut states: StatesOut,
    (previous, kept_u_n): (&mut PreviousGradients, bool),
) -> Result<(), ElementFailure> {
    let npg = initial.len();
    let axis = matches!(initial.first(), Some(Ok(g)) if g.axis);
    let reuse = kept_u_n && previous.holds(generation, npg, axis);
    if !reuse {
        previous.points.clear();
        previous.axi.clear();
        if axis {
            previous.axi.resize(npg, KeptAxi::ZERO);
        } else {
            previous
                .points
                .resize(npg, (Matrix3::zeros(), 0.0, Matrix3::zeros()));
        }
        previous.geometry = generation;
    }
    // Invalid until every point is done.
    previous.u.clear();
    for (p, st) in states_n.iter().enumerate() {
        let geom = initial[p]
            .as_ref()
            .map_err(|message| ElementFailure::BadGeometry {
                point: p,
                message: message.clone(),
            })?;
        // `fn_inv_axi`: the kept F_n⁻¹ of an AXIS point; `fn_inv` the
        // one of the 3 × 3 path (None: the law inverts F_n).
        let (f_n, f, j_n, fn_inv, fn_inv_axi) = if reuse && axis {
            let k = previous.axi[p];
            let fn_inv = (!k.general).then(|| k.f_inv.matrix());
            let f = geom.deformation_axi(u);
            (k.f.matrix(), f, k.j, fn_inv, Some(k.f_inv))
        } else if reuse {
            let (f_n, j_n, fn_inv) = previous.points[p];
            let f = if geom.axis {
                geom.deformation_axi(u)
            } else {
                Matrix3::identity() + geom.gradient(u, d)
            };
            (f_n, f, j_n, Some(fn_inv), None)
        } else {
            let (h_n, h) = geom.gradients(u_n, u, d);
            let f_n = Matrix3::identity() + h_n;
            (f_n, Matrix3::identity() + h, f_n.determinant(), None, None)
        };
        let j = if geom.axis {
            Axi::of(&f).determinant()
        } else {
            f.determinant()
        };
        check_jacobians(p, j_n, j)?;
        if geom.axis {
            // The (r, z) block and θθ only (`Axi`): the same nonzero
            // values at a fraction of the 3 × 3 arithmetic (to the bit but
            // for `two_thirds_power`'s rounding of (J_n/J)^(2/3)).
            let (fa, fna) = (Axi::of(&f), Axi::of(&f_n));
            let fa_inv = fa.inverse(j);
            let fna_inv = match (&fn_inv_axi, &fn_inv) {
                (Some(k), _) => *k,
                (None, Some(m)) => Axi::of(m),
                (None, None) => fna.inverse(j_n),
            };
            let law_span = crate::profile::span(crate::profile::Phase::LawIntegration);
            let r =
                law.integrate_stress_axi(&fna, &fa, j_n, j, &fna_inv, st.internal.as_slice(), dt);
            drop(law_span);
            if let Some(r) = r {
                let out = r.map_err(|failure| ElementFailure::Law { point: p, failure })?;
                previous.axi[p] = KeptAxi {
                    f: fa,
                    j,
                    f_inv: fa_inv,
                    general: false,
                };
                // G⁰ : (τF⁻ᵀ) as below, less the products with the exact
                // zeros of the θ coupling.
                let s = out.kirchhoff.mul_t(&fa_inv);
                for a in 0..nn {
                    let ga = &geom.grad[a];
                    let v0 = (ga[0] * s.m[0][0] + ga[1] * s.m[0][1]) + geom.n_over_r[a] * s.t;
                    let v1 = ga[0] * s.m[1][0] + ga[1] * s.m[1][1];
                    forces[a * 2] += geom.dv * v0;
                    forces[a * 2 + 1] += geom.dv * v1;
                }
                // Written in place: no whole PointState moved.
                match &mut states {
                    StatesOut::Vec(v) => v.push(PointState {
                        stress: out.cauchy.to_stress(),
                        internal: out.internal,
                    }),
                    StatesOut::Slice(o) => {
                        let o = &mut o[p];
                        o.stress = out.cauchy.to_stress();
                        o.internal.assign(&out.internal);
                    }
                }
                continue;
            }
        }
        let f_inv = f.try_inverse().ok_or_else(|| ElementFailure::Inverted {
            point: p,
            message: "singular deformation gradient".into(),
        })?;
        let law_span = crate::profile::span(crate::profile::Phase::LawIntegration);
        let input = FiniteStrainInput {
            f_n,
            f_np1: f,
            internal: st.internal.as_slice(),
            dt,
            tangent: TangentKind::None,
        };
        let out = law
            .integrate_stress(&input, j_n, j, fn_inv.as_ref())
            .map_err(|failure| ElementFailure::Law { point: p, failure })?;
        drop(law_span);
        if axis {
            previous.axi[p] = KeptAxi {
                f: Axi::of(&f),
                j,
                f_inv: Axi::of(&f_inv),
                general: true,
            };
        } else {
            previous.points[p] = (f, j, f_inv);
        }
        // (G⁰F⁻¹) : τ = G⁰ : (τF⁻ᵀ), G⁰ = e_i ⊗ ∇N_a (+ N_a/r e_θ ⊗ e_θ
        // for the radial dof of AXIS), the terms in the order of
        // VGrad::dot.
        let s = out.kirchhoff * f_inv.transpose();
        for a in 0..nn {
            let ga = &geom.grad[a];
            for i in 0..d {
                let mut v = ga[0] * s[(i, 0)] + ga[1] * s[(i, 1)] + ga[2] * s[(i, 2)];
                v += if geom.axis && i == 0 {
                    geom.n_over_r[a] * s[(2, 2)]
                } else {
                    0.0 * s[(2, 2)]
                };
                forces[a * d + i] += geom.dv * v;
            }
        }
        let new = PointState {
            stress: tensor_to_stress(&out.cauchy),
            internal: out.internal,
        };
        match &mut states {
            StatesOut::Vec(v) => v.push(new),
            StatesOut::Slice(o) => o[p] = new,
        }
    }
    previous.u.extend_from_slice(u);
    Ok(())
}

/// K += dv (G_a : M_b) for every pair (a, b), `k` row-major. The inner
/// loop runs over b on the component rows of the partners, so it
/// vectorises; each entry is the same sum in the same order as G_a : M_b
/// written out, less terms that are exact zeros: the third column of G_a
/// in AXIS (∂/∂θ), and the hoop term of every dof but the radial ones of
/// AXIS.
fn add_tangent(k: &mut [f64], g: &[VGrad], mt: &[[f64; MAX_DOFS]], dv: f64, axis: bool) {
    let n = g.len();
    for (ga, row) in g.iter().zip(k.chunks_exact_mut(n)) {
        let i = ga.i;
        let [r0, r1, r2] = ga.row;
        let c0 = &mt[3 * i][..n];
        let c1 = &mt[3 * i + 1][..n];
        if !axis {
            let c2 = &mt[3 * i + 2][..n];
            for (((kb, &x0), &x1), &x2) in row.iter_mut().zip(c0).zip(c1).zip(c2) {
                *kb += dv * ((r0 * x0 + r1 * x1) + r2 * x2);
            }
        } else if ga.hoop != 0.0 {
            let h = ga.hoop;
            let c8 = &mt[8][..n];
            for (((kb, &x0), &x1), &x8) in row.iter_mut().zip(c0).zip(c1).zip(c8) {
                *kb += dv * ((r0 * x0 + r1 * x1) + h * x8);
            }
        } else {
            for ((kb, &x0), &x1) in row.iter_mut().zip(c0).zip(c1) {
                *kb += dv * (r0 * x0 + r1 * x1);
            }
        }
    }
}

/// The columns of ∂τ/∂F (bit 3k + l for ∂/∂F_kl) the element reads: in
/// AXIS a virtual gradient has no θ row or column besides θθ, so only
/// rr, rz, zr, zz and θθ.
fn tangent_columns(axis: bool) -> u16 {
    if axis {
        0b1_0001_1011
    } else {
        0b1_1111_1111
    }
}

/// Where the initial geometry of an element is invalid: a non-positive
/// Jacobian (or, in AXIS, a radius <= 0) at Gauss point `point` (0-based)
/// of `family`, which would make every later quantity of the cell NaN.
#[derive(Debug, Clone, PartialEq)]
pub struct BadPoint {
    pub family: Fpg,
    pub point: usize,
    /// What is wrong, with the value ("non-positive Jacobian -0.25").
    pub message: String,
}

/// Checks the initial geometry of an element at every Gauss point of its
/// stiffness and mass families, the points the computation will use, so
/// that an inverted cell is refused before the first step with its point
/// and value.
pub fn check_initial_geometry(spec: &ElementSpec, coords: &[[f64; 3]]) -> Result<(), BadPoint> {
    for family in [spec.rigi, spec.mass] {
        let Some(tab) = tabulated(spec.cell, family) else {
            continue;
        };
        for (p, (shape, w)) in tab.shapes.iter().zip(&tab.weights).enumerate() {
            point_geometry(spec.formulation, shape, coords, *w).map_err(|message| BadPoint {
                family,
                point: p,
                message,
            })?;
        }
    }
    Ok(())
}

/// HRZ lumped mass of an element: the consistent mass `m` (`nn·d` square,
/// node-major, directions uncoupled) to one positive mass per local dof.
/// Returns None when a diagonal entry is not positive (a degenerate
/// element: zero density or volume).
pub fn hrz_lumped(m: &nalgebra::DMatrix<f64>, d: usize) -> Option<Vec<f64>> {
    let n = m.nrows();
    if n == 0 || d == 0 || !n.is_multiple_of(d) || m.ncols() != n {
        return None;
    }
    let mut out = vec![0.0; n];
    for i in 0..d {
        let dofs: Vec<usize> = (i..n).step_by(d).collect();
        let total: f64 = dofs
            .iter()
            .flat_map(|&a| dofs.iter().map(move |&b| (a, b)))
            .map(|(a, b)| m[(a, b)])
            .sum();
        let diag: f64 = dofs.iter().map(|&a| m[(a, a)]).sum();
        if !(diag > 0.0 && total > 0.0) || dofs.iter().any(|&a| m[(a, a)] <= 0.0) {
            return None;
        }
        for &a in &dofs {
            out[a] = m[(a, a)] * total / diag;
        }
    }
    Some(out)
}

/// Consistent mass ∫ ρ Nᵀ N dV₀ on the MASS family (per radian in AXIS).
pub fn mass(
    spec: &ElementSpec,
    coords: &[[f64; 3]],
    rho: f64,
) -> Result<DMatrix<f64>, ElementFailure> {
    let tab = table(spec, spec.mass)?;
    let nn = spec.nnodes();
    let d = spec.formulation.dofs_per_node();
    check_sizes(spec, coords, true, nn * d, &[])?;
    if !(rho.is_finite() && rho >= 0.0) {
        return Err(ElementFailure::BadInput {
            message: format!("{}: density RHO = {rho} must be finite and >= 0", spec.name),
        });
    }
    let mut out = DMatrix::zeros(nn * d, nn * d);
    for (p, (shape, w)) in tab.shapes.iter().zip(&tab.weights).enumerate() {
        let geom = point_geometry(spec.formulation, shape, coords, *w)
            .map_err(|message| ElementFailure::BadGeometry { point: p, message })?;
        for a in 0..nn {
            for b in 0..nn {
                let v = rho * geom.n[a] * geom.n[b] * geom.dv;
                for i in 0..d {
                    out[(a * d + i, b * d + i)] += v;
                }
            }
        }
    }
    Ok(out)
}

/// The points of the family `fpg` of an element on the geometry `x`, each
/// as (position, dV) with dV the weight × det J (× r in AXIS: per radian;
/// per unit thickness in D_PLAN), the very measure [`mass`] and the
/// internal forces integrate with. POST_ELEM integrates densities and
/// moments of inertia with them, so that its masses are those of the
/// mass matrix. A point the geometry makes invalid is an error naming it.
pub fn point_measures(
    spec: &ElementSpec,
    x: &[[f64; 3]],
    fpg: Fpg,
) -> Result<Vec<([f64; 3], f64)>, String> {
    let t = table(spec, fpg).map_err(|e| e.to_string())?;
    if x.len() != spec.nnodes() {
        return Err(format!(
            "{}: {} node coordinates given, {} expected",
            spec.name,
            x.len(),
            spec.nnodes()
        ));
    }
    t.shapes
        .iter()
        .zip(&t.weights)
        .enumerate()
        .map(|(g, (s, &w))| {
            let pg = point_geometry(spec.formulation, s, x, w)
                .map_err(|m| format!("point {}: {m}", g + 1))?;
            let mut at = [0.0; 3];
            for (a, xa) in x.iter().enumerate() {
                for k in 0..3 {
                    at[k] += pg.n[a] * xa[k];
                }
            }
            Ok((at, pg.dv))
        })
        .collect()
}

// ------------------------------------------------------------ internals

/// The Green-Lagrange strain of the displacement gradient H (F = 1 + H):
/// E = ½(H + Hᵀ + HᵀH), as code_aster's `matG2E` (nmgr3d / nmgrla).
///
/// Written from H, not as ½(FᵀF − 1): that form subtracts 1 from entries
/// of order 1 and so carries an absolute error of about 1e-16 whatever the
/// strain, i.e. a stress noise of E·1e-16 (2e-11 MPa for steel) that does
/// not shrink with the load. Near a zero load (a bar brought back to its
/// length, DX = 3.6e-16 at t = 1.4999999999999982 of an accumulated time
/// list) that noise was 10 % of the reactions and Newton stalled at
/// RESI_GLOB_RELA 0.1 where PETIT converged (probe grotp, zeroload.comm).
/// From H the error is relative to the displacement gradient.
pub fn green_lagrange(h: &Matrix3<f64>) -> Matrix3<f64> {
    0.5 * (h + h.transpose() + h.transpose() * h)
}

/// A step that inverts a Gauss point (det F ≤ 0 at its start or end, or
/// NaN) is a failure of the element the step cutting can act on.
fn check_jacobians(p: usize, j_n: f64, j: f64) -> Result<(), ElementFailure> {
    if j_n > 0.0 && j > 0.0 {
        Ok(())
    } else {
        Err(ElementFailure::Inverted {
            point: p,
            message: format!("det F = {j} (start of step {j_n})"),
        })
    }
}

fn missing_tangent(law: LawRef) -> ElementFailure {
    ElementFailure::BadInput {
        message: format!("law {} returned no tangent", law.name()),
    }
}

fn check_law(kin: Kinematics, law: LawRef) -> Result<(), ElementFailure> {
    let ok = match (kin, law) {
        (Kinematics::Petit | Kinematics::PetitReac | Kinematics::GrotGdep, LawRef::Small(l)) => {
            l.metadata().accepts(kin.strain_measure())
        }
        (Kinematics::SimoMiehe, LawRef::SimoMiehe(_)) => true,
        (Kinematics::GdefLog, LawRef::GdefLog(l)) => l.metadata().accepts(StrainMeasure::GdefLog),
        _ => false,
    };
    if ok {
        Ok(())
    } else {
        Err(ElementFailure::BadInput {
            message: format!(
                "law {} cannot be used with DEFORMATION='{}' here",
                law.name(),
                kin.strain_measure().aster_name()
            ),
        })
    }
}

/// `coords_finite`: check that the coordinates are finite (not when
/// they are those of the geometry already computed and checked); the
/// flag of a field likewise (not when its values are known finite).
fn check_sizes(
    spec: &ElementSpec,
    coords: &[[f64; 3]],
    coords_finite: bool,
    ndof: usize,
    fields: &[(&str, &[f64], bool)],
) -> Result<(), ElementFailure> {
    if coords.len() != spec.nnodes() {
        return Err(ElementFailure::BadInput {
            message: format!(
                "{}: {} node coordinates given, {} expected",
                spec.name,
                coords.len(),
                spec.nnodes()
            ),
        });
    }
    if coords_finite && !all_finite(coords.as_flattened()) {
        return Err(ElementFailure::BadInput {
            message: format!("{}: non-finite node coordinate", spec.name),
        });
    }
    for &(name, f, finite) in fields {
        if f.len() != ndof {
            return Err(ElementFailure::BadInput {
                message: format!(
                    "{}: {name} has {} values, {ndof} expected",
                    spec.name,
                    f.len()
                ),
            });
        }
        if finite && !all_finite(f) {
            return Err(ElementFailure::BadInput {
                message: format!("{}: non-finite value in {name}", spec.name),
            });
        }
    }
    Ok(())
}

/// Whether every value is finite: x − x is +0 for a finite x and NaN for
/// an infinite or NaN one, summed in four independent lanes (a branch
/// per value cost as much as a Gauss point's hoop terms at every step).
#[allow(clippy::eq_op)] // x − x is the test itself
fn all_finite(v: &[f64]) -> bool {
    let mut acc = [0.0f64; 4];
    let mut chunks = v.chunks_exact(4);
    for c in &mut chunks {
        for k in 0..4 {
            acc[k] += c[k] - c[k];
        }
    }
    let mut r = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for x in chunks.remainder() {
        r += x - x;
    }
    r == 0.0
}

/// Shape functions tabulated at the points of one Gauss family.
#[derive(Debug)]
struct Tabulated {
    cell: CellType,
    fpg: Fpg,
    weights: Vec<f64>,
    shapes: Vec<ShapeEval>,
}

/// Every (cell, family) pair, tabulated once per process: the element loop
/// then neither rebuilds rules nor allocates.
fn tabulated(cell: CellType, fpg: Fpg) -> Option<&'static Tabulated> {
    static CACHE: OnceLock<Vec<Tabulated>> = OnceLock::new();
    CACHE
        .get_or_init(|| {
            let mut all = Vec::new();
            for c in CellType::ALL {
                for &f in families(c) {
                    if let Some(q) = rule(c, f) {
                        all.push(Tabulated {
                            cell: c,
                            fpg: f,
                            shapes: q.points.iter().map(|xi| eval(c, *xi)).collect(),
                            weights: q.weights,
                        });
                    }
                }
            }
            all
        })
        .iter()
        .find(|t| t.cell == cell && t.fpg == fpg)
}

fn table(spec: &ElementSpec, fpg: Fpg) -> Result<&'static Tabulated, ElementFailure> {
    tabulated(spec.cell, fpg).ok_or_else(|| ElementFailure::BadInput {
        message: format!(
            "{}: {} has no Gauss family {}",
            spec.name,
            spec.cell.aster_name(),
            fpg.name()
        ),
    })
}

/// Geometry of one Gauss point on some configuration.
#[derive(Debug, Clone)]
struct PointGeometry {
    axis: bool,
    n: [f64; MAX_NODES],
    /// ∇N_a with respect to the configuration's coordinates (third
    /// component 0 in AXIS).
    grad: [[f64; 3]; MAX_NODES],
    /// Radius of the point (AXIS), 0 in 3D.
    r: f64,
    /// N_a / r (AXIS; 0 in 3D): the hoop term of the radial virtual
    /// gradients, divided once here rather than at every use.
    n_over_r: [f64; MAX_NODES],
    /// Weight × det J (× r in AXIS).
    dv: f64,
}

/// A virtual gradient e_i ⊗ row + hoop·e_θ ⊗ e_θ: one row of a 3×3
/// matrix plus, in AXIS, the θθ term. Keeping that structure instead of a
/// dense 3×3 divides the cost of the element tangent (ndof² contractions
/// per Gauss point) by three; it is preserved by G ↦ G F⁻¹ because F is
/// block-diagonal (rz | θ) in AXIS.
#[derive(Clone, Copy, Debug)]
struct VGrad {
    i: usize,
    row: [f64; 3],
    hoop: f64,
}

impl VGrad {
    const ZERO: VGrad = VGrad {
        i: 0,
        row: [0.0; 3],
        hoop: 0.0,
    };

    fn matrix(&self) -> Matrix3<f64> {
        let mut g = Matrix3::zeros();
        for k in 0..3 {
            g[(self.i, k)] = self.row[k];
        }
        g[(2, 2)] += self.hoop;
        g
    }

    /// G : M
    #[inline]
    fn dot(&self, m: &Matrix3<f64>) -> f64 {
        let i = self.i;
        self.row[0] * m[(i, 0)]
            + self.row[1] * m[(i, 1)]
            + self.row[2] * m[(i, 2)]
            + self.hoop * m[(2, 2)]
    }

    /// G F⁻¹ (AXIS: F⁻¹ has no θ coupling, so the hoop term only scales).
    fn times(&self, f_inv: &Matrix3<f64>, axis: bool) -> VGrad {
        let mut row = [0.0; 3];
        for (l, r) in row.iter_mut().enumerate() {
            *r = (0..3).map(|k| self.row[k] * f_inv[(k, l)]).sum();
        }
        let hoop = if axis {
            self.hoop * f_inv[(2, 2)]
        } else {
            debug_assert!(self.hoop == 0.0);
            0.0
        };
        VGrad {
            i: self.i,
            row,
            hoop,
        }
    }

    /// The SIMO_MIEHE tangent partner of `self` = G⁰ (initial virtual
    /// gradient) with `sp` = G⁰F⁻¹: M = (∂τ/∂F : G⁰) − τ spᵀ, where
    /// `c` holds ∂τ/∂F (row 3i+j, column 3k+l). Only the columns of `c`
    /// that G⁰ selects are read. Written into `mt[·][k]`; in AXIS only
    /// the components [`add_tangent`] reads (rr, rz, zr, zz, θθ).
    fn tangent_partner_into(
        &self,
        sp: &VGrad,
        c: &SMatrix<f64, 9, 9>,
        tau: &Matrix3<f64>,
        axis: bool,
        mt: &mut [[f64; MAX_DOFS]],
        k: usize,
    ) {
        // ∂τ/∂F : G⁰, the columns of c that G⁰ selects.
        let mut dtau = [0.0; 9];
        for l in 0..3 {
            let w = self.row[l];
            if w != 0.0 {
                let col = c.column(3 * self.i + l);
                for (r, v) in dtau.iter_mut().enumerate() {
                    *v += col[r] * w;
                }
            }
        }
        if self.hoop != 0.0 {
            let col = c.column(8);
            for (r, v) in dtau.iter_mut().enumerate() {
                *v += col[r] * self.hoop;
            }
        }
        // − τ spᵀ: row j of τ against sp's row in column sp.i, and the
        // hoop term in column 2.
        let t =
            |j: usize| tau[(j, 0)] * sp.row[0] + tau[(j, 1)] * sp.row[1] + tau[(j, 2)] * sp.row[2];
        if axis {
            // sp.i is r or z: the θ column only holds the hoop term.
            for j in 0..2 {
                let tj = t(j);
                for col in 0..2 {
                    let mut v = dtau[3 * j + col];
                    if col == sp.i {
                        v -= tj;
                    }
                    mt[3 * j + col][k] = v;
                }
            }
            mt[8][k] = dtau[8] - tau[(2, 2)] * sp.hoop;
        } else {
            for j in 0..3 {
                let tj = t(j);
                for col in 0..3 {
                    let mut v = dtau[3 * j + col];
                    if col == sp.i {
                        v -= tj;
                    }
                    if col == 2 {
                        v -= tau[(j, 2)] * sp.hoop;
                    }
                    mt[3 * j + col][k] = v;
                }
            }
        }
    }
}

impl PointGeometry {
    /// ∇(N_a e_i): e_i ⊗ ∇N_a, plus N_a/r in θθ for the radial dof.
    fn virtual_gradient(&self, a: usize, i: usize) -> VGrad {
        VGrad {
            i,
            row: self.grad[a],
            hoop: if self.axis && i == 0 {
                self.n_over_r[a]
            } else {
                0.0
            },
        }
    }

    /// [`PointGeometry::gradient`] of two fields in one pass over the
    /// nodes (each sum in the same order).
    fn gradients(&self, v: &[f64], w: &[f64], d: usize) -> (Matrix3<f64>, Matrix3<f64>) {
        let mut hv = Matrix3::zeros();
        let mut hw = Matrix3::zeros();
        // As in `gradient`: AXIS skips ∇N's θ component (exact zeros).
        let nk = if self.axis { 2 } else { 3 };
        for a in 0..v.len() / d {
            let ga = &self.grad[a];
            for i in 0..d {
                for k in 0..nk {
                    hv[(i, k)] += v[a * d + i] * ga[k];
                    hw[(i, k)] += w[a * d + i] * ga[k];
                }
            }
            if self.axis {
                hv[(2, 2)] += v[a * d] * self.n[a] / self.r;
                hw[(2, 2)] += w[a * d] * self.n[a] / self.r;
            }
        }
        (hv, hw)
    }

    /// 1 + [`PointGeometry::gradient`] of an AXIS displacement (2 per
    /// node), written out for the (r, z) block and θθ: the same sums in
    /// the same order.
    fn deformation_axi(&self, v: &[f64]) -> Matrix3<f64> {
        let (mut h00, mut h01, mut h10, mut h11, mut ht) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (a, x) in v.chunks_exact(2).enumerate() {
            let g = &self.grad[a];
            h00 += x[0] * g[0];
            h01 += x[0] * g[1];
            h10 += x[1] * g[0];
            h11 += x[1] * g[1];
            ht += x[0] * self.n[a] / self.r;
        }
        Matrix3::new(1.0 + h00, h01, 0.0, h10, 1.0 + h11, 0.0, 0.0, 0.0, 1.0 + ht)
    }

    /// Gradient of the interpolated field `v` (node-major, `d` per node).
    fn gradient(&self, v: &[f64], d: usize) -> Matrix3<f64> {
        let mut h = Matrix3::zeros();
        // In AXIS ∇N has no θ component: the terms skipped are v·0 added
        // to +0 (+0 whatever the sign of v), so the sums are unchanged.
        let nk = if self.axis { 2 } else { 3 };
        for a in 0..v.len() / d {
            for i in 0..d {
                for k in 0..nk {
                    h[(i, k)] += v[a * d + i] * self.grad[a][k];
                }
            }
            if self.axis {
                h[(2, 2)] += v[a * d] * self.n[a] / self.r;
            }
        }
        h
    }
}

/// Determinant and inverse of the 2D Jacobian J[k][l] = ∂x_k/∂ξ_l of
/// the (x, y) or (r, z) plane, shared by AXIS, D_PLAN and the 2D measures
/// of the load integrals.
pub(crate) fn jacobian_2d(x: &[[f64; 3]], dn: &[[f64; 3]]) -> Result<(f64, [[f64; 2]; 2]), String> {
    let mut j = [[0.0; 2]; 2];
    for (xa, dna) in x.iter().zip(dn) {
        for k in 0..2 {
            for l in 0..2 {
                j[k][l] += xa[k] * dna[l];
            }
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if det.is_nan() || det <= 0.0 {
        return Err(format!("non-positive Jacobian {det}"));
    }
    Ok((
        det,
        [
            [j[1][1] / det, -j[0][1] / det],
            [-j[1][0] / det, j[0][0] / det],
        ],
    ))
}

/// The radius Σ N_a r_a of an AXIS point, which must be positive (Gauss
/// points are interior, so a valid mesh has r > 0 there).
pub(crate) fn gauss_radius(n: &[f64], x: &[[f64; 3]]) -> Result<f64, String> {
    let mut r = 0.0;
    for (na, xa) in n.iter().zip(x) {
        r += na * xa[0];
    }
    if r.is_nan() || r <= 0.0 {
        return Err(format!("Gauss point at radius {r} <= 0"));
    }
    Ok(r)
}

/// Determinant and inverse of the 3D Jacobian J[k][l] = ∂x_k/∂ξ_l
/// (inv[(l, k)] = ∂ξ_l/∂x_k) of nodes `x` with reference derivatives `dn`;
/// one home for every 3D element, so the refusal of a folded cell reads
/// the same whichever element meets it.
pub(crate) fn jacobian_3d(x: &[[f64; 3]], dn: &[[f64; 3]]) -> Result<(f64, Matrix3<f64>), String> {
    let mut j = Matrix3::<f64>::zeros();
    for (xa, dna) in x.iter().zip(dn) {
        for k in 0..3 {
            for l in 0..3 {
                j[(k, l)] += xa[k] * dna[l];
            }
        }
    }
    let det = j.determinant();
    if det.is_nan() || det <= 0.0 {
        return Err(format!("non-positive Jacobian {det}"));
    }
    let inv = j
        .try_inverse()
        .ok_or_else(|| "singular Jacobian".to_string())?;
    Ok((det, inv))
}

/// Maps the reference derivatives to the configuration with node
/// positions `x`; the error message says what is wrong with it.
fn point_geometry(
    formulation: Formulation,
    s: &ShapeEval,
    x: &[[f64; 3]],
    w: f64,
) -> Result<PointGeometry, String> {
    let nn = x.len();
    let mut out = PointGeometry {
        axis: formulation == Formulation::Axis,
        n: [0.0; MAX_NODES],
        n_over_r: [0.0; MAX_NODES],
        grad: [[0.0; 3]; MAX_NODES],
        r: 0.0,
        dv: 0.0,
    };
    out.n[..nn].copy_from_slice(s.n());
    let dn = s.dn();
    match formulation {
        Formulation::Solid3d => {
            let (det, inv) = jacobian_3d(x, dn)?;
            // ∇ₓN = J⁻ᵀ ∇_ξ N
            for a in 0..nn {
                for k in 0..3 {
                    out.grad[a][k] = (0..3).map(|l| inv[(l, k)] * dn[a][l]).sum();
                }
            }
            out.dv = w * det;
        }
        Formulation::PlaneStrain | Formulation::PlaneStress | Formulation::Axis => {
            let (det, inv) = jacobian_2d(x, dn)?;
            // An AXIS point also needs its radius, checked after det J as
            // it always was; D_PLAN is AXIS without it (per unit thickness).
            let r = if formulation == Formulation::Axis {
                gauss_radius(&out.n[..nn], x)?
            } else {
                1.0
            };
            for a in 0..nn {
                for k in 0..2 {
                    out.grad[a][k] = inv[0][k] * dn[a][0] + inv[1][k] * dn[a][1];
                }
            }
            if formulation == Formulation::Axis {
                out.r = r;
                for a in 0..nn {
                    out.n_over_r[a] = out.n[a] / r;
                }
                out.dv = w * det * r;
            } else {
                out.dv = w * det;
            }
        }
    }
    Ok(out)
}
