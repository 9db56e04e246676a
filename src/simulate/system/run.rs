//! The event loop of a system: the single body's ([`crate::simulate::run`]: its integrator,
//! conservative advancement, impact rule and log), over several members and the contacts
//! between them.
//!
//! **Integration.** The packed state (x_b, v_b, q_b, ω_b) is stepped by Dormand–Prince
//! RK5(4) ([`crate::simulate::stepper`], shared with the single body's loop, its samples read
//! from each step's continuous extension) with the accelerations of
//! [`super::persist::accelerations`] (Euler's equations, with the gyroscopic term, for a
//! member that turns); the steps are held to the relative `tolerance` on the scales of the
//! motion (the largest reach or gap for positions, the speed scale for velocities, 1 for the
//! quaternions' components, the speed scale over the member's reach for ω). Ballistic flight
//! is a quadratic in t, which the fifth-order step reproduces to rounding. Joints and closed
//! contacts are projected back onto their constraints after every step
//! ([`super::persist::project`], [`super::joints::hold`]); the largest gap or joint offset so
//! corrected is reported as the drift.
//!
//! **Events.** No step may cross an open gap: with M a bound on |g̈| over the step (twice
//! |a_b| for a sphere on a plane; twice |a_a| + |a_b| + |u|²/|d| for a pair; otherwise twice
//! |a| + ρ (|ω|² + |α|) of each side plus twice the curvature term), each step is capped at
//! the horizon of [`crate::simulate::stepper::horizon`]. A gap within the gap tolerance (10⁻¹¹
//! of the length scale) approaching faster than `rest_speed` is an impact; one slower closes
//! unless the acceleration-level problem with it closed separates it (g̈ > 0), and then caps
//! no step (it separates; the step's crossing check still holds it); a closed
//! contact opens when g̈ > 0 ([`super::persist`]), or when its point reaches its face's edge
//! moving out (located by halving the step, as a crossing of how far inside the edges it is).
//! After every step the members are checked for an overlap ([`super::overlap`]): the run stops
//! there, naming them.
//!
//! **Impacts.** Every open contact approaching within the gap tolerance or within
//! `simultaneity` in time, and every closed contact, strike together: one multiple impact,
//! solved by the law over the whole system ([`super::impact`]). After it a contact at zero gap
//! whose normal rate is below `rest_speed` stays closed.
//!
//! **Friction.** A rough closed contact sticks or slides, as the single body's: it closes
//! sliding along its slip when that is faster than `rest_speed`, sticking otherwise; a sticking
//! one whose force leaves its cone starts to slide ([`super::persist`]; inside a step, the step
//! is cut and the mode switched); sliding ones whose slip has fallen below `rest_speed` stick,
//! together where they can (the corners of a face), one by one otherwise, when sticking needs no
//! more than their cones. At rest: slower than `rest_speed`, and still with every slide stuck.
//!
//! An open contact that enters its region (an edge's closest point past a corner onto the next
//! edge, a corner past an edge onto a face) does so at the gap the contact it takes over from
//! held, within the projection's drift: it is taken as it comes, to the overlap tolerance
//! (10³ times the gap tolerance), and struck or closed there; a closed one that leaves it holds
//! nothing in the projection and lets go.
//!
//! **Zeno.** Where one member bounces on what stays put (a ball on a box resting on the floor,
//! a box dropped flat on another), three impacts in a constant ratio are summed in closed form
//! to their accumulation, as for the single body ([`super::zeno`]); elsewhere a system runs to
//! rest by its `rest_speed`, or to its impact budget.
//!
//! Not here yet: cylinders in a system.

use super::super::body::{Feature, Shape, V3, quaternion_rate};
use super::super::contact::{ContactError, Mode};
use super::super::impact::Law;
use super::super::run::{
    End, Event, ImpactRecord, MAX_STEPS, Options, SimulateError, Struck, Zeno, joins,
    next_output_after,
};
use super::super::stepper::{self, Advance, Stall, Stepper};
use super::super::world::Plane;
use super::gaps::{Candidate, Touch, edge_count, gap};
use super::impact::solve;
use super::joints::Link;
use super::members::{Member, SystemState};
use super::overlap::deepest;
use super::persist::{Accelerations, Held, accelerations, project, slip};
use super::zeno::{Bounce, Scene, accumulation};

