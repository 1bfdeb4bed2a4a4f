//! DEFI_CONTACT keywords → ContactDef, and pairing on the generated SDNV103
//! meshes: after MODI_MAILLAGE/ORIE_PEAU (as the command files do), the
//! initial gap of every slave node of SZZ on RIGID is the bar's height
//! above the foundation, 2.27.

use aster::catalog::args::Args;
use aster::commands;
use aster::contact::{pair, ContactDef, ReacGeom};
use aster::diag::Source;
use aster::mesh::ops::{orie_peau, OrieDim};
use aster::mesh::taylor::{generate, TaylorParams, GAP};
use aster::mesh::Mesh;
use aster::run::driver::parse_and_check;

/// The checked keywords of a DEFI_CONTACT call, through the real parser
/// and checker (defaults filled in as for a study).
fn defi_contact(modelisation: &str, keywords: &str) -> Args {
    let text = format!(
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='{modelisation}'))\n\
         CONT = DEFI_CONTACT(MODELE=MO, {keywords})\nFIN()\n"
    );
    let src = Source::new("contact.comm", text);
    let mut messages = String::new();
    let program = parse_and_check(&src, &commands::all(), &mut messages)
        .unwrap_or_else(|| panic!("check failed:\n{messages}"));
    program
        .commands
        .into_iter()
        .find(|c| c.name == "DEFI_CONTACT")
        .expect("DEFI_CONTACT in the program")
        .args
}

fn mesh(letter: char) -> Mesh {
    let mut m = generate(&TaylorParams::for_modelling(letter).unwrap()).unwrap();
    let dim = if m.dim == 2 { OrieDim::D2 } else { OrieDim::D3 };
    orie_peau(&mut m, dim, &["SZZ", "RIGID"], None).unwrap();
    m
}

const SDNV103B: &str = "FORMULATION='DISCRETE', REAC_GEOM='CONTROLE', NB_ITER_GEOM=2, \
    FROTTEMENT='COULOMB', ZONE=_F(ALGO_CONT='PENALISATION', ALGO_FROT='PENALISATION', \
    COULOMB=0.25, E_N=1.E10, E_T=1.E5, COEF_MATR_FROT=0.4, APPARIEMENT='MAIT_ESCL', \
    GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')";

#[test]
fn sdnv103b_definition() {
    let m = mesh('B');
    let def = ContactDef::from_args(&defi_contact("AXIS", SDNV103B), &m).unwrap();
    assert_eq!(def.dim, 2);
    assert!(def.friction);
    assert_eq!(def.reac_geom, ReacGeom::Controle { nb_iter_geom: 2 });
    let z = &def.zones[0];
    assert_eq!(z.e_n, 1e10);
    let f = z.friction.unwrap();
    assert_eq!((f.mu, f.e_t, f.coef_matr_frot), (0.25, 1e5, 0.4));
    assert_eq!(z.tole_proj_ext, Some(0.5));
    assert_eq!(z.dist_appa, None);
    // SZZ: 5 SEG3 cells across the radius, 11 nodes, all at y = GAP.
    assert_eq!(z.slave_nodes.len(), 11);
    assert!(z
        .slave_nodes
        .iter()
        .all(|&n| (m.coords[n][1] - GAP).abs() < 1e-12));
    assert_eq!(z.master_cells, m.cell_groups["RIGID"]);
}

#[test]
fn defaults_and_sans_group_no() {
    let m = mesh('D');
    let args = defi_contact(
        "AXIS",
        "ZONE=_F(ALGO_CONT='PENALISATION', E_N=1.E5, GROUP_MA_MAIT='RIGID', \
         GROUP_MA_ESCL='SZZ', SANS_GROUP_NO='A1')",
    );
    let def = ContactDef::from_args(&args, &m).unwrap();
    assert!(!def.friction);
    assert_eq!(
        def.reac_geom,
        ReacGeom::Automatique {
            iter_geom_maxi: 10,
            resi_geom: 0.01
        }
    );
    let z = &def.zones[0];
    assert!(z.friction.is_none());
    // SZZ of D has 2 SEG3 cells, 5 nodes; A1 is removed.
    let a1 = m.node_groups["A1"][0];
    assert_eq!(z.slave_nodes.len(), 4);
    assert!(!z.slave_nodes.contains(&a1));
}

