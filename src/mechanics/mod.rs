//! The mechanics of the body and its contacts, in screw coordinates (§2, §9–12).
//!
//! [`screw`]: Plücker coordinates, the mixed product with η (eq. 3–6) · [`inertia`]: the
//! central inertia tensor, principal or full, and its exact inverse · [`body`]: the mass
//! matrix and the body's mobility (eq. 9, 11) · [`contact`]: the contacts and their frames
//! (eq. 2–4, 112–123) · [`constraint`]: ideal constraints and joints (§9–11) · [`reaction`]:
//! the constraint impulse as a force and a moment, per joint at its anchor · [`surface`]:
//! implicit surfaces f(x, y, z) = 0 and their normals (§12) · [`system`]: systems of bodies
//! joined by contacts and joints, in one impact.

pub mod body;
pub mod constraint;
pub mod contact;
pub mod inertia;
pub mod reaction;
pub mod screw;
pub mod surface;
pub mod system;
