//! Coulomb friction at the contacts (§14, eq. 137–145), integrated in impulse space.
//!
//! The paper ends with friction: tangential impulses μ_i P_i opposing the slip, the inertance
//! rows \[H_ix\], \[H_iy\], \[H_iz\] (eq. 143), and the remark that the system must be worked "with
//! differentials" (eq. 145). This module is that integration.
//!
//! **The model.** Contact i has a coefficient of friction μ_i ≥ 0. Let p_i be its accumulated
//! normal impulse and τ_i its tangential impulse (a 2-vector in y_i, z_i; one entry in a plane).
//! The impulse on the body at contact i is −(p_i E_ix + τ_iy E_iy + τ_iz E_iz), so the contact
//! velocities follow the 3×3 inertance blocks (eq. 12, 126–128, 143):
//!
//! ```text
//! v_i = v_i⁰ − Σ_j G_ij [p_j; τ_j]                                        (eq. 144)
//! Coulomb:  |τ_i| ≤ μ_i p_i;
//!   sliding (v_it ≠ 0):  dτ_i = μ_i (v_it / |v_it|) dp_i                   (eq. 137–139)
//!   sticking (v_it = 0): dτ_i keeps v_it = 0, if |dτ_i| ≤ μ_i dp_i allows it
//! ```
//!
//! The impact is followed in a parameter s:
//!
//! * **Compression**, s ∈ [0, 1], under the paper's hypothesis that the normal velocities
//!   vanish simultaneously: dv_ix/ds = −v_ix⁰ for every contact. A negative dp_i/ds means the
//!   hypothesis fails there: a verdict ([`Verdict::TensileRate`]). p_i^c = p_i(1).
//! * **Restitution**, s from 1, by one [`Restitution`] law per scene — Newton:
//!   dv_ix/ds = −k_i^N v_ix⁰ on [1, 2]; Poisson: dp_i/ds = k_i^P p_i^c on [1, 2]; energetic
//!   (Stronge): dp_i/ds = p_i^c until the contact's restitution work −∫ v_ix dp_i reaches
//!   k_i^E² times its compression work ∫ v_ix dp_i, after which it stops.
//!
//! With every μ_i = 0 Newton's and Poisson's laws reduce to the paper's eq. 15, 20–23: the
//! normal rates solve G p' = v⁰ on [0, 1] and G p' = k v⁰ (or p' = k p^c) on [1, 2]. The
//! rates under one assignment of modes are a linear system ([`rates`]); at an event the modes
//! of every contact at zero slip are chosen jointly ([`modes`]).
//!
//! **The unilateral law** ([`Hypothesis::Unilateral`]; `derivations/unilateral-friction.md`).
//! The simultaneous hypothesis drives every normal velocity along its path whatever impulse
//! rate that needs. The unilateral law gives contact i a path rate c_i and a base impulse rate
//! r_i ([`rates::Unilateral`]) and a gap g_i = v_i^path(s) − v_ix, dv_i^path/ds = −c_i:
//!
//! ```text
//! compression:  c_i = v_ix⁰,                Newton:  c_i = k_i^N max(v_ix⁰, 0),   r_i = 0
//! Poisson:      c_i = 0,  r_i = k_i^P p_i^c  (a contact must not approach: v_ix ≤ 0)
//! driven   (g_i = 0):  dv_ix/ds = −c_i,  dp_i/ds ≥ r_i
//! released (g_i ≥ 0):  dp_i/ds = r_i,    dg_i/ds ≥ 0 while g_i = 0
//! ```
//!
//! At s = 0, at s = 1 and at every event the rules of the contacts on their paths are chosen
//! jointly with stick and slip ([`modes::resolve_planar_unilateral`]), a complementarity problem
//! on the rates; a released contact whose gap closes re-engages (an event). With μ = 0 and
//! r = 0 it is LCP(G, −c): compression is Pfeiffer and Glocker's compression LCP (1996)
//! exactly, and Newton's restitution with one k at every approaching contact is Moreau's LCP
//! (1988); a contact released after taking impulse breaks Moreau's complementarity, since its
//! impulse p_i(s) never decreases. Housner's rocking block (1963) lands on its new corner with
//! ω⁺/ω⁻ = 1 − (3/2) sin²α exactly. Planar scenes are solved event by event, exactly (a gap is
//! linear between events); spatial ones by the adaptive integrator, whose release and
//! re-engagement are events located as a stick leaving its cone is ([`spatial`]). Under the
//! energetic law each contact's restitution is Stronge's: from s = 1, where every driven normal
//! velocity vanishes, it takes p_i^c per unit s until its restitution work is k_i² times its
//! compression work, released or held at v_ix = 0 by an extra rate as Poisson's.
//!
//! **Where it differs from physics engines.** Engines solve Coulomb's law as one algebraic
//! complementarity problem per impact (the maximal-dissipation or LCP friction laws, Stewart
//! and Trinkle; Anitescu and Potra): the tangential impulse is the *total* one, chosen once,
//! which cannot follow a slip that stops and reverses during the impact. Here the law holds
//! at every instant of the impact (Routh's and Keller's integration, Stronge's energetic
//! coefficient), so stick, slip reversal and the dependence on where in the impact they occur
//! are resolved — at the cost of integrating.
//!
//! **Mechanisms.** The integration asks only for the contacts' axes and μ, k, the mobility W,
//! the velocity before and the kinetic energy ([`Mechanism`]), so it runs unchanged on one body
//! and on a system of bodies ([`crate::mechanics::system`]): there contact i's impulses act on
//! its first body as above and on its second body oppositely, and the twist after is each
//! body's.
//!
//! **Planar scenes** ([`planar`]) are solved event by event, exactly: every rate is constant
//! between events. **Spatial scenes** ([`spatial`]) are integrated numerically in floats with
//! an adaptive embedded Runge–Kutta pair and event location, with an error estimate.

