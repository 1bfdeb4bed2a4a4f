//! MECA_HEXS8, the element of `MODELISATION='3D_SI'` on HEXA8: a one-point
//! hexahedron whose twelve hourglass modes are stabilised by assumed
//! strains in the style of Belytschko & Bindeman, "Assumed strain
//! stabilization of the eight node hexahedral element", CMAME 105 (1993)
//! 225-260, as code_aster builds it (shared/docs/notes/hexs8.md, the
//! formula-level reading of te0407/nmas3d/calcdq/cast3d).
//!
//! # Why one law call and 72 extra numbers
//! The law is integrated once per element, at the centre. Alone that
//! leaves 12 zero-energy (hourglass) modes; the assumed hourglass strains
//! ε̃_g = B_N,g u, integrated on the 2×2×2 points, give them a stiffness.
//! Their stress is not recomputed from the strain: generalised hourglass
//! stresses Q (6 components × 4 modes × 3 gradient directions = 72) are
//! carried from step to step and updated with the law's current tangent,
//! Q⁺ = Q⁻ + D·E(q(Δu)), so the hourglass stiffness softens with the
//! material. ADS (deviatoric) projection for every law but ELAS, ASQBI
//! (bending-exact, needs ν) for ELAS, as code_aster chooses by law name.
//!
//! # State layout
//! The engine's per-element state has [`STATE_ROWS`] rows: row 0 is the
//! centre point (σ, internal variables), rows 1..=12 hold Q six at a time
//! (flat index k = 12·i + 3·α + j, i the stress component, α the mode, j
//! the gradient direction; row 1 + k/6, component k%6), with a copy of
//! the centre's internal variables so that reductions over rows stay
//! right. Q thus travels with the state through step rejection,
//! archiving and ETAT_INIT continuation; SIEF_ELGA shows it as one point
//! of 78 components (SIXX..SIYZ, FSTAB1..FSTAB72) as in code_aster.
//!
//! # Two variants ([`Variant`])
//! The default, [`Variant::Published`], is the method of the paper:
//! centre strain from the mean gradient b̄ with weight V, hourglass
//! gradients from the centre Jacobian (true index order, weight J₀ per
//! point, so they are orthogonal to the constant strains and the patch
//! test passes on distorted meshes), the law's tangent applied in Voigt
//! form (shear μ), force and stiffness exact derivatives of each other.
//! [`Variant::CodeAster`] reproduces the departures listed in the note
//! (§13): point gradient at the centre, K_c weighted 8J₀ but the centre
//! force V, per-point Jacobians with the transposed index order, the
//! Mandel tangent on engineering hourglass strains (shear 2μ), the cross
//! terms in the force, B0_M in the stiffness cross terms and the lower
//! triangle mirrored. It is selected for a whole run with the
//! environment variable `ASTER_HEXS8=CODE_ASTER`, to measure what the
//! departures change (docs/laws-elements.md).
//!
//! # Frame
//! The inclusion rules of the hourglass shears (γxy takes no ξη mode, γxz
//! no ξζ, γyz no ηζ) are what keeps the bending modes free of shear
//! locking, and they hold only in axes that follow ξ, η, ζ. Written in
//! global axes (as code_aster does, note §14.1) they lock a cantilever
//! whose cells are numbered from another corner (+31 % instead of −7 %).
//! The published variant therefore computes the element in its own frame,
//! the rotation of the polar decomposition of the centre Jacobian, as the
//! paper does in its corotational frame: coordinates, increments and the
//! centre stress are turned into it, the law is called there (every law
//! this element takes is isotropic), Q is kept there (FSTAB are
//! components in the element's frame), and the stress, forces and
//! stiffness are turned back. The law's tensorial internal variables
//! (`LawMetadata::tensor_variables`: VMIS_CINE_LINE's back stress) go in
//! and out with the stress, so that VARI_ELGA is in global axes as
//! SIEF_ELGA is (they once stayed in the element's frame: XCINXX and
//! XCINYY swapped on a cell with ξ along y). Under PETIT_REAC the frame
//! follows the element, so Q turns with it, and the centre stress of the
//! start of the step is taken in the frame of that start: a rigid
//! rotation over a step rotates σ and Q (a corotational update, objective
//! to the order of the spurious strain I − sym ΔR of PETIT_REAC; code_aster
//! rotates neither). An element whose ξ, η, ζ run along x, y, z is
//! computed in global axes, to the bit as before.
//!
//! # Tangent
//! The stiffness is the material one (∂f/∂u at fixed geometry): for
//! PETIT_REAC the change of the working geometry with u is not
//! differentiated, as in code_aster; Newton then converges linearly in the
//! geometric part, which is small over one step.

