//! Plane stress (C_PLAN) for any small-strain law: σ_zz = 0 with ε_zz
//! an unknown of the Gauss point.
//!
//! code_aster treats C_PLAN inside the laws that declare it (`nmisot`
//! for VMIS_ISOT_LINE/TRAC/PUIS, `nmcine`/`nmecmi` for VMIS_CINE_LINE:
//! the radial return solved with σ_zz = 0) and by De Borst's global
//! iterations (ALGO_CPLAN='DEBORST') for the others. Both solve the same
//! discrete equations at convergence: the law's 3D update with the
//! strain increment (Δε_xx, Δε_yy, Δε_zz, Δγ_xy) and σ_zz(Δε_zz) = 0.
//! Here that equation is solved at the Gauss point by Newton on Δε_zz
//! with the law's own consistent tangent (one law call for an elastic
//! step, whose elastic predictor is exact; two or three when it yields),
//! so every 3D law gets the plane-stress answer of its native treatment
//! without a line of its own.
//!
//! The tangent follows by static condensation: with dσ_zz = 0,
//! dε_zz = −(D_z· dε)/D_zz, so D_cp = D − D_·z D_z· / D_zz, whose zz row
//! and column are zero.

use super::{
    IntegrationFailure, Mat6, SmallStrainBehaviour, SmallStrainInput, SmallStrainOutput,
    TangentKind, Vec6,
};

/// Index of zz in the Voigt order (xx, yy, zz, xy, xz, yz).
const ZZ: usize = 2;

/// Newton iterations on Δε_zz before the step is declared not converged
/// (a cut step is retried): the consistent tangent converges in two or
/// three on every law of aster.
const MAX_ITERATIONS: usize = 25;

/// |σ_zz| at convergence, relative to the largest stress component: a
/// few hundred ulps, what the law's own round-off leaves.
const RELATIVE_TOLERANCE: f64 = 1e-12;

/// The law's update under σ_zz = 0, and the Δε_zz that gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneStressOutput {
    /// σ with σ_zz exactly 0, the internal variables of the converged
    /// update, and the condensed tangent as `input.tangent` asks.
    pub output: SmallStrainOutput,
    /// The out-of-plane strain increment Δε_zz.
    pub strain_zz: f64,
}

/// Integrates `law` over `input` with σ_zz = 0 at the end of the step;
/// `input.strain_increment[2]` is ignored (the plane element gives 0),
/// Δε_zz is solved for. A Newton that does not reach |σ_zz| ≤ 1e-12·|σ|
/// is a [`IntegrationFailure::not_converged`] (the step is cut).
pub fn integrate(
    law: &dyn SmallStrainBehaviour,
    input: &SmallStrainInput,
) -> Result<PlaneStressOutput, IntegrationFailure> {
    let name = law.metadata().name;
    let mut de = input.strain_increment;
    // Elastic predictor: exact for an elastic step from any σ_n.
    de[ZZ] = match law.elastic_params() {
        Some(p) => {
            let lambda = p.e * p.nu / ((1.0 + p.nu) * (1.0 - 2.0 * p.nu));
            let c = lambda + 2.0 * p.mu();
            -(lambda * (de[0] + de[1]) + input.stress[ZZ]) / c
        }
        None => 0.0,
    };
    let mut last_residual = f64::NAN;
    for _ in 0..MAX_ITERATIONS {
        let out = law.integrate(&SmallStrainInput {
            strain_increment: de,
            tangent: TangentKind::Consistent,
            ..*input
        })?;
        let d = out.tangent.ok_or_else(|| {
            IntegrationFailure::invalid(name, "no consistent tangent for the plane-stress Newton")
        })?;
        let r = out.stress[ZZ];
        let scale = out.stress.amax();
        last_residual = r;
        let dzz = d[(ZZ, ZZ)];
        // Stagnation: the correction no longer changes Δε_zz.
        let step = if dzz.is_finite() && dzz > 0.0 {
            r / dzz
        } else {
            return Err(IntegrationFailure::not_converged(
                name,
                format!("plane stress (C_PLAN): the tangent D_zzzz = {dzz:e} is not positive"),
            ));
        };
        let stalled = step.abs() <= 4.0 * f64::EPSILON * de.amax();
        if r.abs() <= RELATIVE_TOLERANCE * scale || stalled {
            return Ok(finish(law, input, de, out, &d));
        }
        de[ZZ] -= step;
    }
    Err(IntegrationFailure::not_converged(
        name,
        format!(
            "plane stress (C_PLAN): σ_zz = {last_residual:e} after {MAX_ITERATIONS} Newton \
             iterations on ε_zz"
        ),
    ))
}