pub mod blocks;
pub mod departure;
pub mod modes;
pub mod planar;
pub mod rates;
pub mod spatial;
pub mod tresca;

use std::fmt;

use crate::impact::mechanism::Mechanism;
use crate::impact::restitution::Model;
use crate::mechanics::contact::ContactFrame;
use crate::mechanics::screw::{Screw, Screws, Vec3};
use crate::scalar::Scalar;

pub use blocks::Blocks;
pub use planar::PlanarFrictionWork;
pub use rates::{Mode, Normal, Unilateral};

/// The restitution law of a frictional impact.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Restitution {
    /// Newton's kinematic law: dv_ix/ds = −k_i^N v_ix⁰ on [1, 2].
    Newton,
    /// Poisson's kinetic law: dp_i/ds = k_i^P p_i^c on [1, 2].
    Poisson,
    /// Stronge's energetic law: restitution work = k_i^E² × compression work, per contact.
    Energetic,
}

impl Restitution {
    /// Every law, in report order.
    pub const ALL: [Restitution; 3] = [
        Restitution::Newton,
        Restitution::Poisson,
        Restitution::Energetic,
    ];

    /// The lower-case name used in scenes and reports.
    pub fn name(self) -> &'static str {
        match self {
            Restitution::Newton => "newton",
            Restitution::Poisson => "poisson",
            Restitution::Energetic => "energetic",
        }
    }

    /// The law called `name`.
    pub fn from_name(name: &str) -> Option<Restitution> {
        Restitution::ALL.into_iter().find(|r| r.name() == name)
    }
}

impl From<Model> for Restitution {
    fn from(m: Model) -> Self {
        match m {
            Model::Newton => Restitution::Newton,
            Model::Poisson => Restitution::Poisson,
        }
    }
}

impl fmt::Display for Restitution {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How the contacts' normal velocities are held during the impact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Hypothesis {
    /// The paper's: every contact follows its prescribed path, whatever impulse rate that
    /// needs; a negative one is a verdict ([`Verdict::TensileRate`]).
    #[default]
    Simultaneous,
    /// The unilateral law: a contact whose path would need a tensile rate is released and
    /// stays on the separating side of its path until it re-engages (module docs).
    Unilateral,
}

impl Hypothesis {
    /// The name in reports: `simultaneous`, `unilateral`.
    pub fn name(self) -> &'static str {
        match self {
            Hypothesis::Simultaneous => "simultaneous",
            Hypothesis::Unilateral => "unilateral",
        }
    }
}

/// The phase of the impact a segment belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// s ∈ [0, 1]: the normal velocities are brought to zero.
    Compression,
    /// s ≥ 1: the restitution law.
    Restitution,
}

impl fmt::Display for Phase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Phase::Compression => "compression",
            Phase::Restitution => "restitution",
        })
    }
}

