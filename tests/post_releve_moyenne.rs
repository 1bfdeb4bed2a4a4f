//! POST_RELEVE_T OPERATION='MOYENNE': the mean, first moment and extrema
//! of nodal fields along a line of nodes, against hand values.
//!
//! code_aster's `rvpstm` (its sources, bibfor/postrele) integrates the
//! nodal values, linear between successive nodes, along the curvilinear
//! abscissa s (the sum of the chords from the first node), L the length:
//!   MOMENT_0 = (1/L) ∫ f ds,  MOMENT_1 = (12/L²) ∫ f (s − L/2) ds,
//!   MINIMUM, MAXIMUM of the nodal values,
//!   MOYE_INT = MOMENT_0 − MOMENT_1/2,  MOYE_EXT = MOMENT_0 + MOMENT_1/2,
//! six rows in that order (`rvtamo`), QUANTITE naming them.
//!
//! The synthetic data (test-only commands SYNTH_MAIL, SYNTH_RESU,
//! SYNTH_CHAMP, as tests/post_commands.rs does), a 2D mesh:
//!   LINE  N1..N5 at x = 0, 0.5, 2, 3, 6 on y = 0 (uneven spacing);
//!   ARC   N6..N8 on the circle of radius 2 at θ = 0, π/6, π/2;
//!   GAP   N9..N12 at x = 0, 1, 2, 3 on y = 5 (DZ absent at N12);
//!   UNI   N13..N15 at x = 0, 1, 2 on y = −1;
//!   ONE   N1 alone.
//! CH: DX = 2 + 3x + y, DY = x², DZ = atan2(y, x) (absent at N12).
//! CH7: seven components V1..V7 = 1..7 everywhere.
//! RESU: two steps t = 0.5, 1 with DEPL DX = t (2 + 3x + y), DY = t x².

#![allow(clippy::result_large_err)]

use std::f64::consts::PI;

use aster::catalog::args::Args;
use aster::commands::{CommandDef, ExecResult};
use aster::concepts::{ConceptData, ConceptType as C};
use aster::mesh::{Cell, CellType, Mesh};
use aster::post::table::{Cell as TCell, Table};
use aster::result::{EvolNoli, NodalField, Step};
use aster::study::Study;

mod common;

const GAP_ABSENT: usize = 11;

fn mesh() -> Mesh {
    let r = 2.0;
    let mut coords = vec![];
    for x in [0.0, 0.5, 2.0, 3.0, 6.0] {
        coords.push([x, 0.0, 0.0]);
    }
    for t in [0.0, PI / 6.0, PI / 2.0] {
        coords.push([r * f64::cos(t), r * f64::sin(t), 0.0]);
    }
    for x in [0.0, 1.0, 2.0, 3.0] {
        coords.push([x, 5.0, 0.0]);
    }
    for x in [0.0, 1.0, 2.0] {
        coords.push([x, -1.0, 0.0]);
    }
    let lines: [&[usize]; 4] = [&[0, 1, 2, 3, 4], &[5, 6, 7], &[8, 9, 10, 11], &[12, 13, 14]];
    let mut cells = vec![];
    for l in lines {
        for w in l.windows(2) {
            cells.push(Cell {
                kind: CellType::Seg2,
                nodes: w.to_vec(),
            });
        }
    }
    let mut m = Mesh {
        name: "lines".into(),
        dim: 2,
        coords,
        cells,
        ..Mesh::default()
    };
    for (name, l) in ["LINE", "ARC", "GAP", "UNI"].iter().zip(lines) {
        m.node_groups.insert(name.to_string(), l.to_vec());
    }
    m.node_groups.insert("ONE".into(), vec![0]);
    // The line backwards, to check the path follows the group's order.
    m.node_groups.insert("ENIL".into(), vec![4, 3, 2, 1, 0]);
    m
}

fn dx(p: [f64; 3]) -> f64 {
    2.0 + 3.0 * p[0] + p[1]
}
fn dy(p: [f64; 3]) -> f64 {
    p[0] * p[0]
}

