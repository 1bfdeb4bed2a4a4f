//! The post-processing commands run on a synthetic result whose values are
//! known in closed form: POST_RELEVE_T, TEST_RESU, TEST_TABLE, IMPR_TABLE,
//! RECU_FONCTION, IMPR_FONCTION, IMPR_RESU (MED read back, RESULTAT).
//!
//! The study text goes through the real parser, checker and runner; three
//! test-only commands (SYNTH_MAIL, SYNTH_RESU, SYNTH_CHAMP) produce the
//! mesh, the evol_noli and the cham_no, so the checker knows their types.
//!
//! The synthetic data: a 2D mesh of two QUAD4 (nodes N1..N6 at x = 0, 1, 2
//! on y = 0 then y = 1); five stored steps at t = -1e-5, 0, 2.5e-7, 5e-7,
//! 1e-6 (NUME_ORDRE 0..4) with
//!   DEPL  DX = 1000 t x,  DY = -227000 t + 0.1 (n + 1)   (n = node index)
//!   VITE  DY = -227000, DX absent at N1 (set elsewhere to 0)
//!   SIEF_ELGA (4 points per cell) SIXX = 10 c + p + 1e6 t, SIYY = -SIXX.

// Executors return `Result<_, Diagnostic>` as the registry requires.
#![allow(clippy::result_large_err)]

use std::path::PathBuf;

use aster::catalog::args::Args;
use aster::commands::{CommandDef, ExecResult};
use aster::concepts::{ConceptData, ConceptType as C};
use aster::diag::Source;
use aster::mesh::{Cell, CellType, Mesh};
use aster::post::table::Cell as TCell;
use aster::result::{EvolNoli, GaussField, NodalField, Step};
use aster::run::driver::parse_and_check;
use aster::study::Study;

mod common;

const INSTS: [f64; 5] = [-1e-5, 0.0, 2.5e-7, 5e-7, 1e-6];

fn dx(t: f64, x: f64) -> f64 {
    1000.0 * t * x
}
fn dy(t: f64, n: usize) -> f64 {
    -227000.0 * t + 0.1 * (n as f64 + 1.0)
}
fn sixx(t: f64, c: usize, p: usize) -> f64 {
    10.0 * c as f64 + p as f64 + 1e6 * t
}

fn mesh() -> Mesh {
    let mut m = Mesh {
        name: "synthetic".into(),
        dim: 2,
        coords: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 1.0, 0.0],
        ],
        cells: vec![
            Cell {
                kind: CellType::Quad4,
                nodes: vec![0, 1, 4, 3],
            },
            Cell {
                kind: CellType::Quad4,
                nodes: vec![1, 2, 5, 4],
            },
        ],
        ..Mesh::default()
    };
    m.node_groups.insert("A".into(), vec![4]);
    m.node_groups.insert("B".into(), vec![0, 1]);
    m.node_groups.insert("O".into(), vec![0]);
    m.cell_groups.insert("C1".into(), vec![0]);
    m.cell_groups.insert("C2".into(), vec![1]);
    m
}

fn result(mesh_name: &str) -> EvolNoli {
    let m = mesh();
    let cmps = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let mut r = EvolNoli {
        mesh: mesh_name.to_string(),
        ..EvolNoli::default()
    };
    for (k, &t) in INSTS.iter().enumerate() {
        let mut depl = NodalField::zeros(cmps(&["DX", "DY"]), 6);
        let mut vite = NodalField::absent(cmps(&["DX", "DY"]), 6);
        for n in 0..6 {
            depl.set(n, 0, dx(t, m.coords[n][0]));
            depl.set(n, 1, dy(t, n));
            if n > 0 {
                vite.set(n, 0, 0.0);
            }
            vite.set(n, 1, -227000.0);
        }
        let mut sief = GaussField {
            components: cmps(&["SIXX", "SIYY"]),
            offsets: vec![0, 8, 16],
            values: Vec::new(),
        };
        for c in 0..2 {
            for p in 0..4 {
                sief.values.push(sixx(t, c, p));
                sief.values.push(-sixx(t, c, p));
            }
        }
        let mut s = Step {
            nume_ordre: k,
            inst: t,
            ..Step::default()
        };
        s.nodal.insert("DEPL".into(), depl);
        s.nodal.insert("VITE".into(), vite);
        s.gauss.insert("SIEF_ELGA".into(), sief);
        r.steps.push(s);
    }
    r
}

fn synth_mail(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    Ok(Some(ConceptData::Mesh(Box::new(mesh()))))
}
fn synth_resu(_s: &mut Study, a: &Args, _r: Option<&str>) -> ExecResult {
    Ok(Some(ConceptData::Result(Box::new(result(
        a.concept("MAILLAGE").unwrap(),
    )))))
}
/// A cham_no with DX = n, DY = -n (n = node index), DZ absent.
fn synth_champ(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    let mut f = NodalField::absent(vec!["DX".into(), "DY".into(), "DZ".into()], 6);
    for n in 0..6 {
        f.set(n, 0, n as f64);
        f.set(n, 1, -(n as f64));
    }
    Ok(Some(ConceptData::Field(Box::new(
        aster::concepts::ChamNo {
            mesh: "MA".into(),
            field: f,
        },
    ))))
}

fn registry() -> Vec<CommandDef> {
    common::synth_registry(&[
        ("SYNTH_MAIL", C::Maillage, synth_mail),
        ("SYNTH_RESU", C::EvolNoli, synth_resu),
        ("SYNTH_CHAMP", C::ChamNo, synth_champ),
    ])
}

