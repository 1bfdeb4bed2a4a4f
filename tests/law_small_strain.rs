//! Verification of the small-strain laws ELAS and VMIS_ISOT_LINE against
//! closed-form solutions (bilinear uniaxial curve, pure shear, Hooke's law)
//! and against finite differences of the stress update.

use aster::law::elas::Elas;
use aster::law::vmis_isot_line::VmisIsotLine;
use aster::law::voigt::{isotropic_elastic, trace, von_mises};
use aster::law::{
    EcroLineParams, ElasParams, FailureKind, Mat6, Regime, SmallStrainBehaviour, SmallStrainInput,
    SmallStrainOutput, StrainMeasure, TangentKind, Vec6,
};

const E: f64 = 117_000.0;
const NU: f64 = 0.35;
const SY: f64 = 400.0;
const ET: f64 = 100.0;

fn copper() -> VmisIsotLine {
    let elas = ElasParams::new(E, NU, Some(8.93e-9)).unwrap();
    VmisIsotLine::new(elas, EcroLineParams::new(&elas, SY, ET).unwrap())
}

/// A harder material so that plastic steps have a well-conditioned tangent.
fn steel() -> VmisIsotLine {
    let elas = ElasParams::new(200_000.0, 0.3, None).unwrap();
    VmisIsotLine::new(elas, EcroLineParams::new(&elas, 250.0, 20_000.0).unwrap())
}

