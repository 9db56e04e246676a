//! The impact laws in inequality form: what happens when the simultaneous hypothesis (every
//! contact takes an impulse, every normal velocity reaches its law at once) does not hold.
//!
//! With v_ix⁰ > 0 approaching and v_x = v_x⁰ − G P the normal velocities after impact (eq. 13):
//!
//! ```text
//! Newton (Moreau):  P ≥ 0,  ξ = G P − q ≥ 0,  P_i ξ_i = 0,   q_i = v_ix⁰ + k_i^N max(v_ix⁰, 0)
//! Poisson (Pfeiffer–Glocker), two phases:
//!   compression     P^c ≥ 0,  G P^c − v_x⁰ ≥ 0,  complementary
//!   expansion       P = (1 + k^P)∘P^c + X,  X ≥ 0,  −v_x = G P − v_x⁰ ≥ 0,  complementary
//! ```
//!
//! A contact with P_i > 0 leaves at exactly what its law demands (−k_i v_ix⁰ under Newton); one
//! with P_i = 0 leaves at least that fast, or was separating already and takes no impulse. Each
//! is an LCP in G ([`crate::linalg::lcp`]), solved by Lemke's method in the solver's hatted
//! form: with S = diag|n_i|, Ĝ = S G S and q̂ = S q, so LCP(Ĝ, −q̂) in P̂ = S⁻¹P is the
//! physical LCP with its rows scaled by |n_i| > 0 — the same solutions.
//!
//! **What is unique.** G = Bᵀ W_η B is symmetric positive semidefinite, so w = G P − q — hence
//! every normal velocity after impact, the twist after impact {v} = {v⁰} − W B P (a P₁ − P₂ in
//! ker G has W_η^{1/2} B(P₁ − P₂) = 0), E_p and ΔE_c — is the same for every solution (see
//! [`crate::linalg::lcp`]). With G regular the impulses are unique too; with G singular they may
//! form a set, and this module says so rather than calling its vertex *the* answer. Under
//! Poisson the expansion starts from P^c, which for a singular G may itself be one of a set:
//! then the outcome itself may depend on which compression impulses are taken.
//!
//! **When there is no answer.** For a symmetric semidefinite M, LCP(M, q′) is solvable iff it is
//! feasible (Lemke on a copositive-plus matrix), and by Farkas' lemma infeasible iff some y ≥ 0
//! has Mᵀy ≤ 0 and q′ᵀy < 0 — then yᵀMy ≤ 0 forces My = 0. So Newton's LCP(G, −q) has no
//! solution iff some **y ≥ 0 in ker G** has qᵀy > 0. For such y the impulses Σ y_i {E_ix} change
//! no allowed twist, so Σ y_i v_ix⁰ = 0 (the normal velocities are projections of the twist),
//! and qᵀy = Σ y_i k_i max(v_ix⁰, 0): **the body is jammed iff some y ≥ 0 in ker G has y_i > 0 at
//! an approaching contact with k_i > 0** — impulses that cancel each other, asked to make that
//! contact rebound. Poisson's two LCPs have right-hand sides −v⁰ and G(…) − v⁰, both orthogonal
//! to ker G: **Poisson is never jammed**.
//!
//! **Energy.** With M(u⁺ − u⁻) = −Σ P_i {E_ix}, the loss of kinetic energy is
//! ΔE_c = ½ Σ P_i (v_ix⁰ + v_ix) (eq. 32 with eq. 13). Under Moreau's Newton law an active
//! contact leaves at v_ix = −k_i max(v_ix⁰, 0), so
//!
//! ```text
//! ΔE_c = ½ Σ_i P_i (v_ix⁰ − k_i max(v_ix⁰, 0))
//! ```
//!
//! — every term ≥ 0 when every contact that takes an impulse was approaching, for any
//! k_i ∈ [0, 1], equal or not: the law is then dissipative. A contact that was not approaching
//! yet is pushed into its obstacle (P_i > 0, v_ix⁰ < 0) contributes ½ P_i v_ix⁰ < 0, and the
//! impact can create energy; that is reported as a verdict, not asserted away.
//!
//! **When the simultaneous answer is admissible** — every P_i ≥ 0, every contact approaching
//! before and none still approaching after — it solves these LCPs (ξ = 0, X = 0), and for a
//! regular G it is their only solution: the two laws agree exactly. Otherwise the simultaneous
//! answer is not physical and this is the one to report.

