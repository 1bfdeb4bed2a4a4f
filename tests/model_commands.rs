//! The model-building commands run on the SDNV103 meshes: AFFE_MODELE,
//! DEFI_MATERIAU, AFFE_MATERIAU, AFFE_CHAR_MECA, CREA_CHAMP,
//! DEFI_LIST_INST and DEFI_CONTACT. Each test runs a small command file
//! through the checker and the study runner and compares the concept data
//! with counts derived independently from the mesh construction
//! (sdnv103.md §3) or with code_aster's documented semantics
//! (semantics.md §3, §4.1, §5, §7.2); every error path is checked for its
//! message, command/keyword path and line.

use std::path::Path;

use aster::commands;
use aster::concepts::ConceptData;
use aster::diag::Source;
use aster::mesh::quadrature::Fpg;
use aster::mesh::{CellType, Mesh};
use aster::model::{CellRole, Dof, Material, MaterialField, MechLoad, Model};
use aster::result::NodalField;
use aster::run::driver::parse_and_check;
use aster::study::Study;
use aster::time::list::{Action, Event, Subdivision, TimeList};

/// Runs `comm` with unit 20 mapped to `med/<mesh>.mmed`. Returns the
/// study, the rendered error if the run stopped, and the source text.
fn run(mesh: &str, comm: &str) -> (Study, Option<String>) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let src = Source::new("test.comm", comm);
    let registry = commands::all();
    let mut messages = String::new();
    let program = parse_and_check(&src, &registry, &mut messages)
        .unwrap_or_else(|| panic!("the command file does not check:\n{messages}"));
    let mut study = Study {
        out_dir: Path::new(env!("CARGO_TARGET_TMPDIR")).join("model_commands"),
        stem: "test".into(),
        ..Study::default()
    };
    study
        .units
        .map
        .insert(20, root.join(format!("med/{mesh}.mmed")));
    let err = aster::run::execute(&mut study, &program, &registry, &src)
        .err()
        .map(|d| d.render(Some(&src)));
    (study, err)
}

/// The axisymmetric mesh with node groups from the cell groups, then `body`.
fn axis(body: &str) -> String {
    format!(
        "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
         MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI'))\n\
         {body}\nFIN()\n"
    )
}

/// `axis` with the AXIS + AXIS_SI model MO of sdnv103b.
fn axis_mo(body: &str) -> String {
    axis(&format!(
        "MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=(\
         _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS'),\
         _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS_SI')))\n{body}"
    ))
}

/// The small 3D quarter mesh (sdnv103h) and `body`.
fn quarter(body: &str) -> String {
    format!("DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n{body}\nFIN()\n")
}

fn quarter_3d(body: &str) -> String {
    quarter(&format!(
        "MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n{body}"
    ))
}

/// The 1-based line of the first line of `text` containing `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("'{needle}' not in the command file"))
        + 1
}

/// Asserts the run stopped with an error whose first line holds `path`
/// (COMMAND/KEYWORD) and `words`, located at the line holding `at`.
fn assert_error(comm: &str, err: Option<String>, path: &str, words: &[&str], at: &str) {
    let e = err.expect("the run should stop on an error");
    let first = e.lines().next().unwrap_or_default();
    assert!(first.contains(path), "expected {path} in:\n{e}");
    for w in words {
        assert!(e.contains(w), "expected '{w}' in:\n{e}");
    }
    let loc = format!("test.comm:{}:", line_of(comm, at));
    assert!(e.contains(&loc), "expected location {loc} in:\n{e}");
}

fn data<'a>(study: &'a Study, name: &str) -> &'a ConceptData {
    study
        .concepts
        .data(name)
        .unwrap_or_else(|| panic!("no concept {name}"))
}
fn model<'a>(s: &'a Study, n: &str) -> &'a Model {
    match data(s, n) {
        ConceptData::Model(m) => m,
        d => panic!("{n} is not a model: {d:?}"),
    }
}
fn mesh<'a>(s: &'a Study, n: &str) -> &'a Mesh {
    match data(s, n) {
        ConceptData::Mesh(m) => m,
        _ => panic!("{n} is not a mesh"),
    }
}
fn material<'a>(s: &'a Study, n: &str) -> &'a Material {
    match data(s, n) {
        ConceptData::Material(m) => m,
        _ => panic!("{n} is not a material"),
    }
}
fn matfield<'a>(s: &'a Study, n: &str) -> &'a MaterialField {
    match data(s, n) {
        ConceptData::MaterialField(m) => m,
        _ => panic!("{n} is not a material field"),
    }
}
fn load<'a>(s: &'a Study, n: &str) -> &'a MechLoad {
    match data(s, n) {
        ConceptData::MechLoad(m) => m,
        _ => panic!("{n} is not a load"),
    }
}
fn field<'a>(s: &'a Study, n: &str) -> &'a NodalField {
    match data(s, n) {
        ConceptData::Field(m) => &m.field,
        _ => panic!("{n} is not a field"),
    }
}
fn timelist<'a>(s: &'a Study, n: &str) -> &'a TimeList {
    match data(s, n) {
        ConceptData::TimeList(m) => m,
        _ => panic!("{n} is not a time list"),
    }
}

