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
}

impl Func {
    /// The function of a name, and its number of arguments (None: one or
    /// more).
    pub fn of_name(name: &str) -> Option<(Func, Option<usize>)> {
        use Func::*;
        Some(match name {
            "sin" => (Sin, Some(1)),
            "cos" => (Cos, Some(1)),
            "tan" => (Tan, Some(1)),
            "asin" => (Asin, Some(1)),
            "acos" => (Acos, Some(1)),
            "atan" => (Atan, Some(1)),
            "sinh" => (Sinh, Some(1)),
            "cosh" => (Cosh, Some(1)),
            "tanh" => (Tanh, Some(1)),
            "exp" => (Exp, Some(1)),
            "log" => (Log, Some(1)),
            "log10" => (Log10, Some(1)),
            "sqrt" => (Sqrt, Some(1)),
            "abs" => (Abs, Some(1)),
            "float" => (Float, Some(1)),
            "atan2" => (Atan2, Some(2)),
            "min" => (Min, None),
            "max" => (Max, None),
            _ => return None,
        })
    }

    pub const NAMES: &'static str =
        "sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, exp, log, log10, sqrt, abs, float, atan2, min, max";
}

/// The math constants of a formula's namespace.
pub const CONSTANTS: [(&str, f64); 2] = [("pi", std::f64::consts::PI), ("e", std::f64::consts::E)];

/// An arithmetic operator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

/// The expression tree.
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
                }
            }
            Node::Call(f, xs) => {
                let xs: Vec<f64> = xs
                    .iter()
                    .map(|x| self.value(x, args))
                    .collect::<Result<_, _>>()?;
                let x = xs[0];
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
                    Func::Log => x.ln(),
                    Func::Log10 => x.log10(),
                    Func::Sqrt => x.sqrt(),
                    Func::Abs => x.abs(),
                    Func::Float => x,
                    Func::Atan2 => x.atan2(xs[1]),
                    Func::Min => xs.iter().copied().fold(f64::INFINITY, f64::min),
                    Func::Max => xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
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
