//! The impulse rates dΛ/ds under one assignment of modes: a linear system (eq. 145 in the
//! parameter s of the issue's model).
//!
//! Unknowns: the normal rate dp_i/ds of every *driven* contact (its normal velocity follows a
//! prescribed rate, dv_ix/ds = −c_i) and the tangential rate dτ_i/ds of every *sticking*
//! contact. Knowns: the normal rate of every contact whose impulse rate is prescribed
//! (Poisson's and the energetic restitution). A sliding contact ties its tangential rate to its
//! normal one, dτ_i = μ_i u_i dp_i. The equations, rows of K (see [`super::blocks`]):
//!
//! ```text
//! driven i:    Σ_r K_(ix) r dΛ_r/ds = c_i
//! sticking i:  Σ_r K_(it) r dΛ_r/ds = 0          (one row per tangential dimension)
//! ```
//!
//! A singular system has a family of solutions. When every member moves the body alike
//! (K w = 0 for every null vector w) the split is reported as not unique and one member is
//! taken:
//!
//! * sticking contacts on one line in the plane, whose tangential impulses only their sum
//!   determines (one null direction): the member in the middle of the interval the cones allow;
//! * driven contacts whose normal impulses only their resultant determines — three or more
//!   points of one face, statically indeterminate as a table on four legs: the least-norm
//!   member (for a face landing flat, the impulse shared as evenly as the moments allow), moved
//!   the least needed to make no normal rate negative ([`Rates::normals_unique`]);
//! * then, and for every other family of tangential rates, the member that loads each
//!   sticking contact in proportion to its cone μ_i p'_i (the least Σ |τ'_i|² / (μ_i p'_i)).
//!
//! The member changes the body's motion only through restitution laid down contact by contact
//! (Poisson's with differing k^P, the energetic law), which the verdict says — or through
//! sliding friction that follows a normal split (a face sliding while it turns, its slips in
//! different directions). The rigid model does not decide that one: the least-norm member is
//! still taken — the split of a face on equal, independent compliances, which minimises
//! Σ p_i² — the cone weighting is restricted to the directions of the family that leave the
//! motion alone, and [`Rates::split_moves_body`] says so. Any other family that changes the
//! motion leaves the rates undetermined.

use crate::impact::friction::blocks::Blocks;
use crate::impact::friction::departure::dot;
use crate::linalg::gauss::{basis, null_space, solve_consistent_in, solve_general_in};
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::Screws;
use crate::scalar::Scalar;

/// How contact i's normal impulse evolves over a segment.
#[derive(Clone, Debug, PartialEq)]
pub enum Normal<T: Scalar> {
    /// dv_ix/ds = −c: the rate of the normal impulse is an unknown (compression, Newton).
    Driven(T),
    /// dp_i/ds = r, prescribed (Poisson, energetic; 0 once a contact has stopped).
    Given(T),
}

/// The normal rule of every contact of `contacts` in `phase` under `law` (the module docs of
/// [`super`]): compression drives every normal velocity to zero at s = 1; Newton's restitution
/// drives it to −k^N v⁰; Poisson's prescribes k^P p^c; the energetic law p^c until the contact
/// has `stopped`. `compression` holds p^c (read in restitution only).
pub fn normal_rules<T: Scalar, S: Screws<T>>(
    contacts: &[Contact<T>],
    b: &Blocks<T, S>,
    phase: super::Phase,
    law: super::Restitution,
    compression: &[T],
    stopped: &[bool],
) -> Vec<Normal<T>> {
    let mut out = Vec::with_capacity(contacts.len());
    normal_rules_into(contacts, b, phase, law, compression, stopped, &mut out);
    out
}

