//! FORMULE: a function given by an expression of its parameters
//! (`FORMULE(VALE='2.27 - 0.1 * X', NOM_PARA='X')`), evaluated by
//! parameter name when a command asks for a value. The expression tree is
//! built from the command file's syntax by the FORMULE command
//! (`commands::formule`): Python's arithmetic on reals and the math
//! functions code_aster puts in a formula's namespace.

/// A math function of a formula.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Log,
    Log10,
    Sqrt,
    Abs,
    Float,
    Atan2,
    Min,
    Max,
    Asinh,
    Acosh,
    Atanh,
    Expm1,
    Log1p,
    Log2,
    Fabs,
    Floor,
    Ceil,
    Trunc,
    Degrees,
    Radians,
    Cbrt,
    Copysign,
    Fmod,
    Hypot,
    Pow,
    /// Python's `int(x)` of a real: towards zero.
    Int,
    /// Python's `round(x)` (ties to even) and `round(x, n)` (the exact
    /// binary value rounded to n decimals, ties to even).
    Round,
}

impl Func {
    /// The function of a name, and the smallest and largest numbers of
    /// its arguments (None: no largest). The names are those of a
    /// formula's namespace in code_aster (every name of Python's `math`
    /// module, and the builtins): the real functions of reals among them.
    pub fn of_name(name: &str) -> Option<(Func, usize, Option<usize>)> {
        use Func::*;
        let one = |f| (f, 1, Some(1));
        let two = |f| (f, 2, Some(2));
        Some(match name {
            "sin" => one(Sin),
            "cos" => one(Cos),
            "tan" => one(Tan),
            "asin" => one(Asin),
            "acos" => one(Acos),
            "atan" => one(Atan),
            "sinh" => one(Sinh),
            "cosh" => one(Cosh),
            "tanh" => one(Tanh),
            "asinh" => one(Asinh),
            "acosh" => one(Acosh),
            "atanh" => one(Atanh),
            "exp" => one(Exp),
            "expm1" => one(Expm1),
            // math.log(x[, base])
            "log" => (Log, 1, Some(2)),
            "log10" => one(Log10),
            "log1p" => one(Log1p),
            "log2" => one(Log2),
            "sqrt" => one(Sqrt),
            "cbrt" => one(Cbrt),
            "abs" => one(Abs),
            "fabs" => one(Fabs),
            "float" => one(Float),
            "int" => one(Int),
            "floor" => one(Floor),
            "ceil" => one(Ceil),
            "trunc" => one(Trunc),
            "round" => (Round, 1, Some(2)),
            "degrees" => one(Degrees),
            "radians" => one(Radians),
            "atan2" => two(Atan2),
            "copysign" => two(Copysign),
            "fmod" => two(Fmod),
            "pow" => two(Pow),
            "hypot" => (Hypot, 0, None),
            "min" => (Min, 1, None),
            "max" => (Max, 1, None),
            _ => return None,
        })
    }

    pub const NAMES: &'static str = "sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, asinh, acosh, atanh, exp, expm1, log, log10, log1p, log2, sqrt, cbrt, abs, fabs, float, int, floor, ceil, trunc, round, degrees, radians, atan2, copysign, fmod, pow, hypot, min, max";
}

/// The math constants of a formula's namespace.
pub const CONSTANTS: [(&str, f64); 3] = [
    ("pi", std::f64::consts::PI),
    ("e", std::f64::consts::E),
    ("tau", std::f64::consts::TAU),
];

/// An arithmetic operator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    /// Python's `%` of reals: the sign of the divisor.
    Mod,
    /// Python's `//` of reals: the floor of the quotient, as divmod gives it.
    FloorDiv,
}

/// A comparison of reals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cmp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