use std::sync::OnceLock;

use nalgebra::{DMatrix, DVector, Matrix3, SMatrix};

use super::mechanics::{
    jacobian_3d, ElementFailure, ElementResponse, Kinematics, LawRef, PointState,
};
use crate::law::{InternalVars, Mat6, SmallStrainInput, TangentKind, Vec6};
use crate::mesh::quadrature::{rule, Fpg};
use crate::mesh::shape::{eval, reference_nodes, ShapeEval};
use crate::mesh::CellType;
use crate::model::spec::ElementSpec;

/// Rows of engine state per element: the centre point and 12 rows of Q.
pub const STATE_ROWS: usize = 13;
/// Number of generalised hourglass stresses (FSTAB1..FSTAB72).
pub const NQ: usize = 72;
/// code_aster's element name.
pub const NAME: &str = crate::model::spec::HEXS8_NAME;

type B = SMatrix<f64, 6, 24>;
type K24 = SMatrix<f64, 24, 24>;

/// Which formulation of the stabilisation (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    /// Belytschko & Bindeman (1993), consistent.
    Published,
    /// code_aster 15.x te0407/nmas3d with its departures (note §13).
    CodeAster,
}

impl Variant {
    /// The variant of this process: `ASTER_HEXS8=CODE_ASTER` selects
    /// [`Variant::CodeAster`]; anything else (or nothing) the published one.
    pub fn current() -> Variant {
        static V: OnceLock<Variant> = OnceLock::new();
        *V.get_or_init(|| match std::env::var("ASTER_HEXS8") {
            Ok(v) if v.eq_ignore_ascii_case("CODE_ASTER") => Variant::CodeAster,
            _ => Variant::Published,
        })
    }
}

/// The hourglass strain projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Assumed deviatoric strain (every law but ELAS).
    Ads,
    /// Assumed strain quintessential bending incompatible (ELAS), with ν.
    Asqbi { nu: f64 },
}

/// How to compute the element (the defaults are [`Options::current`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    pub variant: Variant,
    /// False drops the hourglass part: the bare one-point element, whose
    /// 12 hourglass modes have no stiffness (for the spectrum test).
    pub stabilise: bool,
    /// Forces a projection instead of the law-name rule.
    pub projection: Option<Projection>,
}

impl Options {
    pub fn current() -> Options {
        Options {
            variant: Variant::current(),
            stabilise: true,
            projection: None,
        }
    }
}

/// Virgin state rows of one element.
pub fn initial_states(law: LawRef) -> Vec<PointState> {
    vec![
        PointState {
            stress: Vec6::zeros(),
            internal: law.initial_internal(),
        };
        STATE_ROWS
    ]
}

/// Q (72 numbers, flat index 12·i + 3·α + j) from the state rows.
pub fn hourglass_stresses(states: &[PointState]) -> [f64; NQ] {
    let mut q = [0.0; NQ];
    for (k, v) in q.iter_mut().enumerate() {
        *v = states[1 + k / 6].stress[k % 6];
    }
    q
}

/// The engine entry point: [`internal_forces_with`] with [`Options::current`].
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
    internal_forces_with(
        Options::current(),
        spec,
        kin,
        coords,
        u_n,
        u,
        states_n,
        law,
        dt,
        tangent,
    )
}

