//! Equivalent stresses (CALC_CHAMP CRITERES SIEQ_ELGA, SIEQ_ELNO,
//! SIEQ_NOEU) from a stress field, and equivalent strains (EPEQ_ELGA,
//! EPEQ_ELNO, EPEQ_NOEU) from a strain field.
//!
//! The components, their names and order are code_aster's for the SIEQ
//! options (the located components `ECOEQPG`/`ECOEQNO` of the physical
//! quantity SIEF_R in its element catalogue, filled by its `fgequi`
//! routine): VMIS, TRESCA, PRIN_1, PRIN_2, PRIN_3, VMIS_SG, VECT_1_X ...
//! VECT_3_Z, TRSIG, TRIAX, 17 values. What each one is, following
//! `fgequi`:
//! - VMIS = sqrt(3/2 s:s), s the deviator;
//! - PRIN_1 <= PRIN_2 <= PRIN_3, the principal stresses in ascending
//!   order (`fgequi` asks its Jacobi solver for an increasing sort);
//! - TRESCA = the largest difference of two principal stresses,
//!   PRIN_3 - PRIN_1;
//! - VMIS_SG = VMIS with the sign of the trace (+ for a zero trace);
//! - VECT_i_X/Y/Z, the unit principal direction of PRIN_i;
//! - TRSIG = the trace SIXX + SIYY + SIZZ (not the mean stress);
//! - TRIAX = TRSIG / 3 / VMIS, 0 when VMIS <= 1e-10 |TRSIG| (a spherical
//!   state), as `fgequi`.
//!
//! Plane models (4 components SIXX, SIYY, SIZZ, SIXY) are the 3D tensor
//! with SIXZ = SIYZ = 0, as `fgequi` completes them, so SIZZ (the
//! out-of-plane stress of plane strain and axisymmetry) counts among the
//! principal stresses.
//!
//! A principal direction is defined up to its sign, and code_aster's is
//! whatever its Jacobi rotations leave; here each vector is turned so that
//! its largest component (the first of equal ones) is positive, which
//! gives +x, +y, +z for a diagonal tensor, as Jacobi's identity start
//! does. Directions of equal principal stresses are any orthonormal basis
//! of their eigenspace; a zero tensor has zero vectors (code_aster's
//! `fgequi` leaves them at zero too).

//! The EPEQ components are `fgequi`'s for a strain (type 'EPSI',
//! located components EDFEQPG of EPSI_R), 14 values: INVA_2 =
//! sqrt(2/3 d:d), d the deviator of the strain tensor (`lciv2e`, with
//! the tensor shears: `fgequi` turns EPXY into the Mandel √2 ε_xy first);
//! PRIN_1 <= PRIN_2 <= PRIN_3 the principal strains; INVA_2SG = INVA_2
//! with the sign of the trace (+ for a zero trace); VECT_1_X ... VECT_3_Z
//! their directions, signed and completed (plane models: EPXZ = EPYZ =
//! 0, EPZZ among the principal strains) as the stresses' are.

use nalgebra::{Matrix3, SymmetricEigen};

use super::GaussField;

/// The EPEQ components, in code_aster's order (located components
/// EDFEQPG of EPSI_R).
pub const EPEQ_COMPONENTS: [&str; 14] = [
    "INVA_2", "PRIN_1", "PRIN_2", "PRIN_3", "INVA_2SG", "VECT_1_X", "VECT_1_Y", "VECT_1_Z",
    "VECT_2_X", "VECT_2_Y", "VECT_2_Z", "VECT_3_X", "VECT_3_Y", "VECT_3_Z",
];

/// The SIEQ components, in code_aster's order.
pub const SIEQ_COMPONENTS: [&str; 17] = [
    "VMIS", "TRESCA", "PRIN_1", "PRIN_2", "PRIN_3", "VMIS_SG", "VECT_1_X", "VECT_1_Y", "VECT_1_Z",
    "VECT_2_X", "VECT_2_Y", "VECT_2_Z", "VECT_3_X", "VECT_3_Y", "VECT_3_Z", "TRSIG", "TRIAX",
];

