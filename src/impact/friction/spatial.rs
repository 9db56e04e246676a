//! Spatial scenes, numerically: the impulse-space equations integrated by the embedded
//! Runge–Kutta pair of Dormand and Prince (RK5(4), local extrapolation), with adaptive steps
//! and event location, in any float scalar (f64, double-double).
//!
//! The state is y = (Λ, W_c, W_r, E_f): the impulses along every axis, each contact's
//! compression and restitution work, and the friction dissipation; the velocities follow from
//! Λ (eq. 144). Between events the modes are fixed: a sliding contact's direction is
//! u_i = v_it / |v_it| at every evaluation, a sticking one takes its tangential rate from the
//! rate system ([`super::rates`]).
//!
//! **Events.** The end of a phase (the step is clipped to it); a sticking contact whose
//! required rate leaves its cone by more than the tolerance (tol · Λ-scale: without that slack
//! a requirement grazing the cone's edge makes the contact chatter between stick and a slip of
//! λ ≈ 0⁺), and an energetic contact whose restitution work reaches k² times its compression
//! work — margins that cross from ≥ 0 to < 0 within a step, located by bisection of the step,
//! re-integrated from its start; a sliding contact whose slip reaches zero (a stop within the
//! tolerance of a phase's end is resolved in the next phase: Example 8's corner stops a slip
//! exactly at s = 1). At zero slip the modes of every contact there are chosen jointly: all
//! stick if their cones allow it; else the fewest that must slide do, each along an invariant
//! direction u of its tangential block, dv_it/ds = λ u with λ > 0 and a nonnegative normal
//! rate ([`super::departure`]) — for one contact by fixed-point iteration from the direction of
//! the required sticking impulse or, when that does not settle, by a scan of the circle refined
//! by bisection, a direction that attracts the slips around it preferred; for several by a
//! joint fixed-point iteration from every combination of senses, and where that does not
//! settle by Newton's method on their angles ([`departure::joint_root`]), from one common
//! direction and those senses, taken only where the joint direction attracts the slips around
//! it (the iteration diverges at strongly attracting ones: a can's face whose three rim points
//! reverse their slip together, issue 27). A slip that the stop step brings into the stop zone
//! (16 δ) while it slows stops with the contacts that stop there: its direction is noise.
//!
//! **A contact the simultaneous law makes pull.** The paper's hypothesis holds every normal
//! velocity on its path, whatever impulse rate that needs; a contact at zero slip whose path
//! needs a pull (a can pivoting on one rim point as its face lands: the pivot, at zero normal
//! velocity, is held there) has no Coulomb assignment — no cone to stick in, and a slide's
//! friction μ p' u would act along the slip. It carries no friction while it pulls
//! ([`State::pulling`], the verdict [`Verdict::TensileRate`]): the frictionless simultaneous
//! law's own answer at that contact, the rest of the impact under Coulomb's law. A contact
//! already sliding when it starts to pull keeps its slide, as in the plane, whose exact
//! integrator lets a pulling contact at zero slip slide too where the slide's test passes.
//!
//! **Bhatt and Koechling's singular point.** Near zero slip, the slip direction u = v_t/|v_t|
//! turns at |dv_t⊥/ds| / |v_t|, ever faster — a stiff flow. A step turns the direction by at
//! most a quarter radian and is never longer than nine tenths of the predicted time to zero
//! slip, |v_t| / (−d|v_t|/ds), so |v_t| falls geometrically; below 16 δ (δ = tol · max|v⁰|)
//! the direction is held (there the slip's direction is integration noise) and one Euler step
//! of the predicted length finishes the slip, whose residual is set aside (the slip is measured
//! from it afterwards). A slip that leaves zero slip is **held** on its invariant direction,
//! tracked at every evaluation as the root nearest the direction held ([`departure::track`],
//! within a quarter radian per step; a step that loses it is retried shorter, and a slip whose
//! direction no longer leaves zero — a phase's end changed its rates — is released to its own
//! direction), while the step would not resolve the turn (κ h > ρ, with κ the pull per unit
//! angle): the slip that leaves zero is the one trajectory that stays with the invariant
//! direction, which an explicit step would lose — and when that direction repels the slips
//! around it (κ < 0) the impact is sensitive, a verdict (`unstable-slip`). Holding lags the
//! slip's own direction by (ρ/κ) dθ*/ds; a step whose lag moves more impulse than the tolerance
//! allows is refused, as a local error is. The steps near an ordinary singular point grow like
//! log(1/tol), not like 1/tol; after a stick that ends at its cone's edge the slip restarts
//! with λ = 0 and ρ ∝ (s − s*)², the pull is stiffer by 1/(s − s*) and they grow like
//! tol^(−1/4) (10 times over four decades); [`integrate`] reports them ([`Stats`]).
//!
//! **The unilateral law** ([`solve_spatial_under`], `derivations/unilateral-friction.md`). At
//! s = 0, at s = 1 and at every event the contacts on their paths — driven, or released with a
//! gap within δ — are driven or released jointly with the modes (`choose`: the planar
//! resolver's assignments, [`super::modes::unilateral_assignments`], each resolved as above and
//! tested by [`super::modes::normal_consistent`] with the event slack). Two more margins are
//! events: a driven contact's impulse rate over its base, (p'_i − base_i)/Λ-scale + tol (its
//! path turns tensile: release), and a released contact's gap g_i = v_i^path(s) − v_ix, whose
//! path is linear in s within a phase, over max|v⁰| (it closes: re-engagement; with the slack
//! tol until the gap has once exceeded δ, so that a gap that stays at zero does not fire on
//! rounding). Each such event adds the slack's impulse, tol × Λ-scale, to the estimate.
//!
//! **Error estimate.** The sum over accepted steps of the embedded local error estimate of the
//! impulses and a rounding term, plus, per zero-slip stop, twice the largest rate times the
//! predicted time to zero slip, per event the rate times the bisection width, and per held
//! step the held direction's lag μ p′ |Δu| min(ρ/|κ|, h); multiplied by max(1, Σ_q ‖W{E_q}‖∞) so
//! that it bounds the twist as well as the impulses (unit axes). It is tested against planar
//! scenes solved exactly, against runs 10⁴–10⁶ times tighter (`tests/friction_spatial.rs`) and
//! against an independent integration of a ball in a corner through stick exits
//! (`tests/regression_stick_exit_direction.rs`).

use crate::impact::friction::blocks::Blocks;
use crate::impact::friction::departure::{self, dot, norm, of, unit};
use crate::impact::friction::modes::{
    carries, nonnegative, normal_consistent, unilateral_assignments,
};
use crate::impact::friction::rates::{
    Mode, Normal, RateFailure, Rates, Unilateral, max_abs, normal_rules, rates, unilateral_rules,
};
use crate::impact::friction::{
    FrictionError, Frictional, Hypothesis, ModeLabel, Phase, Restitution, Sample, Segment, Verdict,
    labels,
};
use crate::impact::mechanism::Mechanism;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::Screws;
use crate::scalar::{Scalar, ratio};

/// The most accepted and rejected steps before the integration is declared runaway.
const MAX_STEPS: usize = 200_000;

/// tan(1/4): a held slip's direction is tracked within a quarter radian per step, as a free
/// slip's direction turns by at most that much per step.
const QUARTER: f64 = 0.255_341_921_221_036_3;

/// The Dormand–Prince RK5(4) tableau as fractions (p, q), built in the scalar type so that a
/// double-double run does not inherit the f64 rounding of 3/40 or 19372/6561: rows of A (the
/// seventh row is the fifth-order solution, FSAL), and E = fifth- minus fourth-order weights.
/// Shared with the multiple-impact integrator ([`crate::impact::multiple`]).
pub(crate) const A: [[(i64, i64); 6]; 7] = [
    [(0, 1); 6],
    [(1, 5), (0, 1), (0, 1), (0, 1), (0, 1), (0, 1)],
    [(3, 40), (9, 40), (0, 1), (0, 1), (0, 1), (0, 1)],
    [(44, 45), (-56, 15), (32, 9), (0, 1), (0, 1), (0, 1)],
    [
        (19372, 6561),
        (-25360, 2187),
        (64448, 6561),
        (-212, 729),
        (0, 1),
        (0, 1),
    ],
    [
        (9017, 3168),
        (-355, 33),
        (46732, 5247),
        (49, 176),
        (-5103, 18656),
        (0, 1),
    ],
    [
        (35, 384),
        (0, 1),
        (500, 1113),
        (125, 192),
        (-2187, 6784),
        (11, 84),
    ],
];
pub(crate) const E: [(i64, i64); 7] = [
    (71, 57600),
    (0, 1),
    (-71, 16695),
    (71, 1920),
    (-17253, 339200),
    (22, 525),
    (-1, 40),
];

/// What an integration cost, for tests and diagnostics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted Runge–Kutta steps.
    pub accepted: usize,
    /// Rejected ones (local error above the tolerance).
    pub rejected: usize,
    /// Events located (a stick leaving its cone, an energetic stop).
    pub events: usize,
    /// Sliding contacts declared at zero slip.
    pub stops: usize,
}

impl Stats {
    /// Every step tried, accepted or not.
    pub fn steps(&self) -> usize {
        self.accepted + self.rejected
    }
}