/// Internal forces, tangent (unless [`TangentKind::None`]) and new state
/// rows for the step u_n → u. Same contract as
/// [`super::mechanics::internal_forces`].
#[allow(clippy::too_many_arguments)]
pub fn internal_forces_with(
    opts: Options,
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
    let bad = |message: String| ElementFailure::BadInput { message };
    if spec.cell != CellType::Hexa8 {
        return Err(bad(format!(
            "{NAME} needs a HEXA8 cell, got {}",
            spec.cell.aster_name()
        )));
    }
    if coords.len() != 8 || u_n.len() != 24 || u.len() != 24 {
        return Err(bad(format!(
            "{NAME}: 8 nodes and 24 dofs expected, got {} nodes, {} and {} dofs",
            coords.len(),
            u_n.len(),
            u.len()
        )));
    }
    if coords
        .iter()
        .flatten()
        .chain(u_n)
        .chain(u)
        .any(|v| !v.is_finite())
    {
        return Err(bad(format!(
            "{NAME}: non-finite coordinate or displacement"
        )));
    }
    if states_n.len() != STATE_ROWS {
        return Err(ElementFailure::StateCount {
            expected: STATE_ROWS,
            got: states_n.len(),
        });
    }
    let LawRef::Small(l) = law else {
        return Err(bad(format!(
            "{NAME} accepts only DEFORMATION='PETIT' or 'PETIT_REAC' (ELEMENTSSI_1)"
        )));
    };
    if !matches!(kin, Kinematics::Petit | Kinematics::PetitReac) {
        return Err(bad(format!(
            "{NAME} accepts only DEFORMATION='PETIT' or 'PETIT_REAC', not '{}' (ELEMENTSSI_1)",
            kin.strain_measure().aster_name()
        )));
    }
    let projection = match opts.projection {
        Some(p) => p,
        None if l.metadata().name == "ELAS" => {
            let nu = l
                .elastic_params()
                .ok_or_else(|| bad(format!("{NAME}: law ELAS without NU (ELEMENTS4_72)")))?
                .nu;
            Projection::Asqbi { nu }
        }
        None => Projection::Ads,
    };

    let mut x = [[0.0; 3]; 8];
    let mut du = [0.0; 24];
    for a in 0..8 {
        for i in 0..3 {
            x[a][i] = coords[a][i]
                + if kin == Kinematics::PetitReac {
                    u[3 * a + i]
                } else {
                    0.0
                };
        }
    }
    for k in 0..24 {
        du[k] = u[k] - u_n[k];
    }
    // The published variant works in the element's own frame (module doc,
    // "Frame"): coordinates and increments in, stress in and out.
    let frame = match opts.variant {
        Variant::Published => element_frame(&x),
        Variant::CodeAster => None,
    };
    // The centre stress of the start of the step is turned into the frame
    // the element had then (PETIT_REAC: the frame of X + u_n), so that a
    // rotation of the element over the step rotates its stress: the update
    // is corotational, as Q is.
    let frame_n = match (opts.variant, kin) {
        (Variant::Published, Kinematics::PetitReac) => {
            let mut xn = [[0.0; 3]; 8];
            for a in 0..8 {
                for i in 0..3 {
                    xn[a][i] = coords[a][i] + u_n[3 * a + i];
                }
            }
            element_frame(&xn)
        }
        _ => frame,
    };
    let mut sigma_n = states_n[0].stress;
    // The law's tensorial internal variables (VMIS_CINE_LINE's back
    // stress) are stored in global axes, as the stress: they go into the
    // frame with it and come back with it below. Without this they were
    // stored in the element's frame and VARI_ELGA showed, on a cell
    // numbered with ξ along y, XCINXX and XCINYY swapped.
    let tensors = l.metadata().tensor_variables;
    let mut internal_n = states_n[0].internal;
    if let Some(r) = &frame_n {
        sigma_n = rotate_stress(&r.transpose(), &sigma_n);
        rotate_tensor_variables(&r.transpose(), tensors, &mut internal_n);
    }
    if let Some(r) = &frame {
        for a in 0..8 {
            let xl = r.transpose() * nalgebra::Vector3::from(x[a]);
            let dl =
                r.transpose() * nalgebra::Vector3::new(du[3 * a], du[3 * a + 1], du[3 * a + 2]);
            for i in 0..3 {
                x[a][i] = xl[i];
                du[3 * a + i] = dl[i];
            }
        }
    }
    let geom = Geometry::new(&x, opts.variant).map_err(|(point, message)| {
        if kin == Kinematics::PetitReac {
            ElementFailure::Inverted { point, message }
        } else {
            ElementFailure::BadGeometry { point, message }
        }
    })?;

    // The law, once, at the centre. RAPH_MECA is promoted to FULL_MECA:
    // the Q update needs a tangent.
    let deps = geom.b0 * nalgebra::SVector::<f64, 24>::from_column_slice(&du);
    let law_tangent = if tangent == TangentKind::None {
        TangentKind::Consistent
    } else {
        tangent
    };
    let out = {
        let _span = crate::profile::span(crate::profile::Phase::LawIntegration);
        l.integrate(&SmallStrainInput {
            stress: sigma_n,
            internal: internal_n.as_slice(),
            strain_increment: deps,
            dt,
            tangent: law_tangent,
        })
        .map_err(|failure| ElementFailure::Law { point: 0, failure })?
    };
    let dv = out
        .tangent
        .ok_or_else(|| bad(format!("law {} returned no tangent", l.metadata().name)))?;
    let sigma = out.stress;

    // The tangent the hourglass part uses: Voigt (published) or Mandel
    // applied to engineering strains (code_aster, note §13.3).
    let p_inv = Mat6::from_diagonal(&Vec6::new(
        1.0,
        1.0,
        1.0,
        std::f64::consts::SQRT_2,
        std::f64::consts::SQRT_2,
        std::f64::consts::SQRT_2,
    ));
    let dh = match opts.variant {
        Variant::Published => dv,
        Variant::CodeAster => p_inv * dv * p_inv,
    };

    let mut forces = SMatrix::<f64, 24, 1>::zeros();
    let mut kmat = K24::zeros();
    let want_k = tangent != TangentKind::None;
    // Centre part.
    forces += geom.b0.transpose() * (sigma * geom.vol);
    if want_k {
        kmat += geom.b0.transpose() * dv * geom.b0 * geom.w0;
    }

    let mut q_new = hourglass_stresses(states_n);
    if opts.stabilise {
        let e = e_vectors(projection);
        // q_α = γ_α · Δu (3-vector per mode), then ΔQ_{·,α,j} = D E^{αj}(q_α).
        let mut qa = [[0.0; 3]; 4];
        for (al, q) in qa.iter_mut().enumerate() {
            for (a, g) in geom.gamma[al].iter().enumerate() {
                for i in 0..3 {
                    q[i] += g * du[3 * a + i];
                }
            }
        }
        for al in 0..4 {
            for j in 0..3 {
                let mut ej = Vec6::zeros();
                for l in 0..3 {
                    ej += e[al][j][l] * qa[al][l];
                }
                let dq = dh * ej;
                for i in 0..6 {
                    q_new[12 * i + 3 * al + j] += dq[i];
                }
            }
        }
        let p = Mat6::from_diagonal(&Vec6::new(
            1.0,
            1.0,
            1.0,
            std::f64::consts::FRAC_1_SQRT_2,
            std::f64::consts::FRAC_1_SQRT_2,
            std::f64::consts::FRAC_1_SQRT_2,
        ));
        for g in 0..8 {
            let bn = geom.bn(g, &e);
            let mut s = Vec6::zeros();
            for al in 0..4 {
                for j in 0..3 {
                    let c = geom.c[g][al][j];
                    for i in 0..6 {
                        s[i] += c * q_new[12 * i + 3 * al + j];
                    }
                }
            }
            let w = geom.wg[g];
            match opts.variant {
                Variant::Published => {
                    forces += bn.transpose() * (s * w);
                    if want_k {
                        kmat += bn.transpose() * dh * bn * w;
                    }
                }
                Variant::CodeAster => {
                    forces += bn.transpose() * ((sigma + s) * w) + geom.b0.transpose() * (s * w);
                    if want_k {
                        let b0m = p * geom.b0;
                        kmat += (bn.transpose() * dh * bn
                            + bn.transpose() * dh * b0m
                            + b0m.transpose() * dh * bn)
                            * w;
                    }
                }
            }
        }
        if want_k && opts.variant == Variant::CodeAster {
            // cast3d fills the lower triangle only and mirrors it.
            for r in 0..24 {
                for c in r + 1..24 {
                    kmat[(r, c)] = kmat[(c, r)];
                }
            }
        }
    }

    let mut sigma = sigma;
    let mut internal = out.internal;
    if let Some(r) = &frame {
        sigma = rotate_stress(r, &sigma);
        rotate_tensor_variables(r, tensors, &mut internal);
        let mut rb = K24::zeros();
        for a in 0..8 {
            rb.fixed_view_mut::<3, 3>(3 * a, 3 * a).copy_from(r);
        }
        forces = rb * forces;
        if want_k {
            kmat = rb * kmat * rb.transpose();
        }
    }
    let mut states = Vec::with_capacity(STATE_ROWS);
    states.push(PointState {
        stress: sigma,
        internal,
    });
    for r in 0..12 {
        let mut s = Vec6::zeros();
        for c in 0..6 {
            s[c] = q_new[6 * r + c];
        }
        states.push(PointState {
            stress: s,
            internal,
        });
    }
    Ok(ElementResponse {
        forces: DVector::from_column_slice(forces.as_slice()),
        stiffness: want_k.then(|| DMatrix::from_column_slice(24, 24, kmat.as_slice())),
        states,
    })
}