fn synth_mail(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    Ok(Some(ConceptData::Mesh(Box::new(mesh()))))
}

fn synth_resu(_s: &mut Study, a: &Args, _r: Option<&str>) -> ExecResult {
    let m = mesh();
    let mut r = EvolNoli {
        mesh: a.concept("MAILLAGE").unwrap().to_string(),
        ..EvolNoli::default()
    };
    for (k, t) in [0.5, 1.0].into_iter().enumerate() {
        let mut depl = NodalField::zeros(vec!["DX".into(), "DY".into()], m.nnodes());
        for n in 0..m.nnodes() {
            depl.set(n, 0, t * dx(m.coords[n]));
            depl.set(n, 1, t * dy(m.coords[n]));
        }
        let mut s = Step {
            nume_ordre: k + 1,
            inst: t,
            ..Step::default()
        };
        s.nodal.insert("DEPL".into(), depl);
        r.steps.push(s);
    }
    Ok(Some(ConceptData::Result(Box::new(r))))
}

fn champ(f: NodalField) -> ExecResult {
    Ok(Some(ConceptData::Field(Box::new(
        aster::concepts::ChamNo {
            mesh: "MA".into(),
            field: f,
        },
    ))))
}

fn synth_champ(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    let m = mesh();
    let mut f = NodalField::absent(vec!["DX".into(), "DY".into(), "DZ".into()], m.nnodes());
    for n in 0..m.nnodes() {
        let p = m.coords[n];
        f.set(n, 0, dx(p));
        f.set(n, 1, dy(p));
        if n != GAP_ABSENT {
            f.set(n, 2, p[1].atan2(p[0]));
        }
    }
    champ(f)
}

fn synth_champ7(_s: &mut Study, _a: &Args, _r: Option<&str>) -> ExecResult {
    let m = mesh();
    let names = (1..=7).map(|i| format!("V{i}")).collect();
    let mut f = NodalField::absent(names, m.nnodes());
    for n in 0..m.nnodes() {
        for i in 0..7 {
            f.set(n, i, (i + 1) as f64);
        }
    }
    champ(f)
}

fn registry() -> Vec<CommandDef> {
    common::synth_registry(&[
        ("SYNTH_MAIL", C::Maillage, synth_mail),
        ("SYNTH_RESU", C::EvolNoli, synth_resu),
        ("SYNTH_CHAMP", C::ChamNo, synth_champ),
        ("SYNTH_CHAMP7", C::ChamNo, synth_champ7),
    ])
}

const PRELUDE: &str = "DEBUT()\nMA = SYNTH_MAIL()\nRESU = SYNTH_RESU(MAILLAGE=MA)\n\
                       CH = SYNTH_CHAMP()\nCH7 = SYNTH_CHAMP7()\n";

const TEXT: common::TextStudies = common::TextStudies {
    prefix: "post_moyenne",
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

const QUANTITIES: [&str; 6] = [
    "MOMENT_0", "MOMENT_1", "MINIMUM", "MAXIMUM", "MOYE_INT", "MOYE_EXT",
];

/// The six values of component `cmp` in rows `first..first + 6`, after
/// checking their QUANTITE names and order.
fn six(t: &Table, first: usize, cmp: &str) -> [f64; 6] {
    let mut out = [0.0; 6];
    for (k, q) in QUANTITIES.iter().enumerate() {
        match t.cell(first + k, "QUANTITE") {
            Some(TCell::Text(name)) => assert_eq!(name, q, "row {}", first + k),
            other => panic!("row {}: QUANTITE {other:?}", first + k),
        }
        out[k] = t
            .cell(first + k, cmp)
            .and_then(|c| c.as_f64())
            .unwrap_or_else(|| panic!("row {}: no {cmp}", first + k));
    }
    out
}

fn close(got: [f64; 6], want: [f64; 6], tol: f64, what: &str) {
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= tol * w.abs().max(1.0),
            "{what} {}: {g} vs {w} ({got:?})",
            QUANTITIES[k]
        );
    }
}

