//! `VMIS_ISOT_TRAC`: von Mises plasticity with isotropic hardening read
//! from a uniaxial traction curve (DEFI_MATERIAU TRACTION/SIGM), small
//! strains; the same radial return as VMIS_ISOT_LINE
//! ([`super::vmis_isot_line::radial_return`]) with a piecewise linear R(p).
//!
//! The curve σ(ε) becomes R(p) as code_aster's `rctrac` builds it: the
//! law's Young's modulus is the slope of the first point, E = σ₁/ε₁ (not
//! ELAS/E, which code_aster reads only for NU here), the first point is
//! the yield, p_k = ε_k − σ_k/E and R(p_k) = σ_k. Under uniaxial stress
//! the law then reproduces the given curve point for point. Beyond the
//! last point R follows the function's PROL_DROITE: 'CONSTANT' (perfect
//! plasticity), 'LINEAIRE' (the last slope), or 'EXCLU' (code_aster's
//! default for DEFI_FONCTION), which stops the integration with a message.

use super::vmis_isot_line::{self, radial_return, IsotropicHardening};
use super::{
    ElasParams, IntegrationFailure, LawMetadata, MaterialError, SmallStrainBehaviour,
    SmallStrainInput, SmallStrainOutput,
};

/// V1 = EPSPEQ (cumulative plastic strain p), V2 = INDIPLAS (0/1), as
/// VMIS_ISOT_LINE.
pub static METADATA: LawMetadata = LawMetadata {
    name: "VMIS_ISOT_TRAC",
    internal_variables: vmis_isot_line::METADATA.internal_variables,
    strain_measures: vmis_isot_line::METADATA.strain_measures,
    tensor_variables: &[],
};

/// What R(p) does past the last point of the curve: the function's
/// PROL_DROITE, read as it is.
pub use crate::post::function::Extrapolation as RightExtension;

/// R(p), piecewise linear through (p_k, R_k), p_0 = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct TractionCurve {
    young: f64,
    p: Vec<f64>,
    r: Vec<f64>,
    right: RightExtension,
}

impl TractionCurve {
    /// From the points (ε_k, σ_k) of TRACTION/SIGM (abscissas EPSI).
    /// Refused: an empty curve, a first point that is not a positive
    /// (ε, σ), a segment at least as steep as the first slope (p would
    /// not grow: R(p) would not be a function), and a falling σ
    /// (softening, which this return does not handle).
    pub fn new(
        eps: &[f64],
        sig: &[f64],
        right: RightExtension,
    ) -> Result<TractionCurve, MaterialError> {
        let bad = |message: String| MaterialError {
            keyword: "TRACTION/SIGM",
            message,
        };
        if eps.is_empty() || eps.len() != sig.len() {
            return Err(bad("the traction curve has no point".into()));
        }
        if eps.iter().chain(sig).any(|v| !v.is_finite()) {
            return Err(bad("the traction curve has a non-finite value".into()));
        }
        if !(eps[0] > 0.0 && sig[0] > 0.0) {
            return Err(bad(format!(
                "the first point of the traction curve is the elastic limit and gives Young's \
                 modulus E = SIGM/EPSI: it must have EPSI > 0 and SIGM > 0, got ({}, {})",
                eps[0], sig[0]
            )));
        }
        let young = sig[0] / eps[0];
        let mut p = vec![0.0];
        let mut r = vec![sig[0]];
        for k in 1..eps.len() {
            let pk = eps[k] - sig[k] / young;
            if pk <= p[k - 1] {
                return Err(bad(format!(
                    "segment {k} of the traction curve, from ({}, {}) to ({}, {}), is at least \
                     as steep as the first slope E = SIGM/EPSI = {young}: the plastic strain \
                     EPSI - SIGM/E must grow along the curve",
                    eps[k - 1],
                    sig[k - 1],
                    eps[k],
                    sig[k]
                )));
            }
            if sig[k] < sig[k - 1] {
                return Err(bad(format!(
                    "not implemented yet: a falling traction curve (softening, SIGM {} after {} \
                     at EPSI = {})",
                    sig[k],
                    sig[k - 1],
                    eps[k]
                )));
            }
            p.push(pk);
            r.push(sig[k]);
        }
        Ok(TractionCurve { young, p, r, right })
    }

