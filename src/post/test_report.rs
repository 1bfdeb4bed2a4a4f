//! The TEST_RESU / TEST_TABLE checks and the lines they print in the .resu.
//!
//! The pass rules and the text layout follow code_aster 15 (`bibfor/test/
//! trresu.F90`, `tresu_print.F90`, `tresu_ordgrd.F90`, `op0177.F90` and the
//! Python `TestResult.showResult`): a study written for code_aster is judged
//! the same way here, and its .resu can be compared line by line with one
//! produced by code_aster. The format is documented in
//! `docs/testing-report.md`.

/// code_aster's `r8prem()`: the machine epsilon. A VALE_CALC at most this
/// large in magnitude counts as zero for the skip rule.
pub const R8PREM: f64 = f64::EPSILON;

/// The kind of reference a check compares with (keyword REFERENCE).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RefKind {
    NonRegression,
    Analytique,
    SourceExterne,
    AutreAster,
    NonDefini,
}

impl RefKind {
    /// The label code_aster prints in the first column after the status.
    pub fn as_str(self) -> &'static str {
        match self {
            RefKind::NonRegression => "NON_REGRESSION",
            RefKind::Analytique => "ANALYTIQUE",
            RefKind::SourceExterne => "SOURCE_EXTERNE",
            RefKind::AutreAster => "AUTRE_ASTER",
            RefKind::NonDefini => "NON_DEFINI",
        }
    }

    /// Reads a REFERENCE keyword value (or NON_REGRESSION).
    pub fn parse(text: &str) -> Option<RefKind> {
        Some(match text {
            "NON_REGRESSION" => RefKind::NonRegression,
            "ANALYTIQUE" => RefKind::Analytique,
            "SOURCE_EXTERNE" => RefKind::SourceExterne,
            "AUTRE_ASTER" => RefKind::AutreAster,
            "NON_DEFINI" => RefKind::NonDefini,
            _ => return None,
        })
    }
}

impl std::fmt::Display for RefKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Keyword CRITERE: how the distance to the reference is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Critere {
    #[default]
    Relatif,
    Absolu,
}

impl Critere {
    pub fn as_str(self) -> &'static str {
        match self {
            Critere::Relatif => "RELATIF",
            Critere::Absolu => "ABSOLU",
        }
    }

    pub fn parse(text: &str) -> Option<Critere> {
        match text {
            "RELATIF" => Some(Critere::Relatif),
            "ABSOLU" => Some(Critere::Absolu),
            _ => None,
        }
    }
}

/// Outcome of one check line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Ok,
    Nook,
    Skip,
}

impl Status {
    /// The 4-character diagnostic of the line.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Ok => " OK ",
            Status::Nook => "NOOK",
            Status::Skip => "SKIP",
        }
    }
}

/// A computed or reference value: VALE_CALC (real), VALE_CALC_I (integer)
/// or VALE_CALC_K (text).
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Real(f64),
    Int(i64),
    Text(String),
}

impl Value {
    /// Python's `'%s' % value`, which is what code_aster prints.
    pub fn py_str(&self) -> String {
        match self {
            Value::Real(x) => py_repr(*x),
            Value::Int(i) => i.to_string(),
            Value::Text(s) => s.clone(),
        }
    }

    fn type_name(&self) -> &'static str {
        match self {
            Value::Real(_) => "a real",
            Value::Int(_) => "an integer",
            Value::Text(_) => "a text",
        }
    }

    /// The suffix of the keywords that give a value of this type:
    /// VALE_CALC, VALE_CALC_I, VALE_CALC_K (VALE_REFE likewise).
    pub fn keyword_suffix(&self) -> &'static str {
        match self {
            Value::Real(_) => "",
            Value::Int(_) => "_I",
            Value::Text(_) => "_K",
        }
    }

    pub fn same_type(&self, other: &Value) -> bool {
        std::mem::discriminant(self) == std::mem::discriminant(other)
    }
}

impl From<&crate::post::table::Cell> for Value {
    fn from(cell: &crate::post::table::Cell) -> Value {
        use crate::post::table::Cell;
        match cell {
            Cell::Int(i) => Value::Int(*i),
            Cell::Real(x) => Value::Real(*x),
            Cell::Text(s) => Value::Text(s.clone()),
        }
    }
}