/// A linear field along an unevenly spaced straight line: f = 2 + 3x on
/// x ∈ [0, 6]. Linear interpolation between the nodes is exact, so the
/// mean is the value at the midpoint f(3) = 11 whatever the spacing, and
/// the linear part is f itself: MOMENT_1 = f(6) − f(0) = 18, MOYE_INT =
/// f(0) = 2, MOYE_EXT = f(6) = 20 = MAXIMUM. Backwards (group ENIL) the
/// path starts at x = 6: MOMENT_1 changes sign, MOYE_INT and MOYE_EXT
/// swap. The quadratic DY = x² on the same nodes: code_aster integrates
/// the nodal values linearly, segment by segment, so the hand reference
/// is the trapezoidal sum (b − a)(a² + b²)/2 over [0, .5], [.5, 2],
/// [2, 3], [3, 6]: 0.0625 + 3.1875 + 6.5 + 67.5 = 77.25, mean 12.875
/// (the exact mean of x², 12, is not what it computes); ∫ f s ds by
/// Simpson per segment (exact for the quadratic f·s):
/// h/6 (f_a a + 4 f_m m + f_b b), f_m = (f_a + f_b)/2, m = (a + b)/2:
/// 0.0208333 + 4.6875 + 16.666667 + 324 = 345.375 (a fine trapezoidal
/// quadrature of the interpolant gives the same);
/// MOMENT_1 = 12/36 · 345.375 − 6/6 · 77.25 = 37.875.
#[test]
fn moyenne_of_linear_and_quadratic_fields_on_an_uneven_line() {
    let s = run(
        "line",
        "T = POST_RELEVE_T(ACTION=(
             _F(OPERATION='MOYENNE', INTITULE='LIN', CHAM_GD=CH, GROUP_NO='LINE',
                NOM_CMP=('DX', 'DY')),
             _F(OPERATION='MOYENNE', INTITULE='NIL', CHAM_GD=CH, GROUP_NO='ENIL',
                NOM_CMP='DX'),))
         IMPR_TABLE(TABLE=T)
         FIN()\n",
    );
    let t = table(&s, "T");
    assert_eq!(t.columns, ["INTITULE", "CHAM_GD", "DX", "DY", "QUANTITE"]);
    assert_eq!(t.n_rows(), 12);
    close(
        six(t, 0, "DX"),
        [11.0, 18.0, 2.0, 20.0, 2.0, 20.0],
        1e-13,
        "DX",
    );
    let int_fs: f64 = 0.5 / 6.0 * (0.25 * 0.5 + 4.0 * 0.125 * 0.25)
        + 1.5 / 6.0 * (0.25 * 0.5 + 4.0 * 2.125 * 1.25 + 4.0 * 2.0)
        + 1.0 / 6.0 * (4.0 * 2.0 + 4.0 * 6.5 * 2.5 + 9.0 * 3.0)
        + 3.0 / 6.0 * (9.0 * 3.0 + 4.0 * 22.5 * 4.5 + 36.0 * 6.0);
    assert!((int_fs - 345.375).abs() < 1e-12, "{int_fs}");
    let m0 = 77.25 / 6.0;
    let m1 = 12.0 / 36.0 * int_fs - 77.25;
    assert!((m1 - 37.875).abs() < 1e-12, "{m1}");
    close(
        six(t, 0, "DY"),
        [m0, m1, 0.0, 36.0, m0 - m1 / 2.0, m0 + m1 / 2.0],
        1e-13,
        "DY",
    );
    close(
        six(t, 6, "DX"),
        [11.0, -18.0, 2.0, 20.0, 20.0, 2.0],
        1e-13,
        "DX backwards",
    );
    assert!(s.resu.contains("QUANTITE"), "{}", s.resu);
}

