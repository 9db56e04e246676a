//! Planar scenes, event by event, exactly.
//!
//! In a planar scene ([`super::blocks`]) every slip direction is ±t_i, so between two events
//! every rate is constant: Λ(s) and v(s) are piecewise linear, and an event falls where a
//! linear slip velocity reaches zero (a rational s, or in the field of the inputs), at the end
//! of a phase (s = 1, s = 2), or where an energetic contact's restitution work — a quadratic
//! in s — reaches k_i² times its compression work (a root of a quadratic: the radical field).
//! The works and the friction dissipation are integrated exactly segment by segment
//! (∫ v dΛ of a linear v against a constant rate is the trapezoid rule, exact).

use crate::impact::friction::blocks::Blocks;
use crate::impact::friction::modes::{
    MAX_CANDIDATES, NoConsistentModes, Resolution, Work, carries, resolve_planar_unilateral,
    resolve_planar_with,
};
use crate::impact::friction::rates::{
    Mode, Normal, Unilateral, normal_rules_into, unilateral_rules,
};
use crate::impact::friction::{
    FrictionError, Frictional, Hypothesis, Phase, Restitution, Segment, Verdict, labels,
};
use crate::impact::mechanism::Mechanism;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::Screws;
use crate::scalar::Scalar;

/// The most events one impact may have before the integration is declared runaway.
const MAX_EVENTS: usize = 10_000;

/// The state carried from event to event.
struct State<T: Scalar> {
    s: T,
    phase: Phase,
    lambda: Vec<T>,
    v: Vec<T>,
    modes: Vec<Mode<T>>,
    stopped: Vec<bool>,
    compression: Vec<T>,
    work_compression: Vec<T>,
    work_restitution: Vec<T>,
    friction_work: T,
    /// g_i = v_i^path(s) − v_ix per contact (unilateral law; continuous at s = 1, where every
    /// path is at v_ix = 0).
    gap: Vec<T>,
    /// Per contact, under the simultaneous hypothesis: held on its path by a pull at zero slip,
    /// freed of friction ([`resolve_simultaneous`]).
    pulling: Vec<bool>,
    /// The contacts at zero slip whose modes the last search chose (a buffer kept from event
    /// to event, [`assign_simultaneous`]).
    candidates: Vec<usize>,
}

