//! Tabulated functions (fonction_sdaster) and the IMPR_FONCTION writers.
//!
//! RECU_FONCTION builds a function of INST from a result, DEFI_CONSTANTE a
//! constant one; DYNA_NON_LINE evaluates them (FONC_MULT...) and
//! IMPR_FONCTION prints them as a Grace project (XMGRACE) or a table
//! (TABLEAU). The evaluation rules are those of code_aster's `folocx`/
//! `fointe`; the Grace text follows `table_graph.py` (TraceXmgrace).

use super::table::{c_general, Cell, ColumnType, PrintOptions, Table};
use super::test_report::py_repr;

/// Interpolation on one axis (INTERPOL).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interp {
    #[default]
    Lin,
    Log,
}

/// Extension beyond the first or last abscissa (PROL_GAUCHE/PROL_DROITE).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Extrapolation {
    /// 'E' (EXCLU): evaluating outside the domain is an error.
    #[default]
    Excluded,
    /// 'C' (CONSTANT): the end value.
    Constant,
    /// 'L' (LINEAIRE): the end segment extended.
    Linear,
}

impl Extrapolation {
    /// The letter code_aster stores in `.PROL`.
    pub fn letter(self) -> char {
        match self {
            Extrapolation::Excluded => 'E',
            Extrapolation::Constant => 'C',
            Extrapolation::Linear => 'L',
        }
    }

    /// Reads a letter or a keyword value (EXCLU, CONSTANT, LINEAIRE).
    pub fn parse(text: &str) -> Option<Extrapolation> {
        match text {
            "E" | "EXCLU" => Some(Extrapolation::Excluded),
            "C" | "CONSTANT" => Some(Extrapolation::Constant),
            "L" | "LINEAIRE" => Some(Extrapolation::Linear),
            _ => None,
        }
    }
}

/// A function given by points, y(x) between them by LIN LIN (or LOG)
/// interpolation.
#[derive(Debug, Clone, PartialEq)]
pub struct Function {
    /// NOM_PARA: `INST`, `X`..., or `TOUTPARA` for a constant.
    pub para: String,
    /// NOM_RESU: the component name for RECU_FONCTION, `TOUTRESU` default.
    pub resu: String,
    pub abscissas: Vec<f64>,
    pub ordinates: Vec<f64>,
    /// Interpolation on the abscissa and on the ordinate.
    pub interpolation: (Interp, Interp),
    pub left: Extrapolation,
    pub right: Extrapolation,
}

/// Relative precision for "x is on the first/last abscissa" with an
/// excluded extension: a fraction of the end segment. code_aster's fointe
/// uses sqrt(r8prem()) here [mem].
pub const LOCATE_EPS: f64 = 1.4901161193847656e-8;

impl Function {
    /// A tabulated function, LIN LIN, excluded on both sides (as RECU_FONCTION
    /// builds them). Abscissas must be strictly increasing and all values
    /// finite.
    pub fn new(
        para: &str,
        resu: &str,
        abscissas: Vec<f64>,
        ordinates: Vec<f64>,
    ) -> Result<Function, String> {
        if abscissas.len() != ordinates.len() {
            return Err(format!(
                "a function needs as many abscissas as ordinates: {} and {}",
                abscissas.len(),
                ordinates.len()
            ));
        }
        if abscissas.is_empty() {
            return Err("a function needs at least one point".to_string());
        }
        if let Some(i) = abscissas
            .iter()
            .chain(&ordinates)
            .position(|v| !v.is_finite())
        {
            let what = if i < abscissas.len() {
                "abscissa"
            } else {
                "ordinate"
            };
            return Err(format!("a function {what} is not finite (NaN or infinite)"));
        }
        if let Some(w) = abscissas.windows(2).position(|w| w[1] <= w[0]) {
            return Err(format!(
                "the abscissas of a function must be strictly increasing: {} is followed by {}",
                py_repr(abscissas[w]),
                py_repr(abscissas[w + 1])
            ));
        }
        Ok(Function {
            para: para.to_string(),
            resu: resu.to_string(),
            abscissas,
            ordinates,
            interpolation: (Interp::Lin, Interp::Lin),
            left: Extrapolation::Excluded,
            right: Extrapolation::Excluded,
        })
    }

