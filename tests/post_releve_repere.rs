//! POST_RELEVE_T REPERE='CYLINDRIQUE' (ORIGINE, AXE_Z) and
//! REPERE='UTILISATEUR' (ANGL_NAUT) against hand values.
//!
//! code_aster (bibfor/postrele/extchn, rvchn1, rvchn2; utilitai/matrot)
//! turns the nodal field before any operation, DEPL_R fields only
//! (POSTRELE_17 otherwise), keeping the component names:
//! - UTILISATEUR: v' = P v for (DX, DY, DZ) and (DRX, DRY, DRZ), the rows
//!   of P the axes of the frame of the nautical angles (alpha, beta,
//!   gamma) in degrees: the global frame turned by alpha about z, then by
//!   beta about the new y, then by gamma about the newest x;
//! - CYLINDRIQUE: the rows of P at a node are e_r (from the axis to the
//!   node), e_z (AXE_Z) and e_theta = e_z x e_r, in this order: DX is
//!   the radial component, DY the axial one, DZ the tangential one.
//!
//! Synthetic data (test-only commands, as tests/post_releve_moyenne.rs):
//! a 3D cloud of nodes around the oblique axis through C = (1, -2, 0.5)
//! along a = (1, 2, 2)/3; fields on them.

#![allow(clippy::result_large_err)]

use aster::catalog::args::Args;
use aster::commands::{CommandDef, ExecResult};
use aster::concepts::{ConceptData, ConceptType as C};
use aster::mesh::Mesh;
use aster::post::table::Table;
use aster::result::NodalField;
use aster::study::Study;

mod common;

const C0: [f64; 3] = [1.0, -2.0, 0.5];
const AXIS: [f64; 3] = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
/// Two unit vectors normal to AXIS and to each other, with b1 x b2 = AXIS.
const B1: [f64; 3] = [2.0 / 3.0, 1.0 / 3.0, -2.0 / 3.0];
const B2: [f64; 3] = [-2.0 / 3.0, 2.0 / 3.0, -1.0 / 3.0];
const OMEGA: f64 = 1.5e-3;
const W: f64 = -4e-4;

/// Node k: radius R[k], angle T[k] about the axis, height H[k] along it;
/// the last node is on the axis.
const R: [f64; 5] = [1.0, 2.5, 0.3, 4.0, 0.0];
const T: [f64; 5] = [0.0, 1.0, 2.5, -2.0, 0.0];
const H: [f64; 5] = [0.0, 1.0, -2.0, 3.0, 1.0];

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn mesh() -> Mesh {
    let coords = (0..5)
        .map(|k| {
            let (s, c) = T[k].sin_cos();
            let mut x = C0;
            for i in 0..3 {
                x[i] += R[k] * (c * B1[i] + s * B2[i]) + H[k] * AXIS[i];
            }
            x
        })
        .collect();
    let mut m = Mesh {
        name: "cloud".into(),
        dim: 3,
        coords,
        ..Mesh::default()
    };
    m.node_groups.insert("OFF".into(), vec![0, 1, 2, 3]);
    m.node_groups.insert("ALL".into(), vec![0, 1, 2, 3, 4]);
    m
}

fn synth_mail(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    Ok(Some(ConceptData::Mesh(Box::new(mesh()))))
}

fn champ(f: NodalField) -> ExecResult {
    Ok(Some(ConceptData::Field(Box::new(
        aster::concepts::ChamNo {
            mesh: "MA".into(),
            field: f,
        },
    ))))
}

/// A rigid rotation OMEGA about the axis plus a translation W along it:
/// u = OMEGA a x (x - C) + W a, so u_r = 0, u_theta = OMEGA r, u_z = W.
/// DRX..DRZ carry the constant vector (1, 2, 3).
fn synth_rot(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    let m = mesh();
    let names = ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"];
    let mut f = NodalField::zeros(names.iter().map(|s| s.to_string()).collect(), m.nnodes());
    for n in 0..m.nnodes() {
        let d: Vec<f64> = (0..3).map(|i| m.coords[n][i] - C0[i]).collect();
        let u = cross(AXIS, [d[0], d[1], d[2]]);
        for i in 0..3 {
            f.set(n, i, OMEGA * u[i] + W * AXIS[i]);
            f.set(n, 3 + i, (i + 1) as f64);
        }
    }
    champ(f)
}

