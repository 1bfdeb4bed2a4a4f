//! The mesh commands at run time: what they do to the SDNV103 meshes, and
//! the messages a user gets for a missing group, an unmapped unit or a bad
//! file (file, line, command, keyword; never a panic).

use std::path::{Path, PathBuf};

use aster::concepts::ConceptData;
use aster::diag::Source;
use aster::run::driver::{run_file, RunOptions};
use aster::study::Study;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Writes a study to a scratch directory and runs it with unit 20 mapped
/// to `mesh`; returns the exit code and what the terminal shows.
fn run(name: &str, text: &str, mesh: &Path) -> (i32, String, PathBuf) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("mesh_cmd_{name}"));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join(format!("{name}.comm"));
    std::fs::write(&comm, text).unwrap();
    let mut out = Vec::new();
    let code = run_file(
        &RunOptions {
            comm,
            units: vec![(20, mesh.to_path_buf())],
            out_dir: Some(dir.clone()),
            ..RunOptions::default()
        },
        &mut out,
    );
    (code, String::from_utf8(out).unwrap(), dir)
}

/// Runs a study in-process and returns the study (to inspect concepts).
fn run_in_process(text: &str, mesh: &Path) -> Study {
    let src = Source::new("inline.comm", text);
    let reg = aster::commands::all();
    let mut msgs = String::new();
    let prog = aster::run::driver::parse_and_check(&src, &reg, &mut msgs).expect(&msgs);
    let mut study = Study::default();
    study.units.map.insert(20, mesh.to_path_buf());
    aster::run::execute(&mut study, &prog, &reg, &src)
        .unwrap_or_else(|d| panic!("{}", d.render(Some(&src))));
    study
}

fn mesh(study: &Study, name: &str) -> aster::mesh::Mesh {
    match study.concepts.data(name) {
        Some(ConceptData::Mesh(m)) => (**m).clone(),
        _ => panic!("{name} is not a mesh"),
    }
}

#[test]
fn unknown_group_is_named_with_the_line_and_a_suggestion() {
    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
        MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL,\n                  CREA_GROUP_NO=_F(GROUP_MA='SZ', NOM='BAS'))\nFIN()\n";
    let (code, out, _) = run("unknown_group", text, &root().join("med/sdnv103b.mmed"));
    assert_eq!(code, 1);
    assert!(out.contains("DEFI_GROUP/CREA_GROUP_NO/GROUP_MA"), "{out}");
    assert!(out.contains("unknown_group.comm:4:"), "{out}");
    assert!(out.contains("no cell group (GROUP_MA) 'SZ'"), "{out}");
    assert!(out.contains("did you mean 'SZZ'"), "{out}");
}

#[test]
fn unmapped_unit_and_bad_file_are_clear_errors() {
    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED', UNITE=33)\nFIN()\n";
    let (code, out, _) = run("unmapped", text, &root().join("med/sdnv103b.mmed"));
    assert_eq!(code, 1);
    assert!(
        out.contains("LIRE_MAILLAGE/UNITE: logical unit 33 is not mapped"),
        "{out}"
    );
    assert!(out.contains("F mmed <path> D 33"), "{out}");

    let bad = Path::new(env!("CARGO_TARGET_TMPDIR")).join("not_a_mesh.mmed");
    std::fs::write(&bad, b"this is not HDF5 at all").unwrap();
    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\nFIN()\n";
    let (code, out, _) = run("badfile", text, &bad);
    assert_eq!(code, 1);
    assert!(out.contains("LIRE_MAILLAGE/UNITE"), "{out}");
    assert!(out.contains("not_a_mesh.mmed"), "{out}");

    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED', NOM_MED='NOPE')\nFIN()\n";
    let (code, out, _) = run("badname", text, &root().join("med/sdnv103b.mmed"));
    assert_eq!(code, 1);
    assert!(out.contains("LIRE_MAILLAGE/NOM_MED"), "{out}");
    assert!(
        out.contains("TAYLOR_AXIS"),
        "the message lists the meshes present: {out}"
    );
}

