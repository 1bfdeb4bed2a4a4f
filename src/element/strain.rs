//! Strain fields of a displacement (CALC_CHAMP DEFORMATION EPSI_ELGA,
//! EPSG_ELGA, EPSL_ELGA), at the points of SIEF_ELGA.
//!
//! code_aster computes the three options in one elementary routine
//! (`te0025` in 3D, via `epsvmc`), from the displacement DEPL on the
//! **initial** geometry whatever the kinematics of the computation, with
//! F = 1 + Grad_X u:
//! - EPSI, the linearised strain ε = ½(H + Hᵀ), H = Grad_X u;
//! - EPSG, Green-Lagrange E = ½(FᵀF − 1);
//! - EPSL, the logarithmic strain ½ ln(FᵀF) (`epslmc`/`deflog`, the
//!   Lagrangian Hencky strain of GDEF_LOG), refused when an eigenvalue of
//!   FᵀF is not positive (`deflog`'s iret).
//!
//! The components are the tensor's: EPXY = ε_xy = γ_xy / 2 (`epslmc`
//! divides its Mandel shear by √2; `eps1mc` halves the engineering one),
//! 6 in 3D (EPXX EPYY EPZZ EPXY EPXZ EPYZ, located components EDEFOPG of
//! EPSI_R) and 4 in AXIS and D_PLAN (EPXX EPYY EPZZ EPXY). In AXIS x is
//! r, y is z and EPZZ is the hoop strain u_r/r (EPSG: u_r/r + ½(u_r/r)²,
//! EPSL: ln(1 + u_r/r)), as SIZZ is the hoop stress; in D_PLAN EPZZ = 0.
//! In C_PLAN the displacement has no ε_zz: code_aster's `epsvmc` takes
//! it from σ_zz = 0 with the ELAS Hooke matrix, EPZZ = −ν/(1−ν)(EPXX +
//! EPYY) ([`plane_stress_zz`]), the true ε_zz of an elastic point (a
//! plastic one's differs by the plastic part, which EPSI does not see).

use nalgebra::{Matrix3, SymmetricEigen};

use crate::mesh::Mesh;
use crate::model::spec::Formulation;
use crate::model::{CellRole, Model};
use crate::result::{GaussField, NodalField};

/// The strain options of CALC_CHAMP DEFORMATION.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// EPSI_*: ½(H + Hᵀ).
    Linear,
    /// EPSG_*: ½(FᵀF − 1).
    GreenLagrange,
    /// EPSL_*: ½ ln(FᵀF).
    Logarithmic,
}

impl Measure {
    /// The measure of an option name's prefix (EPSI, EPSG, EPSL).
    pub fn of_prefix(prefix: &str) -> Option<Measure> {
        match prefix {
            "EPSI" => Some(Measure::Linear),
            "EPSG" => Some(Measure::GreenLagrange),
            "EPSL" => Some(Measure::Logarithmic),
            _ => None,
        }
    }

    /// The strain tensor of the displacement gradient `h`.
    pub fn tensor(self, h: &Matrix3<f64>) -> Result<Matrix3<f64>, String> {
        let sym = (h + h.transpose()) * 0.5;
        match self {
            Measure::Linear => Ok(sym),
            Measure::GreenLagrange => Ok(sym + h.transpose() * h * 0.5),
            Measure::Logarithmic => {
                let f = Matrix3::identity() + h;
                let c = f.transpose() * f;
                let eig = SymmetricEigen::new(c);
                if let Some(l) = eig
                    .eigenvalues
                    .iter()
                    .find(|l| l.is_nan() || **l <= f64::EPSILON)
                {
                    return Err(format!(
                        "FᵀF has the eigenvalue {l:e}: no logarithmic strain (det F = {:e})",
                        f.determinant()
                    ));
                }
                let logs = eig.eigenvalues.map(|l| 0.5 * l.ln());
                Ok(eig.eigenvectors * Matrix3::from_diagonal(&logs) * eig.eigenvectors.transpose())
            }
        }
    }
}

/// The strain component names of a model: 4 for AXIS and D_PLAN, 6 in 3D.
pub fn components(formulation: Option<Formulation>) -> Vec<String> {
    let all = ["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ"];
    let n = match formulation {
        Some(Formulation::Axis | Formulation::PlaneStrain | Formulation::PlaneStress) => 4,
        _ => 6,
    };
    all[..n].iter().map(|s| s.to_string()).collect()
}

/// The strain field `measure` of the displacement `depl` (components DX,
/// DY, DZ by name) at the SIEF_ELGA points of every element cell of
/// `model` for which `selected` is true; other cells have no point. A
/// node of a selected cell without a displacement value, or a point the
/// measure cannot be taken at, is an error naming the cell.
pub fn strain_field(
    measure: Measure,
    mesh: &Mesh,
    model: &Model,
    depl: &NodalField,
    selected: &[bool],
) -> Result<GaussField, String> {
    let components = components(model.formulation());
    let nc = components.len();
    point_field(mesh, model, depl, selected, components, |h, c, g, out| {
        let e = measure
            .tensor(h)
            .map_err(|m| format!("cell M{} point {}: {m}", c + 1, g + 1))?;
        let v = [
            e[(0, 0)],
            e[(1, 1)],
            e[(2, 2)],
            e[(0, 1)],
            e[(0, 2)],
            e[(1, 2)],
        ];
        out.extend_from_slice(&v[..nc]);
        Ok(())
    })
}