#[test]
fn nb_iter_geom_zero_means_sans() {
    let m = mesh('D');
    let args = defi_contact(
        "AXIS",
        "REAC_GEOM='CONTROLE', NB_ITER_GEOM=0, ZONE=_F(ALGO_CONT='PENALISATION', E_N=1.E5, \
         GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')",
    );
    assert_eq!(
        ContactDef::from_args(&args, &m).unwrap().reac_geom,
        ReacGeom::Sans
    );
}

fn error_of(modelisation: &str, letter: char, keywords: &str) -> aster::diag::Diagnostic {
    let m = mesh(letter);
    ContactDef::from_args(&defi_contact(modelisation, keywords), &m).unwrap_err()
}

#[test]
fn coulomb_without_penalised_contact_is_contact3_3() {
    // ALGO_CONT left to its catalogue default CONTRAINTE.
    let e = error_of(
        "AXIS",
        'D',
        "FROTTEMENT='COULOMB', ZONE=_F(COULOMB=0.25, E_T=1.E5, \
         GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')",
    );
    assert!(e.message.contains("CONTACT3_3"), "{}", e.message);
    assert_eq!(e.keyword.as_deref(), Some("ZONE/ALGO_CONT"));
    assert_eq!(e.command.as_deref(), Some("DEFI_CONTACT"));
}

#[test]
fn unknown_group_is_named_with_a_suggestion() {
    let e = error_of(
        "AXIS",
        'D',
        "ZONE=_F(ALGO_CONT='PENALISATION', E_N=1.E5, GROUP_MA_MAIT='RIGIDE', GROUP_MA_ESCL='SZZ')",
    );
    assert!(e.message.contains("'RIGIDE'"), "{}", e.message);
    assert_eq!(e.keyword.as_deref(), Some("ZONE/GROUP_MA_MAIT"));
    assert_eq!(e.suggestion.as_deref(), Some("RIGID"));
    let e = error_of(
        "AXIS",
        'D',
        "ZONE=_F(ALGO_CONT='PENALISATION', E_N=1.E5, GROUP_MA_MAIT='RIGID', \
         GROUP_MA_ESCL='SZZ', SANS_GROUP_NO='NOPE')",
    );
    assert_eq!(e.keyword.as_deref(), Some("ZONE/SANS_GROUP_NO"));
}

#[test]
fn wrong_cell_dimension_is_refused() {
    // A volume group as slave surface in 2D (QUAD8 cells).
    let e = error_of(
        "AXIS",
        'D',
        "ZONE=_F(ALGO_CONT='PENALISATION', E_N=1.E5, GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='VOL')",
    );
    assert!(
        e.message.contains("QUAD8") && e.message.contains("SEG2/SEG3"),
        "{}",
        e.message
    );
    assert_eq!(e.keyword.as_deref(), Some("ZONE/GROUP_MA_ESCL"));
    // HEXA/PENTA cells as master in 3D.
    let e = error_of(
        "3D",
        'H',
        "ZONE=_F(ALGO_CONT='PENALISATION', E_N=1.E5, GROUP_MA_MAIT='VOL_RIG', GROUP_MA_ESCL='SZZ')",
    );
    assert!(e.message.contains("HEXA8"), "{}", e.message);
    assert_eq!(e.keyword.as_deref(), Some("ZONE/GROUP_MA_MAIT"));
}

