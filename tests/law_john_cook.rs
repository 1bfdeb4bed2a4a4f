//! Verification of VMIS_JOHN_COOK (src/law/john_cook.rs): the flow curve
//! in uniaxial stress at three constant strain rates, the single-step
//! values computed independently in shared/docs/notes/john-cook-gdef-log.md
//! (§C.1, §C.2, mpmath, not code_aster output), a stiff case where Newton
//! on the consistency equation leaves the admissible domain while the
//! bracketed methods converge, the failure status, and the consistent
//! tangent against finite differences.

use aster::law::john_cook::{EcroCookParams, LocalControls, VmisJohnCook, METADATA};
use aster::law::root1d::RootMethod;
use aster::law::voigt::von_mises;
use aster::law::{
    ElasParams, FailureKind, Regime, SmallStrainBehaviour, SmallStrainInput, SmallStrainOutput,
    TangentKind, Vec6,
};

const E: f64 = 117_000.0;
const NU: f64 = 0.35;
const A: f64 = 90.0;
const B: f64 = 292.0;
const N: f64 = 0.31;
const C: f64 = 0.025;

/// OFHC copper of SDNV103 G (no temperature field: TROOM/TMELT inert).
fn copper(controls: LocalControls) -> VmisJohnCook {
    let elas = ElasParams::new(E, NU, Some(8.93e-9)).unwrap();
    let ecro = EcroCookParams::new(A, B, C, N, 1.09, 1.0, 298.0, 1083.0).unwrap();
    VmisJohnCook::new(elas, ecro, controls)
}

fn step(
    law: &VmisJohnCook,
    stress: Vec6,
    internal: &[f64],
    de: Vec6,
    dt: f64,
    tangent: TangentKind,
) -> SmallStrainOutput {
    law.integrate(&SmallStrainInput {
        stress,
        internal,
        strain_increment: de,
        dt,
        tangent,
    })
    .expect("integration")
}

/// Johnson–Cook flow stress with code_aster's rate convention (factor 1
/// at or below EPSP0 = 1).
fn jc(p: f64, rate: f64) -> f64 {
    (A + B * p.powf(N)) * (1.0 + C * rate.max(1.0).ln())
}

/// One uniaxial-stress step: Δε_xx imposed, the lateral strains found by a
/// local Newton iteration so that σ_yy = σ_zz = 0.
fn uniaxial_step(
    law: &VmisJohnCook,
    stress: Vec6,
    internal: &[f64],
    dexx: f64,
    dt: f64,
) -> SmallStrainOutput {
    let mut lat = -0.5 * dexx;
    for _ in 0..50 {
        let de = Vec6::new(dexx, lat, lat, 0.0, 0.0, 0.0);
        let out = step(law, stress, internal, de, dt, TangentKind::Consistent);
        let d = out.tangent.unwrap();
        let r = out.stress[1];
        if r.abs() <= 1e-11 * out.stress[0].abs().max(1.0) {
            return out;
        }
        lat -= r / (d[(1, 1)] + d[(1, 2)]);
    }
    panic!("lateral stress iteration did not converge");
}

#[test]
fn metadata_has_code_aster_names() {
    assert_eq!(METADATA.name, "VMIS_JOHN_COOK");
    assert_eq!(
        METADATA.internal_variables,
        &["EPSPEQ", "INDIPLAS", "DEPSPEQ", "DINSTM", "DDISSM"]
    );
}

#[test]
fn flow_stress_table_c1() {
    // §C.1 of the note (independent mpmath evaluation of the formula).
    let law = copper(LocalControls::default());
    let cases = [
        (0.05, 1.0, 205.362206),
        (0.10, 1e3, 273.255752),
        (0.20, 1e4, 328.844792),
        (0.50, 1e3, 381.758055),
        (0.50, 0.5, 325.539394),
    ];
    for (p, rate, want) in cases {
        let dt = 1e-6;
        // flow_stress(p_n, Δp, Δt): p = p_n + Δp and rate Δp/Δt.
        let dp = rate * dt;
        let (r, _) = law.flow_stress(p - dp, dp, dt);
        assert!((r - want).abs() < 1e-6, "p={p} rate={rate}: {r} vs {want}");
    }
    // First yield: A + B·(1e-9)ⁿ, not A.
    let (r0, _) = law.flow_stress(0.0, 0.0, 1.0);
    assert!((r0 - 90.4735685).abs() < 1e-7, "{r0}");
}

