//! LIRE_MAILLAGE(FORMAT='ASTER'): code_aster's own mesh format
//! (`aster::mesh::mail`). A study on a mixed HEXA8/PENTA6 mesh written in
//! code_aster's orientation against the uniaxial answer, the cells'
//! orientation after reading, and located errors on broken files.

use aster::mesh::mail::parse;
use aster::mesh::ops::jacobian_dets;
use aster::mesh::CellType;

mod common;

/// tests/verification/mail_column.comm: a uniaxial homogeneous state on a
/// HEXA8 under two PENTA6 read from a `.mail` file, DZ, DX, DY of the top
/// corner and SIZZ everywhere against the closed form (1e-10), and the
/// .mess says what the file held.
#[test]
fn a_code_aster_mesh_file_runs_a_study() {
    let run = common::run_study("tests/verification/mail_column.comm", "mail_column");
    let resu = common::assert_all_ok(&run, "mail_column.resu");
    assert_eq!(resu.matches("OK   ANALYTIQUE").count(), 5, "{resu}");
    let mess = run.file("mail_column.mess");
    assert!(mess.contains("mesh 'MA' read from"), "{mess}");
    assert!(mess.contains("PENTA6   2"), "{mess}");
    // N1..N12 and M1..M5 in file order: nothing to say about names.
    assert!(!mess.contains("names of the file are not kept"), "{mess}");
}

const CUBE: &str = "COOR_3D\n\
    A 0 0 0\n B 1 0 0\n C 1 1 0\n D 0 1 0\n\
    E 0 0 1\n F 1 0 1\n G 1 1 1\n H 0 1 1\nFINSF\n\
    HEXA8\n CUBE A B C D E F G H\nFINSF\n\
    TETRA4\n T1 A B D E\nFINSF\n\
    PENTA6\n P1 A B D E F H\nFINSF\n\
    GROUP_MA\n TOUT CUBE T1 P1\nFINSF\n\
    GROUP_NO NOM=BASE\n A B C\n D\nFINSF\nFIN\n";

/// Cells listed in code_aster's orientation (the base turning
/// counter-clockwise seen from the rest of the cell, as VTK) come out in
/// MED order: every Jacobian positive. The names of the file are not kept,
/// and the reader says which k-th node or cell a name became.
#[test]
fn linear_3d_cells_come_out_in_med_order() {
    let (mesh, alarms) = parse(CUBE, "CUBE").unwrap();
    assert_eq!(mesh.nnodes(), 8);
    assert_eq!(mesh.dim, 3);
    let kinds: Vec<CellType> = mesh.cells.iter().map(|c| c.kind).collect();
    assert_eq!(kinds, [CellType::Hexa8, CellType::Tetra4, CellType::Penta6]);
    for cell in &mesh.cells {
        let dets = jacobian_dets(&mesh, cell).unwrap();
        assert!(dets.iter().all(|&d| d > 0.0), "{:?} {dets:?}", cell.kind);
    }
    assert_eq!(mesh.cell_groups["TOUT"], vec![0, 1, 2]);
    assert_eq!(mesh.node_groups["BASE"], vec![0, 1, 2, 3]);
    assert_eq!(alarms.len(), 2, "{alarms:?}");
    assert!(alarms[0].contains("the file's A is N1"), "{alarms:?}");
    assert!(alarms[1].contains("the file's CUBE is M1"), "{alarms:?}");
}

