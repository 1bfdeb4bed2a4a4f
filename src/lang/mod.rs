//! The command language: grammar, syntax tree, parser.

pub mod ast;
pub mod parser;