/// The element's frame: the rotation R of the polar decomposition
/// J₀ = R U of the centre Jacobian (columns ∂x/∂ξ, ∂x/∂η, ∂x/∂ζ), so that
/// the local axes follow ξ, η, ζ as closely as a rotation can. `None` when
/// J₀ is diagonal and positive (ξ, η, ζ along x, y, z: R = I, and the
/// element is computed in global axes to the bit) or not invertible (the
/// geometry check then reports it).
fn element_frame(x: &[[f64; 3]; 8]) -> Option<Matrix3<f64>> {
    let dn = reference().centre.dn();
    let mut j0 = Matrix3::<f64>::zeros();
    for a in 0..8 {
        for i in 0..3 {
            for k in 0..3 {
                j0[(i, k)] += x[a][i] * dn[a][k];
            }
        }
    }
    let aligned = (0..3).all(|i| (0..3).all(|k| i == k || j0[(i, k)] == 0.0))
        && (0..3).all(|i| j0[(i, i)] > 0.0);
    let det: f64 = j0.determinant();
    if aligned || det.is_nan() || det <= 0.0 {
        return None;
    }
    let svd = nalgebra::SVD::<f64, nalgebra::U3, nalgebra::U3>::new(j0, true, true);
    let (w, vt) = (svd.u?, svd.v_t?);
    Some(w * vt)
}

