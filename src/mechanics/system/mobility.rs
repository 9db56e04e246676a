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
//! **Sparsity.** When the joints form a forest — a chain, a branched tree, each tree held to
//! the ground by at most one joint — the articulated-body recursion of [`super::articulated`]
//! (Featherstone 2008, ch. 7) answers in time and memory linear in the bodies, eliminating
//! each joint through its free screws, and neither H nor K is formed: that is the path every
//! open mechanism takes. A closed loop (through the ground too), two joints between the same
//! bodies or a joint whose free screws are dependent take the dense path above, O(rows³): the
//! rows stored sparse (a row touches at most two bodies, [`Row`], and so does W₀ H_k), K
//! formed from them and factored with pivoting, its rank decided exactly in exact types. Both
//! give the same W{E} and, K being nonsingular for a forest, the same λ — equal in exact
//! arithmetic (tested, `tests/system_tree.rs`).
//!
//! **Reactions.** Once the impulses are known the joints' impulses follow from the same
//! balance: H λ = M Δ{V} + Σ P̂_i {Ê_i} =: r, so K λ = Hᵀ η W₀ r on the dense path; a forest
//! reads λ off r summed along its trees ([`super::articulated`]), without a solve. The wrench joint j applies to
//! its first body is Σ_{k∈j} λ_k u_k about the world origin, [F; M_O]; reduced to its anchor p,
//! M_p = M_O − p × F ([`crate::mechanics::reaction::Wrench::about`]); the second body gets the
//! opposite. It is basis-independent when λ is not unique (redundant joints leave only the sum
//! of the redundant reactions determined, and the report says which are).

use std::sync::Arc;

use crate::linalg::{self, NotSemidefinite};
use crate::mechanics::body::Mobility;
use crate::mechanics::screw::{Screw, Screws};
use crate::scalar::Scalar;

use super::articulated::Articulated;
use super::screw::{SystemScrew, about};
use super::{JointScrews, SystemBody, SystemJoint};

/// A row H_k of the joints: one blocked screw of one joint, on the (at most two) bodies it
/// acts on — u_k about C_a on the first, −u_k about C_b on the second.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Row<T: Scalar> {
    /// The first body and H_k's screw on it.
    pub(crate) first: (usize, Screw<T>),
    /// The second body and H_k's screw on it; `None` for a joint to the ground.
    pub(crate) second: Option<(usize, Screw<T>)>,
}

impl<T: Scalar> Row<T> {
    /// The row of the blocked screw `u` (about the world origin) of `joint`.
    pub(crate) fn new(u: &Screw<T>, joint: &SystemJoint<T>, bodies: &[SystemBody<T>]) -> Self {
        let (a, second) = (joint.pair.first, joint.pair.second);
        Row {
            first: (a, about(u, &bodies[a].centre)),
            second: second.map(|b| (b, Screw(-about(u, &bodies[b].centre).0))),
        }
    }

    /// The bodies it acts on, with its screw on each.
    pub(crate) fn entries(&self) -> impl Iterator<Item = (usize, &Screw<T>)> {
        std::iter::once((self.first.0, &self.first.1))
            .chain(self.second.as_ref().map(|(b, s)| (*b, s)))
    }

    /// H_kᵀ η {V}: the rate of {V} along the blocked screw, relative between the bodies.
    pub(crate) fn rate(&self, v: &SystemScrew<T>) -> T {
        let mut r = T::zero();
        for (b, h) in self.entries() {
            r += h.reciprocal(&v.0[b]);
        }
        r
    }
}

/// How the joints' system is solved (module docs).
#[derive(Clone, Debug, PartialEq)]
enum Factor<T: Scalar> {
    /// The articulated-body factorization of a forest of joints, shared by the system's
    /// copies (an impact keeps one: cloning it is then a pointer).
    Articulated(Arc<Articulated<T>>),
    /// K formed and factored densely with pivoting (loops, redundant joints).
    Dense(Arc<Dense<T>>),
}

/// The dense path: the rows, W₀ H_k per row, and the pivoted LDLᵀ of K.
#[derive(Clone, Debug, PartialEq)]
struct Dense<T: Scalar> {
    /// H_k, sparse.
    rows: Vec<Row<T>>,
    /// W₀ H_k on the bodies of row k.
    responses: Vec<Vec<(usize, Screw<T>)>>,
    /// The LDLᵀ of K, row-major, and its pivots.
    factor: Vec<T>,
    perm: Vec<usize>,
}

/// The factorization of the joints' system (module docs), built once per system.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointRows<T: Scalar> {
    factor: Factor<T>,
    /// rank K: fewer than the rows when the joints are redundant.
    pub(crate) rank: usize,
}