use crate::impact::mechanism::Mechanism;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::linalg::lcp::{Lcp, LcpError, LcpWork, lemke, lemke_in};
use crate::mechanics::screw::Screws;
use crate::scalar::Scalar;

/// Which impact law closes the impulse–velocity relation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Law {
    /// The paper's hypothesis: every contact takes an impulse and meets its restitution law
    /// with equality (eq. 15, 21–23) — a linear system in G.
    #[default]
    Simultaneous,
    /// The laws in inequality form (this module): an LCP in G.
    Unilateral,
    /// The LZB multiple-impact law ([`crate::impact::multiple::lzb`]): each contact's own
    /// compression and expansion, integrated in impulse space (f64).
    Lzb,
}

impl Law {
    /// The lower-case name used in scenes and reports.
    pub fn name(self) -> &'static str {
        match self {
            Law::Simultaneous => "simultaneous",
            Law::Unilateral => "unilateral",
            Law::Lzb => "lzb",
        }
    }

    /// The law called `name` (`"simultaneous"`, `"unilateral"` or `"lzb"`).
    pub fn from_name(name: &str) -> Option<Law> {
        match name {
            "simultaneous" => Some(Law::Simultaneous),
            "unilateral" => Some(Law::Unilateral),
            "lzb" => Some(Law::Lzb),
            _ => None,
        }
    }
}

impl std::fmt::Display for Law {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What the unilateral solve found besides the outcome (which contacts are active is read off
/// the outcome: [`active`]). Under Newton with impulses that are not unique, the outcome holds
/// the least-norm member of the set (Σ P_i² least).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Activity {
    /// G is singular (Δ = 0).
    pub singular: bool,
    /// The impulses are unique. Every solution vanishes where w_i > 0 and has the same G z,
    /// so with A = {i : w_i = 0} the solutions differ by vectors of ker G_AA: a regular G_AA
    /// makes them unique. When G_AA is singular they may form a set (they do when every
    /// contact of A takes a positive impulse), and this is `false`: the report says "may".
    pub impulses_unique: bool,
    /// The velocities after impact are decided by the law. Always under Newton (w is
    /// unique); under Poisson the expansion starts from (1 + k)∘P^c, so when the compression
    /// impulses are not unique and the k_i^P differ, the outcome may depend on which are taken.
    pub outcome_decided: bool,
    /// Complementary pivots made by Lemke's method (both phases for Poisson).
    pub pivots: usize,
}

/// Per contact: whether it takes an impulse (P_i > 0); the others separate.
pub fn active<T: Scalar, S: Screws<T>>(out: &Outcome<T, S>) -> Vec<bool> {
    out.impulses_hat.iter().map(|p| p.signum_i8() > 0).collect()
}

/// The buffers of the unilateral solve, kept in the [`Impact`] so that repeated f64 solves
/// allocate nothing: the LCP tableau and solution, the right-hand side, and the regularity
/// test's sub-matrix.
#[derive(Clone, Debug)]
pub struct UnilateralWork<T> {
    lcp: LcpWork<T>,
    q: Vec<T>,
    w: Vec<T>,
    sub: Vec<T>,
    perm: Vec<usize>,
    set: Vec<usize>,
}

impl<T> Default for UnilateralWork<T> {
    fn default() -> Self {
        UnilateralWork {
            lcp: LcpWork::default(),
            q: Vec::new(),
            w: Vec::new(),
            sub: Vec::new(),
            perm: Vec::new(),
            set: Vec::new(),
        }
    }
}

/// Why the unilateral law gave no outcome.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum UnilateralError {
    /// No impulses P ≥ 0 satisfy the law: the body is jammed between its contacts (the LCP
    /// is infeasible, proved by Lemke's ray).
    #[error(
        "no admissible impulses: the contacts jam the body (the {phase} complementarity problem \
         has no solution){}",
        if *rounded {
            " — decided in floating point, where rounding can end Lemke's path on a ray that \
             exact arithmetic does not take (G singular, or a regular G, whose problem always \
             has a solution, rounded): `--exact` decides"
        } else {
            ""
        }
    )]
    Jammed {
        /// `"newton"`, `"compression"` or `"expansion"`.
        phase: &'static str,
        /// Decided in floating point: exact arithmetic may find a solution (a scene of 10
        /// random contacts with k = 0, which no y ≥ 0 in ker G can jam, was called jammed).
        rounded: bool,
    },
    /// The pivot budget ([`crate::linalg::lcp::PIVOTS_PER_ROW`] per contact) ran out: in
    /// floating point, rounding can make the path cycle on a singular G.
    #[error(
        "the {phase} complementarity problem was not solved within {pivots} pivots (the budget \
         that bounds Lemke's method: rounding can make its path cycle when G is singular; \
         `--exact` decides)"
    )]
    IterationLimit {
        /// The phase.
        phase: &'static str,
        /// Pivots made.
        pivots: usize,
    },
    /// The assembled impact could not be solved.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// More contacts than Lemke's method on the N×N tableau takes in this scalar type
    /// ([`max_unilateral_contacts`]), refused before any work.
    #[error(
        "the unilateral law is solved for at most {limit} contacts in this arithmetic ({contacts} \
         given): Lemke's method works on the N×N matrix G, its pivots costing O(N²) each"
    )]
    TooManyContacts {
        /// N.
        contacts: usize,
        /// The limit.
        limit: usize,
    },
}

