//! The lean path: a free body hit at a fixed, small number N of contacts, solved on the stack
//! for the impulses and the twist after impact only.
//!
//! [`crate::impact::solve::Impact`] computes every output — contact frames, the inertances
//! along all three axes, both energies — into buffers it owns, and takes float solves from the
//! orthogonalised wrenches. Many callers (a simulation step, a sweep) want only the impulses
//! and the twist, for N = 2 or a few contacts. [`Lean`] computes exactly those, with N a
//! const generic: stack arrays, no frames, no heap.
//!
//! In the hatted form of [`crate::mechanics::contact`] (normals as given, no square root):
//!
//! ```text
//! {Ê_j} = [n_j; r_j × n_j]                                  axis screws      (eq. 3–4)
//! W{Ê_j} = [J⁻¹ (r_j × n_j); n_j / m]                       responses        (eq. 9, 11)
//! ĝ_ij = {Ê_i}ᵀ η W {Ê_j}                                   inertances       (eq. 12, 57)
//! v̂_jx⁰ = {Ê_j}ᵀ η {v⁰}                                     before impact    (eq. 8)
//! Newton:  Ĝ P̂ = (1 + K^N) v̂_x⁰                                              (eq. 15, 20)
//! Poisson: Ĝ P̂^c = v̂_x⁰,   P̂ = (1 + K^P) P̂^c                                 (eq. 21–23)
//! {v} = {v⁰} − Σ_j P̂_j W{Ê_j}                               after impact     (eq. 24)
//! ```
//!
//! Ĝ is factored once as L D Lᵀ (unit lower L, no pivoting: Ĝ is positive definite whenever
//! the route below accepts it), so both models share it; P̂_j = P_j / |n_j| (P_j itself for
//! unit normals, as the paper writes them).
//!
//! **The route and the accuracy contract.** These are the normal equations, which the generic
//! float solve avoids near a singular G ([`crate::impact::gram_schmidt`]): their error grows
//! with cond G, not √cond G. So a float [`Lean`] takes the route the generic solve takes
//! ([`crate::impact::route`]) and accepts a problem only where that module proves the normal
//! equations within every bound of the contract ([`crate::analysis::accuracy`]): a free body in
//! principal axes whose contact wrenches' correlation matrix C (cosines c_ij = g_ij/√(g_ii g_jj)
//! in the metric ηW) has Gershgorin row sums at most s*(N) = [`route::correlation_limit`]
//! (0.809 for two contacts). Otherwise it says so ([`LeanError::IllConditioned`],
//! [`LeanError::Tensor`]) and the caller falls back to [`crate::impact::solve::Impact`]. The
//! test costs no square root:
//!
//! ```text
//! N = 2:  c₁₂² = 1 − d₂/g₂₂ ≤ s*(2)²     (from the factorization's own pivot, no extra work)
//! N ≥ 3:  (N − 1) Σ_{j≠i} g_ij²/(g_ii g_jj) ≤ s*(N)²   (by Cauchy–Schwarz, Σ_{j≠i} |c_ij| ≤ s*(N))
//! ```
//!
//! The proof in [`crate::impact::route`] bounds the rounding of forming Ĝ, of its L D Lᵀ
//! (Higham, *Accuracy and Stability of Numerical Algorithms*, Thm 10.4, which holds with or
//! without pivoting) and of the sums over the contacts — the operations this module performs —
//! so it covers this path as it covers the generic one.
//!
//! Exact types skip the test: there the normal equations are exact, and [`Lean`] gives the
//! very numbers the generic path gives (tested for equality).
//!
//! The arithmetic is written once over [`crate::scalar::Field`], so that
//! [`crate::impact::batch`] runs the same operations, in the same order, on lanes of f64.

use std::array;

use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::route;
use crate::mechanics::body::Inertia;
use crate::mechanics::screw::Screw;
use crate::scalar::{Field, Scalar};

/// s*(N)², the route test's bound (module docs; [`route::correlation_limit`]).
pub(crate) fn limit2<const N: usize>() -> f64 {
    let s = route::correlation_limit(N);
    s * s
}