/// Broken files: the line and what is wrong, never a panic.
#[test]
fn broken_files_name_the_line() {
    let cases: &[(&str, usize, &str)] = &[
        ("COOR_2D\n N1 0 0\n", 1, "not closed by FINSF"),
        ("COOR_2D\n N1 0 0\nFINSF\n", 3, "does not end with FIN"),
        (
            "COOR_2D\n N1 0 zero\nFINSF\nFIN\n",
            2,
            "'zero' is not a number",
        ),
        (
            "COOR_2D\n N1 0 0\n N1 1 0\nFINSF\nFIN\n",
            3,
            "node N1 is defined twice",
        ),
        ("COOR_2D\n N1 0 0 N2\nFINSF\nFIN\n", 2, "this one has 1"),
        (
            "COOR_2D\n N1 0 0\n N2 1 0\nFINSF\nSEG2\n S1 N1 N3\nFINSF\nFIN\n",
            6,
            "names the node N3",
        ),
        ("COOR_1D\n N1 0\nFINSF\nFIN\n", 1, "not implemented yet: COOR_1D"),
        ("COOR_2D\n N1 0 1E+400\nFINSF\nFIN\n", 2, "not a finite number"),
        (
            "COOR_3D\n N1 0 0 0\n N2 1 0\n N3 0 1 0\nFINSF\nFIN\n",
            3,
            "this one has 3",
        ),
        ("TITRE\nFINSF\nFIN\n", 3, "holds no node"),
        (
            "COOR_2D\n N1 0 0\n N2 1 0\n N3 1 1\n N4 0 1\nFINSF\nHEXA8\n M1 N1 N2 N3 N4 N1 N2 N3 N4\nFINSF\nFIN\n",
            7,
            "a volume cell needs COOR_3D",
        ),
        (
            "COOR_3D\n N1 0 0 0\nFINSF\nPYRAM5\nFINSF\nFIN\n",
            4,
            "not implemented yet: cells of type PYRAM5",
        ),
        (
            "COOR_3D\n N1 0 0 0\nFINSF\nHEXA9\nFINSF\nFIN\n",
            4,
            "unknown sub-file HEXA9",
        ),
        (
            "COOR_2D\n N1 0 0\nFINSF\nGROUP_NO\n G N1 N2\nFINSF\nFIN\n",
            5,
            "names the node N2",
        ),
        (
            "COOR_2D\n N1 0 0\nFINSF\nCOOR_3D\n N2 0 0 0\nFINSF\nFIN\n",
            4,
            "COOR_2D and COOR_3D",
        ),
    ];
    for &(text, line, what) in cases {
        let e = parse(text, "M").unwrap_err();
        assert_eq!(e.line, line, "{text}: {e}");
        assert!(e.message.contains(what), "{text}: {e}");
    }
}

/// A HEXA20 listed as code_aster does (corners as a HEXA8, then the
/// mid-edge nodes of the base, of the vertical edges, of the top) comes
/// out in MED order: every mid-edge node is at the middle of the MED edge
/// of docs/mesh.md's table (base 0-1..3-0, top 4-5..7-4, vertical 0-4..3-7),
/// and the Jacobian is positive. Records written `H = C0 ...` read too
/// (code_aster's comp005b.mail writes `M2 = N0 N1`).
#[test]
fn hexa20_mid_edge_nodes_come_out_in_med_order() {
    // The unit cube; code_aster's corner order turns counter-clockwise
    // seen from the top.
    let corners: [[i32; 3]; 8] = [
        [0, 0, 0],
        [1, 0, 0],
        [1, 1, 0],
        [0, 1, 0],
        [0, 0, 1],
        [1, 0, 1],
        [1, 1, 1],
        [0, 1, 1],
    ];
    let mail_edges = [
        (0, 1),
        (1, 2),
        (2, 3),
        (3, 0),
        (0, 4),
        (1, 5),
        (2, 6),
        (3, 7),
        (4, 5),
        (5, 6),
        (6, 7),
        (7, 4),
    ];
    let mut text = String::from("COOR_3D\n");
    for (k, c) in corners.iter().enumerate() {
        text += &format!(" C{k} {} {} {}\n", c[0], c[1], c[2]);
    }
    for (k, (a, b)) in mail_edges.iter().enumerate() {
        let m: Vec<f64> = (0..3)
            .map(|i| f64::from(corners[*a][i] + corners[*b][i]) / 2.0)
            .collect();
        text += &format!(" E{k} {} {} {}\n", m[0], m[1], m[2]);
    }
    text += "FINSF\nHEXA20\n H =";
    for k in 0..8 {
        text += &format!(" C{k}");
    }
    for k in 0..12 {
        text += &format!(" E{k}");
    }
    text += "\nFINSF\nFIN\n";
    let (mesh, _) = parse(&text, "H").unwrap();
    let cell = &mesh.cells[0];
    assert_eq!(cell.kind, CellType::Hexa20);
    let x = |i: usize| mesh.coords[cell.nodes[i]];
    for (k, (a, b)) in CellType::Hexa20.mid_edges().iter().enumerate() {
        for i in 0..3 {
            assert_eq!(
                x(8 + k)[i],
                (x(*a)[i] + x(*b)[i]) / 2.0,
                "MED node {}",
                8 + k
            );
        }
    }
    let dets = jacobian_dets(&mesh, cell).unwrap();
    assert!(dets.iter().all(|&d| d > 0.0), "{dets:?}");
}

