//! Persistent contact among spheres: the accelerations of a system whose closed contacts (gap
//! zero, not approaching) either press or let go, decided by the acceleration-level linear
//! complementarity problem — the single body's of [`crate::simulate::contact`], generalised to
//! several bodies (Pfeiffer and Glocker, 1996, ch. 6; Siconos' `EventDriven` with its
//! `SICONOS_OSNSP_ED_SMOOTH_ACC` LCP).
//!
//! With the rows J_k of the closed contacts ([`super::gaps`]), the diagonal mass matrix M
//! (m_b I₃ per sphere) and the free accelerations a⁰ (gravity), the gap accelerations are
//!
//! ```text
//! g̈ = W λ + b,   W = J M⁻¹ Jᵀ,   b = J a⁰ + c,   0 ≤ λ ⊥ W λ + b ≥ 0
//! ```
//!
//! so W_kl = Σ_b (s_kb s_lb / m_b) n_k · n_l over the bodies both contacts move (s = ±1 the
//! side). The LCP is solved by Lemke's method ([`crate::linalg::lcp::lemke`], in f64); for a
//! symmetric positive semidefinite W every solution gives the same g̈ (the lcp module's
//! uniqueness argument), so the motion is decided even where λ is not (a bead resting on two
//! others in a plane: more contacts than the motions they stop).
//!
//! A closed contact stays closed while its g̈ is not positive beyond 10⁻⁹ of the scale of the
//! accelerations: one that neither presses nor separates (λ = 0, g̈ = 0: the inner contacts of
//! a column falling as one) persists, so that the impact that ends the fall strikes every one
//! of them (Siconos keeps them in its index set 1 for the same reason).

use nalgebra::{DMatrix, DVector};

use super::super::body::V3;
use super::super::contact::ContactError;
use super::super::world::Plane;
use super::gaps::{Candidate, gap};
use super::spheres::{Sphere, SystemState};
use crate::linalg::lcp::{Lcp, lemke};

/// The accelerations at one state.
#[derive(Clone, Debug, PartialEq)]
pub struct Accelerations {
    /// a_b per sphere (world).
    pub a: Vec<V3>,
    /// λ per closed contact (N).
    pub force: Vec<f64>,
    /// g̈ per closed contact (m/s²).
    pub gap_acceleration: Vec<f64>,
    /// The scale of the accelerations the tests of 10⁻⁹ are relative to (m/s²).
    pub scale: f64,
}

/// W = J M⁻¹ Jᵀ of the contacts `closed` (indices into `candidates`), their normals and the
/// curvature terms.
fn rows(
    spheres: &[Sphere],
    planes: &[Plane],
    candidates: &[Candidate],
    closed: &[usize],
    s: &SystemState,
) -> (DMatrix<f64>, Vec<V3>, Vec<f64>) {
    let gaps: Vec<_> = closed
        .iter()
        .map(|&k| gap(&candidates[k].touch, spheres, planes, s))
        .collect();
    let n = closed.len();
    let w = DMatrix::from_fn(n, n, |p, q| {
        let (bp, bq) = (
            candidates[closed[p]].touch.bodies(),
            candidates[closed[q]].touch.bodies(),
        );
        let mut sum = 0.0;
        for &(i, si) in &bp {
            for &(j, sj) in &bq {
                if i == j {
                    sum += si * sj * gaps[p].normal.dot(&gaps[q].normal) / spheres[i].mass;
                }
            }
        }
        sum
    });
    let normals = gaps.iter().map(|g| g.normal).collect();
    let curvature = gaps.iter().map(|g| g.curvature).collect();
    (w, normals, curvature)
}

/// The accelerations of the spheres at `s` under `gravity` with the `closed` contacts.
///
/// # Errors
/// [`ContactError::NoActiveSet`] when Lemke's method finds no solution (a ray: W is positive
/// semidefinite, so none exists — or the pivot budget ran out).
pub fn accelerations(
    spheres: &[Sphere],
    planes: &[Plane],
    candidates: &[Candidate],
    closed: &[usize],
    s: &SystemState,
    gravity: &V3,
) -> Result<Accelerations, ContactError> {
    let mut a = vec![*gravity; spheres.len()];
    let (w, normals, curvature) = rows(spheres, planes, candidates, closed, s);
    let scale = gravity.norm() + curvature.iter().fold(0.0, |m: f64, c| m.max(c.abs()));
    if closed.is_empty() {
        return Ok(Accelerations {
            a,
            force: Vec::new(),
            gap_acceleration: Vec::new(),
            scale,
        });
    }
    // b = J a⁰ + c
    let b: Vec<f64> = closed
        .iter()
        .enumerate()
        .map(|(p, &k)| {
            let ja: f64 = candidates[k]
                .touch
                .bodies()
                .iter()
                .map(|&(_, si)| si * normals[p].dot(gravity))
                .sum();
            ja + curvature[p]
        })
        .collect();
    let m: Vec<f64> = w.transpose().iter().copied().collect(); // row-major
    let solution = lemke(Lcp { m: &m, q: &b }).map_err(|_| ContactError::NoActiveSet)?;
    for (p, &k) in closed.iter().enumerate() {
        let lambda = solution.z[p];
        if lambda != 0.0 {
            for (i, si) in candidates[k].touch.bodies() {
                a[i] += normals[p] * (si * lambda / spheres[i].mass);
            }
        }
    }
    Ok(Accelerations {
        a,
        force: solution.z,
        gap_acceleration: solution.w,
        scale,
    })
}

/// Hold the closed contacts: the smallest change of the velocities in the kinetic metric that
/// stops every closed contact's normal rate (Δv = M⁻¹ Jᵀ μ, W μ = −J v), and the smallest
/// displacement of the centres in the mass metric that closes their gaps (Δx = M⁻¹ Jᵀ ν,
/// W ν = −g) — what the integration drifted by. Returns the largest gap corrected (m).
pub fn project(
    spheres: &[Sphere],
    planes: &[Plane],
    candidates: &[Candidate],
    closed: &[usize],
    s: &mut SystemState,
) -> f64 {
    if closed.is_empty() {
        return 0.0;
    }
    let (w, normals, _) = rows(spheres, planes, candidates, closed, s);
    let gaps: Vec<_> = closed
        .iter()
        .map(|&k| gap(&candidates[k].touch, spheres, planes, s))
        .collect();
    let svd = w.svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    let apply = |rhs: DVector<f64>, out: &mut Vec<V3>| {
        if let Ok(mu) = svd.solve(&rhs, eps) {
            for (p, &k) in closed.iter().enumerate() {
                for (i, si) in candidates[k].touch.bodies() {
                    out[i] += normals[p] * (si * mu[p] / spheres[i].mass);
                }
            }
        }
    };
    apply(
        DVector::from_fn(closed.len(), |p, _| -gaps[p].rate),
        &mut s.v,
    );
    let worst = gaps.iter().map(|g| g.gap.abs()).fold(0.0, f64::max);
    apply(
        DVector::from_fn(closed.len(), |p, _| -gaps[p].gap),
        &mut s.x,
    );
    worst
}