impl<T: Scalar> JointRows<T> {
    /// The joints `joints` of `bodies`, their screws `screws`: factored along the forest when
    /// they form one and `dense` is false, densely otherwise.
    pub(crate) fn new(
        bodies: &[SystemBody<T>],
        joints: &[SystemJoint<T>],
        screws: &JointScrews<T>,
        dense: bool,
    ) -> Result<Self, NotSemidefinite> {
        if !dense && let Some(tree) = Articulated::new(bodies, joints, screws) {
            return Ok(JointRows {
                rank: screws.rows(),
                factor: Factor::Articulated(Arc::new(tree)),
            });
        }
        let mut rows = Vec::with_capacity(screws.rows());
        for (j, joint) in joints.iter().enumerate() {
            for u in screws.blocked(j) {
                rows.push(Row::new(u, joint, bodies));
            }
        }
        let responses: Vec<Vec<(usize, Screw<T>)>> = rows
            .iter()
            .map(|h| {
                h.entries()
                    .map(|(b, s)| (b, bodies[b].body.response(s)))
                    .collect()
            })
            .collect();
        let n = rows.len();
        let mut factor = Vec::with_capacity(n * n);
        for h in &rows {
            for w in &responses {
                let mut k = T::zero();
                for (b, s) in h.entries() {
                    for (c, r) in w {
                        if *c == b {
                            k += s.reciprocal(r);
                        }
                    }
                }
                factor.push(k);
            }
        }
        let mut perm = vec![0; n];
        let rank = linalg::factor_psd(&mut factor, n, &mut perm)?.rank;
        Ok(JointRows {
            factor: Factor::Dense(Arc::new(Dense {
                rows,
                responses,
                factor,
                perm,
            })),
            rank,
        })
    }

    /// Whether the joints were factored along a forest ([`super::articulated`]).
    pub(crate) fn is_tree(&self) -> bool {
        matches!(self.factor, Factor::Articulated(_))
    }

    /// λ with K λ = Hᵀ η W₀ r for the wrench r = M Δ{V} + Σ P̂_i {Ê_i} the joints exert on
    /// the bodies (module docs), from the twist change `dv` and `applied` = Σ P̂_i {Ê_i}.
    pub(crate) fn multipliers(
        &self,
        bodies: &[SystemBody<T>],
        screws: &JointScrews<T>,
        dv: &SystemScrew<T>,
        applied: &SystemScrew<T>,
    ) -> Vec<T> {
        match &self.factor {
            Factor::Articulated(tree) => {
                let r = bodies
                    .iter()
                    .zip(&dv.0)
                    .zip(&applied.0)
                    .map(|((b, v), e)| {
                        let mut m = b.body.momentum(v);
                        m.add_scaled(&T::one(), e);
                        m
                    })
                    .collect();
                tree.impulses(bodies, screws, r)
            }
            Factor::Dense(d) => {
                // W₀ (M Δ{V} + Σ P̂ Ê) = Δ{V} + W₀ Σ P̂ Ê.
                let mut twist = free_response(bodies, applied);
                twist.add_scaled(&T::one(), dv);
                self.dense_multipliers(d, &twist)
            }
        }
    }

    /// λ with K λ = Hᵀ η `twist` on the dense path.
    fn dense_multipliers(&self, d: &Dense<T>, twist: &SystemScrew<T>) -> Vec<T> {
        let n = d.rows.len();
        let b: Vec<T> = d.rows.iter().map(|h| h.rate(twist)).collect();
        let mut lambda = Vec::with_capacity(n);
        let mut work = vec![T::zero(); n];
        linalg::solve_leading(&d.factor, n, &d.perm, self.rank, &b, &mut lambda, &mut work);
        lambda
    }

    /// W{E} (module docs) for the impulse `e`, on `bodies`.
    pub(crate) fn response(&self, bodies: &[SystemBody<T>], e: &SystemScrew<T>) -> SystemScrew<T> {
        match &self.factor {
            Factor::Articulated(tree) => SystemScrew(tree.response(&e.0)),
            Factor::Dense(d) => {
                let mut free = free_response(bodies, e);
                let lambda = self.dense_multipliers(d, &free);
                for (l, w) in lambda.iter().zip(&d.responses) {
                    if l.is_zero() {
                        continue;
                    }
                    let l = -l.clone();
                    for (b, r) in w {
                        free.0[*b].add_scaled(&l, r);
                    }
                }
                free
            }
        }
    }
}

/// W₀{E}: each body's \[M\]⁻¹ on its block (eq. 11).
pub(crate) fn free_response<T: Scalar>(
    bodies: &[SystemBody<T>],
    e: &SystemScrew<T>,
) -> SystemScrew<T> {
    SystemScrew(
        bodies
            .iter()
            .zip(&e.0)
            .map(|(b, s)| b.body.response(s))
            .collect(),
    )
}
