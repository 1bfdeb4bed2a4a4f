//! Write then read back: meshes with every cell type and groups, result
//! files with nodal and cell fields at several steps.

#[path = "med_common.rs"]
mod common;

use aster::medio::{
    read_elem_fields, read_mesh, read_nodal_fields, write_mesh, write_result, write_result_fields,
    ElemField, FieldStep, NodalField,
};
use aster::mesh::{Cell, CellType, Mesh};
use common::{all_types_mesh, scratch};

const MESH2D: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/mesh2d_quad8.med"
);
const MESH3D: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/mesh3d_mixed.med"
);

#[test]
fn all_cell_types_round_trip_identically() {
    let m = all_types_mesh();
    assert_eq!(m.ncells(), CellType::ALL.len());
    let p = scratch("alltypes.med");
    write_mesh(&p, &m).unwrap();
    let back = read_mesh(&p, None).unwrap();
    assert_eq!(back, m);
    // IndexMap equality ignores order: check the order too
    assert!(back.cell_groups.keys().eq(m.cell_groups.keys()));
    assert!(back.node_groups.keys().eq(m.node_groups.keys()));
    assert_eq!(back.cell_groups["EMPTY"], Vec::<usize>::new());
    assert_eq!(back.node_groups["NEMPTY"], Vec::<usize>::new());
}

#[test]
fn fixtures_round_trip_identically() {
    for (src, name) in [(MESH2D, "rt2d.med"), (MESH3D, "rt3d.med")] {
        let m = read_mesh(src.as_ref(), None).unwrap();
        let p = scratch(name);
        write_mesh(&p, &m).unwrap();
        assert_eq!(read_mesh(&p, None).unwrap(), m, "{src}");
    }
}

#[test]
fn unsorted_cells_come_back_by_type_with_their_groups() {
    // QU4 then SE2: stored SE2 first, so the cells are renumbered and the
    // groups must follow the cells, not the indices.
    let mut m = Mesh {
        name: "M".into(),
        dim: 2,
        coords: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        cells: vec![
            Cell {
                kind: CellType::Quad4,
                nodes: vec![0, 1, 2, 3],
            },
            Cell {
                kind: CellType::Seg2,
                nodes: vec![0, 1],
            },
        ],
        ..Default::default()
    };
    m.cell_groups.insert("SURF".into(), vec![0]);
    m.cell_groups.insert("BAS".into(), vec![1]);
    let p = scratch("unsorted.med");
    write_mesh(&p, &m).unwrap();
    let back = read_mesh(&p, None).unwrap();
    assert_eq!(back.cells[0], m.cells[1]);
    assert_eq!(back.cells[1], m.cells[0]);
    assert_eq!(back.cell_groups["SURF"], [1]);
    assert_eq!(back.cell_groups["BAS"], [0]);
}

fn nodal(name: &str, comps: &[&str], m: &Mesh, steps: &[(i32, f64)]) -> NodalField {
    let nc = comps.len();
    NodalField {
        name: name.into(),
        components: comps.iter().map(|c| c.to_string()).collect(),
        steps: steps
            .iter()
            .map(|&(numdt, time)| FieldStep {
                numdt,
                time,
                values: (0..m.nnodes() * nc)
                    .map(|i| {
                        let (n, k) = (i / nc, i % nc);
                        // distinct, non-round values for every slot
                        (k as f64 + 1.0) * m.coords[n][k % 3] * time + 1e-7 * i as f64
                    })
                    .collect(),
            })
            .collect(),
    }
}

#[test]
fn result_round_trip_values_and_times() {
    let m = all_types_mesh();
    let depl = nodal(
        "RESU____DEPL",
        &["DX", "DY", "DZ"],
        &m,
        &[(0, 0.0), (1, 1.5e-6), (7, 3.25e-6)],
    );
    let vite = nodal("RESU____VITE", &["DX", "DY", "DZ"], &m, &[(1, 1.5e-6)]);
    let p = scratch("resu.med");
    write_result(&p, &m, &[depl.clone(), vite.clone()]).unwrap();
    assert_eq!(read_mesh(&p, None).unwrap(), m);
    let back = read_nodal_fields(&p, Some("ALLTYPES")).unwrap();
    assert_eq!(back, vec![depl, vite]);
}

#[test]
fn cell_fields_round_trip() {
    let m = all_types_mesh();
    let nodal_f = nodal("R_______DEPL", &["DX"], &m, &[(1, 1.0)]);
    let ef = ElemField {
        name: "R_______EPSP".into(),
        components: vec!["V1".into(), "V2".into()],
        steps: vec![
            FieldStep {
                numdt: 1,
                time: 1.0,
                values: (0..2 * CellType::ALL.len())
                    .map(|i| i as f64 * 0.5 - 3.0)
                    .collect(),
            },
            FieldStep {
                numdt: 2,
                time: 2.0,
                values: (0..2 * CellType::ALL.len())
                    .map(|i| (i as f64).sqrt())
                    .collect(),
            },
        ],
    };
    let p = scratch("resu_cells.med");
    write_result_fields(
        &p,
        &m,
        std::slice::from_ref(&nodal_f),
        std::slice::from_ref(&ef),
    )
    .unwrap();
    assert_eq!(read_elem_fields(&p, None).unwrap(), vec![ef]);
    // the nodal reader sees only the nodal field
    assert_eq!(read_nodal_fields(&p, None).unwrap(), vec![nodal_f]);
}

