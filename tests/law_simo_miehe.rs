//! Verification of the finite-strain SIMO_MIEHE law: small-strain limit
//! (against VMIS_ISOT_LINE), objectivity, isochoric plastic flow, tangent
//! against finite differences, and large-strain uniaxial tension against
//! the logarithmic-strain solution with a step-size convergence check.

use aster::law::simo_miehe::{
    two_thirds_power, FiniteStrainInput, FiniteStrainOutput, Mat9, SimoMiehe,
    TWO_THIRDS_SERIES_RANGE,
};
use aster::law::vmis_isot_line::VmisIsotLine;
use aster::law::voigt::{strain_to_tensor, stress_to_tensor};
use aster::law::{
    EcroLineParams, ElasParams, FailureKind, Regime, SmallStrainBehaviour, SmallStrainInput,
    TangentKind, Vec6,
};
use nalgebra::{Matrix3, Rotation3, Vector3};

mod common;

fn params(e: f64, nu: f64, sy: f64, et: f64) -> (ElasParams, EcroLineParams) {
    let elas = ElasParams::new(e, nu, None).unwrap();
    (elas, EcroLineParams::new(&elas, sy, et).unwrap())
}

fn copper() -> SimoMiehe {
    let (e, h) = params(117_000.0, 0.35, 400.0, 100.0);
    SimoMiehe::new(e, h)
}

fn run(
    law: &SimoMiehe,
    f_n: Matrix3<f64>,
    f_np1: Matrix3<f64>,
    internal: &[f64],
    tangent: TangentKind,
) -> FiniteStrainOutput {
    law.integrate(&FiniteStrainInput {
        f_n,
        f_np1,
        internal,
        dt: 1e-6,
        tangent,
    })
    .unwrap()
}

fn rel_norm(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).norm() / b.norm()
}

#[test]
fn tiny_deformations_reproduce_the_small_strain_law() {
    // Yield strain 2.5e-8 and gradients ~2e-7: plastic, while geometric
    // nonlinearity is O(2e-7), below the 1e-6 tolerance.
    let (e, h) = params(200_000.0, 0.3, 0.005, 20_000.0);
    let fin = SimoMiehe::new(e, h);
    let small = VmisIsotLine::new(e, h);
    let steps = [
        Vec6::new(2e-7, -0.5e-7, -0.8e-7, 1.5e-7, 0.4e-7, -0.9e-7),
        Vec6::new(-0.5e-7, 1.5e-7, 0.2e-7, -1.0e-7, 0.8e-7, 0.3e-7),
    ];
    let mut f = Matrix3::identity();
    let mut vf = fin.initial_internal();
    let mut sig = Vec6::zeros();
    let mut vs = small.initial_internal();
    for de in steps {
        let f_new = f + strain_to_tensor(&de);
        let a = run(&fin, f, f_new, vf.as_slice(), TangentKind::None);
        let b = small
            .integrate(&SmallStrainInput {
                stress: sig,
                internal: vs.as_slice(),
                strain_increment: de,
                dt: 0.0,
                tangent: TangentKind::None,
            })
            .unwrap();
        assert_eq!(a.regime, Regime::Plastic);
        assert_eq!(b.regime, Regime::Plastic);
        let err = rel_norm(&a.cauchy, &stress_to_tensor(&b.stress));
        assert!(err < 1e-6, "stress differs by {err}");
        let (pa, pb) = (a.internal.as_slice()[0], b.internal.as_slice()[0]);
        assert!((pa - pb).abs() < 1e-6 * pb, "p {pa} vs {pb}");
        f = f_new;
        vf = a.internal;
        sig = b.stress;
        vs = b.internal;
    }
}

/// A plastically deformed state: stretch with shear, in 5 steps.
fn deformed_state(law: &SimoMiehe) -> (Matrix3<f64>, Vec<f64>) {
    let target = Matrix3::new(1.08, 0.05, 0.0, 0.02, 0.97, 0.03, -0.01, 0.0, 0.99);
    let mut f = Matrix3::identity();
    let mut v = law.initial_internal();
    for i in 1..=5 {
        let f_new = Matrix3::identity() + (target - Matrix3::identity()) * (i as f64 / 5.0);
        let out = run(law, f, f_new, v.as_slice(), TangentKind::None);
        f = f_new;
        v = out.internal;
    }
    assert!(v.as_slice()[0] > 0.01);
    (f, v.as_slice().to_vec())
}

#[test]
fn superposed_rotation_rotates_tau_exactly() {
    let law = copper();
    let (f0, v0) = deformed_state(&law);
    let f1 = f0 * Matrix3::new(1.03, 0.01, 0.0, 0.0, 0.99, 0.02, 0.01, 0.0, 0.985);
    let q = Rotation3::from_axis_angle(
        &nalgebra::Unit::new_normalize(Vector3::new(0.3, -0.5, 0.8)),
        1.1,
    );
    let q = *q.matrix();
    let a = run(&law, f0, f1, &v0, TangentKind::None);
    let b = run(&law, f0, q * f1, &v0, TangentKind::None);
    assert_eq!(a.regime, Regime::Plastic);
    assert!(rel_norm(&b.kirchhoff, &(q * a.kirchhoff * q.transpose())) < 1e-12);
    assert!(rel_norm(&b.cauchy, &(q * a.cauchy * q.transpose())) < 1e-12);
    let pa = a.internal.as_slice()[0];
    assert!((b.internal.as_slice()[0] - pa).abs() < 1e-13 * pa);
    let be_a = SimoMiehe::elastic_left_cauchy_green(a.internal.as_slice());
    let be_b = SimoMiehe::elastic_left_cauchy_green(b.internal.as_slice());
    assert!(rel_norm(&be_b, &(q * be_a * q.transpose())) < 1e-12);
}

