//! Body forces of AFFE_CHAR_MECA/PESANTEUR: the nodal forces
//! f_a = ∫ ρ b N_a dV of a volume element under a uniform acceleration
//! field b = g·d, and their assembly, with the FORCE_NODALE of the same
//! load, into the external force vector.
//!
//! The integral uses the element's **mass** Gauss family, the one of the
//! consistent mass M: then f = M·(b at every node) to round-off, so that a
//! free body under gravity accelerates at exactly g, and the total force is
//! exactly (mass of the element)·b on any geometry the mass integrates.
//! In AXIS the integral is weighted by r without 2π (per radian), like the
//! mass and the internal forces.
//!
//! The 3D elements take their **RIGI** family instead, as code_aster's
//! te0015 (PESANTEUR) and te0016/te0017 (FORCE_INTERNE) do. It is the
//! mass's on MECA_HEXA8, HEXA20, PENTA6, PENTA15 and TETRA4 (one point is
//! exact for ∫ N_a of a TETRA4), and TETRA10's FPG5 is exact on straight
//! edges; the under-integrated elements differ from M·b off
//! parallelepipeds: MECA_HEXS8 puts ρ b J₀ on each node (one point at the
//! centre, J₀ its Jacobian: hexs8 note §10.3), MECA_HEXS20 and
//! MECA_TETRS10 integrate on FPG8 and FPG4. On a distorted HEXS8 cell a
//! free body under gravity then deforms a little, as in code_aster
//! (probe11: a 3 x 3 x 3 HEXS8 cube, interior nodes moved by up to 15 % of
//! a cell, clamped at its base under its weight: the mass family put the
//! top face's DZ up to 8.0e-3 and the base reactions up to 4.7e-3 off
//! code_aster's rule; the total weight differs by Σ 8 J₀ − V, 6e-6 of it).
//!
//! With the lumped mass of an explicit run (MASS_DIAG='OUI') PESANTEUR is
//! instead the lumped mass times b, f_a = m_a b (m_a the HRZ mass of
//! [`super::mechanics::hrz_lumped`]): the lumped counterpart of M·(b at
//! every node), so that a free body falls at exactly b on every element.
//! The consistent load against the HRZ masses does not: on HEXA20 its
//! corner loads are −1/8 of the cell's weight each against positive corner
//! masses (ACCE 4.6 % off g, and stresses in a free fall), on distorted
//! linear cells the two distributions differ by up to 0.6 %. This departs
//! from code_aster, which keeps the consistent load in explicit. Only
//! PESANTEUR, a uniform acceleration field, is lumped; the other body and
//! surface forces (FORCE_INTERNE, FORCE_FACE, PRES_REP...) stay
//! integrated consistently, as they are not an acceleration of the mass.

use indexmap::IndexMap;

use super::mechanics::ElementFailure;
use crate::mesh::quadrature::rule;
use crate::mesh::shape::eval;
use crate::mesh::Mesh;
use crate::model::spec::{ElementSpec, Formulation};
use crate::model::{CellRole, Gravity, Material, MaterialField, MechLoad, Model};

/// The nodal forces ∫ ρ b N_a dV of one element (node-major, 2 or 3
/// components per node as the formulation's dofs; in AXIS b's third
/// component is not used), on the configuration `coords`.
pub fn element_body_force(
    spec: &ElementSpec,
    coords: &[[f64; 3]],
    rho: f64,
    b: [f64; 3],
) -> Result<Vec<f64>, ElementFailure> {
    if !(rho.is_finite() && rho >= 0.0) || b.iter().any(|v| !v.is_finite()) {
        return Err(ElementFailure::BadInput {
            message: format!(
                "{}: density RHO = {rho} and acceleration {b:?} must be finite, RHO >= 0",
                spec.name
            ),
        });
    }
    let f = b.map(|c| rho * c);
    element_body_force_with(spec, coords, |_| Ok(f))
}