/// Principal values of the symmetric tensor `s` = (XX, YY, ZZ, XY, XZ,
/// YZ) in ascending order, with their unit directions (each turned so
/// that its largest component is positive); a zero tensor has zero
/// values and zero directions, as `fgequi` leaves them.
fn principal(s: [f64; 6]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut values = [0.0; 3];
    let mut vectors = [[0.0; 3]; 3];
    if s.iter().all(|&v| v == 0.0) {
        return (values, vectors);
    }
    let [xx, yy, zz, xy, xz, yz] = s;
    let a = Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
    let eig = SymmetricEigen::new(a);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    for (k, &i) in order.iter().enumerate() {
        values[k] = eig.eigenvalues[i];
        let v = eig.eigenvectors.column(i);
        let mut big = 0;
        for c in 1..3 {
            if v[c].abs() > v[big].abs() {
                big = c;
            }
        }
        let sign = if v[big] < 0.0 { -1.0 } else { 1.0 };
        let norm = v.norm();
        for c in 0..3 {
            vectors[k][c] = sign * v[c] / norm;
        }
    }
    (values, vectors)
}

/// The SIEQ values of the stress `s` = (XX, YY, ZZ, XY, XZ, YZ).
pub fn equivalent_stresses(s: [f64; 6]) -> [f64; 17] {
    let mut out = [0.0; 17];
    let [xx, yy, zz, xy, xz, yz] = s;
    let trace = xx + yy + zz;
    let m = trace / 3.0;
    let (dx, dy, dz) = (xx - m, yy - m, zz - m);
    let j2 = 0.5 * (dx * dx + dy * dy + dz * dz) + xy * xy + xz * xz + yz * yz;
    let vmis = (3.0 * j2).sqrt();
    out[0] = vmis;
    out[5] = if trace >= 0.0 { vmis } else { -vmis };
    out[15] = trace;
    out[16] = if vmis > 1e-10 * trace.abs() {
        trace / 3.0 / vmis
    } else {
        0.0
    };
    let (values, vectors) = principal(s);
    out[2..5].copy_from_slice(&values);
    for k in 0..3 {
        out[6 + 3 * k..9 + 3 * k].copy_from_slice(&vectors[k]);
    }
    out[1] = out[4] - out[2];
    out
}

/// The EPEQ values of the strain `e` = (XX, YY, ZZ, XY, XZ, YZ), tensor
/// shear components.
pub fn equivalent_strains(e: [f64; 6]) -> [f64; 14] {
    let mut out = [0.0; 14];
    let [xx, yy, zz, xy, xz, yz] = e;
    let trace = xx + yy + zz;
    let m = trace / 3.0;
    let (dx, dy, dz) = (xx - m, yy - m, zz - m);
    // d:d with the tensor shears counted twice (ε_xy and ε_yx)
    let dd = dx * dx + dy * dy + dz * dz + 2.0 * (xy * xy + xz * xz + yz * yz);
    let inva2 = (2.0 / 3.0 * dd).sqrt();
    out[0] = inva2;
    out[4] = if trace >= 0.0 { inva2 } else { -inva2 };
    let (values, vectors) = principal(e);
    out[1..4].copy_from_slice(&values);
    for k in 0..3 {
        out[5 + 3 * k..8 + 3 * k].copy_from_slice(&vectors[k]);
    }
    out
}

/// The SIEQ field of a stress field (SIEF_ELGA, SIGM_ELNO...): the same
/// cells and points, the 17 SIEQ components at each. The stress is read
/// by component name; SIXZ and SIYZ absent (plane models) are 0, a point
/// where a stress component is absent (NaN) has every SIEQ value absent.
pub fn sieq(stress: &GaussField) -> Result<GaussField, String> {
    map_tensor_field(
        stress,
        ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"],
        "stress",
        &SIEQ_COMPONENTS,
        |s, out| out.extend_from_slice(&equivalent_stresses(s)),
    )
}