/// A plane field (DX, DY only): u = (1, 2) at every node.
fn synth_plan(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    let m = mesh();
    let mut f = NodalField::zeros(vec!["DX".into(), "DY".into()], m.nnodes());
    for n in 0..m.nnodes() {
        f.set(n, 0, 1.0);
        f.set(n, 1, 2.0);
    }
    champ(f)
}

/// A nodal stress field, uniaxial SIXX = 100.
fn synth_sigm(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    let m = mesh();
    let names = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    let mut f = NodalField::zeros(names.iter().map(|s| s.to_string()).collect(), m.nnodes());
    for n in 0..m.nnodes() {
        f.set(n, 0, 100.0);
    }
    champ(f)
}

fn registry() -> Vec<CommandDef> {
    common::synth_registry(&[
        ("SYNTH_MAIL", C::Maillage, synth_mail),
        ("SYNTH_ROT", C::ChamNo, synth_rot),
        ("SYNTH_PLAN", C::ChamNo, synth_plan),
        ("SYNTH_SIGM", C::ChamNo, synth_sigm),
    ])
}

const PRELUDE: &str = "DEBUT()\nMA = SYNTH_MAIL()\nROT = SYNTH_ROT()\nPLAN = SYNTH_PLAN()\n\
                       SIG = SYNTH_SIGM()\n";

const TEXT: common::TextStudies = common::TextStudies {
    prefix: "post_repere",
    prelude: PRELUDE,
    registry,
};

fn run(tag: &str, body: &str) -> Study {
    TEXT.run(tag, body)
}

fn run_err(body: &str) -> String {
    TEXT.run_err(body)
}

use common::table;

fn val(t: &Table, row: usize, cmp: &str) -> f64 {
    t.cell(row, cmp)
        .and_then(|c| c.as_f64())
        .unwrap_or_else(|| panic!("row {row}: no {cmp}"))
}

/// A rigid rotation read in the cylindrical frame of its own axis: at
/// every node off the axis u_r = 0 (DX), u_z = W (DY), u_theta = OMEGA r
/// (DZ), exactly up to rounding (1e-15 absolute on values of 1e-3); the
/// rotation vector (1, 2, 3) reads (e_r, e_z, e_theta)·(1, 2, 3) at each
/// node. The node on the axis has no e_r: refused, named.
#[test]
fn a_rigid_rotation_in_the_cylindrical_frame_of_its_axis() {
    let s = run(
        "rot",
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='R', CHAM_GD=ROT,
             GROUP_NO='OFF', TOUT_CMP='OUI', REPERE='CYLINDRIQUE',
             ORIGINE=(1., -2., 0.5), AXE_Z=(3., 6., 6.)))\n",
    );
    let t = table(&s, "T");
    assert_eq!(t.rows.len(), 4);
    for k in 0..4 {
        assert!(
            val(t, k, "DX").abs() < 1e-15,
            "node {k} u_r {}",
            val(t, k, "DX")
        );
        assert!((val(t, k, "DY") - W).abs() < 1e-15, "node {k} u_z");
        assert!(
            (val(t, k, "DZ") - OMEGA * R[k]).abs() < 1e-15,
            "node {k} u_theta {} vs {}",
            val(t, k, "DZ"),
            OMEGA * R[k]
        );
        let (sn, cs) = T[k].sin_cos();
        let er: Vec<f64> = (0..3).map(|i| cs * B1[i] + sn * B2[i]).collect();
        let et = cross(AXIS, [er[0], er[1], er[2]]);
        let dot = |e: &[f64]| e[0] + 2.0 * e[1] + 3.0 * e[2];
        for (cmp, want) in [("DRX", dot(&er)), ("DRY", dot(&AXIS)), ("DRZ", dot(&et))] {
            assert!((val(t, k, cmp) - want).abs() < 1e-13, "node {k} {cmp}");
        }
    }
    let e = run_err(
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='R', CHAM_GD=ROT,
             GROUP_NO='ALL', NOM_CMP='DX', REPERE='CYLINDRIQUE',
             ORIGINE=(1., -2., 0.5), AXE_Z=(3., 6., 6.)))\n",
    );
    assert!(
        e.contains("POST_RELEVE_T/ACTION/ORIGINE")
            && e.contains("node N5 is on the axis")
            && e.contains("POSTRELE_30")
            && e.contains("t.comm:8:"),
        "{e}"
    );
}