/// What to simulate.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemSetup {
    /// The members.
    pub members: Vec<Member>,
    /// The obstacles.
    pub planes: Vec<Plane>,
    /// Every contact watched (every feature on every plane, every pair of spheres, every
    /// feature on every face of a box, every edge on every other member's edges, every sphere on
    /// every edge and corner), with its law.
    pub candidates: Vec<Candidate>,
    /// The joints (none: free members).
    pub joints: Vec<Link>,
    /// The impact law.
    pub law: Law,
    /// The state at t = 0.
    pub start: SystemState,
    /// The options.
    pub options: Options,
}

impl SystemSetup {
    /// Whether a joint holds members `a` and `b` together (no contact is watched between them).
    pub fn joined(&self, a: usize, b: usize) -> bool {
        self.joints.iter().any(|j| j.joins(a, b))
    }

    /// Every feature of every member on every plane, then every pair of spheres (a < b),
    /// then every feature of every member (but a rim) on every face of every box, then every
    /// edge of a member (a box's, a rod's segment) on every edge of another (a < b), then
    /// every sphere on every edge and every corner (a box's corner, a rod's end) of every
    /// member, each with the law `law_of` gives.
    pub fn candidates(
        members: &[Member],
        planes: usize,
        mut law_of: impl FnMut(&Touch) -> super::super::world::ContactLaw,
    ) -> Vec<Candidate> {
        let mut touches = Vec::new();
        for (body, m) in members.iter().enumerate() {
            for feature in 0..m.body.features.len() {
                for plane in 0..planes {
                    touches.push(Touch::Plane {
                        body,
                        feature,
                        plane,
                    });
                }
            }
        }
        for a in 0..members.len() {
            for b in a + 1..members.len() {
                if members[a].radius().is_some() && members[b].radius().is_some() {
                    touches.push(Touch::Pair { a, b });
                }
            }
        }
        for (b, box_b) in members.iter().enumerate() {
            if !matches!(box_b.body.shape, Shape::Box { .. }) {
                continue;
            }
            for (a, m) in members.iter().enumerate() {
                if a == b {
                    continue;
                }
                for (feature, f) in m.body.features.iter().enumerate() {
                    if matches!(f, Feature::Rim { .. }) {
                        continue;
                    }
                    for face in 0..6 {
                        touches.push(Touch::Face {
                            a,
                            feature,
                            b,
                            face,
                        });
                    }
                }
            }
        }
        let edges = |m: &Member| edge_count(&m.body.shape);
        for a in 0..members.len() {
            for b in a + 1..members.len() {
                for edge_a in 0..edges(&members[a]) {
                    for edge_b in 0..edges(&members[b]) {
                        touches.push(Touch::Edges {
                            a,
                            edge_a,
                            b,
                            edge_b,
                        });
                    }
                }
            }
        }
        for (a, sphere) in members.iter().enumerate() {
            if sphere.radius().is_none() {
                continue;
            }
            for (b, m) in members.iter().enumerate() {
                for edge in 0..edges(m) {
                    touches.push(Touch::OnEdge { a, b, edge });
                }
                if edges(m) == 0 {
                    continue;
                }
                for (feature, f) in m.body.features.iter().enumerate() {
                    if matches!(f, Feature::Point { .. }) {
                        touches.push(Touch::OnCorner { a, b, feature });
                    }
                }
            }
        }
        touches
            .into_iter()
            .map(|touch| Candidate {
                law: law_of(&touch),
                touch,
            })
            .collect()
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
    /// The accumulation of impacts, if one was taken ([`super::zeno`]).
    pub zeno: Option<Zeno>,
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
        zeno: run.zeno,
    }
}

struct Run<'a> {
    setup: &'a SystemSetup,
    stepper: Stepper,
    s: SystemState,
    t: f64,
    closed: Vec<Held>,
    impacts: Vec<ImpactRecord>,
    events: Vec<Event>,
    samples: Vec<SystemSample>,
    length: f64,
    speed: f64,
    gap_tol: f64,
    drift: f64,
    /// Each member's reach (m).
    reaches: Vec<f64>,
    /// What each impact left, for the accumulation ([`super::zeno`]).
    trail: Vec<Bounce>,
    zeno: Option<Zeno>,
}

