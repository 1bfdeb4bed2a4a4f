//! Python's text forms of values: `str()`, `repr()` and printf-style `%`
//! formatting, so that a group name built as `'G_%d' % i` or
//! `'T' + str(x)` is the text Python would build.

use super::PyVal;

/// The longest text a command file may build (repetition, formatting).
pub const MAX_TEXT: usize = 10_000_000;

/// `repr()` of a float: the shortest text that reads back to the same
/// value, in fixed notation for exponents -4..16 and scientific otherwise
/// (`1e-05`, `1e+16`), always with a '.' or an exponent.
pub fn float_repr(x: f64) -> String {
    if x == 0.0 {
        return if x.is_sign_negative() { "-0.0" } else { "0.0" }.into();
    }
    if !x.is_finite() {
        return if x.is_nan() {
            "nan".into()
        } else if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    // `{:e}` gives the shortest round-trip digits: "1.2345e-5".
    let s = format!("{:e}", x.abs());
    let (mant, exp) = s.split_once('e').expect("LowerExp has an exponent");
    let exp: i32 = exp.parse().expect("LowerExp exponent is an integer");
    let digits: String = mant.chars().filter(|c| *c != '.').collect();
    let sign = if x < 0.0 { "-" } else { "" };
    if (-4..16).contains(&exp) {
        let n = digits.len() as i32;
        let body = if exp < 0 {
            format!("0.{}{}", "0".repeat((-exp - 1) as usize), digits)
        } else if exp + 1 >= n {
            format!("{}{}.0", digits, "0".repeat((exp + 1 - n) as usize))
        } else {
            let (a, b) = digits.split_at((exp + 1) as usize);
            format!("{a}.{b}")
        };
        format!("{sign}{body}")
    } else {
        let (first, rest) = digits.split_at(1);
        let m = if rest.is_empty() {
            first.to_string()
        } else {
            format!("{first}.{rest}")
        };
        format!(
            "{sign}{m}e{}{:02}",
            if exp < 0 { '-' } else { '+' },
            exp.abs()
        )
    }
}

/// `repr()` of a text: single quotes unless the text holds one and no
/// double quote, as Python chooses.
pub fn str_repr(s: &str) -> String {
    let q = if s.contains('\'') && !s.contains('"') {
        '"'
    } else {
        '\''
    };
    let mut out = String::with_capacity(s.len() + 2);
    out.push(q);
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c == q => {
                out.push('\\');
                out.push(c);
            }
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                out.push_str(&format!("\\x{:02x}", c as u32))
            }
            c => out.push(c),
        }
    }
    out.push(q);
    out
}

/// `str(v)`; `Err` for values whose text Python has but aster cannot give
/// before the study runs (concepts).
pub fn py_str(v: &PyVal) -> Result<String, String> {
    match v {
        PyVal::Str(s) => Ok(s.clone()),
        _ => py_repr(v),
    }
}

/// `repr(v)`, which is also how items show inside a tuple or a list.
pub fn py_repr(v: &PyVal) -> Result<String, String> {
    let items = |items: &[super::SpVal]| -> Result<Vec<String>, String> {
        items.iter().map(|x| py_repr(&x.v)).collect()
    };
    Ok(match v {
        PyVal::Int(i) => i.to_string(),
        PyVal::Real(r) => float_repr(*r),
        PyVal::Bool(b) => if *b { "True" } else { "False" }.into(),
        PyVal::Str(s) => str_repr(s),
        PyVal::None => "None".into(),
        PyVal::Tuple(t) => {
            let v = items(t)?;
            if v.len() == 1 {
                format!("({},)", v[0])
            } else {
                format!("({})", v.join(", "))
            }
        }
        PyVal::List(_, t) => format!("[{}]", items(t)?.join(", ")),
        PyVal::Range(a, b, s) => {
            if *s == 1 {
                format!("range({a}, {b})")
            } else {
                format!("range({a}, {b}, {s})")
            }
        }
        // code_aster's _F is a dict.
        PyVal::Fact(_, kv) => {
            let v: Vec<String> = kv
                .iter()
                .map(|(k, x)| Ok(format!("{}: {}", str_repr(&k.name), py_repr(&x.v)?)))
                .collect::<Result<_, String>>()?;
            format!("{{{}}}", v.join(", "))
        }
        PyVal::Module(m) => format!("<module '{m}' (built-in)>"),
        PyVal::Func(f) => format!("<built-in function {}>", f.rsplit('.').next().unwrap_or(f)),
        PyVal::Concept { name, .. } => {
            return Err(format!(
                "the text of the concept {name} is not known before the study runs"
            ))
        }
        PyVal::Iter(kind, _) => {
            return Err(format!(
                "the text of {} {kind} object is its address; write list({kind}(...))",
                super::article(kind)
            ))
        }
        PyVal::Stale(name) => {
            return Err(format!(
                "the concept {name} has been defined again since this value took it"
            ))
        }
        PyVal::Poison => return Err("an invalid value".into()),
    })
}