const PRELUDE: &str =
    "DEBUT()\nMA = SYNTH_MAIL()\nRESU = SYNTH_RESU(MAILLAGE=MA)\nCH = SYNTH_CHAMP()\n";

const TEXT: common::TextStudies = common::TextStudies {
    prefix: "post_commands",
    prelude: PRELUDE,
    registry,
};

fn out_dir(tag: &str) -> PathBuf {
    TEXT.out_dir(tag)
}

fn run_in(study: &mut Study, body: &str) -> Result<(), String> {
    TEXT.run_in(study, body)
}

fn run(tag: &str, body: &str) -> Study {
    TEXT.run(tag, body)
}

fn run_err(body: &str) -> String {
    TEXT.run_err(body)
}

use common::table;

/// HDF5 opens files without close-on-exec: a child process started while a
/// MED file is open (insta runs `cargo metadata` on its first snapshot)
/// inherits the descriptor and its lock, and reading the file back then
/// fails with "unable to lock file". Snapshots and the MED test take turns.
static NO_CHILD_PROCESS: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn snapshot(name: &str, text: &str) {
    let _guard = NO_CHILD_PROCESS.lock().unwrap_or_else(|e| e.into_inner());
    insta::assert_snapshot!(name, text);
}

/// The automatic title holds the date: replaced for snapshots.
fn undated(text: &str) -> String {
    text.lines()
        .map(|l| {
            if l.starts_with("#ASTER ") || l.starts_with("#TABLE_SDASTER") {
                "#<title with the date>"
            } else {
                l
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn post_releve_t_extracts_every_stored_step_in_aster_columns() {
    let s = run(
        "releve",
        "TAB = POST_RELEVE_T(ACTION=(
             _F(OPERATION='EXTRACTION', INTITULE='DEPL_B', RESULTAT=RESU, NOM_CHAM='DEPL',
                GROUP_NO='B', NOM_CMP=('DX', 'DY')),
             _F(OPERATION='EXTRACTION', INTITULE='VITE_N1', RESULTAT=RESU, NOM_CHAM='VITE',
                NOEUD='N1', TOUT_CMP='OUI', INST=(0., 1.E-6)),))
         IMPR_TABLE(TABLE=TAB)
         IMPR_TABLE(TABLE=TAB, FORMAT='AGRAF', NOM_PARA=('INTITULE', 'NUME_ORDRE', 'DX'),
                    FILTRE=_F(NOM_PARA='NUME_ORDRE', CRIT_COMP='GE', VALE_I=4), UNITE=9)
         FIN()\n",
    );
    let t = table(&s, "TAB");
    assert_eq!(
        t.columns,
        [
            "INTITULE",
            "RESU",
            "NOM_CHAM",
            "NUME_ORDRE",
            "INST",
            "NOEUD",
            "COOR_X",
            "COOR_Y",
            "DX",
            "DY"
        ]
    );
    // 5 steps x 2 nodes, then 2 instants x 1 node.
    assert_eq!(t.n_rows(), 12);
    let m = mesh();
    for (k, &t_k) in INSTS.iter().enumerate() {
        for (j, n) in [0usize, 1].into_iter().enumerate() {
            let r = 2 * k + j;
            assert_eq!(t.cell(r, "NUME_ORDRE"), Some(&TCell::Int(k as i64)));
            assert_eq!(
                t.cell(r, "NOEUD"),
                Some(&TCell::Text(format!("N{}", n + 1)))
            );
            assert_eq!(t.cell(r, "DX"), Some(&TCell::Real(dx(t_k, m.coords[n][0]))));
            assert_eq!(t.cell(r, "DY"), Some(&TCell::Real(dy(t_k, n))));
        }
    }
    // VITE at N1: DX absent there, so its cell is empty; DY = -227000.
    assert_eq!(t.cell(10, "INST"), Some(&TCell::Real(0.0)));
    assert_eq!(t.cell(11, "NUME_ORDRE"), Some(&TCell::Int(4)));
    assert_eq!(t.cell(11, "DX"), None);
    assert_eq!(t.cell(11, "DY"), Some(&TCell::Real(-227000.0)));
    snapshot("impr_table_releve", &undated(&s.resu));
    // AGRAF: the missing DX cells of the VITE rows print as \-.
    snapshot("impr_table_agraf", &undated(&s.unit_text[&9]));
}

#[test]
fn impr_table_options_filter_sort_and_select() {
    let s = run(
        "impr_table",
        "TAB = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='DEPL_B',
                RESULTAT=RESU, NOM_CHAM='DEPL', GROUP_NO='B', NOM_CMP='DY'), TITRE='synthetic')
         IMPR_TABLE(TABLE=TAB, NOM_PARA=('NUME_ORDRE', 'NOEUD', 'DY', 'NOPE'),
                    FILTRE=_F(NOM_PARA='NUME_ORDRE', CRIT_COMP='GE', VALE_I=3),
                    TRI=_F(NOM_PARA='DY', ORDRE='DECROISSANT'), FORMAT_R='F10.4', UNITE=9)
         FIN()\n",
    );
    assert!(s
        .mess
        .contains("<A> <IMPR_TABLE> <TABLE0_7> the parameter 'NOPE'"));
    assert!(s.resu.is_empty(), "nothing tested, nothing in unit 8");
    snapshot("impr_table_options", &s.unit_text[&9]);
}