/// (element name, RIGI family) of every element cell of a type.
fn elements_of(m: &Model, mesh: &Mesh, kind: CellType) -> Vec<(&'static str, Fpg)> {
    m.element_cells()
        .filter(|(c, _)| mesh.cells[*c].kind == kind)
        .map(|(_, s)| (s.name, s.rigi))
        .collect()
}

fn skins(m: &Model) -> Vec<&str> {
    m.cells
        .iter()
        .filter_map(|r| match r {
            CellRole::Skin { modelisation } => Some(modelisation.as_str()),
            _ => None,
        })
        .collect()
}

// ---------------------------------------------------------------------------
// The whole of sdnv103b up to DYNA_NON_LINE.

/// sdnv103b.comm up to DYNA_NON_LINE runs every model command. The
/// reference counts come from the mesh construction (sdnv103.md §3): a
/// 5 x 20 QUAD8 grid has (2*5+1)(2*20+1) - 5*20 = 351 nodes, the block
/// QUAD8 8 more (359); the axis edge AXE has 2*20+1 = 41 nodes.
#[test]
fn sdnv103b_builds_its_model_data() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let comm = std::fs::read_to_string(root.join("comm/sdnv103b.comm")).unwrap();
    // DYNA_NON_LINE now runs (tests/study_runs.rs): keep the commands
    // before it.
    let cut = comm.find("RESU = DYNA_NON_LINE").unwrap();
    let (s, err) = run("sdnv103b", &format!("{}\nFIN()\n", &comm[..cut]));
    assert!(err.is_none(), "stopped on an error:\n{err:?}");
    let mesh = mesh(&s, "MAIL");
    let bar_nodes = 11 * 41 - 5 * 20;
    assert_eq!(mesh.nnodes(), bar_nodes + 8);

    // AXIS then AXIS_SI: every QUAD8 is the 2x2-point MEAXQS8, with the
    // 3x3 mass; the 26 SEG3 edges are AXIS_SI skins.
    let mo = model(&s, "MO");
    assert_eq!(mo.mesh, "MAIL");
    assert_eq!(mo.dofs, vec![Dof::Dx, Dof::Dy]);
    let quads = elements_of(mo, mesh, CellType::Quad8);
    assert_eq!(quads.len(), 101);
    assert!(quads.iter().all(|q| *q == ("MEAXQS8", Fpg::Fpg4)));
    assert!(mo.element_cells().all(|(_, spec)| spec.mass == Fpg::Fpg9));
    let sk = skins(mo);
    assert_eq!(sk.len(), 26);
    assert!(sk.iter().all(|m| *m == "AXIS_SI"));

    let cuivre = material(&s, "CUIVRE");
    assert_eq!(cuivre.get("ELAS", "E"), Some(117e3));
    assert_eq!(cuivre.get("ELAS", "NU"), Some(0.35));
    assert_eq!(cuivre.get("ELAS", "RHO"), Some(8.93e-9));
    // COEF_AMOR is defaulted by the catalogue (semantics.md §4.1).
    assert_eq!(cuivre.get("ELAS", "COEF_AMOR"), Some(1.0));
    assert_eq!(cuivre.get("ECRO_LINE", "D_SIGM_EPSI"), Some(100.0));
    assert_eq!(cuivre.get("ECRO_LINE", "SY"), Some(400.0));
    assert_eq!(cuivre.get("ELAS", "AMOR_ALPHA"), None);

    let chmat = matfield(&s, "CHMAT");
    assert_eq!(chmat.cell_material.len(), 127);
    assert!(chmat
        .cell_material
        .iter()
        .all(|m| m.as_deref() == Some("CUIVRE")));

    // DDL_IMPO: the 8 block nodes (RIGID's 3 nodes are among them) get DX
    // and DY, then the 41 AXE nodes DX: 57 entries, all zero; the AXE
    // nodes are those of the bar on x = 0.
    let bl = load(&s, "BLOCAGE");
    assert_eq!(bl.model, "MO");
    assert_eq!(bl.imposed.len(), 8 * 2 + 41);
    assert!(bl.imposed.iter().all(|d| d.value == 0.0));
    let (block, axe) = bl.imposed.split_at(16);
    assert!(block.iter().all(|d| mesh.coords[d.node][1] <= 0.0));
    assert_eq!(block.iter().filter(|d| d.dof == Dof::Dy).count(), 8);
    assert!(axe.iter().all(|d| d.dof == Dof::Dx
        && mesh.coords[d.node][0] == 0.0
        && mesh.coords[d.node][1] > 2.0));
    let on_axis = (0..mesh.nnodes())
        .filter(|&n| mesh.coords[n][0] == 0.0 && mesh.coords[n][1] > 0.0)
        .count();
    assert_eq!(on_axis, 41);

    // VITINI: DY = V0 on the bar, overwritten by 0 on the block (y <= 0);
    // DX = 0 everywhere; nothing absent.
    let v = field(&s, "VITINI");
    assert_eq!(v.components, vec!["DX", "DY"]);
    assert_eq!(v.nnodes(), mesh.nnodes());
    let mut bar = 0;
    for n in 0..mesh.nnodes() {
        assert_eq!(v.get(n, "DX"), Some(0.0));
        let expected = if mesh.coords[n][1] <= 0.0 {
            0.0
        } else {
            bar += 1;
            -227000.0
        };
        assert_eq!(v.get(n, "DY"), Some(expected), "node {n}");
    }
    assert_eq!(bar, bar_nodes);

    // DEFLIST: the list of L_INST and the one ERREUR rule as given
    // (SUBD_PAS=4) with the catalogue's SUBD_NIVEAU=3, SUBD_PAS_MINI=0;
    // no implicit rule since ERREUR is given.
    let dl = timelist(&s, "DEFLIST");
    assert_eq!(dl.instants.len(), 1 + 1 + 4 + 158);
    assert!(!dl.auto);
    assert_eq!(dl.rules.len(), 1);
    assert_eq!(
        dl.on_error(),
        &Action::Decoupe(Subdivision::Manuel {
            subd_pas: 4,
            subd_niveau: 3,
            subd_pas_mini: 0.0
        })
    );
    assert_eq!(dl.max_subd_niveau(), Some(3));

    match data(&s, "CONT") {
        ConceptData::Contact(a) => {
            assert_eq!(a.text("FORMULATION"), Some("DISCRETE"));
            assert_eq!(a.fact("ZONE").and_then(|z| z.real("E_N")), Some(1e10));
        }
        d => panic!("CONT: {d:?}"),
    }
    // The count table of AFFE_MODELE is in the message file.
    assert!(s.mess.contains("MEAXQS8"), "{}", s.mess);
}