/// The most contacts the unilateral law is solved for: Lemke's method pivots on the N×N
/// tableau, O(N²) per pivot and at most [`crate::linalg::lcp::PIVOTS_PER_ROW`]·(N + 1)
/// pivots. In f64 a path that rounding makes cycle on a singular G runs to that budget: 0.8 s
/// for `analyze` on 300 random contacts (release build), 48 s on 1000, which the limit was
/// before; in exact arithmetic the rationals grow with every pivot, and 48 contacts take
/// about a second.
pub fn max_unilateral_contacts<T: Scalar>() -> usize {
    if T::IS_EXACT { 48 } else { 300 }
}

impl<T: Scalar, M: Mechanism<T>> Impact<T, M> {
    /// Solve `model` in inequality form (see the module docs) into `out`, in hatted form like
    /// [`Impact::solve`]: the impulses, the twist and contact velocities after impact, both
    /// energies and the constraint impulses.
    ///
    /// # Errors
    /// [`UnilateralError::Jammed`] when no admissible impulses exist.
    pub fn solve_unilateral(
        &mut self,
        model: Model,
        out: &mut Outcome<T, M::Screw>,
    ) -> Result<Activity, UnilateralError> {
        let (contacts, limit) = (self.contacts(), max_unilateral_contacts::<T>());
        if contacts > limit {
            return Err(UnilateralError::TooManyContacts { contacts, limit });
        }
        let mut work = std::mem::take(&mut self.unilateral);
        let result = self.solve_unilateral_in(&mut work, model, out);
        self.unilateral = work;
        let (pivots, unique, decided) = result?;
        self.complete(out);
        Ok(Activity {
            singular: self.singular(),
            impulses_unique: unique,
            outcome_decided: decided,
            pivots,
        })
    }

