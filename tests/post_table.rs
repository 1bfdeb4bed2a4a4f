//! Tables: typed columns, FILTRE semantics and the IMPR_TABLE layouts.
//!
//! Expected printouts were produced by code_aster's `ReprTable`/`FMT`
//! logic (table_py.py, Python 3) on the same table, with the 3-line header
//! of docs/semantics.md §9.5.

use aster::post::table::*;
use aster::post::test_report::Critere;

fn k(s: &str) -> Option<Cell> {
    Some(Cell::Text(s.to_string()))
}
fn r(x: f64) -> Option<Cell> {
    Some(Cell::Real(x))
}
fn i(v: i64) -> Option<Cell> {
    Some(Cell::Int(v))
}

/// A POST_RELEVE_T-like table (EXTRACTION on one node), with an empty
/// MAILLE column and a sparse column with a long name.
fn releve() -> Table {
    let mut t = Table::new();
    t.title = vec![
        "ASTER 15.02.00 CONCEPT TAB CALCULE LE 11/09/2020 A 12:00:00 DE TYPE".to_string(),
        "TABLE_SDASTER".to_string(),
    ];
    for (name, ty) in [
        ("INTITULE", ColumnType::Text(16)),
        ("RESU", ColumnType::Text(8)),
        ("NOM_CHAM", ColumnType::Text(16)),
        ("NUME_ORDRE", ColumnType::Int),
        ("INST", ColumnType::Real),
        ("NOEUD", ColumnType::Text(8)),
        ("MAILLE", ColumnType::Text(8)),
        ("COOR_X", ColumnType::Real),
        ("DY", ColumnType::Real),
        ("LONG_PARAMETER_NAME", ColumnType::Real),
    ] {
        t.add_column(name, ty).unwrap();
    }
    let rows = [
        (0, -1e-5, 0.0, 0.0, None),
        (5, 2.5e-7, 0.0, -2.32675, r(123456.789)),
        (10, 8e-5, 3.2, -5.5e-3, None),
    ];
    for (n, inst, x, dy, extra) in rows {
        t.push_row(vec![
            k("DEPL_A2"),
            k("RESU"),
            k("DEPL"),
            i(n),
            r(inst),
            k("N12"),
            None,
            r(x),
            r(dy),
            extra,
        ])
        .unwrap();
    }
    t
}

#[test]
fn fmt_12_5e_matches_printf() {
    let f = RealFormat::default();
    assert_eq!(f.format(-2.32675), "-2.32675E+00");
    assert_eq!(f.format(1e-5), " 1.00000E-05");
    assert_eq!(f.format(1.5e-5), " 1.50000E-05");
    assert_eq!(f.format(0.0), " 0.00000E+00");
    assert_eq!(f.format(227000.0), " 2.27000E+05");
    assert_eq!(f.format(1.5e100), "1.50000E+100");
    assert_eq!(f.format(5e-324), "4.94066E-324");
    assert_eq!(
        RealFormat::from_fortran("E12.5"),
        Some(RealFormat::default())
    );
    let p = RealFormat::from_fortran("1PE13.6").unwrap();
    assert_eq!(p.format(-2.32675), " -2.326750E+00");
    assert_eq!(
        RealFormat::from_fortran("F10.3").unwrap().format(-1e-5),
        "    -0.000"
    );
    assert_eq!(RealFormat::from_fortran("D12.5").unwrap().kind, 'E');
    assert_eq!(RealFormat::from_fortran("XYZ"), None);
}

#[test]
fn c_general_matches_printf_g() {
    let cases: &[(f64, &str)] = &[
        (227000.0, "227000"),
        (1e-5, "1e-05"),
        (0.0001234, "0.0001234"),
        (123456789.0, "1.2345679e+08"),
        (12345678.0, "12345678"),
        (1e100, "1e+100"),
        (0.0, "0"),
        (-0.0, "-0"),
        (-2.32675, "-2.32675"),
        (1.0 / 3.0, "0.33333333"),
    ];
    for (x, s) in cases {
        assert_eq!(c_general(*x, 8, false), *s, "%.8g of {x:e}");
    }
}

