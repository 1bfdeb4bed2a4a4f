//! POST_RELEVE_T OPERATION='EXTRACTION' of fields by element at nodes
//! (SIEF_ELNO, EPSI_ELNO of CALC_CHAMP) on real static studies whose
//! fields are known in closed form at every node of every cell.
//!
//! code_aster (bibfor/postrele: `rvouex`, `rvpste`, `rveche`/`rvechn`,
//! `tremno`, `rvaffe`, `rvtec0`/`rvtecn`): the cells read at a node of
//! GROUP_NO/NOEUD are the cells of the mesh containing it that hold
//! values of the field, in increasing number, restricted to
//! GROUP_MA/MAILLE when given; MOYE_NOEUD='OUI' (default) gives one row
//! per node with the mean of those cells' values, MOYE_NOEUD='NON' one
//! row per (node, cell), node-major, with the column MAILLE right after
//! NOEUD and before COOR_X.
//!
//! The studies: a bar of two cells along x, [0, 1] of E1 = 1000 and
//! [1, 3] of E2 = 2000, NU = 0, held at x = 0 (DX, and DY/DZ on that face:
//! no lateral stress since NU = 0) and pulled by DX = U = 0.01 at x = 3.
//! In series the stress is uniform, SIXX = U / (L1/E1 + L2/E2) = 5, and
//! the strain differs between the cells, EPXX = 5/E1 = 0.005 in M1 and
//! 5/E2 = 0.0025 in M2; both are exact in the linear cells. The nodes of
//! the interface x = 1 belong to both cells: with MOYE_NOEUD='NON' they
//! give a row per cell, EPXX 0.005 (M1) and 0.0025 (M2); by default the
//! mean 0.00375.

use std::collections::HashMap;

use aster::mesh::{CellType, Mesh};

mod common;

const SIG: f64 = 5.0;
const EPS1: f64 = 0.005;
const EPS2: f64 = 0.0025;

/// 2D: N1 (0,0), N2 (1,0), N3 (3,0), N4 (0,1), N5 (1,1), N6 (3,1);
/// M1 = SEG2 N3 N6 (DROITE_M: a skin cell, no stress there),
/// M2 = QUAD4 N1 N2 N5 N4 (MAT1), M3 = QUAD4 N2 N3 N6 N5 (MAT2).
fn mesh_2d() -> Mesh {
    let coords = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [3.0, 1.0, 0.0],
    ];
    let mut m = Mesh {
        name: "BARRE2D".into(),
        dim: 2,
        coords,
        ..Mesh::default()
    };
    // MED stores (and aster reads back) the cells type by type, SEG2
    // before QUAD4: added in that order, the names are M1, M2, M3 here too.
    common::add_cell(&mut m, "DROITE_M", CellType::Seg2, vec![2, 5]);
    common::add_cell(&mut m, "MAT1", CellType::Quad4, vec![0, 1, 4, 3]);
    common::add_cell(&mut m, "MAT2", CellType::Quad4, vec![1, 2, 5, 4]);
    m.node_groups.insert("GAUCHE".into(), vec![0, 3]);
    m.node_groups.insert("INTER".into(), vec![1, 4]);
    m.node_groups.insert("DROITE".into(), vec![2, 5]);
    m
}

/// 3D: the same bar 1 unit deep: nodes N1..N6 at z = 0 as in 2D, N7..N12
/// the same at z = 1; M1 = HEXA8 (x in [0, 1], MAT1), M2 = HEXA8 (x in
/// [1, 3], MAT2).
fn mesh_3d() -> Mesh {
    let mut coords = Vec::new();
    for z in [0.0, 1.0] {
        for y in [0.0, 1.0] {
            for x in [0.0, 1.0, 3.0] {
                coords.push([x, y, z]);
            }
        }
    }
    let mut m = Mesh {
        name: "BARRE3D".into(),
        dim: 3,
        coords,
        ..Mesh::default()
    };
    // node (i, j, k) = i + 3 j + 6 k; the vertices in the order of the
    // reference HEXA8 (xi, eta, zeta in {-1, 1})
    let a = |x: f64| usize::from(x > 0.0);
    let hexa = |i: usize| -> Vec<usize> {
        aster::mesh::shape::reference_nodes(CellType::Hexa8)
            .iter()
            .map(|x| i + a(x[0]) + 3 * a(x[1]) + 6 * a(x[2]))
            .collect()
    };
    common::add_cell(&mut m, "MAT1", CellType::Hexa8, hexa(0));
    common::add_cell(&mut m, "MAT2", CellType::Hexa8, hexa(1));
    m.node_groups.insert("GAUCHE".into(), vec![0, 3, 6, 9]);
    m.node_groups.insert("INTER".into(), vec![1, 4, 7, 10]);
    m.node_groups.insert("DROITE".into(), vec![2, 5, 8, 11]);
    m
}

