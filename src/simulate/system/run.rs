//! The event loop of a sphere system: the single body's ([`crate::simulate::run`]: its
//! integrator, conservative advancement, impact rule and log), over several spheres and the
//! contacts between them.
//!
//! **Integration.** The packed state (x_b, v_b) is stepped by Dormand–Prince RK5(4)
//! ([`crate::simulate::stepper`], shared with the single body's loop, its samples read from
//! each step's continuous extension) with the accelerations of
//! [`super::persist::accelerations`]; the steps are held to the relative `tolerance` on the
//! scales of the motion (the largest radius or gap for positions, the speed scale for
//! velocities). Ballistic flight is a quadratic in t, which the fifth-order step reproduces to
//! rounding. Closed contacts are projected back onto their constraints after every step
//! ([`super::persist::project`]); the largest gap so corrected is reported as the drift.
//!
//! **Events.** No step may cross an open gap: with M a bound on |g̈| over the step (twice
//! |a_b| for a sphere on a plane; twice |a_a| + |a_b| + |u|²/|d| for a pair), each step is
//! capped at the horizon of [`crate::simulate::stepper::horizon`]. A gap within the gap tolerance (10⁻¹¹ of the length scale) approaching faster than
//! `rest_speed` is an impact; one slower closes unless the acceleration-level problem with it
//! closed separates it (g̈ > 0); a closed contact opens when g̈ > 0 ([`super::persist`]).
//!
//! **Impacts.** Every open contact approaching within the gap tolerance or within
//! `simultaneity` in time, and every closed contact, strike together: one multiple impact,
//! solved by the law over the whole system ([`super::impact`]). After it a contact at zero gap
//! whose normal rate is below `rest_speed` stays closed.
//!
//! Not here yet: friction between spheres, the closed-form accumulation (Zeno) of the single
//! body (a system runs to its impact budget instead), bodies other than spheres.

use super::super::body::V3;
use super::super::contact::ContactError;
use super::super::impact::Law;
use super::super::run::{
    End, Event, ImpactRecord, MAX_STEPS, Options, SimulateError, Struck, joins, next_output_after,
};
use super::super::stepper::{self, Advance, Stall, Stepper};
use super::super::world::Plane;
use super::gaps::{Candidate, Touch, gap};
use super::impact::solve;
use super::persist::{Accelerations, accelerations, project};
use super::spheres::{Sphere, SystemState};

/// What to simulate.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemSetup {
    /// The spheres.
    pub spheres: Vec<Sphere>,
    /// The obstacles.
    pub planes: Vec<Plane>,
    /// Every contact watched (every sphere on every plane, every pair of spheres), with its law.
    pub candidates: Vec<Candidate>,
    /// The impact law.
    pub law: Law,
    /// The state at t = 0.
    pub start: SystemState,
    /// The options.
    pub options: Options,
}

impl SystemSetup {
    /// Every sphere on every plane, then every pair (a < b), each with the law `law_of` gives.
    pub fn candidates(
        spheres: usize,
        planes: usize,
        mut law_of: impl FnMut(&Touch) -> super::super::world::ContactLaw,
    ) -> Vec<Candidate> {
        let mut out = Vec::new();
        for body in 0..spheres {
            for plane in 0..planes {
                let touch = Touch::Plane { body, plane };
                out.push(Candidate {
                    law: law_of(&touch),
                    touch,
                });
            }
        }
        for a in 0..spheres {
            for b in a + 1..spheres {
                let touch = Touch::Pair { a, b };
                out.push(Candidate {
                    law: law_of(&touch),
                    touch,
                });
            }
        }
        out
    }
}

/// A sample of the trajectory.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemSample {
    /// t (s).
    pub t: f64,
    /// The state.
    pub state: SystemState,
    /// Kinetic energy (J).
    pub kinetic: f64,
    /// Potential energy −Σ m g·x (J).
    pub potential: f64,
    /// The number of closed contacts.
    pub closed: usize,
}