/// The expression tree. Python's booleans are the reals 1 and 0 here, as
/// they are in Python's arithmetic (`(INST > 1.) * 2.` is 2 or 0), and
/// a real is true when it is not 0.
#[derive(Debug, Clone, PartialEq)]
pub enum Node {
    Num(f64),
    /// The parameter of this index in NOM_PARA.
    Param(usize),
    Neg(Box<Node>),
    Bin(Op, Box<Node>, Box<Node>),
    Call(Func, Vec<Node>),
    /// A call of the function of this index in `Formula::callees`: a
    /// DEFI_FONCTION or another FORMULE passed to FORMULE as a keyword
    /// (`FORMULE(VALE='GAM(INST) * Z', GAM=GAM, ...)`).
    Apply(usize, Vec<Node>),
    /// `a < b <= c`: each operand evaluated once, stopping at the first
    /// false link, as Python does.
    Compare(Box<Node>, Vec<(Cmp, Node)>),
    /// `then if cond else orelse`: only the branch taken is evaluated.
    IfElse(Box<Node>, Box<Node>, Box<Node>),
    /// `a and b`: a when a is false, else b (Python gives an operand).
    And(Box<Node>, Box<Node>),
    /// `a or b`: a when a is true, else b.
    Or(Box<Node>, Box<Node>),
    Not(Box<Node>),
}

/// A FORMULE.
#[derive(Debug, Clone, PartialEq)]
pub struct Formula {
    /// NOM_PARA, in order.
    pub params: Vec<String>,
    /// VALE as written.
    pub text: String,
    pub node: Node,
    /// The functions VALE calls, by the name it calls them: copies of the
    /// concepts as they were when FORMULE ran, as Python's closure would
    /// see them (a DETRUIRE later does not reach them).
    pub callees: Vec<(String, Coef)>,
}

impl Formula {
    /// The value for the given (parameter, value) pairs; every parameter
    /// of NOM_PARA must be among them.
    pub fn eval(&self, values: &[(&str, f64)]) -> Result<f64, String> {
        let mut args = Vec::with_capacity(self.params.len());
        for p in &self.params {
            match values.iter().find(|(n, _)| n == p) {
                Some(&(_, v)) => args.push(v),
                None => {
                    let given: Vec<&str> = values.iter().map(|v| v.0).collect();
                    return Err(format!(
                        "the formula '{}' needs {p}, which is not among the parameters given here ({})",
                        self.text,
                        given.join(", ")
                    ));
                }
            }
        }
        self.eval_positional(&args)
    }

    /// The value for the parameters in NOM_PARA's order (a call of this
    /// formula from another one).
    pub fn eval_positional(&self, args: &[f64]) -> Result<f64, String> {
        let v = self.value(&self.node, args)?;
        if v.is_finite() {
            Ok(v)
        } else {
            let at: Vec<String> = self
                .params
                .iter()
                .zip(args)
                .map(|(n, x)| format!("{n} = {x:e}"))
                .collect();
            Err(format!(
                "the formula '{}' is not finite at {}",
                self.text,
                at.join(", ")
            ))
        }
    }