impl<'a> Run<'a> {
    fn new(setup: &'a SystemSetup) -> Run<'a> {
        let s = setup.start.clone();
        let reaches: Vec<f64> = setup.members.iter().map(|m| m.body.reach()).collect();
        let reach = reaches.iter().copied().fold(0.0, f64::max);
        let length = setup
            .candidates
            .iter()
            .map(|c| gap(&c.touch, &setup.members, &setup.planes, &s).gap.abs())
            .filter(|g| g.is_finite())
            .fold(reach, f64::max)
            .max(f64::MIN_POSITIVE);
        let g = setup.options.gravity.norm();
        let fastest = (0..setup.members.len())
            .map(|b| {
                let spin = if setup.members[b].turns() {
                    s.w[b].norm() * reaches[b]
                } else {
                    0.0
                };
                s.v[b].norm() + spin
            })
            .fold(0.0, f64::max);
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
            reaches,
            trail: Vec::new(),
            zeno: None,
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
            && (self.s.kinetic_energy(&st.members)
                + self.s.potential_energy(&st.members, &st.options.gravity))
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
            kinetic: s.kinetic_energy(&st.members),
            potential: s.potential_energy(&st.members, &st.options.gravity),
            state: s,
            closed: self.closed.len(),
        });
    }

    fn accelerations_at(
        &self,
        s: &SystemState,
        closed: &[Held],
    ) -> Result<Accelerations, ContactError> {
        let st = &self.setup;
        accelerations(
            &st.members,
            &st.planes,
            &st.candidates,
            closed,
            s,
            &st.options.gravity,
            st.options.rest_speed,
            &st.joints,
        )
    }

    /// Whether candidate `k` is closed.
    fn is_closed(&self, k: usize) -> bool {
        self.closed.iter().any(|h| h.k == k)
    }

    /// How candidate `k`, closing, takes a tangential force: frictionless where μ = 0; else
    /// sliding along its slip when that is faster than the rest speed, sticking otherwise.
    fn mode_of(&self, k: usize) -> Mode {
        let st = self.setup;
        if st.candidates[k].law.mu == 0.0 {
            return Mode::Frictionless;
        }
        let u = slip(&self.gap(k, &self.s), &st.members, &self.s);
        if u.norm() > st.options.rest_speed {
            Mode::Slide(u.normalize())
        } else {
            Mode::Stick
        }
    }

    /// Candidate `k` closed, with the mode [`Self::mode_of`] gives it.
    fn held(&self, k: usize) -> Held {
        Held {
            k,
            mode: self.mode_of(k),
            armed: true,
        }
    }

    /// Closed contact `p` (a sticking one whose force leaves its cone) slides along
    /// `direction`, logged.
    fn starts_to_slide(&mut self, p: usize, direction: V3) {
        self.closed[p].mode = Mode::Slide(direction);
        self.closed[p].armed = false;
        self.events.push(Event {
            t: self.t,
            what: format!("{} starts to slide", self.name(self.closed[p].k)),
        });
    }

    /// The accelerations at the current state, switching a sticking contact that leaves its
    /// cone to sliding (as the single body's).
    fn current(&mut self) -> Result<Accelerations, SimulateError> {
        for _ in 0..=self.closed.len() {
            let s = self.s.clone();
            match self.accelerations_at(&s, &self.closed) {
                Ok(a) => return Ok(a),
                Err(ContactError::Slips { contact, direction }) => {
                    self.starts_to_slide(contact, direction);
                }
                Err(error) => return Err(SimulateError::Contact { t: self.t, error }),
            }
        }
        Err(SimulateError::Contact {
            t: self.t,
            error: ContactError::NoActiveSet,
        })
    }

    /// The last of the closed contacts `trial` (the others already closed), if it presses or
    /// holds at zero gap acceleration rather than separating: with the mode it takes — sliding,
    /// where sticking would need more friction than its cone holds.
    fn closes(&self, mut trial: Vec<Held>) -> Option<Held> {
        let last = trial.len() - 1;
        // each contact switches to sliding at most once: one more try than there are contacts
        for _ in 0..=trial.len() {
            match self.accelerations_at(&self.s, &trial) {
                Ok(a) => {
                    return (a.gap_acceleration[last] <= 1e-9 * a.scale).then_some(trial[last]);
                }
                Err(ContactError::Slips { contact, direction }) => {
                    trial[contact].mode = Mode::Slide(direction);
                    trial[contact].armed = false;
                }
                Err(_) => return None,
            }
        }
        None
    }

    /// The sliding contacts whose slips have stopped stick, if sticking needs no more friction
    /// than their cones allow (else they slide on: no chatter between the two). They are tried
    /// together first — the corners of a face that slides stop at once, and each alone would
    /// need the friction of all — then one by one. A contact may stick again only once its
    /// slip has exceeded twice the rest speed since it started (the single body's rule).
    fn slides_that_stop(&mut self) {
        let rest = self.setup.options.rest_speed;
        let mut stopped = Vec::new();
        for p in 0..self.closed.len() {
            let Mode::Slide(_) = self.closed[p].mode else {
                continue;
            };
            let k = self.closed[p].k;
            let u = slip(&self.gap(k, &self.s), &self.setup.members, &self.s).norm();
            if u > 2.0 * rest {
                self.closed[p].armed = true;
            }
            if u <= rest && self.closed[p].armed {
                stopped.push(p);
            }
        }
        if stopped.is_empty() {
            return;
        }
        let sticking: Vec<usize> = if let Some(trial) = self.stuck(&stopped) {
            self.closed = trial;
            stopped
        } else {
            let mut one = Vec::new();
            for p in stopped {
                if let Some(trial) = self.stuck(&[p]) {
                    self.closed = trial;
                    one.push(p);
                }
            }
            one
        };
        for p in sticking {
            self.events.push(Event {
                t: self.t,
                what: format!("{} sticks", self.name(self.closed[p].k)),
            });
        }
    }

    /// The closed contacts with `these` sticking, if none of them then needs more friction
    /// than its cone holds.
    fn stuck(&self, these: &[usize]) -> Option<Vec<Held>> {
        let mut trial = self.closed.clone();
        for &p in these {
            trial[p].mode = Mode::Stick;
        }
        let slips = matches!(
            self.accelerations_at(&self.s, &trial),
            Err(ContactError::Slips { contact, .. }) if these.contains(&contact)
        );
        (!slips).then_some(trial)
    }

    /// Whether the members, slower than the rest speed, would stay put with every sliding
    /// contact stuck: the accelerations with them sticking are consistent (every friction force
    /// within its cone) and below `still` (the single body's test: a slide that began at zero
    /// slip at the edge of its cone may never speed up enough to be let stick again).
    fn holds_when_stuck(&self, still: f64) -> bool {
        if !self.closed.iter().any(|h| matches!(h.mode, Mode::Slide(_))) {
            return false;
        }
        let stuck: Vec<Held> = self
            .closed
            .iter()
            .map(|h| Held {
                mode: match h.mode {
                    Mode::Slide(_) => Mode::Stick,
                    m => m,
                },
                ..*h
            })
            .collect();
        self.accelerations_at(&self.s, &stuck).is_ok_and(|a| {
            a.gap_acceleration.iter().all(|&g| g <= 1e-9 * a.scale)
                && (0..self.setup.members.len())
                    .all(|b| self.turning(b, a.a[b].norm(), a.alpha[b].norm()) <= still)
        })
    }

    fn name(&self, k: usize) -> String {
        let (a, b) = self.setup.candidates[k]
            .touch
            .name(&self.setup.members, &self.setup.planes);
        format!("{a} on {b}")
    }

    fn gap(&self, k: usize, s: &SystemState) -> super::gaps::Gap {
        gap(
            &self.setup.candidates[k].touch,
            &self.setup.members,
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
            // A closed contact whose point reaches its face's edge (an edge's end, a region's
            // boundary) moving out lets go.
            let off: Vec<usize> = (0..self.closed.len())
                .filter(|&p| self.leaves(&self.gap(self.closed[p].k, &self.s)))
                .collect();
            if !off.is_empty() {
                for &p in off.iter().rev() {
                    let k = self.closed.remove(p).k;
                    self.events.push(Event {
                        t: self.t,
                        what: format!(
                            "{} {}",
                            self.name(k),
                            self.setup.candidates[k].touch.leaving()
                        ),
                    });
                }
                continue;
            }
            let acc = self.current()?;
            let tol = 1e-9 * acc.scale.max(f64::MIN_POSITIVE);
            // Lift-off: a closed contact the accelerations open.
            let opening: Vec<usize> = (0..self.closed.len())
                .filter(|&p| acc.gap_acceleration[p] > tol)
                .collect();
            if !opening.is_empty() {
                self.let_go(&opening, "lifts off");
                continue;
            }
            self.slides_that_stop();
            let fastest = self.fastest(&self.s);
            let accel = (0..self.setup.members.len())
                .map(|b| self.turning(b, acc.a[b].norm(), acc.alpha[b].norm()))
                .fold(0.0, f64::max);
            let still = 1e-9 * (o.gravity.norm() + f64::MIN_POSITIVE);
            if !self.closed.is_empty()
                && fastest <= o.rest_speed
                && (accel <= still || self.holds_when_stuck(still))
            {
                return Ok(End::Rest);
            }
            // The open gaps: impacts, contacts closing, and the horizon of the step.
            let mut horizon = f64::INFINITY;
            let mut striking = false;
            let mut closing = false;
            for k in 0..self.setup.candidates.len() {
                if self.is_closed(k) {
                    continue;
                }
                let g = self.gap(k, &self.s);
                // beside every face, or at a face's edge moving out (it lets go: a zero gap
                // there would hold the horizon at zero while the point leaves sideways)
                if !g.gap.is_finite() || self.leaves(&g) {
                    continue;
                }
                if g.gap <= self.gap_tol {
                    if g.rate < -o.rest_speed {
                        striking = true;
                        continue;
                    } else if g.rate <= o.rest_speed && !self.leaves(&g) {
                        let mut trial = self.closed.clone();
                        trial.push(self.held(k));
                        if let Some(h) = self.closes(trial) {
                            self.closed.push(h);
                            self.events.push(Event {
                                t: self.t,
                                what: format!("{} closes", self.name(k)),
                            });
                            closing = true;
                            continue;
                        }
                        // at zero gap, not approaching beyond the rest speed, and the
                        // accelerations open it: it separates, and caps no step (its horizon
                        // would be zero at a rate of −10⁻¹¹ m/s); the step's crossing check
                        // still holds it
                        continue;
                    }
                }
                let members = &self.setup.members;
                let bound = match self.setup.candidates[k].touch {
                    Touch::Plane { body, .. } if !members[body].turns() => 2.0 * acc.a[body].norm(),
                    Touch::Pair { a, b } => 2.0 * (acc.a[a].norm() + acc.a[b].norm()) + g.curvature,
                    // twice |a| + ρ (|ω|² + |α|) of each side at the step's start, and the
                    // curvature (the single body's bound, over both sides)
                    _ => {
                        g.sides()
                            .map(|i| {
                                let (w, al) = if members[i.body].turns() {
                                    (self.s.w[i.body].norm_squared(), acc.alpha[i.body].norm())
                                } else {
                                    (0.0, 0.0)
                                };
                                2.0 * (acc.a[i.body].norm() + i.arm.norm() * (w + al))
                            })
                            .sum::<f64>()
                            + 2.0 * g.curvature.abs()
                            + f64::MIN_POSITIVE
                    }
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
            let b = self.setup.members.len();
            // positions on the length scale, velocities on the speed scale, each quaternion's
            // components on 1, each ω on the speed scale over the member's reach
            let scales: Vec<f64> = (0..y.len())
                .map(|k| match k {
                    k if k < 3 * b => self.length,
                    k if k < 6 * b => self.speed,
                    k if k < 10 * b => 1.0,
                    k => self.speed / self.reaches[(k - 10 * b) / 3].max(f64::MIN_POSITIVE),
                })
                .collect();
            let closed = self.closed.clone();
            let open: Vec<(usize, f64)> = (0..self.setup.candidates.len())
                .filter(|&k| !self.is_closed(k))
                .map(|k| (k, self.gap(k, &self.s).gap))
                .collect();
            // how far inside its face each closed face contact's point is (an edge contact's
            // end is not located: past it, its gap is +∞ and it lets go, the contact it hands
            // over to entering its region at the same gap)
            let over: Vec<(usize, f64)> = closed
                .iter()
                .filter(|h| matches!(self.setup.candidates[h.k].touch, Touch::Face { .. }))
                .map(|h| (h.k, self.gap(h.k, &self.s).inside))
                .filter(|(_, m)| m.is_finite())
                .collect();
            let mut stepper = std::mem::replace(&mut self.stepper, Stepper::new(1.0, 1.0));
            let advance = {
                let mut f = |_t: f64, y: &[f64]| -> Result<Vec<f64>, ContactError> {
                    let s = SystemState::unpack(y);
                    let a = self.accelerations_at(&s, &closed)?;
                    Ok(derivative(&self.setup.members, &s, &a))
                };
                // No open contact may end the step through its gap: one the step took through
                // is located by halving the step. One that enters its region (from +∞: an
                // edge's point past a corner onto the next edge or face) does so at the gap the
                // contact it takes over from held, within the drift of the projection: it is
                // taken as it comes, up to the overlap tolerance, and struck or closed there.
                let crosses = |y: &[f64]| {
                    let end = SystemState::unpack(y);
                    open.iter().any(|&(k, start)| {
                        let tol = if start.is_finite() {
                            self.gap_tol
                        } else {
                            1e3 * self.gap_tol
                        };
                        stepper::crossed(start, self.gap(k, &end).gap, tol)
                    }) || over.iter().any(|&(k, start)| {
                        stepper::crossed(start, self.gap(k, &end).inside, self.gap_tol)
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
                Advance::Failed(ContactError::Slips { contact, direction }) => {
                    // a mode change inside a step at the resolution of t: the sticking contact
                    // that must slip is switched (the single body's rule)
                    self.starts_to_slide(contact, direction);
                    self.stepper.h = super::super::ode::floor(self.t, o.output_step) * 16.0;
                    continue;
                }
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
                &st.members,
                &st.planes,
                &st.candidates,
                &self.closed,
                &mut self.s,
                &st.joints,
            );
            self.drift = self.drift.max(d);
            let tol = 1e3 * self.gap_tol;
            let joined = |a, b| st.joined(a, b);
            if deepest(&st.members, &self.s, tol, joined).is_some() {
                // where they first overlap: the step's continuous extension, bisected
                let at =
                    |t: f64| deepest(&st.members, &SystemState::unpack(&dense.at(t)), tol, joined);
                let (mut lo, mut hi) = (t0, t1);
                while hi - lo > 1e-12 * hi.abs().max(1.0) {
                    let mid = 0.5 * (lo + hi);
                    if at(mid).is_some() {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                let (a, b, depth) = at(hi)
                    .or_else(|| deepest(&st.members, &self.s, tol, joined))
                    .unwrap_or((0, 1, tol));
                return Err(SimulateError::Overlap {
                    t: hi,
                    first: st.members[a].name.clone(),
                    second: st.members[b].name.clone(),
                    depth,
                });
            }
        }
    }

    /// Whether the contact of gap `g` is a face contact whose point is at (or past) its
    /// face's edge, within the gap tolerance, and moving out over it.
    fn leaves(&self, g: &super::gaps::Gap) -> bool {
        !g.gap.is_finite() || (g.inside <= self.gap_tol && g.inside_rate < 0.0)
    }

    /// The closed contacts at `positions` (indices into the closed list, ascending) let go,
    /// each logged as `name why`.
    fn let_go(&mut self, positions: &[usize], why: &str) {
        for &p in positions.iter().rev() {
            let k = self.closed.remove(p).k;
            self.events.push(Event {
                t: self.t,
                what: format!("{} {why}", self.name(k)),
            });
        }
    }

    /// The fastest a member's point moves: |v_b| + |ω_b| ρ_b (|v_b| for a sphere).
    fn fastest(&self, s: &SystemState) -> f64 {
        (0..self.setup.members.len())
            .map(|b| self.turning(b, s.v[b].norm(), s.w[b].norm()))
            .fold(0.0, f64::max)
    }

    /// `linear` + `angular` ρ_b for a member that turns, `linear` for a sphere.
    fn turning(&self, b: usize, linear: f64, angular: f64) -> f64 {
        if self.setup.members[b].turns() {
            linear + angular * self.reaches[b]
        } else {
            linear
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
            let persisting = self.is_closed(k);
            if !joins(persisting, g.gap, g.rate, self.gap_tol, o.simultaneity) {
                continue;
            }
            if !persisting && g.gap > self.gap_tol {
                spread = spread.max(g.gap / -g.rate);
            }
            let (first, second) = st.candidates[k].touch.name(&st.members, &st.planes);
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
        let kinetic_before = self.s.kinetic_energy(&st.members);
        let before = self.s.clone();
        self.sample();
        let out = solve(
            &st.members,
            &st.planes,
            &st.candidates,
            &at,
            &self.s,
            &st.joints,
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
        if !out.w.iter().all(|v| v.iter().all(|x| x.is_finite())) {
            return Err(SimulateError::NotFinite { t: self.t });
        }
        self.s.v = out.v;
        self.s.w = out.w;
        self.closed.clear();
        for (p, &k) in at.iter().enumerate() {
            let g = self.gap(k, &self.s);
            struck[p].after = g.rate;
            struck[p].impulse = out.impulses[p];
            if g.gap <= self.gap_tol && g.rate <= o.rest_speed {
                let h = self.held(k);
                self.closed.push(h);
            }
        }
        let open = at
            .iter()
            .zip(&struck)
            .filter(|(_, c)| !c.persisting)
            .map(|(&k, _)| k)
            .collect();
        self.impacts.push(ImpactRecord {
            index,
            t: self.t,
            contacts: struck,
            spread,
            kinetic_before,
            kinetic_after: self.s.kinetic_energy(&st.members),
            verdicts: out.verdicts,
            note: out.note,
        });
        self.sample();
        self.trail
            .push(Bounce::new(&st.members, &before, &self.s, open, self.speed));
        self.accumulate(&before);
        Ok(())
    }

    /// The accumulation of a member's bounces after the impact just made, from the state
    /// `before` it, where [`super::zeno`] finds one: the member is moved to t∞ and its
    /// contacts persist, logged.
    fn accumulate(&mut self, before: &SystemState) {
        if self.zeno.is_some() {
            return;
        }
        let st = self.setup;
        let scene = Scene {
            members: &st.members,
            joints: &st.joints,
            planes: &st.planes,
            candidates: &st.candidates,
            gravity: st.options.gravity,
            speed: self.speed,
            length: self.length,
        };
        let closed: Vec<usize> = self.closed.iter().map(|h| h.k).collect();
        let Some(jump) = accumulation(
            &scene,
            &self.impacts,
            &self.trail,
            before,
            &self.s,
            &closed,
            st.options.duration - self.t,
        ) else {
            return;
        };
        self.s = jump.state;
        self.t += jump.dt;
        for &k in &jump.close {
            let h = self.held(k);
            self.closed.push(h);
        }
        let n = self.impacts.len();
        let names: Vec<String> = jump.close.iter().map(|&k| self.name(k)).collect();
        self.events.push(Event {
            t: self.t,
            what: format!(
                "Zeno: the impacts accumulate here (rebound ratio {:.6}, after impact {n}), dissipating {:.6e} J; {} persist{}",
                jump.ratio,
                jump.dissipated,
                names.join(", "),
                if names.len() == 1 { "s" } else { "" }
            ),
        });
        self.zeno = Some(Zeno {
            t_inf: self.t,
            after: n,
            ratio: jump.ratio,
            dissipated: jump.dissipated,
        });
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

/// ẏ of the packed state (the layout of [`SystemState::pack`]): (v_b), (a_b), ½ (0, ω_b) ⊗ q_b
/// and (α_b) — the quaternion and ω of a sphere held (module docs of [`super::members`]).
fn derivative(members: &[Member], s: &SystemState, acc: &Accelerations) -> Vec<f64> {
    let mut out: Vec<f64> =
        s.v.iter()
            .chain(&acc.a)
            .flat_map(|p| [p.x, p.y, p.z])
            .collect();
    for (b, q) in s.q.iter().enumerate() {
        if members[b].turns() {
            out.extend(quaternion_rate(q, &s.w[b]));
        } else {
            out.extend([0.0; 4]);
        }
    }
    out.extend(acc.alpha.iter().flat_map(|p| [p.x, p.y, p.z]));
    out
}
