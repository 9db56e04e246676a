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
//! **Friction.** Where a closed contact is rough (μ > 0), the problem is the single body's of
//! [`crate::simulate::contact`] over the system: a sticking contact has three rows and three
//! unknowns (its normal and two tangents t: its slip u = Σ σ_i (v_i + ω_i × r_i) held at zero,
//! u̇ = Σ σ_i (a_i + α_i × r_i + ω_i × ṙ_i), its force in Coulomb's cone); a sliding one has its
//! normal row and the unknown force λ (n − μ ŝ), ŝ the unit slip (held below the lock speed);
//! each row's entries W_pq = Σ_b σ_pb σ_qb (d_p · e_q / m_b + (r_pb × d_p)ᵀ Ĩ_b (r_qb × e_q)),
//! d_p the row's direction and e_q the unknown's. Its active set is decided as the single body's
//! ([`crate::simulate::contact::decide`]: every subset, largest first, each block solved by LU
//! or the SVD's least-norm member, the friction of a family shared in proportion to the cones),
//! and a sticking contact whose force leaves its cone starts to slide
//! ([`ContactError::Slips`]). W is then not symmetric, and Lemke's method is not used.
//!
//! **Joints.** Where joints hold the members ([`super::joints`]), the free accelerations a⁰ are
//! first projected onto them (a⁰_c, Gauss's principle), every entry of W is that of the
//! jointed system's mobility W_c = M⁻¹ − M⁻¹ Hᵀ K⁺ H M⁻¹ (less z_dᵀ K⁺ z_e), the bias is
//! J a⁰_c + c, and the accelerations found are projected once more (the contacts' forces
//! answered through W_c) — both solvers above unchanged, on that W and bias.
//!
//! A closed contact stays closed while its g̈ is not positive beyond 10⁻⁹ of the scale of the
//! accelerations: one that neither presses nor separates (λ = 0, g̈ = 0: the inner contacts of
//! a column falling as one) persists, so that the impact that ends the fall strikes every one
//! of them (Siconos keeps them in its index set 1 for the same reason).

use nalgebra::{DMatrix, DVector, Matrix3, UnitQuaternion};

use super::super::body::V3;
use super::super::contact::{ContactError, Layout, MAX_CONTACTS, Mode, decide, tangents};
use super::super::world::Plane;
use super::gaps::{Candidate, Gap, gap};
use super::joints::{Frozen, Link, hold, settle};
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

/// A closed contact: the candidate, and how it takes a tangential force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Held {
    /// The candidate (index into the setup's candidates).
    pub k: usize,
    /// Frictionless, sticking or sliding.
    pub mode: Mode,
    /// A sliding contact may stick again once its slip has exceeded the lock speed since it
    /// started (as the single body's [`crate::simulate::contact::Closed::armed`]).
    pub armed: bool,
}

/// The slip of the contact of gap `g` at `s`: the tangential part of
/// u = Σ σ_i (v_i + ω_i × r_i) (the spin of a member that does not turn left out).
pub fn slip(g: &Gap, members: &[Member], s: &SystemState) -> V3 {
    let u: V3 = g
        .sides()
        .map(|i| {
            let spin = if members[i.body].turns() {
                s.w[i.body].cross(&i.arm)
            } else {
                V3::zeros()
            };
            (s.v[i.body] + spin) * i.sign
        })
        .sum();
    u - g.normal * g.normal.dot(&u)
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
    joints: Option<&Frozen>,
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
    let w = match joints {
        None => w,
        Some(f) => {
            let z: Vec<DVector<f64>> = gaps.iter().map(|g| f.z(&normal_row(g))).collect();
            DMatrix::from_fn(n, n, |p, q| w[(p, q)] - f.coupling(&z[p], &z[q]))
        }
    };
    (w, gaps)
}

/// The row of the contact of gap `g` along d, as the joints take it: σ [d; r × d] per side.
fn row_along(g: &Gap, d: &V3) -> Vec<(usize, V3, V3)> {
    g.sides()
        .map(|i| (i.body, d * i.sign, i.arm.cross(d) * i.sign))
        .collect()
}