/// R σ Rᵀ on stress components.
fn rotate_stress(r: &Matrix3<f64>, s: &Vec6) -> Vec6 {
    let t = crate::law::voigt::stress_to_tensor(s);
    crate::law::voigt::tensor_to_stress(&(r * t * r.transpose()))
}

/// R X Rᵀ on each tensorial internal variable (six components from the
/// given indices, stored as a stress is: `LawMetadata::tensor_variables`).
fn rotate_tensor_variables(r: &Matrix3<f64>, starts: &[usize], v: &mut InternalVars) {
    let v = v.as_mut_slice();
    for &k in starts {
        if k + 6 <= v.len() {
            let t = rotate_stress(r, &Vec6::from_column_slice(&v[k..k + 6]));
            v[k..k + 6].copy_from_slice(t.as_slice());
        }
    }
}

/// E^{αj}(e_l) for every mode α, gradient direction j and displacement
/// direction l (note §4.7): normal part n^{αj}_i δ_jl, shear parts by the
/// mode's inclusion rules, the same for both projections.
fn e_vectors(projection: Projection) -> [[[Vec6; 3]; 3]; 4] {
    let third = 1.0 / 3.0;
    let normals: [[[f64; 3]; 3]; 4] = match projection {
        Projection::Ads => {
            let n = [
                [2.0 * third, -third, -third],
                [-third, 2.0 * third, -third],
                [-third, -third, 2.0 * third],
            ];
            [n; 4]
        }
        Projection::Asqbi { nu } => {
            let nb = nu / (1.0 - nu);
            [
                [[1.0, -nu, -nu], [0.0, 1.0, -nb], [0.0, -nb, 1.0]],
                [[1.0, 0.0, -nb], [-nu, 1.0, -nu], [-nb, 0.0, 1.0]],
                [[1.0, -nb, 0.0], [-nb, 1.0, 0.0], [-nu, -nu, 1.0]],
                [[1.0, -nu, -nu], [-nu, 1.0, -nu], [-nu, -nu, 1.0]],
            ]
        }
    };
    // Shear component (3: xy, 4: xz, 5: yz) of the pair of directions, and
    // whether mode α feeds it: γxy has no ξη mode, γxz no ξζ, γyz no ηζ.
    let shear = |a: usize, b: usize| match (a.min(b), a.max(b)) {
        (0, 1) => 3,
        (0, 2) => 4,
        _ => 5,
    };
    let feeds = |al: usize, comp: usize| match comp {
        3 => al == 0 || al == 1,
        4 => al == 0 || al == 2,
        _ => al == 1 || al == 2,
    };
    let mut out = [[[Vec6::zeros(); 3]; 3]; 4];
    for al in 0..4 {
        for j in 0..3 {
            for l in 0..3 {
                let v = &mut out[al][j][l];
                if l == j {
                    for i in 0..3 {
                        v[i] = normals[al][j][i];
                    }
                } else {
                    let comp = shear(j, l);
                    if feeds(al, comp) {
                        v[comp] = 1.0;
                    }
                }
            }
        }
    }
    out
}

/// The 8 reference points of FPG8 and their shape functions.
struct Reference {
    centre: ShapeEval,
    points: Vec<[f64; 3]>,
    weights: Vec<f64>,
    shapes: Vec<ShapeEval>,
    /// h_α at the nodes (MED order): ηζ, ξζ, ξη, ξηζ.
    h: [[f64; 8]; 4],
}

