//! The LZB law: Darboux–Keller shock dynamics with each contact's own compression and
//! expansion (Liu, Zhao & Brogliato, Proc. R. Soc. A 464 (2008) 3193, §2–3; 465 (2009) 1),
//! integrated in f64 or double-double ([`Real`]) by an embedded Runge–Kutta pair with adaptive
//! steps and event location.
//!
//! **The model** (frictionless; friction below). Contact i has a law ([`ContactLaw`]: K_i, η_i,
//! e_i), a normal impulse P_i (along its unit normal) and a normal relative velocity v_i,
//! positive approaching. With G the inertance matrix of the unit normals (the paper's eq. 12, assembled by [`Blocks::spatial`]
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
//! (Λ, u, W_c, W_r, W_f) because the friction integrator's steps are built around its stick/slip
//! modes; what is shared is the tableau and the form of its event location (bisection of the
//! step from its start). The step is accepted when every component's embedded error is below
//! tol × (|y| + its scale), the scales being those of the impact: Π = max v⁰ / max g_ii for the
//! impulses, Π max v⁰ for the works and (Π max v⁰)^(1/(η+1)) for u.
//!
//! **Friction** (Zhao, Liu & Brogliato, Proc. R. Soc. A 465 (2009) 2267, "Planar dynamics of a
//! rigid body system with frictional impacts"; LZB 2009, Part II). A contact with μ_i > 0 also
//! takes a tangential impulse τ_i, and the velocities of every axis follow the full inertance
//! blocks K of the friction layer ([`Blocks::planar`] when the scene stays in a plane — exact
//! hatted axes, one tangent per contact — else [`Blocks::spatial`], two unit tangents):
//! v = v⁰ − K Λ with Λ = (P_1, τ_1, P_2, τ_2, …), so the tangential impulses change the normal
//! velocities and through them dE_i = v_i dP_i. The normal rates are prescribed, dP_i/dτ = F_i
//! ([`Normal::Given`]), and Coulomb's law holds at every instant:
//!
//! ```text
//! sliding:   dτ_i/dτ = μ_i (v_it/|v_it|) F_i      (the impulse on the body, −τ_i, opposes slip)
//! sticking:  dτ_i/dτ keeps v_it = 0, while |dτ_i/dτ| ≤ μ_i F_i
//! at rest:   dτ_i/dτ = 0
//! dW_f,i/dτ = v_it · dτ_i/dτ ≥ 0                   (the friction work)
//! ```
//!
//! the rates under one assignment of modes being the friction layer's linear system
//! ([`rates`]). The state is y = (Λ, u, W_c, W_r, W_f), and ΔE_c = Σ_i (W_c,i − W_r,i + W_f,i).
//! Friction adds three events: a planar slip that crosses zero (bisected); a spatial slip that
//! slows within 1024 lock speeds (16 tol max|v⁰| each) of zero, its steps capped at a turn
//! of a quarter radian and nine tenths of the predicted time to zero slip (its direction turns
//! ever faster there: Bhatt and Koechling's singular point) — within that zone a slip that
//! does not slow keeps the direction it had on entering it or was started along (a slide
//! started at a cone's edge grows at the rates' rounding, and followed its noise-level slip
//! round and round at ever shorter steps); and a sticking contact whose
//! required rate leaves its cone by more than tol relative (bisected). At each, the modes of
//! every contact at zero slip are chosen jointly — in a plane by the friction layer's
//! [`resolve_planar`], a contact leaving its cone sliding in the sense of the impulse it would
//! need to stick; in space all stick if their cones allow it, a contact whose cone does not
//! sliding along an invariant direction of its tangential block ([`invariant_directions`]). A
//! slip that stopped is reported as [`EventKind::Sticks`] or [`EventKind::Reverses`], a stick
//! that left its cone as [`EventKind::SlipStarts`]. With one contact the path in P does not
//! depend on K or η, and LZB is Stronge's energetic law with friction (`tests/lzb_friction.rs`,
//! `derivations/lzb.md`). Several spatial contacts that must leave zero slip together (the
//! search finds their directions one at a time), and slips stopping at their cones' edges
//! (where a consistent assignment is marginal and rounding decides what the search sees),
//! take their modes from Tresca's problem instead: every normal rate here is given, so
//! Coulomb's law at the contacts at zero slip is the minimum of a convex function, which always
//! exists ([`tresca_modes`]). Sticking contacts whose tangential split is not unique stay stuck
//! while Tresca's minimiser keeps them so (a member of the family lies in every cone), whatever
//! the member the rates took; a stick leaves its cone by more than tol relative to the
//! impact's largest rate. [`LzbError::NoConsistentModes`] remains where neither finds modes
//! with rates.
//!
//! **Error estimate.** The sum over accepted steps of the largest embedded error estimate of
//! an impulse (N s). It bounds the difference of the fourth- and fifth-order solutions, not
//! the propagation of earlier errors; each spatial slip stop adds twice its largest rate times
//! its predicted time to zero slip. It is tested against closed forms (one contact: Newton's
//! law with P = (1 + e) v⁰/g; with friction, the energetic law solved exactly in a plane) and
//! against an independent time integration of the compliant model, with Coulomb's force on
//! sliding contacts (`tests/lzb.rs`, `tests/lzb_friction.rs`).
//!
//! **The scalar.** The integration is generic over a float type `T` ([`Real`]: `f64`, and
//! double-double, unit roundoff u = 2⁻¹⁰⁴): the state, the tableau (rounded once from its
//! fractions to `T`, so a double-double run does not inherit f64's rounding of 3/40 or
//! 19372/6561), the step h and τ, and the forces (u^η = e^(η ln u) in double-double, to a few u)
//! are in `T`; what only steers the integration — the step's error ratio, the event tests'
//! signs and thresholds, the error estimate — is read in f64. Events are bisected to
//! 4 ε_T h, so that locating them costs no more than the tolerance asks: with f64's width a
//! double-double run's energies would be cut at 10⁻¹⁶ of a step. The tolerance may go down to
//! 4 ε_T (10⁻²⁵ and below in double-double, where ε_T^(2/3) = 1.3·10⁻²¹ is the default); the
//! steps grow as tol^(−1/5), so the cradle takes 21 041 steps at 1.3·10⁻²¹ against 181 at
//! 3.7·10⁻¹¹ in f64. `tests/lzb_dd.rs` checks double-double against the exact closed forms far
//! below f64's rounding, and against f64 within the f64 estimate.

use crate::impact::friction::Blocks;
use crate::impact::friction::departure::invariant_directions;
use crate::impact::friction::modes::{MAX_CANDIDATES, resolve_planar};
use crate::impact::friction::rates::{Mode, Normal, RateFailure, Rates, rates};
use crate::impact::friction::spatial::{A, E};
use crate::impact::friction::tresca::tresca_modes;
use crate::impact::mechanism::Mechanism;
use crate::mechanics::contact::ContactFrame;
use crate::mechanics::screw::Screws;
use crate::scalar::{Real, Scalar, ratio};
use num_traits::Zero;

use super::law::{ContactLaw, LawError};

/// The most accepted and rejected steps before the integration is declared runaway.
pub const MAX_STEPS: usize = 1_000_000;

/// The most events before the integration is declared runaway.
pub const MAX_EVENTS: usize = 100_000;

/// The relative margin by which another contact's energy must exceed the primary's for the
/// primary to change.
const PRIMARY_MARGIN: f64 = 1e-9;

/// The most a spatial slip's direction may turn over one step (radians): near zero slip the
/// direction turns ever faster (Bhatt and Koechling's singular point), and a step that turns
/// it by more is retried shorter.
const QUARTER: f64 = 0.25;

/// A spatial slip that slows below this many lock speeds is stopped there: near zero slip its
/// direction turns ever faster and the steps that follow it stall at the integration's noise
/// (the error of stopping it early, twice its rate times the predicted time to zero slip, is
/// added to the estimate). One that does not slow keeps its direction below it.
const STOP_ZONE: f64 = 1024.0;

