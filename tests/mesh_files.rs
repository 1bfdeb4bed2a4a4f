//! The meshes committed in med/ are exactly what the generator builds, and
//! they hold the counts of sdnv103.md section 3.

use std::path::Path;

use aster::medio::{read_mesh, write_mesh};
use aster::mesh::taylor::{generate, TaylorParams};
use aster::mesh::CellType;

fn med(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("med").join(name)
}

fn count(m: &aster::mesh::Mesh, t: CellType) -> usize {
    m.cells.iter().filter(|c| c.kind == t).count()
}

#[test]
fn committed_meshes_are_the_generated_ones() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    for m in ['a', 'b', 'd', 'e', 'h'] {
        let file = med(&format!("sdnv103{m}.mmed"));
        let committed = read_mesh(&file, None).unwrap_or_else(|e| panic!("{e}"));
        let fresh = generate(&TaylorParams::for_modelling(m).unwrap()).unwrap();
        // Through our writer and reader, so that both sides get the same
        // MED cell ordering.
        let again = tmp.join(format!("regen_{m}.mmed"));
        write_mesh(&again, &fresh).unwrap();
        let fresh = read_mesh(&again, None).unwrap();
        assert_eq!(committed, fresh, "med/sdnv103{m}.mmed differs from the generator's mesh; regenerate it with `aster mesh taylor --modelling {m} -o med/sdnv103{m}.mmed`");
    }
}

/// The 10 x 40 axisymmetric mesh of comm/sdnv103b_explicit_10x40.comm.
#[test]
fn committed_10x40_mesh_is_the_generated_one() {
    use aster::mesh::taylor::TaylorKind;
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let committed = read_mesh(&med("sdnv103b_10x40.mmed"), None).unwrap();
    let fresh = generate(&TaylorParams {
        kind: TaylorKind::Axis,
        n1: 10,
        n2: 40,
        n3: 0,
        linear: false,
    })
    .unwrap();
    let again = tmp.join("regen_b_10x40.mmed");
    write_mesh(&again, &fresh).unwrap();
    let fresh = read_mesh(&again, None).unwrap();
    assert_eq!(committed, fresh, "med/sdnv103b_10x40.mmed differs from the generator's mesh; regenerate it with `aster mesh taylor --kind axis --n1 10 --n2 40 -o med/sdnv103b_10x40.mmed`");
    assert_eq!(
        (committed.nnodes(), count(&committed, CellType::Quad8)),
        (1309, 401)
    );
}

#[test]
fn section_3_counts() {
    let b = read_mesh(&med("sdnv103b.mmed"), None).unwrap();
    assert_eq!((b.nnodes(), count(&b, CellType::Quad8)), (359, 101));
    let d = read_mesh(&med("sdnv103d.mmed"), None).unwrap();
    assert_eq!((d.nnodes(), count(&d, CellType::Quad8)), (29, 5));
    let a = read_mesh(&med("sdnv103a.mmed"), None).unwrap();
    assert_eq!(
        (
            a.nnodes(),
            count(&a, CellType::Hexa20),
            count(&a, CellType::Penta15)
        ),
        (2849, 480, 120)
    );
    let h = read_mesh(&med("sdnv103h.mmed"), None).unwrap();
    assert_eq!(
        (
            h.nnodes(),
            count(&h, CellType::Hexa20),
            count(&h, CellType::Penta15)
        ),
        (73, 4, 4)
    );
    let e = read_mesh(&med("sdnv103e.mmed"), None).unwrap();
    let tets = count(&e, CellType::Tetra4);
    assert!((1200..=1400).contains(&e.nnodes()), "{} nodes", e.nnodes());
    assert!((5000..=6000).contains(&tets), "{tets} tetrahedra");
    for (mesh, groups) in [
        (&b, &["VOL", "VOL_RIG", "RIGID", "SZZ", "AXE"][..]),
        (&a, &["VOL", "VOL_RIG", "RIGID", "SZZ", "SXX", "SYY"][..]),
        (&e, &["VOL", "VOL_RIG", "RIGID", "SZZ"][..]),
    ] {
        for g in groups {
            assert!(mesh.cell_groups.contains_key(*g), "missing cell group {g}");
        }
        for p in ["A1", "B1", "A2", "B2"] {
            assert_eq!(mesh.node_groups[p].len(), 1, "{p}");
        }
    }
}
