//! MECA_STATIQUE (linear elastic statics, `nonlinear::linear`): studies
//! written as a code_aster user would (tests/studies/meca_*.comm), each
//! against an independent reference, and bad input that must stop with a
//! located error.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;
use std::path::{Path, PathBuf};

mod common;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/studies")
}

/// Runs tests/studies/<name>.comm, asserts every check OK, returns the
/// .resu and the .mess.
fn run_study(name: &str) -> (String, String) {
    let run = common::run_study(&format!("tests/studies/{name}.comm"), name);
    let resu = common::assert_all_ok(&run, &format!("{name}.resu"));
    (resu, run.file(&format!("{name}.mess")))
}

fn num(row: &HashMap<String, String>, col: &str) -> f64 {
    row[col]
        .parse()
        .unwrap_or_else(|_| panic!("{col}: {}", row[col]))
}

/// The linear field of the patch studies, u = A x.
const A: [[f64; 3]; 3] = [
    [1.0e-3, 2.0e-4, -3.0e-4],
    [5.0e-4, -8.0e-4, 1.0e-4],
    [-2.0e-4, 4.0e-4, 6.0e-4],
];

/// The largest |u - A x| over the rows of a printed table (COOR_*, D*),
/// relative to max |u|; and the number of rows.
fn patch_error(rows: &[HashMap<String, String>]) -> (f64, usize) {
    let (mut err, mut scale) = (0.0f64, 0.0f64);
    for r in rows {
        let x = [num(r, "COOR_X"), num(r, "COOR_Y"), num(r, "COOR_Z")];
        for (i, c) in ["DX", "DY", "DZ"].iter().enumerate() {
            let exact: f64 = (0..3).map(|j| A[i][j] * x[j]).sum();
            err = err.max((num(r, c) - exact).abs());
            scale = scale.max(exact.abs());
        }
    }
    (err / scale, rows.len())
}

/// The patch test in 3D (meca_patch.comm): distorted HEXA8 and HEXA20
/// cubes, u = A x on the faces; every node of both meshes reproduces it to
/// 1e-10 relative (the command file checks the stresses to 1e-9).
#[test]
fn patch_test_3d_hexa8_and_hexa20() {
    let (resu, mess) = run_study("meca_patch");
    for (table, nodes) in [("T8", 64), ("T20", 208)] {
        let (err, n) = patch_error(&common::printed_table(&resu, table));
        assert_eq!(n, nodes, "{table}");
        assert!(err < 1e-10, "{table}: {err:e}");
    }
    assert!(mess.contains("relative residual"), "{mess}");
}

/// The skewed patch of meca_patch_hexs8.comm: the 3 × 3 × 3 grid of
/// [0, 3]³ under the linear map `SKEW`, every cell the same
/// parallelepiped with no edge along an axis. Node groups BORD (the 56
/// boundary nodes), INTE and I1..I8 (the interior ones); cell groups VOL,
/// C1, C14 (the centre), C27.
const SKEW: [[f64; 3]; 3] = [[1.0, 0.3, 0.1], [0.2, 1.1, -0.15], [0.1, 0.25, 0.9]];

fn skew_patch_mesh() -> aster::mesh::Mesh {
    use aster::mesh::{Cell, CellType, Mesh};
    let n = 3usize;
    let id = |i: usize, j: usize, k: usize| (k * (n + 1) + j) * (n + 1) + i;
    let mut mesh = Mesh {
        name: "SKEW".into(),
        dim: 3,
        ..Mesh::default()
    };
    let (mut border, mut inner) = (Vec::new(), Vec::new());
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                let g = [i as f64, j as f64, k as f64];
                let x: [f64; 3] = std::array::from_fn(|r| (0..3).map(|c| SKEW[r][c] * g[c]).sum());
                mesh.coords.push(x);
                if [i, j, k].iter().all(|&c| c != 0 && c != n) {
                    inner.push(id(i, j, k));
                } else {
                    border.push(id(i, j, k));
                }
            }
        }
    }
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let b = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                ];
                let t = b.map(|v| v + (n + 1) * (n + 1));
                mesh.cells.push(Cell {
                    kind: CellType::Hexa8,
                    nodes: vec![b[2], b[1], b[0], b[3], t[2], t[1], t[0], t[3]],
                });
            }
        }
    }
    for (k, &node) in inner.iter().enumerate() {
        mesh.node_groups.insert(format!("I{}", k + 1), vec![node]);
    }
    mesh.node_groups.insert("BORD".into(), border);
    mesh.node_groups.insert("INTE".into(), inner);
    mesh.cell_groups
        .insert("VOL".into(), (0..mesh.cells.len()).collect());
    for c in [1usize, 14, 27] {
        mesh.cell_groups.insert(format!("C{c}"), vec![c - 1]);
    }
    mesh
}