/// An alarm raised while checking, with code_aster's message id so that a
/// user can look it up in the code_aster documentation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Alarm {
    pub id: &'static str,
    pub text: String,
}

/// One printed check: the result of comparing a computed value with a
/// reference.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckLine {
    pub status: Status,
    pub kind: RefKind,
    /// Legend column, already normalised as code_aster does (`XXXX` default).
    pub legend: String,
    pub critere: Critere,
    /// Tolerance as given: TOLE_MACHINE or PRECISION (a fraction when
    /// relative).
    pub tolerance: f64,
    /// ORDRE_GRANDEUR when it was used; it scales an absolute tolerance.
    pub ordre_grandeur: Option<f64>,
    /// The reference used (the closest one), absolute value if VALE_ABS.
    /// `None` when no reference value exists (VALE_CALC not recorded).
    pub reference: Option<Value>,
    /// The computed value, absolute value if VALE_ABS.
    pub computed: Value,
    /// The printed error: in percent for RELATIF, absolute for ABSOLU.
    /// `None` for SKIP lines and text checks.
    pub error: Option<f64>,
    pub alarms: Vec<Alarm>,
    /// Aster extension: a short note printed after the TOLE column.
    pub note: Option<String>,
}

/// The message of alarm TEST0_12 (a skipped non-regression check).
pub const TEST0_12: &str = "TEST0_12: the NON_REGRESSION check is skipped: VALE_CALC is zero \
(|VALE_CALC| <= 2.2e-16) and ORDRE_GRANDEUR is not given, so no relative test is possible. \
Give ORDRE_GRANDEUR (and CRITERE='ABSOLU') to test this value.";

/// The message of alarm TEST0_11 (an occurrence that tests nothing).
pub const TEST0_11: &str = "TEST0_11: this occurrence tests nothing: its NON_REGRESSION check \
is skipped and it has no REFERENCE.";

/// Note of the aster extension where VALE_CALC is absent.
pub const NOTE_NOT_RECORDED: &str = "VALE_CALC not recorded";

