//! Multiple-impact laws in impulse space: laws that drop the paper's simultaneous hypothesis
//! (every normal velocity reaches its law at the same instant) and follow instead each
//! contact's own compression and expansion through the impact, as the friction integrator of
//! §14 ([`crate::impact::friction`]) follows stick and slip.
//!
//! [`law`]: a contact's parameters — stiffness K_i, compliance exponent η_i, Stronge's energetic
//! restitution e_i (Siconos' `MultipleImpactNSL`) · [`lzb`]: the Darboux–Keller shock dynamics
//! of Liu, Zhao and Brogliato (2008, 2009), the impulses distributed by the ratio of the
//! contacts' forces expressed through their potential energies, integrated adaptively in f64 or double-double
//! with event location (Siconos' `OSNSMultipleImpact`, which steps in the primary impulse with
//! a fixed step), with Coulomb friction at every instant of the path (Zhao, Liu & Brogliato
//! 2009) through the friction layer's rates and mode resolution; a mechanism is one body, a
//! constrained body or a system of bodies ([`crate::impact::mechanism::Mechanism`]).
//! [`closed_form`]: the exact outcome when every contact is alike (one contact; a body landing
//! flat on equal corners).

pub mod closed_form;
pub mod law;
pub mod lzb;

pub use closed_form::{Alike, alike};
pub use law::{ContactLaw, LawError};
pub use lzb::{Event, EventKind, Lzb, LzbError, Phase, Sample, Stats, solve_lzb};