/// The committed skewed patch is the one built above (regenerate with
/// `UPDATE_MESHES=1 cargo test --release --test meca_statique skew`), its
/// Jacobians positive.
#[test]
fn skew_patch_mesh_is_committed() {
    let mesh = skew_patch_mesh();
    for cell in &mesh.cells {
        let dets = aster::mesh::ops::jacobian_dets(&mesh, cell).unwrap();
        assert!(dets.iter().all(|&d| d > 0.0), "{dets:?}");
    }
    let path = dir().join("meca_skew_patch.mmed");
    if std::env::var_os("UPDATE_MESHES").is_some() {
        aster::medio::write_mesh(&path, &mesh).unwrap();
    }
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("regen_meca_skew_patch.mmed");
    aster::medio::write_mesh(&tmp, &mesh).unwrap();
    assert_eq!(
        aster::medio::read_mesh(&path, None).unwrap(),
        aster::medio::read_mesh(&tmp, None).unwrap()
    );
}

/// MECA_HEXS8's linear matrix (te0392) in the patch test
/// (meca_patch_hexs8.comm): exact on the skewed parallelepipeds (every
/// interior node to 1e-10; the centre stresses to 1e-9 in the file); on
/// the distorted cube of stat_patch_hexs8.comm it is not exact, as
/// code_aster's element is not (note hexs8 §14.2): measured 5.2e-3 of
/// |u| at the interior nodes, checked between 1e-3 and 2e-2 so that a
/// change of the formulation shows.
#[test]
fn patch_test_hexs8_linear_matrix() {
    let (resu, _) = run_study("meca_patch_hexs8");
    let (err, n) = patch_error(&common::printed_table(&resu, "TS"));
    assert_eq!(n, 8);
    assert!(err < 1e-10, "parallelepipeds: {err:e}");
    let (err, n) = patch_error(&common::printed_table(&resu, "TD"));
    assert_eq!(n, 8);
    assert!((1e-3..2e-2).contains(&err), "distorted cells: {err:e}");
}

/// The axisymmetric patch (meca_patch_axis.comm), AXIS and AXIS_SI on
/// distorted QUAD8: the free centre node at u_r = AR r, u_z = BZ z to
/// 1e-10 (the stresses, SIGM_NOEU, EPSI_ELGA and a zero REAC_NODA at the
/// free node are checked in the file); the instants of LIST_INST,
/// INST_FIN and reuse=.
#[test]
fn patch_test_axis_quad8() {
    let (resu, _) = run_study("meca_patch_axis");
    for t in ["TF", "TR"] {
        let rows = common::printed_table(&resu, t);
        let r = &rows[0];
        let (x, y) = (num(r, "COOR_X"), num(r, "COOR_Y"));
        let (ur, uz) = (2e-4 * x, 1e-3 * y);
        assert!((num(r, "DX") - ur).abs() < 1e-10 * ur, "{t}: {r:?}");
        assert!((num(r, "DY") - uz).abs() < 1e-10 * uz, "{t}: {r:?}");
    }
    // LIST_INST with INST_FIN, then reuse= for the last instant, under a
    // FONC_MULT t: NUME_ORDRE 1, 2, 3 at INST 0, 1, 2, the field times t.
    let rows = common::printed_table(&resu, "TL");
    assert_eq!(rows.len(), 3);
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(num(r, "NUME_ORDRE"), (k + 1) as f64);
        let t = num(r, "INST");
        assert_eq!(t, k as f64);
        let uz = t * 1e-3 * num(r, "COOR_Y");
        assert!((num(r, "DY") - uz).abs() <= 1e-10 * uz, "{r:?}");
    }
}

/// The cantilever and column of meca_cantilever.comm.
/// - HEXS8 (te0392) in bending against Euler-Bernoulli + Timoshenko:
///   measured +2.25 % (2 across) and +2.43 % (4 across), checked within
///   +0.5 % .. +3.5 % (the clamp stiffens a continuum by about 1 %, the
///   fine HEXS20 of hexs8_cantilever.comm gives +1.0 %); the renumbered
///   cells give the aligned force to 1e-9. STAT_NON_LINE's HEXS8 (te0407
///   with ADS, the projection of an incremental law) on the same mesh:
///   −0.8 %, printed (FN4) and checked below the linear matrix's.
/// - Full HEXA8: MECA_STATIQUE and STAT_NON_LINE ELAS equal at every node
///   to 1e-10 of the largest displacement (measured 4e-13).
/// - Gravity on the column: the reaction is the weight to 1e-10 (in the
///   file; measured 1.4e-14, 0 and 9.8e-14 for HEXA8, HEXS8, HEXA20).
#[test]
fn cantilever_and_column() {
    let (resu, _) = run_study("meca_cantilever");
    let (e, nu, l, h, b) = (2.0e5, 0.3, 20.0, 2.0, 2.0);
    let g = e / (2.0 * (1.0 + nu));
    let i = b * h * h * h / 12.0;
    let beam = 0.01 / (l * l * l / (3.0 * e * i) + l / (5.0 / 6.0 * g * b * h));
    let force = |name: &str| num(&common::printed_table(&resu, name)[0], "DX");
    for t in ["FS2", "FS4"] {
        let ratio = force(t) / beam - 1.0;
        assert!((0.005..0.035).contains(&ratio), "{t}: {ratio:+e}");
    }
    let (aligned, renumbered) = (force("FS4"), force("FW4"));
    assert!((aligned - renumbered).abs() < 1e-9 * aligned);
    let nonlinear = force("FN4");
    assert!(nonlinear < aligned && (nonlinear / beam - 1.0).abs() < 0.02);
    let (d, s) = (
        common::printed_table(&resu, "TD"),
        common::printed_table(&resu, "TS"),
    );
    assert_eq!(d.len(), s.len());
    let (mut err, mut scale) = (0.0f64, 0.0f64);
    for (a, b) in d.iter().zip(&s) {
        assert_eq!(a["NOEUD"], b["NOEUD"]);
        for c in ["DX", "DY", "DZ"] {
            err = err.max((num(a, c) - num(b, c)).abs());
            scale = scale.max(num(a, c).abs());
        }
    }
    assert!(scale > 1e-3 && err < 1e-10 * scale, "{err:e} of {scale:e}");
}

