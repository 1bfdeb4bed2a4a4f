//! Equivalent stresses (CALC_CHAMP CRITERES SIEQ_ELGA, SIEQ_ELNO,
//! SIEQ_NOEU) from a stress field.
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

use nalgebra::{Matrix3, SymmetricEigen};

use super::GaussField;

/// The SIEQ components, in code_aster's order.
pub const SIEQ_COMPONENTS: [&str; 17] = [
    "VMIS", "TRESCA", "PRIN_1", "PRIN_2", "PRIN_3", "VMIS_SG", "VECT_1_X", "VECT_1_Y", "VECT_1_Z",
    "VECT_2_X", "VECT_2_Y", "VECT_2_Z", "VECT_3_X", "VECT_3_Y", "VECT_3_Z", "TRSIG", "TRIAX",
];

/// The SIEQ values of the stress `s` = (XX, YY, ZZ, XY, XZ, YZ).
pub fn equivalent_stresses(s: [f64; 6]) -> [f64; 17] {
    let [xx, yy, zz, xy, xz, yz] = s;
    let mut out = [0.0; 17];
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
    if s.iter().all(|&v| v == 0.0) {
        return out;
    }
    let a = Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
    let eig = SymmetricEigen::new(a);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    for (k, &i) in order.iter().enumerate() {
        out[2 + k] = eig.eigenvalues[i];
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
            out[6 + 3 * k + c] = sign * v[c] / norm;
        }
    }
    out[1] = out[4] - out[2];
    out
}

/// The SIEQ field of a stress field (SIEF_ELGA, SIGM_ELNO...): the same
/// cells and points, the 17 SIEQ components at each. The stress is read
/// by component name; SIXZ and SIYZ absent (plane models) are 0, a point
/// where a stress component is absent (NaN) has every SIEQ value absent.
pub fn sieq(stress: &GaussField) -> Result<GaussField, String> {
    let names = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    let idx: Vec<Option<usize>> = names
        .iter()
        .map(|n| stress.components.iter().position(|c| c == n))
        .collect();
    if idx[..4].iter().any(Option::is_none) {
        return Err(format!(
            "the stress field has no {} component (components: {})",
            names[idx.iter().position(Option::is_none).unwrap_or(0)],
            stress.components.join(", ")
        ));
    }
    let nc = stress.ncmp();
    let npoints = stress.values.len().checked_div(nc).unwrap_or(0);
    let mut out = GaussField {
        components: SIEQ_COMPONENTS.iter().map(|s| s.to_string()).collect(),
        offsets: stress
            .offsets
            .iter()
            .map(|&o| o.checked_div(nc).unwrap_or(0) * SIEQ_COMPONENTS.len())
            .collect(),
        values: Vec::with_capacity(npoints * SIEQ_COMPONENTS.len()),
    };
    for p in 0..npoints {
        let row = &stress.values[p * nc..(p + 1) * nc];
        let mut s = [0.0; 6];
        for (k, i) in idx.iter().enumerate() {
            if let Some(i) = i {
                s[k] = row[*i];
            }
        }
        if s.iter().any(|v| v.is_nan()) {
            out.values
                .extend(std::iter::repeat_n(f64::NAN, SIEQ_COMPONENTS.len()));
        } else {
            out.values.extend_from_slice(&equivalent_stresses(s));
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