/// [`normal_rules`] written into `out` (cleared first), a buffer kept from event to event.
pub fn normal_rules_into<T: Scalar, S: Screws<T>>(
    contacts: &[Contact<T>],
    b: &Blocks<T, S>,
    phase: super::Phase,
    law: super::Restitution,
    compression: &[T],
    stopped: &[bool],
    out: &mut Vec<Normal<T>>,
) {
    use super::{Phase, Restitution};
    out.clear();
    out.extend(contacts.iter().enumerate().map(|(i, c)| {
        let v0 = b.v0[b.offset[i]].clone();
        match (phase, law) {
            (Phase::Compression, _) => Normal::Driven(v0),
            (Phase::Restitution, Restitution::Newton) => Normal::Driven(c.k_newton.clone() * v0),
            (Phase::Restitution, Restitution::Poisson) => {
                Normal::Given(c.k_poisson.clone() * &compression[i])
            }
            (Phase::Restitution, Restitution::Energetic) if stopped[i] => Normal::Given(T::zero()),
            (Phase::Restitution, Restitution::Energetic) => Normal::Given(compression[i].clone()),
        }
    }));
}

/// Contact i's two rules under the unilateral law ([`super::Hypothesis::Unilateral`]): on its
/// prescribed path, [`Normal::Driven`]`(path)` — dv_ix/ds = −path, its impulse rate the unknown,
/// required to be at least `base` — or off it, [`Normal::Given`]`(base)`, its normal velocity
/// free and required to stay on the separating side of the path: with the gap
/// g_i = v_i^path(s) − v_ix ≥ 0, dg_i/ds = −path − dv_ix/ds ≥ 0 while g_i = 0.
///
/// ```text
/// compression:        path = v_ix⁰,        base = 0          (released: dp_i/ds = 0)
/// Newton restitution: path = k_i^N max(v_ix⁰, 0),  base = 0
/// Poisson:            path = 0,            base = k_i^P p_i^c (held at v_ix = 0 by an extra
/// energetic:          path = 0,            base = p_i^c or 0    impulse rate ≥ 0 when needed)
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Unilateral<T: Scalar> {
    /// The rate of the prescribed normal velocity, dv_ix^path/ds = −path.
    pub path: T,
    /// The normal impulse rate off the path, and the least one on it.
    pub base: T,
    /// Whether the path is the rule the phase prescribes (compression, Newton): then it is
    /// tried first; in impulse-prescribed phases the given rate is.
    pub prefer_driven: bool,
}

impl<T: Scalar> Unilateral<T> {
    /// The two rules, the phase's own first.
    pub fn options(&self) -> [Normal<T>; 2] {
        let driven = Normal::Driven(self.path.clone());
        let given = Normal::Given(self.base.clone());
        if self.prefer_driven {
            [driven, given]
        } else {
            [given, driven]
        }
    }
}

/// The unilateral rules of every contact (see [`Unilateral`]), from the simultaneous ones of
/// [`normal_rules`] in `phase`: a driven rule keeps its path and gets base 0 — except that in
/// restitution a contact that was receding before impact (v_ix⁰ < 0) has the path v_ix = 0, as
/// in Moreau's q_i = v_ix⁰ + k_i max(v_ix⁰, 0), not a rebound towards the obstacle; a given
/// rate r becomes the base over the path v_ix = 0.
pub fn unilateral_rules<T: Scalar, S: Screws<T>>(
    simultaneous: &[Normal<T>],
    b: &Blocks<T, S>,
    phase: super::Phase,
) -> Vec<Unilateral<T>> {
    simultaneous
        .iter()
        .enumerate()
        .map(|(i, n)| match n {
            Normal::Driven(c) => Unilateral {
                path: if phase == super::Phase::Restitution && b.v0[b.offset[i]].signum_i8() < 0 {
                    T::zero()
                } else {
                    c.clone()
                },
                base: T::zero(),
                prefer_driven: true,
            },
            Normal::Given(r) => Unilateral {
                path: T::zero(),
                base: r.clone(),
                prefer_driven: false,
            },
        })
        .collect()
}

/// The tangential mode of a contact over a segment.
#[derive(Clone, Debug, PartialEq)]
pub enum Mode<T: Scalar> {
    /// No tangential impulse: μ_i = 0, or no normal impulse rate to carry friction.
    Free,
    /// No slip: the tangential rate is whatever keeps v_it = 0, if the cone allows it.
    Stick,
    /// Slip along the unit direction u (one entry ±1 in the plane, two in space):
    /// dτ_i = μ_i u dp_i (eq. 137–139).
    Slide(Vec<T>),
}

