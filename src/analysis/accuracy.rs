//! The accuracy contract of a float solve, per output, and its measurement against an exact
//! solve.
//!
//! # The bounds
//!
//! A float solve (f32, f64, double-double; ε its machine epsilon: 2⁻²³, 2⁻⁵², 2⁻¹⁰⁴) of a
//! problem whose G has full rank in that type returns, for each restitution model, outputs
//! within these distances of the exact outputs of the problem as written (every input
//! rounded once into the type), to first order in ε:
//!
//! ```text
//! impulses               ‖δP‖₂        ≤ B_P  = 4 c ε (√κ ‖P‖₂ + κ V / √λ_max)
//! twist after impact     ‖δv‖_M       ≤ B_v  = c ε (√κ V + 4 δk κ ‖v⁰‖_M)
//! contact velocities     |δv_ia|      ≤ B_ia = √g_ia B_v + 4 ε s_ia V
//! E_p                    |δE_p|       ≤ ‖Δv‖_M B_v + ½ B_v² + N ε E_p
//! ΔE_c                   |δΔE_c|      ≤ 3 V B_v + (3/2) B_v² + N ε V²
//!
//! c = μ (2 √N (3ℓ + 16N) + 1)
//! ```
//!
//! in the problem's own terms, so every bound is independent of the units:
//!
//! - κ = cond₂ G = λ_max/λ_min of the physical inertance matrix (unit normals);
//! - ‖v‖_M = (vᵀ η M v)^½ = (2T(v))^½, the kinetic-energy norm of a twist; Δv = {v} − {v⁰};
//!   V = ‖v⁰‖_M + ‖Δv‖_M = (2T⁰)^½ + (2E_p)^½, the velocity scale of the impact;
//! - δk = (max k_i^P − min k_i^P)/2 for Poisson, 0 for Newton;
//! - g_ia = ⟨e_ia, e_ia⟩ the inertance along the unit axis a of contact i (g_ii for a = x), and
//!   s_ia the same norm of |e_ia|, the axis screw's componentwise magnitudes, in the free-body
//!   metric (below);
//! - ℓ = max_j ‖|E_j|‖/‖E_j‖ ≥ 1, the cancellation in the contacts' axis screws
//!   E_j = [n_j; r_j × n_j]: |E_j| holds each component's magnitudes, |n_j| and
//!   |r_b n_c| + |r_c n_b| for (r × n)_a, measured in the free-body metric ηM⁻¹, E_j in the
//!   body's metric ηW. ℓ = 1 when no component of r × n cancels; it grows when a normal
//!   passes close to C, or when a constraint absorbs most of a contact's wrench;
//! - μ = cond₂ M_red (eq. 83) for a constrained body, 1 for a free one: the accuracy to which
//!   its mobility W is applied.
//!
//! **Where the terms come from.** The solve from the orthogonalised wrenches
//! ([`crate::impact::gram_schmidt`]) is, to first order, the exact solve of a problem whose
//! data are perturbed by
//!
//! 1. the rounding of the inputs and of E_j = [n; r × n] and W E_j (a component of E_j is at
//!    most a difference of two products of inputs): ‖δE_j‖ ≤ 3 ε ℓ ‖E_j‖ (the inputs ½ε each,
//!    two products and a difference ½ε each, the mobility's division ½ε, the metric's inputs
//!    ½ε; the free-body metric is diagonal in principal axes, so a componentwise bound
//!    |δE| ≤ 3ε|E| gives ‖δE‖ ≤ 3ε‖|E|‖ — with a full inertia tensor ‖|E|‖ bounds the moment
//!    part by |·|²/λ_min(J), for which the same holds);
//! 2. Gram–Schmidt with reorthogonalisation, backward stable column by column: the computed
//!    factors are exact for E + δE with ‖δE_j‖ ≤ 16 N ε ‖E_j‖ (at most two passes of N − 1
//!    projections, each a 12-flop reciprocal product and a 12-flop update; the triangular
//!    solves with U add at most N ε Σ_k |u_kj| d_k^½ ≤ N^{3/2} ε ‖E_j‖, within the same
//!    constant for N ≤ 6, the most contacts a full-rank G can have);
//! 3. the velocities along the normals before impact, |δv̂⁰_ix| ≤ 3 ε ℓ ‖E_i‖ ‖v⁰‖_M
//!    (weighted Cauchy–Schwarz: Σ|E_k v_k| ≤ ‖|E|‖ ‖v‖_M in the diagonal metrics), so the
//!    right-hand side b = (1 + K) v̂⁰_x (Newton; 1 + k_i ≤ 2) moves by |δb_i| ≤ 2 η_E √g_ii ‖v⁰‖_M.
//!
//! With η_E = (3ℓ + 16N) ε the relative perturbation of each wrench, first-order perturbation
//! of y = E G⁻¹ b (the impulses' wrench; Δv = −W y and ‖Δv‖_M = ‖y‖):
//!
//! ```text
//! δy = (I − Π) δE P − E G⁻¹ δEᵀ A y + E G⁻¹ δb,        Π = E G⁻¹ Eᵀ A
//! ‖(I − Π) δE P‖ ≤ ‖δE P‖ ≤ η_E (Σ g_jj)^½ ‖P‖₂ ≤ η_E √N √λ_max ‖y‖/√λ_min = √N √κ η_E ‖Δv‖_M
//! ‖E G⁻¹ δEᵀ A y‖ = ‖G^(−½) δEᵀ A y‖₂ ≤ √N √κ η_E ‖Δv‖_M
//! ‖E G⁻¹ δb‖ = ‖G^(−½) δb‖₂ ≤ 2 √N √κ η_E ‖v⁰‖_M
//! ```
//!
//! (‖E x‖ = ‖G^½ x‖₂, and ‖δEᵀ A y‖₂ ≤ (Σ_j ‖δE_j‖²)^½ ‖y‖), so ‖δΔv‖_M ≤ 2√N √κ η_E V, plus
//! ε V for forming {v⁰} + Δv: B_v with c = 2√N (3ℓ + 16N) + 1. The same steps on P = G⁻¹ b give
//! ‖G⁻¹ δG P‖ ≤ √N η_E (√κ ‖P‖ + κ ‖Δv‖_M/√λ_max) and ‖G⁻¹ δb‖ ≤ 2√N η_E κ ‖v⁰‖_M/√λ_max,
//! together ≤ c ε (√κ ‖P‖ + κ V/√λ_max). Poisson's impulses are (1 + k_i) P^c_i, with
//! ‖P^c‖ ≤ ‖P‖ and ‖Δv_c‖_M ≤ ‖v⁰‖_M (the compression twist change is a projection of −v⁰):
//! a factor 2 twice, hence the 4 in B_P. Poisson's twist is −W E (1 + K) P^c =
//! (1 + k̄) Δv_c − W E (K − k̄) P^c: the first part is a projection like Newton's, the second
//! weighs the compression impulses' split between the contacts, ‖W E (K − k̄) δP^c‖_M ≤
//! δk √λ_max ‖δP^c‖₂ ≤ 3 c ε δk κ ‖v⁰‖_M (as √λ_max ‖P^c‖ ≤ √κ ‖Δv_c‖_M) — the one term in
//! cond G itself, present only when the k_i^P differ: then the twist does depend on how the
//! impulse splits, and the split is what a nearly singular G leaves uncertain.
//!
//! A contact velocity is v_ia = e_iaᵀ η {v}, so |e_iaᵀ η δv| ≤ √g_ia ‖δv‖_M, plus its own
//! rounding (4 ε s_ia V). E_p = ½ ‖Δv‖²_M = ½ Σ_k d_k (w⁺_k)²: ‖Δv‖_M B_v plus N ε E_p for the
//! sum. ΔE_c = ½ ⟨y⁺, y⁻⟩ with ‖y⁻‖ ≤ ‖v⁰ + v‖_M ≤ 2V and ‖δy⁻‖ ≤ 2‖δy⁰‖ + ‖δy⁺‖: 3 V B_v, plus
//! N ε V² for the sum. The energies are quadratic, so each also has a term of second order,
//! ½ ‖δΔv‖²_M ≤ ½ B_v² and ½ ‖δy⁺‖ ‖δy⁻‖ ≤ (3/2) B_v²: negligible beside the first-order terms
//! unless the impulse vanishes — a contact that is not approaching (v_ix⁰ = 0 exactly, rounded
//! to 10⁻¹⁶) has E_p = 0 exactly and E_p ≈ 10⁻³¹ in f64, which the first-order bound, 0,
//! did not allow (a finding of the fuzz oracle).
//!
//! The bounds are worst cases; measured errors sit 10² to 10⁵ below them (the largest ratio
//! measured on `tests/accuracy_contract.rs`'s corpora is 1.5·10⁻²; [`Check::ratio`], and
//! `inertance bench` prints the largest ratio per output). The impulses are usually far
//! better than B_P's κ term: it is reached only when the rounding of the data hits the
//! nearly dependent direction head on, while the split between two contacts 10⁻⁸ apart is
//! formed from the difference of their wrenches, which the data give to ε‖E‖ absolutely.
//!
//! The bounds hold where the type keeps G of full rank: a float solve declares G singular
//! when a pivot is ≤ N·ε·max g_ii, which happens only for κ ≳ 1/(N ε).
//!
//! **Both routes.** A float solve takes the normal equations G x = b instead where G is well
//! conditioned ([`crate::impact::route`]): their own rounding, at most 2 a(N) θ ε V with
//! θ = 1/λ_min of G's correlation matrix (θ ≤ κ), fits within the share of c that
//! Gram–Schmidt's backward error takes above (2√N·16N), so the same bounds hold, with the
//! same constants, whichever route a problem takes.