// ---------------------------------------------------------------------------
// AFFE_MODELE

/// Swapped order: AXIS_SI then AXIS gives the 3x3-point MEAXQU8 everywhere.
#[test]
fn axis_after_axis_si_overrides_everything() {
    let (s, err) = run(
        "sdnv103b",
        &axis(
            "MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=(\
             _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS_SI'),\
             _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS')))",
        ),
    );
    assert!(err.is_none(), "{err:?}");
    let (mo, mesh) = (model(&s, "MO"), mesh(&s, "MAIL"));
    let quads = elements_of(mo, mesh, CellType::Quad8);
    assert_eq!(quads.len(), 101);
    assert!(quads.iter().all(|q| *q == ("MEAXQU8", Fpg::Fpg9)));
}

/// 3D then 3D_SI on the bar: PENTA15 (no 3D_SI element) keeps the full
/// 21-point MECA_PENTA15, HEXA20 becomes the 8-point MECA_HEXS20, the
/// HEXA8 block outside VOL stays MECA_HEXA8. sdnv103h has 4 + 4 bar cells.
#[test]
fn three_d_then_three_d_si_keeps_penta15() {
    let (s, err) = run(
        "sdnv103h",
        &quarter(
            "MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=(\
             _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'),\
             _F(GROUP_MA='VOL', PHENOMENE='MECANIQUE', MODELISATION='3D_SI')))",
        ),
    );
    assert!(err.is_none(), "{err:?}");
    let (mo, mesh) = (model(&s, "MO"), mesh(&s, "MAIL"));
    assert_eq!(mo.dofs, vec![Dof::Dx, Dof::Dy, Dof::Dz]);
    assert_eq!(
        elements_of(mo, mesh, CellType::Penta15),
        vec![("MECA_PENTA15", Fpg::Fpg21); 4]
    );
    assert_eq!(
        elements_of(mo, mesh, CellType::Hexa20),
        vec![("MECA_HEXS20", Fpg::Fpg8); 4]
    );
    assert_eq!(
        elements_of(mo, mesh, CellType::Hexa8),
        vec![("MECA_HEXA8", Fpg::Fpg8)]
    );
    // The 13 faces (10 QUAD8, 2 TRIA6, 1 QUAD4) are 3D skins: none is in VOL.
    assert_eq!(skins(mo), vec!["3D"; 13]);
    assert!(mo.cells.iter().all(|r| *r != CellRole::None));
    assert!(!s.mess.contains("MODELE1_70"), "{}", s.mess);
}

/// Swapped: 3D_SI on VOL then 3D everywhere gives full 3D everywhere.
#[test]
fn three_d_si_then_three_d_is_full_3d() {
    let (s, err) = run(
        "sdnv103h",
        &quarter(
            "MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=(\
             _F(GROUP_MA='VOL', PHENOMENE='MECANIQUE', MODELISATION='3D_SI'),\
             _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D')))",
        ),
    );
    assert!(err.is_none(), "{err:?}");
    let (mo, mesh) = (model(&s, "MO"), mesh(&s, "MAIL"));
    assert_eq!(
        elements_of(mo, mesh, CellType::Hexa20),
        vec![("MECA_HEXA20", Fpg::Fpg27); 4]
    );
    assert_eq!(
        elements_of(mo, mesh, CellType::Penta15),
        vec![("MECA_PENTA15", Fpg::Fpg21); 4]
    );
    // After the first occurrence alone the PENTA15 of VOL had no element:
    // the MODELE1_70 alarm names 4 holes.
    assert!(
        s.mess.contains("MODELE1_70") && s.mess.contains("4 cell(s) of dimension 3"),
        "{}",
        s.mess
    );
}

