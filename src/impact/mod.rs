//! The impact itself: the problem, the restitution laws and the solve of the simultaneous
//! collision (§2–4, §6, §9–11).
//!
//! [`problem`]: the validated input — body, twist before impact, contacts, constraints ·
//! [`restitution`]: Newton's and Poisson's laws (eq. 14–15, 20–23) · [`solve`](mod@solve): the
//! assembled collision — frames, inertances G, its factorization and Δ — and one law solved on
//! it, in the hatted form the solver works in · [`gram_schmidt`]: the contact wrenches
//! orthogonalised in the metric of the mobility, from which float solves take the twist and
//! the energies, accurate however nearly singular G is · [`route`]: which of the two a float
//! solve takes, by a bound on G's conditioning · [`outputs`]: which outputs a solve computes,
//! the rest not built · [`solution`]: the outcome in the paper's units,
//! and the one-call [`solution::solve`] · [`unilateral`]: the laws in inequality form, as
//! complementarity problems, for when the simultaneous hypothesis fails · [`admissibility`]:
//! whether a simultaneous answer is physical (tensile, separating, still approaching, energy
//! gain) · [`friction`]: Coulomb friction (§14), the impact integrated in impulse space —
//! exactly, event by event, for planar scenes; adaptively in floats for spatial ones ·
//! [`multiple`]: multiple-impact laws (LZB), each contact's compression and expansion
//! integrated in impulse space.

pub mod admissibility;
pub mod batch;
pub mod friction;
pub mod gram_schmidt;
pub mod lean;
pub mod lean_system;
pub mod mechanism;
pub mod multiple;
pub mod outputs;
pub mod problem;
pub mod restitution;
pub mod route;
pub mod solution;
pub mod solve;
pub mod system;
pub mod unilateral;
