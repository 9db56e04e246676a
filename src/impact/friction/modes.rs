//! Choosing the modes at an event, jointly over every contact whose slip is zero.
//!
//! Each such contact may stick, or (in the plane) slide in either sense. An assignment is
//! *consistent* when its rates exist ([`super::rates`]) and
//!
//! ```text
//! stick:      p'_i ≥ 0 and |τ'_i| ≤ μ_i p'_i      (the required rate lies in the cone)
//! slide ±:    ± v'_it > 0                          (the slip grows in the sense assumed)
//! ```
//!
//! Under the unilateral law ([`resolve_planar_unilateral`]) each contact on its prescribed path
//! is also driven along it (p'_i ≥ its base rate) or released (its gap does not close,
//! g'_i ≥ 0): 2^n × 3^m assignments.
//!
//! Every assignment is tried (3^m for m contacts at zero slip); the first consistent one in the
//! order stick, slide+, slide− per contact is taken, and the number of consistent ones is
//! reported, so that "none" and "several" are verdicts rather than silent choices.

use crate::impact::friction::blocks::Blocks;
use crate::impact::friction::rates::{
    Mode, Normal, RateFailure, RateWork, Rates, Unilateral, impulse_rates_with, max_abs,
};
use crate::mechanics::screw::Screws;
use crate::scalar::Scalar;

/// The modes chosen at an event.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolution<T: Scalar> {
    /// The modes of every contact.
    pub modes: Vec<Mode<T>>,
    /// The normal rule of every contact (as given, or as the unilateral law chose it).
    pub normals: Vec<Normal<T>>,
    /// Their rates.
    pub rates: Rates<T>,
    /// How many distinct rates the consistent assignments have (1: the rates are determined).
    pub consistent: usize,
}

/// No assignment was consistent; `undetermined` when some had undetermined rates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoConsistentModes {
    /// Some assignment had a family of rates that moves the body differently.
    pub undetermined: bool,
}

/// The most contacts at zero slip resolved jointly (3^m assignments).
pub const MAX_CANDIDATES: usize = 8;

/// `x ≥ 0`, to rounding relative to `scale` in floats.
pub(super) fn nonnegative<T: Scalar>(x: &T, scale: &T, n: usize) -> bool {
    x.signum_i8() >= 0 || x.is_negligible(scale, n)
}

/// `x > 0`, beyond rounding relative to `scale` in floats.
pub(super) fn positive<T: Scalar>(x: &T, scale: &T, n: usize) -> bool {
    x.signum_i8() > 0 && !x.is_negligible(scale, n)
}

/// Resolve the planar modes of the `candidates` (contacts at zero slip), the others keeping
/// theirs in `current`.
///
/// # Errors
/// [`NoConsistentModes`] when no assignment is consistent.
pub fn resolve_planar<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    current: &[Mode<T>],
    candidates: &[usize],
) -> Result<Resolution<T>, NoConsistentModes> {
    let mut work = Work::default();
    let mut modes = current.to_vec();
    let consistent = resolve_planar_with(b, normals, &mut modes, candidates, &mut work)?;
    Ok(Resolution {
        modes,
        normals: normals.to_vec(),
        rates: work.chosen,
        consistent,
    })
}

/// [`resolve_planar`] on buffers kept from event to event (`work`), in place: the assignments
/// are tried in `modes` itself, which is left holding the one chosen, its rates in
/// [`Work::chosen`]; returns how many distinct rates the consistent assignments have. Nothing is
/// allocated once the buffers have grown (the rates by [`super::rates::rates_with`]); the modes, rates and
/// count are [`resolve_planar`]'s, bit for bit.
///
/// # Errors
/// [`NoConsistentModes`] when no assignment is consistent (`modes` is then left at the last
/// assignment tried).
pub fn resolve_planar_with<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &mut [Mode<T>],
    candidates: &[usize],
    work: &mut Work<T>,
) -> Result<usize, NoConsistentModes> {
    let mut search = Search::new(work, false);
    search.tangential(b, normals, modes, candidates, &[]);
    let Some(code) = search.first_code else {
        return Err(NoConsistentModes {
            undetermined: search.undetermined,
        });
    };
    let distinct = search.distinct;
    assign_all(modes, candidates, code, &mut work.spare);
    Ok(distinct)
}