fn reference() -> &'static Reference {
    static R: OnceLock<Reference> = OnceLock::new();
    R.get_or_init(|| {
        let q = rule(CellType::Hexa8, Fpg::Fpg8).expect("HEXA8 has FPG8");
        let nodes = reference_nodes(CellType::Hexa8);
        let mut h = [[0.0; 8]; 4];
        for (a, p) in nodes.iter().enumerate() {
            h[0][a] = p[1] * p[2];
            h[1][a] = p[0] * p[2];
            h[2][a] = p[0] * p[1];
            h[3][a] = p[0] * p[1] * p[2];
        }
        Reference {
            centre: eval(CellType::Hexa8, [0.0; 3]),
            shapes: q.points.iter().map(|p| eval(CellType::Hexa8, *p)).collect(),
            points: q.points,
            weights: q.weights,
            h,
        }
    })
}

/// The displacement gradient Grad u of the centre point, in global axes,
/// on the cell `x` (initial coordinates) for the nodal displacements `u`
/// (3 per node): the gradient whose symmetric part is the strain the law
/// sees at the element's one point (b̄ for the published variant, the
/// point gradient at ξ = 0 for code_aster's), so that CALC_CHAMP's
/// EPSI_ELGA of a HEXS8 cell is the strain of its SIEF_ELGA.
pub fn centre_gradient(x: &[[f64; 3]; 8], u: &[f64]) -> Result<Matrix3<f64>, String> {
    let geom = Geometry::new(x, Variant::current())
        .map_err(|(point, m)| format!("point {}: {m}", point + 1))?;
    let mut h = Matrix3::zeros();
    for (a, g) in geom.centre.iter().enumerate() {
        for i in 0..3 {
            for k in 0..3 {
                h[(i, k)] += u[3 * a + i] * g[k];
            }
        }
    }
    Ok(h)
}

/// ∂h_α/∂ξ at ξ.
fn dh_dxi(p: &[f64; 3]) -> [[f64; 3]; 4] {
    let (xi, eta, zeta) = (p[0], p[1], p[2]);
    [
        [0.0, zeta, eta],
        [zeta, 0.0, xi],
        [eta, xi, 0.0],
        [eta * zeta, xi * zeta, xi * eta],
    ]
}

/// Jacobian determinant and inverse (inv[(l, k)] = ∂ξ_l/∂x_k).
fn jacobian(s: &ShapeEval, x: &[[f64; 3]; 8]) -> Result<(f64, Matrix3<f64>), String> {
    jacobian_3d(x, s.dn())
}

fn gradient(s: &ShapeEval, inv: &Matrix3<f64>) -> [[f64; 3]; 8] {
    let dn = s.dn();
    let mut g = [[0.0; 3]; 8];
    for a in 0..8 {
        for k in 0..3 {
            g[a][k] = (0..3).map(|l| inv[(l, k)] * dn[a][l]).sum();
        }
    }
    g
}

/// The element's geometric operators on one configuration.
struct Geometry {
    /// ∇N_a of the centre strain (b̄ or the point gradient at ξ = 0).
    centre: [[f64; 3]; 8],
    /// Engineering strain operator of the centre (of `centre`).
    b0: B,
    /// Weight of the centre stiffness (V or 8J₀).
    w0: f64,
    /// Volume V (weight of the centre force).
    vol: f64,
    /// γ_α (per node).
    gamma: [[f64; 8]; 4],
    /// c_αj(g): hourglass-function gradients at the 8 points.
    c: [[[f64; 3]; 4]; 8],
    /// Weights of the hourglass integration.
    wg: [f64; 8],
}

impl Geometry {
    fn new(x: &[[f64; 3]; 8], variant: Variant) -> Result<Geometry, (usize, String)> {
        let r = reference();
        let (j0, inv0) = jacobian(&r.centre, x).map_err(|m| (0, format!("at the centre: {m}")))?;
        let grad0 = gradient(&r.centre, &inv0);
        let mut vol = 0.0;
        let mut bbar = [[0.0; 3]; 8];
        let mut jg = [0.0; 8];
        let mut invg = [Matrix3::zeros(); 8];
        for g in 0..8 {
            let (det, inv) = jacobian(&r.shapes[g], x).map_err(|m| (g, m))?;
            let w = r.weights[g] * det;
            let gr = gradient(&r.shapes[g], &inv);
            for a in 0..8 {
                for k in 0..3 {
                    bbar[a][k] += w * gr[a][k];
                }
            }
            vol += w;
            jg[g] = w;
            invg[g] = inv;
        }
        for b in bbar.iter_mut().flatten() {
            *b /= vol;
        }
        let gamma = gamma_vectors(x, &bbar);
        let mut c = [[[0.0; 3]; 4]; 8];
        let mut wg = [0.0; 8];
        for g in 0..8 {
            let dh = dh_dxi(&r.points[g]);
            for al in 0..4 {
                for j in 0..3 {
                    c[g][al][j] = match variant {
                        // true gradient with the centre Jacobian
                        Variant::Published => (0..3).map(|k| dh[al][k] * inv0[(k, j)]).sum(),
                        // nmas3d: the point's inverse Jacobian, transposed
                        Variant::CodeAster => (0..3).map(|k| dh[al][k] * invg[g][(j, k)]).sum(),
                    };
                }
            }
            wg[g] = match variant {
                Variant::Published => r.weights[g] * j0,
                Variant::CodeAster => jg[g],
            };
        }
        let (centre, w0) = match variant {
            Variant::Published => (bbar, vol),
            Variant::CodeAster => (grad0, 8.0 * j0),
        };
        Ok(Geometry {
            centre,
            b0: strain_operator(&centre),
            w0,
            vol,
            gamma,
            c,
            wg,
        })
    }