//! # Systems of bodies
//!
//! The solve is written once over [`Mechanism`], and so is the measurement ([`Contracted`]): for
//! a system ([`System`]) G, Δ, the frames and the laws are one body's, ‖v‖_M is the kinetic
//! energy norm of the block-diagonal M (Σ_b 2T_b), κ = cond₂ G and ℓ keep their meaning, and
//! the bounds above are stated unchanged. What differs, and how the terms are taken:
//!
//! - **ℓ.** A contact's axis screw is its screw on the first body minus its screw on the
//!   second, each with the lever arm A − C_b formed in the solve by a subtraction: ‖|E|‖ sums
//!   both bodies' (in each body's free metric) with the arm's componentwise magnitudes
//!   |A_k| + |C_bk|, so a system placed far from the origin counts the cancellation in A − C.
//!   The subtraction's own rounding (½ε of |A_k| + |C_bk|) is not added to the 3 of η_E: that
//!   step is measured, not proved.
//! - **μ.** A forest of joints applies W by the articulated-body recursion
//!   ([`crate::mechanics::system`]'s `articulated`), an elimination of the mass matrix in the
//!   joints' own rates, M_q = Jᵀ η M J (each joint's free screws moving its child's subtree,
//!   six rates per root free of the ground); loops and redundant joints apply it densely:
//!   W{E} = W₀{E} − W₀ H λ with K λ = Hᵀ η W₀ {E},
//!   K = Hᵀ η W₀ H the Gram matrix of the joints' rows in the free metric, factored with
//!   pivoting ([`crate::mechanics::system::mobility`]). μ = max(cond₂ K̃, cond₂ M̃_q), each
//!   scaled to a unit diagonal, covers both paths (which one a float solve takes is its own
//!   decision). With cond₂ K̃ alone, the recursion's twist broke the bound by 8.7× (f64, a
//!   joint tree with masses 10^±6): the recursion's rounding follows M_q, not K. For the
//!   dense path: W{E}
//!   is the M-orthogonal projection of W₀{E} onto the admissible twists, so the accuracy of its
//!   application is that of a projection onto the span of the rows, which (as the contacts'
//!   projection above) is governed by the rows' conditioning, not by a basis of the admissible
//!   twists. μ is therefore cond₂ K̃, K̃ = K scaled to a unit diagonal (the rows' own lengths
//!   are immaterial to the projection) on a largest independent set of rows (a redundant row
//!   blocks nothing more); 1 for a free system, whose W₀ is applied body by body as one free
//!   body's. A derivation through the tree's LDLᵀ (or the pivoted dense factorization) that
//!   its backward error enters as μ does for a constrained body's M_red is not given: μ's place
//!   in c is measured, not proved. (cond₂ M_red in a basis D of the admissible twists, the
//!   one body's μ, depends on that basis, which the system never forms.)
//! - **Contact velocities.** A constrained body's float twist is D ξ, admissible by
//!   construction, so its error is seen along an axis through W: √g_ia. A system's float twist
//!   is W₀ applied to the wrench less the joints' impulses, which hold the joints only to
//!   rounding; its error need not be admissible, and |{E}ᵀ η δv| ≤ ({E}ᵀ η W₀ {E})^½ ‖δv‖_M
//!   (Cauchy–Schwarz in M, for every δv) gives the bound with g_ia replaced by the free bodies'
//!   inertance along the axis ([`Contracted::seen_inertance`]). With the constrained g_ia the
//!   bound failed on joint trees by up to 1.4·10⁸ (f64, a contact near a hinge: g_ia small, the
//!   error twist's violating part not): a term missing from the derivation, not a tolerance.
//!
//! Measured (`tests/system_accuracy.rs`, [`crate::tools::accuracy::system_rows`]: the system
//! examples and 60 seeded free systems and joint trees, masses over 10^±6, one in three nearly
//! singular): every ratio ≤ 1, the largest 7·10⁻³ (a twist, f64, on a joint tree), against
//! 2·10⁻² for one body. (With μ = cond₂ K̃ and the earlier block factorization along the
//! tree (Baraff 1996) the largest was 0.59.)

