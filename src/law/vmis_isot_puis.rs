//! `VMIS_ISOT_PUIS`: von Mises plasticity with isotropic hardening by a
//! power law (DEFI_MATERIAU ECRO_PUIS: SY, A_PUIS, N_PUIS), small strains;
//! the radial return of VMIS_ISOT_LINE ([`super::vmis_isot_line::radial_return`])
//! with one more [`IsotropicHardening`].
//!
//! R(p) is code_aster's (`nmisot`, `ecpuis`):
//!   R(p) = SY + SY·(E·p / (A_PUIS·SY))^(1/N_PUIS),
//! E the ELAS Young's modulus (unlike VMIS_ISOT_TRAC, the law's elasticity
//! is ELAS's). Under uniaxial stress ε = σ/E + (A_PUIS·SY/E)·(σ/SY − 1)^N,
//! the Ramberg–Osgood-like curve the law is meant to give. For N > 1,
//! R'(0) is infinite: `ecpuis` replaces R by its chord on [0, p₀],
//! p₀ = 1e-10, and so does this law (R continuous, R' finite).
//!
//! The scalar equation q_tr − 3μΔp = R(p_n + Δp) has its root in
//! [0, (q_tr − R(p_n))/3μ] (the left side falls, R rises); code_aster
//! solves it with DEKKER to |residual| ≤ RESI_INTE_RELA·SY. Here a Newton
//! iteration safeguarded by that bracket ([`super::root1d::newton_bracketed`])
//! goes on to round-off (two more quadratic steps), so that the verification
//! can check the closed form to 1e-9; RESI_INTE_RELA·SY stays the
//! acceptance bound when ITER_INTE_MAXI runs out first.

use super::john_cook::LocalControls;
use super::root1d::{newton_bracketed, RootFailure};
use super::vmis_isot_line::{self, radial_return, IsotropicHardening};
use super::{
    ElasParams, IntegrationFailure, LawMetadata, MaterialError, SmallStrainBehaviour,
    SmallStrainInput, SmallStrainOutput,
};

/// V1 = EPSPEQ, V2 = INDIPLAS, as VMIS_ISOT_LINE (code_aster's
/// vmis_isot_puis.py: nb_vari = 2).
pub static METADATA: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_PUIS",
    internal_variables: vmis_isot_line::METADATA.internal_variables,
    strain_measures: vmis_isot_line::METADATA.strain_measures,
    tensor_variables: &[],
};

/// `ecpuis`'s p₀: below it R is the chord from (0, SY) to (p₀, R(p₀)).
pub const P0: f64 = 1e-10;

/// R(p) = SY (1 + (E p/(A_PUIS SY))^(1/N_PUIS)), with the chord below p₀.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerHardening {
    pub sy: f64,
    pub a_puis: f64,
    pub n_puis: f64,
    /// E/(A_PUIS·SY).
    coef: f64,
    /// The chord's slope (R(p₀) − SY)/p₀.
    chord: f64,
    /// ITER_INTE_MAXI and RESI_INTE_RELA of the scalar equation.
    pub controls: LocalControls,
}