    /// B_N,g, the 6×24 engineering hourglass strain operator at point g.
    fn bn(&self, g: usize, e: &[[[Vec6; 3]; 3]; 4]) -> B {
        let mut b = B::zeros();
        for al in 0..4 {
            for j in 0..3 {
                let c = self.c[g][al][j];
                if c == 0.0 {
                    continue;
                }
                for a in 0..8 {
                    let w = c * self.gamma[al][a];
                    for l in 0..3 {
                        let col = 3 * a + l;
                        for i in 0..6 {
                            b[(i, col)] += w * e[al][j][l][i];
                        }
                    }
                }
            }
        }
        b
    }
}

/// γ_αI = (h_αI − Σ_j (Σ_J h_αJ x_Jj) g_jI) / 8 with the gradient table
/// `g` (b̄ in te0407, the centre point gradient in te0392): each vanishes
/// on every linear field as long as `g` reproduces linear fields.
fn gamma_vectors(x: &[[f64; 3]; 8], g: &[[f64; 3]; 8]) -> [[f64; 8]; 4] {
    let h = &reference().h;
    let mut gamma = [[0.0; 8]; 4];
    for al in 0..4 {
        let mut hx = [0.0; 3];
        for a in 0..8 {
            for j in 0..3 {
                hx[j] += h[al][a] * x[a][j];
            }
        }
        for a in 0..8 {
            gamma[al][a] = (h[al][a] - (0..3).map(|j| hx[j] * g[a][j]).sum::<f64>()) / 8.0;
        }
    }
    gamma
}

/// Engineering strain operator of a gradient table (xx, yy, zz, γxy, γxz, γyz).
fn strain_operator(grad: &[[f64; 3]; 8]) -> B {
    let mut b = B::zeros();
    for (a, g) in grad.iter().enumerate() {
        let (cx, cy, cz) = (3 * a, 3 * a + 1, 3 * a + 2);
        b[(0, cx)] = g[0];
        b[(1, cy)] = g[1];
        b[(2, cz)] = g[2];
        b[(3, cx)] = g[1];
        b[(3, cy)] = g[0];
        b[(4, cx)] = g[2];
        b[(4, cz)] = g[0];
        b[(5, cy)] = g[2];
        b[(5, cz)] = g[1];
    }
    b
}

/// code_aster's RIGI_MECA of MECA_HEXS8 (te0392, note §10.2): the linear
/// elastic stiffness of MECA_STATIQUE (and of modal analyses). It is not
/// the tangent of [`internal_forces`] with an elastic law: Hooke's matrix
/// C in Voigt form (shear μ) on both sides, the ASQBI projection with
/// ν = NU whatever the law, γ built with the point gradient at the
/// centre, the true hourglass gradients at each of the 2×2×2 points with
/// their own Jacobian and weight J_g, and the cross terms kept:
///
/// K = 8J₀ B0ᵀ C B0 + Σ_g J_g [B_Nᵀ C B_N + B_Nᵀ C B0 + B0ᵀ C B_N].
///
/// Under the published variant (the default) the element is computed in
/// its own frame, as [`internal_forces`] is (module doc, "Frame"), so that
/// the answer does not depend on how a cell is numbered; an element whose
/// ξ, η, ζ run along x, y, z is computed in global axes, which is exactly
/// te0392. `Variant::CodeAster` keeps code_aster's global axes for every
/// cell. The matrix is symmetric, with 6 zero eigenvalues (rigid modes).
pub fn rigi_meca(
    coords: &[[f64; 3]],
    young: f64,
    nu: f64,
    variant: Variant,
) -> Result<DMatrix<f64>, ElementFailure> {
    let mut x = hexa8_coords(coords)?;
    if !(young.is_finite() && young > 0.0 && nu.is_finite() && nu > -1.0 && nu < 0.5) {
        return Err(ElementFailure::BadInput {
            message: format!(
                "{NAME}: RIGI_MECA needs E > 0 and -1 < NU < 0.5, got E = {young}, NU = {nu}"
            ),
        });
    }
    let frame = match variant {
        Variant::Published => element_frame(&x),
        Variant::CodeAster => None,
    };
    if let Some(r) = &frame {
        for p in x.iter_mut() {
            let l = r.transpose() * nalgebra::Vector3::from(*p);
            *p = [l[0], l[1], l[2]];
        }
    }
    let geom = rigi_geometry(&x)?;
    let c = hooke(young, nu);
    let e = e_vectors(Projection::Asqbi { nu });
    let mut k = geom.b0.transpose() * c * geom.b0 * geom.w0;
    for g in 0..8 {
        let bn = geom.bn(g, &e);
        let cb0 = c * geom.b0;
        k += (bn.transpose() * c * bn + bn.transpose() * cb0 + cb0.transpose() * bn) * geom.wg[g];
    }
    if let Some(r) = &frame {
        let mut rb = K24::zeros();
        for a in 0..8 {
            rb.fixed_view_mut::<3, 3>(3 * a, 3 * a).copy_from(r);
        }
        k = rb * k * rb.transpose();
    }
    Ok(DMatrix::from_column_slice(24, 24, k.as_slice()))
}