/// [`common::run_variant`] on tests/studies: exit code and terminal.
fn run_variant(study: &str, tag: &str, from: &str, to: &str) -> (i32, String) {
    let run = common::run_variant(&dir(), "meca_statique_bad", study, tag, from, to);
    (run.code, run.term)
}

/// Each refused input stops with exit 1, no panic, and a message naming
/// MECA_STATIQUE, the keyword and the line. (A material without ELAS is
/// refused by DEFI_MATERIAU already: every other block needs it; the
/// command's own check of ELAS E and NU stays for materials built
/// otherwise.)
#[test]
fn bad_input_is_a_located_error() {
    let call = "RES_F = MECA_STATIQUE(MODELE=MO_F, CHAM_MATER=CHMAT,";
    let cases: &[(&str, &str, &str, &[&str])] = &[
        (
            "no_material",
            "CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', MATER=MAT))",
            "CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='M1', MATER=MAT))",
            &["MECA_STATIQUE/CHAM_MATER", "has no material", ":35:"],
        ),
        (
            "rigid_mode",
            "CH_F = AFFE_CHAR_MECA_F(MODELE=MO_F, DDL_IMPO=_F(GROUP_NO=('BAS', 'HAUT', 'COTES'), DX=UR, DY=UZ))",
            "CH_F = AFFE_CHAR_MECA_F(MODELE=MO_F, DDL_IMPO=_F(GROUP_NO='COTES', DX=UR))",
            &["MECA_STATIQUE/EXCIT", "rigid-body mode", "translation DY", ":35:"],
        ),
        (
            "cara_elem",
            call,
            "RES_F = MECA_STATIQUE(MODELE=MO_F, CHAM_MATER=CHMAT, CARA_ELEM=CHMAT,",
            &["MECA_STATIQUE", "CARA_ELEM", "cara_elem", ":35:"],
        ),
        (
            "no_cham_mater",
            call,
            "RES_F = MECA_STATIQUE(MODELE=MO_F,",
            &["MECA_STATIQUE/CHAM_MATER", "CHAM_MATER is needed", ":35:"],
        ),
        (
            "inst_and_list",
            call,
            "LI = DEFI_LIST_REEL(VALE=(0., 1.))\nRES_F = MECA_STATIQUE(MODELE=MO_F, CHAM_MATER=CHMAT, INST=1., LIST_INST=LI,",
            &["MECA_STATIQUE", "INST", "LIST_INST"],
        ),
        (
            "inst_fin",
            call,
            "LI = DEFI_LIST_REEL(VALE=(1., 2.))\nRES_F = MECA_STATIQUE(MODELE=MO_F, CHAM_MATER=CHMAT, LIST_INST=LI, INST_FIN=0.5,",
            &["MECA_STATIQUE/INST_FIN", "nothing to compute"],
        ),
        (
            "fonc_mult",
            call,
            "FM = DEFI_FONCTION(NOM_PARA='INST', VALE=(1., 1., 2., 2.), PROL_GAUCHE='EXCLU')\nRES_F = MECA_STATIQUE(MODELE=MO_F, CHAM_MATER=CHMAT, INST=0.5, EXCIT=_F(CHARGE=CH_F, FONC_MULT=FM))\nRES_X = MECA_STATIQUE(MODELE=MO_F, CHAM_MATER=CHMAT,",
            &["MECA_STATIQUE/EXCIT", "FONC_MULT", "INST = 5e-1"],
        ),
    ];
    for &(tag, from, to, want) in cases {
        let (code, term) = run_variant("meca_patch_axis", tag, from, to);
        assert_eq!(code, 1, "{tag}: {term}");
        assert!(!term.contains("panicked"), "{tag}: {term}");
        for w in want {
            assert!(term.contains(w), "{tag}: {w}\n{term}");
        }
    }
}