/// The buffers of a mode search, kept from one event to the next: the rate solve's
/// ([`RateWork`]), the rates of the assignment being tried, those of the first consistent one,
/// the distinct rates found (flat, `len` entries each), and the slide directions of
/// candidates last tried sticking, kept for their next slide.
#[derive(Clone, Debug)]
pub struct Work<T: Scalar> {
    solve: RateWork<T>,
    rates: Rates<T>,
    /// The rates of the assignment [`resolve_planar_with`] chose.
    pub chosen: Rates<T>,
    distinct: Vec<T>,
    spare: Vec<Vec<T>>,
}

impl<T: Scalar> Work<T> {
    /// Set `mode` to [`Mode::Free`], keeping a slide's direction for a later slide.
    pub fn free(&mut self, mode: &mut Mode<T>) {
        if let Mode::Slide(u) = std::mem::replace(mode, Mode::Free) {
            self.spare.push(u);
        }
    }

    /// Set `mode` to a slide along the single direction `sense` (planar), reusing its
    /// direction or a spare one rather than allocating.
    pub fn slide(&mut self, mode: &mut Mode<T>, sense: T) {
        match mode {
            Mode::Slide(u) => {
                u.clear();
                u.push(sense);
            }
            m => {
                let mut u = self.spare.pop().unwrap_or_default();
                u.clear();
                u.push(sense);
                if let Mode::Slide(old) = std::mem::replace(m, Mode::Slide(u)) {
                    self.spare.push(old);
                }
            }
        }
    }
}

impl<T: Scalar> Default for Work<T> {
    fn default() -> Self {
        Work {
            solve: RateWork::default(),
            rates: Rates::default(),
            chosen: Rates::default(),
            distinct: Vec::new(),
            spare: Vec::new(),
        }
    }
}

/// Set the `candidates`' modes to assignment `code` (base 3, the last candidate varying
/// fastest: stick, slide+, slide−), with the slide directions of `spare`.
fn assign_all<T: Scalar>(
    modes: &mut [Mode<T>],
    candidates: &[usize],
    code: usize,
    spare: &mut Vec<Vec<T>>,
) {
    let mut c = code;
    for &i in candidates.iter().rev() {
        assign(&mut modes[i], c % 3, spare);
        c /= 3;
    }
}

/// Take the `candidates`' modes from assignment `from` (as [`assign_all`] left them; `None`:
/// unknown) to assignment `code`, setting only the candidates whose choice differs: the modes
/// [`assign_all`]`(code)` sets, the others' already theirs.
fn assign_changed<T: Scalar>(
    modes: &mut [Mode<T>],
    candidates: &[usize],
    from: Option<usize>,
    code: usize,
    spare: &mut Vec<Vec<T>>,
) {
    let (mut c, mut p) = (code, from);
    for &i in candidates.iter().rev() {
        if p == Some(c) {
            // the remaining (slower) choices agree
            return;
        }
        if p.is_none_or(|p| p % 3 != c % 3) {
            assign(&mut modes[i], c % 3, spare);
        }
        c /= 3;
        p = p.map(|p| p / 3);
    }
}

/// Set a planar candidate's mode to choice `k` of stick, slide+, slide−, reusing a slide's
/// direction rather than allocating a new one: a slide set to stick leaves its direction in
/// `spare`, and a slide set from another mode takes one from there.
fn assign<T: Scalar>(mode: &mut Mode<T>, k: usize, spare: &mut Vec<Vec<T>>) {
    let sense = || if k == 1 { T::one() } else { -T::one() };
    match (k, &mut *mode) {
        (0, _) => {
            if let Mode::Slide(u) = std::mem::replace(mode, Mode::Stick) {
                spare.push(u);
            }
        }
        (_, Mode::Slide(u)) => {
            u.clear();
            u.push(sense());
        }
        _ => {
            let mut u = spare.pop().unwrap_or_default();
            u.clear();
            u.push(sense());
            *mode = Mode::Slide(u);
        }
    }
}

