//! ETAT_INIT=_F(EVOL_NOLI=...) continuation and SUIVI_DDL (docs/dynamics.md).
//!
//! A plastic Taylor bar against a held face (2 x 8 QUAD8, AXIS,
//! Johnson–Cook copper in GDEF_LOG, full HHT with ALPHA = -0.6, the
//! settings of modelling G) is computed in one DYNA_NON_LINE call and in
//! two (reuse=, ETAT_INIT EVOL_NOLI, the second call starting from the
//! last stored instant of the first), split at several archived instants.
//! Every final field (DEPL, VITE, ACCE, SIEF_ELGA, VARI_ELGA with the
//! GDEF_LOG stress variables) must equal the single run's to round-off,
//! and the continued result must carry on the numbering and instants of
//! the first. SUIVI_DDL's per-step column must show the maximum of V1 over
//! the Gauss points of the bar, as the result holds it.

mod dynamics_support;

use dynamics_support::*;
use indexmap::IndexMap;

use aster::model::{Dof, Material};
use aster::result::EvolNoli;

const V0: f64 = -227000.0;

fn cook_material() -> Material {
    let mut m = material(117_000.0, 0.35, 8.93e-9, None);
    let mut ec = IndexMap::new();
    for (k, v) in [
        ("A", 90.0),
        ("B", 292.0),
        ("C", 0.025),
        ("N_PUIS", 0.31),
        ("EPSP0", 1.0),
    ] {
        ec.insert(k.to_string(), v);
    }
    m.blocks.insert("ECRO_COOK".into(), ec);
    m
}

fn setup() -> aster::study::Study {
    let mesh = taylor_axis(2, 8);
    let vol = mesh.cell_groups["VOL"].clone();
    let nodes = mesh.nodes_of_cells(&vol);
    let held = mesh.nodes_of_cells(&mesh.cell_groups["SZZ"]);
    let axe = mesh.nodes_of_cells(&mesh.cell_groups["AXE"]);
    let moving: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|n| !held.contains(n))
        .collect();
    let mo = model(&mesh, "AXIS", &vol);
    let v = velocity(mesh.nnodes(), &moving, V0);
    let mut imp = imposed(&held, Dof::Dy, 0.0);
    imp.extend(imposed(&axe, Dof::Dx, 0.0));
    study(
        mesh,
        mo,
        cook_material(),
        imp,
        Some(v),
        linspace(0.0, 1.2e-6, 12),
        None,
    )
}

const COMMON: &str = "MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ),
    COMPORTEMENT=_F(RELATION='VMIS_JOHN_COOK', DEFORMATION='GDEF_LOG', ALGO_INTE='BRENT',
                    ITER_INTE_MAXI=30, TOUT='OUI'),
    SCHEMA_TEMPS=_F(SCHEMA='HHT', ALPHA=-0.6, MODI_EQUI='OUI', FORMULATION='DEPLACEMENT'),
    NEWTON=_F(MATRICE='TANGENTE', REAC_ITER=1),
    CONVERGENCE=_F(RESI_GLOB_RELA=1.E-6, ITER_GLOB_MAXI=20),
    SUIVI_DDL=_F(NOM_CHAM='VARI_ELGA', NOM_CMP='V1', TOUT='OUI', EVAL_CHAM='MAX', EVAL_ELGA='MAX')";

fn run_single() -> (aster::study::Study, EvolNoli) {
    let mut st = setup();
    let text = format!(
        "RESU = DYNA_NON_LINE({COMMON}, ETAT_INIT=_F(VITE=V0), INCREMENT=_F(LIST_INST=L_INST))"
    );
    exec(
        &mut st,
        "DYNA_NON_LINE",
        &args_of(&text, "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap();
    let r = result(&st, "RESU").clone();
    (st, r)
}

fn run_split(t_split: f64) -> EvolNoli {
    let mut st = setup();
    let text = format!(
        "RESU = DYNA_NON_LINE({COMMON}, ETAT_INIT=_F(VITE=V0),
             INCREMENT=_F(LIST_INST=L_INST, INST_FIN={t_split:e}))
         RESU = DYNA_NON_LINE(reuse=RESU, {COMMON}, ETAT_INIT=_F(EVOL_NOLI=RESU),
             INCREMENT=_F(LIST_INST=L_INST))"
    );
    for nth in 0..2 {
        exec(
            &mut st,
            "DYNA_NON_LINE",
            &args_of(&text, "DYNA_NON_LINE", nth),
            "RESU",
        )
        .unwrap();
    }
    result(&st, "RESU").clone()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[test]
fn split_run_equals_single_run() {
    let (_, single) = run_single();
    let last = single.steps.last().unwrap();
    let p_max = max_abs(&last.gauss["VARI_ELGA"].values);
    assert!(p_max > 0.01, "the bar must yield: max V1 {p_max}");
    for k in [1usize, 5, 9] {
        let t_split = single.steps[k].inst;
        let split = run_split(t_split);
        // The continued result carries on: same instants, one per step.
        let inst: Vec<f64> = split.steps.iter().map(|s| s.inst).collect();
        let want: Vec<f64> = single.steps.iter().map(|s| s.inst).collect();
        assert_eq!(inst.len(), want.len(), "split at {t_split:e}");
        for (a, b) in inst.iter().zip(&want) {
            assert!((a - b).abs() <= 1e-12 * 1.2e-6, "{inst:?}");
        }
        for (n, s) in split.steps.iter().enumerate() {
            assert_eq!(s.nume_ordre, n);
        }
        let end = split.steps.last().unwrap();
        for f in ["DEPL", "VITE", "ACCE"] {
            let (a, b) = (&end.nodal[f].values, &last.nodal[f].values);
            let scale = max_abs(b);
            let diff = a
                .iter()
                .zip(b.iter())
                .filter(|(x, y)| !x.is_nan() && !y.is_nan())
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            assert!(
                diff <= 1e-9 * scale,
                "split at {t_split:e}: {f} differs by {diff:e} (scale {scale:e})"
            );
        }
        for f in ["SIEF_ELGA", "VARI_ELGA"] {
            let (a, b) = (&end.gauss[f].values, &last.gauss[f].values);
            let scale = max_abs(b);
            let diff = a
                .iter()
                .zip(b.iter())
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            assert!(
                diff <= 1e-9 * scale,
                "split at {t_split:e}: {f} differs by {diff:e} (scale {scale:e})"
            );
        }
    }
}

#[test]
fn suivi_ddl_prints_the_maximum_of_v1_per_step() {
    let (st, single) = run_single();
    let mess = &st.mess;
    assert!(
        mess.contains("VARI_ELGA V1"),
        "no SUIVI_DDL column:\n{mess}"
    );
    // The per-step line of the last step ends with the SUIVI value.
    let last = single.steps.last().unwrap();
    let vari = &last.gauss["VARI_ELGA"];
    let ncmp = vari.ncmp();
    let p_max = vari
        .values
        .chunks(ncmp)
        .map(|row| row[0])
        .fold(f64::NEG_INFINITY, f64::max);
    let t = format!("{:.6e}", last.inst);
    let line = mess
        .lines()
        .rfind(|l| l.contains(&t) && !l.contains("iter"))
        .unwrap_or_else(|| panic!("no step line at {t}:\n{mess}"));
    let printed: f64 = line.split_whitespace().last().unwrap().parse().unwrap();
    assert!(
        (printed - p_max).abs() <= 1e-6 * p_max,
        "printed {printed}, max V1 {p_max}: {line}"
    );
    assert!(p_max > 0.01);
}
