//! TEST_RESU / TEST_TABLE checks: pass rules and the exact printed lines.
//!
//! Expected lines were produced by code_aster's own printing logic
//! (TestResult.showResult, Python 3) on the same inputs; expected numbers of
//! `py_repr` are CPython 3 `repr()` outputs.

use aster::post::test_report::TestCounts;
use aster::post::test_report::*;

fn real(x: f64) -> Value {
    Value::Real(x)
}

#[test]
fn py_repr_matches_python() {
    let table: &[(f64, &str)] = &[
        (0.1, "0.1"),
        (1e-05, "1e-05"),
        (1e16, "1e+16"),
        (1e15, "1000000000000000.0"),
        (123456789012345678.0, "1.2345678901234568e+17"),
        (12345678901234567.0, "1.2345678901234568e+16"),
        (-2.32675, "-2.32675"),
        (227000.0, "227000.0"),
        (3.87, "3.87"),
        (1.5e-07, "1.5e-07"),
        (0.0, "0.0"),
        (-0.0, "-0.0"),
        (0.0001, "0.0001"),
        (0.00012345, "0.00012345"),
        (1.0 / 3.0, "0.3333333333333333"),
        (0.1 + 0.2, "0.30000000000000004"),
        (2.220446049250313e-16, "2.220446049250313e-16"),
        (-1e-300, "-1e-300"),
        (5e-324, "5e-324"),
        (f64::MAX, "1.7976931348623157e+308"),
        (100.0, "100.0"),
        (32.4, "32.4"),
        (-1e22, "-1e+22"),
        (1e-6 * 100.0, "9.999999999999999e-05"),
    ];
    for (x, expected) in table {
        assert_eq!(py_repr(*x), *expected, "py_repr({x:e})");
    }
    assert_eq!(py_repr(f64::INFINITY), "inf");
    assert_eq!(py_repr(f64::NAN), "nan");
}

#[test]
fn c_exp_matches_printf() {
    assert_eq!(c_exp(-2.32675, 12, 5, true), "-2.32675E+00");
    assert_eq!(c_exp(1e-5, 12, 5, true), " 1.00000E-05");
    assert_eq!(c_exp(1.5e100, 12, 5, true), "1.50000E+100");
    assert_eq!(c_exp(5.157408e-05, 13, 6, false), " 5.157408e-05");
    assert_eq!(c_exp(-0.0, 12, 5, true), "-0.00000E+00");
}