/// Resolve the normal rules and the planar modes jointly under the unilateral law: every
/// contact on its path (`on_path[i]`, gap g_i = 0) is driven along it or released
/// ([`Unilateral::options`], the phase's own rule first); every other contact keeps its
/// given rate. A contact that carries a normal impulse rate then sticks or slides as in
/// [`resolve_planar`] when `zero_slip[i]`, or slides in the sense `slip[i]` (±1) otherwise;
/// one that carries none is free. The tests, with those of the module docs:
///
/// ```text
/// driven:    p'_i ≥ base_i                     (no tensile rate beyond the given one)
/// released:  g'_i = −path_i − v'_ix ≥ 0         (it does not cross its path)
/// ```
///
/// — with μ = 0 and base 0, the linear complementarity problem LCP(G, −path) on the contacts
/// on their path. The count of consistent assignments counts distinct rates (a contact with
/// p'_i = 0 and g'_i = 0 is both driven and released, with one set of rates).
///
/// # Errors
/// [`NoConsistentModes`] when no assignment is consistent.
pub fn resolve_planar_unilateral<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    rules: &[Unilateral<T>],
    on_path: &[bool],
    zero_slip: &[bool],
    slip: &[T],
) -> Result<Resolution<T>, NoConsistentModes> {
    let n = rules.len();
    let mut work = Work::default();
    let mut search = Search::new(&mut work, true);
    for a in unilateral_assignments(rules, on_path) {
        let mut modes = Vec::with_capacity(n);
        let mut candidates = Vec::new();
        for i in 0..n {
            modes.push(if b.dims[i] == 0 || !carries(&a.normals[i]) {
                Mode::Free
            } else if zero_slip[i] {
                candidates.push(i);
                Mode::Stick
            } else {
                Mode::Slide(vec![slip[i].clone()])
            });
        }
        search.tangential(b, &a.normals, &mut modes, &candidates, &a.checks);
    }
    search.finish()
}

/// Whether a contact under `normal` takes a normal impulse rate (and so can carry friction).
pub fn carries<T: Scalar>(normal: &Normal<T>) -> bool {
    match normal {
        Normal::Driven(_) => true,
        Normal::Given(r) => !r.is_zero(),
    }
}

/// One assignment of the unilateral law's normal rules: every contact on its path driven or
/// released, the others at their base rate, with the tests the rates must pass.
#[derive(Clone, Debug)]
pub struct Assignment<T: Scalar> {
    /// The rule of every contact.
    pub normals: Vec<Normal<T>>,
    /// The normal tests of the contacts on their paths.
    pub checks: Vec<(usize, Check<T>)>,
}

/// Every assignment of driven/released to the contacts `on_path` ([`Unilateral::options`],
/// each contact's own rule first, the first contact varying slowest): 2^k for k on their
/// paths. The order is the preference: the planar and the spatial integrations both take the
/// first consistent one ([`resolve_planar_unilateral`], `spatial::choose`).
pub fn unilateral_assignments<T: Scalar>(
    rules: &[Unilateral<T>],
    on_path: &[bool],
) -> Vec<Assignment<T>> {
    let engaged: Vec<usize> = (0..rules.len()).filter(|&i| on_path[i]).collect();
    (0..(1usize << engaged.len()))
        .map(|code| {
            let mut normals: Vec<Normal<T>> = rules
                .iter()
                .map(|u| Normal::Given(u.base.clone()))
                .collect();
            let mut checks = Vec::with_capacity(engaged.len());
            for (j, &i) in engaged.iter().enumerate() {
                let choice = (code >> (engaged.len() - 1 - j)) & 1;
                let rule = rules[i].options()[choice].clone();
                checks.push(match &rule {
                    Normal::Driven(_) => (i, Check::AtLeast(rules[i].base.clone())),
                    Normal::Given(_) => (i, Check::Separates(rules[i].path.clone())),
                });
                normals[i] = rule;
            }
            Assignment { normals, checks }
        })
        .collect()
}