/// x² on the evenly spaced nodes x = 0, 1, 2 (group UNI): trapezoid mean
/// (0.5 + 2.5)/2 = 1.5; ∫ f (s − 1) ds = −1/6 + 3/2 = 4/3 (f = s on
/// [0, 1], 3s − 2 on [1, 2]), MOMENT_1 = 12/4 · 4/3 = 4; MOYE_INT −0.5,
/// MOYE_EXT 3.5; MINIMUM 0 and MAXIMUM 4 at the ends.
#[test]
fn moyenne_of_a_quadratic_on_even_nodes() {
    let s = run(
        "uni",
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='MOYENNE', INTITULE='UNI', CHAM_GD=CH,
                GROUP_NO='UNI', NOM_CMP='DY'))\n",
    );
    close(
        six(table(&s, "T"), 0, "DY"),
        [1.5, 4.0, 0.0, 4.0, -0.5, 3.5],
        1e-13,
        "DY",
    );
}

/// A curved line: code_aster's abscissa is the sum of the chords between
/// successive nodes (`rvabsc`), not the arc length. On the circle of
/// radius 2 at θ = 0, π/6, π/2 the chords are c1 = 4 sin(π/12) and
/// c2 = 4 sin(π/6) = 2. With f = θ (DZ = atan2(y, x)): MOMENT_0 =
/// (c1 (0 + π/6) + c2 (π/6 + π/2)) / (2 (c1 + c2)); MOMENT_1 =
/// (12/L²) Σ h/6 (f_a a + 4 f_m m + f_b b) − 6 MOMENT_0.
#[test]
fn moyenne_on_a_curved_line_uses_the_chords() {
    let s = run(
        "arc",
        "T = POST_RELEVE_T(ACTION=_F(OPERATION='MOYENNE', INTITULE='ARC', CHAM_GD=CH,
                GROUP_NO='ARC', NOM_CMP='DZ'))\n",
    );
    let (c1, c2) = (4.0 * (PI / 12.0).sin(), 2.0);
    let l = c1 + c2;
    let (f0, f1, f2) = (0.0, PI / 6.0, PI / 2.0);
    let m0 = (c1 * (f0 + f1) + c2 * (f1 + f2)) / (2.0 * l);
    let simpson = |a: f64, b: f64, fa: f64, fb: f64| {
        (b - a) / 6.0 * (fa * a + 4.0 * (fa + fb) / 2.0 * (a + b) / 2.0 + fb * b)
    };
    let int_fs = simpson(0.0, c1, f0, f1) + simpson(c1, l, f1, f2);
    let m1 = 12.0 / (l * l) * int_fs - 6.0 * m0;
    close(
        six(table(&s, "T"), 0, "DZ"),
        [m0, m1, 0.0, PI / 2.0, m0 - m1 / 2.0, m0 + m1 / 2.0],
        1e-13,
        "DZ",
    );
    // Not the arc-length mean of θ (π/4 for θ uniform in arc length).
    assert!((m0 - PI / 4.0).abs() > 5e-3, "{m0}");
}