/// A field with DX, DY only (a plane field): the absent DZ counts as 0
/// and stays absent, as in code_aster's rvchn2. Axis z through the
/// origin, node 0 at (x, y): DX = u·e_r, DY = u·e_z = 0, no DZ column.
#[test]
fn a_plane_field_keeps_its_components() {
    let s = run(
        "plan",
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='P', CHAM_GD=PLAN,
             NOEUD='N1', TOUT_CMP='OUI', REPERE='CYLINDRIQUE',
             ORIGINE=(0., 0., 0.), AXE_Z=(0., 0., 1.)))\n",
    );
    let t = table(&s, "T");
    let x = mesh().coords[0];
    let r = x[0].hypot(x[1]);
    assert!((val(t, 0, "DX") - (x[0] + 2.0 * x[1]) / r).abs() < 1e-14);
    assert_eq!(val(t, 0, "DY"), 0.0);
    assert!(t.column_index("DZ").is_none());
}

/// ANGL_NAUT = (30, 45, 60) degrees: the frame is the global one turned
/// by alpha about z, beta about the new y, gamma about the newest x, so
/// its axes are the columns of Rz(alpha) Ry(beta) Rx(gamma) (built here
/// from the three elementary rotations, not from code_aster's closed
/// form) and the components are v' = (Rz Ry Rx)^T v, for (DX, DY, DZ)
/// and for (DRX, DRY, DRZ). To 1e-14 on values of order 1.
#[test]
fn nautical_angles_turn_the_vectors() {
    let s = run(
        "naut",
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='U', CHAM_GD=ROT,
             NOEUD='N2', TOUT_CMP='OUI', REPERE='UTILISATEUR', ANGL_NAUT=(30., 45., 60.)))
         G = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='G', CHAM_GD=ROT,
             NOEUD='N2', TOUT_CMP='OUI'))\n",
    );
    let (a, b, g) = (30f64.to_radians(), 45f64.to_radians(), 60f64.to_radians());
    let rz = [
        [a.cos(), -a.sin(), 0.0],
        [a.sin(), a.cos(), 0.0],
        [0.0, 0.0, 1.0],
    ];
    let ry = [
        [b.cos(), 0.0, b.sin()],
        [0.0, 1.0, 0.0],
        [-b.sin(), 0.0, b.cos()],
    ];
    let rx = [
        [1.0, 0.0, 0.0],
        [0.0, g.cos(), -g.sin()],
        [0.0, g.sin(), g.cos()],
    ];
    let mul = |p: [[f64; 3]; 3], q: [[f64; 3]; 3]| {
        let mut o = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                o[i][j] = (0..3).map(|k| p[i][k] * q[k][j]).sum();
            }
        }
        o
    };
    let m = mul(mul(rz, ry), rx);
    let (tu, tg) = (table(&s, "T"), table(&s, "G"));
    for names in [["DX", "DY", "DZ"], ["DRX", "DRY", "DRZ"]] {
        let v: Vec<f64> = names.iter().map(|c| val(tg, 0, c)).collect();
        for (i, c) in names.iter().enumerate() {
            let want: f64 = (0..3).map(|j| m[j][i] * v[j]).sum();
            assert!(
                (val(tu, 0, c) - want).abs() < 1e-14,
                "{c}: {} vs {want}",
                val(tu, 0, c)
            );
        }
    }
    // beta = 90: x' = -z, so DX = -DZ global (code_aster's matrot, as
    // DEFI_GROUP's normal of ANGL_NAUT (0, -90) is +z).
    let s = run(
        "beta",
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='U', CHAM_GD=ROT,
             NOEUD='N2', NOM_CMP='DRX', REPERE='UTILISATEUR', ANGL_NAUT=(0., 90., 0.)))\n",
    );
    assert!((val(table(&s, "T"), 0, "DRX") + 3.0).abs() < 1e-14);
}