/// A test on a contact's normal rate under the unilateral law.
#[derive(Clone, Debug, PartialEq)]
pub enum Check<T> {
    /// Driven: p'_i ≥ the given least rate.
    AtLeast(T),
    /// Released: −path − v'_ix ≥ 0.
    Separates(T),
}

/// The consistent assignments found so far: the first (its code among the candidates', its
/// rates in `work.chosen`, and — when `record`, for searches over several normal rules — its
/// modes and rules), and the count of distinct rates (kept in `work.distinct`).
struct Search<'w, T: Scalar> {
    first_code: Option<usize>,
    record: bool,
    first: Option<Resolution<T>>,
    distinct: usize,
    undetermined: bool,
    work: &'w mut Work<T>,
}

impl<'w, T: Scalar> Search<'w, T> {
    fn new(work: &'w mut Work<T>, record: bool) -> Self {
        work.distinct.clear();
        Search {
            first_code: None,
            record,
            first: None,
            distinct: 0,
            undetermined: false,
            work,
        }
    }

    /// Try every stick/slide+/slide− assignment of the `candidates` under `normals`.
    fn tangential<S: Screws<T>>(
        &mut self,
        b: &Blocks<T, S>,
        normals: &[Normal<T>],
        modes: &mut [Mode<T>],
        candidates: &[usize],
        checks: &[(usize, Check<T>)],
    ) {
        let total = 3usize.pow(candidates.len() as u32);
        for code in 0..total {
            let last = code.checked_sub(1);
            assign_changed(modes, candidates, last, code, &mut self.work.spare);
            let Work { solve, rates, .. } = &mut *self.work;
            match impulse_rates_with(b, normals, modes, solve, rates) {
                Ok(()) => {
                    // v′ = −K λ′ only once a test or the first consistent assignment reads it
                    let mut velocity = Velocity::Stale;
                    let consistent = planar_consistent(b, modes, rates, candidates, &mut velocity)
                        && (checks.is_empty() || {
                            velocity.fresh(b, rates);
                            normal_consistent(b, rates, checks, &T::zero(), &T::zero())
                        });
                    if consistent {
                        if self.first_code.is_none() {
                            velocity.fresh(b, rates);
                        }
                        self.found(code, modes, normals);
                    }
                }
                Err(RateFailure::Undetermined) => self.undetermined = true,
                Err(RateFailure::Inconsistent) => {}
            }
        }
    }

    fn found(&mut self, code: usize, modes: &[Mode<T>], normals: &[Normal<T>]) {
        let Work {
            rates: r,
            chosen,
            distinct,
            ..
        } = &mut *self.work;
        let scale = max_abs(&r.lambda);
        let n = r.lambda.len();
        let same = |d: &[T]| {
            d.iter()
                .zip(&r.lambda)
                .all(|(x, y)| (x.clone() - y).is_negligible(&scale, n))
        };
        let seen = if n == 0 {
            self.distinct > 0
        } else {
            distinct.chunks(n).any(same)
        };
        if !seen {
            distinct.extend_from_slice(&r.lambda);
            self.distinct += 1;
        }
        if self.first_code.is_none() {
            self.first_code = Some(code);
            chosen.lambda.clone_from(&r.lambda);
            chosen.velocity.clone_from(&r.velocity);
            chosen.split_unique = r.split_unique;
            chosen.normals_unique = r.normals_unique;
            chosen.split_moves_body = r.split_moves_body;
            if self.record {
                self.first = Some(Resolution {
                    modes: modes.to_vec(),
                    normals: normals.to_vec(),
                    rates: r.clone(),
                    consistent: 0,
                });
            }
        }
    }