    /// DEFI_CONSTANTE: parameter TOUTPARA, constant extension on both sides,
    /// so it returns `value` for any parameter value.
    pub fn constant(value: f64, nom_resu: &str) -> Function {
        Function {
            para: "TOUTPARA".to_string(),
            resu: nom_resu.to_string(),
            abscissas: vec![1.0],
            ordinates: vec![value],
            interpolation: (Interp::Lin, Interp::Lin),
            left: Extrapolation::Constant,
            right: Extrapolation::Constant,
        }
    }

    pub fn is_constant(&self) -> bool {
        self.para == "TOUTPARA"
    }

    /// `.PROL`-like description: "LIN LIN", "EE"...
    pub fn prol(&self) -> String {
        format!("{}{}", self.left.letter(), self.right.letter())
    }

    /// y(x). Errors outside the domain when that side is excluded (with a
    /// tolerance of [`LOCATE_EPS`] times the end segment), and for LOG
    /// interpolation on non-positive values.
    pub fn eval(&self, x: f64) -> Result<f64, String> {
        if !x.is_finite() {
            return Err(format!(
                "cannot evaluate {} at {}={}",
                self.resu,
                self.para,
                py_repr(x)
            ));
        }
        let xs = &self.abscissas;
        let ys = &self.ordinates;
        let n = xs.len();
        if n == 0 {
            return Err(format!("the function {} has no point", self.resu));
        }
        if self.is_constant() {
            return Ok(ys[0]);
        }
        let out_of = |side: &str| {
            format!(
                "{}({}={}) is outside the domain [{}, {}] of the function and the extension is \
                 excluded on the {side} (PROL_{}='EXCLU')",
                self.resu,
                self.para,
                py_repr(x),
                py_repr(xs[0]),
                py_repr(xs[n - 1]),
                if side == "left" { "GAUCHE" } else { "DROITE" }
            )
        };
        if n == 1 {
            let x0 = xs[0];
            let on_point = (x == 0.0 && x0.abs() <= LOCATE_EPS)
                || (x != 0.0 && ((x0 - x) / x).abs() <= LOCATE_EPS)
                || (x < x0 && self.left != Extrapolation::Excluded)
                || (x > x0 && self.right != Extrapolation::Excluded);
            return if on_point || x == x0 {
                Ok(ys[0])
            } else {
                Err(out_of(if x < x0 { "left" } else { "right" }))
            };
        }
        if x <= xs[0] {
            return match self.left {
                Extrapolation::Excluded => {
                    if (xs[0] - x).abs() <= LOCATE_EPS * (xs[0] - xs[1]).abs() {
                        Ok(ys[0])
                    } else {
                        Err(out_of("left"))
                    }
                }
                Extrapolation::Constant => Ok(ys[0]),
                Extrapolation::Linear => self.interpolate(0, x),
            };
        }
        if x >= xs[n - 1] {
            return match self.right {
                Extrapolation::Excluded => {
                    if (xs[n - 1] - x).abs() <= LOCATE_EPS * (xs[n - 1] - xs[n - 2]).abs() {
                        Ok(ys[n - 1])
                    } else {
                        Err(out_of("right"))
                    }
                }
                Extrapolation::Constant => Ok(ys[n - 1]),
                Extrapolation::Linear => self.interpolate(n - 2, x),
            };
        }
        // xs[i] <= x < xs[i+1]
        let i = xs.partition_point(|&a| a <= x) - 1;
        if xs[i] == x {
            return Ok(ys[i]);
        }
        self.interpolate(i, x)
    }

