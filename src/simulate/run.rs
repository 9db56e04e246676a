//! The event loop: free flight and persistent contact integrated between events, every impact
//! solved by the scene's law, until the duration, the impact budget or rest.
//!
//! **Integration.** The packed state (x, q, v, ω) is stepped by Dormand–Prince RK5(4)
//! ([`super::ode`]) with the accelerations of [`super::contact::accelerations`] (free flight
//! when no contact is closed). Ballistic flight of C is a quadratic in t, which the fifth-order
//! solution reproduces to rounding; the rotation (Euler's equations) and persistent contact are
//! held to the relative `tolerance` per step, on the scales of the motion (the body's reach for
//! positions, the speed scale for velocities). The quaternion is normalised after every step and
//! the closed contacts are projected back onto their constraints ([`super::contact::project`]);
//! the largest gap so corrected is reported as the drift. The steps are not cut at the output
//! times: the samples inside a step are read from its continuous extension (fourth order,
//! [`super::ode::Dense`]) ([`super::stepper`], shared with the system's loop).
//!
//! **Events by conservative advancement.** No step may cross an open gap: with g the gap of a
//! feature, ġ its rate and M a bound on |g̈| over the step (twice |a| + ρ(|ω|² + |α|) at the
//! step's start, ρ the feature's distance from C), g(t + s) ≥ g + ġ s − ½ M s², positive for
//! s < (ġ + √(ġ² + 2 M g))/M ([`super::stepper::horizon`], in the form that does not cancel
//! when ġ < 0). Each step is capped there, so a gap is approached from above at
//! a rate that converges quadratically near a transversal crossing, and no impact between
//! two steps is missed (a grazing one included). A gap within the gap tolerance
//! (10⁻¹¹ of the length scale) with ġ < −`rest_speed` is an impact; with |ġ| ≤ `rest_speed`
//! the contact closes if the accelerations press it, and is left open otherwise.
//!
//! **Impacts.** Every open feature approaching within the gap tolerance, and every one whose
//! time to contact g/|ġ| is within `simultaneity`, strikes together with every closed contact:
//! that is the one multi-point impact the law is asked (the largest time to contact joined is
//! reported with it: it is the simultaneity the answer assumes). After it, a contact at zero
//! gap whose normal velocity is below `rest_speed` stays closed (sticking where μ > 0 and its
//! slip is below the same speed).
//!
//! **Zeno.** When the same contacts on one plane (one, or the corners of a face landing flat)
//! have been struck three times in a row by a body that does not turn, with its tangential
//! velocity unchanged and rebound speeds in a constant ratio r < 1 (a bouncing ball: r = k),
//! the remaining impacts accumulate in closed form: the next
//! flight lasts 2u/g_n (u the rebound speed, g_n the gravity into the plane), and the sum of the
//! geometric series gives t∞ = t + 2u/(g_n (1 − r)). The body is moved there (tangential motion
//! ballistic, normal at zero gap and speed) and the contacts persist; the log reports it.

use super::body::{Body, State, V3};
use super::contact::{Closed, ContactError, Mode, accelerations, derivative, project};
use super::impact::{At, ImpactError, Law, solve};
use super::ode::floor;
use super::stepper::{self, Advance, Stall, Stepper};
use super::world::{Plane, gap};

/// How the simulation runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Gravity (m/s², world).
    pub gravity: V3,
    /// The time simulated (s).
    pub duration: f64,
    /// The most impacts (the run ends at the next one beyond).
    pub max_impacts: usize,
    /// The spacing of the trajectory's samples (s).
    pub output_step: f64,
    /// Contacts within this time to contact strike as one impact (s).
    pub simultaneity: f64,
    /// The relative tolerance of the integration and of the integrated impact laws.
    pub tolerance: f64,
    /// Below this normal speed after an impact a contact stays closed (m/s).
    pub rest_speed: f64,
}

/// What to simulate.
#[derive(Clone, Debug, PartialEq)]
pub struct Setup {
    /// The body.
    pub body: Body,
    /// The obstacles.
    pub planes: Vec<Plane>,
    /// The impact law.
    pub law: Law,
    /// The state at t = 0.
    pub start: State,
    /// The options.
    pub options: Options,
    /// A planar motion: the unit normal (world) of its plane through the start's C. The state
    /// is held in it after every step and impact (rounding would otherwise take it out, and
    /// with it the exact planar solves of the impact layer).
    pub plane: Option<V3>,
}

