//! Degenerate cases (§5, §8, §11): singularity, compatibility, admissibility.
//!
//! For each restitution model the impulses solve G x = b (eq. 15, 21). With Δ = det G and the
//! ranks of G and of [G | b], Rouché–Capelli classifies the system (eq. 61–68, 98–102):
//!
//! * `unique` — rank G = N (Δ ≠ 0);
//! * `singular-compatible` — rank G = rank [G | b] < N: a family x = x_p + Σ t_k z_k with
//!   G z_k = 0. We report the particular solution of least physical norm Σ P_i² and a basis of
//!   the null space. **What stays fixed:** the twist change along z is −Σ z_j W{E_jx}, and
//!   zᵀ G z = ‖Σ z_j W{E_jx}‖² in the positive definite metric η M (eq. 57–58), so for Newton
//!   (where the impulses are x itself) the velocities after impact and both energies are the
//!   same for every member of the family; only the impulses vary. For Poisson the impulses
//!   are (1 + k_i^P) x_i, so the velocities vary unless every k_i^P is equal — reported per
//!   family;
//! * `singular-incompatible` — rank [G | b] > rank G: no impulses satisfy the law.
//!
//! Physical admissibility (eq. 73–74): a contact is **approaching** when v_ix⁰ > 0 and its
//! impulse **compressive** when P_i > 0. A tensile impulse (P_i < 0) means the obstacle would
//! have to pull: the hypothesis that all contacts collide at once fails. A contact that is not
//! approaching would not collide on its own, but the simultaneous hypothesis stops it anyway.
//!
//! In exact types every rank and sign decision is exact. In floats a pivot counts as zero when
//! it is ≤ N·ε·max g_ii — the tolerance is reported.

pub mod accuracy;
pub mod wrench_space;

use crate::impact::mechanism::Mechanism;
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Screws};
use crate::scalar::Scalar;

/// The Rouché–Capelli classification of a model's system.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Classification {
    /// rank G = N.
    Unique,
    /// rank G = rank [G | b] < N.
    SingularCompatible,
    /// rank [G | b] > rank G.
    SingularIncompatible,
}

impl Classification {
    /// The name used in reports (a JSON contract).
    pub fn name(self) -> &'static str {
        match self {
            Classification::Unique => "unique",
            Classification::SingularCompatible => "singular-compatible",
            Classification::SingularIncompatible => "singular-incompatible",
        }
    }
}

/// Per contact: is it approaching, is its impulse compressive (`None` without impulses)?
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Admissibility {
    /// v_ix⁰ > 0 (eq. 74).
    pub approaching: bool,
    /// P_i > 0 (eq. 73), for the unique solution or the family's particular one.
    pub compressive: Option<bool>,
    /// Whether P_i changes along the family (singular-compatible only).
    pub varies: bool,
}

/// The analysis of one model.
#[derive(Clone, Debug)]
pub struct ModelAnalysis<T: Scalar, S: Screws<T> = Screw<T>> {
    /// Which model.
    pub model: Model,
    /// rank [G | b].
    pub augmented_rank: usize,
    /// The classification.
    pub classification: Classification,
    /// The impulses (hatted, see [`crate::mechanics::contact`]) and everything after impact: the unique
    /// solution, or the family's least-norm member; `None` when incompatible.
    pub outcome: Option<Outcome<T, S>>,
    /// A basis of the impulse family's directions (hatted), empty unless singular-compatible;
    /// also empty from the linear-cost route ([`wrench_space`]), which gives only its dimension.
    pub family: Vec<Vec<T>>,
    /// N − rank G for a singular-compatible system: the dimension of the family (else 0).
    pub nullity: usize,
    /// Whether the twist after impact is the same for every member of the family.
    pub twist_fixed: bool,
    /// Per contact.
    pub admissible: Vec<Admissibility>,
    /// ΔE_c < 0 (for the reported outcome).
    pub energy_gain: Option<bool>,
}