    /// The LCPs of `model` in `work`'s buffers, the impulses into `out`: (pivots, impulses
    /// unique, outcome decided).
    fn solve_unilateral_in(
        &self,
        work: &mut UnilateralWork<T>,
        model: Model,
        out: &mut Outcome<T, M::Screw>,
    ) -> Result<(usize, bool, bool), UnilateralError> {
        let n = self.contacts();
        let g = self.g_hat();
        let v0 = |i: usize| &self.before_hat()[i][0];
        let contacts = self.problem().contacts();
        let UnilateralWork {
            lcp,
            q,
            w,
            sub,
            perm,
            set,
        } = work;
        match model {
            Model::Newton => {
                // −q_i = −(v_ix⁰ + k_i max(v_ix⁰, 0)).
                q.clear();
                q.extend((0..n).map(|i| {
                    let v = v0(i);
                    let approach = if v.signum_i8() > 0 {
                        v.clone()
                    } else {
                        T::zero()
                    };
                    -(v.clone() + contacts[i].k_newton.clone() * &approach)
                }));
                let mut pivots = run(lcp, g, q, "newton")?;
                let speed = largest(q);
                let unique = regular_on_equalities(g, &lcp.w, &speed, set, sub, perm);
                if !unique {
                    let norm2: Vec<T> = self.frames().iter().map(|f| f.norm2[0].clone()).collect();
                    pivots += least_norm(g, &lcp.w, &speed, &norm2, &mut lcp.z);
                }
                out.impulses_hat.clone_from(&lcp.z);
                out.compression_hat.clear();
                Ok((pivots, unique, true))
            }
            Model::Poisson => {
                q.clear();
                q.extend((0..n).map(|i| -v0(i).clone()));
                let compression = run(lcp, g, q, "compression")?;
                out.compression_hat.clone_from(&lcp.z);
                w.clone_from(&lcp.w);
                // The expansion LCP in X: w = Ĝ X + (Ĝ (1 + k)∘P̂ᶜ − v̂⁰); (1 + k)∘P̂ᶜ is kept in
                // out.impulses_hat until X is added.
                out.impulses_hat.clear();
                out.impulses_hat.extend(
                    (0..n).map(|j| (T::one() + &contacts[j].k_poisson) * &out.compression_hat[j]),
                );
                q.clear();
                q.extend((0..n).map(|i| {
                    let mut s = -v0(i).clone();
                    for j in 0..n {
                        s += g[i * n + j].clone() * &out.impulses_hat[j];
                    }
                    s
                }));
                let expansion = run(lcp, g, q, "expansion")?;
                for (p, x) in out.impulses_hat.iter_mut().zip(&lcp.z) {
                    *p += x;
                }
                let speed = (0..n).fold(T::zero(), |m, i| {
                    let v = v0(i);
                    if v.abs_gt(&m) { v.clone() } else { m }
                });
                let compression_unique = regular_on_equalities(g, w, &speed, set, sub, perm);
                let unique =
                    compression_unique && regular_on_equalities(g, &lcp.w, &speed, set, sub, perm);
                let equal_k = contacts
                    .iter()
                    .all(|k| k.k_poisson == contacts[0].k_poisson);
                Ok((
                    compression + expansion,
                    unique,
                    compression_unique || equal_k,
                ))
            }
        }
    }
}

/// The largest |x_i| (zero for none).
fn largest<T: Scalar>(x: &[T]) -> T {
    x.iter()
        .fold(T::zero(), |m, v| if v.abs_gt(&m) { v.clone() } else { m })
}

/// What a w_i is negligible against: the largest |w_i| and the impact's speed (the largest
/// |q_i| or |v̂_ix⁰|). The speed matters when every w_i is rounding noise — every contact
/// meets its law with equality, as on `examples/box-on-box.toml` — where the largest |w_i|
/// alone would make that noise look like a velocity and the contacts look separate.
fn velocity_scale<T: Scalar>(w: &[T], speed: &T) -> T {
    let m = largest(w);
    if speed.abs_gt(&m) { speed.clone() } else { m }
}

/// Is G_AA regular, A = {i : w_i = 0} the contacts that meet their law with equality? (In the
/// caller's buffers.)
fn regular_on_equalities<T: Scalar>(
    g: &[T],
    w: &[T],
    speed: &T,
    set: &mut Vec<usize>,
    sub: &mut Vec<T>,
    perm: &mut Vec<usize>,
) -> bool {
    let n = w.len();
    let scale = velocity_scale(w, speed);
    set.clear();
    set.extend((0..n).filter(|&i| w[i].is_negligible(&scale, 16 * n)));
    let k = set.len();
    sub.clear();
    for &i in set.iter() {
        sub.extend(set.iter().map(|&j| g[i * n + j].clone()));
    }
    perm.clear();
    perm.resize(k, 0);
    // In floats a pivot within the rounding of G's entries may be a zero that rounding hid
    // (the base of `examples/box-on-box.toml` on four coplanar corners: rank 3 exactly, a
    // fourth pivot of a few ε in f64): the impulses are then reported as possibly one of a set
    // ("may"), never claimed unique on rounding's word. G's entries carry a relative error of
    // (3ℓ + 16N)ε (the accuracy contract, `crate::analysis::accuracy`) and the elimination adds
    // O(k) of its own: a pivot under 32 k² ε of the largest diagonal is taken as zero. Exact
    // types test exact zeros.
    crate::linalg::factor_psd(sub, k, perm).is_ok_and(|f| {
        f.rank == k && (0..k).all(|i| !sub[i * k + i].is_negligible(&f.scale, 32 * k * k))
    })
}

