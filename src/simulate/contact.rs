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
//! four corners has a family of forces and one acceleration; by LU when A_SS is regular, the
//! SVD otherwise: `solve_square_or_least_squares`) — of such a family, the member that shares
//! the friction among sticking contacts in proportion to their cones (`cone_scales`) — and S
//! is accepted when the
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

/// The most closed contacts decided at once (the subsets of more are not enumerated:
/// [`ContactError::TooMany`]).
pub const MAX_CONTACTS: usize = 12;

/// The most rows of the closed contacts: three per sticking contact.
const MAX_ROWS: usize = 3 * MAX_CONTACTS;

/// The layout of the rows of the closed contacts, what [`decide`] reads besides W: per row p
/// its contact and its bias b_p (the acceleration along it at zero force), per contact the
/// start of its rows and its μ when it sticks — at a capacity M of at least their number, on
/// the stack (no allocation per call, and no clearing of the largest capacity for the one to
/// six rows of the common case: the accelerations are wanted at every stage of every step). A
/// contact's first row is its normal; a sticking one has two tangential rows after it. A
/// contact has as many unknowns as rows, so W = J M⁻¹ Jᵀ is square and so is every candidate's
/// block A_SS. Shared with a system's rough contacts ([`crate::simulate::system::persist`]).
pub(crate) struct Layout<const M: usize> {
    /// Rows in use.
    pub m: usize,
    /// Contacts.
    pub n: usize,
    /// The contact of row p.
    pub contact: [usize; M],
    /// Contact i's rows are start[i]..start[i + 1].
    pub start: [usize; M],
    /// b_p.
    pub b: [f64; M],
    /// Contact i's μ when it sticks (its rows after the first are then tangential), else 0.
    pub stick_mu: [f64; M],
}

impl<const M: usize> Layout<M> {
    /// No rows, for n contacts.
    pub fn new(n: usize) -> Layout<M> {
        Layout {
            m: 0,
            n,
            contact: [0; M],
            start: [0; M],
            b: [0.0; M],
            stick_mu: [0.0; M],
        }
    }

    /// Contact i's rows.
    pub fn rows_of(&self, i: usize) -> std::ops::Range<usize> {
        let hi = if i + 1 < self.n {
            self.start[i + 1]
        } else {
            self.m
        };
        self.start[i]..hi
    }
}

/// The rows of one body's closed contacts: their [`Layout`], and per row its direction d_p (the
/// row of the normal or tangential acceleration), the direction e_p of its unknown force,
/// r_i × d_p and Ĩ (r_i × e_p); per contact its arm r_i.
struct Rows<const M: usize> {
    layout: Layout<M>,
    /// Contact i's arm r_i (from C).
    arm: [V3; M],
    d: [V3; M],
    e: [V3; M],
    row_arm: [V3; M],
    col_arm: [V3; M],
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
    if n > MAX_CONTACTS {
        return Err(ContactError::TooMany { count: n });
    }
    let rows: usize = closed
        .iter()
        .map(|c| if let Mode::Stick = c.mode { 3 } else { 1 })
        .sum();
    let args = (body, planes, s, gravity, closed, lock, &inv, &alpha0);
    match rows {
        0..=3 => accelerations_in::<3>(args, hint),
        4..=6 => accelerations_in::<6>(args, hint),
        7..=12 => accelerations_in::<12>(args, hint),
        _ => accelerations_in::<MAX_ROWS>(args, hint),
    }
}

/// What [`accelerations_in`] is given.
type Given<'a> = (
    &'a Body,
    &'a [Plane],
    &'a State,
    &'a V3,
    &'a [Closed],
    f64,
    &'a Matrix3<f64>,
    &'a V3,
);