/// A contact's mode over a segment, for reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeLabel {
    /// No tangential impulse (μ = 0, or no normal impulse rate: an energetic contact whose
    /// restitution has ended).
    Free,
    /// No slip.
    Stick,
    /// Slip along +y_i, the contact's tangent as given or as §12 chooses it (planar).
    SlidePlus,
    /// Slip along −y_i (planar).
    SlideMinus,
    /// Slip in a direction of the tangent plane (spatial).
    Slide,
    /// Off its prescribed path under the unilateral law: no normal impulse rate, its normal
    /// velocity free on the separating side ([`Hypothesis::Unilateral`]).
    Released,
}

impl ModeLabel {
    /// The name in reports: `free`, `stick`, `slide+`, `slide-`, `slide`, `released`.
    pub fn name(self) -> &'static str {
        match self {
            ModeLabel::Free => "free",
            ModeLabel::Stick => "stick",
            ModeLabel::SlidePlus => "slide+",
            ModeLabel::SlideMinus => "slide-",
            ModeLabel::Slide => "slide",
            ModeLabel::Released => "released",
        }
    }
}

/// The label of a mode.
pub fn label<T: Scalar>(m: &Mode<T>) -> ModeLabel {
    match m {
        Mode::Free => ModeLabel::Free,
        Mode::Stick => ModeLabel::Stick,
        Mode::Slide(u) if u.len() == 1 && u[0].signum_i8() > 0 => ModeLabel::SlidePlus,
        Mode::Slide(u) if u.len() == 1 => ModeLabel::SlideMinus,
        Mode::Slide(_) => ModeLabel::Slide,
    }
}

/// The labels of a segment: a contact the unilateral law has released with no normal impulse
/// rate reads `released`; the others their mode's label.
pub(crate) fn labels<T: Scalar>(
    hypothesis: Hypothesis,
    normals: &[Normal<T>],
    modes: &[Mode<T>],
) -> Vec<ModeLabel> {
    let mut out = Vec::with_capacity(normals.len());
    labels_into(hypothesis, normals, modes, &mut out);
    out
}

/// [`labels`] written into `out` (cleared first).
pub(crate) fn labels_into<T: Scalar>(
    hypothesis: Hypothesis,
    normals: &[Normal<T>],
    modes: &[Mode<T>],
    out: &mut Vec<ModeLabel>,
) {
    out.clear();
    out.extend(normals.iter().zip(modes).map(|(nr, m)| match nr {
        Normal::Given(r) if hypothesis == Hypothesis::Unilateral && r.is_zero() => {
            ModeLabel::Released
        }
        _ => label(m),
    }));
}

/// The vectors of a report's segments and samples taken back for the next report (a kept
/// [`planar::PlanarFrictionWork`]): reused, emptied, rather than allocated again.
#[derive(Clone, Debug)]
pub(crate) struct Spare<T> {
    values: Vec<Vec<T>>,
    labels: Vec<Vec<ModeLabel>>,
}

impl<T> Default for Spare<T> {
    fn default() -> Self {
        Spare {
            values: Vec::new(),
            labels: Vec::new(),
        }
    }
}

impl<T> Spare<T> {
    /// An empty vector of values: a kept one when there is one, else a new one of `capacity`.
    pub(crate) fn values(&mut self, capacity: usize) -> Vec<T> {
        match self.values.pop() {
            Some(mut v) => {
                v.clear();
                v
            }
            None => Vec::with_capacity(capacity),
        }
    }

    /// An empty vector of labels: a kept one when there is one, else a new one of `capacity`.
    pub(crate) fn labels(&mut self, capacity: usize) -> Vec<ModeLabel> {
        match self.labels.pop() {
            Some(mut v) => {
                v.clear();
                v
            }
            None => Vec::with_capacity(capacity),
        }
    }

    /// Keep the vectors of `segments` and `samples`, which are left empty.
    pub(crate) fn take_back(&mut self, segments: &mut Vec<Segment<T>>, samples: &mut Vec<Sample<T>>)
    where
        T: Scalar,
    {
        for s in segments.drain(..) {
            self.values.push(s.rates);
            self.labels.push(s.modes);
        }
        for s in samples.drain(..) {
            self.values.push(s.impulses);
            self.labels.push(s.modes);
        }
    }
}

/// One segment of the impact between two events.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment<T: Scalar> {
    /// Where it starts.
    pub from: T,
    /// Where it ends.
    pub to: T,
    /// Its phase.
    pub phase: Phase,
    /// The mode of every contact.
    pub modes: Vec<ModeLabel>,
    /// dΛ/ds over the segment (constant in a planar scene; at its start in a spatial one).
    pub rates: Vec<T>,
}