/// Why [`Lean`] did not solve a problem. Every case but the last two has an answer through the
/// generic path ([`crate::impact::solve::Impact`]); those two have none.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LeanError {
    /// The problem has another number of contacts than the lean solve was built for.
    #[error("the lean solve is built for {expected} contacts; this problem has {found}")]
    Contacts {
        /// N of the lean solve.
        expected: usize,
        /// Contacts of the problem.
        found: usize,
    },
    /// The body is constrained: the lean path is for a free body.
    #[error("the lean solve is for a free body; this one is constrained (use Impact::solve)")]
    Constrained,
    /// G is too far from diagonal for the normal equations to keep the accuracy contract.
    #[error(
        "the contact wrenches are too nearly dependent for the lean route (largest \
         (N − 1) Σ c_ij² = {spread:.3} > s*(N)², impact::route); Impact::solve keeps the \
         accuracy contract there"
    )]
    IllConditioned {
        /// The largest (N − 1) Σ_{j≠i} c_ij² over the rows (≤ s*(N)² accepted).
        spread: f64,
    },
    /// A full inertia tensor in a float type: the route's proof needs principal axes.
    #[error(
        "the lean route in floats is proved for principal axes; this body has a full inertia \
         tensor (Impact::solve keeps the accuracy contract there)"
    )]
    Tensor,
    /// A pivot of G is not positive: G is singular (§8; [`crate::analysis`]).
    #[error("the inertance matrix G is singular (pivot {pivot} ≤ 0): the impulses are not unique")]
    Singular {
        /// The pivot's index.
        pivot: usize,
    },
    /// An output overflowed the type.
    #[error("an output of the lean solve is not finite (the inputs' magnitudes overflow)")]
    NotFinite,
}

/// J⁻¹ as the lean solve applies it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum InverseInertia<F> {
    /// Principal moments (J_x, J_y, J_z): J⁻¹ μ = μ_k / J_k.
    Principal([F; 3]),
    /// The rows of J⁻¹ (a full tensor).
    Inverse([[F; 3]; 3]),
}

impl<F: Field> InverseInertia<F> {
    /// J⁻¹ μ, in the operation order of [`crate::mechanics::body::RigidBody`]'s response.
    #[inline(always)]
    fn apply(&self, mu: &[F; 3]) -> [F; 3] {
        match self {
            InverseInertia::Principal(j) => array::from_fn(|k| mu[k].clone() / &j[k]),
            InverseInertia::Inverse(inv) => array::from_fn(|i| {
                let mut s = inv[i][0].clone() * &mu[0];
                s += inv[i][1].clone() * &mu[1];
                s += inv[i][2].clone() * &mu[2];
                s
            }),
        }
    }
}

/// A free body hit at N contacts, as plain arrays over a field.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Data<F, const N: usize> {
    /// m.
    pub mass: F,
    /// J⁻¹.
    pub inertia: InverseInertia<F>,
    /// {v⁰} = [ω⁰; v_C⁰].
    pub velocity: [F; 6],
    /// r_j, from C.
    pub points: [[F; 3]; N],
    /// n_j, as given.
    pub normals: [[F; 3]; N],
    /// k_j^N.
    pub k_newton: [F; N],
    /// k_j^P.
    pub k_poisson: [F; N],
}

/// The model-independent part, assembled and factored (module docs).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Factored<F, const N: usize> {
    velocity: [F; 6],
    /// W{Ê_j}.
    responses: [[F; 6]; N],
    /// v̂_jx⁰.
    before: [F; N],
    /// L (strictly below the diagonal).
    l: [[F; N]; N],
    /// D: the pivots d_j.
    d: [F; N],
    /// 1/d_j (0 for a zero pivot, which the route test or the exact pivot test refuses).
    d_inv: [F; N],
    k_newton: [F; N],
    k_poisson: [F; N],
}

/// An array of zeros, to be filled.
#[inline(always)]
fn zeros<F: Field, const K: usize>() -> [F; K] {
    array::from_fn(|_| F::zero())
}

/// x × y.
#[inline(always)]
fn cross<F: Field>(x: &[F; 3], y: &[F; 3]) -> [F; 3] {
    [
        x[1].clone() * &y[2] - x[2].clone() * &y[1],
        x[2].clone() * &y[0] - x[0].clone() * &y[2],
        x[0].clone() * &y[1] - x[1].clone() * &y[0],
    ]
}