#[test]
fn test_resu_prints_ok_nook_and_skip_lines_and_counts_them() {
    // DY at N5 (group A) at t = 5e-7: -227000 * 5e-7 + 0.5 = 0.3865.
    let v = dy(5e-7, 4);
    assert!((v - 0.3865).abs() < 1e-12);
    let s = run(
        "test_resu",
        "TEST_RESU(RESU=(
            _F(RESULTAT=RESU, INST=5.E-7, NOM_CHAM='DEPL', NOM_CMP='DY', GROUP_NO='A',
               VALE_CALC=0.3865, REFERENCE='ANALYTIQUE', VALE_REFE=0.3865, PRECISION=1.E-6),
            _F(RESULTAT=RESU, NUME_ORDRE=3, NOM_CHAM='DEPL', NOM_CMP='DY', GROUP_NO='A',
               VALE_CALC=0.3866, LEGENDE='wrong value'),
            _F(RESULTAT=RESU, INST=1.E-6, NOM_CHAM='DEPL', NOM_CMP='DX', GROUP_NO='O',
               VALE_CALC=0.),
            _F(RESULTAT=RESU, INST=1.E-6, NOM_CHAM='DEPL', NOM_CMP='DX', GROUP_NO='O',
               VALE_CALC=0., ORDRE_GRANDEUR=1., CRITERE='ABSOLU'),
            _F(RESULTAT=RESU, INST=-1.E-5, NOM_CHAM='VITE', NOM_CMP='DY', NOEUD='N6'),
            _F(RESULTAT=RESU, INST=1.E-6, NOM_CHAM='SIEF_ELGA', NOM_CMP='SIYY',
               GROUP_MA='C2', POINT=3, VALE_CALC=-13.),
            _F(RESULTAT=RESU, INST=1.E-6, NOM_CHAM='SIEF_ELGA', NOM_CMP='SIXX',
               TYPE_TEST='MAX', VALE_CALC=14.),
            _F(RESULTAT=RESU, NUME_ORDRE=1, NOM_CHAM='DEPL', TYPE_TEST='SOMM_ABS',
               VALE_CALC=2.1),
            _F(RESULTAT=RESU, NUME_ORDRE=1, NOM_CHAM='DEPL', TYPE_TEST='SOMM_ABS',
               GROUP_NO='A', VALE_CALC=2.1),),
          CHAM_NO=_F(CHAM_GD=CH, GROUP_NO='A', NOM_CMP='DY', VALE_CALC=-4.))
         FIN()\n",
    );
    // OK: 0.3865 twice, ABSOLU zero, SIYY(c=1, p=2, 1e-6) = -(10+2+1) = -13,
    // MAX SIXX = 10+3+1 = 14, SOMM_ABS at t=0 = sum 0.1(n+1) = 2.1, CHAM_NO
    // DY(N5) = -4. NOOK: 0.3866. SKIP: VALE_CALC=0 and VALE_CALC absent.
    // With TYPE_TEST, GROUP_NO is ignored with code_aster's alarm: the sum
    // stays the whole field's 2.1.
    assert_eq!(s.tests.ok, 8, "{}", s.resu);
    assert!(s
        .mess
        .contains("<A> <TEST_RESU> <CALCULEL6_96> RESU with TYPE_TEST ignores GROUP_NO"));
    assert_eq!(s.tests.nook, 1);
    assert_eq!(s.tests.skip, 2);
    assert!(s.mess.contains("<A> <TEST_RESU> <TEST0_12>"));
    assert!(s.mess.contains("<A> <TEST_RESU> <TEST0_11>"));
    assert!(s.resu.contains(" ---- DIAGNOSTIC : NOOK_TEST_RESU"));
    snapshot("test_resu_blocks", &s.resu);
}

#[test]
fn test_resu_refuses_what_it_cannot_find() {
    let occ = |body: &str| {
        run_err(&format!(
            "TEST_RESU(RESU=_F(RESULTAT=RESU, NOM_CHAM='DEPL', {body}, VALE_CALC=1.))\n"
        ))
    };
    let e = occ("INST=5.E-7, NOM_CMP='DY', GROUP_NO='B'");
    assert!(e.contains("GROUP_NO B holds 2 nodes (N1, N2)"), "{e}");
    let e = occ("INST=3.E-7, NOM_CMP='DY', GROUP_NO='A'");
    assert!(
        e.contains("INST=3e-7") && e.contains("nearest is 2.5e-7"),
        "{e}"
    );
    assert!(e.contains("TEST_RESU") && e.contains("RESU/INST"), "{e}");
    let e = occ("NUME_ORDRE=7, NOM_CMP='DY', GROUP_NO='A'");
    assert!(e.contains("NUME_ORDRE 7 is not stored"), "{e}");
    let e = occ("INST=0., NOM_CMP='DZ', GROUP_NO='A'");
    assert!(
        e.contains("no component DZ") && e.contains("RESU/NOM_CMP"),
        "{e}"
    );
    let e = run_err(
        "TEST_RESU(RESU=_F(RESULTAT=RESU, NOM_CHAM='VITE', INST=0., NOM_CMP='DX', \
         GROUP_NO='O', VALE_CALC=0.))\n",
    );
    assert!(
        e.contains("component DX of VITE is absent at node N1"),
        "{e}"
    );
    let e = run_err(
        "TEST_RESU(RESU=_F(RESULTAT=RESU, NOM_CHAM='DEPL', INST=0., NOM_CMP='DX', \
         GROUP_NO='NOPE', VALE_CALC=0.))\n",
    );
    assert!(e.contains("no node group 'NOPE'"), "{e}");
    let e = run_err(
        "TEST_RESU(RESU=_F(RESULTAT=RESU, NOM_CHAM='SIEF_ELGA', INST=0., NOM_CMP='SIXX', \
         GROUP_MA='C1', POINT=5, VALE_CALC=0.))\n",
    );
    assert!(e.contains("POINT must be in 1..4"), "{e}");
}