    /// The law's Young's modulus, σ₁/ε₁.
    pub fn young(&self) -> f64 {
        self.young
    }

    /// Index k of the segment [p_k, p_{k+1}) holding p; the last index
    /// for the extension past the last point.
    fn segment(&self, p: f64) -> usize {
        let last = self.p.len() - 1;
        (0..last).find(|&k| p < self.p[k + 1]).unwrap_or(last)
    }

    /// Slope of segment k (k = last: the extension's).
    fn segment_slope(&self, k: usize) -> f64 {
        let last = self.p.len() - 1;
        if k < last {
            (self.r[k + 1] - self.r[k]) / (self.p[k + 1] - self.p[k])
        } else {
            match self.right {
                RightExtension::Linear if last > 0 => self.segment_slope(last - 1),
                _ => 0.0,
            }
        }
    }

    /// R(p) (p ≥ 0).
    pub fn r(&self, p: f64) -> f64 {
        let k = self.segment(p);
        self.r[k] + self.segment_slope(k) * (p - self.p[k])
    }
}

impl IsotropicHardening for TractionCurve {
    fn yield_stress(&self, p: f64) -> f64 {
        self.r(p)
    }

    /// Walks the segments from p_n's: g(p) = q_tr − 3μ(p − p_n) − R(p)
    /// falls strictly (R does not), so the first segment whose end makes
    /// g ≤ 0 holds the root, which is then exact.
    fn return_map(
        &self,
        q_tr: f64,
        p_n: f64,
        three_mu: f64,
    ) -> Result<(f64, f64), IntegrationFailure> {
        let last = self.p.len() - 1;
        let mut k = self.segment(p_n);
        while k < last && q_tr - three_mu * (self.p[k + 1] - p_n) - self.r[k + 1] > 0.0 {
            k += 1;
        }
        let h = self.segment_slope(k);
        let dp = (q_tr - self.r[k] - h * (p_n - self.p[k])) / (three_mu + h);
        if k == last && self.right == RightExtension::Excluded && p_n + dp > self.p[last] {
            return Err(IntegrationFailure::invalid(
                METADATA.name,
                format!(
                    "the cumulative plastic strain p = {} passes the last point of the traction \
                     curve (EPSI - SIGM/E = {}), and the function of TRACTION/SIGM is excluded \
                     past it (PROL_DROITE='EXCLU', DEFI_FONCTION's default): extend the curve or \
                     give PROL_DROITE='CONSTANT' or 'LINEAIRE'",
                    p_n + dp,
                    self.p[last]
                ),
            ));
        }
        Ok((dp, h))
    }

