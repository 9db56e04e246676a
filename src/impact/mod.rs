//! The impact itself: the restitution laws and the solve of the simultaneous collision
//! (§2–4, §6, §9–11).
//!
//! [`restitution`]: Newton's and Poisson's laws (eq. 14–15, 20–23) · [`solve`]: the
//! assembled collision — frames, inertances G, its factorization and Δ — and one law solved on
//! it, in the hatted form the solver works in.

pub mod restitution;
pub mod solve;
