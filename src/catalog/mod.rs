//! The catalogue language (schema), checked arguments and the checker.

pub mod absent;
pub mod args;
pub mod checker;
pub mod concept_type;
pub mod doc;
pub mod eval;
pub mod inline_commands;
pub mod schema;
