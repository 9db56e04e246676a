//! The N = 2 kernel: two contacts (the paper's case, Example 3's class) at L lanes, every
//! intermediate a named `Lanes<L>` value, so that inside the function `pulp` compiles for
//! AVX-512 or AVX2 each one can live in a vector register.
//!
//! The field-generic lean code run on lanes ([`crate::impact::lean`] over `Lanes<L>`) keeps
//! its arrays — axes, responses, Ĝ, L — in memory, and at eight lanes half its time went to
//! moving them between registers and the stack (module docs of [`super`]). Here the same
//! arithmetic is written out for N = 2, operation by operation in the lean path's order:
//!
//! ```text
//! μ_j = r_j × n_j,   {Ê_j} = [n_j; μ_j]                                 (eq. 3–4)
//! W{Ê_j} = [μ_j,k · (1/J_k); n_j · (1/m)]                               (eq. 9, 11)
//! ĝ_ij = {Ê_i}ᵀ η W{Ê_j},   v̂_jx⁰ = {Ê_j}ᵀ η {v⁰}                        (eq. 8, 12)
//! d₁ = ĝ₁₁,  l₂₁ = ĝ₂₁ · (1/d₁),  d₂ = ĝ₂₂ − (l₂₁ l₂₁) d₁                 (Ĝ = L D Lᵀ)
//! Newton: b_j = (1 + k_j^N) v̂_jx⁰;  Poisson: b_j = v̂_jx⁰                  (eq. 15, 20–21)
//! y₂ = b₂ − l₂₁ b₁;  z_j = y_j · (1/d_j);  P̂₁ = z₁ − l₂₁ z₂,  P̂₂ = z₂
//! Poisson: P̂_j ← P̂_j (1 + k_j^P)                                        (eq. 23)
//! {v} = {v⁰} + (−P̂₁) W{Ê₁} + (−P̂₂) W{Ê₂}                                (eq. 24)
//! ```
//!
//! Every line is the lean path's operation sequence for N = 2 (same operands, same order, no
//! fused multiply-add), so each lane equals [`crate::impact::lean::Lean`]'s answer for its
//! scene bit for bit; tested against the lean path and against the generic lane code at every
//! width ([`super::tests`]). The route test is [`crate::impact::lean::route_test`]'s for
//! N = 2 on lanes: d₁ > 0, d₂ > 0, d₂ ≥ (1 − s*(2)²) ĝ₂₂.

use num_traits::Zero;

use super::Scenes;
use super::lanes::{Lanes, Mask};
use super::sweep::{Kernel, load, load3, load6, valid_parts};
use crate::impact::lean::{LeanError, limit2, route_test};
use crate::impact::restitution::Model;

/// One contact's screw and response at L lanes.
#[derive(Clone, Copy)]
struct Contact<const L: usize> {
    /// {Ê_j} = [n_j; r_j × n_j].
    axis: [Lanes<L>; 6],
    /// W{Ê_j}.
    response: [Lanes<L>; 6],
}

/// Two-contact scenes `start .. start + L`, assembled and factored (module docs).
pub(super) struct Pair<const L: usize> {
    valid: Mask<L>,
    velocity: [Lanes<L>; 6],
    w1: [Lanes<L>; 6],
    w2: [Lanes<L>; 6],
    b1: Lanes<L>,
    b2: Lanes<L>,
    g11: Lanes<L>,
    g21: Lanes<L>,
    g22: Lanes<L>,
    d1: Lanes<L>,
    d2: Lanes<L>,
    l21: Lanes<L>,
    d1_inv: Lanes<L>,
    d2_inv: Lanes<L>,
    k_newton: [Lanes<L>; 2],
    k_poisson: [Lanes<L>; 2],
}

/// {a}ᵀ η {b} in [`crate::mechanics::screw::Screw::reciprocal`]'s order (eq. 6).
#[inline(always)]
fn reciprocal<const L: usize>(a: &[Lanes<L>; 6], b: &[Lanes<L>; 6]) -> Lanes<L> {
    let mut s = a[0] * b[3];
    s += a[3] * b[0];
    s += a[1] * b[4];
    s += a[4] * b[1];
    s += a[2] * b[5];
    s += a[5] * b[2];
    s
}

/// Contact j's axis screw and response from r, n, 1/J_k and 1/m (module docs).
#[inline(always)]
fn contact<const L: usize>(
    r: [Lanes<L>; 3],
    n: [Lanes<L>; 3],
    inv_moments: [Lanes<L>; 3],
    inv_mass: Lanes<L>,
) -> Contact<L> {
    let mu = [
        r[1] * n[2] - r[2] * n[1],
        r[2] * n[0] - r[0] * n[2],
        r[0] * n[1] - r[1] * n[0],
    ];
    Contact {
        axis: [n[0], n[1], n[2], mu[0], mu[1], mu[2]],
        response: [
            mu[0] * inv_moments[0],
            mu[1] * inv_moments[1],
            mu[2] * inv_moments[2],
            n[0] * inv_mass,
            n[1] * inv_mass,
            n[2] * inv_mass,
        ],
    }
}

