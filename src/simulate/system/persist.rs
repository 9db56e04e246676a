//! Persistent contact among spheres: the accelerations of a system whose closed contacts (gap
//! zero, not approaching) either press or let go, decided by the acceleration-level linear
//! complementarity problem — the single body's of [`crate::simulate::contact`], generalised to
//! several bodies (Pfeiffer and Glocker, 1996, ch. 6; Siconos' `EventDriven` with its
//! `SICONOS_OSNSP_ED_SMOOTH_ACC` LCP).
//!
//! With the rows J_k of the closed contacts ([`super::gaps`]: σ [n; r × n] on each member
//! they touch), the block-diagonal mass matrix M (m_b I₃ and the world inertia R_b J_b R_bᵀ
//! per member) and the free accelerations a⁰ (gravity on every centre, and the gyroscopic
//! α⁰_b = Ĩ_b (−ω_b × R_b J_b R_bᵀ ω_b) of a member that turns, Ĩ_b = R_b J_b⁻¹ R_bᵀ), the gap
//! accelerations are
//!
//! ```text
//! g̈ = W λ + b,   W = J M⁻¹ Jᵀ,   b = J a⁰ + c,   0 ≤ λ ⊥ W λ + b ≥ 0
//! ```
//!
//! so W_kl = Σ_b σ_kb σ_lb (n_k · n_l / m_b + (r_kb × n_k)ᵀ Ĩ_b (r_lb × n_l)) over the members
//! both contacts move (σ = ±1 the side; the moments of a sphere's sides are zero). The LCP is solved by Lemke's method ([`crate::linalg::lcp::lemke`], in f64); for a
//! symmetric positive semidefinite W every solution gives the same g̈ (the lcp module's
//! uniqueness argument), so the motion is decided even where λ is not (a bead resting on two
//! others in a plane: more contacts than the motions they stop).
//!
//! A closed contact stays closed while its g̈ is not positive beyond 10⁻⁹ of the scale of the
//! accelerations: one that neither presses nor separates (λ = 0, g̈ = 0: the inner contacts of
//! a column falling as one) persists, so that the impact that ends the fall strikes every one
//! of them (Siconos keeps them in its index set 1 for the same reason).

use nalgebra::{DMatrix, DVector, Matrix3, UnitQuaternion};

use super::super::body::V3;
use super::super::contact::ContactError;
use super::super::world::Plane;
use super::gaps::{Candidate, Gap, gap};
use super::members::{Member, SystemState};
use crate::linalg::lcp::{Lcp, lemke};

/// The accelerations at one state.
#[derive(Clone, Debug, PartialEq)]
pub struct Accelerations {
    /// a_b per member (world).
    pub a: Vec<V3>,
    /// α_b per member (world; zero for a sphere).
    pub alpha: Vec<V3>,
    /// λ per closed contact (N).
    pub force: Vec<f64>,
    /// g̈ per closed contact (m/s²).
    pub gap_acceleration: Vec<f64>,
    /// The scale of the accelerations the tests of 10⁻⁹ are relative to (m/s²).
    pub scale: f64,
}

/// Each member's Ĩ_b = R_b J_b⁻¹ R_bᵀ (`None` for a sphere, which does not turn).
fn inverses(members: &[Member], s: &SystemState) -> Vec<Option<Matrix3<f64>>> {
    members
        .iter()
        .enumerate()
        .map(|(b, m)| m.turns().then(|| m.body.world_inverse(&s.rotation(b))))
        .collect()
}

/// W = J M⁻¹ Jᵀ of the contacts `closed` (indices into `candidates`) and their gaps.
fn rows(
    members: &[Member],
    planes: &[Plane],
    candidates: &[Candidate],
    closed: &[usize],
    s: &SystemState,
    inverse: &[Option<Matrix3<f64>>],
) -> (DMatrix<f64>, Vec<Gap>) {
    let gaps: Vec<Gap> = closed
        .iter()
        .map(|&k| gap(&candidates[k].touch, members, planes, s))
        .collect();
    let n = closed.len();
    let w = DMatrix::from_fn(n, n, |p, q| {
        let mut sum = 0.0;
        for i in gaps[p].sides() {
            for j in gaps[q].sides() {
                if i.body == j.body {
                    sum += i.sign * j.sign * gaps[p].normal.dot(&gaps[q].normal)
                        / members[i.body].mass();
                    if let Some(inv) = &inverse[i.body] {
                        sum += i.sign * j.sign * i.moment.dot(&(inv * j.moment));
                    }
                }
            }
        }
        sum
    });
    (w, gaps)
}

