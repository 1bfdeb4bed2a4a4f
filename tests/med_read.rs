//! Reading the reference MED fixtures (written by medcoupling and by a
//! plain h5py writer, see tests/fixtures/med/README.md): counts, node
//! order and groups must be exactly what the generating script wrote.

use std::path::Path;

use aster::medio::{mesh_info, mesh_names, read_mesh, read_nodal_fields};
use aster::mesh::{CellType, Mesh};

const MESH2D: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/mesh2d_quad8.med"
);
const MESH2D_V42: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/mesh2d_quad8_v42.med"
);
const MESH3D: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/mesh3d_mixed.med"
);
const RESU2D: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/resu2d_depl.med"
);
const H5PY_MIN: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/h5py_minimal.med"
);

fn read(p: &str) -> Mesh {
    read_mesh(Path::new(p), None).unwrap_or_else(|e| panic!("{e}"))
}

fn group<'a>(g: &'a indexmap::IndexMap<String, Vec<usize>>, name: &str) -> &'a [usize] {
    g.get(name)
        .unwrap_or_else(|| panic!("group {name} missing; have {:?}", g.keys()))
}

fn mid(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        (a[0] + b[0]) / 2.0,
        (a[1] + b[1]) / 2.0,
        (a[2] + b[2]) / 2.0,
    ]
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
}

/// Mid-edge node k of a quadratic cell (MED order) sits at the middle of
/// edge k of MED's edge table: checks the node order survived reading.
fn check_mid_nodes(m: &Mesh, c: usize, edges: &[(usize, usize)]) {
    let cell = &m.cells[c];
    let nv = cell.kind.nvertices();
    assert_eq!(edges.len(), cell.kind.nnodes() - nv);
    for (k, &(a, b)) in edges.iter().enumerate() {
        let p = m.coords[cell.nodes[nv + k]];
        let q = mid(m.coords[cell.nodes[a]], m.coords[cell.nodes[b]]);
        assert!(close(p, q), "cell {c} mid node {k}: {p:?} != {q:?}");
    }
}

const QUAD8_EDGES: [(usize, usize); 4] = [(0, 1), (1, 2), (2, 3), (3, 0)];

#[test]
fn mesh2d_counts_order_and_groups() {
    let m = read(MESH2D);
    assert_eq!(m.name, "MAIL2D");
    assert_eq!(m.dim, 2);
    assert_eq!(m.nnodes(), 21);
    assert_eq!(m.ncells(), 10);
    // code_aster numbering: SE3 (code 103) before QU8 (208)
    let kinds: Vec<CellType> = m.cells.iter().map(|c| c.kind).collect();
    assert_eq!(&kinds[..6], &[CellType::Seg3; 6]);
    assert_eq!(&kinds[6..], &[CellType::Quad8; 4]);
    // nodes row by row, no centre nodes: node 7 (index 6) = (1, 0.5), node 21 = (2, 2)
    assert_eq!(m.coords[6], [1.0, 0.5, 0.0]);
    assert_eq!(m.coords[20], [2.0, 2.0, 0.0]);
    assert_eq!(m.coords[10], [1.0, 1.0, 0.0]);
    // first QU8 in the file: NOD column 1 = 1 3 11 9 2 7 10 6 (1-based)
    assert_eq!(m.cells[6].nodes, vec![0, 2, 10, 8, 1, 6, 9, 5]);
    assert_eq!(m.cells[0].nodes, vec![0, 2, 1]);
    for c in 6..10 {
        check_mid_nodes(&m, c, &QUAD8_EDGES);
        // counter-clockwise corners: positive shoelace area of 1
        let p: Vec<[f64; 3]> = m.cells[c].nodes[..4].iter().map(|&n| m.coords[n]).collect();
        let area: f64 = (0..4)
            .map(|k| p[k][0] * p[(k + 1) % 4][1] - p[(k + 1) % 4][0] * p[k][1])
            .sum::<f64>()
            / 2.0;
        assert!((area - 1.0).abs() < 1e-12, "cell {c} area {area}");
    }
    for c in 0..6 {
        check_mid_nodes(&m, c, &[(0, 1)]);
    }
    let names: Vec<&str> = m.cell_groups.keys().map(String::as_str).collect();
    assert_eq!(names, ["BAS", "BORD", "DROITE", "Q1", "SZZ", "VOL"]);
    assert_eq!(group(&m.cell_groups, "VOL"), &[6, 7, 8, 9]);
    assert_eq!(group(&m.cell_groups, "Q1"), &[6]);
    assert_eq!(group(&m.cell_groups, "BAS"), &[0, 1]);
    assert_eq!(group(&m.cell_groups, "DROITE"), &[2, 3]);
    assert_eq!(group(&m.cell_groups, "SZZ"), &[4, 5]);
    assert_eq!(group(&m.cell_groups, "BORD"), &[0, 1, 2, 3, 4, 5]);
    let names: Vec<&str> = m.node_groups.keys().map(String::as_str).collect();
    assert_eq!(names, ["A1", "A2", "C1", "NBAS"]);
    assert_eq!(group(&m.node_groups, "A1"), &[0]);
    assert_eq!(group(&m.node_groups, "A2"), &[4]);
    assert_eq!(group(&m.node_groups, "C1"), &[10]);
    assert_eq!(group(&m.node_groups, "NBAS"), &[0, 1, 2, 3, 4]);
    // the groups mean what their names say
    assert_eq!(m.coords[4], [2.0, 0.0, 0.0]);
    for &c in group(&m.cell_groups, "BAS") {
        assert!(m.cells[c].nodes.iter().all(|&n| m.coords[n][1] == 0.0));
    }
    for &c in group(&m.cell_groups, "DROITE") {
        assert!(m.cells[c].nodes.iter().all(|&n| m.coords[n][0] == 2.0));
    }
    for &c in group(&m.cell_groups, "SZZ") {
        assert!(m.cells[c].nodes.iter().all(|&n| m.coords[n][1] == 2.0));
    }
}

