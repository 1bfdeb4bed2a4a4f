//! Checked arguments: what an executor receives.
//!
//! After the checker has run, every keyword present is known to the
//! catalogue, has the right type, count and allowed value, and defaults are
//! filled in. Executors read values through the typed accessors below and
//! never see the syntax tree; [`Args::error`] builds a diagnostic that
//! points at the keyword in the source.

use indexmap::IndexMap;

use crate::catalog::concept_type::ConceptType;
use crate::diag::{Diagnostic, Span};

/// One checked value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Int(i64),
    Real(f64),
    Text(String),
    Concept { name: String, ty: ConceptType },
}

impl Value {
    pub fn as_real(&self) -> Option<f64> {
        match self {
            Value::Real(r) => Some(*r),
            Value::Int(i) => Some(*i as f64),
            _ => None,
        }
    }
    pub fn as_int(&self) -> Option<i64> {
        match self {
            Value::Int(i) => Some(*i),
            _ => None,
        }
    }
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Value::Text(s) => Some(s),
            _ => None,
        }
    }
    pub fn as_concept(&self) -> Option<&str> {
        match self {
            Value::Concept { name, .. } => Some(name),
            _ => None,
        }
    }
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Value::Int(i) => write!(f, "{i}"),
            Value::Real(r) => write!(f, "{r:?}"),
            Value::Text(s) => write!(f, "'{s}'"),
            Value::Concept { name, .. } => f.write_str(name),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum EntryData {
    Simple(Vec<Value>),
    Factor(Vec<Args>),
}

/// One keyword present at a level, given by the user or defaulted.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// The span of `KEY=value` in the source (of the command call when the
    /// keyword was defaulted).
    pub span: Span,
    pub defaulted: bool,
    pub data: EntryData,
}

/// The checked keywords of one level: a command or one occurrence of a
/// factor keyword.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Args {
    /// The command name, e.g. `DYNA_NON_LINE`.
    pub command: String,
    /// The keyword path of this level inside the command, e.g.
    /// `SCHEMA_TEMPS` (empty at the top level).
    pub path: String,
    /// Span of the whole level (`_F(...)` or the call).
    pub span: Span,
    pub entries: IndexMap<String, Entry>,
    /// `reuse=NAME` at the top level: the concept the command modifies in
    /// place. A command whose result name is already bound without it
    /// makes a new concept (Python rebinds the name), so an executor must
    /// not read the old concept of that name as its own.
    pub reuse: Option<String>,
}

impl Args {
    pub fn new(command: impl Into<String>, path: impl Into<String>, span: Span) -> Self {
        Args {
            command: command.into(),
            path: path.into(),
            span,
            entries: IndexMap::new(),
            reuse: None,
        }
    }

    pub fn get(&self, key: &str) -> Option<&Entry> {
        self.entries.get(key)
    }
    pub fn has(&self, key: &str) -> bool {
        self.entries.contains_key(key)
    }
    /// True if the user wrote the keyword (not filled by a default).
    pub fn given(&self, key: &str) -> bool {
        self.entries.get(key).is_some_and(|e| !e.defaulted)
    }

    /// The values of a simple keyword (empty if absent).
    pub fn values(&self, key: &str) -> &[Value] {
        match self.entries.get(key).map(|e| &e.data) {
            Some(EntryData::Simple(v)) => v,
            _ => &[],
        }
    }
    pub fn real(&self, key: &str) -> Option<f64> {
        self.values(key).first().and_then(Value::as_real)
    }
    pub fn int(&self, key: &str) -> Option<i64> {
        self.values(key).first().and_then(Value::as_int)
    }
    pub fn text(&self, key: &str) -> Option<&str> {
        self.values(key).first().and_then(Value::as_text)
    }
    pub fn concept(&self, key: &str) -> Option<&str> {
        self.values(key).first().and_then(Value::as_concept)
    }
    pub fn reals(&self, key: &str) -> Vec<f64> {
        self.values(key).iter().filter_map(Value::as_real).collect()
    }
    pub fn ints(&self, key: &str) -> Vec<i64> {
        self.values(key).iter().filter_map(Value::as_int).collect()
    }
    pub fn texts(&self, key: &str) -> Vec<&str> {
        self.values(key).iter().filter_map(Value::as_text).collect()
    }
    pub fn concepts(&self, key: &str) -> Vec<&str> {
        self.values(key)
            .iter()
            .filter_map(Value::as_concept)
            .collect()
    }
    /// All occurrences of a factor keyword (empty if absent).
    pub fn facts(&self, key: &str) -> &[Args] {
        match self.entries.get(key).map(|e| &e.data) {
            Some(EntryData::Factor(v)) => v,
            _ => &[],
        }
    }
    /// The first occurrence of a factor keyword.
    pub fn fact(&self, key: &str) -> Option<&Args> {
        self.facts(key).first()
    }

    /// Span of a keyword, or of this level if it is absent.
    pub fn span_of(&self, key: &str) -> Span {
        self.entries.get(key).map(|e| e.span).unwrap_or(self.span)
    }

    /// The keyword path of `key` at this level, e.g. `SCHEMA_TEMPS/ALPHA`.
    pub fn key_path(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else if key.is_empty() {
            self.path.clone()
        } else {
            format!("{}/{}", self.path, key)
        }
    }

    /// A diagnostic about `key` (pass "" for the level itself), pointing at
    /// it in the source and naming the command and keyword path.
    pub fn error(&self, key: &str, message: impl Into<String>) -> Diagnostic {
        let d = Diagnostic::error(message)
            .at(self.span_of(key))
            .in_command(self.command.clone());
        let p = self.key_path(key);
        if p.is_empty() {
            d
        } else {
            d.keyword(p)
        }
    }

    /// "not implemented yet: COMMAND/KEYWORD", for parts of a command whose
    /// engine does not exist yet; never a silent success.
    pub fn not_implemented(&self, key: &str, what: &str) -> Diagnostic {
        let p = self.key_path(key);
        let full = if p.is_empty() {
            self.command.clone()
        } else {
            format!("{}/{}", self.command, p)
        };
        Diagnostic::error(format!(
            "not implemented yet: {full}{}",
            if what.is_empty() {
                String::new()
            } else {
                format!(" ({what})")
            }
        ))
        .at(self.span_of(key))
    }
}