/// The normal row σ [n; r × n] of the contact of gap `g` (the moment as [`rows`] takes it).
fn normal_row(g: &Gap) -> Vec<(usize, V3, V3)> {
    g.sides()
        .map(|i| (i.body, g.normal * i.sign, i.moment * i.sign))
        .collect()
}

/// The accelerations of the members at `s` under `gravity` with the `closed` contacts; `lock`:
/// the slip speed below which a sliding contact keeps its held direction.
///
/// # Errors
/// [`ContactError::NoActiveSet`] when no solution is found (frictionless: Lemke's method ends
/// on a ray — W is positive semidefinite, so none exists — or its pivot budget ran out; rough:
/// no subset of pressing contacts is consistent, Painlevé-like); [`ContactError::Slips`] when
/// a sticking contact needs more friction than its cone holds; [`ContactError::TooMany`] past
/// [`MAX_CONTACTS`] closed contacts with one of them rough.
#[allow(clippy::too_many_arguments)] // the system's parts, one by one as this folder passes them
pub fn accelerations(
    members: &[Member],
    planes: &[Plane],
    candidates: &[Candidate],
    closed: &[Held],
    s: &SystemState,
    gravity: &V3,
    lock: f64,
    joints: &[Link],
) -> Result<Accelerations, ContactError> {
    let mut a = vec![*gravity; members.len()];
    let inverse = inverses(members, s);
    let frozen = Frozen::new(joints, members, s);
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
    // the free accelerations held by the joints (J4 of [`super::joints`])
    if let Some(f) = &frozen {
        f.project(&mut a, &mut alpha, true);
    }
    let ks: Vec<usize> = closed.iter().map(|h| h.k).collect();
    let (w, gaps) = rows(
        members,
        planes,
        candidates,
        &ks,
        s,
        &inverse,
        frozen.as_ref(),
    );
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
                    let linear = i.sign * g.normal.dot(&a[i.body]);
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
    if closed.iter().any(|h| h.mode != Mode::Frictionless) {
        let given = Rough {
            members,
            candidates,
            closed,
            s,
            a0: &a,
            lock,
            inverse: &inverse,
            joints: frozen.as_ref(),
            alpha0: &alpha,
            gaps: &gaps,
            normal_bias: &b,
            scale,
        };
        return rough(&given);
    }
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
    if let Some(f) = &frozen {
        f.project(&mut a, &mut alpha, true);
    }
    Ok(Accelerations {
        a,
        alpha,
        force: solution.z,
        gap_acceleration: solution.w,
        scale,
    })
}

/// What the rough problem is given: the closed contacts' gaps, each member's Ĩ and α⁰, and the
/// normal rows' biases J a⁰ + c.
struct Rough<'a> {
    members: &'a [Member],
    candidates: &'a [Candidate],
    closed: &'a [Held],
    s: &'a SystemState,
    /// a⁰ per member, held by the joints.
    a0: &'a [V3],
    lock: f64,
    inverse: &'a [Option<Matrix3<f64>>],
    joints: Option<&'a Frozen>,
    alpha0: &'a [V3],
    gaps: &'a [Gap],
    normal_bias: &'a [f64],
    scale: f64,
}

/// The entry of W = J M⁻¹ Jᵀ between the row of contact `p` along d and the unknown of contact
/// `q` along e: Σ over the members both move of σ_p σ_q (d · e / m_b + (r_p × d)ᵀ Ĩ_b (r_q × e))
/// (the moment left out for a member that does not turn).
fn entry(
    members: &[Member],
    inverse: &[Option<Matrix3<f64>>],
    (p, d): (&Gap, &V3),
    (q, e): (&Gap, &V3),
) -> f64 {
    let mut sum = 0.0;
    for i in p.sides() {
        for j in q.sides().filter(|j| j.body == i.body) {
            let mut term = d.dot(e) / members[i.body].mass();
            if let Some(inv) = &inverse[i.body] {
                term += i.arm.cross(d).dot(&(inv * j.arm.cross(e)));
            }
            sum += i.sign * j.sign * term;
        }
    }
    sum
}

