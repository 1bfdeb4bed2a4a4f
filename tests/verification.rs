//! The verification studies of tests/verification/: each is a command file
//! whose TEST_RESU compare computed values with independent references
//! (rigid-body kinematics, one-dimensional wave theory, the patch test);
//! every study must end with exit code 0, at least one OK and no NOOK.

#![allow(clippy::needless_range_loop)]

use std::path::{Path, PathBuf};

use aster::mesh::{Cell, CellType, Mesh};
mod common;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification")
}

fn run_study(name: &str) {
    let run = common::run_study(
        &format!("tests/verification/{name}.comm"),
        &format!("verif_{name}"),
    );
    common::assert_all_ok(&run, &format!("{name}.resu"));
}

#[test]
fn free_flight() {
    run_study("free_flight");
}

#[test]
fn elastic_wave_in_a_rod() {
    run_study("wave_rod");
}

/// The Taylor bar on a frictionless wall, 10 x 40 QUAD8, 80 us (about 30 s
/// in an optimised build).
#[test]
fn taylor_bar_on_a_frictionless_wall() {
    run_study("taylor_wall");
}

#[test]
fn patch_test_axis() {
    run_study("patch_axis");
}

/// A 2 x 2 QUAD8 patch of [1, 3] x [0, 2] in the (r, z) plane whose centre
/// vertex is moved off the grid; mid-edge nodes at the middle of straight
/// edges. Groups: PATCH (the cells), M1 (the first cell), BAS (z = 0), HAUT
/// (z = 2), COTES (r = 1 and r = 3), CENTRE (the moved vertex).
fn patch_mesh() -> Mesh {
    let v = |i: usize, j: usize| -> [f64; 3] {
        let (mut r, mut z) = (1.0 + i as f64, j as f64);
        if (i, j) == (1, 1) {
            r += 0.23;
            z -= 0.17;
        }
        [r, z, 0.0]
    };
    let mut coords = Vec::new();
    let mut vid = [[0usize; 3]; 3];
    for j in 0..3 {
        for i in 0..3 {
            vid[i][j] = coords.len();
            coords.push(v(i, j));
        }
    }
    let mut mid = std::collections::BTreeMap::new();
    let mut midpoint = |a: usize, b: usize, coords: &mut Vec<[f64; 3]>| -> usize {
        let key = (a.min(b), a.max(b));
        *mid.entry(key).or_insert_with(|| {
            let (p, q) = (coords[a], coords[b]);
            coords.push([(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, 0.0]);
            coords.len() - 1
        })
    };
    let mut cells = Vec::new();
    for j in 0..2 {
        for i in 0..2 {
            let c = [vid[i][j], vid[i + 1][j], vid[i + 1][j + 1], vid[i][j + 1]];
            let mut nodes = c.to_vec();
            for k in 0..4 {
                nodes.push(midpoint(c[k], c[(k + 1) % 4], &mut coords));
            }
            cells.push(Cell {
                kind: CellType::Quad8,
                nodes,
            });
        }
    }
    let on = |f: &dyn Fn(&[f64; 3]) -> bool| -> Vec<usize> {
        (0..coords.len()).filter(|&n| f(&coords[n])).collect()
    };
    let mut mesh = Mesh {
        name: "PATCH".into(),
        dim: 2,
        coords: coords.clone(),
        cells,
        ..Mesh::default()
    };
    mesh.cell_groups.insert("PATCH".into(), vec![0, 1, 2, 3]);
    mesh.cell_groups.insert("M1".into(), vec![0]);
    mesh.node_groups
        .insert("BAS".into(), on(&|p| p[1].abs() < 1e-12));
    mesh.node_groups
        .insert("HAUT".into(), on(&|p| (p[1] - 2.0).abs() < 1e-12));
    mesh.node_groups.insert(
        "COTES".into(),
        on(&|p| (p[0] - 1.0).abs() < 1e-12 || (p[0] - 3.0).abs() < 1e-12),
    );
    mesh.node_groups.insert("CENTRE".into(), vec![vid[1][1]]);
    mesh
}

/// The committed patch mesh is the one built above (regenerate it with
/// `UPDATE_MESHES=1 cargo test --test verification patch_mesh`).
#[test]
fn patch_mesh_is_committed() {
    let file = dir().join("patch.mmed");
    let mesh = patch_mesh();
    if std::env::var_os("UPDATE_MESHES").is_some() {
        aster::medio::write_mesh(&file, &mesh).unwrap();
    }
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("patch_regen.mmed");
    aster::medio::write_mesh(&tmp, &mesh).unwrap();
    let committed = aster::medio::read_mesh(&file, None).unwrap();
    assert_eq!(committed, aster::medio::read_mesh(&tmp, None).unwrap());
}