/// 3D then 3D_SI on everything (modelling A's AFFE): the HEXA8 block
/// becomes MECA_HEXS8 (one RIGI point), the HEXA20 MECA_HEXS20, the
/// PENTA15 keep their full 3D element; AFFE_MODELE raises MODELE1_7.
#[test]
fn three_d_then_three_d_si_gives_hexs8_on_the_block() {
    let comm = quarter(
        "MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=(\
         _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'),\n\
         _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D_SI')))",
    );
    let (s, err) = run("sdnv103h", &comm);
    assert!(err.is_none(), "{err:?}");
    let (mo, mesh) = (model(&s, "MO"), mesh(&s, "MAIL"));
    assert_eq!(
        elements_of(mo, mesh, CellType::Hexa8),
        vec![("MECA_HEXS8", Fpg::Fpg1)]
    );
    assert_eq!(
        elements_of(mo, mesh, CellType::Hexa20),
        vec![("MECA_HEXS20", Fpg::Fpg8); 4]
    );
    assert_eq!(
        elements_of(mo, mesh, CellType::Penta15),
        vec![("MECA_PENTA15", Fpg::Fpg21); 4]
    );
    assert!(s.mess.contains("<MODELE1_7>"), "{}", s.mess);
}

/// Modelling H's command file with the block under 3D_SI and its
/// COMPORTEMENT on VOL_RIG replaced by `block`.
fn h_with_hexs8_block(block: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let h = std::fs::read_to_string(root.join("comm/sdnv103h.comm")).unwrap();
    let h = h.replace(
        "AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'),)",
        "AFFE=(_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'),\n\
         _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D_SI'),),)",
    );
    assert!(h.contains("MODELISATION='3D_SI'"));
    h.replacen("_F(RELATION='ELAS', DEFORMATION='PETIT',", block, 1)
}

/// The limits of MECA_HEXS8 (te0407): RELATION='ELAS' in PETIT without
/// an initial state is COMP_ELAS (ELEMENTSSI_3), and finite strains are
/// refused (ELEMENTSSI_1); both stop DYNA_NON_LINE before any step, at
/// the COMPORTEMENT occurrence that gives the block its law.
#[test]
fn hexs8_limits_are_located_errors() {
    let comm = h_with_hexs8_block("_F(RELATION='ELAS', DEFORMATION='PETIT',");
    let (_, err) = run("sdnv103h", &comm);
    assert_error(
        &comm,
        err,
        "DYNA_NON_LINE/COMPORTEMENT/RELATION",
        &["MECA_HEXS8", "ELEMENTSSI_3", "PETIT_REAC"],
        "_F(RELATION='ELAS', DEFORMATION='PETIT',",
    );
    let comm = h_with_hexs8_block("_F(RELATION='VMIS_ISOT_LINE', DEFORMATION='SIMO_MIEHE',");
    let (_, err) = run("sdnv103h", &comm);
    let e = err.expect("SIMO_MIEHE on HEXS8 must stop");
    assert!(
        e.contains("DYNA_NON_LINE/COMPORTEMENT/DEFORMATION") && e.contains("ELEMENTSSI_1"),
        "{e}"
    );
}

#[test]
fn affe_modele_errors() {
    // AXIS and 3D in one model.
    let comm = quarter(
        "MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=(\
         _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'),\n\
         _F(GROUP_MA='VOL', PHENOMENE='MECANIQUE', MODELISATION='AXIS')))",
    );
    let (_, err) = run("sdnv103h", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_MODELE/AFFE/MODELISATION",
        &["cannot mix", "occurrence 1 of AFFE uses 3D"],
        "MODELISATION='AXIS'",
    );

    // A modelisation outside aster's list (a shell): refused when the
    // file is checked, before any command. (C_PLAN, refused here until
    // 2026-11-28, is built: tests/c_plan.rs.)
    let comm = axis("MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DKT'))");
    let mut messages = String::new();
    let checked = parse_and_check(
        &Source::new("test.comm", comm.as_str()),
        &commands::all(),
        &mut messages,
    );
    assert!(checked.is_none(), "{messages}");
    assert!(
        messages.contains("AFFE_MODELE/AFFE/MODELISATION") && messages.contains("DKT"),
        "{messages}"
    );
    let comm = axis("MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))");
    let mut messages = String::new();
    assert!(
        parse_and_check(
            &Source::new("test.comm", comm.as_str()),
            &commands::all(),
            &mut messages,
        )
        .is_some(),
        "{messages}"
    );

    // 3D on a 2D mesh: the QUAD8 cells are only faces, no volume element.
    let comm = axis("MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_MODELE/AFFE",
        &["no volume element", "MODELE1_6"],
        "AFFE_MODELE",
    );

    // 3D_SI alone on the SEG3 axis: nothing at all assigned.
    let comm = axis("MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='AXE', PHENOMENE='MECANIQUE', MODELISATION='3D_SI'))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_MODELE/AFFE",
        &["no finite element could be assigned", "MODELE1_6"],
        "AFFE_MODELE",
    );

    // An unknown group, with the closest name suggested.
    let comm = axis("MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL_RIGG', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_MODELE/AFFE/GROUP_MA",
        &[
            "no cell group (GROUP_MA) 'VOL_RIGG'",
            "did you mean 'VOL_RIG'",
        ],
        "VOL_RIGG",
    );
}