/// The accelerations with a rough contact among the closed ones (module docs), at the smallest
/// capacity of rows that holds them.
fn rough(given: &Rough<'_>) -> Result<Accelerations, ContactError> {
    let n = given.closed.len();
    if n > MAX_CONTACTS {
        return Err(ContactError::TooMany { count: n });
    }
    let rows: usize = given
        .closed
        .iter()
        .map(|h| if let Mode::Stick = h.mode { 3 } else { 1 })
        .sum();
    match rows {
        0..=3 => rough_in::<3>(given),
        4..=6 => rough_in::<6>(given),
        7..=12 => rough_in::<12>(given),
        _ => rough_in::<{ 3 * MAX_CONTACTS }>(given),
    }
}

/// [`rough`] of at most M rows.
fn rough_in<const M: usize>(given: &Rough<'_>) -> Result<Accelerations, ContactError> {
    let &Rough {
        members,
        candidates,
        closed,
        s,
        a0,
        lock,
        inverse,
        joints,
        alpha0,
        gaps,
        normal_bias,
        scale,
    } = given;
    let n = closed.len();
    let mut layout = Layout::<M>::new(n);
    // per row: its contact's gap, its direction d and its unknown's e
    let mut d = [V3::zeros(); M];
    let mut e = [V3::zeros(); M];
    for (i, (h, g)) in closed.iter().zip(gaps).enumerate() {
        let nn = g.normal;
        let mu = candidates[h.k].law.mu;
        layout.start[i] = layout.m;
        let mut push = |dir: V3, force: V3, bias: f64| {
            let p = layout.m;
            layout.contact[p] = i;
            d[p] = dir;
            e[p] = force;
            layout.b[p] = bias;
            layout.m += 1;
        };
        match h.mode {
            Mode::Frictionless => push(nn, nn, normal_bias[i]),
            Mode::Stick => {
                layout.stick_mu[i] = mu;
                push(nn, nn, normal_bias[i]);
                let (t1, t2) = tangents(&nn);
                for t in [t1, t2] {
                    // t · u̇ at zero force: Σ σ_i t · (a⁰_i + α⁰_i × r_i + ω_i × ṙ_i)
                    let bias: f64 = g
                        .sides()
                        .map(|side| {
                            let b = side.body;
                            let mut acc = a0[b];
                            if inverse[b].is_some() {
                                acc += alpha0[b].cross(&side.arm) + s.w[b].cross(&side.arm_rate);
                            }
                            side.sign * t.dot(&acc)
                        })
                        .sum();
                    push(t, t, bias);
                }
            }
            Mode::Slide(held) => {
                let u = slip(g, members, s);
                let dir = if u.norm() > lock { u.normalize() } else { held };
                push(nn, nn - dir * mu, normal_bias[i]);
            }
        }
    }
    let m = layout.m;
    // W_pq = Σ over the members both rows move of σσ (d_p · e_q / m_b + (r × d_p)ᵀ Ĩ_b (r × e_q))
    // less z_dᵀ K⁺ z_e where joints hold the members ([`super::joints`])
    let mut w = [[0.0; M]; M];
    let z = |p: usize, dir: &V3| joints.map(|f| f.z(&row_along(&gaps[layout.contact[p]], dir)));
    let zd: Vec<_> = (0..m).map(|p| z(p, &d[p])).collect();
    let ze: Vec<_> = (0..m).map(|q| z(q, &e[q])).collect();
    for p in 0..m {
        for q in 0..m {
            let (gp, gq) = (&gaps[layout.contact[p]], &gaps[layout.contact[q]]);
            w[p][q] = entry(members, inverse, (gp, &d[p]), (gq, &e[q]));
            if let (Some(f), Some(zp), Some(zq)) = (joints, &zd[p], &ze[q]) {
                w[p][q] -= f.coupling(zp, zq);
            }
        }
    }
    let tol = 1e-9 * scale.max(f64::MIN_POSITIVE);
    let heaviest = members.iter().map(Member::mass).fold(0.0, f64::max);
    let force_tol = tol * heaviest;
    let mut lambda = [0.0; M];
    let set =
        decide(&layout, &w, tol, force_tol, None, &mut lambda).ok_or(ContactError::NoActiveSet)?;
    let mut a = a0.to_vec();
    let mut alpha = alpha0.to_vec();
    let mut force = Vec::with_capacity(n);
    let mut gap_acceleration = Vec::with_capacity(n);
    for (i, (h, g)) in closed.iter().zip(gaps).enumerate() {
        let rows = layout.rows_of(i);
        let lo = rows.start;
        // the contact's force on its positive side (σ = +1)
        let f: V3 = rows.clone().map(|p| e[p] * lambda[p]).sum();
        let normal = lambda[lo];
        if let Mode::Stick = h.mode {
            let ft = f - g.normal * g.normal.dot(&f);
            let mu = candidates[h.k].law.mu;
            // (a tangential force of zero never leaves its cone, even where a pull of
            // −force_tol with μ > 1 makes the bound negative: no direction to slide in)
            if set & (1 << i) != 0
                && ft.norm() > 0.0
                && ft.norm() > mu * normal * (1.0 + 1e-9) + force_tol
            {
                return Err(ContactError::Slips {
                    contact: i,
                    direction: -ft.normalize(),
                });
            }
        }
        for side in g.sides() {
            let b = side.body;
            a[b] += f * (side.sign / members[b].mass());
            if let Some(inv) = &inverse[b] {
                alpha[b] += inv * side.arm.cross(&(f * side.sign));
            }
        }
        force.push(normal);
        gap_acceleration.push(layout.b[lo] + (0..m).map(|q| w[lo][q] * lambda[q]).sum::<f64>());
    }
    if let Some(f) = joints {
        f.project(&mut a, &mut alpha, true);
    }
    Ok(Accelerations {
        a,
        alpha,
        force,
        gap_acceleration,
        scale,
    })
}