/// One point of an impact's path: the parameter s, the phase, the impulses Λ along every axis
/// and each contact's mode there (at an event, the segment ending there; the next sample, at
/// the same s, carries the modes that follow).
#[derive(Clone, Debug, PartialEq)]
pub struct Sample<T: Scalar> {
    /// s.
    pub s: T,
    /// Its phase.
    pub phase: Phase,
    /// Λ.
    pub impulses: Vec<T>,
    /// The mode of every contact.
    pub modes: Vec<ModeLabel>,
}

/// What a frictional result says about its own physics. None of these stops the solve: the
/// law is followed as stated and the answer is flagged.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// A normal impulse rate is negative: the simultaneous hypothesis (compression) or
    /// Newton's law (restitution) asks the contact to pull.
    TensileRate {
        /// The contact (0-based).
        contact: usize,
        /// Where the segment starts.
        s: f64,
        /// Its phase.
        phase: Phase,
    },
    /// Several assignments of modes were consistent at an event; the first (stick preferred)
    /// was taken.
    Ambiguous {
        /// Where.
        s: f64,
        /// How many were consistent.
        consistent: usize,
    },
    /// Sticking contacts share a tangential impulse only their sum determines (contacts on one
    /// line): the split reported is one member of a family (the middle of the cones).
    SplitNotUnique {
        /// Where.
        s: f64,
    },
    /// Driven contacts share a normal impulse only its resultant determines (three or more
    /// contacts of one face): the rates taken are the least-norm member with no negative
    /// normal rate. The twist after is the law's under Newton's law and under Poisson's with
    /// one k^P; per-contact restitution (Poisson's with differing k^P, the energetic law) may
    /// depend on the member — then `decided` is false.
    NormalSplitNotUnique {
        /// Where.
        s: f64,
        /// Whether the twist after is decided whatever the member.
        decided: bool,
        /// Whether sliding friction follows the split, so that the member changes the motion
        /// during the impact (a face sliding while it turns): then `decided` is false.
        friction: bool,
    },
    /// A contact still approaches after the impact (v_ix > 0).
    StillApproaching {
        /// The contact.
        contact: usize,
    },
    /// The kinetic energy grew: ΔE_c < 0 (Kane's paradox under Newton's law with friction).
    EnergyGain,
    /// A slip left zero slip along an invariant direction that repels the slips around it
    /// (spatial scenes): the outcome follows that one slip, and neighbouring initial
    /// conditions can end far from it — the impact is sensitive there.
    UnstableSlip {
        /// The contact (0-based).
        contact: usize,
        /// Where.
        s: f64,
    },
}

impl Verdict {
    /// A short name for tables and sweep statuses: `tensile-rate`, `ambiguous`,
    /// `split-not-unique`, `normal-split-not-unique`, `still-approaching`, `energy-gain`,
    /// `unstable-slip`.
    pub fn name(&self) -> &'static str {
        match self {
            Verdict::TensileRate { .. } => "tensile-rate",
            Verdict::Ambiguous { .. } => "ambiguous",
            Verdict::SplitNotUnique { .. } => "split-not-unique",
            Verdict::NormalSplitNotUnique { .. } => "normal-split-not-unique",
            Verdict::StillApproaching { .. } => "still-approaching",
            Verdict::EnergyGain => "energy-gain",
            Verdict::UnstableSlip { .. } => "unstable-slip",
        }
    }
}

/// The verdict on rates whose split is not unique, if any: [`Verdict::NormalSplitNotUnique`]
/// when the family moves normal rates (decided under Newton's law and under Poisson's with one
/// k^P among the `contacts`), else [`Verdict::SplitNotUnique`].
pub(crate) fn split_verdict<T: Scalar>(
    r: &rates::Rates<T>,
    s: f64,
    law: Restitution,
    contacts: &[crate::mechanics::contact::Contact<T>],
) -> Option<Verdict> {
    if r.split_unique {
        return None;
    }
    if r.normals_unique {
        return Some(Verdict::SplitNotUnique { s });
    }
    let friction = r.split_moves_body;
    let decided = !friction
        && match law {
            Restitution::Newton => true,
            Restitution::Poisson => contacts
                .windows(2)
                .all(|w| (w[0].k_poisson.clone() - &w[1].k_poisson).is_zero()),
            Restitution::Energetic => false,
        };
    Some(Verdict::NormalSplitNotUnique {
        s,
        decided,
        friction,
    })
}