#[test]
fn unimplemented_formulations_and_options_are_refused() {
    // The continuous formulation: only nodal points and the augmented
    // Lagrangian are built.
    for (kw, what) in [
        ("INTEGRATION='GAUSS'", "INTEGRATION"),
        ("ALGO_CONT='PENALISATION', COEF_PENA_CONT=1.E5", "ALGO_CONT"),
    ] {
        let e = error_of(
            "AXIS",
            'D',
            &format!(
                "FORMULATION='CONTINUE', ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', {kw})"
            ),
        );
        assert!(
            e.message.starts_with("not implemented yet") && e.message.contains(what),
            "{}",
            e.message
        );
    }
    let m = mesh('D');
    let text = "FORMULATION='LIAISON_UNIL', ZONE=_F(GROUP_NO='A1', NOM_CMP='DY', \
                COEF_MULT=F1, COEF_IMPO=F1)";
    // LIAISON_UNIL needs function concepts: declare one before.
    let args = defi_contact_with_function(text);
    let e = ContactDef::from_args(&args, &m).unwrap_err();
    assert!(e.message.contains("LIAISON_UNIL"), "{}", e.message);
    let e = error_of(
        "AXIS",
        'D',
        "ZONE=_F(ALGO_CONT='GCP', GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')",
    );
    assert!(
        e.message.starts_with("not implemented yet") && e.message.contains("ALGO_CONT='GCP'"),
        "{}",
        e.message
    );
    let e = error_of(
        "AXIS",
        'D',
        "ZONE=(_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ'), \
               _F(ALGO_CONT='PENALISATION', E_N=1.E5, GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ'))",
    );
    assert!(e.message.contains("CONTACT3_4"), "{}", e.message);
    assert_eq!(e.keyword.as_deref(), Some("ZONE/ALGO_CONT"));
    let e = error_of(
        "AXIS",
        'D',
        "ZONE=_F(GLISSIERE='OUI', GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')",
    );
    assert!(
        e.message.starts_with("not implemented yet") && e.message.contains("GLISSIERE"),
        "{}",
        e.message
    );
    // A value of the catalogue that aster does not build stops at check.
    let text = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))\n\
         CONT = DEFI_CONTACT(MODELE=MO, ZONE=_F(ALGO_CONT='PENALISATION', E_N=1.E5, APPARIEMENT='NODAL', \
         GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ'))\nFIN()\n";
    let mut messages = String::new();
    let checked = parse_and_check(
        &Source::new("nodal.comm", text),
        &commands::all(),
        &mut messages,
    );
    assert!(checked.is_none(), "{messages}");
    assert!(
        messages.contains("not implemented yet: DEFI_CONTACT/ZONE/APPARIEMENT='NODAL'"),
        "{messages}"
    );
    let e = error_of(
        "AXIS",
        'D',
        "LISSAGE='OUI', ZONE=_F(ALGO_CONT='PENALISATION', E_N=1.E5, \
         GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')",
    );
    assert!(e.message.contains("LISSAGE"), "{}", e.message);
}

fn defi_contact_with_function(keywords: &str) -> Args {
    let text = format!(
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))\n\
         F1 = DEFI_CONSTANTE(VALE=1.)\n\
         CONT = DEFI_CONTACT(MODELE=MO, {keywords})\nFIN()\n"
    );
    let src = Source::new("contact.comm", text);
    let mut messages = String::new();
    let program = parse_and_check(&src, &commands::all(), &mut messages)
        .unwrap_or_else(|| panic!("check failed:\n{messages}"));
    program
        .commands
        .into_iter()
        .find(|c| c.name == "DEFI_CONTACT")
        .unwrap()
        .args
}

#[test]
fn negative_penalty_is_refused() {
    let e = error_of(
        "AXIS",
        'D',
        "ZONE=_F(ALGO_CONT='PENALISATION', E_N=-1., GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')",
    );
    assert_eq!(e.keyword.as_deref(), Some("ZONE/E_N"));
}

/// Pairs the zone at the given displacement of all slave nodes and checks
/// every gap and normal.
fn check_gaps(letter: char, modelisation: &str, vertical: usize) {
    let m = mesh(letter);
    let def = ContactDef::from_args(&defi_contact(modelisation, SDNV103B), &m).unwrap();
    let nslave = def.zones[0].slave_nodes.len();
    let zero = vec![[0.0; 3]; m.nnodes()];
    let p = pair(&def, &m, &zero);
    assert!(p.unpaired.is_empty());
    assert_eq!(p.links.len(), nslave);
    for l in &p.links {
        // Exactly the generator's GAP up to rounding of the coordinates.
        assert!((l.gap - GAP).abs() < 1e-12, "{letter}: gap {}", l.gap);
        assert!((l.gap_ref - GAP).abs() < 1e-12);
        // n_in points down, into the foundation.
        assert!((l.normal[vertical] + 1.0).abs() < 1e-14);
        // The projection is the slave node brought down to height 0.
        let x = m.coords[l.slave];
        for (c, &xc) in x.iter().enumerate() {
            let expect = if c == vertical { 0.0 } else { xc };
            assert!((l.proj[c] - expect).abs() < 1e-12);
        }
    }
    // The bar moved down by 3: every node is 0.73 inside the foundation.
    let mut u = zero.clone();
    for &n in &def.zones[0].slave_nodes {
        u[n][vertical] = -3.0;
    }
    let p = pair(&def, &m, &u);
    assert_eq!(p.links.len(), nslave);
    for l in &p.links {
        assert!(
            (l.gap - (GAP - 3.0)).abs() < 1e-12,
            "{letter}: gap {}",
            l.gap
        );
        assert!((aster::contact::discrete::link_gap(l, &u) - l.gap).abs() < 1e-12);
    }
}