/// The converged update: σ_zz set to 0 (it is round-off), the tangent
/// asked for condensed.
fn finish(
    law: &dyn SmallStrainBehaviour,
    input: &SmallStrainInput,
    de: Vec6,
    mut out: SmallStrainOutput,
    consistent: &Mat6,
) -> PlaneStressOutput {
    out.stress[ZZ] = 0.0;
    out.tangent = match input.tangent {
        TangentKind::None => None,
        TangentKind::Consistent => Some(condense(consistent)),
        TangentKind::Elastic => Some(law.elastic_params().map_or_else(
            || condense(consistent),
            |p| condense(&super::voigt::isotropic_elastic(p.bulk(), p.mu())),
        )),
    };
    PlaneStressOutput {
        output: out,
        strain_zz: de[ZZ],
    }
}

/// D − D_·z D_z· / D_zz: the tangent at σ_zz = 0 for in-plane strains.
pub fn condense(d: &Mat6) -> Mat6 {
    let dzz = d[(ZZ, ZZ)];
    let mut c = *d;
    for i in 0..6 {
        for j in 0..6 {
            c[(i, j)] = if i == ZZ || j == ZZ {
                0.0
            } else {
                d[(i, j)] - d[(i, ZZ)] * d[(ZZ, j)] / dzz
            };
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::elas::Elas;
    use crate::law::vmis_cine_line::VmisCineLine;
    use crate::law::vmis_isot_line::VmisIsotLine;
    use crate::law::{EcroLineParams, ElasParams, Regime};

    fn input(stress: Vec6, internal: &[f64], de: Vec6) -> SmallStrainInput<'_> {
        SmallStrainInput {
            stress,
            internal,
            strain_increment: de,
            dt: 0.0,
            tangent: TangentKind::Consistent,
        }
    }

    /// Hooke in plane stress: σ_xx = E/(1−ν²)(ε_xx + ν ε_yy), σ_xy = G γ,
    /// ε_zz = −ν/(1−ν)(ε_xx + ε_yy), and the condensed tangent is the
    /// textbook plane-stress matrix.
    #[test]
    fn elastic_plane_stress_is_the_closed_form() {
        let (e, nu) = (200_000.0, 0.3);
        let law = Elas::new(ElasParams::new(e, nu, None).unwrap());
        let de = Vec6::new(1e-3, -2e-4, 0.0, 5e-4, 0.0, 0.0);
        let out = integrate(&law, &input(Vec6::zeros(), &[0.0], de)).unwrap();
        let s = out.output.stress;
        let c = e / (1.0 - nu * nu);
        assert!((s[0] - c * (de[0] + nu * de[1])).abs() < 1e-9 * c * 1e-3);
        assert!((s[1] - c * (de[1] + nu * de[0])).abs() < 1e-9 * c * 1e-3);
        assert!((s[3] - e / (2.0 * (1.0 + nu)) * de[3]).abs() < 1e-9);
        assert_eq!(s[2], 0.0);
        let ezz = -nu / (1.0 - nu) * (de[0] + de[1]);
        assert!((out.strain_zz - ezz).abs() < 1e-15, "{}", out.strain_zz);
        let d = out.output.tangent.unwrap();
        assert!((d[(0, 0)] - c).abs() < 1e-9 * c);
        assert!((d[(0, 1)] - c * nu).abs() < 1e-9 * c);
        assert!(d.row(2).iter().all(|v| *v == 0.0) && d.column(2).iter().all(|v| *v == 0.0));
    }

    /// Uniaxial plane stress past yield is the 1D law: σ = SY + E_T (ε −
    /// SY/E) with p = (ε − σ/E) and ε_zz = ε_yy = −ν σ/E − p/2; the
    /// condensed tangent matches central differences of the update.
    #[test]
    fn plastic_uniaxial_is_one_dimensional_and_the_tangent_is_consistent() {
        let (e, nu, sy, et) = (200_000.0, 0.3, 200.0, 2_000.0);
        let elas = ElasParams::new(e, nu, None).unwrap();
        let law = VmisIsotLine::new(elas, EcroLineParams::new(&elas, sy, et).unwrap());
        // σ_yy = 0 as well: drive ε_yy by the 1D answer, check σ_yy ≈ 0.
        let eps = 0.01;
        let sig = sy + et * (eps - sy / e);
        let p = eps - sig / e;
        let eyy = -nu * sig / e - 0.5 * p;
        let de = Vec6::new(eps, eyy, 0.0, 0.0, 0.0, 0.0);
        let out = integrate(&law, &input(Vec6::zeros(), &[0.0, 0.0], de)).unwrap();
        let s = out.output.stress;
        assert!((s[0] - sig).abs() < 1e-8 * sig, "{} vs {sig}", s[0]);
        assert!(s[1].abs() < 1e-8 * sig, "{}", s[1]);
        assert!((out.output.internal.as_slice()[0] - p).abs() < 1e-12);
        assert!(
            (out.strain_zz - eyy).abs() < 1e-12,
            "{} vs {eyy}",
            out.strain_zz
        );
        assert_eq!(out.output.regime, Regime::Plastic);
        let d = out.output.tangent.unwrap();
        crate::law::assert_tangent_by_differences(&d, de, 1.0, "C_PLAN ", |x| {
            integrate(&law, &input(Vec6::zeros(), &[0.0, 0.0], x))
                .unwrap()
                .output
                .stress
        });
    }

    /// A law with its own local iterations (VMIS_JOHN_COOK's scalar
    /// root at its RESI_INTE_RELA) converges too: σ_zz = 0, the output
    /// is the 3D update at the solved Δε_zz, and the condensed tangent
    /// matches central differences.
    #[test]
    fn john_cook_converges_and_its_tangent_is_consistent() {
        use crate::law::john_cook::{EcroCookParams, LocalControls, VmisJohnCook};
        let elas = ElasParams::new(117_000.0, 0.35, Some(8.93e-9)).unwrap();
        let ecro = EcroCookParams::new(90.0, 292.0, 0.025, 0.31, 1.09, 1.0, 298.0, 1083.0).unwrap();
        let law = VmisJohnCook::new(elas, ecro, LocalControls::default());
        let z = law.initial_internal();
        let de = Vec6::new(4e-3, -1e-3, 0.0, 2e-3, 0.0, 0.0);
        let run = |x: Vec6| {
            integrate(
                &law,
                &SmallStrainInput {
                    dt: 1e-6,
                    ..input(Vec6::zeros(), z.as_slice(), x)
                },
            )
            .unwrap()
        };
        let out = run(de);
        assert_eq!(out.output.regime, Regime::Plastic);
        let mut de3 = de;
        de3[2] = out.strain_zz;
        let direct = law
            .integrate(&SmallStrainInput {
                dt: 1e-6,
                ..input(Vec6::zeros(), z.as_slice(), de3)
            })
            .unwrap();
        assert!(
            direct.stress[2].abs() < 1e-9 * direct.stress.amax(),
            "{}",
            direct.stress
        );
        for i in [0, 1, 3] {
            assert!((direct.stress[i] - out.output.stress[i]).abs() < 1e-12 * direct.stress.amax());
        }
        let d = out.output.tangent.unwrap();
        crate::law::assert_tangent_by_differences(&d, de, 5.0, "C_PLAN john_cook ", |x| {
            run(x).output.stress
        });
    }

    /// Kinematic hardening: a biaxial step past yield and back keeps
    /// σ_zz = 0 with a condensed tangent equal to its differences.
    #[test]
    fn kinematic_hardening_tangent_by_differences() {
        let (e, nu, sy, et) = (200_000.0, 0.3, 200.0, 20_000.0);
        let elas = ElasParams::new(e, nu, None).unwrap();
        let law = VmisCineLine::new(elas, EcroLineParams::new(&elas, sy, et).unwrap());
        let z = [0.0; 7];
        let de = Vec6::new(2e-3, 1e-3, 0.0, 1e-3, 0.0, 0.0);
        let out = integrate(&law, &input(Vec6::zeros(), &z, de)).unwrap();
        assert_eq!(out.output.stress[2], 0.0);
        let d = out.output.tangent.unwrap();
        crate::law::assert_tangent_by_differences(&d, de, 2.0, "C_PLAN cine ", |x| {
            integrate(&law, &input(Vec6::zeros(), &z, x))
                .unwrap()
                .output
                .stress
        });
    }
}
