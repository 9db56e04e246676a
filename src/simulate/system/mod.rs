//! Systems: several bodies — spheres, boxes and thin rods — under gravity among obstacle
//! planes, with contacts between them as well as with the planes: a column of beads falling on
//! a wall, Newton's cradle as a sequence of impacts, a box dropped on a box resting on the
//! floor, a box tipping over another's edge, a rod dropped across a box.
//!
//! **Why a folder beside the one-body loop.** The one body of [`super::run`] carries an
//! attitude, features (corners, rod ends) and friction with stick and slip, in a fixed-size
//! state; a system carries B bodies, contacts between two of them and a mass matrix W = J M⁻¹ Jᵀ
//! over all of them. This folder is that loop for spheres, boxes and rods, with Coulomb
//! friction where μ > 0 (a sphere that no rough contact touches carries its spin without
//! integrating it). It shares with the one body everything that is not about the body: the
//! Runge–Kutta step ([`super::ode::step_slice`]), the obstacle planes and contact laws
//! ([`super::world`]), the impact laws ([`super::impact::Law`]), the options, the log records
//! and the errors ([`super::run`]); each impact is a [`crate::mechanics::system::System`]
//! solved by the impact layer, never here.
//!
//! Members may be held by joints (`[[joint]]`: revolute, spherical, …), bilateral constraints
//! eliminated from the flight's accelerations and held against drift ([`joints`]), and passed
//! to the impact layer at every impact.
//!
//! [`members`]: the bodies and their state · [`gaps`]: the contacts and their gap functions ·
//! [`joints`]: the joints' rows, their elimination and projection ·
//! [`persist`]: persistent contact, the acceleration-level LCP with W = J M⁻¹ Jᵀ ·
//! [`impact`]: one impact as a system's · [`overlap`]: the check that no two bodies pass
//! through each other · [`zeno`]: the accumulation of a member's bounces on what stays put ·
//! [`run`]: the event loop.

pub mod gaps;
pub mod impact;
pub mod joints;
pub mod members;
pub mod overlap;
pub mod persist;
pub mod run;
pub mod zeno;

pub use gaps::{Candidate, Touch};
pub use joints::Link;
pub use members::{Member, SystemState};
pub use run::{SystemSample, SystemSetup, SystemSimulation, after_first_impact, simulate_system};
