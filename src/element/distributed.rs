//! AFFE_CHAR_MECA FORCE_FACE, FORCE_ARETE, FORCE_CONTOUR and
//! FORCE_INTERNE: the consistent nodal forces f_a = ∫ f N_a dΩ of a
//! uniform force density f (global frame) over a face, an edge or a
//! volume, on the initial geometry (dead loads, code_aster's FIXE_CSTE).
//!
//! Consistent means the load is shared by the shape functions, not
//! equally between the nodes: on a QUAD8 or TRIA6 face under a uniform
//! density the corner nodes get a negative or zero share and the mid-side
//! nodes the rest, as in code_aster (its FORCE_FACE elements integrate
//! N_a the same way). The total is f times the measure of the cell.
//!
//! Skin cells use the Gauss families of PRES_REP ([`super::pressure`]),
//! which integrate the force exactly on straight edges and flat faces;
//! volume cells use the mass family of PESANTEUR
//! ([`super::body_force::element_body_force`] with ρ = 1), so that
//! FORCE_INTERNE = ρ g d gives the same nodal forces as PESANTEUR (its
//! consistent form: with the lumped mass of an explicit run PESANTEUR is
//! the lumped mass times g, `body_force`, and FORCE_INTERNE stays this). In
//! AXIS every integral carries r without 2π (per radian), like every
//! nodal force there; in D_PLAN it is per unit thickness.

use super::body_force::element_body_force_with;
use crate::mesh::quadrature::rule;
use crate::mesh::shape::eval;
use crate::mesh::{CellType, Mesh};
use crate::model::spec::Formulation;
use crate::model::{CellRole, DistributedForce, DistributedKind, Model};

/// The nodal forces of the density `f` per unit measure of the skin cell
/// `cell` (node-major, 2 components per node in 2D, 3 in 3D), node
/// coordinates `coords` in MED order: per unit length × r on a SEG of an
/// AXIS model, per unit length on a SEG of a D_PLAN model (per unit
/// thickness) or of a 3D model, per unit area on a TRIA/QUAD of a 3D
/// model. Any other combination, a degenerate cell and, in AXIS, a Gauss
/// point at r < 0 are errors.
pub fn skin_force(
    cell: CellType,
    formulation: Formulation,
    coords: &[[f64; 3]],
    f: [f64; 3],
) -> Result<Vec<f64>, String> {
    if f.iter().any(|v| !v.is_finite()) {
        return Err(format!("force density {f:?} must be finite"));
    }
    skin_force_with(cell, formulation, coords, |_| Ok(f))
}

