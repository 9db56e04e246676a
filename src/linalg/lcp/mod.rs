//! Linear complementarity problems: find z with
//!
//! ```text
//! w = M z + q,   z ≥ 0,   w ≥ 0,   zᵀ w = 0          LCP(M, q)
//! ```
//!
//! the form every unilateral impact law takes (Moreau's Newton law, the two phases of Poisson's
//! in Pfeiffer–Glocker's form): z are the normal impulses, w how fast each contact separates
//! beyond what its law demands. The problem type is [`Lcp`]; the solver, [`lemke`], is written
//! once over the field, so it is exact in rationals and in the radical field and runs in floats
//! with pivot tolerances.
//!
//! **What is unique for a symmetric positive semidefinite M** (an inertance matrix G is one,
//! eq. 57–58). If z₁ and z₂ both solve LCP(M, q), then
//! (z₁ − z₂)ᵀ(w₁ − w₂) = −z₁ᵀw₂ − z₂ᵀw₁ ≤ 0, while (z₁ − z₂)ᵀ(w₁ − w₂) = (z₁ − z₂)ᵀM(z₁ − z₂) ≥ 0;
//! so (z₁ − z₂)ᵀM(z₁ − z₂) = 0, hence M(z₁ − z₂) = 0 (M is symmetric semidefinite) and
//! **w = Mz + q is the same for every solution**, while z may form a set when M is singular.
//! For M = G = Bᵀ W_η B this is the statement that the twist after impact is unique.
//!
//! **Existence.** Lemke's method with a lexicographic ratio test terminates on every LCP; for a
//! positive semidefinite M (copositive-plus) it ends either with a solution or on a secondary
//! ray, and the ray proves that no solution exists (Cottle, Pang and Stone, *The Linear
//! Complementarity Problem*, 1992, Thm. 4.4.13) — a verdict, never a number.

mod lemke;

pub use lemke::{LcpWork, PIVOTS_PER_ROW, lemke, lemke_in};

/// A linear complementarity problem LCP(M, q), M n×n row-major.
#[derive(Debug)]
pub struct Lcp<'a, T> {
    /// M, n×n, row-major.
    pub m: &'a [T],
    /// q, n.
    pub q: &'a [T],
}

impl<T> Clone for Lcp<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for Lcp<'_, T> {}

/// A solution of an LCP, with the work it took.
#[derive(Clone, Debug, PartialEq)]
pub struct LcpSolution<T> {
    /// z ≥ 0.
    pub z: Vec<T>,
    /// w = M z + q ≥ 0, with zᵢ wᵢ = 0.
    pub w: Vec<T>,
    /// The number of complementary pivots made.
    pub pivots: usize,
}

/// Why an LCP has no solution from the solver.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LcpError {
    /// Lemke's path ended on a secondary ray: for a copositive-plus M (a positive semidefinite
    /// one), a proof that the LCP has no solution.
    #[error("no solution: Lemke's method ended on a ray after {pivots} pivots")]
    Ray {
        /// Pivots made.
        pivots: usize,
    },
    /// The pivot budget ran out (a safeguard for floating point, where rounding can cycle).
    #[error("no answer within {pivots} pivots")]
    IterationLimit {
        /// Pivots made.
        pivots: usize,
    },
}
