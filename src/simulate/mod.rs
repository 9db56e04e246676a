//! Sequences of impacts: a body under gravity among obstacle planes, through every impact until
//! the end of the run or rest — bouncing, rocking, tumbling — each impact solved by the scene's
//! law through the impact layer.
//!
//! This layer sits above [`crate::impact`]: it owns the body's motion between impacts (free
//! flight, persistent contact), the gap functions that decide when and where the body strikes,
//! the event loop, the accumulation of impacts (Zeno) and the impact log; at each impact it
//! builds the impact [`crate::impact::problem::Problem`] of the state there and calls the law,
//! and never solves an impact itself.
//!
//! [`body`]: the body, its features and state · [`world`]: the obstacle planes and the gaps ·
//! [`contact`]: persistent contact, the acceleration-level complementarity problem ·
//! [`impact`]: one impact under the chosen law · [`ode`]: the Runge–Kutta step and its
//! continuous extension · [`stepper`]: the adaptive step both loops take ·
//! [`run`]: the event loop, the log and the trajectory · [`exact`]: exact runs of a
//! frictionless sphere among planes (no integration: the event times are roots of quadratics) ·
//! [`system`]: several spheres, with contacts between them as well as with the planes (its own
//! loop over the shared pieces).

pub mod body;
pub mod contact;
pub mod exact;
pub mod impact;
pub mod ode;
pub mod run;
pub mod stepper;
pub mod system;
pub mod world;

pub use body::{Body, Feature, Shape, State};
pub use impact::Law;
pub use run::{End, ImpactRecord, Options, Setup, SimulateError, Simulation, simulate};
pub use world::{ContactLaw, Plane};
