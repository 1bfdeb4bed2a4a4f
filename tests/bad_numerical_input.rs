//! Bad numerical input is refused before the first step, with a message
//! that says where (issue 16): an element with a non-positive Jacobian at
//! a Gauss point, NU at or beyond its limits, a density RHO <= 0 on a
//! dynamic model, a time list that does not increase, a contact surface
//! whose normals point into the body. Each case is built here (meshes
//! written by the test from the SDNV103 meshes), run through the checker
//! and the runner, and the error's text, command/keyword path and line are
//! checked, and that no result was computed.

use std::path::{Path, PathBuf};

use aster::commands;
use aster::diag::Source;
use aster::medio::{read_mesh, write_mesh};
use aster::mesh::ops::{orie_peau, OrieDim};
use aster::mesh::Mesh;
use aster::run::driver::parse_and_check;
use aster::study::Study;

/// Runs `comm` with unit 20 mapped to `mesh`; returns the study and the
/// rendered error, if the run stopped on one.
fn run(mesh: &Path, comm: &str, tag: &str) -> (Study, Option<String>) {
    let src = Source::new("test.comm", comm);
    let registry = commands::all();
    let mut messages = String::new();
    let checked = parse_and_check(&src, &registry, &mut messages);
    let mut study = Study {
        out_dir: Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("bad_input_{tag}")),
        stem: "test".into(),
        ..Study::default()
    };
    let Some(program) = checked else {
        // Refused by the checker: nothing ran.
        return (study, Some(messages));
    };
    study.units.map.insert(20, mesh.to_path_buf());
    let err = aster::run::execute(&mut study, &program, &registry, &src)
        .err()
        .map(|d| d.render(Some(&src)));
    (study, err)
}

fn root_mesh(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("med/{name}.mmed"))
}

/// Writes `mesh` into the test's scratch directory.
fn scratch_mesh(mesh: &Mesh, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bad_input_meshes");
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let path = dir.join(name);
    write_mesh(&path, mesh).expect("the mesh is written");
    path
}

/// The 1-based line of the first line of `text` containing `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("'{needle}' not in the command file"))
        + 1
}

/// The error names `path` on its first line, contains every word, and
/// points at the line of `at`.
fn assert_error(comm: &str, err: &Option<String>, path: &str, words: &[&str], at: &str) {
    let e = err.as_deref().expect("the run should stop on an error");
    let first = e.lines().next().unwrap_or_default();
    assert!(first.contains(path), "expected {path} in:\n{e}");
    for w in words {
        assert!(e.contains(w), "expected '{w}' in:\n{e}");
    }
    let loc = format!("test.comm:{}:", line_of(comm, at));
    assert!(e.contains(&loc), "expected location {loc} in:\n{e}");
}

/// No step was computed: the step table of DYNA_NON_LINE never started
/// and the result concept does not exist.
fn assert_no_step(study: &Study, result: &str) {
    assert!(
        !study.mess.contains("RESI_GLOB_RELA"),
        "a step was started:\n{}",
        study.mess
    );
    assert!(study.concepts.data(result).is_none(), "{result} exists");
}

/// The free flight of the modelling D bar (sdnv103d mesh, group VOL) with
/// the given material line, up to DYNA_NON_LINE.
fn free_flight(material: &str) -> String {
    format!(
        "DEBUT()\n\
         MAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))\n\
         {material}\n\
         CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL', MATER=CUIVRE))\n\
         VITINI = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO,\n\
         AFFE=_F(GROUP_MA='VOL', NOM_CMP=('DX', 'DY'), VALE=(0., -227000.)))\n\
         L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-6, NOMBRE=2))\n\
         RES = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT,\n\
         COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', DEFORMATION='SIMO_MIEHE', GROUP_MA='VOL'),\n\
         ETAT_INIT=_F(VITE=VITINI), INCREMENT=_F(LIST_INST=L_INST),\n\
         SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))\n\
         FIN()\n"
    )
}