#[test]
fn plastic_flow_is_isochoric_and_pressure_is_elastic() {
    let law = copper();
    let (f, v) = deformed_state(&law);
    // det b̄ᵉ = 1 means J_e = J, i.e. J_p = det Fᵖ = 1.
    let be = SimoMiehe::elastic_left_cauchy_green(&v);
    assert!((be.determinant() - 1.0).abs() < 1e-13);
    let out = run(
        &law,
        Matrix3::identity(),
        f,
        law.initial_internal().as_slice(),
        TangentKind::None,
    );
    let be = SimoMiehe::elastic_left_cauchy_green(out.internal.as_slice());
    assert_eq!(out.regime, Regime::Plastic);
    assert!((be.determinant() - 1.0).abs() < 1e-13);
    // tr τ = 3K(J²−1)/2 whatever the plastic history.
    let k = law.elas.bulk();
    let j = f.determinant();
    assert!((out.kirchhoff.trace() - 1.5 * k * (j * j - 1.0)).abs() < 1e-10 * k);
}

#[test]
fn yield_condition_holds_after_plastic_steps() {
    let law = copper();
    let (f0, v0) = deformed_state(&law);
    let f1 = f0 * Matrix3::new(1.02, 0.0, 0.01, 0.0, 0.99, 0.0, 0.0, 0.0, 0.99);
    let out = run(&law, f0, f1, &v0, TangentKind::None);
    let tau = out.kirchhoff;
    let s = tau - Matrix3::identity() * (tau.trace() / 3.0);
    let eq = (1.5f64).sqrt() * s.norm();
    let r = law.yield_stress(out.internal.as_slice()[0]);
    assert!((eq - r).abs() < 1e-10 * r, "{eq} vs {r}");
}

fn fd_tangent(law: &SimoMiehe, f0: Matrix3<f64>, f1: Matrix3<f64>, v: &[f64]) -> Mat9 {
    let h = 1e-7;
    let mut d = Mat9::zeros();
    for k in 0..3 {
        for l in 0..3 {
            let mut fp = f1;
            let mut fm = f1;
            fp[(k, l)] += h;
            fm[(k, l)] -= h;
            let tp = run(law, f0, fp, v, TangentKind::None).kirchhoff;
            let tm = run(law, f0, fm, v, TangentKind::None).kirchhoff;
            let dt = (tp - tm) / (2.0 * h);
            for i in 0..3 {
                for j in 0..3 {
                    d[(3 * i + j, 3 * k + l)] = dt[(i, j)];
                }
            }
        }
    }
    d
}

#[test]
fn tangent_equals_finite_differences_of_the_update() {
    let law = copper();
    let (f0, v0) = deformed_state(&law);
    let cases = [
        // further plastic loading with rotation
        (
            f0 * Matrix3::new(1.02, 0.01, 0.0, -0.015, 0.99, 0.02, 0.0, 0.0, 0.995),
            Regime::Plastic,
        ),
        // elastic unloading
        (
            f0 * Matrix3::new(0.9995, 0.0, 0.0, 0.0, 1.0002, 0.0, 0.0, 0.0, 1.0002),
            Regime::Elastic,
        ),
    ];
    for (f1, regime) in cases {
        let out = run(&law, f0, f1, &v0, TangentKind::Consistent);
        assert_eq!(out.regime, regime);
        let d = out.dtau_df.unwrap();
        let fd = fd_tangent(&law, f0, f1, &v0);
        let err = (d - fd).norm() / d.norm();
        assert!(err < 1e-6, "{regime:?}: relative error {err}");
    }
    // The elastic-trial tangent differs from the consistent one when plastic.
    let f1 = cases[0].0;
    let c = run(&law, f0, f1, &v0, TangentKind::Consistent)
        .dtau_df
        .unwrap();
    let e = run(&law, f0, f1, &v0, TangentKind::Elastic)
        .dtau_df
        .unwrap();
    assert!((c - e).norm() / e.norm() > 1e-3);
}

