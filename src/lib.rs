//! # inertance
//!
//! The simultaneous frictionless collision of a rigid body at N points, after Dragna, Pandrea
//! and Stănescu, *Simultaneous Collision of the Rigid Body at Two Points*, Symmetry 13 (2021)
//! 1924 — "the paper"; equation numbers in the docs are the paper's.
//!
//! ## Notation (used everywhere)
//!
//! * Cxyz: central principal axes of the body; m, J = diag(J_x, J_y, J_z).
//! * Twist {v} = [ω; v_C]; axis screw {E} = [u; r × u] (eq. 3–4); η = [[0, I], [I, 0]] (eq. 5)
//!   and the mixed product {a}ᵀ η {b} (eq. 6).
//! * \[M\] = [[0, m I], [J, 0]] and \[M\]⁻¹ = [[0, J⁻¹], [m⁻¹ I, 0]] (eq. 9).
//! * Inertances g_ij,ab = {E_ia}ᵀ η \[M\]⁻¹ {E_jb} (eq. 12); G = \[g_ij,xx\]; Δ = det G.
//! * P_i: the impulse at A_i, acting along −x_i (x_i is the outward normal, eq. 10).
//!
//! ## Modules, one idea each
//!
//! [`scalar`] (the field a solve runs in) · [`number::expr`] (the one expression grammar) ·
//! [`number`] (exact numbers as written) ·
//! [`linalg`] (field-only LDLᵀ) · [`mechanics::screw`] (Plücker coordinates) ·
//! [`mechanics::body`] (mass matrix, mobility) · [`mechanics::contact`] (contact frames, §12) ·
//! [`impact::restitution`] (Newton, Poisson) · [`impact::solve`] (the collision) ·
//! [`mechanics::constraint`] (ideal constraints, §9–11) · [`mechanics::surface`] (implicit
//! surfaces, §12) · [`analysis`] and [`tools::analyze`] (degenerate cases, §8) · [`scene`] (TOML
//! scenes) · [`report`] (tables and JSON) · [`tools::check`] (the paper's worked examples,
//! checked) · [`scalar::symbolic`] and [`tools::derive`] (closed forms
//! derived by the same solver over rational functions).

#![deny(missing_docs)]
// Index loops over i, j read like the paper's sums (g_ij, Σ_j P_j g_ij); keep them.
#![allow(clippy::needless_range_loop)]

pub mod number;
pub mod scalar;
pub mod linalg;
pub mod mechanics;
pub mod impact;
pub mod analysis;
pub mod report;
pub mod scene;
pub mod tools;