/// A whole run.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemSimulation {
    /// The impacts (a contact between two spheres: `feature` the first, `plane` the second).
    pub impacts: Vec<ImpactRecord>,
    /// The other events: contacts closing and opening.
    pub events: Vec<Event>,
    /// The trajectory, every `output_step`, with the state before and after every impact.
    pub samples: Vec<SystemSample>,
    /// Why it ended.
    pub end: End,
    /// When (s).
    pub t_end: f64,
    /// The state then.
    pub state: SystemState,
    /// Accepted and rejected steps.
    pub steps: (usize, usize),
    /// The largest gap the projection of closed contacts corrected (m).
    pub drift: f64,
    /// Why the run stopped early ([`End::Stopped`]).
    pub stopped: Option<SimulateError>,
}

/// Run `setup` to its end, or to the error that stops it ([`End::Stopped`]), keeping the
/// history up to there.
pub fn simulate_system(setup: &SystemSetup) -> SystemSimulation {
    let mut run = Run::new(setup);
    let (end, stopped) = match run.go().and_then(|end| run.finite(end)) {
        Ok(end) => (end, None),
        Err(e) => (End::Stopped, Some(e)),
    };
    SystemSimulation {
        impacts: run.impacts,
        events: run.events,
        samples: run.samples,
        end,
        t_end: run.t,
        state: run.s,
        steps: run.stepper.steps,
        drift: run.drift,
        stopped,
    }
}

struct Run<'a> {
    setup: &'a SystemSetup,
    stepper: Stepper,
    s: SystemState,
    t: f64,
    closed: Vec<usize>,
    impacts: Vec<ImpactRecord>,
    events: Vec<Event>,
    samples: Vec<SystemSample>,
    length: f64,
    speed: f64,
    gap_tol: f64,
    drift: f64,
}