/// One contact of an impact, as the log reports it.
#[derive(Clone, Debug, PartialEq)]
pub struct Struck {
    /// The feature's name.
    pub feature: String,
    /// The plane's name.
    pub plane: String,
    /// Its gap when struck (m): 0 but for the simultaneity window.
    pub gap: f64,
    /// Its normal velocity before (m/s, negative approaching; 0 for a closed contact).
    pub before: f64,
    /// After.
    pub after: f64,
    /// Its normal impulse (N s).
    pub impulse: f64,
    /// Whether it was closed (persisting) when struck.
    pub persisting: bool,
}

/// One impact.
#[derive(Clone, Debug, PartialEq)]
pub struct ImpactRecord {
    /// Its number (1-based).
    pub index: usize,
    /// Its time (s).
    pub t: f64,
    /// The contacts struck together.
    pub contacts: Vec<Struck>,
    /// The largest time to contact joined into it (s).
    pub spread: f64,
    /// Kinetic energy before and after (J).
    pub kinetic_before: f64,
    /// After.
    pub kinetic_after: f64,
    /// Why the law's answer is not physical, if it is not.
    pub verdicts: Vec<String>,
    /// How it was solved, when that needs saying.
    pub note: Option<String>,
}

/// An event of the log other than an impact.
#[derive(Clone, Debug, PartialEq)]
pub struct Event {
    /// Its time (s).
    pub t: f64,
    /// What happened.
    pub what: String,
}

/// A sample of the trajectory.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// t (s).
    pub t: f64,
    /// The state.
    pub state: State,
    /// Kinetic energy (J).
    pub kinetic: f64,
    /// Potential energy −m g·x (J).
    pub potential: f64,
    /// The number of closed contacts.
    pub closed: usize,
}

/// Why the run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum End {
    /// The duration was reached.
    Duration,
    /// The impact budget was reached.
    Impacts,
    /// The body came to rest on its closed contacts.
    Rest,
    /// The run stopped on an error ([`Simulation::stopped`]): the history up to it is kept.
    Stopped,
}

/// The accumulation of impacts.
#[derive(Clone, Debug, PartialEq)]
pub struct Zeno {
    /// t∞ (s).
    pub t_inf: f64,
    /// The impact after which it was taken (1-based).
    pub after: usize,
    /// The ratio of successive rebound speeds.
    pub ratio: f64,
    /// The energy the accumulated impacts dissipated (J): the rebound's kinetic energy along
    /// the normal.
    pub dissipated: f64,
}

/// A whole run.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation {
    /// The impacts.
    pub impacts: Vec<ImpactRecord>,
    /// The other events: contacts closing, lifting off, sliding, sticking.
    pub events: Vec<Event>,
    /// The trajectory.
    pub samples: Vec<Sample>,
    /// The accumulation of impacts, if one was taken.
    pub zeno: Option<Zeno>,
    /// Why it ended.
    pub end: End,
    /// When (s).
    pub t_end: f64,
    /// The state then.
    pub state: State,
    /// Accepted and rejected steps.
    pub steps: (usize, usize),
    /// The largest gap the projection of closed contacts corrected (m).
    pub drift: f64,
    /// Why the run stopped early ([`End::Stopped`]).
    pub stopped: Option<SimulateError>,
}

/// Why a run stopped before its end.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimulateError {
    /// An impact had no answer under the law.
    #[error("impact {index} at t = {t:.9} s ({contacts}): {error}")]
    Impact {
        /// Its number.
        index: usize,
        /// Its time.
        t: f64,
        /// The contacts.
        contacts: String,
        /// Why.
        error: ImpactError,
    },
    /// Persistent contact could not be decided.
    #[error("t = {t:.9} s: persistent contact: {error}")]
    Contact {
        /// When.
        t: f64,
        /// Why.
        error: ContactError,
    },
    /// The run could not move on: its steps shrank to what f64 resolves in t, or to a pace
    /// that would not reach the end ([`super::stepper::Stall`]).
    #[error("t = {t:.9} s: the run stalled — {why}")]
    Stalled {
        /// When.
        t: f64,
        /// How.
        why: Stall,
    },
    /// The run produced a value that is not finite.
    #[error("t = {t:.9} s: the state overflowed f64")]
    NotFinite {
        /// When.
        t: f64,
    },
    /// Two members of a system overlap: a contact between them was missed
    /// ([`super::system::overlap`]).
    #[error(
        "t = {t:.9} s: {first} and {second} overlap by {depth:.3e} m (a contact between them \
         was missed: every contact of spheres, boxes and rods is watched, so this is a fault \
         to report)"
    )]
    Overlap {
        /// When.
        t: f64,
        /// The first member.
        first: String,
        /// The second.
        second: String,
        /// How deep (m).
        depth: f64,
    },
}

/// The most steps of one run.
pub const MAX_STEPS: usize = 10_000_000;