/// The integration's fixed data.
struct Run<'a, T: Scalar, S: Screws<T>> {
    contacts: &'a [Contact<T>],
    b: &'a Blocks<T, S>,
    law: Restitution,
    hypothesis: Hypothesis,
    tol: f64,
    /// max|v⁰|: the velocity scale of the gaps' margins.
    vscale: f64,
    /// Below this slip speed a contact is at zero slip; within this gap a released contact is
    /// on its path.
    delta: f64,
    /// Below this slip speed (16 δ) a sliding contact keeps the direction it was given rather
    /// than the direction of its slip: near zero the slip's direction is integration noise,
    /// and a slip restarting along its invariant direction would be turned by that noise and
    /// declared at rest again at once (stick–slip chatter at a cone's edge).
    lock: f64,
    /// Impulse scale for the absolute tolerance.
    lambda_scale: f64,
    /// Work scale.
    work_scale: f64,
    /// The tableau in the scalar type.
    a: Vec<Vec<T>>,
    e: Vec<T>,
    /// The last tracked direction of each held slip ([`Run::settle`]).
    tracks: std::cell::RefCell<departure::TrackMemo<T>>,
}

/// The changing part of the integration: what the right-hand side depends on besides y.
#[derive(Clone)]
struct State<T: Scalar> {
    s: T,
    phase: Phase,
    y: Vec<T>,
    modes: Vec<Mode<T>>,
    stopped: Vec<bool>,
    compression: Vec<T>,
    /// Per axis, the slip set aside when a contact was last declared at zero slip (its
    /// residual, below δ): slip directions are measured from it, so that a slip restarting
    /// along its invariant direction is not turned by the residual's arbitrary direction
    /// (which made contacts chatter between zero slip and slip).
    origin: Vec<T>,
    /// Per contact: sliding away from zero slip with its direction held at the invariant
    /// direction, re-found after every step, rather than taken from its slip. Near zero slip
    /// the slip's direction is pulled back to the invariant direction at a rate |dv_t|/ρ: a
    /// stiff flow an explicit step cannot follow (at a cone's edge, where the slip grows at a
    /// small λ, it took 10⁴–10⁵ steps and ran out of budget). The lock is released once
    /// |dv_t| h ≤ ρ, where the step resolves that flow; each re-found direction's change Δu
    /// adds μ p' |Δu| h to the error estimate.
    locked: Vec<bool>,
    /// Per contact, under the unilateral law: released (its rule [`Normal::Given`], its normal
    /// velocity free on the separating side of its path).
    released: Vec<bool>,
    /// Per released contact: its gap has exceeded δ since it was released, so its
    /// re-engagement margin is the gap itself; before that the margin has the slack δ, so that
    /// a gap that stays at zero (released with g' = 0) does not fire on rounding noise.
    armed: Vec<bool>,
    /// Per contact, under the simultaneous hypothesis: held on its path by a pull (a negative
    /// normal impulse rate, [`Verdict::TensileRate`]). Coulomb's law has no cone for a pulling
    /// contact — no stick, and a slide's friction μ p' u would push along the slip, doing
    /// work on the body — so it carries no friction while it pulls ([`Mode::Free`]); a
    /// margin ([`Run::margins`]) ends that where its rate turns positive again.
    pulling: Vec<bool>,
}

/// A slip held on its invariant direction at the end of a step ([`Run::held`]).
struct Held<T: Scalar> {
    contact: usize,
    /// The invariant direction tracked there.
    u: Vec<T>,
    /// Its pull κ.
    kappa: f64,
    /// The slip's speed.
    rho: f64,
    /// The impulse error of holding it over the step.
    lag: f64,
    /// No invariant direction within a quarter radian of the one held before the step.
    lost: bool,
}

/// The right-hand side at one point: dy/ds and the rates it came from.
#[derive(Clone)]
struct Slope<T: Scalar> {
    dy: Vec<T>,
    rates: Rates<T>,
}

/// One trial step.
struct Trial<T: Scalar> {
    /// The fifth-order solution.
    y: Vec<T>,
    /// The slope there (the next step's first stage when it is accepted).
    slope: Slope<T>,
    /// The local error estimate, scaled by the tolerance (≤ 1: accept).
    scaled: f64,
    /// The largest absolute local error of an impulse.
    impulse: f64,
}

