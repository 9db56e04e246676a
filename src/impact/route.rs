//! Which route a float solve takes: the normal equations G x = b, or the contact wrenches
//! orthogonalised in the metric ηW ([`crate::impact::gram_schmidt`]).
//!
//! Both meet the accuracy contract ([`crate::analysis::accuracy`]) when G is well
//! conditioned; only the orthogonalised wrenches meet it near a singular G, and they cost more
//! (Example 3 in f64, assemble + both models: 3,960 instructions against 2,900, callgrind). So
//! each problem is routed once, when it is assembled, by a cheap and rigorous bound on its
//! conditioning. Exact types always solve G x = b: there both routes give the same numbers.
//!
//! # What the normal equations add to the error
//!
//! Notation of [`crate::analysis::accuracy`] (ε, κ = cond₂ G, ‖·‖_M, Δv, V, c); with
//! S = diag(ĝ_ii^½), let C = S⁻¹ Ĝ S⁻¹ be the correlation matrix of the contact wrenches
//! (unit diagonal, the same for hatted and unit normals) and θ = 1/λ_min(C). Each operation
//! rounds by at most ε/2, the model the contract's constants are derived in. Beyond the
//! rounding of the data, which both routes share, the normal equations round
//!
//! 1. the inertances ĝ_ij = {Ê_i}ᵀ η {W Ê_j}, six products summed: |δĝ_ij| ≤ 3ε Σ|Ê_i| |W Ê_j|
//!    ≤ 3ε (ĝ_ii ĝ_jj)^½ by Cauchy–Schwarz in the metric η M⁻¹, diagonal for a free body in
//!    principal axes (and so for the tangential inertances ĝ_ij,ax);
//! 2. the pivoted LDLᵀ and its solve, backward stable with (Ĝ + ΔG) P̂ = b,
//!    |ΔG| ≤ (3N + 1)(ε/2) |L||D||Lᵀ| (Higham, *Accuracy and Stability of Numerical
//!    Algorithms*, Thm 10.4, written without square roots), and (|L||D||Lᵀ|)_ij ≤ (ĝ_ii ĝ_jj)^½
//!    by Cauchy–Schwarz on the rows of L D^½;
//! 3. the sums over the contacts {v} − {v⁰} = −Σ P̂_j W Ê_j and v̂_ia = v̂⁰_ia − Σ_j ĝ_ij,ax P̂_j
//!    (eq. 24–26), each term relative to |P̂_j| ĝ_jj^½.
//!
//! 1 and 2 are one perturbation δĜ = S Γ S with |Γ_ij| ≤ γ = (3N + 7) ε/2, so ‖Γ‖₂ ≤ N γ.
//! With P̂ᵀ Ĝ P̂ = ‖Δv‖²_M ≥ ‖S P̂‖²/θ, the twist moves by
//!
//! ```text
//! ‖W Ê δP̂‖_M = ‖Ĝ^(−½) δĜ P̂‖₂ = ‖C^(−½) Γ S P̂‖₂ ≤ N γ θ ‖Δv‖_M
//! ```
//!
//! and 3 adds (N + 7)(ε/2) Σ_j |P̂_j| ĝ_jj^½ ≤ (N + 7)(ε/2) (N θ)^½ ‖Δv‖_M per unit √g_ia to
//! a contact velocity (less to the twist). With θ ≥ 1 the normal equations' own error is at
//! most a(N) θ ε ‖Δv‖_M in the twist's norm, a(N) = (N(3N + 7) + √N(N + 7))/2, for Newton.
//! Poisson rounds the compression impulses P̂^c instead and multiplies them by 1 + K: the same
//! steps give (1 + k̄) a(N) θ ε ‖Δv_c‖_M plus the split term below, and ‖Δv_c‖_M ≤ ‖v⁰‖_M
//! (a projection of −v⁰), 1 + k̄ ≤ 2. So for both models the own error is at most
//! 2 a(N) θ ε V, plus roundings of order εV the orthogonal route does not make (forming Δv
//! from {v}, the sums over v̂⁰_ia), at most 4εV for N ≤ 6.
//!
//! # The threshold
//!
//! The contract's constant c = μ(2√N(3ℓ + 16N) + 1) budgets 2√N·3ℓ for the rounding of the
//! data, the same in both routes, and 2√N·16N = 32N^{3/2} for Gram–Schmidt's backward error,
//! which the normal equations do not incur. θ ≤ κ (λ_min(C) ≥ λ_min(G)/max g_ii ≥ 1/κ, for
//! any scaling of the normals, C being the same), so √κ ≥ √θ, and they meet the twist's bound
//! cε(√κ V + …) when 2 a(N) θ + 4 ≤ 32 N^{3/2} √θ, that is, for t = √θ between the roots of
//! 2a t² − 32N^{3/2} t + 4,
//!
//! ```text
//! θ ≤ θ*(N) = ((16 N^{3/2} + (256 N³ − 8a)^½) / (2a))²  = 2.70, 5.25, 6.36, 6.74, 6.78, 6.64
//! ```
//!
//! for N = 1 … 6 (θ ≥ 1 always meets the lower root), and then every other bound too, each
//! of which is the twist's error carried through: a contact velocity's (√g_ia times it, item 3
//! included in a(N)); E_p's (‖Δv‖_M times it: E_p is formed from the computed Δv); ΔE_c's,
//! ½ Σ P̂_i (v̂⁰_ix + v̂_ix) = −½⟨Δv, v⁰ + v⟩_M, moves by at most ½(2V + V) times it, within
//! its 3V·B_v. The impulses move by ‖S⁻¹ C⁻¹ Γ S P‖₂ ≤ √κ N γ θ ‖P‖₂ (unit normals, S² ≤ λ_max,
//! S⁻² ≤ 1/λ_min), twice that for Poisson's (1 + K) P^c with ‖P^c‖₂ ≤ ‖P‖₂, within the
//! 4·32N^{3/2} ε √κ ‖P‖₂ of B_P as N(3N + 7)θ ≤ 128 N^{3/2} for θ ≤ θ*(N). Poisson's split term −W Ê (K − k̄) δP̂^c moves the twist by at most
//! δk λ_max(C)^½ N γ θ^{3/2} ‖v⁰‖_M ≤ δk √κ N γ θ^{3/2} ‖v⁰‖_M (λ_max(C) ≤ λ_max(G)/min g_ii
//! ≤ κ), within the contract's 4·32N^{3/2} ε δk κ ‖v⁰‖_M by the same inequality and √θ ≤ √κ
//! (N(3N + 7)θ/2 ≤ 128 N^{3/2}).
//! For these θ both routes meet every bound; beyond, only the orthogonalised wrenches are
//! guaranteed to.
//!
//! # The estimate
//!
//! Gershgorin's theorem on C gives λ_min(C) ≥ 1 − s with s = max_i Σ_{j≠i} |ĝ_ij|/(ĝ_ii ĝ_jj)^½,
//! so θ ≤ 1/(1 − s), and the normal equations are taken when s ≤ s*(N) = 1 − 1/θ*(N)
//! ([`correlation_limit`]: 0.809 for two contacts, 0.84 to 0.85 for three to six; one contact
//! has s = 0). For N = 2 the estimate is exact (λ_min(C) = 1 − |c_12|): two contacts take the
//! normal equations when the cosine of their wrenches in the metric ηW is at most 0.809 in
//! magnitude (cond₂ C ≤ 9.5), Example 3's is 0.19. It costs O(N²) on Ĝ, before the
//! factorization and without it; it is evaluated in f64 (the value of a double-double or a
//! dual number), whose relative error of about 10⁻¹⁶ is nothing beside the slack of the
//! bounds.
//!
//! Item 1's Cauchy–Schwarz needs the diagonal metric of a free body in principal axes. A full
//! inertia tensor multiplies items 1 and 3 by up to (cond J)^½, and constraints bring ℓ and μ
//! into them; neither is known from the assembled data without more work, so those problems
//! keep the orthogonalised wrenches.