/// 1/d, or 0 in every lane when every lane of d is 0 (the lean factorization's rule).
#[inline(always)]
fn inverse<const L: usize>(d: Lanes<L>) -> Lanes<L> {
    if d.is_zero() {
        Lanes::splat(0.0)
    } else {
        Lanes::splat(1.0) / d
    }
}

impl<const L: usize, const N: usize> Kernel<L, N> for Pair<L> {
    /// Scenes `start .. start + L` of `scenes` (past the end, the last repeated), which has
    /// N = 2 contacts: read, checked and factored.
    #[inline(always)]
    fn read<const WHOLE: bool>(scenes: &Scenes<N>, start: usize) -> Self {
        debug_assert_eq!(N, 2);
        // Direct calls, not closures: a closure here was not inlined, and each lane came back
        // through memory.
        let mass = load::<L, WHOLE>(&scenes.mass, start);
        let moments = load3::<L, WHOLE>(&scenes.inertia, start);
        let velocity = load6::<L, WHOLE>(&scenes.velocity, start);
        let r1 = load3::<L, WHOLE>(&scenes.points[0], start);
        let r2 = load3::<L, WHOLE>(&scenes.points[1], start);
        let n1 = load3::<L, WHOLE>(&scenes.normals[0], start);
        let n2 = load3::<L, WHOLE>(&scenes.normals[1], start);
        let k_newton = [
            load::<L, WHOLE>(&scenes.k_newton[0], start),
            load::<L, WHOLE>(&scenes.k_newton[1], start),
        ];
        let k_poisson = [
            load::<L, WHOLE>(&scenes.k_poisson[0], start),
            load::<L, WHOLE>(&scenes.k_poisson[1], start),
        ];
        // The hot loop's whole chunks take the sufficient test, the fallback the exact one.
        let valid = valid_parts::<L, 2, WHOLE>(
            &mass,
            &moments,
            &velocity,
            &[r1, r2],
            &[n1, n2],
            &k_newton,
            &k_poisson,
        );
        let one = Lanes::splat(1.0);
        let inv_mass = one / mass;
        let inv_moments = [one / moments[0], one / moments[1], one / moments[2]];
        let c1 = contact(r1, n1, inv_moments, inv_mass);
        let c2 = contact(r2, n2, inv_moments, inv_mass);
        let b1 = reciprocal(&c1.axis, &velocity);
        let b2 = reciprocal(&c2.axis, &velocity);
        let g11 = reciprocal(&c1.axis, &c1.response);
        let g21 = reciprocal(&c2.axis, &c1.response);
        let g22 = reciprocal(&c2.axis, &c2.response);
        let d1 = g11;
        let d1_inv = inverse(d1);
        let l21 = g21 * d1_inv;
        let mut d2 = g22;
        d2 -= l21 * l21 * d1;
        let d2_inv = inverse(d2);
        Pair {
            valid,
            velocity,
            w1: c1.response,
            w2: c2.response,
            b1,
            b2,
            g11,
            g21,
            g22,
            d1,
            d2,
            l21,
            d1_inv,
            d2_inv,
            k_newton,
            k_poisson,
        }
    }

    #[inline(always)]
    fn valid(&self) -> Mask<L> {
        self.valid
    }

    #[inline(always)]
    fn routed(&self) -> Mask<L> {
        let zero = Lanes::splat(0.0);
        let bound = Lanes::splat(1.0 - limit2::<2>()) * self.g22;
        self.d1.test(&zero, |d, z| d > z)
            & self.d2.test(&zero, |d, z| d > z)
            & self.d2.test(&bound, |d, b| d >= b)
    }

    #[inline(always)]
    fn solve(&self, model: Model) -> ([Lanes<L>; N], [Lanes<L>; 6]) {
        let one = Lanes::splat(1.0);
        let (mut x1, mut x2) = (self.b1, self.b2);
        if model == Model::Newton {
            x1 = (one + self.k_newton[0]) * x1;
            x2 = (one + self.k_newton[1]) * x2;
        }
        x2 -= self.l21 * x1;
        x1 *= self.d1_inv;
        x2 *= self.d2_inv;
        x1 -= self.l21 * x2;
        if model == Model::Poisson {
            x1 *= one + self.k_poisson[0];
            x2 *= one + self.k_poisson[1];
        }
        let (m1, m2) = (-x1, -x2);
        let mut v = self.velocity;
        for k in 0..6 {
            v[k] += m1 * self.w1[k];
        }
        for k in 0..6 {
            v[k] += m2 * self.w2[k];
        }
        let p = [x1, x2];
        (std::array::from_fn(|j| p[j.min(1)]), v)
    }

    #[inline]
    fn route(&self, l: usize) -> Result<(), LeanError> {
        let g = [[self.g11.0[l], 0.0], [self.g21.0[l], self.g22.0[l]]];
        let d = [self.d1.0[l], self.d2.0[l]];
        route_test::<2>(|i, j| g[i][j], |j| d[j])
    }
}