#[test]
fn tableau_layout() {
    let (text, warnings) = releve().impr_table(&PrintOptions::default()).unwrap();
    assert!(warnings.is_empty());
    let expected = "#\n#--------------------------------------------------------------------------------\n#\n#ASTER 15.02.00 CONCEPT TAB CALCULE LE 11/09/2020 A 12:00:00 DE TYPE\n#TABLE_SDASTER\nINTITULE         RESU     NOM_CHAM         NUME_ORDRE   INST         NOEUD    COOR_X       DY           LONG_PARAMETER_NAME\nDEPL_A2          RESU     DEPL                        0 -1.00000E-05 N12       0.00000E+00  0.00000E+00        -           \nDEPL_A2          RESU     DEPL                        5  2.50000E-07 N12       0.00000E+00 -2.32675E+00         1.23457E+05\nDEPL_A2          RESU     DEPL                       10  8.00000E-05 N12       3.20000E+00 -5.50000E-03        -           \n\n";
    assert_eq!(text, expected);
    insta::assert_snapshot!("impr_table_tableau", text.replace(' ', "·"));
}

#[test]
fn agraf_layout_marks_missing_cells() {
    let opts = PrintOptions {
        format: PrintFormat::Agraf,
        ..Default::default()
    };
    let (text, _) = releve().impr_table(&opts).unwrap();
    let row1 = text.lines().nth(6).unwrap();
    assert_eq!(
        row1,
        "DEPL_A2          RESU     DEPL                        0 -1.00000E-05 N12       0.00000E+00  0.00000E+00 \\       -           "
    );
}

#[test]
fn nom_para_order_and_format_r() {
    let opts = PrintOptions {
        nom_para: Some(vec![
            "NUME_ORDRE".into(),
            "DY".into(),
            "LONG_PARAMETER_NAME".into(),
            "NOPE".into(),
        ]),
        format_r: Some("1PE13.6".into()),
        ..Default::default()
    };
    let mut t = releve();
    t.title.clear();
    let (text, warnings) = t.impr_table(&opts).unwrap();
    assert_eq!(
        text,
        "#\n#--------------------------------------------------------------------------------\n#\n  NUME_ORDRE    DY             LONG_PARAMETER_NAME\n             0   0.000000E+00       -            \n             5  -2.326750E+00        1.234568E+05\n            10  -5.500000E-03       -            \n\n"
    );
    assert_eq!(warnings.len(), 1);
    assert!(warnings[0].contains("NOPE"));
    let opts = PrintOptions {
        nom_para: Some(vec!["INST".into(), "DY".into()]),
        format_r: Some("F10.3".into()),
        ..Default::default()
    };
    let (text, _) = t.impr_table(&opts).unwrap();
    assert!(text.ends_with("  INST         DY        \n      -0.000        0.000\n       0.000       -2.327\n       0.000       -0.005\n\n"), "{text}");
}

#[test]
fn empty_columns_and_rows_are_dropped() {
    let t = releve();
    let kept = t.without_empty_columns();
    assert!(kept.column_index("MAILLE").is_none());
    assert!(kept.column_index("LONG_PARAMETER_NAME").is_some());
    // A row that is empty after NOM_PARA is not printed.
    let opts = PrintOptions {
        nom_para: Some(vec!["LONG_PARAMETER_NAME".into()]),
        ..Default::default()
    };
    let (text, _) = t.impr_table(&opts).unwrap();
    let body: Vec<&str> = text.lines().skip(5).collect();
    assert_eq!(body, vec!["LONG_PARAMETER_NAME", "        1.23457E+05", ""]);
}

