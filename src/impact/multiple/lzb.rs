//! The LZB law: Darboux–Keller shock dynamics with each contact's own compression and
//! expansion (Liu, Zhao & Brogliato, Proc. R. Soc. A 464 (2008) 3193, §2–3; 465 (2009) 1),
//! integrated in f64 by an embedded Runge–Kutta pair with adaptive steps and event location.
//!
//! **The model.** Contact i has a law ([`ContactLaw`]: K_i, η_i, e_i), a normal impulse P_i
//! (along its unit normal) and a normal relative velocity v_i, positive approaching. With G the
//! inertance matrix of the unit normals (the paper's eq. 12, assembled by [`Blocks::spatial`]
//! for any [`Mechanism`]), dv = −G dP (eq. 13 in differentials). Each contact stores a
//! potential energy E_i:
//!
//! ```text
//! compression (v_i > 0):           dE_i = v_i dP_i
//! expansion   (v_i ≤ 0, E_i > 0):  dE_i = v_i dP_i / e_i²      (released = e_i² × stored)
//! at rest     (v_i ≤ 0, E_i = 0):  dP_i = 0
//! F_i = K_i^(1/(η_i+1)) ((η_i+1) E_i)^(η_i/(η_i+1)),   dP_j = (F_j / F_k) dP_k
//! ```
//!
//! with k the primary contact: the one with the largest E (Siconos' choice), or, when every
//! E is zero, the one approaching fastest. The impact ends when every E_i = 0 and no v_i > 0.
//!
//! **The variable of integration.** In the primary impulse P_k the equations are singular
//! wherever F_k = 0: at the start (every E = 0) and whenever every energy has returned to zero
//! while a contact still approaches, where dE_k/dP_k = v_k is finite but E_k^(η/(η+1)) has an
//! infinite slope. We integrate the same equations multiplied through by F_k, in the variable
//! τ with dP_k = F_k dτ: dP_j/dτ = F_j for every j. The trajectory in (P, E) is the same, point
//! for point, as the one parametrised by P_k (the primary contact only relabels it); τ is the
//! time of the compliant model with these stiffnesses when every e_i = 1. A second
//! singularity, of a contact loading from rest (E_j = 0, dE_j/dτ = v_j F_j = 0 has E_j ≡ 0 as
//! one solution), is removed by carrying u_j = E_j^(1/(η_j+1)) instead of E_j: with
//! c_j = (K_j/(η_j+1))^(1/(η_j+1)),
//!
//! ```text
//! dP_j/dτ = F_j = (η_j+1) c_j u_j^η_j
//! du_j/dτ = c_j v_j            compression
//!         = c_j v_j / e_j²     expansion
//!         = 0                  at rest
//! ```
//!
//! (dE_j = (η_j+1) u_j^η_j du_j = F_j v_j dτ = v_j dP_j, and /e_j² in expansion: the model
//! above). Every right-hand side is now finite and continuous in a phase; u_j = c_j δ_j with δ_j
//! the indentation while the contact compresses. The primary contact is still followed and
//! its changes are events of the report.
//!
//! **Events** (each located by bisection of the step to a few ε of it): a contact's
//! compression ends (v_j falls through 0; with e_j = 0 its energy is dissipated at once and it
//! rests), its expansion ends (u_j reaches 0: it rests), an expanding contact approaches again
//! (v_j rises through 0: it compresses again), a resting contact approaches (v_j rises
//! through δ_v = max(10⁻³ tol, 64 N ε) max|v⁰|: without that margin a contact carried at zero
//! relative velocity would chatter between rest and compression on rounding), and the primary
//! contact changes (another energy exceeds the primary's by the relative margin 10⁻⁹, so that
//! equal energies do not swap on rounding).
//!
//! **The integrator** is Dormand and Prince's RK5(4) pair with local extrapolation (the
//! tableau of [`crate::impact::friction::spatial`]), written here over the state
//! (P, u, W_c, W_r) because the friction integrator's steps are built around its stick/slip
//! modes; what is shared is the tableau and the form of its event location (bisection of the
//! step from its start). The step is accepted when every component's embedded error is below
//! tol × (|y| + its scale), the scales being those of the impact: Π = max v⁰ / max g_ii for the
//! impulses, Π max v⁰ for the works and (Π max v⁰)^(1/(η+1)) for u.
//!
//! **Error estimate.** The sum over accepted steps of the largest embedded error estimate of
//! an impulse (N s). It bounds the difference of the fourth- and fifth-order solutions, not
//! the propagation of earlier errors; it is tested against closed forms (one contact: Newton's
//! law with P = (1 + e) v⁰/g) and against an independent time integration of the compliant
//! model (`tests/lzb.rs`).

