//! Linear algebra over a field, with no square root: what the solver needs from matrices that
//! nalgebra's `ComplexField` decompositions cannot give an exact rational type.
//!
//! [`ldlt`]: the pivoted LDLᵀ factorization of a symmetric positive semidefinite matrix, its
//! rank, determinant, solves and null space — exact in rationals, stable in floats.
//! [`gauss`]: Gauss–Jordan elimination of general systems — solution sets and null spaces.
//! [`lcp`]: linear complementarity problems and Lemke's method, for the unilateral laws.

pub mod gauss;
pub mod lcp;
pub mod ldlt;

pub use gauss::{Solutions, null_space, solve_general};
pub use ldlt::*;