#[test]
fn filter_eq_on_reals_uses_precision() {
    let t = releve();
    // 2.5e-7 * (1 + 5e-4) is within the default relative 1e-3.
    let f = Filter::new(
        "INST",
        CritComp::Eq,
        FilterValues::Real(vec![2.5e-7 * 1.0005]),
    );
    let out = t.filter(&f).unwrap();
    assert_eq!(out.n_rows(), 1);
    assert_eq!(out.cell(0, "NUME_ORDRE"), Some(&Cell::Int(5)));
    // ... but not within 1e-4.
    let mut f2 = f.clone();
    f2.precision = 1e-4;
    assert_eq!(t.filter(&f2).unwrap().n_rows(), 0);
    // ABSOLU: |8e-5 - 7.9e-5| = 1e-6 <= 2e-6
    let mut f3 = Filter::new("INST", CritComp::Eq, FilterValues::Real(vec![7.9e-5]));
    f3.critere = Critere::Absolu;
    f3.precision = 2e-6;
    assert_eq!(
        t.filter(&f3).unwrap().cell(0, "NUME_ORDRE"),
        Some(&Cell::Int(10))
    );
}

#[test]
fn filter_comparisons() {
    let t = releve();
    let n = |f: Filter| t.filter(&f).unwrap().n_rows();
    assert_eq!(
        n(Filter::new(
            "NUME_ORDRE",
            CritComp::Eq,
            FilterValues::Int(vec![0, 10])
        )),
        2
    );
    assert_eq!(
        n(Filter::new(
            "NUME_ORDRE",
            CritComp::Ne,
            FilterValues::Int(vec![5])
        )),
        2
    );
    assert_eq!(
        n(Filter::new(
            "NUME_ORDRE",
            CritComp::Lt,
            FilterValues::Int(vec![5])
        )),
        1
    );
    assert_eq!(
        n(Filter::new(
            "NUME_ORDRE",
            CritComp::Le,
            FilterValues::Int(vec![5])
        )),
        2
    );
    assert_eq!(
        n(Filter::new(
            "INST",
            CritComp::Gt,
            FilterValues::Real(vec![0.0])
        )),
        2
    );
    assert_eq!(
        n(Filter::new(
            "INST",
            CritComp::Ge,
            FilterValues::Real(vec![2.5e-7])
        )),
        2
    );
    assert_eq!(
        n(Filter::new(
            "NOEUD",
            CritComp::Eq,
            FilterValues::Text(vec!["N12  ".into()])
        )),
        3
    );
    assert_eq!(
        n(Filter::new(
            "LONG_PARAMETER_NAME",
            CritComp::Vide,
            FilterValues::None
        )),
        2
    );
    assert_eq!(
        n(Filter::new(
            "LONG_PARAMETER_NAME",
            CritComp::NonVide,
            FilterValues::None
        )),
        1
    );
}

#[test]
fn maxi_mini_keep_the_first_extreme_row() {
    let mut t = Table::new();
    t.add_column("NUME_ORDRE", ColumnType::Int).unwrap();
    t.add_column("V", ColumnType::Real).unwrap();
    for (n, v) in [(1, 2.0), (2, -5.0), (3, 5.0), (4, -5.0), (5, 1.0)] {
        t.push_row(vec![i(n), r(v)]).unwrap();
    }
    let first = |c: CritComp| {
        let out = t.filter(&Filter::new("V", c, FilterValues::None)).unwrap();
        assert_eq!(out.n_rows(), 1, "{c:?}");
        out.cell(0, "NUME_ORDRE").cloned()
    };
    assert_eq!(first(CritComp::Maxi), Some(Cell::Int(3)));
    assert_eq!(first(CritComp::Mini), Some(Cell::Int(2)));
    assert_eq!(first(CritComp::MaxiAbs), Some(Cell::Int(2)));
    assert_eq!(first(CritComp::MiniAbs), Some(Cell::Int(5)));
}

#[test]
fn filters_are_anded_and_single_value_needs_one_row() {
    let t = releve();
    let fs = [
        Filter::new(
            "NOEUD",
            CritComp::Eq,
            FilterValues::Text(vec!["N12".into()]),
        ),
        Filter::new("NUME_ORDRE", CritComp::Eq, FilterValues::Int(vec![5])),
    ];
    let one = t.filter_all(&fs).unwrap();
    assert_eq!(one.single_value("DY").unwrap(), &Cell::Real(-2.32675));
    let e = t.single_value("DY").unwrap_err();
    assert!(e.message.contains("3 rows"), "{e}");
    let none = t
        .filter(&Filter::new(
            "NUME_ORDRE",
            CritComp::Eq,
            FilterValues::Int(vec![7]),
        ))
        .unwrap();
    assert!(none
        .single_value("DY")
        .unwrap_err()
        .message
        .contains("no row"));
}