#[test]
fn test_table_filters_and_aggregates() {
    let s = run(
        "test_table",
        "TAB = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='DEPL_B',
                RESULTAT=RESU, NOM_CHAM='DEPL', GROUP_NO='B', NOM_CMP='DY'))
         TEST_TABLE(TABLE=TAB, NOM_PARA='DY', VALE_CALC=-0.0135,
                    FILTRE=(_F(NOM_PARA='NUME_ORDRE', VALE_I=3),
                            _F(NOM_PARA='NOEUD', VALE_K='N1')))
         TEST_TABLE(TABLE=TAB, NOM_PARA='DY', FILTRE=_F(NOM_PARA='INST', VALE=2.5E-7),
                    TYPE_TEST='SOMM', VALE_CALC=0.18650000000000003,
                    REFERENCE='ANALYTIQUE', VALE_REFE=0.1865)
         TEST_TABLE(TABLE=TAB, NOM_PARA='NUME_ORDRE', TYPE_TEST='MAX', VALE_CALC_I=4)
         TEST_TABLE(TABLE=TAB, NOM_PARA='NOEUD', FILTRE=_F(NOM_PARA='DY', CRIT_COMP='MAXI'),
                    VALE_CALC_K='N2')
         FIN()\n",
    );
    // t = 5e-7 at N1: -0.1135 + 0.1 = -0.0135.
    assert!((dy(5e-7, 0) + 0.0135).abs() < 1e-12);
    // t = 2.5e-7: DY(N1) + DY(N2) = 2 * (-0.05675) + 0.1 + 0.2 = 0.1865.
    let sum = dy(2.5e-7, 0) + dy(2.5e-7, 1);
    assert!((sum - 0.1865).abs() < 1e-12);
    assert_eq!(s.tests.ok, 5, "{}", s.resu);
    assert_eq!(s.tests.nook, 0);
    snapshot("test_table_blocks", &s.resu);

    let e = run_err(
        "TAB = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='DEPL_B',
                RESULTAT=RESU, NOM_CHAM='DEPL', GROUP_NO='B', NOM_CMP='DY'))
         TEST_TABLE(TABLE=TAB, NOM_PARA='DY', VALE_CALC=0.0865,
                    FILTRE=_F(NOM_PARA='NUME_ORDRE', VALE_I=3))\n",
    );
    assert!(e.contains("2 rows are left after filtering"), "{e}");

    // An integer column tested against a real VALE_REFE: the error is on
    // VALE_REFE and asks for VALE_REFE_I (it was on VALE_CALC, absent here);
    // a real VALE_CALC on it stays an error on VALE_CALC.
    let table = "TAB = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='DEPL_B',
                RESULTAT=RESU, NOM_CHAM='DEPL', GROUP_NO='B', NOM_CMP='DY'))\n";
    let e = run_err(&format!(
        "{table}TEST_TABLE(TABLE=TAB, NOM_PARA='NUME_ORDRE', TYPE_TEST='MAX', \
         REFERENCE='ANALYTIQUE', VALE_REFE=4., PRECISION=1.E-12)\n"
    ));
    assert!(e.contains("TEST_TABLE/VALE_REFE:"), "{e}");
    assert!(e.contains("give it as VALE_REFE_I"), "{e}");
    assert!(!e.contains("VALE_CALC"), "{e}");
    let e = run_err(&format!(
        "{table}TEST_TABLE(TABLE=TAB, NOM_PARA='NUME_ORDRE', TYPE_TEST='MAX', VALE_CALC=4., \
         REFERENCE='ANALYTIQUE', VALE_REFE_I=4)\n"
    ));
    assert!(e.contains("TEST_TABLE/VALE_CALC:"), "{e}");
    assert!(e.contains("give it as VALE_CALC_I"), "{e}");
}