impl PowerHardening {
    /// `e` is ELAS/E. Refused (keyword ECRO_PUIS/...): SY ≤ 0 (R/SY is the
    /// law's variable), A_PUIS ≤ 0 (E/(A_PUIS·SY) would divide by zero:
    /// code_aster's catalogue allows A_PUIS = 0, its law then divides by
    /// it), N_PUIS ≤ 0 (the catalogue's val_min is 1e-6: below it 1/N
    /// overflows).
    pub fn new(
        e: f64,
        sy: f64,
        a_puis: f64,
        n_puis: f64,
        controls: LocalControls,
    ) -> Result<PowerHardening, MaterialError> {
        let bad = |keyword, message: String| Err(MaterialError { keyword, message });
        if !(sy.is_finite() && sy > 0.0) {
            return bad(
                "ECRO_PUIS/SY",
                format!("the yield stress SY must be finite and > 0, got {sy}"),
            );
        }
        if !(a_puis.is_finite() && a_puis > 0.0) {
            return bad(
                "ECRO_PUIS/A_PUIS",
                format!(
                    "A_PUIS must be finite and > 0 (R(p) = SY (1 + (E p/(A_PUIS SY))^(1/N_PUIS)) \
                     divides by it), got {a_puis}"
                ),
            );
        }
        if !(n_puis.is_finite() && n_puis >= 1e-6) {
            return bad(
                "ECRO_PUIS/N_PUIS",
                format!(
                    "N_PUIS must be finite and >= 1e-6 (the catalogue's val_min), got {n_puis}"
                ),
            );
        }
        let coef = e / (a_puis * sy);
        let chord = sy * (coef * P0).powf(1.0 / n_puis) / P0;
        if !(coef.is_finite() && chord.is_finite()) {
            return bad(
                "ECRO_PUIS/N_PUIS",
                format!(
                    "R(p) overflows with E = {e}, SY = {sy}, A_PUIS = {a_puis}, N_PUIS = {n_puis}"
                ),
            );
        }
        Ok(PowerHardening {
            sy,
            a_puis,
            n_puis,
            coef,
            chord,
            controls,
        })
    }

    /// R(p) (p ≥ 0).
    pub fn r(&self, p: f64) -> f64 {
        if p <= P0 {
            self.sy + self.chord * p
        } else {
            self.sy * (1.0 + (self.coef * p).powf(1.0 / self.n_puis))
        }
    }

    /// R'(p), the chord's slope up to p₀ (`ecpuis`).
    pub fn r_prime(&self, p: f64) -> f64 {
        if p <= P0 {
            self.chord
        } else {
            self.sy * self.coef * (self.coef * p).powf(1.0 / self.n_puis - 1.0) / self.n_puis
        }
    }

    fn failure(&self, message: impl std::fmt::Display) -> IntegrationFailure {
        IntegrationFailure::not_converged(METADATA.name, message)
    }
}

impl IsotropicHardening for PowerHardening {
    fn yield_stress(&self, p: f64) -> f64 {
        self.r(p)
    }

    fn return_map(
        &self,
        q_tr: f64,
        p_n: f64,
        three_mu: f64,
    ) -> Result<(f64, f64), IntegrationFailure> {
        let dp_max = (q_tr - self.r(p_n)) / three_mu;
        let mut g = |dp: f64| {
            let p = p_n + dp;
            (self.r(p) + three_mu * dp - q_tr, self.r_prime(p) + three_mu)
        };
        // code_aster's start: the elastic-slope estimate, corrected by
        // R' there (nmisot).
        let x0 = dp_max / (1.0 + self.r_prime(p_n + dp_max) / three_mu);
        let ctl = self.controls;
        let accept = ctl.resi_rela * self.sy;
        let dp = match newton_bracketed(
            &mut g,
            (0.0, dp_max),
            x0,
            4.0 * f64::EPSILON * q_tr,
            ctl.iter_maxi,
        ) {
            Ok(root) => root.x,
            Err(RootFailure::NotConverged { x, fx }) if fx.abs() <= accept => x,
            Err(e) => {
                return Err(self.failure(format!(
                    "{e} in {} iterations (ITER_INTE_MAXI; RESI_INTE_RELA·SY = {accept:e})",
                    ctl.iter_maxi
                )))
            }
        };
        if !(dp.is_finite() && dp >= 0.0) {
            return Err(self.failure(format!("invalid plastic increment {dp:e}")));
        }
        Ok((dp, self.r_prime(p_n + dp)))
    }