impl FrictionError {
    /// The sweep status of a point the integration cannot follow: `no-continuation`,
    /// `undetermined`, `never-ends`; `None` for errors that are not the physics' verdict.
    pub fn status(&self) -> Option<&'static str> {
        match self {
            FrictionError::NoConsistentModes { .. } => Some("no-continuation"),
            FrictionError::Undetermined { .. } => Some("undetermined"),
            FrictionError::NeverEnds { .. } => Some("never-ends"),
            _ => None,
        }
    }
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Verdict::TensileRate { contact, s, phase } => write!(
                f,
                "contact {}: negative normal impulse rate from s = {s} ({phase})",
                contact + 1
            ),
            Verdict::Ambiguous { s, consistent } => write!(
                f,
                "s = {s}: {consistent} assignments of stick/slip are consistent; the first \
                 (stick preferred) was taken"
            ),
            Verdict::SplitNotUnique { s } => write!(
                f,
                "s = {s}: sticking contacts share a tangential impulse only their sum \
                 determines; the split shown is one member of a family"
            ),
            Verdict::NormalSplitNotUnique {
                s,
                decided,
                friction,
            } => {
                write!(
                    f,
                    "s = {s}: contacts of one face share a normal impulse only its resultant \
                     determines; the least-norm member with no pulling contact was taken"
                )?;
                if *friction {
                    write!(
                        f,
                        " — their sliding friction follows the split, so the twist after \
                         depends on the member: the rigid model does not decide it (the \
                         least-norm member is the split of equal, independent compliances)"
                    )
                } else if *decided {
                    write!(f, " (the twist after is the same for every member)")
                } else {
                    write!(
                        f,
                        " — under this restitution law the twist after may depend on the member"
                    )
                }
            }
            Verdict::StillApproaching { contact } => {
                write!(f, "contact {}: still approaching after impact", contact + 1)
            }
            Verdict::EnergyGain => write!(f, "the kinetic energy grew (ΔE_c < 0)"),
            Verdict::UnstableSlip { contact, s } => write!(
                f,
                "contact {}: from s = {s} its slip leaves zero along an invariant direction that \
                 repels nearby slips — the outcome is sensitive to the initial conditions",
                contact + 1
            ),
        }
    }
}

/// Why a frictional impact could not be followed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FrictionError {
    /// No assignment of stick and slip is consistent at an event.
    #[error(
        "at s = {s} ({phase}) no assignment of stick and slip is consistent: Coulomb's law \
         with this restitution law has no continuation here"
    )]
    NoConsistentModes {
        /// Where.
        s: f64,
        /// The phase.
        phase: Phase,
    },
    /// The rates are not determined (G singular on the contacts that take impulses).
    #[error(
        "at s = {s} the impulse rates are not determined: the inertance matrix is singular on \
         the contacts that take impulses, and how they share the impulse changes the motion \
         (sliding friction that follows a statically indeterminate split; see \
         `inertance analyze`)"
    )]
    Undetermined {
        /// Where.
        s: f64,
    },
    /// Too many contacts at zero slip at once to try every assignment.
    #[error(
        "at s = {s}, {contacts} contacts are at zero slip at once: more than 8 are not resolved"
    )]
    TooManyAtRest {
        /// Where.
        s: f64,
        /// How many.
        contacts: usize,
    },
    /// An energetic contact never reaches its restitution work.
    #[error(
        "contact {}: its energetic restitution never ends (its restitution work cannot reach \
         k² times its compression work)",
        contact + 1
    )]
    NeverEnds {
        /// The contact (0-based).
        contact: usize,
    },
    /// An energetic stop lies at a square root the scalar does not hold.
    #[error("contact {}: its energetic stop needs a square root this scalar does not hold", contact + 1)]
    NeedsRadical {
        /// The contact (0-based).
        contact: usize,
    },
    /// A spatial scene in an exact type (spatial scenes are integrated in floats).
    #[error(
        "the scene is not planar (no coordinate plane, nor a plane whose normal has a rational \
         length, holds every frictional contact and the motion), so it is integrated \
         numerically: run it in f64 or double-double"
    )]
    NotPlanar,
    /// A spatial scene in a dual-number type (a sensitivity run): the adaptive integrator
    /// chooses its steps and locates its events in f64, so its result is not a differentiable
    /// function of the inputs the dual numbers could follow.
    #[error(
        "the scene is not planar, or its seeded derivative moves it out of its plane, so it is \
         integrated numerically with adaptive steps and bisected events, which carry no \
         derivative: sensitivities of frictional scenes are computed for planar scenes only \
         (estimate this one by finite differences)"
    )]
    NotDifferentiable,
    /// More events or steps than any physical impact needs.
    #[error("the integration did not end within its event or step budget")]
    Runaway,
    /// The contacts chatter: one cycle of modes repeats, each cycle shorter in s than the one
    /// before — events accumulating at a Zeno point of the impact (`planar::chatter`).
    #[error(
        "the contacts chatter: a cycle of {period} mode change(s) ({phase}) repeated {cycles} \
         times, each shorter in s than the one before, events accumulating near s = {s} — a \
         Zeno point of the impact, whose limit is not computed (no answer rather than a guess)"
    )]
    Chatter {
        /// Where the last event fell (the accumulation point is at or just past it).
        s: f64,
        /// The phase.
        phase: Phase,
        /// Events per cycle.
        period: usize,
        /// Cycles seen.
        cycles: usize,
    },
}