/// Run `setup` to its end.
///
/// # Errors
/// [`SimulateError`] when the run stopped early; the history up to there is in
/// [`Simulation::stopped`]'s run, which [`simulate_history`] returns whole.
pub fn simulate(setup: &Setup) -> Result<Simulation, SimulateError> {
    let sim = simulate_history(setup);
    match sim.stopped {
        Some(e) => Err(e),
        None => Ok(sim),
    }
}

/// Run `setup` to its end, or to the error that stops it ([`End::Stopped`], the error in
/// [`Simulation::stopped`]), keeping the history up to there.
pub fn simulate_history(setup: &Setup) -> Simulation {
    let mut run = Run::new(setup);
    let result = run.go().and_then(|end| run.finite(end));
    let (end, stopped) = match result {
        Ok(end) => (end, None),
        Err(e) => (End::Stopped, Some(e)),
    };
    Simulation {
        impacts: run.impacts,
        events: run.events,
        samples: run.samples,
        zeno: run.zeno,
        end,
        t_end: run.t,
        state: run.s,
        steps: run.stepper.steps,
        drift: run.drift,
        stopped,
    }
}

struct Run<'a> {
    setup: &'a Setup,
    stepper: Stepper,
    s: State,
    t: f64,
    closed: Vec<Closed>,
    hint: Vec<bool>,
    impacts: Vec<ImpactRecord>,
    events: Vec<Event>,
    samples: Vec<Sample>,
    zeno: Option<Zeno>,
    length: f64,
    speed: f64,
    gap_tol: f64,
    drift: f64,
}