/// Hold the closed contacts: the smallest change of the velocities in the kinetic metric that
/// stops every closed contact's normal rate (Δ(v, ω) = M⁻¹ Jᵀ μ, W μ = −J u), and the smallest
/// displacement of the members in the same metric that closes their gaps (Δ(x, θ) = M⁻¹ Jᵀ ν,
/// W ν = −g, the rotation θ applied as exp(θ) q) — what the integration drifted by, to first
/// order in it. Where a contact sticks, its slip is stopped with the normal rates, in one
/// projection ([`hold_sticking`]). With `joints`, they are held first
/// ([`super::joints::hold`]), the contacts' corrections are made through the jointed system's
/// mobility (W_c, and each Δ projected onto the joints' rows), and the joints' velocities are
/// projected again after them. Returns the largest gap, or joint offset, corrected (m).
pub fn project(
    members: &[Member],
    planes: &[Plane],
    candidates: &[Candidate],
    held: &[Held],
    s: &mut SystemState,
    joints: &[Link],
) -> f64 {
    let offset = hold(joints, members, s);
    // a closed contact whose gap the step took out of its region (an edge's normal out of its
    // cone: +∞) holds nothing; the event loop lets it go
    let held: Vec<Held> = held
        .iter()
        .copied()
        .filter(|h| {
            gap(&candidates[h.k].touch, members, planes, s)
                .gap
                .is_finite()
        })
        .collect();
    let held = held.as_slice();
    if held.is_empty() {
        return offset;
    }
    let closed: Vec<usize> = held.iter().map(|h| h.k).collect();
    let closed = closed.as_slice();
    let inverse = inverses(members, s);
    let frozen = Frozen::new(joints, members, s);
    let (w, gaps) = rows(
        members,
        planes,
        candidates,
        closed,
        s,
        &inverse,
        frozen.as_ref(),
    );
    let sticking = held.iter().any(|h| h.mode == Mode::Stick);
    if sticking {
        hold_sticking(members, held, &gaps, &inverse, s, frozen.as_ref());
    }
    let svd = w.svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    let apply = |rhs: DVector<f64>, linear: &mut Vec<V3>, angular: &mut Vec<V3>| {
        let Ok(mu) = svd.solve(&rhs, eps) else {
            return;
        };
        let b = members.len();
        let (mut dl, mut da) = (vec![V3::zeros(); b], vec![V3::zeros(); b]);
        // without joints, straight into the state (as before joints were simulated)
        let (lin, ang): (&mut [V3], &mut [V3]) = match frozen {
            Some(_) => (&mut dl, &mut da),
            None => (linear.as_mut_slice(), angular.as_mut_slice()),
        };
        for (p, g) in gaps.iter().enumerate() {
            for i in g.sides() {
                lin[i.body] += g.normal * (i.sign * mu[p] / members[i.body].mass());
                if let Some(inv) = &inverse[i.body] {
                    ang[i.body] += inv * (i.moment * (i.sign * mu[p]));
                }
            }
        }
        if let Some(f) = &frozen {
            f.project(&mut dl, &mut da, false);
            for k in 0..b {
                linear[k] += dl[k];
                angular[k] += da[k];
            }
        }
    };
    let mut turn = vec![V3::zeros(); members.len()];
    if !sticking {
        apply(
            DVector::from_fn(closed.len(), |p, _| -gaps[p].rate),
            &mut s.v,
            &mut s.w,
        );
    }
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
    if frozen.is_some() {
        settle(joints, members, s);
    }
    worst.max(offset)
}