/// {a}ᵀ η {b} = top·bottom' + bottom·top' (eq. 6), in [`Screw::reciprocal`]'s order.
#[inline(always)]
fn reciprocal<F: Field>(a: &[F; 6], b: &[F; 6]) -> F {
    let mut s = a[0].clone() * &b[3];
    s += a[3].clone() * &b[0];
    for i in 1..3 {
        s += a[i].clone() * &b[i + 3];
        s += a[i + 3].clone() * &b[i];
    }
    s
}

impl<F: Field, const N: usize> Data<F, N> {
    /// Axis screws, responses, v̂_x⁰, Ĝ (its lower triangle, returned beside the rest for the
    /// route test) and its L D Lᵀ (module docs; eq. 3–4, 8, 11, 12).
    #[inline(always)]
    pub(crate) fn factor(&self) -> (Factored<F, N>, [[F; N]; N]) {
        // Arrays of zeros filled by loops rather than `array::from_fn` with these closures:
        // on the batch's lanes the closures were not inlined and every lane went through
        // memory (impact::batch). The operations and their order are the same.
        let mut axes: [[F; 6]; N] = array::from_fn(|_| zeros());
        for (e, (r, n)) in axes.iter_mut().zip(self.points.iter().zip(&self.normals)) {
            let mu = cross(r, n);
            *e = [
                n[0].clone(),
                n[1].clone(),
                n[2].clone(),
                mu[0].clone(),
                mu[1].clone(),
                mu[2].clone(),
            ];
        }
        // 1/m and 1/J_k once, then products: four divisions instead of six per contact (a
        // division costs several multiplications' throughput).
        let inv_mass = F::one() / &self.mass;
        let inv_moments: Option<[F; 3]> = match &self.inertia {
            InverseInertia::Principal(j) => {
                Some([F::one() / &j[0], F::one() / &j[1], F::one() / &j[2]])
            }
            InverseInertia::Inverse(_) => None,
        };
        let mut responses: [[F; 6]; N] = array::from_fn(|_| zeros());
        for (w, e) in responses.iter_mut().zip(&axes) {
            let mu = [e[3].clone(), e[4].clone(), e[5].clone()];
            let [w0, w1, w2] = match &inv_moments {
                Some(inv) => [
                    mu[0].clone() * &inv[0],
                    mu[1].clone() * &inv[1],
                    mu[2].clone() * &inv[2],
                ],
                None => self.inertia.apply(&mu),
            };
            *w = [
                w0,
                w1,
                w2,
                e[0].clone() * &inv_mass,
                e[1].clone() * &inv_mass,
                e[2].clone() * &inv_mass,
            ];
        }
        let mut before: [F; N] = zeros();
        for (b, e) in before.iter_mut().zip(&axes) {
            *b = reciprocal(e, &self.velocity);
        }
        let mut g: [[F; N]; N] = array::from_fn(|_| array::from_fn(|_| F::zero()));
        for i in 0..N {
            for j in 0..=i {
                g[i][j] = reciprocal(&axes[i], &responses[j]);
            }
        }
        let (l, d, d_inv) = ldl(&g);
        let factored = Factored {
            velocity: self.velocity.clone(),
            responses,
            before,
            l,
            d,
            d_inv,
            k_newton: self.k_newton.clone(),
            k_poisson: self.k_poisson.clone(),
        };
        (factored, g)
    }
}

/// Ĝ = L D Lᵀ from Ĝ's lower triangle `g`, column by column (Cholesky's order, without its
/// square roots, no pivoting): L strictly below the diagonal, the pivots d_j, and 1/d_j taken
/// once (0 for a zero pivot — ∞ or NaN in floats then, which the route test refuses; exact
/// callers test the pivots before solving). Shared by the lean path and `Impact`'s small-N lane.
#[inline(always)]
#[allow(clippy::type_complexity)] // L, D and D⁻¹, as the factorization names them
pub(crate) fn ldl<F: Field, const N: usize>(g: &[[F; N]; N]) -> ([[F; N]; N], [F; N], [F; N]) {
    let mut l: [[F; N]; N] = array::from_fn(|_| array::from_fn(|_| F::zero()));
    let mut d: [F; N] = array::from_fn(|_| F::zero());
    let mut d_inv: [F; N] = array::from_fn(|_| F::zero());
    for j in 0..N {
        let mut dj = g[j][j].clone();
        for k in 0..j {
            dj -= l[j][k].clone() * &l[j][k] * &d[k];
        }
        let inv = if dj.is_zero() {
            F::zero()
        } else {
            F::one() / &dj
        };
        for i in j + 1..N {
            let mut s = g[i][j].clone();
            for k in 0..j {
                s -= l[i][k].clone() * &l[j][k] * &d[k];
            }
            l[i][j] = s * &inv;
        }
        d[j] = dj;
        d_inv[j] = inv;
    }
    (l, d, d_inv)
}