use crate::impact::friction::Blocks;
use crate::impact::friction::spatial::{A, E};
use crate::impact::mechanism::Mechanism;
use crate::mechanics::contact::ContactFrame;
use crate::mechanics::screw::Screws;
use crate::scalar::ratio;

use super::law::{ContactLaw, LawError};

/// The most accepted and rejected steps before the integration is declared runaway.
pub const MAX_STEPS: usize = 1_000_000;

/// The most events before the integration is declared runaway.
pub const MAX_EVENTS: usize = 100_000;

/// The relative margin by which another contact's energy must exceed the primary's for the
/// primary to change.
const PRIMARY_MARGIN: f64 = 1e-9;

/// A contact's phase during the impact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Approaching, storing energy: dE = v dP.
    Compression,
    /// Separating with energy stored, releasing it: dE = v dP / e².
    Expansion,
    /// No energy stored, not approaching: no impulse.
    Rest,
}

/// What happened at an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventKind {
    /// v_i fell through 0: the contact starts to expand (or, with e = 0, rests).
    CompressionEnds,
    /// E_i returned to 0: the contact rests.
    ExpansionEnds,
    /// An expanding contact approaches again.
    Recompresses,
    /// A resting contact starts to approach: it loads from E_i = 0.
    Engages,
    /// The contact became the primary one (the largest energy).
    Primary,
}

impl EventKind {
    /// The name in reports.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::CompressionEnds => "compression ends",
            EventKind::ExpansionEnds => "expansion ends",
            EventKind::Recompresses => "compresses again",
            EventKind::Engages => "engages",
            EventKind::Primary => "becomes primary",
        }
    }
}

/// One event of the impact.
#[derive(Clone, Debug, PartialEq)]
pub struct Event {
    /// τ where it was located.
    pub tau: f64,
    /// The contact (0-based).
    pub contact: usize,
    /// What happened.
    pub kind: EventKind,
}

/// One point of the impact's path (at every accepted step).
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// τ.
    pub tau: f64,
    /// The primary contact there.
    pub primary: usize,
    /// P_i.
    pub impulses: Vec<f64>,
    /// v_i.
    pub velocities: Vec<f64>,
    /// E_i.
    pub energies: Vec<f64>,
}

/// What the integration cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted Runge–Kutta steps (bisection trials not counted).
    pub accepted: usize,
    /// Rejected ones.
    pub rejected: usize,
    /// Events located.
    pub events: usize,
}

/// Why the LZB law gave no outcome.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LzbError {
    /// Not one law per contact.
    #[error("{laws} contact laws given for {contacts} contacts")]
    LawCount {
        /// Contacts.
        contacts: usize,
        /// Laws.
        laws: usize,
    },
    /// A contact's parameters have no meaning.
    #[error("contact {}: {error}", contact + 1)]
    Law {
        /// The contact (0-based).
        contact: usize,
        /// Why.
        error: LawError,
    },
    /// A contact with friction: the LZB law is integrated frictionless for now.
    #[error(
        "contact {}: the LZB law is integrated without friction (μ = 0 at every contact); \
         friction with LZB (LZB 2009, Part II) is not implemented",
        contact + 1
    )]
    Friction {
        /// The contact (0-based).
        contact: usize,
    },
    /// The tolerance is not in (0, 1).
    #[error("the tolerance must be a number in (0, 1) (got {value})")]
    Tolerance {
        /// The value.
        value: f64,
    },
    /// A contact's inertance is zero: no impulse there can change its velocity.
    #[error(
        "contact {}: its inertance g_ii is zero (no impulse there moves the mechanism), so its \
         compression never ends",
        contact + 1
    )]
    Immovable {
        /// The contact (0-based).
        contact: usize,
    },
    /// A path of the program that does not run the LZB law (yet).
    #[error(
        "the LZB law is not run by {what}: `inertance solve`, `sweep`, `analyze`, `bench \
         --scene` and Python's `solve` (and the library's `solve_lzb`) run it, in f64"
    )]
    Unsupported {
        /// What was asked.
        what: &'static str,
    },
    /// More steps or events than any physical impact needs, or a step that underflowed.
    #[error("the LZB integration did not end within its budget ({steps} steps, {events} events)")]
    Runaway {
        /// Steps tried.
        steps: usize,
        /// Events located.
        events: usize,
    },
}