#[test]
fn recu_fonction_and_impr_fonction() {
    let s = run(
        "fonction",
        "F = RECU_FONCTION(RESULTAT=RESU, NOM_CHAM='DEPL', NOM_CMP='DY', GROUP_NO='B')
         G = RECU_FONCTION(RESULTAT=RESU, NOM_CHAM='SIEF_ELGA', NOM_CMP='SIXX', GROUP_MA='C2',
                           POINT=2, INST=(0., 1.E-6))
         IMPR_FONCTION(FORMAT='XMGRACE', COURBE=(_F(FONCTION=F), _F(FONCTION=G, LEGENDE='sixx')))
         IMPR_FONCTION(COURBE=_F(FONCTION=F))
         FIN()\n",
    );
    let Some(ConceptData::Function(f)) = s.concepts.data("F") else {
        panic!("F is not a function")
    };
    assert_eq!(f.para, "INST");
    assert_eq!(f.resu, "DY");
    assert_eq!(f.abscissas, INSTS);
    let expected: Vec<f64> = INSTS.iter().map(|&t| dy(t, 0)).collect();
    assert_eq!(f.ordinates, expected);
    assert_eq!(f.prol(), "EE");
    assert!(s
        .mess
        .contains("<A> <RECU_FONCTION> GROUP_NO holds 2 nodes: the first one, N1, is used"));
    let Some(ConceptData::Function(g)) = s.concepts.data("G") else {
        panic!("G is not a function")
    };
    assert_eq!(g.ordinates, vec![sixx(0.0, 1, 1), sixx(1e-6, 1, 1)]);
    let agr = &s.unit_text[&29];
    assert!(agr.starts_with("# Grace project file") || agr.contains("@version 50100"));
    assert!(agr.contains("@    legend \"sixx\"") || agr.contains("legend \"sixx\""));
    // Data lines of F in %.8g: t = 2.5e-07 gives DY = 0.04325.
    assert!(agr.contains("2.5e-07 0.04325\n"), "{agr}");
    snapshot("impr_fonction_tableau", &s.resu);
}

#[test]
fn impr_resu_med_round_trip() {
    let _guard = NO_CHILD_PROCESS.lock().unwrap_or_else(|e| e.into_inner());
    let dir = out_dir("med");
    let path = dir.join("resu.med");
    let _ = std::fs::remove_file(&path);
    let mut s = Study {
        out_dir: dir.clone(),
        ..Study::default()
    };
    s.units.map.insert(80, path.clone());
    run_in(
        &mut s,
        "IMPR_RESU(FORMAT='MED', RESU=(_F(RESULTAT=RESU, NOM_CHAM=('DEPL', 'SIEF_ELGA'),
                                          NUME_ORDRE=(1, 3)),
                                       _F(CHAM_GD=CH)))
         FIN()\n",
    )
    .unwrap();
    let nodal = aster::medio::read_nodal_fields(&path, None).unwrap();
    let names: Vec<&str> = nodal.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["CH", "RESU____DEPL"]);
    let depl = &nodal[1];
    assert_eq!(depl.components, ["DX", "DY"]);
    assert_eq!(depl.steps.len(), 2);
    let m = mesh();
    for (st, k) in depl.steps.iter().zip([1usize, 3]) {
        assert_eq!(st.numdt, k as i32);
        assert_eq!(st.time, INSTS[k]);
        for n in 0..6 {
            assert_eq!(st.values[2 * n], dx(INSTS[k], m.coords[n][0]));
            assert_eq!(st.values[2 * n + 1], dy(INSTS[k], n));
        }
    }
    // The cham_no: DZ absent everywhere comes back as NaN.
    assert_eq!(nodal[0].steps[0].values[3 * 5], 5.0);
    assert!(nodal[0].steps[0].values[3 * 5 + 2].is_nan());
    let cells = aster::medio::read_elem_fields(&path, None).unwrap();
    assert_eq!(cells.len(), 1);
    assert_eq!(cells[0].name, "RESU____SIEF_ELGA");
    // Mean over p = 0..3 of 10 c + p + 1e6 t = 10 c + 1.5 + 1e6 t.
    let st = &cells[0].steps[1];
    assert_eq!(st.time, INSTS[3]);
    for c in 0..2 {
        let mean = 10.0 * c as f64 + 1.5 + 1e6 * INSTS[3];
        assert!((st.values[2 * c] - mean).abs() < 1e-12);
        assert!((st.values[2 * c + 1] + mean).abs() < 1e-12);
    }
    let mesh_back = aster::medio::read_mesh(&path, None).unwrap();
    assert_eq!(mesh_back.name, "MA");
    assert_eq!(mesh_back.coords, m.coords);
    assert!(s
        .mess
        .contains("the mean over the Gauss points of each cell"));

    // A second IMPR_RESU on a unit adds its fields to the file, as
    // code_aster does: here the steps of DEPL written in two calls and the
    // cham_no, read back as one write of all of them.
    let twice = dir.join("twice.med");
    let _ = std::fs::remove_file(&twice);
    s.units.map.insert(81, twice.clone());
    run_in(
        &mut s,
        "IMPR_RESU(FORMAT='MED', UNITE=81, RESU=_F(RESULTAT=RESU, NOM_CHAM='DEPL', NUME_ORDRE=3))
         IMPR_RESU(FORMAT='MED', UNITE=81, RESU=(_F(CHAM_GD=CH),
                   _F(RESULTAT=RESU, NOM_CHAM='DEPL', NUME_ORDRE=1)))\n",
    )
    .unwrap();
    // Compared as printed: the absent DZ of CH is NaN, unequal to itself.
    let back = aster::medio::read_nodal_fields(&twice, None).unwrap();
    assert_eq!(format!("{back:?}"), format!("{nodal:?}"));
    assert!(s
        .mess
        .contains("2 field(s) added to the MED file of unit 81"));
    // Part of a mesh: the fields are written whole, with an alarm (MED
    // profiles are not built); the group must still exist.
    let part = dir.join("part.med");
    let _ = std::fs::remove_file(&part);
    s.units.map.insert(82, part.clone());
    run_in(
        &mut s,
        "IMPR_RESU(FORMAT='MED', UNITE=82, RESU=_F(RESULTAT=RESU, NOM_CHAM='DEPL',
                                                   GROUP_NO='A', NUME_ORDRE=(1, 3)))\n",
    )
    .unwrap();
    let whole = aster::medio::read_nodal_fields(&part, None).unwrap();
    assert_eq!(whole.len(), 1);
    assert_eq!(
        whole[0].steps, depl.steps,
        "the whole field, as without GROUP_NO"
    );
    assert!(
        s.mess
            .contains("GROUP_NO=A: the fields are written on the whole mesh"),
        "{}",
        s.mess
    );
    let e = run_err("IMPR_RESU(FORMAT='MED', RESU=_F(RESULTAT=RESU, GROUP_NO='NOPE'))\n");
    assert!(
        e.contains("IMPR_RESU/RESU/GROUP_NO") && e.contains("NOPE"),
        "{e}"
    );
}