/// The nodal forces ∫ f(x) N_a dV of a force per unit volume that varies
/// over the element (AFFE_CHAR_MECA_F/FORCE_INTERNE), `density` giving f
/// at each Gauss point's position on the configuration `coords`; the
/// family and weights of [`element_body_force`] (which is this with a
/// constant ρ b).
pub fn element_body_force_with(
    spec: &ElementSpec,
    coords: &[[f64; 3]],
    density: impl Fn([f64; 3]) -> Result<[f64; 3], String>,
) -> Result<Vec<f64>, ElementFailure> {
    let nn = spec.nnodes();
    let d = spec.formulation.dofs_per_node();
    if coords.len() != nn {
        return Err(ElementFailure::BadInput {
            message: format!(
                "{}: {} node coordinates given for {nn} nodes",
                spec.name,
                coords.len()
            ),
        });
    }
    // code_aster's 3D volume loads (te0015 PESANTEUR, te0016/te0017
    // FORCE_INTERNE) integrate on the element's RIGI family: the mass's
    // on every 3D element but the under-integrated ones, where RIGI is
    // exact on parallelepipeds only (MECA_HEXS8: one point, ρ b J₀ at
    // each node; MECA_HEXS20 and MECA_TETRS10: FPG8, FPG4).
    let family = match spec.formulation {
        Formulation::Solid3d => spec.rigi,
        _ => spec.mass,
    };
    let q = rule(spec.cell, family).ok_or_else(|| ElementFailure::BadInput {
        message: format!(
            "{}: {} has no Gauss family {}",
            spec.name,
            spec.cell.aster_name(),
            family.name()
        ),
    })?;
    let mut out = vec![0.0; nn * d];
    for (p, (xi, w)) in q.points.iter().zip(&q.weights).enumerate() {
        let s = eval(spec.cell, *xi);
        let dv = w * measure(spec.formulation, s.n(), s.dn(), coords)
            .map_err(|message| ElementFailure::BadGeometry { point: p, message })?;
        let f =
            density(point_position(s.n(), coords)).map_err(|message| ElementFailure::BadInput {
                message: format!("{}: Gauss point {}: {message}", spec.name, p + 1),
            })?;
        for (a, &na) in s.n().iter().enumerate() {
            for i in 0..d {
                out[a * d + i] += f[i] * na * dv;
            }
        }
    }
    Ok(out)
}

/// The lumped nodal forces m_a b of one element (node-major, as
/// [`element_body_force`]): its HRZ lumped mass, the one the explicit
/// run's inertia uses, times the acceleration b.
pub fn lumped_body_force(
    spec: &ElementSpec,
    coords: &[[f64; 3]],
    rho: f64,
    b: [f64; 3],
) -> Result<Vec<f64>, ElementFailure> {
    if b.iter().any(|v| !v.is_finite()) {
        return Err(ElementFailure::BadInput {
            message: format!("{}: acceleration {b:?} must be finite", spec.name),
        });
    }
    let d = spec.formulation.dofs_per_node();
    let m = super::mechanics::mass(spec, coords, rho)?;
    let l = super::mechanics::hrz_lumped(&m, d).ok_or_else(|| ElementFailure::BadInput {
        message: format!(
            "{}: the lumped (HRZ) mass is not positive (zero density or volume)",
            spec.name
        ),
    })?;
    Ok(l.iter().enumerate().map(|(k, m)| m * b[k % d]).collect())
}

/// Σ N_a x_a: where a Gauss point is.
pub(crate) fn point_position(n: &[f64], coords: &[[f64; 3]]) -> [f64; 3] {
    let mut x = [0.0; 3];
    for (na, c) in n.iter().zip(coords) {
        for k in 0..3 {
            x[k] += na * c[k];
        }
    }
    x
}

/// det J at a point (× r in AXIS): the volume (per radian in AXIS, per
/// unit thickness in D_PLAN) per unit reference measure.
fn measure(f: Formulation, n: &[f64], dn: &[[f64; 3]], x: &[[f64; 3]]) -> Result<f64, String> {
    match f {
        Formulation::Solid3d => {
            let mut j = [[0.0; 3]; 3];
            for (a, g) in dn.iter().enumerate() {
                for k in 0..3 {
                    for l in 0..3 {
                        j[k][l] += x[a][k] * g[l];
                    }
                }
            }
            let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
            if det.is_nan() || det <= 0.0 {
                return Err(format!("non-positive Jacobian {det}"));
            }
            Ok(det)
        }
        Formulation::PlaneStrain | Formulation::PlaneStress => {
            Ok(super::mechanics::jacobian_2d(x, dn)?.0)
        }
        Formulation::Axis => {
            let det = super::mechanics::jacobian_2d(x, dn)?.0;
            Ok(det * super::mechanics::gauss_radius(n, x)?)
        }
    }
}

