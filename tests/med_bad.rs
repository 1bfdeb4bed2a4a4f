//! Damaged or foreign files give a MedError naming the file and the
//! problem, never a panic.

#[path = "med_common.rs"]
mod common;

use std::path::Path;

use aster::medio::{mesh_names, read_mesh, read_nodal_fields, MedError, MedErrorKind};
use common::scratch;

const MESH2D: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/mesh2d_quad8.med"
);
const RESU2D: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/resu2d_depl.med"
);

fn copy_fixture(src: &str, name: &str) -> std::path::PathBuf {
    let p = scratch(name);
    std::fs::copy(src, &p).unwrap();
    let mut perm = std::fs::metadata(&p).unwrap().permissions();
    #[allow(clippy::permissions_set_readonly_false)]
    perm.set_readonly(false);
    std::fs::set_permissions(&p, perm).unwrap();
    p
}

fn err_of(p: &Path) -> MedError {
    match read_mesh(p, None) {
        Ok(m) => panic!("{} read as a mesh of {} nodes", p.display(), m.nnodes()),
        Err(e) => e,
    }
}

fn assert_names_file(e: &MedError, p: &Path) {
    let text = e.to_string();
    assert!(text.starts_with(&p.display().to_string()), "{text}");
}

#[test]
fn truncated_file() {
    let p = copy_fixture(MESH2D, "truncated.med");
    let len = std::fs::metadata(&p).unwrap().len();
    let f = std::fs::OpenOptions::new().write(true).open(&p).unwrap();
    f.set_len(len / 2).unwrap();
    drop(f);
    let e = err_of(&p);
    assert!(matches!(e.kind, MedErrorKind::Truncated(_)), "{e}");
    assert_names_file(&e, &p);
    assert!(e.to_string().contains("truncated file"), "{e}");
}

#[test]
fn random_bytes_and_empty_file() {
    let p = scratch("random.med");
    // deterministic pseudo-random bytes (64-bit LCG)
    let mut x: u64 = 0x2545_f491_4f6c_dd1d;
    let bytes: Vec<u8> = (0..5000)
        .map(|_| {
            x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            (x >> 56) as u8
        })
        .collect();
    std::fs::write(&p, bytes).unwrap();
    let e = err_of(&p);
    assert_eq!(e.kind, MedErrorKind::NotHdf5, "{e}");
    assert_names_file(&e, &p);
    assert!(e.to_string().contains("not an HDF5 file"));

    let p = scratch("empty.med");
    std::fs::write(&p, b"").unwrap();
    assert_eq!(err_of(&p).kind, MedErrorKind::NotHdf5);
}

#[test]
fn missing_file() {
    let p = scratch("does_not_exist.med");
    let e = err_of(&p);
    assert!(matches!(e.kind, MedErrorKind::Io(_)), "{e}");
    assert!(e.to_string().contains("cannot open"), "{e}");
}

#[test]
fn hdf5_file_without_med_groups() {
    let p = scratch("plain.h5");
    {
        let f = hdf5::File::create(&p).unwrap();
        f.create_group("results").unwrap();
        f.new_dataset_builder()
            .with_data(&[1.0f64, 2.0])
            .create("x")
            .unwrap();
    }
    let e = err_of(&p);
    assert!(matches!(e.kind, MedErrorKind::NotMed(_)), "{e}");
    let text = e.to_string();
    assert!(
        text.contains("no /ENS_MAA") && text.contains("results"),
        "{text}"
    );
    assert!(read_nodal_fields(&p, None).is_err());
    assert!(mesh_names(&p).is_err());

    let p = scratch("no_mesh.med");
    {
        let f = hdf5::File::create(&p).unwrap();
        f.create_group("ENS_MAA").unwrap();
    }
    assert_eq!(err_of(&p).kind, MedErrorKind::NoMesh);
}

#[test]
fn mesh_name_not_found_lists_names() {
    let e = read_mesh(Path::new(MESH2D), Some("MAILLAGE")).unwrap_err();
    assert_eq!(
        e.kind,
        MedErrorKind::MeshNotFound {
            wanted: "MAILLAGE".into(),
            available: vec!["MAIL2D".into()]
        }
    );
    assert!(e.to_string().contains("meshes present: 'MAIL2D'"), "{e}");
    let e = read_nodal_fields(Path::new(RESU2D), Some("OTHER")).unwrap_err();
    assert!(matches!(e.kind, MedErrorKind::MeshNotFound { .. }), "{e}");
}