#[test]
fn impr_resu_resultat_listing() {
    let s = run(
        "listing",
        "IMPR_RESU(FORMAT='RESULTAT', RESU=_F(RESULTAT=RESU, NOM_CHAM=('VITE', 'SIEF_ELGA'),
                   NUME_ORDRE=2, FORMAT_R='1PE12.5'))
         IMPR_RESU(FORMAT='RESULTAT', RESU=_F(CHAM_GD=CH, GROUP_NO='B'))\n",
    );
    snapshot("impr_resu_resultat", &s.resu);
}

/// The data lines of a listing: (entity, point or node label, values),
/// the block titles and the header lines left out.
fn listing_rows(text: &str) -> Vec<(String, String, Vec<f64>)> {
    text.lines()
        .filter(|l| l.starts_with(" M") || l.starts_with(" N"))
        .filter(|l| {
            !l.starts_with(" MAILLE") && !l.starts_with(" NOEUD") && !l.starts_with(" NUMERO")
        })
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            let vals = |from: usize| {
                w[from..]
                    .iter()
                    .map(|v| v.parse().unwrap_or(f64::NAN))
                    .collect()
            };
            if w[0].starts_with('M') {
                (w[0].to_string(), w[1].to_string(), vals(2))
            } else {
                (w[0].to_string(), String::new(), vals(1))
            }
        })
        .collect()
}

/// FORMAT='RESULTAT' restricts the listing as code_aster's irdepl/irchml:
/// a Gauss field to the cells of GROUP_MA/MAILLE, or to the cells holding
/// a node of GROUP_NO/NOEUD; a nodal field to the nodes of GROUP_NO/NOEUD
/// and of the cells of GROUP_MA; NOM_CMP picks Gauss components too. The
/// values are checked against the closed form of the synthetic result
/// (SIXX = 10 c + p + 1e6 t, DX = 1000 t x, DY = -227000 t + 0.1 (n + 1)).
#[test]
fn impr_resu_resultat_honours_the_selection() {
    let t = INSTS[2];
    let listing = |tag: &str, resu: &str| {
        run(
            tag,
            &format!(
                "IMPR_RESU(FORMAT='RESULTAT', RESU=_F(RESULTAT=RESU, NUME_ORDRE=2, {resu}))\n"
            ),
        )
        .resu
    };
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + b.abs());
    // One cell: its 4 points, SIXX and SIYY exact to the printed 15 digits.
    let text = listing("sel_c2", "NOM_CHAM='SIEF_ELGA', GROUP_MA='C2'");
    let rows = listing_rows(&text);
    assert_eq!(rows.len(), 4, "{text}");
    for (p, (cell, point, v)) in rows.iter().enumerate() {
        assert_eq!(
            (cell.as_str(), point.as_str()),
            ("M2", &*(p + 1).to_string())
        );
        assert!(
            close(v[0], sixx(t, 1, p)) && close(v[1], -sixx(t, 1, p)),
            "{text}"
        );
    }
    // MAILLE too; TOUT='OUI' lists everything.
    assert_eq!(
        listing_rows(&listing("sel_m1", "NOM_CHAM='SIEF_ELGA', MAILLE='M1'")).len(),
        4
    );
    assert_eq!(
        listing_rows(&listing("sel_tout", "NOM_CHAM='SIEF_ELGA', TOUT='OUI'")).len(),
        8
    );
    // Nodes only: the cells that hold them (N1 is in M1 only, N5 in both).
    let rows = listing_rows(&listing("sel_o", "NOM_CHAM='SIEF_ELGA', GROUP_NO='O'"));
    assert!(
        rows.len() == 4 && rows.iter().all(|r| r.0 == "M1"),
        "{rows:?}"
    );
    assert_eq!(
        listing_rows(&listing("sel_a", "NOM_CHAM='SIEF_ELGA', GROUP_NO='A'")).len(),
        8
    );
    // NOM_CMP on a Gauss field: SIYY alone.
    let text = listing(
        "sel_cmp",
        "NOM_CHAM='SIEF_ELGA', GROUP_MA='C1', NOM_CMP='SIYY'",
    );
    assert!(text.contains("SIYY") && !text.contains("SIXX"), "{text}");
    let rows = listing_rows(&text);
    assert_eq!(rows.len(), 4);
    for (p, r) in rows.iter().enumerate() {
        assert!(r.2.len() == 1 && close(r.2[0], -sixx(t, 0, p)), "{text}");
    }
    // A nodal field on GROUP_MA: the 4 nodes of M1 (N1 N2 N5 N4) in
    // increasing order, after the nodes of GROUP_NO in their own order.
    let m = mesh();
    let text = listing("sel_depl", "NOM_CHAM='DEPL', GROUP_MA='C1'");
    let rows = listing_rows(&text);
    let names: Vec<&str> = rows.iter().map(|r| r.0.as_str()).collect();
    assert_eq!(names, ["N1", "N2", "N4", "N5"], "{text}");
    for (r, n) in rows.iter().zip([0usize, 1, 3, 4]) {
        assert!(
            close(r.2[0], dx(t, m.coords[n][0])) && close(r.2[1], dy(t, n)),
            "{text}"
        );
    }
    let rows = listing_rows(&listing(
        "sel_depl2",
        "NOM_CHAM='DEPL', GROUP_NO='A', GROUP_MA='C2'",
    ));
    let names: Vec<&str> = rows.iter().map(|r| r.0.as_str()).collect();
    assert_eq!(names, ["N5", "N2", "N3", "N6"]);
    // A cham_no on a cell group.
    let s = run(
        "sel_ch",
        "IMPR_RESU(FORMAT='RESULTAT', RESU=_F(CHAM_GD=CH, GROUP_MA='C2'))\n",
    );
    let names: Vec<String> = listing_rows(&s.resu).into_iter().map(|r| r.0).collect();
    assert_eq!(names, ["N2", "N3", "N5", "N6"]);

    // What the listing does not do is refused, located.
    for (resu, expected) in [
        (
            "VALE_MAX='OUI'",
            "not implemented yet: IMPR_RESU/RESU/VALE_MAX",
        ),
        (
            "BORNE_INF=0.",
            "not implemented yet: IMPR_RESU/RESU/BORNE_INF",
        ),
        (
            "IMPR_COOR='OUI'",
            "not implemented yet: IMPR_RESU/RESU/IMPR_COOR",
        ),
        ("NOM_CHAM_MED='X'", "IMPR_RESU/RESU/NOM_CHAM_MED"),
        ("GROUP_MA='C3'", "'C3'"),
    ] {
        let e = run_err(&format!(
            "IMPR_RESU(FORMAT='RESULTAT', RESU=_F(RESULTAT=RESU, NOM_CHAM='SIEF_ELGA', {resu}))\n"
        ));
        assert!(
            e.contains(expected) && e.contains("t.comm:5:"),
            "{resu}: {e}"
        );
    }
    let e = run_err("IMPR_RESU(FORMAT='RESULTAT', RESU=_F(MAILLAGE=MA, GROUP_MA='C1'))\n");
    assert!(
        e.contains("IMPR_RESU/RESU/GROUP_MA") && e.contains("MAILLAGE alone"),
        "{e}"
    );
}