/// LINE_QUAD on a mesh with no linear cell to convert (the quadratic B
/// mesh's QUAD8/SEG3 cells) is code_aster's MODELISA3_8, located.
#[test]
fn line_quad_with_nothing_to_convert_is_located() {
    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
        MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, CREA_GROUP_MA=_F(NOM='BAR', GROUP_MA='VOL'))\n\
        QUAD = CREA_MAILLAGE(MAILLAGE=MAIL, LINE_QUAD=_F(GROUP_MA='BAR'))\nFIN()\n";
    let (code, out, _) = run("line_quad_nothing", text, &root().join("med/sdnv103b.mmed"));
    assert_eq!(code, 1);
    assert!(out.contains("CREA_MAILLAGE/LINE_QUAD/GROUP_MA"), "{out}");
    assert!(out.contains("line_quad_nothing.comm:4:"), "{out}");
    assert!(out.contains("no linear cell"), "{out}");
}

#[test]
fn quarter_mesh_groups_as_the_3d_command_files_build_them() {
    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
        MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, CREA_GROUP_NO=(\n\
          _F(TOUT_GROUP_MA='OUI'),\n\
          _F(GROUP_MA='SZZ', NOM='MILIEU', CRIT_NOEUD='MILIEU'),\n\
          _F(DIFFE=('SXX', 'MILIEU'), NOM='SXX1'),\n\
          _F(DIFFE=('SYY', 'MILIEU'), NOM='SYY1'),))\n\
        MAIL = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ORIE_PEAU_3D=_F(GROUP_MA=('SZZ', 'RIGID')))\n\
        LIN = CREA_MAILLAGE(MAILLAGE=MAIL, QUAD_LINE=_F(TOUT='OUI'))\nFIN()\n";
    let study = run_in_process(text, &root().join("med/sdnv103a.mmed"));
    let m = mesh(&study, "MAIL");
    assert_eq!(m.node_groups["MILIEU"].len(), 65);
    let sxx = m.node_groups["SXX"].len();
    assert_eq!(
        m.node_groups["SXX1"].len(),
        sxx - m.node_groups["SXX"]
            .iter()
            .filter(|n| m.node_groups["MILIEU"].contains(n))
            .count()
    );
    // SZZ faces now point down (out of the bar), RIGID up (out of the block).
    for (g, sign) in [("SZZ", -1.0), ("RIGID", 1.0)] {
        for &c in &m.cell_groups[g] {
            let n = &m.cells[c].nodes;
            let (a, b, d) = (m.coords[n[0]], m.coords[n[1]], m.coords[n[2]]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let v = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
            let nz = u[0] * v[1] - u[1] * v[0];
            assert!(nz * sign > 0.0, "{g} cell {c} normal z = {nz}");
        }
    }
    let lin = mesh(&study, "LIN");
    assert!(lin.cells.iter().all(|c| !c.kind.is_quadratic()));
    assert!(
        !lin.node_groups.contains_key("MILIEU"),
        "QUAD_LINE drops node groups left empty"
    );
    assert_eq!(lin.node_groups["A2"].len(), 1);
}

/// ORIE_PEAU, code_aster 15's merge of ORIE_PEAU_2D and ORIE_PEAU_3D (the
/// keyword of current code_aster files, GROUP_MA_PEAU): on the 2D and the
/// 3D SDNV103 meshes it orients every skin cell as the old keyword of its
/// dimension does, and a skin group holding volume cells is a located
/// error.
#[test]
fn orie_peau_orients_as_the_keyword_of_its_dimension() {
    for (mesh_file, old) in [
        ("sdnv103b", "ORIE_PEAU_2D=_F(GROUP_MA=('SZZ', 'RIGID'))"),
        ("sdnv103a", "ORIE_PEAU_3D=_F(GROUP_MA=('SZZ', 'RIGID'))"),
    ] {
        let study = |key: &str| {
            let text = format!(
                "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
                 MAIL = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, {key})\nFIN()\n"
            );
            run_in_process(&text, &root().join(format!("med/{mesh_file}.mmed")))
        };
        let new = mesh(
            &study("ORIE_PEAU=_F(GROUP_MA_PEAU=('SZZ', 'RIGID'))"),
            "MAIL",
        );
        let reference = mesh(&study(old), "MAIL");
        let original = {
            let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\nFIN()\n";
            mesh(
                &run_in_process(text, &root().join(format!("med/{mesh_file}.mmed"))),
                "MAIL",
            )
        };
        let cells = |m: &aster::mesh::Mesh| {
            ["SZZ", "RIGID"]
                .iter()
                .flat_map(|g| m.cell_groups[*g].iter().map(|&c| m.cells[c].nodes.clone()))
                .collect::<Vec<_>>()
        };
        assert_eq!(cells(&new), cells(&reference), "{mesh_file}");
        assert_ne!(
            cells(&new),
            cells(&original),
            "{mesh_file}: some skin cell is reoriented"
        );
    }
    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
        MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, CREA_GROUP_MA=_F(NOM='MIX', UNION=('SZZ', 'VOL')))\n\
        MAIL = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ORIE_PEAU=_F(GROUP_MA_PEAU='MIX'))\nFIN()\n";
    let (code, out, _) = run("orie_peau_mix", text, &root().join("med/sdnv103a.mmed"));
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("MODI_MAILLAGE/ORIE_PEAU"), "{out}");
    assert!(out.contains("orie_peau_mix.comm:4"), "{out}");
    assert!(out.contains("PENTA15"), "{out}");
}

