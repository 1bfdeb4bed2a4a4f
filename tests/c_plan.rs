//! AFFE_MODELE MODELISATION='C_PLAN' / 'C_PLAN_SI' (plane stress,
//! σ_zz = 0): verification studies against closed forms and the located
//! refusals of what is not built. The studies are in tests/verification
//! (cplan_*.comm; the meshes from scripts/cplan_meshes.py).

use std::path::{Path, PathBuf};

mod common;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification")
}

fn run_study(name: &str) -> String {
    let run = common::run_study(
        &format!("tests/verification/{name}.comm"),
        &format!("cplan_{name}"),
    );
    common::assert_all_ok(&run, &format!("{name}.resu"))
}

/// ELAS patch tests on the distorted patch in QUAD4, QUAD8, TRIA3, TRIA6
/// and C_PLAN_SI QUAD8: uniaxial tension (SIYY = E B, SIXX = 0, SIZZ = 0
/// exactly, EPXX = EPZZ = -NU B, reaction 2 E B per unit thickness) and
/// a general linear boundary field (plane-stress Hooke at the Gauss
/// points, the interior nodes on the linear field); the weight under
/// PESANTEUR, RHO g times the area per unit thickness; POST_ELEM
/// ENER_ELAS and ENER_POT of the general field, its plane-stress energy;
/// 1e-9.
#[test]
fn elastic_patch_tests() {
    let resu = run_study("cplan_patch");
    // 4 x 14 checks on the four cells, 2 on C_PLAN_SI, 1 weight, 4 x 2
    // energies: each with its reference.
    assert_eq!(
        resu.lines().filter(|l| l.contains("ANALYTIQUE")).count(),
        67
    );
}

/// VMIS_ISOT_LINE uniaxial past yield and unloading (the 1D law), under
/// displacement and under FORCE_CONTOUR, equibiaxial (closed form of the
/// proportional plane-stress flow), VMIS_CINE_LINE reversed into reverse
/// yield, VMIS_ISOT_TRAC and VMIS_ISOT_PUIS uniaxial (the 1D laws), 1e-8.
#[test]
fn plastic_plane_stress_against_closed_forms() {
    run_study("cplan_plastic");
}

/// DIFF_CENT with the lumped mass: the driving force of the held strip
/// is RHO C V0 h with the plane-stress speed sqrt(E/(RHO (1 - NU^2))).
#[test]
fn explicit_wave_runs_at_the_plane_stress_speed() {
    run_study("cplan_wave_explicit");
}

/// What C_PLAN does not build is refused where it is written: finite
/// strains (COMPORTEMENT/DEFORMATION), MECPQS4 (C_PLAN_SI on QUAD4),
/// EPSL_ELGA (CALC_CHAMP/DEFORMATION), a model mixing C_PLAN and D_PLAN.
#[test]
fn what_is_not_built_is_refused_with_a_located_message() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cplan_refusals");
    std::fs::create_dir_all(&tmp).unwrap();
    let comm = std::fs::read_to_string(dir().join("cplan_plastic.comm")).unwrap();
    let export = format!(
        "F mail {0}/cplan_quad4.mail D 20\nF mail {0}/cplan_quad8.mail D 21\n\
         F mail {0}/cplan_tria3.mail D 22\nF mail {0}/cplan_tria6.mail D 23\n",
        dir().display()
    );
    let cases: [(&str, (&str, &str), &[&str]); 4] = [
        (
            "simo_miehe",
            (
                "COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', TOUT='OUI'),\n                   INCREMENT=_F(LIST_INST=L_INST), CONVERGENCE",
                "COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', DEFORMATION='SIMO_MIEHE', TOUT='OUI'),\n                   INCREMENT=_F(LIST_INST=L_INST), CONVERGENCE",
            ),
            &[
                "not implemented yet: STAT_NON_LINE/COMPORTEMENT/DEFORMATION='SIMO_MIEHE'",
                "DEFORMATION='SIMO_MIEHE' on the plane-stress element MECPQU8 of cell M1",
                "MODELISATION='C_PLAN'",
            ],
        ),
        (
            "si_quad4",
            (
                "MO4 = AFFE_MODELE(MAILLAGE=MA4, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))",
                "MO4 = AFFE_MODELE(MAILLAGE=MA4, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN_SI'))",
            ),
            &["AFFE_MODELE/AFFE/MODELISATION", "C_PLAN_SI on QUAD4 is the element MECPQS4, which aster does not have"],
        ),
        (
            "epsl",
            (
                "R1 = CALC_CHAMP(reuse=R1, RESULTAT=R1, FORCE='REAC_NODA')",
                "R1 = CALC_CHAMP(reuse=R1, RESULTAT=R1, FORCE='REAC_NODA', DEFORMATION='EPSL_ELGA')",
            ),
            &["CALC_CHAMP/DEFORMATION", "EPSL_* on a C_PLAN model"],
        ),
        (
            "mixed",
            (
                "MO8 = AFFE_MODELE(MAILLAGE=MA8, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))",
                "MO8 = AFFE_MODELE(MAILLAGE=MA8, AFFE=(_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'),\n    _F(GROUP_MA='PLAQUE', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN')))",
            ),
            &["AFFE_MODELE/AFFE/MODELISATION", "cannot mix 2D plane stress (C_PLAN, C_PLAN_SI) and 2D plane strain"],
        ),
    ];
    for (tag, (from, to), wanted) in cases {
        let text = comm.replacen(from, to, 1);
        assert_ne!(text, comm, "{tag}");
        std::fs::write(tmp.join(format!("{tag}.comm")), text).unwrap();
        std::fs::write(tmp.join(format!("{tag}.export")), &export).unwrap();
        let run = common::run_study(
            tmp.join(format!("{tag}.comm")).to_str().unwrap(),
            &format!("cplan_refusal_{tag}"),
        );
        assert_eq!(run.code, 1, "{tag}: {}", run.term);
        for w in wanted {
            assert!(run.term.contains(w), "{tag}: {w}\n{}", run.term);
        }
        assert!(
            run.term.contains(&format!("{tag}.comm:")),
            "{tag}: {}",
            run.term
        );
        assert!(!run.term.contains("panicked"), "{tag}: {}", run.term);
    }
}