use num_traits::{One, Zero};

use crate::impact::mechanism::Mechanism;
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::mechanics::body::{Inertia, Mobility, RigidBody};
use crate::mechanics::constraint::complement;
use crate::mechanics::screw::{Screw, Screws, Vec3};
use crate::mechanics::system::{System, SystemScrew, about};
use crate::scalar::{Exact, Scalar};

use super::largest_eigenvalue;

/// What the contract asks of a mechanism, exactly solved, beyond its solve: its float
/// counterparts, the exact value of their screws, the magnitudes its axis screws are rounded
/// relative to (for ℓ), and μ (module docs). One body ([`Problem`]) and a system of bodies
/// ([`System`]) are measured by the same code.
pub trait Contracted: Mechanism<Exact> {
    /// The same mechanism in the float type `T`.
    type In<T: Scalar>: Mechanism<T>;

    /// The exact value of a screw of the float mechanism; `None` if not finite.
    fn exact<T: Scalar>(v: &<Self::In<T> as Mechanism<T>>::Screw) -> Option<Self::Screw>;

    /// ‖|E|‖ in the free metric ηM⁻¹ of the axis screw through contact `i` with direction
    /// `u`: the norm of its componentwise magnitudes, what its rounding is relative to.
    fn magnitude(&self, i: usize, u: &Vec3<Exact>) -> f64;