#[test]
fn relative_ok_and_nook() {
    // |v - ref| = 1.2e-6 <= 1e-6 * 2.32675 = 2.3e-6: OK
    let l = check(
        RefKind::NonRegression,
        &real(-2.3267512),
        &[real(-2.32675)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
    // |v - ref| = 1.0123e-2 > 1e-3: NOOK, error printed in percent
    let l = check(
        RefKind::Analytique,
        &real(1.0123456789),
        &[real(1.0)],
        1e-3,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Nook);
    assert!((l.error.unwrap() - 1.23456789).abs() < 1e-9);
}

#[test]
fn absolute_ok_and_nook() {
    let l = check(
        RefKind::Analytique,
        &real(10.0004),
        &[real(10.0)],
        1e-3,
        Critere::Absolu,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
    let l = check(
        RefKind::Analytique,
        &real(10.002),
        &[real(10.0)],
        1e-3,
        Critere::Absolu,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Nook);
    // ORDRE_GRANDEUR scales the absolute tolerance: 1e-6 * 1e3 = 1e-3.
    let l = check(
        RefKind::Analytique,
        &real(10.0005),
        &[real(10.0)],
        1e-6,
        Critere::Absolu,
        Some(1e3),
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
}

#[test]
fn closest_of_several_references_is_used() {
    // 5.0 fails against 1.0 and 9.0, passes against 5.004 (0.08 % < 0.1 %).
    let refs = [real(1.0), real(5.004), real(9.0)];
    let l = check(
        RefKind::SourceExterne,
        &real(5.0),
        &refs,
        1e-3,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
    assert_eq!(l.reference, Some(real(5.004)));
}

#[test]
fn zero_vale_calc_is_skipped_without_ordre_grandeur() {
    let l = check(
        RefKind::NonRegression,
        &real(3.2e-7),
        &[real(0.0)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Skip);
    assert_eq!(l.alarms[0].id, "TEST0_12");
    // 2.2e-16 still counts as zero, 3e-16 does not.
    let l = check(
        RefKind::NonRegression,
        &real(0.0),
        &[real(2.2e-16)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Skip);
    let l = check(
        RefKind::NonRegression,
        &real(0.0),
        &[real(3e-16)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Nook);
}

#[test]
fn zero_vale_calc_with_ordre_grandeur_is_tested() {
    // |3.2e-7 - 0| <= 1e-6 * 1.0 : OK in ABSOLU
    let l = check(
        RefKind::NonRegression,
        &real(3.2e-7),
        &[real(0.0)],
        1e-6,
        Critere::Absolu,
        Some(1.0),
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
    // with ORDRE_GRANDEUR=1e-3 the bound is 1e-9: NOOK
    let l = check(
        RefKind::NonRegression,
        &real(3.2e-7),
        &[real(0.0)],
        1e-6,
        Critere::Absolu,
        Some(1e-3),
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Nook);
    // RELATIF ignores ORDRE_GRANDEUR (as code_aster): only an exact 0 passes.
    let l = check(
        RefKind::NonRegression,
        &real(3.2e-7),
        &[real(0.0)],
        1e-6,
        Critere::Relatif,
        Some(1.0),
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Nook);
    assert_eq!(l.error, Some(999.999999));
}

#[test]
fn vale_abs_compares_absolute_values() {
    let l = check(
        RefKind::Analytique,
        &real(-3.0),
        &[real(3.0)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Nook);
    let l = check(
        RefKind::Analytique,
        &real(-3.0),
        &[real(3.0)],
        1e-6,
        Critere::Relatif,
        None,
        true,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
    assert_eq!(l.computed, real(3.0));
}

#[test]
fn integer_checks() {
    let l = check(
        RefKind::NonRegression,
        &Value::Int(15),
        &[Value::Int(15)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
    let l = check(
        RefKind::NonRegression,
        &Value::Int(16),
        &[Value::Int(15)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Nook);
    // a difference of 1 within an absolute tolerance of 2
    let l = check(
        RefKind::Analytique,
        &Value::Int(16),
        &[Value::Int(15)],
        2.0,
        Critere::Absolu,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
    // VALE_CALC_I = 0 is not subject to the skip rule (reals only)
    let l = check(
        RefKind::NonRegression,
        &Value::Int(0),
        &[Value::Int(0)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
}

#[test]
fn type_mismatch_is_an_error() {
    let e = check(
        RefKind::NonRegression,
        &real(15.0),
        &[Value::Int(15)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap_err();
    assert!(e.contains("VALE_CALC_I") && e.contains("real"), "{e}");
    // A reference names the VALE_REFE keywords, the one given and the one
    // expected (the message named VALE_CALC).
    let e = check(
        RefKind::Analytique,
        &Value::Int(50),
        &[real(50.0)],
        1e-6,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap_err();
    assert!(
        e.contains("a real (VALE_REFE)") && e.contains("give it as VALE_REFE_I"),
        "{e}"
    );
    assert!(!e.contains("VALE_CALC"), "{e}");
    let e = check(
        RefKind::NonRegression,
        &real(1.0),
        &[real(1.0)],
        -1.0,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap_err();
    assert!(e.contains("tolerance"), "{e}");
}

#[test]
fn text_checks() {
    let t = |s: &str| Value::Text(s.to_string());
    let l = check(
        RefKind::NonRegression,
        &t("RESU"),
        &[t("RESU    ")],
        0.0,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Ok);
    let l = check(
        RefKind::NonRegression,
        &t("RESU"),
        &[t("RES")],
        0.0,
        Critere::Relatif,
        None,
        false,
    )
    .unwrap();
    assert_eq!(l.status, Status::Nook);
    let lines = format_check(&l, true);
    assert_eq!(
        lines[0],
        "      REFERENCE        LEGENDE          VALE_REFE                VALE_CALC               "
    );
    assert_eq!(
        lines[1],
        "NOOK  NON_REGRESSION   XXXX             RES                      RESU                    "
    );
}

#[test]
fn missing_vale_calc_is_a_skip_that_shows_the_value() {
    let spec = TestSpec::new(vec![]);
    let lines = occurrence_checks(&spec, &real(-2.3267512)).unwrap();
    assert_eq!(lines.len(), 1);
    assert_eq!(lines[0].status, Status::Skip);
    assert_eq!(lines[0].note.as_deref(), Some("VALE_CALC not recorded"));
    let text = format_check(&lines[0], false);
    assert_eq!(
        text[0],
        "SKIP  NON_REGRESSION   -                -                  -2.3267512         -                -                VALE_CALC not recorded"
    );
}

#[test]
fn printed_lines_match_code_aster() {
    let mut spec = TestSpec::new(vec![real(-2.32675)]);
    spec.reference = Some(Reference {
        kind: RefKind::SourceExterne,
        values: vec![real(-2.33)],
        precision: 1e-2,
    });
    let lines = occurrence_checks(&spec, &real(-2.3267512)).unwrap();
    let text = format_checks(&lines);
    assert_eq!(
        text,
        vec![
            "      REFERENCE        LEGENDE          VALE_REFE          VALE_CALC          ERREUR           TOLE            ",
            " OK   NON_REGRESSION   XXXX             -2.32675           -2.3267512          5.157408E-05%   9.999999999999999E-05%",
            " OK   SOURCE_EXTERNE   XXXX             -2.33              -2.3267512          1.394335E-01%   1.0%            ",
        ]
    );
    // ORDRE_GRANDEUR line (printed before the titles), absolute test.
    let mut spec = TestSpec::new(vec![real(0.0)]);
    spec.critere = Critere::Absolu;
    spec.ordre_grandeur = Some(1e-3);
    let lines = occurrence_checks(&spec, &real(3.2e-7)).unwrap();
    assert_eq!(
        format_checks(&lines),
        vec![
            "      ORDRE DE GRANDEUR : 0.001           ",
            "      REFERENCE        LEGENDE          VALE_REFE          VALE_CALC          ERREUR           TOLE            ",
            "NOOK  NON_REGRESSION   XXXX             0.0                3.2E-07            3.2E-07          1E-09           ",
        ]
    );
    // SKIP line and TEST0_11 when there is no reference.
    let lines = occurrence_checks(&TestSpec::new(vec![real(0.0)]), &real(3.2e-7)).unwrap();
    assert_eq!(
        format_checks(&lines)[1],
        "SKIP  NON_REGRESSION   -                -                  -                  -                -               "
    );
    let ids: Vec<&str> = lines[0].alarms.iter().map(|a| a.id).collect();
    assert_eq!(ids, ["TEST0_12", "TEST0_11"]);
    // integers
    let lines = occurrence_checks(&TestSpec::new(vec![Value::Int(15)]), &Value::Int(15)).unwrap();
    assert_eq!(
        format_checks(&lines)[1],
        " OK   NON_REGRESSION   XXXX             15                 15                 0.0%             9.999999999999999E-05%"
    );
}

#[test]
fn header_columns() {
    let [l1, l2] = header_lines(
        "RESULTAT",
        "RESU",
        &[
            ("NUME_ORDRE", "21"),
            ("NOM_CHAM", "DEPL"),
            ("NOM_CMP", "DY"),
            ("GROUP_NO", "A_VERY_LONG_GROUP_NAME"),
        ],
    );
    assert_eq!(
        l1,
        " ---- RESULTAT         NUME_ORDRE       NOM_CHAM         NOM_CMP          GROUP_NO"
    );
    assert_eq!(l2, "      RESU             21               DEPL             DY               A_VERY_LONG_GROU");
}

#[test]
fn resu_block_snapshot() {
    let mut spec = TestSpec::new(vec![real(-2.32675)]);
    spec.legend = Some("DY A2".to_string());
    spec.reference = Some(Reference {
        kind: RefKind::SourceExterne,
        values: vec![real(-2.33)],
        precision: 1e-2,
    });
    let lines = occurrence_checks(&spec, &real(-2.3267512)).unwrap();
    let block = resu_block(
        "RESU",
        &[
            ("NUME_ORDRE", "21"),
            ("NOM_CHAM", "DEPL"),
            ("NOM_CMP", "DY"),
            ("GROUP_NO", "A2"),
        ],
        &lines,
    );
    insta::assert_snapshot!("resu_block", block.replace(' ', "·"));
}

#[test]
fn table_block_snapshot() {
    let mut spec = TestSpec::new(vec![real(8.1053e-3)]);
    spec.reference = Some(Reference::new(RefKind::Analytique, vec![real(8.1e-3)]));
    spec.reference.as_mut().unwrap().precision = 0.01;
    let lines = occurrence_checks(&spec, &real(8.10531e-3)).unwrap();
    let block = table_block("TAB_DEPL", "DY", None, &lines);
    insta::assert_snapshot!("table_block", block.replace(' ', "·"));
}

#[test]
fn counts_and_summary() {
    let mut counts = TestCounts::default();
    let ok = occurrence_checks(&TestSpec::new(vec![real(1.0)]), &real(1.0)).unwrap();
    let nook = occurrence_checks(&TestSpec::new(vec![real(1.0)]), &real(2.0)).unwrap();
    let skip = occurrence_checks(&TestSpec::new(vec![real(0.0)]), &real(2.0)).unwrap();
    tally(&mut counts, &ok);
    tally(&mut counts, &nook);
    tally(&mut counts, &skip);
    assert_eq!(
        counts,
        TestCounts {
            ok: 1,
            nook: 1,
            skip: 1
        }
    );
    let s = summary(&counts);
    assert!(s.contains("      NOOK          1\n"), "{s}");
    assert!(s.contains("DIAGNOSTIC : NOOK_TEST_RESU"), "{s}");
    let s = summary(&TestCounts {
        ok: 3,
        nook: 0,
        skip: 2,
    });
    assert!(s.contains("DIAGNOSTIC : OK"), "{s}");
}

#[test]
fn names_are_printed_like_code_aster() {
    assert_eq!(RefKind::SourceExterne.to_string(), "SOURCE_EXTERNE");
    assert_eq!(RefKind::parse("AUTRE_ASTER"), Some(RefKind::AutreAster));
    assert_eq!(RefKind::parse("autre"), None);
    assert_eq!(Status::Ok.as_str(), " OK ");
    assert_eq!(Critere::parse("ABSOLU"), Some(Critere::Absolu));
}