    fn value(&self, n: &Node, args: &[f64]) -> Result<f64, String> {
        Ok(match n {
            Node::Num(x) => *x,
            Node::Param(i) => args[*i],
            Node::Neg(a) => -self.value(a, args)?,
            Node::Bin(op, a, b) => {
                let (a, b) = (self.value(a, args)?, self.value(b, args)?);
                match op {
                    Op::Add => a + b,
                    Op::Sub => a - b,
                    Op::Mul => a * b,
                    Op::Div => {
                        if b == 0.0 {
                            return Err(format!("division by zero in the formula '{}'", self.text));
                        }
                        a / b
                    }
                    Op::Pow => a.powf(b),
                    Op::Mod | Op::FloorDiv => {
                        if b == 0.0 {
                            return Err(format!("division by zero in the formula '{}'", self.text));
                        }
                        let (div, rem) = py_divmod(a, b);
                        if *op == Op::Mod {
                            rem
                        } else {
                            div
                        }
                    }
                }
            }
            Node::Compare(first, rest) => {
                let mut a = self.value(first, args)?;
                let mut holds = true;
                for (cmp, node) in rest {
                    let b = self.value(node, args)?;
                    holds = match cmp {
                        Cmp::Eq => a == b,
                        Cmp::Ne => a != b,
                        Cmp::Lt => a < b,
                        Cmp::Le => a <= b,
                        Cmp::Gt => a > b,
                        Cmp::Ge => a >= b,
                    };
                    if !holds {
                        break;
                    }
                    a = b;
                }
                f64::from(u8::from(holds))
            }
            Node::IfElse(cond, then, orelse) => {
                if self.value(cond, args)? != 0.0 {
                    self.value(then, args)?
                } else {
                    self.value(orelse, args)?
                }
            }
            Node::And(a, b) => {
                let a = self.value(a, args)?;
                if a == 0.0 {
                    a
                } else {
                    self.value(b, args)?
                }
            }
            Node::Or(a, b) => {
                let a = self.value(a, args)?;
                if a != 0.0 {
                    a
                } else {
                    self.value(b, args)?
                }
            }
            Node::Not(a) => f64::from(u8::from(self.value(a, args)? == 0.0)),
            Node::Call(f, xs) => {
                let xs: Vec<f64> = xs
                    .iter()
                    .map(|x| self.value(x, args))
                    .collect::<Result<_, _>>()?;
                // hypot() of nothing is 0.
                let x = xs.first().copied().unwrap_or(0.0);
                match f {
                    Func::Sin => x.sin(),
                    Func::Cos => x.cos(),
                    Func::Tan => x.tan(),
                    Func::Asin => x.asin(),
                    Func::Acos => x.acos(),
                    Func::Atan => x.atan(),
                    Func::Sinh => x.sinh(),
                    Func::Cosh => x.cosh(),
                    Func::Tanh => x.tanh(),
                    Func::Exp => x.exp(),
                    Func::Log => match xs.get(1) {
                        None => x.ln(),
                        Some(base) => x.ln() / base.ln(),
                    },
                    Func::Log10 => x.log10(),
                    Func::Sqrt => x.sqrt(),
                    Func::Abs => x.abs(),
                    Func::Float => x,
                    Func::Atan2 => x.atan2(xs[1]),
                    Func::Min => xs.iter().copied().fold(f64::INFINITY, f64::min),
                    Func::Max => xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                    Func::Asinh => x.asinh(),
                    Func::Acosh => x.acosh(),
                    Func::Atanh => x.atanh(),
                    Func::Expm1 => x.exp_m1(),
                    Func::Log1p => x.ln_1p(),
                    Func::Log2 => x.log2(),
                    Func::Fabs => x.abs(),
                    Func::Floor => x.floor(),
                    Func::Ceil => x.ceil(),
                    Func::Trunc | Func::Int => x.trunc(),
                    Func::Degrees => x.to_degrees(),
                    Func::Radians => x.to_radians(),
                    Func::Cbrt => x.cbrt(),
                    Func::Copysign => x.copysign(xs[1]),
                    Func::Fmod => {
                        if xs[1] == 0.0 {
                            f64::NAN
                        } else {
                            x % xs[1]
                        }
                    }
                    Func::Hypot => xs.iter().fold(0.0, |h: f64, y| h.hypot(*y)),
                    Func::Pow => x.powf(xs[1]),
                    Func::Round => match xs.get(1) {
                        None => x.round_ties_even(),
                        Some(&n) => py_round(x, n),
                    },
                }
            }
            Node::Apply(i, xs) => {
                let xs: Vec<f64> = xs
                    .iter()
                    .map(|x| self.value(x, args))
                    .collect::<Result<_, _>>()?;
                let (name, f) = &self.callees[*i];
                let v = match f {
                    Coef::Function(f) => f.eval(xs[0]),
                    Coef::Formula(g) => g.eval_positional(&xs),
                };
                v.map_err(|e| format!("{name}, called by the formula '{}': {e}", self.text))?
            }
        })
    }
}

/// Python's divmod of reals (CPython's float_divmod): the remainder has
/// the divisor's sign and the quotient is the floor the remainder implies,
/// so that `7. // 0.1` is 69 (not the floor of 7/0.1 = 70), to the last
/// bit and the signs of zeros; the command file's `//` and `%` use it too.
pub fn py_divmod(a: f64, b: f64) -> (f64, f64) {
    let mut rem = a % b;
    let mut div = (a - rem) / b;
    if rem != 0.0 {
        if (b < 0.0) != (rem < 0.0) {
            rem += b;
            div -= 1.0;
        }
    } else {
        rem = 0.0f64.copysign(b);
    }
    let floordiv = if div != 0.0 {
        let f = div.floor();
        if div - f > 0.5 {
            f + 1.0
        } else {
            f
        }
    } else {
        0.0f64.copysign(a / b)
    };
    (floordiv, rem)
}