/// The outcome of a frictional impact. Impulses are along the stacked axes of
/// [`Blocks`]: hatted in a planar scene (exact), unit in a spatial one. `S` is the
/// mechanism's screw space: one body's [`Screw`], a system's stack.
#[derive(Clone, Debug)]
pub struct Frictional<T: Scalar, S: Screws<T> = Screw<T>> {
    /// The restitution law.
    pub law: Restitution,
    /// Whether the contacts were held on their paths or could be released.
    pub hypothesis: Hypothesis,
    /// The axes and inertances.
    pub blocks: Blocks<T, S>,
    /// Λ: the impulses along every axis at the end.
    pub impulses: Vec<T>,
    /// p_i^c: the normal impulses at the end of compression.
    pub compression: Vec<T>,
    /// The velocities along every axis after impact.
    pub after: Vec<T>,
    /// {v} = [ω; v_C] after impact (eq. 142); each body's, for a system.
    pub velocity: S,
    /// ∫ v_ix dp_i over compression, per contact.
    pub work_compression: Vec<T>,
    /// −∫ v_ix dp_i over restitution, per contact.
    pub work_restitution: Vec<T>,
    /// Σ_i ∫ v_it · dτ_i: the energy dissipated by friction.
    pub friction_dissipation: T,
    /// ΔE_c = Σ_i ∫ v_i · dΛ_i = T⁰ − T.
    pub kinetic_energy_loss: T,
    /// E_p = ½ (Δv)ᵀ η M (Δv) (eq. 28).
    pub lost_velocity_energy: T,
    /// (T⁰ − T) − ΔE_c: zero in exact types — a check of the integration.
    pub energy_residual: T,
    /// The segments between events.
    pub segments: Vec<Segment<T>>,
    /// The verdicts.
    pub verdicts: Vec<Verdict>,
    /// The parameter s at the end.
    pub end: T,
    /// The estimated error of the impulses and velocities (spatial integration), in their
    /// units; `None` for planar scenes (exact up to the scalar's rounding).
    pub error_estimate: Option<f64>,
    /// The relative tolerance of the spatial integration (the one asked for, raised to 4ε of
    /// the scalar at least); `None` for planar scenes.
    pub tolerance: Option<f64>,
    /// The path: a planar scene's at the ends of its segments (Λ is linear between them); a
    /// spatial one's at every accepted step and on both sides of every event.
    pub samples: Vec<Sample<T>>,
}

impl<T: Scalar, S: Screws<T>> Frictional<T, S> {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn finish<M: Mechanism<T, Screw = S>>(
        mechanism: &M,
        blocks: Blocks<T, S>,
        law: Restitution,
        impulses: Vec<T>,
        compression: Vec<T>,
        after: Vec<T>,
        work_compression: Vec<T>,
        work_restitution: Vec<T>,
        friction_dissipation: T,
        segments: Vec<Segment<T>>,
        verdicts: Vec<Verdict>,
        end: T,
    ) -> Self {
        let mut out = Self::unsettled(
            blocks,
            law,
            impulses,
            compression,
            after,
            work_compression,
            work_restitution,
            friction_dissipation,
            segments,
            verdicts,
            end,
            Vec::new(),
        );
        out.settle(mechanism, &mut Spare::default());
        out
    }