/// Compares `computed` with the closest of `references`.
///
/// * RELATIF passes when |v - ref| <= tolerance·|ref|; ABSOLU when
///   |v - ref| <= tolerance·ORDRE_GRANDEUR (1 when absent). code_aster
///   ignores ORDRE_GRANDEUR in RELATIF mode, and so does this function.
/// * With `vale_abs` the absolute values are compared (and printed).
/// * A NON_REGRESSION check whose first real reference is zero
///   (|ref| <= [`R8PREM`]) without `ordre_grandeur` is SKIP, with alarm
///   TEST0_12: a relative test against 0 could never pass.
/// * An empty `references` is the aster extension "VALE_CALC absent": a
///   SKIP line that shows the computed value so that it can be recorded.
///
/// Errors: the reference values do not have the type of the computed value
/// (code_aster's CALCULEL6_8), or a tolerance is negative or not finite.
pub fn check(
    kind: RefKind,
    computed: &Value,
    references: &[Value],
    tolerance: f64,
    critere: Critere,
    ordre_grandeur: Option<f64>,
    vale_abs: bool,
) -> Result<CheckLine, String> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(format!(
            "the tolerance of a {kind} check must be a finite non-negative real, got {}",
            py_repr(tolerance)
        ));
    }
    if let Some(og) = ordre_grandeur {
        if !(og.is_finite() && og > 0.0) {
            return Err(format!(
                "ORDRE_GRANDEUR must be a finite positive real, got {}",
                py_repr(og)
            ));
        }
    }
    let computed_shown = if vale_abs {
        abs_value(computed)
    } else {
        computed.clone()
    };
    let mut line = CheckLine {
        status: Status::Skip,
        kind,
        legend: "XXXX".to_string(),
        critere,
        tolerance,
        ordre_grandeur: None,
        reference: None,
        computed: computed_shown,
        error: None,
        alarms: Vec::new(),
        note: None,
    };
    if references.is_empty() {
        line.note = Some(if kind == RefKind::NonRegression {
            NOTE_NOT_RECORDED.to_string()
        } else {
            "VALE_REFE not given".to_string()
        });
        return Ok(line);
    }
    if let Some(bad) = references.iter().find(|r| !r.same_type(computed)) {
        // The non-regression value is VALE_CALC*, a reference's VALE_REFE*.
        let family = if kind == RefKind::NonRegression {
            "VALE_CALC"
        } else {
            "VALE_REFE"
        };
        return Err(format!(
            "the {kind} reference is {} ({family}{}) but the tested value is {}: give it as \
             {family}{}",
            bad.type_name(),
            bad.keyword_suffix(),
            computed.type_name(),
            computed.keyword_suffix()
        ));
    }
    if let Value::Text(text) = computed {
        // Text checks (VALE_CALC_K): exact equality, trailing blanks ignored.
        let found = references.iter().find(|r| match r {
            Value::Text(r) => r.trim_end() == text.trim_end(),
            _ => false,
        });
        line.status = if found.is_some() {
            Status::Ok
        } else {
            Status::Nook
        };
        line.reference = Some(found.unwrap_or(&references[0]).clone());
        return Ok(line);
    }
    if kind == RefKind::NonRegression && ordre_grandeur.is_none() {
        if let Value::Real(first) = references[0] {
            if first.abs() <= R8PREM {
                line.reference = Some(references[0].clone());
                line.alarms.push(Alarm {
                    id: "TEST0_12",
                    text: TEST0_12.to_string(),
                });
                return Ok(line);
            }
        }
    }
    let value = as_f64(computed, vale_abs);
    // The closest reference (the first one on ties).
    let mut best = 0;
    let mut best_dist = f64::INFINITY;
    for (i, r) in references.iter().enumerate() {
        let d = (value - as_f64(r, vale_abs)).abs();
        if d < best_dist || (i == 0 && d.is_nan()) {
            best = i;
            best_dist = d;
        }
    }
    let reference = as_f64(&references[best], vale_abs);
    line.reference = Some(if vale_abs {
        abs_value(&references[best])
    } else {
        references[best].clone()
    });
    // Same operations, in the same order, as TestResult.showResult so that
    // the printed error has the same digits.
    let error = (1.0 * reference - value).abs();
    let ok;
    match critere {
        Critere::Relatif => {
            ok = error <= (tolerance * reference).abs();
            line.error = Some(if reference != 0.0 {
                error / reference.abs() * 100.0
            } else if ok {
                0.0
            } else {
                999.999999
            });
        }
        Critere::Absolu => {
            let compare = ordre_grandeur.unwrap_or(1.0);
            ok = error <= (tolerance * compare).abs();
            line.error = Some(error);
        }
    }
    // The line shows the tolerance (a percentage when relative) and the
    // error: a value, reference or tolerance so large that these overflow
    // would print "inf" or "nan" where a number is expected.
    let shown_tolerance = match critere {
        Critere::Relatif => tolerance * 100.0,
        Critere::Absolu => tolerance * ordre_grandeur.unwrap_or(1.0),
    };
    if !shown_tolerance.is_finite() {
        return Err(format!(
            "the tolerance {} is too large: the {} it gives overflows the reals",
            py_repr(tolerance),
            if critere == Critere::Relatif {
                "percentage"
            } else {
                "absolute tolerance"
            }
        ));
    }
    if !line.error.is_some_and(f64::is_finite) {
        return Err(format!(
            "the difference between the computed value {} and the reference {} overflows the reals",
            py_repr(value),
            py_repr(reference)
        ));
    }
    line.ordre_grandeur = ordre_grandeur;
    line.status = if ok { Status::Ok } else { Status::Nook };
    Ok(line)
}

fn abs_value(v: &Value) -> Value {
    match v {
        Value::Real(x) => Value::Real(x.abs()),
        Value::Int(i) => Value::Int(i.saturating_abs()),
        Value::Text(s) => Value::Text(s.clone()),
    }
}

fn as_f64(v: &Value, vale_abs: bool) -> f64 {
    let x = match v {
        Value::Real(x) => *x,
        Value::Int(i) => *i as f64,
        Value::Text(_) => f64::NAN,
    };
    if vale_abs {
        x.abs()
    } else {
        x
    }
}