/// The study up to CALC_CHAMP (RES holds SIEF_ELNO and EPSI_ELNO at
/// INST 1), then `post`.
fn study(dim: usize, post: &str) -> String {
    let (modelisation, fix, pull) = if dim == 2 {
        ("D_PLAN", "DX=0., DY=0.", "DX=0.01")
    } else {
        ("3D", "DX=0., DY=0., DZ=0.", "DX=0.01")
    };
    format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='{modelisation}'))\n\
         MAT1 = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.))\n\
         MAT2 = DEFI_MATERIAU(ELAS=_F(E=2000., NU=0.))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=(_F(GROUP_MA='MAT1', MATER=MAT1), _F(GROUP_MA='MAT2', MATER=MAT2)))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='GAUCHE', {fix}), _F(GROUP_NO='DROITE', {pull})))\n\
         LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=1))\n\
         RES = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH), \
         COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI), \
         CONVERGENCE=_F(RESI_GLOB_RELA=1.E-10))\n\
         RES = CALC_CHAMP(reuse=RES, RESULTAT=RES, CONTRAINTE='SIEF_ELNO', DEFORMATION='EPSI_ELNO')\n\
         {post}\n\
         FIN()\n"
    )
}

fn run(tag: &str, mesh: &Mesh, comm: &str) -> String {
    let (dir, med) = common::scratch_mesh(tag, mesh);
    let (run, resu) = common::run_generated(&dir, tag, comm, &med);
    common::assert_all_ok(&run, &format!("{tag}.resu"));
    resu
}

/// The column names of table `name` as IMPR_TABLE printed them, in order.
fn header(resu: &str, name: &str) -> Vec<String> {
    let tag = format!("CONCEPT {name} ");
    let mut lines = resu.lines();
    lines
        .by_ref()
        .find(|l| l.starts_with('#') && l.contains(&tag))
        .unwrap_or_else(|| panic!("no table {name} printed"));
    lines
        .find(|l| !l.starts_with('#'))
        .unwrap()
        .split_whitespace()
        .map(String::from)
        .collect()
}

fn analytic_oks(resu: &str) -> usize {
    resu.lines()
        .filter(|l| l.starts_with(" OK ") && l.contains("ANALYTIQUE"))
        .count()
}

fn num(row: &HashMap<String, String>, k: &str) -> f64 {
    row[k]
        .parse()
        .unwrap_or_else(|_| panic!("{k} = {} is not a number", row[k]))
}

/// One TEST_TABLE on the row of INTITULE `it`, node `no` (and cell `ma`
/// when given), column `para`, against `refe` (hand value): the
/// extrapolation of a field constant in each cell is exact to round-off,
/// hence PRECISION 1e-9.
fn check(table: &str, it: &str, no: &str, ma: Option<&str>, para: &str, refe: f64) -> String {
    let maille = ma
        .map(|m| format!(", _F(NOM_PARA='MAILLE', VALE_K='{m}')"))
        .unwrap_or_default();
    format!(
        "TEST_TABLE(TABLE={table}, NOM_PARA='{para}', \
         FILTRE=(_F(NOM_PARA='INTITULE', VALE_K='{it}'), _F(NOM_PARA='NOEUD', VALE_K='{no}'){maille}), \
         VALE_CALC={refe:e}, REFERENCE='ANALYTIQUE', VALE_REFE={refe:e}, PRECISION=1.E-9)\n"
    )
}