const CUIVRE: &str = "CUIVRE = DEFI_MATERIAU(ELAS=_F(E=117.E3, NU=0.35, RHO=8.93E-9), ECRO_LINE=_F(D_SIGM_EPSI=100., SY=400.))";

#[test]
fn the_free_flight_runs_with_good_input() {
    // The control: the same file with a valid material and mesh runs.
    let comm = free_flight(CUIVRE);
    let (study, err) = run(&root_mesh("sdnv103d"), &comm, "control");
    assert!(err.is_none(), "{err:?}");
    assert!(study.concepts.data("RES").is_some());
}

#[test]
fn an_inverted_cell_is_refused_before_the_first_step() {
    let mut mesh = read_mesh(&root_mesh("sdnv103d"), None).expect("sdnv103d mesh");
    let cell = mesh.cell_groups["VOL"][1];
    // Reverse the QUAD8's node order: the cell turns clockwise, and its
    // Jacobian is negative at every point.
    let n = mesh.cells[cell].nodes.clone();
    mesh.cells[cell].nodes = [3, 2, 1, 0, 6, 5, 4, 7].iter().map(|&k| n[k]).collect();
    let path = scratch_mesh(&mesh, "inverted_cell.mmed");
    let comm = free_flight(CUIVRE);
    let (study, err) = run(&path, &comm, "inverted");
    let name = format!("cell M{} (", cell + 1);
    assert_error(
        &comm,
        &err,
        "DYNA_NON_LINE/MODELE",
        &[
            &name,
            "MEAXQU8 QUAD8",
            "group(s) VOL",
            "non-positive Jacobian -",
            "at Gauss point 1 of its FPG9 family",
            "before the first step",
        ],
        "RES = DYNA_NON_LINE",
    );
    assert_no_step(&study, "RES");
    // AFFE_MODELE's VERI_JACOBIEN already warned, naming the group and
    // the cell.
    for alarm in [
        "1 element(s) have a non-positive or vanishing Jacobian determinant (inverted or degenerate cells) in group(s) VOL".to_string(),
        format!("(first: cell M{}, smallest det J -", cell + 1),
    ] {
        assert!(study.mess.contains(&alarm), "{alarm} in:\n{}", study.mess);
    }
}

#[test]
fn a_cell_folded_near_one_corner_is_located() {
    // The mid-side node of an edge slid along it to 95 % of the way to a
    // corner: the corners stay where they were, but the map folds near
    // that corner and the Jacobian is negative at the Gauss point next to
    // it (for a square: one of the 9 points, det J = -0.31 x its area/4).
    let mut mesh = read_mesh(&root_mesh("sdnv103d"), None).expect("sdnv103d mesh");
    let cell = mesh.cell_groups["VOL"][0];
    let nodes = mesh.cells[cell].nodes.clone();
    let (a, b, mid) = (nodes[0], nodes[1], nodes[4]);
    let (pa, pb) = (mesh.coords[a], mesh.coords[b]);
    mesh.coords[mid] = [
        pa[0] + 0.95 * (pb[0] - pa[0]),
        pa[1] + 0.95 * (pb[1] - pa[1]),
        0.0,
    ];
    // The node is shared with the neighbour across that edge, if any,
    // which folds the same way: the error names one of them.
    let holders: Vec<usize> = (0..mesh.ncells())
        .filter(|&c| mesh.cells[c].kind.dim() == 2 && mesh.cells[c].nodes.contains(&mid))
        .collect();
    let path = scratch_mesh(&mesh, "folded_cell.mmed");
    let comm = free_flight(CUIVRE);
    let (study, err) = run(&path, &comm, "folded");
    assert_error(
        &comm,
        &err,
        "DYNA_NON_LINE/MODELE",
        &["non-positive Jacobian -", "Gauss point", "group(s) VOL"],
        "RES = DYNA_NON_LINE",
    );
    let e = err.unwrap();
    assert!(
        holders
            .iter()
            .any(|c| e.contains(&format!("cell M{} (", c + 1))),
        "one of the cells {holders:?} (0-based) is named:\n{e}"
    );
    assert_no_step(&study, "RES");
}