// ---------------------------------------------------------------------------
// DEFI_MATERIAU, AFFE_MATERIAU

#[test]
fn defi_materiau_checks_and_defaults() {
    let comm = axis(
        "M1 = DEFI_MATERIAU(ELAS=_F(E=117.E3, NU=0.35),\n\
         ECRO_COOK=_F(A=90., B=292., N_PUIS=0.31))",
    );
    let (s, err) = run("sdnv103b", &comm);
    assert!(err.is_none(), "{err:?}");
    // Without C/EPSP0 and M_PUIS/TROOM/TMELT the law's absent values are
    // stored (nmtevp: no rate term, TROOM=-1 disables softening).
    let m = material(&s, "M1");
    assert_eq!(m.get("ECRO_COOK", "A"), Some(90.0));
    assert_eq!(m.get("ECRO_COOK", "C"), Some(0.0));
    assert_eq!(m.get("ECRO_COOK", "EPSP0"), Some(1.0));
    assert_eq!(m.get("ECRO_COOK", "TROOM"), Some(-1.0));
    assert_eq!(m.get("ECRO_COOK", "TMELT"), Some(1.0));
    assert_eq!(m.get("ECRO_COOK", "M_PUIS"), Some(0.0));

    // E_T >= E is fatal (COMPOR1_54).
    let comm = axis(
        "M1 = DEFI_MATERIAU(ELAS=_F(E=100., NU=0.3),\n\
         ECRO_LINE=_F(D_SIGM_EPSI=100., SY=1.))",
    );
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_MATERIAU/ECRO_LINE/D_SIGM_EPSI",
        &["COMPOR1_54", "must be smaller than Young's modulus"],
        "D_SIGM_EPSI",
    );

    // Hardening without elasticity.
    let comm = axis("M1 = DEFI_MATERIAU(ECRO_LINE=_F(D_SIGM_EPSI=100., SY=1.))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_MATERIAU/ECRO_LINE",
        &["needs ELAS"],
        "DEFI_MATERIAU",
    );
}

/// On the block, covered by both occurrences, the last one wins.
#[test]
fn affe_materiau_last_occurrence_wins() {
    let comm = axis(
        "M1 = DEFI_MATERIAU(ELAS=_F(E=1., NU=0.3))\n\
         M2 = DEFI_MATERIAU(ELAS=_F(E=2., NU=0.3))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=(_F(TOUT='OUI', MATER=M1), _F(GROUP_MA='VOL_RIG', MATER=M2)))\n\
         CM2 = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL', MATER=M2))",
    );
    let (s, err) = run("sdnv103b", &comm);
    assert!(err.is_none(), "{err:?}");
    let mesh = mesh(&s, "MAIL");
    let block = &mesh.cell_groups["VOL_RIG"];
    let cm = matfield(&s, "CM");
    for (c, m) in cm.cell_material.iter().enumerate() {
        let want = if block.contains(&c) { "M2" } else { "M1" };
        assert_eq!(m.as_deref(), Some(want));
    }
    // Cells outside every occurrence have no material.
    let cm2 = matfield(&s, "CM2");
    assert_eq!(cm2.cell_material.iter().flatten().count(), 100);
}

// ---------------------------------------------------------------------------
// AFFE_CHAR_MECA

#[test]
fn ddl_impo_on_the_quarter() {
    // The block is one HEXA8 (8 nodes, 3 dofs each); TOUT is every node of
    // the model, i.e. all 73 mesh nodes; SANS_GROUP_NO removes one node.
    let comm = quarter_3d(
        "CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_MA='VOL_RIG', DX=0., DY=0., DZ=1.5))\n\
         CH2 = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(TOUT='OUI', SANS_GROUP_NO='A1', DZ=0.))\n\
         CH3 = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='A1', LIAISON='ENCASTRE'))",
    );
    let (s, err) = run("sdnv103h", &comm);
    assert!(err.is_none(), "{err:?}");
    let ch = load(&s, "CH");
    assert_eq!(ch.imposed.len(), 24);
    assert_eq!(
        ch.imposed
            .iter()
            .filter(|d| d.dof == Dof::Dz && d.value == 1.5)
            .count(),
        8
    );
    let ch2 = load(&s, "CH2");
    assert_eq!(ch2.imposed.len(), 72);
    let a1 = mesh(&s, "MAIL").node_groups["A1"][0];
    assert!(ch2.imposed.iter().all(|d| d.node != a1));
    let ch3 = load(&s, "CH3");
    assert_eq!(ch3.imposed.len(), 3);
    assert!(ch3.imposed.iter().all(|d| d.node == a1 && d.value == 0.0));
}