    /// μ ≥ 1, the accuracy to which the mobility W is applied (1 when free).
    fn metric(&self) -> f64;

    /// {E}ᵀ η W′ {E} for the axis screw {E}, W′ the mobility whose metric bounds how an error
    /// of the twist after impact shows along the axis, |{E}ᵀ η δv| ≤ ({E}ᵀ η W′ {E})^½ ‖δv‖_M
    /// (module docs, systems): W itself where the float twist is admissible by construction.
    fn seen_inertance(&self, e: &Self::Screw) -> Exact {
        e.reciprocal(&self.response(e))
    }
}

impl Contracted for Problem<Exact> {
    type In<T: Scalar> = Problem<T>;

    fn exact<T: Scalar>(v: &Screw<T>) -> Option<Screw<Exact>> {
        exact_screw(v)
    }

    fn magnitude(&self, i: usize, u: &Vec3<Exact>) -> f64 {
        magnitude_norm(self.body(), &self.contacts()[i].point, u)
    }

    /// cond₂ M_red (eq. 83) for a constrained body.
    fn metric(&self) -> f64 {
        self.constraints().map_or(1.0, |c| {
            let d = c.free.len();
            let m: Vec<f64> = (0..d * d)
                .map(|k| {
                    let momentum = self.body().momentum(&c.free[k % d]);
                    to_f64(&c.free[k / d].reciprocal(&momentum))
                })
                .collect();
            super::condition_number(&m, d)
        })
    }
}

impl Contracted for System<Exact> {
    type In<T: Scalar> = System<T>;

    fn exact<T: Scalar>(v: &SystemScrew<T>) -> Option<SystemScrew<Exact>> {
        v.0.iter()
            .map(exact_screw)
            .collect::<Option<_>>()
            .map(SystemScrew)
    }

    /// Over the (one or two) bodies the contact joins, each with its lever arm A − C_b formed
    /// in the solve by a subtraction: its components' magnitudes |A_k| + |C_bk|.
    fn magnitude(&self, i: usize, u: &Vec3<Exact>) -> f64 {
        let pair = self.pairs()[i];
        let point = &self.contacts()[i].point;
        let mut sum = 0.0;
        for b in std::iter::once(pair.first).chain(pair.second) {
            let body = &self.bodies()[b];
            let arm = Vec3::new(
                point[0].abs() + body.centre[0].abs(),
                point[1].abs() + body.centre[1].abs(),
                point[2].abs() + body.centre[2].abs(),
            );
            sum += magnitude_norm(&body.body, &arm, u).powi(2);
        }
        sum.sqrt()
    }

    /// W₀ = M⁻¹, the free bodies' mobility: the joints hold a float twist only to rounding
    /// (it is W₀ applied to the wrench less the joints' impulses, found by a solve), so its
    /// error need not be admissible, and Cauchy–Schwarz in the metric M bounds its velocity
    /// along {E} by ({E}ᵀ η M⁻¹ {E})^½ ‖δv‖_M, whatever its direction.
    fn seen_inertance(&self, e: &SystemScrew<Exact>) -> Exact {
        let mut sum = Exact::zero();
        for (body, x) in self.bodies().iter().zip(&e.0) {
            sum += x.reciprocal(&body.body.response(x));
        }
        sum
    }

    /// cond₂ K̃ (module docs, systems): the joints' rows H_k in the free metric, K = Hᵀ η W₀ H,
    /// scaled to a unit diagonal, on a largest independent set of rows (redundant rows block
    /// nothing more); 1 without joints.
    fn metric(&self) -> f64 {
        let bodies = self.bodies();
        let mut rows: Vec<Vec<(usize, Screw<Exact>)>> = Vec::new();
        for joint in self.joints() {
            for u in complement(&joint.joint.free_screws()) {
                let first = joint.pair.first;
                let mut row = vec![(first, about(&u, &bodies[first].centre))];
                if let Some(b) = joint.pair.second {
                    row.push((b, Screw(-about(&u, &bodies[b].centre).0)));
                }
                rows.push(row);
            }
        }
        let gram = |h: &[(usize, Screw<Exact>)], k: &[(usize, Screw<Exact>)]| -> Exact {
            let mut sum = Exact::zero();
            for (a, x) in h {
                for (b, y) in k {
                    if a == b {
                        sum += x.reciprocal(&bodies[*a].body.response(y));
                    }
                }
            }
            sum
        };
        // A largest independent set, greedily: a row is kept when K restricted to the kept
        // rows stays nonsingular (exactly).
        let mut kept: Vec<usize> = Vec::new();
        for k in 0..rows.len() {
            let mut trial = kept.clone();
            trial.push(k);
            let m = trial.len();
            let matrix: Vec<Exact> = (0..m * m)
                .map(|e| gram(&rows[trial[e / m]], &rows[trial[e % m]]))
                .collect();
            if crate::linalg::null_space(&matrix, m, m).0 == m {
                kept = trial;
            }
        }
        let m = kept.len();
        let diagonal: Vec<f64> = kept
            .iter()
            .map(|&k| to_f64(&gram(&rows[k], &rows[k])).sqrt())
            .collect();
        let matrix: Vec<f64> = (0..m * m)
            .map(|e| {
                to_f64(&gram(&rows[kept[e / m]], &rows[kept[e % m]]))
                    / (diagonal[e / m] * diagonal[e % m])
            })
            .collect();
        super::condition_number(&matrix, m).max(joint_space_condition(self))
    }
}