/// EPZZ of the plane-stress (C_PLAN) cells of `field` (a strain field of
/// [`strain_field`], 4 components) from σ_zz = 0 with Hooke's law, as
/// code_aster's `epsvmc`: EPZZ = −ν/(1−ν)(EPXX + EPYY), `nu[c]` the ELAS
/// ν of cell c. A C_PLAN cell with points and no ν is an error naming it.
pub fn plane_stress_zz(
    field: &mut GaussField,
    model: &Model,
    nu: &[Option<f64>],
) -> Result<(), String> {
    let nc = field.ncmp();
    for (c, role) in model.cells.iter().enumerate() {
        let CellRole::Element(spec) = role else {
            continue;
        };
        let range = field.offsets[c]..field.offsets[c + 1];
        if spec.formulation != Formulation::PlaneStress || range.is_empty() {
            continue;
        }
        let nu = nu
            .get(c)
            .copied()
            .flatten()
            .ok_or_else(|| format!("cell M{}: no ELAS NU for the EPZZ of C_PLAN", c + 1))?;
        for point in field.values[range].chunks_mut(nc) {
            point[2] = -nu / (1.0 - nu) * (point[0] + point[1]);
        }
    }
    Ok(())
}

/// J = det F at the SIEF_ELGA points of the selected element cells (one
/// component J), for the energy of SIMO_MIEHE results.
pub fn jacobian_field(
    mesh: &Mesh,
    model: &Model,
    depl: &NodalField,
    selected: &[bool],
) -> Result<GaussField, String> {
    point_field(
        mesh,
        model,
        depl,
        selected,
        vec!["J".into()],
        |h, _, _, out| {
            out.push((Matrix3::identity() + h).determinant());
            Ok(())
        },
    )
}

/// A field with `components` at the SIEF_ELGA points of the selected
/// element cells, `f(H, cell, point, out)` pushing the values of one point
/// from its displacement gradient.
fn point_field(
    mesh: &Mesh,
    model: &Model,
    depl: &NodalField,
    selected: &[bool],
    components: Vec<String>,
    f: impl Fn(&Matrix3<f64>, usize, usize, &mut Vec<f64>) -> Result<(), String>,
) -> Result<GaussField, String> {
    let mut out = GaussField {
        components,
        offsets: Vec::with_capacity(mesh.ncells() + 1),
        values: Vec::new(),
    };
    let mut x = Vec::new();
    let mut u = Vec::new();
    for (c, cell) in mesh.cells.iter().enumerate() {
        out.offsets.push(out.values.len());
        let Some(CellRole::Element(spec)) = model.cells.get(c) else {
            continue;
        };
        if !selected.get(c).copied().unwrap_or(false) {
            continue;
        }
        let d = spec.formulation.dofs_per_node();
        x.clear();
        u.clear();
        for &n in &cell.nodes {
            x.push(mesh.coords[n]);
            for name in &["DX", "DY", "DZ"][..d] {
                let v = depl.get(n, name).ok_or_else(|| {
                    format!("DEPL has no {name} at node N{} of cell M{}", n + 1, c + 1)
                })?;
                u.push(v);
            }
        }
        let grads = super::mechanics::displacement_gradients(spec, &x, &u)
            .map_err(|m| format!("cell M{}: {m}", c + 1))?;
        for (g, h) in grads.iter().enumerate() {
            f(h, c, g, &mut out.values)?;
        }
    }
    out.offsets.push(out.values.len());
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniaxial stretch λ along x: EPSI = λ − 1, EPSG = (λ² − 1)/2,
    /// EPSL = ln λ, zero elsewhere.
    #[test]
    fn stretch_closed_forms() {
        let lam = 1.7_f64;
        let h = Matrix3::new(lam - 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        let e = Measure::Linear.tensor(&h).unwrap();
        assert!((e[(0, 0)] - (lam - 1.0)).abs() < 1e-15);
        let g = Measure::GreenLagrange.tensor(&h).unwrap();
        assert!((g[(0, 0)] - (lam * lam - 1.0) / 2.0).abs() < 1e-15);
        let l = Measure::Logarithmic.tensor(&h).unwrap();
        assert!((l[(0, 0)] - lam.ln()).abs() < 1e-14, "{l}");
        assert!(l[(1, 1)].abs() < 1e-15 && l[(0, 1)].abs() < 1e-15);
    }

    /// A simple shear of amount γ: EPXY = γ/2 (the tensor component, not
    /// the engineering γ), EPSG adds γ²/2 in yy, and the logarithmic
    /// strain of a rotation is zero.
    #[test]
    fn shear_is_the_tensor_component_and_rotations_have_no_log_strain() {
        let gam = 0.3;
        let h = Matrix3::new(0.0, gam, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        let e = Measure::Linear.tensor(&h).unwrap();
        assert_eq!(e[(0, 1)], gam / 2.0);
        let g = Measure::GreenLagrange.tensor(&h).unwrap();
        assert!((g[(1, 1)] - gam * gam / 2.0).abs() < 1e-16 && g[(0, 1)] == gam / 2.0);
        let (c, s) = (0.6_f64.cos(), 0.6_f64.sin());
        let rot = Matrix3::new(c - 1.0, -s, 0.0, s, c - 1.0, 0.0, 0.0, 0.0, 0.0);
        let l = Measure::Logarithmic.tensor(&rot).unwrap();
        assert!(l.iter().all(|v| v.abs() < 1e-15), "{l}");
        let flat = Matrix3::new(-1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        assert!(Measure::Logarithmic.tensor(&flat).is_err());
    }
}
