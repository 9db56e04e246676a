//! Persistent contact: the accelerations of a body resting, rocking or sliding on the planes it
//! touches, with the contact forces decided by the acceleration-level complementarity problem
//! (the event-driven recipe of Pfeiffer and Glocker, *Multibody Dynamics with Unilateral
//! Contacts*, 1996, ch. 6; Siconos' `EventDriven`): of the closed contacts (gap zero, not
//! approaching), each either presses (λ ≥ 0, normal acceleration 0) or lifts off (λ = 0,
//! normal acceleration ≥ 0).
//!
//! With the body's world inverse inertia Ĩ = R J⁻¹ Rᵀ and a contact i at r_i from C, a force
//! λ_j e_j at contact j changes the acceleration of contact i's point along d by
//!
//! ```text
//! A_(i,d),(j,e) = d·e / m + (r_i × d)ᵀ Ĩ (r_j × e)
//! b_(i,d)       = d · (g + α₀ × r_i + ω × ṙ_i),     α₀ = Ĩ (−ω × R J Rᵀ ω)
//! ```
//!
//! with ṙ_i the velocity of the contact point relative to C: ω × r_i for a body point (a
//! corner, a rod's end), 0 for a sphere's nearest point, which stays at −r N from C however the
//! sphere rolls (so a rolling ball's contact neither lifts off nor slips from its spin).
//!
//! so the accelerations along the rows are A λ + b. A frictionless contact has one unknown
//! along N and one row (its normal acceleration). A sticking contact (μ > 0, no slip) has three
//! unknowns (N and two tangents) and three rows: its point does not accelerate at all, while
//! its friction force stays in Coulomb's cone |λ_t| ≤ μ λ_n. A sliding contact has one unknown
//! along N − μ ŝ (ŝ the unit slip velocity) and its normal row. The active set S (the contacts
//! that press) is found by trying the last one first and then every subset, largest first:
//! λ_S solves A_SS λ_S = −b_S in the least-squares sense of smallest norm (a body resting on
//! four corners has a family of forces and one acceleration), and S is accepted when the
//! system is consistent, every λ_n ≥ 0 and every other contact's normal acceleration ≥ 0, each
//! to 10⁻⁹ of the scale of the accelerations (|g| + |ω|² ρ, ρ the body's reach).

use nalgebra::{DMatrix, DVector, Matrix3};

use super::body::{Body, State, V3};
use super::world::{Plane, gap};

/// How a closed contact takes a tangential force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// μ = 0: the normal force only.
    Frictionless,
    /// No slip: any force in Coulomb's cone.
    Stick,
    /// Slipping along the held unit direction when the slip is slower than the lock speed, else
    /// along its own: the force λ (N − μ ŝ).
    Slide(V3),
}

/// A closed contact: a feature on a plane, and its mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Closed {
    /// The feature (index in [`Body::features`]).
    pub feature: usize,
    /// The plane.
    pub plane: usize,
    /// Its mode.
    pub mode: Mode,
    /// A sliding contact may stick again once its slip has exceeded the lock speed since it
    /// started (a slide that began at zero slip, at the edge of its cone, would otherwise
    /// chatter between the two).
    pub armed: bool,
}

/// The accelerations at one state, and the forces that give them.
#[derive(Clone, Debug, PartialEq)]
pub struct Accelerations {
    /// The acceleration of C (world).
    pub a: V3,
    /// The angular acceleration (world).
    pub alpha: V3,
    /// Per closed contact, whether it presses.
    pub active: Vec<bool>,
    /// Per closed contact, its normal force λ_n (N).
    pub normal: Vec<f64>,
    /// Per closed contact, its force on the body (world).
    pub force: Vec<V3>,
}

/// Why no accelerations could be decided.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ContactError {
    /// No active set satisfies the complementarity conditions (with friction, Painlevé's
    /// paradox can leave none).
    #[error(
        "no set of pressing contacts satisfies the contact conditions (Painlevé-like inconsistency)"
    )]
    NoActiveSet,
    /// A sticking contact needs more friction than its cone allows: it starts to slide,
    /// opposite to the friction force it would need (the unit direction given).
    #[error("contact {contact} starts to slide")]
    Slips {
        /// The closed contact (index).
        contact: usize,
        /// The direction it slides in.
        direction: V3,
    },
    /// More closed contacts than the subsets can be enumerated for.
    #[error("{count} closed contacts at once: more than the 12 the contact phase decides")]
    TooMany {
        /// The count.
        count: usize,
    },
}