#[test]
fn same_mesh_from_three_writers() {
    // medcoupling 4.1, medcoupling 4.2 stamp, h5py without libmed (other
    // family numbers, MED 4.0): the same mesh must come out.
    let a = read(MESH2D);
    assert_eq!(read(MESH2D_V42), a);
    assert_eq!(read(H5PY_MIN), a);
    assert_eq!(read(RESU2D), a);
}

#[test]
fn mesh3d_mixed_cells_and_groups() {
    let m = read(MESH3D);
    assert_eq!(m.name, "MAIL3D");
    assert_eq!(m.dim, 3);
    assert_eq!(m.nnodes(), 31);
    let kinds: Vec<CellType> = m.cells.iter().map(|c| c.kind).collect();
    assert_eq!(
        kinds,
        [
            CellType::Quad8,
            CellType::Hexa8,
            CellType::Penta15,
            CellType::Hexa20
        ]
    );
    assert_eq!(m.cells[3].nodes, (0..20).collect::<Vec<_>>());
    assert_eq!(m.cells[1].nodes, vec![4, 5, 6, 7, 27, 28, 29, 30]);
    check_mid_nodes(
        &m,
        3,
        &[
            (0, 1),
            (1, 2),
            (2, 3),
            (3, 0),
            (4, 5),
            (5, 6),
            (6, 7),
            (7, 4),
            (0, 4),
            (1, 5),
            (2, 6),
            (3, 7),
        ],
    );
    check_mid_nodes(
        &m,
        2,
        &[
            (0, 1),
            (1, 2),
            (2, 0),
            (3, 4),
            (4, 5),
            (5, 3),
            (0, 3),
            (1, 4),
            (2, 5),
        ],
    );
    check_mid_nodes(&m, 0, &QUAD8_EDGES);
    assert_eq!(group(&m.cell_groups, "VOL"), &[1, 2, 3]);
    assert_eq!(group(&m.cell_groups, "H8"), &[1]);
    assert_eq!(group(&m.cell_groups, "P15"), &[2]);
    assert_eq!(group(&m.cell_groups, "H20"), &[3]);
    assert_eq!(group(&m.cell_groups, "QUADRA"), &[2, 3]);
    assert_eq!(group(&m.cell_groups, "FBAS"), &[0]);
    assert_eq!(m.cell_groups.len(), 6);
    assert_eq!(group(&m.node_groups, "A1"), &[0]);
    assert_eq!(m.coords[0], [0.0, 0.0, 0.0]);
    let top: Vec<usize> = (0..31).filter(|&n| m.coords[n][2] == 2.0).collect();
    assert_eq!(top, [27, 28, 29, 30]);
    assert_eq!(group(&m.node_groups, "NTOP"), top.as_slice());
    assert_eq!(m.node_groups.len(), 2);
    // FBAS is the bottom face z=0 of the HEXA20
    assert!(m.cells[0].nodes.iter().all(|&n| m.coords[n][2] == 0.0));
}

#[test]
fn mesh_by_name_and_names_list() {
    assert_eq!(mesh_names(Path::new(MESH3D)).unwrap(), ["MAIL3D"]);
    let m = read_mesh(Path::new(MESH3D), Some("MAIL3D")).unwrap();
    assert_eq!(m.nnodes(), 31);
}

#[test]
fn resu2d_depl_values() {
    let m = read(RESU2D);
    for path in [RESU2D, H5PY_MIN] {
        let fields = read_nodal_fields(Path::new(path), Some("MAIL2D")).unwrap();
        assert_eq!(fields.len(), 1, "{path}");
        let f = &fields[0];
        assert_eq!(f.name, "DEPL");
        assert_eq!(f.components, ["DX", "DY"]);
        let st: Vec<(i32, f64)> = f.steps.iter().map(|s| (s.numdt, s.time)).collect();
        assert_eq!(st, [(1, 0.5), (2, 1.0), (3, 2.0)]);
        for s in &f.steps {
            assert_eq!(s.values.len(), 42);
            for (n, p) in m.coords.iter().enumerate() {
                let t = s.time;
                let dx = 1e-3 * t * p[0];
                let dy = -2e-3 * t * p[1] + 1e-4 * f64::from(s.numdt);
                assert!((s.values[2 * n] - dx).abs() < 1e-15, "{path} DX node {n}");
                assert!(
                    (s.values[2 * n + 1] - dy).abs() < 1e-15,
                    "{path} DY node {n}"
                );
            }
        }
    }
    // a mesh file has no field
    assert!(read_nodal_fields(Path::new(MESH2D), None)
        .unwrap()
        .is_empty());
}

#[test]
fn info_text_of_mesh2d() {
    let text = mesh_info(&read(MESH2D));
    let expected = "\
mesh            MAIL2D
space dimension 2
mesh dimension  2
nodes           21
cells           10
  SEG3             6
  QUAD8            4
cell groups     6
  BAS              2 cells
  BORD             6 cells
  DROITE           2 cells
  Q1               1 cells
  SZZ              2 cells
  VOL              4 cells
node groups     4
  A1               1 nodes
  A2               1 nodes
  C1               1 nodes
  NBAS             5 nodes
bounding box
  x  0 .. 2
  y  0 .. 2
";
    assert_eq!(text, expected);
}