impl<T: Scalar, S: Screws<T>> ModelAnalysis<T, S> {
    /// rank [G | b] > rank G (`augmented_rank`): no impulses satisfy the law; only whether
    /// each contact is approaching is known.
    pub(crate) fn incompatible(model: Model, augmented_rank: usize, approaching: &[bool]) -> Self {
        ModelAnalysis {
            model,
            augmented_rank,
            classification: Classification::SingularIncompatible,
            outcome: None,
            family: Vec::new(),
            nullity: 0,
            twist_fixed: false,
            admissible: approaching
                .iter()
                .map(|&a| Admissibility {
                    approaching: a,
                    compressive: None,
                    varies: false,
                })
                .collect(),
            energy_gain: None,
        }
    }
}

/// A pair of contacts at the same point.
#[derive(Clone, Debug, PartialEq)]
pub struct Coincidence<T: Scalar> {
    /// The contacts (0-based), i < j.
    pub pair: (usize, usize),
    /// Whether their normals are parallel too ({E_ix} ∥ {E_jx}, so Δ = 0).
    pub same_axis: bool,
    /// The single-impulse reduction (eq. 69–72), hatted: (1 + k_i) v̂_ix⁰ / ĝ_ii for Newton
    /// and for Poisson, the total impulse of the merged contact; `None` when ĝ_ii = 0 (to the
    /// rank tolerance in floats): constraints absorb any impulse along this normal, and the
    /// reduction 0·P = 0 fixes none (it divided by zero: a panic in exact arithmetic).
    pub single_impulse: Option<[T; 2]>,
}

/// At most this many coincident pairs are listed ([`Analysis::coincident_truncated`] says
/// when there are more): 3000 contacts at one point made 4.5 million pairs — 97 s, 10 GB and
/// 900 MB of JSON for `analyze`.
pub const MAX_COINCIDENT: usize = 1000;

/// At most this many candidate pairs are examined for coincidence (the dense route's all
/// pairs, or the wrench route's neighbours on a grid, which a cluster of near points fills).
pub const MAX_COINCIDENT_CANDIDATES: usize = 1_000_000;

/// The analysis of a scene.
#[derive(Clone, Debug)]
pub struct Analysis<T: Scalar, S: Screws<T> = Screw<T>> {
    /// rank G.
    pub rank: usize,
    /// The zero-pivot tolerance used (floats), relative quantities in the units of G.
    pub tolerance: Option<f64>,
    /// Per model.
    pub models: Vec<ModelAnalysis<T, S>>,
    /// Whether Newton and Poisson give the same impulses, and why.
    pub newton_equals_poisson: Option<(bool, String)>,
    /// Contacts at the same point: at most [`MAX_COINCIDENT`] pairs, in order.
    pub coincident: Vec<Coincidence<T>>,
    /// Whether more pairs may be coincident than are listed (the list reached
    /// [`MAX_COINCIDENT`], or [`MAX_COINCIDENT_CANDIDATES`] candidates were examined).
    pub coincident_truncated: bool,
}

/// Analyse the assembled `impact` for `models`.
pub fn analyze<T: Scalar, M: Mechanism<T>>(
    impact: &mut Impact<T, M>,
    models: &[Model],
) -> Analysis<T, M::Screw> {
    let n = impact.contacts();
    let tolerance = if T::IS_EXACT {
        None
    } else {
        let gmax = (0..n)
            .map(|i| impact.g_hat()[i * n + i].to_f64())
            .fold(0.0, f64::max);
        Some(n as f64 * T::epsilon_f64() * gmax)
    };
    let mut out_models = Vec::with_capacity(models.len());
    for &model in models {
        out_models.push(analyze_model(impact, model));
    }
    let n = impact.contacts();
    let diagonal = (0..n).all(|i| {
        (0..n).all(|j| {
            i == j || impact.g_hat()[i * n + j].is_negligible(&impact.g_hat()[i * n + i], 16 * n)
        })
    });
    let newton_equals_poisson =
        newton_equals_poisson(impact.problem().contacts(), &out_models, diagonal);
    let (coincident, coincident_truncated) = coincident(
        impact.problem().contacts(),
        all_pairs(n),
        |i| {
            (
                impact.g_hat()[i * n + i].clone(),
                impact.before_hat()[i][0].clone(),
            )
        },
        tolerance,
    );
    Analysis {
        rank: impact.rank(),
        tolerance,
        models: out_models,
        newton_equals_poisson,
        coincident,
        coincident_truncated,
    }
}