#[test]
fn single_step_matches_c2() {
    // Isochoric increment diag(δ, −δ/2, −δ/2), δ = 0.01, Δt = 1e-5.
    let law = copper(LocalControls::default());
    let d = 0.01;
    let out = step(
        &law,
        Vec6::zeros(),
        &[0.0; 5],
        Vec6::new(d, -d / 2.0, -d / 2.0, 0.0, 0.0, 0.0),
        1e-5,
        TangentKind::None,
    );
    assert_eq!(out.regime, Regime::Plastic);
    let v = out.internal.as_slice();
    assert!((v[0] - 8.5899358e-3).abs() < 1e-9, "V1 = {}", v[0]);
    assert_eq!(v[0], v[2]);
    assert_eq!(v[3], 1e-5);
    assert!(v[1] >= 1.0, "V2 counts iterations: {}", v[1]);
    assert!(
        (out.stress[0] - 122.205564).abs() < 1e-5,
        "{}",
        out.stress[0]
    );
    assert!(
        (out.stress[1] + 61.102782).abs() < 1e-5,
        "{}",
        out.stress[1]
    );
    assert!((v[4] - 1.417146e5).abs() < 1.0, "V5 = {}", v[4]);
}

/// The flow curve in uniaxial stress at constant strain rate: at every
/// plastic step σ_xx = (A + B pⁿ)(1 + C ln(ṗ/EPSP0)) with p = V1 and
/// ṗ = V3/V4, to 1e-8 relative (RESI_INTE_RELA = 1e-10 so that the
/// residual tolerance is below the check). With the imposed rate instead
/// of ṗ the rigid-plastic curve holds to O(H/E) (1e-3 after p = 0.05).
/// Below EPSP0 (1e-3 /s) the rate factor is exactly 1: code_aster never
/// softens below the reference rate.
#[test]
fn uniaxial_flow_curve_at_three_rates() {
    let law = copper(LocalControls {
        resi_rela: 1e-10,
        ..LocalControls::default()
    });
    for rate in [1e-3, 1.0, 1e4] {
        let dexx = 1e-3;
        let dt = dexx / rate;
        let mut stress = Vec6::zeros();
        let mut internal = vec![0.0; 5];
        let mut worst = 0.0f64;
        let mut worst_rigid = 0.0f64;
        let mut plastic_steps = 0;
        for _ in 0..500 {
            let out = uniaxial_step(&law, stress, &internal, dexx, dt);
            stress = out.stress;
            internal = out.internal.as_slice().to_vec();
            if internal[1] >= 0.5 {
                plastic_steps += 1;
                let p = internal[0];
                let want = jc(p, internal[2] / internal[3]);
                let err = ((stress[0] - want) / want).abs();
                worst = worst.max(err);
                assert!(
                    (von_mises(&stress) - stress[0]).abs() < 1e-8 * stress[0],
                    "not uniaxial"
                );
                if p > 0.05 {
                    let rigid = jc(p, rate);
                    worst_rigid = worst_rigid.max(((stress[0] - rigid) / rigid).abs());
                }
            }
        }
        assert!(
            plastic_steps > 490,
            "rate {rate}: {plastic_steps} plastic steps"
        );
        assert!(worst < 1e-8, "rate {rate}: flow stress error {worst:e}");
        assert!(
            worst_rigid < 1e-3,
            "rate {rate}: rigid-plastic error {worst_rigid:e}"
        );
        if rate < 1.0 {
            // No rate factor at all: σ = A + B pⁿ.
            let static_r = A + B * internal[0].powf(N);
            assert!(((stress[0] - static_r) / static_r).abs() < 1e-8);
        }
        // V1 accumulates V3.
        assert!(internal[0] > 0.45 && internal[0] < 0.5);
    }
}

/// A saturated state (p_n = 0.5, previous step elastic) hit by a small
/// deviatoric increment in 1 ns: the plastic rate ~1e5 /s switches the
/// rate term on, f(Δp) = R + 3μΔp − σ_eq^tr is very concave near 0, and
/// Newton's first iterate from Δp₀ = (σ_eq^tr − R_chk)/3μ is negative,
/// outside the domain of ln(Δp/Δt). Brent (and Dekker, secant) stay in
/// the bracket and converge within ITER_INTE_MAXI.
fn stiff_case() -> (f64, Vec6, [f64; 5], f64) {
    let p_n: f64 = 0.5;
    let mu3 = 3.0 * E / (2.0 * (1.0 + NU));
    let q_tr = A + B * p_n.powf(N) + 13.0;
    let d = q_tr / mu3;
    (
        p_n,
        Vec6::new(d, -d / 2.0, -d / 2.0, 0.0, 0.0, 0.0),
        [p_n, 0.0, 0.0, 1e-6, 0.0],
        1e-9,
    )
}