#[test]
fn post_releve_t_refuses_other_operations() {
    // MOYENNE is built on nodal fields (tests/post_releve_moyenne.rs),
    // not on Gauss-point ones.
    let e = run_err(
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='MOYENNE', INTITULE='M', RESULTAT=RESU,
                NOM_CHAM='SIEF_ELGA', GROUP_NO='B', NOM_CMP='SIXX'))\n",
    );
    assert!(
        e.contains("not implemented yet: POST_RELEVE_T/ACTION/NOM_CHAM"),
        "{e}"
    );
    let e = run_err(
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='M', RESULTAT=RESU,
                NOM_CHAM='DEPL', GROUP_NO='B', RESULTANTE='DY', MOMENT='DRZ', POINT=(0., 0.)))\n",
    );
    assert!(
        e.contains("not implemented yet: POST_RELEVE_T/ACTION/MOMENT"),
        "{e}"
    );
    // The frames not built (LOCAL, POLAIRE; UTILISATEUR and CYLINDRIQUE
    // are, tests/post_releve_repere.rs) are refused on REPERE, when the
    // file is checked, at its line: they passed `aster check` and
    // stopped only when POST_RELEVE_T ran.
    for (repere, extra) in [
        ("LOCAL", "VECT_Y=(0., 1., 0.)"),
        ("POLAIRE", "VECT_Y=(0., 1., 0.)"),
    ] {
        let body = format!(
            "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='M', RESULTAT=RESU,\n\
             NOM_CHAM='DEPL', GROUP_NO='B', NOM_CMP='DY', REPERE='{repere}',\n\
             {extra}))\n"
        );
        let src = Source::new("t.comm", format!("{PRELUDE}{body}"));
        let mut msgs = String::new();
        assert!(
            parse_and_check(&src, &registry(), &mut msgs).is_none(),
            "{repere} passed the check"
        );
        assert!(
            msgs.contains(&format!(
                "not implemented yet: POST_RELEVE_T/ACTION/REPERE='{repere}'"
            )) && msgs.contains("t.comm:6:"),
            "{repere}: {msgs}"
        );
    }
    // EXTRACTION by GROUP_MA alone: code_aster's catalogue refuses it
    // (AU_MOINS_UN('GROUP_NO', 'NOEUD'), in its 2012 and its current
    // post_releve_t.py alike), for nodal fields (DEPL, REAC_NODA,
    // CONT_NOEU: probe s7a d06) as for Gauss-point ones. The error says
    // so at GROUP_MA and gives the DEFI_GROUP that makes the node group
    // of the cells' nodes; it said "not implemented yet" and advised
    // extracting "a nodal field on the cells' nodes" of a nodal field.
    for (field, cmp) in [
        ("DEPL", "NOM_CMP='DY'"),
        ("DEPL", "RESULTANTE='DY'"),
        ("SIEF_ELGA", "NOM_CMP='SIYY'"),
    ] {
        let e = run_err(&format!(
            "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='M', RESULTAT=RESU,\n\
             NOM_CHAM='{field}', GROUP_MA='C1', {cmp}))\n"
        ));
        assert!(
            e.contains("POST_RELEVE_T/ACTION/GROUP_MA")
                && e.contains("AU_MOINS_UN('GROUP_NO', 'NOEUD') refuses GROUP_MA alone")
                && e.contains("CREA_GROUP_NO=_F(GROUP_MA='C1')")
                && e.contains("GROUP_NO='C1'")
                && !e.contains("not implemented")
                && e.contains("t.comm:6:"),
            "{field} {cmp}: {e}"
        );
    }
    // The advised way runs: the nodes of C1 as a node group.
    let s = run(
        "relevet_cells_nodes",
        "MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(GROUP_MA='C1'))\n\
         T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='M', RESULTAT=RESU,\n\
         NOM_CHAM='DEPL', GROUP_NO='C1', NOM_CMP='DY', NUME_ORDRE=0))\n",
    );
    let Some(ConceptData::Mesh(m)) = s.concepts.data("MA") else {
        panic!("no mesh");
    };
    let mut nodes: Vec<usize> = m.cell_groups["C1"]
        .iter()
        .flat_map(|&c| m.cells[c].nodes.clone())
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    assert_eq!(table(&s, "T").n_rows(), nodes.len());
}