use crate::impact::problem::Problem;
use crate::mechanics::inertia::Inertia;
use crate::scalar::Scalar;

/// How a solve computes its outputs from the assembled problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// The impulses from G x = b by the pivoted LDLᵀ of G, every other output from them
    /// (eq. 24–32): exact types, and float types where G is well conditioned (module docs).
    NormalEquations,
    /// Every output from the contact wrenches orthogonalised in ηW
    /// ([`crate::impact::gram_schmidt`]).
    OrthogonalWrenches,
}

/// s*(N) = 1 − 1/θ*(N) for N = 1 … 6 (module docs), rounded down to three decimals; index 0
/// is unused. Beyond six contacts G cannot have full rank.
const LIMITS: [f64; 7] = [0.0, 0.629, 0.809, 0.842, 0.851, 0.852, 0.849];

/// θ*(N) = ((16 N^{3/2} + (256 N³ − 8a)^½)/(2a))², a = a(N) = (N(3N + 7) + √N(N + 7))/2:
/// the largest θ = 1/λ_min(C) for which the normal equations meet every bound of the
/// contract (module docs).
pub fn theta_limit(n: usize) -> f64 {
    let n = n as f64;
    let a = (n * (3.0 * n + 7.0) + n.sqrt() * (n + 7.0)) / 2.0;
    let t = (16.0 * n * n.sqrt() + (256.0 * n * n * n - 8.0 * a).sqrt()) / (2.0 * a);
    t * t
}