/// A PENTA15 and a TETRA10 listed as code_aster does (corners as the
/// linear cells, then the mid-edge nodes in the order of code_aster's
/// reference cells, elrfno.F90 P15 and T10: the PENTA15's base edges
/// 1-2, 2-3, 3-1, vertical edges 1-4, 2-5, 3-6, top edges 4-5, 5-6, 6-4;
/// the TETRA10's 1-2, 2-3, 3-1, 1-4, 2-4, 3-4) come out in MED order:
/// every mid-edge node at the middle of its MED edge, every Jacobian
/// positive. They were refused as "not implemented yet" (probe11).
#[test]
fn penta15_and_tetra10_mid_edge_nodes_come_out_in_med_order() {
    type Case = (CellType, &'static [[f64; 3]], &'static [(usize, usize)]);
    let cases: [Case; 2] = [
        (
            CellType::Penta15,
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 2.0],
                [1.0, 0.0, 2.0],
                [0.0, 1.0, 2.0],
            ],
            &[
                (0, 1),
                (1, 2),
                (2, 0),
                (0, 3),
                (1, 4),
                (2, 5),
                (3, 4),
                (4, 5),
                (5, 3),
            ],
        ),
        (
            CellType::Tetra10,
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            &[(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
        ),
    ];
    for (kind, corners, mail_edges) in cases {
        let mut text = String::from("COOR_3D\n");
        for (k, c) in corners.iter().enumerate() {
            text += &format!(" C{k} {} {} {}\n", c[0], c[1], c[2]);
        }
        for (k, (a, b)) in mail_edges.iter().enumerate() {
            let m: Vec<f64> = (0..3)
                .map(|i| (corners[*a][i] + corners[*b][i]) / 2.0)
                .collect();
            text += &format!(" E{k} {} {} {}\n", m[0], m[1], m[2]);
        }
        text += &format!("FINSF\n{}\n M1", kind.aster_name());
        for k in 0..corners.len() {
            text += &format!(" C{k}");
        }
        for k in 0..mail_edges.len() {
            text += &format!(" E{k}");
        }
        text += "\nFINSF\nFIN\n";
        let (mesh, _) = parse(&text, "Q").unwrap();
        let cell = &mesh.cells[0];
        assert_eq!(cell.kind, kind);
        let x = |i: usize| mesh.coords[cell.nodes[i]];
        let nv = corners.len();
        for (k, (a, b)) in kind.mid_edges().iter().enumerate() {
            for i in 0..3 {
                assert_eq!(
                    x(nv + k)[i],
                    (x(*a)[i] + x(*b)[i]) / 2.0,
                    "{kind:?} MED node {}",
                    nv + k
                );
            }
        }
        let dets = jacobian_dets(&mesh, cell).unwrap();
        assert!(dets.iter().all(|&d| d > 0.0), "{kind:?} {dets:?}");
    }
}

/// A node named N<k> that is not the k-th of the file: the alarm says
/// that NOEUD='N<k>' reaches another node (code_aster's zzzz101a names its
/// first nodes P1.., then N1..).
#[test]
fn a_name_of_the_form_n_k_elsewhere_is_a_caution() {
    let text = "COOR_2D\n P1 0 0\n N1 1 0\n N2 1 1\nFINSF\nTRIA3\n M1 P1 N1 N2\nFINSF\nFIN\n";
    let (_, alarms) = parse(text, "M").unwrap();
    assert_eq!(alarms.len(), 1, "{alarms:?}");
    assert!(alarms[0].contains("the file's P1 is N1"), "{alarms:?}");
    assert!(
        alarms[0].contains("CAUTION: the file's own N1 is N2 here"),
        "{alarms:?}"
    );
}

/// A `.mail` read as MED (an old code_aster file's `LIRE_MAILLAGE()`,
/// FORMAT='ASTER' by default up to code_aster 12): the error says to give
/// FORMAT='ASTER'.
#[test]
fn a_mail_file_read_as_med_points_to_format_aster() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification");
    let run = common::run_variant(
        &dir,
        "mail_format_variants",
        "mail_column",
        "mail_as_med",
        "LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)",
        "LIRE_MAILLAGE(UNITE=20)",
    );
    assert_eq!(run.code, 1, "{}", run.term);
    assert!(run.term.contains("not an HDF5 file"), "{}", run.term);
    assert!(
        run.term
            .contains("read it with LIRE_MAILLAGE(FORMAT='ASTER')"),
        "{}",
        run.term
    );
}