/// Python's `round(x, n)` of a real: the exact binary value rounded to n
/// decimals, ties to even (what Rust's fixed-point formatting does; n < 0
/// rounds to tens, hundreds...). A non-integral n is refused as Python
/// refuses it.
fn py_round(x: f64, n: f64) -> f64 {
    if n.fract() != 0.0 || !x.is_finite() {
        return f64::NAN;
    }
    if n >= 0.0 {
        let digits = n.min(400.0) as usize;
        format!("{x:.digits$}").parse().unwrap_or(f64::NAN)
    } else {
        let scale = 10f64.powf(-n);
        (x / scale).round_ties_even() * scale
    }
}

/// A function-valued argument: a tabulated or constant function (one
/// parameter), or a FORMULE (evaluated by parameter name). LIAISON_UNIL's
/// COEF_IMPO/COEF_MULT and AFFE_CHAR_MECA_F's values are of this kind.
#[derive(Debug, Clone, PartialEq)]
pub enum Coef {
    Function(super::function::Function),
    Formula(Formula),
}

impl From<super::function::Function> for Coef {
    fn from(f: super::function::Function) -> Coef {
        Coef::Function(f)
    }
}

/// The parameters a value given at a node may depend on: the instant and
/// the node's initial coordinates (code_aster's convention for COEF_IMPO
/// and AFFE_CHAR_MECA_F; TOUTPARA is DEFI_CONSTANTE's).
pub const NODE_PARAMS: [&str; 4] = ["INST", "X", "Y", "Z"];

impl Coef {
    /// The value at instant `t` of a time multiplier (EXCIT FONC_MULT): a
    /// function of INST, a constant, or a formula whose only parameter is
    /// INST (what [`Coef::unknown_param`] with `["INST"]` checked), so that
    /// a ramp may be written `FORMULE(VALE='min(INST / T1, 1.)', ...)`
    /// as code_aster allows.
    pub fn eval(&self, t: f64) -> Result<f64, String> {
        match self {
            Coef::Function(f) => f.eval(t),
            Coef::Formula(g) => g.eval(&[("INST", t)]),
        }
    }

    /// Whether the value may change with the parameter `name` (a
    /// function of it, or a formula that takes it): a constant or a
    /// function of another parameter does not.
    pub fn depends_on(&self, name: &str) -> bool {
        match self {
            Coef::Function(f) => f.para == name,
            Coef::Formula(g) => g.params.iter().any(|p| p == name),
        }
    }

    /// The name of the concept's type in messages.
    pub fn type_name(&self) -> &'static str {
        match self {
            Coef::Function(_) => "function",
            Coef::Formula(_) => "formula",
        }
    }

    /// How many arguments a call takes: one for a tabulated or constant
    /// function, NOM_PARA's count for a formula.
    pub fn arity(&self) -> usize {
        match self {
            Coef::Function(_) => 1,
            Coef::Formula(g) => g.params.len(),
        }
    }

    /// The first parameter of the function that is not among `allowed`
    /// (TOUTPARA, a constant's, always is).
    pub fn unknown_param(&self, allowed: &[&str]) -> Option<String> {
        match self {
            Coef::Function(f) => (f.para != "TOUTPARA" && !allowed.contains(&f.para.as_str()))
                .then(|| f.para.clone()),
            Coef::Formula(g) => g
                .params
                .iter()
                .find(|p| !allowed.contains(&p.as_str()))
                .cloned(),
        }
    }
}

/// `f` at instant `inst` and initial coordinates `x`; `what` names the
/// keyword in the message when the function depends on another parameter.
pub fn eval_inst_xyz(f: &Coef, inst: f64, x: [f64; 3], what: &str) -> Result<f64, String> {
    let f = match f {
        Coef::Function(f) => f,
        Coef::Formula(g) => {
            return g.eval(&[("INST", inst), ("X", x[0]), ("Y", x[1]), ("Z", x[2])])
        }
    };
    let v = match f.para.as_str() {
        "TOUTPARA" | "INST" => inst,
        "X" => x[0],
        "Y" => x[1],
        "Z" => x[2],
        other => {
            return Err(format!(
            "{what} is evaluated with INST, X, Y, Z; the function of {other} cannot be evaluated"
        ))
        }
    };
    f.eval(v)
}