#[test]
fn a_zero_or_negative_density_is_refused_on_a_dynamic_model() {
    for rho in ["0.", "-8.93E-9"] {
        let comm = free_flight(&format!(
            "CUIVRE = DEFI_MATERIAU(ELAS=_F(E=117.E3, NU=0.35, RHO={rho}), ECRO_LINE=_F(D_SIGM_EPSI=100., SY=400.))"
        ));
        let (study, err) = run(&root_mesh("sdnv103d"), &comm, "rho");
        let value: f64 = rho.parse().unwrap();
        assert_error(
            &comm,
            &err,
            "DYNA_NON_LINE/CHAM_MATER",
            &[
                "the material CUIVRE (DEFI_MATERIAU, ELAS/RHO = ",
                &format!("RHO = {value:e})"),
                "group(s) VOL",
                "needs a density RHO > 0",
            ],
            "CHAM_MATER=CHMAT",
        );
        assert_no_step(&study, "RES");
    }
    // A material without RHO at all.
    let comm = free_flight(
        "CUIVRE = DEFI_MATERIAU(ELAS=_F(E=117.E3, NU=0.35), ECRO_LINE=_F(D_SIGM_EPSI=100., SY=400.))",
    );
    let (study, err) = run(&root_mesh("sdnv103d"), &comm, "no_rho");
    assert_error(
        &comm,
        &err,
        "DYNA_NON_LINE/COMPORTEMENT",
        &["material CUIVRE: ELAS/RHO is needed by the mass matrix"],
        "COMPORTEMENT=_F",
    );
    assert_no_step(&study, "RES");
}

#[test]
fn nu_at_its_limits_or_beyond_is_refused() {
    // The limits of the catalogue's range: accepted by the checker,
    // refused by DEFI_MATERIAU as no material.
    for (nu, word) in [("0.5", "incompressible limit"), ("-1.", "shear modulus")] {
        let comm = free_flight(&format!(
            "CUIVRE = DEFI_MATERIAU(ELAS=_F(E=117.E3, NU={nu}, RHO=8.93E-9))"
        ));
        let (study, err) = run(&root_mesh("sdnv103d"), &comm, "nu_limit");
        assert_error(
            &comm,
            &err,
            "DEFI_MATERIAU/ELAS/NU",
            &[word],
            &format!("NU={nu}"),
        );
        assert_no_step(&study, "RES");
    }
    // Beyond: the catalogue's bounds (checked before anything runs).
    for nu in ["0.6", "-1.5"] {
        let comm = free_flight(&format!(
            "CUIVRE = DEFI_MATERIAU(ELAS=_F(E=117.E3, NU={nu}, RHO=8.93E-9))"
        ));
        let (study, err) = run(&root_mesh("sdnv103d"), &comm, "nu_range");
        let e = err.expect("refused by the checker");
        assert!(e.contains("DEFI_MATERIAU/ELAS/NU"), "{e}");
        assert!(
            e.contains(&format!(
                "test.comm:{}:",
                line_of(&comm, &format!("NU={nu}"))
            )),
            "{e}"
        );
        assert!(e.contains("nothing was run"), "{e}");
        assert!(study.concepts.data("CUIVRE").is_none());
    }
}

/// Steps of 1e-16 s and below are fine when written with VALE (the
/// snap to 0 is DEFI_LIST_REEL's INTERVALLE rule only): the free flight
/// over 2 steps of 1e-30 s moves the bar by v·t = 227000 × 2e-30 (no
/// force acts on it), and steps of 1e-15 from 0 by INTERVALLE still run.
#[test]
fn tiny_steps_run_when_the_list_holds_them() {
    let base = free_flight(CUIVRE);
    let list = "L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-6, NOMBRE=2))";
    for (line, tag) in [
        (
            "L_INST = DEFI_LIST_REEL(VALE=(0., 1.E-30, 2.E-30))",
            "tiny_vale",
        ),
        (
            "L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=2.E-15, NOMBRE=2))",
            "tiny_nombre",
        ),
    ] {
        let comm = base.replace(list, line);
        let (study, err) = run(&root_mesh("sdnv103d"), &comm, tag);
        assert!(err.is_none(), "{tag}: {err:?}");
        let Some(aster::concepts::ConceptData::Result(r)) = study.concepts.data("RES") else {
            panic!("{tag}: no result");
        };
        assert_eq!(r.steps.len(), 3, "{tag}");
        let t = r.steps[2].inst;
        let dy = r.steps[2].nodal["DEPL"].get(0, "DY").expect("DY of N1");
        assert!(
            ((dy - (-227000.0 * t)) / (227000.0 * t)).abs() < 1e-9,
            "{tag}: DY {dy:e} at t {t:e}"
        );
    }
}