fn as_f64(v: &PyVal) -> Option<f64> {
    match v {
        PyVal::Int(i) => Some(*i as f64),
        PyVal::Real(r) => Some(*r),
        PyVal::Bool(b) => Some(*b as i64 as f64),
        _ => None,
    }
}

/// Python's type name of a value, for its TypeError-like messages.
pub fn type_name(v: &PyVal) -> &'static str {
    match v {
        PyVal::Int(_) => "int",
        PyVal::Real(_) => "float",
        PyVal::Bool(_) => "bool",
        PyVal::Str(_) => "str",
        PyVal::None => "NoneType",
        PyVal::Tuple(_) => "tuple",
        PyVal::List(..) => "list",
        PyVal::Range(..) => "range",
        PyVal::Fact(..) => "dict",
        PyVal::Module(_) => "module",
        PyVal::Func(_) => "builtin_function",
        PyVal::Iter(kind, _) => kind,
        PyVal::Concept { .. } | PyVal::Stale(_) => "concept",
        PyVal::Poison => "invalid value",
    }
}

/// One `%` conversion specification.
struct Spec {
    left: bool,
    zero: bool,
    plus: bool,
    space: bool,
    alt: bool,
    width: usize,
    precision: Option<usize>,
    conv: char,
}

/// `fmt % args`, as Python's printf-style formatting: a tuple gives the
/// arguments, any other value is the only one.
pub fn percent_format(fmt: &str, args: &PyVal) -> Result<String, String> {
    let args: Vec<&PyVal> = match args {
        PyVal::Tuple(t) => t.iter().map(|x| &x.v).collect(),
        v => vec![v],
    };
    let mut next = 0;
    let mut out = String::new();
    let mut chars = fmt.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        let mut spec = Spec {
            left: false,
            zero: false,
            plus: false,
            space: false,
            alt: false,
            width: 0,
            precision: None,
            conv: ' ',
        };
        if chars.peek() == Some(&'(') {
            return Err("formats by name (%(name)s) are not supported".into());
        }
        while let Some(&f) = chars.peek() {
            match f {
                '-' => spec.left = true,
                '0' => spec.zero = true,
                '+' => spec.plus = true,
                ' ' => spec.space = true,
                '#' => spec.alt = true,
                _ => break,
            }
            chars.next();
        }
        let number = |chars: &mut std::iter::Peekable<std::str::Chars<'_>>| {
            let mut n: usize = 0;
            while let Some(d) = chars.peek().and_then(|c| c.to_digit(10)) {
                n = n.saturating_mul(10).saturating_add(d as usize);
                chars.next();
            }
            n
        };
        if chars.peek() == Some(&'*') {
            return Err("'*' widths are not supported in formats".into());
        }
        spec.width = number(&mut chars);
        if chars.peek() == Some(&'.') {
            chars.next();
            spec.precision = Some(number(&mut chars));
        }
        if spec.width > 10_000 || spec.precision.is_some_and(|p| p > 10_000) {
            return Err("a width or precision above 10000 in a format".into());
        }
        while matches!(chars.peek(), Some('h' | 'l' | 'L')) {
            chars.next();
        }
        let Some(conv) = chars.next() else {
            return Err("incomplete format".into());
        };
        spec.conv = conv;
        if conv == '%' {
            out.push('%');
            continue;
        }
        let Some(arg) = args.get(next) else {
            return Err("not enough arguments for format string".into());
        };
        next += 1;
        out.push_str(&convert(&spec, arg)?);
        if out.len() > MAX_TEXT {
            return Err(format!(
                "the formatted text is longer than {MAX_TEXT} bytes"
            ));
        }
    }
    if next < args.len() {
        return Err("not all arguments converted during string formatting".into());
    }
    Ok(out)
}