/// Replace the solution `z` of a Newton LCP with a singular G_AA by the member of its solution
/// set of least physical norm Σ (P̂_i |n_i|)²; the pivots it took.
///
/// Every solution vanishes off A = {i : w_i = 0} and has z_A ∈ z*_A + range N, N a basis of
/// ker G_AA (module docs). So the least-norm solution minimises ½ yᵀ S y (S = diag|n_i|²) over
/// y = z*_A + N t ≥ 0. Its KKT conditions — Nᵀ(S y − μ) = 0, y ≥ 0 ⊥ μ ≥ 0 — eliminate
/// t = (NᵀSN)⁻¹Nᵀ(μ − S z*_A) and leave the LCP
///
/// ```text
/// y = (I − Π S) z*_A + Π μ ≥ 0,  μ ≥ 0,  yᵀμ = 0,     Π = N (NᵀSN)⁻¹ Nᵀ  (symmetric, ⪰ 0)
/// ```
///
/// solved by Lemke; it is feasible (μ = 0 … z* itself is a feasible y) and the convex QP's KKT
/// point is its minimiser.
fn least_norm<T: Scalar>(g: &[T], w: &[T], speed: &T, norm2: &[T], z: &mut [T]) -> usize {
    let n = w.len();
    let scale = velocity_scale(w, speed);
    let a: Vec<usize> = (0..n)
        .filter(|&i| w[i].is_negligible(&scale, 16 * n))
        .collect();
    let k = a.len();
    let sub: Vec<T> = a
        .iter()
        .flat_map(|&i| a.iter().map(move |&j| g[i * n + j].clone()))
        .collect();
    let (_, basis) = crate::linalg::null_space(&sub, k, k);
    let d = basis.len();
    if d == 0 {
        return 0;
    }
    // NᵀSN (d×d, positive definite) and X = (NᵀSN)⁻¹ Nᵀ (d×k), column by column.
    let s = |r: usize| norm2[a[r]].clone();
    let mut nsn: Vec<T> = (0..d * d)
        .map(|e| {
            (0..k).fold(T::zero(), |acc, r| {
                acc + basis[e / d][r].clone() * s(r) * &basis[e % d][r]
            })
        })
        .collect();
    let mut perm = vec![0; d];
    if crate::linalg::factor_psd(&mut nsn, d, &mut perm).map_or(true, |f| f.rank < d) {
        return 0;
    }
    let mut x = vec![T::zero(); d * k];
    let mut work = vec![T::zero(); d];
    for r in 0..k {
        let mut col: Vec<T> = (0..d).map(|e| basis[e][r].clone()).collect();
        crate::linalg::solve_factored(&nsn, d, &perm, &mut col, &mut work);
        for e in 0..d {
            x[e * k + r] = col[e].clone();
        }
    }
    // Π = N X (k×k); q = z*_A − Π S z*_A.
    let pi: Vec<T> = (0..k * k)
        .map(|e| {
            (0..d).fold(T::zero(), |acc, f| {
                acc + basis[f][e / k].clone() * &x[f * k + e % k]
            })
        })
        .collect();
    let za: Vec<T> = a.iter().map(|&i| z[i].clone()).collect();
    let q: Vec<T> = (0..k)
        .map(|r| {
            (0..k).fold(za[r].clone(), |acc, c| {
                acc - pi[r * k + c].clone() * s(c) * &za[c]
            })
        })
        .collect();
    match lemke(Lcp { m: &pi, q: &q }) {
        Ok(sol) => {
            for (r, &i) in a.iter().enumerate() {
                z[i] = sol.w[r].clone();
            }
            sol.pivots
        }
        // Not reached for a feasible QP; keep the vertex found.
        Err(_) => 0,
    }
}

/// Lemke on LCP(Ĝ, q) in `work`, the errors named by phase; the pivots made.
fn run<T: Scalar>(
    work: &mut LcpWork<T>,
    g: &[T],
    q: &[T],
    phase: &'static str,
) -> Result<usize, UnilateralError> {
    lemke_in(work, Lcp { m: g, q }).map_err(|e| match e {
        LcpError::Ray { .. } => UnilateralError::Jammed {
            phase,
            rounded: !T::IS_EXACT,
        },
        LcpError::IterationLimit { pivots } => UnilateralError::IterationLimit { phase, pivots },
    })
}

/// At most this many contacts meeting Poisson's compression law with equality are enumerated
/// for [`Impact::poisson_vertex_outcomes`] (2^12 supports).
pub const MAX_ENUMERATED: usize = 12;

