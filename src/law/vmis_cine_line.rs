//! `VMIS_CINE_LINE`: von Mises plasticity with linear kinematic (Prager)
//! hardening, small strains (code_aster `nmcine.F90`, R5.03.02 §2;
//! Simo & Hughes, *Computational Inelasticity*, 1998, §3.3 with H = 0).
//!
//! Yield f = (σ − X)_eq − SY ≤ 0 with the back stress X = C εᵖ, whose
//! constant is code_aster's C = (2/3)·E·E_T/(E − E_T) (`nmcine`'s
//! c = 2/3·D_SIGM_EPSI/(1 − D_SIGM_EPSI/E)), i.e. X = (2/3)·H·εᵖ with the
//! H = E·E_T/(E − E_T) of VMIS_ISOT_LINE: under uniaxial stress the curve
//! has slope E_T, as for the isotropic law, and the reverse yield is at
//! σ_max − 2·SY (the Bauschinger effect).
//!
//! Radial return on ξ = s − X (closed form, no local iteration):
//! ξ_tr = dev σ_n + 2μ Δe − X_n, q = (ξ_tr)_eq; elastic when q ≤ SY;
//! otherwise Δp = (q − SY)/(3μ + 3C/2), n = 3/2 ξ_tr/q, s = s_tr − 2μΔp n,
//! X = X_n + C Δp n. The mean stress is elastic.
//!
//! Consistent tangent (the derivative of that update):
//! K 1⊗1 + 2μθ I_dev − 2μθ̄ n̂⊗n̂, n̂ = ξ_tr/|ξ_tr|, θ = 1 − 3μΔp/q,
//! θ̄ = 3μ/(3μ + 3C/2) − (1 − θ): VMIS_ISOT_LINE's with H = 3C/2.
//! code_aster's FULL_MECA tangent in `nmcine` is written in the end
//! state's σ − X; it is not used here, the update's derivative is what a
//! Newton iteration converges with.
//!
//! Internal variables (code_aster's vmis_cine_line.py, nb_vari = 7 in
//! every modelisation): V1..V6 = XCINXX, XCINYY, XCINZZ, XCINXY, XCINXZ,
//! XCINYZ, the back stress with tensor shear components (`nmcine`
//! divides its √2-scaled shears back), V7 = INDIPLAS (0/1). There is no
//! cumulative plastic strain among them. code_aster 15.2's catalogue
//! briefly had an eighth, EPSPEQ; its 16+ catalogue and its law write 7.

use super::voigt::{deviator, deviatoric_projector, double_dot, isotropic_elastic, one_one, trace};
use super::{
    check_small_strain_input, EcroLineParams, ElasParams, IntegrationFailure, InternalVars,
    LawMetadata, Regime, SmallStrainBehaviour, SmallStrainInput, SmallStrainOutput, StrainMeasure,
    TangentKind, Vec6,
};

/// code_aster's DEFORMATION list for the law has no SIMO_MIEHE.
pub static METADATA: LawMetadata = LawMetadata {
    name: "VMIS_CINE_LINE",
    internal_variables: &[
        "XCINXX", "XCINYY", "XCINZZ", "XCINXY", "XCINXZ", "XCINYZ", "INDIPLAS",
    ],
    strain_measures: &[
        StrainMeasure::Petit,
        StrainMeasure::PetitReac,
        StrainMeasure::GrotGdep,
        StrainMeasure::GdefLog,
    ],
    tensor_variables: &[0],
};

/// As VMIS_ISOT_LINE's rule for a zero increment on the surface.
const ON_SURFACE: f64 = 1e-10;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VmisCineLine {
    pub elas: ElasParams,
    pub ecro: EcroLineParams,
    mu: f64,
    bulk: f64,
    c: f64,
}

impl VmisCineLine {
    pub fn new(elas: ElasParams, ecro: EcroLineParams) -> VmisCineLine {
        VmisCineLine {
            elas,
            ecro,
            mu: elas.mu(),
            bulk: elas.bulk(),
            c: 2.0 / 3.0 * ecro.hardening(&elas),
        }
    }

    /// Prager's constant C = (2/3)·E·E_T/(E − E_T): X = C εᵖ.
    pub fn prager(&self) -> f64 {
        self.c
    }
}