/// Two unit tangents of a unit normal.
pub fn tangents(n: &V3) -> (V3, V3) {
    let k = (0..3)
        .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(0);
    let mut e = V3::zeros();
    e[k] = 1.0;
    let t1 = n.cross(&e).normalize();
    let t2 = n.cross(&t1);
    (t1, t2)
}

/// The accelerations of `body` at `s` under `gravity` with the `closed` contacts on `planes`;
/// `hint`: the active set tried first (updated to the one found); `lock`: the slip speed
/// below which a sliding contact keeps its held direction.
///
/// # Errors
/// [`ContactError`].
pub fn accelerations(
    body: &Body,
    planes: &[Plane],
    s: &State,
    gravity: &V3,
    closed: &[Closed],
    hint: &mut Vec<bool>,
    lock: f64,
) -> Result<Accelerations, ContactError> {
    let r = s.rotation();
    let inv = body.world_inverse(&r);
    let jw = body.world_inertia(&r) * s.w;
    let alpha0 = inv * (-s.w.cross(&jw));
    if closed.is_empty() {
        return Ok(Accelerations {
            a: *gravity,
            alpha: alpha0,
            active: Vec::new(),
            normal: Vec::new(),
            force: Vec::new(),
        });
    }
    let n = closed.len();
    if n > 12 {
        return Err(ContactError::TooMany { count: n });
    }
    // Per contact: its arm, its rows (directions) and its unknowns (force directions), and the
    // acceleration of its point at zero v̇, ω̇ beyond C's (ω × ṙ: [`super::world::Gap::drift`]).
    let mut arms: Vec<V3> = Vec::with_capacity(n);
    let mut turning: Vec<V3> = Vec::with_capacity(n);
    let mut rows: Vec<Vec<V3>> = Vec::with_capacity(n);
    let mut cols: Vec<Vec<V3>> = Vec::with_capacity(n);
    for c in closed {
        let plane = &planes[c.plane];
        let g = gap(&body.features[c.feature], plane, s);
        let arm = g.point - s.x;
        turning.push(s.w.cross(&g.drift));
        let nn = plane.normal;
        match c.mode {
            Mode::Frictionless => {
                rows.push(vec![nn]);
                cols.push(vec![nn]);
            }
            Mode::Stick => {
                let (t1, t2) = tangents(&nn);
                rows.push(vec![nn, t1, t2]);
                cols.push(vec![nn, t1, t2]);
            }
            Mode::Slide(held) => {
                let u = s.v + s.w.cross(&arm);
                let slip = u - nn * nn.dot(&u);
                let dir = if slip.norm() > lock {
                    slip.normalize()
                } else {
                    held
                };
                rows.push(vec![nn]);
                cols.push(vec![nn - dir * plane.law.mu]);
            }
        }
        arms.push(arm);
    }
    let scale = gravity.norm() + s.w.norm_squared() * body.reach() + f64::MIN_POSITIVE;
    let tol = 1e-9 * scale;
    let row_of: Vec<(usize, V3)> = rows
        .iter()
        .enumerate()
        .flat_map(|(i, ds)| ds.iter().map(move |d| (i, *d)))
        .collect();
    let col_of: Vec<(usize, V3)> = cols
        .iter()
        .enumerate()
        .flat_map(|(j, es)| es.iter().map(move |e| (j, *e)))
        .collect();
    // W = J M⁻¹ Jᵀ entry by entry, d·e/m + (r_i × d)·J⁻¹(r_j × e), computed once: every
    // candidate active set reads its block
    let row_arm: Vec<V3> = row_of.iter().map(|&(i, d)| arms[i].cross(&d)).collect();
    let col_arm: Vec<V3> = col_of
        .iter()
        .map(|&(j, e)| inv * arms[j].cross(&e))
        .collect();
    let w_full = DMatrix::from_fn(row_of.len(), col_of.len(), |p, q| {
        row_of[p].1.dot(&col_of[q].1) / body.mass + row_arm[p].dot(&col_arm[q])
    });
    let entry = |p: usize, q: usize| -> f64 { w_full[(p, q)] };
    let b: Vec<f64> = row_of
        .iter()
        .map(|&(i, d)| d.dot(&(gravity + alpha0.cross(&arms[i]) + turning[i])))
        .collect();
    let try_set = |set: &[bool]| -> Option<Vec<f64>> {
        let rs: Vec<usize> = (0..row_of.len()).filter(|&k| set[row_of[k].0]).collect();
        let cs: Vec<usize> = (0..col_of.len()).filter(|&k| set[col_of[k].0]).collect();
        let mut lambda = vec![0.0; col_of.len()];
        if !rs.is_empty() {
            let a = DMatrix::from_fn(rs.len(), cs.len(), |p, q| entry(rs[p], cs[q]));
            let rhs = DVector::from_fn(rs.len(), |p, _| -b[rs[p]]);
            let x = solve_square_or_least_squares(&a, &rhs)?;
            if (&a * &x - &rhs).amax() > tol {
                return None;
            }
            for (q, &k) in cs.iter().enumerate() {
                lambda[k] = x[q];
            }
        }
        // λ_n ≥ 0 on the active set; normal acceleration ≥ 0 elsewhere.
        let force_tol = tol * body.mass;
        let mut k = 0;
        for (j, es) in cols.iter().enumerate() {
            if set[j] && lambda[k] < -force_tol {
                return None;
            }
            k += es.len();
        }
        let mut k = 0;
        for (i, ds) in rows.iter().enumerate() {
            if !set[i] {
                let acc: f64 = b[k]
                    + (0..col_of.len())
                        .map(|q| entry(k, q) * lambda[q])
                        .sum::<f64>();
                if acc < -tol {
                    return None;
                }
            }
            k += ds.len();
        }
        Some(lambda)
    };
    let mut found: Option<(Vec<bool>, Vec<f64>)> = None;
    if hint.len() == n
        && let Some(l) = try_set(hint)
    {
        found = Some((hint.clone(), l));
    }
    if found.is_none() {
        let mut subsets: Vec<u32> = (0..(1u32 << n)).collect();
        subsets.sort_by_key(|m| std::cmp::Reverse(m.count_ones()));
        for m in subsets {
            let set: Vec<bool> = (0..n).map(|i| m & (1 << i) != 0).collect();
            if let Some(l) = try_set(&set) {
                found = Some((set, l));
                break;
            }
        }
    }
    let (set, lambda) = found.ok_or(ContactError::NoActiveSet)?;
    *hint = set.clone();
    let mut force = Vec::with_capacity(n);
    let mut normal = Vec::with_capacity(n);
    let mut k = 0;
    for (j, es) in cols.iter().enumerate() {
        let mut f = V3::zeros();
        for e in es {
            f += e * lambda[k];
            k += 1;
        }
        let nn = planes[closed[j].plane].normal;
        let ln = lambda[k - es.len()];
        if let Mode::Stick = closed[j].mode {
            let ft = f - nn * nn.dot(&f);
            let mu = planes[closed[j].plane].law.mu;
            if set[j] && ft.norm() > mu * ln * (1.0 + 1e-9) + tol * body.mass {
                return Err(ContactError::Slips {
                    contact: j,
                    direction: -ft.normalize(),
                });
            }
        }
        normal.push(ln);
        force.push(f);
    }
    let total: V3 = force.iter().sum();
    let moment: V3 = arms.iter().zip(&force).map(|(r, f)| r.cross(f)).sum();
    Ok(Accelerations {
        a: gravity + total / body.mass,
        alpha: alpha0 + inv * moment,
        active: set,
        normal,
        force,
    })
}