    fn slope(&self, p: f64) -> f64 {
        self.r_prime(p)
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VmisIsotPuis {
    pub elas: ElasParams,
    pub hardening: PowerHardening,
    mu: f64,
    bulk: f64,
}

impl VmisIsotPuis {
    pub fn new(elas: ElasParams, hardening: PowerHardening) -> VmisIsotPuis {
        VmisIsotPuis {
            elas,
            hardening,
            mu: elas.mu(),
            bulk: elas.bulk(),
        }
    }
}

impl SmallStrainBehaviour for VmisIsotPuis {
    fn metadata(&self) -> &'static LawMetadata {
        &METADATA
    }

    fn elastic_params(&self) -> Option<ElasParams> {
        Some(self.elas)
    }

    fn integrate(&self, input: &SmallStrainInput) -> Result<SmallStrainOutput, IntegrationFailure> {
        radial_return(&METADATA, input, self.mu, self.bulk, &self.hardening)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::{TangentKind, Vec6};

    const E: f64 = 200_000.0;
    const SY: f64 = 200.0;

    fn law(a: f64, n: f64) -> VmisIsotPuis {
        let elas = ElasParams::new(E, 0.3, None).unwrap();
        let h = PowerHardening::new(E, SY, a, n, LocalControls::default()).unwrap();
        VmisIsotPuis::new(elas, h)
    }

    /// ε(σ) of uniaxial stress, written from the formula: σ/E + p with
    /// R(p) = σ inverted by hand, p = (A SY/E)(σ/SY − 1)^N.
    fn eps_of_sigma(a: f64, n: f64, s: f64) -> f64 {
        s / E + a * SY / E * (s / SY - 1.0).max(0.0).powf(n)
    }

    /// Uniaxial stress σ_zz by a strain path, lateral strains by a Newton
    /// on σ_xx = σ_yy = 0; (σ_zz, p) after each point.
    fn uniaxial(law: &VmisIsotPuis, strains: &[f64]) -> Vec<(f64, f64)> {
        let mut stress = Vec6::zeros();
        let mut internal = law.initial_internal();
        let (mut ez_prev, mut lat_prev) = (0.0, 0.0);
        let mut out = Vec::new();
        for &ez in strains {
            let mut lat = lat_prev;
            let mut done = None;
            for _ in 0..50 {
                let de = Vec6::new(lat - lat_prev, lat - lat_prev, ez - ez_prev, 0., 0., 0.);
                let o = law
                    .integrate(&SmallStrainInput {
                        stress,
                        internal: internal.as_slice(),
                        strain_increment: de,
                        dt: 0.0,
                        tangent: TangentKind::Consistent,
                    })
                    .unwrap();
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
            out.push((o.stress[2], o.internal.as_slice()[0]));
        }
        out
    }

    /// The stress at the strains ε(σ_k) of chosen σ_k is σ_k to 1e-9, and
    /// p = ε − σ/E, for a concave (N = 3), a linear (N = 1: H = E/A) and
    /// a convex (N = 0.5) law, each point reached in one step from the
    /// previous one (the return solves the whole increment).
    #[test]
    fn uniaxial_stress_follows_the_power_curve() {
        for (a, n) in [(0.5, 3.0), (2.0, 1.0), (50.0, 0.5)] {
            let law = law(a, n);
            let sigmas = [100.0, 200.0 + 1e-9, 230.0, 300.0, 450.0, 700.0];
            let strains: Vec<f64> = sigmas.iter().map(|&s| eps_of_sigma(a, n, s)).collect();
            for ((s, p), (&want, &e)) in uniaxial(&law, &strains)
                .iter()
                .zip(sigmas.iter().zip(&strains))
            {
                assert!(
                    (s - want).abs() <= 1e-9 * want,
                    "A {a} N {n}: eps {e}: sigma {s} against {want}"
                );
                let p_want = (e - want / E).max(0.0);
                assert!(
                    (p - p_want).abs() <= 1e-9 * p_want.max(1e-9),
                    "A {a} N {n}: p {p} against {p_want}"
                );
            }
        }
    }

    /// R is code_aster's: SY at 0, its chord below p₀, the power above,
    /// continuous at p₀; E enters through E/(A SY).
    #[test]
    fn hardening_is_ecpuis() {
        let h = PowerHardening::new(E, SY, 0.5, 3.0, LocalControls::default()).unwrap();
        assert_eq!(h.r(0.0), SY);
        let p = 0.01;
        let want = SY + SY * (E * p / (0.5 * SY)).powf(1.0 / 3.0);
        assert!((h.r(p) - want).abs() < 1e-12 * want);
        let r0 = SY + SY * (E * P0 / (0.5 * SY)).powf(1.0 / 3.0);
        assert!((h.r(P0) - r0).abs() < 1e-12 * r0);
        assert!((h.r(P0 * (1.0 + 1e-9)) - r0).abs() < 1e-6);
        assert!((h.r(P0 / 2.0) - (SY + (r0 - SY) / 2.0)).abs() < 1e-9);
        // R' against a central difference away from p₀.
        let d = 1e-9;
        let fd = (h.r(p + d) - h.r(p - d)) / (2.0 * d);
        assert!((h.r_prime(p) - fd).abs() < 1e-5 * fd);
    }

    /// The consistent tangent against central differences of the update,
    /// from a hardened state, for a concave and a convex law.
    #[test]
    fn tangent_is_the_derivative_of_the_update() {
        for (a, n) in [(0.5, 3.0), (50.0, 0.5)] {
            let law = law(a, n);
            let stress = Vec6::new(300.0, -100.0, 0.0, 100.0, 0.0, 50.0);
            let internal = [0.0005, 1.0];
            let de = Vec6::new(0.003, -0.001, 0.004, 0.002, 0.001, 0.0);
            let run = |d: Vec6, tangent| {
                law.integrate(&SmallStrainInput {
                    stress,
                    internal: &internal,
                    strain_increment: d,
                    dt: 0.0,
                    tangent,
                })
                .unwrap()
            };
            let base = run(de, TangentKind::Consistent);
            assert!(
                base.internal.as_slice()[0] > 0.0006,
                "{}",
                base.internal.as_slice()[0]
            );
            let d = base.tangent.unwrap();
            crate::law::assert_tangent_by_differences(&d, de, 1e-6 * E, &format!("N {n}: "), |x| {
                run(x, TangentKind::None).stress
            });
        }
    }

    #[test]
    fn bad_parameters_are_refused_with_their_keyword() {
        let c = LocalControls::default();
        let k = |r: Result<PowerHardening, MaterialError>| r.unwrap_err().keyword;
        assert_eq!(k(PowerHardening::new(E, 0.0, 1.0, 2.0, c)), "ECRO_PUIS/SY");
        assert_eq!(
            k(PowerHardening::new(E, SY, 0.0, 2.0, c)),
            "ECRO_PUIS/A_PUIS"
        );
        assert_eq!(
            k(PowerHardening::new(E, SY, 1.0, 0.0, c)),
            "ECRO_PUIS/N_PUIS"
        );
        assert_eq!(
            k(PowerHardening::new(E, SY, 1.0, -1.0, c)),
            "ECRO_PUIS/N_PUIS"
        );
        assert_eq!(
            k(PowerHardening::new(E, SY, 1.0, f64::NAN, c)),
            "ECRO_PUIS/N_PUIS"
        );
    }

    /// ITER_INTE_MAXI = 1 cannot reach round-off; the step is refused
    /// unless RESI_INTE_RELA·SY accepts the residual, and then returns.
    #[test]
    fn too_few_iterations_cut_the_step() {
        let elas = ElasParams::new(E, 0.3, None).unwrap();
        let tight = LocalControls {
            iter_maxi: 1,
            resi_rela: 1e-12,
            ..LocalControls::default()
        };
        let h = PowerHardening::new(E, SY, 0.5, 3.0, tight).unwrap();
        let law = VmisIsotPuis::new(elas, h);
        let input = SmallStrainInput {
            stress: Vec6::zeros(),
            internal: &[0.0, 0.0],
            strain_increment: Vec6::new(-0.002, -0.002, 0.01, 0., 0., 0.),
            dt: 0.0,
            tangent: TangentKind::None,
        };
        let e = law.integrate(&input).unwrap_err();
        assert_eq!(e.kind, crate::law::FailureKind::NotConverged);
        assert!(e.message.contains("ITER_INTE_MAXI"), "{e}");
        let loose = LocalControls {
            iter_maxi: 1,
            resi_rela: 1e3,
            ..LocalControls::default()
        };
        let h = PowerHardening::new(E, SY, 0.5, 3.0, loose).unwrap();
        assert!(VmisIsotPuis::new(elas, h).integrate(&input).is_ok());
    }
}