/// A node where the component is absent. Asked alone (NOM_CMP='DZ'), N12
/// carries none of the components and leaves the path (code_aster's
/// `rvouex` keeps the nodes carrying one of them): the path is N9..N11,
/// x = 0..2 on y = 5, f = atan2(5, x). Asked with DX (present at N12),
/// N12 stays on the path and its DZ segment [2, 3] is left out, with
/// code_aster's alarm POSTRELE_62: the same DZ numbers. The DX row of
/// the second occurrence runs over x = 0..3: f = 7 + 3x, mean f(1.5) =
/// 11.5, MOMENT_1 = 9.
#[test]
fn moyenne_leaves_out_the_segments_of_an_absent_component() {
    let s = run(
        "gap",
        "T = POST_RELEVE_T(ACTION=(
             _F(OPERATION='MOYENNE', INTITULE='DZ', CHAM_GD=CH, GROUP_NO='GAP', NOM_CMP='DZ'),
             _F(OPERATION='MOYENNE', INTITULE='DXDZ', CHAM_GD=CH, GROUP_NO='GAP',
                NOM_CMP=('DX', 'DZ')),))\n",
    );
    let t = table(&s, "T");
    let f: Vec<f64> = (0..3).map(|x| 5f64.atan2(x as f64)).collect();
    let m0 = ((f[0] + f[1]) / 2.0 + (f[1] + f[2]) / 2.0) / 2.0;
    let int_fs = (f[0] * 0.0 + 4.0 * (f[0] + f[1]) / 2.0 * 0.5 + f[1]) / 6.0
        + (f[1] + 4.0 * (f[1] + f[2]) / 2.0 * 1.5 + f[2] * 2.0) / 6.0;
    let m1 = 12.0 / 4.0 * int_fs - 6.0 * m0;
    let want = [m0, m1, f[2], f[0], m0 - m1 / 2.0, m0 + m1 / 2.0];
    close(six(t, 0, "DZ"), want, 1e-13, "DZ alone");
    close(six(t, 6, "DZ"), want, 1e-13, "DZ with DX");
    close(
        six(t, 6, "DX"),
        [11.5, 9.0, 7.0, 16.0, 7.0, 16.0],
        1e-13,
        "DX",
    );
    assert_eq!(
        s.mess.matches("<A> <POST_RELEVE_T> <POSTRELE_62>").count(),
        1,
        "{}",
        s.mess
    );
}

/// A transient result: six rows per stored step, with RESU, NOM_CHAM,
/// NUME_ORDRE and INST, checked by TEST_TABLE as a code_aster user
/// writes it (FILTRE on INST and QUANTITE). DEPL DX = t (2 + 3x) on LINE:
/// MOMENT_0 = 11 t, MOMENT_1 = 18 t. NOEUD before GROUP_NO: code_aster's
/// path takes the nodes of NOEUD first (`rvgnoe`), so N5 then N1..N4 is
/// the path x = 6, 0, 0.5, 2, 3 (abscissae 0, 6, 6.5, 8, 9), not the
/// line: f = 20 t, 2 t, 3.5 t, 8 t, 11 t; trapezoid sum 6·11 + 0.5·2.75
/// + 1.5·5.75 + 1·9.5 = 85.5 (× t), MOMENT_0 = 9.5 t.
#[test]
fn moyenne_of_a_result_per_step_and_test_table() {
    let s = run(
        "resu",
        "T = POST_RELEVE_T(ACTION=(
             _F(OPERATION='MOYENNE', INTITULE='LIN', RESULTAT=RESU, NOM_CHAM='DEPL',
                GROUP_NO='LINE', TOUT_CMP='OUI'),
             _F(OPERATION='MOYENNE', INTITULE='N5_FIRST', RESULTAT=RESU, NOM_CHAM='DEPL',
                NOEUD='N5', GROUP_NO='LINE', NOM_CMP='DX', INST=1.),))
         TEST_TABLE(TABLE=T, NOM_PARA='DX', VALE_CALC=11., VALE_REFE=11.,
                    REFERENCE='ANALYTIQUE', PRECISION=1.E-12,
                    FILTRE=(_F(NOM_PARA='INTITULE', VALE_K='LIN'),
                            _F(NOM_PARA='INST', VALE=1.),
                            _F(NOM_PARA='QUANTITE', VALE_K='MOMENT_0')))
         TEST_TABLE(TABLE=T, NOM_PARA='DX', VALE_CALC=9., VALE_REFE=9.,
                    REFERENCE='ANALYTIQUE', PRECISION=1.E-12,
                    FILTRE=(_F(NOM_PARA='INTITULE', VALE_K='LIN'),
                            _F(NOM_PARA='NUME_ORDRE', VALE_I=1),
                            _F(NOM_PARA='QUANTITE', VALE_K='MOMENT_1')))
         TEST_TABLE(TABLE=T, NOM_PARA='DX', VALE_CALC=20., VALE_REFE=20.,
                    REFERENCE='ANALYTIQUE', PRECISION=1.E-12,
                    FILTRE=(_F(NOM_PARA='INST', VALE=1.),
                            _F(NOM_PARA='QUANTITE', VALE_K='MOYE_EXT'),
                            _F(NOM_PARA='INTITULE', VALE_K='LIN'),))
         TEST_TABLE(TABLE=T, NOM_PARA='DX', VALE_CALC=9.5, VALE_REFE=9.5,
                    REFERENCE='ANALYTIQUE', PRECISION=1.E-12,
                    FILTRE=(_F(NOM_PARA='INTITULE', VALE_K='N5_FIRST'),
                            _F(NOM_PARA='QUANTITE', VALE_K='MOMENT_0')))
         FIN()\n",
    );
    let t = table(&s, "T");
    assert_eq!(
        t.columns,
        [
            "INTITULE",
            "RESU",
            "NOM_CHAM",
            "NUME_ORDRE",
            "INST",
            "DX",
            "DY",
            "QUANTITE"
        ]
    );
    assert_eq!(t.n_rows(), 18);
    for (k, time) in [0.5, 1.0].into_iter().enumerate() {
        let mut want = [11.0, 18.0, 2.0, 20.0, 2.0, 20.0];
        want.iter_mut().for_each(|v| *v *= time);
        close(six(t, 6 * k, "DX"), want, 1e-13, "DX");
        assert_eq!(t.cell(6 * k, "INST").and_then(|c| c.as_f64()), Some(time));
    }
    assert_eq!(s.tests.ok, 8, "{}", s.resu); // REFERENCE and NON_REGRESSION lines
    assert_eq!(s.tests.nook, 0, "{}", s.resu);
}