/// [`accelerations`] of n ≥ 1 closed contacts with at most M rows.
fn accelerations_in<const M: usize>(
    (body, planes, s, gravity, closed, lock, inv, alpha0): Given<'_>,
    hint: &mut Vec<bool>,
) -> Result<Accelerations, ContactError> {
    let n = closed.len();
    // Per contact: its arm, its rows (directions) and its unknowns (force directions), and the
    // acceleration of its point at zero v̇, ω̇ beyond C's (ω × ṙ: [`super::world::Gap::drift`]).
    let mut rows = Rows::<M> {
        layout: Layout::new(n),
        arm: [V3::zeros(); M],
        d: [V3::zeros(); M],
        e: [V3::zeros(); M],
        row_arm: [V3::zeros(); M],
        col_arm: [V3::zeros(); M],
    };
    for (i, c) in closed.iter().enumerate() {
        let plane = &planes[c.plane];
        let g = gap(&body.features[c.feature], plane, s);
        let arm = g.point - s.x;
        let turning = s.w.cross(&g.drift);
        let nn = plane.normal;
        rows.layout.start[i] = rows.layout.m;
        let mut push = |d: V3, e: V3| {
            let p = rows.layout.m;
            rows.layout.contact[p] = i;
            rows.d[p] = d;
            rows.e[p] = e;
            // W = J M⁻¹ Jᵀ entry by entry, d·e/m + (r_i × d)·Ĩ(r_j × e): its factors
            rows.row_arm[p] = arm.cross(&d);
            rows.col_arm[p] = inv * arm.cross(&e);
            rows.layout.b[p] = d.dot(&(gravity + alpha0.cross(&arm) + turning));
            rows.layout.m += 1;
        };
        match c.mode {
            Mode::Frictionless => push(nn, nn),
            Mode::Stick => {
                rows.layout.stick_mu[i] = plane.law.mu;
                let (t1, t2) = tangents(&nn);
                push(nn, nn);
                push(t1, t1);
                push(t2, t2);
            }
            Mode::Slide(held) => {
                let u = s.v + s.w.cross(&arm);
                let slip = u - nn * nn.dot(&u);
                let dir = if slip.norm() > lock {
                    slip.normalize()
                } else {
                    held
                };
                push(nn, nn - dir * plane.law.mu);
            }
        }
        rows.arm[i] = arm;
    }
    let scale = gravity.norm() + s.w.norm_squared() * body.reach() + f64::MIN_POSITIVE;
    let tol = 1e-9 * scale;
    let first = (hint.len() == n).then(|| {
        hint.iter()
            .enumerate()
            .fold(0u32, |m, (i, &on)| m | (u32::from(on) << i))
    });
    // W computed once, at the size of the rows: every candidate active set reads its block
    let m = rows.layout.m;
    let mut w = [[0.0; M]; M];
    for p in 0..m {
        for q in 0..m {
            w[p][q] = rows.d[p].dot(&rows.e[q]) / body.mass + rows.row_arm[p].dot(&rows.col_arm[q]);
        }
    }
    let mut lambda = [0.0; M];
    let set = decide(&rows.layout, &w, tol, tol * body.mass, first, &mut lambda)
        .ok_or(ContactError::NoActiveSet)?;
    let active: Vec<bool> = (0..n).map(|i| set & (1 << i) != 0).collect();
    hint.clear();
    hint.extend_from_slice(&active);
    let mut force = Vec::with_capacity(n);
    let mut normal = Vec::with_capacity(n);
    for j in 0..n {
        let lo = rows.layout.start[j];
        let mut f = V3::zeros();
        for k in rows.layout.rows_of(j) {
            f += rows.e[k] * lambda[k];
        }
        let nn = planes[closed[j].plane].normal;
        let ln = lambda[lo];
        if let Mode::Stick = closed[j].mode {
            let ft = f - nn * nn.dot(&f);
            let mu = planes[closed[j].plane].law.mu;
            // (a tangential force of zero never leaves its cone, even where a pull within the
            // tolerance with μ > 1 makes the bound negative: no direction to slide in)
            if active[j] && ft.norm() > 0.0 && ft.norm() > mu * ln * (1.0 + 1e-9) + tol * body.mass
            {
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
    let moment: V3 = rows.arm[..n]
        .iter()
        .zip(&force)
        .map(|(r, f)| r.cross(f))
        .sum();
    Ok(Accelerations {
        a: gravity + total / body.mass,
        alpha: alpha0 + inv * moment,
        active,
        normal,
        force,
    })
}

/// The active set (a bit per closed contact) and its forces λ (per row, 0 off the set) of the
/// rows `rows` with W = `w`: `first` tried first, then every subset, largest first (ascending
/// within a size). A set is accepted when its block solves to `tol` (accelerations), every
/// λ_n ≥ −`force_tol` and every other contact's normal acceleration ≥ −`tol`. W is held at
/// M × M (M ≥ the rows), so that the few rows of the common case do not clear the largest.
pub(crate) fn decide<const M: usize>(
    rows: &Layout<M>,
    w: &[[f64; M]; M],
    tol: f64,
    force_tol: f64,
    first: Option<u32>,
    lambda: &mut [f64; M],
) -> Option<u32> {
    let m = rows.m;
    let try_set = |set: u32, lambda: &mut [f64; M]| -> bool {
        let on = |p: usize| set & (1 << rows.contact[p]) != 0;
        let mut idx = [0usize; M];
        let mut k = 0;
        for p in (0..m).filter(|&p| on(p)) {
            idx[k] = p;
            k += 1;
        }
        lambda[..m].fill(0.0);
        if k > 0 {
            let mut x = [0.0; M];
            let Some((mut residual, singular)) =
                solve_system::<M>(k, |p, q| w[idx[p]][idx[q]], |p| -rows.b[idx[p]], &mut x)
            else {
                return false;
            };
            if singular && let Some(sc) = cone_scales(rows, &idx[..k], &x) {
                // the family's member that loads each sticking contact in proportion to its
                // cone: λ = S y with y of least norm, S² the cones (see `cone_scales`)
                let mut y = [0.0; M];
                if let Some((r, _)) = solve_system::<M>(
                    k,
                    |p, q| w[idx[p]][idx[q]] * sc[q],
                    |p| -rows.b[idx[p]],
                    &mut y,
                ) && r <= tol
                {
                    for q in 0..k {
                        x[q] = sc[q] * y[q];
                    }
                    residual = r;
                }
            }
            if residual > tol {
                return false;
            }
            for (q, &p) in idx[..k].iter().enumerate() {
                lambda[p] = x[q];
            }
        }
        // λ_n ≥ 0 on the active set; normal acceleration ≥ 0 elsewhere (a contact's first row
        // is its normal).
        for j in 0..rows.n {
            let k = rows.start[j];
            if set & (1 << j) != 0 {
                if lambda[k] < -force_tol {
                    return false;
                }
            } else {
                let acc: f64 = rows.b[k] + (0..m).map(|q| w[k][q] * lambda[q]).sum::<f64>();
                if acc < -tol {
                    return false;
                }
            }
        }
        true
    };
    if let Some(set) = first
        && try_set(set, lambda)
    {
        return Some(set);
    }
    let n = rows.n;
    for size in (0..=n as u32).rev() {
        for set in (0..(1u32 << n)).filter(|s| s.count_ones() == size) {
            if try_set(set, lambda) {
                return Some(set);
            }
        }
    }
    None
}

/// The column scales s_q of the rows `idx` of an active set whose forces `x` (the least-norm
/// member) are a family: 1 on a normal row, √(μ_i λ_n,i / max λ_n) on a sticking contact's
/// tangential row (floored at 10⁻⁹ of the largest cone). The least-norm y of W S y = −b is
/// then the member λ = S y of least Σ_normal λ² + Σ_tangential λ² / c_i — friction shared among
/// contacts that stand for one another (four corners of a face) in proportion to their cones,
/// each at the same fraction of it, where the plain least-norm member can overload a lightly
/// pressed corner and make it slide at zero slip. `None` when no sticking contact is active.
fn cone_scales<const M: usize>(rows: &Layout<M>, idx: &[usize], x: &[f64; M]) -> Option<[f64; M]> {
    let normal = |p: usize| rows.start[rows.contact[p]] == p;
    let largest = idx
        .iter()
        .enumerate()
        .filter(|&(_, &p)| normal(p))
        .map(|(q, _)| x[q])
        .fold(0.0f64, f64::max);
    if !idx.iter().any(|&p| !normal(p)) || largest <= 0.0 {
        return None;
    }
    let mut sc = [1.0; M];
    for (q, &p) in idx.iter().enumerate() {
        if normal(p) {
            continue;
        }
        let j = rows.contact[p];
        // the normal force of contact j: its first row's entry in x
        let n = idx
            .iter()
            .position(|&r| r == rows.start[j])
            .map_or(0.0, |qn| x[qn]);
        let cone = rows.stick_mu[j] * n.max(0.0) / largest;
        sc[q] = cone.max(1e-9 * rows.stick_mu[j]).sqrt();
    }
    Some(sc)
}

/// x with A x = b for the k × k system `a(p, q)`, `b(p)` (k ≤ M), the largest residual
/// |A x − b|, and whether A was singular (x then the least-norm member); `None` when no x was
/// found ([`solve_square_or_least_squares`]).
fn solve_system<const M: usize>(
    k: usize,
    a: impl Fn(usize, usize) -> f64,
    b: impl Fn(usize) -> f64,
    x: &mut [f64; M],
) -> Option<(f64, bool)> {
    let mut am = [[0.0; M]; M];
    let mut rhs = [0.0; M];
    for p in 0..k {
        for q in 0..k {
            am[p][q] = a(p, q);
        }
        rhs[p] = b(p);
    }
    let singular = solve_square_or_least_squares(&am, &rhs, k, x)?;
    let mut worst = 0.0f64;
    for p in 0..k {
        let mut ax = am[p][0] * x[0];
        for q in 1..k {
            ax += am[p][q] * x[q];
        }
        let r = (ax - rhs[p]).abs();
        if r > worst {
            worst = r;
        }
    }
    Some((worst, singular))
}

/// x with A x = b, A k × k (the leading block of `a`): by LU with partial pivoting when its
/// pivots are not below 10⁻¹⁰ of the largest (the common case: one contact, or contacts whose
/// rows are independent); otherwise the minimum-norm least-squares solution by the SVD,
/// singular values below 10⁻¹² of the largest taken as zero — the member of a family of forces
/// (sticking contacts on one line) that does not grow without bound. The caller checks the
/// residual. (The LU is about five times cheaper than the SVD on the 1–6 unknowns of a
/// persistent contact, and the SVD was half the time of a rocking run: benches/simulate.rs.)
/// The LU is nalgebra's, step for step (the first largest pivot of the column, the column
/// scaled by the pivot's reciprocal, the rows swapped whole), on the stack. `Some(singular)`
/// when x was found: whether the SVD was needed.
fn solve_square_or_least_squares<const M: usize>(
    a: &[[f64; M]; M],
    b: &[f64; M],
    k: usize,
    x: &mut [f64; M],
) -> Option<bool> {
    if lu_solve(a, b, k, x) {
        return Some(false);
    }
    let am = DMatrix::from_fn(k, k, |p, q| a[p][q]);
    let rhs = DVector::from_fn(k, |p, _| b[p]);
    let svd = am.svd(true, true);
    let sol = svd.solve(&rhs, 1e-12 * svd.singular_values.max()).ok()?;
    x[..k].copy_from_slice(sol.as_slice());
    Some(true)
}

/// The LU solve of [`solve_square_or_least_squares`]: false when a pivot is below 10⁻¹⁰ of
/// the largest.
fn lu_solve<const M: usize>(a: &[[f64; M]; M], b: &[f64; M], k: usize, x: &mut [f64; M]) -> bool {
    let mut lu = [[0.0; M]; M];
    for p in 0..k {
        lu[p][..k].copy_from_slice(&a[p][..k]);
    }
    x[..k].copy_from_slice(&b[..k]);
    for i in 0..k {
        let mut piv = i;
        let mut best = lu[i][i].abs();
        for r in i + 1..k {
            let v = lu[r][i].abs();
            if v > best {
                best = v;
                piv = r;
            }
        }
        let diag = lu[piv][i];
        if diag == 0.0 {
            return false;
        }
        if piv != i {
            lu.swap(i, piv);
            x.swap(i, piv);
        }
        let inv = 1.0 / diag;
        for r in i + 1..k {
            lu[r][i] *= inv;
        }
        for c in i + 1..k {
            let u = lu[i][c];
            for r in i + 1..k {
                lu[r][c] -= u * lu[r][i];
            }
        }
    }
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for i in 0..k {
        lo = lo.min(lu[i][i].abs());
        hi = hi.max(lu[i][i].abs());
    }
    if !(hi > 0.0 && lo > 1e-10 * hi) {
        return false;
    }
    // L y = P b (unit diagonal), then U x = y, column by column
    for i in 0..k {
        let c = x[i];
        for r in i + 1..k {
            x[r] -= c * lu[r][i];
        }
    }
    for i in (0..k).rev() {
        let c = x[i] / lu[i][i];
        x[i] = c;
        for r in 0..i {
            x[r] -= c * lu[r][i];
        }
    }
    true
}

/// The derivative of the packed state y = (x, q, v, ω) given the accelerations: ẋ = v,
/// q̇ = ½ (0, ω) q, v̇ = a, ω̇ = α.
pub fn derivative(s: &State, acc: &Accelerations) -> [f64; 13] {
    let [dw, di, dj, dk] = super::body::quaternion_rate(&s.q, &s.w);
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
///
/// The velocity change is Δv = M⁻¹ Jᵀ l with W l = −J u (W = J M⁻¹ Jᵀ), and the displacement
/// the minimum-norm solution of N_p · Δx = −g_p, both by the SVD (singular values below 10⁻¹²
/// of the largest, and below 10⁻¹², taken as zero), the rows gathered on the stack. (An LU
/// where the rows are independent would be cheaper, but it leaves no rounding residual where
/// the SVD leaves one of an ulp, and a ball under 10³⁰⁶ m/s² of gravity, `tests/simulate.rs`,
/// then ends at rest instead of overflowing.) At most 36 rows are held (twelve sticking
/// contacts; the accelerations refuse more than [`MAX_CONTACTS`] contacts, so no step with more
/// is accepted): with more, nothing is moved.
pub fn project(
    body: &Body,
    planes: &[Plane],
    s: &mut State,
    closed: &[Closed],
    active: &[bool],
) -> f64 {
    let rows: usize = closed
        .iter()
        .zip(active)
        .filter(|&(_, &on)| on)
        .map(|(c, _)| if let Mode::Stick = c.mode { 3 } else { 1 })
        .sum();
    match rows {
        0 => 0.0,
        1..=3 => project_in::<3>(body, planes, s, closed, active),
        4..=6 => project_in::<6>(body, planes, s, closed, active),
        7..=12 => project_in::<12>(body, planes, s, closed, active),
        13..=MAX_ROWS => project_in::<MAX_ROWS>(body, planes, s, closed, active),
        _ => 0.0,
    }
}

/// [`project`] of at most M rows.
fn project_in<const M: usize>(
    body: &Body,
    planes: &[Plane],
    s: &mut State,
    closed: &[Closed],
    active: &[bool],
) -> f64 {
    let r: Matrix3<f64> = s.rotation();
    let inv = body.world_inverse(&r);
    // per row: d, r, r × d, Ĩ (r × d), the velocity along d, the gap (0 but on a normal row)
    let mut rows = [(V3::zeros(), V3::zeros(), V3::zeros(), V3::zeros(), 0.0, 0.0); M];
    let mut m = 0;
    for (c, &on) in closed.iter().zip(active) {
        if !on {
            continue;
        }
        let plane = &planes[c.plane];
        let g = gap(&body.features[c.feature], plane, s);
        let arm = g.point - s.x;
        let nn = plane.normal;
        let u = s.v + s.w.cross(&arm);
        let mut push = |d: V3, gap: f64| {
            let rd = arm.cross(&d);
            rows[m] = (d, arm, rd, inv * rd, d.dot(&u), gap);
            m += 1;
        };
        push(nn, g.gap);
        if let Mode::Stick = c.mode {
            let (t1, t2) = tangents(&nn);
            push(t1, 0.0);
            push(t2, 0.0);
        }
    }
    let w = |p: usize, q: usize| {
        let (d, _, rd, _, _, _) = rows[p];
        let (e, _, _, ire, _, _) = rows[q];
        d.dot(&e) / body.mass + rd.dot(&ire)
    };
    let svd = DMatrix::from_fn(m, m, w).svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    let rhs = DVector::from_fn(m, |p, _| -rows[p].4);
    if let Ok(l) = svd.solve(&rhs, eps) {
        let mut dv = V3::zeros();
        let mut dm = V3::zeros();
        for (p, (d, arm, _, _, _, _)) in rows[..m].iter().enumerate() {
            dv += d * l[p];
            dm += arm.cross(&(d * l[p]));
        }
        s.v += dv / body.mass;
        s.w += inv * dm;
    }
    // Position: translate C along the normals to close the gaps (the attitude is kept).
    let mut normals = [(V3::zeros(), 0.0); M];
    let mut k = 0;
    for &(d, _, _, _, _, g) in rows[..m].iter().filter(|r| r.5 != 0.0) {
        normals[k] = (d, g);
        k += 1;
    }
    let mut worst = 0.0f64;
    if k > 0 {
        worst = normals[..k].iter().map(|r| r.1.abs()).fold(0.0, f64::max);
        let a = DMatrix::from_fn(k, 3, |p, q| normals[p].0[q]);
        let rhs = DVector::from_fn(k, |p, _| -normals[p].1);
        let svd = a.svd(true, true);
        if let Ok(dx) = svd.solve(&rhs, 1e-12) {
            s.x += V3::new(dx[0], dx[1], dx[2]);
        }
    }
    worst
}