    /// Interpolation (or extension) on the segment [i, i+1].
    fn interpolate(&self, i: usize, x: f64) -> Result<f64, String> {
        let (x0, x1) = (self.abscissas[i], self.abscissas[i + 1]);
        let (y0, y1) = (self.ordinates[i], self.ordinates[i + 1]);
        let log_err = |what: &str| {
            format!(
                "LOG interpolation of {} needs positive {what} values near {}={}",
                self.resu,
                self.para,
                py_repr(x)
            )
        };
        let t = match self.interpolation.0 {
            Interp::Lin => (x - x0) / (x1 - x0),
            Interp::Log => {
                if x0 <= 0.0 || x1 <= 0.0 || x <= 0.0 {
                    return Err(log_err("abscissa"));
                }
                (x / x0).ln() / (x1 / x0).ln()
            }
        };
        match self.interpolation.1 {
            Interp::Lin => Ok(y0 + t * (y1 - y0)),
            Interp::Log => {
                if y0 <= 0.0 || y1 <= 0.0 {
                    return Err(log_err("ordinate"));
                }
                Ok((y0.ln() + t * (y1.ln() - y0.ln())).exp())
            }
        }
    }
}

/// Axis scale (ECHELLE_X / ECHELLE_Y).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scale {
    #[default]
    Lin,
    Log,
}

/// Graph options of IMPR_FONCTION / IMPR_TABLE (XMGRACE).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GraphOptions {
    pub titre: String,
    pub sous_titre: String,
    pub legende_x: String,
    pub legende_y: String,
    pub borne_x: Option<(f64, f64)>,
    pub borne_y: Option<(f64, f64)>,
    pub echelle_x: Scale,
    pub echelle_y: Scale,
    pub grille_x: Option<f64>,
    pub grille_y: Option<f64>,
}

/// One curve to draw: points, labels of the two columns, legend and the
/// optional STYLE / COULEUR / MARQUEUR / FREQ_MARQUEUR.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct XyCurve {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub legend: String,
    pub style: Option<i64>,
    pub color: Option<i64>,
    pub marker: Option<i64>,
    pub marker_freq: Option<i64>,
}

/// One COURBE occurrence of IMPR_FONCTION.
#[derive(Debug, Clone, PartialEq)]
pub struct FunctionCurve<'a> {
    pub function: &'a Function,
    /// LEGENDE, by default the function's concept name.
    pub legend: String,
    pub style: Option<i64>,
    pub color: Option<i64>,
    pub marker: Option<i64>,
    pub marker_freq: Option<i64>,
}