const ACTIONS: &str = "T = POST_RELEVE_T(ACTION=(\n\
    _F(INTITULE='SIG', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', INST=1., GROUP_NO='INTER', \
       NOM_CMP=('SIXX', 'SIYY'), MOYE_NOEUD='NON', OPERATION='EXTRACTION'),\n\
    _F(INTITULE='EPS', RESULTAT=RES, NOM_CHAM='EPSI_ELNO', INST=1., GROUP_NO='INTER', \
       NOM_CMP=('EPXX', 'EPYY'), MOYE_NOEUD='NON', OPERATION='EXTRACTION'),\n\
    _F(INTITULE='EPS_MOY', RESULTAT=RES, NOM_CHAM='EPSI_ELNO', INST=1., GROUP_NO='INTER', \
       NOM_CMP='EPXX', OPERATION='EXTRACTION'),\n\
    _F(INTITULE='EPS_M2', RESULTAT=RES, NOM_CHAM='EPSI_ELNO', INST=1., GROUP_NO='INTER', \
       GROUP_MA='MAT2', NOM_CMP='EPXX', OPERATION='EXTRACTION'),\n\
    _F(INTITULE='BORD', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', INST=1., GROUP_NO='DROITE', \
       NOM_CMP='SIXX', MOYE_NOEUD='NON', OPERATION='EXTRACTION'),\n\
    ))\n\
IMPR_TABLE(TABLE=T, FORMAT_R='E24.16')\n";

/// The rows of INTITULE `it`, as (NOEUD, MAILLE or "-") pairs in order.
fn places(rows: &[HashMap<String, String>], it: &str) -> Vec<(String, String)> {
    rows.iter()
        .filter(|r| r["INTITULE"] == it)
        .map(|r| {
            (
                r["NOEUD"].clone(),
                r.get("MAILLE").cloned().unwrap_or_default(),
            )
        })
        .collect()
}