/// cond₂ M̃_q: the system's mass matrix in the joints' own rates, M_q = Jᵀ η M J, scaled to a
/// unit diagonal, for a forest of joints (1 otherwise, and without joints). A forest is solved
/// by the articulated-body recursion (`mechanics::system::articulated`), which is an
/// elimination of M_q in these coordinates — each joint's free screws, moving its child's
/// whole subtree, and six rates of each root free of the ground about its centre — so its
/// rounding grows with cond M̃_q as the dense path's does with cond K̃ ([`Contracted::metric`]
/// takes the larger: which path a float solve takes is its own decision).
fn joint_space_condition(system: &System<Exact>) -> f64 {
    let (bodies, joints) = (system.bodies(), system.joints());
    let b = bodies.len();
    if joints.is_empty() {
        return 1.0;
    }
    // The forest: each body's joint to its parent, found from the roots outwards.
    let mut parent: Vec<Option<usize>> = vec![None; b]; // the joint to the parent
    let mut placed = vec![false; b];
    let mut roots: Vec<(usize, Option<usize>)> = Vec::new(); // (body, its joint to the ground)
    for (j, joint) in joints.iter().enumerate() {
        if joint.pair.second.is_none() {
            let r = joint.pair.first;
            if placed[r] {
                return 1.0; // two joints to the ground on one body: a loop
            }
            placed[r] = true;
            roots.push((r, Some(j)));
        }
    }
    let mut used = vec![false; joints.len()];
    for &(_, j) in &roots {
        if let Some(j) = j {
            used[j] = true;
        }
    }
    let mut frontier: Vec<usize> = roots.iter().map(|&(r, _)| r).collect();
    loop {
        while let Some(x) = frontier.pop() {
            for (j, joint) in joints.iter().enumerate() {
                let (a, c) = (joint.pair.first, joint.pair.second);
                let other = match c {
                    Some(c) if a == x => c,
                    Some(c) if c == x => a,
                    _ => continue,
                };
                if used[j] {
                    continue;
                }
                used[j] = true;
                if placed[other] {
                    return 1.0; // a loop: the dense path answers
                }
                placed[other] = true;
                parent[other] = Some(j);
                frontier.push(other);
            }
        }
        match (0..b).find(|&i| !placed[i]) {
            Some(r) => {
                placed[r] = true;
                roots.push((r, None));
                frontier.push(r);
            }
            None => break,
        }
    }
    // The body whose joint to its parent (or the ground) is joint j, for each body its chain
    // of ancestors (itself included).
    let mut child_of = vec![usize::MAX; joints.len()];
    for (i, p) in parent.iter().enumerate() {
        if let Some(j) = p {
            child_of[*j] = i;
        }
    }
    for &(r, j) in &roots {
        if let Some(j) = j {
            child_of[j] = r;
        }
    }
    let root_of_tree = |mut i: usize| {
        while let Some(j) = parent[i] {
            let joint = &joints[j];
            i = if joint.pair.first == i {
                joint.pair.second.unwrap_or(i)
            } else {
                joint.pair.first
            };
        }
        i
    };
    let moves = |i: usize, top: usize| {
        // Whether body i is in the subtree of body `top`.
        let mut k = i;
        loop {
            if k == top {
                return true;
            }
            let Some(j) = parent[k] else { return false };
            let joint = &joints[j];
            k = if joint.pair.first == k {
                joint.pair.second.unwrap_or(k)
            } else {
                joint.pair.first
            };
        }
    };
    // The columns: a world screw (about the origin) and the bodies it moves.
    let mut columns: Vec<(Screw<Exact>, usize)> = Vec::new();
    for (j, joint) in joints.iter().enumerate() {
        for f in joint.joint.free_screws() {
            columns.push((f, child_of[j]));
        }
    }
    for &(r, j) in &roots {
        if j.is_none() {
            let c = &bodies[r].centre;
            for k in 0..6 {
                let mut e = Screw::<Exact>::zero();
                e.0[k] = Exact::one();
                // A unit twist of the root about its centre, written about the origin.
                columns.push((Screw::new(e.top(), e.bottom() + c.cross(&e.top())), r));
            }
        }
    }
    let n = columns.len();
    let column = |k: usize, i: usize| -> Option<Screw<Exact>> {
        let (s, top) = &columns[k];
        (root_of_tree(i) == root_of_tree(*top) && moves(i, *top))
            .then(|| about(s, &bodies[i].centre))
    };
    let entry = |k: usize, l: usize| -> Exact {
        let mut sum = Exact::zero();
        for (i, body) in bodies.iter().enumerate() {
            if let (Some(x), Some(y)) = (column(k, i), column(l, i)) {
                sum += x.reciprocal(&body.body.momentum(&y));
            }
        }
        sum
    };
    let diagonal: Vec<f64> = (0..n).map(|k| to_f64(&entry(k, k)).sqrt()).collect();
    if diagonal.iter().any(|d| !(d.is_finite() && *d > 0.0)) {
        return 1.0;
    }
    let matrix: Vec<f64> = (0..n * n)
        .map(|e| to_f64(&entry(e / n, e % n)) / (diagonal[e / n] * diagonal[e % n]))
        .collect();
    super::condition_number(&matrix, n)
}