impl<T: Scalar, S: Screws<T>> Run<'_, T, S> {
    fn n(&self) -> usize {
        self.b.contacts()
    }

    fn len(&self) -> usize {
        self.b.len()
    }

    fn fail(&self, e: RateFailure, st: &State<T>) -> FrictionError {
        match e {
            RateFailure::Undetermined => FrictionError::Undetermined { s: st.s.to_f64() },
            RateFailure::Inconsistent => FrictionError::NoConsistentModes {
                s: st.s.to_f64(),
                phase: st.phase,
            },
        }
    }

    /// v = v⁰ − K Λ.
    fn velocities(&self, y: &[T]) -> Vec<T> {
        let mut dv = Vec::new();
        self.b.velocity_change(&y[..self.len()], &mut dv);
        dv.iter()
            .zip(&self.b.v0)
            .map(|(d, v0)| v0.clone() + d)
            .collect()
    }

    fn normals(&self, st: &State<T>) -> Vec<Normal<T>> {
        normal_rules(
            self.contacts,
            self.b,
            st.phase,
            self.law,
            &st.compression,
            &st.stopped,
        )
    }

    /// The unilateral rules of the current phase ([`unilateral_rules`]).
    fn rules(&self, st: &State<T>) -> Vec<Unilateral<T>> {
        unilateral_rules(&self.normals(st), self.b, st.phase)
    }

    /// The gaps g_i = v_i^path(s) − v_ix at `s`, `y` (derivations/unilateral-friction.md): each
    /// path starts at v_ix⁰ at s = 0 and at 0 at s = 1 and falls at its rule's path rate, so
    /// it is known in closed form; v_ix follows from Λ (eq. 144).
    fn gaps(&self, st: &State<T>, rules: &[Unilateral<T>], s: &T, y: &[T]) -> Vec<f64> {
        let v = self.velocities(y);
        (0..self.n())
            .map(|i| {
                let off = self.b.offset[i];
                let (start, from) = match st.phase {
                    Phase::Compression => (self.b.v0[off].clone(), T::zero()),
                    Phase::Restitution => (T::zero(), T::one()),
                };
                let path = start - rules[i].path.clone() * (s.clone() - from);
                (path - &v[off]).to_f64()
            })
            .collect()
    }

    /// The slip of contact i along its tangent axes, measured from its `origin`, and its
    /// speed.
    fn slip(&self, v: &[T], origin: &[T], i: usize) -> (Vec<T>, f64) {
        let off = self.b.offset[i] + 1;
        let vt: Vec<T> = (off..off + 2).map(|q| v[q].clone() - &origin[q]).collect();
        let rho = norm(&vt).to_f64();
        (vt, rho)
    }

    /// The modes at velocities `v`: a sliding contact takes the direction of its slip above δ
    /// and keeps the direction it was given at or below (where the slip is rounding and the
    /// direction chosen at zero slip governs).
    ///
    /// Slips of contacts with the same tangent axes that agree to within δ, the velocity
    /// tolerance, are one slip and take one direction, the first one's ([`Run::shared`]): a
    /// face sliding in translation slips alike at every corner in exact arithmetic, and the
    /// integration's error in the twist (δ) turns each corner's direction by a different
    /// δ/ρ, which would make the statically indeterminate split of its normal impulses change
    /// the motion — the rank of the rate system would be decided on that error.
    fn modes_at(&self, v: &[T], st: &State<T>) -> Vec<Mode<T>> {
        let mut modes: Vec<Mode<T>> = st
            .modes
            .iter()
            .enumerate()
            .map(|(i, m)| match m {
                Mode::Slide(_) => {
                    let (vt, rho) = self.slip(v, &st.origin, i);
                    if rho > self.lock && !st.locked[i] {
                        Mode::Slide(unit(&vt))
                    } else {
                        m.clone()
                    }
                }
                other => other.clone(),
            })
            .collect();
        for (j, i) in self.shared(v, st, &modes) {
            modes[j] = modes[i].clone();
        }
        modes
    }

    /// The pairs (j, i), i < j the first such, of free sliding contacts ([`Run::modes_at`])
    /// with the same tangent axes whose slips differ by at most δ.
    fn shared(&self, v: &[T], st: &State<T>, modes: &[Mode<T>]) -> Vec<(usize, usize)> {
        let free =
            |i: usize| matches!(modes[i], Mode::Slide(_)) && !st.locked[i] && self.b.dims[i] == 2;
        let mut pairs = Vec::new();
        if (0..self.n()).filter(|&i| free(i)).nth(1).is_none() {
            return pairs;
        }
        // Each free contact's slip once (this runs at every stage of every step).
        let slips: Vec<Option<Vec<T>>> = (0..self.n())
            .map(|i| free(i).then(|| self.slip(v, &st.origin, i).0))
            .collect();
        for (j, vj) in slips.iter().enumerate().skip(1) {
            let Some(vj) = vj else {
                continue;
            };
            let same = (0..j).find(|&i| {
                slips[i].as_ref().is_some_and(|vi| {
                    self.same_axes(i, j)
                        && vi
                            .iter()
                            .zip(vj)
                            .all(|(a, c)| (a.clone() - c).to_f64().abs() <= self.delta)
                })
            });
            if let Some(i) = same {
                pairs.push((j, i));
            }
        }
        pairs
    }

    /// The impulse error of sharing directions over a step of length h ending at velocities
    /// `v` with rates `r`: Σ μ_j |p'_j| |u_j − u_i| h over the pairs of [`Run::shared`], u_j
    /// contact j's own slip direction.
    fn shared_lag(&self, v: &[T], st: &State<T>, r: &Rates<T>, h: f64) -> f64 {
        self.shared(v, st, &st.modes)
            .into_iter()
            .map(|(j, i)| {
                let (vj, rj) = self.slip(v, &st.origin, j);
                let (vi, ri) = self.slip(v, &st.origin, i);
                if rj <= self.lock || ri <= self.lock {
                    return 0.0;
                }
                let (uj, ui) = (unit(&vj), unit(&vi));
                let turn = uj
                    .iter()
                    .zip(&ui)
                    .map(|(a, c)| (a.clone() - c).to_f64().abs())
                    .fold(0.0, f64::max);
                let p = r.lambda[self.b.offset[j]].to_f64().abs();
                self.b.mu[j].to_f64() * p * turn * h
            })
            .sum()
    }

    /// Whether contacts i and j have the same tangent directions.
    fn same_axes(&self, i: usize, j: usize) -> bool {
        let (oi, oj) = (self.b.offset[i], self.b.offset[j]);
        (1..3).all(|a| {
            let (di, dj) = (&self.b.directions[oi + a], &self.b.directions[oj + a]);
            (0..3).all(|k| (di[k].clone() - &dj[k]).to_f64().abs() <= 4.0 * T::epsilon_f64())
        })
    }

    /// dy/ds at `y`.
    fn slope(
        &self,
        st: &State<T>,
        normals: &[Normal<T>],
        y: &[T],
    ) -> Result<Slope<T>, FrictionError> {
        let v = self.velocities(y);
        let mut modes = self.modes_at(&v, st);
        for i in 0..self.n() {
            if st.locked[i] {
                self.settle(&mut modes, normals, i);
            }
        }
        let r = rates(self.b, normals, &modes).map_err(|e| self.fail(e, st))?;
        let n = self.n();
        let len = self.len();
        let mut dy = Vec::with_capacity(len + 2 * n + 1);
        dy.extend(r.lambda.iter().cloned());
        let mut wc = vec![T::zero(); n];
        let mut wr = vec![T::zero(); n];
        let mut ef = T::zero();
        let mut contact = 0;
        for q in 0..len {
            while contact + 1 < n && self.b.offset[contact + 1] <= q {
                contact += 1;
            }
            let power = v[q].clone() * &r.lambda[q];
            if q != self.b.offset[contact] {
                ef += power;
            } else if st.phase == Phase::Compression {
                wc[contact] = power;
            } else {
                wr[contact] = -power;
            }
        }
        dy.extend(wc);
        dy.extend(wr);
        dy.push(ef);
        Ok(Slope { dy, rates: r })
    }

    /// A locked slip's direction at the current state (see `State::locked`): the invariant
    /// direction nearest the one held in `modes`, tracked by [`departure::track`] (kept when
    /// none is found).
    fn settle(&self, modes: &mut [Mode<T>], normals: &[Normal<T>], i: usize) -> bool {
        self.tracks
            .borrow_mut()
            .track(self.b, normals, modes, i, self.settled(), QUARTER)
    }

    /// The slips held on their invariant direction at the end `y` (slope `k`) of a step of
    /// length `h` from `st`: each one's direction tracked there, its pull κ, its speed ρ and the
    /// lag of holding it — the slip's own direction trails the invariant one by the angle
    /// (ρ/κ) dθ*/ds, where it relaxes at κ/ρ (by at most the turn over the step, when that
    /// relaxation is slower than the step), which moves μ p′ times that angle of impulse
    /// per unit s: μ p′ |Δu| min(ρ/|κ|, h).
    fn held(
        &self,
        st: &State<T>,
        normals: &[Normal<T>],
        y: &[T],
        k: &Slope<T>,
        h: f64,
    ) -> Vec<Held<T>> {
        let v = self.velocities(y);
        let mut modes = self.modes_at(&v, st);
        let mut out = Vec::new();
        for i in 0..self.n() {
            let Mode::Slide(old) = modes[i].clone() else {
                continue;
            };
            if !st.locked[i] {
                continue;
            }
            let (_, rho) = self.slip(&v, &st.origin, i);
            if !self.settle(&mut modes, normals, i) {
                out.push(Held {
                    contact: i,
                    u: old,
                    kappa: f64::NAN,
                    rho,
                    lag: 0.0,
                    lost: true,
                });
                continue;
            }
            let Mode::Slide(u) = modes[i].clone() else {
                continue;
            };
            let kappa =
                departure::pull(self.b, normals, &mut modes, i, &u).unwrap_or(f64::INFINITY);
            let change = u
                .iter()
                .zip(&old)
                .map(|(a, c)| (a.clone() - c).to_f64().abs())
                .fold(0.0, f64::max);
            let p = k.rates.lambda[self.b.offset[i]].to_f64().abs();
            let lag = self.b.mu[i].to_f64() * p * change * (rho / kappa.abs()).min(h);
            out.push(Held {
                contact: i,
                u,
                kappa,
                rho,
                lag,
                lost: false,
            });
        }
        out
    }

    /// How closely directions are settled: the tolerance, above rounding.
    fn settled(&self) -> f64 {
        self.tol.max(64.0 * T::epsilon_f64())
    }

    /// One Dormand–Prince step of length h from st.y, whose slope is `k0`.
    fn step(
        &self,
        st: &State<T>,
        normals: &[Normal<T>],
        k0: &Slope<T>,
        h: &T,
    ) -> Result<Trial<T>, FrictionError> {
        let y = &st.y;
        let mut k: Vec<Vec<T>> = Vec::with_capacity(7);
        k.push(k0.dy.clone());
        let mut last = None;
        for stage in 1..7 {
            let mut yi = y.clone();
            for (j, kj) in k.iter().enumerate() {
                if self.a[stage][j].is_zero() {
                    continue;
                }
                let c = self.a[stage][j].clone() * h;
                for (x, d) in yi.iter_mut().zip(kj) {
                    *x += c.clone() * d;
                }
            }
            let slope = self.slope(st, normals, &yi)?;
            k.push(slope.dy.clone());
            if stage == 6 {
                last = Some((yi, slope));
            }
        }
        let (y5, slope) = last.expect("seven stages");
        let len = self.len();
        let mut scaled: f64 = 0.0;
        let mut impulse: f64 = 0.0;
        for q in 0..y.len() {
            let mut e = T::zero();
            for (ej, kj) in self.e.iter().zip(&k) {
                if !ej.is_zero() {
                    e += ej.clone() * &kj[q];
                }
            }
            let e = (e * h).to_f64().abs();
            let scale = if q < len {
                self.lambda_scale
            } else {
                self.work_scale
            };
            scaled = scaled.max(e / (self.tol * (scale + y5[q].to_f64().abs())));
            if q < len {
                impulse = impulse.max(e);
            }
        }
        Ok(Trial {
            y: y5,
            slope,
            scaled,
            impulse,
        })
    }

    /// The event functions at a state with rates `r`: per contact, the margin of a sticking
    /// contact's cone, (μ p' − |τ'|) / Λ-scale + tol (a stick holds until its required rate
    /// leaves the cone by more than the tolerance — without that slack a requirement grazing
    /// the cone's edge makes the contact chatter between stick and a slip of λ ≈ 0⁺), and of an energetic contact's restitution work,
    /// (k² W_c − W_r) / work scale; under the unilateral law, of a driven contact's impulse
    /// rate over its base, (p'_i − base_i) / Λ-scale + tol (it is released once its path needs
    /// a pull beyond the slack, as a stick leaves its cone), and of a released contact's gap,
    /// g_i / max|v⁰| (+ tol before it is `armed`): it re-engages where its gap closes. +∞ where
    /// a function does not apply; under the simultaneous law, of a contact freed of friction
    /// while it pulls ([`State::pulling`]), tol − p'_i / Λ-scale: it pulls until its rate turns
    /// positive. An event is a margin that was ≥ 0 and is < 0. The state is at `s`, `y`.
    fn margins(
        &self,
        st: &State<T>,
        normals: &[Normal<T>],
        rules: &[Unilateral<T>],
        s: &T,
        y: &[T],
        r: &Rates<T>,
    ) -> Vec<f64> {
        let b = self.b;
        let (n, len) = (self.n(), self.len());
        let mut g = vec![f64::INFINITY; 4 * n];
        if self.hypothesis == Hypothesis::Unilateral {
            let gaps = self.gaps(st, rules, s, y);
            for i in 0..n {
                let off = b.offset[i];
                if let Normal::Driven(_) = normals[i] {
                    g[2 * n + 2 * i] = (r.lambda[off].clone() - &rules[i].base).to_f64()
                        / self.lambda_scale
                        + self.tol;
                }
                if st.released[i] {
                    let slack = if st.armed[i] { 0.0 } else { self.tol };
                    g[2 * n + 2 * i + 1] = gaps[i] / self.vscale + slack;
                }
            }
        }
        if self.hypothesis == Hypothesis::Simultaneous {
            for i in 0..n {
                if st.pulling[i] {
                    // it pulls until its rate turns positive (a stick that starts to pull
                    // leaves its cone: that margin's event)
                    g[2 * n + 2 * i] =
                        self.tol - r.lambda[b.offset[i]].to_f64() / self.lambda_scale;
                }
            }
        }
        for i in 0..n {
            if st.modes[i] == Mode::Stick {
                let off = b.offset[i];
                let tau = norm(&r.lambda[off + 1..off + 1 + b.dims[i]]);
                g[2 * i] = (b.mu[i].clone() * &r.lambda[off] - tau).to_f64() / self.lambda_scale
                    + self.tol;
            }
            if st.phase == Phase::Restitution
                && self.law == Restitution::Energetic
                && !st.stopped[i]
            {
                let k = &self.contacts[i].k_energetic;
                let left = k.clone() * k * &y[len + i] - &y[len + n + i];
                g[2 * i + 1] = left.to_f64() / self.work_scale;
            }
        }
        g
    }
}