fn pairs(v: &[(&str, &str)]) -> Vec<(String, String)> {
    v.iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

#[test]
fn elno_rows_per_cell_and_means_2d() {
    let mut post = ACTIONS.to_string();
    for no in ["N2", "N5"] {
        for (ma, eps) in [("M2", EPS1), ("M3", EPS2)] {
            post += &check("T", "SIG", no, Some(ma), "SIXX", SIG);
            post += &check("T", "EPS", no, Some(ma), "EPXX", eps);
        }
        post += &check("T", "EPS_MOY", no, None, "EPXX", (EPS1 + EPS2) / 2.0);
        post += &check("T", "EPS_M2", no, None, "EPXX", EPS2);
    }
    post += &check("T", "BORD", "N3", Some("M3"), "SIXX", SIG);
    // GROUP_NO and NOEUD together: code_aster's rvgnoe takes NOEUD's nodes
    // first, then each group's, a node kept at its first place (probe
    // elnop: GROUP_NO's came first), for nodal fields and ELNO alike.
    post += "T2 = POST_RELEVE_T(ACTION=(\n\
        _F(INTITULE='ORDRE', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', INST=1., GROUP_NO='INTER', \
           NOEUD=('N6', 'N2'), NOM_CMP='SIXX', MOYE_NOEUD='NON', OPERATION='EXTRACTION'),\n\
        _F(INTITULE='ORDRE_DEPL', RESULTAT=RES, NOM_CHAM='DEPL', INST=1., GROUP_NO='INTER', \
           NOEUD=('N6', 'N2'), NOM_CMP='DX', OPERATION='EXTRACTION'),\n\
        ))\n\
        IMPR_TABLE(TABLE=T2)\n";
    let resu = run("elno_2d", &mesh_2d(), &study(2, &post));
    // 2 nodes x (2 cells x 2 + 2) + 1 checks against the hand values,
    // every one OK (assert_all_ok)
    assert_eq!(analytic_oks(&resu), 13, "{resu}");
    // code_aster's rvtec0 columns: NOEUD, MAILLE, then the coordinates,
    // then the components in their order of first appearance.
    let h = header(&resu, "T");
    assert_eq!(
        h,
        [
            "INTITULE",
            "RESU",
            "NOM_CHAM",
            "NUME_ORDRE",
            "INST",
            "NOEUD",
            "MAILLE",
            "COOR_X",
            "COOR_Y",
            "SIXX",
            "SIYY",
            "EPXX",
            "EPYY"
        ],
        "{resu}"
    );
    let rows = common::printed_table(&resu, "T");
    // node-major, cells in increasing number; the skin cell M1 at N3, N6
    // has no stress and gives no row.
    let per_cell = pairs(&[("N2", "M2"), ("N2", "M3"), ("N5", "M2"), ("N5", "M3")]);
    assert_eq!(places(&rows, "SIG"), per_cell);
    assert_eq!(places(&rows, "EPS"), per_cell);
    assert_eq!(places(&rows, "BORD"), pairs(&[("N3", "M3"), ("N6", "M3")]));
    // MOYE_NOEUD='OUI': one row per node (MAILLE empty, printed '-').
    assert_eq!(places(&rows, "EPS_MOY"), pairs(&[("N2", "-"), ("N5", "-")]));
    let rows2 = common::printed_table(&resu, "T2");
    assert_eq!(
        places(&rows2, "ORDRE"),
        pairs(&[
            ("N6", "M3"),
            ("N2", "M2"),
            ("N2", "M3"),
            ("N5", "M2"),
            ("N5", "M3")
        ])
    );
    let depl: Vec<String> = places(&rows2, "ORDRE_DEPL")
        .into_iter()
        .map(|p| p.0)
        .collect();
    assert_eq!(depl, ["N6", "N2", "N5"]);
    for r in rows.iter().filter(|r| r["INTITULE"] == "EPS") {
        assert!(num(r, "EPYY").abs() < 1e-12, "NU = 0: EPYY = 0, {r:?}");
        assert_eq!(num(r, "COOR_X"), 1.0);
    }
}

#[test]
fn elno_rows_per_cell_and_means_3d() {
    let mut post = ACTIONS
        .replace("'EPYY'", "'EPZZ'")
        .replace("'SIYY'", "'SIZZ'");
    for no in ["N2", "N11"] {
        for (ma, eps) in [("M1", EPS1), ("M2", EPS2)] {
            post += &check("T", "SIG", no, Some(ma), "SIXX", SIG);
            post += &check("T", "EPS", no, Some(ma), "EPXX", eps);
        }
        post += &check("T", "EPS_MOY", no, None, "EPXX", (EPS1 + EPS2) / 2.0);
        post += &check("T", "EPS_M2", no, None, "EPXX", EPS2);
    }
    let resu = run("elno_3d", &mesh_3d(), &study(3, &post));
    assert_eq!(analytic_oks(&resu), 12, "{resu}");
    let h = header(&resu, "T");
    assert_eq!(
        &h[5..10],
        ["NOEUD", "MAILLE", "COOR_X", "COOR_Y", "COOR_Z"],
        "{resu}"
    );
    let rows = common::printed_table(&resu, "T");
    let inter = ["N2", "N5", "N8", "N11"];
    let per_cell: Vec<(String, String)> = inter
        .iter()
        .flat_map(|n| {
            [
                (n.to_string(), "M1".to_string()),
                (n.to_string(), "M2".to_string()),
            ]
        })
        .collect();
    assert_eq!(places(&rows, "EPS"), per_cell);
    assert_eq!(places(&rows, "EPS_MOY").len(), 4);
    assert_eq!(places(&rows, "EPS_M2").len(), 4);
    // every value of every row against the closed form
    for r in &rows {
        let it = r["INTITULE"].as_str();
        let want = match (it, r.get("MAILLE").map(String::as_str)) {
            ("SIG" | "BORD", _) => (SIG, "SIXX"),
            ("EPS", Some("M1")) => (EPS1, "EPXX"),
            ("EPS", Some("M2")) | ("EPS_M2", _) => (EPS2, "EPXX"),
            ("EPS_MOY", _) => ((EPS1 + EPS2) / 2.0, "EPXX"),
            other => panic!("unexpected row {other:?}"),
        };
        let v = num(r, want.1);
        assert!(
            (v - want.0).abs() <= 1e-9 * want.0,
            "{it}: {v} vs {}",
            want.0
        );
    }
}

#[test]
fn elno_refusals_are_located() {
    let cases = [
        (
            "elno_extrema",
            "T = POST_RELEVE_T(ACTION=_F(INTITULE='X', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', \
             GROUP_NO='INTER', OPERATION='EXTREMA'))",
            "POST_RELEVE_T/ACTION/GROUP_NO",
            "EXTREMA of the field by element at nodes SIEF_ELNO reads cells",
        ),
        (
            "elno_resultante",
            "T = POST_RELEVE_T(ACTION=_F(INTITULE='X', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', \
             GROUP_NO='INTER', RESULTANTE='DX', OPERATION='EXTRACTION'))",
            "RESULTANTE",
            "RESULTANTE of the field by element at nodes SIEF_ELNO is not built",
        ),
        (
            "elno_outside",
            "T = POST_RELEVE_T(ACTION=_F(INTITULE='X', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', \
             GROUP_NO='DROITE', GROUP_MA='MAT1', NOM_CMP='SIXX', OPERATION='EXTRACTION'))",
            "GROUP_NO",
            "node N3 is on no cell of GROUP_MA/MAILLE where SIEF_ELNO has values",
        ),
        // N3 comes from GROUP_NO although NOEUD is given too: the error
        // names GROUP_NO (it named NOEUD whenever NOEUD was present,
        // probe elnop).
        (
            "elno_outside_group",
            "T = POST_RELEVE_T(ACTION=_F(INTITULE='X', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', \
             NOEUD='N2', GROUP_NO='DROITE', GROUP_MA='MAT1', NOM_CMP='SIXX', OPERATION='EXTRACTION'))",
            "POST_RELEVE_T/ACTION/GROUP_NO",
            "node N3 is on no cell of GROUP_MA/MAILLE where SIEF_ELNO has values",
        ),
        (
            "elno_absent",
            "T = POST_RELEVE_T(ACTION=_F(INTITULE='X', RESULTAT=RES, NOM_CHAM='SIGM_ELNO', \
             GROUP_NO='INTER', NOM_CMP='SIXX', OPERATION='EXTRACTION'))",
            "NOM_CHAM",
            "result RES has no field SIGM_ELNO at NUME_ORDRE",
        ),
    ];
    for (tag, post, key, what) in cases {
        let (d, med) = common::scratch_mesh(tag, &mesh_2d());
        let run = common::run_generated_any(&d, tag, &study(2, post), &med);
        let mess = run.file(&format!("{tag}.mess"));
        let all = format!("{}\n{mess}", run.term);
        assert_ne!(run.code, 0, "{tag} should fail:\n{all}");
        assert!(all.contains(what), "{tag}: no '{what}' in\n{all}");
        assert!(all.contains(key), "{tag}: no '{key}' in\n{all}");
        // located: the line of the POST_RELEVE_T in the generated file
        assert!(
            all.contains(&format!("{tag}.comm:11")),
            "{tag}: not located\n{all}"
        );
    }
}

/// VARI_ELNO with plasticity in one cell only: two QUAD4 stacked in y in
/// C_PLAN, M1 = [0, 1]² (SY = 2) under M2 = [0, 1] x [1, 2] (SY = 1000),
/// both E = 1000, NU = 0, ET = 100 (VMIS_ISOT_LINE), held DX = 0 at
/// x = 0 (and DY at N1 only) and pulled DX = 0.01 at x = 1. Both cells
/// take the strain EPXX = 0.01 (in parallel), uniaxially (sigma_yy = 0
/// free, sigma_zz = 0 plane stress; the different lateral strains,
/// -p/2 in M1 and 0 in M2, are compatible across the interface y = 1).
/// M2 stays elastic: SIXX = 10, V1 = V2 = 0. M1 yields: with H = E ET /
/// (E - ET) = 1000/9, sigma/E + (sigma - 2)/H = 0.01 gives sigma = 2.8
/// and p = V1 = 0.0072, V2 = 1 (radial return exact for linear
/// hardening in one step). The interface nodes N3, N4 give one row per
/// cell with those values, and the means (0.0036 for V1) by default.
#[test]
fn vari_elno_plastic_in_one_cell() {
    let mut m = Mesh {
        name: "PARALLELE".into(),
        dim: 2,
        coords: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 2.0, 0.0],
        ],
        ..Mesh::default()
    };
    common::add_cell(&mut m, "MAT1", CellType::Quad4, vec![0, 1, 3, 2]);
    common::add_cell(&mut m, "MAT2", CellType::Quad4, vec![2, 3, 5, 4]);
    m.node_groups.insert("GAUCHE".into(), vec![0, 2, 4]);
    m.node_groups.insert("DROITE".into(), vec![1, 3, 5]);
    m.node_groups.insert("COIN".into(), vec![0]);
    m.node_groups.insert("INTER".into(), vec![2, 3]);
    let (p, sig1, sig2) = (0.0072, 2.8, 10.0);
    let mut post = String::from(
        "T = POST_RELEVE_T(ACTION=(\n\
         _F(INTITULE='V', RESULTAT=RES, NOM_CHAM='VARI_ELNO', INST=1., GROUP_NO='INTER', \
            NOM_CMP=('V1', 'V2'), MOYE_NOEUD='NON', OPERATION='EXTRACTION'),\n\
         _F(INTITULE='S', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', INST=1., GROUP_NO='INTER', \
            NOM_CMP='SIXX', MOYE_NOEUD='NON', OPERATION='EXTRACTION'),\n\
         _F(INTITULE='V_MOY', RESULTAT=RES, NOM_CHAM='VARI_ELNO', INST=1., NOEUD=('N4', 'N3'), \
            TOUT_CMP='OUI', OPERATION='EXTRACTION'),\n\
         ))\n\
         IMPR_TABLE(TABLE=T, FORMAT_R='E24.16')\n",
    );
    for no in ["N3", "N4"] {
        post += &check("T", "V", no, Some("M1"), "V1", p);
        post += &check("T", "V", no, Some("M1"), "V2", 1.0);
        post += &check("T", "S", no, Some("M1"), "SIXX", sig1);
        post += &check("T", "S", no, Some("M2"), "SIXX", sig2);
        post += &check("T", "V_MOY", no, None, "V1", p / 2.0);
    }
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))\n\
         MAT1 = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.), ECRO_LINE=_F(D_SIGM_EPSI=100., SY=2.))\n\
         MAT2 = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.), ECRO_LINE=_F(D_SIGM_EPSI=100., SY=1000.))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=(_F(GROUP_MA='MAT1', MATER=MAT1), _F(GROUP_MA='MAT2', MATER=MAT2)))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='GAUCHE', DX=0.), _F(GROUP_NO='COIN', DY=0.), \
         _F(GROUP_NO='DROITE', DX=0.01)))\n\
         LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=1))\n\
         RES = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH), \
         COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI), \
         CONVERGENCE=_F(RESI_GLOB_RELA=1.E-10, ITER_GLOB_MAXI=20))\n\
         RES = CALC_CHAMP(reuse=RES, RESULTAT=RES, CONTRAINTE='SIEF_ELNO', VARI_INTERNE='VARI_ELNO')\n\
         {post}\n\
         FIN()\n"
    );
    let resu = run("elno_vari", &m, &comm);
    assert_eq!(analytic_oks(&resu), 10, "{resu}");
    let rows = common::printed_table(&resu, "T");
    let per_cell = pairs(&[("N3", "M1"), ("N3", "M2"), ("N4", "M1"), ("N4", "M2")]);
    assert_eq!(places(&rows, "V"), per_cell);
    // the elastic cell: no plastic strain at the shared nodes
    for r in rows
        .iter()
        .filter(|r| r["INTITULE"] == "V" && r["MAILLE"] == "M2")
    {
        assert!(
            num(r, "V1").abs() < 1e-12 && num(r, "V2").abs() < 1e-12,
            "{r:?}"
        );
    }
    // NOEUD in the order given, TOUT_CMP: every internal variable
    assert_eq!(places(&rows, "V_MOY"), pairs(&[("N4", "-"), ("N3", "-")]));
    let h = header(&resu, "T");
    assert!(h.iter().any(|c| c == "V2"), "{h:?}");
}