/// The external forces of the PESANTEUR of `loads` (full vector, dof
/// `node·ndpn + component`, as the engine's numbering), on the initial
/// geometry: a dead load (FIXE_CSTE), constant in time. Each load's
/// gravity acts on its cells that are volume elements of the model (skin
/// cells of a GROUP_MA carry no mass); the loads add up. `lumped`: each
/// cell's HRZ lumped mass times b (an explicit run with MASS_DIAG='OUI',
/// see the module doc), else the consistent ∫ ρ b N.
pub fn gravity_forces(
    mesh: &Mesh,
    model: &Model,
    matfield: &MaterialField,
    materials: &IndexMap<String, Material>,
    loads: &[&MechLoad],
    lumped: bool,
) -> Result<Vec<f64>, String> {
    let d = model.ndof_per_node();
    let mut out = vec![0.0; mesh.nnodes() * d];
    for g in loads.iter().filter_map(|l| l.gravity.as_ref()) {
        let b = acceleration(g);
        let cells: Vec<usize> = match &g.cells {
            Some(c) => c.clone(),
            None => (0..model.cells.len()).collect(),
        };
        for c in cells {
            let Some(CellRole::Element(spec)) = model.cells.get(c) else {
                continue;
            };
            let rho = matfield
                .cell_material
                .get(c)
                .and_then(|m| m.as_ref())
                .and_then(|m| materials.get(m))
                .and_then(|m| m.get("ELAS", "RHO"))
                .ok_or_else(|| {
                    format!(
                        "PESANTEUR: cell M{} has no density (ELAS/RHO of its material)",
                        c + 1
                    )
                })?;
            let nodes = &mesh.cells[c].nodes;
            let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
            let f = if lumped {
                lumped_body_force(spec, &coords, rho, b)
            } else {
                element_body_force(spec, &coords, rho, b)
            }
            .map_err(|e| format!("PESANTEUR: cell M{}: {e}", c + 1))?;
            for (a, &n) in nodes.iter().enumerate() {
                for i in 0..d {
                    out[n * d + i] += f[a * d + i];
                }
            }
        }
    }
    Ok(out)
}

/// The external forces of one load (full vector, dof `node·ndpn +
/// component`): its PESANTEUR ([`gravity_forces`]) plus its FORCE_NODALE,
/// each node receiving the force given for it, plus its PRES_REP
/// ([`super::pressure`], on the initial geometry), plus its FORCE_FACE,
/// FORCE_ARETE, FORCE_CONTOUR and FORCE_INTERNE ([`super::distributed`]).
/// DYNA_NON_LINE scales this
/// vector by the load's FONC_MULT. `lumped_gravity`: PESANTEUR as the
/// lumped mass times g ([`gravity_forces`]).
pub fn load_forces(
    mesh: &Mesh,
    model: &Model,
    matfield: &MaterialField,
    materials: &IndexMap<String, Material>,
    load: &MechLoad,
    lumped_gravity: bool,
) -> Result<Vec<f64>, String> {
    let mut out = gravity_forces(mesh, model, matfield, materials, &[load], lumped_gravity)?;
    let d = model.ndof_per_node();
    for &(node, dof, f) in &load.nodal_forces {
        let k = model
            .dofs
            .iter()
            .position(|x| *x == dof)
            .ok_or_else(|| format!("FORCE_NODALE: the model has no {}", dof.name()))?;
        out[node * d + k] += f;
    }
    for pr in &load.pressures {
        if !pr.p.is_finite() {
            return Err(format!("PRES_REP: PRES = {} must be finite", pr.p));
        }
        super::distributed::add_pressure_forces_with(
            mesh,
            model,
            &pr.cells,
            |_| Ok(pr.p),
            &mut out,
        )?;
    }
    super::distributed::add_distributed_forces(mesh, model, &load.distributed, &mut out)?;
    Ok(out)
}

