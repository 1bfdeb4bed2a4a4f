//! AFFE_CHAR_MECA/PRES_REP on skin cells: the consistent nodal forces
//! f_a = −∫ p n N_a dS of a uniform pressure p on one edge (AXIS) or face
//! (3D), on the initial geometry (a dead load, code_aster's FIXE_CSTE).
//!
//! The normal is code_aster's (`nmpr2d`/`nmpr3d`): in AXIS the tangent
//! t = ∂x/∂ξ of the edge turned clockwise, n ∝ (t_z, −t_r), i.e. the
//! outward normal of an edge of a counter-clockwise cell; in 3D
//! n ∝ ∂x/∂ξ × ∂x/∂η, outward for the node order ORIE_PEAU_3D gives a
//! skin. A positive pressure therefore pushes into the solid. In AXIS the
//! integral is weighted by r without 2π (per radian), like every nodal
//! force there; in D_PLAN it is per unit thickness (the same edge normal,
//! no weight).

use crate::mesh::quadrature::{rule, Fpg};
use crate::mesh::shape::{eval, ShapeEval};
use crate::mesh::CellType;
use crate::model::spec::Formulation;

/// The Gauss family that integrates the force exactly on straight edges
/// and flat faces: N_a·r is of degree 4 on a SEG3 (FPG3 is exact to 5),
/// N_a of degree 2 on a QUAD8 face times a bilinear Jacobian (FPG9), N_a
/// of degree 2 on a TRIA6 (FPG6, degree 4).
pub(super) fn family(cell: CellType) -> Option<Fpg> {
    match cell {
        CellType::Seg2 | CellType::Seg3 => Some(Fpg::Fpg3),
        CellType::Tria3 | CellType::Tria6 => Some(Fpg::Fpg6),
        CellType::Quad4 | CellType::Quad8 => Some(Fpg::Fpg9),
        _ => None,
    }
}

/// At a point of a skin cell with shape values `s` and node positions
/// `coords`: the tangents ∂x/∂ξ and ∂x/∂η (the second is zero on an edge)
/// and the radius Σ N_a x_a, the ingredients of every load on a skin.
pub(crate) fn skin_tangents(s: &ShapeEval, coords: &[[f64; 3]]) -> ([f64; 3], [f64; 3], f64) {
    let mut t1 = [0.0; 3];
    let mut t2 = [0.0; 3];
    let mut r = 0.0;
    for (a, g) in s.dn().iter().enumerate() {
        r += s.n()[a] * coords[a][0];
        for k in 0..3 {
            t1[k] += coords[a][k] * g[0];
            t2[k] += coords[a][k] * g[1];
        }
    }
    (t1, t2, r)
}

/// The nodal forces of the pressure `p` on the skin cell `cell` (node-major,
/// 2 components per node in AXIS and D_PLAN, 3 in 3D) with node
/// coordinates `coords` (MED order). A SEG is an edge of a 2D model, a
/// TRIA/QUAD a 3D face; any other
/// combination is an error, as is a degenerate cell or, in AXIS, a Gauss
/// point at r < 0.
pub fn pressure_forces(
    cell: CellType,
    formulation: Formulation,
    coords: &[[f64; 3]],
    p: f64,
) -> Result<Vec<f64>, String> {
    if !p.is_finite() {
        return Err(format!("PRES = {p} must be finite"));
    }
    pressure_forces_with(cell, formulation, coords, |_| Ok(p))
}