const STEP: &str = "ENS_MAA/MAIL2D/-0000000000000000001-0000000000000000001";

#[test]
fn unknown_cell_type() {
    let p = copy_fixture(MESH2D, "pyramid.med");
    {
        let f = hdf5::File::open_rw(&p).unwrap();
        let mai = f.group(&format!("{STEP}/MAI")).unwrap();
        mai.relink("SE3", "PY5").unwrap();
    }
    let e = err_of(&p);
    assert_eq!(e.kind, MedErrorKind::UnknownCellType("PY5".into()));
    assert!(
        e.to_string()
            .contains("unknown or unsupported cell type 'PY5'"),
        "{e}"
    );
}

/// Replaces dataset `name` of group `g` of a copy of the 2D fixture.
fn with_dataset(file: &str, g: &str, name: &str, data: &[i64]) -> std::path::PathBuf {
    let p = copy_fixture(MESH2D, file);
    {
        let f = hdf5::File::open_rw(&p).unwrap();
        let grp = f.group(g).unwrap();
        grp.unlink(name).unwrap();
        grp.new_dataset_builder()
            .with_data(data)
            .create(name)
            .unwrap();
    }
    p
}

#[test]
fn inconsistent_sizes() {
    // 31 node numbers cannot be 4 cells of 8 nodes
    let p = with_dataset("nod_len.med", &format!("{STEP}/MAI/QU8"), "NOD", &[1; 31]);
    let e = err_of(&p);
    assert!(matches!(e.kind, MedErrorKind::Inconsistent(_)), "{e}");
    assert!(e.to_string().contains("not a multiple of 8"), "{e}");

    // node number 99 in a 21-node mesh
    let mut nod = vec![1i64; 32];
    nod[5] = 99;
    let p = with_dataset("nod_range.med", &format!("{STEP}/MAI/QU8"), "NOD", &nod);
    let e = err_of(&p);
    assert!(
        e.to_string().contains("refers to node 99, outside 1..21"),
        "{e}"
    );

    // family table shorter than the node table
    let p = with_dataset("fam_len.med", &format!("{STEP}/NOE"), "FAM", &[0; 20]);
    let e = err_of(&p);
    assert!(
        e.to_string().contains("20 family numbers for 21 entities"),
        "{e}"
    );

    // @NBR disagreeing with the data
    let p = copy_fixture(MESH2D, "nbr.med");
    {
        let f = hdf5::File::open_rw(&p).unwrap();
        let coo = f.dataset(&format!("{STEP}/NOE/COO")).unwrap();
        coo.delete_attr("NBR").unwrap();
        coo.new_attr::<i64>()
            .create("NBR")
            .unwrap()
            .write_scalar(&22i64)
            .unwrap();
    }
    let e = err_of(&p);
    assert!(e.to_string().contains("@NBR says 22 nodes"), "{e}");
}

#[test]
fn field_values_of_wrong_size() {
    let p = copy_fixture(RESU2D, "short_field.med");
    {
        let f = hdf5::File::open_rw(&p).unwrap();
        let g = f
            .group("CHA/DEPL/00000000000000000002-0000000000000000001/NOE/MED_NO_PROFILE_INTERNAL")
            .unwrap();
        g.unlink("CO").unwrap();
        g.new_dataset_builder()
            .with_data(&[0.0f64; 41])
            .create("CO")
            .unwrap();
    }
    let e = read_nodal_fields(&p, None).unwrap_err();
    assert!(matches!(e.kind, MedErrorKind::Inconsistent(_)), "{e}");
    assert!(e.to_string().contains("41 values"), "{e}");
}

#[test]
fn med2_file_is_refused() {
    let p = copy_fixture(MESH2D, "med2.med");
    {
        let f = hdf5::File::open_rw(&p).unwrap();
        let g = f.group("INFOS_GENERALES").unwrap();
        g.delete_attr("MAJ").unwrap();
        g.new_attr::<i64>()
            .create("MAJ")
            .unwrap()
            .write_scalar(&2i64)
            .unwrap();
    }
    let e = err_of(&p);
    assert!(matches!(e.kind, MedErrorKind::Unsupported(_)), "{e}");
    assert!(e.to_string().contains("MED file format 2.1"), "{e}");
}