#[test]
fn a_time_list_that_does_not_increase_is_refused() {
    let base = free_flight(CUIVRE);
    let cases = [
        (
            "L_INST = DEFI_LIST_REEL(VALE=(0., 1.E-6, 5.E-7))",
            "DEFI_LIST_REEL/VALE",
            "strictly increasing",
        ),
        (
            "L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=-1.E-6, NOMBRE=2))",
            "DEFI_LIST_REEL/INTERVALLE/JUSQU_A",
            "",
        ),
        // Steps of 1e-30 s from 0 (probe s7b D5): code_aster's snap of
        // |v| <= 2.2e-16 to 0 puts every value back on 0. It said "the
        // list must hold at least 2 strictly increasing instants" at
        // DYNA_NON_LINE, of a list written as 11 increasing instants.
        (
            "L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-29, NOMBRE=10))",
            "DEFI_LIST_REEL/INTERVALLE/NOMBRE",
            "from 0e0 is not above the machine precision 2.220446049250313e-16",
        ),
        (
            "L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-15, PAS=1.E-16))",
            "DEFI_LIST_REEL/INTERVALLE/PAS",
            "give such instants with VALE=(...)",
        ),
    ];
    for (line, path, word) in cases {
        let comm = base.replace(
            "L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-6, NOMBRE=2))",
            line,
        );
        let (study, err) = run(&root_mesh("sdnv103d"), &comm, "time_list");
        assert_error(&comm, &err, path, &[word], "L_INST =");
        assert_no_step(&study, "RES");
    }
}

/// The SDNV103 B contact definition on `mesh`, with `orient` (a
/// MODI_MAILLAGE line or nothing) before it and `veri` in DEFI_CONTACT.
fn contact_b(orient: &str, veri: &str) -> String {
    format!(
        "DEBUT()\n\
         MAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
         {orient}\n\
         MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))\n\
         CONT = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE',{veri}\n\
         ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', ALGO_CONT='PENALISATION', E_N=1.E10))\n\
         FIN()\n"
    )
}