/// ('EXTRACTION', 'MOYENNE'): the node rows then the six MOYENNE rows, as
/// code_aster's `rvpost` writes them for each field.
#[test]
fn extraction_and_moyenne_together() {
    let s = run(
        "pair",
        "T = POST_RELEVE_T(ACTION=_F(OPERATION=('EXTRACTION', 'MOYENNE'), INTITULE='P',
                CHAM_GD=CH, GROUP_NO='UNI', NOM_CMP='DY'))\n",
    );
    let t = table(&s, "T");
    assert_eq!(t.n_rows(), 3 + 6);
    for (k, x) in [0.0, 1.0, 2.0].into_iter().enumerate() {
        assert_eq!(t.cell(k, "DY").and_then(|c| c.as_f64()), Some(x * x));
        assert!(t.cell(k, "QUANTITE").is_none());
    }
    close(
        six(t, 3, "DY"),
        [1.5, 4.0, 0.0, 4.0, -0.5, 3.5],
        1e-13,
        "DY",
    );
    assert!(t.cell(3, "NOEUD").is_none());
}

/// What MOYENNE refuses, each at its keyword with the file position.
#[test]
fn moyenne_bad_input_is_located() {
    let cases: [(&str, &[&str]); 9] = [
        // Cells next to the nodes: what code_aster does with them (the
        // cells of a field by element) is not built.
        (
            "CHAM_GD=CH, GROUP_NO='LINE', GROUP_MA='M1', NOM_CMP='DX'",
            &[
                "not implemented yet: POST_RELEVE_T/ACTION/GROUP_MA",
                "MOYENNE",
            ],
        ),
        // N11-N12: DZ absent at N12, no segment left for it.
        (
            "CHAM_GD=CH, NOEUD=('N11', 'N12'), NOM_CMP=('DX', 'DZ')",
            &[
                "POST_RELEVE_T/ACTION/NOEUD",
                "MOYENNE of DZ of CH",
                "has no length",
            ],
        ),
        // One node: no path (code_aster's POSTRELE_6).
        (
            "CHAM_GD=CH, GROUP_NO='ONE', NOM_CMP='DX'",
            &[
                "POST_RELEVE_T/ACTION/GROUP_NO",
                "at least 2 nodes",
                "POSTRELE_6",
            ],
        ),
        // More than six components (POSTRELE_7).
        (
            "CHAM_GD=CH7, GROUP_NO='LINE', TOUT_CMP='OUI'",
            &["POST_RELEVE_T/ACTION/TOUT_CMP", "at most 6", "7 components"],
        ),
        // RESULTANTE is EXTRACTION's (POSTRELE_67).
        (
            "CHAM_GD=CH, GROUP_NO='LINE', RESULTANTE='DX'",
            &["POST_RELEVE_T/ACTION/RESULTANTE", "POSTRELE_67"],
        ),
        // A cell group alone: the catalogue rule AU_MOINS_UN.
        (
            "CHAM_GD=CH, GROUP_MA='M1', NOM_CMP='DX'",
            &[
                "POST_RELEVE_T/ACTION/GROUP_MA",
                "AU_MOINS_UN('GROUP_NO', 'NOEUD')",
                "group's order",
            ],
        ),
        (
            "CHAM_GD=CH, GROUP_NO='LINE', NOM_CMP='DX', REPERE='LOCAL'",
            &["not implemented yet: POST_RELEVE_T/ACTION/REPERE"],
        ),
        (
            "RESULTAT=RESU, NOM_CHAM='DEPL', GROUP_NO='LINES', NOM_CMP='DX'",
            &["POST_RELEVE_T/ACTION/GROUP_NO", "no node group 'LINES'"],
        ),
        (
            "CHAM_GD=CH, GROUP_NO='LINE', NOM_CMP='TEMP'",
            &["POST_RELEVE_T/ACTION/NOM_CMP", "TEMP"],
        ),
    ];
    for (args, wants) in cases {
        let e = run_err(&format!(
            "T = POST_RELEVE_T(ACTION=_F(OPERATION='MOYENNE', INTITULE='M', {args}))\n"
        ));
        for w in wants {
            assert!(e.contains(w), "{args}: {w}: {e}");
        }
        assert!(e.contains("t.comm:6:"), "{args}: {e}");
    }
    // Two operations other than the pair ('EXTRACTION', 'MOYENNE').
    let e = run_err(
        "T = POST_RELEVE_T(ACTION=_F(OPERATION=('MOYENNE', 'EXTREMA'), INTITULE='M',
                CHAM_GD=CH, GROUP_NO='LINE', NOM_CMP='DX'))\n",
    );
    assert!(
        e.contains("not implemented yet: POST_RELEVE_T/ACTION/OPERATION")
            && e.contains("the pair ('EXTRACTION', 'MOYENNE')"),
        "{e}"
    );
}