/// A contact's phase during the impact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Approaching, storing energy: dE = v dP.
    Compression,
    /// Separating with energy stored, releasing it: dE = v dP / e².
    Expansion,
    /// No energy stored, not approaching: no impulse, normal or tangential.
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
    /// A sliding contact's slip stopped and it sticks.
    Sticks,
    /// A sliding contact's slip stopped and started again the other way (in space: along
    /// another direction).
    Reverses,
    /// A sticking contact's tangential impulse rate reached its cone: it slides.
    SlipStarts,
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
            EventKind::Sticks => "slip stops, sticks",
            EventKind::Reverses => "slip stops, reverses",
            EventKind::SlipStarts => "slip starts",
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
    /// τ_i: each contact's tangential impulse along its unit tangent axes, as
    /// [`Lzb::tangential`] (none for a frictionless contact, one entry in a plane, two in space).
    pub tangential: Vec<Vec<f64>>,
    /// v_it: each contact's slip velocity along the same axes (m/s).
    pub slips: Vec<Vec<f64>>,
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
    /// A rough contact whose tangent frame cannot be built.
    #[error("contact {}: {message}", contact + 1)]
    Frame {
        /// The contact (0-based).
        contact: usize,
        /// Why.
        message: String,
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
    /// No assignment of stick and slip is consistent at a slip event.
    #[error(
        "at τ = {tau} no assignment of stick and slip is consistent at the contacts at zero \
         slip: Coulomb's law has no continuation here"
    )]
    NoConsistentModes {
        /// Where.
        tau: f64,
    },
    /// The tangential rates are not determined.
    #[error(
        "at τ = {tau} the tangential impulse rates are not determined: the inertance matrix is \
         singular on the sticking contacts (see `inertance analyze`)"
    )]
    Undetermined {
        /// Where.
        tau: f64,
    },
    /// Too many contacts at zero slip at once to try every assignment.
    #[error(
        "at τ = {tau}, {contacts} contacts are at zero slip at once: more than 8 are not resolved"
    )]
    TooManyAtRest {
        /// Where.
        tau: f64,
        /// How many.
        contacts: usize,
    },
    /// A path of the program that does not run the LZB law (yet).
    #[error(
        "the LZB law is not run by {what}: `inertance solve`, `sweep`, `analyze`, `bench \
         --scene` and Python's `solve` (and the library's `solve_lzb`) run it, in f64 (and \
         double-double)"
    )]
    Unsupported {
        /// What was asked.
        what: &'static str,
    },
    /// A number of the outcome overflowed or is not a number (inputs at the ends of f64's
    /// range): no answer is given rather than a NaN or an infinity.
    #[error(
        "the LZB integration gave a number f64 cannot hold (an impulse, a velocity or a work \
         overflowed): scale the scene's units so that its speeds, masses and stiffnesses are \
         nearer 1"
    )]
    NotFinite,
    /// More steps or events than any physical impact needs, or a step that underflowed.
    #[error("the LZB integration did not end within its budget ({steps} steps, {events} events)")]
    Runaway {
        /// Steps tried.
        steps: usize,
        /// Events located.
        events: usize,
    },
}

impl LzbError {
    /// The error located at `tau` where the rates it came from did not know where they were
    /// evaluated (inside a step: the step's start).
    fn at(self, tau: f64) -> Self {
        match self {
            LzbError::NoConsistentModes { tau: t } if t.is_nan() => {
                LzbError::NoConsistentModes { tau }
            }
            LzbError::Undetermined { tau: t } if t.is_nan() => LzbError::Undetermined { tau },
            e => e,
        }
    }
}