/// Whether a margin crossed from ≥ 0 to < 0.
fn crossed(before: &[f64], after: &[f64]) -> bool {
    before.iter().zip(after).any(|(a, b)| *a >= 0.0 && *b < 0.0)
}

/// Integrate a spatial scene under `law` and the simultaneous hypothesis to the relative
/// tolerance `tol`.
///
/// # Errors
/// [`FrictionError`] as for planar scenes, and [`FrictionError::Runaway`] past the step budget.
pub fn solve_spatial<T: Scalar, S: Screws<T>, M: Mechanism<T, Screw = S>>(
    mechanism: &M,
    b: Blocks<T, S>,
    law: Restitution,
    tol: f64,
) -> Result<Frictional<T, S>, FrictionError> {
    solve_spatial_under(mechanism, b, law, Hypothesis::Simultaneous, tol)
}

/// [`solve_spatial`] under `hypothesis`: under the unilateral law the normal rules are chosen
/// with the modes at s = 0, at s = 1 and at every event (`choose`), and a driven contact
/// whose path turns tensile (its release margin) or a released one whose gap closes (its
/// re-engagement margin) is an event, located as a stick leaving its cone is.
///
/// # Errors
/// As [`solve_spatial`].
pub fn solve_spatial_under<T: Scalar, S: Screws<T>, M: Mechanism<T, Screw = S>>(
    mechanism: &M,
    b: Blocks<T, S>,
    law: Restitution,
    hypothesis: Hypothesis,
    tol: f64,
) -> Result<Frictional<T, S>, FrictionError> {
    integrate_under(mechanism, b, law, hypothesis, tol).map(|(out, _)| out)
}

/// [`solve_spatial`], with what the integration cost.
///
/// # Errors
/// As [`solve_spatial`].
pub fn integrate<T: Scalar, S: Screws<T>, M: Mechanism<T, Screw = S>>(
    mechanism: &M,
    b: Blocks<T, S>,
    law: Restitution,
    tol: f64,
) -> Result<(Frictional<T, S>, Stats), FrictionError> {
    integrate_under(mechanism, b, law, Hypothesis::Simultaneous, tol)
}