#[test]
fn ddl_impo_errors() {
    // DZ on an axisymmetric model.
    let comm =
        axis_mo("CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='AXE',\n DX=0., DZ=0.))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_CHAR_MECA/DDL_IMPO/DZ",
        &["DZ is not a degree of freedom of the model MO", "DX, DY"],
        "DZ=0.",
    );
    // An unknown node group.
    let comm = axis_mo("CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='AXES', DX=0.))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_CHAR_MECA/DDL_IMPO/GROUP_NO",
        &["'AXES'", "did you mean 'AXE'"],
        "AXES",
    );
    // Nodes outside the model: the block is not in this model.
    let comm = axis(
        "MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_MA='VOL_RIG', DX=0.))",
    );
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_CHAR_MECA/DDL_IMPO",
        &[
            "8 of the nodes of GROUP_MA=VOL_RIG",
            "belong to no cell of the model MO",
        ],
        "AFFE_CHAR_MECA",
    );
}

/// PESANTEUR: DIRECTION is normalised (code_aster's `capesa`), GROUP_MA
/// restricts the cells, no GROUP_MA means every cell; a load may hold
/// only PESANTEUR.
#[test]
fn pesanteur_on_the_quarter() {
    let comm = quarter_3d(
        "PES = AFFE_CHAR_MECA(MODELE=MO, PESANTEUR=_F(GRAVITE=9810., DIRECTION=(0., 3., -4.)))\n\
         PES2 = AFFE_CHAR_MECA(MODELE=MO, PESANTEUR=_F(GRAVITE=1., DIRECTION=(0., 0., -1.),\n\
         GROUP_MA='VOL_RIG'), DDL_IMPO=_F(GROUP_MA='VOL_RIG', DZ=0.))",
    );
    let (s, err) = run("sdnv103h", &comm);
    assert!(err.is_none(), "{err:?}");
    let g = load(&s, "PES").gravity.clone().unwrap();
    assert_eq!(g.g, 9810.0);
    assert_eq!(g.direction, [0.0, 0.6, -0.8]);
    assert_eq!(g.cells, None);
    assert!(load(&s, "PES").imposed.is_empty());
    let g2 = load(&s, "PES2").gravity.clone().unwrap();
    let m = mesh(&s, "MAIL");
    assert_eq!(g2.cells.as_deref(), Some(&m.cell_groups["VOL_RIG"][..]));
    assert_eq!(load(&s, "PES2").imposed.len(), 8);
}

#[test]
fn pesanteur_errors() {
    // A zero direction (code_aster's fatal CHARGES2_53).
    let comm = quarter_3d(
        "PES = AFFE_CHAR_MECA(MODELE=MO, PESANTEUR=_F(GRAVITE=9810.,\n DIRECTION=(0., 0., 0.)))",
    );
    let (_, err) = run("sdnv103h", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_CHAR_MECA/PESANTEUR/DIRECTION",
        &["non-zero vector"],
        "DIRECTION=",
    );
    // Only skin cells: no volume to carry a weight.
    let comm = quarter_3d(
        "PES = AFFE_CHAR_MECA(MODELE=MO, PESANTEUR=_F(GRAVITE=9810., DIRECTION=(0., 0., -1.),\n GROUP_MA='RIGID'))",
    );
    let (_, err) = run("sdnv103h", &comm);
    assert_error(
        &comm,
        err,
        "AFFE_CHAR_MECA/PESANTEUR/GROUP_MA",
        &["no volume element"],
        "GROUP_MA='RIGID'",
    );
}

// ---------------------------------------------------------------------------
// CREA_CHAMP

/// Components are the union in order of first appearance; later
/// occurrences overwrite pair by pair; pairs never given stay absent.
#[test]
fn crea_champ_override_and_absent_pairs() {
    let comm = axis_mo(
        "V = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO, AFFE=(\
         _F(GROUP_MA='VOL', NOM_CMP='DY', VALE=-5.),\
         _F(GROUP_MA='VOL_RIG', NOM_CMP=('DX', 'LAGS_C'), VALE=(1., 2.)),\
         _F(GROUP_NO='AXE', NOM_CMP=('LAGS_C', 'DY'), VALE=(3., 4.))))",
    );
    let (s, err) = run("sdnv103b", &comm);
    assert!(err.is_none(), "{err:?}");
    let mesh = mesh(&s, "MAIL");
    let v = field(&s, "V");
    assert_eq!(v.components, vec!["DY", "DX", "LAGS_C"]);
    let axe = &mesh.node_groups["AXE"];
    for n in 0..mesh.nnodes() {
        let on_block = mesh.coords[n][1] <= 0.0;
        let on_axe = axe.contains(&n);
        let dy = if on_axe {
            Some(4.0)
        } else if on_block {
            None
        } else {
            Some(-5.0)
        };
        assert_eq!(v.get(n, "DY"), dy, "node {n}");
        assert_eq!(v.get(n, "DX"), on_block.then_some(1.0), "node {n}");
        let lags = if on_axe {
            Some(3.0)
        } else if on_block {
            Some(2.0)
        } else {
            None
        };
        assert_eq!(v.get(n, "LAGS_C"), lags, "node {n}");
    }
    // The absent count in the message file: block nodes lack DY (8), bar
    // nodes off the axis lack DX and LAGS_C, axis nodes lack DX.
    let bar = 351;
    let absent = 8 + 2 * (bar - 41) + 41;
    assert!(s.mess.contains(&format!("{absent} absent")), "{}", s.mess);
}