impl<'a> Run<'a> {
    fn new(setup: &'a Setup) -> Run<'a> {
        let body = &setup.body;
        let s = setup.start.clone();
        let g = setup.options.gravity.norm();
        let gaps: Vec<f64> = pairs(setup)
            .map(|(f, p)| gap(&body.features[f], &setup.planes[p], &s).gap.abs())
            .collect();
        let length = gaps
            .iter()
            .copied()
            .fold(body.reach(), f64::max)
            .max(f64::MIN_POSITIVE);
        let speed = (s.v.norm() + s.w.norm() * body.reach())
            .max((2.0 * g * length).sqrt())
            .max(f64::MIN_POSITIVE);
        Run {
            setup,
            stepper: Stepper::new(setup.options.output_step, setup.options.duration),
            s,
            t: 0.0,
            closed: Vec::new(),
            hint: Vec::new(),
            impacts: Vec::new(),
            events: Vec::new(),
            samples: Vec::new(),
            zeno: None,
            length,
            speed,
            gap_tol: 1e-11 * length,
            drift: 0.0,
        }
    }

    /// `end`, when every energy of the run and the state it ends in are finite numbers; a run
    /// whose scales overflow f64 (an energy m g·x beyond 10³⁰⁸) stops instead of printing one.
    fn finite(&self, end: End) -> Result<End, SimulateError> {
        let body = &self.setup.body;
        let energy =
            |s: &State| body.kinetic_energy(s) - body.mass * self.setup.options.gravity.dot(&s.x);
        let finite = self
            .samples
            .iter()
            .all(|s| s.kinetic.is_finite() && s.potential.is_finite())
            && energy(&self.s).is_finite()
            && self.drift.is_finite();
        if finite {
            Ok(end)
        } else {
            Err(SimulateError::NotFinite { t: self.t })
        }
    }

    fn sample(&mut self) {
        self.sample_at(self.t, self.s.clone());
    }

    /// A sample of the state `s` at `t` (the current one, or one interpolated inside a step).
    fn sample_at(&mut self, t: f64, s: State) {
        let body = &self.setup.body;
        self.samples.push(Sample {
            t,
            kinetic: body.kinetic_energy(&s),
            potential: -body.mass * self.setup.options.gravity.dot(&s.x),
            state: s,
            closed: self.closed.len(),
        });
    }

    fn is_closed(&self, f: usize, p: usize) -> bool {
        self.closed.iter().any(|c| c.feature == f && c.plane == p)
    }

    fn accelerations(&mut self, s: &State) -> Result<super::contact::Accelerations, ContactError> {
        let o = &self.setup.options;
        accelerations(
            &self.setup.body,
            &self.setup.planes,
            s,
            &o.gravity,
            &self.closed,
            &mut self.hint,
            o.rest_speed,
        )
    }

    /// The accelerations at the current state, switching a sticking contact that leaves its
    /// cone to sliding.
    fn current(&mut self) -> Result<super::contact::Accelerations, SimulateError> {
        for _ in 0..=self.closed.len() {
            let s = self.s.clone();
            match self.accelerations(&s) {
                Ok(a) => return Ok(a),
                Err(ContactError::Slips { contact, direction }) => {
                    self.closed[contact].mode = Mode::Slide(direction);
                    self.closed[contact].armed = false;
                    let name = self.name(self.closed[contact].feature, self.closed[contact].plane);
                    self.events.push(Event {
                        t: self.t,
                        what: format!("{name} starts to slide"),
                    });
                }
                Err(error) => return Err(SimulateError::Contact { t: self.t, error }),
            }
        }
        Err(SimulateError::Contact {
            t: self.t,
            error: ContactError::NoActiveSet,
        })
    }

    /// Whether the body, slower than the rest speed, would stay put with every sliding
    /// contact stuck: the accelerations with them sticking are consistent (every friction force
    /// within its cone) and below `still`. A slide that began at zero slip at the edge of its
    /// cone may never speed up enough to be let stick again ([`Closed::armed`]), and would then
    /// chatter about zero slip at a body that is at rest.
    fn holds_when_stuck(&self, still: f64) -> bool {
        if !self.closed.iter().any(|c| matches!(c.mode, Mode::Slide(_))) {
            return false;
        }
        let stuck: Vec<Closed> = self
            .closed
            .iter()
            .map(|c| Closed {
                mode: match c.mode {
                    Mode::Slide(_) => Mode::Stick,
                    m => m,
                },
                ..c.clone()
            })
            .collect();
        let o = &self.setup.options;
        let mut hint = Vec::new();
        accelerations(
            &self.setup.body,
            &self.setup.planes,
            &self.s,
            &o.gravity,
            &stuck,
            &mut hint,
            o.rest_speed,
        )
        .is_ok_and(|a| {
            a.active.iter().all(|&on| on)
                && a.a.norm() + a.alpha.norm() * self.setup.body.reach() <= still
        })
    }

    fn name(&self, f: usize, p: usize) -> String {
        format!(
            "{} on {}",
            self.setup.body.features[f].label(),
            self.setup.planes[p].name
        )
    }

    fn go(&mut self) -> Result<End, SimulateError> {
        let o = self.setup.options.clone();
        let mut next_output = 0.0;
        let end;
        loop {
            if self.t >= next_output {
                self.sample();
                next_output = next_output_after(self.t, o.output_step);
            }
            if self.t >= o.duration {
                end = End::Duration;
                break;
            }
            if self.impacts.len() >= o.max_impacts {
                end = End::Impacts;
                break;
            }
            if let Some(why) = self.stepper.stall(MAX_STEPS) {
                return Err(SimulateError::Stalled { t: self.t, why });
            }
            let acc = self.current()?;
            // Lift-off: a closed contact the accelerations no longer press.
            if acc.active.iter().any(|a| !a) {
                let mut kept = Vec::new();
                for (c, &on) in self.closed.clone().into_iter().zip(&acc.active) {
                    if on {
                        kept.push(c);
                    } else {
                        self.events.push(Event {
                            t: self.t,
                            what: format!("{} lifts off", self.name(c.feature, c.plane)),
                        });
                    }
                }
                self.closed = kept;
                self.hint.clear();
                continue;
            }
            // Slides that stop.
            for k in 0..self.closed.len() {
                if let Mode::Slide(_) = self.closed[k].mode {
                    let c = self.closed[k].clone();
                    let plane = &self.setup.planes[c.plane];
                    let g = gap(&self.setup.body.features[c.feature], plane, &self.s);
                    let u = self.s.v + self.s.w.cross(&(g.point - self.s.x));
                    let slip = u - plane.normal * plane.normal.dot(&u);
                    // it sticks if its slip has stopped and sticking needs no more than its
                    // cone allows (else it slides on: no chatter between the two)
                    if slip.norm() > 2.0 * o.rest_speed {
                        self.closed[k].armed = true;
                    }
                    if slip.norm() <= o.rest_speed && c.armed {
                        let held = self.closed[k].mode;
                        self.closed[k].mode = Mode::Stick;
                        let s = self.s.clone();
                        let mut hint = Vec::new();
                        let sticks = !matches!(
                            accelerations(
                                &self.setup.body,
                                &self.setup.planes,
                                &s,
                                &o.gravity,
                                &self.closed,
                                &mut hint,
                                o.rest_speed,
                            ),
                            Err(ContactError::Slips { contact, .. }) if contact == k
                        );
                        if sticks {
                            let name = self.name(c.feature, c.plane);
                            self.events.push(Event {
                                t: self.t,
                                what: format!("{name} sticks"),
                            });
                        } else {
                            self.closed[k].mode = held;
                        }
                    }
                }
            }
            let speed = self.s.v.norm() + self.s.w.norm() * self.setup.body.reach();
            let accel = acc.a.norm() + acc.alpha.norm() * self.setup.body.reach();
            let still = 1e-9 * (o.gravity.norm() + f64::MIN_POSITIVE);
            if !self.closed.is_empty()
                && speed <= o.rest_speed
                && (accel <= still || self.holds_when_stuck(still))
            {
                end = End::Rest;
                break;
            }
            // The open gaps: impacts, contacts closing, and the horizon of the step.
            let mut horizon = f64::INFINITY;
            let mut striking = false;
            let pairs: Vec<(usize, usize)> = pairs(self.setup).collect();
            for &(f, p) in &pairs {
                if self.is_closed(f, p) {
                    continue;
                }
                let g = gap(&self.setup.body.features[f], &self.setup.planes[p], &self.s);
                if g.gap <= self.gap_tol {
                    if g.rate < -o.rest_speed {
                        striking = true;
                    } else if g.rate <= o.rest_speed
                        && !self.face_carries(
                            f,
                            p,
                            &self
                                .closed
                                .iter()
                                .map(|c| (c.feature, c.plane))
                                .collect::<Vec<_>>(),
                        )
                        && !self.closed.iter().any(|c| {
                            c.plane == p
                                && self.same_point(
                                    &gap(
                                        &self.setup.body.features[c.feature],
                                        &self.setup.planes[p],
                                        &self.s,
                                    )
                                    .point,
                                    &g.point,
                                )
                        })
                        && self.presses(f, p)
                    {
                        self.closed.push(Closed {
                            feature: f,
                            plane: p,
                            mode: self.mode_of(f, p),
                            armed: true,
                        });
                        self.hint.clear();
                        self.events.push(Event {
                            t: self.t,
                            what: format!("{} closes", self.name(f, p)),
                        });
                    }
                    continue;
                }
                let m = 2.0 * (acc.a.norm() + g.arm * (self.s.w.norm_squared() + acc.alpha.norm()))
                    + f64::MIN_POSITIVE;
                horizon = horizon.min(stepper::horizon(g.gap, g.rate, m));
            }
            if striking {
                self.impact()?;
                self.stepper.h = self.stepper.h.max(1e-6 * o.output_step);
                continue;
            }
            // One step.
            let y = self.s.pack();
            let t0 = self.t;
            let scales = [
                self.length,
                self.length,
                self.length,
                1.0,
                1.0,
                1.0,
                1.0,
                self.speed,
                self.speed,
                self.speed,
                self.speed / self.length,
                self.speed / self.length,
                self.speed / self.length,
            ];
            let mut stepper = std::mem::replace(&mut self.stepper, Stepper::new(1.0, 1.0));
            let open: Vec<(usize, usize, f64)> = pairs
                .iter()
                .copied()
                .filter(|&(f, p)| !self.is_closed(f, p))
                .map(|(f, p)| {
                    let g = gap(&self.setup.body.features[f], &self.setup.planes[p], &self.s);
                    (f, p, g.gap)
                })
                .collect();
            let (setup, gap_tol) = (self.setup, self.gap_tol);
            let advance = {
                let mut f = |_t: f64, y: &[f64]| -> Result<Vec<f64>, ContactError> {
                    let s = unpack(y);
                    let a = self.accelerations(&s)?;
                    Ok(derivative(&s, &a).to_vec())
                };
                // No open feature may end the step beyond its plane: a touching one that the
                // step took through is located by halving the step.
                let crosses = |y: &[f64]| {
                    let end = unpack(y);
                    open.iter().any(|&(f, p, start)| {
                        let g = gap(&setup.body.features[f], &setup.planes[p], &end).gap;
                        stepper::crossed(start, g, gap_tol)
                    })
                };
                stepper.advance(
                    t0,
                    &y,
                    horizon,
                    o.duration,
                    o.output_step,
                    o.tolerance,
                    &scales,
                    &mut f,
                    crosses,
                )
            };
            self.stepper = stepper;
            let (t1, y5, dense) = match advance {
                Advance::Accepted { t, y, dense } => (t, y, dense),
                Advance::Retry => continue,
                Advance::NotFinite => return Err(SimulateError::NotFinite { t: self.t }),
                Advance::Failed(error) => {
                    // A mode change inside a step at the resolution of t: a sticking contact
                    // that must slip is switched.
                    if let ContactError::Slips { contact, direction } = error {
                        self.closed[contact].mode = Mode::Slide(direction);
                        self.closed[contact].armed = false;
                        let c = &self.closed[contact];
                        let name = self.name(c.feature, c.plane);
                        self.events.push(Event {
                            t: self.t,
                            what: format!("{name} starts to slide"),
                        });
                        self.stepper.h = floor(self.t, o.output_step) * 16.0;
                        continue;
                    }
                    return Err(SimulateError::Stalled {
                        t: self.t,
                        why: Stall::Resolution,
                    });
                }
            };
            // The output times inside the step, from its continuous extension.
            while next_output < t1 {
                let s = unpack(&dense.at(next_output));
                self.sample_at(next_output, s);
                next_output = next_output_after(next_output, o.output_step);
            }
            self.t = t1;
            self.s = unpack(&y5);
            if !self.closed.is_empty() {
                let active = vec![true; self.closed.len()];
                let d = project(
                    &self.setup.body,
                    &self.setup.planes,
                    &mut self.s,
                    &self.closed,
                    &active,
                );
                self.drift = self.drift.max(d);
            }
            self.hold_plane();
        }
        Ok(end)
    }

    /// A planar motion held in its plane: C on it, v in it, ω along its normal, the attitude
    /// the twist of q about the normal (its swing, rounding, dropped).
    fn hold_plane(&mut self) {
        let Some(n) = self.setup.plane else {
            return;
        };
        let x0 = self.setup.start.x;
        self.s.x -= n * n.dot(&(self.s.x - x0));
        self.s.v -= n * n.dot(&self.s.v);
        self.s.w = n * n.dot(&self.s.w);
        let q0 = self.setup.start.q;
        // the rotation from the start's attitude, reduced to its twist about n
        let d = self.s.q * q0.inverse();
        let qd = d.quaternion();
        let along = n * n.dot(&qd.imag());
        let twist = nalgebra::Quaternion::new(qd.w, along.x, along.y, along.z);
        if twist.norm() > 0.0 {
            self.s.q = nalgebra::UnitQuaternion::from_quaternion(twist) * q0;
        }
    }

    /// A contact's mode when it closes: sticking where μ > 0.
    /// Whether feature `f` is a rim whose face on plane `p` is carried by three or more of its
    /// body points among `contacts` (feature, plane).
    fn face_carries(&self, f: usize, p: usize, contacts: &[(usize, usize)]) -> bool {
        let features = &self.setup.body.features;
        let super::body::Feature::Rim { label, .. } = &features[f] else {
            return false;
        };
        let prefix = format!("{label} at ");
        contacts
            .iter()
            .filter(|&&(g, q)| q == p && features[g].label().starts_with(&prefix))
            .count()
            >= 3
    }

    /// Whether two contact points are one: within 10⁻⁶ of the length scale (a rim's nearest
    /// point passing one of its body points, or lying on it by symmetry).
    fn same_point(&self, a: &V3, b: &V3) -> bool {
        (a - b).norm() <= 1e-6 * self.length
    }

    /// The mode a contact (f, p) closes in at the current state: frictionless where μ = 0;
    /// else sliding along its slip when the slip is faster than `rest_speed`, sticking when not
    /// (a contact that closed sticking with a slip would have it cancelled by the velocity
    /// projection of the closed contacts: an impulse no cone bounds).
    fn mode_of(&self, f: usize, p: usize) -> Mode {
        let plane = &self.setup.planes[p];
        if plane.law.mu <= 0.0 {
            return Mode::Frictionless;
        }
        let g = gap(&self.setup.body.features[f], plane, &self.s);
        let u = self.s.v + self.s.w.cross(&(g.point - self.s.x));
        let slip = u - plane.normal * plane.normal.dot(&u);
        if slip.norm() > self.setup.options.rest_speed {
            Mode::Slide(slip.normalize())
        } else {
            Mode::Stick
        }
    }

    /// Whether the accelerations press the open contact (f, p) at zero gap: with it closed,
    /// it takes a positive normal force.
    fn presses(&mut self, f: usize, p: usize) -> bool {
        let mut closed = self.closed.clone();
        closed.push(Closed {
            feature: f,
            plane: p,
            mode: self.mode_of(f, p),
            armed: true,
        });
        let o = &self.setup.options;
        let mut hint = Vec::new();
        match accelerations(
            &self.setup.body,
            &self.setup.planes,
            &self.s,
            &o.gravity,
            &closed,
            &mut hint,
            o.rest_speed,
        ) {
            Ok(a) => {
                a.active.last().copied().unwrap_or(false)
                    && a.normal.last().is_some_and(|&l| l > 0.0)
            }
            Err(ContactError::Slips { .. }) => true,
            Err(_) => false,
        }
    }

    /// The impact at the current state.
    fn impact(&mut self) -> Result<(), SimulateError> {
        let o = self.setup.options.clone();
        let body = &self.setup.body;
        let planes = &self.setup.planes;
        let mut at: Vec<At> = Vec::new();
        let mut struck: Vec<Struck> = Vec::new();
        let mut spread = 0.0f64;
        // (a rim's body points come before it in the features: one it is nearest at is the
        // contact, and a landing face is its four points)
        for (f, p) in pairs(self.setup) {
            let g = gap(&body.features[f], &planes[p], &self.s);
            let persisting = self.is_closed(f, p);
            if !joins(persisting, g.gap, g.rate, self.gap_tol, o.simultaneity) {
                continue;
            }
            // a feature at another's contact point (a rim's body point where the rim is
            // nearest) is that contact, not a second one
            if at
                .iter()
                .any(|a| a.plane == p && self.same_point(&a.point, &g.point))
            {
                continue;
            }
            if !persisting && g.gap > self.gap_tol {
                spread = spread.max(g.gap / -g.rate);
            }
            at.push(At {
                feature: f,
                plane: p,
                point: g.point,
            });
            struck.push(Struck {
                feature: body.features[f].label().to_string(),
                plane: planes[p].name.clone(),
                gap: g.gap.max(0.0),
                before: g.rate,
                after: 0.0,
                impulse: 0.0,
                persisting,
            });
        }
        // a rim whose face lands (three or more of its body points in the impact) is carried
        // by them: its own nearest point, anywhere on the circle, would be a fourth, redundant
        // and nearly coincident contact
        let keep: Vec<bool> = at
            .iter()
            .map(|a| {
                !self.face_carries(
                    a.feature,
                    a.plane,
                    &at.iter().map(|b| (b.feature, b.plane)).collect::<Vec<_>>(),
                )
            })
            .collect();
        let mut k = 0;
        at.retain(|_| {
            k += 1;
            keep[k - 1]
        });
        let mut k = 0;
        struck.retain(|_| {
            k += 1;
            keep[k - 1]
        });
        let index = self.impacts.len() + 1;
        let kinetic_before = body.kinetic_energy(&self.s);
        let out =
            solve(body, planes, &self.s, &at, self.setup.law, o.tolerance).map_err(|error| {
                SimulateError::Impact {
                    index,
                    t: self.t,
                    contacts: struck
                        .iter()
                        .map(|c| format!("{} on {}", c.feature, c.plane))
                        .collect::<Vec<_>>()
                        .join(", "),
                    error,
                }
            })?;
        let w_before = self.s.w;
        let v_before = self.s.v;
        self.s.v = out.v;
        self.s.w = out.w;
        self.hold_plane();
        if !(self
            .s
            .v
            .iter()
            .chain(self.s.w.iter())
            .all(|x| x.is_finite()))
        {
            return Err(SimulateError::NotFinite { t: self.t });
        }
        // What stays closed.
        self.closed.clear();
        self.hint.clear();
        for (k, a) in at.iter().enumerate() {
            let g = gap(&body.features[a.feature], &planes[a.plane], &self.s);
            struck[k].after = g.rate;
            struck[k].impulse = out.impulses[k];
            if g.gap <= self.gap_tol && g.rate <= o.rest_speed {
                let u = self.s.v + self.s.w.cross(&(g.point - self.s.x));
                let n = planes[a.plane].normal;
                let slip = u - n * n.dot(&u);
                let mode = if planes[a.plane].law.mu == 0.0 {
                    Mode::Frictionless
                } else if slip.norm() <= o.rest_speed {
                    Mode::Stick
                } else {
                    Mode::Slide(slip.normalize())
                };
                self.closed.push(Closed {
                    feature: a.feature,
                    plane: a.plane,
                    mode,
                    armed: true,
                });
            }
        }
        self.impacts.push(ImpactRecord {
            index,
            t: self.t,
            contacts: struck,
            spread,
            kinetic_before,
            kinetic_after: body.kinetic_energy(&self.s),
            verdicts: out.verdicts,
            note: out.note,
        });
        self.zeno(w_before, v_before);
        Ok(())
    }

    /// The accumulation of impacts of a bouncing body (module docs).
    fn zeno(&mut self, w_before: V3, v_before: V3) {
        let n = self.impacts.len();
        if n < 3 || self.zeno.is_some() {
            return;
        }
        let last = &self.impacts[n - 3..];
        let struck = |r: &ImpactRecord| -> Vec<(String, String, bool)> {
            r.contacts
                .iter()
                .map(|c| (c.feature.clone(), c.plane.clone(), c.persisting))
                .collect()
        };
        let contacts = &last[2].contacts;
        let same = !contacts.is_empty()
            && last.iter().all(|r| struck(r) == struck(&last[2]))
            && contacts
                .iter()
                .all(|c| !c.persisting && c.plane == contacts[0].plane);
        let turning = self.s.w.norm() * self.setup.body.reach() > 1e-12 * self.speed
            || w_before.norm() * self.setup.body.reach() > 1e-12 * self.speed;
        let Some(p) = self
            .setup
            .planes
            .iter()
            .position(|p| p.name == contacts[0].plane)
        else {
            return;
        };
        let features: Vec<usize> = contacts
            .iter()
            .filter_map(|c| {
                self.setup
                    .body
                    .features
                    .iter()
                    .position(|f| f.label() == c.feature)
            })
            .collect();
        if !same || features.len() != contacts.len() {
            return;
        }
        // a sphere on a frictionless plane: its spin changes neither its gap nor its impacts
        let spin_free = matches!(
            self.setup.body.features[features[0]],
            super::body::Feature::Sphere { .. }
        ) && self.setup.planes[p].law.mu == 0.0;
        let turning = turning && !spin_free;
        let nn = self.setup.planes[p].normal;
        let dv = (self.s.v - v_before) - nn * nn.dot(&(self.s.v - v_before));
        let gn = -nn.dot(&self.setup.options.gravity);
        if turning || dv.norm() > 1e-12 * self.speed || gn <= 0.0 {
            return;
        }
        // every point of a body that does not turn rebounds at its centre's speed
        let u: Vec<f64> = last
            .iter()
            .map(|r| {
                r.contacts
                    .iter()
                    .map(|c| c.after)
                    .fold(f64::NEG_INFINITY, f64::max)
            })
            .collect();
        let (r1, r2) = (u[1] / u[0], u[2] / u[1]);
        // a ratio within 10⁻⁹ of 1 is an elastic bounce (rounding), not an accumulation
        if !(r2 > 0.0 && r2 < 1.0 - 1e-9 && (r1 - r2).abs() <= 1e-9 * r2) {
            return;
        }
        let dt = 2.0 * u[2] / (gn * (1.0 - r2));
        if self.t + dt > self.setup.options.duration {
            return;
        }
        let g = self.setup.options.gravity;
        let energy =
            |s: &State| self.setup.body.kinetic_energy(s) - self.setup.body.mass * g.dot(&s.x);
        let before = energy(&self.s);
        let gt = g + nn * gn;
        let vt = self.s.v - nn * nn.dot(&self.s.v);
        self.s.x += vt * dt + gt * (0.5 * dt * dt);
        // a spinning sphere turns steadily meanwhile (no torque about its centre)
        self.s.q = nalgebra::UnitQuaternion::from_scaled_axis(self.s.w * dt) * self.s.q;
        self.s.v = vt + gt * dt;
        self.t += dt;
        let lowest = features
            .iter()
            .map(|&f| gap(&self.setup.body.features[f], &self.setup.planes[p], &self.s).gap)
            .fold(f64::INFINITY, f64::min);
        self.s.x -= nn * lowest;
        self.closed = features
            .iter()
            .map(|&f| Closed {
                feature: f,
                plane: p,
                mode: self.mode_of(f, p),
                armed: true,
            })
            .collect();
        self.hint.clear();
        let dissipated = before - energy(&self.s);
        self.zeno = Some(Zeno {
            t_inf: self.t,
            after: n,
            ratio: r2,
            dissipated,
        });
        let names: Vec<String> = features.iter().map(|&f| self.name(f, p)).collect();
        self.events.push(Event {
            t: self.t,
            what: format!(
                "Zeno: the impacts accumulate here (rebound ratio {r2:.6}, after impact {n}), dissipating {dissipated:.6e} J; {} persist{}",
                names.join(", "),
                if names.len() == 1 { "s" } else { "" }
            ),
        });
    }
}

/// Whether a contact of gap `gap` and rate `rate` joins an impact (module docs): a closed one
/// always; an open one approaching within the gap tolerance, or within `simultaneity` in time.
pub(super) fn joins(
    persisting: bool,
    gap: f64,
    rate: f64,
    gap_tol: f64,
    simultaneity: f64,
) -> bool {
    persisting || (rate < 0.0 && (gap <= gap_tol || gap / -rate <= simultaneity))
}

/// The first output time k·Δ after t (the grid resumes after a jump in time, such as the
/// accumulation of a Zeno sequence).
pub(super) fn next_output_after(t: f64, output_step: f64) -> f64 {
    let mut k = (t / output_step).floor();
    while k * output_step <= t {
        k += 1.0;
    }
    k * output_step
}

/// The packed state y as a state.
fn unpack(y: &[f64]) -> State {
    let y: [f64; 13] = std::array::from_fn(|k| y[k]);
    State::unpack(&y)
}

/// Every (feature, plane) pair.
fn pairs(setup: &Setup) -> impl Iterator<Item = (usize, usize)> + '_ {
    let planes = setup.planes.len();
    (0..setup.body.features.len()).flat_map(move |f| (0..planes).map(move |p| (f, p)))
}