/// The rates of one segment.
#[derive(Clone, Debug, PartialEq)]
pub struct Rates<T: Scalar> {
    /// dΛ/ds, in the order of the stacked axes.
    pub lambda: Vec<T>,
    /// dv/ds = −K dΛ/ds along every axis.
    pub velocity: Vec<T>,
    /// `false` when sticking contacts share a tangential impulse whose split is not determined.
    pub split_unique: bool,
    /// `false` when driven contacts share a normal impulse rate only its resultant determines
    /// (three or more contacts of one face, four corners of a box landing flat): the member
    /// taken is the least-norm one, moved the least needed to make no normal rate negative.
    pub normals_unique: bool,
    /// `true` when the member taken of such a normal family changes the motion: sliding
    /// contacts whose friction follows the split (a face sliding while it turns). The rigid
    /// model does not decide it; the least-norm member is the split of equal, independent
    /// compliances.
    pub split_moves_body: bool,
}

impl<T: Scalar> Default for Rates<T> {
    fn default() -> Self {
        Rates {
            lambda: Vec::new(),
            velocity: Vec::new(),
            split_unique: true,
            normals_unique: true,
            split_moves_body: false,
        }
    }
}

/// Why an assignment of modes has no rates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RateFailure {
    /// The equations contradict each other.
    Inconsistent,
    /// A family of solutions that moves the body differently, or splits a normal impulse.
    Undetermined,
}

/// What an unknown of the system is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Unknown {
    Normal(usize),
    Stick(usize),
}

/// Each unknown's column in Λ-space, sparse: (axis, coefficient) entries, stored flat.
#[derive(Clone, Debug)]
struct Columns<T> {
    unknowns: Vec<Unknown>,
    /// Column j's entries end at `ends[j]` (and start where column j − 1's end).
    ends: Vec<usize>,
    entries: Vec<(usize, T)>,
}

impl<T> Columns<T> {
    fn clear(&mut self) {
        self.unknowns.clear();
        self.ends.clear();
        self.entries.clear();
    }

    /// Start the column of `unknown`.
    fn open(&mut self, unknown: Unknown) {
        self.unknowns.push(unknown);
        self.ends.push(self.entries.len());
    }

    /// Add an entry to the last column opened.
    fn entry(&mut self, axis: usize, coefficient: T) {
        self.entries.push((axis, coefficient));
        if let Some(end) = self.ends.last_mut() {
            *end = self.entries.len();
        }
    }

    /// The columns in order: (unknown, entries).
    fn iter(&self) -> impl Iterator<Item = (Unknown, &[(usize, T)])> {
        let starts = std::iter::once(0).chain(self.ends.iter().copied());
        self.unknowns
            .iter()
            .zip(starts.zip(&self.ends))
            .map(|(u, (a, &b))| (*u, &self.entries[a..b]))
    }
}

/// The buffers of a rate solve, kept from one solve to the next: a planar impact solves the
/// rates of every assignment it tries at every event ([`super::modes`]), and with a kept
/// `RateWork` (and a kept [`Rates`] to write into) none of those solves allocates once the
/// buffers have grown ([`rates_with`]).
#[derive(Clone, Debug)]
pub struct RateWork<T: Scalar> {
    known: Vec<T>,
    columns: Columns<T>,
    /// One equation per unknown: (axis of its row of K, right-hand side).
    rows: Vec<(usize, T)>,
    a: Vec<T>,
    rhs: Vec<T>,
    pivots: Vec<usize>,
    particular: Vec<T>,
}

impl<T: Scalar> Default for RateWork<T> {
    fn default() -> Self {
        RateWork {
            known: Vec::new(),
            columns: Columns {
                unknowns: Vec::new(),
                ends: Vec::new(),
                entries: Vec::new(),
            },
            rows: Vec::new(),
            a: Vec::new(),
            rhs: Vec::new(),
            pivots: Vec::new(),
            particular: Vec::new(),
        }
    }
}

/// Solve for the rates of one segment.
///
/// The system is built and solved in a [`RateWork`] kept per thread and scalar type
/// ([`with_kept_work`]): the spatial integrator solves rates several times per Runge–Kutta
/// stage (a held slip's direction is tracked by a root search, each trial a solve), and a
/// fresh `RateWork` allocated and freed its seven buffers every time — a third of the
/// integration's instructions (issue 29). [`rates_with`] on kept buffers gives the same rates
/// bit for bit.
///
/// # Errors
/// [`RateFailure`] when the assignment admits no rates, or no determined ones.
pub fn rates<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &[Mode<T>],
) -> Result<Rates<T>, RateFailure> {
    let mut out = Rates::default();
    rates_into(b, normals, modes, &mut out)?;
    Ok(out)
}