/// Solve a planar scene under `law` and `hypothesis`, event by event.
///
/// Under the unilateral law the normal rules are chosen with the modes at every event
/// ([`resolve_planar_unilateral`]), and a released contact's gap, linear between events,
/// adds an event where it closes (the contact re-engages).
///
/// # Errors
/// [`FrictionError`] when the modes cannot be chosen, the rates are undetermined, an
/// energetic contact never stops, or a stop needs a square root the scalar does not hold.
pub fn solve_planar<T: Scalar, S: Screws<T>, M: Mechanism<T, Screw = S>>(
    mechanism: &M,
    b: Blocks<T, S>,
    law: Restitution,
    hypothesis: Hypothesis,
) -> Result<Frictional<T, S>, FrictionError> {
    let contacts = mechanism.contacts();
    let n = b.contacts();
    let two = T::one() + T::one();
    let mut st = State {
        s: T::zero(),
        phase: Phase::Compression,
        lambda: vec![T::zero(); b.len()],
        v: b.v0.clone(),
        modes: vec![Mode::Free; n],
        stopped: vec![false; n],
        compression: Vec::new(),
        work_compression: vec![T::zero(); n],
        work_restitution: vec![T::zero(); n],
        friction_work: T::zero(),
        gap: vec![T::zero(); n],
        pulling: vec![false; n],
        candidates: Vec::with_capacity(n),
    };
    let mut segments = Vec::new();
    let mut verdicts = Vec::new();
    // The mode search's buffers and the events' candidates, kept from event to event.
    let mut work = Work::default();
    let (mut reversals, mut engages, mut stops) = (Vec::new(), Vec::new(), Vec::new());
    // The phase's normal rules, rewritten in place at every event.
    let mut simultaneous = Vec::with_capacity(n);
    for events in 1..=MAX_EVENTS {
        normals(contacts, &b, &st, law, &mut simultaneous);
        let rules = match hypothesis {
            Hypothesis::Simultaneous => Vec::new(),
            Hypothesis::Unilateral => unilateral_rules(&simultaneous, &b, st.phase),
        };
        let (unilateral, unilateral_normals);
        let (normals, r, consistent) = match hypothesis {
            Hypothesis::Simultaneous => {
                let consistent = resolve_simultaneous(&b, &simultaneous, &mut st, &mut work)?;
                (simultaneous.as_slice(), &work.chosen, consistent)
            }
            Hypothesis::Unilateral => {
                let res = resolve_unilateral(&b, &rules, &st)?;
                st.modes = res.modes;
                unilateral = res.rates;
                unilateral_normals = res.normals;
                (unilateral_normals.as_slice(), &unilateral, res.consistent)
            }
        };
        if consistent > 1 {
            verdicts.push(Verdict::Ambiguous {
                s: st.s.to_f64(),
                consistent,
            });
        }
        if let Some(v) = super::split_verdict(r, st.s.to_f64(), law, contacts) {
            verdicts.push(v);
        }
        for (i, normal) in normals.iter().enumerate() {
            if hypothesis == Hypothesis::Simultaneous
                && matches!(normal, Normal::Driven(_))
                && r.lambda[b.offset[i]].signum_i8() < 0
            {
                verdicts.push(Verdict::TensileRate {
                    contact: i,
                    s: st.s.to_f64(),
                    phase: st.phase,
                });
            }
        }
        // The next event.
        let end = match (st.phase, law) {
            (Phase::Compression, _) => Some(T::one() - &st.s),
            (Phase::Restitution, Restitution::Energetic) => None,
            (Phase::Restitution, _) => Some(two.clone() - &st.s),
        };
        let mut h = end.clone();
        let take = |cand: T, h: &mut Option<T>| {
            if h.as_ref()
                .is_none_or(|x| (cand.clone() - x).signum_i8() < 0)
            {
                *h = Some(cand);
            }
        };
        reversals.clear();
        for i in 0..n {
            if let Mode::Slide(u) = &st.modes[i] {
                let off = b.offset[i] + 1;
                let dv = &r.velocity[off];
                if (u[0].clone() * dv).signum_i8() < 0 {
                    let hi = -st.v[off].clone() / dv.clone();
                    reversals.push((i, hi.clone()));
                    take(hi, &mut h);
                }
            }
        }
        // A released contact whose gap closes re-engages.
        engages.clear();
        if hypothesis == Hypothesis::Unilateral {
            for i in 0..n {
                if let Normal::Given(_) = normals[i] {
                    let closing = r.velocity[b.offset[i]].clone() + &rules[i].path;
                    if closing.signum_i8() > 0 && !st.gap[i].is_zero() {
                        let hi = st.gap[i].clone() / closing;
                        engages.push((i, hi.clone()));
                        take(hi, &mut h);
                    }
                }
            }
        }
        stops.clear();
        if st.phase == Phase::Restitution && law == Restitution::Energetic {
            for i in 0..n {
                if st.stopped[i] {
                    continue;
                }
                if let Some(hi) = energetic_stop(contacts, &b, &st, &r.lambda, &r.velocity, i)? {
                    stops.push((i, hi.clone()));
                    take(hi, &mut h);
                }
            }
        }
        let Some(h) = h else {
            let contact = (0..n).find(|&i| !st.stopped[i]).unwrap_or(0);
            return Err(FrictionError::NeverEnds { contact });
        };
        let from = st.s.clone();
        advance(&b, &mut st, &r.lambda, &r.velocity, &h);
        if hypothesis == Hypothesis::Unilateral {
            close_gaps(&b, &mut st, &rules, normals, &r.velocity, &h);
        }
        let fired = |hi: &T| (hi.clone() - &h).is_negligible(&h, n);
        for (i, hi) in &engages {
            if fired(hi) {
                st.gap[*i] = T::zero();
            }
        }
        for (i, hi) in &reversals {
            if fired(hi) {
                st.v[b.offset[*i] + 1] = T::zero();
            }
        }
        for (i, hi) in &stops {
            if fired(hi) {
                st.stopped[*i] = true;
            }
        }
        for i in 0..n {
            if st.modes[i] == Mode::Stick {
                st.v[b.offset[i] + 1] = T::zero();
            }
        }
        if !h.is_zero() {
            segments.push(Segment {
                from,
                to: st.s.clone(),
                phase: st.phase,
                modes: labels(hypothesis, normals, &st.modes),
                rates: r.lambda.clone(),
            });
        }
        let at_end = end.as_ref().is_some_and(fired);
        match (st.phase, at_end) {
            (Phase::Compression, true) => {
                st.s = T::one();
                st.phase = Phase::Restitution;
                st.compression = b.offset.iter().map(|&o| st.lambda[o].clone()).collect();
                if law == Restitution::Energetic {
                    for i in 0..n {
                        let left = contacts[i].k_energetic.clone()
                            * &contacts[i].k_energetic
                            * &st.work_compression[i];
                        st.stopped[i] = st.compression[i].is_zero() || left.signum_i8() <= 0;
                    }
                }
            }
            (Phase::Restitution, true) => {
                st.s = two.clone();
                break;
            }
            _ => {}
        }
        if law == Restitution::Energetic
            && st.phase == Phase::Restitution
            && st.stopped.iter().all(|&x| x)
        {
            break;
        }
        if events == MAX_EVENTS {
            return Err(FrictionError::Runaway);
        }
    }
    let mut out = Frictional::finish(
        mechanism,
        b,
        law,
        st.lambda,
        st.compression,
        st.v,
        st.work_compression,
        st.work_restitution,
        st.friction_work,
        segments,
        verdicts,
        st.s,
    );
    out.hypothesis = hypothesis;
    Ok(out)
}