/// EXTREMA and MOYENNE_ARITH: a cell group the mesh lacks is named with
/// the closest existing one, two operations at once are refused naming
/// the ones built, a component absent at every selected node is an error
/// on NOM_CMP rather than a row of sentinels; the file position is shown.
#[test]
fn post_releve_t_extrema_bad_input_is_located() {
    let e = run_err(
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTREMA', INTITULE='M', RESULTAT=RESU,
                NOM_CHAM='DEPL', GROUP_MA='C3', NOM_CMP='DY'))\n",
    );
    assert!(e.contains("POST_RELEVE_T/ACTION/GROUP_MA"), "{e}");
    assert!(e.contains("'C3'") && e.contains("t.comm:6:"), "{e}");
    let e = run_err(
        "T = POST_RELEVE_T(ACTION=_F(OPERATION=('EXTREMA', 'MOYENNE_ARITH'), INTITULE='M',
                RESULTAT=RESU, NOM_CHAM='DEPL', GROUP_NO='B', NOM_CMP='DY'))\n",
    );
    assert!(
        e.contains("not implemented yet: POST_RELEVE_T/ACTION/OPERATION")
            && e.contains("EXTRACTION, MOYENNE, EXTREMA and MOYENNE_ARITH, one at a time"),
        "{e}"
    );
    for op in ["EXTREMA", "MOYENNE_ARITH"] {
        let e = run_err(&format!(
            "T = POST_RELEVE_T(ACTION=_F(OPERATION='{op}', INTITULE='M', CHAM_GD=CH,
                GROUP_NO='B', NOM_CMP='DZ'))\n"
        ));
        assert!(e.contains("POST_RELEVE_T/ACTION/NOM_CMP"), "{e}");
        assert!(e.contains(&format!("{op} of CH: no value of DZ")), "{e}");
    }
}

/// RESULTANTE: one row per stored step, each component summed over the
/// nodes of GROUP_NO and NOEUD (a node named twice counts once), in a
/// column named after it; a component absent at a node adds nothing.
#[test]
fn post_releve_t_resultante_sums_over_the_nodes() {
    let s = run(
        "resultante",
        "TAB = POST_RELEVE_T(ACTION=(
             _F(OPERATION='EXTRACTION', INTITULE='DEPL_B', RESULTAT=RESU, NOM_CHAM='DEPL',
                GROUP_NO='B', NOEUD=('N3', 'N1'), RESULTANTE=('DX', 'DY')),
             _F(OPERATION='EXTRACTION', INTITULE='VITE', RESULTAT=RESU, NOM_CHAM='VITE',
                NOEUD=('N1', 'N2'), RESULTANTE='DX', INST=0.),))
         FIN()\n",
    );
    let t = table(&s, "TAB");
    assert_eq!(
        t.columns,
        [
            "INTITULE",
            "RESU",
            "NOM_CHAM",
            "NUME_ORDRE",
            "INST",
            "DX",
            "DY"
        ]
    );
    assert_eq!(t.n_rows(), INSTS.len() + 1);
    let m = mesh();
    for (k, &t_k) in INSTS.iter().enumerate() {
        let nodes = [0usize, 1, 2];
        let sx: f64 = nodes.iter().map(|&n| dx(t_k, m.coords[n][0])).sum();
        let sy: f64 = nodes.iter().map(|&n| dy(t_k, n)).sum();
        let (TCell::Real(gx), TCell::Real(gy)) =
            (t.cell(k, "DX").unwrap(), t.cell(k, "DY").unwrap())
        else {
            panic!("real cells expected");
        };
        assert!((gx - sx).abs() <= 1e-12 * sx.abs().max(1.0), "{gx} {sx}");
        assert!((gy - sy).abs() <= 1e-12 * sy.abs().max(1.0), "{gy} {sy}");
    }
    // VITE DX is absent at N1 and 0 at N2.
    assert_eq!(t.cell(INSTS.len(), "DX"), Some(&TCell::Real(0.0)));
    assert_eq!(t.cell(INSTS.len(), "DY"), None);
}