#[test]
fn a_contact_surface_with_inward_normals_is_refused() {
    // Outward skins (ORIE_PEAU_2D as the study does), then one cell of
    // the slave surface SZZ turned over.
    let mut mesh = read_mesh(&root_mesh("sdnv103b"), None).expect("sdnv103b mesh");
    orie_peau(&mut mesh, OrieDim::D2, &["SZZ", "RIGID"], None).expect("orientation");
    let outward = scratch_mesh(&mesh, "contact_outward.mmed");
    let szz = mesh.cell_groups["SZZ"].clone();
    let cell = szz[szz.len() / 2];
    let n = mesh.cells[cell].nodes.clone();
    mesh.cells[cell].nodes = vec![n[1], n[0], n[2]];
    let one_inward = scratch_mesh(&mesh, "contact_one_inward.mmed");

    // Control: outward normals pass.
    let comm = contact_b("", "");
    let (study, err) = run(&outward, &comm, "contact_ok");
    assert!(err.is_none(), "{err:?}");
    assert!(study.concepts.data("CONT").is_some());

    let (study, err) = run(&one_inward, &comm, "contact_inward");
    assert_error(
        &comm,
        &err,
        "DEFI_CONTACT/ZONE/GROUP_MA_ESCL",
        &[
            &format!(
                "zone 1: the normals of 1 of the {} cells of GROUP_MA_ESCL='SZZ' point into the body",
                szz.len()
            ),
            &format!("(first: cell M{}, on cell M", cell + 1),
            "MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ORIE_PEAU_2D=_F(GROUP_MA='SZZ'))",
        ],
        "ZONE=_F",
    );
    assert!(study.concepts.data("CONT").is_none());

    // The advice works: orienting the skin in the file clears the error.
    let comm = contact_b(
        "MAIL = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ORIE_PEAU_2D=_F(GROUP_MA='SZZ'))",
        "",
    );
    let (_, err) = run(&one_inward, &comm, "contact_fixed");
    assert!(err.is_none(), "{err:?}");

    // VERI_NORM='NON' skips the check, as in code_aster.
    let comm = contact_b("", " VERI_NORM='NON',");
    let (_, err) = run(&one_inward, &comm, "contact_unchecked");
    assert!(err.is_none(), "{err:?}");

    // The master surface is checked too: every RIGID cell turned over.
    let mut mesh = read_mesh(&outward, None).expect("outward mesh");
    let rigid = mesh.cell_groups["RIGID"].clone();
    for &c in &rigid {
        let n = mesh.cells[c].nodes.clone();
        mesh.cells[c].nodes = vec![n[1], n[0], n[2]];
    }
    let master_inward = scratch_mesh(&mesh, "contact_master_inward.mmed");
    let comm = contact_b("", "");
    let (_, err) = run(&master_inward, &comm, "contact_master");
    assert_error(
        &comm,
        &err,
        "DEFI_CONTACT/ZONE/GROUP_MA_MAIT",
        &[&format!(
            "the normals of {0} of the {0} cells of GROUP_MA_MAIT='RIGID' point into the body",
            rigid.len()
        )],
        "ZONE=_F",
    );
}

/// The modelling D bar held on its face SZZ (DY) and axis (DX), pulled at
/// its top node A2 by `load` (an AFFE_CHAR_MECA line defining TR), in
/// `command` (STAT_NON_LINE, DYNA_NON_LINE or MECA_STATIQUE) with `excit`
/// for TR.
fn pulled_bar(load: &str, command: &str, excit: &str) -> String {
    let steps = match command {
        "STAT_NON_LINE" => {
            "COMPORTEMENT=_F(RELATION='ELAS', GROUP_MA='VOL'), INCREMENT=_F(LIST_INST=L_INST)"
        }
        "DYNA_NON_LINE" => {
            "COMPORTEMENT=_F(RELATION='ELAS', GROUP_MA='VOL'), INCREMENT=_F(LIST_INST=L_INST), \
             SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT')"
        }
        _ => "LIST_INST=L_INST",
    };
    format!(
        "DEBUT()\n\
         MAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
         MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI'))\n\
         MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))\n\
         {CUIVRE}\n\
         CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL', MATER=CUIVRE))\n\
         BC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='SZZ', DY=0.), _F(GROUP_NO='AXE', DX=0.)))\n\
         {load}\n\
         RAMPE = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))\n\
         L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=10))\n\
         RES = {command}(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BC), _F(CHARGE=TR{excit})),\n\
         {steps})\n\
         FIN()\n"
    )
}