/// code_aster turns DEPL_R fields only (extchn -> rvchn1/rvchn2 stop with
/// POSTRELE_17 on any other quantity): a nodal stress tensor is not
/// turned by POST_RELEVE_T, so aster refuses it at REPERE rather than
/// turn what code_aster does not.
#[test]
fn a_stress_field_is_refused_as_code_aster_refuses_it() {
    for repere in [
        "REPERE='UTILISATEUR', ANGL_NAUT=(30., 0., 0.)",
        "REPERE='CYLINDRIQUE', ORIGINE=(0., 0., 0.), AXE_Z=(0., 0., 1.)",
    ] {
        let e = run_err(&format!(
            "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='S', CHAM_GD=SIG,\n\
             NOEUD='N1', NOM_CMP='SIXX', {repere}))\n"
        ));
        assert!(
            e.contains("POST_RELEVE_T/ACTION/REPERE")
                && e.contains("POSTRELE_17")
                && e.contains("SIG is not one")
                && e.contains("t.comm:7:"),
            "{e}"
        );
    }
}

/// The keywords of the frames, each refused at its place.
#[test]
fn frame_keywords_are_checked() {
    for (args, wants) in [
        (
            "NOM_CMP='DX', REPERE='UTILISATEUR'",
            &["POST_RELEVE_T/ACTION/REPERE", "needs ANGL_NAUT"][..],
        ),
        (
            // (ORIGINE without AXE_Z is the catalogue's PRESENT_PRESENT.)
            "NOM_CMP='DX', REPERE='CYLINDRIQUE', AXE_Z=(0., 0., 1.)",
            &["POST_RELEVE_T/ACTION/REPERE", "ORIGINE is missing"],
        ),
        (
            "NOM_CMP='DX', ANGL_NAUT=(30., 0., 0.)",
            &[
                "POST_RELEVE_T/ACTION/ANGL_NAUT",
                "goes with REPERE='UTILISATEUR'",
            ],
        ),
        (
            "NOM_CMP='DX', REPERE='UTILISATEUR', ANGL_NAUT=(30., 0., 0.), ORIGINE=(0., 0., 0.), AXE_Z=(0., 0., 1.)",
            &["POST_RELEVE_T/ACTION/ORIGINE", "goes with REPERE='CYLINDRIQUE'"],
        ),
        (
            "NOM_CMP='DX', REPERE='CYLINDRIQUE', ORIGINE=(0., 0., 0.), AXE_Z=(0., 0., 0.)",
            &["POST_RELEVE_T/ACTION/AXE_Z", "PREPOST_38"],
        ),
    ] {
        let e = run_err(&format!(
            "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='E', CHAM_GD=ROT,\n\
             NOEUD='N1', {args}))\n"
        ));
        for w in wants {
            assert!(e.contains(w) && e.contains("t.comm:"), "{args}: {w}: {e}");
        }
    }
    // EXTREMA and MOYENNE_ARITH have no frame in code_aster's catalogue.
    let e = run_err(
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTREMA', INTITULE='E', CHAM_GD=ROT,\n\
         NOEUD='N1', REPERE='UTILISATEUR', ANGL_NAUT=(30., 0., 0.)))\n",
    );
    assert!(
        e.contains("POST_RELEVE_T/ACTION/ANGL_NAUT") && e.contains("EXTREMA and MOYENNE_ARITH"),
        "{e}"
    );
    // LOCAL and POLAIRE stop the check, at their line.
    let e = run_err(
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='E', CHAM_GD=ROT,\n\
         NOEUD='N1', NOM_CMP='DX', REPERE='POLAIRE'))\n",
    );
    assert!(
        e.contains("not implemented yet: POST_RELEVE_T/ACTION/REPERE='POLAIRE'")
            && e.contains("t.comm:7:"),
        "{e}"
    );
}

/// tests/studies/post_repere.comm: the frames as a user writes them,
/// CREA_CHAMP of a displacement known in closed form (radial expansion,
/// rigid rotation, axial translation about an axis off the origin) on a
/// HEXA8 read from a `.mail`, TEST_TABLE filtering INTITULE and NOEUD:
/// EXTRACTION in the cylindrical frame (and with the axis reversed), in
/// three frames of nautical angles, RESULTANTE and MOYENNE in the
/// cylindrical frame. 21 ANALYTIQUE checks to 1e-12 relative.
#[test]
fn a_user_study_checks_the_frames_with_test_table() {
    let run = common::run_study("tests/studies/post_repere.comm", "post_repere");
    let resu = common::assert_all_ok(&run, "post_repere.resu");
    assert_eq!(resu.matches("OK   ANALYTIQUE").count(), 21, "{resu}");
}