    fn finish(self) -> Result<Resolution<T>, NoConsistentModes> {
        match self.first {
            Some(first) => Ok(Resolution {
                consistent: self.distinct,
                ..first
            }),
            None => Err(NoConsistentModes {
                undetermined: self.undetermined,
            }),
        }
    }
}

/// The normal tests of [`resolve_planar_unilateral`] on the rates `r`: each margin p'_i − base
/// and −path − v'_ix, plus its slack (`slack_impulse`, `slack_velocity`: zero in the planar
/// solve, where only rounding is forgiven; the spatial integration's event slack, whose rates
/// carry its tolerance), nonnegative to rounding.
pub fn normal_consistent<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    r: &Rates<T>,
    checks: &[(usize, Check<T>)],
    slack_impulse: &T,
    slack_velocity: &T,
) -> bool {
    if checks.is_empty() {
        return true;
    }
    let n = b.len();
    let scale_l = max_abs(&r.lambda);
    let scale_v = max_abs(&r.velocity);
    checks.iter().all(|(i, check)| {
        let off = b.offset[*i];
        match check {
            Check::AtLeast(base) => {
                nonnegative(&(r.lambda[off].clone() - base + slack_impulse), &scale_l, n)
            }
            Check::Separates(path) => nonnegative(
                &(-path.clone() - &r.velocity[off] + slack_velocity),
                &scale_v,
                n,
            ),
        }
    })
}

/// Whether the velocity rates of a search's [`Rates`] are those of its impulse rates: the
/// search solves the impulse rates alone ([`impulse_rates_with`]) and computes v′ = −K λ′ when
/// it first reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Velocity {
    /// `velocity` is left from an earlier solve.
    Stale,
    /// `velocity` is −K `lambda`.
    Fresh,
}

impl Velocity {
    /// Make `r.velocity` −K `r.lambda` ([`Blocks::velocity_change`]) if it is not yet.
    fn fresh<T: Scalar, S: Screws<T>>(&mut self, b: &Blocks<T, S>, r: &mut Rates<T>) {
        if *self == Velocity::Stale {
            b.velocity_change(&r.lambda, &mut r.velocity);
            *self = Velocity::Fresh;
        }
    }
}

/// The tests of the module docs for the candidates, in their order, the first failure ending
/// them. Each scale is found when a test first needs it: max |λ′| for a stick's, max |v′| for a
/// slide whose slip rate has the sense assumed — a slide whose slip rate has not fails whatever
/// the scale, its one entry of v′ = −K λ′ computed alone ([`Blocks::velocity_change_at`]); the
/// velocity rates are made fresh by the first slide that needs their scale.
fn planar_consistent<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    modes: &[Mode<T>],
    r: &mut Rates<T>,
    candidates: &[usize],
    velocity: &mut Velocity,
) -> bool {
    if candidates.is_empty() {
        return true;
    }
    let n = b.len();
    let mut scale_l: Option<T> = None;
    let mut scale_v: Option<T> = None;
    for &i in candidates {
        let off = b.offset[i];
        let holds = match &modes[i] {
            Mode::Stick => {
                let scale_l = scale_l.get_or_insert_with(|| max_abs(&r.lambda));
                let p = &r.lambda[off];
                let bound = b.mu[i].clone() * p;
                let t = &r.lambda[off + 1];
                let t_abs = if t.signum_i8() < 0 {
                    -t.clone()
                } else {
                    t.clone()
                };
                nonnegative(p, scale_l, n) && nonnegative(&(bound - t_abs), scale_l, n)
            }
            Mode::Slide(u) => {
                let slip = match velocity {
                    Velocity::Fresh => r.velocity[off + 1].clone(),
                    Velocity::Stale => b.velocity_change_at(&r.lambda, off + 1),
                };
                let grows = u[0].clone() * &slip;
                grows.signum_i8() > 0 && {
                    let scale_v = scale_v.get_or_insert_with(|| {
                        velocity.fresh(b, r);
                        max_abs(&r.velocity)
                    });
                    positive(&grows, scale_v, n)
                }
            }
            Mode::Free => true,
        };
        if !holds {
            return false;
        }
    }
    true
}