impl SmallStrainBehaviour for VmisCineLine {
    fn metadata(&self) -> &'static LawMetadata {
        &METADATA
    }

    fn elastic_params(&self) -> Option<ElasParams> {
        Some(self.elas)
    }

    fn integrate(&self, input: &SmallStrainInput) -> Result<SmallStrainOutput, IntegrationFailure> {
        check_small_strain_input(&METADATA, input)?;
        let (mu, k, c, sy) = (self.mu, self.bulk, self.c, self.ecro.sy);
        let x_n = Vec6::from_column_slice(&input.internal[..6]);
        let de = input.strain_increment;
        let s_tr = deviator(&input.stress) + deviatoric_projector() * de * (2.0 * mu);
        let sigma_m = trace(&input.stress) / 3.0 + k * trace(&de);
        let hydro = Vec6::new(sigma_m, sigma_m, sigma_m, 0.0, 0.0, 0.0);
        let xi = s_tr - x_n;
        let q = (1.5 * double_dot(&xi, &xi)).sqrt();
        let elastic_d = isotropic_elastic(k, mu);
        let mut internal = InternalVars::zeros(METADATA.internal_variables.len());
        // The zero-increment rule of VMIS_ISOT_LINE (a prediction from a
        // point on the surface takes the plastic tangent), for the same
        // reason: the regime must not be the sign of the last bits of q − SY.
        let on_surface = de.iter().all(|v| *v == 0.0) && q > 0.0 && q >= sy * (1.0 - ON_SURFACE);
        if q <= sy && !on_surface {
            internal.as_mut_slice()[..6].copy_from_slice(x_n.as_slice());
            return Ok(SmallStrainOutput {
                stress: s_tr + hydro,
                internal,
                tangent: match input.tangent {
                    TangentKind::None => None,
                    _ => Some(elastic_d),
                },
                regime: Regime::Elastic,
            });
        }
        let h = 1.5 * c;
        let dp = if on_surface {
            0.0
        } else {
            (q - sy) / (3.0 * mu + h)
        };
        // n = 3/2 ξ_tr/q: s loses 2μΔp n, X gains C Δp n.
        let n = xi * (1.5 / q);
        let s = s_tr - n * (2.0 * mu * dp);
        let x = x_n + n * (c * dp);
        let v = internal.as_mut_slice();
        v[..6].copy_from_slice(x.as_slice());
        v[6] = 1.0;
        let tangent = match input.tangent {
            TangentKind::None => None,
            TangentKind::Elastic => Some(elastic_d),
            TangentKind::Consistent => {
                let theta = 1.0 - 3.0 * mu * dp / q;
                let theta_bar = 3.0 * mu / (3.0 * mu + h) - (1.0 - theta);
                let unit = xi / double_dot(&xi, &xi).sqrt();
                Some(
                    one_one() * k + deviatoric_projector() * (2.0 * mu * theta)
                        - unit * unit.transpose() * (2.0 * mu * theta_bar),
                )
            }
        };
        Ok(SmallStrainOutput {
            stress: s + hydro,
            internal,
            tangent,
            regime: Regime::Plastic,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const E: f64 = 200_000.0;
    const NU: f64 = 0.3;
    const SY: f64 = 200.0;
    const ET: f64 = 20_000.0;

    fn law() -> VmisCineLine {
        let elas = ElasParams::new(E, NU, None).unwrap();
        VmisCineLine::new(elas, EcroLineParams::new(&elas, SY, ET).unwrap())
    }

    fn step(
        law: &VmisCineLine,
        stress: Vec6,
        internal: &[f64],
        de: Vec6,
        tangent: TangentKind,
    ) -> SmallStrainOutput {
        law.integrate(&SmallStrainInput {
            stress,
            internal,
            strain_increment: de,
            dt: 0.0,
            tangent,
        })
        .unwrap()
    }

    /// Uniaxial stress σ_zz by a strain path ε_zz, the lateral strains
    /// found by a Newton on σ_xx = σ_yy = 0; returns (σ_zz, X_zz, V)
    /// after each point.
    fn uniaxial(law: &VmisCineLine, strains: &[f64]) -> Vec<(f64, f64, InternalVars)> {
        let mut stress = Vec6::zeros();
        let mut internal = law.initial_internal();
        let (mut ez_prev, mut lat_prev) = (0.0, 0.0);
        let mut out = Vec::new();
        for &ez in strains {
            let mut lat = lat_prev;
            let mut done = None;
            for _ in 0..50 {
                let de = Vec6::new(lat - lat_prev, lat - lat_prev, ez - ez_prev, 0., 0., 0.);
                let o = step(
                    law,
                    stress,
                    internal.as_slice(),
                    de,
                    TangentKind::Consistent,
                );
                if o.stress[0].abs() < 1e-11 {
                    done = Some(o);
                    break;
                }
                let d = o.tangent.unwrap();
                lat -= o.stress[0] / (d[(0, 0)] + d[(0, 1)]);
            }
            let o = done.expect("lateral Newton converged");
            stress = o.stress;
            internal = o.internal;
            (ez_prev, lat_prev) = (ez, lat);
            out.push((o.stress[2], o.internal.as_slice()[2], o.internal));
        }
        out
    }

    /// Tension to 1 %, unloading through zero stress to the reverse yield
    /// σ_max − 2 SY and compression past it: every stress on the closed
    /// form of the bilinear kinematic curve, and X_zz = (2/3)·H·εᵖ_zz
    /// (H = E E_T/(E − E_T), C = 2H/3) to 1e-9.
    #[test]
    fn uniaxial_tension_unloading_compression_is_the_bauschinger_curve() {
        let law = law();
        let h = E * ET / (E - ET);
        assert!((law.prager() - 2.0 / 3.0 * h).abs() < 1e-9 * h);
        let eps_y = SY / E;
        // loading: σ = SY + E_T (ε − ε_y); σ_max at ε = 0.01.
        let s_max = SY + ET * (0.01 - eps_y);
        // reverse yield at σ_max − 2 SY, reached at ε_r:
        let e_r = 0.01 - 2.0 * SY / E;
        let closed = |e: f64, loading: bool| {
            if loading {
                if e <= eps_y {
                    E * e
                } else {
                    SY + ET * (e - eps_y)
                }
            } else if e >= e_r {
                s_max - E * (0.01 - e)
            } else {
                s_max - 2.0 * SY + ET * (e - e_r)
            }
        };
        let path: Vec<(f64, bool)> = [
            (5e-4, true),
            (1e-3, true),
            (4e-3, true),
            (0.01, true),
            (0.009, false),
            (0.0085, false),
            (0.0079, false),
            (0.004, false),
            (-0.004, false),
        ]
        .to_vec();
        let strains: Vec<f64> = path.iter().map(|p| p.0).collect();
        let got = uniaxial(&law, &strains);
        for ((e, loading), (s, x_zz, _)) in path.iter().zip(&got) {
            let want = closed(*e, *loading);
            assert!(
                (s - want).abs() <= 1e-9 * want.abs().max(SY),
                "eps {e}: sigma {s} against {want}"
            );
            // εᵖ_zz = ε − σ/E, and X_zz = (2/3) H εᵖ_zz.
            let x_want = 2.0 / 3.0 * h * (e - want / E);
            assert!(
                (x_zz - x_want).abs() <= 1e-9 * SY,
                "eps {e}: X_zz {x_zz} against {x_want}"
            );
        }
        // The reverse yield itself: σ_max − 2 SY = −20 at ε = 0.008.
        assert!((closed(e_r, false) - (s_max - 2.0 * SY)).abs() < 1e-9);
        assert!((s_max - 2.0 * SY + 20.0).abs() < 1e-9);
        // X is deviatoric: X_xx = X_yy = −X_zz/2, no shear; plastic.
        let x = got.last().unwrap().2;
        let x = x.as_slice();
        assert!((x[0] - x[1]).abs() < 1e-9 && (x[0] + x[1] + x[2]).abs() < 1e-9);
        assert!(x[3..6].iter().all(|v| v.abs() < 1e-12));
        assert_eq!(x[6], 1.0);
    }

    /// The continuum flow rule integrated explicitly in 200 000 steps of
    /// σ̇ = D_ep ε̇ (D_ep = K 1⊗1 + 2μ I_dev − 2μ·3μ/(3μ + 3C/2) n̂⊗n̂ on
    /// the surface, loading; elastic otherwise), with Ẋ = C ε̇ᵖ written
    /// here from the rate equations, against the law in 2 000 steps, on
    /// a shear-then-tension path (non-proportional: the return is not
    /// exact there, both are first order in the step).
    #[test]
    fn shear_then_tension_matches_an_explicit_integration() {
        let law = law();
        let (mu, k, c) = (law.mu, law.bulk, law.prager());
        // strain path: γ_xy to 0.01, then ε_zz to 0.01 with γ held.
        let legs = [
            Vec6::new(0., 0., 0., 0.01, 0., 0.),
            Vec6::new(-0.003, -0.003, 0.01, 0., 0., 0.),
        ];
        // the law
        let mut s = Vec6::zeros();
        let mut v = law.initial_internal();
        let n_law = 2000;
        for leg in legs {
            for _ in 0..n_law {
                let o = step(&law, s, v.as_slice(), leg / n_law as f64, TangentKind::None);
                s = o.stress;
                v = o.internal;
            }
        }
        // explicit integration of the rate equations
        let mut se = Vec6::zeros();
        let mut xe = Vec6::zeros();
        let n_exp = 200_000;
        let dev = deviatoric_projector();
        for leg in legs {
            let de = leg / n_exp as f64;
            for _ in 0..n_exp {
                let xi = deviator(&se) - xe;
                let q = (1.5 * double_dot(&xi, &xi)).sqrt();
                let de_dev = dev * de; // tensor deviatoric strain rate
                let n = xi * (1.5 / q.max(1e-300));
                // ε̇ᵖ = λ n with λ from the consistency condition.
                let lambda = if q >= SY * (1.0 - 1e-12) {
                    let num = double_dot(&n, &de_dev) * 2.0 * mu;
                    if num > 0.0 {
                        // ∂f/∂σ : (2μ(ė − λn) − Cλn) = 0, n:n = 3/2.
                        num / (1.5 * (2.0 * mu + c))
                    } else {
                        0.0
                    }
                } else {
                    0.0
                };
                let dep = n * lambda;
                se += de_dev * (2.0 * mu) - dep * (2.0 * mu)
                    + Vec6::new(1., 1., 1., 0., 0., 0.) * (k * trace(&de));
                xe += dep * c;
                // pull back onto the surface (the drift of explicit steps)
                let xi = deviator(&se) - xe;
                let q = (1.5 * double_dot(&xi, &xi)).sqrt();
                if q > SY {
                    let excess = xi * (1.0 - SY / q);
                    se -= excess * (2.0 * mu / (2.0 * mu + c));
                    xe += excess * (c / (2.0 * mu + c));
                }
            }
        }
        let x = Vec6::from_column_slice(&v.as_slice()[..6]);
        let tol = 2e-3 * SY;
        assert!(
            (s - se).amax() < tol,
            "stress {s} against the explicit {se}"
        );
        assert!((x - xe).amax() < tol, "X {x} against the explicit {xe}");
        // The path is indeed non-proportional: shear and axial stresses
        // both present, and the shear stress fell while pulling.
        assert!(s[3].abs() > 20.0 && s[2] > SY, "{s}");
        let xi = deviator(&s) - x;
        assert!(((1.5 * double_dot(&xi, &xi)).sqrt() - SY).abs() < 1e-9 * SY);
    }

    /// The consistent tangent against central differences of the update,
    /// from a hardened state with a back stress, on a plastic step.
    #[test]
    fn tangent_is_the_derivative_of_the_update() {
        let law = law();
        // a state on the surface: X from a prior shear.
        let o = step(
            &law,
            Vec6::zeros(),
            law.initial_internal().as_slice(),
            Vec6::new(0., 0., 0., 0.006, 0.002, 0.),
            TangentKind::None,
        );
        let (stress, internal) = (o.stress, o.internal);
        let de = Vec6::new(0.002, -0.001, 0.003, -0.004, 0.001, 0.002);
        let run = |d: Vec6, t| step(&law, stress, internal.as_slice(), d, t);
        let base = run(de, TangentKind::Consistent);
        assert_eq!(base.regime, Regime::Plastic);
        let d = base.tangent.unwrap();
        crate::law::assert_tangent_by_differences(&d, de, 1e-6 * E, "", |x| {
            run(x, TangentKind::None).stress
        });
        // symmetric, as code_aster declares it (syme_matr_tang).
        assert!((d - d.transpose()).amax() < 1e-9 * E);
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let law = law();
        let e = law
            .integrate(&SmallStrainInput {
                stress: Vec6::zeros(),
                internal: &[0.0; 2],
                strain_increment: Vec6::zeros(),
                dt: 0.0,
                tangent: TangentKind::None,
            })
            .unwrap_err();
        assert!(e.message.contains("7 expected"), "{e}");
        let e = law
            .integrate(&SmallStrainInput {
                stress: Vec6::repeat(f64::NAN),
                internal: &[0.0; 7],
                strain_increment: Vec6::zeros(),
                dt: 0.0,
                tangent: TangentKind::None,
            })
            .unwrap_err();
        assert!(e.message.contains("non-finite"), "{e}");
    }
}