/// Uniaxial stress by stretch λ along x: solves τ_yy = τ_zz = 0 for the
/// lateral stretch with a Newton on ∂τ/∂F, over `n` equal stretch steps.
fn uniaxial(law: &SimoMiehe, lambda: f64, n: usize) -> (FiniteStrainOutput, f64) {
    let mut f: Matrix3<f64> = Matrix3::identity();
    let mut v = law.initial_internal();
    let mut out = None;
    for i in 1..=n {
        let l = 1.0 + (lambda - 1.0) * i as f64 / n as f64;
        let mut lt: f64 = f[(1, 1)] * (f[(0, 0)] / l).sqrt();
        let mut converged = None;
        for _ in 0..30 {
            let f1 = Matrix3::from_diagonal(&Vector3::new(l, lt, lt));
            let o = run(law, f, f1, v.as_slice(), TangentKind::Consistent);
            let r = o.kirchhoff[(1, 1)];
            if r.abs() < 1e-9 {
                converged = Some((f1, o));
                break;
            }
            let d = o.dtau_df.unwrap();
            lt -= r / (d[(4, 4)] + d[(4, 8)]);
        }
        let (f1, o) = converged.expect("lateral Newton did not converge");
        f = f1;
        v = o.internal;
        out = Some(o);
    }
    (out.unwrap(), f[(1, 1)])
}

/// The continuum limit of the model in uniaxial stress, derived by hand
/// and integrated by quadrature (independent of the law's code).
///
/// Everything is coaxial, b̄ᵉ = diag(a, a^-½, a^-½), τ_eq = μ g(a) with
/// g(a) = a − a^-½, and τ_yy = 0 gives J(a) = √(1 + 2μ g(a)/(3K)). In the
/// limit of small steps the return of Box 9.1 gives, on the yield surface
/// μ g(a) = SY + H p,
///   dε_iso/dp = (Ī + H/(3μ)) / (⅔ (a + ½ a^-½)),  Ī = (a + 2a^-½)/3,
/// with ε_iso = ln λ − ⅓ ln J the isochoric axial log strain, and
/// a = exp(2 ε_iso) while elastic. Returns p at stretch λ.
fn uniaxial_reference_p(law: &SimoMiehe, lambda: f64) -> f64 {
    let (sy, h) = (law.ecro.sy, law.hardening_modulus());
    uniaxial_reference_p_of(law, |p| sy + h * p, |_| h, lambda)
}