/// s*(N): the largest Gershgorin row sum s of the correlation matrix C for which N contacts
/// take the normal equations (0 for N > 6, where G is never of full rank).
pub fn correlation_limit(n: usize) -> f64 {
    LIMITS.get(n).copied().unwrap_or(0.0)
}

/// s = max_i Σ_{j≠i} |ĝ_ij| / (ĝ_ii ĝ_jj)^½ for the `n`×`n` row-major Ĝ, in f64; infinite when
/// a diagonal entry is not positive. λ_min(C) ≥ 1 − s (Gershgorin).
pub fn correlation<T: Scalar>(g_hat: &[T], n: usize) -> f64 {
    let g = |i: usize, j: usize| g_hat[i * n + j].to_f64();
    let mut s = 0f64;
    for i in 0..n {
        let mut row = 0.0;
        for j in (0..n).filter(|&j| j != i) {
            row += g(i, j).abs() / (g(i, i) * g(j, j)).sqrt();
        }
        if g(i, i) <= 0.0 || g(i, i).is_nan() || row.is_nan() {
            return f64::INFINITY;
        }
        s = s.max(row);
    }
    s
}

/// The route a solve of `problem`, whose inertance matrix is the `n`×`n` row-major `g_hat`,
/// takes: the normal equations for exact types, and for a free body in principal axes whose
/// Gershgorin estimate s is at most [`correlation_limit`]; the orthogonalised wrenches
/// otherwise.
pub fn route<T: Scalar>(problem: &Problem<T>, g_hat: &[T], n: usize) -> Route {
    if T::IS_EXACT {
        return Route::NormalEquations;
    }
    let principal = matches!(problem.body().inertia, Inertia::Principal(_));
    if problem.constraints().is_none() && principal && well_conditioned(g_hat, n) {
        Route::NormalEquations
    } else {
        Route::OrthogonalWrenches
    }
}

/// s ≤ s*(N), with N = 1 and 2 written out: one contact is always well conditioned, and two
/// compare ĝ_12² ≤ s*² ĝ_11 ĝ_22 without a square root (false when that product is not a
/// normal f64, so an overflow cannot pass the test).
pub(crate) fn well_conditioned<T: Scalar>(g_hat: &[T], n: usize) -> bool {
    match n {
        1 => true,
        2 => {
            let (a, b, c) = (g_hat[0].to_f64(), g_hat[3].to_f64(), g_hat[1].to_f64());
            let limit = LIMITS[2] * LIMITS[2] * a * b;
            limit.is_normal() && limit > 0.0 && c * c <= limit
        }
        _ => correlation(g_hat, n) <= correlation_limit(n),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table is s*(N) = 1 − 1/θ*(N) rounded down, never above it.
    #[test]
    fn the_limits_are_the_derived_ones_rounded_down() {
        for n in 1..=6 {
            let exact = 1.0 - 1.0 / theta_limit(n);
            let table = correlation_limit(n);
            assert!(table <= exact && exact - table < 1e-3, "N = {n}");
        }
        assert_eq!(correlation_limit(7), 0.0);
        // The values the docs state.
        let theta: Vec<String> = (1..=6).map(|n| format!("{:.2}", theta_limit(n))).collect();
        assert_eq!(theta, ["2.70", "5.25", "6.36", "6.74", "6.78", "6.64"]);
    }

    /// For two contacts Gershgorin is exact: 1/(1 − |c_12|) = 1/λ_min(C).
    #[test]
    fn two_contacts_switch_at_the_derived_correlation() {
        // C = [1 c; c 1] scaled by diag(2, 1/2) (hatted normals): the test is scale free.
        let g = |c: f64| [4.0, c, c, 0.25];
        assert!(well_conditioned(&g(0.809), 2));
        assert!(!well_conditioned(&g(0.810), 2));
        assert!(well_conditioned(&g(-0.5), 2));
        assert_eq!(correlation(&g(0.5), 2), 0.5);
        assert!(well_conditioned(&[1e-3f64], 1));
    }

    /// Three contacts: the row sums decide; a singular G is never well conditioned.
    #[test]
    fn row_sums_decide_for_more_contacts() {
        let g = |c: f64| [1.0, c, c, c, 1.0, c, c, c, 1.0];
        assert!(well_conditioned(&g(0.42), 3));
        assert!(!well_conditioned(&g(0.43), 3));
        assert!(!well_conditioned(&g(1.0), 3));
        assert_eq!(correlation(&[0.0, 0.0, 0.0, 1.0], 2), f64::INFINITY);
    }
}