#[test]
fn newton_overshoots_where_bracketed_methods_converge() {
    let law = copper(LocalControls::default());
    let (p_n, de, internal, dt) = stiff_case();
    let mu3 = 3.0 * E / (2.0 * (1.0 + NU));
    let q_tr = mu3 * de[0];
    let r_chk = A + B * p_n.powf(N);
    let dp0 = (q_tr - r_chk) / mu3;
    let f = |dp: f64| law.flow_stress(p_n, dp, dt).0 + mu3 * dp - q_tr;
    let fp = |dp: f64| law.flow_stress(p_n, dp, dt).1 + mu3;
    let newton1 = dp0 - f(dp0) / fp(dp0);
    assert!(
        newton1 < 0.0,
        "Newton's first iterate {newton1:e} should leave Δp ≥ 0"
    );
    for method in [RootMethod::Brent, RootMethod::Dekker, RootMethod::Secante] {
        let law = copper(LocalControls {
            method,
            ..LocalControls::default()
        });
        let out = step(&law, Vec6::zeros(), &internal, de, dt, TangentKind::None);
        let v = out.internal.as_slice();
        assert_eq!(out.regime, Regime::Plastic);
        let dp = v[2];
        assert!(dp > 0.0 && dp < dp0, "{method:?}: dp = {dp:e}");
        let resid = f(dp);
        let (r, _) = law.flow_stress(p_n, dp, dt);
        assert!(
            resid.abs() <= 1e-6 * r * 1.5,
            "{method:?}: residual {resid:e}"
        );
        assert!(
            v[1] >= 1.0 && v[1] <= 20.0,
            "{method:?}: {} iterations",
            v[1]
        );
        // The rate term is active at the root (ṗ > EPSP0 = 1), although
        // much weaker than at Δp₀ (ṗ ≈ 1e5): that gap is what defeats Newton.
        assert!(dp / dt > 1.0, "{method:?}: rate {}", dp / dt);
    }
}

#[test]
fn a_step_that_cannot_converge_is_a_failure() {
    let law = copper(LocalControls {
        iter_maxi: 1,
        ..LocalControls::default()
    });
    let (_, de, internal, dt) = stiff_case();
    let err = law
        .integrate(&SmallStrainInput {
            stress: Vec6::zeros(),
            internal: &internal,
            strain_increment: de,
            dt,
            tangent: TangentKind::Consistent,
        })
        .unwrap_err();
    assert_eq!(err.kind, FailureKind::NotConverged);
    assert!(err.dt_factor > 0.0 && err.dt_factor < 1.0);
    assert!(err.message.contains("VMIS_JOHN_COOK"), "{}", err.message);
    // Δt = 0 (a state evaluation) is the elastic limit of infinite rate,
    // finite everywhere, never NaN.
    let law = copper(LocalControls::default());
    let de = Vec6::new(0.01, -0.005, -0.005, 0.0, 0.0, 0.0);
    let out = step(
        &law,
        Vec6::zeros(),
        &[0.0; 5],
        de,
        0.0,
        TangentKind::Consistent,
    );
    assert_eq!(out.regime, Regime::Elastic);
    let mu2 = E / (1.0 + NU);
    assert!((out.stress[0] - mu2 * 0.01).abs() < 1e-9);
    assert!(out.internal.as_slice().iter().all(|v| v.is_finite()));
}

/// The consistent tangent (rate term in R′) against central differences
/// of the stress update, in a plastic step with shear.
#[test]
fn consistent_tangent_matches_finite_differences() {
    let law = copper(LocalControls {
        resi_rela: 1e-13,
        iter_maxi: 100,
        ..LocalControls::default()
    });
    // A prestressed, hardened state.
    let stress = Vec6::new(150.0, -40.0, 10.0, 30.0, -20.0, 15.0);
    let internal = [0.2, 3.0, 1e-3, 1e-6, 0.0];
    let de = Vec6::new(3e-3, -1e-3, -1.5e-3, 2e-3, 1e-3, -5e-4);
    let dt = 1e-6;
    let out = step(&law, stress, &internal, de, dt, TangentKind::Consistent);
    assert_eq!(out.regime, Regime::Plastic);
    let d = out.tangent.unwrap();
    let h = 1e-8;
    let mut worst = 0.0f64;
    for j in 0..6 {
        let mut dp = de;
        dp[j] += h;
        let mut dm = de;
        dm[j] -= h;
        let sp = step(&law, stress, &internal, dp, dt, TangentKind::None).stress;
        let sm = step(&law, stress, &internal, dm, dt, TangentKind::None).stress;
        let col = (sp - sm) / (2.0 * h);
        for i in 0..6 {
            worst = worst.max((col[i] - d[(i, j)]).abs());
        }
    }
    assert!(worst < 1e-5 * E, "tangent error {worst:e}");
}