/// [`uniaxial_reference_p`] for any hardening R(p) with slope R'(p) (the
/// hand derivation holds with H = R'(p) at each p).
fn uniaxial_reference_p_of(
    law: &SimoMiehe,
    r: impl Fn(f64) -> f64,
    rp: impl Fn(f64) -> f64,
    lambda: f64,
) -> f64 {
    let (mu, k) = (law.elas.mu(), law.elas.bulk());
    let g = |a: f64| a - a.powf(-0.5);
    let a_of_tau = |t: f64| {
        let mut a = 1.0;
        for _ in 0..60 {
            a -= (g(a) - t / mu) / (1.0 + 0.5 * a.powf(-1.5));
        }
        a
    };
    let j_of_a = |a: f64| (1.0 + 2.0 * mu * g(a) / (3.0 * k)).sqrt();
    let deps_dp = |p: f64| {
        let a = a_of_tau(r(p));
        let i = (a + 2.0 * a.powf(-0.5)) / 3.0;
        (i + rp(p) / (3.0 * mu)) / (2.0 / 3.0 * (a + 0.5 * a.powf(-0.5)))
    };
    let a_y = a_of_tau(r(0.0));
    // ln λ as a function of p (composite Simpson on 2000 intervals).
    let ln_lambda = |p: f64| {
        let n = 2000;
        let dx = p / n as f64;
        let mut s = deps_dp(0.0) + deps_dp(p);
        for i in 1..n {
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * deps_dp(i as f64 * dx);
        }
        0.5 * a_y.ln() + s * dx / 3.0 + j_of_a(a_of_tau(r(p))).ln() / 3.0
    };
    let (mut lo, mut hi) = (0.0, 2.0 * lambda.ln());
    for _ in 0..60 {
        let m = 0.5 * (lo + hi);
        if ln_lambda(m) < lambda.ln() {
            lo = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo + hi)
}

/// VMIS_ISOT_TRAC under SIMO_MIEHE (a traction curve of three points,
/// continued linearly) against the same continuum solution with R(p) the
/// curve: first-order convergence in the step, the extrapolation within
/// 1e-4 (Simpson across the curve's kinks is the reference's own limit),
/// and τ = R(p) at the end.
#[test]
fn traction_curve_uniaxial_matches_the_continuum_solution() {
    use aster::law::vmis_isot_trac::{RightExtension, TractionCurve};
    let elas = ElasParams::new(117e3, 0.35, None).unwrap();
    let eps1 = 400.0 / 117e3;
    let curve = TractionCurve::new(
        &[eps1, 0.05, 0.3],
        &[400.0, 600.0, 700.0],
        RightExtension::Linear,
    )
    .unwrap();
    let law = SimoMiehe::with_curve(elas, curve.clone());
    let h = 1e-6;
    let rp = |p: f64| (curve.r(p + h) - curve.r(p)) / h;
    let lambda = 1.5;
    let p_ref = uniaxial_reference_p_of(&law, |p| curve.r(p), rp, lambda);
    let (o200, _) = uniaxial(&law, lambda, 200);
    let (o400, _) = uniaxial(&law, lambda, 400);
    let p200 = o200.internal.as_slice()[0];
    let p400 = o400.internal.as_slice()[0];
    assert!(p400 > 0.3, "the path passes both kinks: p = {p400}");
    let p_extra = 2.0 * p400 - p200;
    assert!(
        (p_extra - p_ref).abs() < 1e-4 * p_ref,
        "extrapolated p {p_extra} vs {p_ref}"
    );
    assert!((p400 - p_ref).abs() < 2e-3 * p_ref, "p {p400} vs {p_ref}");
    let tau = o400.kirchhoff[(0, 0)];
    assert!((tau - curve.r(p400)).abs() < 1e-9 * tau);
}

/// VMIS_ISOT_PUIS under SIMO_MIEHE (R(p) = SY (1 + (E p/(A SY))^(1/N)),
/// N = 3: R'(0) is infinite) against the continuum solution of
/// [`uniaxial_reference_p_of`] rewritten with τ as the variable of the
/// quadrature (p = (A SY/E)(τ/SY − 1)^N, R'(p) dp = dτ: the integrand is
/// smooth where the one in p is not): first order in the step, the
/// Richardson extrapolation within 1e-5, and τ = R(p) at the end.
#[test]
fn power_law_uniaxial_matches_the_continuum_solution() {
    use aster::law::john_cook::LocalControls;
    use aster::law::simo_miehe::Hardening;
    use aster::law::vmis_isot_puis::PowerHardening;
    let (e, sy, a, n) = (117e3, 400.0, 0.5, 3.0);
    let elas = ElasParams::new(e, 0.35, None).unwrap();
    let power = PowerHardening::new(e, sy, a, n, LocalControls::default()).unwrap();
    let law = SimoMiehe::with_hardening(elas, Hardening::Power(power));
    assert_eq!(law.metadata().name, "VMIS_ISOT_PUIS");
    let lambda: f64 = 1.5;
    let (mu, k) = (elas.mu(), elas.bulk());
    let g = |x: f64| x - x.powf(-0.5);
    let a_of_tau = |t: f64| {
        let mut x = 1.0;
        for _ in 0..60 {
            x -= (g(x) - t / mu) / (1.0 + 0.5 * x.powf(-1.5));
        }
        x
    };
    let j_of_a = |x: f64| (1.0 + 2.0 * mu * g(x) / (3.0 * k)).sqrt();
    let p_of_tau = |t: f64| a * sy / e * (t / sy - 1.0).powf(n);
    let dp_dtau = |t: f64| n * a / e * (t / sy - 1.0).powf(n - 1.0);
    let integrand = |t: f64| {
        let x = a_of_tau(t);
        let i = (x + 2.0 * x.powf(-0.5)) / 3.0;
        (i * dp_dtau(t) + 1.0 / (3.0 * mu)) / (2.0 / 3.0 * (x + 0.5 * x.powf(-0.5)))
    };
    let a_y = a_of_tau(sy);
    let ln_lambda = |t: f64| {
        let m = 2000;
        let dx = (t - sy) / m as f64;
        let mut s = integrand(sy) + integrand(t);
        for i in 1..m {
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * integrand(sy + i as f64 * dx);
        }
        0.5 * a_y.ln() + s * dx / 3.0 + j_of_a(a_of_tau(t)).ln() / 3.0
    };
    let (mut lo, mut hi) = (sy, power.r(2.0 * lambda.ln()));
    for _ in 0..60 {
        let m = 0.5 * (lo + hi);
        if ln_lambda(m) < lambda.ln() {
            lo = m;
        } else {
            hi = m;
        }
    }
    let p_ref = p_of_tau(0.5 * (lo + hi));
    let (o200, _) = uniaxial(&law, lambda, 200);
    let (o400, _) = uniaxial(&law, lambda, 400);
    let p200 = o200.internal.as_slice()[0];
    let p400 = o400.internal.as_slice()[0];
    assert!(p400 > 0.3, "p = {p400}");
    let p_extra = 2.0 * p400 - p200;
    assert!(
        (p_extra - p_ref).abs() < 1e-5 * p_ref,
        "extrapolated p {p_extra} vs {p_ref}"
    );
    assert!((p400 - p_ref).abs() < 2e-3 * p_ref, "p {p400} vs {p_ref}");
    let tau = o400.kirchhoff[(0, 0)];
    assert!((tau - power.r(p400)).abs() < 1e-9 * tau);
}

#[test]
fn uniaxial_large_strain_tension_matches_the_continuum_solution() {
    let law = copper();
    let (e, nu) = (law.elas.e, law.elas.nu);
    let lambda = 1.5;
    let p_ref = uniaxial_reference_p(&law, lambda);
    let (o200, _) = uniaxial(&law, lambda, 200);
    let (o400, lt) = uniaxial(&law, lambda, 400);
    let p200 = o200.internal.as_slice()[0];
    let p400 = o400.internal.as_slice()[0];
    // First-order convergence: the Richardson extrapolation hits the
    // continuum value far closer than either run.
    let p_extra = 2.0 * p400 - p200;
    assert!(
        (p_extra - p_ref).abs() < 1e-5 * p_ref,
        "extrapolated p {p_extra} vs {p_ref}"
    );
    assert!((p400 - p_ref).abs() < 1e-3 * p_ref, "p {p400} vs {p_ref}");
    let tau = o400.kirchhoff[(0, 0)];
    assert!((tau - law.yield_stress(p400)).abs() < 1e-9 * tau);
    // Log-strain plasticity (τ = SY + H p, p = ln λ − τ/E) agrees only to
    // O(τ/μ) ≈ 3e-3, because Simo's flow rule carries the factor tr(b̄ᵉ)/3
    // on n rather than b̄ᵉ: a loose sanity check, not the reference.
    let h = law.hardening_modulus();
    let tau_log = (law.ecro.sy + h * lambda.ln()) / (1.0 + h / e);
    let p_log = lambda.ln() - tau_log / e;
    assert!((p_ref - p_log).abs() < 5e-3 * p_log);
    // Lateral stretch: plastic part −½ p (isochoric), elastic −ν τ/E.
    let lt_log = (-0.5 * p_log - nu * tau_log / e).exp();
    assert!((lt - lt_log).abs() < 1e-5, "λt {lt} vs {lt_log}");
    // Cauchy = Kirchhoff / J.
    let j = lambda * lt * lt;
    assert!((o400.cauchy[(0, 0)] - tau / j).abs() < 1e-12 * tau);
}

#[test]
fn uniaxial_result_converges_at_first_order_in_the_step_size() {
    let law = copper();
    let p = |n| uniaxial(&law, 1.5, n).0.internal.as_slice()[0];
    let (p10, p20, p40) = (p(10), p(20), p(40));
    let ratio = (p10 - p20) / (p20 - p40);
    assert!((ratio - 2.0).abs() < 0.1, "error ratio {ratio}");
}

#[test]
fn bad_inputs_are_errors_not_panics() {
    let law = copper();
    let v = law.initial_internal();
    let ok = FiniteStrainInput {
        f_n: Matrix3::identity(),
        f_np1: Matrix3::identity() * 1.01,
        internal: v.as_slice(),
        dt: 1e-6,
        tangent: TangentKind::Consistent,
    };
    assert!(law.integrate(&ok).is_ok());
    let mut nan = ok;
    nan.f_np1[(0, 1)] = f64::NAN;
    assert_eq!(
        law.integrate(&nan).unwrap_err().kind,
        FailureKind::InvalidInput
    );
    let mut inverted = ok;
    inverted.f_np1[(2, 2)] = -1.0;
    let err = law.integrate(&inverted).unwrap_err();
    assert_eq!(err.kind, FailureKind::NotConverged);
    assert!(err.dt_factor > 0.0 && err.dt_factor < 1.0);
    let mut short = ok;
    short.internal = &[0.0, 0.0];
    assert_eq!(
        law.integrate(&short).unwrap_err().kind,
        FailureKind::InvalidInput
    );
    let bad_be = [0.0, 0.0, -2.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let mut be = ok;
    be.internal = &bad_be;
    assert_eq!(
        law.integrate(&be).unwrap_err().kind,
        FailureKind::InvalidInput
    );
}

/// The axisymmetric element asks for 5 columns of ∂τ/∂F only: those are
/// the full tangent's to the bit, the others zero, and the stress and
/// state do not depend on the selection (plastic step, consistent tangent).
#[test]
fn selected_tangent_columns_equal_the_full_tangent_columns() {
    let law = copper();
    let f_n = Matrix3::new(1.01, 0.02, 0.0, -0.01, 0.97, 0.0, 0.0, 0.0, 1.015);
    let f = Matrix3::new(1.04, 0.05, 0.0, -0.03, 0.90, 0.0, 0.0, 0.0, 1.05);
    let internal = [0.0; 8];
    let input = FiniteStrainInput {
        f_n,
        f_np1: f,
        internal: &internal,
        dt: 1e-6,
        tangent: TangentKind::Consistent,
    };
    let full = law.integrate(&input).unwrap();
    assert_eq!(full.regime, aster::law::Regime::Plastic);
    let mask: u16 = 0b1_0001_1011;
    let some = law.integrate_columns(&input, mask).unwrap();
    assert_eq!(some.kirchhoff, full.kirchhoff);
    assert_eq!(some.internal, full.internal);
    let (d_full, d_some) = (full.dtau_df.unwrap(), some.dtau_df.unwrap());
    for c in 0..9 {
        for r in 0..9 {
            let want = if mask & (1 << c) != 0 {
                d_full[(r, c)]
            } else {
                0.0
            };
            assert_eq!(d_some[(r, c)].to_bits(), want.to_bits(), "({r}, {c})");
        }
    }
}

/// The element keeps the start of the step (det F_n, A = F_n⁻¹ b̄ᵉ_n F_n⁻ᵀ)
/// for the Newton iterations of a step: the update from it is
/// `integrate_columns`' to the bit, on an elastic and on a plastic point
/// with a non-virgin b̄ᵉ_n, and its failures on F are the same.
#[test]
fn update_from_a_kept_start_of_step_is_the_same_to_the_bit() {
    let law = copper();
    let (f_n, internal) = deformed_state(&law);
    let mask: u16 = 0b1_0001_1011;
    for (k, scale) in [1.0 + 1e-5, 1.03].into_iter().enumerate() {
        let f = f_n * Matrix3::new(scale, 0.01, 0.0, -0.02, 1.0 / scale, 0.0, 0.0, 0.0, 1.0);
        let input = FiniteStrainInput {
            f_n,
            f_np1: f,
            internal: &internal,
            dt: 1e-6,
            tangent: TangentKind::Consistent,
        };
        let direct = law.integrate_columns(&input, mask).unwrap();
        let start = law.step_start(&input).unwrap();
        let kept = law.integrate_with_start(&input, &start, mask).unwrap();
        assert_eq!(kept.regime, direct.regime, "case {k}");
        for (a, b) in kept.kirchhoff.iter().zip(direct.kirchhoff.iter()) {
            assert_eq!(a.to_bits(), b.to_bits(), "case {k}");
        }
        for (a, b) in kept
            .internal
            .as_slice()
            .iter()
            .zip(direct.internal.as_slice())
        {
            assert_eq!(a.to_bits(), b.to_bits(), "case {k}");
        }
        let (dk, dd) = (kept.dtau_df.unwrap(), direct.dtau_df.unwrap());
        for (a, b) in dk.iter().zip(dd.iter()) {
            assert_eq!(a.to_bits(), b.to_bits(), "case {k}");
        }
        // A non-finite or inverted F fails as the full update does.
        for bad in [f * f64::NAN, -f] {
            let input = FiniteStrainInput {
                f_np1: bad,
                ..input
            };
            assert_eq!(
                law.integrate_with_start(&input, &start, mask).unwrap_err(),
                law.integrate_columns(&input, mask).unwrap_err()
            );
        }
    }
}

/// The explicit step's stress update (`integrate_stress`, no tangent slot,
/// det F_n, det F and optionally F_n⁻¹ given by the element) is
/// `integrate_columns`' with `TangentKind::None` to the bit, elastic and
/// plastic, and fails as it does on an inverted F.
#[test]
fn stress_update_alone_is_the_full_update_to_the_bit() {
    let law = copper();
    let (f_n, internal) = deformed_state(&law);
    for (k, scale) in [1.0 + 1e-5, 1.03].into_iter().enumerate() {
        let f = f_n * Matrix3::new(scale, 0.01, 0.0, -0.02, 1.0 / scale, 0.0, 0.0, 0.0, 1.0);
        let input = FiniteStrainInput {
            f_n,
            f_np1: f,
            internal: &internal,
            dt: 1e-6,
            tangent: TangentKind::None,
        };
        let full = law.integrate_columns(&input, 0x1ff).unwrap();
        assert!(full.dtau_df.is_none());
        let fn_inv = f_n.try_inverse().unwrap();
        for given in [None, Some(&fn_inv)] {
            let s = law
                .integrate_stress(&input, f_n.determinant(), f.determinant(), given)
                .unwrap();
            assert_eq!(s.regime, full.regime, "case {k}");
            for (a, b) in s
                .kirchhoff
                .iter()
                .chain(s.cauchy.iter())
                .chain(s.internal.as_slice())
                .zip(
                    full.kirchhoff
                        .iter()
                        .chain(full.cauchy.iter())
                        .chain(full.internal.as_slice()),
                )
            {
                assert_eq!(a.to_bits(), b.to_bits(), "case {k}");
            }
        }
        let bad = FiniteStrainInput { f_np1: -f, ..input };
        assert_eq!(
            law.integrate_stress(&bad, f_n.determinant(), (-f).determinant(), None)
                .unwrap_err(),
            law.integrate_columns(&bad, 0x1ff).unwrap_err()
        );
    }
}

/// The axisymmetric stress update (`integrate_stress_axi`, the (r, z)
/// block and θθ only) gives the 3 × 3 update's values to the bit, on
/// elastic and plastic steps from an axisymmetric plastic state (the
/// components that are exactly zero compare equal whatever their sign),
/// where J_n/J is outside the range of `two_thirds_power`'s series; inside
/// it (a step's volume change, the explicit steps') the two differ only by
/// that series' rounding, checked here to 4 units in the last place.
#[test]
fn axisymmetric_stress_update_is_the_3x3_update_to_the_bit() {
    use aster::law::simo_miehe::Axi;
    let law = copper();
    let axi =
        |a: f64, b: f64, c: f64, d: f64, t: f64| Matrix3::new(a, b, 0.0, c, d, 0.0, 0.0, 0.0, t);
    // An axisymmetric plastic history.
    let mut f_n = Matrix3::identity();
    let mut internal = law.initial_internal();
    for i in 1..=4 {
        let s = i as f64 / 4.0;
        let f = axi(
            1.0 + 0.06 * s,
            0.04 * s,
            -0.02 * s,
            1.0 - 0.08 * s,
            1.0 + 0.03 * s,
        );
        let out = run(&law, f_n, f, internal.as_slice(), TangentKind::None);
        f_n = f;
        internal = out.internal;
    }
    assert!(internal.as_slice()[0] > 0.0);
    for (k, f) in [
        f_n * axi(1.0 + 1e-6, 1e-7, 0.0, 1.0, 1.0),
        f_n * axi(1.02, 0.01, -0.015, 0.97, 1.01),
    ]
    .into_iter()
    .enumerate()
    {
        let input = FiniteStrainInput {
            f_n,
            f_np1: f,
            internal: internal.as_slice(),
            dt: 1e-6,
            tangent: TangentKind::None,
        };
        let (j_n, j) = (f_n.determinant(), f.determinant());
        let full = law.integrate_stress(&input, j_n, j, None).unwrap();
        let (fa, fna) = (Axi::of(&f), Axi::of(&f_n));
        assert_eq!(fa.determinant().to_bits(), j.to_bits());
        let inv = fa.inverse(j).matrix();
        assert_eq!(inv, f.try_inverse().unwrap(), "case {k}");
        let ax = law
            .integrate_stress_axi(
                &fna,
                &fa,
                j_n,
                j,
                &fna.inverse(j_n),
                internal.as_slice(),
                1e-6,
            )
            .unwrap()
            .unwrap();
        assert_eq!(ax.regime, full.regime, "case {k}");
        let series = ((j_n / j) - 1.0).abs() <= TWO_THIRDS_SERIES_RANGE;
        assert_eq!(series, k == 0, "case {k}: which path it takes");
        // Equal to the bit on the pow path; within 4 ulp of the larger
        // magnitude on the series path.
        let same = |a: f64, b: f64, scale: f64| {
            if series {
                (a - b).abs() <= 4.0 * f64::EPSILON * scale
            } else {
                a.to_bits() == b.to_bits() || (a == 0.0 && b == 0.0)
            }
        };
        let close = |x: &Matrix3<f64>, y: &Matrix3<f64>| {
            let scale = y.amax();
            x.iter().zip(y.iter()).all(|(a, b)| same(*a, *b, scale))
        };
        assert!(close(&ax.kirchhoff.matrix(), &full.kirchhoff), "case {k}");
        assert!(close(&ax.cauchy.matrix(), &full.cauchy), "case {k}");
        for (a, b) in ax.internal.as_slice().iter().zip(full.internal.as_slice()) {
            assert!(same(*a, *b, b.abs().max(1.0)), "case {k}");
        }
    }
    // Not an axisymmetric state: the caller takes the 3 × 3 path.
    let mut skew = internal.as_slice().to_vec();
    skew[6] = 1e-3;
    let fa = Axi::of(&f_n);
    assert!(law
        .integrate_stress_axi(&fa, &fa, 1.0, 1.0, &fa, &skew, 1e-6)
        .is_none());
}

/// `two_thirds_power` (the explicit AXIS step's (J_n/J)^(2/3)) within one
/// unit in the last place of libm's `pow` across its series range, the
/// same as `pow` outside it, and exact at 1.
#[test]
fn two_thirds_power_is_pow_within_one_ulp() {
    assert_eq!(two_thirds_power(1.0), 1.0);
    let r = TWO_THIRDS_SERIES_RANGE;
    let mut worst = 0u64;
    let n = 200_000;
    for i in 0..=n {
        // Evenly over [1 - r, 1 + r], and a geometric sweep of tiny e.
        let e = r * (2.0 * i as f64 / n as f64 - 1.0);
        let tiny = r * (-(i as f64) / 4000.0).exp() * if i % 2 == 0 { 1.0 } else { -1.0 };
        for x in [1.0 + e, 1.0 + tiny] {
            let (a, b) = (two_thirds_power(x), x.powf(2.0 / 3.0));
            worst = worst.max(a.to_bits().abs_diff(b.to_bits()));
        }
    }
    assert!(worst <= 1, "largest difference {worst} ulp");
    for x in [1.0 + 1.01 * r, 1.0 - 1.01 * r, 0.5, 1.7, 1e-3, 30.0] {
        assert_eq!(two_thirds_power(x).to_bits(), x.powf(2.0 / 3.0).to_bits());
    }
}

/// The prediction of a step (a tangent asked at F = F_n) takes its regime
/// from V2, as code_aster's `lcpivm`: after a plastic step it is the
/// plastic tangent with a zero multiplier, which is the limit of the
/// consistent tangent of a plastic step whose increment goes to zero;
/// the stress and the internal variables are those of the start.
#[test]
fn prediction_after_a_plastic_step_is_the_zero_multiplier_tangent() {
    let law = copper();
    let (f0, v0) = deformed_state(&law);
    assert_eq!(v0[1], 1.0, "the state must come from a plastic step");
    let start = run(&law, f0, f0, &v0, TangentKind::Consistent);
    assert_eq!(start.regime, Regime::Plastic);
    assert_eq!(start.internal.as_slice()[..2], v0[..2]);
    // A further plastic step of shrinking size: its consistent tangent
    // tends to the prediction's at first order.
    let dir = Matrix3::new(1e-3, 2e-4, 0.0, -1e-4, -4e-4, 3e-4, 0.0, 0.0, -5e-4);
    let pred = start.dtau_df.unwrap();
    let mut errs = Vec::new();
    for s in [1e-2, 1e-3] {
        let f1 = f0 + f0 * dir * s;
        let out = run(&law, f0, f1, &v0, TangentKind::Consistent);
        assert_eq!(out.regime, Regime::Plastic, "step {s}");
        errs.push((out.dtau_df.unwrap() - pred).norm() / pred.norm());
    }
    assert!(errs[1] < 2e-4, "{errs:?}");
    assert!(errs[1] < errs[0] / 5.0, "not first order: {errs:?}");
    // The elastic tangent (which the round-off sign of q - c0 could have
    // given) is far from it.
    let e = run(&law, f0, f0, &v0, TangentKind::Elastic)
        .dtau_df
        .unwrap();
    assert!((e - pred).norm() / e.norm() > 1e-3);
}

/// After an elastic step (V2 = 0) the prediction is elastic even when the
/// stress lies on the yield surface up to round-off on its outer side.
#[test]
fn prediction_after_an_elastic_step_is_elastic_on_the_surface() {
    let law = copper();
    let (f0, mut v0) = deformed_state(&law);
    // The same state flagged elastic, its b̄ᵉ - 1 (V3..V8) enlarged by a
    // relative 1e-10, so that q exceeds √(2/3) R(p) by about that much: the
    // sign of q - c0 says plastic.
    v0[1] = 0.0;
    for v in &mut v0[2..8] {
        *v *= 1.0 + 1e-10;
    }
    let trial = run(&law, f0, f0 * 1.0000001, &v0, TangentKind::None);
    assert_eq!(trial.regime, Regime::Plastic, "the state must be outside");
    let out = run(&law, f0, f0, &v0, TangentKind::Consistent);
    assert_eq!(out.regime, Regime::Elastic);
    assert_eq!(out.internal.as_slice()[..2], v0[..2]);
    let e = run(&law, f0, f0, &v0, TangentKind::Elastic);
    assert_eq!(out.dtau_df.unwrap(), e.dtau_df.unwrap());
}

/// Probe s8g D1: one AXIS QUAD8 (r in [4, 5], 9 Gauss points) stretched
/// along its axis in perfect plasticity (D_SIGM_EPSI = 0, NU = 0) in 7
/// steps. With the prediction's regime taken from the round-off sign of
/// q - c0, at the prediction of the fourth step some points came out
/// plastic and some elastic, and the predicted increment inverted the cell
/// ("element inverted", the run stopped). Uniaxial Kirchhoff stress SY
/// with J^2 = 1 + 2 SY/(3K) gives the Cauchy stress SY/sqrt(1 + 2 SY/3K)
/// at every point.
#[test]
fn perfect_plasticity_axis_quad8_stretch() {
    use aster::mesh::{Cell, CellType, Mesh};
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("sm_pp_quad8_src");
    std::fs::create_dir_all(&dir).unwrap();
    let coords = vec![
        [4.0, 0.0, 0.0],
        [5.0, 0.0, 0.0],
        [5.0, 1.0, 0.0],
        [4.0, 1.0, 0.0],
        [4.5, 0.0, 0.0],
        [5.0, 0.5, 0.0],
        [4.5, 1.0, 0.0],
        [4.0, 0.5, 0.0],
    ];
    let mut mesh = Mesh {
        name: "BARRE".into(),
        dim: 2,
        coords,
        ..Mesh::default()
    };
    for (group, kind, nodes) in [
        ("BAR", CellType::Quad8, vec![0, 1, 2, 3, 4, 5, 6, 7]),
        ("BAS", CellType::Seg3, vec![0, 1, 4]),
        ("HAUT", CellType::Seg3, vec![2, 3, 6]),
    ] {
        mesh.cells.push(Cell { kind, nodes });
        let c = mesh.cells.len() - 1;
        mesh.cell_groups.insert(group.into(), vec![c]);
    }
    let med = dir.join("mesh.mmed");
    aster::medio::write_mesh(&med, &mesh).unwrap();
    let (sy, e): (f64, f64) = (100.0, 200_000.0);
    let sigma = sy / (1.0 + 2.0 * sy / (e / 1.0)).sqrt();
    let tests: String = (1..=9)
        .map(|g| {
            format!(
                "TEST_RESU(RESU=_F(RESULTAT=R, INST=1., NOM_CHAM='SIEF_ELGA', NOM_CMP='SIYY', \
                 GROUP_MA='BAR', POINT={g}, VALE_CALC={sigma:.12}, REFERENCE='ANALYTIQUE', \
                 VALE_REFE={sigma:.12}, PRECISION=1.E-9))\n"
            )
        })
        .collect();
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))\n\
         ACIER = DEFI_MATERIAU(ELAS=_F(E={e}, NU=0.), ECRO_LINE=_F(SY={sy}, D_SIGM_EPSI=0.))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))\n\
         RAMPE = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 0.2))\n\
         BAS = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_MA='BAS', DY=0.))\n\
         HAUT = AFFE_CHAR_MECA_F(MODELE=MO, DDL_IMPO=_F(GROUP_MA='HAUT', DY=RAMPE))\n\
         L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=7))\n\
         R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=BAS), _F(CHARGE=HAUT)),\n\
             COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', DEFORMATION='SIMO_MIEHE', TOUT='OUI'),\n\
             INCREMENT=_F(LIST_INST=L))\n\
         {tests}\
         FIN()\n"
    );
    let (r, _) = common::run_generated(&dir, "sm_pp_quad8", &comm, &med);
    common::assert_all_ok(&r, "sm_pp_quad8.resu");
    let mess = r.file("sm_pp_quad8.mess");
    assert!(mess.contains("7 steps (0 cuts)"), "{mess}");
}