/// The REFERENCE part of a TEST_RESU / TEST_TABLE occurrence.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    pub kind: RefKind,
    /// VALE_REFE / VALE_REFE_I / VALE_REFE_K.
    pub values: Vec<Value>,
    /// PRECISION (default 1e-3).
    pub precision: f64,
}

impl Reference {
    pub fn new(kind: RefKind, values: Vec<Value>) -> Reference {
        Reference {
            kind,
            values,
            precision: 1e-3,
        }
    }
}

/// The test keywords of one TEST_RESU RESU occurrence (or of TEST_TABLE).
#[derive(Debug, Clone, PartialEq)]
pub struct TestSpec {
    /// LEGENDE (printed `XXXX` when absent).
    pub legend: Option<String>,
    /// VALE_CALC / VALE_CALC_I / VALE_CALC_K; empty when not recorded yet.
    pub vale_calc: Vec<Value>,
    /// TOLE_MACHINE(1), default 1e-6.
    pub tole_machine: f64,
    /// CRITERE(1), default RELATIF; used by both checks.
    pub critere: Critere,
    pub reference: Option<Reference>,
    pub ordre_grandeur: Option<f64>,
    /// VALE_ABS='OUI'.
    pub vale_abs: bool,
}

impl TestSpec {
    /// A spec with code_aster's defaults.
    pub fn new(vale_calc: Vec<Value>) -> TestSpec {
        TestSpec {
            legend: None,
            vale_calc,
            tole_machine: 1e-6,
            critere: Critere::Relatif,
            reference: None,
            ordre_grandeur: None,
            vale_abs: false,
        }
    }
}

