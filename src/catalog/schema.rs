//! The keyword schema: how a command's syntax is declared, as data.
//!
//! This mirrors code_aster's catalogue language (SIMP, FACT, BLOC and the
//! rules UN_PARMI, AU_MOINS_UN, EXCLUS, ENSEMBLE, PRESENT_PRESENT,
//! PRESENT_ABSENT) so that each command declaration reads like its
//! code_aster catalogue. The checker in [`super::checker`] interprets it.

use crate::catalog::concept_type::ConceptType;

/// The type of a simple keyword's values.
#[derive(Debug, Clone, PartialEq)]
pub enum Ty {
    /// `'R'`: a real; integers are accepted and converted.
    Real,
    /// `'I'`: an integer; a real with an integral value is accepted.
    Int,
    /// `'TXM'`: a text (also group names, component names).
    Text,
    /// A concept of one of the listed types.
    Concept(Vec<ConceptType>),
}

impl Ty {
    pub fn describe(&self) -> String {
        match self {
            Ty::Real => "a real".into(),
            Ty::Int => "an integer".into(),
            Ty::Text => "a text".into(),
            Ty::Concept(tys) => {
                let names: Vec<&str> = tys.iter().map(|t| t.aster_name()).collect();
                format!("a concept of type {}", names.join(" or "))
            }
        }
    }
}

/// A literal used for defaults, `into` lists and block conditions.
#[derive(Debug, Clone, PartialEq)]
pub enum Lit {
    Int(i64),
    Real(f64),
    Text(&'static str),
}

/// `statut` of a keyword.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// 'o': compulsory.
    Required,
    /// 'f': optional, absent when not given.
    Optional,
    /// 'd': filled with its default when absent. For a factor keyword, one
    /// occurrence filled with its own defaults is created.
    Defaulted,
    /// 'c': hidden (accepted, not documented).
    Hidden,
}

/// A simple keyword (SIMP).
/// The `not_built` entry of a keyword refused whatever its value.
const ANY_VALUE: &str = "*";

#[derive(Debug, Clone)]
pub struct Simple {
    pub name: &'static str,
    pub ty: Ty,
    pub status: Status,
    /// Default values (when `status` is Defaulted).
    pub default: Vec<Lit>,
    /// Closed list of allowed values.
    pub into: Option<Vec<Lit>>,
    /// Values of `into` that code_aster has and aster does not build, with
    /// what aster builds instead: refused when the file is checked, so a
    /// study stops before its first command rather than at the one that
    /// would use them (probes of 2026-11-28 on code_aster's test files).
    pub not_built: Vec<&'static str>,
    pub not_built_why: &'static str,
    pub val_min: Option<f64>,
    pub val_max: Option<f64>,
    /// Minimum and maximum number of values (`max = None` is `'**'`).
    pub min: usize,
    pub max: Option<usize>,
    pub doc: &'static str,
}

/// A factor keyword (FACT), taking `_F(...)` occurrences.
#[derive(Debug, Clone)]
pub struct Factor {
    pub name: &'static str,
    pub status: Status,
    /// Maximum number of occurrences (`None` is `'**'`).
    pub max: Option<usize>,
    pub min: usize,
    pub keywords: Vec<Keyword>,
    pub rules: Vec<Rule>,
    pub doc: &'static str,
}

/// A conditional block (BLOC): its keywords exist only when the condition
/// holds on the keywords of the same level (after defaults are filled).
#[derive(Debug, Clone)]
pub struct Block {
    pub name: &'static str,
    pub condition: Cond,
    pub keywords: Vec<Keyword>,
    pub rules: Vec<Rule>,
}

#[derive(Debug, Clone)]
pub enum Keyword {
    Simple(Simple),
    Factor(Factor),
    Block(Block),
}

impl Keyword {
    pub fn name(&self) -> &'static str {
        match self {
            Keyword::Simple(s) => s.name,
            Keyword::Factor(f) => f.name,
            Keyword::Block(b) => b.name,
        }
    }
}