fn step(
    law: &dyn SmallStrainBehaviour,
    stress: Vec6,
    internal: &[f64],
    de: Vec6,
    tangent: TangentKind,
) -> SmallStrainOutput {
    law.integrate(&SmallStrainInput {
        stress,
        internal,
        strain_increment: de,
        dt: 1e-6,
        tangent,
    })
    .unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// Uniaxial stress: imposes Δε_xx and solves for Δε_yy = Δε_zz so that
/// σ_yy = σ_zz = 0, with a Newton on the consistent tangent (the test's
/// own outer loop, as a strain-driven material point would).
fn uniaxial_step(
    law: &VmisIsotLine,
    stress: Vec6,
    internal: &[f64],
    dexx: f64,
) -> SmallStrainOutput {
    let mut lat = -NU * dexx;
    for _ in 0..50 {
        let de = Vec6::new(dexx, lat, lat, 0.0, 0.0, 0.0);
        let out = step(law, stress, internal, de, TangentKind::Consistent);
        let r = out.stress[1];
        if r.abs() < 1e-10 * SY {
            return out;
        }
        let d = out.tangent.unwrap();
        lat -= r / (d[(1, 1)] + d[(1, 2)]);
    }
    panic!("uniaxial driver did not converge");
}

#[test]
fn hardening_modulus_from_tangent_modulus() {
    // semantics.md §4.1: E = 117000, E_T = 100 gives H = 100.0855 MPa.
    assert!((copper().hardening() - 100.0855).abs() < 1e-4);
    let h = copper().hardening();
    assert!(rel(h, E * ET / (E - ET)) < 1e-15);
}

#[test]
fn uniaxial_tension_follows_bilinear_curve_then_unloads_with_slope_e() {
    let law = copper();
    let mut stress = Vec6::zeros();
    let mut vars = law.initial_internal();
    let n = 100;
    let eps_max = 0.05;
    let mut eps = 0.0;
    for _ in 0..n {
        let out = uniaxial_step(&law, stress, vars.as_slice(), eps_max / n as f64);
        eps += eps_max / n as f64;
        stress = out.stress;
        vars = out.internal;
        let want = if eps <= SY / E {
            E * eps
        } else {
            SY + ET * (eps - SY / E)
        };
        assert!(
            rel(stress[0], want) < 1e-9,
            "eps {eps}: {} vs {want}",
            stress[0]
        );
        assert!(stress[2].abs() < 1e-8 && stress[3].abs() < 1e-12);
    }
    let sig_max = stress[0];
    // Axial plastic strain equals p in uniaxial stress.
    assert!(rel(vars.as_slice()[0], eps_max - sig_max / E) < 1e-9);
    assert_eq!(vars.as_slice()[1], 1.0);
    // Unloading by 2e-3 stays elastic with slope E.
    let out = uniaxial_step(&law, stress, vars.as_slice(), -2e-3);
    assert_eq!(out.regime, Regime::Elastic);
    assert!(rel(out.stress[0], sig_max - E * 2e-3) < 1e-9);
    assert_eq!(out.internal.as_slice(), &[vars.as_slice()[0], 0.0]);
}

#[test]
fn pure_shear_matches_closed_form() {
    let law = copper();
    let mu = E / (2.0 * (1.0 + NU));
    let h = law.hardening();
    let mut stress = Vec6::zeros();
    let mut vars = law.initial_internal();
    let mut gamma = 0.0;
    for _ in 0..40 {
        let dg = 5e-4;
        gamma += dg;
        let out = step(
            &law,
            stress,
            vars.as_slice(),
            Vec6::new(0.0, 0.0, 0.0, dg, 0.0, 0.0),
            TangentKind::None,
        );
        stress = out.stress;
        vars = out.internal;
        let tau_y = SY / 3f64.sqrt();
        let want = if mu * gamma <= tau_y {
            mu * gamma
        } else {
            (tau_y + h * gamma / 3.0) / (1.0 + h / (3.0 * mu))
        };
        assert!(
            rel(stress[3], want) < 1e-10,
            "gamma {gamma}: {} vs {want}",
            stress[3]
        );
        assert!(stress[0].abs() < 1e-9 && stress[4].abs() < 1e-12);
    }
}

fn fd_tangent(law: &dyn SmallStrainBehaviour, stress: Vec6, internal: &[f64], de: Vec6) -> Mat6 {
    let h = 1e-9;
    let mut d = Mat6::zeros();
    for j in 0..6 {
        let mut p = de;
        let mut m = de;
        p[j] += h;
        m[j] -= h;
        let sp = step(law, stress, internal, p, TangentKind::None).stress;
        let sm = step(law, stress, internal, m, TangentKind::None).stress;
        d.set_column(j, &((sp - sm) / (2.0 * h)));
    }
    d
}

/// A state on the yield surface after prior plastic loading.
fn hardened_state(law: &VmisIsotLine) -> (Vec6, Vec<f64>) {
    let out = step(
        law,
        Vec6::zeros(),
        law.initial_internal().as_slice(),
        Vec6::new(9e-3, -3e-3, -1.5e-3, 6e-3, -3e-3, 2.1e-3),
        TangentKind::None,
    );
    assert_eq!(out.regime, Regime::Plastic);
    (out.stress, out.internal.as_slice().to_vec())
}

#[test]
fn consistent_tangent_equals_finite_difference_tangent() {
    for law in [copper(), steel()] {
        let (s0, v0) = hardened_state(&law);
        // A further plastic step in a different direction, and an elastic unloading.
        let cases = [
            (
                Vec6::new(1e-3, 0.4e-3, -0.9e-3, -0.5e-3, 1.2e-3, 0.3e-3),
                Regime::Plastic,
            ),
            (
                Vec6::new(-2e-4, 0.5e-4, 0.5e-4, -1e-4, 0.5e-4, -0.3e-4),
                Regime::Elastic,
            ),
        ];
        for (de, regime) in cases {
            let out = step(&law, s0, &v0, de, TangentKind::Consistent);
            assert_eq!(out.regime, regime);
            let d = out.tangent.unwrap();
            let fd = fd_tangent(&law, s0, &v0, de);
            let err = (d - fd).norm() / d.norm();
            assert!(err < 1e-6, "{regime:?}: relative tangent error {err}");
        }
    }
}

/// The prediction of a step (a zero increment) from a state on the yield
/// surface takes the continuum plastic tangent at every point, whatever
/// the last bits of q − R: σ nudged by ±4 ulp around the surface gives
/// the same tangent, K 1⊗1 + 2μ I_dev − 2μ·3μ/(3μ+H) n⊗n, and leaves σ
/// and p unchanged. Off the surface (q < R by 1e-6) it is elastic. (Left
/// to round-off, one point of a hardened bar took the elastic tangent and
/// its neighbour the plastic one, and MECA_HEXS8 stalled on unloading:
/// tests/studies/stat_plastic_bar.comm.)
#[test]
fn zero_increment_on_the_yield_surface_takes_the_plastic_tangent() {
    for law in [copper(), steel()] {
        let (s0, v0) = hardened_state(&law);
        let elastic = isotropic_elastic(law.elas.bulk(), law.elas.mu());
        let mu = law.elas.mu();
        let h = law.hardening();
        let dev = aster::law::voigt::deviator(&s0);
        let n = dev / aster::law::voigt::double_dot(&dev, &dev).sqrt();
        let expect = elastic - n * n.transpose() * (2.0 * mu * 3.0 * mu / (3.0 * mu + h));
        for ulps in [-4i64, -1, 0, 1, 4] {
            let f = 1.0 + ulps as f64 * f64::EPSILON;
            let out = step(&law, s0 * f, &v0, Vec6::zeros(), TangentKind::Consistent);
            assert_eq!(out.regime, Regime::Plastic, "{ulps} ulp");
            let d = out.tangent.unwrap();
            assert!((d - expect).norm() / expect.norm() < 1e-12, "{ulps} ulp");
            assert_eq!(out.stress, s0 * f);
            assert_eq!(out.internal.as_slice()[0], v0[0]);
        }
        let inside = step(
            &law,
            s0 * (1.0 - 1e-6),
            &v0,
            Vec6::zeros(),
            TangentKind::Consistent,
        );
        assert_eq!(inside.regime, Regime::Elastic);
        assert_eq!(inside.tangent.unwrap(), elastic);
    }
}

#[test]
fn consistent_tangent_is_not_the_elastic_one_in_plastic_steps() {
    // Guards the previous test: in a plastic step the two tangents differ.
    let law = steel();
    let (s0, v0) = hardened_state(&law);
    let de = Vec6::new(1e-3, 0.4e-3, -0.9e-3, -0.5e-3, 1.2e-3, 0.3e-3);
    let c = step(&law, s0, &v0, de, TangentKind::Consistent)
        .tangent
        .unwrap();
    let e = step(&law, s0, &v0, de, TangentKind::Elastic)
        .tangent
        .unwrap();
    assert!((c - e).norm() / e.norm() > 0.1);
    assert!(step(&law, s0, &v0, de, TangentKind::None).tangent.is_none());
}

#[test]
fn yield_condition_and_plastic_incompressibility_after_plastic_step() {
    for law in [copper(), steel()] {
        let (s0, v0) = hardened_state(&law);
        let de = Vec6::new(1e-3, 0.4e-3, -0.9e-3, -0.5e-3, 1.2e-3, 0.3e-3);
        let out = step(&law, s0, &v0, de, TangentKind::None);
        let p = out.internal.as_slice()[0];
        assert!(p > v0[0]);
        let r = law.yield_stress(p);
        assert!(rel(von_mises(&out.stress), r) < 1e-10);
        assert!(rel(von_mises(&s0), law.yield_stress(v0[0])) < 1e-10);
        // Δε_p = Δε − D⁻¹Δσ must be traceless.
        let d = isotropic_elastic(law.elas.bulk(), law.elas.mu());
        let dep = de - d.try_inverse().unwrap() * (out.stress - s0);
        assert!(
            trace(&dep).abs() < 1e-12 * dep.norm(),
            "tr Δε_p = {}",
            trace(&dep)
        );
        // And its equivalent value is Δp: √(2/3 Δε_p:Δε_p) with tensor shears.
        let t = Vec6::new(
            dep[0],
            dep[1],
            dep[2],
            dep[3] / 2.0,
            dep[4] / 2.0,
            dep[5] / 2.0,
        );
        let eq = (2.0 / 3.0 * aster::law::voigt::double_dot(&t, &t)).sqrt();
        assert!(rel(eq, p - v0[0]) < 1e-9);
    }
}

#[test]
fn one_big_step_equals_many_small_steps_for_proportional_loading() {
    let law = steel();
    let dir = Vec6::new(2e-3, -0.5e-3, -0.8e-3, 1.5e-3, 0.4e-3, -0.9e-3);
    let big = step(
        &law,
        Vec6::zeros(),
        law.initial_internal().as_slice(),
        dir * 5.0,
        TangentKind::None,
    );
    let mut s = Vec6::zeros();
    let mut v = law.initial_internal();
    for _ in 0..50 {
        let o = step(&law, s, v.as_slice(), dir * 0.1, TangentKind::None);
        s = o.stress;
        v = o.internal;
    }
    assert!((big.stress - s).norm() / s.norm() < 1e-10);
    assert!(rel(big.internal.as_slice()[0], v.as_slice()[0]) < 1e-10);
}

#[test]
fn elas_is_hookes_law() {
    let elas = ElasParams::new(E, NU, None).unwrap();
    let law = Elas::new(elas);
    let sig = 123.0;
    let de = Vec6::new(sig / E, -NU * sig / E, -NU * sig / E, 0.0, 0.0, 0.0);
    let out = step(&law, Vec6::zeros(), &[0.0], de, TangentKind::Consistent);
    assert!(rel(out.stress[0], sig) < 1e-13);
    assert!(out.stress[1].abs() < 1e-11 && out.stress[2].abs() < 1e-11);
    let g = E / (2.0 * (1.0 + NU));
    let out = step(
        &law,
        Vec6::zeros(),
        &[0.0],
        Vec6::new(0.0, 0.0, 0.0, 0.0, 1e-3, 0.0),
        TangentKind::None,
    );
    assert!(rel(out.stress[4], g * 1e-3) < 1e-13);
    // Below yield, VMIS_ISOT_LINE and ELAS agree exactly.
    let de = Vec6::new(1e-4, 2e-4, -1e-4, 0.5e-4, 0.0, 1e-4);
    let a = step(&law, Vec6::zeros(), &[0.0], de, TangentKind::Consistent);
    let b = step(
        &copper(),
        Vec6::zeros(),
        &[0.0, 0.0],
        de,
        TangentKind::Consistent,
    );
    assert_eq!(b.regime, Regime::Elastic);
    assert!((a.stress - b.stress).norm() < 1e-10);
    assert!((a.tangent.unwrap() - b.tangent.unwrap()).norm() < 1e-9);
}

#[test]
fn bad_inputs_are_errors_not_panics() {
    let law = copper();
    let base = SmallStrainInput {
        stress: Vec6::zeros(),
        internal: &[0.0, 0.0],
        strain_increment: Vec6::zeros(),
        dt: 1e-6,
        tangent: TangentKind::Consistent,
    };
    let mut nan_strain = base;
    nan_strain.strain_increment[3] = f64::NAN;
    let mut inf_stress = base;
    inf_stress.stress[0] = f64::INFINITY;
    let mut neg_dt = base;
    neg_dt.dt = -1.0;
    let mut nan_var = base;
    nan_var.internal = &[f64::NAN, 0.0];
    let mut short = base;
    short.internal = &[0.0];
    let mut neg_p = base;
    neg_p.internal = &[-1e-3, 0.0];
    for bad in [nan_strain, inf_stress, neg_dt, nan_var, short, neg_p] {
        let err = law.integrate(&bad).unwrap_err();
        assert_eq!(err.kind, FailureKind::InvalidInput);
        assert!(err.message.starts_with("VMIS_ISOT_LINE"), "{}", err.message);
    }
    assert!(law.integrate(&base).is_ok());
    let elas = ElasParams::new(E, NU, None).unwrap();
    assert!(Elas::new(elas).integrate(&nan_strain).is_err());
}

#[test]
fn material_parameters_are_checked() {
    let elas = ElasParams::new(E, NU, None).unwrap();
    let err = EcroLineParams::new(&elas, SY, E).unwrap_err();
    assert_eq!(err.keyword, "ECRO_LINE/D_SIGM_EPSI");
    assert!(EcroLineParams::new(&elas, SY, 2.0 * E).is_err());
    assert_eq!(
        EcroLineParams::new(&elas, -1.0, ET).unwrap_err().keyword,
        "ECRO_LINE/SY"
    );
    assert_eq!(
        ElasParams::new(E, 0.5, None).unwrap_err().keyword,
        "ELAS/NU"
    );
    assert_eq!(
        ElasParams::new(f64::NAN, 0.3, None).unwrap_err().keyword,
        "ELAS/E"
    );
    assert_eq!(
        ElasParams::new(E, 0.3, Some(-1.0)).unwrap_err().keyword,
        "ELAS/RHO"
    );
}

#[test]
fn metadata_follows_code_aster_declarations() {
    let law = copper();
    let m = law.metadata();
    assert_eq!(m.name, "VMIS_ISOT_LINE");
    assert_eq!(m.internal_variables, &["EPSPEQ", "INDIPLAS"]);
    assert!(m.accepts(StrainMeasure::SimoMiehe));
    let e = Elas::new(ElasParams::new(E, NU, None).unwrap());
    assert!(!e.metadata().accepts(StrainMeasure::SimoMiehe));
    assert!(!e.metadata().accepts(StrainMeasure::GdefLog));
    assert_eq!(
        StrainMeasure::from_aster_name("PETIT_REAC"),
        Some(StrainMeasure::PetitReac)
    );
}

/// Each tensorial internal variable a law declares
/// (`LawMetadata::tensor_variables`, what MECA_HEXS8 turns with the stress)
/// names six components in the stress order xx, yy, zz, xy, xz, yz, and
/// the variables so named are all declared (VMIS_CINE_LINE's back stress,
/// the Kirchhoff T of GDEF_LOG, b̄ᵉ of SIMO_MIEHE).
#[test]
fn tensor_variables_are_declared_with_their_six_components() {
    use aster::law::{elas, gdef_log, john_cook, simo_miehe, vmis_cine_line};
    use aster::law::{vmis_isot_line, vmis_isot_puis, vmis_isot_trac};
    let all = [
        &elas::METADATA,
        &vmis_isot_line::METADATA,
        &vmis_isot_trac::METADATA,
        &vmis_isot_puis::METADATA,
        &vmis_cine_line::METADATA,
        &john_cook::METADATA,
        &gdef_log::ISOT_LINE_LOG,
        &gdef_log::ISOT_TRAC_LOG,
        &gdef_log::ISOT_PUIS_LOG,
        &gdef_log::CINE_LINE_LOG,
        &gdef_log::JOHN_COOK_LOG,
        &simo_miehe::METADATA,
        &simo_miehe::TRAC_METADATA,
        &simo_miehe::PUIS_METADATA,
    ];
    let suffixes = ["XX", "YY", "ZZ", "XY", "XZ", "YZ"];
    for m in all {
        let names = m.internal_variables;
        let mut covered = vec![false; names.len()];
        for &k in m.tensor_variables {
            for (i, s) in suffixes.iter().enumerate() {
                assert!(names[k + i].ends_with(s), "{}: {:?} at {k}", m.name, names);
                covered[k + i] = true;
            }
        }
        for (i, n) in names.iter().enumerate() {
            let tensor_like = n.len() > 2 && suffixes.contains(&&n[n.len() - 2..]);
            assert_eq!(tensor_like, covered[i], "{}: {n} undeclared", m.name);
        }
    }
    assert_eq!(vmis_cine_line::METADATA.tensor_variables, &[0]);
}