/// The outputs the contract covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// P_i.
    Impulses,
    /// {v} = [ω; v_C] after impact.
    Twist,
    /// v_ix, v_iy, v_iz after impact.
    ContactVelocities,
    /// E_p.
    LostVelocityEnergy,
    /// ΔE_c.
    KineticEnergyLoss,
}

impl Output {
    /// Every output, in report order.
    pub const ALL: [Output; 5] = [
        Output::Impulses,
        Output::Twist,
        Output::ContactVelocities,
        Output::LostVelocityEnergy,
        Output::KineticEnergyLoss,
    ];

    /// The name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Output::Impulses => "impulses",
            Output::Twist => "twist",
            Output::ContactVelocities => "contact velocities",
            Output::LostVelocityEnergy => "E_p",
            Output::KineticEnergyLoss => "ΔE_c",
        }
    }

    /// The bound's form, as the module docs state it.
    pub fn bound_text(self) -> &'static str {
        match self {
            Output::Impulses => "‖δP‖₂ ≤ 4cε(√κ‖P‖₂ + κV/√λ_max)",
            Output::Twist => "‖δv‖_M ≤ B_v = cε(√κV + 4δk κ‖v⁰‖_M)",
            Output::ContactVelocities => "|δv_ia| ≤ √g_ia B_v + 4ε s_ia V",
            Output::LostVelocityEnergy => "|δE_p| ≤ ‖Δv‖_M B_v + ½B_v² + NεE_p",
            Output::KineticEnergyLoss => "|δΔE_c| ≤ 3V B_v + (3/2)B_v² + NεV²",
        }
    }
}

/// One output's measured error and its bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Check {
    /// The measured error (in the output's norm, see the module docs).
    pub error: f64,
    /// The contract's bound.
    pub bound: f64,
}

impl Check {
    /// error / bound: at most 1 when the contract holds (0 when both vanish).
    pub fn ratio(&self) -> f64 {
        if self.error == 0.0 {
            0.0
        } else {
            self.error / self.bound
        }
    }
}

/// What the bounds of one exactly solved problem are made of (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Conditioning {
    /// κ = cond₂ G (physical, unit normals).
    pub cond: f64,
    /// λ_max(G).
    pub lambda_max: f64,
    /// ℓ ≥ 1, the cancellation in the axis screws.
    pub lever: f64,
    /// μ = cond₂ M_red (1 for a free body).
    pub metric: f64,
    /// N.
    pub contacts: usize,
}

impl Conditioning {
    /// The conditioning of an exactly assembled problem; `None` when G is singular.
    pub fn of<M: Contracted>(impact: &mut Impact<Exact, M>) -> Option<Self> {
        let n = impact.contacts();
        if impact.singular() {
            return None;
        }
        let norm: Vec<f64> = impact
            .frames()
            .iter()
            .map(|f| to_f64(&f.norm2[0]).sqrt())
            .collect();
        let g: Vec<f64> = (0..n * n)
            .map(|k| to_f64(&impact.g_hat()[k]) / (norm[k / n] * norm[k % n]))
            .collect();
        // G⁻¹ exactly, then rounded: its eigenvalues are accurate however large κ is.
        let mut inv = vec![0.0; n * n];
        for j in 0..n {
            let mut col: Vec<Exact> = (0..n)
                .map(|i| if i == j { Exact::one() } else { Exact::zero() })
                .collect();
            impact.solve_system(&mut col);
            for (i, x) in col.iter().enumerate() {
                inv[i * n + j] = to_f64(x) * norm[i] * norm[j];
            }
        }
        let lambda_max = largest_eigenvalue(&g, n);
        let problem = impact.problem();
        let lever = impact
            .frames()
            .iter()
            .enumerate()
            .map(|(j, f)| {
                let own = to_f64(&impact.g_hat()[j * n + j]).sqrt();
                problem.magnitude(j, &f.directions[0]) / own
            })
            .fold(1.0, f64::max);
        let metric = problem.metric();
        Some(Conditioning {
            cond: lambda_max * largest_eigenvalue(&inv, n),
            lambda_max,
            lever,
            metric,
            contacts: n,
        })
    }