/// [`solve_spatial_under`], with what the integration cost.
///
/// # Errors
/// As [`solve_spatial`].
pub fn integrate_under<T: Scalar, S: Screws<T>, M: Mechanism<T, Screw = S>>(
    mechanism: &M,
    b: Blocks<T, S>,
    law: Restitution,
    hypothesis: Hypothesis,
    tol: f64,
) -> Result<(Frictional<T, S>, Stats), FrictionError> {
    let n = b.contacts();
    let len = b.len();
    let tol = tol.max(4.0 * T::epsilon_f64());
    let vscale = max_abs(&b.v0).to_f64().max(f64::MIN_POSITIVE);
    let kscale = (0..len)
        .map(|q| b.at(q, q).to_f64())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    // Twist change per unit impulse on all axes: turns an impulse error into a velocity one.
    let response: f64 = b.responses.iter().map(Screws::max_abs_f64).sum();
    let ratio_t = |(p, q): (i64, i64)| ratio::<T>(p, q);
    let run = Run {
        contacts: mechanism.contacts(),
        b: &b,
        law,
        hypothesis,
        tol,
        vscale,
        delta: tol * vscale,
        lock: 16.0 * tol * vscale,
        lambda_scale: vscale / kscale,
        work_scale: vscale * vscale / kscale,
        a: A.iter()
            .map(|row| row.iter().copied().map(ratio_t).collect())
            .collect(),
        e: E.iter().copied().map(ratio_t).collect(),
        tracks: std::cell::RefCell::new(departure::TrackMemo::new(n)),
    };
    let mut st = State {
        s: T::zero(),
        phase: Phase::Compression,
        y: vec![T::zero(); len + 2 * n + 1],
        modes: vec![Mode::Free; n],
        stopped: vec![false; n],
        compression: Vec::new(),
        origin: vec![T::zero(); len],
        locked: vec![false; n],
        released: vec![false; n],
        armed: vec![false; n],
        pulling: vec![false; n],
    };
    let mut stats = Stats::default();
    let mut segments: Vec<Segment<T>> = Vec::new();
    let mut verdicts = Vec::new();
    // The error of the impulses: local estimates, zero-slip stops, rounding.
    let mut error = 0.0;
    let rounding = 16.0 * (len as f64) * T::epsilon_f64();
    let mut h: f64 = 0.05;
    let mut normals = choose(&run, &mut st, &Fired::default(), &mut verdicts)?;
    let mut k0 = run.slope(&st, &normals, &st.y)?;
    let mut seg_start = st.s.clone();
    let mut seg_modes = labels(hypothesis, &normals, &st.modes);
    let mut samples = vec![sample(&st, &seg_modes, len)];
    let mut seg_rates = k0.rates.lambda.clone();
    loop {
        if stats.steps() + stats.events + stats.stops > MAX_STEPS {
            return Err(FrictionError::Runaway);
        }
        let r = &k0.rates;
        for (i, normal) in normals.iter().enumerate() {
            let known = verdicts.iter().any(|v| {
                matches!(v, Verdict::TensileRate { contact, phase, .. }
                    if *contact == i && *phase == st.phase)
            });
            if !known
                && hypothesis == Hypothesis::Simultaneous
                && matches!(normal, Normal::Driven(_))
                && r.lambda[b.offset[i]].to_f64() < -tol * run.lambda_scale
            {
                verdicts.push(Verdict::TensileRate {
                    contact: i,
                    s: st.s.to_f64(),
                    phase: st.phase,
                });
            }
        }
        // Slip approaching zero: clip the step to 0.9 of the predicted time, or declare it.
        let v = run.velocities(&st.y);
        let rate_scale = max_abs(&r.lambda).to_f64();
        let mut at_rest: Option<f64> = None;
        let mut resting: Vec<usize> = Vec::new();
        for i in 0..n {
            let Mode::Slide(u) = &st.modes[i] else {
                continue;
            };
            let off = b.offset[i] + 1;
            let dv = &r.velocity[off..off + 2];
            let (vt, rho) = run.slip(&v, &st.origin, i);
            let free = rho > run.lock && !st.locked[i];
            let drho = if free {
                dot(&vt, dv).to_f64() / rho
            } else {
                dot(u, dv).to_f64()
            };
            if free {
                // The direction turns at |dv_t⊥| / ρ: at most a quarter radian per step, or
                // the step outruns it and the slip chatters about a fixed speed.
                let along = drho;
                let across = (dot(dv, dv).to_f64() - along * along).max(0.0).sqrt();
                if across > 0.0 {
                    h = h.min(0.25 * rho / across);
                }
            }
            if drho >= 0.0 {
                continue;
            }
            if rho <= run.lock {
                // Sliding on to zero would take rho / −drho more; stick and slide rates differ
                // by at most twice the largest rate over that interval.
                let left = rho / -drho;
                at_rest = Some(at_rest.map_or(left, |x| x.min(left)));
                resting.push(i);
                error += 2.0 * left * rate_scale;
            } else {
                h = h.min(0.9 * rho / -drho);
            }
        }
        if let Some(left) = at_rest {
            // Finish the slip with one Euler step (exact when the direction does not turn, as
            // in the plane), within the phase.
            stats.stops += 1;
            let mut ds: T = of(left);
            let mut phase_end = false;
            if st.phase == Phase::Compression || law != Restitution::Energetic {
                let end = if st.phase == Phase::Compression {
                    T::one()
                } else {
                    T::one() + T::one()
                };
                let rest = end - &st.s;
                // Within the tolerance of the phase's end, the stop is at the end.
                if (ds.clone() - &rest).to_f64() >= -tol {
                    ds = rest;
                    phase_end = true;
                }
            }
            for (x, d) in st.y.iter_mut().zip(&k0.dy) {
                *x += d.clone() * &ds;
            }
            st.s += &ds;
            close_segment(&mut segments, &seg_start, &st, &seg_modes, &seg_rates);
            samples.push(sample(&st, &seg_modes, len));
            // A slip that stops with its phase (Example 8's corner: A₁'s slip vanishes exactly
            // at the end of compression) is resolved in the next phase.
            if phase_end {
                if st.phase == Phase::Restitution {
                    break;
                }
                begin_restitution(&run, &mut st);
            }
            // A slip the step brought into the stop zone while it slows stops with the others:
            // its direction there is integration noise (the corners of a face sliding in
            // translation stop together in exact arithmetic; integrated, their slips end
            // within a few δ of one another), and resolved as a slide it would take friction
            // along that noise. Its residual is set aside as the others' is, and the estimate
            // counts it as theirs.
            let v_after = run.velocities(&st.y);
            for i in 0..n {
                let Mode::Slide(u) = &st.modes[i] else {
                    continue;
                };
                if resting.contains(&i) {
                    continue;
                }
                let (vt, rho) = run.slip(&v_after, &st.origin, i);
                if rho > run.lock {
                    continue;
                }
                let off = b.offset[i] + 1;
                let dv = &r.velocity[off..off + 2];
                let drho = if rho > 0.0 && !st.locked[i] {
                    dot(&vt, dv).to_f64() / rho
                } else {
                    dot(u, dv).to_f64()
                };
                if drho < 0.0 {
                    resting.push(i);
                    error += 2.0 * (rho / -drho) * rate_scale;
                }
            }
            let fired = Fired {
                resting,
                ..Fired::default()
            };
            normals = choose(&run, &mut st, &fired, &mut verdicts)?;
            k0 = run.slope(&st, &normals, &st.y)?;
            seg_start = st.s.clone();
            seg_modes = labels(hypothesis, &normals, &st.modes);
            samples.push(sample(&st, &seg_modes, len));
            seg_rates = k0.rates.lambda.clone();
            continue;
        }
        let end = match (st.phase, law) {
            (Phase::Compression, _) => Some(T::one()),
            (Phase::Restitution, Restitution::Energetic) => None,
            (Phase::Restitution, _) => Some(T::one() + T::one()),
        };
        if end.is_none() && st.s.to_f64() > 1e3 {
            let contact = (0..n).find(|&i| !st.stopped[i]).unwrap_or(0);
            return Err(FrictionError::NeverEnds { contact });
        }
        let mut hh: T = of(h);
        let mut hit_end = false;
        if let Some(e) = &end {
            let rest = e.clone() - &st.s;
            if rest.to_f64() <= h * (1.0 + 1e-9) {
                hh = rest;
                hit_end = true;
            }
        }
        let trial = run.step(&st, &normals, &k0, &hh)?;
        if trial.scaled.is_nan() || trial.scaled > 1.0 {
            stats.rejected += 1;
            h *= (0.9 * trial.scaled.powf(-0.2)).clamp(0.1, 0.9);
            continue;
        }
        // A held slip's direction lags behind the invariant one it is held on: a step whose lag
        // exceeds the tolerance is refused as the local error is.
        let held = run.held(&st, &normals, &trial.y, &trial.slope, hh.to_f64());
        let allowed = tol * (run.lambda_scale + max_abs(&trial.y[..len]).to_f64());
        let lag = held.iter().map(|x| x.lag).fold(0.0, f64::max);
        // A held direction that moved more than a quarter radian, or vanished: a shorter step,
        // until the step is as short as the tolerance — then the slip is released to its own
        // direction (its invariant direction no longer leaves zero slip).
        if held.iter().any(|x| x.lost) && hh.to_f64() > run.settled() {
            stats.rejected += 1;
            h = hh.to_f64() / 4.0;
            continue;
        }
        if lag > allowed {
            stats.rejected += 1;
            h = hh.to_f64() * (0.9 * allowed / lag).clamp(0.1, 0.9);
            continue;
        }
        stats.accepted += 1;
        let rules = run.rules(&st);
        let before = run.margins(&st, &normals, &rules, &st.s, &st.y, &k0.rates);
        let s_end = st.s.clone() + &hh;
        let after = run.margins(&st, &normals, &rules, &s_end, &trial.y, &trial.slope.rates);
        let grow = (0.9 * trial.scaled.max(1e-10).powf(-0.2)).min(5.0);
        error += trial.impulse + rounding * (run.lambda_scale + max_abs(&trial.y[..len]).to_f64());
        if crossed(&before, &after) {
            // Locate the first crossing by bisection of the step, re-integrated from its start.
            stats.events += 1;
            let (mut lo, mut hi) = (T::zero(), hh.clone());
            let mut at_hi = (trial.y, trial.slope, after);
            let two = T::one() + T::one();
            let width = hh.to_f64() * tol * 1e-3;
            while (hi.clone() - &lo).to_f64() > width {
                let mid = (lo.clone() + &hi) / two.clone();
                if (mid.clone() - &lo).is_zero() || (hi.clone() - &mid).is_zero() {
                    break;
                }
                let tm = run.step(&st, &normals, &k0, &mid)?;
                let s_mid = st.s.clone() + &mid;
                let gm = run.margins(&st, &normals, &rules, &s_mid, &tm.y, &tm.slope.rates);
                if crossed(&before, &gm) {
                    hi = mid;
                    at_hi = (tm.y, tm.slope, gm);
                } else {
                    lo = mid;
                }
            }
            let (y, slope, g) = at_hi;
            error += (hi.clone() - &lo).to_f64() * max_abs(&slope.rates.lambda).to_f64();
            st.y = y;
            st.s += &hi;
            let fire = |k: usize| before[k] >= 0.0 && g[k] < 0.0;
            let fired = Fired {
                leaving: (0..n).filter(|&i| fire(2 * i)).collect(),
                resting: Vec::new(),
                releasing: (0..n).filter(|&i| fire(2 * n + 2 * i)).collect(),
                engaging: (0..n).filter(|&i| fire(2 * n + 2 * i + 1)).collect(),
            };
            for i in 0..n {
                if fire(2 * i + 1) {
                    st.stopped[i] = true;
                }
            }
            // A release or re-engagement located past its slack: the slack's impulse.
            let slacked = fired.releasing.len() + fired.engaging.len();
            error += slacked as f64 * tol * run.lambda_scale;
            close_segment(&mut segments, &seg_start, &st, &seg_modes, &seg_rates);
            samples.push(sample(&st, &seg_modes, len));
            normals = choose(&run, &mut st, &fired, &mut verdicts)?;
            k0 = run.slope(&st, &normals, &st.y)?;
            seg_start = st.s.clone();
            seg_modes = labels(hypothesis, &normals, &st.modes);
            samples.push(sample(&st, &seg_modes, len));
            seg_rates = k0.rates.lambda.clone();
            h = (h * grow).max(hi.to_f64());
        } else {
            st.y = trial.y;
            st.s = if hit_end {
                end.clone().expect("a phase end was hit")
            } else {
                st.s.clone() + &hh
            };
            k0 = trial.slope;
            let v_end = run.velocities(&st.y);
            error += run.shared_lag(&v_end, &st, &k0.rates, hh.to_f64());
            st.modes = run.modes_at(&v_end, &st);
            // Locked slips: hold the direction tracked at the new state, add its lag to the
            // estimate, and release once the next step resolves the pull, κ h ≤ ρ.
            let next_h = hh.to_f64() * grow;
            for x in held {
                let i = x.contact;
                if x.lost {
                    st.locked[i] = false;
                    continue;
                }
                error += x.lag;
                st.modes[i] = Mode::Slide(x.u);
                // A direction pushed away from the invariant one (κ < 0) is held all the same:
                // the slip that leaves zero slip is the one trajectory that stays with the
                // invariant direction, and an explicit step would leave it (the neighbouring
                // slips diverge from it: a verdict).
                if x.kappa.abs() * next_h <= x.rho {
                    st.locked[i] = false;
                } else if x.kappa < 0.0
                    && !verdicts.iter().any(
                        |v| matches!(v, Verdict::UnstableSlip { contact, .. } if *contact == i),
                    )
                {
                    verdicts.push(Verdict::UnstableSlip {
                        contact: i,
                        s: st.s.to_f64(),
                    });
                }
            }
            for i in 0..n {
                if !matches!(st.modes[i], Mode::Slide(_)) {
                    st.locked[i] = false;
                }
            }
            h = hh.to_f64() * grow;
            if hypothesis == Hypothesis::Unilateral {
                let gaps = run.gaps(&st, &rules, &st.s, &st.y);
                for i in 0..n {
                    st.armed[i] |= st.released[i] && gaps[i] > run.delta;
                }
            }
            samples.push(sample(&st, &seg_modes, len));
            if hit_end {
                close_segment(&mut segments, &seg_start, &st, &seg_modes, &seg_rates);
                if st.phase == Phase::Restitution {
                    break;
                }
                begin_restitution(&run, &mut st);
                normals = choose(&run, &mut st, &Fired::default(), &mut verdicts)?;
                k0 = run.slope(&st, &normals, &st.y)?;
                seg_start = st.s.clone();
                seg_modes = labels(hypothesis, &normals, &st.modes);
                samples.push(sample(&st, &seg_modes, len));
                seg_rates = k0.rates.lambda.clone();
            }
        }
        if st.phase == Phase::Restitution
            && law == Restitution::Energetic
            && st.stopped.iter().all(|&x| x)
        {
            close_segment(&mut segments, &seg_start, &st, &seg_modes, &seg_rates);
            break;
        }
    }
    let v = run.velocities(&st.y);
    let lambda = st.y[..len].to_vec();
    let wc = st.y[len..len + n].to_vec();
    let wr = st.y[len + n..len + 2 * n].to_vec();
    let ef = st.y[len + 2 * n].clone();
    let end = st.s.clone();
    let mut out = Frictional::finish(
        mechanism,
        b,
        law,
        lambda,
        st.compression,
        v,
        wc,
        wr,
        ef,
        segments,
        verdicts,
        end,
    );
    out.hypothesis = hypothesis;
    out.error_estimate = Some(error * response.max(1.0));
    out.tolerance = Some(tol);
    out.samples = samples;
    Ok((out, stats))
}

/// Enter the restitution phase: the compression impulses p^c, and under the energetic law
/// which contacts have no restitution work to do.
fn begin_restitution<T: Scalar, S: Screws<T>>(run: &Run<'_, T, S>, st: &mut State<T>) {
    let (n, len) = (run.n(), run.len());
    st.phase = Phase::Restitution;
    st.compression = run.b.offset.iter().map(|&o| st.y[o].clone()).collect();
    if run.law == Restitution::Energetic {
        for i in 0..n {
            let k = &run.contacts[i].k_energetic;
            let left = k.clone() * k * &st.y[len + i];
            st.stopped[i] = st.compression[i].is_zero() || left.signum_i8() <= 0;
        }
    }
}

/// The path's sample at the current state, with the modes of the segment it belongs to.
fn sample<T: Scalar>(st: &State<T>, modes: &[ModeLabel], len: usize) -> Sample<T> {
    Sample {
        s: st.s.clone(),
        phase: st.phase,
        impulses: st.y[..len].to_vec(),
        modes: modes.to_vec(),
    }
}