#[test]
fn crea_champ_errors() {
    let head = "V = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO,\n AFFE=";
    // NOM_CMP and VALE of different lengths.
    let comm = axis_mo(&format!(
        "{head}_F(TOUT='OUI', NOM_CMP=('DX', 'DY'), VALE=0.))"
    ));
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "CREA_CHAMP/AFFE/VALE",
        &["NOM_CMP gives 2 component(s) and VALE 1 value(s)"],
        "VALE=0.",
    );
    // DZ on the AXIS model.
    let comm = axis_mo(&format!("{head}_F(TOUT='OUI', NOM_CMP='DZ', VALE=0.))"));
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "CREA_CHAMP/AFFE/NOM_CMP",
        &["DZ is not a degree of freedom of the model MO"],
        "NOM_CMP='DZ'",
    );
    // Not a DEPL_R component.
    let comm = axis_mo(&format!("{head}_F(TOUT='OUI', NOM_CMP='DYY', VALE=0.))"));
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "CREA_CHAMP/AFFE/NOM_CMP",
        &[
            "not a component of the quantity DEPL_R",
            "did you mean 'DY'",
        ],
        "NOM_CMP='DYY'",
    );
    // On a mesh, no model: DZ is a DEPL_R component and is accepted.
    let comm = axis(
        "V = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MAILLAGE=MAIL,\
         AFFE=_F(GROUP_NO='A1', NOM_CMP='DZ', VALE=7.))",
    );
    let (s, err) = run("sdnv103b", &comm);
    assert!(err.is_none(), "{err:?}");
    let v = field(&s, "V");
    let a1 = mesh(&s, "MAIL").node_groups["A1"][0];
    assert_eq!(v.get(a1, "DZ"), Some(7.0));
    assert_eq!(v.values.iter().filter(|x| !x.is_nan()).count(), 1);
}

// ---------------------------------------------------------------------------
// DEFI_LIST_INST

fn manuel(subd_pas: usize, subd_niveau: usize, subd_pas_mini: f64) -> Action {
    Action::Decoupe(Subdivision::Manuel {
        subd_pas,
        subd_niveau,
        subd_pas_mini,
    })
}

#[test]
fn defi_list_inst_defaults_and_implicit_error_rule() {
    let comm = axis(
        "L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=4))\n\
         D0 = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=L))\n\
         D1 = DEFI_LIST_INST(DEFI_LIST=_F(VALE=(0., 0.5, 2.)),\
              ECHEC=_F(EVENEMENT='COLLISION', SUBD_INST=0.1, SUBD_DUREE=0.3))\n\
         D2 = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=L), ECHEC=(\
              _F(EVENEMENT='ERREUR', SUBD_NIVEAU=2),\
              _F(EVENEMENT='DELTA_GRANDEUR', VALE_REF=0.1, NOM_CHAM='DEPL', NOM_CMP='DX', SUBD_NIVEAU=5)))\n\
         D3 = DEFI_LIST_INST(METHODE='AUTO', DEFI_LIST=_F(LIST_INST=L, PAS_MINI=1.E-6, PAS_MAXI=0.5, NB_PAS_MAXI=100))",
    );
    let (s, err) = run("sdnv103b", &comm);
    assert!(err.is_none(), "{err:?}");

    // No ECHEC: only the implicit ERREUR rule, with SUBD_PAS_MINI 1e-12
    // (not the catalogue's 0).
    let d0 = timelist(&s, "D0");
    assert_eq!(d0.instants, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    assert_eq!(d0.rules.len(), 1);
    assert_eq!(d0.on_error(), &manuel(4, 3, 1e-12));
    assert_eq!(d0.nb_pas_maxi, 1_000_000);
    assert!(d0.adaptation.is_empty());

    // COLLISION alone: its AUTO refinement, plus the implicit ERREUR rule.
    let d1 = timelist(&s, "D1");
    assert_eq!(d1.instants, vec![0.0, 0.5, 2.0]);
    assert_eq!(d1.rules.len(), 2);
    assert_eq!(d1.rules[0].event, Event::Collision);
    assert_eq!(
        d1.rules[0].action,
        Action::Decoupe(Subdivision::AutoCollision {
            subd_inst: 0.1,
            subd_duree: 0.3
        })
    );
    assert_eq!(d1.on_error(), &manuel(4, 3, 1e-12));

    // The level limit is shared: the largest SUBD_NIVEAU applies.
    let d2 = timelist(&s, "D2");
    assert_eq!(d2.on_error(), &manuel(4, 2, 0.0));
    assert_eq!(d2.max_subd_niveau(), Some(5));

    let d3 = timelist(&s, "D3");
    assert!(d3.auto);
    assert_eq!(d3.pas_mini, Some(1e-6));
    assert_eq!(d3.pas_maxi, Some(0.5));
    assert_eq!(d3.nb_pas_maxi, 100);
    assert_eq!(d3.max_subd_niveau(), None);
    // ADAPTATION defaulted: after 2 steps within the Newton-iteration
    // threshold, grow by 100 %.
    assert_eq!(d3.adaptation.len(), 1);
    assert_eq!(
        d3.adaptation[0].mode,
        aster::time::list::TplusMode::Fixe { pcent_augm: 100.0 }
    );
}

#[test]
fn defi_list_inst_errors() {
    // SUBD_PAS_MINI above the smallest step (0.25).
    let comm = axis(
        "L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=4))\n\
         D = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=L),\n ECHEC=_F(EVENEMENT='ERREUR', SUBD_PAS_MINI=0.3))",
    );
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_LIST_INST/ECHEC/SUBD_PAS_MINI",
        &["DISCRETISATION_6", "smallest step of the list, 2.5e-1"],
        "SUBD_PAS_MINI=0.3",
    );
    // Steps below the implicit rule's 1e-12.
    let comm = axis("D = DEFI_LIST_INST(DEFI_LIST=_F(VALE=(0., 1.E-13)))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_LIST_INST/DEFI_LIST",
        &["implicit ERREUR rule", "DISCRETISATION_6"],
        "DEFI_LIST_INST",
    );
    // Instants not increasing.
    let comm = axis("D = DEFI_LIST_INST(DEFI_LIST=_F(VALE=(0., 2., 1.)))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_LIST_INST/DEFI_LIST/VALE",
        &["strictly increasing: instant 3"],
        "VALE=",
    );
    // ERREUR given twice.
    let comm = axis(
        "D = DEFI_LIST_INST(DEFI_LIST=_F(VALE=(0., 1.)), ECHEC=(_F(EVENEMENT='ERREUR'),\n\
         _F(EVENEMENT='ERREUR', ACTION='ARRET')))",
    );
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_LIST_INST/ECHEC/EVENEMENT",
        &["ERREUR is given twice (occurrences 1 and 2"],
        "ACTION='ARRET'",
    );
    // A step cap that is not positive (the run would never move on).
    let comm =
        axis("D = DEFI_LIST_INST(METHODE='AUTO',\n DEFI_LIST=_F(VALE=(0., 1.), PAS_MAXI=0.))");
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_LIST_INST/DEFI_LIST/PAS_MAXI",
        &["PAS_MAXI = 0e0 must be a positive finite step"],
        "PAS_MAXI=0.",
    );
}