    /// c = μ (2 √N (3ℓ + 16N) + 1).
    pub fn constant(&self) -> f64 {
        let n = self.contacts as f64;
        self.metric * (2.0 * n.sqrt() * (3.0 * self.lever + 16.0 * n) + 1.0)
    }
}

/// ‖|E|‖ in the free-body metric η M⁻¹: the norm of the componentwise magnitudes of the axis
/// screw E = [u; r × u] through the point `r` with direction `u`, (r × u)_a's magnitude being
/// |r_b u_c| + |r_c u_b| (what its rounding is relative to). With a full inertia tensor the
/// moment part is bounded by |·|²/λ_min(J), which a componentwise bound does imply.
fn magnitude_norm(body: &RigidBody<Exact>, r: &Vec3<Exact>, u: &Vec3<Exact>) -> f64 {
    let mut s = 0.0;
    let mut moment = [0.0; 3];
    for a in 0..3 {
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        let m = (&r[b] * &u[c]).abs() + (&r[c] * &u[b]).abs();
        s += to_f64(&(&u[a] * &u[a] / &body.mass));
        moment[a] = match &body.inertia {
            Inertia::Principal(j) => to_f64(&(&m * &m / &j[a])),
            Inertia::Tensor(_) => to_f64(&(&m * &m)),
        };
    }
    s + match &body.inertia {
        Inertia::Principal(_) => moment.iter().sum::<f64>(),
        Inertia::Tensor(t) => {
            let j = t.matrix().map(|x| to_f64(&x));
            let smallest = j
                .symmetric_eigenvalues()
                .iter()
                .cloned()
                .fold(f64::INFINITY, f64::min);
            moment.iter().sum::<f64>() / smallest
        }
    }
    .sqrt()
}

/// The nearest f64 to an exact value.
fn to_f64(x: &Exact) -> f64 {
    Scalar::to_f64(x)
}

/// ‖v‖_M = (2 T(v))^½ of an exact twist.
pub fn energy_norm(body: &RigidBody<Exact>, v: &Screw<Exact>) -> f64 {
    (2.0 * to_f64(&body.kinetic_energy(v))).sqrt()
}

/// ‖v‖_M = (2 T(v))^½ of an exact twist of `mechanism` (for a system, M block-diagonal).
fn mechanism_norm<M: Mechanism<Exact>>(mechanism: &M, v: &M::Screw) -> f64 {
    (2.0 * to_f64(&mechanism.kinetic_energy(v))).sqrt()
}

/// (‖v⁰‖_M, ‖Δv‖_M) of an exact outcome on `exact`: V is their sum.
pub fn speeds<M: Mechanism<Exact>>(
    exact: &Impact<Exact, M>,
    out: &Outcome<Exact, M::Screw>,
) -> (f64, f64) {
    let problem = exact.problem();
    let mut dv = out.velocity.clone();
    dv.add_scaled(&-Exact::one(), problem.velocity());
    (
        mechanism_norm(problem, problem.velocity()),
        mechanism_norm(problem, &dv),
    )
}

/// The exact value of a float twist; `None` if not finite.
fn exact_screw<T: Scalar>(v: &Screw<T>) -> Option<Screw<Exact>> {
    let mut out = Screw::zero();
    for k in 0..6 {
        out.0[k] = Exact::from(v.0[k].exact_value()?);
    }
    Some(out)
}

/// The contract's bounds on the impulses, the twist and the energies of a float solve of
/// `model` with unit roundoff `eps` (module docs), from the exact solve, with the speeds they
/// are built from. (The contact velocities' bounds are per axis: [`measure`].)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// B_P, on ‖δP‖₂ of the physical impulses P_i = P̂_i |n_i|.
    pub impulses: f64,
    /// B_v, on ‖δv‖_M of the twist after impact.
    pub twist: f64,
    /// On |δE_p|: ‖Δv‖_M B_v + ½ B_v² + N ε E_p.
    pub lost_velocity_energy: f64,
    /// On |δΔE_c|: 3 V B_v + (3/2) B_v² + N ε V².
    pub kinetic_energy_loss: f64,
    /// ‖v⁰‖_M ([`speeds`]).
    pub v0: f64,
    /// ‖Δv‖_M ([`speeds`]).
    pub dv: f64,
}