/// A cell field absent (NaN) on every cell of a type at every step, as
/// the mean per cell of a Gauss field on skin cells (no point), gets no
/// block of that type in the file rather than a block of NaN; a type with
/// one defined value keeps its whole block. The reader gives the absent
/// cells NaN again.
#[test]
fn cells_without_the_field_get_no_block() {
    let m = all_types_mesh();
    let n = CellType::ALL.len();
    let values = |k: f64| -> Vec<f64> {
        (0..2 * n)
            .map(|i| if i < 2 { f64::NAN } else { k + i as f64 })
            .collect()
    };
    let ef = ElemField {
        name: "R_______SIEF".into(),
        components: vec!["SIXX".into(), "SIYY".into()],
        steps: vec![
            FieldStep {
                numdt: 1,
                time: 1.0,
                values: values(0.0),
            },
            FieldStep {
                numdt: 2,
                time: 2.0,
                values: values(10.0),
            },
        ],
    };
    let p = scratch("resu_absent_cells.med");
    write_result_fields(&p, &m, &[], std::slice::from_ref(&ef)).unwrap();
    let back = read_elem_fields(&p, None).unwrap();
    assert_eq!(back.len(), 1);
    for (a, b) in back[0].steps.iter().zip(&ef.steps) {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a.values), bits(&b.values));
    }
    let first = m.cells[0].kind.med_name();
    let f = hdf5::File::open(&p).unwrap();
    let field = f.group("CHA/R_______SIEF").unwrap();
    let steps = field.member_names().unwrap();
    assert_eq!(steps.len(), 2, "{steps:?}");
    let blocks = field.group(&steps[0]).unwrap().member_names().unwrap();
    assert!(!blocks.contains(&format!("MAI.{first}")), "{blocks:?}");
    assert_eq!(blocks.len(), n - 1, "{blocks:?}");
}

#[test]
fn writer_refuses_bad_input_without_creating_a_file() {
    let m = all_types_mesh();
    let p = scratch("refused.med");
    let mut bad = m.clone();
    bad.cells[3].nodes.pop();
    let e = write_mesh(&p, &bad).unwrap_err().to_string();
    assert!(e.contains("cell 4") && e.contains("expected 3"), "{e}");
    let mut bad = m.clone();
    bad.node_groups.insert("X".repeat(81), vec![0]);
    let e = write_mesh(&p, &bad).unwrap_err().to_string();
    assert!(e.contains("MED allows 80"), "{e}");
    let f = nodal("F", &["DX"], &m, &[(1, 1.0)]);
    let mut short = f.clone();
    short.steps[0].values.pop();
    let e = write_result(&p, &m, &[short]).unwrap_err().to_string();
    assert!(e.contains("expected"), "{e}");
    let long = nodal("F", &["COMPONENT_NAME_TOO_LONG"], &m, &[(1, 1.0)]);
    let e = write_result(&p, &m, &[long]).unwrap_err().to_string();
    assert!(e.contains("MED allows 16"), "{e}");
    let e = write_result(&p, &m, &[f.clone(), f])
        .unwrap_err()
        .to_string();
    assert!(e.contains("two fields"), "{e}");
    assert!(!p.exists());
}

#[test]
fn meshes_without_groups_or_cells() {
    let tri = Mesh {
        name: "TRI".into(),
        dim: 2,
        coords: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        cells: vec![Cell {
            kind: CellType::Tria3,
            nodes: vec![0, 1, 2],
        }],
        ..Default::default()
    };
    let points = Mesh {
        name: "POINTS".into(),
        dim: 3,
        coords: vec![[0.5, -1.0, 2.0], [1.0, 1e-300, -3.5]],
        ..Default::default()
    };
    for (m, file) in [(tri, "nogroups.med"), (points, "points.med")] {
        let p = scratch(file);
        write_mesh(&p, &m).unwrap();
        assert_eq!(read_mesh(&p, None).unwrap(), m, "{file}");
    }
}

#[test]
fn unwritable_path_is_an_io_error() {
    let p = scratch("no_such_dir").join("x.med");
    let e = write_mesh(&p, &all_types_mesh()).unwrap_err();
    assert!(matches!(e.kind, aster::medio::MedErrorKind::Io(_)), "{e}");
    assert!(e.to_string().contains("cannot create"), "{e}");
}