/// The accelerations of the members at `s` under `gravity` with the `closed` contacts.
///
/// # Errors
/// [`ContactError::NoActiveSet`] when Lemke's method finds no solution (a ray: W is positive
/// semidefinite, so none exists — or the pivot budget ran out).
pub fn accelerations(
    members: &[Member],
    planes: &[Plane],
    candidates: &[Candidate],
    closed: &[usize],
    s: &SystemState,
    gravity: &V3,
) -> Result<Accelerations, ContactError> {
    let mut a = vec![*gravity; members.len()];
    let inverse = inverses(members, s);
    // the gyroscopic α⁰ = Ĩ (−ω × R J Rᵀ ω) of each member that turns
    let mut alpha: Vec<V3> = members
        .iter()
        .enumerate()
        .map(|(b, m)| match &inverse[b] {
            Some(inv) => {
                let w = s.w[b];
                let jw = m.body.world_inertia(&s.rotation(b)) * w;
                inv * (-w.cross(&jw))
            }
            None => V3::zeros(),
        })
        .collect();
    let (w, gaps) = rows(members, planes, candidates, closed, s, &inverse);
    let scale = gravity.norm() + gaps.iter().fold(0.0, |m: f64, g| m.max(g.curvature.abs()));
    if closed.is_empty() {
        return Ok(Accelerations {
            a,
            alpha,
            force: Vec::new(),
            gap_acceleration: Vec::new(),
            scale,
        });
    }
    // b = J a⁰ + c
    let b: Vec<f64> = gaps
        .iter()
        .map(|g| {
            let ja: f64 = g
                .sides()
                .map(|i| {
                    let linear = i.sign * g.normal.dot(gravity);
                    if inverse[i.body].is_some() {
                        linear + i.sign * i.moment.dot(&alpha[i.body])
                    } else {
                        linear
                    }
                })
                .sum();
            ja + g.curvature
        })
        .collect();
    let m: Vec<f64> = w.transpose().iter().copied().collect(); // row-major
    let solution = lemke(Lcp { m: &m, q: &b }).map_err(|_| ContactError::NoActiveSet)?;
    for (p, g) in gaps.iter().enumerate() {
        let lambda = solution.z[p];
        if lambda != 0.0 {
            for i in g.sides() {
                a[i.body] += g.normal * (i.sign * lambda / members[i.body].mass());
                if let Some(inv) = &inverse[i.body] {
                    alpha[i.body] += inv * (i.moment * (i.sign * lambda));
                }
            }
        }
    }
    Ok(Accelerations {
        a,
        alpha,
        force: solution.z,
        gap_acceleration: solution.w,
        scale,
    })
}

/// Hold the closed contacts: the smallest change of the velocities in the kinetic metric that
/// stops every closed contact's normal rate (Δ(v, ω) = M⁻¹ Jᵀ μ, W μ = −J u), and the smallest
/// displacement of the members in the same metric that closes their gaps (Δ(x, θ) = M⁻¹ Jᵀ ν,
/// W ν = −g, the rotation θ applied as exp(θ) q) — what the integration drifted by, to first
/// order in it. Returns the largest gap corrected (m).
pub fn project(
    members: &[Member],
    planes: &[Plane],
    candidates: &[Candidate],
    closed: &[usize],
    s: &mut SystemState,
) -> f64 {
    if closed.is_empty() {
        return 0.0;
    }
    let inverse = inverses(members, s);
    let (w, gaps) = rows(members, planes, candidates, closed, s, &inverse);
    let svd = w.svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    let apply = |rhs: DVector<f64>, linear: &mut Vec<V3>, angular: &mut Vec<V3>| {
        if let Ok(mu) = svd.solve(&rhs, eps) {
            for (p, g) in gaps.iter().enumerate() {
                for i in g.sides() {
                    linear[i.body] += g.normal * (i.sign * mu[p] / members[i.body].mass());
                    if let Some(inv) = &inverse[i.body] {
                        angular[i.body] += inv * (i.moment * (i.sign * mu[p]));
                    }
                }
            }
        }
    };
    let mut turn = vec![V3::zeros(); members.len()];
    apply(
        DVector::from_fn(closed.len(), |p, _| -gaps[p].rate),
        &mut s.v,
        &mut s.w,
    );
    let worst = gaps.iter().map(|g| g.gap.abs()).fold(0.0, f64::max);
    apply(
        DVector::from_fn(closed.len(), |p, _| -gaps[p].gap),
        &mut s.x,
        &mut turn,
    );
    for (b, theta) in turn.iter().enumerate() {
        if inverse[b].is_some() && *theta != V3::zeros() {
            s.q[b] = UnitQuaternion::from_scaled_axis(*theta) * s.q[b];
        }
    }
    worst
}