    /// The report of an integration's end before [`Frictional::settle`]: the twist after and
    /// the energies zero, `samples` (emptied by `settle`) the vector its samples will fill.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn unsettled(
        blocks: Blocks<T, S>,
        law: Restitution,
        impulses: Vec<T>,
        compression: Vec<T>,
        after: Vec<T>,
        work_compression: Vec<T>,
        work_restitution: Vec<T>,
        friction_dissipation: T,
        segments: Vec<Segment<T>>,
        verdicts: Vec<Verdict>,
        end: T,
        samples: Vec<Sample<T>>,
    ) -> Self {
        Frictional {
            law,
            hypothesis: Hypothesis::Simultaneous,
            blocks,
            impulses,
            compression,
            after,
            velocity: S::default(),
            work_compression,
            work_restitution,
            friction_dissipation,
            kinetic_energy_loss: T::zero(),
            lost_velocity_energy: T::zero(),
            energy_residual: T::zero(),
            segments,
            verdicts,
            end,
            error_estimate: None,
            tolerance: None,
            samples,
        }
    }

    /// What follows from the integration's end: the twist after (eq. 142), the energies, the
    /// verdicts on the end state (still approaching, energy gain) and the linear samples of the
    /// segments, their vectors taken from `spare`.
    pub(crate) fn settle<M: Mechanism<T, Screw = S>>(
        &mut self,
        mechanism: &M,
        spare: &mut Spare<T>,
    ) {
        let before = mechanism.velocity();
        self.velocity = self.blocks.twist_after(before, &self.impulses);
        let mut change = self.velocity.clone();
        change.add_scaled(&-T::one(), before);
        self.lost_velocity_energy = mechanism.kinetic_energy(&change);
        let mut kinetic_energy_loss = self.friction_dissipation.clone();
        for (c, r) in self.work_compression.iter().zip(&self.work_restitution) {
            kinetic_energy_loss += c.clone() - r;
        }
        let kinetic_before = mechanism.kinetic_energy(before);
        self.energy_residual = kinetic_before.clone()
            - mechanism.kinetic_energy(&self.velocity)
            - &kinetic_energy_loss;
        self.verdicts.dedup_by(|a, b| match (a, b) {
            (
                Verdict::TensileRate {
                    contact: i,
                    phase: p,
                    ..
                },
                Verdict::TensileRate {
                    contact: j,
                    phase: q,
                    ..
                },
            ) => i == j && p == q,
            _ => false,
        });
        let len = self.blocks.len();
        let scale = rates::max_abs(&self.blocks.v0);
        for (i, &o) in self.blocks.offset.iter().enumerate() {
            if modes::positive(&self.after[o], &scale, len) {
                self.verdicts.push(Verdict::StillApproaching { contact: i });
            }
        }
        if !modes::nonnegative(&kinetic_energy_loss, &kinetic_before, len) {
            self.verdicts.push(Verdict::EnergyGain);
        }
        self.kinetic_energy_loss = kinetic_energy_loss;
        linear_samples_into(&self.segments, len, &mut self.samples, spare);
    }

    /// p̂_i: contact i's normal impulse along its stacked normal axis (hatted in a planar
    /// scene: P_i = p̂_i |n_i|; unit in a spatial one).
    pub fn normal_hat(&self, i: usize) -> &T {
        &self.impulses[self.blocks.offset[i]]
    }

    /// The impulse vector the obstacle applies at contact i, split into its normal and
    /// tangential parts, in body axes: −(p_i n̂_i) and −(τ_i t̂_i) with the axes as stacked.
    /// Exact in a planar scene (no norm is taken). For a contact of a system, the impulse on
    /// its first body, in world axes (its second body takes the opposite).
    pub fn impulse_vectors(&self, i: usize) -> (Vec3<T>, Vec3<T>) {
        let off = self.blocks.offset[i];
        let dir = |q: usize| self.blocks.directions[q].clone() * self.impulses[q].clone();
        let normal = -dir(off);
        let mut tangential = Vec3::zeros();
        for a in 0..self.blocks.dims[i] {
            tangential -= dir(off + 1 + a);
        }
        (normal, tangential)
    }

    /// Whether the energy balance ΔE_c = Σ∫ v·dΛ = T⁰ − T holds, T⁰ = `kinetic_before`:
    /// exactly in exact types; to 16·N·ε·T⁰ (N contacts) for a planar float solve; for a
    /// spatial integration, whose residual carries the local errors it accepted, to the power
    /// an impulse error of the estimate can carry, estimate × max|v⁰| × 2 × axes, plus that
    /// rounding.
    pub fn energy_balance_holds(&self, kinetic_before: &T) -> bool {
        let n = self.blocks.contacts();
        match self.error_estimate {
            None => self.energy_residual.is_negligible(kinetic_before, 16 * n),
            Some(est) => {
                let speed = rates::max_abs(&self.blocks.v0).to_f64();
                let axes = self.blocks.len() as f64;
                let bound = est * speed * 2.0 * axes
                    + 16.0 * n as f64 * T::epsilon_f64() * kinetic_before.to_f64().abs();
                self.energy_residual.to_f64().abs() <= bound
            }
        }
    }

    /// The mode history of contact i: the label of each segment, repeats merged.
    pub fn history(&self, i: usize) -> Vec<ModeLabel> {
        let mut h: Vec<ModeLabel> = Vec::new();
        for s in &self.segments {
            if h.last() != Some(&s.modes[i]) {
                h.push(s.modes[i]);
            }
        }
        h
    }
}