    fn slope(&self, p: f64) -> f64 {
        self.segment_slope(self.segment(p))
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct VmisIsotTrac {
    /// E of the curve's first point, NU of ELAS.
    pub elas: ElasParams,
    pub curve: TractionCurve,
    mu: f64,
    bulk: f64,
}

impl VmisIsotTrac {
    /// `nu` and `rho` come from ELAS; E from the curve.
    pub fn new(
        curve: TractionCurve,
        nu: f64,
        rho: Option<f64>,
    ) -> Result<VmisIsotTrac, MaterialError> {
        let elas = ElasParams::new(curve.young(), nu, rho)?;
        Ok(VmisIsotTrac {
            elas,
            curve,
            mu: elas.mu(),
            bulk: elas.bulk(),
        })
    }
}

impl SmallStrainBehaviour for VmisIsotTrac {
    fn metadata(&self) -> &'static LawMetadata {
        &METADATA
    }

    fn elastic_params(&self) -> Option<ElasParams> {
        Some(self.elas)
    }

    fn integrate(&self, input: &SmallStrainInput) -> Result<SmallStrainOutput, IntegrationFailure> {
        radial_return(&METADATA, input, self.mu, self.bulk, &self.curve)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::vmis_isot_line::VmisIsotLine;
    use crate::law::{EcroLineParams, TangentKind, Vec6};

    const E: f64 = 200_000.0;

    fn curve(right: RightExtension) -> TractionCurve {
        // yield 200 at 1e-3, then slopes 10000 and 2000 (in σ-ε).
        TractionCurve::new(&[1e-3, 0.011, 0.061], &[200.0, 300.0, 400.0], right).unwrap()
    }

    /// Uniaxial stress by a strain path ε_zz with the lateral strains
    /// found by a Newton on σ_xx = σ_yy = 0.
    fn uniaxial(law: &dyn SmallStrainBehaviour, strains: &[f64]) -> Vec<(f64, f64)> {
        let mut stress = Vec6::zeros();
        let mut internal = law.initial_internal();
        let mut lateral = 0.0;
        let mut eps_prev = (0.0, 0.0);
        let mut out = Vec::new();
        for &ez in strains {
            let mut lat = lateral;
            let mut result = None;
            for _ in 0..50 {
                let de = Vec6::new(
                    lat - eps_prev.1,
                    lat - eps_prev.1,
                    ez - eps_prev.0,
                    0.,
                    0.,
                    0.,
                );
                let o = law
                    .integrate(&SmallStrainInput {
                        stress,
                        internal: internal.as_slice(),
                        strain_increment: de,
                        dt: 0.0,
                        tangent: TangentKind::Consistent,
                    })
                    .unwrap();
                let d = o.tangent.unwrap();
                let sxx = o.stress[0];
                if sxx.abs() < 1e-10 {
                    result = Some(o);
                    break;
                }
                lat -= sxx / (d[(0, 0)] + d[(0, 1)]);
            }
            let o = result.expect("lateral Newton converged");
            stress = o.stress;
            internal = o.internal;
            lateral = lat;
            eps_prev = (ez, lat);
            out.push((o.stress[2], o.internal.as_slice()[0]));
        }
        out
    }

    #[test]
    fn uniaxial_stress_reproduces_the_curve() {
        let law = VmisIsotTrac::new(curve(RightExtension::Linear), 0.3, None).unwrap();
        assert_eq!(law.elas.e, E);
        let strains = [5e-4, 1e-3, 6e-3, 0.011, 0.036, 0.061, 0.081];
        // σ(ε) of the curve, continued with the last slope 2000.
        let expect = [100.0, 200.0, 250.0, 300.0, 350.0, 400.0, 440.0];
        for ((s, p), (&e, &x)) in uniaxial(&law, &strains)
            .iter()
            .zip(strains.iter().zip(&expect))
        {
            assert!((s - x).abs() < 1e-9 * x, "eps {e}: sigma {s} against {x}");
            let p_expect = (e - x / E).max(0.0);
            assert!(
                (p - p_expect).abs() < 1e-12,
                "eps {e}: p {p} against {p_expect}"
            );
        }
    }

    #[test]
    fn constant_extension_is_perfect_plasticity_and_excluded_stops() {
        let law = VmisIsotTrac::new(curve(RightExtension::Constant), 0.3, None).unwrap();
        let s = uniaxial(&law, &[0.03, 0.061, 0.1]);
        assert!((s[2].0 - 400.0).abs() < 1e-9);
        let law = VmisIsotTrac::new(curve(RightExtension::Excluded), 0.3, None).unwrap();
        let e = law
            .integrate(&SmallStrainInput {
                stress: Vec6::zeros(),
                internal: &[0.0, 0.0],
                strain_increment: Vec6::new(0., 0., 0.2, 0., 0., 0.),
                dt: 0.0,
                tangent: TangentKind::None,
            })
            .unwrap_err();
        assert!(e.message.contains("PROL_DROITE"), "{e}");
    }

    /// The curve (SY/E, SY), slope 3000 continued linearly, and the line
    /// that is the same hardening: SY = 250, D_SIGM_EPSI = 3000.
    fn two_point_curve() -> (TractionCurve, ElasParams, EcroLineParams) {
        let (sy, et) = (250.0, 3000.0);
        let eps1 = sy / E;
        let c = TractionCurve::new(
            &[eps1, eps1 + 0.01],
            &[sy, sy + et * 0.01],
            RightExtension::Linear,
        )
        .unwrap();
        let elas = ElasParams::new(E, 0.3, None).unwrap();
        (c, elas, EcroLineParams::new(&elas, sy, et).unwrap())
    }

    /// A two-point curve continued linearly is VMIS_ISOT_LINE with
    /// SY = σ₁ and D_SIGM_EPSI the segment's slope: same stress, p and
    /// tangent on a multiaxial path, to round-off.
    #[test]
    fn two_point_linear_curve_is_vmis_isot_line() {
        let (c, elas, ecro) = two_point_curve();
        let trac = VmisIsotTrac::new(c, 0.3, None).unwrap();
        let line = VmisIsotLine::new(elas, ecro);
        let path = [
            Vec6::new(1e-3, -2e-4, 3e-3, 1e-3, 0.0, -5e-4),
            Vec6::new(2e-3, 1e-3, -1e-3, 0.0, 2e-3, 1e-3),
            Vec6::new(-4e-3, 0.0, 0.0, -1e-3, 0.0, 0.0),
            Vec6::zeros(),
        ];
        let (mut s1, mut s2) = (Vec6::zeros(), Vec6::zeros());
        let (mut v1, mut v2) = (trac.initial_internal(), line.initial_internal());
        for de in path {
            fn inp(stress: Vec6, internal: &[f64], de: Vec6) -> SmallStrainInput<'_> {
                SmallStrainInput {
                    stress,
                    internal,
                    strain_increment: de,
                    dt: 0.0,
                    tangent: TangentKind::Consistent,
                }
            }
            let a = trac.integrate(&inp(s1, v1.as_slice(), de)).unwrap();
            let b = line.integrate(&inp(s2, v2.as_slice(), de)).unwrap();
            assert!(
                (a.stress - b.stress).norm() < 1e-9,
                "{} {}",
                a.stress,
                b.stress
            );
            assert!((a.internal.as_slice()[0] - b.internal.as_slice()[0]).abs() < 1e-14);
            assert!((a.tangent.unwrap() - b.tangent.unwrap()).norm() < 1e-6);
            (s1, s2, v1, v2) = (a.stress, b.stress, a.internal, b.internal);
        }
    }

    /// The consistent tangent against central differences of the update,
    /// on a step that crosses a kink of the curve.
    #[test]
    fn tangent_is_the_derivative_of_the_update() {
        let law = VmisIsotTrac::new(curve(RightExtension::Linear), 0.3, None).unwrap();
        let stress = Vec6::new(150.0, -20.0, 30.0, 40.0, 0.0, 10.0);
        let internal = [0.0, 0.0];
        let de = Vec6::new(0.016, -0.004, 0.024, 0.008, 0.004, 0.0);
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
            base.internal.as_slice()[0] > 0.01,
            "the step crosses the kink at p = 0.01"
        );
        let d = base.tangent.unwrap();
        crate::law::assert_tangent_by_differences(&d, de, 1e-6 * E, "", |x| {
            run(x, TangentKind::None).stress
        });
    }