/// tests/studies/post_moyenne.comm: MOYENNE as a user writes it, on the
/// exact linear field of a plane strain plate pulled along x (a patch
/// test on an unevenly spaced QUAD4 mesh read from a `.mail`), TEST_TABLE
/// filtering INTITULE and QUANTITE: means at mid-path, MOMENT_1 as the
/// difference of the ends (its sign with the path's direction), a bent
/// path by NOEUD, a constant stress (MOMENT_1 = 0). All 14 ANALYTIQUE
/// checks to 1e-10 relative (1e-8 absolute for the zeros).
#[test]
fn a_user_study_checks_moyenne_with_test_table() {
    let run = common::run_study("tests/studies/post_moyenne.comm", "post_moyenne");
    let resu = common::assert_all_ok(&run, "post_moyenne.resu");
    assert_eq!(resu.matches("OK   ANALYTIQUE").count(), 14, "{resu}");
    let rows = common::printed_table(&resu, "MOY");
    assert_eq!(rows.len(), 5 * 6, "{resu}");
    let coude: Vec<_> = rows.iter().filter(|r| r["INTITULE"] == "COUDE").collect();
    let q: Vec<&str> = coude.iter().map(|r| r["QUANTITE"].as_str()).collect();
    assert_eq!(
        q,
        ["MOMENT_0", "MOMENT_1", "MINIMUM", "MAXIMUM", "MOYE_INT", "MOYE_EXT"]
    );
}