/// [`analyze`] at a cost linear in N, from the contact wrenches ([`wrench_space`]): the
/// same rank, classification, least-norm impulses, twist, energies and admissibility, with
/// the family given by its dimension (`nullity`) and no basis.
pub fn analyze_reduced<T: Scalar>(
    space: &wrench_space::WrenchSpace<T>,
    models: &[Model],
) -> Analysis<T> {
    let out_models: Vec<ModelAnalysis<T>> =
        models.iter().map(|&m| space.analyze_model(m)).collect();
    let newton_equals_poisson =
        newton_equals_poisson(space.problem().contacts(), &out_models, space.g_diagonal());
    let (coincident, coincident_truncated) = coincident(
        space.problem().contacts(),
        near_pairs(space.problem()),
        |i| {
            (
                space.diagonal()[i].clone(),
                space.before_hat()[i][0].clone(),
            )
        },
        space.tolerance(),
    );
    Analysis {
        rank: space.rank(),
        tolerance: space.tolerance(),
        models: out_models,
        newton_equals_poisson,
        coincident,
        coincident_truncated,
    }
}

fn analyze_model<T: Scalar, M: Mechanism<T>>(
    impact: &mut Impact<T, M>,
    model: Model,
) -> ModelAnalysis<T, M::Screw> {
    let n = impact.contacts();
    let problem = impact.problem().clone();
    let approaching: Vec<bool> = impact
        .before_hat()
        .iter()
        .map(|v| v[0].signum_i8() > 0)
        .collect();
    let scale = |i: usize, model: Model| -> T {
        match model {
            Model::Newton => T::one(),
            Model::Poisson => T::one() + &problem.contacts()[i].k_poisson,
        }
    };
    if impact.rank() == n {
        let mut out = Outcome::default();
        let solved = impact.solve(model, &mut out);
        // rank = N, so the solve cannot fail.
        let ok = solved.is_ok();
        let admissible = (0..n)
            .map(|i| Admissibility {
                approaching: approaching[i],
                compressive: ok.then(|| out.impulses_hat[i].signum_i8() > 0),
                varies: false,
            })
            .collect();
        let gain = ok.then(|| out.kinetic_energy_loss.signum_i8() < 0);
        return ModelAnalysis {
            model,
            augmented_rank: n,
            classification: Classification::Unique,
            outcome: ok.then_some(out),
            family: Vec::new(),
            nullity: 0,
            twist_fixed: true,
            admissible,
            energy_gain: gain,
        };
    }
    let mut b = Vec::new();
    impact.rhs(model, &mut b);
    let mut x = Vec::new();
    if impact.solve_singular(&b, &mut x).is_none() {
        return ModelAnalysis::incompatible(model, impact.rank() + 1, &approaching);
    }
    // The impulses: x (Newton) or (1 + k_i^P) x_i (Poisson), and the same map on the basis.
    let mut impulses: Vec<T> = (0..n).map(|i| scale(i, model) * &x[i]).collect();
    let family: Vec<Vec<T>> = impact
        .null_space()
        .into_iter()
        .map(|z| (0..n).map(|i| scale(i, model) * &z[i]).collect())
        .collect();
    least_norm(&mut impulses, &family, impact);
    let compression = match model {
        Model::Newton => Vec::new(),
        Model::Poisson => (0..n)
            .map(|i| impulses[i].clone() / scale(i, model))
            .collect(),
    };
    let mut out = Outcome {
        impulses_hat: impulses,
        compression_hat: compression,
        ..Outcome::default()
    };
    impact.complete(&mut out);
    // The twist change along each direction of the family: −Σ z_j W{E_jx}.
    let twist_fixed = family.iter().all(|z| {
        let v0 = problem.velocity();
        let mut dv = v0.zero_like();
        for (zj, r) in z.iter().zip(impact.responses()) {
            dv.add_scaled(zj, r);
        }
        // {v⁰}ᵀ η M {v⁰} = 2 T⁰, the scale of the energies.
        let t0 = problem.kinetic_energy(v0);
        let reference = t0.clone() + &t0;
        problem
            .kinetic_energy(&dv)
            .is_negligible(&reference, 16 * n)
    });
    let admissible = (0..n)
        .map(|i| Admissibility {
            approaching: approaching[i],
            compressive: Some(out.impulses_hat[i].signum_i8() > 0),
            varies: family.iter().any(|z| !z[i].is_negligible(&T::one(), n)),
        })
        .collect();
    let gain = Some(out.kinetic_energy_loss.signum_i8() < 0);
    ModelAnalysis {
        model,
        augmented_rank: impact.rank(),
        classification: Classification::SingularCompatible,
        outcome: Some(out),
        nullity: family.len(),
        family,
        twist_fixed,
        admissible,
        energy_gain: gain,
    }
}

