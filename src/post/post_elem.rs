//! POST_ELEM's reductions: mass, centre of gravity and inertia from point
//! masses, and the share of an energy in a part of the model.
//!
//! The command gathers the points (position, ρ dV) of the elements on
//! the family of their mass matrix (`element::mechanics::point_measures`),
//! so that the mass here is the mass the dynamics uses; this module only
//! sums, below anything that knows elements.

/// What MASS_INER writes for one part: code_aster's columns MASSE, CDG_X,
/// CDG_Y, CDG_Z, IX_G, IY_G, IZ_G, IXY_G, IXZ_G, IYZ_G. The inertia is
/// about the centre of gravity, IX_G = ∫ ρ ((y − y_G)² + (z − z_G)²) dV,
/// and the products are taken positive, IXY_G = ∫ ρ (x − x_G)(y − y_G) dV
/// (code_aster's `te0065`, `pemica`, which put the minus signs only when
/// they build the inertia matrix for its principal axes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MassProperties {
    pub mass: f64,
    pub cdg: [f64; 3],
    pub ix: f64,
    pub iy: f64,
    pub iz: f64,
    pub ixy: f64,
    pub ixz: f64,
    pub iyz: f64,
}

impl MassProperties {
    /// The values in code_aster's column order, with the column names.
    pub fn columns(&self) -> [(&'static str, f64); 10] {
        [
            ("MASSE", self.mass),
            ("CDG_X", self.cdg[0]),
            ("CDG_Y", self.cdg[1]),
            ("CDG_Z", self.cdg[2]),
            ("IX_G", self.ix),
            ("IY_G", self.iy),
            ("IZ_G", self.iz),
            ("IXY_G", self.ixy),
            ("IXZ_G", self.ixz),
            ("IYZ_G", self.iyz),
        ]
    }
}

/// The mass properties of point masses `(position, m)` of a 3D model, or
/// of a plane (D_PLAN) one with z = 0 everywhere (per unit thickness: the
/// plane `te0285` gives IZ_G = IX_G + IY_G and no IXZ, IYZ, which is
/// this with z = 0). Two passes, the centre first, so that the central
/// moments do not come from differences of large numbers. No mass gives
/// all zeros, as code_aster leaves the centre at 0 when |M| ≤ 1e-6.
pub fn mass_properties(points: &[([f64; 3], f64)]) -> MassProperties {
    let mass: f64 = points.iter().map(|(_, m)| m).sum();
    if mass == 0.0 {
        return MassProperties::default();
    }
    let mut cdg = [0.0; 3];
    for (x, m) in points {
        for k in 0..3 {
            cdg[k] += m * x[k];
        }
    }
    cdg.iter_mut().for_each(|c| *c /= mass);
    let mut p = MassProperties {
        mass,
        cdg,
        ..MassProperties::default()
    };
    for (x, m) in points {
        let [dx, dy, dz] = [x[0] - cdg[0], x[1] - cdg[1], x[2] - cdg[2]];
        p.ix += m * (dy * dy + dz * dz);
        p.iy += m * (dx * dx + dz * dz);
        p.iz += m * (dx * dx + dy * dy);
        p.ixy += m * dx * dy;
        p.ixz += m * dx * dz;
        p.iyz += m * dy * dz;
    }
    p
}

/// The mass properties of the full body of revolution (2π) an AXIS
/// model stands for, from its point masses per radian `(position, m)`
/// with position (r, z, 0): code_aster's `te0285` (option MASS_INER of
/// the plane and axisymmetric elements) multiplies by 2π = `r8depi` and
/// puts the centre on the axis, CDG_X = CDG_Y = 0 and CDG_Z the axial
/// centre ∫ ρ z r / ∫ ρ r (the model's y becomes the 3D z); IZ_G, about
/// the axis, is 2π ∫ ρ r³, and IX_G = IY_G = 2π ∫ ρ (z − z_G)² r + IZ_G/2
/// (a ring of radius r has its inertia r²/2 about a diameter); the
/// products are zero. The kinetic energy and the forces of an AXIS
/// model stay per radian (`te0082`): only MASS_INER is for the whole body.
pub fn mass_properties_axis(points: &[([f64; 3], f64)]) -> MassProperties {
    let two_pi = 2.0 * std::f64::consts::PI;
    let per_radian: f64 = points.iter().map(|(_, m)| m).sum();
    if per_radian == 0.0 {
        return MassProperties::default();
    }
    let zg = points.iter().map(|(x, m)| m * x[1]).sum::<f64>() / per_radian;
    let iz = two_pi * points.iter().map(|(x, m)| m * x[0] * x[0]).sum::<f64>();
    let axial = two_pi
        * points
            .iter()
            .map(|(x, m)| m * (x[1] - zg) * (x[1] - zg))
            .sum::<f64>();
    MassProperties {
        mass: two_pi * per_radian,
        cdg: [0.0, 0.0, zg],
        ix: axial + iz / 2.0,
        iy: axial + iz / 2.0,
        iz,
        ..MassProperties::default()
    }
}

/// POUR_CENT of a part of an energy: 100 × part / total, 0 when both are
/// below the machine precision (code_aster's `peenca`, which writes 100
/// exactly for TOUT without dividing).
pub fn percent(part: f64, total: f64) -> f64 {
    if part < f64::EPSILON && total < f64::EPSILON {
        0.0
    } else {
        100.0 * part / total
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two unit masses at (±1, 0, 0): centre at the origin, IY = IZ = 2,
    /// IX = 0, no product.
    #[test]
    fn two_point_masses() {
        let p = mass_properties(&[([1.0, 0.0, 0.0], 1.0), ([-1.0, 0.0, 0.0], 1.0)]);
        assert_eq!(p.mass, 2.0);
        assert_eq!(p.cdg, [0.0; 3]);
        assert_eq!((p.ix, p.iy, p.iz), (0.0, 2.0, 2.0));
        assert_eq!((p.ixy, p.ixz, p.iyz), (0.0, 0.0, 0.0));
    }

    /// A thin ring of radius a and mass m (one point per radian at r = a):
    /// m a² about its axis, m a²/2 about a diameter.
    #[test]
    fn thin_ring_about_axis_and_diameter() {
        let (a, m_rad) = (2.0, 0.5);
        let p = mass_properties_axis(&[([a, 3.0, 0.0], m_rad)]);
        let m = 2.0 * std::f64::consts::PI * m_rad;
        assert!((p.mass - m).abs() < 1e-15 * m);
        assert_eq!(p.cdg, [0.0, 0.0, 3.0]);
        assert!((p.iz - m * a * a).abs() < 1e-14 * p.iz);
        assert!((p.ix - m * a * a / 2.0).abs() < 1e-14 * p.ix);
    }

    #[test]
    fn percent_of_nothing_is_zero() {
        assert_eq!(percent(0.0, 0.0), 0.0);
        assert_eq!(percent(1.0, 4.0), 25.0);
    }
}