#[test]
fn initial_gap_is_2_27_on_modelling_b() {
    check_gaps('B', "AXIS", 1);
}

#[test]
fn initial_gap_is_2_27_on_modelling_h() {
    check_gaps('H', "3D", 2);
}

#[test]
fn far_slave_nodes_stay_unpaired() {
    // The 2x2 axis mesh with the master group moved 30 mm sideways: SZZ
    // (x ∈ [0, 3.2]) projects beyond TOLE_PROJ_EXT of RIGID (x ∈ [30, 50]).
    let m = mesh('D');
    let def = ContactDef::from_args(&defi_contact("AXIS", SDNV103B), &m).unwrap();
    let mut u = vec![[0.0; 3]; m.nnodes()];
    for &c in &m.cell_groups["RIGID"] {
        for &n in &m.cells[c].nodes {
            u[n][0] = 30.0;
        }
    }
    let p = pair(&def, &m, &u);
    assert!(p.links.is_empty());
    assert_eq!(p.unpaired.len(), 5);
}

/// With ALGO_CONT='PENALISATION' every node of the slave cells is a slave
/// node, the mid-side nodes of the QUAD8 (and TRIA6) faces of SZZ
/// included, each with its own link: code_aster ties QUAD8 mid nodes to
/// their edge only in the active-set discrete method (`quadco` turns the
/// treatment off for CONT_PENA; docs/contact.md §2). Modelling H: SZZ
/// holds QUAD8 and TRIA6 faces.
#[test]
fn penalised_contact_keeps_quad8_mid_nodes() {
    use aster::mesh::CellType;
    let m = mesh('H');
    let def = ContactDef::from_args(&defi_contact("3D", SDNV103B), &m).unwrap();
    let szz = &m.cell_groups["SZZ"];
    assert!(szz.iter().any(|&c| m.cells[c].kind == CellType::Quad8));
    let mut all = m.nodes_of_cells(szz);
    all.sort_unstable();
    all.dedup();
    let mut mid: Vec<usize> = szz
        .iter()
        .flat_map(|&c| {
            let cell = &m.cells[c];
            cell.nodes[cell.kind.nvertices()..].to_vec()
        })
        .collect();
    mid.sort_unstable();
    mid.dedup();
    assert!(!mid.is_empty());
    let mut slaves = def.zones[0].slave_nodes.clone();
    slaves.sort_unstable();
    assert_eq!(slaves, all);
    let p = pair(&def, &m, &vec![[0.0; 3]; m.nnodes()]);
    for n in mid {
        assert!(
            p.links.iter().any(|l| l.slave == n),
            "mid node {n} unlinked"
        );
    }
}

/// ALGO_CONT='CONTRAINTE' (the default) on H's QUAD8 face: every mid-side
/// node of SZZ whose edge has both vertices among the slave nodes is tied
/// to them and leaves the slave nodes (code_aster's `elimcq`/`cacoeq`);
/// the vertices stay. On the AXIS mesh of D (SEG3 faces) nothing is tied.
#[test]
fn active_set_ties_quad8_mid_nodes() {
    use aster::contact::DiscreteAlgo;
    use aster::mesh::CellType;
    let m = mesh('H');
    let def = ContactDef::from_args(
        &defi_contact("3D", "ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')"),
        &m,
    )
    .unwrap();
    assert_eq!(def.algo, DiscreteAlgo::ActiveSet);
    let szz = &m.cell_groups["SZZ"];
    let mut expected = Vec::new();
    for &c in szz {
        let cell = &m.cells[c];
        // TRIA6 faces (the prisms at the axis) are not tied.
        if cell.kind != CellType::Quad8 {
            continue;
        }
        for (k, &mid) in cell.nodes[4..].iter().enumerate() {
            expected.push((mid, [cell.nodes[k], cell.nodes[(k + 1) % 4]]));
        }
    }
    assert!(!expected.is_empty());
    expected.sort_unstable();
    expected.dedup_by_key(|e| e.0);
    let mut slaves = m.nodes_of_cells(szz);
    slaves.sort_unstable();
    slaves.dedup();
    slaves.retain(|n| expected.binary_search_by_key(n, |e| e.0).is_err());
    let mut ties: Vec<(usize, [usize; 2])> = def.ties.iter().map(|t| (t.mid, t.ends)).collect();
    ties.sort_unstable();
    assert_eq!(ties.len(), expected.len());
    for ((mid, ends), (emid, eends)) in ties.iter().zip(&expected) {
        assert_eq!(mid, emid);
        let (mut a, mut b) = (*ends, *eends);
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b, "tie of {mid}");
    }
    assert_eq!(def.zones[0].slave_nodes, slaves);
    let d = ContactDef::from_args(
        &defi_contact(
            "AXIS",
            "ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')",
        ),
        &mesh('D'),
    )
    .unwrap();
    assert!(d.ties.is_empty());
}