/// Replace `p` by the member of p + span(basis) of least physical norm Σ (P̂_i |x̂_i|)², for
/// `basis` the null space of G from [`Impact::null_space`] scaled per contact: with the
/// contacts in pivot order, basis vector j is Πᵀ [−m_j; e_j] up to a factor, where the first
/// r = rank G entries are the pivoted ones. With W = diag(|x̂_i|²) split the same way, the
/// minimiser x satisfies Bᵀ W x = 0, i.e. x₂ = W₂⁻¹ Mᵀ W₁ x₁, and x₁ + M x₂ = p₁ + M p₂; so
///
/// ```text
/// S y = p₁ + M p₂,   S = W₁⁻¹ + M W₂⁻¹ Mᵀ (r×r, positive definite),   x₁ = W₁⁻¹ y,   x₂ = W₂⁻¹ Mᵀ y
/// ```
///
/// — O(r² (N − r)) work where the normal equations of the family, (Bᵀ W B) c = Bᵀ W p, cost
/// O((N − r)³): a minute in rationals for 220 contacts (r ≤ 6), milliseconds this way.
fn least_norm<T: Scalar, M: Mechanism<T>>(p: &mut [T], basis: &[Vec<T>], impact: &Impact<T, M>) {
    let k = basis.len();
    if k == 0 {
        return;
    }
    let (n, perm) = (impact.contacts(), impact.pivots());
    let r = n - k;
    let w: Vec<T> = perm
        .iter()
        .map(|&i| impact.frames()[i].norm2[0].clone())
        .collect();
    // m_j: the pivoted entries of basis vector j over its entry at its own free contact.
    let m: Vec<Vec<T>> = basis
        .iter()
        .enumerate()
        .map(|(j, b)| {
            let own = b[perm[r + j]].clone();
            (0..r).map(|i| -(b[perm[i]].clone() / &own)).collect()
        })
        .collect();
    let mut s = vec![T::zero(); r * r];
    let mut rhs: Vec<T> = (0..r).map(|i| p[perm[i]].clone()).collect();
    for i in 0..r {
        s[i * r + i] = T::one() / &w[i];
    }
    for (j, mj) in m.iter().enumerate() {
        let (wj, pj) = (&w[r + j], &p[perm[r + j]]);
        for a in 0..r {
            rhs[a] += mj[a].clone() * pj;
            let t = mj[a].clone() / wj;
            for c in 0..r {
                s[a * r + c] += t.clone() * &mj[c];
            }
        }
    }
    let mut pivots = vec![0; r];
    if !crate::linalg::factor_psd(&mut s, r, &mut pivots).is_ok_and(|f| f.rank == r) {
        return;
    }
    let mut work = vec![T::zero(); r];
    crate::linalg::solve_factored(&s, r, &pivots, &mut rhs, &mut work);
    for (j, mj) in m.iter().enumerate() {
        let mut x = T::zero();
        for (a, y) in rhs.iter().enumerate() {
            x += mj[a].clone() * y;
        }
        p[perm[r + j]] = x / &w[r + j];
    }
    for (i, y) in rhs.into_iter().enumerate() {
        p[perm[i]] = y / &w[i];
    }
}