/// The simultaneous law's modes at an event: contacts at zero slip stick or slide jointly
/// ([`resolve_planar_with`]), the others slide in the sense of their slip. A contact at zero
/// slip that its path makes pull has no Coulomb assignment (no cone to stick in; a slide's
/// friction μ p' u would act along the slip): where no assignment is consistent, the first
/// such contact (in order) whose freeing of friction leaves a consistent assignment in which
/// it still pulls carries no friction while it pulls — checked at every event, the rates being
/// constant between events (the spatial integrator's rule, [`super::spatial`]).
fn resolve_simultaneous<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    st: &mut State<T>,
    work: &mut Work<T>,
) -> Result<usize, FrictionError> {
    let n = b.contacts();
    let pulls = |i: usize, work: &Work<T>| work.chosen.lambda[b.offset[i]].signum_i8() < 0;
    // The freed contacts and the candidates' buffer are taken out of the state while the
    // searches run on it, and put back (an error ends the impact: the state is dropped).
    let mut pulling = std::mem::take(&mut st.pulling);
    let mut candidates = std::mem::take(&mut st.candidates);
    for _ in 0..=n {
        let found = assign_simultaneous(b, normals, st, &pulling, work, &mut candidates)?;
        match found {
            Ok(count) => {
                // a contact freed that no longer pulls takes Coulomb's law again
                if let Some(i) = (0..n).find(|&i| pulling[i] && !pulls(i, work)) {
                    pulling[i] = false;
                    continue;
                }
                st.pulling = pulling;
                st.candidates = candidates;
                return Ok(count);
            }
            Err(e) => {
                let mut scratch = Vec::new();
                for &i in &candidates {
                    if !matches!(normals[i], Normal::Driven(_)) {
                        continue;
                    }
                    let mut trial = pulling.clone();
                    trial[i] = true;
                    let found = assign_simultaneous(b, normals, st, &trial, work, &mut scratch)?;
                    if let Ok(count) = found
                        && (0..n).all(|j| !trial[j] || pulls(j, work))
                    {
                        st.pulling = trial;
                        st.candidates = candidates;
                        return Ok(count);
                    }
                }
                // leave the modes as the failed search left them
                let _ = assign_simultaneous(b, normals, st, &pulling, work, &mut scratch)?;
                return Err(no_modes(e, st));
            }
        }
    }
    Err(no_modes(
        NoConsistentModes {
            undetermined: false,
        },
        st,
    ))
}

/// One search of [`resolve_simultaneous`] with the contacts `pulling` freed: the search's
/// result; the contacts at zero slip it chose modes for are left in `candidates`.
fn assign_simultaneous<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    st: &mut State<T>,
    pulling: &[bool],
    work: &mut Work<T>,
    candidates: &mut Vec<usize>,
) -> Result<Result<usize, NoConsistentModes>, FrictionError> {
    candidates.clear();
    for i in 0..b.contacts() {
        let off = b.offset[i];
        if b.dims[i] == 0 || !carries(&normals[i]) || pulling[i] {
            st.modes[i] = Mode::Free;
        } else if st.v[off + 1].is_zero() {
            candidates.push(i);
        } else {
            let sense = sign(&st.v[off + 1]);
            work.slide(&mut st.modes[i], sense);
        }
    }
    if candidates.len() > MAX_CANDIDATES {
        return Err(FrictionError::TooManyAtRest {
            s: st.s.to_f64(),
            contacts: candidates.len(),
        });
    }
    Ok(resolve_planar_with(
        b,
        normals,
        &mut st.modes,
        candidates,
        work,
    ))
}