fn close_segment<T: Scalar>(
    segments: &mut Vec<Segment<T>>,
    from: &T,
    st: &State<T>,
    modes: &[ModeLabel],
    rates: &[T],
) {
    if (st.s.clone() - from).is_zero() {
        return;
    }
    segments.push(Segment {
        from: from.clone(),
        to: st.s.clone(),
        phase: st.phase,
        modes: modes.to_vec(),
        rates: rates.to_vec(),
    });
}

/// One consistent assignment of [`choose`]: the state resolved under it, its rules and the
/// verdicts its resolution gave.
#[derive(Clone)]
struct Choice<T: Scalar> {
    st: State<T>,
    normals: Vec<Normal<T>>,
    said: Vec<Verdict>,
}

/// The events that fired at the state being resolved.
#[derive(Default)]
struct Fired {
    /// Sticking contacts whose required rate left the cone: they must slide.
    leaving: Vec<usize>,
    /// Sliding contacts just declared at zero slip.
    resting: Vec<usize>,
    /// Driven contacts whose path needs a pull (unilateral law).
    releasing: Vec<usize>,
    /// Released contacts whose gap closed (unilateral law).
    engaging: Vec<usize>,
}

/// Choose the normal rules and the modes at the current state (s = 0, a phase's end, an event)
/// and return the rules. Under the simultaneous law they are the phase's ([`normal_rules`]) and
/// only the modes are chosen ([`resolve`]). Under the unilateral law every contact on its path
/// — driven, or released with its gap within δ — is driven or released jointly with stick and
/// slip, as in the plane: the assignments of [`unilateral_assignments`] in their order, each
/// resolved by [`resolve`] and consistent when its rates pass [`normal_consistent`] with the
/// slack of the event margins (tol × Λ-scale on an impulse rate, δ = tol × max|v⁰| on a gap's
/// rate). The first consistent assignment is taken — except that one in which every contact
/// whose release (re-engagement) margin fired is released (driven) is preferred: the event is
/// located just past the slack, where the rule left behind may still pass within it. Distinct
/// consistent rates (beyond twice the slack) are a verdict ([`Verdict::Ambiguous`]).
fn choose<T: Scalar, S: Screws<T>>(
    run: &Run<'_, T, S>,
    st: &mut State<T>,
    fired: &Fired,
    verdicts: &mut Vec<Verdict>,
) -> Result<Vec<Normal<T>>, FrictionError> {
    let normals = run.normals(st);
    if run.hypothesis == Hypothesis::Simultaneous {
        resolve(run, st, &normals, &fired.leaving, &fired.resting, verdicts)?;
        return Ok(normals);
    }
    let (b, n) = (run.b, run.n());
    let rules = unilateral_rules(&normals, b, st.phase);
    let gaps = run.gaps(st, &rules, &st.s, &st.y);
    let on_path: Vec<bool> = (0..n)
        .map(|i| !st.released[i] || gaps[i] <= run.delta || fired.engaging.contains(&i))
        .collect();
    let slack_impulse: T = of(run.tol * run.lambda_scale);
    let slack_velocity: T = of(run.delta);
    let mut first: Option<Choice<T>> = None;
    let mut honoured: Option<Choice<T>> = None;
    let mut distinct: Vec<Vec<T>> = Vec::new();
    let mut failure: Option<FrictionError> = None;
    for a in unilateral_assignments(&rules, &on_path) {
        let mut trial = st.clone();
        let mut said = Vec::new();
        let resolved = resolve(
            run,
            &mut trial,
            &a.normals,
            &fired.leaving,
            &fired.resting,
            &mut said,
        )
        .and_then(|()| rates(b, &a.normals, &trial.modes).map_err(|e| run.fail(e, st)));
        let r = match resolved {
            Ok(r) => r,
            Err(e) => {
                if failure.is_none() || matches!(e, FrictionError::Undetermined { .. }) {
                    failure = Some(e);
                }
                continue;
            }
        };
        if !normal_consistent(b, &r, &a.checks, &slack_impulse, &slack_velocity) {
            continue;
        }
        let near = 2.0 * (run.tol * run.lambda_scale);
        let same = |d: &Vec<T>| {
            d.iter()
                .zip(&r.lambda)
                .all(|(x, y)| (x.clone() - y).to_f64().abs() <= near)
        };
        if !distinct.iter().any(same) {
            distinct.push(r.lambda.clone());
        }
        let honours = fired
            .releasing
            .iter()
            .all(|&i| matches!(a.normals[i], Normal::Given(_)))
            && fired
                .engaging
                .iter()
                .all(|&i| matches!(a.normals[i], Normal::Driven(_)));
        let choice = Choice {
            st: trial,
            normals: a.normals,
            said,
        };
        if honours && honoured.is_none() {
            honoured = Some(choice.clone());
        }
        if first.is_none() {
            first = Some(choice);
        }
    }
    let Some(Choice {
        st: chosen,
        normals,
        said,
    }) = honoured.or(first)
    else {
        return Err(match failure {
            Some(e @ FrictionError::Undetermined { .. }) => e,
            _ => FrictionError::NoConsistentModes {
                s: st.s.to_f64(),
                phase: st.phase,
            },
        });
    };
    *st = chosen;
    verdicts.extend(said);
    if distinct.len() > 1 {
        verdicts.push(Verdict::Ambiguous {
            s: st.s.to_f64(),
            consistent: distinct.len(),
        });
    }
    for i in 0..n {
        st.released[i] = matches!(normals[i], Normal::Given(_));
        st.armed[i] = st.released[i] && gaps[i] > run.delta;
    }
    Ok(normals)
}

/// Choose the modes at the current state: contacts without friction or normal impulse rate
/// are free; slipping ones slide; those at zero slip stick if their cones allow it (and they
/// are not `leaving` it: their cone margin was just found negative), else slide along an
/// invariant direction of their tangential block, one contact at a time.
fn resolve<T: Scalar, S: Screws<T>>(
    run: &Run<'_, T, S>,
    st: &mut State<T>,
    normals: &[Normal<T>],
    leaving: &[usize],
    resting: &[usize],
    verdicts: &mut Vec<Verdict>,
) -> Result<(), FrictionError> {
    let b = run.b;
    let n = run.n();
    let v = run.velocities(&st.y);
    if run.hypothesis == Hypothesis::Simultaneous {
        find_pulling(run, st, normals, &v, resting);
    }
    let mut candidates = Vec::new();
    for i in 0..n {
        if b.dims[i] == 0 || !carries(&normals[i]) || st.pulling[i] {
            st.modes[i] = Mode::Free;
            st.locked[i] = false;
            continue;
        }
        let (vt, rho) = run.slip(&v, &st.origin, i);
        // A contact just declared at zero slip is at zero slip, whatever the turn of its
        // direction left over the last (Euler) stretch.
        if rho > run.delta && !resting.contains(&i) {
            // A held slip stays held while its invariant direction under the rules from here
            // on is where it was (an event elsewhere); a phase's end that moves or removes it
            // releases the slip to its own direction.
            let mut tracked = st.modes.clone();
            let holds = st.locked[i]
                && matches!(st.modes[i], Mode::Slide(_))
                && run.settle(&mut tracked, normals, i);
            if holds {
                st.modes[i] = tracked[i].clone();
            } else {
                st.modes[i] = Mode::Slide(unit(&vt));
                st.locked[i] = false;
            }
        } else {
            // At zero slip: its residual is set aside (see `State::origin`).
            let off = b.offset[i] + 1;
            st.origin[off..off + 2].clone_from_slice(&v[off..off + 2]);
            candidates.push(i);
            st.modes[i] = Mode::Stick;
            st.locked[i] = false;
        }
    }
    // A contact that left its cone and is released since carries no friction to slide with.
    let leaving: Vec<usize> = leaving
        .iter()
        .copied()
        .filter(|l| candidates.contains(l))
        .collect();
    let m = candidates.len();
    if m > crate::impact::friction::modes::MAX_CANDIDATES {
        return Err(FrictionError::TooManyAtRest {
            s: st.s.to_f64(),
            contacts: m,
        });
    }
    // All at zero slip stick, if their cones hold them.
    let all_stick = rates(b, normals, &st.modes);
    if let Ok(r) = &all_stick
        && leaving.is_empty()
        && sticks_hold(run, st, &candidates, r)
    {
        if let Some(v) = super::split_verdict(r, st.s.to_f64(), run.law, run.contacts) {
            verdicts.push(v);
        }
        return Ok(());
    }
    // The slip starts along the required sticking impulse, to first approximation (along the
    // first tangent axis when sticking has no rates at all).
    let guesses: Vec<Vec<T>> = candidates
        .iter()
        .map(|&i| {
            let off = b.offset[i];
            match &all_stick {
                Ok(r) if !norm(&r.lambda[off + 1..off + 3]).is_zero() => {
                    unit(&r.lambda[off + 1..off + 3])
                }
                _ => vec![T::one(), T::zero()],
            }
        })
        .collect();
    // Otherwise the fewest contacts slide: every subset S of the candidates that holds the
    // contacts forced out of stick, by size, each slide along its invariant direction (jointly
    // when several slide), the others sticking in their cones.
    let mut subsets: Vec<usize> = (1..1usize << m)
        .filter(|&bits| {
            leaving.iter().all(|l| {
                candidates
                    .iter()
                    .position(|c| c == l)
                    .is_none_or(|k| bits >> k & 1 == 1)
            })
        })
        .collect();
    subsets.sort_by_key(|bits| bits.count_ones());
    let start = st.modes.clone();
    for bits in subsets {
        st.modes.clone_from(&start);
        let sliding: Vec<usize> = (0..m).filter(|k| bits >> k & 1 == 1).collect();
        let found = if let [k] = sliding[..] {
            invariant_direction(
                run,
                st,
                normals,
                candidates[k],
                guesses[k].clone(),
                verdicts,
            )
            .map(|u| st.modes[candidates[k]] = Mode::Slide(u))
            .is_ok()
        } else {
            // Jointly, from the guesses in every combination of senses.
            (0..1usize << sliding.len()).any(|flips| {
                st.modes.clone_from(&start);
                let flipped: Vec<Vec<T>> = guesses
                    .iter()
                    .enumerate()
                    .map(|(k, g)| match sliding.iter().position(|&x| x == k) {
                        Some(j) if flips >> j & 1 == 1 => g.iter().map(|x| -x.clone()).collect(),
                        _ => g.clone(),
                    })
                    .collect();
                joint_directions(run, st, normals, &candidates, &sliding, &flipped)
            }) || {
                st.modes.clone_from(&start);
                joint_by_root(
                    run,
                    st,
                    normals,
                    &candidates,
                    &sliding,
                    &guesses,
                    all_stick.as_ref().ok(),
                )
            }
        };
        if !found {
            continue;
        }
        let Ok(r) = rates(b, normals, &st.modes) else {
            continue;
        };
        if sticks_hold(run, st, &candidates, &r) {
            if let Some(v) = super::split_verdict(&r, st.s.to_f64(), run.law, run.contacts) {
                verdicts.push(v);
            }
            for &k in &sliding {
                st.locked[candidates[k]] = true;
            }
            return Ok(());
        }
    }
    Err(FrictionError::NoConsistentModes {
        s: st.s.to_f64(),
        phase: st.phase,
    })
}