/// x with A x = b: by LU with partial pivoting when A is square and its pivots are not
/// below 10⁻¹⁰ of the largest (the common case: one contact, or contacts whose rows are
/// independent); otherwise the minimum-norm least-squares solution by the SVD, singular values
/// below 10⁻¹² of the largest taken as zero — the member of a family of forces (sticking
/// contacts on one line) that does not grow without bound. The caller checks the residual.
/// (The LU is about five times cheaper than the SVD on the 1–6 unknowns of a persistent
/// contact, and the SVD was half the time of a rocking run: benches/simulate.rs.)
fn solve_square_or_least_squares(a: &DMatrix<f64>, rhs: &DVector<f64>) -> Option<DVector<f64>> {
    if a.is_square() {
        let lu = a.clone().lu();
        let u = lu.u();
        let pivots = u.diagonal().map(f64::abs);
        let (lo, hi) = (pivots.min(), pivots.max());
        if hi > 0.0
            && lo > 1e-10 * hi
            && let Some(x) = lu.solve(rhs)
        {
            return Some(x);
        }
    }
    let svd = a.clone().svd(true, true);
    svd.solve(rhs, 1e-12 * svd.singular_values.max()).ok()
}

/// The derivative of the packed state y = (x, q, v, ω) given the accelerations: ẋ = v,
/// q̇ = ½ (0, ω) q, v̇ = a, ω̇ = α.
pub fn derivative(s: &State, acc: &Accelerations) -> [f64; 13] {
    let q = s.q.quaternion();
    let w = s.w;
    // ½ (0, ω) ⊗ q
    let dw = -0.5 * (w.x * q.i + w.y * q.j + w.z * q.k);
    let di = 0.5 * (w.x * q.w + w.y * q.k - w.z * q.j);
    let dj = 0.5 * (-w.x * q.k + w.y * q.w + w.z * q.i);
    let dk = 0.5 * (w.x * q.j - w.y * q.i + w.z * q.w);
    [
        s.v.x,
        s.v.y,
        s.v.z,
        dw,
        di,
        dj,
        dk,
        acc.a.x,
        acc.a.y,
        acc.a.z,
        acc.alpha.x,
        acc.alpha.y,
        acc.alpha.z,
    ]
}