/// The unilateral law's rules and modes at an event: every contact on its path is driven or
/// released, jointly with stick and slip.
fn resolve_unilateral<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    rules: &[Unilateral<T>],
    st: &State<T>,
) -> Result<Resolution<T>, FrictionError> {
    let n = b.contacts();
    let on_path: Vec<bool> = st.gap.iter().map(|g| g.is_zero()).collect();
    let zero_slip: Vec<bool> = (0..n)
        .map(|i| b.dims[i] > 0 && st.v[b.offset[i] + 1].is_zero())
        .collect();
    let slip: Vec<T> = (0..n)
        .map(|i| match b.dims[i] {
            0 => T::zero(),
            _ if zero_slip[i] => T::zero(),
            _ => sign(&st.v[b.offset[i] + 1]),
        })
        .collect();
    // 2 rules per contact on its path, 3 modes per contact at zero slip.
    let joint = on_path.iter().filter(|&&x| x).count() + zero_slip.iter().filter(|&&x| x).count();
    if joint > MAX_CANDIDATES + 2 {
        return Err(FrictionError::TooManyAtRest {
            s: st.s.to_f64(),
            contacts: joint,
        });
    }
    resolve_planar_unilateral(b, rules, &on_path, &zero_slip, &slip).map_err(|e| no_modes(e, st))
}

/// The error of an event with no consistent assignment.
fn no_modes<T: Scalar>(e: NoConsistentModes, st: &State<T>) -> FrictionError {
    if e.undetermined {
        FrictionError::Undetermined { s: st.s.to_f64() }
    } else {
        FrictionError::NoConsistentModes {
            s: st.s.to_f64(),
            phase: st.phase,
        }
    }
}

/// Move the gaps by `h`: g'_i = −path_i − v'_ix; a driven contact stays on its path exactly.
fn close_gaps<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    st: &mut State<T>,
    rules: &[Unilateral<T>],
    normals: &[Normal<T>],
    dv: &[T],
    h: &T,
) {
    for i in 0..b.contacts() {
        st.gap[i] = match normals[i] {
            Normal::Driven(_) => T::zero(),
            Normal::Given(_) => st.gap[i].clone() - (rules[i].path.clone() + &dv[b.offset[i]]) * h,
        };
    }
}

/// ±1 by the sign of `x` (x ≠ 0).
fn sign<T: Scalar>(x: &T) -> T {
    if x.signum_i8() < 0 {
        -T::one()
    } else {
        T::one()
    }
}

/// The normal rule of every contact in the current phase, written into `out`.
fn normals<T: Scalar, S: Screws<T>>(
    contacts: &[Contact<T>],
    b: &Blocks<T, S>,
    st: &State<T>,
    law: Restitution,
    out: &mut Vec<Normal<T>>,
) {
    normal_rules_into(
        contacts,
        b,
        st.phase,
        law,
        &st.compression,
        &st.stopped,
        out,
    );
}

/// Move the state by `h` at the rates `dl` (impulses) and `dv` (velocities), integrating the
/// works exactly (trapezoid rule on a linear velocity).
fn advance<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    st: &mut State<T>,
    dl: &[T],
    dv: &[T],
    h: &T,
) {
    let two = T::one() + T::one();
    for q in 0..b.len() {
        let before = st.v[q].clone();
        st.lambda[q] += dl[q].clone() * h;
        st.v[q] += dv[q].clone() * h;
        if dl[q].is_zero() {
            continue;
        }
        let work = dl[q].clone() * h * (before + &st.v[q]) / two.clone();
        match b.offset.iter().position(|&o| o == q) {
            Some(i) if st.phase == Phase::Compression => st.work_compression[i] += work,
            Some(i) => st.work_restitution[i] -= work,
            None => st.friction_work += work,
        }
    }
    st.s += h;
}

/// The step after which energetic contact `i` has done its restitution work, k_i² W_c,i: the
/// smallest h > 0 with W_r(h) = k² W_c, where over the segment
/// W_r(h) = W_r − r (v_a h + ½ v' h²) (rate r, normal velocity v_a, its rate v'). Written in
/// the cancellation-free form h = −2C / (B + √(B² − 4AC)) of the root of A h² + B h + C.
fn energetic_stop<T: Scalar, S: Screws<T>>(
    contacts: &[Contact<T>],
    b: &Blocks<T, S>,
    st: &State<T>,
    dl: &[T],
    dv: &[T],
    i: usize,
) -> Result<Option<T>, FrictionError> {
    let off = b.offset[i];
    let k = &contacts[i].k_energetic;
    let two = T::one() + T::one();
    let c = st.work_restitution[i].clone() - k.clone() * k * &st.work_compression[i];
    if c.signum_i8() >= 0 {
        return Ok(Some(T::zero()));
    }
    let a = -(dl[off].clone() * &dv[off]) / two.clone();
    let bb = -(dl[off].clone() * &st.v[off]);
    let d = bb.clone() * &bb - (two.clone() + &two) * &a * &c;
    if d.signum_i8() < 0 {
        return Ok(None);
    }
    let root = d
        .sqrt_value()
        .ok_or(FrictionError::NeedsRadical { contact: i })?;
    let den = bb + root;
    if den.signum_i8() <= 0 {
        return Ok(None);
    }
    Ok(Some(-(two * c) / den))
}
