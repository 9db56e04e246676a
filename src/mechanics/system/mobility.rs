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
//! **Sparsity.** A row touches at most two bodies, so it is stored as those (the rest of H_k
//! is zero, [`Row`]), and so is W₀ H_k. When the joints form a forest — a chain, a branched
//! tree, each tree held to the ground by at most one joint — the KKT system is factored along
//! the tree in time and memory linear in the bodies ([`super::tree`], Baraff 1996), and K is
//! never formed: that is the path every open mechanism takes. A closed loop (through the
//! ground too) or two joints between the same bodies take the dense path above, O(rows³):
//! K formed from the sparse rows and factored with pivoting, its rank decided exactly in
//! exact types. Both give the same W{E} and, K being nonsingular for a forest, the same λ —
//! equal in exact arithmetic (tested, `tests/system_tree.rs`).
//!
//! **Reactions.** Once the impulses are known the joints' impulses follow from the same
//! balance: H λ = M Δ{V} + Σ P̂_i {Ê_i} =: r, so K λ = Hᵀ η W₀ r. The wrench joint j applies to
//! its first body is Σ_{k∈j} λ_k u_k about the world origin, [F; M_O]; reduced to its anchor p,
//! M_p = M_O − p × F ([`crate::mechanics::reaction::Wrench::about`]); the second body gets the
//! opposite. It is basis-independent when λ is not unique (redundant joints leave only the sum
//! of the redundant reactions determined, and the report says which are).

use std::sync::Arc;

use crate::linalg::{self, NotSemidefinite};
use crate::mechanics::body::{Mobility, RigidBody};
use crate::mechanics::screw::Screw;
use crate::scalar::Scalar;

use super::screw::SystemScrew;
use super::tree::Tree;

/// A row H_k of the joints: one blocked screw of one joint, on the (at most two) bodies it
/// acts on — u_k about C_a on the first, −u_k about C_b on the second.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Row<T: Scalar> {
    /// The joint it belongs to.
    pub(crate) joint: usize,
    /// u_k about the world origin.
    pub(crate) blocked: Screw<T>,
    /// The first body and H_k's screw on it.
    pub(crate) first: (usize, Screw<T>),
    /// The second body and H_k's screw on it; `None` for a joint to the ground.
    pub(crate) second: Option<(usize, Screw<T>)>,
}

impl<T: Scalar> Row<T> {
    /// The bodies it acts on, with its screw on each.
    pub(crate) fn entries(&self) -> impl Iterator<Item = (usize, &Screw<T>)> {
        std::iter::once((self.first.0, &self.first.1))
            .chain(self.second.as_ref().map(|(b, s)| (*b, s)))
    }

    /// Its screw on body `b`, one of its bodies.
    pub(crate) fn on(&self, b: usize) -> &Screw<T> {
        match &self.second {
            Some((second, s)) if *second == b => s,
            _ => &self.first.1,
        }
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

/// How K λ = … is solved (module docs).
#[derive(Clone, Debug, PartialEq)]
enum Factor<T: Scalar> {
    /// The KKT system factored along a forest of joints, shared by the system's copies (an
    /// impact keeps one: cloning it is then O(bodies) pointers, not the factor's 2 × 36 numbers
    /// per node).
    Tree(Arc<Tree<T>>),
    /// K formed and factored densely with pivoting (loops, redundant joints).
    Dense(Dense<T>),
}

/// The dense path: W₀ H_k per row, and the pivoted LDLᵀ of K.
#[derive(Clone, Debug, PartialEq)]
struct Dense<T: Scalar> {
    /// W₀ H_k on the bodies of row k.
    responses: Vec<Vec<(usize, Screw<T>)>>,
    /// The LDLᵀ of K, row-major, and its pivots.
    factor: Vec<T>,
    perm: Vec<usize>,
}

/// The joints' rows and the factorization of their system (module docs), built once per
/// system.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointRows<T: Scalar> {
    /// H_k, sparse.
    pub(crate) rows: Vec<Row<T>>,
    factor: Factor<T>,
    /// rank K: fewer than the rows when the joints are redundant.
    pub(crate) rank: usize,
}

impl<T: Scalar> JointRows<T> {
    /// The rows `rows` of a system of `bodies` whose joints join `pairs` (first, second or
    /// the ground): factored along the tree when the joints form a forest and `dense` is
    /// false, densely otherwise.
    pub(crate) fn new(
        bodies: &[RigidBody<T>],
        rows: Vec<Row<T>>,
        pairs: &[(usize, Option<usize>)],
        dense: bool,
    ) -> Result<Self, NotSemidefinite> {
        if !dense && let Some(tree) = Tree::new(bodies, &rows, pairs) {
            return Ok(JointRows {
                rank: rows.len(),
                rows,
                factor: Factor::Tree(Arc::new(tree)),
            });
        }
        let responses: Vec<Vec<(usize, Screw<T>)>> = rows
            .iter()
            .map(|h| {
                h.entries()
                    .map(|(b, s)| (b, bodies[b].response(s)))
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
            rows,
            factor: Factor::Dense(Dense {
                responses,
                factor,
                perm,
            }),
            rank,
        })
    }