/// A load of 1e308 is finite, but the stiffness times it (or the mass
/// over it) is not: the stop says that the numbers left the range of
/// doubles and names the load, its node and the instant, instead of
/// "singular matrix ... add the missing DDL_IMPO" (probe s7b D3: the
/// matrix is regular, as the same runs with 1 instead of 1e308 show).
#[test]
fn a_load_too_large_for_doubles_is_named_not_called_singular() {
    // The control: the same bar with a load of 1 runs.
    for (load, excit) in [
        (
            "TR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='A2', DY=1.))",
            ", FONC_MULT=RAMPE",
        ),
        (
            "TR = AFFE_CHAR_MECA(MODELE=MO, FORCE_NODALE=_F(GROUP_NO='A2', FY=1.))",
            "",
        ),
    ] {
        let comm = pulled_bar(load, "STAT_NON_LINE", excit);
        let (_, err) = run(&root_mesh("sdnv103d"), &comm, "load_control");
        assert!(err.is_none(), "{err:?}");
    }
    // DDL_IMPO 1e308 under a ramp: at INST 0.1 the imposed value is
    // 1e307, and the stiffness (E = 117e3) times it overflows.
    let comm = pulled_bar(
        "TR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='A2', DY=1.E308))",
        "STAT_NON_LINE",
        ", FONC_MULT=RAMPE",
    );
    let (_, err) = run(&root_mesh("sdnv103d"), &comm, "load_ddl_impo");
    assert_error(
        &comm,
        &err,
        "STAT_NON_LINE",
        &[
            "stopped at the step from t = 0e0 to t = 1e-1",
            "beyond the range of doubles (1.8e308)",
            "the largest load value at INST = 1e-1 is DDL_IMPO DY at node N",
            "of load TR (EXCIT 2) = 1e308 times FONC_MULT RAMPE = 1e-1",
            "check the load's value and its units",
        ],
        "RES = STAT_NON_LINE",
    );
    let e = err.unwrap();
    assert!(!e.contains("add the missing DDL_IMPO"), "{e}");
    assert!(!e.contains("singular"), "{e}");

    // FORCE_NODALE 1e308, constant: the solve's values overflow.
    let comm = pulled_bar(
        "TR = AFFE_CHAR_MECA(MODELE=MO, FORCE_NODALE=_F(GROUP_NO='A2', FY=1.E308))",
        "STAT_NON_LINE",
        "",
    );
    let (_, err) = run(&root_mesh("sdnv103d"), &comm, "load_force");
    assert_error(
        &comm,
        &err,
        "STAT_NON_LINE",
        &[
            "beyond the range of doubles (1.8e308)",
            "the largest load value at INST = 1e-1 is FORCE_NODALE FY at node N",
            "of load TR (EXCIT 2) = 1e308:",
        ],
        "RES = STAT_NON_LINE",
    );
    assert!(!err.unwrap().contains("singular"));

    // DYNA_NON_LINE: the initial acceleration M a0 = F overflows (an
    // alarm, a0 = 0 as code_aster), then the first step.
    let comm = pulled_bar(
        "TR = AFFE_CHAR_MECA(MODELE=MO, FORCE_NODALE=_F(GROUP_NO='A2', FY=1.E308))",
        "DYNA_NON_LINE",
        "",
    );
    let (study, err) = run(&root_mesh("sdnv103d"), &comm, "load_dyna");
    assert_error(
        &comm,
        &err,
        "DYNA_NON_LINE",
        &[
            "beyond the range of doubles (1.8e308)",
            "the largest load value at INST = 1e-1 is FORCE_NODALE FY at node N",
        ],
        "RES = DYNA_NON_LINE",
    );
    assert!(!err.unwrap().contains("singular"));
    let alarm = study
        .mess
        .lines()
        .find(|l| l.contains("the initial acceleration could not be solved"))
        .unwrap_or_else(|| panic!("no alarm on a0:\n{}", study.mess));
    for part in [
        "beyond the range of doubles (1.8e308)",
        "the largest load value at INST = 0e0 is FORCE_NODALE FY",
    ] {
        assert!(alarm.contains(part), "{part} in {alarm}");
    }
    assert!(!alarm.contains("singular"), "{alarm}");

    // MECA_STATIQUE: the same solve, no "singular stiffness".
    let comm = pulled_bar(
        "TR = AFFE_CHAR_MECA(MODELE=MO, FORCE_NODALE=_F(GROUP_NO='A2', FY=1.E308))",
        "MECA_STATIQUE",
        "",
    );
    let (_, err) = run(&root_mesh("sdnv103d"), &comm, "load_meca");
    assert_error(
        &comm,
        &err,
        "MECA_STATIQUE",
        &["beyond the range of doubles (1.8e308)"],
        "RES = MECA_STATIQUE",
    );
    assert!(!err.unwrap().contains("singular"));
}