/// [`rates`] written into `out`, a [`Rates`] the caller keeps from solve to solve (a root
/// search over one contact's slip direction solves the rates at every trial): bit for bit
/// the same rates.
///
/// # Errors
/// As [`rates`] (`out` is then left unspecified).
pub fn rates_into<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &[Mode<T>],
    out: &mut Rates<T>,
) -> Result<(), RateFailure> {
    with_kept_work(|work| rates_with(b, normals, modes, work, out))
}

thread_local! {
    /// The kept [`RateWork`]s of this thread, one per scalar type at most (boxed as `Any`).
    static KEPT: std::cell::RefCell<Vec<Box<dyn std::any::Any>>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

/// Run `f` on this thread's kept [`RateWork`] for `T` (a fresh one the first time). The work
/// is taken out while `f` runs and put back after, so a nested call gets a fresh one rather
/// than a borrow conflict.
fn with_kept_work<T: Scalar, R>(f: impl FnOnce(&mut RateWork<T>) -> R) -> R {
    let taken = KEPT.with(|kept| {
        let mut kept = kept.borrow_mut();
        let at = kept.iter().position(|w| w.is::<RateWork<T>>())?;
        Some(kept.swap_remove(at))
    });
    let mut work: Box<RateWork<T>> = taken.and_then(|w| w.downcast().ok()).unwrap_or_default();
    let out = f(&mut work);
    KEPT.with(|kept| kept.borrow_mut().push(work));
    out
}

/// [`rates`] on kept buffers: the rates are written into `out`, the system is built and solved
/// in `work`. The same operations in the same order as a fresh solve, so the same rates bit
/// for bit; nothing is allocated once the buffers have grown, except on the rare singular
/// systems (sticking contacts on one line), whose null space is built fresh.
///
/// # Errors
/// [`RateFailure`] when the assignment admits no rates, or no determined ones (`out` is then
/// left unspecified).
pub fn rates_with<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &[Mode<T>],
    work: &mut RateWork<T>,
    out: &mut Rates<T>,
) -> Result<(), RateFailure> {
    impulse_rates_with(b, normals, modes, work, out)?;
    b.velocity_change(&out.lambda, &mut out.velocity);
    Ok(())
}

