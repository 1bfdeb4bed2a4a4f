//! Finite elements: reference shape functions ([`shape`]), Gauss rules
//! ([`quadrature`]), the element catalogue ([`spec`]) and the mechanical
//! formulations built on them ([`mechanics`], the engine's entry point;
//! [`axis`], the earlier small-strain axisymmetric QUAD8).
//!
//! The reference data follow code_aster (node coordinates of `elrfno`,
//! Gauss families of `elraga`) so that per-Gauss-point results can be
//! compared with code_aster listings point by point.

pub mod axis;
pub mod body_force;
pub mod distributed;
pub mod fold;
pub mod hexs8;
pub mod mechanics;
pub mod pressure;
pub mod strain;

pub use mechanics::{
    check_initial_geometry, initial_states, internal_forces, internal_forces_into,
    internal_forces_to, mass, output_points, rigi_points, BadPoint, ElementBuffers, ElementFailure,
    ElementResponse, Kinematics, LawRef, PointState, MAX_DOFS,
};