// ---------------------------------------------------------------------------
// DEFI_CONTACT

#[test]
fn defi_contact_checks() {
    let zone = "ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ',\n";
    // DISCRETE + COULOMB with the catalogue's ALGO_CONT='CONTRAINTE':
    // code_aster's CONTACT3_3 at DEFI_CONTACT; aster accepts it for the
    // kinematic contact of explicit dynamics and says so (an implicit
    // DYNA_NON_LINE refuses it: tests/contact_def.rs).
    let comm = axis_mo(&format!(
        "MAIL = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ORIE_PEAU_2D=_F(GROUP_MA=('SZZ', 'RIGID')))\n\
         C = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', FROTTEMENT='COULOMB', {zone} COULOMB=0.25, E_T=1.E5))"
    ));
    let (study, err) = run("sdnv103b", &comm);
    assert!(err.is_none(), "{err:?}");
    assert!(
        study.mess.contains("only for an explicit DYNA_NON_LINE")
            && study.mess.contains("CONTACT3_3"),
        "{}",
        study.mess
    );
    // A slave group that does not exist.
    let comm = axis_mo(
        "C = DEFI_CONTACT(MODELE=MO, ZONE=_F(GROUP_MA_MAIT='RIGID',\n GROUP_MA_ESCL='SZ'))",
    );
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_CONTACT/ZONE/GROUP_MA_ESCL",
        &["'SZ'", "did you mean 'SZZ'"],
        "GROUP_MA_ESCL='SZ'",
    );
    // A volume group as contact surface.
    let comm = axis_mo(
        "C = DEFI_CONTACT(MODELE=MO, ZONE=_F(GROUP_MA_MAIT='VOL_RIG',\n GROUP_MA_ESCL='SZZ'))",
    );
    let (_, err) = run("sdnv103b", &comm);
    assert_error(
        &comm,
        err,
        "DEFI_CONTACT/ZONE/GROUP_MA_MAIT",
        &["holds a QUAD8 cell", "dimension 1"],
        "DEFI_CONTACT",
    );
    // Frictionless discrete contact with the default algorithm is kept
    // (on outward skins: the mesh's RIGID edge points into the foundation
    // until ORIE_PEAU_2D turns it, as the study does; VERI_NORM checks it).
    let comm = axis_mo(&format!(
        "MAIL = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ORIE_PEAU_2D=_F(GROUP_MA=('SZZ', 'RIGID')))\n\
         C = DEFI_CONTACT(MODELE=MO, {zone}))"
    ));
    let (s, err) = run("sdnv103b", &comm);
    assert!(err.is_none(), "{err:?}");
    match data(&s, "C") {
        ConceptData::Contact(a) => {
            assert_eq!(
                a.fact("ZONE").and_then(|z| z.text("ALGO_CONT")),
                Some("CONTRAINTE")
            );
        }
        d => panic!("{d:?}"),
    }
}