/// eq. 50–55: equal impulses, and why.
fn newton_equals_poisson<T: Scalar, S: Screws<T>>(
    cs: &[Contact<T>],
    models: &[ModelAnalysis<T, S>],
    diagonal: bool,
) -> Option<(bool, String)> {
    let newton = models.iter().find(|m| m.model == Model::Newton)?;
    let poisson = models.iter().find(|m| m.model == Model::Poisson)?;
    let n = cs.len();
    let equal = match (&newton.outcome, &poisson.outcome) {
        (Some(a), Some(b)) => {
            (0..n).all(|i| {
                let d = a.impulses_hat[i].clone() - &b.impulses_hat[i];
                let reference = if a.impulses_hat[i].abs_gt(&b.impulses_hat[i]) {
                    a.impulses_hat[i].clone()
                } else {
                    b.impulses_hat[i].clone()
                };
                d.is_negligible(&reference, 16 * n)
            }) && newton.nullity == poisson.nullity
        }
        (None, None) => newton.classification == poisson.classification,
        _ => false,
    };
    let same_k = cs
        .iter()
        .all(|c| c.k_newton == c.k_poisson && c.k_newton == cs[0].k_newton);
    let reason = match (equal, same_k, diagonal) {
        (true, true, _) => "equal coefficients at every contact (k_i^N = k_i^P = k): eq. 55, first possibility".to_string(),
        (true, false, true) => "g_ij = 0 for i ≠ j: every contact answers only its own impulse (eq. 55, second possibility; eq. 59–60)".to_string(),
        (true, false, false) => "equal here although the coefficients differ and G is not diagonal (a special right-hand side, eq. 53–54)".to_string(),
        (false, _, _) => "the coefficients differ and some g_ij ≠ 0 (i ≠ j), so eq. 53–54 fail".to_string(),
    };
    Some((equal, reason))
}

/// Pairs of contacts at the same point (A_i ≡ A_j, §8), with the single-impulse reduction.
/// Every pair i < j of N contacts, in order (the N×N route).
fn all_pairs(n: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..n).flat_map(move |i| (i + 1..n).map(move |j| (i, j)))
}

/// The pairs i < j of contacts that may share a point, in order, lazily: the points are
/// hashed on a grid of cells 10⁻⁶·max |A_i| wide (in f64), and each point is paired with
/// those of its own and the 26 neighbouring cells — O(N) expected work for scattered points,
/// as much as the caller draws for a cluster ([`MAX_COINCIDENT_CANDIDATES`]). Two points the
/// test of [`coincident`] calls equal are within √(6ε)·max |A_i| ≈ 4·10⁻⁸·max |A_i| of each
/// other in floats, and round to the same f64 in exact types, so they are neighbours on the
/// grid.
fn near_pairs<T: Scalar>(problem: &Problem<T>) -> impl Iterator<Item = (usize, usize)> {
    use std::collections::HashMap;
    let points: Vec<[f64; 3]> = problem
        .contacts()
        .iter()
        .map(|c| {
            [
                c.point[0].to_f64(),
                c.point[1].to_f64(),
                c.point[2].to_f64(),
            ]
        })
        .collect();
    let extent = points
        .iter()
        .flatten()
        .map(|x| x.abs())
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    let h = if extent > 0.0 { 1e-6 * extent } else { 1.0 };
    let cell = move |p: &[f64; 3]| {
        p.map(|x| {
            let c = (x / h).floor();
            if c.is_finite() { c as i64 } else { i64::MAX }
        })
    };
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, p) in points.iter().enumerate() {
        grid.entry(cell(p)).or_default().push(i);
    }
    (0..points.len()).flat_map(move |i| {
        let c = cell(&points[i]);
        let mut near = Vec::new();
        for dx in -1..=1i64 {
            for dy in -1..=1i64 {
                for dz in -1..=1i64 {
                    let key = [
                        c[0].saturating_add(dx),
                        c[1].saturating_add(dy),
                        c[2].saturating_add(dz),
                    ];
                    if let Some(list) = grid.get(&key) {
                        near.extend(list.iter().filter(|&&j| j > i));
                    }
                }
            }
        }
        near.sort_unstable();
        near.dedup();
        near.into_iter().map(move |j| (i, j))
    })
}