/// The nodal forces −∫ p(x) n N_a dS of a pressure that varies over the
/// cell (AFFE_CHAR_MECA_F/PRES_REP), `pressure` giving p at each Gauss
/// point's position; the family, normal and checks of
/// [`pressure_forces`] (which is this with a constant p).
pub fn pressure_forces_with(
    cell: CellType,
    formulation: Formulation,
    coords: &[[f64; 3]],
    pressure: impl Fn([f64; 3]) -> Result<f64, String>,
) -> Result<Vec<f64>, String> {
    // A 2D model's edges; in AXIS their measure carries the radius.
    let axis = formulation == Formulation::Axis;
    let plane = formulation != Formulation::Solid3d;
    let nn = cell.nnodes();
    if coords.len() != nn {
        return Err(format!(
            "{}: {} node coordinates for {nn} nodes",
            cell.aster_name(),
            coords.len()
        ));
    }
    let want = if plane { 1 } else { 2 };
    let fpg = family(cell).filter(|_| cell.dim() == want).ok_or_else(|| {
        format!(
            "a pressure acts on {} cells of an {} model, not on a {}",
            if plane {
                "SEG2/SEG3"
            } else {
                "TRIA3/TRIA6/QUAD4/QUAD8"
            },
            formulation.label(),
            cell.aster_name()
        )
    })?;
    let q =
        rule(cell, fpg).ok_or_else(|| format!("{} has no family {fpg:?}", cell.aster_name()))?;
    let d = if plane { 2 } else { 3 };
    let mut out = vec![0.0; nn * d];
    for (xi, w) in q.points.iter().zip(&q.weights) {
        let s = eval(cell, *xi);
        let (t1, t2, r) = skin_tangents(&s, coords);
        // the normal scaled by the surface (or length × r) per unit
        // reference measure
        let nds: [f64; 3] = if axis {
            if r.is_nan() || r < 0.0 {
                return Err(format!("Gauss point at radius {r} < 0"));
            }
            [t1[1] * r, -t1[0] * r, 0.0]
        } else if plane {
            [t1[1], -t1[0], 0.0]
        } else {
            [
                t1[1] * t2[2] - t1[2] * t2[1],
                t1[2] * t2[0] - t1[0] * t2[2],
                t1[0] * t2[1] - t1[1] * t2[0],
            ]
        };
        let norm = nds.iter().map(|v| v * v).sum::<f64>().sqrt();
        if (norm.is_nan() || norm <= 0.0) && !(axis && r == 0.0) {
            return Err(format!("degenerate {} (zero Jacobian)", cell.aster_name()));
        }
        let p = pressure(super::body_force::point_position(s.n(), coords))?;
        if !p.is_finite() {
            return Err(format!("PRES = {p} must be finite"));
        }
        for (a, &na) in s.n().iter().enumerate() {
            for i in 0..d {
                out[a * d + i] -= p * nds[i] * na * w;
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, scale: f64) -> bool {
        (a - b).abs() <= 1e-13 * scale
    }

    /// A QUAD8 on the plane z = 2 spanning [0, a] × [0, b], turning
    /// counter-clockwise seen from +z: n = +z. The serendipity split of a
    /// uniform load: −1/12 of the total on each corner, +1/3 on each
    /// mid-side node; the total is −p A n.
    #[test]
    fn quad8_uniform_pressure_is_the_serendipity_split() {
        let (a, b, p) = (3.0, 2.0, 5.0);
        let v = [[0., 0., 2.], [a, 0., 2.], [a, b, 2.], [0., b, 2.]];
        let mut x = v.to_vec();
        for k in 0..4 {
            let (u, w) = (v[k], v[(k + 1) % 4]);
            x.push([(u[0] + w[0]) / 2.0, (u[1] + w[1]) / 2.0, 2.0]);
        }
        let f = pressure_forces(CellType::Quad8, Formulation::Solid3d, &x, p).unwrap();
        let total = -p * a * b;
        let scale = p * a * b;
        for n in 0..8 {
            let expect = if n < 4 { -total / 12.0 } else { total / 3.0 };
            assert!(
                close(f[3 * n + 2], expect, scale),
                "node {n}: {}",
                f[3 * n + 2]
            );
            assert!(close(f[3 * n], 0.0, scale) && close(f[3 * n + 1], 0.0, scale));
        }
        let sum: f64 = (0..8).map(|n| f[3 * n + 2]).sum();
        assert!(close(sum, total, scale), "{sum}");
    }

    /// A QUAD4 on a tilted plane: each node gets a quarter of −p A n, with
    /// n = e1 × e2 / |e1 × e2| of its edges.
    #[test]
    fn quad4_uniform_pressure_is_a_quarter_per_node() {
        let e1 = [2.0, 0.5, 1.0];
        let e2 = [-0.4, 1.5, 0.3];
        let o = [1.0, -2.0, 0.5];
        let at = |s: f64, t: f64| [0, 1, 2].map(|k| o[k] + s * e1[k] + t * e2[k]);
        let x = [at(0., 0.), at(1., 0.), at(1., 1.), at(0., 1.)];
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let p = -7.0;
        let f = pressure_forces(CellType::Quad4, Formulation::Solid3d, &x, p).unwrap();
        for n in 0..4 {
            for i in 0..3 {
                // |c| n = c: −p A n / 4 = −p c / 4
                assert!(
                    close(f[3 * n + i], -p * c[i] / 4.0, 10.0),
                    "{n} {i}: {}",
                    f[3 * n + i]
                );
            }
        }
    }

    /// A TRIA6 face: the corners carry nothing, the mid-sides a third each.
    #[test]
    fn tria6_uniform_pressure_goes_to_the_mid_side_nodes() {
        let v = [[0., 0., 0.], [0., 4., 0.], [0., 0., 3.]];
        let mut x = v.to_vec();
        for k in 0..3 {
            let (u, w) = (v[k], v[(k + 1) % 3]);
            x.push([0.0, (u[1] + w[1]) / 2.0, (u[2] + w[2]) / 2.0]);
        }
        // n = +x (e_y × e_z), A = 6
        let f = pressure_forces(CellType::Tria6, Formulation::Solid3d, &x, 2.0).unwrap();
        for n in 0..6 {
            let expect = if n < 3 { 0.0 } else { -2.0 * 6.0 / 3.0 };
            assert!(close(f[3 * n], expect, 12.0), "node {n}: {}", f[3 * n]);
        }
    }

    /// An AXIS SEG3 parallel to the axis at radius r, from z0 to z0 + L
    /// (going up: n = +r). Per radian the total is −p L r along r, split
    /// 1/6, 1/6, 2/3 (r is constant on the edge).
    #[test]
    fn axis_seg3_parallel_to_the_axis() {
        let (r, l, p) = (2.5, 4.0, 3.0);
        let x = [[r, 1.0, 0.], [r, 1.0 + l, 0.], [r, 1.0 + l / 2.0, 0.]];
        let f = pressure_forces(CellType::Seg3, Formulation::Axis, &x, p).unwrap();
        let total = -p * l * r;
        for (n, share) in [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0].iter().enumerate() {
            assert!(close(f[2 * n], share * total, 30.0), "{n}: {}", f[2 * n]);
            assert!(close(f[2 * n + 1], 0.0, 30.0));
        }
    }

    /// An AXIS SEG2 on a radial edge from r1 to r2 at height h (going
    /// outward: n = −z). Per radian the total is p (r2² − r1²)/2 along +z,
    /// node a getting p ∫ N_a r dr: (2 r1 + r2) and (r1 + 2 r2) × p (r2 − r1)/6.
    #[test]
    fn axis_seg2_radial_edge_has_the_r_weighting() {
        let (r1, r2, p) = (1.0, 4.0, 2.0);
        let x = [[r1, 5.0, 0.], [r2, 5.0, 0.]];
        let f = pressure_forces(CellType::Seg2, Formulation::Axis, &x, p).unwrap();
        let c = p * (r2 - r1) / 6.0;
        assert!(close(f[1], c * (2.0 * r1 + r2), 30.0), "{}", f[1]);
        assert!(close(f[3], c * (r1 + 2.0 * r2), 30.0), "{}", f[3]);
        assert!(close(f[1] + f[3], p * (r2 * r2 - r1 * r1) / 2.0, 30.0));
        assert!(close(f[0], 0.0, 30.0) && close(f[2], 0.0, 30.0));
    }

    /// D_PLAN: the same edge as the AXIS test above, no weight r: the
    /// total is p (r2 − r1) along +z, shared (1/2, 1/2) by a SEG2 and
    /// (1/6, 1/6, 2/3) by a SEG3.
    #[test]
    fn plane_strain_edges_are_per_unit_thickness() {
        let (r1, r2, p) = (1.0, 4.0, 2.0);
        let x = [[r1, 5.0, 0.], [r2, 5.0, 0.]];
        let f = pressure_forces(CellType::Seg2, Formulation::PlaneStrain, &x, p).unwrap();
        let total = p * (r2 - r1);
        assert!(close(f[1], total / 2.0, 30.0) && close(f[3], total / 2.0, 30.0));
        assert!(close(f[0], 0.0, 30.0) && close(f[2], 0.0, 30.0));
        let x3 = [[r1, 5.0, 0.], [r2, 5.0, 0.], [0.5 * (r1 + r2), 5.0, 0.]];
        let f = pressure_forces(CellType::Seg3, Formulation::PlaneStrain, &x3, p).unwrap();
        for (k, share) in [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0].iter().enumerate() {
            assert!(
                close(f[2 * k + 1], share * total, 30.0),
                "{k}: {}",
                f[2 * k + 1]
            );
        }
        let e = pressure_forces(CellType::Quad4, Formulation::PlaneStrain, &[[0.0; 3]; 4], p)
            .unwrap_err();
        assert!(e.contains("D_PLAN") && e.contains("SEG2/SEG3"), "{e}");
    }

    #[test]
    fn wrong_cell_for_the_model_is_an_error() {
        let x = [[0., 0., 0.], [1., 0., 0.]];
        let e = pressure_forces(CellType::Seg2, Formulation::Solid3d, &x, 1.0).unwrap_err();
        assert!(e.contains("TRIA3/TRIA6/QUAD4/QUAD8"), "{e}");
        let e = pressure_forces(
            CellType::Seg2,
            Formulation::Axis,
            &[[1., 0., 0.], [1., 0., 0.]],
            1.0,
        )
        .unwrap_err();
        assert!(e.contains("degenerate"), "{e}");
    }
}
