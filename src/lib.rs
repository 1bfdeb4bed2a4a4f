//! aster: a Rust reimplementation of the part of code_aster that runs
//! nonlinear dynamic impact studies (the SDNV103 Taylor bar family).
//!
//! Layers, from the bottom (docs/engine.md, enforced by tests/layering.rs):
//! data ([`mesh`], [`model`], [`result`], [`post`], [`diag`], [`profile`], [`interrupt`]), the
//! engine ([`law`], [`element`], [`contact`], [`solver`], [`time`],
//! [`nonlinear`]), language and files ([`lang`], [`catalog`],
//! [`concepts`], [`medio`], [`study`]), [`commands`] (one file
//! per command: declaration and executor) and the drivers ([`run`],
//! [`bench`], [`sweep`], [`plot`]). A module uses its own layer and those below.

// Diagnostics are large by design (they carry spans, choices and notes)
// and only travel on the error path.
#![allow(clippy::result_large_err)]
// Numerical kernels index several arrays with one loop variable; iterator
// chains would hide the mathematics.
#![allow(clippy::needless_range_loop)]

pub mod bench;
pub mod catalog;
pub mod commands;
pub mod concepts;
pub mod contact;
pub mod diag;
pub mod element;
pub mod interrupt;
pub mod lang;
pub mod law;
pub mod medio;
pub mod mesh;
pub mod model;
pub mod nonlinear;
pub mod plot;
pub mod post;
pub mod profile;
pub mod result;
pub mod run;
pub mod solver;
pub mod study;
pub mod sweep;
pub mod time;