/// The outcome of an impact under the LZB law. `S` is the mechanism's screw space.
#[derive(Clone, Debug)]
pub struct Lzb<S: Screws<f64>> {
    /// The law of every contact.
    pub laws: Vec<ContactLaw>,
    /// The unit normal axes and their inertance matrix G.
    pub blocks: Blocks<f64, S>,
    /// P_i along the unit normals (N s).
    pub impulses: Vec<f64>,
    /// v_i after impact (m/s, positive approaching).
    pub after: Vec<f64>,
    /// {v} after impact: the mechanism's twist (each body's, for a system).
    pub velocity: S,
    /// ∫ v_i dP_i over the compression phases (J): the energy stored.
    pub work_compression: Vec<f64>,
    /// −∫ v_i dP_i over the expansion phases (J): the energy given back.
    pub work_expansion: Vec<f64>,
    /// The largest potential energy each contact held (J).
    pub max_energy: Vec<f64>,
    /// ΔE_c = T⁰ − T from the kinetic energies (J).
    pub kinetic_energy_loss: f64,
    /// ΔE_c − Σ_i (W_c,i − W_r,i): zero but for the integration's error.
    pub energy_residual: f64,
    /// The events, in order.
    pub events: Vec<Event>,
    /// Steps and events.
    pub stats: Stats,
    /// The estimated error of the impulses (N s; module docs).
    pub error_estimate: f64,
    /// The relative tolerance the steps were held to.
    pub tolerance: f64,
    /// τ at the end.
    pub end: f64,
    /// The path, at every accepted step.
    pub samples: Vec<Sample>,
}

impl<S: Screws<f64>> Lzb<S> {
    /// The energy dissipated at contact i: W_c,i − W_r,i = (1 − e_i²) W_c,i once the impact has
    /// ended (J).
    pub fn dissipation(&self, i: usize) -> f64 {
        self.work_compression[i] - self.work_expansion[i]
    }

    /// Σ_i (W_c,i − W_r,i): the dissipation at the contacts, which equals ΔE_c.
    pub fn total_dissipation(&self) -> f64 {
        (0..self.impulses.len()).map(|i| self.dissipation(i)).sum()
    }

    /// The order in which the contacts last came to rest (0-based): the end of an expansion,
    /// or of the compression of a plastic contact (e = 0, which has no expansion).
    pub fn ending_order(&self) -> Vec<usize> {
        let mut order: Vec<usize> = Vec::new();
        for e in self.events.iter().rev() {
            let rests = match e.kind {
                EventKind::ExpansionEnds => true,
                EventKind::CompressionEnds => self.laws[e.contact].restitution == 0.0,
                _ => false,
            };
            if rests && !order.contains(&e.contact) {
                order.push(e.contact);
            }
        }
        order.reverse();
        order
    }
}