/// b = g·d.
fn acceleration(g: &Gravity) -> [f64; 3] {
    g.direction.map(|c| g.g * c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::mass;
    use crate::mesh::CellType;
    use crate::model::spec::element_spec;

    /// f = M·(b at every node) (the consistent mass, same Gauss family),
    /// and Σ_a f_a = ρ·V·b with the volume V computed by hand.
    fn check(spec: ElementSpec, coords: &[[f64; 3]], rho: f64, b: [f64; 3], volume: f64) {
        let d = spec.formulation.dofs_per_node();
        let f = element_body_force(&spec, coords, rho, b).unwrap();
        let m = mass(&spec, coords, rho).unwrap();
        let ones: Vec<f64> = (0..spec.ndofs()).map(|k| b[k % d]).collect();
        // round-off scale: the total force
        let tol = 1e-12 * rho * volume * b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for r in 0..spec.ndofs() {
            let mb: f64 = (0..spec.ndofs()).map(|c| m[(r, c)] * ones[c]).sum();
            assert!((f[r] - mb).abs() <= tol, "{r}: {} vs {mb}", f[r]);
        }
        for i in 0..d {
            let total: f64 = (0..spec.nnodes()).map(|a| f[a * d + i]).sum();
            let exact = rho * volume * b[i];
            assert!(
                (total - exact).abs() <= tol,
                "component {i}: {total} vs {exact}"
            );
        }
    }

    /// A HEXA8 made of the unit cube under the affine map x ↦ A x + c: a
    /// skewed parallelepiped whose volume is det A.
    #[test]
    fn hexa8_total_gravity_is_mass_times_g() {
        let a = [[1.2, 0.3, -0.1], [0.2, 0.9, 0.25], [-0.15, 0.1, 1.4]];
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        // MED order: the bottom face turns clockwise seen from the top.
        let cube = [
            [0., 0., 0.],
            [0., 1., 0.],
            [1., 1., 0.],
            [1., 0., 0.],
            [0., 0., 1.],
            [0., 1., 1.],
            [1., 1., 1.],
            [1., 0., 1.],
        ];
        let coords: Vec<[f64; 3]> = cube
            .iter()
            .map(|p| {
                let mut x = [3.0, -1.0, 2.0];
                for k in 0..3 {
                    for l in 0..3 {
                        x[k] += a[k][l] * p[l];
                    }
                }
                x
            })
            .collect();
        let spec = element_spec("3D", CellType::Hexa8).unwrap();
        check(spec, &coords, 7.8e-9, [0.3e4, -2.0e4, -9.81e3], det);
    }

    /// A non-affine HEXA8: the 2×1×1 cuboid with the vertex (2, 1, 1)
    /// raised by h. The map is z = Z (1 + h X Y / 2), det J = 1 + h X Y / 2,
    /// so V = 2 + h/2; the 2×2×2 mass family integrates it exactly.
    #[test]
    fn distorted_hexa8_total_gravity_is_mass_times_g() {
        let mut x = [
            [0., 0., 0.],
            [0., 1., 0.],
            [2., 1., 0.],
            [2., 0., 0.],
            [0., 0., 1.],
            [0., 1., 1.],
            [2., 1., 1.],
            [2., 0., 1.],
        ];
        let h = 0.6;
        x[6][2] += h;
        let volume = 2.0 + h / 2.0;
        let spec = element_spec("3D", CellType::Hexa8).unwrap();
        check(spec, &x, 2.5e-9, [0.0, 1e4, -3e4], volume);
    }

    /// MECA_HEXS8 (3D_SI on HEXA8) integrates PESANTEUR on its one RIGI
    /// point, as code_aster's te0015: ρ b J₀ on every node, J₀ the
    /// Jacobian at the centre. On the non-affine cell of
    /// `distorted_hexa8_total_gravity_is_mass_times_g` (the vertex
    /// (2, 1, 1) raised by h), det J = (1/4)(1 + h X Y / 2) per unit
    /// reference volume, so J₀ = (1 + h/4)/4 at the centre (X = 1,
    /// Y = 1/2): every node gets the same force, where M·b gives the
    /// raised corner more.
    #[test]
    fn hexs8_gravity_is_rho_b_j0_on_every_node() {
        let mut x = [
            [0., 0., 0.],
            [0., 1., 0.],
            [2., 1., 0.],
            [2., 0., 0.],
            [0., 0., 1.],
            [0., 1., 1.],
            [2., 1., 1.],
            [2., 0., 1.],
        ];
        let h = 0.6;
        x[6][2] += h;
        let j0 = (1.0 + h / 4.0) / 4.0;
        let rho = 2.5e-9;
        let b = [0.0, 1e4, -3e4];
        let spec = element_spec("3D_SI", CellType::Hexa8).unwrap();
        let f = element_body_force(&spec, &x, rho, b).unwrap();
        for a in 0..8 {
            for i in 0..3 {
                let want = rho * b[i] * j0;
                assert!(
                    (f[a * 3 + i] - want).abs() <= 1e-14 * rho * 3e4,
                    "{a} {i}: {}",
                    f[a * 3 + i]
                );
            }
        }
        // The full HEXA8 (3D) on the same cell is M·b: the raised corner
        // gets more than the opposite corner (0, 0, 0), node 0 (DZ: index 2).
        let full =
            element_body_force(&element_spec("3D", CellType::Hexa8).unwrap(), &x, rho, b).unwrap();
        assert!(full[6 * 3 + 2].abs() > 1.01 * full[2].abs(), "{full:?}");
    }

    /// An AXIS QUAD8 ring of section [1, 3] × [0, 2] with a skewed top
    /// edge: per radian, the volume is ∫∫ r dr dz computed exactly for a
    /// trapezoid (z from 0 to 2 + s·(r − 1)).
    #[test]
    fn axis_quad8_total_gravity_is_mass_times_g_per_radian() {
        let s = 0.2;
        let top = |r: f64| 2.0 + s * (r - 1.0);
        let v = [
            [1.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, top(3.0), 0.0],
            [1.0, top(1.0), 0.0],
        ];
        let mut coords = v.to_vec();
        for k in 0..4 {
            let (p, q) = (v[k], v[(k + 1) % 4]);
            coords.push([(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, 0.0]);
        }
        // ∫_1^3 r (2 + s (r − 1)) dr = [r²] + s ([r³/3] − [r²/2])
        let volume = (9.0 - 1.0) + s * ((27.0 - 1.0) / 3.0 - (9.0 - 1.0) / 2.0);
        let spec = element_spec("AXIS", CellType::Quad8).unwrap();
        check(spec, &coords, 8.93e-9, [0.0, -9.81e3, 0.0], volume);
    }

    /// The lumped PESANTEUR of a HEXA20 cube: the HRZ fractions of the
    /// element mass times b (7/248 at the corners, 16/248 at the mid-edges,
    /// notes/explicit.md §6), positive along b at every node where the
    /// consistent load gives each corner −1/8 of the weight; the total is
    /// still ρ V b.
    #[test]
    fn hexa20_lumped_gravity_is_the_hrz_mass_times_g() {
        let spec = element_spec("3D", CellType::Hexa20).unwrap();
        let corners = [
            [0., 0., 0.],
            [0., 1., 0.],
            [1., 1., 0.],
            [1., 0., 0.],
            [0., 0., 1.],
            [0., 1., 1.],
            [1., 1., 1.],
            [1., 0., 1.],
        ];
        let mut coords = corners.to_vec();
        for &(a, b) in CellType::Hexa20.mid_edges() {
            let (p, q) = (corners[a], corners[b]);
            coords.push([0, 1, 2].map(|k| (p[k] + q[k]) / 2.0));
        }
        let (rho, b) = (8.0e-9, [0.0, 0.0, -1.0e9]);
        let weight = rho * b[2];
        let lumped = lumped_body_force(&spec, &coords, rho, b).unwrap();
        let consistent = element_body_force(&spec, &coords, rho, b).unwrap();
        for a in 0..20 {
            let share = if a < 8 { 7.0 / 248.0 } else { 16.0 / 248.0 };
            let f = lumped[a * 3 + 2];
            assert!(
                (f - share * weight).abs() <= 1e-13 * weight.abs(),
                "{a}: {f}"
            );
            assert_eq!(lumped[a * 3], 0.0);
            if a < 8 {
                let c = consistent[a * 3 + 2];
                assert!((c + weight / 8.0).abs() <= 1e-13 * weight.abs(), "{a}: {c}");
            }
        }
        let total: f64 = (0..20).map(|a| lumped[a * 3 + 2]).sum();
        assert!((total - weight).abs() <= 1e-13 * weight.abs());
    }

    #[test]
    fn inverted_cell_is_an_error_not_a_panic() {
        let spec = element_spec("AXIS", CellType::Quad4).unwrap();
        let coords = [[1., 0., 0.], [1., 1., 0.], [2., 1., 0.], [2., 0., 0.]];
        let e = element_body_force(&spec, &coords, 1.0, [0., -1., 0.]).unwrap_err();
        assert!(e.to_string().contains("Jacobian"), "{e}");
    }
}
