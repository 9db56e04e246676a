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
    FrictionError, Frictional, Hypothesis, Phase, Restitution, Sample, Segment, Spare, Verdict,
    labels_into,
};
use crate::impact::mechanism::Mechanism;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::Screws;
use crate::scalar::Scalar;

/// The most events one impact may have before the integration is declared runaway.
const MAX_EVENTS: usize = 10_000;

/// Events after which the loop starts looking for chatter ([`chatter`]): far more than the
/// few per contact an impact without chatter has (4.4 per impact on the bench's scenes), so
/// that the common case keeps no history.
const CHATTER_AFTER: usize = 64;

/// Cycles of repeated modes, each shorter than the one before, that make chatter.
const CHATTER_CYCLES: usize = 16;

/// The longest cycle of modes looked for.
const CHATTER_PERIOD: usize = 4;

/// One event as [`chatter`] compares them: the modes and phase it starts, and where.
type Event<T> = (Vec<Mode<T>>, Phase, f64);

/// Whether the last events chatter: for some period p ≤ [`CHATTER_PERIOD`], the modes and
/// phase of each of the last p · [`CHATTER_CYCLES`] events equal those p events before, and
/// each cycle advanced s no more than the one before. That is a Zeno sequence — infinitely
/// many events before a finite s, as when two contacts take turns to separate and re-engage
/// in ever shorter intervals: in rationals each event costs more than the last and the loop
/// would never end, in floats s stalls one ulp short of the accumulation point. Returns the
/// period.
fn chatter<T: Scalar>(history: &[Event<T>]) -> Option<usize> {
    (1..=CHATTER_PERIOD).find(|&p| {
        let need = p * (CHATTER_CYCLES + 1);
        let Some(tail) = history.len().checked_sub(need).map(|at| &history[at..]) else {
            return false;
        };
        let repeats = (p..need).all(|i| tail[i].0 == tail[i - p].0 && tail[i].1 == tail[i - p].1);
        let advances: Vec<f64> = (p..need)
            .step_by(p)
            .map(|i| tail[i].2 - tail[i - p].2)
            .collect();
        repeats && advances.windows(2).all(|w| w[1] <= w[0])
    })
}

/// The state carried from event to event.
#[derive(Clone, Debug)]
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

impl<T: Scalar> State<T> {
    fn empty() -> Self {
        State {
            s: T::zero(),
            phase: Phase::Compression,
            lambda: Vec::new(),
            v: Vec::new(),
            modes: Vec::new(),
            stopped: Vec::new(),
            compression: Vec::new(),
            work_compression: Vec::new(),
            work_restitution: Vec::new(),
            friction_work: T::zero(),
            gap: Vec::new(),
            pulling: Vec::new(),
            candidates: Vec::new(),
        }
    }

    /// The state at s = 0 of an impact on the blocks `b`: no impulse, the velocities before,
    /// every contact free; in place (slide directions go to `work`'s spares).
    fn start<S: Screws<T>>(&mut self, b: &Blocks<T, S>, work: &mut Work<T>) {
        let n = b.contacts();
        self.s = T::zero();
        self.phase = Phase::Compression;
        self.lambda.clear();
        self.lambda.resize(b.len(), T::zero());
        self.v.clone_from(&b.v0);
        for m in &mut self.modes {
            work.free(m);
        }
        self.modes.resize(n, Mode::Free);
        self.modes.truncate(n);
        for flags in [&mut self.stopped, &mut self.pulling] {
            flags.clear();
            flags.resize(n, false);
        }
        self.compression.clear();
        for xs in [
            &mut self.work_compression,
            &mut self.work_restitution,
            &mut self.gap,
        ] {
            xs.clear();
            xs.resize(n, T::zero());
        }
        self.friction_work = T::zero();
        self.candidates.clear();
        self.candidates.reserve(n);
    }
}