/// The EPEQ field of a strain field (EPSI_ELGA, EPSI_ELNO): the 14 EPEQ
/// components at each point, read and completed as [`sieq`] does.
pub fn epeq(strain: &GaussField) -> Result<GaussField, String> {
    map_tensor_field(
        strain,
        ["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ"],
        "strain",
        &EPEQ_COMPONENTS,
        |e, out| out.extend_from_slice(&equivalent_strains(e)),
    )
}

/// A field of `out_names` computed point by point from the symmetric
/// tensor whose components are `names` in `field` (the last two may be
/// absent: plane models, read as 0).
fn map_tensor_field(
    field: &GaussField,
    names: [&str; 6],
    what: &str,
    out_names: &[&str],
    f: impl Fn([f64; 6], &mut Vec<f64>),
) -> Result<GaussField, String> {
    let idx: Vec<Option<usize>> = names
        .iter()
        .map(|n| field.components.iter().position(|c| c == n))
        .collect();
    if let Some(k) = idx[..4].iter().position(Option::is_none) {
        return Err(format!(
            "the {what} field has no {} component (components: {})",
            names[k],
            field.components.join(", ")
        ));
    }
    let nc = field.ncmp();
    let no = out_names.len();
    let npoints = field.values.len().checked_div(nc).unwrap_or(0);
    let mut out = GaussField {
        components: out_names.iter().map(|s| s.to_string()).collect(),
        offsets: field
            .offsets
            .iter()
            .map(|&o| o.checked_div(nc).unwrap_or(0) * no)
            .collect(),
        values: Vec::with_capacity(npoints * no),
    };
    for p in 0..npoints {
        let row = &field.values[p * nc..(p + 1) * nc];
        let mut s = [0.0; 6];
        for (k, i) in idx.iter().enumerate() {
            if let Some(i) = i {
                s[k] = row[*i];
            }
        }
        if s.iter().any(|v| v.is_nan()) {
            out.values.extend(std::iter::repeat_n(f64::NAN, no));
        } else {
            f(s, &mut out.values);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, scale: f64) -> bool {
        (a - b).abs() <= 1e-12 * scale
    }

    /// R diag(l) R^T for a rotation R of axis (1, 2, 2)/3 and angle 0.7:
    /// the principal values must be l sorted and the directions R's
    /// columns (up to sign), to 1e-12.
    #[test]
    fn rotated_tensor_gives_back_its_principal_frame() {
        let axis = nalgebra::Unit::new_normalize(nalgebra::Vector3::new(1.0, 2.0, 2.0));
        let r = nalgebra::Rotation3::from_axis_angle(&axis, 0.7).into_inner();
        let l = [250.0, -80.0, 40.0];
        let d = Matrix3::from_diagonal(&nalgebra::Vector3::new(l[0], l[1], l[2]));
        let a = r * d * r.transpose();
        let s = [
            a[(0, 0)],
            a[(1, 1)],
            a[(2, 2)],
            a[(0, 1)],
            a[(0, 2)],
            a[(1, 2)],
        ];
        let e = equivalent_stresses(s);
        assert!(close(e[2], -80.0, 250.0), "{e:?}");
        assert!(close(e[3], 40.0, 250.0), "{e:?}");
        assert!(close(e[4], 250.0, 250.0), "{e:?}");
        assert!(close(e[1], 330.0, 250.0), "{e:?}");
        // PRIN_1 is l[1]: column 1 of R, and so on
        for (k, col) in [1usize, 2, 0].iter().enumerate() {
            let v = r.column(*col);
            let dot: f64 = (0..3).map(|c| e[6 + 3 * k + c] * v[c]).sum();
            assert!((dot.abs() - 1.0).abs() < 1e-12, "VECT_{} {e:?}", k + 1);
        }
        // invariants do not depend on the frame
        let vm =
            (0.5 * ((l[0] - l[1]).powi(2) + (l[1] - l[2]).powi(2) + (l[2] - l[0]).powi(2))).sqrt();
        assert!(close(e[0], vm, 250.0));
        assert!(close(e[15], 210.0, 250.0));
        assert!(close(e[16], 70.0 / vm, 1.0));
        assert_eq!(e[5], e[0]);
    }

    #[test]
    fn uniaxial_compression_signs_von_mises() {
        let e = equivalent_stresses([0.0, 0.0, -300.0, 0.0, 0.0, 0.0]);
        assert_eq!(e[0], 300.0);
        assert_eq!(e[5], -300.0);
        assert_eq!(e[2], -300.0);
        assert_eq!(&e[6..9], &[0.0, 0.0, 1.0]);
        assert!(close(e[16], -1.0 / 3.0, 1.0));
        assert_eq!(e[1], 300.0);
    }

    #[test]
    fn spherical_and_zero_states() {
        let e = equivalent_stresses([5.0, 5.0, 5.0, 0.0, 0.0, 0.0]);
        assert_eq!((e[0], e[16], e[15]), (0.0, 0.0, 15.0));
        let z = equivalent_stresses([0.0; 6]);
        assert!(z.iter().all(|&v| v == 0.0));
    }

    /// Uniaxial strain ε along z with lateral −ν ε: INVA_2 = 2/3 (1 + ν)
    /// |ε| (the von Mises equivalent strain), sign of the trace; a pure
    /// shear ε_xy = g/2 (tensor component) gives INVA_2 = g/√3 and
    /// principal strains ∓ g/2 along (1, ∓1)/√2.
    #[test]
    fn equivalent_strains_closed_forms() {
        let (eps, nu) = (2e-3, 0.3);
        let e = equivalent_strains([-nu * eps, -nu * eps, eps, 0.0, 0.0, 0.0]);
        assert!(close(e[0], 2.0 / 3.0 * (1.0 + nu) * eps, eps), "{e:?}");
        assert_eq!(e[4], e[0]);
        assert!(close(e[1], -nu * eps, eps) && close(e[3], eps, eps));
        assert_eq!(&e[11..14], &[0.0, 0.0, 1.0]);
        let c = equivalent_strains([nu * eps, nu * eps, -eps, 0.0, 0.0, 0.0]);
        assert_eq!(c[4], -c[0]);
        let g = 1e-3;
        let s = equivalent_strains([0.0, 0.0, 0.0, g / 2.0, 0.0, 0.0]);
        assert!(close(s[0], g / 3.0_f64.sqrt(), g), "{s:?}");
        assert!(close(s[1], -g / 2.0, g) && close(s[2], 0.0, g) && close(s[3], g / 2.0, g));
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(s[5], h, 1.0) && close(s[6], -h, 1.0), "{s:?}");
        assert!(close(s[11], h, 1.0) && close(s[12], h, 1.0), "{s:?}");
        assert!(equivalent_strains([0.0; 6]).iter().all(|&v| v == 0.0));
    }

    /// A plane field: SIXZ = SIYZ = 0 and SIZZ a principal stress.
    #[test]
    fn plane_field_components() {
        let f = GaussField {
            components: ["SIXX", "SIYY", "SIZZ", "SIXY"]
                .iter()
                .map(|s| s.to_string())
                .collect(),
            offsets: vec![0, 4, 4],
            values: vec![10.0, 10.0, -3.0, 4.0],
        };
        let q = sieq(&f).unwrap();
        assert_eq!(q.offsets, vec![0, 17, 17]);
        assert_eq!(q.npg(0), 1);
        let v = q.cell(0);
        assert!(close(v[2], -3.0, 14.0) && close(v[3], 6.0, 14.0) && close(v[4], 14.0, 14.0));
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(v[12], h, 1.0) && close(v[13], h, 1.0) && v[14].abs() < 1e-15);
        assert!(sieq(&GaussField {
            components: vec!["V1".into()],
            offsets: vec![0, 1],
            values: vec![1.0]
        })
        .unwrap_err()
        .contains("SIXX"));
    }
}