/// Which frictional contacts at zero slip the simultaneous hypothesis holds on their paths by a
/// pull ([`State::pulling`]): a contact freed before stays free while, free, it still pulls;
/// then, with every contact at zero slip sticking and every other sliding
/// along its slip, the one whose normal rate is the most negative beyond the tolerance is
/// freed of friction — if it still pulls once free (else the pull is friction's own doing, as
/// in a slide whose friction drives the contact into the surface, and the contact is left to
/// the search of modes) — and the rates are found again, until none is. A contact sliding
/// when it pulls keeps its slide (its friction μ p' u then acts along the slip, the verdict
/// [`Verdict::TensileRate`] says so), as in the plane. A contact just declared at zero slip
/// (`resting`) is at zero slip here as in [`resolve`], whatever residual the stop step left it
/// (the can of issue 27 at its impact 19: four corners stopped with residuals of 1–7.5 δ, none
/// was taken to stick, and its pivot was not freed).
fn find_pulling<T: Scalar, S: Screws<T>>(
    run: &Run<'_, T, S>,
    st: &mut State<T>,
    normals: &[Normal<T>],
    v: &[T],
    resting: &[usize],
) {
    let b = run.b;
    let n = run.n();
    let was = std::mem::replace(&mut st.pulling, vec![false; n]);
    let slack = -run.tol * run.lambda_scale;
    let at_zero_slip: Vec<bool> = (0..n)
        .map(|i| {
            b.dims[i] > 0 && (run.slip(v, &st.origin, i).1 <= run.delta || resting.contains(&i))
        })
        .collect();
    let rates_now = |pulling: &[bool]| {
        let modes: Vec<Mode<T>> = (0..n)
            .map(|i| {
                if b.dims[i] == 0 || !carries(&normals[i]) || pulling[i] {
                    Mode::Free
                } else if at_zero_slip[i] {
                    Mode::Stick
                } else {
                    Mode::Slide(unit(&run.slip(v, &st.origin, i).0))
                }
            })
            .collect();
        rates(b, normals, &modes).ok().map(|r| (modes, r))
    };
    // A contact freed before stays free while it still pulls so.
    st.pulling.clone_from(&was);
    for i in 0..n {
        if was[i]
            && !rates_now(&st.pulling).is_some_and(|(_, r)| r.lambda[b.offset[i]].to_f64() < slack)
        {
            st.pulling[i] = false;
        }
    }
    for _ in 0..n {
        let Some((modes, r)) = rates_now(&st.pulling) else {
            return;
        };
        let most = (0..n)
            .filter(|&i| modes[i] == Mode::Stick && matches!(normals[i], Normal::Driven(_)))
            .map(|i| (i, r.lambda[b.offset[i]].to_f64()))
            .filter(|(_, p)| *p < slack)
            .min_by(|x, y| x.1.total_cmp(&y.1));
        let Some((i, _)) = most else { return };
        st.pulling[i] = true;
        let still =
            rates_now(&st.pulling).is_some_and(|(_, r)| r.lambda[b.offset[i]].to_f64() < slack);
        if !still {
            st.pulling[i] = false;
            return;
        }
    }
}

/// Whether every sticking candidate's required rate lies in its cone (to the tolerance's
/// slack, as the event margins) with a nonnegative normal rate.
fn sticks_hold<T: Scalar, S: Screws<T>>(
    run: &Run<'_, T, S>,
    st: &State<T>,
    candidates: &[usize],
    r: &Rates<T>,
) -> bool {
    let b = run.b;
    let scale = max_abs(&r.lambda);
    candidates.iter().all(|&i| {
        if st.modes[i] != Mode::Stick {
            return true;
        }
        let off = b.offset[i];
        let p = &r.lambda[off];
        let tau = norm(&r.lambda[off + 1..off + 3]);
        let margin = (b.mu[i].clone() * p - tau).to_f64() + run.tol * run.lambda_scale;
        nonnegative(p, &scale, b.len()) && margin >= 0.0
    })
}

/// Several contacts leaving zero slip together: their slip directions by a joint fixed-point
/// iteration u_i ← dv_it/|dv_it| from the `guesses`; true when it settles with every λ_i > 0
/// and nonnegative normal rates (the modes are left set).
fn joint_directions<T: Scalar, S: Screws<T>>(
    run: &Run<'_, T, S>,
    st: &mut State<T>,
    normals: &[Normal<T>],
    candidates: &[usize],
    sliding: &[usize],
    guesses: &[Vec<T>],
) -> bool {
    let b = run.b;
    let settled = run.tol.max(64.0 * T::epsilon_f64());
    for &k in sliding {
        st.modes[candidates[k]] = Mode::Slide(guesses[k].clone());
    }
    for _ in 0..200 {
        let Ok(r) = rates(b, normals, &st.modes) else {
            return false;
        };
        let mut diff: f64 = 0.0;
        let mut all_out = true;
        for &k in sliding {
            let i = candidates[k];
            let off = b.offset[i];
            let dv = &r.velocity[off + 1..off + 3];
            if norm(dv).is_zero() {
                return false;
            }
            let next = unit(dv);
            let Mode::Slide(u) = &st.modes[i] else {
                return false;
            };
            diff = diff.max(
                next.iter()
                    .zip(u)
                    .map(|(a, c)| (a.clone() - c).to_f64().abs())
                    .fold(0.0, f64::max),
            );
            all_out &= dot(u, dv).signum_i8() > 0
                && nonnegative(&r.lambda[off], &max_abs(&r.lambda), b.len());
            st.modes[i] = Mode::Slide(next);
        }
        if diff <= settled {
            return all_out;
        }
    }
    false
}

/// Several contacts leaving zero slip together where the joint fixed-point iteration
/// ([`joint_directions`]) does not settle: their joint invariant directions by Newton's method
/// ([`departure::joint_root`]) — the module's rule for one contact (a root finder, since the
/// iteration diverges at strongly attracting directions) applied to several. Started from one
/// common direction — the resultant of the sliding contacts' required sticking impulses
/// (`sticking`), in each contact's tangent axes: the contacts of one face whose slips stop
/// together restart along one direction when the face slides in translation — then from the
/// `guesses` in every combination of senses. A root is consistent as in
/// [`joint_directions`]: every λ_k > 0 and nonnegative normal rates. The first consistent root
/// that attracts the slips around it (every eigenvalue of D J with a negative real part,
/// [`departure::JointRoot::attraction`]) is taken: the roots the fixed-point iteration settles
/// on are those with the eigenvalues in the disc |1 + z| < 1, a part of them, so this widens the
/// search to every attracting root and to nothing else — a repelling one is not taken (the
/// search of modes goes on, as when the iteration does not settle). True when one is taken
/// (the modes are left set).
#[allow(clippy::too_many_arguments)]
fn joint_by_root<T: Scalar, S: Screws<T>>(
    run: &Run<'_, T, S>,
    st: &mut State<T>,
    normals: &[Normal<T>],
    candidates: &[usize],
    sliding: &[usize],
    guesses: &[Vec<T>],
    sticking: Option<&Rates<T>>,
) -> bool {
    let b = run.b;
    let contacts: Vec<usize> = sliding.iter().map(|&k| candidates[k]).collect();
    let mut starts: Vec<Vec<Vec<T>>> = Vec::new();
    if let Some(r) = sticking {
        let mut resultant = [T::zero(), T::zero(), T::zero()];
        for &i in &contacts {
            let off = b.offset[i];
            for a in 0..b.dims[i] {
                let e = &b.directions[off + 1 + a];
                for (x, c) in resultant.iter_mut().enumerate() {
                    *c += e[x].clone() * &r.lambda[off + 1 + a];
                }
            }
        }
        let common: Vec<Vec<T>> = contacts
            .iter()
            .map(|&i| {
                let off = b.offset[i];
                (0..b.dims[i])
                    .map(|a| {
                        let e = &b.directions[off + 1 + a];
                        (0..3).fold(T::zero(), |acc, x| acc + resultant[x].clone() * &e[x])
                    })
                    .collect()
            })
            .collect();
        if common.iter().all(|u| u.len() == 2 && !norm(u).is_zero()) {
            starts.push(common.iter().map(|u| unit(u)).collect());
        }
    }
    for flips in 0..1usize << sliding.len() {
        starts.push(
            sliding
                .iter()
                .enumerate()
                .map(|(j, &k)| match flips >> j & 1 {
                    1 => guesses[k].iter().map(|x| -x.clone()).collect(),
                    _ => guesses[k].clone(),
                })
                .collect(),
        );
    }
    let start_modes = st.modes.clone();
    for from in &starts {
        st.modes.clone_from(&start_modes);
        let Some(root) =
            departure::joint_root(b, normals, &mut st.modes, &contacts, from, run.settled())
        else {
            continue;
        };
        let Ok(r) = rates(b, normals, &st.modes) else {
            continue;
        };
        let consistent = root.lambda.iter().all(|l| l.signum_i8() > 0)
            && contacts
                .iter()
                .all(|&i| nonnegative(&r.lambda[b.offset[i]], &max_abs(&r.lambda), b.len()));
        if consistent && root.attraction < 0.0 {
            return true;
        }
    }
    st.modes = start_modes;
    false
}