/// [`rates_with`] without the velocity rates: `out.velocity` is left as it was, for a caller
/// that computes v′ = −K λ′ ([`super::blocks::Blocks::velocity_change`] of `out.lambda`) only
/// when it reads it — the mode search, which reads it for a slide's test and for the
/// assignment it keeps, not for a stick's ([`super::modes`]). The impulse rates and flags are
/// [`rates_with`]'s, bit for bit.
///
/// # Errors
/// As [`rates_with`].
pub(super) fn impulse_rates_with<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &[Mode<T>],
    work: &mut RateWork<T>,
    out: &mut Rates<T>,
) -> Result<(), RateFailure> {
    let len = b.len();
    let RateWork {
        known,
        columns,
        rows,
        a,
        rhs,
        pivots,
        particular,
    } = work;
    known.clear();
    known.resize(len, T::zero());
    columns.clear();
    rows.clear();
    // at most one unknown and one equation per axis, two entries per column: the buffers
    // grow once, to their size, rather than by doubling (tested on one of them: they grow
    // together)
    if rows.capacity() < len {
        columns.unknowns.reserve(len);
        columns.ends.reserve(len);
        columns.entries.reserve(2 * len);
        rows.reserve(len);
    }
    // whether some normal rate is driven (an unknown), and some given (a known rate, maybe
    // nonzero): with none given, every right-hand side is its target alone
    let (mut driven, mut given) = (false, false);
    for (i, (normal, mode)) in normals.iter().zip(modes).enumerate() {
        let off = b.offset[i];
        let slide = match mode {
            Mode::Slide(u) => Some(u),
            _ => None,
        };
        match normal {
            Normal::Driven(c) => {
                driven = true;
                columns.open(Unknown::Normal(i));
                columns.entry(off, T::one());
                if let Some(u) = slide {
                    for (a, ua) in u.iter().enumerate() {
                        columns.entry(off + 1 + a, b.mu[i].clone() * ua);
                    }
                }
                rows.push((off, c.clone()));
            }
            Normal::Given(r) => {
                given = true;
                known[off] = r.clone();
                if let Some(u) = slide {
                    for (a, ua) in u.iter().enumerate() {
                        known[off + 1 + a] = b.mu[i].clone() * r * ua;
                    }
                }
            }
        }
        if *mode == Mode::Stick {
            for a in 0..b.dims[i] {
                columns.open(Unknown::Stick(i));
                columns.entry(off + 1 + a, T::one());
                rows.push((off + 1 + a, T::zero()));
            }
        }
    }
    let m = rows.len();
    a.clear();
    rhs.clear();
    a.reserve(m * m);
    rhs.reserve(m);
    for (q, target) in rows.iter() {
        // row q of K
        let k_q = &b.k[q * len..(q + 1) * len];
        let mut start = 0;
        for &end in &columns.ends {
            let mut s = T::zero();
            for (r, c) in &columns.entries[start..end] {
                s += k_q[*r].clone() * c;
            }
            a.push(s);
            start = end;
        }
        let mut t = target.clone();
        if given {
            for (k_qr, kr) in k_q.iter().zip(known.iter()) {
                if !kr.is_zero() {
                    t -= k_qr.clone() * kr;
                }
            }
        }
        rhs.push(t);
    }
    // With every unknown a stick's (every normal rate given), the matrix is K_SS, a principal
    // submatrix of the positive semidefinite K = J M⁻¹ Jᵀ, and the right-hand side
    // −K_S,known Λ'_known = −J_S M⁻¹ J_knownᵀ Λ'_known lies in its range (that of J_S M⁻¹ J_Sᵀ,
    // M positive definite): the system is consistent, and a family of its solutions moves
    // no body (K_SS w = 0 gives wᵀ K_SS w = |M^(-1/2) J_Sᵀ w|² = 0). What a nearly singular
    // elimination says otherwise in floats (a face flat on the floor to the events'
    // tolerance) is its rounding.
    let only_sticks = !driven;
    if only_sticks {
        solve_consistent_in(a, m, m, rhs, pivots, particular);
    } else if !solve_general_in(a, m, m, rhs, pivots, particular) {
        return Err(RateFailure::Inconsistent);
    }
    let expand = |z: &[T], into: &mut Vec<T>| {
        for ((_, col), zj) in columns.iter().zip(z) {
            for (r, c) in col {
                into[*r] += c.clone() * zj;
            }
        }
    };
    let lambda = &mut out.lambda;
    lambda.clone_from(known);
    expand(particular, lambda);
    out.split_unique = pivots.len() == m;
    out.normals_unique = true;
    out.split_moves_body = false;
    if !out.split_unique {
        let null = basis(a, m, pivots);
        // Per null direction, the twist change it makes (columns of `moves`, len × k).
        let k = null.len();
        let mut moves = vec![T::zero(); len * k];
        // Only sticks: no member moves the body (above), whatever the rounding of the
        // computed null directions says.
        let mut moving = false;
        for (col, w) in null.iter().enumerate() {
            let touches_normal = columns
                .iter()
                .zip(w)
                .any(|((u, _), wj)| matches!(u, Unknown::Normal(_)) && !wj.is_zero());
            out.normals_unique &= !touches_normal;
            let mut dir = vec![T::zero(); len];
            expand(w, &mut dir);
            let mut moved = Vec::new();
            b.velocity_change(&dir, &mut moved);
            let scale = max_abs(&b.k) * max_abs(&dir);
            if !only_sticks && moved.iter().any(|x| !x.is_negligible(&scale, len)) {
                moving = true;
            }
            for (q, x) in moved.into_iter().enumerate() {
                moves[q * k + col] = x;
            }
        }
        // A family that changes the motion is taken only where it splits a normal impulse
        // among the contacts of one face (sliding friction following the split): the member
        // of least norm, the split of equal independent compliances. Otherwise the rigid model
        // leaves the rates undetermined.
        if moving && out.normals_unique {
            return Err(RateFailure::Undetermined);
        }
        out.split_moves_body = moving;
        // The directions of the family that leave the motion alone: for the cone weighting.
        let still: Vec<Vec<T>> = match moving {
            false => null.clone(),
            true => null_space(&moves, len, k)
                .1
                .into_iter()
                .map(|c| {
                    let mut w = vec![T::zero(); m];
                    for (wj, cj) in null.iter().zip(&c) {
                        for (x, y) in w.iter_mut().zip(wj) {
                            *x += y.clone() * cj;
                        }
                    }
                    w
                })
                .collect(),
        };
        let planar_pair = null.len() == 1
            && !moving
            && columns
                .iter()
                .all(|(u, _)| !matches!(u, Unknown::Stick(i) if b.dims[i] != 1));
        if !out.normals_unique || !planar_pair {
            // Every member moves the body alike. Normal rates that are a family too (three or
            // more contacts of one face) take the least-norm member, then the nearest one with
            // no negative normal rate; the tangential rates then the member that loads each
            // sticking contact in proportion to its cone (see `cone_weighted_shift`).
            if !out.normals_unique {
                let shift = least_norm_member(particular, &null);
                add(particular, &shift);
                let nonnegative = nonnegative_shift(columns, particular, &null);
                add(particular, &nonnegative);
            }
            lambda.clone_from(known);
            expand(particular, lambda);
            let shift = cone_weighted_shift(b, columns, particular, &still, lambda);
            add(particular, &shift);
            // The cone weighting leaves the normal rates alone up to its own rounding, which a
            // contact weighted near zero magnifies: a rate left at zero by the nonnegative shift
            // is put back on the boundary.
            if !out.normals_unique && !shift.is_empty() {
                let nonnegative = nonnegative_shift(columns, particular, &null);
                add(particular, &nonnegative);
            }
            lambda.clone_from(known);
            expand(particular, lambda);
        } else if let [w] = null.as_slice() {
            let c = middle_of_cones(b, columns, particular, w, lambda);
            let mut shift = vec![T::zero(); len];
            let scaled: Vec<T> = w.iter().map(|x| x.clone() * &c).collect();
            expand(&scaled, &mut shift);
            for (l, s) in lambda.iter_mut().zip(shift) {
                *l += s;
            }
        }
    }
    Ok(())
}