/// A planar frictional solve kept by a caller that solves impact after impact — a bench, a
/// sweep — as the frictionless solve keeps its [`crate::impact::solve::Impact`]: the blocks
/// are refilled in place ([`Blocks::planar_into`]), and the state, the mode search's buffers,
/// the events' candidates and the last report's vectors are kept and refilled, so that once
/// they have grown a solve allocates little (the report's verdicts and twist aside). Every
/// output is [`super::solve_frictional_under`]'s, bit for bit: the same operations in the same
/// order.
#[derive(Clone, Debug)]
pub struct PlanarFrictionWork<T: Scalar, S: Screws<T>> {
    blocks: Blocks<T, S>,
    state: State<T>,
    /// The mode search's buffers.
    search: Work<T>,
    /// The phase's normal rules, rewritten at every event.
    simultaneous: Vec<Normal<T>>,
    /// The events' candidates: slip reversals, re-engagements, energetic stops.
    reversals: Vec<(usize, T)>,
    engages: Vec<(usize, T)>,
    stops: Vec<(usize, T)>,
    segments: Vec<Segment<T>>,
    verdicts: Vec<Verdict>,
    samples: Vec<Sample<T>>,
    spare: Spare<T>,
    /// The last report, taken apart by the next solve.
    report: Option<Frictional<T, S>>,
}

impl<T: Scalar, S: Screws<T>> Default for PlanarFrictionWork<T, S> {
    fn default() -> Self {
        PlanarFrictionWork {
            blocks: Blocks::empty(),
            state: State::empty(),
            search: Work::default(),
            simultaneous: Vec::new(),
            reversals: Vec::new(),
            engages: Vec::new(),
            stops: Vec::new(),
            segments: Vec::new(),
            verdicts: Vec::new(),
            samples: Vec::new(),
            spare: Spare::default(),
            report: None,
        }
    }
}

impl<T: Scalar, S: Screws<T>> PlanarFrictionWork<T, S> {
    /// A workspace with nothing grown yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Solve the frictional impact of `mechanism` under `law` and `hypothesis`, as
    /// [`super::solve_frictional_under`] does, into this workspace: the report is kept here
    /// (returned by reference, and by [`PlanarFrictionWork::report`]) and taken apart by the
    /// next solve. A planar scene is solved on the kept buffers; a spatial one is handed to
    /// the adaptive integrator, to the relative `tolerance`, as a one-off.
    ///
    /// # Errors
    /// As [`super::solve_frictional_under`]; the report is then gone.
    pub fn solve_into<M: Mechanism<T, Screw = S>>(
        &mut self,
        mechanism: &M,
        law: Restitution,
        hypothesis: Hypothesis,
        tolerance: f64,
    ) -> Result<&Frictional<T, S>, FrictionError> {
        self.take_back();
        let report = if self.blocks.planar_into(mechanism) {
            self.solve(mechanism, law, hypothesis)?
        } else {
            super::solve_spatial(mechanism, law, hypothesis, tolerance)?
        };
        Ok(self.report.insert(report))
    }

    /// The last report, if the last solve succeeded.
    pub fn report(&self) -> Option<&Frictional<T, S>> {
        self.report.as_ref()
    }

    /// Take the last report apart: its blocks, state vectors, verdicts, segments and samples
    /// come back to be refilled.
    fn take_back(&mut self) {
        let Some(r) = self.report.take() else {
            return;
        };
        let Frictional {
            blocks,
            impulses,
            compression,
            after,
            work_compression,
            work_restitution,
            mut segments,
            mut verdicts,
            mut samples,
            ..
        } = r;
        // a spatial report's blocks are unit axes and sizes of no use here, but their vectors
        // are as good as any to refill
        self.blocks = blocks;
        let st = &mut self.state;
        st.lambda = impulses;
        st.compression = compression;
        st.v = after;
        st.work_compression = work_compression;
        st.work_restitution = work_restitution;
        self.spare.take_back(&mut segments, &mut samples);
        verdicts.clear();
        (self.segments, self.verdicts, self.samples) = (segments, verdicts, samples);
    }

    /// Solve on the blocks held (planar), event by event; the report takes the buffers.
    fn solve<M: Mechanism<T, Screw = S>>(
        &mut self,
        mechanism: &M,
        law: Restitution,
        hypothesis: Hypothesis,
    ) -> Result<Frictional<T, S>, FrictionError> {
        self.run(mechanism, law, hypothesis)?;
        let st = &mut self.state;
        use std::mem::take;
        let mut out = Frictional::unsettled(
            std::mem::replace(&mut self.blocks, Blocks::empty()),
            law,
            take(&mut st.lambda),
            take(&mut st.compression),
            take(&mut st.v),
            take(&mut st.work_compression),
            take(&mut st.work_restitution),
            std::mem::replace(&mut st.friction_work, T::zero()),
            take(&mut self.segments),
            take(&mut self.verdicts),
            st.s.clone(),
            take(&mut self.samples),
        );
        out.settle(mechanism, &mut self.spare);
        out.hypothesis = hypothesis;
        Ok(out)
    }