impl<'a> Run<'a> {
    fn new(setup: &'a SystemSetup) -> Run<'a> {
        let s = setup.start.clone();
        let reach = setup.spheres.iter().map(|b| b.radius).fold(0.0, f64::max);
        let length = setup
            .candidates
            .iter()
            .map(|c| gap(&c.touch, &setup.spheres, &setup.planes, &s).gap.abs())
            .fold(reach, f64::max)
            .max(f64::MIN_POSITIVE);
        let g = setup.options.gravity.norm();
        let fastest = s.v.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let speed = fastest
            .max((2.0 * g * length).sqrt())
            .max(f64::MIN_POSITIVE);
        Run {
            setup,
            stepper: Stepper::new(setup.options.output_step, setup.options.duration),
            s,
            t: 0.0,
            closed: Vec::new(),
            impacts: Vec::new(),
            events: Vec::new(),
            samples: Vec::new(),
            length,
            speed,
            gap_tol: 1e-11 * length,
            drift: 0.0,
        }
    }

    /// `end`, when every energy of the run and the state it ends in are finite numbers; a run
    /// whose scales overflow f64 stops instead of printing one (as the single body's).
    fn finite(&self, end: End) -> Result<End, SimulateError> {
        let st = &self.setup;
        let finite = self
            .samples
            .iter()
            .all(|s| s.kinetic.is_finite() && s.potential.is_finite())
            && (self.s.kinetic_energy(&st.spheres)
                + self.s.potential_energy(&st.spheres, &st.options.gravity))
            .is_finite()
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
    fn sample_at(&mut self, t: f64, s: SystemState) {
        let st = &self.setup;
        self.samples.push(SystemSample {
            t,
            kinetic: s.kinetic_energy(&st.spheres),
            potential: s.potential_energy(&st.spheres, &st.options.gravity),
            state: s,
            closed: self.closed.len(),
        });
    }

    fn accelerations_at(
        &self,
        s: &SystemState,
        closed: &[usize],
    ) -> Result<Accelerations, ContactError> {
        let st = &self.setup;
        accelerations(
            &st.spheres,
            &st.planes,
            &st.candidates,
            closed,
            s,
            &st.options.gravity,
        )
    }

    fn name(&self, k: usize) -> String {
        let (a, b) = self.setup.candidates[k]
            .touch
            .name(&self.setup.spheres, &self.setup.planes);
        format!("{a} on {b}")
    }

    fn gap(&self, k: usize, s: &SystemState) -> super::gaps::Gap {
        gap(
            &self.setup.candidates[k].touch,
            &self.setup.spheres,
            &self.setup.planes,
            s,
        )
    }

    fn go(&mut self) -> Result<End, SimulateError> {
        let o = self.setup.options.clone();
        let mut next_output = 0.0;
        loop {
            if self.t >= next_output {
                self.sample();
                next_output = next_output_after(self.t, o.output_step);
            }
            if self.t >= o.duration {
                return Ok(End::Duration);
            }
            if self.impacts.len() >= o.max_impacts {
                return Ok(End::Impacts);
            }
            if let Some(why) = self.stepper.stall(MAX_STEPS) {
                return Err(SimulateError::Stalled { t: self.t, why });
            }
            let s = self.s.clone();
            let acc = self
                .accelerations_at(&s, &self.closed)
                .map_err(|error| SimulateError::Contact { t: self.t, error })?;
            let tol = 1e-9 * acc.scale.max(f64::MIN_POSITIVE);
            // Lift-off: a closed contact the accelerations open.
            let opening: Vec<usize> = (0..self.closed.len())
                .filter(|&p| acc.gap_acceleration[p] > tol)
                .collect();
            if !opening.is_empty() {
                for &p in opening.iter().rev() {
                    let k = self.closed.remove(p);
                    self.events.push(Event {
                        t: self.t,
                        what: format!("{} lifts off", self.name(k)),
                    });
                }
                continue;
            }
            let fastest = self.s.v.iter().map(|v| v.norm()).fold(0.0, f64::max);
            let accel = acc.a.iter().map(|a| a.norm()).fold(0.0, f64::max);
            if !self.closed.is_empty()
                && fastest <= o.rest_speed
                && accel <= 1e-9 * (o.gravity.norm() + f64::MIN_POSITIVE)
            {
                return Ok(End::Rest);
            }
            // The open gaps: impacts, contacts closing, and the horizon of the step.
            let mut horizon = f64::INFINITY;
            let mut striking = false;
            let mut closing = false;
            for k in 0..self.setup.candidates.len() {
                if self.closed.contains(&k) {
                    continue;
                }
                let g = self.gap(k, &self.s);
                if g.gap <= self.gap_tol {
                    if g.rate < -o.rest_speed {
                        striking = true;
                        continue;
                    } else if g.rate <= o.rest_speed {
                        let mut trial = self.closed.clone();
                        trial.push(k);
                        let keeps = self
                            .accelerations_at(&self.s, &trial)
                            .map(|a| a.gap_acceleration[trial.len() - 1] <= 1e-9 * a.scale)
                            .unwrap_or(false);
                        if keeps {
                            self.closed.push(k);
                            self.events.push(Event {
                                t: self.t,
                                what: format!("{} closes", self.name(k)),
                            });
                            closing = true;
                            continue;
                        }
                    }
                }
                let bound = match self.setup.candidates[k].touch {
                    Touch::Plane { body, .. } => 2.0 * acc.a[body].norm(),
                    Touch::Pair { a, b } => 2.0 * (acc.a[a].norm() + acc.a[b].norm()) + g.curvature,
                };
                horizon = horizon.min(stepper::horizon(g.gap, g.rate, bound));
            }
            if closing {
                continue;
            }
            if striking {
                self.impact()?;
                self.stepper.h = self.stepper.h.max(1e-6 * o.output_step);
                continue;
            }
            // One step.
            let y = self.s.pack();
            let t0 = self.t;
            let half = y.len() / 2;
            let scales: Vec<f64> = (0..y.len())
                .map(|k| if k < half { self.length } else { self.speed })
                .collect();
            let closed = self.closed.clone();
            let open: Vec<(usize, f64)> = (0..self.setup.candidates.len())
                .filter(|k| !self.closed.contains(k))
                .map(|k| (k, self.gap(k, &self.s).gap))
                .collect();
            let mut stepper = std::mem::replace(&mut self.stepper, Stepper::new(1.0, 1.0));
            let advance = {
                let mut f = |_t: f64, y: &[f64]| -> Result<Vec<f64>, ContactError> {
                    let s = SystemState::unpack(y);
                    let a = self.accelerations_at(&s, &closed)?;
                    Ok(s.v
                        .iter()
                        .chain(&a.a)
                        .flat_map(|p| [p.x, p.y, p.z])
                        .collect())
                };
                // No open contact may end the step through its gap: one the step took through
                // is located by halving the step.
                let crosses = |y: &[f64]| {
                    let end = SystemState::unpack(y);
                    open.iter().any(|&(k, start)| {
                        stepper::crossed(start, self.gap(k, &end).gap, self.gap_tol)
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
                Advance::Failed(_) => {
                    return Err(SimulateError::Stalled {
                        t: self.t,
                        why: Stall::Resolution,
                    });
                }
            };
            // The output times inside the step, from its continuous extension.
            while next_output < t1 {
                let s = SystemState::unpack(&dense.at(next_output));
                self.sample_at(next_output, s);
                next_output = next_output_after(next_output, o.output_step);
            }
            self.t = t1;
            self.s = SystemState::unpack(&y5);
            let st = self.setup;
            let d = project(
                &st.spheres,
                &st.planes,
                &st.candidates,
                &self.closed,
                &mut self.s,
            );
            self.drift = self.drift.max(d);
        }
    }

    /// The impact at the current state: the samples before and after it are kept (as Siconos'
    /// event rows).
    fn impact(&mut self) -> Result<(), SimulateError> {
        let o = self.setup.options.clone();
        let st = self.setup;
        let mut at: Vec<usize> = Vec::new();
        let mut struck: Vec<Struck> = Vec::new();
        let mut spread = 0.0f64;
        for k in 0..st.candidates.len() {
            let g = self.gap(k, &self.s);
            let persisting = self.closed.contains(&k);
            if !joins(persisting, g.gap, g.rate, self.gap_tol, o.simultaneity) {
                continue;
            }
            if !persisting && g.gap > self.gap_tol {
                spread = spread.max(g.gap / -g.rate);
            }
            let (first, second) = st.candidates[k].touch.name(&st.spheres, &st.planes);
            at.push(k);
            struck.push(Struck {
                feature: first,
                plane: second,
                gap: g.gap.max(0.0),
                before: g.rate,
                after: 0.0,
                impulse: 0.0,
                persisting,
            });
        }
        let index = self.impacts.len() + 1;
        let kinetic_before = self.s.kinetic_energy(&st.spheres);
        self.sample();
        let out = solve(
            &st.spheres,
            &st.planes,
            &st.candidates,
            &at,
            &self.s,
            st.law,
            o.tolerance,
        )
        .map_err(|error| SimulateError::Impact {
            index,
            t: self.t,
            contacts: struck
                .iter()
                .map(|c| format!("{} on {}", c.feature, c.plane))
                .collect::<Vec<_>>()
                .join(", "),
            error,
        })?;
        if !out.v.iter().all(|v| v.iter().all(|x| x.is_finite())) {
            return Err(SimulateError::NotFinite { t: self.t });
        }
        self.s.v = out.v;
        self.closed.clear();
        for (p, &k) in at.iter().enumerate() {
            let g = self.gap(k, &self.s);
            struck[p].after = g.rate;
            struck[p].impulse = out.impulses[p];
            if g.gap <= self.gap_tol && g.rate <= o.rest_speed {
                self.closed.push(k);
            }
        }
        self.impacts.push(ImpactRecord {
            index,
            t: self.t,
            contacts: struck,
            spread,
            kinetic_before,
            kinetic_after: self.s.kinetic_energy(&st.spheres),
            verdicts: out.verdicts,
            note: None,
        });
        self.sample();
        Ok(())
    }
}

/// The velocity of every sphere after the first impact of `sim`, if there was one (the
/// sample that follows it).
pub fn after_first_impact(sim: &SystemSimulation) -> Option<&[V3]> {
    let t = sim.impacts.first()?.t;
    sim.samples
        .iter()
        .filter(|s| s.t == t)
        .nth(1)
        .map(|s| s.state.v.as_slice())
}