impl<F: Field, const N: usize> Factored<F, N> {
    /// The impulses P̂ of `model` and the twist after impact (eq. 15, 20–24).
    #[inline(always)]
    pub(crate) fn solve(&self, model: Model) -> ([F; N], [F; 6]) {
        let one = F::one();
        // L y = b, then z = D⁻¹ y, then Lᵀ x = z.
        let mut x: [F; N] = self.before.clone();
        if model == Model::Newton {
            for (x, k) in x.iter_mut().zip(&self.k_newton) {
                *x = (one.clone() + k) * &*x;
            }
        }
        for i in 1..N {
            for k in 0..i {
                let t = self.l[i][k].clone() * &x[k];
                x[i] -= t;
            }
        }
        for i in 0..N {
            x[i] *= &self.d_inv[i];
        }
        for i in (0..N).rev() {
            for k in i + 1..N {
                let t = self.l[k][i].clone() * &x[k];
                x[i] -= t;
            }
        }
        if model == Model::Poisson {
            for (p, k) in x.iter_mut().zip(&self.k_poisson) {
                *p *= one.clone() + k; // eq. 23
            }
        }
        // eq. 24, in the generic path's order: {v} ← {v} − P̂_j W{Ê_j}, j = 1 … N.
        let mut v = self.velocity.clone();
        for (p, r) in x.iter().zip(&self.responses) {
            let minus = -p.clone();
            for (vk, rk) in v.iter_mut().zip(r) {
                *vk += minus.clone() * rk;
            }
        }
        (x, v)
    }

    /// The pivots d_j.
    pub(crate) fn pivots(&self) -> &[F; N] {
        &self.d
    }
}

/// The route test of the module docs on f64 values of Ĝ's lower triangle and the pivots:
/// `Err` when a pivot is not positive or G is too far from diagonal. NaN is refused (hence
/// the negated comparisons).
#[inline]
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub(crate) fn route_test<const N: usize>(
    g: impl Fn(usize, usize) -> f64,
    d: impl Fn(usize) -> f64,
) -> Result<(), LeanError> {
    for j in 0..N {
        if !(d(j) > 0.0) {
            return Err(LeanError::Singular { pivot: j });
        }
    }
    if N == 2 {
        // c₁₂² = 1 − d₂/g₂₂ (the Schur complement).
        if !(d(1) >= (1.0 - limit2::<N>()) * g(1, 1)) {
            return Err(LeanError::IllConditioned {
                spread: 1.0 - d(1) / g(1, 1),
            });
        }
    } else if N > 2 {
        let mut worst: f64 = 0.0;
        for i in 0..N {
            let mut s = 0.0;
            for j in (0..N).filter(|&j| j != i) {
                let gij = if i >= j { g(i, j) } else { g(j, i) };
                s += gij * gij / g(j, j);
            }
            let spread = (N - 1) as f64 * s / g(i, i);
            if !(spread <= limit2::<N>()) {
                worst = if spread.is_nan() {
                    f64::INFINITY
                } else {
                    spread
                };
            }
        }
        if worst > 0.0 {
            return Err(LeanError::IllConditioned { spread: worst });
        }
    }
    Ok(())
}

/// A free body's collision at N contacts, assembled and factored on the stack: both models
/// then solve from it (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Lean<T: Scalar, const N: usize> {
    factored: Factored<T, N>,
}

/// What [`Lean::solve`] gives.
#[derive(Clone, Debug, PartialEq)]
pub struct LeanOutcome<T, const N: usize> {
    /// P̂_j = P_j / |n_j| (P_j for unit normals).
    pub impulses_hat: [T; N],
    /// {v} = [ω; v_C] after impact (eq. 24).
    pub velocity: [T; 6],
}