/// The outcome of an impact under the LZB law. `S` is the mechanism's screw space, `T` the
/// float type the law was integrated in (`f64` or double-double, [`Real`]); the values of the
/// outcome are in `T`, the path's samples, the events and the error estimate in `f64`.
#[derive(Clone, Debug)]
pub struct Lzb<S, T = f64>
where
    T: Real,
    S: Screws<T>,
{
    /// The law of every contact.
    pub laws: Vec<ContactLaw>,
    /// The stacked axes and their inertance matrix K ([`Blocks`]): every contact's unit normal
    /// when no contact has friction (then K = G); with friction also the tangent axes of the
    /// rough contacts — hatted (|t_i| = |n_i|) in a planar scene, unit in a spatial one.
    pub blocks: Blocks<T, S>,
    /// v_i⁰ along the unit normals (m/s, positive approaching).
    pub before: Vec<T>,
    /// P_i along the unit normals (N s).
    pub impulses: Vec<T>,
    /// τ_i: each contact's tangential impulse along its unit tangent axes (N s): none without
    /// friction, one entry in a planar scene (along the in-plane tangent, in the sense of the
    /// contact's y axis), two in space (the frame's y and z). The impulse on the body is
    /// −(P_i n_i + τ_i · t_i): τ_i points along the slip it opposes.
    pub tangential: Vec<Vec<T>>,
    /// v_i after impact (m/s, positive approaching).
    pub after: Vec<T>,
    /// {v} after impact: the mechanism's twist (each body's, for a system).
    pub velocity: S,
    /// ∫ v_i dP_i over the compression phases (J): the energy stored.
    pub work_compression: Vec<T>,
    /// −∫ v_i dP_i over the expansion phases (J): the energy given back.
    pub work_expansion: Vec<T>,
    /// ∫ v_it · dτ_i (J): the energy friction dissipated at each contact (≥ 0).
    pub friction_dissipation: Vec<T>,
    /// The largest potential energy each contact held (J).
    pub max_energy: Vec<T>,
    /// ΔE_c = T⁰ − T from the kinetic energies (J).
    pub kinetic_energy_loss: T,
    /// ΔE_c − Σ_i (W_c,i − W_r,i + W_f,i): zero but for the integration's error.
    pub energy_residual: T,
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

impl<S: Screws<T>, T: Real> Lzb<S, T> {
    /// The energy dissipated in the normal direction at contact i: W_c,i − W_r,i =
    /// (1 − e_i²) W_c,i once the impact has ended (J); friction's is
    /// [`Lzb::friction_dissipation`].
    pub fn dissipation(&self, i: usize) -> T {
        self.work_compression[i] - self.work_expansion[i]
    }

    /// Σ_i (W_c,i − W_r,i + W_f,i): the dissipation at the contacts, normal and by friction,
    /// which equals ΔE_c.
    pub fn total_dissipation(&self) -> T {
        (0..self.impulses.len()).fold(T::zero(), |s, i| {
            s + self.dissipation(i) + self.friction_dissipation[i]
        })
    }

    /// Whether any contact has friction (the tangential columns of reports).
    pub fn has_friction(&self) -> bool {
        self.blocks.dims.iter().any(|&d| d > 0)
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
/// held to the relative `tolerance` (module docs), in the mechanism's float type `T` (`f64` or
/// double-double; a tolerance below 4ε of `T` is raised to it). Contacts with μ_i > 0 take
/// Coulomb friction along the way.
///
/// # Errors
/// [`LzbError`]: a law count or parameter out of range, a tolerance outside (0, 1), a contact
/// no impulse moves, no consistent stick/slip at a slip event, or an integration that did not
/// end.
pub fn solve_lzb<T: Real, M: Mechanism<T>>(
    mechanism: &M,
    laws: &[ContactLaw],
    tolerance: f64,
) -> Result<Lzb<M::Screw, T>, LzbError> {
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
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(LzbError::Tolerance { value: tolerance });
    }
    let tolerance = tolerance.max(4.0 * T::epsilon_f64());
    let rough = mechanism.contacts().iter().any(|c| !c.mu.is_zero());
    let blocks = match rough.then(|| Blocks::planar(mechanism)).flatten() {
        Some(b) => b,
        None => {
            let frames = (0..n)
                .map(|i| {
                    let c = &mechanism.contacts()[i];
                    if c.mu.is_zero() {
                        Ok(ContactFrame::normal_with(c, |u| {
                            mechanism.contact_axis(i, u)
                        }))
                    } else {
                        mechanism.frame(i, true).map_err(|e| LzbError::Frame {
                            contact: i,
                            message: e.to_string(),
                        })
                    }
                })
                .collect::<Result<Vec<ContactFrame<T, M::Screw>>, _>>()?;
            Blocks::spatial(mechanism, &frames)
        }
    };
    let run = Run::new(&blocks, laws, tolerance)?;
    let path = run.integrate()?;
    let (len, y) = (run.len, &path.y);
    let unit = |q: usize| y[q] * run.axis[q];
    let impulses: Vec<T> = blocks.offset.iter().map(|&o| unit(o)).collect();
    let tangential: Vec<Vec<T>> = (0..n)
        .map(|i| {
            let o = blocks.offset[i];
            (o + 1..o + 1 + blocks.dims[i]).map(unit).collect()
        })
        .collect();
    let v = run.velocities(y);
    let after: Vec<T> = (0..n).map(|i| run.normal(&v, i)).collect();
    let before: Vec<T> = (0..n).map(|i| run.normal(&blocks.v0, i)).collect();
    let velocity = blocks.twist_after(mechanism.velocity(), &y[..len]);
    let kinetic_energy_loss =
        mechanism.kinetic_energy(mechanism.velocity()) - mechanism.kinetic_energy(&velocity);
    let work_compression = y[len + n..len + 2 * n].to_vec();
    let work_expansion = y[len + 2 * n..len + 3 * n].to_vec();
    let friction_dissipation = y[len + 3 * n..].to_vec();
    let dissipated = (0..n).fold(T::zero(), |s, i| {
        s + work_compression[i] - work_expansion[i] + friction_dissipation[i]
    });
    if !(y.iter().chain(&after).all(Scalar::is_finite) && kinetic_energy_loss.is_finite()) {
        return Err(LzbError::NotFinite);
    }
    Ok(Lzb {
        laws: laws.to_vec(),
        before,
        impulses,
        tangential,
        after,
        velocity,
        work_compression,
        work_expansion,
        friction_dissipation,
        max_energy: path.max_energy,
        kinetic_energy_loss,
        energy_residual: kinetic_energy_loss - dissipated,
        events: path.events,
        stats: path.stats,
        error_estimate: path.estimate,
        tolerance,
        end: path.tau.to_f64(),
        samples: path.samples,
        blocks,
    })
}

/// The integration's fixed data.
struct Run<'a, T: Real, S: Screws<T>> {
    n: usize,
    /// The number of stacked axes.
    len: usize,
    b: &'a Blocks<T, S>,
    laws: &'a [ContactLaw],
    c: Vec<T>,
    /// η_j + 1 per contact, in `T`.
    power: Vec<T>,
    /// |direction| of every axis: 1, or |n_i| on a planar scene's hatted axes.
    axis: Vec<T>,
    tol: f64,
    /// Per component of y: the scale of its absolute tolerance.
    scale: Vec<f64>,
    /// δ_v: the approach speed at which a resting contact engages, and the slip speed above
    /// which a contact that starts to take impulse slides.
    engage: f64,
    /// 16 tol max|v⁰|: below this slip speed a spatial slip keeps the direction it was given
    /// (its own direction is integration noise there), and a slip falling through it stops.
    lock: f64,
    /// The first step.
    h0: T,
    /// The Dormand–Prince tableau rounded to `T` once ([`A`], [`E`]): converting its
    /// fractions at every stage of every step cost more than the rest of the step, and
    /// rounding them to `f64` would cap a double-double run at f64's accuracy.
    a: [[T; 6]; 7],
    /// Its error weights.
    e: [T; 7],
}

/// The contacts' modes: the phase of each one's normal impulse and the friction mode of its
/// tangential one.
#[derive(Clone, Debug)]
struct Regime<T: Real> {
    phases: Vec<Phase>,
    modes: Vec<Mode<T>>,
    /// Per axis, the slip set aside when a contact was last at zero slip (its residual, below
    /// the event's resolution): slips are measured from it, so that a slip restarting from
    /// zero is not turned by the residual's direction.
    origin: Vec<T>,
}

/// Where the integration ended.
struct Path<T: Real> {
    y: Vec<T>,
    tau: T,
    max_energy: Vec<T>,
    events: Vec<Event>,
    stats: Stats,
    estimate: f64,
    samples: Vec<Sample>,
}

/// The velocities of every axis at a point, the modes in force there and their rates.
type AtPoint<T> = (Vec<T>, Vec<Mode<T>>, Rates<T>);

/// |x|.
fn norm<T: Real>(x: &[T]) -> T {
    x.iter().fold(T::zero(), |s, a| s + *a * *a).sqrt()
}

/// x · y.
fn dot<T: Real>(x: &[T], y: &[T]) -> T {
    x.iter().zip(y).fold(T::zero(), |s, (a, b)| s + *a * *b)
}

/// max(a, b) of values of `T`, compared in `f64` (ties and near-ties: either).
fn larger<T: Real>(a: T, b: T) -> T {
    if b.to_f64() > a.to_f64() { b } else { a }
}

impl<'a, T: Real, S: Screws<T>> Run<'a, T, S> {
    fn new(b: &'a Blocks<T, S>, laws: &'a [ContactLaw], tol: f64) -> Result<Self, LzbError> {
        let n = b.contacts();
        let len = b.len();
        let axis: Vec<T> = b
            .directions
            .iter()
            .map(|d| norm(&[d[0], d[1], d[2]]))
            .collect();
        let g = |i: usize| {
            let o = b.offset[i];
            (*b.at(o, o) / (axis[o] * axis[o])).to_f64()
        };
        let v0 = |i: usize| (b.v0[b.offset[i]] / axis[b.offset[i]]).to_f64();
        let speed = (0..len).fold(0.0_f64, |m, q| m.max((b.v0[q] / axis[q]).to_f64().abs()));
        let mut gmax = 0.0_f64;
        for i in 0..n {
            let gii = g(i);
            if gii.is_nan() || gii <= 0.0 {
                return Err(LzbError::Immovable { contact: i });
            }
            gmax = gmax.max(gii);
        }
        let impulse = speed / gmax;
        let energy = impulse * speed;
        let mut scale: Vec<f64> = axis.iter().map(|a| impulse / a.to_f64()).collect();
        scale.extend(laws.iter().map(|l| energy.powf(1.0 / (l.exponent + 1.0))));
        scale.extend(std::iter::repeat_n(energy, 3 * n));
        let c: Vec<T> = laws.iter().map(ContactLaw::c).collect();
        let power: Vec<T> = laws.iter().map(|l| T::of(l.exponent) + T::one()).collect();
        // The duration of the fastest contact's compression alone: δ* = ((η+1) v²/(2 g K))^(1/(η+1))
        // reached at the speed v, so τ* ≈ δ*/v.
        let h0 = (0..n)
            .filter(|&i| v0(i) > 0.0)
            .map(|i| {
                let l = &laws[i];
                let m = l.exponent + 1.0;
                let delta = (m * v0(i) * v0(i) / (2.0 * g(i) * l.stiffness)).powf(1.0 / m);
                1e-3 * delta / v0(i)
            })
            .fold(f64::INFINITY, f64::min);
        Ok(Run {
            n,
            len,
            b,
            laws,
            c,
            power,
            axis,
            tol,
            scale,
            engage: (1e-3 * tol).max(64.0 * n as f64 * T::epsilon_f64()) * speed,
            lock: 16.0 * tol * speed,
            h0: T::of(h0),
            a: A.map(|row| row.map(|(p, q)| ratio::<T>(p, q))),
            e: E.map(|(p, q)| ratio::<T>(p, q)),
        })
    }

    /// v = v⁰ − K Λ along every axis.
    fn velocities(&self, y: &[T]) -> Vec<T> {
        let mut dv = Vec::with_capacity(self.len);
        self.b.velocity_change(&y[..self.len], &mut dv);
        dv.iter().zip(&self.b.v0).map(|(d, v0)| *v0 + *d).collect()
    }

    /// Contact i's normal velocity along its unit normal, from the axes' velocities `v`.
    fn normal(&self, v: &[T], i: usize) -> T {
        let o = self.b.offset[i];
        v[o] / self.axis[o]
    }

    /// Contact i's slip along its unit tangent axes, measured from its `origin`.
    fn slip(&self, v: &[T], origin: &[T], i: usize) -> Vec<T> {
        let o = self.b.offset[i] + 1;
        (o..o + self.b.dims[i])
            .map(|q| (v[q] - origin[q]) / self.axis[q])
            .collect()
    }

    /// Whether contact i's friction is integrated in space (two tangent axes).
    fn spatial(&self, i: usize) -> bool {
        self.b.dims[i] == 2
    }

    /// E_j = u_j^(η_j+1).
    fn energy(&self, j: usize, u: T) -> T {
        if u.signum_i8() <= 0 {
            T::zero()
        } else {
            u.powf(self.power[j])
        }
    }

    /// F_j at y (zero at rest).
    fn force(&self, y: &[T], phases: &[Phase], j: usize) -> T {
        match phases[j] {
            Phase::Rest => T::zero(),
            _ => self.laws[j].force_of_u(self.c[j], y[self.len + j]),
        }
    }

    /// The prescribed normal rates dp_j/dτ = F_j, along the stacked normal axes.
    fn normals(&self, forces: &[T]) -> Vec<Normal<T>> {
        (0..self.n)
            .map(|j| Normal::Given(forces[j] / self.axis[self.b.offset[j]]))
            .collect()
    }

    /// The modes at velocities `v`: a spatial slip takes the direction of its slip above
    /// [`STOP_ZONE`] lock speeds and keeps the direction it was given within them (one that
    /// slows there is stopped, `stopped_slips`).
    fn modes_at(&self, v: &[T], regime: &Regime<T>) -> Vec<Mode<T>> {
        (0..self.n)
            .map(|i| match &regime.modes[i] {
                Mode::Slide(u) if self.spatial(i) => {
                    let s = self.slip(v, &regime.origin, i);
                    let rho = norm(&s);
                    if rho.to_f64() > STOP_ZONE * self.lock {
                        Mode::Slide(s.iter().map(|x| *x / rho).collect())
                    } else {
                        Mode::Slide(u.clone())
                    }
                }
                m => m.clone(),
            })
            .collect()
    }

    fn fail(e: RateFailure, tau: f64) -> LzbError {
        match e {
            RateFailure::Undetermined => LzbError::Undetermined { tau },
            RateFailure::Inconsistent => LzbError::NoConsistentModes { tau },
        }
    }

    /// The velocities, the modes in force and their impulse rates dΛ/dτ at y.
    fn rates_at(&self, y: &[T], regime: &Regime<T>, tau: f64) -> Result<AtPoint<T>, LzbError> {
        let v = self.velocities(y);
        let forces: Vec<T> = (0..self.n)
            .map(|j| self.force(y, &regime.phases, j))
            .collect();
        let modes = self.modes_at(&v, regime);
        let r = rates(self.b, &self.normals(&forces), &modes).map_err(|e| Self::fail(e, tau))?;
        Ok((v, modes, r))
    }

    /// dy/dτ under `regime` (module docs).
    fn rhs(&self, y: &[T], regime: &Regime<T>, dy: &mut [T]) -> Result<(), LzbError> {
        let (n, len) = (self.n, self.len);
        let (v, _, r) = self.rates_at(y, regime, f64::NAN)?;
        dy[..len].copy_from_slice(&r.lambda);
        for j in 0..n {
            let (law, c) = (&self.laws[j], self.c[j]);
            let o = self.b.offset[j];
            let vn = self.normal(&v, j);
            // v̂ p̂' = v_j F_j along the unit normal.
            let power = v[o] * r.lambda[o];
            let e = T::of(law.restitution);
            let zero = T::zero();
            let (du, dwc, dwr) = match regime.phases[j] {
                Phase::Compression => (c * vn, power, zero),
                Phase::Expansion => (c * vn / (e * e), zero, -power),
                Phase::Rest => (zero, zero, zero),
            };
            dy[len + j] = du;
            dy[len + n + j] = dwc;
            dy[len + 2 * n + j] = dwr;
            dy[len + 3 * n + j] =
                (o + 1..o + 1 + self.b.dims[j]).fold(zero, |s, q| s + v[q] * r.lambda[q]);
        }
        Ok(())
    }

    /// One Dormand–Prince step of length h from y: (y_new, embedded error).
    fn step(&self, y: &[T], h: T, regime: &Regime<T>) -> Result<(Vec<T>, Vec<T>), LzbError> {
        let len = y.len();
        let mut k: Vec<Vec<T>> = vec![vec![T::zero(); len]; 7];
        let mut stage = y.to_vec();
        for s in 0..7 {
            for (q, x) in stage.iter_mut().enumerate() {
                *x = y[q] + h * (0..s).fold(T::zero(), |acc, r| acc + self.a[s][r] * k[r][q]);
            }
            let mut d = vec![T::zero(); len];
            self.rhs(&stage, regime, &mut d)?;
            k[s] = d;
        }
        // The seventh stage is evaluated at the fifth-order solution (FSAL).
        let err: Vec<T> = (0..len)
            .map(|q| h * (0..7).fold(T::zero(), |acc, r| acc + self.e[r] * k[r][q]))
            .collect();
        Ok((stage, err))
    }

    /// The largest error relative to what the tolerance allows.
    fn error_ratio(&self, y: &[T], yn: &[T], err: &[T]) -> f64 {
        (0..y.len())
            .map(|q| {
                let size = y[q].to_f64().abs().max(yn[q].to_f64().abs());
                err[q].to_f64().abs() / (self.tol * (size + self.scale[q]))
            })
            .fold(0.0, f64::max)
    }

    /// The events between y and yn under `regime`, `primary` being the primary contact at y.
    /// A planar slip that stops is reported as [`EventKind::Sticks`] until its modes are
    /// resolved.
    fn crossings(
        &self,
        y: &[T],
        yn: &[T],
        regime: &Regime<T>,
        primary: usize,
    ) -> Result<Vec<(usize, EventKind)>, LzbError> {
        let (n, len) = (self.n, self.len);
        let v = self.velocities(yn);
        let phases = &regime.phases;
        let mut out = Vec::new();
        for j in 0..n {
            let u = yn[len + j].to_f64();
            let vj = self.normal(&v, j).to_f64();
            match phases[j] {
                Phase::Compression if vj < 0.0 => out.push((j, EventKind::CompressionEnds)),
                Phase::Expansion if u < 0.0 => out.push((j, EventKind::ExpansionEnds)),
                Phase::Expansion if vj > 0.0 => out.push((j, EventKind::Recompresses)),
                Phase::Rest if vj > self.engage => out.push((j, EventKind::Engages)),
                _ => {}
            }
        }
        if regime.modes.iter().any(|m| *m != Mode::Free) {
            let (_, modes, r) = self.rates_at(yn, regime, f64::NAN)?;
            let mut leaving = Vec::new();
            for j in 0..n {
                let o = self.b.offset[j];
                match &regime.modes[j] {
                    Mode::Slide(u)
                        if !self.spatial(j)
                            && (u[0] * (v[o + 1] - regime.origin[o + 1])).signum_i8() < 0 =>
                    {
                        out.push((j, EventKind::Sticks));
                    }
                    Mode::Stick if self.leaves_cone(&r, j) => leaving.push(j),
                    _ => {}
                }
            }
            let forces: Vec<T> = (0..n).map(|j| self.force(yn, phases, j)).collect();
            if leaving.is_empty() || !self.sticks_hold(&r, &self.normals(&forces), &modes) {
                out.extend(leaving.into_iter().map(|j| (j, EventKind::SlipStarts)));
            }
        }
        if self.energy(primary, y[len + primary]).signum_i8() > 0 {
            let ek = self.energy(primary, yn[len + primary]).to_f64();
            if let Some(j) = self.largest_energy(yn)
                && j != primary
                && self.energy(j, yn[len + j]).to_f64() > ek * (1.0 + PRIMARY_MARGIN)
            {
                out.push((j, EventKind::Primary));
            }
        }
        Ok(out)
    }

    /// The contact with the largest positive energy, if any.
    fn largest_energy(&self, y: &[T]) -> Option<usize> {
        let (n, len) = (self.n, self.len);
        (0..n)
            .map(|j| (j, self.energy(j, y[len + j]).to_f64()))
            .filter(|(_, e)| *e > 0.0)
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(j, _)| j)
    }

    /// The primary contact at y: the largest energy, kept on ties within the margin; when every
    /// energy is zero, the fastest approaching.
    fn primary(&self, y: &[T], current: usize) -> usize {
        let len = self.len;
        match self.largest_energy(y) {
            Some(j) => {
                let ek = self.energy(current, y[len + current]).to_f64();
                if self.energy(j, y[len + j]).to_f64() > ek * (1.0 + PRIMARY_MARGIN) {
                    j
                } else {
                    current
                }
            }
            None => {
                let v = self.velocities(y);
                (0..self.n)
                    .max_by(|&a, &b| {
                        self.normal(&v, a)
                            .to_f64()
                            .total_cmp(&self.normal(&v, b).to_f64())
                    })
                    .unwrap_or(0)
            }
        }
    }

    /// The longest step the spatial slips allow from y: nine tenths of the predicted time to
    /// zero slip of a slip that slows, and a turn of its direction of at most [`QUARTER`].
    fn slip_cap(&self, y: &[T], regime: &Regime<T>) -> Result<f64, LzbError> {
        let mut cap = f64::INFINITY;
        if !(0..self.n).any(|i| self.spatial(i) && matches!(regime.modes[i], Mode::Slide(_))) {
            return Ok(cap);
        }
        let (v, modes, r) = self.rates_at(y, regime, f64::NAN)?;
        for i in 0..self.n {
            let Mode::Slide(u) = &modes[i] else { continue };
            if !self.spatial(i) {
                continue;
            }
            let rho = norm(&self.slip(&v, &regime.origin, i)).to_f64();
            if rho <= self.lock {
                continue;
            }
            let o = self.b.offset[i] + 1;
            let f: Vec<f64> = (o..o + 2)
                .map(|q| (r.velocity[q] / self.axis[q]).to_f64())
                .collect();
            let u = [u[0].to_f64(), u[1].to_f64()];
            let along = u[0] * f[0] + u[1] * f[1];
            if along < 0.0 {
                cap = cap.min(0.9 * rho / -along);
            }
            let (x, z) = (f[0] - along * u[0], f[1] - along * u[1]);
            let turn = (x * x + z * z).sqrt() / rho;
            if turn > 0.0 && rho > STOP_ZONE * self.lock {
                cap = cap.min(QUARTER / turn);
            }
        }
        Ok(cap)
    }

    /// Whether a spatial slip turned by more than [`QUARTER`] from y to yn.
    fn turned(&self, y: &[T], yn: &[T], regime: &Regime<T>) -> bool {
        let (v, vn) = (self.velocities(y), self.velocities(yn));
        (0..self.n).any(|i| {
            if !self.spatial(i) || !matches!(regime.modes[i], Mode::Slide(_)) {
                return false;
            }
            let (a, b) = (
                self.slip(&v, &regime.origin, i),
                self.slip(&vn, &regime.origin, i),
            );
            let (ra, rb) = (norm(&a).to_f64(), norm(&b).to_f64());
            ra > STOP_ZONE * self.lock
                && rb > STOP_ZONE * self.lock
                && dot(&a, &b).to_f64() < (QUARTER.cos()) * ra * rb
        })
    }

    /// The spatial slips that reached zero at y: slowing, within [`STOP_ZONE`] lock speeds. Each one's
    /// bound on the impulse error of stopping it there (twice its largest rate times the
    /// predicted time to zero slip) is added to `estimate`.
    fn stopped_slips(
        &self,
        y: &[T],
        regime: &Regime<T>,
        tau: f64,
        estimate: &mut f64,
    ) -> Result<Vec<usize>, LzbError> {
        let mut out = Vec::new();
        if !(0..self.n).any(|i| self.spatial(i) && matches!(regime.modes[i], Mode::Slide(_))) {
            return Ok(out);
        }
        let (v, modes, r) = self.rates_at(y, regime, tau)?;
        for i in 0..self.n {
            let Mode::Slide(u) = &modes[i] else { continue };
            if !self.spatial(i) {
                continue;
            }
            let rho = norm(&self.slip(&v, &regime.origin, i)).to_f64();
            let o = self.b.offset[i];
            let f: Vec<T> = (o + 1..o + 3)
                .map(|q| r.velocity[q] / self.axis[q])
                .collect();
            let along = dot(u, &f).to_f64();
            if rho <= STOP_ZONE * self.lock && along < 0.0 {
                let rate = (o..o + 3).fold(0.0_f64, |m, q| m.max(r.lambda[q].to_f64().abs()));
                *estimate += 2.0 * rate * rho / -along;
                out.push(i);
            }
        }
        Ok(out)
    }

    /// The normal rates with which to choose modes at y: the forces there, or, when no
    /// contact is loaded yet (the start, where every F_j = 0 while the contacts load at the
    /// ratios of their forces), the forces at u_j = c_j v_j (a unit τ of loading).
    fn choice_normals(&self, y: &[T], regime: &Regime<T>, v: &[T]) -> Vec<Normal<T>> {
        let mut forces: Vec<T> = (0..self.n)
            .map(|j| self.force(y, &regime.phases, j))
            .collect();
        if forces.iter().all(Zero::is_zero) {
            for (j, f) in forces.iter_mut().enumerate() {
                if regime.phases[j] == Phase::Compression {
                    let u = self.c[j] * larger(self.normal(v, j), T::zero());
                    *f = self.laws[j].force_of_u(self.c[j], u);
                }
            }
        }
        self.normals(&forces)
    }

    /// Choose the friction modes at y: contacts at rest or without friction are free;
    /// `fresh` contacts (that start to take impulse) slide if they slip, else are at zero
    /// slip; `stopped` slips are at zero slip; `leaving` contacts (a stick whose required
    /// impulse left its cone) slide. The modes of every contact at zero slip (the sticking
    /// ones too) are chosen jointly: in the plane by the frictional integrator's resolution
    /// ([`resolve_planar`]), in space all stick if their cones allow it, else those whose
    /// cones do not slide along an invariant direction ([`invariant_directions`]). Returns
    /// the slip events.
    fn resolve(
        &self,
        y: &[T],
        regime: &mut Regime<T>,
        fresh: &[usize],
        stopped: &[usize],
        leaving: &[usize],
        tau: f64,
    ) -> Result<Vec<(usize, EventKind)>, LzbError> {
        let b = self.b;
        let v = self.velocities(y);
        let normals = self.choice_normals(y, regime, &v);
        let before = regime.modes.clone();
        let mut candidates: Vec<usize> = Vec::new();
        let mut out: Vec<usize> = leaving.to_vec();
        for i in 0..self.n {
            let o = b.offset[i] + 1;
            let dims = b.dims[i];
            if dims == 0 || regime.phases[i] == Phase::Rest {
                regime.modes[i] = Mode::Free;
                continue;
            }
            if fresh.contains(&i) {
                regime.origin[o..o + dims].fill(T::zero());
                let s = self.slip(&v, &regime.origin, i);
                let rho = norm(&s);
                if rho.to_f64() > self.engage {
                    regime.modes[i] = Mode::Slide(s.iter().map(|x| *x / rho).collect());
                    continue;
                }
            } else if !stopped.contains(&i) && regime.modes[i] != Mode::Stick {
                continue;
            }
            regime.origin[o..o + dims].copy_from_slice(&v[o..o + dims]);
            if !leaving.contains(&i) {
                candidates.push(i);
                regime.modes[i] = Mode::Stick;
            }
        }
        if candidates.len() + out.len() > MAX_CANDIDATES {
            return Err(LzbError::TooManyAtRest {
                tau,
                contacts: candidates.len() + out.len(),
            });
        }
        // The direction of the impulse each would need to stick: the sense a slip starts in.
        let mut all = regime.modes.clone();
        for &i in &out {
            all[i] = Mode::Stick;
        }
        let required = rates(b, &normals, &all).ok();
        let guess = |i: usize| -> Vec<T> {
            let o = b.offset[i];
            match &required {
                Some(r) if norm(&r.lambda[o + 1..o + 1 + b.dims[i]]).signum_i8() > 0 => {
                    let t = &r.lambda[o + 1..o + 1 + b.dims[i]];
                    t.iter().map(|x| *x / norm(t)).collect()
                }
                _ => {
                    let mut u = vec![T::zero(); b.dims[i]];
                    u[0] = T::one();
                    u
                }
            }
        };
        let zero_slip: Vec<usize> = candidates.iter().chain(&out).copied().collect();
        let held = regime.modes.clone();
        let mut search = || -> Result<(), LzbError> {
            if b.plane.is_some() {
                for &i in &out {
                    regime.modes[i] = Mode::Slide(guess(i));
                }
                if !candidates.is_empty() {
                    let res =
                        resolve_planar(b, &normals, &regime.modes, &candidates).map_err(|e| {
                            if e.undetermined {
                                LzbError::Undetermined { tau }
                            } else {
                                LzbError::NoConsistentModes { tau }
                            }
                        })?;
                    regime.modes = res.modes;
                }
            } else {
                let mut assigned: Vec<usize> = Vec::new();
                loop {
                    for &i in &out {
                        if assigned.contains(&i) {
                            continue;
                        }
                        assigned.push(i);
                        let mut modes = regime.modes.clone();
                        let roots = invariant_directions(b, &normals, &mut modes, i)
                            .map_err(|e| Self::fail(e, tau))?;
                        let g = guess(i);
                        let best = roots
                            .iter()
                            .max_by(|x, z| {
                                (x.kappa > 0.0)
                                    .cmp(&(z.kappa > 0.0))
                                    .then(dot(&x.u, &g).to_f64().total_cmp(&dot(&z.u, &g).to_f64()))
                            })
                            .ok_or(LzbError::NoConsistentModes { tau })?;
                        regime.modes[i] = Mode::Slide(best.u.clone());
                    }
                    let r = rates(b, &normals, &regime.modes).map_err(|e| Self::fail(e, tau))?;
                    let failing: Vec<usize> = candidates
                        .iter()
                        .copied()
                        .filter(|&i| regime.modes[i] == Mode::Stick && !out.contains(&i))
                        .filter(|&i| self.leaves_cone(&r, i))
                        .collect();
                    if failing.is_empty() || self.sticks_hold(&r, &normals, &regime.modes) {
                        break;
                    }
                    for i in failing {
                        regime.modes[i] = Mode::Stick;
                        out.push(i);
                    }
                }
            }
            Ok(())
        };
        if let Err(e) = search() {
            // The search of assignments found none consistent: Tresca's problem, which always
            // has a minimiser when every normal rate is given (every LZB rate is).
            if !matches!(
                e,
                LzbError::NoConsistentModes { .. } | LzbError::Undetermined { .. }
            ) {
                return Err(e);
            }
            regime.modes = self.tresca(&normals, &held, &zero_slip).ok_or(e)?;
        }
        let mut events = Vec::new();
        for i in 0..self.n {
            let kind = if stopped.contains(&i) {
                match (&before[i], &regime.modes[i]) {
                    (_, Mode::Stick) => EventKind::Sticks,
                    _ => EventKind::Reverses,
                }
            } else if before[i] == Mode::Stick && matches!(regime.modes[i], Mode::Slide(_)) {
                EventKind::SlipStarts
            } else {
                continue;
            };
            events.push((i, kind));
        }
        Ok(events)
    }

    /// Whether contact j's sticking rates in `r` leave its cone |τ'_j| ≤ μ_j p'_j by more than
    /// tol relative to the largest rate of the impact (the rates' rounding scale: a contact
    /// that carries next to no normal impulse is judged as finely as the others are computed,
    /// not relative to its own vanishing cone).
    fn leaves_cone(&self, r: &Rates<T>, j: usize) -> bool {
        let o = self.b.offset[j];
        let cone = (self.b.mu[j] * r.lambda[o]).to_f64();
        let t = norm(&r.lambda[o + 1..o + 1 + self.b.dims[j]]).to_f64();
        let scale = r
            .lambda
            .iter()
            .fold(cone + t, |m, x| m.max(x.to_f64().abs()));
        cone - t < -self.tol * scale
    }

    /// The modes of the contacts at `zero_slip` by Tresca's problem ([`tresca_modes`]), if
    /// they have rates and every stick's required impulse lies in its cone to `tol` relative.
    fn tresca(
        &self,
        normals: &[Normal<T>],
        modes: &[Mode<T>],
        zero_slip: &[usize],
    ) -> Option<Vec<Mode<T>>> {
        let b = self.b;
        let modes = tresca_modes(b, normals, modes, zero_slip, self.tol)?;
        let r = rates(b, normals, &modes).ok()?;
        let in_cones = zero_slip
            .iter()
            .filter(|&&i| modes[i] == Mode::Stick)
            .all(|&i| !self.leaves_cone(&r, i));
        (in_cones || !r.split_unique).then_some(modes)
    }

    /// Whether the sticking contacts of `modes` can all stay stuck where the member of their
    /// rates `r` taken leaves a cone: when their split is not unique ([`Rates::split_unique`])
    /// another member may lie in every cone, and Tresca's problem ([`tresca_modes`]) finds
    /// one if there is one (its minimiser keeps every slip rate at zero exactly when a member
    /// of the family lies in every cone).
    ///
    /// A family of one direction (two corners of one edge: only the sum of their tangential
    /// impulses along the edge is determined) is decided exactly by [`one_direction_holds`];
    /// Tresca's sweeps crawl along such a family, and where it only grazes a cone (a slip
    /// that stopped at its cone's edge, held there while the forces fade) they ran their full
    /// budget at every test.
    fn sticks_hold(&self, r: &Rates<T>, normals: &[Normal<T>], modes: &[Mode<T>]) -> bool {
        if r.split_unique {
            return false;
        }
        let sticks: Vec<usize> = (0..self.n).filter(|&i| modes[i] == Mode::Stick).collect();
        if let Some(holds) = self.one_direction_holds(r, &sticks) {
            return holds;
        }
        tresca_modes(self.b, normals, modes, &sticks, self.tol)
            .is_some_and(|m| sticks.iter().all(|&i| m[i] == Mode::Stick))
    }

    /// Whether some member τ' + α w of the sticking rates' family lies in every cone, when the
    /// family has one direction w: `None` when it has more (or none the f64 test sees).
    ///
    /// The family is τ' + null(K_SS), K_SS the inertance blocks of the sticking contacts'
    /// tangent axes (a null direction moves no body: wᵀK_SS w = |M^(-1/2) J_Sᵀ w|² = 0, so it
    /// changes no other rate). With one direction w, stick i holds for the α with
    ///
    /// ```text
    /// |τ'_i + α w_i|² ≤ R_i²,   R_i = μ_i p'_i + tol · scale
    /// ```
    ///
    /// (the slack of [`Run::leaves_cone`]: tol relative to the impact's largest rate), a
    /// quadratic inequality whose solutions form an interval [−b − √Δ, −b + √Δ]/|w_i|²,
    /// b = τ'_i·w_i, Δ = b² − |w_i|²(|τ'_i|² − R_i²) — or every α (w_i = 0 and |τ'_i| ≤ R_i),
    /// or none. The sticks hold iff the intervals meet. w is the right singular vector of
    /// K_SS of the one singular value below 10⁻⁹ of the largest.
    fn one_direction_holds(&self, r: &Rates<T>, sticks: &[usize]) -> Option<bool> {
        let b = self.b;
        let axes: Vec<usize> = sticks
            .iter()
            .flat_map(|&i| (b.offset[i] + 1..b.offset[i] + 1 + b.dims[i]).collect::<Vec<_>>())
            .collect();
        let m = axes.len();
        if m == 0 {
            return None;
        }
        let k = nalgebra::DMatrix::<f64>::from_fn(m, m, |x, y| b.at(axes[x], axes[y]).to_f64());
        let svd = k.svd(false, true);
        let v_t = svd.v_t?;
        let largest = svd.singular_values.max();
        let null: Vec<usize> = (0..m)
            .filter(|&x| svd.singular_values[x] <= 1e-9 * largest)
            .collect();
        let [w] = null.as_slice() else {
            return None;
        };
        let w: Vec<f64> = (0..m).map(|x| v_t[(*w, x)]).collect();
        let scale = r
            .lambda
            .iter()
            .fold(0.0_f64, |z, x| z.max(x.to_f64().abs()));
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        let mut at = 0;
        for &i in sticks {
            let o = b.offset[i];
            let d = b.dims[i];
            let t: Vec<f64> = (o + 1..o + 1 + d).map(|q| r.lambda[q].to_f64()).collect();
            let wi = &w[at..at + d];
            at += d;
            let radius = (b.mu[i] * r.lambda[o]).to_f64() + self.tol * scale;
            let (ww, tw) = (dot(wi, wi), dot(&t, wi));
            let excess = dot(&t, &t) - radius * radius;
            if ww <= f64::EPSILON * f64::EPSILON {
                if excess > 0.0 {
                    return Some(false);
                }
                continue;
            }
            let disc = tw * tw - ww * excess;
            if disc < 0.0 {
                return Some(false);
            }
            lo = lo.max((-tw - disc.sqrt()) / ww);
            hi = hi.min((-tw + disc.sqrt()) / ww);
        }
        Some(lo <= hi)
    }

    fn integrate(&self) -> Result<Path<T>, LzbError> {
        let (n, len) = (self.n, self.len);
        let mut y = vec![T::zero(); len + 4 * n];
        let v0 = self.velocities(&y);
        let phases: Vec<Phase> = (0..n)
            .map(|j| {
                if self.normal(&v0, j).to_f64() > self.engage {
                    Phase::Compression
                } else {
                    Phase::Rest
                }
            })
            .collect();
        let mut regime = Regime {
            phases,
            modes: vec![Mode::Free; n],
            origin: vec![T::zero(); len],
        };
        let all: Vec<usize> = (0..n).collect();
        self.resolve(&y, &mut regime, &all, &[], &[], 0.0)?;
        let mut primary = self.primary(&y, 0);
        let mut path = Path {
            y: Vec::new(),
            tau: T::zero(),
            max_energy: vec![T::zero(); n],
            events: Vec::new(),
            stats: Stats::default(),
            estimate: 0.0,
            samples: Vec::new(),
        };
        let record = |path: &mut Path<T>, y: &[T], primary: usize| {
            let v = self.velocities(y);
            path.samples.push(Sample {
                tau: path.tau.to_f64(),
                primary,
                impulses: (0..n)
                    .map(|j| (y[self.b.offset[j]] * self.axis[self.b.offset[j]]).to_f64())
                    .collect(),
                velocities: (0..n).map(|j| self.normal(&v, j).to_f64()).collect(),
                energies: (0..n)
                    .map(|j| self.energy(j, y[len + j]).to_f64())
                    .collect(),
                tangential: (0..n)
                    .map(|j| {
                        let o = self.b.offset[j] + 1;
                        (o..o + self.b.dims[j])
                            .map(|q| (y[q] * self.axis[q]).to_f64())
                            .collect()
                    })
                    .collect(),
                slips: (0..n)
                    .map(|j| {
                        let o = self.b.offset[j] + 1;
                        (o..o + self.b.dims[j])
                            .map(|q| (v[q] / self.axis[q]).to_f64())
                            .collect()
                    })
                    .collect(),
            });
        };
        record(&mut path, &y, primary);
        let mut h = self.h0;
        while regime.phases.iter().any(|p| *p != Phase::Rest) {
            let steps = path.stats.accepted + path.stats.rejected;
            let cap = self
                .slip_cap(&y, &regime)
                .map_err(|e| e.at(path.tau.to_f64()))?;
            if cap < h.to_f64() {
                h = T::of(cap);
            }
            if steps >= MAX_STEPS || path.stats.events >= MAX_EVENTS || path.tau + h == path.tau {
                return Err(LzbError::Runaway {
                    steps,
                    events: path.stats.events,
                });
            }
            let (yn, err) = self
                .step(&y, h, &regime)
                .map_err(|e| e.at(path.tau.to_f64()))?;
            let ratio = self.error_ratio(&y, &yn, &err);
            if !ratio.is_finite() || ratio > 1.0 || self.turned(&y, &yn, &regime) {
                path.stats.rejected += 1;
                h *= T::of(if ratio.is_finite() && ratio > 1.0 {
                    (0.9 * ratio.powf(-0.2)).max(0.2)
                } else if ratio.is_finite() {
                    0.5
                } else {
                    0.2
                });
                continue;
            }
            let (taken, yn, err) = if self
                .crossings(&y, &yn, &regime, primary)
                .map_err(|e| e.at(path.tau.to_f64()))?
                .is_empty()
            {
                (h, yn, err)
            } else {
                self.locate(&y, h, yn, err, &regime, primary)
                    .map_err(|e| e.at(path.tau.to_f64()))?
            };
            let found = self
                .crossings(&y, &yn, &regime, primary)
                .map_err(|e| e.at(path.tau.to_f64()))?;
            path.stats.accepted += 1;
            path.tau += taken;
            path.estimate += err[..len]
                .iter()
                .zip(&self.axis)
                .fold(0.0_f64, |m, (e, a)| m.max((*e * *a).to_f64().abs()));
            y = yn;
            let (mut fresh, mut stopped, mut leaving) = (Vec::new(), Vec::new(), Vec::new());
            for (j, kind) in found {
                match kind {
                    EventKind::Sticks => {
                        stopped.push(j);
                        continue;
                    }
                    EventKind::SlipStarts => {
                        leaving.push(j);
                        continue;
                    }
                    _ => {}
                }
                path.stats.events += 1;
                path.events.push(Event {
                    tau: path.tau.to_f64(),
                    contact: j,
                    kind,
                });
                match kind {
                    EventKind::CompressionEnds => {
                        path.max_energy[j] = larger(path.max_energy[j], self.energy(j, y[len + j]));
                        if self.laws[j].restitution == 0.0 {
                            y[len + j] = T::zero();
                            regime.phases[j] = Phase::Rest;
                        } else {
                            regime.phases[j] = Phase::Expansion;
                        }
                    }
                    EventKind::ExpansionEnds => {
                        y[len + j] = T::zero();
                        regime.phases[j] = Phase::Rest;
                    }
                    EventKind::Recompresses => regime.phases[j] = Phase::Compression,
                    EventKind::Engages => {
                        regime.phases[j] = Phase::Compression;
                        fresh.push(j);
                    }
                    EventKind::Primary => primary = j,
                    _ => {}
                }
            }
            let v = self.velocities(&y);
            // A resting contact already approaching (the end of another's expansion left it so).
            for j in 0..n {
                if regime.phases[j] == Phase::Rest && self.normal(&v, j).to_f64() > self.engage {
                    regime.phases[j] = Phase::Compression;
                    fresh.push(j);
                    path.stats.events += 1;
                    path.events.push(Event {
                        tau: path.tau.to_f64(),
                        contact: j,
                        kind: EventKind::Engages,
                    });
                }
            }
            // A spatial slip holds the direction of its slip at the last accepted step once it
            // falls below the lock speed.
            regime.modes = self.modes_at(&v, &regime);
            let tau = path.tau.to_f64();
            stopped.extend(self.stopped_slips(&y, &regime, tau, &mut path.estimate)?);
            let rests =
                (0..n).any(|j| regime.phases[j] == Phase::Rest && regime.modes[j] != Mode::Free);
            if rests || !(fresh.is_empty() && stopped.is_empty() && leaving.is_empty()) {
                let slips = self.resolve(&y, &mut regime, &fresh, &stopped, &leaving, tau)?;
                for (j, kind) in slips {
                    path.stats.events += 1;
                    path.events.push(Event {
                        tau,
                        contact: j,
                        kind,
                    });
                }
            }
            primary = self.primary(&y, primary);
            record(&mut path, &y, primary);
            if taken == h {
                h *= T::of((0.9 * ratio.max(1e-10).powf(-0.2)).min(5.0));
            }
        }
        for j in 0..n {
            path.max_energy[j] = larger(path.max_energy[j], self.energy(j, y[len + j]));
        }
        path.y = y;
        Ok(path)
    }

    /// The shortest step from y, within a few ε of `T` of it, at whose end an event has
    /// happened: the step, its end and its error estimate.
    #[allow(clippy::type_complexity)]
    fn locate(
        &self,
        y: &[T],
        h: T,
        yn: Vec<T>,
        err: Vec<T>,
        regime: &Regime<T>,
        primary: usize,
    ) -> Result<(T, Vec<T>, Vec<T>), LzbError> {
        let (mut lo, mut hi) = (T::zero(), h);
        let mut best = (yn, err);
        let half = T::of(0.5);
        let width = 4.0 * T::epsilon_f64();
        while (hi - lo).to_f64() > width * hi.to_f64() {
            let mid = half * (lo + hi);
            if mid == lo || mid == hi {
                break;
            }
            let (ym, em) = self.step(y, mid, regime)?;
            if self.crossings(y, &ym, regime, primary)?.is_empty() {
                lo = mid;
            } else {
                hi = mid;
                best = (ym, em);
            }
        }
        Ok((hi, best.0, best.1))
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

    /// A contact under the centre of mass (no coupling of normal and tangent), slipping at
    /// 2 m/s with μ = 3/10 and e = 1/2: P = (1 + e) v⁰/g = 3/2, the slip 2 − μ P stays
    /// positive, so |τ| = μ P and friction dissipates μ ∫ (2 − μ p) dp = μ (3 − 9μ/8).
    #[test]
    fn a_contact_sliding_throughout_takes_mu_times_its_normal_impulse() {
        let body = RigidBody::principal(1.0, Vec3::new(0.5, 0.5, 0.5));
        let twist = Screw::new(Vec3::zeros(), Vec3::new(2.0, 0.0, -1.0));
        let c = Contact::new(Vec3::zeros(), Vec3::new(0.0, 0.0, -1.0), 0.5).with_friction(0.3);
        let p = Problem::new(body, twist, vec![c]).expect("valid");
        let law = ContactLaw::new(2.0, 1.5, 0.5).expect("valid");
        let out = solve_lzb(&p, &[law], 1e-11).expect("ends");
        assert!(out.blocks.plane.is_some(), "planar in the xz-plane");
        let bound = 2.0 * out.error_estimate + 1e-14;
        assert!((out.impulses[0] - 1.5).abs() <= bound, "{:?}", out.impulses);
        assert!((out.tangential[0][0].abs() - 0.45).abs() <= bound);
        let wf = 0.3 * (3.0 - 9.0 * 0.3 / 8.0);
        assert!((out.friction_dissipation[0] - wf).abs() <= 8.0 * bound);
        assert!(out.energy_residual.abs() <= 8.0 * bound);
        assert!(
            out.events
                .iter()
                .all(|e| !matches!(e.kind, EventKind::Sticks | EventKind::Reverses))
        );
    }

    /// A speed whose energy overflows f64 gives no answer rather than an infinity: here the
    /// first step's error is not finite and the step underflows (a runaway); `NotFinite` is
    /// the backstop for an outcome that overflows after steps that did not.
    #[test]
    fn an_overflowing_impact_gives_no_number() {
        let body = RigidBody::principal(1e300, Vec3::new(1e300, 1e300, 1e300));
        let twist = Screw::new(Vec3::zeros(), Vec3::new(0.0, 0.0, -1e300));
        let c = Contact::new(Vec3::zeros(), Vec3::new(0.0, 0.0, -1.0), 0.5);
        let p = Problem::new(body, twist, vec![c]).expect("valid");
        let out = solve_lzb(&p, &[ContactLaw::default()], 1e-9);
        assert!(
            matches!(out, Err(LzbError::Runaway { steps: 1, .. })),
            "{out:?}"
        );
    }

    /// Two corners of one edge stuck, their normal rates given: whether a member of the
    /// sticking family lies in both cones, decided by the one-direction test, is Tresca's
    /// answer (its minimiser keeps both slips at zero exactly then), over a grid of μ and
    /// normal rates on both sides of the answer, away from its boundary (where the two
    /// tests' tolerances, not the problem, decide).
    #[test]
    fn the_edges_sticking_family_holds_when_tresca_says_so() {
        let body = RigidBody::principal(1.0, Vec3::new(0.5, 0.7, 0.9));
        let twist = Screw::new(Vec3::zeros(), Vec3::new(0.0, 0.0, -1.0));
        let corner = |x: f64, mu: f64| {
            Contact::new(Vec3::new(x, 0.3, 0.2), Vec3::new(0.0, 0.0, -1.0), 0.5).with_friction(mu)
        };
        let (mut held, mut refused) = (0, 0);
        for mu in [0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.8, 1.2] {
            let p = Problem::new(
                body.clone(),
                twist.clone(),
                vec![corner(1.0, mu), corner(-1.0, mu)],
            )
            .expect("valid");
            let frames: Vec<_> = (0..2).map(|i| p.frame(i, true).expect("a frame")).collect();
            let blocks = Blocks::spatial(&p, &frames);
            let laws = [ContactLaw::default(), ContactLaw::default()];
            let run = Run::new(&blocks, &laws, 1e-10).expect("a run");
            for f2 in [0.05, 0.2, 0.5, 1.0, 2.0, 5.0] {
                let normals = [Normal::Given(1.0), Normal::Given(f2)];
                let modes = [Mode::Stick, Mode::Stick];
                let r = rates(&blocks, &normals, &modes).expect("rates");
                assert!(
                    !r.split_unique,
                    "the corners' tangents along the edge are a family"
                );
                let holds = run.one_direction_holds(&r, &[0, 1]).expect("one direction");
                // away from the boundary: the same answer with the cones 10⁻⁴ wider and narrower
                let scaled = |k: f64| {
                    let mut b = blocks.clone();
                    b.mu.iter_mut().for_each(|m| *m *= k);
                    let run = Run::new(&b, &laws, 1e-10).expect("a run");
                    run.one_direction_holds(&r, &[0, 1]).expect("one direction")
                };
                if scaled(1.0 + 1e-4) != holds || scaled(1.0 - 1e-4) != holds {
                    continue;
                }
                let tresca =
                    tresca_modes(&blocks, &normals, &modes, &[0, 1], 1e-10).expect("a minimiser");
                assert_eq!(
                    holds,
                    tresca.iter().all(|m| *m == Mode::Stick),
                    "mu {mu}, f2 {f2}: {tresca:?}"
                );
                if holds {
                    held += 1;
                } else {
                    refused += 1;
                }
            }
        }
        assert!(
            held >= 5 && refused >= 5,
            "both answers occur: {held} held, {refused} refused"
        );
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