/// A load far too large for the model but short of overflowing the
/// equilibrium: the motion stays finite while its energies (½ v·M v,
/// F·Δu) overflow. Implicit: one alarm naming the columns, the run goes
/// on; explicit: a stop naming the balance (before, the run ended "done"
/// with ENER_CIN inf and DISS_SCH NaN in every row). A force whose
/// acceleration overflows at once stops the explicit run naming the node
/// and component and the forces, not "the step exceeds the stability
/// limit".
#[test]
fn energies_that_overflow_are_named_in_both_schemes() {
    let mesh = root_mesh("sdnv103d");
    let implicit = pulled_bar(
        "TR = AFFE_CHAR_MECA(MODELE=MO, FORCE_NODALE=_F(GROUP_NO='A2', FY=1.E160))",
        "DYNA_NON_LINE",
        "",
    );
    let (study, err) = run(&mesh, &implicit, "energy_overflow_implicit");
    assert!(err.is_none(), "{err:?}");
    let alarms: Vec<&str> = study
        .mess
        .lines()
        .filter(|l| l.contains("the energy balance is not finite ("))
        .collect();
    assert_eq!(alarms.len(), 1, "{}", study.mess);
    assert!(alarms[0].contains("TRAV_EXT = inf"), "{}", alarms[0]);

    let explicit = |force: &str| {
        implicit
            .replace("FY=1.E160", force)
            .replace(
                "SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT')",
                "MASS_DIAG='OUI', SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION')",
            )
            .replace("JUSQU_A=1., NOMBRE=10", "JUSQU_A=1.E-8, NOMBRE=10")
    };
    let comm = explicit("FY=1.E290");
    let (_, err) = run(&mesh, &comm, "energy_overflow_explicit");
    assert_error(
        &comm,
        &err,
        "DYNA_NON_LINE",
        &[
            "stopped at the step from t = 0e0 to t = 1e-9",
            "the energy balance is not finite (",
            "ENER_CIN = inf",
            "the loads are far too large for the masses",
        ],
        "RES = DYNA_NON_LINE",
    );
    let comm = explicit("FY=1.E305");
    let (_, err) = run(&mesh, &comm, "motion_overflow_explicit");
    assert_error(
        &comm,
        &err,
        "DYNA_NON_LINE",
        &[
            "the acceleration is not finite at node N",
            "component DY",
            "a force there is too large for the node's mass",
        ],
        "RES = DYNA_NON_LINE",
    );
}

/// A column of unit HEXA8 (x, y in [0, 1]) with its levels at `zs`, as
/// probe s7b built it: groups VOL, node groups NBAS (z = zs[0]), NHAUT
/// (top), NX0 and NY0 (the symmetry planes).
fn hexa_column(zs: &[f64]) -> Mesh {
    use aster::mesh::{Cell, CellType};
    let mut mesh = Mesh {
        name: "COLUMN".into(),
        dim: 3,
        ..Mesh::default()
    };
    for &z in zs {
        for (x, y) in [(0.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, 0.0)] {
            mesh.coords.push([x, y, z]);
        }
    }
    for k in 0..zs.len() - 1 {
        mesh.cells.push(Cell {
            kind: CellType::Hexa8,
            nodes: (4 * k..4 * k + 8).collect(),
        });
    }
    mesh.cell_groups
        .insert("VOL".into(), (0..zs.len() - 1).collect());
    let n = mesh.coords.len();
    let top = 4 * (zs.len() - 1);
    mesh.node_groups.insert("NBAS".into(), (0..4).collect());
    mesh.node_groups
        .insert("NHAUT".into(), (top..top + 4).collect());
    let on = |k: usize| {
        (0..n)
            .filter(|&i| mesh.coords[i][k] == 0.0)
            .collect::<Vec<_>>()
    };
    let (nx0, ny0) = (on(0), on(1));
    mesh.node_groups.insert("NX0".into(), nx0);
    mesh.node_groups.insert("NY0".into(), ny0);
    mesh
}