/// The nodal forces ∫ f(x) N_a dΓ of a density that varies over the skin
/// cell (AFFE_CHAR_MECA_F/FORCE_FACE, FORCE_ARETE, FORCE_CONTOUR),
/// `density` giving f at each Gauss point's position; the family, measure
/// and checks of [`skin_force`] (which is this with a constant f).
pub fn skin_force_with(
    cell: CellType,
    formulation: Formulation,
    coords: &[[f64; 3]],
    density: impl Fn([f64; 3]) -> Result<[f64; 3], String>,
) -> Result<Vec<f64>, String> {
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
    let fits = match cell.dim() {
        1 => true,
        2 => !plane,
        _ => false,
    };
    let fpg = super::pressure::family(cell)
        .filter(|_| fits)
        .ok_or_else(|| {
            format!(
                "a distributed force acts on {} cells of an {} model, not on a {}",
                if plane {
                    "SEG2/SEG3"
                } else {
                    "SEG2/SEG3 (per length) or TRIA3/TRIA6/QUAD4/QUAD8 (per area)"
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
        let (t1, t2, r) = super::pressure::skin_tangents(&s, coords);
        let norm = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
        // the measure per unit reference measure
        let dm = if cell.dim() == 1 {
            norm(t1)
        } else {
            norm([
                t1[1] * t2[2] - t1[2] * t2[1],
                t1[2] * t2[0] - t1[0] * t2[2],
                t1[0] * t2[1] - t1[1] * t2[0],
            ])
        };
        if dm.is_nan() || dm <= 0.0 {
            return Err(format!("degenerate {} (zero Jacobian)", cell.aster_name()));
        }
        let dm = if axis {
            if r.is_nan() || r < 0.0 {
                return Err(format!("Gauss point at radius {r} < 0"));
            }
            dm * r
        } else {
            dm
        };
        let f = density(super::body_force::point_position(s.n(), coords))?;
        if f.iter().any(|v| !v.is_finite()) {
            return Err(format!("force density {f:?} must be finite"));
        }
        for (a, &na) in s.n().iter().enumerate() {
            for i in 0..d {
                out[a * d + i] += f[i] * na * dm * w;
            }
        }
    }
    Ok(out)
}

/// Adds the nodal forces of `forces` to `out` (full vector, dof
/// `node·ndpn + component`). FORCE_INTERNE acts on the volume elements of
/// its cells, the other keywords on the skin cells (AFFE_CHAR_MECA has
/// checked the kinds; a cell of another role is skipped).
pub fn add_distributed_forces(
    mesh: &Mesh,
    model: &Model,
    forces: &[DistributedForce],
    out: &mut [f64],
) -> Result<(), String> {
    for df in forces {
        add_distributed_forces_with(mesh, model, df.kind, &df.cells, |_| Ok(df.force), out)?;
    }
    Ok(())
}

/// The formulation the loads of `model` are integrated in.
pub fn load_formulation(model: &Model) -> Formulation {
    model
        .formulation()
        .unwrap_or(if model.ndof_per_node() == 2 {
            Formulation::Axis
        } else {
            Formulation::Solid3d
        })
}

/// Adds to `out` the nodal forces of the density `density(x)` of kind
/// `kind` on `cells` (AFFE_CHAR_MECA_F, whose values are functions of the
/// position; [`add_distributed_forces`] is this with a constant).
pub fn add_distributed_forces_with(
    mesh: &Mesh,
    model: &Model,
    kind: DistributedKind,
    cells: &[usize],
    density: impl Fn([f64; 3]) -> Result<[f64; 3], String>,
    out: &mut [f64],
) -> Result<(), String> {
    add_cell_forces(
        mesh,
        model,
        cells,
        kind.keyword(),
        out,
        |role, cell, f, coords| cell_force(kind, role, cell, f, coords, &density),
    )
}

/// The nodal forces of the density `density(x)` of kind `kind` on one
/// cell of role `role` (node-major), or `None` when that cell carries no
/// such load: FORCE_INTERNE loads volume elements, the other keywords skin
/// cells.
pub fn cell_force(
    kind: DistributedKind,
    role: &CellRole,
    cell: CellType,
    formulation: Formulation,
    coords: &[[f64; 3]],
    density: impl Fn([f64; 3]) -> Result<[f64; 3], String>,
) -> Option<Result<Vec<f64>, String>> {
    match (kind, role) {
        (DistributedKind::Internal, CellRole::Element(spec)) => {
            Some(element_body_force_with(spec, coords, density).map_err(|e| e.to_string()))
        }
        (DistributedKind::Internal, _) => None,
        (_, CellRole::Skin { .. }) => Some(skin_force_with(cell, formulation, coords, density)),
        _ => None,
    }
}

/// Adds to `out` the nodal forces of the pressure `pressure(x)` on the
/// skin cells `cells` (PRES_REP of AFFE_CHAR_MECA, constant, and of
/// AFFE_CHAR_MECA_F, a function of the position).
pub fn add_pressure_forces_with(
    mesh: &Mesh,
    model: &Model,
    cells: &[usize],
    pressure: impl Fn([f64; 3]) -> Result<f64, String>,
    out: &mut [f64],
) -> Result<(), String> {
    add_cell_forces(mesh, model, cells, "PRES_REP", out, |_, cell, f, coords| {
        Some(super::pressure::pressure_forces_with(
            cell, f, coords, &pressure,
        ))
    })
}

/// Adds to `out` the nodal forces `forces` gives each cell of `cells`
/// (from its role, type, the model's formulation and its initial node
/// positions; `None`: the cell carries none), errors prefixed with
/// `keyword` and the cell.
fn add_cell_forces(
    mesh: &Mesh,
    model: &Model,
    cells: &[usize],
    keyword: &str,
    out: &mut [f64],
    forces: impl Fn(&CellRole, CellType, Formulation, &[[f64; 3]]) -> Option<Result<Vec<f64>, String>>,
) -> Result<(), String> {
    let d = model.ndof_per_node();
    let formulation = load_formulation(model);
    for &c in cells {
        let cell = &mesh.cells[c];
        let Some(role) = model.cells.get(c) else {
            continue;
        };
        let coords: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| mesh.coords[n]).collect();
        let Some(f) = forces(role, cell.kind, formulation, &coords) else {
            continue;
        };
        let f = f.map_err(|e| format!("{keyword}: cell M{}: {e}", c + 1))?;
        scatter(&cell.nodes, d, &f, out);
    }
    Ok(())
}

/// out[n·d + i] += f[a·d + i] for the nodes n of a cell.
pub fn scatter(nodes: &[usize], d: usize, f: &[f64], out: &mut [f64]) {
    for (a, &n) in nodes.iter().enumerate() {
        for i in 0..d {
            out[n * d + i] += f[a * d + i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, scale: f64) -> bool {
        (a - b).abs() <= 1e-13 * scale
    }

    fn totals(f: &[f64], d: usize) -> [f64; 3] {
        let mut t = [0.0; 3];
        for (k, v) in f.iter().enumerate() {
            t[k % d] += v;
        }
        t
    }

    /// A flat QUAD8 parallelogram: the serendipity split of a uniform
    /// density, −1/12 of the total on each corner and +1/3 on each
    /// mid-side node, along the force, whatever its direction.
    #[test]
    fn quad8_uniform_density_is_the_serendipity_split() {
        let (e1, e2) = ([3.0, 0.0, 1.0], [0.5, 2.0, 0.0]);
        let at = |s: f64, t: f64| [0, 1, 2].map(|k| s * e1[k] + t * e2[k]);
        let v = [at(0., 0.), at(1., 0.), at(1., 1.), at(0., 1.)];
        let mut x = v.to_vec();
        for k in 0..4 {
            let (u, w) = (v[k], v[(k + 1) % 4]);
            x.push([0, 1, 2].map(|i| (u[i] + w[i]) / 2.0));
        }
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let area = c.iter().map(|v| v * v).sum::<f64>().sqrt();
        let f = [1.5, -2.0, 0.25];
        let fe = skin_force(CellType::Quad8, Formulation::Solid3d, &x, f).unwrap();
        for n in 0..8 {
            let share = if n < 4 { -1.0 / 12.0 } else { 1.0 / 3.0 };
            for i in 0..3 {
                assert!(
                    close(fe[3 * n + i], share * f[i] * area, 10.0 * area),
                    "node {n} {i}: {}",
                    fe[3 * n + i]
                );
            }
        }
    }

    /// A SEG3 edge in 3D with its middle node off the centre (but on the
    /// segment): the total is f L whatever the parametrisation.
    #[test]
    fn seg3_edge_total_is_density_times_length() {
        let (p, q) = ([1.0, 2.0, -1.0], [3.0, 0.5, 2.0]);
        let m = [0, 1, 2].map(|k| p[k] + 0.4 * (q[k] - p[k]));
        let len = [0, 1, 2]
            .map(|k: usize| (q[k] - p[k]) * (q[k] - p[k]))
            .iter()
            .sum::<f64>()
            .sqrt();
        let f = [0.3, 4.0, -1.0];
        let t = totals(
            &skin_force(CellType::Seg3, Formulation::Solid3d, &[p, q, m], f).unwrap(),
            3,
        );
        for i in 0..3 {
            assert!(close(t[i], f[i] * len, 10.0 * len), "{i}: {}", t[i]);
        }
    }

    /// AXIS SEG2 on an oblique edge: per radian the total is f ∫ r ds =
    /// f L (r1 + r2)/2, node a getting f L (2 r_a + r_b)/6.
    #[test]
    fn axis_contour_carries_the_radius() {
        let (a, b) = ([1.0, 0.5, 0.0], [4.0, 4.5, 0.0]);
        let l = 5.0;
        let f = [2.0, -3.0, 0.0];
        let fe = skin_force(CellType::Seg2, Formulation::Axis, &[a, b], f).unwrap();
        for i in 0..2 {
            assert!(close(fe[i], f[i] * l * (2.0 + 4.0) / 6.0, 100.0));
            assert!(close(fe[2 + i], f[i] * l * (1.0 + 8.0) / 6.0, 100.0));
        }
    }

    /// The same oblique SEG2 in D_PLAN: per unit thickness, f L / 2 on
    /// each node (no r).
    #[test]
    fn plane_strain_contour_is_per_unit_thickness() {
        let (a, b) = ([1.0, 0.5, 0.0], [4.0, 4.5, 0.0]);
        let f = [2.0, -3.0, 0.0];
        let fe = skin_force(CellType::Seg2, Formulation::PlaneStrain, &[a, b], f).unwrap();
        for i in 0..2 {
            assert!(close(fe[i], f[i] * 2.5, 100.0));
            assert!(close(fe[2 + i], f[i] * 2.5, 100.0));
        }
    }

    #[test]
    fn wrong_cells_are_errors() {
        let tri = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]];
        let e = skin_force(CellType::Tria3, Formulation::Axis, &tri, [1.0, 0.0, 0.0]).unwrap_err();
        assert!(e.contains("SEG2/SEG3 cells of an AXIS model"), "{e}");
        let e = skin_force(
            CellType::Seg2,
            Formulation::Solid3d,
            &[[1., 0., 0.]; 2],
            [1.0; 3],
        )
        .unwrap_err();
        assert!(e.contains("degenerate"), "{e}");
        let e = skin_force(
            CellType::Seg2,
            Formulation::Axis,
            &[[-1., 0., 0.], [-1., 1., 0.]],
            [1.0; 3],
        )
        .unwrap_err();
        assert!(e.contains("radius"), "{e}");
    }
}