/// Replaces the characters code_aster refuses in a legend by `_` and keeps
/// 16 characters, as `tresu_read_refe` (lxnoac) does.
pub fn normalize_legend(legend: &str) -> String {
    legend
        .trim_end()
        .chars()
        .take(16)
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

/// The lines of one occurrence: the non-regression check (VALE_CALC,
/// TOLE_MACHINE, CRITERE) and, with REFERENCE, the reference check
/// (VALE_REFE, PRECISION, the same CRITERE).
///
/// ORDRE_GRANDEUR is used only when VALE_CALC is zero and only by the
/// non-regression check, as in `tresu_ordgrd`. When the non-regression
/// check is skipped and there is no reference, alarm TEST0_11 is added.
pub fn occurrence_checks(spec: &TestSpec, computed: &Value) -> Result<Vec<CheckLine>, String> {
    let legend = spec
        .legend
        .as_deref()
        .map(normalize_legend)
        .unwrap_or_else(|| "XXXX".to_string());
    let zero_calc = matches!(spec.vale_calc.first(), Some(Value::Real(x)) if x.abs() <= R8PREM);
    let og = if zero_calc { spec.ordre_grandeur } else { None };
    let mut first = check(
        RefKind::NonRegression,
        computed,
        &spec.vale_calc,
        spec.tole_machine,
        spec.critere,
        og,
        spec.vale_abs,
    )?;
    first.legend = legend.clone();
    if first.status == Status::Skip && spec.reference.is_none() && first.note.is_none() {
        first.alarms.push(Alarm {
            id: "TEST0_11",
            text: TEST0_11.to_string(),
        });
    }
    let mut lines = vec![first];
    if let Some(r) = &spec.reference {
        let mut second = check(
            r.kind,
            computed,
            &r.values,
            r.precision,
            spec.critere,
            None,
            spec.vale_abs,
        )?;
        second.legend = legend;
        lines.push(second);
    }
    Ok(lines)
}

/// Python's `str(float)` / `repr(float)`: the shortest digits that read
/// back to the same double, in fixed notation when the decimal exponent is
/// in [-4, 16) and in exponent notation (`1e-05`, `1.5e+16`) otherwise.
pub fn py_repr(x: f64) -> String {
    if x.is_nan() {
        return "nan".to_string();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.to_string();
    }
    if x == 0.0 {
        return if x.is_sign_negative() { "-0.0" } else { "0.0" }.to_string();
    }
    // Rust's `{:e}` gives the shortest round-trip digits, as Python does.
    let sci = format!("{:e}", x.abs());
    let (mantissa, exponent) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
    let exp: i32 = exponent.parse().unwrap_or(0);
    let digits: String = mantissa.chars().filter(|c| c.is_ascii_digit()).collect();
    let sign = if x < 0.0 { "-" } else { "" };
    // Position of the decimal point relative to the digit string.
    let decpt = exp + 1;
    let body = if decpt > -4 && decpt <= 16 {
        if decpt <= 0 {
            format!("0.{}{}", "0".repeat((-decpt) as usize), digits)
        } else if decpt as usize >= digits.len() {
            format!("{}{}.0", digits, "0".repeat(decpt as usize - digits.len()))
        } else {
            let (int, frac) = digits.split_at(decpt as usize);
            format!("{int}.{frac}")
        }
    } else {
        let (first, rest) = digits.split_at(1);
        let mant = if rest.is_empty() {
            first.to_string()
        } else {
            format!("{first}.{rest}")
        };
        let esign = if exp < 0 { '-' } else { '+' };
        format!("{mant}e{esign}{:02}", exp.abs())
    };
    format!("{sign}{body}")
}

/// `_fortran` of TestResult.py: exponents printed with a capital E.
fn fortran_look(s: &str) -> String {
    s.replace('e', "E")
}

/// One row in TestResult.write's columns: `%-4s ` then `%-16s`, `%-16s`,
/// two values of `width`, `%-16s`, `%-16s`, joined by one space.
fn write_row(width: usize, cols: &[&str]) -> String {
    let mut out = String::new();
    for (i, col) in cols.iter().enumerate() {
        match i {
            0 => out.push_str(&format!("{col:<4} ")),
            3 | 4 => out.push_str(&format!(" {col:<width$}")),
            _ => out.push_str(&format!(" {col:<16}")),
        }
    }
    out
}

/// The lines a check prints. `label` adds the column titles first (code_aster
/// prints them before the first check of an occurrence only).
pub fn format_check(line: &CheckLine, label: bool) -> Vec<String> {
    if let Value::Text(_) = line.computed {
        return format_text_check(line, label);
    }
    let relative = line.critere == Critere::Relatif;
    let compare = line.ordre_grandeur.unwrap_or(1.0);
    let sref = line
        .reference
        .as_ref()
        .map(Value::py_str)
        .unwrap_or_else(|| "-".to_string());
    let sval = line.computed.py_str();
    let width = 16.max(sref.len()).max(sval.len()) + 2;
    let mut out = Vec::new();
    if compare != 1.0 {
        out.push(write_row(
            width,
            &[" ", "ORDRE DE GRANDEUR :", &py_repr(compare)],
        ));
    }
    if label {
        out.push(write_row(
            width,
            &[
                " ",
                "REFERENCE",
                "LEGENDE",
                "VALE_REFE",
                "VALE_CALC",
                "ERREUR",
                "TOLE",
            ],
        ));
    }
    let kind = line.kind.as_str();
    let mut text = if line.status == Status::Skip {
        // Aster extension: a value that is not recorded yet is shown so that
        // the user can copy it into the command file.
        let shown = if line.note.as_deref() == Some(NOTE_NOT_RECORDED) {
            fortran_look(&sval)
        } else {
            "-".to_string()
        };
        write_row(width, &["SKIP", kind, "-", "-", &shown, "-", "-"])
    } else {
        let error = line.error.unwrap_or(f64::NAN);
        let mut serr = py_repr(error);
        if serr.len() > 15 {
            serr = c_exp(error, 13, 6, false);
        }
        let tole = if relative {
            line.tolerance * 100.0
        } else {
            (line.tolerance * compare).abs()
        };
        let mut stol = py_repr(tole);
        if relative {
            serr.push('%');
            stol.push('%');
        }
        write_row(
            width,
            &[
                line.status.as_str(),
                kind,
                &line.legend,
                &fortran_look(&sref),
                &fortran_look(&sval),
                &fortran_look(&serr),
                &fortran_look(&stol),
            ],
        )
    };
    if let Some(note) = &line.note {
        text.push(' ');
        text.push_str(note);
    }
    out.push(text);
    out
}

/// Text checks use the Fortran layout of `tresu_str`: no error column and
/// values in 24 characters.
fn format_text_check(line: &CheckLine, label: bool) -> Vec<String> {
    let a24 = |s: &str| -> String { format!("{:<24}", s.chars().take(24).collect::<String>()) };
    let a16 = |s: &str| -> String { format!("{:<16}", s.chars().take(16).collect::<String>()) };
    let mut out = Vec::new();
    if label {
        out.push(format!(
            "      {} {} {} {}",
            a16("REFERENCE"),
            a16("LEGENDE"),
            a24("VALE_REFE"),
            a24("VALE_CALC")
        ));
    }
    let sref = line
        .reference
        .as_ref()
        .map(Value::py_str)
        .unwrap_or_else(|| "-".into());
    let mut text = format!(
        "{}  {} {} {} {}",
        line.status.as_str(),
        a16(line.kind.as_str()),
        a16(&line.legend),
        a24(&sref),
        a24(&line.computed.py_str())
    );
    if let Some(note) = &line.note {
        text.push(' ');
        text.push_str(note);
    }
    out.push(text);
    out
}

/// The check lines of one occurrence, column titles before the first.
pub fn format_checks(lines: &[CheckLine]) -> Vec<String> {
    lines
        .iter()
        .enumerate()
        .flat_map(|(i, l)| format_check(l, i == 0))
        .collect()
}

/// The two header lines trresu/op0177 build in fixed columns: 21 characters
/// for `---- RESULTAT` (or `---- TABLE`) and the concept name (8 characters),
/// then 17 per field (a blank and 16 characters, longer values cut), written
/// by a Fortran list-directed WRITE (hence the leading blank) with trailing
/// blanks removed.
pub fn header_lines(keyword: &str, concept: &str, fields: &[(&str, &str)]) -> [String; 2] {
    let k16 = |s: &str| -> String { format!("{:<16}", s.chars().take(16).collect::<String>()) };
    let kw: String = keyword.chars().take(8).collect();
    let name: String = concept.chars().take(8).collect();
    let mut l1 = format!("{:<21}", format!("---- {kw}"));
    let mut l2 = format!("{:<21}", format!("     {name}"));
    for (label, value) in fields {
        l1.push(' ');
        l1.push_str(&k16(label));
        l2.push(' ');
        l2.push_str(&k16(value));
    }
    [format!(" {}", l1.trim_end()), format!(" {}", l2.trim_end())]
}

/// The .resu block of one TEST_RESU occurrence: header, check lines, and
/// the blank record (`write(ific,*) ' '`, i.e. two blanks) that ends it.
/// `fields` are the header columns, e.g. `[("NUME_ORDRE", "1"),
/// ("NOM_CHAM", "DEPL"), ("NOM_CMP", "DX"), ("GROUP_NO", "A1")]`.
pub fn resu_block(resultat: &str, fields: &[(&str, &str)], lines: &[CheckLine]) -> String {
    check_block("RESULTAT", resultat, fields, lines)
}

/// A header of `keyword` and `concept` with `fields`, the check lines and
/// the blank record that closes every block of the .resu.
fn check_block(
    keyword: &str,
    concept: &str,
    fields: &[(&str, &str)],
    lines: &[CheckLine],
) -> String {
    let mut out = String::new();
    for l in header_lines(keyword, concept, fields)
        .into_iter()
        .chain(format_checks(lines))
    {
        out.push_str(&l);
        out.push('\n');
    }
    out.push_str("  \n");
    out
}

/// The .resu block of one TEST_FONCTION VALEUR occurrence: the header
/// (`---- FONCTION`, the parameter and its value), the check lines and the
/// closing blank record, as TEST_RESU's blocks.
pub fn function_block(function: &str, para: &str, values: &[f64], lines: &[CheckLine]) -> String {
    let v = match values {
        [x] => py_repr(*x),
        _ => {
            let xs: Vec<String> = values.iter().map(|x| py_repr(*x)).collect();
            format!("({})", xs.join(", "))
        }
    };
    check_block(
        "FONCTION",
        function,
        &[("NOM_PARA", para), ("VALE_PARA", &v)],
        lines,
    )
}

/// The .resu block of one TEST_TABLE: an empty line and 80 dashes, the
/// header (`---- TABLE`, `NOM_PARA`, and `TYPE_TEST` when given), the check
/// lines and the closing blank record.
pub fn table_block(
    table: &str,
    nom_para: &str,
    type_test: Option<&str>,
    lines: &[CheckLine],
) -> String {
    let mut out = String::from("\n");
    out.push_str(&"-".repeat(80));
    out.push('\n');
    let mut fields = vec![("NOM_PARA", nom_para)];
    if let Some(t) = type_test {
        fields.push(("TYPE_TEST", t));
    }
    out.push_str(&check_block("TABLE", table, &fields, lines));
    out
}

/// Counts of the test report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TestCounts {
    pub ok: usize,
    pub nook: usize,
    pub skip: usize,
}