const COLUMN: &str = "DEBUT()\n\
    MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
    MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
    MAT = DEFI_MATERIAU(ELAS=_F(E=2.E5, NU=0.3, RHO=7.8E-9))\n\
    CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
    BC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='NX0', DX=0.), _F(GROUP_NO='NY0', DY=0.), _F(GROUP_NO='NBAS', DZ=0.)))\n\
    RAMPE = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))\n\
    TR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='NHAUT', DZ=0.01))\n\
    LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=2))\n\
    R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=BC), _F(CHARGE=TR, FONC_MULT=RAMPE)),\n\
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI))\n\
    FIN()\n";

/// A HEXA8 of zero height is refused before the first step like an
/// inverted one, naming the cell (probe s7b D4: its det J, a hair above
/// 0 through rounding or exactly 0 at the Gauss points, passed the sign
/// test and the run ended on "the matrix is singular ... node N8 DZ").
/// The threshold (|det J|·V_ref/h³ < 1e-12, `mesh::ops::DEGENERATE_RATIO`)
/// refuses a height of 1e-13 and lets 1e-6 through, which then runs with
/// the uniaxial answer σ_zz = E·ε_zz of the stack (checked).
#[test]
fn a_cell_of_no_volume_is_refused_like_an_inverted_one() {
    for (tag, zs) in [
        ("flat", [0.0, 1.0, 1.0, 2.0]),
        ("flat_1e-13", [0.0, 1.0, 1.0 + 1e-13, 2.0]),
    ] {
        let path = scratch_mesh(&hexa_column(&zs), &format!("column_{tag}.mmed"));
        // The cell to name, found on the mesh as LIRE_MAILLAGE reads it:
        // the HEXA8 whose nodes all lie within 1e-12 of z = 1.
        let mesh = read_mesh(&path, None).expect("column mesh");
        let flat = (0..mesh.ncells())
            .find(|&c| {
                mesh.cells[c].kind.dim() == 3
                    && mesh.cells[c]
                        .nodes
                        .iter()
                        .all(|&n| (mesh.coords[n][2] - 1.0).abs() < 1e-12)
            })
            .expect("the flat cell");
        let (study, err) = run(&path, COLUMN, tag);
        assert_error(
            COLUMN,
            &err,
            "STAT_NON_LINE/MODELE",
            &[
                &format!("cell M{} (MECA_HEXA8 HEXA8, group(s) VOL)", flat + 1),
                "degenerate on the initial mesh",
                "below 1e-12",
                "correct the mesh before the first step",
            ],
            "R = STAT_NON_LINE",
        );
        assert_no_step(&study, "R");
        // AFFE_MODELE's VERI_JACOBIEN warned of it, as of an inverted one.
        assert!(
            study.mess.contains(
                "1 element(s) have a non-positive or vanishing Jacobian determinant (inverted or degenerate cells) in group(s) VOL"
            ),
            "{}",
            study.mess
        );
    }
    // A thin cell, 1e-6 high: not degenerate, and exact. Each cell of the
    // stack, NU = 0.3 free to contract, carries σ_zz = E·ε with ε = 0.01
    // over the height 2 + 1e-6.
    let path = scratch_mesh(
        &hexa_column(&[0.0, 1.0, 1.0 + 1e-6, 2.0 + 1e-6]),
        "column_thin.mmed",
    );
    let (study, err) = run(&path, COLUMN, "thin");
    assert!(err.is_none(), "{err:?}");
    let Some(aster::concepts::ConceptData::Result(r)) = study.concepts.data("R") else {
        panic!("no result");
    };
    let sig = &r.steps[2].gauss["SIEF_ELGA"];
    let k = sig
        .components
        .iter()
        .position(|c| c == "SIZZ")
        .expect("SIZZ");
    let expected = 2e5 * 0.01 / (2.0 + 1e-6);
    for c in 0..3 {
        for p in 0..sig.npg(c) {
            let v = sig.cell(c)[p * sig.ncmp() + k];
            assert!(
                ((v - expected) / expected).abs() < 1e-6,
                "cell {c} point {p}: {v}"
            );
        }
    }
}