/// SDNV103 F's definition: the continuous keywords with their defaults.
#[test]
fn continuous_definition_of_f() {
    use aster::contact::continuous::{ContactInit, Resolution};
    let m = mesh('D');
    let args = defi_contact(
        "AXIS",
        "FORMULATION='CONTINUE', FROTTEMENT='COULOMB', ALGO_RESO_CONT='NEWTON', \
         ALGO_RESO_FROT='NEWTON', ALGO_RESO_GEOM='NEWTON', \
         ZONE=_F(APPARIEMENT='MAIT_ESCL', GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', COULOMB=0.25)",
    );
    let d = ContactDef::from_args(&args, &m).expect("F's definition");
    let c = d.continuous.as_ref().expect("continuous");
    assert_eq!(c.algo_reso_geom, Resolution::Newton);
    assert_eq!(c.resi_frot, 1e-4);
    let z = &c.zones[0];
    assert_eq!((z.coef_cont, z.coef_frot, z.mu), (100.0, 100.0, Some(0.25)));
    assert_eq!(z.contact_init, ContactInit::Interpenetre);
    assert_eq!(z.seuil_init, None);
    assert_eq!(z.slave_cells.len(), m.cell_groups["SZZ"].len());
    assert_eq!(d.zones[0].slave_nodes.len(), 5);
}

/// The friction fixed point: ITER_FROT_MAXI (default 10) and RESI_FROT
/// read; ITER_FROT_MAXI below 1 refused, naming the keyword.
#[test]
fn friction_fixed_point_definition() {
    use aster::contact::continuous::Resolution;
    let m = mesh('D');
    let text = |extra: &str| {
        format!(
            "FORMULATION='CONTINUE', FROTTEMENT='COULOMB', ALGO_RESO_FROT='POINT_FIXE', {extra} \
             ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', COULOMB=0.25)"
        )
    };
    let d = ContactDef::from_args(&defi_contact("AXIS", &text("")), &m).expect("definition");
    let c = d.continuous.as_ref().expect("continuous");
    assert_eq!(c.algo_reso_frot, Resolution::PointFixe);
    assert_eq!((c.iter_frot_maxi, c.resi_frot), (10, 1e-4));
    let d = ContactDef::from_args(
        &defi_contact("AXIS", &text("ITER_FROT_MAXI=3, RESI_FROT=1.E-6,")),
        &m,
    )
    .expect("definition");
    let c = d.continuous.as_ref().expect("continuous");
    assert_eq!((c.iter_frot_maxi, c.resi_frot), (3, 1e-6));
    let e = error_of("AXIS", 'D', &text("ITER_FROT_MAXI=0,"));
    assert!(e.message.contains("ITER_FROT_MAXI"), "{}", e.message);
}

/// The continuous formulation in 3D takes linear slave faces only: the
/// quadratic faces of the 3D Taylor bar (QUAD8, TRIA6) are refused at
/// DEFI_CONTACT, naming GROUP_MA_ESCL and the face type.
#[test]
fn continuous_3d_refuses_quadratic_slave_faces() {
    let e = error_of(
        "3D",
        'H',
        "FORMULATION='CONTINUE', ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')",
    );
    assert!(
        e.message.starts_with("not implemented yet")
            && (e.message.contains("QUAD8") || e.message.contains("TRIA6")),
        "{}",
        e.message
    );
    assert!(e.message.contains("ZONE/GROUP_MA_ESCL"), "{}", e.message);
}