/// OPERATION='EXTREMA' of a field by element at nodes (code_aster's
/// `prexel`): over the cells and each cell's nodes. EPXX is 0.005 at every
/// node of M2 (E1) and 0.0025 at every node of M3 (E2), to round-off: MAX
/// and MAXI_ABS at a node of M2, MIN and MINI_ABS at a node of M3 (which
/// node, the last bits decide); restricted to MAT2, all four are M3's
/// 0.0025. SIXX = 5 everywhere. The table has code_aster's columns, the
/// cell before the node.
#[test]
fn elno_extrema_follow_cells_then_their_nodes() {
    let post = "T = POST_RELEVE_T(ACTION=(\n\
        _F(INTITULE='EPS', RESULTAT=RES, NOM_CHAM='EPSI_ELNO', INST=1., TOUT='OUI', \
           NOM_CMP='EPXX', OPERATION='EXTREMA'),\n\
        _F(INTITULE='EPS2', RESULTAT=RES, NOM_CHAM='EPSI_ELNO', INST=1., GROUP_MA='MAT2', \
           NOM_CMP='EPXX', OPERATION='EXTREMA'),\n\
        _F(INTITULE='SIG', RESULTAT=RES, NOM_CHAM='SIEF_ELNO', INST=1., \
           NOM_CMP=('SIXX',), OPERATION='EXTREMA'),))\n\
        IMPR_TABLE(TABLE=T, FORMAT_R='E24.16')\n\
        TEST_TABLE(TABLE=T, NOM_PARA='VALE', FILTRE=(_F(NOM_PARA='INTITULE', VALE_K='EPS'), \
           _F(NOM_PARA='EXTREMA', VALE_K='MAX')), VALE_CALC=0.005, REFERENCE='ANALYTIQUE', \
           VALE_REFE=0.005, PRECISION=1.E-9)\n\
        TEST_TABLE(TABLE=T, NOM_PARA='VALE', FILTRE=(_F(NOM_PARA='INTITULE', VALE_K='EPS'), \
           _F(NOM_PARA='EXTREMA', VALE_K='MIN')), VALE_CALC=0.0025, REFERENCE='ANALYTIQUE', \
           VALE_REFE=0.0025, PRECISION=1.E-9)\n";
    let resu = run("elno_extrema_ok", &mesh_2d(), &study(2, post));
    assert_eq!(analytic_oks(&resu), 2);
    assert_eq!(
        header(&resu, "T"),
        [
            "INTITULE",
            "RESU",
            "NOM_CHAM",
            "NUME_ORDRE",
            "INST",
            "EXTREMA",
            "MAILLE",
            "NOEUD",
            "CMP",
            "VALE"
        ]
    );
    let rows = common::printed_table(&resu, "T");
    let at = |it: &str| -> Vec<(String, String, String, f64)> {
        rows.iter()
            .filter(|r| r["INTITULE"] == it)
            .map(|r| {
                (
                    r["EXTREMA"].clone(),
                    r["MAILLE"].clone(),
                    r["NOEUD"].clone(),
                    num(r, "VALE"),
                )
            })
            .collect()
    };
    let expect = |v: &[(&str, &str, &str, f64)]| -> Vec<(String, String, String, f64)> {
        v.iter()
            .map(|(a, b, c, d)| (a.to_string(), b.to_string(), c.to_string(), *d))
            .collect()
    };
    // The node: one of the cell's (M2: N1 N2 N5 N4, M3: N2 N3 N6 N5).
    let cell_nodes = |m: &str| match m {
        "M2" => ["N1", "N2", "N5", "N4"],
        _ => ["N2", "N3", "N6", "N5"],
    };
    let close = |got: Vec<(String, String, String, f64)>,
                 want: Vec<(String, String, String, f64)>| {
        assert_eq!(got.len(), want.len());
        for (g, w) in got.iter().zip(&want) {
            assert_eq!((&g.0, &g.1), (&w.0, &w.1), "{got:?}");
            assert!(cell_nodes(&g.1).contains(&g.2.as_str()), "{got:?}");
            assert!((g.3 - w.3).abs() <= 1e-12 * w.3.abs(), "{got:?}");
        }
    };
    close(
        at("EPS"),
        expect(&[
            ("MAX", "M2", "N1", EPS1),
            ("MIN", "M3", "N2", EPS2),
            ("MAXI_ABS", "M2", "N1", EPS1),
            ("MINI_ABS", "M3", "N2", EPS2),
        ]),
    );
    close(
        at("EPS2"),
        expect(&[
            ("MAX", "M3", "N2", EPS2),
            ("MIN", "M3", "N2", EPS2),
            ("MAXI_ABS", "M3", "N2", EPS2),
            ("MINI_ABS", "M3", "N2", EPS2),
        ]),
    );
    let sig = at("SIG");
    assert_eq!(sig.len(), 4);
    assert!(
        sig.iter().all(|r| cell_nodes(&r.1).contains(&r.2.as_str())),
        "{sig:?}"
    );
    assert!(sig.iter().all(|r| (r.3 - SIG).abs() < 1e-9), "{sig:?}");
}
