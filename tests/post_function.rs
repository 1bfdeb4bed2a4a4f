//! Tabulated functions: evaluation rules and the IMPR_FONCTION writers.

use aster::post::function::*;
use aster::post::table::PrintOptions;

/// DY(INST) of a node as RECU_FONCTION builds it (extension 'EE').
fn dy() -> Function {
    Function::new("INST", "DY", vec![-1e-5, 0.0, 8e-5], vec![0.0, -0.5, -2.5]).unwrap()
}

#[test]
fn linear_interpolation_between_points() {
    let f = dy();
    assert_eq!(f.eval(-1e-5).unwrap(), 0.0);
    assert_eq!(f.eval(0.0).unwrap(), -0.5);
    // halfway in [0, 8e-5]: -0.5 + 0.5 * (-2.0) = -1.5
    assert!((f.eval(4e-5).unwrap() + 1.5).abs() < 1e-12);
    // a quarter in [-1e-5, 0]: -0.125
    assert!((f.eval(-7.5e-6).unwrap() + 0.125).abs() < 1e-12);
    assert_eq!(f.prol(), "EE");
}

#[test]
fn excluded_extension_is_an_error() {
    let f = dy();
    let e = f.eval(9e-5).unwrap_err();
    assert!(
        e.contains("outside the domain") && e.contains("PROL_DROITE"),
        "{e}"
    );
    let e = f.eval(-2e-5).unwrap_err();
    assert!(e.contains("PROL_GAUCHE"), "{e}");
    // a rounding error on the last instant is still on the point
    assert_eq!(f.eval(8e-5 * (1.0 + 1e-15)).unwrap(), -2.5);
    assert!(f.eval(f64::NAN).is_err());
}

#[test]
fn constant_and_linear_extensions() {
    let mut f = dy();
    f.left = Extrapolation::Constant;
    f.right = Extrapolation::Linear;
    assert_eq!(f.eval(-1.0).unwrap(), 0.0);
    // slope of the last segment: -2 / 8e-5 = -25000
    assert!((f.eval(1.2e-4).unwrap() - (-2.5 - 25000.0 * 4e-5)).abs() < 1e-12);
    assert_eq!(
        Extrapolation::parse("LINEAIRE"),
        Some(Extrapolation::Linear)
    );
}

#[test]
fn log_interpolation() {
    let mut f = Function::new("X", "Y", vec![1.0, 100.0], vec![1.0, 10000.0]).unwrap();
    f.interpolation = (Interp::Log, Interp::Log);
    // y = x^2 is a straight line in log-log axes
    assert!((f.eval(10.0).unwrap() - 100.0).abs() < 1e-9);
}

#[test]
fn constant_function_ignores_its_parameter() {
    let f = Function::constant(227000.0, "TOUTRESU");
    assert!(f.is_constant());
    for x in [-1e9, -1e-5, 0.0, 3.0, 1e30] {
        assert_eq!(f.eval(x).unwrap(), 227000.0);
    }
}

#[test]
fn bad_functions_are_refused() {
    assert!(Function::new("INST", "DY", vec![0.0, 1.0], vec![0.0]).is_err());
    assert!(Function::new("INST", "DY", vec![], vec![]).is_err());
    let e = Function::new("INST", "DY", vec![0.0, 1.0, 1.0], vec![0.0, 1.0, 2.0]).unwrap_err();
    assert!(e.contains("strictly increasing"), "{e}");
    assert!(Function::new("INST", "DY", vec![0.0, f64::NAN], vec![0.0, 1.0]).is_err());
}

#[test]
fn xmgrace_project() {
    let f = dy();
    let opts = GraphOptions {
        titre: "Taylor bar".into(),
        legende_x: "INST".into(),
        legende_y: "DY".into(),
        ..Default::default()
    };
    let text = write_xmgrace(&[FunctionCurve::new(&f, "FDY")], &opts);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines.contains(&"@version 50100"));
    assert!(lines.contains(&"@    title \"Taylor bar\""));
    assert!(lines.contains(&"@    xaxis  label \"INST\""));
    assert!(lines.contains(&"@    s1 legend \"FDY\""));
    // the box is the data range widened by 2.5 % on each side
    assert!(lines.contains(&"@    world xmin -1.2250000000000001e-05"));
    assert!(lines.contains(&"@    world xmax 8.225000000000001e-05"));
    assert!(lines.contains(&"@    world ymin -2.5625"));
    assert!(lines.contains(&"@    world ymax 0.0625"));
    assert!(lines.contains(&"@    xaxis  tick major 1.8900000000000002e-05"));
    assert!(lines.contains(&"@    yaxis  tick major 0.525"));
    let data = lines.iter().position(|l| *l == "@target g0.s1").unwrap();
    assert_eq!(
        &lines[data..data + 6],
        &[
            "@target g0.s1",
            "@type xy",
            "-1e-05 0",
            "0 -0.5",
            "8e-05 -2.5",
            "&"
        ]
    );
    insta::assert_snapshot!("xmgrace", text);
}

#[test]
fn tableau_interpolates_on_the_first_curve() {
    let f = dy();
    let g = Function::new("INST", "DY", vec![-1e-5, 1e-4], vec![1.0, 0.0]).unwrap();
    let short = Function::new("INST", "DX", vec![0.0, 1e-5], vec![1.0, 0.0]).unwrap();
    let curves = [
        FunctionCurve::new(&f, "F1"),
        FunctionCurve::new(&short, "F2"),
        FunctionCurve::new(&g, "F3"),
    ];
    let (text, warnings) = write_tableau(
        &curves,
        &GraphOptions::default(),
        None,
        &PrintOptions::default(),
    )
    .unwrap();
    // the curve defined on [0, 1e-5] cannot be evaluated at -1e-5: dropped
    assert_eq!(warnings.len(), 1);
    assert!(warnings[0].contains("F2"));
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        &lines[3..9],
        &["## ", "## ", "## Courbe 0", "## F1", "## Courbe 1", "## F3"]
    );
    assert_eq!(lines[9], "INST         DY_0         DY_1        ");
    // g(0) = 1 - 1e-5/1.1e-4
    assert_eq!(lines[11], " 0.00000E+00 -5.00000E-01  9.09091E-01");
    assert_eq!(lines[12], " 8.00000E-05 -2.50000E+00  1.81818E-01");
}