/// The largest |x|.
pub(super) fn max_abs<T: Scalar>(xs: &[T]) -> T {
    let mut m = T::zero();
    for x in xs {
        if x.abs_gt(&m) {
            m = x.clone();
        }
    }
    if m.signum_i8() < 0 { -m } else { m }
}

/// The parameter c of the member z + c·w (one null direction) in the middle of the interval
/// where every sticking contact it moves stays in its cone, |τ'_i| ≤ μ_i p'_i (planar: one
/// tangential entry per contact); 0 when the interval is empty (the stick then fails its test).
fn middle_of_cones<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    columns: &Columns<T>,
    z: &[T],
    w: &[T],
    lambda: &[T],
) -> T {
    let mut lo: Option<T> = None;
    let mut hi: Option<T> = None;
    for (((u, _), zj), wj) in columns.iter().zip(z).zip(w) {
        let Unknown::Stick(i) = u else { continue };
        if wj.is_zero() || b.dims[i] != 1 {
            continue;
        }
        let bound = b.mu[i].clone() * &lambda[b.offset[i]];
        let mut ends = [
            (-bound.clone() - zj) / wj.clone(),
            (bound - zj) / wj.clone(),
        ];
        if wj.signum_i8() < 0 {
            ends.swap(0, 1);
        }
        let [l, h] = ends;
        if lo.as_ref().is_none_or(|x| (l.clone() - x).signum_i8() > 0) {
            lo = Some(l);
        }
        if hi.as_ref().is_none_or(|x| (h.clone() - x).signum_i8() < 0) {
            hi = Some(h);
        }
    }
    match (lo, hi) {
        (Some(l), Some(h)) if (h.clone() - &l).signum_i8() >= 0 => (l + h) / (T::one() + T::one()),
        _ => T::zero(),
    }
}