impl Bounds {
    /// The bounds for `exact` solved into `exact_out`, conditioned as `cond`.
    pub fn of<M: Mechanism<Exact>>(
        exact: &Impact<Exact, M>,
        cond: &Conditioning,
        model: Model,
        exact_out: &Outcome<Exact, M::Screw>,
        eps: f64,
    ) -> Bounds {
        let (v0, dv) = speeds(exact, exact_out);
        let speed = v0 + dv;
        // Poisson with unequal k: half the spread of the k_i (module docs).
        let spread = match model {
            Model::Newton => 0.0,
            Model::Poisson => {
                let (lo, hi) = exact
                    .problem()
                    .contacts()
                    .iter()
                    .map(|c| to_f64(&c.k_poisson))
                    .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
                (hi - lo) / 2.0
            }
        };
        let c = cond.constant();
        let mut size2 = Exact::zero();
        for (i, f) in exact.frames().iter().enumerate() {
            size2 += &exact_out.impulses_hat[i] * &exact_out.impulses_hat[i] * &f.norm2[0];
        }
        let twist = c * eps * (cond.cond.sqrt() * speed + 4.0 * spread * cond.cond * v0);
        let n = exact.contacts() as f64;
        Bounds {
            impulses: 4.0
                * c
                * eps
                * (cond.cond.sqrt() * to_f64(&size2).sqrt()
                    + cond.cond * speed / cond.lambda_max.sqrt()),
            twist,
            lost_velocity_energy: dv * twist
                + 0.5 * twist * twist
                + n * eps * to_f64(&exact_out.lost_velocity_energy),
            kinetic_energy_loss: 3.0 * speed * twist
                + 1.5 * twist * twist
                + n * eps * speed * speed,
            v0,
            dv,
        }
    }
}

/// Measure `out`, a float solve of `model` (on `float`, the same problem rounded into `T`),
/// against `exact_out` (on `exact`, with conditioning `cond`): one [`Check`] per [`Output`],
/// in [`Output::ALL`] order. `None` when a float output is not finite.
pub fn measure<M: Contracted, T: Scalar>(
    exact: &Impact<Exact, M>,
    cond: &Conditioning,
    model: Model,
    exact_out: &Outcome<Exact, M::Screw>,
    float: &Impact<T, M::In<T>>,
    out: &Outcome<T, <M::In<T> as Mechanism<T>>::Screw>,
) -> Option<[Check; 5]> {
    let eps = T::epsilon_f64();
    let problem = exact.problem();
    let bounds = Bounds::of(exact, cond, model, exact_out, eps);
    let (speed, b_v) = (bounds.v0 + bounds.dv, bounds.twist);

    // Impulses, physical: P_i = P̂_i |n_i|.
    let mut diff2 = Exact::zero();
    for (i, f) in exact.frames().iter().enumerate() {
        let d = Exact::from(out.impulses_hat[i].exact_value()?) - &exact_out.impulses_hat[i];
        diff2 += &d * &d * &f.norm2[0];
    }
    let impulses = Check {
        error: to_f64(&diff2).sqrt(),
        bound: bounds.impulses,
    };

    let velocity = M::exact::<T>(&out.velocity)?;
    let mut twist_error = velocity.clone();
    twist_error.add_scaled(&-Exact::one(), &exact_out.velocity);
    let twist = Check {
        error: mechanism_norm(problem, &twist_error),
        bound: b_v,
    };

    // Contact velocities, on the float solve's own frame (its axes as the exact values of the
    // rounded ones): the solver is measured, not the choice of tangent.
    let mut contact = Check {
        error: 0.0,
        bound: 1.0,
    };
    for (i, f) in float.frames().iter().enumerate() {
        for a in 0..3 {
            let axis = M::exact::<T>(&f.axes[a])?;
            let d = &f.directions[a];
            let direction = Vec3::new(
                Exact::from(d[0].exact_value()?),
                Exact::from(d[1].exact_value()?),
                Exact::from(d[2].exact_value()?),
            );
            let unit2: Exact = direction.iter().map(|x| x * x).sum();
            let unit = to_f64(&unit2).sqrt();
            let reference = axis.reciprocal(&exact_out.velocity);
            let error =
                to_f64(&(Exact::from(out.after_hat[i][a].exact_value()?) - reference).abs()) / unit;
            let g = to_f64(&(problem.seen_inertance(&axis) / &unit2));
            let bound = g.max(0.0).sqrt() * b_v
                + 4.0 * eps * problem.magnitude(i, &direction) / unit * speed;
            let check = Check { error, bound };
            if check.ratio() >= contact.ratio() {
                contact = check;
            }
        }
    }

    let err = |x: &T, e: &Exact| -> Option<f64> {
        Some(to_f64(&(Exact::from(x.exact_value()?) - e).abs()))
    };
    let lost = Check {
        error: err(&out.lost_velocity_energy, &exact_out.lost_velocity_energy)?,
        bound: bounds.lost_velocity_energy,
    };
    let loss = Check {
        error: err(&out.kinetic_energy_loss, &exact_out.kinetic_energy_loss)?,
        bound: bounds.kinetic_energy_loss,
    };
    Some([impulses, twist, contact, lost, loss])
}