/// Solve the impact of `mechanism` under the LZB law, one [`ContactLaw`] per contact, the steps
/// held to the relative `tolerance` (module docs).
///
/// # Errors
/// [`LzbError`]: a law count or parameter out of range, friction at a contact, a tolerance
/// outside (0, 1), a contact no impulse moves, or an integration that did not end.
pub fn solve_lzb<M: Mechanism<f64>>(
    mechanism: &M,
    laws: &[ContactLaw],
    tolerance: f64,
) -> Result<Lzb<M::Screw>, LzbError> {
    let n = mechanism.contacts().len();
    if laws.len() != n {
        return Err(LzbError::LawCount {
            contacts: n,
            laws: laws.len(),
        });
    }
    for (contact, law) in laws.iter().enumerate() {
        law.validate()
            .map_err(|error| LzbError::Law { contact, error })?;
    }
    if let Some(contact) = mechanism.contacts().iter().position(|c| c.mu != 0.0) {
        return Err(LzbError::Friction { contact });
    }
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(LzbError::Tolerance { value: tolerance });
    }
    let tolerance = tolerance.max(4.0 * f64::EPSILON);
    let frames: Vec<ContactFrame<f64, M::Screw>> = (0..n)
        .map(|i| {
            ContactFrame::normal_with(&mechanism.contacts()[i], |u| mechanism.contact_axis(i, u))
        })
        .collect();
    let blocks = Blocks::spatial(mechanism, &frames);
    let run = Run::new(&blocks, laws, tolerance)?;
    let path = run.integrate()?;
    let impulses: Vec<f64> = path.y[..n].to_vec();
    let mut after = vec![0.0; n];
    run.velocities(&impulses, &mut after);
    let velocity = blocks.twist_after(mechanism.velocity(), &impulses);
    let kinetic_energy_loss =
        mechanism.kinetic_energy(mechanism.velocity()) - mechanism.kinetic_energy(&velocity);
    let work_compression = path.y[2 * n..3 * n].to_vec();
    let work_expansion = path.y[3 * n..].to_vec();
    let dissipated: f64 = (0..n)
        .map(|i| work_compression[i] - work_expansion[i])
        .sum();
    Ok(Lzb {
        laws: laws.to_vec(),
        impulses,
        after,
        velocity,
        work_compression,
        work_expansion,
        max_energy: path.max_energy,
        kinetic_energy_loss,
        energy_residual: kinetic_energy_loss - dissipated,
        events: path.events,
        stats: path.stats,
        error_estimate: path.estimate,
        tolerance,
        end: path.tau,
        samples: path.samples,
        blocks,
    })
}

/// The integration's fixed data.
struct Run<'a> {
    n: usize,
    g: &'a [f64],
    v0: &'a [f64],
    laws: &'a [ContactLaw],
    c: Vec<f64>,
    tol: f64,
    /// Per component of y: the scale of its absolute tolerance.
    scale: Vec<f64>,
    /// δ_v: the approach speed at which a resting contact engages.
    engage: f64,
    /// The first step.
    h0: f64,
}

/// Where the integration ended.
struct Path {
    y: Vec<f64>,
    tau: f64,
    max_energy: Vec<f64>,
    events: Vec<Event>,
    stats: Stats,
    estimate: f64,
    samples: Vec<Sample>,
}

impl<'a> Run<'a> {
    fn new<S: Screws<f64>>(
        blocks: &'a Blocks<f64, S>,
        laws: &'a [ContactLaw],
        tol: f64,
    ) -> Result<Self, LzbError> {
        let n = blocks.contacts();
        let g = &blocks.k[..];
        let v0 = &blocks.v0[..];
        let speed = v0.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let mut gmax = 0.0_f64;
        for i in 0..n {
            let gii = g[i * n + i];
            if gii.is_nan() || gii <= 0.0 {
                return Err(LzbError::Immovable { contact: i });
            }
            gmax = gmax.max(gii);
        }
        let impulse = speed / gmax;
        let energy = impulse * speed;
        let mut scale = vec![impulse; n];
        scale.extend(laws.iter().map(|l| energy.powf(1.0 / (l.exponent + 1.0))));
        scale.extend(std::iter::repeat_n(energy, 2 * n));
        let c: Vec<f64> = laws.iter().map(ContactLaw::c).collect();
        // The duration of the fastest contact's compression alone: δ* = ((η+1) v²/(2 g K))^(1/(η+1))
        // reached at the speed v, so τ* ≈ δ*/v.
        let h0 = (0..n)
            .filter(|&i| v0[i] > 0.0)
            .map(|i| {
                let l = &laws[i];
                let m = l.exponent + 1.0;
                let delta = (m * v0[i] * v0[i] / (2.0 * g[i * n + i] * l.stiffness)).powf(1.0 / m);
                1e-3 * delta / v0[i]
            })
            .fold(f64::INFINITY, f64::min);
        Ok(Run {
            n,
            g,
            v0,
            laws,
            c,
            tol,
            scale,
            engage: (1e-3 * tol).max(64.0 * n as f64 * f64::EPSILON) * speed,
            h0,
        })
    }

    /// v = v⁰ − G P.
    fn velocities(&self, p: &[f64], v: &mut [f64]) {
        let n = self.n;
        for i in 0..n {
            let row = &self.g[i * n..(i + 1) * n];
            v[i] = self.v0[i] - row.iter().zip(p).map(|(g, p)| g * p).sum::<f64>();
        }
    }