/// DEFI_GROUP's geometric and by-name selections on the 3D quarter bar
/// (radius 3.2, bottom face at z = 2.27, the block a HEXA8 far from the
/// bar's axis): ENV_SPHERE picks a node by its coordinates (the A1 of the
/// MED file), ENV_CYLINDRE the bar's lateral surface (every bar node at
/// radius 3.2, whichever way the axis is given), NOEUD and MAILLE take
/// names, TYPE_MAILLE keeps one dimension or one type, INTERSEC and DIFFE
/// combine cell groups, and an empty result is not created (SOUSTRUC_38).
#[test]
fn envelopes_names_and_cell_types_select_what_code_aster_selects() {
    let mesh_file = root().join("med/sdnv103a.mmed");
    let text = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
        MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, CREA_GROUP_NO=(\n\
          _F(OPTION='ENV_SPHERE', NOM='PA1', POINT=(0., 0., 2.27), RAYON=1.e-3, PRECISION=1.e-3),\n\
          _F(OPTION='ENV_SPHERE', NOM='RING', GROUP_NO_CENTRE='A1', RAYON=3.2, PRECISION=1.e-6),\n\
          _F(OPTION='ENV_CYLINDRE', NOM='LAT', POINT=(0., 0., 0.), VECT_NORMALE=(0., 0., 2.),\n\
             RAYON=3.2, PRECISION=1.e-6),\n\
          _F(OPTION='ENV_CYLINDRE', NOM='LAT2', POINT=(0., 0., 5.), ANGL_NAUT=(30., -90.),\n\
             RAYON=3.2, PRECISION=1.e-6),\n\
          _F(NOEUD=('N5', 'N1', 'N5'), NOM='TWO'),),\n\
        CREA_GROUP_MA=(\n\
          _F(TOUT='OUI', TYPE_MAILLE='3D', NOM='SOLID'),\n\
          _F(GROUP_MA='VOL', TYPE_MAILLE='PENTA15', NOM='PRISMS'),\n\
          _F(MAILLE=('M3', 'M1'), NOM='M13'),\n\
          _F(INTERSEC=('VOL', 'SXX'), NOM='NONE'),\n\
          _F(DIFFE=('SOLID', 'VOL'), NOM='BLOCK'),\n\
          _F(UNION=('SZZ', 'SXX'), TYPE_MAILLE='TRIA6', NOM='AXIS_T6'),))\nFIN()\n";
    let study = run_in_process(text, &mesh_file);
    let m = mesh(&study, "MAIL");
    assert_eq!(m.node_groups["PA1"], m.node_groups["A1"]);
    let ring = &m.node_groups["RING"];
    assert!(ring.contains(&m.node_groups["B1"][0]), "B1 is 3.2 from A1");
    assert!(!ring.contains(&m.node_groups["A1"][0]));
    let bar: Vec<usize> = m.nodes_of_cells(&m.cell_groups["VOL"]);
    let radius = |n: usize| m.coords[n][0].hypot(m.coords[n][1]);
    let mut lateral: Vec<usize> = bar
        .iter()
        .copied()
        .filter(|&n| radius(n) > 3.2 - 1e-6)
        .collect();
    lateral.sort_unstable();
    assert!(lateral.len() > 100, "{} lateral nodes", lateral.len());
    for g in ["LAT", "LAT2"] {
        let mut got = m.node_groups[g].clone();
        got.sort_unstable();
        assert_eq!(got, lateral, "{g}");
    }
    assert_eq!(m.node_groups["TWO"], vec![4, 0]);
    let count = |kinds: &[&str]| {
        m.cells
            .iter()
            .filter(|c| kinds.contains(&c.kind.aster_name()))
            .count()
    };
    assert_eq!(
        m.cell_groups["SOLID"].len(),
        count(&["HEXA8", "HEXA20", "PENTA15"])
    );
    assert_eq!(m.cell_groups["PRISMS"].len(), 120);
    assert_eq!(m.cell_groups["M13"], vec![0, 2]);
    assert!(
        !m.cell_groups.contains_key("NONE"),
        "a volume is never a face"
    );
    assert_eq!(m.cell_groups["BLOCK"], m.cell_groups["VOL_RIG"]);
    // The impact face's six triangles are the cells around the axis.
    let t6 = &m.cell_groups["AXIS_T6"];
    assert_eq!(t6.len(), count(&["TRIA6"]));
    assert!(t6.iter().all(|c| m.cell_groups["SZZ"].contains(c)));
}

