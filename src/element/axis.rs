//! Axisymmetric QUAD8 element for small strains (DEFORMATION='PETIT'):
//! code_aster's MEAXQU8 (AXIS, FPG9) and MEAXQS8 (AXIS_SI, FPG4, no
//! stabilisation), both with the FPG9 mass.
//!
//! Coordinates: x is the radius r, y is the axial z (code_aster AXIS).
//! Degrees of freedom per node: (u_r, u_z) = (DX, DY), node-major.
//! Strain and stress components are the first four of the 6-vector
//! convention of [`crate::law::voigt`], read as (rr, zz, θθ, rz): the hoop
//! component sits in the "zz" slot, as SIZZ does in code_aster's AXIS
//! output. The hoop strain is u_r / r.
//!
//! Integrals are **per radian**: the weight is r dr dz, without 2π, as in
//! code_aster (forces, reactions and masses of an AXIS model are per
//! radian; multiply by 2π for the full ring).

use nalgebra::{SMatrix, SVector};

use crate::law::{Mat6, SmallStrainBehaviour, SmallStrainInput, TangentKind, Vec6};
use crate::mesh::quadrature::{rule, Fpg};
use crate::mesh::shape::eval;
use crate::mesh::CellType;

// Shared with the generic element interface, which supersedes this module
// for the engine (it also covers PETIT_REAC and SIMO_MIEHE).
pub use super::mechanics::{ElementFailure, PointState};

pub const NODES: usize = 8;
pub const DOFS: usize = 16;

pub type ElemVec = SVector<f64, DOFS>;
pub type ElemMat = SMatrix<f64, DOFS, DOFS>;
/// Rows ε_rr, ε_zz, ε_θθ, γ_rz; columns the 16 dofs.
pub type BMatrix = SMatrix<f64, 4, DOFS>;

/// AXIS (full, FPG9) or AXIS_SI (reduced, FPG4) on QUAD8.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisModelisation {
    Axis,
    AxisSi,
}

impl AxisModelisation {
    /// Family for stiffness and internal forces (code_aster's RIGI).
    pub fn rigi(self) -> Fpg {
        match self {
            AxisModelisation::Axis => Fpg::Fpg9,
            AxisModelisation::AxisSi => Fpg::Fpg4,
        }
    }
    /// Family for the mass (code_aster's MASS): FPG9 for both.
    pub fn mass(self) -> Fpg {
        Fpg::Fpg9
    }
}

/// Geometry of one Gauss point on the current cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussPoint {
    /// Radius of the point.
    pub r: f64,
    /// Quadrature weight × det J × r (per radian).
    pub weight: f64,
    pub n: [f64; NODES],
    /// ∂N/∂r, ∂N/∂z.
    pub dn: [[f64; 2]; NODES],
}

/// The Gauss points of family `fpg` on a QUAD8 with nodes `coords` (r, z),
/// MED node order.
pub fn gauss_points(
    coords: &[[f64; 2]; NODES],
    fpg: Fpg,
) -> Result<Vec<GaussPoint>, ElementFailure> {
    let q = rule(CellType::Quad8, fpg).ok_or_else(|| ElementFailure::BadGeometry {
        point: 0,
        message: format!("QUAD8 has no Gauss family {}", fpg.name()),
    })?;
    let mut out = Vec::with_capacity(q.len());
    for (g, (xi, w)) in q.points.iter().zip(&q.weights).enumerate() {
        let s = eval(CellType::Quad8, *xi);
        // J = [∂r/∂ξ ∂r/∂η; ∂z/∂ξ ∂z/∂η]
        let mut j = [[0.0; 2]; 2];
        let mut r = 0.0;
        for (a, x) in coords.iter().enumerate() {
            r += s.n()[a] * x[0];
            let d = s.dn()[a];
            j[0][0] += x[0] * d[0];
            j[0][1] += x[0] * d[1];
            j[1][0] += x[1] * d[0];
            j[1][1] += x[1] * d[1];
        }
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det.is_nan() || det <= 0.0 {
            return Err(ElementFailure::BadGeometry {
                point: g,
                message: format!("non-positive Jacobian {det}"),
            });
        }
        if r.is_nan() || r <= 0.0 {
            return Err(ElementFailure::BadGeometry {
                point: g,
                message: format!("Gauss point at radius {r} <= 0"),
            });
        }
        // ∇ₓN = J⁻ᵀ ∇_ξ N
        let inv = [
            [j[1][1] / det, -j[0][1] / det],
            [-j[1][0] / det, j[0][0] / det],
        ];
        let mut n = [0.0; NODES];
        let mut dn = [[0.0; 2]; NODES];
        for a in 0..NODES {
            n[a] = s.n()[a];
            let d = s.dn()[a];
            dn[a] = [
                inv[0][0] * d[0] + inv[1][0] * d[1],
                inv[0][1] * d[0] + inv[1][1] * d[1],
            ];
        }
        out.push(GaussPoint {
            r,
            weight: w * det * r,
            n,
            dn,
        });
    }
    Ok(out)
}