    /// E_j = u_j^(η_j+1).
    fn energy(&self, j: usize, u: f64) -> f64 {
        u.max(0.0).powf(self.laws[j].exponent + 1.0)
    }

    /// dy/dτ in the phases `phases` (module docs); `v` is a buffer for the velocities.
    fn rhs(&self, y: &[f64], phases: &[Phase], dy: &mut [f64], v: &mut [f64]) {
        let n = self.n;
        self.velocities(&y[..n], v);
        for j in 0..n {
            let (law, c) = (&self.laws[j], self.c[j]);
            let f = match phases[j] {
                Phase::Rest => 0.0,
                _ => law.force_of_u(c, y[n + j]),
            };
            dy[j] = f;
            let e2 = law.restitution * law.restitution;
            let (du, dwc, dwr) = match phases[j] {
                Phase::Compression => (c * v[j], v[j] * f, 0.0),
                Phase::Expansion => (c * v[j] / e2, 0.0, -v[j] * f),
                Phase::Rest => (0.0, 0.0, 0.0),
            };
            dy[n + j] = du;
            dy[2 * n + j] = dwc;
            dy[3 * n + j] = dwr;
        }
    }

    /// One Dormand–Prince step of length h from y: (y_new, embedded error).
    fn step(&self, y: &[f64], h: f64, phases: &[Phase]) -> (Vec<f64>, Vec<f64>) {
        let len = y.len();
        let mut k: Vec<Vec<f64>> = vec![vec![0.0; len]; 7];
        let mut v = vec![0.0; self.n];
        let mut stage = y.to_vec();
        for s in 0..7 {
            for (q, x) in stage.iter_mut().enumerate() {
                *x = y[q]
                    + h * (0..s)
                        .map(|r| ratio::<f64>(A[s][r].0, A[s][r].1) * k[r][q])
                        .sum::<f64>();
            }
            let mut d = vec![0.0; len];
            self.rhs(&stage, phases, &mut d, &mut v);
            k[s] = d;
        }
        // The seventh stage is evaluated at the fifth-order solution (FSAL).
        let err: Vec<f64> = (0..len)
            .map(|q| {
                h * (0..7)
                    .map(|r| ratio::<f64>(E[r].0, E[r].1) * k[r][q])
                    .sum::<f64>()
            })
            .collect();
        (stage, err)
    }

    /// The largest error relative to what the tolerance allows.
    fn error_ratio(&self, y: &[f64], yn: &[f64], err: &[f64]) -> f64 {
        (0..y.len())
            .map(|q| err[q].abs() / (self.tol * (y[q].abs().max(yn[q].abs()) + self.scale[q])))
            .fold(0.0, f64::max)
    }

    /// The events between y and yn under `phases`, `primary` being the primary contact at y.
    fn crossings(
        &self,
        y: &[f64],
        yn: &[f64],
        phases: &[Phase],
        primary: usize,
    ) -> Vec<(usize, EventKind)> {
        let n = self.n;
        let mut v = vec![0.0; n];
        self.velocities(&yn[..n], &mut v);
        let mut out = Vec::new();
        for j in 0..n {
            let u = yn[n + j];
            match phases[j] {
                Phase::Compression if v[j] < 0.0 => out.push((j, EventKind::CompressionEnds)),
                Phase::Expansion if u < 0.0 => out.push((j, EventKind::ExpansionEnds)),
                Phase::Expansion if v[j] > 0.0 => out.push((j, EventKind::Recompresses)),
                Phase::Rest if v[j] > self.engage => out.push((j, EventKind::Engages)),
                _ => {}
            }
        }
        if self.energy(primary, y[n + primary]) > 0.0 {
            let ek = self.energy(primary, yn[n + primary]);
            if let Some(j) = self.largest_energy(yn)
                && j != primary
                && self.energy(j, yn[n + j]) > ek * (1.0 + PRIMARY_MARGIN)
            {
                out.push((j, EventKind::Primary));
            }
        }
        out
    }