fn convert(spec: &Spec, arg: &PyVal) -> Result<String, String> {
    let number = |what: &str| {
        as_f64(arg).ok_or_else(|| {
            format!(
                "%{} format: {what} is required, not {}",
                spec.conv,
                type_name(arg)
            )
        })
    };
    let (sign_neg, body, numeric) = match spec.conv {
        's' | 'r' => {
            let mut s = if spec.conv == 's' {
                py_str(arg)?
            } else {
                py_repr(arg)?
            };
            if let Some(p) = spec.precision {
                s = s.chars().take(p).collect();
            }
            (false, s, false)
        }
        'd' | 'i' | 'u' => {
            let s = match arg {
                PyVal::Int(i) => i.unsigned_abs().to_string(),
                PyVal::Bool(b) => (*b as u8).to_string(),
                _ => {
                    let x = number("a real number")?;
                    format!("{:.0}", x.trunc().abs())
                }
            };
            let neg = match arg {
                PyVal::Int(i) => *i < 0,
                _ => number("a real number")?.trunc() < 0.0,
            };
            let s = match spec.precision {
                Some(p) if s.len() < p => format!("{}{s}", "0".repeat(p - s.len())),
                _ => s,
            };
            (neg, s, true)
        }
        'f' | 'F' => {
            let x = number("a real number")?;
            let p = spec.precision.unwrap_or(6);
            let mut s = format!("{:.*}", p, x.abs());
            if spec.alt && p == 0 {
                s.push('.');
            }
            (x.is_sign_negative(), s, true)
        }
        'e' | 'E' => {
            let x = number("a real number")?;
            let p = spec.precision.unwrap_or(6);
            let s = exp_form(x.abs(), p, spec.alt);
            let s = if spec.conv == 'E' {
                s.to_uppercase()
            } else {
                s
            };
            (x.is_sign_negative(), s, true)
        }
        'g' | 'G' => {
            let x = number("a real number")?;
            let s = general_form(x.abs(), spec.precision.unwrap_or(6), spec.alt);
            let s = if spec.conv == 'G' {
                s.to_uppercase()
            } else {
                s
            };
            (x.is_sign_negative(), s, true)
        }
        c => return Err(format!("unsupported format character '{c}'")),
    };
    let sign = if !numeric {
        ""
    } else if sign_neg {
        "-"
    } else if spec.plus {
        "+"
    } else if spec.space {
        " "
    } else {
        ""
    };
    let len = sign.chars().count() + body.chars().count();
    let pad = spec.width.saturating_sub(len);
    Ok(if spec.left {
        format!("{sign}{body}{}", " ".repeat(pad))
    } else if spec.zero && numeric {
        format!("{sign}{}{body}", "0".repeat(pad))
    } else {
        format!("{}{sign}{body}", " ".repeat(pad))
    })
}