/// The limits of ENV_SPHERE / ENV_CYLINDRE as code_aster states them,
/// each at its keyword and line: RAYON and PRECISION > 0, the cylinder on
/// a 3D mesh only.
#[test]
fn envelope_limits_are_located_errors() {
    let cases = [
        (
            "sdnv103a",
            "_F(OPTION='ENV_SPHERE', NOM='P', POINT=(0., 0., 0.), RAYON=0., PRECISION=1.e-3)",
            "CREA_GROUP_NO/RAYON",
        ),
        (
            "sdnv103a",
            "_F(OPTION='ENV_SPHERE', NOM='P', POINT=(0., 0.), RAYON=1., PRECISION=1.e-3)",
            "CREA_GROUP_NO/POINT",
        ),
        (
            "sdnv103b",
            "_F(OPTION='ENV_CYLINDRE', NOM='P', POINT=(0., 0.), VECT_NORMALE=(0., 1., 0.), RAYON=1., PRECISION=1.e-3)",
            "3D mesh",
        ),
    ];
    for (i, (file, occ, expected)) in cases.iter().enumerate() {
        let text = format!(
            "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
             MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL,\n    CREA_GROUP_NO={occ})\nFIN()\n"
        );
        let name = format!("envelope_limit_{i}");
        let (code, out, _) = run(&name, &text, &root().join(format!("med/{file}.mmed")));
        assert_eq!(code, 1, "{out}");
        assert!(out.contains(expected), "{expected}: {out}");
        assert!(out.contains(&format!("{name}.comm:4:")), "{out}");
    }
}

/// SEGM_DROI_ORDO orders, it does not select: the impact face of B's
/// axisymmetric mesh (the nodes of its SEG3 cells, from CREA_GROUP_NO)
/// comes out from A1 on the axis to B1 at the edge, radius strictly
/// increasing; a node off the segment (the bar's top) stops DEFI_GROUP
/// at the keyword with the node's name, as code_aster's assertion does.
#[test]
fn segm_droi_ordo_orders_the_impact_face_from_axis_to_edge() {
    let head = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
        MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, CREA_GROUP_NO=(\n\
          _F(GROUP_MA='SZZ', NOM='FACE'),\n";
    let text = format!(
        "{head}  _F(OPTION='SEGM_DROI_ORDO', NOM='ORDO', GROUP_NO='FACE', GROUP_NO_ORIG='A1',\n\
             GROUP_NO_EXTR='B1', PRECISION=1.e-6, CRITERE='ABSOLU'),))\nFIN()\n"
    );
    let m = mesh(
        &run_in_process(&text, &root().join("med/sdnv103b.mmed")),
        "MAIL",
    );
    let ordo = &m.node_groups["ORDO"];
    assert_eq!(ordo.len(), m.node_groups["FACE"].len());
    assert_eq!(ordo.len(), 11, "5 SEG3: 11 nodes");
    assert_eq!(ordo[0], m.node_groups["A1"][0]);
    assert_eq!(*ordo.last().unwrap(), m.node_groups["B1"][0]);
    assert!(ordo
        .windows(2)
        .all(|w| m.coords[w[0]][0] < m.coords[w[1]][0]));

    let bad = format!(
        "{head}  _F(OPTION='SEGM_DROI_ORDO', NOM='ORDO', GROUP_NO=('FACE', 'A2'), GROUP_NO_ORIG='A1',\n\
             GROUP_NO_EXTR='B1', PRECISION=1.e-6, CRITERE='RELATIF'),))\nFIN()\n"
    );
    let (code, out, _) = run(
        "segm_droi_ordo_off",
        &bad,
        &root().join("med/sdnv103b.mmed"),
    );
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("SOUSTRUC_22") && out.contains("from the line"),
        "{out}"
    );
    assert!(out.contains("segm_droi_ordo_off.comm:5:"), "{out}");
}