    /// The contact with the largest positive energy, if any.
    fn largest_energy(&self, y: &[f64]) -> Option<usize> {
        let n = self.n;
        (0..n)
            .map(|j| (j, self.energy(j, y[n + j])))
            .filter(|(_, e)| *e > 0.0)
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(j, _)| j)
    }

    /// The primary contact at y: the largest energy, kept on ties within the margin; when every
    /// energy is zero, the fastest approaching.
    fn primary(&self, y: &[f64], current: usize) -> usize {
        let n = self.n;
        match self.largest_energy(y) {
            Some(j) => {
                let ek = self.energy(current, y[n + current]);
                if self.energy(j, y[n + j]) > ek * (1.0 + PRIMARY_MARGIN) {
                    j
                } else {
                    current
                }
            }
            None => {
                let mut v = vec![0.0; n];
                self.velocities(&y[..n], &mut v);
                (0..n).max_by(|&a, &b| v[a].total_cmp(&v[b])).unwrap_or(0)
            }
        }
    }

    fn integrate(&self) -> Result<Path, LzbError> {
        let n = self.n;
        let mut y = vec![0.0; 4 * n];
        let mut v = self.v0.to_vec();
        let mut phases: Vec<Phase> = (0..n)
            .map(|j| {
                if v[j] > self.engage {
                    Phase::Compression
                } else {
                    Phase::Rest
                }
            })
            .collect();
        let mut primary = self.primary(&y, 0);
        let mut path = Path {
            y: Vec::new(),
            tau: 0.0,
            max_energy: vec![0.0; n],
            events: Vec::new(),
            stats: Stats::default(),
            estimate: 0.0,
            samples: Vec::new(),
        };
        let record = |path: &mut Path, y: &[f64], v: &[f64], primary: usize| {
            path.samples.push(Sample {
                tau: path.tau,
                primary,
                impulses: y[..n].to_vec(),
                velocities: v.to_vec(),
                energies: (0..n).map(|j| self.energy(j, y[n + j])).collect(),
            });
        };
        record(&mut path, &y, &v, primary);
        let mut h = self.h0;
        while phases.iter().any(|p| *p != Phase::Rest) {
            let steps = path.stats.accepted + path.stats.rejected;
            if steps >= MAX_STEPS || path.stats.events >= MAX_EVENTS || path.tau + h == path.tau {
                return Err(LzbError::Runaway {
                    steps,
                    events: path.stats.events,
                });
            }
            let (yn, err) = self.step(&y, h, &phases);
            let ratio = self.error_ratio(&y, &yn, &err);
            if !ratio.is_finite() || ratio > 1.0 {
                path.stats.rejected += 1;
                h *= if ratio.is_finite() {
                    (0.9 * ratio.powf(-0.2)).max(0.2)
                } else {
                    0.2
                };
                continue;
            }
            let (taken, yn, err) = if self.crossings(&y, &yn, &phases, primary).is_empty() {
                (h, yn, err)
            } else {
                self.locate(&y, h, yn, err, &phases, primary)
            };
            let found = self.crossings(&y, &yn, &phases, primary);
            path.stats.accepted += 1;
            path.tau += taken;
            path.estimate += err[..n].iter().fold(0.0_f64, |m, e| m.max(e.abs()));
            y = yn;
            for (j, kind) in found {
                path.stats.events += 1;
                path.events.push(Event {
                    tau: path.tau,
                    contact: j,
                    kind,
                });
                match kind {
                    EventKind::CompressionEnds => {
                        path.max_energy[j] = path.max_energy[j].max(self.energy(j, y[n + j]));
                        if self.laws[j].restitution == 0.0 {
                            y[n + j] = 0.0;
                            phases[j] = Phase::Rest;
                        } else {
                            phases[j] = Phase::Expansion;
                        }
                    }
                    EventKind::ExpansionEnds => {
                        y[n + j] = 0.0;
                        phases[j] = Phase::Rest;
                    }
                    EventKind::Recompresses | EventKind::Engages => {
                        phases[j] = Phase::Compression;
                    }
                    EventKind::Primary => primary = j,
                }
            }
            self.velocities(&y[..n], &mut v);
            // A resting contact already approaching (the end of another's expansion left it so).
            for j in 0..n {
                if phases[j] == Phase::Rest && v[j] > self.engage {
                    phases[j] = Phase::Compression;
                    path.stats.events += 1;
                    path.events.push(Event {
                        tau: path.tau,
                        contact: j,
                        kind: EventKind::Engages,
                    });
                }
            }
            primary = self.primary(&y, primary);
            record(&mut path, &y, &v, primary);
            if taken == h {
                h *= (0.9 * ratio.max(1e-10).powf(-0.2)).min(5.0);
            }
        }
        for j in 0..n {
            path.max_energy[j] = path.max_energy[j].max(self.energy(j, y[n + j]));
        }
        path.y = y;
        Ok(path)
    }

    /// The shortest step from y, within a few ε of it, at whose end an event has happened: the
    /// step, its end and its error estimate.
    fn locate(
        &self,
        y: &[f64],
        h: f64,
        yn: Vec<f64>,
        err: Vec<f64>,
        phases: &[Phase],
        primary: usize,
    ) -> (f64, Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi) = (0.0, h);
        let mut best = (yn, err);
        while hi - lo > 4.0 * f64::EPSILON * hi {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let (ym, em) = self.step(y, mid, phases);
            if self.crossings(y, &ym, phases, primary).is_empty() {
                lo = mid;
            } else {
                hi = mid;
                best = (ym, em);
            }
        }
        (hi, best.0, best.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::problem::Problem;
    use crate::mechanics::body::RigidBody;
    use crate::mechanics::contact::Contact;
    use crate::mechanics::screw::{Screw, Vec3};

    /// A unit point mass (with some inertia) falling at 1 m/s onto `contacts` normals −z.
    fn falling(points: &[[f64; 3]], mu: f64) -> Problem<f64> {
        let body = RigidBody::principal(1.0, Vec3::new(0.5, 0.5, 0.5));
        let twist = Screw::new(Vec3::zeros(), Vec3::new(0.0, 0.0, -1.0));
        let contacts = points
            .iter()
            .map(|p| {
                Contact::new(Vec3::new(p[0], p[1], p[2]), Vec3::new(0.0, 0.0, -1.0), 0.5)
                    .with_friction(mu)
            })
            .collect();
        Problem::new(body, twist, contacts).expect("valid")
    }

    /// A plastic contact (e = 0) stops at v = 0 with P = v⁰/g and comes to rest at the end of
    /// its compression: the compression work is all dissipated.
    #[test]
    fn a_plastic_contact_stops_and_rests() {
        let p = falling(&[[0.0, 0.0, 0.0]], 0.0);
        let law = ContactLaw::new(2.0, 1.5, 0.0).expect("valid");
        let out = solve_lzb(&p, &[law], 1e-11).expect("ends");
        let g = out.blocks.k[0];
        assert!((out.impulses[0] - 1.0 / g).abs() <= 2.0 * out.error_estimate + 1e-15);
        assert_eq!(out.work_expansion[0], 0.0);
        assert_eq!(out.ending_order(), vec![0]);
        assert!(
            out.events
                .iter()
                .all(|e| e.kind == EventKind::CompressionEnds)
        );
    }

    #[test]
    fn what_the_law_does_not_take_is_refused() {
        let law = ContactLaw::default();
        let one = falling(&[[0.0, 0.0, 0.0]], 0.0);
        assert_eq!(
            solve_lzb(&one, &[law, law], 1e-9).err(),
            Some(LzbError::LawCount {
                contacts: 1,
                laws: 2
            })
        );
        assert_eq!(
            solve_lzb(&falling(&[[0.0, 0.0, 0.0]], 0.3), &[law], 1e-9).err(),
            Some(LzbError::Friction { contact: 0 })
        );
        for tol in [0.0, 1.0, f64::NAN] {
            assert!(matches!(
                solve_lzb(&one, &[law], tol).err(),
                Some(LzbError::Tolerance { .. })
            ));
        }
        let bad = ContactLaw {
            restitution: 2.0,
            ..law
        };
        assert!(matches!(
            solve_lzb(&one, &[bad], 1e-9).err(),
            Some(LzbError::Law { contact: 0, .. })
        ));
    }

    /// A contact that does not approach, alone: no impulse, no step.
    #[test]
    fn nothing_approaches_nothing_happens() {
        let body = RigidBody::principal(1.0, Vec3::new(0.5, 0.5, 0.5));
        let twist = Screw::new(Vec3::zeros(), Vec3::new(0.0, 0.0, 1.0));
        let c = Contact::new(Vec3::zeros(), Vec3::new(0.0, 0.0, -1.0), 0.5);
        let p = Problem::new(body, twist, vec![c]).expect("valid");
        let out = solve_lzb(&p, &[ContactLaw::default()], 1e-9).expect("ends");
        assert_eq!(out.impulses, vec![0.0]);
        assert_eq!(out.stats, Stats::default());
    }
}