impl<T: Scalar, M: Mechanism<T>> Impact<T, M> {
    /// When Poisson's law does not decide the outcome (compression impulses that form a set,
    /// unequal k_i), the outcomes obtained from each **vertex of the set of compression
    /// impulses**: every Pᶜ ≥ 0 with G Pᶜ = G Pᶜ* that vanishes off A = {i : w_i = 0} and has a
    /// support S with G_SS regular (the vertices of that polytope), each followed by its
    /// expansion LCP. Their spread shows how far the law leaves the answer open; `None` when
    /// A has more than [`MAX_ENUMERATED`] contacts.
    ///
    /// # Errors
    /// As [`Impact::solve_unilateral`].
    pub fn poisson_vertex_outcomes(
        &mut self,
    ) -> Result<Option<Vec<Outcome<T, M::Screw>>>, UnilateralError> {
        let n = self.contacts();
        let mut first = Outcome::default();
        self.solve_unilateral(Model::Poisson, &mut first)?;
        let g = self.g_hat().to_vec();
        // The compression LCP's w, and the fixed G Pᶜ.
        let v0: Vec<T> = self.before_hat().iter().map(|v| v[0].clone()).collect();
        let gp: Vec<T> = (0..n)
            .map(|i| {
                (0..n).fold(T::zero(), |s, j| {
                    s + g[i * n + j].clone() * &first.compression_hat[j]
                })
            })
            .collect();
        let w: Vec<T> = (0..n).map(|i| gp[i].clone() - &v0[i]).collect();
        let scale = w
            .iter()
            .fold(T::zero(), |m, x| if x.abs_gt(&m) { x.clone() } else { m });
        let a: Vec<usize> = (0..n)
            .filter(|&i| w[i].is_negligible(&scale, 16 * n))
            .collect();
        if a.len() > MAX_ENUMERATED {
            return Ok(None);
        }
        let mut outcomes = Vec::new();
        for mask in 1u32..(1 << a.len()) {
            let s: Vec<usize> = (0..a.len())
                .filter(|b| mask >> b & 1 == 1)
                .map(|b| a[b])
                .collect();
            let k = s.len();
            let g = &g;
            let mut sub: Vec<T> = s
                .iter()
                .flat_map(|&i| s.iter().map(move |&j| g[i * n + j].clone()))
                .collect();
            let mut perm = vec![0; k];
            if !crate::linalg::factor_psd(&mut sub, k, &mut perm).is_ok_and(|f| f.rank == k) {
                continue;
            }
            let mut y: Vec<T> = s.iter().map(|&i| gp[i].clone()).collect();
            let mut work = vec![T::zero(); k];
            crate::linalg::solve_factored(&sub, k, &perm, &mut y, &mut work);
            if y.iter()
                .any(|x| x.signum_i8() < 0 && !x.is_negligible(&scale, 16 * n))
            {
                continue;
            }
            let mut pc = vec![T::zero(); n];
            for (&i, x) in s.iter().zip(y) {
                pc[i] = x;
            }
            // A vertex only if G Pᶜ = G Pᶜ* on every row (not only on S).
            let consistent = (0..n).all(|i| {
                let r = (0..n).fold(-gp[i].clone(), |acc, j| acc + g[i * n + j].clone() * &pc[j]);
                r.is_negligible(&scale, 16 * n)
            });
            if consistent {
                outcomes.push(self.expand_from(&pc)?);
            }
        }
        Ok(Some(outcomes))
    }

    /// Poisson's expansion phase from the compression impulses `pc`, completed.
    fn expand_from(&mut self, pc: &[T]) -> Result<Outcome<T, M::Screw>, UnilateralError> {
        let n = self.contacts();
        let g = self.g_hat();
        let contacts = self.problem().contacts();
        let base: Vec<T> = (0..n)
            .map(|j| (T::one() + &contacts[j].k_poisson) * &pc[j])
            .collect();
        let q: Vec<T> = (0..n)
            .map(|i| {
                (0..n).fold(-self.before_hat()[i][0].clone(), |s, j| {
                    s + g[i * n + j].clone() * &base[j]
                })
            })
            .collect();
        let mut x = LcpWork::default();
        run(&mut x, g, &q, "expansion")?;
        let mut out = Outcome {
            impulses_hat: base.into_iter().zip(x.z).map(|(b, x)| b + x).collect(),
            compression_hat: pc.to_vec(),
            ..Outcome::default()
        };
        self.complete(&mut out);
        Ok(out)
    }
}