/// Flipping bytes anywhere in a valid file must give Ok or Err, never a
/// panic: every number read is checked before use.
#[test]
fn corrupted_bytes_never_panic() {
    let orig = std::fs::read(MESH2D).unwrap();
    let p = scratch("flipped.med");
    let mut outcomes = (0, 0);
    for pos in (0..orig.len()).step_by(97) {
        let mut b = orig.clone();
        b[pos] ^= 0x5a;
        std::fs::write(&p, &b).unwrap();
        match read_mesh(&p, None) {
            Ok(_) => outcomes.0 += 1,
            Err(_) => outcomes.1 += 1,
        }
        let _ = read_nodal_fields(&p, None);
    }
    eprintln!(
        "corrupted copies: {} read, {} refused",
        outcomes.0, outcomes.1
    );
    assert!(outcomes.0 + outcomes.1 > 100);
    assert!(outcomes.1 > 0, "no corruption was detected at all");
}

/// A cell whose family number /FAS does not describe (probe s7b D7:
/// family -99) was dropped from its groups without a word. The reader
/// reports it (family, count, first cell) and LIRE_MAILLAGE turns that
/// into an alarm; the cell stays in the mesh, in no group.
#[test]
fn undescribed_family_is_an_alarm_of_lire_maillage() {
    // The fixture's 4 QUAD8 are in VOL; the first gets family -99.
    let fam: Vec<i64> = {
        let f = hdf5::File::open(MESH2D).unwrap();
        f.dataset(&format!("{STEP}/MAI/QU8/FAM"))
            .unwrap()
            .read_raw::<i64>()
            .unwrap()
    };
    let good = read_mesh(Path::new(MESH2D), None).unwrap();
    assert_eq!(good.cell_groups["VOL"].len(), 4);
    let mut bad = fam.clone();
    bad[0] = -99;
    let p = with_dataset("fam_unknown.med", &format!("{STEP}/MAI/QU8"), "FAM", &bad);
    let (mesh, notes) = aster::medio::read_mesh_with_notes(&p, None).unwrap();
    // The SEG3 come first (type order): the first QUAD8 is cell 7 (M7).
    let first_quad = good
        .cells
        .iter()
        .position(|c| c.kind == aster::mesh::CellType::Quad8)
        .unwrap();
    assert_eq!(
        notes,
        vec![aster::medio::UndescribedFamily {
            cells: true,
            family: -99,
            count: 1,
            first: first_quad,
        }]
    );
    assert_eq!(mesh.ncells(), good.ncells());
    assert_eq!(mesh.cell_groups["VOL"].len(), 3);
    assert!(!mesh.cell_groups["VOL"].contains(&first_quad));
    // The fixture itself has no such family.
    let (_, none) = aster::medio::read_mesh_with_notes(Path::new(MESH2D), None).unwrap();
    assert!(none.is_empty(), "{none:?}");

    // LIRE_MAILLAGE: an alarm naming the family, the count, the first
    // cell and the file; the run goes on.
    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\nFIN()\n";
    let src = aster::diag::Source::new("fam.comm", text);
    let reg = aster::commands::all();
    let mut msgs = String::new();
    let prog = aster::run::driver::parse_and_check(&src, &reg, &mut msgs).expect(&msgs);
    let mut study = aster::study::Study::default();
    study.units.map.insert(20, p.clone());
    aster::run::execute(&mut study, &prog, &reg, &src)
        .unwrap_or_else(|d| panic!("{}", d.render(Some(&src))));
    let alarm = format!(
        "<A> <LIRE_MAILLAGE> 1 cell(s) of mesh 'MAIL2D' (first: M{}) refer to the family -99, \
         which the file's /FAS/MAIL2D/ELEME does not describe: they belong to no group",
        first_quad + 1
    );
    assert!(study.mess.contains(&alarm), "{alarm}\nin:\n{}", study.mess);
    assert!(study.mess.contains("fam_unknown.med"), "{}", study.mess);
}
