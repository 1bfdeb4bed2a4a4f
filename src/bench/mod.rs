//! The benchmark harness (`aster bench`): runs a study several times with
//! the profiler of [`crate::profile`] on and reports phases, counts and
//! memory as a table and as JSON.

pub mod harness;
pub mod json;