    #[test]
    fn bad_curves_are_refused() {
        let c = |e: &[f64], s: &[f64]| TractionCurve::new(e, s, RightExtension::Constant);
        assert!(c(&[], &[]).is_err());
        assert!(c(&[0.0], &[1.0]).is_err());
        // second segment steeper than E: p would decrease.
        assert!(c(&[1e-3, 2e-3], &[200.0, 500.0])
            .unwrap_err()
            .message
            .contains("steep"));
        assert!(c(&[1e-3, 2e-2], &[200.0, 150.0])
            .unwrap_err()
            .message
            .contains("softening"));
    }

    mod simo_miehe {
        use super::*;
        use crate::law::simo_miehe::{FiniteStrainInput, SimoMiehe};
        use nalgebra::Matrix3;

        fn path() -> Vec<Matrix3<f64>> {
            let mut out = Vec::new();
            for k in 1..=12 {
                let t = k as f64;
                out.push(Matrix3::new(
                    1.0 - 0.004 * t,
                    0.003 * t,
                    0.0,
                    0.0,
                    1.0 - 0.004 * t,
                    0.0,
                    0.001 * t,
                    0.0,
                    1.0 + 0.01 * t,
                ));
            }
            out
        }

        fn step(
            law: &SimoMiehe,
            f_n: Matrix3<f64>,
            f: Matrix3<f64>,
            v: &[f64],
            tangent: TangentKind,
        ) -> crate::law::simo_miehe::FiniteStrainOutput {
            law.integrate(&FiniteStrainInput {
                f_n,
                f_np1: f,
                internal: v,
                dt: 0.0,
                tangent,
            })
            .unwrap()
        }

