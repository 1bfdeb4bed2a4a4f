//! Finite elements: reference shape functions ([`shape`]), Gauss rules
//! ([`quadrature`]) and the mechanical formulations built on them.
//!
//! The reference data follow code_aster (node coordinates of `elrfno`,
//! Gauss families of `elraga`) so that per-Gauss-point results can be
//! compared with code_aster listings point by point.

pub mod axis;
pub mod quadrature;
pub mod shape;