#[test]
fn type_mismatch_in_filter_is_an_error() {
    let t = releve();
    let e = t
        .filter(&Filter::new(
            "NUME_ORDRE",
            CritComp::Eq,
            FilterValues::Real(vec![5.0]),
        ))
        .unwrap_err();
    assert_eq!(e.keyword.as_deref(), Some("FILTRE/VALE"));
    assert!(
        e.message.contains("use") || e.message.contains("VALE_I"),
        "{e}"
    );
    assert!(e.message.contains("VALE_I"), "{e}");
    let e = t
        .filter(&Filter::new(
            "INST",
            CritComp::Eq,
            FilterValues::Int(vec![0]),
        ))
        .unwrap_err();
    assert!(e.message.contains("with VALE,"), "{e}");
    let e = t
        .filter(&Filter::new(
            "INSTT",
            CritComp::Eq,
            FilterValues::Real(vec![0.0]),
        ))
        .unwrap_err();
    assert!(e.message.contains("did you mean 'INST'"), "{e}");
    assert_eq!(e.keyword.as_deref(), Some("FILTRE/NOM_PARA"));
}

#[test]
fn typed_rows() {
    let mut t = Table::new();
    t.add_column("N", ColumnType::Int).unwrap();
    t.add_column("X", ColumnType::Real).unwrap();
    t.add_column("NOEUD", ColumnType::Text(8)).unwrap();
    // an integer in a real column becomes a real
    t.push_row(vec![i(1), i(2), k("N1")]).unwrap();
    assert_eq!(t.cell(0, "X"), Some(&Cell::Real(2.0)));
    assert!(t.push_row(vec![r(1.0), None, None]).is_err());
    assert!(t
        .push_row(vec![None, None, k("TOO_LONG_NAME")])
        .unwrap_err()
        .message
        .contains("K8"));
    assert!(t.push_row(vec![None]).is_err());
    assert!(t.add_column("N", ColumnType::Int).is_err());
    // add_row creates columns with the type of their value
    t.add_row(&[("N", Cell::Int(2)), ("DY", Cell::Real(0.5))])
        .unwrap();
    assert_eq!(t.column_type(3), ColumnType::Real);
    assert_eq!(t.column("DY").unwrap(), vec![None, Some(&Cell::Real(0.5))]);
    assert_eq!(ColumnType::parse("K16"), Some(ColumnType::Text(16)));
    assert_eq!(ColumnType::Text(24).aster_name(), "K24");
}

#[test]
fn filter_trace_and_sort() {
    let mut t = releve();
    t.sort_by(&["DY"], false).unwrap();
    assert_eq!(t.cell(0, "NUME_ORDRE"), Some(&Cell::Int(5)));
    let opts = PrintOptions {
        filters: vec![Filter::new(
            "NUME_ORDRE",
            CritComp::Ge,
            FilterValues::Int(vec![5]),
        )],
        tri: Some((vec!["NUME_ORDRE".into()], true)),
        nom_para: Some(vec!["NUME_ORDRE".into()]),
        ..Default::default()
    };
    let (text, _) = releve().impr_table(&opts).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[5],
        "#FILTRE -> NOM_PARA: NUME_ORDRE       CRIT_COMP: GE   VALE: 5"
    );
    assert_eq!(
        &lines[6..9],
        &["NUME_ORDRE  ", "          10", "           5"]
    );
}

#[test]
fn default_title_lines() {
    // 81 characters in all: cut at the last blank before column 80.
    let t = default_title("15.02.00", "TAB", "11/09/2020", "12:00:00", "table_sdaster");
    assert_eq!(
        t,
        [
            "ASTER 15.02.00 CONCEPT TAB CALCULE LE 11/09/2020 A 12:00:00 DE TYPE",
            "TABLE_SDASTER"
        ]
    );
}