        /// A two-point curve continued linearly under SIMO_MIEHE is
        /// VMIS_ISOT_LINE's SIMO_MIEHE law: the same τ, p and ∂τ/∂F along
        /// a path that yields, to round-off.
        #[test]
        fn two_point_linear_curve_is_the_line() {
            let (c, elas, ecro) = two_point_curve();
            let trac = SimoMiehe::with_curve(elas, c);
            let line = SimoMiehe::new(elas, ecro);
            assert_eq!(trac.metadata().name, "VMIS_ISOT_TRAC");
            let (mut v1, mut v2) = (trac.initial_internal(), line.initial_internal());
            let mut f_n = Matrix3::identity();
            for f in path() {
                let a = step(&trac, f_n, f, v1.as_slice(), TangentKind::Consistent);
                let b = step(&line, f_n, f, v2.as_slice(), TangentKind::Consistent);
                assert!((a.kirchhoff - b.kirchhoff).norm() < 1e-9 * b.kirchhoff.norm());
                assert!((a.internal.as_slice()[0] - b.internal.as_slice()[0]).abs() < 1e-14);
                let (da, db) = (a.dtau_df.unwrap(), b.dtau_df.unwrap());
                assert!((da - db).norm() < 1e-9 * db.norm());
                (v1, v2, f_n) = (a.internal, b.internal, f);
            }
            assert!(
                v1.as_slice()[0] > 0.05,
                "the path yields: p = {}",
                v1.as_slice()[0]
            );
        }

        /// On the three-point curve: at the end of each plastic step the
        /// Kirchhoff von Mises stress is R(p) (the yield condition the
        /// return solves), and ∂τ/∂F is the derivative of the update
        /// (central differences), on steps that cross the kinks.
        #[test]
        fn return_lands_on_the_curve_with_its_tangent() {
            let elas = ElasParams::new(E, 0.3, None).unwrap();
            let c = curve(RightExtension::Linear);
            let law = SimoMiehe::with_curve(elas, c.clone());
            let mut v = law.initial_internal();
            let mut f_n = Matrix3::identity();
            let mut crossed = 0;
            for f in path() {
                let o = step(&law, f_n, f, v.as_slice(), TangentKind::Consistent);
                let p = o.internal.as_slice()[0];
                let tau = o.kirchhoff;
                let dev = tau - Matrix3::identity() * (tau.trace() / 3.0);
                let vm = (1.5 * dev.norm_squared()).sqrt();
                if o.internal.as_slice()[1] == 1.0 {
                    assert!(
                        (vm - c.r(p)).abs() < 1e-9 * vm,
                        "{vm} against R(p) = {}",
                        c.r(p)
                    );
                }
                if (v.as_slice()[0] < 0.011 - 0.001) != (p < 0.011 - 0.001) {
                    crossed += 1;
                }
                let d = o.dtau_df.unwrap();
                let h = 1e-7;
                for kk in 0..3 {
                    for ll in 0..3 {
                        let mut e = Matrix3::zeros();
                        e[(kk, ll)] = h;
                        let plus = step(&law, f_n, f + e, v.as_slice(), TangentKind::None);
                        let minus = step(&law, f_n, f - e, v.as_slice(), TangentKind::None);
                        let col = (plus.kirchhoff - minus.kirchhoff) / (2.0 * h);
                        for ii in 0..3 {
                            for jj in 0..3 {
                                let a = d[(3 * ii + jj, 3 * kk + ll)];
                                assert!(
                                    (col[(ii, jj)] - a).abs() < 1e-5 * E,
                                    "dtau[{ii}{jj}]/dF[{kk}{ll}] = {a} against {}",
                                    col[(ii, jj)]
                                );
                            }
                        }
                    }
                }
                (v, f_n) = (o.internal, f);
            }
            assert!(crossed >= 1, "the path crosses the first kink");
            assert!(v.as_slice()[0] > 0.011, "p = {}", v.as_slice()[0]);
        }
    }
}