/// Of the candidate `pairs` (i < j, in order), those at the same point, with the
/// single-impulse reduction from `own(i)` = (ĝ_ii, v̂_ix⁰) — none where ĝ_ii is zero, to
/// `tolerance` in floats — and whether the list stopped short: at [`MAX_COINCIDENT`] pairs,
/// or after [`MAX_COINCIDENT_CANDIDATES`] candidates.
fn coincident<T: Scalar>(
    contacts: &[Contact<T>],
    pairs: impl IntoIterator<Item = (usize, usize)>,
    own: impl Fn(usize) -> (T, T),
    tolerance: Option<f64>,
) -> (Vec<Coincidence<T>>, bool) {
    use crate::mechanics::screw::{dot, norm2};
    let mut out = Vec::new();
    for (examined, (i, j)) in pairs.into_iter().enumerate() {
        if examined == MAX_COINCIDENT_CANDIDATES {
            return (out, true);
        }
        let (pi, pj) = (&contacts[i].point, &contacts[j].point);
        let d = pi - pj;
        if !norm2(&d).is_negligible(&(norm2(pi) + norm2(pj)), 3) {
            continue;
        }
        if out.len() == MAX_COINCIDENT {
            return (out, true);
        }
        let (ni, nj) = (&contacts[i].normal, &contacts[j].normal);
        let same_axis = norm2(&ni.cross(nj)).is_negligible(&(norm2(ni) * norm2(nj)), 3)
            && dot(ni, nj).signum_i8() > 0;
        let c = &contacts[i];
        let (gii, v0) = own(i);
        let zero = match tolerance {
            Some(t) => gii.to_f64() <= t,
            None => gii.signum_i8() <= 0,
        };
        let single_impulse = (!zero).then(|| {
            [
                (T::one() + &c.k_newton) * &v0 / gii.clone(), // eq. 70
                (T::one() + &c.k_poisson) * &v0 / gii,        // eq. 72
            ]
        });
        out.push(Coincidence {
            pair: (i, j),
            same_axis,
            single_impulse,
        });
    }
    (out, false)
}

/// The 2-norm condition number of a symmetric positive semidefinite matrix (row-major, n×n),
/// λ_max/λ_min from its eigenvalues in f64 (∞ when singular to working precision).
pub fn condition_number(g: &[f64], n: usize) -> f64 {
    if n == 0 {
        return 1.0;
    }
    let m = nalgebra::DMatrix::from_row_slice(n, n, g);
    let eig = m.symmetric_eigenvalues();
    let max = eig.iter().cloned().fold(f64::MIN, f64::max);
    let min = eig.iter().cloned().fold(f64::MAX, f64::min);
    if min <= max * n as f64 * f64::EPSILON || min <= 0.0 {
        f64::INFINITY
    } else {
        max / min
    }
}

/// λ_max of a symmetric matrix (row-major, n×n), in f64.
pub fn largest_eigenvalue(g: &[f64], n: usize) -> f64 {
    nalgebra::DMatrix::from_row_slice(n, n, g)
        .symmetric_eigenvalues()
        .iter()
        .cloned()
        .fold(f64::MIN, f64::max)
}