impl<'a> FunctionCurve<'a> {
    pub fn new(function: &'a Function, legend: &str) -> FunctionCurve<'a> {
        FunctionCurve {
            function,
            legend: legend.to_string(),
            style: None,
            color: None,
            marker: None,
            marker_freq: None,
        }
    }

    fn xy(&self) -> XyCurve {
        XyCurve {
            x: self.function.abscissas.clone(),
            y: self.function.ordinates.clone(),
            legend: self.legend.clone(),
            style: self.style,
            color: self.color,
            marker: self.marker,
            marker_freq: self.marker_freq,
        }
    }
}

/// code_aster's ValCycl: `val` within [vmin, vmax] cyclically, `vdef` when
/// absent or below vmin; no upper bound when vmax < vmin.
fn val_cycl(val: Option<i64>, vmin: i64, vmax: i64, vdef: i64) -> i64 {
    let v = match val {
        Some(v) if v >= vmin => v,
        _ => vdef,
    };
    if vmax < vmin {
        v
    } else {
        (v - vmin).rem_euclid(vmax + 1 - vmin) + vmin
    }
}

/// Python's `str()` of a value that may be an int (the grid step).
fn py_num(x: f64, is_int: bool) -> String {
    if is_int {
        format!("{}", x as i64)
    } else {
        py_repr(x)
    }
}

/// The plotting box: the data bounds widened by 5 % of their range (as
/// Graph.SetExtrema(0.05)), unless BORNE_X/Y are given.
fn extrema(values: impl Iterator<Item = f64>, fixed: Option<(f64, f64)>) -> (f64, f64) {
    if let Some(b) = fixed {
        if b.0 <= b.1 {
            return b;
        }
    }
    let (mut lo, mut hi) = (1.0e99_f64, -1.0e99_f64);
    for v in values {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    let mut d = (hi - lo).max(0.01 * hi);
    if d == 0.0 {
        d = 1.0e-6;
    }
    (lo - 0.05 * d / 2.0, hi + 0.05 * d / 2.0)
}

/// A Grace (xmgrace) project with one set per curve, sets numbered from 1
/// as code_aster does for a new file. Data lines are "x y" with `%.8g`.
pub fn grace_project(curves: &[XyCurve], opts: &GraphOptions) -> String {
    let (xmin, xmax) = extrema(
        curves.iter().flat_map(|c| c.x.iter().copied()),
        opts.borne_x,
    );
    let (ymin, ymax) = extrema(
        curves.iter().flat_map(|c| c.y.iter().copied()),
        opts.borne_y,
    );
    let grid = |given: Option<f64>, lo: f64, hi: f64, scale: Scale| -> String {
        if scale == Scale::Log {
            return "10".to_string();
        }
        if let Some(g) = given {
            return py_repr(g);
        }
        let delta = hi - lo;
        let g = delta / 5.0;
        if delta > 4.0 {
            let r = g.round();
            if r == 0.0 {
                return py_repr(1.0e-6);
            }
            return py_num(r, true);
        }
        py_repr(if g == 0.0 { 1.0e-6 } else { g })
    };
    let scale = |s: Scale| {
        if s == Scale::Log {
            "Logarithmic"
        } else {
            "Normal"
        }
    };
    let q = |s: &str| s.replace('"', "'");
    let mut out: Vec<String> = vec![
        String::new(),
        "# Grace project file".into(),
        "#".into(),
        "@version 50100".into(),
        "@page size 842, 595".into(),
        "@default sformat \"%.8g\"".into(),
        "@g0 on".into(),
        "@g0 hidden false".into(),
        "@g0 type XY".into(),
        "@with g0".into(),
        "@    view xmin 0.150000".into(),
        "@    view xmax 1.150000".into(),
        "@    view ymin 0.150000".into(),
        "@    view ymax 0.850000".into(),
        "@    legend on".into(),
        "@    legend loctype view".into(),
        "@    legend 0.85, 0.8".into(),
        format!("@    title \"{}\"", q(&opts.titre)),
        format!("@    subtitle \"{}\"", q(&opts.sous_titre)),
        format!("@    xaxis  label \"{}\"", q(&opts.legende_x)),
        format!("@    yaxis  label \"{}\"", q(&opts.legende_y)),
        format!("@    xaxes scale {}", scale(opts.echelle_x)),
        format!("@    yaxes scale {}", scale(opts.echelle_y)),
        format!(
            "@    xaxis  tick major {}",
            grid(opts.grille_x, xmin, xmax, opts.echelle_x)
        ),
        format!(
            "@    yaxis  tick major {}",
            grid(opts.grille_y, ymin, ymax, opts.echelle_y)
        ),
        format!("@    world xmin {}", py_repr(xmin)),
        format!("@    world xmax {}", py_repr(xmax)),
        format!("@    world ymin {}", py_repr(ymin)),
        format!("@    world ymax {}", py_repr(ymax)),
        String::new(),
    ];
    for (k, c) in curves.iter().enumerate() {
        let n = k as i64 + 1;
        let s = format!("@    s{n}");
        let color = val_cycl(c.color, 1, 15, n + 1);
        out.push(format!("{s} hidden false"));
        out.push(format!("{s} type xy"));
        out.push(format!("{s} symbol {}", val_cycl(c.marker, 0, 10, n)));
        out.push(format!("{s} symbol color {color}"));
        out.push(format!(
            "{s} symbol skip {}",
            val_cycl(c.marker_freq, 0, -1, 0)
        ));
        out.push(format!("{s} symbol fill color {color}"));
        out.push(format!("{s} line type 1"));
        out.push(format!("{s} line linestyle {}", val_cycl(c.style, 0, 8, 1)));
        out.push(format!("{s} line color {color}"));
        out.push(format!(
            "{s} legend \"{}\"",
            q(&c.legend.replace('\n', " ; "))
        ));
        out.push(String::new());
    }
    for (k, c) in curves.iter().enumerate() {
        out.push(format!("@target g0.s{}", k + 1));
        out.push("@type xy".into());
        for (x, y) in c.x.iter().zip(&c.y) {
            out.push(format!(
                "{} {}",
                c_general(*x, 8, false),
                c_general(*y, 8, false)
            ));
        }
        out.push("&".into());
    }
    out.push(String::new());
    out.join("\n")
}

/// IMPR_FONCTION FORMAT='XMGRACE': the functions' own points.
pub fn write_xmgrace(curves: &[FunctionCurve], opts: &GraphOptions) -> String {
    let xy: Vec<XyCurve> = curves.iter().map(FunctionCurve::xy).collect();
    grace_project(&xy, opts)
}

/// IMPR_FONCTION FORMAT='TABLEAU': every curve evaluated on `list_para`
/// (LIST_PARA) or on the abscissas of the first curve, printed as a table
/// whose columns are NOM_PARA and NOM_RESU_i (i = curve index). A curve that
/// cannot be evaluated on these abscissas (outside an excluded domain) is
/// left out, as code_aster does, and reported in the returned warnings.
pub fn write_tableau(
    curves: &[FunctionCurve],
    opts: &GraphOptions,
    list_para: Option<&[f64]>,
    print: &PrintOptions,
) -> Result<(String, Vec<String>), String> {
    let Some(first) = curves.first() else {
        return Err("IMPR_FONCTION needs at least one COURBE".to_string());
    };
    let xs: Vec<f64> = match list_para {
        Some(l) => l.to_vec(),
        None => first.function.abscissas.clone(),
    };
    let mut warnings = Vec::new();
    let mut columns: Vec<(String, Vec<f64>, String)> = Vec::new();
    for c in curves {
        match xs
            .iter()
            .map(|&x| c.function.eval(x))
            .collect::<Result<Vec<f64>, String>>()
        {
            Ok(ys) => {
                let label = format!("{}_{}", c.function.resu.trim(), columns.len());
                columns.push((label, ys, c.legend.clone()));
            }
            Err(e) => warnings.push(format!("curve '{}' is not printed: {e}", c.legend)),
        }
    }
    // Title lines as TraceTableau builds them; the printer adds its own '#'.
    let com = &print.comment;
    let mut title = vec![
        format!("{com} {}", opts.titre),
        format!("{com} {}", opts.sous_titre),
    ];
    for (i, (_, _, legend)) in columns.iter().enumerate() {
        title.push(format!("{com} Courbe {i}"));
        for l in legend.split('\n') {
            title.push(format!("{com} {l}"));
        }
    }
    let mut table = Table {
        title,
        ..Table::default()
    };
    let para = first.function.para.clone();
    table
        .add_column(&para, ColumnType::Real)
        .map_err(|e| e.message)?;
    for (label, _, _) in &columns {
        table
            .add_column(label, ColumnType::Real)
            .map_err(|e| e.message)?;
    }
    for (j, x) in xs.iter().enumerate() {
        let mut row = vec![Some(Cell::Real(*x))];
        row.extend(columns.iter().map(|(_, ys, _)| Some(Cell::Real(ys[j]))));
        table.push_row(row).map_err(|e| e.message)?;
    }
    let text = table.print(print).map_err(|e| e.message)?;
    Ok((text, warnings))
}