/// The shift N c that takes z to the least-norm member z + N c of its family (the columns of
/// N, the `null` directions, independent): c solves NᵀN c = −Nᵀz. Empty when NᵀN is singular
/// in the scalar's arithmetic.
fn least_norm_member<T: Scalar>(z: &[T], null: &[Vec<T>]) -> Vec<T> {
    let k = null.len();
    let mut gram: Vec<T> = Vec::with_capacity(k * k);
    for p in null {
        for q in null {
            gram.push(dot(p, q));
        }
    }
    let mut rhs: Vec<T> = null.iter().map(|p| -dot(p, z)).collect();
    let (mut pivots, mut c) = (Vec::new(), Vec::new());
    let mut out = vec![T::zero(); z.len()];
    if solve_general_in(&mut gram, k, k, &mut rhs, &mut pivots, &mut c) && pivots.len() == k {
        for (w, cj) in null.iter().zip(&c) {
            for (o, wj) in out.iter_mut().zip(w) {
                *o += wj.clone() * cj;
            }
        }
    }
    out
}

/// With null directions whose normal parts lie on one line (the usual face: four points, one
/// way to shift impulse between its diagonals), the further shift c·w from z to the
/// nearest member whose normal rates are all nonnegative — the interval of c where
/// p_j + c w_j ≥ 0 for every normal unknown j, clamped at 0; empty when no shift is needed,
/// the interval is empty (the tensile rate is then reported), or the family is wider.
fn nonnegative_shift<T: Scalar>(columns: &Columns<T>, z: &[T], null: &[Vec<T>]) -> Vec<T> {
    let normal_null: Vec<&Vec<T>> = null
        .iter()
        .filter(|w| {
            columns
                .iter()
                .zip(w.iter())
                .any(|((u, _), wj)| matches!(u, Unknown::Normal(_)) && !wj.is_zero())
        })
        .collect();
    // Their normal parts: one line for a face (four points, one way to shift impulse between
    // its diagonals), however many basis directions touch it (sticking contacts add
    // tangential unknowns to each). The direction with the largest normal part stands for it.
    let normal_part = |w: &[T]| -> Vec<T> {
        columns
            .iter()
            .zip(w)
            .filter(|((u, _), _)| matches!(u, Unknown::Normal(_)))
            .map(|(_, wj)| wj.clone())
            .collect()
    };
    let Some(w) = normal_null.iter().copied().reduce(|a, c| {
        match max_abs(&normal_part(c)).abs_gt(&max_abs(&normal_part(a))) {
            true => c,
            false => a,
        }
    }) else {
        return Vec::new();
    };
    let wn = normal_part(w);
    let ww = dot(&wn, &wn);
    let on_one_line = normal_null.iter().all(|v| {
        let vn = normal_part(v);
        let alpha = dot(&vn, &wn) / ww.clone();
        let scale = max_abs(&vn);
        vn.iter().zip(&wn).all(|(a, c)| {
            (a.clone() - alpha.clone() * c).is_negligible(&scale, vn.len() * vn.len())
        })
    });
    if !on_one_line {
        return Vec::new();
    }
    let mut lo: Option<T> = None;
    let mut hi: Option<T> = None;
    for (((u, _), zj), wj) in columns.iter().zip(z).zip(w.iter()) {
        if !matches!(u, Unknown::Normal(_)) || wj.is_zero() {
            continue;
        }
        // p_j + c w_j ≥ 0: c ≥ −p_j/w_j when w_j > 0, c ≤ −p_j/w_j when w_j < 0
        let end = -zj.clone() / wj.clone();
        if wj.signum_i8() > 0 {
            if lo
                .as_ref()
                .is_none_or(|x| (end.clone() - x).signum_i8() > 0)
            {
                lo = Some(end);
            }
        } else if hi
            .as_ref()
            .is_none_or(|x| (end.clone() - x).signum_i8() < 0)
        {
            hi = Some(end);
        }
    }
    let c = match (lo, hi) {
        (Some(l), Some(h)) if (h.clone() - &l).signum_i8() < 0 => return Vec::new(),
        (Some(l), _) if l.signum_i8() > 0 => l,
        (_, Some(h)) if h.signum_i8() < 0 => h,
        _ => return Vec::new(),
    };
    w.iter().map(|wj| wj.clone() * &c).collect()
}