impl<T: Scalar, const N: usize> LeanOutcome<T, N> {
    /// The twist after impact as a [`Screw`].
    pub fn twist(&self) -> Screw<T> {
        Screw::new(
            crate::mechanics::screw::Vec3::new(
                self.velocity[0].clone(),
                self.velocity[1].clone(),
                self.velocity[2].clone(),
            ),
            crate::mechanics::screw::Vec3::new(
                self.velocity[3].clone(),
                self.velocity[4].clone(),
                self.velocity[5].clone(),
            ),
        )
    }
}

impl<T: Scalar, const N: usize> Lean<T, N> {
    /// Assemble and factor the free-body `problem` (validated by [`Problem::new`]).
    ///
    /// # Errors
    /// [`LeanError::Contacts`] when it has not N contacts, [`LeanError::Constrained`] for a
    /// constrained body, [`LeanError::Singular`] for a singular G, and in float types
    /// [`LeanError::IllConditioned`] when the route test refuses G (module docs) — in all
    /// three the generic [`crate::impact::solve::Impact`] is the path to take.
    #[inline(always)]
    pub fn new(problem: &Problem<T>) -> Result<Self, LeanError> {
        let contacts = problem.contacts();
        if contacts.len() != N {
            return Err(LeanError::Contacts {
                expected: N,
                found: contacts.len(),
            });
        }
        if problem.constraints().is_some() {
            return Err(LeanError::Constrained);
        }
        let body = problem.body();
        let inertia = match &body.inertia {
            Inertia::Principal(j) => {
                InverseInertia::Principal([j[0].clone(), j[1].clone(), j[2].clone()])
            }
            // A validated tensor has its inverse; an unvalidated singular one is singular G.
            Inertia::Tensor(t) => match t.inverse() {
                Some(inv) => InverseInertia::Inverse(array::from_fn(|i| {
                    array::from_fn(|k| inv[(i, k)].clone())
                })),
                None => return Err(LeanError::Singular { pivot: 0 }),
            },
        };
        let v = problem.velocity().as_slice();
        let data = Data {
            mass: body.mass.clone(),
            inertia,
            velocity: array::from_fn(|k| v[k].clone()),
            points: array::from_fn(|j| {
                let p = &contacts[j].point;
                [p[0].clone(), p[1].clone(), p[2].clone()]
            }),
            normals: array::from_fn(|j| {
                let n = &contacts[j].normal;
                [n[0].clone(), n[1].clone(), n[2].clone()]
            }),
            k_newton: array::from_fn(|j| contacts[j].k_newton.clone()),
            k_poisson: array::from_fn(|j| contacts[j].k_poisson.clone()),
        };
        Self::from_data(&data)
    }

    /// [`Lean::new`] on plain arrays (validated by the caller).
    #[inline(always)]
    pub(crate) fn from_data(data: &Data<T, N>) -> Result<Self, LeanError> {
        let (factored, g) = data.factor();
        if T::IS_EXACT {
            if let Some(pivot) = factored.d.iter().position(|d| d.signum_i8() <= 0) {
                return Err(LeanError::Singular { pivot });
            }
        } else {
            if matches!(data.inertia, InverseInertia::Inverse(_)) {
                return Err(LeanError::Tensor);
            }
            let d = &factored.d;
            route_test::<N>(|i, j| g[i][j].to_f64(), |j| d[j].to_f64())?;
        }
        Ok(Lean { factored })
    }

    /// The impulses and the twist after impact under `model` (eq. 15, 20–24).
    ///
    /// # Errors
    /// [`LeanError::NotFinite`] when an output overflowed (never for exact types).
    #[inline]
    pub fn solve(&self, model: Model) -> Result<LeanOutcome<T, N>, LeanError> {
        let (impulses_hat, velocity) = self.factored.solve(model);
        if !T::IS_EXACT {
            // Σ 0·x is 0 when every x is finite, NaN otherwise: one test for all.
            let mut zero = T::zero();
            for x in &impulses_hat {
                zero += T::zero() * x;
            }
            for x in &velocity {
                zero += T::zero() * x;
            }
            if !(zero.is_finite() && zero.signum_i8() == 0) {
                return Err(LeanError::NotFinite);
            }
        }
        Ok(LeanOutcome {
            impulses_hat,
            velocity,
        })
    }

    /// Ĝ's pivots d_j (Δ̂ = Π d_j).
    pub fn pivots(&self) -> &[T; N] {
        self.factored.pivots()
    }
}