/// Small-strain B matrix: (ε_rr, ε_zz, ε_θθ, γ_rz) = B u.
pub fn b_matrix(g: &GaussPoint) -> BMatrix {
    let mut b = BMatrix::zeros();
    for a in 0..NODES {
        let (ur, uz) = (2 * a, 2 * a + 1);
        b[(0, ur)] = g.dn[a][0];
        b[(1, uz)] = g.dn[a][1];
        b[(2, ur)] = g.n[a] / g.r;
        b[(3, ur)] = g.dn[a][1];
        b[(3, uz)] = g.dn[a][0];
    }
    b
}

/// Internal forces, optional stiffness and the new Gauss-point states.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementResponse {
    pub forces: ElemVec,
    pub stiffness: Option<ElemMat>,
    pub states: Vec<PointState>,
}

/// Integrates the law at every RIGI point for the displacement increment
/// `du` (from the states `states` at the start of the step) and assembles
/// ∫ Bᵀσ r dr dz and, if requested, ∫ Bᵀ D B r dr dz.
pub fn internal_forces(
    model: AxisModelisation,
    coords: &[[f64; 2]; NODES],
    du: &ElemVec,
    states: &[PointState],
    law: &dyn SmallStrainBehaviour,
    dt: f64,
    tangent: TangentKind,
) -> Result<ElementResponse, ElementFailure> {
    let points = gauss_points(coords, model.rigi())?;
    if states.len() != points.len() {
        return Err(ElementFailure::StateCount {
            expected: points.len(),
            got: states.len(),
        });
    }
    let mut forces = ElemVec::zeros();
    let mut stiffness = (tangent != TangentKind::None).then(ElemMat::zeros);
    let mut new_states = Vec::with_capacity(points.len());
    for (g, (gp, st)) in points.iter().zip(states).enumerate() {
        let b = b_matrix(gp);
        let de4 = b * du;
        let de = Vec6::new(de4[0], de4[1], de4[2], de4[3], 0.0, 0.0);
        let law_span = crate::profile::span(crate::profile::Phase::LawIntegration);
        let out = law
            .integrate(&SmallStrainInput {
                stress: st.stress,
                internal: st.internal.as_slice(),
                strain_increment: de,
                dt,
                tangent,
            })
            .map_err(|failure| ElementFailure::Law { point: g, failure })?;
        drop(law_span);
        let s4 = SVector::<f64, 4>::new(out.stress[0], out.stress[1], out.stress[2], out.stress[3]);
        forces += b.transpose() * s4 * gp.weight;
        if let (Some(k), Some(d)) = (stiffness.as_mut(), out.tangent) {
            let d4 = axis_block(&d);
            *k += b.transpose() * d4 * b * gp.weight;
        }
        new_states.push(PointState {
            stress: out.stress,
            internal: out.internal,
        });
    }
    Ok(ElementResponse {
        forces,
        stiffness,
        states: new_states,
    })
}

/// The (rr, zz, θθ, rz) block of a 6×6 tangent.
fn axis_block(d: &Mat6) -> SMatrix<f64, 4, 4> {
    d.fixed_view::<4, 4>(0, 0).into_owned()
}

/// Consistent mass ∫ ρ Nᵀ N r dr dz (per radian), on FPG9.
pub fn mass(
    model: AxisModelisation,
    coords: &[[f64; 2]; NODES],
    rho: f64,
) -> Result<ElemMat, ElementFailure> {
    let mut m = ElemMat::zeros();
    for gp in gauss_points(coords, model.mass())? {
        for a in 0..NODES {
            for b in 0..NODES {
                let v = rho * gp.n[a] * gp.n[b] * gp.weight;
                m[(2 * a, 2 * b)] += v;
                m[(2 * a + 1, 2 * b + 1)] += v;
            }
        }
    }
    Ok(m)
}