/// `%.{p}e` of a non-negative number: at least two exponent digits.
fn exp_form(x: f64, p: usize, alt: bool) -> String {
    let s = format!("{:.*e}", p, x);
    let (m, e) = s.split_once('e').expect("LowerExp has an exponent");
    let e: i32 = e.parse().expect("exponent");
    let m = if alt && p == 0 {
        format!("{m}.")
    } else {
        m.to_string()
    };
    format!("{m}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs())
}

/// `%.{p}g` of a non-negative number: scientific when the exponent is
/// below -4 or at least the precision, trailing zeros removed (kept with
/// `#`).
fn general_form(x: f64, p: usize, alt: bool) -> String {
    let p = p.max(1);
    if x == 0.0 {
        return if alt {
            format!("0.{}", "0".repeat(p - 1))
        } else {
            "0".into()
        };
    }
    // The exponent after rounding to p significant digits.
    let e_form = format!("{:.*e}", p - 1, x);
    let exp: i32 = e_form
        .split_once('e')
        .and_then(|(_, e)| e.parse().ok())
        .expect("LowerExp has an exponent");
    let strip = |s: String| -> String {
        if alt || !s.contains('.') {
            return s;
        }
        let t = s.trim_end_matches('0');
        t.trim_end_matches('.').to_string()
    };
    if exp < -4 || exp >= p as i32 {
        let s = exp_form(x, p - 1, alt);
        let (m, e) = s.split_once('e').expect("exponent");
        format!("{}e{e}", strip(m.to_string()))
    } else {
        let decimals = (p as i32 - 1 - exp).max(0) as usize;
        strip(format!("{:.*}", decimals, x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog::eval::SpVal;
    use crate::diag::Span;

    fn sp(v: PyVal) -> SpVal {
        SpVal {
            v,
            span: Span::new(0, 0),
        }
    }

    /// Expected texts are what CPython 3.11 prints for the same formats.
    #[test]
    fn floats_print_as_python() {
        for (x, s) in [
            (0.1, "0.1"),
            (1e16, "1e+16"),
            (1e15, "1000000000000000.0"),
            (0.0001, "0.0001"),
            (0.00001, "1e-05"),
            (-0.0, "-0.0"),
            (1.5e-7, "1.5e-07"),
            (2.27, "2.27"),
            (227000.0, "227000.0"),
            (1.0 / 3.0, "0.3333333333333333"),
            (123456789012345680.0, "1.2345678901234568e+17"),
        ] {
            assert_eq!(float_repr(x), s);
        }
    }

    #[test]
    fn percent_formats_as_python() {
        let f = |fmt: &str, v: PyVal| percent_format(fmt, &v).unwrap();
        let t = |items: Vec<PyVal>| PyVal::Tuple(items.into_iter().map(sp).collect());
        assert_eq!(f("G_%d", PyVal::Int(3)), "G_3");
        assert_eq!(
            f(
                "%i|%5d|%-5d|%05d",
                t(vec![
                    PyVal::Int(-2),
                    PyVal::Int(42),
                    PyVal::Int(7),
                    PyVal::Int(-42)
                ])
            ),
            "-2|   42|7    |-0042"
        );
        assert_eq!(f("%d", PyVal::Real(3.7)), "3");
        assert_eq!(f("%d", PyVal::Real(-3.7)), "-3");
        assert_eq!(
            f("%s/%s", t(vec![PyVal::Str("A".into()), PyVal::Real(0.5)])),
            "A/0.5"
        );
        assert_eq!(f("%g", PyVal::Real(1e-5)), "1e-05");
        assert_eq!(f("%g", PyVal::Real(123456.0)), "123456");
        assert_eq!(f("%g", PyVal::Real(1234567.0)), "1.23457e+06");
        assert_eq!(f("%g", PyVal::Real(0.0001)), "0.0001");
        assert_eq!(f("%g", PyVal::Int(100)), "100");
        assert_eq!(f("%.3g", PyVal::Real(2.0)), "2");
        assert_eq!(f("%e", PyVal::Real(12345.678)), "1.234568e+04");
        assert_eq!(f("%.2E", PyVal::Real(-0.00012)), "-1.20E-04");
        assert_eq!(f("%f", PyVal::Real(2.5)), "2.500000");
        assert_eq!(f("%5.2f", PyVal::Real(3.14659)), " 3.15");
        assert_eq!(f("%.0f", PyVal::Real(2.5)), "2");
        assert_eq!(f("%.2f", PyVal::Real(0.125)), "0.12");
        assert_eq!(f("%+.1f", PyVal::Real(1.25)), "+1.2");
        assert_eq!(f("%8.3e", PyVal::Real(1.0)), "1.000e+00");
        assert_eq!(f("100%%", t(vec![])), "100%");
        assert_eq!(f("%s", PyVal::Bool(true)), "True");
        assert_eq!(f("%r", PyVal::Str("a".into())), "'a'");
        assert_eq!(
            f(
                "%s",
                PyVal::List(0, vec![sp(PyVal::Int(1)), sp(PyVal::Str("b".into()))])
            ),
            "[1, 'b']"
        );
        assert_eq!(f("%s", t(vec![PyVal::Int(1)])), "1");
        assert_eq!(
            percent_format("%d %d", &PyVal::Int(1)).unwrap_err(),
            "not enough arguments for format string"
        );
        assert_eq!(
            percent_format("%d", &t(vec![PyVal::Int(1), PyVal::Int(2)])).unwrap_err(),
            "not all arguments converted during string formatting"
        );
        assert!(percent_format("%d", &PyVal::Str("x".into()))
            .unwrap_err()
            .contains("not str"));
        assert!(percent_format("%q", &PyVal::Int(1)).is_err());
    }
}