/// Adds the lines' statuses to the study's counts.
pub fn tally(counts: &mut TestCounts, lines: &[CheckLine]) {
    for l in lines {
        match l.status {
            Status::Ok => counts.ok += 1,
            Status::Nook => counts.nook += 1,
            Status::Skip => counts.skip += 1,
        }
    }
}

/// The summary that ends the .resu (an aster extension: code_aster leaves
/// the count to its test tools). The diagnostic is NOOK_TEST_RESU as soon
/// as one check fails; SKIP lines do not fail a study.
pub fn summary(counts: &TestCounts) -> String {
    let total = counts.ok + counts.nook + counts.skip;
    let diag = if counts.nook > 0 {
        "NOOK_TEST_RESU"
    } else {
        "OK"
    };
    let dashes = "-".repeat(80);
    format!(
        "\n{dashes}\n ---- SUMMARY OF TEST_RESU / TEST_TABLE\n      OK     {:>8}\n      NOOK   {:>8}\n      SKIP   {:>8}\n      TOTAL  {:>8}\n ---- DIAGNOSTIC : {diag}\n{dashes}\n",
        counts.ok, counts.nook, counts.skip, total
    )
}

/// C's `printf("%W.Pe")` (or `%W.PE` with `upper`): one digit, P decimals,
/// an exponent of at least two digits, right-justified in W characters.
pub fn c_exp(x: f64, width: usize, precision: usize, upper: bool) -> String {
    let body = if x.is_nan() {
        "nan".to_string()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.to_string()
    } else {
        let s = format!("{:.*e}", precision, x);
        let (mant, exp) = s.split_once('e').unwrap_or((s.as_str(), "0"));
        let exp: i32 = exp.parse().unwrap_or(0);
        let esign = if exp < 0 { '-' } else { '+' };
        format!("{mant}e{esign}{:02}", exp.abs())
    };
    let body = if upper { body.to_uppercase() } else { body };
    format!("{body:>width$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn write_row_matches_python_column_layout() {
        // '%-4s ' % ' OK ' + ' ' + '%-16s' % 'NON_REGRESSION' ...
        let row = write_row(
            18,
            &[
                " OK ",
                "NON_REGRESSION",
                "XXXX",
                "1.0",
                "1.0",
                "0.0%",
                "1E-4%",
            ],
        );
        assert_eq!(
            row,
            " OK   NON_REGRESSION   XXXX             1.0                1.0                0.0%             1E-4%           "
        );
    }

    /// Found by tests/fuzz_runner.rs: PRECISION=1.E308 printed "inf%".
    #[test]
    fn overflowing_tolerance_or_error_is_refused() {
        let check_with = |v: f64, r: f64, tol: f64, c: Critere| {
            check(
                RefKind::NonRegression,
                &Value::Real(v),
                &[Value::Real(r)],
                tol,
                c,
                None,
                false,
            )
        };
        let e = check_with(1.0, 1.0, 1e308, Critere::Relatif).unwrap_err();
        assert!(e.contains("too large"), "{e}");
        let e = check_with(1e308, -1e308, 1e-6, Critere::Absolu).unwrap_err();
        assert!(e.contains("overflows"), "{e}");
        assert!(check_with(1.0, 1.0, 1e300, Critere::Absolu).is_ok());
    }

    #[test]
    fn legend_is_cut_and_cleaned() {
        assert_eq!(normalize_legend("DX au point A1"), "DX_au_point_A1");
        assert_eq!(normalize_legend("ABCDEFGHIJKLMNOPQRS"), "ABCDEFGHIJKLMNOP");
    }
}