/// Stop the slip of the sticking contacts among `held` (with their normal rates): the smallest
/// change of the velocities in the kinetic metric, Δ(v, ω) = M⁻¹ Jᵀ μ with W μ = −J u over
/// every closed contact's normal and every sticking one's two tangents (the SVD's least-norm
/// μ, singular values below 10⁻¹² of the largest taken as zero), as the single body's
/// [`crate::simulate::contact::project`].
fn hold_sticking(
    members: &[Member],
    held: &[Held],
    gaps: &[Gap],
    inverse: &[Option<Matrix3<f64>>],
    s: &mut SystemState,
    joints: Option<&Frozen>,
) {
    // per row: its contact and its direction
    let mut rows: Vec<(usize, V3)> = Vec::new();
    for (i, (h, g)) in held.iter().zip(gaps).enumerate() {
        rows.push((i, g.normal));
        if h.mode == Mode::Stick {
            let (t1, t2) = tangents(&g.normal);
            rows.push((i, t1));
            rows.push((i, t2));
        }
    }
    let velocity = |g: &Gap, d: &V3, s: &SystemState| -> f64 {
        g.sides()
            .map(|i| {
                let spin = if inverse[i.body].is_some() {
                    s.w[i.body].cross(&i.arm)
                } else {
                    V3::zeros()
                };
                i.sign * d.dot(&(s.v[i.body] + spin))
            })
            .sum()
    };
    let z: Vec<_> = rows
        .iter()
        .map(|(k, d)| joints.map(|f| f.z(&row_along(&gaps[*k], d))))
        .collect();
    let w = DMatrix::from_fn(rows.len(), rows.len(), |p, q| {
        let ((gp, dp), (gq, dq)) = (rows[p], rows[q]);
        let free = entry(members, inverse, (&gaps[gp], &dp), (&gaps[gq], &dq));
        match (joints, &z[p], &z[q]) {
            (Some(f), Some(zp), Some(zq)) => free - f.coupling(zp, zq),
            _ => free,
        }
    });
    let rhs = DVector::from_fn(rows.len(), |p, _| {
        -velocity(&gaps[rows[p].0], &rows[p].1, s)
    });
    let svd = w.svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    if let Ok(mu) = svd.solve(&rhs, eps) {
        let b = members.len();
        let (mut dv, mut dw) = (vec![V3::zeros(); b], vec![V3::zeros(); b]);
        // without joints, straight into the state (as before joints were simulated)
        let (lin, ang): (&mut [V3], &mut [V3]) = match joints {
            Some(_) => (&mut dv, &mut dw),
            None => (&mut s.v, &mut s.w),
        };
        for (p, &(k, d)) in rows.iter().enumerate() {
            for i in gaps[k].sides() {
                lin[i.body] += d * (i.sign * mu[p] / members[i.body].mass());
                if let Some(inv) = &inverse[i.body] {
                    ang[i.body] += inv * i.arm.cross(&(d * (i.sign * mu[p])));
                }
            }
        }
        if let Some(f) = joints {
            f.project(&mut dv, &mut dw, false);
            for k in 0..b {
                s.v[k] += dv[k];
                s.w[k] += dw[k];
            }
        }
    }
}