/// The direction along which contact i leaves zero slip (Bhatt and Koechling): a unit u with
/// dv_t/ds = λ u and λ > 0 when the contact slides along u. Fixed-point iteration
/// u ← dv_t(u)/|dv_t(u)| from `guess` (it settles only on a direction that attracts with
/// κ < 2λ: [`departure`]); otherwise every invariant direction of the circle
/// ([`departure::invariant_directions`]), those that attract the slips around them preferred
/// (a slip restarting at a cone's edge, λ → 0⁺, must take the one that grows out of the edge's
/// direction, which attracts), then the nearest `guess` — a verdict when there are several.
fn invariant_direction<T: Scalar, S: Screws<T>>(
    run: &Run<'_, T, S>,
    st: &mut State<T>,
    normals: &[Normal<T>],
    i: usize,
    guess: Vec<T>,
    verdicts: &mut Vec<Verdict>,
) -> Result<Vec<T>, FrictionError> {
    let b = run.b;
    let settled = run.settled();
    let mut u = guess.clone();
    for _ in 0..100 {
        let (_, lambda, dv) =
            departure::slip_rate(b, normals, &mut st.modes, i, &u).map_err(|e| run.fail(e, st))?;
        if norm(&dv).is_zero() {
            break;
        }
        let next = unit(&dv);
        let diff = next
            .iter()
            .zip(&u)
            .map(|(a, c)| (a.clone() - c).to_f64().abs())
            .fold(0.0, f64::max);
        u = next;
        if diff <= settled && lambda.signum_i8() > 0 {
            return Ok(u);
        }
    }
    let roots = departure::invariant_directions(b, normals, &mut st.modes, i)
        .map_err(|e| run.fail(e, st))?;
    let best = roots
        .iter()
        .max_by(|x, y| {
            (x.kappa > 0.0).cmp(&(y.kappa > 0.0)).then(
                dot(&x.u, &guess)
                    .to_f64()
                    .total_cmp(&dot(&y.u, &guess).to_f64()),
            )
        })
        .map(|r| r.u.clone())
        .ok_or(FrictionError::NoConsistentModes {
            s: st.s.to_f64(),
            phase: st.phase,
        })?;
    if roots.len() > 1 {
        verdicts.push(Verdict::Ambiguous {
            s: st.s.to_f64(),
            consistent: roots.len(),
        });
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use crate::impact::friction::{FrictionError, Hypothesis, Restitution, solve_frictional_under};
    use crate::impact::problem::Problem;
    use crate::mechanics::body::RigidBody;
    use crate::mechanics::contact::Contact;
    use crate::mechanics::screw::{Screw, Vec3};

    /// Impact 18 of the can of examples/simulate/tumbling-can.toml on a floor with μ = 0.5
    /// under the simultaneous law (issue 27), recorded: its face lands flat on the rim's four
    /// body points, tipping about x on the point at 90° (normal velocity 0) while it slides in
    /// translation along +y (slip 2.43·10⁻⁴ m/s at every point). All four slips stop together
    /// at s = 0.0819; sticking would need |F_t| = 1.2 F_z on the face, beyond μ = 0.5; the
    /// point at 90° pulls in every member of the normal family and is freed; the other three
    /// reverse their slip together along one direction (−y), a joint invariant direction with
    /// λ = 9.1·10⁻⁴ > 0 at each, which attracts the slips around it (D J has the eigenvalue
    /// −3) — so the joint fixed-point iteration, whose derivative there is 1 + D J = −2,
    /// cycled and the impact stopped with "no assignment of stick and slip is consistent".
    fn landing() -> Problem<f64> {
        let tensor = [
            [0.00073, -3.504573386819196e-30, -3.7625164266306867e-19],
            [-3.504573386819196e-30, 0.00073, -2.1430244674468287e-15],
            [-3.7625164266306867e-19, -2.1430244674468287e-15, 0.0005],
        ];
        let w = [
            0.03492262692065631,
            4.5819160775490105e-11,
            4.1766985460790356e-11,
        ];
        let v = [
            -1.3916519764134747e-12,
            -0.001852285045158771,
            -0.0017461313460132926,
        ];
        let points = [
            [
                0.049999999999999906,
                -5.599479213636016e-13,
                -0.060000000000465875,
            ],
            [
                8.018315286146461e-16,
                0.04999999999944096,
                -0.060000000000465875,
            ],
            [
                -0.0500000000000001,
                -5.581507478424896e-13,
                -0.060000000000465875,
            ],
            [
                -9.98136733482334e-16,
                -0.050000000000559056,
                -0.060000000000465875,
            ],
        ];
        let contacts = points
            .iter()
            .map(|d| {
                Contact::new(Vec3::new(d[0], d[1], d[2]), Vec3::new(0.0, 0.0, -1.0), 0.3)
                    .with_friction(0.5)
            })
            .collect();
        Problem::new(
            RigidBody::with_tensor(0.4, tensor),
            Screw::new(Vec3::new(w[0], w[1], w[2]), Vec3::new(v[0], v[1], v[2])),
            contacts,
        )
        .unwrap()
    }

    /// The recorded landing now has an answer, and it meets what the law asks, checked on the
    /// twist after itself: Newton's law at every contact (v_x⁺ = −k v_x⁰, the simultaneous
    /// path), to twice the run's error estimate (which bounds the twist; a contact's normal
    /// velocity is the twist's product with unit directions and arms of 0.078 m, so within
    /// (1 + 3 · 0.078) of it); Coulomb's cone on the whole impulse of the three points that
    /// never pull (|τ_i| ≤ μ P_i, a consequence of |dτ_i| ≤ μ dp_i at every instant, to the
    /// same estimate); the kinetic energy after, from the twist and the inertia, no more than
    /// before; and the face leaving without yaw (the three points slide along one direction:
    /// ω_z⁺ within the estimate of ω_z⁰ = 4·10⁻¹¹).
    #[test]
    fn a_face_whose_three_points_reverse_their_slip_together_slides_on() {
        let problem = landing();
        let out = solve_frictional_under::<f64, _>(
            &problem,
            Restitution::Newton,
            Hypothesis::Simultaneous,
            1e-10,
        )
        .unwrap_or_else(|e: FrictionError| panic!("{e}"));
        let est = out.error_estimate.expect("a spatial run has an estimate");
        let b = &out.blocks;
        for i in 0..4 {
            let o = b.offset[i];
            let (before, after) = (b.v0[o], out.after[o]);
            assert!(
                (after + 0.3 * before).abs() <= 2.0 * est,
                "contact {i}: v⁺ = {after}, v⁰ = {before}, estimate {est}"
            );
        }
        for i in [0, 2, 3] {
            let o = b.offset[i];
            let (p, t) = (
                out.impulses[o],
                out.impulses[o + 1].hypot(out.impulses[o + 2]),
            );
            assert!(p > 0.0, "contact {i}: P = {p}");
            assert!(
                t <= 0.5 * p + 2.0 * est,
                "contact {i}: |τ| = {t}, μP = {}",
                0.5 * p
            );
        }
        let energy = |w: [f64; 3], v: [f64; 3]| {
            let j = [[0.00073, 0.0, 0.0], [0.0, 0.00073, 0.0], [0.0, 0.0, 0.0005]];
            let rot: f64 = (0..3)
                .map(|p| (0..3).map(|q| w[p] * j[p][q] * w[q]).sum::<f64>())
                .sum();
            0.5 * rot + 0.5 * 0.4 * v.iter().map(|x| x * x).sum::<f64>()
        };
        let (w0, v0) = (
            [
                0.03492262692065631,
                4.5819160775490105e-11,
                4.1766985460790356e-11,
            ],
            [
                -1.3916519764134747e-12,
                -0.001852285045158771,
                -0.0017461313460132926,
            ],
        );
        let (w, v) = (out.velocity.top(), out.velocity.bottom());
        let after = energy([w[0], w[1], w[2]], [v[0], v[1], v[2]]);
        assert!(
            after < energy(w0, v0),
            "{after} J after, {} before",
            energy(w0, v0)
        );
        assert!(out.friction_dissipation >= 0.0);
        assert!(
            (w[2] - w0[2]).abs() <= 2.0 * est,
            "ω_z⁺ = {}, estimate {est}",
            w[2]
        );
    }
}