/// code_aster's SIEF_ELGA of MECA_HEXS8 in a linear computation (te0022,
/// note §10.3): σ = C B0 u with B0 the point gradient at the centre, the
/// element's one point; no hourglass stress (FSTAB) is computed. The
/// centre strain is a tensor, so no frame is involved.
pub fn rigi_meca_stress(
    coords: &[[f64; 3]],
    young: f64,
    nu: f64,
    u: &[f64],
) -> Result<Vec6, ElementFailure> {
    let x = hexa8_coords(coords)?;
    if u.len() != 24 || u.iter().any(|v| !v.is_finite()) {
        return Err(ElementFailure::BadInput {
            message: format!("{NAME}: 24 finite displacements expected, got {}", u.len()),
        });
    }
    let geom = rigi_geometry(&x)?;
    let eps = geom.b0 * nalgebra::SVector::<f64, 24>::from_column_slice(u);
    Ok(hooke(young, nu) * eps)
}

/// The 8 nodes of a HEXA8, checked finite.
fn hexa8_coords(coords: &[[f64; 3]]) -> Result<[[f64; 3]; 8], ElementFailure> {
    if coords.len() != 8 || coords.iter().flatten().any(|v| !v.is_finite()) {
        return Err(ElementFailure::BadInput {
            message: format!(
                "{NAME}: 8 finite node coordinates expected, got {}",
                coords.len()
            ),
        });
    }
    let mut x = [[0.0; 3]; 8];
    x.copy_from_slice(coords);
    Ok(x)
}

/// Hooke's matrix in Voigt form (engineering shears, C_44 = μ).
fn hooke(young: f64, nu: f64) -> Mat6 {
    let lambda = young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = young / (2.0 * (1.0 + nu));
    crate::law::voigt::isotropic_elastic(lambda + 2.0 * mu / 3.0, mu)
}

/// te0392's operators: the centre point gradient (in B0 and in γ), weight
/// 8J₀, and the true hourglass gradients at each point with weight J_g.
fn rigi_geometry(x: &[[f64; 3]; 8]) -> Result<Geometry, ElementFailure> {
    let bad = |(point, message): (usize, String)| ElementFailure::BadGeometry { point, message };
    let r = reference();
    let (j0, inv0) = jacobian(&r.centre, x).map_err(|m| bad((0, format!("at the centre: {m}"))))?;
    let grad0 = gradient(&r.centre, &inv0);
    let gamma = gamma_vectors(x, &grad0);
    let mut c = [[[0.0; 3]; 4]; 8];
    let mut wg = [0.0; 8];
    let mut vol = 0.0;
    for g in 0..8 {
        let (det, inv) = jacobian(&r.shapes[g], x).map_err(|m| bad((g, m)))?;
        let dh = dh_dxi(&r.points[g]);
        for al in 0..4 {
            for j in 0..3 {
                c[g][al][j] = (0..3).map(|k| dh[al][k] * inv[(k, j)]).sum();
            }
        }
        wg[g] = r.weights[g] * det;
        vol += wg[g];
    }
    Ok(Geometry {
        centre: grad0,
        b0: strain_operator(&grad0),
        w0: 8.0 * j0,
        vol,
        gamma,
        c,
        wg,
    })
}