/// Hold the closed contacts: the smallest change of (v, ω) in the body's kinetic metric that
/// stops every pressing contact's point along its rows (a sticking one entirely, another along
/// its normal), and the smallest displacement of C that closes their gaps — what the integration
/// drifted by (returned: the largest gap corrected, m).
pub fn project(
    body: &Body,
    planes: &[Plane],
    s: &mut State,
    closed: &[Closed],
    active: &[bool],
) -> f64 {
    let r: Matrix3<f64> = s.rotation();
    let inv = body.world_inverse(&r);
    let mut rows: Vec<(V3, V3, f64, f64)> = Vec::new(); // (d, arm, velocity, gap)
    for (c, &on) in closed.iter().zip(active) {
        if !on {
            continue;
        }
        let plane = &planes[c.plane];
        let g = gap(&body.features[c.feature], plane, s);
        let arm = g.point - s.x;
        let nn = plane.normal;
        let u = s.v + s.w.cross(&arm);
        rows.push((nn, arm, nn.dot(&u), g.gap));
        if let Mode::Stick = c.mode {
            let (t1, t2) = tangents(&nn);
            rows.push((t1, arm, t1.dot(&u), 0.0));
            rows.push((t2, arm, t2.dot(&u), 0.0));
        }
    }
    if rows.is_empty() {
        return 0.0;
    }
    let m = rows.len();
    let a = DMatrix::from_fn(m, m, |p, q| {
        let (d, ri, _, _) = rows[p];
        let (e, rj, _, _) = rows[q];
        d.dot(&e) / body.mass + ri.cross(&d).dot(&(inv * rj.cross(&e)))
    });
    let svd = a.svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    let rhs = DVector::from_fn(m, |p, _| -rows[p].2);
    if let Ok(l) = svd.solve(&rhs, eps) {
        let mut dv = V3::zeros();
        let mut dm = V3::zeros();
        for (p, (d, arm, _, _)) in rows.iter().enumerate() {
            dv += d * l[p];
            dm += arm.cross(&(d * l[p]));
        }
        s.v += dv / body.mass;
        s.w += inv * dm;
    }
    // Position: translate C along the normals to close the gaps (the attitude is kept).
    let mut worst = 0.0f64;
    let normal_rows: Vec<&(V3, V3, f64, f64)> = rows.iter().filter(|r| r.3 != 0.0).collect();
    if !normal_rows.is_empty() {
        let k = normal_rows.len();
        let a = DMatrix::from_fn(k, 3, |p, q| normal_rows[p].0[q]);
        let rhs = DVector::from_fn(k, |p, _| -normal_rows[p].3);
        worst = normal_rows.iter().map(|r| r.3.abs()).fold(0.0, f64::max);
        let svd = a.svd(true, true);
        if let Ok(dx) = svd.solve(&rhs, 1e-12) {
            s.x += V3::new(dx[0], dx[1], dx[2]);
        }
    }
    worst
}