/// Conditions of blocks, on the keywords of the enclosing level.
#[derive(Debug, Clone)]
pub enum Cond {
    /// The keyword's (first) value equals the literal.
    Eq(&'static str, Lit),
    /// The keyword's (first) value is one of the literals.
    In(&'static str, Vec<Lit>),
    Present(&'static str),
    Absent(&'static str),
    And(Vec<Cond>),
    Or(Vec<Cond>),
    Not(Box<Cond>),
}

/// Rules between keywords of one level (code_aster's `regles`).
#[derive(Debug, Clone)]
pub enum Rule {
    /// UN_PARMI: exactly one of.
    ExactlyOne(Vec<&'static str>),
    /// AU_MOINS_UN: at least one of.
    AtLeastOne(Vec<&'static str>),
    /// EXCLUS: at most one of.
    Exclusive(Vec<&'static str>),
    /// ENSEMBLE: all or none.
    Together(Vec<&'static str>),
    /// PRESENT_PRESENT(a, b...): if the first is present, all others must be.
    IfPresentAllPresent(&'static str, Vec<&'static str>),
    /// PRESENT_ABSENT(a, b...): if the first is present, the others must be absent.
    IfPresentAllAbsent(&'static str, Vec<&'static str>),
}

/// Whether `reuse=` is allowed and which keyword names the reused object.
#[derive(Debug, Clone, PartialEq)]
pub enum Reentrant {
    /// 'n': no reuse.
    No,
    /// 'f:KEY': reuse optional; if given, it must be the concept under KEY.
    Optional(&'static str),
    /// 'o:KEY': reuse compulsory, on the concept under KEY.
    Required(&'static str),
}

/// What a command produces.
#[derive(Debug, Clone, PartialEq)]
pub enum Produces {
    /// A procedure: no result (DEBUT, FIN, TEST_RESU, IMPR_*...).
    Nothing,
    Concept(ConceptType),
    /// The type of the concept given in a keyword of the command's top
    /// level (code_aster's sd_prod returning the type of RESULTAT), or the
    /// first type when that keyword holds no concept of a listed type.
    SameAs(&'static str, ConceptType),
    /// The type chosen by the value of a text keyword of the top level:
    /// the first (prefix, type) whose prefix starts the value, else the
    /// default (code_aster's CREA_CHAMP: TYPE_CHAM='ELGA_SIEF_R' makes a
    /// cham_elem, 'NOEU_DEPL_R' a cham_no_sdaster).
    ByText(
        &'static str,
        &'static [(&'static str, ConceptType)],
        ConceptType,
    ),
}

/// The declaration of one command.
#[derive(Debug, Clone)]
pub struct CommandSpec {
    pub name: &'static str,
    pub doc: &'static str,
    pub produces: Produces,
    pub reentrant: Reentrant,
    pub keywords: Vec<Keyword>,
    pub rules: Vec<Rule>,
    /// The concepts named in its keywords no longer exist after it
    /// (DETRUIRE): the checker forgets them, so that a later use of the
    /// name is an error before anything runs.
    pub destroys: bool,
    /// code_aster's `compat_syntax` hook: rewrites the keywords as given
    /// (an older syntax into the current one) before they are checked, and
    /// returns the errors of a malformed older form.
    pub compat: Option<CompatFn>,
}

/// See [`CommandSpec::compat`].
pub type CompatFn = fn(
    &mut Vec<(crate::lang::ast::Ident, crate::catalog::eval::SpVal)>,
) -> Vec<crate::diag::Diagnostic>;

// ---------------------------------------------------------------------------
// Builders: terse constructors so declarations read like the catalogue.

/// A simple keyword, optional, one value.
pub fn simp(name: &'static str, ty: Ty) -> Simple {
    Simple {
        name,
        ty,
        status: Status::Optional,
        default: Vec::new(),
        into: None,
        not_built: Vec::new(),
        not_built_why: "",
        val_min: None,
        val_max: None,
        min: 1,
        max: Some(1),
        doc: "",
    }
}

pub fn real(name: &'static str) -> Simple {
    simp(name, Ty::Real)
}
pub fn int(name: &'static str) -> Simple {
    simp(name, Ty::Int)
}
pub fn text(name: &'static str) -> Simple {
    simp(name, Ty::Text)
}
pub fn concept(name: &'static str, tys: &[ConceptType]) -> Simple {
    simp(name, Ty::Concept(tys.to_vec()))
}

impl Simple {
    pub fn required(mut self) -> Self {
        self.status = Status::Required;
        self
    }
    pub fn hidden(mut self) -> Self {
        self.status = Status::Hidden;
        self
    }
    /// Default value (makes the keyword 'd').
    pub fn default(mut self, v: Lit) -> Self {
        self.status = Status::Defaulted;
        self.default = vec![v];
        self
    }
    pub fn defaults(mut self, v: Vec<Lit>) -> Self {
        self.status = Status::Defaulted;
        self.default = v;
        self
    }
    /// Closed list of texts.
    pub fn into(mut self, choices: &[&'static str]) -> Self {
        self.into = Some(choices.iter().map(|c| Lit::Text(c)).collect());
        self
    }
    /// Values of the closed list that aster does not build, and what it
    /// builds (for the message and the generated documentation).
    pub fn not_built(mut self, values: &[&'static str], why: &'static str) -> Self {
        self.not_built = values.to_vec();
        self.not_built_why = why;
        self
    }
    /// A keyword aster does not build whatever its value (a criterion or a
    /// frame that would change the answer if ignored): refused when the
    /// file is checked, like the values of [`Simple::not_built`].
    pub fn not_built_any(mut self, why: &'static str) -> Self {
        self.not_built = vec![ANY_VALUE];
        self.not_built_why = why;
        self
    }
    /// Whether the keyword is refused with any value.
    pub fn not_built_at_all(&self) -> bool {
        self.not_built == [ANY_VALUE]
    }
    pub fn into_ints(mut self, choices: &[i64]) -> Self {
        self.into = Some(choices.iter().map(|&c| Lit::Int(c)).collect());
        self
    }
    pub fn min_val(mut self, v: f64) -> Self {
        self.val_min = Some(v);
        self
    }
    pub fn max_val(mut self, v: f64) -> Self {
        self.val_max = Some(v);
        self
    }
    /// Any number of values (`max='**'`).
    pub fn many(mut self) -> Self {
        self.max = None;
        self
    }
    pub fn count(mut self, min: usize, max: usize) -> Self {
        self.min = min;
        self.max = Some(max);
        self
    }
    pub fn doc(mut self, d: &'static str) -> Self {
        self.doc = d;
        self
    }
    pub fn kw(self) -> Keyword {
        Keyword::Simple(self)
    }
}

/// A factor keyword, optional, at most one occurrence.
pub fn fact(name: &'static str, keywords: Vec<Keyword>) -> Factor {
    Factor {
        name,
        status: Status::Optional,
        max: Some(1),
        min: 1,
        keywords,
        rules: Vec::new(),
        doc: "",
    }
}

impl Factor {
    pub fn required(mut self) -> Self {
        self.status = Status::Required;
        self
    }
    /// 'd': one default occurrence when absent.
    pub fn defaulted(mut self) -> Self {
        self.status = Status::Defaulted;
        self
    }
    pub fn many(mut self) -> Self {
        self.max = None;
        self
    }
    pub fn max(mut self, n: usize) -> Self {
        self.max = Some(n);
        self
    }
    pub fn rules(mut self, rules: Vec<Rule>) -> Self {
        self.rules = rules;
        self
    }
    pub fn doc(mut self, d: &'static str) -> Self {
        self.doc = d;
        self
    }
    pub fn kw(self) -> Keyword {
        Keyword::Factor(self)
    }
}

pub fn block(name: &'static str, condition: Cond, keywords: Vec<Keyword>) -> Block {
    Block {
        name,
        condition,
        keywords,
        rules: Vec::new(),
    }
}

impl Block {
    pub fn rules(mut self, rules: Vec<Rule>) -> Self {
        self.rules = rules;
        self
    }
    pub fn kw(self) -> Keyword {
        Keyword::Block(self)
    }
}

impl AsRef<CommandSpec> for CommandSpec {
    fn as_ref(&self) -> &CommandSpec {
        self
    }
}

pub fn command(name: &'static str, produces: Produces, keywords: Vec<Keyword>) -> CommandSpec {
    CommandSpec {
        name,
        doc: "",
        produces,
        reentrant: Reentrant::No,
        keywords,
        rules: Vec::new(),
        destroys: false,
        compat: None,
    }
}

impl CommandSpec {
    /// Marks a command whose named concepts are gone after it.
    pub fn destroys(mut self) -> Self {
        self.destroys = true;
        self
    }
    pub fn doc(mut self, d: &'static str) -> Self {
        self.doc = d;
        self
    }
    pub fn compat(mut self, f: CompatFn) -> Self {
        self.compat = Some(f);
        self
    }
    pub fn reentrant(mut self, r: Reentrant) -> Self {
        self.reentrant = r;
        self
    }
    pub fn rules(mut self, rules: Vec<Rule>) -> Self {
        self.rules = rules;
        self
    }
}

/// Rule shorthands, named as in code_aster's catalogues.
pub fn un_parmi(k: &[&'static str]) -> Rule {
    Rule::ExactlyOne(k.to_vec())
}
pub fn au_moins_un(k: &[&'static str]) -> Rule {
    Rule::AtLeastOne(k.to_vec())
}
pub fn exclus(k: &[&'static str]) -> Rule {
    Rule::Exclusive(k.to_vec())
}
pub fn ensemble(k: &[&'static str]) -> Rule {
    Rule::Together(k.to_vec())
}
pub fn present_present(first: &'static str, others: &[&'static str]) -> Rule {
    Rule::IfPresentAllPresent(first, others.to_vec())
}
pub fn present_absent(first: &'static str, others: &[&'static str]) -> Rule {
    Rule::IfPresentAllAbsent(first, others.to_vec())
}