    /// The event loop of [`solve_planar`] on the kept buffers: it leaves the end state in
    /// `self.state`, the segments and verdicts in `self`.
    fn run<M: Mechanism<T, Screw = S>>(
        &mut self,
        mechanism: &M,
        law: Restitution,
        hypothesis: Hypothesis,
    ) -> Result<(), FrictionError> {
        let PlanarFrictionWork {
            blocks: b,
            state: st,
            search: work,
            simultaneous,
            reversals,
            engages,
            stops,
            segments,
            verdicts,
            spare,
            ..
        } = self;
        let b = &*b;
        let contacts = mechanism.contacts();
        let n = b.contacts();
        let two = T::one() + T::one();
        st.start(b, work);
        spare.take_back(segments, &mut Vec::new());
        verdicts.clear();
        let mut history: Vec<Event<T>> = Vec::new();
        for events in 1..=MAX_EVENTS {
            if events > CHATTER_AFTER {
                history.push((st.modes.clone(), st.phase, st.s.to_f64()));
                if let Some(period) = chatter(&history) {
                    return Err(FrictionError::Chatter {
                        s: st.s.to_f64(),
                        phase: st.phase,
                        period,
                        cycles: CHATTER_CYCLES,
                    });
                }
                let keep = CHATTER_PERIOD * (CHATTER_CYCLES + 1);
                if history.len() > 2 * keep {
                    history.drain(..history.len() - keep);
                }
            }
            normals(contacts, b, st, law, simultaneous);
            let rules = match hypothesis {
                Hypothesis::Simultaneous => Vec::new(),
                Hypothesis::Unilateral => unilateral_rules(simultaneous, b, st.phase),
            };
            let (unilateral, unilateral_normals);
            let (normals, r, consistent) = match hypothesis {
                Hypothesis::Simultaneous => {
                    let consistent = resolve_simultaneous(b, simultaneous, st, work)?;
                    (simultaneous.as_slice(), &work.chosen, consistent)
                }
                Hypothesis::Unilateral => {
                    let res = resolve_unilateral(b, &rules, st)?;
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
                    if let Some(hi) = energetic_stop(contacts, b, st, &r.lambda, &r.velocity, i)? {
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
            advance(b, st, &r.lambda, &r.velocity, &h);
            if hypothesis == Hypothesis::Unilateral {
                close_gaps(b, st, &rules, normals, &r.velocity, &h);
            }
            let fired = |hi: &T| (hi.clone() - &h).is_negligible(&h, n);
            for (i, hi) in engages.iter() {
                if fired(hi) {
                    st.gap[*i] = T::zero();
                }
            }
            for (i, hi) in reversals.iter() {
                if fired(hi) {
                    st.v[b.offset[*i] + 1] = T::zero();
                }
            }
            for (i, hi) in stops.iter() {
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
                let mut modes = spare.labels(n);
                labels_into(hypothesis, normals, &st.modes, &mut modes);
                let mut rates = spare.values(r.lambda.len());
                rates.extend_from_slice(&r.lambda);
                segments.push(Segment {
                    from,
                    to: st.s.clone(),
                    phase: st.phase,
                    modes,
                    rates,
                });
            }
            let at_end = end.as_ref().is_some_and(fired);
            match (st.phase, at_end) {
                (Phase::Compression, true) => {
                    st.s = T::one();
                    st.phase = Phase::Restitution;
                    st.compression.clear();
                    st.compression
                        .extend(b.offset.iter().map(|&o| st.lambda[o].clone()));
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
        Ok(())
    }
}

/// Solve a planar scene under `law` and `hypothesis`, event by event, on the blocks `b`
/// ([`Blocks::planar`]), as a one-off: a fresh [`PlanarFrictionWork`].
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
    let mut work = PlanarFrictionWork {
        blocks: b,
        ..PlanarFrictionWork::default()
    };
    work.solve(mechanism, law, hypothesis)
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
