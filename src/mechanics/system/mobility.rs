//! The mobility of a system held by joints, and the joints' reactions.
//!
//! Each joint blocks the relative twist of its two bodies (or of one body and the ground) along
//! its blocked screws u_k — the η-orthogonal complement of the screws it leaves free
//! ([`crate::mechanics::constraint::Joint::free_screws`], about the world origin). As a row of
//! the system, a blocked screw acts on the first body as u_k and on the second as −u_k, each
//! about its own centre ([`super::screw::about`]): H_k = [.. u_k@C_a .. −u_k@C_b ..], and the
//! joint allows exactly the twists with H_kᵀ η {V} = 0 — a bilateral contact along u_k.
//!
//! With W₀ = M⁻¹ the free system's mobility (block diagonal, each body's \[M\]⁻¹, eq. 11) and
//! the joints' impulses λ acting as H λ, the momentum balance and the constraints
//!
//! ```text
//! M Δ{V} = −Σ P̂_i {Ê_i} + H λ,      Hᵀ η ({V⁰} + Δ{V}) = 0,   Hᵀ η {V⁰} = 0
//! ```
//!
//! give K λ = Hᵀ η W₀ Σ P̂_i {Ê_i} with K = Hᵀ η W₀ H (a Gram matrix, positive semidefinite), so
//! the system answers an impulse along {E} with
//!
//! ```text
//! W{E} = W₀{E} − W₀ H λ,   K λ = Hᵀ η W₀ {E}
//! ```
//!
//! — the same W = D M_red⁻¹ Dᵀ η as §9–11 for D a basis of the allowed twists, without forming
//! D: it is the Schur complement of the KKT system [[M, −H], [Hᵀ η, 0]] (Gauss's principle). A
//! redundant set of joints (a closed loop, two joints blocking the same motion) makes K
//! singular; the right-hand side lies in its range, W{E} is then still unique and the pivoted
//! LDLᵀ of K ([`crate::linalg::factor_psd`]) takes the particular solution
//! ([`crate::linalg::solve_leading`]). Exact types decide that rank exactly.
//!
//! **Reactions.** Once the impulses are known the joints' impulses follow from the same
//! balance: H λ = M Δ{V} + Σ P̂_i {Ê_i} =: r, so K λ = Hᵀ η W₀ r. The wrench joint j applies to
//! its first body is Σ_{k∈j} λ_k u_k about the world origin, [F; M_O]; reduced to its anchor p,
//! M_p = M_O − p × F ([`crate::mechanics::reaction::Wrench::about`]); the second body gets the
//! opposite. It is basis-independent when λ is not unique (redundant joints leave only the sum
//! of the redundant reactions determined, and the report says which are).

use crate::linalg::{self, NotSemidefinite};
use crate::mechanics::body::RigidBody;
use crate::mechanics::screw::{Screw, Screws};
use crate::scalar::Scalar;

use super::screw::SystemScrew;

/// The joints' rows and the factorization of K (module docs), built once per system.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointRows<T: Scalar> {
    /// H_k, each about the centres of the bodies it acts on.
    pub(crate) rows: Vec<SystemScrew<T>>,
    /// W₀ H_k.
    responses: Vec<SystemScrew<T>>,
    /// u_k about the world origin, with the joint it belongs to.
    pub(crate) blocked: Vec<(usize, Screw<T>)>,
    /// The LDLᵀ of K, row-major, and its pivots.
    factor: Vec<T>,
    perm: Vec<usize>,
    /// rank K: fewer than the rows when the joints are redundant.
    pub(crate) rank: usize,
}

impl<T: Scalar> JointRows<T> {
    /// The rows `rows` (with their screws about the origin, `blocked`) of a system of `bodies`.
    pub(crate) fn new(
        bodies: &[RigidBody<T>],
        rows: Vec<SystemScrew<T>>,
        blocked: Vec<(usize, Screw<T>)>,
    ) -> Result<Self, NotSemidefinite> {
        let responses: Vec<SystemScrew<T>> =
            rows.iter().map(|h| free_response(bodies, h)).collect();
        let n = rows.len();
        let mut factor = Vec::with_capacity(n * n);
        for h in &rows {
            for w in &responses {
                factor.push(h.reciprocal(w));
            }
        }
        let mut perm = vec![0; n];
        let rank = linalg::factor_psd(&mut factor, n, &mut perm)?.rank;
        Ok(JointRows {
            rows,
            responses,
            blocked,
            factor,
            perm,
            rank,
        })
    }

    /// λ with K λ = Hᵀ η `twist` (a twist of the free system, W₀ of a wrench).
    pub(crate) fn multipliers(&self, twist: &SystemScrew<T>) -> Vec<T> {
        let n = self.rows.len();
        let b: Vec<T> = self.rows.iter().map(|h| h.reciprocal(twist)).collect();
        let mut lambda = Vec::with_capacity(n);
        let mut work = vec![T::zero(); n];
        linalg::solve_leading(
            &self.factor,
            n,
            &self.perm,
            self.rank,
            &b,
            &mut lambda,
            &mut work,
        );
        lambda
    }

    /// W{E} = W₀{E} − W₀ H λ (module docs), from `free` = W₀{E}.
    pub(crate) fn constrain(&self, mut free: SystemScrew<T>) -> SystemScrew<T> {
        let lambda = self.multipliers(&free);
        for (l, w) in lambda.iter().zip(&self.responses) {
            free.add_scaled(&-l.clone(), w);
        }
        free
    }
}

/// W₀{E}: each body's \[M\]⁻¹ on its block (eq. 11).
pub(crate) fn free_response<T: Scalar>(
    bodies: &[RigidBody<T>],
    e: &SystemScrew<T>,
) -> SystemScrew<T> {
    use crate::mechanics::body::Mobility;
    SystemScrew(
        bodies
            .iter()
            .zip(&e.0)
            .map(|(b, s)| b.response(s))
            .collect(),
    )
}