/// The path of an impact whose rates are constant over each segment (a planar scene): Λ at
/// both ends of every segment, from Λ = 0 at its start, written into `out` (emptied first into
/// `spare`, whose vectors the samples take).
fn linear_samples_into<T: Scalar>(
    segments: &[Segment<T>],
    len: usize,
    out: &mut Vec<Sample<T>>,
    spare: &mut Spare<T>,
) {
    spare.take_back(&mut Vec::new(), out);
    out.reserve(2 * segments.len());
    let mut at = spare.values(len);
    at.resize(len, T::zero());
    for seg in segments {
        let mut sample = |s: &T, at: &[T]| {
            let mut impulses = spare.values(at.len());
            impulses.extend_from_slice(at);
            let mut modes = spare.labels(seg.modes.len());
            modes.extend_from_slice(&seg.modes);
            out.push(Sample {
                s: s.clone(),
                phase: seg.phase,
                impulses,
                modes,
            });
        };
        sample(&seg.from, &at);
        let ds = seg.to.clone() - &seg.from;
        for (x, r) in at.iter_mut().zip(&seg.rates) {
            *x += r.clone() * &ds;
        }
        sample(&seg.to, &at);
    }
    spare.values.push(at);
}

/// Solve the frictional impact of `mechanism` (one body, or a system of bodies) under `law`:
/// event by event, exactly, when the scene is planar ([`Blocks::planar`]); by the adaptive
/// integrator in floats otherwise, to the relative `tolerance`.
///
/// # Errors
/// [`FrictionError`]; [`FrictionError::NotPlanar`] for a spatial scene in an exact type,
/// [`FrictionError::NotDifferentiable`] in a dual-number type (a planar scene runs event by
/// event, its events solved in the scalar type, so their dependence on the inputs is carried;
/// the spatial integrator's step sizes and bisected events are f64 and would drop it).
pub fn solve_frictional<T: Scalar, M: Mechanism<T>>(
    mechanism: &M,
    law: Restitution,
    tolerance: f64,
) -> Result<Frictional<T, M::Screw>, FrictionError> {
    solve_frictional_under(mechanism, law, Hypothesis::Simultaneous, tolerance)
}

/// [`solve_frictional`] under `hypothesis`: the simultaneous law, or the unilateral one —
/// event by event in a planar scene, by the adaptive integrator in a spatial one, under each
/// restitution law.
///
/// # Errors
/// As [`solve_frictional`].
pub fn solve_frictional_under<T: Scalar, M: Mechanism<T>>(
    mechanism: &M,
    law: Restitution,
    hypothesis: Hypothesis,
    tolerance: f64,
) -> Result<Frictional<T, M::Screw>, FrictionError> {
    if let Some(b) = Blocks::planar(mechanism) {
        return planar::solve_planar(mechanism, b, law, hypothesis);
    }
    solve_spatial(mechanism, law, hypothesis, tolerance)
}

/// [`solve_frictional_under`] for a scene that [`Blocks::planar`] refused.
pub(crate) fn solve_spatial<T: Scalar, M: Mechanism<T>>(
    mechanism: &M,
    law: Restitution,
    hypothesis: Hypothesis,
    tolerance: f64,
) -> Result<Frictional<T, M::Screw>, FrictionError> {
    if T::IS_EXACT {
        return Err(FrictionError::NotPlanar);
    }
    if T::IS_DUAL {
        return Err(FrictionError::NotDifferentiable);
    }
    let frames: Vec<ContactFrame<T, M::Screw>> = (0..mechanism.contacts().len())
        .map(|i| {
            mechanism
                .frame(i, true)
                .expect("a validated problem's tangents")
        })
        .collect();
    spatial::solve_spatial_under(
        mechanism,
        Blocks::spatial(mechanism, &frames),
        law,
        hypothesis,
        tolerance,
    )
}