    /// `f(k, at)` for every row k, in order, with `at` its place in the tree's stacked vector.
    fn each_joint(&self, tree: &Tree<T>, mut f: impl FnMut(usize, usize)) {
        let mut k = 0;
        let mut j = 0;
        while k < self.rows.len() {
            let (at, m) = tree.joint_span(j);
            for r in 0..m {
                f(k + r, at + r);
            }
            k += m;
            j += 1;
        }
    }

    /// Whether the KKT system was factored along a tree ([`super::tree`]).
    pub(crate) fn is_tree(&self) -> bool {
        matches!(self.factor, Factor::Tree(_))
    }

    /// λ with K λ = Hᵀ η `twist` (a twist of the free system, W₀ of a wrench).
    pub(crate) fn multipliers(&self, twist: &SystemScrew<T>) -> Vec<T> {
        let n = self.rows.len();
        match &self.factor {
            Factor::Tree(tree) => {
                // E = 0, c = −Hᵀ η t ([`super::tree`]).
                let mut x = vec![T::zero(); tree.len()];
                self.each_joint(tree, |k, at| x[at] = -self.rows[k].rate(twist));
                tree.solve(&mut x);
                let mut lambda = Vec::with_capacity(n);
                self.each_joint(tree, |_, at| lambda.push(x[at].clone()));
                lambda
            }
            Factor::Dense(d) => {
                let b: Vec<T> = self.rows.iter().map(|h| h.rate(twist)).collect();
                let mut lambda = Vec::with_capacity(n);
                let mut work = vec![T::zero(); n];
                linalg::solve_leading(&d.factor, n, &d.perm, self.rank, &b, &mut lambda, &mut work);
                lambda
            }
        }
    }

    /// W{E} (module docs) for the impulse `e`, on `bodies`.
    pub(crate) fn response(&self, bodies: &[RigidBody<T>], e: &SystemScrew<T>) -> SystemScrew<T> {
        match &self.factor {
            Factor::Tree(tree) => {
                // [E; 0] ↦ [y; λ], W{E} = η y ([`super::tree`]).
                let mut x = Vec::with_capacity(tree.len());
                for s in &e.0 {
                    x.extend_from_slice(s.as_slice());
                }
                x.resize(tree.len(), T::zero());
                tree.solve(&mut x);
                SystemScrew(
                    x[..6 * e.bodies()]
                        .chunks_exact(6)
                        .map(|y| {
                            Screw(nalgebra::SVector::<T, 6>::from_fn(|k, _| {
                                y[(k + 3) % 6].clone()
                            }))
                        })
                        .collect(),
                )
            }
            Factor::Dense(d) => {
                let mut free = free_response(bodies, e);
                let lambda = self.multipliers(&free);
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
    bodies: &[RigidBody<T>],
    e: &SystemScrew<T>,
) -> SystemScrew<T> {
    SystemScrew(
        bodies
            .iter()
            .zip(&e.0)
            .map(|(b, s)| b.response(s))
            .collect(),
    )
}