/// z += d, entry by entry (nothing when d is empty).
fn add<T: Scalar>(z: &mut [T], d: &[T]) {
    for (zj, dj) in z.iter_mut().zip(d) {
        *zj += dj.clone();
    }
}

/// The shift, along the directions of the family that leave every normal rate alone, to the
/// member that loads the sticking contacts in proportion to their cones: the least
/// Σ_i |τ'_i|² / (μ_i p'_i) over the sticking contacts i (p'_i their normal rates in
/// `lambda`). A force shared by contacts that stand for one another is then split in proportion
/// to μ_i p'_i, each at the same fraction of its cone — the member most likely inside every
/// cone, which is what [`super::modes`] checks next. A sticking contact with no normal rate is
/// weighted as one with 10⁻⁹ of the largest cone (its tangential rate is kept near zero).
/// Empty when no sticking contact shares an impulse.
fn cone_weighted_shift<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    columns: &Columns<T>,
    z: &[T],
    null: &[Vec<T>],
    lambda: &[T],
) -> Vec<T> {
    let unknowns: Vec<Unknown> = columns.iter().map(|(u, _)| u).collect();
    let normal_rows: Vec<usize> = (0..unknowns.len())
        .filter(|&j| matches!(unknowns[j], Unknown::Normal(_)))
        .collect();
    // combinations of the null directions with no normal entry
    let k = null.len();
    let mut a = Vec::with_capacity(normal_rows.len() * k);
    for &j in &normal_rows {
        a.extend(null.iter().map(|w| w[j].clone()));
    }
    let (_, combinations) = crate::linalg::gauss::null_space(&a, normal_rows.len(), k);
    let dirs: Vec<Vec<T>> = combinations
        .iter()
        .map(|c| {
            let mut d = vec![T::zero(); z.len()];
            for (w, cl) in null.iter().zip(c) {
                if !cl.is_zero() {
                    add(
                        &mut d,
                        &w.iter().map(|x| x.clone() * cl).collect::<Vec<T>>(),
                    );
                }
            }
            d
        })
        .collect();
    // the cone of each sticking unknown's contact
    let cone = |j: usize| match unknowns[j] {
        Unknown::Stick(i) => Some(b.mu[i].clone() * &lambda[b.offset[i]]),
        Unknown::Normal(_) => None,
    };
    let largest = max_abs(&(0..z.len()).filter_map(cone).collect::<Vec<T>>());
    let Some(floor) = T::from_f64(1e-9).map(|f| f * &largest) else {
        return Vec::new();
    };
    if dirs.is_empty() || largest.is_zero() {
        return Vec::new();
    }
    let weight = |j: usize| {
        cone(j).map(|c| {
            let c = if (c.clone() - &floor).signum_i8() > 0 {
                c
            } else {
                floor.clone()
            };
            T::one() / c
        })
    };
    let weights: Vec<Option<T>> = (0..z.len()).map(weight).collect();
    let m = dirs.len();
    let mut gram = Vec::with_capacity(m * m);
    for p in &dirs {
        for q in &dirs {
            let mut s = T::zero();
            for (j, wj) in weights.iter().enumerate() {
                if let Some(wj) = wj {
                    s += p[j].clone() * &q[j] * wj;
                }
            }
            gram.push(s);
        }
    }
    let mut rhs: Vec<T> = dirs
        .iter()
        .map(|p| {
            let mut s = T::zero();
            for (j, wj) in weights.iter().enumerate() {
                if let Some(wj) = wj {
                    s -= p[j].clone() * &z[j] * wj;
                }
            }
            s
        })
        .collect();
    let (mut pivots, mut c) = (Vec::new(), Vec::new());
    if !solve_general_in(&mut gram, m, m, &mut rhs, &mut pivots, &mut c) || pivots.len() != m {
        return Vec::new();
    }
    let mut out = vec![T::zero(); z.len()];
    for (d, cl) in dirs.iter().zip(&c) {
        add(
            &mut out,
            &d.iter().map(|x| x.clone() * cl).collect::<Vec<T>>(),
        );
    }
    out
}
